//! Entering the wall zone: at most one UAV (or one orange pair) inside at a time.
//!
//! Only the carrier of the brick next needed, with its supports heard placed, may enter, and
//! only when every teammate that still counts is heard outside the zone, has heard its claim,
//! and could not declare it out before it is out again ([`Agent::zone_clear`]). Then, with
//! `comm`, it asks: a [`Request`] with a lease of `lease_s`, renewed under a new number when
//! it runs out, that every teammate that counts must acknowledge in its own latest status
//! ([`Agent::acknowledged`]). A UAV acknowledges the request of a brick's first carrier when
//! it is outside the zone and its own request does not come first (rank in the order, then
//! UAV number), and it honours what it acknowledged — it keeps out — until the request is
//! released or its lease and the longest zone time have passed. With `windows` (or `auto`
//! without heartbeats) it enters only in its own slot. When everybody waits and nobody may
//! enter, the holder of the latest brick puts it down (the simulator's deadlock rule).

use super::wire::{Ack, Request, Status};
use super::{Agent, MessageKind, GROUND};
use crate::coord::Coord;
use crate::core::{heard_mode, kind, put_down, Board, Seen};
use crate::state::{CommMode, EventKind, UavState};
use crate::windows::Windows;
use mason_wall::BrickId;

/// Priority of a zone request: the brick's rank in the order, then the UAV number (lower
/// goes first).
pub(super) type Priority = (u32, u32);

/// A teammate's request this UAV acknowledged: it keeps out of the zone for it until it is
/// released or runs out.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Honored {
    /// The requester's incarnation.
    pub(super) incarnation: u64,
    /// The request's number.
    pub(super) id: u64,
    /// The end of the request's lease (s).
    pub(super) expires: f64,
    /// The request's priority.
    pub(super) priority: Priority,
}

impl Honored {
    /// Whether it still binds at `now`: a request may be used until its lease ends, and the
    /// zone time it started may last `longest` (s) more.
    pub(super) fn binds(&self, now: f64, longest: f64) -> bool {
        now <= self.expires + longest
    }
}

/// The wall zone as one UAV sees it.
#[derive(Clone, Debug)]
pub(super) struct ZoneState {
    /// Whether it is inside.
    pub(super) in_zone: bool,
    /// Its own request, if any.
    pub(super) request: Option<Request>,
    /// The number of its next request (from 1 in each incarnation).
    pub(super) next_request: u64,
    /// For each teammate, the request it acknowledged and honours.
    pub(super) honored: Vec<Option<Honored>>,
    /// Its coordination mode (`auto` switches it).
    pub(super) mode: CommMode,
    /// The longest zone time of any brick (s).
    pub(super) longest: f64,
}

impl ZoneState {
    /// Outside, no request, nothing honoured, in a team of `n`; `longest` is the longest zone
    /// time of any brick (s).
    pub(super) fn new(n: usize, longest: f64) -> Self {
        ZoneState {
            in_zone: false,
            request: None,
            next_request: 1,
            honored: vec![None; n],
            mode: CommMode::Comm,
            longest,
        }
    }

    /// Whether its request for `brick` must be made or renewed at `now`.
    pub(super) fn needs_request(&self, brick: BrickId, now: f64) -> bool {
        self.request
            .is_none_or(|r| r.brick != brick.0 || r.expires < now)
    }

    /// Makes a new request for `brick` of rank `rank` at `now`, with a lease of `lease_s`.
    pub(super) fn make_request(&mut self, brick: BrickId, rank: u32, now: f64, lease_s: f64) {
        self.request = Some(Request {
            id: self.next_request,
            brick: brick.0,
            rank,
            expires: now + lease_s,
        });
        self.next_request += 1;
    }

    /// Whether a request it honours comes before `priority`.
    pub(super) fn honours_before(&self, priority: Priority) -> bool {
        self.honored.iter().flatten().any(|h| h.priority < priority)
    }
}

impl Agent<'_> {
    /// `auto`: falls back to `windows` when a flying teammate is unheard for the heartbeat
    /// timeout, and back to `comm` when all are heard again.
    pub(super) fn update_mode(&mut self) {
        if self.setup.coord != Coord::Auto || GROUND.contains(&self.flight.state) {
            return;
        }
        let heard = self.members.last_heard(self.me, self.now);
        let timeout = self.setup.config.coord.heartbeat_timeout_s;
        let mode = heard_mode(self.now, self.me, &heard, |v| self.flying(v), timeout);
        if mode != self.zone.mode {
            self.zone.mode = mode;
            self.emit(EventKind::Comm { mode });
            self.mark(MessageKind::State);
        }
    }

    fn zone_mode(&self) -> CommMode {
        match self.setup.coord {
            Coord::Comm => CommMode::Comm,
            Coord::Windows => CommMode::Windows,
            Coord::Auto => self.zone.mode,
        }
    }

    /// The leader of the brick's carriers at the wall: enter when the rules allow.
    pub(super) fn zone(&mut self, b: BrickId) {
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
            debug_assert!(board.carriers(b).contains(&self.me));
            self.zone.in_zone = true;
            self.emit(EventKind::ZoneEnter);
            self.go(UavState::EnterAndPlace, "granted", Some(zone_time));
            self.mark(MessageKind::ZoneEnter);
        }
    }

    /// The checks of every mode: the zone heard free, no acknowledged request first, every
    /// flying teammate has heard its claim, and no teammate could declare it out before it
    /// is out of the zone again.
    pub(super) fn zone_clear(&mut self, zone_time: f64, prio: Priority) -> bool {
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
            if !self.is_out(v) && heard_me < self.work.claimed_at {
                return false;
            }
            if self.now + zone_time + 3.0 * hb >= heard_me + self.setup.dead_after_s {
                return false;
            }
        }
        self.refresh_honored();
        !self.zone.honours_before(prio)
    }

    /// With `comm`: its request, renewed when its lease runs out, acknowledged by every
    /// teammate that counts.
    pub(super) fn acknowledged(&mut self, b: BrickId, rank: u32) -> bool {
        if self.zone.needs_request(b, self.now) {
            let lease = self.setup.lease_s;
            self.zone.make_request(b, rank, self.now, lease);
            self.mark(MessageKind::ZoneRequest);
            return false;
        }
        let r = self.zone.request.expect("requested");
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
        if self.zone.request.take().is_some() {
            self.mark(MessageKind::ZoneRelease);
        }
    }

    /// Forgets acknowledged requests that were released or ran out.
    fn refresh_honored(&mut self) {
        for v in 0..self.n {
            let Some(h) = self.zone.honored[v] else {
                continue;
            };
            let released = self.members.peers[v].as_ref().is_some_and(|p| {
                p.incarnation > h.incarnation
                    || (!p.status.in_zone && p.status.request.is_none_or(|r| r.id != h.id))
            });
            if released || !h.binds(self.now, self.zone.longest) || self.is_out(v) {
                self.zone.honored[v] = None;
            }
        }
    }

    /// The acknowledgements this UAV gives now (and remembers, to keep out of the zone).
    pub(super) fn acks(&mut self) -> Vec<Ack> {
        let board = self.board();
        let mine = self.zone.request.map(|r| (r.rank, self.me as u32));
        let mut acks = Vec::new();
        for v in 0..self.n {
            if !self.flying(v) || self.zone.in_zone {
                continue;
            }
            let Some(p) = &self.members.peers[v] else {
                continue;
            };
            let Some(r) = p.status.request else {
                continue;
            };
            if r.expires < self.now
                || self
                    .work
                    .known_placed(r.brick as usize)
                    .is_none_or(|placed| placed)
            {
                continue;
            }
            let theirs = (r.rank, v as u32);
            let b = BrickId(r.brick);
            // Its partner in a pair always agrees; a claim it lost never gets an ack.
            let partner = self.work.brick == Some(b);
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
                self.zone.honored[v] = Some(Honored {
                    incarnation: p.incarnation,
                    id: r.id,
                    expires: r.expires,
                    priority: theirs,
                });
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
                        state: self.flight.state,
                        waiting_partner: false,
                        brick: self.work.brick,
                    };
                }
                let st = self.peer_status(v);
                Seen {
                    alive: board.alive(v),
                    state: st.map_or(UavState::Check, |s| s.state),
                    waiting_partner: st.is_some_and(waits_for_partner),
                    brick: st.and_then(|s| s.brick).map(BrickId),
                }
            })
            .collect();
        if put_down(board, self.n, |i| team[i]) == Some(self.me) {
            if let Some(b) = self.work.brick {
                if self.work.grasped {
                    self.emit(EventKind::Lost { brick: b });
                    self.work.grasped = false;
                }
                self.forget_brick();
                self.go(UavState::ChooseBrick, "put_down", None);
                self.choose("put_down");
            }
        }
    }

    /// When its `windows` slot next opens while it waits at the wall, if later than now.
    pub(super) fn windows_wake(&self) -> Option<f64> {
        if self.flight.state != UavState::WaitForZone || self.zone_mode() != CommMode::Windows {
            return None;
        }
        let b = self.work.brick?;
        let s = self.setup;
        let zt = self
            .board()
            .zone_time(s.wall, s.model, s.config.uav.zone_transit_s, b);
        let w = Windows { slot: s.slot_s };
        // A slot open now but not used (something else holds it back) is looked at again
        // on the next message or heartbeat.
        Some(w.next_entry(self.now, self.me, self.n, zt)).filter(|&t| t > self.now)
    }
}

/// Whether a teammate's status says it waits at the pile for an orange brick's partner: it
/// arrived first (`waiting_partner`), or its partner let go, restarted or is gone and it waits
/// for another (`partner_failed`, which leaves it in `Detect` with no timer). The deadlock rule
/// must count both, or a team whose pair lost a UAV waits forever: the survivor at the pile
/// for a partner, a teammate at the wall with a later brick for the zone.
fn waits_for_partner(st: &Status) -> bool {
    st.state == UavState::Detect
        && matches!(st.outcome.as_str(), "waiting_partner" | "partner_failed")
}

#[cfg(test)]
mod tests {
    use super::super::testkit::{fly, Fixture};
    use super::*;
    use crate::state::Event;

    #[test]
    fn a_request_is_numbered_and_renewed_when_its_lease_runs_out() {
        let mut z = ZoneState::new(3, 20.0);
        assert!(z.needs_request(BrickId(4), 0.0));
        z.make_request(BrickId(4), 2, 10.0, 5.0);
        assert_eq!(
            z.request,
            Some(Request {
                id: 1,
                brick: 4,
                rank: 2,
                expires: 15.0
            })
        );
        assert!(!z.needs_request(BrickId(4), 15.0));
        assert!(z.needs_request(BrickId(4), 15.1), "the lease ran out");
        assert!(z.needs_request(BrickId(5), 11.0), "another brick");
        z.make_request(BrickId(4), 2, 15.1, 5.0);
        assert_eq!(z.request.map(|r| r.id), Some(2));
    }

    #[test]
    fn an_honoured_request_binds_for_its_lease_and_the_longest_zone_time() {
        let h = Honored {
            incarnation: 1,
            id: 3,
            expires: 15.0,
            priority: (2, 1),
        };
        assert!(h.binds(30.0, 15.0));
        assert!(!h.binds(30.1, 15.0));
        let mut z = ZoneState::new(3, 15.0);
        z.honored[1] = Some(h);
        assert!(z.honours_before((3, 0)), "a later brick waits");
        assert!(
            z.honours_before((2, 2)),
            "the same brick rank: by UAV number"
        );
        assert!(!z.honours_before((2, 0)));
        assert!(!z.honours_before((1, 2)));
    }

    /// Each UAV's zone entries in time order.
    fn entries(events: &[Event], uav: u32) -> Vec<f64> {
        events
            .iter()
            .filter(|e| e.uav == uav && e.kind == EventKind::ZoneEnter)
            .map(|e| e.t)
            .collect()
    }

    #[test]
    fn with_comm_every_solo_entry_was_acknowledged_by_every_teammate() {
        let fixture = Fixture::new("thesis-2x5", 3);
        let mut agents = fixture.agents(Coord::Comm);
        let (events, sent) = fly(&mut agents, 5000.0, |_, _, _, _| true);
        fixture.check(&events);
        assert!(agents
            .iter()
            .all(|a| a.finished() && a.placed_known() == 10));
        for u in 0..3u32 {
            for t in entries(&events, u) {
                // The request it held when it entered.
                let request = sent
                    .iter()
                    .filter(|(v, m)| *v == u as usize && m.t <= t)
                    .filter_map(|(_, m)| m.status.request)
                    .next_back()
                    .expect("a request");
                for v in (0..3).filter(|&v| v != u as usize) {
                    let acked = sent.iter().any(|(w, m)| {
                        *w == v
                            && m.t <= t
                            && m.status
                                .acks
                                .iter()
                                .any(|a| a.uav == u && a.id == request.id)
                    });
                    assert!(acked, "UAV {u} entered at {t} without UAV {v}'s ack");
                }
            }
        }
    }

    #[test]
    fn with_windows_each_uav_enters_only_in_its_own_slot() {
        let fixture = Fixture::new("thesis-2x5", 3);
        let slot = fixture.setup(Coord::Windows, 0).slot_s;
        let mut agents = fixture.agents(Coord::Windows);
        let (events, sent) = fly(&mut agents, 5000.0, |_, _, _, _| true);
        fixture.check(&events);
        assert!(agents
            .iter()
            .all(|a| a.finished() && a.placed_known() == 10));
        for u in 0..3u32 {
            for t in entries(&events, u) {
                let slot_owner = (t / slot).floor() as u64 % 3;
                assert_eq!(slot_owner, u64::from(u), "UAV {u} entered at {t}");
            }
        }
        assert!(sent.iter().all(|(_, m)| m.status.request.is_none()));
    }
}
