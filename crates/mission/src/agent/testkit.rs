//! Test support for the agent's unit tests: a team on a built-in wall, and an instant bus on
//! which a test decides which messages get through.

use super::{agent_seed, Agent, AgentSetup, Message, SimulatedVehicle};
use super::{DEFAULT_DEAD_AFTER_S, DEFAULT_LEASE_S};
use crate::config::MissionConfig;
use crate::coord::Coord;
use crate::state::Event;
use mason_order::CostModel;
use mason_wall::{BrickId, Wall};

/// A wall, its optimal order, the default model and a team's configuration.
pub(super) struct Fixture {
    pub(super) wall: Wall,
    pub(super) order: Vec<BrickId>,
    pub(super) model: CostModel,
    pub(super) config: MissionConfig,
}

impl Fixture {
    /// Built-in wall `name`, `uavs` UAVs.
    pub(super) fn new(name: &str, uavs: usize) -> Self {
        let wall = mason_wall::builtin(name).expect("built-in").wall();
        let model = CostModel::default();
        let problem = mason_order::BuildProblem::new(&wall, model.clone()).expect("a problem");
        let order = mason_order::PlannerSpec::Exact
            .plan(&problem, &mason_order::Budget::unlimited())
            .order
            .expect("an order");
        Fixture {
            order,
            wall,
            model,
            config: MissionConfig::with_uavs(uavs),
        }
    }

    /// UAV `uav`'s setup under `coord`.
    pub(super) fn setup(&self, coord: Coord, uav: usize) -> AgentSetup<'_> {
        AgentSetup {
            wall: &self.wall,
            order: &self.order,
            assignment: None,
            model: &self.model,
            config: &self.config,
            coord,
            slot_s: crate::coord::slot_length(&self.wall, &self.model, &self.config)
                .expect("a slot"),
            uav,
            mission: "test",
            incarnation: 1,
            dead_after_s: DEFAULT_DEAD_AFTER_S,
            lease_s: DEFAULT_LEASE_S,
        }
    }

    /// The team's agents, on fault-free simulated vehicles without cameras.
    pub(super) fn agents(&self, coord: Coord) -> Vec<Agent<'_>> {
        (0..self.config.uavs)
            .map(|u| {
                let vehicle = SimulatedVehicle::new(&self.config, agent_seed(1, u, 1));
                Agent::new(self.setup(coord, u), Box::new(vehicle))
            })
            .collect()
    }

    /// Asserts that `events` pass `check_trace`.
    pub(super) fn check(&self, events: &[Event]) {
        let summary = crate::check::check_trace(&self.wall, self.config.uavs, events);
        assert!(summary.is_ok(), "{summary:?}");
    }
}

/// Runs `agents` until every one has finished or `until` (s) has passed, on a bus that
/// delivers a message sent at `t` from `from` to `to` at once if `deliver(from, to, &m, t)`,
/// and never otherwise. Returns every event by time, and every message sent with its sender.
pub(super) fn fly(
    agents: &mut [Agent<'_>],
    until: f64,
    mut deliver: impl FnMut(usize, usize, &Message, f64) -> bool,
) -> (Vec<Event>, Vec<(usize, Message)>) {
    let n = agents.len();
    let mut wake = vec![0.0_f64; n];
    let (mut events, mut sent) = (Vec::new(), Vec::new());
    while !agents.iter().all(Agent::finished) {
        let (t, u) = (0..n)
            .map(|u| (wake[u], u))
            .min_by(|a, b| a.0.total_cmp(&b.0))
            .expect("a team");
        if t > until {
            break;
        }
        let tick = agents[u].tick(t);
        wake[u] = tick.wake;
        events.extend(tick.events);
        for m in tick.messages {
            for to in (0..n).filter(|&v| v != u) {
                if deliver(u, to, &m, t) {
                    let _ = agents[to].hear(t, super::Arrival::keyed(m.clone()));
                    wake[to] = wake[to].min(t);
                }
            }
            sent.push((u, m));
        }
    }
    events.sort_by(|a, b| a.t.total_cmp(&b.t));
    (events, sent)
}
