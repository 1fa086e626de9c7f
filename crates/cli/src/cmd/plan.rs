//! `mason plan`: a build order (or, with `--objective`, a team schedule: [`super::schedule`]),
//! checked by the order validator, printed as a table or JSON.

use crate::fail::{check_outputs, input_error, no_solution, write_all, CliResult};
use crate::input::DesignArgs;
use mason_order::{plan_checked, Budget, BuildProblem, CheckedPlan, PlannerSpec, Status};
use serde_json::Value;
use std::path::PathBuf;
use std::time::Duration;

/// `mason plan`'s options.
#[derive(clap::Args)]
pub struct PlanArgs {
    #[command(flatten)]
    pub design: DesignArgs,
    /// brute, greedy, improved:N,K (e.g. improved:1,4) or exact
    #[arg(long, default_value = "exact")]
    pub planner: String,
    /// Cost model parameters (TOML); defaults are the thesis's. With --objective: the team
    /// model, thesis, cmcp or a TOML file (default thesis)
    #[arg(long)]
    pub model: Option<String>,
    /// With --objective and a distance rule: measure it in the horizontal plane (xy, the
    /// default) or in 3-D (xyz)
    #[arg(long)]
    pub metric: Option<String>,
    /// Plan a team schedule instead of a build order: makespan (whole wall, shortest),
    /// reward (most reward by --budget), expected (most expected reward by --budget when
    /// UAVs fail at --uav-hazard)
    #[arg(long)]
    pub objective: Option<String>,
    /// Team size for --objective
    #[arg(long, default_value_t = 3, allow_negative_numbers = true)]
    pub uavs: usize,
    /// Time budget T in seconds for --objective reward|expected (bricks count if placed by T)
    #[arg(long, allow_negative_numbers = true)]
    pub budget: Option<f64>,
    /// UAV failures per hour per UAV, for --objective expected
    #[arg(long, allow_negative_numbers = true)]
    pub uav_hazard: Option<f64>,
    /// Seed of the schedule search (same seed, same schedule unless --time-limit stops it)
    #[arg(long, default_value_t = 0, allow_negative_numbers = true)]
    pub seed: u64,
    /// Search budget in seconds (brute, improved, schedules); the best so far is reported
    #[arg(long, allow_negative_numbers = true)]
    pub time_limit: Option<f64>,
    /// Print JSON instead of a table
    #[arg(long)]
    pub json: bool,
    /// Also draw the wall with its build order as SVG
    #[arg(long)]
    pub svg: Option<PathBuf>,
    /// Also write an HTML page with the figure and the step table
    #[arg(long)]
    pub html: Option<PathBuf>,
}

/// `mason plan` without `--objective` (with it, [`super::schedule::run`]).
pub fn run(a: PlanArgs) -> CliResult<()> {
    let started = std::time::Instant::now();
    check_outputs(&[&a.svg, &a.html])?;
    if a.uav_hazard.is_some() || a.budget.is_some() || a.metric.is_some() {
        return Err(input_error(
            "--budget, --uav-hazard and --metric belong to team schedules: add --objective",
        ));
    }
    let spec: PlannerSpec = a
        .planner
        .parse()
        .map_err(|e| input_error(format!("--planner: {e}")))?;
    let limit = time_limit(a.time_limit)?;
    let wall = a.design.load()?;
    let model = mason_io::load_model(a.model.as_deref().map(std::path::Path::new))?;
    let problem = BuildProblem::new(&wall, model).map_err(|e| input_error(e.to_string()))?;
    // The limit counts from the start: the search gets what reading and printing leave.
    let share = limit.map(|l| {
        crate::cmd::schedule::search_share(l, started.elapsed(), wall.len()).as_secs_f64()
    });
    let checked = solve(&problem, spec, share)?;
    let figure = if a.svg.is_some() || a.html.is_some() {
        mason_report::wall_svg(&wall, checked.outcome.order.as_deref())
    } else {
        String::new()
    };
    let mut files: Vec<(PathBuf, Vec<u8>)> = Vec::new();
    if let Some(path) = a.svg {
        files.push((path, figure.clone().into_bytes()));
    }
    if let Some(path) = a.html {
        let page = mason_report::report_page(
            &format!("{} — {}", wall.name(), spec),
            "Build order (bold numbers: step; small: brick id), checked by order::validate.",
            &[
                mason_report::Section {
                    heading: "Wall".into(),
                    html: figure,
                },
                mason_report::Section {
                    heading: "Steps".into(),
                    html: mason_report::pre(&plan_table(&problem, &checked)),
                },
            ],
        );
        files.push((path, page.into_bytes()));
    }
    write_all(&files)?;
    if a.json {
        print_json(&mason_report::PlanDoc {
            problem: &problem,
            checked: &checked,
        })?;
    } else {
        print!("{}", plan_table(&problem, &checked));
    }
    report_overrun(limit, started, checked.outcome.stats.elapsed.as_secs_f64());
    exit_for(&checked)
}

/// JSON as printed.
pub fn pretty(v: &Value) -> String {
    serde_json::to_string_pretty(v).unwrap_or_default()
}

/// Prints a document as pretty JSON on stdout as it serialises, holding no copy of it.
pub fn print_json<T: serde::Serialize>(v: &T) -> CliResult<()> {
    use std::io::Write;
    let mut out = std::io::BufWriter::new(std::io::stdout().lock());
    serde_json::to_writer_pretty(&mut out, v)
        .map_err(std::io::Error::from)
        .and_then(|()| writeln!(out))
        .and_then(|()| out.flush())
        .map_err(|e| input_error(format!("stdout: {e}")))
}

/// A planner's outcome after validation.
pub type Checked = CheckedPlan;

/// Runs a planner and validates its order (a failed validation is a bug: reported, exit 2).
pub fn solve(
    problem: &BuildProblem<'_>,
    spec: PlannerSpec,
    limit: Option<f64>,
) -> CliResult<Checked> {
    let budget = match limit {
        Some(s) => Budget::time(Duration::from_secs_f64(s)),
        None => Budget::unlimited(),
    };
    plan_checked(problem, spec, &budget).map_err(|e| input_error(format!("internal error: {e}")))
}

/// Parses `--time-limit` ([`mason_io::time_limit`]).
pub fn time_limit(s: Option<f64>) -> CliResult<Option<f64>> {
    Ok(mason_io::time_limit("--time-limit", s)?)
}

/// With `--time-limit L`, says on stderr when the whole command took more than 10 % over L.
/// The searches stop in time; reading, checking and printing a huge input take the rest, so
/// the message gives the search's own share (`search_s`).
pub fn report_overrun(limit: Option<f64>, started: std::time::Instant, search_s: f64) {
    if let Some(text) = overrun_message(limit, started.elapsed().as_secs_f64(), search_s) {
        eprintln!("mason: warning: {text}");
    }
}

/// The overrun warning for a command that took `total_s` under `--time-limit limit`, if any.
pub fn overrun_message(limit: Option<f64>, total_s: f64, search_s: f64) -> Option<String> {
    let limit = limit?;
    (total_s > 1.1 * limit).then(|| {
        format!(
            "--time-limit {limit} s overrun: the command took {total_s:.2} s, of which the search {search_s:.2} s (the rest is reading, checking and writing)"
        )
    })
}

/// The exit status for an outcome.
pub fn exit_for(checked: &Checked) -> CliResult<()> {
    match (checked.outcome.status, &checked.evaluation) {
        (Status::Infeasible, _) => Err(no_solution("no valid build order exists")),
        (_, None) => Err(no_solution(format!(
            "{}: no complete build order within the budget",
            checked.outcome.planner
        ))),
        _ => Ok(()),
    }
}

/// The plan as a table.
pub fn plan_table(problem: &BuildProblem<'_>, checked: &Checked) -> String {
    let wall = problem.wall();
    let o = &checked.outcome;
    let mut out = format!(
        "wall {} ({} bricks, {} levels) · planner {} · status {} · {:.3} ms · {} nodes\n",
        wall.name(),
        wall.len(),
        wall.levels(),
        o.planner,
        o.status,
        o.stats.elapsed.as_secs_f64() * 1e3,
        o.stats.nodes
    );
    if let Some(e) = &checked.evaluation {
        out.push_str(" step   brick  type    level  placed nb   cost (s)\n");
        for (i, s) in e.steps.iter().enumerate() {
            let b = wall.brick(s.brick);
            out.push_str(&format!(
                "{:>5}  {:>6}  {:<6}  {:>5}  {:>9}  {:>9.2}\n",
                i + 1,
                b.label,
                b.kind.name(),
                b.level,
                s.placed_neighbours,
                s.cost
            ));
        }
        out.push_str(&format!(
            "total cost {:.2} s (checked by order::validate)\n",
            e.total_cost
        ));
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_overrun_is_reported_past_ten_percent_with_the_searchs_share() {
        assert_eq!(overrun_message(None, 100.0, 1.0), None);
        assert_eq!(overrun_message(Some(5.0), 5.5, 5.0), None);
        let text = overrun_message(Some(5.0), 14.6, 5.01).expect("14.6 s is over 5.5 s");
        assert!(text.contains("--time-limit 5 s overrun"), "{text}");
        assert!(text.contains("took 14.60 s"), "{text}");
        assert!(text.contains("search 5.01 s"), "{text}");
    }

    #[test]
    fn time_limits_are_checked_for_range() {
        assert_eq!(time_limit(None).unwrap(), None);
        assert_eq!(time_limit(Some(2.0)).unwrap(), Some(2.0));
        assert!(time_limit(Some(1e300)).is_err());
        assert!(time_limit(Some(f64::NAN)).is_err());
        assert!(time_limit(Some(-1.0)).is_err());
    }
}
