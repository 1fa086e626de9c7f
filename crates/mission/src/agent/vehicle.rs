//! The vehicle under an agent: what the decision core cannot decide by itself. A real
//! autopilot implements [`Autopilot`]; [`SimulatedVehicle`] draws its detections and grasps
//! from a seeded generator and sees a shared simulated wall ([`WallView`]).

use crate::config::MissionConfig;
use mason_wall::BrickId;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::sync::Arc;

/// The physical side of one UAV: what the decision core cannot decide.
pub trait Autopilot: Send {
    /// Whether detecting the brick below succeeds.
    fn detect(&mut self) -> bool;
    /// Whether grasping succeeds.
    fn grasp(&mut self) -> bool;
    /// At the wall, its camera sees whether `brick` is on it (`None`: no camera). Used when
    /// a teammate went silent holding a brick, and before every placement.
    fn sees_on_wall(&mut self, brick: BrickId) -> Option<bool> {
        let _ = brick;
        None
    }
    /// Carrying an orange brick with a partner: whether the brick has fallen since `since`
    /// (s), because the partner let go (`None`: no such sensor). The pair is one rigid load:
    /// when one side lets go, the other feels it at once.
    fn pair_dropped(&mut self, brick: BrickId, since: f64) -> Option<bool> {
        let _ = (brick, since);
        None
    }
}

/// The simulated world the vehicles share: the bricks on the wall, and the bricks that fell.
pub trait WallView: Send + Sync {
    /// Whether `brick` is on the wall.
    fn placed(&self, brick: BrickId) -> bool;
    /// Whether `brick` was reported lost after `since` (s).
    fn lost_since(&self, brick: BrickId, since: f64) -> bool;
}

/// A vehicle simulated in-process: detection and grasps fail with the configured
/// probabilities, from its own seeded generator; its camera sees a [`WallView`], if given.
pub struct SimulatedVehicle {
    rng: ChaCha8Rng,
    detect_fail: f64,
    grasp_fail: f64,
    world: Option<Arc<dyn WallView>>,
}

impl SimulatedVehicle {
    /// A vehicle with `config`'s fault probabilities and no camera.
    pub fn new(config: &MissionConfig, seed: u64) -> Self {
        SimulatedVehicle {
            rng: ChaCha8Rng::seed_from_u64(seed),
            detect_fail: config.faults.detect_fail,
            grasp_fail: config.faults.grasp_fail,
            world: None,
        }
    }

    /// The same, with a camera on `world`.
    pub fn with_world(mut self, world: Arc<dyn WallView>) -> Self {
        self.world = Some(world);
        self
    }
}

impl Autopilot for SimulatedVehicle {
    fn detect(&mut self) -> bool {
        self.rng.gen::<f64>() >= self.detect_fail
    }
    fn grasp(&mut self) -> bool {
        self.rng.gen::<f64>() >= self.grasp_fail
    }
    fn sees_on_wall(&mut self, brick: BrickId) -> Option<bool> {
        self.world.as_ref().map(|w| w.placed(brick))
    }
    fn pair_dropped(&mut self, brick: BrickId, since: f64) -> Option<bool> {
        self.world.as_ref().map(|w| w.lost_since(brick, since))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Brick 1 is on the wall; brick 2 fell at 10 s.
    struct Fixed;

    impl WallView for Fixed {
        fn placed(&self, brick: BrickId) -> bool {
            brick == BrickId(1)
        }
        fn lost_since(&self, brick: BrickId, since: f64) -> bool {
            brick == BrickId(2) && 10.0 > since
        }
    }

    fn config(detect_fail: f64, grasp_fail: f64) -> MissionConfig {
        let mut c = MissionConfig::with_uavs(1);
        c.faults.detect_fail = detect_fail;
        c.faults.grasp_fail = grasp_fail;
        c
    }

    #[test]
    fn a_fault_free_vehicle_always_succeeds() {
        let mut v = SimulatedVehicle::new(&config(0.0, 0.0), 1);
        assert!((0..100).all(|_| v.detect() && v.grasp()));
    }

    #[test]
    fn failures_come_at_the_configured_rate_and_repeat_with_the_seed() {
        let draw = |seed| {
            let mut v = SimulatedVehicle::new(&config(0.5, 0.25), seed);
            (0..4000)
                .map(|_| (v.detect(), v.grasp()))
                .collect::<Vec<_>>()
        };
        let a = draw(7);
        assert_eq!(a, draw(7));
        assert_ne!(a, draw(8));
        let detected = a.iter().filter(|x| x.0).count() as f64 / 4000.0;
        let grasped = a.iter().filter(|x| x.1).count() as f64 / 4000.0;
        assert!((detected - 0.5).abs() < 0.03, "{detected}");
        assert!((grasped - 0.75).abs() < 0.03, "{grasped}");
    }

    #[test]
    fn without_a_camera_it_sees_nothing_and_with_one_it_sees_the_world() {
        let mut blind = SimulatedVehicle::new(&config(0.0, 0.0), 1);
        assert_eq!(blind.sees_on_wall(BrickId(1)), None);
        assert_eq!(blind.pair_dropped(BrickId(2), 0.0), None);
        let mut v = SimulatedVehicle::new(&config(0.0, 0.0), 1).with_world(Arc::new(Fixed));
        assert_eq!(v.sees_on_wall(BrickId(1)), Some(true));
        assert_eq!(v.sees_on_wall(BrickId(0)), Some(false));
        assert_eq!(v.pair_dropped(BrickId(2), 5.0), Some(true));
        assert_eq!(v.pair_dropped(BrickId(2), 10.0), Some(false));
    }
}
