//! `awl test`: scenario files run on every core, each on a thread of its own, and reported in
//! the order given (PASS or FAIL lines, or JUnit XML for CI systems).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::mpsc;
use std::time::Instant;

use clap::ValueEnum;
use miette::Report;

use crate::diagnostics::Totals;
use crate::runner::{self, NotRun, Ran, RunOptions};

use super::run::failures;
use super::watch::{EXIT_HALTED, Watch};
use super::{Console, EXIT_EXPECTATION, EXIT_OK};

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum TestFormat {
    /// PASS and FAIL lines on stdout, diagnostics as text on stderr
    Text,
    /// PASS and FAIL lines on stderr, diagnostics as JSON lines on stdout
    Json,
    /// JUnit XML on stdout (one testcase per scenario), diagnostics as text on stderr
    Junit,
}

#[derive(Debug, clap::Args)]
#[command(
    after_long_help = "Each scenario runs its program as `awl run --scenario FILE` \
would: its [[event]]s set inputs and request interrupts at their times (`every` repeats one), \
and it passes when its [expect] table holds at the run's end and each [[check]] table at its \
time (`at`). `awl test` prints PASS or FAIL per scenario, in the order given, though the \
scenarios run in parallel; the watch table of a scenario's `watch` list is what `awl run \
--scenario FILE` prints. `awl help scenario` describes every key."
)]
pub struct TestArgs {
    /// Scenario files (TOML): each with its program, events, [expect] table and [[check]]
    /// tables
    #[arg(required = true)]
    pub scenarios: Vec<PathBuf>,
    /// Scenarios run at once [default: one per core]
    #[arg(long, short, value_parser = clap::value_parser!(u16).range(1..))]
    pub jobs: Option<u16>,
    /// How the results are reported [default: text]
    #[arg(long, value_enum, value_name = "FORMAT")]
    pub format: Option<TestFormat>,
    /// Print only what is wrong: error diagnostics, FAIL lines [default: off]
    #[arg(long, short)]
    pub quiet: bool,
}

/// How one scenario ended.
enum Outcome {
    Pass {
        expectations: usize,
        cycles: u64,
        mode: &'static str,
    },
    /// It ran, and what it expected did not hold.
    Fail(String),
    /// It could not run (the program's or the scenario's errors).
    Error(&'static str),
}

/// One scenario's result, made on its thread and printed in order on the main one.
struct Judged {
    outcome: Outcome,
    reports: Vec<Report>,
    totals: Option<Totals>,
    seconds: f64,
}

pub fn test(args: &TestArgs, console: &mut Console) -> u8 {
    let format = args.format.unwrap_or(TestFormat::Text);
    console.set_output(format == TestFormat::Json, args.quiet);
    super::watch::install_handler();
    let jobs = args.jobs.map_or_else(cores, usize::from);
    let started = Instant::now();
    let mut judged = Vec::with_capacity(args.scenarios.len());
    let mut halted = false;
    in_parallel(&args.scenarios, jobs, |index, result| {
        if let Some(result) = result {
            if format != TestFormat::Junit {
                print_verdict(&args.scenarios[index], &result, console);
            } else {
                console.reports(&result.reports);
            }
            judged.push(result);
        } else {
            halted = true;
        }
    });
    if halted {
        console.err("awl test: halted\n");
        return EXIT_HALTED;
    }
    let failed = judged
        .iter()
        .filter(|result| !matches!(result.outcome, Outcome::Pass { .. }))
        .count();
    match format {
        TestFormat::Junit => {
            let seconds = started.elapsed().as_secs_f64();
            console.out(&junit(&args.scenarios, &judged, seconds));
        }
        _ if !console.is_quiet() => console.out_text(&format!(
            "{} passed, {failed} failed\n",
            judged.len() - failed
        )),
        _ => {}
    }
    if failed == 0 {
        EXIT_OK
    } else {
        EXIT_EXPECTATION
    }
}

fn cores() -> usize {
    std::thread::available_parallelism().map_or(1, usize::from)
}

/// Runs each scenario on one of `jobs` threads and hands the results to `report` in the order
/// of `scenarios`, each as soon as those before it are in; `None` for a run Ctrl-C halted,
/// after which nothing more is handed.
fn in_parallel(scenarios: &[PathBuf], jobs: usize, mut report: impl FnMut(usize, Option<Judged>)) {
    let next = AtomicUsize::new(0);
    let (send, receive) = mpsc::channel();
    std::thread::scope(|scope| {
        for _ in 0..jobs.min(scenarios.len()) {
            let send = send.clone();
            let next = &next;
            scope.spawn(move || {
                loop {
                    let index = next.fetch_add(1, Ordering::Relaxed);
                    let Some(path) = scenarios.get(index) else {
                        return;
                    };
                    if send.send((index, judge(path))).is_err() {
                        return;
                    }
                }
            });
        }
        drop(send);
        let mut waiting = BTreeMap::new();
        let mut due = 0;
        for (index, result) in receive {
            waiting.insert(index, result);
            while let Some(result) = waiting.remove(&due) {
                let halted = result.is_none();
                report(due, result);
                due += 1;
                if halted {
                    // The other threads see the halt at their next cycle end.
                    return;
                }
            }
        }
    });
}

/// Runs one scenario; `None` when Ctrl-C halted it.
fn judge(path: &Path) -> Option<Judged> {
    let started = Instant::now();
    let options = RunOptions {
        scenario: Some(path.to_path_buf()),
        ..RunOptions::default()
    };
    let (outcome, reports, totals) = match runner::prepare(&options) {
        Ok(prepared) => {
            let mut watch = Watch::start().without_progress();
            let ran = prepared.run(&mut |cpu| watch.go_on(cpu));
            if watch.finish() {
                return None;
            }
            let outcome = outcome_of(&ran);
            (outcome, ran.warnings, None)
        }
        Err(NotRun::SourceErrors(reports, totals)) => (
            Outcome::Error("the program has errors"),
            reports,
            Some(totals),
        ),
        Err(NotRun::Usage(report)) => (
            Outcome::Error("the scenario could not run"),
            vec![report],
            None,
        ),
        Err(NotRun::Failed(reports)) => {
            (Outcome::Error("the scenario could not run"), reports, None)
        }
    };
    Some(Judged {
        outcome,
        reports,
        totals,
        seconds: started.elapsed().as_secs_f64(),
    })
}

fn outcome_of(ran: &Ran) -> Outcome {
    if ran.failed() {
        Outcome::Fail(failures(ran).join("; "))
    } else {
        Outcome::Pass {
            expectations: ran.expectation_count(),
            cycles: ran.outcome.cycles,
            mode: ran.outcome.mode.name(),
        }
    }
}

/// One scenario's line: PASS (left out when quiet), or FAIL with the reason.
fn print_verdict(path: &Path, judged: &Judged, console: &mut Console) {
    console.reports(&judged.reports);
    if let Some(totals) = judged.totals {
        console.totals("test", totals);
    }
    match &judged.outcome {
        Outcome::Pass {
            expectations,
            cycles,
            mode,
        } => {
            if !console.is_quiet() {
                console.out_text(&format!(
                    "PASS {}  ({}, {}, mode {mode})\n",
                    path.display(),
                    super::plural(*expectations as u64, "expectation"),
                    super::plural(*cycles, "cycle"),
                ));
            }
        }
        Outcome::Fail(failure) => {
            console.out_text(&format!("FAIL {}  {failure}\n", path.display()))
        }
        Outcome::Error(why) => console.out_text(&format!("FAIL {}  {why}\n", path.display())),
    }
}

/// The results as JUnit XML: one test suite, a test case per scenario (named by its file), a
/// `failure` for what did not hold, an `error` for a scenario that could not run.
fn junit(scenarios: &[PathBuf], judged: &[Judged], seconds: f64) -> String {
    let count = |error: bool| {
        judged
            .iter()
            .filter(|result| match result.outcome {
                Outcome::Pass { .. } => false,
                Outcome::Fail(_) => !error,
                Outcome::Error(_) => error,
            })
            .count()
    };
    let (failures, errors) = (count(false), count(true));
    let mut xml = format!(
        "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n<testsuites name=\"awl test\" tests=\"{}\" \
         failures=\"{failures}\" errors=\"{errors}\" time=\"{seconds:.3}\">\n  <testsuite \
         name=\"awl test\" tests=\"{}\" failures=\"{failures}\" errors=\"{errors}\" \
         time=\"{seconds:.3}\">\n",
        judged.len(),
        judged.len()
    );
    for (path, result) in scenarios.iter().zip(judged) {
        let name = escape(&path.display().to_string());
        let opening = format!(
            "    <testcase classname=\"awl\" name=\"{name}\" time=\"{:.3}\"",
            result.seconds
        );
        match &result.outcome {
            Outcome::Pass { .. } => xml.push_str(&format!("{opening}/>\n")),
            Outcome::Fail(failure) => xml.push_str(&format!(
                "{opening}>\n      <failure message=\"{}\"/>\n    </testcase>\n",
                escape(failure)
            )),
            Outcome::Error(why) => {
                let details: Vec<String> = result
                    .reports
                    .iter()
                    .map(|report| escape(&crate::diagnostics::render_plain(report)))
                    .collect();
                xml.push_str(&format!(
                    "{opening}>\n      <error message=\"{}\">{}</error>\n    </testcase>\n",
                    escape(why),
                    details.join("\n")
                ));
            }
        }
    }
    xml.push_str("  </testsuite>\n</testsuites>\n");
    xml
}

/// Text as XML character data or an attribute value.
fn escape(text: &str) -> String {
    let mut escaped = String::with_capacity(text.len());
    for character in text.chars() {
        match character {
            '&' => escaped.push_str("&amp;"),
            '<' => escaped.push_str("&lt;"),
            '>' => escaped.push_str("&gt;"),
            '"' => escaped.push_str("&quot;"),
            '\'' => escaped.push_str("&apos;"),
            // Characters XML 1.0 does not allow (terminal colours) are left out.
            c if c < ' ' && !matches!(c, '\n' | '\t' | '\r') => {}
            c => escaped.push(c),
        }
    }
    escaped
}
