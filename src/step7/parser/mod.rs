//! The STEP 7 parser: a source file as STEP 7 exports it (blocks from `ORGANIZATION_BLOCK` …
//! to `END_…`, their headers, interfaces, statements and data) to an [`S7Unit`]. A file without
//! any block keyword is a flat statement list: OB 1's body.
//!
//! Recovery: every error is reported at its line and parsing goes on: a bad statement, a bad
//! declaration or a bad data line is dropped, a missing `END_…` is one error at its opening
//! keyword.

mod bare_names;
mod interface;
pub use interface::TYPE_NAMES;
mod operand;
mod statement;
pub(crate) use statement::takes_label;
mod step5;
mod tokens;
pub(crate) use tokens::letters_and_digits;

use std::cell::Cell;

use crate::ast::Name;
use crate::mnemonics::MnemonicSet;
use crate::source::{FileId, Span};
use crate::syntax::token::runs;
use crate::syntax::votes::Votes;

use super::ast::{
    DataType, S7Block, S7BlockKind, S7BlockRef, S7Body, S7Statement, S7Unit, VarSection,
};
use super::error::S7ParseError;
use super::lexer::{Token, TokenKind, lex};
use super::mnemonics;

use statement::Line;
use tokens::Ctx;

/// How to read the file.
#[derive(Debug, Clone, Copy, Default)]
pub struct ParseOptions {
    /// `--mnemonics en|de`: the set to use instead of the detected one.
    pub mnemonics: Option<MnemonicSet>,
    /// awlsim's test extensions (`__ASSERT==`, `__STW`, …) are allowed.
    pub extensions: bool,
}

/// The result of parsing one file: whatever blocks could be built, and every error found, in
/// the order of the text.
#[derive(Debug)]
pub struct Parsed {
    pub unit: S7Unit,
    pub errors: Vec<S7ParseError>,
}

/// The block keywords, their kind and their end.
pub(crate) fn block_keyword(upper: &str) -> Option<(S7BlockKind, &'static str)> {
    Some(match upper {
        "ORGANIZATION_BLOCK" => (S7BlockKind::Ob, "END_ORGANIZATION_BLOCK"),
        "FUNCTION" => (S7BlockKind::Fc, "END_FUNCTION"),
        "FUNCTION_BLOCK" => (S7BlockKind::Fb, "END_FUNCTION_BLOCK"),
        "DATA_BLOCK" => (S7BlockKind::Db, "END_DATA_BLOCK"),
        "TYPE" => (S7BlockKind::Udt, "END_TYPE"),
        _ => return None,
    })
}

/// Header lines before the interface: read and dropped with the rest of their line.
pub const HEADER_WORDS: &[&str] = &[
    "TITLE",
    "AUTHOR",
    "FAMILY",
    "NAME",
    "VERSION",
    "KNOW_HOW_PROTECT",
    "STANDARD",
    "UNLINKED",
    "NON_RETAIN",
    "READ_ONLY",
    "CODE_VERSION1",
];

/// Parses one STEP 7 file.
pub fn parse(file: FileId, text: &str, options: ParseOptions) -> Parsed {
    let tokens = lex(text);
    let flat = !tokens.iter().enumerate().any(|(index, token)| {
        starts_line(&tokens, index)
            && token.kind == TokenKind::Word
            && block_keyword(&token.text(text).to_ascii_uppercase()).is_some()
    });
    let detected = detect(text, &tokens, flat);
    let set = options
        .mnemonics
        .or(detected.map(|(set, _)| set))
        .unwrap_or(MnemonicSet::English);
    let foreign = Cell::new(None);
    let ctx = Ctx {
        context: crate::syntax::Context {
            source: text,
            file,
            set,
        },
        extensions: options.extensions,
        foreign: &foreign,
    };
    let mut parser = Parser {
        ctx,
        tokens: &tokens,
        pos: 0,
        errors: Vec::new(),
    };
    let blocks = if flat {
        parser.flat_file()
    } else {
        parser.blocks()
    };
    let mut errors = parser.errors;
    if let Some((token, operation)) = foreign.get() {
        let decided_by = if options.mnemonics.is_some() {
            None
        } else {
            detected.map(|(_, span)| Span { file, ..span })
        };
        errors.push(mixed(ctx, token, operation, decided_by));
    }
    errors.sort_by_key(|error| error.span().start);
    Parsed {
        unit: S7Unit {
            file,
            mnemonics: set,
            blocks,
        },
        errors,
    }
}

fn starts_line(tokens: &[Token], index: usize) -> bool {
    index == 0 || tokens[index - 1].kind == TokenKind::Newline
}

/// The mixed-mnemonics error for the first word of the other set.
fn mixed(ctx: Ctx<'_>, token: Token, operation: bool, decided_by: Option<Span>) -> S7ParseError {
    let upper = ctx.upper(token);
    let other = ctx.set.other();
    let instead = if operation {
        mnemonics::operation(other, &upper).map(|op| mnemonics::op_word(ctx.set, op))
    } else {
        mnemonics::area(other, &upper)
            .map(|(area, width)| mnemonics::area_word(ctx.set, area, width))
    };
    S7ParseError::MixedMnemonics {
        word: ctx.text(token).into(),
        word_set: other.with_article(),
        file_set: ctx.set.name(),
        at: ctx.span(token),
        decided_by,
        help: instead.map(|word| {
            format!(
                "the {} set writes `{word}`; a file uses one set (`--mnemonics en|de` chooses it)",
                ctx.set.name()
            )
        }),
    }
}

/// Decides the mnemonic set from the words of statements that only one set has (`U`, `SPA`,
/// `E 0.0` German; `A`, `JU`, `I 0.0` English): the set with more such words wins; the span is
/// its first word.
fn detect(source: &str, tokens: &[Token], flat: bool) -> Option<(MnemonicSet, Span)> {
    let mut votes = Votes::default();
    let mut in_body = flat;
    for line in runs(tokens, |kind| {
        matches!(kind, TokenKind::Newline | TokenKind::Semicolon)
    }) {
        let words: Vec<String> = line
            .iter()
            .filter(|t| t.kind == TokenKind::Word)
            .map(|t| t.text(source).to_ascii_uppercase())
            .collect();
        let Some(first) = words.first() else { continue };
        if first == "BEGIN" {
            in_body = true;
            continue;
        }
        if first.starts_with("END_") {
            in_body = false;
            continue;
        }
        if !in_body {
            continue;
        }
        // A call's actual parameter (`stoerung := E 10.0`) names its area in one set's words.
        if let Some(assign) = line.iter().position(|t| t.kind == TokenKind::Assign) {
            if let Some(actual) = line.get(assign + 1).filter(|t| t.kind == TokenKind::Word)
                && let Some(set) = area_evidence(source, *actual)
            {
                votes.vote(set, *actual);
            }
            continue;
        }
        let line = match line {
            [word, colon, rest @ ..]
                if word.kind == TokenKind::Word && colon.kind == TokenKind::Colon =>
            {
                rest
            }
            _ => line,
        };
        let Some(op_token) = line.first().filter(|t| t.kind == TokenKind::Word) else {
            continue;
        };
        let op = op_token.text(source).to_ascii_uppercase();
        let op = match line.get(1) {
            Some(paren) if paren.kind == TokenKind::LParen && op_token.touches(*paren) => {
                format!("{op}(")
            }
            _ => op,
        };
        if let Some(set) = mnemonics::operation_evidence(&op) {
            votes.vote(set, *op_token);
        }
        let takes_address = [MnemonicSet::English, MnemonicSet::German]
            .iter()
            .filter_map(|set| mnemonics::operation(*set, &op))
            .any(statement::takes_address);
        if let Some(operand) = line
            .get(1)
            .filter(|t| t.kind == TokenKind::Word && takes_address)
            && let Some(set) = area_evidence(source, *operand)
        {
            votes.vote(set, *operand);
        }
    }
    votes.winner()
}

/// The set whose area word `operand` is (`E`, `EW` German; `I`, `IW` English), if only one's.
fn area_evidence(source: &str, operand: Token) -> Option<MnemonicSet> {
    let upper = operand.text(source).to_ascii_uppercase();
    let area = tokens::letters_and_digits(&upper).map_or(upper.as_str(), |(letters, _)| letters);
    mnemonics::operand_evidence(area)
}

/// The cursor over a file's tokens.
struct Parser<'a> {
    ctx: Ctx<'a>,
    tokens: &'a [Token],
    pos: usize,
    errors: Vec<S7ParseError>,
}

impl<'a> Parser<'a> {
    fn peek(&self) -> Option<Token> {
        self.tokens.get(self.pos).copied()
    }

    fn peek_word(&self) -> Option<String> {
        self.peek().and_then(|token| self.ctx.word(token))
    }

    fn skip_newlines(&mut self) {
        while self.peek().is_some_and(|t| t.kind == TokenKind::Newline) {
            self.pos += 1;
        }
    }

    /// Line ends and empty statements.
    fn skip_blank(&mut self) {
        while self
            .peek()
            .is_some_and(|t| matches!(t.kind, TokenKind::Newline | TokenKind::Semicolon))
        {
            self.pos += 1;
        }
    }

    fn rest_of_line(&self) -> &'a [Token] {
        let rest = &self.tokens[self.pos..];
        let end = rest
            .iter()
            .position(|t| t.kind == TokenKind::Newline)
            .unwrap_or(rest.len());
        &rest[..end]
    }

    fn skip_line(&mut self) {
        self.pos += self.rest_of_line().len();
    }

    /// `{ S7_language := '…'; … }`, over lines.
    fn skip_attributes(&mut self) {
        while let Some(token) = self.peek() {
            self.pos += 1;
            if token.kind == TokenKind::RBrace {
                return;
            }
        }
    }

    fn at_end(&self, expected: &str) -> S7ParseError {
        let last = self.tokens.last().copied();
        S7ParseError::UnexpectedToken {
            found: "end of file".into(),
            at: last.map_or(
                Span {
                    file: self.ctx.file,
                    start: 0,
                    end: 0,
                },
                |t| self.ctx.span(t),
            ),
            expected: expected.into(),
        }
    }

    /// A file without block keywords: OB 1's statements.
    fn flat_file(&mut self) -> Vec<S7Block> {
        let statements = self.statements(None);
        let (Some(first), Some(last)) = (statements.first(), statements.last()) else {
            return Vec::new();
        };
        let (header, end) = (first.span, last.span);
        vec![S7Block {
            kind: S7BlockKind::Ob,
            name: S7BlockRef::Number {
                kind: S7BlockKind::Ob,
                number: 1,
            },
            header,
            return_type: None,
            interface: Vec::new(),
            body: S7Body::Logic(statements),
            end: Some(end),
        }]
    }

    fn blocks(&mut self) -> Vec<S7Block> {
        let mut blocks = Vec::new();
        let mut outside_reported = false;
        loop {
            self.skip_blank();
            let Some(token) = self.peek() else {
                return blocks;
            };
            if token.kind == TokenKind::LBrace {
                self.skip_attributes();
                continue;
            }
            match self.peek_word().as_deref().and_then(block_keyword) {
                Some((kind, end)) => {
                    outside_reported = false;
                    if let Some(block) = self.block(kind, end) {
                        blocks.push(block);
                    }
                }
                None => {
                    if !outside_reported {
                        self.errors.push(S7ParseError::OutsideBlock {
                            at: self.line_span(),
                        });
                        outside_reported = true;
                    }
                    self.skip_line();
                }
            }
        }
    }

    /// The span of the rest of the current line.
    fn line_span(&self) -> Span {
        let line = self.rest_of_line();
        match (line.first(), line.last()) {
            (Some(first), Some(last)) => self.ctx.span_of(*first, *last),
            _ => Span::default(),
        }
    }

    /// One block, from its keyword to its `END_…`; `None` when its header was bad (its lines
    /// are still checked).
    fn block(&mut self, kind: S7BlockKind, end: &'static str) -> Option<S7Block> {
        let keyword = self.peek().expect("checked by the caller");
        self.pos += 1;
        let header = self.header(kind, keyword);
        let header_span = self.ctx.span_of(keyword, self.tokens[self.pos - 1]);
        let mut interface: Vec<VarSection> = Vec::new();
        let mut members = Vec::new();
        let mut instance_of = None;
        let mut body = None;
        let mut end_span = None;
        loop {
            self.skip_blank();
            let Some(token) = self.peek() else { break };
            if token.kind == TokenKind::LBrace {
                self.skip_attributes();
                continue;
            }
            let word = self.ctx.word(token);
            let word = word.as_deref().unwrap_or("");
            if let Some(section) = interface::section_kind(word) {
                self.pos += 1;
                interface.push(self.section(section, token));
                continue;
            }
            if word.starts_with("END_") {
                end_span = Some(self.end(token, keyword, end));
                break;
            }
            if block_keyword(word).is_some() {
                break;
            }
            match word {
                "BEGIN" => {
                    self.pos += 1;
                    body = Some(match kind {
                        S7BlockKind::Db | S7BlockKind::Udt => S7Body::Data {
                            instance_of: None,
                            members: Vec::new(),
                            initial: self.initial_lines(),
                        },
                        _ => {
                            let mut statements = self.statements(Some(end));
                            let returns = matches!(&header, Some((_, Some(_))));
                            bare_names::declared_as_locals(
                                self.ctx.source,
                                &interface,
                                returns,
                                &mut statements,
                            );
                            S7Body::Logic(statements)
                        }
                    });
                }
                "STRUCT" if matches!(kind, S7BlockKind::Db | S7BlockKind::Udt) => {
                    self.pos += 1;
                    members = self.declarations(token, "END_STRUCT");
                }
                _ if HEADER_WORDS.contains(&word) => self.skip_line(),
                _ if kind == S7BlockKind::Db && instance_of.is_none() => {
                    match self.instance_line() {
                        Ok(instance) => instance_of = Some(instance),
                        Err(error) => {
                            self.errors.push(error);
                            self.skip_line();
                        }
                    }
                }
                _ => {
                    self.errors.push(statement::unexpected(
                        self.ctx,
                        token,
                        "`VAR_INPUT`, `VAR_OUTPUT`, `VAR_IN_OUT`, `VAR`, `VAR_TEMP`, `BEGIN` or the block's end",
                    ));
                    self.skip_line();
                }
            }
        }
        if end_span.is_none() {
            self.errors.push(S7ParseError::UnclosedBlock {
                keyword: self.ctx.text(keyword).into(),
                end: end.into(),
                at: self.ctx.span(keyword),
                help: format!(
                    "end the block with `{end}` before the next block or the end of the file"
                ),
            });
        }
        let (name, return_type) = header?;
        let body = match kind {
            S7BlockKind::Db => S7Body::Data {
                instance_of,
                members,
                initial: match body {
                    Some(S7Body::Data { initial, .. }) => initial,
                    _ => Vec::new(),
                },
            },
            S7BlockKind::Udt => S7Body::Type(members),
            _ => body.unwrap_or(S7Body::Logic(Vec::new())),
        };
        Some(S7Block {
            kind,
            name,
            header: header_span,
            return_type,
            interface,
            body,
            end: end_span,
        })
    }

    /// The rest of the header line: the block (`FC 1`, `"Valve"`) and a function's type.
    fn header(
        &mut self,
        kind: S7BlockKind,
        keyword: Token,
    ) -> Option<(S7BlockRef, Option<DataType>)> {
        let result = self.header_line(kind, keyword);
        match result {
            Ok(header) => {
                // `DATA_BLOCK "ValveDB" "Valve"`, `DATA_BLOCK DB 5 FB 5`, `DATA_BLOCK DB 6
                // UDT 2`: the FB of an instance DB, or the UDT, on the header line, read as the
                // line after it would be.
                let instance_follows = kind == S7BlockKind::Db
                    && self.rest_of_line().first().is_some_and(|t| {
                        t.kind == TokenKind::Symbol
                            || self.ctx.word(*t).is_some_and(|word| {
                                ["FB", "SFB", "UDT"].iter().any(|k| word.starts_with(k))
                            })
                    });
                if instance_follows {
                    return Some(header);
                }
                if let Some(extra) = self
                    .rest_of_line()
                    .first()
                    .filter(|t| t.kind != TokenKind::Semicolon)
                {
                    self.errors.push(statement::unexpected(
                        self.ctx,
                        *extra,
                        "the end of the header line",
                    ));
                }
                self.skip_line();
                Some(header)
            }
            Err(error) => {
                self.errors.push(error);
                self.skip_line();
                None
            }
        }
    }

    fn header_line(
        &mut self,
        kind: S7BlockKind,
        keyword: Token,
    ) -> Result<(S7BlockRef, Option<DataType>), S7ParseError> {
        let ctx = self.ctx;
        let expected = match kind {
            S7BlockKind::Udt => "`UDT n` or a name in quotes",
            _ => "the block: `FC 1` or a name in quotes",
        };
        let name = match self.peek() {
            Some(token) if token.kind == TokenKind::Symbol => {
                self.pos += 1;
                S7BlockRef::Symbol(operand::symbol_name(ctx, token))
            }
            Some(token) if token.kind != TokenKind::Newline => {
                let input = tokens::Tokens::new(self.rest_of_line());
                match operand::block_number_tokens(ctx, input) {
                    Some((Some((found, number)), rest)) if found == kind => {
                        self.pos += input.tokens.len() - rest.tokens.len();
                        S7BlockRef::Number { kind, number }
                    }
                    _ => return Err(self.bad_header(token, kind, expected)),
                }
            }
            _ => return Err(self.at_line_end(keyword, expected)),
        };
        if kind == S7BlockKind::Fb
            && self.peek().is_some_and(|t| t.kind == TokenKind::Colon)
            && self
                .tokens
                .get(self.pos + 1)
                .and_then(|t| self.ctx.word(*t))
                .as_deref()
                == Some("VOID")
        {
            // `FUNCTION_BLOCK FB 1 : VOID`: awlsim's files give FBs a type; it says nothing.
            self.pos += 2;
        }
        if kind != S7BlockKind::Fc {
            return Ok((name, None));
        }
        match self.peek() {
            Some(token) if token.kind == TokenKind::Colon => self.pos += 1,
            _ => return Ok((name, None)),
        }
        let return_type = match self.peek_word().as_deref() {
            Some("VOID") => {
                self.pos += 1;
                None
            }
            _ => Some(self.data_type()?),
        };
        Ok((name, return_type))
    }

    fn bad_header(&self, token: Token, kind: S7BlockKind, expected: &str) -> S7ParseError {
        if let Some(word) = self.ctx.word(token) {
            let number = tokens::letters_and_digits(&word).map(|(_, digits)| digits);
            if let Some(digits) = number.filter(|d| d.parse::<u16>().is_err()) {
                return S7ParseError::BlockNumber {
                    number: digits.into(),
                    at: self.ctx.span(token),
                };
            }
            if let Some(next) = self
                .tokens
                .get(self.pos + 1)
                .filter(|t| t.kind == TokenKind::Number)
                && self.ctx.text(*next).parse::<u16>().is_err()
            {
                return S7ParseError::BlockNumber {
                    number: self.ctx.text(*next).into(),
                    at: self.ctx.span(*next),
                };
            }
        }
        S7ParseError::UnexpectedToken {
            found: format!("`{}`", self.ctx.text(token)),
            at: self.ctx.span(token),
            expected: format!("{expected} ({} for this keyword)", kind.name()),
        }
    }

    fn at_line_end(&self, after: Token, expected: &str) -> S7ParseError {
        S7ParseError::UnexpectedToken {
            found: "end of line".into(),
            at: self.ctx.span(after),
            expected: expected.into(),
        }
    }

    /// `END_…`: checked against the block's keyword; the rest of its line is dropped.
    fn end(&mut self, token: Token, keyword: Token, end: &'static str) -> Span {
        let found = self.ctx.upper(token);
        if found != end {
            self.errors.push(S7ParseError::MismatchedEnd {
                found: self.ctx.text(token).into(),
                opened: self.ctx.text(keyword).into(),
                at: self.ctx.span(token),
                expected: end.into(),
            });
        }
        self.pos += 1;
        self.skip_line();
        self.ctx.span(token)
    }

    /// A data block's `FB 1`, `SFB 3`, `UDT 1` or `"Name"` line: the block it is the instance
    /// DB of, or the UDT it is laid out as.
    fn instance_line(&mut self) -> Result<S7BlockRef, S7ParseError> {
        let ctx = self.ctx;
        let token = self.peek().expect("checked by the caller");
        let line = tokens::Tokens::new(self.rest_of_line());
        let (reference, rest) = match token.kind {
            TokenKind::Symbol => (
                S7BlockRef::Symbol(operand::symbol_name(ctx, token)),
                line.skip(1),
            ),
            _ => match operand::block_number_tokens(ctx, line) {
                // `UDT 1`: a global DB laid out as the UDT.
                Some((
                    Some((kind @ (S7BlockKind::Fb | S7BlockKind::Sfb | S7BlockKind::Udt), number)),
                    rest,
                )) => (S7BlockRef::Number { kind, number }, rest),
                _ => {
                    if let Some(nom::Err::Failure(fail) | nom::Err::Error(fail)) =
                        statement::bad_block_number(ctx, line)
                        && let Some(diagnostic) = fail.diagnostic
                    {
                        return Err(*diagnostic);
                    }
                    return Err(statement::unexpected(
                        ctx,
                        token,
                        "`STRUCT`, the FB of an instance DB (`FB 1`, `SFB 3`), a UDT (`UDT 1`) \
                         or `BEGIN`",
                    ));
                }
            },
        };
        if let Some(extra) = rest.first().filter(|t| t.kind != TokenKind::Semicolon) {
            return Err(statement::unexpected(ctx, extra, "the end of the line"));
        }
        self.skip_line();
        Ok(reference)
    }

    /// Statements up to the block's `END_…` (not consumed), or the end of a flat file.
    fn statements(&mut self, end: Option<&'static str>) -> Vec<S7Statement> {
        let mut statements = Vec::new();
        let mut network = 0u16;
        let mut pending_label: Option<Name> = None;
        loop {
            self.skip_blank();
            let Some(token) = self.peek() else { break };
            let word = self.ctx.word(token);
            if let Some(word) = word.as_deref() {
                let at_line_start = starts_line(self.tokens, self.pos);
                if end.is_some()
                    && (word.starts_with("END_")
                        || (at_line_start && block_keyword(word).is_some()))
                {
                    break;
                }
                if word == "NETWORK" && at_line_start {
                    network = network.saturating_add(1);
                    self.skip_line();
                    continue;
                }
                if word == "TITLE"
                    && self
                        .tokens
                        .get(self.pos + 1)
                        .is_some_and(|t| t.kind == TokenKind::Equals)
                {
                    self.skip_line();
                    continue;
                }
            }
            if token.kind == TokenKind::LBrace {
                self.skip_attributes();
                continue;
            }
            let tokens = self.statement_tokens();
            match statement::statement(self.ctx, &tokens) {
                Ok(Line::Label(label)) => {
                    pending_label = Some(label);
                }
                Ok(Line::Statement(mut statement)) => {
                    statement.network = network;
                    if statement.label.is_none() {
                        statement.label = pending_label.take();
                    }
                    statements.push(*statement);
                }
                Err(error) => self.errors.push(error),
            }
        }
        statements
    }

    /// The tokens of one statement: to its `;` or line end; a `CALL`'s parameter list goes on
    /// over lines to its `)`. The cursor moves past them (and the `;`).
    fn statement_tokens(&mut self) -> Vec<Token> {
        let rest = &self.tokens[self.pos..];
        let is_call = rest
            .iter()
            .take(4)
            .any(|t| t.kind == TokenKind::Word && self.ctx.upper(*t) == "CALL");
        let mut depth = 0usize;
        let mut taken = Vec::new();
        let mut used = 0;
        for (index, token) in rest.iter().enumerate() {
            used = index + 1;
            match token.kind {
                TokenKind::LParen if is_call => depth += 1,
                TokenKind::RParen if is_call => depth = depth.saturating_sub(1),
                TokenKind::Semicolon if depth == 0 => break,
                TokenKind::Newline if depth == 0 => break,
                TokenKind::Newline => {
                    // A parameter list does not go on past a block's end.
                    let next = self.tokens.get(self.pos + index + 1);
                    if next.is_some_and(|t| {
                        self.ctx
                            .word(*t)
                            .is_some_and(|w| w.starts_with("END_") || w == "NETWORK")
                    }) {
                        break;
                    }
                    continue;
                }
                _ => {}
            }
            taken.push(*token);
        }
        self.pos += used;
        taken
    }
}

#[cfg(test)]
mod tests;
