//! `mason bench cmcp`: every CMCP benchmark wall under the `cmcp` team model with 3 UAVs, at
//! T = 2500 s and for the whole wall, beside the CMCP planner's GRASP results, which are read
//! at run time from `GRASP-RESULTS.md` in the benchmark directory (GPL data, not copied here).

use crate::support::{input_error, BenchError, BenchResult};
use mason_order::schedule::{schedule_checked, Metric, Objective, TeamModel, TeamProblem};
use mason_order::Budget;
use mason_report::text::format_ms;
use mason_wall::{parse_cmcp, CmcpSizes};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// Where the benchmark walls are looked for when `--data` is not given.
pub const DEFAULT_DIRS: [&str; 2] = [
    "../shared/benchmarks/walls-cmcp",
    "shared/benchmarks/walls-cmcp",
];

/// The budget of the CMCP experiments (s).
pub const CMCP_BUDGET: f64 = 2500.0;

/// GRASP's published figures for one wall: the cells of its row in each table.
#[derive(Default)]
struct Grasp {
    budget: Option<Vec<String>>,
    whole: Option<Vec<String>>,
}

/// Reads the two tables of GRASP-RESULTS.md, keyed by wall name.
fn read_grasp(dir: &Path) -> BTreeMap<String, Grasp> {
    let mut out: BTreeMap<String, Grasp> = BTreeMap::new();
    let Ok(text) =
        mason_io::read_input_text(&dir.join("GRASP-RESULTS.md"), mason_io::MAX_TOML_BYTES)
    else {
        return out;
    };
    let mut section = 0;
    for line in text.lines() {
        if line.starts_with("## Budget") {
            section = 1;
        } else if line.starts_with("## Unlimited") {
            section = 2;
        } else if line.starts_with("## ") {
            section = 0;
        }
        let cells: Vec<String> = line
            .trim()
            .trim_matches('|')
            .split('|')
            .map(|c| c.trim().to_string())
            .collect();
        if section == 0
            || !line.starts_with('|')
            || cells.len() < 5
            || cells[0] == "wall"
            || cells[0].starts_with("---")
        {
            continue;
        }
        let g = out.entry(cells[0].clone()).or_default();
        if section == 1 {
            g.budget = Some(cells);
        } else {
            g.whole = Some(cells);
        }
    }
    out
}

/// The benchmark directory: `--data`, else the first default that exists.
pub fn data_dir(given: Option<&Path>) -> BenchResult<PathBuf> {
    if let Some(d) = given {
        return Ok(d.to_path_buf());
    }
    DEFAULT_DIRS
        .iter()
        .map(PathBuf::from)
        .find(|d| d.join("config").is_dir())
        .ok_or_else(|| {
            input_error(format!(
                "bench cmcp: no benchmark directory at {} (give --data DIR, the directory that holds config/ and GRASP-RESULTS.md)",
                DEFAULT_DIRS.join(" or ")
            ))
        })
}

fn wall_names(dir: &Path) -> BenchResult<Vec<String>> {
    let config = dir.join("config");
    let rd = std::fs::read_dir(&config)
        .map_err(|e| input_error(format!("{}: {e}", config.display())))?;
    let mut names: Vec<String> = rd
        .filter_map(|e| e.ok())
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.ends_with(".txt"))
        .collect();
    // Natural order: by the number in the name, then by name.
    let key = |n: &str| -> (String, u64) {
        let digits: String = n.chars().filter(|c| c.is_ascii_digit()).collect();
        let stem: String = n.chars().filter(|c| !c.is_ascii_digit()).collect();
        (stem, digits.parse().unwrap_or(0))
    };
    names.sort_by_key(|n| key(n));
    Ok(names)
}

/// Runs the suite. `time_limit` caps each solve (None: the deterministic default).
pub fn cmcp(dir: Option<&Path>, time_limit: Option<f64>) -> BenchResult<String> {
    let dir = data_dir(dir)?;
    let grasp = read_grasp(&dir);
    let mut text = format!(
        "CMCP walls ({}) under the cmcp model: 3 UAVs, 40 s placing + 10 s return, 0.80 m, rewards 1/2/4/6.\n\
         metric: the distance rule in the plan (xy, the default, as CMCP's MILP) or in 3-D (xyz, as its GRASP).\n\
         Ours: every schedule checked by order::validate_schedule, so it breaks 0 precedence pairs.\n\
         bound: an upper bound on the reward (T = 2500 s) or a lower bound on the makespan (whole wall).\n\
         GRASP: the CMCP planner's published runs, read from GRASP-RESULTS.md (3 runs per wall).\n",
        dir.display()
    );
    for (title, budget) in [
        ("T = 2500 s", Some(CMCP_BUDGET)),
        ("whole wall, no budget", None),
    ] {
        text.push_str(&format!(
            "\n{title}\n  {:<22} {:<7} {:<6} {:>6} {:>7} {:>7} {:>10} {:>9} {:>8} {:>9} {:<8} {:>6} | {}\n",
            "wall",
            "sizes",
            "metric",
            "bricks",
            "reward",
            "placed",
            "makespan",
            "bound",
            "gap",
            "time",
            "status",
            "broken",
            if budget.is_some() {
                "GRASP reward min/mean/max · placed · makespan · time · broken"
            } else {
                "GRASP placed · makespan · time · broken"
            }
        ));
        for name in wall_names(&dir)? {
            let path = dir.join("config").join(&name);
            let src = mason_io::read_input_text(&path, mason_io::MAX_INPUT_BYTES)?;
            let stem = name.trim_end_matches(".txt");
            let tables: &[(CmcpSizes, &str)] = if stem.ends_with("_multi") {
                &[(CmcpSizes::Yaml, "yaml"), (CmcpSizes::Swapped, "swapped")]
            } else {
                &[(CmcpSizes::Yaml, "yaml")]
            };
            for (&(sizes, sizes_name), metric) in tables
                .iter()
                .flat_map(|t| [Metric::Xy, Metric::Xyz].map(|m| (t, m)))
            {
                let wall = parse_cmcp(&src, &path.display().to_string(), sizes)
                    .map_err(|e| input_error(e.to_string()))?;
                let model = TeamModel::cmcp()
                    .with_metric(metric)
                    .map_err(|e| input_error(e.to_string()))?;
                let objective = if budget.is_some() {
                    Objective::Reward
                } else {
                    Objective::Makespan
                };
                let p = TeamProblem::new(&wall, model, 3, budget, objective)
                    .map_err(|e| input_error(e.to_string()))?;
                let search = Budget::anytime(time_limit.map(std::time::Duration::from_secs_f64));
                let c = schedule_checked(&p, &search, 0)
                    .map_err(|e| BenchError::Invalid(format!("an invalid schedule: {e}")))?;
                let o = &c.outcome;
                let gap = o.gap(objective);
                let gap = if budget.is_some() {
                    format!("{gap}")
                } else {
                    format!("{:.2} %", 100.0 * gap / o.bound.max(1e-9))
                };
                let theirs = grasp
                    .get(stem)
                    .filter(|_| sizes == CmcpSizes::Yaml && metric == Metric::Xyz)
                    .and_then(|g| {
                        let row = if budget.is_some() {
                            g.budget.as_ref()
                        } else {
                            g.whole.as_ref()
                        }?;
                        Some(if budget.is_some() {
                            format!(
                                "{} · {} · {} · {} s · {}",
                                row.get(3)?,
                                row.get(4)?,
                                row.get(5)?,
                                row.get(6)?,
                                row.get(7)?
                            )
                        } else {
                            format!(
                                "{} · {} · {} s · {}",
                                row.get(2)?,
                                row.get(3)?,
                                row.get(5)?,
                                row.get(7)?
                            )
                        })
                    });
                text.push_str(&format!(
                    "  {:<22} {:<7} {:<6} {:>6} {:>7} {:>7} {:>10} {:>9} {:>8} {:>9} {:<8} {:>6} | {}\n",
                    stem,
                    sizes_name,
                    metric.name(),
                    wall.len(),
                    o.reward,
                    c.evaluation.bricks,
                    format!("{:.0} s", o.makespan_s),
                    format!("{:.0}", o.bound),
                    gap,
                    format_ms(o.stats.elapsed.as_secs_f64() * 1e3),
                    o.status.to_string(),
                    0,
                    theirs.unwrap_or_else(|| "-".into())
                ));
            }
        }
    }
    Ok(text)
}
