//! The discrete-event simulation of a UAV team building a wall (thesis ch. 4–5).
//!
//! Each UAV runs the state machine of [`crate::state::UavState`]; timed states end by events
//! on one queue ordered by (time, sequence), so runs are deterministic for a seed. Bricks are
//! taken in the shared build order. The UAV (or orange pair) carrying the earliest taken,
//! unplaced brick of the order may enter the zone once the brick's supports are placed, the
//! zone is empty, and its coordination policy agrees; placement and leaving the zone happen
//! at the same instant. If every live UAV is stuck waiting (a brick they need was lost), the
//! one holding the latest brick puts it down and fetches what is needed.

use crate::arena::Point;
use crate::channel::Channel;
use crate::config::MissionConfig;
use crate::core::{after, heard_mode, put_down, After, Board, Brick, Pick, Seen};
use crate::metrics::{Metrics, MetricsObserver};
use crate::policy::{Coordination, EntryQuery};
use crate::state::{CommMode, Event, EventKind, Flood, Observer, UavState};
use mason_order::CostModel;
use mason_wall::{BrickId, BrickType, Wall};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::cmp::{Ordering, Reverse};
use std::collections::BinaryHeap;

/// What a mission flies.
#[derive(Clone, Copy)]
pub struct MissionInput<'a> {
    /// The wall.
    pub wall: &'a Wall,
    /// The shared build order (every brick once, supports first).
    pub order: &'a [BrickId],
    /// Grasp and placement times (t_g, t_d, κ) come from the cost model.
    pub model: &'a CostModel,
    /// A team schedule's bricks per UAV, in the order each UAV places them (`None`: every
    /// UAV takes the next untaken brick of `order`). A UAV takes its own next brick first and
    /// helps with the rest of `order` when its list is done (a failed teammate's bricks).
    pub assignment: Option<&'a [Vec<BrickId>]>,
    /// With a schedule: who re-plans the rest when a UAV fails (`None`: the survivors keep
    /// their lists and help with the orphaned bricks).
    pub replanner: Option<&'a dyn crate::replan::Replanner>,
    /// Team, arena, UAV model, coordination parameters, faults.
    pub config: &'a MissionConfig,
}

/// How a mission ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum MissionStatus {
    /// Every brick placed and every live UAV landed.
    Complete,
    /// The team landed or was lost with bricks left.
    Incomplete,
    /// The time limit came first.
    Timeout,
    /// The mission made more events than its cap allows ([`crate::state::event_cap`]): its
    /// durations are too short to make progress. `MissionResult::flood` says by how much.
    Flooded,
}

/// A mission's result.
#[derive(Clone, Debug, PartialEq, serde::Serialize)]
pub struct MissionResult {
    /// How it ended.
    pub status: MissionStatus,
    /// The metrics.
    pub metrics: Metrics,
    /// When the status is [`MissionStatus::Flooded`], the events and the time at the cap.
    #[serde(skip)]
    pub flood: Option<Flood>,
}

#[derive(Clone, Debug)]
struct Uav {
    state: UavState,
    pos: Point,
    brick: Option<BrickId>,
    partner: Option<usize>,
    grasped: bool,
    waiting_partner: bool,
    joined: bool,
    failures: u32,
    /// When the current timed state ends.
    until: f64,
    token: u64,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum What {
    Timer,
    Fail,
    Heartbeat,
    Enter,
}

#[derive(Clone, Copy, Debug)]
struct Pending {
    t: f64,
    seq: u64,
    uav: usize,
    token: u64,
    what: What,
}

impl PartialEq for Pending {
    fn eq(&self, o: &Self) -> bool {
        self.cmp(o) == Ordering::Equal
    }
}
impl Eq for Pending {}
impl PartialOrd for Pending {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}
impl Ord for Pending {
    fn cmp(&self, o: &Self) -> Ordering {
        self.t.total_cmp(&o.t).then(self.seq.cmp(&o.seq))
    }
}

/// The cached decision for the UAV allowed next.
#[derive(Clone, Copy, Debug, PartialEq)]
struct EntryPlan {
    leader: usize,
    free_since: f64,
    mode: CommMode,
    token: u64,
}

struct Sim<'a, 'o> {
    input: MissionInput<'a>,
    policy: &'a mut dyn Coordination,
    channel: Channel,
    rng: ChaCha8Rng,
    /// What the team knows: with a perfect view, one board for all.
    board: Board,
    uavs: Vec<Uav>,
    queue: BinaryHeap<Reverse<Pending>>,
    seq: u64,
    now: f64,
    zone: Vec<usize>,
    zone_free_since: f64,
    entry: Option<EntryPlan>,
    entry_token: u64,
    modes: Vec<CommMode>,
    last_heard: Vec<Vec<f64>>,
    metrics: MetricsObserver,
    observer: &'o mut dyn Observer,
    /// Events emitted so far, against [`crate::state::event_cap`].
    events: u64,
}

/// Flies one mission and reports every event to `observer`.
pub fn simulate(
    input: MissionInput<'_>,
    policy: &mut dyn Coordination,
    seed: u64,
    observer: &mut dyn Observer,
) -> MissionResult {
    let cfg = input.config;
    let n = cfg.uavs;
    let rewards = input
        .wall
        .bricks()
        .iter()
        .map(|b| b.kind.default_reward())
        .collect();
    // On a perfect channel every heartbeat arrives (and draws nothing from the generator),
    // so `auto` never leaves `comm`: the heartbeats are skipped, and the trace is the same.
    let uses_heartbeats =
        policy.uses_heartbeats() && !Channel::new(&cfg.faults, &cfg.coord).perfect();
    let mut sim = Sim {
        channel: Channel::new(&cfg.faults, &cfg.coord),
        rng: ChaCha8Rng::seed_from_u64(seed),
        board: Board::new(input.wall, input.order, input.assignment, n),
        uavs: (0..n)
            .map(|i| Uav {
                state: UavState::Check,
                pos: cfg.arena.uav_starts[i],
                brick: None,
                partner: None,
                grasped: false,
                waiting_partner: false,
                joined: false,
                failures: 0,
                until: 0.0,
                token: 0,
            })
            .collect(),
        queue: BinaryHeap::new(),
        seq: 0,
        now: 0.0,
        zone: Vec::new(),
        zone_free_since: 0.0,
        entry: None,
        entry_token: 0,
        modes: vec![CommMode::Comm; n],
        last_heard: vec![vec![0.0; n]; n],
        metrics: MetricsObserver::new(n, rewards),
        observer,
        events: 0,
        input,
        policy,
    };
    sim.run(uses_heartbeats)
}

impl Sim<'_, '_> {
    fn emit(&mut self, uav: usize, kind: EventKind) {
        let e = Event {
            t: self.now,
            uav: uav as u32,
            kind,
        };
        self.events += 1;
        self.metrics.event(&e);
        self.observer.event(&e);
    }

    fn push(&mut self, t: f64, uav: usize, token: u64, what: What) {
        self.seq += 1;
        self.queue.push(Reverse(Pending {
            t,
            seq: self.seq,
            uav,
            token,
            what,
        }));
    }

    fn kind_of(&self, b: BrickId) -> BrickType {
        self.input.wall.brick(b).kind
    }

    fn speed(&self) -> f64 {
        self.input.config.uav.speed
    }

    /// `u` and, when they act together, its partner. Owns its items, so `self` stays free.
    fn team(
        &self,
        u: usize,
    ) -> std::iter::Chain<std::iter::Once<usize>, std::option::IntoIter<usize>> {
        std::iter::once(u).chain(self.together(u))
    }

    /// Moves `u` (and its partner, when they act together) to `state`.
    fn go(&mut self, u: usize, state: UavState, outcome: &'static str, duration: Option<f64>) {
        for w in self.team(u) {
            let uav = &mut self.uavs[w];
            uav.state = state;
            uav.token += 1;
            let (x, y) = (uav.pos.x, uav.pos.y);
            self.emit(
                w,
                EventKind::State {
                    state,
                    outcome,
                    x,
                    y,
                },
            );
        }
        if let Some(d) = duration {
            for w in self.team(u) {
                self.uavs[w].until = self.now + d;
            }
            let token = self.uavs[u].token;
            self.push(self.now + d, u, token, What::Timer);
        }
    }

    /// The partner of `u` when both are at the pile or beyond, acting as one.
    fn together(&self, u: usize) -> Option<usize> {
        let p = self.uavs[u].partner?;
        let joined = self.uavs[u].joined && self.uavs[p].joined;
        (joined && self.board.alive(p) && self.uavs[p].brick == self.uavs[u].brick).then_some(p)
    }

    fn run(&mut self, heartbeats: bool) -> MissionResult {
        let cfg = self.input.config;
        let n = cfg.uavs;
        for u in 0..n {
            let (x, y) = (self.uavs[u].pos.x, self.uavs[u].pos.y);
            self.emit(
                u,
                EventKind::State {
                    state: UavState::Check,
                    outcome: "start",
                    x,
                    y,
                },
            );
            self.push(cfg.uav.check_s, u, 0, What::Timer);
            let mut fail_at = cfg
                .faults
                .uav_fail
                .iter()
                .filter(|f| f.uav == u)
                .map(|f| f.at)
                .fold(f64::INFINITY, f64::min);
            if cfg.faults.uav_hazard > 0.0 {
                let rate = cfg.faults.uav_hazard / 3600.0;
                let draw: f64 = self.rng.gen_range(f64::MIN_POSITIVE..1.0);
                fail_at = fail_at.min(-draw.ln() / rate);
            }
            if fail_at.is_finite() {
                self.push(fail_at, u, 0, What::Fail);
            }
            if heartbeats {
                self.push(cfg.coord.heartbeat_s, u, 0, What::Heartbeat);
            }
        }
        let mut status = MissionStatus::Complete;
        let mut flood = None;
        while let Some(Reverse(p)) = self.queue.pop() {
            if p.t > cfg.max_time_s {
                self.now = cfg.max_time_s;
                status = MissionStatus::Timeout;
                break;
            }
            self.now = p.t;
            match p.what {
                What::Timer if p.token == self.uavs[p.uav].token && self.board.alive(p.uav) => {
                    self.timer(p.uav)
                }
                What::Timer
                    if p.token == self.uavs[p.uav].token
                        && self.uavs[p.uav].state == UavState::SafeLand =>
                {
                    self.safe_landed(p.uav)
                }
                What::Fail => self.fail(p.uav),
                What::Heartbeat => self.heartbeat(p.uav),
                What::Enter if p.token == self.entry_token => self.enter(),
                _ => {}
            }
            flood = Flood::check(n, self.now, self.events);
            if flood.is_some() {
                status = MissionStatus::Flooded;
                break;
            }
            if self
                .uavs
                .iter()
                .all(|u| matches!(u.state, UavState::Landed | UavState::Down))
            {
                break;
            }
        }
        if status == MissionStatus::Complete && !self.board.finished() {
            status = MissionStatus::Incomplete;
        }
        let metrics = std::mem::replace(&mut self.metrics, MetricsObserver::new(0, Vec::new()))
            .finish(self.now);
        MissionResult {
            status,
            metrics,
            flood,
        }
    }

    fn timer(&mut self, u: usize) {
        let cfg = self.input.config;
        let model = self.input.model;
        match after(self.uavs[u].state, cfg.uav.takeoff_s) {
            After::Go {
                state,
                outcome,
                duration,
            } => self.go(u, state, outcome, Some(duration)),
            After::Choose => self.choose(u, "airborne"),
            After::AtPile => self.at_pile(u),
            After::Detected => {
                if self.rng.gen::<f64>() < cfg.faults.detect_fail {
                    self.attempt_failed(u);
                } else {
                    self.go(u, UavState::FlyAbove, "found", Some(cfg.uav.above_s));
                }
            }
            After::Above => {
                let b = self.uavs[u].brick.expect("carrying");
                let t_g = model.times(self.kind_of(b)).grasp;
                self.go(u, UavState::Grasp, "above", Some(t_g));
            }
            After::Grasped => {
                if self.rng.gen::<f64>() < cfg.faults.grasp_fail {
                    self.attempt_failed(u);
                } else {
                    let b = self.uavs[u].brick.expect("carrying");
                    for w in self.team(u) {
                        self.uavs[w].grasped = true;
                        self.emit(w, EventKind::Grasp { brick: b });
                    }
                    let wait = cfg.arena.wall_wait(u);
                    let d = self.uavs[u].pos.distance(wait) / self.speed();
                    self.go(u, UavState::FlyToWallWait, "grasped", Some(d));
                }
            }
            After::AtWall => {
                let wait = cfg.arena.wall_wait(u);
                for w in self.team(u) {
                    self.uavs[w].pos = wait;
                }
                self.go(u, UavState::WaitForZone, "arrived", None);
                self.review();
            }
            After::Placed => self.place(u),
            After::Landed => {
                let start = cfg.arena.uav_starts[u];
                self.uavs[u].pos = start;
                self.go(u, UavState::Landed, "landed", None);
            }
            After::Nothing => {}
        }
    }

    /// Takes the next brick of the order, joins an orange pair, idles, or lands.
    fn choose(&mut self, u: usize, outcome: &'static str) {
        let cfg = self.input.config;
        self.uavs[u].brick = None;
        self.uavs[u].partner = None;
        self.uavs[u].grasped = false;
        self.uavs[u].waiting_partner = false;
        self.uavs[u].joined = false;
        self.uavs[u].failures = 0;
        let b = match self.board.pick(self.input.wall, u) {
            Pick::Brick(b) => b,
            Pick::Land => return self.go_land(u, outcome),
            // What is left needs a pair that no longer exists.
            Pick::CannotFinish => return self.go_land(u, "cannot_finish"),
            Pick::Idle => {
                if self.uavs[u].state != UavState::ChooseBrick {
                    self.go(u, UavState::ChooseBrick, "none_free", None);
                }
                return self.review();
            }
        };
        if self.uavs[u].state != UavState::ChooseBrick {
            self.go(u, UavState::ChooseBrick, outcome, None);
        }
        if let Some(first) = self.board.take(b, u) {
            self.uavs[first].partner = Some(u);
            self.uavs[u].partner = Some(first);
        }
        self.uavs[u].brick = Some(b);
        let pile = cfg.arena.pile(self.kind_of(b));
        let d = self.uavs[u].pos.distance(pile) / self.speed();
        self.go(u, UavState::FlyToPile, "chosen", Some(d));
    }

    fn go_land(&mut self, u: usize, outcome: &'static str) {
        let cfg = self.input.config;
        let d = self.uavs[u].pos.distance(cfg.arena.uav_starts[u]) / self.speed();
        self.go(u, UavState::Land, outcome, Some(d + cfg.uav.land_s));
    }

    fn at_pile(&mut self, u: usize) {
        let cfg = self.input.config;
        let b = self.uavs[u].brick.expect("carrying");
        self.uavs[u].pos = cfg.arena.pile(self.kind_of(b));
        if self.kind_of(b).uavs_needed() == 1 {
            return self.go(u, UavState::Detect, "arrived", Some(cfg.uav.detect_s));
        }
        match self.uavs[u].partner {
            Some(p) if self.uavs[p].waiting_partner => {
                // The partner was first; it leads from here.
                self.uavs[p].waiting_partner = false;
                self.uavs[u].waiting_partner = false;
                self.uavs[p].joined = true;
                self.uavs[u].joined = true;
                self.go(
                    p,
                    UavState::Detect,
                    "partner_arrived",
                    Some(cfg.uav.detect_s),
                );
            }
            _ => {
                self.uavs[u].waiting_partner = true;
                self.go(u, UavState::Detect, "waiting_partner", None);
                self.review();
            }
        }
    }

    fn attempt_failed(&mut self, u: usize) {
        let cfg = self.input.config;
        self.uavs[u].failures += 1;
        if self.uavs[u].failures > cfg.uav.retries {
            let who = self.team(u);
            let b = self.uavs[u].brick.expect("carrying");
            self.release(b);
            for w in who.clone() {
                self.uavs[w].partner = None;
                self.uavs[w].joined = false;
            }
            for w in who.clone() {
                self.go(w, UavState::ChooseBrick, "gave_up", None);
            }
            for w in who {
                self.choose(w, "gave_up");
            }
            self.wake_idle();
        } else {
            self.go(u, UavState::Detect, "failed", Some(cfg.uav.detect_s));
        }
    }

    fn release(&mut self, b: BrickId) {
        self.board.release(b);
    }

    /// The expected time in the zone for brick `b` now.
    fn zone_time(&self, b: BrickId) -> f64 {
        let transit = self.input.config.uav.zone_transit_s;
        self.board
            .zone_time(self.input.wall, self.input.model, transit, b)
    }

    /// Re-decides who may enter next, and breaks deadlocks.
    fn review(&mut self) {
        if !self.zone.is_empty() {
            return;
        }
        let Some(b) = self.board.needed() else {
            self.entry = None;
            return;
        };
        let carriers = self.board.carriers(b);
        let ready = carriers.len() == self.kind_of(b).uavs_needed() as usize
            && carriers.iter().all(|&c| {
                let u = &self.uavs[c];
                self.board.alive(c) && u.grasped && u.state == UavState::WaitForZone
            })
            && self.board.supported(self.input.wall, b);
        if !ready {
            self.entry = None;
            self.entry_token += 1;
            return self.break_deadlock();
        }
        let leader = carriers[0];
        let mode = self.modes[leader];
        if let Some(plan) = self.entry {
            if plan.leader == leader && plan.free_since == self.zone_free_since && plan.mode == mode
            {
                return;
            }
        }
        self.entry_token += 1;
        let zone_time = self.zone_time(b);
        let mut q = EntryQuery {
            now: self.now,
            uav: leader,
            team: self.input.config.uavs,
            zone_free_since: self.zone_free_since,
            zone_time,
            mode,
            channel: &self.channel,
            rng: &mut self.rng,
        };
        let t = self.policy.entry_time(&mut q);
        self.entry = Some(EntryPlan {
            leader,
            free_since: self.zone_free_since,
            mode,
            token: self.entry_token,
        });
        if t.is_finite() {
            self.push(t, leader, self.entry_token, What::Enter);
        }
    }

    /// When every live UAV waits and nobody may enter, the holder of the latest brick puts it
    /// down and goes to fetch what is missing.
    fn break_deadlock(&mut self) {
        let seen = |i: usize| Seen {
            alive: self.board.alive(i),
            state: self.uavs[i].state,
            waiting_partner: self.uavs[i].waiting_partner,
            brick: self.uavs[i].brick,
        };
        let Some(h) = put_down(&self.board, self.uavs.len(), seen) else {
            return;
        };
        let b = self.uavs[h].brick.expect("carrying");
        let who = self.board.carriers(b).to_vec();
        self.emit(h, EventKind::Lost { brick: b });
        self.release(b);
        for &w in &who {
            self.go(w, UavState::ChooseBrick, "put_down", None);
        }
        for &w in &who {
            self.choose(w, "put_down");
        }
    }

    fn enter(&mut self) {
        let Some(plan) = self.entry.take() else {
            return;
        };
        let b = self.uavs[plan.leader].brick.expect("carrying");
        let zone_time = self.zone_time(b);
        let who = self.board.carriers(b).to_vec();
        for &w in &who {
            self.zone.push(w);
            self.emit(w, EventKind::ZoneEnter);
        }
        self.go(
            plan.leader,
            UavState::EnterAndPlace,
            "granted",
            Some(zone_time),
        );
    }

    fn place(&mut self, u: usize) {
        let b = self.uavs[u].brick.expect("carrying");
        let who = self.board.place(b);
        self.emit(u, EventKind::Place { brick: b });
        for &w in &who {
            self.zone.retain(|&z| z != w);
            self.emit(w, EventKind::ZoneLeave);
        }
        self.zone_free_since = self.now;
        for &w in &who {
            self.choose(w, "placed");
        }
        self.wake_idle();
        self.review();
    }

    /// Idle UAVs look for work again.
    fn wake_idle(&mut self) {
        for i in 0..self.uavs.len() {
            if self.board.alive(i)
                && self.uavs[i].state == UavState::ChooseBrick
                && self.uavs[i].brick.is_none()
            {
                self.choose(i, "woken");
            }
        }
    }

    fn fail(&mut self, u: usize) {
        if !self.board.alive(u) || matches!(self.uavs[u].state, UavState::Landed | UavState::Land) {
            return;
        }
        let cfg = self.input.config;
        let partner = self.together(u).or(self.uavs[u].partner);
        self.board.set_alive(u, false);
        self.emit(u, EventKind::Fail);
        if let Some(b) = self.uavs[u].brick {
            if self.uavs[u].grasped {
                self.emit(u, EventKind::Lost { brick: b });
                self.release(b);
                if let Some(p) = partner.filter(|&p| self.board.alive(p)) {
                    if self.zone.contains(&p) {
                        self.zone.retain(|&z| z != p);
                        self.emit(p, EventKind::ZoneLeave);
                    }
                    self.uavs[p].partner = None;
                    self.go(p, UavState::ChooseBrick, "partner_failed", None);
                    self.choose(p, "partner_failed");
                }
            } else {
                self.board.drop_carrier(b, u);
                match partner.filter(|&p| self.board.alive(p)) {
                    Some(p) => {
                        // The partner keeps the orange brick and waits for a new partner.
                        self.uavs[p].partner = None;
                        self.uavs[p].joined = false;
                        if self.uavs[p].state == UavState::Detect
                            || self.uavs[p].state == UavState::FlyAbove
                            || self.uavs[p].state == UavState::Grasp
                        {
                            self.uavs[p].waiting_partner = true;
                            self.go(p, UavState::Detect, "partner_failed", None);
                        }
                    }
                    None => self.release(b),
                }
            }
        }
        self.uavs[u].brick = None;
        self.uavs[u].partner = None;
        self.uavs[u].grasped = false;
        // A UAV failing in the zone leaves it when it is down.
        self.uavs[u].token += 1;
        let (x, y) = (self.uavs[u].pos.x, self.uavs[u].pos.y);
        self.uavs[u].state = UavState::SafeLand;
        self.emit(
            u,
            EventKind::State {
                state: UavState::SafeLand,
                outcome: "fault",
                x,
                y,
            },
        );
        let token = self.uavs[u].token;
        self.push(self.now + cfg.uav.land_s, u, token, What::Timer);
        if let Some(r) = self.input.replanner {
            self.replan(r);
        }
        self.wake_idle();
        self.review();
    }

    /// Seconds until `b`'s carrier `c` could start placing it, from `c`'s state.
    fn eta(&self, c: usize, b: BrickId) -> f64 {
        let cfg = self.input.config;
        let kind = self.kind_of(b);
        let left = (self.uavs[c].until - self.now).max(0.0);
        let grasp = self.input.model.times(kind).grasp;
        let to_wall = cfg.arena.pile(kind).distance(cfg.arena.wall_wait(c)) / self.speed();
        let (detect, above) = (cfg.uav.detect_s, cfg.uav.above_s);
        match self.uavs[c].state {
            UavState::FlyToPile => left + detect + above + grasp + to_wall,
            UavState::Detect => left + above + grasp + to_wall,
            UavState::FlyAbove => left + grasp + to_wall,
            UavState::Grasp => left + to_wall,
            UavState::FlyToWallWait => left,
            _ => 0.0,
        }
    }

    /// The survivors plan the rest of the wall from here; their new lists replace the old.
    fn replan(&mut self, replanner: &dyn crate::replan::Replanner) {
        use mason_order::schedule::{Placement, TeamStart};
        let wall = self.input.wall;
        let placed: Vec<BrickId> = wall
            .ids()
            .filter(|&b| self.board.brick(b) == Brick::Placed)
            .collect();
        // Bricks on their way, supports first; one whose support is neither placed nor on
        // its way is left to its carrier and out of the plan.
        let mut on_way = vec![false; wall.len()];
        let mut taken: Vec<BrickId> = wall
            .ids()
            .filter(|&b| self.board.brick(b) == Brick::Taken)
            .collect();
        taken.sort_by_key(|b| (wall.brick(*b).level, b.index()));
        let mut committed = Vec::new();
        for b in taken {
            let crew: Vec<usize> = self
                .board
                .carriers(b)
                .iter()
                .copied()
                .filter(|&c| self.board.alive(c))
                .collect();
            let supported = wall
                .supports(b)
                .iter()
                .all(|&s| self.board.brick(s) == Brick::Placed || on_way[s.index()]);
            let Some(&first) = crew.first().filter(|_| supported) else {
                continue;
            };
            on_way[b.index()] = true;
            let start_s = if self.uavs[first].state == UavState::EnterAndPlace {
                // Placing now: it started when the zone time began.
                self.uavs[first].until - self.now - self.zone_time(b)
            } else {
                self.eta(first, b)
            };
            committed.push(Placement {
                brick: b,
                uavs: crew,
                start_s,
            });
        }
        let carrying: Vec<bool> = (0..self.uavs.len())
            .map(|u| committed.iter().any(|c| c.uavs.contains(&u)))
            .collect();
        let uav_ready_s = self
            .uavs
            .iter()
            .enumerate()
            .map(|(u, v)| {
                let gone =
                    !self.board.alive(u) || matches!(v.state, UavState::Land | UavState::Landed);
                match (gone, carrying[u]) {
                    (true, _) => f64::INFINITY,
                    (false, true) => 0.0,
                    (false, false) => (v.until - self.now).max(0.0),
                }
            })
            .collect();
        let start = TeamStart {
            placed,
            committed,
            uav_ready_s,
        };
        let Some(plan) = replanner.replan(wall, start, self.now) else {
            return;
        };
        // The new order of need: bricks on their way first (as they were), then the plan.
        let mut order: Vec<BrickId> = wall
            .ids()
            .filter(|&b| self.board.brick(b) == Brick::Taken)
            .collect();
        order.sort_by_key(|&b| self.board.rank(b));
        let mut listed = vec![false; wall.len()];
        for &b in &order {
            listed[b.index()] = true;
        }
        for &b in plan.order.iter().chain(self.board.order()) {
            if !std::mem::replace(&mut listed[b.index()], true) {
                order.push(b);
            }
        }
        self.board.set_order(order);
        let reporter = (0..self.uavs.len())
            .find(|&u| self.board.alive(u))
            .unwrap_or(0);
        self.emit(
            reporter,
            EventKind::Replan {
                bricks: plan.order.len() as u32,
            },
        );
        self.board.lists = Some(plan.lists);
    }

    fn safe_landed(&mut self, u: usize) {
        if self.zone.contains(&u) {
            self.zone.retain(|&z| z != u);
            self.emit(u, EventKind::ZoneLeave);
            if self.zone.is_empty() {
                self.zone_free_since = self.now;
            }
        }
        self.uavs[u].token += 1;
        self.uavs[u].state = UavState::Down;
        let (x, y) = (self.uavs[u].pos.x, self.uavs[u].pos.y);
        self.emit(
            u,
            EventKind::State {
                state: UavState::Down,
                outcome: "down",
                x,
                y,
            },
        );
        self.wake_idle();
        self.review();
    }

    fn heartbeat(&mut self, u: usize) {
        if !self.board.alive(u) || matches!(self.uavs[u].state, UavState::Landed | UavState::Down) {
            return;
        }
        let cfg = self.input.config;
        let n = self.uavs.len();
        for v in 0..n {
            if v != u && self.board.alive(v) && self.channel.delivers(self.now, &mut self.rng) {
                self.last_heard[u][v] = self.now;
            }
        }
        let flying = |v: usize| self.board.alive(v) && self.uavs[v].state != UavState::Landed;
        let timeout = cfg.coord.heartbeat_timeout_s;
        let mode = heard_mode(self.now, u, &self.last_heard[u], flying, timeout);
        if mode != self.modes[u] {
            self.modes[u] = mode;
            self.emit(u, EventKind::Comm { mode });
            self.review();
        }
        self.push(self.now + cfg.coord.heartbeat_s, u, 0, What::Heartbeat);
    }
}
