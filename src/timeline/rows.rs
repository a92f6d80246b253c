//! The picture's marks, kept per row and merged where they would fall into one pixel: a long
//! run stays legible and its file small, and every merged mark keeps how many it stands for.

use std::collections::BTreeMap;

/// What a mark is; its CSS class in the picture.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Mark {
    /// A level had the CPU.
    Run,
    Block,
    /// A block change: a call or a block end, an interrupt point.
    Tick,
    Request,
    Service,
    Lost,
    Ignored,
    /// A request SFC 39 DIS_IRT had disabled.
    Discarded,
    /// The wait of a request SFC 41 DIS_AIRT delayed, from the delay to its service.
    Delayed,
    /// A call of SFC 39 to SFC 42 on the calling OB's level.
    IrtCall,
    /// A module's hardware event that is no request.
    ModuleEvent,
    DataCycle,
    OsTime,
    /// S7: the wait for the minimum cycle time.
    CycleWait,
    /// A cycle's start.
    Cycle,
    Stop,
    Input,
    Output,
    /// A network client's write (`awl serve`).
    ClientWrite,
}

impl Mark {
    pub fn class(self) -> &'static str {
        match self {
            Mark::Run => "run",
            Mark::Block => "block",
            Mark::Tick => "tick",
            Mark::Request => "request",
            Mark::Service => "service",
            Mark::Lost => "lost",
            Mark::Ignored => "ignored",
            Mark::Discarded => "discarded",
            Mark::Delayed => "delayed",
            Mark::IrtCall => "irt-call",
            Mark::ModuleEvent => "module-event",
            Mark::DataCycle => "data-cycle",
            Mark::OsTime => "os-time",
            Mark::CycleWait => "cycle-wait",
            Mark::Cycle => "cycle",
            Mark::Stop => "stop",
            Mark::Input => "input",
            Mark::Output => "output",
            Mark::ClientWrite => "client-write",
        }
    }

    /// What several of them are called in a merged mark's title.
    pub fn plural(self) -> &'static str {
        match self {
            Mark::Run => "stretches of running",
            Mark::Block => "block runs",
            Mark::Tick => "block changes",
            Mark::Request => "requests",
            Mark::Service => "services",
            Mark::Lost => "lost requests",
            Mark::Ignored => "ignored requests",
            Mark::Discarded => "discarded requests",
            Mark::Delayed => "delayed requests",
            Mark::IrtCall => "SFC 39–42 calls",
            Mark::ModuleEvent => "module events",
            Mark::DataCycle => "data cycles",
            Mark::OsTime => "stretches of operating-system time",
            Mark::CycleWait => "waits for the minimum cycle time",
            Mark::Cycle => "cycle starts",
            Mark::Stop => "STOPs",
            Mark::Input => "input changes",
            Mark::Output => "output changes",
            Mark::ClientWrite => "client writes",
        }
    }
}

/// Where a mark goes: its kind, its level's OB (0: the whole height or the I/O strip) and,
/// for blocks, the call depth.
pub type RowKey = (Mark, u8, u8);

/// One drawn mark, or several merged into one.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Item {
    pub start: u64,
    pub end: u64,
    /// How many events of its kind it stands for (0: a block called before the window).
    pub count: u32,
    /// The time it covers in total (its parts' lengths).
    pub busy_ns: u64,
    /// Its name inside a bar (`PB 3`), or the short label above a mark.
    pub label: String,
    /// Its details, for the title.
    pub detail: String,
    /// A service: when the earliest request it stands for came, and the latencies.
    pub requested_at: u64,
    pub latency: (u64, u64),
    /// Merged from marks with different labels.
    pub mixed: bool,
}

impl Item {
    pub fn new(start: u64, end: u64, label: String, detail: String) -> Self {
        Item {
            start,
            end,
            count: 1,
            busy_ns: end - start,
            label,
            detail,
            requested_at: start,
            latency: (0, 0),
            mixed: false,
        }
    }

    fn width(&self) -> u64 {
        self.end - self.start
    }

    /// Whether `next` falls into this one's last pixel and one of them is too thin to see.
    fn merges(&self, next: &Item, pixel_ns: u64) -> bool {
        pixel_ns > 0
            && next.start < self.end.saturating_add(pixel_ns)
            && (self.width() < pixel_ns || next.width() < pixel_ns)
    }

    fn absorb(&mut self, next: Item) {
        self.mixed |= next.mixed || next.label != self.label;
        self.latency = (
            self.latency.0.min(next.latency.0),
            self.latency.1.max(next.latency.1),
        );
        self.end = self.end.max(next.end);
        self.count += next.count;
        self.busy_ns += next.busy_ns;
        self.requested_at = self.requested_at.min(next.requested_at);
    }
}

/// Every row's marks, merged at `pixel_ns`.
#[derive(Debug, Default)]
pub struct Rows {
    pub rows: BTreeMap<RowKey, Vec<Item>>,
    pixel_ns: u64,
    items: usize,
}

/// Above this many marks kept, the rows merge at a coarser pixel.
const KEEP_AT_MOST: usize = 100_000;

impl Rows {
    pub fn push(&mut self, key: RowKey, item: Item) {
        let row = self.rows.entry(key).or_default();
        match row.last_mut() {
            Some(last) if last.merges(&item, self.pixel_ns) => last.absorb(item),
            _ => {
                row.push(item);
                self.items += 1;
            }
        }
    }

    /// Whether `item` would merge into the last mark of its row.
    pub fn merges(&self, key: &RowKey, item: &Item) -> bool {
        self.rows
            .get(key)
            .and_then(|row| row.last())
            .is_some_and(|last| last.merges(item, self.pixel_ns))
    }

    /// Keeps memory bounded on a long run: merges at a coarser pixel when too many marks are
    /// kept; `span_ns` is the time seen so far.
    pub fn bound(&mut self, span_ns: u64, plot_width: u64) {
        if self.items > KEEP_AT_MOST {
            let pixel = (self.pixel_ns * 2).max(span_ns / (plot_width * 4)).max(1);
            self.merge_at(pixel);
        }
    }

    /// Merges every row at `pixel_ns`.
    pub fn merge_at(&mut self, pixel_ns: u64) {
        self.pixel_ns = pixel_ns;
        self.items = 0;
        for row in self.rows.values_mut() {
            let mut merged: Vec<Item> = Vec::with_capacity(row.len());
            for item in row.drain(..) {
                match merged.last_mut() {
                    Some(last) if last.merges(&item, pixel_ns) => last.absorb(item),
                    _ => merged.push(item),
                }
            }
            self.items += merged.len();
            *row = merged;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tick(at: u64) -> Item {
        Item::new(at, at, String::new(), format!("at {at}"))
    }

    #[test]
    fn marks_in_one_pixel_merge_and_keep_their_count() {
        let mut rows = Rows::default();
        rows.merge_at(10);
        for at in [0, 3, 9, 25] {
            rows.push((Mark::Tick, 1, 0), tick(at));
        }
        let row = &rows.rows[&(Mark::Tick, 1, 0)];
        assert_eq!(row.len(), 2);
        assert_eq!((row[0].count, row[0].start, row[0].end), (3, 0, 9));
        assert_eq!(row[1].count, 1);
    }

    #[test]
    fn wide_bars_stay_apart_and_exact_rows_never_merge() {
        let mut rows = Rows::default();
        rows.merge_at(10);
        let bar = |start, end| Item::new(start, end, "PB 3".into(), String::new());
        rows.push((Mark::Block, 1, 1), bar(0, 50));
        rows.push((Mark::Block, 1, 1), bar(52, 100));
        assert_eq!(rows.rows[&(Mark::Block, 1, 1)].len(), 2);
        let mut exact = Rows::default();
        exact.push((Mark::Tick, 1, 0), tick(5));
        exact.push((Mark::Tick, 1, 0), tick(5));
        assert_eq!(exact.rows[&(Mark::Tick, 1, 0)].len(), 2);
    }

    #[test]
    fn a_coarser_pixel_merges_what_was_kept() {
        let mut rows = Rows::default();
        for at in 0..10 {
            rows.push((Mark::Tick, 1, 0), tick(at * 10));
        }
        rows.merge_at(1000);
        let row = &rows.rows[&(Mark::Tick, 1, 0)];
        assert_eq!(row.len(), 1);
        assert_eq!(row[0].count, 10);
    }
}
