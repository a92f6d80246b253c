//! The jsonl trace: one JSON object per event and line, `t_ns` and `ev` first; the fields are
//! documented in programs/README.md and stay stable.

use std::io::Write;

use serde::Serialize;

use super::{Event, Sink, TraceFilter};

#[derive(Serialize)]
struct Record<'a> {
    t_ns: u64,
    #[serde(flatten)]
    event: &'a Event,
}

pub struct Jsonl {
    out: Box<dyn Write>,
    filter: TraceFilter,
}

impl Jsonl {
    pub fn new(out: Box<dyn Write>, filter: TraceFilter) -> Self {
        Jsonl { out, filter }
    }
}

impl Sink for Jsonl {
    fn event(&mut self, t_ns: u64, event: &Event) -> std::io::Result<()> {
        if !self.filter.shows(t_ns, event) {
            return Ok(());
        }
        serde_json::to_writer(&mut self.out, &Record { t_ns, event })
            .map_err(std::io::Error::other)?;
        self.out.write_all(b"\n")
    }

    fn finish(&mut self, _end_ns: u64) -> std::io::Result<()> {
        self.out.flush()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn jsonl_has_the_stable_field_names() {
        let record = Record {
            t_ns: 1500,
            event: &Event::IrqService {
                id: 1,
                ob: 3,
                latency_ns: 20,
                point: "block_end",
                block: None,
                waited: None,
            },
        };
        assert_eq!(
            serde_json::to_string(&record).unwrap(),
            r#"{"t_ns":1500,"ev":"irq_service","id":1,"ob":3,"latency_ns":20,"point":"block_end"}"#
        );
    }
}
