//! One mission flown and its trace checked by [`crate::check_trace`], the independent oracle.

use crate::{
    check_trace, make_policy, simulate, Coord, Event, MissionInput, MissionResult, TraceError,
};

/// Flies `input` once with `coord` (windows slot `slot` s) from `seed`, and checks the trace
/// (an error is a simulator bug, never a result, except [`TraceError::Flooded`]: a mission
/// stopped at its event cap, whose durations are too short to make progress).
pub fn fly_checked(
    input: MissionInput<'_>,
    coord: Coord,
    slot: f64,
    seed: u64,
) -> Result<(MissionResult, Vec<Event>), TraceError> {
    let mut trace = Vec::new();
    let r = simulate(input, make_policy(coord, slot).as_mut(), seed, &mut trace);
    if let Some(f) = r.flood {
        return Err(f.into());
    }
    check_trace(input.wall, input.config.uavs, &trace)?;
    Ok((r, trace))
}
