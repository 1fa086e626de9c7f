//! One UAV on its own (issue #14): the decision core of [`crate::core`] driven by what this
//! UAV has heard, for a team of separate processes over a real, lossy network.
//!
//! An [`Agent`] is a pure step machine, so the same code runs against a real clock and Zenoh
//! (`mason agent`) and against a virtual clock and a simulated bus ([`crate::bus`]):
//!
//! * [`Agent::receive`] takes a teammate's [`Message`];
//! * [`Agent::tick`] runs everything due at `now` and returns the messages to publish, the
//!   trace events, and when to wake next.
//!
//! One concept per file:
//!
//! | file | what |
//! |---|---|
//! | [`wire`] | the message schema every program on the team network follows |
//! | `vehicle.rs` | the vehicle: [`Autopilot`], [`WallView`], [`SimulatedVehicle`] |
//! | `membership.rs` | the teammates heard, liveness, majority, declaring out |
//! | `work.rs` | its brick, the claims, the board, choosing and placing |
//! | `pairs.rs` | carrying an orange brick with a partner |
//! | `zone.rs` | entering the wall zone: requests, acknowledgements, leases, windows |
//! | `machine.rs` | its own state machine: states, legs, timers, the step after each state |
//! | `mod.rs` | the agent: its parts, receiving, ticking, publishing its status |
//!
//! **What it knows.** Every message carries the sender's whole [`Status`]: state, position,
//! the brick it claims, its zone request, the requests it acknowledges, every brick it knows
//! placed, when it last heard each teammate, and whom it has declared out. A newer status
//! (by incarnation, then sequence number) replaces an older one, so lost, duplicated and
//! reordered messages do no harm: the next heartbeat repairs what was lost.
//!
//! **The zone** (DESIGN §5). Only the carrier of the brick next needed, with its supports
//! heard placed and the zone heard free, may enter. With `comm`, it first asks: a zone
//! request with a lease (`lease_s`), which every flying teammate must acknowledge in its own
//! latest status; a UAV acknowledges a request when it is outside the zone and its own
//! request does not come first (order rank, then UAV number), and it then keeps out until the
//! request is released or its lease and the longest zone time have passed. With `windows`
//! (or `auto` without heartbeats) it enters only in its own slot. In every mode it also
//! respects the requests it has acknowledged.
//!
//! **Claims.** A UAV claims a brick by carrying it in its status. Two claims of one brick
//! (heard late) are settled by claim time, then UAV number, the same way by everybody; the
//! loser puts its brick down. A UAV places a brick only after every flying teammate's status
//! shows it has heard the claim, so two UAVs cut off from each other never place one brick
//! twice.
//!
//! **Failures.** A teammate unheard for `dead_after_s` is declared out, but only by a UAV
//! that hears a strict majority of the team (itself included); its bricks go back to the
//! piles and the others finish the wall. A UAV never starts a zone entry that could outlast
//! the moment a teammate could declare it out (its lease on the teammate's last hearing of
//! it), so an agent cut off from the majority stops placing before the others take over its
//! work. An agent that learns it was declared out puts its brick down and rejoins under a
//! new incarnation; an agent restarted mid-mission does the same, and learns the bricks
//! already placed from its teammates before it chooses one.
//!
//! **Altitude.** [`Agent::pose`] follows the one rule of [`mod@crate::altitude`]: on the ground
//! before take-off, climbing through `TakeOff`, at its cruise altitude in the air, descending
//! through `Land`.

mod commands;
pub mod gate;
mod machine;
mod membership;
mod pairs;
#[cfg(test)]
mod testkit;
mod vehicle;
pub mod wire;
mod work;
mod zone;

pub use gate::{
    max_message_bytes, Arrival, Body, Checked, DropCause, DropCounts, Dropped, SampleKey,
    MAX_STATIONS,
};
pub use vehicle::{Autopilot, SimulatedVehicle, WallView};
pub use wire::{
    Ack, Command, Message, MessageKind, Order, Out, PairRef, Request, Status, SCHEMA_VERSION,
};

use crate::altitude::altitude_during;
use crate::config::MissionConfig;
use crate::coord::Coord;
use crate::state::{Event, EventKind, UavState};
use machine::{Flight, GROUND};
use mason_order::CostModel;
use mason_wall::{BrickId, Wall};
use membership::Membership;
use pairs::PairState;
use work::Work;
use zone::ZoneState;

/// What an agent flies.
#[derive(Clone, Copy)]
pub struct AgentSetup<'a> {
    /// The wall.
    pub wall: &'a Wall,
    /// The shared build order.
    pub order: &'a [BrickId],
    /// A team schedule's lists per UAV, if any.
    pub assignment: Option<&'a [Vec<BrickId>]>,
    /// Grasp and placement times.
    pub model: &'a CostModel,
    /// Team, arena, UAV model, coordination parameters.
    pub config: &'a MissionConfig,
    /// The coordination policy.
    pub coord: Coord,
    /// The `windows` slot (s).
    pub slot_s: f64,
    /// This UAV (0-based).
    pub uav: usize,
    /// The mission id every message carries.
    pub mission: &'a str,
    /// This agent's incarnation: larger than any earlier run of the same UAV in this mission.
    pub incarnation: u64,
    /// A teammate unheard this long is declared out (s).
    pub dead_after_s: f64,
    /// A zone request may be used this long before it is renewed (s).
    pub lease_s: f64,
}

/// The default time after which an unheard teammate is declared out (s).
pub const DEFAULT_DEAD_AFTER_S: f64 = 30.0;
/// The default lease of a zone request (s).
pub const DEFAULT_LEASE_S: f64 = 5.0;

/// The seed of UAV `uav`'s vehicle (and of its link's fault draws) in incarnation
/// `incarnation` of a mission run with `seed`: one formula for the simulated bus and for
/// `mason agent`, so that a UAV draws the same in both. The two odd constants (the golden
/// ratio's and a xorshift multiplier) keep UAVs and incarnations apart: no two (UAV,
/// incarnation) pairs of one mission share a seed unless the products collide modulo 2⁶⁴.
pub fn agent_seed(seed: u64, uav: usize, incarnation: u64) -> u64 {
    seed ^ (uav as u64 + 1).wrapping_mul(0x9e37_79b9_7f4a_7c15)
        ^ incarnation.wrapping_mul(0x2545_f491_4f6c_dd1d)
}

/// What one [`Agent::tick`] produced.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Tick {
    /// Messages to publish, in order.
    pub messages: Vec<Message>,
    /// Trace events, in order.
    pub events: Vec<Event>,
    /// When to call [`Agent::tick`] again at the latest (s; a received message may call for
    /// it sooner).
    pub wake: f64,
}

/// What goes out: the messages' numbering, the next heartbeat, and the current tick's output.
#[derive(Clone, Debug, Default)]
struct Outbox {
    /// The last sequence number sent in this incarnation.
    seq: u64,
    /// When the next heartbeat is due (s).
    next_heartbeat: f64,
    /// The reason for a message this tick, if anything happened.
    pending: Option<MessageKind>,
    /// The tick being built.
    tick: Tick,
}

/// One UAV: its own state machine and its view of the team.
pub struct Agent<'a> {
    setup: AgentSetup<'a>,
    autopilot: Box<dyn Autopilot + 'a>,
    /// This UAV.
    me: usize,
    /// The team's size.
    n: usize,
    /// Its incarnation now.
    incarnation: u64,
    /// Mission time of the tick being run (s).
    now: f64,
    /// Its own state machine.
    flight: Flight,
    /// Its brick, and what it knows of the wall.
    work: Work,
    /// What it knows of its teammates.
    members: Membership,
    /// The wall zone: inside, its request, the requests it honours.
    zone: ZoneState,
    /// Its orange brick's pair.
    pair: PairState,
    /// What goes out.
    outbox: Outbox,
    /// The check on arrival: its bounds and counts.
    inbox: gate::Inbox,
    /// What the ground stations have ordered.
    orders: commands::Orders,
}

impl<'a> Agent<'a> {
    /// A UAV on the ground at its start, about to run its checks.
    pub fn new(setup: AgentSetup<'a>, autopilot: Box<dyn Autopilot + 'a>) -> Self {
        let n = setup.config.uavs;
        let me = setup.uav;
        Agent {
            me,
            n,
            incarnation: setup.incarnation,
            now: 0.0,
            flight: Flight {
                state: UavState::Check,
                outcome: "start",
                since: f64::NAN,
                pos: setup.config.arena.uav_starts[me],
                leg: None,
                until: f64::INFINITY,
            },
            work: Work::new(setup.wall.len()),
            members: Membership::new(n),
            zone: ZoneState::new(
                n,
                crate::coord::longest_zone_time(setup.wall, setup.model, setup.config),
            ),
            pair: PairState::default(),
            outbox: Outbox::default(),
            inbox: gate::Inbox::new(&setup),
            orders: commands::Orders::default(),
            setup,
            autopilot,
        }
    }

    /// Bricks this UAV placed in earlier incarnations (read back from its own log), so that
    /// a restarted agent never forgets its own work.
    pub fn remember(&mut self, placed: &[BrickId]) {
        self.work.learn_placed(placed.iter().map(|b| b.0));
    }

    /// This UAV.
    pub fn uav(&self) -> usize {
        self.me
    }

    /// Its incarnation now.
    pub fn incarnation(&self) -> u64 {
        self.incarnation
    }

    /// Its state.
    pub fn state(&self) -> UavState {
        self.flight.state
    }

    /// On the ground for good (landed, or down after a fault).
    pub fn finished(&self) -> bool {
        matches!(self.flight.state, UavState::Landed | UavState::Down)
    }

    /// How many bricks it knows placed.
    pub fn placed_known(&self) -> usize {
        self.work.placed_count()
    }

    /// Where it is at `now` (m): straight legs at constant speed; the altitude of
    /// [`crate::altitude::altitude_during`], by how far through its state it is.
    pub fn pose(&self, now: f64) -> (f64, f64, f64) {
        let f = &self.flight;
        let p = f.position(now);
        let z = altitude_during(self.me as u32, f.state, f.progress(now));
        (p.x, p.y, z)
    }

    /// Takes a teammate's message heard at `now`, checked on arrival ([`Agent::admit`]; or
    /// [`Agent::hear`] for both steps).
    pub fn receive(&mut self, now: f64, m: Checked) {
        let m = match m.0 {
            gate::Heard::Status(m) => *m,
            gate::Heard::Command(c) => return self.obey(&c),
        };
        let u = m.uav as usize;
        self.work.learn_placed(m.status.placed.iter().copied());
        self.hear_outs(&m.status.out);
        self.members.back_in(u, m.incarnation);
        // A UAV heard again settles the bricks it held when it went silent: its placed set
        // says whether it placed them.
        self.work.settle_unknown(u, m.incarnation);
        self.members.keep(now, m);
    }

    /// Runs everything due at `now`.
    pub fn tick(&mut self, now: f64) -> Tick {
        self.now = now;
        self.outbox.tick = Tick::default();
        if self.members.started.is_nan() {
            self.members.started = now;
            self.flight.since = now;
            self.emit(EventKind::State {
                state: UavState::Check,
                outcome: "start",
                x: self.flight.pos.x,
                y: self.flight.pos.y,
            });
            self.flight.until = now + self.setup.config.uav.check_s;
            self.outbox.pending = Some(MessageKind::State);
        }
        if !self.finished() {
            self.ground_orders();
            self.expelled();
            self.liveness();
            self.update_mode();
            // A few rounds: a decision may enable another at the same instant.
            for _ in 0..3 {
                if self.flight.until <= now {
                    self.flight.until = f64::INFINITY;
                    self.on_timer();
                }
                self.decide();
            }
        }
        if self.outbox.pending.is_some() || (now >= self.outbox.next_heartbeat && !self.finished())
        {
            let kind = self.outbox.pending.take().unwrap_or(MessageKind::Heartbeat);
            self.publish(kind);
        }
        let mut wake = self.flight.until.min(self.outbox.next_heartbeat);
        if let Some(w) = self.windows_wake() {
            wake = wake.min(w);
        }
        self.outbox.tick.wake = if self.finished() {
            f64::INFINITY
        } else {
            wake.max(now)
        };
        std::mem::take(&mut self.outbox.tick)
    }

    fn emit(&mut self, kind: EventKind) {
        self.outbox.tick.events.push(Event {
            t: self.now,
            uav: self.me as u32,
            kind,
        });
    }

    /// Asks for a message this tick; the most telling reason wins, since every message
    /// carries the whole status anyway.
    fn mark(&mut self, kind: MessageKind) {
        if self
            .outbox
            .pending
            .is_none_or(|p| kind.weight() > p.weight())
        {
            self.outbox.pending = Some(kind);
        }
    }

    fn publish(&mut self, kind: MessageKind) {
        let acks = self.acks();
        let (x, y, z) = self.pose(self.now);
        let status = Status {
            state: self.flight.state,
            outcome: self.flight.outcome.to_string(),
            x,
            y,
            z,
            mode: self.zone.mode,
            brick: self.work.brick.map(|b| b.0),
            claimed_at: self.work.claimed_at,
            grasped: self.work.grasped,
            pair: self.pair.follower,
            in_zone: self.zone.in_zone,
            request: self.zone.request,
            acks,
            placed: self.work.placed_list(),
            heard: self.members.heard(self.me, self.now),
            out: self.members.outs(),
        };
        self.outbox.seq += 1;
        self.outbox.tick.messages.push(Message {
            v: SCHEMA_VERSION,
            mission: self.setup.mission.to_string(),
            uav: self.me as u32,
            incarnation: self.incarnation,
            seq: self.outbox.seq,
            t: self.now,
            kind,
            status,
        });
        self.outbox.next_heartbeat = self.now + self.setup.config.coord.heartbeat_s;
    }
}

#[cfg(test)]
mod tests {
    use super::testkit::Fixture;
    use super::*;

    #[test]
    fn agent_seeds_differ_by_uav_and_incarnation() {
        assert_eq!(agent_seed(5, 0, 1), agent_seed(5, 0, 1));
        let seeds: Vec<u64> = (0..8)
            .flat_map(|u| (1..=8).map(move |i| agent_seed(5, u, i)))
            .collect();
        let mut unique = seeds.clone();
        unique.sort_unstable();
        unique.dedup();
        assert_eq!(unique.len(), seeds.len());
        // The formula `mason agent` has always used.
        assert_eq!(agent_seed(0, 0, 0), 0x9e37_79b9_7f4a_7c15);
        assert_eq!(
            agent_seed(1, 1, 1),
            1 ^ 2u64.wrapping_mul(0x9e37_79b9_7f4a_7c15) ^ 0x2545_f491_4f6c_dd1d
        );
    }

    #[test]
    fn a_lone_agent_builds_the_wall_and_lands() {
        let fixture = Fixture::new("thesis-2x5", 1);
        let mut agents = fixture.agents(Coord::Comm);
        let a = &mut agents[0];
        let (mut t, mut events, mut seqs) = (0.0, Vec::new(), Vec::new());
        let mut land = Vec::new();
        for _ in 0..100_000 {
            if a.finished() {
                break;
            }
            let tick = a.tick(t);
            events.extend(tick.events);
            seqs.extend(tick.messages.iter().map(|m| m.seq));
            if a.state() == UavState::Land {
                land.push(a.pose(t).2);
            }
            t = tick.wake.min(t + 0.5);
        }
        fixture.check(&events);
        assert_eq!(a.state(), UavState::Landed);
        assert_eq!(a.placed_known(), 10);
        assert_eq!(a.pose(t).2, 0.0);
        assert!(seqs.windows(2).all(|w| w[1] == w[0] + 1), "{seqs:?}");
        // It descends through Land, from its cruise altitude.
        assert!(land.windows(2).all(|w| w[1] <= w[0]), "{land:?}");
        assert!(land[0] <= 3.0 && land.iter().any(|&z| z > 0.0 && z < 3.0));
    }

    #[test]
    fn messages_of_other_missions_versions_and_itself_are_ignored() {
        let fixture = Fixture::new("thesis-2x5", 2);
        let mut agents = fixture.agents(Coord::Comm);
        let a = &mut agents[0];
        let mut m = a.tick(0.0).messages.pop().unwrap();
        m.status.placed = vec![3];
        let from_other = |f: &dyn Fn(&mut Message)| {
            let mut x = m.clone();
            x.uav = 1;
            f(&mut x);
            x
        };
        let _ = a.hear(0.1, Arrival::keyed(m.clone())); // its own
        let _ = a.hear(
            0.1,
            Arrival::keyed(from_other(&|x| x.mission = "other".into())),
        );
        let _ = a.hear(
            0.1,
            Arrival::keyed(from_other(&|x| x.v = SCHEMA_VERSION + 1)),
        );
        let _ = a.hear(0.1, Arrival::keyed(from_other(&|x| x.uav = 2)));
        let _ = a.hear(
            0.1,
            Arrival::keyed(from_other(&|x| x.status.heard = vec![0.0])),
        );
        assert_eq!(a.placed_known(), 0);
        let _ = a.hear(0.1, Arrival::keyed(from_other(&|_| {})));
        assert_eq!(a.placed_known(), 1);
        // The same message again, or an older one, changes nothing.
        let mut again = from_other(&|_| {});
        again.status.placed = vec![3, 4];
        let _ = a.hear(0.2, Arrival::keyed(again.clone()));
        assert_eq!(a.placed_known(), 1);
        again.seq += 1;
        let _ = a.hear(0.2, Arrival::keyed(again));
        assert_eq!(a.placed_known(), 2);
    }

    #[test]
    fn remembered_bricks_stay_placed() {
        let fixture = Fixture::new("thesis-2x5", 1);
        let mut agents = fixture.agents(Coord::Comm);
        agents[0].remember(&[BrickId(0), BrickId(2), BrickId(99)]);
        assert_eq!(agents[0].placed_known(), 2);
        let m = agents[0].tick(0.0).messages.pop().unwrap();
        assert_eq!(m.status.placed, vec![0, 2]);
    }
}
