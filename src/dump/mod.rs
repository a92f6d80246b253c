//! `awl dump`: each block's bytecode with source line numbers.

use std::fmt::Write as _;

use crate::compiler::bytecode::{
    BitSource, BitTarget, DataPart, ImageBit, IndirectSource, Op, Width,
};
use crate::compiler::{Layout, Program};
use crate::mnemonics::{self, Area, MnemonicSet};
use crate::source::SourceSet;

pub mod listing;

/// Operand names in the block's mnemonic set: `I 0.0` or `E 0.0`, `FW 10` or `MW 10`, with
/// the assignment list's symbol after them: `E 1.0 (-START)`.
#[derive(Clone, Copy)]
struct Names<'a> {
    layout: Layout,
    set: MnemonicSet,
    symbols: &'a crate::symbols::Symbols,
}

impl Names<'_> {
    /// `text` with its symbol, if it has one.
    fn named(self, text: String) -> String {
        match self.symbols.name_of(&text) {
            Some(name) => format!("{text} (-{name})"),
            None => text,
        }
    }

    fn word(self, area: Area) -> &'static str {
        mnemonics::area_word(self.set, area)
    }

    /// The bit area of an image byte offset and the byte's number in it.
    fn image(self, byte: u16) -> (Area, u16) {
        let layout = self.layout;
        if byte >= layout.flag_base() {
            (Area::Flag, byte - layout.flag_base())
        } else if byte >= layout.output_base() {
            (Area::Output, byte - layout.output_base())
        } else {
            (Area::Input, byte)
        }
    }

    /// `IW 2`, `MB 10`, `FD 4` for a sized image access.
    fn sized(self, width: Width, byte: u16) -> String {
        let (area, number) = self.image(byte);
        let sized = match (area, width) {
            (Area::Input, Width::Byte) => Area::InputByte,
            (Area::Input, _) => Area::InputWord,
            (Area::Output, Width::Byte) => Area::OutputByte,
            (Area::Output, _) => Area::OutputWord,
            (_, Width::Byte) => Area::FlagByte,
            (_, Width::Word) => Area::FlagWord,
            (_, Width::Double) => Area::FlagDouble,
        };
        self.named(format!("{} {number}", self.word(sized)))
    }

    fn bit(self, bit: ImageBit) -> String {
        let (area, number) = self.image(bit.byte);
        self.named(format!("{} {number}.{}", self.word(area), bit.bit))
    }

    fn data_bit(self, word: u16, bit: u8) -> String {
        format!("{} {word}.{bit}", self.word(Area::DataBit))
    }

    fn bit_target(self, target: BitTarget) -> String {
        match target {
            BitTarget::Image(bit) => self.bit(bit),
            BitTarget::Data { word, bit } => self.data_bit(word, bit),
        }
    }
}

/// A compact, readable form of one op.
/// `params` are the declarations of the block the op is in (for formal operands).
/// The operand words are the block's mnemonic set's; the verbs are English.
pub fn op_text(
    op: Op,
    program: &Program,
    set: MnemonicSet,
    params: &[crate::ast::ParamDecl],
) -> String {
    let names = Names {
        layout: program.layout,
        set,
        symbols: &program.symbols,
    };
    match op {
        Op::And(bit) => format!("and {}", names.bit(bit)),
        Op::AndNot(bit) => format!("and-not {}", names.bit(bit)),
        Op::Or(bit) => format!("or {}", names.bit(bit)),
        Op::OrNot(bit) => format!("or-not {}", names.bit(bit)),
        Op::Assign(bit) => format!("assign {}", names.bit(bit)),
        Op::Set(bit) => format!("set {}", names.bit(bit)),
        Op::Reset(bit) => format!("reset {}", names.bit(bit)),
        Op::LogicOther(logic, source) => {
            let source = match source {
                BitSource::Data { word, bit } => names.data_bit(word, bit),
                BitSource::Timer(n) => names.named(format!("{} {n}", names.word(Area::Timer))),
                BitSource::Counter(n) => names.named(format!("{} {n}", names.word(Area::Counter))),
            };
            format!("{} {source}", format!("{logic:?}").to_lowercase())
        }
        Op::WriteData { write, word, bit } => format!(
            "{} {}",
            format!("{write:?}").to_lowercase(),
            names.data_bit(word, bit)
        ),
        Op::LoadImageByte(byte) => format!("load {}", names.sized(Width::Byte, byte)),
        Op::LoadImageWord(byte) => format!("load {}", names.sized(Width::Word, byte)),
        Op::LoadImageDouble(byte) => format!("load {}", names.sized(Width::Double, byte)),
        Op::TransferImageByte(byte) => format!("transfer {}", names.sized(Width::Byte, byte)),
        Op::TransferImageWord(byte) => format!("transfer {}", names.sized(Width::Word, byte)),
        Op::TransferImageDouble(byte) => {
            format!("transfer {}", names.sized(Width::Double, byte))
        }
        Op::LoadConstant(value) => format!("load-constant {value:#06X}"),
        Op::Call {
            block,
            conditional,
            params,
        } => {
            let id = names.named(program.blocks[usize::from(block)].id.to_string());
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
            IndirectSource::FlagWord(byte) => format!("do {}", names.sized(Width::Word, byte)),
            IndirectSource::DataWord(word) => format!("do {} {word}", names.word(Area::DataWord)),
        },
        Op::SetUnconditional(target) => {
            format!("set-unconditional {}", names.bit_target(target))
        }
        Op::ResetUnconditional(target) => {
            format!("reset-unconditional {}", names.bit_target(target))
        }
        Op::TestBit { negate, target } => {
            format!(
                "{} {}",
                if negate { "test-bit-not" } else { "test-bit" },
                names.bit_target(target)
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
                (false, Width::Byte) => Area::PeripheralByte,
                (false, _) => Area::PeripheralWord,
                (true, Width::Byte) => Area::ExtendedByte,
                (true, _) => Area::ExtendedWord,
            };
            format!(
                "{verb} {}",
                names.named(format!("{} {byte}", names.word(area)))
            )
        }
        Op::LoadData(part, word) | Op::TransferData(part, word) => {
            let verb = if matches!(op, Op::LoadData(..)) {
                "load"
            } else {
                "transfer"
            };
            let area = match part {
                DataPart::Left => Area::DataLeft,
                DataPart::Right => Area::DataRight,
                DataPart::Word => Area::DataWord,
                DataPart::Double => Area::DataDouble,
            };
            format!("{verb} {} {word}", names.word(area))
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
            if let Some(&(_, segment)) = block
                .segments
                .iter()
                .find(|(first, _)| *first as usize == pc)
                && segment != 0
            {
                let _ = writeln!(out, "  segment {segment}");
            }
            let line = sources.line_of(*span);
            let text = sources.get(span.file).slice(*span);
            let _ = writeln!(
                out,
                "  {pc:>4}  line {line:>4}  {:<28} {}",
                text,
                op_text(*op, program, block.mnemonics, &block.params)
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
