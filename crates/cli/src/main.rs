//! `mason`: plans and rehearses missions for robot construction crews.
//!
//! The binary is glue: it parses arguments, calls the libraries (every result checked by its
//! validator there), and prints. One module per subcommand in [`cmd`]. Exit codes: 0 success,
//! 1 infeasible or nothing found in the budget, 2 bad input or usage, 3 a launched team's
//! merged trace fails its check, 130 interrupted, 141 standard output closed early (a pipe into
//! `head`; quietly, as a program killed by SIGPIPE).

mod cmd;
mod fail;
mod input;
mod progress;

use clap::{Parser, Subcommand};
use std::process::ExitCode;

#[derive(Parser)]
#[command(name = "mason", version, about = "Plan and rehearse missions for robot construction crews", long_about = None)]
struct Cli {
    /// No progress bars
    #[arg(long, global = true)]
    quiet: bool,
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Run everything on the built-in walls: plan with every planner, print a comparison
    Demo(cmd::demo::DemoArgs),
    /// Wall designs
    Wall {
        #[command(subcommand)]
        command: cmd::wall::WallCommand,
    },
    /// Generate seeded inputs: a layer-text wall of N bricks, a bird's-eye crew scene
    Generate {
        #[command(subcommand)]
        command: cmd::generate::GenerateCommand,
    },
    /// Find a build order for a wall, or a team schedule with --objective
    Plan(cmd::plan::PlanArgs),
    /// Fly a build order with a UAV team (discrete-event simulation, faults, Monte Carlo)
    Simulate(cmd::simulate::SimArgs),
    /// Fly one UAV as its own process, coordinating with its team over Zenoh (feature
    /// `zenoh`); the vehicle is simulated in-process
    Agent(cmd::agent::AgentArgs),
    /// Start one agent process per UAV on this machine, kill or restart some, merge their
    /// traces and check the result (feature `zenoh`)
    Launch(cmd::launch::LaunchArgs),
    /// Make a mission authority and TLS files for each UAV and ground station of a real
    /// deployment (feature `zenoh`)
    Keys(cmd::keys::KeysArgs),
    /// Assign ground robots to goals and plan collision-free paths (seen from a UAV)
    Crew(cmd::crew::CrewArgs),
    /// Check a build order, team schedule, mission trace or crew plan, Mason's or another
    /// tool's, with the validator of its domain (exit 1 naming the first broken rule)
    Check(cmd::check::CheckArgs),
    /// Reproduce published comparisons and measure throughput
    Bench {
        #[command(subcommand)]
        suite: cmd::bench::Suite,
    },
}

fn run(cli: Cli) -> fail::CliResult<()> {
    let quiet = cli.quiet;
    match cli.command {
        Command::Demo(a) => cmd::demo::run(a, quiet),
        Command::Wall { command } => cmd::wall::run(command),
        Command::Generate { command } => cmd::generate::run(command),
        Command::Plan(a) if a.objective.is_some() => cmd::schedule::run(a),
        Command::Plan(a) => cmd::plan::run(a),
        Command::Simulate(a) => cmd::simulate::run(a, quiet),
        Command::Agent(a) => cmd::agent::run(a, quiet),
        Command::Launch(a) => cmd::launch::run(a, quiet),
        Command::Keys(a) => cmd::keys::run(a),
        Command::Crew(a) => cmd::crew::run(a),
        Command::Check(a) => cmd::check::run(a),
        Command::Bench { suite } => cmd::bench::run(suite, quiet),
    }
}

/// Exit code when standard output is closed before everything is printed (128 + SIGPIPE).
const STDOUT_CLOSED: i32 = 141;

/// Makes a write to a closed standard output end the process quietly with [`STDOUT_CLOSED`]
/// (`mason … | head`), not with a panic's message: `print!` panics on a broken pipe, and
/// Rust ignores SIGPIPE (restoring it would take `unsafe`, which the workspace forbids).
fn quiet_on_closed_stdout() {
    let default = std::panic::take_hook();
    std::panic::set_hook(Box::new(move |info| {
        let payload = info.payload();
        let message = payload
            .downcast_ref::<String>()
            .map(String::as_str)
            .or_else(|| payload.downcast_ref::<&str>().copied())
            .unwrap_or("");
        if message.starts_with("failed printing to stdout") && message.contains("Broken pipe") {
            std::process::exit(STDOUT_CLOSED);
        }
        default(info);
    }));
}

fn main() -> ExitCode {
    quiet_on_closed_stdout();
    let cli = Cli::parse();
    match run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(f) => {
            eprintln!("mason: {}", f.message);
            ExitCode::from(f.code)
        }
    }
}
