//! `mason demo`: every built-in wall with every planner, a comparison table, and figures.

use crate::cmd::crew::run_solve;
use crate::cmd::mission::prepare;
use crate::cmd::plan::{solve, time_limit, Checked};
use crate::cmd::simulate::{fly_many, fly_once};
use crate::fail::{write_file, CliResult};
use mason_bench::search_limit;
use mason_crew::generate::{random_tasks, warehouse};
use mason_crew::{
    AssignMethod, Connectivity, CrewConfig, Instance, PathMethod, PrmConfig, Resolution,
};
use mason_mission::{summarise, Coord, MissionConfig, MissionInput, Window};
use mason_order::{BuildProblem, CostModel, PlannerSpec};
use mason_report::plan_json;
use mason_report::text::{clock, format_ms, spread_clock};
use mason_report::{pre, Section, Series};
use mason_wall::BUILTIN_WALLS;
use std::path::{Path, PathBuf};

/// The planners the demo and the thesis bench compare, in table order.
pub const COMPARED: [PlannerSpec; 5] = [
    PlannerSpec::Brute,
    PlannerSpec::Greedy,
    PlannerSpec::Improved { n: 1, k: 4 },
    PlannerSpec::Improved { n: 2, k: 3 },
    PlannerSpec::Exact,
];

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

/// `mason demo`'s options.
#[derive(clap::Args)]
pub struct DemoArgs {
    /// Output directory for figures and JSON
    #[arg(long, default_value = "mason-out")]
    pub out: PathBuf,
    /// Seconds brute force and improved greedy may search per wall
    #[arg(long, default_value_t = 2.0, allow_negative_numbers = true)]
    pub time_limit: f64,
}

/// `mason demo`: prints the summary and writes `out`.
pub fn run(a: DemoArgs, quiet: bool) -> CliResult<()> {
    let limit = time_limit(Some(a.time_limit))?.unwrap_or(2.0);
    print!("{}", demo(&a.out, limit, !quiet)?);
    Ok(())
}

/// Runs the demo; writes figures and plans under `out`.
pub fn demo(out: &Path, brute_limit: f64, show_progress: bool) -> CliResult<String> {
    // The demo's own output folder is made if missing (DESIGN §1); its parent must exist.
    crate::fail::check_output(&out.join("report.html")).or_else(|_| {
        std::fs::create_dir(out)
            .map_err(|e| crate::fail::input_error(format!("{}: {e}", out.display())))
    })?;
    let model = CostModel::default();
    let bar = crate::progress::bar(BUILTIN_WALLS.len() as u64 + 2, "demo", show_progress);
    let mut text = String::from(
        "Build orders for the built-in walls (thesis cost model, DESIGN §4).\n\
         Every order below was checked by order::validate; gap is against `exact`.\n",
    );
    let mut plans = Vec::new();
    let mut wall_figures = String::new();
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
        wall_figures.push_str(&svg);
        bar.inc(1);
    }
    let json = serde_json::to_string_pretty(&plans).expect("plans serialise");
    write_file(&out.join("plans.json"), json.as_bytes())?;
    text.push_str(&format!(
        "\n(brute and improved stop after {brute_limit} s and report `timeout` with their best order.)\n"
    ));
    let planning_text = text.clone();
    let (schedule_text, schedule_html) = schedules(&model, out)?;
    let (mission_text, mission_html) = missions(&model, out)?;
    bar.inc(1);
    let (crew_text, crew_html) = crew(out)?;
    bar.finish_and_clear();
    text.push_str(&schedule_text);
    text.push_str(&mission_text);
    text.push_str(&crew_text);
    let report = mason_report::report_page(
        "Mason demo report",
        "Everything below was produced by `mason demo` from built-in data; every plan and trace was checked by its validator.",
        &[
            Section {
                heading: "Build orders".into(),
                html: format!("{}{wall_figures}", pre(&planning_text)),
            },
            Section { heading: "Team schedules".into(), html: format!("{}{schedule_html}", pre(&schedule_text)) },
            Section { heading: "Missions".into(), html: format!("{}{mission_html}", pre(&mission_text)) },
            Section { heading: "Crew".into(), html: format!("{}{crew_html}", pre(&crew_text)) },
        ],
    );
    let report_path = out.join("report.html");
    write_file(&report_path, report.as_bytes())?;
    text.push_str(&format!(
        "\nwrote {} (figures, tables and replays), with wall-*.svg, schedule-*.svg, gantt-*.svg, reward.svg,\ncrew.svg, replay-mission.html, replay-crew.html and plans.json beside it\n",
        report_path.display()
    ));
    Ok(text)
}

/// Team schedules for the MBZIRC wall (thesis model, 3 UAVs): the whole wall, and the most
/// reward in 900 s, each with its bound; the makespan schedule flown against the `exact` order.
/// Returns the text and the report's figures.
fn schedules(model: &CostModel, out: &Path) -> CliResult<(String, String)> {
    use crate::cmd::schedule::{
        flight_plan, problem, solve as plan_team, summary_line, ScheduleRequest,
    };
    use mason_order::schedule::{Objective, TeamModel};
    let wall = mason_wall::builtin("mbzirc").expect("built-in").wall();
    let mut text = String::from(
        "\nTeam schedules: the MBZIRC wall, 3 UAVs, thesis model (the simulator's timings, zone rule);\nevery schedule checked by order::schedule::validate_schedule.\n",
    );
    let mut html = String::new();
    for (objective, budget, file) in [
        (Objective::Makespan, None, "schedule-makespan.svg"),
        (Objective::Reward, Some(900.0), "schedule-reward-900.svg"),
    ] {
        let req = ScheduleRequest::new(objective, 3, budget);
        let p = problem(&wall, TeamModel::from_cost_model(model), &req)?;
        let c = plan_team(&p, &req)?;
        text.push_str(&format!(
            "  {:<8} {}\n",
            objective.name(),
            summary_line(&p, &c.outcome)
        ));
        let title = format!("mbzirc — {objective} schedule, 3 UAVs, thesis model");
        let svg = mason_report::schedule_svg(
            &title,
            &p,
            c.outcome.schedule.as_ref().expect("a schedule"),
        );
        write_file(&out.join(file), svg.as_bytes())?;
        html.push_str(&svg);
    }
    let config = MissionConfig::with_uavs(3);
    let slot = prepare(&wall, model, &config)?;
    let problem_order = BuildProblem::new(&wall, model.clone()).expect("default model is valid");
    let exact = solve(&problem_order, PlannerSpec::Exact, None)?
        .outcome
        .order
        .expect("an order");
    let req = ScheduleRequest::new(Objective::Makespan, 3, None);
    let flight = flight_plan(&wall, model, &req, &exact)?;
    let fly = |order: &[mason_wall::BrickId], lists: Option<&[Vec<mason_wall::BrickId>]>| {
        let input = MissionInput {
            wall: &wall,
            order,
            model,
            assignment: lists,
            replanner: None,
            config: &config,
        };
        fly_once(input, Coord::Comm, slot, 0).map(|(r, _)| r.metrics.makespan_s)
    };
    let from_exact = fly(&exact, None)?;
    let from_schedule = fly(&flight.order, Some(&flight.lists))?;
    let show = |t: Option<f64>| t.map_or("-".into(), clock);
    text.push_str(&format!(
        "  flown fault-free with comm: the makespan schedule {} against the exact order {}\n",
        show(from_schedule),
        show(from_exact)
    ));
    Ok((text, html))
}

/// The mission comparison: 3 UAVs fly the exact order of two walls under each policy.
/// Returns the text and the report's figures.
fn missions(model: &CostModel, out: &Path) -> CliResult<(String, String)> {
    let mut html = String::new();
    let mut text = String::from(
        "\nMissions: 3 UAVs fly the exact order (DESIGN §5). `clean` is one fault-free run; `faults` is\n\
         200 seeded runs with 10% grasp failures, 10% message loss and a blackout from 120 to 240 s\n\
         (mean [p5, p95] makespan). Every trace was checked by mission::check_trace.\n",
    );
    for name in ["thesis-2x5", "mbzirc"] {
        let wall = mason_wall::builtin(name).expect("built-in").wall();
        let problem = BuildProblem::new(&wall, model.clone()).expect("valid model");
        let order = solve(&problem, PlannerSpec::Exact, None)?
            .outcome
            .order
            .expect("an order");
        let clean = MissionConfig::with_uavs(3);
        let mut faulty = clean.clone();
        faulty.faults.grasp_fail = 0.1;
        faulty.faults.msg_loss = 0.1;
        faulty.faults.blackout = vec![Window {
            from: 120.0,
            to: 240.0,
        }];
        let slot = prepare(&wall, model, &clean)?;
        text.push_str(&format!(
            "\n{name} ({} bricks)\n  {:<8} {:>9} {:>30}\n",
            wall.len(),
            "coord",
            "clean",
            "faults"
        ));
        let flight = |config| MissionInput {
            wall: &wall,
            order: &order,
            model,
            assignment: None,
            replanner: None,
            config,
        };
        let mut rewards = Vec::new();
        for coord in [Coord::Comm, Coord::Windows, Coord::Auto] {
            let (r, _) = fly_once(flight(&clean), coord, slot, 0)?;
            if name == "mbzirc" {
                let (f, trace) = fly_once(flight(&faulty), coord, slot, 0)?;
                let label = format!("{coord:?}").to_lowercase();
                let title = format!("{name} — 3 UAVs, {label}, faults (seed 0)");
                let gantt = mason_report::gantt_svg(&title, &wall, 3, &trace, f.metrics.end_s);
                write_file(&out.join(format!("gantt-{label}.svg")), gantt.as_bytes())?;
                html.push_str(&gantt);
                if coord == Coord::Auto {
                    let page = mason_report::mission_replay_html(
                        &title,
                        &wall,
                        &faulty.arena,
                        3,
                        &trace,
                        f.metrics.end_s,
                    );
                    write_file(&out.join("replay-mission.html"), page.as_bytes())?;
                }
                rewards.push((label, f.metrics.reward_over_time.clone()));
            }
            let s = summarise(&fly_many(flight(&faulty), coord, slot, 0, 200)?);
            text.push_str(&format!(
                "  {:<8} {:>9} {:>30}\n",
                format!("{coord:?}").to_lowercase(),
                r.metrics.makespan_s.map_or("-".into(), clock),
                spread_clock(&s.makespan_s)
            ));
        }
        if !rewards.is_empty() {
            let series: Vec<Series<'_>> = rewards
                .iter()
                .map(|(l, p)| Series {
                    label: l,
                    points: p,
                })
                .collect();
            let total: f64 = wall.bricks().iter().map(|b| b.kind.default_reward()).sum();
            let svg = mason_report::reward_svg(
                &format!("{name} — reward over time with faults (seed 0)"),
                &series,
                total,
            );
            write_file(&out.join("reward.svg"), svg.as_bytes())?;
            html.push_str(&svg);
        }
    }
    html.push_str("<h3>Replay (auto, with faults)</h3><p><a href=\"replay-mission.html\">open the replay on its own page</a></p><iframe src=\"replay-mission.html\"></iframe>");
    Ok((text, html))
}

/// The crew scenario: 40 robots in a generated warehouse, the paper's method against ours.
/// Returns the text and the report's figures.
fn crew(out: &Path) -> CliResult<(String, String)> {
    let mut html = String::new();
    let grid = warehouse(160, 100, 0.005, 7);
    let (robots, goals) = random_tasks(&grid, 40, 7);
    let inst = Instance::new(
        grid,
        Connectivity::Eight,
        robots,
        goals,
        None,
        "demo warehouse",
    )
    .expect("valid instance");
    let mut text = format!(
        "\nCrew: 40 robots in a 160×100 warehouse ({} free cells), Hungarian assignment, 8-connected.\n  {:<22} {:<11} {:>12} {:>10} {:>10}\n",
        inst.grid.free_count(),
        "method",
        "status",
        "sum of costs",
        "makespan",
        "time"
    );
    let mut best = None;
    for (label, paths, resolve) in [
        ("prm + paper waits", PathMethod::Prm, Resolution::Paper),
        ("astar + paper waits", PathMethod::Astar, Resolution::Paper),
        ("astar + st (ours)", PathMethod::Astar, Resolution::St),
        ("lacam, 200 rounds", PathMethod::Astar, Resolution::Lacam),
    ] {
        let mut config = CrewConfig {
            assign: AssignMethod::Hungarian,
            paths,
            resolve,
            prm: PrmConfig::default(),
            ..CrewConfig::default()
        };
        // A fixed number of refinement rounds keeps the demo the same on every machine.
        config.refine.rounds = Some(200);
        config.refine.stall = None;
        let r = run_solve(&inst, &config, Some(60.0))?;
        text.push_str(&format!(
            "  {:<22} {:<11} {:>12} {:>10} {:>10}\n",
            label,
            r.outcome.status.to_string(),
            r.metrics.map_or("-".into(), |m| m.sum_of_costs.to_string()),
            r.metrics.map_or("-".into(), |m| m.makespan.to_string()),
            format_ms(r.outcome.stats.elapsed.as_secs_f64() * 1e3)
        ));
        if r.outcome.paths.is_some() {
            best = Some((label, r));
        }
    }
    if let Some((label, r)) = best {
        let title = format!("demo warehouse — 40 robots, {label}");
        let svg = mason_report::crew_svg(
            &title,
            &inst.grid,
            &inst.robots,
            &r.outcome.goals,
            r.outcome.paths.as_deref().unwrap_or_default(),
        );
        write_file(&out.join("crew.svg"), svg.as_bytes())?;
        html.push_str(&svg);
        let page = mason_report::crew_replay_html(
            &title,
            &inst.grid,
            &r.outcome.goals,
            r.outcome.paths.as_deref().unwrap_or_default(),
        );
        write_file(&out.join("replay-crew.html"), page.as_bytes())?;
        html.push_str("<h3>Replay</h3><p><a href=\"replay-crew.html\">open the replay on its own page</a></p><iframe src=\"replay-crew.html\"></iframe>");
    }
    text.push_str(
        "  (every plan was checked by crew::validate; a failed method shows its status)\n",
    );
    Ok((text, html))
}
