//! One statement of a STEP 7 body: `[LABEL:] OPERATION [operand]`, with `CALL`'s block,
//! instance and parameter list, and awlsim's test statements.

use nom::Parser;
use nom::combinator::opt;
use nom::multi::separated_list0;
use nom::sequence::preceded;

use crate::ast::Name;
use crate::source::Span;
use crate::step7::ast::{
    CallParam, CallSpec, Cmp, Combination, S7BlockRef, S7Op, S7Operand, S7Statement,
};
use crate::step7::error::S7ParseError;
use crate::step7::lexer::{Token, TokenKind};
use crate::step7::mnemonics;

use super::operand::{Expect, block_number_tokens, local_path, operand, symbol_name};
use super::step5;
use super::tokens::{Ctx, Fail, PResult, Tokens, fail, kind};

/// What a statement's tokens hold.
#[derive(Debug)]
pub enum Line {
    Statement(Box<S7Statement>),
    /// `M001:` alone: the label of the next statement.
    Label(Name),
}

/// Parses the tokens of one statement (without its `;` and line ends).
pub fn statement(ctx: Ctx<'_>, tokens: &[Token]) -> Result<Line, S7ParseError> {
    let input = Tokens::new(tokens);
    // `DES :EIN I BI` would read as a label `DES`.
    let declaration = input.first().and_then(|first| ctx.word(first));
    if matches!(declaration.as_deref(), Some("DES" | "BEZ"))
        && let Some(diagnostic) = input.first().and_then(|first| step5::operation(ctx, first))
    {
        return Err(diagnostic);
    }
    let (input, label) = label(ctx, input)?;
    let Some(first) = input.first() else {
        let label = label.expect("a statement has tokens");
        return Ok(Line::Label(label));
    };
    let (rest, (op, op_span)) = operation(ctx, input)?;
    let (rest, op) = special_operand(ctx, rest, op);
    let last = *tokens.last().unwrap_or(&first);
    let (rest, operand, call) = if op == S7Op::Call {
        let (rest, (operand, call)) = finish(ctx, last, call(ctx, rest))?;
        (rest, operand, Some(call))
    } else {
        let (rest, operand) = finish(ctx, last, operand_of(ctx, op)(rest))?;
        (rest, operand, None)
    };
    let operand_span = operand_span(ctx, input.skip(op_tokens(input, op_span)), rest, op_span);
    if let Some(extra) = rest.first() {
        return Err(unexpected(ctx, extra, "the end of the statement"));
    }
    check_operand(ctx, op, &operand, op_span)?;
    Ok(Line::Statement(Box::new(S7Statement {
        label,
        op,
        op_span,
        operand,
        operand_span,
        call,
        network: 0,
        span: ctx.span_of(*tokens.first().unwrap_or(&first), last),
    })))
}

/// How many tokens the operation took.
fn op_tokens(input: Tokens<'_>, op_span: Span) -> usize {
    input
        .tokens
        .iter()
        .take_while(|t| t.end <= op_span.end)
        .count()
}

fn operand_span(ctx: Ctx<'_>, before: Tokens<'_>, after: Tokens<'_>, op_span: Span) -> Span {
    if before.tokens.len() == after.tokens.len() {
        return Span {
            start: op_span.end,
            end: op_span.end,
            ..op_span
        };
    }
    ctx.consumed(before, after)
}

/// A nom result as the statement's diagnostic; `last` is the statement's last token, where a
/// statement that ends too early is reported.
pub fn finish<'a, T>(
    ctx: Ctx<'_>,
    last: Token,
    result: PResult<'a, T>,
) -> Result<(Tokens<'a>, T), S7ParseError> {
    result.map_err(|error| {
        let fail = Fail::of(error);
        match (fail.diagnostic, fail.at) {
            (Some(diagnostic), _) => *diagnostic,
            (None, Some(at)) => unexpected(ctx, at, fail.expected),
            (None, None) => S7ParseError::UnexpectedToken {
                found: "end of statement".into(),
                at: ctx.span(last),
                expected: fail.expected.into(),
            },
        }
    })
}

pub fn unexpected(ctx: Ctx<'_>, token: Token, expected: &str) -> S7ParseError {
    if token.kind == TokenKind::Invalid {
        return S7ParseError::UnexpectedCharacter {
            found: ctx.text(token).into(),
            at: ctx.span(token),
        };
    }
    S7ParseError::UnexpectedToken {
        found: format!("`{}`", ctx.text(token)),
        at: ctx.span(token),
        expected: expected.into(),
    }
}

/// `M001:` before the operation.
fn label<'a>(ctx: Ctx<'a>, input: Tokens<'a>) -> Result<(Tokens<'a>, Option<Name>), S7ParseError> {
    match (input.first(), input.second()) {
        (Some(word), Some(colon))
            if word.kind == TokenKind::Word && colon.kind == TokenKind::Colon =>
        {
            let text = ctx.text(word);
            if text.chars().count() > 4 {
                return Err(S7ParseError::BadLabel {
                    label: text.into(),
                    at: ctx.span(word),
                });
            }
            Ok((
                input.skip(2),
                Some(Name {
                    text: text.into(),
                    span: ctx.span(word),
                }),
            ))
        }
        _ => Ok((input, None)),
    }
}

/// The operation word, with `(` or `)` where it has one (`A(`, `)MCR`, `RND+`).
fn operation<'a>(
    ctx: Ctx<'a>,
    input: Tokens<'a>,
) -> Result<(Tokens<'a>, (S7Op, Span)), S7ParseError> {
    let first = input.first().expect("checked");
    let next = input.second();
    let touching = |kind: TokenKind| next.filter(|t| t.kind == kind && first.touches(*t));
    let (word, used) = match first.kind {
        TokenKind::Word => {
            let upper = ctx.upper(first);
            if let Some(paren) = touching(TokenKind::LParen) {
                (format!("{upper}("), Some(paren))
            } else if let Some(sign) = touching(TokenKind::Plus).or(touching(TokenKind::Minus)) {
                (format!("{upper}{}", ctx.text(sign)), Some(sign))
            } else if next.is_some_and(|t| t.kind == TokenKind::LParen)
                && input.tokens.len() == 2
                && mnemonics::operation(ctx.set, &format!("{upper}(")).is_some()
            {
                (format!("{upper}("), next)
            } else {
                (upper, None)
            }
        }
        TokenKind::RParen => match touching(TokenKind::Word) {
            Some(word) if ctx.upper(word) == "MCR" => (")MCR".into(), Some(word)),
            _ => (")".into(), None),
        },
        TokenKind::SignedWord | TokenKind::Compare => (ctx.upper(first), None),
        TokenKind::Plus => ("+".into(), None),
        TokenKind::Equals => ("=".into(), None),
        TokenKind::Assert => {
            let cmp = match &ctx.text(first)[8..] {
                "==" => Cmp::Eq,
                "<>" => Cmp::Ne,
                ">" => Cmp::Gt,
                "<" => Cmp::Lt,
                ">=" => Cmp::Ge,
                _ => Cmp::Le,
            };
            extension_allowed(ctx, first)?;
            return Ok((input.skip(1), (S7Op::Assert(cmp), ctx.span(first))));
        }
        _ => {
            return Err(step5::operation(ctx, first)
                .unwrap_or_else(|| unexpected(ctx, first, "an operation")));
        }
    };
    let span = ctx.span_of(first, used.unwrap_or(first));
    let rest = input.skip(if used.is_some() { 2 } else { 1 });
    if let Some(op) = mnemonics::operation(ctx.set, &word) {
        return Ok((rest, (op, span)));
    }
    if let Some(op) = mnemonics::EXTENSION_OPERATIONS
        .iter()
        .find(|words| words.en == word)
    {
        extension_allowed(ctx, first)?;
        return Ok((rest, (op.op, span)));
    }
    if let Some(op) = mnemonics::operation(ctx.set.other(), &word) {
        ctx.foreign_word(first, true);
        return Ok((rest, (op, span)));
    }
    if let Some(diagnostic) = step5::operation(ctx, first) {
        return Err(diagnostic);
    }
    Err(S7ParseError::UnknownOperation {
        help: suggest_operation(ctx, &word, next),
        word: ctx.source[span.start as usize..span.end as usize].into(),
        at: span,
        set: ctx.set.name(),
    })
}

fn extension_allowed(ctx: Ctx<'_>, token: Token) -> Result<(), S7ParseError> {
    if ctx.extensions {
        Ok(())
    } else {
        Err(S7ParseError::ExtensionNotEnabled {
            word: ctx.text(token).into(),
            at: ctx.span(token),
        })
    }
}

/// What to write instead of an unknown operation: a label's missing `:`, or a close spelling
/// that starts with the same letter (`JUU` → `JU`).
fn suggest_operation(ctx: Ctx<'_>, upper: &str, next: Option<Token>) -> Option<String> {
    if let Some(next) = next.filter(|t| t.kind == TokenKind::Word)
        && upper.len() <= 4
        && mnemonics::operation(ctx.set, &ctx.upper(next)).is_some()
    {
        return Some(format!(
            "a label ends with `:`: write `{upper}: {}`",
            ctx.text(next)
        ));
    }
    Some(
        match crate::syntax::close_spelling(upper, mnemonics::operation_words(ctx.set)) {
            Some(candidate) => format!("did you mean `{candidate}`?"),
            None => format!(
                "`awl help mnemonics` lists the operations of the {} set (STEP 7)",
                ctx.set.name()
            ),
        },
    )
}

/// `L STW`, `T STW` are operations of their own; `OPN DI 2` opens the instance DB.
fn special_operand<'a>(ctx: Ctx<'a>, rest: Tokens<'a>, op: S7Op) -> (Tokens<'a>, S7Op) {
    let word = rest.first().and_then(|t| ctx.word(t));
    match (op, word.as_deref()) {
        (S7Op::Load, Some("STW")) => (rest.skip(1), S7Op::LoadStatusWord),
        (S7Op::Transfer, Some("STW")) => (rest.skip(1), S7Op::TransferStatusWord),
        (S7Op::OpenDb, Some(word))
            if word == "DI"
                || (word.starts_with("DI") && word[2..].chars().all(|c| c.is_ascii_digit())) =>
        {
            (rest, S7Op::OpenInstanceDb)
        }
        _ => (rest, op),
    }
}

fn expect_of(op: S7Op) -> Expect {
    use S7Op::*;
    match op {
        JumpAlways | JumpIfRlo | JumpIfNotRlo | JumpIfRloSave | JumpIfNotRloSave | JumpIfBr
        | JumpIfNotBr | JumpIfOverflow | JumpIfStoredOverflow | JumpIfZero | JumpIfNotZero
        | JumpIfPositive | JumpIfMinus | JumpIfPositiveOrZero | JumpIfMinusOrZero
        | JumpIfUnordered | Loop | JumpList => Expect::Label,
        ShiftSignedInt | ShiftSignedDint | ShiftLeftWord | ShiftRightWord | ShiftLeftDouble
        | ShiftRightDouble | RotateLeftDouble | RotateRightDouble | Increment | Decrement
        | Display | Nop | Sleep | Feature => Expect::Count,
        OpenDb | OpenInstanceDb | Call | CallUnconditional | CallConditional => Expect::Block,
        _ => Expect::Value,
    }
}

/// The operation's operand is a jump label (`JU M001`, `LOOP NEXT`).
pub fn takes_label(op: S7Op) -> bool {
    expect_of(op) == Expect::Label
}

/// The operation reads or writes an operand of the common forms (an address, a constant).
pub fn takes_address(op: S7Op) -> bool {
    expect_of(op) == Expect::Value
}

/// The operand of `op`: one, or two for `__ASSERT` and `__FEATURE`.
fn operand_of<'a>(ctx: Ctx<'a>, op: S7Op) -> impl Fn(Tokens<'a>) -> PResult<'a, S7Operand> {
    move |input: Tokens<'a>| {
        let expect = expect_of(op);
        let (rest, first) = operand(ctx, expect)(input)?;
        if !matches!(op, S7Op::Assert(_) | S7Op::Feature) {
            return Ok((rest, first));
        }
        let (rest, second) = opt(preceded(
            kind(TokenKind::Comma, "`,`"),
            operand(ctx, expect),
        ))
        .parse(rest)?;
        match second {
            Some(second) => Ok((rest, S7Operand::Pair(Box::new(first), Box::new(second)))),
            None if op == S7Op::Feature => Ok((rest, first)),
            None => Err(fail(rest, "`,` and a second operand")),
        }
    }
}

/// Operations that take no operand, and those that need one.
fn check_operand(
    ctx: Ctx<'_>,
    op: S7Op,
    operand: &S7Operand,
    op_span: Span,
) -> Result<(), S7ParseError> {
    if needs_operand(op) && *operand == S7Operand::None {
        return Err(S7ParseError::MissingOperand {
            op: mnemonics::op_word(ctx.set, op).into(),
            at: op_span,
            help: operand_example(op).map(|example| format!("for example `{example}`")),
        });
    }
    Ok(())
}

fn needs_operand(op: S7Op) -> bool {
    use S7Op::*;
    matches!(
        op,
        Logic(
            Combination::And
                | Combination::AndNot
                | Combination::Xor
                | Combination::XorNot
                | Combination::OrNot
        ) | Assign
            | Set
            | Reset
            | EdgePositive
            | EdgeNegative
            | Load
            | LoadCoded
            | Transfer
            | TimerPulse
            | TimerExtendedPulse
            | TimerOnDelay
            | TimerRetentiveOnDelay
            | TimerOffDelay
            | Enable
            | CountUp
            | CountDown
            | AddConstant
            | Display
            | Nop
            | OpenDb
            | OpenInstanceDb
            | Call
            | CallUnconditional
            | CallConditional
            | Assert(_)
            | Sleep
            | Feature
    ) || expect_of(op) == Expect::Label
}

fn operand_example(op: S7Op) -> Option<&'static str> {
    use S7Op::*;
    Some(match op {
        Logic(_) | Assign | Set | Reset => "I 0.0",
        EdgePositive | EdgeNegative => "M 10.0",
        Load | Transfer => "MW 10",
        LoadCoded => "T 1",
        TimerPulse | TimerExtendedPulse | TimerOnDelay | TimerRetentiveOnDelay | TimerOffDelay => {
            "T 1"
        }
        Enable => "T 1",
        CountUp | CountDown => "C 1",
        AddConstant => "+ 5",
        Display | Nop => "NOP 0",
        OpenDb => "OPN DB 10",
        Call => "CALL FC 1",
        CallUnconditional | CallConditional => "UC FC 1",
        _ if expect_of(op) == Expect::Label => "JU M001",
        _ => return None,
    })
}

/// `CALL FC 1`, `CALL FB 1, DB 1 (…)`, `CALL "Valve"`, `CALL #motor (…)`.
fn call<'a>(ctx: Ctx<'a>, input: Tokens<'a>) -> PResult<'a, (S7Operand, CallSpec)> {
    let (rest, (block, multi_instance)) = called_block(ctx, input)?;
    let (rest, instance) = opt(preceded(kind(TokenKind::Comma, "`,`"), |input| {
        instance_block(ctx, input)
    }))
    .parse(rest)?;
    let (rest, params) = match rest.first() {
        Some(token) if token.kind == TokenKind::LParen => parameters(ctx, rest)?,
        _ => (rest, Vec::new()),
    };
    let operand = match &multi_instance {
        Some(name) => S7Operand::Local(vec![crate::step7::ast::PathPart::Member(name.clone())]),
        None => S7Operand::Block(block.clone()),
    };
    Ok((
        rest,
        (
            operand,
            CallSpec {
                block,
                instance,
                multi_instance,
                params,
            },
        ),
    ))
}

/// The called block; for a multi-instance `#motor` its name (as a symbol) and the local.
fn called_block<'a>(ctx: Ctx<'a>, input: Tokens<'a>) -> PResult<'a, (S7BlockRef, Option<Name>)> {
    match input.first() {
        Some(token) if token.kind == TokenKind::Local => {
            let (rest, path) = local_path(ctx)(input)?;
            let Some(crate::step7::ast::PathPart::Member(name)) = path.into_iter().next() else {
                return Err(fail(input, "`#instance`"));
            };
            Ok((rest, (S7BlockRef::Symbol(name.clone()), Some(name))))
        }
        _ => {
            let (rest, block) = instance_block(ctx, input)?;
            Ok((rest, (block, None)))
        }
    }
}

/// `FB 1`, `DB 1`, `"Name"`.
fn instance_block<'a>(ctx: Ctx<'a>, input: Tokens<'a>) -> PResult<'a, S7BlockRef> {
    match input.first() {
        Some(token) if token.kind == TokenKind::Symbol => {
            Ok((input.skip(1), S7BlockRef::Symbol(symbol_name(ctx, token))))
        }
        Some(_) => match block_number_tokens(ctx, input) {
            Some((Some((kind, number)), rest)) => Ok((rest, S7BlockRef::Number { kind, number })),
            _ => Err(bad_block_number(ctx, input).unwrap_or_else(|| {
                fail(input, "a block such as `FC 1`, `FB 2, DB 2` or `\"Name\"`")
            })),
        },
        None => Err(fail(input, "a block such as `FC 1`")),
    }
}

/// A block number STEP 7 does not have: awlsim's internal blocks `SFC -1`, `SFB -1`, or one
/// past 65535 (`FC 70000`).
pub fn bad_block_number(ctx: Ctx<'_>, input: Tokens<'_>) -> Option<nom::Err<Fail>> {
    if let Some(error) = super::operand::block_number_out_of_range(ctx, input) {
        return Some(Fail::with(error));
    }
    match input.tokens {
        [word, minus, number, ..]
            if word.kind == TokenKind::Word
                && minus.kind == TokenKind::Minus
                && number.kind == TokenKind::Number =>
        {
            Some(Fail::with(S7ParseError::BlockNumber {
                number: format!("-{}", ctx.text(*number)),
                at: ctx.span_of(*minus, *number),
            }))
        }
        _ => None,
    }
}

/// `( NAME := actual, … )`.
fn parameters<'a>(ctx: Ctx<'a>, input: Tokens<'a>) -> PResult<'a, Vec<CallParam>> {
    let (rest, _) = kind(TokenKind::LParen, "`(`")(input)?;
    let (rest, params) =
        separated_list0(kind(TokenKind::Comma, "`,`"), |input| parameter(ctx, input))
            .parse(rest)?;
    // A comma after the last parameter, as awlsim's files write it.
    let (rest, _) = opt(kind(TokenKind::Comma, "`,`")).parse(rest)?;
    let (rest, _) = kind(TokenKind::RParen, "`,` or `)`")(rest)?;
    Ok((rest, params))
}

fn parameter<'a>(ctx: Ctx<'a>, input: Tokens<'a>) -> PResult<'a, CallParam> {
    let (rest, name) = kind(TokenKind::Word, "a parameter name")(input)?;
    let (rest, _) = kind(TokenKind::Assign, "`:=`")(rest)?;
    let (after, actual) = operand(ctx, Expect::Value)(rest)?;
    if actual == S7Operand::None {
        return Err(Fail::with(S7ParseError::MissingOperand {
            op: ctx.text(name).into(),
            at: ctx.consumed(input, rest),
            help: Some("give the actual parameter: `IN := M 0.0`".into()),
        }));
    }
    Ok((
        after,
        CallParam {
            name: Name {
                text: ctx.text(name).into(),
                span: ctx.span(name),
            },
            actual,
            actual_span: ctx.consumed(rest, after),
            span: ctx.consumed(input, after),
        },
    ))
}
