//! Interfaces and data: `VAR_INPUT … END_VAR` sections, declarations with their data types and
//! initial values, `STRUCT … END_STRUCT`, and the `name := value;` lines of a data block.

use nom::Parser;
use nom::branch::alt;
use nom::multi::separated_list1;
use nom::sequence::{delimited, separated_pair};

use crate::ast::Name;
use crate::step7::ast::{
    ConstKind, DataType, InitialValue, PathPart, S7BlockKind, S7Constant, VarDecl, VarKind,
    VarSection,
};
use crate::step7::error::S7ParseError;
use crate::step7::lexer::{Token, TokenKind};

use super::Parser as Driver;
use super::operand::{constant, members, symbol_name};
use super::statement::finish;
use super::tokens::{
    Ctx, PResult, Tokens, fail, integer, kind, letters_and_digits, signed_integer,
};

/// The section keywords and what they declare.
pub fn section_kind(upper: &str) -> Option<VarKind> {
    Some(match upper {
        "VAR_INPUT" => VarKind::Input,
        "VAR_OUTPUT" => VarKind::Output,
        "VAR_IN_OUT" => VarKind::InOut,
        "VAR" => VarKind::Static,
        "VAR_TEMP" => VarKind::Temp,
        _ => return None,
    })
}

/// The elementary types by name.
fn elementary(upper: &str) -> Option<DataType> {
    Some(match upper {
        "BOOL" => DataType::Bool,
        "BYTE" => DataType::Byte,
        "WORD" => DataType::Word,
        "DWORD" => DataType::Dword,
        "INT" => DataType::Int,
        "DINT" => DataType::Dint,
        "REAL" => DataType::Real,
        "S5TIME" => DataType::S5Time,
        "TIME" => DataType::Time,
        "DATE" => DataType::Date,
        "TIME_OF_DAY" | "TOD" => DataType::TimeOfDay,
        "CHAR" => DataType::Char,
        "DATE_AND_TIME" | "DT" => DataType::DateAndTime,
        "TIMER" => DataType::Timer,
        "COUNTER" => DataType::Counter,
        "POINTER" => DataType::Pointer,
        "ANY" => DataType::Any,
        "BLOCK_DB" => DataType::BlockDb,
        "BLOCK_FB" => DataType::BlockFb,
        "BLOCK_FC" => DataType::BlockFc,
        _ => return None,
    })
}

pub const TYPE_NAMES: &[&str] = &[
    "BOOL",
    "BYTE",
    "WORD",
    "DWORD",
    "INT",
    "DINT",
    "REAL",
    "S5TIME",
    "TIME",
    "DATE",
    "TIME_OF_DAY",
    "CHAR",
    "DATE_AND_TIME",
    "STRING",
    "ARRAY",
    "STRUCT",
    "UDT",
    "TIMER",
    "COUNTER",
    "POINTER",
    "ANY",
    "BLOCK_DB",
    "BLOCK_FB",
    "BLOCK_FC",
];

impl<'a> Driver<'a> {
    /// `VAR_INPUT` (already consumed) … `END_VAR`.
    pub(super) fn section(&mut self, kind: VarKind, keyword: Token) -> VarSection {
        let vars = self.declarations(keyword, "END_VAR");
        let end = self
            .tokens
            .get(self.pos.saturating_sub(1))
            .copied()
            .unwrap_or(keyword);
        VarSection {
            kind,
            vars,
            span: self.ctx.span_of(keyword, end),
        }
    }

    /// Declarations up to `end` (`END_VAR`, `END_STRUCT`), which is consumed. A missing `end`
    /// is one error at `opened`.
    pub(super) fn declarations(&mut self, opened: Token, end: &'static str) -> Vec<VarDecl> {
        let mut vars = Vec::new();
        loop {
            self.skip_blank();
            let Some(token) = self.peek() else {
                self.unclosed(opened, end);
                return vars;
            };
            let word = self.ctx.word(token);
            match word.as_deref() {
                Some(word) if word == end => {
                    self.pos += 1;
                    return vars;
                }
                Some(word) if self.ends_declarations(word) => {
                    self.unclosed(opened, end);
                    return vars;
                }
                _ => {}
            }
            if token.kind == TokenKind::LBrace {
                self.skip_attributes();
                continue;
            }
            match self.declaration() {
                Ok(declaration) => vars.push(declaration),
                Err(error) => {
                    self.errors.push(error);
                    self.skip_declaration();
                }
            }
        }
    }

    fn unclosed(&mut self, opened: Token, end: &'static str) {
        self.errors.push(S7ParseError::UnclosedBlock {
            keyword: self.ctx.text(opened).into(),
            end: end.into(),
            at: self.ctx.span(opened),
            help: format!("close it with `{end}`"),
        });
    }

    /// A word that cannot start a declaration: the next section, `BEGIN`, a block's end.
    fn ends_declarations(&self, word: &str) -> bool {
        word == "BEGIN"
            || word.starts_with("END_")
            || section_kind(word).is_some()
            || super::block_keyword(word).is_some()
    }

    /// Skips a bad declaration: to its `;` or the end of its line.
    fn skip_declaration(&mut self) {
        while let Some(token) = self.peek() {
            self.pos += 1;
            if matches!(token.kind, TokenKind::Semicolon | TokenKind::Newline) {
                return;
            }
        }
    }

    /// `name {attributes} : TYPE [:= initial] ;`
    fn declaration(&mut self) -> Result<VarDecl, S7ParseError> {
        let first = self.peek().expect("checked by the caller");
        if first.kind != TokenKind::Word {
            return Err(super::statement::unexpected(self.ctx, first, "a name"));
        }
        self.pos += 1;
        if self.peek().is_some_and(|t| t.kind == TokenKind::LBrace) {
            self.skip_attributes();
        }
        self.expect(TokenKind::Colon, "`:` and a data type")?;
        let ty = self.data_type()?;
        let mut initial = Vec::new();
        if self.peek().is_some_and(|t| t.kind == TokenKind::Assign) {
            self.pos += 1;
            initial = self.initial_values()?;
        }
        let last = self.tokens[self.pos - 1];
        match self.peek() {
            Some(token) if token.kind == TokenKind::Semicolon => self.pos += 1,
            Some(token) if token.kind == TokenKind::Newline => {}
            None => {}
            Some(token) => {
                return Err(super::statement::unexpected(self.ctx, token, "`;`"));
            }
        }
        Ok(VarDecl {
            name: Name {
                text: self.ctx.text(first).into(),
                span: self.ctx.span(first),
            },
            ty,
            initial,
            span: self.ctx.span_of(first, last),
        })
    }

    fn expect(&mut self, wanted: TokenKind, expected: &str) -> Result<Token, S7ParseError> {
        self.skip_newlines();
        match self.peek() {
            Some(token) if token.kind == wanted => {
                self.pos += 1;
                Ok(token)
            }
            Some(token) => Err(super::statement::unexpected(self.ctx, token, expected)),
            None => Err(self.at_end(expected)),
        }
    }

    /// A data type, the structures spread over lines; a UDT or FB also by its symbol
    /// (`"MotorData"`), which the compiler resolves.
    pub(super) fn data_type(&mut self) -> Result<DataType, S7ParseError> {
        self.skip_newlines();
        let Some(token) = self.peek() else {
            return Err(self.at_end("a data type"));
        };
        if token.kind == TokenKind::Symbol {
            self.pos += 1;
            return Ok(DataType::Named(symbol_name(self.ctx, token)));
        }
        let Some(upper) = self.ctx.word(token) else {
            return Err(super::statement::unexpected(self.ctx, token, "a data type"));
        };
        self.pos += 1;
        if let Some(ty) = elementary(&upper) {
            return Ok(ty);
        }
        match upper.as_str() {
            "STRING" => self.string_type(),
            "ARRAY" => self.array_type(),
            "STRUCT" => Ok(DataType::Struct(self.declarations(token, "END_STRUCT"))),
            _ => self.numbered_type(token, &upper),
        }
    }

    fn string_type(&mut self) -> Result<DataType, S7ParseError> {
        if !self.peek().is_some_and(|t| t.kind == TokenKind::LBracket) {
            return Ok(DataType::String(254));
        }
        let ctx = self.ctx;
        let length = self.nom(|input| {
            delimited(
                kind(TokenKind::LBracket, "`[`"),
                integer(ctx),
                kind(TokenKind::RBracket, "`]`"),
            )
            .parse(input)
        })?;
        match u8::try_from(length.0).ok().filter(|n| *n <= 254) {
            Some(length) => Ok(DataType::String(length)),
            None => Err(S7ParseError::BadDeclaration {
                at: self.ctx.span(length.1),
                reason: "a STRING holds 0 to 254 characters".into(),
            }),
        }
    }

    /// `ARRAY [1..10, 0..3] OF T`
    fn array_type(&mut self) -> Result<DataType, S7ParseError> {
        let ctx = self.ctx;
        let dims = self.nom(|input| {
            delimited(
                kind(TokenKind::LBracket, "`[`"),
                separated_list1(
                    kind(TokenKind::Comma, "`,`"),
                    separated_pair(
                        signed_integer(ctx),
                        kind(TokenKind::Range, "`..`"),
                        signed_integer(ctx),
                    ),
                ),
                kind(TokenKind::RBracket, "`]`"),
            )
            .parse(input)
        })?;
        let mut bounds = Vec::with_capacity(dims.len());
        for ((low, low_token), (high, high_token)) in dims {
            let fits = |value: i64| (-32768..=32767).contains(&value);
            if !fits(low) || !fits(high) || low > high {
                return Err(S7ParseError::BadDeclaration {
                    at: self.ctx.span_of(low_token, high_token),
                    reason: "bounds from −32768 to 32767, the lower first".into(),
                });
            }
            bounds.push((low as i32, high as i32));
        }
        self.skip_newlines();
        match self.peek() {
            Some(token) if self.ctx.word(token).as_deref() == Some("OF") => self.pos += 1,
            Some(token) => return Err(super::statement::unexpected(self.ctx, token, "`OF`")),
            None => return Err(self.at_end("`OF`")),
        }
        let element = self.data_type()?;
        Ok(DataType::Array {
            dims: bounds,
            element: Box::new(element),
        })
    }

    /// `UDT 5`, `UDT5`, `FB 5`, `SFB 3`.
    fn numbered_type(&mut self, token: Token, upper: &str) -> Result<DataType, S7ParseError> {
        let (word, number) = match letters_and_digits(upper) {
            Some((letters, digits)) => (letters.to_string(), digits.parse::<u16>().ok()),
            None => {
                let number = match self.peek() {
                    Some(next) if next.kind == TokenKind::Number => {
                        self.pos += 1;
                        self.ctx.text(next).parse::<u16>().ok()
                    }
                    _ => None,
                };
                (upper.to_string(), number)
            }
        };
        let kind = match word.as_str() {
            "UDT" => None,
            "FB" => Some(S7BlockKind::Fb),
            "SFB" => Some(S7BlockKind::Sfb),
            _ => {
                return Err(S7ParseError::UnknownType {
                    word: self.ctx.text(token).into(),
                    at: self.ctx.span(token),
                    help: suggest_type(upper),
                });
            }
        };
        let Some(number) = number else {
            return Err(S7ParseError::BadDeclaration {
                at: self.ctx.span(token),
                reason: format!("`{word}` needs its number, such as `{word} 5`"),
            });
        };
        Ok(match kind {
            None => DataType::Udt(number),
            Some(kind) => DataType::Instance(kind, number),
        })
    }

    /// Runs a nom parser on the tokens up to the end of the line; the cursor moves past what it
    /// took.
    pub(super) fn nom<T>(
        &mut self,
        parser: impl Fn(Tokens<'a>) -> PResult<'a, T>,
    ) -> Result<T, S7ParseError> {
        let line = self.rest_of_line();
        let last = *line
            .last()
            .unwrap_or(&self.tokens[self.pos.saturating_sub(1)]);
        let input = Tokens::new(line);
        let (rest, value) = finish(self.ctx, last, parser(input))?;
        self.pos += line.len() - rest.tokens.len();
        Ok(value)
    }

    /// `1`, `1, 2, 3`, `3 (0)`, `2 (1, 2)`: one value per element, repeats expanded.
    fn initial_values(&mut self) -> Result<Vec<S7Constant>, S7ParseError> {
        let ctx = self.ctx;
        let items = self.nom(|input| {
            separated_list1(kind(TokenKind::Comma, "`,`"), |input| {
                initial_item(ctx, input)
            })
            .parse(input)
        })?;
        Ok(items.into_iter().flatten().collect())
    }

    /// `name := value;` lines after a data block's `BEGIN`, up to its `END_…` (not consumed).
    pub(super) fn initial_lines(&mut self) -> Vec<InitialValue> {
        let mut values = Vec::new();
        loop {
            self.skip_blank();
            let Some(token) = self.peek() else {
                return values;
            };
            if self.ctx.word(token).is_some_and(|word| {
                word.starts_with("END_") || super::block_keyword(&word).is_some()
            }) {
                return values;
            }
            match self.initial_line() {
                Ok(value) => values.push(value),
                Err(error) => {
                    self.errors.push(error);
                    self.skip_declaration();
                }
            }
        }
    }

    fn initial_line(&mut self) -> Result<InitialValue, S7ParseError> {
        let ctx = self.ctx;
        let start = self.peek().expect("checked");
        let (path, value) = self.nom(|input| {
            let (rest, (path, value)) = separated_pair(
                |input| path(ctx, input),
                kind(TokenKind::Assign, "`:=`"),
                |input| data_value(ctx, input),
            )
            .parse(input)?;
            Ok((rest, (path, value)))
        })?;
        let last = self.tokens[self.pos - 1];
        match self.peek() {
            Some(token) if token.kind == TokenKind::Semicolon => self.pos += 1,
            Some(token) if token.kind == TokenKind::Newline => {}
            None => {}
            Some(token) => return Err(super::statement::unexpected(self.ctx, token, "`;`")),
        }
        Ok(InitialValue {
            path,
            value,
            span: self.ctx.span_of(start, last),
        })
    }
}

/// `a.b[1, 2]` at the start of a data block's line.
fn path<'a>(ctx: Ctx<'a>, input: Tokens<'a>) -> PResult<'a, Vec<PathPart>> {
    let (rest, first) = kind(TokenKind::Word, "a member name")(input)?;
    let (rest, mut tail) = members(ctx)(rest)?;
    tail.insert(
        0,
        PathPart::Member(Name {
            text: ctx.text(first).into(),
            span: ctx.span(first),
        }),
    );
    Ok((rest, tail))
}

/// A value of a data block or declaration: a constant, or a timer or counter number.
fn data_value<'a>(ctx: Ctx<'a>, input: Tokens<'a>) -> PResult<'a, S7Constant> {
    let timer_or_counter = |input: Tokens<'a>| -> PResult<'a, S7Constant> {
        let (rest, word) = kind(TokenKind::Word, "a constant")(input)?;
        let kind_of = match (ctx.upper(word).as_str(), ctx.set) {
            ("T", _) => ConstKind::TimerNumber,
            ("C", crate::mnemonics::MnemonicSet::English)
            | ("Z", crate::mnemonics::MnemonicSet::German) => ConstKind::CounterNumber,
            _ => return Err(fail(input, "a constant")),
        };
        let (rest, (number, _)) = integer(ctx)(rest)?;
        Ok((
            rest,
            S7Constant {
                kind: kind_of,
                value: number as u32,
                bytes: Vec::new(),
            },
        ))
    };
    alt((constant(ctx), timer_or_counter)).parse(input)
}

/// One item of an initial value list: a value, or `count (values)`.
fn initial_item<'a>(ctx: Ctx<'a>, input: Tokens<'a>) -> PResult<'a, Vec<S7Constant>> {
    let repeated = |input: Tokens<'a>| -> PResult<'a, Vec<S7Constant>> {
        let (rest, (count, _)) = integer(ctx)(input)?;
        let (rest, values) = delimited(
            kind(TokenKind::LParen, "`(`"),
            separated_list1(kind(TokenKind::Comma, "`,`"), |input| {
                data_value(ctx, input)
            }),
            kind(TokenKind::RParen, "`)`"),
        )
        .parse(rest)?;
        let count = usize::try_from(count).unwrap_or(0).min(65_536);
        Ok((
            rest,
            values
                .iter()
                .cloned()
                .cycle()
                .take(values.len() * count)
                .collect(),
        ))
    };
    alt((repeated, |input| {
        data_value(ctx, input).map(|(rest, value)| (rest, vec![value]))
    }))
    .parse(input)
}

fn suggest_type(upper: &str) -> Option<String> {
    TYPE_NAMES
        .iter()
        .map(|name| (strsim::damerau_levenshtein(upper, name), name))
        .filter(|(distance, _)| *distance <= 2)
        .min_by_key(|(distance, _)| *distance)
        .map(|(_, name)| format!("did you mean `{name}`?"))
        .or_else(|| Some(format!("STEP 7 data types: {}", TYPE_NAMES.join(", "))))
}
