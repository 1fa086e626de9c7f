//! `mason check`: checks an artefact made by Mason or by another tool with the validator of
//! its domain, and reports the first broken rule (or, with `--all`, every one). Reading is
//! [`mason_io::artefacts`]; the rules are the validators' (`order::validate`,
//! `order::schedule::validate_schedule`, `mission::check_trace`, `crew::validate`) and their
//! `*_violations` twins.

use crate::fail::{input_error, no_solution, CliResult};
use crate::input::DesignArgs;
use mason_io::artefacts;
use std::fmt::{Debug, Display};
use std::path::{Path, PathBuf};

/// What to check.
#[derive(clap::Subcommand)]
pub enum CheckCommand {
    /// A build order: `plan --json` output or a list of brick ids (spaces, commas or newlines;
    /// `#` comments)
    Order(OrderArgs),
    /// A team schedule: `plan --objective … --json` output or a CSV of uav,brick,start[,end]
    /// rows (an optional header line)
    Schedule(ScheduleArgs),
    /// A mission trace: `simulate --json` output, `launch`'s trace.json, a JSON list of events
    /// in that schema, or an agent's trace file (one event per line)
    Trace(TraceArgs),
    /// A crew plan: `crew --json` output or a result file whose `solution=` line is followed by
    /// one `t:(x,y),(x,y),…` configuration per time step
    Crew(CrewCheckArgs),
}

/// `mason check`'s options.
#[derive(clap::Args)]
pub struct CheckArgs {
    /// List every violation (stdout, one per line) instead of stopping at the first
    #[arg(long, global = true)]
    pub all: bool,
    #[command(subcommand)]
    pub what: CheckCommand,
}

/// `mason check order`.
#[derive(clap::Args)]
pub struct OrderArgs {
    #[command(flatten)]
    pub design: DesignArgs,
    /// The build order
    pub plan: PathBuf,
    /// Cost model parameters (TOML); defaults are the thesis's
    #[arg(long)]
    pub model: Option<PathBuf>,
}

/// `mason check schedule`.
#[derive(clap::Args)]
pub struct ScheduleArgs {
    #[command(flatten)]
    pub design: DesignArgs,
    /// The schedule
    pub schedule: PathBuf,
    /// Team model: thesis, cmcp or a TOML file (default: the file's, else thesis)
    #[arg(long)]
    pub model: Option<String>,
    /// The distance rule's metric: xy (horizontal plane) or xyz (3-D) (default: the file's,
    /// else the model's)
    #[arg(long)]
    pub metric: Option<String>,
    /// Team size (default: the file's, else the largest UAV index plus one)
    #[arg(long, allow_negative_numbers = true)]
    pub uavs: Option<usize>,
    /// Budget T in seconds: bricks must be placed by T (default: the file's, else none)
    #[arg(long, allow_negative_numbers = true)]
    pub budget: Option<f64>,
}

/// `mason check trace`.
#[derive(clap::Args)]
pub struct TraceArgs {
    #[command(flatten)]
    pub design: DesignArgs,
    /// The trace
    pub trace: PathBuf,
    /// Team size (default: the file's, else the largest UAV index plus one)
    #[arg(long, allow_negative_numbers = true)]
    pub uavs: Option<usize>,
}

/// `mason check crew`.
#[derive(clap::Args)]
pub struct CrewCheckArgs {
    /// MovingAI .map file or occupancy PNG
    pub map: String,
    /// The plan
    pub plan: PathBuf,
    /// MovingAI scenario: the plan's starts and goals must be its first N agents' (N robots)
    #[arg(long)]
    pub scen: Option<PathBuf>,
    /// 4 or 8 (diagonals only past two free sides)
    #[arg(long, default_value = "8")]
    pub connectivity: String,
}

/// `mason check`.
pub fn run(a: CheckArgs) -> CliResult<()> {
    match a.what {
        CheckCommand::Order(o) => order(o, a.all),
        CheckCommand::Schedule(s) => schedule(s, a.all),
        CheckCommand::Trace(t) => trace(t, a.all),
        CheckCommand::Crew(c) => crew(c, a.all),
    }
}

/// Exit 1 naming the first violation; with `all`, every one listed on stdout first.
fn broken<E: Debug + Display>(file: &Path, all: bool, found: &[E]) -> CliResult<()> {
    let Some(first) = found.first() else {
        return Ok(());
    };
    if all {
        for e in found {
            println!("{}: {e}", artefacts::rule(e));
        }
        return Err(no_solution(format!(
            "{}: {} violation(s); the first: {}: {first}",
            file.display(),
            found.len(),
            artefacts::rule(first)
        )));
    }
    Err(no_solution(format!(
        "{}: breaks {}: {first}",
        file.display(),
        artefacts::rule(first)
    )))
}

/// A number as a person writes it: plain when short, scientific when huge.
fn short(x: f64) -> String {
    if x.abs() < 1e12 {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

/// `x` beside what the file states, when it states something.
fn beside<T: Display>(x: T, stated: Option<T>) -> String {
    match stated {
        Some(s) => format!("{x} (file: {s})"),
        None => x.to_string(),
    }
}

fn order(a: OrderArgs, all: bool) -> CliResult<()> {
    let wall = a.design.load()?;
    let model = mason_io::load_model(a.model.as_deref())?;
    let file = artefacts::read_order(&a.plan, &wall)?;
    let eval = match file.check(&wall, &model, all) {
        Ok(eval) => eval,
        Err(found) => return broken(&a.plan, all, &found),
    };
    println!(
        "{}: valid build order ({}) of the {} bricks of {} · total cost {} (recomputed with {})",
        a.plan.display(),
        file.format,
        wall.len(),
        wall.name(),
        beside(
            format!("{:.3}", eval.total_cost),
            file.total_cost.map(|c| format!("{c:.3}"))
        ),
        a.model
            .as_ref()
            .map_or("the thesis's cost model".to_string(), |m| m
                .display()
                .to_string())
    );
    Ok(())
}

fn schedule(a: ScheduleArgs, all: bool) -> CliResult<()> {
    let wall = a.design.load()?;
    let file = artefacts::read_schedule(&a.schedule, &wall)?;
    let setting = file.setting(
        &a.schedule,
        a.model.as_deref(),
        a.metric.as_deref(),
        a.uavs,
        a.budget,
    )?;
    let eval = match file.check(&wall, &setting, all) {
        Ok(eval) => eval,
        Err(found) => return broken(&a.schedule, all, &found),
    };
    let (model, uavs, budget) = (&setting.model, setting.uavs, setting.budget_s);
    println!(
        "{}: valid team schedule ({}) · {} of {} bricks placed · reward {} · makespan {} (recomputed) · model {}{}, {} UAVs, budget {}",
        a.schedule.display(),
        file.format,
        eval.bricks,
        wall.len(),
        beside(short(eval.reward), file.claims.reward.map(short)),
        beside(
            format!("{} s", short(eval.makespan_s)),
            file.claims.makespan_s.map(|m| format!("{} s", short(m)))
        ),
        model.name,
        model
            .concurrency
            .metric()
            .map_or(String::new(), |m| format!(" (distance {m})")),
        uavs,
        budget.map_or("none".to_string(), |t| format!("{t} s"))
    );
    Ok(())
}

fn trace(a: TraceArgs, all: bool) -> CliResult<()> {
    use mason_order::schedule::MAX_UAVS;
    let wall = a.design.load()?;
    let text = mason_io::read_input_text(&a.trace, mason_fleet::MAX_TRACE_BYTES)?;
    let file = if artefacts::is_json_lines(&text) {
        let events = mason_fleet::parse_trace(&text, &a.trace, false)
            .map_err(|e| input_error(e.to_string()))?;
        // One event per line: event i is on line i + 1.
        if let Some((i, e)) = (events.iter().enumerate()).find(|(_, e)| e.uav as usize >= MAX_UAVS)
        {
            return Err(input_error(format!(
                "{}:{}: UAV {}: a team has at most {MAX_UAVS} UAVs",
                a.trace.display(),
                i + 1,
                e.uav
            )));
        }
        let uavs = events.iter().map(|e| e.uav as usize + 1).max().unwrap_or(1);
        artefacts::TraceFile {
            events,
            uavs,
            claimed_check: None,
            format: "agent trace file",
        }
    } else {
        artefacts::parse_trace_json(&text, &a.trace, &wall)?
    };
    let uavs = a.uavs.unwrap_or(file.uavs);
    if uavs == 0 || uavs > MAX_UAVS {
        return Err(input_error(format!(
            "--uavs {uavs}: expected 1 to {MAX_UAVS}"
        )));
    }
    let summary = match file.check(&wall, uavs, all) {
        Ok(s) => s,
        Err(found) => return broken(&a.trace, all, &found),
    };
    let last_place = file
        .events
        .iter()
        .filter(|e| matches!(e.kind, mason_mission::EventKind::Place { .. }))
        .map(|e| e.t)
        .fold(0.0, f64::max);
    println!(
        "{}: valid mission trace ({}) · {} events, {} UAVs · {} of {} bricks placed, {} lost, {} in flight at the end · last placement at {} s{}",
        a.trace.display(),
        file.format,
        file.events.len(),
        uavs,
        summary.placed,
        wall.len(),
        summary.lost,
        summary.in_flight,
        short(last_place),
        file.claimed_check
            .map(|c| format!(" · the file states check_trace: {c}"))
            .unwrap_or_default()
    );
    Ok(())
}

fn crew(a: CrewCheckArgs, all: bool) -> CliResult<()> {
    let conn: mason_crew::Connectivity = a
        .connectivity
        .parse()
        .map_err(|e| input_error(format!("--connectivity: {e}")))?;
    let grid = mason_io::load_grid(&a.map)?;
    let file = artefacts::read_crew_plan(&a.plan, &grid)?;
    let scenario = match &a.scen {
        Some(scen) => Some(mason_io::load_scenario(
            scen,
            &grid,
            Some(file.paths.len().max(1)),
        )?),
        None => None,
    };
    let inst = artefacts::crew_instance(
        &file,
        &grid,
        scenario.as_ref().map(|(s, g)| (s.as_slice(), g.as_slice())),
    );
    let (starts, goals) = (&inst.starts, &inst.goals);
    let metrics = match (
        inst.mismatches.first(),
        mason_crew::validate(&grid, conn, starts, goals, &file.paths),
    ) {
        (None, Ok(m)) => m,
        (first, result) => {
            let found = if all {
                let mut found = inst.mismatches.clone();
                found.extend(mason_crew::plan_violations(
                    &grid,
                    conn,
                    starts,
                    goals,
                    &file.paths,
                ));
                found
            } else {
                first
                    .cloned()
                    .into_iter()
                    .chain(result.err())
                    .take(1)
                    .collect()
            };
            return broken(&a.plan, all, &found);
        }
    };
    let found = mason_crew::claim_violations(&metrics, file.sum_of_costs, file.makespan);
    broken(&a.plan, all, &found)?;
    println!(
        "{}: valid crew plan ({}) · {} robots on {} ({}×{}, {}-connected){} · sum of costs {} · makespan {} (recomputed)",
        a.plan.display(),
        file.format,
        file.paths.len(),
        a.map,
        grid.width(),
        grid.height(),
        conn.degree(),
        if a.scen.is_some() { ", starts and goals of the scenario" } else { "" },
        beside(metrics.sum_of_costs, file.sum_of_costs),
        beside(metrics.makespan, file.makespan)
    );
    Ok(())
}
