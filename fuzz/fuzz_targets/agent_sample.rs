//! A sample off the network as an agent hears it (issue #27): whatever its bytes and key, the
//! check on arrival never panics, counts every sample it drops once, and what it lets through
//! keeps every bound; the agent then takes it and ticks without a panic.
#![no_main]
use libfuzzer_sys::fuzz_target;
use mason_mission::agent::{
    Agent, AgentSetup, Arrival, SampleKey, SimulatedVehicle, DEFAULT_DEAD_AFTER_S, DEFAULT_LEASE_S,
};
use mason_mission::{Coord, MissionConfig};
use mason_order::CostModel;
use mason_wall::{BrickId, Wall};
use std::sync::OnceLock;

struct Team {
    wall: Wall,
    order: Vec<BrickId>,
    model: CostModel,
    config: MissionConfig,
    slot: f64,
}

fn team() -> &'static Team {
    static TEAM: OnceLock<Team> = OnceLock::new();
    TEAM.get_or_init(|| {
        let wall = mason_wall::builtin("thesis-2x5").expect("built-in").wall();
        let order = wall.ids().collect(); // level by level: a valid order
        let model = CostModel::default();
        let config = MissionConfig::with_uavs(3);
        let slot = mason_mission::slot_length(&wall, &model, &config).expect("a slot");
        Team {
            wall,
            order,
            model,
            config,
            slot,
        }
    })
}

fuzz_target!(|data: &[u8]| {
    let Some((&which, body)) = data.split_first() else {
        return;
    };
    let t = team();
    let setup = AgentSetup {
        wall: &t.wall,
        order: &t.order,
        assignment: None,
        model: &t.model,
        config: &t.config,
        coord: Coord::Auto,
        slot_s: t.slot,
        uav: 0,
        mission: "m",
        incarnation: 1,
        dead_after_s: DEFAULT_DEAD_AFTER_S,
        lease_s: DEFAULT_LEASE_S,
    };
    let mut agent = Agent::new(setup, Box::new(SimulatedVehicle::new(&t.config, 1)));
    agent.tick(10.0);
    let key = match which % 4 {
        0 => None,
        1 => SampleKey::parse("mason/m/1/heartbeat"),
        2 => SampleKey::parse("mason/m/2/placed"),
        _ => SampleKey::parse("mason/m/station-0/command"),
    };
    match agent.admit(10.5, Arrival::bytes(key, body.to_vec())) {
        Ok(checked) => {
            if let Some(m) = checked.message() {
                assert!(m.uav == 1 || m.uav == 2);
                assert_eq!(m.status.heard.len(), 3);
                assert!(m.status.placed.windows(2).all(|w| w[0] < w[1]));
                assert!(m.status.placed.iter().all(|&b| (b as usize) < t.wall.len()));
                assert!(m.t.is_finite() && (m.t - 10.5).abs() <= 120.0);
            }
            agent.receive(10.5, checked);
            agent.tick(11.0);
            assert_eq!(agent.drops().total(), 0);
        }
        Err(d) => {
            assert!(d.first);
            assert_eq!(agent.drops().total(), 1);
            assert_eq!(agent.drops().count(d.cause), 1);
        }
    }
});
