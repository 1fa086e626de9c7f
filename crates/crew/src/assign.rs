//! Giving each robot a goal (DESIGN §6): `given`, `perm`, `hungarian` and `path`.

use crate::distance::path_lengths;
use crate::hungarian::hungarian;
use crate::instance::Instance;
use crate::moves::goal_distances;
use crate::perm::{permutation_assignment, PERM_LIMIT};
use crate::tswap::bottleneck_assignment;
use thiserror::Error;

/// How robots get their goals.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AssignMethod {
    /// Keep the scenario's pairing (labelled MAPF).
    Given,
    /// The paper's n! enumeration, least sum of Euclidean distances.
    Perm,
    /// Hungarian method, least sum of Euclidean distances.
    Hungarian,
    /// Hungarian method on true shortest-path lengths.
    Path,
    /// Assignment and paths solved together for interchangeable robots (TSWAP,
    /// [`crate::tswap`]); on its own, the greedy step-distance assignment TSWAP starts from.
    Joint,
}

impl std::str::FromStr for AssignMethod {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        Ok(match s {
            "given" => AssignMethod::Given,
            "perm" => AssignMethod::Perm,
            "hungarian" => AssignMethod::Hungarian,
            "path" => AssignMethod::Path,
            "joint" => AssignMethod::Joint,
            _ => {
                return Err(format!(
                    "unknown assignment `{s}` (given, perm, hungarian, path, joint)"
                ))
            }
        })
    }
}

/// Why an assignment method cannot be used on an instance.
#[derive(Clone, Debug, PartialEq, Eq, Error)]
pub enum AssignError {
    /// `perm` with too many robots.
    #[error("perm tries all n! assignments and accepts at most {limit} robots, not {robots}; use --assign hungarian (same objective, O(n³))")]
    TooManyForPerm {
        /// Robots in the instance.
        robots: usize,
        /// The limit.
        limit: usize,
    },
    /// `given` without a pairing in the input.
    #[error(
        "--assign given needs the pairing of a scenario file; this input has none (use hungarian)"
    )]
    NoPairing,
}

/// Cost standing in for "unreachable" in `path` assignment, so that the Hungarian method stays
/// finite; such a pairing is only chosen when no complete reachable one exists.
const UNREACHABLE_COST: f64 = 1e12;

/// The goal index of each robot.
pub fn assign(inst: &Instance, method: AssignMethod) -> Result<Vec<usize>, AssignError> {
    let n = inst.robot_count();
    let euclid = || -> Vec<Vec<f64>> {
        inst.robots
            .iter()
            .map(|&r| {
                inst.goals
                    .iter()
                    .map(|&g| inst.grid.euclidean(r, g))
                    .collect()
            })
            .collect()
    };
    Ok(match method {
        AssignMethod::Given => inst.pairing.clone().ok_or(AssignError::NoPairing)?,
        AssignMethod::Perm => {
            if n > PERM_LIMIT {
                return Err(AssignError::TooManyForPerm {
                    robots: n,
                    limit: PERM_LIMIT,
                });
            }
            permutation_assignment(&euclid())
        }
        AssignMethod::Hungarian => hungarian(&euclid()),
        AssignMethod::Path => {
            let cost: Vec<Vec<f64>> = inst
                .robots
                .iter()
                .map(|&r| {
                    let d = path_lengths(&inst.grid, inst.connectivity, r);
                    inst.goals
                        .iter()
                        .map(|g| d[g.0 as usize].min(UNREACHABLE_COST))
                        .collect()
                })
                .collect();
            hungarian(&cost)
        }
        AssignMethod::Joint => {
            let dist = goal_distances(&inst.grid, inst.connectivity, &inst.goals);
            let starts: Vec<u32> = inst.robots.iter().map(|c| c.0).collect();
            let greedy = bottleneck_assignment(&dist, &starts);
            let mut free: Vec<usize> = {
                let mut used = vec![false; inst.goals.len()];
                greedy.iter().flatten().for_each(|&g| used[g] = true);
                (0..inst.goals.len()).filter(|&g| !used[g]).collect()
            };
            free.reverse();
            greedy
                .into_iter()
                .map(|g| g.unwrap_or_else(|| free.pop().expect("n ≤ m goals")))
                .collect()
        }
    })
}
