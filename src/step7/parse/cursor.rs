//! A position in the token list of a STEP 7 text, with the moves the parser makes: over blank
//! lines, to a statement's end, through a brace attribute block or a call's parameter list.

use crate::source::{FileId, Span};

use super::lexer::{Tok, Token};

pub struct Cursor<'t> {
    pub text: &'t str,
    tokens: &'t [Token],
    at: usize,
    file: FileId,
}

/// The text of the run of touching tokens that starts at `index` (an operation word such as
/// `A(`, `==I`, `+AR1`, `__ASSERT==`), up to a `;` or a line end.
pub fn run_text(text: &str, tokens: &[Token], index: usize) -> String {
    let mut end = index;
    while end + 1 < tokens.len()
        && tokens[end].touches(tokens[end + 1])
        && run_continues(tokens[end], tokens[end + 1])
    {
        end += 1;
    }
    text[tokens[index].start as usize..tokens[end].end as usize].to_ascii_uppercase()
}

/// Whether `next` belongs to the operation word `previous` ends: operators and letters join
/// (`==I`, `+AR1`, `RND+`, `A(`, `)MCR`); a `;`, a line end, a local or a literal do not.
fn run_continues(previous: Token, next: Token) -> bool {
    let joinable = |token: Token| {
        matches!(
            token.kind,
            Tok::Word | Tok::Operator | Tok::LParen | Tok::RParen | Tok::Number
        )
    };
    joinable(previous)
        && joinable(next)
        && !(previous.kind == Tok::Word && next.kind == Tok::Number)
}

impl<'t> Cursor<'t> {
    pub fn new(text: &'t str, tokens: &'t [Token], file: FileId) -> Self {
        Cursor {
            text,
            tokens,
            at: 0,
            file,
        }
    }

    pub fn span(&self, start: u32, end: u32) -> Span {
        Span {
            file: self.file,
            start,
            end: end.max(start),
        }
    }

    pub fn end_span(&self) -> Span {
        let end = self.text.len() as u32;
        self.span(end, end)
    }

    pub fn at_end(&self) -> bool {
        self.at >= self.tokens.len()
    }

    pub fn position(&self) -> u32 {
        self.peek().map_or(self.text.len() as u32, |t| t.start)
    }

    pub fn peek(&self) -> Option<Token> {
        self.tokens.get(self.at).copied()
    }

    pub fn peek_at(&self, ahead: usize) -> Option<Token> {
        self.tokens.get(self.at + ahead).copied()
    }

    pub fn peek_kind(&self) -> Option<Tok> {
        self.peek().map(|t| t.kind)
    }

    pub fn next(&mut self) -> Option<Token> {
        let token = self.peek()?;
        self.at += 1;
        Some(token)
    }

    pub fn previous_end(&self) -> u32 {
        self.at
            .checked_sub(1)
            .and_then(|i| self.tokens.get(i))
            .map_or(0, |t| t.end)
    }

    pub fn eat(&mut self, kind: Tok) -> bool {
        if self.peek_kind() == Some(kind) {
            self.at += 1;
            true
        } else {
            false
        }
    }

    /// The word at the cursor, if a word is there.
    pub fn word(&self) -> Option<String> {
        let token = self.peek()?;
        (token.kind == Tok::Word).then(|| token.text(self.text).to_string())
    }

    pub fn skip_blank(&mut self) {
        while matches!(self.peek_kind(), Some(Tok::Newline | Tok::Semicolon)) {
            self.at += 1;
        }
    }

    pub fn skip_line(&mut self) {
        while let Some(kind) = self.peek_kind() {
            self.at += 1;
            if kind == Tok::Newline {
                break;
            }
        }
    }

    /// Past the next `;` or line end.
    pub fn skip_statement(&mut self) {
        while let Some(kind) = self.peek_kind() {
            self.at += 1;
            if matches!(kind, Tok::Newline | Tok::Semicolon) {
                break;
            }
        }
    }

    /// Past a `{ … }` attribute block (it may span lines and hold `;`).
    pub fn skip_braces(&mut self) {
        let mut depth = 0;
        while let Some(kind) = self.peek_kind() {
            self.at += 1;
            match kind {
                Tok::LBrace => depth += 1,
                Tok::RBrace => {
                    depth -= 1;
                    if depth <= 0 {
                        break;
                    }
                }
                _ => {}
            }
        }
    }

    /// The byte extent of the current line's tokens.
    pub fn line_extent(&self) -> (u32, u32) {
        let start = self.position();
        let end = self.tokens[self.at.min(self.tokens.len())..]
            .iter()
            .take_while(|t| t.kind != Tok::Newline)
            .last()
            .map_or(start, |t| t.end);
        (start, end)
    }

    /// The byte extent from the cursor to the statement's end (`;` or line end).
    pub fn statement_extent(&self) -> (u32, u32) {
        let start = self.position();
        let end = self.tokens[self.at.min(self.tokens.len())..]
            .iter()
            .take_while(|t| !matches!(t.kind, Tok::Newline | Tok::Semicolon))
            .last()
            .map_or(start, |t| t.end);
        (start, end)
    }

    /// Whether some line starts with a word `matches` accepts.
    pub fn any_line_starts_with(&self, matches: impl Fn(&str) -> bool) -> bool {
        let mut at_start = true;
        for token in self.tokens {
            if token.kind == Tok::Newline {
                at_start = true;
                continue;
            }
            if at_start && token.kind == Tok::Word && matches(token.text(self.text)) {
                return true;
            }
            at_start = false;
        }
        false
    }

    /// The operation word: the run of touching tokens at the cursor, and where it ends.
    pub fn take_run(&mut self) -> (String, u32) {
        let word = run_text(self.text, self.tokens, self.at);
        let mut end = self.tokens[self.at].end;
        self.at += 1;
        while let Some(next) = self.peek() {
            let previous = self.tokens[self.at - 1];
            if previous.touches(next) && run_continues(previous, next) {
                end = next.end;
                self.at += 1;
            } else {
                break;
            }
        }
        (word, end)
    }

    /// A possibly negative integer.
    pub fn signed_number(&mut self) -> Option<i32> {
        let negative = self
            .peek()
            .is_some_and(|t| t.kind == Tok::Operator && t.text(self.text) == "-");
        if negative {
            self.at += 1;
        }
        let token = self.next()?;
        let value: i32 = token.text(self.text).parse().ok()?;
        Some(if negative { -value } else { value })
    }

    /// The comma-separated items up to the statement's end (initial values).
    pub fn comma_items(&mut self) -> Vec<(String, Span)> {
        let mut items = Vec::new();
        let mut depth = 0;
        let mut start: Option<u32> = None;
        let mut end = 0;
        while let Some(token) = self.peek() {
            match token.kind {
                Tok::Semicolon | Tok::Newline if depth == 0 => break,
                Tok::Comma if depth == 0 => {
                    if let Some(s) = start.take() {
                        items.push((
                            self.text[s as usize..end as usize].to_string(),
                            self.span(s, end),
                        ));
                    }
                    self.at += 1;
                    continue;
                }
                Tok::LParen => depth += 1,
                Tok::RParen => depth -= 1,
                _ => {}
            }
            start.get_or_insert(token.start);
            end = token.end;
            self.at += 1;
        }
        if let Some(s) = start {
            items.push((
                self.text[s as usize..end as usize].to_string(),
                self.span(s, end),
            ));
        }
        items
    }

    /// The call's target text (`FB 1, DB 1`) up to its `(`, `;` or line end.
    pub fn call_target(&mut self) -> (u32, u32) {
        let start = self.position();
        let mut end = start;
        while let Some(token) = self.peek() {
            if matches!(token.kind, Tok::LParen | Tok::Semicolon | Tok::Newline) {
                break;
            }
            end = token.end;
            self.at += 1;
        }
        (start, end)
    }

    /// The `NAME := operand` items of a parameter list, over lines, up to its `)`.
    pub fn call_items(&mut self) -> Vec<(String, Span)> {
        let mut items = Vec::new();
        let mut depth = 0;
        let mut start: Option<u32> = None;
        let mut end = 0;
        let (text, file) = (self.text, self.file);
        let flush = |start: &mut Option<u32>, end: u32, items: &mut Vec<(String, Span)>| {
            if let Some(s) = start.take() {
                let span = Span {
                    file,
                    start: s,
                    end,
                };
                items.push((text[s as usize..end as usize].to_string(), span));
            }
        };
        while let Some(token) = self.peek() {
            self.at += 1;
            match token.kind {
                Tok::RParen if depth == 0 => break,
                Tok::Comma if depth == 0 => {
                    flush(&mut start, end, &mut items);
                    continue;
                }
                Tok::Newline | Tok::Semicolon => continue,
                Tok::LParen | Tok::LBracket => depth += 1,
                Tok::RParen | Tok::RBracket => depth -= 1,
                _ => {}
            }
            start.get_or_insert(token.start);
            end = token.end;
        }
        flush(&mut start, end, &mut items);
        items
    }
}
