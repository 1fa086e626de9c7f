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
