//! The agent's own state machine (thesis Fig. 4.3): its state, the straight leg it flies,
//! the state's timer, and the steps from one state to the next. The timed steps come from the
//! decision core ([`crate::core::after`]); what it decides between them — its brick, its pair,
//! the zone — lives in the files of those concepts, called from [`Agent::decide`].

use super::{Agent, MessageKind};
use crate::arena::Point;
use crate::core::{after, kind, After};
use crate::state::{EventKind, UavState};

/// States in which it is on the ground and decides nothing.
pub(super) const GROUND: [UavState; 3] = [UavState::Check, UavState::Landed, UavState::Down];

/// A straight leg at constant speed, from `from` at `t0` to `to` at `t1`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Leg {
    pub(super) from: Point,
    pub(super) to: Point,
    pub(super) t0: f64,
    pub(super) t1: f64,
}

impl Leg {
    /// Where the leg is at `now` (its ends before and after it).
    fn at(&self, now: f64) -> Point {
        let f = ((now - self.t0) / (self.t1 - self.t0)).clamp(0.0, 1.0);
        Point {
            x: self.from.x + (self.to.x - self.from.x) * f,
            y: self.from.y + (self.to.y - self.from.y) * f,
        }
    }
}

/// Its own state machine: the state, where it is, and when the state's timer runs out.
#[derive(Clone, Debug)]
pub(super) struct Flight {
    /// Its state.
    pub(super) state: UavState,
    /// The outcome that led to `state`.
    pub(super) outcome: &'static str,
    /// When `state` began (s; `NaN` before the first tick).
    pub(super) since: f64,
    /// Where it is when not on a leg (and where the current leg began).
    pub(super) pos: Point,
    /// The leg it flies, if any.
    pub(super) leg: Option<Leg>,
    /// When the state's timer runs out (s; infinite: an untimed state).
    pub(super) until: f64,
}

impl Flight {
    /// Where it is at `now`: on its leg, or where it stopped.
    pub(super) fn position(&self, now: f64) -> Point {
        match self.leg {
            Some(leg) if leg.t1 > leg.t0 => leg.at(now),
            _ => self.pos,
        }
    }

    /// How far through its state it is at `now`: 0 at the start, 1 when its timer runs out
    /// (0 throughout an untimed or instant state).
    pub(super) fn progress(&self, now: f64) -> f64 {
        if self.until.is_finite() && self.until > self.since {
            ((now - self.since) / (self.until - self.since)).clamp(0.0, 1.0)
        } else {
            0.0
        }
    }
}

impl Agent<'_> {
    /// Enters `state` after `outcome`, for `duration` (s; `None`: until something happens).
    pub(super) fn go(&mut self, state: UavState, outcome: &'static str, duration: Option<f64>) {
        let f = &mut self.flight;
        f.state = state;
        f.outcome = outcome;
        f.since = self.now;
        let (x, y) = (f.pos.x, f.pos.y);
        self.emit(EventKind::State {
            state,
            outcome,
            x,
            y,
        });
        self.flight.until = duration.map_or(f64::INFINITY, |d| self.now + d);
        self.mark(MessageKind::State);
    }

    /// Enters `state` flying straight to `to`; the state lasts the flight plus `extra` (s).
    pub(super) fn fly(&mut self, state: UavState, outcome: &'static str, to: Point, extra: f64) {
        let d = self.flight.pos.distance(to) / self.setup.config.uav.speed;
        self.go(state, outcome, Some(d + extra));
        self.flight.leg = Some(Leg {
            from: self.flight.pos,
            to,
            t0: self.now,
            t1: self.now + d,
        });
    }

    /// At `at`, off its leg.
    pub(super) fn arrive(&mut self, at: Point) {
        self.flight.pos = at;
        self.flight.leg = None;
    }

    /// The state's timer ran out: the step of the state machine that follows.
    pub(super) fn on_timer(&mut self) {
        let cfg = self.setup.config;
        match after(self.flight.state, cfg.uav.takeoff_s) {
            After::Go {
                state,
                outcome,
                duration,
            } => {
                // Ordered down before take-off: it waits (an abort ends it at the next tick).
                if state == UavState::TakeOff && self.orders.landing().is_some() {
                    self.flight.until = self.now + cfg.coord.heartbeat_s;
                    return;
                }
                // A (re)started agent learns the wall from its teammates before it flies.
                if state == UavState::TakeOff
                    && !self.members.heard_all(self.me)
                    && self.now - self.members.started < self.setup.dead_after_s
                {
                    self.flight.until = self.now + cfg.coord.heartbeat_s;
                    return;
                }
                self.go(state, outcome, Some(duration));
            }
            After::Choose => self.choose("airborne"),
            After::AtPile => {
                let b = self.work.brick.expect("carrying");
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
                let b = self.work.brick.expect("carrying");
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
            After::Placed => match self.work.brick {
                Some(b) if !self.leader(b) => self.leave_with_leader(),
                _ => self.place(),
            },
            After::Landed => {
                self.arrive(cfg.arena.uav_starts[self.me]);
                if self.flight.outcome == super::commands::COMMANDED && !self.orders.abort {
                    // Landed on a station's order: it waits for `resume` on the ground.
                    self.go(UavState::Check, super::commands::HELD, None);
                } else {
                    self.go(UavState::Landed, "landed", None);
                }
            }
            After::Nothing => {}
        }
    }

    /// Everything it decides on what it knows now, in the air.
    pub(super) fn decide(&mut self) {
        let state = self.flight.state;
        if GROUND.contains(&state) || matches!(state, UavState::Land | UavState::TakeOff) {
            return;
        }
        if state == UavState::WaitForZone {
            self.inspect();
        }
        if self.settle_claim() || self.pair_let_go() {
            return;
        }
        if self.flight.state == UavState::ChooseBrick && self.work.brick.is_none() {
            return self.choose("woken");
        }
        let Some(b) = self.work.brick else {
            return;
        };
        if kind(self.setup.wall, b).uavs_needed() == 2 {
            self.pair(b);
        }
        if self.flight.state == UavState::WaitForZone && self.leader(b) {
            self.zone(b);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::testkit::Fixture;
    use super::*;
    use crate::coord::Coord;

    #[test]
    fn a_leg_is_flown_straight_at_constant_speed() {
        let leg = Leg {
            from: Point { x: 0.0, y: 0.0 },
            to: Point { x: 10.0, y: -4.0 },
            t0: 2.0,
            t1: 4.0,
        };
        assert_eq!(leg.at(1.0), leg.from);
        assert_eq!(leg.at(3.0), Point { x: 5.0, y: -2.0 });
        assert_eq!(leg.at(9.0), leg.to);
    }

    #[test]
    fn progress_runs_from_the_state_start_to_its_timer() {
        let mut f = Flight {
            state: UavState::TakeOff,
            outcome: "ok",
            since: 10.0,
            pos: Point { x: 1.0, y: 1.0 },
            leg: None,
            until: 14.0,
        };
        assert_eq!(f.progress(9.0), 0.0);
        assert_eq!(f.progress(11.0), 0.25);
        assert_eq!(f.progress(20.0), 1.0);
        assert_eq!(f.position(11.0), f.pos);
        f.until = f64::INFINITY;
        assert_eq!(f.progress(11.0), 0.0);
    }

    #[test]
    fn the_pose_climbs_through_take_off() {
        let fixture = Fixture::new("thesis-2x5", 1);
        let (check, takeoff) = (fixture.config.uav.check_s, fixture.config.uav.takeoff_s);
        let mut agents = fixture.agents(Coord::Comm);
        let a = &mut agents[0];
        a.tick(0.0);
        assert_eq!(a.state(), UavState::Check);
        assert_eq!(a.pose(0.0).2, 0.0);
        let tick = a.tick(check);
        assert_eq!(a.state(), UavState::TakeOff);
        // Its status at the start of the take-off says it is on the ground.
        assert!(tick.messages.iter().all(|m| m.status.z == 0.0));
        assert_eq!(a.pose(check + takeoff / 2.0).2, 1.5);
        let tick = a.tick(check + takeoff);
        assert_ne!(a.state(), UavState::TakeOff);
        assert_eq!(a.pose(check + takeoff).2, 3.0);
        assert!(tick.messages.iter().all(|m| m.status.z == 3.0));
    }
}
