//! awlsim's project format version 0 (awlsim before 0.50; awlsim 0.77.1 still reads it): text
//! in the INI form Python's `configparser` reads. `[AWLSIM_PROJECT]` holds `file_version=0`;
//! `[CPU]` the STL sources and the CPU's settings (`nr_accus`, `mnemonics`,
//! `clock_memory_byte`, `ob_startinfo_enable`, `ext_insns_enable`); `[SYMBOLS]` the symbol
//! tables; `[FUP]`, `[KOP]`, `[LIBS]` and `[HWMODS]` what awl cannot run; `[CORE_LINK]` and
//! `[GUI]` nothing that touches the run. A source is a file (`awl_file_0=plant.awl`, relative
//! to the project) or text inside the project in base64 (`awl_0=…`, named by `awl_name_0`, its
//! name in base64 too); awlsim reads the files of a list, then the texts, each numbered from 0
//! to the first number missing.

use std::ops::Range;

use super::{Kind, LIBRARY_HELP, Reader, Setting, built_in_library_block, invalid, not_run, span};

/// How a format 0 project begins.
pub(super) const MAGIC: &str = "[AWLSIM_PROJECT]";

/// The settings of `[CPU]` awlsim reads in format 0; the others it takes as its defaults.
const CPU_SETTINGS: &[&str] = &[
    "mnemonics",
    "nr_accus",
    "clock_memory_byte",
    "ob_startinfo_enable",
    "ext_insns_enable",
];

/// The settings `configparser` reads as booleans.
const BOOLEAN_SETTINGS: &[&str] = &["ob_startinfo_enable", "ext_insns_enable"];

/// One `[NAME]` section and its entries, in the order written.
#[derive(Debug)]
struct Section<'a> {
    name: &'a str,
    at: Range<usize>,
    entries: Vec<Entry<'a>>,
}

/// `key = value` (or `key: value`); the key lowercased as `configparser` reads it.
#[derive(Debug)]
struct Entry<'a> {
    key: String,
    key_at: Range<usize>,
    /// The value's lines, each trimmed: more than one when indented lines continue it.
    lines: Vec<&'a str>,
    at: Range<usize>,
}

impl<'a> Entry<'a> {
    fn setting(&self) -> Setting<'_> {
        Setting {
            value: self.lines.first().copied().unwrap_or(""),
            at: self.at.clone(),
        }
    }

    /// The value's lines joined as `configparser` joins them.
    fn value(&self) -> String {
        self.lines.join("\n")
    }
}

impl<'a> Section<'a> {
    fn get(&self, key: &str) -> Option<&Entry<'a>> {
        self.entries.iter().find(|entry| entry.key == key)
    }
}

/// Reads project text in format 0 into `reader`.
pub(super) fn read(text: &str, reader: &mut Reader<'_>) {
    let Some(sections) = sections(text, reader) else {
        return;
    };
    let section = |name: &str| sections.iter().find(|section| section.name == name);
    let Some(head) = section("AWLSIM_PROJECT") else {
        let at = sections.first().map_or(0..0, |first| first.at.clone());
        reader.errors.push(invalid(
            "the project has no `[AWLSIM_PROJECT]` section",
            span(at),
            "not `[AWLSIM_PROJECT]`",
            Some("a format 0 project begins with `[AWLSIM_PROJECT]` and `file_version=0`".into()),
        ));
        return;
    };
    match head.get("file_version") {
        None => reader.errors.push(invalid(
            "the project has no format version",
            span(head.at.clone()),
            "no `file_version`",
            Some("awlsim writes `file_version=0` below `[AWLSIM_PROJECT]`".into()),
        )),
        Some(version) if version.setting().value.trim() == "0" => {}
        Some(version) => reader.errors.push(not_run(
            format!("project format version {} is not read", version.value()),
            span(version.at.clone()),
            "this version",
            Some(
                "awl reads awlsim's INI-like projects of format version 0, and XML projects of \
                 format 1"
                    .into(),
            ),
        )),
    }
    if let Some(cpu) = section("CPU") {
        let settings = |name: &str| {
            let entry = cpu.get(name).filter(|_| CPU_SETTINGS.contains(&name))?;
            let setting = entry.setting();
            let value = if BOOLEAN_SETTINGS.contains(&name) {
                boolean(setting.value).unwrap_or(setting.value)
            } else {
                setting.value
            };
            Some(Setting { value, ..setting })
        };
        reader.specs(&settings);
        reader.config(&settings);
        sources(reader, cpu, "awl", Kind::Program);
    }
    if let Some(symbols) = section("SYMBOLS") {
        sources(reader, symbols, "sym_tab", Kind::SymbolTable);
    }
    for (name, prefix, language) in [
        ("FUP", "fup", "FUP (function block diagram)"),
        ("KOP", "kop", "KOP (ladder)"),
    ] {
        for entry in section(name).into_iter().flat_map(|s| listed(s, prefix)) {
            reader.errors.push(not_run(
                format!("a {language} source is not run"),
                span(entry.key_at.clone()),
                "this source",
                Some("awl runs STL only; awlsim compiles these to STL itself".into()),
            ));
        }
    }
    if let Some(libraries) = section("LIBS") {
        refuse_foreign_libraries(reader, libraries);
    }
    for entry in section("HWMODS")
        .into_iter()
        .flat_map(|s| numbered(s, "loaded_mod"))
    {
        reader.errors.push(not_run(
            "an awlsim hardware module is not simulated",
            span(entry.key_at.clone()),
            "this entry",
            Some("awl runs awlsim's projects on its dummy hardware only".into()),
        ));
    }
}

/// The library blocks of `[LIBS]` (`lib_name_N` in base64, `lib_block_N` as `FC 21`,
/// `lib_block_effective_N`): those awl has built in are called as they are, each other one is
/// an error.
fn refuse_foreign_libraries(reader: &mut Reader<'_>, libraries: &Section<'_>) {
    for (index, entry) in numbered(libraries, "lib_name").into_iter().enumerate() {
        let value = |key: &str| {
            libraries
                .get(&format!("{key}_{index}"))
                .map(|entry| entry.value())
                .unwrap_or_default()
        };
        let library = base64(&entry.value())
            .ok()
            .and_then(|bytes| String::from_utf8(bytes).ok())
            .unwrap_or_default();
        let block = value("lib_block");
        let (kind, number) = block.trim().split_once(' ').unwrap_or(("", ""));
        let effective = value("lib_block_effective");
        if !built_in_library_block(&library, kind, number, &effective) {
            reader.errors.push(not_run(
                "a block of awlsim's libraries is not run",
                span(entry.key_at.clone()),
                "this entry",
                Some(LIBRARY_HELP.into()),
            ));
        }
    }
}

/// `configparser`'s boolean words as the numbers the settings are checked as.
fn boolean(value: &str) -> Option<&'static str> {
    match value.trim().to_ascii_lowercase().as_str() {
        "1" | "yes" | "true" | "on" => Some("1"),
        "0" | "no" | "false" | "off" => Some("0"),
        _ => None,
    }
}

/// `prefix_0`, `prefix_1`, … up to the first number missing, as awlsim reads a list.
fn numbered<'s, 'a>(section: &'s Section<'a>, prefix: &str) -> Vec<&'s Entry<'a>> {
    (0..)
        .map_while(|index| section.get(&format!("{prefix}_{index}")))
        .collect()
}

/// The sources of a list: the files (`prefix_file_N`), then the texts (`prefix_N`).
fn listed<'s, 'a>(section: &'s Section<'a>, prefix: &str) -> Vec<&'s Entry<'a>> {
    let mut entries = numbered(section, &format!("{prefix}_file"));
    entries.extend(numbered(section, prefix));
    entries
}

/// The sources of `section`: files relative to the project, then texts in base64.
fn sources(reader: &mut Reader<'_>, section: &Section<'_>, prefix: &str, kind: Kind) {
    for file in numbered(section, &format!("{prefix}_file")) {
        reader.source_file(kind, file.setting());
    }
    for (index, entry) in numbered(section, prefix).into_iter().enumerate() {
        let bytes = match base64(&entry.value()) {
            Ok(bytes) => bytes,
            Err(problem) => {
                reader.errors.push(invalid(
                    format!("`{}` is not base64: {problem}", entry.key),
                    span(entry.at.clone()),
                    "this source",
                    Some(
                        "a source inside a format 0 project is its UTF-8 text in base64 \
                         (A–Z, a–z, 0–9, `+`, `/`, `=` at the end)"
                            .into(),
                    ),
                ));
                continue;
            }
        };
        // awlsim names a source whose name does not decode by its list and number.
        let name = section
            .get(&format!("{prefix}_name_{index}"))
            .and_then(|name| base64(&name.value()).ok())
            .and_then(|name| String::from_utf8(name).ok())
            .unwrap_or_else(|| format!("#{index}"));
        let text = String::from_utf8_lossy(&bytes);
        reader.inline_source(kind, &format!("{}: {name}", entry.key), &text);
    }
}

/// Decodes base64 (RFC 4648's alphabet; whitespace, as in continued lines, is skipped).
fn base64(text: &str) -> Result<Vec<u8>, String> {
    let mut bits: u32 = 0;
    let mut count = 0;
    let mut padding = 0;
    let mut out = Vec::with_capacity(text.len() / 4 * 3);
    for c in text.chars().filter(|c| !c.is_ascii_whitespace()) {
        let sextet = match c {
            'A'..='Z' => c as u32 - 'A' as u32,
            'a'..='z' => c as u32 - 'a' as u32 + 26,
            '0'..='9' => c as u32 - '0' as u32 + 52,
            '+' => 62,
            '/' => 63,
            '=' => {
                padding += 1;
                count += 1;
                continue;
            }
            _ => return Err(format!("`{c}` is not a base64 character")),
        };
        if padding > 0 {
            return Err("text after the `=` that ends it".into());
        }
        bits = bits << 6 | sextet;
        count += 1;
        if count % 4 == 0 {
            out.extend_from_slice(&bits.to_be_bytes()[1..]);
            bits = 0;
        }
    }
    if count % 4 != 0 || padding > 2 {
        return Err("it is cut off (its length is not a multiple of 4)".into());
    }
    match padding {
        1 => out.extend_from_slice(&(bits << 6).to_be_bytes()[1..3]),
        2 => out.push((bits << 12).to_be_bytes()[1]),
        _ => {}
    }
    Ok(out)
}

/// The sections of the text, as `configparser` reads them; `None` (errors kept) when a line
/// is not INI.
fn sections<'a>(text: &'a str, reader: &mut Reader<'_>) -> Option<Vec<Section<'a>>> {
    let mut sections: Vec<Section<'a>> = Vec::new();
    let mut continues = false;
    let mut offset = 0;
    let errors = reader.errors.len();
    for raw in text.split_inclusive('\n') {
        let start = offset;
        offset += raw.len();
        let line = raw.trim_end_matches(['\n', '\r']);
        let content = line.trim_start_matches('\u{feff}');
        let indent = line.len() - content.trim_start().len();
        let trimmed = content.trim();
        let at = start + indent..start + indent + trimmed.len();
        if trimmed.is_empty() {
            continues = false;
            continue;
        }
        if trimmed.starts_with(['#', ';']) {
            continue;
        }
        if continues
            && indent > 0
            && let Some(entry) = sections.last_mut().and_then(|s| s.entries.last_mut())
        {
            entry.lines.push(trimmed);
            entry.at.end = at.end;
            continue;
        }
        if let Some(name) = trimmed
            .strip_prefix('[')
            .and_then(|rest| rest.rfind(']').map(|end| &rest[..end]))
            .filter(|name| !name.is_empty())
        {
            if sections.iter().any(|section| section.name == name) {
                reader.errors.push(invalid(
                    format!("section `[{name}]` given twice"),
                    span(at.clone()),
                    "again",
                    Some("each section of an INI-like project is written once".into()),
                ));
            }
            sections.push(Section {
                name,
                at,
                entries: Vec::new(),
            });
            continues = false;
            continue;
        }
        let Some(split) = trimmed.find(['=', ':']) else {
            reader.errors.push(invalid(
                "neither a `[SECTION]` nor a `key = value` line",
                span(at),
                "this line",
                Some(
                    "a format 0 project holds `[SECTION]` lines and `key = value` below them"
                        .into(),
                ),
            ));
            continue;
        };
        let key = trimmed[..split].trim_end();
        let value = trimmed[split + 1..].trim_start();
        let key_at = at.start..at.start + key.len();
        let value_at = at.end - value.len()..at.end;
        let Some(section) = sections.last_mut().filter(|_| !key.is_empty()) else {
            reader.errors.push(invalid(
                if key.is_empty() {
                    "a value without a key"
                } else {
                    "a setting before any `[SECTION]`"
                },
                span(at),
                "this line",
                Some("a format 0 project begins with `[AWLSIM_PROJECT]`".into()),
            ));
            continue;
        };
        let key = key.to_ascii_lowercase();
        if section.get(&key).is_some() {
            reader.errors.push(invalid(
                format!("`{key}` given twice in `[{}]`", section.name),
                span(key_at),
                "again",
                Some("awlsim refuses a project with a key written twice in a section".into()),
            ));
            continue;
        }
        section.entries.push(Entry {
            key,
            key_at,
            lines: vec![value],
            at: value_at,
        });
        continues = true;
    }
    (reader.errors.len() == errors).then_some(sections)
}

#[cfg(test)]
mod tests {
    use super::super::Project;
    use super::super::tests::{messages, parse};
    use super::*;
    use crate::mnemonics::MnemonicSet;

    fn encode(text: &str) -> String {
        const ALPHABET: &[u8] = b"ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
        let mut out = String::new();
        for chunk in text.as_bytes().chunks(3) {
            let n = chunk
                .iter()
                .enumerate()
                .fold(0u32, |n, (i, &b)| n | u32::from(b) << (16 - 8 * i));
            for i in 0..4 {
                if i <= chunk.len() {
                    out.push(ALPHABET[(n >> (18 - 6 * i) & 63) as usize] as char);
                } else {
                    out.push('=');
                }
            }
        }
        out
    }

    #[test]
    fn an_iec_function_under_its_own_number_is_built_in() {
        // `SUVD` is "IEC" in base64.
        let libraries = |block: &str, effective: &str| {
            messages(&format!(
                "[AWLSIM_PROJECT]\nfile_version=0\n[LIBS]\nlib_name_0=SUVD\n\
                 lib_block_0={block}\nlib_block_effective_0={effective}\n"
            ))
        };
        assert!(
            parse(
                "[AWLSIM_PROJECT]\nfile_version=0\n[LIBS]\nlib_name_0=SUVD\n\
                 lib_block_0=FC 21\nlib_block_effective_0=21\n"
            )
            .is_ok()
        );
        for (block, effective) in [("FC 21", "5"), ("FB 21", "21"), ("FC 99", "99")] {
            assert_eq!(
                libraries(block, effective),
                ["a block of awlsim's libraries is not run"],
                "{block}"
            );
        }
    }

    #[test]
    fn base64_decodes_as_rfc_4648_says() {
        for text in [
            "",
            "f",
            "fo",
            "foo",
            "foob",
            "fooba",
            "foobar",
            "Zähler\r\n",
        ] {
            assert_eq!(base64(&encode(text)).unwrap(), text.as_bytes(), "{text}");
        }
        assert_eq!(base64("Zm9v\n  YmFy").unwrap(), b"foobar");
        assert!(base64("Zm9").is_err());
        assert!(base64("Zm9v!").is_err());
        assert!(base64("Zg==Zg==").is_err());
        assert!(base64("Z===").is_err());
    }

    #[test]
    fn sources_and_settings_are_read() {
        let text = format!(
            "[AWLSIM_PROJECT]\nfile_version = 0\ncreate_date=2014-01-01 00:00:00.000000\n\n\
             [CPU]\nawl_file_0=main.awl\nawl_0={}\nAWL_NAME_0={}\nnr_accus=4\nmnemonics=2\n\
             clock_memory_byte: 10\nob_startinfo_enable=True\next_insns_enable=off\n\
             ; a comment\n# another\n\n[SYMBOLS]\nsym_tab_file_0=plant.sym\n\
             sym_tab_0={}\n\n[LIBS]\n\n[GUI]\neditor_font=x\n",
            encode("FUNCTION FC 1 : VOID\nBEGIN\nEND_FUNCTION\n"),
            encode("FC 1"),
            encode("\"Stop\" I 0.1 BOOL"),
        );
        let project = parse(&text).unwrap();
        assert_eq!(project.accus, 4);
        assert_eq!(project.mnemonics, Some(MnemonicSet::German));
        assert_eq!(project.clock_memory, Some(10));
        assert!(project.start_info && !project.extensions);
        let names: Vec<String> = project
            .programs
            .iter()
            .chain(&project.symbols)
            .map(|(name, _)| name.display().to_string())
            .collect();
        assert_eq!(
            names,
            [
                "dir/main.awl",
                "dir/p.awlpro [awl_0: FC 1]",
                "dir/plant.sym",
                "dir/p.awlpro [sym_tab_0: #0]"
            ]
        );
        assert_eq!(
            project.programs[1].1,
            b"FUNCTION FC 1 : VOID\nBEGIN\nEND_FUNCTION"
        );
    }

    #[test]
    fn a_value_continues_on_indented_lines() {
        let source = encode("FUNCTION FC 1 : VOID\nBEGIN\nEND_FUNCTION");
        let (first, second) = source.split_at(8);
        let text = format!(
            "[AWLSIM_PROJECT]\nfile_version=0\n[CPU]\nawl_0={first}\n  {second}\n\
             [SYMBOLS]\n"
        );
        assert_eq!(parse(&text).unwrap().programs.len(), 1);
    }

    #[test]
    fn a_list_ends_at_its_first_missing_number() {
        let text = "[AWLSIM_PROJECT]\nfile_version=0\n[CPU]\nawl_file_0=main.awl\n\
                    awl_file_2=gone.awl\n";
        assert_eq!(parse(text).unwrap().programs.len(), 1);
    }

    #[test]
    fn every_error_is_reported() {
        assert_eq!(
            messages(
                "[AWLSIM_PROJECT]\nfile_version=0\nfile_version=0\n[CPU]\nawl stuff\n\
                 [CPU]\n=1\n"
            ),
            [
                "`file_version` given twice in `[AWLSIM_PROJECT]`",
                "neither a `[SECTION]` nor a `key = value` line",
                "section `[CPU]` given twice",
                "a value without a key",
            ]
        );
        assert_eq!(
            messages("[AWLSIM_PROJECT]]\nfile_version=0\n"),
            ["the project has no `[AWLSIM_PROJECT]` section"]
        );
        assert_eq!(
            messages("[AWLSIM_PROJECT]\ndate=1990-01-01\n"),
            ["the project has no format version"]
        );
        assert_eq!(
            messages("[AWLSIM_PROJECT]\nfile_version=2\n"),
            ["project format version 2 is not read"]
        );
        assert_eq!(
            messages(
                "[AWLSIM_PROJECT]\nfile_version=0\n[CPU]\nawl_file_0=gone.awl\nawl_0=Zm9v!\n\
                 nr_accus=3\nob_startinfo_enable=maybe\n[FUP]\nfup_0=Zm9v\n\
                 [KOP]\nkop_file_0=x.kop\n[LIBS]\nlib_name_0=SUVD\nlib_block_0=FB 1\n\
                 [HWMODS]\nloaded_mod_0=ZHVtbXk=\n"
            ),
            [
                "`nr_accus` 3 is out of range",
                "`ob_startinfo_enable` is not a number",
                "cannot read `gone.awl`: no such file",
                "`awl_0` is not base64: `!` is not a base64 character",
                "a FUP (function block diagram) source is not run",
                "a KOP (ladder) source is not run",
                "a block of awlsim's libraries is not run",
                "an awlsim hardware module is not simulated",
            ]
        );
    }

    #[test]
    fn awlsim_s_other_settings_in_cpu_are_its_defaults() {
        let project = parse(
            "[AWLSIM_PROJECT]\nfile_version=0\n[CPU]\nnr_flags=99999\ncycle_time_target_us=5\n",
        )
        .unwrap();
        assert_eq!(project, Project::default());
    }
}
