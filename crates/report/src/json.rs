//! The JSON that other tools read (DESIGN §7, README): walls, build orders, team schedules,
//! mission events (bricks as thesis ids) and a run's metrics. The CLI prints these and the
//! Python package returns them, so both say the same.

use mason_mission::{Coord, Event, EventKind, Faults, MissionResult, Summary, UavState};
use mason_order::schedule::{CheckedSchedule, Objective, TeamProblem};
use mason_order::{BuildProblem, CheckedPlan};
use mason_wall::{BrickId, Wall};
use serde_json::{json, Value};

/// The trace event as JSON (bricks as thesis ids): `t`, `uav`, `kind` and the kind's fields.
pub fn event_json(wall: &Wall, e: &Event) -> Value {
    let label = |b: BrickId| wall.brick(b).label;
    let mut v = json!({"t": e.t, "uav": e.uav});
    let extra = match e.kind {
        EventKind::State {
            state,
            outcome,
            x,
            y,
        } => {
            json!({"kind": "state", "state": state.name(), "outcome": outcome, "x": x, "y": y})
        }
        EventKind::Grasp { brick } => json!({"kind": "grasp", "brick": label(brick)}),
        EventKind::Place { brick } => json!({"kind": "place", "brick": label(brick)}),
        EventKind::Lost { brick } => json!({"kind": "lost", "brick": label(brick)}),
        EventKind::ZoneEnter => json!({"kind": "zone_enter"}),
        EventKind::ZoneLeave => json!({"kind": "zone_leave"}),
        EventKind::Fail => json!({"kind": "fail"}),
        EventKind::Replan { bricks } => json!({"kind": "replan", "bricks": bricks}),
        EventKind::Comm { mode } => json!({"kind": "comm", "mode": mode}),
    };
    if let (Some(v), Value::Object(extra)) = (v.as_object_mut(), extra) {
        v.extend(extra);
    }
    v
}

/// A run's metrics as JSON.
pub fn metrics_json(r: &MissionResult) -> Value {
    let m = &r.metrics;
    let per_uav: Vec<Value> = m
        .time_in_state
        .iter()
        .map(|times| {
            let mut o = serde_json::Map::new();
            for s in UavState::ALL {
                if times[s.index()] > 0.0 {
                    o.insert(s.name().into(), json!(times[s.index()]));
                }
            }
            Value::Object(o)
        })
        .collect();
    json!({
        "status": r.status,
        "makespan_s": m.makespan_s,
        "end_s": m.end_s,
        "bricks_placed": m.bricks_placed,
        "bricks_total": m.bricks_total,
        "reward": m.reward,
        "reward_over_time": m.reward_over_time,
        "time_in_state_s": per_uav,
        "waiting_s": m.time_in_state.iter().map(|t| t[UavState::WaitForZone.index()]).collect::<Vec<_>>(),
        "zone_busy_s": m.zone_busy_s,
        "zone_utilisation": m.zone_utilisation,
        "bricks_lost": m.bricks_lost,
        "uavs_failed": m.uavs_failed,
    })
}

/// The plan as the JSON of DESIGN §7, with the wall and the model so it can be checked alone.
pub fn plan_json(problem: &BuildProblem<'_>, checked: &CheckedPlan) -> Value {
    let wall = problem.wall();
    let o = &checked.outcome;
    let steps: Vec<Value> = checked
        .evaluation
        .iter()
        .flat_map(|e| &e.steps)
        .map(|s| {
            json!({
                "id": wall.brick(s.brick).label,
                "placed_neighbours": s.placed_neighbours,
                "cost": s.cost,
            })
        })
        .collect();
    json!({
        "planner": o.planner,
        "status": o.status,
        "order": o.order.as_ref().map(|ord| ord.iter().map(|&b| wall.brick(b).label).collect::<Vec<_>>()),
        "total_cost": checked.evaluation.as_ref().map(|e| e.total_cost),
        "steps": steps,
        "stats": {
            "elapsed_ms": o.stats.elapsed.as_secs_f64() * 1e3,
            "nodes": o.stats.nodes,
            "leaves": o.stats.leaves,
        },
        "model": problem.model(),
        "wall": wall_json(wall),
    })
}

/// The wall's bricks with their supports and neighbours, by label.
pub fn wall_json(wall: &Wall) -> Value {
    let labels =
        |ids: &[mason_wall::BrickId]| ids.iter().map(|&i| wall.brick(i).label).collect::<Vec<_>>();
    let bricks: Vec<Value> = wall
        .ids()
        .map(|id| {
            let b = wall.brick(id);
            json!({
                "id": b.label,
                "type": b.kind,
                "level": b.level,
                "segment": b.segment,
                "footprint": [b.footprint.x0, b.footprint.x1, b.footprint.y0, b.footprint.y1],
                "supports": labels(wall.supports(id)),
                "neighbours": labels(wall.neighbours(id)),
            })
        })
        .collect();
    json!({ "name": wall.name(), "levels": wall.levels(), "bricks": bricks, "warnings": wall.warnings() })
}

/// A number as JSON: whole values as integers.
fn num(x: f64) -> Value {
    if x.fract() == 0.0 && x.abs() < 1e15 {
        json!(x as i64)
    } else {
        json!(x)
    }
}

/// The schedule as JSON (README: "Team schedule JSON").
pub fn schedule_json(p: &TeamProblem<'_>, c: &CheckedSchedule, seed: u64) -> Value {
    let wall = p.wall();
    let o = &c.outcome;
    let rows: Vec<Value> = o
        .schedule
        .iter()
        .flat_map(|s| &s.placements)
        .flat_map(|pl| {
            pl.uavs.iter().map(move |&u| {
                json!({
                    "uav": u,
                    "brick": wall.brick(pl.brick).label,
                    "type": wall.brick(pl.brick).kind,
                    "start_s": num(pl.start_s),
                    "end_s": num(pl.start_s + p.place_s(pl.brick)),
                })
            })
        })
        .collect();
    json!({
        "objective": p.objective().name(),
        "model": p.model().name,
        "uavs": p.uavs(),
        "budget_s": p.budget_s().map(num),
        "uav_hazard_per_hour": match p.objective() { Objective::Expected { hazard_per_hour } => Some(hazard_per_hour), _ => None },
        "seed": seed,
        "reward": num(o.reward),
        "expected_reward": o.expected_reward,
        "bricks_placed": c.evaluation.bricks,
        "bricks_total": wall.len(),
        "makespan_s": num(o.makespan_s),
        "bound": num(o.bound),
        "gap": num(o.gap(p.objective())),
        "status": o.status,
        "schedule": rows,
        "stats": {
            "elapsed_ms": o.stats.elapsed.as_secs_f64() * 1e3,
            "decodes": o.stats.decodes,
            "improvements": o.stats.improvements,
        },
        "team_model": p.model(),
        "wall": wall_json(wall),
    })
}

/// What a simulated mission was flown with: the head of `simulate --json`.
pub struct RunSetting<'a> {
    /// The wall.
    pub wall: &'a Wall,
    /// Team size.
    pub uavs: usize,
    /// Coordination policy.
    pub coord: Coord,
    /// The planner of the order, as on the command line.
    pub planner: &'a str,
    /// The shared build order.
    pub order: &'a [BrickId],
    /// The seed (of the first run, for a batch).
    pub seed: u64,
    /// The windows slot (s).
    pub slot_s: f64,
    /// The faults.
    pub faults: &'a Faults,
}

/// One flown mission as `simulate --json` prints it: its setting, metrics and events.
pub fn simulate_json(s: &RunSetting<'_>, r: &MissionResult, trace: &[Event]) -> Value {
    let events: Vec<Value> = trace.iter().map(|e| event_json(s.wall, e)).collect();
    json!({
        "wall": s.wall.name(), "uavs": s.uavs, "coord": s.coord, "planner": s.planner,
        "order": s.order.iter().map(|b| s.wall.brick(*b).label).collect::<Vec<_>>(),
        "seed": s.seed, "slot_s": s.slot_s, "faults": s.faults,
        "metrics": metrics_json(r), "events": events,
    })
}

/// A Monte Carlo batch as `simulate --runs N --json` prints it.
pub fn runs_json(s: &RunSetting<'_>, summary: &Summary) -> Value {
    json!({
        "wall": s.wall.name(), "uavs": s.uavs, "coord": s.coord, "planner": s.planner,
        "first_seed": s.seed, "slot_s": s.slot_s, "faults": s.faults, "summary": summary,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn events_name_bricks_by_thesis_id() {
        let wall = mason_wall::builtin("thesis-2x5").unwrap().wall();
        let b = wall.ids().nth(6).unwrap();
        let e = Event {
            t: 3.0,
            uav: 1,
            kind: EventKind::Place { brick: b },
        };
        let v = event_json(&wall, &e);
        assert_eq!(v["kind"], "place");
        assert_eq!(v["brick"], wall.brick(b).label);
        assert_eq!(v["uav"], 1);
    }
}
