//! An awlsim project file (`clockmem.awlpro`, XML, format version 1): awlsim's harness runs
//! some tests through one instead of a bare `.awl` file. awl reads what it can honour: the
//! number of accumulators, the clock memory byte, whether the OBs' start information is
//! written, the mnemonics, the program's STL sources and the symbol tables (each a file beside
//! the project or text inside it). The cycle time limit, run time limit and extended
//! instructions are read and checked, but awlsim's harness overrides them from its command
//! line (the `.conf`'s `cycle_limit` and `max_runtime`, the extensions always on), and so does
//! awl. Whatever else would change the run (FUP or KOP sources, library blocks, hardware
//! modules, CPU sizes other than awlsim's defaults, a target cycle time) is reported, since
//! awl cannot run it; the rest (the GUI's and the core server's settings) is ignored.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use miette::{Diagnostic, NamedSource, Report, SourceSpan};
use thiserror::Error;

use crate::mnemonics::MnemonicSet;

/// The format version awlsim 0.77.1 writes and reads.
const FORMAT_VERSION: &str = "1";

/// awlsim's CPU sizes that awl runs on the speed7 profile: a project may ask for these or less
/// (a program fits a larger CPU), not more. The defaults of awlsim 0.77.1 (`S7CPUSpecs`) but
/// for the process images (up to the SPEED7's largest, set as a project asks) and the flags,
/// where the SPEED7 CPU has more; `nr_accus` is read on its own.
const SPEED7_SPECS: &[(&str, i64)] = &[
    ("nr_timers", 256),
    ("nr_counters", 256),
    ("nr_flags", 8192),
    ("nr_inputs", 2048),
    ("nr_outputs", 2048),
    ("nr_localbytes", 1024),
    ("parenthesis_stack_size", 7),
    ("call_stack_size", 256),
];

/// The speed7 profile's process images, in bytes: a project asking for more gets them.
const PRESET_IMAGE_BYTES: i64 = 256;

/// awlsim's source types (`type=`): STL sources and symbol tables.
const AWL_SOURCE: &str = "0";
const SYMBOL_TABLE: &str = "3";

/// What a project file asks for, as awl runs it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Project {
    /// `<specs nr_accus=…>`: 2 or 4.
    pub accus: u8,
    /// `<specs nr_inputs=… nr_outputs=…>`: bytes of each process image, when the larger is
    /// more than the speed7 profile's preset.
    pub image_bytes: Option<u16>,
    /// `<config clock_memory_byte=…>`: the flag byte, when not −1.
    pub clock_memory: Option<u16>,
    /// `ob_startinfo_enable`: whether the OBs' start information is written.
    pub start_info: bool,
    /// `mnemonics`: `None` (0) detects them; 1 English, 2 German.
    pub mnemonics: Option<MnemonicSet>,
    /// `ext_insns_enable`, overridden by awlsim's harness (always on).
    pub extensions: bool,
    /// `cycle_time_limit_us`, in nanoseconds; overridden by the harness's `cycle_limit`.
    pub cycle_limit_ns: u64,
    /// `run_time_limit_us`, in nanoseconds (`None`: −1, no limit); overridden by the
    /// harness's `max_runtime`.
    pub max_runtime_ns: Option<u64>,
    /// The enabled STL sources, in order: a name and the text.
    pub programs: Vec<(PathBuf, Vec<u8>)>,
    /// The enabled symbol tables, in order.
    pub symbols: Vec<(PathBuf, Vec<u8>)>,
}

#[derive(Debug, Error, Diagnostic)]
pub enum ProjectError {
    #[error("cannot read `{path}`: {reason}")]
    #[diagnostic(
        code(awl::conformance::read_project),
        help("an awlsim project file is XML text in UTF-8")
    )]
    Read { path: String, reason: String },

    #[error("{message}")]
    #[diagnostic(code(awl::conformance::bad_project))]
    Bad {
        message: String,
        #[label("{label}")]
        at: SourceSpan,
        label: String,
        #[help]
        help: Option<String>,
    },

    #[error("{message}")]
    #[diagnostic(code(awl::conformance::project_not_run))]
    NotRun {
        message: String,
        #[label("{label}")]
        at: SourceSpan,
        label: String,
        #[help]
        help: Option<String>,
    },
}

/// Reads the project file `path` and the source files it names (relative to it).
pub fn read_project(path: &Path) -> Result<Project, Vec<Report>> {
    let read = |reason: String| {
        vec![Report::new(ProjectError::Read {
            path: path.display().to_string(),
            reason,
        })]
    };
    let bytes = std::fs::read(path).map_err(|error| read(error.to_string()))?;
    let text = String::from_utf8(bytes).map_err(|error| read(error.to_string()))?;
    let dir = path.parent().unwrap_or(Path::new(""));
    parse_project(&text, path, &mut |file| std::fs::read(dir.join(file))).map_err(|errors| {
        let source = NamedSource::new(path.display().to_string(), Arc::<str>::from(text));
        errors
            .into_iter()
            .map(|error| Report::new(error).with_source_code(source.clone()))
            .collect()
    })
}

/// Reads project text; `path` names its inline sources, `read` reads a source file by the
/// name the project gives. Every error found, each at its place.
pub fn parse_project(
    text: &str,
    path: &Path,
    read: &mut dyn FnMut(&str) -> std::io::Result<Vec<u8>>,
) -> Result<Project, Vec<ProjectError>> {
    let document = match roxmltree::Document::parse(text) {
        Ok(document) => document,
        Err(error) => {
            let at = offset_of(text, error.pos());
            return Err(vec![bad(
                format!("not an awlsim project file: {error}"),
                (at, 0).into(),
                "here",
                Some("an awlsim project file is XML; awl reads format version 1".into()),
            )]);
        }
    };
    let mut reader = Reader {
        project: Project {
            accus: 2,
            image_bytes: None,
            clock_memory: None,
            start_info: false,
            mnemonics: None,
            extensions: false,
            cycle_limit_ns: 1_000_000_000,
            max_runtime_ns: None,
            programs: Vec::new(),
            symbols: Vec::new(),
        },
        errors: Vec::new(),
    };
    let root = document.root_element();
    if root.tag_name().name() != "awlsim_project" {
        reader.errors.push(bad(
            format!("`<{}>` is not an awlsim project", root.tag_name().name()),
            tag_span(root),
            "not `<awlsim_project>`",
            Some("an awlsim project file's root element is `<awlsim_project>`".into()),
        ));
        return Err(reader.errors);
    }
    match root.attribute_node("format_version") {
        Some(version) if version.value() == FORMAT_VERSION => {}
        Some(version) => reader.errors.push(not_run(
            format!("project format version {} is not read", version.value()),
            span(version.range_value()),
            "this version",
            Some("awl reads awlsim's project format version 1 (awlsim 0.77.1 writes it)".into()),
        )),
        None => reader.errors.push(bad(
            "the project has no format version",
            tag_span(root),
            "no `format_version`",
            Some("awlsim writes `format_version=\"1\"`".into()),
        )),
    }
    for section in root.children().filter(roxmltree::Node::is_element) {
        match section.tag_name().name() {
            "cpu" => {
                for part in section.children().filter(roxmltree::Node::is_element) {
                    match part.tag_name().name() {
                        "specs" => reader.specs(part),
                        "config" => reader.config(part),
                        _ => {}
                    }
                }
            }
            "language_awl" => reader.sources(section, AWL_SOURCE, path, read, false),
            "symbols" => reader.sources(section, SYMBOL_TABLE, path, read, true),
            "language_fup" | "language_kop" => {
                let language = if section.tag_name().name() == "language_fup" {
                    "FUP (function block diagram)"
                } else {
                    "KOP (ladder)"
                };
                for source in enabled_sources(section) {
                    reader.errors.push(not_run(
                        format!("a {language} source is not run"),
                        span(source.range()),
                        "this source",
                        Some("awl runs STL only; awlsim compiles these to STL itself".into()),
                    ));
                }
            }
            "libraries" => reader.refuse_each(
                section,
                "lib_selection",
                "a block of awlsim's libraries is not run",
                "this library block",
                "awl has no copy of awlsim's library blocks (IEC, …)",
            ),
            "hardware" => reader.refuse_each(
                section,
                "module",
                "an awlsim hardware module is not simulated",
                "this module",
                "awl runs awlsim's tests on its dummy hardware only",
            ),
            // The core server's link and the GUI's settings do not touch the run.
            _ => {}
        }
    }
    if reader.errors.is_empty() {
        Ok(reader.project)
    } else {
        Err(reader.errors)
    }
}

struct Reader {
    project: Project,
    errors: Vec<ProjectError>,
}

impl Reader {
    /// An error for each `tag` element of `section`: a part of the project awl cannot run.
    fn refuse_each(
        &mut self,
        section: roxmltree::Node<'_, '_>,
        tag: &str,
        message: &str,
        label: &str,
        help: &str,
    ) {
        for node in section.children().filter(|node| node.has_tag_name(tag)) {
            self.errors.push(not_run(
                message,
                span(node.range()),
                label,
                Some(help.into()),
            ));
        }
    }

    /// An integer attribute, or `default` when absent; `None` (an error kept) when bad.
    fn int(&mut self, node: roxmltree::Node<'_, '_>, name: &str, default: i64) -> Option<i64> {
        let Some(attribute) = node.attribute_node(name) else {
            return Some(default);
        };
        match attribute.value().trim().parse::<i64>() {
            Ok(value) => Some(value),
            Err(_) => {
                self.errors.push(bad(
                    format!("`{name}` is not a number"),
                    span(attribute.range_value()),
                    "this value",
                    Some(format!("write a whole number, e.g. `{name}=\"{default}\"`")),
                ));
                None
            }
        }
    }

    /// `value` checked by `fits`; `None` (an error kept, `expected` its help) when it does
    /// not fit.
    fn checked<T>(
        &mut self,
        node: roxmltree::Node<'_, '_>,
        name: &str,
        default: i64,
        fits: impl Fn(i64) -> Option<T>,
        expected: &str,
    ) -> Option<T> {
        let value = self.int(node, name, default)?;
        let result = fits(value);
        if result.is_none() {
            let at = node
                .attribute_node(name)
                .map_or(node.range(), |attribute| attribute.range_value());
            self.errors.push(bad(
                format!("`{name}` {value} is out of range"),
                span(at),
                "this value",
                Some(expected.into()),
            ));
        }
        result
    }

    fn specs(&mut self, node: roxmltree::Node<'_, '_>) {
        if let Some(accus) = self.checked(
            node,
            "nr_accus",
            2,
            |n| matches!(n, 2 | 4).then_some(n as u8),
            "2 (as an S7-300) or 4 (as an S7-400)",
        ) {
            self.project.accus = accus;
        }
        for &(name, limit) in SPEED7_SPECS {
            let Some(value) = self.int(node, name, limit) else {
                continue;
            };
            if matches!(name, "nr_inputs" | "nr_outputs")
                && (PRESET_IMAGE_BYTES..=limit).contains(&value)
                && value
                    > i64::from(
                        self.project
                            .image_bytes
                            .unwrap_or(PRESET_IMAGE_BYTES as u16),
                    )
            {
                self.project.image_bytes = Some(value as u16);
            }
            if value > limit {
                let at = node
                    .attribute_node(name)
                    .map_or(node.range(), |attribute| attribute.range_value());
                self.errors.push(not_run(
                    format!("`{name}` {value} is more than awl's CPU has"),
                    span(at),
                    "not run as given",
                    Some(format!(
                        "awl runs awlsim's tests on the speed7 CPU, which has {name} {limit}"
                    )),
                ));
            }
        }
    }

    fn config(&mut self, node: roxmltree::Node<'_, '_>) {
        if let Some(byte) = self.checked(
            node,
            "clock_memory_byte",
            -1,
            |n| match n {
                -1 => Some(None),
                0..2048 => Some(Some(n as u16)),
                _ => None,
            },
            "a flag byte, 0 to 2047 (awlsim's 2048 flag bytes), or -1 for none",
        ) {
            self.project.clock_memory = byte;
        }
        if let Some(mnemonics) = self.checked(
            node,
            "mnemonics",
            0,
            |n| match n {
                0 => Some(None),
                1 => Some(Some(MnemonicSet::English)),
                2 => Some(Some(MnemonicSet::German)),
                _ => None,
            },
            "0 (detected), 1 (English) or 2 (German)",
        ) {
            self.project.mnemonics = mnemonics;
        }
        let flag = |n: i64| Some(n != 0);
        if let Some(on) = self.checked(node, "ob_startinfo_enable", 0, flag, "0 or 1") {
            self.project.start_info = on;
        }
        if let Some(on) = self.checked(node, "ext_insns_enable", 0, flag, "0 or 1") {
            self.project.extensions = on;
        }
        if let Some(limit) = self.checked(
            node,
            "cycle_time_limit_us",
            1_000_000,
            |n| {
                (1..=i64::from(u32::MAX))
                    .contains(&n)
                    .then(|| n as u64 * 1000)
            },
            "microseconds, above 0",
        ) {
            self.project.cycle_limit_ns = limit;
        }
        if let Some(limit) = self.checked(
            node,
            "run_time_limit_us",
            -1,
            |n| match n {
                ..0 => Some(None),
                0..=1_000_000_000_000 => Some(Some(n as u64 * 1000)),
                _ => None,
            },
            "microseconds, or -1 for no limit",
        ) {
            self.project.max_runtime_ns = limit;
        }
        if let Some(target) = self.int(node, "cycle_time_target_us", 0)
            && target != 0
        {
            let at = node
                .attribute_node("cycle_time_target_us")
                .map_or(node.range(), |attribute| attribute.range_value());
            self.errors.push(not_run(
                "a target cycle time is not simulated",
                span(at),
                "not 0",
                Some("awl's cycles take the time their operations take".into()),
            ));
        }
    }

    /// The `<source>`s of a section: each a file (relative to the project) or text inside.
    fn sources(
        &mut self,
        section: roxmltree::Node<'_, '_>,
        kind: &str,
        path: &Path,
        read: &mut dyn FnMut(&str) -> std::io::Result<Vec<u8>>,
        symbols: bool,
    ) {
        for (index, source) in enabled_sources(section).enumerate() {
            if let Some(given) = source.attribute_node("type")
                && given.value().trim() != kind
            {
                self.errors.push(bad(
                    format!(
                        "a source of type {} in `<{}>`",
                        given.value(),
                        section.tag_name().name()
                    ),
                    span(given.range_value()),
                    "this type",
                    Some(format!(
                        "awlsim writes type {kind} for the sources of `<{}>`",
                        section.tag_name().name()
                    )),
                ));
                continue;
            }
            let loaded = match source
                .attribute_node("file")
                .filter(|f| !f.value().is_empty())
            {
                Some(file) => match read(file.value()) {
                    Ok(bytes) => {
                        let dir = path.parent().unwrap_or(Path::new(""));
                        (dir.join(file.value()), bytes)
                    }
                    Err(error) => {
                        self.errors.push(bad(
                            format!("cannot read `{}`: {error}", file.value()),
                            span(file.range_value()),
                            "this file",
                            Some("a source file's name is relative to the project file".into()),
                        ));
                        continue;
                    }
                },
                None => {
                    let name = source.attribute("name").unwrap_or("source");
                    let text: String = source
                        .descendants()
                        .filter(roxmltree::Node::is_text)
                        .filter_map(|node| node.text())
                        .collect();
                    if text.trim().is_empty() {
                        // An empty table, as awlsim writes one for a new project: nothing.
                        continue;
                    }
                    let named = format!(
                        "{} [{} {}: {name}]",
                        path.display(),
                        section.tag_name().name(),
                        index + 1
                    );
                    (
                        PathBuf::from(named),
                        text.trim_matches(['\r', '\n']).as_bytes().to_vec(),
                    )
                }
            };
            if symbols {
                self.project.symbols.push(loaded);
            } else {
                self.project.programs.push(loaded);
            }
        }
    }
}

/// The `<source>`s of a section not switched off (`enabled="0"`).
fn enabled_sources<'a, 'input>(
    section: roxmltree::Node<'a, 'input>,
) -> impl Iterator<Item = roxmltree::Node<'a, 'input>> {
    section
        .children()
        .filter(|node| node.has_tag_name("source"))
        .filter(|node| node.attribute("enabled").is_none_or(|on| on.trim() != "0"))
}

/// The byte offset of a row and column (1-based, the column in characters).
fn offset_of(text: &str, pos: roxmltree::TextPos) -> usize {
    let line_start: usize = text
        .split_inclusive('\n')
        .take(pos.row.saturating_sub(1) as usize)
        .map(str::len)
        .sum();
    let line = &text[line_start.min(text.len())..];
    line_start
        + line
            .char_indices()
            .nth(pos.col.saturating_sub(1) as usize)
            .map_or(line.len(), |(at, _)| at)
}

/// An element's start: `<` and its name.
fn tag_span(node: roxmltree::Node<'_, '_>) -> SourceSpan {
    (node.range().start, node.tag_name().name().len() + 1).into()
}

fn span(range: std::ops::Range<usize>) -> SourceSpan {
    (range.start, range.len()).into()
}

fn bad(
    message: impl Into<String>,
    at: SourceSpan,
    label: &str,
    help: Option<String>,
) -> ProjectError {
    ProjectError::Bad {
        message: message.into(),
        at,
        label: label.into(),
        help,
    }
}

fn not_run(
    message: impl Into<String>,
    at: SourceSpan,
    label: &str,
    help: Option<String>,
) -> ProjectError {
    ProjectError::NotRun {
        message: message.into(),
        at,
        label: label.into(),
        help,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<Project, Vec<ProjectError>> {
        parse_project(text, Path::new("dir/p.awlpro"), &mut |file| match file {
            "a.awl" => Ok(b"ORGANIZATION_BLOCK OB 1\nBEGIN\nEND_ORGANIZATION_BLOCK\n".to_vec()),
            _ => Err(std::io::Error::new(
                std::io::ErrorKind::NotFound,
                "no such file",
            )),
        })
    }

    fn messages(text: &str) -> Vec<String> {
        parse(text)
            .expect_err("errors")
            .iter()
            .map(ToString::to_string)
            .collect()
    }

    #[test]
    fn without_settings_the_project_has_awlsim_s_defaults() {
        let project = parse("<awlsim_project format_version=\"1\"/>").unwrap();
        assert_eq!(project.accus, 2);
        assert_eq!(project.image_bytes, None);
        assert_eq!(project.clock_memory, None);
        assert!(!project.start_info && !project.extensions);
        assert_eq!(project.mnemonics, None);
        assert_eq!(project.cycle_limit_ns, 1_000_000_000);
        assert_eq!(project.max_runtime_ns, None);
        assert!(project.programs.is_empty() && project.symbols.is_empty());
    }

    #[test]
    fn every_key_awl_honours_is_read() {
        let project = parse(
            "<awlsim_project format_version=\"1\"><cpu>\
             <specs nr_accus=\"4\" nr_inputs=\"1024\" nr_outputs=\"512\"/>\
             <config clock_memory_byte=\"7\" mnemonics=\"1\" ob_startinfo_enable=\"1\" \
             ext_insns_enable=\"1\" cycle_time_limit_us=\"2000\" run_time_limit_us=\"300\"/>\
             </cpu><language_awl>\
             <source enabled=\"1\" file=\"a.awl\" type=\"0\"/>\
             <source enabled=\"0\" type=\"0\">not read</source>\
             <source name=\"B\" type=\"0\"><![CDATA[\nFC text\n]]></source>\
             </language_awl><symbols><source name=\"S\" type=\"3\">\n\n</source></symbols>\
             <core_link/><gui/></awlsim_project>",
        )
        .unwrap();
        assert_eq!(project.accus, 4);
        assert_eq!(project.image_bytes, Some(1024));
        assert_eq!(project.clock_memory, Some(7));
        assert_eq!(project.mnemonics, Some(MnemonicSet::English));
        assert!(project.start_info && project.extensions);
        assert_eq!(project.cycle_limit_ns, 2_000_000);
        assert_eq!(project.max_runtime_ns, Some(300_000));
        let names: Vec<String> = project
            .programs
            .iter()
            .map(|(name, _)| name.display().to_string())
            .collect();
        assert_eq!(names, ["dir/a.awl", "dir/p.awlpro [language_awl 2: B]"]);
        assert_eq!(project.programs[1].1, b"FC text");
        // An empty symbol table is none.
        assert!(project.symbols.is_empty());
        let german = parse(
            "<awlsim_project format_version=\"1\"><cpu><config mnemonics=\"2\"/></cpu>\
             </awlsim_project>",
        )
        .unwrap();
        assert_eq!(german.mnemonics, Some(MnemonicSet::German));
    }

    #[test]
    fn malformed_text_is_an_error_never_a_panic() {
        for text in [
            "",
            "not xml",
            "<awlsim_project",
            "<a></b>",
            "\u{feff}<?xml version=\"1.0\"?>\n<x>\n</y>",
            "<awlsim_project format_version=\"1\"><cpu><specs nr_accus=\"ä\"/></cpu>",
        ] {
            assert!(parse(text).is_err(), "{text:?}");
        }
        assert_eq!(
            messages("<project/>"),
            ["`<project>` is not an awlsim project"]
        );
        assert_eq!(
            messages("<awlsim_project/>"),
            ["the project has no format version"]
        );
        assert_eq!(
            messages("<awlsim_project format_version=\"0\"/>"),
            ["project format version 0 is not read"]
        );
    }

    #[test]
    fn what_awl_cannot_honour_is_reported() {
        let found = messages(
            "<awlsim_project format_version=\"1\"><cpu>\
             <specs nr_accus=\"3\" nr_flags=\"9000\"/>\
             <config clock_memory_byte=\"5000\" mnemonics=\"x\" cycle_time_target_us=\"1\"/>\
             </cpu><language_awl><source file=\"gone.awl\" type=\"0\"/>\
             <source file=\"a.awl\" type=\"3\"/></language_awl>\
             <language_kop><source type=\"2\"/></language_kop>\
             <libraries><lib_selection/></libraries>\
             <hardware><module name=\"dummy\"/></hardware></awlsim_project>",
        );
        assert_eq!(
            found,
            [
                "`nr_accus` 3 is out of range",
                "`nr_flags` 9000 is more than awl's CPU has",
                "`clock_memory_byte` 5000 is out of range",
                "`mnemonics` is not a number",
                "a target cycle time is not simulated",
                "cannot read `gone.awl`: no such file",
                "a source of type 3 in `<language_awl>`",
                "a KOP (ladder) source is not run",
                "a block of awlsim's libraries is not run",
                "an awlsim hardware module is not simulated",
            ]
        );
    }
}
