//! The grammar of one line (see `grammar/stl.ebnf`), as nom parsers over the line's tokens.

use nom::Parser;
use nom::combinator::opt;
use nom::sequence::{pair, terminated};

use crate::ast::{
    Address, BlockId, CallParam, Constant, Name, Operand, ParamDecl, ParamFormat, Statement,
};
use crate::lexer::{Token, TokenKind};
use crate::mnemonics::{self, Area, BlockKind, ConstFormat, OpCode, OpInfo, ParamKind};
use crate::source::Span;

use super::constant::parse_constant;
use super::error::ParseError;
use super::listing::header_information;
use super::tokens::{
    Context, LineError, LineResult, Tokens, decimal, end_of_line, fail, keyword, kind, touching,
};

/// What one line holds.
#[derive(Debug, Clone)]
pub enum Line {
    Header(BlockId),
    /// `NAME :MOTOR`
    Name(Name),
    Declaration(ParamDecl),
    DataWord {
        index: Option<u16>,
        constant: Constant,
        span: Span,
    },
    Param(CallParam),
    Statement(Statement),
}

fn remaining_span(context: Context<'_>, tokens: &[Token]) -> Option<Span> {
    Some(context.span_of(*tokens.first()?, *tokens.last()?))
}

/// `PB 3` or `PB3`, in a listing with its information (`PB 3   LAE=12`).
pub fn header<'a>(context: Context<'a>) -> impl Fn(Tokens<'a>) -> LineResult<'a, BlockId> {
    move |input: Tokens<'a>| {
        let (rest, word) = kind(TokenKind::Word, "a block header such as `PB 3`")(input)?;
        let text = context.text(word);
        if let Some(kind) = BlockKind::from_word(text) {
            let (rest, number) = kind_number(context, rest)?;
            let (rest, _) = header_information(rest)?;
            return Ok((
                rest,
                BlockId {
                    kind,
                    number: u16::from(number),
                },
            ));
        }
        let split = text
            .find(|c: char| c.is_ascii_digit())
            .unwrap_or(text.len());
        let (kind_text, digits) = text.split_at(split);
        match (BlockKind::from_word(kind_text), digits.parse::<u32>()) {
            (Some(kind), Ok(number)) if !digits.is_empty() => {
                let (rest, _) = header_information(rest)?;
                let number = block_number(context, word, number)?;
                Ok((
                    rest,
                    BlockId {
                        kind,
                        number: u16::from(number),
                    },
                ))
            }
            _ => Err(nom::Err::Error(LineError {
                at: Some(word),
                expected: "",
                diagnostic: None,
            })),
        }
    }
}

/// The block type of a header line whose number is bad (`PB 300`, `PB300`).
pub fn header_kind(source: &str, first: Token) -> BlockKind {
    let text = first.text(source);
    let letters = text.trim_end_matches(|c: char| c.is_ascii_digit());
    BlockKind::from_word(letters).unwrap_or(BlockKind::Pb)
}

fn kind_number<'a>(context: Context<'a>, input: Tokens<'a>) -> LineResult<'a, u8> {
    match input.first() {
        Some(token) if token.kind == TokenKind::Number => {
            let value = context.text(token).parse::<u32>().unwrap_or(u32::MAX);
            Ok((
                Tokens::new(&input.tokens[1..]),
                block_number(context, token, value)?,
            ))
        }
        _ => Err(fail(input, "a block number 0…255")),
    }
}

fn block_number(context: Context<'_>, token: Token, value: u32) -> Result<u8, nom::Err<LineError>> {
    u8::try_from(value).map_err(|_| {
        LineError::with(ParseError::BlockNumber {
            number: context.text(token).to_string(),
            at: context.span(token),
        })
    })
}

/// `NAME :MOTOR`
pub fn name_line<'a>(context: Context<'a>) -> impl Fn(Tokens<'a>) -> LineResult<'a, Name> {
    move |input: Tokens<'a>| {
        let (rest, _) = keyword(context, &[mnemonics::NAME_WORD], "NAME")(input)?;
        let (rest, _) = kind(TokenKind::Colon, "`:`")(rest)?;
        // The PG takes any characters in a name (`RAD:GP`, `RLG:AE`): the rest of the line.
        let (Some(first), Some(last)) = (rest.first(), rest.tokens.last().copied()) else {
            return Err(fail(rest, "the block's name"));
        };
        let span = context.span_of(first, last);
        Ok((
            Tokens::new(&[]),
            Name {
                text: context.source[span.start as usize..span.end as usize].to_string(),
                span,
            },
        ))
    }
}

/// The PG prints each choice of a declaration with its legend: `E/A/D/B/T/Z: E`,
/// `BI/BY/W/D: BI`. The legend, up to and including its `:`, is skipped.
fn without_legend(input: Tokens<'_>) -> Tokens<'_> {
    let tokens = input.tokens;
    let legend = tokens
        .iter()
        .take_while(|token| matches!(token.kind, TokenKind::Word | TokenKind::Invalid))
        .count();
    match tokens.get(legend) {
        Some(colon) if legend > 0 && colon.kind == TokenKind::Colon => {
            Tokens::new(&tokens[legend + 1..])
        }
        _ => input,
    }
}

/// `DES :EIN I BI`, or as the PG prints it, `DES :EIN  I/Q/D/B/T/C: I  BI/BY/W/D: BI`
pub fn declaration<'a>(context: Context<'a>) -> impl Fn(Tokens<'a>) -> LineResult<'a, ParamDecl> {
    move |input: Tokens<'a>| {
        let words = &[mnemonics::DECLARATION_EN, mnemonics::DECLARATION_DE];
        let (rest, start) = keyword(context, words, "DES")(input)?;
        let line_span = remaining_span(context, input.tokens).unwrap_or_default();
        let bad = |reason: &str, at: Span| {
            LineError::with(ParseError::BadDeclaration {
                at,
                reason: reason.to_string(),
            })
        };
        let (rest, _) =
            kind(TokenKind::Colon, "`:`")(rest).map_err(|_| bad("`:` expected", line_span))?;
        let (rest, name) = kind(TokenKind::Word, "name")(rest)
            .map_err(|_| bad("parameter name expected", line_span))?;
        let rest = without_legend(rest);
        let (rest, kind_token) = kind(TokenKind::Word, "kind")(rest)
            .map_err(|_| bad("kind expected (I Q D B T C)", line_span))?;
        let param_kind =
            mnemonics::param_kind(context.set, context.text(kind_token)).ok_or_else(|| {
                bad(
                    "unknown kind; I Q D B T C expected",
                    context.span(kind_token),
                )
            })?;
        let (rest, format_token) =
            opt(kind(TokenKind::Word, "format")).parse(without_legend(rest))?;
        if let Some(extra) = rest.first() {
            return Err(bad("end of line expected", context.span(extra)));
        }
        let format = match format_token {
            Some(token) => Some(
                param_format(context, token)
                    .ok_or_else(|| bad("unknown format", context.span(token)))?,
            ),
            None => None,
        };
        let last = format_token.unwrap_or(kind_token);
        let ok = matches!(
            (param_kind, format),
            (
                ParamKind::Input | ParamKind::Output,
                Some(ParamFormat::Bit | ParamFormat::Byte | ParamFormat::Word),
            ) | (ParamKind::Data, Some(ParamFormat::Constant(_)))
                | (
                    ParamKind::Block | ParamKind::Timer | ParamKind::Counter,
                    None
                )
        );
        if !ok {
            let reason = match param_kind {
                ParamKind::Input | ParamKind::Output => "kinds I and Q take the format BI, BY or W",
                ParamKind::Data => {
                    "kind D takes a constant format (KF, KH, KM, KY, KT, KC, KS, KG)"
                }
                _ => "kinds B, T and C take no format",
            };
            return Err(bad(reason, context.span_of(kind_token, last)));
        }
        Ok((
            rest,
            ParamDecl {
                name: Name {
                    text: context.text(name).to_string(),
                    span: context.span(name),
                },
                kind: param_kind,
                format,
                span: context.span_of(start, last),
            },
        ))
    }
}

fn param_format(context: Context<'_>, token: Token) -> Option<ParamFormat> {
    let text = context.text(token);
    match text.to_ascii_uppercase().as_str() {
        "BI" => Some(ParamFormat::Bit),
        "BY" => Some(ParamFormat::Byte),
        "W" => Some(ParamFormat::Word),
        _ => mnemonics::constant_format(context.set, text).map(ParamFormat::Constant),
    }
}

/// `0: KF +100`, `1: KH = 00FF`, or a constant alone (the next word).
pub fn data_word<'a>(
    context: Context<'a>,
) -> impl Fn(Tokens<'a>) -> LineResult<'a, (Option<u16>, Constant, Span)> {
    move |input: Tokens<'a>| {
        let span = remaining_span(context, input.tokens).unwrap_or_default();
        let (rest, index) = opt(terminated(
            decimal(context, "word number"),
            kind(TokenKind::Colon, "`:`"),
        ))
        .parse(input)?;
        let (rest, format_token) = kind(TokenKind::Word, "a constant format such as KF")(rest)?;
        let Some(format) = mnemonics::constant_format(context.set, context.text(format_token))
        else {
            return Err(nom::Err::Error(LineError {
                at: Some(format_token),
                expected: "a constant format such as KF",
                diagnostic: None,
            }));
        };
        let (rest, _) = opt(kind(TokenKind::Equals, "`=`")).parse(rest)?;
        let constant =
            parse_constant(context, format, format_token, rest.tokens).map_err(LineError::with)?;
        Ok((
            Tokens::new(&[]),
            (index.map(|(value, _)| value), constant, span),
        ))
    }
}

/// `EIN :I 0.0` — an actual parameter after an FB call.
pub fn param_line<'a>(context: Context<'a>) -> impl Fn(Tokens<'a>) -> LineResult<'a, CallParam> {
    move |input: Tokens<'a>| {
        let (rest, name) = kind(TokenKind::Word, "parameter name")(input)?;
        // `Z3=0`: the integral FBs' names for "result is zero" (S5-115U manual, FB 242/243).
        let (rest, zero_test) = opt(pair(
            kind(TokenKind::Equals, "`=`"),
            kind(TokenKind::Number, "number"),
        ))
        .parse(rest)?;
        let (rest, _) = kind(TokenKind::Colon, "`:`")(rest)?;
        let (rest, (actual, actual_span)) = operand(context, None)(rest)?;
        if actual == Operand::None || matches!(actual, Operand::Number(_)) {
            return Err(fail(rest, ""));
        }
        let (rest, _) = end_of_line(rest)?;
        let span = remaining_span(context, input.tokens).unwrap_or_default();
        let name = match zero_test {
            Some((_, number)) => Name {
                text: format!("{}={}", context.text(name), context.text(number)),
                span: context.span_of(name, number),
            },
            None => Name {
                text: context.text(name).to_string(),
                span: context.span(name),
            },
        };
        Ok((
            rest,
            CallParam {
                name,
                actual,
                actual_span,
                span,
            },
        ))
    }
}

/// `[:] [LABEL :] [:] OPERATION [OPERAND]`
pub fn statement<'a>(context: Context<'a>) -> impl Fn(Tokens<'a>) -> LineResult<'a, Statement> {
    move |input: Tokens<'a>| {
        let input = without_colon_before_label(input);
        let span = remaining_span(context, input.tokens).unwrap_or_default();
        let (rest, label) = opt(terminated(
            kind(TokenKind::Word, "label"),
            kind(TokenKind::Colon, "`:`"),
        ))
        .parse(input)?;
        let (rest, op) = match divide(context)(rest) {
            Ok(parsed) => parsed,
            Err(_) => operation(context)(without_colon(rest))?,
        };
        let (rest, (operand, operand_span)) = match op.inline_operand.clone() {
            Some(inline) => Ok((rest, inline)),
            None => operand_for(context, op.info, op.last)(rest),
        }?;
        end_of_line(rest).map_err(|_| {
            let extra = remaining_span(context, rest.tokens).unwrap_or_default();
            LineError::with(ParseError::UnexpectedToken {
                found: describe(context, rest.first()),
                at: extra,
                expected: "end of line".to_string(),
            })
        })?;
        Ok((
            Tokens::new(&[]),
            Statement {
                label: label.map(|token| Name {
                    text: context.text(token).to_string(),
                    span: context.span(token),
                }),
                op: op.info.op,
                op_span: op.span,
                operand,
                operand_span,
                call_params: Vec::new(),
                segment: 0,
                span,
            },
        ))
    }
}

pub fn describe(context: Context<'_>, token: Option<Token>) -> String {
    match token {
        None => "end of line".to_string(),
        Some(token) if token.kind == TokenKind::Newline => "end of line".to_string(),
        Some(token) => format!("`{}`", context.text(token)),
    }
}

struct ParsedOp {
    info: OpInfo,
    span: Span,
    last: Token,
    inline_operand: Option<(Operand, Span)>,
}

/// `:F` or `:G` written right after the leading colon of a PG listing, or alone.
fn divide<'a>(context: Context<'a>) -> impl Fn(Tokens<'a>) -> LineResult<'a, ParsedOp> {
    move |input: Tokens<'a>| {
        let (rest, _) = opt(pair(
            kind(TokenKind::Colon, ":"),
            nom::combinator::peek(kind(TokenKind::Colon, ":")),
        ))
        .parse(input)?;
        let (rest, colon) = kind(TokenKind::Colon, "`:F`")(rest)?;
        let (rest, f) = touching(colon, TokenKind::Word, "`:F`")(rest)?;
        let op = match context.text(f) {
            "F" | "f" => Some(OpCode::DivFixed),
            "G" | "g" => Some(OpCode::DivFloat),
            _ => None,
        };
        let Some(op) = op.filter(|_| rest.is_empty()) else {
            return Err(nom::Err::Error(LineError {
                at: Some(colon),
                expected: "",
                diagnostic: None,
            }));
        };
        let info = *mnemonics::op_info(op);
        Ok((
            rest,
            ParsedOp {
                info,
                span: context.span_of(colon, f),
                last: f,
                inline_operand: None,
            },
        ))
    }
}

/// The line without the `:` a PG printout puts before a label (`0037: M004: L DW12`,
/// `0037 :M004 :L DW12`, the address already taken off).
fn without_colon_before_label(input: Tokens<'_>) -> Tokens<'_> {
    match input.tokens {
        [colon, label, label_colon, _, ..]
            if colon.kind == TokenKind::Colon
                && label.kind == TokenKind::Word
                && label_colon.kind == TokenKind::Colon =>
        {
            Tokens::new(&input.tokens[1..])
        }
        _ => input,
    }
}

/// The line without the leading `:` of a PG listing before the operation.
fn without_colon(input: Tokens<'_>) -> Tokens<'_> {
    match input.first() {
        Some(colon) if colon.kind == TokenKind::Colon => Tokens::new(&input.tokens[1..]),
        _ => input,
    }
}

fn operation<'a>(context: Context<'a>) -> impl Fn(Tokens<'a>) -> LineResult<'a, ParsedOp> {
    move |input: Tokens<'a>| {
        let Some(first) = input.first() else {
            return Err(fail(input, "an operation"));
        };
        let mut rest = Tokens::new(&input.tokens[1..]);
        let mut last = first;
        let mut inline_operand = None;
        // Borrowed in the common case; the lookup ignores case.
        let word: std::borrow::Cow<'a, str> = match first.kind {
            TokenKind::Word => {
                let text = context.text(first);
                // `A(` as the PG prints it, `A (` as people type it.
                if let Ok((after, paren)) = kind(TokenKind::LParen, "(")(rest) {
                    rest = after;
                    last = paren;
                    format!("{text}(").into()
                } else if text.eq_ignore_ascii_case("X") {
                    let (after, f) = keyword(context, &["F", "G"], "`X F` or `X G`")(rest)?;
                    rest = after;
                    last = f;
                    format!("X {}", context.text(f).to_ascii_uppercase()).into()
                } else if text.eq_ignore_ascii_case("XF") || text.eq_ignore_ascii_case("XG") {
                    format!("X {}", &text[1..].to_ascii_uppercase()).into()
                } else {
                    if let Ok((after, equals)) = touching(first, TokenKind::Equals, "=")(rest) {
                        let (after, target) = kind(TokenKind::Word, "a label after `=`")(after)?;
                        inline_operand = Some((
                            Operand::Symbol(context.text(target).to_string()),
                            context.span_of(equals, target),
                        ));
                        rest = after;
                    }
                    text.into()
                }
            }
            TokenKind::RParen => ")".into(),
            TokenKind::Equals => "=".into(),
            TokenKind::AddSub | TokenKind::Compare => context.text(first).into(),
            _ => {
                return Err(nom::Err::Error(LineError {
                    at: Some(first),
                    expected: "an operation",
                    diagnostic: None,
                }));
            }
        };
        let span = context.span_of(first, last);
        match mnemonics::operation(context.set, &word) {
            Some(info) => Ok((
                rest,
                ParsedOp {
                    info,
                    span,
                    last,
                    inline_operand,
                },
            )),
            None => Err(nom::Err::Error(LineError {
                at: Some(first),
                expected: "an operation",
                diagnostic: Some(Box::new(ParseError::UnknownOperation {
                    help: suggest_operation(context, &word, rest.first()),
                    word: word.into_owned(),
                    at: span,
                    set: context.set.name(),
                })),
            })),
        }
    }
}

/// What to write instead of an unknown operation: the operation and its operand without their
/// blank (`T1`), a label without its `:` (`M001 A I 1.0`), or a close spelling (`JUU`).
fn suggest_operation(context: Context<'_>, word: &str, next: Option<Token>) -> Option<String> {
    let set = context.set;
    let upper = word.to_ascii_uppercase();
    if upper.ends_with('(') {
        return Some(format!(
            "STEP 5 opens brackets with `{}` and `{}` only",
            mnemonics::op_word(set, OpCode::AndBracket),
            mnemonics::op_word(set, OpCode::OrBracket)
        ));
    }
    if let Some(split) = upper
        .find(|c: char| c.is_ascii_digit())
        .filter(|at| *at > 0)
    {
        let (op, operand) = upper.split_at(split);
        if mnemonics::operation(set, op).is_some() {
            return Some(format!(
                "a blank separates the operation from its operand: write `{op} {operand}`"
            ));
        }
    }
    let label_shaped = word.len() <= 4 && word.ends_with(|c: char| c.is_ascii_digit());
    if let Some(next) = next.filter(|next| next.kind == TokenKind::Word && label_shaped)
        && mnemonics::operation(set, context.text(next)).is_some()
    {
        return Some(format!(
            "a label ends with `:`: write `{word} :{}`",
            context.text(next)
        ));
    }
    Some(
        match crate::syntax::close_spelling(&upper, mnemonics::operation_words(set)) {
            Some(candidate) => format!("did you mean `{candidate}`?"),
            None => format!(
                "`awl help mnemonics` lists the operations of the {} set",
                set.name()
            ),
        },
    )
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum Shape {
    Nothing,
    Number,
    Optional,
    Required,
}

fn shape(op: OpCode) -> Shape {
    use OpCode::*;
    match op {
        AndBracket
        | OrBracket
        | CloseBracket
        | AddFixed
        | SubFixed
        | MulFixed
        | DivFixed
        | CmpEq
        | CmpNe
        | CmpGt
        | CmpGe
        | CmpLt
        | CmpLe
        | AddFloat
        | SubFloat
        | MulFloat
        | DivFloat
        | CmpEqFloat
        | CmpNeFloat
        | CmpGtFloat
        | CmpGeFloat
        | CmpLtFloat
        | CmpLeFloat
        | FixedToFloat
        | FloatToFixed
        | BcdToFixed
        | FixedToBcd
        | BcdToFixedDouble
        | FixedToBcdDouble
        | BlockEnd
        | BlockEndConditional
        | BlockEndUnconditional
        | Stop
        | AndWord
        | OrWord
        | XorWord
        | OnesComplement
        | TwosComplement
        | Swap
        | Enter
        | DisableInterrupts
        | EnableInterrupts
        | MoveBrToAccu
        | MoveAccuToBr
        | MoveSaToAccu
        | MoveAccuToSa => Shape::Nothing,
        Nop | Display | ShiftLeft | ShiftRight | Increment | Decrement | TransferBytes
        | LoadIndirect | TransferIndirect | AddToBr | LoadRelativeBr | TransferRelativeBr => {
            Shape::Number
        }
        Or => Shape::Optional,
        _ => Shape::Required,
    }
}

fn operand_for<'a>(
    context: Context<'a>,
    info: OpInfo,
    op_last: Token,
) -> impl Fn(Tokens<'a>) -> LineResult<'a, (Operand, Span)> {
    move |input: Tokens<'a>| {
        let empty_span = Span {
            file: context.file,
            start: op_last.end,
            end: op_last.end,
        };
        let missing = || {
            let example = match context.set {
                mnemonics::MnemonicSet::English => (info.en, info.example_en),
                mnemonics::MnemonicSet::German => (info.de, info.example_de),
            };
            LineError::with(ParseError::MissingOperand {
                op: example.0.to_string(),
                at: context.span(op_last),
                help: (!example.1.is_empty())
                    .then(|| format!("for example `{} {}`", example.0, example.1)),
            })
        };
        match shape(info.op) {
            Shape::Nothing => Ok((input, (Operand::None, empty_span))),
            Shape::Number => match input.first() {
                None if matches!(info.op, OpCode::Increment | OpCode::Decrement) => Err(missing()),
                None => Err(missing()),
                Some(token) if token.kind == TokenKind::Number => {
                    let (rest, (value, token)) =
                        decimal(context, "a number")(input).map_err(|_| {
                            LineError::with(ParseError::UnexpectedToken {
                                found: describe(context, Some(token)),
                                at: context.span(token),
                                expected: "a decimal number".to_string(),
                            })
                        })?;
                    Ok((rest, (Operand::Number(value), context.span(token))))
                }
                Some(_) => operand(context, Some(info.op))(input),
            },
            Shape::Optional if input.is_empty() => Ok((input, (Operand::None, empty_span))),
            Shape::Required if input.is_empty() => Err(missing()),
            Shape::Required if info.op == OpCode::Load => match bare_constant(context, input) {
                Some(error) => Err(LineError::with(error)),
                None => operand(context, Some(info.op))(input),
            },
            _ => operand(context, Some(info.op))(input),
        }
    }
}

/// `L 1`, `L -5`, `L 0FFH`: a number without its constant format, with the constant STEP 5
/// writes for it (`L KF +1`).
fn bare_constant(context: Context<'_>, input: Tokens<'_>) -> Option<ParseError> {
    let (negative, number) = match input.tokens {
        [number] if number.kind == TokenKind::Number => (false, *number),
        [sign, number] if matches!(sign.kind, TokenKind::Plus | TokenKind::Minus) => {
            (sign.kind == TokenKind::Minus, *number)
        }
        _ => return None,
    };
    if number.kind != TokenKind::Number {
        return None;
    }
    let constant = super::constant::format_for_bare(negative, context.text(number))?;
    let op = match context.set {
        mnemonics::MnemonicSet::English => mnemonics::op_info(OpCode::Load).en,
        mnemonics::MnemonicSet::German => mnemonics::op_info(OpCode::Load).de,
    };
    Some(ParseError::BareConstant {
        op: op.to_string(),
        help: "STEP 5 writes a constant with its format: KF fixed point -32768 to +32767, KH \
               hexadecimal, KB a byte, KT a time, KZ a count"
            .to_string(),
        constant,
        at: context.span_of(input.tokens[0], number),
    })
}

/// An operand: `=NAME`, a number, a block (`PB 3`), an address (`I 0.0`, `FW 10`, `T 5`) or a
/// constant (`KF +5`). Block words come first after block operations, since German `PB` is also
/// the peripheral byte.
pub fn operand<'a>(
    context: Context<'a>,
    op: Option<OpCode>,
) -> impl Fn(Tokens<'a>) -> LineResult<'a, (Operand, Span)> {
    move |input: Tokens<'a>| {
        let Some(first) = input.first() else {
            return Err(fail(input, "an operand"));
        };
        let rest = Tokens::new(&input.tokens[1..]);
        match first.kind {
            TokenKind::FormalRef => {
                let name = context.text(first)[1..].to_string();
                Ok((rest, (Operand::Symbol(name), context.span(first))))
            }
            // `JC = M001`, `A = EIN`: a blank after the `=`.
            TokenKind::Equals => {
                let (rest, name) = kind(TokenKind::Word, "a name after `=`")(rest)?;
                let text = context.text(name).to_string();
                Ok((rest, (Operand::Symbol(text), context.span_of(first, name))))
            }
            TokenKind::SymbolRef => {
                let name = context.text(first)[1..].to_string();
                Ok((rest, (Operand::Assigned(name), context.span(first))))
            }
            TokenKind::Number => {
                let (rest, (value, token)) = decimal(context, "a number")(input)?;
                Ok((rest, (Operand::Number(value), context.span(token))))
            }
            TokenKind::Word => word_operand(context, op, first, rest),
            _ => Err(nom::Err::Error(LineError {
                at: Some(first),
                expected: "an operand",
                diagnostic: None,
            })),
        }
        .map_err(|error| match error {
            nom::Err::Error(LineError {
                diagnostic: None,
                at,
                ..
            }) if at == Some(first) => nom::Err::Error(LineError {
                at: Some(first),
                expected: "an operand",
                diagnostic: Some(Box::new(unknown_operand(context, first))),
            }),
            other => other,
        })
    }
}

fn unknown_operand(context: Context<'_>, token: Token) -> ParseError {
    let word = context.text(token).to_string();
    let known = mnemonics::AREAS
        .iter()
        .map(|info| match context.set {
            mnemonics::MnemonicSet::English => info.en,
            mnemonics::MnemonicSet::German => info.de,
        })
        .chain(BlockKind::ALL.iter().map(|kind| kind.name()));
    let help = known
        .map(|candidate| {
            (
                strsim::damerau_levenshtein(&word.to_ascii_uppercase(), candidate),
                candidate,
            )
        })
        .filter(|(distance, _)| *distance <= 1 && word.len() > 1)
        .min_by_key(|(distance, _)| *distance)
        .map(|(_, candidate)| format!("did you mean `{candidate}`?"));
    ParseError::UnknownOperand {
        word,
        at: context.span(token),
        set: context.set.name(),
        help,
    }
}

fn word_operand<'a>(
    context: Context<'a>,
    op: Option<OpCode>,
    word: Token,
    rest: Tokens<'a>,
) -> LineResult<'a, (Operand, Span)> {
    let text = context.text(word);
    let block_first = matches!(
        op,
        Some(
            OpCode::JumpUnconditional
                | OpCode::JumpConditional
                | OpCode::OpenDb
                | OpCode::GenerateDb
        )
    );
    let block = BlockKind::from_word(text);
    let area = mnemonics::area(context.set, text);
    match (block, area) {
        (Some(kind), _) if block_first || area.is_none() => {
            let number_token = rest.first().unwrap_or(word);
            let (rest, number) = kind_number(context, rest).map_err(|error| match error {
                nom::Err::Error(_) => LineError::with(ParseError::BadAddress {
                    area: text.to_string(),
                    at: context.span(word),
                    expected: "a block number 0…255 must follow".to_string(),
                }),
                other => other,
            })?;
            let span = context.span_of(word, number_token);
            Ok((
                rest,
                (
                    Operand::Block(BlockId {
                        kind,
                        number: u16::from(number),
                    }),
                    span,
                ),
            ))
        }
        (_, Some(area)) => address(context, area, word, rest),
        _ => match mnemonics::constant_format(context.set, text) {
            Some(format) => constant_operand(context, format, word, rest),
            None => glued_operand(context, op, word, rest),
        },
    }
}

/// An operand written without its blank: `DW10`, `DB105`, `T1`, `KT050.0`, `F67.1`. The word
/// is split where its digits start and read as the two tokens it stands for. A bit address
/// needs its `.bit` (`F1` could be meant as `F 1.0` or `FY 1`).
fn glued_operand<'a>(
    context: Context<'a>,
    op: Option<OpCode>,
    word: Token,
    rest: Tokens<'a>,
) -> LineResult<'a, (Operand, Span)> {
    let not_an_operand = || {
        nom::Err::Error(LineError {
            at: Some(word),
            expected: "an operand",
            diagnostic: None,
        })
    };
    let text = context.text(word);
    let split = text
        .find(|c: char| c.is_ascii_digit())
        .filter(|at| *at > 0)
        .ok_or_else(not_an_operand)?;
    let (letters, digits) = text.split_at(split);
    let is_constant = mnemonics::constant_format(context.set, letters).is_some();
    if !is_constant && !digits.bytes().all(|b| b.is_ascii_digit()) {
        return Err(not_an_operand());
    }
    if mnemonics::area(context.set, letters).is_some_and(|area| area.is_bit())
        && BlockKind::from_word(letters).is_none()
        && rest.first().is_none_or(|dot| dot.kind != TokenKind::Dot)
    {
        return Err(nom::Err::Failure(LineError {
            at: Some(word),
            expected: "an operand",
            diagnostic: Some(Box::new(ParseError::UnknownOperand {
                word: text.to_string(),
                at: context.span(word),
                set: context.set.name(),
                help: Some(format!(
                    "`{letters}` is a bit operand: write `{letters} {digits}.0` (byte {digits}, bit 0)"
                )),
            })),
        }));
    }
    let middle = word.start + split as u32;
    let tokens: Vec<Token> = [
        Token {
            kind: TokenKind::Word,
            start: word.start,
            end: middle,
        },
        Token {
            kind: TokenKind::Number,
            start: middle,
            end: word.end,
        },
    ]
    .into_iter()
    .chain(rest.tokens.iter().copied())
    .collect();
    let (after, operand) = word_operand(context, op, tokens[0], Tokens::new(&tokens[1..]))
        .map_err(|error| match error {
            nom::Err::Error(_) => not_an_operand(),
            other => other,
        })?;
    let left = after.tokens.len();
    if left > rest.tokens.len() {
        return Err(not_an_operand());
    }
    Ok((
        Tokens::new(&rest.tokens[rest.tokens.len() - left..]),
        operand,
    ))
}

fn constant_operand<'a>(
    context: Context<'a>,
    format: ConstFormat,
    word: Token,
    rest: Tokens<'a>,
) -> LineResult<'a, (Operand, Span)> {
    let (rest, _) = opt(kind(TokenKind::Equals, "=")).parse(rest)?;
    let constant = parse_constant(context, format, word, rest.tokens).map_err(LineError::with)?;
    let last = rest.tokens.last().copied().unwrap_or(word);
    Ok((
        Tokens::new(&[]),
        (Operand::Constant(constant), context.span_of(word, last)),
    ))
}

fn address<'a>(
    context: Context<'a>,
    area: Area,
    word: Token,
    rest: Tokens<'a>,
) -> LineResult<'a, (Operand, Span)> {
    let area_text = context.text(word).to_uppercase();
    let bad = |expected: &str, at: Span| {
        LineError::with(ParseError::BadAddress {
            area: area_text.clone(),
            at,
            expected: expected.to_string(),
        })
    };
    let word_span = context.span(word);
    if area.is_bit() {
        let expected = "a bit address byte.bit, e.g. 4.1";
        let (after, (index, index_token)) = decimal(context, expected)(rest)
            .map_err(|_| bad(expected, span_or(context, rest, word_span)))?;
        let (after, dot) = kind(TokenKind::Dot, expected)(after)
            .map_err(|_| bad(expected, context.span_of(word, index_token)))?;
        let (after, (bit, bit_token)) = decimal(context, expected)(after)
            .map_err(|_| bad(expected, context.span_of(word, dot)))?;
        let bit = u8::try_from(bit).unwrap_or(u8::MAX);
        Ok((
            after,
            (
                Operand::Address(Address { area, index, bit }),
                context.span_of(word, bit_token),
            ),
        ))
    } else {
        let expected = "a number, e.g. 10";
        let (after, (index, token)) = decimal(context, expected)(rest)
            .map_err(|_| bad(expected, span_or(context, rest, word_span)))?;
        if let Some(dot) = after.first().filter(|token| token.kind == TokenKind::Dot) {
            return Err(bad(
                "no bit number here: this operand is a byte, word or number",
                context.span(dot),
            ));
        }
        Ok((
            after,
            (
                Operand::Address(Address {
                    area,
                    index,
                    bit: 0,
                }),
                context.span_of(word, token),
            ),
        ))
    }
}

fn span_or(context: Context<'_>, rest: Tokens<'_>, fallback: Span) -> Span {
    rest.first()
        .map(|token| context.span(token))
        .unwrap_or(fallback)
}
