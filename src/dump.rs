//! `awl dump`: each block's bytecode with source line numbers.

use std::fmt::Write as _;

use crate::compiler::bytecode::{
    BitSource, BitTarget, DataPart, ImageBit, IndirectSource, Op, Width,
};
use crate::compiler::{Layout, Program};
use crate::source::SourceSet;

/// `I 0`, `Q 4`, `F 10` for an image byte offset.
fn image_byte(layout: Layout, byte: u16) -> String {
    if byte >= layout.flag_base() {
        format!("F {}", byte - layout.flag_base())
    } else if byte >= layout.output_base() {
        format!("Q {}", byte - layout.output_base())
    } else {
        format!("I {byte}")
    }
}

/// `IW 2`, `FY 10`, `FD 4` for a sized image access.
fn sized(layout: Layout, width: Width, byte: u16) -> String {
    let plain = image_byte(layout, byte);
    let (area, number) = plain.split_once(' ').unwrap_or(("I", "0"));
    let suffix = match (area, width) {
        ("F", Width::Byte) => "Y",
        (_, Width::Byte) => "B",
        (_, Width::Word) => "W",
        (_, Width::Double) => "D",
    };
    format!("{area}{suffix} {number}")
}

fn image_bit(layout: Layout, bit: ImageBit) -> String {
    format!("{}.{}", image_byte(layout, bit.byte), bit.bit)
}

fn bit_target(layout: Layout, target: BitTarget) -> String {
    match target {
        BitTarget::Image(bit) => image_bit(layout, bit),
        BitTarget::Data { word, bit } => format!("D {word}.{bit}"),
    }
}

/// A compact, readable form of one op.
/// `params` are the declarations of the block the op is in (for formal operands).
pub fn op_text(op: Op, program: &Program, params: &[crate::ast::ParamDecl]) -> String {
    let layout = program.layout;
    match op {
        Op::And(bit) => format!("and {}", image_bit(layout, bit)),
        Op::AndNot(bit) => format!("and-not {}", image_bit(layout, bit)),
        Op::Or(bit) => format!("or {}", image_bit(layout, bit)),
        Op::OrNot(bit) => format!("or-not {}", image_bit(layout, bit)),
        Op::Assign(bit) => format!("assign {}", image_bit(layout, bit)),
        Op::Set(bit) => format!("set {}", image_bit(layout, bit)),
        Op::Reset(bit) => format!("reset {}", image_bit(layout, bit)),
        Op::LogicOther(logic, source) => {
            let source = match source {
                BitSource::Data { word, bit } => format!("D {word}.{bit}"),
                BitSource::Timer(n) => format!("T {n}"),
                BitSource::Counter(n) => format!("C {n}"),
            };
            format!("{logic:?} {source}").to_lowercase()
        }
        Op::WriteData { write, word, bit } => format!("{write:?} D {word}.{bit}").to_lowercase(),
        Op::LoadImageByte(byte) => format!("load {}", sized(layout, Width::Byte, byte)),
        Op::LoadImageWord(byte) => format!("load {}", sized(layout, Width::Word, byte)),
        Op::LoadImageDouble(byte) => format!("load {}", sized(layout, Width::Double, byte)),
        Op::TransferImageByte(byte) => format!("transfer {}", sized(layout, Width::Byte, byte)),
        Op::TransferImageWord(byte) => format!("transfer {}", sized(layout, Width::Word, byte)),
        Op::TransferImageDouble(byte) => format!("transfer {}", sized(layout, Width::Double, byte)),
        Op::LoadConstant(value) => format!("load-constant {value:#06X}"),
        Op::Call {
            block,
            conditional,
            params,
        } => {
            let id = program.blocks[usize::from(block)].id;
            let kind = if conditional { "call-if-rlo" } else { "call" };
            if params == crate::compiler::bytecode::NO_PARAMS {
                format!("{kind} {id}")
            } else {
                format!(
                    "{kind} {id} with {} parameters",
                    program.param_lists[usize::from(params)].len()
                )
            }
        }
        Op::CallMissing { kind, number, .. } => {
            format!("call-missing {} {number} (STOP)", kind.name())
        }
        Op::Jump(condition, target) => format!("jump-{condition:?} -> {target}").to_lowercase(),
        Op::Indirect { source, .. } => match source {
            IndirectSource::FlagWord(byte) => {
                format!("do {}", image_byte(layout, byte).replace("F ", "FW "))
            }
            IndirectSource::DataWord(word) => format!("do DW {word}"),
        },
        Op::SetUnconditional(target) => format!("set-unconditional {}", bit_target(layout, target)),
        Op::ResetUnconditional(target) => {
            format!("reset-unconditional {}", bit_target(layout, target))
        }
        Op::TestBit { negate, target } => {
            format!(
                "{} {}",
                if negate { "test-bit-not" } else { "test-bit" },
                bit_target(layout, target)
            )
        }
        Op::Formal { op, param } => {
            let name = params
                .get(usize::from(param))
                .map_or("?", |decl| decl.name.text.as_str());
            format!(
                "{} ={name} (parameter {})",
                kebab(&format!("{op:?}")),
                param + 1
            )
        }
        Op::LoadPeripheral {
            width,
            byte,
            extended,
        }
        | Op::TransferPeripheral {
            width,
            byte,
            extended,
        } => {
            let verb = if matches!(op, Op::LoadPeripheral { .. }) {
                "load"
            } else {
                "transfer"
            };
            let area = match (extended, width) {
                (false, Width::Byte) => "PY",
                (false, _) => "PW",
                (true, Width::Byte) => "OY",
                (true, _) => "OW",
            };
            format!("{verb} {area} {byte}")
        }
        Op::LoadData(part, word) | Op::TransferData(part, word) => {
            let verb = if matches!(op, Op::LoadData(..)) {
                "load"
            } else {
                "transfer"
            };
            let area = match part {
                DataPart::Left => "DL",
                DataPart::Right => "DR",
                DataPart::Word => "DW",
                DataPart::Double => "DD",
            };
            format!("{verb} {area} {word}")
        }
        Op::OpenDb(number) => format!("open DB {number}"),
        Op::ArithmeticStack(kind) => {
            format!(
                "arithmetic {}, ACCU 3/4 up",
                format!("{kind:?}").to_lowercase()
            )
        }
        Op::GenerateDb(number) => format!("generate DB {number}"),
        other => kebab(&format!("{other:?}")),
    }
}

/// `StartTimer(OnDelay, 1)` → `start-timer on-delay 1`: Debug names made readable.
fn kebab(debug: &str) -> String {
    let mut out = String::new();
    let mut previous_lower = false;
    for c in debug.chars() {
        match c {
            '(' | ',' => out.push(' '),
            ')' => {}
            c if c.is_ascii_uppercase() => {
                if previous_lower {
                    out.push('-');
                }
                out.push(c.to_ascii_lowercase());
            }
            c => out.push(c),
        }
        previous_lower = c.is_ascii_lowercase();
    }
    out.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// `PB 3  (file.awl:12, 4 ops)`
fn header(
    out: &mut String,
    sources: &SourceSet,
    id: crate::ast::BlockId,
    at: crate::source::Span,
    count: usize,
    unit: &str,
) {
    let file = sources.get(at.file);
    let _ = writeln!(
        out,
        "{id}  ({}:{}, {count} {unit})",
        file.name,
        file.line_of(at.start)
    );
}

/// The whole dump: a header line per block, then one line per op.
pub fn dump(program: &Program, sources: &SourceSet) -> String {
    let mut out = String::new();
    for block in &program.blocks {
        header(
            &mut out,
            sources,
            block.id,
            block.header,
            block.code.len(),
            "ops",
        );
        for (pc, (op, span)) in block.code.iter().zip(&block.spans).enumerate() {
            let line = sources.line_of(*span);
            let text = sources.get(span.file).slice(*span);
            let _ = writeln!(
                out,
                "  {pc:>4}  line {line:>4}  {:<28} {}",
                text,
                op_text(*op, program, &block.params)
            );
        }
        out.push('\n');
    }
    for data in &program.data_blocks {
        header(
            &mut out,
            sources,
            data.id,
            data.header,
            data.words.len(),
            "words",
        );
        for (index, word) in data.words.iter().enumerate() {
            let _ = writeln!(out, "  DW {index:>4}  {word:#06X}  {}", *word as i16);
        }
        out.push('\n');
    }
    out
}
