//! Go to definition, find references, document and workspace symbols: blocks, jump labels,
//! the symbols of the assignment list, networks and segments.

use std::path::Path;

use lsp_types::{DocumentSymbol, Location, Range, SymbolInformation, SymbolKind, Uri};

use super::lookup::{self, Block, Statement, covers};
use super::position::LineIndex;
use super::workspace::{Analysis, Workspace, uri_of};
use crate::source::Span;
use crate::step7::ast::{DataType, S7BlockKind, S7BlockRef, S7Body};

/// What a name at the cursor stands for.
#[derive(Debug, Clone, PartialEq)]
pub enum Target {
    /// A jump label of the block with that index in file 0's outline.
    Label { block: usize, name: String },
    /// `PB 3`, `FC 1`, `"Valve"`.
    Block(String),
    /// A symbol of the assignment list, without `-` or quotes.
    Symbol(String),
    /// A STEP 7 variable (`#speed`, `"Data".speed`), declared at the span.
    Variable(Span),
}

/// The label name an operand or a label definition writes: `M001`, `=M001` → `M001`.
fn label_name(word: &str) -> &str {
    word.trim_start_matches('=').trim_end_matches(':')
}

/// What stands at byte `offset` of the document.
pub fn target_at(analysis: &Analysis, offset: usize) -> Option<Target> {
    let text = analysis.text(0);
    let (_, statements) = lookup::outline(analysis, 0);
    if let Some(name) = lookup::block_name_at(text, offset)
        && blocks_named(analysis, &name).next().is_some()
    {
        return Some(Target::Block(name));
    }
    let (word, _) = lookup::word_at(text, offset)?;
    if word.starts_with('"') && blocks_named(analysis, word).next().is_some() {
        return Some(Target::Block(word.to_string()));
    }
    if let Some(name) = crate::symbols::symbol_written(word)
        && analysis.built.compiled.program.symbols.get(name).is_some()
    {
        return Some(Target::Symbol(name.to_string()));
    }
    if let Some(declared) = declaration_of(analysis, word, offset) {
        return Some(Target::Variable(declared));
    }
    if let Some(declared) = parameter_at(analysis, offset) {
        return Some(Target::Variable(declared));
    }
    let statement = statements
        .iter()
        .find(|statement| covers(statement.whole, offset))?;
    let name = label_name(word);
    labels_of(&statements, statement.block)
        .any(|label| label.text == name)
        .then(|| Target::Label {
            block: statement.block,
            name: name.to_string(),
        })
}

fn labels_of<'a>(
    statements: &'a [Statement<'a>],
    block: usize,
) -> impl Iterator<Item = &'a crate::ast::Name> {
    statements
        .iter()
        .filter(move |statement| statement.block == block)
        .filter_map(|statement| statement.label)
}

/// The blocks called `name` in every file of the analysis, with their file's outline.
fn blocks_named<'a>(analysis: &'a Analysis, name: &'a str) -> impl Iterator<Item = Block> + 'a {
    (0..analysis.built.sources.files.len() as u16).flat_map(move |file| {
        lookup::outline(analysis, file)
            .0
            .into_iter()
            .filter(move |block| block.name.eq_ignore_ascii_case(name))
    })
}

/// The location of a span of any file of the analysis.
pub fn location(analysis: &Analysis, span: Span) -> Option<Location> {
    let text = analysis.text(span.file);
    let range = LineIndex::new(text).range(span.start as usize..span.end as usize);
    Some(Location::new(analysis.uri(span.file)?, range))
}

/// Where the target is defined.
pub fn definition(analysis: &Analysis, target: &Target) -> Option<Location> {
    match target {
        Target::Label { block, name } => {
            let (_, statements) = lookup::outline(analysis, 0);
            let label = labels_of(&statements, *block).find(|label| &label.text == name)?;
            location(analysis, label.span)
        }
        Target::Block(name) => {
            let block = blocks_named(analysis, name).next()?;
            location(analysis, block.header)
        }
        Target::Variable(declared) => location(analysis, *declared),
        Target::Symbol(name) => {
            let symbols = &analysis.built.compiled.program.symbols;
            let entry = symbols.get(name)?;
            let block = symbols.block_of(name).map(|id| id.to_string());
            match block.and_then(|block| blocks_named(analysis, &block).next()) {
                Some(block) => location(analysis, block.header),
                None => location(analysis, entry.name_span),
            }
        }
    }
}

/// Every place the target is written: its definition first (with `include_definition`),
/// then its uses in the document's program.
pub fn references(analysis: &Analysis, target: &Target, include_definition: bool) -> Vec<Location> {
    let mut found: Vec<Location> = Vec::new();
    if include_definition {
        found.extend(definition(analysis, target));
    }
    for file in 0..analysis.built.sources.files.len() as u16 {
        let text = analysis.text(file);
        let (_, statements) = lookup::outline(analysis, file);
        for statement in &statements {
            if statement.operand.is_empty() {
                continue;
            }
            let start = statement.operand.start as usize;
            let written = lookup::slice(analysis, statement.operand);
            let hit = match target {
                Target::Label { block, name } => {
                    file == 0 && statement.block == *block && label_name(written.trim()) == name
                }
                Target::Block(name) => {
                    lookup::block_name_at(text, start)
                        .is_some_and(|at| at.eq_ignore_ascii_case(name))
                        || written.trim().eq_ignore_ascii_case(name)
                }
                Target::Variable(declared) => lookup::word_at(text, start)
                    .and_then(|(word, _)| declaration_of(analysis, word, start))
                    .is_some_and(|at| at == *declared),
                Target::Symbol(name) => lookup::word_at(text, start)
                    .and_then(|(word, _)| crate::symbols::symbol_written(word))
                    .is_some_and(|word| word.eq_ignore_ascii_case(name)),
            };
            if hit {
                found.extend(location(analysis, statement.operand));
            }
        }
    }
    found
}

/// Where the STEP 7 variable `word` at `offset` of the document is declared: `#speed` in the
/// interface of the block around it, `"Data".speed` among the members of that data block.
pub fn declaration_of(analysis: &Analysis, word: &str, offset: usize) -> Option<Span> {
    let (owner, member) = match word.strip_prefix('#') {
        Some(local) => (None, local),
        None => {
            let (db, member) = word.split_once("\".")?;
            (Some(db.trim_start_matches('"')), member)
        }
    };
    let member = member.split('.').next()?;
    let symbols = &analysis.built.compiled.program.symbols;
    let owner_number = owner
        .and_then(|name| symbols.block_of(name))
        .map(|id| id.number);
    for unit in &analysis.built.s7_units {
        for block in &unit.blocks {
            let is_owner = match (owner, &block.name) {
                (None, _) => {
                    unit.file == 0
                        && block.header.start as usize <= offset
                        && block.end.is_none_or(|end| offset <= end.end as usize)
                }
                (Some(name), S7BlockRef::Symbol(written)) => {
                    written.text.eq_ignore_ascii_case(name)
                }
                (Some(_), S7BlockRef::Number { kind, number }) => {
                    *kind == S7BlockKind::Db && owner_number == Some(*number)
                }
            };
            if !is_owner {
                continue;
            }
            let members: Vec<&crate::step7::ast::VarDecl> = match &block.body {
                S7Body::Data { members, .. } if owner.is_some() => members.iter().collect(),
                _ => block
                    .interface
                    .iter()
                    .flat_map(|section| &section.vars)
                    .collect(),
            };
            if let Some(declared) = members
                .iter()
                .find(|declared| declared.name.text.eq_ignore_ascii_case(member))
            {
                return Some(declared.span);
            }
        }
    }
    None
}

/// A formal parameter a call names (`start := I 0.0`): its declaration in the called block,
/// the FB a multi-instance (`CALL #pump`) is declared of included.
fn parameter_at(analysis: &Analysis, offset: usize) -> Option<Span> {
    let unit = analysis.built.s7_units.iter().find(|unit| unit.file == 0)?;
    let (caller, call, parameter) = unit.blocks.iter().find_map(|block| {
        let S7Body::Logic(statements) = &block.body else {
            return None;
        };
        statements.iter().find_map(|statement| {
            let call = statement.call.as_ref()?;
            let parameter = call
                .params
                .iter()
                .find(|parameter| covers(parameter.name.span, offset))?;
            Some((block, call, parameter))
        })
    })?;
    let called = match &call.multi_instance {
        Some(instance) => {
            let declared = caller
                .interface
                .iter()
                .flat_map(|section| &section.vars)
                .find(|declared| declared.name.text.eq_ignore_ascii_case(&instance.text))?;
            match &declared.ty {
                DataType::Instance(kind, number) => format!("{} {number}", kind.name()),
                DataType::Named(name) => format!("\"{}\"", name.text),
                _ => return None,
            }
        }
        None => call.block.written(),
    };
    let symbols = &analysis.built.compiled.program.symbols;
    let numbered = called
        .strip_prefix('"')
        .and_then(|name| symbols.block_of(name.trim_end_matches('"')))
        .map(|id| id.to_string());
    analysis
        .built
        .s7_units
        .iter()
        .flat_map(|unit| &unit.blocks)
        .filter(|block| {
            let written = block.name.written();
            written.eq_ignore_ascii_case(&called)
                || numbered
                    .as_ref()
                    .is_some_and(|id| written.eq_ignore_ascii_case(id))
        })
        .flat_map(|block| block.interface.iter().flat_map(|section| &section.vars))
        .find(|declared| {
            declared
                .name
                .text
                .eq_ignore_ascii_case(&parameter.name.text)
        })
        .map(|declared| declared.span)
}

/// The document's blocks, each with its networks or segments.
#[allow(deprecated)] // `DocumentSymbol::deprecated` has no replacement field to fill
pub fn document_symbols(analysis: &Analysis) -> Vec<DocumentSymbol> {
    let text = analysis.text(0);
    let index = LineIndex::new(text);
    let range = |span: Span| index.range(span.start as usize..span.end as usize);
    let (blocks, _) = lookup::outline(analysis, 0);
    blocks
        .iter()
        .map(|block| {
            let children: Vec<DocumentSymbol> = block
                .parts
                .iter()
                .map(|(number, first)| DocumentSymbol {
                    name: format!("{} {number}", part_word(analysis)),
                    detail: None,
                    kind: SymbolKind::NAMESPACE,
                    tags: None,
                    deprecated: None,
                    range: range(*first),
                    selection_range: range(*first),
                    children: None,
                })
                .collect();
            DocumentSymbol {
                name: block.name.clone(),
                detail: None,
                kind: SymbolKind::FUNCTION,
                tags: None,
                deprecated: None,
                range: range(block.whole),
                selection_range: range(block.header),
                children: (!children.is_empty()).then_some(children),
            }
        })
        .collect()
}

/// STEP 7 programs have networks, STEP 5 listings segments.
fn part_word(analysis: &Analysis) -> &'static str {
    if analysis.built.s7_units.is_empty() {
        "segment"
    } else {
        "network"
    }
}

/// The blocks whose names contain `query` (case-insensitive), in the open documents and the
/// `.awl` files of the workspace folder.
#[allow(deprecated)] // `SymbolInformation::deprecated` has no replacement field to fill
pub fn workspace_symbols(workspace: &Workspace, query: &str) -> Vec<SymbolInformation> {
    let query = query.to_uppercase();
    let mut uris: Vec<Uri> = workspace.documents.uris().cloned().collect();
    if let Some(root) = &workspace.root {
        uris.extend(awl_files(root).filter_map(|path| uri_of(&path)));
    }
    uris.sort_by(|a, b| a.as_str().cmp(b.as_str()));
    uris.dedup();
    let mut found = Vec::new();
    for uri in uris {
        let text = match workspace.documents.get(&uri) {
            Some(text) => text.to_string(),
            None => match super::workspace::path_of(&uri).and_then(|path| std::fs::read(path).ok())
            {
                Some(bytes) => String::from_utf8_lossy(&bytes).into_owned(),
                None => continue,
            },
        };
        let analysis = workspace.analyse(&uri, &text);
        let index = LineIndex::new(&text);
        for block in lookup::outline(&analysis, 0).0 {
            if !block.name.to_uppercase().contains(&query) {
                continue;
            }
            let range: Range = index.range(block.header.start as usize..block.header.end as usize);
            found.push(SymbolInformation {
                name: block.name,
                kind: SymbolKind::FUNCTION,
                tags: None,
                deprecated: None,
                location: Location::new(uri.clone(), range),
                container_name: None,
            });
        }
    }
    found
}

/// The `.awl` files below `root`, hidden folders and build output left out.
fn awl_files(root: &Path) -> impl Iterator<Item = std::path::PathBuf> {
    walkdir::WalkDir::new(root)
        .max_depth(4)
        .into_iter()
        .filter_entry(|entry| {
            let name = entry.file_name().to_string_lossy();
            entry.depth() == 0 || !(name.starts_with('.') || name == "target")
        })
        .filter_map(Result::ok)
        .map(walkdir::DirEntry::into_path)
        .filter(|path| {
            path.extension()
                .is_some_and(|ext| ext.eq_ignore_ascii_case("awl"))
        })
}
