//! `mason`: plans and rehearses missions for robot construction crews.
//!
//! The binary is glue: it parses arguments, reads files, calls the libraries, validates every
//! result, and prints. Exit codes: 0 success, 1 infeasible or nothing found in the budget,
//! 2 bad input or usage.

mod bench;
mod crew_bench;
mod crew_cmd;
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
    /// Assign ground robots to goals and plan collision-free paths (seen from a UAV)
    Crew(CrewArgs),
    /// Reproduce published comparisons
    Bench {
        /// thesis (Tables 3.3–3.5 setting), planning (whole-process planning time) or paper
        /// (the crew paper's Table 2 setting and the MovingAI warehouse)
        suite: String,
        /// Seconds brute force may search per wall (thesis)
        #[arg(long, default_value_t = 60.0, allow_negative_numbers = true)]
        time_limit: f64,
        /// Repetitions per wall (planning)
        #[arg(long, default_value_t = 20)]
        runs: usize,
    },
}

#[derive(clap::Args)]
struct CrewArgs {
    /// MovingAI .map file or occupancy PNG (dark pixels are obstacles); omit with --image
    map: Option<String>,
    /// MovingAI .scen file with the robots' starts and goals
    #[arg(long)]
    scen: Option<PathBuf>,
    /// Take the first N agents of the scenario (default: all)
    #[arg(long)]
    agents: Option<usize>,
    /// Bird's-eye PNG: robots red, goals green, obstacles dark (one pixel per cell)
    #[arg(long)]
    image: Option<PathBuf>,
    /// given (scenario pairing; default with --scen), perm (the paper's n!), hungarian
    /// (default with --image) or path (Hungarian on path lengths)
    #[arg(long)]
    assign: Option<String>,
    /// Single-robot paths: astar or prm
    #[arg(long, default_value = "astar")]
    paths: String,
    /// Collision resolution: paper (priority waits) or st (space-time A*)
    #[arg(long, default_value = "st")]
    resolve: String,
    /// 4 or 8 (diagonals only past two free sides)
    #[arg(long, default_value = "8")]
    connectivity: String,
    /// Seed of the roadmap sampler
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// PRM samples
    #[arg(long, default_value_t = 2000)]
    samples: usize,
    /// PRM neighbours per node
    #[arg(long, default_value_t = 10)]
    neighbours: usize,
    /// Time budget in seconds
    #[arg(long, allow_negative_numbers = true)]
    time_limit: Option<f64>,
    /// Print JSON instead of a table
    #[arg(long)]
    json: bool,
    /// Draw the map, starts, goals and paths as SVG
    #[arg(long)]
    svg: Option<PathBuf>,
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
        Command::Crew(args) => crew(args),
        Command::Bench {
            suite,
            time_limit,
            runs,
        } => {
            let limit = plan::time_limit(Some(time_limit))?.unwrap_or(60.0);
            let text = match suite.as_str() {
                "thesis" => bench::thesis(limit)?,
                "planning" => bench::planning(runs)?,
                "paper" => crew_bench::paper(runs)?,
                other => {
                    return Err(input_error(format!(
                        "unknown bench suite `{other}`: expected thesis, planning or paper"
                    )))
                }
            };
            print!("{text}");
            Ok(())
        }
    }
}

fn crew(a: CrewArgs) -> CliResult<()> {
    let limit = plan::time_limit(a.time_limit)?;
    let prm = mason_crew::PrmConfig {
        samples: a.samples,
        neighbours: a.neighbours,
        seed: a.seed,
    };
    let choices = crew_cmd::choices(
        a.assign.as_deref(),
        &a.paths,
        &a.resolve,
        &a.connectivity,
        prm,
        a.scen.is_some(),
    )?;
    let input = crew_cmd::CrewInput {
        map: a.map.as_deref(),
        scen: a.scen.as_deref(),
        agents: a.agents,
        image: a.image.as_deref(),
    };
    let (inst, source) = crew_cmd::load_instance(&input, choices.connectivity)?;
    let result = crew_cmd::run_solve(&inst, &choices.config, limit)?;
    if let Some(path) = &a.svg {
        let title = format!(
            "{source} — {} robots, {} ({})",
            inst.robot_count(),
            result.outcome.status,
            a.resolve
        );
        let paths = result.outcome.paths.clone().unwrap_or_default();
        let svg = mason_report::crew_svg(
            &title,
            &inst.grid,
            &inst.robots,
            &result.outcome.goals,
            &paths,
        );
        write_file(path, svg.as_bytes())?;
    }
    if a.json {
        let v = crew_cmd::crew_json(&inst, &source, &choices.config, a.seed, &result);
        println!("{}", serde_json::to_string_pretty(&v).expect("json"));
    } else {
        print!(
            "{}",
            crew_cmd::crew_table(&inst, &source, &choices.config, &result)
        );
    }
    crew_cmd::exit_for(&result)
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
