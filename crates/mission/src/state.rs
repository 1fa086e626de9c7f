//! The per-UAV state machine's states (thesis Fig. 4.3) and the events of a trace.

use mason_wall::BrickId;
use serde::{Deserialize, Serialize};

/// A UAV's state.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
pub enum UavState {
    /// Pre-flight check.
    Check,
    /// Taking off.
    TakeOff,
    /// Choosing the next brick of the shared order (or idling when none is free).
    ChooseBrick,
    /// Flying to the brick's pile.
    FlyToPile,
    /// Looking for the brick (or, for an orange brick, waiting for the partner).
    Detect,
    /// Descending over the detected brick.
    FlyAbove,
    /// Grasping.
    Grasp,
    /// Flying to the waiting point in front of the wall zone.
    FlyToWallWait,
    /// Waiting for permission to enter the wall zone.
    WaitForZone,
    /// In the zone, placing the brick.
    EnterAndPlace,
    /// Landing at the end.
    Land,
    /// Landing after a fault.
    SafeLand,
    /// On the ground, done.
    Landed,
    /// On the ground after a fault.
    Down,
}

impl UavState {
    /// Every state, in machine order.
    pub const ALL: [UavState; 14] = [
        UavState::Check,
        UavState::TakeOff,
        UavState::ChooseBrick,
        UavState::FlyToPile,
        UavState::Detect,
        UavState::FlyAbove,
        UavState::Grasp,
        UavState::FlyToWallWait,
        UavState::WaitForZone,
        UavState::EnterAndPlace,
        UavState::Land,
        UavState::SafeLand,
        UavState::Landed,
        UavState::Down,
    ];

    /// Dense index.
    pub fn index(self) -> usize {
        self as usize
    }

    /// The name used in JSON and figures.
    pub fn name(self) -> &'static str {
        match self {
            UavState::Check => "Check",
            UavState::TakeOff => "TakeOff",
            UavState::ChooseBrick => "ChooseBrick",
            UavState::FlyToPile => "FlyToPile",
            UavState::Detect => "Detect",
            UavState::FlyAbove => "FlyAbove",
            UavState::Grasp => "Grasp",
            UavState::FlyToWallWait => "FlyToWallWait",
            UavState::WaitForZone => "WaitForZone",
            UavState::EnterAndPlace => "EnterAndPlace",
            UavState::Land => "Land",
            UavState::SafeLand => "SafeLand",
            UavState::Landed => "Landed",
            UavState::Down => "Down",
        }
    }
}

/// How the team coordinates at a given moment.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum CommMode {
    /// By messages.
    Comm,
    /// By fixed time windows.
    Windows,
}

/// What happened.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
pub enum EventKind {
    /// A state transition: the new state, and the outcome of the state left.
    State {
        /// The new state.
        state: UavState,
        /// The outcome that led here (`done`, `failed`, `gave_up`, `none_free`, …).
        outcome: &'static str,
        /// Position (m).
        x: f64,
        /// Position (m).
        y: f64,
    },
    /// A brick grasped.
    Grasp {
        /// The brick.
        brick: BrickId,
    },
    /// A brick placed on the wall.
    Place {
        /// The brick.
        brick: BrickId,
    },
    /// A grasped brick lost (its UAV failed, or it was put down to break a deadlock).
    Lost {
        /// The brick.
        brick: BrickId,
    },
    /// The UAV entered the wall zone.
    ZoneEnter,
    /// The UAV left the wall zone.
    ZoneLeave,
    /// The UAV failed and is out.
    Fail,
    /// The survivors re-planned the rest of the wall (reported by the lowest live UAV).
    Replan {
        /// Bricks in the new plan.
        bricks: u32,
    },
    /// The UAV switched coordination mode.
    Comm {
        /// The new mode.
        mode: CommMode,
    },
}

/// One timestamped event of one UAV.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Event {
    /// Mission time, seconds.
    pub t: f64,
    /// 0-based UAV.
    pub uav: u32,
    /// What happened.
    #[serde(flatten)]
    pub kind: EventKind,
}

/// Events a mission may produce at the start, whatever its length: the trace cap's base.
pub const EVENTS_BASE: u64 = 100_000;
/// Events a mission may add per UAV and second of mission time.
pub const EVENTS_PER_UAV_S: u64 = 100;
/// Events a mission may produce in all (about 200 MB of `simulate --json`).
pub const MAX_EVENTS: u64 = 2_000_000;

/// The most events a mission of `uavs` UAVs may have produced by mission time `t`:
/// [`EVENTS_BASE`] + [`EVENTS_PER_UAV_S`] · uavs · t, at most [`MAX_EVENTS`]. A mission whose
/// durations are (near) zero makes events without making progress; past this cap the simulator
/// and the agents stop it ([`crate::MissionStatus::Flooded`]) instead of filling the memory or
/// the disk.
pub fn event_cap(uavs: usize, t: f64) -> u64 {
    let grown = EVENTS_BASE as f64 + EVENTS_PER_UAV_S as f64 * uavs as f64 * t.max(0.0);
    if grown >= MAX_EVENTS as f64 {
        MAX_EVENTS
    } else {
        grown as u64
    }
}

/// A mission that produced more events than [`event_cap`] allows.
#[derive(Clone, Copy, Debug, PartialEq, thiserror::Error)]
#[error(
    "{events} events by mission time {t:.3} s, over the event cap of {cap} (100 000 + 100 per \
     UAV and second, at most 2 000 000): a duration is too short to make progress"
)]
pub struct Flood {
    /// Events produced.
    pub events: u64,
    /// Mission time (s).
    pub t: f64,
    /// The cap at that time.
    pub cap: u64,
}

impl Flood {
    /// `Some` when `events` by mission time `t` are over the cap of a team of `uavs`.
    pub fn check(uavs: usize, t: f64, events: u64) -> Option<Flood> {
        let cap = event_cap(uavs, t);
        (events > cap).then_some(Flood { events, t, cap })
    }
}

/// Receives the simulator's events as they happen. Traces, metrics and plots are observers.
pub trait Observer {
    /// One event.
    fn event(&mut self, e: &Event);
}

impl Observer for () {
    fn event(&mut self, _: &Event) {}
}

impl Observer for Vec<Event> {
    fn event(&mut self, e: &Event) {
        self.push(*e);
    }
}

/// Every outcome a state transition may carry (the simulator's and the agents').
pub const OUTCOMES: [&str; 30] = [
    "start",
    "ok",
    "airborne",
    "found",
    "above",
    "grasped",
    "arrived",
    "landed",
    "cannot_finish",
    "none_free",
    "chosen",
    "partner_arrived",
    "waiting_partner",
    "gave_up",
    "failed",
    "put_down",
    "granted",
    "placed",
    "woken",
    "partner_failed",
    "fault",
    "down",
    "claim_lost",
    "declared_out",
    "rejoined",
    "killed",
    "pair_left",
    "commanded",
    "aborted",
    "held",
];

/// The outcome named `s`, if it is one of [`OUTCOMES`].
pub fn outcome(s: &str) -> Option<&'static str> {
    OUTCOMES.iter().copied().find(|o| *o == s)
}

/// One trace line as read back from JSON (an agent's trace file): [`Event`] with an owned
/// outcome, so that it can be checked before it becomes an [`Event`].
#[derive(Clone, Debug, PartialEq, Deserialize)]
pub struct EventRecord {
    /// Time (s).
    pub t: f64,
    /// The UAV.
    pub uav: u32,
    /// What happened.
    #[serde(flatten)]
    pub kind: KindRecord,
}

/// [`EventKind`] as read back from JSON.
#[derive(Clone, Debug, PartialEq, Deserialize)]
#[serde(tag = "kind", rename_all = "snake_case")]
#[allow(missing_docs)]
pub enum KindRecord {
    State {
        state: UavState,
        outcome: String,
        x: f64,
        y: f64,
    },
    Grasp {
        brick: BrickId,
    },
    Place {
        brick: BrickId,
    },
    Lost {
        brick: BrickId,
    },
    ZoneEnter,
    ZoneLeave,
    Fail,
    Replan {
        bricks: u32,
    },
    Comm {
        mode: CommMode,
    },
}

impl EventRecord {
    /// The event, or why it is not one (an unknown outcome, a time that is not finite).
    pub fn into_event(self) -> Result<Event, String> {
        if !self.t.is_finite() {
            return Err(format!("time {} is not finite", self.t));
        }
        let kind = match self.kind {
            KindRecord::State {
                state,
                outcome: o,
                x,
                y,
            } => EventKind::State {
                state,
                outcome: outcome(&o).ok_or_else(|| format!("unknown outcome `{o}`"))?,
                x,
                y,
            },
            KindRecord::Grasp { brick } => EventKind::Grasp { brick },
            KindRecord::Place { brick } => EventKind::Place { brick },
            KindRecord::Lost { brick } => EventKind::Lost { brick },
            KindRecord::ZoneEnter => EventKind::ZoneEnter,
            KindRecord::ZoneLeave => EventKind::ZoneLeave,
            KindRecord::Fail => EventKind::Fail,
            KindRecord::Replan { bricks } => EventKind::Replan { bricks },
            KindRecord::Comm { mode } => EventKind::Comm { mode },
        };
        Ok(Event {
            t: self.t,
            uav: self.uav,
            kind,
        })
    }
}

#[cfg(test)]
mod cap_tests {
    use super::*;

    #[test]
    fn the_event_cap_grows_with_time_and_team_and_stops_at_the_total() {
        assert_eq!(event_cap(3, 0.0), EVENTS_BASE);
        assert_eq!(event_cap(3, -5.0), EVENTS_BASE);
        assert_eq!(event_cap(3, 10.0), EVENTS_BASE + 3_000);
        assert!(event_cap(3, 100.0) < event_cap(4, 100.0));
        assert_eq!(event_cap(3, 1e6), MAX_EVENTS);
        assert_eq!(event_cap(256, f64::INFINITY), MAX_EVENTS);
        assert_eq!(event_cap(1, f64::NAN), EVENTS_BASE);
        assert_eq!(Flood::check(3, 10.0, EVENTS_BASE + 3_000), None);
        let f = Flood::check(3, 10.0, EVENTS_BASE + 3_001).unwrap();
        assert_eq!(
            (f.events, f.cap),
            (EVENTS_BASE + 3_001, EVENTS_BASE + 3_000)
        );
        assert!(f.to_string().contains("too short"), "{f}");
    }
}
