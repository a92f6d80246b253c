//! Help that stands on its own after `cargo install`: `awl help TOPIC` prints the repository's
//! own documentation from the binary, every command's help names only its own options and says
//! each option's default, and no help sends the user to a file an installed awl does not have.

use std::process::Command;

use awl::cli::Cli;
use awl::docs::{self, TOPICS};
use clap::CommandFactory;

fn awl(args: &[&str]) -> (bool, String, String) {
    let output = Command::new(env!("CARGO_BIN_EXE_awl"))
        .args(args)
        .output()
        .expect("awl runs");
    (
        output.status.success(),
        String::from_utf8(output.stdout).expect("UTF-8"),
        String::from_utf8(output.stderr).expect("UTF-8"),
    )
}

/// The `## heading` section of a file as it is in the repository now.
fn section(path: &str, heading: &str) -> String {
    let text = std::fs::read_to_string(path).expect("the repository's file");
    let start = text
        .find(&format!("## {heading}\n"))
        .unwrap_or_else(|| panic!("`## {heading}` in {path}"));
    let rest = &text[start + 3..];
    let end = rest
        .find("\n## ")
        .map_or(text.len(), |at| start + 3 + at + 1);
    text[start..end].to_string()
}

#[test]
fn each_topic_prints_the_repository_s_text_of_it() {
    for (topic, file, heading) in [
        ("scenario", "programs/README.md", Some("Scenario files")),
        ("trace", "programs/README.md", Some("Traces")),
        ("listing", "grammar/README.md", Some("PG listings")),
        ("symbols", "grammar/README.md", Some("Symbolic operands")),
        ("library", "grammar/README.md", Some("Library blocks")),
        ("errors", "grammar/errors.md", None),
        ("language", "grammar/README.md", None),
        ("lsp", "editors/README.md", None),
        ("mnemonics", "grammar/mnemonics.md", None),
    ] {
        let (ok, out, err) = awl(&["help", topic]);
        assert!(ok, "{err}");
        let expected = match heading {
            Some(heading) => section(file, heading),
            None => std::fs::read_to_string(file).expect("the repository's file"),
        };
        // A line with a link is printed without the link's target.
        for line in expected.lines().filter(|line| !line.contains("](")) {
            assert!(out.contains(line), "awl help {topic} lacks `{line}`");
        }
    }
}

#[test]
fn the_listing_topic_says_how_statements_are_numbered() {
    let (_, listing, _) = awl(&["help", "listing"]);
    assert!(listing.contains("### Statement addresses"), "{listing}");
}

#[test]
fn every_topic_has_text_and_the_list_names_it() {
    let (ok, list, _) = awl(&["help"]);
    assert!(ok);
    for topic in TOPICS {
        assert!(topic.text().len() > 100, "{}", topic.name);
        assert!(list.contains(topic.name), "{}", topic.name);
        let (ok, out, _) = awl(&["help", topic.name]);
        assert!(ok && out == topic.text(), "{}", topic.name);
        assert!(
            list.contains(&format!("  {}  ", topic.name)),
            "{}",
            topic.name
        );
    }
    assert!(
        list.contains("Usage: awl <COMMAND>"),
        "the list follows the usage"
    );
}

#[test]
fn help_on_a_command_is_its_own_help() {
    for command in ["run", "test", "analyze", "status"] {
        let (_, via_help, _) = awl(&["help", command]);
        let (_, via_flag, _) = awl(&[command, "--help"]);
        assert_eq!(via_help, via_flag, "{command}");
    }
}

#[test]
fn analyze_offers_no_run_length() {
    let (_, help, _) = awl(&["analyze", "--help"]);
    assert!(
        !help.contains("--cycles") && !help.contains("--for <"),
        "{help}"
    );
    assert!(
        help.contains("--scenario") && help.contains("--cpu"),
        "{help}"
    );
    for command in ["run", "status", "debug"] {
        let (_, help, _) = awl(&[command, "--help"]);
        assert!(
            help.contains("--cycles") && help.contains("--for <"),
            "{help}"
        );
    }
}

#[test]
fn test_help_explains_what_a_scenario_checks() {
    let (_, help, _) = awl(&["test", "--help"]);
    for word in [
        "[expect]",
        "[[check]]",
        "every",
        "watch",
        "awl help scenario",
    ] {
        assert!(help.contains(word), "`{word}` in\n{help}");
    }
}

#[test]
fn every_option_says_its_default() {
    let mut cli = Cli::command();
    cli.build();
    for command in cli.get_subcommands() {
        for arg in command.get_arguments() {
            let id = arg.get_id().as_str();
            if arg.is_positional() || arg.is_required_set() || matches!(id, "help" | "version") {
                continue;
            }
            let help = arg
                .get_long_help()
                .or(arg.get_help())
                .map(ToString::to_string)
                .unwrap_or_default();
            assert!(
                !arg.get_default_values().is_empty() || help.contains("[default: "),
                "awl {} --{id}: `{help}` says no default",
                command.get_name()
            );
        }
    }
}

/// What names a file of the repository, which an installed awl does not have.
const REPOSITORY_FILES: &[&str] = &[
    "README", ".md", ".ebnf", "src/", "grammar/", "tests/", ".rs", "SPEC §", "seed 000",
];

fn assert_names_no_file(what: &str, text: &str) {
    for name in REPOSITORY_FILES {
        if let Some(at) = text.find(name) {
            let from = text[..at].rfind('\n').map_or(0, |line| line + 1);
            let to = text[at..].find('\n').map_or(text.len(), |end| at + end);
            panic!("{what} names `{name}`: {}", &text[from..to]);
        }
    }
}

#[test]
fn no_printed_text_names_a_repository_file() {
    let mut texts = vec![
        ("awl --help".to_string(), awl(&["--help"]).1),
        ("awl help".to_string(), awl(&["help"]).1),
        ("awl help error".to_string(), awl(&["help", "error"]).1),
    ];
    for command in Cli::command().get_subcommands() {
        let name = command.get_name();
        texts.push((format!("awl {name} --help"), awl(&[name, "--help"]).1));
    }
    for topic in TOPICS {
        texts.push((format!("awl help {}", topic.name), topic.text()));
    }
    for page in docs::error_pages() {
        let text = docs::error_page(page.code).expect("its own page");
        texts.push((format!("awl help error {}", page.code), text));
    }
    for (what, text) in texts {
        assert_names_no_file(&what, &text);
    }
}

/// The rendered diagnostics the tests keep: none sends the user to a file.
#[test]
fn no_diagnostic_snapshot_names_a_repository_file() {
    let mut files: Vec<_> = std::fs::read_dir("tests/snapshots")
        .expect("the snapshots")
        .chain(std::fs::read_dir("tests/cmd").expect("the CLI cases"))
        .map(|entry| entry.expect("an entry").path())
        .filter(|path| {
            path.extension()
                .is_some_and(|ext| ext == "snap" || ext == "toml")
        })
        .collect();
    files.sort();
    assert!(files.len() > 100, "{}", files.len());
    for path in files {
        let text = std::fs::read_to_string(&path).expect("text");
        // A snapshot's header names its test; the CLI cases name the sample files they run.
        let printed: String = text
            .lines()
            .filter(|line| !line.starts_with("source:") && !line.starts_with("args ="))
            .filter(|line| !line.starts_with("expression:") && !line.contains("╭─["))
            .collect::<Vec<_>>()
            .join("\n");
        for name in [
            "README",
            ".ebnf",
            "mnemonics.md",
            "errors.md",
            "grammar/",
            "src/",
            "SPEC §",
        ] {
            assert!(!printed.contains(name), "{} names `{name}`", path.display());
        }
    }
}

/// Every `code(awl::…)` in the sources.
fn codes_in_the_sources(dir: &std::path::Path, codes: &mut Vec<String>) {
    for entry in std::fs::read_dir(dir).expect("a source folder") {
        let path = entry.expect("an entry").path();
        if path.is_dir() {
            codes_in_the_sources(&path, codes);
        } else if path.extension().is_some_and(|ext| ext == "rs") {
            let text = std::fs::read_to_string(&path).expect("a source file");
            for piece in text.split("code(awl::").skip(1) {
                let code: String = piece
                    .chars()
                    .take_while(|c| c.is_alphanumeric() || *c == '_' || *c == ':')
                    .collect();
                codes.push(format!("awl::{code}"));
            }
        }
    }
}

#[test]
fn every_code_the_sources_emit_has_a_page_in_the_binary() {
    let mut codes = Vec::new();
    codes_in_the_sources(std::path::Path::new("src"), &mut codes);
    codes.sort();
    codes.dedup();
    assert!(codes.len() > 100, "{}", codes.len());
    for code in &codes {
        let page = docs::error_page(code).unwrap_or_else(|_| panic!("{code} has no page"));
        assert!(page.starts_with(&format!("### {code}")), "{page}");
        let (ok, out, err) = awl(&["help", "error", code.strip_prefix("awl::").unwrap()]);
        assert!(ok && out == page, "awl help error {code}: {err}");
    }
    let (_, list, _) = awl(&["help", "error"]);
    for code in &codes {
        assert!(
            list.contains(&format!("  {code}")),
            "{code} not in the list"
        );
    }
}

#[test]
fn an_unknown_code_gets_the_codes_it_may_mean() {
    for (asked, meant) in [
        (
            "awl::parse::unknown_operaton",
            "`awl::parse::unknown_operation`?",
        ),
        (
            "unknown_operation",
            "`awl::parse::unknown_operation` or `awl::s7::unknown_operation`?",
        ),
        ("stop::zik", "`awl::stop::zyk`?"),
    ] {
        let (ok, out, err) = awl(&["help", "error", asked]);
        assert!(!ok && out.is_empty(), "{out}");
        assert!(err.contains("awl::help::unknown_code"), "{err}");
        let err = err.split_whitespace().collect::<Vec<_>>().join(" ");
        assert!(err.contains(&format!("did you mean {meant}")), "{err}");
    }
    let (ok, _, err) = awl(&["help", "error", "banana"]);
    assert!(
        !ok && err.contains("`awl help error` lists every code"),
        "{err}"
    );
}

#[test]
fn the_mnemonics_topic_has_both_dialects_tables() {
    let (ok, out, _) = awl(&["help", "mnemonics"]);
    assert!(ok);
    for info in awl::mnemonics::OPERATIONS {
        assert!(
            out.contains(&format!("| `{}` | `{}` |", info.en, info.de)),
            "{}",
            info.en
        );
    }
    use awl::step7::mnemonics as s7;
    for words in s7::OPERATIONS.iter().chain(s7::EXTENSION_OPERATIONS) {
        assert!(
            out.contains(&format!("| `{}` | `{}` |", words.en, words.de)),
            "{}",
            words.en
        );
    }
    for area in s7::AREAS {
        assert!(
            out.contains(&format!("| `{}` | `{}` |", area.en, area.de)),
            "{}",
            area.en
        );
    }
}

#[test]
fn the_scenario_topic_gives_each_cpu_s_watchdog() {
    let (_, out, _) = awl(&["help", "scenario"]);
    for cpu in awl::profile::PROFILES {
        let row = format!("| `{}` | {} ms |", cpu.name, cpu.watchdog_ns / 1_000_000);
        assert!(out.contains(&row), "{row}");
    }
}

#[test]
fn the_exit_codes_cover_every_command() {
    let (_, out, _) = awl(&["help", "exit-codes"]);
    for command in Cli::command().get_subcommands() {
        let name = format!("`awl {}`", command.get_name());
        assert!(out.contains(&name), "{name} in\n{out}");
    }
}

#[test]
fn a_scenario_s_key_errors_point_to_the_help_not_the_repository() {
    for text in ["[[evnt]]\nat = \"1ms\"\n", "progrm = \"a.awl\"\n"] {
        let (_, reports) = awl::scenario::Scenario::parse(std::path::Path::new("s.toml"), text);
        assert!(!reports.is_empty(), "{text}");
        for report in reports {
            let rendered = awl::diagnostics::render_plain(&report);
            assert!(!rendered.contains("README"), "{rendered}");
        }
    }
    let (_, reports) =
        awl::scenario::Scenario::parse(std::path::Path::new("s.toml"), "progrm = \"a.awl\"\n");
    assert!(awl::diagnostics::render_plain(&reports[0]).contains("awl help scenario"));
}

#[test]
fn only_error_takes_a_second_word() {
    let (ok, out, err) = awl(&["help", "scenario", "run"]);
    assert!(!ok && out.is_empty(), "{out}");
    assert!(
        err.contains("`scenario run` is neither a help topic nor a command"),
        "{err}"
    );
}
