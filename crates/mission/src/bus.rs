//! A team of [`Agent`]s on one virtual clock and a simulated bus that loses, duplicates,
//! delays, reorders and cuts messages ([`LinkFaults`], the same fault model as the real
//! transport's), and kills and restarts agents: the agents' protocol tested fast and
//! deterministically, with the same code `mason agent` runs over Zenoh.
//!
//! **Randomness.** The bus draws every message's [`Fate`] from one generator seeded with the
//! run's seed, once per (message, receiver), receivers in UAV order; each vehicle draws from
//! its own generator, seeded with [`agent_seed`]. A fault-free bus draws nothing.

use crate::agent::{agent_seed, Agent, AgentSetup, Arrival, DropCounts, SimulatedVehicle};
use crate::link::{Fate, LinkFaults};
use crate::state::{Event, EventKind, UavState};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use std::cmp::{Ordering, Reverse};
use std::collections::BinaryHeap;

/// What the bus and the launcher do to the team.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct BusFaults {
    /// What the radio link does to each message, per receiver.
    pub link: LinkFaults,
    /// `(uav, t)`: the agent is killed at t (as `kill -9`: no last word).
    pub kills: Vec<(usize, f64)>,
    /// `(uav, t)`: the killed agent starts again at t, as a new incarnation.
    pub restarts: Vec<(usize, f64)>,
    /// `(t, sample)`: what other peers on the network send (a ground station's commands, a
    /// rogue's samples): each reaches every agent at t, untouched by link faults.
    pub injected: Vec<(f64, Arrival)>,
}

/// The events that record an agent killed at `t`, from its own trace so far: it fails, leaves
/// the zone if it was inside, loses what it held, and is down. `mason launch` adds the same
/// events for the agents it kills.
pub fn killed_events(trace: &[Event], uav: u32, t: f64) -> Vec<Event> {
    let mut holding = None;
    let mut in_zone = false;
    let mut state = UavState::Check;
    for e in trace.iter().filter(|e| e.uav == uav) {
        match e.kind {
            EventKind::Grasp { brick } => holding = Some(brick),
            EventKind::Place { .. } | EventKind::Lost { .. } => holding = None,
            EventKind::ZoneEnter => in_zone = true,
            EventKind::ZoneLeave => in_zone = false,
            EventKind::State { state: s, .. } => state = s,
            _ => {}
        }
    }
    let mut out = Vec::new();
    if matches!(state, UavState::Landed | UavState::Down) {
        return out;
    }
    let at = |kind| Event { t, uav, kind };
    out.push(at(EventKind::Fail));
    if in_zone {
        out.push(at(EventKind::ZoneLeave));
    }
    // An orange pair's brick placed by its partner (whose trace has the placement) is not
    // held any more, although this agent's own trace never placed it.
    let placed = |b| {
        trace
            .iter()
            .any(|e| e.t <= t && matches!(e.kind, EventKind::Place { brick } if brick == b))
    };
    // What it held falls, unless its pair's partner still holds the brick and carries on
    // (the partner learns of the loss only when it declares the agent out).
    if let Some(brick) = holding.filter(|&b| !placed(b)) {
        let partner_holds = trace
            .iter()
            .filter(|e| e.uav != uav && e.t <= t)
            .fold(std::collections::BTreeMap::new(), |mut h, e| {
                match e.kind {
                    EventKind::Grasp { brick } => {
                        h.insert(e.uav, Some(brick));
                    }
                    EventKind::Place { brick: b } | EventKind::Lost { brick: b } => {
                        h.retain(|_, held| *held != Some(b));
                    }
                    _ => {}
                }
                h
            })
            .values()
            .any(|held| *held == Some(brick));
        if !partner_holds {
            out.push(at(EventKind::Lost { brick }));
        }
    }
    out.push(at(EventKind::State {
        state: UavState::Down,
        outcome: "killed",
        x: 0.0,
        y: 0.0,
    }));
    out
}

/// A team run on the virtual bus.
#[derive(Clone, Debug, PartialEq)]
pub struct BusRun {
    /// Every agent's events (and the killed agents' last ones), by time.
    pub events: Vec<Event>,
    /// Whether every agent still running finished (landed or down) in time.
    pub finished: bool,
    /// Messages sent.
    pub sent: usize,
    /// Messages delivered (duplicates included).
    pub delivered: usize,
    /// Messages the agents dropped on arrival, per cause, summed over the team (duplicates
    /// are `replay`).
    pub drops: DropCounts,
}

struct Delivery {
    t: f64,
    seq: u64,
    to: usize,
    sample: Arrival,
}

impl PartialEq for Delivery {
    fn eq(&self, o: &Self) -> bool {
        self.cmp(o) == Ordering::Equal
    }
}
impl Eq for Delivery {}
impl PartialOrd for Delivery {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}
impl Ord for Delivery {
    fn cmp(&self, o: &Self) -> Ordering {
        self.t.total_cmp(&o.t).then(self.seq.cmp(&o.seq))
    }
}

/// The wall as the simulated cameras see it: every placement so far.
struct World(std::sync::Mutex<WorldState>);

type WorldState = (Vec<bool>, Vec<(mason_wall::BrickId, f64)>);

impl World {
    fn lock(&self) -> std::sync::MutexGuard<'_, WorldState> {
        self.0
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
    }
}

impl crate::agent::WallView for World {
    fn placed(&self, brick: mason_wall::BrickId) -> bool {
        self.lock().0.get(brick.index()).copied().unwrap_or(false)
    }
    fn lost_since(&self, brick: mason_wall::BrickId, since: f64) -> bool {
        self.lock().1.iter().any(|&(b, t)| b == brick && t > since)
    }
}

/// Flies `setup`'s team (`setup.uav` is ignored: one agent per UAV) on the virtual bus until
/// every agent has finished or `setup.config.max_time_s` has passed.
pub fn fly_bus(setup: AgentSetup<'_>, faults: &BusFaults, seed: u64) -> BusRun {
    let n = setup.config.uavs;
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let world = std::sync::Arc::new(World(std::sync::Mutex::new((
        vec![false; setup.wall.len()],
        Vec::new(),
    ))));
    let make = |u: usize, incarnation: u64| {
        let vehicle = SimulatedVehicle::new(setup.config, agent_seed(seed, u, incarnation))
            .with_world(world.clone());
        Agent::new(
            AgentSetup {
                uav: u,
                incarnation,
                ..setup
            },
            Box::new(vehicle),
        )
    };
    let mut agents: Vec<Option<Agent<'_>>> = (0..n).map(|u| Some(make(u, 1))).collect();
    let mut wake = vec![0.0_f64; n];
    let mut kills = faults.kills.clone();
    kills.sort_by(|a, b| a.1.total_cmp(&b.1));
    let mut restarts = faults.restarts.clone();
    restarts.sort_by(|a, b| a.1.total_cmp(&b.1));
    let (mut ki, mut ri) = (0, 0);
    let mut queue: BinaryHeap<Reverse<Delivery>> = BinaryHeap::new();
    let mut seq = 0u64;
    for (t, sample) in &faults.injected {
        for to in 0..n {
            seq += 1;
            queue.push(Reverse(Delivery {
                t: *t,
                seq,
                to,
                sample: sample.clone(),
            }));
        }
    }
    let mut events: Vec<Event> = Vec::new();
    let (mut sent, mut delivered) = (0, 0);
    let mut drops = DropCounts::default();
    let max_t = setup.config.max_time_s;
    loop {
        // The next thing to happen: a kill, a restart, a delivery or an agent's wake-up.
        let next_wake = (0..n)
            .filter(|&u| agents[u].is_some())
            .map(|u| (wake[u], u))
            .min_by(|a, b| a.0.total_cmp(&b.0));
        let next_msg = queue.peek().map(|Reverse(d)| d.t);
        let next_kill = kills.get(ki).map(|k| k.1);
        let next_restart = restarts.get(ri).map(|r| r.1);
        let t = [next_wake.map(|w| w.0), next_msg, next_kill, next_restart]
            .into_iter()
            .flatten()
            .fold(f64::INFINITY, f64::min);
        let running = agents.iter().flatten().any(|a| !a.finished());
        if !running && next_restart.is_none() {
            break;
        }
        if !t.is_finite() || t > max_t {
            break;
        }
        let target = if next_kill == Some(t) {
            let (u, at) = kills[ki];
            ki += 1;
            if let Some(a) = agents[u].take() {
                drops.add(a.drops());
                let tail = killed_events(&events, u as u32, at);
                for e in &tail {
                    if let EventKind::Lost { brick } = e.kind {
                        world.lock().1.push((brick, e.t));
                    }
                }
                events.extend(tail);
            }
            continue;
        } else if next_restart == Some(t) {
            let (u, _) = restarts[ri];
            ri += 1;
            if agents[u].is_none() {
                let inc = 1 + restarts[..ri].iter().filter(|r| r.0 == u).count() as u64;
                let mut agent = make(u, inc);
                // It reads back what it placed from its own log.
                let mine: Vec<_> = events
                    .iter()
                    .filter_map(|e| match e.kind {
                        EventKind::Place { brick } if e.uav == u as u32 => Some(brick),
                        _ => None,
                    })
                    .collect();
                agent.remember(&mine);
                agents[u] = Some(agent);
                wake[u] = t;
            }
            continue;
        } else if next_msg == Some(t) {
            let Reverse(d) = queue.pop().expect("peeked");
            delivered += 1;
            match agents[d.to].as_mut() {
                // A sample dropped on arrival changes nothing but the counters: no tick.
                Some(a) => {
                    if a.hear(t, d.sample).is_err() {
                        continue;
                    }
                }
                None => continue,
            }
            d.to
        } else {
            next_wake.expect("a wake-up").1
        };
        let tick = agents[target].as_mut().expect("running").tick(t);
        wake[target] = tick.wake;
        for e in &tick.events {
            match e.kind {
                EventKind::Place { brick } => world.lock().0[brick.index()] = true,
                EventKind::Lost { brick } => world.lock().1.push((brick, e.t)),
                _ => {}
            }
        }
        events.extend(tick.events);
        for m in tick.messages {
            sent += 1;
            for to in (0..n).filter(|&v| v != target) {
                let Fate::Delivered { first, second } = faults.link.fate(t, &mut rng) else {
                    continue;
                };
                for delay in std::iter::once(first).chain(second) {
                    seq += 1;
                    queue.push(Reverse(Delivery {
                        t: t + delay,
                        seq,
                        to,
                        sample: Arrival::keyed(m.clone()),
                    }));
                }
            }
        }
    }
    events.sort_by(|a, b| a.t.total_cmp(&b.t));
    let finished = agents.iter().flatten().all(|a| a.finished());
    for a in agents.iter().flatten() {
        drops.add(a.drops());
    }
    BusRun {
        events,
        finished,
        sent,
        delivered,
        drops,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use mason_wall::BrickId;

    fn at(t: f64, uav: u32, kind: EventKind) -> Event {
        Event { t, uav, kind }
    }

    fn state(t: f64, uav: u32, state: UavState) -> Event {
        at(
            t,
            uav,
            EventKind::State {
                state,
                outcome: "ok",
                x: 1.0,
                y: 2.0,
            },
        )
    }

    #[test]
    fn an_agent_killed_in_the_zone_leaves_it_and_loses_its_brick() {
        let b = BrickId(3);
        let trace = vec![
            state(1.0, 0, UavState::TakeOff),
            at(5.0, 0, EventKind::Grasp { brick: b }),
            at(9.0, 0, EventKind::ZoneEnter),
        ];
        let kinds: Vec<EventKind> = killed_events(&trace, 0, 10.0)
            .into_iter()
            .inspect(|e| assert_eq!((e.t, e.uav), (10.0, 0)))
            .map(|e| e.kind)
            .collect();
        assert_eq!(
            kinds,
            vec![
                EventKind::Fail,
                EventKind::ZoneLeave,
                EventKind::Lost { brick: b },
                EventKind::State {
                    state: UavState::Down,
                    outcome: "killed",
                    x: 0.0,
                    y: 0.0
                }
            ]
        );
    }

    #[test]
    fn a_brick_its_partner_still_holds_does_not_fall() {
        let b = BrickId(0);
        let trace = vec![
            at(5.0, 0, EventKind::Grasp { brick: b }),
            at(5.0, 1, EventKind::Grasp { brick: b }),
        ];
        let lost = |events: Vec<Event>| {
            events
                .iter()
                .any(|e| matches!(e.kind, EventKind::Lost { .. }))
        };
        assert!(!lost(killed_events(&trace, 0, 6.0)));
        assert!(lost(killed_events(&trace[..1], 0, 6.0)));
        // The partner placed the pair's brick: the follower killed after it lost nothing (the
        // follower's own trace has the grasp, not the placement).
        let mut placed = trace.clone();
        placed.push(at(8.0, 1, EventKind::Place { brick: b }));
        assert!(!lost(killed_events(&placed, 0, 9.0)));
        // A placement after the kill does not count, nor a partner's grasp after it.
        let late = vec![
            at(5.0, 0, EventKind::Grasp { brick: b }),
            at(9.0, 1, EventKind::Place { brick: b }),
        ];
        assert!(lost(killed_events(&late, 0, 6.0)));
    }

    #[test]
    fn an_agent_on_the_ground_for_good_has_no_last_events() {
        let trace = vec![state(1.0, 2, UavState::Landed)];
        assert!(killed_events(&trace, 2, 5.0).is_empty());
        let trace = vec![state(1.0, 2, UavState::Down)];
        assert!(killed_events(&trace, 2, 5.0).is_empty());
    }
}
