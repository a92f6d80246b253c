//! The whole front end in one call: parse each file read ([`crate::program_files`]), compile
//! them together, and keep every diagnostic of every file.

use crate::ast::SourceUnit;
use crate::compiler::{self, Compiled};
use crate::diagnostics::SourceDiagnostic;
use crate::dialect::Dialect;
use crate::fragment;
use crate::mnemonics::MnemonicSet;
use crate::parser;
use crate::profile::Profile;
use crate::source::{SourceFile, SourceSet};
use crate::symbols;

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

/// The profiles on which the program compiles without errors, each checked as with `--cpu`;
/// `awl check` without `--cpu` names them. Every error counts, so an operation or a block a
/// CPU lacks rules that CPU out.
pub fn profiles_without_errors(
    sources: &SourceSet,
    symbol_files: &[SourceFile],
    language: Language,
) -> Vec<&'static str> {
    crate::profile::PROFILES
        .iter()
        .filter(|profile| {
            !build_with_symbols(sources.clone(), symbol_files.to_vec(), language, profile)
                .has_errors()
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
