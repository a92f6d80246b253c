//! The text timeline: one line per event, indented one step per level entered and per block
//! called on it, so a call, the called block's end, a request and a service line up with
//! what ran when they happened.

use std::borrow::Cow;
use std::io::Write;

use super::activity::{Activity, CYCLE_WAIT, data_cycle_name};
use super::{Event, Sink, TraceFilter, format_ms, format_us};
use crate::symbols::Symbols;

/// Width of the time column: aligned up to 999 s (`999999.999999 ms`).
const TIME_WIDTH: usize = 16;

pub struct Text {
    out: Box<dyn Write>,
    filter: TraceFilter,
    activity: Activity,
    spans: Vec<super::activity::Span>,
    symbols: Symbols,
}

impl Text {
    pub fn new(out: Box<dyn Write>, filter: TraceFilter, symbols: Symbols) -> Self {
        Text {
            out,
            filter,
            activity: Activity::default(),
            spans: Vec::new(),
            symbols,
        }
    }

    /// The event with its blocks and operands named by their symbols (`PB 3 (-FILL)`).
    fn named<'e>(&self, event: &'e Event) -> Cow<'e, Event> {
        if self.symbols.is_empty() {
            return Cow::Borrowed(event);
        }
        let name = |text: &str| self.symbols.decorate(text);
        let mut event = event.clone();
        match &mut event {
            Event::BlockCall { from, to, .. } => {
                *from = name(from).into();
                *to = name(to).into();
            }
            Event::BlockEnd { block, .. } => *block = name(block).into(),
            Event::Stop { block, .. } => *block = name(block),
            Event::IrqRequest {
                block: Some(block), ..
            }
            | Event::IrqService {
                block: Some(block), ..
            } => *block = name(block),
            Event::Input { operand, .. }
            | Event::Output { operand, .. }
            | Event::ClientWrite { operand, .. }
            | Event::Modify { operand, .. }
            | Event::Force { operand, .. }
            | Event::Unforce { operand, .. } => *operand = name(operand),
            _ => {}
        }
        Cow::Owned(event)
    }
}

impl Sink for Text {
    fn event(&mut self, t_ns: u64, event: &Event) -> std::io::Result<()> {
        let before = self.activity.indent();
        self.activity.apply(t_ns, event, &mut self.spans);
        self.spans.clear();
        if !self.filter.shows(t_ns, event) {
            return Ok(());
        }
        let indent = match event {
            Event::Mode { .. }
            | Event::CycleStart { .. }
            | Event::CycleEnd { .. }
            | Event::Stop { .. }
            | Event::Watch { .. } => 0,
            // Back on the interrupted level.
            Event::IrqEnd { .. } => self.activity.indent(),
            _ => before,
        };
        writeln!(
            self.out,
            "{:>TIME_WIDTH$}  {}{}",
            format_ms(t_ns),
            "  ".repeat(indent),
            line(&self.named(event))
        )
    }

    fn finish(&mut self, _end_ns: u64) -> std::io::Result<()> {
        self.out.flush()
    }
}

/// An event as a line of the timeline (without time and indent).
pub fn line(event: &Event) -> String {
    match event {
        Event::Mode { from, to, cause } => match cause {
            Some(cause) => format!("mode {from} → {to} (cause {cause})"),
            None => format!("mode {from} → {to}"),
        },
        Event::CycleStart { cycle } => format!("── cycle {cycle} ──"),
        Event::CycleEnd {
            cycle,
            cycle_time_ns,
        } => format!(
            "── cycle {cycle} end, cycle time {} ──",
            format_ms(*cycle_time_ns)
        ),
        Event::BlockCall { from, to, .. } => format!("{from} calls {to}"),
        Event::BlockEnd { block, .. } => format!("{block} ends (BE)"),
        Event::IrqRequest {
            id,
            ob,
            module,
            channel,
            block,
            line,
            segment,
            during,
        } => {
            let source = match (module, channel) {
                (Some(module), Some(channel)) => format!(" by module {module} channel {channel}"),
                _ => String::new(),
            };
            let place = match (block, line, during) {
                (Some(block), Some(line), _) => {
                    format!(" while {block} runs {}line {line}", segment_text(*segment))
                }
                (Some(block), None, _) => format!(" while {block} runs"),
                (None, _, Some(during)) => format!(" during the {during}"),
                _ => " between cycles".to_string(),
            };
            format!("⚡ OB {ob} requested (#{id}){source}{place}")
        }
        Event::IrqService {
            id,
            ob,
            latency_ns,
            point,
            block,
            waited,
        } => {
            let block = block.as_deref().unwrap_or("?");
            let place = match *point {
                "block_end" => format!("at the block end of {block}"),
                "block_call" => format!("at the call of {block}"),
                "operation" => format!("after an operation of {block}"),
                _ => "at a point of the operating system".to_string(),
            };
            let waited = match waited {
                Some("priority") => " (a higher or equal priority ran first)",
                Some("disabled") => " (IA held it back)",
                Some("startup") => " (it came before RUN)",
                Some("delayed") => " (SFC 41 DIS_AIRT delayed it)",
                _ => "",
            };
            format!(
                "▶ OB {ob} serviced (#{id}) {place}, latency {}{waited}",
                format_us(*latency_ns)
            )
        }
        Event::IrqEnd { id, ob } => {
            format!("◀ OB {ob} done (#{id}), back to the interrupted level")
        }
        Event::IrqLost { id, ob, reason } => format!("✗ OB {ob} request #{id} lost: {reason}"),
        Event::IrqIgnored { id, ob, reason } => {
            format!("✗ OB {ob} request #{id} ignored: {reason}")
        }
        Event::IrqDiscarded { id, ob, reason } => {
            format!("✗ OB {ob} request #{id} discarded: {reason}")
        }
        Event::IrqDelayed { id, ob, delays } => format!(
            "⏸ OB {ob} request #{id} delayed by SFC 41 DIS_AIRT ({})",
            plural_delays(*delays)
        ),
        Event::DelayEnd { ob, by } => match *by {
            "EN_AIRT" => format!("⏵ OB {ob}'s delays end: SFC 42 EN_AIRT"),
            _ => format!("⏵ OB {ob}'s delays end with the OB"),
        },
        Event::IrtCall {
            sfc,
            name,
            mode,
            ob_nr,
            ret_val,
            ob,
        } => {
            let arguments = match (mode, ob_nr) {
                (Some(mode), Some(ob_nr)) => format!(" MODE {mode}, OB_NR {ob_nr},"),
                _ => String::new(),
            };
            let result = if *ret_val < 0 {
                format!("16#{:04X}", *ret_val as u16)
            } else {
                ret_val.to_string()
            };
            format!("OB {ob} calls SFC {sfc} {name}:{arguments} RET_VAL {result}")
        }
        Event::DataCycle {
            kind,
            direction,
            duration_ns,
        } => {
            format!(
                "{}, {}",
                data_cycle_name(kind, direction),
                format_us(*duration_ns)
            )
        }
        Event::OsTime { duration_ns } => {
            format!("operating-system time, {}", format_us(*duration_ns))
        }
        Event::CycleWait { duration_ns } => {
            format!("{CYCLE_WAIT}, {}", format_us(*duration_ns))
        }
        Event::ModuleEvent {
            module,
            channel,
            ob,
            reason,
        } => format!("· module {module} channel {channel} (OB {ob}): {reason}"),
        Event::Stop {
            cause,
            block,
            line,
            segment,
        } => format!(
            "STOP {cause} in {block} {}line {line}",
            segment_text(*segment)
        ),
        Event::Input { operand, value } => format!("input {operand} = {value}"),
        Event::Output { operand, value } => format!("output {operand} = {value}"),
        Event::ClientWrite {
            client,
            operand,
            value,
        } => format!("{client} wrote {operand} = {value}"),
        Event::Modify {
            client,
            operand,
            value,
        } => format!("{client} modified {operand} = {value}"),
        Event::Force {
            client,
            operand,
            value,
        } => format!("{client} forced {operand} = {value}"),
        Event::Unforce { client, operand } => format!("{client} unforced {operand}"),
        Event::Watch { values, .. } => {
            let values: Vec<String> = values
                .iter()
                .map(|(operand, value)| format!("{operand} = {value}"))
                .collect();
            format!("watch: {}", values.join(", "))
        }
    }
}

/// `1 delay in force`, `2 delays in force`.
fn plural_delays(delays: u16) -> String {
    if delays == 1 {
        "1 delay in force".to_string()
    } else {
        format!("{delays} delays in force")
    }
}

/// `segment 2 ` before a line number in a PG listing.
pub fn segment_text(segment: Option<u16>) -> String {
    segment.map_or_else(String::new, |segment| format!("segment {segment} "))
}
