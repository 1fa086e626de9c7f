//! `mason simulate`: fly a build order with a UAV team, once or as a Monte Carlo batch.

use crate::fail::{input_error, no_solution, CliResult};
use mason_mission::{
    check_trace, for_each_run, make_policy, run_many, simulate, slot_length, Coord, Event,
    EventKind, Faults, MissionConfig, MissionInput, MissionResult, MissionStatus, Spread,
    Summariser, Summary, UavFailure, UavState, Window,
};
use mason_order::CostModel;
use mason_wall::{BrickId, Wall};
use serde::Deserialize;
use serde_json::{json, Value};
use std::path::Path;

/// Fault options as written on the command line or in `--faults F.toml`.
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FaultSpec {
    /// Probability per grasp attempt.
    pub grasp_fail: Option<f64>,
    /// Probability per detection attempt.
    pub detect_fail: Option<f64>,
    /// `U@T` entries.
    #[serde(default)]
    pub uav_fail: Vec<String>,
    /// Failures per hour.
    pub uav_hazard: Option<f64>,
    /// `A-B` entries.
    #[serde(default)]
    pub blackout: Vec<String>,
    /// Probability per message.
    pub msg_loss: Option<f64>,
    /// Seconds.
    pub latency: Option<f64>,
}

impl FaultSpec {
    /// Reads a faults TOML file and checks its values on their own, for a team of `uavs`
    /// (errors name the file, and the line or the key).
    pub fn read_checked(path: &Path, uavs: usize) -> CliResult<FaultSpec> {
        let spec: FaultSpec = crate::input::read_toml(path)?;
        let in_file = |e: crate::fail::Failure| {
            let msg = e.message.replace("--uav-fail", "uav_fail");
            input_error(format!(
                "{}: {}",
                path.display(),
                msg.replace("--blackout", "blackout")
            ))
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
                .map_err(|e| input_error(format!("{}: {e}", path.display())))?;
        }
        Ok(spec)
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

    /// The faults, with `U@T` and `A-B` parsed.
    pub fn resolve(&self) -> CliResult<Faults> {
        let num = |what: &str, s: &str| -> CliResult<f64> {
            s.trim()
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite())
                .ok_or_else(|| input_error(format!("{what}: `{s}` is not a number")))
        };
        let mut f = Faults {
            grasp_fail: self.grasp_fail.unwrap_or(0.0),
            detect_fail: self.detect_fail.unwrap_or(0.0),
            uav_hazard: self.uav_hazard.unwrap_or(0.0),
            msg_loss: self.msg_loss.unwrap_or(0.0),
            latency: self.latency.unwrap_or(0.0),
            ..Faults::default()
        };
        for s in &self.uav_fail {
            let (u, t) = s.split_once('@').ok_or_else(|| {
                input_error(format!("--uav-fail `{s}`: expected U@T, e.g. 1@120"))
            })?;
            let uav = u
                .trim()
                .parse::<usize>()
                .map_err(|_| input_error(format!("--uav-fail `{s}`: `{u}` is not a UAV number")))?;
            f.uav_fail.push(UavFailure {
                uav,
                at: num("--uav-fail", t)?,
            });
        }
        for s in &self.blackout {
            let (a, b) = s.split_once('-').ok_or_else(|| {
                input_error(format!("--blackout `{s}`: expected A-B, e.g. 100-160"))
            })?;
            f.blackout.push(Window {
                from: num("--blackout", a)?,
                to: num("--blackout", b)?,
            });
        }
        Ok(f)
    }
}

/// Reads a mission TOML file and checks it for a team of `uavs` (errors name the file, and the
/// line or the key).
pub fn read_mission(path: &Path, uavs: usize) -> CliResult<MissionConfig> {
    let mut config: MissionConfig = crate::input::read_toml(path)?;
    let file_uavs = config.uavs;
    config.uavs = uavs;
    if uavs >= 1 && uavs <= config.arena.uav_starts.len() {
        config
            .validate()
            .map_err(|e| input_error(format!("{}: {e}", path.display())))?;
    }
    config.uavs = file_uavs;
    Ok(config)
}

/// Validates a configuration and computes the windows slot for a wall.
pub fn prepare(wall: &Wall, model: &CostModel, config: &MissionConfig) -> CliResult<f64> {
    config
        .validate()
        .map_err(|e| input_error(format!("mission: {e}")))?;
    slot_length(wall, model, config).map_err(|e| input_error(format!("--{e}")))
}

/// One checked mission and its trace.
pub fn fly_once(
    input: MissionInput,
    coord: Coord,
    slot: f64,
    seed: u64,
) -> CliResult<(MissionResult, Vec<Event>)> {
    let mut trace = Vec::new();
    let r = simulate(input, make_policy(coord, slot).as_mut(), seed, &mut trace);
    check_trace(input.wall, input.config.uavs, &trace).map_err(|e| {
        input_error(format!(
            "internal error: mission trace failed check_trace: {e}"
        ))
    })?;
    Ok((r, trace))
}

/// A Monte Carlo batch, every trace checked.
pub fn fly_many(
    input: MissionInput,
    coord: Coord,
    slot: f64,
    seed: u64,
    runs: usize,
    progress: &(dyn Fn() + Sync),
) -> CliResult<Vec<MissionResult>> {
    run_many(input, coord, slot, seed, runs, progress).map_err(|(s, e)| {
        input_error(format!(
            "internal error: mission seed {s} failed check_trace: {e}"
        ))
    })
}

/// A Monte Carlo batch streamed into a [`Summariser`] (memory flat in `runs`), every trace
/// checked; `reward_by_t` also summarises the reward placed by that time. Off a terminal,
/// `lines` reports progress on stderr.
#[allow(clippy::too_many_arguments)]
pub fn fly_summary(
    input: MissionInput,
    coord: Coord,
    slot: f64,
    seed: u64,
    runs: usize,
    reward_by_t: Option<f64>,
    progress: &(dyn Fn() + Sync),
    lines: &mut crate::progress::Lines,
) -> CliResult<Summariser> {
    let mut summary = Summariser::new(reward_by_t);
    let mut done = 0u64;
    for_each_run(input, coord, slot, seed, runs, progress, &mut |r| {
        summary.push(r);
        done += 1;
        lines.at(done);
    })
    .map_err(|(s, e)| {
        input_error(format!(
            "internal error: mission seed {s} failed check_trace: {e}"
        ))
    })?;
    Ok(summary)
}

/// `m:ss.s`.
pub fn clock(t: f64) -> String {
    if !t.is_finite() {
        return "-".into();
    }
    let m = (t / 60.0).floor();
    format!("{}:{:04.1}", m as u64, t - 60.0 * m)
}

/// `mean [p5, p95]` of a time spread, as clocks.
pub fn spread_clock(s: &Spread) -> String {
    format!("{} [{}, {}]", clock(s.mean), clock(s.p5), clock(s.p95))
}

/// The trace event as the JSON of DESIGN §7 (bricks as thesis ids).
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
    for (k, x) in extra.as_object().expect("object") {
        v[k] = x.clone();
    }
    v
}

/// The metrics as JSON.
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

/// A readable single-run report.
pub fn result_table(r: &MissionResult, trace: &[Event]) -> String {
    let m = &r.metrics;
    let mut s = format!(
        "status: {:?}\nmakespan: {} ({} s); mission end {}\nbricks placed: {}/{}, reward {}, lost {}, UAVs failed {}\nzone utilisation: {:.1} %\n",
        r.status,
        m.makespan_s.map_or("-".into(), clock),
        m.makespan_s.map_or("-".into(), |t| format!("{t:.1}")),
        clock(m.end_s),
        m.bricks_placed,
        m.bricks_total,
        m.reward,
        m.bricks_lost,
        m.uavs_failed,
        m.zone_utilisation * 100.0
    )
    .to_lowercase();
    s.push_str("seconds per UAV:   flying  detect+grasp  waiting  placing  idle/ground\n");
    for (u, t) in m.time_in_state.iter().enumerate() {
        let sum = |states: &[UavState]| states.iter().map(|s| t[s.index()]).sum::<f64>();
        s.push_str(&format!(
            "  UAV {u}        {:>8.1} {:>13.1} {:>8.1} {:>8.1} {:>12.1}\n",
            sum(&[
                UavState::TakeOff,
                UavState::FlyToPile,
                UavState::FlyToWallWait,
                UavState::Land,
                UavState::SafeLand
            ]),
            sum(&[UavState::Detect, UavState::FlyAbove, UavState::Grasp]),
            sum(&[UavState::WaitForZone]),
            sum(&[UavState::EnterAndPlace]),
            sum(&[
                UavState::Check,
                UavState::ChooseBrick,
                UavState::Landed,
                UavState::Down
            ]),
        ));
    }
    let switches = trace
        .iter()
        .filter(|e| matches!(e.kind, EventKind::Comm { .. }))
        .count();
    if switches > 0 {
        s.push_str(&format!("coordination mode switches: {switches}\n"));
    }
    s.push_str("trace checked by mission::check_trace\n");
    s
}

/// A Monte Carlo summary table.
pub fn summary_table(s: &Summary) -> String {
    format!(
        "runs: {}, walls completed: {}\n{:<18} {:>10} {:>10} {:>10}\n{:<18} {:>10} {:>10} {:>10}\n{:<18} {:>10.2} {:>10.2} {:>10.2}\n{:<18} {:>10.2} {:>10.2} {:>10.2}\n{:<18} {:>9.1}% {:>9.1}% {:>9.1}%\nevery trace checked by mission::check_trace\n",
        s.runs,
        s.completed,
        "",
        "mean",
        "p5",
        "p95",
        "makespan",
        clock(s.makespan_s.mean),
        clock(s.makespan_s.p5),
        clock(s.makespan_s.p95),
        "bricks placed",
        s.bricks_placed.mean,
        s.bricks_placed.p5,
        s.bricks_placed.p95,
        "reward",
        s.reward.mean,
        s.reward.p5,
        s.reward.p95,
        "zone utilisation",
        s.zone_utilisation.mean * 100.0,
        s.zone_utilisation.p5 * 100.0,
        s.zone_utilisation.p95 * 100.0,
    )
}

/// A replan that failed `order::team::validate_continuation` is a bug: reported, exit 2.
pub fn check_replans(r: Option<&mason_mission::ScheduleReplanner>) -> CliResult<()> {
    match r.map(|r| r.rejected.load(std::sync::atomic::Ordering::Relaxed)) {
        Some(n) if n > 0 => Err(input_error(format!(
            "internal error: {n} replans failed order::team::validate_continuation"
        ))),
        _ => Ok(()),
    }
}

/// One policy's Monte Carlo figures in a static-vs-replanned comparison.
#[derive(Clone, Debug, serde::Serialize)]
pub struct PolicyRow {
    /// `static` or `replanned`.
    pub policy: String,
    /// The usual summary.
    pub summary: Summary,
    /// Reward placed by the budget, when there is one.
    pub reward_by_budget: Option<Spread>,
    /// Mean re-plans per mission.
    pub replans_mean: f64,
}

impl PolicyRow {
    /// The figures of a streamed batch (see [`fly_summary`]).
    pub fn of_summary(policy: &str, s: &Summariser) -> Self {
        PolicyRow {
            policy: policy.to_string(),
            summary: s.summary(),
            reward_by_budget: s.reward_by(),
            replans_mean: s.replans_mean(),
        }
    }

    /// The figures of `results`.
    pub fn of(policy: &str, results: &[MissionResult], budget: Option<f64>) -> Self {
        PolicyRow {
            policy: policy.to_string(),
            summary: mason_mission::summarise(results),
            reward_by_budget: budget.map(|t| mason_mission::reward_by(results, t)),
            replans_mean: results
                .iter()
                .map(|r| r.metrics.replans as f64)
                .sum::<f64>()
                / results.len().max(1) as f64,
        }
    }
}

/// The comparison as a table: one column per policy.
pub fn policy_table(rows: &[PolicyRow], budget: Option<f64>) -> String {
    let mut out = format!("{:<26}", "");
    for r in rows {
        out.push_str(&format!(" {:>22}", r.policy));
    }
    out.push('\n');
    let mut line = |name: &str, cell: &dyn Fn(&PolicyRow) -> String| {
        out.push_str(&format!("{name:<26}"));
        for r in rows {
            out.push_str(&format!(" {:>22}", cell(r)));
        }
        out.push('\n');
    };
    line("walls completed", &|r| {
        format!("{} of {}", r.summary.completed, r.summary.runs)
    });
    line("makespan (completed)", &|r| {
        spread_clock(&r.summary.makespan_s)
    });
    line("bricks placed, mean", &|r| {
        format!("{:.2}", r.summary.bricks_placed.mean)
    });
    line("reward, mean", &|r| format!("{:.2}", r.summary.reward.mean));
    if let Some(t) = budget {
        line(&format!("reward by {t} s, mean"), &|r| {
            r.reward_by_budget
                .map_or("-".into(), |s| format!("{:.2}", s.mean))
        });
    }
    line("re-plans per mission", &|r| {
        format!("{:.2}", r.replans_mean)
    });
    out.push_str("every trace checked by mission::check_trace\n");
    out
}

/// Exit 1 when the wall was not completed (single run).
pub fn exit_for(r: &MissionResult) -> CliResult<()> {
    match r.status {
        MissionStatus::Complete => Ok(()),
        MissionStatus::Incomplete => Err(no_solution(format!(
            "mission incomplete: {}/{} bricks placed",
            r.metrics.bricks_placed, r.metrics.bricks_total
        ))),
        MissionStatus::Timeout => Err(no_solution(format!(
            "mission hit the time limit: {}/{} bricks placed",
            r.metrics.bricks_placed, r.metrics.bricks_total
        ))),
    }
}
