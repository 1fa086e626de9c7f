//! Two passes over the image: every pixel's class, and (once [`super::shelves`] has judged
//! the large blobs, and the specks of an obstacle's colour are set aside,
//! [`set_aside_specks`]) how much of each cell's floor an obstacle covers.
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
//! rows; the counts are whole numbers, summed, so the result does not depend on the cores.

use super::colour::{Class, Classifier};
use super::homography::Homography;
use super::pale;
use image::RgbImage;
use rayon::prelude::*;

/// A pixel outside the floor, or one of a painted line set aside (see [`super::lined`]):
/// neither floor nor obstacle, and counted nowhere.
pub const OUTSIDE: u8 = 5;

/// An 8-connected blob of obstacle pixels under this share of a cell's area is a speck
/// ([`set_aside_specks`]).
pub const SPECK: f64 = 0.1;

/// Sets aside the specks of an obstacle's colour: the 8-connected blobs of obstacle pixels
/// under [`SPECK`] of a cell (`cell_px` pixels a side; at least 3 pixels) become [`OUTSIDE`],
/// counted neither as obstacle nor as floor (in the cells' cover, their looks and their
/// shadows), as painted lines are. A shelf stands on whole cells: its top, its faces and its
/// edges are one piece, or pieces a cell long. Specks are a dark or noisy floor's grain, or
/// JPEG's blocks, saturated by white balance (R0004's and X0020's dark floors, d0016's shadow),
/// the crossings of painted lines (S0025), a pale top's grain at the obstacle colour's limit.
/// Counted as obstacle, they made free cells half covered (refused), or moved a cover's edge
/// (a lean measured off by them). A top read as specks alone is judged by what is left, its
/// pixels of the floor's colour: a free cell that does not look like the floor is refused.
/// Since issue #29's thirtieth round: on families A–Z and a–y, +5 views read exactly (P0018,
/// S0025, X0023, n0012, t0021), one refused that read exactly (K0004: a cell whose specks made
/// it covered is now free and does not look like the floor), and the views that the truth
/// shows would read wrongly were their refusals settled are as many as before (212). At 0.2
/// cell, +7 −1; at 0.3, R0026 read wrongly (a speckled top's cells read free): 0.1 keeps a
/// factor of three.
///
/// Cost: one labelling of the obstacle pixels.
pub fn set_aside_specks(classes: &mut [u8], width: usize, cell_px: f64) -> usize {
    let least = (SPECK * cell_px * cell_px).max(3.0);
    let mut specks = 0;
    for b in super::blobs::find(classes, width, Class::Obstacle as u8) {
        if (b.area() as f64) < least {
            b.paint(classes, width, OUTSIDE);
            specks += 1;
        }
    }
    specks
}

/// Obstacle and floor pixels counted in the middle of each cell.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Coverage {
    /// Obstacle pixels per cell, row-major.
    pub obstacle: Vec<u32>,
    /// Pixels per cell that showed floor, robots or goals.
    pub floor: Vec<u32>,
    /// Of those, the goals' pixels.
    pub goal: Vec<u32>,
}

impl Coverage {
    /// The share of the middle of cell `i` an obstacle covers; `None` when no pixel was
    /// counted there. Goal-coloured pixels count as floor when they are half the pixels or
    /// more (a goal painted on the cell), and not at all otherwise: a goal is flat paint, which
    /// an obstacle beside it hides rather than covers with its own colour, while a shelf of a
    /// colour near the goals' (olive, dark green) reads partly as goal on the cells it stands
    /// on (issue #29's thirteenth round: E0004's olive shelf read 46 % covered).
    pub fn share(&self, i: usize) -> Option<f64> {
        let (obstacle, floor, goal) = (self.obstacle[i], self.floor[i], self.goal[i]);
        let total = obstacle + floor;
        if total == 0 {
            return None;
        }
        let judged = if 2 * goal < total {
            total - goal
        } else {
            total
        };
        Some(f64::from(obstacle) / f64::from(judged.max(1)))
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
    if width > 2 * r {
        // The windows cut by the row's ends, each summed whole; then the window slides over
        // the rest, always the same count of pixels, in a loop without the ends' tests.
        for at in (0..r).chain(width - r..width) {
            let (a, b) = (at.saturating_sub(r), (at + r).min(width - 1));
            let count = rows * (b - a + 1) as u32;
            for c in 0..3 {
                let sum = (a..=b).map(|x| cols[3 * x + c]).sum();
                out[3 * at + c] = rounded_mean(sum, count, inverse[count as usize]);
            }
        }
        let full = rows * (2 * r as u32 + 1);
        let inverse = inverse[full as usize];
        let mut sum = [0u32; 3];
        for x in 0..=2 * r {
            for c in 0..3 {
                sum[c] += cols[3 * x + c];
            }
        }
        for c in 0..3 {
            out[3 * r + c] = rounded_mean(sum[c], full, inverse);
        }
        for at in r + 1..width - r {
            for c in 0..3 {
                sum[c] = sum[c] + cols[3 * (at + r) + c] - cols[3 * (at - r - 1) + c];
                out[3 * at + c] = rounded_mean(sum[c], full, inverse);
            }
        }
        return;
    }
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

/// The pixels of row `y` inside the `w` × `h` floor, the same as [`floor_row`] visits, as one
/// range, when the row's denominator is 1 (a view straight down); `None` otherwise. Then u
/// and v are each a product and a sum of x, both rounded monotonically, so each bound holds
/// on a prefix or a suffix of the row, found by bisection with the same arithmetic.
fn floor_span(
    image_to_floor: &Homography,
    (w, h): (u32, u32),
    width: usize,
    y: usize,
) -> Option<std::ops::Range<usize>> {
    let m = image_to_floor.0;
    let y = y as f64 + 0.5;
    let (bu, bv, bd) = (m[1] * y + m[2], m[4] * y + m[5], m[7] * y + m[8]);
    if !(m[6] == 0.0 && bd == 1.0) || width == 0 {
        return None;
    }
    let uv = |k: usize| {
        let x = k as f64 + 0.5;
        (m[0] * x + bu, m[3] * x + bv)
    };
    let bounds: [&dyn Fn(usize) -> bool; 4] = [
        &|k| uv(k).0 >= 0.0,
        &|k| uv(k).1 >= 0.0,
        &|k| uv(k).0 < f64::from(w),
        &|k| uv(k).1 < f64::from(h),
    ];
    let (mut lo, mut hi) = (0, width);
    for holds in bounds {
        // The first k (in 0..width) where `holds` differs from its value at 0.
        let first = holds(0);
        let (mut a, mut b) = (0, width);
        while a < b {
            let mid = a + (b - a) / 2;
            if holds(mid) == first {
                a = mid + 1;
            } else {
                b = mid;
            }
        }
        if first {
            hi = hi.min(a);
        } else {
            lo = lo.max(a);
        }
    }
    Some(lo..hi.max(lo))
}

/// The floor's pixels, each judged as [`classify`] judges it (averaged over its square of
/// radius `radius`), sampled every 8th pixel of every 8th row inside the floor, each row of
/// samples shifted by 3 pixels from the one before: the saturation after white balance of
/// those of the floor's colour class and the lit floor's brightness (see
/// [`pale::lit_floor_bright`]), for [`pale::lean_tint`], and the colours after white balance
/// of those of the floor's class as dark as a shadow ([`pale::SHADE_BRIGHT`]), for
/// [`pale::shade`].
pub struct FloorSamples {
    /// The lit floor's saturations.
    pub lit_saturations: Vec<f64>,
    /// The shaded floor's colours.
    pub shaded: Vec<[f64; 3]>,
}

/// See [`FloorSamples`].
pub fn floor_samples(
    img: &RgbImage,
    classifier: &Classifier,
    image_to_floor: &Homography,
    (w, h): (u32, u32),
    radius: usize,
) -> FloorSamples {
    let (width, height) = (img.width() as usize, img.height() as usize);
    let raw = img.as_raw();
    let (fw, fh) = (f64::from(w), f64::from(h));
    let mut out = FloorSamples {
        lit_saturations: Vec::new(),
        shaded: Vec::new(),
    };
    for y in (0..height).step_by(8) {
        for x in ((y / 8 * 3) % 8..width).step_by(8) {
            let inside = image_to_floor
                .apply((x as f64 + 0.5, y as f64 + 0.5))
                .is_some_and(|(u, v)| u >= 0.0 && v >= 0.0 && u < fw && v < fh);
            if !inside {
                continue;
            }
            let (x0, x1) = (x.saturating_sub(radius), (x + radius).min(width - 1));
            let (y0, y1) = (y.saturating_sub(radius), (y + radius).min(height - 1));
            let mut sum = [0u32; 3];
            for yy in y0..=y1 {
                for xx in x0..=x1 {
                    for (c, s) in sum.iter_mut().enumerate() {
                        *s += u32::from(raw[(yy * width + xx) * 3 + c]);
                    }
                }
            }
            let n = ((x1 - x0 + 1) * (y1 - y0 + 1)) as u32;
            let mean = sum.map(|s| ((s + n / 2) / n) as u8);
            let balanced = classifier.balanced(mean);
            if classifier.classify(mean) != Class::Floor {
                continue;
            }
            if pale::lit_floor_bright(balanced) {
                out.lit_saturations.push(pale::saturation(balanced));
            } else if pale::shade_bright(balanced) {
                out.shaded.push(balanced);
            }
        }
    }
    out
}

/// Classifies every pixel (class codes of [`Class`], [`pale::PALE`] for floor-coloured pixels
/// that lean pale, to be settled by [`pale::settle`], or [`OUTSIDE`]) of a floor of `w` × `h`
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
                let mut visit = |k: usize| {
                    let colour = |p: &[u8]| [p[3 * k], p[3 * k + 1], p[3 * k + 2]];
                    let leaning = |p: [u8; 3]| classifier.leaning(classifier.balanced(p));
                    if own_grey[k] && mean_grey[k] {
                        // Floor by its own colour and by the mean's (by its own alone when
                        // colours are not averaged): pale or not, as below.
                        let judged = if radius == 0 {
                            colour(own)
                        } else {
                            colour(&mean)
                        };
                        line[k] = if leaning(judged) {
                            pale::pale_code(classifier, classifier.balanced(judged))
                        } else {
                            Class::Floor as u8
                        };
                        return;
                    }
                    let judged = |p: [u8; 3]| match classifier.classify(p) {
                        Class::Floor if leaning(p) => {
                            pale::pale_code(classifier, classifier.balanced(p))
                        }
                        c => c as u8,
                    };
                    line[k] = match classifier.classify(colour(own)) {
                        // A speck of a mark's colour on a pale shelf (a tan top's reddest
                        // pixels): the mark's class unless `pale::settle` finds the shelf.
                        mark @ (Class::Robot | Class::Goal) if radius > 0 => {
                            match judged(colour(&mean)) {
                                pale::PALE | pale::PALE_SHADE => pale::speck(mark),
                                _ => mark as u8,
                            }
                        }
                        mark @ (Class::Robot | Class::Goal) => mark as u8,
                        _ if radius == 0 => judged(colour(own)),
                        _ => judged(colour(&mean)),
                    };
                };
                match floor_span(image_to_floor, floor, width, y) {
                    Some(span) => span.for_each(visit),
                    None => floor_row(image_to_floor, floor, width, y, |k, _| visit(k)),
                }
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
    // u, v → the cell whose window holds them, along one axis.
    let in_window = |t: f64, n: u32, windows: &[(f64, f64)]| -> Option<usize> {
        if !(t >= 0.0 && t < f64::from(n)) {
            return None;
        }
        // t is non-negative: the cast truncates toward zero = floor.
        let c = t as usize;
        let (f, o) = (t - c as f64, windows[c]);
        (f >= o.0 && f <= o.1).then_some(c)
    };
    // A view straight down with the grid along the image's axes: u depends on the column
    // alone and v on the row alone (as `floor_row` computes them, up to the sign of a
    // zero), so each column's cell is found once.
    let m = image_to_floor.0;
    let columns: Option<Vec<Option<usize>>> =
        (m[6] == 0.0 && m[7] == 0.0 && m[8] == 1.0 && m[1] == 0.0 && m[3] == 0.0).then(|| {
            let bu = m[1] * 0.5 + m[2];
            (0..width)
                .map(|k| in_window(m[0] * (k as f64 + 0.5) + bu, w, &wu))
                .collect()
        });
    let count = |cov: &mut Coverage, class: u8, cell: usize| match class {
        c if c == Class::Obstacle as u8 => cov.obstacle[cell] += 1,
        c if c == Class::Unsure as u8 || c == OUTSIDE => {}
        c => {
            cov.floor[cell] += 1;
            if c == Class::Goal as u8 {
                cov.goal[cell] += 1;
            }
        }
    };
    let empty = || Coverage {
        obstacle: vec![0; cells],
        floor: vec![0; cells],
        goal: vec![0; cells],
    };
    // Counts per run of bands (as many as the cores split the rows into), then their sums:
    // whole numbers, so the totals do not depend on how the rows were split.
    classes
        .par_chunks(width * BAND_ROWS)
        .enumerate()
        .fold(empty, |mut cov, (band, out)| {
            for (row, line) in out.chunks(width).enumerate() {
                let y = band * BAND_ROWS + row;
                if let Some(columns) = &columns {
                    let v = m[3] * 0.5 + (m[4] * (y as f64 + 0.5) + m[5]);
                    if let Some(cv) = in_window(v, h, &wv) {
                        for (&class, &cu) in line.iter().zip(columns) {
                            if let Some(cu) = cu {
                                count(&mut cov, class, cv * w as usize + cu);
                            }
                        }
                    }
                    continue;
                }
                floor_row(image_to_floor, (w, h), width, y, |k, (u, v)| {
                    // u and v are non-negative here: the casts truncate toward zero = floor.
                    let (cu, cv) = (u as usize, v as usize);
                    let (fu, fv) = (u - cu as f64, v - cv as f64);
                    let (ou, ov) = (wu[cu], wv[cv]);
                    if fu < ou.0 || fu > ou.1 || fv < ov.0 || fv > ov.1 {
                        return;
                    }
                    count(&mut cov, line[k], cv * w as usize + cu);
                });
            }
            cov
        })
        .reduce(empty, |mut total, c| {
            for (t, n) in total.obstacle.iter_mut().zip(&c.obstacle) {
                *t += n;
            }
            for (t, n) in total.floor.iter_mut().zip(&c.floor) {
                *t += n;
            }
            for (t, n) in total.goal.iter_mut().zip(&c.goal) {
                *t += n;
            }
            total
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_lit_floor_s_saturations_are_sampled_inside_the_floor() {
        // A grey floor of 10 × 10 cells of 8 px, straight down, with every pixel of its left
        // half tinted (+12 red) by noise of one sign: half the samples are tinted, and the
        // median saturation is that of the grey half or the tinted one.
        let img = RgbImage::from_fn(80, 80, |x, _| {
            if x < 40 {
                image::Rgb([132, 120, 120])
            } else {
                image::Rgb([120, 120, 120])
            }
        });
        let classifier = Classifier::new(
            [120.0; 3],
            super::super::colour::Hue::RED,
            super::super::colour::Hue::GREEN,
        );
        let to_floor = Homography::floor_to_image(
            10.0,
            10.0,
            [(0.0, 0.0), (80.0, 0.0), (80.0, 80.0), (0.0, 80.0)],
        )
        .unwrap()
        .inverse()
        .unwrap();
        let mut s = floor_samples(&img, &classifier, &to_floor, (10, 10), 0).lit_saturations;
        assert_eq!(s.len(), 100);
        assert_eq!(s.iter().filter(|&&x| x > 0.0).count(), 50);
        let tinted = 1.0 - 1.0 / 1.1;
        assert!(s.iter().all(|&x| x == 0.0 || (x - tinted).abs() < 1e-9));
        // Twice the median (of 100: the 51st, tinted) is above the loose limit.
        assert!((pale::lean_tint(&mut s) - 2.0 * tinted).abs() < 1e-9);
        // A floor only a quarter of whose pixels are tinted keeps the loose limit.
        let quarter = RgbImage::from_fn(80, 80, |x, _| {
            image::Rgb(if x < 20 {
                [132, 120, 120]
            } else {
                [120, 120, 120]
            })
        });
        let mut s = floor_samples(&quarter, &classifier, &to_floor, (10, 10), 0).lit_saturations;
        assert_eq!(pale::lean_tint(&mut s), pale::LEANING.2);
        // Outside the floor nothing is sampled.
        let half_floor = Homography::floor_to_image(
            10.0,
            10.0,
            [(0.0, 0.0), (40.0, 0.0), (40.0, 80.0), (0.0, 80.0)],
        )
        .unwrap()
        .inverse()
        .unwrap();
        assert_eq!(
            floor_samples(&img, &classifier, &half_floor, (10, 10), 0)
                .lit_saturations
                .len(),
            50
        );
        // A bluish shadow over the right half (the sky's light): its colour is sampled as the
        // shaded floor's, none of it as the lit floor's.
        let shadowed = RgbImage::from_fn(80, 80, |x, _| {
            image::Rgb(if x < 40 {
                [120, 120, 120]
            } else {
                [66, 74, 90]
            })
        });
        let samples = floor_samples(&shadowed, &classifier, &to_floor, (10, 10), 0);
        assert_eq!(samples.lit_saturations.len(), 50);
        assert_eq!(samples.shaded.len(), 50);
        let mut shaded = samples.shaded;
        let shade = pale::shade(&mut shaded, 100).unwrap();
        assert!((shade[0] - 0.55).abs() < 1e-9 && (shade[2] - 0.75).abs() < 1e-9);
    }

    #[test]
    fn goal_coloured_pixels_count_as_floor_only_as_a_goal() {
        let cov = Coverage {
            obstacle: vec![60, 10, 0, 0],
            floor: vec![40, 90, 0, 5],
            goal: vec![30, 60, 0, 5],
        };
        // A shelf of a colour near the goals' over a third of its cell: covered as the rest.
        assert_eq!(cov.share(0), Some(60.0 / 70.0));
        // A goal painted on the cell: its pixels are floor.
        assert_eq!(cov.share(1), Some(0.1));
        assert_eq!(cov.share(2), None);
        assert_eq!(cov.share(3), Some(0.0));
    }

    #[test]
    fn a_straight_down_row_s_span_is_the_pixels_its_row_visits() {
        // Floors placed anyhow in the image (some partly outside it, some flipped), seen
        // straight down: the span holds exactly the pixels `floor_row` visits.
        let mut seed = 7u64;
        let mut next = |lo: f64, hi: f64| {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            lo + (hi - lo) * ((seed >> 11) as f64 / (1u64 << 53) as f64)
        };
        let (mut spans, mut partial) = (0, 0);
        for _ in 0..300 {
            let (w, h) = (
                next(1.0, 40.0).floor() as u32,
                next(1.0, 40.0).floor() as u32,
            );
            let (x0, y0) = (next(-30.0, 60.0), next(-30.0, 60.0));
            let (sx, sy) = (next(-9.0, 9.0), next(-9.0, 9.0));
            let (fw, fh) = (f64::from(w), f64::from(h));
            let corners = [
                (x0, y0),
                (x0 + sx * fw, y0),
                (x0 + sx * fw, y0 + sy * fh),
                (x0, y0 + sy * fh),
            ];
            let Some(to_image) = Homography::floor_to_image(fw, fh, corners) else {
                continue;
            };
            let Some(to_floor) = to_image.inverse() else {
                continue;
            };
            let width = 97;
            for y in 0..90 {
                let mut visited = Vec::new();
                floor_row(&to_floor, (w, h), width, y, |k, _| visited.push(k));
                if let Some(span) = floor_span(&to_floor, (w, h), width, y) {
                    spans += 1;
                    partial += usize::from(!visited.is_empty() && visited.len() < width);
                    assert_eq!(span.collect::<Vec<_>>(), visited, "{corners:?} row {y}");
                }
            }
        }
        assert!(
            spans > 10_000 && partial > 1_000,
            "{spans} spans, {partial} partial"
        );
    }
    #[test]
    fn a_row_s_means_are_the_square_s_rounded_means() {
        let (w, h) = (23u32, 9u32);
        let img = RgbImage::from_fn(w, h, |x, y| {
            image::Rgb([
                (x * 37 + y * 11) as u8,
                (x * x + 3 * y) as u8,
                (255 - x * y) as u8,
            ])
        });
        for r in 0..=3usize {
            for width in [w, 2 * r as u32 + 1, 2 * r as u32] {
                let img = image::imageops::crop_imm(&img, 0, 0, width.max(1), h).to_image();
                let wd = img.width() as usize;
                let (mut cols, mut out) = (vec![0u32; wd * 3], vec![0u8; wd * 3]);
                for y in 0..h as usize {
                    mean_row(&img, y, r, &mut cols, &mut out);
                    for x in 0..wd {
                        let (xs, ys) = (
                            x.saturating_sub(r)..=(x + r).min(wd - 1),
                            y.saturating_sub(r)..=(y + r).min(h as usize - 1),
                        );
                        let n = (xs.clone().count() * ys.clone().count()) as u32;
                        for c in 0..3 {
                            let sum: u32 = ys
                                .clone()
                                .flat_map(|yy| xs.clone().map(move |xx| (xx, yy)))
                                .map(|(xx, yy)| u32::from(img.get_pixel(xx as u32, yy as u32)[c]))
                                .sum();
                            assert_eq!(
                                out[3 * x + c],
                                ((sum + n / 2) / n) as u8,
                                "r {r} ({x}, {y})"
                            );
                        }
                    }
                }
            }
        }
    }

    #[test]
    fn specks_of_an_obstacle_s_colour_are_set_aside_and_a_shelf_is_not() {
        // Cells of 10 px: a shelf of 10 × 20 px, a speck of 3 × 3 (0.09 cell), a thin strip of
        // 1 × 12 (0.12 cell), and two specks of 2 px touching at a corner (one blob of 4 px:
        // diagonal neighbours join).
        let (w, h) = (40usize, 30usize);
        let mut classes = vec![Class::Floor as u8; w * h];
        let mut put = |x0: usize, y0: usize, x1: usize, y1: usize| {
            for y in y0..y1 {
                for x in x0..x1 {
                    classes[y * w + x] = Class::Obstacle as u8;
                }
            }
        };
        put(0, 0, 10, 20);
        put(20, 2, 23, 5);
        put(30, 2, 31, 14);
        put(20, 25, 22, 26);
        put(22, 26, 24, 27);
        assert_eq!(set_aside_specks(&mut classes, w, 10.0), 2);
        assert_eq!(classes[5 * w + 5], Class::Obstacle as u8);
        assert_eq!(classes[3 * w + 21], OUTSIDE);
        assert_eq!(classes[8 * w + 30], Class::Obstacle as u8);
        // The two diagonal specks are one blob of 4 px: set aside as one.
        assert_eq!(classes[25 * w + 20], OUTSIDE);
        assert_eq!(classes[26 * w + 23], OUTSIDE);
        assert_eq!(classes[10 * w + 15], Class::Floor as u8);
        // On cells of 4 px, 3 px at least: a speck of 2 px goes, the 3 × 3 one stays.
        let mut classes = vec![Class::Floor as u8; w * h];
        classes[0] = Class::Obstacle as u8;
        classes[1] = Class::Obstacle as u8;
        for y in 10..13 {
            for x in 10..13 {
                classes[y * w + x] = Class::Obstacle as u8;
            }
        }
        assert_eq!(set_aside_specks(&mut classes, w, 4.0), 1);
        assert_eq!(classes[0], OUTSIDE);
        assert_eq!(classes[11 * w + 11], Class::Obstacle as u8);
    }

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
