//! awlsim projects (`tauchbad.awlpro`): a program's STL sources, its symbol tables and the CPU's
//! settings in one file, in awlsim's XML format (version 1, [`format1`]) or its older INI-like
//! text (version 0, [`format0`]). Every command reads one as its program; `awl conformance` runs
//! awlsim's tests through them.
//!
//! awl reads what it can honour: the number of accumulators, the process images, the L stack,
//! the clock memory byte, whether the OBs' start information is written, the mnemonics, awlsim's
//! test operations, the cycle time limit and the run time limit, the STL sources and the symbol
//! tables (each a file beside the project or text inside it). Whatever else would change the
//! run (FUP or KOP sources, library blocks, hardware modules, CPU sizes other than awlsim's
//! defaults, a target cycle time) is reported, since awl cannot run it; the rest (the GUI's and
//! the core server's settings) is ignored.

mod format0;
#[cfg(not(target_arch = "wasm32"))]
mod format1;

use std::ops::Range;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use miette::{Diagnostic, NamedSource, Report, SourceSpan};
use thiserror::Error;

use crate::diagnostics::Finding;
use crate::dialect::Dialect;
use crate::frontend::Language;
use crate::mnemonics::MnemonicSet;
use crate::profile::{self, Profile};
use crate::source::Files;
use crate::vm::s7::memory::LOCAL_BYTES;

/// awlsim's CPU sizes that awl runs on the speed7 profile: a project may ask for these or less
/// (a program fits a larger CPU), not more. The defaults of awlsim 0.77.1 (`S7CPUSpecs`) but
/// for the process images (up to the SPEED7's largest, set as a project asks) and the flags,
/// where the SPEED7 CPU has more; `nr_accus` and `nr_localbytes` are read on their own.
const SPEED7_SPECS: &[(&str, i64)] = &[
    ("nr_timers", 256),
    ("nr_counters", 256),
    ("nr_flags", 8192),
    ("nr_inputs", 2048),
    ("nr_outputs", 2048),
    ("parenthesis_stack_size", 7),
    ("call_stack_size", 256),
];

/// awlsim's L stack when a project does not size it (`nr_localbytes`).
const AWLSIM_LOCAL_BYTES: u32 = 1024;

/// The speed7 profile's process images, in bytes: a project asking for more gets them.
const PRESET_IMAGE_BYTES: i64 = 256;

/// What a project file asks for, as awl runs it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Project {
    /// `nr_accus`: 2 or 4.
    pub accus: u8,
    /// `nr_localbytes`: the L stack's size in bytes, up to the speed7 CPU's.
    pub local_bytes: u32,
    /// `nr_inputs`, `nr_outputs`: bytes of each process image, when the larger is more than
    /// the speed7 profile's preset.
    pub image_bytes: Option<u16>,
    /// `clock_memory_byte`: the flag byte, when not −1.
    pub clock_memory: Option<u16>,
    /// `ob_startinfo_enable`: whether the OBs' start information is written.
    pub start_info: bool,
    /// `mnemonics`: `None` (0) detects them; 1 English, 2 German.
    pub mnemonics: Option<MnemonicSet>,
    /// `ext_insns_enable`: awlsim's test operations are operations.
    pub extensions: bool,
    /// `cycle_time_limit_us`, in nanoseconds: the cycle monitoring time.
    pub cycle_limit_ns: u64,
    /// `run_time_limit_us`, in nanoseconds (`None`: −1, no limit).
    pub max_runtime_ns: Option<u64>,
    /// `cycle_time_target_us`, in nanoseconds (`None`: 0, none): the minimum cycle time, at
    /// most half the cycle monitoring time, as awlsim holds it.
    pub min_cycle_ns: Option<u64>,
    /// The STL sources, in order: a name and the text.
    pub programs: Vec<(PathBuf, Vec<u8>)>,
    /// The symbol tables, in order.
    pub symbols: Vec<(PathBuf, Vec<u8>)>,
}

impl Default for Project {
    /// awlsim's defaults, as a project that sets nothing runs.
    fn default() -> Self {
        Project {
            accus: 2,
            local_bytes: AWLSIM_LOCAL_BYTES,
            image_bytes: None,
            clock_memory: None,
            start_info: false,
            mnemonics: None,
            extensions: false,
            cycle_limit_ns: 1_000_000_000,
            max_runtime_ns: None,
            min_cycle_ns: None,
            programs: Vec::new(),
            symbols: Vec::new(),
        }
    }
}

impl Project {
    /// The language its sources are read in, where `given` (the command line, a scenario)
    /// leaves a choice: STEP 7 (awlsim's only dialect), the project's mnemonics, its test
    /// operations.
    pub fn language(&self, given: Language) -> Language {
        Language {
            mnemonics: given.mnemonics.or(self.mnemonics),
            dialect: given.dialect.or(Some(Dialect::Step7)),
            extensions: given.extensions || self.extensions,
        }
    }

    /// `cpu` set as the project's specifications ask: its accumulators, then its process
    /// images; a CPU that cannot be set so (a STEP 5 one) is left as it is.
    pub fn cpu(&self, cpu: &'static Profile) -> &'static Profile {
        let cpu = profile::with_accumulators(cpu, self.accus).unwrap_or(cpu);
        self.image_bytes
            .and_then(|bytes| profile::with_image_bytes(cpu, bytes))
            .unwrap_or(cpu)
    }
}

#[derive(Debug, Error, Diagnostic)]
pub enum ProjectError {
    #[error("cannot read `{path}`: {reason}")]
    #[diagnostic(
        code(awl::project::read),
        help("an awlsim project file is UTF-8 text: XML (format 1) or INI-like (format 0)")
    )]
    Read { path: String, reason: String },

    #[error(transparent)]
    #[diagnostic(code(awl::project::invalid), forward(0))]
    Invalid(Finding),

    #[error(transparent)]
    #[diagnostic(code(awl::project::not_run), forward(0))]
    NotRun(Finding),
}

/// Whether `bytes`, the file `path`, is an awlsim project: named `.awlpro`, or beginning as
/// awlsim's projects do (awlsim itself looks at the text, not the name).
pub fn is_project(path: &Path, bytes: &[u8]) -> bool {
    if has_project_name(path) {
        return true;
    }
    let head = &bytes[..bytes.len().min(4096)];
    let head = String::from_utf8_lossy(head);
    let head = head.trim_start_matches('\u{feff}');
    head.trim_start().starts_with(format0::MAGIC)
        || head.lines().any(|line| line.starts_with("<awlsim_project"))
}

/// Whether `path` is named as awlsim names its projects: `.awlpro`.
pub fn has_project_name(path: &Path) -> bool {
    path.extension()
        .is_some_and(|ext| ext.eq_ignore_ascii_case("awlpro"))
}

/// Reads the project file `path` from `store`, and the source files it names (relative to it).
pub fn read_project(store: &Files, path: &Path) -> Result<Project, Vec<Report>> {
    let bytes = store.read(path).map_err(|error| read_error(path, error))?;
    project_of(store, path, bytes)
}

/// The project `bytes` hold, the file `path`; the source files it names are read from `store`.
pub fn project_of(store: &Files, path: &Path, bytes: Vec<u8>) -> Result<Project, Vec<Report>> {
    let text = String::from_utf8(bytes).map_err(|error| read_error(path, error))?;
    let dir = path.parent().unwrap_or(Path::new(""));
    parse_project(&text, path, &mut |file| store.read(&dir.join(file))).map_err(|errors| {
        let source = NamedSource::new(path.display().to_string(), Arc::<str>::from(text));
        errors
            .into_iter()
            .map(|error| Report::new(error).with_source_code(source.clone()))
            .collect()
    })
}

fn read_error(path: &Path, error: impl ToString) -> Vec<Report> {
    vec![Report::new(ProjectError::Read {
        path: path.display().to_string(),
        reason: error.to_string(),
    })]
}

/// Reads project text in either format; `path` names its inline sources, `read` reads a
/// source file by the name the project gives. Every error found, each at its place.
pub fn parse_project(
    text: &str,
    path: &Path,
    read: &mut dyn FnMut(&str) -> std::io::Result<Vec<u8>>,
) -> Result<Project, Vec<ProjectError>> {
    let mut reader = Reader {
        project: Project::default(),
        errors: Vec::new(),
        path,
        read,
    };
    if text
        .trim_start_matches('\u{feff}')
        .trim_start()
        .starts_with(format0::MAGIC)
    {
        format0::read(text, &mut reader);
    } else {
        read_xml(text, &mut reader);
    }
    if reader.errors.is_empty() {
        Ok(reader.project)
    } else {
        Err(reader.errors)
    }
}

#[cfg(not(target_arch = "wasm32"))]
fn read_xml(text: &str, reader: &mut Reader<'_>) {
    format1::read(text, reader);
}

/// The playground carries no XML reader (its page size is counted); it has no project files.
#[cfg(target_arch = "wasm32")]
fn read_xml(_text: &str, reader: &mut Reader<'_>) {
    reader.errors.push(invalid(
        "awlsim's XML projects are read by the awl command, not here",
        (0, 0).into(),
        "this project",
        None,
    ));
}

/// A setting's value as the project writes it, and where.
#[derive(Debug, Clone)]
struct Setting<'a> {
    value: &'a str,
    at: Range<usize>,
}

/// Where a format finds a setting by awlsim's name for it (`nr_accus`).
type Settings<'s, 'a> = &'s dyn Fn(&str) -> Option<Setting<'a>>;

/// Which of a project's lists a source joins.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Kind {
    Program,
    SymbolTable,
}

/// The project read so far and every error found; both formats fill it.
struct Reader<'r> {
    project: Project,
    errors: Vec<ProjectError>,
    /// The project file, which names its inline sources.
    path: &'r Path,
    read: &'r mut dyn FnMut(&str) -> std::io::Result<Vec<u8>>,
}

impl Reader<'_> {
    /// An integer setting, or `default` when absent; `None` (an error kept) when bad.
    fn int(&mut self, settings: Settings<'_, '_>, name: &str, default: i64) -> Option<i64> {
        let Some(setting) = settings(name) else {
            return Some(default);
        };
        match setting.value.trim().parse::<i64>() {
            Ok(value) => Some(value),
            Err(_) => {
                self.errors.push(invalid(
                    format!("`{name}` is not a number"),
                    span(setting.at),
                    "this value",
                    Some(format!("write a whole number, e.g. `{name}` {default}")),
                ));
                None
            }
        }
    }

    /// A setting checked by `fits`; `None` (an error kept, `expected` its help) when it does
    /// not fit.
    fn checked<T>(
        &mut self,
        settings: Settings<'_, '_>,
        name: &str,
        default: i64,
        fits: impl Fn(i64) -> Option<T>,
        expected: &str,
    ) -> Option<T> {
        let value = self.int(settings, name, default)?;
        let result = fits(value);
        if result.is_none()
            && let Some(setting) = settings(name)
        {
            self.errors.push(invalid(
                format!("`{name}` {value} is out of range"),
                span(setting.at),
                "this value",
                Some(expected.into()),
            ));
        }
        result
    }

    /// The CPU's specifications: the accumulators and the sizes.
    fn specs(&mut self, settings: Settings<'_, '_>) {
        if let Some(accus) = self.checked(
            settings,
            "nr_accus",
            2,
            |n| matches!(n, 2 | 4).then_some(n as u8),
            "2 (as an S7-300) or 4 (as an S7-400)",
        ) {
            self.project.accus = accus;
        }
        let largest = LOCAL_BYTES as u32;
        if let Some(bytes) = self.checked(
            settings,
            "nr_localbytes",
            i64::from(AWLSIM_LOCAL_BYTES),
            |n| u32::try_from(n).ok().filter(|&n| n <= largest),
            &format!("bytes of the L stack, 0 to {largest} (the speed7 CPU's L stack)"),
        ) {
            self.project.local_bytes = bytes;
        }
        // A size not given is awlsim's default, which the speed7 CPU has.
        for &(name, limit) in SPEED7_SPECS {
            if settings(name).is_none() {
                continue;
            }
            let Some(value) = self.int(settings, name, limit) else {
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
            if value > limit
                && let Some(setting) = settings(name)
            {
                self.errors.push(not_run(
                    format!("`{name}` {value} is more than awl's CPU has"),
                    span(setting.at),
                    "not run as given",
                    Some(format!(
                        "awl runs awlsim's projects on the speed7 CPU, which has {name} {limit}"
                    )),
                ));
            }
        }
    }

    /// The CPU's configuration: clock memory, mnemonics, start information, test operations,
    /// time limits.
    fn config(&mut self, settings: Settings<'_, '_>) {
        if let Some(byte) = self.checked(
            settings,
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
            settings,
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
        if let Some(on) = self.checked(settings, "ob_startinfo_enable", 0, flag, "0 or 1") {
            self.project.start_info = on;
        }
        if let Some(on) = self.checked(settings, "ext_insns_enable", 0, flag, "0 or 1") {
            self.project.extensions = on;
        }
        if let Some(limit) = self.checked(
            settings,
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
            settings,
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
        if let Some(target) = self.checked(
            settings,
            "cycle_time_target_us",
            0,
            |n| match n {
                0 => Some(None),
                1..=0x7FFF_FFFF => Some(Some(n as u64 * 1000)),
                _ => None,
            },
            "microseconds, or 0 for none",
        ) {
            // awlsim waits at most half the cycle time limit: a project's own watchdog never
            // trips on the wait.
            let half_limit = self.project.cycle_limit_ns / 2;
            self.project.min_cycle_ns = target.map(|ns| ns.min(half_limit));
        }
    }

    /// A source file the project names (`file`, relative to the project), read; an error kept
    /// when it cannot be.
    fn source_file(&mut self, kind: Kind, file: Setting<'_>) {
        match (self.read)(file.value) {
            Ok(bytes) => {
                let dir = self.path.parent().unwrap_or(Path::new(""));
                self.push(kind, dir.join(file.value), bytes);
            }
            Err(error) => self.errors.push(invalid(
                format!("cannot read `{}`: {error}", file.value),
                span(file.at),
                "this file",
                Some("a source file's name is relative to the project file".into()),
            )),
        }
    }

    /// A source written inside the project, named after the project and `place`; an empty
    /// one (as awlsim writes an empty symbol table for a new project) is none.
    fn inline_source(&mut self, kind: Kind, place: &str, text: &str) {
        let text = text.trim_matches(['\r', '\n']);
        if text.trim().is_empty() {
            return;
        }
        let name = format!("{} [{place}]", self.path.display());
        self.push(kind, PathBuf::from(name), text.as_bytes().to_vec());
    }

    fn push(&mut self, kind: Kind, name: PathBuf, bytes: Vec<u8>) {
        match kind {
            Kind::Program => self.project.programs.push((name, bytes)),
            Kind::SymbolTable => self.project.symbols.push((name, bytes)),
        }
    }
}

/// Whether awl has a library block a project selects built in, under the number the program
/// calls it by: an IEC function (FC 1 to 40) not moved to another number.
fn built_in_library_block(library: &str, kind: &str, number: &str, effective: &str) -> bool {
    let number = number.trim().parse::<u16>().ok();
    library.trim().eq_ignore_ascii_case("IEC")
        && kind.trim().eq_ignore_ascii_case("FC")
        && number.is_some_and(|number| crate::step7::library::by_number(number).is_some())
        && number == effective.trim().parse::<u16>().ok()
}

/// The help for a library block awl does not run.
const LIBRARY_HELP: &str = "awl has the IEC functions (FC 1 to 40) built in under their own \
    numbers; other libraries, and a library block moved to another number, are not run";

fn span(range: Range<usize>) -> SourceSpan {
    (range.start, range.len()).into()
}

fn invalid(
    message: impl Into<String>,
    at: SourceSpan,
    label: &str,
    help: Option<String>,
) -> ProjectError {
    ProjectError::Invalid(Finding::new(message, at, label, help))
}

fn not_run(
    message: impl Into<String>,
    at: SourceSpan,
    label: &str,
    help: Option<String>,
) -> ProjectError {
    ProjectError::NotRun(Finding::new(message, at, label, help))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `text` read as `dir/p.awlpro`, beside the formats' tests' sources and symbol table; any
    /// other file is missing.
    pub(super) fn parse(text: &str) -> Result<Project, Vec<ProjectError>> {
        parse_project(text, Path::new("dir/p.awlpro"), &mut |file| match file {
            "main.awl" | "a.awl" => {
                Ok(b"ORGANIZATION_BLOCK OB 1\nBEGIN\nEND_ORGANIZATION_BLOCK\n".to_vec())
            }
            "plant.sym" => Ok(b"\"Start\" I 0.0 BOOL\n".to_vec()),
            _ => Err(std::io::Error::new(
                std::io::ErrorKind::NotFound,
                "no such file",
            )),
        })
    }

    /// The errors reading `text`, as printed.
    pub(super) fn messages(text: &str) -> Vec<String> {
        parse(text)
            .expect_err("errors")
            .iter()
            .map(ToString::to_string)
            .collect()
    }

    #[test]
    fn projects_are_known_by_name_or_by_their_beginning() {
        let xml = b"<?xml version=\"1.0\"?>\n<awlsim_project format_version=\"1\"/>";
        assert!(is_project(Path::new("p.AWLPRO"), b"anything"));
        assert!(is_project(Path::new("p.awl"), xml));
        assert!(is_project(
            Path::new("p"),
            b"\xEF\xBB\xBF\n[AWLSIM_PROJECT]\n"
        ));
        assert!(!is_project(
            Path::new("p.awl"),
            b"ORGANIZATION_BLOCK OB 1\n"
        ));
    }

    #[test]
    fn a_project_sets_the_language_and_the_cpu_left_open() {
        let project = Project {
            accus: 4,
            image_bytes: Some(1024),
            mnemonics: Some(MnemonicSet::German),
            extensions: true,
            ..Project::default()
        };
        let language = project.language(Language::default());
        assert_eq!(language.dialect, Some(Dialect::Step7));
        assert_eq!(language.mnemonics, Some(MnemonicSet::German));
        assert!(language.extensions);
        let given = project.language(Language::with_mnemonics(MnemonicSet::English));
        assert_eq!(given.mnemonics, Some(MnemonicSet::English));
        let speed7 = profile::find("speed7").unwrap();
        let cpu = project.cpu(speed7);
        assert_eq!((cpu.accumulators, cpu.sizes.image_bytes), (4, 1024));
        let step5 = profile::default_for(Dialect::Step5);
        assert_eq!(project.cpu(step5).name, step5.name);
    }
}
