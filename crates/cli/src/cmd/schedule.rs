//! `mason plan --objective …`: team schedules — solve, validate, print a table or JSON.

use crate::cmd::plan::{print_json, report_overrun, time_limit, PlanArgs};
use crate::fail::{check_outputs, input_error, write_all, CliResult};
use mason_mission::{FlightPlan, FlightPlanError, FlightRequest};
use mason_order::schedule::{
    schedule_checked, CheckedSchedule, Objective, TeamModel, TeamOutcome, TeamProblem,
};
use mason_order::Budget;
use mason_order::CostModel;
use mason_wall::{BrickId, Wall};
use std::path::PathBuf;
use std::time::{Duration, Instant};

/// `mason plan --objective`.
pub fn run(a: PlanArgs) -> CliResult<()> {
    let started = std::time::Instant::now();
    check_outputs(&[&a.svg, &a.html])?;
    let req = ScheduleRequest::resolve(
        a.objective.as_deref().unwrap_or_default(),
        a.uavs,
        a.budget,
        a.uav_hazard,
        a.seed,
        a.time_limit,
    )?;
    let team = mason_io::load_team_model(a.model.as_deref(), a.metric.as_deref())?;
    let wall = a.design.load()?;
    let problem = problem(&wall, team, &req)?;
    let checked = solve(&problem, &req)?;
    let schedule = checked.outcome.schedule.clone().unwrap_or_default();
    let title = format!(
        "{} — {} schedule, {} UAVs, model {}",
        wall.name(),
        problem.objective(),
        problem.uavs(),
        problem.model().name
    );
    // Drawn only when asked for: on a huge wall the figure costs seconds.
    let figure = if a.svg.is_some() || a.html.is_some() {
        mason_report::schedule_svg(&title, &problem, &schedule)
    } else {
        String::new()
    };
    let mut files: Vec<(PathBuf, Vec<u8>)> = Vec::new();
    if let Some(path) = a.svg {
        files.push((path, figure.clone().into_bytes()));
    }
    if let Some(path) = a.html {
        let page = mason_report::report_page(
            &title,
            &summary_line(&problem, &checked.outcome),
            &[
                mason_report::Section {
                    heading: "Schedule".into(),
                    html: figure,
                },
                mason_report::Section {
                    heading: "Placements".into(),
                    html: mason_report::pre(&schedule_table(&problem, &checked)),
                },
            ],
        );
        files.push((path, page.into_bytes()));
    }
    write_all(&files)?;
    if a.json {
        print_json(&mason_report::ScheduleDoc {
            problem: &problem,
            checked: &checked,
            seed: req.seed,
        })?;
    } else {
        print!("{}", schedule_table(&problem, &checked));
    }
    report_overrun(
        req.time_limit,
        started,
        checked.outcome.stats.elapsed.as_secs_f64(),
    );
    Ok(())
}

/// What `mason plan --objective` was asked.
pub struct ScheduleRequest {
    /// The objective (with its hazard for `expected`).
    pub objective: Objective,
    /// Team size.
    pub uavs: usize,
    /// The budget T.
    pub budget_s: Option<f64>,
    /// Deadline of the search.
    pub time_limit: Option<f64>,
    /// Seed.
    pub seed: u64,
    /// When the command started: `time_limit` counts from here.
    pub started: Instant,
}

impl ScheduleRequest {
    /// The request of the raw flags (`--objective`, `--uavs`, `--budget`, `--uav-hazard`,
    /// `--seed`, `--time-limit`), checked.
    pub fn resolve(
        objective: &str,
        uavs: usize,
        budget_s: Option<f64>,
        uav_hazard: Option<f64>,
        seed: u64,
        limit: Option<f64>,
    ) -> CliResult<Self> {
        Ok(ScheduleRequest {
            objective: mason_io::objective(objective, uav_hazard)?,
            uavs,
            budget_s,
            time_limit: time_limit(limit)?,
            seed,
            started: Instant::now(),
        })
    }

    /// Seed 0 and the deterministic default search (no deadline).
    pub fn new(objective: Objective, uavs: usize, budget_s: Option<f64>) -> Self {
        ScheduleRequest {
            objective,
            uavs,
            budget_s,
            time_limit: None,
            seed: 0,
            started: Instant::now(),
        }
    }
}

/// Poses the problem (bad parameters: exit 2).
pub fn problem<'w>(
    wall: &'w Wall,
    model: TeamModel,
    req: &ScheduleRequest,
) -> CliResult<TeamProblem<'w>> {
    TeamProblem::new(wall, model, req.uavs, req.budget_s, req.objective)
        .map_err(|e| input_error(e.to_string()))
}

/// The schedule search's budget: until the deadline when there is a time limit, else the
/// deterministic default.
fn search_budget(limit: Option<f64>) -> Budget {
    Budget::anytime(limit.map(Duration::from_secs_f64))
}

/// Seconds per brick kept from a `--time-limit` for what follows the search: the last decode,
/// the validator and the output (measured on a 400 000-brick wall: about 5 µs per brick for
/// all three, with the JSON).
const AFTER_SEARCH_S_PER_BRICK: f64 = 5e-6;

/// The search's share of `--time-limit L`, which counts from the command's start: L less what
/// reading and posing took and what checking and printing `bricks` bricks will take, and at
/// least a tenth of L (a wall too large for L then overruns, and says so).
pub fn search_share(limit: f64, spent: Duration, bricks: usize) -> Duration {
    let after = AFTER_SEARCH_S_PER_BRICK * bricks as f64;
    Duration::from_secs_f64((limit - spent.as_secs_f64() - after).max(0.1 * limit))
}

/// Plans and validates (an invalid schedule is a bug: reported, exit 2).
pub fn solve(p: &TeamProblem<'_>, req: &ScheduleRequest) -> CliResult<CheckedSchedule> {
    let share = req
        .time_limit
        .map(|l| search_share(l, req.started.elapsed(), p.len()).as_secs_f64());
    schedule_checked(p, &search_budget(share), req.seed).map_err(|e| {
        input_error(format!(
            "internal error: the planner produced an invalid schedule: {e}"
        ))
    })
}

/// One line that states the result, its bound and the gap.
pub fn summary_line(p: &TeamProblem<'_>, o: &TeamOutcome) -> String {
    let gap = o.gap(p.objective());
    match p.objective() {
        Objective::Makespan => format!(
            "makespan {:.1} s · lower bound {:.1} s · gap {:.1} s ({:.2} %) · {}",
            o.makespan_s,
            o.bound,
            gap,
            100.0 * gap / o.bound.max(1e-9),
            o.status
        ),
        Objective::Reward => format!(
            "reward {} by {} s · upper bound {} · gap {} · makespan {:.1} s · {}",
            o.reward,
            p.budget_s().unwrap_or(0.0),
            o.bound,
            gap,
            o.makespan_s,
            o.status
        ),
        Objective::Expected { hazard_per_hour } => format!(
            "expected reward {:.2} by {} s at {} failures/h per UAV · upper bound {:.2} · gap {:.2} · fault-free reward {} · makespan {:.1} s · {}",
            o.expected_reward.unwrap_or(0.0),
            p.budget_s().unwrap_or(0.0),
            hazard_per_hour,
            o.bound,
            gap,
            o.reward,
            o.makespan_s,
            o.status
        ),
    }
}

/// The schedule as a table.
pub fn schedule_table(p: &TeamProblem<'_>, c: &CheckedSchedule) -> String {
    let wall = p.wall();
    let o = &c.outcome;
    let mut out = format!(
        "wall {} ({} bricks) · objective {} · model {}{} · {} UAVs · {:.1} ms · {} schedules decoded\n",
        wall.name(),
        wall.len(),
        p.objective(),
        p.model().name,
        p.model()
            .concurrency
            .metric()
            .map_or(String::new(), |m| format!(" (distance {m})")),
        p.uavs(),
        o.stats.elapsed.as_secs_f64() * 1e3,
        o.stats.decodes
    );
    out.push_str("  start (s)    end (s)   brick  type    level  UAVs\n");
    for pl in o.schedule.iter().flat_map(|s| &s.placements) {
        let b = wall.brick(pl.brick);
        let uavs: Vec<String> = pl.uavs.iter().map(|u| u.to_string()).collect();
        out.push_str(&format!(
            "{:>11.1} {:>10.1}  {:>6}  {:<6}  {:>5}  {}\n",
            pl.start_s,
            pl.start_s + p.place_s(pl.brick),
            b.label,
            b.kind.name(),
            b.level,
            uavs.join("+")
        ));
    }
    out.push_str(&format!(
        "{} of {} bricks · {} (checked by order::validate_schedule)\n",
        c.evaluation.bricks,
        wall.len(),
        summary_line(p, o)
    ));
    out
}

/// Plans (and validates) the schedule a mission flies ([`mason_mission::flight_plan`]).
/// Bricks the schedule leaves out (after the budget) follow in `base`'s order, so that the
/// mission can still finish the wall.
pub fn flight_plan(
    wall: &Wall,
    cost: &CostModel,
    req: &ScheduleRequest,
    base: &[BrickId],
) -> CliResult<FlightPlan> {
    let request = FlightRequest {
        objective: req.objective,
        uavs: req.uavs,
        budget_s: req.budget_s,
        seed: req.seed,
    };
    mason_mission::flight_plan(wall, cost, &request, base, &search_budget(req.time_limit)).map_err(
        |e| match e {
            FlightPlanError::InvalidSchedule(e) => input_error(format!(
                "internal error: the planner produced an invalid schedule: {e}"
            )),
            e => input_error(e.to_string()),
        },
    )
}
