//! How high a UAV flies: the one altitude rule of the simulator's logs and the agents' status.
//!
//! **The rule.** UAV `i` cruises at its own altitude, [`cruise_altitude`]`(i)` = 3 + i metres,
//! so that UAVs never meet on a straight leg. It is on the ground (0 m) in `Check`, `Landed` and
//! `Down`. It changes altitude only in three states, linearly over the state's whole duration:
//! it climbs from 0 to its cruise altitude during `TakeOff`, and descends from its cruise
//! altitude to 0 during `Land` (flying home and landing) and `SafeLand` (landing where it is).
//! In every other state it holds its cruise altitude.
//!
//! So [`altitude`] — the altitude at the *start* of a state — is 0 for `Check`, `TakeOff`,
//! `Landed` and `Down` and the cruise altitude otherwise, and a log that knows only the state
//! transitions (a trace) draws the true altitude by interpolating linearly between them. A
//! vehicle that knows how far through its state it is uses [`altitude_during`].

use crate::state::UavState;

/// Cruise altitude of UAV `uav` (0-based; m): 3 + `uav`, so that the UAVs fly at their own
/// altitudes.
pub fn cruise_altitude(uav: u32) -> f64 {
    3.0 + f64::from(uav)
}

/// Altitude of UAV `uav` at the start of `state` (m): 0 on the ground before take-off
/// (`Check`, `TakeOff`) and after landing (`Landed`, `Down`), its [`cruise_altitude`]
/// otherwise (so take-off climbs and landing descends).
pub fn altitude(uav: u32, state: UavState) -> f64 {
    match state {
        UavState::Check | UavState::TakeOff | UavState::Landed | UavState::Down => 0.0,
        _ => cruise_altitude(uav),
    }
}

/// The fraction of its cruise altitude a UAV is at when it is `progress` (0 at the state's
/// start, 1 at its end; clamped to `[0, 1]`) of the way through `state`: it rises from 0 to 1
/// in `TakeOff`, falls from 1 to 0 in `Land` and `SafeLand`, and is constant (0 on the ground,
/// 1 in the air) in every other state.
pub fn climb_fraction(state: UavState, progress: f64) -> f64 {
    let f = if progress.is_nan() {
        0.0
    } else {
        progress.clamp(0.0, 1.0)
    };
    match state {
        UavState::TakeOff => f,
        UavState::Land | UavState::SafeLand => 1.0 - f,
        UavState::Check | UavState::Landed | UavState::Down => 0.0,
        _ => 1.0,
    }
}

/// Altitude of UAV `uav` `progress` of the way through `state` (m): [`climb_fraction`] of its
/// [`cruise_altitude`]. At `progress` 0 it is [`altitude`]`(uav, state)`.
pub fn altitude_during(uav: u32, state: UavState, progress: f64) -> f64 {
    climb_fraction(state, progress) * cruise_altitude(uav)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_uav_cruises_at_its_own_altitude() {
        assert_eq!(cruise_altitude(0), 3.0);
        assert_eq!(cruise_altitude(2), 5.0);
        assert_eq!(altitude(1, UavState::FlyToPile), 4.0);
        assert_eq!(altitude(1, UavState::EnterAndPlace), 4.0);
    }

    #[test]
    fn take_off_starts_on_the_ground_and_landing_in_the_air() {
        assert_eq!(altitude(0, UavState::Check), 0.0);
        assert_eq!(altitude(0, UavState::TakeOff), 0.0);
        assert_eq!(altitude(0, UavState::Land), 3.0);
        assert_eq!(altitude(0, UavState::SafeLand), 3.0);
        assert_eq!(altitude(0, UavState::Landed), 0.0);
        assert_eq!(altitude(0, UavState::Down), 0.0);
    }

    #[test]
    fn take_off_climbs_and_landing_descends_linearly() {
        assert_eq!(altitude_during(1, UavState::TakeOff, 0.0), 0.0);
        assert_eq!(altitude_during(1, UavState::TakeOff, 0.5), 2.0);
        assert_eq!(altitude_during(1, UavState::TakeOff, 1.0), 4.0);
        assert_eq!(altitude_during(1, UavState::Land, 0.25), 3.0);
        assert_eq!(altitude_during(1, UavState::SafeLand, 1.0), 0.0);
        // Out of range and undefined progress is clamped.
        assert_eq!(altitude_during(1, UavState::TakeOff, 2.0), 4.0);
        assert_eq!(altitude_during(1, UavState::Land, -1.0), 4.0);
        assert_eq!(altitude_during(1, UavState::TakeOff, f64::NAN), 0.0);
    }

    #[test]
    fn every_state_starts_where_the_rule_says_and_ends_where_the_next_starts() {
        for s in UavState::ALL {
            assert_eq!(altitude_during(2, s, 0.0), altitude(2, s), "{s:?}");
        }
        // The end of a moving state is the start of the state after it.
        assert_eq!(
            altitude_during(2, UavState::TakeOff, 1.0),
            altitude(2, UavState::ChooseBrick)
        );
        assert_eq!(
            altitude_during(2, UavState::Land, 1.0),
            altitude(2, UavState::Landed)
        );
        assert_eq!(
            altitude_during(2, UavState::SafeLand, 1.0),
            altitude(2, UavState::Down)
        );
    }
}
