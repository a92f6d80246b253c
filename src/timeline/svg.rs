//! Draws the recorded marks as one SVG: lanes from the highest priority at the top to OB 1,
//! then the operating system's strip, the inputs and outputs, the time axis and a legend.

use std::fmt::Write;

use super::PLOT_WIDTH;
use super::axis;
use super::rows::{Item, Mark, Rows};
use crate::trace::{Levels, format_us};

/// Left margin (the lane names), right margin.
const LEFT: f64 = 96.0;
const RIGHT: f64 = 24.0;
/// Height of a row in a lane: the level's bar, then one per call depth.
const ROW: f64 = 16.0;
const PAD: f64 = 4.0;
const GAP: f64 = 6.0;
/// Where the lanes start: below the caption and the cycle labels.
const TOP: f64 = 44.0;
const STRIP: f64 = 18.0;

/// The lanes' colours, from OB 1 upwards.
pub const PALETTE: [&str; 8] = [
    "#4e79a7", "#f28e2b", "#59a14f", "#e15759", "#b07aa1", "#76b7b2", "#edc948", "#9c755f",
];
const INK: &str = "#222";

pub struct Scene<'a> {
    pub rows: &'a Rows,
    pub levels: &'a Levels,
    pub caption: &'a str,
    pub from: u64,
    pub to: u64,
}

/// A lane: its OB, what it is, its colour and where it is.
struct Lane {
    ob: u8,
    title: String,
    colour: &'static str,
    top: f64,
    height: f64,
}

impl Scene<'_> {
    fn x(&self, t_ns: u64) -> f64 {
        let span = (self.to - self.from) as f64;
        LEFT + (t_ns.saturating_sub(self.from)) as f64 / span * PLOT_WIDTH as f64
    }

    fn items(&self, mark: Mark, ob: u8) -> impl Iterator<Item = (u8, &Item)> {
        self.rows
            .rows
            .range((mark, ob, 0)..=(mark, ob, u8::MAX))
            .flat_map(|((_, _, depth), items)| items.iter().map(move |item| (*depth, item)))
    }

    fn has(&self, mark: Mark) -> bool {
        self.rows
            .rows
            .range((mark, 0, 0)..=(mark, u8::MAX, u8::MAX))
            .any(|(_, items)| !items.is_empty())
    }

    /// The lanes, top to bottom: every level the program has or the run touched.
    fn lanes(&self) -> Vec<Lane> {
        let mut obs: Vec<(u8, u8, String)> = Vec::new();
        let touched = |ob: u8| self.rows.rows.keys().any(|(_, row_ob, _)| *row_ob == ob);
        for level in self.levels {
            if level.ob == 1 || level.loaded || touched(level.ob) {
                let title = format!(
                    "OB {}: {}, priority {}",
                    level.ob, level.what, level.priority
                );
                obs.push((level.priority, level.ob, title));
            }
        }
        for (_, ob, _) in self.rows.rows.keys() {
            if *ob != 0 && !obs.iter().any(|(_, known, _)| known == ob) {
                obs.push((0, *ob, format!("OB {ob}: not an interrupt OB of this CPU")));
            }
        }
        obs.sort_by_key(|(priority, ob, _)| (*priority, *ob));
        let colours = obs
            .iter()
            .enumerate()
            .map(|(n, _)| PALETTE[n % PALETTE.len()]);
        let mut lanes: Vec<Lane> = obs
            .iter()
            .zip(colours)
            .map(|((_, ob, title), colour)| Lane {
                ob: *ob,
                title: title.clone(),
                colour,
                top: 0.0,
                height: 0.0,
            })
            .collect();
        lanes.reverse();
        let mut top = TOP;
        for lane in &mut lanes {
            let depth = self
                .items(Mark::Block, lane.ob)
                .map(|(depth, _)| depth)
                .max()
                .unwrap_or(0);
            lane.top = top;
            lane.height = ROW * f64::from(1 + depth) + 2.0 * PAD;
            top += lane.height + GAP;
        }
        lanes
    }
}

/// The picture.
pub fn render(scene: &Scene) -> String {
    let lanes = scene.lanes();
    let lanes_bottom = lanes.last().map_or(TOP, |lane| lane.top + lane.height);
    let system_top = lanes_bottom + GAP;
    let io = [Mark::Input, Mark::Output, Mark::ClientWrite]
        .into_iter()
        .any(|mark| scene.has(mark));
    let io_top = system_top + STRIP + GAP;
    let axis_top = if io { io_top + STRIP + GAP } else { io_top };
    // The marks of SFC 39–42 get a legend line of their own, only when the run has them.
    let interrupt_sfcs = [Mark::Discarded, Mark::Delayed, Mark::IrtCall]
        .into_iter()
        .any(|mark| scene.has(mark));
    let height = axis_top + 52.0 + if interrupt_sfcs { 14.0 } else { 0.0 };
    let width = LEFT + PLOT_WIDTH as f64 + RIGHT;
    let mut svg = String::new();
    let _ = write!(
        svg,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width}" height="{height}" viewBox="0 0 {width} {height}" font-family="DejaVu Sans, Arial, sans-serif" font-size="10">"#
    );
    svg.push_str(r##"<rect class="background" width="100%" height="100%" fill="#ffffff"/>"##);
    // The hatching of a delayed request's wait.
    svg.push_str(
        r##"<defs><pattern id="hatch" width="6" height="6" patternUnits="userSpaceOnUse" patternTransform="rotate(45)"><rect width="6" height="6" fill="#fff4d6"/><line x1="0" y1="0" x2="0" y2="6" stroke="#e8a33d" stroke-width="2.5"/></pattern></defs>"##,
    );
    let _ = write!(
        svg,
        r#"<text class="caption" x="{LEFT}" y="16" font-size="13" fill="{INK}">{}</text>"#,
        escape(scene.caption)
    );
    for lane in &lanes {
        draw_lane_background(&mut svg, lane);
    }
    draw_system(&mut svg, scene, system_top, axis_top);
    for lane in &lanes {
        draw_lane(&mut svg, scene, lane);
    }
    if io {
        draw_io(&mut svg, scene, io_top);
    }
    draw_cycles(&mut svg, scene, axis_top);
    draw_axis(&mut svg, scene, axis_top);
    draw_stops(&mut svg, scene, axis_top);
    draw_legend(&mut svg, axis_top + 40.0);
    if interrupt_sfcs {
        draw_sfc_legend(&mut svg, axis_top + 54.0);
    }
    svg.push_str("</svg>\n");
    svg
}

fn draw_lane_background(svg: &mut String, lane: &Lane) {
    let _ = write!(
        svg,
        r##"<rect class="lane" data-ob="{}" x="{LEFT}" y="{:.1}" width="{PLOT_WIDTH}" height="{:.1}" fill="#f3f4f6"><title>{}</title></rect>"##,
        lane.ob,
        lane.top,
        lane.height,
        escape(&lane.title)
    );
    let _ = write!(
        svg,
        r#"<text class="lane-name" x="{:.1}" y="{:.1}" text-anchor="end" font-size="12" fill="{}">OB {}</text>"#,
        LEFT - 8.0,
        lane.top + PAD + ROW - 4.0,
        lane.colour,
        lane.ob
    );
}

/// A bar with its name inside when it fits.
fn bar(svg: &mut String, mark: Mark, scene: &Scene, item: &Item, y: f64, fill: &str) {
    let x = scene.x(item.start);
    let width = (scene.x(item.end) - x).max(0.8);
    let _ = write!(
        svg,
        r#"<rect class="{}" data-count="{}" x="{x:.1}" y="{y:.1}" width="{width:.1}" height="{:.1}" fill="{fill}" stroke="{INK}" stroke-width="0.3"><title>{}</title></rect>"#,
        mark.class(),
        item.count,
        ROW - 2.0,
        escape(&title(mark, item))
    );
    let label = if item.mixed { "…" } else { &item.label };
    if !label.is_empty() && width > 6.2 * label.chars().count() as f64 + 4.0 {
        let _ = write!(
            svg,
            r#"<text class="label" x="{:.1}" y="{:.1}" fill="{INK}" pointer-events="none">{}</text>"#,
            x + 2.0,
            y + ROW - 5.0,
            escape(label)
        );
    }
}

fn draw_lane(svg: &mut String, scene: &Scene, lane: &Lane) {
    let bar_top = lane.top + PAD;
    let middle = bar_top + ROW / 2.0 - 1.0;
    for (_, item) in scene.items(Mark::Run, lane.ob) {
        bar(svg, Mark::Run, scene, item, bar_top, lane.colour);
    }
    for (depth, item) in scene.items(Mark::Block, lane.ob) {
        let fill = tint(lane.colour, 0.35 + 0.12 * f64::from(depth.min(4)));
        let y = bar_top + ROW * f64::from(depth);
        bar(svg, Mark::Block, scene, item, y, &fill);
    }
    for (_, item) in scene.items(Mark::Tick, lane.ob) {
        let x = scene.x(item.start);
        let _ = write!(
            svg,
            r#"<line class="tick" data-count="{}" x1="{x:.1}" x2="{x:.1}" y1="{:.1}" y2="{:.1}" stroke="{INK}" stroke-width="1.2"><title>{}</title></line>"#,
            item.count,
            lane.top + 1.0,
            bar_top + ROW + 1.0,
            escape(&title(Mark::Tick, item))
        );
    }
    for (_, item) in scene.items(Mark::Delayed, lane.ob) {
        let x = scene.x(item.start);
        let width = (scene.x(item.end) - x).max(0.8);
        let _ = write!(
            svg,
            r##"<rect class="delayed" data-count="{}" x="{x:.1}" y="{:.1}" width="{width:.1}" height="6" fill="url(#hatch)" stroke="#e8a33d" stroke-width="0.6"><title>{}</title></rect>"##,
            item.count,
            middle - 3.0,
            escape(&title(Mark::Delayed, item))
        );
    }
    for (_, item) in scene.items(Mark::Service, lane.ob) {
        draw_service(svg, scene, item, middle);
    }
    for (_, item) in scene.items(Mark::Request, lane.ob) {
        let _ = write!(
            svg,
            r##"<circle class="request" data-count="{}" cx="{:.1}" cy="{middle:.1}" r="4" fill="#ffffff" stroke="{INK}" stroke-width="1.5"><title>{}</title></circle>"##,
            item.count,
            scene.x(item.start),
            escape(&title(Mark::Request, item))
        );
    }
    for (_, item) in scene.items(Mark::IrtCall, lane.ob) {
        let x = scene.x(item.start);
        let _ = write!(
            svg,
            r##"<g class="irt-call" data-count="{}"><title>{}</title><path d="M{x:.1} {:.1}L{:.1} {:.1}L{x:.1} {:.1}L{:.1} {:.1}Z" fill="#e8a33d" stroke="{INK}" stroke-width="0.6"/></g>"##,
            item.count,
            escape(&title(Mark::IrtCall, item)),
            bar_top - 3.0,
            x + 4.0,
            bar_top + 1.0,
            bar_top + 5.0,
            x - 4.0,
            bar_top + 1.0,
        );
    }
    for (mark, colour) in [
        (Mark::Lost, "#d62728"),
        (Mark::Ignored, "#7f7f7f"),
        (Mark::Discarded, "#e8a33d"),
    ] {
        for (_, item) in scene.items(mark, lane.ob) {
            cross(svg, scene, mark, item, middle, colour);
        }
    }
    for (_, item) in scene.items(Mark::ModuleEvent, lane.ob) {
        let x = scene.x(item.start);
        let _ = write!(
            svg,
            r##"<rect class="module-event" data-count="{}" x="{:.1}" y="{:.1}" width="7" height="7" fill="#7f7f7f"><title>{}</title></rect>"##,
            item.count,
            x - 3.5,
            middle - 3.5,
            escape(&title(Mark::ModuleEvent, item))
        );
    }
}

/// A service: a triangle where the OB started, joined to its request by the latency.
fn draw_service(svg: &mut String, scene: &Scene, item: &Item, y: f64) {
    let (from, to) = (scene.x(item.requested_at), scene.x(item.start));
    let _ = write!(
        svg,
        r#"<g class="service" data-count="{}"><title>{}</title><line class="latency" x1="{from:.1}" x2="{to:.1}" y1="{y:.1}" y2="{y:.1}" stroke="{INK}" stroke-width="1.2" stroke-dasharray="3 2"/><path d="M{:.1} {:.1}L{:.1} {y:.1}L{:.1} {:.1}Z" fill="{INK}"/>"#,
        item.count,
        escape(&title(Mark::Service, item)),
        to - 4.0,
        y - 5.0,
        to + 5.0,
        to - 4.0,
        y + 5.0,
    );
    let latency = latency_text(item);
    if to - from > 6.0 * latency.chars().count() as f64 + 12.0 {
        let _ = write!(
            svg,
            r#"<text class="latency-label" x="{:.1}" y="{:.1}" text-anchor="middle" fill="{INK}">{}</text>"#,
            (from + to) / 2.0,
            y - 3.0,
            escape(&latency)
        );
    }
    svg.push_str("</g>");
}

fn latency_text(item: &Item) -> String {
    let (low, high) = item.latency;
    if low == high {
        format_us(low)
    } else {
        format!("{}–{}", format_us(low), format_us(high))
    }
}

fn cross(svg: &mut String, scene: &Scene, mark: Mark, item: &Item, y: f64, colour: &str) {
    let x = scene.x(item.start);
    let _ = write!(
        svg,
        r#"<g class="{}" data-count="{}"><title>{}</title><path d="M{:.1} {:.1}L{:.1} {:.1}M{:.1} {:.1}L{:.1} {:.1}" stroke="{colour}" stroke-width="2.2"/></g>"#,
        mark.class(),
        item.count,
        escape(&title(mark, item)),
        x - 5.0,
        y - 5.0,
        x + 5.0,
        y + 5.0,
        x - 5.0,
        y + 5.0,
        x + 5.0,
        y - 5.0
    );
    let word = match mark {
        Mark::Lost => "lost",
        Mark::Discarded => "discarded",
        _ => "ignored",
    };
    let _ = write!(
        svg,
        r#"<text class="cross-label" x="{:.1}" y="{:.1}" fill="{colour}" pointer-events="none">{word}</text>"#,
        x + 7.0,
        y + 3.5
    );
}

/// The operating system's strip (data cycles, its time at the cycle end, an S7 CPU's wait for
/// the minimum cycle time) and their shading across the lanes.
fn draw_system(svg: &mut String, scene: &Scene, top: f64, bottom: f64) {
    strip_name(svg, "system", top);
    for (mark, fill) in [
        (Mark::DataCycle, "#8c9db5"),
        (Mark::OsTime, "#c4c4c4"),
        (Mark::CycleWait, "#a8d5a2"),
    ] {
        for (_, item) in scene.items(mark, 0) {
            let x = scene.x(item.start);
            let width = (scene.x(item.end) - x).max(0.8);
            let _ = write!(
                svg,
                r#"<rect class="shade" x="{x:.1}" y="{TOP}" width="{width:.1}" height="{:.1}" fill="{fill}" fill-opacity="0.25" pointer-events="none"/>"#,
                bottom - TOP
            );
            bar(svg, mark, scene, item, top, fill);
        }
    }
}

/// The name of the strip at `top`, left of the plot.
fn strip_name(svg: &mut String, name: &str, top: f64) {
    let _ = write!(
        svg,
        r##"<text class="lane-name" x="{:.1}" y="{:.1}" text-anchor="end" font-size="11" fill="#555">{name}</text>"##,
        LEFT - 8.0,
        top + ROW - 4.0
    );
}

fn draw_io(svg: &mut String, scene: &Scene, top: f64) {
    strip_name(svg, "I/O", top);
    let y = top + STRIP / 2.0;
    for (mark, fill) in [
        (Mark::Input, "#2ca02c"),
        (Mark::Output, "#9467bd"),
        (Mark::ClientWrite, "#1f77b4"),
    ] {
        for (_, item) in scene.items(mark, 0) {
            let x = scene.x(item.start);
            let _ = write!(
                svg,
                r#"<path class="{}" data-count="{}" d="M{x:.1} {:.1}L{:.1} {y:.1}L{x:.1} {:.1}L{:.1} {y:.1}Z" fill="{fill}"><title>{}</title></path>"#,
                mark.class(),
                item.count,
                y - 5.0,
                x + 4.0,
                y + 5.0,
                x - 4.0,
                escape(&title(mark, item))
            );
        }
    }
}

/// Cycle starts: a dashed line down to the axis, its number on top where there is room.
fn draw_cycles(svg: &mut String, scene: &Scene, bottom: f64) {
    let mut free_from = f64::MIN;
    for (_, item) in scene.items(Mark::Cycle, 0) {
        let x = scene.x(item.start);
        let _ = write!(
            svg,
            r##"<line class="cycle" data-count="{}" x1="{x:.1}" x2="{x:.1}" y1="{:.1}" y2="{bottom:.1}" stroke="#666" stroke-width="0.8" stroke-dasharray="4 3"><title>{}</title></line>"##,
            item.count,
            TOP - 12.0,
            escape(&title(Mark::Cycle, item))
        );
        let label = if item.count == 1 {
            item.label.clone()
        } else {
            format!("{} cycles", item.count)
        };
        if x >= free_from {
            let _ = write!(
                svg,
                r##"<text class="cycle-label" x="{:.1}" y="{:.1}" fill="#555">{}</text>"##,
                x + 3.0,
                TOP - 6.0,
                escape(&label)
            );
            free_from = x + 6.5 * label.chars().count() as f64 + 10.0;
        }
    }
}

fn draw_axis(svg: &mut String, scene: &Scene, top: f64) {
    let right = LEFT + PLOT_WIDTH as f64;
    let _ = write!(
        svg,
        r#"<g class="axis"><line x1="{LEFT}" x2="{right}" y1="{top:.1}" y2="{top:.1}" stroke="{INK}"/>"#
    );
    let step = axis::step(scene.to - scene.from, 10);
    for t in axis::ticks(scene.from, scene.to, step) {
        let x = scene.x(t);
        let _ = write!(
            svg,
            r#"<line x1="{x:.1}" x2="{x:.1}" y1="{top:.1}" y2="{:.1}" stroke="{INK}"/><text x="{x:.1}" y="{:.1}" text-anchor="middle" fill="{INK}">{}</text>"#,
            top + 5.0,
            top + 17.0,
            axis::label(t, step, scene.to)
        );
    }
    let _ = write!(
        svg,
        r##"<text x="{right}" y="{:.1}" text-anchor="end" fill="#555">simulated time</text></g>"##,
        top + 30.0
    );
}

fn draw_stops(svg: &mut String, scene: &Scene, bottom: f64) {
    for (_, item) in scene.items(Mark::Stop, 0) {
        let x = scene.x(item.start);
        let _ = write!(
            svg,
            r##"<g class="stop" data-count="{}"><title>{}</title><line x1="{x:.1}" x2="{x:.1}" y1="{:.1}" y2="{bottom:.1}" stroke="#d62728" stroke-width="2.5"/><text x="{:.1}" y="{:.1}" text-anchor="end" font-weight="bold" fill="#d62728">{}</text></g>"##,
            item.count,
            escape(&title(Mark::Stop, item)),
            TOP - 12.0,
            x - 3.0,
            TOP - 6.0,
            escape(&item.label)
        );
    }
}

fn draw_legend(svg: &mut String, y: f64) {
    let _ = write!(
        svg,
        r##"<g class="legend" fill="#555"><circle cx="{:.1}" cy="{:.1}" r="4" fill="#ffffff" stroke="{INK}" stroke-width="1.5"/><text x="{:.1}" y="{y:.1}">request</text><path d="M{:.1} {:.1}L{:.1} {:.1}L{:.1} {:.1}Z" fill="{INK}"/><text x="{:.1}" y="{y:.1}">service (dashed: the latency)</text><text x="{:.1}" y="{y:.1}">| tick: block change, an interrupt point</text><text x="{:.1}" y="{y:.1}" fill="#d62728">✕ lost</text><text x="{:.1}" y="{y:.1}" fill="#7f7f7f">✕ ignored</text><text x="{:.1}" y="{y:.1}">shaded: data cycles and operating-system time; hover a mark for its details</text></g>"##,
        LEFT + 4.0,
        y - 4.0,
        LEFT + 12.0,
        LEFT + 60.0,
        y - 9.0,
        LEFT + 69.0,
        y - 4.0,
        LEFT + 60.0,
        y + 1.0,
        LEFT + 74.0,
        LEFT + 230.0,
        LEFT + 430.0,
        LEFT + 480.0,
        LEFT + 560.0,
    );
}

/// The legend of the SFC 39–42 marks.
fn draw_sfc_legend(svg: &mut String, y: f64) {
    let _ = write!(
        svg,
        r##"<g class="legend sfc-legend" fill="#555"><path d="M{:.1} {:.1}L{:.1} {:.1}L{:.1} {:.1}L{:.1} {:.1}Z" fill="#e8a33d" stroke="{INK}" stroke-width="0.6"/><text x="{:.1}" y="{y:.1}">SFC 39–42 call</text><rect x="{:.1}" y="{:.1}" width="24" height="6" fill="url(#hatch)" stroke="#e8a33d" stroke-width="0.6"/><text x="{:.1}" y="{y:.1}">delayed by SFC 41 DIS_AIRT</text><text x="{:.1}" y="{y:.1}" fill="#e8a33d">✕ discarded: disabled by SFC 39 DIS_IRT</text></g>"##,
        LEFT + 4.0,
        y - 8.0,
        LEFT + 8.0,
        y - 4.0,
        LEFT + 4.0,
        y,
        LEFT,
        y - 4.0,
        LEFT + 12.0,
        LEFT + 110.0,
        y - 7.0,
        LEFT + 138.0,
        LEFT + 300.0,
    );
}

/// A mark's title: its details, or for a merged mark how many it stands for.
fn title(mark: Mark, item: &Item) -> String {
    let mut title = if item.count <= 1 {
        item.detail.clone()
    } else {
        let mut title = format!(
            "{} {} from {} to {}",
            item.count,
            mark.plural(),
            crate::trace::format_ms(item.start),
            crate::trace::format_ms(item.end)
        );
        if item.end > item.start && item.busy_ns > 0 {
            let busy = item.busy_ns as f64 / (item.end - item.start) as f64 * 100.0;
            let _ = write!(title, ", {busy:.0} % of the time");
        }
        let _ = write!(title, "; the first: {}", item.detail);
        title
    };
    if mark == Mark::Service && item.count > 1 {
        let _ = write!(title, "; latency {}", latency_text(item));
    }
    title
}

/// `colour` mixed with white: `amount` 0 keeps it, 1 gives white.
fn tint(colour: &str, amount: f64) -> String {
    let channel = |at: usize| {
        let value = u8::from_str_radix(&colour[at..at + 2], 16).unwrap_or(0);
        (f64::from(value) + (255.0 - f64::from(value)) * amount).round() as u8
    };
    format!("#{:02x}{:02x}{:02x}", channel(1), channel(3), channel(5))
}

/// Text for XML: `&`, `<`, `>` and `"` escaped.
fn escape(text: &str) -> String {
    let mut escaped = String::with_capacity(text.len());
    for c in text.chars() {
        match c {
            '&' => escaped.push_str("&amp;"),
            '<' => escaped.push_str("&lt;"),
            '>' => escaped.push_str("&gt;"),
            '"' => escaped.push_str("&quot;"),
            c => escaped.push(c),
        }
    }
    escaped
}
