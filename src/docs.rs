//! The formats awl reads and writes, as the repository documents them: `awl help TOPIC` prints
//! them from the same files, compiled into the binary, so an installed awl carries its own
//! documentation and it cannot drift from the repository's.

use miette::Diagnostic;
use thiserror::Error;

const PROGRAMS: &str = include_str!("../programs/README.md");
const GRAMMAR: &str = include_str!("../grammar/README.md");
const ERRORS: &str = include_str!("../grammar/errors.md");

/// A topic of `awl help`: a file, or one `## ` section of it.
pub struct Topic {
    pub name: &'static str,
    pub summary: &'static str,
    file: &'static str,
    /// The `## ` heading of the section; `None` is the whole file.
    heading: Option<&'static str>,
}

pub const TOPICS: &[Topic] = &[
    Topic {
        name: "scenario",
        summary: "scenario files (TOML): run length, CPU, events, [expect], [[check]], watch",
        file: PROGRAMS,
        heading: Some("Scenario files"),
    },
    Topic {
        name: "trace",
        summary: "the trace of `awl run --trace`: its events in jsonl, text and chrome",
        file: PROGRAMS,
        heading: Some("Traces"),
    },
    Topic {
        name: "timeline",
        summary: "the timeline pictures of `awl run --timeline` (SVG, HTML)",
        file: PROGRAMS,
        heading: Some("Timeline pictures"),
    },
    Topic {
        name: "state",
        summary: "the CPU's state as JSON (`awl run --state-format json`)",
        file: PROGRAMS,
        heading: Some("The state as JSON"),
    },
    Topic {
        name: "analysis",
        summary: "the analysis as JSON (`awl analyze --format json`)",
        file: PROGRAMS,
        heading: Some("The analysis as JSON"),
    },
    Topic {
        name: "exit-codes",
        summary: "what each exit code means",
        file: PROGRAMS,
        heading: Some("Exit codes"),
    },
    Topic {
        name: "listing",
        summary: "STEP 5 PG listings: segments, statement addresses, `***`",
        file: GRAMMAR,
        heading: Some("PG listings"),
    },
    Topic {
        name: "symbols",
        summary: "symbolic operands (`-START`, STEP 7 `\"Motor\"`), the assignment list and STEP 7 symbol tables (`--symbols`)",
        file: GRAMMAR,
        heading: Some("Symbolic operands"),
    },
    Topic {
        name: "library",
        summary: "the library FCs a STEP 7 program calls without writing them (IEC FC 1–40, SCALE, UNSCALE)",
        file: GRAMMAR,
        heading: Some("Library blocks"),
    },
    Topic {
        name: "language",
        summary: "the STL awl reads: blocks, statements, operands, constants",
        file: GRAMMAR,
        heading: None,
    },
    Topic {
        name: "errors",
        summary: "every error and warning code, what causes it and how to fix it",
        file: ERRORS,
        heading: None,
    },
];

#[derive(Debug, Error, Diagnostic)]
#[error("`{asked}` is neither a help topic nor a command")]
#[diagnostic(
    code(awl::help::unknown_topic),
    help("topics: {topics}; commands: {commands}")
)]
pub struct UnknownTopic {
    pub asked: String,
    pub topics: String,
    pub commands: String,
}

/// The topic of that name.
pub fn find(name: &str) -> Option<&'static Topic> {
    TOPICS
        .iter()
        .find(|topic| topic.name.eq_ignore_ascii_case(name.trim()))
}

/// One line per topic: its name and what it covers.
pub fn list() -> String {
    let width = TOPICS
        .iter()
        .map(|topic| topic.name.len())
        .max()
        .unwrap_or(0);
    TOPICS
        .iter()
        .map(|topic| format!("  {:width$}  {}\n", topic.name, topic.summary))
        .collect()
}

impl Topic {
    /// The topic's text: its section from its heading up to the next heading of the same
    /// level, or the whole file.
    pub fn text(&self) -> &'static str {
        let Some(heading) = self.heading else {
            return self.file;
        };
        let title = format!("## {heading}\n");
        let start = self
            .file
            .find(&title)
            .expect("a topic's heading is in its file (tests/help.rs)");
        let rest = &self.file[start + title.len()..];
        let end = rest
            .find("\n## ")
            .map_or(self.file.len(), |at| start + title.len() + at + 1);
        &self.file[start..end]
    }
}
