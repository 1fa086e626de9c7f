//! One UAV on its own (issue #14): the decision core of [`crate::core`] driven by what this
//! UAV has heard, for a team of separate processes over a real, lossy network.
//!
//! An [`Agent`] is a pure step machine, so the same code runs against a real clock and Zenoh
//! (`mason agent`) and against a virtual clock and a simulated bus ([`crate::team`]):
//!
//! * [`Agent::receive`] takes a teammate's [`Message`];
//! * [`Agent::tick`] runs everything due at `now` and returns the messages to publish, the
//!   trace events, and when to wake next.
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

use crate::arena::Point;
use crate::config::MissionConfig;
use crate::coord::Coord;
use crate::core::{after, heard_mode, kind, put_down, After, Board, Pick, Seen};
use crate::state::{outcome, CommMode, Event, EventKind, UavState};
use crate::windows::Windows;
use mason_order::CostModel;
use mason_wall::{BrickId, Wall};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};

/// The message schema's version; a message of another version is ignored.
pub const SCHEMA_VERSION: u32 = 1;

/// Why a message was sent. Every message carries the whole status anyway.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum MessageKind {
    /// The periodic heartbeat.
    Heartbeat,
    /// A state transition.
    State,
    /// A brick claimed (or a claim dropped).
    Claim,
    /// A zone request made or renewed.
    ZoneRequest,
    /// Entered the zone.
    ZoneEnter,
    /// Left the zone (and released the request).
    ZoneRelease,
    /// A brick placed.
    Placed,
}

impl MessageKind {
    /// The last segment of the message's key (`<prefix>/<mission>/<uav>/<kind>`).
    pub fn key(self) -> &'static str {
        match self {
            MessageKind::Heartbeat => "heartbeat",
            MessageKind::State => "state",
            MessageKind::Claim => "claim",
            MessageKind::ZoneRequest => "zone_request",
            MessageKind::ZoneEnter => "zone_enter",
            MessageKind::ZoneRelease => "zone_release",
            MessageKind::Placed => "placed",
        }
    }
}

/// A zone request.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Request {
    /// Numbered per incarnation.
    pub id: u64,
    /// The brick to place.
    pub brick: u32,
    /// Its rank in the order (lower goes first; ties by UAV number).
    pub rank: u32,
    /// The request may be used to enter until then (s); renewed while waiting.
    pub expires: f64,
}

/// An acknowledgement of a teammate's zone request.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Ack {
    /// The requester.
    pub uav: u32,
    /// Its incarnation.
    pub incarnation: u64,
    /// The request.
    pub id: u64,
}

/// The partner a pair's leader carries an orange brick with: that UAV under that claim.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct PairRef {
    /// The partner.
    pub uav: u32,
    /// Its incarnation.
    pub incarnation: u64,
    /// When it claimed the brick (s).
    pub claimed_at: f64,
    /// When the pair formed (s): a fall reported since then is this pair's.
    pub since: f64,
}

/// A teammate declared out.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Out {
    /// The UAV.
    pub uav: u32,
    /// The incarnation declared out (a later one is back in).
    pub incarnation: u64,
}

/// What a UAV tells its team in every message.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Status {
    /// Its state.
    pub state: UavState,
    /// The outcome that led there.
    pub outcome: String,
    /// Position (m, arena frame).
    pub x: f64,
    /// Position (m).
    pub y: f64,
    /// Altitude (m).
    pub z: f64,
    /// Its coordination mode.
    pub mode: CommMode,
    /// The brick it claims (wall index), if any.
    pub brick: Option<u32>,
    /// When it claimed it (s).
    pub claimed_at: f64,
    /// Whether it holds the brick.
    pub grasped: bool,
    /// Leading an orange brick's pair: the partner it carries it with.
    pub pair: Option<PairRef>,
    /// Whether it is inside the wall zone.
    pub in_zone: bool,
    /// Its zone request, if any.
    pub request: Option<Request>,
    /// The teammates' requests it acknowledges.
    pub acks: Vec<Ack>,
    /// Every brick it knows placed (wall indices, ascending).
    pub placed: Vec<u32>,
    /// For each UAV, the send time of the last message heard from it (-1: never).
    pub heard: Vec<f64>,
    /// Teammates it holds out.
    pub out: Vec<Out>,
}

/// One message of the team protocol (schema version [`SCHEMA_VERSION`]); JSON on the wire.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Message {
    /// Schema version.
    pub v: u32,
    /// The mission: two missions on one network never mix.
    pub mission: String,
    /// The sender.
    pub uav: u32,
    /// The sender's incarnation (it grows when an agent restarts or rejoins).
    pub incarnation: u64,
    /// Sequence number within the incarnation.
    pub seq: u64,
    /// Mission time when sent (s).
    pub t: f64,
    /// Why it was sent.
    pub kind: MessageKind,
    /// The sender's status.
    pub status: Status,
}

/// The physical side of one UAV: what the decision core cannot decide.
pub trait Autopilot: Send {
    /// Whether detecting the brick below succeeds.
    fn detect(&mut self) -> bool;
    /// Whether grasping succeeds.
    fn grasp(&mut self) -> bool;
    /// At the wall, its camera sees whether `brick` is on it (`None`: no camera). Used when
    /// a teammate went silent holding a brick, and before every placement.
    fn sees_on_wall(&mut self, brick: BrickId) -> Option<bool> {
        let _ = brick;
        None
    }
    /// Carrying an orange brick with a partner: whether the brick has fallen since `since`
    /// (s), because the partner let go (`None`: no such sensor). The pair is one rigid load:
    /// when one side lets go, the other feels it at once.
    fn pair_dropped(&mut self, brick: BrickId, since: f64) -> Option<bool> {
        let _ = (brick, since);
        None
    }
}

/// The simulated world the vehicles share: the bricks on the wall, and the bricks that fell.
pub trait WallView: Send + Sync {
    /// Whether `brick` is on the wall.
    fn placed(&self, brick: BrickId) -> bool;
    /// Whether `brick` was reported lost after `since` (s).
    fn lost_since(&self, brick: BrickId, since: f64) -> bool;
}

/// A vehicle simulated in-process: detection and grasps fail with the configured
/// probabilities, from its own seeded generator; its camera sees a [`WallView`], if given.
pub struct SimulatedVehicle {
    rng: ChaCha8Rng,
    detect_fail: f64,
    grasp_fail: f64,
    world: Option<std::sync::Arc<dyn WallView>>,
}

impl SimulatedVehicle {
    /// A vehicle with `config`'s fault probabilities and no camera.
    pub fn new(config: &MissionConfig, seed: u64) -> Self {
        SimulatedVehicle {
            rng: ChaCha8Rng::seed_from_u64(seed),
            detect_fail: config.faults.detect_fail,
            grasp_fail: config.faults.grasp_fail,
            world: None,
        }
    }

    /// The same, with a camera on `world`.
    pub fn with_world(mut self, world: std::sync::Arc<dyn WallView>) -> Self {
        self.world = Some(world);
        self
    }
}

impl Autopilot for SimulatedVehicle {
    fn detect(&mut self) -> bool {
        self.rng.gen::<f64>() >= self.detect_fail
    }
    fn grasp(&mut self) -> bool {
        self.rng.gen::<f64>() >= self.grasp_fail
    }
    fn sees_on_wall(&mut self, brick: BrickId) -> Option<bool> {
        self.world.as_ref().map(|w| w.placed(brick))
    }
    fn pair_dropped(&mut self, brick: BrickId, since: f64) -> Option<bool> {
        self.world.as_ref().map(|w| w.lost_since(brick, since))
    }
}

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

/// Whether two times that may have crossed the wire name the same instant: a JSON round trip
/// by another client may change a float's last bits.
fn same_time(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-6 * (1.0 + a.abs().max(b.abs()))
}

/// The default time after which an unheard teammate is declared out (s).
pub const DEFAULT_DEAD_AFTER_S: f64 = 30.0;
/// The default lease of a zone request (s).
pub const DEFAULT_LEASE_S: f64 = 5.0;

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

#[derive(Clone, Debug)]
struct Peer {
    incarnation: u64,
    seq: u64,
    /// The sender's time of its last message.
    sent_t: f64,
    /// Local time when last heard.
    heard_at: f64,
    status: Status,
}

/// A teammate's request this UAV acknowledged: (incarnation, request id, lease end,
/// priority). It keeps out of the zone for it until it is released or runs out.
type Honored = (u64, u64, f64, (u32, u32));

/// One UAV: its own state machine and its view of the team.
pub struct Agent<'a> {
    setup: AgentSetup<'a>,
    autopilot: Box<dyn Autopilot + 'a>,
    me: usize,
    n: usize,
    incarnation: u64,
    seq: u64,
    // Own state.
    state: UavState,
    outcome: &'static str,
    pos: Point,
    leg: Option<(Point, Point, f64, f64)>,
    until: f64,
    brick: Option<BrickId>,
    claimed_at: f64,
    grasped: bool,
    failures: u32,
    in_zone: bool,
    /// A pair's follower that left the zone with its leader's time and waits to hear the
    /// brick placed.
    pair_left: bool,
    /// A pair's follower: the leader it carries the brick with.
    pair_leader: Option<(usize, u64)>,
    /// A pair's leader: the partner it started detecting with.
    pair_follower: Option<PairRef>,
    /// When its pair formed (both had claimed the brick; `NaN`: no pair).
    pair_since: f64,
    request: Option<Request>,
    next_request: u64,
    mode: CommMode,
    next_heartbeat: f64,
    started: f64,
    // What it knows.
    peers: Vec<Option<Peer>>,
    placed: Vec<bool>,
    out: Vec<Option<u64>>,
    honored: Vec<Option<Honored>>,
    /// Bricks whose fate is unknown: the UAV (and incarnation) declared out while holding
    /// them may have placed them. Settled when that UAV is heard again.
    unknown: Vec<Option<(usize, u64)>>,
    /// The longest zone time of any brick (s).
    zone_max: f64,
    // Output of the current tick.
    pending: Option<MessageKind>,
    tick: Tick,
    now: f64,
}

const GROUND: [UavState; 3] = [UavState::Check, UavState::Landed, UavState::Down];

impl<'a> Agent<'a> {
    /// A UAV on the ground at its start, about to run its checks.
    pub fn new(setup: AgentSetup<'a>, autopilot: Box<dyn Autopilot + 'a>) -> Self {
        let n = setup.config.uavs;
        let me = setup.uav;
        Agent {
            me,
            n,
            incarnation: setup.incarnation,
            seq: 0,
            state: UavState::Check,
            outcome: "start",
            pos: setup.config.arena.uav_starts[me],
            leg: None,
            until: f64::INFINITY,
            brick: None,
            claimed_at: 0.0,
            grasped: false,
            failures: 0,
            in_zone: false,
            pair_left: false,
            pair_leader: None,
            pair_follower: None,
            pair_since: f64::NAN,
            request: None,
            next_request: 1,
            mode: CommMode::Comm,
            next_heartbeat: 0.0,
            started: f64::NAN,
            peers: vec![None; n],
            placed: vec![false; setup.wall.len()],
            out: vec![None; n],
            honored: vec![None; n],
            unknown: vec![None; setup.wall.len()],
            zone_max: crate::coord::longest_zone_time(setup.wall, setup.model, setup.config),
            pending: None,
            tick: Tick::default(),
            now: 0.0,
            setup,
            autopilot,
        }
    }

    /// Bricks this UAV placed in earlier incarnations (read back from its own log), so that
    /// a restarted agent never forgets its own work.
    pub fn remember(&mut self, placed: &[BrickId]) {
        for b in placed {
            if let Some(p) = self.placed.get_mut(b.index()) {
                *p = true;
            }
        }
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
        self.state
    }

    /// On the ground for good (landed, or down after a fault).
    pub fn finished(&self) -> bool {
        matches!(self.state, UavState::Landed | UavState::Down)
    }

    /// How many bricks it knows placed.
    pub fn placed_known(&self) -> usize {
        self.placed.iter().filter(|p| **p).count()
    }

    /// Where it is at `now` (m): straight legs at constant speed, at its own altitude.
    pub fn pose(&self, now: f64) -> (f64, f64, f64) {
        let z = if GROUND.contains(&self.state) {
            0.0
        } else {
            3.0 + self.me as f64
        };
        match self.leg {
            Some((a, b, t0, t1)) if t1 > t0 => {
                let f = ((now - t0) / (t1 - t0)).clamp(0.0, 1.0);
                (a.x + (b.x - a.x) * f, a.y + (b.y - a.y) * f, z)
            }
            _ => (self.pos.x, self.pos.y, z),
        }
    }

    /// Takes a teammate's message heard at `now`. Other missions, other schema versions, its
    /// own messages and stale ones are ignored.
    pub fn receive(&mut self, now: f64, m: Message) {
        let u = m.uav as usize;
        if m.v != SCHEMA_VERSION
            || m.mission != self.mission_id()
            || u >= self.n
            || u == self.me
            || m.status.heard.len() != self.n
        {
            return;
        }
        if let Some(p) = &self.peers[u] {
            if (m.incarnation, m.seq) <= (p.incarnation, p.seq) {
                return;
            }
        }
        for &b in &m.status.placed {
            if let Some(p) = self.placed.get_mut(b as usize) {
                *p = true;
            }
        }
        for o in &m.status.out {
            let v = o.uav as usize;
            if v == self.me {
                continue; // handled in tick
            }
            if v < self.n && self.out[v].is_none_or(|i| i < o.incarnation) {
                let known = self.peers[v].as_ref().map_or(0, |p| p.incarnation);
                if known <= o.incarnation {
                    self.out[v] = Some(o.incarnation);
                    self.mark_unknown(v, o.incarnation);
                }
            }
        }
        if self.out[u].is_some_and(|i| m.incarnation > i) {
            self.out[u] = None; // back under a new incarnation
        }
        // A UAV heard again settles the bricks it held when it went silent: its placed set
        // says whether it placed them.
        for k in &mut self.unknown {
            if k.is_some_and(|(v, inc)| v == u && m.incarnation > inc) {
                *k = None;
            }
        }
        self.peers[u] = Some(Peer {
            incarnation: m.incarnation,
            seq: m.seq,
            heard_at: now,
            sent_t: m.t,
            status: m.status,
        });
    }

    fn mission_id(&self) -> &'a str {
        self.setup.mission
    }

    /// Runs everything due at `now`.
    pub fn tick(&mut self, now: f64) -> Tick {
        self.now = now;
        self.tick = Tick::default();
        if self.started.is_nan() {
            self.started = now;
            self.emit(EventKind::State {
                state: UavState::Check,
                outcome: "start",
                x: self.pos.x,
                y: self.pos.y,
            });
            self.until = now + self.setup.config.uav.check_s;
            self.pending = Some(MessageKind::State);
        }
        if !self.finished() {
            self.expelled();
            self.liveness();
            self.update_mode();
            // A few rounds: a decision may enable another at the same instant.
            for _ in 0..3 {
                if self.until <= now {
                    self.until = f64::INFINITY;
                    self.on_timer();
                }
                self.decide();
            }
        }
        if self.pending.is_some() || (now >= self.next_heartbeat && !self.finished()) {
            let kind = self.pending.take().unwrap_or(MessageKind::Heartbeat);
            self.publish(kind);
        }
        let mut wake = self.until.min(self.next_heartbeat);
        if let Some(w) = self.windows_wake() {
            wake = wake.min(w);
        }
        self.tick.wake = if self.finished() {
            f64::INFINITY
        } else {
            wake.max(now)
        };
        std::mem::take(&mut self.tick)
    }

    fn emit(&mut self, kind: EventKind) {
        self.tick.events.push(Event {
            t: self.now,
            uav: self.me as u32,
            kind,
        });
    }

    fn mark(&mut self, kind: MessageKind) {
        // The most telling reason wins; every message carries the whole status anyway.
        let order = |k: MessageKind| match k {
            MessageKind::Heartbeat => 0,
            MessageKind::State => 1,
            MessageKind::Claim => 2,
            MessageKind::ZoneRequest => 3,
            MessageKind::ZoneEnter => 4,
            MessageKind::ZoneRelease => 5,
            MessageKind::Placed => 6,
        };
        if self.pending.is_none_or(|p| order(kind) > order(p)) {
            self.pending = Some(kind);
        }
    }

    fn go(&mut self, state: UavState, outcome: &'static str, duration: Option<f64>) {
        self.state = state;
        self.outcome = outcome;
        self.emit(EventKind::State {
            state,
            outcome,
            x: self.pos.x,
            y: self.pos.y,
        });
        self.until = duration.map_or(f64::INFINITY, |d| self.now + d);
        self.mark(MessageKind::State);
    }

    fn fly(&mut self, state: UavState, outcome: &'static str, to: Point, extra: f64) {
        let d = self.pos.distance(to) / self.setup.config.uav.speed;
        self.go(state, outcome, Some(d + extra));
        self.leg = Some((self.pos, to, self.now, self.now + d));
    }

    fn arrive(&mut self, at: Point) {
        self.pos = at;
        self.leg = None;
    }

    // ----- what it knows -------------------------------------------------------------------

    fn peer_status(&self, v: usize) -> Option<&Status> {
        self.peers[v].as_ref().map(|p| &p.status)
    }

    fn is_out(&self, v: usize) -> bool {
        match (self.out[v], &self.peers[v]) {
            (Some(i), Some(p)) => p.incarnation <= i,
            (Some(_), None) => true,
            (None, _) => false,
        }
    }

    /// Whether teammate `v` should still be heard: not out, not on the ground for good.
    fn flying(&self, v: usize) -> bool {
        v != self.me
            && !self.is_out(v)
            && self
                .peer_status(v)
                .is_none_or(|s| !matches!(s.state, UavState::Landed | UavState::Down))
    }

    fn last_heard(&self) -> Vec<f64> {
        (0..self.n)
            .map(|v| match &self.peers[v] {
                _ if v == self.me => self.now,
                Some(p) => p.heard_at,
                None => self.started,
            })
            .collect()
    }

    /// The board as this UAV knows it.
    fn board(&self) -> Board {
        let s = self.setup;
        let mut board = Board::new(s.wall, s.order, s.assignment, self.n);
        for v in 0..self.n {
            let alive = if v == self.me {
                true
            } else {
                self.flying(v)
                    && self
                        .peer_status(v)
                        .is_none_or(|st| st.state != UavState::SafeLand)
            };
            board.set_alive(v, alive);
        }
        for (i, p) in self.placed.iter().enumerate() {
            if *p {
                board.place(BrickId(i as u32));
            }
        }
        for (i, k) in self.unknown.iter().enumerate() {
            if k.is_some() && !self.placed[i] {
                board.hold_unknown(BrickId(i as u32));
            }
        }
        for (b, _, v) in self.claims() {
            let needed = kind(s.wall, b).uavs_needed() as usize;
            let unknown = self.unknown[b.index()].is_some();
            if !unknown
                && board.brick(b) != crate::core::Brick::Placed
                && board.carriers(b).len() < needed
            {
                board.take(b, v);
            }
        }
        board
    }

    /// Every claim known (its own and its flying teammates'), first claimed first.
    fn claims(&self) -> Vec<(BrickId, f64, usize)> {
        let mut claims: Vec<(BrickId, f64, usize)> = Vec::new();
        if let Some(b) = self.brick {
            claims.push((b, self.claimed_at, self.me));
        }
        for v in 0..self.n {
            if !self.flying(v) {
                continue;
            }
            if let Some(st) = self.peer_status(v) {
                if let Some(b) = st.brick.filter(|&b| (b as usize) < self.placed.len()) {
                    claims.push((BrickId(b), st.claimed_at, v));
                }
            }
        }
        claims.sort_by(|a, b| a.1.total_cmp(&b.1).then(a.2.cmp(&b.2)));
        claims
    }

    fn majority(&self) -> bool {
        let timeout = self.setup.config.coord.heartbeat_timeout_s;
        let heard = (0..self.n)
            .filter(|&v| {
                v != self.me
                    && !self.is_out(v)
                    && self.peers[v]
                        .as_ref()
                        .is_some_and(|p| self.now - p.heard_at <= timeout)
            })
            .count();
        2 * (heard + 1) > self.n
    }

    /// Declares out the teammates unheard for `dead_after_s`, when it hears a majority.
    fn liveness(&mut self) {
        if !self.majority() || self.held_out() {
            return;
        }
        for v in 0..self.n {
            if !self.flying(v) {
                continue;
            }
            let last = self.peers[v].as_ref().map_or(self.started, |p| p.heard_at);
            if self.now - last > self.setup.dead_after_s {
                let inc = self.peers[v].as_ref().map_or(0, |p| p.incarnation);
                self.out[v] = Some(inc);
                self.honored[v] = None;
                self.mark_unknown(v, inc);
                self.mark(MessageKind::State);
            }
        }
    }

    /// Whether its orange brick fell since it claimed it (its partner let go).
    fn pair_fell(&mut self, b: BrickId) -> bool {
        kind(self.setup.wall, b).uavs_needed() == 2
            && !self.pair_since.is_nan()
            && self.autopilot.pair_dropped(b, self.pair_since) == Some(true)
    }

    /// At the wall: look at the bricks whose fate is unknown, and at its own.
    fn inspect(&mut self) {
        let mut look: Vec<usize> = (0..self.unknown.len())
            .filter(|&i| self.unknown[i].is_some())
            .collect();
        look.extend(self.brick.map(BrickId::index));
        for i in look {
            match self.autopilot.sees_on_wall(BrickId(i as u32)) {
                Some(true) => {
                    self.placed[i] = true;
                    self.unknown[i] = None;
                }
                Some(false) => self.unknown[i] = None,
                None => {}
            }
        }
    }

    /// `v` (incarnation `inc`) is out: the brick it held, grasped, may be on the wall.
    fn mark_unknown(&mut self, v: usize, inc: u64) {
        let Some(p) = self.peers[v].as_ref().filter(|p| p.incarnation == inc) else {
            return;
        };
        if let Some(b) = p.status.brick.filter(|_| p.status.grasped) {
            let b = b as usize;
            if b < self.placed.len() && !self.placed[b] {
                self.unknown[b] = Some((v, inc));
            }
        }
    }

    /// A teammate holds it out: it puts its brick down and rejoins as a new incarnation.
    fn held_out(&self) -> bool {
        let me = self.me as u32;
        (0..self.n).any(|v| {
            self.peer_status(v).is_some_and(|s| {
                s.out
                    .iter()
                    .any(|o| o.uav == me && o.incarnation >= self.incarnation)
            })
        })
    }

    fn expelled(&mut self) {
        if !self.held_out() || GROUND.contains(&self.state) {
            return;
        }
        self.incarnation += 1;
        self.seq = 0;
        self.next_request = 1;
        self.drop_brick("declared_out");
        self.choose("rejoined");
    }

    fn update_mode(&mut self) {
        if self.setup.coord != Coord::Auto || GROUND.contains(&self.state) {
            return;
        }
        let heard = self.last_heard();
        let timeout = self.setup.config.coord.heartbeat_timeout_s;
        let mode = heard_mode(self.now, self.me, &heard, |v| self.flying(v), timeout);
        if mode != self.mode {
            self.mode = mode;
            self.emit(EventKind::Comm { mode });
            self.mark(MessageKind::State);
        }
    }

    fn zone_mode(&self) -> CommMode {
        match self.setup.coord {
            Coord::Comm => CommMode::Comm,
            Coord::Windows => CommMode::Windows,
            Coord::Auto => self.mode,
        }
    }

    // ----- the state machine ---------------------------------------------------------------

    fn on_timer(&mut self) {
        let cfg = self.setup.config;
        match after(self.state, cfg.uav.takeoff_s) {
            After::Go {
                state,
                outcome,
                duration,
            } => {
                // A (re)started agent learns the wall from its teammates before it flies.
                let heard_all = (0..self.n).all(|v| v == self.me || self.peers[v].is_some());
                if state == UavState::TakeOff
                    && !heard_all
                    && self.now - self.started < self.setup.dead_after_s
                {
                    self.until = self.now + cfg.coord.heartbeat_s;
                    return;
                }
                self.go(state, outcome, Some(duration));
            }
            After::Choose => self.choose("airborne"),
            After::AtPile => {
                let b = self.brick.expect("carrying");
                self.arrive(cfg.arena.pile(kind(self.setup.wall, b)));
                if kind(self.setup.wall, b).uavs_needed() == 1 {
                    self.go(UavState::Detect, "arrived", Some(cfg.uav.detect_s));
                } else {
                    // Wait for the partner; the pair's leader detects and grasps for both.
                    self.go(UavState::Detect, "waiting_partner", None);
                }
            }
            After::Detected => {
                if self.autopilot.detect() {
                    self.go(UavState::FlyAbove, "found", Some(cfg.uav.above_s));
                } else {
                    self.attempt_failed();
                }
            }
            After::Above => {
                let b = self.brick.expect("carrying");
                let t_g = self.setup.model.times(kind(self.setup.wall, b)).grasp;
                self.go(UavState::Grasp, "above", Some(t_g));
            }
            After::Grasped => {
                if self.autopilot.grasp() {
                    self.grasped_brick();
                } else {
                    self.attempt_failed();
                }
            }
            After::AtWall => {
                self.arrive(cfg.arena.wall_wait(self.me));
                self.go(UavState::WaitForZone, "arrived", None);
            }
            After::Placed => match self.brick {
                Some(b) if !self.leader(b) => {
                    // A pair's follower: the leader's zone time is over, so the pair has left;
                    // the brick counts as placed once the leader says so.
                    self.in_zone = false;
                    self.pair_left = true;
                    self.emit(EventKind::ZoneLeave);
                    self.go(UavState::WaitForZone, "pair_left", None);
                    self.mark(MessageKind::ZoneRelease);
                }
                _ => self.place(),
            },
            After::Landed => {
                self.arrive(cfg.arena.uav_starts[self.me]);
                self.go(UavState::Landed, "landed", None);
            }
            After::Nothing => {}
        }
    }

    fn grasped_brick(&mut self) {
        let b = self.brick.expect("carrying");
        self.grasped = true;
        self.emit(EventKind::Grasp { brick: b });
        let wait = self.setup.config.arena.wall_wait(self.me);
        self.fly(UavState::FlyToWallWait, "grasped", wait, 0.0);
    }

    fn attempt_failed(&mut self) {
        self.failures += 1;
        if self.failures > self.setup.config.uav.retries {
            self.drop_brick("gave_up");
            self.choose("gave_up");
        } else {
            let d = self.setup.config.uav.detect_s;
            self.go(UavState::Detect, "failed", Some(d));
        }
    }

    /// Lets go of its brick (lost if grasped) and of its request.
    fn drop_brick(&mut self, outcome: &'static str) {
        let covered = self.brick.is_some_and(|b| self.pair_fell(b));
        if let Some(b) = self.brick.take() {
            // An orange brick its partner already let fall was reported lost by the partner.
            if self.grasped && !covered {
                self.emit(EventKind::Lost { brick: b });
            }
            if self.in_zone {
                self.in_zone = false;
                self.emit(EventKind::ZoneLeave);
            }
            self.grasped = false;
            self.request = None;
            self.failures = 0;
            self.mark(MessageKind::Claim);
            if self.state != UavState::ChooseBrick {
                self.go(UavState::ChooseBrick, outcome, None);
            }
        }
    }

    fn choose(&mut self, outcome: &'static str) {
        let board = self.board();
        let wall = self.setup.wall;
        self.failures = 0;
        self.pair_left = false;
        self.pair_leader = None;
        self.pair_follower = None;
        self.pair_since = f64::NAN;
        match board.pick(wall, self.me) {
            Pick::Brick(b) => {
                if self.state != UavState::ChooseBrick {
                    self.go(UavState::ChooseBrick, outcome, None);
                }
                self.brick = Some(b);
                self.claimed_at = self.now;
                self.grasped = false;
                self.mark(MessageKind::Claim);
                let pile = self.setup.config.arena.pile(kind(wall, b));
                self.fly(UavState::FlyToPile, "chosen", pile, 0.0);
            }
            Pick::Land | Pick::CannotFinish => {
                let o = if board.finished() {
                    outcome
                } else {
                    "cannot_finish"
                };
                let start = self.setup.config.arena.uav_starts[self.me];
                let land = self.setup.config.uav.land_s;
                self.fly(UavState::Land, o, start, land);
            }
            Pick::Idle => {
                if self.state != UavState::ChooseBrick {
                    self.go(UavState::ChooseBrick, "none_free", None);
                }
            }
        }
    }

    fn place(&mut self) {
        let b = self.brick.take().expect("carrying");
        self.placed[b.index()] = true;
        self.emit(EventKind::Place { brick: b });
        self.in_zone = false;
        self.emit(EventKind::ZoneLeave);
        self.grasped = false;
        self.request = None;
        self.mark(MessageKind::Placed);
        self.choose("placed");
    }

    // ----- decisions -----------------------------------------------------------------------

    fn decide(&mut self) {
        if GROUND.contains(&self.state) || matches!(self.state, UavState::Land | UavState::TakeOff)
        {
            return;
        }
        let wall = self.setup.wall;
        if self.state == UavState::WaitForZone {
            self.inspect();
        }
        // Its brick placed by somebody else, or its claim lost to an earlier one.
        if let Some(b) = self.brick {
            if self.placed[b.index()] {
                // Placed: by its pair's leader (it leaves the zone with it), or by a UAV
                // that won the claim (its own copy is put down).
                let pair = kind(wall, b).uavs_needed() == 2;
                if self.in_zone {
                    self.in_zone = false;
                    self.emit(EventKind::ZoneLeave);
                }
                if !pair && self.grasped {
                    self.emit(EventKind::Lost { brick: b });
                }
                self.brick = None;
                self.grasped = false;
                self.request = None;
                self.mark(MessageKind::Claim);
                return self.choose("placed");
            }
            let mine = self.board().carriers(b).contains(&self.me);
            if !self.in_zone && !mine {
                self.drop_brick("claim_lost");
                return self.choose("claim_lost");
            }
        }
        // The partner let an orange brick fall: it is gone for both.
        if let Some(b) = self.brick {
            if self.grasped && !self.placed[b.index()] && self.pair_fell(b) {
                self.drop_brick("partner_failed");
                return self.choose("partner_failed");
            }
        }
        // A pair's follower lets go when its leader does (the leader's `lost` covers both).
        if let (Some(b), Some((l, inc))) = (self.brick, self.pair_leader) {
            if self.grasped && !self.flying(l) {
                // Its leader is out: the brick fell with it.
                self.drop_brick("partner_failed");
                return self.choose("partner_failed");
            }
            let restarted = self.peers[l].as_ref().is_some_and(|p| p.incarnation != inc);
            let let_go = self.grasped
                && self.flying(l)
                && self.peer_status(l).is_some_and(|st| {
                    st.brick != Some(b.0)
                        || !st.grasped
                        || st.pair.is_none_or(|r| r.uav != self.me as u32)
                });
            if let_go {
                if restarted {
                    // The leader was killed and is back: nobody said the brick fell.
                    self.emit(EventKind::Lost { brick: b });
                }
                if self.in_zone {
                    self.in_zone = false;
                    self.emit(EventKind::ZoneLeave);
                }
                self.brick = None;
                self.grasped = false;
                self.request = None;
                self.mark(MessageKind::Claim);
                self.go(UavState::ChooseBrick, "put_down", None);
                return self.choose("put_down");
            }
        }
        if self.state == UavState::ChooseBrick && self.brick.is_none() {
            return self.choose("woken");
        }
        let Some(b) = self.brick else {
            return;
        };
        if kind(wall, b).uavs_needed() == 2 {
            self.pair(b);
        }
        if self.state == UavState::WaitForZone && self.leader(b) {
            self.zone(b);
        }
    }

    /// The pair's leader: its first taker.
    fn leader(&self, b: BrickId) -> bool {
        self.board().carriers(b).first() == Some(&self.me)
    }

    fn partner(&self, b: BrickId) -> Option<usize> {
        self.board()
            .carriers(b)
            .iter()
            .copied()
            .find(|&c| c != self.me)
    }

    /// An orange brick: the leader detects and grasps once the partner is at the pile; the
    /// partner follows the leader's steps as it hears them.
    fn pair(&mut self, b: BrickId) {
        let cfg = self.setup.config;
        let partner = self.partner(b);
        let partner_status = partner.and_then(|p| self.peer_status(p)).cloned();
        let same = |s: &Status| s.brick == Some(b.0);
        if self.leader(b) {
            let mirrored = matches!(self.state, UavState::FlyAbove | UavState::Grasp);
            if mirrored && self.until.is_infinite() {
                // It followed a leader that is gone: it leads now, from the start.
                self.go(UavState::Detect, "partner_failed", None);
            }
            // The partner it started with let go, restarted, or is gone.
            if let Some(r) = self.pair_follower {
                let v = r.uav as usize;
                let still = self.flying(v)
                    && self.peers[v].as_ref().is_some_and(|p| {
                        p.incarnation == r.incarnation
                            && p.status.brick == Some(b.0)
                            && same_time(p.status.claimed_at, r.claimed_at)
                    });
                if !still {
                    self.pair_follower = None;
                    if self.grasped {
                        self.drop_brick("partner_failed");
                        return self.choose("partner_failed");
                    }
                    self.go(UavState::Detect, "partner_failed", None);
                }
            }
            if self.state == UavState::Detect && self.until.is_infinite() {
                let ready = partner_status.as_ref().is_some_and(|s| {
                    same(s)
                        && matches!(
                            s.state,
                            UavState::Detect | UavState::FlyAbove | UavState::Grasp
                        )
                });
                if let (true, Some(p)) = (ready, partner) {
                    let peer = self.peers[p].as_ref().expect("heard");
                    self.pair_since = self.now;
                    self.pair_follower = Some(PairRef {
                        uav: p as u32,
                        incarnation: peer.incarnation,
                        claimed_at: peer.status.claimed_at,
                        since: self.now,
                    });
                    self.go(UavState::Detect, "partner_arrived", Some(cfg.uav.detect_s));
                }
            }
            // A partner lost after the grasp: the brick is lost with it.
            if self.grasped && partner.is_none() {
                self.drop_brick("partner_failed");
                self.choose("partner_failed");
            }
            return;
        }
        // The follower follows a leader that carries the brick with this very claim.
        let (me, inc, at) = (self.me as u32, self.incarnation, self.claimed_at);
        let mine = |r: &PairRef| r.uav == me && r.incarnation == inc && same_time(r.claimed_at, at);
        let Some(lead) = partner_status.filter(|s| same(s) && s.pair.as_ref().is_some_and(mine))
        else {
            return;
        };
        let since = lead.pair.map_or(f64::NAN, |r| r.since);
        let at_pile = matches!(
            self.state,
            UavState::Detect | UavState::FlyAbove | UavState::Grasp
        );
        match lead.state {
            UavState::FlyAbove | UavState::Grasp if at_pile && lead.state != self.state => {
                self.pair_since = since;
                self.go(lead.state, outcome(&lead.outcome).unwrap_or("ok"), None);
            }
            UavState::FlyToWallWait | UavState::WaitForZone | UavState::EnterAndPlace
                if at_pile && lead.grasped =>
            {
                self.pair_since = since;
                if self.pair_fell(b) {
                    // The leader's status is old news: the brick already fell.
                    self.drop_brick("partner_failed");
                    return self.choose("partner_failed");
                }
                self.grasped = true;
                self.pair_leader = partner.map(|l| {
                    let inc = self.peers[l].as_ref().map_or(0, |p| p.incarnation);
                    (l, inc)
                });
                self.emit(EventKind::Grasp { brick: b });
                let wait = cfg.arena.wall_wait(self.me);
                self.fly(UavState::FlyToWallWait, "grasped", wait, 0.0);
            }
            UavState::EnterAndPlace
                if lead.in_zone
                    && self.state == UavState::WaitForZone
                    && !self.in_zone
                    && !self.pair_left =>
            {
                // Enter with the leader, and leave by the end of its zone time at the latest.
                let s = self.setup;
                let board = self.board();
                let zt = board.zone_time(s.wall, s.model, s.config.uav.zone_transit_s, b);
                let hb = s.config.coord.heartbeat_s;
                self.in_zone = true;
                self.emit(EventKind::ZoneEnter);
                self.go(UavState::EnterAndPlace, "granted", Some(zt + 2.0 * hb));
                self.mark(MessageKind::ZoneEnter);
            }
            _ => {}
        }
    }

    /// The leader of the brick's carriers at the wall: enter when the rules allow.
    fn zone(&mut self, b: BrickId) {
        let s = self.setup;
        let board = self.board();
        if board.needed() != Some(b) || !board.supported(s.wall, b) {
            self.clear_request();
            return self.deadlock(&board);
        }
        if let Some(p) = self.partner(b) {
            // The partner must be at the wall with the brick.
            let ready = self.peer_status(p).is_some_and(|st| {
                st.brick == Some(b.0) && st.grasped && st.state == UavState::WaitForZone
            });
            if !ready {
                return;
            }
        } else if kind(s.wall, b).uavs_needed() == 2 {
            return;
        }
        let zone_time = board.zone_time(s.wall, s.model, s.config.uav.zone_transit_s, b);
        let prio = (board.rank(b) as u32, self.me as u32);
        if !self.zone_clear(zone_time, prio) {
            return;
        }
        let go = match self.zone_mode() {
            CommMode::Windows => {
                let w = Windows { slot: s.slot_s };
                w.next_entry(self.now, self.me, self.n, zone_time) <= self.now
            }
            CommMode::Comm => self.acknowledged(b, prio.0),
        };
        if go {
            let who: Vec<usize> = board.carriers(b).to_vec();
            debug_assert!(who.contains(&self.me));
            self.in_zone = true;
            self.emit(EventKind::ZoneEnter);
            self.go(UavState::EnterAndPlace, "granted", Some(zone_time));
            self.mark(MessageKind::ZoneEnter);
        }
    }

    /// The checks of every mode: the zone heard free, no acknowledged request first, every
    /// flying teammate has heard its claim, and no teammate could declare it out before it
    /// is out of the zone again.
    fn zone_clear(&mut self, zone_time: f64, prio: (u32, u32)) -> bool {
        let hb = self.setup.config.coord.heartbeat_s;
        let me = self.me;
        for v in 0..self.n {
            if !self.counts(v) {
                continue;
            }
            let Some(st) = self.peer_status(v) else {
                return false;
            };
            if st.in_zone {
                return false;
            }
            let heard_me = st.heard.get(me).copied().unwrap_or(-1.0);
            if !self.is_out(v) && heard_me < self.claimed_at {
                return false;
            }
            if self.now + zone_time + 3.0 * hb >= heard_me + self.setup.dead_after_s {
                return false;
            }
        }
        self.refresh_honored();
        !self.honored.iter().flatten().any(|&(_, _, _, p)| p < prio)
    }

    /// Whether teammate `v` may still be in the game: not on the ground for good, and not
    /// held out by a fresh majority. A teammate only this UAV holds out may still be flying,
    /// cut off, and could come back and hold this UAV out: its lease, its zone and its
    /// acknowledgement still count.
    fn counts(&self, v: usize) -> bool {
        v != self.me
            && self
                .peer_status(v)
                .is_none_or(|s| !matches!(s.state, UavState::Landed | UavState::Down))
            && !(self.is_out(v) && self.out_confirmed(v))
    }

    /// Whether a strict majority of the team, heard lately, holds `v` out: `v` then cannot
    /// form a majority of its own without hearing that it is out.
    fn out_confirmed(&self, v: usize) -> bool {
        let timeout = self.setup.config.coord.heartbeat_timeout_s;
        let inc = self.out[v].unwrap_or(0);
        let holders = (0..self.n)
            .filter(|&w| w != v && w != self.me)
            .filter(|&w| {
                self.peers[w].as_ref().is_some_and(|p| {
                    self.now - p.heard_at <= timeout
                        && p.status
                            .out
                            .iter()
                            .any(|o| o.uav as usize == v && o.incarnation >= inc)
                })
            })
            .count();
        2 * (holders + 1) > self.n
    }

    /// With `comm`: its request, renewed when its lease runs out, acknowledged by every
    /// flying teammate.
    fn acknowledged(&mut self, b: BrickId, rank: u32) -> bool {
        let renew = self
            .request
            .is_none_or(|r| r.brick != b.0 || r.expires < self.now);
        if renew {
            self.request = Some(Request {
                id: self.next_request,
                brick: b.0,
                rank,
                expires: self.now + self.setup.lease_s,
            });
            self.next_request += 1;
            self.mark(MessageKind::ZoneRequest);
            return false;
        }
        let r = self.request.expect("requested");
        let me = self.me as u32;
        (0..self.n).filter(|&v| self.counts(v)).all(|v| {
            self.peer_status(v).is_some_and(|st| {
                !st.in_zone
                    && st
                        .acks
                        .iter()
                        .any(|a| a.uav == me && a.incarnation == self.incarnation && a.id == r.id)
            })
        })
    }

    fn clear_request(&mut self) {
        if self.request.take().is_some() {
            self.mark(MessageKind::ZoneRelease);
        }
    }

    /// Forgets acknowledged requests that were released or ran out.
    fn refresh_honored(&mut self) {
        let longest = self.zone_max;
        for v in 0..self.n {
            let Some((inc, id, until, _)) = self.honored[v] else {
                continue;
            };
            let released = self.peers[v].as_ref().is_some_and(|p| {
                p.incarnation > inc
                    || (!p.status.in_zone && p.status.request.is_none_or(|r| r.id != id))
            });
            if released || self.now > until + longest || self.is_out(v) {
                self.honored[v] = None;
            }
        }
    }

    /// The acknowledgements this UAV gives now (and remembers, to keep out of the zone).
    fn acks(&mut self) -> Vec<Ack> {
        let board = self.board();
        let mine = self.request.map(|r| (r.rank, self.me as u32));
        let mut acks = Vec::new();
        for v in 0..self.n {
            if !self.flying(v) || self.in_zone {
                continue;
            }
            let Some(p) = &self.peers[v] else {
                continue;
            };
            let Some(r) = p.status.request else {
                continue;
            };
            if r.expires < self.now || self.placed.get(r.brick as usize).is_none_or(|&x| x) {
                continue;
            }
            let theirs = (r.rank, v as u32);
            let b = BrickId(r.brick);
            // Its partner in a pair always agrees; a claim it lost never gets an ack.
            let partner = self.brick == Some(b);
            let winner = board.carriers(b).first() == Some(&v);
            if !winner {
                continue;
            }
            if partner || mine.is_none_or(|m| theirs < m) {
                acks.push(Ack {
                    uav: v as u32,
                    incarnation: p.incarnation,
                    id: r.id,
                });
                self.honored[v] = Some((p.incarnation, r.id, r.expires, theirs));
            }
        }
        acks
    }

    /// Every live UAV waits and nobody may enter: the holder of the latest brick puts it
    /// down (the same rule as the simulator, on what it has heard).
    fn deadlock(&mut self, board: &Board) {
        let team: Vec<Seen> = (0..self.n)
            .map(|v| {
                if v == self.me {
                    return Seen {
                        alive: true,
                        state: self.state,
                        waiting_partner: false,
                        brick: self.brick,
                    };
                }
                let st = self.peer_status(v);
                Seen {
                    alive: board.alive(v),
                    state: st.map_or(UavState::Check, |s| s.state),
                    waiting_partner: st.is_some_and(|s| s.outcome == "waiting_partner"),
                    brick: st.and_then(|s| s.brick).map(BrickId),
                }
            })
            .collect();
        if put_down(board, self.n, |i| team[i]) == Some(self.me) {
            if let Some(b) = self.brick {
                if self.grasped {
                    self.emit(EventKind::Lost { brick: b });
                    self.grasped = false;
                }
                self.brick = None;
                self.request = None;
                self.mark(MessageKind::Claim);
                self.go(UavState::ChooseBrick, "put_down", None);
                self.choose("put_down");
            }
        }
    }

    fn windows_wake(&self) -> Option<f64> {
        if self.state != UavState::WaitForZone || self.zone_mode() != CommMode::Windows {
            return None;
        }
        let b = self.brick?;
        let s = self.setup;
        let zt = self
            .board()
            .zone_time(s.wall, s.model, s.config.uav.zone_transit_s, b);
        let w = Windows { slot: s.slot_s };
        // A slot open now but not used (something else holds it back) is looked at again
        // on the next message or heartbeat.
        Some(w.next_entry(self.now, self.me, self.n, zt)).filter(|&t| t > self.now)
    }

    fn publish(&mut self, kind: MessageKind) {
        let acks = self.acks();
        let (x, y, z) = self.pose(self.now);
        let heard = (0..self.n)
            .map(|v| {
                if v == self.me {
                    self.now
                } else {
                    // The sender's time of the last message heard (its own clock).
                    self.peers[v].as_ref().map_or(-1.0, |p| p.sent_t)
                }
            })
            .collect();
        let status = Status {
            state: self.state,
            outcome: self.outcome.to_string(),
            x,
            y,
            z,
            mode: self.mode,
            brick: self.brick.map(|b| b.0),
            claimed_at: self.claimed_at,
            grasped: self.grasped,
            pair: self.pair_follower,
            in_zone: self.in_zone,
            request: self.request,
            acks,
            placed: (0..self.placed.len() as u32)
                .filter(|&b| self.placed[b as usize])
                .collect(),
            heard,
            out: (0..self.n)
                .filter_map(|v| {
                    self.out[v].map(|i| Out {
                        uav: v as u32,
                        incarnation: i,
                    })
                })
                .collect(),
        };
        self.seq += 1;
        self.tick.messages.push(Message {
            v: SCHEMA_VERSION,
            mission: self.mission_id().to_string(),
            uav: self.me as u32,
            incarnation: self.incarnation,
            seq: self.seq,
            t: self.now,
            kind,
            status,
        });
        self.next_heartbeat = self.now + self.setup.config.coord.heartbeat_s;
    }
}
