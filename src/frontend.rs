//! The whole front end in one call: parse each file read ([`crate::program_files`]), compile
//! them together, and keep every diagnostic of every file.

use crate::ast::SourceUnit;
use crate::compiler::{self, CheckError, Compiled};
use crate::diagnostics::SourceDiagnostic;
use crate::dialect::{self, Dialect};
use crate::fragment;
use crate::mnemonics::MnemonicSet;
use crate::parser;
use crate::profile::Profile;
use crate::source::{FileId, SourceFile, SourceSet};
use crate::step7::error::S7ParseError;
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
    /// The dialect the program was read in, as `--dialect` named it or the text showed it.
    pub dialect: Dialect,
}

impl Frontend {
    /// The outcome of either dialect's front end, its diagnostics in file order.
    fn new(
        sources: SourceSet,
        compiled: Compiled,
        mut diagnostics: Vec<SourceDiagnostic>,
        mnemonics: Vec<MnemonicSet>,
        units: Vec<SourceUnit>,
        s7_units: Vec<crate::step7::ast::S7Unit>,
        dialect: Dialect,
    ) -> Frontend {
        diagnostics.sort_by_key(|diagnostic| {
            let span = diagnostic.span();
            (span.file, span.start)
        });
        Frontend {
            sources,
            compiled,
            diagnostics,
            mnemonics,
            units,
            s7_units,
            dialect,
        }
    }

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
/// compiles, in the dialect `--dialect` names or the text shows (see [`decide`]).
pub fn build_with_symbols(
    sources: SourceSet,
    symbol_files: Vec<SourceFile>,
    language: Language,
    profile: &'static Profile,
) -> Frontend {
    build_for_dialect(sources, symbol_files, language, |_| profile)
}

/// [`build_with_symbols`] on the profile `profile_of` gives for the dialect the program is
/// read in, which is decided once.
pub fn build_for_dialect(
    sources: SourceSet,
    symbol_files: Vec<SourceFile>,
    language: Language,
    profile_of: impl FnOnce(Dialect) -> &'static Profile,
) -> Frontend {
    let decision = decide(&sources, language);
    let profile = profile_of(decision.dialect);
    match decision.dialect {
        Dialect::Step7 => build_step7(sources, symbol_files, language, profile, decision.note),
        Dialect::Step5 => build_step5(sources, symbol_files, language, profile),
    }
}

/// The STEP 5 front end: each file parsed as STEP 5, the assignment lists read, all compiled
/// together.
fn build_step5(
    mut sources: SourceSet,
    symbol_files: Vec<SourceFile>,
    language: Language,
    profile: &'static Profile,
) -> Frontend {
    let mut diagnostics = Vec::new();
    let programs = sources.files.len();
    let mut units = Vec::with_capacity(programs);
    let mut fragments = Vec::with_capacity(programs);
    for (id, file) in sources.files.iter().enumerate() {
        let parsed = parser::parse_file(id as u16, &file.text, language.mnemonics);
        let set = parsed.unit.mnemonics;
        diagnostics.extend(parsed.errors.into_iter().map(|error| {
            SourceDiagnostic::Parse(parser::explain_step7_word(&file.text, set, error))
        }));
        units.push(parsed.unit);
        fragments.push(parsed.fragment);
    }
    let placed = fragment::place(&mut units, &fragments);
    diagnostics.extend(placed.into_iter().map(|error| {
        let file = error.span().file;
        let set = units[usize::from(file)].mnemonics;
        SourceDiagnostic::Parse(parser::explain_step7_word(
            &sources.get(file).text,
            set,
            error,
        ))
    }));
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
        let explained = match error {
            CheckError::OperandNotAllowed { op, at, .. } => {
                uses.explain(op, *at, &symbols, &sources, set)
            }
            _ => None,
        };
        diagnostics.push(match explained {
            Some(explained) => SourceDiagnostic::Symbol(explained),
            None => SourceDiagnostic::Check(error.clone()),
        });
    }
    let mut compiled = compiled;
    compiled.program.symbols = symbols;
    let mnemonics = units.iter().map(|unit| unit.mnemonics).collect();
    Frontend::new(
        sources,
        compiled,
        diagnostics,
        mnemonics,
        units,
        Vec::new(),
        Dialect::Step5,
    )
}

/// The CPU profile a program runs on when none is chosen: its dialect's
/// ([`crate::profile::default_for`]).
pub fn default_profile(sources: &SourceSet, language: Language) -> &'static Profile {
    crate::profile::default_for(decide(sources, language).dialect)
}

/// The dialect a program is read in, and the note that says why when the text decided it
/// without block keywords.
struct Decision {
    dialect: Dialect,
    note: Option<S7ParseError>,
}

impl Decision {
    fn plain(dialect: Dialect) -> Self {
        Decision {
            dialect,
            note: None,
        }
    }
}

/// The dialect: as `--dialect` says; else STEP 7 when a file is in STEP 7 source form
/// (block keywords, `#local`, `"symbol"`, typed constants); else by the words only one
/// dialect writes (`ITB`, `+I`, `LW 0`, `JU m1` against `KF +5`, `=M001`, `PB 1`); where
/// those are missing or disagree, the dialect the program compiles in, STEP 5 when neither
/// (its errors name the STEP 7 words).
fn decide(sources: &SourceSet, language: Language) -> Decision {
    if let Some(dialect) = language.dialect {
        return Decision::plain(dialect);
    }
    let source_form = sources.files.iter().any(|file| {
        let tokens = crate::lexer::lex(&file.text);
        dialect::detect(&file.text, &tokens).is_some()
    });
    if source_form {
        return Decision::plain(Dialect::Step7);
    }
    let (mut step5_lines, mut first_step7) = (0, None);
    for (id, file) in sources.files.iter().enumerate() {
        let words = dialect::word_evidence(&file.text);
        step5_lines += words.step5.lines;
        if first_step7.is_none() {
            first_step7 = words.step7.first.map(|evidence| (id as FileId, evidence));
        }
    }
    match (first_step7, step5_lines) {
        (Some((file, evidence)), 0) => Decision {
            dialect: Dialect::Step7,
            note: Some(words_note(sources, file, evidence)),
        },
        (None, lines) if lines > 0 => Decision::plain(Dialect::Step5),
        // Both dialects show, or neither: the one the program compiles in; STEP 5 when
        // neither (the errors of a STEP 5 text name each STEP 7 word in it).
        _ => match step7_only_compiles(sources, language) {
            Some(note) => Decision {
                dialect: Dialect::Step7,
                note: Some(note),
            },
            None => Decision::plain(Dialect::Step5),
        },
    }
}

/// The note for a program that compiles as STEP 7 and not as STEP 5 (each on its dialect's
/// default CPU, without symbol tables); `None` otherwise.
fn step7_only_compiles(sources: &SourceSet, language: Language) -> Option<S7ParseError> {
    let default = crate::profile::default_for;
    let as_step5 = build_step5(
        sources.clone(),
        Vec::new(),
        language,
        default(Dialect::Step5),
    );
    let mut step5_errors = as_step5.diagnostics.iter().filter(|d| !d.is_warning());
    let first_error = step5_errors.next()?;
    let as_step7 = build_step7(
        sources.clone(),
        Vec::new(),
        language,
        default(Dialect::Step7),
        None,
    );
    if as_step7.has_errors() {
        return None;
    }
    let errors = 1 + step5_errors.count();
    Some(S7ParseError::ReadAsStep7 {
        at: first_error.span(),
        reason: format!("as STEP 5: {first_error}"),
        help: format!(
            "the text compiles as STEP 7 and has {errors} {} as STEP 5, so it was read as STEP 7; \
             statements without block keywords are OB 1; `--dialect s5` reads it as STEP 5",
            if errors == 1 { "error" } else { "errors" }
        ),
    })
}

/// The note for a text read as STEP 7 because of a word only STEP 7 writes.
fn words_note(sources: &SourceSet, file: FileId, evidence: dialect::Evidence) -> S7ParseError {
    let text = &sources.get(file).text[evidence.start as usize..evidence.end as usize];
    S7ParseError::ReadAsStep7 {
        at: evidence.span(file),
        reason: format!("`{text}`: {}", evidence.what),
        help: "STEP 5 does not write it; statements without block keywords are OB 1; \
               `--dialect s5` reads the text as STEP 5"
            .into(),
    }
}

/// The STEP 7 front end: each file parsed as STEP 7, the symbol tables `symbol_files` read
/// (they join the set, so their diagnostics show their lines), all compiled together.
fn build_step7(
    mut sources: SourceSet,
    symbol_files: Vec<SourceFile>,
    language: Language,
    profile: &'static Profile,
    note: Option<S7ParseError>,
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
        crate::compiler::step7::compile(&units, &sources, profile, language.extensions, symbols);
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
    diagnostics.extend(note.map(SourceDiagnostic::Step7));
    let mnemonics = units.iter().map(|unit| unit.mnemonics).collect();
    Frontend::new(
        sources,
        compiled,
        diagnostics,
        mnemonics,
        Vec::new(),
        units,
        Dialect::Step7,
    )
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
    let language = Language {
        dialect: Some(built.dialect),
        ..language
    };
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

/// The note "compiles without errors for --cpu …" after `awl check` without `--cpu` (and in the
/// editor).
pub fn runs_on_note(profiles: &[&str]) -> String {
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
pub fn cpu_cannot_help(built: &Frontend) -> bool {
    built.diagnostics.iter().any(|diagnostic| {
        !diagnostic.is_warning()
            && matches!(
                diagnostic,
                crate::diagnostics::SourceDiagnostic::Parse(_)
                    | crate::diagnostics::SourceDiagnostic::Symbol(_)
            )
    })
}
