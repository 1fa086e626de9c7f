//! Painted lines of a clear colour are the floor's paint, not an obstacle.
//!
//! Lines painted along the cell borders belong to the floor, whatever their colour. White
//! balance on a dark floor can tint white lines (p0000: lavender-white lines on a near-black
//! floor read as obstacle pixels, i0034's on a navy floor as obstacle and as a colour that
//! cannot be told), and lines of a clear colour read so whatever the balance. Such pixels
//! joined every goal and robot that touches a line into one blob that spans the floor, which
//! [`super::shelves`] then took for a shelf, marks and all (p0000 kept one goal of seven), and
//! counted as obstacle in each cell's cover (i0034: the cell under a white top's lean was
//! refused as one that top might cover whole).
//!
//! A line is thin and lies on a border. An obstacle pixel, or one of a colour that cannot be
//! told, within [`BAND`] of a cell's border (on the floor, through the homography) is the
//! line's when the pixels across the border, [`REACH`] from it on both sides (near a corner,
//! where two lines cross, the four pixels [`REACH`] from it diagonally), are the floor's (lit,
//! shaded or pale; outside the floor counts as floor). For a pixel of a colour that cannot be
//! told, a mark across the border counts as floor too, so long as one side is floor: a
//! robot's or a goal's blurred edge against a line is of such a colour, and it would stay a
//! blob of it beside the mark (f0000). An obstacle pixel needs floor on both sides: a shelf
//! of a colour near the goals' reads partly as goal, partly as a colour that cannot be told,
//! and partly as obstacle, and Y0007's teal shelf lost its obstacle pixels on the borders
//! when a mark's pixels counted as the floor's (read as free, wrongly). An obstacle fills its
//! cells, and its top, face or edge beside a border has the obstacle on one side: a shelf's
//! pixels stay.
//!
//! Only on a floor with painted lines: the median contrast of its inner borders against the
//! floor 0.2 cell beside them ([`lines_contrast`], from the image alone, on at most
//! [`SAMPLED_BORDERS`] borders) is at least 0.06 (pale lines) or at most −0.15 (dark ones;
//! [`LINES`]). Over the 962 rendered views without lines it lies between −0.092 (tile seams on
//! the borders) and 0.025; 332 of the 341 with white lines reach 0.06, and 438 of the 537
//! with dark lines −0.15 (dark lines seldom read as an obstacle's colour). Elsewhere a few
//! thin pixels on the borders are specks of the floor's texture or a shelf's edge between
//! pixels of a colour that cannot be told, and are left as read (set aside on every floor,
//! they moved 16 verdicts, 8 of them lost; with a count of pixels in place of the contrast,
//! Y0018's white lines, read as floor but where they cross, were left out). The lines'
//! pixels are set aside ([`OUTSIDE`]): neither floor nor obstacle, part of no blob and of no
//! cell's cover, as the floor's edge is. Taken as floor pixels instead, a white line on a dark
//! floor made the cells beside it darker than the "lit floor" around them (u0038, read as a
//! shadow nothing casts).
//!
//! The band and the reach grow to [`MIN_PX`] and [`MIN_PX`] + [`REACH`] − [`BAND`] pixels on
//! small cells (blur spreads a line over a pixel or two either side), the band at most
//! [`MAX_BAND`] of a cell.
//!
//! Cost: 8 × 3 pixels for each of at most [`SAMPLED_BORDERS`] borders; on a floor with painted
//! lines, one inverse map per obstacle or unsure pixel, and at most four forward maps for each
//! within a band of a border, on all cores.

use super::colour::Class;
use super::homography::Homography;
use super::pale;
use super::pixels::OUTSIDE;
use rayon::prelude::*;

/// How far from a border (cells) a line's pixel may lie.
pub const BAND: f64 = 0.12;
/// How far from the border (cells), on each side, the pixels must be the floor's.
pub const REACH: f64 = 0.25;
/// The band on small cells, in pixels.
pub const MIN_PX: f64 = 1.6;
/// The widest band, in cells.
pub const MAX_BAND: f64 = 0.2;
/// The floor has painted lines when its borders' median contrast ([`lines_contrast`]) is at
/// least the first (pale lines) or at most the second (dark lines).
pub const LINES: (f64, f64) = (0.06, -0.15);

/// What lies across a border from a line's pixel.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Side {
    Floor,
    Mark,
    Other,
}

/// Sets the pixels of painted lines read as obstacle or unsure aside ([`OUTSIDE`]); returns
/// how many.
pub fn settle(
    img: &image::RgbImage,
    classes: &mut [u8],
    width: usize,
    (floor_to_image, image_to_floor): (&Homography, &Homography),
    (gw, gh): (u32, u32),
    cell_px: f64,
) -> usize {
    // Only on a floor with painted lines (a few thin pixels on the borders of a floor without
    // them are specks of its texture, or a shelf's edge between pixels of a colour that
    // cannot be told, and are left as read).
    let contrast = lines_contrast(img, floor_to_image, (gw, gh));
    if !(contrast >= LINES.0 || contrast <= LINES.1) {
        return 0;
    }
    let height = classes.len() / width.max(1);
    let (obstacle, unsure) = (Class::Obstacle as u8, Class::Unsure as u8);
    let band = (MIN_PX / cell_px.max(1.0)).clamp(BAND, MAX_BAND);
    let reach = band + (REACH - BAND);
    let (fw, fh) = (f64::from(gw), f64::from(gh));
    let class_at = |classes: &[u8], (u, v): (f64, f64)| -> Option<u8> {
        let (x, y) = floor_to_image.apply((u, v))?;
        let (x, y) = (x.floor(), y.floor());
        (x >= 0.0 && y >= 0.0 && (x as usize) < width && (y as usize) < height)
            .then(|| classes[y as usize * width + x as usize])
    };
    // What lies across the border: the floor's, pale or not (outside the floor counts: a line
    // on the floor's edge), or a mark's (a robot or a goal against the line), or else
    // something else. A line has the floor on one side at least: a shelf of a colour near the
    // goals' reads partly as goal, partly as a colour that cannot be told, and partly as
    // obstacle (Y0007's teal shelf lost its obstacle pixels on the borders when a mark's
    // pixels counted as the floor's, and read as free).
    let side = |classes: &[u8], p: (f64, f64)| -> Side {
        let inside = p.0 >= 0.0 && p.1 >= 0.0 && p.0 < fw && p.1 < fh;
        if !inside {
            return Side::Floor;
        }
        match class_at(classes, p) {
            Some(c) if c == Class::Floor as u8 || c == pale::PALE || c == pale::PALE_SHADE => {
                Side::Floor
            }
            Some(c) if c == Class::Robot as u8 || c == Class::Goal as u8 => Side::Mark,
            _ => Side::Other,
        }
    };
    let across = |classes: &[u8], points: &[(f64, f64)], marks: bool| {
        let sides: Vec<Side> = points.iter().map(|&p| side(classes, p)).collect();
        sides
            .iter()
            .all(|&s| s == Side::Floor || (marks && s == Side::Mark))
            && sides.contains(&Side::Floor)
    };
    let lines: Vec<usize> = {
        let classes = &*classes;
        classes
            .par_iter()
            .enumerate()
            .filter(|&(_, &c)| c == obstacle || c == unsure)
            .filter_map(|(i, &c)| {
                let marks = c == unsure;
                let (x, y) = ((i % width) as f64 + 0.5, (i / width) as f64 + 0.5);
                let (u, v) = image_to_floor.apply((x, y))?;
                let (bu, bv) = (u.round(), v.round());
                let (near_u, near_v) = ((u - bu).abs() < band, (v - bv).abs() < band);
                let line = match (near_u, near_v) {
                    (true, true) => across(
                        classes,
                        &[(-1.0, -1.0), (1.0, -1.0), (1.0, 1.0), (-1.0, 1.0)]
                            .map(|(su, sv)| (bu + su * reach, bv + sv * reach)),
                        marks,
                    ),
                    (true, false) => across(classes, &[(bu - reach, v), (bu + reach, v)], marks),
                    (false, true) => across(classes, &[(u, bv - reach), (u, bv + reach)], marks),
                    (false, false) => false,
                };
                line.then_some(i)
            })
            .collect()
    };
    for &i in &lines {
        classes[i] = OUTSIDE;
    }
    lines.len()
}

/// The median contrast of the floor's inner borders against the floor beside them: the mean
/// brightness (sum of channels) of 8 points along the middle 0.2–0.8 of a border, over that of
/// the points 0.2 cell from it on both sides, less 1 (negative for dark lines). At most
/// [`SAMPLED_BORDERS`] borders, spread evenly.
pub fn lines_contrast(
    img: &image::RgbImage,
    floor_to_image: &Homography,
    (gw, gh): (u32, u32),
) -> f64 {
    let (w, h) = (img.width(), img.height());
    let at = |(u, v): (f64, f64)| -> Option<f64> {
        let (x, y) = floor_to_image.apply((u, v))?;
        (x >= 0.0 && y >= 0.0 && x < f64::from(w) && y < f64::from(h)).then(|| {
            let p = img.get_pixel(x as u32, y as u32).0;
            f64::from(p[0]) + f64::from(p[1]) + f64::from(p[2])
        })
    };
    // Inner borders: vertical ones (x = 1..gw, along cell row y), then horizontal ones.
    let vertical = (gw.saturating_sub(1) * gh) as usize;
    let horizontal = (gh.saturating_sub(1) * gw) as usize;
    let total = vertical + horizontal;
    if total == 0 {
        return 0.0;
    }
    let step = total.div_ceil(SAMPLED_BORDERS).max(1);
    let mut contrasts: Vec<f64> = (0..total)
        .step_by(step)
        .filter_map(|k| {
            // The border's start point and its direction along and across.
            let (origin, along, across) = if k < vertical {
                let (x, y) = ((k as u32 % (gw - 1)) + 1, k as u32 / (gw - 1));
                ((f64::from(x), f64::from(y)), (0.0, 1.0), (1.0, 0.0))
            } else {
                let k = k - vertical;
                let (x, y) = (k as u32 % gw, k as u32 / gw + 1);
                ((f64::from(x), f64::from(y)), (1.0, 0.0), (0.0, 1.0))
            };
            let (mut band, mut side) = (0.0, 0.0);
            for i in 0..8 {
                let t = 0.2 + 0.6 * (f64::from(i) + 0.5) / 8.0;
                let p = |d: f64| {
                    (
                        origin.0 + along.0 * t + across.0 * d,
                        origin.1 + along.1 * t + across.1 * d,
                    )
                };
                band += at(p(0.0))?;
                side += (at(p(-0.2))? + at(p(0.2))?) / 2.0;
            }
            (side > 0.0).then(|| band / side - 1.0)
        })
        .collect();
    if contrasts.is_empty() {
        return 0.0;
    }
    let mid = contrasts.len() / 2;
    *contrasts.select_nth_unstable_by(mid, f64::total_cmp).1
}

/// See [`lines_contrast`].
pub const SAMPLED_BORDERS: usize = 400;

#[cfg(test)]
mod tests {
    use super::*;
    use image::{Rgb, RgbImage};

    /// A 4 × 3-cell floor, 20 px per cell, straight down.
    fn maps() -> (Homography, Homography) {
        let corners = [(0.0, 0.0), (80.0, 0.0), (80.0, 60.0), (0.0, 60.0)];
        let f2i = Homography::floor_to_image(4.0, 3.0, corners).unwrap();
        let i2f = f2i.inverse().unwrap();
        (f2i, i2f)
    }

    const W: usize = 80;
    const H: usize = 60;

    fn on_border(x: usize, y: usize) -> bool {
        x % 20 < 1 || x % 20 >= 19 || y % 20 < 1 || y % 20 >= 19
    }

    /// The floor with lines 2 px wide of class `line` on every border.
    fn lined(line: Class) -> Vec<u8> {
        let mut classes = vec![Class::Floor as u8; W * H];
        for y in 0..H {
            for x in 0..W {
                if on_border(x, y) {
                    classes[y * W + x] = line as u8;
                }
            }
        }
        classes
    }

    /// A grey floor, with white lines 2 px wide on every border when `lines`.
    fn image(lines: bool) -> RgbImage {
        RgbImage::from_fn(W as u32, H as u32, |x, y| {
            if lines && on_border(x as usize, y as usize) {
                Rgb([235, 235, 240])
            } else {
                Rgb([90, 80, 70])
            }
        })
    }

    fn fill(classes: &mut [u8], (x0, x1): (usize, usize), (y0, y1): (usize, usize), c: Class) {
        for y in y0..y1 {
            for x in x0..x1 {
                classes[y * W + x] = c as u8;
            }
        }
    }

    fn settled(img: &RgbImage, classes: &mut [u8]) -> usize {
        let (f2i, i2f) = maps();
        settle(img, classes, W, (&f2i, &i2f), (4, 3), 20.0)
    }

    #[test]
    fn the_borders_contrast_tells_painted_lines() {
        let (f2i, _) = maps();
        assert!(lines_contrast(&image(true), &f2i, (4, 3)) > 1.0);
        assert!(lines_contrast(&image(false), &f2i, (4, 3)).abs() < 1e-9);
        // Dark lines.
        let dark = RgbImage::from_fn(W as u32, H as u32, |x, y| {
            Rgb(if on_border(x as usize, y as usize) {
                [20; 3]
            } else {
                [150; 3]
            })
        });
        assert!(lines_contrast(&dark, &f2i, (4, 3)) < -0.8);
    }

    #[test]
    fn thin_obstacle_lines_on_the_borders_are_set_aside_and_a_shelf_stays() {
        let mut classes = lined(Class::Obstacle);
        // A shelf on cells (1, 1) and (2, 1), inset 1 px.
        fill(&mut classes, (21, 59), (21, 39), Class::Obstacle);
        assert!(settled(&image(true), &mut classes) > 0);
        let at = |x: usize, y: usize| classes[y * W + x];
        // The lines between free cells, where they cross, and on the floor's edge are set
        // aside.
        assert_eq!(at(19, 5), OUTSIDE);
        assert_eq!(at(20, 0), OUTSIDE);
        assert_eq!(at(60, H - 1), OUTSIDE);
        assert_eq!(at(79, 30), OUTSIDE);
        // The shelf's own pixels, its edge on the border included, stay.
        assert_eq!(at(30, 30), Class::Obstacle as u8);
        assert_eq!(at(21, 30), Class::Obstacle as u8);
        assert_eq!(at(40, 21), Class::Obstacle as u8);
        // The line beside the shelf has the shelf on one side: it stays too.
        assert_eq!(at(20, 30), Class::Obstacle as u8);
        assert_eq!(at(40, 20), Class::Obstacle as u8);
    }

    #[test]
    fn a_line_of_a_colour_that_cannot_be_told_beside_a_mark_is_set_aside_an_obstacle_s_is_not() {
        for (line, beside_mark) in [
            (Class::Unsure, OUTSIDE),
            (Class::Obstacle, Class::Obstacle as u8),
        ] {
            let mut classes = lined(line);
            // A goal against the border x = 40, in cell (2, 1).
            fill(&mut classes, (41, 52), (25, 35), Class::Goal);
            settled(&image(true), &mut classes);
            assert_eq!(classes[30 * W + 40], beside_mark, "{line:?}");
            assert_eq!(classes[10 * W + 40], OUTSIDE, "{line:?}");
        }
    }

    #[test]
    fn a_wide_band_along_a_border_is_no_line() {
        let mut classes = lined(Class::Floor);
        // A strip 12 px wide centred on the border x = 40: more than a line.
        fill(&mut classes, (34, 46), (0, H), Class::Obstacle);
        assert_eq!(settled(&image(true), &mut classes), 0);
    }

    #[test]
    fn a_floor_without_painted_lines_keeps_its_thin_pixels_on_the_borders() {
        let mut classes = lined(Class::Obstacle);
        let before = classes.clone();
        assert_eq!(settled(&image(false), &mut classes), 0);
        assert_eq!(classes, before);
    }
}
