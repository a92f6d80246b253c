//! `awl conformance`: awlsim's test files, a verdict line each and the totals.

use std::path::{Path, PathBuf};

use crate::conformance::{self, Conf, Project, Tested};

use super::watch::{EXIT_HALTED, Watch};
use super::{Console, EXIT_EXPECTATION, EXIT_OK};

#[derive(Debug, clap::Args)]
#[command(
    after_long_help = "Each FILE is one test: a STEP 7 STL program with awlsim's test \
operations (`__ASSERT==` and the like), run on the speed7 CPU: startup, then OB 1 cycle after \
cycle until the program stops the CPU with CALL SFC 46. An awlsim project file (.awlpro) is \
run as awlsim runs it: its STL sources and symbol tables, its accumulators, clock memory byte, \
start information switch and mnemonics. A directory stands for every .awl and .awlpro file \
below it, except those awlsim runs through another file of the same name (a project file or a \
shell test, .sh); a FILE named alone is skipped alike. FILE.conf beside a test may set `exit_code` (0, or 30: the test must end in an \
error), `cycle_limit` and `max_runtime` (seconds), `accus` and `disabled`, as in awlsim's \
harness. A test passes when it ends as awlsim must: 0 when the program stops the CPU or \
max_runtime is over; 30 for source errors, a failed assertion or any other STOP. Each PASS and \
FAIL line ends with the simulated time and the cycles the test ran."
)]
pub struct ConformanceArgs {
    /// awlsim test files (.awl, .awlpro) or directories of them
    #[arg(required = true)]
    pub files: Vec<PathBuf>,
    /// Print only the verdict lines and the totals, no diagnostics under a failure [default:
    /// off]
    #[arg(long)]
    pub quiet: bool,
    /// A STEP 7 symbol table (ASCII export, SDF or CSV with `;`) every test is run with, as
    /// awlsim's project files give one; repeatable [default: none]
    #[arg(long = "symbols", value_name = "FILE")]
    pub symbols: Vec<PathBuf>,
}

/// Runs one test with the symbol tables `symbols`, the progress line and Ctrl-C.
fn watched_test(
    path: &Path,
    conf: &Conf,
    project: Option<&Project>,
    symbols: &[PathBuf],
) -> Tested {
    let mut watch = Watch::start();
    let mut tested =
        conformance::run_test(path, conf, project, symbols, &mut |cpu| watch.go_on(cpu));
    tested.halted |= watch.finish();
    tested
}

pub fn conformance(args: &ConformanceArgs, console: &mut Console) -> u8 {
    let mut run = |path: &Path, conf: &Conf, project: Option<&Project>| {
        watched_test(path, conf, project, &args.symbols)
    };
    let totals = conformance::run_suite(&args.files, &mut run, &mut |checked| {
        console.out(&checked.line());
        if !args.quiet {
            console.reports(&checked.reports);
            if let Some(totals) = checked.source_totals {
                console.totals("conformance", totals);
            }
        }
    });
    if totals.halted {
        console.err("awl conformance: halted\n");
        return EXIT_HALTED;
    }
    console.out(&totals.line());
    if totals.all_passed() {
        EXIT_OK
    } else {
        EXIT_EXPECTATION
    }
}
