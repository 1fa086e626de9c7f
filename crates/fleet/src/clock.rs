//! Mission time for an agent process: the [`Clock`] trait and the real [`MissionClock`].

use std::time::{Duration, Instant, SystemTime, UNIX_EPOCH};

/// Mission time.
pub trait Clock {
    /// Mission time now (s; negative before the start).
    fn now(&self) -> f64;
    /// The wall-clock instant at which mission time reaches `t`.
    fn instant_at(&self, t: f64) -> Instant;
}

/// The fastest clock accepted: a heartbeat every millisecond of wall time.
pub const MAX_SPEED: f64 = 1000.0;
/// The slowest clock accepted: a mission second every 1000 wall seconds (slower would make
/// every wait practically endless).
pub const MIN_SPEED: f64 = 1e-3;

/// The real clock: mission time = (wall time − `start_at`) × `speed`. Read from the system
/// clock once, then from the monotonic clock, so that it never goes back; processes on one
/// machine agree on it.
#[derive(Clone, Copy, Debug)]
pub struct MissionClock {
    origin: Instant,
    /// Mission time at `origin` (s).
    origin_t: f64,
    speed: f64,
}

/// Seconds since the Unix epoch, now.
pub fn unix_now() -> f64 {
    SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .map_or(0.0, |d| d.as_secs_f64())
}

impl MissionClock {
    /// A clock whose mission time 0 is `start_at` (Unix seconds), running `speed` times
    /// faster than the wall clock.
    pub fn new(start_at: f64, speed: f64) -> Self {
        MissionClock {
            origin: Instant::now(),
            origin_t: (unix_now() - start_at) * speed,
            speed,
        }
    }
}

impl Clock for MissionClock {
    fn now(&self) -> f64 {
        self.origin_t + self.origin.elapsed().as_secs_f64() * self.speed
    }

    fn instant_at(&self, t: f64) -> Instant {
        let wall = ((t - self.origin_t) / self.speed).clamp(0.0, 1e6);
        self.origin + Duration::from_secs_f64(wall)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_mission_clock_runs_at_its_speed_from_its_start() {
        let start = unix_now() + 10.0;
        let c = MissionClock::new(start, 2.0);
        let t = c.now();
        assert!((-20.5..=-19.5).contains(&t), "{t}");
        let at = c.instant_at(t + 2.0);
        let wall = at.saturating_duration_since(Instant::now()).as_secs_f64();
        assert!((0.5..=1.01).contains(&wall), "{wall}");
        // Far past or far future are clamped, never a panic.
        let _ = c.instant_at(-1e300);
        let _ = c.instant_at(1e300);
    }
}
