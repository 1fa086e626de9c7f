//! `mason bench paper`: the crew paper's Table 2 setting and the MovingAI warehouse.

use crate::support::{benchmarks_dir, input_error, BenchError, BenchResult};
use mason_crew::generate::{random_tasks, warehouse};
use mason_crew::movingai::{parse_map, parse_scen};
use mason_crew::{
    AssignMethod, Connectivity, CrewConfig, Instance, PathMethod, PrmConfig, Resolution, Status,
};
use std::path::PathBuf;

/// The paper's Table 2 robot counts (one row each).
pub const PAPER_ROBOTS: [usize; 7] = [3, 5, 10, 15, 25, 30, 50];

/// The paper's Table 2: path-planning time (s) on its 450×450 warehouse, Python 3.6 on a
/// Core i5 at 2.3 GHz, 3-minute bound: (robots, A*, PRM); A* did not finish above 30.
const PAPER_TABLE_2: [(usize, Option<f64>, f64); 7] = [
    (3, Some(9.549), 5.424),
    (5, Some(16.814), 7.982),
    (10, Some(35.458), 15.136),
    (15, Some(65.271), 20.568),
    (25, Some(135.569), 37.435),
    (30, Some(178.326), 44.283),
    (50, None, 75.209),
];

fn paper_figure(robots: usize, method: &str) -> String {
    let row = PAPER_TABLE_2.iter().find(|r| r.0 == robots);
    match (row, method) {
        (Some(r), "prm") => format!("{:.3} s", r.2),
        (Some(&(_, Some(t), _)), "astar") => format!("{t:.3} s"),
        (Some(_), "astar") => "> 180 s".into(),
        _ => "-".into(),
    }
}

/// The paper's Table 1 example through Mason's Hungarian assignment.
fn paper_table_1() -> String {
    let cost: Vec<Vec<f64>> = mason_crew::hungarian::PAPER_TABLE_1
        .iter()
        .map(|r| r.to_vec())
        .collect();
    let assignment = mason_crew::hungarian::hungarian(&cost);
    let total: f64 = assignment
        .iter()
        .enumerate()
        .map(|(r, &g)| cost[r][g])
        .sum();
    let pairs: Vec<String> = assignment
        .iter()
        .enumerate()
        .map(|(r, g)| format!("R{r}→G{g}"))
        .collect();
    format!(
        "Table 1 (the paper's worked 3-robot example): Mason assigns {}, cost {total} \
         (paper: R0→G1, R1→G0, R2→G2, cost 19).\n\n",
        pairs.join(", ")
    )
}

/// Roadmap size for the paper's setting: enough to connect most of a 450×450 warehouse.
const PRM_SAMPLES: usize = 8000;

struct Method {
    name: &'static str,
    paper_column: &'static str,
    config: CrewConfig,
}

fn methods(seed: u64) -> Vec<Method> {
    let prm = PrmConfig {
        samples: PRM_SAMPLES,
        neighbours: 10,
        seed,
    };
    let base = CrewConfig {
        assign: AssignMethod::Hungarian,
        paths: PathMethod::Astar,
        resolve: Resolution::Paper,
        prm,
        ..CrewConfig::default()
    };
    vec![
        Method {
            name: "prm + paper waits",
            paper_column: "prm",
            config: CrewConfig {
                paths: PathMethod::Prm,
                ..base
            },
        },
        Method {
            name: "astar + paper waits",
            paper_column: "astar",
            config: base,
        },
        Method {
            name: "astar + st (ours)",
            paper_column: "",
            config: CrewConfig {
                resolve: Resolution::St,
                ..base
            },
        },
    ]
}

#[derive(Default)]
struct Tally {
    ok: usize,
    runs: usize,
    times_ms: Vec<f64>,
    soc: u64,
    lower: u64,
}

impl Tally {
    fn cell(&mut self) -> String {
        self.times_ms.sort_by(f64::total_cmp);
        let median = self
            .times_ms
            .get(self.times_ms.len() / 2)
            .copied()
            .unwrap_or(f64::NAN);
        let ratio = if self.ok > 0 && self.lower > 0 {
            format!("{:.3}", self.soc as f64 / self.lower as f64)
        } else {
            "-".into()
        };
        format!(
            "{:>3}/{:<3} {:>9.1} ms {:>6}",
            self.ok, self.runs, median, ratio
        )
    }
}

/// Runs the suite. `runs` random instances per robot count.
pub fn paper(runs: usize, progress: &(dyn Fn() + Sync)) -> BenchResult<String> {
    if runs == 0 {
        return Err(input_error("--runs must be at least 1"));
    }
    let grid = warehouse(450, 450, 0.005, 1);
    let mut text = format!(
        "Crew paper Table 2 setting: a 450×450 warehouse-like grid ({} free cells: 10×2 shelves, \
         3-cell aisles, 0.5% clutter), 8-connected, Hungarian assignment (the paper's objective; its \
         n! enumeration stops at 10 robots); PRM with {PRM_SAMPLES} samples and 10 neighbours. {runs} random instances per row. Each cell: solved/runs, \
         median solve time, mean sum of costs over Σ shortest paths. Every plan passed crew::validate.\n\n",
        grid.free_count()
    );
    text.push_str(&paper_table_1());
    text.push_str("Table 2 (time per instance; the paper's times are one run each, its map is not published):\n");
    let all = methods(0);
    text.push_str(&format!("{:>6}", "robots"));
    for m in &all {
        text.push_str(&format!("  {:<27}", m.name));
    }
    text.push_str("  paper: PRM | A*\n");
    for &n in &PAPER_ROBOTS {
        let mut tallies: Vec<Tally> = all.iter().map(|_| Tally::default()).collect();
        for run in 0..runs {
            let seed = (n * 1000 + run) as u64;
            let (robots, goals) = random_tasks(&grid, n, seed);
            let inst = Instance::new(
                grid.clone(),
                Connectivity::Eight,
                robots,
                goals,
                None,
                "bench",
            )
            .expect("generated instance is valid");
            for (m, tally) in methods(seed).iter().zip(&mut tallies) {
                let r = crew_solve(&inst, &m.config)?;
                tally.runs += 1;
                tally
                    .times_ms
                    .push(r.outcome.stats.elapsed.as_secs_f64() * 1e3);
                if let (Some(metrics), Some(lb)) = (r.metrics, r.lower_bound(&inst)) {
                    tally.ok += 1;
                    tally.soc += metrics.sum_of_costs;
                    tally.lower += lb;
                }
            }
            progress();
        }
        text.push_str(&format!("{n:>6}"));
        for t in &mut tallies {
            text.push_str(&format!("  {:<27}", t.cell()));
        }
        text.push_str(&format!(
            "  {} | {}\n",
            paper_figure(n, all[0].paper_column),
            paper_figure(n, all[1].paper_column)
        ));
    }
    text.push('\n');
    text.push_str(&movingai_warehouse()?);
    Ok(text)
}

fn movingai_warehouse() -> BenchResult<String> {
    let name = "warehouse-20-40-10-2-2";
    let Some(dir) = benchmarks_dir() else {
        return Ok(format!(
            "MovingAI {name}: benchmark data not found (looked in $MASON_BENCHMARKS, \
             ../shared/benchmarks, ./benchmarks); skipped.\n"
        ));
    };
    let map_path = dir.join("maps").join(format!("{name}.map"));
    let scen_path = dir.join("scen").join(format!("{name}-random-1.scen"));
    let read = |p: &PathBuf| mason_io::read_input_text(p, mason_io::MAX_INPUT_BYTES);
    let map_name = map_path.display().to_string();
    let grid = parse_map(&read(&map_path)?, &map_name).map_err(|e| input_error(e.to_string()))?;
    let scen_text = read(&scen_path)?;
    let mut text = format!(
        "MovingAI {name} ({}×{}, {} free cells), scenario random-1, first N agents, given pairing \
         (labelled MAPF), 8-connected.\n{:>6}  {:<22} {:<10} {:>8} {:>10} {:>7} {:>11}\n",
        grid.width(),
        grid.height(),
        grid.free_count(),
        "agents",
        "method",
        "status",
        "SoC",
        "Σ shortest",
        "ratio",
        "time"
    );
    for n in [50usize, 100, 200] {
        let agents = parse_scen(&scen_text, &scen_path.display().to_string(), &grid, n)
            .map_err(|e| input_error(e.to_string()))?;
        let inst = Instance::new(
            grid.clone(),
            Connectivity::Eight,
            agents.iter().map(|a| a.start).collect(),
            agents.iter().map(|a| a.goal).collect(),
            Some((0..n).collect()),
            name,
        )
        .map_err(|e| input_error(e.to_string()))?;
        for (label, resolve) in [
            ("astar + paper waits", Resolution::Paper),
            ("astar + st (ours)", Resolution::St),
        ] {
            let config = CrewConfig {
                assign: AssignMethod::Given,
                paths: PathMethod::Astar,
                resolve,
                prm: PrmConfig::default(),
                ..CrewConfig::default()
            };
            let r = crew_solve(&inst, &config)?;
            let (soc, ratio) = match (r.metrics, r.lower_bound(&inst)) {
                (Some(m), Some(lb)) => (
                    m.sum_of_costs.to_string(),
                    format!("{:.3}", m.sum_of_costs as f64 / lb as f64),
                ),
                _ => ("-".into(), "-".into()),
            };
            let status = match r.outcome.status {
                Status::Optimal | Status::Feasible => "solved".to_string(),
                s => s.to_string(),
            };
            text.push_str(&format!(
                "{n:>6}  {label:<22} {status:<10} {soc:>8} {:>10} {ratio:>7} {:>8.1} ms\n",
                r.lower_bound(&inst).map_or("-".into(), |b| b.to_string()),
                r.outcome.stats.elapsed.as_secs_f64() * 1e3
            ));
        }
    }
    Ok(text)
}

/// A checked solve with the suite's 10-minute cap.
fn crew_solve(inst: &Instance, config: &CrewConfig) -> BenchResult<mason_crew::CheckedCrewPlan> {
    let limit = mason_crew::Budget::time(std::time::Duration::from_secs(600));
    mason_crew::solve_checked(inst, config, &limit).map_err(|e| match e {
        mason_crew::CheckedSolveError::Setup(e) => input_error(e.to_string()),
        e => BenchError::Invalid(e.to_string()),
    })
}
