//! The table of which status bits each STEP 7 operation reads and writes (the editor's hover
//! shows it) against what the VM does: every operation of the table runs on `speed7` after
//! `T STW` has set a random status word, with random accumulators and bit operands, once as
//! drawn and once for each status bit flipped. A bit the table says is kept must come out as it
//! went in, a bit it fixes must come out fixed, and a bit it says is not read must change
//! nothing else when flipped. Every bit it says is read must change something for some draw.

use std::sync::Arc;

use awl::frontend;
use awl::profile;
use awl::rules::effects::{self, BITS, Effect};
use std::cell::RefCell;
use std::rc::Rc;

use awl::compiler::Op;
use awl::rules::status::Status;
use awl::vm::Cpu;
use awl::vm::cycle::RunLimit;
use awl::vm::probe::{Flow, Probe};

/// Random draws per operation; each runs once more per status bit flipped. The draws are the
/// same on every run (a fixed seed); a STEP 5 run costs less, so it takes more.
const DRAWS: usize = 16;
const STEP5_DRAWS: usize = 48;

/// Where a case's results lie in the flags, and how many bytes it takes.
const RESULTS: usize = 100;
const RESULT_BYTES: usize = 14;

/// The status word as `L STW` holds it: /FC, RLO, STA, OR, OS, OV, CC 0, CC 1, BR in bits 0 to 8;
/// [`BITS`] lists them the other way round.
fn word_bit(table_index: usize) -> u16 {
    1 << (BITS.len() - 1 - table_index)
}

/// One run's outcome: the status word after the operation, ACCU 1, which way a jump went,
/// the two bytes of bit operands, and the timer's or counter's value.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Outcome {
    status: u16,
    accu1: u32,
    path: u16,
    bits: u16,
    timer_or_counter: u16,
    timer_or_counter_bit: u16,
}

#[derive(Debug, Clone, Copy)]
struct Draw {
    status: u16,
    accu1: u32,
    accu2: u32,
    bits: u16,
}

struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }
}

/// How the operation is written, and what it needs before the status is set and after the
/// results are taken.
struct Written {
    statement: String,
    /// What `L` reads to see the operation's effect on a timer or counter.
    probe: String,
    before: String,
    after: &'static str,
    accu1: Option<u32>,
}

/// `word` as case `case` writes it; a timer or counter operation takes the case's own, so
/// that no case sees another's edge.
fn written(word: &str, case: usize, label: &str) -> Written {
    let none = String::new;
    let mut accu1 = None;
    let mut probe = "0".to_string();
    let (operand, before, after) = match word {
        "A" | "AN" | "O" | "ON" | "X" | "XN" | "=" | "S" | "R" => ("M 0.0".to_string(), none(), ""),
        "FP" | "FN" => ("M 1.0".to_string(), none(), ""),
        "A(" | "AN(" | "O(" | "ON(" | "X(" | "XN(" => (String::new(), none(), ")"),
        "MCR(" => (String::new(), none(), ")MCR"),
        ")MCR" => (String::new(), "MCR(".to_string(), ""),
        "MCRA" => (String::new(), none(), "MCRD"),
        // A bracket of its own, of known contents, for the `)` to close: CLR, and SAVE for BR.
        ")" => (String::new(), "CLR;\n      SAVE;\n      A(".to_string(), ""),
        "SP" | "SE" | "SD" | "SS" | "SF" | "FR" => {
            accu1 = Some(0x0010);
            probe = format!("T {case}");
            (probe.clone(), none(), "")
        }
        "CU" => {
            probe = format!("C {case}");
            (probe.clone(), none(), "")
        }
        "CD" => {
            // From 5, so that counting down shows.
            probe = format!("C {case}");
            let set = format!("SET;\n      L C#5;\n      S {probe}");
            (probe.clone(), set, "")
        }
        "LC" => ("T 1".to_string(), none(), ""),
        "L" | "T" => ("MW 20".to_string(), none(), ""),
        "BTI" | "BTD" => {
            accu1 = Some(0x1234);
            (String::new(), none(), "")
        }
        "+" => ("5".to_string(), none(), ""),
        "INC" | "DEC" | "NOP" | "BLD" => ("1".to_string(), none(), ""),
        // A count of 0 changes nothing (the table's note); the rows hold for the others.
        "SSI" | "SSD" | "SLW" | "SRW" | "SLD" | "SRD" | "RLD" | "RRD" => {
            ("5".to_string(), none(), "")
        }
        "OPN" => ("DB 1".to_string(), none(), ""),
        _ if word.starts_with('J') || word == "LOOP" => (label.to_string(), none(), ""),
        _ => (String::new(), none(), ""),
    };
    Written {
        statement: format!("{word} {operand}"),
        probe,
        before,
        after,
        accu1,
    }
}

/// The program that runs `word` once for each status word of `draws`, each case with its
/// results at its own place in the flags.
fn program(word: &str, draws: &[Draw]) -> String {
    let mut body = String::new();
    for (case, draw) in draws.iter().enumerate() {
        let label = format!("D{case:03}");
        let end = format!("E{case:03}");
        let written = written(word, case, &label);
        let at = RESULTS + case * RESULT_BYTES;
        let accu1 = written.accu1.unwrap_or(draw.accu1);
        let record = |path: u16| {
            format!(
                "      T MD {};\n      L STW;\n      T MW {at};\n      L {path};\n      T MW {};\n      L MW 0;\n      T MW {};\n      L {};\n      T MW {};\n{}",
                at + 2,
                at + 6,
                at + 8,
                written.probe,
                at + 10,
                probe_bit(&written.probe, at + 12)
            )
        };
        body.push_str(&format!(
            "      L DW#16#{:08X};\n      T MD 10;\n      L DW#16#{accu1:08X};\n      T MD 14;\n      L W#16#{:04X};\n      T MW 0;\n      {};\n      L W#16#{:04X};\n      T STW;\n      L MD 10;\n      L MD 14;\n      {};\n",
            draw.accu2, draw.bits, if written.before.is_empty() { "NOP 0" } else { &written.before }, draw.status, written.statement
        ));
        body.push_str(&record(1));
        body.push_str(&format!("      JU {end};\n{label}: NOP 0;\n"));
        body.push_str(&record(2));
        body.push_str(&format!("{end}: NOP 0;\n"));
        if !written.after.is_empty() {
            body.push_str(&format!("      {};\n", written.after));
        }
    }
    format!(
        "DATA_BLOCK DB 1\nSTRUCT\n  x : INT;\nEND_STRUCT\nBEGIN\nEND_DATA_BLOCK\n\n\
         ORGANIZATION_BLOCK OB 1\nBEGIN\nNETWORK\n{body}END_ORGANIZATION_BLOCK\n"
    )
}

/// The timer's or counter's bit to the word at `at` (the status no longer matters there).
fn probe_bit(probe: &str, at: usize) -> String {
    if probe == "0" {
        return String::new();
    }
    format!(
        "      L 0;\n      T MW {at};\n      CLR;\n      A {probe};\n      = M {}.0;\n",
        at + 1
    )
}

fn outcomes(word: &str, draws: &[Draw]) -> Vec<Outcome> {
    let source = program(word, draws);
    let built = frontend::build_text("effects.awl", &source, profile::find("speed7").unwrap());
    assert!(
        !built.has_errors(),
        "{word}: {:?}",
        built.diagnostics.first()
    );
    let mut cpu = Cpu::new(
        Arc::new(built.compiled.program.clone()),
        Arc::new(built.sources.clone()),
    );
    let ran = cpu.run(RunLimit::Cycles(1));
    assert!(ran.stop.is_none(), "{word}: {:?}", ran.stop);
    let flags = usize::from(cpu.program.layout.flag_base());
    let byte = |at: usize| cpu.image[flags + at];
    let word_at = |at: usize| u16::from_be_bytes([byte(at), byte(at + 1)]);
    (0..draws.len())
        .map(|case| {
            let at = RESULTS + case * RESULT_BYTES;
            Outcome {
                status: word_at(at) & 0x1FF,
                accu1: u32::from(word_at(at + 2)) << 16 | u32::from(word_at(at + 4)),
                path: word_at(at + 6),
                bits: word_at(at + 8),
                timer_or_counter: word_at(at + 10),
                timer_or_counter_bit: word_at(at + 12),
            }
        })
        .collect()
}

/// What the table says a bit comes out as, given what went in.
fn check_written(word: &str, effect: Effect, columns: &[usize], draw: Draw, outcome: Outcome) {
    for &index in columns {
        let mark = effect.writes.as_bytes()[index] as char;
        let bit = word_bit(index);
        let before = draw.status & bit != 0;
        let after = outcome.status & bit != 0;
        let holds = match mark {
            '-' => after == before,
            '0' => !after,
            '1' => after,
            's' => after || !before,
            _ => true,
        };
        assert!(
            holds,
            "{word}: {} is `{mark}` in the table, but went from {before} to {after} (status in {:#05x}, out {:#05x})",
            BITS[index], draw.status, outcome.status
        );
    }
}

/// Whether flipping a bit the table says is not read changed nothing but the bit itself.
fn unread_changes_nothing(effect: Effect, index: usize, plain: Outcome, flipped: Outcome) -> bool {
    let bit = word_bit(index);
    let own = match effect.writes.as_bytes()[index] {
        b'-' => flipped.status & bit == (plain.status & bit) ^ bit,
        b's' => true,
        _ => flipped.status & bit == plain.status & bit,
    };
    own && plain.status & !bit == flipped.status & !bit
        && Outcome { status: 0, ..plain }
            == Outcome {
                status: 0,
                ..flipped
            }
}

/// `count` random draws of the bits in `columns` (the others 0), each followed by itself with
/// one of those bits flipped, for each bit.
fn draws(rng: &mut Rng, count: usize, columns: &[usize]) -> Vec<Draw> {
    let mask: u16 = columns.iter().map(|&index| word_bit(index)).sum();
    let mut draws = Vec::new();
    for _ in 0..count {
        let draw = Draw {
            status: rng.next() as u16 & mask,
            accu1: rng.next() as u32,
            accu2: rng.next() as u32,
            bits: rng.next() as u16,
        };
        draws.push(draw);
        for &index in columns {
            draws.push(Draw {
                status: draw.status ^ word_bit(index),
                ..draw
            });
        }
    }
    draws
}

#[test]
fn the_status_table_says_what_the_vm_does() {
    let mut rng = Rng(0x9E37_79B9_7F4A_7C15);
    for (word, effect) in effects::all() {
        let draws = draws(&mut rng, DRAWS, &effects::STEP7_BITS);
        let found = outcomes(word, &draws);
        let mut read_seen = [false; 9];
        for (group, chunk) in found.chunks(BITS.len() + 1).enumerate() {
            let draw = draws[group * (BITS.len() + 1)];
            check_written(word, effect, &effects::STEP7_BITS, draw, chunk[0]);
            for index in 0..BITS.len() {
                let flipped = chunk[index + 1];
                check_written(
                    word,
                    effect,
                    &effects::STEP7_BITS,
                    draws[group * (BITS.len() + 1) + index + 1],
                    flipped,
                );
                let unchanged = unread_changes_nothing(effect, index, chunk[0], flipped);
                if effect.reads.as_bytes()[index] == b'-' {
                    assert!(
                        unchanged,
                        "{word}: the table says {} is not read, but flipping it changed {:?} into {:?}",
                        BITS[index], chunk[0], flipped
                    );
                } else {
                    read_seen[index] |= !unchanged;
                }
            }
        }
        for (index, seen) in read_seen.iter().enumerate() {
            assert!(
                *seen || effect.reads.as_bytes()[index] == b'-',
                "{word}: the table says {} is read, but no draw showed it",
                BITS[index]
            );
        }
    }
}

/// One STEP 5 run: the status word after the operation (the bits STEP 5 has), ACCU 1, the
/// op that ran next, the flags the operand lies in, and the timer's and counter's state.
#[derive(Debug, Clone, PartialEq, Eq)]
struct Step5Outcome {
    status: u16,
    accu1: u32,
    next_pc: u32,
    bits: u16,
    timer_and_counter: String,
}

/// Sets the drawn registers just before op `at` of `block` runs, and records what it did.
struct Step5Probe {
    block: u16,
    at: u32,
    draw: Draw,
    flags: usize,
    ran: bool,
    outcome: Rc<RefCell<Option<Step5Outcome>>>,
}

impl Probe for Step5Probe {
    fn before(&mut self, cpu: &mut Cpu) -> Flow {
        if self.ran {
            if let Some(outcome) = self.outcome.borrow_mut().as_mut() {
                outcome.next_pc = cpu.level.pc;
            }
            return Flow::Halt;
        }
        if cpu.level.block == self.block && cpu.level.pc == self.at {
            cpu.level.status = Status::from_word(self.draw.status).0;
            cpu.level.accu1 = self.draw.accu1;
            cpu.level.accu2 = self.draw.accu2;
            cpu.image[self.flags..self.flags + 2].copy_from_slice(&self.draw.bits.to_be_bytes());
            cpu.counters[1].value = 5;
        }
        Flow::Go
    }

    fn after(&mut self, cpu: &Cpu, block: u16, pc: u32, _op: Op) -> Flow {
        if block == self.block && pc == self.at {
            self.ran = true;
            let bits = u16::from_be_bytes([cpu.image[self.flags], cpu.image[self.flags + 1]]);
            *self.outcome.borrow_mut() = Some(Step5Outcome {
                status: cpu.level.status.to_word(false),
                accu1: cpu.level.accu1,
                next_pc: u32::MAX,
                bits,
                timer_and_counter: format!("{:?} {:?}", cpu.timers[1], cpu.counters[1]),
            });
        }
        Flow::Go
    }
}

/// How a STEP 5 operation is written here: bit operands in the flags, timer and counter 1.
fn step5_operand(word: &str, example: &'static str) -> &'static str {
    match word {
        "A" | "AN" | "O" | "ON" | "=" | "S" | "R" => "F 0.0",
        "SP" | "SE" | "SD" | "SS" | "SF" | "FR" => "T 1",
        "CU" | "CD" => "C 1",
        "LC" => "T 1",
        "L" | "T" => "FW 20",
        _ if word.starts_with('J') => "=M001",
        _ => example,
    }
}

/// The STEP 5 CPUs an operation is tried on; the first that has it counts.
const STEP5_CPUS: [&str; 3] = ["s5-135u", "sinumerik-840c", "s5-155u"];

fn step5_program(word: &str) -> (String, std::ops::Range<usize>) {
    let info = awl::mnemonics::operation(awl::mnemonics::MnemonicSet::English, word)
        .unwrap_or_else(|| panic!("{word} is a STEP 5 operation"));
    let statement = format!("{word} {}", step5_operand(word, info.example_en));
    let close = if word.ends_with('(') { "      )\n" } else { "" };
    // Jumps to labels are written in function blocks.
    let head =
        "OB 1\n      JU FB 1\n      BE\nFB 1\nNAME :TEST\n      L KT 010.1\n      NOP 0\n      ";
    // An op between the operation and the label, so that a jump shows in the op run next.
    let source = format!("{head}{statement}\n{close}      NOP 0\nM001 :NOP 0\n      BE\n");
    (source, head.len()..head.len() + statement.len())
}

fn step5_outcomes(word: &str, draws: &[Draw]) -> Vec<Step5Outcome> {
    let (source, statement) = step5_program(word);
    let built = STEP5_CPUS
        .iter()
        .map(|cpu| frontend::build_text("twin.awl", &source, profile::find(cpu).unwrap()))
        .find(|built| !built.has_errors())
        .unwrap_or_else(|| panic!("{word} compiles on none of {STEP5_CPUS:?}:\n{source}"));
    let program = Arc::new(built.compiled.program.clone());
    let (block, at) = program
        .blocks
        .iter()
        .enumerate()
        .find_map(|(index, block)| {
            let at = block
                .spans
                .iter()
                .position(|span| span.start as usize == statement.start)?;
            Some((index as u16, at as u32))
        })
        .expect("the operation's op");
    let flags = usize::from(program.layout.flag_base());
    draws
        .iter()
        .map(|draw| {
            let mut cpu = Cpu::new(program.clone(), Arc::new(built.sources.clone()));
            let outcome = Rc::new(RefCell::new(None));
            cpu.probe = Some(Box::new(Step5Probe {
                block,
                at,
                draw: *draw,
                flags,
                ran: false,
                outcome: outcome.clone(),
            }));
            cpu.run(RunLimit::Cycles(1));
            let found = outcome.borrow_mut().take();
            found.unwrap_or_else(|| panic!("{word} ran"))
        })
        .collect()
}

#[test]
fn the_step5_table_says_what_the_vm_does() {
    let mut rng = Rng(0x2545_F491_4F6C_DD1D);
    let step5_bits = effects::STEP5_BITS;
    for (word, effect) in effects::step5_all() {
        let draws = draws(&mut rng, STEP5_DRAWS, &step5_bits);
        let found = step5_outcomes(word, &draws);
        let mask: u16 = step5_bits.iter().map(|&index| word_bit(index)).sum();
        let mut read_seen = [false; 9];
        for (group, chunk) in found.chunks(step5_bits.len() + 1).enumerate() {
            let first = group * (step5_bits.len() + 1);
            let as_step7 = |outcome: &Step5Outcome, draw: Draw| Outcome {
                // The bits STEP 5 lacks are left out of the comparison: they read as drawn.
                status: outcome.status & mask | draw.status & !mask,
                accu1: outcome.accu1,
                path: outcome.next_pc as u16,
                bits: outcome.bits,
                timer_or_counter: 0,
                timer_or_counter_bit: 0,
            };
            let plain = as_step7(&chunk[0], draws[first]);
            check_written(word, effect, &step5_bits, draws[first], plain);
            for (n, &index) in step5_bits.iter().enumerate() {
                let flipped = as_step7(&chunk[n + 1], draws[first + n + 1]);
                check_written(word, effect, &step5_bits, draws[first + n + 1], flipped);
                let unchanged = unread_changes_nothing(effect, index, plain, flipped)
                    && (chunk[0].timer_and_counter == chunk[n + 1].timer_and_counter
                        // What the operation keeps aside is read later, not here.
                        || !effect.keeps.is_empty());
                if effect.reads.as_bytes()[index] == b'-' {
                    assert!(
                        unchanged,
                        "{word}: the table says {} is not read, but flipping it changed {:?} into {:?}",
                        BITS[index],
                        chunk[0],
                        chunk[n + 1]
                    );
                } else {
                    read_seen[index] |= !unchanged;
                }
            }
        }
        for &index in &step5_bits {
            assert!(
                read_seen[index] || effect.reads.as_bytes()[index] == b'-',
                "{word}: the table says {} is read, but no draw showed it",
                BITS[index]
            );
        }
    }
}
