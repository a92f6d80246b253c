//! The STEP 7 parser: a source file as STEP 7 exports it (blocks with header lines,
//! interfaces, `BEGIN`, networks and statements, data blocks with their initial values), or a
//! file of bare statements, which is OB 1's body. Every error is kept and parsing goes on at
//! the next statement, declaration or line.

mod cursor;
pub mod error;
pub mod lexer;
pub mod literal;
mod operand;

use crate::ast::Name;
use crate::mnemonics::MnemonicSet;
use crate::source::{FileId, Span};
use crate::step7::ast::*;
use crate::step7::mnemonics;

use cursor::Cursor;
pub use error::S7ParseError;
use lexer::{Tok, Token};

#[derive(Debug, Clone, Copy, Default)]
pub struct ParseOptions {
    /// The mnemonic set, instead of detecting it.
    pub mnemonics: Option<MnemonicSet>,
    /// awlsim's test instructions (`__ASSERT==` …).
    pub extensions: bool,
}

#[derive(Debug)]
pub struct Parsed {
    pub unit: S7Unit,
    pub errors: Vec<S7ParseError>,
}

const BLOCK_WORDS: &[(&str, S7BlockKind, &str)] = &[
    (
        "ORGANIZATION_BLOCK",
        S7BlockKind::Ob,
        "END_ORGANIZATION_BLOCK",
    ),
    ("FUNCTION_BLOCK", S7BlockKind::Fb, "END_FUNCTION_BLOCK"),
    ("FUNCTION", S7BlockKind::Fc, "END_FUNCTION"),
    ("DATA_BLOCK", S7BlockKind::Db, "END_DATA_BLOCK"),
    ("TYPE", S7BlockKind::Udt, "END_TYPE"),
];

/// Parses one STEP 7 source file.
pub fn parse(file: FileId, text: &str, options: ParseOptions) -> Parsed {
    let tokens = lexer::lex(text);
    let set = options
        .mnemonics
        .unwrap_or_else(|| detect_set(text, &tokens));
    let mut parser = Parser {
        cursor: Cursor::new(text, &tokens, file),
        set,
        extensions: options.extensions,
        errors: Vec::new(),
    };
    let blocks = parser.file();
    Parsed {
        unit: S7Unit {
            file,
            mnemonics: set,
            blocks,
        },
        errors: parser.errors,
    }
}

/// The mnemonic set of the first statement word that only one set has; English if none.
fn detect_set(text: &str, tokens: &[Token]) -> MnemonicSet {
    let mut at_line_start = true;
    let mut index = 0;
    while index < tokens.len() {
        let token = tokens[index];
        if matches!(token.kind, Tok::Newline | Tok::Semicolon) {
            at_line_start = true;
            index += 1;
            continue;
        }
        if at_line_start {
            at_line_start = false;
            let word = cursor::run_text(text, tokens, index);
            for set in [MnemonicSet::English, MnemonicSet::German] {
                if mnemonics::only_in(&word, set) {
                    return set;
                }
            }
        }
        index += 1;
    }
    MnemonicSet::English
}

struct Parser<'t> {
    cursor: Cursor<'t>,
    set: MnemonicSet,
    extensions: bool,
    errors: Vec<S7ParseError>,
}

impl Parser<'_> {
    fn span(&self, start: u32, end: u32) -> Span {
        self.cursor.span(start, end)
    }

    fn syntax(&mut self, what: impl Into<String>, expected: impl Into<String>, at: Span) {
        self.errors.push(S7ParseError::Syntax {
            what: what.into(),
            expected: expected.into(),
            at,
        });
    }

    fn block_word(&self) -> Option<(S7BlockKind, &'static str)> {
        let word = self.cursor.word()?;
        BLOCK_WORDS
            .iter()
            .find(|(name, _, _)| name.eq_ignore_ascii_case(&word))
            .map(|(_, kind, end)| (*kind, *end))
    }

    fn file(&mut self) -> Vec<S7Block> {
        let has_blocks = self.cursor.any_line_starts_with(|word| {
            BLOCK_WORDS
                .iter()
                .any(|(name, _, _)| name.eq_ignore_ascii_case(word))
        });
        if !has_blocks {
            return self.flat().into_iter().collect();
        }
        let mut blocks = Vec::new();
        loop {
            self.cursor.skip_blank();
            if self.cursor.at_end() {
                break;
            }
            match self.block_word() {
                Some((kind, end)) => {
                    if let Some(block) = self.block(kind, end) {
                        blocks.push(block);
                    }
                }
                None => {
                    let (start, end) = self.cursor.line_extent();
                    let at = self.span(start, end);
                    self.syntax(
                        "a statement outside any block",
                        "expected ORGANIZATION_BLOCK, FUNCTION, FUNCTION_BLOCK, DATA_BLOCK or TYPE",
                        at,
                    );
                    self.cursor.skip_line();
                }
            }
        }
        blocks
    }

    /// A file of bare statements: OB 1.
    fn flat(&mut self) -> Option<S7Block> {
        self.cursor.skip_blank();
        if self.cursor.at_end() {
            return None;
        }
        let start = self.cursor.position();
        let statements = self.statements(None);
        let header = self.span(start, start);
        Some(S7Block {
            kind: S7BlockKind::Ob,
            name: S7BlockRef::Number {
                kind: S7BlockKind::Ob,
                number: 1,
            },
            header,
            return_type: None,
            interface: Vec::new(),
            body: S7Body::Logic(statements),
            end: None,
        })
    }

    fn block(&mut self, kind: S7BlockKind, end_word: &'static str) -> Option<S7Block> {
        let keyword = self.cursor.next()?;
        let name = self.block_name(kind);
        let mut return_type = None;
        if kind == S7BlockKind::Fc && self.cursor.eat(Tok::Colon) {
            let ty = self.data_type();
            return_type = ty.filter(|_| true);
        }
        let header_end = self.cursor.previous_end();
        let header = self.span(keyword.start, header_end);
        self.cursor.skip_line();
        let name = name.unwrap_or(S7BlockRef::Number { kind, number: 0 });
        let mut interface = Vec::new();
        let mut members = Vec::new();
        let mut instance_of = None;
        let mut began = false;
        let mut end = None;
        loop {
            self.cursor.skip_blank();
            if self.cursor.at_end() {
                break;
            }
            let Some(word) = self.cursor.word().map(|w| w.to_ascii_uppercase()) else {
                if self.cursor.peek_kind() == Some(Tok::LBrace) {
                    self.cursor.skip_braces();
                    continue;
                }
                if kind == S7BlockKind::Db && self.cursor.peek_kind() == Some(Tok::Symbol) {
                    let token = self.cursor.next()?;
                    let text = token.text(self.cursor.text).trim_matches('"').to_string();
                    instance_of = Some(S7BlockRef::Symbol(Name {
                        text,
                        span: self.span(token.start, token.end),
                    }));
                    self.cursor.skip_line();
                    continue;
                }
                let (start, stop) = self.cursor.line_extent();
                let at = self.span(start, stop);
                self.syntax(
                    "unexpected text in the block header",
                    "not a header line",
                    at,
                );
                self.cursor.skip_line();
                continue;
            };
            match word.as_str() {
                "TITLE" | "AUTHOR" | "FAMILY" | "NAME" | "VERSION" | "KNOW_HOW_PROTECT"
                | "STANDARD" | "UNLINKED" | "READ_ONLY" | "NON_RETAIN" | "CODE_VERSION1" => {
                    self.cursor.skip_line();
                }
                "VAR_INPUT" | "VAR_OUTPUT" | "VAR_IN_OUT" | "VAR" | "VAR_TEMP" => {
                    let var_kind = match word.as_str() {
                        "VAR_INPUT" => VarKind::Input,
                        "VAR_OUTPUT" => VarKind::Output,
                        "VAR_IN_OUT" => VarKind::InOut,
                        "VAR" => VarKind::Static,
                        _ => VarKind::Temp,
                    };
                    let token = self.cursor.next()?;
                    let span = self.span(token.start, token.end);
                    let vars = self.declarations("END_VAR");
                    interface.push(VarSection {
                        kind: var_kind,
                        vars,
                        span,
                    });
                }
                "STRUCT" => {
                    self.cursor.next();
                    members = self.declarations("END_STRUCT");
                    self.cursor.eat(Tok::Semicolon);
                }
                "FB" | "SFB" if kind == S7BlockKind::Db => {
                    let token = self.cursor.next()?;
                    let number = self.number_after();
                    let block_kind = if word == "FB" {
                        S7BlockKind::Fb
                    } else {
                        S7BlockKind::Sfb
                    };
                    match number {
                        Some(number) => {
                            instance_of = Some(S7BlockRef::Number {
                                kind: block_kind,
                                number,
                            })
                        }
                        None => {
                            let at = self.span(token.start, token.end);
                            self.syntax("an instance DB's FB needs its number", "`FB 1`", at);
                        }
                    }
                    self.cursor.skip_line();
                }
                "BEGIN" => {
                    self.cursor.next();
                    began = true;
                    break;
                }
                w if w == end_word => {
                    let token = self.cursor.next()?;
                    end = Some(self.span(token.start, token.end));
                    break;
                }
                w if w.starts_with("END_") || self.block_word().is_some() => break,
                _ if kind == S7BlockKind::Udt || kind == S7BlockKind::Db => {
                    let (start, stop) = self.cursor.line_extent();
                    let at = self.span(start, stop);
                    self.syntax(
                        "unexpected line before BEGIN",
                        "a header line, STRUCT or BEGIN",
                        at,
                    );
                    self.cursor.skip_line();
                }
                _ => {
                    // A logic block without BEGIN: its statements start here.
                    began = true;
                    break;
                }
            }
        }
        let body = match kind {
            S7BlockKind::Udt => S7Body::Type(members),
            S7BlockKind::Db => {
                let initial = if began {
                    self.assignments(end_word)
                } else {
                    Vec::new()
                };
                S7Body::Data {
                    instance_of,
                    members,
                    initial,
                }
            }
            _ => S7Body::Logic(if began {
                self.statements(Some(end_word))
            } else {
                Vec::new()
            }),
        };
        if began || end.is_none() {
            end = self.block_end(end_word);
        }
        if end.is_none() {
            self.errors.push(S7ParseError::UnclosedBlock {
                block: block_text(&name),
                end: end_word,
                at: header,
            });
        }
        Some(S7Block {
            kind,
            name,
            header,
            return_type,
            interface,
            body,
            end,
        })
    }

    /// The `END_…` line, if it comes next.
    fn block_end(&mut self, end_word: &str) -> Option<Span> {
        self.cursor.skip_blank();
        let word = self.cursor.word()?;
        if !word.eq_ignore_ascii_case(end_word) {
            return None;
        }
        let token = self.cursor.next()?;
        self.cursor.skip_line();
        Some(self.span(token.start, token.end))
    }

    fn number_after(&mut self) -> Option<u16> {
        let token = self.cursor.peek()?;
        if token.kind != Tok::Number {
            return None;
        }
        self.cursor.next();
        token.text(self.cursor.text).parse().ok()
    }

    /// `OB 1`, `FC1`, `"Name"`.
    fn block_name(&mut self, kind: S7BlockKind) -> Option<S7BlockRef> {
        let token = self.cursor.peek()?;
        let at = self.span(token.start, token.end);
        if token.kind == Tok::Symbol {
            self.cursor.next();
            return Some(S7BlockRef::Symbol(Name {
                text: token.text(self.cursor.text).trim_matches('"').to_string(),
                span: at,
            }));
        }
        let word = self.cursor.word()?.to_ascii_uppercase();
        self.cursor.next();
        let digits = word.trim_start_matches(|c: char| c.is_ascii_alphabetic());
        let letters = &word[..word.len() - digits.len()];
        let number = if digits.is_empty() {
            self.number_after()
        } else {
            digits.parse().ok()
        };
        if letters != kind.name() || number.is_none() {
            self.syntax(
                format!("a {} block needs its number", kind.name()),
                format!("write `{} 1`", kind.name()),
                at,
            );
            return None;
        }
        Some(S7BlockRef::Number {
            kind,
            number: number?,
        })
    }

    /// Declarations up to `end` (`END_VAR`, `END_STRUCT`).
    fn declarations(&mut self, end: &str) -> Vec<VarDecl> {
        let mut vars = Vec::new();
        loop {
            self.cursor.skip_blank();
            if self.cursor.at_end() {
                let at = self.cursor.end_span();
                self.syntax(
                    format!("the declarations have no `{end}`"),
                    format!("add `{end}`"),
                    at,
                );
                return vars;
            }
            if let Some(word) = self.cursor.word()
                && word.eq_ignore_ascii_case(end)
            {
                self.cursor.next();
                if end == "END_VAR" {
                    self.cursor.skip_line();
                }
                return vars;
            }
            if self.block_word().is_some()
                || self
                    .cursor
                    .word()
                    .is_some_and(|w| w.eq_ignore_ascii_case("BEGIN"))
            {
                let at = self.cursor.end_span();
                self.syntax(
                    format!("the declarations have no `{end}`"),
                    format!("add `{end}`"),
                    at,
                );
                return vars;
            }
            match self.declaration() {
                Some(var) => vars.push(var),
                None => self.cursor.skip_statement(),
            }
        }
    }

    /// `name [{…}] : TYPE [:= value] ;`
    fn declaration(&mut self) -> Option<VarDecl> {
        let token = self.cursor.peek()?;
        if token.kind != Tok::Word {
            let at = self.span(token.start, token.end);
            self.syntax(
                "a declaration starts with a name",
                "expected `name : TYPE;`",
                at,
            );
            return None;
        }
        self.cursor.next();
        let name = Name {
            text: token.text(self.cursor.text).to_string(),
            span: self.span(token.start, token.end),
        };
        if self.cursor.peek_kind() == Some(Tok::LBrace) {
            self.cursor.skip_braces();
        }
        if !self.cursor.eat(Tok::Colon) {
            let at = name.span;
            self.syntax(
                format!("`{}` needs its type", name.text),
                "expected `: TYPE`",
                at,
            );
            return None;
        }
        let ty = self.data_type()?;
        let mut initial = Vec::new();
        if self.cursor.eat(Tok::Assign) {
            initial = self.initial_values();
        }
        let end = self.cursor.previous_end();
        self.cursor.eat(Tok::Semicolon);
        Some(VarDecl {
            name: name.clone(),
            ty,
            initial,
            span: self.span(token.start, end),
        })
    }

    /// `1, 2, 3 (0)` up to `;`.
    fn initial_values(&mut self) -> Vec<S7Constant> {
        let mut values = Vec::new();
        for (text, at) in self.cursor.comma_items() {
            if let Some((count, inner)) = text.split_once('(')
                && let Ok(count) = count.trim().parse::<usize>()
            {
                match literal::parse(inner.trim_end_matches(')').trim()) {
                    Ok(value) => values.extend(std::iter::repeat_n(value, count)),
                    Err(problem) => self.errors.push(S7ParseError::BadConstant { problem, at }),
                }
                continue;
            }
            match literal::parse(&text) {
                Ok(value) => values.push(value),
                Err(problem) => self.errors.push(S7ParseError::BadConstant { problem, at }),
            }
        }
        values
    }

    fn data_type(&mut self) -> Option<DataType> {
        let token = self.cursor.peek()?;
        let at = self.span(token.start, token.end);
        let Some(word) = self.cursor.word() else {
            self.syntax("a data type", "expected BOOL, INT, STRUCT …", at);
            return None;
        };
        let word = word.to_ascii_uppercase();
        self.cursor.next();
        Some(match word.as_str() {
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
            "VOID" => return None,
            "STRING" => {
                let mut length = 254;
                if self.cursor.eat(Tok::LBracket) {
                    length = self.number_after().unwrap_or(254).min(254) as u8;
                    self.cursor.eat(Tok::RBracket);
                }
                DataType::String(length)
            }
            "ARRAY" => return self.array(at),
            "STRUCT" => {
                let members = self.declarations("END_STRUCT");
                DataType::Struct(members)
            }
            "UDT" | "FB" | "SFB" => {
                let Some(number) = self.number_after() else {
                    self.syntax(
                        format!("`{word}` needs its number"),
                        format!("`{word} 1`"),
                        at,
                    );
                    return None;
                };
                match word.as_str() {
                    "UDT" => DataType::Udt(number),
                    "FB" => DataType::Instance(S7BlockKind::Fb, number),
                    _ => DataType::Instance(S7BlockKind::Sfb, number),
                }
            }
            other => {
                let digits = other.trim_start_matches(|c: char| c.is_ascii_alphabetic());
                let letters = &other[..other.len() - digits.len()];
                match (letters, digits.parse::<u16>()) {
                    ("UDT", Ok(number)) => DataType::Udt(number),
                    ("FB", Ok(number)) => DataType::Instance(S7BlockKind::Fb, number),
                    ("SFB", Ok(number)) => DataType::Instance(S7BlockKind::Sfb, number),
                    _ => {
                        self.syntax(
                            format!("`{other}` is no STEP 7 data type"),
                            "unknown type",
                            at,
                        );
                        return None;
                    }
                }
            }
        })
    }

    /// `ARRAY [1..10, 0..3] OF T`
    fn array(&mut self, at: Span) -> Option<DataType> {
        if !self.cursor.eat(Tok::LBracket) {
            self.syntax(
                "an ARRAY needs its bounds",
                "write `ARRAY [1..10] OF INT`",
                at,
            );
            return None;
        }
        let mut dims = Vec::new();
        loop {
            let low = self.cursor.signed_number()?;
            if !self.cursor.eat(Tok::Range) {
                self.syntax("array bounds are written `low..high`", "expected `..`", at);
                return None;
            }
            let high = self.cursor.signed_number()?;
            dims.push((low, high));
            if !self.cursor.eat(Tok::Comma) {
                break;
            }
        }
        self.cursor.eat(Tok::RBracket);
        if !self
            .cursor
            .word()
            .is_some_and(|w| w.eq_ignore_ascii_case("OF"))
        {
            self.syntax(
                "an ARRAY needs `OF` and the element type",
                "expected `OF`",
                at,
            );
            return None;
        }
        self.cursor.next();
        let element = self.data_type()?;
        Some(DataType::Array {
            dims,
            element: Box::new(element),
        })
    }

    /// `name := value;` lines of a DB up to `END_DATA_BLOCK`.
    fn assignments(&mut self, end: &str) -> Vec<InitialValue> {
        let mut values = Vec::new();
        loop {
            self.cursor.skip_blank();
            if self.cursor.at_end()
                || self
                    .cursor
                    .word()
                    .is_some_and(|w| w.eq_ignore_ascii_case(end))
            {
                return values;
            }
            if self.block_word().is_some() {
                return values;
            }
            let (start, stop) = self.cursor.statement_extent();
            let text = &self.cursor.text[start as usize..stop as usize];
            let span = self.span(start, stop);
            self.cursor.skip_statement();
            let Some((path_text, value_text)) = text.split_once(":=") else {
                self.syntax(
                    "an initial value is written `name := value;`",
                    "expected `:=`",
                    span,
                );
                continue;
            };
            let path = match member_path(path_text.trim(), span) {
                Ok(path) => path,
                Err(problem) => {
                    self.syntax(problem, "not a member", span);
                    continue;
                }
            };
            match literal::parse(value_text.trim()) {
                Ok(value) => values.push(InitialValue { path, value, span }),
                Err(problem) => self
                    .errors
                    .push(S7ParseError::BadConstant { problem, at: span }),
            }
        }
    }

    /// Statements up to `end` (or the end of the file).
    fn statements(&mut self, end: Option<&str>) -> Vec<S7Statement> {
        let mut statements = Vec::new();
        let mut network = 0u16;
        loop {
            self.cursor.skip_blank();
            if self.cursor.at_end() {
                return statements;
            }
            if let Some(word) = self.cursor.word().map(|w| w.to_ascii_uppercase()) {
                if end.is_some_and(|end| end == word) || self.block_word().is_some() {
                    return statements;
                }
                if word == "NETWORK" {
                    network += 1;
                    self.cursor.skip_line();
                    continue;
                }
                if word == "TITLE"
                    && self
                        .cursor
                        .peek_at(1)
                        .is_some_and(|t| t.kind == Tok::Operator)
                {
                    self.cursor.skip_line();
                    continue;
                }
            }
            if let Some(statement) = self.statement(network) {
                statements.push(statement);
            }
        }
    }

    fn statement(&mut self, network: u16) -> Option<S7Statement> {
        let first = self.cursor.peek()?;
        let mut label = None;
        if first.kind == Tok::Word && self.cursor.peek_at(1).is_some_and(|t| t.kind == Tok::Colon) {
            self.cursor.next();
            self.cursor.next();
            label = Some(Name {
                text: first.text(self.cursor.text).to_string(),
                span: self.span(first.start, first.end),
            });
            // A label alone on its line labels the next statement.
            if matches!(self.cursor.peek_kind(), Some(Tok::Newline) | None) {
                self.cursor.skip_blank();
            }
        }
        let op_start = self.cursor.peek()?;
        let (word, op_end) = self.cursor.take_run();
        let op_span = self.span(op_start.start, op_end);
        let Some(op) = self.operation(&word, op_span) else {
            self.cursor.skip_statement();
            return None;
        };
        if op == S7Op::Call {
            return self.call(label, op_span, network);
        }
        let (start, stop) = self.cursor.statement_extent();
        let operand_text = &self.cursor.text[start as usize..stop as usize];
        let operand_span = if stop > start {
            self.span(start, stop)
        } else {
            self.span(op_end, op_end)
        };
        self.cursor.skip_statement();
        let statement_span = self.span(
            label.as_ref().map_or(op_start.start, |l| l.span.start),
            stop.max(op_end),
        );
        let (op, operand) = self.operand(op, operand_text, operand_span, &word)?;
        Some(S7Statement {
            label,
            op,
            op_span,
            operand,
            operand_span,
            call: None,
            network,
            span: statement_span,
        })
    }

    /// The operation `word` names, or an error.
    fn operation(&mut self, word: &str, at: Span) -> Option<S7Op> {
        let upper = word.to_ascii_uppercase();
        if let Some(op) = mnemonics::lookup(&upper, self.set) {
            if is_extension(op) && !self.extensions {
                self.errors.push(S7ParseError::ExtensionNotEnabled {
                    word: word.into(),
                    at,
                });
                return None;
            }
            return Some(op);
        }
        if let Some(op) = mnemonics::lookup(&upper, self.set.other()) {
            self.errors.push(S7ParseError::MixedMnemonics {
                word: word.into(),
                other: self.set.other().with_article(),
                set: self.set.name(),
                suggestion: mnemonics::word(op, self.set).into(),
                at,
            });
            return None;
        }
        if let Some(help) = step5_operation(&upper) {
            self.errors.push(S7ParseError::Step5Spelling {
                word: word.into(),
                at,
                help: help.into(),
            });
            return None;
        }
        let suggestions = mnemonics::suggestions(&upper, self.set);
        self.errors.push(S7ParseError::UnknownOperation {
            word: word.into(),
            at,
            set: self.set.name(),
            help: (!suggestions.is_empty())
                .then(|| format!("did you mean {}?", quoted_list(&suggestions))),
        });
        None
    }

    /// The operand of `op`; `L STW`/`T STW` become their own operations.
    fn operand(&mut self, op: S7Op, text: &str, at: Span, word: &str) -> Option<(S7Op, S7Operand)> {
        let upper = text.trim().to_ascii_uppercase();
        match (op, upper.as_str()) {
            (S7Op::Load, "STW") => return Some((S7Op::LoadStatusWord, S7Operand::None)),
            (S7Op::Transfer, "STW") => return Some((S7Op::TransferStatusWord, S7Operand::None)),
            _ => {}
        }
        if let Some(help) = step5_operand(&upper) {
            self.errors.push(S7ParseError::Step5Spelling {
                word: text.trim().into(),
                at,
                help: help.into(),
            });
            return None;
        }
        let written = operand::Written {
            text,
            span: at,
            set: self.set,
            extensions: self.extensions,
        };
        let op = match (op, &upper) {
            (S7Op::OpenDb, u) if u.starts_with("DI") && !u.starts_with("DIX") => {
                S7Op::OpenInstanceDb
            }
            _ => op,
        };
        match operand::parse(op, &written) {
            Ok(operand) => Some((op, operand)),
            Err(problem) if operand::looks_constant(&upper) => {
                self.errors.push(S7ParseError::BadConstant { problem, at });
                None
            }
            Err(problem) => {
                self.errors.push(S7ParseError::BadOperand {
                    text: text.trim().into(),
                    op: word.into(),
                    at,
                    problem,
                    help: None,
                });
                None
            }
        }
    }

    /// `CALL FB 1, DB 1 (IN := …, OUT := …)`
    fn call(&mut self, label: Option<Name>, op_span: Span, network: u16) -> Option<S7Statement> {
        let (start, _) = self.cursor.statement_extent();
        let target = self.cursor.call_target();
        let target_text = &self.cursor.text[target.0 as usize..target.1 as usize];
        let target_span = self.span(target.0, target.1);
        let (block_text, instance_text) = match target_text.split_once(',') {
            Some((block, instance)) => (block.trim(), Some(instance.trim())),
            None => (target_text.trim(), None),
        };
        let block = self.block_reference(block_text, target_span)?;
        let mut multi_instance = None;
        if let S7Operand::Local(path) = &block
            && let Some(PathPart::Member(name)) = path.first()
        {
            multi_instance = Some(name.clone());
        }
        let block_ref = match &block {
            S7Operand::Block(reference) => reference.clone(),
            S7Operand::Symbol { name, .. } => S7BlockRef::Symbol(name.clone()),
            _ => S7BlockRef::Number {
                kind: S7BlockKind::Fb,
                number: 0,
            },
        };
        let instance = match instance_text {
            Some(text) => match self.block_reference(text, target_span)? {
                S7Operand::Block(reference) => Some(reference),
                S7Operand::Symbol { name, .. } => Some(S7BlockRef::Symbol(name)),
                _ => None,
            },
            None => None,
        };
        let mut params = Vec::new();
        let mut stop = target.1;
        if self.cursor.eat(Tok::LParen) {
            for (text, at) in self.cursor.call_items() {
                stop = at.end;
                let Some((name, actual)) = text.split_once(":=") else {
                    self.syntax(
                        "a parameter is written `NAME := operand`",
                        "expected `:=`",
                        at,
                    );
                    continue;
                };
                let name_text = name.trim();
                let actual_text = actual.trim();
                let offset = text.find(actual_text).unwrap_or(0) as u32;
                let actual_span = Span {
                    file: at.file,
                    start: at.start + offset,
                    end: at.end,
                };
                let written = operand::Written {
                    text: actual_text,
                    span: actual_span,
                    set: self.set,
                    extensions: self.extensions,
                };
                match operand::parse(S7Op::Load, &written) {
                    Ok(actual) => params.push(CallParam {
                        name: Name {
                            text: name_text.to_string(),
                            span: Span {
                                file: at.file,
                                start: at.start,
                                end: at.start + name_text.len() as u32,
                            },
                        },
                        actual,
                        actual_span,
                        span: at,
                    }),
                    Err(problem) => self.errors.push(S7ParseError::BadOperand {
                        text: actual_text.into(),
                        op: format!("CALL ({name_text})"),
                        at: actual_span,
                        problem,
                        help: None,
                    }),
                }
            }
        }
        self.cursor.skip_statement();
        Some(S7Statement {
            label,
            op: S7Op::Call,
            op_span,
            operand: S7Operand::Block(block_ref.clone()),
            operand_span: target_span,
            call: Some(CallSpec {
                block: block_ref,
                instance,
                multi_instance,
                params,
            }),
            network,
            span: self.span(op_span.start.min(start), stop),
        })
    }

    fn block_reference(&mut self, text: &str, at: Span) -> Option<S7Operand> {
        let written = operand::Written {
            text,
            span: at,
            set: self.set,
            extensions: self.extensions,
        };
        match operand::parse(S7Op::Call, &written) {
            Ok(
                operand @ (S7Operand::Block(_) | S7Operand::Symbol { .. } | S7Operand::Local(_)),
            ) => Some(operand),
            _ => {
                self.syntax(
                    format!("`{text}` is no block to call"),
                    "expected FC n, FB n, DB n, SFC n, \"name\" or #instance",
                    at,
                );
                None
            }
        }
    }
}

fn is_extension(op: S7Op) -> bool {
    matches!(
        op,
        S7Op::Assert(_) | S7Op::ResetStatusWord | S7Op::Sleep | S7Op::Feature
    )
}

fn quoted_list(words: &[&str]) -> String {
    words
        .iter()
        .map(|w| format!("`{w}`"))
        .collect::<Vec<_>>()
        .join(" or ")
}

fn block_text(name: &S7BlockRef) -> String {
    match name {
        S7BlockRef::Number { kind, number } => format!("{} {number}", kind.name()),
        S7BlockRef::Symbol(name) => format!("\"{}\"", name.text),
    }
}

/// STEP 5 operations STEP 7 does not have, with the STEP 7 way.
fn step5_operation(word: &str) -> Option<&'static str> {
    Some(match word {
        "JU" | "SPA" => return None,
        "DO" => "STEP 7 has no `DO`: use memory-indirect addressing, `L MW [MD 10]`",
        "C" => "STEP 5's `C DB n` is `OPN DB n` (German `AUF DB n`) in STEP 7",
        "TNB" | "TIR" | "LIR" => "STEP 7 copies blocks with SFC 20 `BLKMOV`",
        "ADD" => "STEP 7 adds a constant with `+ 5` or `+ L#5`",
        "+F" | "-F" | "XF" | ":F" => "STEP 7 writes `+I`, `-I`, `*I`, `/I`",
        "+G" | "-G" | "XG" | ":G" => "STEP 7 writes REAL arithmetic `+R`, `-R`, `*R`, `/R`",
        "DES" | "BEZ" => "STEP 7 declares parameters in `VAR_INPUT` … `END_VAR`",
        "BEB" | "BEA" => return None,
        _ => return None,
    })
}

/// STEP 5 operand spellings, with the STEP 7 one.
fn step5_operand(upper: &str) -> Option<&'static str> {
    let (letters, rest) = {
        let at = upper
            .find(|c: char| !c.is_ascii_alphabetic())
            .unwrap_or(upper.len());
        (&upper[..at], upper[at..].trim_start())
    };
    let numbered = rest.starts_with(|c: char| c.is_ascii_digit() || c == '+' || c == '-');
    if !numbered && !matches!(letters, "PB" | "SB") {
        return None;
    }
    Some(match letters {
        "PB" | "SB" => "STEP 7 has no PB or SB: call an FC (`CALL FC 3`)",
        "KF" => "a STEP 7 integer constant is written plainly: `L 5` (`L#5` for 32 bits)",
        "KH" => "a STEP 7 hexadecimal constant is written `W#16#00FF`",
        "KT" => "a STEP 7 time constant is written `S5T#5S`",
        "KC" => "a STEP 7 count is written `C#5`",
        "KM" => "a STEP 7 bit pattern is written `2#0000_0000_0000_0000`",
        "KY" => "two bytes are written `B#(1, 2)` in STEP 7",
        "KG" => "a STEP 7 REAL is written `1.5` or `1.5e3`",
        "DW" => "STEP 7 addresses data blocks by byte: data word n is `DBW 2n`",
        "DL" | "DR" => "STEP 7 addresses data blocks by byte: `DBB`",
        "D" => "a data bit is `DBX n.m` in STEP 7",
        "F" | "FY" | "FW" | "FD" => "STEP 7 writes flags (memory) `M`, `MB`, `MW`, `MD`",
        "PY" => "a peripheral byte is `PIB`/`PQB` in STEP 7",
        _ => return None,
    })
}

/// `a.b[1, 2]` in a DB's initial values.
fn member_path(text: &str, span: Span) -> Result<Vec<PathPart>, String> {
    let end = text.find(['.', '[']).unwrap_or(text.len());
    let first = text[..end].trim();
    if first.is_empty() {
        return Err("a name before `:=`".into());
    }
    let name = |text: &str| Name {
        text: text.to_string(),
        span,
    };
    let mut parts = vec![PathPart::Member(name(first))];
    let mut rest = &text[end..];
    while !rest.is_empty() {
        if let Some(after) = rest.strip_prefix('.') {
            let end = after.find(['.', '[']).unwrap_or(after.len());
            parts.push(PathPart::Member(name(after[..end].trim())));
            rest = &after[end..];
        } else if let Some(after) = rest.strip_prefix('[') {
            let close = after.find(']').ok_or("a `]` after the index")?;
            let indexes: Result<Vec<i32>, _> = after[..close]
                .split(',')
                .map(|i| i.trim().parse())
                .collect();
            parts.push(PathPart::Index(
                indexes.map_err(|_| "constant indexes only")?,
            ));
            rest = &after[close + 1..];
        } else {
            return Err(format!("`{rest}` after the name"));
        }
    }
    Ok(parts)
}
