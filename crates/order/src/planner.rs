//! Choosing a planner by name: `brute`, `greedy`, `improved:n,k`, `exact`.

use crate::outcome::{Budget, Outcome};
use crate::problem::BuildProblem;
use crate::{brute, exact, greedy, improved};
use std::fmt;
use std::str::FromStr;
use thiserror::Error;

/// A planner and its parameters.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum PlannerSpec {
    /// Exhaustive enumeration.
    Brute,
    /// Cheapest available brick first.
    Greedy,
    /// The thesis's improved greedy.
    Improved {
        /// Greedy while the lowest available level is ≤ n.
        n: u32,
        /// Branching factor above that.
        k: u32,
    },
    /// Provably optimal dynamic programming.
    Exact,
}

/// A planner name that does not parse.
#[derive(Clone, Debug, PartialEq, Eq, Error)]
#[error("unknown planner `{0}`: expected brute, greedy, improved:N,K (e.g. improved:1,4) or exact")]
pub struct PlannerParseError(pub String);

impl FromStr for PlannerSpec {
    type Err = PlannerParseError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let err = || PlannerParseError(s.to_string());
        match s {
            "brute" => Ok(PlannerSpec::Brute),
            "greedy" => Ok(PlannerSpec::Greedy),
            "exact" => Ok(PlannerSpec::Exact),
            "improved" => Ok(PlannerSpec::Improved { n: 1, k: 4 }),
            _ => {
                let args = s.strip_prefix("improved:").ok_or_else(err)?;
                let (n, k) = args.split_once(',').ok_or_else(err)?;
                let n = n.trim().parse().map_err(|_| err())?;
                let k: u32 = k.trim().parse().map_err(|_| err())?;
                if k == 0 {
                    return Err(err());
                }
                Ok(PlannerSpec::Improved { n, k })
            }
        }
    }
}

impl fmt::Display for PlannerSpec {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            PlannerSpec::Brute => f.write_str("brute"),
            PlannerSpec::Greedy => f.write_str("greedy"),
            PlannerSpec::Improved { n, k } => write!(f, "improved:{n},{k}"),
            PlannerSpec::Exact => f.write_str("exact"),
        }
    }
}

impl PlannerSpec {
    /// Runs this planner.
    pub fn plan(&self, problem: &BuildProblem<'_>, budget: &Budget) -> Outcome {
        match *self {
            PlannerSpec::Brute => brute::plan(problem, budget),
            PlannerSpec::Greedy => greedy::plan(problem, budget),
            PlannerSpec::Improved { n, k } => improved::plan(problem, n, k, budget),
            PlannerSpec::Exact => exact::plan(problem, budget),
        }
    }
}
