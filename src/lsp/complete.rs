//! Completion: at an operation's place the operations of the file's mnemonic set, at an
//! operand's place the program's symbols, the enclosing block's variables and labels, the data
//! blocks' members and the blocks.

use std::ops::Range;

use crate::ast::{BlockBody, SourceUnit};
use crate::dialect::Dialect;
use crate::frontend::Frontend;
use crate::lsp::text::{FileLanguage, LineIndex, Position};
use crate::mnemonics::{self, MnemonicSet};
use crate::source::{FileId, SourceFile, Span};
use crate::step7::ast::{S7Block, S7BlockRef, S7Body, S7Unit};
use crate::step7::mnemonics as s7_mnemonics;
use crate::symbols::Symbols;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CompletionKind {
    Operation,
    Symbol,
    Variable,
    Member,
    Block,
    Label,
}

#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Completion {
    /// What is inserted: `JU`, `-START`, `=EIN`, `#speed`, `"Data".level`, `PB 3`, `M001`.
    pub label: String,
    pub kind: CompletionKind,
    pub detail: String,
}

/// A name the program declares; `scope` is the byte range of the block it belongs to (`None`:
/// the whole program).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Named {
    pub name: String,
    pub detail: String,
    pub scope: Option<Range<usize>>,
}

/// What the program around a document declares, as the front end read it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct CompletionContext {
    pub language: FileLanguage,
    pub symbols: Vec<Named>,
    /// Formal operands of FBs (`=EIN`), STEP 7 interface variables (`#speed`).
    pub variables: Vec<Named>,
    /// Members of STEP 7 data blocks with a symbol: `"Tank".level`.
    pub db_members: Vec<Named>,
    pub blocks: Vec<Named>,
    pub labels: Vec<Named>,
}

impl CompletionContext {
    /// The context of file `file` of a built program.
    pub fn from_frontend(frontend: &Frontend, file: FileId) -> CompletionContext {
        let language = FileLanguage::of(frontend, file);
        let mut context = CompletionContext {
            language,
            symbols: symbols(frontend, language.mnemonics),
            variables: Vec::new(),
            db_members: Vec::new(),
            blocks: Vec::new(),
            labels: Vec::new(),
        };
        let Some(source) = frontend.sources.files.get(file as usize) else {
            return context;
        };
        for unit in &frontend.units {
            context.add_step5(unit, source, unit.file == file);
        }
        for unit in &frontend.s7_units {
            let symbols = &frontend.compiled.program.symbols;
            context.add_step7(unit, source, unit.file == file, symbols);
        }
        context
    }

    fn add_step5(&mut self, unit: &SourceUnit, source: &SourceFile, own: bool) {
        let scopes = scopes(unit.blocks.iter().map(|b| b.header), source.text.len());
        for (block, scope) in unit.blocks.iter().zip(scopes) {
            let BlockBody::Logic(body) = &block.body else {
                self.blocks
                    .push(named(block.id.to_string(), "data block", None));
                continue;
            };
            let name = body.name.as_ref().map_or("", |name| name.text.as_str());
            self.blocks.push(named(block.id.to_string(), name, None));
            if !own {
                continue;
            }
            for param in &body.params {
                let declared = source.slice(param.span).trim();
                self.variables.push(named(
                    format!("={}", param.name.text),
                    declared,
                    scope.clone(),
                ));
            }
            for label in body.statements.iter().filter_map(|s| s.label.as_ref()) {
                let detail = format!("label in {}", block.id);
                self.labels
                    .push(named(label.text.clone(), &detail, scope.clone()));
            }
        }
    }

    fn add_step7(&mut self, unit: &S7Unit, source: &SourceFile, own: bool, symbols: &Symbols) {
        let scopes = scopes(unit.blocks.iter().map(|b| b.header), source.text.len());
        for (block, scope) in unit.blocks.iter().zip(scopes) {
            let written = block.name.written();
            let header = if own {
                source.slice(block.header).trim().to_string()
            } else {
                String::new()
            };
            self.blocks.push(named(written.clone(), &header, None));
            if let (S7Body::Data { members, .. }, Some(symbol)) =
                (&block.body, symbol_of(block, &written, symbols))
            {
                for member in members {
                    let detail = if own {
                        source.slice(member.span).trim()
                    } else {
                        ""
                    };
                    let path = format!("{symbol}.{}", member.name.text);
                    self.db_members.push(named(path, detail, None));
                }
            }
            if !own {
                continue;
            }
            for var in block.interface.iter().flat_map(|section| &section.vars) {
                let declared = source.slice(var.span).trim();
                self.variables.push(named(
                    format!("#{}", var.name.text),
                    declared,
                    scope.clone(),
                ));
            }
            if let S7Body::Logic(statements) = &block.body {
                for label in statements.iter().filter_map(|s| s.label.as_ref()) {
                    let detail = format!("label in {written}");
                    self.labels
                        .push(named(label.text.clone(), &detail, scope.clone()));
                }
            }
        }
    }
}

fn named(name: String, detail: &str, scope: Option<Range<usize>>) -> Named {
    Named {
        name,
        detail: detail.to_string(),
        scope,
    }
}

/// Each block's scope: from its header to the next block's, the last one's to `end`.
fn scopes(headers: impl Iterator<Item = Span>, end: usize) -> Vec<Option<Range<usize>>> {
    let starts: Vec<usize> = headers.map(|header| header.start as usize).collect();
    let ends = starts.iter().skip(1).copied().chain([end]);
    starts
        .iter()
        .zip(ends)
        .map(|(&start, end)| Some(start..end))
        .collect()
}

/// A data block as a member access writes it, `"Tank"`: members are reached by the block's
/// symbol only (`DB 1.level` is no STL).
fn symbol_of(block: &S7Block, written: &str, symbols: &Symbols) -> Option<String> {
    match &block.name {
        S7BlockRef::Symbol(_) => Some(written.to_string()),
        S7BlockRef::Number { .. } => symbols.written_of(written),
    }
}

fn symbols(frontend: &Frontend, set: MnemonicSet) -> Vec<Named> {
    frontend
        .compiled
        .program
        .symbols
        .entries()
        .iter()
        .map(|entry| {
            let operand = entry.operand_text(set).unwrap_or_default();
            let detail = if entry.comment.is_empty() {
                operand
            } else {
                format!("{operand} — {}", entry.comment)
            };
            named(entry.written(), &detail, None)
        })
        .collect()
}

/// The completions at `position` of `text`.
pub fn completions(text: &str, position: Position, context: &CompletionContext) -> Vec<Completion> {
    let offset = LineIndex::new(text).offset(position);
    let line_start = text[..offset].rfind('\n').map_or(0, |at| at + 1);
    let before = &text[line_start..offset];
    if in_comment(before, context.language.dialect) {
        return Vec::new();
    }
    let typed = typed_word(before);
    let lead = &before[..before.len() - typed.len()];
    let mut items = if at_operation_place(lead, context.language.dialect) {
        operations(context.language)
    } else {
        operands(context, offset)
    };
    items.retain(|item| starts_with_ignoring_case(&item.label, typed));
    items
}

fn starts_with_ignoring_case(label: &str, typed: &str) -> bool {
    label
        .get(..typed.len())
        .is_some_and(|head| head.eq_ignore_ascii_case(typed))
}

fn in_comment(before: &str, dialect: Dialect) -> bool {
    let outside_quotes = |mark: &str| {
        before
            .find(mark)
            .is_some_and(|at| before[..at].matches('\'').count().is_multiple_of(2))
    };
    outside_quotes("//") || (dialect == Dialect::Step5 && outside_quotes(";"))
}

/// The part of a name typed before the cursor: `-STA`, `#sp`, `"Da`, `=EI`, `JU`.
fn typed_word(before: &str) -> &str {
    let start = before
        .char_indices()
        .rev()
        .take_while(|(_, c)| c.is_alphanumeric() || matches!(c, '_' | '-' | '#' | '=' | '"' | '.'))
        .last()
        .map_or(before.len(), |(at, _)| at);
    &before[start..]
}

/// Whether only an address, a label and `:` stand before the cursor (STEP 7: and the statement
/// before it, ended by `;`).
fn at_operation_place(lead: &str, dialect: Dialect) -> bool {
    let lead = match dialect {
        Dialect::Step7 => lead.rsplit(';').next().unwrap_or(lead),
        Dialect::Step5 => lead,
    };
    let lead = lead.trim();
    let after_colon = lead.rsplit(':').next().unwrap_or("").trim();
    if !after_colon.is_empty() {
        return false;
    }
    // `0004 M001 :`, `M001:`, `:`: at most an address and a label before the colon.
    lead.split_whitespace().count() <= 3
}

fn operations(language: FileLanguage) -> Vec<Completion> {
    let set = language.mnemonics;
    match language.dialect {
        Dialect::Step5 => mnemonics::OPERATIONS
            .iter()
            .map(|info| Completion {
                label: mnemonics::op_word(set, info.op).to_string(),
                kind: CompletionKind::Operation,
                detail: if info.supplementary {
                    format!("{} (function blocks only)", info.summary)
                } else {
                    info.summary.to_string()
                },
            })
            .collect(),
        Dialect::Step7 => {
            let mut words: Vec<&str> = s7_mnemonics::operation_words(set).collect();
            words.sort_unstable();
            words.dedup();
            words
                .into_iter()
                .map(|word| Completion {
                    label: word.to_string(),
                    kind: CompletionKind::Operation,
                    detail: format!("STEP 7 operation ({})", set.name()),
                })
                .collect()
        }
    }
}

fn operands(context: &CompletionContext, offset: usize) -> Vec<Completion> {
    let in_scope = |named: &&Named| {
        named
            .scope
            .as_ref()
            .is_none_or(|scope| scope.contains(&offset))
    };
    let groups = [
        (&context.labels, CompletionKind::Label),
        (&context.variables, CompletionKind::Variable),
        (&context.symbols, CompletionKind::Symbol),
        (&context.db_members, CompletionKind::Member),
        (&context.blocks, CompletionKind::Block),
    ];
    groups
        .into_iter()
        .flat_map(|(names, kind)| {
            names.iter().filter(in_scope).map(move |named| Completion {
                label: named.name.clone(),
                kind,
                detail: named.detail.clone(),
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::frontend::{Language, build_text_with};

    fn context(text: &str) -> CompletionContext {
        let language = Language::default();
        let mut sources = crate::source::SourceSet::default();
        sources.add(SourceFile::new("t.awl", text)).unwrap();
        let profile = crate::frontend::default_profile(&sources, language);
        CompletionContext::from_frontend(&build_text_with("t.awl", text, language, profile), 0)
    }

    /// The labels offered with the cursor at `|` in `marked`.
    fn offered(marked: &str) -> Vec<String> {
        let at = marked.find('|').unwrap();
        let text = marked.replace('|', "");
        let position = LineIndex::new(&text).position(at);
        completions(&text, position, &context(&text))
            .into_iter()
            .map(|item| item.label)
            .collect()
    }

    const GERMAN_FB: &str = "OB 1\n      SPA FB 1\nNAME :MOTOR\nEIN  :E 0.0\n      BE\nFB 1\nNAME :MOTOR\nBEZ :EIN  E BI\nM001 :U =EIN\n      SPB =M001\n      BE\n";

    #[test]
    fn operations_of_the_files_set() {
        let text = GERMAN_FB.replace("M001 :U =EIN", "M001 :S|");
        let words = offered(&text);
        assert!(words.contains(&"SPA".to_string()), "{words:?}");
        assert!(words.contains(&"SPB".to_string()));
        assert!(!words.contains(&"JU".to_string()));
        assert!(words.iter().all(|word| word.starts_with('S')));
    }

    #[test]
    fn operations_carry_their_summary() {
        let text = "PB 1\n      A I 0.0\n      |\n      BE\n";
        let items = completions(
            text,
            Position {
                line: 2,
                character: 6,
            },
            &context(&text.replace('|', "")),
        );
        let ju = items.iter().find(|item| item.label == "JU").unwrap();
        assert_eq!(ju.kind, CompletionKind::Operation);
        assert!(!ju.detail.is_empty());
        let supplementary = mnemonics::OPERATIONS
            .iter()
            .find(|info| info.supplementary)
            .unwrap();
        let item = items
            .iter()
            .find(|item| item.label == supplementary.en)
            .unwrap();
        assert!(item.detail.ends_with("(function blocks only)"), "{item:?}");
        assert!(items.iter().all(|item| item.label != "SPA"));
    }

    #[test]
    fn formal_operands_labels_and_blocks_in_the_enclosing_fb() {
        let text = GERMAN_FB.replace("SPB =M001", "SPB |");
        let in_fb = offered(&text);
        for expected in ["M001", "=EIN", "FB 1", "OB 1"] {
            assert!(
                in_fb.contains(&expected.to_string()),
                "{expected} in {in_fb:?}"
            );
        }
        let in_ob = offered(&GERMAN_FB.replace("SPA FB 1", "SPA |"));
        assert!(!in_ob.contains(&"M001".to_string()), "{in_ob:?}");
        assert!(!in_ob.contains(&"=EIN".to_string()));
    }

    #[test]
    fn no_completion_in_a_comment() {
        assert!(offered("PB 1\n      A I 0.0 ; J|\n      BE\n").is_empty());
    }

    #[test]
    fn step7_variables_members_and_operations() {
        let text = "DATA_BLOCK \"Tank\"\nSTRUCT\n  level : INT;\nEND_STRUCT\nBEGIN\nEND_DATA_BLOCK\n\nFUNCTION FC 1 : VOID\nVAR_TEMP\n  speed : INT;\nEND_VAR\nBEGIN\n      L     |;\nEND_FUNCTION\n";
        let values = offered(text);
        for expected in ["#speed", "\"Tank\".level", "FC 1"] {
            assert!(
                values.contains(&expected.to_string()),
                "{expected} in {values:?}"
            );
        }
        let operations = offered(&text.replace("L     |;", "|"));
        assert!(operations.contains(&"JU".to_string()), "{operations:?}");
        assert!(operations.contains(&"L".to_string()));
    }

    #[test]
    fn symbols_of_the_program() {
        let context = CompletionContext {
            language: FileLanguage {
                dialect: Dialect::Step5,
                mnemonics: MnemonicSet::English,
            },
            symbols: vec![named("-START".into(), "I 0.0", None)],
            variables: Vec::new(),
            db_members: Vec::new(),
            blocks: Vec::new(),
            labels: Vec::new(),
        };
        let text = "PB 1\n      A -ST\n";
        let items = completions(
            text,
            Position {
                line: 1,
                character: 11,
            },
            &context,
        );
        assert_eq!(items.len(), 1);
        assert_eq!(items[0].kind, CompletionKind::Symbol);
    }
}
