//! A program run with the interrupt engine set up by the input: the text up to the first NUL
//! byte is the program (so the files of `programs/` are seeds as they are), the bytes after it
//! pick the CPU, the interrupt points, the SINUMERIK mode, the trace format, the OB 13
//! interval and a list of interrupt requests or hardware events. Whatever compiles runs for
//! 4 cycles under a watchdog of 20,000 fast operations a cycle; nothing may panic, every
//! request is accounted for, and the summary and STOP report are built and checked.
#![no_main]

use awl::frontend;
use awl::profile::{Family, InterruptPoints};
use awl::source::{SourceFile, SourceSet};
use awl::trace::TraceFormat;
use awl::vm::cycle::RunLimit;
use awl::vm::interrupts::{EngineConfig, Happening, OB35_DEFAULT_NS, Ob13Timing, Scheduled};
use libfuzzer_sys::fuzz_target;

/// The cycles a program runs.
const CYCLES: u64 = 4;

/// Reads the setup bytes one at a time; past their end, zeros.
struct Header<'a>(std::slice::Iter<'a, u8>);

impl Header<'_> {
    fn byte(&mut self) -> u8 {
        self.0.next().copied().unwrap_or(0)
    }

    fn word(&mut self) -> u64 {
        u64::from(self.byte()) << 8 | u64::from(self.byte())
    }
}

/// Flag bits 2 and 3: no trace, or one of the three formats.
fn trace_format(flags: u8) -> Option<TraceFormat> {
    match (flags >> 2) & 3 {
        0 => None,
        1 => Some(TraceFormat::Text),
        2 => Some(TraceFormat::Jsonl),
        _ => Some(TraceFormat::Chrome),
    }
}

fuzz_target!(
    init: awl_fuzz::quiet_reports(),
    |bytes: &[u8]| {
        let bytes = awl_fuzz::bounded(bytes);
        let render = awl_fuzz::renders_in_full(bytes);
        let split = bytes.iter().position(|&b| b == 0).unwrap_or(bytes.len());
        let (program, setup) = bytes.split_at(split);
        let mut header = Header(setup.get(1..).unwrap_or_default().iter());
        let profile = awl_fuzz::cpu(header.byte());
        let flags = header.byte();
        let mut sources = SourceSet::default();
        sources.add(SourceFile::from_bytes("fuzz.awl", program.to_vec()));
        let built = frontend::build(sources, frontend::Language::default(), profile);
        awl_fuzz::check_diagnostics(&built, render);
        if built.has_errors() {
            return;
        }
        let interrupt_obs: Vec<u8> = profile.interrupt_obs.iter().map(|entry| entry.ob).collect();
        let ob13_interval_ns = 100_000 + header.word() * 1_000;
        let mut schedule = Vec::new();
        for _ in 0..usize::from(header.byte() % 16) {
            let at_ns = header.word() * 500;
            let which = header.byte();
            let what = match profile.family {
                Family::Speed7 => Happening::Hardware {
                    module: u16::from(which % 3),
                    channel: u16::from(header.byte() % 4),
                    active_for_ns: header.word() * 100,
                },
                _ if !interrupt_obs.is_empty() => Happening::Interrupt {
                    ob: interrupt_obs[usize::from(which) % interrupt_obs.len()],
                },
                _ => continue,
            };
            schedule.push(Scheduled { at_ns, what });
        }
        let config = EngineConfig {
            points: if flags & 1 == 0 {
                InterruptPoints::Block
            } else {
                InterruptPoints::Operation
            },
            special_mode: profile.family == Family::Sinumerik840c && flags & 2 != 0,
            ob13: (profile.family == Family::S5_95f).then_some(Ob13Timing {
                interval_ns: ob13_interval_ns,
                delay_ns: 0,
                max_delay_ns: None,
            }),
            hw_modules: vec![(0, 40), (1, 41)],
            hw_addresses: Vec::new(),
            ob35_interval_ns: OB35_DEFAULT_NS,
            watchdog_ns: awl_fuzz::watchdog_ns(profile),
        };
        let setup = awl_fuzz::Setup {
            profile,
            config,
            schedule,
            limit: RunLimit::Cycles(CYCLES),
            max_cycles: CYCLES,
            trace: trace_format(flags),
            render,
        };
        awl_fuzz::run(built, setup);
    }
);
