//! `comm`: the UAVs exchange position, state and intent. The UAV carrying the next needed
//! brick enters as soon as it *knows* the zone is free: the leaving UAV's message (or, if it
//! is lost, a later heartbeat) has reached it. Only one UAV carries the next needed brick, so
//! ties cannot arise (first come, first served would break them).

use crate::policy::{Coordination, EntryQuery};

/// The message-based policy.
#[derive(Clone, Copy, Debug, Default)]
pub struct Comm;

impl Coordination for Comm {
    fn name(&self) -> &'static str {
        "comm"
    }

    fn entry_time(&mut self, q: &mut EntryQuery<'_>) -> f64 {
        if q.zone_free_since <= 0.0 {
            return q.now;
        }
        q.channel.known_at(q.zone_free_since, q.rng).max(q.now)
    }
}
