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
    /// The agent made more events than its cap ([`mason_mission::event_cap`] for one UAV):
    /// durations too short to make progress.
    Flooded,
}

/// After it has finished, an agent repeats its last message this many heartbeats, so that a
/// teammate on a lossy link still hears that it landed.
pub const LAST_WORD_REPEATS: u32 = 3;

/// The longest a driver sleeps at once (wall), to notice a stop request.
const POLL: Duration = Duration::from_millis(100);

/// Runs `agent` on `clock` and `transport` until it finishes, mission time passes `max_time`,
/// or `stop` is set. Messages heard before mission time 0 are dropped; every later sample is
/// checked on arrival ([`Agent::admit`]) before the agent or the log sees it. The agent's
/// events, the messages it sent or kept, and the first drop of each cause go to `log` as they
/// happen.
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
    let mut events = 0u64;
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
        events += tick.events.len() as u64;
        if mason_mission::Flood::check(1, now, events).is_some() {
            return Ok(Ending::Flooded);
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
        if let Some(d) = agent.overflowed(transport.overflowed()) {
            log.dropped(clock.now(), d.cause)?;
        }
        if !heard.is_empty() {
            let now = clock.now();
            for sample in heard {
                // Checked before anything reads it, the log included: a sample that fails is
                // counted, and the first of each cause logged.
                match agent.admit(now, sample) {
                    Ok(checked) => {
                        if let Some(m) = checked.message() {
                            log.message(now, m, false)?;
                        }
                        if let Some(c) = checked.command() {
                            log.command(now, c)?;
                        }
                        agent.receive(now, checked);
                    }
                    Err(d) if d.first => log.dropped(now, d.cause)?,
                    Err(_) => {}
                }
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
    use crate::transport::{Hub, HubLink};
    use mason_mission::agent::{Arrival, Body, DropCause, DropCounts, SampleKey, SimulatedVehicle};
    use mason_mission::{check_trace, Event, EventKind, LinkFaults};
    use std::sync::atomic::AtomicUsize;

    /// Three agents on threads, an in-memory bus, the real clock at the setting's speed.
    fn fly_threads(s: &crate::FleetSetting, faults: LinkFaults) -> Vec<Event> {
        fly_with_rogue(s, faults, None).0
    }

    /// What a rogue on the bus does: given its link, the clock, and whether the team is done.
    type Rogue<'r> = &'r (dyn Fn(&mut HubLink, &MissionClock, &AtomicUsize) + Sync);

    /// Three agents on threads, and a rogue, if any, as a fourth member of the bus: the merged
    /// trace and each agent's drops.
    fn fly_with_rogue(
        s: &crate::FleetSetting,
        faults: LinkFaults,
        rogue: Option<Rogue<'_>>,
    ) -> (Vec<Event>, Vec<DropCounts>) {
        let start = unix_now() + 0.05;
        let stop = AtomicBool::new(false);
        let done = AtomicUsize::new(0);
        let mut links = Hub::new(4).links();
        let mut rogue_link = links.pop().expect("a fourth member");
        let runs: Vec<(Vec<Event>, DropCounts)> = std::thread::scope(|scope| {
            let handles: Vec<_> = links
                .into_iter()
                .enumerate()
                .map(|(u, link)| {
                    let (stop, done, faults) = (&stop, &done, faults.clone());
                    scope.spawn(move || {
                        let clock = MissionClock::new(start, s.speed);
                        let seed = crate::agent_seed(s.seed, u, 1);
                        let mut t = FaultLayer::new(link, clock, faults, seed);
                        let v = SimulatedVehicle::new(&s.config, seed);
                        let mut agent = Agent::new(s.setup(u, "test", 1), Box::new(v));
                        let mut log: Vec<Event> = Vec::new();
                        let end =
                            drive(&mut agent, &mut t, &clock, &mut log, 7200.0, 1.0, stop).unwrap();
                        done.fetch_add(1, Ordering::SeqCst);
                        assert_eq!(end, Ending::Finished, "UAV {u}");
                        (log, *agent.drops())
                    })
                })
                .collect();
            if let Some(r) = rogue {
                let (done, link) = (&done, &mut rogue_link);
                scope.spawn(move || r(link, &MissionClock::new(start, s.speed), done));
            }
            handles.into_iter().map(|h| h.join().unwrap()).collect()
        });
        let (traces, drops): (Vec<_>, Vec<_>) = runs.into_iter().unzip();
        let mut all: Vec<Event> = traces.into_iter().flatten().collect();
        all.sort_by(|a, b| a.t.total_cmp(&b.t));
        (all, drops)
    }

    /// Waits for mission time `t`, keeping what the team sends (each message once).
    fn listen_until(link: &mut HubLink, clock: &MissionClock, t: f64, heard: &mut Vec<Message>) {
        while clock.now() < t {
            let deadline = Instant::now() + Duration::from_millis(1);
            for a in link.recv(deadline) {
                if let Body::Message(m) = a.body {
                    heard.push(*m);
                }
            }
        }
    }

    /// Issue #27's stranger on a shared network: speaks as a UAV outside the team, sends
    /// malformed samples, replays what it heard, forges UAV 1's status under a higher
    /// incarnation with every brick placed, and floods the team with 10 000 samples.
    fn rogue(link: &mut HubLink, clock: &MissionClock, done: &AtomicUsize) {
        let mut heard = Vec::new();
        listen_until(link, clock, 5.0, &mut heard);
        let Some(template) = heard.iter().find(|m| m.uav == 1).cloned() else {
            return;
        };
        let at_now = |mut m: Message| {
            m.t = clock.now();
            m
        };
        let mut stranger = at_now(template.clone());
        stranger.uav = 7;
        link.inject(&Arrival::keyed(stranger));
        for junk in [&b"{"[..], br#"{"v":1,"uav":"one"}"#, b"\xff\xfe"] {
            link.inject(&Arrival::bytes(
                SampleKey::parse("mason/test/1/state"),
                junk.to_vec(),
            ));
        }
        link.inject(&Arrival::bytes(None, vec![b'['; 1 << 20]));
        listen_until(link, clock, 10.0, &mut heard);
        for m in heard.iter().filter(|m| m.uav != 1).take(5) {
            link.inject(&Arrival::keyed(m.clone()));
        }
        let mut forged = at_now(template.clone());
        forged.incarnation += 1;
        forged.seq = 1;
        forged.kind = mason_mission::agent::MessageKind::Placed;
        forged.status.placed = (0..10).collect();
        link.inject(&Arrival::keyed(forged));
        for i in 0..10_000u64 {
            let mut m = at_now(template.clone());
            match i % 3 {
                0 => m.uav = 3 + (i % 100) as u32,
                1 => m.mission = "elsewhere".into(),
                _ => m.v = 99,
            }
            link.inject(&Arrival::keyed(m));
        }
        while done.load(Ordering::SeqCst) < 3 {
            listen_until(link, clock, clock.now() + 1.0, &mut heard);
        }
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
    fn a_rogue_on_the_bus_changes_nothing_but_the_counters() {
        let s = setting("thesis-2x5", mason_mission::Coord::Auto, 200.0);
        let (events, drops) = fly_with_rogue(&s, LinkFaults::default(), Some(&rogue));
        check_trace(&s.wall, 3, &events).expect("a safe trace");
        assert_eq!(placed(&events), s.wall.len());
        for (u, d) in drops.iter().enumerate() {
            // Every agent heard every rogue sample (all sent while it flew).
            assert_eq!(d.count(DropCause::Malformed), 3, "UAV {u}: {d:?}");
            assert_eq!(d.count(DropCause::Size), 1, "UAV {u}: {d:?}");
            assert_eq!(d.count(DropCause::UnknownUav), 1 + 3334, "UAV {u}: {d:?}");
            assert_eq!(d.count(DropCause::Mission), 3333, "UAV {u}: {d:?}");
            assert_eq!(d.count(DropCause::Version), 3333, "UAV {u}: {d:?}");
            // UAV 1 drops the forgery in its name as its own; the others find it implausible.
            let forged = if u == 1 {
                DropCause::Own
            } else {
                DropCause::Implausible
            };
            assert!(d.count(forged) >= 1, "UAV {u}: {d:?}");
            // Five replays of the others' messages: each is its own, or a replay.
            let replays = d.count(DropCause::Replay) + d.count(DropCause::Own);
            assert!(replays >= 5, "UAV {u}: {d:?}");
        }
    }

    /// A ground station: an abort at mission time 60 s.
    fn station(link: &mut HubLink, clock: &MissionClock, done: &AtomicUsize) {
        let mut heard = Vec::new();
        listen_until(link, clock, 60.0, &mut heard);
        let abort = mason_mission::agent::Command {
            v: 1,
            mission: "test".into(),
            station: 0,
            seq: 1,
            t: clock.now(),
            order: mason_mission::agent::Order::Abort,
        };
        link.inject(&Arrival::command(abort));
        while done.load(Ordering::SeqCst) < 3 {
            listen_until(link, clock, clock.now() + 1.0, &mut heard);
        }
    }

    #[test]
    fn an_abort_from_a_station_lands_every_agent() {
        let s = setting("mbzirc", mason_mission::Coord::Auto, 200.0);
        let (events, drops) = fly_with_rogue(&s, LinkFaults::default(), Some(&station));
        check_trace(&s.wall, 3, &events).expect("a safe trace");
        assert!(placed(&events) < s.wall.len());
        for u in 0..3 {
            let aborted = events.iter().any(|e| {
                e.uav == u
                    && matches!(
                        e.kind,
                        EventKind::State {
                            outcome: "aborted",
                            ..
                        }
                    )
            });
            assert!(aborted, "UAV {u}");
        }
        // Nothing dropped but the last words a landed teammate repeats.
        assert!(
            drops
                .iter()
                .all(|d| d.total() == d.count(DropCause::Replay)),
            "{drops:?}"
        );
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
