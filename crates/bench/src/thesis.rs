//! The thesis's Tables 3.3–3.5 and the planning-speed benchmark (`mason bench thesis`,
//! `mason bench planning`).

use crate::support::{input_error, search_limit, solve, BenchResult};
use mason_order::{BuildProblem, CostModel, PlannerSpec};
use mason_report::text::format_ms;
use mason_wall::generate::large_layer_text;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use std::process::{Command, Stdio};
use std::time::Instant;

/// One row of a thesis table: the planner, and its published time (s), total cost and
/// relative speed (brute force's time over the planner's; Table 3.3 only).
type Published = (PlannerSpec, f64, f64, Option<f64>);

const fn improved(n: u32, k: u32) -> PlannerSpec {
    PlannerSpec::Improved { n, k }
}

/// The thesis's Tables 3.3–3.5 (Petrić 2019), as published (`../shared/benchmarks/thesis`).
/// Brute force did not finish within 10 minutes on Tables 3.4 and 3.5.
const THESIS_TABLES: [(&str, &str, &[Published]); 3] = [
    (
        "3.3",
        "thesis-2x5",
        &[
            (PlannerSpec::Brute, 1.5914, 336.22, Some(1.0)),
            (PlannerSpec::Greedy, 0.0005, 341.16, Some(3183.0)),
            (improved(1, 2), 0.0021, 340.03, Some(758.0)),
            (improved(1, 3), 0.0039, 339.55, Some(408.0)),
            (improved(1, 4), 0.0039, 338.87, Some(408.0)),
            (improved(1, 5), 0.0040, 338.87, Some(398.0)),
        ],
    ),
    (
        "3.4",
        "levels5-width5",
        &[
            (PlannerSpec::Greedy, 0.0020, 1546.99, None),
            (improved(4, 2), 0.0028, 1545.32, None),
            (improved(4, 3), 0.0033, 1543.76, None),
            (improved(3, 3), 0.1902, 1536.75, None),
            (improved(3, 4), 0.2876, 1533.41, None),
            (improved(2, 2), 1.7343, 1533.27, None),
            (improved(2, 3), 44.1548, 1522.89, None),
            (improved(2, 4), 108.5388, 1522.89, None),
        ],
    ),
    (
        "3.5",
        "levels5-width10",
        &[
            (PlannerSpec::Greedy, 0.0100, 3061.80, None),
            (improved(4, 2), 0.1622, 3059.22, None),
            (improved(4, 3), 0.6459, 3054.39, None),
            (improved(4, 5), 1.7765, 3048.39, None),
            (improved(4, 10), 1.8965, 3048.39, None),
            (improved(3, 2), 199.6822, 3036.63, None),
            (improved(3, 3), 220.7225, 3033.84, None),
        ],
    ),
];

/// `bench thesis`: the thesis's Tables 3.3–3.5 beside ours, planner by planner, on the
/// built-in walls of the same sizes, with brute force and `exact` added where the thesis has
/// none. The thesis's absolute costs come from times and colours it does not publish (its own
/// Table 3.2 gives more than 80 s for the cheapest brick), so compare the gaps to the best
/// cost in each table, the relative speeds, and which planners finish.
pub fn thesis(limit: f64) -> BenchResult<String> {
    let model = CostModel::default();
    let mut text = format!(
        "Thesis Tables 3.3–3.5 (Petrić 2019) beside Mason on walls of the same sizes, thesis cost \
         model (DESIGN §4).\n\
         Tree searches (brute, improved) stop at {limit} s and return their best order so far.\n\
         `gap` is the cost over the best cost among the thesis's planners in the same table (ours \
         among ours, theirs among theirs); `speed` is brute force's time over the planner's.\n\
         The thesis's absolute costs cannot be reproduced (see ../shared/benchmarks/thesis); its \
         times are Python on a 2019 PC.\n"
    );
    for (table, name, published) in THESIS_TABLES {
        let wall = mason_wall::builtin(name).expect("built-in").wall();
        let problem = BuildProblem::new(&wall, model.clone()).expect("valid model");
        let mut specs: Vec<PlannerSpec> = published.iter().map(|p| p.0).collect();
        if !specs.contains(&PlannerSpec::Brute) {
            specs.insert(0, PlannerSpec::Brute);
        }
        let mut ours = Vec::new();
        for &spec in &specs {
            ours.push(solve(&problem, spec, search_limit(spec, limit))?);
        }
        let exact = solve(&problem, PlannerSpec::Exact, None)?;
        let cost = |c: &mason_order::CheckedPlan| c.evaluation.as_ref().map(|e| e.total_cost);
        let compared: Vec<f64> = specs
            .iter()
            .zip(&ours)
            .filter(|(s, _)| published.iter().any(|p| p.0 == **s))
            .filter_map(|(_, c)| cost(c))
            .collect();
        let our_best = compared.iter().copied().fold(f64::INFINITY, f64::min);
        let their_best = published.iter().map(|p| p.2).fold(f64::INFINITY, f64::min);
        // Relative speeds only where brute force finished.
        let brute_s = (ours[0].outcome.status == mason_order::Status::Optimal)
            .then(|| ours[0].outcome.stats.elapsed.as_secs_f64());
        text.push_str(&format!(
            "\nTable {table}: {name} ({} bricks, {} levels)\n  {:<16} {:<9} {:>10} {:>10} {:>8} {:>9}   {:>10} {:>10} {:>8} {:>7}\n",
            wall.len(),
            wall.levels(),
            "planner",
            "status",
            "time",
            "cost",
            "gap",
            "speed",
            "thesis: t",
            "cost",
            "gap",
            "speed"
        ));
        for (spec, c) in specs.iter().zip(&ours) {
            let s = c.outcome.stats.elapsed.as_secs_f64();
            let theirs = published.iter().find(|p| p.0 == *spec);
            let thesis_cols = match theirs {
                Some(&(_, t, total, speed)) => format!(
                    "{:>10} {:>10.2} {:>8} {:>7}",
                    format!("{t:.4} s"),
                    total,
                    percent(total / their_best - 1.0),
                    speed.map_or("-".into(), |v| format!("×{v:.0}"))
                ),
                None => format!("{:>10} {:>10} {:>8} {:>7}", "> 600 s", "-", "-", "-"),
            };
            text.push_str(&format!(
                "  {:<16} {:<9} {:>10} {:>10} {:>8} {:>9}   {thesis_cols}\n",
                spec.to_string(),
                c.outcome.status.to_string(),
                format_ms(s * 1e3),
                cost(c).map_or("-".into(), |v| format!("{v:.2}")),
                cost(c).map_or("-".into(), |v| percent(v / our_best - 1.0)),
                brute_s.map_or("-".into(), |b| format!("×{:.0}", b / s.max(1e-9))),
            ));
        }
        let optimum = cost(&exact).unwrap_or(f64::NAN);
        text.push_str(&format!(
            "  {:<16} {:<9} {:>10} {:>10} {:>8}   (the optimum; best thesis planner above it: {})\n",
            "exact",
            exact.outcome.status.to_string(),
            format_ms(exact.outcome.stats.elapsed.as_secs_f64() * 1e3),
            format!("{optimum:.2}"),
            percent(optimum / our_best - 1.0),
            percent(our_best / optimum - 1.0),
        ));
    }
    Ok(text)
}

fn percent(share: f64) -> String {
    format!("{:+.2} %", share * 100.0)
}

/// `bench planning`: wall-clock time of whole `mason plan --planner exact` processes.
pub fn planning(exe: &std::path::Path, runs: usize) -> BenchResult<String> {
    let dir = std::env::temp_dir().join(format!("mason-bench-{}", std::process::id()));
    std::fs::create_dir_all(&dir).map_err(|e| input_error(format!("{}: {e}", dir.display())))?;
    let mut text = format!(
        "Whole-process time of `mason plan FILE --planner exact --json` ({runs} runs each; \
         build with --release for meaningful figures)\n  {:<12} {:>8} {:>12} {:>12} {:>12}\n",
        "wall", "bricks", "min", "median", "max"
    );
    for (bricks, levels) in [(50usize, 5usize), (5000, 50)] {
        let mut rng = ChaCha8Rng::seed_from_u64(bricks as u64);
        let design = large_layer_text(&mut rng, bricks, levels);
        let path = dir.join(format!("wall-{bricks}.txt"));
        mason_io::write_file(&path, design.as_bytes())?;
        let wall = mason_wall::parse_layer_text(&design, "bench")
            .map_err(|e| input_error(e.to_string()))?;
        let mut times = Vec::with_capacity(runs);
        for _ in 0..runs.max(1) {
            let start = Instant::now();
            let status = Command::new(exe)
                .args([
                    "plan",
                    &path.to_string_lossy(),
                    "--planner",
                    "exact",
                    "--json",
                ])
                .stdout(Stdio::null())
                .status()
                .map_err(|e| input_error(format!("cannot run mason: {e}")))?;
            times.push(start.elapsed().as_secs_f64() * 1e3);
            if !status.success() {
                return Err(input_error(format!(
                    "mason plan failed on {}",
                    path.display()
                )));
            }
        }
        times.sort_by(f64::total_cmp);
        text.push_str(&format!(
            "  {:<12} {:>8} {:>12} {:>12} {:>12}\n",
            format!("{bricks}-brick"),
            wall.len(),
            format_ms(times[0]),
            format_ms(times[times.len() / 2]),
            format_ms(times[times.len() - 1])
        ));
    }
    let _ = std::fs::remove_dir_all(&dir);
    Ok(text)
}
