//! `validate_schedule`: checks a team schedule against DESIGN §4.1 with no knowledge of any
//! planner. It recomputes what it needs from the wall and the model: supports from the wall's
//! canonical precedence, centres from the footprints, every time from the placements.

use super::model::{Concurrency, Metric, TeamModel};
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
                Concurrency::Distance { distance_m, metric } => {
                    let (a, b) = (centre(i), centre(j));
                    let axes = if metric == Metric::Xy { 2 } else { 3 };
                    let d = (0..axes).map(|k| (a[k] - b[k]).powi(2)).sum::<f64>().sqrt();
                    (d < distance_m).then(|| {
                        format!(
                            "their centres are {d:.3} m apart ({metric}), closer than {distance_m} m"
                        )
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

#[cfg(test)]
mod tests {
    //! One broken schedule per rule: a valid schedule with exactly one rule broken, and that
    //! rule alone reported, by the first-error check and by the all-violations one alike.
    use super::*;
    use crate::schedule::{exhaustive_schedule, plan_schedule, Objective, Placement, TeamProblem};
    use crate::Budget;

    fn wall() -> Wall {
        mason_wall::builtin("thesis-2x5").unwrap().wall()
    }

    /// A build order of the wall: level by level.
    fn order(wall: &Wall) -> Vec<BrickId> {
        let mut ids: Vec<BrickId> = wall.ids().collect();
        ids.sort_by_key(|&b| (wall.brick(b).level, b));
        ids
    }

    /// A slow, valid schedule for 3 UAVs: brick k of [`order`] starts at k·C (C three times
    /// the longest cycle) with UAV k mod 2; UAV 2 stays idle. Every rule holds with room.
    fn base(wall: &Wall, model: &TeamModel) -> (Schedule, f64) {
        let c = 3.0
            * wall
                .bricks()
                .iter()
                .map(|b| model.of(b.kind).cycle_s())
                .fold(0.0, f64::max);
        let placements = order(wall)
            .into_iter()
            .enumerate()
            .map(|(k, brick)| Placement {
                brick,
                uavs: vec![k % 2],
                start_s: k as f64 * c,
            })
            .collect();
        (Schedule { placements }, c)
    }

    fn rule(e: &ScheduleError) -> String {
        mason_wall::violations::rule(e)
    }

    /// The rules `s` breaks (3 UAVs, `budget`), checked both ways.
    fn broken(wall: &Wall, model: &TeamModel, budget: Option<f64>, s: &Schedule) -> Vec<String> {
        let every = schedule_violations(wall, model, 3, budget, s);
        let first = validate_schedule(wall, model, 3, budget, s);
        // Debug text, so that a NaN start compares equal to itself.
        let first = format!("{:?}", first.err());
        assert_eq!(
            first,
            format!("{:?}", every.first().cloned()),
            "first and all agree"
        );
        every.iter().map(rule).collect()
    }

    #[test]
    fn the_base_schedule_is_valid_and_recomputed() {
        let w = wall();
        let m = TeamModel::thesis();
        let (s, c) = base(&w, &m);
        let eval = validate_schedule(&w, &m, 3, None, &s).unwrap();
        let last = w.brick(*order(&w).last().unwrap());
        assert_eq!(eval.bricks, w.len());
        assert_eq!(eval.makespan_s, 9.0 * c + m.of(last.kind).place_s);
        let reward: f64 = w.bricks().iter().map(|b| m.of(b.kind).reward).sum();
        assert_eq!(eval.reward, reward);
        assert!(schedule_violations(&w, &m, 3, None, &s).is_empty());
    }

    #[test]
    fn one_broken_schedule_per_rule_reports_exactly_that_rule() {
        let w = wall();
        let m = TeamModel::thesis();
        let (s, c) = base(&w, &m);
        let n = s.placements.len();
        let ord = order(&w);
        let place = |b: BrickId| m.of(w.brick(b).kind).place_s;
        let cycle = |b: BrickId| m.of(w.brick(b).kind).cycle_s();
        let with = |f: &dyn Fn(&mut Vec<Placement>)| {
            let mut p = s.placements.clone();
            f(&mut p);
            Schedule { placements: p }
        };
        let top = ord[n - 1];
        assert!(
            w.ids().all(|b| !w.supports(b).contains(&top)),
            "the last brick supports none"
        );
        // The top brick's support placed last, and the placement just before it.
        let j = (0..n)
            .rev()
            .find(|&j| w.supports(top).contains(&ord[j]))
            .unwrap();
        let cases: Vec<(&str, Schedule, Option<f64>, &str)> = vec![
            (
                "a brick outside the wall",
                with(&|p| p.push(Placement { brick: BrickId(99), uavs: vec![2], start_s: 0.0 })),
                None,
                "UnknownBrick",
            ),
            (
                "the first brick again, at the end, by the idle UAV",
                with(&|p| p.push(Placement { brick: ord[0], uavs: vec![2], start_s: n as f64 * c })),
                None,
                "Twice",
            ),
            (
                "the top brick by UAV 5 of 3",
                with(&|p| p[n - 1].uavs = vec![5]),
                None,
                "Crew",
            ),
            (
                "the top brick by the idle UAV twice over",
                with(&|p| p[n - 1].uavs = vec![2, 2]),
                None,
                "Crew",
            ),
            (
                "the top brick at -1 s",
                with(&|p| p[n - 1].start_s = -1.0),
                None,
                "Start",
            ),
            (
                "the top brick at NaN s",
                with(&|p| p[n - 1].start_s = f64::NAN),
                None,
                "Start",
            ),
            (
                "the top brick by the UAV of the brick before, after its placing phase but before its cycle ends",
                with(&|p| {
                    let prev = ord[n - 2];
                    p[n - 1].uavs = p[n - 2].uavs.clone();
                    p[n - 1].start_s = p[n - 2].start_s + (place(prev) + cycle(prev)) / 2.0;
                }),
                None,
                "Cycle",
            ),
            (
                "the top brick by the idle UAV, before its last support starts",
                with(&|p| {
                    p[n - 1].uavs = vec![2];
                    p[n - 1].start_s = (j as f64 - 1.0) * c + place(ord[j - 1]) + 1.0;
                }),
                None,
                "Precedence",
            ),
            (
                "the top brick by the idle UAV, while the brick before is placing (zone rule)",
                with(&|p| {
                    p[n - 1].uavs = vec![2];
                    p[n - 1].start_s = p[n - 2].start_s + place(ord[n - 2]) / 2.0;
                }),
                None,
                "Concurrent",
            ),
            (
                "a budget that ends 1 s before the top brick is placed",
                s.clone(),
                Some((n - 1) as f64 * c + place(top) - 1.0),
                "Budget",
            ),
        ];
        assert!(
            !w.supports(top).contains(&ord[n - 2]),
            "the zone case must not break precedence"
        );
        for (what, schedule, budget, want) in cases {
            assert_eq!(broken(&w, &m, budget, &schedule), [want], "{what}");
        }
    }

    #[test]
    fn the_distance_rule_names_the_pair_that_is_too_close() {
        let w = wall();
        let m = TeamModel::cmcp();
        let (mut s, _) = base(&w, &m);
        // Two neighbours of one level whose centres are 0.30 m apart (the red 103 and 104),
        // by two UAVs at once.
        let (a, b) = (s.placements[2].clone(), s.placements[3].clone());
        assert_eq!((w.brick(a.brick).label, w.brick(b.brick).label), (103, 104));
        s.placements[3].start_s = a.start_s;
        let found = schedule_violations(&w, &m, 3, None, &s);
        assert_eq!(found.len(), 1, "{found:?}");
        assert!(
            matches!(&found[0], ScheduleError::Concurrent { a: x, b: y, why, .. }
                if *x == w.brick(a.brick).label && *y == w.brick(b.brick).label && why.contains("closer than 0.8")),
            "{found:?}"
        );
    }

    #[test]
    fn stated_figures_and_ends_are_checked_apart() {
        let w = wall();
        let m = TeamModel::thesis();
        let (s, _) = base(&w, &m);
        let eval = validate_schedule(&w, &m, 3, None, &s).unwrap();
        assert!(claim_violations(&eval, Some(eval.reward), Some(eval.makespan_s)).is_empty());
        assert!(claim_violations(&eval, None, None).is_empty());
        let wrong = claim_violations(&eval, Some(eval.reward + 1.0), Some(eval.makespan_s));
        assert_eq!(
            wrong,
            [ScheduleError::Claim {
                what: "reward",
                claimed: eval.reward + 1.0,
                actual: eval.reward
            }]
        );
        let wrong = claim_violations(&eval, None, Some(eval.makespan_s - 1.0));
        assert!(matches!(
            wrong[..],
            [ScheduleError::Claim {
                what: "makespan",
                ..
            }]
        ));
        assert!(
            validate_schedule_claim(&w, &m, 3, None, &s, eval.reward, eval.makespan_s + 1.0)
                .is_err()
        );
        assert!(validate_schedule_claim(&w, &m, 3, None, &s, eval.reward, eval.makespan_s).is_ok());
        let p = &s.placements[0];
        let place = m.of(w.brick(p.brick).kind).place_s;
        let end = |end_s| ClaimedEnd {
            brick: p.brick,
            uav: 0,
            start_s: p.start_s,
            end_s,
        };
        assert!(end_violations(&w, &m, &[end(p.start_s + place)]).is_empty());
        let found = end_violations(&w, &m, &[end(p.start_s + place + 1.0)]);
        assert_eq!(
            found,
            [ScheduleError::End {
                brick: w.brick(p.brick).label,
                uav: 0,
                claimed: p.start_s + place + 1.0,
                actual: p.start_s + place
            }]
        );
        // At exactly the slack (from an empty schedule's 0 reward and 0 s), a claim holds.
        let none = validate_schedule(&w, &m, 3, None, &Schedule::default()).unwrap();
        assert_eq!((none.reward, none.makespan_s), (0.0, 0.0));
        assert!(claim_violations(&none, Some(1e-6), Some(TIME_EPS)).is_empty());
        // A stated end exactly one slack from the placing phase's end holds (a phase ending
        // at 0 s, so that the slack is exact).
        let at_zero = ClaimedEnd {
            brick: p.brick,
            uav: 0,
            start_s: -place,
            end_s: TIME_EPS,
        };
        assert_eq!(at_zero.start_s + place, 0.0);
        assert!(end_violations(&w, &m, &[at_zero]).is_empty());
        let outside = ClaimedEnd {
            brick: BrickId(99),
            uav: 0,
            start_s: 0.0,
            end_s: 1.0,
        };
        assert!(
            end_violations(&w, &m, &[outside]).is_empty(),
            "left to validate_schedule"
        );
    }

    #[test]
    fn one_broken_continuation_per_rule_reports_exactly_that_rule() {
        let w = wall();
        let m = TeamModel::thesis();
        let (s, _) = base(&w, &m);
        let ready = TeamStart {
            placed: vec![],
            committed: vec![],
            uav_ready_s: vec![0.0; 3],
        };
        let check = |st: &TeamStart| {
            let every = continuation_violations(&w, &m, 3, None, st, &s);
            let first = validate_continuation(&w, &m, 3, None, st, &s);
            assert_eq!(first.err().as_ref(), every.first(), "first and all agree");
            every.iter().map(rule).collect::<Vec<_>>()
        };
        assert!(check(&ready).is_empty());
        // UAV 0 is ready 1 s after its first start.
        let late = TeamStart {
            uav_ready_s: vec![s.placements[0].start_s + 1.0, 0.0, 0.0],
            ..ready.clone()
        };
        assert_eq!(check(&late), ["NotReady"]);
        // The first brick was on its way and may not start before 1 s.
        let p = s.placements[0].clone();
        let on_its_way = TeamStart {
            committed: vec![Placement {
                start_s: p.start_s + 1.0,
                ..p.clone()
            }],
            ..ready.clone()
        };
        assert_eq!(check(&on_its_way), ["Committed"]);
        // Kept as committed, it passes.
        let kept = TeamStart {
            committed: vec![p],
            ..ready.clone()
        };
        assert!(check(&kept).is_empty());
        // A brick already on the wall is placed again.
        let placed = TeamStart {
            placed: vec![s.placements[0].brick],
            ..ready
        };
        assert_eq!(check(&placed), ["Twice"]);
    }

    #[test]
    fn a_crew_of_the_wrong_size_is_refused_unless_it_was_on_its_way() {
        let w = wall();
        let m = TeamModel::thesis();
        let (mut s, _) = base(&w, &m);
        let n = s.placements.len();
        // Two distinct UAVs of the team for a brick that needs one.
        s.placements[n - 1].uavs = vec![1, 2];
        assert_eq!(broken(&w, &m, None, &s), ["Crew"]);
        // Nobody at all.
        s.placements[n - 1].uavs = vec![];
        assert_eq!(broken(&w, &m, None, &s), ["Crew"]);
    }

    #[test]
    fn a_brick_on_its_way_keeps_its_crew_and_may_start_before_now() {
        let w = wall();
        let m = TeamModel::thesis();
        let (mut s, c) = base(&w, &m);
        // Brick 0 is being placed by UAV 0 since 5 s ago.
        s.placements[0].start_s = -5.0;
        let first = s.placements[0].clone();
        let start = TeamStart {
            placed: vec![],
            committed: vec![first.clone()],
            uav_ready_s: vec![1.0, 0.0, 0.0],
        };
        let found = |st: &TeamStart, s: &Schedule| {
            let every = continuation_violations(&w, &m, 3, None, st, s);
            let first = validate_continuation(&w, &m, 3, None, st, s);
            assert_eq!(first.err().as_ref(), every.first(), "first and all agree");
            every.iter().map(rule).collect::<Vec<_>>()
        };
        assert!(found(&start, &s).is_empty());
        // UAV 0's next brick (at 2C) may not start before UAV 0 is ready.
        let late = TeamStart {
            uav_ready_s: vec![2.0 * c + 1.0, 0.0, 0.0],
            ..start.clone()
        };
        assert_eq!(found(&late, &s), ["NotReady"]);
        // Not on its way, the same start is before 0 (and the brick is not placed).
        assert_eq!(broken(&w, &m, None, &s)[0], "Start");
        // Kept no earlier than given, within the time slack.
        let (mut t, _) = base(&w, &m);
        let second = t.placements[1].clone();
        let slack = TeamStart {
            committed: vec![Placement {
                start_s: second.start_s + TIME_EPS / 2.0,
                ..second.clone()
            }],
            uav_ready_s: vec![0.0; 3],
            placed: vec![],
        };
        assert!(found(&slack, &t).is_empty());
        t.placements[1].start_s -= 2.0 * TIME_EPS;
        let early = TeamStart {
            committed: vec![second],
            ..slack
        };
        assert_eq!(found(&early, &t), ["Committed"]);
    }

    /// A start `s` with `s + TIME_EPS == e` exactly, or below `e - TIME_EPS` by one step.
    fn at_the_slack(e: f64) -> f64 {
        let mut s = e - TIME_EPS;
        for _ in 0..64 {
            if s + TIME_EPS == e {
                return s;
            }
            s = if s + TIME_EPS < e {
                s.next_up()
            } else {
                s.next_down()
            };
        }
        panic!("no start {TIME_EPS} s before {e}")
    }

    #[test]
    fn the_time_slack_is_allowed_and_not_more() {
        let w = wall();
        let m = TeamModel::thesis();
        let (s, c) = base(&w, &m);
        let n = s.placements.len();
        let ord = order(&w);
        // UAV 0 ready TIME_EPS after its first start: within the slack.
        let ready = TeamStart {
            placed: vec![],
            committed: vec![],
            uav_ready_s: vec![TIME_EPS, 0.0, 0.0],
        };
        assert!(continuation_violations(&w, &m, 3, None, &ready, &s).is_empty());
        // The top brick by UAV 2, starting exactly one slack before its support is placed.
        let top = ord[n - 1];
        let support = *w.supports(top).iter().max().unwrap();
        let support_end = (ord.iter().position(|&b| b == support).unwrap() as f64) * c
            + m.of(w.brick(support).kind).place_s;
        let mut prec = s.clone();
        prec.placements[n - 1].uavs = vec![2];
        prec.placements[n - 1].start_s = at_the_slack(support_end);
        assert!(schedule_violations(&w, &m, 3, None, &prec).is_empty());
        prec.placements[n - 1].start_s = at_the_slack(support_end).next_down();
        // (It then also overlaps its support's placing phase: the zone rule's slack is the same.)
        assert_eq!(broken(&w, &m, None, &prec), ["Precedence", "Concurrent"]);
        // A UAV starting again one slack before its cycle ends.
        let mut again = s.clone();
        let prev = &s.placements[n - 2];
        again.placements[n - 1].uavs = prev.uavs.clone();
        let free = prev.start_s + m.of(w.brick(prev.brick).kind).cycle_s();
        again.placements[n - 1].start_s = at_the_slack(free);
        assert!(schedule_violations(&w, &m, 3, None, &again).is_empty());
        again.placements[n - 1].start_s = at_the_slack(free).next_down();
        assert_eq!(broken(&w, &m, None, &again), ["Cycle"]);
    }

    /// A 3-D wall of red bricks (CMCP format: id type x y z yaw): pairs side by side in y,
    /// and pairs a level apart.
    fn spread() -> Wall {
        let text = "\
1 1 0 0 0.1 0
2 1 0 0.5 0.1 0
3 1 3 0 0.1 0
4 1 3 0.9 0.1 0
5 1 6 0 0.1 0
6 1 6.78 0 0.3 0
7 1 9 0 0.1 0
8 1 9.5 0 0.3 0
9 1 0 5 0.1 0
10 1 0.8 5 0.1 0
11 1 12 0 0.1 0
12 1 12.75 0 0.3 0
13 1 20 5 0.1 0
14 1 20.5 5 0.1 0
";
        mason_wall::parse_cmcp(text, "spread", mason_wall::CmcpSizes::Yaml).unwrap()
    }

    /// Two bricks placed at the same time under `metric`: the rules they break.
    fn together_rules(w: &Wall, metric: Metric, a: u32, b: u32) -> Vec<String> {
        let m = TeamModel::cmcp().with_metric(metric).unwrap();
        let together = Schedule {
            placements: [a, b]
                .iter()
                .enumerate()
                .map(|(u, &l)| Placement {
                    brick: w.by_label(l).unwrap(),
                    uavs: vec![u],
                    start_s: 0.0,
                })
                .collect(),
        };
        let found = schedule_violations(w, &m, 3, None, &together);
        found.iter().map(rule).collect()
    }

    #[test]
    fn the_distance_rule_measures_all_three_axes_under_xyz() {
        let w = spread();
        let rules = |a, b| together_rules(&w, Metric::Xyz, a, b);
        // 0.5 m apart in y: too close; 0.9 m: far enough.
        assert_eq!(rules(1, 2), ["Concurrent"]);
        assert!(rules(3, 4).is_empty());
        // 0.78 m in x and a level (0.2 m) up: 0.805 m, far enough; 0.5 m and a level: too close.
        assert!(rules(5, 6).is_empty());
        assert_eq!(rules(7, 8), ["Concurrent"]);
        // 0.75 m and a level: 0.776 m (0.85 m were a level counted 0.4 m).
        assert_eq!(rules(11, 12), ["Concurrent"]);
        // 0.5 m apart along x, away from y = 0: too close.
        assert_eq!(rules(13, 14), ["Concurrent"]);
        // Exactly D apart is not closer than D.
        let centre = |l: u32| crate::schedule::brick_centre(w.brick(w.by_label(l).unwrap()));
        let (a, b) = (centre(9), centre(10));
        assert_eq!(((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)).sqrt(), 0.8);
        assert!(rules(9, 10).is_empty());
    }

    #[test]
    fn the_distance_rule_ignores_height_under_xy() {
        let w = spread();
        let rules = |a, b| together_rules(&w, Metric::Xy, a, b);
        assert_eq!(rules(1, 2), ["Concurrent"]);
        assert!(rules(3, 4).is_empty());
        // A level apart no longer helps: 0.78 m, 0.5 m and 0.75 m in the plan are too close.
        assert_eq!(rules(5, 6), ["Concurrent"]);
        assert_eq!(rules(7, 8), ["Concurrent"]);
        assert_eq!(rules(11, 12), ["Concurrent"]);
        assert_eq!(rules(13, 14), ["Concurrent"]);
        assert!(rules(9, 10).is_empty());
        // The default model measures in the plan.
        assert_eq!(
            TeamModel::cmcp().concurrency.metric(),
            Some(Metric::Xy),
            "xy is the default"
        );
    }

    /// #31: `wall.big` at T = 2500 and a 599-brick wall overlapped bricks 0.796 m apart in the
    /// plan and a level apart, valid only when the height counts.
    #[test]
    fn bricks_0_796_m_apart_on_two_levels_overlap_only_under_xyz() {
        let text = "\
1 1 0 0 0.1 0
2 1 0.796 0 0.3 0
";
        let w = mason_wall::parse_cmcp(text, "levels", mason_wall::CmcpSizes::Yaml).unwrap();
        assert_eq!(together_rules(&w, Metric::Xy, 1, 2), ["Concurrent"]);
        assert!(together_rules(&w, Metric::Xyz, 1, 2).is_empty());
        let e = &schedule_violations(
            &w,
            &TeamModel::cmcp(),
            3,
            None,
            &Schedule {
                placements: vec![
                    Placement {
                        brick: BrickId(0),
                        uavs: vec![0],
                        start_s: 0.0,
                    },
                    Placement {
                        brick: BrickId(1),
                        uavs: vec![1],
                        start_s: 20.0,
                    },
                ],
            },
        )[0];
        assert!(e.to_string().contains("0.796 m apart (xy)"), "{e}");
    }

    #[test]
    fn a_brick_on_its_way_may_end_after_the_budget_and_earns_nothing() {
        let w = wall();
        let m = TeamModel::thesis();
        let (s, c) = base(&w, &m);
        let n = s.placements.len();
        let top = s.placements[n - 1].clone();
        let kind = m.of(w.brick(top.brick).kind);
        let end = (n - 1) as f64 * c + kind.place_s;
        let budget = Some(end - 1.0);
        assert_eq!(broken(&w, &m, budget, &s), ["Budget"]);
        let start = TeamStart {
            placed: vec![],
            committed: vec![top],
            uav_ready_s: vec![0.0; 3],
        };
        assert!(continuation_violations(&w, &m, 3, budget, &start, &s).is_empty());
        let eval = validate_continuation(&w, &m, 3, budget, &start, &s).unwrap();
        let all = validate_schedule(&w, &m, 3, None, &s).unwrap();
        assert_eq!(eval.reward, all.reward - kind.reward);
        assert_eq!(eval.makespan_s, end);
        // Placed by the budget, within the slack, it earns its reward.
        let budget = Some(at_the_slack(end));
        let eval = validate_continuation(&w, &m, 3, budget, &start, &s).unwrap();
        assert_eq!(eval.reward, all.reward);
        assert_eq!(
            validate_schedule(&w, &m, 3, budget, &s).unwrap().reward,
            all.reward
        );
    }

    #[test]
    fn schedules_from_every_planner_pass() {
        let w = wall();
        for model in [TeamModel::thesis(), TeamModel::cmcp()] {
            for (objective, budget) in [
                (Objective::Makespan, None),
                (Objective::Reward, Some(400.0)),
                (
                    Objective::Expected {
                        hazard_per_hour: 2.0,
                    },
                    Some(400.0),
                ),
            ] {
                let p = TeamProblem::new(&w, model.clone(), 3, budget, objective).unwrap();
                let searched = plan_schedule(&p, &Budget::unlimited(), 1);
                let small = mason_wall::builtin("thesis-2x5").unwrap().wall();
                let q = TeamProblem::new(&small, model.clone(), 2, budget, objective).unwrap();
                let exhaustive = exhaustive_schedule(&q, &Budget::nodes(200_000));
                for (wall, uavs, o) in [(&w, 3, searched), (&small, 2, exhaustive)] {
                    let s = o.schedule.expect("a schedule");
                    let found = schedule_violations(wall, &model, uavs, budget, &s);
                    assert!(found.is_empty(), "{} {objective}: {found:?}", model.name);
                    let eval = validate_schedule(wall, &model, uavs, budget, &s).unwrap();
                    assert!(claim_violations(&eval, Some(o.reward), Some(o.makespan_s)).is_empty());
                }
            }
        }
    }
}
