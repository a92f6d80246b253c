//! The formats awl reads and writes, as the repository documents them: `awl help TOPIC` prints
//! them from the same files, compiled into the binary, so an installed awl carries its own
//! documentation and it cannot drift from the repository's. Where the text is a table awl itself
//! uses (the STEP 7 mnemonics, each CPU's watchdog), it is made from that table.
//!
//! The repository's files link to each other; the binary prints a link's text without its
//! target, so nothing it prints sends the user to a file an installed awl does not have.

use std::fmt::Write;

use miette::Diagnostic;
use thiserror::Error;

use crate::profile;
use crate::step7::mnemonics as s7;

const PROGRAMS: &str = include_str!("../programs/README.md");
const GRAMMAR: &str = include_str!("../grammar/README.md");
const ERRORS: &str = include_str!("../grammar/errors.md");
const MNEMONICS: &str = include_str!("../grammar/mnemonics.md");
const STL_EBNF: &str = include_str!("../grammar/stl.ebnf");
const STL7_EBNF: &str = include_str!("../grammar/stl7.ebnf");
const EDITORS: &str = include_str!("../editors/README.md");

/// Where a topic's text comes from.
enum Body {
    /// A section of a file: from its heading line (`## Traces`) to the next heading of the same
    /// or a higher level.
    Section(&'static str, &'static str),
    /// A whole file.
    File(&'static str),
    /// Made when asked.
    Made(fn() -> String),
}

/// A topic of `awl help`.
pub struct Topic {
    pub name: &'static str,
    pub summary: &'static str,
    body: Body,
}

pub const TOPICS: &[Topic] = &[
    Topic {
        name: "scenario",
        summary: "scenario files (TOML): run length, CPU, events, [expect], [[check]], watch",
        body: Body::Made(scenario),
    },
    Topic {
        name: "trace",
        summary: "the trace of `awl run --trace`: its events in jsonl, text and chrome",
        body: Body::Section(PROGRAMS, "## Traces"),
    },
    Topic {
        name: "timeline",
        summary: "the timeline pictures of `awl run --timeline` (SVG, HTML)",
        body: Body::Section(PROGRAMS, "## Timeline pictures"),
    },
    Topic {
        name: "state",
        summary: "the CPU's state as JSON (`awl run --state-format json`)",
        body: Body::Section(PROGRAMS, "## The state as JSON"),
    },
    Topic {
        name: "analysis",
        summary: "the analysis as JSON (`awl analyze --format json`)",
        body: Body::Section(PROGRAMS, "## The analysis as JSON"),
    },
    Topic {
        name: "start-info",
        summary: "the start information a STEP 7 OB gets in its local data (OB1_PREV_CYCLE, OB40_POINT_ADDR, …)",
        body: Body::Section(PROGRAMS, "#### OB start information"),
    },
    Topic {
        name: "serve",
        summary: "`awl serve`: the virtual PLC on the network (S7comm, Modbus TCP, OPC UA), its areas and maps",
        body: Body::Section(PROGRAMS, "## The virtual PLC (`awl serve`)"),
    },
    Topic {
        name: "online",
        summary: "`awl serve --http`: the online page and its JSON API (watch, modify, force, program status, the live timeline)",
        body: Body::Section(PROGRAMS, "## The online page (`awl serve --http`)"),
    },
    Topic {
        name: "retain",
        summary: "retentive memory kept across restarts (`--retain`) and snapshots to continue from (`--from`)",
        body: Body::Section(PROGRAMS, "## Retentive memory and snapshots"),
    },
    Topic {
        name: "lsp",
        summary: "`awl lsp` in an editor: what the language server offers, its settings, the setup of VS Code, Neovim and Helix",
        body: Body::File(EDITORS),
    },
    Topic {
        name: "dap",
        summary: "`awl dap` in an editor: launching, breakpoints, stepping, OB levels as threads, scopes, the setup of VS Code, Neovim (nvim-dap) and Helix",
        body: Body::Section(EDITORS, "## Debugging: awl dap"),
    },
    Topic {
        name: "exit-codes",
        summary: "what each command's exit codes mean",
        body: Body::Section(PROGRAMS, "## Exit codes"),
    },
    Topic {
        name: "listing",
        summary: "STEP 5 PG listings: segments, statement addresses, `***`",
        body: Body::Section(GRAMMAR, "## PG listings"),
    },
    Topic {
        name: "symbols",
        summary: "symbolic operands (`-START`, STEP 7 `\"Motor\"`), the assignment list and STEP 7 symbol tables (`--symbols`)",
        body: Body::Section(GRAMMAR, "## Symbolic operands"),
    },
    Topic {
        name: "library",
        summary: "the library FCs a STEP 7 program calls without writing them (IEC FC 1–40, SCALE, UNSCALE)",
        body: Body::Section(GRAMMAR, "## Library blocks"),
    },
    Topic {
        name: "language",
        summary: "the STL awl reads, STEP 5 and STEP 7: blocks, statements, operands, constants",
        body: Body::File(GRAMMAR),
    },
    Topic {
        name: "mnemonics",
        summary: "every word of the English and German mnemonics, STEP 5 and STEP 7",
        body: Body::Made(mnemonics),
    },
    Topic {
        name: "grammar",
        summary: "the formal grammars (EBNF) of STEP 5 and STEP 7 STL",
        body: Body::Made(grammars),
    },
    Topic {
        name: "errors",
        summary: "every error and warning code, what causes it and how to fix it (one: `awl help error CODE`)",
        body: Body::File(ERRORS),
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

#[derive(Debug, Error, Diagnostic)]
#[error("`{asked}` is no error code of awl")]
#[diagnostic(code(awl::help::unknown_code))]
pub struct UnknownCode {
    pub asked: String,
    #[help]
    pub help: String,
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
    let mut list: String = TOPICS
        .iter()
        .map(|topic| format!("  {:width$}  {}\n", topic.name, topic.summary))
        .collect();
    let _ = writeln!(
        list,
        "\nOne diagnostic code explained: `awl help error CODE` (`awl help error parse::unknown_operation`)"
    );
    list
}

impl Topic {
    /// The topic's text, as printed.
    pub fn text(&self) -> String {
        without_link_targets(&match self.body {
            Body::Section(file, heading) => section(file, heading).to_string(),
            Body::File(file) => file.to_string(),
            Body::Made(make) => make(),
        })
    }
}

/// The section of `file` that starts at the line `heading`, up to the next heading of the same
/// or a higher level.
fn section(file: &'static str, heading: &str) -> &'static str {
    let level = heading.bytes().take_while(|&byte| byte == b'#').count();
    let start = file
        .match_indices(heading)
        .map(|(at, _)| at)
        .find(|&at| {
            (at == 0 || file[..at].ends_with('\n')) && file[at + heading.len()..].starts_with('\n')
        })
        .expect("a topic's heading is in its file (tests/help.rs)");
    let body_start = start + heading.len();
    let mut offset = body_start;
    for line in file[body_start..].split_inclusive('\n') {
        let hashes = line.bytes().take_while(|&byte| byte == b'#').count();
        if hashes > 0 && hashes <= level && line[hashes..].starts_with(' ') {
            return &file[start..offset];
        }
        offset += line.len();
    }
    &file[start..]
}

/// Markdown links without their targets: `[the grammar](stl.ebnf)` → `the grammar`. Links to
/// the web keep theirs.
fn without_link_targets(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(open) = rest.find('[') {
        let after = &rest[open + 1..];
        let link = after.find("](").and_then(|close| {
            let target_start = close + 2;
            let target_end = after[target_start..].find(')')? + target_start;
            let target = &after[target_start..target_end];
            let inside = &after[..close];
            let plain = !inside.contains(['\n', '[', ']']) && !target.contains(char::is_whitespace);
            (plain && !target.starts_with("http")).then_some((inside, target_end + 1))
        });
        match link {
            Some((inside, end)) => {
                out.push_str(&rest[..open]);
                out.push_str(inside);
                rest = &after[end..];
            }
            None => {
                out.push_str(&rest[..=open]);
                rest = after;
            }
        }
    }
    out.push_str(rest);
    out
}

/// What the language reference says about the status bits of the operation `english` (its
/// English word): the paragraphs that name it in code and name a status bit, and the rows of
/// the status tables that name it, at most `MOST_NOTES`. The STEP 5 part of the reference or
/// the STEP 7 part, as `step7` says.
pub fn status_notes(english: &str, step7: bool) -> Vec<String> {
    const MOST_NOTES: usize = 3;
    const BITS: &[&str] = &[
        "RLO", "STA", "OR", "OS", "OV", "CC 0", "CC0", "CC 1", "CC1", "BR", "/FC",
    ];
    let split = GRAMMAR
        .find("\n## STEP 7 operations")
        .unwrap_or(GRAMMAR.len());
    let part = if step7 {
        &GRAMMAR[split..]
    } else {
        &GRAMMAR[..split]
    };
    let names_it = |text: &str| {
        text.split('`')
            .skip(1)
            .step_by(2)
            .any(|code| code.split_whitespace().any(|word| word == english))
    };
    let names_a_bit = |text: &str| {
        BITS.iter().any(|bit| {
            text.match_indices(bit).any(|(at, _)| {
                let before = text[..at].chars().next_back();
                let after = text[at + bit.len()..].chars().next();
                !before.is_some_and(char::is_alphanumeric)
                    && !after.is_some_and(char::is_alphanumeric)
            })
        })
    };
    let mut notes = Vec::new();
    for paragraph in part.split("\n\n").map(str::trim) {
        if paragraph.starts_with('|') {
            let mut lines = paragraph.lines();
            let (Some(header), Some(rule)) = (lines.next(), lines.next()) else {
                continue;
            };
            let rows: Vec<&str> = lines
                .filter(|row| row.split('|').nth(1).is_some_and(names_it))
                .collect();
            if !rows.is_empty() && names_a_bit(header) {
                notes.push(format!("{header}\n{rule}\n{}", rows.join("\n")));
            }
        } else if !paragraph.starts_with('#') && names_it(paragraph) && names_a_bit(paragraph) {
            notes.push(without_link_targets(paragraph));
        }
        if notes.len() == MOST_NOTES {
            break;
        }
    }
    notes
}

/// The scenario format, with each CPU's watchdog as its profile sets it.
fn scenario() -> String {
    let mut text = section(PROGRAMS, "## Scenario files")
        .trim_end()
        .to_string();
    text.push_str(
        "\n\n### Each CPU's watchdog\n\nWithout `watchdog`, a run monitors the cycle with its CPU's \
         time (`awl cpus`):\n\n| CPU | watchdog |\n|---|---|\n",
    );
    for cpu in profile::PROFILES {
        let _ = writeln!(
            text,
            "| `{}` | {} ms |",
            cpu.name,
            cpu.watchdog_ns / 1_000_000
        );
    }
    text
}

/// The STEP 5 mnemonic table and the STEP 7 one, made from the table the STEP 7 parser reads.
fn mnemonics() -> String {
    let mut text = MNEMONICS.trim_end().to_string();
    text.push_str(
        "\n\n# STEP 7 mnemonics\n\nBoth sets of STEP 7 STL, as the parser reads them: a file uses \
         one, detected as in STEP 5 files, and `--mnemonics en|de` overrides the detection. \
         `awl help language` says what each operation does.\n\n## Operations\n\n\
         | English | German |\n|---|---|\n",
    );
    for words in s7::OPERATIONS {
        let _ = writeln!(text, "| `{}` | `{}` |", words.en, words.de);
    }
    text.push_str("\n## Operand areas\n\n| English | German |\n|---|---|\n");
    for area in s7::AREAS {
        let _ = writeln!(text, "| `{}` | `{}` |", area.en, area.de);
    }
    text.push_str("\n## Status conditions (`A ==0`, `A OV`)\n\n| English | German |\n|---|---|\n");
    for (_, en, de) in s7::CONDITIONS {
        let _ = writeln!(text, "| `{en}` | `{de}` |");
    }
    text.push_str(
        "\n## awlsim's test operations (`--extended`)\n\n| English | German |\n|---|---|\n",
    );
    for words in s7::EXTENSION_OPERATIONS {
        let _ = writeln!(text, "| `{}` | `{}` |", words.en, words.de);
    }
    text
}

fn grammars() -> String {
    format!(
        "STEP 5 STL\n\n{}\nSTEP 7 STL\n\n{}",
        STL_EBNF.trim_end(),
        STL7_EBNF
    )
}

/// One diagnostic code's page: its heading and text.
pub struct ErrorPage {
    pub code: &'static str,
    pub text: &'static str,
}

/// Every code's page, in the order of the error reference.
pub fn error_pages() -> Vec<ErrorPage> {
    let mut pages = Vec::new();
    let mut rest = ERRORS;
    while let Some(at) = rest.find("\n### ") {
        let page = &rest[at + 1..];
        let end = page.find("\n#").map_or(page.len(), |end| end + 1);
        let code = page["### ".len()..]
            .split_whitespace()
            .next()
            .unwrap_or_default();
        pages.push(ErrorPage {
            code,
            text: &page[..end],
        });
        rest = &page[end.saturating_sub(1)..];
    }
    pages
}

/// The page of `asked`, written with or without its `awl::`.
pub fn error_page(asked: &str) -> Result<String, UnknownCode> {
    let asked = asked.trim();
    let code = asked
        .strip_prefix("awl::")
        .unwrap_or(asked)
        .to_ascii_lowercase();
    let pages = error_pages();
    if let Some(page) = pages.iter().find(|page| page.code["awl::".len()..] == code) {
        return Ok(without_link_targets(page.text));
    }
    Err(UnknownCode {
        asked: asked.to_string(),
        help: code_help(&code, &pages),
    })
}

/// The codes close to a mistyped one, or those that end the same way (`unknown_operation`).
fn code_help(code: &str, pages: &[ErrorPage]) -> String {
    let full = format!("awl::{code}");
    let mut close: Vec<&str> = pages
        .iter()
        .map(|page| page.code)
        .filter(|known| known.ends_with(&format!("::{code}")))
        .collect();
    if close.is_empty() {
        close.extend(crate::suggest::did_you_mean(
            &full,
            pages.iter().map(|page| page.code),
        ));
    }
    let list = "`awl help error` lists every code";
    match close.as_slice() {
        [] => format!("{list}; a diagnostic names its code above its message"),
        codes => format!(
            "did you mean {}? {list}",
            codes
                .iter()
                .map(|known| format!("`{known}`"))
                .collect::<Vec<_>>()
                .join(" or ")
        ),
    }
}

/// The list of codes under the headings of the error reference.
pub fn error_list() -> String {
    let mut text = String::from(
        "Every diagnostic code; `awl help error CODE` explains one, `awl help errors` all.\n",
    );
    for line in ERRORS.lines() {
        if let Some(group) = line.strip_prefix("## ") {
            let _ = write!(text, "\n{group}\n");
        } else if let Some(code) = line.strip_prefix("### ") {
            let _ = writeln!(text, "  {code}");
        }
    }
    text
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn links_keep_their_text_and_lose_a_file_target() {
        assert_eq!(
            without_link_targets("see [`awl help mnemonics`](mnemonics.md#x), [web](https://a.b)"),
            "see `awl help mnemonics`, [web](https://a.b)"
        );
        assert_eq!(
            without_link_targets("[[event]]\nat = 1 [x] and [y](t.md)"),
            "[[event]]\nat = 1 [x] and y"
        );
    }

    #[test]
    fn the_status_notes_of_an_operation_name_its_bits() {
        let notes = status_notes("JC", false);
        assert!(notes.iter().any(|note| note.contains("RLO")), "{notes:?}");
        let float = status_notes("+G", false);
        assert!(
            float.iter().any(|note| note.starts_with("| operation |")),
            "{float:?}"
        );
        assert!(status_notes("NOSUCHWORD", true).is_empty());
    }

    #[test]
    fn a_section_ends_at_a_heading_of_its_level_or_higher() {
        let file = "# A\n## B\ntext\n### C\nmore\n## D\nrest\n";
        assert_eq!(section(file, "## B"), "## B\ntext\n### C\nmore\n");
        assert_eq!(section(file, "### C"), "### C\nmore\n");
        assert_eq!(section(file, "## D"), "## D\nrest\n");
    }
}
