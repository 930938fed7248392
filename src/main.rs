use clap::{Parser, Subcommand};

/// tumble: high-accuracy rigid-body dynamics.
#[derive(Parser, Debug)]
#[command(name = "tumble", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {}

fn main() -> std::process::ExitCode {
    let cli = Cli::parse();
    match cli.command {}
}
