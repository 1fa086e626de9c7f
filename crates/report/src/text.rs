//! Plain-text figures and tables: mission clocks and durations, a mission's result
//! ([`result_table`]), a Monte Carlo summary ([`summary_table`]), and the comparison of two
//! policies over the same seeds ([`PolicyRow`], [`policy_table`]).

use mason_mission::{Event, EventKind, MissionResult, Spread, Summariser, Summary, UavState};

/// `m:ss.s` (a dash for a time that is not finite).
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

/// Milliseconds with sensible precision (seconds from 1 s on).
pub fn format_ms(ms: f64) -> String {
    if ms < 1.0 {
        format!("{ms:.3} ms")
    } else if ms < 1000.0 {
        format!("{ms:.1} ms")
    } else {
        format!("{:.2} s", ms / 1e3)
    }
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
    /// The figures of a streamed batch (streamed).
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clocks_read_as_minutes_and_seconds() {
        assert_eq!(clock(0.0), "0:00.0");
        assert_eq!(clock(320.6), "5:20.6");
        assert_eq!(clock(f64::NAN), "-");
    }
}
