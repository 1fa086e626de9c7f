//! `mason crew`: read a map and a scenario (or a bird's-eye image), solve, validate, print.

use crate::fail::{input_error, no_solution, CliResult};
use mason_crew::distance::{step_distances, UNREACHABLE};
use mason_crew::image::{read_birdseye, read_occupancy};
use mason_crew::movingai::{parse_map, parse_scen};
use mason_crew::{
    solve, validate, AssignMethod, Budget, Cell, Connectivity, CrewConfig, CrewOutcome, Grid,
    Instance, PathMethod, PlanMetrics, PrmConfig, Resolution, Status,
};
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

/// Parses the solver options (usage errors exit 2).
pub fn choices(
    assign: Option<&str>,
    paths: &str,
    resolve: &str,
    connectivity: &str,
    prm: PrmConfig,
    has_pairing: bool,
) -> CliResult<CrewChoices> {
    let assign: AssignMethod = match assign {
        Some(a) => a
            .parse()
            .map_err(|e| input_error(format!("--assign: {e}")))?,
        None if has_pairing => AssignMethod::Given,
        None => AssignMethod::Hungarian,
    };
    let paths: PathMethod = paths
        .parse()
        .map_err(|e| input_error(format!("--paths: {e}")))?;
    let resolve: Resolution = resolve
        .parse()
        .map_err(|e| input_error(format!("--resolve: {e}")))?;
    let connectivity: Connectivity = connectivity
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
    Ok(CrewChoices {
        config: CrewConfig {
            assign,
            paths,
            resolve,
            prm,
        },
        connectivity,
    })
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
    /// Each robot's fewest steps to its assigned goal; `None` when unreachable.
    pub shortest: Vec<Option<u64>>,
}

impl CrewResult {
    /// Σ of the robots' shortest step distances (a lower bound on the sum of costs); `None`
    /// when some goal is unreachable.
    pub fn lower_bound(&self) -> Option<u64> {
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
    let shortest = inst
        .robots
        .iter()
        .zip(&outcome.goals)
        .map(|(&s, &g)| {
            let d = step_distances(&inst.grid, inst.connectivity, s)[g.0 as usize];
            (d != UNREACHABLE).then_some(u64::from(d))
        })
        .collect();
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
        "status": o.status,
        "reason": o.reason,
        "agents": agents,
        "sum_of_costs": r.metrics.map(|m| m.sum_of_costs),
        "makespan": r.metrics.map(|m| m.makespan),
        "lower_bound_sum_of_costs": r.lower_bound(),
        "stats": {
            "elapsed_ms": o.stats.elapsed.as_secs_f64() * 1e3,
            "expanded": o.stats.expanded,
            "waits": o.stats.waits,
        },
    })
}

/// A readable summary, with one row per robot for up to 60 robots.
pub fn crew_table(inst: &Instance, source: &str, config: &CrewConfig, r: &CrewResult) -> String {
    let g = &inst.grid;
    let o = &r.outcome;
    let mut s = format!(
        "{source}: {} robots on {}×{} ({} free cells), {}-connected; assign {:?}, paths {:?}, resolve {:?}\n",
        inst.robot_count(),
        g.width(),
        g.height(),
        g.free_count(),
        inst.connectivity.degree(),
        config.assign,
        config.paths,
        config.resolve
    )
    .to_lowercase();
    if let Some(paths) = &o.paths {
        if inst.robot_count() <= 60 {
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
            "sum of costs: {} (lower bound {}), makespan: {}\n",
            m.sum_of_costs,
            r.lower_bound().map_or("-".into(), |b| b.to_string()),
            m.makespan
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
