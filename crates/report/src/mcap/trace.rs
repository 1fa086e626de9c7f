//! A simulated mission's trace turned into a log ([`write_trace`], [`mission_mcap`]): every
//! event, and each UAV's poses, which the trace does not hold and are rebuilt here. The trace's
//! state events give where each UAV is (x, y); between two of them it flies a straight leg,
//! sampled at the ticks the [`PoseSampler`] asks for; its altitude comes from the project's one altitude
//! rule, [`mason_mission::altitude`] (on the ground before take-off, climbing through it).
//!
//! The heading is the sampler's, shared with live agents: along the move from the last pose
//! logged. Before the sampler, this conversion headed every pose of a leg along the whole leg,
//! whose end it knows; on a straight leg the two are one direction up to float rounding
//! (at most 2.3e-11 rad over 5.6 million poses of simulated missions, none of which changed
//! the quaternion as written, to 1e-9).

use super::pose_sampler::{ticks_between, PoseSampler};
use super::{LogMeta, McapLog, McapLogError, UavPose};
use mason_mission::{altitude, Event, EventKind};

/// Cruise altitude of UAV `i` (m): the project's one altitude rule ([`mason_mission::altitude`]).
pub use mason_mission::cruise_altitude;
use std::io::{Cursor, Seek, Write};

/// A position (x east, y north, z up; m).
type Position = (f64, f64, f64);

/// A pose to log: mission time, UAV, pose.
pub(crate) type Sample = (f64, u32, UavPose);

/// Writes a simulated mission's trace into `log`, ending at `end_s`: every event, and each
/// UAV's poses as its [`PoseSampler`] decides: at each of its state events, at the ticks of
/// [`POSE_RATE_HZ`](super::POSE_RATE_HZ) (`k / POSE_RATE_HZ`) along every leg between two of
/// them where it moves (straight, at constant speed), and a last pose at `end_s`. The trace's
/// state events give the positions (x, y); z is [`cruise_altitude`] in the air and 0 on the
/// ground; the heading follows the last move. The trace is taken in time order, as the
/// simulator emits it; poses and events are merged in time order (at one instant, the poses
/// first).
pub fn write_trace<W: Write + Seek>(
    log: &mut McapLog<'_, W>,
    trace: &[Event],
    end_s: f64,
) -> Result<(), McapLogError> {
    let samples = trace_poses(log.uavs(), trace, end_s)?;
    let mut events = trace.iter().peekable();
    for (t, uav, p) in samples {
        while let Some(e) = events.next_if(|e| e.t < t) {
            log.event(e)?;
        }
        log.pose(t, uav, p)?;
    }
    for e in events {
        log.event(e)?;
    }
    Ok(())
}

/// Every UAV's poses in a team of `uavs` (see [`write_trace`]), in time order: at one time,
/// UAVs in order, and a UAV's poses in the order made. Shared with the ROS 2 bag.
pub(crate) fn trace_poses(
    uavs: usize,
    trace: &[Event],
    end_s: f64,
) -> Result<Vec<Sample>, McapLogError> {
    let mut samplers: Vec<PoseSampler> = (0..uavs as u32).map(PoseSampler::new).collect();
    // Where each UAV's current leg starts: its last state event's time and position.
    let mut leg_start: Vec<Option<(f64, Position)>> = vec![None; uavs];
    let mut samples: Vec<Sample> = Vec::new();
    for e in trace {
        let EventKind::State { state, x, y, .. } = e.kind else {
            continue;
        };
        let i = e.uav as usize;
        if i >= uavs {
            return Err(McapLogError::UnknownUav { uav: e.uav, uavs });
        }
        let here = (x, y, altitude(e.uav, state));
        if let Some((t0, from)) = leg_start[i] {
            fly_leg(&mut samplers[i], (t0, from), (e.t, here), &mut samples);
        }
        samplers[i].mark_due();
        take(&mut samplers[i], e.t, here, &mut samples);
        leg_start[i] = Some((e.t, here));
    }
    for (sampler, start) in samplers.iter_mut().zip(&leg_start) {
        if let Some((t, p)) = *start {
            if end_s > t {
                sampler.mark_due();
                take(sampler, end_s, p, &mut samples);
            }
        }
    }
    // Stable: at one time, UAVs in order, and a UAV's samples in the order made.
    samples.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    Ok(samples)
}

/// The poses along a straight leg flown at constant speed from `from` to `to` (times and
/// positions), strictly between its ends, at the ticks the sampler is due; none when the UAV
/// does not move.
fn fly_leg(
    sampler: &mut PoseSampler,
    (t0, from): (f64, Position),
    (t1, to): (f64, Position),
    samples: &mut Vec<Sample>,
) {
    let (dx, dy, dz) = (to.0 - from.0, to.1 - from.1, to.2 - from.2);
    let moving = dx != 0.0 || dy != 0.0 || to.2 != from.2;
    if !moving {
        return;
    }
    for t in ticks_between(t0, t1) {
        let f = (t - t0) / (t1 - t0);
        let p = (from.0 + dx * f, from.1 + dy * f, from.2 + dz * f);
        take(sampler, t, p, samples);
    }
}

/// The sampler's pose at `t` at `p`, if one is due.
fn take(sampler: &mut PoseSampler, t: f64, p: Position, samples: &mut Vec<Sample>) {
    if let Some(pose) = sampler.sample(t, p) {
        samples.push((t, sampler.uav(), pose));
    }
}

/// The MCAP log of a simulated mission (see [`write_trace`]) as bytes.
pub fn mission_mcap(
    meta: &LogMeta<'_>,
    trace: &[Event],
    end_s: f64,
) -> Result<Vec<u8>, McapLogError> {
    let mut log = McapLog::new(Cursor::new(Vec::new()), meta)?;
    write_trace(&mut log, trace, end_s)?;
    Ok(log.finish()?.into_inner())
}

#[cfg(test)]
mod tests {
    use super::*;
    use mason_mission::{Arena, UavState};
    use std::f64::consts::FRAC_PI_2;

    fn state(t: f64, uav: u32, state: UavState, x: f64, y: f64) -> Event {
        let kind = EventKind::State {
            state,
            outcome: "ok",
            x,
            y,
        };
        Event { t, uav, kind }
    }

    #[test]
    fn legs_are_sampled_at_the_ticks_heading_along_them() {
        let wall = mason_wall::parse_layer_text("R G", "two").unwrap();
        let arena = Arena::default();
        let meta = LogMeta {
            mission_id: "legs",
            uavs: 2,
            arena: &arena,
            wall: &wall,
        };
        let cruise = cruise_altitude(1);
        // UAV 1 climbs in place, flies 4 m north, hovers; UAV 0 logs nothing.
        let trace = [
            state(0.3, 1, UavState::TakeOff, 10.0, 10.0),
            state(1.2, 1, UavState::FlyToPile, 10.0, 10.0),
            state(3.0, 1, UavState::Detect, 10.0, 14.0),
            state(4.0, 1, UavState::Grasp, 10.0, 14.0),
        ];
        let poses = trace_poses(meta.uavs, &trace, 5.0).unwrap();
        let times: Vec<f64> = poses.iter().map(|p| p.0).collect();
        // Every state event, the ticks inside each leg that moves (none while hovering), the end.
        assert_eq!(
            times,
            [0.3, 0.5, 1.0, 1.2, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0],
            "{poses:?}"
        );
        assert!(poses.iter().all(|p| p.1 == 1));
        let at = |t: f64| poses.iter().find(|p| p.0 == t).unwrap().2;
        // The climb: z along the leg, heading kept (east).
        assert!((at(0.5).z - cruise * 0.2 / 0.9).abs() < 1e-12);
        assert_eq!(at(1.2).z, cruise);
        assert!([0.3, 0.5, 1.0, 1.2].iter().all(|&t| at(t).yaw == 0.0));
        // The flight north: y along the leg, heading north, kept while hovering.
        assert!((at(2.0).y - (10.0 + 4.0 * 0.8 / 1.8)).abs() < 1e-12);
        for t in [1.5, 2.0, 2.5, 3.0, 4.0, 5.0] {
            assert!((at(t).yaw - FRAC_PI_2).abs() < 1e-12, "{t}");
        }
        assert_eq!((at(5.0).x, at(5.0).y, at(5.0).z), (10.0, 14.0, cruise));
    }

    #[test]
    fn a_uav_outside_the_team_is_refused() {
        let wall = mason_wall::parse_layer_text("R", "one").unwrap();
        let arena = Arena::default();
        let meta = LogMeta {
            mission_id: "stranger",
            uavs: 1,
            arena: &arena,
            wall: &wall,
        };
        let trace = [state(0.0, 1, UavState::Check, 10.0, 10.0)];
        assert!(matches!(
            mission_mcap(&meta, &trace, 1.0),
            Err(McapLogError::UnknownUav { uav: 1, uavs: 1 })
        ));
    }
}
