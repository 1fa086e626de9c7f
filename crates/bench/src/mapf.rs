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
    if long {
        text.push_str(&against_lacam3(exe, &dir, progress)?);
    }
    Ok(text)
}

/// lacam3's figures, measured once with `scripts/mapf-vs-lacam3.sh` (see the file's header):
/// the maps of `shared/benchmarks/mapf` and their published random-1 scenarios.
const LACAM3: &str = include_str!("../data/lacam3-mapf.tsv");

/// lacam3's figures on the other 24 maps of the MovingAI benchmark, measured once with
/// `scripts/mapf-vs-lacam3.sh … --wide` (see the file's header); a map without its published
/// scenario in `--data` runs on the one `mason generate scen` makes (seed 1).
const LACAM3_WIDE: &str = include_str!("../data/lacam3-mapf-wide.tsv");

/// One measured lacam3 run: map, agents, limit (s), seed, then its sum of costs (`None`: no
/// plan), the lower bound and the time to its first plan (ms).
type Anchor = (String, usize, f64, u64, Option<u64>, u64, Option<u64>);

/// The rows of a lacam3 results file (tab-separated, `#` comments, one header line).
fn anchors(text: &str, file: &str) -> BenchResult<Vec<Anchor>> {
    let mut rows = Vec::new();
    for (k, line) in text.lines().enumerate() {
        if line.starts_with('#') || line.starts_with("map\t") || line.trim().is_empty() {
            continue;
        }
        let f: Vec<&str> = line.split('\t').collect();
        let bad = || {
            input_error(format!("{file}:{}: expected 9 tab-separated fields `map agents limit_s seed solved soc soc_lb makespan first_ms`", k + 1))
        };
        if f.len() != 9 {
            return Err(bad());
        }
        let opt = |s: &str| s.parse::<u64>().ok();
        rows.push((
            f[0].to_string(),
            f[1].parse().map_err(|_| bad())?,
            f[2].parse().map_err(|_| bad())?,
            f[3].parse().map_err(|_| bad())?,
            (f[4] == "1").then(|| opt(f[5])).flatten(),
            f[6].parse().map_err(|_| bad())?,
            (f[4] == "1").then(|| opt(f[8])).flatten(),
        ));
    }
    Ok(rows)
}

/// The scenario file of a point: DATA's published `NAME-random-1.scen` when it has one, else
/// (wide points only) the scenario `mason generate scen --map MAP --agents MAX --seed 1` writes,
/// made once in `tmp`. `None` when neither can be had.
fn scenario_for(
    dir: &Path,
    map_name: &str,
    generate: Option<usize>,
    tmp: &Path,
) -> BenchResult<Option<std::path::PathBuf>> {
    let published = dir.join("scen").join(format!("{map_name}-random-1.scen"));
    let Some(max_agents) = generate.filter(|_| !published.is_file()) else {
        return Ok(published.is_file().then_some(published));
    };
    let made = tmp.join(format!("{map_name}-mason-1.scen"));
    if made.is_file() {
        return Ok(Some(made));
    }
    let map = dir.join("maps").join(format!("{map_name}.map"));
    let Ok(grid) = mason_io::load_grid(&map.to_string_lossy()) else {
        return Ok(None);
    };
    let Some(pairs) = mason_crew::generate::random_scenario(&grid, max_agents, 1) else {
        return Ok(None);
    };
    let text = mason_crew::movingai::scen_text(&format!("{map_name}.map"), &grid, &pairs);
    std::fs::create_dir_all(tmp)
        .and_then(|()| std::fs::write(&made, text))
        .map_err(|e| input_error(format!("{}: {e}", made.display())))?;
    Ok(Some(made))
}

/// Mason at every point of both lacam3 results files, beside lacam3's figures.
fn against_lacam3(exe: &Path, dir: &Path, progress: &mut dyn FnMut(&str)) -> BenchResult<String> {
    let tmp = std::env::temp_dir().join(format!("mason-bench-scen-{}", std::process::id()));
    let mut text = String::new();
    for (file, rows, wide) in [
        ("lacam3-mapf.tsv", LACAM3, false),
        ("lacam3-mapf-wide.tsv", LACAM3_WIDE, true),
    ] {
        text.push_str(&against_file(exe, dir, (file, rows, wide), &tmp, progress)?);
    }
    let _ = std::fs::remove_dir_all(&tmp);
    Ok(text)
}

/// Mason at every point of one lacam3 results file.
fn against_file(
    exe: &Path,
    dir: &Path,
    (file, rows, wide): (&str, &str, bool),
    tmp: &Path,
    progress: &mut dyn FnMut(&str),
) -> BenchResult<String> {
    let mut text = format!(
        "\nAgainst lacam3 (Kei18/lacam3, its figures measured once and read from \
         crates/bench/data/{file}; Mason measured now, so the two saw different loads):\n"
    );
    text.push_str(&format!(
        "{:<24} {:>6} {:>6} {:>4} {:>10} {:>10} {:>9} {:>9} {:>8}\n",
        "map",
        "agents",
        "limit",
        "seed",
        "lacam3 SOC",
        "Mason SOC",
        "Mason/l3",
        "l3 first",
        "M first"
    ));
    let (mut points, mut at_or_below) = (0, 0);
    let anchors = anchors(rows, file)?;
    for (map_name, agents, limit, seed, l_soc, _lb, l_first) in anchors.iter().cloned() {
        let map = dir.join("maps").join(format!("{map_name}.map"));
        let most = anchors
            .iter()
            .filter(|a| a.0 == map_name)
            .map(|a| a.1)
            .max();
        let scen = scenario_for(dir, &map_name, most.filter(|_| wide), tmp)?;
        let head = format!(
            "{map_name:<24} {agents:>6} {:>6} {seed:>4}",
            format!("{limit}s")
        );
        let (true, Some(scen)) = (map.is_file(), scen) else {
            text.push_str(&format!("{head} data missing; skipped\n"));
            continue;
        };
        progress(&format!(
            "bench mapf: {map_name} {agents} agents against lacam3"
        ));
        let c = Case {
            map: "",
            agents,
            method: "lacam",
            limit,
        };
        let v = run_child(exe, (&map, &scen), &c, seed)?.ok();
        let m_soc = v.as_ref().and_then(|v| v["sum_of_costs"].as_u64());
        let m_first = v
            .as_ref()
            .and_then(|v| v["stats"]["first_solution_ms"].as_f64());
        let show = |x: Option<u64>| x.map_or("no plan".to_string(), |s| s.to_string());
        let ratio = match (m_soc, l_soc) {
            (Some(m), Some(l)) => {
                points += 1;
                if m <= l {
                    at_or_below += 1;
                }
                format!("{:.3}", m as f64 / l as f64)
            }
            (Some(_), None) => {
                points += 1;
                at_or_below += 1;
                "l3 none".into()
            }
            _ => "-".into(),
        };
        text.push_str(&format!(
            "{head} {:>10} {:>10} {:>9} {:>9} {:>8}\n",
            show(l_soc),
            show(m_soc),
            ratio,
            l_first.map_or("-".into(), |f| format!("{:.3}", f as f64 / 1e3)),
            m_first.map_or("-".into(), |f| format!("{:.3}", f / 1e3)),
        ));
    }
    text.push_str(&format!(
        "Mason at or below lacam3 at {at_or_below} of {points} points (a point where only Mason has a plan counts as below).\n"
    ));
    Ok(text)
}

/// Runs one child `mason crew … --json` (seed `seed`); its JSON answer, or the last line it
/// wrote to stderr.
fn run_child(
    exe: &Path,
    (map, scen): (&Path, &Path),
    c: &Case,
    seed: u64,
) -> BenchResult<Result<Value, String>> {
    let mut cmd = Command::new(exe);
    cmd.arg("crew")
        .arg(map)
        .arg("--scen")
        .arg(scen)
        .args(["--agents", &c.agents.to_string()])
        .args(["--connectivity", "4"])
        .args(["--time-limit", &c.limit.to_string()])
        .args(["--seed", &seed.to_string()])
        .arg("--json");
    if c.method == "joint" {
        cmd.args(["--assign", "joint"]);
    } else {
        cmd.args(["--resolve", "lacam"]);
    }
    let out = cmd
        .output()
        .map_err(|e| input_error(format!("running {}: {e}", exe.display())))?;
    Ok(serde_json::from_slice(&out.stdout).map_err(|_| {
        let err = String::from_utf8_lossy(&out.stderr);
        err.lines().last().unwrap_or("no output").to_string()
    }))
}

fn run_case(exe: &Path, map: &Path, scen: &Path, c: &Case) -> BenchResult<String> {
    let head = format!(
        "{:<24} {:>6} {:<6} {:>6}",
        c.map,
        c.agents,
        c.method,
        format!("{}s", c.limit)
    );
    let v = match run_child(exe, (map, scen), c, 0)? {
        Ok(v) => v,
        Err(e) => return Ok(format!("{head} error: {e}\n")),
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_committed_lacam3_figures_parse() {
        for (text, file) in [(LACAM3, "n"), (LACAM3_WIDE, "w")] {
            let rows = anchors(text, file).unwrap();
            assert!(rows.len() >= 20);
            assert!(rows.iter().all(|r| r.5 > 0 && r.4.is_none_or(|s| s >= r.5)));
        }
    }

    #[test]
    fn a_malformed_lacam3_line_is_one_clear_error() {
        let e = anchors("map\tagents\nroom\t3\t1\n", "lacam3-mapf.tsv")
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("lacam3-mapf.tsv:2") && e.contains("9 tab-separated"),
            "{e}"
        );
        assert!(anchors("room\tx\t1\t0\t1\t5\t3\t4\t10\n", "f").is_err());
    }

    #[test]
    fn a_wide_point_without_its_published_scenario_gets_a_generated_one() {
        let dir = std::env::temp_dir().join(format!("mason-bench-wide-{}", std::process::id()));
        let tmp = dir.join("tmp");
        std::fs::create_dir_all(dir.join("maps")).unwrap();
        std::fs::write(
            dir.join("maps/x.map"),
            "type octile\nheight 2\nwidth 4\nmap\n....\n.@..\n",
        )
        .unwrap();
        assert_eq!(scenario_for(&dir, "x", None, &tmp).unwrap(), None);
        assert_eq!(scenario_for(&dir, "x", Some(99), &tmp).unwrap(), None);
        let made = scenario_for(&dir, "x", Some(5), &tmp).unwrap().unwrap();
        let text = std::fs::read_to_string(&made).unwrap();
        assert_eq!(text.lines().count(), 6, "{text}");
        assert!(text.lines().nth(1).unwrap().starts_with("0\tx.map\t4\t2\t"));
        std::fs::create_dir_all(dir.join("scen")).unwrap();
        std::fs::write(dir.join("scen/x-random-1.scen"), "version 1\n").unwrap();
        let published = scenario_for(&dir, "x", Some(5), &tmp).unwrap().unwrap();
        assert!(published.ends_with("scen/x-random-1.scen"));
        let _ = std::fs::remove_dir_all(&dir);
    }
}
