//! The team schedule problem (DESIGN §4.1) and what a planner returns.

use super::model::{Concurrency, Metric, TeamModel, TeamModelError};
use crate::outcome::Status;
use mason_wall::{Brick, BrickId, Wall, BRICK_HEIGHT};
use serde::Serialize;
use std::fmt;
use std::str::FromStr;
use std::time::Duration;
use thiserror::Error;

/// What a schedule optimises.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(rename_all = "lowercase", tag = "objective")]
pub enum Objective {
    /// The whole wall in the shortest time.
    Makespan,
    /// The most reward placed by the budget, then the shortest makespan.
    Reward,
    /// The most expected reward by the budget when each UAV fails at `hazard_per_hour`; a
    /// failed UAV's later bricks fall to the others.
    Expected {
        /// Failures per hour per UAV (exponential).
        hazard_per_hour: f64,
    },
}

impl Objective {
    /// `makespan`, `reward` or `expected`.
    pub fn name(&self) -> &'static str {
        match self {
            Objective::Makespan => "makespan",
            Objective::Reward => "reward",
            Objective::Expected { .. } => "expected",
        }
    }
}

/// An objective name that does not parse.
#[derive(Clone, Debug, PartialEq, Eq, Error)]
#[error("unknown objective `{0}`: expected makespan, reward or expected")]
pub struct ObjectiveParseError(pub String);

impl FromStr for Objective {
    type Err = ObjectiveParseError;
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "makespan" => Ok(Objective::Makespan),
            "reward" => Ok(Objective::Reward),
            "expected" => Ok(Objective::Expected {
                hazard_per_hour: 0.0,
            }),
            _ => Err(ObjectiveParseError(s.to_string())),
        }
    }
}

impl fmt::Display for Objective {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// A number as written by a person: plain when short, scientific when huge.
fn short(x: f64) -> String {
    if x.is_finite() && x.abs() < 1e12 {
        format!("{x}")
    } else {
        format!("{x:e}")
    }
}

/// A problem that cannot be posed.
#[derive(Clone, Debug, PartialEq, Error)]
pub enum TeamProblemError {
    /// The model is invalid.
    #[error(transparent)]
    Model(#[from] TeamModelError),
    /// No UAV, or fewer than a brick needs.
    #[error("a team of {uavs} UAV(s) cannot place {kind} bricks, which need {needed} each")]
    TeamTooSmall {
        /// The team.
        uavs: usize,
        /// The brick type.
        kind: mason_wall::BrickType,
        /// UAVs it needs.
        needed: u32,
    },
    /// More UAVs than the planners take.
    #[error("a team of {0} UAVs is more than the {max} the planners take", max = MAX_UAVS)]
    TeamTooLarge(usize),
    /// The budget is not a positive number.
    #[error("budget {} s: expected a number of seconds in (0, 10⁹]", short(*.0))]
    Budget(f64),
    /// `makespan` plans the whole wall: a budget would leave bricks out.
    #[error(
        "objective `makespan` plans the whole wall; a budget belongs to `reward` or `expected`"
    )]
    BudgetWithMakespan,
    /// `reward` and `expected` need a budget.
    #[error("objective `{0}` needs a budget (--budget T)")]
    NeedsBudget(&'static str),
    /// A start state that does not fit the problem.
    #[error("start state: {0}")]
    Start(String),
    /// The hazard rate is not a finite number ≥ 0.
    #[error("UAV hazard {0} per hour: expected a finite number ≥ 0")]
    Hazard(f64),
    /// The distance rule relates too many pairs of bricks for the planners.
    #[error(
        "the distance rule ({} m) puts more than {MAX_CONFLICT_PAIRS} pairs of bricks in conflict (mason_order::schedule::MAX_CONFLICT_PAIRS); use a smaller distance or the zone rule",
        short(*distance_m)
    )]
    TooManyConflicts {
        /// The rule's distance (m).
        distance_m: f64,
    },
}

/// The most pairs of bricks the distance rule may put in conflict: each pair is checked in
/// every decode, so more would make one schedule take minutes.
pub const MAX_CONFLICT_PAIRS: u64 = 2_000_000;

/// The most UAVs a team may have (the planners keep per-UAV state in small arrays).
pub const MAX_UAVS: usize = 1024;

/// A wall, a team of `uavs`, a [`TeamModel`], an optional budget and an objective, with the
/// per-brick terms precomputed.
#[derive(Clone, Debug)]
pub struct TeamProblem<'w> {
    wall: &'w Wall,
    model: TeamModel,
    uavs: usize,
    budget_s: Option<f64>,
    objective: Objective,
    /// Per brick: placing time, rest of cycle, UAVs, reward.
    place: Vec<f64>,
    rest: Vec<f64>,
    need: Vec<u32>,
    reward: Vec<f64>,
    /// Distance rule: for every brick, the bricks closer than D (sorted).
    conflicts: Vec<Vec<BrickId>>,
    start: Option<TeamStart>,
}

/// Where a team stands when it plans again (times relative to now): the bricks already on
/// the wall, the bricks on their way with their crews and earliest starts (they keep their
/// crews and start as early as the rules allow from then on), and when each UAV could start
/// a new brick (∞: the UAV is gone).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct TeamStart {
    /// Bricks on the wall.
    pub placed: Vec<BrickId>,
    /// Bricks on their way: crew and the earliest start of the placing phase (< 0 for a brick
    /// placing now). Every support of each must be placed or on its way.
    pub committed: Vec<Placement>,
    /// Per UAV: the earliest start of a new brick, if it carries none (s from now; ∞: gone).
    pub uav_ready_s: Vec<f64>,
}

/// The 3-D centre of a brick (m): footprint middle, layer mid-height.
pub fn brick_centre(b: &Brick) -> [f64; 3] {
    let f = &b.footprint;
    [
        (f.x0 + f.x1) / 2.0,
        (f.y0 + f.y1) / 2.0,
        (f64::from(b.level) - 0.5) * BRICK_HEIGHT,
    ]
}

fn distance_conflicts(
    wall: &Wall,
    d: f64,
    metric: Metric,
) -> Result<Vec<Vec<BrickId>>, TeamProblemError> {
    let n = wall.len();
    let centres: Vec<[f64; 3]> = wall.bricks().iter().map(brick_centre).collect();
    let mut by_x: Vec<usize> = (0..n).collect();
    by_x.sort_by(|&a, &b| centres[a][0].total_cmp(&centres[b][0]).then(a.cmp(&b)));
    let mut out = vec![Vec::new(); n];
    let mut pairs = 0u64;
    for (k, &i) in by_x.iter().enumerate() {
        for &j in &by_x[k + 1..] {
            if centres[j][0] - centres[i][0] >= d {
                break;
            }
            if metric.distance2(centres[i], centres[j]) < d * d {
                out[i].push(BrickId(j as u32));
                out[j].push(BrickId(i as u32));
                pairs += 1;
                if pairs > MAX_CONFLICT_PAIRS {
                    return Err(TeamProblemError::TooManyConflicts { distance_m: d });
                }
            }
        }
    }
    for l in &mut out {
        l.sort_unstable();
    }
    Ok(out)
}

impl<'w> TeamProblem<'w> {
    /// A problem; fails on an invalid model, a team too small for some brick, a bad budget,
    /// or a `reward`/`expected` objective without a budget.
    pub fn new(
        wall: &'w Wall,
        model: TeamModel,
        uavs: usize,
        budget_s: Option<f64>,
        objective: Objective,
    ) -> Result<Self, TeamProblemError> {
        model.validate()?;
        if let Some(t) = budget_s {
            if !(t > 0.0 && t <= 1e9) {
                return Err(TeamProblemError::Budget(t));
            }
        }
        match objective {
            Objective::Makespan if budget_s.is_some() => {
                return Err(TeamProblemError::BudgetWithMakespan)
            }
            Objective::Reward if budget_s.is_none() => {
                return Err(TeamProblemError::NeedsBudget("reward"))
            }
            Objective::Expected { .. } if budget_s.is_none() => {
                return Err(TeamProblemError::NeedsBudget("expected"))
            }
            Objective::Expected { hazard_per_hour: h } if !(h.is_finite() && h >= 0.0) => {
                return Err(TeamProblemError::Hazard(h))
            }
            _ => {}
        }
        if uavs > MAX_UAVS {
            return Err(TeamProblemError::TeamTooLarge(uavs));
        }
        for b in wall.bricks() {
            let needed = model.of(b.kind).uavs;
            if uavs < needed as usize {
                return Err(TeamProblemError::TeamTooSmall {
                    uavs,
                    kind: b.kind,
                    needed,
                });
            }
        }
        let per = |f: &dyn Fn(&super::model::TypeSchedule) -> f64| -> Vec<f64> {
            wall.bricks().iter().map(|b| f(model.of(b.kind))).collect()
        };
        let place = per(&|t| t.place_s);
        let rest = per(&|t| t.cycle_rest_s);
        let reward = per(&|t| t.reward);
        let need = wall
            .bricks()
            .iter()
            .map(|b| model.of(b.kind).uavs)
            .collect();
        let conflicts = match model.concurrency {
            Concurrency::Zone => Vec::new(),
            Concurrency::Distance { distance_m, metric } => {
                distance_conflicts(wall, distance_m, metric)?
            }
        };
        Ok(TeamProblem {
            wall,
            model,
            uavs,
            budget_s,
            objective,
            place,
            rest,
            need,
            reward,
            conflicts,
            start: None,
        })
    }

    /// The same problem planned from a [`TeamStart`] instead of an empty wall and idle UAVs.
    /// Its planners report no bound (NaN): the bounds are for whole problems.
    pub fn with_start(mut self, start: TeamStart) -> Result<Self, TeamProblemError> {
        let n = self.len();
        let bad = |m: String| Err(TeamProblemError::Start(m));
        if start.uav_ready_s.len() != self.uavs {
            return bad(format!(
                "{} UAV ready times for {} UAVs",
                start.uav_ready_s.len(),
                self.uavs
            ));
        }
        if start.uav_ready_s.iter().any(|t| t.is_nan()) {
            return bad("a UAV ready time is not a number".into());
        }
        let mut seen = vec![false; n];
        let bricks = start
            .placed
            .iter()
            .chain(start.committed.iter().map(|c| &c.brick));
        for b in bricks {
            if b.index() >= n || std::mem::replace(&mut seen[b.index()], true) {
                return bad(format!(
                    "brick index {} is out of range or listed twice",
                    b.0
                ));
            }
        }
        for c in &start.committed {
            if !c.start_s.is_finite() || c.uavs.is_empty() || c.uavs.iter().any(|&u| u >= self.uavs)
            {
                return bad(format!("brick index {}: bad crew or start", c.brick.0));
            }
        }
        self.start = Some(start);
        Ok(self)
    }

    /// The start state, if the problem is planned from one.
    pub fn start(&self) -> Option<&TeamStart> {
        self.start.as_ref()
    }

    /// The wall.
    pub fn wall(&self) -> &'w Wall {
        self.wall
    }
    /// The model.
    pub fn model(&self) -> &TeamModel {
        &self.model
    }
    /// Team size.
    pub fn uavs(&self) -> usize {
        self.uavs
    }
    /// The budget T, if any.
    pub fn budget_s(&self) -> Option<f64> {
        self.budget_s
    }
    /// The objective.
    pub fn objective(&self) -> Objective {
        self.objective
    }
    /// Number of bricks.
    pub fn len(&self) -> usize {
        self.place.len()
    }
    /// Always false: walls are never empty.
    pub fn is_empty(&self) -> bool {
        self.place.is_empty()
    }
    /// Placing time of `b`.
    pub fn place_s(&self, b: BrickId) -> f64 {
        self.place[b.index()]
    }
    /// Rest of the cycle after placing `b`.
    pub fn rest_s(&self, b: BrickId) -> f64 {
        self.rest[b.index()]
    }
    /// UAVs `b` needs.
    pub fn need(&self, b: BrickId) -> u32 {
        self.need[b.index()]
    }
    /// Reward of `b`.
    pub fn reward(&self, b: BrickId) -> f64 {
        self.reward[b.index()]
    }
    /// True under the zone rule (every pair of bricks conflicts).
    pub fn zone_rule(&self) -> bool {
        self.model.concurrency == Concurrency::Zone
    }
    /// Under the distance rule, the bricks closer to `b` than D.
    pub fn conflicts(&self, b: BrickId) -> &[BrickId] {
        self.conflicts.get(b.index()).map_or(&[], Vec::as_slice)
    }
}

/// One brick placed by one UAV or a pair, starting at `start_s`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Placement {
    /// The brick.
    pub brick: BrickId,
    /// The UAVs that place it (0-based), one or two.
    pub uavs: Vec<usize>,
    /// When its placing phase starts (s).
    pub start_s: f64,
}

/// A team schedule: the placements, sorted by start time, then brick.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Schedule {
    /// The placements.
    pub placements: Vec<Placement>,
}

impl Schedule {
    /// Sorts placements by start, then brick (the canonical order of outputs).
    pub fn sort(&mut self) {
        self.placements
            .sort_by(|a, b| a.start_s.total_cmp(&b.start_s).then(a.brick.cmp(&b.brick)));
    }

    /// Each UAV's bricks in start order.
    pub fn by_uav(&self, uavs: usize) -> Vec<Vec<BrickId>> {
        let mut out = vec![Vec::new(); uavs];
        let mut sorted = self.clone();
        sorted.sort();
        for p in &sorted.placements {
            for &u in &p.uavs {
                if let Some(list) = out.get_mut(u) {
                    list.push(p.brick);
                }
            }
        }
        out
    }
}

/// Search statistics of a schedule planner.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct TeamStats {
    /// Wall-clock time spent.
    pub elapsed: Duration,
    /// Schedules decoded.
    pub decodes: u64,
    /// Improvements accepted.
    pub improvements: u64,
}

/// What a schedule planner returns.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TeamOutcome {
    /// How the search ended.
    pub status: Status,
    /// The best schedule found (`None` only when none was found).
    pub schedule: Option<Schedule>,
    /// Its reward (fault-free).
    pub reward: f64,
    /// Its makespan: the last placement's end (0 for an empty schedule).
    pub makespan_s: f64,
    /// For `expected`: the estimated expected reward under the failure rate.
    pub expected_reward: Option<f64>,
    /// The proven bound: a lower bound on the makespan (`makespan`) or an upper bound on the
    /// reward (`reward`, `expected`).
    pub bound: f64,
    /// Statistics.
    pub stats: TeamStats,
}

impl TeamOutcome {
    /// The gap to the bound: makespan − bound, or bound − (expected) reward; never negative.
    pub fn gap(&self, objective: Objective) -> f64 {
        let g = match objective {
            Objective::Makespan => self.makespan_s - self.bound,
            Objective::Reward => self.bound - self.reward,
            Objective::Expected { .. } => self.bound - self.expected_reward.unwrap_or(self.reward),
        };
        g.max(0.0)
    }
}
