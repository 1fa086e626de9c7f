//! One agent process: a UAV's decision core ([`Agent`]) with a simulated vehicle, a real clock,
//! a transport behind the fault layer, its trace file and MCAP log, driven until it lands.

use crate::clock::{unix_now, Clock, MissionClock};
use crate::drive::{drive, Ending};
use crate::error::{FleetError, FleetResult};
use crate::faults::{FaultLayer, FaultStats};
use crate::log::{AgentLog, JsonLines, McapAgentLog};
use crate::network::Network;
use crate::setting::FleetSetting;
use crate::transport::Transport;
use crate::world::TraceWorld;
use mason_mission::agent::{Agent, SimulatedVehicle};
use std::path::PathBuf;
use std::sync::atomic::AtomicBool;
use std::sync::Arc;
use std::time::Instant;

/// The furthest a start may lie ahead (s): a day.
pub const MAX_START_AHEAD_S: f64 = 86_400.0;

/// One agent's own options (besides the team's [`FleetSetting`] and its [`Network`]).
#[derive(Clone, Debug, Default)]
pub struct AgentOptions {
    /// This UAV (0-based).
    pub uav: usize,
    /// This run's incarnation, from 1 (a restarted agent takes a higher one).
    pub incarnation: u64,
    /// Mission time 0 as Unix seconds (default: now).
    pub start_at: Option<f64>,
    /// The trace file: one JSON event per line.
    pub trace: Option<PathBuf>,
    /// The MCAP log.
    pub mcap: Option<PathBuf>,
    /// Traces of this UAV's earlier runs: the bricks it placed are remembered.
    pub remember: Vec<PathBuf>,
    /// The folder of the team's trace files the simulated camera reads (see [`TraceWorld`]).
    pub world: Option<PathBuf>,
}

impl AgentOptions {
    /// Checks these options against the team (errors name the flag).
    pub fn check(&self, setting: &FleetSetting) -> FleetResult<()> {
        let n = setting.config.uavs;
        if self.uav >= n {
            return Err(FleetError::bad(format!(
                "--uav {}: not in a team of {n} (0..{})",
                self.uav,
                n.saturating_sub(1)
            )));
        }
        if self.incarnation == 0 {
            return Err(FleetError::bad("--incarnation: starts at 1"));
        }
        if let Some(s) = self.start_at {
            if !(s.is_finite() && s >= 0.0) {
                return Err(FleetError::bad(format!(
                    "--start-at {s}: expected Unix seconds"
                )));
            }
            if s > unix_now() + MAX_START_AHEAD_S {
                return Err(FleetError::bad(format!(
                    "--start-at {s}: more than a day ({MAX_START_AHEAD_S} s) from now"
                )));
            }
        }
        for p in self.trace.iter().chain(&self.mcap) {
            mason_io::check_output(p)?;
        }
        if let Some(d) = self.world.as_ref().filter(|d| !d.is_dir()) {
            return Err(FleetError::bad(format!(
                "--world {}: not a folder",
                d.display()
            )));
        }
        Ok(())
    }
}

/// How an agent's run went.
#[derive(Clone, Debug)]
pub struct AgentReport {
    /// How the drive ended.
    pub ending: Ending,
    /// Mission time at the end (s).
    pub mission_time: f64,
    /// Wall time the run took (s).
    pub wall_s: f64,
    /// What the fault layer did.
    pub stats: FaultStats,
    /// Bricks this agent knows are placed.
    pub placed_known: usize,
    /// Samples dropped on arrival, per cause.
    pub drops: mason_mission::agent::DropCounts,
    /// The first bad line the simulated camera met in the team's traces, if any.
    pub world_problem: Option<String>,
}

fn create(p: &std::path::Path) -> FleetResult<std::fs::File> {
    std::fs::File::create(p).map_err(|source| FleetError::Io {
        path: p.to_path_buf(),
        source,
    })
}

/// Flies UAV `opts.uav` of `setting` over `transport` (behind the fault layer of
/// `setting.link`) until it lands, mission time passes `max_time_s`, or `stop` is set.
pub fn fly_agent<T: Transport>(
    setting: &FleetSetting,
    network: &Network,
    opts: &AgentOptions,
    transport: &mut T,
    stop: &AtomicBool,
) -> FleetResult<AgentReport> {
    opts.check(setting)?;
    let trace_file = opts.trace.as_deref().map(create).transpose()?;
    let mcap_file = opts.mcap.as_deref().map(create).transpose()?;
    let clock = MissionClock::new(opts.start_at.unwrap_or_else(unix_now), setting.speed);
    let seed = crate::agent_seed(setting.seed, opts.uav, opts.incarnation);
    let mut layer = FaultLayer::new(transport, clock, setting.link.clone(), seed);
    let mut vehicle = SimulatedVehicle::new(&setting.config, seed);
    let world = opts
        .world
        .as_ref()
        .map(|dir| Arc::new(TraceWorld::new(dir.clone(), setting.wall.len())));
    if let Some(w) = &world {
        vehicle = vehicle.with_world(w.clone());
    }
    let mut agent = Agent::new(
        setting.setup(opts.uav, &network.mission, opts.incarnation),
        Box::new(vehicle),
    );
    agent.remember(&crate::trace::placed_by(opts.uav, &opts.remember)?);
    let mut logs: Vec<Box<dyn AgentLog + '_>> = Vec::new();
    if let Some(f) = trace_file {
        logs.push(Box::new(JsonLines::new(f)));
    }
    let meta = mason_report::LogMeta {
        mission_id: &network.mission,
        uavs: setting.config.uavs,
        arena: &setting.config.arena,
        wall: &setting.wall,
    };
    if let (Some(f), Some(p)) = (mcap_file, &opts.mcap) {
        let log = McapAgentLog::new(f, &meta, opts.uav).map_err(|source| FleetError::Io {
            path: p.clone(),
            source,
        })?;
        logs.push(Box::new(log));
    }
    let started = Instant::now();
    let ending = drive(
        &mut agent,
        &mut layer,
        &clock,
        &mut logs,
        setting.config.max_time_s,
        setting.config.coord.heartbeat_s,
        stop,
    )
    .and_then(|ending| logs.drops(clock.now(), agent.drops()).map(|()| ending))
    .and_then(|ending| logs.finish().map(|()| ending))
    .map_err(|source| FleetError::Io {
        path: opts.trace.clone().unwrap_or_else(|| "trace".into()),
        source,
    })?;
    Ok(AgentReport {
        ending,
        mission_time: clock.now(),
        wall_s: started.elapsed().as_secs_f64(),
        stats: layer.stats,
        placed_known: agent.placed_known(),
        drops: *agent.drops(),
        world_problem: world.and_then(|w| w.problem()),
    })
}

/// A borrowed transport is a transport.
impl<T: Transport + ?Sized> Transport for &mut T {
    fn send(&mut self, m: &mason_mission::agent::Message) {
        (**self).send(m)
    }
    fn recv(&mut self, deadline: Instant) -> Vec<mason_mission::agent::Arrival> {
        (**self).recv(deadline)
    }
    fn overflowed(&mut self) -> u64 {
        (**self).overflowed()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::setting::tests::setting;
    use crate::transport::Hub;
    use mason_mission::Coord;

    #[test]
    fn a_lone_agent_builds_the_wall_and_writes_its_trace() {
        let mut s = setting("thesis-2x5", Coord::Comm, 500.0);
        s.config.uavs = 1;
        let dir = std::env::temp_dir().join(format!("mason-fleet-agent-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let trace = dir.join("uav-0-1.jsonl");
        let opts = AgentOptions {
            uav: 0,
            incarnation: 1,
            trace: Some(trace.clone()),
            mcap: Some(dir.join("uav-0-1.mcap")),
            ..AgentOptions::default()
        };
        let flags = crate::NetworkFlags {
            mission: Some("m".into()),
            insecure: true,
            ..crate::NetworkFlags::default()
        };
        let net = Network::resolve(None, &flags).unwrap();
        let mut link = Hub::new(1).links().pop().unwrap();
        let r = fly_agent(&s, &net, &opts, &mut link, &AtomicBool::new(false)).unwrap();
        assert_eq!(r.ending, Ending::Finished);
        assert_eq!(r.placed_known, 10);
        let events = crate::trace::read_trace(&trace, false).unwrap();
        mason_mission::check_trace(&s.wall, 1, &events).unwrap();
        assert!(std::fs::metadata(dir.join("uav-0-1.mcap")).unwrap().len() > 1000);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn options_are_checked_against_the_team() {
        let s = setting("thesis-2x5", Coord::Comm, 1.0);
        let bad = |o: AgentOptions| o.check(&s).unwrap_err().to_string();
        let good = AgentOptions {
            incarnation: 1,
            ..AgentOptions::default()
        };
        assert!(good.check(&s).is_ok());
        assert!(bad(AgentOptions {
            uav: 3,
            ..good.clone()
        })
        .starts_with("--uav 3"));
        assert!(bad(AgentOptions {
            incarnation: 0,
            ..good.clone()
        })
        .starts_with("--incarnation"));
        assert!(bad(AgentOptions {
            start_at: Some(1e18),
            ..good.clone()
        })
        .contains("a day"));
        assert!(bad(AgentOptions {
            world: Some("/nonexistent".into()),
            ..good
        })
        .contains("--world"));
    }
}
