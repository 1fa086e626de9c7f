//! The cost of the check on arrival (issue #27: under 5 µs per message): one agent of a
//! three-UAV team on the MBZIRC wall checks a teammate's mid-mission status again and again,
//! as bytes off the network (decoded and checked, as over Zenoh) and as a message (checked
//! only, as on the in-process bus), and a mix of hostile samples that are dropped.
//!
//! The samples are made before the timed loops; each loop copies one sample per check (the
//! copy a transport makes anyway) and counts it in the time.

use crate::support::BenchResult;
use mason_mission::agent::{
    Agent, AgentSetup, Arrival, SampleKey, SimulatedVehicle, DEFAULT_DEAD_AFTER_S, DEFAULT_LEASE_S,
};
use mason_mission::{slot_length, Coord, MissionConfig};
use mason_order::{BuildProblem, CostModel, PlannerSpec};
use std::time::Instant;

/// Mission time of the samples and of the receiver (s).
const NOW: f64 = 600.0;

/// Checks `samples` in turn `checks` times on `agent`; returns µs per check and how many
/// passed.
fn time_checks(agent: &mut Agent<'_>, samples: &[Arrival], checks: usize) -> (f64, usize) {
    let started = Instant::now();
    let mut passed = 0;
    for i in 0..checks {
        let sample = samples[i % samples.len()].clone();
        passed += usize::from(agent.admit(NOW, sample).is_ok());
    }
    (
        started.elapsed().as_secs_f64() * 1e6 / checks as f64,
        passed,
    )
}

/// `mason bench arrivals`: µs per message checked on arrival, `runs` × 100 000 checks a row.
pub fn arrivals(runs: usize) -> BenchResult<String> {
    let checks = runs.max(1) * 100_000;
    let wall = mason_wall::builtin("mbzirc").expect("built-in").wall();
    let model = CostModel::default();
    let problem = BuildProblem::new(&wall, model.clone()).expect("valid model");
    let order = PlannerSpec::Exact
        .plan(&problem, &mason_order::Budget::unlimited())
        .order
        .expect("an order");
    let config = MissionConfig::with_uavs(3);
    let slot = slot_length(&wall, &model, &config).expect("a slot");
    let setup = |uav| AgentSetup {
        wall: &wall,
        order: &order,
        assignment: None,
        model: &model,
        config: &config,
        coord: Coord::Auto,
        slot_s: slot,
        uav,
        mission: "bench",
        incarnation: 1,
        dead_after_s: DEFAULT_DEAD_AFTER_S,
        lease_s: DEFAULT_LEASE_S,
    };
    let agent = |uav| Agent::new(setup(uav), Box::new(SimulatedVehicle::new(&config, 1)));
    // UAV 1's status half way through the wall: 21 bricks placed, an acknowledgement.
    let mut sender = agent(1);
    let mut m = sender.tick(NOW).messages.pop().expect("a message");
    m.status.placed = (0..21).collect();
    m.status.acks = vec![mason_mission::agent::Ack {
        uav: 2,
        incarnation: 1,
        id: 4,
    }];
    let bytes = serde_json::to_vec(&m).expect("a message serialises");
    let key = SampleKey::of(&m);
    let honest_bytes = [Arrival::bytes(Some(key.clone()), bytes.clone())];
    let honest = [Arrival::keyed(m.clone())];
    let mut hostile = Vec::new();
    for (i, f) in [
        |m: &mut mason_mission::agent::Message| m.uav = 7,
        |m: &mut mason_mission::agent::Message| m.seq = u64::MAX,
        |m: &mut mason_mission::agent::Message| m.t = -1e6,
        |m: &mut mason_mission::agent::Message| m.status.heard.push(0.0),
    ]
    .into_iter()
    .enumerate()
    {
        let mut x = m.clone();
        f(&mut x);
        let b = serde_json::to_vec(&x).expect("serialises");
        hostile.push(Arrival::bytes(Some(SampleKey::of(&x)), b));
        // And a sample that is not a message.
        hostile.push(Arrival::bytes(
            None,
            format!("{{\"v\":1,\"junk\":{i}").into_bytes(),
        ));
    }
    let mut text = format!(
        "The check on arrival: one agent of 3 on {} ({} bricks), {checks} checks per row,\n\
         one sample of {} bytes (21 bricks placed); target < 5 µs per message.\n{:<40} {:>10} {:>8}\n",
        wall.name(),
        wall.len(),
        bytes.len(),
        "sample",
        "µs/check",
        "passed"
    );
    let rows: [(&str, &[Arrival]); 3] = [
        ("honest, bytes (decoded and checked)", &honest_bytes),
        ("honest, message (checked)", &honest),
        ("hostile mix, bytes (all dropped)", &hostile),
    ];
    for (label, samples) in rows {
        let mut receiver = agent(0);
        receiver.tick(NOW);
        let (us, passed) = time_checks(&mut receiver, samples, checks);
        debug_assert!(
            passed == 0 || samples.len() == 1,
            "{label}: {passed} passed"
        );
        text.push_str(&format!("{label:<40} {us:>10.3} {passed:>8}\n"));
    }
    Ok(text)
}
