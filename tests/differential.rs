//! Differential test of the VM's ways of running a program: random STL programs, STEP 5 on
//! every STEP 5 CPU and STEP 7 on the SPEED7, with interrupts requested and inputs changed at
//! random simulated times, run in every execution mode of [`EXECUTIONS`] and in both
//! interrupt-point modes. Every mode must write the same trace (the jsonl events) and leave the
//! same state: memory, registers, time, operation count, and the STOP with its cause and place.
//! Native stretches (a loop's passes in one call, leaf blocks called inside them) run against
//! the same program interpreted.
//! Each run is made twice, traced and untraced, as the VM runs a traced program in loops of
//! their own.
//!
//! The programs: bit logic (`A AN O ON`, STEP 7 also `X XN`; `= S R`) on inputs, outputs,
//! flags and timer bits, loads and transfers of words and constants, integer arithmetic,
//! comparisons, forward jumps of every condition, counted loops (backward jumps; now and then
//! one that never ends and meets the watchdog), block calls (STEP 5 `JU`/`JC` of PBs and of FBs
//! with formal operands; STEP 7 `UC`/`CC`/`CALL` of FCs, with and without parameters, and
//! `CALL FB n, DB n` with parameters, image and constant actuals, a static variable and a
//! multi-instance), and
//! timers. Blocks call blocks after them, so calls nest without recursion, but for a rare block
//! that calls itself until the nesting limit stops the CPU.

use std::fmt::Write as _;
use std::sync::Arc;

use awl::compiler::Program;
use awl::frontend;
use awl::profile::{self, Family, InterruptPoints, Profile};
use awl::state::State;
use awl::trace::{TraceFormat, Tracer};
use awl::vm::Cpu;
use awl::vm::cycle::{RunLimit, RunOutcome};
use awl::vm::interrupts::{
    Engine, EngineConfig, Happening, InputChange, InputTarget, Ob13Timing, Scheduled,
};
use proptest::prelude::*;
use serde_json::{Value, json};

mod common;

/// A way of running a compiled program: the program it runs and how it runs it to a limit.
struct Execution {
    name: &'static str,
    program: fn(Program) -> Program,
    run: fn(&mut Cpu, RunLimit) -> RunOutcome,
}

/// Every way of running a program; the first is the reference the others must match. A new
/// way of running is one more entry.
const EXECUTIONS: &[Execution] = &[
    Execution {
        name: "optimised (specialised FB bodies, fused pairs, native stretches)",
        program: |program| program,
        run: Cpu::run,
    },
    Execution {
        name: "optimised, every op interpreted",
        program: Program::interpreted,
        run: Cpu::run,
    },
    Execution {
        name: "op by op as compiled",
        program: Program::unoptimised,
        run: Cpu::run,
    },
];

const POINTS: [InterruptPoints; 2] = [InterruptPoints::Block, InterruptPoints::Operation];

/// The STEP 5 CPUs the programs run on: every one (the SINUMERIK 840C in either mode: OB 2 and
/// OB 5 run only in its special mode).
fn step5_cpus() -> Vec<&'static str> {
    profile::PROFILES
        .iter()
        .filter(|cpu| cpu.family != Family::Speed7)
        .map(|cpu| cpu.name)
        .collect()
}

// ---------------------------------------------------------------------------------------------
// The programs

/// A bit operand: an input, output, flag or timer bit (a timer only read; written, it stands
/// for a flag), or the block's formal bit operand where it has one.
#[derive(Debug, Clone, Copy)]
enum Bit {
    Input(u8),
    Output(u8),
    Flag(u8),
    Timer(u8),
    Formal,
}

/// A word operand or a constant.
#[derive(Debug, Clone, Copy)]
enum Word {
    Flag(u8),
    Input(u8),
    Output(u8),
    Data(u8),
    Constant(i16),
    Formal,
}

#[derive(Debug, Clone)]
enum Step {
    /// `A AN O ON X XN`, by index (STEP 5 has the first four).
    Logic(u8, Bit),
    /// `= S R`, by index.
    Write(u8, Bit),
    Load(Word),
    Transfer(Word),
    Arithmetic(u8),
    Compare(u8),
    /// Starts (or resets) a timer: kind by index, timer number, time in tens of ms.
    Timer(u8, u8, u8),
    /// Calls a block after this one, chosen by the number; one number in 64 has a block call
    /// itself, nesting calls to the limit (a STOP).
    Call(u8, bool),
    /// A forward jump over the steps, its condition by index.
    Skip(u8, Vec<Step>),
    /// The steps run this many times, counted down in a flag word of their own.
    Loop(u8, Vec<Step>),
    /// A jump to itself (or to three NOPs before it): the cycle meets the watchdog.
    Forever,
}

/// The blocks of a program: OB 1, the blocks it may call (each only calls those after it),
/// the startup OB and the interrupt OBs.
#[derive(Debug, Clone)]
struct Plan {
    cyclic: Vec<Step>,
    called: Vec<Vec<Step>>,
    startup: Vec<Step>,
    interrupts: Vec<Vec<Step>>,
}

fn bit() -> impl Strategy<Value = Bit> {
    prop_oneof![
        3 => (0u8..16).prop_map(Bit::Input),
        2 => (0u8..16).prop_map(Bit::Output),
        4 => (0u8..32).prop_map(Bit::Flag),
        1 => (0u8..4).prop_map(Bit::Timer),
        1 => Just(Bit::Formal),
    ]
}

fn word() -> impl Strategy<Value = Word> {
    prop_oneof![
        4 => (0u8..16).prop_map(Word::Flag),
        1 => (0u8..2).prop_map(Word::Input),
        1 => (0u8..2).prop_map(Word::Output),
        // Now and then a data word past the block's end: a STOP.
        1 => prop_oneof![31 => 0u8..8, 1 => Just(8u8)].prop_map(Word::Data),
        3 => prop_oneof![-3i16..=3, any::<i16>()].prop_map(Word::Constant),
        1 => Just(Word::Formal),
    ]
}

/// Straight-line steps: no jump, no call.
fn straight() -> impl Strategy<Value = Step> {
    prop_oneof![
        6 => (0u8..6, bit()).prop_map(|(op, bit)| Step::Logic(op, bit)),
        3 => (0u8..3, bit()).prop_map(|(op, bit)| Step::Write(op, bit)),
        4 => word().prop_map(Step::Load),
        2 => word().prop_map(Step::Transfer),
        2 => (0u8..3).prop_map(Step::Arithmetic),
        1 => (0u8..6).prop_map(Step::Compare),
        1 => (0u8..6, 0u8..4, 1u8..4).prop_map(|(kind, timer, tens)| Step::Timer(kind, timer, tens)),
    ]
}

fn step() -> impl Strategy<Value = Step> {
    let leaf = prop_oneof![
        12 => straight(),
        2 => (any::<u8>(), any::<bool>()).prop_map(|(to, conditional)| Step::Call(to, conditional)),
    ];
    leaf.prop_recursive(2, 24, 8, |inner| {
        prop_oneof![
            (0u8..8, prop::collection::vec(inner.clone(), 1..6))
                .prop_map(|(jump, body)| Step::Skip(jump, body)),
            (1u8..4, prop::collection::vec(inner, 1..8))
                .prop_map(|(passes, body)| Step::Loop(passes, body)),
        ]
    })
}

/// A block's steps; one block in a few dozen loops for ever.
fn block() -> impl Strategy<Value = Vec<Step>> {
    (
        prop::collection::vec(step(), 1..16),
        prop::bool::weighted(0.05),
    )
        .prop_map(|(mut steps, forever)| {
            if forever {
                steps.push(Step::Forever);
            }
            steps
        })
}

fn plan() -> impl Strategy<Value = Plan> {
    (
        block(),
        prop::collection::vec(block(), 1..5),
        prop::collection::vec(straight(), 0..8),
        prop::collection::vec(prop::collection::vec(straight(), 1..8), 8),
    )
        .prop_map(|(cyclic, called, startup, interrupts)| Plan {
            cyclic,
            called,
            startup,
            interrupts,
        })
}

/// Requests and input changes: (time as a fraction of the run in 1/65536, which).
fn happenings() -> impl Strategy<Value = Vec<(u16, u8)>> {
    prop::collection::vec((any::<u16>(), any::<u8>()), 0..24)
}

/// Writes a [`Plan`] as the source text of one dialect.
trait Dialect {
    /// Whether block `index` of the called ones has formal operands (and so may jump, in
    /// STEP 5, where only FBs have labels).
    fn formal(&self, index: usize) -> bool;
    /// Whether block `index` of the called ones (`None`: an OB) may jump.
    fn jumps(&self, index: Option<usize>) -> bool;
    fn bit(&self, bit: Bit, formal: bool, written: bool) -> String;
    fn word(&self, word: Word, formal: bool, written: bool) -> String;
    /// One operation, its label if any.
    fn line(&self, label: Option<&str>, op: &str) -> String;
    fn label(&self, number: usize) -> String;
    fn logic(&self, op: u8) -> &'static str;
    fn arithmetic(&self, op: u8) -> &'static str;
    fn compare(&self, op: u8) -> &'static str;
    fn jump(&self, condition: u8) -> &'static str;
    /// The jump operand to `label`.
    fn target(&self, label: &str) -> String;
    /// Loads the time for a timer, in tens of ms.
    fn timer_value(&self, tens: u8) -> String;
    fn timer(&self, number: u8) -> String;
    /// The flag word counting loop `number`'s passes.
    fn counter(&self, number: usize) -> String;
    /// The text that calls block `index` of the called ones.
    fn call(&self, index: usize, conditional: bool) -> String;
    /// A counted loop around `body`; `label` is free.
    fn counted(&self, passes: u8, counter: &str, label: &str, body: String) -> String;
    /// A block's text around its body.
    fn block(&self, which: Block, body: String) -> String;
    /// The text after every block: data blocks.
    fn trailer(&self) -> String;
    /// Whether called block `index` runs, in every other program, only the straight-line
    /// steps of its body: a leaf block, which a native stretch may call.
    fn straight_now_and_then(&self, _index: usize) -> bool {
        false
    }
}

/// The straight-line steps of `steps` that a native stretch runs: no jump, call or timer, no
/// timer bit, data word or multiplication.
fn straight_steps(steps: &[Step]) -> Vec<Step> {
    steps
        .iter()
        .flat_map(|step| match step {
            Step::Skip(_, body) | Step::Loop(_, body) => straight_steps(body),
            Step::Call(..) | Step::Timer(..) | Step::Forever | Step::Arithmetic(2) => Vec::new(),
            Step::Logic(_, Bit::Timer(_)) => Vec::new(),
            Step::Load(Word::Data(_)) | Step::Transfer(Word::Data(_)) => Vec::new(),
            other => vec![other.clone()],
        })
        .collect()
}

#[derive(Debug, Clone, Copy)]
enum Block {
    Cyclic,
    Called(usize),
    Startup(u8),
    Interrupt(u8),
}

const TIMER_STARTS: [&str; 6] = ["SD", "SE", "SP", "SS", "SF", "R"];
const WRITES: [&str; 3] = ["=", "S", "R"];

/// Renders the steps of one block, numbering its labels and the program's loop counters.
struct Writer<'a> {
    dialect: &'a dyn Dialect,
    /// The block's index among the called ones; `None` for an OB.
    index: Option<usize>,
    called: usize,
    labels: usize,
    counters: &'a mut usize,
    text: String,
}

impl Writer<'_> {
    fn op(&mut self, op: &str) {
        self.text += &self.dialect.line(None, op);
    }

    fn labelled(&mut self, label: &str) {
        self.text += &self.dialect.line(Some(label), "NOP 0");
    }

    fn new_label(&mut self) -> String {
        self.labels += 1;
        self.dialect.label(self.labels)
    }

    fn steps(&mut self, steps: &[Step]) {
        for step in steps {
            self.step(step);
        }
    }

    fn step(&mut self, step: &Step) {
        let d = self.dialect;
        let formal = self.index.is_some_and(|index| d.formal(index));
        match step {
            Step::Logic(op, bit) => {
                let op = d.logic(*op);
                self.op(&format!("{op:<2} {}", d.bit(*bit, formal, false)));
            }
            Step::Write(op, bit) => {
                let op = WRITES[usize::from(*op)];
                self.op(&format!("{op:<2} {}", d.bit(*bit, formal, true)));
            }
            Step::Load(word) => self.op(&format!("L  {}", d.word(*word, formal, false))),
            Step::Transfer(word) => self.op(&format!("T  {}", d.word(*word, formal, true))),
            Step::Arithmetic(op) => self.op(d.arithmetic(*op)),
            Step::Compare(op) => self.op(d.compare(*op)),
            Step::Timer(kind, number, tens) => {
                let kind = TIMER_STARTS[usize::from(*kind)];
                if kind != "R" {
                    self.op(&d.timer_value(*tens));
                }
                self.op(&format!("{kind:<2} {}", d.timer(*number)));
            }
            Step::Call(to, conditional) => {
                let first = self.index.map_or(0, |index| index + 1);
                if let Some(index) = self.index.filter(|_| to % 64 == 63) {
                    self.text += &d.call(index, *conditional);
                } else if first < self.called {
                    let callee = first + usize::from(*to) % (self.called - first);
                    self.text += &d.call(callee, *conditional);
                }
            }
            Step::Skip(condition, body) if d.jumps(self.index) => {
                let label = self.new_label();
                let jump = d.jump(*condition);
                self.op(&format!("{jump:<2} {}", d.target(&label)));
                self.steps(body);
                self.labelled(&label);
            }
            Step::Loop(passes, body) if d.jumps(self.index) => {
                let label = self.new_label();
                let counter = d.counter(*self.counters);
                *self.counters += 1;
                let outer = std::mem::take(&mut self.text);
                self.steps(body);
                let body = std::mem::replace(&mut self.text, outer);
                self.text += &d.counted(*passes, &counter, &label, body);
            }
            // Where jumps are not allowed, a skip is its steps and a loop one pass of them.
            Step::Skip(_, body) | Step::Loop(_, body) => self.steps(body),
            // A jump to itself, or to a few operations before it.
            Step::Forever if d.jumps(self.index) => {
                let label = self.new_label();
                if self.text.len().is_multiple_of(2) {
                    self.text += &d.line(Some(&label), &format!("JU {}", d.target(&label)));
                } else {
                    self.text += &d.line(Some(&label), "NOP 0");
                    self.text += &d.line(None, "NOP 0");
                    self.text += &d.line(None, "NOP 0");
                    self.text += &d.line(None, &format!("JU {}", d.target(&label)));
                }
            }
            Step::Forever => {}
        }
    }
}

fn source(dialect: &dyn Dialect, plan: &Plan, cpu: &Profile) -> String {
    let mut counters = 0;
    let mut render = |index: Option<usize>, steps: &[Step]| {
        let mut writer = Writer {
            dialect,
            index,
            called: plan.called.len(),
            labels: 0,
            counters: &mut counters,
            text: String::new(),
        };
        writer.steps(steps);
        writer.text
    };
    let mut text = dialect.block(Block::Cyclic, render(None, &plan.cyclic));
    for (index, steps) in plan.called.iter().enumerate() {
        let steps = if dialect.straight_now_and_then(index) && steps.len().is_multiple_of(2) {
            straight_steps(steps)
        } else {
            steps.clone()
        };
        text += &dialect.block(Block::Called(index), render(Some(index), &steps));
    }
    if let Some(&ob) = cpu.startup_obs.first() {
        text += &dialect.block(Block::Startup(ob), render(None, &plan.startup));
    }
    for (entry, steps) in cpu.interrupt_obs.iter().zip(plan.interrupts.iter().cycle()) {
        text += &dialect.block(Block::Interrupt(entry.ob), render(None, steps));
    }
    text + &dialect.trailer()
}

/// STEP 5, English mnemonics. Even called blocks are FBs with formal operands (and labels),
/// odd ones PBs.
struct Step5;

impl Step5 {
    fn block_id(index: usize) -> String {
        let kind = if index.is_multiple_of(2) { "FB" } else { "PB" };
        format!("{kind} {}", 10 + index)
    }
}

impl Dialect for Step5 {
    fn formal(&self, index: usize) -> bool {
        index.is_multiple_of(2)
    }

    fn jumps(&self, index: Option<usize>) -> bool {
        index.is_some_and(|index| self.formal(index))
    }

    fn bit(&self, bit: Bit, formal: bool, written: bool) -> String {
        match bit {
            Bit::Input(n) if !written => format!("I {}.{}", n / 8, n % 8),
            Bit::Input(n) | Bit::Output(n) => format!("Q {}.{}", 4 + n / 8, n % 8),
            Bit::Flag(n) => format!("F {}.{}", n / 8, n % 8),
            Bit::Timer(n) if !written => format!("T {n}"),
            Bit::Formal if formal => if written { "=OUT" } else { "=IN" }.into(),
            Bit::Timer(n) => format!("F 7.{}", n % 8),
            Bit::Formal => "F 6.0".into(),
        }
    }

    fn word(&self, word: Word, formal: bool, written: bool) -> String {
        match word {
            Word::Input(n) if !written => format!("IW {}", 2 * n),
            Word::Input(n) | Word::Output(n) => format!("QW {}", 4 + 2 * n),
            Word::Data(n) => format!("DW {n}"),
            Word::Constant(value) if !written => format!("KF {value:+}"),
            Word::Formal if formal => if written { "=RES" } else { "=VAL" }.into(),
            Word::Flag(n) => format!("FW {}", 2 * n),
            Word::Constant(_) | Word::Formal => "FW 30".into(),
        }
    }

    fn line(&self, label: Option<&str>, op: &str) -> String {
        match label {
            Some(label) => format!("{label:<4} :{op}\n"),
            None => format!("      {op}\n"),
        }
    }

    fn label(&self, number: usize) -> String {
        format!("M{number:03}")
    }

    fn logic(&self, op: u8) -> &'static str {
        ["A", "AN", "O", "ON"][usize::from(op % 4)]
    }

    fn arithmetic(&self, op: u8) -> &'static str {
        ["+F", "-F"][usize::from(op % 2)]
    }

    fn compare(&self, op: u8) -> &'static str {
        ["!=F", "><F", ">F", "<F", ">=F", "<=F"][usize::from(op)]
    }

    fn jump(&self, condition: u8) -> &'static str {
        // STEP 5 has no `JCN`: `JC` again in its place.
        ["JU", "JC", "JZ", "JN", "JP", "JM", "JC", "JO"][usize::from(condition)]
    }

    fn target(&self, label: &str) -> String {
        format!("={label}")
    }

    fn timer_value(&self, tens: u8) -> String {
        format!("L  KT {tens:03}.0")
    }

    fn timer(&self, number: u8) -> String {
        format!("T {number}")
    }

    fn counter(&self, number: usize) -> String {
        format!("FW {}", 40 + 2 * number)
    }

    fn call(&self, index: usize, conditional: bool) -> String {
        let op = if conditional { "JC" } else { "JU" };
        let call = self.line(None, &format!("{op} {}", Step5::block_id(index)));
        if !self.formal(index) {
            return call;
        }
        let n = index as u8;
        format!(
            "{call}NAME :F{}\nIN   :I {}.{n}\nOUT  :Q {}.{n}\nVAL  :FW {}\nRES  :FW {}\n",
            10 + index,
            n % 2,
            4 + n % 2,
            2 * n,
            2 + 2 * n,
        )
    }

    fn counted(&self, passes: u8, counter: &str, label: &str, body: String) -> String {
        let line = |op: &str| self.line(None, op);
        [
            line(&format!("L  KF +{passes}")),
            line(&format!("T  {counter}")),
            self.line(Some(label), "NOP 0"),
            body,
            line(&format!("L  {counter}")),
            line("L  KF +1"),
            line("-F"),
            line(&format!("T  {counter}")),
            line(&format!("JP ={label}")),
        ]
        .concat()
    }

    fn block(&self, which: Block, body: String) -> String {
        let (head, opens_db) = match which {
            Block::Cyclic => ("OB 1".to_string(), true),
            Block::Called(index) if self.formal(index) => (
                format!(
                    "FB {number}\nNAME :F{number}\nDES  :IN   I BI\nDES  :OUT  Q BI\n\
                     DES  :VAL  I W\nDES  :RES  Q W",
                    number = 10 + index
                ),
                false,
            ),
            Block::Called(index) => (Step5::block_id(index), false),
            Block::Startup(ob) | Block::Interrupt(ob) => (format!("OB {ob}"), true),
        };
        let open = if opens_db { "      C  DB 9\n" } else { "" };
        format!("{head}\n{open}{body}      BE\n\n")
    }

    fn trailer(&self) -> String {
        let words: String = (0..8)
            .map(|n| format!(" {n}: KF {:+}\n", n * 7 - 20))
            .collect();
        format!("DB 9\n{words}")
    }
}

/// STEP 7 on the SPEED7, English mnemonics. Of every three called blocks, the first is an FC
/// without parameters (`UC`, `CC`), the second an FC with parameters, the third an FB with
/// parameters and a static variable, called on an instance DB of its own.
struct Step7;

impl Step7 {
    fn instance(index: usize) -> bool {
        index % 3 == 2
    }
}

impl Dialect for Step7 {
    fn formal(&self, index: usize) -> bool {
        !index.is_multiple_of(3)
    }

    fn jumps(&self, _: Option<usize>) -> bool {
        true
    }

    fn bit(&self, bit: Bit, formal: bool, written: bool) -> String {
        match bit {
            Bit::Input(n) if !written => format!("I {}.{}", n / 8, n % 8),
            Bit::Input(n) | Bit::Output(n) => format!("Q {}.{}", 4 + n / 8, n % 8),
            Bit::Flag(n) => format!("M {}.{}", n / 8, n % 8),
            Bit::Timer(n) if !written => format!("T {n}"),
            Bit::Formal if formal => if written { "#out_bit" } else { "#in_bit" }.into(),
            Bit::Timer(n) => format!("M 7.{}", n % 8),
            Bit::Formal => "M 6.0".into(),
        }
    }

    fn word(&self, word: Word, formal: bool, written: bool) -> String {
        match word {
            Word::Input(n) if !written => format!("IW {}", 2 * n),
            Word::Input(n) | Word::Output(n) => format!("QW {}", 4 + 2 * n),
            Word::Data(n) => format!("DB9.DBW {}", 2 * n),
            Word::Constant(value) if !written => value.to_string(),
            Word::Formal if formal => if written { "#out_word" } else { "#in_word" }.into(),
            Word::Flag(n) => format!("MW {}", 2 * n),
            Word::Constant(_) | Word::Formal => "MW 30".into(),
        }
    }

    fn line(&self, label: Option<&str>, op: &str) -> String {
        match label {
            Some(label) => format!("{label}: {op};\n"),
            None => format!("      {op};\n"),
        }
    }

    fn label(&self, number: usize) -> String {
        format!("M{number:03}")
    }

    fn logic(&self, op: u8) -> &'static str {
        ["A", "AN", "O", "ON", "X", "XN"][usize::from(op)]
    }

    fn arithmetic(&self, op: u8) -> &'static str {
        ["+I", "-I", "*I"][usize::from(op)]
    }

    fn compare(&self, op: u8) -> &'static str {
        ["==I", "<>I", ">I", "<I", ">=I", "<=I"][usize::from(op)]
    }

    fn jump(&self, condition: u8) -> &'static str {
        ["JU", "JC", "JZ", "JN", "JP", "JM", "JCN", "JO"][usize::from(condition)]
    }

    fn target(&self, label: &str) -> String {
        label.to_string()
    }

    fn timer_value(&self, tens: u8) -> String {
        format!("L  S5T#{}MS", 10 * u16::from(tens))
    }

    fn timer(&self, number: u8) -> String {
        format!("T {number}")
    }

    fn counter(&self, number: usize) -> String {
        format!("MW {}", 40 + 2 * number)
    }

    fn call(&self, index: usize, conditional: bool) -> String {
        let number = 10 + index;
        if !self.formal(index) {
            let op = if conditional { "CC" } else { "UC" };
            return self.line(None, &format!("{op} FC {number}"));
        }
        let n = index as u8;
        let (block, in_word) = if Self::instance(index) {
            // Now and then a constant, which the call copies into the instance DB.
            let in_word = if n.is_multiple_of(2) {
                format!("{}", 100 * u16::from(n))
            } else {
                format!("MW {}", 2 * n)
            };
            (format!("FB {number}, DB {number}"), in_word)
        } else {
            (format!("FC {number}"), format!("MW {}", 2 * n))
        };
        let call = self.line(
            None,
            &format!(
                "CALL {block} (in_bit := I {}.{n}, in_word := {in_word}, out_bit := Q {}.{n}, \
             out_word := MW {})",
                n % 2,
                4 + n % 2,
                2 + 2 * n,
            ),
        );
        if !Self::instance(index) {
            return call;
        }
        // After `CALL FB n, DB n` the DB register holds the instance DB.
        call + &self.line(None, "L  DBW 2") + &self.line(None, "T  MW 34")
    }

    fn counted(&self, passes: u8, counter: &str, label: &str, body: String) -> String {
        // STEP 7's own loop: `LOOP` counts ACCU 1 down and jumps while it is not 0; or, for an
        // even count, the counter counted down by hand and `JP` back, as STEP 5 does.
        if passes.is_multiple_of(2) {
            return [
                self.line(None, &format!("L  {passes}")),
                self.line(None, &format!("T  {counter}")),
                self.line(Some(label), "NOP 0"),
                body,
                self.line(None, &format!("L  {counter}")),
                self.line(None, "L  1"),
                self.line(None, "-I"),
                self.line(None, &format!("T  {counter}")),
                self.line(None, &format!("JP {label}")),
            ]
            .concat();
        }
        [
            self.line(None, &format!("L  {passes}")),
            self.line(Some(label), &format!("T  {counter}")),
            body,
            self.line(None, &format!("L  {counter}")),
            self.line(None, &format!("LOOP {label}")),
        ]
        .concat()
    }

    fn block(&self, which: Block, body: String) -> String {
        match which {
            Block::Called(index) if Self::instance(index) => {
                let number = 10 + index;
                // Now and then it calls a multi-instance of FB 90 at its end.
                let (inner, call) = if body.len().is_multiple_of(2) {
                    (
                        "  inner : FB 90;\n",
                        "      CALL #inner (in_bit := M 5.0, in_word := MW 8, out_bit := M 5.1, \
                         out_word := MW 36);\n",
                    )
                } else {
                    ("", "")
                };
                format!(
                    "FUNCTION_BLOCK FB {number}\n{PARAMETERS}VAR\n  count : INT;\n{inner}END_VAR\n\
                     BEGIN\n{body}      L #count;\n      L 1;\n      +I;\n      T #count;\n{call}\
                     END_FUNCTION_BLOCK\n\nDATA_BLOCK DB {number}\nFB {number}\nBEGIN\n\
                     END_DATA_BLOCK\n\n"
                )
            }
            Block::Called(index) => {
                let interface = if self.formal(index) { PARAMETERS } else { "" };
                format!(
                    "FUNCTION FC {} : VOID\n{interface}BEGIN\n{body}      NOP 0;\nEND_FUNCTION\n\n",
                    10 + index
                )
            }
            Block::Cyclic => ob(1, body),
            Block::Startup(number) | Block::Interrupt(number) => ob(number, body),
        }
    }

    fn straight_now_and_then(&self, index: usize) -> bool {
        self.formal(index)
    }

    fn trailer(&self) -> String {
        // FB 90: the multi-instance the called FBs hold, a leaf on its instance data.
        format!(
            "FUNCTION_BLOCK FB 90\n{PARAMETERS}VAR\n  count : INT;\nEND_VAR\nBEGIN\n\
             A #in_bit;\n= #out_bit;\nL #in_word;\nL #count;\n+I;\nT #count;\nT #out_word;\n\
             END_FUNCTION_BLOCK\n\n\
             DATA_BLOCK DB 9\nSTRUCT\n  words : ARRAY [0..7] OF INT;\nEND_STRUCT;\nBEGIN\n\
             END_DATA_BLOCK\n"
        )
    }
}

/// The parameters of STEP 7's called blocks that have any.
const PARAMETERS: &str = "VAR_INPUT\n  in_bit : BOOL;\n  in_word : INT;\nEND_VAR\n\
                          VAR_OUTPUT\n  out_bit : BOOL;\n  out_word : INT;\nEND_VAR\n";

fn ob(number: u8, body: String) -> String {
    format!("ORGANIZATION_BLOCK OB {number}\nBEGIN\n{body}      NOP 0;\nEND_ORGANIZATION_BLOCK\n\n")
}

// ---------------------------------------------------------------------------------------------
// The runs

/// What a run is set up with besides its program.
struct Setup {
    cpu: &'static Profile,
    /// The run's length and the watchdog, simulated ns.
    duration_ns: u64,
    watchdog_ns: u64,
    /// The SINUMERIK 840C's special mode.
    special_mode: bool,
    schedule: Vec<Scheduled>,
}

impl Setup {
    fn new(cpu: &'static Profile, special_mode: bool, happenings: &[(u16, u8)]) -> Self {
        // An S5 operation takes about a µs, a SPEED7 one 10 ns: the SPEED7 cycles are drawn out
        // to a minimum cycle time, so both runs are some dozen cycles, long enough for timers.
        let (duration_ns, watchdog_ns) = match cpu.family {
            Family::Speed7 => (10_000_000, 1_000_000),
            _ => (40_000_000, 10_000_000),
        };
        let requested = common::requestable_obs(cpu);
        let mut schedule = Vec::new();
        for &(when, which) in happenings {
            let at_ns = duration_ns * u64::from(when) / 65_536;
            let what = match which % 3 {
                0 => Happening::SetInputs(vec![InputChange {
                    target: InputTarget::Process,
                    byte: u16::from(which / 8 % 2),
                    bit: which % 8,
                    bytes: 0,
                    value: u32::from(which / 16 % 2),
                }]),
                _ if cpu.family == Family::Speed7 => Happening::Hardware {
                    module: 1 + u16::from(which / 3 % 2),
                    channel: u16::from(which / 6 % 2),
                    active_for_ns: 2_000 + u64::from(which) * 100,
                },
                _ => Happening::Interrupt {
                    ob: requested[usize::from(which / 3) % requested.len()],
                },
            };
            schedule.push(Scheduled { at_ns, what });
        }
        Setup {
            cpu,
            duration_ns,
            watchdog_ns,
            special_mode: special_mode && cpu.family == Family::Sinumerik840c,
            schedule,
        }
    }

    fn config(&self, points: InterruptPoints) -> EngineConfig {
        EngineConfig {
            points,
            special_mode: self.special_mode,
            ob13: (self.cpu.family == Family::S5_95f).then_some(Ob13Timing {
                interval_ns: 3_000_000,
                delay_ns: 0,
                max_delay_ns: None,
            }),
            hw_modules: vec![(1, 40), (2, 41)],
            ob35_interval_ns: 1_000_000,
            watchdog_ns: self.watchdog_ns,
            min_cycle_ns: if self.cpu.runs_step7() { 250_000 } else { 0 },
            ..EngineConfig::default()
        }
    }
}

/// What a run left: its trace (when traced), one jsonl event a line, and its state at the end.
#[derive(Debug, PartialEq)]
struct Observed {
    trace: Vec<String>,
    end: Value,
}

fn run(
    execution: &Execution,
    built: &frontend::Frontend,
    setup: &Setup,
    points: InterruptPoints,
    traced: bool,
) -> Observed {
    let program = (execution.program)(built.compiled.program.clone());
    let mut cpu = Cpu::new(Arc::new(program), Arc::new(built.sources.clone()));
    cpu.engine = Engine::new(setup.cpu, setup.config(points), setup.schedule.clone());
    let buffer = common::Buffer::default();
    if traced {
        cpu.tracer = Tracer::new(TraceFormat::Jsonl, Box::new(buffer.clone()));
    }
    let outcome = (execution.run)(&mut cpu, RunLimit::Duration(setup.duration_ns));
    let finished = cpu.tracer.finish(cpu.clock);
    assert!(finished.iter().all(|output| output.error.is_none()));
    Observed {
        trace: String::from_utf8(buffer.0.lock().unwrap().clone())
            .expect("a jsonl trace")
            .lines()
            .map(str::to_string)
            .collect(),
        end: end_state(&cpu, &outcome),
    }
}

/// The state a run left: what a PG shows (with the processing levels at a STOP), every byte of
/// the images and flags, the time, the operation count, the STOP with its place, and the
/// longest stretch between block points.
fn end_state(cpu: &Cpu, outcome: &RunOutcome) -> Value {
    json!({
        "state": State::capture(cpu, outcome.stop.as_ref()),
        "stop": format!("{:?}", outcome.stop),
        "mode": format!("{:?}", outcome.mode),
        "cycles": outcome.cycles,
        "clock_ns": outcome.clock_ns,
        "instructions": outcome.instructions,
        "image": cpu.image[..].to_vec(),
        "outputs": cpu.outputs,
        // The longest stretch between two block points, which the bound is made of: native
        // stretches that call mark the points they cross.
        "longest_block": format!("{:?}", cpu.longest_block),
    })
}

/// Where two observations first differ, in words.
fn difference(reference: &Observed, other: &Observed) -> Option<String> {
    if let Some(at) = (0..reference.trace.len().max(other.trace.len()))
        .find(|&at| reference.trace.get(at) != other.trace.get(at))
    {
        let near = |trace: &[String]| {
            trace[at.saturating_sub(3)..(at + 2).min(trace.len())].join("\n    ")
        };
        return Some(format!(
            "trace event {at} differs:\n  reference:\n    {}\n  this:\n    {}",
            near(&reference.trace),
            near(&other.trace)
        ));
    }
    (reference.end != other.end).then(|| {
        let mut text = String::from("state at the end differs:\n");
        let (Value::Object(first), Value::Object(second)) = (&reference.end, &other.end) else {
            unreachable!("an object");
        };
        for (key, value) in first {
            if second.get(key) != Some(value) {
                let _ = writeln!(text, "  {key}: {value}\n  vs {key}: {}", second[key]);
            }
        }
        text
    })
}

/// Builds `source` for `cpu` and runs it in every execution, point mode, traced and not; the
/// first difference from the reference (optimised, traced) if there is one.
fn differences(source: &str, setup: &Setup) -> Result<(), String> {
    let built = frontend::build_text("random.awl", source, setup.cpu);
    if built.has_errors() {
        return Err(format!("does not compile: {:#?}", built.diagnostics));
    }
    for points in POINTS {
        let reference = run(&EXECUTIONS[0], &built, setup, points, true);
        for execution in EXECUTIONS {
            for traced in [true, false] {
                let observed = run(execution, &built, setup, points, traced);
                let compared = Observed {
                    trace: if traced {
                        reference.trace.clone()
                    } else {
                        Vec::new()
                    },
                    end: reference.end.clone(),
                };
                if let Some(difference) = difference(&compared, &observed) {
                    return Err(format!(
                        "{} on {}, {points:?} points, {}: {difference}",
                        execution.name,
                        setup.cpu.name,
                        if traced { "traced" } else { "untraced" },
                    ));
                }
            }
        }
    }
    Ok(())
}

/// 64 cases per dialect; `PROPTEST_CASES` sets another number.
fn config() -> ProptestConfig {
    ProptestConfig {
        cases: std::env::var("PROPTEST_CASES")
            .ok()
            .and_then(|cases| cases.parse().ok())
            .unwrap_or(64),
        ..ProptestConfig::default()
    }
}

proptest! {
    #![proptest_config(config())]

    #[test]
    fn step5_programs_run_the_same_in_every_execution_mode(
        plan in plan(),
        cpu in prop::sample::select(step5_cpus()),
        special_mode in any::<bool>(),
        happenings in happenings(),
    ) {
        let cpu = profile::find(cpu).expect("a STEP 5 CPU");
        let source = source(&Step5, &plan, cpu);
        let result = differences(&source, &Setup::new(cpu, special_mode, &happenings));
        prop_assert!(result.is_ok(), "{}\n\n{source}", result.unwrap_err());
    }

    #[test]
    fn step7_programs_run_the_same_in_every_execution_mode(
        plan in plan(),
        happenings in happenings(),
    ) {
        let cpu = profile::find("speed7").expect("the SPEED7");
        let source = source(&Step7, &plan, cpu);
        let result = differences(&source, &Setup::new(cpu, false, &happenings));
        prop_assert!(result.is_ok(), "{}\n\n{source}", result.unwrap_err());
    }
}
