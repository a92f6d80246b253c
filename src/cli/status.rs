//! `awl status`: program status (STATUS BAUSTEIN) of one block invocation.

use miette::Report;

use crate::program_status::{self, BlockRef, Recorder, StatusError, Window};
use crate::runner::{self, Ran, RunOptions};
use crate::vm::cycle::RunLimit;

use super::run::{ProgramArgs, RunLength, not_run, program_options, watched};
use super::watch::EXIT_HALTED;
use super::{Console, EXIT_OK, EXIT_SOURCE_ERRORS, EXIT_STOP, EXIT_USAGE};

/// How long `--at` looks for the block after its time when no run length is given.
const LOOK_AFTER_AT_NS: u64 = 1_000_000_000;

#[derive(Debug, clap::Args)]
pub struct StatusArgs {
    #[command(flatten)]
    pub program: ProgramArgs,
    #[command(flatten)]
    pub length: RunLength,
    /// The block to show, e.g. "PB 3", or its symbol, e.g. -FILL or '"Valve"' (STEP 7)
    #[arg(long, value_parser = BlockRef::parse, allow_hyphen_values = true)]
    pub block: BlockRef,
    /// Its first invocation in this cycle [default: its first in the run]
    #[arg(long, conflicts_with = "at", value_parser = clap::value_parser!(u64).range(1..))]
    pub cycle: Option<u64>,
    /// Its first invocation that begins at or after this simulated time, e.g. 250ms [default:
    /// the run's start]
    #[arg(long, value_name = "TIME", value_parser = parse_time)]
    pub at: Option<u64>,
}

fn parse_time(text: &str) -> Result<u64, String> {
    crate::scenario::parse_duration(text)
        .ok_or_else(|| format!("`{text}` is not a time; write e.g. 250ms, 2s, 500us"))
}

/// Why the block was not shown: the window lies past the run's end, or the block was not
/// invoked in it.
fn did_not_run(args: &StatusArgs, window: Window, ran: &Ran, halted: bool) -> StatusError {
    let (cycles, clock_ns) = (ran.outcome.cycles, ran.outcome.clock_ns);
    let ended = crate::trace::format_ms(clock_ns);
    if window.after(cycles, clock_ns) && !halted {
        return StatusError::PastTheEnd {
            window: window.name(),
            cycles: super::plural(cycles, "cycle"),
            ended: format!("ended at {ended}"),
            why: if args.length.limit().is_some() {
                "the command line's `--cycles`/`--for` set the run's length".into()
            } else {
                "the scenario's `run` sets the run's length".into()
            },
        };
    }
    StatusError::DidNotRun {
        block: args.block.written(),
        window: window.describe(),
        ended: format!("{ended} after {}", super::plural(cycles, "cycle")),
    }
}

pub fn status(args: &StatusArgs, console: &mut Console) -> u8 {
    let options = RunOptions {
        limit: args.length.limit(),
        ..program_options(&args.program)
    };
    let mut prepared = match runner::prepare(&options) {
        Ok(prepared) => prepared,
        Err(reason) => return not_run("status", reason, console),
    };
    let index = match program_status::block::find(&prepared.cpu.program, &args.block) {
        Ok(index) => index,
        Err(error) => {
            console.report(&Report::new(error));
            return EXIT_USAGE;
        }
    };
    let window = match (args.cycle, args.at) {
        (Some(cycle), _) => Window::Cycle(cycle),
        (None, at) => Window::At(at.unwrap_or(0)),
    };
    // Without a run length (command line or scenario), the run lasts until the window.
    if !prepared.limit_given {
        prepared.limit = match window {
            Window::Cycle(cycle) => RunLimit::Cycles(cycle),
            Window::At(0) => prepared.limit,
            Window::At(ns) => RunLimit::Duration(ns.saturating_add(LOOK_AFTER_AT_NS)),
        };
    }
    let ops = prepared.cpu.program.blocks[usize::from(index)].code.len();
    let (recorder, recording) = Recorder::new(index, ops, window);
    prepared.cpu.probe = Some(Box::new(recorder));
    let (ran, halted) = watched(prepared);
    console.reports(&ran.warnings);
    let recording = recording.borrow();
    if recording.invocation.is_none() {
        if let Some(stop) = &ran.outcome.stop {
            console.err(&format!("{:?}\n", runner::stop_report(&ran, stop)));
            return EXIT_STOP;
        }
        let error = did_not_run(args, window, &ran, halted);
        console.report(&Report::new(error));
        return if halted {
            EXIT_HALTED
        } else {
            EXIT_SOURCE_ERRORS
        };
    }
    let block = &ran.cpu.program.blocks[usize::from(index)];
    console.out(&program_status::render(
        block,
        &ran.frontend.sources,
        &recording,
    ));
    if let Some(stop) = &ran.outcome.stop {
        console.err(&format!("{:?}\n", runner::stop_report(&ran, stop)));
        return EXIT_STOP;
    }
    if halted && !recording.complete {
        return EXIT_HALTED;
    }
    EXIT_OK
}
