use std::process::ExitCode;

use clap::Parser;

fn main() -> ExitCode {
    awl::cli::run(awl::cli::Cli::parse())
}
