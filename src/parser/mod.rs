//! Parser: a file's tokens to blocks of statements. Line oriented, with line-wise recovery: a bad
//! line is reported and skipped, and parsing goes on with the next line.

mod constant;
pub mod error;
pub mod line;
pub mod listing;
#[cfg(test)]
mod spellings;
mod step7_word;
pub mod tokens;

pub use constant::pg_float_form;
pub use error::ParseError;
pub use step7_word::explain_step7_word;

use crate::ast::{Block, BlockBody, BlockId, DataWord, LogicBody, Operand, SourceUnit, Statement};
use crate::dialect;
use crate::lexer::{Token, TokenKind, lex};
use crate::mnemonics::{self, MnemonicSet, OpCode, Position};
use crate::source::{FileId, Span};
use crate::syntax::token::runs;
use crate::syntax::votes::Votes;

use line::describe;
use tokens::{Context, LineError, Tokens, fail};

/// The result of parsing one file: whatever blocks could be built, and every error found.
#[derive(Debug)]
pub struct ParsedFile {
    pub unit: SourceUnit,
    pub errors: Vec<ParseError>,
    /// The file starts with statements before any block header: `unit.blocks[0]` holds them,
    /// as a provisional FB 0 until the front end, knowing all files, gives them their block.
    pub fragment: bool,
}

/// Parses one file. `forced` overrides the mnemonic set detected from the file's words.
pub fn parse_file(file: FileId, source: &str, forced: Option<MnemonicSet>) -> ParsedFile {
    let tokens = lex(source);
    if let Some(evidence) = dialect::detect(source, &tokens) {
        return step7_file(file, forced, evidence);
    }
    let lines: Vec<&[Token]> = runs(&tokens, |kind| kind == TokenKind::Newline).collect();
    let detected = detect(source, &lines);
    let set = forced
        .or(detected.map(|(set, _)| set))
        .unwrap_or(MnemonicSet::English);
    let mut builder = Builder {
        source,
        file,
        set,
        decided_by: if forced.is_some() {
            None
        } else {
            detected.map(|(_, span)| Span { file, ..span })
        },
        blocks: Vec::new(),
        current: None,
        ended: false,
        discard: false,
        outside_reported: false,
        next_data_word: 0,
        segment: 0,
        listing: false,
        foreign: None,
        fragment: false,
        errors: Vec::new(),
    };
    for line in lines {
        builder.line(line);
    }
    let mut parsed = builder.finish();
    parsed
        .errors
        .extend(constant::decimal_float_warnings(file, source, &tokens));
    parsed
}

/// A STEP 7 source: one error at its first evidence, and no blocks (checking it line by line as
/// STEP 5 would report every line).
fn step7_file(
    file: FileId,
    forced: Option<MnemonicSet>,
    evidence: dialect::Evidence,
) -> ParsedFile {
    ParsedFile {
        unit: SourceUnit {
            file,
            mnemonics: forced.unwrap_or(MnemonicSet::English),
            blocks: Vec::new(),
        },
        errors: vec![ParseError::Step7Source {
            at: evidence.span(file),
            what: evidence.what,
        }],
        fragment: false,
    }
}

/// Decides the mnemonic set from the words that only one set has in their position: the set with
/// more such words wins; the span is its first word.
fn detect(source: &str, lines: &[&[Token]]) -> Option<(MnemonicSet, Span)> {
    let mut votes = Votes::default();
    for line in lines {
        let mut words = strip_label(line)
            .iter()
            .filter(|token| token.kind == TokenKind::Word);
        let Some(first) = words.next() else { continue };
        let text = first.text(source);
        if text.eq_ignore_ascii_case(mnemonics::DECLARATION_EN) {
            votes.vote(MnemonicSet::English, *first);
            continue;
        }
        if text.eq_ignore_ascii_case(mnemonics::DECLARATION_DE) {
            votes.vote(MnemonicSet::German, *first);
            continue;
        }
        if let Some(set) = mnemonics::evidence(Position::Operation, text) {
            votes.vote(set, *first);
        }
        if let Some(second) = words.next()
            && let Some(set) = mnemonics::evidence(Position::Operand, second.text(source))
        {
            votes.vote(set, *second);
        }
    }
    votes.winner()
}

/// The tokens after an optional listing address, an optional `LABEL :` and the optional
/// leading `:`.
fn strip_label(line: &[Token]) -> &[Token] {
    let line = match line {
        [first, rest @ ..] if first.kind == TokenKind::Number => rest,
        _ => line,
    };
    let line = match line {
        [first, second, rest @ ..]
            if first.kind == TokenKind::Word && second.kind == TokenKind::Colon =>
        {
            rest
        }
        _ => line,
    };
    match line {
        [first, rest @ ..] if first.kind == TokenKind::Colon => rest,
        _ => line,
    }
}

struct Builder<'a> {
    source: &'a str,
    file: FileId,
    set: MnemonicSet,
    decided_by: Option<Span>,
    blocks: Vec<Block>,
    current: Option<Block>,
    /// The current logic block has had its `BE`.
    ended: bool,
    /// The current block's header was bad: its lines are checked, the block is dropped.
    discard: bool,
    outside_reported: bool,
    next_data_word: u16,
    /// The segment of a PG listing the lines are in (0 before any heading).
    segment: u16,
    /// Statement addresses have been seen: the file is a PG listing.
    listing: bool,
    /// The first word of the other mnemonic set.
    /// The first word of the other set, and whether it stands in the operation's place.
    foreign: Option<(Span, bool)>,
    /// The file started with statements before any header (see [`ParsedFile::fragment`]).
    fragment: bool,
    errors: Vec<ParseError>,
}

impl<'a> Builder<'a> {
    fn context(&self, set: MnemonicSet) -> Context<'a> {
        Context {
            source: self.source,
            file: self.file,
            set,
        }
    }

    fn span_of(&self, line: &[Token]) -> Span {
        line[0].span_to(line[line.len() - 1], self.file)
    }

    fn line(&mut self, line: &'a [Token]) {
        let invalid = line.iter().find(|token| token.kind == TokenKind::Invalid);
        if let Some(invalid) = invalid.filter(|_| !self.is_name_line(line)) {
            self.errors.push(ParseError::UnexpectedCharacter {
                found: invalid.text(self.source).to_string(),
                at: invalid.span(self.file),
            });
            return;
        }
        match line::header(self.context(self.set))(Tokens::new(line)) {
            Ok((_, id)) => return self.start_block(id, self.span_of(line)),
            Err(nom::Err::Failure(LineError {
                diagnostic: Some(diagnostic),
                ..
            })) => {
                // A header with a bad number: its lines are still checked, so they are not
                // reported as outside a block, but the block stays out of the program.
                self.errors.push(*diagnostic);
                let kind = line::header_kind(self.source, line[0]);
                self.start_block(BlockId { kind, number: 0 }, self.span_of(line));
                self.discard = true;
                return;
            }
            Err(_) => {}
        }
        if self.current.is_none() && self.blocks.is_empty() {
            // Statements before any header, as forum posts and manuals show them: an FB until
            // the front end knows all files (so `NAME` and `DES` lines are read as in an FB).
            self.fragment = true;
            let id = BlockId {
                kind: mnemonics::BlockKind::Fb,
                number: 0,
            };
            self.start_block(id, self.span_of(line));
        }
        let in_block = match &self.current {
            Some(block) => matches!(block.body, BlockBody::Data(_)) || !self.ended,
            None => false,
        };
        if !in_block {
            if !self.outside_reported {
                self.outside_reported = true;
                self.errors.push(ParseError::OutsideBlock {
                    at: self.span_of(line),
                });
            }
            return;
        }
        let result = if matches!(
            self.current.as_ref().map(|b| &b.body),
            Some(BlockBody::Data(_))
        ) {
            self.data_line(line)
        } else {
            self.logic_line(line)
        };
        if let Err(error) = result {
            self.errors.push(error);
            self.end_on_bad_block_end(line);
            self.open_on_bad_bracket(line);
        }
    }

    /// A bad line that opens a bracket (`AN(`, `A( X`) still opens it, so its `)` is not
    /// reported as well: one error per bad bracket. The block has an error, so it never runs.
    fn open_on_bad_bracket(&mut self, line: &[Token]) {
        let context = self.context(self.set);
        let line = listing::without_address(context, line, self.listing);
        let opens = matches!(strip_label(line), [word, paren, ..]
            if word.kind == TokenKind::Word && paren.kind == TokenKind::LParen);
        let span = self.span_of(line);
        let Some(Block {
            body: BlockBody::Logic(body),
            ..
        }) = &mut self.current
        else {
            return;
        };
        if opens && !self.ended {
            body.statements.push(Statement {
                label: None,
                op: OpCode::AndBracket,
                op_span: span,
                operand: Operand::None,
                operand_span: span,
                call_params: Vec::new(),
                segment: self.segment,
                span,
            });
        }
    }

    /// `NAME :…`: the PG takes any characters in a block's name.
    /// A `NAME` line (any characters in the name) or a declaration line (the PG's legend
    /// `E/A/D/B/T/Z:` has slashes).
    fn is_name_line(&self, line: &[Token]) -> bool {
        let words = [
            mnemonics::NAME_WORD,
            mnemonics::DECLARATION_EN,
            mnemonics::DECLARATION_DE,
        ];
        matches!(line, [name, colon, ..]
            if colon.kind == TokenKind::Colon
                && words.iter().any(|word| name.text(self.source).eq_ignore_ascii_case(word)))
    }

    /// A `BE` line with something wrong after it still ends the block, so the error is not
    /// followed by a "block has no BE".
    fn end_on_bad_block_end(&mut self, line: &[Token]) {
        let Some(Block {
            body: BlockBody::Logic(body),
            ..
        }) = &mut self.current
        else {
            return;
        };
        let Some(&first) = strip_label(line).first() else {
            return;
        };
        let word = first.text(self.source);
        if mnemonics::operation(self.set, word).is_some_and(|info| info.op == OpCode::BlockEnd) {
            body.end = Some(first.span(self.file));
            self.ended = true;
        }
    }

    fn start_block(&mut self, id: BlockId, header: Span) {
        self.finish_block();
        let body = if id.kind.is_data() {
            BlockBody::Data(Vec::new())
        } else {
            BlockBody::Logic(LogicBody::default())
        };
        self.current = Some(Block { id, header, body });
        self.ended = false;
        self.outside_reported = false;
        self.next_data_word = 0;
        self.segment = 0;
    }

    fn finish_block(&mut self) {
        if let Some(block) = self.current.take()
            && !std::mem::take(&mut self.discard)
        {
            self.blocks.push(block);
        }
    }

    fn data_line(&mut self, line: &'a [Token]) -> Result<(), ParseError> {
        let (index, constant, span) =
            self.parse(line, line::data_word)
                .map_err(|error| match error {
                    ParseError::UnexpectedToken { at, expected, .. } => ParseError::BadDataWord {
                        at,
                        reason: format!("expected {expected}"),
                    },
                    other => other,
                })?;
        let index = index.unwrap_or(self.next_data_word);
        let values = 1 + constant.extra_words.len() as u16;
        self.next_data_word = index.saturating_add(values * constant.format.words());
        if let Some(Block {
            body: BlockBody::Data(words),
            ..
        }) = &mut self.current
        {
            words.push(DataWord {
                index,
                constant,
                span,
            });
        }
        Ok(())
    }

    fn logic_line(&mut self, line: &'a [Token]) -> Result<(), ParseError> {
        let context = self.context(self.set);
        let stripped = listing::without_address(context, line, self.listing);
        self.listing |= stripped.len() < line.len();
        let line = stripped;
        if let Ok((_, number)) = listing::segment_heading(context)(Tokens::new(line)) {
            self.segment = number;
            return Ok(());
        }
        if listing::segment_end(Tokens::new(line)).is_ok() || listing::empty_statement(line) {
            return Ok(());
        }
        let Some(Block {
            id,
            body: BlockBody::Logic(body),
            ..
        }) = &self.current
        else {
            return Ok(());
        };
        let input = Tokens::new(line);
        let header_phase = id.kind.is_function() && body.statements.is_empty();
        let after_fb_call = body.statements.last().is_some_and(|last| {
            matches!(last.op, OpCode::JumpUnconditional | OpCode::JumpConditional)
                && matches!(last.operand, Operand::Block(target) if target.kind.is_function())
        });
        if (header_phase || after_fb_call)
            && let Ok((_, name)) = line::name_line(context)(input)
        {
            if header_phase {
                self.logic_body().name = Some(name);
            }
            return Ok(());
        }
        if header_phase {
            match line::declaration(context)(input) {
                Ok((_, declaration)) => {
                    self.logic_body().params.push(declaration);
                    return Ok(());
                }
                Err(nom::Err::Failure(LineError {
                    diagnostic: Some(diagnostic),
                    ..
                })) => return Err(*diagnostic),
                Err(_) => {}
            }
        }
        if after_fb_call && let Ok(param) = self.parse(line, line::param_line) {
            if let Some(last) = self.logic_body().statements.last_mut() {
                last.call_params.push(param);
            }
            return Ok(());
        }
        let mut statement = self.parse(line, line::statement)?;
        statement.segment = self.segment;
        if statement.op == OpCode::BlockEnd {
            self.logic_body().end = Some(statement.op_span);
            self.ended = true;
        }
        self.logic_body().statements.push(statement);
        Ok(())
    }

    fn logic_body(&mut self) -> &mut LogicBody {
        match &mut self.current {
            Some(Block {
                body: BlockBody::Logic(body),
                ..
            }) => body,
            _ => unreachable!("logic lines are parsed only inside logic blocks"),
        }
    }

    /// Runs a line parser in the file's set and, when that fails, in the other set; success there
    /// records the first foreign word instead of failing the line.
    fn parse<T, P>(
        &mut self,
        line: &'a [Token],
        parser: impl Fn(Context<'a>) -> P,
    ) -> Result<T, ParseError>
    where
        P: Fn(Tokens<'a>) -> tokens::LineResult<'a, T>,
    {
        let run = |set: MnemonicSet| -> Result<T, LineError> {
            match parser(self.context(set))(Tokens::new(line)) {
                Ok((rest, value)) if rest.is_empty() => Ok(value),
                Ok((rest, _)) => Err(LineError::of(fail(rest, "end of line"))),
                Err(error) => Err(LineError::of(error)),
            }
        };
        match run(self.set) {
            Ok(value) => Ok(value),
            Err(error) => match run(self.set.other()) {
                Ok(value) => {
                    let at = self.error_span(&error, line);
                    self.foreign
                        .get_or_insert((at, in_operation_place(line, at.start)));
                    Ok(value)
                }
                Err(_) => Err(self.to_diagnostic(error, line)),
            },
        }
    }

    fn error_span(&self, error: &LineError, line: &[Token]) -> Span {
        match (&error.diagnostic, error.at) {
            (Some(diagnostic), _) => diagnostic.span(),
            (None, Some(token)) => token.span(self.file),
            (None, None) => {
                let last = line[line.len() - 1];
                Span {
                    file: self.file,
                    start: last.end,
                    end: last.end,
                }
            }
        }
    }

    fn to_diagnostic(&self, error: LineError, line: &[Token]) -> ParseError {
        let at = self.error_span(&error, line);
        match error.diagnostic {
            Some(diagnostic) => *diagnostic,
            None => ParseError::UnexpectedToken {
                found: describe(self.context(self.set), error.at),
                at,
                expected: if error.expected.is_empty() {
                    "a statement".to_string()
                } else {
                    error.expected.to_string()
                },
            },
        }
    }

    fn finish(mut self) -> ParsedFile {
        self.finish_block();
        if let Some((at, operation)) = self.foreign {
            let word = self.source[at.start as usize..at.end as usize].to_string();
            self.errors.push(ParseError::MixedMnemonics {
                help: equivalent(self.set, &word, operation),
                word,
                word_set: self.set.other().with_article(),
                file_set: self.set.name(),
                at,
                decided_by: self.decided_by,
            });
        }
        self.errors.sort_by_key(|error| error.span().start);
        ParsedFile {
            unit: SourceUnit {
                file: self.file,
                mnemonics: self.set,
                blocks: self.blocks,
            },
            errors: self.errors,
            fragment: self.fragment,
        }
    }
}

/// Whether the token at `start` stands where the operation of a line does: first, or right
/// after a label (`M001 :`).
fn in_operation_place(line: &[Token], start: u32) -> bool {
    match line.iter().position(|token| token.start == start) {
        Some(0) => true,
        Some(2) => line[1].kind == TokenKind::Colon,
        _ => false,
    }
}

/// "the German word is `U`" for an English word, and the other way round. `operation` tells
/// whether the word stands in the place of the operation (`I` is the English increment there,
/// and the English input area as an operand).
fn equivalent(file_set: MnemonicSet, word: &str, operation: bool) -> Option<String> {
    let other = file_set.other();
    let as_operation = operation
        .then(|| mnemonics::operation(other, word))
        .flatten()
        .map(|info| mnemonics::op_word(file_set, info.op));
    let as_area = (!operation)
        .then(|| mnemonics::area(other, word))
        .flatten()
        .map(|area| mnemonics::area_word(file_set, area));
    let Some(own) = as_operation.or(as_area) else {
        return Some(format!(
            "use {} mnemonics throughout the file, or pass `--mnemonics`",
            file_set.name()
        ));
    };
    Some(format!(
        "the {} word is `{own}`; a file uses one set throughout",
        file_set.name()
    ))
}

/// Convenience for tests and tools: parse text as file 0.
pub fn parse_text(source: &str) -> ParsedFile {
    parse_file(0, source, None)
}
