//! `validate_schedule`: checks a team schedule against DESIGN §4.1 with no knowledge of any
//! planner. It recomputes what it needs from the wall and the model: supports from the wall's
//! canonical precedence, centres from the footprints, every time from the placements.

use super::model::{Concurrency, TeamModel};
use super::problem::{Schedule, TeamStart};
use mason_wall::violations::Violations;
use mason_wall::{BrickId, Wall, BRICK_HEIGHT};
use std::ops::ControlFlow;
use thiserror::Error;

/// Times are compared with this slack (s), so that sums of decimal durations pass.
pub const TIME_EPS: f64 = 1e-6;

/// A rule a schedule breaks. Bricks are named by their labels.
#[derive(Clone, Debug, PartialEq, Error)]
pub enum ScheduleError {
    /// A brick index outside the wall.
    #[error("placement {index}: brick index {brick} is not in the wall")]
    UnknownBrick {
        /// Position in the schedule.
        index: usize,
        /// The index.
        brick: u32,
    },
    /// A brick placed twice.
    #[error("brick {0} is placed twice")]
    Twice(u32),
    /// Wrong number of UAVs, a UAV out of range, or the same UAV twice.
    #[error("brick {brick}: UAVs {uavs:?}, but it needs {needed} distinct UAVs of 0..{team}")]
    Crew {
        /// The brick.
        brick: u32,
        /// The UAVs given.
        uavs: Vec<usize>,
        /// UAVs it needs.
        needed: u32,
        /// Team size.
        team: usize,
    },
    /// A start before 0 or not finite.
    #[error("brick {brick}: start {start_s} s is not a finite time ≥ 0")]
    Start {
        /// The brick.
        brick: u32,
        /// Its start.
        start_s: f64,
    },
    /// A UAV starts again before its cycle ends.
    #[error("UAV {uav}: brick {next} starts at {next_start} s, before the cycle of brick {prev} ends at {ready} s")]
    Cycle {
        /// The UAV.
        uav: usize,
        /// The earlier brick.
        prev: u32,
        /// When the UAV is free again.
        ready: f64,
        /// The later brick.
        next: u32,
        /// Its start.
        next_start: f64,
    },
    /// A brick starts before a support is placed (or the support is never placed).
    #[error("brick {brick} starts at {start} s but its support {support} is {}", match .support_end { Some(e) => format!("placed only at {e} s"), None => "never placed".into() })]
    Precedence {
        /// The brick.
        brick: u32,
        /// Its start.
        start: f64,
        /// The support.
        support: u32,
        /// When the support is placed, if ever.
        support_end: Option<f64>,
    },
    /// Two bricks place at overlapping times against the concurrency rule.
    #[error("bricks {a} and {b} place at overlapping times ({a_start}–{a_end} s and {b_start}–{b_end} s) but {why}")]
    Concurrent {
        /// One brick.
        a: u32,
        /// Its placing phase.
        a_start: f64,
        /// Its end.
        a_end: f64,
        /// The other.
        b: u32,
        /// Its placing phase.
        b_start: f64,
        /// Its end.
        b_end: f64,
        /// The rule.
        why: String,
    },
    /// A brick placed after the budget.
    #[error("brick {brick} is placed at {end} s, after the budget of {budget} s")]
    Budget {
        /// The brick.
        brick: u32,
        /// When it is placed.
        end: f64,
        /// The budget.
        budget: f64,
    },
    /// A replan moves a UAV before it is ready, or uses one that is gone (ready at ∞).
    #[error(
        "UAV {uav}: brick {brick} starts at {start_s} s, but the UAV is ready only at {ready_s} s"
    )]
    NotReady {
        /// The UAV.
        uav: usize,
        /// The brick.
        brick: u32,
        /// Its start.
        start_s: f64,
        /// When the UAV is ready.
        ready_s: f64,
    },
    /// A replan drops a brick that was on its way, changes its crew, or starts it too early.
    #[error(
        "brick {0} was on its way but the replan drops it, changes its crew or starts it too early"
    )]
    Committed(u32),
    /// A planner's objective lies on the wrong side of its own proven bound.
    #[error("the {objective} {value} lies beyond its proven bound {bound}")]
    OutsideBound {
        /// `makespan`, `reward` or `expected reward`.
        objective: &'static str,
        /// The reported value.
        value: f64,
        /// The bound.
        bound: f64,
    },
    /// A row's stated end is not its start plus the placing time of its brick's type.
    #[error("UAV {uav}: brick {brick} is said to be placed at {claimed} s but its placing phase ends at {actual} s")]
    End {
        /// The brick.
        brick: u32,
        /// The UAV of the row.
        uav: usize,
        /// The end stated.
        claimed: f64,
        /// Start + placing time.
        actual: f64,
    },
    /// The reported reward or makespan is not what the schedule gives.
    #[error("reported {what} {claimed} but the schedule gives {actual}")]
    Claim {
        /// `reward` or `makespan`.
        what: &'static str,
        /// Reported.
        claimed: f64,
        /// Recomputed.
        actual: f64,
    },
}

/// What the validator recomputed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ScheduleEvaluation {
    /// Bricks placed.
    pub bricks: usize,
    /// Their total reward.
    pub reward: f64,
    /// The last placement's end (0 when empty).
    pub makespan_s: f64,
}

/// Checks every rule of DESIGN §4.1 and recomputes reward and makespan.
pub fn validate_schedule(
    wall: &Wall,
    model: &TeamModel,
    uavs: usize,
    budget_s: Option<f64>,
    schedule: &Schedule,
) -> Result<ScheduleEvaluation, ScheduleError> {
    let mut found = Violations::first();
    let eval = check(wall, model, uavs, budget_s, schedule, None, &mut found);
    first_of(eval, found)
}

/// Every rule of [`validate_schedule`] that `schedule` breaks (it stops at the first). A
/// placement with an unknown brick, a repeated brick, a wrong crew or a bad start is skipped
/// after it is reported; every other broken rule is reported once per pair of bricks or UAV
/// cycle that breaks it.
pub fn schedule_violations(
    wall: &Wall,
    model: &TeamModel,
    uavs: usize,
    budget_s: Option<f64>,
    schedule: &Schedule,
) -> Vec<ScheduleError> {
    let mut found = Violations::every();
    let _ = check(wall, model, uavs, budget_s, schedule, None, &mut found);
    found.into_vec()
}

/// Every rule of [`validate_continuation`] that `schedule` breaks.
pub fn continuation_violations(
    wall: &Wall,
    model: &TeamModel,
    uavs: usize,
    budget_s: Option<f64>,
    start: &TeamStart,
    schedule: &Schedule,
) -> Vec<ScheduleError> {
    let mut found = Violations::every();
    let _ = continuation(wall, model, uavs, budget_s, start, schedule, &mut found);
    found.into_vec()
}

fn first_of(
    eval: ControlFlow<(), ScheduleEvaluation>,
    found: Violations<ScheduleError>,
) -> Result<ScheduleEvaluation, ScheduleError> {
    match eval {
        ControlFlow::Continue(eval) => found.into_result(eval),
        ControlFlow::Break(()) => Err(found.into_vec().remove(0)),
    }
}

/// Checks a schedule planned from a [`TeamStart`] (a replan; times from then): the same rules,
/// with the bricks already on the wall counting as placed long before, the bricks on their way
/// kept with their crews and no earlier than given (they may start before 0, and a half-carried
/// orange may have one UAV),
/// no new brick for a UAV before it is ready, and none for a UAV that is gone; a brick on its
/// way may end after the budget (it earns nothing). The reward and makespan are those of the
/// new part.
pub fn validate_continuation(
    wall: &Wall,
    model: &TeamModel,
    uavs: usize,
    budget_s: Option<f64>,
    start: &TeamStart,
    schedule: &Schedule,
) -> Result<ScheduleEvaluation, ScheduleError> {
    let mut found = Violations::first();
    let eval = continuation(wall, model, uavs, budget_s, start, schedule, &mut found);
    first_of(eval, found)
}

fn continuation(
    wall: &Wall,
    model: &TeamModel,
    uavs: usize,
    budget_s: Option<f64>,
    start: &TeamStart,
    schedule: &Schedule,
    found: &mut Violations<ScheduleError>,
) -> ControlFlow<(), ScheduleEvaluation> {
    for c in &start.committed {
        let kept = schedule
            .placements
            .iter()
            .any(|p| p.brick == c.brick && p.uavs == c.uavs && p.start_s >= c.start_s - TIME_EPS);
        if !kept {
            let label = wall
                .bricks()
                .get(c.brick.index())
                .map_or(c.brick.0, |b| b.label);
            found.report(ScheduleError::Committed(label))?;
        }
    }
    check(wall, model, uavs, budget_s, schedule, Some(start), found)
}

fn check(
    wall: &Wall,
    model: &TeamModel,
    uavs: usize,
    budget_s: Option<f64>,
    schedule: &Schedule,
    before: Option<&TeamStart>,
    found: &mut Violations<ScheduleError>,
) -> ControlFlow<(), ScheduleEvaluation> {
    let n = wall.len();
    let label = |i: usize| wall.bricks()[i].label;
    let mut start: Vec<Option<f64>> = vec![None; n];
    for b in before.iter().flat_map(|st| &st.placed) {
        if let Some(s) = start.get_mut(b.index()) {
            *s = Some(f64::NEG_INFINITY);
        }
    }
    let mut per_uav: Vec<Vec<(f64, usize)>> = vec![Vec::new(); uavs];
    for (index, p) in schedule.placements.iter().enumerate() {
        let i = p.brick.index();
        if i >= n {
            found.report(ScheduleError::UnknownBrick {
                index,
                brick: p.brick.0,
            })?;
            continue;
        }
        if start[i].is_some() {
            found.report(ScheduleError::Twice(label(i)))?;
            continue;
        }
        let committed = before.is_some_and(|st| {
            st.committed
                .iter()
                .any(|c| c.brick == p.brick && c.uavs == p.uavs)
        });
        let needed = model.of(wall.bricks()[i].kind).uavs;
        let mut crew = p.uavs.clone();
        crew.sort_unstable();
        crew.dedup();
        if crew.len() != p.uavs.len()
            || (crew.len() != needed as usize && !committed)
            || crew.is_empty()
            || crew.iter().any(|&u| u >= uavs)
        {
            found.report(ScheduleError::Crew {
                brick: label(i),
                uavs: p.uavs.clone(),
                needed,
                team: uavs,
            })?;
            continue;
        }
        if !(p.start_s.is_finite() && (p.start_s >= 0.0 || committed)) {
            found.report(ScheduleError::Start {
                brick: label(i),
                start_s: p.start_s,
            })?;
            continue;
        }
        if let (Some(st), false) = (before, committed) {
            for &u in &crew {
                let ready = st.uav_ready_s.get(u).copied().unwrap_or(f64::INFINITY);
                if p.start_s < ready - TIME_EPS {
                    found.report(ScheduleError::NotReady {
                        uav: u,
                        brick: label(i),
                        start_s: p.start_s,
                        ready_s: ready,
                    })?;
                }
            }
        }
        start[i] = Some(p.start_s);
        for &u in &crew {
            per_uav[u].push((p.start_s, i));
        }
    }
    let times = |i: usize| model.of(wall.bricks()[i].kind);
    let end = |i: usize| start[i].map(|s| s + times(i).place_s);

    for (u, list) in per_uav.iter_mut().enumerate() {
        list.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
        for w in list.windows(2) {
            let (s0, i0) = w[0];
            let (s1, i1) = w[1];
            let ready = s0 + times(i0).cycle_s();
            if s1 < ready - TIME_EPS {
                found.report(ScheduleError::Cycle {
                    uav: u,
                    prev: label(i0),
                    ready,
                    next: label(i1),
                    next_start: s1,
                })?;
            }
        }
    }

    for (i, s) in start.iter().enumerate() {
        let Some(s) = *s else { continue };
        for sup in wall.supports(BrickId(i as u32)) {
            let e = end(sup.index());
            if e.is_none_or(|e| e > s + TIME_EPS) {
                found.report(ScheduleError::Precedence {
                    brick: label(i),
                    start: s,
                    support: label(sup.index()),
                    support_end: e,
                })?;
            }
        }
    }

    // Concurrency: sweep the placing phases in start order against those still running.
    let mut phases: Vec<(f64, f64, usize)> = (0..n)
        .filter_map(|i| Some((start[i]?, end(i)?, i)))
        .filter(|&(s, _, _)| s.is_finite())
        .collect();
    phases.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.2.cmp(&b.2)));
    let centre = |i: usize| {
        let b = &wall.bricks()[i];
        let f = &b.footprint;
        [
            (f.x0 + f.x1) / 2.0,
            (f.y0 + f.y1) / 2.0,
            (f64::from(b.level) - 0.5) * BRICK_HEIGHT,
        ]
    };
    let mut running: Vec<(f64, f64, usize)> = Vec::new();
    for &(s, e, i) in &phases {
        running.retain(|&(_, re, _)| re > s + TIME_EPS);
        for &(rs, re, j) in &running {
            let why = match model.concurrency {
                Concurrency::Zone => Some("the zone holds one brick at a time".to_string()),
                Concurrency::Distance { distance_m } => {
                    let (a, b) = (centre(i), centre(j));
                    let d = ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2))
                        .sqrt();
                    (d < distance_m).then(|| {
                        format!("their centres are {d:.3} m apart, closer than {distance_m} m")
                    })
                }
            };
            if let Some(why) = why {
                found.report(ScheduleError::Concurrent {
                    a: label(j),
                    a_start: rs,
                    a_end: re,
                    b: label(i),
                    b_start: s,
                    b_end: e,
                    why,
                })?;
            }
        }
        running.push((s, e, i));
    }

    let mut eval = ScheduleEvaluation {
        bricks: phases.len(),
        reward: 0.0,
        makespan_s: 0.0,
    };
    let on_its_way =
        |i: usize| before.is_some_and(|st| st.committed.iter().any(|c| c.brick.index() == i));
    for &(_, e, i) in &phases {
        if let Some(t) = budget_s {
            if e > t + TIME_EPS && on_its_way(i) {
                // Flown, but it earns nothing.
                eval.makespan_s = eval.makespan_s.max(e);
                continue;
            }
            if e > t + TIME_EPS {
                found.report(ScheduleError::Budget {
                    brick: label(i),
                    end: e,
                    budget: t,
                })?;
                continue;
            }
        }
        eval.reward += times(i).reward;
        eval.makespan_s = eval.makespan_s.max(e);
    }
    ControlFlow::Continue(eval)
}

/// [`validate_schedule`], then checks the reported reward and makespan.
pub fn validate_schedule_claim(
    wall: &Wall,
    model: &TeamModel,
    uavs: usize,
    budget_s: Option<f64>,
    schedule: &Schedule,
    reward: f64,
    makespan_s: f64,
) -> Result<ScheduleEvaluation, ScheduleError> {
    let eval = validate_schedule(wall, model, uavs, budget_s, schedule)?;
    match claim_violations(&eval, Some(reward), Some(makespan_s))
        .into_iter()
        .next()
    {
        Some(e) => Err(e),
        None => Ok(eval),
    }
}

/// The claims (reported reward, makespan) that a recomputed evaluation does not bear out:
/// the reward within 1e-6, the makespan within [`TIME_EPS`].
pub fn claim_violations(
    eval: &ScheduleEvaluation,
    reward: Option<f64>,
    makespan_s: Option<f64>,
) -> Vec<ScheduleError> {
    let mut out = Vec::new();
    if let Some(reward) = reward {
        if (eval.reward - reward).abs() > 1e-6 {
            out.push(ScheduleError::Claim {
                what: "reward",
                claimed: reward,
                actual: eval.reward,
            });
        }
    }
    if let Some(makespan_s) = makespan_s {
        if (eval.makespan_s - makespan_s).abs() > TIME_EPS {
            out.push(ScheduleError::Claim {
                what: "makespan",
                claimed: makespan_s,
                actual: eval.makespan_s,
            });
        }
    }
    out
}

/// One UAV's row of a schedule file that also states when the brick is placed.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClaimedEnd {
    /// The brick.
    pub brick: BrickId,
    /// The UAV of the row.
    pub uav: usize,
    /// The start given.
    pub start_s: f64,
    /// The end given.
    pub end_s: f64,
}

/// The rows whose end is not start + the placing time of their brick's type (within
/// [`TIME_EPS`]), as [`ScheduleError::End`]. Rows naming a brick outside the wall are left to
/// [`validate_schedule`].
pub fn end_violations(wall: &Wall, model: &TeamModel, ends: &[ClaimedEnd]) -> Vec<ScheduleError> {
    ends.iter()
        .filter_map(|c| {
            let b = wall.bricks().get(c.brick.index())?;
            let actual = c.start_s + model.of(b.kind).place_s;
            ((c.end_s - actual).abs() > TIME_EPS).then_some(ScheduleError::End {
                brick: b.label,
                uav: c.uav,
                claimed: c.end_s,
                actual,
            })
        })
        .collect()
}
