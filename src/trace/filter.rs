//! What a trace shows: kinds of events (`--trace-filter`) and a window of simulated time
//! (`--from`, `--to`). Mode changes and a STOP are always shown: they say what the run was.

use super::Event;

/// A kind of event, as `--trace-filter` names it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// Requests, services, ends of interrupt OBs, lost, ignored, discarded and delayed
    /// requests, SFC 39–42 calls, module events.
    Interrupts,
    /// Block calls and block ends.
    Blocks,
    /// Cycle starts and ends, data cycles, operating-system time.
    Cycles,
    /// Input and output changes and watch rows.
    Io,
}

impl Kind {
    fn bit(self) -> u8 {
        match self {
            Kind::Interrupts => 1,
            Kind::Blocks => 2,
            Kind::Cycles => 4,
            Kind::Io => 8,
        }
    }
}

/// The kind of an event; `None` for those every trace shows.
pub fn kind(event: &Event) -> Option<Kind> {
    match event {
        Event::Mode { .. } | Event::Stop { .. } => None,
        Event::CycleStart { .. }
        | Event::CycleEnd { .. }
        | Event::DataCycle { .. }
        | Event::OsTime { .. }
        | Event::CycleWait { .. } => Some(Kind::Cycles),
        Event::BlockCall { .. } | Event::BlockEnd { .. } => Some(Kind::Blocks),
        Event::IrqRequest { .. }
        | Event::IrqService { .. }
        | Event::IrqEnd { .. }
        | Event::IrqLost { .. }
        | Event::IrqIgnored { .. }
        | Event::IrqDiscarded { .. }
        | Event::IrqDelayed { .. }
        | Event::DelayEnd { .. }
        | Event::IrtCall { .. }
        | Event::ModuleEvent { .. } => Some(Kind::Interrupts),
        Event::Watch { .. }
        | Event::Input { .. }
        | Event::Output { .. }
        | Event::ClientWrite { .. }
        | Event::Modify { .. }
        | Event::Force { .. }
        | Event::Unforce { .. } => Some(Kind::Io),
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct TraceFilter {
    kinds: u8,
    /// The window, `from` included, `to` included.
    pub from_ns: u64,
    pub to_ns: u64,
}

impl Default for TraceFilter {
    fn default() -> Self {
        TraceFilter::all()
    }
}

impl TraceFilter {
    pub fn all() -> Self {
        TraceFilter {
            kinds: u8::MAX,
            from_ns: 0,
            to_ns: u64::MAX,
        }
    }

    /// Only these kinds (an empty list: all of them).
    pub fn kinds(self, kinds: &[Kind]) -> Self {
        let kinds = match kinds {
            [] => u8::MAX,
            kinds => kinds.iter().fold(0, |bits, kind| bits | kind.bit()),
        };
        TraceFilter { kinds, ..self }
    }

    pub fn window(self, from_ns: Option<u64>, to_ns: Option<u64>) -> Self {
        TraceFilter {
            from_ns: from_ns.unwrap_or(0),
            to_ns: to_ns.unwrap_or(u64::MAX),
            ..self
        }
    }

    pub fn shows_kind(&self, kind: Kind) -> bool {
        self.kinds & kind.bit() != 0
    }

    pub fn in_window(&self, t_ns: u64) -> bool {
        (self.from_ns..=self.to_ns).contains(&t_ns)
    }

    /// The part of `start..end` inside the window, if any of it is.
    pub fn clip(&self, start: u64, end: u64) -> Option<(u64, u64)> {
        let (start, end) = (start.max(self.from_ns), end.min(self.to_ns));
        (start <= end && (start < end || self.in_window(start))).then_some((start, end))
    }

    /// Whether the event at `t_ns` is shown.
    pub fn shows(&self, t_ns: u64, event: &Event) -> bool {
        self.in_window(t_ns) && kind(event).is_none_or(|kind| self.shows_kind(kind))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_kind_list_shows_those_kinds_and_always_the_mode() {
        let filter = TraceFilter::all().kinds(&[Kind::Interrupts, Kind::Cycles]);
        let call = Event::BlockCall {
            from: "OB 1".into(),
            to: "PB 3".into(),
            depth: 1,
        };
        let mode = Event::Mode {
            from: "RUN",
            to: "STOP",
            cause: None,
        };
        assert!(!filter.shows(0, &call));
        assert!(filter.shows(0, &mode));
        assert!(filter.shows(0, &Event::CycleStart { cycle: 1 }));
    }

    #[test]
    fn the_window_includes_both_ends_and_clips_spans() {
        let filter = TraceFilter::all().window(Some(100), Some(200));
        assert!(filter.in_window(100) && filter.in_window(200) && !filter.in_window(201));
        assert_eq!(filter.clip(50, 150), Some((100, 150)));
        assert_eq!(filter.clip(150, 250), Some((150, 200)));
        assert_eq!(filter.clip(10, 20), None);
        assert_eq!(filter.clip(200, 300), Some((200, 200)));
    }
}
