//! One pass over the image: every pixel's class, and how much of each cell's floor an
//! obstacle covers.
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
fn window(lo: f64, nadir: Option<f64>) -> (f64, f64) {
    match nadir {
        Some(n) if n < lo => (0.4, 0.95),
        Some(n) if n > lo + 1.0 => (0.05, 0.6),
        _ => (0.2, 0.8),
    }
}
const BAND_ROWS: usize = 32;

/// Classifies every pixel (class codes of [`Class`], or [`OUTSIDE`]) and counts the cells'
/// coverage, for a floor of `w` × `h` cells seen through `image_to_floor`.
pub fn classify(
    img: &RgbImage,
    classifier: &Classifier,
    image_to_floor: &Homography,
    (w, h): (u32, u32),
    nadir: Option<(f64, f64)>,
) -> (Vec<u8>, Coverage) {
    let width = img.width() as usize;
    let cells = w as usize * h as usize;
    let raw = img.as_raw();
    let mut classes = vec![OUTSIDE; raw.len() / 3];
    // The counted window of every column and every row of cells.
    let windows = |n: u32, at: Option<f64>| -> Vec<(f64, f64)> {
        (0..n).map(|k| window(f64::from(k), at)).collect()
    };
    let (wu, wv) = (
        windows(w, nadir.map(|n| n.0)),
        windows(h, nadir.map(|n| n.1)),
    );
    let m = image_to_floor.0;
    let counts: Vec<Coverage> = classes
        .par_chunks_mut(width * BAND_ROWS)
        .enumerate()
        .map(|(band, out)| {
            let mut cov = Coverage {
                obstacle: vec![0; cells],
                floor: vec![0; cells],
            };
            for (row, line) in out.chunks_mut(width).enumerate() {
                let y = (band * BAND_ROWS + row) as f64 + 0.5;
                // The homography's numerators and denominator are linear along a row.
                let (bu, bv, bd) = (m[1] * y + m[2], m[4] * y + m[5], m[7] * y + m[8]);
                let start = (band * BAND_ROWS + row) * width;
                for (k, class) in line.iter_mut().enumerate() {
                    let x = k as f64 + 0.5;
                    let d = m[6] * x + bd;
                    if d.abs() < 1e-12 {
                        continue;
                    }
                    let (u, v) = ((m[0] * x + bu) / d, (m[3] * x + bv) / d);
                    if !(u >= 0.0 && v >= 0.0 && u < f64::from(w) && v < f64::from(h)) {
                        continue;
                    }
                    let i = start + k;
                    let c = classifier.classify([raw[3 * i], raw[3 * i + 1], raw[3 * i + 2]]);
                    *class = c as u8;
                    // u and v are non-negative here: the casts truncate toward zero = floor.
                    let (cu, cv) = (u as usize, v as usize);
                    let (fu, fv) = (u - cu as f64, v - cv as f64);
                    let (ou, ov) = (wu[cu], wv[cv]);
                    if fu < ou.0 || fu > ou.1 || fv < ov.0 || fv > ov.1 {
                        continue;
                    }
                    let cell = cv * w as usize + cu;
                    match c {
                        Class::Obstacle => cov.obstacle[cell] += 1,
                        Class::Unsure => {}
                        _ => cov.floor[cell] += 1,
                    }
                }
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
    (classes, total)
}
