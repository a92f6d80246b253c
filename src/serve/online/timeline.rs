//! The live timeline: the last seconds of the OB levels as the static timeline
//! ([`crate::timeline`]) draws them, requests, services and client writes marked. While the
//! page watches it, a tracer output keeps the recent events (tracing runs the CPU through the
//! traced variant of its loop); ten seconds after the last request the output goes and the
//! loop is the plain one again.

use std::cell::RefCell;
use std::collections::VecDeque;
use std::rc::Rc;
use std::time::{Duration, Instant};

use tokio::sync::oneshot;

use crate::timeline::Recorder;
use crate::trace::{Event, Sink, TraceFilter};
use crate::vm::{Cpu, Mode};

/// The tracer output's name.
const OUTPUT: &str = "online timeline";

/// The most simulated time a request may ask for, and kept.
pub const MOST_SECONDS: f64 = 60.0;

/// The most events kept (a SPEED7 running a short cycle makes some 100 000 a second).
const MOST_EVENTS: usize = 500_000;

/// The first answer waits this long (wall time) for events to be recorded.
const FIRST_WAIT: Duration = Duration::from_millis(500);

/// Without a request for this long, the recording stops.
const IDLE: Duration = Duration::from_secs(10);

type Events = Rc<RefCell<VecDeque<(u64, Event)>>>;

/// The tracer output that keeps the recent events.
struct Keep {
    events: Events,
}

impl Sink for Keep {
    fn event(&mut self, t_ns: u64, event: &Event) -> std::io::Result<()> {
        let mut events = self.events.borrow_mut();
        let oldest = t_ns.saturating_sub((MOST_SECONDS * 1e9) as u64);
        while events
            .front()
            .is_some_and(|(t, _)| *t < oldest || events.len() >= MOST_EVENTS)
        {
            events.pop_front();
        }
        events.push_back((t_ns, event.clone()));
        Ok(())
    }

    fn finish(&mut self, _end_ns: u64) -> std::io::Result<()> {
        Ok(())
    }
}

/// Removes the tracer output that keeps the events: the loop runs untraced again (unless a
/// trace file is written).
pub fn stop_recording(cpu: &mut Cpu) {
    cpu.tracer.remove(OUTPUT);
}

/// The recording, while the page watches the timeline.
pub struct LiveTimeline {
    events: Events,
    started: Instant,
    last_asked: Instant,
    /// Requests that came before [`FIRST_WAIT`] had passed: the seconds each asks for.
    waiting: Vec<(f64, oneshot::Sender<String>)>,
}

impl LiveTimeline {
    /// The page asks for the last `seconds`: recording starts with the first request, whose
    /// answer waits until there is something to draw.
    pub fn ask(
        live: &mut Option<LiveTimeline>,
        cpu: &mut Cpu,
        seconds: f64,
        reply: oneshot::Sender<String>,
    ) {
        let timeline = live.get_or_insert_with(|| {
            let events = Events::default();
            let keep = Keep {
                events: Rc::clone(&events),
            };
            cpu.tracer.add(OUTPUT, Box::new(keep), TraceFilter::all());
            LiveTimeline {
                events,
                started: Instant::now(),
                last_asked: Instant::now(),
                waiting: Vec::new(),
            }
        });
        timeline.last_asked = Instant::now();
        timeline.waiting.push((seconds, reply));
        timeline.look(cpu);
    }

    /// At a control point: answers the waiting requests once the first wait is over (at once
    /// in STOP, where nothing more comes).
    pub fn look(&mut self, cpu: &Cpu) {
        if self.waiting.is_empty() || self.started.elapsed() < FIRST_WAIT && cpu.mode != Mode::Stop
        {
            return;
        }
        for (seconds, reply) in std::mem::take(&mut self.waiting) {
            // A page that left before its answer needs none.
            let _ = reply.send(self.svg(cpu, seconds));
        }
    }

    /// Ends the recording when nobody asked for a while.
    pub fn look_now_and_then(live: &mut Option<LiveTimeline>, cpu: &mut Cpu) {
        if live.as_ref().is_some_and(|timeline| {
            timeline.waiting.is_empty() && timeline.last_asked.elapsed() > IDLE
        }) {
            stop_recording(cpu);
            *live = None;
        }
    }

    /// The last `seconds` up to the CPU's clock, drawn from the first cycle start before them
    /// (so the drawing knows which blocks are open).
    fn svg(&self, cpu: &Cpu, seconds: f64) -> String {
        let end = cpu.clock;
        let from = end.saturating_sub((seconds.clamp(0.001, MOST_SECONDS) * 1e9) as u64);
        let window = TraceFilter::all().window(Some(from), Some(end));
        let levels = crate::trace::levels(cpu.profile, &cpu.program);
        let caption = format!(
            "the last {seconds} s, up to {}",
            crate::trace::format_ms(end)
        );
        let mut recorder = Recorder::new(window, levels, caption);
        let events = self.events.borrow();
        let begin = events
            .iter()
            .rposition(|(t, event)| *t <= from && matches!(event, Event::CycleStart { .. }))
            .unwrap_or(0);
        for (t, event) in events.iter().skip(begin) {
            recorder.record(*t, event);
        }
        recorder.svg(end)
    }
}
