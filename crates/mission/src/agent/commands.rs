//! Obeying a ground station (DESIGN §8, issue #27 item 4): `abort`, `land` one UAV, `resume`.
//!
//! A command never cuts a step short: a UAV finishes the brick it has claimed (placed, or put
//! down by the usual rules) before it lands, so every rule of `check_trace` still holds, and
//! no command can make a UAV enter the zone, skip a support or place a brick twice; a command
//! only keeps a UAV from choosing its next brick. Each one shows in the trace as the state
//! transitions it causes, with its own outcome:
//!
//! * `abort`: at its next choice every UAV flies home and lands (`Land`, outcome `aborted`),
//!   and its mission ends (`Landed`); a UAV still on the ground before take-off lands at once.
//! * `land` (one UAV): it lands at its next choice (`Land`, outcome `commanded`) and waits on
//!   the ground (`Check`, outcome `held`) until `resume`; its teammates carry on.
//! * `resume`: calls off the landings not yet begun (an abort included), and a UAV waiting on
//!   the ground takes off again after its checks.

use super::wire::{Command, Order};
use super::Agent;
use crate::state::UavState;

/// The outcome of a landing ordered by `land`.
pub(super) const COMMANDED: &str = "commanded";
/// The outcome of a landing ordered by `abort`.
pub(super) const ABORTED: &str = "aborted";
/// The outcome of waiting on the ground after a commanded landing.
pub(super) const HELD: &str = "held";

/// What the ground stations have ordered this UAV, in force now.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(super) struct Orders {
    /// Abort: land, and end the mission.
    pub(super) abort: bool,
    /// Land and wait for `resume`.
    pub(super) land: bool,
}

impl Orders {
    /// Whether it must land at its next choice, and with which outcome.
    pub(super) fn landing(&self) -> Option<&'static str> {
        if self.abort {
            Some(ABORTED)
        } else if self.land {
            Some(COMMANDED)
        } else {
            None
        }
    }
}

impl Agent<'_> {
    /// Takes a checked command: what it orders is in force from the next tick.
    pub(super) fn obey(&mut self, c: &Command) {
        self.inbox.heard_command(c);
        match c.order {
            Order::Abort => self.orders.abort = true,
            Order::Land { uav } => self.orders.land |= uav as usize == self.me,
            Order::Resume => self.orders = Orders::default(),
        }
    }

    /// Orders for a UAV on the ground: an abort before take-off ends its mission; after a
    /// `resume`, a UAV held on the ground runs its checks and takes off again.
    pub(super) fn ground_orders(&mut self) {
        if self.flight.state != UavState::Check {
            return;
        }
        if self.orders.abort {
            self.go(UavState::Landed, ABORTED, None);
        } else if self.flight.outcome == HELD
            && !self.orders.land
            && self.flight.until == f64::INFINITY
        {
            self.flight.until = self.now + self.setup.config.uav.check_s;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::testkit::Fixture;
    use super::super::{Arrival, Command, Order};
    use super::*;

    #[test]
    fn command_outcomes_read_back_from_a_trace() {
        // Regression: `mason launch` could not read back the trace of an aborted team
        // ("unknown outcome `aborted`"): every outcome a command causes is a known one.
        for o in [COMMANDED, ABORTED, HELD] {
            assert_eq!(crate::state::outcome(o), Some(o));
        }
    }
    use crate::coord::Coord;
    use crate::state::{EventKind, UavState};

    fn command(seq: u64, t: f64, order: Order) -> Arrival {
        Arrival::command(Command {
            v: 1,
            mission: "test".into(),
            station: 0,
            seq,
            t,
            order,
        })
    }

    /// A lone agent on thesis-2x5, the commands delivered at their times: its events.
    fn fly(commands: &[(f64, Arrival)]) -> (Vec<crate::Event>, UavState, usize) {
        let fixture = Fixture::new("thesis-2x5", 1);
        let mut agents = fixture.agents(Coord::Comm);
        let a = &mut agents[0];
        let (mut t, mut events, mut next) = (0.0, Vec::new(), 0);
        for _ in 0..100_000 {
            if a.finished() || t > 3000.0 {
                break;
            }
            while next < commands.len() && commands[next].0 <= t {
                a.hear(t, commands[next].1.clone()).expect("obeyed");
                next += 1;
            }
            let tick = a.tick(t);
            events.extend(tick.events);
            t = tick.wake.min(t + 0.5);
        }
        fixture.check(&events);
        (events, a.state(), a.placed_known())
    }

    fn outcomes(events: &[crate::Event]) -> Vec<(UavState, &'static str)> {
        events
            .iter()
            .filter_map(|e| match e.kind {
                EventKind::State { state, outcome, .. } => Some((state, outcome)),
                _ => None,
            })
            .collect()
    }

    #[test]
    fn an_abort_lands_the_uav_after_its_brick_and_ends_its_mission() {
        let (events, state, placed) = fly(&[(100.0, command(1, 100.0, Order::Abort))]);
        assert_eq!(state, UavState::Landed);
        assert!(placed > 0 && placed < 10, "{placed}");
        let o = outcomes(&events);
        assert!(o.contains(&(UavState::Land, ABORTED)), "{o:?}");
    }

    #[test]
    fn an_abort_before_take_off_keeps_it_on_the_ground() {
        let (events, state, placed) = fly(&[(0.0, command(1, 0.0, Order::Abort))]);
        assert_eq!(state, UavState::Landed);
        assert_eq!(placed, 0);
        assert!(outcomes(&events).contains(&(UavState::Landed, ABORTED)));
        assert!(!outcomes(&events).iter().any(|s| s.0 == UavState::TakeOff));
    }

    #[test]
    fn a_landed_uav_waits_for_resume_and_then_finishes_the_wall() {
        let (events, state, placed) = fly(&[
            (100.0, command(1, 100.0, Order::Land { uav: 0 })),
            (600.0, command(2, 600.0, Order::Resume)),
        ]);
        assert_eq!(state, UavState::Landed);
        assert_eq!(placed, 10);
        let o = outcomes(&events);
        let held = o.iter().position(|s| *s == (UavState::Check, HELD));
        let land = o.iter().position(|s| *s == (UavState::Land, COMMANDED));
        assert!(land.is_some() && held > land, "{o:?}");
        // Nothing between the hold and the resume.
        let resumed = events
            .iter()
            .filter(|e| {
                matches!(
                    e.kind,
                    EventKind::State {
                        state: UavState::TakeOff,
                        ..
                    }
                )
            })
            .map(|e| e.t)
            .collect::<Vec<_>>();
        assert_eq!(resumed.len(), 2, "{resumed:?}");
        assert!(resumed[1] >= 600.0, "{resumed:?}");
    }

    #[test]
    fn a_land_order_for_another_uav_changes_nothing() {
        let fixture = Fixture::new("thesis-2x5", 2);
        let mut agents = fixture.agents(Coord::Comm);
        agents[0].tick(0.0);
        assert!(agents[0]
            .hear(0.0, command(1, 0.0, Order::Land { uav: 1 }))
            .is_ok());
        assert_eq!(agents[0].orders, Orders::default());
    }
}
