//! `auto`: `comm` with heartbeats. A UAV that has not heard a live teammate for longer than the
//! timeout falls back to `windows`, and returns to `comm` when every teammate is heard again.
//! The simulator runs the heartbeat process and sets each UAV's mode; this policy applies the
//! rule of the mode.

use crate::comm::Comm;
use crate::policy::{Coordination, EntryQuery};
use crate::state::CommMode;
use crate::windows::Windows;

/// The adaptive policy.
#[derive(Clone, Copy, Debug)]
pub struct Auto {
    /// The rule used without communication.
    pub windows: Windows,
}

impl Coordination for Auto {
    fn name(&self) -> &'static str {
        "auto"
    }

    fn entry_time(&mut self, q: &mut EntryQuery<'_>) -> f64 {
        match q.mode {
            CommMode::Comm => Comm.entry_time(q),
            CommMode::Windows => self.windows.entry_time(q),
        }
    }

    fn uses_heartbeats(&self) -> bool {
        true
    }
}
