//! `mason demo`: every built-in wall with every planner, a comparison table, and figures.

use crate::fail::{write_file, CliResult};
use crate::plan::{plan_json, solve, Checked};
use mason_order::{BuildProblem, CostModel, PlannerSpec};
use mason_wall::BUILTIN_WALLS;
use std::path::Path;

/// The planners the demo and the thesis bench compare, in table order.
pub const COMPARED: [PlannerSpec; 5] = [
    PlannerSpec::Brute,
    PlannerSpec::Greedy,
    PlannerSpec::Improved { n: 1, k: 4 },
    PlannerSpec::Improved { n: 2, k: 3 },
    PlannerSpec::Exact,
];

/// The time limit a compared planner gets: the tree searches are capped, the others not.
pub fn search_limit(spec: PlannerSpec, limit: f64) -> Option<f64> {
    matches!(spec, PlannerSpec::Brute | PlannerSpec::Improved { .. }).then_some(limit)
}

/// One row of a comparison table.
pub fn row(spec: &str, c: &Checked, optimum: f64, extra: &str) -> String {
    let o = &c.outcome;
    let (cost, gap) = match &c.evaluation {
        Some(e) => (
            format!("{:.2}", e.total_cost),
            format!("{:+.2} %", (e.total_cost / optimum - 1.0) * 100.0),
        ),
        None => ("-".into(), "-".into()),
    };
    format!(
        "  {:<14} {:<9} {:>12} {:>12} {:>10}{extra}\n",
        spec,
        o.status.to_string(),
        format_ms(o.stats.elapsed.as_secs_f64() * 1e3),
        cost,
        gap
    )
}

/// Milliseconds with sensible precision.
pub fn format_ms(ms: f64) -> String {
    if ms < 1.0 {
        format!("{ms:.3} ms")
    } else if ms < 1000.0 {
        format!("{ms:.1} ms")
    } else {
        format!("{:.2} s", ms / 1e3)
    }
}

/// Runs the demo; writes figures and plans under `out`.
pub fn run(out: &Path, brute_limit: f64) -> CliResult<String> {
    let model = CostModel::default();
    let mut text = String::from(
        "Build orders for the built-in walls (thesis cost model, DESIGN §4).\n\
         Every order below was checked by order::validate; gap is against `exact`.\n",
    );
    let mut plans = Vec::new();
    for builtin in &BUILTIN_WALLS {
        let wall = builtin.wall();
        let problem = BuildProblem::new(&wall, model.clone()).expect("default model is valid");
        let exact = solve(&problem, PlannerSpec::Exact, None)?;
        let optimum = exact.evaluation.as_ref().map_or(f64::NAN, |e| e.total_cost);
        text.push_str(&format!(
            "\n{} — {} ({} bricks)\n  {:<14} {:<9} {:>12} {:>12} {:>10}\n",
            builtin.name,
            builtin.description,
            wall.len(),
            "planner",
            "status",
            "time",
            "total (s)",
            "gap"
        ));
        for spec in COMPARED {
            let c = if spec == PlannerSpec::Exact {
                exact.clone()
            } else {
                solve(&problem, spec, search_limit(spec, brute_limit))?
            };
            text.push_str(&row(&spec.to_string(), &c, optimum, ""));
            plans.push(plan_json(&problem, &c));
        }
        let svg = mason_report::wall_svg(&wall, exact.outcome.order.as_deref());
        write_file(
            &out.join(format!("wall-{}.svg", builtin.name)),
            svg.as_bytes(),
        )?;
    }
    let json = serde_json::to_string_pretty(&plans).expect("plans serialise");
    write_file(&out.join("plans.json"), json.as_bytes())?;
    text.push_str(&format!(
        "\n(brute and improved stop after {brute_limit} s and report `timeout` with their best order.)\nwrote {}/wall-*.svg and {}/plans.json\n",
        out.display(),
        out.display()
    ));
    Ok(text)
}
