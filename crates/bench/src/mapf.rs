//! `mason bench mapf`: the MovingAI maps at rising agent counts, labelled (`--resolve lacam`)
//! and unlabelled (`--assign joint`).
//!
//! Each case runs as a child process (`mason crew … --json`), so that its peak memory is its
//! own (the child reports `VmHWM`) and a case that runs wild cannot take the suite with it. The
//! child validates its plan with `crew::validate` before it answers. The table gives success,
//! the time to the first plan and the final time, the sum of costs over the lower bound (Σ of
//! the shortest paths), the makespan and the peak memory.

use crate::support::{benchmarks_dir, input_error, BenchResult};
use serde_json::Value;
use std::path::Path;
use std::process::Command;

/// One case of the sweep.
struct Case {
    map: &'static str,
    agents: usize,
    /// `lacam` (labelled, given pairing) or `joint` (unlabelled).
    method: &'static str,
    /// Seconds for the child's `--time-limit`.
    limit: f64,
}

fn case(map: &'static str, agents: usize, method: &'static str, limit: f64) -> Case {
    Case {
        map,
        agents,
        method,
        limit,
    }
}

/// The default sweep (a few minutes) or the long one.
fn sweep(long: bool) -> Vec<Case> {
    let w = "warehouse-10-20-10-2-1";
    let mut cases = vec![
        case(w, 100, "lacam", 1.0),
        case(w, 200, "lacam", 2.0),
        case(w, 300, "lacam", 3.0),
        case(w, 500, "lacam", 10.0),
        case(w, 700, "lacam", 20.0),
        case(w, 800, "lacam", 20.0),
        case(w, 1000, "lacam", 30.0),
        case("random-32-32-10", 100, "lacam", 1.0),
        case("random-32-32-10", 461, "lacam", 1.0),
        case(w, 100, "joint", 10.0),
        case(w, 500, "joint", 10.0),
        case(w, 1000, "joint", 10.0),
    ];
    if long {
        for (map, counts) in [
            ("random-32-32-20", &[100, 200, 409][..]),
            ("empty-32-32", &[100, 300, 512][..]),
            ("maze-32-32-2", &[50, 100, 333][..]),
            ("random-64-64-10", &[200, 500, 1000][..]),
            ("room-64-64-8", &[100, 300, 1000][..]),
            ("den520d", &[200, 500, 1000][..]),
            ("Boston_0_256", &[200, 500, 1000][..]),
            ("warehouse-10-20-10-2-2", &[200, 500, 1000][..]),
            ("warehouse-20-40-10-2-1", &[200, 500, 1000][..]),
            ("warehouse-20-40-10-2-2", &[200, 500, 1000][..]),
        ] {
            for &n in counts {
                cases.push(case(map, n, "lacam", 30.0));
            }
            cases.push(case(map, counts[counts.len() - 1], "joint", 30.0));
        }
    }
    cases
}

/// Runs the sweep on the data in `data` (default: the shared benchmarks) and returns the table.
pub fn mapf(
    exe: &Path,
    data: Option<&Path>,
    long: bool,
    progress: &mut dyn FnMut(&str),
) -> BenchResult<String> {
    let dir = match data {
        Some(d) => {
            let d = d.to_path_buf();
            if !d.join("maps").is_dir() {
                return Err(input_error(format!(
                    "{}: not a MovingAI benchmark directory (no maps/ inside)",
                    d.display()
                )));
            }
            d
        }
        None => benchmarks_dir().ok_or_else(|| {
            input_error(
                "MAPF benchmark data not found (looked in $MASON_BENCHMARKS/mapf, \
                 ../shared/benchmarks/mapf, ./benchmarks/mapf); give --data DIR",
            )
        })?,
    };
    let mut text = format!(
        "MovingAI MAPF benchmarks from {}: scenario random-1, first N agents, 4-connected.\n\
         lacam: labelled (the scenario's pairing), LaCAM first plan then refinement until the \
         limit; joint: unlabelled (the scenario's goals as a set), TSWAP.\n\
         Each case is one child process (`mason crew … --json`) that validates its plan; peak \
         memory is the child's VmHWM.\n\n",
        dir.display()
    );
    text.push_str(&format!(
        "{:<24} {:>6} {:<6} {:>6} {:<9} {:>10} {:>10} {:>9} {:>9} {:>8} {:>8}\n",
        "map",
        "agents",
        "method",
        "limit",
        "status",
        "first (s)",
        "final (s)",
        "SOC",
        "SOC/LB",
        "makespan",
        "peak MB"
    ));
    for c in sweep(long) {
        let map = dir.join("maps").join(format!("{}.map", c.map));
        let scen = dir.join("scen").join(format!("{}-random-1.scen", c.map));
        if !map.is_file() || !scen.is_file() {
            text.push_str(&format!(
                "{:<24} {:>6} data missing; skipped\n",
                c.map, c.agents
            ));
            continue;
        }
        progress(&format!(
            "bench mapf: {} {} agents, {}",
            c.map, c.agents, c.method
        ));
        let row = run_case(exe, &map, &scen, &c)?;
        text.push_str(&row);
    }
    text.push_str(
        "\nSOC/LB: sum of costs over Σ of the agents' shortest paths, +%. first: time to the \
         first plan; final: the whole solve (refinement runs until the limit or 1000 rounds \
         without improvement). Command: mason bench mapf [--data DIR] [--long].\n",
    );
    Ok(text)
}

fn run_case(exe: &Path, map: &Path, scen: &Path, c: &Case) -> BenchResult<String> {
    let mut cmd = Command::new(exe);
    cmd.arg("crew")
        .arg(map)
        .arg("--scen")
        .arg(scen)
        .args(["--agents", &c.agents.to_string()])
        .args(["--connectivity", "4"])
        .args(["--time-limit", &c.limit.to_string()])
        .arg("--json");
    if c.method == "joint" {
        cmd.args(["--assign", "joint"]);
    } else {
        cmd.args(["--resolve", "lacam"]);
    }
    let out = cmd
        .output()
        .map_err(|e| input_error(format!("running {}: {e}", exe.display())))?;
    let head = format!(
        "{:<24} {:>6} {:<6} {:>6}",
        c.map,
        c.agents,
        c.method,
        format!("{}s", c.limit)
    );
    let v: Value = match serde_json::from_slice(&out.stdout) {
        Ok(v) => v,
        Err(_) => {
            let err = String::from_utf8_lossy(&out.stderr);
            return Ok(format!(
                "{head} error: {}\n",
                err.lines().last().unwrap_or("no output")
            ));
        }
    };
    let num = |p: &[&str]| -> Option<f64> {
        let mut x = &v;
        for k in p {
            x = x.get(k)?;
        }
        x.as_f64()
    };
    let status = v["status"].as_str().unwrap_or("?").to_string();
    let secs = |ms: Option<f64>| ms.map_or("-".to_string(), |m| format!("{:.3}", m / 1e3));
    let soc = num(&["sum_of_costs"]);
    let lb = num(&["lower_bound_sum_of_costs"]);
    let ratio = match (soc, lb) {
        (Some(s), Some(l)) if l > 0.0 => format!("+{:.1} %", (s / l - 1.0) * 100.0),
        _ => "-".into(),
    };
    Ok(format!(
        "{head} {:<9} {:>10} {:>10} {:>9} {:>9} {:>8} {:>8}\n",
        status,
        secs(num(&["stats", "first_solution_ms"])),
        secs(num(&["stats", "elapsed_ms"])),
        soc.map_or("-".into(), |s| format!("{s:.0}")),
        ratio,
        num(&["makespan"]).map_or("-".into(), |m| format!("{m:.0}")),
        num(&["stats", "peak_memory_mb"]).map_or("-".into(), |m| format!("{m:.0}")),
    ))
}
