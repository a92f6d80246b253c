//! A document's program as `awl` would read it: the scenario beside it that names it gives
//! the other program files, the assignment lists and the CPU; else the settings the client
//! sent (`initializationOptions`: `cpu`, `symbols`); else the document alone, on the default
//! CPU of its dialect.

use std::path::{Path, PathBuf};
use std::str::FromStr;

use lsp_types::Uri;
use miette::{Diagnostic, Report};
use serde::Deserialize;
use thiserror::Error;

use super::documents::Documents;
use crate::frontend::{self, Frontend, Language};
use crate::profile::{self, Profile};
use crate::program_files::SourceError;
use crate::scenario::Scenario;
use crate::source::{SourceFile, SourceSet, normalize};

/// What the client may set (`initializationOptions`, or `workspace/didChangeConfiguration`
/// with an `awl` section).
#[derive(Debug, Clone, Default, Deserialize)]
#[serde(default)]
pub struct Settings {
    /// The CPU profile where no scenario names one (`awl cpus`).
    pub cpu: Option<String>,
    /// Assignment lists or STEP 7 symbol tables where no scenario names them; relative
    /// paths are the workspace folder's.
    pub symbols: Vec<PathBuf>,
}

/// A setting the server cannot use; told once as a message to the user.
#[derive(Debug, Error, Diagnostic)]
pub enum SettingsError {
    #[error("the setting `cpu` names `{name}`, which is no CPU profile")]
    #[diagnostic(
        code(awl::lsp::unknown_cpu),
        help("the profiles are: {}; the default CPU is used instead", profile::names().join(", "))
    )]
    UnknownCpu { name: String },

    #[error("the settings are not understood: {reason}")]
    #[diagnostic(
        code(awl::lsp::bad_settings),
        help(
            "the settings are an object such as {{\"cpu\": \"s5-115u\", \"symbols\": [\"plant.seq\"]}}"
        )
    )]
    Malformed { reason: String },
}

impl Settings {
    /// The settings of a JSON value, or why they are not understood (`null` is none set).
    pub fn from_json(value: Option<serde_json::Value>) -> Result<Settings, SettingsError> {
        let value = value.unwrap_or(serde_json::Value::Null);
        if value.is_null() {
            return Ok(Settings::default());
        }
        let settings: Settings =
            serde_json::from_value(value).map_err(|error| SettingsError::Malformed {
                reason: error.to_string(),
            })?;
        if let Some(name) = &settings.cpu
            && profile::find(name).is_none()
        {
            return Err(SettingsError::UnknownCpu { name: name.clone() });
        }
        Ok(settings)
    }
}

/// The workspace: its folder, the settings and the open documents.
#[derive(Debug, Default)]
pub struct Workspace {
    pub root: Option<PathBuf>,
    pub settings: Settings,
    pub documents: Documents,
}

/// One document's program, through the front end.
#[derive(Debug)]
pub struct Analysis {
    pub built: Frontend,
    /// The path of each file of `built.sources`; the document is file 0.
    pub paths: Vec<PathBuf>,
    pub profile: &'static Profile,
    /// Whether a scenario or a setting chose the CPU.
    cpu_chosen: bool,
    /// The program files and assignment lists the scenario or the settings name that could
    /// not be read.
    pub unread: Vec<Report>,
    /// What the front end read, to ask which CPUs the program compiles on.
    programs: SourceSet,
    symbol_files: Vec<SourceFile>,
    language: Language,
}

impl Analysis {
    /// The text of file `file`.
    pub fn text(&self, file: u16) -> &str {
        &self.built.sources.get(file).text
    }

    /// Without a chosen CPU and with errors: the profiles the program compiles on, as
    /// `awl check` says them.
    pub fn runs_on(&self) -> Option<Vec<&'static str>> {
        (!self.cpu_chosen && self.built.has_errors()).then(|| {
            frontend::profiles_without_errors(
                &self.built,
                &self.programs,
                &self.symbol_files,
                self.language,
            )
        })
    }

    pub fn uri(&self, file: u16) -> Option<Uri> {
        self.paths
            .get(usize::from(file))
            .and_then(|path| uri_of(path))
    }
}

/// The path a `file:` URI names; `None` for another scheme.
pub fn path_of(uri: &Uri) -> Option<PathBuf> {
    let rest = uri.as_str().strip_prefix("file://")?;
    let bytes = rest.as_bytes();
    let mut decoded = Vec::with_capacity(bytes.len());
    let mut at = 0;
    while at < bytes.len() {
        let escaped = (bytes[at] == b'%')
            .then(|| rest.get(at + 1..at + 3))
            .flatten()
            .and_then(|hex| u8::from_str_radix(hex, 16).ok());
        match escaped {
            Some(byte) => {
                decoded.push(byte);
                at += 3;
            }
            None => {
                decoded.push(bytes[at]);
                at += 1;
            }
        }
    }
    String::from_utf8(decoded).ok().map(PathBuf::from)
}

/// The `file:` URI of an absolute path.
pub fn uri_of(path: &Path) -> Option<Uri> {
    let mut text = String::from("file://");
    for byte in path.to_str()?.bytes() {
        if byte.is_ascii_alphanumeric() || b"/-._~:".contains(&byte) {
            text.push(char::from(byte));
        } else {
            text.push_str(&format!("%{byte:02X}"));
        }
    }
    Uri::from_str(&text).ok()
}

impl Workspace {
    /// The text of `path`: the open document's, else the file's on disk.
    fn text_of(&self, path: &Path) -> std::io::Result<String> {
        if let Some(text) = uri_of(path).and_then(|uri| self.documents.get(&uri)) {
            return Ok(text.to_string());
        }
        let bytes = std::fs::read(path)?;
        Ok(String::from_utf8_lossy(&bytes).into_owned())
    }

    /// The file at `path` for the front end, or why it cannot be read (as `awl check` says it).
    fn file_of(&self, path: &Path, unread: &mut Vec<Report>) -> Option<SourceFile> {
        match self.text_of(path) {
            Ok(text) => Some(SourceFile::new(path.display().to_string(), text)),
            Err(error) => {
                unread.push(Report::new(SourceError::Read {
                    path: path.to_path_buf(),
                    reason: error.to_string(),
                }));
                None
            }
        }
    }

    /// The scenario in the document's folder (or the workspace folder) that names it as a
    /// program, in name order.
    fn scenario_of(&self, path: &Path) -> Option<Scenario> {
        let wanted = normalize(path);
        let mut folders = vec![path.parent()?.to_path_buf()];
        folders.extend(self.root.clone());
        for folder in folders {
            let Ok(entries) = std::fs::read_dir(&folder) else {
                continue;
            };
            let mut tomls: Vec<PathBuf> = entries
                .filter_map(|entry| entry.ok().map(|entry| entry.path()))
                .filter(|file| file.extension().is_some_and(|ext| ext == "toml"))
                .collect();
            tomls.sort();
            for toml in tomls {
                let Ok(text) = self.text_of(&toml) else {
                    continue;
                };
                let (scenario, _) = Scenario::parse(&toml, &text);
                if scenario
                    .programs
                    .iter()
                    .any(|program| normalize(program) == wanted)
                {
                    return Some(scenario);
                }
            }
        }
        None
    }

    fn absolute(&self, path: &Path) -> PathBuf {
        match &self.root {
            Some(root) if path.is_relative() => root.join(path),
            _ => path.to_path_buf(),
        }
    }

    /// The front end over the document `uri` with the text `text` and its program's other
    /// files.
    pub fn analyse(&self, uri: &Uri, text: &str) -> Analysis {
        let path = path_of(uri).unwrap_or_else(|| PathBuf::from(uri.as_str()));
        let scenario = path
            .is_absolute()
            .then(|| self.scenario_of(&path))
            .flatten();
        let mut paths = vec![path.clone()];
        let mut sources = SourceSet::default();
        sources.add(SourceFile::new(path.display().to_string(), text));
        let (others, symbols, cpu, language) = match &scenario {
            Some(scenario) => (
                scenario.programs.clone(),
                scenario.symbols.clone(),
                scenario.cpu,
                Language {
                    dialect: scenario.dialect,
                    extensions: scenario.extended,
                    ..Language::default()
                },
            ),
            None => (
                Vec::new(),
                self.settings
                    .symbols
                    .iter()
                    .map(|file| self.absolute(file))
                    .collect(),
                self.settings.cpu.as_deref().and_then(profile::find),
                Language::default(),
            ),
        };
        let mut unread = Vec::new();
        for other in others
            .iter()
            .filter(|other| normalize(other) != normalize(&path))
        {
            if let Some(file) = self.file_of(other, &mut unread) {
                sources.add(file);
                paths.push(other.clone());
            }
        }
        let mut symbol_files = Vec::new();
        for list in &symbols {
            if let Some(file) = self.file_of(list, &mut unread) {
                symbol_files.push(file);
                paths.push(list.clone());
            }
        }
        let built = frontend::build_for_dialect(
            sources.clone(),
            symbol_files.clone(),
            language,
            |dialect| cpu.unwrap_or_else(|| crate::profile::default_for(dialect)),
        );
        let profile = built.compiled.program.profile;
        Analysis {
            built,
            paths,
            profile,
            cpu_chosen: cpu.is_some(),
            unread,
            programs: sources,
            symbol_files,
            language,
        }
    }
}
