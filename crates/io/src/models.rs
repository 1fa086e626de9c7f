//! Cost models: the thesis's build-order cost model and the team models of schedules.

use crate::error::{InputError, InputResult};
use crate::files::read_toml;
use mason_order::schedule::{Metric, Objective, TeamModel, TeamModelPatch};
use mason_order::CostModel;
use std::path::Path;

/// Loads a cost model from TOML, or the thesis's defaults when no file is given.
pub fn load_model(path: Option<&Path>) -> InputResult<CostModel> {
    let Some(path) = path else {
        return Ok(CostModel::default());
    };
    let model: CostModel = read_toml(path)?;
    model
        .validate()
        .map_err(|e| InputError::bad(format!("{}: {e}", path.display())))?;
    Ok(model)
}

/// Loads a team model: `thesis` (the default), `cmcp`, or a TOML file patching one of them;
/// with `metric` (`--metric xy|xyz`), its distance rule measured that way.
pub fn load_team_model(spec: Option<&str>, metric: Option<&str>) -> InputResult<TeamModel> {
    let model = team_model_named(spec)?;
    match metric {
        None => Ok(model),
        Some(m) => {
            let metric = Metric::parse(m).ok_or_else(|| {
                InputError::bad(format!(
                    "--metric {}: expected xy (horizontal plane) or xyz (3-D)",
                    m.chars().take(80).collect::<String>()
                ))
            })?;
            let name = model.name.clone();
            model
                .with_metric(metric)
                .map_err(|e| InputError::bad(format!("--metric with model {name}: {e}")))
        }
    }
}

fn team_model_named(spec: Option<&str>) -> InputResult<TeamModel> {
    let spec = spec.unwrap_or("thesis");
    if let Some(m) = TeamModel::builtin(spec) {
        return Ok(m);
    }
    let path = Path::new(spec);
    if !path.exists() {
        return Err(InputError::bad(format!(
            "--model {spec}: expected thesis, cmcp or a TOML file (no such file)"
        )));
    }
    let patch: TeamModelPatch = read_toml(path)?;
    TeamModel::from_patch(&patch, spec).map_err(|e| InputError::bad(format!("{spec}: {e}")))
}

/// The schedule objective named `objective` (`makespan`, `reward` or `expected`), with the
/// failure rate `uav_hazard` (per UAV per hour) that `expected` needs and the others refuse.
pub fn objective(objective: &str, uav_hazard: Option<f64>) -> InputResult<Objective> {
    let mut o: Objective = objective
        .parse()
        .map_err(|e| InputError::bad(format!("--objective: {e}")))?;
    match (&mut o, uav_hazard) {
        (Objective::Expected { hazard_per_hour }, Some(h)) => *hazard_per_hour = h,
        (Objective::Expected { .. }, None) => {
            return Err(InputError::bad(
                "--objective expected needs --uav-hazard λ (failures per hour)",
            ))
        }
        (_, Some(_)) => return Err(InputError::bad("--uav-hazard is for --objective expected")),
        _ => {}
    }
    Ok(o)
}

/// The largest time limit accepted, in seconds (about 31 years): a larger one is refused,
/// never turned into a `Duration` that overflows. No limit is written by leaving it out.
pub const MAX_TIME_LIMIT_S: f64 = 1e9;

/// A time limit given as `name` (`--time-limit` on the command line, `time_limit` in Python):
/// a positive number of seconds up to [`MAX_TIME_LIMIT_S`].
pub fn time_limit(name: &str, limit: Option<f64>) -> InputResult<Option<f64>> {
    match limit {
        Some(v) if !(v.is_finite() && v > 0.0) => Err(InputError::bad(format!(
            "{name} {v}: expected a positive number of seconds"
        ))),
        Some(v) if v > MAX_TIME_LIMIT_S => Err(InputError::bad(format!(
            "{name} {v:e}: at most {MAX_TIME_LIMIT_S:e} s (leave {name} out for no limit)"
        ))),
        other => Ok(other),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn builtin_team_models_and_a_missing_file() {
        assert_eq!(load_team_model(None, None).unwrap().name, "thesis");
        assert_eq!(load_team_model(Some("cmcp"), None).unwrap().name, "cmcp");
        let xyz = load_team_model(Some("cmcp"), Some("xyz")).unwrap();
        assert_eq!(xyz.concurrency.metric(), Some(Metric::Xyz));
        let e = load_team_model(Some("cmcp"), Some("3d")).unwrap_err();
        assert!(e.to_string().contains("--metric 3d: expected xy"), "{e}");
        let e = load_team_model(Some("thesis"), Some("xy")).unwrap_err();
        assert!(e.to_string().contains("zone rule"), "{e}");
        let e = load_team_model(Some("/nonexistent/x.toml"), None)
            .unwrap_err()
            .to_string();
        assert!(e.contains("expected thesis, cmcp or a TOML file"), "{e}");
        assert_eq!(load_model(None).unwrap(), CostModel::default());
    }
}
