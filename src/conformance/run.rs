//! One awlsim test file run as awlsim's harness runs it: STEP 7 with awlsim's test operations,
//! the S7 CPU, startup, then OB 1 until the CPU stops or `max_runtime` has passed.

use std::path::{Path, PathBuf};

use miette::Report;

use crate::dialect::Dialect;
use crate::frontend::Language;
use crate::profile;
use crate::runner::{self, NotRun, RunOptions};
use crate::vm::Cpu;
use crate::vm::cycle::RunLimit;

use super::conf::Conf;
use super::{Ending, Tested};

/// The CPU the tests run on: the S7 CPU of the profiles.
pub const PROFILE: &str = "speed7";

/// How long a test without `max_runtime` may run, in simulated time, before it counts as one
/// that never stops (awlsim would run it forever).
pub const UNBOUNDED_RUN_NS: u64 = 60_000_000_000;

/// The language of awlsim's tests: STEP 7 STL with awlsim's test operations, the mnemonic
/// set detected.
pub fn language() -> Language {
    Language {
        mnemonics: None,
        dialect: Some(Dialect::Step7),
        extensions: true,
    }
}

/// The run `conf` asks for, of the test file `path` with the symbol tables `symbols`.
pub fn options(path: &Path, conf: &Conf, symbols: &[PathBuf]) -> RunOptions {
    let limit = conf.max_runtime_ns.unwrap_or(UNBOUNDED_RUN_NS);
    RunOptions {
        files: vec![path.to_path_buf()],
        symbols: symbols.to_vec(),
        // `accus=4` sets the S7 CPU to four accumulators (its S7-400 variant).
        cpu: profile::find(PROFILE).and_then(|cpu| match conf.accus {
            Some(count) => profile::with_accumulators(cpu, count),
            None => Some(cpu),
        }),
        language: language(),
        // A run of no time ends at the first cycle end, as awlsim checks its limit there.
        limit: Some(RunLimit::Duration(limit.max(1))),
        watchdog_ns: Some(conf.cycle_limit_ns),
        ..RunOptions::default()
    }
}

/// Runs the test `path` as `conf` asks, with the symbol tables `symbols` (awlsim gives them
/// in a project file); `go_on` may halt it at a cycle boundary (Ctrl-C).
pub fn run_test(
    path: &Path,
    conf: &Conf,
    symbols: &[PathBuf],
    go_on: &mut dyn FnMut(&Cpu) -> bool,
) -> Tested {
    run_with(
        &options(path, conf, symbols),
        conf.max_runtime_ns.is_some(),
        go_on,
    )
}

/// Runs `options`; a run that reaches its limit ended cleanly when `limit_is_max_runtime`,
/// else it never stopped.
pub(super) fn run_with(
    options: &RunOptions,
    limit_is_max_runtime: bool,
    go_on: &mut dyn FnMut(&Cpu) -> bool,
) -> Tested {
    let not_run = |ending, reports| Tested {
        ending,
        reports,
        halted: false,
    };
    let mut prepared = match runner::prepare(options) {
        Ok(prepared) => prepared,
        Err(NotRun::SourceErrors(reports)) => return not_run(Ending::SourceErrors, reports),
        Err(NotRun::Failed(reports)) => return not_run(Ending::NotRun, reports),
        Err(NotRun::Usage(report)) => return not_run(Ending::NotRun, vec![report]),
    };
    // awlsim runs its tests on its dummy hardware (insn_MISC's direct reads rely on it).
    prepared.cpu.inputs_echo_pii = true;
    let ran = prepared.run(go_on);
    let (ending, reports): (Ending, Vec<Report>) = match &ran.outcome.stop {
        Some(stop) => (
            Ending::Stop(stop.cause),
            vec![runner::stop_report(&ran, stop)],
        ),
        None if limit_is_max_runtime => (Ending::RuntimeReached, Vec::new()),
        None => (Ending::NeverStopped, Vec::new()),
    };
    Tested {
        ending,
        reports,
        halted: ran.outcome.halted,
    }
}

#[cfg(test)]
mod tests {
    use std::collections::BTreeMap;
    use std::path::PathBuf;
    use std::sync::Arc;

    use super::*;
    use crate::source::Files;
    use crate::vm::stop::StopCause;

    /// A STEP 5 program run as a test is run, on the default CPU: the endings do not depend
    /// on the dialect.
    fn run_step5(text: &str, limit_ns: u64, watchdog_ns: u64, is_max_runtime: bool) -> Ending {
        let path = PathBuf::from("test.awl");
        let files = BTreeMap::from([(path.clone(), text.as_bytes().to_vec())]);
        let options = RunOptions {
            files: vec![path],
            store: Files::Memory(Arc::new(files)),
            limit: Some(RunLimit::Duration(limit_ns)),
            watchdog_ns: Some(watchdog_ns),
            ..RunOptions::default()
        };
        run_with(&options, is_max_runtime, &mut |_| true).ending
    }

    const MS: u64 = 1_000_000;
    const IDLE: &str = "OB 1\n      A  I 0.0\n      =  Q 4.0\n      BE\n";

    #[test]
    fn a_stop_by_the_program_is_a_clean_end() {
        let ending = run_step5("OB 1\n      STP\n      BE\n", 10 * MS, 150 * MS, false);
        assert_eq!(ending, Ending::Stop(StopCause::Stp));
        assert_eq!(ending.exit_code(), Some(0));
    }

    #[test]
    fn any_other_stop_is_a_simulator_error() {
        let ending = run_step5("OB 1\n      JU PB 9\n      BE\n", 10 * MS, 150 * MS, false);
        assert_eq!(ending, Ending::Stop(StopCause::LzfBlock));
        assert_eq!(ending.exit_code(), Some(30));
    }

    #[test]
    fn the_cycle_limit_is_the_watchdog() {
        // A thousand passes of a loop: a cycle of some milliseconds.
        let long_cycle = "OB 1\n      JU FB 1\nNAME :LOOP\n      BE\nFB 1\nNAME :LOOP\n      L  KF +1000\nM001: T  FW 12\n      L  FW 12\n      L  KF +1\n      -F\n      JN =M001\n      BE\n";
        assert_eq!(
            run_step5(long_cycle, 10 * MS, MS, false),
            Ending::Stop(StopCause::Zyk)
        );
        assert_eq!(
            run_step5(long_cycle, 10 * MS, 150 * MS, false),
            Ending::NeverStopped
        );
    }

    #[test]
    fn the_limit_ends_cleanly_only_when_it_is_max_runtime() {
        assert_eq!(
            run_step5(IDLE, 5 * MS, 150 * MS, true),
            Ending::RuntimeReached
        );
        assert_eq!(
            run_step5(IDLE, 5 * MS, 150 * MS, false),
            Ending::NeverStopped
        );
    }

    #[test]
    fn source_errors_and_missing_files_do_not_run() {
        assert_eq!(
            run_step5("OB 1\n      XYZ\n      BE\n", MS, MS, false),
            Ending::SourceErrors
        );
        let options = RunOptions {
            files: vec![PathBuf::from("no such file.awl")],
            store: Files::Memory(Arc::new(BTreeMap::new())),
            ..RunOptions::default()
        };
        assert_eq!(
            run_with(&options, false, &mut |_| true).ending,
            Ending::NotRun
        );
    }

    #[test]
    fn a_test_runs_as_step7_with_extensions_on_the_s7_cpu() {
        let conf = Conf {
            max_runtime_ns: Some(0),
            cycle_limit_ns: 2_000_000_000,
            ..Conf::default()
        };
        let options = options(Path::new("t.awl"), &conf, &[]);
        assert_eq!(options.language.dialect, Some(Dialect::Step7));
        assert!(options.language.extensions);
        assert_eq!(options.language.mnemonics, None);
        assert_eq!(options.cpu.map(|cpu| cpu.name), Some("speed7"));
        assert_eq!(options.limit, Some(RunLimit::Duration(1)));
        assert_eq!(options.watchdog_ns, Some(2_000_000_000));
        let unbounded = super::options(Path::new("t.awl"), &Conf::default(), &[]);
        assert_eq!(unbounded.limit, Some(RunLimit::Duration(UNBOUNDED_RUN_NS)));
    }
}
