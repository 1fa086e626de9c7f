//! `mason bench`: the thesis tables and the planning-speed benchmark.

use crate::demo::{format_ms, row, search_limit, COMPARED};
use crate::fail::{input_error, write_file, CliResult};
use crate::plan::solve;
use mason_order::{BuildProblem, CostModel, PlannerSpec};
use mason_wall::generate::large_layer_text;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use std::process::{Command, Stdio};
use std::time::Instant;

/// `bench thesis`: the thesis's Tables 3.3–3.5 setting on the built-in walls.
pub fn thesis(brute_limit: f64) -> CliResult<String> {
    let model = CostModel::default();
    let mut text = String::from(
        "Thesis Tables 3.3–3.5 setting: brute (until it finishes or the limit), greedy, improved\n\
         greedy, exact. `speed` is brute's time over the planner's. The thesis's published\n\
         figures are not on file in this repository (the thesis text was not available), so\n\
         the `thesis` column says so instead of inventing numbers.\n",
    );
    for (table, name) in ["3.3", "3.4", "3.5", "extra"].iter().zip([
        "thesis-2x5",
        "levels5-width5",
        "levels5-width10",
        "mbzirc",
    ]) {
        let wall = mason_wall::builtin(name).expect("built-in").wall();
        let problem = BuildProblem::new(&wall, model.clone()).expect("valid model");
        let exact = solve(&problem, PlannerSpec::Exact, None)?;
        let optimum = exact.evaluation.as_ref().map_or(f64::NAN, |e| e.total_cost);
        text.push_str(&format!(
            "\nTable {table}: {name} ({} bricks, {} levels)\n  {:<14} {:<9} {:>12} {:>12} {:>10} {:>10}  thesis\n",
            wall.len(),
            wall.levels(),
            "planner", "status", "time", "total (s)", "gap", "speed"
        ));
        let mut brute_ms = None;
        for spec in COMPARED {
            let c = if spec == PlannerSpec::Exact {
                exact.clone()
            } else {
                solve(&problem, spec, search_limit(spec, brute_limit))?
            };
            let ms = c.outcome.stats.elapsed.as_secs_f64() * 1e3;
            if spec == PlannerSpec::Brute {
                brute_ms = Some(ms);
            }
            let speed = brute_ms.map_or("-".to_string(), |b| format!("{:.0}×", b / ms.max(1e-6)));
            text.push_str(&row(
                &spec.to_string(),
                &c,
                optimum,
                &format!(" {speed:>10}  not on file"),
            ));
        }
    }
    Ok(text)
}

/// `bench planning`: wall-clock time of whole `mason plan --planner exact` processes.
pub fn planning(runs: usize) -> CliResult<String> {
    let exe =
        std::env::current_exe().map_err(|e| input_error(format!("cannot find mason: {e}")))?;
    let dir = std::env::temp_dir().join(format!("mason-bench-{}", std::process::id()));
    let mut text = format!(
        "Whole-process time of `mason plan FILE --planner exact --json` ({runs} runs each; \
         build with --release for meaningful figures)\n  {:<12} {:>8} {:>12} {:>12} {:>12}\n",
        "wall", "bricks", "min", "median", "max"
    );
    for (bricks, levels) in [(50usize, 5usize), (5000, 50)] {
        let mut rng = ChaCha8Rng::seed_from_u64(bricks as u64);
        let design = large_layer_text(&mut rng, bricks, levels);
        let path = dir.join(format!("wall-{bricks}.txt"));
        write_file(&path, design.as_bytes())?;
        let wall = mason_wall::parse_layer_text(&design, "bench")
            .map_err(|e| input_error(e.to_string()))?;
        let mut times = Vec::with_capacity(runs);
        for _ in 0..runs.max(1) {
            let start = Instant::now();
            let status = Command::new(&exe)
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
