//! The wall seen from the front, bricks in their colours, labelled with their ids and, when an
//! order is given, their place in it.

use crate::svg::escape;
use crate::wall_layout::front_layout;
use mason_wall::{brick_rgb, BrickId, Wall, BRICK_HEIGHT};
use std::fmt::Write;

const SCALE: f64 = 120.0; // px per metre
const MARGIN: f64 = 24.0;

/// An SVG of the wall. With `order`, each brick shows its step number (1 = first placed) in
/// bold and its id below; without, only its id.
pub fn wall_svg(wall: &Wall, order: Option<&[BrickId]>) -> String {
    let bricks = wall.bricks();
    // Segments are stacked, each from its own left edge, so that a wall of several segments
    // keeps the scale (and readable labels) of a one-segment wall.
    let layout = front_layout(wall);
    let width = layout.width * SCALE + 2.0 * MARGIN;
    let wall_h = layout.height * SCALE;
    let height = wall_h + 2.0 * MARGIN + 18.0;
    let mut step = vec![None; wall.len()];
    if let Some(order) = order {
        for (i, b) in order.iter().enumerate() {
            if let Some(s) = step.get_mut(b.index()) {
                *s = Some(i + 1);
            }
        }
    }
    let mut svg = String::new();
    let _ = write!(
        svg,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width:.0}" height="{height:.0}" viewBox="0 0 {width:.1} {height:.1}" font-family="sans-serif">"#
    );
    let _ = write!(svg, r#"<rect width="100%" height="100%" fill="white"/>"#);
    let title = match order {
        Some(_) => format!(
            "{} — build order (bold: step, small: brick id)",
            wall.name()
        ),
        None => format!(
            "{} — {} bricks, {} levels",
            wall.name(),
            wall.len(),
            wall.levels()
        ),
    };
    let _ = write!(
        svg,
        r##"<text x="{MARGIN}" y="16" font-size="13" fill="#222">{}</text>"##,
        escape(&title)
    );
    if layout.captions {
        for band in &layout.bands {
            let _ = write!(
                svg,
                r##"<text x="{MARGIN}" y="{:.1}" font-size="12" fill="#555">segment {}</text>"##,
                MARGIN + 18.0 + band.top * SCALE + 0.18 * SCALE,
                band.segment
            );
        }
    }
    // Draw far bricks first so that near ones (smaller y) are on top in 3-D walls.
    let mut idx: Vec<usize> = (0..bricks.len()).collect();
    idx.sort_by(|&a, &b| bricks[b].footprint.y0.total_cmp(&bricks[a].footprint.y0));
    for i in idx {
        let b = &bricks[i];
        let spot = &layout.spots[i];
        let x = MARGIN + spot.x0 * SCALE;
        let w = (spot.x1 - spot.x0) * SCALE;
        let y = MARGIN + 18.0 + spot.y * SCALE;
        let h = BRICK_HEIGHT * SCALE;
        let [r, g, bl] = brick_rgb(b.kind);
        let _ = write!(
            svg,
            r##"<g><title>{} {} level {}</title><rect x="{x:.1}" y="{y:.1}" width="{w:.1}" height="{h:.1}" fill="rgb({r},{g},{bl})" stroke="#1b1b1b" stroke-width="2"/>"##,
            b.label, b.kind, b.level
        );
        let cx = x + w / 2.0;
        let text_colour = if b.kind == mason_wall::BrickType::Orange {
            "#222"
        } else {
            "white"
        };
        match step[i] {
            Some(s) => {
                let _ = write!(
                    svg,
                    r#"<text x="{cx:.1}" y="{:.1}" font-size="13" font-weight="bold" text-anchor="middle" fill="{text_colour}">{s}</text><text x="{cx:.1}" y="{:.1}" font-size="9" text-anchor="middle" fill="{text_colour}">{}</text>"#,
                    y + h / 2.0 + 1.0,
                    y + h - 3.0,
                    b.label
                );
            }
            None => {
                let _ = write!(
                    svg,
                    r#"<text x="{cx:.1}" y="{:.1}" font-size="11" text-anchor="middle" fill="{text_colour}">{}</text>"#,
                    y + h / 2.0 + 4.0,
                    b.label
                );
            }
        }
        svg.push_str("</g>");
    }
    svg.push_str("</svg>\n");
    svg
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_brick_is_drawn_with_its_step() {
        let wall = mason_wall::parse_layer_text("R G\nB R R", "w<1>").unwrap();
        let order: Vec<BrickId> = wall.ids().collect();
        let svg = wall_svg(&wall, Some(&order));
        assert_eq!(svg.matches("<rect x=").count(), wall.len());
        assert!(svg.contains(">5</text>"));
        assert!(svg.contains("w&lt;1&gt;"));
        assert!(svg.contains("rgb(255,165,0)") || !svg.contains("orange"));
    }

    /// Regression (#30): the 17.7 m MBZIRC wall was drawn 2 172 px wide with its three segments
    /// side by side, and shrunk to the page its labels could not be read. Its segments are now
    /// stacked, at the scale of the other walls.
    #[test]
    fn the_mbzirc_segments_are_stacked_at_the_scale_of_the_other_walls() {
        let wall = mason_wall::builtin("mbzirc").unwrap().wall();
        let svg = wall_svg(&wall, None);
        let width: f64 = svg
            .split("width=\"")
            .nth(1)
            .and_then(|w| w.split('"').next())
            .and_then(|w| w.parse().ok())
            .unwrap();
        // One segment: 5.9 m at 120 px/m plus margins, not 17.7 m.
        assert!(width < 800.0, "{width}");
        for k in 1..=3 {
            assert!(svg.contains(&format!(">segment {k}</text>")), "segment {k}");
        }
        assert_eq!(svg.matches("<rect x=").count(), 42);
        // Brick rectangles keep the full scale: 0.20 m × 120 px/m.
        assert!(svg.contains(r#"height="24.0""#));
    }
}
