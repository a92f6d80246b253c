//! The files' envelope and their crash-safe writing. A file is
//! `{"format": …, "version": 1, "checksum": …, "body": {…}}`; the checksum (SHA-1 of the body's
//! canonical JSON) tells a damaged file from a good one. A write goes to a new file beside the
//! old one, is made durable, then renamed over it, so a crash or a power cut at any instant
//! leaves the old file or the new one, never a mix.

use std::fs::File;
use std::io::Write;
use std::path::{Path, PathBuf};

use serde::Serialize;
use serde::de::DeserializeOwned;
use serde_json::Value;
use sha1::{Digest, Sha1};

use super::RetainError;

/// The version of both formats this awl writes and reads.
pub const VERSION: u64 = 1;

/// A file's kind: its `format` name and what the error messages call it.
#[derive(Debug, Clone, Copy)]
pub struct Kind {
    pub format: &'static str,
    pub name: &'static str,
}

fn checksum(body: &Value) -> String {
    // serde_json's maps are sorted, so the same body gives the same text.
    let text = body.to_string();
    data_encoding::HEXLOWER.encode(&Sha1::digest(text.as_bytes()))
}

/// A file as written: what it is first, then its contents.
#[derive(Serialize)]
struct Envelope {
    format: &'static str,
    version: u64,
    checksum: String,
    body: Value,
}

/// The file's text for `body`.
pub fn encode<T: Serialize>(kind: Kind, body: &T) -> String {
    let body = serde_json::to_value(body).expect("plain data serializes");
    let envelope = Envelope {
        format: kind.format,
        version: VERSION,
        checksum: checksum(&body),
        body,
    };
    serde_json::to_string_pretty(&envelope).expect("plain data serializes") + "\n"
}

/// The body of the file at `path`, which must be of `kind`.
pub fn read<T: DeserializeOwned>(kind: Kind, path: &Path) -> Result<T, RetainError> {
    let text = std::fs::read_to_string(path).map_err(|error| RetainError::Unreadable {
        path: path.to_path_buf(),
        reason: error.to_string(),
    })?;
    decode(kind, path, &text)
}

/// The body of `text`, the contents of `path`.
pub fn decode<T: DeserializeOwned>(kind: Kind, path: &Path, text: &str) -> Result<T, RetainError> {
    let damaged = |reason: String| RetainError::Damaged {
        path: path.to_path_buf(),
        reason,
    };
    let foreign = |reason: String| RetainError::Foreign {
        path: path.to_path_buf(),
        expected: kind.name,
        reason,
    };
    let mut envelope: Value = serde_json::from_str(text).map_err(|error| {
        if error.is_eof() || text.trim_start().starts_with('{') {
            damaged(format!("not complete JSON ({error})"))
        } else {
            foreign("not JSON".into())
        }
    })?;
    match envelope.get("format").and_then(Value::as_str) {
        Some(format) if format == kind.format => {}
        Some(format) => return Err(foreign(format!("its format is `{format}`"))),
        None => return Err(foreign("it has no `format`".into())),
    }
    match envelope.get("version").and_then(Value::as_u64) {
        Some(VERSION) => {}
        Some(version) => {
            return Err(foreign(format!(
                "it is version {version}; this awl reads version {VERSION}"
            )));
        }
        None => return Err(damaged("it has no `version`".into())),
    }
    let body = envelope.get_mut("body").map(Value::take);
    let Some(body) = body else {
        return Err(damaged("it has no `body`".into()));
    };
    let written = envelope.get("checksum").and_then(Value::as_str);
    if written != Some(checksum(&body).as_str()) {
        return Err(damaged("its checksum does not match its contents".into()));
    }
    serde_json::from_value(body)
        .map_err(|error| damaged(format!("its body is not as awl writes it ({error})")))
}

/// Writes `text` to `path` so that a crash at any moment leaves the old file or the new one.
pub fn write_durably(path: &Path, text: &str) -> Result<(), RetainError> {
    let failed = |error: std::io::Error| RetainError::Write {
        path: path.to_path_buf(),
        reason: error.to_string(),
    };
    let fresh = beside(path);
    let mut file = File::create(&fresh).map_err(failed)?;
    file.write_all(text.as_bytes()).map_err(failed)?;
    file.sync_all().map_err(failed)?;
    drop(file);
    std::fs::rename(&fresh, path).map_err(failed)?;
    // The rename itself is durable once the folder is.
    let folder = path
        .parent()
        .filter(|folder| !folder.as_os_str().is_empty());
    if let Ok(folder) = File::open(folder.unwrap_or(Path::new("."))) {
        let _not_every_system_syncs_folders = folder.sync_all();
    }
    Ok(())
}

/// The new file's name: beside the old one, so the rename stays on one file system.
fn beside(path: &Path) -> PathBuf {
    let mut name = path.file_name().unwrap_or_default().to_os_string();
    name.push(".new");
    path.with_file_name(name)
}

#[cfg(test)]
mod tests {
    use super::*;

    const KIND: Kind = Kind {
        format: "awl-test",
        name: "a test file",
    };

    #[derive(Debug, PartialEq, serde::Serialize, serde::Deserialize)]
    struct Body {
        count: u32,
        bytes: String,
    }

    fn good() -> String {
        encode(
            KIND,
            &Body {
                count: 42,
                bytes: "00ff".into(),
            },
        )
    }

    #[test]
    fn a_file_reads_back_as_written() {
        let body: Body = decode(KIND, Path::new("f"), &good()).unwrap();
        assert_eq!(body.count, 42);
    }

    #[test]
    fn a_crash_leaves_the_old_file_or_the_new_one() {
        let folder = std::env::temp_dir().join(format!("awl-retain-{}", std::process::id()));
        std::fs::create_dir_all(&folder).unwrap();
        let path = folder.join("memory.json");
        write_durably(&path, "old").unwrap();
        // A crash after the new file was written and before the rename.
        std::fs::write(beside(&path), "half").unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "old");
        write_durably(&path, "new").unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "new");
        assert!(!beside(&path).exists());
        std::fs::remove_dir_all(folder).unwrap();
    }

    proptest::proptest! {
        /// Any text is read or refused with an error, never a panic.
        #[test]
        fn any_text_is_read_or_refused(text in ".{0,200}") {
            let _ = decode::<Body>(KIND, Path::new("f"), &text);
        }

        /// A file with one character changed is refused, or reads as the original when the
        /// change is only in its layout.
        #[test]
        fn a_changed_character_is_found(at in 0usize..400, with in proptest::char::range(' ', '~')) {
            let text = good();
            let at = at % text.len();
            let mut changed: Vec<char> = text.chars().collect();
            changed[at] = with;
            let changed: String = changed.into_iter().collect();
            if let Ok(body) = decode::<Body>(KIND, Path::new("f"), &changed) {
                proptest::prop_assert_eq!(body, decode::<Body>(KIND, Path::new("f"), &text).unwrap());
            }
        }
    }
}
