//! What Mason read from an aerial view, drawn over the view itself: the floor grid, the
//! blocked cells, each robot (circle, numbered) and goal (square) where it was read, and the
//! planned paths, all mapped into the image through the floor's homography; the cells the
//! operator settled (dashed orange), the cells read as a shelf of the floor's colour (dotted
//! magenta); for an audit, the refusals too, where they point.

use crate::crew_svg::MAX_PATHS;
use crate::svg::{escape, robot_colour};
use base64::Engine;
use mason_crew::aerial::AerialReading;
use mason_crew::Cell;
use std::fmt::Write;

/// The title's attributes that squeeze it into an image `w` pixels wide when it would not fit
/// (13 px type, about 0.6 em a character), so that a small image keeps its whole title.
fn title_fit(title: &str, w: u32) -> String {
    let room = (f64::from(w) - 8.0).max(1.0);
    match title.chars().count() as f64 * 0.6 * 13.0 > room {
        true => format!(r#" textLength="{room:.0}" lengthAdjust="spacingAndGlyphs""#),
        false => String::new(),
    }
}

/// An SVG of the image `image` (its file's bytes, PNG or JPEG) with the reading drawn over it.
/// `starts[i]` goes to `goals[i]` along `paths[i]` (`paths` may be empty: no plan).
pub fn aerial_svg(
    title: &str,
    image: &[u8],
    reading: &AerialReading,
    starts: &[Cell],
    goals: &[Cell],
    paths: &[Vec<Cell>],
) -> String {
    aerial_audit_svg(title, image, reading, (starts, goals, paths), &[])
}

/// [`aerial_svg`] with the refusals of an audit (`mason crew --audit`) marked where they point:
/// a magenta ring with a question mark at each `(pixel, reason)`, the reason as its tooltip.
pub fn aerial_audit_svg(
    title: &str,
    image: &[u8],
    reading: &AerialReading,
    (starts, goals, paths): (&[Cell], &[Cell], &[Vec<Cell>]),
    doubts: &[((f64, f64), String)],
) -> String {
    let (w, h) = reading.image_size;
    let grid = &reading.grid;
    let to_image = |u: f64, v: f64| reading.floor_to_image.apply((u, v)).unwrap_or((0.0, 0.0));
    let centre = |c: Cell| {
        let (x, y) = grid.xy(c);
        to_image(f64::from(x) + 0.5, f64::from(y) + 0.5)
    };
    let mime = if image.starts_with(&[0xFF, 0xD8]) {
        "image/jpeg"
    } else {
        "image/png"
    };
    let data = base64::engine::general_purpose::STANDARD.encode(image);
    let stroke = (reading.cell_px / 14.0).clamp(0.6, 3.0);
    let top = 24.0;
    let mut s = String::new();
    let _ = write!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{}" viewBox="0 {} {w} {}" font-family="sans-serif">"#,
        f64::from(h) + top,
        -top,
        f64::from(h) + top
    );
    let fit = title_fit(title, w);
    let _ = write!(
        s,
        r##"<rect x="0" y="{}" width="{w}" height="{top}" fill="#ffffff"/><text x="4" y="-7" font-size="13"{fit}>{}</text>"##,
        -top,
        escape(title)
    );
    let _ = write!(
        s,
        r#"<image width="{w}" height="{h}" href="data:{mime};base64,{data}"/>"#
    );
    // The grid.
    let (gw, gh) = (f64::from(grid.width()), f64::from(grid.height()));
    s.push_str(&format!(
        r##"<g stroke="#00e5ff" stroke-width="{:.2}" stroke-opacity="0.7">"##,
        stroke / 2.0
    ));
    for k in 0..=grid.width() {
        let (a, b) = (to_image(f64::from(k), 0.0), to_image(f64::from(k), gh));
        let _ = write!(
            s,
            r#"<line x1="{:.1}" y1="{:.1}" x2="{:.1}" y2="{:.1}"/>"#,
            a.0, a.1, b.0, b.1
        );
    }
    for k in 0..=grid.height() {
        let (a, b) = (to_image(0.0, f64::from(k)), to_image(gw, f64::from(k)));
        let _ = write!(
            s,
            r#"<line x1="{:.1}" y1="{:.1}" x2="{:.1}" y2="{:.1}"/>"#,
            a.0, a.1, b.0, b.1
        );
    }
    s.push_str("</g>");
    // Blocked cells.
    s.push_str(r##"<g fill="#000000" fill-opacity="0.45" stroke="#ffffff" stroke-width="0.5">"##);
    for i in 0..grid.len() as u32 {
        if grid.is_free(Cell(i)) {
            continue;
        }
        let (x, y) = grid.xy(Cell(i));
        let (x, y) = (f64::from(x), f64::from(y));
        let pts: Vec<String> = [(x, y), (x + 1.0, y), (x + 1.0, y + 1.0), (x, y + 1.0)]
            .iter()
            .map(|&(u, v)| {
                let p = to_image(u, v);
                format!("{:.1},{:.1}", p.0, p.1)
            })
            .collect();
        let _ = write!(s, r#"<polygon points="{}"/>"#, pts.join(" "));
    }
    s.push_str("</g>");
    // Cells the operator settled: a dashed orange outline inside the cell; cells read as a
    // shelf of the floor's colour: a dotted magenta one; half-covered cells read as free
    // under a mark: a dotted white one.
    let outlined = reading
        .settled
        .iter()
        .map(|&(c, blocked)| {
            let how = if blocked { "blocked" } else { "free" };
            (c, "#ff9100", 2.0, format!("settled {how} by the operator"))
        })
        .chain(reading.floor_tops.iter().map(|&c| {
            (
                c,
                "#ff40ff",
                0.8,
                "read as a shelf of the floor's colour (it does not look like the floor, and a shadow nothing else casts or a hidden painted line agrees)".to_string(),
            )
        }))
        .chain(reading.under_marks.iter().map(|&c| {
            (
                c,
                "#ffffff",
                0.8,
                "half covered, read as free: a robot or a goal stands on it".to_string(),
            )
        }));
    for (c, colour, dash, why) in outlined {
        let (x, y) = grid.xy(c);
        let (x, y) = (f64::from(x), f64::from(y));
        let (a, b) = (0.08, 0.92);
        let pts: Vec<String> = [(a, a), (b, a), (b, b), (a, b)]
            .iter()
            .map(|&(du, dv)| {
                let p = to_image(x + du, y + dv);
                format!("{:.1},{:.1}", p.0, p.1)
            })
            .collect();
        let _ = write!(
            s,
            r##"<polygon points="{}" fill="none" stroke="{colour}" stroke-width="{:.2}" stroke-dasharray="{:.1}"><title>cell ({x}, {y}) {why}</title></polygon>"##,
            pts.join(" "),
            stroke,
            dash * stroke,
        );
    }
    // Paths (every k-th beyond MAX_PATHS).
    let every = paths.len().div_ceil(MAX_PATHS).max(1);
    for (i, path) in paths.iter().enumerate().step_by(every) {
        let pts: Vec<String> = path
            .iter()
            .map(|&c| {
                let p = centre(c);
                format!("{:.1},{:.1}", p.0, p.1)
            })
            .collect();
        let _ = write!(
            s,
            r#"<polyline points="{}" fill="none" stroke="{}" stroke-width="{:.2}" stroke-opacity="0.9" stroke-linejoin="round"/>"#,
            pts.join(" "),
            robot_colour(i),
            stroke
        );
    }
    let r = (reading.cell_px * 0.3).max(2.0);
    for (i, &g) in goals.iter().enumerate() {
        let p = centre(g);
        let _ = write!(
            s,
            r##"<rect x="{:.1}" y="{:.1}" width="{:.1}" height="{:.1}" fill="none" stroke="#39ff14" stroke-width="{:.2}"><title>goal of robot {i}</title></rect>"##,
            p.0 - r,
            p.1 - r,
            2.0 * r,
            2.0 * r,
            stroke
        );
    }
    let font = (reading.cell_px * 0.45).clamp(6.0, 16.0);
    for (i, &c) in starts.iter().enumerate() {
        let p = centre(c);
        let _ = write!(
            s,
            r##"<circle cx="{:.1}" cy="{:.1}" r="{r:.1}" fill="none" stroke="#ffff00" stroke-width="{:.2}"/>"##,
            p.0, p.1, stroke
        );
        if starts.len() <= 60 {
            let _ = write!(
                s,
                r##"<text x="{:.1}" y="{:.1}" font-size="{font:.1}" fill="#ffff00" text-anchor="middle">{i}</text>"##,
                p.0,
                p.1 - r - 1.0
            );
        }
    }
    let ring = (reading.cell_px * 0.42).max(3.0);
    for ((x, y), reason) in doubts {
        let _ = write!(
            s,
            r##"<g><title>{}</title><circle cx="{x:.1}" cy="{y:.1}" r="{ring:.1}" fill="none" stroke="#ff00ff" stroke-width="{:.2}"/><text x="{x:.1}" y="{:.1}" font-size="{font:.1}" fill="#ff00ff" text-anchor="middle" font-weight="bold">?</text></g>"##,
            escape(reason),
            1.5 * stroke,
            y + font / 3.0
        );
    }
    s.push_str("</svg>\n");
    s
}

#[cfg(test)]
mod tests {
    use super::title_fit;

    #[test]
    fn a_long_title_is_squeezed_into_a_small_image_and_a_short_one_is_left_alone() {
        assert_eq!(title_fit("A0011.jpg — read 17×11 cells", 605), "");
        let long = "x".repeat(120);
        assert_eq!(
            title_fit(&long, 605),
            r#" textLength="597" lengthAdjust="spacingAndGlyphs""#
        );
        assert!(title_fit(&long, 4).contains(r#"textLength="1""#));
    }
}
