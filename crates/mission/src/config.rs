//! Mission settings: the UAV model, timings, coordination parameters and faults. Plain structs
//! with `Default` and validation; TOML-readable.

use crate::arena::Arena;
use mason_wall::limits::shown;
use serde::{Deserialize, Serialize};
use thiserror::Error;

/// The UAV model and per-state timings (seconds, metres per second).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct UavModel {
    /// Maximum speed on straight legs.
    pub speed: f64,
    /// Pre-flight check.
    pub check_s: f64,
    /// Take-off.
    pub takeoff_s: f64,
    /// Landing (and safe landing).
    pub land_s: f64,
    /// One detection attempt at a pile.
    pub detect_s: f64,
    /// Descending over a detected brick.
    pub above_s: f64,
    /// Flying into and out of the wall zone, together.
    pub zone_transit_s: f64,
    /// Detect or grasp failures tolerated on one brick before the UAV gives it back.
    pub retries: u32,
}

impl Default for UavModel {
    fn default() -> Self {
        UavModel {
            speed: 2.0,
            check_s: 2.0,
            takeoff_s: 5.0,
            land_s: 5.0,
            detect_s: 2.0,
            above_s: 1.0,
            zone_transit_s: 2.0,
            retries: 3,
        }
    }
}

/// Coordination parameters.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct CoordParams {
    /// Heartbeat (and status re-broadcast) period.
    pub heartbeat_s: f64,
    /// `auto`: fall back to windows when a live teammate is unheard for this long.
    pub heartbeat_timeout_s: f64,
    /// `windows`: slot length per UAV; `None` means 20 s, raised to the longest expected zone
    /// time of the wall's bricks if that is longer.
    pub slot_s: Option<f64>,
}

impl Default for CoordParams {
    fn default() -> Self {
        CoordParams {
            heartbeat_s: 1.0,
            heartbeat_timeout_s: 3.0,
            slot_s: None,
        }
    }
}

/// A time window, seconds. Written as a table `{from = A, to = B}` or as the string `"A-B"`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Window {
    /// Start.
    pub from: f64,
    /// End.
    pub to: f64,
}

impl Window {
    /// Whether `t` lies in the window.
    pub fn contains(&self, t: f64) -> bool {
        t >= self.from && t < self.to
    }
}

/// A UAV failing at a given time. Written as a table `{uav = U, at = T}` or as the string
/// `"U@T"`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct UavFailure {
    /// 0-based UAV.
    pub uav: usize,
    /// Time, seconds.
    pub at: f64,
}

/// A time in seconds, finite and ≥ 0.
fn seconds(x: &str) -> Option<f64> {
    x.trim()
        .parse::<f64>()
        .ok()
        .filter(|v| v.is_finite() && *v >= 0.0)
}

/// `A-B` in seconds, 0 ≤ A < B: the one parser of windows (flags and files alike).
impl std::str::FromStr for Window {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        let (a, b) = s
            .split_once('-')
            .ok_or("expected A-B in mission seconds, e.g. 100-125")?;
        let num = |x: &str| seconds(x).ok_or(format!("`{x}` is not a time in seconds"));
        let (from, to) = (num(a)?, num(b)?);
        if from >= to {
            return Err("the window ends before it starts".into());
        }
        Ok(Window { from, to })
    }
}

/// `U@T`: UAV U (0-based) at T ≥ 0 s: the one parser of timed failures (flags and files).
impl std::str::FromStr for UavFailure {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        let (u, t) = s.split_once('@').ok_or("expected U@T, e.g. 1@300")?;
        let uav = u
            .trim()
            .parse::<usize>()
            .map_err(|_| format!("`{u}` is not a UAV number"))?;
        let at = seconds(t).ok_or(format!("`{t}` is not a time in seconds"))?;
        Ok(UavFailure { uav, at })
    }
}

impl std::fmt::Display for Window {
    /// The text form, `A-B`, that [`Window`]'s `from_str` reads back.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}-{}", self.from, self.to)
    }
}

impl std::fmt::Display for UavFailure {
    /// The text form, `U@T`, that [`UavFailure`]'s `from_str` reads back.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}@{}", self.uav, self.at)
    }
}

/// Reads a value written either as a table (`Table`, converted) or as its text form
/// (`T::from_str`); a value of neither form gets `expected`, naming both.
fn table_or_text<'de, D, Table, T>(d: D, expected: &'static str) -> Result<T, D::Error>
where
    D: serde::Deserializer<'de>,
    Table: Deserialize<'de> + Into<T>,
    T: std::str::FromStr<Err = String>,
{
    use serde::de::Error;
    #[derive(Deserialize)]
    #[serde(untagged)]
    enum Form<Table> {
        Table(Table),
        Text(String),
    }
    match Form::<Table>::deserialize(d).map_err(|_| D::Error::custom(expected))? {
        Form::Table(t) => Ok(t.into()),
        Form::Text(s) => s
            .parse()
            .map_err(|why| D::Error::custom(format!("`{}`: {why}", shown(&s)))),
    }
}

/// A window as a table.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct WindowTable {
    from: f64,
    to: f64,
}

impl From<WindowTable> for Window {
    fn from(t: WindowTable) -> Self {
        Window {
            from: t.from,
            to: t.to,
        }
    }
}

impl<'de> Deserialize<'de> for Window {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        table_or_text::<D, WindowTable, Window>(
            d,
            "expected a window as {from = A, to = B} or \"A-B\" (seconds)",
        )
    }
}

/// A UAV failure as a table.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct UavFailureTable {
    uav: usize,
    at: f64,
}

impl From<UavFailureTable> for UavFailure {
    fn from(t: UavFailureTable) -> Self {
        UavFailure {
            uav: t.uav,
            at: t.at,
        }
    }
}

impl<'de> Deserialize<'de> for UavFailure {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        table_or_text::<D, UavFailureTable, UavFailure>(
            d,
            "expected a UAV failure as {uav = U, at = T} or \"U@T\" (0-based UAV, seconds)",
        )
    }
}

/// Every fault of DESIGN §5.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct Faults {
    /// Probability that one grasp attempt fails.
    pub grasp_fail: f64,
    /// Probability that one detection attempt fails.
    pub detect_fail: f64,
    /// UAVs failing at set times.
    pub uav_fail: Vec<UavFailure>,
    /// Failures per hour per UAV (exponential).
    pub uav_hazard: f64,
    /// No message gets through in these windows.
    pub blackout: Vec<Window>,
    /// Probability that one message is lost.
    pub msg_loss: f64,
    /// Message latency, seconds.
    pub latency: f64,
}

/// A setting out of range.
#[derive(Clone, Debug, PartialEq, Error)]
#[error("{field} = {value}: {reason}")]
pub struct ConfigError {
    /// The setting.
    pub field: String,
    /// Its value.
    pub value: String,
    /// Why it is wrong.
    pub reason: String,
}

fn err(field: &str, value: impl ToString, reason: &str) -> ConfigError {
    let mut value = value.to_string();
    if value.len() > 16 {
        if let Ok(v) = value.parse::<f64>() {
            value = format!("{v:e}");
        }
    }
    ConfigError {
        field: field.into(),
        value,
        reason: reason.into(),
    }
}

/// The shortest heartbeat period or timeout accepted (s).
pub const MIN_HEARTBEAT_S: f64 = 0.1;

/// The longest mission time accepted (s): a mission stops by then, whatever happens.
pub const MAX_MISSION_TIME_S: f64 = 1e6;

/// Everything a mission needs besides the wall, the order and the seed.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct MissionConfig {
    /// Team size.
    pub uavs: usize,
    /// Layout.
    pub arena: Arena,
    /// UAV model.
    pub uav: UavModel,
    /// Coordination parameters.
    pub coord: CoordParams,
    /// Faults.
    pub faults: Faults,
    /// Give up after this much mission time (s).
    pub max_time_s: f64,
}

impl Default for MissionConfig {
    fn default() -> Self {
        MissionConfig {
            uavs: 3,
            arena: Arena::default(),
            uav: UavModel::default(),
            coord: CoordParams::default(),
            faults: Faults::default(),
            max_time_s: 7200.0,
        }
    }
}

impl MissionConfig {
    /// The defaults with `uavs` UAVs.
    pub fn with_uavs(uavs: usize) -> Self {
        MissionConfig {
            uavs,
            ..MissionConfig::default()
        }
    }

    /// Checks every setting.
    pub fn validate(&self) -> Result<(), ConfigError> {
        if self.uavs == 0 {
            return Err(err("uavs", self.uavs, "a mission needs at least one UAV"));
        }
        if self.uavs > self.arena.uav_starts.len() {
            return Err(err(
                "uavs",
                self.uavs,
                &format!(
                    "the arena has only {} start positions",
                    self.arena.uav_starts.len()
                ),
            ));
        }
        self.arena.validate().map_err(|r| err("arena", "…", &r))?;
        let u = &self.uav;
        if !(u.speed.is_finite() && u.speed > 0.0) {
            return Err(err("uav.speed", u.speed, "must be positive"));
        }
        for (name, v) in [
            ("uav.check_s", u.check_s),
            ("uav.takeoff_s", u.takeoff_s),
            ("uav.land_s", u.land_s),
            ("uav.detect_s", u.detect_s),
            ("uav.above_s", u.above_s),
            ("uav.zone_transit_s", u.zone_transit_s),
            ("faults.latency", self.faults.latency),
            ("faults.uav_hazard", self.faults.uav_hazard),
        ] {
            if !(v.is_finite() && v >= 0.0) {
                return Err(err(name, v, "must be a number ≥ 0"));
            }
        }
        let c = &self.coord;
        for (name, v) in [
            ("coord.heartbeat_s", c.heartbeat_s),
            ("coord.heartbeat_timeout_s", c.heartbeat_timeout_s),
        ] {
            if !(MIN_HEARTBEAT_S..=MAX_MISSION_TIME_S).contains(&v) {
                return Err(err(
                    name,
                    v,
                    "must be between 0.1 s and 1e6 s (a shorter heartbeat floods the simulation)",
                ));
            }
        }
        if let Some(s) = c.slot_s {
            if !(s.is_finite() && s > 0.0) {
                return Err(err("coord.slot_s", s, "must be positive"));
            }
        }
        let f = &self.faults;
        for (name, p) in [
            ("faults.grasp_fail", f.grasp_fail),
            ("faults.detect_fail", f.detect_fail),
            ("faults.msg_loss", f.msg_loss),
        ] {
            if !(0.0..=1.0).contains(&p) {
                return Err(err(name, p, "must be a probability in [0, 1]"));
            }
        }
        if f.grasp_fail >= 1.0 || f.detect_fail >= 1.0 {
            return Err(err(
                "faults",
                "1",
                "a grasp or detection that always fails can never build the wall",
            ));
        }
        for w in &f.blackout {
            if !(w.from.is_finite() && w.to.is_finite() && 0.0 <= w.from && w.from < w.to) {
                return Err(err(
                    "faults.blackout",
                    format!("{}-{}", w.from, w.to),
                    "expected 0 ≤ A < B",
                ));
            }
        }
        for fail in &f.uav_fail {
            if fail.uav >= self.uavs {
                return Err(err(
                    "faults.uav_fail",
                    format!("{}@{}", fail.uav, fail.at),
                    &format!("there are only {} UAVs (0-based)", self.uavs),
                ));
            }
            if !(fail.at.is_finite() && fail.at >= 0.0) {
                return Err(err(
                    "faults.uav_fail",
                    format!("{}@{}", fail.uav, fail.at),
                    "the time must be ≥ 0",
                ));
            }
        }
        if !(self.max_time_s > 0.0 && self.max_time_s <= MAX_MISSION_TIME_S) {
            return Err(err(
                "max_time_s",
                self.max_time_s,
                "must be positive and at most 1e6 s (MAX_MISSION_TIME_S, about 11.6 days)",
            ));
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn failures_and_windows_read_as_tables_or_as_text() {
        let f: Faults = serde_json::from_str(
            r#"{"uav_fail": [{"uav": 1, "at": 10.0}, "2@30"], "blackout": ["100-160", {"from": 5.0, "to": 6.0}]}"#,
        )
        .unwrap();
        assert_eq!(f.uav_fail[1], UavFailure { uav: 2, at: 30.0 });
        assert_eq!(
            f.blackout[0],
            Window {
                from: 100.0,
                to: 160.0
            }
        );
        assert_eq!(f.blackout[1], Window { from: 5.0, to: 6.0 });
    }

    #[test]
    fn a_bad_entry_names_the_accepted_forms() {
        let e = serde_json::from_str::<Faults>(r#"{"uav_fail": [7]}"#)
            .unwrap_err()
            .to_string();
        assert!(e.contains("{uav = U, at = T} or \"U@T\""), "{e}");
        let e = serde_json::from_str::<Faults>(r#"{"uav_fail": ["1-10"]}"#)
            .unwrap_err()
            .to_string();
        assert!(e.contains("`1-10`: expected U@T"), "{e}");
        let e = serde_json::from_str::<Faults>(r#"{"blackout": ["9-3"]}"#)
            .unwrap_err()
            .to_string();
        assert!(e.contains("ends before it starts"), "{e}");
        let long = format!(r#"{{"blackout": ["{}"]}}"#, "9".repeat(500));
        let e = serde_json::from_str::<Faults>(&long)
            .unwrap_err()
            .to_string();
        assert!(e.contains("(500 characters)"), "{e}");
    }

    #[test]
    fn text_forms_parse_once() {
        assert_eq!(
            "1@300".parse::<UavFailure>().unwrap(),
            UavFailure { uav: 1, at: 300.0 }
        );
        for bad in ["1", "x@3", "1@-3", "1@nan", "-1@3"] {
            assert!(bad.parse::<UavFailure>().is_err(), "{bad}");
        }
        for bad in ["100", "125-100", "a-b", "-5-10", "10-inf", "5-5"] {
            assert!(bad.parse::<Window>().is_err(), "{bad}");
        }
    }
}
