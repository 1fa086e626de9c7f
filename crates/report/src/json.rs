//! The JSON that other tools read (DESIGN §7, README): walls, build orders, team schedules,
//! mission events (bricks as thesis ids) and a run's metrics. The CLI prints these and the
//! Python package returns them, so both say the same.

use mason_mission::{Coord, Event, EventKind, Faults, MissionResult, Summary, UavState};
use mason_order::schedule::{CheckedSchedule, Objective, TeamProblem};
use mason_order::{BuildProblem, CheckedPlan};
use mason_wall::{BrickId, Wall};
use serde::ser::{Serialize, SerializeMap, Serializer};
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
    serde_json::to_value(PlanDoc { problem, checked }).unwrap_or(Value::Null)
}

/// The wall's bricks with their supports and neighbours, by label.
pub fn wall_json(wall: &Wall) -> Value {
    serde_json::to_value(WallDoc(wall)).unwrap_or(Value::Null)
}

/// The schedule as JSON (README: "Team schedule JSON").
pub fn schedule_json(p: &TeamProblem<'_>, c: &CheckedSchedule, seed: u64) -> Value {
    serde_json::to_value(ScheduleDoc {
        problem: p,
        checked: c,
        seed,
    })
    .unwrap_or(Value::Null)
}

// The documents above serialise as they are written, so that printing one of a huge wall holds
// no tree of values in memory (a 400 000-brick schedule's tree took most of 1.8 GB). Keys go in
// sorted order, as `serde_json::Value`'s maps print them: both ways give the same text.

/// [`wall_json`] as a document that serialises as it is written.
pub struct WallDoc<'a>(pub &'a Wall);

/// [`plan_json`] as a document that serialises as it is written.
pub struct PlanDoc<'a, 'w> {
    /// The problem (wall and cost model).
    pub problem: &'a BuildProblem<'w>,
    /// The planner's checked outcome.
    pub checked: &'a CheckedPlan,
}

/// [`schedule_json`] as a document that serialises as it is written.
pub struct ScheduleDoc<'a, 'w> {
    /// The problem.
    pub problem: &'a TeamProblem<'w>,
    /// The checked schedule.
    pub checked: &'a CheckedSchedule,
    /// The search's seed.
    pub seed: u64,
}

/// Serialises the items of an iterator as a sequence, without collecting them.
struct Seq<I>(std::cell::RefCell<Option<I>>);

impl<I> Seq<I> {
    fn of(items: I) -> Self {
        Seq(std::cell::RefCell::new(Some(items)))
    }
}

impl<I: Iterator<Item = T>, T: Serialize> Serialize for Seq<I> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let items = self.0.borrow_mut().take();
        s.collect_seq(items.into_iter().flatten())
    }
}

/// A number as JSON: whole values as integers.
#[derive(Clone, Copy)]
struct Num(f64);

impl Serialize for Num {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let x = self.0;
        if x.fract() == 0.0 && x.abs() < 1e15 {
            s.serialize_i64(x as i64)
        } else {
            s.serialize_f64(x)
        }
    }
}

/// A small nested document with its keys sorted, as a `Value` prints them.
fn sorted<T: Serialize>(v: &T) -> Value {
    serde_json::to_value(v).unwrap_or(Value::Null)
}

fn labels<'a>(wall: &'a Wall, ids: &'a [BrickId]) -> Seq<impl Iterator<Item = u32> + 'a> {
    Seq::of(ids.iter().map(|&i| wall.brick(i).label))
}

impl Serialize for WallDoc<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let wall = self.0;
        let bricks = Seq::of(wall.ids().map(|id| BrickDoc(wall, id)));
        let mut m = s.serialize_map(Some(4))?;
        m.serialize_entry("bricks", &bricks)?;
        m.serialize_entry("levels", &wall.levels())?;
        m.serialize_entry("name", wall.name())?;
        m.serialize_entry("warnings", wall.warnings())?;
        m.end()
    }
}

struct BrickDoc<'a>(&'a Wall, BrickId);

impl Serialize for BrickDoc<'_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let (wall, id) = (self.0, self.1);
        let b = wall.brick(id);
        let f = &b.footprint;
        let mut m = s.serialize_map(Some(7))?;
        m.serialize_entry("footprint", &[f.x0, f.x1, f.y0, f.y1])?;
        m.serialize_entry("id", &b.label)?;
        m.serialize_entry("level", &b.level)?;
        m.serialize_entry("neighbours", &labels(wall, wall.neighbours(id)))?;
        m.serialize_entry("segment", &b.segment)?;
        m.serialize_entry("supports", &labels(wall, wall.supports(id)))?;
        m.serialize_entry("type", &b.kind)?;
        m.end()
    }
}

impl Serialize for PlanDoc<'_, '_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let wall = self.problem.wall();
        let o = &self.checked.outcome;
        let steps = Seq::of(
            self.checked
                .evaluation
                .iter()
                .flat_map(|e| &e.steps)
                .map(|st| {
                    json!({
                        "id": wall.brick(st.brick).label,
                        "placed_neighbours": st.placed_neighbours,
                        "cost": st.cost,
                    })
                }),
        );
        let order = o.order.as_deref().map(|ord| labels(wall, ord));
        let mut m = s.serialize_map(Some(8))?;
        m.serialize_entry("model", &sorted(self.problem.model()))?;
        m.serialize_entry("order", &order)?;
        m.serialize_entry("planner", &o.planner)?;
        m.serialize_entry(
            "stats",
            &json!({
                "elapsed_ms": o.stats.elapsed.as_secs_f64() * 1e3,
                "nodes": o.stats.nodes,
                "leaves": o.stats.leaves,
            }),
        )?;
        m.serialize_entry("status", &o.status)?;
        m.serialize_entry("steps", &steps)?;
        m.serialize_entry(
            "total_cost",
            &self.checked.evaluation.as_ref().map(|e| e.total_cost),
        )?;
        m.serialize_entry("wall", &WallDoc(wall))?;
        m.end()
    }
}

impl Serialize for ScheduleDoc<'_, '_> {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let p = self.problem;
        let wall = p.wall();
        let c = self.checked;
        let o = &c.outcome;
        let rows = Seq::of(
            o.schedule
                .iter()
                .flat_map(|s| &s.placements)
                .flat_map(|pl| {
                    pl.uavs.iter().map(move |&u| {
                        let b = wall.brick(pl.brick);
                        json!({
                            "uav": u,
                            "brick": b.label,
                            "type": b.kind,
                            "start_s": Num(pl.start_s),
                            "end_s": Num(pl.start_s + p.place_s(pl.brick)),
                        })
                    })
                }),
        );
        let hazard = match p.objective() {
            Objective::Expected { hazard_per_hour } => Some(hazard_per_hour),
            _ => None,
        };
        let mut m = s.serialize_map(Some(19))?;
        m.serialize_entry("bound", &Num(o.bound))?;
        m.serialize_entry("bricks_placed", &c.evaluation.bricks)?;
        m.serialize_entry("bricks_total", &wall.len())?;
        m.serialize_entry("budget_s", &p.budget_s().map(Num))?;
        m.serialize_entry("expected_reward", &o.expected_reward)?;
        m.serialize_entry("gap", &Num(o.gap(p.objective())))?;
        m.serialize_entry("makespan_s", &Num(o.makespan_s))?;
        // The distance rule's metric (`xy` or `xyz`; null under the zone rule).
        m.serialize_entry("metric", &p.model().concurrency.metric())?;
        m.serialize_entry("model", &p.model().name)?;
        m.serialize_entry("objective", p.objective().name())?;
        m.serialize_entry("reward", &Num(o.reward))?;
        m.serialize_entry("schedule", &rows)?;
        m.serialize_entry("seed", &self.seed)?;
        m.serialize_entry(
            "stats",
            &json!({
                "elapsed_ms": o.stats.elapsed.as_secs_f64() * 1e3,
                "decodes": o.stats.decodes,
                "improvements": o.stats.improvements,
            }),
        )?;
        m.serialize_entry("status", &o.status)?;
        m.serialize_entry("team_model", &sorted(p.model()))?;
        m.serialize_entry("uav_hazard_per_hour", &hazard)?;
        m.serialize_entry("uavs", &p.uavs())?;
        m.serialize_entry("wall", &WallDoc(wall))?;
        m.end()
    }
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
