//! The drive loop: one [`Agent`] on a [`Clock`] and a [`Transport`], until it finishes, mission
//! time runs out, or it is asked to stop.

use crate::clock::Clock;
use crate::log::AgentLog;
use crate::transport::Transport;
use mason_mission::agent::{Agent, Message};
use std::sync::atomic::{AtomicBool, Ordering};
use std::time::{Duration, Instant};

/// How a drive ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Ending {
    /// The UAV is on the ground for good (landed, or down).
    Finished,
    /// Mission time ran past `max_time_s`.
    Timeout,
    /// Asked to stop (Ctrl-C, SIGTERM).
    Interrupted,
}

/// After it has finished, an agent repeats its last message this many heartbeats, so that a
/// teammate on a lossy link still hears that it landed.
pub const LAST_WORD_REPEATS: u32 = 3;

/// The longest a driver sleeps at once (wall), to notice a stop request.
const POLL: Duration = Duration::from_millis(100);

/// Runs `agent` on `clock` and `transport` until it finishes, mission time passes `max_time`,
/// or `stop` is set. Messages heard before mission time 0 are dropped; the agent's events go
/// to `log` as they happen.
pub fn drive(
    agent: &mut Agent<'_>,
    transport: &mut dyn Transport,
    clock: &dyn Clock,
    log: &mut dyn AgentLog,
    max_time: f64,
    heartbeat_s: f64,
    stop: &AtomicBool,
) -> std::io::Result<Ending> {
    // Before the start: wait, and drop what is heard.
    while clock.now() < 0.0 {
        if stop.load(Ordering::Relaxed) {
            return Ok(Ending::Interrupted);
        }
        let deadline = clock.instant_at(0.0).min(Instant::now() + POLL);
        transport.recv(deadline);
    }
    let mut last: Option<Message> = None;
    loop {
        if stop.load(Ordering::Relaxed) {
            return Ok(Ending::Interrupted);
        }
        let now = clock.now();
        if now > max_time {
            return Ok(Ending::Timeout);
        }
        let tick = agent.tick(now);
        for e in &tick.events {
            log.event(e)?;
        }
        for m in &tick.messages {
            transport.send(m);
            log.message(now, m, true)?;
        }
        log.pose(now, agent.pose(now))?;
        if let Some(m) = tick.messages.last() {
            last = Some(m.clone());
        }
        if agent.finished() {
            last_words(transport, clock, last.as_ref(), heartbeat_s, stop);
            return Ok(Ending::Finished);
        }
        let idle = tick.messages.is_empty() && tick.events.is_empty() && tick.wake <= now;
        let mut deadline = clock
            .instant_at(tick.wake.min(max_time + heartbeat_s))
            .min(Instant::now() + POLL);
        if idle {
            // Nothing happened and it asks to be woken now: do not spin.
            deadline = deadline.max(Instant::now() + Duration::from_millis(1));
        }
        let heard = transport.recv(deadline);
        if !heard.is_empty() {
            let now = clock.now();
            for m in heard {
                log.message(now, &m, false)?;
                agent.receive(now, m);
            }
        }
    }
}

/// Repeats the last message [`LAST_WORD_REPEATS`] times, a heartbeat apart (duplicates are
/// ignored by whoever heard it already).
fn last_words(
    transport: &mut dyn Transport,
    clock: &dyn Clock,
    last: Option<&Message>,
    heartbeat_s: f64,
    stop: &AtomicBool,
) {
    let Some(m) = last else { return };
    let mut at = clock.now();
    for _ in 0..LAST_WORD_REPEATS {
        at += heartbeat_s;
        while Instant::now() < clock.instant_at(at) && !stop.load(Ordering::Relaxed) {
            let deadline = clock.instant_at(at).min(Instant::now() + POLL);
            transport.recv(deadline);
        }
        transport.send(m);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::clock::{unix_now, MissionClock};
    use crate::faults::FaultLayer;
    use crate::setting::tests::setting;
    use crate::transport::Hub;
    use mason_mission::agent::SimulatedVehicle;
    use mason_mission::{check_trace, Event, EventKind, LinkFaults};

    /// Three agents on threads, an in-memory bus, the real clock at the setting's speed.
    fn fly_threads(s: &crate::FleetSetting, faults: LinkFaults) -> Vec<Event> {
        let start = unix_now() + 0.05;
        let stop = AtomicBool::new(false);
        let links = Hub::new(3).links();
        let traces: Vec<Vec<Event>> = std::thread::scope(|scope| {
            let handles: Vec<_> = links
                .into_iter()
                .enumerate()
                .map(|(u, link)| {
                    let (stop, faults) = (&stop, faults.clone());
                    scope.spawn(move || {
                        let clock = MissionClock::new(start, s.speed);
                        let seed = crate::agent_seed(s.seed, u, 1);
                        let mut t = FaultLayer::new(link, clock, faults, seed);
                        let v = SimulatedVehicle::new(&s.config, seed);
                        let mut agent = Agent::new(s.setup(u, "test", 1), Box::new(v));
                        let mut log: Vec<Event> = Vec::new();
                        let end =
                            drive(&mut agent, &mut t, &clock, &mut log, 7200.0, 1.0, stop).unwrap();
                        assert_eq!(end, Ending::Finished, "UAV {u}");
                        log
                    })
                })
                .collect();
            handles.into_iter().map(|h| h.join().unwrap()).collect()
        });
        let mut all: Vec<Event> = traces.into_iter().flatten().collect();
        all.sort_by(|a, b| a.t.total_cmp(&b.t));
        all
    }

    fn placed(events: &[Event]) -> usize {
        events
            .iter()
            .filter(|e| matches!(e.kind, EventKind::Place { .. }))
            .count()
    }

    #[test]
    fn three_threads_on_a_real_clock_build_the_wall() {
        let s = setting("thesis-2x5", mason_mission::Coord::Auto, 200.0);
        let events = fly_threads(&s, LinkFaults::default());
        check_trace(&s.wall, 3, &events).expect("a safe trace");
        assert_eq!(placed(&events), s.wall.len());
    }

    #[test]
    fn the_fault_layer_does_no_harm_to_the_driver() {
        let s = setting("thesis-2x5", mason_mission::Coord::Comm, 200.0);
        let faults = LinkFaults {
            loss: 0.3,
            duplicate: 0.2,
            jitter: 0.5,
            ..LinkFaults::default()
        };
        let events = fly_threads(&s, faults);
        check_trace(&s.wall, 3, &events).expect("a safe trace");
        assert_eq!(placed(&events), s.wall.len());
    }

    #[test]
    fn a_stop_request_interrupts_before_the_start() {
        let s = setting("thesis-2x5", mason_mission::Coord::Comm, 1.0);
        let clock = MissionClock::new(unix_now() + 3600.0, 1.0);
        let v = SimulatedVehicle::new(&s.config, 1);
        let mut agent = Agent::new(s.setup(0, "test", 1), Box::new(v));
        let mut link = Hub::new(1).links().pop().unwrap();
        let stop = AtomicBool::new(true);
        let mut log: Vec<Event> = Vec::new();
        let end = drive(&mut agent, &mut link, &clock, &mut log, 10.0, 1.0, &stop).unwrap();
        assert_eq!(end, Ending::Interrupted);
        assert!(log.is_empty());
    }
}
