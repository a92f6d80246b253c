//! What ran when, read back from the events in time order: the levels (OB 1's cycle, the
//! interrupt OBs entered on top of it), the blocks open on each, and the operating system's
//! work. The text trace indents by it; the Chrome trace and the timeline picture draw its
//! spans.

use super::{BlockName, Event};

/// A stretch of time something ran or was open.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Span {
    /// A level had the CPU: no higher level ran and the operating system did not work.
    Run { ob: u8, start: u64, end: u64 },
    /// A called block, from its call to its end (interruptions included).
    Block {
        ob: u8,
        /// 1 for a block the level's OB called, 2 for one that block called, …
        depth: usize,
        name: BlockName,
        start: u64,
        end: u64,
    },
    /// A level, from its OB's start to its end (interruptions included).
    Level { ob: u8, start: u64, end: u64 },
    /// The operating system's work: a data cycle, or its time at the cycle end.
    System {
        what: &'static str,
        start: u64,
        end: u64,
    },
    /// A cycle, from its start to its end.
    Cycle { cycle: u64, start: u64, end: u64 },
}

#[derive(Debug)]
struct Level {
    ob: u8,
    /// The text trace's indent of the level's OB.
    base: usize,
    /// The called blocks open on it: name and call time.
    blocks: Vec<(BlockName, u64)>,
    /// When it started: the service, or for OB 1 the first time it had the CPU.
    since: Option<u64>,
    /// Its OB has ended; the level waits for its end (an interrupt data cycle may come).
    ended: bool,
}

#[derive(Debug, Default)]
pub struct Activity {
    levels: Vec<Level>,
    /// Since when the top level has had the CPU, if it has.
    running_since: Option<u64>,
    /// The operating system works until then.
    system_until: u64,
    /// The cycle under way: its number and start.
    cycle: Option<(u64, u64)>,
}

/// What the operating system's time at the cycle end is called.
pub const OS_TIME: &str = "operating-system time";

/// What the wait for the minimum cycle time is called.
pub const CYCLE_WAIT: &str = "wait for the minimum cycle time";

/// What a data cycle is called in a picture.
pub fn data_cycle_name(kind: &str, direction: &str) -> &'static str {
    match (kind, direction) {
        ("process_image", "input") => "process image read (PII)",
        ("process_image", _) => "process image write (PIQ)",
        ("interrupt_input", _) => "interrupt input data cycle",
        _ => "interrupt output data cycle",
    }
}

impl Activity {
    /// The text trace's indent of what runs now: one step per level entered and per block
    /// called on it.
    pub fn indent(&self) -> usize {
        self.levels
            .last()
            .map_or(1, |level| level.base + level.blocks.len())
    }

    /// The OB of the level on top, if one is entered.
    pub fn top_ob(&self) -> Option<u8> {
        self.levels.last().map(|level| level.ob)
    }

    /// Takes in the event at `t_ns`; the spans it closes go to `spans`.
    pub fn apply(&mut self, t_ns: u64, event: &Event, spans: &mut Vec<Span>) {
        match event {
            Event::CycleStart { cycle } => {
                self.close_all(t_ns, spans);
                self.cycle = Some((*cycle, t_ns));
                self.levels.push(Level::new(1, 1, None));
                self.resume(t_ns);
            }
            Event::CycleEnd { .. } => {
                self.close_all(t_ns, spans);
            }
            Event::DataCycle {
                kind,
                direction,
                duration_ns,
            } => self.system(t_ns, *duration_ns, data_cycle_name(kind, direction), spans),
            Event::OsTime { duration_ns } => self.system(t_ns, *duration_ns, OS_TIME, spans),
            Event::CycleWait { duration_ns } => self.system(t_ns, *duration_ns, CYCLE_WAIT, spans),
            Event::BlockCall { to, .. } => {
                if let Some(level) = self.levels.last_mut() {
                    level.blocks.push((BlockName::clone(to), t_ns));
                }
            }
            Event::BlockEnd { .. } => self.block_end(t_ns, spans),
            Event::IrqService { ob, .. } => {
                self.pause(t_ns, spans);
                let base = self.indent() + 1;
                self.levels.push(Level::new(*ob, base, Some(t_ns)));
                self.resume(t_ns);
            }
            Event::IrqEnd { ob, .. } => {
                self.pause(t_ns, spans);
                if self.top_ob() == Some(*ob) {
                    let level = self.levels.pop().expect("the top level");
                    if !level.ended {
                        close_level(level, t_ns, spans);
                    }
                }
                self.resume(t_ns);
            }
            Event::Stop { .. } => self.close_all(t_ns, spans),
            Event::Mode { .. }
            | Event::IrqRequest { .. }
            | Event::IrqLost { .. }
            | Event::IrqIgnored { .. }
            | Event::IrqDiscarded { .. }
            | Event::IrqDelayed { .. }
            | Event::DelayEnd { .. }
            | Event::IrtCall { .. }
            | Event::ModuleEvent { .. }
            | Event::Watch { .. }
            | Event::Input { .. }
            | Event::Output { .. }
            | Event::ClientWrite { .. }
            | Event::Modify { .. }
            | Event::Force { .. }
            | Event::Unforce { .. } => {}
        }
    }

    /// The run ended at `end_ns`: closes what is open.
    pub fn finish(&mut self, end_ns: u64, spans: &mut Vec<Span>) {
        self.close_all(end_ns, spans);
    }

    fn block_end(&mut self, t_ns: u64, spans: &mut Vec<Span>) {
        let Some(level) = self.levels.last_mut() else {
            return;
        };
        if level.end_block(t_ns, spans) {
            return;
        }
        // The level's own OB ended: OB 1's level is over; an interrupt OB's waits for its end.
        self.pause(t_ns, spans);
        let level = self.levels.last_mut().expect("the top level");
        if level.ob == 1 {
            let level = self.levels.pop().expect("the top level");
            close_level(level, t_ns, spans);
        } else {
            level.ended = true;
            spans.push(Span::Level {
                ob: level.ob,
                start: level.since.unwrap_or(t_ns),
                end: t_ns,
            });
        }
    }

    fn system(&mut self, t_ns: u64, duration_ns: u64, what: &'static str, spans: &mut Vec<Span>) {
        self.pause(t_ns, spans);
        spans.push(Span::System {
            what,
            start: t_ns,
            end: t_ns + duration_ns,
        });
        self.system_until = t_ns + duration_ns;
        self.resume(t_ns);
    }

    /// The top level loses the CPU at `t_ns`.
    fn pause(&mut self, t_ns: u64, spans: &mut Vec<Span>) {
        let (Some(since), Some(level)) = (self.running_since.take(), self.levels.last_mut()) else {
            return;
        };
        if t_ns > since {
            level.since.get_or_insert(since);
            spans.push(Span::Run {
                ob: level.ob,
                start: since,
                end: t_ns,
            });
        }
    }

    /// The top level, if one waits to go on, gets the CPU once the operating system is done.
    fn resume(&mut self, t_ns: u64) {
        self.running_since = self
            .levels
            .last()
            .filter(|level| !level.ended)
            .map(|_| t_ns.max(self.system_until));
    }

    fn close_all(&mut self, t_ns: u64, spans: &mut Vec<Span>) {
        self.pause(t_ns, spans);
        while let Some(level) = self.levels.pop() {
            if !level.ended {
                close_level(level, t_ns, spans);
            }
        }
        if let Some((cycle, start)) = self.cycle.take() {
            spans.push(Span::Cycle {
                cycle,
                start,
                end: t_ns,
            });
        }
    }
}

impl Level {
    /// The innermost open block ends at `t_ns`; whether one was open.
    fn end_block(&mut self, t_ns: u64, spans: &mut Vec<Span>) -> bool {
        let Some((name, start)) = self.blocks.pop() else {
            return false;
        };
        spans.push(Span::Block {
            ob: self.ob,
            depth: self.blocks.len() + 1,
            name,
            start,
            end: t_ns,
        });
        true
    }

    fn new(ob: u8, base: usize, since: Option<u64>) -> Self {
        Level {
            ob,
            base,
            blocks: Vec::new(),
            since,
            ended: false,
        }
    }
}

/// A level that ends at `t_ns`: its open blocks and itself.
fn close_level(mut level: Level, t_ns: u64, spans: &mut Vec<Span>) {
    while level.end_block(t_ns, spans) {}
    if let Some(start) = level.since {
        spans.push(Span::Level {
            ob: level.ob,
            start,
            end: t_ns,
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn call(to: &str) -> Event {
        Event::BlockCall {
            from: "".into(),
            to: to.into(),
            depth: 0,
        }
    }

    fn end() -> Event {
        Event::BlockEnd {
            block: "".into(),
            depth: 0,
        }
    }

    /// Fig. 5.2's cycle: PII, OB 1 calls PB 3, OB 3 serviced at PB 3's end, OB 1 ends.
    #[test]
    fn levels_blocks_and_the_system_s_work_become_spans() {
        let mut activity = Activity::default();
        let mut spans = Vec::new();
        let events = [
            (0, Event::CycleStart { cycle: 1 }),
            (
                0,
                Event::DataCycle {
                    kind: "process_image",
                    direction: "input",
                    duration_ns: 10,
                },
            ),
            (20, call("PB 3")),
            (40, end()),
            (
                40,
                Event::IrqService {
                    id: 1,
                    ob: 3,
                    latency_ns: 15,
                    point: "block_end",
                    block: None,
                    waited: None,
                },
            ),
            (50, end()),
            (50, Event::IrqEnd { id: 1, ob: 3 }),
            (60, end()),
        ];
        let mut indents = Vec::new();
        for (t, event) in &events {
            indents.push(activity.indent());
            activity.apply(*t, event, &mut spans);
        }
        activity.finish(70, &mut spans);
        assert_eq!(indents, [1, 1, 1, 2, 1, 2, 2, 1]);
        let block = Span::Block {
            ob: 1,
            depth: 1,
            name: "PB 3".into(),
            start: 20,
            end: 40,
        };
        assert!(spans.contains(&block));
        for span in [
            Span::System {
                what: "process image read (PII)",
                start: 0,
                end: 10,
            },
            Span::Run {
                ob: 1,
                start: 10,
                end: 40,
            },
            Span::Run {
                ob: 3,
                start: 40,
                end: 50,
            },
            Span::Level {
                ob: 3,
                start: 40,
                end: 50,
            },
            Span::Run {
                ob: 1,
                start: 50,
                end: 60,
            },
            Span::Level {
                ob: 1,
                start: 10,
                end: 60,
            },
            Span::Cycle {
                cycle: 1,
                start: 0,
                end: 70,
            },
        ] {
            assert!(spans.contains(&span), "{span:?} in {spans:#?}");
        }
    }
}
