//! A team schedule read back: Mason's `plan --objective … --json` or a CSV of
//! `uav,brick,start[,end]` rows (an optional header line, `#` comments). Each row is one UAV's
//! part in one placement: rows of the same brick with the same start are one placement (an
//! orange brick's pair); rows of the same brick with different starts are two placements.

use super::json::{document, value, LineIndex};
use super::{at, looks_like_json, Labels};
use crate::error::{InputError, InputResult};
use crate::files::{read_input_text, MAX_INPUT_BYTES};
use mason_order::schedule::{ClaimedEnd, Placement, Schedule, MAX_UAVS};
use mason_wall::Wall;
use serde::Deserialize;
use serde_json::value::RawValue;
use std::collections::HashMap;
use std::path::Path;

/// What a schedule file states about itself (Mason's JSON; a CSV states none of it).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ScheduleClaims {
    /// Team size.
    pub uavs: Option<usize>,
    /// Team model name (`thesis`, `cmcp` or a file's name).
    pub model: Option<String>,
    /// The distance rule's metric (`xy` or `xyz`) the schedule was planned under.
    pub metric: Option<String>,
    /// The budget T (s).
    pub budget_s: Option<f64>,
    /// The reward.
    pub reward: Option<f64>,
    /// The makespan (s).
    pub makespan_s: Option<f64>,
}

/// A schedule as read.
#[derive(Clone, Debug, PartialEq)]
pub struct ScheduleFile {
    /// The placements, in the order of their first row.
    pub schedule: Schedule,
    /// The rows that state an end.
    pub ends: Vec<ClaimedEnd>,
    /// What the file states.
    pub claims: ScheduleClaims,
    /// The largest UAV index of any row, plus one (0 without rows).
    pub uavs_seen: usize,
    /// `plan --json` or `csv`.
    pub format: &'static str,
}

#[derive(Deserialize)]
struct ScheduleJson<'a> {
    #[serde(borrow)]
    schedule: Vec<&'a RawValue>,
    uavs: Option<usize>,
    model: Option<String>,
    metric: Option<String>,
    budget_s: Option<f64>,
    reward: Option<f64>,
    makespan_s: Option<f64>,
}

#[derive(Deserialize)]
struct RowJson {
    uav: usize,
    brick: u32,
    start_s: f64,
    end_s: Option<f64>,
}

/// One row: UAV, brick label, start, stated end; with its line.
struct Row {
    line: usize,
    uav: usize,
    brick: u32,
    start_s: f64,
    end_s: Option<f64>,
}

/// Reads `path` ([`parse_schedule`]).
pub fn read_schedule(path: &Path, wall: &Wall) -> InputResult<ScheduleFile> {
    parse_schedule(&read_input_text(path, MAX_INPUT_BYTES)?, path, wall)
}

/// The schedule in `text` (from `path`, named in errors). A brick label not in `wall`, or a
/// UAV index of [`MAX_UAVS`] or more, is an error naming its line.
pub fn parse_schedule(text: &str, path: &Path, wall: &Wall) -> InputResult<ScheduleFile> {
    let (rows, claims, format) = if looks_like_json(text) {
        let doc: ScheduleJson<'_> = document(text, path)?;
        let lines = LineIndex::new(text);
        let rows = doc
            .schedule
            .iter()
            .map(|raw| {
                let r: RowJson = value(text, raw, path)?;
                Ok(Row {
                    line: lines.of(raw.get()),
                    uav: r.uav,
                    brick: r.brick,
                    start_s: r.start_s,
                    end_s: r.end_s,
                })
            })
            .collect::<InputResult<Vec<_>>>()?;
        let claims = ScheduleClaims {
            uavs: doc.uavs,
            model: doc.model,
            metric: doc.metric,
            budget_s: doc.budget_s,
            reward: doc.reward,
            makespan_s: doc.makespan_s,
        };
        (rows, claims, "plan --json")
    } else {
        let rows = csv_rows(text, path)?;
        if rows.is_empty() {
            return Err(InputError::bad(format!(
                "{}: no rows (expected uav,brick,start[,end] lines)",
                path.display()
            )));
        }
        (rows, ScheduleClaims::default(), "csv")
    };
    assemble(rows, claims, format, path, wall)
}

fn csv_rows(text: &str, path: &Path) -> InputResult<Vec<Row>> {
    let mut rows = Vec::new();
    let mut first = true;
    for (i, line) in text.lines().enumerate() {
        let line_no = i + 1;
        let content = line.split('#').next().unwrap_or("").trim();
        if content.is_empty() {
            continue;
        }
        let fields: Vec<&str> = content.split(',').map(str::trim).collect();
        let header = first && fields[0].parse::<f64>().is_err();
        first = false;
        if header {
            continue;
        }
        if !(3..=4).contains(&fields.len()) {
            return Err(at(
                path,
                line_no,
                format!("{} fields; expected uav,brick,start[,end]", fields.len()),
            ));
        }
        let number = |k: usize, what: &str| -> InputResult<f64> {
            fields[k].parse::<f64>().map_err(|_| {
                at(
                    path,
                    line_no,
                    format!("{what} `{}` is not a number", fields[k]),
                )
            })
        };
        let whole = |k: usize, what: &str| -> InputResult<u64> {
            fields[k].parse::<u64>().map_err(|_| {
                at(
                    path,
                    line_no,
                    format!("{what} `{}` is not a whole number ≥ 0", fields[k]),
                )
            })
        };
        let uav = whole(0, "UAV")?;
        let brick = whole(1, "brick")?;
        rows.push(Row {
            line: line_no,
            uav: usize::try_from(uav).unwrap_or(usize::MAX),
            brick: u32::try_from(brick).unwrap_or(u32::MAX),
            start_s: number(2, "start")?,
            end_s: if fields.len() == 4 {
                Some(number(3, "end")?)
            } else {
                None
            },
        });
    }
    Ok(rows)
}

fn assemble(
    rows: Vec<Row>,
    claims: ScheduleClaims,
    format: &'static str,
    path: &Path,
    wall: &Wall,
) -> InputResult<ScheduleFile> {
    let labels = Labels::new(wall);
    let mut placements: Vec<Placement> = Vec::new();
    let mut index: HashMap<(u32, u64), usize> = HashMap::new();
    let mut ends = Vec::new();
    let mut uavs_seen = 0;
    for r in rows {
        if r.uav >= MAX_UAVS {
            return Err(too_many(path, r.line, r.uav));
        }
        uavs_seen = uavs_seen.max(r.uav + 1);
        let b = labels.brick(r.brick, path, r.line)?;
        // -0.0 and 0.0 are one start.
        let key = (b.0, (r.start_s + 0.0).to_bits());
        let k = *index.entry(key).or_insert_with(|| {
            placements.push(Placement {
                brick: b,
                uavs: Vec::new(),
                start_s: r.start_s,
            });
            placements.len() - 1
        });
        placements[k].uavs.push(r.uav);
        if let Some(end_s) = r.end_s {
            ends.push(ClaimedEnd {
                brick: b,
                uav: r.uav,
                start_s: r.start_s,
                end_s,
            });
        }
    }
    Ok(ScheduleFile {
        schedule: Schedule { placements },
        ends,
        claims,
        uavs_seen,
        format,
    })
}

fn too_many(path: &Path, line: usize, uav: usize) -> InputError {
    at(
        path,
        line,
        format!("UAV {uav}: a team has at most {MAX_UAVS} UAVs (0..{MAX_UAVS})"),
    )
}

/// What a schedule is checked against: the team model, the team size and the budget.
#[derive(Clone, Debug, PartialEq)]
pub struct ScheduleSetting {
    /// The team model.
    pub model: mason_order::schedule::TeamModel,
    /// Team size.
    pub uavs: usize,
    /// The budget T (s), if any.
    pub budget_s: Option<f64>,
}

impl ScheduleFile {
    /// The setting to check against: what is given, else what the file states (a model it
    /// names must be built in, else it must be given; the distance rule's metric), else the
    /// UAVs its rows use and no budget. Errors name `path` and the option (`--model`,
    /// `--metric`, `--uavs`, `--budget`).
    pub fn setting(
        &self,
        path: &Path,
        model: Option<&str>,
        metric: Option<&str>,
        uavs: Option<usize>,
        budget_s: Option<f64>,
    ) -> InputResult<ScheduleSetting> {
        use mason_order::schedule::TeamModel;
        let name = match (model, &self.claims.model) {
            (Some(m), _) => Some(m),
            (None, Some(m)) if TeamModel::builtin(m).is_some() => Some(m.as_str()),
            (None, Some(m)) => {
                return Err(InputError::bad(format!(
                    "{}: planned with team model `{m}`: give it with --model",
                    path.display()
                )))
            }
            (None, None) => None,
        };
        let model = crate::load_team_model(name, metric)?;
        // No metric given: the one the file states, when the model has a distance rule.
        let stated = match (metric, &self.claims.metric) {
            (None, Some(m)) if model.concurrency.metric().is_some() => Some(m),
            _ => None,
        };
        let model = match stated {
            Some(m) => crate::load_team_model(name, Some(m)).map_err(|e| {
                InputError::bad(format!(
                    "{}: the metric the file states: {e}",
                    path.display()
                ))
            })?,
            None => model,
        };
        let uavs = uavs.or(self.claims.uavs).unwrap_or(self.uavs_seen.max(1));
        if uavs == 0 || uavs > MAX_UAVS {
            return Err(InputError::bad(format!(
                "--uavs {uavs}: expected 1 to {MAX_UAVS}"
            )));
        }
        let budget_s = budget_s.or(self.claims.budget_s);
        if let Some(t) = budget_s.filter(|t| !(*t > 0.0 && *t <= 1e9)) {
            return Err(InputError::bad(format!(
                "--budget {t}: expected a number of seconds in (0, 10⁹]"
            )));
        }
        Ok(ScheduleSetting {
            model,
            uavs,
            budget_s,
        })
    }

    /// Checks the schedule with `validate_schedule` in `setting`, the ends its rows state and
    /// the reward and makespan the file claims: the evaluation, or the broken rules (the
    /// first one; with `all`, every one).
    pub fn check(
        &self,
        wall: &Wall,
        setting: &ScheduleSetting,
        all: bool,
    ) -> Result<mason_order::schedule::ScheduleEvaluation, Vec<mason_order::schedule::ScheduleError>>
    {
        use mason_order::schedule as sch;
        let s = &setting;
        let eval = match sch::validate_schedule(wall, &s.model, s.uavs, s.budget_s, &self.schedule)
        {
            Ok(eval) => eval,
            Err(first) if !all => return Err(vec![first]),
            Err(_) => {
                let mut found =
                    sch::schedule_violations(wall, &s.model, s.uavs, s.budget_s, &self.schedule);
                found.extend(sch::end_violations(wall, &s.model, &self.ends));
                return Err(found);
            }
        };
        let mut found = sch::end_violations(wall, &s.model, &self.ends);
        found.extend(sch::claim_violations(
            &eval,
            self.claims.reward,
            self.claims.makespan_s,
        ));
        if found.is_empty() {
            Ok(eval)
        } else {
            Err(found)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn wall() -> Wall {
        mason_wall::builtin("mbzirc").unwrap().wall()
    }

    #[test]
    fn csv_rows_of_one_brick_and_start_are_one_placement() {
        let w = wall();
        let orange = w
            .ids()
            .find(|&b| w.brick(b).kind.uavs_needed() == 2)
            .unwrap();
        let o = w.brick(orange).label;
        let red = w
            .ids()
            .find(|&b| w.brick(b).kind.uavs_needed() == 1)
            .unwrap();
        let r = w.brick(red).label;
        let text =
            format!("uav,brick,start,end\n# a pair\n0,{o},0,40\n1,{o},0\n2,{r},0.5\n2,{r},90\n");
        let f = parse_schedule(&text, Path::new("s.csv"), &w).unwrap();
        assert_eq!(f.format, "csv");
        assert_eq!(f.uavs_seen, 3);
        let p = &f.schedule.placements;
        assert_eq!(p.len(), 3);
        assert_eq!((p[0].brick, p[0].uavs.clone()), (orange, vec![0, 1]));
        assert_eq!((p[1].start_s, p[2].start_s), (0.5, 90.0));
        assert_eq!(f.ends.len(), 1);
        assert_eq!(f.ends[0].end_s, 40.0);
    }

    #[test]
    fn bad_csv_rows_name_the_line() {
        let w = wall();
        let cases = [
            (
                "0,101\n",
                "s.csv:1: 2 fields; expected uav,brick,start[,end]",
            ),
            (
                "uav,brick,start\n0,101,x\n",
                "s.csv:2: start `x` is not a number",
            ),
            (
                "0,101,0\n-1,101,0\n",
                "s.csv:2: UAV `-1` is not a whole number ≥ 0",
            ),
            (
                "0,101,0\n5000,102,0\n",
                "s.csv:2: UAV 5000: a team has at most 1024 UAVs (0..1024)",
            ),
            (
                "\n\n0,9999,0\n",
                "s.csv:3: brick 9999 is not in the wall builtin:mbzirc",
            ),
            (
                "uav,brick,start\nuav,brick,start\n",
                "s.csv:2: UAV `uav` is not a whole number ≥ 0",
            ),
            (
                "uav,brick,start\n# none\n",
                "s.csv: no rows (expected uav,brick,start[,end] lines)",
            ),
        ];
        for (text, want) in cases {
            let e = parse_schedule(text, Path::new("s.csv"), &w)
                .unwrap_err()
                .to_string();
            assert_eq!(e, want, "{text:?}");
        }
    }

    #[test]
    fn json_rows_and_claims() {
        let w = wall();
        let text = "{\"uavs\": 3, \"model\": \"cmcp\", \"reward\": 1, \"makespan_s\": 40,\n\"schedule\": [\n{\"uav\": 0, \"brick\": 101, \"start_s\": 0, \"end_s\": 40}]}";
        let f = parse_schedule(text, Path::new("s.json"), &w).unwrap();
        assert_eq!(f.claims.uavs, Some(3));
        assert_eq!(f.claims.model.as_deref(), Some("cmcp"));
        assert_eq!(f.schedule.placements.len(), 1);
        let bad = "{\"schedule\": [\n{\"uav\": 0, \"brick\": 101, \"start_s\": 0},\n{\"uav\": 0, \"start_s\": 0}]}";
        let e = parse_schedule(bad, Path::new("s.json"), &w)
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("s.json:3: missing field `brick`"), "{e}");
    }
}
