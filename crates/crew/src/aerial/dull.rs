//! Shelves of the robots' hue, duller than the robots.
//!
//! A view's robots share one paint: under shading and blur their colour keeps its hue and,
//! for the most part, its saturation (a shadow darkens a colour; it does not grey it). A shelf
//! of the robots' hue (dusty rose, mauve, salmon, terracotta against red robots) reads as the
//! robots' colour pixel by pixel, but it is far less saturated. So every 8-connected blob of
//! the robots' colour whose median saturation after white balance is under [`DULL`] times the
//! robots' typical one becomes an obstacle's, before the cells' cover is counted. Since issue
//! #29's fourteenth round; until then such a shelf was read as a robot (a robot more than
//! goals, refused) and its cells as free.
//!
//! The robots' typical saturation, and their typical hue, are the medians over the blobs of
//! about a typical robot's area (within a factor [`blobs::ALIKE`] of [`blobs::sort`]'s), each
//! blob one vote. Until issue #29's twenty-fifth round they were the medians over every blob
//! of at least [`blobs::MIN_AREA`] pixels, and a dull shelf broken into specks outvoted the
//! robots (M0026).
//!
//! A shelf of a hue near the robots' but not theirs (terracotta, brick, rust against red
//! robots, 20° to 30° away after white balance) is as saturated as the robots. Robots of one
//! view agree on their hue within a few degrees (measured on families A-F and K-e at the
//! robots' rendered centres: within 6.4° of the view's median for 90 % of the views). So a
//! blob more than [`LARGE`] typical robots large (larger than one robot: a shelf, or robots
//! touching) whose median hue is more than [`HUE_APART`] from the robots' typical hue is an
//! obstacle's too, but for the robots within it, as below (since the twenty-fifth round;
//! before, such a shelf was refused as robots touching, U0020, or took the robot standing
//! against it, U0016).
//!
//! Measured on families A-F and K-Z: of 6188 robots' blobs of at least 20 pixels, 3 (20 to 41
//! pixels: robots mostly hidden, refused then as a robot lost) are under 0.7 times the typical
//! saturation, the next 0.75; the dull shelves that were read as robots are 0.44 to 0.69.
//!
//! A robot standing against such a shelf makes one blob with it, dull for the most part: the
//! blob's pieces of pixels at least [`VIVID`] times as saturated as the robots and within
//! [`HUE_APART`] of their hue, each at least
//! [`blobs::SMALL`] times the typical robot large, stay the robots', with the blob's pixels
//! next to them (their rims); until issue #29's twenty-fifth round the robot was turned with
//! the shelf (a0030, Y0011, p0037: refused as a robot lost, "more goals than robots").
//! Goals are left as they are: their paint varies more, and a goal-coloured shelf is told by
//! its shape ([`super::shelves`]).
//!
//! Cost: O(pixels of the robots' colour).

use super::blobs;
use super::colour::{Class, Classifier};
use image::RgbImage;

/// A blob at most this many times as saturated as the robots is a shelf's.
pub const DULL: f64 = 0.7;

/// A blob larger than this many typical robots ...
pub const LARGE: f64 = 1.7;
/// ... whose median hue is more than this many degrees from the robots' typical one is
/// another thing's: a terracotta shelf against red robots (U0009, U0020; issue #29's
/// twenty-fifth round).
pub const HUE_APART: f64 = 12.0;

/// A dull blob's pixels at least this many times as saturated as the robots may be a robot
/// against the shelf ([`robots_within`]).
pub const VIVID: f64 = 0.85;

/// Turns the dull blobs of the robots' colour, and the large ones of another hue, into
/// obstacle blobs, but for the robots within them ([`robots_within`]); returns how many.
pub fn settle(classes: &mut [u8], img: &RgbImage, classifier: &Classifier) -> usize {
    let width = img.width() as usize;
    let found = blobs::find(classes, width, Class::Robot as u8);
    let colour = |(x, y): (u32, u32)| classifier.hue_from_robots(img.get_pixel(x, y).0);
    // Each blob's median saturation and median hue (from the robots').
    let median = |b: &blobs::Blob| {
        let (mut hues, mut sats): (Vec<f64>, Vec<f64>) =
            b.pixels.iter().map(|&p| colour(p)).unzip();
        (middle(&mut sats), middle(&mut hues))
    };
    let sized: Vec<(&blobs::Blob, (f64, f64))> = found
        .iter()
        .filter(|b| b.area() >= blobs::MIN_AREA)
        .map(|b| (b, median(b)))
        .collect();
    if sized.len() < 2 {
        return 0;
    }
    // The typical robot's area, and its saturation and hue: the median over the blobs of
    // about that area (within a factor [`blobs::ALIKE`]), each blob one vote: a dull shelf
    // broken into specks makes more blobs than the robots (M0026).
    let robot_area = blobs::sort(sized.iter().map(|s| s.0.clone()).collect()).median_area;
    let alike = |b: &blobs::Blob| {
        b.area() * blobs::ALIKE >= robot_area && b.area() <= blobs::ALIKE * robot_area
    };
    let (mut sats, mut hues): (Vec<f64>, Vec<f64>) =
        sized.iter().filter(|s| alike(s.0)).map(|s| s.1).unzip();
    if sats.is_empty() {
        return 0;
    }
    let (typical, hue) = (middle(&mut sats), middle(&mut hues));
    let mut turned = 0;
    for (b, (s, h)) in sized {
        let unhued = b.area() as f64 > LARGE * robot_area as f64 && (h - hue).abs() > HUE_APART;
        if s < DULL * typical || unhued {
            let vivid = |&p: &(u32, u32)| {
                let (h, s) = colour(p);
                s >= VIVID * typical && (h - hue).abs() <= HUE_APART
            };
            let kept = robots_within(b, vivid, width, robot_area);
            for &(x, y) in &b.pixels {
                let i = y as usize * width + x as usize;
                if !kept.contains(&i) {
                    classes[i] = Class::Obstacle as u8;
                }
            }
            turned += 1;
        }
    }
    turned
}

/// The median of `values` (NaN for none).
fn middle(values: &mut [f64]) -> f64 {
    if values.is_empty() {
        return f64::NAN;
    }
    let mid = values.len() / 2;
    *values.select_nth_unstable_by(mid, f64::total_cmp).1
}

/// The pixels of a dull blob that stay a robot's: the 8-connected pieces of its `vivid`
/// pixels (as saturated as the robots) of at least [`blobs::SMALL`] times the typical robot's
/// `area`, each with the blob's pixels next to it (its rim, blurred toward the shelf's
/// colour): a robot standing against a shelf of its hue joins the shelf's blob (a0030,
/// Y0011: red robots against dusty-rose shelves; issue #29's twenty-fifth round), and was
/// turned with it. Pixel indices (row-major, `width` wide), sorted.
fn robots_within(
    b: &blobs::Blob,
    vivid: impl Fn(&(u32, u32)) -> bool,
    width: usize,
    area: usize,
) -> std::collections::BTreeSet<usize> {
    let (x0, y0, x1, y1) = b.bbox;
    let (w, h) = ((x1 - x0 + 3) as usize, (y1 - y0 + 3) as usize);
    // A local map of the blob with a one-pixel margin: 1 vivid, 2 dull.
    let mut local = vec![0u8; w * h];
    let at = |x: u32, y: u32| (y - y0 + 1) as usize * w + (x - x0 + 1) as usize;
    for p in &b.pixels {
        local[at(p.0, p.1)] = if vivid(p) { 1 } else { 2 };
    }
    let mut kept = std::collections::BTreeSet::new();
    let least = (blobs::SMALL * area as f64).max(blobs::MIN_AREA as f64);
    let mut seen = vec![false; w * h];
    let mut stack = Vec::new();
    for start in 0..local.len() {
        if local[start] != 1 || seen[start] {
            continue;
        }
        seen[start] = true;
        stack.push(start);
        let mut piece = Vec::new();
        while let Some(i) = stack.pop() {
            piece.push(i);
            let (x, y) = (i % w, i / w);
            for (dx, dy) in blobs::NEIGHBOURS {
                let j = (y as i64 + dy) as usize * w + (x as i64 + dx) as usize;
                if local[j] == 1 && !seen[j] {
                    seen[j] = true;
                    stack.push(j);
                }
            }
        }
        if (piece.len() as f64) < least {
            continue;
        }
        let global = |i: usize| (y0 as usize + i / w - 1) * width + x0 as usize + i % w - 1;
        for &i in &piece {
            kept.insert(global(i));
            let (x, y) = (i % w, i / w);
            for (dx, dy) in blobs::NEIGHBOURS {
                let j = (y as i64 + dy) as usize * w + (x as i64 + dx) as usize;
                if local[j] == 2 {
                    kept.insert(global(j));
                }
            }
        }
    }
    kept
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::aerial::colour::Hue;
    use image::Rgb;

    #[test]
    fn a_dull_blob_of_the_robots_hue_is_a_shelf() {
        // A grey floor, three red robots (saturated) and a dusty-rose shelf of the robots' hue.
        let mut img = RgbImage::from_pixel(60, 20, Rgb([128, 128, 128]));
        let classifier = Classifier::new([128.0, 128.0, 128.0], Hue::RED, Hue::GREEN);
        let mut classes = vec![Class::Floor as u8; 60 * 20];
        let mut put = |x0: u32, x1: u32, c: [u8; 3]| {
            for y in 5..15u32 {
                for x in x0..x1 {
                    img.put_pixel(x, y, Rgb(c));
                    classes[y as usize * 60 + x as usize] = Class::Robot as u8;
                }
            }
        };
        put(2, 8, [200, 20, 20]);
        put(12, 18, [150, 15, 15]);
        put(22, 28, [220, 40, 30]);
        put(34, 56, [170, 110, 105]);
        assert_eq!(settle(&mut classes, &img, &classifier), 1);
        assert_eq!(classes[10 * 60 + 40], Class::Obstacle as u8);
        for x in [4, 14, 24] {
            assert_eq!(classes[10 * 60 + x], Class::Robot as u8);
        }
    }

    #[test]
    fn a_robot_against_a_dull_shelf_stays_a_robot() {
        // As above, with a fourth robot standing against the shelf: one blob of the robots'
        // colour, dull for the most part.
        let mut img = RgbImage::from_pixel(70, 20, Rgb([128, 128, 128]));
        let classifier = Classifier::new([128.0, 128.0, 128.0], Hue::RED, Hue::GREEN);
        let mut classes = vec![Class::Floor as u8; 70 * 20];
        let mut put = |x0: u32, x1: u32, c: [u8; 3]| {
            for y in 5..15u32 {
                for x in x0..x1 {
                    img.put_pixel(x, y, Rgb(c));
                    classes[y as usize * 70 + x as usize] = Class::Robot as u8;
                }
            }
        };
        put(2, 8, [200, 20, 20]);
        put(12, 18, [150, 15, 15]);
        put(22, 28, [220, 40, 30]);
        put(34, 56, [170, 110, 105]);
        put(56, 62, [190, 25, 20]);
        // Its rim, blurred toward the shelf's colour, stays the robot's.
        for y in 5..15u32 {
            img.put_pixel(56, y, Rgb([180, 70, 60]));
        }
        assert_eq!(settle(&mut classes, &img, &classifier), 1);
        for x in 34..56 {
            assert_eq!(classes[10 * 70 + x], Class::Obstacle as u8, "x = {x}");
        }
        for x in 56..62 {
            assert_eq!(classes[10 * 70 + x], Class::Robot as u8, "x = {x}");
        }
        // A piece of the shelf as saturated as the robots, too small for a robot, is the
        // shelf's.
        let mut classes = vec![Class::Floor as u8; 70 * 20];
        let mut img = RgbImage::from_pixel(70, 20, Rgb([128, 128, 128]));
        for (x0, x1, c) in [
            (2, 8, [200, 20, 20]),
            (12, 18, [150, 15, 15]),
            (22, 28, [220, 40, 30]),
            (34, 56, [170, 110, 105]),
        ] {
            for y in 5..15u32 {
                for x in x0..x1 {
                    img.put_pixel(x, y, Rgb(c));
                    classes[y as usize * 70 + x as usize] = Class::Robot as u8;
                }
            }
        }
        for (x, y) in [(40, 8), (41, 8), (40, 9)] {
            img.put_pixel(x, y, Rgb([200, 20, 20]));
        }
        assert_eq!(settle(&mut classes, &img, &classifier), 1);
        assert_eq!(classes[8 * 70 + 40], Class::Obstacle as u8);
    }

    #[test]
    fn a_shelf_of_a_hue_near_the_robots_is_an_obstacle() {
        // Four red robots, one against a terracotta shelf as saturated as they are, its
        // hue 25° away.
        let mut img = RgbImage::from_pixel(80, 20, Rgb([128, 128, 128]));
        let classifier = Classifier::new([128.0, 128.0, 128.0], Hue::RED, Hue::GREEN);
        let mut classes = vec![Class::Floor as u8; 80 * 20];
        for (x0, x1, c) in [
            (2, 8, [200, 20, 20]),
            (12, 18, [150, 15, 15]),
            (22, 28, [220, 40, 30]),
            (34, 56, [200, 100, 30]),
            (56, 62, [190, 25, 20]),
        ] {
            for y in 5..15u32 {
                for x in x0..x1 {
                    img.put_pixel(x, y, Rgb(c));
                    classes[y as usize * 80 + x as usize] = Class::Robot as u8;
                }
            }
        }
        let (hue, s) = classifier.hue_from_robots([200, 100, 30]);
        assert!(hue > HUE_APART && s > 0.8, "{hue} {s}");
        assert_eq!(settle(&mut classes, &img, &classifier), 1);
        // (The shelf's column against the robot stays the robot's, as its rim.)
        for x in 34..55 {
            assert_eq!(classes[10 * 80 + x], Class::Obstacle as u8, "x = {x}");
        }
        for x in [4, 14, 24, 56, 59, 61] {
            assert_eq!(classes[10 * 80 + x], Class::Robot as u8, "x = {x}");
        }
        // The robots' typical colour is theirs, however many dull specks the view has.
        let mut classes = vec![Class::Floor as u8; 80 * 20];
        let mut img = RgbImage::from_pixel(80, 20, Rgb([128, 128, 128]));
        for (x0, x1, c) in [
            (2, 8, [200, 20, 20]),
            (12, 18, [150, 15, 15]),
            (22, 28, [220, 40, 30]),
        ] {
            for y in 5..15u32 {
                for x in x0..x1 {
                    img.put_pixel(x, y, Rgb(c));
                    classes[y as usize * 80 + x as usize] = Class::Robot as u8;
                }
            }
        }
        for k in 0..6u32 {
            for (dx, dy) in [(0, 0), (1, 0), (0, 1), (1, 1), (2, 0), (2, 1)] {
                let (x, y) = (34 + 7 * k + dx, 2 + dy + 10 * (k % 2));
                img.put_pixel(x, y, Rgb([170, 110, 105]));
                classes[y as usize * 80 + x as usize] = Class::Robot as u8;
            }
        }
        assert_eq!(settle(&mut classes, &img, &classifier), 6);
        assert_eq!(classes[10 * 80 + 4], Class::Robot as u8);
        assert_eq!(classes[2 * 80 + 34], Class::Obstacle as u8);
    }

    #[test]
    fn robots_alike_or_a_lone_blob_stay_robots() {
        let mut img = RgbImage::from_pixel(30, 20, Rgb([128, 128, 128]));
        let classifier = Classifier::new([128.0, 128.0, 128.0], Hue::RED, Hue::GREEN);
        let mut classes = vec![Class::Floor as u8; 30 * 20];
        for y in 5..15u32 {
            for x in 2..8u32 {
                img.put_pixel(x, y, Rgb([200, 20, 20]));
                classes[y as usize * 30 + x as usize] = Class::Robot as u8;
            }
        }
        let alone = classes.clone();
        // One blob: nothing to compare it with.
        assert_eq!(settle(&mut classes, &img, &classifier), 0);
        assert_eq!(classes, alone);
        // A second robot in a shadow: darker, as saturated.
        for y in 5..15u32 {
            for x in 12..18u32 {
                img.put_pixel(x, y, Rgb([70, 8, 9]));
                classes[y as usize * 30 + x as usize] = Class::Robot as u8;
            }
        }
        assert_eq!(settle(&mut classes, &img, &classifier), 0);
    }
}
