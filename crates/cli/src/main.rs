//! `mason`: plans and rehearses missions for robot construction crews.
//!
//! The binary is glue: it parses arguments, reads files, calls the libraries, validates every
//! result, and prints. Exit codes: 0 success, 1 infeasible or nothing found in the budget,
//! 2 bad input or usage.

mod bench;
mod demo;
mod fail;
mod input;
mod plan;
mod wall_cmd;

use clap::{Parser, Subcommand};
use fail::{input_error, write_file, CliResult};
use input::{load_model, load_wall, Format, Sizes};
use mason_order::{BuildProblem, PlannerSpec};
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Parser)]
#[command(name = "mason", version, about = "Plan and rehearse missions for robot construction crews", long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(clap::Args)]
struct DesignArgs {
    /// Wall design: a layer-text, MBZIRC, PNG or CMCP file, or builtin:NAME
    /// (thesis-2x5, levels5-width5, levels5-width10, mbzirc)
    design: String,
    /// How to read the design
    #[arg(long, value_enum, default_value = "auto")]
    format: Format,
    /// Size table for CMCP walls
    #[arg(long, value_enum, default_value = "yaml")]
    cmcp_sizes: Sizes,
}

#[derive(Subcommand)]
enum Command {
    /// Run everything on the built-in walls: plan with every planner, print a comparison
    Demo {
        /// Output directory for figures and JSON
        #[arg(long, default_value = "mason-out")]
        out: PathBuf,
        /// Seconds brute force and improved greedy may search per wall
        #[arg(long, default_value_t = 2.0, allow_negative_numbers = true)]
        time_limit: f64,
    },
    /// Wall designs
    Wall {
        #[command(subcommand)]
        command: WallCommand,
    },
    /// Find a build order for a wall
    Plan {
        #[command(flatten)]
        design: DesignArgs,
        /// brute, greedy, improved:N,K (e.g. improved:1,4) or exact
        #[arg(long, default_value = "exact")]
        planner: String,
        /// Cost model parameters (TOML); defaults are the thesis's
        #[arg(long)]
        model: Option<PathBuf>,
        /// Search budget in seconds (brute, improved); the best order so far is reported
        #[arg(long, allow_negative_numbers = true)]
        time_limit: Option<f64>,
        /// Print JSON instead of a table
        #[arg(long)]
        json: bool,
        /// Also draw the wall with its build order as SVG
        #[arg(long)]
        svg: Option<PathBuf>,
    },
    /// Reproduce published comparisons
    Bench {
        /// thesis (Tables 3.3–3.5 setting) or planning (whole-process planning time)
        suite: String,
        /// Seconds brute force may search per wall (thesis)
        #[arg(long, default_value_t = 60.0, allow_negative_numbers = true)]
        time_limit: f64,
        /// Repetitions per wall (planning)
        #[arg(long, default_value_t = 20)]
        runs: usize,
    },
}

#[derive(Subcommand)]
enum WallCommand {
    /// Parse, validate and describe a wall design
    Show {
        #[command(flatten)]
        design: DesignArgs,
        /// Draw the wall as SVG
        #[arg(long)]
        svg: Option<PathBuf>,
        /// Print JSON instead of a table
        #[arg(long)]
        json: bool,
    },
}

fn run(cli: Cli) -> CliResult<()> {
    match cli.command {
        Command::Demo { out, time_limit } => {
            let limit = plan::time_limit(Some(time_limit))?.unwrap_or(2.0);
            print!("{}", demo::run(&out, limit)?);
            Ok(())
        }
        Command::Wall {
            command: WallCommand::Show { design, svg, json },
        } => {
            let wall = load_wall(&design.design, design.format, design.cmcp_sizes)?;
            if let Some(path) = svg {
                write_file(&path, mason_report::wall_svg(&wall, None).as_bytes())?;
            }
            if json {
                println!(
                    "{}",
                    serde_json::to_string_pretty(&plan::wall_json(&wall)).expect("json")
                );
            } else {
                print!("{}", wall_cmd::wall_table(&wall));
            }
            Ok(())
        }
        Command::Plan {
            design,
            planner,
            model,
            time_limit,
            json,
            svg,
        } => {
            let spec: PlannerSpec = planner
                .parse()
                .map_err(|e| input_error(format!("--planner: {e}")))?;
            let limit = plan::time_limit(time_limit)?;
            let wall = load_wall(&design.design, design.format, design.cmcp_sizes)?;
            let model = load_model(model.as_deref())?;
            let problem =
                BuildProblem::new(&wall, model).map_err(|e| input_error(e.to_string()))?;
            let checked = plan::solve(&problem, spec, limit)?;
            if let Some(path) = svg {
                let svg = mason_report::wall_svg(&wall, checked.outcome.order.as_deref());
                write_file(&path, svg.as_bytes())?;
            }
            if json {
                println!(
                    "{}",
                    serde_json::to_string_pretty(&plan::plan_json(&problem, &checked))
                        .expect("json")
                );
            } else {
                print!("{}", plan::plan_table(&problem, &checked));
            }
            plan::exit_for(&checked)
        }
        Command::Bench {
            suite,
            time_limit,
            runs,
        } => {
            let limit = plan::time_limit(Some(time_limit))?.unwrap_or(60.0);
            let text = match suite.as_str() {
                "thesis" => bench::thesis(limit)?,
                "planning" => bench::planning(runs)?,
                other => {
                    return Err(input_error(format!(
                        "unknown bench suite `{other}`: expected thesis or planning"
                    )))
                }
            };
            print!("{text}");
            Ok(())
        }
    }
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(f) => {
            eprintln!("mason: {}", f.message);
            ExitCode::from(f.code)
        }
    }
}
