//! The thesis cost model (Petrić 2019, ch. 3; DESIGN §4).
//!
//! `c_b = (1 + e^(−α·l_b)) · (n_g·t_g(type) + t_f(type) + κ_k·t_d(type))`, where `k ∈ {0,1,2}`
//! is the number of the brick's neighbours already placed (capped at 2).

use mason_wall::BrickType;
use serde::{Deserialize, Serialize};
use thiserror::Error;

/// Grasp, flight and drop times of one brick type (s).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TypeTimes {
    /// `t_g`: one grasp attempt.
    pub grasp: f64,
    /// `t_f`: the flight from the pile to the wall.
    pub fly: f64,
    /// `t_d`: the drop (placement), scaled by κ.
    pub drop: f64,
}

/// Every parameter of the thesis cost model. Loadable from TOML; missing keys keep defaults,
/// also inside a colour's table (`[red]` with only `grasp = 10` keeps red's other times).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(from = "ModelFile")]
pub struct CostModel {
    /// α, the level discount rate.
    pub alpha: f64,
    /// `n_g`, grasp attempts per brick (may be fractional: an expected count).
    pub grasp_attempts: f64,
    /// κ₀, κ₁, κ₂: drop-time factors for 0, 1 and 2 placed neighbours.
    pub kappa: [f64; 3],
    /// Red brick times.
    pub red: TypeTimes,
    /// Green brick times.
    pub green: TypeTimes,
    /// Blue brick times.
    pub blue: TypeTimes,
    /// Orange brick times (our default; the thesis has no orange).
    pub orange: TypeTimes,
}

/// A colour's table as written in TOML: any key may be left out.
#[derive(Clone, Copy, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct TimesFile {
    grasp: Option<f64>,
    fly: Option<f64>,
    drop: Option<f64>,
}

impl TimesFile {
    fn over(self, d: TypeTimes) -> TypeTimes {
        TypeTimes {
            grasp: self.grasp.unwrap_or(d.grasp),
            fly: self.fly.unwrap_or(d.fly),
            drop: self.drop.unwrap_or(d.drop),
        }
    }
}

/// The cost model as written in TOML: every key optional, defaults for the rest.
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct ModelFile {
    alpha: Option<f64>,
    grasp_attempts: Option<f64>,
    kappa: Option<[f64; 3]>,
    #[serde(default)]
    red: TimesFile,
    #[serde(default)]
    green: TimesFile,
    #[serde(default)]
    blue: TimesFile,
    #[serde(default)]
    orange: TimesFile,
}

impl From<ModelFile> for CostModel {
    fn from(f: ModelFile) -> Self {
        let d = CostModel::default();
        CostModel {
            alpha: f.alpha.unwrap_or(d.alpha),
            grasp_attempts: f.grasp_attempts.unwrap_or(d.grasp_attempts),
            kappa: f.kappa.unwrap_or(d.kappa),
            red: f.red.over(d.red),
            green: f.green.over(d.green),
            blue: f.blue.over(d.blue),
            orange: f.orange.over(d.orange),
        }
    }
}

/// The largest time (s) and factor the model accepts, so that every cost stays finite.
pub const MAX_MODEL_VALUE: f64 = 1e6;

impl Default for CostModel {
    fn default() -> Self {
        let t = |grasp, fly, drop| TypeTimes { grasp, fly, drop };
        CostModel {
            alpha: 0.1,
            grasp_attempts: 1.0,
            kappa: [1.0, 1.25, 1.5],
            red: t(14.0, 22.5, 8.0),
            green: t(26.0, 18.5, 9.0),
            blue: t(16.0, 22.5, 15.0),
            orange: t(30.0, 25.0, 20.0),
        }
    }
}

/// A parameter out of range.
#[derive(Clone, Debug, PartialEq, Error)]
#[error("cost model: `{field}` = {} is invalid: {reason}", short(*.value))]
pub struct ModelError {
    /// The parameter.
    pub field: String,
    /// Its value.
    pub value: f64,
    /// The rule it breaks.
    pub reason: &'static str,
}

/// `v` as written, or in scientific notation when that is long.
fn short(v: f64) -> String {
    let plain = v.to_string();
    if plain.len() > 16 {
        format!("{v:e}")
    } else {
        plain
    }
}

impl CostModel {
    /// The times of one brick type.
    pub fn times(&self, kind: BrickType) -> &TypeTimes {
        match kind {
            BrickType::Red => &self.red,
            BrickType::Green => &self.green,
            BrickType::Blue => &self.blue,
            BrickType::Orange => &self.orange,
        }
    }

    /// The level factor `1 + e^(−α·l)`.
    pub fn level_factor(&self, level: u32) -> f64 {
        1.0 + (-self.alpha * f64::from(level)).exp()
    }

    /// Checks every parameter: all finite and at most [`MAX_MODEL_VALUE`], times and κ
    /// non-negative, `n_g ≥ 1`, `α ≥ 0`.
    pub fn validate(&self) -> Result<(), ModelError> {
        let err = |field: &str, value: f64, reason| {
            Err(ModelError {
                field: field.to_string(),
                value,
                reason,
            })
        };
        let within = |v: f64, low: f64| (low..=MAX_MODEL_VALUE).contains(&v);
        if !within(self.alpha, 0.0) {
            return err("alpha", self.alpha, "must be a number in [0, 1e6]");
        }
        if !within(self.grasp_attempts, 1.0) {
            return err(
                "grasp_attempts",
                self.grasp_attempts,
                "must be a number in [1, 1e6]",
            );
        }
        for (i, &k) in self.kappa.iter().enumerate() {
            if !within(k, 0.0) {
                return err(&format!("kappa[{i}]"), k, "must be a number in [0, 1e6]");
            }
        }
        for kind in BrickType::ALL {
            let t = self.times(kind);
            for (name, v) in [("grasp", t.grasp), ("fly", t.fly), ("drop", t.drop)] {
                if !within(v, 0.0) {
                    return err(
                        &format!("{}.{name}", kind.name()),
                        v,
                        "must be a number of seconds in [0, 1e6]",
                    );
                }
            }
        }
        Ok(())
    }
}
