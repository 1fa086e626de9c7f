//! Front-view raster rendering of a wall (the inverse of [`crate::read_png`]).
//!
//! Bricks are drawn at `unit_px` pixels per 0.30 m (fractional scales allowed) and
//! `layer_units` units high (0.20 m, two thirds of a unit, by default; drawings of walls are
//! seldom to scale in height), separated by borders of `border_px` pixels. Edges are anti-aliased by 4×4
//! supersampling, so the output looks like an exported drawing rather than a pixel grid.

use crate::brick::{BrickType, UNIT_LENGTH};
use crate::wall::Wall;
use image::{Rgb, RgbImage};

/// Brick colours used by the renderer and the SVG figures.
pub fn brick_rgb(kind: BrickType) -> [u8; 3] {
    match kind {
        BrickType::Red => [235, 20, 20],
        BrickType::Green => [20, 200, 40],
        BrickType::Blue => [25, 50, 235],
        BrickType::Orange => [255, 165, 0],
    }
}

/// How to draw a wall.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RasterStyle {
    /// Pixels per 0.30 m (at least 1).
    pub unit_px: f64,
    /// Height of a layer in units of 0.30 m (the physical 0.20 m is 2/3).
    pub layer_units: f64,
    /// Border thickness between bricks (px).
    pub border_px: f64,
    /// Border colour.
    pub border: [u8; 3],
    /// Background colour.
    pub background: [u8; 3],
    /// Margin around the wall (px).
    pub margin_px: u32,
}

impl Default for RasterStyle {
    fn default() -> Self {
        RasterStyle {
            unit_px: 24.0,
            layer_units: 2.0 / 3.0,
            border_px: 2.0,
            border: [0, 0, 0],
            background: [255, 255, 255],
            margin_px: 12,
        }
    }
}

const SS: usize = 4;

/// Renders the wall seen from the front (x to the right, level 1 at the bottom).
pub fn render(wall: &Wall, style: &RasterStyle) -> RgbImage {
    let unit = style.unit_px.max(1.0);
    let height_px = unit * style.layer_units.max(1.0 / unit);
    let x_min = wall
        .bricks()
        .iter()
        .map(|b| b.footprint.x0)
        .fold(f64::INFINITY, f64::min);
    let x_max = wall
        .bricks()
        .iter()
        .map(|b| b.footprint.x1)
        .fold(f64::NEG_INFINITY, f64::max);
    let margin = f64::from(style.margin_px);
    let width = ((x_max - x_min) / UNIT_LENGTH * unit + 2.0 * margin).ceil() as usize;
    let height = (f64::from(wall.levels()) * height_px + 2.0 * margin).ceil() as usize;
    let (w, h) = (width * SS, height * SS);
    // Supersampled canvas of colour indices: 0 background, 1 border, 2.. brick types.
    let mut canvas = vec![0u8; w * h];
    let s = SS as f64;
    let half = style.border_px / 2.0;
    for b in wall.bricks() {
        let left = margin + (b.footprint.x0 - x_min) / UNIT_LENGTH * unit;
        let right = margin + (b.footprint.x1 - x_min) / UNIT_LENGTH * unit;
        let top = margin + f64::from(wall.levels() - b.level) * height_px;
        let bottom = top + height_px;
        let px = |v: f64| ((v * s).round().max(0.0) as usize).min(w);
        let py = |v: f64| ((v * s).round().max(0.0) as usize).min(h);
        for y in py(top - half)..py(bottom + half) {
            for x in px(left - half)..px(right + half) {
                let cell = &mut canvas[y * w + x];
                if *cell < 2 {
                    *cell = 1;
                }
            }
        }
        let code = 2 + b.kind.index() as u8;
        for y in py(top + half)..py(bottom - half) {
            for x in px(left + half)..px(right - half) {
                canvas[y * w + x] = code;
            }
        }
    }
    let palette: [[u8; 3]; 6] = [
        style.background,
        style.border,
        brick_rgb(BrickType::Red),
        brick_rgb(BrickType::Green),
        brick_rgb(BrickType::Blue),
        brick_rgb(BrickType::Orange),
    ];
    let mut img = RgbImage::new(width as u32, height as u32);
    for (x, y, pixel) in img.enumerate_pixels_mut() {
        let mut acc = [0u32; 3];
        for dy in 0..SS {
            for dx in 0..SS {
                let c = palette[canvas[(y as usize * SS + dy) * w + x as usize * SS + dx] as usize];
                for k in 0..3 {
                    acc[k] += u32::from(c[k]);
                }
            }
        }
        let n = (SS * SS) as u32;
        *pixel = Rgb([(acc[0] / n) as u8, (acc[1] / n) as u8, (acc[2] / n) as u8]);
    }
    img
}
