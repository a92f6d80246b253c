//! What the browser playground asks of awl: runs, debugger sessions and live runs of files held
//! in memory, each answered with plain data (the page gets it as JSON). The page's WebAssembly
//! module only converts; native tests call these same functions, so the browser and the
//! command line run one code path.

mod debug;
mod diagnostic;
pub mod json;
mod live;
mod words;

use std::cell::RefCell;
use std::collections::BTreeMap;
use std::io::Write;
use std::path::PathBuf;
use std::rc::Rc;
use std::sync::Arc;

use miette::Report;
use serde::{Deserialize, Serialize};

use crate::diagnostics::render_plain;
use crate::profile::{self, InterruptPoints};
use crate::runner::{self, NotRun, Prepared, Ran, RunOptions};
use crate::source::Files;
use crate::state::{self, State};
use crate::timeline;
use crate::trace::{self, TraceFilter};
use crate::vm::Cpu;

pub use debug::{DebugOutcome, debug, debug_reporting};
pub use diagnostic::{Diagnostic, Place};
pub use live::{IoBit, Live, LiveView};
pub use words::{Words, words};

pub use crate::vm::pulse::{Progress, Pulse};

/// A run as the page asks for it: its files by name, which of them to run, and the selectors.
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Request {
    /// Every file the run may read (programs, scenarios, assignment lists), by name.
    pub files: BTreeMap<String, String>,
    /// The program to run when there is no scenario.
    #[serde(default)]
    pub program: Option<String>,
    /// The scenario to run (it names its programs).
    #[serde(default)]
    pub scenario: Option<String>,
    /// A CPU profile's name, overriding the scenario's.
    #[serde(default)]
    pub cpu: Option<String>,
    /// `normal` or `special` (SINUMERIK 840C), overriding the scenario's.
    #[serde(default)]
    pub mode: Option<String>,
    /// `block` or `operation`, overriding the scenario's.
    #[serde(default)]
    pub points: Option<String>,
}

/// What a run has to say, every part ready to show.
#[derive(Debug, Clone, Default, Serialize)]
pub struct Outcome {
    /// Whether the program ran (no source, scenario or request errors).
    pub ran: bool,
    /// The summary `awl run` prints (or why nothing ran).
    pub summary: String,
    /// Errors and warnings, each with its place in a file.
    pub diagnostics: Vec<Diagnostic>,
    /// The STOP report, and the line the CPU stopped at.
    pub stop: Option<String>,
    pub stop_at: Option<Place>,
    /// The final state (`awl run --state`).
    pub state: Option<String>,
    /// The watch table (the scenario's `watch`), when it has rows.
    pub watch: Option<String>,
    /// The timeline picture (SVG).
    pub timeline: Option<String>,
}

/// A request that cannot run as asked: an unknown selector value.
#[derive(Debug, thiserror::Error, miette::Diagnostic)]
pub enum RequestError {
    #[error("no CPU profile `{0}`")]
    #[diagnostic(
        code(awl::playground::cpu),
        help("choose one of the CPU selector's profiles")
    )]
    Cpu(String),
    #[error("no interrupt points `{0}`")]
    #[diagnostic(code(awl::playground::points), help("choose `block` or `operation`"))]
    Points(String),
    #[error("no mode `{0}`")]
    #[diagnostic(code(awl::playground::mode), help("choose `normal` or `special`"))]
    Mode(String),
    #[error("nothing to run")]
    #[diagnostic(
        code(awl::playground::nothing),
        help("write a program, or choose an example")
    )]
    Nothing,
}

impl Request {
    /// The run options this request stands for, its files in memory.
    fn options(&self) -> Result<RunOptions, RequestError> {
        let cpu = match self.cpu.as_deref() {
            None | Some("") => None,
            Some(name) => Some(profile::find(name).ok_or(RequestError::Cpu(name.into()))?),
        };
        let points = match self.points.as_deref() {
            None | Some("") => None,
            Some("block") => Some(InterruptPoints::Block),
            Some("operation") => Some(InterruptPoints::Operation),
            Some(other) => return Err(RequestError::Points(other.into())),
        };
        let special_mode = match self.mode.as_deref() {
            None | Some("") => None,
            Some("normal") => Some(false),
            Some("special") => Some(true),
            Some(other) => return Err(RequestError::Mode(other.into())),
        };
        let scenario = self.scenario.as_deref().filter(|name| !name.is_empty());
        let program = self.program.as_deref().filter(|name| !name.is_empty());
        let files = match (scenario, program) {
            (Some(_), _) => Vec::new(),
            (None, Some(program)) => vec![PathBuf::from(program)],
            (None, None) => return Err(RequestError::Nothing),
        };
        let store = self
            .files
            .iter()
            .map(|(name, text)| (PathBuf::from(name), text.clone().into_bytes()))
            .collect();
        Ok(RunOptions {
            files,
            scenario: scenario.map(PathBuf::from),
            cpu,
            points,
            special_mode,
            store: Files::Memory(Arc::new(store)),
            ..RunOptions::default()
        })
    }

    /// The run set up, or the outcome that tells why it cannot run.
    fn prepare(&self) -> Result<Prepared, Box<Outcome>> {
        let options = self
            .options()
            .map_err(|error| Box::new(not_run(vec![Report::new(error)], "the request".into())))?;
        runner::prepare(&options).map_err(|reason| Box::new(refused(reason)))
    }
}

/// Runs the request to its end (the scenario's length, else a second) or a STOP.
pub fn run(request: &Request) -> Outcome {
    run_with(request, None)
}

/// Runs the request as [`run`] does, the pulse telling how far it has come (the page's
/// progress line); the outcome is the same.
pub fn run_reporting(request: &Request, pulse: Pulse) -> Outcome {
    run_with(request, Some(pulse))
}

fn run_with(request: &Request, pulse: Option<Pulse>) -> Outcome {
    let mut prepared = match request.prepare() {
        Ok(prepared) => prepared,
        Err(outcome) => return *outcome,
    };
    if let Some(pulse) = pulse {
        prepared.cpu.set_pulse(pulse);
    }
    let picture = add_timeline(&mut prepared.cpu);
    let ran = prepared.run(&mut |_| true);
    let mut outcome = finished(&ran);
    outcome.timeline = Some(picture.take());
    outcome
}

/// The outcome of a run that ran (its timeline aside).
fn finished(ran: &Ran) -> Outcome {
    let stop = ran.outcome.stop.as_ref();
    let state = State::capture(&ran.cpu, stop);
    Outcome {
        ran: true,
        summary: crate::report::summary_on_simulated_time(ran),
        diagnostics: ran.warnings.iter().map(Diagnostic::of).collect(),
        stop: stop.map(|stop| render_plain(&runner::stop_report(ran, stop))),
        stop_at: stop.and_then(|stop| Place::of_op(&ran.cpu, stop.block?, stop.pc)),
        state: Some(state::render(&state)),
        watch: (!ran.watch.is_empty()).then(|| ran.watch.render()),
        timeline: None,
    }
}

/// Why a request did not run, as an outcome.
fn refused(reason: NotRun) -> Outcome {
    match reason {
        NotRun::Usage(report) => not_run(vec![report], "the selectors".into()),
        NotRun::SourceErrors(reports, _) => not_run(reports, "the program".into()),
        NotRun::Failed(reports) => not_run(reports, "the scenario or its files".into()),
    }
}

fn not_run(reports: Vec<Report>, whose: String) -> Outcome {
    let diagnostics: Vec<Diagnostic> = reports.iter().map(Diagnostic::of).collect();
    let errors = diagnostics
        .iter()
        .filter(|diagnostic| diagnostic.severity == "error")
        .count();
    Outcome {
        summary: format!(
            "not run: {} in {whose}\n",
            crate::diagnostics::plural(errors as u64, "error")
        ),
        diagnostics,
        ..Outcome::default()
    }
}

/// A buffer the tracer's timeline writes the picture into.
#[derive(Clone, Default)]
struct Picture(Rc<RefCell<Vec<u8>>>);

impl Picture {
    fn take(&self) -> String {
        String::from_utf8_lossy(&self.0.borrow_mut().split_off(0)).into_owned()
    }
}

impl Write for Picture {
    fn write(&mut self, bytes: &[u8]) -> std::io::Result<usize> {
        self.0.borrow_mut().extend_from_slice(bytes);
        Ok(bytes.len())
    }

    fn flush(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

/// Records the run's timeline; the picture is in the buffer once the tracer has finished.
fn add_timeline(cpu: &mut Cpu) -> Picture {
    let picture = Picture::default();
    let levels = trace::levels(cpu.profile, &cpu.program);
    let caption = format!(
        "{} — {} points",
        cpu.profile.name,
        cpu.engine.config.points.name()
    );
    let sink = timeline::sink(
        timeline::Format::Svg,
        Box::new(picture.clone()),
        TraceFilter::all(),
        levels,
        caption,
    );
    cpu.tracer.add("timeline", sink, TraceFilter::all());
    picture
}

/// The CPU profiles the selector offers: name and title.
pub fn cpus() -> Vec<(&'static str, &'static str)> {
    profile::PROFILES
        .iter()
        .map(|profile| (profile.name, profile.title))
        .collect()
}
