//! Fragments: statements before any block header, as forum posts, knowledge-base articles and
//! manuals print them. They are taken as a block they can live in, so they are checked like any
//! other: OB 1 when no file defines it, otherwise a PB with a number no other block uses. A
//! fragment that uses supplementary operations (jumps to labels, `DO`, formal operands) can only
//! be an FB: it gets a free FB number, and a generated OB 1 calls it (`JU FB n`) when no file
//! defines OB 1 and the FB has no parameters. A fragment needs no `BE`. A note says which block
//! it became; its statements keep their spans, so every error points at the user's line.

use std::collections::HashSet;

use crate::ast::{
    Block, BlockBody, BlockId, LogicBody, Name, Operand, ParamDecl, ParamFormat, SourceUnit,
    Statement,
};
use crate::compiler::describe_decl;
use crate::mnemonics::{self, BlockKind, ConstFormat, MnemonicSet, OpCode, ParamKind};
use crate::parser::ParseError;
use crate::source::Span;

const OB_1: BlockId = BlockId {
    kind: BlockKind::Ob,
    number: 1,
};

/// Gives each file's fragment (`fragments[i]`: file `i` starts with one, in `blocks[0]`) its
/// block, declares the formal operands a fragment or an FB without `DES` lines uses, and
/// returns the notes.
pub fn place(units: &mut [SourceUnit], fragments: &[bool]) -> Vec<ParseError> {
    let is_fragment = |file: usize, index: usize| index == 0 && fragments[file];
    let mut used = HashSet::new();
    for (file, unit) in units.iter().enumerate() {
        for (index, block) in unit.blocks.iter().enumerate() {
            if !is_fragment(file, index) {
                used.insert(block.id);
            }
            if let BlockBody::Logic(body) = &block.body {
                used.extend(body.statements.iter().filter_map(
                    |statement| match statement.operand {
                        Operand::Block(id) => Some(id),
                        _ => None,
                    },
                ));
            }
        }
    }
    let mut ob1_taken = units.iter().enumerate().any(|(file, unit)| {
        unit.blocks
            .iter()
            .enumerate()
            .any(|(index, block)| block.id == OB_1 && !is_fragment(file, index))
    });
    let mut diagnostics = Vec::new();
    for (file, unit) in units.iter_mut().enumerate() {
        let set = unit.mnemonics;
        for (index, block) in unit.blocks.iter_mut().enumerate() {
            if let BlockBody::Logic(body) = &mut block.body
                && !is_fragment(file, index)
                && block.id.kind.is_function()
                && body.params.is_empty()
            {
                diagnostics.extend(declare_from_use(body, set));
            }
        }
        if !fragments[file] {
            continue;
        }
        let block = &mut unit.blocks[0];
        let BlockBody::Logic(body) = &mut block.body else {
            continue;
        };
        let needs_fb = needs_function_block(body);
        if needs_fb {
            diagnostics.extend(declare_from_use(body, set));
        }
        end_block(body, block.header);
        let mut calls = false;
        let (id, reason) = if needs_fb {
            let id = free(&mut used, BlockKind::Fb);
            calls = !ob1_taken && body.params.is_empty();
            ob1_taken |= calls;
            (id, fb_reason(body, set, id, calls))
        } else if !ob1_taken {
            ob1_taken = true;
            (
                OB_1,
                "add a header line such as `PB 1` above them to put them in a block of your choice"
                    .to_string(),
            )
        } else {
            let id = free(&mut used, BlockKind::Pb);
            (
                id,
                format!(
                    "OB 1 is defined, so they are checked as {id}, a number no other block uses; add a header line above them to choose the block"
                ),
            )
        };
        block.id = id;
        let header = block.header;
        if calls {
            unit.blocks.insert(1, generated_ob1(id, header));
        }
        diagnostics.push(ParseError::Fragment {
            block: id.to_string(),
            at: header,
            help: reason,
        });
    }
    diagnostics
}

/// Supplementary operations, jumps to labels and formal operands exist in FBs only.
fn needs_function_block(body: &LogicBody) -> bool {
    !body.params.is_empty()
        || body.statements.iter().any(|statement| {
            mnemonics::op_info(statement.op).supplementary
                || matches!(statement.operand, Operand::Symbol(_))
        })
}

fn fb_reason(body: &LogicBody, set: MnemonicSet, id: BlockId, calls: bool) -> String {
    let ju = mnemonics::op_word(set, OpCode::JumpUnconditional);
    if !body.params.is_empty() {
        let example = first_use(body, set, |statement| {
            matches!(statement.operand, Operand::Symbol(_)) && !is_label_jump(statement.op)
        });
        return format!(
            "they use parameters{example}, so they are a function block; call {id} from OB 1 with `{ju} {id}` and a line per parameter"
        );
    }
    let example = first_use(body, set, |statement| {
        mnemonics::op_info(statement.op).supplementary
            || matches!(statement.operand, Operand::Symbol(_))
    });
    let caller = if calls {
        format!("a generated OB 1 calls {id} with `{ju} {id}`")
    } else {
        format!("OB 1 is defined, so call {id} from it with `{ju} {id}`")
    };
    format!(
        "they use supplementary operations{example}, which STEP 5 allows in function blocks only; {caller}"
    )
}

/// ` (`A =EIN`)`: the first statement that shows why, as written in the file's set.
fn first_use(body: &LogicBody, set: MnemonicSet, shows: impl Fn(&Statement) -> bool) -> String {
    let Some(statement) = body.statements.iter().find(|statement| shows(statement)) else {
        return String::new();
    };
    let word = mnemonics::op_word(set, statement.op);
    match &statement.operand {
        Operand::Symbol(name) => format!(" (`{word} ={name}`)"),
        _ => format!(" (`{word}`)"),
    }
}

/// The lowest number of `kind` no block has or calls, taken.
fn free(used: &mut HashSet<BlockId>, kind: BlockKind) -> BlockId {
    let id = (1..=255)
        .chain(std::iter::once(0))
        .map(|number| BlockId { kind, number })
        .find(|id| !used.contains(id))
        .unwrap_or(BlockId { kind, number: 255 });
    used.insert(id);
    id
}

/// A fragment needs no `BE`: one is added after its last statement.
fn end_block(body: &mut LogicBody, header: Span) {
    if body.end.is_some() {
        return;
    }
    let last = body.statements.last();
    let end = last.map_or(header.end, |statement| statement.span.end);
    let at = Span {
        start: end,
        end,
        ..header
    };
    body.statements.push(Statement {
        label: None,
        op: OpCode::BlockEnd,
        op_span: at,
        operand: Operand::None,
        operand_span: at,
        call_params: Vec::new(),
        segment: last.map_or(0, |statement| statement.segment),
        span: at,
    });
    body.end = Some(at);
}

/// OB 1 that calls the fragment's FB, made where the fragment starts.
fn generated_ob1(fb: BlockId, at: Span) -> Block {
    let statement = |op, operand| Statement {
        label: None,
        op,
        op_span: at,
        operand,
        operand_span: at,
        call_params: Vec::new(),
        segment: 0,
        span: at,
    };
    Block {
        id: OB_1,
        header: at,
        body: BlockBody::Logic(LogicBody {
            statements: vec![
                statement(OpCode::JumpUnconditional, Operand::Block(fb)),
                statement(OpCode::BlockEnd, Operand::None),
            ],
            end: Some(at),
            ..LogicBody::default()
        }),
    }
}

/// Formal operands `=NAME` a block uses without a `DES` line (a fragment's, or an FB printed
/// without its declarations): each is declared with the kind and format its uses imply, and
/// one note lists them with the lines that would declare them. A jump's `=M001` and the
/// block's own labels are no formal operands.
fn declare_from_use(body: &mut LogicBody, set: MnemonicSet) -> Option<ParseError> {
    let labels: HashSet<String> = body
        .statements
        .iter()
        .filter_map(|statement| Some(statement.label.as_ref()?.text.to_ascii_uppercase()))
        .collect();
    let declared = body.params.len();
    for statement in &body.statements {
        let Operand::Symbol(name) = &statement.operand else {
            continue;
        };
        if is_label_jump(statement.op) || labels.contains(&name.to_ascii_uppercase()) {
            continue;
        }
        let (kind, format) = implied_kind(statement.op);
        match body
            .params
            .iter_mut()
            .position(|param| param.name.text.eq_ignore_ascii_case(name))
        {
            // A later write makes an input of the same format an output (`A =X` … `= =X`).
            Some(index) if index >= declared => {
                let param = &mut body.params[index];
                if param.kind == ParamKind::Input
                    && kind == ParamKind::Output
                    && param.format == format
                {
                    param.kind = kind;
                }
            }
            Some(_) => {}
            None => body.params.push(ParamDecl {
                name: Name {
                    text: name.clone(),
                    span: statement.operand_span,
                },
                kind,
                format,
                span: statement.operand_span,
            }),
        }
    }
    let inferred = &body.params[declared..];
    let first = inferred.first()?;
    let des = match set {
        MnemonicSet::English => mnemonics::DECLARATION_EN,
        MnemonicSet::German => mnemonics::DECLARATION_DE,
    };
    let list: Vec<String> = inferred
        .iter()
        .map(|param| format!("={} ({})", param.name.text, describe_decl(param, set)))
        .collect();
    let lines: Vec<String> = inferred
        .iter()
        .map(|param| format!("`{des} :{} {}`", param.name.text, describe_decl(param, set)))
        .collect();
    Some(ParseError::FormalsFromUse {
        list: list.join(", "),
        first: first.name.text.clone(),
        at: first.span,
        help: format!(
            "no `{des}` line declares them; to choose their kinds, declare them before the \
             first statement: {}",
            lines.join(", ")
        ),
    })
}

fn is_label_jump(op: OpCode) -> bool {
    matches!(
        op,
        OpCode::JumpUnconditional
            | OpCode::JumpConditional
            | OpCode::JumpZero
            | OpCode::JumpNotZero
            | OpCode::JumpPositive
            | OpCode::JumpMinus
            | OpCode::JumpOverflow
    )
}

/// The parameter kind a use implies: a bit input for scanning, a bit output for `=`, `S`, `R`
/// and `RB`, a word input for `L`, a word output for `T`, a timer or counter for their
/// operations (`RD` resets either: a timer), a data constant for `LW` (`KH`) and `LD` (`KF`).
fn implied_kind(op: OpCode) -> (ParamKind, Option<ParamFormat>) {
    use OpCode::*;
    match op {
        And | AndNot | Or | OrNot => (ParamKind::Input, Some(ParamFormat::Bit)),
        Assign | Set | Reset | ResetBinary => (ParamKind::Output, Some(ParamFormat::Bit)),
        Transfer => (ParamKind::Output, Some(ParamFormat::Word)),
        TimerPulse | TimerExtendedPulse | TimerOnDelay | TimerStoredOnDelay | TimerOffDelay
        | Enable | ResetDigital => (ParamKind::Timer, None),
        CountUp | CountDown => (ParamKind::Counter, None),
        LoadBitPattern => (
            ParamKind::Data,
            Some(ParamFormat::Constant(ConstFormat::Hex)),
        ),
        LoadDecimal => (
            ParamKind::Data,
            Some(ParamFormat::Constant(ConstFormat::Fixed)),
        ),
        _ => (ParamKind::Input, Some(ParamFormat::Word)),
    }
}

#[cfg(test)]
mod tests {
    use crate::frontend::{Frontend, Language, build};
    use crate::profile;
    use crate::source::{SourceFile, SourceSet};

    fn check(files: &[&str]) -> Frontend {
        let mut sources = SourceSet::default();
        for (index, text) in files.iter().enumerate() {
            sources.add(SourceFile::new(format!("f{index}.awl"), *text));
        }
        build(
            sources,
            Language::default(),
            profile::find("sinumerik-840c").unwrap(),
        )
    }

    fn codes_and_messages(built: &Frontend) -> Vec<String> {
        built
            .diagnostics
            .iter()
            .map(|d| format!("{}: {d}", miette::Diagnostic::code(d).unwrap()))
            .collect()
    }

    fn blocks(built: &Frontend) -> Vec<String> {
        let program = &built.compiled.program;
        program.blocks.iter().map(|b| b.id.to_string()).collect()
    }

    #[test]
    fn a_fragment_is_ob1_and_needs_no_be() {
        let built = check(&["      A I 0.0\n      = Q 4.0\n"]);
        assert_eq!(
            codes_and_messages(&built),
            ["awl::parse::fragment: statements before any block header are taken as OB 1"]
        );
        assert!(!built.has_errors());
        assert_eq!(blocks(&built), ["OB 1"]);
    }

    #[test]
    fn with_ob1_defined_a_fragment_is_a_pb_no_block_uses() {
        let built = check(&[
            "      A I 0.0\n      = Q 4.0\n",
            "OB 1\n      JU PB 1\n      BE\nPB 1\n      BE\n",
        ]);
        assert_eq!(
            codes_and_messages(&built),
            ["awl::parse::fragment: statements before any block header are taken as PB 2"]
        );
    }

    #[test]
    fn label_jumps_make_an_fb_that_a_generated_ob1_calls() {
        let built = check(&["      A I 0.0\n      JC =M001\n      = Q 4.0\nM001 :A I 0.1\n"]);
        assert_eq!(
            codes_and_messages(&built),
            ["awl::parse::fragment: statements before any block header are taken as FB 1"]
        );
        assert!(!built.has_errors());
        assert_eq!(blocks(&built), ["FB 1", "OB 1"]);
    }

    #[test]
    fn every_other_error_is_still_reported() {
        let built = check(&["      A I 0.0\n      XYZ\n      = Q 400.0\n      L KH 12345\n"]);
        let codes = codes_and_messages(&built);
        assert_eq!(codes.len(), 4, "{codes:#?}");
        assert!(codes[0].starts_with("awl::parse::fragment"));
    }

    #[test]
    fn undeclared_formal_operands_are_declared_from_their_use_with_one_note() {
        let built = check(&[
            "      A =EIN\n      AN =EIN\n      = =AUS\n      L =WERT\n      T =ZIEL\n\
             \x20     JC =M001\nM001 :A =MERK\n      = =MERK\n      RB =FMSS\n      LW =KON\n",
        ]);
        let codes = codes_and_messages(&built);
        assert_eq!(
            codes,
            [
                "awl::parse::fragment: statements before any block header are taken as FB 1",
                "awl::parse::formals_from_use: formal operands declared from their use: \
                 =EIN (I BI), =AUS (Q BI), =WERT (I W), =ZIEL (Q W), =MERK (Q BI), =FMSS (Q BI), \
                 =KON (D KH)",
            ]
        );
        assert!(!built.has_errors());
        let help = crate::syntax::error::help_text(&built.diagnostics[1]);
        assert!(help.contains("`DES :EIN I BI`, `DES :AUS Q BI`"), "{help}");
    }

    #[test]
    fn an_fb_printed_without_its_des_lines_gets_them_from_its_use() {
        let built = check(&[
            "OB 1\n      JU FB 5\nNAME :MOTOR\nEIN  :I 0.0\nAUS  :Q 4.0\n      BE\n\
             FB 5\nNAME :MOTOR\n      A =EIN\n      = =AUS\n      JC =M001\nM001 :BE\n",
        ]);
        assert_eq!(
            codes_and_messages(&built),
            [
                "awl::parse::formals_from_use: formal operands declared from their use: \
              =EIN (I BI), =AUS (Q BI)"
            ]
        );
    }

    #[test]
    fn an_fb_with_des_lines_keeps_its_undefined_operand_errors() {
        let built = check(&[
            "OB 1\n      BE\nFB 5\nNAME :MOTOR\nDES :EIN I BI\n      A =EIN\n      = =AUS\n      BE\n",
        ]);
        assert!(built.has_errors());
        assert!(
            codes_and_messages(&built)
                .iter()
                .all(|code| !code.contains("formals_from_use"))
        );
    }

    #[test]
    fn german_fragments_get_german_declarations() {
        let built = check(&["      U =EIN\n      = A 4.0\n"]);
        let help = crate::syntax::error::help_text(&built.diagnostics[1]);
        assert!(help.ends_with("`BEZ :EIN E BI`"), "{help}");
        assert!(!built.has_errors());
    }
}
