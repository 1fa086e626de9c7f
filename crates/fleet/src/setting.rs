//! A fleet's setting: what every agent of a team shares besides its own number and network.

use crate::clock::{MAX_SPEED, MIN_SPEED};
use crate::error::{FleetError, FleetResult};
use mason_mission::agent::{AgentSetup, DEFAULT_LEASE_S};
use mason_mission::{Coord, LinkFaults, MissionConfig};
use mason_order::CostModel;
use mason_wall::{BrickId, Wall};

/// What every agent of a team shares, checked ([`FleetSetting::check`]).
#[derive(Clone, Debug)]
pub struct FleetSetting {
    /// The wall.
    pub wall: Wall,
    /// The cost model.
    pub model: CostModel,
    /// The shared build order (every agent plans the same one).
    pub order: Vec<BrickId>,
    /// Team, arena, UAV model, coordination timings (vehicle faults only).
    pub config: MissionConfig,
    /// The coordination policy.
    pub coord: Coord,
    /// The windows slot (s).
    pub slot: f64,
    /// Clock speed: mission seconds per wall second.
    pub speed: f64,
    /// Seed of the vehicles and fault layers (mixed per UAV and incarnation by
    /// [`crate::agent_seed`]).
    pub seed: u64,
    /// A teammate unheard this long (mission s) is declared out by a majority.
    pub dead_after: f64,
    /// Faults put on purpose between each agent and its transport.
    pub link: LinkFaults,
}

/// Heartbeats of margin between the longest zone time and the time a teammate is declared out.
pub const DEAD_AFTER_HEARTBEATS: f64 = 5.0;

/// The shortest `dead_after` with which every brick of `wall` can still be placed: an agent
/// enters the zone only when it can leave (its zone time plus three heartbeats) before a
/// teammate that last heard it could declare it out; two more heartbeats cover how old that
/// hearing may be.
pub fn least_dead_after(wall: &Wall, model: &CostModel, config: &MissionConfig) -> f64 {
    mason_mission::coord::longest_zone_time(wall, model, config)
        + DEAD_AFTER_HEARTBEATS * config.coord.heartbeat_s
}

/// The default `dead_after` for a wall: 30 s ([`mason_mission::agent::DEFAULT_DEAD_AFTER_S`]),
/// or longer where a brick's zone time needs it ([`least_dead_after`]).
pub fn default_dead_after(wall: &Wall, model: &CostModel, config: &MissionConfig) -> f64 {
    mason_mission::agent::DEFAULT_DEAD_AFTER_S.max(least_dead_after(wall, model, config).ceil())
}

impl FleetSetting {
    /// Checks the settings a mission configuration does not cover: clock speed, declaration
    /// time and link faults (errors name the flag).
    pub fn check(&self) -> FleetResult<()> {
        if !(self.speed.is_finite() && (MIN_SPEED..=MAX_SPEED).contains(&self.speed)) {
            return Err(FleetError::bad(format!(
                "--speed {:e}: expected a factor in [{MIN_SPEED}, {MAX_SPEED}]",
                self.speed
            )));
        }
        if !(self.dead_after.is_finite() && self.dead_after > 0.0) {
            return Err(FleetError::bad(format!(
                "--dead-after {}: expected seconds > 0",
                self.dead_after
            )));
        }
        let least = least_dead_after(&self.wall, &self.model, &self.config);
        if self.dead_after < least {
            return Err(FleetError::bad(format!(
                "--dead-after {}: at least {least:.1} s for this wall (its longest zone time plus {DEAD_AFTER_HEARTBEATS} heartbeats): an agent enters the zone only if it can leave before a teammate could declare it out",
                self.dead_after
            )));
        }
        let l = &self.link;
        for (flag, p) in [("--drop", l.loss), ("--duplicate", l.duplicate)] {
            if !(0.0..=1.0).contains(&p) {
                return Err(FleetError::bad(format!(
                    "{flag} {p}: a probability must lie in [0, 1]"
                )));
            }
        }
        for (flag, s) in [("--latency", l.latency), ("--delay-jitter", l.jitter)] {
            if !(s.is_finite() && s >= 0.0) {
                return Err(FleetError::bad(format!("{flag} {s}: expected seconds ≥ 0")));
            }
        }
        Ok(())
    }

    /// The agent setup of UAV `uav` in incarnation `incarnation` of mission `mission`.
    pub fn setup<'a>(&'a self, uav: usize, mission: &'a str, incarnation: u64) -> AgentSetup<'a> {
        AgentSetup {
            wall: &self.wall,
            order: &self.order,
            assignment: None,
            model: &self.model,
            config: &self.config,
            coord: self.coord,
            slot_s: self.slot,
            uav,
            mission,
            incarnation,
            dead_after_s: self.dead_after,
            lease_s: DEFAULT_LEASE_S,
        }
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use mason_mission::agent::DEFAULT_DEAD_AFTER_S;

    /// A checked setting for three UAVs on a built-in wall.
    pub fn setting(name: &str, coord: Coord, speed: f64) -> FleetSetting {
        let wall = mason_wall::builtin(name).unwrap().wall();
        let model = CostModel::default();
        let problem = mason_order::BuildProblem::new(&wall, model.clone()).unwrap();
        let order = mason_order::PlannerSpec::Exact
            .plan(&problem, &mason_order::Budget::unlimited())
            .order
            .unwrap();
        let config = MissionConfig::with_uavs(3);
        let slot = mason_mission::slot_length(&wall, &model, &config).unwrap();
        let s = FleetSetting {
            wall,
            model,
            order,
            config,
            coord,
            slot,
            speed,
            seed: 1,
            dead_after: 0.0,
            link: LinkFaults::default(),
        };
        let s = FleetSetting {
            dead_after: default_dead_after(&s.wall, &s.model, &s.config),
            ..s
        };
        s.check().unwrap();
        s
    }

    /// Found in #25's review: an orange brick with two placed neighbours needs 32 s in the zone
    /// on MBZIRC, and with 30 s to be declared out no agent could ever enter for it.
    #[test]
    fn dead_after_leaves_room_for_the_longest_zone_time() {
        let mut s = setting("mbzirc", Coord::Comm, 1.0);
        let least = least_dead_after(&s.wall, &s.model, &s.config);
        assert!(least > DEFAULT_DEAD_AFTER_S, "{least}");
        assert_eq!(
            default_dead_after(&s.wall, &s.model, &s.config),
            least.ceil()
        );
        s.dead_after = DEFAULT_DEAD_AFTER_S;
        let e = s.check().unwrap_err().to_string();
        assert!(e.starts_with("--dead-after 30: at least"), "{e}");
        let small = setting("thesis-2x5", Coord::Comm, 1.0);
        assert_eq!(
            default_dead_after(&small.wall, &small.model, &small.config),
            DEFAULT_DEAD_AFTER_S
                .max(least_dead_after(&small.wall, &small.model, &small.config).ceil())
        );
    }

    /// The stall itself, on the virtual bus: the level-by-level order puts orange bricks with
    /// placed neighbours early on MBZIRC; with 30 s to be declared out the team never finishes,
    /// with the wall's default it does, and its trace is safe.
    #[test]
    fn the_default_dead_after_lets_a_team_place_every_brick() {
        let mut s = setting("mbzirc", Coord::Comm, 1.0);
        s.order = s.wall.ids().collect();
        let fly = |dead_after: f64| {
            let s = FleetSetting {
                dead_after,
                ..s.clone()
            };
            let faults = mason_mission::bus::BusFaults::default();
            let run = mason_mission::bus::fly_bus(s.setup(0, "bus", 1), &faults, 1);
            let placed = run
                .events
                .iter()
                .filter(|e| matches!(e.kind, mason_mission::EventKind::Place { .. }))
                .count();
            (run, placed)
        };
        let (run, placed) = fly(default_dead_after(&s.wall, &s.model, &s.config));
        assert!(run.finished, "placed {placed}");
        assert_eq!(placed, s.wall.len());
        mason_mission::check_trace(&s.wall, 3, &run.events).unwrap();
        let (_, stalled) = fly(DEFAULT_DEAD_AFTER_S);
        assert!(stalled < s.wall.len(), "30 s no longer stalls: {stalled}");
    }

    #[test]
    fn out_of_range_settings_name_their_flag() {
        let good = setting("thesis-2x5", Coord::Auto, 1.0);
        let mut s = good.clone();
        s.speed = 0.0;
        assert!(s.check().unwrap_err().to_string().starts_with("--speed"));
        let mut s = good.clone();
        s.speed = 1e-300;
        assert!(s.check().unwrap_err().to_string().contains("[0.001, 1000]"));
        let mut s = good.clone();
        s.link.loss = 1.5;
        assert!(s.check().unwrap_err().to_string().starts_with("--drop"));
        let mut s = good;
        s.link.jitter = f64::NAN;
        assert!(s
            .check()
            .unwrap_err()
            .to_string()
            .starts_with("--delay-jitter"));
    }
}
