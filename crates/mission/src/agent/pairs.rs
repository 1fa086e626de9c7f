//! Orange bricks, carried by two UAVs together (DESIGN §5).
//!
//! The first of the brick's two carriers on the board is the pair's *leader*: once its
//! partner is at the pile too, it detects and grasps for both and names the partner, under
//! the partner's claim, in its status ([`PairRef`]). The *follower* follows the steps of a
//! leader that names it, grasps when the leader has, and enters and leaves the zone with it.
//! The pair is one rigid load: when one side lets go — it fails, restarts, or takes another
//! brick — the brick falls for both, and the side that reports it lost is the one that let
//! go (or the leader, for a follower that cannot tell).

use super::membership::Member;
use super::wire::{same_time, PairRef, Status};
use super::{Agent, MessageKind};
use crate::core::kind;
use crate::state::{outcome, EventKind, UavState};
use mason_wall::BrickId;

/// Its orange brick's pair, if it carries one.
#[derive(Clone, Copy, Debug)]
pub(super) struct PairState {
    /// A follower that left the zone with its leader's time and waits to hear the brick
    /// placed.
    pub(super) left: bool,
    /// A follower: the leader it carries the brick with.
    pub(super) leader: Option<Member>,
    /// A leader: the partner it started detecting with.
    pub(super) follower: Option<PairRef>,
    /// When the pair formed (s; `NaN`: no pair): a fall reported since then is this pair's.
    pub(super) since: f64,
}

impl Default for PairState {
    /// No pair.
    fn default() -> Self {
        PairState {
            left: false,
            leader: None,
            follower: None,
            since: f64::NAN,
        }
    }
}

impl Agent<'_> {
    /// The pair's leader: its first taker.
    pub(super) fn leader(&self, b: BrickId) -> bool {
        self.board().carriers(b).first() == Some(&self.me)
    }

    /// The other carrier of `b`, if any.
    pub(super) fn partner(&self, b: BrickId) -> Option<usize> {
        self.board()
            .carriers(b)
            .iter()
            .copied()
            .find(|&c| c != self.me)
    }

    /// Whether its orange brick fell since the pair formed (its partner let go).
    pub(super) fn pair_fell(&mut self, b: BrickId) -> bool {
        kind(self.setup.wall, b).uavs_needed() == 2
            && !self.pair.since.is_nan()
            && self.autopilot.pair_dropped(b, self.pair.since) == Some(true)
    }

    /// Whether its orange brick fell since the pair formed and since it grasped it: a fall
    /// its partner reported then covers its own grasp.
    pub(super) fn fell_since_grasp(&mut self, b: BrickId) -> bool {
        let since = self.pair.since.max(self.work.grasped_at);
        kind(self.setup.wall, b).uavs_needed() == 2
            && !self.pair.since.is_nan()
            && self.autopilot.pair_dropped(b, since) == Some(true)
    }

    /// The partner let go of the brick they carry: it lets go too and chooses again.
    /// Whether it did.
    pub(super) fn pair_let_go(&mut self) -> bool {
        // The partner let an orange brick fall: it is gone for both.
        if let Some(b) = self.work.brick {
            if self.work.grasped
                && self.work.known_placed(b.index()) == Some(false)
                && self.pair_fell(b)
            {
                self.drop_brick("partner_failed");
                self.choose("partner_failed");
                return true;
            }
        }
        // A follower lets go when its leader does (the leader's `lost` covers both).
        let (Some(b), Some(leader)) = (self.work.brick, self.pair.leader) else {
            return false;
        };
        let l = leader.uav;
        if self.work.grasped && !self.flying(l) {
            // Its leader is out: the brick fell with it.
            self.drop_brick("partner_failed");
            self.choose("partner_failed");
            return true;
        }
        let restarted = self.members.peers[l]
            .as_ref()
            .is_some_and(|p| p.incarnation != leader.incarnation);
        let let_go = self.work.grasped
            && self.flying(l)
            && self.peer_status(l).is_some_and(|st| {
                st.brick != Some(b.0)
                    || !st.grasped
                    || st.pair.is_none_or(|r| r.uav != self.me as u32)
            });
        if !let_go {
            return false;
        }
        if restarted {
            // The leader was killed and is back: nobody said the brick fell.
            self.emit(EventKind::Lost { brick: b });
        }
        self.leave_zone();
        self.forget_brick();
        self.go(UavState::ChooseBrick, "put_down", None);
        self.choose("put_down");
        true
    }

    /// An orange brick: the leader detects and grasps once the partner is at the pile; the
    /// partner follows the leader's steps as it hears them.
    pub(super) fn pair(&mut self, b: BrickId) {
        if self.leader(b) {
            self.lead(b);
        } else {
            self.follow(b);
        }
    }

    /// The leader's side of a pair.
    fn lead(&mut self, b: BrickId) {
        let cfg = self.setup.config;
        let partner = self.partner(b);
        let partner_status = partner.and_then(|p| self.peer_status(p)).cloned();
        let mirrored = matches!(self.flight.state, UavState::FlyAbove | UavState::Grasp);
        if mirrored && self.flight.until.is_infinite() {
            // It followed a leader that is gone: it leads now, from the start.
            self.go(UavState::Detect, "partner_failed", None);
        }
        // The partner it started with let go, restarted, or is gone.
        if let Some(r) = self.pair.follower {
            let v = r.uav as usize;
            let still = self.flying(v)
                && self.members.peers[v].as_ref().is_some_and(|p| {
                    p.incarnation == r.incarnation
                        && p.status.brick == Some(b.0)
                        && same_time(p.status.claimed_at, r.claimed_at)
                });
            if !still {
                self.pair.follower = None;
                if self.work.grasped {
                    self.drop_brick("partner_failed");
                    return self.choose("partner_failed");
                }
                self.go(UavState::Detect, "partner_failed", None);
            }
        }
        if self.flight.state == UavState::Detect && self.flight.until.is_infinite() {
            let ready = partner_status.as_ref().is_some_and(|s| {
                s.brick == Some(b.0)
                    && matches!(
                        s.state,
                        UavState::Detect | UavState::FlyAbove | UavState::Grasp
                    )
            });
            if let (true, Some(p)) = (ready, partner) {
                let peer = self.members.peers[p].as_ref().expect("heard");
                self.pair.since = self.now;
                self.pair.follower = Some(PairRef {
                    uav: p as u32,
                    incarnation: peer.incarnation,
                    claimed_at: peer.status.claimed_at,
                    since: self.now,
                });
                self.go(UavState::Detect, "partner_arrived", Some(cfg.uav.detect_s));
            }
        }
        // A partner lost after the grasp: the brick is lost with it.
        if self.work.grasped && partner.is_none() {
            self.drop_brick("partner_failed");
            self.choose("partner_failed");
        }
    }

    /// The follower's side: it follows a leader that carries the brick with this very claim.
    fn follow(&mut self, b: BrickId) {
        let cfg = self.setup.config;
        let partner = self.partner(b);
        let (me, inc, at) = (self.me as u32, self.incarnation, self.work.claimed_at);
        let mine = |r: &PairRef| r.uav == me && r.incarnation == inc && same_time(r.claimed_at, at);
        let Some(lead) = partner
            .and_then(|p| self.peer_status(p))
            .filter(|s: &&Status| s.brick == Some(b.0) && s.pair.as_ref().is_some_and(mine))
            .cloned()
        else {
            return;
        };
        let since = lead.pair.map_or(f64::NAN, |r| r.since);
        let state = self.flight.state;
        let at_pile = matches!(
            state,
            UavState::Detect | UavState::FlyAbove | UavState::Grasp
        );
        match lead.state {
            UavState::FlyAbove | UavState::Grasp if at_pile && lead.state != state => {
                self.pair.since = since;
                self.go(lead.state, outcome(&lead.outcome).unwrap_or("ok"), None);
            }
            UavState::FlyToWallWait | UavState::WaitForZone | UavState::EnterAndPlace
                if at_pile && lead.grasped =>
            {
                self.pair.since = since;
                if self.pair_fell(b) {
                    // The leader's status is old news: the brick already fell.
                    self.drop_brick("partner_failed");
                    return self.choose("partner_failed");
                }
                self.work.grasped = true;
                self.work.grasped_at = self.now;
                self.pair.leader = partner.map(|l| Member {
                    uav: l,
                    incarnation: self.members.incarnation_of(l),
                });
                self.emit(EventKind::Grasp { brick: b });
                let wait = cfg.arena.wall_wait(self.me);
                self.fly(UavState::FlyToWallWait, "grasped", wait, 0.0);
            }
            UavState::EnterAndPlace
                if lead.in_zone
                    && state == UavState::WaitForZone
                    && !self.zone.in_zone
                    && !self.pair.left =>
            {
                // Enter with the leader, and leave by the end of its zone time at the latest.
                let s = self.setup;
                let board = self.board();
                let zt = board.zone_time(s.wall, s.model, s.config.uav.zone_transit_s, b);
                let hb = s.config.coord.heartbeat_s;
                self.zone.in_zone = true;
                self.emit(EventKind::ZoneEnter);
                self.go(UavState::EnterAndPlace, "granted", Some(zt + 2.0 * hb));
                self.mark(MessageKind::ZoneEnter);
            }
            _ => {}
        }
    }

    /// A follower whose zone time with its leader is over: the pair has left the zone; the
    /// brick counts as placed once the leader says so.
    pub(super) fn leave_with_leader(&mut self) {
        self.zone.in_zone = false;
        self.pair.left = true;
        self.emit(EventKind::ZoneLeave);
        self.go(UavState::WaitForZone, "pair_left", None);
        self.mark(MessageKind::ZoneRelease);
    }
}

#[cfg(test)]
mod tests {
    use super::super::testkit::{fly, Fixture};
    use super::*;
    use crate::coord::Coord;
    use crate::state::Event;

    #[test]
    fn no_pair_by_default() {
        let p = PairState::default();
        assert!(!p.left && p.leader.is_none() && p.follower.is_none());
        assert!(p.since.is_nan());
    }

    /// The UAVs that grasped each brick placed, by brick.
    fn carriers(events: &[Event]) -> Vec<(BrickId, Vec<u32>)> {
        let mut out: Vec<(BrickId, Vec<u32>)> = Vec::new();
        for e in events {
            if let EventKind::Grasp { brick } = e.kind {
                match out.iter_mut().find(|(b, _)| *b == brick) {
                    Some((_, who)) => who.push(e.uav),
                    None => out.push((brick, vec![e.uav])),
                }
            }
        }
        out
    }

    #[test]
    fn orange_bricks_are_carried_by_a_leader_and_a_follower() {
        let fixture = Fixture::new("mbzirc", 3);
        let mut agents = fixture.agents(Coord::Comm);
        let (events, sent) = fly(&mut agents, 5000.0, |_, _, _, _| true);
        fixture.check(&events);
        assert!(agents.iter().all(|a| a.finished()));
        let orange: Vec<_> = carriers(&events)
            .into_iter()
            .filter(|(b, _)| kind(&fixture.wall, *b).uavs_needed() == 2)
            .collect();
        assert!(!orange.is_empty());
        for (b, who) in &orange {
            assert_eq!(who.len(), 2, "brick {b:?}: {who:?}");
            assert_ne!(who[0], who[1]);
            // The first to grasp is the leader, which named the other in its status.
            let named = sent.iter().any(|(u, m)| {
                *u == who[0] as usize
                    && m.status.brick == Some(b.0)
                    && m.status.pair.is_some_and(|r| r.uav == who[1])
            });
            assert!(named, "brick {b:?}");
        }
    }

    #[test]
    fn a_follower_whose_leader_goes_silent_lets_the_brick_fall() {
        // Find who leads the first orange brick on a perfect bus, then fly again and silence
        // that leader as soon as its partner has grasped.
        let fixture = Fixture::new("mbzirc", 3);
        let mut agents = fixture.agents(Coord::Comm);
        let (events, _) = fly(&mut agents, 5000.0, |_, _, _, _| true);
        let (brick, who) = carriers(&events)
            .into_iter()
            .find(|(b, _)| kind(&fixture.wall, *b).uavs_needed() == 2)
            .expect("an orange brick");
        let grasped_at = events
            .iter()
            .find(|e| e.uav == who[1] && e.kind == EventKind::Grasp { brick })
            .expect("the follower's grasp")
            .t;
        let leader = who[0] as usize;
        let mut agents = fixture.agents(Coord::Comm);
        let (events, _) = fly(&mut agents, 5000.0, |from, _, _, t| {
            from != leader || t <= grasped_at
        });
        // The follower lets the brick fall (once the leader is declared out, the follower's
        // claim alone cannot carry it) and goes on with other bricks.
        let fell = events
            .iter()
            .find(|e| e.uav == who[1] && e.t > grasped_at && e.kind == EventKind::Lost { brick })
            .expect("the follower lets the brick fall")
            .t;
        assert!(events
            .iter()
            .any(|e| e.uav == who[1] && e.t >= fell && matches!(e.kind, EventKind::Place { .. })));
    }
}
