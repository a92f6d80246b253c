//! awlsim's project format version 1 (awlsim 0.77.1 writes it): XML, `<awlsim_project
//! format_version="1">` holding `<cpu>` (`<specs nr_accus=…>`, `<config mnemonics=…>`), the
//! sources of each language (`<language_awl><source type="0" file=… enabled=…>`, the text
//! inside the element when there is no file), the symbol tables (`<symbols>`), library
//! selections, hardware modules and the GUI's and core server's settings.

use super::{Kind, LIBRARY_HELP, Reader, Setting, built_in_library_block, invalid, not_run, span};

/// The format version this module reads.
const FORMAT_VERSION: &str = "1";

/// awlsim's source types (`type=`): STL sources and symbol tables.
const AWL_SOURCE: &str = "0";
const SYMBOL_TABLE: &str = "3";

/// Reads project text in format 1 into `reader`.
pub(super) fn read(text: &str, reader: &mut Reader<'_>) {
    let document = match roxmltree::Document::parse(text) {
        Ok(document) => document,
        Err(error) => {
            let at = offset_of(text, error.pos());
            reader.errors.push(invalid(
                format!("not an awlsim project file: {error}"),
                (at, 0).into(),
                "here",
                Some(
                    "an awlsim project file is XML (format 1) or begins with `[AWLSIM_PROJECT]` \
                     (format 0)"
                        .into(),
                ),
            ));
            return;
        }
    };
    let root = document.root_element();
    if root.tag_name().name() != "awlsim_project" {
        reader.errors.push(invalid(
            format!("`<{}>` is not an awlsim project", root.tag_name().name()),
            tag_span(root),
            "not `<awlsim_project>`",
            Some("an awlsim project file's root element is `<awlsim_project>`".into()),
        ));
        return;
    }
    match root.attribute_node("format_version") {
        Some(version) if version.value() == FORMAT_VERSION => {}
        Some(version) => reader.errors.push(not_run(
            format!("project format version {} is not read", version.value()),
            span(version.range_value()),
            "this version",
            Some(
                "awl reads awlsim's XML projects of format version 1 (awlsim 0.77.1 writes it)"
                    .into(),
            ),
        )),
        None => reader.errors.push(invalid(
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
                    let settings = |name: &str| attribute(part, name);
                    match part.tag_name().name() {
                        "specs" => reader.specs(&settings),
                        "config" => reader.config(&settings),
                        _ => {}
                    }
                }
            }
            "language_awl" => sources(reader, section, AWL_SOURCE, Kind::Program),
            "symbols" => sources(reader, section, SYMBOL_TABLE, Kind::SymbolTable),
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
            "libraries" => libraries(reader, section),
            "hardware" => refuse_each(
                reader,
                section,
                "module",
                "an awlsim hardware module is not simulated",
                "this module",
                "awl runs awlsim's projects on its dummy hardware only",
            ),
            // The core server's link and the GUI's settings do not touch the run.
            _ => {}
        }
    }
}

/// The library blocks a project selects: those awl has built in are called as they are, each
/// other one is an error.
fn libraries(reader: &mut Reader<'_>, section: roxmltree::Node<'_, '_>) {
    for node in section
        .children()
        .filter(|node| node.has_tag_name("lib_selection"))
    {
        let value = |name: &str| node.attribute(name).unwrap_or("");
        if !built_in_library_block(
            value("name"),
            value("type"),
            value("index"),
            value("effective_index"),
        ) {
            reader.errors.push(not_run(
                "a block of awlsim's libraries is not run",
                span(node.range()),
                "this library block",
                Some(LIBRARY_HELP.into()),
            ));
        }
    }
}

/// An attribute as a setting.
fn attribute<'a>(node: roxmltree::Node<'a, '_>, name: &str) -> Option<Setting<'a>> {
    node.attribute_node(name).map(|attribute| Setting {
        value: attribute.value(),
        at: attribute.range_value(),
    })
}

/// An error for each `tag` element of `section`: a part of the project awl cannot run.
fn refuse_each(
    reader: &mut Reader<'_>,
    section: roxmltree::Node<'_, '_>,
    tag: &str,
    message: &str,
    label: &str,
    help: &str,
) {
    for node in section.children().filter(|node| node.has_tag_name(tag)) {
        reader.errors.push(not_run(
            message,
            span(node.range()),
            label,
            Some(help.into()),
        ));
    }
}

/// The `<source>`s of a section: each a file (relative to the project) or text inside.
fn sources(reader: &mut Reader<'_>, section: roxmltree::Node<'_, '_>, type_id: &str, kind: Kind) {
    let tag = section.tag_name().name();
    for (index, source) in enabled_sources(section).enumerate() {
        if let Some(given) = source.attribute_node("type")
            && given.value().trim() != type_id
        {
            reader.errors.push(invalid(
                format!("a source of type {} in `<{tag}>`", given.value()),
                span(given.range_value()),
                "this type",
                Some(format!(
                    "awlsim writes type {type_id} for the sources of `<{tag}>`"
                )),
            ));
            continue;
        }
        match attribute(source, "file").filter(|file| !file.value.is_empty()) {
            Some(file) => reader.source_file(kind, file),
            None => {
                let name = source.attribute("name").unwrap_or("source");
                let text: String = source
                    .descendants()
                    .filter(roxmltree::Node::is_text)
                    .filter_map(|node| node.text())
                    .collect();
                reader.inline_source(kind, &format!("{tag} {}: {name}", index + 1), &text);
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
fn tag_span(node: roxmltree::Node<'_, '_>) -> miette::SourceSpan {
    (node.range().start, node.tag_name().name().len() + 1).into()
}

#[cfg(test)]
mod tests {
    use super::super::tests::{messages, parse};
    use crate::mnemonics::MnemonicSet;

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
        assert_eq!(project.min_cycle_ns, None);
        assert!(project.programs.is_empty() && project.symbols.is_empty());
    }

    #[test]
    fn every_key_awl_honours_is_read() {
        let project = parse(
            "<awlsim_project format_version=\"1\"><cpu>\
             <specs nr_accus=\"4\" nr_inputs=\"1024\" nr_outputs=\"512\"/>\
             <config clock_memory_byte=\"7\" mnemonics=\"1\" ob_startinfo_enable=\"1\" \
             ext_insns_enable=\"1\" cycle_time_limit_us=\"2000\" run_time_limit_us=\"300\" \
             cycle_time_target_us=\"500\"/>\
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
        assert_eq!(project.min_cycle_ns, Some(500_000));
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
    fn an_iec_function_under_its_own_number_is_built_in() {
        let libraries = |selections: &str| {
            messages(&format!(
                "<awlsim_project format_version=\"1\"><libraries>{selections}</libraries>\
                 </awlsim_project>"
            ))
        };
        let selection = |name: &str, kind: &str, index: u16, effective: u16| {
            format!(
                "<lib_selection name=\"{name}\" type=\"{kind}\" index=\"{index}\" \
                 effective_index=\"{effective}\"/>"
            )
        };
        assert!(
            parse(&format!(
                "<awlsim_project format_version=\"1\"><libraries>{}</libraries></awlsim_project>",
                selection("IEC", "FC", 21, 21)
            ))
            .is_ok()
        );
        for refused in [
            selection("IEC", "FC", 21, 5),
            selection("IEC", "FC", 41, 41),
            selection("IEC", "FB", 21, 21),
            selection("TI-S7", "FC", 105, 105),
        ] {
            assert_eq!(
                libraries(&refused),
                ["a block of awlsim's libraries is not run"],
                "{refused}"
            );
        }
    }

    #[test]
    fn what_awl_cannot_honour_is_reported() {
        let found = messages(
            "<awlsim_project format_version=\"1\"><cpu>\
             <specs nr_accus=\"3\" nr_flags=\"9000\" nr_localbytes=\"70000\"/>\
             <config clock_memory_byte=\"5000\" mnemonics=\"x\" cycle_time_target_us=\"-1\"/>\
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
                "`nr_localbytes` 70000 is out of range",
                "`nr_flags` 9000 is more than awl's CPU has",
                "`clock_memory_byte` 5000 is out of range",
                "`mnemonics` is not a number",
                "`cycle_time_target_us` -1 is out of range",
                "cannot read `gone.awl`: no such file",
                "a source of type 3 in `<language_awl>`",
                "a KOP (ladder) source is not run",
                "a block of awlsim's libraries is not run",
                "an awlsim hardware module is not simulated",
            ]
        );
    }
}
