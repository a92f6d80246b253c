//! One awlsim test file run as awlsim's harness runs it: STEP 7 with awlsim's test operations,
//! the S7 CPU, startup, then OB 1 until the CPU stops or `max_runtime` has passed.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use miette::Report;

use crate::dialect::Dialect;
use crate::frontend::Language;
use crate::profile;
use crate::runner::{self, NotRun, RunOptions};
use crate::source::{Files, normalize};
use crate::vm::Cpu;
use crate::vm::cycle::RunLimit;

use super::conf::Conf;
use super::project::Project;
use super::{Ending, Simulated, Tested};

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

/// The run `conf` asks for, of the test file `path` with the symbol tables `symbols`; of the
/// sources of `project` when the test is a project file.
pub fn options(
    path: &Path,
    conf: &Conf,
    project: Option<&Project>,
    symbols: &[PathBuf],
) -> RunOptions {
    let limit = conf.max_runtime_ns.unwrap_or(UNBOUNDED_RUN_NS);
    // awlsim's harness sets the accumulators when the `.conf` says; else the project's count.
    let accus = conf.accus.or(project.map(|project| project.accus));
    let mut options = RunOptions {
        files: vec![path.to_path_buf()],
        symbols: symbols.to_vec(),
        // `accus=4` sets the S7 CPU to four accumulators (its S7-400 variant).
        // awlsim's tests are STEP 7: they run on its default CPU.
        cpu: Some(profile::default_for(Dialect::Step7))
            .and_then(|cpu| match accus {
                Some(count) => profile::with_accumulators(cpu, count),
                None => Some(cpu),
            })
            .and_then(
                |cpu| match project.and_then(|project| project.image_bytes) {
                    Some(bytes) => profile::with_image_bytes(cpu, bytes),
                    None => Some(cpu),
                },
            ),
        language: language(),
        // A run of no time ends at the first cycle end, as awlsim checks its limit there.
        limit: Some(RunLimit::Duration(limit.max(1))),
        // awlsim's harness gives the cycle limit and run time on awlsim's command line, over
        // the project's: awl takes them from the `.conf` alike.
        watchdog_ns: Some(conf.cycle_limit_ns),
        ..RunOptions::default()
    };
    if let Some(project) = project {
        // Every source in memory: the project's own, the files it names, and the symbol
        // tables of the command line.
        let mut files = BTreeMap::new();
        for (name, text) in project.programs.iter().chain(&project.symbols) {
            files.insert(normalize(name), text.clone());
        }
        for table in symbols {
            // A table that cannot be read is left out here, and reported as missing.
            if let Ok(text) = std::fs::read(table) {
                files.insert(normalize(table), text);
            }
        }
        options.files = project
            .programs
            .iter()
            .map(|(name, _)| name.clone())
            .collect();
        options.symbols = project
            .symbols
            .iter()
            .map(|(name, _)| name.clone())
            .collect();
        options.symbols.extend(symbols.iter().cloned());
        options.store = Files::Memory(Arc::new(files));
        options.language.mnemonics = project.mnemonics;
    }
    options
}

/// Runs the test `path` as `conf` asks, with the symbol tables `symbols` (besides those of its
/// project file, when it is one); `go_on` may halt it at a cycle boundary (Ctrl-C).
pub fn run_test(
    path: &Path,
    conf: &Conf,
    project: Option<&Project>,
    symbols: &[PathBuf],
    go_on: &mut dyn FnMut(&Cpu) -> bool,
) -> Tested {
    let setup = CpuSetup {
        clock_memory: project.and_then(|project| project.clock_memory),
        // Without a project file, awl writes the start information, as it always does.
        start_info: project.is_none_or(|project| project.start_info),
        local_bytes: project.map(|project| project.local_bytes as usize),
    };
    run_with(
        &options(path, conf, project, symbols),
        setup,
        conf.max_runtime_ns.is_some(),
        go_on,
    )
}

/// What a project file sets on the CPU itself.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct CpuSetup {
    /// The clock memory byte's number (`MB 100`).
    pub clock_memory: Option<u16>,
    /// Whether the OBs' start information is written.
    pub start_info: bool,
    /// The L stack's size (`None`: the CPU's).
    pub local_bytes: Option<usize>,
}

impl Default for CpuSetup {
    fn default() -> Self {
        CpuSetup {
            clock_memory: None,
            start_info: true,
            local_bytes: None,
        }
    }
}

/// Runs `options`; a run that reaches its limit ended cleanly when `limit_is_max_runtime`,
/// else it never stopped.
pub(super) fn run_with(
    options: &RunOptions,
    setup: CpuSetup,
    limit_is_max_runtime: bool,
    go_on: &mut dyn FnMut(&Cpu) -> bool,
) -> Tested {
    let not_run = |ending, reports| Tested {
        ending,
        reports,
        halted: false,
        simulated: None,
        source_totals: None,
    };
    let mut prepared = match runner::prepare(options) {
        Ok(prepared) => prepared,
        Err(NotRun::SourceErrors(reports, totals)) => {
            return Tested {
                source_totals: Some(totals),
                ..not_run(Ending::SourceErrors, reports)
            };
        }
        Err(NotRun::Failed(reports)) => return not_run(Ending::NotRun, reports),
        Err(NotRun::Usage(report)) => return not_run(Ending::NotRun, vec![report]),
    };
    // awlsim runs its tests on its dummy hardware (insn_MISC's direct reads rely on it).
    prepared.cpu.inputs_echo_pii = true;
    prepared.cpu.writes_start_info = setup.start_info;
    if let Some(bytes) = setup.local_bytes {
        prepared.cpu.set_local_bytes(bytes);
    }
    if let Some(byte) = setup.clock_memory {
        let flags = prepared.cpu.program.profile.sizes.flag_bytes;
        // The project's byte is one of awlsim's flag bytes, which the S7 CPU has too.
        if byte < flags {
            prepared.cpu.clock_memory = Some(prepared.cpu.program.layout.flag_base() + byte);
        }
    }
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
        simulated: Some(Simulated {
            clock_ns: ran.outcome.clock_ns,
            cycles: ran.outcome.cycles,
        }),
        source_totals: None,
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
        run_with(&options, CpuSetup::default(), is_max_runtime, &mut |_| true).ending
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
            run_with(&options, CpuSetup::default(), false, &mut |_| true).ending,
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
        let options = options(Path::new("t.awl"), &conf, None, &[]);
        assert_eq!(options.language.dialect, Some(Dialect::Step7));
        assert!(options.language.extensions);
        assert_eq!(options.language.mnemonics, None);
        assert_eq!(options.cpu.map(|cpu| cpu.name), Some("speed7"));
        assert_eq!(options.limit, Some(RunLimit::Duration(1)));
        assert_eq!(options.watchdog_ns, Some(2_000_000_000));
        let unbounded = super::options(Path::new("t.awl"), &Conf::default(), None, &[]);
        assert_eq!(unbounded.limit, Some(RunLimit::Duration(UNBOUNDED_RUN_NS)));
    }
}
