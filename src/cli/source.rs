//! `awl check` and `awl dump`: the front end alone.

use miette::Report;

use crate::analyze::warnings::program_warnings;
use crate::diagnostics;
use crate::frontend::{self, Frontend};
use crate::program_files::{ProgramFiles, read_program};
use crate::source::Files;

use super::{
    CheckArgs, Console, DumpArgs, EXIT_OK, EXIT_SOURCE_ERRORS, EXIT_USAGE, SourceOptions, plural,
    selected_profile,
};
use crate::diagnostics::Totals;

/// Runs the front end and prints its diagnostics; `None` when a file could not be read. With
/// `with_profiles`, no `--cpu` and no project, also the profiles the program compiles on
/// without errors.
fn build(
    options: &SourceOptions,
    console: &mut Console,
    with_profiles: bool,
) -> Option<(Frontend, Option<Vec<&'static str>>)> {
    let read = match read_program(&Files::Disk, &options.files, &options.symbols) {
        Ok(read) => read,
        Err(errors) => {
            console.reports(&errors);
            return None;
        }
    };
    let ProgramFiles {
        sources,
        symbol_files,
        project,
    } = read;
    let mut language = options.language.language();
    if let Some(project) = &project {
        language = project.language(language);
    }
    let chosen = options.cpu.as_deref().map(selected_profile);
    let profile_of = |dialect| match chosen {
        Some(profile) => profile,
        None => {
            let profile = crate::profile::default_for(dialect);
            project
                .as_ref()
                .map_or(profile, |project| project.cpu(profile))
        }
    };
    // A project sets its CPU itself: which profiles would do instead is not asked.
    let inputs = (with_profiles && options.cpu.is_none() && project.is_none())
        .then(|| (sources.clone(), symbol_files.clone()));
    let built = frontend::build_for_dialect(sources, symbol_files, language, profile_of);
    let runs_on = inputs.map(|(sources, symbol_files)| {
        frontend::profiles_without_errors(&built, &sources, &symbol_files, language)
    });
    let reports: Vec<Report> = built
        .diagnostics
        .iter()
        .map(|diagnostic| diagnostics::report(&built.sources, diagnostic))
        .collect();
    console.reports(&reports);
    Some((built, runs_on))
}

/// The counts of the front end's diagnostics and `more_warnings` besides.
fn totals(built: &Frontend, more_warnings: usize) -> Totals {
    Totals::of(&built.diagnostics, built.sources.files.len()).with_warnings(more_warnings)
}

/// `awl check`: the diagnostics, then the totals and the CPUs the program compiles on (on
/// stderr with errors or `--format json`); with `--quiet` the errors alone.
pub fn check(args: &CheckArgs, console: &mut Console) -> u8 {
    args.output.apply(console);
    let Some((built, runs_on)) = build(&args.source, console, true) else {
        return EXIT_SOURCE_ERRORS;
    };
    let blocks = built.compiled.program.block_count();
    if built.has_errors() {
        console.totals("check", totals(&built, 0));
        if let Some(profiles) =
            runs_on.filter(|_| !frontend::cpu_cannot_help(&built) && !console.is_quiet())
        {
            console.err(&frontend::runs_on_note(&profiles));
        }
        return EXIT_SOURCE_ERRORS;
    }
    let warnings = program_warnings(&built.compiled.program, &built.sources);
    console.reports(&warnings);
    if console.is_quiet() {
        return EXIT_OK;
    }
    console.out_text(&format!(
        "awl check: ok, {}, {}\n",
        plural(blocks as u64, "block"),
        totals(&built, warnings.len())
    ));
    if let Some(profiles) = runs_on {
        console.out_text(&frontend::runs_on_note(&profiles));
    }
    EXIT_OK
}

pub fn dump(args: &DumpArgs, console: &mut Console) -> u8 {
    let options = &args.source;
    let Some((built, _)) = build(options, console, false) else {
        return EXIT_SOURCE_ERRORS;
    };
    if built.has_errors() {
        console.totals("dump", totals(&built, 0));
        return EXIT_SOURCE_ERRORS;
    }
    if args.listing {
        match crate::dump::listing_of(&built) {
            Ok(listing) => console.out(&listing),
            Err(error) => {
                console.report(&Report::new(error));
                return EXIT_USAGE;
            }
        }
    } else {
        console.out(&crate::dump::dump(&built));
    }
    EXIT_OK
}
