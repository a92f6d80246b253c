//! `awl dap`: a debug adapter over stdio, speaking the Debug Adapter Protocol that VS Code,
//! Neovim (nvim-dap), Helix, Emacs (dape) and JetBrains speak. It translates; the debugger's
//! engine ([`crate::debug::Engine`]) sets the breakpoints and steps, as for `awl debug`.
//!
//! A launch runs the program on the CPU this thread owns, with the engine's probe; while the
//! CPU pauses, the probe answers the editor's requests (simulated time stands still). A
//! reader thread takes the messages in, so the editor's `pause` reaches a running CPU: the
//! probe looks at one flag before each operation. Every request is answered exactly once; a
//! message that is no request is answered with an error, and a client that vanishes ends the
//! adapter.

mod attach;
mod breakpoints;
mod inspect;
pub mod wire;

use std::io::BufReader;
use std::path::PathBuf;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{Receiver, TryRecvError, channel};
use std::thread::JoinHandle;

use miette::Report;
use serde_json::{Value, json};

use crate::debug::command::Command;
use crate::debug::{Engine, Front, Pause, Resume};
use crate::mnemonics::MnemonicSet;
use crate::runner::{self, NotRun, RunOptions};
use crate::source::Files;
use crate::vm::Cpu;
use crate::vm::probe::Flow;
use crate::vm::stop::Stop;

use wire::{Incoming, Outgoing, Request};

/// Where the adapter is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Phase {
    /// Before the run: initialize, launch, breakpoints, configurationDone.
    Setup,
    /// The CPU runs: requests are looked at between two operations.
    Running,
    Paused,
    /// The run has ended (its length, a STOP): the CPU can still be inspected.
    Ended,
}

/// What a request asks of the loop that took it.
#[derive(Debug, Clone, PartialEq)]
enum Next {
    Stay,
    Launch {
        seq: i64,
        arguments: Value,
    },
    Attach {
        seq: i64,
        arguments: Value,
    },
    /// The configuration is done: the run may begin.
    Run,
    Resume(Resume),
    Quit,
}

/// The messages from the editor, taken in by a reader thread.
struct Messages {
    receiver: Receiver<Incoming>,
    /// Set when a message has come (or the input ended): the running CPU looks at it.
    arrived: Arc<AtomicBool>,
}

impl Messages {
    /// Reads `input` on a thread of its own, whose handle comes with the messages.
    fn read(input: impl std::io::Read + Send + 'static) -> (Messages, JoinHandle<()>) {
        let (sender, receiver) = channel();
        let arrived = Arc::new(AtomicBool::new(false));
        let flag = Arc::clone(&arrived);
        let reader = std::thread::spawn(move || {
            let mut input = BufReader::new(input);
            while let Some(message) = wire::read(&mut input) {
                if sender.send(message).is_err() {
                    break;
                }
                flag.store(true, Ordering::Release);
            }
            drop(sender);
            flag.store(true, Ordering::Release);
        });
        (Messages { receiver, arrived }, reader)
    }
}

/// What a served debugger's message did (`awl dap` attached to `awl serve`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Told {
    Stay,
    /// A held CPU goes on (continue, a step).
    GoOn,
    /// The debugger leaves: its breakpoints go with it.
    Detach,
}

pub struct Adapter {
    /// The editor's messages; `None` for a served session, whose messages come over the
    /// online API.
    messages: Option<Messages>,
    pub(crate) out: Outgoing,
    files: Files,
    pub(crate) engine: Engine,
    mnemonics: MnemonicSet,
    breakpoints: breakpoints::Set,
    stop_on_entry: bool,
    /// Pause before the CPU goes to STOP (the `stop` exception filter).
    stop_filter: bool,
    /// The editor asked for a pause while the CPU ran.
    pause_asked: bool,
    /// The session ends: disconnect, terminate, or the client is gone.
    quit: bool,
}

/// Runs the adapter on stdin and stdout until the editor disconnects or goes away.
pub fn serve_stdio() {
    let (messages, _reader) = Messages::read(std::io::stdin());
    // An editor may keep stdin open after its disconnect: the reader ends with the process.
    let out = Outgoing::new(Box::new(std::io::stdout()));
    Adapter::new(Some(messages), out, Files::Disk).serve();
}

/// A whole session on an input that ends (bytes in memory, a file) and any output, its program
/// read from `files` (the fuzz target keeps them in memory); returns when the session is over
/// and the input's reader has stopped.
pub fn session(
    input: impl std::io::Read + Send + 'static,
    out: Box<dyn std::io::Write>,
    files: Files,
) {
    let (messages, reader) = Messages::read(input);
    Adapter::new(Some(messages), Outgoing::new(out), files).serve();
    // The adapter and its receiver are gone: the reader stops at its next message or the end.
    let _ = reader.join();
}

/// The text of a launch that cannot run: every diagnostic, as `awl run` prints them.
fn not_run_text(reason: &NotRun) -> String {
    let reports: Vec<&Report> = match reason {
        NotRun::Usage(report) => vec![report],
        NotRun::SourceErrors(reports, _) | NotRun::Failed(reports) => reports.iter().collect(),
    };
    reports
        .into_iter()
        .map(crate::diagnostics::render_plain)
        .collect()
}

/// The launch configuration: `program` (a file or a list), `scenario`, `cpu`, `symbols`.
fn launch_options(arguments: &Value, files: &Files) -> Result<RunOptions, String> {
    let paths = |value: &Value| -> Result<Vec<PathBuf>, String> {
        match value {
            Value::Null => Ok(Vec::new()),
            Value::String(path) => Ok(vec![PathBuf::from(path)]),
            Value::Array(paths) => paths
                .iter()
                .map(|path| path.as_str().map(PathBuf::from))
                .collect::<Option<_>>()
                .ok_or_else(|| "`program` and `symbols` take a path or a list of paths".into()),
            _ => Err("`program` and `symbols` take a path or a list of paths".into()),
        }
    };
    let files_given = paths(&arguments["program"])?;
    let scenario = arguments["scenario"].as_str().map(PathBuf::from);
    if files_given.is_empty() && scenario.is_none() {
        return Err(
            "the launch configuration names no `program` (a file or a list of files) and no `scenario`"
                .into(),
        );
    }
    let cpu = match arguments["cpu"].as_str() {
        None => None,
        Some(name) => Some(crate::profile::find(name).ok_or_else(|| {
            format!(
                "`{name}` is no CPU awl knows; `awl cpus` lists them: {}",
                crate::profile::names().join(", ")
            )
        })?),
    };
    Ok(RunOptions {
        files: files_given,
        scenario,
        cpu,
        symbols: paths(&arguments["symbols"])?,
        store: files.clone(),
        ..RunOptions::default()
    })
}

/// What the adapter can do, told at `initialize`.
fn capabilities() -> Value {
    json!({
        "supportsConfigurationDoneRequest": true,
        "supportsFunctionBreakpoints": true,
        "supportsConditionalBreakpoints": true,
        "supportsHitConditionalBreakpoints": true,
        "supportsLogPoints": true,
        "supportsEvaluateForHovers": true,
        "supportsSetVariable": true,
        "supportsTerminateRequest": true,
        "exceptionBreakpointFilters": [
            { "filter": "interrupt", "label": "Interrupt OB serviced", "default": false,
              "description": "Pause when an interrupt OB starts being serviced" },
            { "filter": "request", "label": "Interrupt requested", "default": false,
              "description": "Pause when an interrupt OB is requested" },
            { "filter": "stop", "label": "CPU goes to STOP", "default": true,
              "description": "Pause where the CPU goes to STOP, with its cause" },
        ],
    })
}

impl Adapter {
    fn new(messages: Option<Messages>, out: Outgoing, files: Files) -> Adapter {
        Adapter {
            messages,
            out,
            files,
            engine: Engine::default(),
            mnemonics: MnemonicSet::English,
            breakpoints: breakpoints::Set::default(),
            stop_on_entry: false,
            stop_filter: true,
            pause_asked: false,
            quit: false,
        }
    }

    /// The session of a debugger attached to `awl serve`: its messages come, and its answers
    /// go, over the online API.
    pub(crate) fn served(mnemonics: MnemonicSet) -> Adapter {
        let mut adapter = Adapter::new(None, Outgoing::queued(), Files::Disk);
        adapter.mnemonics = mnemonics;
        adapter.engine.resume = Resume::Continue;
        adapter
    }

    /// Answers the served session's `attach`.
    pub(crate) fn attached(&mut self, seq: i64, cpu: &Cpu) {
        self.out.respond(seq, "attach", json!({}));
        self.out.event("initialized", json!({}));
        let text = format!(
            "attached to the {} in {}\n",
            cpu.profile.name,
            cpu.mode.name()
        );
        self.out.output("console", &text);
    }

    /// Answers a served session's message; `held`: a breakpoint holds the CPU.
    pub(crate) fn served_message(&mut self, cpu: &mut Cpu, held: bool, message: Incoming) -> Told {
        let phase = if held { Phase::Paused } else { Phase::Running };
        match self.take(Some(cpu), phase, message) {
            Next::Resume(resume) => {
                self.engine.resume = resume;
                Told::GoOn
            }
            Next::Quit => Told::Detach,
            _ => Told::Stay,
        }
    }

    /// What the served session has to send.
    pub(crate) fn take_queued(&mut self) -> Vec<Value> {
        self.out.take_queued()
    }

    /// Why the CPU pauses before its next operation, if it does (the editor's pause, a
    /// breakpoint, a step's end); what log points said goes to the console.
    pub(crate) fn pause_here(&mut self, cpu: &Cpu) -> Option<Pause> {
        let interrupted = std::mem::take(&mut self.pause_asked);
        let pause = self.engine.pause_reason(cpu, interrupted);
        for text in self.engine.take_logged() {
            self.log(&text);
        }
        pause
    }

    /// The next message, waiting for it; `None` once the client is gone.
    fn next_message(&mut self) -> Option<Incoming> {
        let message = self
            .messages
            .as_ref()
            .and_then(|messages| messages.receiver.recv().ok());
        if message.is_none() || self.out.broken {
            self.quit = true;
            return None;
        }
        message
    }

    /// The next message, waiting at most `longest` for it.
    fn next_message_within(
        &mut self,
        longest: std::time::Duration,
    ) -> Result<Incoming, std::sync::mpsc::RecvTimeoutError> {
        let Some(messages) = &self.messages else {
            return Err(std::sync::mpsc::RecvTimeoutError::Disconnected);
        };
        messages.receiver.recv_timeout(longest)
    }

    /// The whole session: setup, the run, after the run.
    fn serve(mut self) {
        let Some(prepared) = self.setup() else { return };
        self.run(prepared);
    }

    /// Takes requests until the editor's configuration is done after a launch; the program
    /// ready to run.
    fn setup(&mut self) -> Option<runner::Prepared> {
        let mut launched: Option<runner::Prepared> = None;
        while !self.quit {
            let message = self.next_message()?;
            let cpu = launched.as_mut().map(|prepared| &mut prepared.cpu);
            match self.take(cpu, Phase::Setup, message) {
                Next::Launch { seq, arguments } if launched.is_none() => {
                    launched = self.launch(seq, &arguments);
                }
                Next::Launch { seq, .. } | Next::Attach { seq, .. } if launched.is_some() => {
                    self.out
                        .refuse(seq, "launch", "the program is launched already");
                }
                Next::Attach { seq, arguments } => {
                    let command = "attach".to_string();
                    let request = Request {
                        seq,
                        command,
                        arguments,
                    };
                    if attach::attach(self, request) {
                        return None;
                    }
                }
                Next::Run if launched.is_some() => return launched,
                Next::Quit => return None,
                _ => {}
            }
        }
        None
    }

    /// Reads the launch's program; refuses the launch with the diagnostics when it cannot run.
    fn launch(&mut self, seq: i64, arguments: &Value) -> Option<runner::Prepared> {
        let prepared = launch_options(arguments, &self.files)
            .and_then(|options| runner::prepare(&options).map_err(|reason| not_run_text(&reason)));
        match prepared {
            Ok(mut prepared) => {
                for warning in prepared.take_warnings() {
                    self.out
                        .output("console", &crate::diagnostics::render_plain(&warning));
                }
                self.mnemonics = prepared.mnemonics;
                self.stop_on_entry = arguments["stopOnEntry"].as_bool().unwrap_or(false);
                self.out.respond(seq, "launch", json!({}));
                self.out.event("initialized", json!({}));
                Some(prepared)
            }
            Err(text) => {
                self.out.output("stderr", &text);
                self.out.refuse(seq, "launch", &text);
                None
            }
        }
    }

    /// Runs the program with the engine's probe, then ends the session.
    fn run(self, mut prepared: runner::Prepared) {
        let stop_on_entry = self.stop_on_entry;
        let adapter = std::rc::Rc::new(std::cell::RefCell::new(self));
        adapter.borrow_mut().engine.resume = if stop_on_entry {
            Resume::Start
        } else {
            Resume::Continue
        };
        let probe = crate::debug::Debugger(std::rc::Rc::clone(&adapter));
        prepared.cpu.probe = Some(Box::new(probe));
        let mut ran = prepared.run(&mut |_| true);
        ran.cpu.probe = None;
        adapter.borrow_mut().end();
    }

    /// The CPU is about to go to STOP: its report in the console, and with the `stop` filter
    /// a pause with the cause as the exception's text; whether the editor is told of it.
    pub(crate) fn stop_reached(&mut self, cpu: &mut Cpu, stop: &Stop) -> bool {
        // The loop has left the level past the faulting operation; the editor shows that
        // operation (the level is cleared at the next start anyway).
        if stop.block == Some(cpu.level.block) {
            cpu.level.pc = stop.pc;
        }
        let report = runner::cpu_stop_report(cpu, stop);
        self.out
            .output("stderr", &crate::diagnostics::render_plain(&report));
        if !self.stop_filter || self.quit {
            return false;
        }
        self.out.event(
            "stopped",
            json!({
                "reason": "exception",
                "description": format!("STOP: {}", stop.cause.code()),
                "text": report.to_string(),
                "threadId": inspect::running_thread(cpu),
                "allThreadsStopped": true,
            }),
        );
        true
    }

    /// Answers the editor while the CPU pauses, until it lets the CPU go on (`true`) or leaves.
    fn paused(&mut self, cpu: &mut Cpu) -> bool {
        while let Some(message) = self.next_message() {
            match self.take(Some(cpu), Phase::Paused, message) {
                Next::Resume(resume) => {
                    self.engine.resume = resume;
                    return true;
                }
                Next::Quit => break,
                _ => {}
            }
        }
        false
    }

    /// Tells the editor the session is over, then answers until it disconnects or goes.
    fn end(&mut self) {
        if self.quit {
            return;
        }
        self.out.event("exited", json!({ "exitCode": 0 }));
        self.out.event("terminated", json!({}));
        while let Some(message) = self.next_message() {
            if self.take(None, Phase::Ended, message) == Next::Quit {
                return;
            }
        }
    }

    /// Answers one message.
    fn take(&mut self, cpu: Option<&mut Cpu>, phase: Phase, message: Incoming) -> Next {
        match message {
            Incoming::Malformed { seq, reason } => {
                self.out.refuse(seq, "", &reason);
                Next::Stay
            }
            Incoming::Request(request) => self.request(cpu, phase, request),
        }
    }

    fn request(&mut self, cpu: Option<&mut Cpu>, phase: Phase, request: Request) -> Next {
        let Request {
            seq,
            command,
            arguments,
        } = request;
        let command = command.as_str();
        let ok = |adapter: &mut Adapter, body: Value| adapter.out.respond(seq, command, body);
        match (command, cpu) {
            ("initialize", _) => ok(self, capabilities()),
            ("launch", _) if phase == Phase::Setup => return Next::Launch { seq, arguments },
            ("attach", _) if phase == Phase::Setup => return Next::Attach { seq, arguments },
            ("launch" | "attach", _) => {
                self.out
                    .refuse(seq, command, "the session has launched its program already");
            }
            ("configurationDone", cpu) => {
                ok(self, json!({}));
                if phase == Phase::Setup && cpu.is_some() {
                    return Next::Run;
                }
            }
            ("disconnect" | "terminate", _) => {
                ok(self, json!({}));
                self.quit = true;
                return Next::Quit;
            }
            ("setExceptionBreakpoints", _) => {
                let filters = breakpoints::filters(&arguments);
                self.engine.filters = filters.engine;
                self.stop_filter = filters.stop;
                ok(self, json!({ "breakpoints": filters.verified }));
            }
            (command @ ("setBreakpoints" | "setFunctionBreakpoints"), cpu) => {
                let body = match cpu {
                    Some(cpu) => {
                        let set = if command == "setBreakpoints" {
                            breakpoints::Set::set_lines
                        } else {
                            breakpoints::Set::set_functions
                        };
                        set(
                            &mut self.breakpoints,
                            &mut self.engine,
                            cpu,
                            &arguments,
                            self.mnemonics,
                        )
                    }
                    None => breakpoints::before_launch(&arguments["breakpoints"]),
                };
                ok(self, body);
            }
            ("threads", Some(cpu)) => ok(self, inspect::threads_body(cpu)),
            ("threads", None) => ok(self, json!({ "threads": [] })),
            ("pause", _) => {
                self.pause_asked = phase == Phase::Running;
                ok(self, json!({}));
            }
            ("continue" | "next" | "stepIn" | "stepOut", Some(cpu)) if phase == Phase::Paused => {
                let stepping = match command {
                    "next" => Command::Next,
                    "stepIn" => Command::Step,
                    "stepOut" => Command::Finish,
                    _ => Command::Continue,
                };
                let body = if command == "continue" {
                    json!({ "allThreadsContinued": true })
                } else {
                    json!({})
                };
                ok(self, body);
                return Next::Resume(Resume::after(cpu, &stepping));
            }
            ("continue" | "next" | "stepIn" | "stepOut", _) if phase == Phase::Ended => {
                ok(self, json!({}));
                return Next::Resume(Resume::Continue);
            }
            ("continue" | "next" | "stepIn" | "stepOut", _) if phase == Phase::Running => {
                ok(self, json!({ "allThreadsContinued": true }));
            }
            ("stackTrace" | "scopes" | "variables" | "evaluate" | "setVariable", Some(cpu))
                if matches!(phase, Phase::Paused | Phase::Ended) =>
            {
                match self.inspect(cpu, command, &arguments) {
                    Ok(body) => ok(self, body),
                    Err(reason) => self.out.refuse(seq, command, &reason),
                }
            }
            (
                "stackTrace" | "scopes" | "variables" | "evaluate" | "setVariable" | "continue"
                | "next" | "stepIn" | "stepOut",
                _,
            ) => {
                let reason = match phase {
                    Phase::Running => "the CPU is running: pause it first",
                    _ => "no program runs yet: launch one first",
                };
                self.out.refuse(seq, command, reason);
            }
            (other, _) => {
                let reason = format!("awl's debug adapter does not know the request `{other}`");
                self.out.refuse(seq, command, &reason);
            }
        }
        Next::Stay
    }

    /// The requests that look at (or write into) a paused CPU.
    fn inspect(
        &mut self,
        cpu: &mut Cpu,
        command: &str,
        arguments: &Value,
    ) -> Result<Value, String> {
        let number = |name: &str| {
            arguments[name]
                .as_i64()
                .ok_or_else(|| format!("`{command}` needs `{name}`, a number"))
        };
        let text = |name: &str| {
            arguments[name]
                .as_str()
                .ok_or_else(|| format!("`{command}` needs `{name}`, a string"))
        };
        match command {
            "stackTrace" => inspect::stack_trace(cpu, number("threadId")?)
                .ok_or_else(|| "no OB level has that thread id".to_string()),
            "scopes" => Ok(inspect::scopes(number("frameId")?)),
            "variables" => inspect::variables(cpu, number("variablesReference")?, self.mnemonics)
                .map(|variables| inspect::variables_body(&variables))
                .ok_or_else(|| "no scope has that reference".to_string()),
            "setVariable" => {
                let reference = number("variablesReference")?;
                let (name, value) = (text("name")?, text("value")?);
                let variables = inspect::variables(cpu, reference, self.mnemonics)
                    .ok_or_else(|| "no scope has that reference".to_string())?;
                let operand = variables
                    .iter()
                    .find(|variable| variable.name == name)
                    .and_then(|variable| variable.operand.clone())
                    .ok_or_else(|| format!("`{name}` cannot be set; set an operand (`set MW 4 7` in the debug console)"))?;
                let value = self.write(cpu, &operand, value)?;
                Ok(json!({ "value": value }))
            }
            _ => self.evaluate(cpu, text("expression")?),
        }
    }

    /// `MW 4` (its value), `set MW 4 7` (writes it).
    fn evaluate(&mut self, cpu: &mut Cpu, expression: &str) -> Result<Value, String> {
        if let Some(Ok(Command::Set { operand, value })) = crate::debug::command::parse(expression)
        {
            let shown = self.write(cpu, &operand, &value.to_string())?;
            return Ok(json!({ "result": shown, "variablesReference": 0 }));
        }
        let operands = crate::address::operand::list(expression);
        let text = crate::debug::show::print(cpu, &operands, self.mnemonics)?;
        let result = match operands.as_slice() {
            [_] => text
                .trim_end()
                .split_once(" = ")
                .map_or(text.trim_end(), |(_, value)| value)
                .to_string(),
            _ => text.trim_end().replace('\n', ", "),
        };
        Ok(json!({ "result": result, "variablesReference": 0 }))
    }

    /// Writes `value` into `operand` as `set` does; the value it holds then.
    fn write(&mut self, cpu: &mut Cpu, operand: &str, value: &str) -> Result<String, String> {
        let number = crate::debug::condition::parse_number(value)
            .ok_or_else(|| format!("`{value}` is not a number"))?;
        let text = crate::debug::force(cpu, operand, number, self.mnemonics)?;
        let text = text.trim_end();
        Ok(text
            .split_once(" = ")
            .map_or(text, |(_, value)| value)
            .to_string())
    }

    /// Tells the editor why the CPU paused.
    pub(crate) fn stopped(&mut self, cpu: &Cpu, pause: &Pause) {
        let mut body = json!({
            "threadId": inspect::running_thread(cpu),
            "allThreadsStopped": true,
            "description": pause.to_string(),
        });
        let (reason, hit) = match pause {
            Pause::Interrupted => ("pause", None),
            Pause::Breakpoint(n) => (self.breakpoints.reason(*n), Some(vec![*n])),
            Pause::Events(events) => {
                let hit: Vec<usize> = events.iter().filter_map(|event| event.breakpoint).collect();
                body["text"] = json!(pause.to_string());
                if hit.is_empty() {
                    ("exception", None)
                } else {
                    ("breakpoint", Some(hit))
                }
            }
            Pause::Resumed(Resume::Start) => ("entry", None),
            Pause::Resumed(_) => ("step", None),
        };
        body["reason"] = json!(reason);
        if let Some(hit) = hit {
            body["hitBreakpointIds"] = json!(hit);
        }
        self.out.event("stopped", body);
    }
}

impl Front for Adapter {
    fn engine(&mut self) -> &mut Engine {
        &mut self.engine
    }

    /// Answers what came while the CPU ran; whether the editor asked for a pause (or left).
    fn interrupted(&mut self, cpu: &mut Cpu) -> bool {
        let Some(messages) = &self.messages else {
            return std::mem::take(&mut self.pause_asked);
        };
        if !messages.arrived.swap(false, Ordering::Acquire) {
            return false;
        }
        while let Some(messages) = &self.messages {
            match messages.receiver.try_recv() {
                Ok(message) => {
                    if self.take(Some(cpu), Phase::Running, message) == Next::Quit {
                        break;
                    }
                }
                Err(TryRecvError::Empty) => break,
                Err(TryRecvError::Disconnected) => {
                    self.quit = true;
                    break;
                }
            }
        }
        std::mem::take(&mut self.pause_asked) || self.quit
    }

    fn pause(&mut self, cpu: &mut Cpu, pause: &Pause) -> Flow {
        if self.quit {
            return Flow::Halt;
        }
        self.stopped(cpu, pause);
        if self.paused(cpu) {
            Flow::Go
        } else {
            Flow::Halt
        }
    }

    fn stopping(&mut self, cpu: &mut Cpu, stop: &Stop) {
        if self.stop_reached(cpu, stop) {
            self.paused(cpu);
        }
    }

    fn log(&mut self, text: &str) {
        self.out.output("console", &format!("{text}\n"));
    }
}
