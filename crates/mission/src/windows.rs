//! `windows`, for no communication (thesis §4.3): time is cut into slots of `slot` seconds, a
//! cycle of one slot per UAV. A UAV enters only in its own slot, only with the next needed
//! brick, and only if the rest of the slot covers its expected zone time.

use crate::policy::{Coordination, EntryQuery};

/// The time-window policy.
#[derive(Clone, Copy, Debug)]
pub struct Windows {
    /// Slot length, seconds.
    pub slot: f64,
}

impl Windows {
    /// The earliest entry time ≥ `now` for `uav` of `team` needing `zone_time` in the zone.
    pub fn next_entry(&self, now: f64, uav: usize, team: usize, zone_time: f64) -> f64 {
        let cycle = self.slot * team as f64;
        let offset = self.slot * uav as f64;
        let k = ((now - offset) / cycle).floor();
        let start = k * cycle + offset;
        if now >= start && now + zone_time <= start + self.slot + 1e-9 {
            return now;
        }
        // The next own slot (zone_time ≤ slot is checked when the policy is built).
        let mut next = start + cycle;
        while next < now {
            next += cycle;
        }
        next
    }
}

impl Coordination for Windows {
    fn name(&self) -> &'static str {
        "windows"
    }

    fn entry_time(&mut self, q: &mut EntryQuery<'_>) -> f64 {
        self.next_entry(q.now, q.uav, q.team, q.zone_time)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn enters_only_in_its_own_slot_with_time_to_spare() {
        let w = Windows { slot: 20.0 };
        // UAV 1 of 3: slots [20, 40), [80, 100), …
        assert_eq!(w.next_entry(25.0, 1, 3, 10.0), 25.0);
        assert_eq!(w.next_entry(35.0, 1, 3, 10.0), 80.0);
        assert_eq!(w.next_entry(5.0, 1, 3, 10.0), 20.0);
        assert_eq!(w.next_entry(100.0, 1, 3, 10.0), 140.0);
        assert_eq!(w.next_entry(0.0, 0, 3, 20.0), 0.0);
    }
}
