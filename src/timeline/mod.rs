//! The timeline picture of a run (`awl run … --timeline FILE.svg` or `FILE.html`): simulated
//! time across, one lane per priority level (OB 1 at the bottom), bars where a level runs with
//! its called blocks nested below, ticks at the block changes (the interrupt points), requests
//! joined to their service with the latency, lost, ignored and discarded requests crossed out,
//! the wait of a request SFC 41 delayed hatched, SFC 39–42 calls marked on their level, data
//! cycles and operating-system time shaded, a STOP marked. Every mark has a class and a
//! `<title>`; marks closer than a pixel are merged and say how many they stand for.

mod axis;
mod page;
pub mod rows;
mod svg;

use std::collections::HashMap;
use std::io::Write;
use std::path::Path;

use crate::trace::activity::{Activity, CYCLE_WAIT, OS_TIME, Span};
use crate::trace::{Event, Levels, Sink, TraceFilter, describe, format_ms};
use rows::{Item, Mark, RowKey, Rows};

/// The plot's width in pixels: marks closer than `span / PLOT_WIDTH` merge.
pub const PLOT_WIDTH: u64 = 1200;

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    Svg,
    /// The SVG in a page with pan, zoom and hover details.
    Html,
}

impl Format {
    /// `.html` (or `.htm`) gives the page, anything else the SVG.
    pub fn of(path: &Path) -> Format {
        let html = path.extension().is_some_and(|extension| {
            extension.eq_ignore_ascii_case("html") || extension.eq_ignore_ascii_case("htm")
        });
        if html { Format::Html } else { Format::Svg }
    }
}

/// The timeline as an output of the tracer: records the run, writes the picture at its end.
pub fn sink(
    format: Format,
    out: Box<dyn Write>,
    window: TraceFilter,
    levels: Levels,
    caption: String,
) -> Box<dyn Sink> {
    Box::new(Output {
        format,
        out,
        recorder: Recorder::new(window, levels, caption),
    })
}

struct Output {
    format: Format,
    out: Box<dyn Write>,
    recorder: Recorder,
}

impl Sink for Output {
    fn event(&mut self, t_ns: u64, event: &Event) -> std::io::Result<()> {
        self.recorder.record(t_ns, event);
        Ok(())
    }

    fn finish(&mut self, end_ns: u64) -> std::io::Result<()> {
        let svg = self.recorder.svg(end_ns);
        match self.format {
            Format::Svg => self.out.write_all(svg.as_bytes())?,
            Format::Html => self
                .out
                .write_all(page::html(&self.recorder.caption, &svg).as_bytes())?,
        }
        self.out.flush()
    }
}

/// What the picture will show, taken from the events in time order.
pub struct Recorder {
    window: TraceFilter,
    levels: Levels,
    caption: String,
    activity: Activity,
    spans: Vec<Span>,
    rows: Rows,
    /// Open requests: id → when they came.
    requests: HashMap<u64, u64>,
    /// Delayed requests: id → when the delay took them.
    delayed: HashMap<u64, u64>,
}

impl Recorder {
    pub fn new(window: TraceFilter, levels: Levels, caption: String) -> Self {
        Recorder {
            window,
            levels,
            caption,
            activity: Activity::default(),
            spans: Vec::new(),
            rows: Rows::default(),
            requests: HashMap::new(),
            delayed: HashMap::new(),
        }
    }

    pub fn record(&mut self, t_ns: u64, event: &Event) {
        let running = self.activity.top_ob().unwrap_or(1);
        self.activity.apply(t_ns, event, &mut self.spans);
        self.take_spans();
        let point = |mark: Mark, ob: u8| ((mark, ob, 0), String::new());
        let (key, label) = match event {
            Event::BlockCall { .. } | Event::BlockEnd { .. } => point(Mark::Tick, running),
            Event::CycleStart { cycle } => ((Mark::Cycle, 0, 0), format!("cycle {cycle}")),
            Event::IrqRequest { id, ob, .. } => {
                self.requests.insert(*id, t_ns);
                point(Mark::Request, *ob)
            }
            Event::IrqService {
                id, ob, latency_ns, ..
            } => {
                let requested_at = self.requests.remove(id).unwrap_or(t_ns);
                if let Some(delayed_at) = self.delayed.remove(id) {
                    let wait = Item::new(delayed_at, t_ns, String::new(), String::new());
                    self.add((Mark::Delayed, *ob, 0), wait, || {
                        format!(
                            "OB {ob} request #{id} delayed by SFC 41 DIS_AIRT from {} to {}",
                            format_ms(delayed_at),
                            format_ms(t_ns)
                        )
                    });
                }
                let mut item = Item::new(t_ns, t_ns, String::new(), String::new());
                item.requested_at = requested_at;
                item.latency = (*latency_ns, *latency_ns);
                self.add((Mark::Service, *ob, 0), item, || detail(t_ns, event));
                return;
            }
            Event::IrqLost { id, ob, .. } => {
                self.requests.remove(id);
                point(Mark::Lost, *ob)
            }
            Event::IrqIgnored { id, ob, .. } => {
                self.requests.remove(id);
                point(Mark::Ignored, *ob)
            }
            Event::IrqDiscarded { id, ob, .. } => {
                self.requests.remove(id);
                point(Mark::Discarded, *ob)
            }
            Event::IrqDelayed { id, .. } => {
                self.delayed.entry(*id).or_insert(t_ns);
                return;
            }
            Event::IrtCall { name, ob, .. } => ((Mark::IrtCall, *ob, 0), name.to_string()),
            Event::ModuleEvent { ob, .. } => point(Mark::ModuleEvent, *ob),
            Event::Stop { cause, .. } => ((Mark::Stop, 0, 0), format!("STOP {cause}")),
            Event::Input { .. } => point(Mark::Input, 0),
            Event::Output { .. } => point(Mark::Output, 0),
            Event::ClientWrite { client, .. }
            | Event::Modify { client, .. }
            | Event::Force { client, .. }
            | Event::Unforce { client, .. } => ((Mark::ClientWrite, 0, 0), client.clone()),
            Event::Mode { .. }
            | Event::CycleEnd { .. }
            | Event::DataCycle { .. }
            | Event::OsTime { .. }
            | Event::CycleWait { .. }
            | Event::IrqEnd { .. }
            | Event::DelayEnd { .. }
            | Event::Watch { .. } => return,
        };
        let item = Item::new(t_ns, t_ns, label, String::new());
        self.add(key, item, || detail(t_ns, event));
    }

    fn take_spans(&mut self) {
        for span in std::mem::take(&mut self.spans) {
            if let Some((key, item)) = span_item(&span) {
                self.add(key, item, || span_detail(&span));
            }
        }
    }

    /// Keeps the part of `item` inside the window; its details are written only when it is
    /// not merged into the mark before it (a long run merges most).
    fn add(&mut self, key: RowKey, mut item: Item, detail: impl FnOnce() -> String) {
        let Some((start, end)) = self.window.clip(item.start, item.end) else {
            return;
        };
        if start > item.start {
            // Called before the window: no call of it in the window.
            item.count = 0;
        }
        item.start = start;
        item.end = end;
        item.busy_ns = end - start;
        if !self.rows.merges(&key, &item) {
            item.detail = detail();
        }
        self.rows.push(key, item);
        self.rows
            .bound(end.saturating_sub(self.window.from_ns), PLOT_WIDTH);
    }

    /// The picture of everything recorded, the run having ended at `end_ns`.
    pub fn svg(&mut self, end_ns: u64) -> String {
        self.activity.finish(end_ns, &mut self.spans);
        self.take_spans();
        let from = self.window.from_ns.min(end_ns);
        let to = self.window.to_ns.min(end_ns).max(from + 1);
        self.rows.merge_at((to - from).div_ceil(PLOT_WIDTH));
        svg::render(&svg::Scene {
            rows: &self.rows,
            levels: &self.levels,
            caption: &self.caption,
            from,
            to,
        })
    }
}

/// Where a span is drawn, and its mark without details.
fn span_item(span: &Span) -> Option<(RowKey, Item)> {
    let (key, start, end, label) = match span {
        Span::Run { ob, start, end } => ((Mark::Run, *ob, 0), start, end, format!("OB {ob}")),
        Span::Block {
            ob,
            depth,
            name,
            start,
            end,
        } => {
            let depth = u8::try_from(*depth).unwrap_or(u8::MAX);
            ((Mark::Block, *ob, depth), start, end, name.to_string())
        }
        Span::System { what, start, end } => {
            let mark = match *what {
                OS_TIME => Mark::OsTime,
                CYCLE_WAIT => Mark::CycleWait,
                _ => Mark::DataCycle,
            };
            ((mark, 0, 0), start, end, short(what))
        }
        Span::Level { .. } | Span::Cycle { .. } => return None,
    };
    Some((key, Item::new(*start, *end, label, String::new())))
}

/// A span's details for its title.
fn span_detail(span: &Span) -> String {
    match span {
        Span::Run { ob, start, end } => format!(
            "OB {ob}'s level runs from {} to {}",
            format_ms(*start),
            format_ms(*end)
        ),
        Span::Block {
            ob,
            depth,
            name,
            start,
            end,
        } => format!(
            "{name} (called at depth {depth} on OB {ob}'s level) from {} to {}",
            format_ms(*start),
            format_ms(*end)
        ),
        Span::System { what, start, end } => format!(
            "{what}, {} from {}",
            crate::trace::format_us(end - start),
            format_ms(*start)
        ),
        Span::Level { .. } | Span::Cycle { .. } => String::new(),
    }
}

/// A mark's details: when, and the trace's words for it.
fn detail(t_ns: u64, event: &Event) -> String {
    format!("{}: {}", format_ms(t_ns), describe(event))
}

/// A data cycle's label inside its shading.
fn short(what: &str) -> String {
    match what {
        "process image read (PII)" => "PII",
        "process image write (PIQ)" => "PIQ",
        "interrupt input data cycle" => "IDC in",
        "interrupt output data cycle" => "IDC out",
        CYCLE_WAIT => "wait",
        _ => "OS",
    }
    .to_string()
}
