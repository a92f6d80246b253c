//! The Chrome trace-event JSON that Perfetto (ui.perfetto.dev) and chrome://tracing open:
//! each priority level a thread (its OB's number is the thread id, the operating system's
//! work is thread 0), blocks and levels as nested complete slices, requests and services as
//! instants joined by a flow, counters for inputs, outputs and watched values. Times are in
//! microseconds with nanosecond fractions.

use std::collections::{BTreeMap, BTreeSet};
use std::io::Write;

use serde::Serialize;
use serde_json::{Value, json};

use super::activity::{Activity, Span};
use super::{Event, Kind, Levels, Sink, TraceFilter};

/// The one process; its threads are the levels.
const PID: u32 = 1;
/// The operating system's thread: cycles, data cycles, its time at the cycle end.
const SYSTEM_TID: u32 = 0;

/// One trace event as the trace-event format defines it.
#[derive(Debug, Serialize)]
struct TraceEvent {
    name: String,
    ph: &'static str,
    ts: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    dur: Option<f64>,
    pid: u32,
    tid: u32,
    #[serde(skip_serializing_if = "Option::is_none")]
    cat: Option<&'static str>,
    #[serde(skip_serializing_if = "Option::is_none")]
    id: Option<u64>,
    /// An instant's scope: `t` thread, `g` global.
    #[serde(skip_serializing_if = "Option::is_none")]
    s: Option<&'static str>,
    /// A flow end binds to the slice that encloses it.
    #[serde(skip_serializing_if = "Option::is_none")]
    bp: Option<&'static str>,
    #[serde(skip_serializing_if = "Value::is_null")]
    args: Value,
}

impl TraceEvent {
    fn new(ph: &'static str, name: String, t_ns: u64, tid: u32) -> Self {
        TraceEvent {
            name,
            ph,
            ts: micros(t_ns),
            dur: None,
            pid: PID,
            tid,
            cat: None,
            id: None,
            s: None,
            bp: None,
            args: Value::Null,
        }
    }

    fn slice(name: String, start: u64, end: u64, tid: u32, cat: &'static str) -> Self {
        TraceEvent {
            dur: Some(micros(end - start)),
            cat: Some(cat),
            ..TraceEvent::new("X", name, start, tid)
        }
    }

    fn instant(name: String, t_ns: u64, tid: u32, args: Value) -> Self {
        TraceEvent {
            cat: Some("interrupt"),
            s: Some("t"),
            args,
            ..TraceEvent::new("i", name, t_ns, tid)
        }
    }

    fn metadata(name: &'static str, tid: u32, args: Value) -> Self {
        TraceEvent {
            args,
            ..TraceEvent::new("M", name.to_string(), 0, tid)
        }
    }
}

fn micros(ns: u64) -> f64 {
    ns as f64 / 1000.0
}

pub struct Chrome {
    out: Box<dyn Write>,
    filter: TraceFilter,
    levels: Levels,
    activity: Activity,
    spans: Vec<Span>,
    /// Threads named so far.
    named: BTreeSet<u32>,
    /// Requests shown and not yet serviced: id → when, and the thread that ran then.
    flows: BTreeMap<u64, (u64, u32)>,
    written: usize,
}

impl Chrome {
    pub fn new(out: Box<dyn Write>, filter: TraceFilter, levels: Levels) -> Self {
        Chrome {
            out,
            filter,
            levels,
            activity: Activity::default(),
            spans: Vec::new(),
            named: BTreeSet::new(),
            flows: BTreeMap::new(),
            written: 0,
        }
    }

    fn write(&mut self, event: &TraceEvent) -> std::io::Result<()> {
        let lead: &[u8] = if self.written == 0 {
            b"{\"displayTimeUnit\":\"ns\",\"traceEvents\":[\n"
        } else {
            b",\n"
        };
        self.written += 1;
        self.out.write_all(lead)?;
        serde_json::to_writer(&mut self.out, event).map_err(std::io::Error::other)
    }

    /// Names the thread of `tid` (and sorts it: the highest priority on top) before its
    /// first event.
    fn thread(&mut self, tid: u32) -> std::io::Result<u32> {
        if self.named.insert(tid) {
            if self.written == 0 {
                let process = TraceEvent::metadata("process_name", tid, json!({"name": "awl"}));
                self.write(&process)?;
            }
            let known = self.levels.iter().find(|level| u32::from(level.ob) == tid);
            let (name, sort) = match (tid, known) {
                (SYSTEM_TID, _) => ("operating system".to_string(), 1000),
                (_, Some(level)) => (
                    format!("OB {} ({})", level.ob, level.what),
                    300 - u32::from(level.priority),
                ),
                (ob, None) => (format!("OB {ob}"), 300),
            };
            self.write(&TraceEvent::metadata(
                "thread_name",
                tid,
                json!({ "name": name }),
            ))?;
            self.write(&TraceEvent::metadata(
                "thread_sort_index",
                tid,
                json!({ "sort_index": sort }),
            ))?;
        }
        Ok(tid)
    }

    fn span(&mut self, span: Span) -> std::io::Result<()> {
        let (kind, name, start, end, tid, cat) = match span {
            Span::Run { .. } => return Ok(()),
            Span::Block {
                ob,
                name,
                start,
                end,
                ..
            } => (
                Kind::Blocks,
                name.to_string(),
                start,
                end,
                u32::from(ob),
                "block",
            ),
            Span::Level { ob, start, end } => (
                Kind::Blocks,
                format!("OB {ob}"),
                start,
                end,
                u32::from(ob),
                "level",
            ),
            Span::System { what, start, end } => (
                Kind::Cycles,
                what.to_string(),
                start,
                end,
                SYSTEM_TID,
                "system",
            ),
            Span::Cycle { cycle, start, end } => (
                Kind::Cycles,
                format!("cycle {cycle}"),
                start,
                end,
                SYSTEM_TID,
                "cycle",
            ),
        };
        let Some((start, end)) = self.filter.clip(start, end) else {
            return Ok(());
        };
        if !self.filter.shows_kind(kind) {
            return Ok(());
        }
        let tid = self.thread(tid)?;
        self.write(&TraceEvent::slice(name, start, end, tid, cat))
    }

    /// The instants, flows and counters of an event at `t_ns`, shown by the filter.
    fn marks(&mut self, t_ns: u64, event: &Event, running: u32) -> std::io::Result<()> {
        match event {
            Event::IrqRequest { id, ob, .. } => {
                self.on_level(*ob, "requested", t_ns, event)?;
                self.flows.insert(*id, (t_ns, running));
                Ok(())
            }
            Event::IrqService { id, ob, .. } => {
                self.on_level(*ob, "serviced", t_ns, event)?;
                // The flow from the request, which a lost or ignored request never gets.
                let Some((requested_at, from)) = self.flows.remove(id) else {
                    return Ok(());
                };
                let from = self.thread(from)?;
                self.write(&TraceEvent {
                    cat: Some("interrupt"),
                    id: Some(*id),
                    ..TraceEvent::new("s", format!("OB {ob} request"), requested_at, from)
                })?;
                self.write(&TraceEvent {
                    cat: Some("interrupt"),
                    id: Some(*id),
                    bp: Some("e"),
                    ..TraceEvent::new("f", format!("OB {ob} request"), t_ns, u32::from(*ob))
                })
            }
            Event::IrqLost { id, ob, .. } => {
                self.flows.remove(id);
                self.on_level(*ob, "request lost", t_ns, event)
            }
            Event::IrqIgnored { id, ob, .. } => {
                self.flows.remove(id);
                self.on_level(*ob, "request ignored", t_ns, event)
            }
            Event::IrqDiscarded { id, ob, .. } => {
                self.flows.remove(id);
                self.on_level(*ob, "request discarded", t_ns, event)
            }
            Event::IrqDelayed { ob, .. } => self.on_level(*ob, "request delayed", t_ns, event),
            Event::DelayEnd { ob, .. } => self.on_level(*ob, "delays end", t_ns, event),
            Event::IrtCall { ob, name, .. } => self.on_level(*ob, name, t_ns, event),
            Event::ModuleEvent { ob, .. } => self.on_level(*ob, "module event", t_ns, event),
            Event::Mode { from, to, .. } => self.global(format!("mode {from} → {to}"), t_ns, event),
            Event::Stop { cause, .. } => self.global(format!("STOP {cause}"), t_ns, event),
            Event::Watch { numbers, .. } => {
                for (operand, value) in numbers {
                    self.counter(operand, *value, t_ns)?;
                }
                Ok(())
            }
            Event::Input { operand, value } | Event::Output { operand, value } => {
                self.counter(operand, i64::from(*value), t_ns)
            }
            Event::ClientWrite {
                client, operand, ..
            } => self.global(format!("{client} wrote {operand}"), t_ns, event),
            Event::Modify {
                client, operand, ..
            } => self.global(format!("{client} modified {operand}"), t_ns, event),
            Event::Force {
                client, operand, ..
            } => self.global(format!("{client} forced {operand}"), t_ns, event),
            Event::Unforce { client, operand } => {
                self.global(format!("{client} unforced {operand}"), t_ns, event)
            }
            Event::CycleStart { .. }
            | Event::CycleEnd { .. }
            | Event::BlockCall { .. }
            | Event::BlockEnd { .. }
            | Event::IrqEnd { .. }
            | Event::DataCycle { .. }
            | Event::OsTime { .. }
            | Event::CycleWait { .. } => Ok(()),
        }
    }

    /// An instant on OB `ob`'s level, with the event's fields.
    fn on_level(&mut self, ob: u8, what: &str, t_ns: u64, event: &Event) -> std::io::Result<()> {
        let tid = self.thread(u32::from(ob))?;
        let args = serde_json::to_value(event).map_err(std::io::Error::other)?;
        let name = format!("OB {ob} {what}");
        self.write(&TraceEvent::instant(name, t_ns, tid, args))
    }

    /// An instant over every thread (a mode change, a STOP).
    fn global(&mut self, name: String, t_ns: u64, event: &Event) -> std::io::Result<()> {
        let tid = self.thread(SYSTEM_TID)?;
        let args = serde_json::to_value(event).map_err(std::io::Error::other)?;
        self.write(&TraceEvent {
            s: Some("g"),
            cat: Some("mode"),
            ..TraceEvent::instant(name, t_ns, tid, args)
        })
    }

    fn counter(&mut self, operand: &str, value: i64, t_ns: u64) -> std::io::Result<()> {
        let tid = self.thread(SYSTEM_TID)?;
        self.write(&TraceEvent {
            cat: Some("io"),
            args: json!({ "value": value }),
            ..TraceEvent::new("C", operand.to_string(), t_ns, tid)
        })
    }

    fn flush_spans(&mut self) -> std::io::Result<()> {
        for span in std::mem::take(&mut self.spans) {
            self.span(span)?;
        }
        Ok(())
    }
}

impl Sink for Chrome {
    fn event(&mut self, t_ns: u64, event: &Event) -> std::io::Result<()> {
        let running = self.activity.top_ob().map_or(SYSTEM_TID, u32::from);
        self.activity.apply(t_ns, event, &mut self.spans);
        self.flush_spans()?;
        if self.filter.shows(t_ns, event) {
            self.marks(t_ns, event, running)?;
        }
        Ok(())
    }

    fn finish(&mut self, end_ns: u64) -> std::io::Result<()> {
        self.activity.finish(end_ns, &mut self.spans);
        self.flush_spans()?;
        if self.written == 0 {
            self.thread(SYSTEM_TID)?;
        }
        self.out.write_all(b"\n]}\n")?;
        self.out.flush()
    }
}
