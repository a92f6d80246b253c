//! `awl conformance`: awlsim's test files run as awlsim's own harness runs them (`tests/run.sh`
//! in awlsim 0.77.1). Each `.awl` file is one program in STEP 7 STL with awlsim's test
//! operations (`__ASSERT==` …); a `.conf` beside it may set the exit code awlsim must end
//! with, the cycle limit, a run time, the accumulators, or disable the test. awlsim ends with
//! 0 when the program stops the CPU by `CALL SFC 46` or the run time is over, and with 30 when
//! the simulator reports an error: a source error, a failed assertion, any other STOP. A test
//! passes when awl ends as awlsim must. An awlsim project file (`.awlpro`) is a test too: its
//! sources and settings ([`crate::project`]) make the program and the CPU.

pub mod collect;
pub mod conf;
pub mod run;

use std::path::{Path, PathBuf};

use miette::Report;

use crate::project;
use crate::source::Files;

use crate::vm::stop::StopCause;

pub use collect::{Entry, collect};
pub use conf::{Conf, parse_conf, read_conf};
pub use project::Project;
pub use run::run_test;

/// awlsim's exit code when the simulator reported an error (`EXIT_ERR_SIM`).
pub const EXIT_SIMULATOR_ERROR: u8 = 30;

/// How a test's run ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Ending {
    /// The front end reported errors.
    SourceErrors,
    /// The CPU went to STOP.
    Stop(StopCause),
    /// `max_runtime` of simulated time passed without a STOP.
    RuntimeReached,
    /// No `max_runtime`, and the program did not stop the CPU within
    /// [`run::UNBOUNDED_RUN_NS`]: awlsim would run it forever.
    NeverStopped,
    /// The file could not be read.
    NotRun,
}

impl Ending {
    /// The exit code awlsim ends with, when it ends.
    pub fn exit_code(self) -> Option<u8> {
        match self {
            Ending::Stop(StopCause::Stp) | Ending::RuntimeReached => Some(0),
            Ending::SourceErrors | Ending::Stop(_) => Some(EXIT_SIMULATOR_ERROR),
            Ending::NeverStopped | Ending::NotRun => None,
        }
    }

    fn describe(self) -> String {
        match self {
            Ending::SourceErrors => "the program has errors".into(),
            Ending::Stop(StopCause::Stp) => "the program stopped the CPU (CALL SFC 46)".into(),
            Ending::Stop(cause) => format!("STOP {}", cause.code()),
            Ending::RuntimeReached => "ran for max_runtime without an error".into(),
            Ending::NeverStopped => format!(
                "did not reach CALL SFC 46 within {} s of simulated time (no max_runtime)",
                run::UNBOUNDED_RUN_NS / 1_000_000_000
            ),
            Ending::NotRun => "could not be read".into(),
        }
    }
}

/// A test's run: how it ended, and the diagnostics that tell why (source errors, the STOP
/// report).
pub struct Tested {
    pub ending: Ending,
    pub reports: Vec<Report>,
    /// Ctrl-C halted the run.
    pub halted: bool,
    /// How far it ran; `None` when it did not start.
    pub simulated: Option<Simulated>,
    /// The counts of the source errors, when the program had some.
    pub source_totals: Option<crate::diagnostics::Totals>,
}

/// How far a test ran: its simulated time and its cycles.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Simulated {
    pub clock_ns: u64,
    pub cycles: u64,
}

#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Verdict {
    Pass,
    Fail(String),
    Skip(String),
}

/// Whether a run that ended with `ending` is what the test expects: awlsim's `expected`
/// exit code.
pub fn judge(expected: u8, ending: Ending) -> Verdict {
    match ending.exit_code() {
        Some(code) if code == expected => Verdict::Pass,
        Some(code) => Verdict::Fail(format!(
            "{} (exit code {code}, expected {expected})",
            ending.describe()
        )),
        None => Verdict::Fail(ending.describe()),
    }
}

/// One entry's verdict and the diagnostics that explain a failure.
pub struct Checked {
    pub path: PathBuf,
    pub verdict: Verdict,
    pub reports: Vec<Report>,
    /// How far the test ran, when it ran.
    pub simulated: Option<Simulated>,
    /// The counts of the source errors among `reports`, when the program had some.
    pub source_totals: Option<crate::diagnostics::Totals>,
}

impl Checked {
    /// An entry that did not run.
    fn not_run(path: PathBuf, verdict: Verdict, reports: Vec<Report>) -> Self {
        Checked {
            path,
            verdict,
            reports,
            simulated: None,
            source_totals: None,
        }
    }

    /// `PASS path  (simulated 1.250 ms, 12 cycles)`, `FAIL path: reason  (…)`, `SKIP path:
    /// reason`; a test that did not start has no simulated time.
    pub fn line(&self) -> String {
        let path = self.path.display();
        let ran = self.simulated.map_or(String::new(), |simulated| {
            format!(
                "  (simulated {:.3} ms, {})",
                simulated.clock_ns as f64 / 1e6,
                crate::diagnostics::plural(simulated.cycles, "cycle")
            )
        });
        match &self.verdict {
            Verdict::Pass => format!("PASS {path}{ran}\n"),
            Verdict::Fail(reason) => format!("FAIL {path}: {reason}{ran}\n"),
            Verdict::Skip(reason) => format!("SKIP {path}: {reason}\n"),
        }
    }
}

/// The counts of a suite.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Totals {
    pub passed: u64,
    pub failed: u64,
    pub skipped: u64,
    /// Ctrl-C halted the suite.
    pub halted: bool,
}

impl Totals {
    /// `N passed, M failed`, and `, K skipped` when any were.
    pub fn line(&self) -> String {
        let skipped = match self.skipped {
            0 => String::new(),
            skipped => format!(", {skipped} skipped"),
        };
        format!("{} passed, {} failed{skipped}\n", self.passed, self.failed)
    }

    /// Every test that ran passed (skipped ones do not count).
    pub fn all_passed(&self) -> bool {
        self.failed == 0 && !self.halted
    }

    fn count(&mut self, verdict: &Verdict) {
        match verdict {
            Verdict::Pass => self.passed += 1,
            Verdict::Fail(_) => self.failed += 1,
            Verdict::Skip(_) => self.skipped += 1,
        }
    }
}

/// Runs every test `paths` name with `run`, handing each verdict to `each` as it is known;
/// stops early when a run was halted.
pub fn run_suite(
    paths: &[PathBuf],
    run: &mut dyn FnMut(&Path, &Conf, Option<&Project>) -> Tested,
    each: &mut dyn FnMut(&Checked),
) -> Totals {
    let mut totals = Totals::default();
    for entry in collect(paths) {
        let checked = match entry {
            Entry::Skip(path, reason) => Checked::not_run(path, Verdict::Skip(reason), Vec::new()),
            Entry::Empty(path) => Checked::not_run(
                path,
                Verdict::Fail("no .awl test file below this directory".into()),
                Vec::new(),
            ),
            Entry::Test(path) => match check(&path, run) {
                Some(checked) => checked,
                None => {
                    totals.halted = true;
                    break;
                }
            },
        };
        totals.count(&checked.verdict);
        each(&checked);
    }
    totals
}

/// One test: its `.conf`, its project file when it is one, then the run unless the `.conf`
/// rules it out; `None` when halted.
fn check(
    path: &Path,
    run: &mut dyn FnMut(&Path, &Conf, Option<&Project>) -> Tested,
) -> Option<Checked> {
    let checked = |verdict, reports| Checked::not_run(path.to_path_buf(), verdict, reports);
    let conf = match read_conf(path) {
        Ok(conf) => conf,
        Err(reports) => {
            return Some(checked(
                Verdict::Fail("its .conf has errors".into()),
                reports,
            ));
        }
    };
    if let Some(reason) = skip_reason(&conf) {
        return Some(checked(Verdict::Skip(reason), Vec::new()));
    }
    let project = match collect::is_project(path).then(|| project::read_project(&Files::Disk, path))
    {
        None => None,
        Some(Ok(project)) => Some(project),
        Some(Err(reports)) => {
            return Some(checked(
                Verdict::Fail("awl cannot run its project file as given".into()),
                reports,
            ));
        }
    };
    let tested = run(path, &conf, project.as_ref());
    if tested.halted {
        return None;
    }
    let verdict = judge(conf.exit_code, tested.ending);
    let (reports, source_totals) = match verdict {
        Verdict::Pass => (Vec::new(), None),
        _ => (tested.reports, tested.source_totals),
    };
    Some(Checked {
        simulated: tested.simulated,
        source_totals,
        ..checked(verdict, reports)
    })
}

/// Why the `.conf` rules the test out: it is disabled. (Its `accus`, 2 or 4, the S7 CPU
/// is set to.)
fn skip_reason(conf: &Conf) -> Option<String> {
    conf.disabled
        .as_ref()
        .map(|reason| format!("disabled: {reason}"))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn endings_are_judged_by_awlsim_s_exit_code() {
        let cases = [
            (Ending::Stop(StopCause::Stp), 0, Verdict::Pass),
            (Ending::RuntimeReached, 0, Verdict::Pass),
            (Ending::SourceErrors, 30, Verdict::Pass),
            (Ending::Stop(StopCause::Bcf), 30, Verdict::Pass),
            (Ending::Stop(StopCause::Zyk), 30, Verdict::Pass),
            (
                Ending::SourceErrors,
                0,
                Verdict::Fail("the program has errors (exit code 30, expected 0)".into()),
            ),
            (
                Ending::Stop(StopCause::LzfData),
                0,
                Verdict::Fail("STOP LZF (exit code 30, expected 0)".into()),
            ),
            (
                Ending::Stop(StopCause::Stp),
                30,
                Verdict::Fail(
                    "the program stopped the CPU (CALL SFC 46) (exit code 0, expected 30)".into(),
                ),
            ),
            (
                Ending::RuntimeReached,
                30,
                Verdict::Fail(
                    "ran for max_runtime without an error (exit code 0, expected 30)".into(),
                ),
            ),
            (
                Ending::NeverStopped,
                0,
                Verdict::Fail(
                    "did not reach CALL SFC 46 within 60 s of simulated time (no max_runtime)"
                        .into(),
                ),
            ),
            (
                Ending::NeverStopped,
                30,
                Verdict::Fail(Ending::NeverStopped.describe()),
            ),
            (Ending::NotRun, 0, Verdict::Fail("could not be read".into())),
            (
                Ending::NotRun,
                30,
                Verdict::Fail("could not be read".into()),
            ),
        ];
        for (ending, expected, verdict) in cases {
            assert_eq!(judge(expected, ending), verdict, "{ending:?}, {expected}");
        }
    }

    #[test]
    fn the_totals_name_skips_only_when_there_are_some() {
        let mut totals = Totals {
            passed: 3,
            failed: 1,
            ..Totals::default()
        };
        assert_eq!(totals.line(), "3 passed, 1 failed\n");
        assert!(!totals.all_passed());
        totals.failed = 0;
        totals.skipped = 2;
        assert_eq!(totals.line(), "3 passed, 0 failed, 2 skipped\n");
        assert!(totals.all_passed());
    }

    /// A directory of tests, removed when dropped.
    struct Suite(PathBuf);

    impl Suite {
        fn new(name: &str, files: &[(&str, &str)]) -> Self {
            let dir =
                std::env::temp_dir().join(format!("awl-conformance-{}-{name}", std::process::id()));
            let _ = std::fs::remove_dir_all(&dir);
            for (path, text) in files {
                let path = dir.join(path);
                std::fs::create_dir_all(path.parent().unwrap()).unwrap();
                std::fs::write(path, text).unwrap();
            }
            Suite(dir)
        }
    }

    impl Drop for Suite {
        fn drop(&mut self) {
            let _ = std::fs::remove_dir_all(&self.0);
        }
    }

    /// The suite run with a fake simulator that ends each file as its text says; the lines
    /// printed (paths relative to the suite), the files run, the totals.
    fn run_fake(suite: &Suite, paths: &[PathBuf]) -> (Vec<String>, Vec<String>, Totals) {
        let relative = |path: &Path| {
            let path = path.strip_prefix(&suite.0).unwrap_or(path);
            path.display().to_string().replace('\\', "/")
        };
        let mut ran = Vec::new();
        let mut run = |path: &Path, _: &Conf, _: Option<&Project>| {
            ran.push(relative(path));
            let text = std::fs::read_to_string(path).unwrap_or_default();
            let ending = match text.trim() {
                "stop" => Ending::Stop(StopCause::Stp),
                "assert" => Ending::Stop(StopCause::Bcf),
                "halt" => {
                    return Tested {
                        ending: Ending::Stop(StopCause::Stp),
                        reports: Vec::new(),
                        halted: true,
                        simulated: None,
                        source_totals: None,
                    };
                }
                _ => Ending::SourceErrors,
            };
            Tested {
                ending,
                reports: vec![miette::miette!("why {}", relative(path))],
                halted: false,
                simulated: None,
                source_totals: None,
            }
        };
        let mut lines = Vec::new();
        let totals = run_suite(paths, &mut run, &mut |checked| {
            let line = checked
                .line()
                .replace(&format!("{}/", suite.0.display()), "");
            let reports = checked.reports.len();
            lines.push(format!("{} [{reports}]", line.trim_end()));
        });
        (lines, ran, totals)
    }

    #[test]
    fn a_directory_is_every_awl_and_awlpro_file_below_it_with_awlsim_s_skips() {
        let suite = Suite::new(
            "walk",
            &[
                ("b.awl", "assert"),
                ("a.awl", "stop"),
                ("a.awl.conf", "# runs\nmax_runtime=1\n"),
                ("errors.awl", "garbage"),
                ("errors.awl.conf", "exit_code=30\r\n"),
                ("notes.txt", "stop"),
                ("sub/project.awl", "stop"),
                ("sub/project.awlpro", "[project]"),
                ("sub/shell.awl", "stop"),
                ("sub/shell.sh", "sh_test() { :; }"),
                ("sub/shell.awlpro", "[project]"),
                ("sub/off.awl", "stop"),
                ("sub/off.awl.conf", "disabled=needs hardware\n"),
                ("sub/four.awl", "stop"),
                ("sub/four.awl.conf", "accus=4\n"),
                ("sub/two.awl", "stop"),
                ("sub/two.awl.conf", "accus=2\n"),
                ("sub/bad.awl", "stop"),
                ("sub/bad.awl.conf", "exit_code=3\nloud=yes\n"),
                ("z/empty/.keep", ""),
            ],
        );
        let (lines, ran, totals) = run_fake(
            &suite,
            &[
                suite.0.clone(),
                suite.0.join("z"),
                suite.0.join("sub/project.awlpro"),
                suite.0.join("sub/shell.sh"),
            ],
        );
        assert_eq!(
            lines,
            [
                "PASS a.awl [0]",
                "FAIL b.awl: STOP BCF (exit code 30, expected 0) [1]",
                "PASS errors.awl [0]",
                "FAIL sub/bad.awl: its .conf has errors [2]",
                "PASS sub/four.awl [0]",
                "SKIP sub/off.awl: disabled: needs hardware [0]",
                "SKIP sub/project.awl: awlsim runs it through project.awlpro (awlsim project file) [0]",
                "FAIL sub/project.awlpro: awl cannot run its project file as given [1]",
                "SKIP sub/shell.awl: awlsim runs it through shell.awlpro (awlsim project file) [0]",
                "SKIP sub/shell.awlpro: awlsim runs it through shell.sh (awlsim shell test) [0]",
                "PASS sub/two.awl [0]",
                "FAIL z: no .awl test file below this directory [0]",
                "FAIL sub/project.awlpro: awl cannot run its project file as given [1]",
                "SKIP sub/shell.sh: awl conformance runs .awl and .awlpro files (awlsim shell test) [0]",
            ]
        );
        assert_eq!(
            ran,
            [
                "a.awl",
                "b.awl",
                "errors.awl",
                "sub/four.awl",
                "sub/two.awl"
            ]
        );
        assert_eq!(
            totals,
            Totals {
                passed: 4,
                failed: 5,
                skipped: 5,
                halted: false
            }
        );
    }

    #[test]
    fn files_run_in_the_order_given_and_a_halt_ends_the_suite() {
        let suite = Suite::new(
            "halt",
            &[
                ("one.awl", "stop"),
                ("two.awl", "halt"),
                ("three.awl", "stop"),
            ],
        );
        let paths = ["one.awl", "two.awl", "three.awl"].map(|name| suite.0.join(name));
        let (lines, ran, totals) = run_fake(&suite, &paths);
        assert_eq!(lines, ["PASS one.awl [0]"]);
        assert_eq!(ran, ["one.awl", "two.awl"]);
        assert!(totals.halted && !totals.all_passed());
    }
}
