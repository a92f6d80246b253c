//! `awl help [TOPIC | COMMAND]`: the formats compiled into the binary, or a command's help.

use clap::CommandFactory;
use miette::Report;

use crate::docs::{self, UnknownTopic};

use super::{Cli, Console, EXIT_OK, EXIT_USAGE};

#[derive(Debug, clap::Args)]
pub struct HelpArgs {
    /// A topic (scenario, language, mnemonics, errors, …), `error` or a command (run, test, …)
    /// [default: the list of topics and commands]
    #[arg(value_name = "TOPIC")]
    pub topic: Option<String>,
    /// After `error`: the diagnostic code to explain, with or without `awl::`
    /// (`awl help error parse::unknown_operation`) [default: the list of codes]
    #[arg(value_name = "CODE")]
    pub code: Option<String>,
}

pub fn help(args: &HelpArgs, console: &mut Console) -> u8 {
    let mut cli = Cli::command();
    cli.build();
    let Some(asked) = args.topic.as_deref() else {
        console.out(&format!(
            "{}\nHelp topics (`awl help TOPIC`):\n{}",
            cli.render_long_help(),
            docs::list()
        ));
        return EXIT_OK;
    };
    if asked.trim().eq_ignore_ascii_case("error") {
        return error(args.code.as_deref(), console);
    }
    // Only `error` takes a second word: `awl help scenario run` asks for no topic awl has.
    let asked = match &args.code {
        Some(code) => &format!("{asked} {code}"),
        None => asked,
    };
    if let Some(topic) = docs::find(asked) {
        console.out(&topic.text());
        return EXIT_OK;
    }
    if let Some(command) = cli.find_subcommand(asked.trim()) {
        // What `awl COMMAND --help` prints, laid out by clap the same way.
        let name = command.get_name().to_string();
        if let Err(shown) = cli.try_get_matches_from_mut(["awl", name.as_str(), "--help"]) {
            console.out(&shown.render().to_string());
        }
        return EXIT_OK;
    }
    let error = UnknownTopic {
        asked: asked.to_string(),
        topics: docs::TOPICS
            .iter()
            .map(|topic| topic.name)
            .chain(["error CODE"])
            .collect::<Vec<_>>()
            .join(", "),
        commands: cli
            .get_subcommands()
            .map(|command| command.get_name())
            .collect::<Vec<_>>()
            .join(", "),
    };
    console.report(&Report::new(error));
    EXIT_USAGE
}

/// `awl help error [CODE]`: one code's page, or the list of codes.
fn error(code: Option<&str>, console: &mut Console) -> u8 {
    let Some(code) = code else {
        console.out(&docs::error_list());
        return EXIT_OK;
    };
    match docs::error_page(code) {
        Ok(page) => {
            console.out(&page);
            EXIT_OK
        }
        Err(unknown) => {
            console.report(&Report::new(unknown));
            EXIT_USAGE
        }
    }
}
