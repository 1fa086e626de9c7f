//! `mission::check_trace`: checks a mission's events knowing nothing of the policies.
//!
//! * the wall zone holds at most one UAV, or two carrying the same orange brick;
//! * a brick is placed once, by a UAV in the zone holding it, after all its supports;
//! * every grasped brick is placed or reported lost, unless its UAV is still flying when the
//!   trace ends (a time limit).

use crate::state::{Event, EventKind, Observer, UavState};
use mason_wall::violations::Violations;
use mason_wall::{BrickId, Wall};
use std::ops::ControlFlow;
use thiserror::Error;

/// A broken rule, with the time it was broken. Bricks are named by their labels.
#[derive(Clone, Debug, PartialEq, Error)]
pub enum TraceError {
    /// The mission was stopped at its event cap: not a broken safety rule, but no trace to
    /// judge either.
    #[error("{0}")]
    Flooded(#[from] crate::state::Flood),
    /// Events out of time order.
    #[error("t = {t}: events go back in time")]
    OutOfOrder {
        /// Time.
        t: f64,
    },
    /// Two UAVs in the zone that are not one orange pair.
    #[error("t = {t}: UAVs {a} and {b} are in the wall zone together")]
    ZoneShared {
        /// Time.
        t: f64,
        /// One UAV.
        a: u32,
        /// The other.
        b: u32,
    },
    /// A zone event that does not match the UAV's whereabouts.
    #[error("t = {t}: UAV {uav} {what}")]
    Zone {
        /// Time.
        t: f64,
        /// UAV.
        uav: u32,
        /// What is wrong.
        what: &'static str,
    },
    /// A placement before a support.
    #[error("t = {t}: brick {brick} placed before its support {support}")]
    Precedence {
        /// Time.
        t: f64,
        /// The brick (its label).
        brick: u32,
        /// The missing support (its label).
        support: u32,
    },
    /// A brick placed twice, or not held, or outside the zone.
    #[error("t = {t}: UAV {uav} places brick {brick}: {what}")]
    Placement {
        /// Time.
        t: f64,
        /// UAV.
        uav: u32,
        /// Brick.
        brick: u32,
        /// What is wrong.
        what: &'static str,
    },
    /// An event of a UAV outside the team, or naming a brick outside the wall.
    #[error("t = {t}: {what}")]
    Unknown {
        /// Time.
        t: f64,
        /// What it names.
        what: String,
    },
    /// A grasp while holding, or a brick left unaccounted.
    #[error("UAV {uav}: brick {brick} {what}")]
    Unaccounted {
        /// UAV.
        uav: u32,
        /// Brick.
        brick: u32,
        /// What is wrong.
        what: &'static str,
    },
}

/// What a valid trace shows.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct TraceSummary {
    /// Bricks placed.
    pub placed: usize,
    /// Bricks lost.
    pub lost: usize,
    /// Bricks still held by flying UAVs at the end.
    pub in_flight: usize,
}

/// Checks events as they arrive; [`TraceChecker::finish`] gives the verdict.
#[derive(Clone, Debug)]
pub struct TraceChecker<'w> {
    wall: &'w Wall,
    placed: Vec<bool>,
    holding: Vec<Option<BrickId>>,
    in_zone: Vec<bool>,
    last_state: Vec<UavState>,
    last_t: f64,
    summary: TraceSummary,
    found: Violations<TraceError>,
    stopped: bool,
}

impl<'w> TraceChecker<'w> {
    /// A checker for a team of `uavs` building `wall` that stops at the first broken rule.
    pub fn new(wall: &'w Wall, uavs: usize) -> Self {
        Self::with(wall, uavs, Violations::first())
    }

    /// A checker that goes on after a broken rule and lists every one
    /// ([`TraceChecker::violations`]). After a violation it keeps the facts the event states:
    /// a brick placed against a rule is on the wall, a UAV that entered against a rule is in
    /// the zone.
    pub fn every(wall: &'w Wall, uavs: usize) -> Self {
        Self::with(wall, uavs, Violations::every())
    }

    fn with(wall: &'w Wall, uavs: usize, found: Violations<TraceError>) -> Self {
        TraceChecker {
            wall,
            placed: vec![false; wall.len()],
            holding: vec![None; uavs],
            in_zone: vec![false; uavs],
            last_state: vec![UavState::Check; uavs],
            last_t: 0.0,
            summary: TraceSummary::default(),
            found,
            stopped: false,
        }
    }

    fn check(&mut self, e: &Event) -> ControlFlow<()> {
        let t = e.t;
        let u = e.uav as usize;
        if t < self.last_t {
            self.found.report(TraceError::OutOfOrder { t })?;
        }
        self.last_t = self.last_t.max(t);
        if u >= self.holding.len() {
            return self.found.report(TraceError::Unknown {
                t,
                what: format!("UAV {u} is not in the team of {}", self.holding.len()),
            });
        }
        let brick = match e.kind {
            EventKind::Grasp { brick } | EventKind::Place { brick } | EventKind::Lost { brick } => {
                Some(brick)
            }
            _ => None,
        };
        if let Some(b) = brick.filter(|b| b.index() >= self.wall.len()) {
            return self.found.report(TraceError::Unknown {
                t,
                what: format!(
                    "brick index {} is not in the wall of {} bricks",
                    b.0,
                    self.wall.len()
                ),
            });
        }
        match e.kind {
            EventKind::State { state, .. } => self.last_state[u] = state,
            EventKind::Grasp { brick } => {
                if self.holding[u].is_some() {
                    self.found.report(TraceError::Unaccounted {
                        uav: e.uav,
                        brick: self.wall.brick(brick).label,
                        what: "grasped while holding another",
                    })?;
                }
                self.holding[u] = Some(brick);
            }
            EventKind::ZoneEnter => self.enter(t, u)?,
            EventKind::ZoneLeave => {
                if !self.in_zone[u] {
                    self.found.report(TraceError::Zone {
                        t,
                        uav: e.uav,
                        what: "leaves a zone it is not in",
                    })?;
                }
                self.in_zone[u] = false;
            }
            EventKind::Place { brick } => self.place(t, u, brick)?,
            EventKind::Lost { brick } => {
                self.summary.lost += 1;
                // The UAV lets go of it; an orange brick falls for both of its pair.
                let pair = self.wall.brick(brick).kind.uavs_needed() == 2;
                for (w, h) in self.holding.iter_mut().enumerate() {
                    if *h == Some(brick) && (w == u || pair) {
                        *h = None;
                    }
                }
            }
            EventKind::Fail | EventKind::Comm { .. } | EventKind::Replan { .. } => {}
        }
        ControlFlow::Continue(())
    }

    fn enter(&mut self, t: f64, u: usize) -> ControlFlow<()> {
        let uav = u as u32;
        if self.in_zone[u] {
            return self.found.report(TraceError::Zone {
                t,
                uav,
                what: "enters the zone twice",
            });
        }
        self.in_zone[u] = true;
        let Some(b) = self.holding[u] else {
            return self.found.report(TraceError::Zone {
                t,
                uav,
                what: "enters the zone without a brick",
            });
        };
        let inside: Vec<usize> = (0..self.in_zone.len())
            .filter(|&i| self.in_zone[i])
            .collect();
        // Alone, the UAV shares the zone with nobody; two carrying one orange brick are a pair.
        let pair = inside.len() == 2
            && self.wall.brick(b).kind.uavs_needed() == 2
            && inside.iter().all(|&i| self.holding[i] == Some(b));
        if !pair {
            for &other in inside.iter().filter(|&&i| i != u) {
                self.found.report(TraceError::ZoneShared {
                    t,
                    a: other as u32,
                    b: uav,
                })?;
            }
        }
        ControlFlow::Continue(())
    }

    fn place(&mut self, t: f64, u: usize, brick: BrickId) -> ControlFlow<()> {
        let label = self.wall.brick(brick).label;
        let err = |what| TraceError::Placement {
            t,
            uav: u as u32,
            brick: label,
            what,
        };
        if self.placed[brick.index()] {
            return self.found.report(err("placed twice"));
        }
        if self.holding[u] != Some(brick) {
            self.found.report(err("the UAV does not hold it"))?;
        }
        if !self.in_zone[u] {
            self.found.report(err("the UAV is not in the zone"))?;
        }
        let wall = self.wall;
        for s in wall.supports(brick) {
            if self.placed[s.index()] {
                continue;
            }
            self.found.report(TraceError::Precedence {
                t,
                brick: label,
                support: wall.brick(*s).label,
            })?;
        }
        self.placed[brick.index()] = true;
        self.summary.placed += 1;
        for h in &mut self.holding {
            if *h == Some(brick) {
                *h = None;
            }
        }
        ControlFlow::Continue(())
    }

    /// The verdict: the summary, or the first broken rule.
    pub fn finish(self) -> Result<TraceSummary, TraceError> {
        let (summary, found) = self.close();
        found.into_result(summary)
    }

    /// Every broken rule, in the order found, those of the end (a brick neither placed nor
    /// lost) last; empty when the trace is valid. Meant for [`TraceChecker::every`].
    pub fn violations(self) -> Vec<TraceError> {
        self.close().1.into_vec()
    }

    fn close(mut self) -> (TraceSummary, Violations<TraceError>) {
        if !self.stopped {
            for (u, h) in self.holding.iter().enumerate() {
                if let Some(b) = h {
                    if matches!(self.last_state[u], UavState::Landed | UavState::Down) {
                        let e = TraceError::Unaccounted {
                            uav: u as u32,
                            brick: self.wall.brick(*b).label,
                            what: "is neither placed nor lost",
                        };
                        if self.found.report(e).is_break() {
                            break;
                        }
                    } else {
                        self.summary.in_flight += 1;
                    }
                }
            }
        }
        (self.summary, self.found)
    }
}

impl Observer for TraceChecker<'_> {
    fn event(&mut self, e: &Event) {
        if !self.stopped && self.check(e).is_break() {
            self.stopped = true;
        }
    }
}

/// Checks a whole trace of a team of `uavs` building `wall`: the first broken rule, or what
/// the trace shows ([`trace_violations`] lists every broken rule).
pub fn check_trace(wall: &Wall, uavs: usize, events: &[Event]) -> Result<TraceSummary, TraceError> {
    let mut c = TraceChecker::new(wall, uavs);
    for e in events {
        c.event(e);
    }
    c.finish()
}

/// Every rule of [`check_trace`] that `events` break, in order.
pub fn trace_violations(wall: &Wall, uavs: usize, events: &[Event]) -> Vec<TraceError> {
    let mut c = TraceChecker::every(wall, uavs);
    for e in events {
        c.event(e);
    }
    c.violations()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::state::{Event, EventKind};
    use mason_wall::BrickId;

    fn at(t: f64, uav: u32, kind: EventKind) -> Event {
        Event { t, uav, kind }
    }

    use crate::state::UavState;

    /// The rule a violation breaks, and what it says (`Zone` alone says little).
    fn rules(found: &[TraceError]) -> Vec<String> {
        found
            .iter()
            .map(|e| {
                let name = mason_wall::violations::rule(e);
                match e {
                    TraceError::Zone { what, .. }
                    | TraceError::Placement { what, .. }
                    | TraceError::Unaccounted { what, .. } => format!("{name}: {what}"),
                    _ => name,
                }
            })
            .collect()
    }

    fn landed(t: f64, uav: u32) -> Event {
        at(
            t,
            uav,
            EventKind::State {
                state: UavState::Landed,
                outcome: "landed",
                x: 0.0,
                y: 0.0,
            },
        )
    }

    /// Bricks of the thesis 2×5 wall: `b0` supports the level-2 brick `top` and `other` is the
    /// one more support `top` needs; `b1` and `b3` are further level-1 bricks.
    struct Bricks {
        b0: BrickId,
        b1: BrickId,
        b3: BrickId,
        top: BrickId,
        other: BrickId,
    }

    fn bricks(wall: &Wall) -> Bricks {
        let top = wall
            .ids()
            .find(|&b| wall.brick(b).level == 2 && wall.supports(b).len() == 2)
            .expect("a level-2 brick on two supports");
        let (b0, other) = (wall.supports(top)[0], wall.supports(top)[1]);
        let mut rest = wall
            .ids()
            .filter(|&b| wall.brick(b).level == 1 && b != b0 && b != other);
        Bricks {
            b0,
            b1: rest.next().unwrap(),
            b3: rest.next().unwrap(),
            top,
            other,
        }
    }

    /// A valid trace of two UAVs: UAV 0 places `b0` (in the zone 2–4 s), UAV 1 places `b1`
    /// (5–7 s), both land at 10 s. `extra` events are merged in by time (stable: an extra
    /// event at the time of a base event comes after it).
    fn trace(b: &Bricks, extra: &[Event], drop: &[usize]) -> Vec<Event> {
        let base = [
            at(1.0, 0, EventKind::Grasp { brick: b.b0 }),
            at(1.0, 1, EventKind::Grasp { brick: b.b1 }),
            at(2.0, 0, EventKind::ZoneEnter),
            at(3.0, 0, EventKind::Place { brick: b.b0 }),
            at(4.0, 0, EventKind::ZoneLeave),
            at(5.0, 1, EventKind::ZoneEnter),
            at(6.0, 1, EventKind::Place { brick: b.b1 }),
            at(7.0, 1, EventKind::ZoneLeave),
            landed(10.0, 0),
            landed(10.0, 1),
        ];
        let mut out: Vec<Event> = base
            .iter()
            .enumerate()
            .filter(|(i, _)| !drop.contains(i))
            .map(|(_, e)| *e)
            .collect();
        out.extend_from_slice(extra);
        out.sort_by(|a, b| a.t.total_cmp(&b.t));
        out
    }

    /// Checks `events` both ways: the first broken rule and every one.
    fn broken(wall: &Wall, events: &[Event]) -> Vec<String> {
        let every = trace_violations(wall, 2, events);
        let first = check_trace(wall, 2, events);
        assert_eq!(first.err().as_ref(), every.first(), "first and all agree");
        rules(&every)
    }

    #[test]
    fn the_base_trace_is_valid() {
        let wall = mason_wall::builtin("thesis-2x5").unwrap().wall();
        let b = bricks(&wall);
        let s = check_trace(&wall, 2, &trace(&b, &[], &[])).unwrap();
        assert_eq!((s.placed, s.lost, s.in_flight), (2, 0, 0));
        assert!(trace_violations(&wall, 2, &trace(&b, &[], &[])).is_empty());
        // A UAV still flying at the end may hold its brick (a time limit).
        let flying = trace(&b, &[at(8.0, 1, EventKind::Grasp { brick: b.b3 })], &[9]);
        assert_eq!(check_trace(&wall, 2, &flying).unwrap().in_flight, 1);
    }

    #[test]
    fn one_broken_trace_per_rule_reports_exactly_that_rule() {
        let wall = mason_wall::builtin("thesis-2x5").unwrap().wall();
        let b = bricks(&wall);
        let comm = EventKind::Comm {
            mode: crate::state::CommMode::Windows,
        };
        let cases: Vec<(&str, Vec<Event>, &str)> = vec![
            (
                "an event earlier than the one before",
                {
                    let mut t = trace(&b, &[], &[]);
                    t.insert(5, at(0.5, 1, comm));
                    t
                },
                "OutOfOrder",
            ),
            (
                "UAV 1 enters at 3.5 s while UAV 0 is inside",
                trace(&b, &[at(3.5, 1, EventKind::ZoneEnter)], &[5]),
                "ZoneShared",
            ),
            (
                "UAV 0 enters twice",
                trace(&b, &[at(2.5, 0, EventKind::ZoneEnter)], &[]),
                "Zone: enters the zone twice",
            ),
            (
                "UAV 1 enters without a brick after placing",
                trace(
                    &b,
                    &[
                        at(8.0, 1, EventKind::ZoneEnter),
                        at(9.0, 1, EventKind::ZoneLeave),
                    ],
                    &[],
                ),
                "Zone: enters the zone without a brick",
            ),
            (
                "UAV 1 leaves again",
                trace(&b, &[at(8.0, 1, EventKind::ZoneLeave)], &[]),
                "Zone: leaves a zone it is not in",
            ),
            (
                "UAV 1 places the level-2 brick with one of its supports missing",
                {
                    let mut t = trace(&b, &[], &[]);
                    for e in &mut t {
                        match &mut e.kind {
                            EventKind::Grasp { brick } | EventKind::Place { brick }
                                if *brick == b.b1 =>
                            {
                                *brick = b.top
                            }
                            _ => {}
                        }
                    }
                    t
                },
                "Precedence",
            ),
            (
                "UAV 1 grasps b0 once it is placed, places it again, lets go of it",
                trace(
                    &b,
                    &[
                        at(4.5, 1, EventKind::Grasp { brick: b.b0 }),
                        at(6.0, 1, EventKind::Place { brick: b.b0 }),
                        at(6.5, 1, EventKind::Lost { brick: b.b0 }),
                    ],
                    &[1, 6],
                ),
                "Placement: placed twice",
            ),
            (
                "UAV 1 places b3, which it does not hold, then lets go of b1",
                trace(
                    &b,
                    &[
                        at(6.0, 1, EventKind::Place { brick: b.b3 }),
                        at(6.5, 1, EventKind::Lost { brick: b.b1 }),
                    ],
                    &[6],
                ),
                "Placement: the UAV does not hold it",
            ),
            (
                "UAV 1 places after leaving the zone",
                trace(&b, &[at(7.5, 1, EventKind::Place { brick: b.b1 })], &[6]),
                "Placement: the UAV is not in the zone",
            ),
            (
                "UAV 1 grasps b1 while holding b3",
                trace(&b, &[at(0.5, 1, EventKind::Grasp { brick: b.b3 })], &[]),
                "Unaccounted: grasped while holding another",
            ),
            (
                "UAV 1 lands holding b3",
                trace(&b, &[at(8.0, 1, EventKind::Grasp { brick: b.b3 })], &[]),
                "Unaccounted: is neither placed nor lost",
            ),
            (
                "a third UAV in a team of two",
                trace(&b, &[at(8.0, 2, comm)], &[]),
                "Unknown",
            ),
            (
                "the brick just past the wall's last",
                trace(
                    &b,
                    &[at(
                        8.0,
                        1,
                        EventKind::Lost {
                            brick: BrickId(wall.len() as u32),
                        },
                    )],
                    &[],
                ),
                "Unknown",
            ),
            (
                "a brick outside the wall",
                trace(
                    &b,
                    &[at(8.0, 1, EventKind::Grasp { brick: BrickId(99) })],
                    &[],
                ),
                "Unknown",
            ),
        ];
        for (what, events, rule) in cases {
            assert_eq!(broken(&wall, &events), [rule], "{what}");
        }
        // The support the level-2 brick misses is named, by label.
        let other = wall.brick(b.other).label;
        let mut t = trace(&b, &[], &[]);
        for e in &mut t {
            if let EventKind::Grasp { brick } | EventKind::Place { brick } = &mut e.kind {
                if *brick == b.b1 {
                    *brick = b.top;
                }
            }
        }
        assert!(matches!(
            check_trace(&wall, 2, &t),
            Err(TraceError::Precedence { support, t, .. }) if support == other && t == 6.0
        ));
    }

    #[test]
    fn lost_bricks_are_counted_and_a_downed_uav_must_account_for_its_brick() {
        let wall = mason_wall::builtin("thesis-2x5").unwrap().wall();
        let b = bricks(&wall);
        let lost = trace(
            &b,
            &[
                at(8.0, 1, EventKind::Grasp { brick: b.b3 }),
                at(9.0, 1, EventKind::Lost { brick: b.b3 }),
            ],
            &[],
        );
        let s = check_trace(&wall, 2, &lost).unwrap();
        assert_eq!((s.placed, s.lost, s.in_flight), (2, 1, 0));
        let down = |t| {
            at(
                t,
                1,
                EventKind::State {
                    state: UavState::Down,
                    outcome: "down",
                    x: 0.0,
                    y: 0.0,
                },
            )
        };
        let held = trace(
            &b,
            &[at(8.0, 1, EventKind::Grasp { brick: b.b3 }), down(10.5)],
            &[9],
        );
        assert_eq!(
            check_trace(&wall, 2, &held),
            Err(TraceError::Unaccounted {
                uav: 1,
                brick: wall.brick(b.b3).label,
                what: "is neither placed nor lost"
            })
        );
    }

    #[test]
    fn after_events_out_of_order_time_goes_on_from_the_latest() {
        let wall = mason_wall::builtin("thesis-2x5").unwrap().wall();
        let b = bricks(&wall);
        let comm = EventKind::Comm {
            mode: crate::state::CommMode::Comm,
        };
        // 0.5 s comes after 3 s, then 2 s: both go back in time (from 3 s).
        let mut t = trace(&b, &[], &[]);
        t.insert(4, at(0.5, 1, comm));
        t.insert(5, at(2.0, 1, comm));
        let found = trace_violations(&wall, 2, &t);
        assert_eq!(
            found,
            [
                TraceError::OutOfOrder { t: 0.5 },
                TraceError::OutOfOrder { t: 2.0 }
            ]
        );
    }

    #[test]
    fn an_orange_pair_shares_the_zone_and_a_third_uav_may_not() {
        let wall = mason_wall::builtin("mbzirc").unwrap().wall();
        let o = wall
            .ids()
            .find(|&b| wall.brick(b).kind.uavs_needed() == 2 && wall.supports(b).is_empty())
            .unwrap();
        let red = wall
            .ids()
            .find(|&b| wall.brick(b).kind.uavs_needed() == 1 && wall.supports(b).is_empty())
            .unwrap();
        let pair = [
            at(1.0, 0, EventKind::Grasp { brick: o }),
            at(1.0, 1, EventKind::Grasp { brick: o }),
            at(1.0, 2, EventKind::Grasp { brick: red }),
            at(2.0, 0, EventKind::ZoneEnter),
            at(2.0, 1, EventKind::ZoneEnter),
            at(3.0, 0, EventKind::Place { brick: o }),
            at(3.0, 0, EventKind::ZoneLeave),
            at(3.0, 1, EventKind::ZoneLeave),
        ];
        assert_eq!(check_trace(&wall, 3, &pair).unwrap().placed, 1);
        // Two UAVs with copies of one red brick are no pair.
        let copies = [
            at(1.0, 0, EventKind::Grasp { brick: red }),
            at(1.0, 1, EventKind::Grasp { brick: red }),
            at(2.0, 0, EventKind::ZoneEnter),
            at(2.0, 1, EventKind::ZoneEnter),
        ];
        assert_eq!(
            trace_violations(&wall, 3, &copies),
            [TraceError::ZoneShared { t: 2.0, a: 0, b: 1 }]
        );
        // Three UAVs with copies of one orange brick are one too many.
        let mut three = pair.to_vec();
        three[2] = at(1.0, 2, EventKind::Grasp { brick: o });
        three.insert(5, at(2.5, 2, EventKind::ZoneEnter));
        assert_eq!(
            trace_violations(&wall, 3, &three),
            [
                TraceError::ZoneShared { t: 2.5, a: 0, b: 2 },
                TraceError::ZoneShared { t: 2.5, a: 1, b: 2 }
            ]
        );
        let mut third = pair.to_vec();
        third.insert(5, at(2.5, 2, EventKind::ZoneEnter));
        let found = trace_violations(&wall, 3, &third);
        assert_eq!(
            found,
            [
                TraceError::ZoneShared { t: 2.5, a: 0, b: 2 },
                TraceError::ZoneShared { t: 2.5, a: 1, b: 2 }
            ]
        );
    }

    #[test]
    fn a_brick_lost_by_one_uav_is_not_lost_by_another_holding_a_copy() {
        // Two UAVs grasped copies of one red brick (a claim settled late); one puts its copy
        // down: the other still holds its own and may place it.
        let wall = mason_wall::builtin("thesis-2x5").unwrap().wall();
        let b = BrickId(0);
        let trace = [
            at(1.0, 0, EventKind::Grasp { brick: b }),
            at(1.0, 1, EventKind::Grasp { brick: b }),
            at(2.0, 1, EventKind::Lost { brick: b }),
            at(3.0, 0, EventKind::ZoneEnter),
            at(4.0, 0, EventKind::Place { brick: b }),
            at(4.0, 0, EventKind::ZoneLeave),
        ];
        assert_eq!(check_trace(&wall, 2, &trace).unwrap().placed, 1);
        // Without its own grasp, the second UAV cannot place it.
        let bad = [
            at(1.0, 0, EventKind::Grasp { brick: b }),
            at(2.0, 0, EventKind::Lost { brick: b }),
            at(3.0, 0, EventKind::ZoneEnter),
        ];
        assert!(check_trace(&wall, 2, &bad).is_err());
    }

    #[test]
    fn an_orange_brick_lost_by_one_of_its_pair_is_lost_for_both() {
        let wall = mason_wall::builtin("mbzirc").unwrap().wall();
        let b = wall
            .ids()
            .find(|&b| wall.brick(b).kind.uavs_needed() == 2)
            .unwrap();
        let trace = [
            at(1.0, 0, EventKind::Grasp { brick: b }),
            at(1.0, 1, EventKind::Grasp { brick: b }),
            at(2.0, 1, EventKind::Lost { brick: b }),
            at(3.0, 0, EventKind::ZoneEnter),
        ];
        assert!(matches!(
            check_trace(&wall, 2, &trace),
            Err(TraceError::Zone { .. })
        ));
    }
}
