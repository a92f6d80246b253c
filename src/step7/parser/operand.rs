//! Operands: absolute addresses (`I 0.1`, `MW10`, `DB5.DBW 4`), indirect addresses
//! (`MW [MD 10]`, `DBX [AR1, P#2.0]`, `W [AR1, P#0.0]`), locals and symbols with member paths,
//! blocks, constants, status conditions and awlsim's test operands.

use nom::Parser;
use nom::branch::alt;
use nom::multi::separated_list1;
use nom::sequence::{delimited, preceded};

use crate::ast::Name;
use crate::step7::ast::{
    AccessWidth, Condition, DbRegister, Extension, IndirectPointer, PathPart, S7Address, S7Area,
    S7BlockKind, S7BlockRef, S7Constant, S7Operand,
};
use crate::step7::error::S7ParseError;
use crate::step7::lexer::{Token, TokenKind};
use crate::step7::literal::{self, LiteralError};
use crate::step7::mnemonics;

use super::step5;
use super::tokens::{Ctx, Fail, PResult, Tokens, end, fail, integer, kind, letters_and_digits};

/// What an operation takes as its operand, beyond the common forms.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Expect {
    /// Addresses, constants, locals, symbols, blocks.
    Value,
    /// A jump label.
    Label,
    /// A plain count (`SLW 3`, `INC 1`, `BLD 1`, `NOP 0`).
    Count,
    /// A block (`CALL`, `UC`, `CC`, `OPN`): `OPN DB [MW 2]` gives the pointer word itself.
    Block,
}

/// One operand, up to the end of `input` or a `,` / `)` that ends it.
pub fn operand<'a>(ctx: Ctx<'a>, expect: Expect) -> impl Fn(Tokens<'a>) -> PResult<'a, S7Operand> {
    move |input: Tokens<'a>| {
        let Some(first) = input.first() else {
            return Ok((input, S7Operand::None));
        };
        if first.kind == TokenKind::Invalid {
            return Err(Fail::with(S7ParseError::UnexpectedCharacter {
                found: ctx.text(first).into(),
                at: ctx.span(first),
            }));
        }
        match expect {
            Expect::Label if first.kind == TokenKind::Word => {
                // `JU PB 3`: a STEP 5 block jump.
                if input.second().is_some()
                    && let Some(diagnostic) = step5::operand(ctx, input)
                {
                    return Err(Fail::with(diagnostic));
                }
                return Ok((input.skip(1), S7Operand::Label(name(ctx, first))));
            }
            Expect::Count if first.kind == TokenKind::Number => {
                let (rest, (value, _)) = integer(ctx)(input)?;
                return Ok((rest, S7Operand::Number(value)));
            }
            Expect::Block if first.kind == TokenKind::Word => {
                if let Some(result) = block_operand(ctx, input) {
                    return result;
                }
            }
            _ => {}
        }
        value(ctx, input)
    }
}

/// The common forms.
fn value<'a>(ctx: Ctx<'a>, input: Tokens<'a>) -> PResult<'a, S7Operand> {
    let first = input.first().expect("checked by the caller");
    if let Some(result) = pointer_to(ctx, input) {
        return result;
    }
    match first.kind {
        TokenKind::Typed | TokenKind::Number | TokenKind::Minus | TokenKind::Plus => {
            let (rest, constant) = constant(ctx)(input)?;
            Ok((rest, S7Operand::Constant(constant)))
        }
        TokenKind::Quoted => {
            let (rest, constant) = constant(ctx)(input)?;
            Ok((rest, S7Operand::Constant(constant)))
        }
        TokenKind::Local => {
            let (rest, path) = local_path(ctx)(input)?;
            Ok((rest, S7Operand::Local(path)))
        }
        TokenKind::Symbol => {
            let (rest, (name, members)) = symbol_path(ctx)(input)?;
            Ok((rest, S7Operand::Symbol { name, members }))
        }
        TokenKind::Compare => match condition(ctx, first) {
            Some(condition) => Ok((input.skip(1), S7Operand::Condition(condition))),
            None => Err(unknown_operand(ctx, first)),
        },
        TokenKind::LBracket => {
            let (rest, (ar, offset)) = register_pointer(ctx)(input)?;
            Ok((
                rest,
                S7Operand::AreaCrossing {
                    width: AccessWidth::Bit,
                    ar,
                    offset,
                },
            ))
        }
        TokenKind::Word => word_operand(ctx, input),
        _ => Err(fail(input, "an operand")),
    }
}

fn name(ctx: Ctx<'_>, token: Token) -> Name {
    Name {
        text: ctx.text(token).to_string(),
        span: ctx.span(token),
    }
}

/// An operand that starts with a word.
fn word_operand<'a>(ctx: Ctx<'a>, input: Tokens<'a>) -> PResult<'a, S7Operand> {
    let first = input.first().expect("a word");
    let upper = ctx.upper(first);
    let rest = input.skip(1);
    match upper.as_str() {
        "TRUE" | "FALSE" => {
            return Ok((rest, S7Operand::Constant(literal::boolean(upper == "TRUE"))));
        }
        "DBNO" => return Ok((rest, S7Operand::DbRegister(DbRegister::DbNumber))),
        "DBLG" => return Ok((rest, S7Operand::DbRegister(DbRegister::DbLength))),
        "DINO" => return Ok((rest, S7Operand::DbRegister(DbRegister::DiNumber))),
        "DILG" => return Ok((rest, S7Operand::DbRegister(DbRegister::DiLength))),
        "STW" if ctx.extensions => {
            return Ok((rest, S7Operand::Extension(Extension::StatusWord)));
        }
        "AR1" => return Ok((rest, S7Operand::AddressRegister(1))),
        "AR2" => return Ok((rest, S7Operand::AddressRegister(2))),
        "B" | "W" | "D" if rest.first().is_some_and(|t| t.kind == TokenKind::LBracket) => {
            let width = match upper.as_str() {
                "B" => AccessWidth::Byte,
                "W" => AccessWidth::Word,
                _ => AccessWidth::Double,
            };
            let (rest, (ar, offset)) = register_pointer(ctx)(rest)?;
            return Ok((rest, S7Operand::AreaCrossing { width, ar, offset }));
        }
        _ => {}
    }
    if upper.starts_with("__") {
        return extension(ctx, input);
    }
    if let Some(condition) = condition(ctx, first) {
        return Ok((rest, S7Operand::Condition(condition)));
    }
    if let Some(result) = block_operand(ctx, input) {
        return result;
    }
    if let Some(result) = address_operand(ctx, input) {
        return result;
    }
    if let Some(diagnostic) = step5::operand(ctx, input) {
        return Err(Fail::with(diagnostic));
    }
    // A bare name, as STEP 7's source compiler takes it: the block's own variable when the
    // block declares it (see `parser::bare_names`), else a symbol.
    let ends_operand = rest.first().is_none_or(|next| {
        matches!(
            next.kind,
            TokenKind::Dot | TokenKind::LBracket | TokenKind::Comma | TokenKind::RParen
        )
    });
    if ends_operand {
        let (rest, members) = members(ctx)(rest)?;
        return Ok((
            rest,
            S7Operand::Symbol {
                name: name(ctx, first),
                members,
            },
        ));
    }
    Err(unknown_operand(ctx, first))
}

fn unknown_operand(ctx: Ctx<'_>, token: Token) -> nom::Err<Fail> {
    Fail::with(S7ParseError::UnknownOperand {
        word: ctx.text(token).into(),
        at: ctx.span(token),
        set: ctx.set.name(),
        help: None,
    })
}

fn condition(ctx: Ctx<'_>, token: Token) -> Option<Condition> {
    let upper = ctx.upper(token);
    if let Some(condition) = mnemonics::condition(ctx.set, &upper) {
        return Some(condition);
    }
    let foreign = mnemonics::condition(ctx.set.other(), &upper)?;
    ctx.foreign_word(token, false);
    Some(foreign)
}

/// The area and width of an area word, in the file's set or (noted as foreign) the other.
fn area(ctx: Ctx<'_>, token: Token, upper: &str) -> Option<(S7Area, AccessWidth)> {
    if let Some(found) = mnemonics::area(ctx.set, upper) {
        return Some(found);
    }
    let found = mnemonics::area(ctx.set.other(), upper)?;
    ctx.foreign_word(token, false);
    Some(found)
}

fn block_kind(upper: &str) -> Option<S7BlockKind> {
    Some(match upper {
        "OB" => S7BlockKind::Ob,
        "FC" => S7BlockKind::Fc,
        "FB" => S7BlockKind::Fb,
        "DB" | "DI" => S7BlockKind::Db,
        "SFC" => S7BlockKind::Sfc,
        "SFB" => S7BlockKind::Sfb,
        "UDT" => S7BlockKind::Udt,
        _ => return None,
    })
}

/// `FC 1`, `FC1`, `DB 3`, `DI 2`, `SFB 4`; `OPN DB [MW 2]` and `OPN DI [#nr]` give the pointer
/// word. `None` when the word is no block kind (or `DB5.DBW` follows).
fn block_operand<'a>(ctx: Ctx<'a>, input: Tokens<'a>) -> Option<PResult<'a, S7Operand>> {
    let Some((number, rest)) = block_number_tokens(ctx, input) else {
        return block_number_out_of_range(ctx, input).map(|error| Err(Fail::with(error)));
    };
    let Some((kind, number)) = number else {
        // `DB [MW 2]`, `FC [MW 50]`: the word the block number is read from.
        let block = input
            .first()
            .and_then(|token| ctx.word(token))
            .and_then(|upper| block_kind(&upper))
            .unwrap_or(S7BlockKind::Db);
        let result = delimited(
            kind(TokenKind::LBracket, "`[`"),
            |input| pointer_operand(ctx, input),
            kind(TokenKind::RBracket, "`]`"),
        )
        .parse(rest)
        .map(|(rest, word)| {
            (
                rest,
                S7Operand::BlockFrom {
                    kind: block,
                    word: Box::new(word),
                },
            )
        });
        return Some(result);
    };
    Some(Ok((
        rest,
        S7Operand::Block(S7BlockRef::Number { kind, number }),
    )))
}

/// A block kind and its number (`FC 1`, `FC1`), or a block kind before `[` (number `None`).
/// The outer `None`: not a block.
#[allow(clippy::type_complexity)]
pub fn block_number_tokens<'a>(
    ctx: Ctx<'a>,
    input: Tokens<'a>,
) -> Option<(Option<(S7BlockKind, u16)>, Tokens<'a>)> {
    let first = input.first()?;
    let upper = ctx.word(first)?;
    let next = input.second();
    if let Some(kind) = block_kind(&upper) {
        match next {
            Some(token) if token.kind == TokenKind::Number => {
                let number = block_number(ctx, token).ok()?;
                return Some((Some((kind, number)), input.skip(2)));
            }
            Some(token) if token.kind == TokenKind::Minus => {
                let digits = input.tokens.get(2).copied()?;
                let number = awlsim_system_block(ctx, kind, token, digits)?;
                return Some((Some((kind, number)), input.skip(3)));
            }
            Some(token) if token.kind == TokenKind::LBracket => {
                return Some((None, input.skip(1)));
            }
            _ => return None,
        }
    }
    let (letters, digits) = letters_and_digits(&upper)?;
    let kind = block_kind(letters)?;
    // `DB5.DBW 4` is an address.
    if next.is_some_and(|t| t.kind == TokenKind::Dot && first.touches(t)) {
        return None;
    }
    let number = digits.parse::<u16>().ok()?;
    Some((Some((kind, number)), input.skip(1)))
}

/// A block kind with a number past 65535 (`FC 70000`, `FC70000`), where
/// [`block_number_tokens`] finds no block.
pub fn block_number_out_of_range(ctx: Ctx<'_>, input: Tokens<'_>) -> Option<S7ParseError> {
    let first = input.first()?;
    let upper = ctx.word(first)?;
    let next = input.second();
    if block_kind(&upper).is_some() {
        let token = next.filter(|token| token.kind == TokenKind::Number)?;
        return block_number(ctx, token).err();
    }
    let (letters, digits) = letters_and_digits(&upper)?;
    block_kind(letters)?;
    // `DB70000.DBW 4` is an address; its number is checked there.
    if next.is_some_and(|t| t.kind == TokenKind::Dot && first.touches(t)) {
        return None;
    }
    digits
        .parse::<u16>()
        .is_err()
        .then(|| S7ParseError::BlockNumber {
            number: digits.into(),
            at: ctx.span(first),
        })
}

/// awlsim's own system blocks, `SFC -1` to `SFC -4` and `SFB -1` (with the test extensions
/// only): the number as a 16-bit two's complement, 65535 down to 65532 (see
/// [`crate::step7::bytecode::AWLSIM_SFC_REBOOT`]).
fn awlsim_system_block(
    ctx: Ctx<'_>,
    kind: S7BlockKind,
    minus: Token,
    digits: Token,
) -> Option<u16> {
    let number = ctx.text(digits).parse::<i16>().ok()?;
    let known = match kind {
        S7BlockKind::Sfc => (1..=4).contains(&number),
        S7BlockKind::Sfb => number == 1,
        _ => false,
    };
    let awlsim =
        ctx.extensions && known && digits.kind == TokenKind::Number && minus.touches(digits);
    awlsim.then_some(number.wrapping_neg() as u16)
}

fn block_number(ctx: Ctx<'_>, token: Token) -> Result<u16, S7ParseError> {
    ctx.text(token)
        .parse::<u16>()
        .map_err(|_| S7ParseError::BlockNumber {
            number: ctx.text(token).into(),
            at: ctx.span(token),
        })
}

/// Inside `[ … ]` of a block or memory-indirect address: an address or a local.
fn pointer_operand<'a>(ctx: Ctx<'a>, input: Tokens<'a>) -> PResult<'a, S7Operand> {
    match input.first() {
        Some(token) if token.kind == TokenKind::Local => {
            let (rest, path) = local_path(ctx)(input)?;
            Ok((rest, S7Operand::Local(path)))
        }
        Some(token) if token.kind == TokenKind::Word => match address_operand(ctx, input) {
            Some(result) => result,
            None => Err(unknown_operand(ctx, token)),
        },
        _ => Err(fail(
            input,
            "an address such as `MD 10` or a local `#pointer`",
        )),
    }
}

/// An absolute or indirect address; `None` when the word is no area.
fn address_operand<'a>(ctx: Ctx<'a>, input: Tokens<'a>) -> Option<PResult<'a, S7Operand>> {
    let first = input.first()?;
    let upper = ctx.word(first)?;
    // `DB5.DBW 4`
    if let Some(("DB", digits)) = letters_and_digits(&upper)
        && input
            .second()
            .is_some_and(|t| t.kind == TokenKind::Dot && first.touches(t))
    {
        let db = match digits.parse::<u16>() {
            Ok(db) => db,
            Err(_) => {
                return Some(Err(Fail::with(S7ParseError::BlockNumber {
                    number: digits.into(),
                    at: ctx.span(first),
                })));
            }
        };
        let rest = input.skip(2);
        let names_member = rest.first().is_some_and(|member| {
            member.kind == TokenKind::Word
                && !matches!(
                    mnemonics::area(ctx.set, &ctx.upper(member)),
                    Some((S7Area::Data, _))
                )
                && letters_and_digits(&ctx.upper(member)).is_none_or(|(letters, _)| {
                    letters != "DBX" && letters != "DBB" && letters != "DBW" && letters != "DBD"
                })
        });
        if names_member {
            let member = rest.first().expect("checked");
            return Some(members(ctx)(rest.skip(1)).map(|(after, mut path)| {
                path.insert(0, PathPart::Member(name(ctx, member)));
                (after, S7Operand::DbMember { db, path })
            }));
        }
        let result = match address_operand(ctx, rest) {
            Some(Ok((rest, S7Operand::Address(address))))
                if matches!(address.area, S7Area::Data) =>
            {
                Ok((
                    rest,
                    S7Operand::Address(S7Address {
                        db: Some(db),
                        ..address
                    }),
                ))
            }
            Some(Err(error)) => Err(error),
            _ => Err(Fail::with(S7ParseError::BadAddress {
                text: ctx.text(first).into(),
                at: ctx.consumed(input, rest.skip(1)),
                expected: "`DB5.DBX 0.1`, `DB5.DBB 2`, `DB5.DBW 4` or `DB5.DBD 6`".into(),
            })),
        };
        return Some(result);
    }
    // The area word alone (`MW 10`, `MW [MD 2]`) or with its number (`MW10`, `I0.1`).
    if let Some((area, width)) = area(ctx, first, &upper) {
        let rest = input.skip(1);
        return Some(match rest.first() {
            Some(token) if token.kind == TokenKind::LBracket => {
                indirect(ctx, area, width, first, rest)
            }
            Some(token) if token.kind == TokenKind::Number => {
                let (rest, (byte, bit)) = match location(ctx, width, first, token, rest.skip(1)) {
                    Ok(found) => found,
                    Err(error) => return Some(Err(error)),
                };
                Ok((rest, address(area, width, byte, bit)))
            }
            _ => Err(Fail::with(S7ParseError::BadAddress {
                text: ctx.text(first).into(),
                at: ctx.span(first),
                expected: address_shape(width).into(),
            })),
        });
    }
    let (letters, digits) = letters_and_digits(&upper)?;
    let (area, width) = self::area(ctx, first, letters)?;
    let byte: u32 = digits.parse().ok()?;
    let rest = input.skip(1);
    if width != AccessWidth::Bit {
        return Some(Ok((rest, address(area, width, byte, 0))));
    }
    // `I0.1`: the bit after a touching `.`.
    let result = match (rest.first(), rest.second()) {
        (Some(dot), Some(bit))
            if dot.kind == TokenKind::Dot
                && bit.kind == TokenKind::Number
                && first.touches(dot)
                && dot.touches(bit) =>
        {
            match ctx.text(bit).parse::<u8>() {
                Ok(bit_number) if bit_number <= 7 => {
                    Ok((rest.skip(2), address(area, width, byte, bit_number)))
                }
                _ => Err(bad_address(ctx, first, bit, width)),
            }
        }
        _ => Err(bad_address(ctx, first, first, width)),
    };
    Some(result)
}

fn address(area: S7Area, width: AccessWidth, byte: u32, bit: u8) -> S7Operand {
    S7Operand::Address(S7Address {
        area,
        width,
        byte,
        bit,
        db: None,
    })
}

fn address_shape(width: AccessWidth) -> &'static str {
    match width {
        AccessWidth::Bit => "a byte and a bit: `I 0.1`",
        _ => "a byte number: `MW 10`",
    }
}

fn bad_address(ctx: Ctx<'_>, first: Token, last: Token, width: AccessWidth) -> nom::Err<Fail> {
    Fail::with(S7ParseError::BadAddress {
        text: ctx.source[first.start as usize..last.end as usize].into(),
        at: ctx.span_of(first, last),
        expected: address_shape(width).into(),
    })
}

/// The number token after an area word: `0.1` for a bit, `10` otherwise (a bit of 0 … 7).
fn location<'a>(
    ctx: Ctx<'a>,
    width: AccessWidth,
    area: Token,
    token: Token,
    rest: Tokens<'a>,
) -> Result<(Tokens<'a>, (u32, u8)), nom::Err<Fail>> {
    let text = ctx.text(token).replace('_', "");
    let parsed = match (width, text.split_once('.')) {
        (AccessWidth::Bit, Some((byte, bit))) => byte
            .parse::<u32>()
            .ok()
            .zip(bit.parse::<u8>().ok().filter(|bit| *bit <= 7)),
        (AccessWidth::Bit, None) => None,
        (_, None) => text.parse::<u32>().ok().map(|byte| (byte, 0)),
        (_, Some(_)) => None,
    };
    match parsed {
        Some(found) => Ok((rest, found)),
        None => Err(bad_address(ctx, area, token, width)),
    }
}

/// After the area word: `[MD 10]`, `[#pointer]` or `[AR1, P#2.0]`.
fn indirect<'a>(
    ctx: Ctx<'a>,
    area: S7Area,
    width: AccessWidth,
    area_token: Token,
    input: Tokens<'a>,
) -> PResult<'a, S7Operand> {
    let is_register = input.second().is_some_and(|t| {
        t.kind == TokenKind::Word && matches!(ctx.upper(t).as_str(), "AR1" | "AR2")
    });
    if is_register {
        let (rest, (ar, offset)) = register_pointer(ctx)(input)?;
        return Ok((
            rest,
            S7Operand::Indirect {
                area,
                width,
                pointer: IndirectPointer::Register { ar, offset },
            },
        ));
    }
    let (rest, inner) = delimited(
        kind(TokenKind::LBracket, "`[`"),
        |input| pointer_operand(ctx, input),
        kind(TokenKind::RBracket, "`]`"),
    )
    .parse(input)?;
    let at = ctx.consumed(input, rest);
    match inner {
        S7Operand::Address(pointer) => {
            let wanted = if matches!(area, S7Area::Timer | S7Area::Counter) {
                AccessWidth::Word
            } else {
                AccessWidth::Double
            };
            if pointer.width != wanted || matches!(pointer.area, S7Area::Timer | S7Area::Counter) {
                return Err(Fail::with(S7ParseError::BadAddress {
                    text: ctx.source[area_token.start as usize..at.end as usize].into(),
                    at,
                    expected: if wanted == AccessWidth::Word {
                        "a word holding the number, such as `[MW 4]`".into()
                    } else {
                        "a double word holding the pointer, such as `[MD 10]`".into()
                    },
                }));
            }
            Ok((
                rest,
                S7Operand::Indirect {
                    area,
                    width,
                    pointer: IndirectPointer::Memory(pointer),
                },
            ))
        }
        S7Operand::Local(path) => Ok((
            rest,
            S7Operand::IndirectLocal {
                area,
                width,
                pointer: path,
            },
        )),
        _ => Err(fail(input, "an address")),
    }
}

/// `[AR1, P#2.0]`: the register and the offset in bits.
fn register_pointer<'a>(ctx: Ctx<'a>) -> impl Fn(Tokens<'a>) -> PResult<'a, (u8, u32)> {
    move |input: Tokens<'a>| {
        let (rest, _) = kind(TokenKind::LBracket, "`[`")(input)?;
        let (rest, register) = kind(TokenKind::Word, "`AR1` or `AR2`")(rest)?;
        let ar = match ctx.upper(register).as_str() {
            "AR1" => 1,
            "AR2" => 2,
            _ => return Err(fail(rest, "`AR1` or `AR2`")),
        };
        let (rest, _) = kind(TokenKind::Comma, "`,`")(rest)?;
        let (rest, offset) = kind(TokenKind::Typed, "an offset `P#2.0`")(rest)?;
        let text = ctx.text(offset);
        let Some(spec) = text
            .get(..2)
            .filter(|p| p.eq_ignore_ascii_case("P#"))
            .map(|_| &text[2..])
        else {
            return Err(fail(input.skip(3), "an offset `P#2.0`"));
        };
        let pointer = literal::pointer(ctx.set, spec)
            .map_err(|error| Fail::with(literal_error(error, ctx.span(offset))))?;
        if pointer.value >> 24 != 0 {
            return Err(fail(input.skip(3), "an offset without area: `P#2.0`"));
        }
        let (rest, _) = kind(TokenKind::RBracket, "`]`")(rest)?;
        Ok((rest, (ar, pointer.value)))
    }
}

/// `#name`, `#a.b`, `#arr[1, 2]`.
pub fn local_path<'a>(ctx: Ctx<'a>) -> impl Fn(Tokens<'a>) -> PResult<'a, Vec<PathPart>> {
    move |input: Tokens<'a>| {
        let (rest, token) = kind(TokenKind::Local, "`#name`")(input)?;
        let first = Name {
            text: ctx.text(token)[1..].to_string(),
            span: ctx.span(token),
        };
        let (rest, mut tail) = members(ctx)(rest)?;
        tail.insert(0, PathPart::Member(first));
        Ok((rest, tail))
    }
}

/// `"Motor"` with members: `"DB".on`, `"DB".speeds[3]`.
fn symbol_path<'a>(ctx: Ctx<'a>) -> impl Fn(Tokens<'a>) -> PResult<'a, (Name, Vec<PathPart>)> {
    move |input: Tokens<'a>| {
        let (rest, token) = kind(TokenKind::Symbol, "`\"symbol\"`")(input)?;
        let (rest, members) = members(ctx)(rest)?;
        Ok((rest, (symbol_name(ctx, token), members)))
    }
}

/// The name of a `"symbol"` token, without its quotes.
pub fn symbol_name(ctx: Ctx<'_>, token: Token) -> Name {
    let text = ctx.text(token);
    Name {
        text: text[1..text.len() - 1].to_string(),
        span: ctx.span(token),
    }
}

/// `.member` and `[1, 2]` steps of a path.
pub fn members<'a>(ctx: Ctx<'a>) -> impl Fn(Tokens<'a>) -> PResult<'a, Vec<PathPart>> {
    move |mut input: Tokens<'a>| {
        let mut parts = Vec::new();
        loop {
            let member = preceded(
                kind(TokenKind::Dot, "`.`"),
                alt((
                    kind(TokenKind::Word, "a member name"),
                    kind(TokenKind::Symbol, "a member name"),
                )),
            )
            .parse(input);
            if let Ok((rest, token)) = member {
                let name = if token.kind == TokenKind::Symbol {
                    symbol_name(ctx, token)
                } else {
                    Name {
                        text: ctx.text(token).into(),
                        span: ctx.span(token),
                    }
                };
                parts.push(PathPart::Member(name));
                input = rest;
                continue;
            }
            let index = delimited(
                kind(TokenKind::LBracket, "`[`"),
                separated_list1(
                    kind(TokenKind::Comma, "`,`"),
                    super::tokens::signed_integer(ctx),
                ),
                kind(TokenKind::RBracket, "`]`"),
            )
            .parse(input);
            if let Ok((rest, indices)) = index {
                parts.push(PathPart::Index(
                    indices.into_iter().map(|(value, _)| value as i32).collect(),
                ));
                input = rest;
                continue;
            }
            return Ok((input, parts));
        }
    }
}

/// A constant: a number with its sign, a typed constant, a pointer, a quoted character or
/// string, `B#(1, 2)`, `TRUE`/`FALSE`.
pub fn constant<'a>(ctx: Ctx<'a>) -> impl Fn(Tokens<'a>) -> PResult<'a, S7Constant> {
    move |input: Tokens<'a>| {
        let Some(first) = input.first() else {
            return Err(fail(input, "a constant"));
        };
        let at = |last: Token| ctx.span_of(first, last);
        let literal = |result: Result<S7Constant, LiteralError>, last: Token| {
            result.map_err(|error| Fail::with(literal_error(error, at(last))))
        };
        match first.kind {
            TokenKind::Minus | TokenKind::Plus => {
                let (rest, number) = kind(TokenKind::Number, "a number")(input.skip(1))?;
                let value = literal(
                    literal::number(ctx.text(number), first.kind == TokenKind::Minus),
                    number,
                )?;
                Ok((rest, value))
            }
            TokenKind::Number => Ok((
                input.skip(1),
                literal(literal::number(ctx.text(first), false), first)?,
            )),
            TokenKind::Quoted => {
                let text = ctx.text(first);
                Ok((
                    input.skip(1),
                    literal(literal::quoted(&text[1..text.len() - 1]), first)?,
                ))
            }
            TokenKind::Word => match ctx.upper(first).as_str() {
                "TRUE" => Ok((input.skip(1), literal::boolean(true))),
                "FALSE" => Ok((input.skip(1), literal::boolean(false))),
                _ => Err(fail(input, "a constant")),
            },
            TokenKind::Typed => typed_constant(ctx, input, first),
            _ => Err(fail(input, "a constant")),
        }
    }
}

/// `P##local`, `P#DB1.member`, `P#"symbol"`: a pointer to a named operand. The text after
/// `P#` and the tokens that touch it are read again as an operand.
fn pointer_to<'a>(ctx: Ctx<'a>, input: Tokens<'a>) -> Option<PResult<'a, S7Operand>> {
    let first = input.first().filter(|t| t.kind == TokenKind::Typed)?;
    let text = ctx.text(first);
    let spec = text
        .get(..2)
        .filter(|p| p.eq_ignore_ascii_case("P#"))
        .map(|_| &text[2..])?;
    let upper = spec.to_ascii_uppercase();
    let db_member = upper
        .strip_prefix("DB")
        .and_then(|tail| tail.split_once('.'))
        .is_some_and(|(number, member)| {
            !number.is_empty()
                && number.chars().all(|c| c.is_ascii_digit())
                && !["DBX", "DBB", "DBW", "DBD"]
                    .iter()
                    .any(|area| member.starts_with(area))
        });
    let named = spec.starts_with('#') || db_member;
    let symbol = spec.is_empty()
        && input
            .second()
            .is_some_and(|t| t.kind == TokenKind::Symbol && first.touches(t));
    if !named && !symbol {
        return None;
    }
    // The run of touching tokens: `P##a.b[1, 2]` lexes as `P##a.b`, `[`, `1`, … .
    let mut end = 1;
    let mut depth = 0usize;
    while let Some(token) = input.tokens.get(end) {
        let previous = input.tokens[end - 1];
        let continues = depth > 0 || previous.touches(*token);
        if !continues || (depth == 0 && matches!(token.kind, TokenKind::Comma | TokenKind::RParen))
        {
            break;
        }
        match token.kind {
            TokenKind::LBracket => depth += 1,
            TokenKind::RBracket => depth = depth.saturating_sub(1),
            _ => {}
        }
        end += 1;
    }
    let start = first.start + 2;
    let stop = input.tokens[end - 1].end;
    let relexed: Vec<Token> = crate::step7::lexer::lex(&ctx.source[start as usize..stop as usize])
        .into_iter()
        .map(|t| Token {
            start: t.start + start,
            end: t.end + start,
            ..t
        })
        .collect();
    let inner = match value(ctx, Tokens::new(&relexed)) {
        Ok((rest, operand)) if rest.is_empty() => operand,
        Ok((rest, _)) => return Some(Err(fail(rest, "the end of the pointer"))),
        Err(error) => return Some(Err(error)),
    };
    Some(Ok((input.skip(end), S7Operand::PointerTo(Box::new(inner)))))
}

fn typed_constant<'a>(ctx: Ctx<'a>, input: Tokens<'a>, first: Token) -> PResult<'a, S7Constant> {
    let text = ctx.text(first);
    let upper = text.to_ascii_uppercase();
    let rest = input.skip(1);
    if upper == "B#" && rest.first().is_some_and(|t| t.kind == TokenKind::LParen) {
        let (after, values) = delimited(
            kind(TokenKind::LParen, "`(`"),
            separated_list1(kind(TokenKind::Comma, "`,`"), integer(ctx)),
            kind(TokenKind::RParen, "`)`"),
        )
        .parse(rest)?;
        let values: Vec<i64> = values.into_iter().map(|(value, _)| value).collect();
        let at = ctx.consumed(input, after);
        let constant =
            literal::byte_tuple(&values).map_err(|error| Fail::with(literal_error(error, at)))?;
        return Ok((after, constant));
    }
    if let Some(spec) = upper.strip_prefix("P#") {
        // The address may go on in the following tokens: `P#M 1.0`, `P#DB1.DBX 0.0 BYTE 10`.
        let mut words = vec![text[2..].to_string()];
        let mut after = rest;
        while let Some(token) = after.first() {
            let joins = matches!(
                token.kind,
                TokenKind::Number | TokenKind::Word | TokenKind::Dot
            ) && words.len() < 4;
            if !joins {
                break;
            }
            words.push(ctx.text(token).to_string());
            after = after.skip(1);
        }
        let _ = spec;
        let at = ctx.consumed(input, after);
        let constant = literal::pointer(ctx.set, &words.join(" "))
            .map_err(|error| Fail::with(literal_error(error, at)))?;
        return Ok((after, constant));
    }
    // awlsim reads `DW#16#0xFF` too; its test files write it.
    let awlsim_hex;
    let text = if ctx.extensions && upper.contains("#0X") {
        awlsim_hex = upper.replacen("#0X", "#", 1);
        awlsim_hex.as_str()
    } else {
        text
    };
    let constant =
        literal::typed(text).map_err(|error| Fail::with(literal_error(error, ctx.span(first))))?;
    Ok((rest, constant))
}

pub fn literal_error(error: LiteralError, at: crate::source::Span) -> S7ParseError {
    if error.out_of_range {
        S7ParseError::ConstantRange {
            format: error.format.into(),
            at,
            range: error.expected,
        }
    } else {
        S7ParseError::BadConstant {
            format: error.format.into(),
            at,
            expected: error.expected,
        }
    }
}

/// awlsim's test operands: `__STW`, `__STW n`, `__STW VKE`, `__ACCU n`, `__AR n`, `__DBR n`,
/// `__CNST_PI` …
fn extension<'a>(ctx: Ctx<'a>, input: Tokens<'a>) -> PResult<'a, S7Operand> {
    let first = input.first().expect("a word");
    let upper = ctx.upper(first);
    if !ctx.extensions {
        return Err(Fail::with(S7ParseError::ExtensionNotEnabled {
            word: ctx.text(first).into(),
            at: ctx.span(first),
        }));
    }
    let rest = input.skip(1);
    let constant = match upper.as_str() {
        "__CNST_PI" => Some(Extension::Pi),
        "__CNST_E" => Some(Extension::E),
        "__CNST_PINF" => Some(Extension::PositiveInfinity),
        "__CNST_NINF" => Some(Extension::NegativeInfinity),
        "__CNST_PNAN" => Some(Extension::PositiveNan),
        "__CNST_NNAN" => Some(Extension::NegativeNan),
        _ => None,
    };
    if let Some(constant) = constant {
        return Ok((rest, S7Operand::Extension(constant)));
    }
    let numbered = |make: fn(u8) -> Extension| {
        let (after, (value, token)) = integer(ctx)(rest)?;
        match u8::try_from(value) {
            Ok(number) => Ok((after, S7Operand::Extension(make(number)))),
            Err(_) => Err(Fail::with(S7ParseError::BadAddress {
                text: ctx.text(token).into(),
                at: ctx.span(token),
                expected: "a small number".into(),
            })),
        }
    };
    match upper.as_str() {
        "__ACCU" => numbered(Extension::Accu),
        "__AR" => numbered(Extension::AddressRegister),
        "__DBR" => numbered(Extension::DbRegister),
        "__STW" => status_word(ctx, rest),
        _ => Err(unknown_operand(ctx, first)),
    }
}

/// `__STW` alone, `__STW 1`, `__STW VKE`, `__STW /ER`.
fn status_word<'a>(ctx: Ctx<'a>, input: Tokens<'a>) -> PResult<'a, S7Operand> {
    let bit_name = |input: Tokens<'a>| -> PResult<'a, u8> {
        // `/FC` and `/ER` lex as one token, like `/I`.
        let (rest, word) = alt((
            kind(TokenKind::Word, "a status bit"),
            kind(TokenKind::SignedWord, "a status bit"),
        ))
        .parse(input)?;
        let name = ctx.upper(word);
        let bit = mnemonics::status_bit(ctx.set, &name)
            .or_else(|| mnemonics::status_bit(ctx.set.other(), &name));
        match bit {
            Some(bit) => Ok((rest, bit)),
            None => Err(Fail::with(S7ParseError::UnknownOperand {
                word: name,
                at: ctx.consumed(input, rest),
                set: ctx.set.name(),
                help: Some(
                    "status bits: /FC RLO STA OR OS OV CC0 CC1 BR (German /ER VKE STA OR OS OV A0 A1 BIE), or 0 … 8"
                        .into(),
                ),
            })),
        }
    };
    let number = |input: Tokens<'a>| -> PResult<'a, u8> {
        let (rest, (value, token)) = integer(ctx)(input)?;
        match u8::try_from(value).ok().filter(|bit| *bit <= 8) {
            Some(bit) => Ok((rest, bit)),
            None => Err(Fail::with(S7ParseError::BadAddress {
                text: ctx.text(token).into(),
                at: ctx.span(token),
                expected: "a status bit 0 … 8".into(),
            })),
        }
    };
    if end(input).is_ok() || input.first().is_some_and(|t| t.kind == TokenKind::Comma) {
        return Ok((input, S7Operand::Extension(Extension::StatusWord)));
    }
    let (rest, bit) = alt((number, bit_name)).parse(input)?;
    Ok((rest, S7Operand::Extension(Extension::StatusBit(bit))))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mnemonics::MnemonicSet;
    use crate::step7::lexer::lex;
    use std::cell::Cell;

    fn parse_in(set: MnemonicSet, text: &str, expect: Expect) -> Result<S7Operand, Fail> {
        let tokens = lex(text);
        let foreign = Cell::new(None);
        let ctx = Ctx {
            context: crate::syntax::Context {
                source: text,
                file: 0,
                set,
            },
            extensions: true,
            foreign: &foreign,
        };
        match operand(ctx, expect)(Tokens::new(&tokens)) {
            Ok((rest, operand)) if rest.is_empty() => Ok(operand),
            Ok((rest, operand)) => panic!("{text}: {operand:?} leaves {:?}", rest.tokens),
            Err(nom::Err::Error(error) | nom::Err::Failure(error)) => Err(error),
            Err(nom::Err::Incomplete(_)) => unreachable!(),
        }
    }

    fn parse(text: &str) -> S7Operand {
        parse_in(MnemonicSet::English, text, Expect::Value)
            .unwrap_or_else(|error| panic!("{text}: {error:?}"))
    }

    /// The code of the error an English operand fails with.
    fn error_code(text: &str) -> String {
        let error = parse_in(MnemonicSet::English, text, Expect::Value).unwrap_err();
        error.diagnostic.expect("a diagnostic").stable_code()
    }

    fn addr(area: S7Area, width: AccessWidth, byte: u32, bit: u8) -> S7Operand {
        address(area, width, byte, bit)
    }

    #[test]
    fn absolute_addresses_with_or_without_a_blank() {
        use AccessWidth::*;
        assert_eq!(parse("I 0.1"), addr(S7Area::Input, Bit, 0, 1));
        assert_eq!(parse("I0.1"), addr(S7Area::Input, Bit, 0, 1));
        assert_eq!(parse("MW10"), addr(S7Area::Flag, Word, 10, 0));
        assert_eq!(parse("MW 10"), addr(S7Area::Flag, Word, 10, 0));
        assert_eq!(parse("DBX 0.0"), addr(S7Area::Data, Bit, 0, 0));
        assert_eq!(
            parse("PIW 256"),
            addr(S7Area::PeripheralInput, Word, 256, 0)
        );
        assert_eq!(parse("T 5"), addr(S7Area::Timer, Word, 5, 0));
        assert_eq!(parse("C 3"), addr(S7Area::Counter, Word, 3, 0));
        let german = parse_in(MnemonicSet::German, "Z 3", Expect::Value).unwrap();
        assert_eq!(german, addr(S7Area::Counter, Word, 3, 0));
        let S7Operand::Address(data) = parse("DB5.DBW 4") else {
            panic!()
        };
        assert_eq!((data.db, data.byte, data.width), (Some(5), 4, Word));
        let S7Operand::Address(data) = parse("DB5.DBX0.7") else {
            panic!()
        };
        assert_eq!((data.db, data.bit), (Some(5), 7));
    }

    #[test]
    fn bad_addresses() {
        for text in ["I 0.8", "I 4", "MW 1.0"] {
            assert_eq!(error_code(text), "awl::s7::bad_address", "{text}");
        }
        assert_eq!(error_code("XY 1"), "awl::s7::unknown_operand");
    }

    #[test]
    fn indirect_addresses() {
        assert_eq!(
            parse("MW [MD 10]"),
            S7Operand::Indirect {
                area: S7Area::Flag,
                width: AccessWidth::Word,
                pointer: IndirectPointer::Memory(S7Address {
                    area: S7Area::Flag,
                    width: AccessWidth::Double,
                    byte: 10,
                    bit: 0,
                    db: None
                })
            }
        );
        assert_eq!(
            parse("DBX [AR1, P#2.0]"),
            S7Operand::Indirect {
                area: S7Area::Data,
                width: AccessWidth::Bit,
                pointer: IndirectPointer::Register { ar: 1, offset: 16 }
            }
        );
        assert_eq!(
            parse("W [AR2,P#0.0]"),
            S7Operand::AreaCrossing {
                width: AccessWidth::Word,
                ar: 2,
                offset: 0
            }
        );
        assert_eq!(
            parse("[AR1,P#2.1]"),
            S7Operand::AreaCrossing {
                width: AccessWidth::Bit,
                ar: 1,
                offset: 17
            }
        );
        let S7Operand::Indirect { area, pointer, .. } = parse("T [MW 4]") else {
            panic!()
        };
        assert_eq!(area, S7Area::Timer);
        assert!(matches!(pointer, IndirectPointer::Memory(a) if a.width == AccessWidth::Word));
        assert!(matches!(
            parse("MW [#ptr]"),
            S7Operand::IndirectLocal { .. }
        ));
        assert_eq!(error_code("MW [MW 10]"), "awl::s7::bad_address");
    }

    #[test]
    fn blocks_and_block_pointers() {
        let block = |kind, number| S7Operand::Block(S7BlockRef::Number { kind, number });
        assert_eq!(
            parse_in(MnemonicSet::English, "FC 1", Expect::Block).unwrap(),
            block(S7BlockKind::Fc, 1)
        );
        assert_eq!(
            parse_in(MnemonicSet::English, "SFC46", Expect::Block).unwrap(),
            block(S7BlockKind::Sfc, 46)
        );
        assert_eq!(
            parse_in(MnemonicSet::English, "DI 2", Expect::Block).unwrap(),
            block(S7BlockKind::Db, 2)
        );
        assert_eq!(
            parse_in(MnemonicSet::English, "DB [MW 2]", Expect::Block).unwrap(),
            S7Operand::BlockFrom {
                kind: S7BlockKind::Db,
                word: Box::new(addr(S7Area::Flag, AccessWidth::Word, 2, 0))
            }
        );
        assert!(matches!(
            parse_in(MnemonicSet::German, "DB [#DBNR]", Expect::Block).unwrap(),
            S7Operand::BlockFrom { word, .. } if matches!(*word, S7Operand::Local(_))
        ));
        assert!(matches!(
            parse_in(MnemonicSet::English, "FB [MW 50]", Expect::Block).unwrap(),
            S7Operand::BlockFrom {
                kind: S7BlockKind::Fb,
                ..
            }
        ));
    }

    #[test]
    fn locals_and_symbols_with_paths() {
        let S7Operand::Local(path) = parse("#arr[1, 2]") else {
            panic!()
        };
        assert!(matches!(&path[0], PathPart::Member(n) if n.text == "arr"));
        assert_eq!(path[1], PathPart::Index(vec![1, 2]));
        let S7Operand::Local(path) = parse("#a.b") else {
            panic!()
        };
        assert_eq!(path.len(), 2);
        let S7Operand::Symbol { name, members } = parse(r#""DB".member"#) else {
            panic!()
        };
        assert_eq!((name.text.as_str(), members.len()), ("DB", 1));
    }

    #[test]
    fn constants_conditions_registers_and_labels() {
        let S7Operand::Constant(c) = parse("-5") else {
            panic!()
        };
        assert_eq!(c.value, 0xFFFB);
        let S7Operand::Constant(c) = parse("P#M 1.0") else {
            panic!()
        };
        assert_eq!(c.value, 0x8300_0008);
        let S7Operand::Constant(c) = parse("P#DB1.DBX 0.0 BYTE 10") else {
            panic!()
        };
        assert_eq!(c.bytes.len(), 10);
        let S7Operand::Constant(c) = parse("B#(1, 2)") else {
            panic!()
        };
        assert_eq!(c.value, 0x0102);
        assert_eq!(parse("==0"), S7Operand::Condition(Condition::Zero));
        assert_eq!(parse("BR"), S7Operand::Condition(Condition::BinaryResult));
        assert_eq!(
            parse_in(MnemonicSet::German, "BIE", Expect::Value).unwrap(),
            S7Operand::Condition(Condition::BinaryResult)
        );
        assert_eq!(parse("DBNO"), S7Operand::DbRegister(DbRegister::DbNumber));
        assert_eq!(parse("AR2"), S7Operand::AddressRegister(2));
        assert!(matches!(
            parse_in(MnemonicSet::English, "M001", Expect::Label).unwrap(),
            S7Operand::Label(n) if n.text == "M001"
        ));
        assert_eq!(
            parse_in(MnemonicSet::English, "3", Expect::Count).unwrap(),
            S7Operand::Number(3)
        );
    }

    #[test]
    fn test_extension_operands() {
        assert_eq!(
            parse("__STW VKE"),
            S7Operand::Extension(Extension::StatusBit(1))
        );
        assert_eq!(
            parse("__STW /FC"),
            S7Operand::Extension(Extension::StatusBit(0))
        );
        assert_eq!(
            parse("__STW 8"),
            S7Operand::Extension(Extension::StatusBit(8))
        );
        assert_eq!(parse("__STW"), S7Operand::Extension(Extension::StatusWord));
        assert_eq!(parse("__ACCU 2"), S7Operand::Extension(Extension::Accu(2)));
        assert_eq!(
            parse("__CNST_PINF"),
            S7Operand::Extension(Extension::PositiveInfinity)
        );
    }
}
