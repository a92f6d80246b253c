//! Help that stands on its own after `cargo install`: `awl help TOPIC` prints the repository's
//! own documentation from the binary, every command's help names only its own options and says
//! each option's default, and no help sends the user to a file an installed awl does not have.

use std::process::Command;

use awl::cli::Cli;
use awl::docs::TOPICS;
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
    ] {
        let (ok, out, err) = awl(&["help", topic]);
        assert!(ok, "{err}");
        let expected = match heading {
            Some(heading) => section(file, heading),
            None => std::fs::read_to_string(file).expect("the repository's file"),
        };
        assert_eq!(out, expected, "awl help {topic}");
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

#[test]
fn no_help_points_into_the_repository() {
    let mut texts = vec![awl(&["--help"]).1, awl(&["help"]).1];
    for command in Cli::command().get_subcommands() {
        texts.push(awl(&[command.get_name(), "--help"]).1);
    }
    for text in texts {
        assert!(!text.contains("README"), "{text}");
    }
}

#[test]
fn a_scenario_s_key_errors_point_to_the_help_not_the_repository() {
    for text in ["[[evnt]]\nat = \"1ms\"\n", "progrm = \"a.awl\"\n"] {
        let (_, reports) =
            awl::scenario::Scenario::parse(std::path::Path::new("s.toml"), text, None);
        assert!(!reports.is_empty(), "{text}");
        for report in reports {
            let rendered = awl::diagnostics::render_plain(&report);
            assert!(!rendered.contains("README"), "{rendered}");
        }
    }
    let (_, reports) = awl::scenario::Scenario::parse(
        std::path::Path::new("s.toml"),
        "progrm = \"a.awl\"\n",
        None,
    );
    assert!(awl::diagnostics::render_plain(&reports[0]).contains("awl help scenario"));
}
