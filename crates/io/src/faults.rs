//! Fault settings and mission files: the one parser of `U@T` and of `A-B`, the fault flags and
//! `--faults F.toml` ([`FaultSpec`]), and mission TOML files ([`read_mission`]).

use crate::error::{InputError, InputResult};
use crate::files::read_toml;
use mason_mission::{Faults, MissionConfig, UavFailure, Window};
use serde::Deserialize;
use std::path::Path;

/// Parses `A-B`: a window of mission seconds, 0 ≤ A < B ([`Window`]'s one parser). Errors
/// name `flag` and the value.
pub fn parse_window(flag: &str, s: &str) -> InputResult<Window> {
    s.parse()
        .map_err(|why| InputError::bad(format!("{flag} `{s}`: {why}")))
}

/// Parses `U@T`: UAV U (0-based) at mission time T ≥ 0 s ([`UavFailure`]'s one parser).
/// Errors name `flag` and the value. Whether U is in the team is the caller's check
/// ([`check_uav`]).
pub fn parse_at(flag: &str, s: &str) -> InputResult<(usize, f64)> {
    let f: UavFailure = s
        .parse()
        .map_err(|why| InputError::bad(format!("{flag} `{s}`: {why}")))?;
    Ok((f.uav, f.at))
}

/// Checks that UAV `uav` of the value `s` given to `flag` is in a team of `uavs`.
pub fn check_uav(flag: &str, s: &str, uav: usize, uavs: usize) -> InputResult<()> {
    if uav < uavs {
        return Ok(());
    }
    Err(InputError::bad(format!(
        "{flag} `{s}`: UAV {uav} is not in a team of {uavs} (0..{})",
        uavs.saturating_sub(1)
    )))
}

/// Fault options as written on the command line or in `--faults F.toml`.
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FaultSpec {
    /// Probability per grasp attempt.
    pub grasp_fail: Option<f64>,
    /// Probability per detection attempt.
    pub detect_fail: Option<f64>,
    /// `U@T` entries (a file may also write `{uav = U, at = T}`).
    #[serde(default, deserialize_with = "uav_fails")]
    pub uav_fail: Vec<String>,
    /// Failures per hour.
    pub uav_hazard: Option<f64>,
    /// `A-B` entries (a file may also write `{from = A, to = B}`).
    #[serde(default, deserialize_with = "blackouts")]
    pub blackout: Vec<String>,
    /// Probability per message.
    pub msg_loss: Option<f64>,
    /// Seconds.
    pub latency: Option<f64>,
}

/// A file's list `key` of `T` in either of its forms, table or text (a bad entry gets `T`'s
/// message, which names both forms, after the key), kept as the text that the flags give.
fn entries<'de, D, T>(d: D, key: &str) -> Result<Vec<String>, D::Error>
where
    D: serde::Deserializer<'de>,
    T: Deserialize<'de> + std::fmt::Display,
{
    use serde::de::Error;
    let v: Vec<T> = Vec::deserialize(d).map_err(|e| D::Error::custom(format!("{key}: {e}")))?;
    Ok(v.iter().map(T::to_string).collect())
}

fn uav_fails<'de, D: serde::Deserializer<'de>>(d: D) -> Result<Vec<String>, D::Error> {
    entries::<D, UavFailure>(d, "uav_fail")
}

fn blackouts<'de, D: serde::Deserializer<'de>>(d: D) -> Result<Vec<String>, D::Error> {
    entries::<D, Window>(d, "blackout")
}

impl FaultSpec {
    /// Reads a faults TOML file and checks its values on their own, for a team of `uavs`
    /// (errors name the file, and the line or the key).
    pub fn read_checked(path: &Path, uavs: usize) -> InputResult<FaultSpec> {
        let spec: FaultSpec = read_toml(path)?;
        let in_file = |e: InputError| {
            let msg = e
                .to_string()
                .replace("--uav-fail", "uav_fail")
                .replace("--blackout", "blackout");
            InputError::bad(format!("{}: {msg}", path.display()))
        };
        let faults = spec.resolve().map_err(in_file)?;
        let config = MissionConfig {
            uavs,
            faults,
            ..MissionConfig::default()
        };
        if uavs >= 1 && uavs <= config.arena.uav_starts.len() {
            config
                .validate()
                .map_err(|e| InputError::bad(format!("{}: {e}", path.display())))?;
        }
        Ok(spec)
    }

    /// Whether any fault is set.
    pub fn is_empty(&self) -> bool {
        self.grasp_fail.is_none()
            && self.detect_fail.is_none()
            && self.uav_fail.is_empty()
            && self.uav_hazard.is_none()
            && self.blackout.is_empty()
            && self.msg_loss.is_none()
            && self.latency.is_none()
    }

    /// The file's settings with the command line's on top (lists are joined).
    pub fn merged(mut self, cli: FaultSpec) -> FaultSpec {
        self.grasp_fail = cli.grasp_fail.or(self.grasp_fail);
        self.detect_fail = cli.detect_fail.or(self.detect_fail);
        self.uav_hazard = cli.uav_hazard.or(self.uav_hazard);
        self.msg_loss = cli.msg_loss.or(self.msg_loss);
        self.latency = cli.latency.or(self.latency);
        self.uav_fail.extend(cli.uav_fail);
        self.blackout.extend(cli.blackout);
        self
    }

    /// The faults, with `U@T` and `A-B` parsed (the team's size and the values' ranges are
    /// checked by [`MissionConfig::validate`]).
    pub fn resolve(&self) -> InputResult<Faults> {
        let mut f = Faults {
            grasp_fail: self.grasp_fail.unwrap_or(0.0),
            detect_fail: self.detect_fail.unwrap_or(0.0),
            uav_hazard: self.uav_hazard.unwrap_or(0.0),
            msg_loss: self.msg_loss.unwrap_or(0.0),
            latency: self.latency.unwrap_or(0.0),
            ..Faults::default()
        };
        for s in &self.uav_fail {
            let (uav, at) = parse_at("--uav-fail", s)?;
            f.uav_fail.push(UavFailure { uav, at });
        }
        for s in &self.blackout {
            f.blackout.push(parse_window("--blackout", s)?);
        }
        Ok(f)
    }
}

/// Reads a mission TOML file and checks it for a team of `uavs` (errors name the file, and the
/// line or the key). The file's own `uavs` is kept in the result.
pub fn read_mission(path: &Path, uavs: usize) -> InputResult<MissionConfig> {
    let mut config: MissionConfig = read_toml(path)?;
    let file_uavs = config.uavs;
    config.uavs = uavs;
    if uavs >= 1 && uavs <= config.arena.uav_starts.len() {
        config
            .validate()
            .map_err(|e| InputError::bad(format!("{}: {e}", path.display())))?;
    }
    config.uavs = file_uavs;
    Ok(config)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_faults_file_takes_both_forms_and_a_bad_entry_names_them() {
        let p = Path::new("f.toml");
        let spec: FaultSpec = crate::files::parse_toml(
            "uav_fail = [\"1@10\", { uav = 2, at = 30.5 }]\nblackout = [{ from = 5, to = 6.25 }, \"7-8\"]\n",
            p,
        )
        .unwrap();
        let f = spec.resolve().unwrap();
        assert_eq!(f.uav_fail[1], UavFailure { uav: 2, at: 30.5 });
        assert_eq!(
            f.blackout[0],
            Window {
                from: 5.0,
                to: 6.25
            }
        );
        assert_eq!(f.blackout[1], Window { from: 7.0, to: 8.0 });
        for (text, needle) in [
            ("uav_fail = [5]", "{uav = U, at = T} or \"U@T\""),
            ("uav_fail = [{ uav = 1 }]", "{uav = U, at = T} or \"U@T\""),
            ("blackout = [3]", "{from = A, to = B} or \"A-B\""),
            ("uav_fail = [\"x\"]", "uav_fail: `x`: expected U@T"),
        ] {
            let e = crate::files::parse_toml::<FaultSpec>(text, p)
                .unwrap_err()
                .to_string();
            assert!(e.contains(needle) && e.starts_with("f.toml"), "{text}: {e}");
        }
    }

    #[test]
    fn windows_are_parsed_once_for_every_flag() {
        assert_eq!(
            parse_window("--cut", "100-125").unwrap(),
            Window {
                from: 100.0,
                to: 125.0
            }
        );
        for bad in ["100", "125-100", "a-b", "-5-10", "10-inf", "5-5", ""] {
            let e = parse_window("--blackout", bad).unwrap_err().to_string();
            assert!(e.starts_with(&format!("--blackout `{bad}`")), "{e}");
        }
    }

    #[test]
    fn times_at_are_parsed_once_for_every_flag() {
        assert_eq!(parse_at("--kill", "1@300").unwrap(), (1, 300.0));
        assert_eq!(parse_at("--kill", " 2 @ 0 ").unwrap(), (2, 0.0));
        for bad in ["1", "x@3", "1@-3", "1@nan", "-1@3", "@"] {
            let e = parse_at("--uav-fail", bad).unwrap_err().to_string();
            assert!(e.starts_with(&format!("--uav-fail `{bad}`")), "{e}");
        }
        assert!(check_uav("--kill", "3@300", 3, 3).is_err());
        assert!(check_uav("--kill", "2@300", 2, 3).is_ok());
    }

    #[test]
    fn flags_override_the_file_and_lists_are_joined() {
        let file = FaultSpec {
            grasp_fail: Some(0.1),
            uav_fail: vec!["0@10".into()],
            ..FaultSpec::default()
        };
        let cli = FaultSpec {
            grasp_fail: Some(0.2),
            uav_fail: vec!["1@20".into()],
            ..FaultSpec::default()
        };
        let f = file.merged(cli).resolve().unwrap();
        assert_eq!(f.grasp_fail, 0.2);
        assert_eq!(f.uav_fail.len(), 2);
        assert!(FaultSpec::default().is_empty());
    }
}
