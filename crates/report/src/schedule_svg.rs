//! The team schedule Gantt chart: one lane per UAV with its placing phases (in the brick's
//! colour, labelled) and the rest of each cycle, a lane for the wall showing how many bricks
//! are placing at once, and the budget line.

use crate::svg::{open_figure, time_axis};
use mason_order::schedule::{Schedule, TeamProblem};
use std::fmt::Write;

/// An SVG Gantt chart of a team schedule.
pub fn schedule_svg(title: &str, p: &TeamProblem<'_>, schedule: &Schedule) -> String {
    let wall = p.wall();
    let uavs = p.uavs();
    let last_cycle = schedule
        .placements
        .iter()
        .map(|pl| pl.start_s + p.place_s(pl.brick) + p.rest_s(pl.brick))
        .fold(0.0, f64::max);
    let end = last_cycle.max(p.budget_s().unwrap_or(0.0)).max(1.0);
    let (left, right, top) = (70.0, 20.0, 34.0);
    let lane = if uavs > 20 { 10.0 } else { 24.0 };
    let gap = lane / 3.0;
    let plot_w = 1000.0;
    let lane_y = |i: usize| top + i as f64 * (lane + gap);
    let axis_y = lane_y(uavs + 1);
    let height = axis_y + 40.0;
    let width = left + plot_w + right;
    let x = |t: f64| left + t / end * plot_w;
    let mut svg = open_figure(width, height, left, 10, title);
    for u in 0..uavs {
        let _ = write!(
            svg,
            r##"<text x="8" y="{:.1}" fill="#222">UAV {u}</text><rect x="{left}" y="{:.1}" width="{plot_w}" height="{lane}" fill="none" stroke="#ccc"/>"##,
            lane_y(u) + lane * 0.7,
            lane_y(u)
        );
    }
    for pl in &schedule.placements {
        let b = wall.brick(pl.brick);
        let [r, g, bl] = mason_wall::brick_rgb(b.kind);
        let (s, e) = (pl.start_s, pl.start_s + p.place_s(pl.brick));
        let rest_end = e + p.rest_s(pl.brick);
        for &u in &pl.uavs {
            let y = lane_y(u);
            let _ = write!(
                svg,
                r##"<rect x="{:.2}" y="{:.1}" width="{:.2}" height="{:.1}" fill="#e0e0e0"><title>UAV {u}: back to the pile, grasp, fly to the wall {e:.1}–{rest_end:.1} s</title></rect>"##,
                x(e),
                y + lane * 0.3,
                x(rest_end) - x(e),
                lane * 0.4
            );
            let _ = write!(
                svg,
                r##"<rect x="{:.2}" y="{y:.1}" width="{:.2}" height="{lane}" fill="rgb({r},{g},{bl})" stroke="#222" stroke-width="0.5"><title>brick {} ({}, level {}) by UAV {} {s:.1}–{e:.1} s</title></rect>"##,
                x(s),
                x(e) - x(s),
                b.label,
                b.kind.name(),
                b.level,
                pl.uavs
                    .iter()
                    .map(|u| u.to_string())
                    .collect::<Vec<_>>()
                    .join("+")
            );
            let label = b.label.to_string();
            if x(e) - x(s) > 6.0 * label.len() as f64 && lane >= 20.0 {
                let _ = write!(
                    svg,
                    r##"<text x="{:.2}" y="{:.1}" text-anchor="middle" fill="#fff" font-size="9" stroke="#000" stroke-width="0.3">{label}</text>"##,
                    (x(s) + x(e)) / 2.0,
                    y + lane * 0.65
                );
            }
        }
    }
    // The wall lane: how many bricks place at once (darker: more).
    let y = lane_y(uavs);
    let _ = write!(
        svg,
        r##"<text x="8" y="{:.1}" fill="#222">wall</text><rect x="{left}" y="{y:.1}" width="{plot_w}" height="{lane}" fill="none" stroke="#999"/>"##,
        y + lane * 0.7
    );
    let mut edges: Vec<(f64, i32)> = schedule
        .placements
        .iter()
        .flat_map(|pl| [(pl.start_s, 1), (pl.start_s + p.place_s(pl.brick), -1)])
        .collect();
    edges.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    let mut busy = 0;
    let mut since = 0.0;
    for (t, d) in edges {
        if busy > 0 && t > since {
            let _ = write!(
                svg,
                r##"<rect x="{:.2}" y="{y:.1}" width="{:.2}" height="{lane}" fill="#2e7d32" opacity="{:.2}"><title>{busy} placing {since:.1}–{t:.1} s</title></rect>"##,
                x(since),
                x(t) - x(since),
                (0.25 * f64::from(busy)).min(1.0)
            );
        }
        busy += d;
        since = t;
    }
    if let Some(t) = p.budget_s() {
        let _ = write!(
            svg,
            r##"<line x1="{0:.2}" x2="{0:.2}" y1="{1:.1}" y2="{2:.1}" stroke="#c62828" stroke-width="1.5" stroke-dasharray="5 3"/><text x="{0:.2}" y="{3:.1}" fill="#c62828" text-anchor="end">budget {t} s</text>"##,
            x(t),
            top - 6.0,
            axis_y,
            top - 8.0
        );
    }
    time_axis(&mut svg, x, end, top - 4.0, axis_y);
    let _ = write!(svg, "</svg>");
    svg
}

#[cfg(test)]
mod tests {
    use super::*;
    use mason_order::schedule::{plan_schedule, Objective, TeamModel};
    use mason_order::Budget;

    #[test]
    fn a_box_per_uav_and_brick_and_a_lane_per_uav() {
        let wall = mason_wall::parse_layer_text("O R\nB G R R", "t").unwrap();
        let p =
            TeamProblem::new(&wall, TeamModel::cmcp(), 3, Some(500.0), Objective::Reward).unwrap();
        let out = plan_schedule(&p, &Budget::nodes(200), 1);
        let s = out.schedule.unwrap();
        let svg = schedule_svg("t", &p, &s);
        for u in 0..3 {
            assert!(svg.contains(&format!(">UAV {u}<")));
        }
        let boxes: usize = s.placements.iter().map(|pl| pl.uavs.len()).sum();
        assert_eq!(
            svg.matches("</title></rect>").count() - svg.matches("placing ").count(),
            2 * boxes
        );
        assert!(svg.contains("budget 500 s"));
    }
}
