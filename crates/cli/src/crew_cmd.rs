//! `mason crew`: read a map and a scenario (or a bird's-eye image), solve, validate, print.

use crate::fail::{input_error, no_solution, CliResult};
use mason_crew::distance::{step_distances, UNREACHABLE};
use mason_crew::image::{read_birdseye, read_occupancy};
use mason_crew::movingai::{parse_map, parse_scen};
use mason_crew::{
    solve, validate, AssignMethod, Budget, Cell, Connectivity, CrewConfig, CrewOutcome, Grid,
    Instance, PathMethod, PlanMetrics, PrmConfig, RefineConfig, Resolution, Status,
};
use rayon::prelude::*;
use serde_json::{json, Value};
use std::path::Path;
use std::time::Duration;

/// Where the robots and goals come from.
pub struct CrewInput<'a> {
    /// A `.map` file or an occupancy PNG.
    pub map: Option<&'a str>,
    /// A MovingAI scenario.
    pub scen: Option<&'a Path>,
    /// Take the first N agents of the scenario.
    pub agents: Option<usize>,
    /// A bird's-eye PNG with robots and goals.
    pub image: Option<&'a Path>,
}

/// The parsed solver choices.
pub struct CrewChoices {
    /// The solver configuration.
    pub config: CrewConfig,
    /// Moves allowed.
    pub connectivity: Connectivity,
}

/// The time limit of `--resolve lacam` when `--time-limit` is not given, in seconds.
pub const LACAM_DEFAULT_LIMIT_S: f64 = 60.0;

/// The solver flags as given.
pub struct RawChoices<'a> {
    /// `--assign`.
    pub assign: Option<&'a str>,
    /// `--paths`.
    pub paths: &'a str,
    /// `--resolve`.
    pub resolve: Option<&'a str>,
    /// `--connectivity`.
    pub connectivity: &'a str,
    /// `--seed`.
    pub seed: u64,
    /// `--refine-rounds`.
    pub refine_rounds: Option<u64>,
    /// `--refine-batch`.
    pub refine_batch: Option<usize>,
}

/// The largest `--refine-batch`: more neighbourhoods than that per batch would mostly be
/// planned against a stale plan.
const MAX_REFINE_BATCH: usize = 64;

/// Parses the solver options (usage errors exit 2).
pub fn choices(raw: RawChoices<'_>, prm: PrmConfig, has_pairing: bool) -> CliResult<CrewChoices> {
    let assign: AssignMethod = match raw.assign {
        Some(a) => a
            .parse()
            .map_err(|e| input_error(format!("--assign: {e}")))?,
        None if has_pairing => AssignMethod::Given,
        None => AssignMethod::Joint,
    };
    let paths: PathMethod = raw
        .paths
        .parse()
        .map_err(|e| input_error(format!("--paths: {e}")))?;
    if assign == AssignMethod::Joint && raw.resolve.is_some() {
        return Err(input_error(
            "--assign joint plans the paths itself (TSWAP); drop --resolve, or choose another --assign",
        ));
    }
    if assign == AssignMethod::Joint && paths != PathMethod::Astar {
        return Err(input_error(
            "--assign joint moves robots on the grid itself; drop --paths prm",
        ));
    }
    let resolve: Resolution = raw
        .resolve
        .unwrap_or("st")
        .parse()
        .map_err(|e| input_error(format!("--resolve: {e}")))?;
    let connectivity: Connectivity = raw
        .connectivity
        .parse()
        .map_err(|e| input_error(format!("--connectivity: {e}")))?;
    if prm.samples == 0 || prm.neighbours == 0 {
        return Err(input_error("--samples and --neighbours must be at least 1"));
    }
    if prm.samples > MAX_PRM_SAMPLES || prm.neighbours > MAX_PRM_NEIGHBOURS {
        return Err(input_error(format!(
            "--samples is at most {MAX_PRM_SAMPLES} and --neighbours at most {MAX_PRM_NEIGHBOURS}"
        )));
    }
    if raw.refine_rounds.is_some() && resolve != Resolution::Lacam {
        return Err(input_error("--refine-rounds applies to --resolve lacam"));
    }
    if raw.refine_batch.is_some() && resolve != Resolution::Lacam {
        return Err(input_error("--refine-batch applies to --resolve lacam"));
    }
    let mut refine = RefineConfig::default();
    if let Some(r) = raw.refine_rounds {
        refine.rounds = Some(r);
        refine.stall = None;
    }
    if let Some(b) = raw.refine_batch {
        if !(1..=MAX_REFINE_BATCH).contains(&b) {
            return Err(input_error(format!(
                "--refine-batch is 1 to {MAX_REFINE_BATCH}"
            )));
        }
        refine.batch = b;
    }
    Ok(CrewChoices {
        config: CrewConfig {
            assign,
            paths,
            resolve,
            prm,
            seed: raw.seed,
            refine,
        },
        connectivity,
    })
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

/// The most PRM samples `--samples` accepts.
pub const MAX_PRM_SAMPLES: usize = 1_000_000;
/// The most PRM neighbours `--neighbours` accepts.
pub const MAX_PRM_NEIGHBOURS: usize = 1_000;

/// Refuses an instance over [`mason_crew::limits::MAX_AGENT_CELLS`] (robots × free cells).
pub fn check_size(inst: &Instance, source: &str) -> CliResult<()> {
    let size = inst.robot_count() as u64 * inst.grid.free_count() as u64;
    let limit = mason_crew::limits::MAX_AGENT_CELLS;
    if size > limit {
        return Err(input_error(format!(
            "{source}: {} robots × {} free cells is more than {limit} (mason_crew::limits::MAX_AGENT_CELLS); take fewer robots (--agents N) or a smaller map",
            inst.robot_count(),
            inst.grid.free_count()
        )));
    }
    Ok(())
}

fn read(path: &Path) -> CliResult<Vec<u8>> {
    crate::input::read_input(path, crate::input::MAX_INPUT_BYTES)
}

fn read_text(path: &Path) -> CliResult<String> {
    String::from_utf8(read(path)?)
        .map_err(|_| input_error(format!("{}: not UTF-8 text", path.display())))
}

/// Reads the grid, robots and goals.
pub fn load_instance(input: &CrewInput<'_>, conn: Connectivity) -> CliResult<(Instance, String)> {
    let bad = |e: mason_crew::CrewError| input_error(e.to_string());
    match (input.map, input.scen, input.image) {
        (None, None, Some(image)) => {
            let name = image.display().to_string();
            let seen = read_birdseye(&read(image)?, &name).map_err(bad)?;
            if input.agents.is_some() {
                return Err(input_error("--agents applies to --scen, not to --image"));
            }
            let inst = Instance::new(seen.grid, conn, seen.robots, seen.goals, None, &name)
                .map_err(bad)?;
            Ok((inst, name))
        }
        (Some(map), Some(scen), None) => {
            let grid = load_grid(map)?;
            let scen_name = scen.display().to_string();
            if input.agents == Some(0) {
                return Err(input_error("--agents must be at least 1"));
            }
            let agents = parse_scen(
                &read_text(scen)?,
                &scen_name,
                &grid,
                input.agents.unwrap_or(usize::MAX),
            )
            .map_err(bad)?;
            let robots = agents.iter().map(|a| a.start).collect();
            let goals = agents.iter().map(|a| a.goal).collect();
            let pairing = Some((0..agents.len()).collect());
            let inst =
                Instance::new(grid, conn, robots, goals, pairing, &scen_name).map_err(bad)?;
            Ok((inst, map.to_string()))
        }
        (Some(_), None, None) => Err(input_error(
            "a map needs a scenario: give --scen F [--agents N], or use --image PNG alone",
        )),
        (_, _, Some(_)) => Err(input_error(
            "--image brings its own robots and goals; give it without a map or --scen",
        )),
        (None, _, None) => Err(input_error("give a MAP with --scen F, or --image PNG")),
    }
}

fn load_grid(map: &str) -> CliResult<Grid> {
    let path = Path::new(map);
    let bytes = read(path)?;
    let is_png = path
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("png"));
    if is_png {
        read_occupancy(&bytes, map).map_err(|e| input_error(e.to_string()))
    } else {
        let text = String::from_utf8(bytes).map_err(|_| {
            input_error(format!(
                "{map}: not UTF-8 text (a PNG map must end in .png)"
            ))
        })?;
        parse_map(&text, map).map_err(|e| input_error(e.to_string()))
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
    let outcome = solve(inst, config, &budget).map_err(|e| input_error(e.to_string()))?;
    let metrics = match &outcome.paths {
        Some(paths) => Some(
            validate(
                &inst.grid,
                inst.connectivity,
                &inst.robots,
                &outcome.goals,
                paths,
            )
            .map_err(|e| {
                input_error(format!(
                    "internal error: the crew plan failed validation: {e}"
                ))
            })?,
        ),
        None => None,
    };
    // Per robot only where the table shows it, or when the solver did not sum it already.
    let shortest = if inst.robot_count() <= TABLE_ROWS || outcome.stats.lower_bound.is_none() {
        inst.robots
            .par_iter()
            .zip(&outcome.goals)
            .map(|(&s, &g)| {
                let d = step_distances(&inst.grid, inst.connectivity, s)[g.0 as usize];
                (d != UNREACHABLE).then_some(u64::from(d))
            })
            .collect()
    } else {
        Vec::new()
    };
    Ok(CrewResult {
        outcome,
        metrics,
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
                    r.shortest[i].map_or("-".into(), |d| d.to_string())
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
