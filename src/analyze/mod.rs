//! `awl analyze`: the worst cases computed from the program, before it runs, on the profile's
//! operation times (the ones the VM counts): each block's worst-case execution time with what
//! it calls and its longest stretch between two interrupt points, the response bound of the
//! cyclic level and of each interrupt OB, the deepest call chain against the CPU's limit
//! (STOP `STUEB`), the S5-95F's wake-up risk (STOP `WECK`), the cycle against the watchdog
//! (STOP `ZYK`), and what never runs. Loops need a `; @bound N` comment on their first line;
//! without one the figures that depend on them are unbounded (`null`), never guessed. On a
//! STEP 7 program an SFC 41 DIS_AIRT … SFC 42 EN_AIRT section delays the interrupts for its
//! whole length, so the longest one is a candidate for the response bound.

mod calls;
pub mod flow;
mod text;
pub mod warnings;

use serde::Serialize;

use crate::compiler::Program;
use crate::profile::{Family, InterruptPoints, Nesting, Profile};
use crate::source::SourceSet;

pub use text::render;

use flow::{Airt, Callee, Loop, Measure, Paths, Walker};

use crate::compiler::Op;
use crate::step7::bytecode::S7Code;
use crate::vm::interrupts::control::{DIS_AIRT, EN_AIRT};

/// What the analysis assumes: the CPU and the run's settings.
#[derive(Debug, Clone, Copy)]
pub struct Config {
    pub profile: &'static Profile,
    pub points: InterruptPoints,
    /// SINUMERIK 840C special mode (OB 2 and OB 5 run).
    pub special_mode: bool,
    /// The S5-95F's OB 13 interval, from a scenario's `[ob13]`.
    pub ob13_interval_ns: Option<u64>,
    pub watchdog_ns: u64,
}

impl Config {
    /// The settings a CPU was set up with for a run (its profile and engine).
    pub fn of(cpu: &crate::vm::Cpu) -> Config {
        let engine = &cpu.engine.config;
        Config {
            profile: cpu.profile,
            points: engine.points,
            special_mode: engine.special_mode,
            ob13_interval_ns: engine.ob13.map(|timing| timing.interval_ns),
            watchdog_ns: engine.watchdog_ns,
        }
    }
}

#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct Analysis {
    pub cpu: &'static str,
    pub interrupt_points: &'static str,
    /// The 840C's mode; none on the other CPUs.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub mode: Option<&'static str>,
    /// The longest time from a request to its service while the cyclic level runs (`null`:
    /// unbounded).
    pub response_bound_ns: Option<u64>,
    /// What sets it.
    pub response_bound_by: String,
    pub blocks: Vec<BlockFigures>,
    pub obs: Vec<ObFigures>,
    pub nesting: NestingFigures,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub weck: Option<WeckFigures>,
    pub watchdog: WatchdogFigures,
    pub unused: Unused,
}

#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct BlockFigures {
    pub block: String,
    /// From its start to its end, with everything it calls.
    pub wcet_ns: Option<u64>,
    /// The longest stretch between two interrupt points inside it.
    pub stretch_ns: Option<u64>,
    /// The lines the longest stretch runs through (`null` when unbounded).
    pub stretch_path: Option<Vec<u32>>,
    /// Why a figure is unbounded.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub unbounded: Option<String>,
    pub loops: Vec<LoopFigures>,
    pub calls: Vec<String>,
    /// STEP 7: the longest SFC 41 DIS_AIRT section in it, to the next SFC 42 EN_AIRT or the
    /// block's end, with what it calls (`null` when unbounded); only in a block with DIS_AIRT.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub airt_section: Option<AirtSection>,
}

#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct AirtSection {
    pub ns: Option<u64>,
    /// The first and the last line of the longest section.
    pub lines: Option<[u32; 2]>,
}

#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct LoopFigures {
    /// The loop's first line (the backward jump's target).
    pub line: u32,
    /// Its `@bound`: the most passes; `null` when it has none.
    pub bound: Option<u32>,
}

#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct ObFigures {
    pub ob: u8,
    pub priority: u8,
    /// The OB's run, with its data cycles (S5-95F OB 13).
    pub wcet_ns: Option<u64>,
    /// From its request to its service: the response bound plus the runs of the OBs of the
    /// same or a higher priority that can come first.
    pub response_bound_ns: Option<u64>,
    pub waits_for: Vec<String>,
}

#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct NestingFigures {
    /// Blocks on the deepest call chain, the OB included (`null` with recursion).
    pub max_depth: Option<usize>,
    pub limit: u16,
    pub exceeds: bool,
    pub path: Vec<String>,
    #[serde(skip_serializing_if = "Option::is_none")]
    pub recursion: Option<Vec<String>>,
}

#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct WeckFigures {
    /// `[ob13].interval`; without it there is nothing to compare with.
    pub interval_ns: Option<u64>,
    /// From OB 13's request to its end: the response bound, what can run before or inside
    /// it, OB 13 itself and its data cycles.
    pub ob13_ns: Option<u64>,
    pub margin_ns: Option<i64>,
    pub risk: Option<bool>,
}

#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct WatchdogFigures {
    /// PII, OB 1, PIQ, operating-system time, and each interrupt OB once.
    pub cycle_ns: Option<u64>,
    pub watchdog_ns: u64,
    pub margin_ns: Option<i64>,
    pub risk: Option<bool>,
}

#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct Unused {
    /// Logic blocks no OB calls.
    pub blocks: Vec<String>,
    /// Code no path reaches: after an unconditional jump or block end, with no label to it.
    pub code: Vec<UnusedCode>,
}

#[derive(Debug, Clone, Serialize, PartialEq)]
pub struct UnusedCode {
    pub block: String,
    pub lines: [u32; 2],
}

/// A block's longest DIS_AIRT section: the block, its time (or why unbounded), its lines.
type Section = (usize, Result<u64, String>, Option<[u32; 2]>);

struct Analyzer<'a> {
    program: &'a Program,
    sources: &'a SourceSet,
    config: Config,
    loops: Vec<Vec<Loop>>,
    wcet: Vec<Option<Result<u64, String>>>,
    /// The longest DIS_AIRT section of each block with one, found with its WCET.
    sections: Vec<Option<Paths>>,
    visiting: Vec<bool>,
}

/// Analyses `program` (its source for lines and `@bound` comments) under `config`.
pub fn analyze(program: &Program, sources: &SourceSet, config: Config) -> Analysis {
    let count = program.blocks.len();
    let loops = (0..count)
        .map(|index| {
            let bound_at = |pc: usize| bound_at(program, sources, index, pc);
            flow::loops(&program.blocks[index], &bound_at)
        })
        .collect();
    Analyzer {
        program,
        sources,
        config,
        loops,
        wcet: vec![None; count],
        sections: vec![None; count],
        visiting: vec![false; count],
    }
    .run()
}

/// Whether op `pc` of block `block` calls SFC 41 DIS_AIRT or SFC 42 EN_AIRT.
fn airt_at(program: &Program, block: usize, pc: usize) -> Option<Airt> {
    let Op::S7(S7Code::Sfc { call }) = *program.blocks[block].code.get(pc)? else {
        return None;
    };
    match program.s7.sfc_calls.get(usize::from(call))?.number {
        DIS_AIRT => Some(Airt::Disable),
        EN_AIRT => Some(Airt::Enable),
        _ => None,
    }
}

/// The line of op `pc` of block `block`.
fn line_of(program: &Program, sources: &SourceSet, block: usize, pc: usize) -> u32 {
    let code = &program.blocks[block];
    sources.line_of(code.spans.get(pc).copied().unwrap_or(code.header))
}

/// `; @bound N` on the line of op `pc`: the loop's most passes.
fn bound_at(program: &Program, sources: &SourceSet, block: usize, pc: usize) -> Option<u32> {
    let span = program.blocks[block].spans.get(pc)?;
    let text = sources
        .get(span.file)
        .line(line_of(program, sources, block, pc));
    let after = &text[text.find("@bound")? + "@bound".len()..];
    after.split_whitespace().next()?.parse().ok()
}

impl Analyzer<'_> {
    fn line(&self, block: usize, pc: usize) -> u32 {
        line_of(self.program, self.sources, block, pc)
    }

    fn name(&self, block: usize) -> String {
        self.program.blocks[block].id.to_string()
    }

    /// A block's worst-case time with what it calls; the blocks it calls first.
    fn wcet(&mut self, block: u16) -> Result<u64, String> {
        let index = usize::from(block);
        if let Some(known) = &self.wcet[index] {
            return known.clone();
        }
        if self.visiting[index] {
            return Err(format!("{} calls itself (recursion)", self.name(index)));
        }
        self.visiting[index] = true;
        let mut called: Vec<(u16, Result<u64, String>)> = Vec::new();
        for callee in calls::callees(self.program, block) {
            let time = self.wcet(callee);
            called.push((callee, time));
        }
        self.visiting[index] = false;
        let parameters = calls::parameter_blocks(self.program);
        let callee = |which: Callee| -> Result<u64, String> {
            let time_of = |block: u16| {
                called
                    .iter()
                    .find(|(known, _)| *known == block)
                    .map_or(Ok(0), |(_, time)| time.clone())
            };
            match which {
                Callee::Block(block) => time_of(block),
                Callee::Parameter => parameters
                    .iter()
                    .map(|block| time_of(*block))
                    .try_fold(0, |most, time| time.map(|time| most.max(time))),
            }
        };
        let result = self.walk(index, Measure::Wcet, &callee).value;
        self.wcet[index] = Some(result.clone());
        let code = &self.program.blocks[index].code;
        if (0..code.len()).any(|pc| airt_at(self.program, index, pc) == Some(Airt::Disable)) {
            self.sections[index] = Some(self.walk(index, Measure::Delayed, &callee));
        }
        result
    }

    fn walk(
        &self,
        index: usize,
        measure: Measure,
        callee: &dyn Fn(Callee) -> Result<u64, String>,
    ) -> Paths {
        let line = |pc: usize| self.line(index, pc);
        let airt = |pc: usize| airt_at(self.program, index, pc);
        Walker {
            block: &self.program.blocks[index],
            loops: &self.loops[index],
            callee,
            measure,
            line: &line,
            airt: &airt,
        }
        .run()
    }

    /// The longest stretch inside a block: between two points, or with operation points the
    /// longest operation.
    fn stretch(&self, index: usize) -> Paths {
        let code = &self.program.blocks[index];
        if self.config.points == InterruptPoints::Operation {
            let longest = (0..code.code.len()).max_by_key(|pc| code.cost(*pc));
            return Paths {
                value: Ok(longest.map_or(0, |pc| code.cost(pc))),
                path: longest.into_iter().collect(),
            };
        }
        self.walk(index, Measure::Stretch, &|_| Ok(0))
    }

    /// The interrupt OBs the program has that the CPU runs in this mode: (OB, priority, block).
    fn interrupt_obs(&self) -> Vec<(u8, u8, u16)> {
        let profile = self.config.profile;
        profile
            .interrupt_obs
            .iter()
            .filter(|entry| {
                !(profile.family == Family::Sinumerik840c
                    && !self.config.special_mode
                    && matches!(entry.ob, 2 | 5))
            })
            .filter_map(|entry| {
                let block = self.program.ob(entry.ob)?;
                Some((entry.ob, entry.priority, block))
            })
            .collect()
    }

    fn data_cycles(&self, ob: u8) -> u64 {
        let timings = &self.config.profile.timings;
        if self.config.profile.family == Family::S5_95f && ob == 13 {
            2 * u64::from(timings.data_cycle)
        } else {
            0
        }
    }

    fn run(mut self) -> Analysis {
        let program = self.program;
        let profile = self.config.profile;
        let obs = self.interrupt_obs();
        let mut roots: Vec<u16> = std::iter::once(1)
            .chain(profile.startup_obs.iter().copied())
            .filter_map(|ob| program.ob(ob))
            .collect();
        roots.extend(obs.iter().map(|(_, _, block)| *block));
        let reachable = calls::reachable(program, &roots);

        let mut blocks = Vec::new();
        let mut stretches: Vec<(usize, Result<u64, String>)> = Vec::new();
        let mut sections: Vec<Section> = Vec::new();
        for (index, &runs) in reachable.iter().enumerate() {
            let wcet = self.wcet(index as u16);
            let stretch = self.stretch(index);
            if runs {
                stretches.push((index, stretch.value.clone()));
            }
            let airt_section = self.sections[index].as_ref().map(|section| {
                let lines = section.value.is_ok().then(|| {
                    let first = section.path.first().map(|pc| self.line(index, *pc));
                    let last = section.path.last().map(|pc| self.line(index, *pc));
                    first.zip(last).map(|(first, last)| [first, last])
                });
                AirtSection {
                    ns: section.value.clone().ok(),
                    lines: lines.flatten(),
                }
            });
            if runs && let Some(section) = &self.sections[index] {
                let lines = airt_section.as_ref().and_then(|section| section.lines);
                sections.push((index, section.value.clone(), lines));
            }
            let unbounded = wcet.clone().err().or(stretch.value.clone().err());
            blocks.push(BlockFigures {
                block: self.name(index),
                wcet_ns: wcet.ok(),
                stretch_ns: stretch.value.clone().ok(),
                stretch_path: stretch.value.is_ok().then(|| {
                    let mut lines: Vec<u32> = stretch
                        .path
                        .iter()
                        .map(|pc| self.line(index, *pc))
                        .collect();
                    lines.dedup();
                    lines
                }),
                unbounded,
                loops: self.loops[index]
                    .iter()
                    .map(|l| LoopFigures {
                        line: self.line(index, l.head),
                        bound: l.bound,
                    })
                    .collect(),
                calls: calls::callees(program, index as u16)
                    .into_iter()
                    .map(|callee| self.name(usize::from(callee)))
                    .collect(),
                airt_section,
            });
        }

        let (response, by) = self.response_bound(&stretches, &sections);
        let ob_runs: Vec<(u8, u8, Result<u64, String>)> = obs
            .iter()
            .map(|&(ob, priority, block)| {
                let run = self.wcet(block).map(|ns| ns + self.data_cycles(ob));
                (ob, priority, run)
            })
            .collect();
        let ob_figures = ob_runs
            .iter()
            .map(|&(ob, priority, ref run)| {
                let first: Vec<&(u8, u8, Result<u64, String>)> =
                    ob_runs.iter().filter(|(_, p, _)| *p >= priority).collect();
                let waited: Option<u64> = first
                    .iter()
                    .map(|(_, _, run)| run.clone().ok())
                    .sum::<Option<u64>>();
                ObFigures {
                    ob,
                    priority,
                    wcet_ns: run.clone().ok(),
                    response_bound_ns: response.zip(waited).map(|(a, b)| a + b),
                    waits_for: first.iter().map(|(ob, ..)| format!("OB {ob}")).collect(),
                }
            })
            .collect();
        let nesting = self.nesting(&obs);
        let weck = self.weck(response, &ob_runs);
        let watchdog = self.watchdog(&ob_runs);
        let unused = Unused {
            blocks: (0..program.blocks.len())
                .filter(|index| !reachable[*index])
                .map(|index| self.name(index))
                .collect(),
            code: (0..program.blocks.len())
                .flat_map(|index| {
                    let block = &program.blocks[index];
                    // STEP 7 ends every logic block with a block end of its own after the
                    // last network: after a `BEU` it is never reached, and that is no mistake.
                    let implicit_end = program
                        .s7
                        .step7
                        .then(|| block.code.len().checked_sub(1))
                        .flatten();
                    flow::unreachable(block)
                        .into_iter()
                        .filter(move |&(first, last)| Some(first) != implicit_end || first != last)
                        .map(move |run| (index, run))
                })
                .map(|(index, (first, last))| UnusedCode {
                    block: self.name(index),
                    lines: [self.line(index, first), self.line(index, last)],
                })
                .collect(),
        };
        Analysis {
            cpu: profile.name,
            interrupt_points: self.config.points.name(),
            mode: (profile.family == Family::Sinumerik840c).then_some(
                if self.config.special_mode {
                    "special"
                } else {
                    "normal"
                },
            ),
            response_bound_ns: response,
            response_bound_by: by,
            blocks,
            obs: ob_figures,
            nesting,
            weck,
            watchdog,
            unused,
        }
    }

    /// The operating system's stretches: PII read, PIQ write, its time at the cycle end.
    fn system(&self) -> Vec<(u64, String)> {
        let timings = &self.config.profile.timings;
        let image =
            u64::from(timings.process_image_per_byte) * u64::from(self.program.layout.image_bytes);
        vec![
            (image, "the process image read (PII)".to_string()),
            (image, "the process image write (PIQ)".to_string()),
            (
                u64::from(timings.cycle_overhead),
                "the operating-system time at the cycle end".to_string(),
            ),
        ]
    }

    /// The longest stretch without an interrupt point anywhere: in a block that can run, or
    /// the operating system's work (S5-95F: OB 13's end with its output data cycle).
    fn response_bound(
        &self,
        stretches: &[(usize, Result<u64, String>)],
        sections: &[Section],
    ) -> (Option<u64>, String) {
        let mut candidates = self.system();
        for (index, section, lines) in sections {
            match section {
                Ok(ns) => {
                    let lines = match lines {
                        Some([first, last]) if first == last => format!(", line {first}"),
                        Some([first, last]) => format!(", lines {first}–{last}"),
                        None => String::new(),
                    };
                    let what = format!(
                        "the SFC 41 DIS_AIRT section of {}{lines}, which delays the interrupts",
                        self.name(*index)
                    );
                    candidates.push((*ns, what));
                }
                Err(reason) => return (None, format!("unbounded: {reason}")),
            }
        }
        for (index, stretch) in stretches {
            match stretch {
                Ok(ns) => {
                    let what = match self.config.points {
                        InterruptPoints::Block => {
                            format!("the longest stretch of {}", self.name(*index))
                        }
                        InterruptPoints::Operation => {
                            format!("the longest operation of {}", self.name(*index))
                        }
                    };
                    candidates.push((*ns, what));
                    if self.config.profile.family == Family::S5_95f
                        && self.program.ob(13) == Some(*index as u16)
                    {
                        let end = ns + u64::from(self.config.profile.timings.data_cycle);
                        candidates.push((end, "OB 13's end with its output data cycle".into()));
                    }
                }
                Err(reason) => return (None, format!("unbounded: {reason}")),
            }
        }
        let (ns, what) = candidates
            .into_iter()
            .max_by_key(|(ns, _)| *ns)
            .expect("the operating system's stretches");
        (Some(ns), what)
    }

    fn nesting(&self, obs: &[(u8, u8, u16)]) -> NestingFigures {
        let program = self.program;
        let profile = self.config.profile;
        let limit = profile.nesting_limit;
        let names = |path: &[u16]| path.iter().map(|b| self.name(usize::from(*b))).collect();
        let mut chains: Vec<Vec<u16>> = Vec::new();
        let roots = std::iter::once(1)
            .chain(profile.startup_obs.iter().copied())
            .filter_map(|ob| program.ob(ob));
        let levels = obs.iter().map(|(_, _, block)| *block);
        for root in roots.clone().chain(levels.clone()) {
            match calls::deepest(program, root) {
                Ok(chain) => chains.push(chain),
                Err(cycle) => {
                    return NestingFigures {
                        max_depth: None,
                        limit,
                        exceeds: true,
                        path: Vec::new(),
                        recursion: Some(names(&cycle)),
                    };
                }
            }
        }
        let deepest_cyclic = roots
            .filter_map(|root| calls::deepest(program, root).ok())
            .max_by_key(Vec::len)
            .unwrap_or_default();
        let path = match profile.nesting {
            Nesting::PerLevel => chains.into_iter().max_by_key(Vec::len).unwrap_or_default(),
            // The whole CPU: the levels stack on the cyclic one, each interrupt OB once.
            Nesting::WholeCpu => {
                let mut path = deepest_cyclic;
                for level in levels {
                    path.extend(calls::deepest(program, level).unwrap_or_default());
                }
                path
            }
        };
        let level_roots: Vec<u16> = obs.iter().map(|(_, _, block)| *block).collect();
        let named = path
            .iter()
            .enumerate()
            .map(|(at, block)| {
                let name = self.name(usize::from(*block));
                if at > 0 && level_roots.contains(block) {
                    format!("{name} (interrupt level)")
                } else {
                    name
                }
            })
            .collect();
        NestingFigures {
            max_depth: Some(path.len()),
            limit,
            exceeds: path.len() > usize::from(limit),
            path: named,
            recursion: None,
        }
    }

    fn weck(
        &self,
        response: Option<u64>,
        runs: &[(u8, u8, Result<u64, String>)],
    ) -> Option<WeckFigures> {
        if self.config.profile.family != Family::S5_95f {
            return None;
        }
        let ob13 = runs.iter().find(|(ob, ..)| *ob == 13)?;
        let higher: Option<u64> = runs
            .iter()
            .filter(|(_, priority, _)| *priority > ob13.1)
            .map(|(_, _, run)| run.clone().ok())
            .sum();
        let total = response
            .zip(ob13.2.clone().ok())
            .zip(higher)
            .map(|((a, b), c)| a + b + c);
        let interval = self.config.ob13_interval_ns;
        let margin = total
            .zip(interval)
            .map(|(total, interval)| interval as i64 - total as i64);
        Some(WeckFigures {
            interval_ns: interval,
            ob13_ns: total,
            margin_ns: margin,
            risk: margin.map(|margin| margin < 0),
        })
    }

    fn watchdog(&mut self, runs: &[(u8, u8, Result<u64, String>)]) -> WatchdogFigures {
        let system: u64 = self.system().iter().map(|(ns, _)| ns).sum();
        let ob1 = match self.program.ob(1) {
            Some(block) => self.wcet(block).ok(),
            None => Some(0),
        };
        let interrupts: Option<u64> = runs.iter().map(|(_, _, run)| run.clone().ok()).sum();
        let cycle = ob1.zip(interrupts).map(|(a, b)| a + b + system);
        let watchdog = self.config.watchdog_ns;
        let margin = cycle.map(|cycle| watchdog as i64 - cycle as i64);
        WatchdogFigures {
            cycle_ns: cycle,
            watchdog_ns: watchdog,
            margin_ns: margin,
            risk: margin.map(|margin| margin < 0),
        }
    }
}
