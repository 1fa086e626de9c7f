//! Painted lines must show between free cells.
//!
//! Lines painted on a floor along the cell borders are hidden by whatever stands on them. A
//! shelf of nearly the floor's colour and brightness, under a high sun that gives it hardly a
//! shadow, looks like floor in every test of [`super::looks`] and [`super::shadows`] (issue
//! #29's held-out family S, S0005: a pale grey shelf two cells long on light concrete, read as
//! free), yet the line between its two cells is not there.
//!
//! So, on a floor with painted lines, every border between two cells read free is measured:
//! the mean brightness (after white balance) of its floor pixels within [`LINE`] of the border,
//! against that of the floor pixels from [`SIDE`].0 to [`SIDE`].1 of it on each side, over the
//! middle [`ALONG`] of the border (away from the lines across it), as a share of the latter;
//! the line's contrast is the larger of the two the lines' way (brighter or darker than the
//! floor, by the median of the borders' mean contrasts), as a shadow's edge along a border
//! darkens one side only. Pixels near a mark (within a quarter cell: its shadow and its blurred
//! edge), and any not read as floor, are left out; a border with fewer than [`MIN_PIXELS`] on
//! either band, or under half of the band's pixels, is not judged (a robot standing on it). The floor has painted lines
//! when the borders' median contrast is at least [`PAINTED`] either way (bright or dark lines)
//! and a consistent one: at least [`STEADY`] of the median at the borders' lower fifth. A
//! border whose contrast is then under [`MISSING`] of the median is refused: something of the
//! floor's colour may stand over it.
//!
//! A floor whose lines run at every second border only, or not at all, is not judged. Cost:
//! O(pixels of the free cells' borders), once.

use super::colour::{Class, Classifier};
use super::homography::Homography;
use super::looks::NEAR_HALO;
use image::RgbImage;

/// Half the band of a border measured as its line, in cells, and at least [`LINE_PX`] pixels
/// (a line thinner than a pixel darkens one pixel or two, as it falls).
pub const LINE: f64 = 0.05;
/// The least half band of a line, in pixels.
pub const LINE_PX: f64 = 1.0;
/// The band on each side of a border measured as floor beside its line, in cells (from at
/// least twice the line's half band).
pub const SIDE: (f64, f64) = (0.12, 0.3);
/// The middle of a border measured, along it (in cells).
pub const ALONG: (f64, f64) = (0.2, 0.8);
/// The fewest floor pixels in each band of a judged border.
pub const MIN_PIXELS: usize = 6;
/// The least median contrast of painted lines (either way).
pub const PAINTED: f64 = 0.12;
/// The borders' lower fifth must show at least this share of the median contrast.
pub const STEADY: f64 = 0.5;
/// A border showing under this share of the median contrast misses its line.
pub const MISSING: f64 = 0.25;

/// A border between two free cells whose painted line does not show.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Missing {
    /// The two cells, (x, y) each.
    pub cells: [(u32, u32); 2],
    /// The image point at the border's middle.
    pub at: (f64, f64),
    /// Its contrast, and the median contrast of the floor's borders.
    pub contrast: (f64, f64),
}

/// A border between two cells: the cell before it, and whether it is the cell's right border
/// (else its lower one).
type Border = ((u32, u32), bool);
/// A border's contrast against the floor on each side of it.
type Contrast = (f64, f64);

/// At most this many borders, spread over the floor, first tell whether it has painted lines.
const SAMPLE: usize = 400;

/// The borders between free cells (`blocked` per cell, row-major) whose painted lines do not
/// show, on a floor that has painted lines (see the module's comment); empty otherwise.
#[allow(clippy::too_many_arguments)]
pub fn missing(
    img: &RgbImage,
    classes: &[u8],
    classifier: &Classifier,
    maps: (&Homography, &Homography),
    (gw, gh): (u32, u32),
    blocked: &[bool],
    (near_mark, px): (&[u8], f64),
) -> Vec<Missing> {
    use rayon::prelude::*;
    let line = LINE.max(LINE_PX / px.max(1.0));
    let bands = (line, (SIDE.0.max(2.0 * line), SIDE.1.max(3.0 * line)));
    let free = |x: u32, y: u32| !blocked[y as usize * gw as usize + x as usize];
    let all: Vec<Border> = (0..gh)
        .flat_map(|y| (0..gw).map(move |x| (x, y)))
        .flat_map(|(x, y)| [((x, y), true), ((x, y), false)])
        .filter(|&((x, y), vertical)| {
            let (nx, ny) = if vertical { (x + 1, y) } else { (x, y + 1) };
            nx < gw && ny < gh && free(x, y) && free(nx, ny)
        })
        .collect();
    let measure = |borders: &[Border]| -> Vec<(Border, Contrast)> {
        borders
            .par_iter()
            .filter_map(|&b| {
                border_contrast(img, classes, classifier, maps, (b, bands), near_mark)
                    .map(|c| (b, c))
            })
            .collect()
    };
    // Painted lines or not, from a sample of the borders first.
    let step = all.len().div_ceil(SAMPLE).max(1);
    let sample: Vec<Border> = all.iter().step_by(step).copied().collect();
    if lines_way(&measure(&sample)).is_none() {
        return Vec::new();
    }
    let borders = measure(&all);
    let Some((way, median)) = lines_way(&borders) else {
        return Vec::new();
    };
    borders
        .into_iter()
        .filter_map(|(((x, y), vertical), (a, b))| {
            let c = way * (way * a).max(way * b);
            (c * way < MISSING * median).then(|| {
                let (nx, ny) = if vertical { (x + 1, y) } else { (x, y + 1) };
                let mid = if vertical {
                    (f64::from(nx), f64::from(y) + 0.5)
                } else {
                    (f64::from(x) + 0.5, f64::from(ny))
                };
                Missing {
                    cells: [(x, y), (nx, ny)],
                    at: maps.0.apply(mid).unwrap_or((0.0, 0.0)),
                    contrast: (c, way * median),
                }
            })
        })
        .collect()
}

/// Which way a floor's painted lines go (1 brighter than the floor, −1 darker) and the
/// borders' median contrast that way, from the borders measured; `None` when they show no
/// painted lines (too few borders, a median under [`PAINTED`], or a lower fifth under
/// [`STEADY`] of it). Each border's contrast that way is the larger of its two sides' (a
/// shadow's edge along a border darkens one side only).
fn lines_way(borders: &[(Border, Contrast)]) -> Option<(f64, f64)> {
    if borders.len() < 5 {
        return None;
    }
    let mut means: Vec<f64> = borders.iter().map(|b| (b.1 .0 + b.1 .1) / 2.0).collect();
    means.sort_by(f64::total_cmp);
    let way = means[means.len() / 2].signum();
    let mut along: Vec<f64> = borders
        .iter()
        .map(|b| (way * b.1 .0).max(way * b.1 .1))
        .collect();
    along.sort_by(f64::total_cmp);
    let median = along[along.len() / 2];
    (median >= PAINTED && along[along.len() / 5] >= STEADY * median).then_some((way, median))
}

/// The contrast of the line on border `((x, y), vertical)` (the cell's right border when
/// `vertical`, else its lower one) against the floor on each side of it, or `None` when too
/// few floor pixels show.
fn border_contrast(
    img: &RgbImage,
    classes: &[u8],
    classifier: &Classifier,
    (floor_to_image, image_to_floor): (&Homography, &Homography),
    (((x, y), vertical), (line_band, side_band)): (Border, (f64, (f64, f64))),
    near_mark: &[u8],
) -> Option<Contrast> {
    let (width, height) = (img.width() as usize, img.height() as usize);
    let border = if vertical {
        f64::from(x) + 1.0
    } else {
        f64::from(y) + 1.0
    };
    let start = if vertical { f64::from(y) } else { f64::from(x) };
    // The image box of the measured bands: across the border to SIDE.1, along it over ALONG.
    let floor_point = |across: f64, along: f64| {
        if vertical {
            (border + across, start + along)
        } else {
            (start + along, border + across)
        }
    };
    let (mut x0, mut y0, mut x1, mut y1) = (f64::INFINITY, f64::INFINITY, 0.0f64, 0.0f64);
    let far = side_band.1;
    for (a, t) in [
        (-far, ALONG.0),
        (far, ALONG.0),
        (-far, ALONG.1),
        (far, ALONG.1),
    ] {
        let (px, py) = floor_to_image.apply(floor_point(a, t))?;
        (x0, y0, x1, y1) = (x0.min(px), y0.min(py), x1.max(px), y1.max(py));
    }
    let clamp = |v: f64, n: usize| (v.max(0.0) as usize).min(n);
    let (x0, x1) = (clamp(x0.floor(), width), clamp(x1.ceil() + 1.0, width));
    let (y0, y1) = (clamp(y0.floor(), height), clamp(y1.ceil() + 1.0, height));
    let axes = image_to_floor.along_axes((x0, x1), (y0, y1));
    // The line's band, and the floor beside it on either side.
    let (mut line, mut side) = ((0.0, 0usize), [(0.0, 0usize); 2]);
    // All the pixels of each band, whatever they show.
    let (mut line_all, mut side_all) = (0usize, 0usize);
    for py in y0..y1 {
        for px in x0..x1 {
            let i = py * width + px;
            let point = match &axes {
                Some(axes) => Some(axes.at(px, py)),
                None => image_to_floor.apply((px as f64 + 0.5, py as f64 + 0.5)),
            };
            let Some((u, v)) = point else {
                continue;
            };
            let (across, at) = if vertical {
                ((u - border).abs(), v - start)
            } else {
                ((v - border).abs(), u - start)
            };
            if !(ALONG.0..=ALONG.1).contains(&at) {
                continue;
            }
            let in_line = across < line_band;
            if in_line {
                line_all += 1;
            } else if (side_band.0..=side_band.1).contains(&across) {
                side_all += 1;
            } else {
                continue;
            }
            if classes[i] != Class::Floor as u8 || near_mark[i] <= NEAR_HALO {
                continue;
            }
            let rgb = classifier.balanced(img.get_pixel(px as u32, py as u32).0);
            let bright = (rgb[0] + rgb[1] + rgb[2]) / 3.0;
            if in_line {
                line = (line.0 + bright, line.1 + 1);
            } else {
                let beyond = usize::from(if vertical { u > border } else { v > border });
                let s = &mut side[beyond];
                *s = (s.0 + bright, s.1 + 1);
            }
        }
    }
    // A border mostly under a mark or an obstacle is not judged.
    let enough = |n: usize, all: usize| n >= MIN_PIXELS.max(all / 2);
    if !enough(line.1, line_all)
        || !enough(side[0].1, side_all / 2)
        || !enough(side[1].1, side_all / 2)
    {
        return None;
    }
    let l = line.0 / line.1 as f64;
    let c = side.map(|(sum, n)| {
        let s = sum / n as f64;
        if s > 0.0 {
            (l - s) / s
        } else {
            0.0
        }
    });
    Some((c[0], c[1]))
}

#[cfg(test)]
mod tests {
    use super::*;
    use image::Rgb;

    /// A 6 × 4-cell floor, 20 px per cell, straight down, grey with white lines 2 px wide on
    /// every border but those `hidden` (a shelf of the floor's colour over them).
    fn floor(hidden: &[(u32, u32, bool)]) -> (RgbImage, Homography) {
        let to_image = Homography::floor_to_image(
            6.0,
            4.0,
            [(0.0, 0.0), (120.0, 0.0), (120.0, 80.0), (0.0, 80.0)],
        )
        .unwrap();
        let img = RgbImage::from_fn(120, 80, |x, y| {
            let on = |p: u32| p % 20 >= 19 || p % 20 == 0;
            let (cx, cy) = (x / 20, y / 20);
            let vertical = on(x) && x > 0 && x < 119;
            let horizontal = on(y) && y > 0 && y < 79;
            let hid = |c: (u32, u32, bool)| {
                if c.2 {
                    vertical && (x + 1) / 20 == c.0 + 1 && cy == c.1
                } else {
                    horizontal && (y + 1) / 20 == c.1 + 1 && cx == c.0
                }
            };
            if (vertical || horizontal) && !hidden.iter().any(|&c| hid(c)) {
                Rgb([235, 235, 235])
            } else {
                Rgb([150, 150, 150])
            }
        });
        (img, to_image)
    }

    fn run(img: &RgbImage, to_image: &Homography) -> Vec<Missing> {
        let classes = vec![Class::Floor as u8; 120 * 80];
        let classifier = Classifier::new(
            [150.0, 150.0, 150.0],
            super::super::colour::Hue::RED,
            super::super::colour::Hue::GREEN,
        );
        missing(
            img,
            &classes,
            &classifier,
            (to_image, &to_image.inverse().unwrap()),
            (6, 4),
            &[false; 24],
            (&[3; 120 * 80], 20.0),
        )
    }

    #[test]
    fn a_border_whose_line_is_hidden_is_found() {
        let (img, to_image) = floor(&[]);
        assert!(run(&img, &to_image).is_empty());
        // The line between cells (2, 1) and (3, 1) hidden.
        let (img, to_image) = floor(&[(2, 1, true)]);
        let found = run(&img, &to_image);
        assert_eq!(found.len(), 1);
        assert_eq!(found[0].cells, [(2, 1), (3, 1)]);
        assert!(found[0].contrast.1 > 0.4 && found[0].contrast.0.abs() < 0.05);
    }

    #[test]
    fn a_shadow_s_edge_along_a_line_does_not_hide_it() {
        // The upper two rows of cells in a shadow half as bright, its edge on the border
        // between rows 1 and 2.
        let (mut img, to_image) = floor(&[]);
        for y in 0..40 {
            for x in 0..120 {
                let p = img.get_pixel_mut(x, y);
                p.0 = p.0.map(|c| c / 2);
            }
        }
        assert!(run(&img, &to_image).is_empty());
    }

    #[test]
    fn a_floor_without_lines_or_with_lines_at_some_borders_is_not_judged() {
        let plain = RgbImage::from_pixel(120, 80, Rgb([150, 150, 150]));
        let to_image = floor(&[]).1;
        assert!(run(&plain, &to_image).is_empty());
        // Every vertical line hidden: half the borders show none.
        let hidden: Vec<(u32, u32, bool)> = (0..5)
            .flat_map(|x| (0..4).map(move |y| (x, y, true)))
            .collect();
        let (img, to_image) = floor(&hidden);
        assert!(run(&img, &to_image).is_empty());
    }
}
