//! Pale obstacles: a shelf whose colour after white balance is nearly grey.
//!
//! The colour classes of [`super::colour`] take an obstacle by its colour. A shelf of a pale
//! colour (cream, pale lilac, light grey on a darker floor) is nearly grey after white
//! balance, and its pixels read as floor. Yet its top, horizontal like the floor and lit by
//! the same sun, differs from the floor by its reflectance: it is brighter than the lit
//! floor can be, or, as bright as the lit floor (no shadow), it is tinted.
//!
//! Pixel by pixel that difference drowns in noise and texture, so it is judged over squares
//! [`OPENING`] of a cell wide. [`super::pixels::classify`] marks the floor-coloured pixels
//! that lean that way ([`is_leaning_with`], loose limits, or above the floor's own tint), and the specks of a mark's colour whose
//! surroundings lean that way (the reddest pixels of a tan top). A square is pale when
//! - at least [`FULL`] of its pixels lean that way or are already an obstacle's (or of a
//!   colour that cannot be told: the rest of a top whose colour noise splits between floor
//!   and obstacle),
//! - none is a robot's or a goal's (marks stand on the floor, not on a shelf's top), and
//! - the mean colour of its floor-coloured pixels (leaning or not) is pale ([`is_pale`]:
//!   brighter than [`BRIGHTER`] times the lit floor, or lit and tinted).
//!
//! The leaning pixels of pale squares are an obstacle's; the others are floor, robot or goal
//! pixels again. Under a coloured sky or sun the floor itself is tinted where the sun is
//! partly hidden: a soft shadow's rim, a faint shadow (bluish under a blue sky, brownish under
//! a warm one, after white balance on the sunlit floor). A leaning pixel whose tint a mix of
//! the sun's light and the shadows' explains ([`shade_explains`], against the view's
//! shadows' colour, [`shade`]) still counts toward a pale square, so a pale top keeps its
//! cover, but left floor it is told apart ([`LEANED_IN_SHADE`]): [`super::looks`] does not
//! count it against a free cell (issue #29's twenty-fourth round). Painted lines (at most a tenth of a cell wide, a little more with blur) fill
//! less than half of such a square, and specks of noise less still, so they stay floor.
//!
//! Pixels as bright as the lit floor or darker, and grey ones, are not judged here: a shelf
//! of the floor's own colour and brightness shows only by its shadow ([`super::shadows`]),
//! and a region of free cells brighter or more tinted than the floor around it, below these
//! limits, is refused by [`super::looks`].
//!
//! Cost: O(pixels) time, on all cores in bands of rows, and a flag a pixel of memory when
//! some pixels lean pale (running sums down the columns, then along each row), nothing
//! otherwise.

use super::colour::{Class, Classifier};
use image::RgbImage;
use rayon::prelude::*;

/// Rows per band of the passes on all cores (the result does not depend on the cores).
const BAND_ROWS: usize = 64;

/// A pixel class used only between [`super::pixels::classify`] and [`settle`]: floor by its
/// colour class, but leaning pale.
pub const PALE: u8 = 6;

/// Like [`PALE`], for a floor-coloured pixel whose tint the view's shadows' light explains
/// ([`Classifier::shaded`]): it counts toward a pale square as [`PALE`] does (a pale top of
/// the sky's tint stays an obstacle), but left floor it is not reported as leaning pale (a
/// shadow's faint or soft rim under a coloured sky is floor).
pub const PALE_SHADE: u8 = 9;

/// How a pixel left floor by [`settle`] leaned pale: not at all, ...
pub const NOT_LEANED: u8 = 0;
/// ... as [`PALE`] ...
pub const LEANED: u8 = 1;
/// ... or as [`PALE_SHADE`].
pub const LEANED_IN_SHADE: u8 = 2;

/// Like [`PALE`], for a pixel of a robot's colour whose surroundings lean pale: a robot's
/// pixel unless [`settle`] finds it in a pale square.
pub const PALE_ROBOT: u8 = 7;
/// Likewise for a goal's colour.
pub const PALE_GOAL: u8 = 8;

/// The code of a pixel of mark `mark`'s own colour whose surroundings lean pale.
pub fn speck(mark: Class) -> u8 {
    if mark == Class::Robot {
        PALE_ROBOT
    } else {
        PALE_GOAL
    }
}

fn leaning_code(c: u8) -> bool {
    c == PALE || c == PALE_SHADE || c == PALE_ROBOT || c == PALE_GOAL
}

/// The code of a floor-coloured pixel that leans pale, after white balance `balanced`:
/// [`PALE_SHADE`] when the shadows' light explains its tint, [`PALE`] otherwise.
pub fn pale_code(classifier: &Classifier, balanced: [f64; 3]) -> u8 {
    if classifier.shaded(balanced) {
        PALE_SHADE
    } else {
        PALE
    }
}

/// The brightest the lit floor may be after white balance over a square (the lit floor's
/// median is 1): its texture, uneven light and the camera's noise stay below this. 1.5 until
/// the ninth round's end; 1.4 reads F0006, K0021, L0011 and L0013 exactly and adds no
/// error behind the refusals of A–O (with every refusal bypassed and logged).
pub const BRIGHTER: f64 = 1.4;
/// At least this bright (relative to the lit floor) a tinted square is lit, not in a shadow
/// (a shadow's tint depends on the light).
pub const LIT: f64 = 0.9;
/// The saturation after white balance from which a lit square is tinted (the lit floor is
/// grey). [`super::colour`] takes a lit pixel as an obstacle's from a saturation of 0.25.
pub const TINTED: f64 = 0.17;
/// The loose limits of a pixel that leans pale: brightness, lit brightness and saturation.
pub const LEANING: (f64, f64, f64) = (1.3, 0.8, 0.1);
/// The share of a square's pixels that must lean pale.
pub const FULL: f64 = 0.8;
/// The side of the squares, in cells.
pub const OPENING: f64 = 0.5;

fn bright_and_saturation([r, g, b]: [f64; 3]) -> (f64, f64) {
    let max = r.max(g).max(b);
    let min = r.min(g).min(b);
    (max, if max > 0.0 { (max - min) / max } else { 0.0 })
}

/// Whether a colour after white balance (the lit floor 1 in every channel) is pale: brighter
/// than the lit floor can be, or lit and tinted.
pub fn is_pale(rgb: [f64; 3]) -> bool {
    let (max, min) = extremes(rgb);
    max >= BRIGHTER || (max >= LIT && saturation_at_least(max, min, TINTED))
}

fn extremes([r, g, b]: [f64; 3]) -> (f64, f64) {
    (r.max(g).max(b), r.min(g).min(b))
}

/// Whether the saturation of a colour with channels from `min` to `max` (`max` > 0), as
/// [`bright_and_saturation`] divides it out, is at least `t` (> 0): answered by a product
/// where the two differ by more than a relative 2^-50, by the division itself nearer, so
/// that the answer is the division's, bit for bit. On every floor pixel the division's
/// latency was a third of the pixel classification's time.
#[inline]
fn saturation_at_least(max: f64, min: f64, t: f64) -> bool {
    const MARGIN: f64 = 1.0 / (1u64 << 50) as f64;
    let (chroma, bound) = (max - min, t * max);
    if chroma > bound * (1.0 + MARGIN) {
        true
    } else if chroma < bound * (1.0 - MARGIN) {
        false
    } else {
        chroma / max >= t
    }
}

/// Whether a colour after white balance leans pale (the loose limits [`LEANING`]), lit ones
/// from saturation `tint` (see [`lean_tint`]; [`super::colour::Classifier::leaning`]).
pub fn is_leaning_with(rgb: [f64; 3], tint: f64) -> bool {
    let (max, min) = extremes(rgb);
    max >= LEANING.0 || (max >= LEANING.1 && saturation_at_least(max, min, tint))
}

/// The lit floor leans pale by its tint from this many times its median saturation.
pub const TINT_NOISE: f64 = 2.0;

/// The saturation from which a lit floor-coloured pixel leans pale in this view: the loose
/// limit of [`LEANING`], or [`TINT_NOISE`] times the median saturation of the lit floor's
/// pixels after white balance, `saturations` (each pixel's colour as it is judged: averaged
/// over its square), whichever is more.
///
/// The loose limit is chosen for a clean floor. On a dark floor the camera's noise and JPEG's
/// colour blocks tint every pixel: a floor at a quarter of white with noise of 2 % of white
/// has a median saturation near 0.1 (E0022's after averaging over 3 × 3 pixels: 0.11), and
/// half its pixels then leaned pale, so that free cells were refused for looking unlike the
/// floor all over the view (issue #29's thirteenth round). For noise twice the median
/// saturation is about its 95th percentile. `saturations` is reordered.
pub fn lean_tint(saturations: &mut [f64]) -> f64 {
    if saturations.is_empty() {
        return LEANING.2;
    }
    let mid = saturations.len() / 2;
    let median = *saturations.select_nth_unstable_by(mid, f64::total_cmp).1;
    (TINT_NOISE * median).max(LEANING.2)
}

/// The saturation after white balance of a colour.
pub fn saturation(rgb: [f64; 3]) -> f64 {
    bright_and_saturation(rgb).1
}

/// Whether a colour after white balance is of the lit floor's brightness: neither in a
/// shadow nor brighter than a pixel leaning pale.
pub fn lit_floor_bright(rgb: [f64; 3]) -> bool {
    let max = rgb[0].max(rgb[1]).max(rgb[2]);
    (LEANING.1..LEANING.0).contains(&max)
}

/// The brightness (relative to the lit floor) of the floor in a shadow, sampled for [`shade`]:
/// darker than the lit floor ([`LEANING`]'s lit limit), brighter than a painted line or a
/// shelf's dark side is likely to be.
pub const SHADE_BRIGHT: (f64, f64) = (0.3, LEANING.1);
/// At least this share of the floor's samples, and [`SHADE_SAMPLES`] of them, must be shaded for
/// [`shade`] to tell the shadows' colour.
pub const SHADE_SHARE: f64 = 0.02;
/// See [`SHADE_SHARE`].
pub const SHADE_SAMPLES: usize = 32;

/// Whether a colour after white balance is as dark as the floor in a shadow ([`SHADE_BRIGHT`]).
pub fn shade_bright(rgb: [f64; 3]) -> bool {
    let max = rgb[0].max(rgb[1]).max(rgb[2]);
    (SHADE_BRIGHT.0..SHADE_BRIGHT.1).contains(&max)
}

/// The colour after white balance of the floor in the view's shadows, lit by the sky alone:
/// the median of each channel of the `shaded` samples (see [`super::pixels::floor_samples`]),
/// when they are at least [`SHADE_SHARE`] of all `samples` and [`SHADE_SAMPLES`] in number;
/// `None` otherwise. Under a coloured sky or sun the shadows are tinted (bluish under a blue
/// sky, brownish under a warm one, after white balance on the sunlit floor), and so is the
/// floor where the sun is partly hidden (a soft shadow's rim) or a shadow is faint: see
/// [`shade_explains`]. `shaded` is reordered.
pub fn shade(shaded: &mut [[f64; 3]], samples: usize) -> Option<[f64; 3]> {
    let n = shaded.len();
    if n < SHADE_SAMPLES || (n as f64) < SHADE_SHARE * samples as f64 {
        return None;
    }
    let mut channel = vec![0.0; n];
    let mut out = [0.0; 3];
    for (c, o) in out.iter_mut().enumerate() {
        for (v, p) in channel.iter_mut().zip(shaded.iter()) {
            *v = p[c];
        }
        *o = *channel.select_nth_unstable_by(n / 2, f64::total_cmp).1;
    }
    Some(out)
}

/// The brightest a relit floor pixel may be ([`shade_explains`]), relative to the lit floor.
/// The lowest of those tried in issue #29's twenty-fourth round (1.05, 1.15, and 1.3, the
/// loose limit of a pixel leaning by its brightness): at 1.3, M0018's shelf of the floor's
/// colour no longer showed as cells unlike the floor, and its shadow was refused as cast by
/// nothing; 1.15 read one view more (U0008) than 1.05.
pub const RELIT: f64 = 1.05;
/// The sun's share of the light tried by [`shade_explains`]: 0, 0.1, …, 0.9.
const SUN_SHARES: usize = 10;

/// Whether a colour after white balance, tinted, is floor under a mix of the sun's light and
/// the sky's: relit (divided by the light of a sun's share α of the lit floor's and the rest
/// `shade`'s, for some α below 1), it is no brighter than the lit floor's texture allows
/// ([`RELIT`]) and less saturated than `tint`. A tinted pale top lit by the sun is brighter
/// than any relit floor where its tint is the sky's, and of another hue elsewhere.
pub fn shade_explains(rgb: [f64; 3], shade: [f64; 3], tint: f64) -> bool {
    (0..SUN_SHARES).any(|k| {
        let (max, min) = extremes(relit(rgb, shade, k));
        max < RELIT && !saturation_at_least(max, min, tint)
    })
}

/// `rgb` divided by the light of a sun's share `k` / [`SUN_SHARES`] of the lit floor's and the
/// rest the shadows' `shade`.
fn relit(rgb: [f64; 3], shade: [f64; 3], k: usize) -> [f64; 3] {
    let sun = k as f64 / SUN_SHARES as f64;
    std::array::from_fn(|c| rgb[c] / (sun + (1.0 - sun) * shade[c]).max(1e-6))
}

/// The least saturation a colour after white balance keeps, relit by any mix of the sun's light
/// and the shadows' `shade` (a sun's share α of 0, 0.1, …, 1; see [`shade_explains`]): the
/// tint that no shadow gives the floor. A shadow, or a soft one's rim, keeps little; a dark
/// top of another hue than the shadows' keeps its own.
pub fn least_relit_saturation(rgb: [f64; 3], shade: [f64; 3]) -> f64 {
    (0..=SUN_SHARES)
        .map(|k| saturation(relit(rgb, shade, k)))
        .fold(f64::INFINITY, f64::min)
}

/// The side in pixels of the squares for cells `cell_px` wide: at least 3.
pub fn square_px(cell_px: f64) -> usize {
    (OPENING * cell_px).round().max(3.0) as usize
}

/// Adds `by` to `v` (`sign` 1) or takes it away (−1).
fn step(v: &mut u32, by: u32, sign: i32) {
    *v = if sign > 0 { *v + by } else { *v - by };
}

/// The counts of a column (or a square) of pixels: see [`settle`].
#[derive(Clone, Copy, Debug, Default)]
struct Column {
    /// Pixels that lean pale or are already not floor (an obstacle's, or a colour that
    /// cannot be told), and specks of a mark's colour on pale surroundings.
    leaning: u32,
    /// Pixels of a robot or a goal.
    marks: u32,
    /// Floor-coloured pixels, leaning pale or not, and their colour sums.
    floor: u32,
    sums: [u32; 3],
}

impl Column {
    /// Adds (`sign` 1) or takes away (−1) a pixel of class code `c` and colour `p`.
    fn add(&mut self, c: u8, p: [u8; 3], sign: i32) {
        let step = |v: &mut u32, by: u32| step(v, by, sign);
        match c {
            _ if c == Class::Obstacle as u8 || c == Class::Unsure as u8 => {
                step(&mut self.leaning, 1)
            }
            PALE_ROBOT | PALE_GOAL => step(&mut self.leaning, 1),
            _ if c == Class::Robot as u8 || c == Class::Goal as u8 => step(&mut self.marks, 1),
            _ if c == PALE || c == PALE_SHADE || c == Class::Floor as u8 => {
                if c != Class::Floor as u8 {
                    step(&mut self.leaning, 1);
                }
                step(&mut self.floor, 1);
                for (sum, v) in self.sums.iter_mut().zip(p) {
                    step(sum, u32::from(v));
                }
            }
            _ => {}
        }
    }

    /// Adds (`sign` 1) or takes away (−1) another column's counts.
    fn merge(&mut self, o: &Column, sign: i32) {
        let step = |v: &mut u32, by: u32| step(v, by, sign);
        step(&mut self.leaning, o.leaning);
        step(&mut self.marks, o.marks);
        step(&mut self.floor, o.floor);
        for (sum, v) in self.sums.iter_mut().zip(o.sums) {
            step(sum, v);
        }
    }
}

/// Turns [`PALE`], [`PALE_ROBOT`] and [`PALE_GOAL`] pixels into obstacle pixels where they
/// lie in a pale `side` × `side` square (see the module's comment), and into floor, robot
/// and goal pixels elsewhere. Returns how each pixel that became floor leaned pale
/// ([`NOT_LEANED`], [`LEANED`] or [`LEANED_IN_SHADE`]; empty when none leaned):
/// [`super::faint`] reads tops of nearly the floor's colour from both, and [`super::looks`]
/// refuses a free cell whose floor mostly leans pale as [`PALE`] does.
pub fn settle(classes: &mut [u8], img: &RgbImage, classifier: &Classifier, side: usize) -> Vec<u8> {
    let width = img.width() as usize;
    if width == 0 || !classes.iter().any(|&c| leaning_code(c)) {
        return Vec::new();
    }
    let height = classes.len() / width;
    let side = side.max(1);
    let raw = img.as_raw();
    let need = (FULL * (side * side) as f64).ceil() as u32;
    // Rows with a leaning pixel, counted: a square without one changes nothing, and neither
    // does a row without one in the last pass.
    let has: Vec<bool> = classes
        .par_chunks(width)
        .map(|row| row.iter().any(|&c| leaning_code(c)))
        .collect();
    let mut before = vec![0usize; height + 1];
    for y in 0..height {
        before[y + 1] = before[y] + usize::from(has[y]);
    }
    let any_in = |y0: usize, y1: usize| before[y1.min(height)] > before[y0.min(height)];
    // Squares by their top-left corner, in bands of rows on all cores: the counts of their
    // pixels (see `Column`) over `side` rows (column sums, moved down a row at a time), then
    // along the row.
    let mut corner = vec![false; classes.len()];
    if height >= side && width >= side {
        let tops = height - side + 1;
        let add = |y: usize, sign: i32, cols: &mut [Column]| {
            for (x, col) in cols.iter_mut().enumerate() {
                let i = y * width + x;
                col.add(
                    classes[i],
                    [raw[3 * i], raw[3 * i + 1], raw[3 * i + 2]],
                    sign,
                );
            }
        };
        let corners_of = |band: usize, out: &mut [bool]| {
            let t0 = band * BAND_ROWS;
            if t0 >= tops {
                return;
            }
            let t1 = (t0 + BAND_ROWS).min(tops);
            if !any_in(t0, t1 + side - 1) {
                return;
            }
            let mut cols = vec![Column::default(); width];
            for y in t0..t0 + side {
                add(y, 1, &mut cols);
            }
            for top in t0..t1 {
                if top > t0 {
                    add(top - 1, -1, &mut cols);
                    add(top + side - 1, 1, &mut cols);
                }
                let mut sq = Column::default();
                for x in 0..width {
                    sq.merge(&cols[x], 1);
                    if x >= side {
                        sq.merge(&cols[x - side], -1);
                    }
                    if x + 1 >= side && sq.leaning >= need && sq.marks == 0 && sq.floor > 0 {
                        let f = sq.floor;
                        let mean = sq.sums.map(|v| ((v + f / 2) / f).min(255) as u8);
                        out[(top - t0) * width + x + 1 - side] = is_pale(classifier.balanced(mean));
                    }
                }
            }
        };
        corner
            .par_chunks_mut(width * BAND_ROWS)
            .enumerate()
            .for_each(|(band, out)| corners_of(band, out));
    }
    // A pixel is in a pale square when a corner lies within `side` − 1 up and to the left of
    // it: spread the corners right along rows, then down along columns (each band of rows
    // looking back `side` − 1 rows).
    // In place: each row's corners become the pixels they spread to.
    corner.par_chunks_mut(width).for_each(|row| {
        let mut last: Option<usize> = None;
        for (x, flag) in row.iter_mut().enumerate() {
            if *flag {
                last = Some(x);
            }
            *flag = last.is_some_and(|l| x - l < side);
        }
    });
    let right = corner;
    let mut leaned = vec![NOT_LEANED; classes.len()];
    classes
        .par_chunks_mut(width * BAND_ROWS)
        .zip(leaned.par_chunks_mut(width * BAND_ROWS))
        .enumerate()
        .for_each(|(band, (out, out_leaned))| {
            let y0 = band * BAND_ROWS;
            if !any_in(y0, y0 + BAND_ROWS) {
                return;
            }
            // The last row (absolute) at or above each pixel of the band's first row where
            // the spread corners reach.
            let mut last: Vec<Option<usize>> = vec![None; width];
            for y in y0.saturating_sub(side - 1)..y0 {
                for (x, l) in last.iter_mut().enumerate() {
                    if right[y * width + x] {
                        *l = Some(y);
                    }
                }
            }
            for (row, (line, line_leaned)) in out
                .chunks_mut(width)
                .zip(out_leaned.chunks_mut(width))
                .enumerate()
            {
                let y = y0 + row;
                for (x, (c, was)) in line.iter_mut().zip(line_leaned.iter_mut()).enumerate() {
                    if right[y * width + x] {
                        last[x] = Some(y);
                    }
                    if leaning_code(*c) {
                        let covered = last[x].is_some_and(|l| y - l < side);
                        *was = match *c {
                            _ if covered => NOT_LEANED,
                            PALE => LEANED,
                            PALE_SHADE => LEANED_IN_SHADE,
                            _ => NOT_LEANED,
                        };
                        *c = match *c {
                            _ if covered => Class::Obstacle as u8,
                            PALE_ROBOT => Class::Robot as u8,
                            PALE_GOAL => Class::Goal as u8,
                            _ => Class::Floor as u8,
                        };
                    }
                }
            }
        });
    leaned
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::aerial::colour::Hue;
    use crate::aerial::pixels::OUTSIDE;

    proptest::proptest! {
        #[test]
        fn saturation_at_least_answers_as_the_division(
            max in 1e-3f64..1e3,
            share in 0.0f64..1.0,
            t in 1e-3f64..1.0,
            ulps in -4i64..=4,
        ) {
            // Anywhere, and on the boundary itself (min where the division gives t), a few
            // doubles either side.
            let division = |min: f64| (max - min) / max >= t;
            for min in [max * share, f64::from_bits((max * (1.0 - t)).to_bits().wrapping_add_signed(ulps))] {
                if (0.0..=max).contains(&min) {
                    proptest::prop_assert_eq!(saturation_at_least(max, min, t), division(min), "{} {} {}", max, min, t);
                }
            }
        }
    }

    const F: u8 = Class::Floor as u8;
    const O: u8 = Class::Obstacle as u8;
    const R: u8 = Class::Robot as u8;

    /// An image of grey floor (150) with, by the letters of `rows`: `l` lilac (pale by its
    /// tint), `w` white (brighter than the floor can be), `r` a red speck on lilac, `x`
    /// outside the floor; the classes as [`super::super::pixels::classify`] gives them.
    fn scene(rows: &[&str]) -> (Vec<u8>, RgbImage, Classifier) {
        let (w, h) = (rows[0].len() as u32, rows.len() as u32);
        let classifier = Classifier::new([150.0; 3], Hue::RED, Hue::GREEN);
        let colour = |c: u8| match c {
            b'l' => [168, 145, 175],
            b'w' => [240, 240, 240],
            b'r' => [200, 40, 40],
            _ => [150, 150, 150],
        };
        let img = RgbImage::from_fn(w, h, |x, y| {
            image::Rgb(colour(rows[y as usize].as_bytes()[x as usize]))
        });
        let classes = rows
            .iter()
            .flat_map(|r| {
                r.bytes().map(|b| match b {
                    b'x' => OUTSIDE,
                    b'r' => PALE_ROBOT,
                    _ if is_leaning_with(classifier.balanced(colour(b)), LEANING.2) => PALE,
                    _ => F,
                })
            })
            .collect();
        (classes, img, classifier)
    }

    #[test]
    fn a_pale_square_becomes_an_obstacle_and_a_thin_line_stays_floor() {
        let (mut c, img, classifier) = scene(&[
            "..w.......",
            "..w.llll..",
            "..w.lrll..",
            "..w.llll.l",
            "..w.......",
        ]);
        let _ = settle(&mut c, &img, &classifier, 3);
        // The lilac block (its red speck too): obstacle; the white line and the speck of
        // lilac: floor.
        for y in 0..5 {
            for x in 0..10 {
                let want = if (1..=3).contains(&y) && (4..=7).contains(&x) {
                    O
                } else {
                    F
                };
                assert_eq!(c[y * 10 + x], want, "pixel ({x}, {y})");
            }
        }
    }

    #[test]
    fn a_square_with_a_mark_in_it_is_no_shelf_top() {
        // A white block with a goal's pixel in its middle: every 3 × 3 square of it holds
        // the goal's pixel, so none is a pale top; the 4 × 4 block without it is.
        let rows = [
            "wwwww.wwww",
            "wwwww.wwww",
            "wwgww.wwww",
            "wwwww.wwww",
            "wwwww.....",
        ];
        let (mut c, img, classifier) = scene(&rows);
        let g = 2 * 10 + 2;
        c[g] = Class::Goal as u8;
        let _ = settle(&mut c, &img, &classifier, 5);
        assert_eq!(c[g], Class::Goal as u8);
        assert!((0..5).all(|y| (0..5).all(|x| c[y * 10 + x] != O || (x, y) == (2, 2))));
        let (mut c, img, classifier) = scene(&rows);
        let _ = settle(&mut c, &img, &classifier, 4);
        assert!((0..4).all(|y| (6..10).all(|x| c[y * 10 + x] == O)));
    }

    #[test]
    fn a_pale_l_keeps_only_what_a_square_fits_in() {
        let (mut c, img, classifier) = scene(&["www...", "www...", "wwwwww", "ww...r"]);
        let _ = settle(&mut c, &img, &classifier, 3);
        let obstacle: Vec<usize> = (0..c.len()).filter(|&i| c[i] == O).collect();
        // The 3 × 3 square at the top-left, and the one below it, 8 of its 9 pixels white
        // ([`FULL`]); the rest of the arm along row 2 is narrower than a square; the red
        // speck alone is a robot's pixel again.
        assert_eq!(obstacle, vec![0, 1, 2, 6, 7, 8, 12, 13, 14, 18, 19]);
        assert_eq!(c[23], R);
        assert!(!c.iter().any(|&k| leaning_code(k)));
    }

    #[test]
    fn a_square_must_be_pale_on_average_not_only_lean() {
        // Pixels that lean pale (saturation 0.13, as bright as the floor) but whose mean is
        // not tinted enough (under 0.17) stay floor.
        let classifier = Classifier::new([150.0; 3], Hue::RED, Hue::GREEN);
        let faint = [150u8, 130, 150];
        assert!(is_leaning_with(classifier.balanced(faint), LEANING.2));
        assert!(!is_pale(classifier.balanced(faint)));
        let img = RgbImage::from_pixel(6, 6, image::Rgb(faint));
        let mut c = vec![PALE; 36];
        let _ = settle(&mut c, &img, &classifier, 3);
        assert!(c.iter().all(|&k| k == F));
    }

    #[test]
    fn pale_means_brighter_than_the_floor_or_lit_and_tinted() {
        assert!(!is_pale([1.0, 1.0, 1.0]));
        assert!(!is_pale([1.3, 1.32, 1.28]));
        assert!(is_pale([1.6, 1.6, 1.55]));
        // Lit and tinted: lilac at the floor's brightness.
        assert!(is_pale([1.0, 0.85, 1.05]));
        // Tinted but dark: a shadow under a blue sky, not judged here.
        assert!(!is_pale([0.4, 0.5, 0.7]));
        assert!(!is_leaning_with([0.4, 0.5, 0.7], LEANING.2));
        assert!(is_leaning_with([1.35, 1.3, 1.3], LEANING.2));
    }

    #[test]
    fn nothing_pale_changes_nothing() {
        let (mut c, img, classifier) = scene(&["..x", "...", "x.."]);
        let before = c.clone();
        let _ = settle(&mut c, &img, &classifier, 3);
        assert_eq!(c, before);
        assert_eq!(square_px(8.0), 4);
        assert_eq!(square_px(4.0), 3);
        assert_eq!(square_px(30.0), 15);
    }

    #[test]
    fn the_shadows_colour_is_the_median_of_enough_shaded_samples() {
        // Too few samples, or too small a share of the floor's.
        assert_eq!(shade(&mut [[0.5, 0.55, 0.7]; 10], 100), None);
        assert_eq!(shade(&mut vec![[0.5, 0.55, 0.7]; 40], 4000), None);
        let mut shaded: Vec<[f64; 3]> = (0..40)
            .map(|k| [0.5 + 0.001 * k as f64, 0.6, 0.7 - 0.001 * k as f64])
            .collect();
        let got = shade(&mut shaded, 400).unwrap();
        assert!((got[0] - 0.52).abs() < 1e-12, "{got:?}");
        assert_eq!(got[1], 0.6);
        assert!((got[2] - 0.681).abs() < 1e-12, "{got:?}");
        assert!(shade_bright([0.5, 0.6, 0.7]));
        assert!(!shade_bright([0.2, 0.25, 0.28]), "a painted line's dark");
        assert!(!shade_bright([0.8, 0.8, 0.85]), "lit");
    }

    #[test]
    fn a_tint_the_sky_s_light_gives_the_floor_is_explained_and_a_pale_top_s_is_not() {
        // The floor in a shadow under a blue sky, after white balance on the sunlit floor.
        let sky = [0.55, 0.62, 0.75];
        // Half the sun's light (a soft shadow's rim): lit by the loose limit, and tinted.
        let rim = [0.775, 0.81, 0.875];
        assert!(is_leaning_with(rim, LEANING.2));
        assert!(shade_explains(rim, sky, LEANING.2));
        // Lilac at the floor's brightness: another hue than the sky's.
        let lilac = [1.0, 0.85, 1.05];
        assert!(is_leaning_with(lilac, LEANING.2));
        assert!(!shade_explains(lilac, sky, LEANING.2));
        // A pale blue top: the sky's hue, but relit brighter than the floor can be.
        let blue = [1.05, 1.1, 1.25];
        assert!(is_leaning_with(blue, LEANING.2));
        assert!(!shade_explains(blue, sky, LEANING.2));
        // Under a grey sky the rim is grey, and a tinted pixel stays unexplained.
        assert!(!shade_explains(rim, [0.6, 0.6, 0.6], LEANING.2));
        // The classifier knows no shadows' colour until it is told one.
        let classifier = Classifier::new([150.0; 3], Hue::RED, Hue::GREEN);
        assert!(!classifier.shaded(rim));
        assert!(classifier.with_shade(Some(sky)).shaded(rim));
        assert_eq!(
            pale_code(&classifier.with_shade(Some(sky)), rim),
            PALE_SHADE
        );
        assert_eq!(pale_code(&classifier, rim), PALE);
    }

    #[test]
    fn a_dark_top_keeps_a_tint_the_shadows_light_does_not_give() {
        let sky = [0.55, 0.62, 0.75];
        // The shadow itself, its rim, and the lit floor keep no tint.
        assert!(least_relit_saturation(sky, sky) < 1e-9);
        assert!(least_relit_saturation([0.775, 0.81, 0.875], sky) < 1e-9);
        assert!(least_relit_saturation([1.0, 1.0, 1.0], sky) < 1e-9);
        // A dark grey top lit by the sun, warmer than the shadows, keeps its own tint.
        let top = [0.6, 0.56, 0.5];
        assert!(
            least_relit_saturation(top, sky) > 0.15,
            "{}",
            least_relit_saturation(top, sky)
        );
        // Under a grey sky the shadows explain no tint: a top's saturation is its own.
        assert!((least_relit_saturation(top, [0.6; 3]) - saturation(top)).abs() < 1e-9);
    }

    #[test]
    fn pixels_leaning_by_the_shadows_tint_make_pale_tops_but_are_told_apart_as_floor() {
        let rows = ["llll...l", "llll....", "llll....", "llll...."];
        for (code, left) in [(PALE, LEANED), (PALE_SHADE, LEANED_IN_SHADE)] {
            let (mut c, img, classifier) = scene(&rows);
            for k in c.iter_mut().filter(|k| **k == PALE) {
                *k = code;
            }
            let leaned = settle(&mut c, &img, &classifier, 3);
            // The 4 × 4 block is a top either way; the lone pixel is floor that leaned.
            assert!((0..4).all(|y| (0..4).all(|x| c[y * 8 + x] == O)), "{c:?}");
            assert_eq!(c[7], F);
            assert_eq!(leaned[7], left);
            assert_eq!(leaned[0], NOT_LEANED, "a top's pixel");
            assert_eq!(leaned[12], NOT_LEANED, "floor");
        }
    }

    #[test]
    fn the_leaning_tint_rises_with_the_floor_s_own() {
        // A clean floor keeps the loose limit; a noisy one twice its median saturation.
        assert_eq!(lean_tint(&mut []), LEANING.2);
        assert_eq!(lean_tint(&mut [0.03, 0.01, 0.04]), LEANING.2);
        let mut noisy = [0.2, 0.05, 0.09, 0.12, 0.08];
        assert!((lean_tint(&mut noisy) - 0.18).abs() < 1e-12);
        assert!(is_leaning_with([1.0, 0.85, 0.85], 0.1));
        assert!(!is_leaning_with([1.0, 0.85, 0.85], 0.18));
        // Brightness leans whatever the tint.
        assert!(is_leaning_with([1.35, 1.35, 1.35], 0.5));
    }
}
