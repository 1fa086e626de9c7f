//! The mission Gantt chart: one lane per UAV coloured by state, a lane for the wall zone with
//! placement marks, and the UAVs' communication-mode changes.

use crate::svg::{open_figure, time_axis};
use mason_mission::{CommMode, Event, EventKind, UavState};
use mason_wall::Wall;
use std::fmt::Write;

/// The colour of a state.
pub fn state_colour(s: UavState) -> &'static str {
    match s {
        UavState::Check | UavState::TakeOff | UavState::Land => "#b0bec5",
        UavState::ChooseBrick => "#eceff1",
        UavState::FlyToPile => "#90caf9",
        UavState::Detect | UavState::FlyAbove => "#ffe082",
        UavState::Grasp => "#ffb300",
        UavState::FlyToWallWait => "#1e88e5",
        UavState::WaitForZone => "#ef9a9a",
        UavState::EnterAndPlace => "#43a047",
        UavState::SafeLand => "#8e24aa",
        UavState::Landed => "#ffffff",
        UavState::Down => "#424242",
    }
}

/// States shown in the legend, in machine order.
const LEGEND: [(&str, UavState); 10] = [
    ("take-off/land", UavState::TakeOff),
    ("idle", UavState::ChooseBrick),
    ("to pile", UavState::FlyToPile),
    ("detect", UavState::Detect),
    ("grasp", UavState::Grasp),
    ("to wall", UavState::FlyToWallWait),
    ("wait for zone", UavState::WaitForZone),
    ("place", UavState::EnterAndPlace),
    ("safe-land", UavState::SafeLand),
    ("down", UavState::Down),
];

/// An SVG Gantt chart of a mission's events, from 0 to `end` seconds.
pub fn gantt_svg(title: &str, wall: &Wall, uavs: usize, events: &[Event], end: f64) -> String {
    let end = end.max(1.0);
    let (left, right, top, lane, gap) = (70.0, 20.0, 34.0, 26.0, 8.0);
    let plot_w = 1000.0;
    let lanes = uavs + 1;
    let axis_y = top + lanes as f64 * (lane + gap);
    let height = axis_y + 70.0;
    let width = left + plot_w + right;
    let x = |t: f64| left + t / end * plot_w;
    let mut svg = open_figure(width, height, left, 11, title);
    let lane_y = |i: usize| top + i as f64 * (lane + gap);
    // UAV lanes.
    for u in 0..uavs {
        let y = lane_y(u);
        let _ = write!(
            svg,
            r##"<text x="8" y="{:.1}" fill="#222">UAV {u}</text>"##,
            y + lane * 0.65
        );
        let mut current: Option<(UavState, f64)> = None;
        let draw = |svg: &mut String, s: UavState, from: f64, to: f64| {
            if to > from {
                let _ = write!(
                    svg,
                    r##"<rect x="{:.2}" y="{y:.1}" width="{:.2}" height="{lane}" fill="{}"><title>{} {:.1}–{:.1} s</title></rect>"##,
                    x(from),
                    x(to) - x(from),
                    state_colour(s),
                    s.name(),
                    from,
                    to
                );
            }
        };
        for e in events.iter().filter(|e| e.uav as usize == u) {
            match e.kind {
                EventKind::State { state, .. } => {
                    if let Some((s, from)) = current {
                        draw(&mut svg, s, from, e.t);
                    }
                    current = Some((state, e.t));
                }
                EventKind::Comm { mode } => {
                    let label = match mode {
                        CommMode::Comm => "comm",
                        CommMode::Windows => "windows",
                    };
                    let _ = write!(
                        svg,
                        r##"<line x1="{0:.2}" x2="{0:.2}" y1="{1:.1}" y2="{2:.1}" stroke="#6a1b9a" stroke-width="2" stroke-dasharray="3 2"/><text x="{3:.2}" y="{4:.1}" fill="#6a1b9a" font-size="9">{label}</text>"##,
                        x(e.t),
                        y - 3.0,
                        y + lane + 3.0,
                        x(e.t) + 2.0,
                        y - 1.0
                    );
                }
                EventKind::Fail => {
                    let _ = write!(
                        svg,
                        r##"<text x="{:.2}" y="{:.1}" fill="#b71c1c" font-weight="bold">✕</text>"##,
                        x(e.t) - 4.0,
                        y + lane * 0.7
                    );
                }
                _ => {}
            }
        }
        if let Some((s, from)) = current {
            draw(&mut svg, s, from, end);
        }
        let _ = write!(
            svg,
            r##"<rect x="{left}" y="{y:.1}" width="{plot_w}" height="{lane}" fill="none" stroke="#999"/>"##
        );
    }
    // Zone lane.
    let y = lane_y(uavs);
    let _ = write!(
        svg,
        r##"<text x="8" y="{:.1}" fill="#222">zone</text>"##,
        y + lane * 0.65
    );
    for (from, to) in zone_intervals(events) {
        let _ = write!(
            svg,
            r##"<rect x="{:.2}" y="{y:.1}" width="{:.2}" height="{lane}" fill="#43a047" opacity="0.75"/>"##,
            x(from),
            x(to) - x(from)
        );
    }
    for e in events {
        if let EventKind::Place { brick } = e.kind {
            {
                let b = wall.brick(brick);
                let [r, g, bl] = mason_wall::brick_rgb(b.kind);
                let _ = write!(
                    svg,
                    r##"<path d="M{0:.2},{1:.1} l-4,-7 h8 z" fill="rgb({2},{3},{4})" stroke="#222" stroke-width="0.6"><title>{5} placed at {6:.1} s</title></path>"##,
                    x(e.t),
                    y + lane + 8.0,
                    r,
                    g,
                    bl,
                    b.label,
                    e.t
                );
            }
        }
    }
    let _ = write!(
        svg,
        r##"<rect x="{left}" y="{y:.1}" width="{plot_w}" height="{lane}" fill="none" stroke="#999"/>"##
    );
    time_axis(&mut svg, x, end, top - 4.0, axis_y + 4.0);
    // Legend.
    let mut lx = left;
    for (name, s) in LEGEND {
        let _ = write!(
            svg,
            r##"<rect x="{lx:.1}" y="{:.1}" width="12" height="12" fill="{}" stroke="#999"/><text x="{:.1}" y="{:.1}" fill="#333">{name}</text>"##,
            axis_y + 30.0,
            state_colour(s),
            lx + 16.0,
            axis_y + 40.0
        );
        lx += 22.0 + 6.5 * name.len() as f64;
    }
    let _ = write!(svg, "</svg>");
    svg
}

/// The intervals (enter, leave) during which the wall zone was occupied.
pub fn zone_intervals(events: &[Event]) -> Vec<(f64, f64)> {
    let mut out = Vec::new();
    let mut inside = 0usize;
    let mut since = 0.0;
    for e in events {
        match e.kind {
            EventKind::ZoneEnter => {
                if inside == 0 {
                    since = e.t;
                }
                inside += 1;
            }
            EventKind::ZoneLeave => {
                inside = inside.saturating_sub(1);
                if inside == 0 {
                    out.push((since, e.t));
                }
            }
            _ => {}
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use mason_mission::{make_policy, simulate, Coord, MissionConfig, MissionInput};

    #[test]
    fn one_lane_per_uav_a_zone_lane_and_a_mark_per_placement() {
        let wall = mason_wall::builtin("thesis-2x5").unwrap().wall();
        let model = mason_order::CostModel::default();
        let order: Vec<_> = wall.ids().collect();
        let config = MissionConfig::with_uavs(3);
        let input = MissionInput {
            wall: &wall,
            order: &order,
            model: &model,
            assignment: None,
            replanner: None,
            config: &config,
        };
        let mut trace = Vec::new();
        let r = simulate(
            input,
            make_policy(Coord::Comm, 25.0).as_mut(),
            0,
            &mut trace,
        );
        let svg = gantt_svg("t", &wall, 3, &trace, r.metrics.end_s);
        for u in 0..3 {
            assert!(svg.contains(&format!(">UAV {u}<")));
        }
        assert_eq!(svg.matches("placed at").count(), 10);
        let zone = zone_intervals(&trace);
        assert_eq!(zone.len(), 10, "one zone visit per brick");
        assert!(
            zone.windows(2).all(|w| w[0].1 <= w[1].0),
            "visits do not overlap"
        );
    }
}
