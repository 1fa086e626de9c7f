//! When a UAV's pose is logged, and its heading: one rule for the simulated trace
//! ([`write_trace`](super::write_trace)) and for an agent's live log.
//!
//! A pose is due
//! - at the first sample, and at the first sample after [`PoseSampler::mark_due`] (an event:
//!   the log then shows where it happened);
//! - otherwise once the mission time reaches the next tick of the [`POSE_RATE_HZ`] grid
//!   (`k / POSE_RATE_HZ`, k = 1, 2, …) after the last pose logged.
//!
//! Ticks on a fixed grid, not a period after the last pose, so that a pose forced by an event
//! does not shift the later ones: the rate stays [`POSE_RATE_HZ`] whatever the events, and a
//! caller that can choose its sample times (the trace conversion, which samples each leg at
//! exactly the ticks [`ticks_between`] lists) gets every one of them.
//!
//! The heading (yaw, radians from east, counter-clockwise) follows the horizontal move from the
//! last pose logged when it is longer than [`MIN_MOVE`]; a UAV that hovers, climbs or lands in
//! place keeps its heading. The first heading is 0 (east).

use super::UavPose;

/// Rate of the poses logged between events (per second): the ticks `k / POSE_RATE_HZ`.
pub const POSE_RATE_HZ: f64 = 2.0;

/// Interval between two ticks (s).
const TICK: f64 = 1.0 / POSE_RATE_HZ;

/// The shortest horizontal move that turns the heading (m); a shorter one is noise.
const MIN_MOVE: f64 = 1e-6;

/// Index of the first tick strictly after `t`.
fn first_tick_index_after(t: f64) -> f64 {
    (t * POSE_RATE_HZ).floor() + 1.0
}

/// The ticks strictly after `from` and strictly before `to`, in order: the times at which a
/// pose is due along a leg flown from `from` to `to` with no event in between.
pub(super) fn ticks_between(from: f64, to: f64) -> impl Iterator<Item = f64> {
    let first = first_tick_index_after(from);
    (0u32..)
        .map(move |j| (first + f64::from(j)) * TICK)
        .take_while(move |&t| t < to)
}

/// Decides when UAV `uav`'s pose is logged and which way it heads (see the module's rule).
///
/// ```
/// use mason_report::PoseSampler;
/// let mut s = PoseSampler::new(0);
/// assert!(s.sample(0.0, (0.0, 0.0, 3.0)).is_some()); // the first pose
/// assert!(s.sample(0.2, (1.0, 0.0, 3.0)).is_none()); // before the next tick (0.5 s)
/// let p = s.sample(0.5, (0.0, 1.0, 3.0)).unwrap(); // heading north
/// assert!((p.yaw - std::f64::consts::FRAC_PI_2).abs() < 1e-12);
/// s.mark_due(); // an event
/// assert!(s.sample(0.6, (0.0, 1.0, 3.0)).is_some());
/// ```
#[derive(Clone, Debug)]
pub struct PoseSampler {
    /// The UAV whose poses these are.
    uav: u32,
    /// Time and position of the last pose logged.
    last: Option<(f64, (f64, f64, f64))>,
    /// Heading of the last pose logged (rad).
    yaw: f64,
    /// An event happened since the last pose logged.
    due: bool,
}

impl PoseSampler {
    /// A sampler for UAV `uav`: its first sample is logged, heading east.
    pub fn new(uav: u32) -> Self {
        PoseSampler {
            uav,
            last: None,
            yaw: 0.0,
            due: true,
        }
    }

    /// The UAV whose poses these are.
    pub fn uav(&self) -> u32 {
        self.uav
    }

    /// Something happened (an event): the next pose is logged whatever its time.
    pub fn mark_due(&mut self) {
        self.due = true;
    }

    /// The pose to log at mission time t at position p, or None when none is due; heading along the last move.
    pub fn sample(&mut self, t: f64, p: (f64, f64, f64)) -> Option<UavPose> {
        let (x, y, z) = p;
        let tick_reached = |(t0, _): (f64, _)| t >= first_tick_index_after(t0) * TICK;
        if !(self.due || self.last.is_none_or(tick_reached)) {
            return None;
        }
        if let Some((_, (x0, y0, _))) = self.last {
            let (dx, dy) = (x - x0, y - y0);
            if dx.hypot(dy) > MIN_MOVE {
                self.yaw = dy.atan2(dx);
            }
        }
        self.last = Some((t, p));
        self.due = false;
        Some(UavPose {
            x,
            y,
            z,
            yaw: self.yaw,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::{FRAC_PI_2, PI};

    /// Samples every 0.1 s along x at 1 m/s for `seconds`; the times logged.
    fn logged_times(s: &mut PoseSampler, from: f64, seconds: f64) -> Vec<f64> {
        let mut out = Vec::new();
        let steps = (seconds * 10.0).round() as u32;
        for k in 0..=steps {
            let t = from + f64::from(k) / 10.0;
            if s.sample(t, (t, 0.0, 3.0)).is_some() {
                out.push(t);
            }
        }
        out
    }

    fn close(a: &[f64], b: &[f64]) -> bool {
        a.len() == b.len() && a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-9)
    }

    #[test]
    fn the_first_sample_is_logged_then_one_per_tick() {
        let mut s = PoseSampler::new(3);
        assert_eq!(s.uav(), 3);
        let times = logged_times(&mut s, 0.0, 3.0);
        assert!(
            close(&times, &[0.0, 0.5, 1.0, 1.5, 2.0, 2.5, 3.0]),
            "{times:?}"
        );
    }

    #[test]
    fn the_rate_is_pose_rate_hz_on_a_fixed_grid_from_any_start() {
        // Starting between ticks: the next pose is at the next tick, not a period later.
        let mut s = PoseSampler::new(0);
        let times = logged_times(&mut s, 0.3, 2.0);
        assert!(close(&times, &[0.3, 0.5, 1.0, 1.5, 2.0]), "{times:?}");
        // Over a long run, POSE_RATE_HZ poses a second.
        let mut s = PoseSampler::new(0);
        let times = logged_times(&mut s, 0.05, 100.0);
        assert_eq!(times.len() as f64, 100.0 * POSE_RATE_HZ + 1.0);
    }

    #[test]
    fn a_pose_is_due_after_an_event_whatever_its_time() {
        let mut s = PoseSampler::new(0);
        assert!(s.sample(1.0, (0.0, 0.0, 3.0)).is_some());
        assert!(s.sample(1.1, (0.1, 0.0, 3.0)).is_none());
        s.mark_due();
        assert!(s.sample(1.1, (0.1, 0.0, 3.0)).is_some());
        // Once: the next sample waits for the next tick again.
        assert!(s.sample(1.2, (0.2, 0.0, 3.0)).is_none());
        // An event does not shift the grid: the tick at 1.5 s still comes.
        assert!(s.sample(1.5, (0.5, 0.0, 3.0)).is_some());
        // Two events before one sample give one pose.
        s.mark_due();
        s.mark_due();
        assert!(s.sample(1.6, (0.6, 0.0, 3.0)).is_some());
        assert!(s.sample(1.7, (0.7, 0.0, 3.0)).is_none());
    }

    #[test]
    fn the_heading_follows_the_last_move() {
        let mut s = PoseSampler::new(0);
        assert_eq!(s.sample(0.0, (0.0, 0.0, 3.0)).unwrap().yaw, 0.0);
        let north = s.sample(0.5, (0.0, 2.0, 3.0)).unwrap();
        assert!((north.yaw - FRAC_PI_2).abs() < 1e-12);
        let west = s.sample(1.0, (-1.0, 2.0, 3.0)).unwrap();
        assert!((west.yaw - PI).abs() < 1e-12);
        assert_eq!((west.x, west.y, west.z), (-1.0, 2.0, 3.0));
    }

    #[test]
    fn the_heading_is_kept_when_hovering_climbing_or_barely_moving() {
        let mut s = PoseSampler::new(0);
        s.sample(0.0, (0.0, 0.0, 0.0));
        let yaw = s.sample(0.5, (-1.0, -1.0, 0.0)).unwrap().yaw;
        assert!((yaw + 3.0 * PI / 4.0).abs() < 1e-12);
        // Hovering, climbing in place, and a drift below MIN_MOVE keep the heading.
        for (t, p) in [
            (1.0, (-1.0, -1.0, 0.0)),
            (1.5, (-1.0, -1.0, 3.0)),
            (2.0, (-1.0 + 0.5 * MIN_MOVE, -1.0, 3.0)),
        ] {
            assert_eq!(s.sample(t, p).unwrap().yaw, yaw, "at {t} s");
        }
        // Samples that are not logged do not count as moves: the heading is from the last
        // pose logged.
        assert!(s.sample(2.1, (5.0, -1.0, 3.0)).is_none());
        let back = s.sample(2.5, (-1.0, 0.0, 3.0)).unwrap();
        assert!((back.yaw - FRAC_PI_2).abs() < 1e-6);
    }

    #[test]
    fn ticks_between_lists_the_grid_strictly_inside() {
        let t: Vec<f64> = ticks_between(0.3, 2.0).collect();
        assert_eq!(t, [0.5, 1.0, 1.5]);
        let t: Vec<f64> = ticks_between(0.5, 1.7).collect();
        assert_eq!(t, [1.0, 1.5]);
        assert_eq!(ticks_between(1.0, 1.4).count(), 0);
        // Every tick listed after a pose is due for the sampler.
        let mut s = PoseSampler::new(0);
        s.sample(0.3, (0.0, 0.0, 3.0));
        for t in ticks_between(0.3, 10.0) {
            assert!(s.sample(t, (t, 0.0, 3.0)).is_some(), "{t}");
        }
    }
}
