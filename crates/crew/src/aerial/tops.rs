//! A half-covered cell that something stands on: a block inside it, or a pale shelf's top.
//!
//! A shelf with cartons on a pale top reads as a block of obstacle inside a frame read as
//! floor; a shelf's top of a pale colour reads partly as obstacle and partly as floor. Either
//! cell's window reads 30–70 % covered, and no neighbour's leaning top explains it, so it was
//! refused. Two kinds of evidence that the cover stands on the cell itself:
//! - [`standing`]: the covered bins (see [`super::cover`]) stay off the cell's outer row and
//!   column of bins on the sides toward the nadir. A neighbour's top leaning over the cell
//!   enters it across the border it shares with that neighbour, on the side toward the
//!   nadir; a block in the middle of the cell does not reach that border.
//! - [`Window::pale_top`]: the pixels read as floor are a paler shade of the obstacle pixels
//!   beside them, as follows.
//! - [`Window::top_read_as_floor`] (since issue #29's twenty-sixth round): the pixels read as
//!   floor are of the obstacle pixels' colour, not the free floor's around the cell. Then the
//!   whole window is the top's, and the cell is judged as a covered one (a neighbour's top may
//!   still cover it almost whole: see [`super::cover`]), whatever its neighbours.
//!
//! The pixels of the window read as floor tell it apart from a free cell half under a
//! shelf's edge: on a shelf's top they are lit (no shadow), clearly tinted after white
//! balance ([`TINT`]; the lit floor is grey, and the floor pixels of the half-covered free
//! cells of the eighth round's family G scenes read 0.01–0.14), more tinted than the lit
//! free floor around the cell ([`ABOVE_RING`]), and of the hue of the obstacle pixels beside
//! them ([`SAME_HUE`]): one surface, not floor beside a shelf.
//!
//! A free cell under the leaning top of a pale shelf, or of one with cartons on a pale top,
//! would look the same, so either evidence counts only when no neighbour on the cell's side
//! toward the nadir (whose top could lean over it) is covered more than
//! [`super::HALF_COVERED`]'s lower bound; otherwise the cell is refused as before. That is
//! the limit: in a rack two or more cells deep, or a run of cells along the nadir's
//! direction, the cells beyond the first are leaned on by their own shelf's cells and stay
//! refused (the lean k of the neighbour's top is not known: a camera's height is not
//! recovered from the corners).

use super::colour::{hue_saturation, Class, Classifier};
use super::cover::{Bins, BINS};
use super::homography::Homography;
use super::pixels::window;
use image::RgbImage;

/// The least saturation after white balance of a pale top's floor-coloured pixels (mean
/// colour of the window's floor pixels).
pub const TINT: f64 = 0.2;
/// The least saturation above the lit free floor around the cell.
pub const ABOVE_RING: f64 = 0.12;
/// The largest hue difference (degrees) between the window's floor pixels and its obstacle
/// pixels.
pub const SAME_HUE: f64 = 30.0;
/// At least this bright (the brightest channel of the mean colour, 1 for the lit floor).
pub const LIT: f64 = 0.85;
/// The fewest floor and obstacle pixels the window must show.
pub const MIN_PIXELS: usize = 12;
/// The fewest lit free neighbours (of the eight) the cell is compared with.
pub const RING_MIN: usize = 2;

/// The mean colours after white balance of a cell's window (the part counted by
/// [`super::pixels::coverage`]): its obstacle pixels and its floor pixels.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Window {
    /// Mean colour and count of the obstacle pixels.
    pub obstacle: ([f64; 3], usize),
    /// Mean colour and count of the floor pixels.
    pub floor: ([f64; 3], usize),
}

impl Window {
    /// The floor pixels' saturation, when they are lit and enough (a free neighbour's
    /// measure for the ring).
    pub fn lit_floor_saturation(&self) -> Option<f64> {
        let (rgb, n) = self.floor;
        let bright = rgb[0].max(rgb[1]).max(rgb[2]);
        (n >= MIN_PIXELS && bright >= LIT).then(|| hue_saturation(rgb).1)
    }

    /// The floor pixels' mean colour, when they are lit and enough (a free neighbour's
    /// measure for [`Window::top_read_as_floor`]'s ring).
    pub fn lit_floor(&self) -> Option<[f64; 3]> {
        let (rgb, n) = self.floor;
        let bright = rgb[0].max(rgb[1]).max(rgb[2]);
        (n >= MIN_PIXELS && bright >= LIT).then_some(rgb)
    }

    /// Whether the floor pixels are a pale shade of the obstacle pixels (see the module's
    /// comment), against `ring`, the saturations of the lit free neighbours.
    pub fn pale_top(&self, ring: &[f64]) -> bool {
        if self.obstacle.1 < MIN_PIXELS || ring.len() < RING_MIN {
            return false;
        }
        let Some(s) = self.lit_floor_saturation() else {
            return false;
        };
        let mut ring = ring.to_vec();
        ring.sort_by(f64::total_cmp);
        let median = ring[ring.len() / 2];
        let (hf, _) = hue_saturation(self.floor.0);
        let (ho, so) = hue_saturation(self.obstacle.0);
        let d = (hf - ho).rem_euclid(360.0);
        s >= TINT && s - median >= ABOVE_RING && so >= s && d.min(360.0 - d) <= SAME_HUE
    }
}

/// How unlike two colours are: 100 times the log of their brightness ratio (the sum of the
/// channels), plus 300 times the sum of the differences of their chromaticities (each channel
/// over that sum). The lit floor and a shadow on it differ by about 40–70; two pixels' worth of
/// one surface's noise by a few.
pub fn unlike(a: [f64; 3], b: [f64; 3]) -> f64 {
    let (la, lb) = (a[0] + a[1] + a[2], b[0] + b[1] + b[2]);
    if la <= 0.0 || lb <= 0.0 {
        return f64::INFINITY;
    }
    let chroma: f64 = (0..3).map(|c| (a[c] / la - b[c] / lb).abs()).sum();
    100.0 * (la / lb).ln().abs() + 300.0 * chroma
}

/// The floor pixels of a top read as floor are at most this share as unlike the obstacle
/// pixels beside them as they are unlike the free floor around the cell.
pub const TOP_NOT_FLOOR: f64 = 0.2;
/// ... and at least this unlike the free floor around ([`unlike`]).
pub const FLOOR_APART: f64 = 15.0;

impl Window {
    /// Whether the window's floor pixels are the obstacle's, read as floor: lit (at least
    /// [`LIT`] as bright as the free floor around), and of the colour of the window's obstacle
    /// pixels rather than of `ring`, the mean colours of the floor pixels of the lit free
    /// neighbours ([`TOP_NOT_FLOOR`], [`FLOOR_APART`]), and unlike each of those (a free
    /// neighbour whose floor is of the top's colour may be the same top, all read as floor:
    /// p0003's dark brown shelf). A top of nearly the floor's colour
    /// (tan on sand, lilac on grey, grey on a darker grey) reads partly as floor where its
    /// light or noise brings it near the floor's colour, yet those pixels keep the top's
    /// colour, not the floor's; a free cell's floor pixels beside a shelf's edge keep the
    /// floor's, a glow on the floor lies between the two (issue #29's twenty-sixth round).
    pub fn top_read_as_floor(&self, ring: &[[f64; 3]]) -> bool {
        let ((floor, nf), (obstacle, no)) = (self.floor, self.obstacle);
        if nf < MIN_PIXELS || no < MIN_PIXELS || ring.len() < RING_MIN {
            return false;
        }
        let channel = |c: usize| {
            let mut v: Vec<f64> = ring.iter().map(|r| r[c]).collect();
            v.sort_by(f64::total_cmp);
            v[v.len() / 2]
        };
        let around = [channel(0), channel(1), channel(2)];
        let bright = |c: [f64; 3]| c[0] + c[1] + c[2];
        let apart = unlike(floor, around);
        bright(floor) >= LIT * bright(around)
            && apart >= FLOOR_APART
            && unlike(floor, obstacle) <= TOP_NOT_FLOOR * apart
            && ring.iter().all(|&r| unlike(floor, r) >= FLOOR_APART)
    }
}

/// The fewest covered bins (of [`BINS`]²) of an object standing on the cell.
pub const STANDING: usize = 25;
/// A bin is covered at this share of obstacle pixels (as in [`super::cover`]).
const COVERED: f64 = 0.6;

/// Whether a cell's cover stands on it: at least [`STANDING`] covered bins, none of them in the
/// outer row or column of bins on a side toward the nadir `toward` (−1, 0 or 1 along each
/// axis; 0: the nadir is level with the cell, both sides). A neighbour's top leaning over the
/// cell covers it from the border it shares with that neighbour, on the side toward the
/// nadir; cartons on a pale shelf's top, read as obstacle inside a frame read as floor, do
/// not reach it.
pub fn standing(bins: &Bins, toward: (i32, i32)) -> bool {
    let last = BINS - 1;
    let mut covered = 0;
    for v in 0..BINS {
        for u in 0..BINS {
            let k = v * BINS + u;
            let (o, f) = (bins.obstacle[k], bins.floor[k]);
            if o + f == 0 || f64::from(o) < COVERED * f64::from(o + f) {
                continue;
            }
            let near = |at: usize, side: i32| (at == 0 && side <= 0) || (at == last && side >= 0);
            if near(u, toward.0) || near(v, toward.1) {
                return false;
            }
            covered += 1;
        }
    }
    covered >= STANDING
}

/// The least share of the bins along a cell's far border (away from the nadir) that its own
/// leaning top covers ([`faced`]).
pub const FAR_EDGE: f64 = 0.8;

/// How far (bins) the inner edge of a top's band may wander across the cell ([`faced`]).
pub const EDGE_SPREAD: usize = 3;

/// Whether a cell's cover is its own top, leaning away from the nadir, with its face toward
/// the nadir not read as an obstacle (a face in the shelf's own shadow reads as floor in a
/// shadow): along an axis on which the nadir lies to one side (`toward`, −1 or 1; see
/// [`standing`]), at least [`FAR_EDGE`] of the bins along the cell's far border are covered,
/// none along its near border, and [`STANDING`] bins in all, each line of bins across the
/// cell covered from the far border inward to depths within [`EDGE_SPREAD`] of each other
/// (a top's straight edge), and at most [`super::cover::MISFIT`] of the bins covered
/// beyond (the face's noise, or its colour read as an obstacle's in places), while
/// `clear[axis]`: the
/// neighbours toward the nadir along that axis (beside it and diagonally) are not covered, so
/// no top of theirs leans over the cell. A neighbour's top enters a cell across the border
/// toward the nadir, never across the far one. When `across[axis]`, the neighbour toward the
/// nadir along the other axis is mostly covered, and its top, leaning both ways, may reach
/// the far side along this axis across the border they share: then no bin along that border
/// may be covered, or the band must run across the whole cell (a top leaning off that
/// neighbour covers the cell's part next to it; K0038's free cell (8, 19), under the end of a
/// pale top leaning over (7, 19), was read blocked at first).
/// Since issue #29's twenty-fourth round: a shelf whose face is dark reads 40–70 % covered on
/// its own cells, its top half over the cells beyond.
pub fn faced(bins: &Bins, toward: (i32, i32), clear: [bool; 2], across: [bool; 2]) -> bool {
    let last = BINS - 1;
    let covered = |u: usize, v: usize| {
        let k = v * BINS + u;
        let (o, f) = (bins.obstacle[k], bins.floor[k]);
        o + f > 0 && f64::from(o) >= COVERED * f64::from(o + f)
    };
    let count = (0..BINS)
        .flat_map(|v| (0..BINS).map(move |u| (u, v)))
        .filter(|&(u, v)| covered(u, v))
        .count();
    if count < STANDING {
        return false;
    }
    [toward.0, toward.1]
        .into_iter()
        .enumerate()
        .any(|(axis, side)| {
            if side == 0 || !clear[axis] {
                return false;
            }
            let ends = |side: i32| if side > 0 { (last, 0) } else { (0, last) };
            let (near, far) = ends(side);
            let other_side = if axis == 0 { toward.1 } else { toward.0 };
            // Whether the bin `along` this axis and `across` it is covered.
            let bin = |along: usize, across: usize| {
                if axis == 0 {
                    covered(along, across)
                } else {
                    covered(across, along)
                }
            };
            // Across the cell, the covered bins from the far border inward: a solid band whose
            // inner edge is straight (a top's edge), not a speckle of noise or texture.
            let inward = |k: usize| if far == 0 { k } else { last - k };
            let mut depths = Vec::with_capacity(BINS);
            let mut strays = 0;
            for j in 0..BINS {
                let depth = (0..BINS).take_while(|&k| bin(inward(k), j)).count();
                strays += (depth..BINS).filter(|&k| bin(inward(k), j)).count();
                if depth > 0 {
                    depths.push(depth);
                }
            }
            if strays as f64 > super::cover::MISFIT * (BINS * BINS) as f64 {
                return false;
            }
            let (lo, hi) = (
                depths.iter().copied().min().unwrap_or(0),
                depths.iter().copied().max().unwrap_or(0),
            );
            // Nothing along the near border; the far border covered (the lines with a depth);
            // along the border toward the nadir on the other axis, nothing or the band whole.
            let shared = ends(other_side).0;
            (0..BINS).all(|j| !bin(near, j))
                && depths.len() as f64 >= FAR_EDGE * BINS as f64
                && hi - lo <= EDGE_SPREAD
                && (!across[axis] || (0..BINS).all(|k| !bin(k, shared)) || depths.len() == BINS)
        })
}

/// The mean colours of cell `(cx, cy)`'s window (see [`Window`]).
pub fn window_colours(
    img: &RgbImage,
    classes: &[u8],
    classifier: &Classifier,
    (floor_to_image, image_to_floor): (&Homography, &Homography),
    nadir: Option<(f64, f64)>,
    (cx, cy): (u32, u32),
) -> Window {
    let width = img.width() as usize;
    let (fx, fy) = (f64::from(cx), f64::from(cy));
    let (wu, wv) = (
        window(fx, nadir.map(|n| n.0)),
        window(fy, nadir.map(|n| n.1)),
    );
    let mut sums = [[0.0; 3]; 2];
    let mut counts = [0usize; 2];
    if let Some((x0, y0, x1, y1)) = floor_to_image.cell_box((cx, cy), width, img.height() as usize)
    {
        for y in y0..y1 {
            for x in x0..x1 {
                let k = match classes[y * width + x] {
                    c if c == Class::Obstacle as u8 => 0,
                    c if c == Class::Floor as u8 => 1,
                    _ => continue,
                };
                let Some((u, v)) = image_to_floor.apply((x as f64 + 0.5, y as f64 + 0.5)) else {
                    continue;
                };
                let (du, dv) = (u - fx, v - fy);
                if du < wu.0 || du > wu.1 || dv < wv.0 || dv > wv.1 {
                    continue;
                }
                let rgb = classifier.balanced(img.get_pixel(x as u32, y as u32).0);
                for c in 0..3 {
                    sums[k][c] += rgb[c];
                }
                counts[k] += 1;
            }
        }
    }
    let mean = |k: usize| {
        let n = counts[k].max(1) as f64;
        ([sums[k][0] / n, sums[k][1] / n, sums[k][2] / n], counts[k])
    };
    Window {
        obstacle: mean(0),
        floor: mean(1),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn win(obstacle: [f64; 3], floor: [f64; 3]) -> Window {
        Window {
            obstacle: (obstacle, 100),
            floor: (floor, 100),
        }
    }

    #[test]
    fn colours_are_unlike_by_brightness_and_chromaticity() {
        let grey = [1.0, 1.0, 1.0];
        assert_eq!(unlike(grey, grey), 0.0);
        // A shadow at half the light: 100 ln 2.
        assert!((unlike(grey, [0.5, 0.5, 0.5]) - 100.0 * 2f64.ln()).abs() < 1e-9);
        // As bright, a tint: 300 times the chromaticities' differences.
        let tan = [1.2, 1.0, 0.8];
        assert!((unlike(grey, tan) - 300.0 * (0.4 / 3.0)).abs() < 1e-9);
        assert_eq!(unlike(grey, tan), unlike(tan, grey));
        assert!(unlike([0.0; 3], grey).is_infinite());
    }

    #[test]
    fn a_top_read_as_floor_keeps_the_top_s_colour() {
        // A tan top on a grey floor: its floor pixels tan, as its obstacle pixels.
        let ring = [[1.0, 1.0, 1.0], [0.98, 1.0, 1.02], [1.02, 1.0, 0.98]];
        let tan = [1.1, 0.98, 0.78];
        let top = win([1.12, 0.98, 0.76], tan);
        assert!(top.top_read_as_floor(&ring));
        // A free cell beside a shelf's edge: its floor pixels grey.
        assert!(!win([1.12, 0.98, 0.76], [1.0, 0.99, 0.98]).top_read_as_floor(&ring));
        // A glow between the floor and the top.
        assert!(!win([1.12, 0.98, 0.76], [1.05, 0.99, 0.88]).top_read_as_floor(&ring));
        // A shadow of the obstacle's tint, darker than the lit floor.
        assert!(!win([0.55, 0.5, 0.4], [0.55, 0.5, 0.4]).top_read_as_floor(&ring));
        // A top nearly the floor's colour: too near to tell (FLOOR_APART).
        assert!(!win([1.0, 1.0, 0.97], [1.0, 1.0, 0.97]).top_read_as_floor(&ring));
        // A free neighbour whose floor is of the top's colour: it may be the same top.
        let mut with_top = ring.to_vec();
        with_top.push([1.1, 0.97, 0.78]);
        assert!(!top.top_read_as_floor(&with_top));
        // Too few free neighbours, or pixels, to judge.
        assert!(!top.top_read_as_floor(&ring[..1]));
        let few = Window {
            obstacle: ([1.12, 0.98, 0.76], 5),
            floor: (tan, 100),
        };
        assert!(!few.top_read_as_floor(&ring));
    }

    #[test]
    fn a_pale_lilac_top_is_one_surface() {
        // G0004's cell (13, 11): lilac read partly as obstacle, partly as floor.
        let w = win([1.26, 0.99, 1.33], [1.27, 1.02, 1.33]);
        assert!(w.pale_top(&[0.04, 0.02, 0.05]));
    }

    fn bins(covered: impl Fn(usize, usize) -> bool) -> Bins {
        let mut b = Bins {
            obstacle: [0; BINS * BINS],
            floor: [0; BINS * BINS],
        };
        for v in 0..BINS {
            for u in 0..BINS {
                if covered(u, v) {
                    b.obstacle[v * BINS + u] = 4;
                } else {
                    b.floor[v * BINS + u] = 4;
                }
            }
        }
        b
    }

    #[test]
    fn a_carton_inside_a_pale_frame_stands_on_the_cell() {
        // G0001's cell (2, 6): a carton in rows 1-6, columns 2-7; the nadir lies left and below.
        let carton = bins(|u, v| (2..=7).contains(&u) && (1..=6).contains(&v));
        assert!(standing(&carton, (-1, 1)));
        assert!(standing(&carton, (0, 0)));
        // Touching the top row is allowed when the nadir is below.
        let top = bins(|u, v| (2..=7).contains(&u) && v <= 5);
        assert!(standing(&top, (-1, 1)));
        assert!(!standing(&top, (0, -1)));
    }

    #[test]
    fn a_leaning_top_or_a_speck_does_not() {
        // A band along the border toward the nadir (left), a small speck.
        assert!(!standing(&bins(|u, _| u <= 4), (-1, 0)));
        assert!(!standing(
            &bins(|u, v| u == 0 || (3..=6).contains(&u) && v < 8),
            (-1, 0)
        ));
        assert!(!standing(
            &bins(|u, v| (4..=6).contains(&u) && (4..=6).contains(&v)),
            (0, 0)
        ));
    }

    #[test]
    fn a_top_leaning_off_its_own_cell_over_its_face_is_its_own() {
        // The nadir below: the top covers the cell's upper four rows of bins, its face (read
        // as floor) the rest, down to the border toward the nadir.
        let band = bins(|_, v| v <= 3);
        let below = (0, 1);
        assert!(faced(&band, below, [false, true], [false, false]));
        // Unless a neighbour toward the nadir is covered (its top could lean over the cell),
        // or the nadir lies level with the cell along that axis.
        assert!(!faced(&band, below, [true, false], [false, false]));
        assert!(!faced(&band, (0, 0), [true, true], [false, false]));
        // Covered to the border toward the nadir: a neighbour's top, or the cell's own whole.
        assert!(!faced(
            &bins(|_, v| v >= 6),
            below,
            [false, true],
            [false, false]
        ));
        assert!(!faced(
            &bins(|_, _| true),
            below,
            [false, true],
            [false, false]
        ));
        // Too little of the far border: a top's corner.
        assert!(!faced(
            &bins(|u, v| v <= 5 && u <= 5),
            below,
            [false, true],
            [false, false]
        ));
        // A ragged band: U0034's free cell (3, 8), floor's texture read as an obstacle's.
        let ragged = [3, 2, 1, 2, 2, 2, 2, 2, 3, 6];
        assert!(!faced(
            &bins(|u, v| v < ragged[u]),
            below,
            [false, true],
            [false, false]
        ));
        // A few specks in the face are its noise; many are not.
        let specks = bins(|u, v| v <= 3 || (v == 6 && u % 3 == 0));
        assert!(faced(&specks, below, [false, true], [false, false]));
        let many = bins(|u, v| v <= 3 || ((6..=7).contains(&v) && u % 2 == 0) || (v == 8 && u < 3));
        assert!(!faced(&many, below, [false, true], [false, false]));
    }

    #[test]
    fn a_top_leaning_diagonally_from_a_neighbour_along_the_other_axis_is_not() {
        // The nadir above and to the right; a covered neighbour above may lean its top over the
        // cell's upper part, and, leaning left too, along its left border (the far one along
        // x): K0038's free cell (8, 19), its band ending short of the bottom border.
        let toward = (1, -1);
        let corner = bins(|u, v| u <= 3 && v <= 7);
        assert!(faced(&corner, toward, [true, false], [false, false]));
        assert!(!faced(&corner, toward, [true, false], [true, false]));
        // The band across the whole cell, to the far border along y too: the cell's own top,
        // a run's (e.g. Y0021's (0, 8), K0039's (20, 4)).
        let left = bins(|u, _| u <= 3);
        assert!(faced(&left, toward, [true, false], [true, false]));
        // Clear of the border toward that neighbour, it is the cell's own too.
        let clear = bins(|u, v| u <= 3 && v >= 2);
        assert!(faced(&clear, toward, [true, false], [true, false]));
    }

    #[test]
    fn floor_beside_a_shelf_is_not() {
        // Grey floor (G0011's free cells), a shadow, another hue, a tinted ring, too few.
        let amber = [1.20, 1.0, 0.83];
        assert!(!win(amber, [1.14, 1.10, 1.05]).pale_top(&[0.03, 0.0, 0.02]));
        assert!(!win(amber, [0.70, 0.60, 0.50]).pale_top(&[0.03, 0.0, 0.02]));
        assert!(!win(amber, [0.95, 0.80, 1.10]).pale_top(&[0.03, 0.0, 0.02]));
        assert!(!win(amber, [1.2, 1.0, 0.9]).pale_top(&[0.15, 0.12, 0.14]));
        assert!(!win(amber, [1.2, 1.0, 0.9]).pale_top(&[0.03]));
        let few = Window {
            obstacle: (amber, 5),
            floor: ([1.2, 1.0, 0.9], 100),
        };
        assert!(!few.pale_top(&[0.03, 0.0, 0.02]));
    }
}
