//! Choosing a coordination policy by name, and the windows slot length for a wall.

use crate::auto::Auto;
use crate::comm::Comm;
use crate::config::{ConfigError, MissionConfig};
use crate::policy::Coordination;
use crate::windows::Windows;
use mason_order::CostModel;
use mason_wall::Wall;

/// The policies.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Coord {
    /// Messages.
    Comm,
    /// Fixed time windows.
    Windows,
    /// Messages, windows during heartbeat loss.
    Auto,
}

impl std::str::FromStr for Coord {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "comm" => Ok(Coord::Comm),
            "windows" => Ok(Coord::Windows),
            "auto" => Ok(Coord::Auto),
            _ => Err(format!("unknown coordination `{s}` (comm, windows, auto)")),
        }
    }
}

/// The default slot (DESIGN §5).
pub const DEFAULT_SLOT_S: f64 = 20.0;

/// The longest time any brick of `wall` can need in the zone (κ₂ placement).
pub fn longest_zone_time(wall: &Wall, model: &CostModel, config: &MissionConfig) -> f64 {
    wall.bricks()
        .iter()
        .map(|b| {
            config.uav.zone_transit_s
                + model.kappa.iter().copied().fold(0.0, f64::max) * model.times(b.kind).drop
        })
        .fold(0.0, f64::max)
}

/// The windows slot: the configured one (an error if some brick cannot fit in it), else 20 s
/// raised to the longest zone time.
pub fn slot_length(
    wall: &Wall,
    model: &CostModel,
    config: &MissionConfig,
) -> Result<f64, ConfigError> {
    let longest = longest_zone_time(wall, model, config);
    match config.coord.slot_s {
        Some(s) if s + 1e-9 < longest => Err(ConfigError {
            field: "slot".into(),
            value: Some(format!("{s}"))
                .filter(|v| v.len() <= 16)
                .unwrap_or_else(|| format!("{s:e}")),
            reason: format!("too small: a brick of this wall may need {longest:.1} s in the zone, so it could never enter; use at least that"),
        }),
        Some(s) => Ok(s),
        None => Ok(DEFAULT_SLOT_S.max(longest.ceil())),
    }
}

/// A fresh policy object.
pub fn make_policy(coord: Coord, slot: f64) -> Box<dyn Coordination> {
    match coord {
        Coord::Comm => Box::new(Comm),
        Coord::Windows => Box::new(Windows { slot }),
        Coord::Auto => Box::new(Auto {
            windows: Windows { slot },
        }),
    }
}
