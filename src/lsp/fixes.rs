//! Quick fixes: the edit a diagnostic's help names, for the diagnostics where the fix is
//! mechanical. Each code has its function; [`quick_fixes`] picks it.

use crate::ast::BlockBody;
use crate::diagnostics::SourceDiagnostic;
use crate::dialect::Dialect;
use crate::lsp::text::{FileLanguage, LineIndex, TextEdit};
use crate::mnemonics;
use crate::step7::mnemonics as s7_mnemonics;

/// What the server knows of one diagnostic: its code, its primary span in bytes, its message
/// and its help.
#[derive(Debug, Clone, Copy)]
pub struct Diagnostic<'a> {
    pub code: &'a str,
    pub start: usize,
    pub end: usize,
    pub message: &'a str,
    pub help: Option<&'a str>,
}

/// A code action: a title and the edits that make it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct QuickFix {
    pub title: String,
    pub edits: Vec<TextEdit>,
}

/// The codes [`quick_fixes`] has a fix for.
pub const FIXABLE: &[&str] = &[
    "awl::parse::unknown_operation",
    "awl::s7::unknown_operation",
    "awl::parse::unknown_operand",
    "awl::s7::unknown_operand",
    "awl::parse::mixed_mnemonics",
    "awl::s7::mixed_mnemonics",
    "awl::parse::formals_from_use",
    "awl::parse::decimal_float",
];

/// The fixes of `diagnostic` in `text` (none when its help names no mechanical edit).
pub fn quick_fixes(text: &str, diagnostic: &Diagnostic, language: FileLanguage) -> Vec<QuickFix> {
    if diagnostic.start > diagnostic.end || text.get(diagnostic.start..diagnostic.end).is_none() {
        return Vec::new();
    }
    let fix = match diagnostic.code {
        "awl::parse::unknown_operation" | "awl::s7::unknown_operation" => {
            unknown_operation(text, diagnostic)
        }
        "awl::parse::unknown_operand" | "awl::s7::unknown_operand" => {
            unknown_operand(text, diagnostic)
        }
        "awl::parse::mixed_mnemonics" | "awl::s7::mixed_mnemonics" => {
            mixed_mnemonics(text, diagnostic, language)
        }
        "awl::parse::formals_from_use" => formals_from_use(text, diagnostic),
        "awl::parse::decimal_float" => decimal_float(text, diagnostic),
        _ => None,
    };
    fix.into_iter().collect()
}

/// The fixes of a diagnostic of the front end about `text`.
pub fn quick_fixes_of(
    text: &str,
    diagnostic: &SourceDiagnostic,
    language: FileLanguage,
) -> Vec<QuickFix> {
    let Some(code) = miette::Diagnostic::code(diagnostic).map(|code| code.to_string()) else {
        return Vec::new();
    };
    let help = miette::Diagnostic::help(diagnostic).map(|help| help.to_string());
    let message = diagnostic.to_string();
    let span = diagnostic.span();
    let plain = Diagnostic {
        code: &code,
        start: span.start as usize,
        end: span.end as usize,
        message: &message,
        help: help.as_deref(),
    };
    quick_fixes(text, &plain, language)
}

/// The texts in backticks of a help or message.
fn quoted(text: &str) -> impl Iterator<Item = &str> {
    text.split('`').skip(1).step_by(2)
}

fn replace(text: &str, diagnostic: &Diagnostic, new_text: &str, title: String) -> QuickFix {
    let index = LineIndex::new(text);
    QuickFix {
        title,
        edits: vec![index.edit(diagnostic.start, diagnostic.end, new_text)],
    }
}

/// `T1` → `T 1` (the operation and its operand without their blank), `M001 A` → `M001 :A`
/// (a label without its colon), `JUU` → `JU` (a close spelling).
fn unknown_operation(text: &str, diagnostic: &Diagnostic) -> Option<QuickFix> {
    let help = diagnostic.help?;
    let word = &text[diagnostic.start..diagnostic.end];
    let written = quoted(help).last()?;
    if help.starts_with("a blank separates") && written.replace(' ', "").eq_ignore_ascii_case(word)
    {
        return Some(replace(
            text,
            diagnostic,
            written,
            format!("Write `{written}`"),
        ));
    }
    if help.starts_with("a label ends with") {
        let (label, _) = written.split_once(':')?;
        if !label.trim().eq_ignore_ascii_case(word) {
            return None;
        }
        let index = LineIndex::new(text);
        let colon = if written.contains(" :") { " :" } else { ":" };
        return Some(QuickFix {
            title: format!("Write `{written}`"),
            edits: vec![index.edit(diagnostic.end, diagnostic.end, colon)],
        });
    }
    close_spelling(text, diagnostic)
}

/// A bit operand without its bit (`F1` → `F 1.0`), or a close spelling of an operand word.
fn unknown_operand(text: &str, diagnostic: &Diagnostic) -> Option<QuickFix> {
    let help = diagnostic.help?;
    let word = &text[diagnostic.start..diagnostic.end];
    if help.contains("is a bit operand") {
        let written = quoted(help).last()?;
        let without_bit = written.strip_suffix(".0")?.replace(' ', "");
        return without_bit
            .eq_ignore_ascii_case(word)
            .then(|| replace(text, diagnostic, written, format!("Write `{written}`")));
    }
    close_spelling(text, diagnostic)
}

fn close_spelling(text: &str, diagnostic: &Diagnostic) -> Option<QuickFix> {
    let help = diagnostic.help?;
    if !help.starts_with("did you mean") {
        return None;
    }
    let candidate = quoted(help).next()?;
    Some(replace(
        text,
        diagnostic,
        candidate,
        format!("Change to `{candidate}`"),
    ))
}

/// A word of the other mnemonic set → the file's word for it, looked up in the mnemonic
/// tables; of the operation and the area reading, the one the help names.
fn mixed_mnemonics(
    text: &str,
    diagnostic: &Diagnostic,
    language: FileLanguage,
) -> Option<QuickFix> {
    let help = diagnostic.help?;
    let word = &text[diagnostic.start..diagnostic.end];
    let named: Vec<&str> = quoted(help).collect();
    let own = equivalents(word, language)
        .into_iter()
        .find(|candidate| named.contains(candidate))?;
    Some(replace(
        text,
        diagnostic,
        own,
        format!("Write the {} word `{own}`", language.mnemonics.name()),
    ))
}

/// What `word` of the other set is in the file's set, as an operation and as an area.
fn equivalents(word: &str, language: FileLanguage) -> Vec<&'static str> {
    let set = language.mnemonics;
    let other = set.other();
    let upper = word.to_ascii_uppercase();
    match language.dialect {
        Dialect::Step5 => [
            mnemonics::operation(other, word).map(|info| mnemonics::op_word(set, info.op)),
            mnemonics::area(other, word).map(|area| mnemonics::area_word(set, area)),
        ]
        .into_iter()
        .flatten()
        .collect(),
        Dialect::Step7 => [
            s7_mnemonics::operation(other, &upper).map(|op| s7_mnemonics::op_word(set, op)),
            s7_mnemonics::area(other, &upper)
                .map(|(area, width)| s7_mnemonics::area_word(set, area, width)),
        ]
        .into_iter()
        .flatten()
        .collect(),
    }
}

/// Formal operands used but not declared: the `DES`/`BEZ` lines the help lists, inserted
/// before the block's first statement.
fn formals_from_use(text: &str, diagnostic: &Diagnostic) -> Option<QuickFix> {
    let help = diagnostic.help?;
    let declarations: Vec<&str> = quoted(help)
        .filter(|line| {
            let upper = line.to_ascii_uppercase();
            upper.starts_with(mnemonics::DECLARATION_EN)
                || upper.starts_with(mnemonics::DECLARATION_DE)
        })
        .collect();
    if declarations.is_empty() {
        return None;
    }
    let at = first_statement_line(text, diagnostic.start)?;
    let mut inserted = declarations.join("\n");
    inserted.push('\n');
    let index = LineIndex::new(text);
    Some(QuickFix {
        title: format!(
            "Declare the formal operand{}",
            if declarations.len() == 1 { "" } else { "s" }
        ),
        edits: vec![index.edit(at, at, inserted)],
    })
}

/// The start of the line of the first statement of the block holding `offset`.
fn first_statement_line(text: &str, offset: usize) -> Option<usize> {
    let parsed = crate::parser::parse_file(0, text, None);
    let block = parsed
        .unit
        .blocks
        .iter()
        .rfind(|block| (block.header.start as usize) <= offset)
        .or(parsed.unit.blocks.first())?;
    let BlockBody::Logic(body) = &block.body else {
        return None;
    };
    let first = body.statements.first()?.span.start as usize;
    Some(text[..first].rfind('\n').map_or(0, |at| at + 1))
}

/// `KG 1.5` → the PG's `KG +1500000+01`, as the message names it.
fn decimal_float(text: &str, diagnostic: &Diagnostic) -> Option<QuickFix> {
    let pg_form = quoted(diagnostic.message).find(|quoted| quoted.starts_with("KG "))?;
    Some(replace(
        text,
        diagnostic,
        pg_form,
        format!("Write `{pg_form}`"),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frontend::{Frontend, Language, build_text_with, default_profile};
    use crate::lsp::text::apply;
    use crate::source::{SourceFile, SourceSet};

    fn build(text: &str) -> Frontend {
        let language = Language::default();
        let mut sources = SourceSet::default();
        sources.add(SourceFile::new("t.awl", text)).unwrap();
        build_text_with("t.awl", text, language, default_profile(&sources, language))
    }

    /// `text` with the first fix of its first diagnostic with `code` applied.
    fn fixed(text: &str, code: &str) -> String {
        let frontend = build(text);
        let language = FileLanguage::of(&frontend, 0);
        let diagnostic = frontend
            .diagnostics
            .iter()
            .find(|d| miette::Diagnostic::code(*d).is_some_and(|c| c.to_string() == code))
            .unwrap_or_else(|| panic!("no {code} in {:?}", frontend.diagnostics));
        let fixes = quick_fixes_of(text, diagnostic, language);
        assert!(!fixes.is_empty(), "no fix for {diagnostic:?}");
        apply(text, &fixes[0].edits)
    }

    /// `text` with its `code` fixed holds `wanted` and compiles.
    fn assert_fixed_to(text: &str, code: &str, wanted: &str) {
        let result = fixed(text, code);
        assert!(result.contains(wanted), "{result}");
        compiles(&result);
    }

    fn compiles(text: &str) {
        let frontend = build(text);
        assert!(!frontend.has_errors(), "{:?}", frontend.diagnostics);
    }

    #[test]
    fn operation_and_operand_without_their_blank() {
        let text = "PB 1\n      A I 0.0\n      NOP0\n      BE\n";
        let result = fixed(text, "awl::parse::unknown_operation");
        assert_eq!(result, "PB 1\n      A I 0.0\n      NOP 0\n      BE\n");
        compiles(&result);
    }

    #[test]
    fn transfer_without_its_blank() {
        let text = "PB 1\n      L KF +5\n      T1\n      BE\n";
        let result = fixed(text, "awl::parse::unknown_operation");
        assert!(result.contains("\n      T 1\n"), "{result}");
    }

    #[test]
    fn bit_operand_without_its_bit() {
        let text = "PB 1\n      A F1\n      = Q 4.0\n      BE\n";
        assert_fixed_to(text, "awl::parse::unknown_operand", "      A F 1.0\n");
    }

    #[test]
    fn label_without_its_colon() {
        let text = "FB 1\nNAME :X\nM001 A I 1.0\n      BE\n";
        let result = fixed(text, "awl::parse::unknown_operation");
        assert!(
            result.contains("M001 : A I 1.0") || result.contains("M001: A I 1.0"),
            "{result}"
        );
        compiles(&result);
    }

    #[test]
    fn close_spelling_of_an_operation() {
        let text = "PB 1\n      A I 0.0\n      JUU PB 2\n      BE\nPB 2\n      BE\n";
        assert_fixed_to(text, "awl::parse::unknown_operation", "      JU PB 2");
    }

    #[test]
    fn german_word_in_an_english_file() {
        let text = "PB 1\n      A I 0.0\n      JC PB 2\n      SPA PB 2\n      BE\nPB 2\n      BE\n";
        assert_fixed_to(text, "awl::parse::mixed_mnemonics", "      JU PB 2");
    }

    #[test]
    fn german_word_in_an_english_step7_file() {
        let text = "FUNCTION FC 1 : VOID\nBEGIN\n      A I 0.0;\n      AN I 0.1;\n      U I 0.2;\n      = Q 4.0;\nEND_FUNCTION\n";
        assert_fixed_to(text, "awl::s7::mixed_mnemonics", "      A I 0.2;");
    }

    #[test]
    fn undeclared_formal_operands_get_their_declarations() {
        let text = "FB 1\nNAME :X\n      A =EIN\n      = =AUS\n      BE\n";
        let result = fixed(text, "awl::parse::formals_from_use");
        let declared = result.find("DES :EIN").expect(&result);
        assert!(declared < result.find("A =EIN").unwrap(), "{result}");
        let frontend = build(&result);
        assert!(
            frontend.diagnostics.iter().all(|d| {
                miette::Diagnostic::code(d)
                    .is_none_or(|c| c.to_string() != "awl::parse::formals_from_use")
            }),
            "{:?}",
            frontend.diagnostics
        );
    }

    #[test]
    fn decimal_floating_point_constant_in_the_pg_form() {
        let text = "PB 1\n      L KG 1.5\n      T FD 10\n      BE\n";
        let result = fixed(text, "awl::parse::decimal_float");
        assert!(!result.contains("1.5"), "{result}");
        let frontend = build(&result);
        assert!(
            frontend.diagnostics.is_empty(),
            "{:?}",
            frontend.diagnostics
        );
    }

    #[test]
    fn no_fix_without_a_named_edit_or_for_a_span_outside_the_text() {
        let language = FileLanguage::of_text("PB 1\n      BE\n");
        let unknown = Diagnostic {
            code: "awl::parse::unknown_operation",
            start: 5,
            end: 7,
            message: "unknown operation",
            help: Some("`awl help mnemonics` lists the operations"),
        };
        assert!(quick_fixes("PB 1\n      BE\n", &unknown, language).is_empty());
        let outside = Diagnostic {
            start: 90,
            end: 99,
            ..unknown
        };
        assert!(quick_fixes("PB 1\n", &outside, language).is_empty());
    }
}
