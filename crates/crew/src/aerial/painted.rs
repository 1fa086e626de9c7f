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
use image::RgbImage;

/// Half the band of a border measured as its line, in cells.
pub const LINE: f64 = 0.05;
/// The band on each side of a border measured as floor beside its line, in cells.
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

/// The borders between free cells (`blocked` per cell, row-major) whose painted lines do not
/// show, on a floor that has painted lines (see the module's comment); empty otherwise.
#[allow(clippy::too_many_arguments)]
pub fn missing(
    img: &RgbImage,
    classes: &[u8],
    classifier: &Classifier,
    (floor_to_image, image_to_floor): (&Homography, &Homography),
    (gw, gh): (u32, u32),
    blocked: &[bool],
    near_mark: &[bool],
) -> Vec<Missing> {
    let (width, height) = (img.width() as usize, img.height() as usize);
    let free = |x: u32, y: u32| !blocked[y as usize * gw as usize + x as usize];
    // Each border between free cells, with its contrast when it can be judged.
    let mut borders: Vec<([(u32, u32); 2], (f64, f64))> = Vec::new();
    for y in 0..gh {
        for x in 0..gw {
            for (dx, dy) in [(1u32, 0u32), (0, 1)] {
                let (nx, ny) = (x + dx, y + dy);
                if nx >= gw || ny >= gh || !free(x, y) || !free(nx, ny) {
                    continue;
                }
                let contrast = border_contrast(
                    img,
                    classes,
                    classifier,
                    (floor_to_image, image_to_floor),
                    ((x, y), dx == 1),
                    near_mark,
                    (width, height),
                );
                if let Some(c) = contrast {
                    borders.push(([(x, y), (nx, ny)], c));
                }
            }
        }
    }
    if borders.len() < 5 {
        return Vec::new();
    }
    // Which way the lines go: the median of the borders' mean contrasts.
    let mut means: Vec<f64> = borders.iter().map(|b| (b.1 .0 + b.1 .1) / 2.0).collect();
    means.sort_by(f64::total_cmp);
    let way = means[means.len() / 2].signum();
    // Each border's contrast that way against the side it stands out from most (a shadow's
    // edge along a border darkens one side only).
    let borders: Vec<([(u32, u32); 2], f64)> = borders
        .into_iter()
        .map(|(cells, (a, b))| (cells, way * (way * a).max(way * b)))
        .collect();
    let mut along: Vec<f64> = borders.iter().map(|b| b.1 * way).collect();
    along.sort_by(f64::total_cmp);
    let median = along[along.len() / 2];
    if median < PAINTED {
        return Vec::new();
    }
    if along[along.len() / 5] < STEADY * median {
        return Vec::new();
    }
    let median = median * way;
    borders
        .into_iter()
        .filter(|(_, c)| c * way < MISSING * median.abs())
        .map(|(cells, c)| {
            let [(x, y), (nx, ny)] = cells;
            let mid = if nx > x {
                (f64::from(nx), f64::from(y) + 0.5)
            } else {
                (f64::from(x) + 0.5, f64::from(ny))
            };
            Missing {
                cells,
                at: floor_to_image.apply(mid).unwrap_or((0.0, 0.0)),
                contrast: (c, median),
            }
        })
        .collect()
}

/// The contrast of the line on the border after cell `(x, y)` (its right border when
/// `vertical`, else its lower one) against the floor on each side of it, or `None` when too
/// few floor pixels show.
fn border_contrast(
    img: &RgbImage,
    classes: &[u8],
    classifier: &Classifier,
    (floor_to_image, image_to_floor): (&Homography, &Homography),
    ((x, y), vertical): ((u32, u32), bool),
    near_mark: &[bool],
    (width, height): (usize, usize),
) -> Option<(f64, f64)> {
    // The image box of the two cells the border divides.
    let next = if vertical { (x + 1, y) } else { (x, y + 1) };
    let (a, b) = (
        floor_to_image.cell_box((x, y), width, height)?,
        floor_to_image.cell_box(next, width, height)?,
    );
    let (x0, y0, x1, y1) = (a.0.min(b.0), a.1.min(b.1), a.2.max(b.2), a.3.max(b.3));
    let border = if vertical {
        f64::from(x) + 1.0
    } else {
        f64::from(y) + 1.0
    };
    let start = if vertical { f64::from(y) } else { f64::from(x) };
    // The line's band, and the floor beside it on either side.
    let (mut line, mut side) = ((0.0, 0usize), [(0.0, 0usize); 2]);
    // All the pixels of each band, whatever they show.
    let (mut line_all, mut side_all) = (0usize, 0usize);
    for py in y0..y1 {
        for px in x0..x1 {
            let i = py * width + px;
            let Some((u, v)) = image_to_floor.apply((px as f64 + 0.5, py as f64 + 0.5)) else {
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
            if across < LINE {
                line_all += 1;
            } else if (SIDE.0..=SIDE.1).contains(&across) {
                side_all += 1;
            }
            if classes[i] != Class::Floor as u8 || near_mark[i] {
                continue;
            }
            let rgb = classifier.balanced(img.get_pixel(px as u32, py as u32).0);
            let bright = (rgb[0] + rgb[1] + rgb[2]) / 3.0;
            let beyond = usize::from(if vertical { u > border } else { v > border });
            if across < LINE {
                line = (line.0 + bright, line.1 + 1);
            } else if (SIDE.0..=SIDE.1).contains(&across) {
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
            &[false; 120 * 80],
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
