//! Coordination policies behind one trait, so that a new policy is one new file
//! (see [`crate::comm`], [`crate::windows`], [`crate::auto`]).

use crate::channel::Channel;
use crate::state::CommMode;
use rand_chacha::ChaCha8Rng;

/// What a policy may look at when a UAV that carries the next needed brick waits in front of
/// a free zone.
pub struct EntryQuery<'a> {
    /// Now.
    pub now: f64,
    /// The waiting UAV (for a pair, the leader).
    pub uav: usize,
    /// Team size.
    pub team: usize,
    /// When the zone last became free (0 at the start).
    pub zone_free_since: f64,
    /// The time this entry is expected to take in the zone.
    pub zone_time: f64,
    /// The UAV's current mode (only `auto` switches it).
    pub mode: CommMode,
    /// The radio.
    pub channel: &'a Channel,
    /// The mission's random stream.
    pub rng: &'a mut ChaCha8Rng,
}

/// A coordination policy: when may the UAV that carries the next needed brick enter the zone?
/// The simulator asks again whenever anything relevant changes, so a policy only answers for
/// the present state.
pub trait Coordination: Send {
    /// The policy's name (`comm`, `windows`, `auto`).
    fn name(&self) -> &'static str;
    /// The earliest time ≥ `q.now` at which the UAV may enter.
    fn entry_time(&mut self, q: &mut EntryQuery<'_>) -> f64;
    /// Whether the policy follows heartbeats and switches modes (then the simulator runs a
    /// heartbeat process).
    fn uses_heartbeats(&self) -> bool {
        false
    }
}
