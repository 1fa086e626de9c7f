//! `mason bench thesis-mission` (the thesis's Table 5.1 setting) and `mason bench missions`
//! (simulator throughput).

use crate::support::{fly_many, fly_once, input_error, prepare, solve, BenchError, BenchResult};
use mason_mission::{summarise, Coord, MissionConfig, MissionInput};
use mason_order::Budget;
use mason_order::{BuildProblem, CostModel, PlannerSpec};
use mason_report::text::{clock, policy_table, spread_clock, PolicyRow};
use std::time::Instant;

/// The thesis's Table 5.1 mission times (Gazebo, 3 UAVs, the 2×5 wall of its Figure 5.5, with
/// communication), as published (`../shared/benchmarks/thesis`).
const THESIS_TABLE_5_1: [(&str, &str); 3] = [
    ("brute", "5:10"),
    ("greedy", "5:55"),
    ("improved:1,4", "5:40"),
];

/// `bench thesis-mission`.
pub fn thesis_mission(runs: usize) -> BenchResult<String> {
    if runs == 0 {
        return Err(input_error("--runs must be at least 1"));
    }
    let wall = mason_wall::builtin("thesis-2x5").expect("built-in").wall();
    let model = CostModel::default();
    let problem = BuildProblem::new(&wall, model.clone()).expect("valid model");
    let base = MissionConfig::with_uavs(3);
    let mut faulty = base.clone();
    faulty.faults.grasp_fail = 0.2;
    let slot = prepare(&wall, &model, &base)?;
    let mut text = format!(
        "Thesis Table 5.1 setting: the 2×5 wall, 3 UAVs, default arena (pile→wall flights take the\n\
         thesis's t_f), windows slot {slot:.0} s. `fault-free` is one deterministic run; `20% grasp\n\
         failures` is {runs} seeded runs (mean [p5, p95]). The thesis's column is its Table 5.1:\n\
         one Gazebo flight per plan, with communication.\n\n{:<14} {:<8} {:>11} {:>28}  {:>7}\n",
        "plan", "coord", "fault-free", "20% grasp failures", "thesis"
    );
    for (name, thesis) in THESIS_TABLE_5_1 {
        let spec: PlannerSpec = name.parse().expect("known planner");
        let checked = solve(&problem, spec, Some(60.0))?;
        let order = checked.outcome.order.clone().expect("an order");
        for coord in [Coord::Comm, Coord::Windows] {
            let flight = |config| MissionInput {
                wall: &wall,
                order: &order,
                model: &model,
                assignment: None,
                replanner: None,
                config,
            };
            let (r, _) = fly_once(flight(&base), coord, slot, 0)?;
            let many = fly_many(flight(&faulty), coord, slot, 0, runs)?;
            let s = summarise(&many);
            text.push_str(&format!(
                "{:<14} {:<8} {:>11} {:>28}  {:>7}\n",
                name,
                format!("{coord:?}").to_lowercase(),
                r.metrics.makespan_s.map_or("-".into(), clock),
                spread_clock(&s.makespan_s),
                if coord == Coord::Comm { thesis } else { "" }
            ));
        }
    }
    Ok(text)
}

/// `bench missions`: missions per second on the 42-brick MBZIRC wall with 3 UAVs, both cores.
pub fn throughput(runs: usize) -> BenchResult<String> {
    let missions = runs.max(1) * 1000;
    let wall = mason_wall::builtin("mbzirc").expect("built-in").wall();
    let model = CostModel::default();
    let problem = BuildProblem::new(&wall, model.clone()).expect("valid model");
    let order = solve(&problem, PlannerSpec::Exact, None)?
        .outcome
        .order
        .expect("an order");
    let mut text = format!(
        "Simulator throughput: {} ({} bricks), 3 UAVs, {missions} seeded missions per row on {} threads,\n\
         every trace checked by check_trace (included in the time).\n{:<8} {:<26} {:>10} {:>14}\n",
        wall.name(),
        wall.len(),
        rayon::current_num_threads(),
        "coord",
        "faults",
        "time",
        "missions/s"
    );
    let mut faulty = MissionConfig::with_uavs(3);
    faulty.faults.grasp_fail = 0.1;
    faulty.faults.msg_loss = 0.1;
    for (label, config) in [
        ("none", MissionConfig::with_uavs(3)),
        ("grasp 10%, msg loss 10%", faulty),
    ] {
        let slot = prepare(&wall, &model, &config)?;
        for coord in [Coord::Comm, Coord::Windows, Coord::Auto] {
            let started = Instant::now();
            let input = MissionInput {
                wall: &wall,
                order: &order,
                model: &model,
                assignment: None,
                replanner: None,
                config: &config,
            };
            let results = fly_many(input, coord, slot, 0, missions)?;
            let secs = started.elapsed().as_secs_f64();
            debug_assert_eq!(results.len(), missions);
            text.push_str(&format!(
                "{:<8} {:<26} {:>8.3} s {:>14.0}\n",
                format!("{coord:?}").to_lowercase(),
                label,
                secs,
                missions as f64 / secs
            ));
        }
    }
    Ok(text)
}

/// A replanner that records how long each replan took.
struct Timed<'a> {
    inner: &'a mason_mission::ScheduleReplanner,
    ms: std::sync::Mutex<Vec<f64>>,
}

impl mason_mission::Replanner for Timed<'_> {
    fn replan(
        &self,
        wall: &mason_wall::Wall,
        start: mason_order::schedule::TeamStart,
        now: f64,
    ) -> Option<mason_mission::Replan> {
        let t0 = Instant::now();
        let r = self.inner.replan(wall, start, now);
        let ms = t0.elapsed().as_secs_f64() * 1e3;
        self.ms.lock().expect("not poisoned").push(ms);
        r
    }
}

/// `bench replan`: static against re-planned team schedules on the MBZIRC wall, 3 UAVs, each
/// failing at 2 per hour, `runs` missions per row on seeds 0.., and how long the replans took.
pub fn replan(runs: usize) -> BenchResult<String> {
    use mason_order::schedule::Objective;
    if runs == 0 {
        return Err(input_error("--runs must be at least 1"));
    }
    let wall = mason_wall::builtin("mbzirc").expect("built-in").wall();
    let model = CostModel::default();
    let mut config = MissionConfig::with_uavs(3);
    config.faults.uav_hazard = 2.0;
    let slot = prepare(&wall, &model, &config)?;
    let base: Vec<_> = wall.ids().collect();
    let mut text = format!(
        "Re-planning: the MBZIRC wall ({} bricks), 3 UAVs failing at 2 per hour each, comm, {runs}\n\
         missions per policy on seeds 0..{}. Static: each UAV flies its list and helps with the\n\
         orphaned bricks; re-planned: the survivors re-plan at every failure.\n",
        wall.len(),
        runs - 1
    );
    for (objective, budget) in [
        (Objective::Makespan, None),
        (Objective::Reward, Some(1500.0)),
    ] {
        let request = mason_mission::FlightRequest {
            objective,
            uavs: 3,
            budget_s: budget,
            seed: 0,
        };
        let flight =
            mason_mission::flight_plan(&wall, &model, &request, &base, &Budget::unlimited())
                .map_err(|e| BenchError::Invalid(e.to_string()))?;
        let planner =
            mason_mission::ScheduleReplanner::new(flight.team.clone(), objective, budget, 0);
        let timed = Timed {
            inner: &planner,
            ms: std::sync::Mutex::new(Vec::new()),
        };
        let input = MissionInput {
            wall: &wall,
            order: &flight.order,
            model: &model,
            assignment: Some(&flight.lists),
            replanner: None,
            config: &config,
        };
        let fixed = fly_many(input, Coord::Comm, slot, 0, runs)?;
        let with = MissionInput {
            replanner: Some(&timed),
            ..input
        };
        let replanned = fly_many(with, Coord::Comm, slot, 0, runs)?;
        let rows = [
            PolicyRow::of("static", &fixed, budget),
            PolicyRow::of("replanned", &replanned, budget),
        ];
        let ms = timed.ms.into_inner().expect("not poisoned");
        let rejected = planner.rejected.load(std::sync::atomic::Ordering::Relaxed);
        if rejected > 0 {
            return Err(input_error(format!(
                "internal error: {rejected} replans failed order::schedule::validate_continuation"
            )));
        }
        let spread = mason_mission::Spread::of(&ms);
        let max = ms.iter().copied().fold(0.0, f64::max);
        text.push_str(&format!(
            "\n{} schedule{}\n{}replan time over {} replans (each checked by order::schedule::validate_continuation): mean {:.2} ms, p95 {:.2} ms, max {:.2} ms (deadline 100 ms)\n",
            objective,
            budget.map_or(String::new(), |t| format!(", budget {t} s")),
            policy_table(&rows, budget),
            ms.len(),
            spread.mean,
            spread.p95,
            max
        ));
    }
    Ok(text)
}
