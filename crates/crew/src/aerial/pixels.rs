//! Two passes over the image: every pixel's class, and (once [`super::shelves`] has judged
//! the large blobs) how much of each cell's floor an obstacle covers.
//!
//! A pixel is classified by its own colour when that is a robot's or a goal's (marks keep
//! their every pixel, a sliver of a robot under a leaning top too), and otherwise by its
//! colour averaged over a small square (noise and JPEG blocks average out, so a shelf or a
//! shadow reads as one colour, not as speckle).
//!
//! A pixel belongs to the cell under its centre on the floor, through the inverse homography.
//! Under a perspective camera a tall obstacle's top leans away from the nadir (the point under
//! the camera), over the near side of the cells beyond it; nothing leans toward the nadir. So
//! only a window of the cell is counted: along each axis, 0.4–0.95 of the cell on the side away
//! from the nadir (0.2–0.8 when the nadir is level with the cell, or unknown). An obstacle on
//! the cell covers that window whole; a neighbour's top leaning less than 0.4 cell misses it.
//! Robot and goal pixels cover floor, not obstacle. The pass runs on all cores, in bands of
//! rows; the counts are summed in band order, so the result does not depend on the cores.

use super::colour::{Class, Classifier};
use super::homography::Homography;
use image::RgbImage;
use rayon::prelude::*;

/// A pixel outside the floor.
pub const OUTSIDE: u8 = 5;

/// Obstacle and floor pixels counted in the middle of each cell.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Coverage {
    /// Obstacle pixels per cell, row-major.
    pub obstacle: Vec<u32>,
    /// Pixels per cell that showed floor, robots or goals.
    pub floor: Vec<u32>,
}

impl Coverage {
    /// The share of the middle of cell `i` an obstacle covers; `None` when no pixel was
    /// counted there.
    pub fn share(&self, i: usize) -> Option<f64> {
        let total = self.obstacle[i] + self.floor[i];
        (total > 0).then(|| f64::from(self.obstacle[i]) / f64::from(total))
    }
}

/// The counted window of a cell along one axis (fractions of the side), for a cell from `lo`
/// to `lo + 1` and the nadir at `nadir` on that axis.
pub(super) fn window(lo: f64, nadir: Option<f64>) -> (f64, f64) {
    match nadir {
        Some(n) if n < lo => (0.4, 0.95),
        Some(n) if n > lo + 1.0 => (0.05, 0.6),
        _ => (0.2, 0.8),
    }
}
const BAND_ROWS: usize = 32;

/// The radius (pixels) of the square over which a pixel's colour is averaged before it is
/// classified, for cells `cell_px` wide: 0 under 12 px per cell (the smallest marks are 3.5
/// px wide), then one more every 12 px, at most 3.
pub fn denoise_radius(cell_px: f64) -> usize {
    ((cell_px / 12.0).floor().max(0.0) as usize).min(3)
}

/// The mean colour of every pixel of row `y` over the (2r + 1)² square around it (clipped to
/// the image), into `out` (3 values a pixel); `cols` is scratch space of the same length.
fn mean_row(img: &RgbImage, y: usize, r: usize, cols: &mut [u32], out: &mut [u8]) {
    let (width, height) = (img.width() as usize, img.height() as usize);
    let raw = img.as_raw();
    let (y0, y1) = (y.saturating_sub(r), (y + r).min(height - 1));
    cols.fill(0);
    for yy in y0..=y1 {
        let row = &raw[yy * width * 3..(yy + 1) * width * 3];
        for (c, &v) in cols.iter_mut().zip(row) {
            *c += u32::from(v);
        }
    }
    let rows = (y1 - y0 + 1) as u32;
    // Division by the window's pixel count as a multiplication (see `rounded_mean`).
    let inverse: Vec<u64> = (0..=rows * (2 * r as u32 + 1))
        .map(|n| (1u64 << 32).div_ceil(u64::from(n.max(1))))
        .collect();
    let mut sum = [0u32; 3];
    let mut count = 0u32;
    // The window [x - r, x + r] slides along the row.
    for x in 0..width + r {
        if x < width {
            for c in 0..3 {
                sum[c] += cols[3 * x + c];
            }
            count += rows;
        }
        if x > 2 * r {
            let gone = x - 2 * r - 1;
            for c in 0..3 {
                sum[c] -= cols[3 * gone + c];
            }
            count -= rows;
        }
        if x >= r {
            let at = x - r;
            let inverse = inverse[count as usize];
            for c in 0..3 {
                out[3 * at + c] = rounded_mean(sum[c], count, inverse);
            }
        }
    }
}

/// `(sum + count / 2) / count` (the rounded mean of `count` values of at most 255 that add up
/// to `sum`) with `inverse` = ⌈2³² / count⌉: exact while (sum + count / 2) · count < 2³²
/// (the error of the product is under (sum + count / 2) · count / 2³² < 1 of the count),
/// which holds for every count up to 4000 (a window of 2·3 + 1 pixels squared is 49).
#[inline]
fn rounded_mean(sum: u32, count: u32, inverse: u64) -> u8 {
    ((u64::from(sum + count / 2) * inverse) >> 32) as u8
}

/// Calls `visit(k, (u, v))` for every pixel `k` of row `y` inside the `w` × `h` floor, with
/// its point on the floor.
fn floor_row(
    image_to_floor: &Homography,
    (w, h): (u32, u32),
    width: usize,
    y: usize,
    mut visit: impl FnMut(usize, (f64, f64)),
) {
    let m = image_to_floor.0;
    let y = y as f64 + 0.5;
    // The homography's numerators and denominator are linear along a row.
    let (bu, bv, bd) = (m[1] * y + m[2], m[4] * y + m[5], m[7] * y + m[8]);
    if m[6] == 0.0 && bd == 1.0 {
        // The denominator is 1 along the whole row (a view straight down): the same points
        // without dividing by it.
        for k in 0..width {
            let x = k as f64 + 0.5;
            let (u, v) = (m[0] * x + bu, m[3] * x + bv);
            if u >= 0.0 && v >= 0.0 && u < f64::from(w) && v < f64::from(h) {
                visit(k, (u, v));
            }
        }
        return;
    }
    for k in 0..width {
        let x = k as f64 + 0.5;
        let d = m[6] * x + bd;
        if d.abs() < 1e-12 {
            continue;
        }
        let (u, v) = ((m[0] * x + bu) / d, (m[3] * x + bv) / d);
        if u >= 0.0 && v >= 0.0 && u < f64::from(w) && v < f64::from(h) {
            visit(k, (u, v));
        }
    }
}

/// Classifies every pixel (class codes of [`Class`], or [`OUTSIDE`]) of a floor of `w` × `h`
/// cells seen through `image_to_floor`, colours other than marks averaged over a square of
/// radius `radius` (see [`denoise_radius`]).
pub fn classify(
    img: &RgbImage,
    classifier: &Classifier,
    image_to_floor: &Homography,
    floor: (u32, u32),
    radius: usize,
) -> Vec<u8> {
    let width = img.width() as usize;
    let raw = img.as_raw();
    let mut classes = vec![OUTSIDE; raw.len() / 3];
    classes
        .par_chunks_mut(width * BAND_ROWS)
        .enumerate()
        .for_each(|(band, out)| {
            let mut cols = vec![0u32; width * 3];
            let mut mean = vec![0u8; width * 3];
            // Where the first test of `classify` already says floor, by the pixel's own
            // colour and by the mean's (most pixels).
            let (mut own_grey, mut mean_grey) = (vec![false; width], vec![true; width]);
            for (row, line) in out.chunks_mut(width).enumerate() {
                let y = band * BAND_ROWS + row;
                if radius > 0 {
                    mean_row(img, y, radius, &mut cols, &mut mean);
                    classifier.greyish_row(&mean, &mut mean_grey);
                }
                let own = &raw[y * width * 3..(y + 1) * width * 3];
                classifier.greyish_row(own, &mut own_grey);
                floor_row(image_to_floor, floor, width, y, |k, _| {
                    if own_grey[k] && mean_grey[k] {
                        line[k] = Class::Floor as u8;
                        return;
                    }
                    let colour = |p: &[u8]| [p[3 * k], p[3 * k + 1], p[3 * k + 2]];
                    line[k] = match classifier.classify(colour(own)) {
                        mark @ (Class::Robot | Class::Goal) => mark,
                        c if radius == 0 => c,
                        _ => classifier.classify(colour(&mean)),
                    } as u8;
                });
            }
        });
    classes
}

/// Counts each cell's coverage (see the module's comment) from the pixels' classes.
pub fn coverage(
    classes: &[u8],
    width: usize,
    image_to_floor: &Homography,
    (w, h): (u32, u32),
    nadir: Option<(f64, f64)>,
) -> Coverage {
    let cells = w as usize * h as usize;
    // The counted window of every column and every row of cells.
    let windows = |n: u32, at: Option<f64>| -> Vec<(f64, f64)> {
        (0..n).map(|k| window(f64::from(k), at)).collect()
    };
    let (wu, wv) = (
        windows(w, nadir.map(|n| n.0)),
        windows(h, nadir.map(|n| n.1)),
    );
    let counts: Vec<Coverage> = classes
        .par_chunks(width * BAND_ROWS)
        .enumerate()
        .map(|(band, out)| {
            let mut cov = Coverage {
                obstacle: vec![0; cells],
                floor: vec![0; cells],
            };
            for (row, line) in out.chunks(width).enumerate() {
                let y = band * BAND_ROWS + row;
                floor_row(image_to_floor, (w, h), width, y, |k, (u, v)| {
                    // u and v are non-negative here: the casts truncate toward zero = floor.
                    let (cu, cv) = (u as usize, v as usize);
                    let (fu, fv) = (u - cu as f64, v - cv as f64);
                    let (ou, ov) = (wu[cu], wv[cv]);
                    if fu < ou.0 || fu > ou.1 || fv < ov.0 || fv > ov.1 {
                        return;
                    }
                    let cell = cv * w as usize + cu;
                    match line[k] {
                        c if c == Class::Obstacle as u8 => cov.obstacle[cell] += 1,
                        c if c == Class::Unsure as u8 || c == OUTSIDE => {}
                        _ => cov.floor[cell] += 1,
                    }
                });
            }
            cov
        })
        .collect();
    let mut total = Coverage {
        obstacle: vec![0; cells],
        floor: vec![0; cells],
    };
    for c in counts {
        for i in 0..cells {
            total.obstacle[i] += c.obstacle[i];
            total.floor[i] += c.floor[i];
        }
    }
    total
}

#[cfg(test)]
mod tests {
    #[test]
    fn the_rounded_mean_by_multiplication_is_the_division() {
        for count in 1..=49u32 {
            let inverse = (1u64 << 32).div_ceil(u64::from(count));
            for sum in 0..=255 * count {
                let want = ((sum + count / 2) / count) as u8;
                assert_eq!(
                    super::rounded_mean(sum, count, inverse),
                    want,
                    "{sum} / {count}"
                );
            }
        }
    }
}
