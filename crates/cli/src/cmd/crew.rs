//! `mason crew`: read a map and a scenario (or a bird's-eye image), solve, validate, print.

use crate::cmd::plan::{pretty, report_overrun, time_limit};
use crate::fail::{check_outputs, input_error, no_solution, write_all, CliResult};
use mason_crew::{
    AssignMethod, Budget, Cell, CrewConfig, CrewOutcome, Grid, Instance, PlanMetrics, Status,
};
use mason_io::crew::{check_size, choices, RawChoices, LACAM_DEFAULT_LIMIT_S};
use serde_json::{json, Value};
use std::path::PathBuf;
use std::time::Duration;

/// `mason crew`'s options.
#[derive(clap::Args)]
pub struct CrewArgs {
    /// MovingAI .map file or occupancy PNG (dark pixels are obstacles); omit with --image
    pub map: Option<String>,
    /// MovingAI .scen file with the robots' starts and goals
    #[arg(long)]
    pub scen: Option<PathBuf>,
    /// Take the first N agents of the scenario (default: all)
    #[arg(long, allow_negative_numbers = true)]
    pub agents: Option<usize>,
    /// Bird's-eye PNG: robots red, goals green, obstacles dark (one pixel per cell)
    #[arg(long)]
    pub image: Option<PathBuf>,
    /// given (scenario pairing; default with --scen), perm (the paper's n!), hungarian,
    /// path (Hungarian on path lengths) or joint (interchangeable robots: TSWAP solves the
    /// assignment and the paths together; default with --image)
    #[arg(long)]
    pub assign: Option<String>,
    /// Single-robot paths: astar or prm
    #[arg(long, default_value = "astar")]
    pub paths: String,
    /// Collision resolution: paper (priority waits), st (prioritized space-time A*; default)
    /// or lacam (complete LaCAM, then refinement until --time-limit); not with --assign joint
    #[arg(long)]
    pub resolve: Option<String>,
    /// 4 or 8 (diagonals only past two free sides)
    #[arg(long, default_value = "8")]
    pub connectivity: String,
    /// Seed of the roadmap sampler and of lacam (same seed, same plan, unless --time-limit
    /// stops the restarts or the refinement)
    #[arg(long, default_value_t = 0, allow_negative_numbers = true)]
    pub seed: u64,
    /// lacam: refinement rounds at most (0: the first plan as it is; default: until
    /// --time-limit, or 1000 rounds in a row without improvement)
    #[arg(long)]
    pub refine_rounds: Option<u64>,
    /// lacam: refinement neighbourhoods planned side by side in one batch, on all cores
    /// (default 4; 1: one at a time, better on one core). The plan depends on it and on the
    /// seed, not on the cores
    #[arg(long)]
    pub refine_batch: Option<usize>,
    /// PRM samples
    #[arg(long, default_value_t = 2000, allow_negative_numbers = true)]
    pub samples: usize,
    /// PRM neighbours per node
    #[arg(long, default_value_t = 10, allow_negative_numbers = true)]
    pub neighbours: usize,
    /// Time budget in seconds (lacam: 60 when not given; it refines until then)
    #[arg(long, allow_negative_numbers = true)]
    pub time_limit: Option<f64>,
    /// Print JSON instead of a table
    #[arg(long)]
    pub json: bool,
    /// Draw the map, starts, goals and paths as SVG
    #[arg(long)]
    pub svg: Option<PathBuf>,
    /// Write the self-contained HTML replay of the plan
    #[arg(long)]
    pub html: Option<PathBuf>,
}

/// `mason crew`.
pub fn run(a: CrewArgs) -> CliResult<()> {
    let started = std::time::Instant::now();
    check_outputs(&[&a.svg, &a.html])?;
    let limit = time_limit(a.time_limit)?;
    let prm = mason_crew::PrmConfig {
        samples: a.samples,
        neighbours: a.neighbours,
        seed: a.seed,
    };
    let choices = choices(
        RawChoices {
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
            Some(LACAM_DEFAULT_LIMIT_S)
        }
        (l, _, _) => l,
    };
    let input = mason_io::CrewInput {
        map: a.map.as_deref(),
        scen: a.scen.as_deref(),
        agents: a.agents,
        image: a.image.as_deref(),
    };
    let (inst, source) = mason_io::load_crew(&input, choices.connectivity)?;
    check_size(&inst, &source)?;
    let result = run_solve(&inst, &choices.config, limit)?;
    let mut files: Vec<(PathBuf, Vec<u8>)> = Vec::new();
    if let Some(path) = &a.svg {
        let title = format!(
            "{source} — {} robots, {} ({})",
            inst.robot_count(),
            result.outcome.status,
            method_label(&choices.config)
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
            method_label(&choices.config)
        );
        let page = mason_report::crew_replay_html(&title, &inst.grid, &result.outcome.goals, paths);
        files.push((path.clone(), page.into_bytes()));
    }
    write_all(&files)?;
    if a.json {
        let v = crew_json(&inst, &source, &choices.config, a.seed, &result);
        println!("{}", pretty(&v));
    } else {
        print!("{}", crew_table(&inst, &source, &choices.config, &result));
    }
    report_overrun(limit, started, result.outcome.stats.elapsed.as_secs_f64());
    exit_for(&result)
}

/// "assign joint", "resolve lacam", … for titles.
pub fn method_label(config: &CrewConfig) -> String {
    if config.assign == AssignMethod::Joint {
        "joint (TSWAP)".into()
    } else {
        format!(
            "assign {:?}, paths {:?}, resolve {:?}",
            config.assign, config.paths, config.resolve
        )
        .to_lowercase()
    }
}

/// A solve with its validation.
pub struct CrewResult {
    /// The solver's outcome.
    pub outcome: CrewOutcome,
    /// The validator's metrics, when there is a plan.
    pub metrics: Option<PlanMetrics>,
    /// Each robot's fewest steps to its assigned goal (`None` when unreachable); empty when the
    /// solver gave the sum and there are too many robots to list.
    pub shortest: Vec<Option<u64>>,
}

/// Robots listed one per row in the text table.
const TABLE_ROWS: usize = 60;

impl CrewResult {
    /// Σ of the robots' shortest step distances (a lower bound on the sum of costs); `None`
    /// when some goal is unreachable.
    pub fn lower_bound(&self) -> Option<u64> {
        if self.shortest.is_empty() {
            return self.outcome.stats.lower_bound;
        }
        self.shortest.iter().copied().sum()
    }
}

/// Solves and validates (a plan the validator rejects is a bug, reported as such).
pub fn run_solve(
    inst: &Instance,
    config: &CrewConfig,
    limit: Option<f64>,
) -> CliResult<CrewResult> {
    let budget = match limit {
        Some(s) => Budget::time(Duration::from_secs_f64(s)),
        None => Budget::unlimited(),
    };
    let checked = mason_crew::solve_checked(inst, config, &budget).map_err(|e| match e {
        mason_crew::CheckedSolveError::Setup(e) => input_error(e.to_string()),
        e => input_error(format!("internal error: {e}")),
    })?;
    let outcome = checked.outcome;
    // Per robot only where the table shows it, or when the solver did not sum it already;
    // never past the time limit (a BFS per robot on a huge map takes seconds).
    let shortest = if (inst.robot_count() <= TABLE_ROWS || outcome.stats.lower_bound.is_none())
        && !budget.out_of_time()
    {
        mason_crew::shortest_steps(inst, &outcome.goals)
    } else {
        Vec::new()
    };
    Ok(CrewResult {
        outcome,
        metrics: checked.metrics,
        shortest,
    })
}

fn xy(grid: &Grid, c: Cell) -> [u32; 2] {
    let (x, y) = grid.xy(c);
    [x, y]
}

/// The JSON of DESIGN §7, with the inputs' parameters.
pub fn crew_json(
    inst: &Instance,
    source: &str,
    config: &CrewConfig,
    seed: u64,
    r: &CrewResult,
) -> Value {
    let g = &inst.grid;
    let o = &r.outcome;
    let agents: Vec<Value> = (0..inst.robot_count())
        .map(|i| {
            let path: Vec<[u32; 2]> = o
                .paths
                .as_ref()
                .map(|p| p[i].iter().map(|&c| xy(g, c)).collect())
                .unwrap_or_default();
            json!({"start": xy(g, inst.robots[i]), "goal": xy(g, o.goals[i]), "path": path})
        })
        .collect();
    json!({
        "map": {"source": source, "width": g.width(), "height": g.height()},
        "connectivity": inst.connectivity.degree(),
        "assign": format!("{:?}", config.assign).to_lowercase(),
        "paths": format!("{:?}", config.paths).to_lowercase(),
        "resolve": format!("{:?}", config.resolve).to_lowercase(),
        "prm": {"samples": config.prm.samples, "neighbours": config.prm.neighbours},
        "seed": seed,
        "refine_rounds_limit": config.refine.rounds,
        "refine_batch": config.refine.batch,
        "status": o.status,
        "reason": o.reason,
        "agents": agents,
        "sum_of_costs": r.metrics.map(|m| m.sum_of_costs),
        "makespan": r.metrics.map(|m| m.makespan),
        "lower_bound_sum_of_costs": r.lower_bound(),
        "stats": {
            "elapsed_ms": o.stats.elapsed.as_secs_f64() * 1e3,
            "first_solution_ms": o.stats.first_solution.map(|d| d.as_secs_f64() * 1e3),
            "first_sum_of_costs": o.stats.first_sum_of_costs,
            "configurations": o.stats.configurations,
            "refine_rounds": o.stats.refine_rounds,
            "improvements": o.stats.improvements,
            "expanded": o.stats.expanded,
            "waits": o.stats.waits,
            "peak_memory_mb": peak_memory_mb(),
        },
    })
}

/// A readable summary, with one row per robot for up to 60 robots.
pub fn crew_table(inst: &Instance, source: &str, config: &CrewConfig, r: &CrewResult) -> String {
    let g = &inst.grid;
    let o = &r.outcome;
    let mut s = format!(
        "{source}: {} robots on {}×{} ({} free cells), {}-connected; {}\n",
        inst.robot_count(),
        g.width(),
        g.height(),
        g.free_count(),
        inst.connectivity.degree(),
        method_label(config)
    );
    if let Some(paths) = &o.paths {
        if inst.robot_count() <= TABLE_ROWS {
            s.push_str(&format!(
                "  {:>5} {:>12} {:>12} {:>8} {:>9}\n",
                "robot", "start", "goal", "arrives", "shortest"
            ));
            for (i, p) in paths.iter().enumerate() {
                s.push_str(&format!(
                    "  {:>5} {:>12} {:>12} {:>8} {:>9}\n",
                    i,
                    format!("{:?}", g.xy(inst.robots[i])),
                    format!("{:?}", g.xy(o.goals[i])),
                    mason_crew::validate::arrival(p),
                    r.shortest
                        .get(i)
                        .copied()
                        .flatten()
                        .map_or("-".into(), |d| d.to_string())
                ));
            }
        }
    }
    s.push_str(&format!("status: {}\n", o.status));
    if let Some(reason) = &o.reason {
        s.push_str(&format!("reason: {reason}\n"));
    }
    if let Some(m) = r.metrics {
        s.push_str(&format!(
            "sum of costs: {} (lower bound {}{}), makespan: {}\n",
            m.sum_of_costs,
            r.lower_bound().map_or("-".into(), |b| b.to_string()),
            r.lower_bound()
                .filter(|&b| b > 0)
                .map_or(String::new(), |b| format!(
                    ", +{:.1} %",
                    (m.sum_of_costs as f64 / b as f64 - 1.0) * 100.0
                )),
            m.makespan
        ));
    }
    if let (Some(first), Some(soc)) = (o.stats.first_solution, o.stats.first_sum_of_costs) {
        s.push_str(&format!(
            "first plan after {:.2} ms with sum of costs {soc}; {} configurations; {} refinement rounds, {} kept\n",
            first.as_secs_f64() * 1e3,
            o.stats.configurations,
            o.stats.refine_rounds,
            o.stats.improvements
        ));
    }
    s.push_str(&format!(
        "time: {:.2} ms, {} nodes expanded, {} waits inserted; plan checked by crew::validate\n",
        o.stats.elapsed.as_secs_f64() * 1e3,
        o.stats.expanded,
        o.stats.waits
    ));
    s
}

/// Exit status: 1 with the reason when there is no plan.
pub fn exit_for(r: &CrewResult) -> CliResult<()> {
    match r.outcome.status {
        Status::Optimal | Status::Feasible => Ok(()),
        status => Err(no_solution(format!(
            "crew: {status}: {}",
            r.outcome.reason.as_deref().unwrap_or("no plan")
        ))),
    }
}

/// The process's peak resident memory in MB (Linux `VmHWM`), if known.
pub fn peak_memory_mb() -> Option<f64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kb: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb / 1024.0)
}
