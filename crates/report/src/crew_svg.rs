//! Crew paths from above: the map, each robot's start (circle) and goal (square), and its path
//! as a line in its own colour.

use crate::svg::{escape, robot_colour};
use mason_crew::{Cell, Grid};
use std::fmt::Write;

/// Paths drawn at most; beyond, every k-th robot's path is drawn and the title says so.
pub const MAX_PATHS: usize = 150;

/// An SVG of a crew plan. `paths` may be empty (no plan): then only starts and goals show.
/// With more than [`MAX_PATHS`] robots, only every k-th path is drawn (the title says which);
/// every start and goal is always drawn.
pub fn crew_svg(
    title: &str,
    grid: &Grid,
    starts: &[Cell],
    goals: &[Cell],
    paths: &[Vec<Cell>],
) -> String {
    let (w, h) = (grid.width(), grid.height());
    let cell = (900.0 / f64::from(w.max(h))).clamp(1.5, 24.0);
    let top = 28.0;
    let (width, height) = (f64::from(w) * cell, f64::from(h) * cell + top);
    let mut svg = String::new();
    let thinned = if paths.len() > MAX_PATHS {
        let every = paths.len().div_ceil(MAX_PATHS);
        format!(
            " — paths drawn for one robot in {every} ({} of {}); every start (circle) and goal (square) shown",
            paths.len().div_ceil(every),
            paths.len()
        )
    } else {
        String::new()
    };
    let _ = write!(
        svg,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width:.0}" height="{height:.0}" viewBox="0 0 {width:.1} {height:.1}" font-family="sans-serif">"#
    );
    let _ = write!(
        svg,
        r##"<rect width="100%" height="100%" fill="#ffffff"/>"##
    );
    let _ = write!(
        svg,
        r##"<text x="4" y="18" font-size="13" fill="#222">{}{}</text>"##,
        escape(title),
        escape(&thinned)
    );
    let _ = write!(
        svg,
        r##"<g transform="translate(0 {top})"><rect width="{:.1}" height="{:.1}" fill="#f4f4f0"/>"##,
        f64::from(w) * cell,
        f64::from(h) * cell
    );
    // Obstacles as horizontal runs, one rect each.
    let _ = write!(svg, r##"<g fill="#3a3a3a">"##);
    for y in 0..h {
        let mut x = 0;
        while x < w {
            let blocked = |x: u32| !grid.is_free(grid.cell(x as i64, y as i64).expect("inside"));
            if blocked(x) {
                let x0 = x;
                while x < w && blocked(x) {
                    x += 1;
                }
                let _ = write!(
                    svg,
                    r#"<rect x="{:.2}" y="{:.2}" width="{:.2}" height="{:.2}"/>"#,
                    f64::from(x0) * cell,
                    f64::from(y) * cell,
                    f64::from(x - x0) * cell,
                    cell
                );
            } else {
                x += 1;
            }
        }
    }
    let _ = write!(svg, "</g>");
    let centre = |c: Cell| {
        let (x, y) = grid.xy(c);
        ((f64::from(x) + 0.5) * cell, (f64::from(y) + 0.5) * cell)
    };
    let stroke = (cell * 0.35).max(0.8);
    let every = paths.len().div_ceil(MAX_PATHS).max(1);
    for (i, path) in paths.iter().enumerate().step_by(every) {
        let points: Vec<String> = dedup(path)
            .into_iter()
            .map(|c| {
                let (x, y) = centre(c);
                format!("{x:.1},{y:.1}")
            })
            .collect();
        let _ = write!(
            svg,
            r#"<polyline points="{}" fill="none" stroke="{}" stroke-width="{stroke:.2}" stroke-linejoin="round" stroke-opacity="0.85"/>"#,
            points.join(" "),
            robot_colour(i)
        );
    }
    let r = (cell * 0.45).max(1.5);
    for (i, (&s, &g)) in starts.iter().zip(goals).enumerate() {
        let colour = robot_colour(i);
        let (sx, sy) = centre(s);
        let (gx, gy) = centre(g);
        let _ = write!(
            svg,
            r##"<circle cx="{sx:.1}" cy="{sy:.1}" r="{r:.2}" fill="{colour}" stroke="#000" stroke-width="{:.2}"><title>robot {i} start</title></circle>"##,
            r * 0.25
        );
        let _ = write!(
            svg,
            r##"<rect x="{:.1}" y="{:.1}" width="{:.2}" height="{:.2}" fill="none" stroke="{colour}" stroke-width="{:.2}"><title>robot {i} goal</title></rect>"##,
            gx - r,
            gy - r,
            2.0 * r,
            2.0 * r,
            r * 0.4
        );
    }
    let _ = write!(svg, "</g></svg>");
    svg
}

/// The path without consecutive repeats (waits do not change the drawing).
fn dedup(path: &[Cell]) -> Vec<Cell> {
    let mut out: Vec<Cell> = path.to_vec();
    out.dedup();
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn many_robots_thin_the_paths_and_say_so() {
        let grid = Grid::open(40, 40);
        let n = 400;
        let starts: Vec<Cell> = (0..n).map(|i| Cell(i as u32)).collect();
        let goals: Vec<Cell> = (0..n).map(|i| Cell(1599 - i as u32)).collect();
        let paths: Vec<Vec<Cell>> = starts
            .iter()
            .zip(&goals)
            .map(|(&s, &g)| vec![s, g])
            .collect();
        let svg = crew_svg("t", &grid, &starts, &goals, &paths);
        assert_eq!(svg.matches("<polyline").count(), 134);
        assert!(svg.contains("one robot in 3 (134 of 400)"));
        assert_eq!(svg.matches("<circle").count(), n);
        let few = crew_svg("t", &grid, &starts[..5], &goals[..5], &paths[..5]);
        assert_eq!(few.matches("<polyline").count(), 5);
        assert!(!few.contains("one robot in"));
    }
}
