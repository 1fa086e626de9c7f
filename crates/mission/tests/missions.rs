//! Mission scenarios, with `check_trace` as the oracle on every run.

use mason_mission::{
    check_trace, make_policy, simulate, slot_length, trace_violations, Coord, Event, EventKind,
    MissionConfig, MissionInput, MissionResult, MissionStatus, TraceError, UavFailure, Window,
};
use mason_order::{BuildProblem, CostModel, PlannerSpec};
use mason_wall::Wall;
use proptest::prelude::*;

fn wall(name: &str) -> Wall {
    mason_wall::builtin(name).unwrap().wall()
}

fn exact_order(wall: &Wall, model: &CostModel) -> Vec<mason_wall::BrickId> {
    let p = BuildProblem::new(wall, model.clone()).unwrap();
    PlannerSpec::Exact
        .plan(&p, &mason_order::Budget::unlimited())
        .order
        .unwrap()
}

fn fly(
    wall: &Wall,
    config: &MissionConfig,
    coord: Coord,
    seed: u64,
) -> (MissionResult, Vec<Event>) {
    let model = CostModel::default();
    let order = exact_order(wall, &model);
    let input = MissionInput {
        wall,
        order: &order,
        model: &model,
        assignment: None,
        replanner: None,
        config,
    };
    let slot = slot_length(wall, &model, config).unwrap();
    let mut trace = Vec::new();
    let r = simulate(input, make_policy(coord, slot).as_mut(), seed, &mut trace);
    let summary = check_trace(wall, config.uavs, &trace);
    assert!(summary.is_ok(), "{coord:?} seed {seed}: {summary:?}");
    let all = trace_violations(wall, config.uavs, &trace);
    assert!(all.is_empty(), "{coord:?} seed {seed}: {all:?}");
    (r, trace)
}

const COORDS: [Coord; 3] = [Coord::Comm, Coord::Windows, Coord::Auto];

#[test]
fn same_seed_same_trace_bit_for_bit() {
    let w = wall("mbzirc");
    let mut config = MissionConfig::with_uavs(3);
    config.faults.grasp_fail = 0.2;
    config.faults.detect_fail = 0.1;
    config.faults.msg_loss = 0.3;
    config.faults.uav_hazard = 2.0;
    for coord in COORDS {
        let (a, ta) = fly(&w, &config, coord, 42);
        let (b, tb) = fly(&w, &config, coord, 42);
        assert_eq!(ta, tb);
        assert_eq!(
            serde_json::to_string(&ta).unwrap(),
            serde_json::to_string(&tb).unwrap()
        );
        assert_eq!(a, b);
        let (_, tc) = fly(&w, &config, coord, 43);
        assert_ne!(ta, tc, "a different seed changes the run");
    }
}

#[test]
fn fault_free_missions_complete_and_windows_is_not_faster() {
    for name in ["thesis-2x5", "levels5-width5", "levels5-width10", "mbzirc"] {
        let w = wall(name);
        let config = MissionConfig::with_uavs(3);
        let (comm, _) = fly(&w, &config, Coord::Comm, 1);
        let (windows, _) = fly(&w, &config, Coord::Windows, 1);
        let (auto, _) = fly(&w, &config, Coord::Auto, 1);
        for r in [&comm, &windows, &auto] {
            assert_eq!(r.status, MissionStatus::Complete, "{name}");
            assert_eq!(r.metrics.bricks_placed, w.len());
        }
        let (c, wi) = (
            comm.metrics.makespan_s.unwrap(),
            windows.metrics.makespan_s.unwrap(),
        );
        assert!(wi >= c, "{name}: windows {wi} < comm {c}");
        assert_eq!(
            auto.metrics.makespan_s, comm.metrics.makespan_s,
            "{name}: auto without faults is comm"
        );
    }
}

#[test]
fn windows_is_not_faster_on_average_with_grasp_faults() {
    let w = wall("mbzirc");
    let mut config = MissionConfig::with_uavs(3);
    config.faults.grasp_fail = 0.2;
    let mean = |coord| {
        let spans: Vec<f64> = (0..40)
            .map(|s| fly(&w, &config, coord, s).0.metrics.makespan_s.unwrap())
            .collect();
        spans.iter().sum::<f64>() / spans.len() as f64
    };
    let (c, wi) = (mean(Coord::Comm), mean(Coord::Windows));
    assert!(wi >= c, "windows {wi} < comm {c}");
}

#[test]
fn a_uav_failing_mid_mission_leaves_a_wall_the_others_finish() {
    let w = wall("mbzirc");
    for coord in COORDS {
        for at in [30.0, 200.0, 611.0] {
            let mut config = MissionConfig::with_uavs(3);
            config.faults.uav_fail = vec![UavFailure { uav: 1, at }];
            let (r, trace) = fly(&w, &config, coord, 5);
            assert_eq!(r.status, MissionStatus::Complete, "{coord:?} fail at {at}");
            assert_eq!(r.metrics.uavs_failed, 1);
            assert!(trace
                .iter()
                .any(|e| e.uav == 1 && e.kind == EventKind::Fail));
            // UAV 1 places nothing after it failed.
            assert!(!trace
                .iter()
                .any(|e| e.uav == 1 && e.t > at && matches!(e.kind, EventKind::Place { .. })));
        }
    }
}

#[test]
fn orange_bricks_are_always_carried_by_a_pair() {
    let w = wall("mbzirc");
    let mut config = MissionConfig::with_uavs(3);
    config.faults.grasp_fail = 0.1;
    for coord in COORDS {
        for seed in 0..10 {
            let (_, trace) = fly(&w, &config, coord, seed);
            let mut oranges = 0;
            for (i, e) in trace.iter().enumerate() {
                if let EventKind::Place { brick } = e.kind {
                    if w.brick(brick).kind.uavs_needed() == 2 {
                        oranges += 1;
                        // Two UAVs entered the zone for it and both grasped it.
                        let grasps = trace[..i]
                            .iter()
                            .filter(|g| g.kind == EventKind::Grasp { brick })
                            .count();
                        assert!(grasps >= 2, "orange {brick:?} grasped by {grasps}");
                        let leaves = trace[i..]
                            .iter()
                            .take_while(|x| x.t == e.t)
                            .filter(|x| x.kind == EventKind::ZoneLeave)
                            .count();
                        assert_eq!(leaves, 2, "orange {brick:?} leaves the zone as a pair");
                    }
                }
            }
            assert!(oranges > 0);
        }
    }
}

#[test]
fn auto_switches_to_windows_in_a_blackout_and_back() {
    let w = wall("mbzirc");
    let mut config = MissionConfig::with_uavs(3);
    config.faults.blackout = vec![Window {
        from: 100.0,
        to: 220.0,
    }];
    let (r, trace) = fly(&w, &config, Coord::Auto, 3);
    assert_eq!(r.status, MissionStatus::Complete);
    let modes: Vec<(f64, u32, String)> = trace
        .iter()
        .filter_map(|e| match e.kind {
            EventKind::Comm { mode } => Some((e.t, e.uav, format!("{mode:?}"))),
            _ => None,
        })
        .collect();
    for u in 0..3 {
        let mine: Vec<_> = modes.iter().filter(|m| m.1 == u).collect();
        assert_eq!(mine.len(), 2, "UAV {u}: {mine:?}");
        assert_eq!(mine[0].2, "Windows");
        assert!(mine[0].0 > 100.0 && mine[0].0 < 110.0);
        assert_eq!(mine[1].2, "Comm");
        assert!(mine[1].0 >= 220.0 && mine[1].0 < 225.0);
    }
    // Pure comm waits out the blackout; auto does not lose more than that.
    let (c, _) = fly(&w, &config, Coord::Comm, 3);
    assert_eq!(c.status, MissionStatus::Complete);
    let (auto, comm) = (
        r.metrics.makespan_s.expect("auto completed"),
        c.metrics.makespan_s.expect("comm completed"),
    );
    assert!(
        auto <= comm + 1e-9,
        "auto {auto} s against comm {comm} s through the same blackout"
    );
}

#[test]
fn check_trace_rejects_a_shared_zone_and_a_premature_placement() {
    let w = wall("thesis-2x5");
    let config = MissionConfig::with_uavs(3);
    let (_, trace) = fly(&w, &config, Coord::Comm, 0);
    assert!(trace_violations(&w, 3, &trace).is_empty());
    // Forge: a second UAV, which holds a brick, enters while the first is inside.
    let i = trace
        .iter()
        .position(|e| e.kind == EventKind::ZoneEnter)
        .unwrap();
    let (other, _) = trace[..i]
        .iter()
        .rev()
        .find_map(|e| match e.kind {
            EventKind::Grasp { brick } if e.uav != trace[i].uav => Some((e.uav, brick)),
            _ => None,
        })
        .expect("another UAV holds a brick when the first enters the zone");
    let mut forged = trace.clone();
    let mut e = forged[i];
    e.uav = other;
    forged.insert(i + 1, e);
    assert_eq!(
        check_trace(&w, 3, &forged),
        Err(TraceError::ZoneShared {
            t: e.t,
            a: trace[i].uav,
            b: other
        })
    );
    // Forge: drop the first placement, so that a later brick lands before its support.
    let mut forged = trace.clone();
    let first = forged
        .iter()
        .position(|e| matches!(e.kind, EventKind::Place { .. }))
        .unwrap();
    let EventKind::Place { brick: dropped } = forged.remove(first).kind else {
        unreachable!()
    };
    let label = w.brick(dropped).label;
    let found = trace_violations(&w, 3, &forged);
    assert!(
        found
            .iter()
            .any(|e| matches!(e, TraceError::Precedence { support, .. } if *support == label)),
        "{found:?}"
    );
    assert!(check_trace(&w, 3, &forged).is_err());
}

/// 150 random missions in CI; the stress command sets more:
/// `MASON_STRESS_CASES=5000 cargo test --release -p mason-mission --test missions random_faulty`.
fn stress_cases() -> u32 {
    std::env::var("MASON_STRESS_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(150)
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: stress_cases(),
        rng_seed: proptest::test_runner::RngSeed::Fixed(0x6d69_7373),
        ..ProptestConfig::default()
    })]

    /// `check_trace` passes on random fault-injected missions with every policy.
    #[test]
    fn random_faulty_missions_pass_check_trace(
        name in prop::sample::select(vec!["thesis-2x5", "levels5-width5", "mbzirc"]),
        coord in prop::sample::select(COORDS.to_vec()),
        uavs in 1usize..=4,
        grasp in 0.0f64..0.6,
        detect in 0.0f64..0.4,
        loss in 0.0f64..0.8,
        latency in 0.0f64..3.0,
        hazard in 0.0f64..6.0,
        fail in prop::option::of((0usize..4, 0.0f64..900.0)),
        blackout in prop::option::of((0.0f64..600.0, 1.0f64..300.0)),
        seed in any::<u64>(),
    ) {
        let w = wall(name);
        let mut config = MissionConfig::with_uavs(uavs);
        config.faults.grasp_fail = grasp;
        config.faults.detect_fail = detect;
        config.faults.msg_loss = loss;
        config.faults.latency = latency;
        config.faults.uav_hazard = hazard;
        config.max_time_s = 4000.0;
        if let Some((u, at)) = fail {
            if u < uavs {
                config.faults.uav_fail = vec![UavFailure { uav: u, at }];
            }
        }
        if let Some((from, len)) = blackout {
            config.faults.blackout = vec![Window { from, to: from + len }];
        }
        let (r, _) = fly(&w, &config, coord, seed);
        if r.metrics.uavs_failed == 0 && uavs >= 2 {
            prop_assert_eq!(r.status, MissionStatus::Complete);
        }
        prop_assert!(r.metrics.bricks_placed <= w.len());
    }
}

/// The MBZIRC makespan schedule's flight plan (planned and validated by `flight_plan`).
fn makespan_plan(w: &Wall, model: &CostModel) -> mason_mission::FlightPlan {
    let request = mason_mission::FlightRequest {
        objective: mason_order::schedule::Objective::Makespan,
        uavs: 3,
        budget_s: None,
        seed: 0,
    };
    let base: Vec<_> = w.ids().collect();
    mason_mission::flight_plan(w, model, &request, &base, &mason_order::Budget::nodes(300)).unwrap()
}

/// Flies the MBZIRC makespan schedule; every replan must pass `validate_continuation`.
fn fly_schedule(
    w: &Wall,
    config: &MissionConfig,
    replan: bool,
    seed: u64,
) -> (MissionResult, Vec<Event>) {
    let model = CostModel::default();
    let mason_mission::FlightPlan { team, order, lists } = makespan_plan(w, &model);
    let replanner = mason_mission::ScheduleReplanner {
        time_limit: std::time::Duration::from_secs(60), // deterministic: the node cap decides
        ..mason_mission::ScheduleReplanner::new(
            team,
            mason_order::schedule::Objective::Makespan,
            None,
            0,
        )
    };
    let input = MissionInput {
        wall: w,
        order: &order,
        model: &model,
        assignment: Some(&lists),
        replanner: replan.then_some(&replanner as &dyn mason_mission::Replanner),
        config,
    };
    let slot = slot_length(w, &model, config).unwrap();
    let mut trace = Vec::new();
    let r = simulate(
        input,
        make_policy(Coord::Comm, slot).as_mut(),
        seed,
        &mut trace,
    );
    let summary = check_trace(w, config.uavs, &trace);
    assert!(summary.is_ok(), "seed {seed}: {summary:?}");
    assert_eq!(
        replanner.rejected.into_inner(),
        0,
        "seed {seed}: a replan failed validation"
    );
    (r, trace)
}

#[test]
fn survivors_replan_when_a_uav_fails_and_finish_sooner() {
    let w = wall("mbzirc");
    let mut config = MissionConfig::with_uavs(3);
    config.faults.uav_fail = vec![UavFailure { uav: 1, at: 300.0 }];
    let (fixed, fixed_trace) = fly_schedule(&w, &config, false, 0);
    let (re, re_trace) = fly_schedule(&w, &config, true, 0);
    assert_eq!(re.status, MissionStatus::Complete);
    assert!(!fixed_trace
        .iter()
        .any(|e| matches!(e.kind, EventKind::Replan { .. })));
    let replans: Vec<&Event> = re_trace
        .iter()
        .filter(|e| matches!(e.kind, EventKind::Replan { .. }))
        .collect();
    assert_eq!(replans.len(), 1);
    assert_eq!(replans[0].t, 300.0);
    assert_eq!(re.metrics.replans, 1);
    // Measured: 1925 s re-planned against 2321 s static on this seed.
    assert!(re.metrics.makespan_s.unwrap() < fixed.metrics.makespan_s.unwrap());
    // Deterministic with a node cap.
    let (_, again) = fly_schedule(&w, &config, true, 0);
    assert_eq!(re_trace, again);
}

#[test]
fn replanned_missions_under_random_failures_pass_check_trace() {
    let w = wall("mbzirc");
    let mut config = MissionConfig::with_uavs(3);
    config.faults.uav_hazard = 3.0;
    config.faults.grasp_fail = 0.1;
    for seed in 0..20 {
        fly_schedule(&w, &config, true, seed);
    }
}
