//! `mason`: plans and rehearses missions for robot construction crews.
//!
//! The binary is glue: it parses arguments, reads files, calls the libraries, validates every
//! result, and prints. Exit codes: 0 success, 1 infeasible or nothing found in the budget,
//! 2 bad input or usage.

// Without the `zenoh` feature the agent driver is built for its tests only.
#[cfg_attr(not(feature = "zenoh"), allow(dead_code))]
mod agent_cmd;
mod bench;
mod cmcp_bench;
mod crew_bench;
mod crew_cmd;
mod demo;
mod fail;
mod input;
mod launch;
mod mapf_bench;
mod mission_bench;
mod plan;
mod progress;
mod schedule_cmd;
mod sim_cmd;
#[cfg_attr(not(feature = "zenoh"), allow(dead_code))]
mod transport;
mod wall_cmd;
#[cfg_attr(not(feature = "zenoh"), allow(dead_code))]
mod world;
#[cfg(feature = "zenoh")]
mod zenoh_link;

use clap::{Parser, Subcommand};
use fail::{check_outputs, input_error, write_all, write_file, CliResult};
use input::{load_model, load_wall, Format, Sizes};
use mason_order::team::Objective;
use mason_order::{BuildProblem, PlannerSpec};
use std::path::PathBuf;
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

#[derive(clap::Args, Clone)]
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
    /// CMCP walls: refuse floating bricks and overlapping same-level bricks instead of warning
    #[arg(long)]
    strict: bool,
}

impl DesignArgs {
    fn load(&self) -> CliResult<mason_wall::Wall> {
        load_wall(&self.design, self.format, self.cmcp_sizes, self.strict)
    }
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
        /// Cost model parameters (TOML); defaults are the thesis's. With --objective: the team
        /// model, thesis, cmcp or a TOML file (default thesis)
        #[arg(long)]
        model: Option<String>,
        /// Plan a team schedule instead of a build order: makespan (whole wall, shortest),
        /// reward (most reward by --budget), expected (most expected reward by --budget when
        /// UAVs fail at --uav-hazard)
        #[arg(long)]
        objective: Option<String>,
        /// Team size for --objective
        #[arg(long, default_value_t = 3, allow_negative_numbers = true)]
        uavs: usize,
        /// Time budget T in seconds for --objective reward|expected (bricks count if placed by T)
        #[arg(long, allow_negative_numbers = true)]
        budget: Option<f64>,
        /// UAV failures per hour per UAV, for --objective expected
        #[arg(long, allow_negative_numbers = true)]
        uav_hazard: Option<f64>,
        /// Seed of the schedule search (same seed, same schedule unless --time-limit stops it)
        #[arg(long, default_value_t = 0, allow_negative_numbers = true)]
        seed: u64,
        /// Search budget in seconds (brute, improved, schedules); the best so far is reported
        #[arg(long, allow_negative_numbers = true)]
        time_limit: Option<f64>,
        /// Print JSON instead of a table
        #[arg(long)]
        json: bool,
        /// Also draw the wall with its build order as SVG
        #[arg(long)]
        svg: Option<PathBuf>,
        /// Also write an HTML page with the figure and the step table
        #[arg(long)]
        html: Option<PathBuf>,
    },
    /// Fly a build order with a UAV team (discrete-event simulation, faults, Monte Carlo)
    Simulate(SimArgs),
    /// Fly one UAV as its own process, coordinating with its team over Zenoh (feature
    /// `zenoh`); the vehicle is simulated in-process
    Agent(agent_cmd::AgentArgs),
    /// Start one agent process per UAV on this machine, kill or restart some, merge their
    /// traces and check the result (feature `zenoh`)
    Launch(launch::LaunchArgs),
    /// Assign ground robots to goals and plan collision-free paths (seen from a UAV)
    Crew(CrewArgs),
    /// Reproduce published comparisons
    Bench {
        /// thesis (Tables 3.3–3.5 setting), planning (whole-process planning time), paper (the
        /// crew paper's Table 2 setting and the MovingAI warehouse), thesis-mission (Table 5.1
        /// setting), missions (simulator throughput), cmcp (team schedules on the CMCP walls
        /// beside GRASP), replan (static against re-planned schedules under UAV failures) or
        /// mapf (MovingAI maps at rising agent counts: lacam and joint)
        suite: String,
        /// Seconds brute force may search per wall (thesis)
        #[arg(long, default_value_t = 60.0, allow_negative_numbers = true)]
        time_limit: f64,
        /// Repetitions: per wall (planning), instances per row (paper), Monte Carlo runs
        /// (thesis-mission, at least 100), thousands of missions per row (missions), fifties of
        /// missions per policy (replan: 20 → 1000)
        #[arg(long, default_value_t = 20, allow_negative_numbers = true)]
        runs: usize,
        /// cmcp: the benchmark directory holding config/ and GRASP-RESULTS.md (default
        /// ../shared/benchmarks/walls-cmcp); mapf: the directory holding maps/ and scen/
        /// (default ../shared/benchmarks/mapf)
        #[arg(long)]
        data: Option<PathBuf>,
        /// mapf: the long sweep (more maps, 30 s per case) instead of the default few minutes
        #[arg(long)]
        long: bool,
    },
}

#[derive(clap::Args)]
struct SimArgs {
    #[command(flatten)]
    design: DesignArgs,
    /// Team size
    #[arg(long, default_value_t = 3, allow_negative_numbers = true)]
    uavs: usize,
    /// Coordination: comm (messages), windows (fixed time slots) or auto (comm, windows
    /// while heartbeats are lost)
    #[arg(long, default_value = "comm")]
    coord: String,
    /// Planner for the shared build order (see `mason plan`)
    #[arg(long, default_value = "exact")]
    planner: String,
    /// Fly a team schedule instead of a shared order: makespan, reward or expected (see
    /// `mason plan --objective`; the team model is the thesis model of --model's times; expected
    /// takes its failure rate from --uav-hazard). Each UAV takes its own bricks in its own order
    #[arg(long)]
    objective: Option<String>,
    /// Budget T in seconds for --objective reward|expected
    #[arg(long, allow_negative_numbers = true)]
    budget: Option<f64>,
    /// With --objective: when a UAV fails, the survivors re-plan the rest of the wall (within
    /// 100 ms). With --runs N, flies the static and the re-planned schedule on the same seeds
    /// and compares them
    #[arg(long)]
    replan: bool,
    /// Cost model (grasp and placement times, κ)
    #[arg(long)]
    model: Option<PathBuf>,
    /// Windows slot length in seconds (default 20, raised to the longest zone time)
    #[arg(long, allow_negative_numbers = true)]
    slot: Option<f64>,
    /// Probability that one grasp attempt fails
    #[arg(long, allow_negative_numbers = true)]
    grasp_fail: Option<f64>,
    /// Probability that one detection attempt fails
    #[arg(long, allow_negative_numbers = true)]
    detect_fail: Option<f64>,
    /// UAV U (0-based) fails at T seconds, as U@T; repeatable
    #[arg(long)]
    uav_fail: Vec<String>,
    /// UAV failures per hour (each UAV)
    #[arg(long, allow_negative_numbers = true)]
    uav_hazard: Option<f64>,
    /// No message gets through from A to B seconds, as A-B; repeatable
    #[arg(long)]
    blackout: Vec<String>,
    /// Probability that one message is lost
    #[arg(long, allow_negative_numbers = true)]
    msg_loss: Option<f64>,
    /// Message latency in seconds
    #[arg(long, allow_negative_numbers = true)]
    latency: Option<f64>,
    /// Faults from a TOML file (keys as the flags, with underscores); flags add to it
    #[arg(long)]
    faults: Option<PathBuf>,
    /// Arena, UAV model and coordination settings from a TOML file (see README); its
    /// [faults] are used unless --faults or a fault flag is given
    #[arg(long)]
    mission: Option<PathBuf>,
    /// Monte Carlo runs (seeds S, S+1, …), spread over the cores
    #[arg(long, default_value_t = 1, allow_negative_numbers = true)]
    runs: usize,
    /// Seed of the first run
    #[arg(long, default_value_t = 0, allow_negative_numbers = true)]
    seed: u64,
    /// Print JSON instead of a table
    #[arg(long)]
    json: bool,
    /// Draw the mission Gantt chart as SVG (single run)
    #[arg(long)]
    svg: Option<PathBuf>,
    /// Write the self-contained HTML replay (single run)
    #[arg(long)]
    html: Option<PathBuf>,
    /// Write the run as an MCAP log that Foxglove opens as it is (single run): UAV poses
    /// (foxglove.PoseInFrame, 2 Hz along each leg), states, the wall zone, bricks grasped, placed
    /// and lost, the wall as a 3-D scene (foxglove.SceneUpdate), every event as a log line
    /// (foxglove.Log); JSON messages, mission time in ns (see README)
    #[arg(long)]
    mcap: Option<PathBuf>,
}

#[derive(clap::Args)]
struct CrewArgs {
    /// MovingAI .map file or occupancy PNG (dark pixels are obstacles); omit with --image
    map: Option<String>,
    /// MovingAI .scen file with the robots' starts and goals
    #[arg(long)]
    scen: Option<PathBuf>,
    /// Take the first N agents of the scenario (default: all)
    #[arg(long, allow_negative_numbers = true)]
    agents: Option<usize>,
    /// Bird's-eye PNG: robots red, goals green, obstacles dark (one pixel per cell)
    #[arg(long)]
    image: Option<PathBuf>,
    /// given (scenario pairing; default with --scen), perm (the paper's n!), hungarian,
    /// path (Hungarian on path lengths) or joint (interchangeable robots: TSWAP solves the
    /// assignment and the paths together; default with --image)
    #[arg(long)]
    assign: Option<String>,
    /// Single-robot paths: astar or prm
    #[arg(long, default_value = "astar")]
    paths: String,
    /// Collision resolution: paper (priority waits), st (prioritized space-time A*; default)
    /// or lacam (complete LaCAM, then refinement until --time-limit); not with --assign joint
    #[arg(long)]
    resolve: Option<String>,
    /// 4 or 8 (diagonals only past two free sides)
    #[arg(long, default_value = "8")]
    connectivity: String,
    /// Seed of the roadmap sampler and of lacam (same seed, same plan, unless --time-limit
    /// stops the refinement)
    #[arg(long, default_value_t = 0, allow_negative_numbers = true)]
    seed: u64,
    /// lacam: refinement rounds at most (0: the first plan as it is; default: until
    /// --time-limit, or 1000 rounds in a row without improvement)
    #[arg(long)]
    refine_rounds: Option<u64>,
    /// lacam: refinement neighbourhoods planned side by side in one batch, on all cores
    /// (default 4; 1: one at a time, better on one core). The plan depends on it and on the
    /// seed, not on the cores
    #[arg(long)]
    refine_batch: Option<usize>,
    /// PRM samples
    #[arg(long, default_value_t = 2000, allow_negative_numbers = true)]
    samples: usize,
    /// PRM neighbours per node
    #[arg(long, default_value_t = 10, allow_negative_numbers = true)]
    neighbours: usize,
    /// Time budget in seconds (lacam: 60 when not given; it refines until then)
    #[arg(long, allow_negative_numbers = true)]
    time_limit: Option<f64>,
    /// Print JSON instead of a table
    #[arg(long)]
    json: bool,
    /// Draw the map, starts, goals and paths as SVG
    #[arg(long)]
    svg: Option<PathBuf>,
    /// Write the self-contained HTML replay of the plan
    #[arg(long)]
    html: Option<PathBuf>,
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
            print!("{}", demo::run(&out, limit, !cli.quiet)?);
            Ok(())
        }
        Command::Wall {
            command: WallCommand::Show { design, svg, json },
        } => {
            let wall = design.load()?;
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
            objective,
            uavs,
            budget,
            uav_hazard,
            seed,
            time_limit,
            json,
            svg,
            html,
        } => {
            let started = std::time::Instant::now();
            check_outputs(&[&svg, &html])?;
            if let Some(objective) = objective {
                let req = ScheduleArgs {
                    objective,
                    uavs,
                    budget,
                    uav_hazard,
                    seed,
                    time_limit,
                };
                return plan_schedule(design, model, req, json, svg, html, started);
            }
            if uav_hazard.is_some() || budget.is_some() {
                return Err(input_error(
                    "--budget and --uav-hazard belong to team schedules: add --objective",
                ));
            }
            let spec: PlannerSpec = planner
                .parse()
                .map_err(|e| input_error(format!("--planner: {e}")))?;
            let limit = plan::time_limit(time_limit)?;
            let wall = design.load()?;
            let model = load_model(model.as_deref().map(std::path::Path::new))?;
            let problem =
                BuildProblem::new(&wall, model).map_err(|e| input_error(e.to_string()))?;
            let checked = plan::solve(&problem, spec, limit)?;
            let figure = mason_report::wall_svg(&wall, checked.outcome.order.as_deref());
            let mut files: Vec<(PathBuf, Vec<u8>)> = Vec::new();
            if let Some(path) = svg {
                files.push((path, figure.clone().into_bytes()));
            }
            if let Some(path) = html {
                let page = mason_report::report_page(
                    &format!("{} — {}", wall.name(), spec),
                    "Build order (bold numbers: step; small: brick id), checked by order::validate.",
                    &[
                        mason_report::Section { heading: "Wall".into(), html: figure.clone() },
                        mason_report::Section {
                            heading: "Steps".into(),
                            html: mason_report::pre(&plan::plan_table(&problem, &checked)),
                        },
                    ],
                );
                files.push((path, page.into_bytes()));
            }
            write_all(&files)?;
            if json {
                println!(
                    "{}",
                    serde_json::to_string_pretty(&plan::plan_json(&problem, &checked))
                        .expect("json")
                );
            } else {
                print!("{}", plan::plan_table(&problem, &checked));
            }
            plan::report_overrun(limit, started, checked.outcome.stats.elapsed.as_secs_f64());
            plan::exit_for(&checked)
        }
        Command::Simulate(args) => simulate(args, cli.quiet),
        Command::Crew(args) => crew(args),
        Command::Agent(args) => agent_cmd::run(args, cli.quiet),
        Command::Launch(args) => launch::run(args, cli.quiet),
        Command::Bench {
            suite,
            time_limit,
            runs,
            data,
            long,
        } => {
            if long && suite != "mapf" {
                return Err(input_error("--long applies to bench mapf"));
            }
            if runs == 0 {
                return Err(input_error("--runs must be at least 1"));
            }
            let limit = plan::time_limit(Some(time_limit))?.unwrap_or(60.0);
            let text = match suite.as_str() {
                "thesis" => bench::thesis(limit)?,
                "planning" => bench::planning(runs)?,
                "paper" => crew_bench::paper(runs, !cli.quiet)?,
                "thesis-mission" => mission_bench::thesis_mission(runs.max(100))?,
                "missions" => mission_bench::throughput(runs)?,
                "cmcp" => cmcp_bench::cmcp(data.as_deref(), None)?,
                "replan" => mission_bench::replan(runs.max(1) * 50)?,
                "mapf" => mapf_bench::mapf(data.as_deref(), long, !cli.quiet)?,
                other => {
                    return Err(input_error(format!(
                        "unknown bench suite `{other}`: expected thesis, planning, paper, thesis-mission, missions, cmcp, replan or mapf"
                    )))
                }
            };
            print!("{text}");
            Ok(())
        }
    }
}

/// The raw team-schedule flags of `mason plan`.
struct ScheduleArgs {
    objective: String,
    uavs: usize,
    budget: Option<f64>,
    uav_hazard: Option<f64>,
    seed: u64,
    time_limit: Option<f64>,
}

impl ScheduleArgs {
    fn resolve(&self) -> CliResult<schedule_cmd::ScheduleRequest> {
        let mut objective: Objective = self
            .objective
            .parse()
            .map_err(|e| input_error(format!("--objective: {e}")))?;
        match (&mut objective, self.uav_hazard) {
            (Objective::Expected { hazard_per_hour }, Some(h)) => *hazard_per_hour = h,
            (Objective::Expected { .. }, None) => {
                return Err(input_error(
                    "--objective expected needs --uav-hazard λ (failures per hour)",
                ))
            }
            (_, Some(_)) => return Err(input_error("--uav-hazard is for --objective expected")),
            _ => {}
        }
        Ok(schedule_cmd::ScheduleRequest {
            objective,
            uavs: self.uavs,
            budget_s: self.budget,
            time_limit: plan::time_limit(self.time_limit)?,
            seed: self.seed,
        })
    }
}

fn plan_schedule(
    design: DesignArgs,
    model: Option<String>,
    args: ScheduleArgs,
    json: bool,
    svg: Option<PathBuf>,
    html: Option<PathBuf>,
    started: std::time::Instant,
) -> CliResult<()> {
    let req = args.resolve()?;
    let team = schedule_cmd::load_team_model(model.as_deref())?;
    let wall = design.load()?;
    let problem = schedule_cmd::problem(&wall, team, &req)?;
    let checked = schedule_cmd::solve(&problem, &req)?;
    let schedule = checked.outcome.schedule.clone().unwrap_or_default();
    let title = format!(
        "{} — {} schedule, {} UAVs, model {}",
        wall.name(),
        problem.objective(),
        problem.uavs(),
        problem.model().name
    );
    let figure = mason_report::schedule_svg(&title, &problem, &schedule);
    let mut files: Vec<(PathBuf, Vec<u8>)> = Vec::new();
    if let Some(path) = svg {
        files.push((path, figure.clone().into_bytes()));
    }
    if let Some(path) = html {
        let page = mason_report::report_page(
            &title,
            &schedule_cmd::summary_line(&problem, &checked.outcome),
            &[
                mason_report::Section {
                    heading: "Schedule".into(),
                    html: figure.clone(),
                },
                mason_report::Section {
                    heading: "Placements".into(),
                    html: mason_report::pre(&schedule_cmd::schedule_table(&problem, &checked)),
                },
            ],
        );
        files.push((path, page.into_bytes()));
    }
    write_all(&files)?;
    if json {
        let v = schedule_cmd::schedule_json(&problem, &checked, req.seed);
        println!("{}", serde_json::to_string_pretty(&v).expect("json"));
    } else {
        print!("{}", schedule_cmd::schedule_table(&problem, &checked));
    }
    plan::report_overrun(
        req.time_limit,
        started,
        checked.outcome.stats.elapsed.as_secs_f64(),
    );
    Ok(())
}

fn simulate(a: SimArgs, quiet: bool) -> CliResult<()> {
    check_outputs(&[&a.svg, &a.html, &a.mcap])?;
    let coord: mason_mission::Coord = a
        .coord
        .parse()
        .map_err(|e| input_error(format!("--coord: {e}")))?;
    let spec: PlannerSpec = a
        .planner
        .parse()
        .map_err(|e| input_error(format!("--planner: {e}")))?;
    if a.runs == 0 {
        return Err(input_error("--runs must be at least 1"));
    }
    if a.seed.checked_add(a.runs as u64 - 1).is_none() {
        return Err(input_error(format!(
            "--seed {} --runs {}: the seeds would run past {}",
            a.seed,
            a.runs,
            u64::MAX
        )));
    }
    let cli_faults = sim_cmd::FaultSpec {
        grasp_fail: a.grasp_fail,
        detect_fail: a.detect_fail,
        uav_fail: a.uav_fail.clone(),
        uav_hazard: a.uav_hazard,
        blackout: a.blackout.clone(),
        msg_loss: a.msg_loss,
        latency: a.latency,
    };
    let file_faults = match &a.faults {
        Some(p) => sim_cmd::FaultSpec::read_checked(p, a.uavs)?,
        None => sim_cmd::FaultSpec::default(),
    };
    let any_fault_option = a.faults.is_some()
        || cli_faults.grasp_fail.is_some()
        || cli_faults.detect_fail.is_some()
        || !cli_faults.uav_fail.is_empty()
        || cli_faults.uav_hazard.is_some()
        || !cli_faults.blackout.is_empty()
        || cli_faults.msg_loss.is_some()
        || cli_faults.latency.is_some();
    let faults = file_faults.merged(cli_faults).resolve()?;
    let wall = a.design.load()?;
    let model = load_model(a.model.as_deref())?;
    let problem =
        BuildProblem::new(&wall, model.clone()).map_err(|e| input_error(e.to_string()))?;
    let checked = plan::solve(&problem, spec, Some(60.0))?;
    plan::exit_for(&checked)?;
    let mut order = checked.outcome.order.clone().expect("checked order");
    let mut assignment: Option<Vec<Vec<mason_wall::BrickId>>> = None;
    let mut replanner: Option<mason_mission::ScheduleReplanner> = None;
    if a.replan && a.objective.is_none() {
        return Err(input_error(
            "--replan re-plans a team schedule: add --objective",
        ));
    }
    if let Some(objective) = &a.objective {
        let args = ScheduleArgs {
            objective: objective.clone(),
            uavs: a.uavs,
            budget: a.budget,
            uav_hazard: if objective == "expected" {
                a.uav_hazard
            } else {
                None
            },
            seed: a.seed,
            time_limit: None,
        };
        let req = args.resolve()?;
        let flight = schedule_cmd::flight_plan(&wall, &model, &req, &order)?;
        if a.replan {
            replanner = Some(mason_mission::ScheduleReplanner::new(
                flight.team,
                req.objective,
                req.budget_s,
                a.seed,
            ));
        }
        order = flight.order;
        assignment = Some(flight.lists);
    } else if a.budget.is_some() {
        return Err(input_error(
            "--budget belongs to --objective reward|expected",
        ));
    }
    let mut config: mason_mission::MissionConfig = match &a.mission {
        Some(p) => sim_cmd::read_mission(p, a.uavs)?,
        None => mason_mission::MissionConfig::default(),
    };
    config.uavs = a.uavs;
    if any_fault_option || a.mission.is_none() {
        config.faults = faults;
    }
    if a.slot.is_some() {
        config.coord.slot_s = a.slot;
    }
    let slot = sim_cmd::prepare(&wall, &model, &config)?;
    if a.runs > 1 && (a.svg.is_some() || a.html.is_some() || a.mcap.is_some()) {
        return Err(input_error(
            "--svg, --html and --mcap show one mission; drop --runs (or use --runs 1 --seed S)",
        ));
    }
    let input = mason_mission::MissionInput {
        wall: &wall,
        order: &order,
        model: &model,
        assignment: assignment.as_deref(),
        replanner: replanner
            .as_ref()
            .map(|r| r as &dyn mason_mission::Replanner),
        config: &config,
    };
    if a.runs == 1 {
        let (r, trace) = sim_cmd::fly_once(input, coord, slot, a.seed)?;
        sim_cmd::check_replans(replanner.as_ref())?;
        let title = format!(
            "{} — {} UAVs, {}, seed {}",
            wall.name(),
            a.uavs,
            a.coord,
            a.seed
        );
        let mut files: Vec<(PathBuf, Vec<u8>)> = Vec::new();
        if let Some(path) = &a.svg {
            let svg = mason_report::gantt_svg(&title, &wall, a.uavs, &trace, r.metrics.end_s);
            files.push((path.clone(), svg.into_bytes()));
        }
        if let Some(path) = &a.html {
            let page = mason_report::mission_replay_html(
                &title,
                &wall,
                &config.arena,
                a.uavs,
                &trace,
                r.metrics.end_s,
            );
            files.push((path.clone(), page.into_bytes()));
        }
        if let Some(path) = &a.mcap {
            let mission_id = format!("simulate/{}/seed-{}", wall.name(), a.seed);
            let meta = mason_report::LogMeta {
                mission_id: &mission_id,
                uavs: a.uavs,
                arena: &config.arena,
                wall: &wall,
            };
            let bytes = mason_report::mission_mcap(&meta, &trace, r.metrics.end_s)
                .map_err(|e| input_error(format!("internal error: {}: {e}", path.display())))?;
            files.push((path.clone(), bytes));
        }
        write_all(&files)?;
        if a.json {
            let events: Vec<_> = trace
                .iter()
                .map(|e| sim_cmd::event_json(&wall, e))
                .collect();
            let v = serde_json::json!({
                "wall": wall.name(), "uavs": a.uavs, "coord": coord, "planner": spec.to_string(),
                "order": order.iter().map(|b| wall.brick(*b).label).collect::<Vec<_>>(),
                "seed": a.seed, "slot_s": slot, "faults": config.faults,
                "metrics": sim_cmd::metrics_json(&r), "events": events,
            });
            println!("{}", serde_json::to_string_pretty(&v).expect("json"));
        } else {
            println!(
                "{}: {} UAVs, coord {}, order from {} (seed {})",
                wall.name(),
                a.uavs,
                a.coord,
                spec,
                a.seed
            );
            print!("{}", sim_cmd::result_table(&r, &trace));
        }
        return sim_cmd::exit_for(&r);
    }
    if input.replanner.is_some() {
        compare_replanning(&a, input, coord, slot, quiet)?;
        return sim_cmd::check_replans(replanner.as_ref());
    }
    let pb = progress::bar(a.runs as u64, "simulating", !quiet && !a.json);
    let mut lines = progress::Lines::new("simulating", a.runs as u64, !quiet);
    let summary = sim_cmd::fly_summary(
        input,
        coord,
        slot,
        a.seed,
        a.runs,
        None,
        &|| pb.inc(1),
        &mut lines,
    )?
    .summary();
    pb.finish_and_clear();
    if a.json {
        let v = serde_json::json!({
            "wall": wall.name(), "uavs": a.uavs, "coord": coord, "planner": spec.to_string(),
            "first_seed": a.seed, "slot_s": slot, "faults": config.faults, "summary": summary,
        });
        println!("{}", serde_json::to_string_pretty(&v).expect("json"));
    } else {
        println!(
            "{}: {} UAVs, coord {}, order from {}, seeds {}..{}",
            wall.name(),
            a.uavs,
            a.coord,
            spec,
            a.seed,
            a.seed + a.runs as u64 - 1
        );
        print!("{}", sim_cmd::summary_table(&summary));
    }
    Ok(())
}

/// `simulate --objective … --replan --runs N`: the static and the re-planned schedule on the
/// same seeds.
fn compare_replanning(
    a: &SimArgs,
    input: mason_mission::MissionInput<'_>,
    coord: mason_mission::Coord,
    slot: f64,
    quiet: bool,
) -> CliResult<()> {
    let pb = progress::bar(2 * a.runs as u64, "simulating", !quiet && !a.json);
    let fixed = mason_mission::MissionInput {
        replanner: None,
        ..input
    };
    let mut lines = progress::Lines::new("simulating", 2 * a.runs as u64, !quiet);
    let mut rows = Vec::new();
    for (name, flown) in [("static", fixed), ("replanned", input)] {
        let s = sim_cmd::fly_summary(
            flown,
            coord,
            slot,
            a.seed,
            a.runs,
            a.budget,
            &|| pb.inc(1),
            &mut lines,
        )?;
        rows.push(sim_cmd::PolicyRow::of_summary(name, &s));
    }
    pb.finish_and_clear();
    if a.json {
        let v = serde_json::json!({
            "wall": input.wall.name(), "uavs": a.uavs, "coord": coord,
            "objective": a.objective, "budget_s": a.budget, "first_seed": a.seed,
            "faults": input.config.faults, "compare": rows,
        });
        println!("{}", serde_json::to_string_pretty(&v).expect("json"));
    } else {
        println!(
            "{}: {} UAVs, coord {}, {} schedule, static vs re-planned on seeds {}..{}",
            input.wall.name(),
            a.uavs,
            a.coord,
            a.objective.as_deref().unwrap_or("-"),
            a.seed,
            a.seed + a.runs as u64 - 1
        );
        print!("{}", sim_cmd::policy_table(&rows, a.budget));
    }
    Ok(())
}

fn crew(a: CrewArgs) -> CliResult<()> {
    let started = std::time::Instant::now();
    check_outputs(&[&a.svg, &a.html])?;
    let limit = plan::time_limit(a.time_limit)?;
    let prm = mason_crew::PrmConfig {
        samples: a.samples,
        neighbours: a.neighbours,
        seed: a.seed,
    };
    let choices = crew_cmd::choices(
        crew_cmd::RawChoices {
            assign: a.assign.as_deref(),
            paths: &a.paths,
            resolve: a.resolve.as_deref(),
            connectivity: &a.connectivity,
            seed: a.seed,
            refine_rounds: a.refine_rounds,
            refine_batch: a.refine_batch,
        },
        prm,
        a.scen.is_some(),
    )?;
    // lacam is anytime and, on a hard instance, its search could grow until memory runs out:
    // without a limit it gets a default one.
    let limit = match (limit, choices.config.resolve, choices.config.assign) {
        (None, mason_crew::Resolution::Lacam, a) if a != mason_crew::AssignMethod::Joint => {
            Some(crew_cmd::LACAM_DEFAULT_LIMIT_S)
        }
        (l, _, _) => l,
    };
    let input = crew_cmd::CrewInput {
        map: a.map.as_deref(),
        scen: a.scen.as_deref(),
        agents: a.agents,
        image: a.image.as_deref(),
    };
    let (inst, source) = crew_cmd::load_instance(&input, choices.connectivity)?;
    crew_cmd::check_size(&inst, &source)?;
    let result = crew_cmd::run_solve(&inst, &choices.config, limit)?;
    let mut files: Vec<(PathBuf, Vec<u8>)> = Vec::new();
    if let Some(path) = &a.svg {
        let title = format!(
            "{source} — {} robots, {} ({})",
            inst.robot_count(),
            result.outcome.status,
            crew_cmd::method_label(&choices.config)
        );
        let paths = result.outcome.paths.clone().unwrap_or_default();
        let svg = mason_report::crew_svg(
            &title,
            &inst.grid,
            &inst.robots,
            &result.outcome.goals,
            &paths,
        );
        files.push((path.clone(), svg.into_bytes()));
    }
    if let (Some(path), Some(paths)) = (&a.html, &result.outcome.paths) {
        let title = format!(
            "{source} — {} robots ({})",
            inst.robot_count(),
            crew_cmd::method_label(&choices.config)
        );
        let page = mason_report::crew_replay_html(&title, &inst.grid, &result.outcome.goals, paths);
        files.push((path.clone(), page.into_bytes()));
    }
    write_all(&files)?;
    if a.json {
        let v = crew_cmd::crew_json(&inst, &source, &choices.config, a.seed, &result);
        println!("{}", serde_json::to_string_pretty(&v).expect("json"));
    } else {
        print!(
            "{}",
            crew_cmd::crew_table(&inst, &source, &choices.config, &result)
        );
    }
    plan::report_overrun(limit, started, result.outcome.stats.elapsed.as_secs_f64());
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
