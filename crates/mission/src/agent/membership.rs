//! Who is in the team, as one agent knows it: the last status heard from each teammate,
//! whom it holds out, liveness and the majority rule.
//!
//! A teammate unheard for `dead_after_s` is declared out, but only by an agent that hears a
//! strict majority of the team (itself included) within the heartbeat timeout, and that is
//! not itself held out. A declaration names the incarnation declared out: the same UAV under
//! a later incarnation is back in. An agent that hears it is held out rejoins under a new
//! incarnation. A teammate held out only by this agent may still be flying, cut off, so its
//! zone and acknowledgements still count until a fresh majority holds it out too.

use super::wire::{Message, Out, Status};
use super::{Agent, MessageKind, GROUND};
use crate::state::UavState;

/// The last message kept from a teammate.
#[derive(Clone, Debug)]
pub(super) struct Peer {
    pub(super) incarnation: u64,
    pub(super) seq: u64,
    /// The sender's time of its last message.
    pub(super) sent_t: f64,
    /// Local time when last heard.
    pub(super) heard_at: f64,
    pub(super) status: Status,
}

/// One UAV under one incarnation.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) struct Member {
    pub(super) uav: usize,
    pub(super) incarnation: u64,
}

/// What an agent knows of its teammates (its own entries stay empty).
#[derive(Clone, Debug)]
pub(super) struct Membership {
    /// The last message kept from each UAV.
    pub(super) peers: Vec<Option<Peer>>,
    /// For each UAV, the incarnation this agent holds out, if any.
    pub(super) out: Vec<Option<u64>>,
    /// When the agent started (s; `NaN` before its first tick): a teammate never heard counts
    /// as heard then.
    pub(super) started: f64,
}

impl Membership {
    /// A team of `n` nobody has heard yet.
    pub(super) fn new(n: usize) -> Self {
        Membership {
            peers: vec![None; n],
            out: vec![None; n],
            started: f64::NAN,
        }
    }

    /// Whether a message of `u` numbered (`incarnation`, `seq`) is newer than the last kept.
    pub(super) fn is_newer(&self, u: usize, incarnation: u64, seq: u64) -> bool {
        self.peers[u]
            .as_ref()
            .is_none_or(|p| (incarnation, seq) > (p.incarnation, p.seq))
    }

    /// Keeps `m`, heard at `now`, as its sender's latest.
    pub(super) fn keep(&mut self, now: f64, m: Message) {
        self.peers[m.uav as usize] = Some(Peer {
            incarnation: m.incarnation,
            seq: m.seq,
            heard_at: now,
            sent_t: m.t,
            status: m.status,
        });
    }

    /// `u` heard under `incarnation`: back in if it was held out under an earlier one.
    pub(super) fn back_in(&mut self, u: usize, incarnation: u64) {
        if self.out[u].is_some_and(|i| incarnation > i) {
            self.out[u] = None;
        }
    }

    /// The last status heard from `v`.
    pub(super) fn status(&self, v: usize) -> Option<&Status> {
        self.peers[v].as_ref().map(|p| &p.status)
    }

    /// The incarnation of `v` last heard (0: never heard).
    pub(super) fn incarnation_of(&self, v: usize) -> u64 {
        self.peers[v].as_ref().map_or(0, |p| p.incarnation)
    }

    /// Whether `v` is held out: the incarnation declared out is the last heard, or later.
    pub(super) fn is_out(&self, v: usize) -> bool {
        match (self.out[v], &self.peers[v]) {
            (Some(i), Some(p)) => p.incarnation <= i,
            (Some(_), None) => true,
            (None, _) => false,
        }
    }

    /// Whether teammate `v` of `me` should still be heard: not out, not on the ground for
    /// good.
    pub(super) fn flying(&self, me: usize, v: usize) -> bool {
        v != me
            && !self.is_out(v)
            && self
                .status(v)
                .is_none_or(|s| !matches!(s.state, UavState::Landed | UavState::Down))
    }

    /// Whether `v` was heard at most `timeout` (s) before `now`.
    fn heard_within(&self, v: usize, now: f64, timeout: f64) -> bool {
        self.peers[v]
            .as_ref()
            .is_some_and(|p| now - p.heard_at <= timeout)
    }

    /// When `me` last heard each UAV (itself: `now`; never heard: when it started).
    pub(super) fn last_heard(&self, me: usize, now: f64) -> Vec<f64> {
        (0..self.peers.len())
            .map(|v| match &self.peers[v] {
                _ if v == me => now,
                Some(p) => p.heard_at,
                None => self.started,
            })
            .collect()
    }

    /// The status's `heard`: the send time of the last message heard from each UAV, by the
    /// sender's clock (itself: `now`; never heard: -1).
    pub(super) fn heard(&self, me: usize, now: f64) -> Vec<f64> {
        (0..self.peers.len())
            .map(|v| {
                if v == me {
                    now
                } else {
                    self.peers[v].as_ref().map_or(-1.0, |p| p.sent_t)
                }
            })
            .collect()
    }

    /// The status's `out`: every UAV it holds out, with the incarnation.
    pub(super) fn outs(&self) -> Vec<Out> {
        (0..self.out.len())
            .filter_map(|v| {
                self.out[v].map(|i| Out {
                    uav: v as u32,
                    incarnation: i,
                })
            })
            .collect()
    }

    /// Whether `me` has heard every teammate at least once.
    pub(super) fn heard_all(&self, me: usize) -> bool {
        (0..self.peers.len()).all(|v| v == me || self.peers[v].is_some())
    }

    /// Whether `me` hears a strict majority of the team (itself included): teammates not
    /// out, heard within `timeout` (s) of `now`.
    pub(super) fn majority(&self, me: usize, now: f64, timeout: f64) -> bool {
        let heard = (0..self.peers.len())
            .filter(|&v| v != me && !self.is_out(v) && self.heard_within(v, now, timeout))
            .count();
        2 * (heard + 1) > self.peers.len()
    }

    /// Whether a strict majority of the team, heard lately, holds `v` out (`me` counted among
    /// them): `v` then cannot form a majority of its own without hearing that it is out.
    pub(super) fn out_confirmed(&self, me: usize, v: usize, now: f64, timeout: f64) -> bool {
        let inc = self.out[v].unwrap_or(0);
        let holders = (0..self.peers.len())
            .filter(|&w| w != v && w != me)
            .filter(|&w| {
                self.heard_within(w, now, timeout)
                    && self.status(w).is_some_and(|s| {
                        s.out
                            .iter()
                            .any(|o| o.uav as usize == v && o.incarnation >= inc)
                    })
            })
            .count();
        2 * (holders + 1) > self.peers.len()
    }

    /// Whether a teammate holds `me`, incarnation `incarnation` (or a later one), out.
    pub(super) fn holds_out(&self, me: usize, incarnation: u64) -> bool {
        let me = me as u32;
        (0..self.peers.len()).any(|v| {
            self.status(v).is_some_and(|s| {
                s.out
                    .iter()
                    .any(|o| o.uav == me && o.incarnation >= incarnation)
            })
        })
    }
}

impl Agent<'_> {
    pub(super) fn peer_status(&self, v: usize) -> Option<&Status> {
        self.members.status(v)
    }

    pub(super) fn is_out(&self, v: usize) -> bool {
        self.members.is_out(v)
    }

    /// Whether teammate `v` should still be heard: not out, not on the ground for good.
    pub(super) fn flying(&self, v: usize) -> bool {
        self.members.flying(self.me, v)
    }

    /// Takes the declarations of a teammate's status: it holds out whom they hold out,
    /// unless it has heard them since under a later incarnation.
    pub(super) fn hear_outs(&mut self, outs: &[Out]) {
        for o in outs {
            let v = o.uav as usize;
            if v == self.me {
                continue; // handled in tick
            }
            if v < self.n
                && self.members.out[v].is_none_or(|i| i < o.incarnation)
                && self.members.incarnation_of(v) <= o.incarnation
            {
                self.members.out[v] = Some(o.incarnation);
                self.mark_unknown(v, o.incarnation);
            }
        }
    }

    fn majority(&self) -> bool {
        let timeout = self.setup.config.coord.heartbeat_timeout_s;
        self.members.majority(self.me, self.now, timeout)
    }

    /// Declares out the teammates unheard for `dead_after_s`, when it hears a majority.
    pub(super) fn liveness(&mut self) {
        if !self.majority() || self.held_out() {
            return;
        }
        for v in 0..self.n {
            if !self.flying(v) {
                continue;
            }
            let last = self.members.peers[v]
                .as_ref()
                .map_or(self.members.started, |p| p.heard_at);
            if self.now - last > self.setup.dead_after_s {
                let inc = self.members.incarnation_of(v);
                self.members.out[v] = Some(inc);
                self.zone.honored[v] = None;
                self.mark_unknown(v, inc);
                self.mark(MessageKind::State);
            }
        }
    }

    /// A teammate holds it out: it puts its brick down and rejoins as a new incarnation.
    pub(super) fn held_out(&self) -> bool {
        self.members.holds_out(self.me, self.incarnation)
    }

    /// Held out while flying: rejoins under a new incarnation, without its brick.
    pub(super) fn expelled(&mut self) {
        if !self.held_out() || GROUND.contains(&self.flight.state) {
            return;
        }
        self.incarnation += 1;
        self.outbox.seq = 0;
        self.zone.next_request = 1;
        self.drop_brick("declared_out");
        self.choose("rejoined");
    }

    /// Whether teammate `v` may still be in the game: not on the ground for good, and not
    /// held out by a fresh majority. A teammate only this UAV holds out may still be flying,
    /// cut off, and could come back and hold this UAV out: its lease, its zone and its
    /// acknowledgement still count.
    pub(super) fn counts(&self, v: usize) -> bool {
        let timeout = self.setup.config.coord.heartbeat_timeout_s;
        v != self.me
            && self
                .peer_status(v)
                .is_none_or(|s| !matches!(s.state, UavState::Landed | UavState::Down))
            && !(self.is_out(v) && self.members.out_confirmed(self.me, v, self.now, timeout))
    }
}

#[cfg(test)]
mod tests {
    use super::super::testkit::{fly, Fixture};
    use super::*;
    use crate::coord::Coord;
    use crate::state::CommMode;

    fn status(state: UavState, out: Vec<Out>) -> Status {
        Status {
            state,
            outcome: "ok".into(),
            x: 0.0,
            y: 0.0,
            z: 0.0,
            mode: CommMode::Comm,
            brick: None,
            claimed_at: 0.0,
            grasped: false,
            pair: None,
            in_zone: false,
            request: None,
            acks: Vec::new(),
            placed: Vec::new(),
            heard: Vec::new(),
            out,
        }
    }

    fn message(uav: u32, incarnation: u64, seq: u64, t: f64, status: Status) -> Message {
        Message {
            v: super::super::SCHEMA_VERSION,
            mission: "m".into(),
            uav,
            incarnation,
            seq,
            t,
            kind: MessageKind::Heartbeat,
            status,
        }
    }

    fn hear(m: &mut Membership, now: f64, uav: u32, incarnation: u64, state: UavState) {
        let seq = m.peers[uav as usize].as_ref().map_or(1, |p| p.seq + 1);
        m.keep(
            now,
            message(uav, incarnation, seq, now - 0.1, status(state, Vec::new())),
        );
    }

    #[test]
    fn only_newer_messages_are_kept() {
        let mut m = Membership::new(3);
        assert!(m.is_newer(1, 1, 1));
        m.keep(1.0, message(1, 2, 5, 0.9, status(UavState::Check, vec![])));
        assert!(!m.is_newer(1, 2, 5));
        assert!(!m.is_newer(1, 2, 4));
        assert!(!m.is_newer(1, 1, 99));
        assert!(m.is_newer(1, 2, 6));
        assert!(m.is_newer(1, 3, 1));
    }

    #[test]
    fn a_later_incarnation_is_back_in() {
        let mut m = Membership::new(3);
        m.out[1] = Some(1);
        assert!(m.is_out(1), "held out, never heard");
        hear(&mut m, 1.0, 1, 1, UavState::FlyToPile);
        assert!(m.is_out(1));
        assert!(!m.flying(0, 1));
        hear(&mut m, 2.0, 1, 2, UavState::FlyToPile);
        assert!(!m.is_out(1), "heard under incarnation 2");
        m.back_in(1, 2);
        assert_eq!(m.out[1], None);
        assert!(m.flying(0, 1));
    }

    #[test]
    fn landed_teammates_and_itself_are_not_flying() {
        let mut m = Membership::new(3);
        assert!(m.flying(0, 1), "never heard: still expected");
        assert!(!m.flying(0, 0));
        hear(&mut m, 1.0, 2, 1, UavState::Landed);
        assert!(!m.flying(0, 2));
        hear(&mut m, 1.0, 1, 1, UavState::Down);
        assert!(!m.flying(0, 1));
    }

    #[test]
    fn a_majority_is_strict_and_counts_itself() {
        let mut m = Membership::new(3);
        assert!(!m.majority(0, 0.0, 3.0), "1 of 3");
        hear(&mut m, 10.0, 1, 1, UavState::Detect);
        assert!(m.majority(0, 12.0, 3.0), "2 of 3");
        assert!(!m.majority(0, 13.5, 3.0), "heard too long ago");
        m.out[1] = Some(1);
        assert!(!m.majority(0, 12.0, 3.0), "an out teammate does not count");
        let mut four = Membership::new(4);
        hear(&mut four, 10.0, 1, 1, UavState::Detect);
        assert!(!four.majority(0, 10.0, 3.0), "2 of 4 is no majority");
        hear(&mut four, 10.0, 2, 1, UavState::Detect);
        assert!(four.majority(0, 10.0, 3.0), "3 of 4");
    }

    #[test]
    fn a_declaration_is_confirmed_by_a_fresh_majority() {
        let mut m = Membership::new(3);
        m.out[2] = Some(1);
        assert!(!m.out_confirmed(0, 2, 5.0, 3.0), "only itself");
        let out = vec![Out {
            uav: 2,
            incarnation: 1,
        }];
        m.keep(5.0, message(1, 1, 1, 5.0, status(UavState::Detect, out)));
        assert!(m.out_confirmed(0, 2, 6.0, 3.0));
        assert!(
            !m.out_confirmed(0, 2, 9.0, 3.0),
            "the holder is no longer fresh"
        );
    }

    #[test]
    fn it_knows_when_a_teammate_holds_it_out() {
        let mut m = Membership::new(3);
        let out = vec![Out {
            uav: 0,
            incarnation: 2,
        }];
        m.keep(1.0, message(1, 1, 1, 1.0, status(UavState::Detect, out)));
        assert!(m.holds_out(0, 1));
        assert!(m.holds_out(0, 2));
        assert!(!m.holds_out(0, 3), "rejoined under incarnation 3");
        assert!(!m.holds_out(2, 1));
    }

    #[test]
    fn the_status_reports_send_times_and_declarations() {
        let mut m = Membership::new(3);
        m.started = 0.5;
        hear(&mut m, 4.0, 2, 1, UavState::Detect);
        m.out[1] = Some(3);
        assert_eq!(m.heard(0, 7.0), vec![7.0, -1.0, 3.9]);
        assert_eq!(m.last_heard(0, 7.0), vec![7.0, 0.5, 4.0]);
        assert_eq!(
            m.outs(),
            vec![Out {
                uav: 1,
                incarnation: 3
            }]
        );
        assert!(!m.heard_all(0));
        hear(&mut m, 5.0, 1, 4, UavState::Detect);
        assert!(m.heard_all(0));
    }

    #[test]
    fn a_teammate_cut_off_is_declared_out_and_rejoins_as_a_new_incarnation() {
        let fixture = Fixture::new("levels5-width5", 3);
        let mut agents = fixture.agents(Coord::Comm);
        let cut = |t: f64| (100.0..160.0).contains(&t);
        let (events, sent) = fly(&mut agents, 5000.0, |from, to, _, t| {
            !(cut(t) && (from == 2 || to == 2))
        });
        fixture.check(&events);
        assert!(agents
            .iter()
            .all(|a| a.finished() && a.placed_known() == 25));
        let declared = |u: usize| {
            sent.iter().any(|(v, m)| {
                *v == u
                    && m.status.out
                        == vec![Out {
                            uav: 2,
                            incarnation: 1,
                        }]
            })
        };
        assert!(declared(0) && declared(1));
        // UAV 2, alone, hears no majority and declares nobody out.
        assert!(sent
            .iter()
            .all(|(v, m)| *v != 2 || m.incarnation > 1 || m.status.out.is_empty()));
        let back = sent
            .iter()
            .find(|(v, m)| *v == 2 && m.incarnation == 2)
            .expect("back as incarnation 2");
        assert!(back.1.t >= 160.0 && back.1.seq == 1, "{:?}", back.1);
        assert_eq!(agents[2].incarnation(), 2);
    }
}
