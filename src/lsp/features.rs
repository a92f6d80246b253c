//! Completion, quick fixes, semantic tokens and formatting served: the pure modules' plain
//! types (`text`) turned into the protocol's.

use std::collections::HashMap;

use lsp_types::{
    CodeAction, CodeActionKind, CodeActionOrCommand, CompletionItem, CompletionItemKind,
    SemanticTokens, Uri, WorkspaceEdit,
};

use super::complete::{self, CompletionContext, CompletionKind};
use super::fixes;
use super::position::{plain, protocol};
use super::text::{self, FileLanguage};
use super::workspace::Analysis;
use super::{format, tokens};

/// The document is file 0 of its analysis.
const DOCUMENT: crate::source::FileId = 0;

pub fn completions(analysis: &Analysis, position: lsp_types::Position) -> Vec<CompletionItem> {
    let context = CompletionContext::from_frontend(&analysis.built, DOCUMENT);
    complete::completions(analysis.text(DOCUMENT), plain(position), &context)
        .into_iter()
        .map(|completion| CompletionItem {
            label: completion.label,
            kind: Some(completion_kind(completion.kind)),
            detail: Some(completion.detail),
            ..CompletionItem::default()
        })
        .collect()
}

fn completion_kind(kind: CompletionKind) -> CompletionItemKind {
    match kind {
        CompletionKind::Operation => CompletionItemKind::KEYWORD,
        CompletionKind::Symbol => CompletionItemKind::CONSTANT,
        CompletionKind::Variable => CompletionItemKind::VARIABLE,
        CompletionKind::Member => CompletionItemKind::FIELD,
        CompletionKind::Block => CompletionItemKind::MODULE,
        CompletionKind::Label => CompletionItemKind::REFERENCE,
    }
}

/// The quick fixes of the document's diagnostics whose span meets `range`.
pub fn code_actions(
    analysis: &Analysis,
    uri: &Uri,
    range: lsp_types::Range,
) -> Vec<CodeActionOrCommand> {
    let text = analysis.text(DOCUMENT);
    let index = text::LineIndex::new(text);
    let (start, end) = (
        index.offset(plain(range.start)),
        index.offset(plain(range.end)),
    );
    let language = FileLanguage::of(&analysis.built, DOCUMENT);
    analysis
        .built
        .diagnostics
        .iter()
        .filter(|diagnostic| {
            let span = diagnostic.span();
            span.file == DOCUMENT && span.start as usize <= end && start <= span.end as usize
        })
        .flat_map(|diagnostic| fixes::quick_fixes_of(text, diagnostic, language))
        .map(|fix| {
            let edits = fix.edits.into_iter().map(edit).collect();
            CodeActionOrCommand::CodeAction(CodeAction {
                title: fix.title,
                kind: Some(CodeActionKind::QUICKFIX),
                edit: Some(WorkspaceEdit {
                    changes: Some(HashMap::from([(uri.clone(), edits)])),
                    ..WorkspaceEdit::default()
                }),
                ..CodeAction::default()
            })
        })
        .collect()
}

pub fn semantic_tokens(analysis: &Analysis) -> SemanticTokens {
    let language = FileLanguage::of(&analysis.built, DOCUMENT);
    let data = tokens::semantic_tokens(analysis.text(DOCUMENT), language)
        .into_iter()
        .map(|token| lsp_types::SemanticToken {
            delta_line: token.delta_line,
            delta_start: token.delta_start,
            length: token.length,
            token_type: token.token_type,
            token_modifiers_bitset: token.modifiers,
        })
        .collect();
    SemanticTokens {
        result_id: None,
        data,
    }
}

pub fn formatting(analysis: &Analysis) -> Vec<lsp_types::TextEdit> {
    let language = FileLanguage::of(&analysis.built, DOCUMENT);
    format::format(analysis.text(DOCUMENT), language)
        .into_iter()
        .map(edit)
        .collect()
}

/// The legend [`semantic_tokens`] encodes with.
pub fn legend() -> lsp_types::SemanticTokensLegend {
    lsp_types::SemanticTokensLegend {
        token_types: tokens::LEGEND
            .iter()
            .map(|name| lsp_types::SemanticTokenType::new(name))
            .collect(),
        token_modifiers: Vec::new(),
    }
}

fn edit(edit: text::TextEdit) -> lsp_types::TextEdit {
    lsp_types::TextEdit {
        range: lsp_types::Range::new(protocol(edit.range.start), protocol(edit.range.end)),
        new_text: edit.new_text,
    }
}
