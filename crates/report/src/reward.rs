//! Reward over time, one step line per run or coordination mode.

use crate::svg::{escape, robot_colour};
use std::fmt::Write;

/// A named series of (time s, cumulative reward).
pub struct Series<'a> {
    /// Legend label.
    pub label: &'a str,
    /// Points, time ascending.
    pub points: &'a [(f64, f64)],
}

/// An SVG of cumulative reward over time; `total` is the wall's full reward (a dashed line).
pub fn reward_svg(title: &str, series: &[Series<'_>], total: f64) -> String {
    let (left, top, w, h) = (60.0, 34.0, 720.0, 300.0);
    let t_max = series
        .iter()
        .flat_map(|s| s.points.iter().map(|p| p.0))
        .fold(60.0f64, f64::max);
    let r_max = total.max(
        series
            .iter()
            .flat_map(|s| s.points.iter().map(|p| p.1))
            .fold(1.0, f64::max),
    );
    let x = |t: f64| left + t / t_max * w;
    let y = |r: f64| top + h - r / r_max * h;
    let mut svg = String::new();
    let _ = write!(
        svg,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{0:.0}" height="{1:.0}" viewBox="0 0 {0:.0} {1:.0}" font-family="sans-serif" font-size="11">"#,
        left + w + 170.0,
        top + h + 44.0
    );
    let _ = write!(svg, r##"<rect width="100%" height="100%" fill="#fff"/>"##);
    let _ = write!(
        svg,
        r##"<text x="{left}" y="18" font-size="13" fill="#222">{}</text>"##,
        escape(title)
    );
    let _ = write!(
        svg,
        r##"<rect x="{left}" y="{top}" width="{w}" height="{h}" fill="none" stroke="#999"/>"##
    );
    let _ = write!(
        svg,
        r##"<line x1="{left}" x2="{0:.1}" y1="{1:.1}" y2="{1:.1}" stroke="#888" stroke-dasharray="4 3"/><text x="{2:.1}" y="{3:.1}" fill="#666">full wall: {total}</text>"##,
        left + w,
        y(total),
        left + 4.0,
        y(total) - 4.0
    );
    let step = [60.0, 120.0, 300.0, 600.0]
        .into_iter()
        .find(|s| t_max / s <= 12.0)
        .unwrap_or(1200.0);
    let mut t = 0.0;
    while t <= t_max + 1e-9 {
        let _ = write!(
            svg,
            r##"<text x="{:.1}" y="{:.1}" text-anchor="middle" fill="#444">{}:{:02}</text>"##,
            x(t),
            top + h + 16.0,
            (t / 60.0).floor() as u64,
            (t % 60.0) as u64
        );
        t += step;
    }
    for r in [0.0, 0.25, 0.5, 0.75, 1.0].map(|f| f * r_max) {
        let _ = write!(
            svg,
            r##"<text x="{:.1}" y="{:.1}" text-anchor="end" fill="#444">{r:.0}</text>"##,
            left - 6.0,
            y(r) + 4.0
        );
    }
    for (i, s) in series.iter().enumerate() {
        let colour = robot_colour(i);
        let mut d = format!("M{:.2},{:.2}", x(0.0), y(0.0));
        let mut last = 0.0;
        for &(t, r) in s.points {
            let _ = write!(d, " H{:.2} V{:.2}", x(t), y(r));
            last = t;
        }
        let _ = write!(d, " H{:.2}", x(last));
        let _ = write!(
            svg,
            r#"<path d="{d}" fill="none" stroke="{colour}" stroke-width="2"/>"#
        );
        let ly = top + 14.0 + 18.0 * i as f64;
        let _ = write!(
            svg,
            r##"<line x1="{0:.1}" x2="{1:.1}" y1="{ly:.1}" y2="{ly:.1}" stroke="{colour}" stroke-width="3"/><text x="{2:.1}" y="{3:.1}" fill="#222">{4}</text>"##,
            left + w + 12.0,
            left + w + 32.0,
            left + w + 38.0,
            ly + 4.0,
            escape(s.label)
        );
    }
    let _ = write!(svg, "</svg>");
    svg
}
