//! Program status on the running CPU (the online page's "Monitor" of a block): the latest
//! invocation of the watched block, recorded by `awl status`'s recorder. The recorder is set at
//! a control point when the page asks and the last recording is older than a refresh; it runs
//! the CPU through the stepping loop until the block's next invocation has ended, then leaves,
//! so the CPU steps at most once per refresh, and not at all while nobody watches.

use std::cell::RefCell;
use std::rc::Rc;
use std::time::{Duration, Instant};

use crate::program_status::{self, BlockRef, Recorder, Recording, StatusError, Window};
use crate::serve::request::{Answer, Refusal, Refused, StatusRow, StatusView};
use crate::vm::{Cpu, Mode};

use super::error::OnlineError;

/// A recording this young answers a request without a new one: the page refreshes about four
/// times a second.
const FRESH: Duration = Duration::from_millis(200);

/// How long (wall time) a request waits for the block to run; then it gets the last
/// recording, or is told that the block did not run.
const WAIT: Duration = Duration::from_secs(2);

/// The block watched, and on which level.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Watched {
    block: u16,
    level: Option<u16>,
}

/// Program status of one block, as the page watches it.
pub struct StatusWatch {
    watched: Watched,
    /// The text the page named the block and the level with, for its messages.
    named: (String, Option<String>),
    /// The recording under way (the recorder is on the CPU) and since when.
    recording: Option<(Rc<RefCell<Recording>>, Instant)>,
    /// The last complete one, and when it was taken.
    last: Option<(Recording, Instant)>,
    waiting: Vec<Answer<StatusView>>,
}

/// The logic block `text` names, or why it names none.
fn block(cpu: &Cpu, text: &str) -> Result<u16, Refusal> {
    let named = BlockRef::parse(text).map_err(|reason| {
        OnlineError::Block {
            text: text.to_string(),
            reason,
        }
        .refusal()
    })?;
    program_status::block::find(&cpu.program, &named).map_err(|error| {
        let kind = match error {
            StatusError::DataBlock { .. } => Refused::BadRequest,
            _ => Refused::NotFound,
        };
        Refusal::of(kind, &error)
    })
}

/// The OB whose level `text` names.
fn level(cpu: &Cpu, text: &str) -> Result<u16, Refusal> {
    let index = block(cpu, text)?;
    let id = cpu.block_id(index);
    match id.kind {
        crate::mnemonics::BlockKind::Ob => Ok(index),
        _ => Err(OnlineError::Level {
            text: text.to_string(),
        }
        .refusal()),
    }
}

impl StatusWatch {
    /// The page asks for `block` (on the level of `level`): answered now from a fresh
    /// recording, else once the block has run again (or [`WAIT`] has passed).
    pub fn ask(
        watch: &mut Option<StatusWatch>,
        cpu: &mut Cpu,
        named: (String, Option<String>),
        reply: Answer<StatusView>,
    ) {
        let watched = match resolve(cpu, &named) {
            Ok(watched) => watched,
            Err(refusal) => {
                let _ = reply.send(Err(refusal));
                return;
            }
        };
        if watch.as_ref().is_none_or(|watch| watch.watched != watched) {
            // Another block: the recorder of the last one, if on the CPU, goes.
            if watch
                .as_ref()
                .is_some_and(|watch| watch.recording.is_some())
            {
                cpu.probe = None;
            }
            *watch = Some(StatusWatch {
                watched,
                named,
                recording: None,
                last: None,
                waiting: Vec::new(),
            });
        }
        let Some(watch) = watch else { return };
        match &watch.last {
            Some((recording, taken)) if taken.elapsed() < FRESH => {
                let _ = reply.send(Ok(watch.view(cpu, recording)));
            }
            _ => {
                watch.waiting.push(reply);
                watch.look(cpu);
            }
        }
    }

    /// At a control point (or in STOP): answers the waiting requests once the recording is
    /// complete, sets the recorder when requests wait for one, and gives up after [`WAIT`].
    pub fn look(&mut self, cpu: &mut Cpu) {
        if self.waiting.is_empty() {
            return;
        }
        let stopped = cpu.mode == Mode::Stop;
        match self.recording.take() {
            Some((recording, _)) if recording.borrow().complete => {
                let recording = recording.take();
                let answer = self.view(cpu, &recording);
                self.last = Some((recording, Instant::now()));
                self.answer(|| Ok(answer.clone()));
            }
            Some((_, since)) if stopped || since.elapsed() > WAIT => {
                cpu.probe = None;
                self.give_up(cpu);
            }
            Some(under_way) => self.recording = Some(under_way),
            None if stopped => self.give_up(cpu),
            None => {
                let ops = cpu.program.blocks[usize::from(self.watched.block)]
                    .code
                    .len();
                let (recorder, recording) =
                    Recorder::new(self.watched.block, ops, Window::At(cpu.clock));
                let recorder = match self.watched.level {
                    Some(level) => recorder.on_level(level),
                    None => recorder,
                };
                cpu.probe = Some(Box::new(recorder.going_on()));
                self.recording = Some((recording, Instant::now()));
            }
        }
    }

    /// The block did not run in time (or the CPU is in STOP): the last recording, if any.
    fn give_up(&mut self, cpu: &Cpu) {
        let last = self
            .last
            .as_ref()
            .map(|(recording, _)| self.view(cpu, recording));
        let (block, level) = &self.named;
        let refusal = OnlineError::DidNotRun {
            block: block.clone(),
            on_level: level
                .as_ref()
                .map(|level| format!(" on the level of {level}"))
                .unwrap_or_default(),
            mode: cpu.mode.name(),
        }
        .refusal();
        self.answer(|| last.clone().ok_or_else(|| refusal.clone()));
    }

    fn answer(&mut self, answer: impl Fn() -> Result<StatusView, Refusal>) {
        for reply in self.waiting.drain(..) {
            // A page that left before its answer needs none.
            let _ = reply.send(answer());
        }
    }

    /// The recording as the page shows it: each statement with what `awl status` prints.
    fn view(&self, cpu: &Cpu, recording: &Recording) -> StatusView {
        let block = &cpu.program.blocks[usize::from(self.watched.block)];
        let step7 = recording.step7;
        let rows = program_status::statements(block, &cpu.sources, recording)
            .into_iter()
            .map(|(line, statement, status)| StatusRow {
                line,
                statement,
                executed: status.is_some(),
                rlo: status.map(|status| u8::from(status.rlo)),
                sta: status.map(|status| u8::from(status.sta)),
                accu1: status.map(|status| program_status::accu(status.accu1, step7)),
                accu2: status.map(|status| program_status::accu(status.accu2, step7)),
                operand: status.and_then(|status| status.operand.clone()),
                passes: status.map(|status| status.runs),
            })
            .collect();
        let invocation = recording.invocation.as_ref();
        StatusView {
            block: block.id.to_string(),
            level: invocation.map_or_else(String::new, |invocation| invocation.level.clone()),
            cycle: invocation.map_or(0, |invocation| invocation.cycle),
            time_ms: invocation.map_or(0.0, |invocation| invocation.t_ns as f64 / 1e6),
            rows,
        }
    }
}

fn resolve(
    cpu: &Cpu,
    (block_text, level_text): &(String, Option<String>),
) -> Result<Watched, Refusal> {
    Ok(Watched {
        block: block(cpu, block_text)?,
        level: level_text
            .as_deref()
            .map(|text| level(cpu, text))
            .transpose()?,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::vm::cycle::RunLimit;
    use tokio::sync::oneshot;

    const PROGRAM: &str = "OB 1\n L KF +5\n T FW 0\n JU FB 1\n BE\nFB 1\nNAME :TEST\n A I 0.0\n JC =SKIP\n L KF +7\n T FW 2\nSKIP :BE\n";

    fn ask(
        watch: &mut Option<StatusWatch>,
        cpu: &mut Cpu,
        block: &str,
    ) -> oneshot::Receiver<Result<StatusView, Refusal>> {
        let (reply, answer) = oneshot::channel();
        StatusWatch::ask(watch, cpu, (block.to_string(), None), reply);
        answer
    }

    #[test]
    fn the_recorder_steps_one_invocation_then_leaves_the_cpu() {
        let mut cpu = crate::serve::testing::cpu(PROGRAM, false);
        // I 0.0 set: the jump skips two lines, which program status marks as not executed.
        cpu.inputs[0] = 1;
        cpu.run(RunLimit::Cycles(1));
        let mut watch = None;
        let mut answer = ask(&mut watch, &mut cpu, "FB 1");
        assert!(cpu.probe.is_some(), "the recorder waits for FB 1");
        cpu.run(RunLimit::Cycles(2));
        assert!(cpu.probe.is_none(), "it left after FB 1's block end");
        let watch_now = watch.as_mut().unwrap();
        watch_now.look(&mut cpu);
        let view = answer.try_recv().unwrap().unwrap();
        assert_eq!((view.block.as_str(), view.level.as_str()), ("FB 1", "OB 1"));
        assert_eq!(view.cycle, 2);
        let executed: Vec<(&str, bool)> = view
            .rows
            .iter()
            .map(|row| (row.statement.as_str(), row.executed))
            .collect();
        assert_eq!(
            executed,
            [
                ("A I 0.0", true),
                ("JC =SKIP", true),
                ("L KF +7", false),
                ("T FW 2", false),
                ("SKIP :BE", true)
            ]
        );
        assert_eq!(view.rows[0].accu1.as_deref(), Some("KH 0005"));
        assert_eq!(view.rows[0].rlo, Some(1));
        assert_eq!(view.rows[2].rlo, None);

        // A refresh within a fresh recording's age is answered from it, without stepping.
        let mut again = ask(&mut watch, &mut cpu, "FB 1");
        assert!(cpu.probe.is_none());
        assert_eq!(again.try_recv().unwrap().unwrap(), view);
    }

    #[test]
    fn an_unknown_block_or_level_is_refused_and_a_stopped_cpu_has_no_status() {
        let mut cpu = crate::serve::testing::cpu(PROGRAM, false);
        let mut watch = None;
        let refused = ask(&mut watch, &mut cpu, "FB 9")
            .try_recv()
            .unwrap()
            .unwrap_err();
        assert_eq!(refused.kind, Refused::NotFound);
        assert_eq!(refused.error, "the program has no FB 9");
        let refused = ask(&mut watch, &mut cpu, "FB")
            .try_recv()
            .unwrap()
            .unwrap_err();
        assert_eq!(refused.code.as_deref(), Some("awl::online::block"));
        let (reply, mut answer) = oneshot::channel();
        let named = ("FB 1".to_string(), Some("FB 1".to_string()));
        StatusWatch::ask(&mut watch, &mut cpu, named, reply);
        let refused = answer.try_recv().unwrap().unwrap_err();
        assert_eq!(refused.code.as_deref(), Some("awl::online::level"));
        // The CPU is in STOP (it has not started): the block cannot run.
        let refused = ask(&mut watch, &mut cpu, "FB 1")
            .try_recv()
            .unwrap()
            .unwrap_err();
        assert_eq!(refused.error, "FB 1 did not run (the CPU is in STOP)");
        assert!(cpu.probe.is_none());
    }
}
