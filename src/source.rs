//! Source files: reading and decoding, line lookup, and the snippets diagnostics show.
//!
//! Decoding: a UTF-8 byte-order mark is skipped; UTF-16 with a byte-order mark is decoded;
//! other text that is not UTF-8 is read as ISO-8859-1 (old PG exports). Lines may end in LF,
//! CR LF or a lone CR (old Macs); a lone CR is read as LF. Control characters other than tab,
//! line ends, vertical tab and form feed are shown as their Unicode control pictures (`␇`), so
//! a diagnostic never sends them to the terminal.

use std::path::Path;
use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};

use miette::{MietteError, MietteSpanContents, SourceCode, SourceSpan, SpanContents};

/// `span()` of an error type whose variants carry their span in a field `at`, the rule every
/// error of awl follows: `error_span!(Error { special arms } Variant, …)`, the special arms
/// (`pattern => span`) for the variants that find their span another way.
macro_rules! error_span {
    ($error:ident { $($special:pat => $span:expr),* $(,)? } $($variant:ident),+ $(,)?) => {
        impl $error {
            pub fn span(&self) -> $crate::source::Span {
                match self {
                    $($special => $span,)*
                    $($error::$variant { at, .. })|+ => *at,
                }
            }
        }
    };
}
pub(crate) use error_span;

/// Index of a file in a [`SourceSet`].
pub type FileId = u16;

/// A byte range in one source file.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub struct Span {
    pub file: FileId,
    pub start: u32,
    pub end: u32,
}

impl Span {
    pub fn new(file: FileId, range: std::ops::Range<usize>) -> Self {
        Span {
            file,
            start: range.start as u32,
            end: range.end as u32,
        }
    }

    pub fn len(self) -> usize {
        (self.end - self.start) as usize
    }

    pub fn is_empty(self) -> bool {
        self.end == self.start
    }
}

impl From<Span> for miette::SourceSpan {
    fn from(span: Span) -> Self {
        (span.start as usize, span.len()).into()
    }
}

/// One loaded source file.
#[derive(Debug, Clone)]
pub struct SourceFile {
    pub name: String,
    pub text: Arc<str>,
    line_starts: Arc<[u32]>,
}

impl SourceFile {
    pub fn new(name: impl Into<String>, text: impl Into<Arc<str>>) -> Self {
        let text: Arc<str> = text.into();
        let line_starts = std::iter::once(0)
            .chain(
                (0u32..)
                    .zip(text.bytes())
                    .filter(|(_, byte)| *byte == b'\n')
                    .map(|(at, _)| at + 1),
            )
            .collect();
        SourceFile {
            name: name.into(),
            text,
            line_starts,
        }
    }

    /// Decodes a file's bytes (see the module documentation).
    pub fn from_bytes(name: impl Into<String>, bytes: Vec<u8>) -> Self {
        SourceFile::new(name, clean(&decode(bytes)))
    }

    pub fn read(path: &Path) -> std::io::Result<Self> {
        Files::Disk.source(path)
    }

    /// 1-based line number of a byte offset.
    pub fn line_of(&self, offset: u32) -> u32 {
        self.line_starts.partition_point(|&start| start <= offset) as u32
    }

    /// The text of 1-based line `line`, without its line end; empty past the end.
    pub fn line(&self, line: u32) -> &str {
        let Some(&start) = self.line_starts.get(line.saturating_sub(1) as usize) else {
            return "";
        };
        let rest = &self.text[start as usize..];
        rest.split('\n').next().unwrap_or("").trim_end_matches('\r')
    }

    pub fn slice(&self, span: Span) -> &str {
        &self.text[span.start as usize..span.end as usize]
    }

    /// The file as miette reads it for a diagnostic.
    pub fn named_source(&self) -> IndexedSource {
        IndexedSource {
            name: self.name.clone(),
            text: self.text.clone(),
            line_starts: self.line_starts.clone(),
        }
    }
}

/// How many bytes from a file's start [`binary_reason`] looks at.
const SNIFFED_BYTES: usize = 4096;

/// Why `bytes` are a binary file rather than text (a picture, an executable, a STEP 5 PG's
/// `.S5D`), or `None` for text: text holds no NUL byte (but UTF-16 with its byte-order mark,
/// which is text), and few control characters or bytes that are not UTF-8 (ISO-8859-1 text has
/// some: its umlauts). Only the file's first few KB are looked at.
pub fn binary_reason(bytes: &[u8]) -> Option<String> {
    if bytes.starts_with(&[0xFF, 0xFE]) || bytes.starts_with(&[0xFE, 0xFF]) {
        return None;
    }
    let head = &bytes[..bytes.len().min(SNIFFED_BYTES)];
    if head.contains(&0) {
        return Some("it holds NUL bytes, as binary files do".into());
    }
    let control = |byte: &&u8| {
        (**byte < 0x20 && !matches!(**byte, b'\t' | b'\n' | b'\r' | 0x0B | 0x0C | 0x1A))
            || **byte == 0x7F
    };
    let odd: usize = head
        .utf8_chunks()
        .map(|chunk| {
            chunk.valid().as_bytes().iter().filter(control).count() + chunk.invalid().len()
        })
        .sum();
    // Text has a few such bytes at most; binary data has them everywhere.
    (odd * 10 > head.len() * 3).then(|| {
        format!(
            "{odd} of its first {} bytes are control characters or not UTF-8",
            head.len()
        )
    })
}

fn decode(bytes: Vec<u8>) -> String {
    match bytes.as_slice() {
        [0xEF, 0xBB, 0xBF, rest @ ..] => String::from_utf8_lossy(rest).into_owned(),
        [0xFF, 0xFE, rest @ ..] => utf16(rest, u16::from_le_bytes),
        [0xFE, 0xFF, rest @ ..] => utf16(rest, u16::from_be_bytes),
        _ => match String::from_utf8(bytes) {
            Ok(text) => text,
            Err(err) => err.into_bytes().iter().map(|&b| char::from(b)).collect(),
        },
    }
}

fn utf16(bytes: &[u8], unit: fn([u8; 2]) -> u16) -> String {
    let units = bytes.chunks_exact(2).map(|pair| unit([pair[0], pair[1]]));
    char::decode_utf16(units)
        .map(|c| c.unwrap_or(char::REPLACEMENT_CHARACTER))
        .collect()
}

/// Lone CRs become LFs; control characters become their control pictures.
fn clean(text: &str) -> String {
    // Most sources have nothing to replace: copy them whole.
    let plain =
        |byte: u8| byte >= 0x20 && byte != 0x7F || matches!(byte, b'\t' | b'\n' | 0x0B | 0x0C);
    if text.bytes().all(plain) {
        return text.to_string();
    }
    let mut out = String::with_capacity(text.len());
    let mut chars = text.chars().peekable();
    while let Some(c) = chars.next() {
        match c {
            '\r' if chars.peek() == Some(&'\n') => out.push(c),
            '\r' => out.push('\n'),
            '\t' | '\n' | '\x0B' | '\x0C' => out.push(c),
            '\x00'..='\x1F' => out.push(char::from_u32(0x2400 + c as u32).unwrap_or('?')),
            '\x7F' => out.push('\u{2421}'),
            _ => out.push(c),
        }
    }
    out
}

/// Bytes of source text diagnostics have read, over the whole process: what rendering costs.
static SNIPPET_BYTES: AtomicU64 = AtomicU64::new(0);

/// How many bytes of source diagnostics have read so far (rendering work, for tests).
pub fn snippet_bytes_read() -> u64 {
    SNIPPET_BYTES.load(Ordering::Relaxed)
}

/// A named source whose snippets are found through its line index: a diagnostic reads only the
/// lines around its span, not the file from its start, so rendering many diagnostics of one
/// file takes linear time.
#[derive(Debug, Clone)]
pub struct IndexedSource {
    name: String,
    text: Arc<str>,
    line_starts: Arc<[u32]>,
}

impl IndexedSource {
    /// The 0-based line holding byte `offset`.
    fn line(&self, offset: usize) -> usize {
        self.line_starts
            .partition_point(|&start| start as usize <= offset)
            .saturating_sub(1)
    }

    fn line_start(&self, line: usize) -> usize {
        self.line_starts
            .get(line)
            .map_or(self.text.len(), |start| *start as usize)
    }
}

impl SourceCode for IndexedSource {
    fn read_span<'a>(
        &'a self,
        span: &SourceSpan,
        context_lines_before: usize,
        context_lines_after: usize,
    ) -> Result<Box<dyn SpanContents<'a> + 'a>, MietteError> {
        let end = span.offset() + span.len();
        if end > self.text.len() {
            return Err(MietteError::OutOfBounds);
        }
        // The lines miette would show, and the one before them (miette's reading of an empty
        // span at a line start looks at the character before), cut out of the text; miette
        // reads only those.
        let first = self
            .line(span.offset())
            .saturating_sub(context_lines_before + 1);
        let last = self.line(end.saturating_sub(1).max(span.offset())) + context_lines_after + 1;
        let (from, to) = (self.line_start(first), self.line_start(last + 1));
        let window = &self.text[from..to];
        SNIPPET_BYTES.fetch_add(window.len() as u64, Ordering::Relaxed);
        let inner = SourceSpan::new((span.offset() - from).into(), span.len());
        let found = window.read_span(&inner, context_lines_before, context_lines_after)?;
        let data = found.data();
        let start = data.as_ptr() as usize - self.text.as_ptr() as usize;
        Ok(Box::new(MietteSpanContents::new_named(
            self.name.clone(),
            data,
            SourceSpan::new(start.into(), data.len()),
            found.line() + first,
            found.column(),
            found.line_count() + first,
        )))
    }
}

/// All files of one program.
#[derive(Debug, Clone, Default)]
pub struct SourceSet {
    pub files: Vec<SourceFile>,
}

impl SourceSet {
    /// Adds a file; `None` when the set is full (a span names its file in 16 bits).
    pub fn add(&mut self, file: SourceFile) -> Option<FileId> {
        let id = FileId::try_from(self.files.len()).ok()?;
        self.files.push(file);
        Some(id)
    }

    pub fn get(&self, id: FileId) -> &SourceFile {
        &self.files[id as usize]
    }

    pub fn line_of(&self, span: Span) -> u32 {
        self.get(span.file).line_of(span.start)
    }
}

/// Where files are read from: the file system, or texts held in memory by their paths (the
/// browser playground, which has no file system; tests). Paths are compared after `.` and `..`
/// are taken out.
#[derive(Debug, Clone, Default)]
pub enum Files {
    #[default]
    Disk,
    Memory(std::sync::Arc<std::collections::BTreeMap<std::path::PathBuf, Vec<u8>>>),
}

impl Files {
    pub fn read(&self, path: &Path) -> std::io::Result<Vec<u8>> {
        match self {
            Files::Disk => std::fs::read(path),
            Files::Memory(files) => files
                .get(&normalize(path))
                .cloned()
                .ok_or_else(|| std::io::Error::new(std::io::ErrorKind::NotFound, "no such file")),
        }
    }

    pub fn source(&self, path: &Path) -> std::io::Result<SourceFile> {
        Ok(SourceFile::from_bytes(
            path.display().to_string(),
            self.read(path)?,
        ))
    }
}

/// `a/./b/../c` → `a/c`, without looking at the file system.
pub fn normalize(path: &Path) -> std::path::PathBuf {
    use std::path::Component;
    let mut out = std::path::PathBuf::new();
    for component in path.components() {
        match component {
            Component::CurDir => {}
            Component::ParentDir if out.file_name().is_some() => {
                out.pop();
            }
            other => out.push(other),
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cleaning_keeps_plain_text_and_makes_control_characters_visible() {
        let plain = "OB 1\n\tA  I 0.0 ; Ä\x0B\x0C\n";
        assert_eq!(clean(plain), plain);
        assert_eq!(clean("A\r\nB\rC"), "A\r\nB\nC");
        assert_eq!(clean("A\x01B\x7F"), "A\u{2401}B\u{2421}");
    }

    #[test]
    fn binary_files_are_told_from_text() {
        let png = b"\x89PNG\r\n\x1a\n\0\0\0\rIHDR\0\0\x01\0";
        assert!(binary_reason(png).unwrap().contains("NUL"));
        let noise: Vec<u8> = (0..2000u32)
            .map(|n| (n * 7919 % 251) as u8 | 0x80)
            .collect();
        assert!(binary_reason(&noise).unwrap().contains("not UTF-8"));
        let controls: Vec<u8> = b"OB 1\n"
            .iter()
            .chain(&[1u8, 2, 3, 4, 5, 6, 7, 8])
            .copied()
            .collect();
        assert!(binary_reason(&controls).is_some());
        let text: [&[u8]; 7] = [
            b"",
            b"OB 1\n  A I 0.0\n  BE\n",
            b"\xEF\xBB\xBFPB 1\r\nBE\r\n",
            b"\xFF\xFEP\0B\0",
            b"PB 1\rBE\r",
            b"OB 1\n  A I 0.0\x07\x1b[31m\n  BE\n\x1a",
            b"; Z\xe4hler f\xfcr \xd6l\nPB 1\n  BE\n",
        ];
        for bytes in text {
            assert_eq!(binary_reason(bytes), None, "{bytes:?}");
        }
    }

    #[test]
    fn files_in_memory_are_found_by_their_normal_path() {
        let mut map = std::collections::BTreeMap::new();
        map.insert(std::path::PathBuf::from("programs/a.awl"), b"BE".to_vec());
        let files = Files::Memory(std::sync::Arc::new(map));
        assert!(files.read(Path::new("programs/./x/../a.awl")).is_ok());
        assert!(files.read(Path::new("programs/b.awl")).is_err());
    }

    #[test]
    fn latin1_fallback_keeps_umlauts() {
        let file = SourceFile::from_bytes("x.awl", b"; Z\xe4hler\nBE\n".to_vec());
        assert_eq!(&*file.text, "; Zähler\nBE\n");
    }

    #[test]
    fn line_numbers_are_one_based() {
        let file = SourceFile::new("x", "a\nb\r\nc");
        assert_eq!(file.line_of(0), 1);
        assert_eq!(file.line_of(2), 2);
        assert_eq!(file.line_of(5), 3);
    }

    #[test]
    fn byte_order_marks_and_line_ends() {
        let bom = SourceFile::from_bytes("a", b"\xEF\xBB\xBFPB 1\n".to_vec());
        assert_eq!(&*bom.text, "PB 1\n");
        let utf16: Vec<u8> = [0xFF, 0xFE]
            .into_iter()
            .chain("PB 1\r\nBE".encode_utf16().flat_map(u16::to_le_bytes))
            .collect();
        assert_eq!(&*SourceFile::from_bytes("b", utf16).text, "PB 1\r\nBE");
        let cr = SourceFile::from_bytes("c", b"PB 1\rBE\r".to_vec());
        assert_eq!(&*cr.text, "PB 1\nBE\n");
        assert_eq!(cr.line_of(5), 2);
        let bell = SourceFile::from_bytes("d", b"A\x07B\x7F".to_vec());
        assert_eq!(&*bell.text, "A\u{2407}B\u{2421}");
    }

    #[test]
    fn snippets_match_a_plain_read() {
        let text = "PB 1\n  A I 0.0\r\n  = Q 4.0\n\n  BE\n";
        let file = SourceFile::new("x", text);
        let indexed = file.named_source();
        for start in 0..text.len() {
            for len in 0..12.min(text.len() - start) {
                let span = SourceSpan::new(start.into(), len);
                for context in 0..3 {
                    let plain = text.read_span(&span, context, context).unwrap();
                    let ours = indexed.read_span(&span, context, context).unwrap();
                    assert_eq!(ours.data(), plain.data(), "{start}+{len} ±{context}");
                    assert_eq!(ours.line(), plain.line(), "{start}+{len} ±{context}");
                    assert_eq!(ours.column(), plain.column());
                    assert_eq!(ours.span(), plain.span());
                }
            }
        }
    }
}
