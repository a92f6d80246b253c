//! Which STL a text is written in. awl reads STEP 5 and STEP 7 STL; a STEP 7 source
//! (`ORGANIZATION_BLOCK` … `BEGIN` … `END_ORGANIZATION_BLOCK`, `S5T#2S`, `DBX 0.1`, `#local`,
//! `"symbol"`) is told apart here ([`detect`]), on words STEP 5 never writes, so a STEP 5 parse
//! reports it once instead of failing on every line. A trailing `;` is no evidence: it starts a
//! comment in STEP 5. Nor is `NETWORK n`, the heading of a STEP 5 listing's segment. A text
//! without that form is weighed by the words only one dialect writes ([`word_evidence`]), and a
//! STEP 5 parse error on a STEP 7 word is said as such ([`step7_word_on_line`]).

use std::borrow::Cow;

use crate::lexer::{Token, TokenKind};
use crate::mnemonics::{self, BlockKind, MnemonicSet, OpCode};
use crate::source::{FileId, Span};
use crate::step7::ast::{Cmp, S7Op};
use crate::step7::lexer::{self as s7, Token as S7Token, TokenKind as S7Kind};
use crate::syntax::token::runs;

/// The STL dialects awl tells apart.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Dialect {
    Step5,
    Step7,
}

/// A place in a text that shows its dialect.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Evidence {
    pub dialect: Dialect,
    /// Byte offsets of the evidence in the text.
    pub start: u32,
    pub end: u32,
    /// What the evidence is, for the diagnostic's label.
    pub what: &'static str,
}

impl Evidence {
    pub fn span(&self, file: FileId) -> Span {
        Span {
            file,
            start: self.start,
            end: self.end,
        }
    }
}

/// Words that open a line of a STEP 7 source and never one of STEP 5.
pub const STEP7_LINE_WORDS: &[&str] = &[
    "ORGANIZATION_BLOCK",
    "FUNCTION_BLOCK",
    "FUNCTION",
    "DATA_BLOCK",
    "BEGIN",
    "VAR",
    "VAR_INPUT",
    "VAR_OUTPUT",
    "VAR_IN_OUT",
    "VAR_TEMP",
    "VERSION",
    "KNOW_HOW_PROTECT",
];

/// Addresses of STEP 7's data blocks (`DBX 0.1`, `DBW 4`); STEP 5 writes `D 0.1`, `DW 4`.
const STEP7_DATA_AREAS: &[&str] = &["DBX", "DBB", "DBW", "DBD", "DIX", "DIB", "DIW", "DID"];

/// The first STEP 7 evidence in the text, if any: the text is STEP 5 otherwise.
pub fn detect(source: &str, tokens: &[Token]) -> Option<Evidence> {
    runs(tokens, |kind| kind == TokenKind::Newline).find_map(|line| step7_in_line(source, line))
}

fn step7_in_line(source: &str, line: &[Token]) -> Option<Evidence> {
    let evidence = |first: Token, last: Token, what| Evidence {
        dialect: Dialect::Step7,
        start: first.start,
        end: last.end,
        what,
    };
    let first = line[0];
    let word = |token: Token| (token.kind == TokenKind::Word).then(|| token.text(source));
    if let Some(text) = word(first) {
        let keyword = STEP7_LINE_WORDS
            .iter()
            .any(|keyword| keyword.eq_ignore_ascii_case(text));
        let end = text
            .get(..4)
            .is_some_and(|start| start.eq_ignore_ascii_case("END_"));
        if keyword || end {
            return Some(evidence(first, first, "a STEP 7 block keyword"));
        }
        if text.eq_ignore_ascii_case("TITLE")
            && line.get(1).is_some_and(|t| t.kind == TokenKind::Equals)
        {
            return Some(evidence(first, line[1], "a STEP 7 title line"));
        }
    }
    line.windows(2).find_map(|pair| {
        let (a, b) = (pair[0], pair[1]);
        let hash = |token: Token| token.kind == TokenKind::Invalid && token.text(source) == "#";
        if hash(b) && a.touches(b) && a.kind == TokenKind::Word {
            return Some(evidence(
                a,
                b,
                "a STEP 7 constant such as `S5T#2S` or `W#16#FF`",
            ));
        }
        if hash(a) && a.touches(b) && b.kind == TokenKind::Word {
            return Some(evidence(a, b, "a STEP 7 local variable (`#name`)"));
        }
        if a.kind == TokenKind::Invalid && a.text(source) == "\"" {
            return Some(evidence(a, a, "a STEP 7 symbol in quotes"));
        }
        let data_area = word(a).is_some_and(|text| {
            STEP7_DATA_AREAS
                .iter()
                .any(|area| area.eq_ignore_ascii_case(text))
        });
        (data_area && b.kind == TokenKind::Number)
            .then(|| evidence(a, b, "a STEP 7 data block address"))
    })
}

/// The words of a text that only one dialect writes, counted per dialect with the first of
/// each: what decides a text that has none of [`detect`]'s certain evidence (a flat statement
/// list, a forum post). The words are derived from the two mnemonic tables, so they stay in
/// step with them.
#[derive(Debug, Default, Clone, Copy, PartialEq, Eq)]
pub struct WordEvidence {
    pub step7: Tally,
    pub step5: Tally,
}

/// How many lines show one dialect, and the first of them.
#[derive(Debug, Default, Clone, Copy, PartialEq, Eq)]
pub struct Tally {
    pub lines: usize,
    pub first: Option<Evidence>,
}

impl Tally {
    fn add(&mut self, evidence: Evidence) {
        self.lines += 1;
        self.first.get_or_insert(evidence);
    }
}

/// The words of `source` that only STEP 7 or only STEP 5 writes, one per line at most. The
/// text is read with the STEP 7 lexer (it knows `+I`, `==I`, `L#5`) and each line only up to
/// its first `;`, which ends a STEP 7 statement and starts a STEP 5 comment.
pub fn word_evidence(source: &str) -> WordEvidence {
    let tokens = s7::lex(source);
    let mut evidence = WordEvidence::default();
    for line in tokens.split(|token| token.kind == S7Kind::Newline) {
        let statement = line
            .split(|token| token.kind == S7Kind::Semicolon)
            .next()
            .unwrap_or_default();
        match line_evidence(source, statement) {
            Some(found) if found.dialect == Dialect::Step7 => evidence.step7.add(found),
            Some(found) => evidence.step5.add(found),
            None => {}
        }
    }
    evidence
}

/// What a jump to a label written without `=` is, as evidence.
const JUMP_LABEL: &str = "a STEP 7 jump label, written without `=`";

/// What an operand area only STEP 7 has is, as evidence.
const STEP7_AREA: &str = "a STEP 7 operand area";

/// What a typed constant is, as evidence.
const STEP7_CONSTANT: &str = "a STEP 7 constant";

const SETS: [MnemonicSet; 2] = [MnemonicSet::English, MnemonicSet::German];

/// A word that STEP 7 has as an operation and STEP 5 has not, in either mnemonic set (`ITB`,
/// `+I`, `==I`, `LOOP`).
pub fn step7_only_operation(upper: &str) -> Option<S7Op> {
    let s7 = SETS
        .iter()
        .find_map(|set| crate::step7::mnemonics::operation(*set, upper))?;
    let s5 = SETS
        .iter()
        .any(|set| mnemonics::operation(*set, upper).is_some());
    (!s5).then_some(s7)
}

/// An operand area that STEP 7 has and STEP 5 has not (`LW`, `DBX`, `PIW`); `MW` is German
/// STEP 5 too.
pub fn step7_only_area(upper: &str) -> bool {
    let s7 = SETS
        .iter()
        .any(|set| crate::step7::mnemonics::area(*set, upper).is_some());
    s7 && !step5_operand_word(upper)
}

/// An operand word of STEP 5: an area, a constant format or a block.
fn step5_operand_word(upper: &str) -> bool {
    BlockKind::from_word(upper).is_some()
        || SETS.iter().any(|set| {
            mnemonics::area(*set, upper).is_some()
                || mnemonics::constant_format(*set, upper).is_some()
        })
}

fn step5_only_operation(upper: &str) -> bool {
    SETS.iter()
        .any(|set| mnemonics::operation(*set, upper).is_some())
        && !SETS
            .iter()
            .any(|set| crate::step7::mnemonics::operation(*set, upper).is_some())
}

fn step5_only_operand(upper: &str) -> bool {
    step5_operand_word(upper)
        && BlockKind::from_word(upper).is_none()
        && !SETS
            .iter()
            .any(|set| crate::step7::mnemonics::area(*set, upper).is_some())
}

/// The tokens after a PG listing's address (`0034 :`), a label (`M001 :`, `m1:`) and a
/// listing's leading `:`.
fn without_label(line: &[S7Token]) -> &[S7Token] {
    let mut line = line;
    for kind in [S7Kind::Number, S7Kind::Word] {
        if let [first, colon, rest @ ..] = line
            && first.kind == kind
            && colon.kind == S7Kind::Colon
        {
            line = rest;
        }
    }
    match line {
        [colon, rest @ ..] if colon.kind == S7Kind::Colon => rest,
        _ => line,
    }
}

/// The operation word of a statement as the tables spell it (`A(`, `RND+`, `+I`, `==I`,
/// STEP 5's `X F`), and the tokens after it.
fn operation_word<'s, 't>(
    source: &'s str,
    line: &'t [S7Token],
) -> Option<(Cow<'s, str>, &'t [S7Token])> {
    let (first, rest) = line.split_first()?;
    let text = first.text(source);
    // Most listings write their operations in capitals: those are taken as they are.
    let upper = if text.bytes().any(|byte| byte.is_ascii_lowercase()) {
        Cow::Owned(text.to_ascii_uppercase())
    } else {
        Cow::Borrowed(text)
    };
    match first.kind {
        S7Kind::Word => {
            // STEP 5's `X F` (fixed-point multiply), not STEP 7's `X` (XOR).
            if upper == "X"
                && let Some(next) = rest.first().filter(|t| t.kind == S7Kind::Word)
            {
                let multiply = format!("X {}", next.text(source).to_ascii_uppercase());
                if mnemonics::operation(MnemonicSet::English, &multiply).is_some() {
                    return Some((Cow::Owned(multiply), &rest[1..]));
                }
            }
            match rest.first() {
                Some(next)
                    if first.touches(*next)
                        && matches!(next.kind, S7Kind::LParen | S7Kind::Plus | S7Kind::Minus) =>
                {
                    Some((
                        Cow::Owned(format!("{upper}{}", next.text(source))),
                        &rest[1..],
                    ))
                }
                _ => Some((upper, rest)),
            }
        }
        S7Kind::SignedWord | S7Kind::Compare => Some((upper, rest)),
        _ => None,
    }
}

fn evidence_at(first: S7Token, last: S7Token, dialect: Dialect, what: &'static str) -> Evidence {
    Evidence {
        dialect,
        start: first.start,
        end: last.end,
        what,
    }
}

/// The word of one statement (a line up to its `;`) that only one dialect writes, if any.
fn line_evidence(source: &str, line: &[S7Token]) -> Option<Evidence> {
    if let Some(found) = step5_line(source, line) {
        return Some(found);
    }
    let line = without_label(line);
    let (op, rest) = operation_word(source, line)?;
    let (op_first, op_last) = (line[0], line[line.len() - rest.len() - 1]);
    if step7_only_operation(&op).is_some() {
        return Some(evidence_at(
            op_first,
            op_last,
            Dialect::Step7,
            "a STEP 7 operation",
        ));
    }
    if step5_only_operation(&op) {
        return Some(evidence_at(
            op_first,
            op_last,
            Dialect::Step5,
            "a STEP 5 operation",
        ));
    }
    operand_evidence(source, &op, rest)
}

/// The lines only STEP 5 writes: a PG listing's address, a block's `NAME` or `DES` line, a
/// block header (`PB 1`).
fn step5_line(source: &str, line: &[S7Token]) -> Option<Evidence> {
    let (&first, second) = (line.first()?, line.get(1));
    let step5 = |last, what| Some(evidence_at(first, last, Dialect::Step5, what));
    let colon = second.filter(|t| t.kind == S7Kind::Colon);
    if let (S7Kind::Number, Some(colon)) = (first.kind, colon) {
        return step5(*colon, "a PG listing's address");
    }
    if first.kind != S7Kind::Word {
        return None;
    }
    let word = first.text(source);
    let declaration = [
        mnemonics::NAME_WORD,
        mnemonics::DECLARATION_EN,
        mnemonics::DECLARATION_DE,
    ];
    if colon.is_some()
        && declaration
            .iter()
            .any(|known| known.eq_ignore_ascii_case(word))
    {
        return step5(first, "a STEP 5 block's `NAME` or `DES` line");
    }
    match line {
        [_, number] if number.kind == S7Kind::Number && BlockKind::from_word(word).is_some() => {
            step5(*number, "a STEP 5 block header")
        }
        _ => None,
    }
}

/// The operand of the operation `op` (`rest`) when only one dialect writes it: a typed
/// constant, `=NAME`, a jump label without `=`, a STEP 5 constant format, an area of one
/// dialect only.
fn operand_evidence(source: &str, op: &str, rest: &[S7Token]) -> Option<Evidence> {
    let (&operand, &last) = (rest.first()?, rest.last()?);
    let with = |dialect, what| Some(evidence_at(operand, last, dialect, what));
    match operand.kind {
        // `16#FF`, `2#1010`: the typed constants `detect` does not see (they start with digits).
        S7Kind::Typed => {
            return Some(evidence_at(
                operand,
                operand,
                Dialect::Step7,
                STEP7_CONSTANT,
            ));
        }
        S7Kind::Equals if rest.get(1).is_some_and(|name| operand.touches(*name)) => {
            return Some(evidence_at(
                operand,
                rest[1],
                Dialect::Step5,
                "a STEP 5 label or formal operand (`=NAME`)",
            ));
        }
        S7Kind::Word => {}
        _ => return None,
    }
    let word = operand.text(source).to_ascii_uppercase();
    let glued = crate::step7::parser::letters_and_digits(&word);
    let is_jump = SETS.iter().any(|set| {
        crate::step7::mnemonics::operation(*set, op).is_some_and(crate::step7::parser::takes_label)
    });
    if is_jump {
        let block = glued.map_or(word.as_str(), |(letters, _)| letters);
        let bare_label = rest.len() == 1 && BlockKind::from_word(block).is_none();
        return bare_label.then(|| evidence_at(operand, operand, Dialect::Step7, JUMP_LABEL));
    }
    if SETS
        .iter()
        .any(|set| mnemonics::constant_format(*set, &word).is_some())
    {
        return with(Dialect::Step5, "a STEP 5 constant");
    }
    let (area, addressed) = match glued {
        Some((letters, _)) => (letters, true),
        None => (
            word.as_str(),
            rest.get(1).is_some_and(|t| t.kind == S7Kind::Number),
        ),
    };
    if !addressed {
        None
    } else if step7_only_area(area) {
        with(Dialect::Step7, STEP7_AREA)
    } else if step5_only_operand(area) {
        with(Dialect::Step5, "a STEP 5 operand")
    } else {
        None
    }
}

/// A word only STEP 7 writes, found on a line a STEP 5 parse failed on: where it stands, what it
/// is, and what STEP 5 writes instead where it has the operation (`+F` for `+I`), with
/// `--dialect s7` for a STEP 7 text.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Step7Word {
    pub evidence: Evidence,
    pub help: String,
}

/// The word only STEP 7 writes in the first statement of the line holding byte `start`, if any.
pub fn step7_word_on_line(source: &str, set: MnemonicSet, start: usize) -> Option<Step7Word> {
    if start > source.len() {
        return None;
    }
    let line_start = source[..start].rfind('\n').map_or(0, |at| at + 1);
    let line_end = source[start..]
        .find('\n')
        .map_or(source.len(), |at| start + at);
    let line = &source[line_start..line_end];
    let tokens: Vec<S7Token> = s7::lex(line)
        .into_iter()
        .map(|token| S7Token {
            start: token.start + line_start as u32,
            end: token.end + line_start as u32,
            ..token
        })
        .collect();
    let statement = tokens
        .split(|token| token.kind == S7Kind::Semicolon)
        .next()
        .unwrap_or_default();
    let evidence = line_evidence(source, statement).filter(|e| e.dialect == Dialect::Step7)?;
    let word = &source[evidence.start as usize..evidence.end as usize];
    let read_as_step7 = "if the text is STEP 7, read it with `--dialect s7`";
    let help = match step7_only_operation(&word.to_ascii_uppercase()).and_then(step5_equivalent) {
        Some(op) => format!(
            "STEP 5 writes `{}`; {read_as_step7}",
            mnemonics::op_word(set, op)
        ),
        None if word.ends_with('(') => format!(
            "STEP 5 opens brackets with `{}` and `{}` only; {read_as_step7}",
            mnemonics::op_word(set, OpCode::AndBracket),
            mnemonics::op_word(set, OpCode::OrBracket)
        ),
        None if evidence.what == STEP7_CONSTANT => format!(
            "STEP 5 writes a constant with its format: `KF +255`, `KH 00FF`, `KM 1010…`; \
             {read_as_step7}"
        ),
        None if evidence.what == JUMP_LABEL => {
            format!("STEP 5 writes a jump's label with `=`: `={word}`; {read_as_step7}")
        }
        None if evidence.what == STEP7_AREA => {
            let area = word.split(|c: char| !c.is_ascii_alphabetic()).next();
            format!(
                "STEP 5 has no operand area `{}`; {read_as_step7}",
                area.unwrap_or(word)
            )
        }
        None => format!("STEP 5 has no `{word}`; {read_as_step7}"),
    };
    Some(Step7Word { evidence, help })
}

/// The STEP 5 operation that does what a STEP 7 one does, where STEP 5 has one: its 16-bit
/// fixed-point and floating-point arithmetic, comparisons and conversions.
fn step5_equivalent(op: S7Op) -> Option<OpCode> {
    let compare = |cmp: Cmp, fixed: [OpCode; 6]| {
        let index = match cmp {
            Cmp::Eq => 0,
            Cmp::Ne => 1,
            Cmp::Gt => 2,
            Cmp::Ge => 3,
            Cmp::Lt => 4,
            Cmp::Le => 5,
        };
        fixed[index]
    };
    use OpCode::*;
    Some(match op {
        S7Op::AddInt => AddFixed,
        S7Op::SubInt => SubFixed,
        S7Op::MulInt => MulFixed,
        S7Op::DivInt => DivFixed,
        S7Op::AddReal => AddFloat,
        S7Op::SubReal => SubFloat,
        S7Op::MulReal => MulFloat,
        S7Op::DivReal => DivFloat,
        S7Op::CmpInt(cmp) => compare(cmp, [CmpEq, CmpNe, CmpGt, CmpGe, CmpLt, CmpLe]),
        S7Op::CmpReal(cmp) => compare(
            cmp,
            [
                CmpEqFloat, CmpNeFloat, CmpGtFloat, CmpGeFloat, CmpLtFloat, CmpLeFloat,
            ],
        ),
        S7Op::IntToBcd => FixedToBcd,
        S7Op::BcdToInt => BcdToFixed,
        S7Op::BcdToDint => BcdToFixedDouble,
        S7Op::DintToBcd => FixedToBcdDouble,
        S7Op::DintToReal => FixedToFloat,
        S7Op::Truncate => FloatToFixed,
        _ => return None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::lexer::lex;

    fn what(source: &str) -> Option<&'static str> {
        detect(source, &lex(source)).map(|evidence| evidence.what)
    }

    #[test]
    fn step7_sources_are_recognised_by_their_first_evidence() {
        assert_eq!(
            what("ORGANIZATION_BLOCK OB 1\nBEGIN\n"),
            Some("a STEP 7 block keyword")
        );
        assert_eq!(what("TITLE = Motor\n"), Some("a STEP 7 title line"));
        assert_eq!(
            what("      L S5T#2S;\n"),
            Some("a STEP 7 constant such as `S5T#2S` or `W#16#FF`")
        );
        assert_eq!(
            what("      A #START;\n"),
            Some("a STEP 7 local variable (`#name`)")
        );
        assert_eq!(
            what("      A \"Motor\";\n"),
            Some("a STEP 7 symbol in quotes")
        );
        assert_eq!(
            what("      A DBX 0.1;\n"),
            Some("a STEP 7 data block address")
        );
    }

    #[test]
    fn step7_only_words_come_from_both_tables() {
        for word in [
            "ITB", "BTI", "ITD", "DTR", "RND", "LOOP", "SPL", "JL", "+I", "-D", "*R", "/I", "==I",
            "<>D", ">=R", "TAR1", "CALL", "OPN",
        ] {
            assert!(step7_only_operation(word).is_some(), "{word}");
        }
        // STEP 5 has these too (German and English).
        for word in [
            "TAK", "L", "T", "U", "A", "SPA", "JU", "SPB", "BE", "NOP", "LW", "+F",
        ] {
            assert!(step7_only_operation(word).is_none(), "{word}");
        }
        for area in [
            "LW", "LB", "LD", "L", "DBX", "DBW", "DIW", "PIW", "PEW", "V",
        ] {
            assert!(step7_only_area(area), "{area}");
        }
        // German STEP 5 writes flag words `MW`; `EW`, `AW`, `T`, `Z` are both dialects'.
        for area in [
            "MW", "MB", "MD", "M", "EW", "AW", "IW", "T", "Z", "C", "DB", "KF",
        ] {
            assert!(!step7_only_area(area), "{area}");
        }
    }

    fn words(source: &str) -> (Option<&'static str>, usize, Option<&'static str>, usize) {
        let found = word_evidence(source);
        (
            found.step7.first.map(|e| e.what),
            found.step7.lines,
            found.step5.first.map(|e| e.what),
            found.step5.lines,
        )
    }

    #[test]
    fn words_of_each_dialect_are_counted_per_line() {
        assert_eq!(
            words("      L 30\n      T LW 0\n      ITB\n      L MW 2;\n"),
            (Some(STEP7_AREA), 2, None, 0)
        );
        assert_eq!(
            words("      SPA m1\nm1:   NOP 0\n"),
            (Some(JUMP_LABEL), 1, None, 0)
        );
        assert_eq!(
            words("PB 1\n      L KF +5\n      SPA =M001\nM001 :T FW 2\n      BE\n"),
            (None, 0, Some("a STEP 5 block header"), 4)
        );
        // `X F` is STEP 5's multiplication, not STEP 7's XOR; a `;` starts a STEP 5 comment.
        assert_eq!(
            words("      X F ; ITB\n"),
            (None, 0, Some("a STEP 5 operation"), 1)
        );
        assert_eq!(words("      A I 0.0\n      = Q 4.0\n"), (None, 0, None, 0));
        assert_eq!(words("      L 16#FF\n"), (Some(STEP7_CONSTANT), 1, None, 0));
    }

    #[test]
    fn step5_texts_show_no_evidence() {
        assert_eq!(what("OB 1\nNETWORK 1\n      A I 0.0;\n      BE\n"), None);
        assert_eq!(what("FB 1\nNAME :RAD:GP\nDES :EIN I BI\n      BE\n"), None);
        assert_eq!(what("PB 1\n      A § 1\n      BE\n"), None);
    }
}
