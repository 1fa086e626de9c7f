//! The team time model of DESIGN §4.1: per brick type the placing phase, the rest of the
//! cycle, the UAVs it needs and its reward; the concurrency rule. Two built-ins (`thesis`,
//! `cmcp`) and a TOML patch that starts from either and may set every parameter.

use crate::model::CostModel;
use mason_wall::BrickType;
use serde::{Deserialize, Serialize};
use thiserror::Error;

/// Times, team size and reward of one brick type.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TypeSchedule {
    /// The placing phase (s): the brick occupies the wall; it counts as placed at its end.
    pub place_s: f64,
    /// The rest of the UAV's cycle (s): back to the pile, grasp, fly to the wall.
    pub cycle_rest_s: f64,
    /// UAVs that carry one brick together (they start together).
    pub uavs: u32,
    /// Reward for placing one brick.
    pub reward: f64,
}

impl TypeSchedule {
    /// `place_s + cycle_rest_s`: the shortest gap between a UAV's starts.
    pub fn cycle_s(&self) -> f64 {
        self.place_s + self.cycle_rest_s
    }
}

/// How the distance rule measures the distance between two brick centres.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Metric {
    /// In the horizontal plane (x, y), as CMCP's exact model (its MILP) does: a UAV hovers
    /// above the brick it places, so a height difference does not keep two UAVs apart.
    #[default]
    Xy,
    /// In 3-D, the centres at their layers' mid-heights (closer to CMCP's GRASP).
    Xyz,
}

impl Metric {
    /// `xy` or `xyz`.
    pub fn name(self) -> &'static str {
        match self {
            Metric::Xy => "xy",
            Metric::Xyz => "xyz",
        }
    }

    /// The metric named `s` (`xy` or `xyz`).
    pub fn parse(s: &str) -> Option<Metric> {
        match s {
            "xy" => Some(Metric::Xy),
            "xyz" => Some(Metric::Xyz),
            _ => None,
        }
    }

    /// The squared distance between two centres under this metric.
    pub fn distance2(self, a: [f64; 3], b: [f64; 3]) -> f64 {
        let axes = match self {
            Metric::Xy => 2,
            Metric::Xyz => 3,
        };
        (0..axes).map(|k| (a[k] - b[k]).powi(2)).sum()
    }
}

impl std::fmt::Display for Metric {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// Which bricks may be in their placing phase at the same time.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(rename_all = "lowercase", tag = "rule")]
pub enum Concurrency {
    /// At most one brick (one UAV, or an orange pair) places at any time: the thesis's zone.
    Zone,
    /// Two bricks whose centres are closer than `distance_m` never place at overlapping times
    /// (CMCP). A centre is the footprint's middle at the layer's mid-height; `metric` says
    /// whether the height counts.
    Distance {
        /// The distance (m).
        distance_m: f64,
        /// `xy` (the default) or `xyz`.
        metric: Metric,
    },
}

impl Concurrency {
    /// The distance rule's metric (`None` under the zone rule).
    pub fn metric(&self) -> Option<Metric> {
        match *self {
            Concurrency::Zone => None,
            Concurrency::Distance { metric, .. } => Some(metric),
        }
    }
}

/// Every parameter of a team schedule problem apart from the wall, the team and the budget.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TeamModel {
    /// `thesis`, `cmcp`, or the file it was read from.
    pub name: String,
    /// Per type, in the order red, green, blue, orange.
    pub types: [TypeSchedule; 4],
    /// The concurrency rule.
    pub concurrency: Concurrency,
}

/// The longest placing phase or rest a model may set (s).
pub const MAX_SECONDS: f64 = 1e7;
/// The shortest placing phase accepted (s): a thousand times the validator's time tolerance
/// ([`super::TIME_EPS`]), so that no two placements can hide inside it.
pub const MIN_PLACE_S: f64 = 1e-3;
/// The largest reward a model may set.
pub const MAX_REWARD: f64 = 1e9;
/// The largest concurrency distance (m): beyond it the conflict lists grow with the square of
/// the wall, and the zone rule says the same thing.
pub const MAX_DISTANCE_M: f64 = 10.0;

/// Flying into and out of the wall zone (s) in the simulator's UAV model, duplicated here because `order` sits
/// below `mission`; a mission test checks the two agree.
pub const THESIS_ZONE_TRANSIT_S: f64 = 2.0;
/// Detection plus descent above the brick (s), as in the simulator's defaults.
pub const THESIS_PICK_OVERHEAD_S: f64 = 3.0;

impl TeamModel {
    /// The thesis model: the simulator's default-arena timings, zone rule.
    ///
    /// Placing is the zone time `zone_transit + κ₁·t_d` (a brick usually finds one neighbour
    /// placed); the rest of the cycle is the flight back to the pile, detection and descent,
    /// one grasp, and the flight to the wall: `2·t_f + 3 + n_g·t_g`. Rewards are 1/2/4/6.
    pub fn thesis() -> TeamModel {
        Self::from_cost_model(&CostModel::default())
    }

    /// The thesis model for a given cost model's times.
    pub fn from_cost_model(cost: &CostModel) -> TeamModel {
        let types = BrickType::ALL.map(|k| {
            let t = cost.times(k);
            TypeSchedule {
                place_s: THESIS_ZONE_TRANSIT_S + cost.kappa[1] * t.drop,
                cycle_rest_s: 2.0 * t.fly + THESIS_PICK_OVERHEAD_S + cost.grasp_attempts * t.grasp,
                uavs: k.uavs_needed(),
                reward: k.default_reward(),
            }
        });
        TeamModel {
            name: "thesis".into(),
            types,
            concurrency: Concurrency::Zone,
        }
    }

    /// CMCP's GRASP convention: 40 s placing, 10 s return trip, 0.80 m, rewards 1/2/4/6.
    pub fn cmcp() -> TeamModel {
        let types = BrickType::ALL.map(|k| TypeSchedule {
            place_s: 40.0,
            cycle_rest_s: 10.0,
            uavs: k.uavs_needed(),
            reward: k.default_reward(),
        });
        TeamModel {
            name: "cmcp".into(),
            types,
            concurrency: Concurrency::Distance {
                distance_m: 0.80,
                metric: Metric::Xy,
            },
        }
    }

    /// The same model with the distance rule measured by `metric`; an error under the zone
    /// rule, which measures nothing.
    pub fn with_metric(mut self, metric: Metric) -> Result<TeamModel, TeamModelError> {
        match &mut self.concurrency {
            Concurrency::Distance { metric: m, .. } => {
                *m = metric;
                Ok(self)
            }
            Concurrency::Zone => Err(TeamModelError {
                field: format!("metric = \"{metric}\""),
                value: f64::NAN,
                reason: "the metric belongs to the distance rule; this model uses the zone rule (concurrency = \"zone\")",
            }),
        }
    }

    /// A built-in model by name.
    pub fn builtin(name: &str) -> Option<TeamModel> {
        match name {
            "thesis" => Some(Self::thesis()),
            "cmcp" => Some(Self::cmcp()),
            _ => None,
        }
    }

    /// The parameters of one type.
    pub fn of(&self, kind: BrickType) -> &TypeSchedule {
        &self.types[kind.index()]
    }

    /// Checks every parameter: placing in [10⁻³, 10⁷] s, rest in [0, 10⁷] s, 1–2 UAVs per brick,
    /// rewards in [0, 10⁹], a distance in [0, 10] m.
    pub fn validate(&self) -> Result<(), TeamModelError> {
        let err = |field: String, value: f64, reason| {
            Err(TeamModelError {
                field,
                value,
                reason,
            })
        };
        for kind in BrickType::ALL {
            let t = self.of(kind);
            let n = kind.name();
            if !(MIN_PLACE_S..=MAX_SECONDS).contains(&t.place_s) {
                return err(
                    format!("{n}.place_s"),
                    t.place_s,
                    "must be a number of seconds in [0.001, 10⁷] (a shorter placing phase is not a physical one)",
                );
            }
            if !(0.0..=MAX_SECONDS).contains(&t.cycle_rest_s) {
                return err(
                    format!("{n}.cycle_rest_s"),
                    t.cycle_rest_s,
                    "must be a number of seconds in [0, 10⁷]",
                );
            }
            if !(1..=2).contains(&t.uavs) {
                return err(format!("{n}.uavs"), f64::from(t.uavs), "must be 1 or 2");
            }
            if !(0.0..=MAX_REWARD).contains(&t.reward) {
                return err(
                    format!("{n}.reward"),
                    t.reward,
                    "must be a number in [0, 10⁹]",
                );
            }
        }
        if let Concurrency::Distance { distance_m, .. } = self.concurrency {
            if !(0.0..=MAX_DISTANCE_M).contains(&distance_m) {
                return err(
                    "distance_m".into(),
                    distance_m,
                    "must be a number of metres in [0, 10] (one brick at a time is concurrency = \"zone\")",
                );
            }
        }
        Ok(())
    }

    /// The model a TOML patch describes: its `base` (default `thesis`) with every key the
    /// patch sets replaced. `name` names the model in outputs.
    pub fn from_patch(patch: &TeamModelPatch, name: &str) -> Result<TeamModel, TeamModelError> {
        let base = patch.base.as_deref().unwrap_or("thesis");
        let mut m = TeamModel::builtin(base).ok_or_else(|| TeamModelError {
            field: {
                let n = base.chars().count();
                let head: String = base.chars().take(80).collect();
                if n > 80 {
                    format!("base = \"{head}…\" ({n} characters)")
                } else {
                    format!("base = \"{head}\"")
                }
            },
            value: f64::NAN,
            reason: "unknown base model: expected \"thesis\" or \"cmcp\"",
        })?;
        m.name = name.to_string();
        for (kind, p) in
            BrickType::ALL
                .into_iter()
                .zip([&patch.red, &patch.green, &patch.blue, &patch.orange])
        {
            let Some(p) = p else { continue };
            let t = &mut m.types[kind.index()];
            t.place_s = p.place_s.unwrap_or(t.place_s);
            t.cycle_rest_s = p.cycle_rest_s.unwrap_or(t.cycle_rest_s);
            t.uavs = p.uavs.unwrap_or(t.uavs);
            t.reward = p.reward.unwrap_or(t.reward);
        }
        let (distance, metric) = match m.concurrency {
            Concurrency::Distance { distance_m, metric } => (distance_m, metric),
            Concurrency::Zone => (0.80, Metric::default()),
        };
        let metric = match patch.metric.as_deref() {
            None => metric,
            Some(s) => Metric::parse(s).ok_or_else(|| TeamModelError {
                field: format!("metric = \"{}\"", s.chars().take(80).collect::<String>()),
                value: f64::NAN,
                reason: "expected \"xy\" (horizontal plane) or \"xyz\" (3-D)",
            })?,
        };
        let distance_rule = Concurrency::Distance {
            distance_m: patch.distance_m.unwrap_or(distance),
            metric,
        };
        m.concurrency =
            match patch.concurrency.as_deref() {
                None if patch.distance_m.is_some() || patch.metric.is_some() => distance_rule,
                None => m.concurrency,
                Some("zone") if patch.metric.is_some() => return Err(TeamModelError {
                    field: "concurrency = \"zone\"".into(),
                    value: f64::NAN,
                    reason:
                        "the zone rule takes no metric (it belongs to concurrency = \"distance\")",
                }),
                Some("zone") => Concurrency::Zone,
                Some("distance") => distance_rule,
                Some(other) => {
                    return Err(TeamModelError {
                        field: format!("concurrency = \"{other}\""),
                        value: f64::NAN,
                        reason: "expected \"zone\" or \"distance\"",
                    })
                }
            };
        m.validate()?;
        Ok(m)
    }
}

/// ` = value` as a person writes it (nothing for a text value, which the field shows).
fn shown_value(x: f64) -> String {
    match x {
        x if x.is_nan() => String::new(),
        x if x.abs() < 1e12 => format!(" = {x}"),
        x => format!(" = {x:e}"),
    }
}

/// A parameter out of range.
#[derive(Clone, Debug, PartialEq, Error)]
#[error("team model: `{field}`{} is invalid: {reason}", shown_value(*.value))]
pub struct TeamModelError {
    /// The parameter.
    pub field: String,
    /// Its value (NaN for a text value, which `field` shows).
    pub value: f64,
    /// The rule it breaks.
    pub reason: &'static str,
}

/// A TOML team model: a base and the keys that differ from it.
///
/// ```toml
/// base = "cmcp"            # or "thesis" (the default)
/// concurrency = "distance" # or "zone"
/// distance_m = 1.0
/// metric = "xy"            # or "xyz" (the distance rule only)
/// [orange]
/// place_s = 60
/// reward = 8
/// ```
#[derive(Clone, Debug, Default, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TeamModelPatch {
    /// `thesis` or `cmcp`.
    pub base: Option<String>,
    /// `zone` or `distance`.
    pub concurrency: Option<String>,
    /// The distance of the `distance` rule (m).
    pub distance_m: Option<f64>,
    /// The metric of the `distance` rule: `xy` (the default) or `xyz`.
    pub metric: Option<String>,
    /// Red bricks.
    pub red: Option<TypePatch>,
    /// Green bricks.
    pub green: Option<TypePatch>,
    /// Blue bricks.
    pub blue: Option<TypePatch>,
    /// Orange bricks.
    pub orange: Option<TypePatch>,
}

/// The keys of one brick type that a patch sets.
#[derive(Clone, Copy, Debug, Default, PartialEq, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct TypePatch {
    /// Placing phase (s).
    pub place_s: Option<f64>,
    /// Rest of the cycle (s).
    pub cycle_rest_s: Option<f64>,
    /// UAVs per brick.
    pub uavs: Option<u32>,
    /// Reward.
    pub reward: Option<f64>,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn builtins_validate_and_cmcp_cycles_are_50_s() {
        TeamModel::thesis().validate().unwrap();
        let c = TeamModel::cmcp();
        c.validate().unwrap();
        assert!(BrickType::ALL.iter().all(|&k| c.of(k).cycle_s() == 50.0));
        assert_eq!(c.of(BrickType::Orange).uavs, 2);
    }

    #[test]
    fn patch_overrides_only_what_it_sets() {
        let patch = TeamModelPatch {
            base: Some("cmcp".into()),
            orange: Some(TypePatch {
                reward: Some(8.0),
                ..TypePatch::default()
            }),
            ..TeamModelPatch::default()
        };
        let m = TeamModel::from_patch(&patch, "mine").unwrap();
        assert_eq!(m.of(BrickType::Orange).reward, 8.0);
        assert_eq!(m.of(BrickType::Orange).place_s, 40.0);
        assert_eq!(
            m.concurrency,
            Concurrency::Distance {
                distance_m: 0.8,
                metric: Metric::Xy
            }
        );
        let zone = TeamModelPatch {
            concurrency: Some("zone".into()),
            ..patch
        };
        assert_eq!(
            TeamModel::from_patch(&zone, "z").unwrap().concurrency,
            Concurrency::Zone
        );
    }

    #[test]
    fn the_metric_key_sets_the_distance_rule_and_nothing_else() {
        let xyz = TeamModelPatch {
            base: Some("cmcp".into()),
            metric: Some("xyz".into()),
            ..TeamModelPatch::default()
        };
        let m = TeamModel::from_patch(&xyz, "m").unwrap();
        assert_eq!(m.concurrency.metric(), Some(Metric::Xyz));
        // On the thesis base, a metric alone turns the distance rule on (as distance_m does).
        let thesis = TeamModelPatch {
            base: None,
            ..xyz.clone()
        };
        let t = TeamModel::from_patch(&thesis, "t").unwrap();
        assert_eq!(
            t.concurrency,
            Concurrency::Distance {
                distance_m: 0.8,
                metric: Metric::Xyz
            }
        );
        let bad = TeamModelPatch {
            metric: Some("3d".into()),
            ..xyz.clone()
        };
        let e = TeamModel::from_patch(&bad, "b").unwrap_err();
        assert!(e.to_string().contains("metric = \"3d\""), "{e}");
        let zone = TeamModelPatch {
            concurrency: Some("zone".into()),
            ..xyz
        };
        assert!(TeamModel::from_patch(&zone, "z").is_err());
        assert!(TeamModel::thesis().with_metric(Metric::Xy).is_err());
    }

    #[test]
    fn bad_patches_are_typed_errors() {
        let bad_base = TeamModelPatch {
            base: Some("nope".into()),
            ..Default::default()
        };
        assert!(TeamModel::from_patch(&bad_base, "x")
            .unwrap_err()
            .field
            .contains("nope"));
        let three = TeamModelPatch {
            red: Some(TypePatch {
                uavs: Some(3),
                ..Default::default()
            }),
            ..Default::default()
        };
        assert_eq!(
            TeamModel::from_patch(&three, "x").unwrap_err().field,
            "red.uavs"
        );
        let neg = TeamModelPatch {
            distance_m: Some(-1.0),
            ..Default::default()
        };
        assert_eq!(
            TeamModel::from_patch(&neg, "x").unwrap_err().field,
            "distance_m"
        );
        let far = TeamModelPatch {
            distance_m: Some(1e9),
            ..Default::default()
        };
        assert_eq!(
            TeamModel::from_patch(&far, "x").unwrap_err().field,
            "distance_m"
        );
        let rich = TeamModelPatch {
            green: Some(TypePatch {
                reward: Some(1e300),
                ..Default::default()
            }),
            ..Default::default()
        };
        assert_eq!(
            TeamModel::from_patch(&rich, "x").unwrap_err().field,
            "green.reward"
        );
        let nan = TeamModelPatch {
            orange: Some(TypePatch {
                cycle_rest_s: Some(f64::NAN),
                ..Default::default()
            }),
            ..Default::default()
        };
        assert_eq!(
            TeamModel::from_patch(&nan, "x").unwrap_err().field,
            "orange.cycle_rest_s"
        );
        let zero = TeamModelPatch {
            blue: Some(TypePatch {
                place_s: Some(0.0),
                ..Default::default()
            }),
            ..Default::default()
        };
        assert_eq!(
            TeamModel::from_patch(&zero, "x").unwrap_err().field,
            "blue.place_s"
        );
    }
}
