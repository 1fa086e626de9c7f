//! The JSON of a mission that other tools read (DESIGN §7): events with bricks as thesis ids,
//! and a run's metrics.

use mason_mission::{Event, EventKind, MissionResult, UavState};
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
