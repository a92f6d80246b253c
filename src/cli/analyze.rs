//! `awl analyze`: the worst cases computed from the program, before it runs.

use clap::ValueEnum;

use crate::analyze::{self, Config};
use crate::runner;

use super::run::{ProgramArgs, not_run, program_options};
use super::{Console, EXIT_OK};

#[derive(Debug, Clone, Copy, PartialEq, Eq, ValueEnum)]
pub enum AnalyzeFormat {
    Text,
    Json,
}

#[derive(Debug, clap::Args)]
pub struct AnalyzeArgs {
    #[command(flatten)]
    pub program: ProgramArgs,
    /// A table to read, or one JSON object (`awl help analysis` describes its fields)
    #[arg(long, value_enum, default_value = "text")]
    pub format: AnalyzeFormat,
}

pub fn analyze(args: &AnalyzeArgs, console: &mut Console) -> u8 {
    let mut prepared = match runner::prepare(&program_options(&args.program)) {
        Ok(prepared) => prepared,
        Err(reason) => return not_run("analyze", reason, console),
    };
    console.reports(&prepared.take_warnings());
    let cpu = &prepared.cpu;
    let analysis = analyze::analyze(&cpu.program, &prepared.frontend.sources, Config::of(cpu));
    match args.format {
        AnalyzeFormat::Text => console.out(&analyze::render(&analysis)),
        AnalyzeFormat::Json => console.out(&format!(
            "{}\n",
            serde_json::to_string_pretty(&analysis).expect("the analysis is plain data")
        )),
    }
    EXIT_OK
}
