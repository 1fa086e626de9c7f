//! The per-UAV state machine's states (thesis Fig. 4.3) and the events of a trace.

use mason_wall::BrickId;
use serde::Serialize;

/// A UAV's state.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize)]
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
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
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
