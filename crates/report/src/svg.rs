//! Small SVG helpers shared by the figures.

use std::fmt::Write;

/// Escapes text for SVG and HTML.
pub fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// A distinct colour for robot or UAV `i`: hues a golden angle apart.
pub fn robot_colour(i: usize) -> String {
    let hue = (i as f64 * 137.508) % 360.0;
    format!("hsl({hue:.0},70%,45%)")
}

/// Opens an SVG of `width` × `height` with a white background and `title` at (`left`, 18).
pub fn open_figure(width: f64, height: f64, left: f64, font_size: u32, title: &str) -> String {
    let mut svg = String::new();
    let _ = write!(
        svg,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width:.0}" height="{height:.0}" viewBox="0 0 {width:.0} {height:.0}" font-family="sans-serif" font-size="{font_size}">"#
    );
    let _ = write!(svg, r##"<rect width="100%" height="100%" fill="#fff"/>"##);
    let _ = write!(
        svg,
        r##"<text x="{left}" y="18" font-size="13" fill="#222">{}</text>"##,
        escape(title)
    );
    svg
}

/// A time axis from 0 to `end` s: a grid line from `top` to `axis_y` and an m:ss label below
/// it, every minute (or every 2, 5, 10, … minutes for long spans, at most about 16 ticks).
pub fn time_axis(svg: &mut String, x: impl Fn(f64) -> f64, end: f64, top: f64, axis_y: f64) {
    let step = [60.0, 120.0, 300.0, 600.0, 1200.0, 1800.0, 3600.0]
        .into_iter()
        .find(|s| end / s <= 16.0)
        .unwrap_or(7200.0);
    let mut t = 0.0;
    while t <= end + 1e-9 {
        let _ = write!(
            svg,
            r##"<line x1="{0:.2}" x2="{0:.2}" y1="{1:.1}" y2="{2:.1}" stroke="#bbb"/><text x="{0:.2}" y="{3:.1}" text-anchor="middle" fill="#444">{4}:{5:02}</text>"##,
            x(t),
            top,
            axis_y,
            axis_y + 14.0,
            (t / 60.0).floor() as u64,
            (t % 60.0) as u64
        );
        t += step;
    }
}
