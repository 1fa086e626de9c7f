//! The simulator's traces are a contract: refactoring the engine (issue #14 moved the per-UAV
//! decisions into `mission::core`) must not change one event. This test flies a matrix of
//! walls, team sizes, coordination policies, faults, seeds, shared orders and team schedules
//! (with and without a replanner), and compares a digest of every trace with
//! `tests/data/golden-traces.txt`, which the simulator wrote before that refactor (commit
//! c271a9e). A deliberate change of the simulator's behaviour re-writes the file with
//! `MASON_BLESS=1 cargo test -p mason-mission --test golden_traces` and says why in its commit.

use mason_mission::{
    make_policy, simulate, slot_length, Coord, Event, MissionConfig, MissionInput, UavFailure,
    Window,
};
use mason_order::{BuildProblem, CostModel, PlannerSpec};
use mason_wall::{BrickId, Wall};

/// FNV-1a, 64 bits: a stable digest that needs no dependency.
fn digest(bytes: &[u8]) -> u64 {
    bytes.iter().fold(0xcbf2_9ce4_8422_2325, |h, &b| {
        (h ^ u64::from(b)).wrapping_mul(0x0000_0100_0000_01b3)
    })
}

fn faults(which: usize, config: &mut MissionConfig) -> &'static str {
    let f = &mut config.faults;
    match which {
        0 => "none",
        1 => {
            f.grasp_fail = 0.25;
            f.detect_fail = 0.15;
            "grasp+detect"
        }
        2 => {
            f.msg_loss = 0.3;
            f.latency = 0.7;
            f.blackout = vec![Window {
                from: 40.0,
                to: 160.0,
            }];
            "loss+latency+blackout"
        }
        3 => {
            f.uav_fail = vec![UavFailure { uav: 0, at: 75.0 }];
            f.uav_hazard = 3.0;
            "fail+hazard"
        }
        _ => {
            f.grasp_fail = 0.2;
            f.detect_fail = 0.1;
            f.msg_loss = 0.2;
            f.latency = 0.3;
            f.blackout = vec![Window {
                from: 100.0,
                to: 130.0,
            }];
            f.uav_fail = vec![UavFailure { uav: 1, at: 140.0 }];
            f.uav_hazard = 1.0;
            "everything"
        }
    }
}

fn fly(
    w: &Wall,
    order: &[BrickId],
    lists: Option<&[Vec<BrickId>]>,
    replanner: Option<&dyn mason_mission::Replanner>,
    config: &MissionConfig,
    coord: Coord,
    seed: u64,
) -> Vec<Event> {
    let model = CostModel::default();
    let input = MissionInput {
        wall: w,
        order,
        model: &model,
        assignment: lists,
        replanner,
        config,
    };
    let slot = slot_length(w, &model, config).unwrap();
    let mut trace = Vec::new();
    simulate(input, make_policy(coord, slot).as_mut(), seed, &mut trace);
    trace
}

fn lines() -> Vec<String> {
    use mason_mission::{flight_plan, FlightRequest};
    use mason_order::schedule::Objective;
    let model = CostModel::default();
    let mut out = Vec::new();
    for name in ["thesis-2x5", "levels5-width5", "mbzirc"] {
        let w = mason_wall::builtin(name).unwrap().wall();
        let p = BuildProblem::new(&w, model.clone()).unwrap();
        let order = PlannerSpec::Exact
            .plan(&p, &mason_order::Budget::unlimited())
            .order
            .unwrap();
        for uavs in 1..=4 {
            for coord in [Coord::Comm, Coord::Windows, Coord::Auto] {
                for which in 0..5 {
                    for seed in 1..=3 {
                        let mut config = MissionConfig::with_uavs(uavs);
                        let label = faults(which, &mut config);
                        let trace = fly(&w, &order, None, None, &config, coord, seed);
                        let json = serde_json::to_string(&trace).unwrap();
                        out.push(format!(
                            "{name} uavs={uavs} {coord:?} {label} seed={seed} events={} {:016x}",
                            trace.len(),
                            digest(json.as_bytes())
                        ));
                    }
                }
            }
        }
        // A team schedule for three, flown with and without a replanner.
        let request = FlightRequest {
            objective: Objective::Makespan,
            uavs: 3,
            budget_s: None,
            seed: 0,
        };
        let plan = flight_plan(
            &w,
            &model,
            &request,
            &order,
            &mason_order::Budget::nodes(300),
        )
        .unwrap();
        let (sorder, lists) = (plan.order, plan.lists);
        let replanner = mason_mission::ScheduleReplanner {
            time_limit: std::time::Duration::from_secs(60), // the node cap decides
            ..mason_mission::ScheduleReplanner::new(plan.team, Objective::Makespan, None, 0)
        };
        for replan in [false, true] {
            for which in 0..5 {
                for seed in 1..=3 {
                    let mut config = MissionConfig::with_uavs(3);
                    let label = faults(which, &mut config);
                    let r = replan.then_some(&replanner as &dyn mason_mission::Replanner);
                    let trace = fly(&w, &sorder, Some(&lists), r, &config, Coord::Comm, seed);
                    let json = serde_json::to_string(&trace).unwrap();
                    out.push(format!(
                        "{name} schedule replan={replan} {label} seed={seed} events={} {:016x}",
                        trace.len(),
                        digest(json.as_bytes())
                    ));
                }
            }
        }
    }
    out
}

#[test]
fn traces_match_the_simulator_before_the_decision_core() {
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/golden-traces.txt");
    let got = lines();
    if std::env::var_os("MASON_BLESS").is_some() {
        std::fs::write(&path, got.join("\n") + "\n").unwrap();
        return;
    }
    let want = std::fs::read_to_string(&path).unwrap();
    let want: Vec<&str> = want.lines().collect();
    assert_eq!(want.len(), got.len(), "the matrix changed size");
    let differ: Vec<String> = want
        .iter()
        .zip(&got)
        .filter(|(w, g)| *w != g)
        .map(|(w, g)| format!("want {w}\n got {g}"))
        .collect();
    assert!(
        differ.is_empty(),
        "{} of {} traces changed:\n{}",
        differ.len(),
        got.len(),
        differ
            .iter()
            .take(10)
            .cloned()
            .collect::<Vec<_>>()
            .join("\n")
    );
}
