//! A crew plan read back: Mason's `crew --json` (per agent its `start`, `goal` and `path` of
//! `[x, y]` cells) or a result file of `key=value` lines, as MAPF solvers write them:
//!
//! ```text
//! agents=2
//! starts=(0,0),(3,0),
//! goals=(3,0),(0,0),
//! soc=9
//! makespan=5
//! solution=
//! 0:(0,0),(3,0),
//! 1:(1,0),(3,1),
//! ```
//!
//! Each line after `solution=` is one time step `t:` and the cell of every agent at t, so that
//! agent i's path is the i-th cell of each line. `starts=` and `goals=`, when present, are the
//! instance the plan claims to solve; `soc=` and `makespan=` are claims to recompute. Other
//! keys are ignored.

use super::at;
use super::json::{document, value, LineIndex};
use crate::error::{InputError, InputResult};
use crate::files::{read_input_text, MAX_INPUT_BYTES};
use mason_crew::{Cell, Grid, PlanError};
use serde::Deserialize;
use serde_json::value::RawValue;
use std::path::Path;

/// A crew plan as read.
#[derive(Clone, Debug, PartialEq)]
pub struct CrewPlanFile {
    /// One path per robot.
    pub paths: Vec<Vec<Cell>>,
    /// The starts the file states, if any.
    pub starts: Option<Vec<Cell>>,
    /// The goals the file states, if any.
    pub goals: Option<Vec<Cell>>,
    /// How robots were paired with goals (`crew --json`'s `assign`), if stated.
    pub assign: Option<String>,
    /// The sum of costs the file states.
    pub sum_of_costs: Option<u64>,
    /// The makespan the file states.
    pub makespan: Option<u64>,
    /// `crew --json` or `result`.
    pub format: &'static str,
}

#[derive(Deserialize)]
struct CrewJson<'a> {
    #[serde(borrow)]
    agents: Vec<&'a RawValue>,
    assign: Option<String>,
    sum_of_costs: Option<u64>,
    makespan: Option<u64>,
}

#[derive(Deserialize)]
struct AgentJson {
    start: (i64, i64),
    goal: (i64, i64),
    path: Vec<(i64, i64)>,
}

/// Reads `path` ([`parse_crew_plan`]).
pub fn read_crew_plan(path: &Path, grid: &Grid) -> InputResult<CrewPlanFile> {
    parse_crew_plan(&read_input_text(path, MAX_INPUT_BYTES)?, path, grid)
}

/// The plan in `text` (from `path`, named in errors) on `grid`. A cell off the grid, a step
/// with another number of agents than the first, or steps out of sequence are errors naming
/// their line; a blocked cell is left to the validator.
pub fn parse_crew_plan(text: &str, path: &Path, grid: &Grid) -> InputResult<CrewPlanFile> {
    if text.trim_start().starts_with('{') {
        mason_json(text, path, grid)
    } else {
        result_file(text, path, grid)
    }
}

fn cell(grid: &Grid, (x, y): (i64, i64), path: &Path, line: usize) -> InputResult<Cell> {
    grid.cell(x, y).ok_or_else(|| {
        at(
            path,
            line,
            format!(
                "cell ({x}, {y}) is off the {}×{} map",
                grid.width(),
                grid.height()
            ),
        )
    })
}

fn mason_json(text: &str, path: &Path, grid: &Grid) -> InputResult<CrewPlanFile> {
    let doc: CrewJson<'_> = document(text, path)?;
    let lines = LineIndex::new(text);
    let (mut starts, mut goals, mut paths) = (Vec::new(), Vec::new(), Vec::new());
    for raw in &doc.agents {
        let line = lines.of(raw.get());
        let a: AgentJson = value(text, raw, path)?;
        starts.push(cell(grid, a.start, path, line)?);
        goals.push(cell(grid, a.goal, path, line)?);
        paths.push(
            a.path
                .iter()
                .map(|&xy| cell(grid, xy, path, line))
                .collect::<InputResult<Vec<_>>>()?,
        );
    }
    Ok(CrewPlanFile {
        paths,
        starts: Some(starts),
        goals: Some(goals),
        assign: doc.assign,
        sum_of_costs: doc.sum_of_costs,
        makespan: doc.makespan,
        format: "crew --json",
    })
}

/// `(x,y),(x,y),…` (a trailing comma allowed) as cells.
fn cells(list: &str, grid: &Grid, path: &Path, line: usize) -> InputResult<Vec<Cell>> {
    let bad = |why: &str| at(path, line, format!("{why}; expected (x,y),(x,y),…"));
    let mut out = Vec::new();
    let mut rest = list.trim();
    while !rest.is_empty() {
        let Some(inner) = rest.strip_prefix('(') else {
            return Err(bad(&format!("`{}` is not a cell", shown(rest))));
        };
        let Some(close) = inner.find(')') else {
            return Err(bad("a cell without its `)`"));
        };
        let (x, y) = inner[..close]
            .split_once(',')
            .and_then(|(x, y)| Some((x.trim().parse::<i64>().ok()?, y.trim().parse::<i64>().ok()?)))
            .ok_or_else(|| bad(&format!("`({})` is not a cell", shown(&inner[..close]))))?;
        out.push(cell(grid, (x, y), path, line)?);
        rest = inner[close + 1..].trim_start();
        rest = rest.strip_prefix(',').unwrap_or(rest).trim_start();
    }
    Ok(out)
}

/// At most 40 characters of `s`, for a message.
fn shown(s: &str) -> String {
    let mut out: String = s.chars().take(40).collect();
    if s.chars().count() > 40 {
        out.push('…');
    }
    out
}

fn number(value: &str, key: &str, path: &Path, line: usize) -> InputResult<u64> {
    value.trim().parse().map_err(|_| {
        at(
            path,
            line,
            format!("{key}=`{}` is not a whole number", shown(value.trim())),
        )
    })
}

fn result_file(text: &str, path: &Path, grid: &Grid) -> InputResult<CrewPlanFile> {
    let mut plan = CrewPlanFile {
        paths: Vec::new(),
        starts: None,
        goals: None,
        assign: None,
        sum_of_costs: None,
        makespan: None,
        format: "result",
    };
    let mut in_solution = false;
    let mut steps = 0usize;
    let mut solution_line = None;
    for (i, raw_line) in text.lines().enumerate() {
        let line = i + 1;
        let l = raw_line.trim();
        if l.is_empty() {
            continue;
        }
        if in_solution {
            if let Some((t, config)) = l.split_once(':').filter(|(t, _)| !t.contains('=')) {
                let t: usize = t.trim().parse().map_err(|_| {
                    at(
                        path,
                        line,
                        format!("time step `{}` is not a whole number", shown(t)),
                    )
                })?;
                if t != steps {
                    return Err(at(path, line, format!("time step {t}, expected {steps}")));
                }
                let config = cells(config, grid, path, line)?;
                if steps == 0 {
                    plan.paths = config.iter().map(|&c| vec![c]).collect();
                } else if config.len() != plan.paths.len() {
                    return Err(at(
                        path,
                        line,
                        format!(
                            "{} agents at step {t}, but {} at step 0",
                            config.len(),
                            plan.paths.len()
                        ),
                    ));
                } else {
                    for (p, c) in plan.paths.iter_mut().zip(config) {
                        p.push(c);
                    }
                }
                steps += 1;
                continue;
            }
            in_solution = false;
        }
        let Some((key, value)) = l.split_once('=') else {
            return Err(at(
                path,
                line,
                format!("`{}` is neither key=value nor a time step", shown(l)),
            ));
        };
        match key.trim() {
            "solution" => {
                if solution_line.is_some() {
                    return Err(at(path, line, "a second solution="));
                }
                solution_line = Some(line);
                in_solution = true;
            }
            "starts" => plan.starts = Some(cells(value, grid, path, line)?),
            "goals" => plan.goals = Some(cells(value, grid, path, line)?),
            "soc" => plan.sum_of_costs = Some(number(value, "soc", path, line)?),
            "makespan" => plan.makespan = Some(number(value, "makespan", path, line)?),
            _ => {}
        }
    }
    match solution_line {
        None => Err(no_solution(path)),
        Some(line) if steps == 0 => Err(at(path, line, "solution= has no time steps")),
        Some(_) => Ok(plan),
    }
}

fn no_solution(path: &Path) -> InputError {
    InputError::bad(format!(
        "{}: no solution= line (a result file lists the plan after solution=)",
        path.display()
    ))
}

/// The instance a plan is checked against, and what the file's own statements break.
#[derive(Clone, Debug, PartialEq)]
pub struct CrewInstance {
    /// Robot i's start.
    pub starts: Vec<Cell>,
    /// Robot i's goal.
    pub goals: Vec<Cell>,
    /// The file's `starts=`/`goals=` that differ from the scenario, as
    /// [`PlanError::WrongStart`]/[`PlanError::WrongGoal`] (found: the file's, expected: the
    /// scenario's).
    pub mismatches: Vec<PlanError>,
}

/// The starts and goals to check `file` against. With a scenario (its agents in order), robot
/// i starts on the scenario's start i; its goal is the scenario's goal i, or, for a plan that
/// states another assignment than `given` (`crew --assign hungarian`, …), the goal the file
/// gives it when the file's goals are the scenario's goals in some order. The file's own
/// starts and goals must then agree with the scenario. Without a scenario the file's starts
/// and goals are used, or else each path's first and last cells.
pub fn crew_instance(
    file: &CrewPlanFile,
    grid: &Grid,
    scenario: Option<(&[Cell], &[Cell])>,
) -> CrewInstance {
    let first = |p: &Vec<Cell>| p.first().copied().unwrap_or(Cell(u32::MAX));
    let last = |p: &Vec<Cell>| p.last().copied().unwrap_or(Cell(u32::MAX));
    let Some((scen_starts, scen_goals)) = scenario else {
        return CrewInstance {
            starts: (file.starts.clone()).unwrap_or_else(|| file.paths.iter().map(first).collect()),
            goals: (file.goals.clone()).unwrap_or_else(|| file.paths.iter().map(last).collect()),
            mismatches: Vec::new(),
        };
    };
    let starts = scen_starts.to_vec();
    let reassigned = file.assign.as_deref().is_some_and(|a| a != "given");
    let goals = match &file.goals {
        Some(g) if reassigned && same_cells(g, scen_goals) => g.clone(),
        _ => scen_goals.to_vec(),
    };
    let mut mismatches = Vec::new();
    for (r, (&stated, &expected)) in (file.starts.iter().flatten()).zip(&starts).enumerate() {
        if stated != expected {
            mismatches.push(PlanError::WrongStart {
                robot: r,
                found: grid.xy(stated),
                expected: grid.xy(expected),
            });
        }
    }
    for (r, (&stated, &expected)) in (file.goals.iter().flatten()).zip(&goals).enumerate() {
        if stated != expected {
            mismatches.push(PlanError::WrongGoal {
                robot: r,
                found: grid.xy(stated),
                expected: grid.xy(expected),
            });
        }
    }
    CrewInstance {
        starts,
        goals,
        mismatches,
    }
}

fn same_cells(a: &[Cell], b: &[Cell]) -> bool {
    let (mut a, mut b) = (a.to_vec(), b.to_vec());
    a.sort_unstable();
    b.sort_unstable();
    a == b
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_result_file_gives_one_path_per_agent() {
        let g = Grid::open(4, 3);
        let text = "agents=2\nstarts=(0,0),(3,0),\ngoals=(3,0),(0,0)\nsoc=4\nsolution=\n0:(0,0),(3,0),\n1:(0,1),(2,0),\n";
        let f = parse_crew_plan(text, Path::new("r.txt"), &g).unwrap();
        assert_eq!(f.format, "result");
        assert_eq!(f.paths.len(), 2);
        assert_eq!(
            f.paths[1],
            vec![g.cell(3, 0).unwrap(), g.cell(2, 0).unwrap()]
        );
        assert_eq!(f.starts.unwrap()[1], g.cell(3, 0).unwrap());
        assert_eq!(f.goals.unwrap()[0], g.cell(3, 0).unwrap());
        assert_eq!((f.sum_of_costs, f.makespan), (Some(4), None));
    }

    #[test]
    fn bad_result_lines_are_named() {
        let g = Grid::open(4, 3);
        let cases = [
            (
                "solution=\n0:(0,0),(1,0),\n1:(0,1),\n",
                "r.txt:3: 1 agents at step 1, but 2 at step 0",
            ),
            (
                "solution=\n0:(0,0),\n2:(0,1),\n",
                "r.txt:3: time step 2, expected 1",
            ),
            (
                "solution=\n0:(0,0),(9,0),\n",
                "r.txt:2: cell (9, 0) is off the 4×3 map",
            ),
            (
                "solution=\n0:(0,0),(1;0),\n",
                "r.txt:2: `(1;0)` is not a cell",
            ),
            ("solution=\n0:(0,0),x\n", "r.txt:2: `x` is not a cell"),
            ("soc=3\n", "r.txt: no solution= line"),
            (
                "soc=three\nsolution=\n0:(0,0)\n",
                "r.txt:1: soc=`three` is not a whole number",
            ),
            ("solution=\n", "r.txt:1: solution= has no time steps"),
            (
                "hello\n",
                "r.txt:1: `hello` is neither key=value nor a time step",
            ),
        ];
        for (text, want) in cases {
            let e = parse_crew_plan(text, Path::new("r.txt"), &g)
                .unwrap_err()
                .to_string();
            assert!(e.starts_with(want), "{e} / {want}");
        }
    }

    #[test]
    fn mason_json_agents() {
        let g = Grid::open(4, 3);
        let text = "{\"assign\": \"given\", \"agents\": [\n{\"start\": [0, 0], \"goal\": [1, 0], \"path\": [[0, 0], [1, 0]]},\n{\"start\": [3, 2], \"goal\": [3, 2], \"path\": [[3, 7]]}]}";
        let e = parse_crew_plan(text, Path::new("c.json"), &g)
            .unwrap_err()
            .to_string();
        assert_eq!(e, "c.json:3: cell (3, 7) is off the 4×3 map");
        let ok = text.replace("[3, 7]", "[3, 2]");
        let f = parse_crew_plan(&ok, Path::new("c.json"), &g).unwrap();
        assert_eq!(f.paths[0].len(), 2);
        assert_eq!(f.assign.as_deref(), Some("given"));
    }
}
