//! Metamorphic property of the interrupted level's context (SINUMERIK 840C PLC manual, 5.3.1:
//! interrupt servicing between the blocks of the cyclic program; the interrupted level goes on
//! as if nothing had happened).
//!
//! Random cyclic programs (bit logic with brackets and `O`, word arithmetic, condition-code
//! jumps, DB access, block calls) run once without interrupts and once with an interrupt OB
//! that clobbers ACCU 1/2, the RLO and status bits, the bracket stack and the open DB, and
//! writes only its own flag area (F 200 and up). On every CPU and in both interrupt-point
//! modes, with requests at random times — also inside data cycles and the cycle-end work —
//! the cyclic program's I, Q and F outside that area and every data word end the same.

use std::sync::Arc;

use awl::frontend;
use awl::profile::{self, Family, InterruptPoints, Profile};
use awl::trace::{TraceFormat, Tracer};
use awl::vm::Cpu;
use awl::vm::cycle::RunLimit;
use awl::vm::interrupts::{Engine, EngineConfig, Happening, Ob13Timing, Scheduled};
use proptest::prelude::*;

mod common;

/// A small deterministic generator (SplitMix64): one seed gives one program.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    fn below(&mut self, n: u64) -> u64 {
        self.next() % n
    }

    fn pick<'a>(&mut self, items: &[&'a str]) -> &'a str {
        items[self.below(items.len() as u64) as usize]
    }
}

/// Where the cyclic program's own flags end; the interrupt OBs write F 200 and up.
const OB_FLAG_AREA: usize = 200;
const FUNCTION_BLOCKS: u8 = 4;

struct Generator {
    rng: Rng,
    labels: u32,
    /// Writing an FB: the supplementary operations are allowed.
    supplementary: bool,
    out: String,
}

impl Generator {
    fn line(&mut self, text: &str) {
        self.out.push_str("      ");
        self.out.push_str(text);
        self.out.push('\n');
    }

    fn bit_operand(&mut self) -> String {
        match self.rng.below(3) {
            0 => format!("I {}.{}", self.rng.below(4), self.rng.below(8)),
            1 => format!("Q {}.{}", 4 + self.rng.below(4), self.rng.below(8)),
            _ => format!("F {}.{}", self.rng.below(16), self.rng.below(8)),
        }
    }

    fn written_bit(&mut self) -> String {
        if self.rng.below(3) == 0 {
            format!("Q {}.{}", 4 + self.rng.below(4), self.rng.below(8))
        } else {
            format!("F {}.{}", self.rng.below(16), self.rng.below(8))
        }
    }

    fn word_source(&mut self) -> String {
        match self.rng.below(4) {
            0 => format!("FW {}", 2 * self.rng.below(16)),
            1 => format!("DW {}", self.rng.below(8)),
            2 => format!("KF {:+}", self.rng.below(2001) as i64 - 1000),
            _ => format!("KF {:+}", self.rng.below(60001) as i64 - 30000),
        }
    }

    fn word_target(&mut self) -> String {
        match self.rng.below(3) {
            0 => format!("FW {}", 2 * self.rng.below(16)),
            1 => format!("DW {}", self.rng.below(8)),
            _ => format!("QW {}", 4 + 2 * self.rng.below(2)),
        }
    }

    /// A logic string: combinations, `O` alone, brackets; the string is not assigned.
    fn logic(&mut self, depth: u32) {
        for _ in 0..1 + self.rng.below(4) {
            match self.rng.below(8) {
                0 if depth < 3 => {
                    let open = self.rng.pick(&["A(", "O("]);
                    self.line(open);
                    self.logic(depth + 1);
                    // A call only from the outermost bracket: OB 1 and the four FBs then hold
                    // at most 1 + 1 + 1 + 1 + 3 open brackets, the 7 every CPU allows.
                    if depth == 0 && self.rng.below(4) == 0 {
                        self.call();
                        self.logic(depth + 1);
                    }
                    self.line(")");
                }
                1 => self.line("O"),
                _ => {
                    let op = self.rng.pick(&["A", "AN", "O", "ON"]);
                    let operand = self.bit_operand();
                    self.line(&format!("{op}  {operand}"));
                }
            }
        }
    }

    fn assignment(&mut self) {
        let op = self.rng.pick(&["=", "S", "R"]);
        let operand = self.written_bit();
        self.line(&format!("{op}  {operand}"));
    }

    fn arithmetic(&mut self) {
        let (a, b) = (self.word_source(), self.word_source());
        self.line(&format!("L  {a}"));
        self.line(&format!("L  {b}"));
        let basic = ["+F", "-F", "X  F", ":F", "!=F", ">F", "<=F"];
        let supplementary = [
            "AW", "OW", "XOW", "SLW 3", "SRW 2", "CSW", "CFW", "TAK", "I  3", "D  2",
        ];
        let op = if self.supplementary && self.rng.below(2) == 0 {
            self.rng.pick(&supplementary)
        } else {
            self.rng.pick(&basic)
        };
        self.line(op);
        if op.ends_with('F') && (op.starts_with('!') || op.starts_with('>') || op.starts_with('<'))
        {
            self.assignment();
        } else {
            let target = self.word_target();
            self.line(&format!("T  {target}"));
        }
    }

    fn call(&mut self) {
        let target = 1 + self.rng.below(u64::from(FUNCTION_BLOCKS)) as u8;
        let op = self.rng.pick(&["JU", "JC"]);
        self.line(&format!("{op} FB {target}"));
        self.out.push_str("NAME :WORK\n");
    }

    /// A conditional jump forward over a balanced stretch of statements.
    fn jump(&mut self, budget: u32) {
        self.labels += 1;
        let label = format!("M{:03}", self.labels);
        let op = self.rng.pick(&["JZ", "JN", "JP", "JM", "JO", "JC", "JU"]);
        self.line(&format!("{op} ={label}"));
        self.statements(budget / 2);
        self.out.push_str(&format!("{label} :NOP 0\n"));
    }

    fn statements(&mut self, budget: u32) {
        for _ in 0..budget {
            match self.rng.below(9) {
                0 | 1 => {
                    self.logic(0);
                    self.assignment();
                }
                2 => self.logic(0),
                3 | 4 => self.arithmetic(),
                5 => self.call(),
                6 if self.supplementary && budget > 2 => self.jump(budget),
                7 => {
                    let db = self.rng.pick(&["C  DB 10", "C  DB 11"]);
                    self.line(db);
                }
                _ => self.assignment(),
            }
        }
    }

    /// FB n calls only FBs with higher numbers, so nothing recurses; each generated call
    /// names a random FB and is rewritten here to a higher one or dropped.
    fn function_block(&mut self, number: u8) -> String {
        self.out.clear();
        self.supplementary = true;
        let count = 6 + self.rng.below(10) as u32;
        self.statements(count);
        let body = std::mem::take(&mut self.out);
        let mut text = format!("FB {number}\nNAME :WORK\n");
        let mut lines = body.lines().peekable();
        while let Some(line) = lines.next() {
            let call = line.trim_start().strip_prefix("JU FB ").map(|n| ("JU", n));
            let call = call.or(line.trim_start().strip_prefix("JC FB ").map(|n| ("JC", n)));
            if let Some((op, _)) = call {
                lines.next(); // NAME line
                let target = number + 1 + self.rng.below(2) as u8;
                if target <= FUNCTION_BLOCKS {
                    text.push_str(&format!("      {op} FB {target}\nNAME :WORK\n"));
                } else {
                    text.push_str("      NOP 0\n");
                }
                continue;
            }
            text.push_str(line);
            text.push('\n');
        }
        text + "      BE\n"
    }
}

/// The interrupt OB body: every part of the level state clobbered, only F 200 and up written.
fn clobber(rng: &mut Rng) -> String {
    let mut parts = vec![
        format!(
            "      L  KF {:+}\n      L  KF {:+}\n",
            rng.below(30000),
            rng.below(30000)
        ),
        "      L  KF +30000\n      L  KF +30000\n      +F\n      T  FW 210\n".to_string(),
        "      C  DB 12\n      L  DW 1\n      T  FW 212\n".to_string(),
        format!("      A  F 200.{}\n      O  F 201.1\n", rng.below(8)),
        "      O\n      AN F 202.0\n".to_string(),
        "      =  F 205.3\n      JU PB 20\n".to_string(),
        "      L  KH FFFF\n      L  KF +1\n      -F\n".to_string(),
    ];
    let mut body = String::new();
    while !parts.is_empty() {
        body.push_str(&parts.remove(rng.below(parts.len() as u64) as usize));
    }
    // A logic string and a bracket left open when the block ends (BEU before its `)`).
    body + "      A(\n      O  F 203.0\n      A  F 204.0\n      BEU\n      )\n"
}

const INTERRUPT_OBS: [u8; 9] = [2, 3, 4, 5, 6, 7, 13, 40, 41];

fn program(seed: u64) -> String {
    let mut generator = Generator {
        rng: Rng(seed),
        labels: 0,
        supplementary: false,
        out: String::new(),
    };
    let mut text = String::from("OB 1\n      C  DB 10\n");
    generator.out.clear();
    let count = 4 + generator.rng.below(6) as u32;
    generator.statements(count);
    let main = std::mem::take(&mut generator.out);
    // OB 1 calls FB 1 at least once; its own calls may name any FB.
    text.push_str(&main);
    text.push_str("      JU FB 1\nNAME :WORK\n      BE\n");
    for number in 1..=FUNCTION_BLOCKS {
        text.push_str(&generator.function_block(number));
    }
    let body = clobber(&mut generator.rng);
    for ob in INTERRUPT_OBS {
        text.push_str(&format!("OB {ob}\n{body}      BE\n"));
    }
    text.push_str("PB 20\n      L  KF +5\n      T  FW 220\n      C  DB 11\n      BE\n");
    for db in [10, 11, 12] {
        text.push_str(&format!("DB {db}\n"));
        for word in 0..8 {
            text.push_str(&format!("  {word}: KF {:+}\n", word * db - 40));
        }
    }
    text
}

struct Outcome {
    image: Vec<u8>,
    data: Vec<Option<Vec<u16>>>,
    /// Cycle ends and data cycles of a run without interrupts: moments the requests aim at.
    landmarks: Vec<u64>,
    end_ns: u64,
    serviced: u64,
}

fn run(
    source: &str,
    cpu: &'static Profile,
    points: InterruptPoints,
    schedule: Vec<Scheduled>,
    ob13: bool,
) -> Outcome {
    let schedule_is_empty = schedule.is_empty();
    let built = frontend::build_text("random.awl", source, cpu);
    assert!(
        !built.has_errors(),
        "the generator wrote a program with errors: {:?}\n{source}",
        built.diagnostics
    );
    let mut machine = Cpu::new(
        Arc::new(built.compiled.program.clone()),
        Arc::new(built.sources.clone()),
    );
    machine.engine = Engine::new(
        cpu,
        EngineConfig {
            points,
            special_mode: true,
            ob13: ob13.then_some(Ob13Timing {
                interval_ns: 3_000_000,
                delay_ns: 0,
                max_delay_ns: None,
            }),
            hw_modules: vec![(1, 40), (2, 41)],
            hw_addresses: Vec::new(),
            ob35_interval_ns: awl::vm::interrupts::OB35_DEFAULT_NS,
            watchdog_ns: 150_000_000,
            interrupt_inputs: Vec::new(),
            min_cycle_ns: 0,
        },
        schedule,
    );
    // Only the run without interrupts needs its landmarks.
    let trace = common::Buffer::default();
    if schedule_is_empty {
        machine.tracer = Tracer::new(TraceFormat::Jsonl, Box::new(trace.clone()));
    }
    let outcome = machine.run(RunLimit::Cycles(4));
    assert!(
        machine
            .tracer
            .finish(machine.clock)
            .iter()
            .all(|output| output.error.is_none())
    );
    assert!(
        outcome.stop.is_none(),
        "the run stopped: {:?}\n{source}",
        outcome.stop
    );
    let landmarks = trace
        .events()
        .iter()
        .filter(|event| event["ev"] == "cycle_end" || event["ev"] == "data_cycle")
        .map(|event| event["t_ns"].as_u64().unwrap())
        .collect();
    let flags = usize::from(machine.program.layout.flag_base());
    Outcome {
        image: machine.image[..flags + OB_FLAG_AREA].to_vec(),
        data: machine.data_blocks.clone(),
        landmarks,
        end_ns: outcome.clock_ns,
        serviced: machine
            .engine
            .requested_obs()
            .map(|(_, s)| s.serviced)
            .sum(),
    }
}

/// Requests at random times: anywhere in the run, or just after a cycle end or a data cycle of
/// the run without interrupts, where the cycle-end work and data cycles are. All come before
/// the run without interrupts ends, so each is taken before the longer run with them ends.
fn requests(cpu: &Profile, baseline: &Outcome, picks: &[(u64, u64, bool)]) -> Vec<Scheduled> {
    picks
        .iter()
        .map(|&(which, offset, near_landmark)| {
            let at_ns = if near_landmark && !baseline.landmarks.is_empty() {
                let landmark =
                    baseline.landmarks[(which % baseline.landmarks.len() as u64) as usize];
                (landmark + offset % 500_000).min(baseline.end_ns - 1)
            } else {
                offset % baseline.end_ns
            };
            let what = match cpu.family {
                Family::Speed7 => Happening::Hardware {
                    module: 1 + (which % 2) as u16,
                    channel: (which / 2 % 3) as u16,
                    active_for_ns: offset % 50_000,
                },
                Family::S5_95f => Happening::Interrupt { ob: 3 },
                Family::S5 => Happening::Interrupt { ob: 2 },
                Family::Sinumerik840c => Happening::Interrupt {
                    ob: 2 + (which % 6) as u8,
                },
            };
            Scheduled { at_ns, what }
        })
        .collect()
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    #[test]
    fn interrupts_leave_the_cyclic_program_unchanged(
        seed in any::<u64>(),
        picks in prop::collection::vec((any::<u64>(), any::<u64>(), any::<bool>()), 1..12),
    ) {
        let source = program(seed);
        for cpu in profile::PROFILES {
            for points in [InterruptPoints::Block, InterruptPoints::Operation] {
                let baseline = run(&source, cpu, points, Vec::new(), false);
                let schedule = requests(cpu, &baseline, &picks);
                let interrupted = run(&source, cpu, points, schedule, cpu.family == Family::S5_95f);
                let name = format!("{} with {} points", cpu.name, points.name());
                prop_assert!(interrupted.serviced > 0 || cpu.family == Family::Speed7, "{}: nothing serviced", name);
                prop_assert_eq!(&baseline.image, &interrupted.image, "{}: I/Q/F differ\n{}", name, source);
                prop_assert_eq!(&baseline.data, &interrupted.data, "{}: data words differ\n{}", name, source);
            }
        }
    }
}

/// The generator writes programs that compile on every CPU (no case is skipped).
#[test]
fn generated_programs_compile_everywhere() {
    for seed in 0..200 {
        let source = program(seed);
        for cpu in profile::PROFILES {
            let built = frontend::build_text("random.awl", &source, cpu);
            assert!(
                !built.has_errors(),
                "seed {seed} on {}: {:?}\n{source}",
                cpu.name,
                built.diagnostics
            );
        }
    }
}
