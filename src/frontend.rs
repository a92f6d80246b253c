//! The whole front end in one call: read files, parse each, compile them together, and keep
//! every diagnostic of every file.

use std::path::{Path, PathBuf};

use miette::Diagnostic;
use thiserror::Error;

use crate::ast::SourceUnit;
use crate::compiler::{self, Compiled};
use crate::diagnostics::SourceDiagnostic;
use crate::dialect::Dialect;
use crate::fragment;
use crate::mnemonics::MnemonicSet;
use crate::parser;
use crate::profile::Profile;
use crate::source::{Files, SourceFile, SourceSet};
use crate::symbols;

/// Why the source files could not be loaded.
#[derive(Debug, Error, Diagnostic)]
pub enum SourceError {
    #[error("cannot read `{}`: {reason}", path.display())]
    #[diagnostic(
        code(awl::cli::read_file),
        help("check the path; program files are plain text (.awl)")
    )]
    Read { path: PathBuf, reason: String },

    #[error("`{}` is a scenario file, not a program", path.display())]
    #[diagnostic(
        code(awl::cli::scenario_as_program),
        help("run a scenario with `awl run --scenario {}`", path.display())
    )]
    ScenarioAsProgram { path: PathBuf },

    #[error("{count} source files: awl reads at most 65,536 at once")]
    #[diagnostic(
        code(awl::cli::too_many_files),
        help("join the files, or check them in parts")
    )]
    TooMany { count: usize },
}

/// What language the sources are read as: each choice left open (`None`, `false`) is the
/// default, so `Language::default()` is what a file says by itself.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct Language {
    /// The mnemonic set (`--mnemonics`); `None`: detected per file.
    pub mnemonics: Option<MnemonicSet>,
    /// STEP 5 or STEP 7 STL (`--dialect`); `None`: detected per file.
    pub dialect: Option<Dialect>,
    /// awlsim's test operations (`__ASSERT==` and the like) are operations too
    /// (`--extended`); off, they are unknown operations as on a real CPU.
    pub extensions: bool,
}

impl Language {
    /// The default language with the mnemonic set `set` forced.
    pub fn with_mnemonics(set: MnemonicSet) -> Self {
        Language {
            mnemonics: Some(set),
            ..Language::default()
        }
    }
}

/// The outcome of the front end.
#[derive(Debug)]
pub struct Frontend {
    pub sources: SourceSet,
    pub compiled: Compiled,
    pub diagnostics: Vec<SourceDiagnostic>,
    /// The mnemonic set of each file, detected or forced.
    pub mnemonics: Vec<MnemonicSet>,
    /// The parsed program files with their symbols resolved: what each statement was written
    /// as (`awl dump` shows constants and labels as written).
    pub units: Vec<SourceUnit>,
    /// The parsed STEP 7 files (empty for a STEP 5 program): what each STEP 7 statement was
    /// written as, for the tools that show S7 operations (`awl dump`, program status).
    pub s7_units: Vec<crate::step7::ast::S7Unit>,
}

impl Frontend {
    pub fn has_errors(&self) -> bool {
        self.diagnostics
            .iter()
            .any(|diagnostic| !diagnostic.is_warning())
    }
}

/// Reads the assignment lists; every file that cannot be read is reported.
pub fn read_symbol_files(paths: &[impl AsRef<Path>]) -> Result<Vec<SourceFile>, Vec<SourceError>> {
    read_symbol_files_in(&Files::Disk, paths)
}

/// [`read_symbol_files`] from `store`.
pub fn read_symbol_files_in(
    store: &Files,
    paths: &[impl AsRef<Path>],
) -> Result<Vec<SourceFile>, Vec<SourceError>> {
    let mut files = Vec::new();
    let mut errors = Vec::new();
    for path in paths {
        let path = path.as_ref();
        match store.source(path) {
            Ok(file) => files.push(file),
            Err(error) => errors.push(SourceError::Read {
                path: path.to_path_buf(),
                reason: error.to_string(),
            }),
        }
    }
    if errors.is_empty() {
        Ok(files)
    } else {
        Err(errors)
    }
}

/// Reads every file; every file that cannot be read is reported.
pub fn read_sources(paths: &[impl AsRef<Path>]) -> Result<SourceSet, Vec<SourceError>> {
    read_sources_in(&Files::Disk, paths)
}

/// [`read_sources`] from `store`.
pub fn read_sources_in(
    store: &Files,
    paths: &[impl AsRef<Path>],
) -> Result<SourceSet, Vec<SourceError>> {
    let mut sources = SourceSet::default();
    let mut errors = Vec::new();
    for path in paths {
        let path = path.as_ref();
        if path
            .extension()
            .is_some_and(|ext| ext.eq_ignore_ascii_case("toml"))
        {
            errors.push(SourceError::ScenarioAsProgram {
                path: path.to_path_buf(),
            });
            continue;
        }
        match store.source(path) {
            Ok(file) => {
                if sources.add(file).is_none() {
                    return Err(vec![SourceError::TooMany { count: paths.len() }]);
                }
            }
            Err(error) => errors.push(SourceError::Read {
                path: path.to_path_buf(),
                reason: error.to_string(),
            }),
        }
    }
    if errors.is_empty() {
        Ok(sources)
    } else {
        Err(errors)
    }
}

/// Parses and compiles every file of the set.
pub fn build(sources: SourceSet, language: Language, profile: &'static Profile) -> Frontend {
    build_with_symbols(sources, Vec::new(), language, profile)
}

/// Parses every program file of `sources`, reads the assignment lists `symbol_files` (they
/// join the set, so their diagnostics show their lines), replaces the program's symbols and
/// compiles.
pub fn build_with_symbols(
    mut sources: SourceSet,
    symbol_files: Vec<SourceFile>,
    language: Language,
    profile: &'static Profile,
) -> Frontend {
    if is_step7(&sources, language) {
        return build_step7(sources, symbol_files, language, profile);
    }
    let mut diagnostics = Vec::new();
    let programs = sources.files.len();
    let mut units = Vec::with_capacity(programs);
    let mut fragments = Vec::with_capacity(programs);
    for (id, file) in sources.files.iter().enumerate() {
        let parsed = parser::parse_file(id as u16, &file.text, language.mnemonics);
        diagnostics.extend(parsed.errors.into_iter().map(SourceDiagnostic::Parse));
        units.push(parsed.unit);
        fragments.push(parsed.fragment);
    }
    let placed = fragment::place(&mut units, &fragments);
    diagnostics.extend(placed.into_iter().map(SourceDiagnostic::Parse));
    for file in symbol_files {
        sources.add(file);
    }
    let default = units
        .first()
        .map_or(MnemonicSet::English, |unit| unit.mnemonics);
    let (symbols, mut symbol_errors) = symbols::load(
        &sources,
        programs..sources.files.len(),
        default,
        profile,
        false,
    );
    let uses = symbols::resolve(&mut units, &symbols, &sources, &mut symbol_errors);
    diagnostics.extend(symbol_errors.into_iter().map(SourceDiagnostic::Symbol));
    let compiled = compiler::compile(&units, &sources, profile);
    for error in &compiled.diagnostics {
        // A symbol that could not be resolved is reported once, as such; an operand a
        // symbol stands for is explained by the symbol.
        if uses.failed.contains(&error.span()) {
            continue;
        }
        let set = units
            .get(usize::from(error.span().file))
            .map_or(default, |unit| unit.mnemonics);
        diagnostics.push(match uses.explain(error, &symbols, &sources, set) {
            Some(explained) => SourceDiagnostic::Symbol(explained),
            None => SourceDiagnostic::Check(error.clone()),
        });
    }
    let mut compiled = compiled;
    compiled.program.symbols = symbols;
    diagnostics.sort_by_key(|diagnostic| {
        let span = diagnostic.span();
        (span.file, span.start)
    });
    let mnemonics = units.iter().map(|unit| unit.mnemonics).collect();
    Frontend {
        sources,
        compiled,
        diagnostics,
        mnemonics,
        units,
        s7_units: Vec::new(),
    }
}

/// The CPU profile a program runs on when none is chosen: the S7 CPU for a STEP 7 program,
/// else the default STEP 5 one.
pub fn default_profile(sources: &SourceSet, language: Language) -> &'static Profile {
    let name = if is_step7(sources, language) {
        crate::profile::DEFAULT_STEP7_PROFILE
    } else {
        crate::profile::DEFAULT_PROFILE
    };
    crate::profile::find(name).expect("the default profiles exist")
}

/// Whether the program is read as STEP 7: as `--dialect` says, else when a file shows it.
fn is_step7(sources: &SourceSet, language: Language) -> bool {
    match language.dialect {
        Some(dialect) => dialect == Dialect::Step7,
        None => sources.files.iter().any(|file| {
            let tokens = crate::lexer::lex(&file.text);
            crate::dialect::detect(&file.text, &tokens).is_some()
        }),
    }
}

/// The STEP 7 front end: each file parsed as STEP 7, the symbol tables `symbol_files` read
/// (they join the set, so their diagnostics show their lines), all compiled together.
fn build_step7(
    mut sources: SourceSet,
    symbol_files: Vec<SourceFile>,
    language: Language,
    profile: &'static Profile,
) -> Frontend {
    let options = crate::step7::ParseOptions {
        mnemonics: language.mnemonics,
        extensions: language.extensions,
    };
    let mut diagnostics = Vec::new();
    let mut units = Vec::with_capacity(sources.files.len());
    for (id, file) in sources.files.iter().enumerate() {
        let parsed = crate::step7::parse(id as u16, &file.text, options);
        diagnostics.extend(parsed.errors.into_iter().map(SourceDiagnostic::Step7));
        units.push(parsed.unit);
    }
    let programs = sources.files.len();
    for file in symbol_files {
        sources.add(file);
    }
    let default = units
        .first()
        .map_or(MnemonicSet::English, |unit| unit.mnemonics);
    let (symbols, symbol_errors) = symbols::load(
        &sources,
        programs..sources.files.len(),
        default,
        profile,
        true,
    );
    diagnostics.extend(symbol_errors.into_iter().map(SourceDiagnostic::Symbol));
    let compiled =
        crate::step7::compile::compile(&units, &sources, profile, language.extensions, symbols);
    diagnostics.extend(
        compiled
            .diagnostics
            .iter()
            .cloned()
            .map(SourceDiagnostic::Check),
    );
    if !profile.runs_step7()
        && let Some(block) = units.iter().flat_map(|unit| &unit.blocks).next()
    {
        diagnostics.push(SourceDiagnostic::Check(
            compiler::CheckError::Step7OnStep5Cpu {
                cpu: profile.name,
                profiles: crate::profile::step7_profiles().join(", "),
                at: block.header,
            },
        ));
    }
    diagnostics.sort_by_key(|diagnostic| {
        let span = diagnostic.span();
        (span.file, span.start)
    });
    let mnemonics = units.iter().map(|unit| unit.mnemonics).collect();
    Frontend {
        sources,
        compiled,
        diagnostics,
        mnemonics,
        units: Vec::new(),
        s7_units: units,
    }
}

/// The profiles on which the program compiles without errors, as each `--cpu` would check it;
/// `awl check` without `--cpu` names them. Every error counts, so an operation or a block a
/// CPU lacks rules that CPU out. `built` is the program compiled for the default profile
/// from `sources` and `symbol_files`: what its checks asked of the CPU is held against each
/// profile, so the program is not compiled per profile.
pub fn profiles_without_errors(
    built: &Frontend,
    sources: &SourceSet,
    symbol_files: &[SourceFile],
    language: Language,
) -> Vec<&'static str> {
    if !built.s7_units.is_empty() {
        return step7_profiles_without_errors(built, sources, symbol_files, language);
    }
    // A need the default profile did not meet may hide other checks of its statement: the
    // program is then compiled for a CPU that meets every need some profile meets.
    let widest;
    let checked = if all_needs_met(built) {
        built
    } else {
        widest = build_with_symbols(
            sources.clone(),
            symbol_files.to_vec(),
            language,
            crate::profile::widest(),
        );
        &widest
    };
    if checked.has_errors() {
        return Vec::new();
    }
    let mut needs = checked.compiled.program.needs.clone();
    for address in checked.compiled.program.symbols.step5_addresses() {
        needs.add(compiler::Need::Address {
            area: address.area,
            index: address.index,
        });
    }
    crate::profile::PROFILES
        .iter()
        .filter(|profile| needs.met_by(profile))
        .map(|profile| profile.name)
        .collect()
}

/// Whether the profile a STEP 5 program was compiled for met every need of its checks and of
/// its assignment lists' operands.
fn all_needs_met(built: &Frontend) -> bool {
    built.compiled.program.needs.all_met()
        && !built.diagnostics.iter().any(|diagnostic| {
            matches!(
                diagnostic,
                SourceDiagnostic::Symbol(symbols::SymbolError::OutOfRange { .. })
            )
        })
}

/// [`profiles_without_errors`] for a STEP 7 program: a block rules out every STEP 5 CPU, and
/// the S7 CPU it was compiled for is told by its errors. A program without blocks (only a
/// symbol table) is quick to compile for each profile.
fn step7_profiles_without_errors(
    built: &Frontend,
    sources: &SourceSet,
    symbol_files: &[SourceFile],
    language: Language,
) -> Vec<&'static str> {
    let has_block = built.s7_units.iter().any(|unit| !unit.blocks.is_empty());
    crate::profile::PROFILES
        .iter()
        .filter(|profile| !has_block || profile.runs_step7())
        .filter(|profile| {
            let has_errors = if profile.name == built.compiled.program.profile.name {
                built.has_errors()
            } else {
                build_with_symbols(sources.clone(), symbol_files.to_vec(), language, profile)
                    .has_errors()
            };
            !has_errors
        })
        .map(|profile| profile.name)
        .collect()
}

/// Parses and compiles source text held in memory (tests, benchmarks, fuzzing).
pub fn build_text(name: &str, text: &str, profile: &'static Profile) -> Frontend {
    build_text_with(name, text, Language::default(), profile)
}

/// [`build_text`] in the language `language`.
pub fn build_text_with(
    name: &str,
    text: &str,
    language: Language,
    profile: &'static Profile,
) -> Frontend {
    let mut sources = SourceSet::default();
    sources
        .add(SourceFile::new(name, text))
        .expect("one file fits");
    build(sources, language, profile)
}
