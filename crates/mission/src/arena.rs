//! The arena: where the UAVs start, the piles, the wall, its zone and the waiting points.
//!
//! The default is MBZIRC-like, 60 × 50 m, calibrated so that at the default 2 m/s the flight
//! from each pile to the wall's middle waiting point takes the thesis's t_f: red 22.5 s,
//! green 18.5 s, blue 22.5 s, orange 25 s.

use mason_wall::BrickType;
use serde::{Deserialize, Serialize};

/// A point on the ground plane, metres.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Point {
    /// East.
    pub x: f64,
    /// North.
    pub y: f64,
}

impl Point {
    /// A point.
    pub const fn new(x: f64, y: f64) -> Self {
        Point { x, y }
    }

    /// Straight-line distance.
    pub fn distance(self, o: Point) -> f64 {
        (self.x - o.x).hypot(self.y - o.y)
    }
}

/// The arena's layout.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Arena {
    /// Width (x), metres.
    pub width: f64,
    /// Depth (y), metres.
    pub depth: f64,
    /// Where each UAV takes off and lands; the team size may not exceed their number.
    pub uav_starts: Vec<Point>,
    /// The pile of each colour, in the order red, green, blue, orange.
    pub piles: [Point; 4],
    /// The middle of the wall.
    pub wall: Point,
    /// Half-size of the wall zone box (x, y) around `wall`.
    pub zone_half: Point,
    /// The waiting points in front of the wall zone, one per UAV (cycled if fewer).
    pub wall_waits: Vec<Point>,
}

/// The most UAV starts or wall waiting points an arena may list.
pub const MAX_ARENA_POINTS: usize = 256;
/// The longest side of an arena (m).
pub const MAX_ARENA_M: f64 = 100_000.0;

/// The thesis's pile→wall flight times t_f (s), red, green, blue, orange.
pub const CALIBRATED_FLIGHT: [f64; 4] = [22.5, 18.5, 22.5, 25.0];

/// The default UAV speed the arena is calibrated for (m/s).
pub const CALIBRATED_SPEED: f64 = 2.0;

impl Default for Arena {
    fn default() -> Self {
        let wait_mid = Point::new(42.0, 10.0);
        // Pile directions (degrees from east), chosen to keep every pile inside 60 × 50 m.
        let angles = [125.0f64, 100.0, 152.0, 138.0];
        let piles = std::array::from_fn(|i| {
            let d = CALIBRATED_FLIGHT[i] * CALIBRATED_SPEED;
            let a = angles[i].to_radians();
            Point::new(wait_mid.x + d * a.cos(), wait_mid.y + d * a.sin())
        });
        Arena {
            width: 60.0,
            depth: 50.0,
            uav_starts: (0..6)
                .map(|i| Point::new(50.0 + 1.5 * i as f64, 45.0))
                .collect(),
            piles,
            wall: Point::new(42.0, 4.0),
            zone_half: Point::new(5.0, 4.0),
            wall_waits: vec![wait_mid, Point::new(38.0, 10.0), Point::new(46.0, 10.0)],
        }
    }
}

impl Arena {
    /// The pile of a colour.
    pub fn pile(&self, kind: BrickType) -> Point {
        self.piles[kind.index()]
    }

    /// UAV `i`'s waiting point at the wall.
    pub fn wall_wait(&self, i: usize) -> Point {
        self.wall_waits[i % self.wall_waits.len()]
    }

    /// Checks the layout: positive size, every point inside, at least one start and one wait.
    pub fn validate(&self) -> Result<(), String> {
        if !(self.width > 0.0 && self.depth > 0.0) {
            return Err("arena width and depth must be positive".into());
        }
        if self.uav_starts.is_empty() || self.wall_waits.is_empty() {
            return Err("the arena needs at least one UAV start and one wall waiting point".into());
        }
        for (what, n) in [
            ("UAV starts", self.uav_starts.len()),
            ("wall waiting points", self.wall_waits.len()),
        ] {
            if n > MAX_ARENA_POINTS {
                return Err(format!(
                    "{n} {what}: at most {MAX_ARENA_POINTS} (MAX_ARENA_POINTS), one per UAV is enough"
                ));
            }
        }
        if !(self.width <= MAX_ARENA_M && self.depth <= MAX_ARENA_M) {
            return Err(format!(
                "an arena of {} × {} m: at most {MAX_ARENA_M} m a side (MAX_ARENA_M)",
                self.width, self.depth
            ));
        }
        let inside = |p: &Point| {
            p.x.is_finite()
                && p.y.is_finite()
                && (0.0..=self.width).contains(&p.x)
                && (0.0..=self.depth).contains(&p.y)
        };
        let named = self
            .uav_starts
            .iter()
            .map(|p| ("a UAV start", p))
            .chain(self.piles.iter().map(|p| ("a pile", p)))
            .chain(self.wall_waits.iter().map(|p| ("a wall waiting point", p)))
            .chain(std::iter::once(("the wall", &self.wall)));
        for (what, p) in named {
            if !inside(p) {
                return Err(format!(
                    "{what} at ({}, {}) is outside the {} × {} m arena",
                    p.x, p.y, self.width, self.depth
                ));
            }
        }
        if !(self.zone_half.x > 0.0 && self.zone_half.y > 0.0) {
            return Err("the wall zone must have a positive size".into());
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// #32: a mission file listing 20 000 positions is refused before anything is built.
    #[test]
    fn an_arena_of_thousands_of_points_is_refused() {
        let mut a = Arena::default();
        a.uav_starts = vec![a.uav_starts[0]; 20_000];
        let e = a.validate().unwrap_err();
        assert!(e.contains("MAX_ARENA_POINTS"), "{e}");
        let a = Arena {
            width: 1e300,
            ..Arena::default()
        };
        assert!(a.validate().unwrap_err().contains("MAX_ARENA_M"));
    }

    #[test]
    fn default_arena_is_calibrated_to_the_thesis() {
        let a = Arena::default();
        a.validate().unwrap();
        for kind in BrickType::ALL {
            let t = a.pile(kind).distance(a.wall_wait(0)) / CALIBRATED_SPEED;
            assert!(
                (t - CALIBRATED_FLIGHT[kind.index()]).abs() < 1e-9,
                "{kind}: {t}"
            );
            // The other waiting points are within 2.5 s of it.
            for i in 1..3 {
                let t_i = a.pile(kind).distance(a.wall_wait(i)) / CALIBRATED_SPEED;
                assert!((t_i - t).abs() < 2.5, "{kind} wait {i}: {t_i} vs {t}");
            }
        }
    }
}
