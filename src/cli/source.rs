//! `awl check` and `awl dump`: the front end alone.

use miette::Report;

use crate::analyze::warnings::program_warnings;
use crate::diagnostics;
use crate::frontend::{self, Frontend};

use super::{
    Console, DumpArgs, EXIT_OK, EXIT_SOURCE_ERRORS, EXIT_USAGE, SourceOptions, plural,
    selected_profile,
};

/// Runs the front end and prints its diagnostics; `None` when a file could not be read. With
/// `with_profiles` and no `--cpu`, also the profiles the program compiles on without errors.
fn build(
    options: &SourceOptions,
    console: &mut Console,
    with_profiles: bool,
) -> Option<(Frontend, Option<Vec<&'static str>>)> {
    let sources = match frontend::read_sources(&options.files) {
        Ok(sources) => sources,
        Err(errors) => {
            for error in errors {
                console.report(&Report::new(error));
            }
            return None;
        }
    };
    let symbol_files = match frontend::read_symbol_files(&options.symbols) {
        Ok(files) => files,
        Err(errors) => {
            for error in errors {
                console.report(&Report::new(error));
            }
            return None;
        }
    };
    let language = options.language.language();
    let profile = match options.cpu.as_deref() {
        Some(name) => selected_profile(Some(name)),
        None => frontend::default_profile(&sources, language),
    };
    let inputs =
        (with_profiles && options.cpu.is_none()).then(|| (sources.clone(), symbol_files.clone()));
    let built = frontend::build_with_symbols(sources, symbol_files, language, profile);
    let runs_on = inputs.map(|(sources, symbol_files)| {
        frontend::profiles_without_errors(&built, &sources, &symbol_files, language)
    });
    for diagnostic in &built.diagnostics {
        console.report(&diagnostics::report(&built.sources, diagnostic));
    }
    Some((built, runs_on))
}

/// "runs on: …" after `awl check` without `--cpu`.
fn runs_on_note(profiles: &[&str]) -> String {
    if profiles.is_empty() {
        "note: no CPU profile compiles it without errors\n".to_string()
    } else if profiles.len() == crate::profile::PROFILES.len() {
        "note: compiles without errors for every CPU profile (`awl cpus`)\n".to_string()
    } else {
        format!(
            "note: compiles without errors for --cpu {}\n",
            profiles.join(", ")
        )
    }
}

/// Whether the errors are ones no choice of CPU removes: the text itself does not parse, or an
/// assignment list is wrong. The "compiles for --cpu" note is then left out.
fn cpu_cannot_help(built: &Frontend) -> bool {
    built.diagnostics.iter().any(|diagnostic| {
        !diagnostic.is_warning()
            && matches!(
                diagnostic,
                diagnostics::SourceDiagnostic::Parse(_) | diagnostics::SourceDiagnostic::Symbol(_)
            )
    })
}

/// "0 errors, 2 warnings in 1 file": the front end's diagnostics and `more_warnings` besides.
fn count_summary(built: &Frontend, more_warnings: usize) -> String {
    let errors = built.diagnostics.iter().filter(|d| !d.is_warning()).count();
    let notes = built.diagnostics.iter().filter(|d| d.is_note()).count();
    let warnings = built.diagnostics.len() - errors - notes + more_warnings;
    let notes = match notes {
        0 => String::new(),
        _ => format!(", {}", plural(notes as u64, "note")),
    };
    format!(
        "{}, {}{notes} in {}",
        plural(errors as u64, "error"),
        plural(warnings as u64, "warning"),
        plural(built.sources.files.len() as u64, "file")
    )
}

pub fn check(options: &SourceOptions, console: &mut Console) -> u8 {
    let Some((built, runs_on)) = build(options, console, true) else {
        return EXIT_SOURCE_ERRORS;
    };
    let blocks = built.compiled.program.blocks.len() + built.compiled.program.data_blocks.len();
    if built.has_errors() {
        console.err(&format!("awl check: {}\n", count_summary(&built, 0)));
        if let Some(profiles) = runs_on.filter(|_| !cpu_cannot_help(&built)) {
            console.err(&runs_on_note(&profiles));
        }
        return EXIT_SOURCE_ERRORS;
    }
    let warnings = program_warnings(&built.compiled.program, &built.sources);
    console.reports(&warnings);
    console.out(&format!(
        "awl check: ok, {}, {}\n",
        plural(blocks as u64, "block"),
        count_summary(&built, warnings.len())
    ));
    if let Some(profiles) = runs_on {
        console.out(&runs_on_note(&profiles));
    }
    EXIT_OK
}

pub fn dump(args: &DumpArgs, console: &mut Console) -> u8 {
    let options = &args.source;
    let Some((built, _)) = build(options, console, false) else {
        return EXIT_SOURCE_ERRORS;
    };
    if built.has_errors() {
        console.err(&format!("awl dump: {}\n", count_summary(&built, 0)));
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
