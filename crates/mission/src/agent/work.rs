//! The agent's work: the brick it claims and carries, what it knows of the wall, the board it
//! builds from the claims it has heard, and choosing, grasping, placing and putting down.
//!
//! A UAV claims a brick by carrying it in its status. Every agent settles two claims of one
//! brick the same way, by claim time and then UAV number ([`Agent::claims`]); the loser puts
//! its brick down. A brick held by a teammate declared out is *unknown* — it may be on the
//! wall — until that teammate is heard again or a camera at the wall sees it.

use super::membership::Member;
use super::wire::Status;
use super::{Agent, MessageKind};
use crate::core::{kind, Board, Brick, Pick};
use crate::state::{EventKind, UavState};
use mason_wall::BrickId;

/// Its brick, and what it knows of the wall.
#[derive(Clone, Debug)]
pub(super) struct Work {
    /// The brick it claims.
    pub(super) brick: Option<BrickId>,
    /// When it claimed it (s).
    pub(super) claimed_at: f64,
    /// Whether it holds it.
    pub(super) grasped: bool,
    /// When it last grasped a brick (s; `NaN` before its first grasp).
    pub(super) grasped_at: f64,
    /// Detect and grasp failures on this brick so far.
    pub(super) failures: u32,
    /// Every brick known placed (by wall index).
    placed: Vec<bool>,
    /// Bricks whose fate is unknown: the UAV (under that incarnation) declared out while
    /// holding them may have placed them. Settled when that UAV is heard again.
    pub(super) unknown: Vec<Option<Member>>,
}

/// A claim heard (or its own): `uav` claimed `brick` at `at`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Claim {
    pub(super) brick: BrickId,
    pub(super) at: f64,
    pub(super) uav: usize,
}

impl Work {
    /// Nothing claimed, nothing known placed, on a wall of `bricks` bricks.
    pub(super) fn new(bricks: usize) -> Self {
        Work {
            brick: None,
            claimed_at: 0.0,
            grasped: false,
            grasped_at: f64::NAN,
            failures: 0,
            placed: vec![false; bricks],
            unknown: vec![None; bricks],
        }
    }

    /// Whether brick `i` is known placed (`None`: no such brick on the wall).
    pub(super) fn known_placed(&self, i: usize) -> Option<bool> {
        self.placed.get(i).copied()
    }

    /// Learns bricks placed (wall indices; those outside the wall are ignored).
    pub(super) fn learn_placed(&mut self, bricks: impl IntoIterator<Item = u32>) {
        for b in bricks {
            if let Some(p) = self.placed.get_mut(b as usize) {
                *p = true;
            }
        }
    }

    /// `uav` heard under an incarnation later than `incarnation`: the bricks it held when it
    /// was declared out are no longer unknown (its status says whether it placed them).
    pub(super) fn settle_unknown(&mut self, uav: usize, incarnation: u64) {
        for k in &mut self.unknown {
            if k.is_some_and(|h| h.uav == uav && incarnation > h.incarnation) {
                *k = None;
            }
        }
    }

    /// `holder`, last heard with `status`, is out: the brick it held, grasped, may be on the
    /// wall.
    pub(super) fn held_by_out(&mut self, holder: Member, status: &Status) {
        if let Some(b) = status.brick.filter(|_| status.grasped) {
            let b = b as usize;
            if b < self.placed.len() && !self.placed[b] {
                self.unknown[b] = Some(holder);
            }
        }
    }

    /// How many bricks it knows placed.
    pub(super) fn placed_count(&self) -> usize {
        self.placed.iter().filter(|p| **p).count()
    }

    /// The bricks it knows placed, ascending (the status's `placed`).
    pub(super) fn placed_list(&self) -> Vec<u32> {
        (0..self.placed.len() as u32)
            .filter(|&b| self.placed[b as usize])
            .collect()
    }
}

impl Agent<'_> {
    /// The board as this UAV knows it.
    pub(super) fn board(&self) -> Board {
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
        for (i, p) in self.work.placed.iter().enumerate() {
            if *p {
                board.place(BrickId(i as u32));
            }
        }
        for (i, k) in self.work.unknown.iter().enumerate() {
            if k.is_some() && !self.work.placed[i] {
                board.hold_unknown(BrickId(i as u32));
            }
        }
        for c in self.claims() {
            let needed = kind(s.wall, c.brick).uavs_needed() as usize;
            let unknown = self.work.unknown[c.brick.index()].is_some();
            if !unknown
                && board.brick(c.brick) != Brick::Placed
                && board.carriers(c.brick).len() < needed
            {
                board.take(c.brick, c.uav);
            }
        }
        board
    }

    /// Every claim known (its own and its flying teammates'), first claimed first (ties by
    /// UAV number).
    pub(super) fn claims(&self) -> Vec<Claim> {
        let mut claims: Vec<Claim> = Vec::new();
        if let Some(b) = self.work.brick {
            claims.push(Claim {
                brick: b,
                at: self.work.claimed_at,
                uav: self.me,
            });
        }
        for v in 0..self.n {
            if !self.flying(v) {
                continue;
            }
            if let Some(st) = self.peer_status(v) {
                if let Some(b) = st.brick.filter(|&b| (b as usize) < self.work.placed.len()) {
                    claims.push(Claim {
                        brick: BrickId(b),
                        at: st.claimed_at,
                        uav: v,
                    });
                }
            }
        }
        claims.sort_by(|a, b| a.at.total_cmp(&b.at).then(a.uav.cmp(&b.uav)));
        claims
    }

    /// `v` (incarnation `inc`) is out: the brick it held, grasped, may be on the wall.
    pub(super) fn mark_unknown(&mut self, v: usize, inc: u64) {
        let Some(p) = self.members.peers[v]
            .as_ref()
            .filter(|p| p.incarnation == inc)
        else {
            return;
        };
        let holder = Member {
            uav: v,
            incarnation: inc,
        };
        self.work.held_by_out(holder, &p.status);
    }

    /// At the wall: look at the bricks whose fate is unknown, and at its own.
    pub(super) fn inspect(&mut self) {
        let mut look: Vec<usize> = (0..self.work.unknown.len())
            .filter(|&i| self.work.unknown[i].is_some())
            .collect();
        look.extend(self.work.brick.map(BrickId::index));
        for i in look {
            match self.autopilot.sees_on_wall(BrickId(i as u32)) {
                Some(true) => {
                    self.work.placed[i] = true;
                    self.work.unknown[i] = None;
                }
                Some(false) => self.work.unknown[i] = None,
                None => {}
            }
        }
    }

    /// Leaves the zone, if inside.
    pub(super) fn leave_zone(&mut self) {
        if self.zone.in_zone {
            self.zone.in_zone = false;
            self.emit(EventKind::ZoneLeave);
        }
    }

    /// Forgets its brick and its request (what it held, it no longer holds), and says so.
    pub(super) fn forget_brick(&mut self) {
        self.work.brick = None;
        self.work.grasped = false;
        self.zone.request = None;
        self.mark(MessageKind::Claim);
    }

    pub(super) fn grasped_brick(&mut self) {
        let b = self.work.brick.expect("carrying");
        self.work.grasped = true;
        self.work.grasped_at = self.now;
        self.emit(EventKind::Grasp { brick: b });
        let wait = self.setup.config.arena.wall_wait(self.me);
        self.fly(UavState::FlyToWallWait, "grasped", wait, 0.0);
    }

    pub(super) fn attempt_failed(&mut self) {
        self.work.failures += 1;
        if self.work.failures > self.setup.config.uav.retries {
            self.drop_brick("gave_up");
            self.choose("gave_up");
        } else {
            let d = self.setup.config.uav.detect_s;
            self.go(UavState::Detect, "failed", Some(d));
        }
    }

    /// Lets go of its brick (lost if grasped) and of its request.
    pub(super) fn drop_brick(&mut self, outcome: &'static str) {
        let covered = self.work.brick.is_some_and(|b| self.fell_since_grasp(b));
        if let Some(b) = self.work.brick.take() {
            // An orange brick its partner let fall while it held it was reported lost by the
            // partner; a fall reported before its own grasp does not cover that grasp.
            if self.work.grasped && !covered {
                self.emit(EventKind::Lost { brick: b });
            }
            self.leave_zone();
            self.work.grasped = false;
            self.zone.request = None;
            self.work.failures = 0;
            self.mark(MessageKind::Claim);
            if self.flight.state != UavState::ChooseBrick {
                self.go(UavState::ChooseBrick, outcome, None);
            }
        }
    }

    /// Chooses its next brick on the board it knows, or lands, or waits.
    pub(super) fn choose(&mut self, outcome: &'static str) {
        let board = self.board();
        let wall = self.setup.wall;
        self.work.failures = 0;
        self.pair = Default::default();
        // A ground station ordered it down: it takes no brick and flies home.
        let pick = match self.orders.landing() {
            Some(o) => Err(o),
            None => Ok(board.pick(wall, self.me)),
        };
        let pick = match pick {
            Ok(p) => p,
            Err(o) => {
                let start = self.setup.config.arena.uav_starts[self.me];
                let land = self.setup.config.uav.land_s;
                return self.fly(UavState::Land, o, start, land);
            }
        };
        match pick {
            Pick::Brick(b) => {
                if self.flight.state != UavState::ChooseBrick {
                    self.go(UavState::ChooseBrick, outcome, None);
                }
                self.work.brick = Some(b);
                self.work.claimed_at = self.now;
                self.work.grasped = false;
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
                if self.flight.state != UavState::ChooseBrick {
                    self.go(UavState::ChooseBrick, "none_free", None);
                }
            }
        }
    }

    /// Its brick is on the wall: it leaves the zone and chooses again.
    pub(super) fn place(&mut self) {
        let b = self.work.brick.take().expect("carrying");
        self.work.placed[b.index()] = true;
        self.emit(EventKind::Place { brick: b });
        self.zone.in_zone = false;
        self.emit(EventKind::ZoneLeave);
        self.work.grasped = false;
        self.zone.request = None;
        self.mark(MessageKind::Placed);
        self.choose("placed");
    }

    /// Its brick placed by somebody else, or its claim lost to an earlier one: it lets go
    /// and chooses again. Whether it did.
    pub(super) fn settle_claim(&mut self) -> bool {
        let Some(b) = self.work.brick else {
            return false;
        };
        if self.work.placed[b.index()] {
            // Placed: by its pair's leader (it leaves the zone with it), or by a UAV that won
            // the claim (its own copy is put down).
            let pair = kind(self.setup.wall, b).uavs_needed() == 2;
            self.leave_zone();
            if !pair && self.work.grasped {
                self.emit(EventKind::Lost { brick: b });
            }
            self.forget_brick();
            self.choose("placed");
            return true;
        }
        let mine = self.board().carriers(b).contains(&self.me);
        if !self.zone.in_zone && !mine {
            self.drop_brick("claim_lost");
            self.choose("claim_lost");
            return true;
        }
        false
    }
}

#[cfg(test)]
mod tests {
    use super::super::testkit::{fly, Fixture};
    use super::*;
    use crate::coord::Coord;
    use crate::state::CommMode;

    fn grasping(brick: u32) -> Status {
        Status {
            state: UavState::FlyToWallWait,
            outcome: "grasped".into(),
            x: 0.0,
            y: 0.0,
            z: 0.0,
            mode: CommMode::Comm,
            brick: Some(brick),
            claimed_at: 0.0,
            grasped: true,
            pair: None,
            in_zone: false,
            request: None,
            acks: Vec::new(),
            placed: Vec::new(),
            heard: Vec::new(),
            out: Vec::new(),
        }
    }

    #[test]
    fn it_learns_placed_bricks_and_ignores_bricks_outside_the_wall() {
        let mut w = Work::new(5);
        w.learn_placed([3, 1, 3, 99]);
        assert_eq!(w.placed_list(), vec![1, 3]);
        assert_eq!(w.placed_count(), 2);
        assert_eq!(w.known_placed(3), Some(true));
        assert_eq!(w.known_placed(0), Some(false));
        assert_eq!(w.known_placed(99), None);
    }

    #[test]
    fn a_brick_held_by_an_out_teammate_is_unknown_until_it_is_heard_again() {
        let mut w = Work::new(5);
        let holder = Member {
            uav: 2,
            incarnation: 1,
        };
        w.held_by_out(holder, &grasping(4));
        assert_eq!(w.unknown[4], Some(holder));
        w.settle_unknown(2, 1);
        assert_eq!(
            w.unknown[4],
            Some(holder),
            "the same incarnation settles nothing"
        );
        w.settle_unknown(1, 2);
        assert_eq!(w.unknown[4], Some(holder), "another UAV settles nothing");
        w.settle_unknown(2, 2);
        assert_eq!(w.unknown[4], None);
        // A brick not grasped, or already placed, is not unknown.
        let mut claimed = grasping(2);
        claimed.grasped = false;
        w.held_by_out(holder, &claimed);
        w.learn_placed([3]);
        w.held_by_out(holder, &grasping(3));
        assert!(w.unknown.iter().all(Option::is_none));
    }

    #[test]
    fn two_claims_of_one_brick_go_to_the_first_and_the_other_puts_it_down() {
        // Nobody hears anybody until 35.5 s: both take off after `dead_after_s` (30 s), claim
        // the first brick at 35 s, and only then hear each other.
        let fixture = Fixture::new("thesis-2x5", 2);
        let mut agents = fixture.agents(Coord::Comm);
        let (events, _) = fly(&mut agents, 2000.0, |_, _, _, t| t > 35.5);
        let claim_lost: Vec<u32> = events
            .iter()
            .filter(|e| {
                matches!(
                    e.kind,
                    EventKind::State {
                        outcome: "claim_lost",
                        ..
                    }
                )
            })
            .map(|e| e.uav)
            .collect();
        assert_eq!(
            claim_lost,
            vec![1],
            "equal claim times: the lower UAV number wins"
        );
        fixture.check(&events);
        assert!(agents
            .iter()
            .all(|a| a.finished() && a.placed_known() == 10));
    }
}
