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
//! the shelf (a0030, Y0011, p0037: refused as a robot lost, "more goals than robots"). A
//! robot's vivid piece is smaller where its rim blurs into the shelf: since the thirtieth
//! round a compact piece ([`PIECE_COMPACT`], [`PIECE_ROUND`]) of at least [`PIECE_SMALL`]
//! robots stays the robots' too (o0039's and P0031's robots against tan shelves, 0.44 to 0.6
//! robots; of the compact pieces from 0.35 to 0.6 robots on families A-Z and a-y, 13 lay on a
//! robot's centre, none elsewhere).
//! Goals are left as they are: their paint varies more, and a goal-coloured shelf is told by
//! its shape ([`super::shelves`]).
//!
//! A robot under a highlight is dull too: the sun's or the sky's white on its top greys its
//! paint, and G0019's frustums and H0000's domes in a bright band read at 0.57 to 0.70 of the
//! robots' saturation, as a dusty shelf does. White added makes a colour brighter, never
//! darker, and a robot keeps its shape: so a dull blob of a robot's size, shape and place
//! ([`highlighted`]) stays the robots' (since issue #29's thirtieth round; such robots were
//! turned into shelves, and the view refused for a robot lost).
//!
//! Cost: O(pixels of the robots' colour).

use super::blobs;
use super::colour::{Class, Classifier};
use super::homography::Homography;
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

/// A dull blob of a robot's size: from this to [`ROBOT_SIZE`]`.1` times the typical robot ...
pub const ROBOT_SIZE: (f64, f64) = (0.6, 1.5);
/// ... compact (at least this [`blobs::Blob::solidity`] ...
pub const COMPACT: f64 = 0.8;
/// ... and under this [`blobs::Blob::elongation`]: a robot is a disc or a square, 1) ...
pub const ROUND: f64 = 1.3;
/// ... under this many cells across on the floor, along both axes (a shelf's top over one
/// cell, raised toward the camera, spans more than its cell less its inset, 0.9 and more) ...
pub const SMALLER_THAN_A_CELL: f64 = 0.85;
/// ... and at least this many times as bright as the typical robot (its median brightest
/// channel after white balance) is a robot under a highlight ([`highlighted`]). Measured on
/// families A-Z and a-y: the 22 dull blobs so shaped on a robot's centre were 1.00 to 1.41
/// as bright as their view's robots; the 5 elsewhere (shadows read as the robots' hue, a
/// dark shelf) 0.25 to 0.97.
pub const HIGHLIGHT: f64 = 1.0;

/// The median brightness of a blob's pixels: their brightest channel after white balance.
pub(crate) fn brightness_of(b: &blobs::Blob, img: &RgbImage, classifier: &Classifier) -> f64 {
    let mut v: Vec<f64> = b
        .pixels
        .iter()
        .map(|&(x, y)| {
            let c = classifier.balanced(img.get_pixel(x, y).0);
            c[0].max(c[1]).max(c[2])
        })
        .collect();
    middle(&mut v)
}

/// The blob with its holes: the pixels of its bounding box that no path of pixels outside it
/// (4-connected) joins to the box's edge. A highlight may read as pale floor in a robot's
/// middle (G0019's frustum, a ring of the robots' colour).
fn with_holes(b: &blobs::Blob) -> blobs::Blob {
    let (x0, y0, x1, y1) = b.bbox;
    let (w, h) = ((x1 - x0 + 3) as usize, (y1 - y0 + 3) as usize);
    // A local map with a one-pixel margin: 1 the blob's, 2 reached from the edge.
    let mut local = vec![0u8; w * h];
    for &(x, y) in &b.pixels {
        local[(y - y0 + 1) as usize * w + (x - x0 + 1) as usize] = 1;
    }
    local[0] = 2;
    let mut stack = vec![0usize];
    while let Some(i) = stack.pop() {
        let (x, y) = (i % w, i / w);
        let steps = [
            (x > 0).then(|| i - 1),
            (x + 1 < w).then(|| i + 1),
            (y > 0).then(|| i - w),
            (y + 1 < h).then(|| i + w),
        ];
        for j in steps.into_iter().flatten() {
            if local[j] == 0 {
                local[j] = 2;
                stack.push(j);
            }
        }
    }
    blobs::Blob::from_pixels(
        (0..local.len())
            .filter(|&i| local[i] != 2)
            .map(|i| ((i % w) as u32 + x0 - 1, (i / w) as u32 + y0 - 1))
            .collect(),
    )
}

/// The dull blob with its holes ([`with_holes`]) when it is a robot under a highlight: of a
/// robot's size ([`ROBOT_SIZE`] times the typical robot's `area`), compact ([`COMPACT`],
/// [`ROUND`]), smaller than a cell on the floor along both axes ([`SMALLER_THAN_A_CELL`]) and
/// at least [`HIGHLIGHT`] times as bright as the typical robot (`bright`).
fn highlighted(
    b: &blobs::Blob,
    (area, bright): (usize, f64),
    img: &RgbImage,
    classifier: &Classifier,
    image_to_floor: &Homography,
) -> Option<blobs::Blob> {
    let whole = with_holes(b);
    let robots = whole.area() as f64 / area as f64;
    if !(ROBOT_SIZE.0..=ROBOT_SIZE.1).contains(&robots)
        || whole.solidity() < COMPACT
        || whole.elongation() >= ROUND
    {
        return None;
    }
    let (u0, v0, u1, v1) = blobs::on_floor(&whole, image_to_floor).into_iter().fold(
        (
            f64::INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::NEG_INFINITY,
        ),
        |(u0, v0, u1, v1), (u, v)| (u0.min(u), v0.min(v), u1.max(u), v1.max(v)),
    );
    (u0.is_finite()
        && u1 - u0 < SMALLER_THAN_A_CELL
        && v1 - v0 < SMALLER_THAN_A_CELL
        && brightness_of(&whole, img, classifier) >= HIGHLIGHT * bright)
        .then_some(whole)
}

/// A compact piece of vivid pixels in a dull blob, of at least this many typical robots, is a
/// robot's ([`robots_within`]) ...
pub const PIECE_SMALL: f64 = 0.35;
/// ... at least this [`blobs::Blob::solidity`] ...
pub const PIECE_COMPACT: f64 = 0.8;
/// ... and at most this [`blobs::Blob::elongation`] (a shelf's vivid specks and strips are
/// ragged or long).
pub const PIECE_ROUND: f64 = 1.6;

/// Turns the dull blobs of the robots' colour, and the large ones of another hue, into
/// obstacle blobs, but for the robots within them ([`robots_within`]) and for robots under a
/// highlight ([`highlighted`]); returns how many.
pub fn settle(
    classes: &mut [u8],
    img: &RgbImage,
    classifier: &Classifier,
    image_to_floor: &Homography,
) -> usize {
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
    // The typical robot's brightness, the same way, when a dull blob asks for it.
    let mut bright = None;
    let mut typical_brightness = || {
        *bright.get_or_insert_with(|| {
            let mut v: Vec<f64> = sized
                .iter()
                .filter(|s| alike(s.0))
                .map(|s| brightness_of(s.0, img, classifier))
                .collect();
            middle(&mut v)
        })
    };
    let mut turned = 0;
    for &(b, (s, h)) in &sized {
        let unhued = b.area() as f64 > LARGE * robot_area as f64 && (h - hue).abs() > HUE_APART;
        let dull = s < DULL * typical;
        if dull && !unhued {
            let typical = (robot_area, typical_brightness());
            if let Some(whole) = highlighted(b, typical, img, classifier, image_to_floor) {
                whole.paint(classes, width, Class::Robot as u8);
                continue;
            }
        }
        if dull || unhued {
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
/// `area` (or [`PIECE_SMALL`] times it when compact), each with the blob's pixels next to it
/// (its rim, blurred toward the shelf's colour): a robot standing against a shelf of its hue
/// joins the shelf's blob (a0030,
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
        let compact = || {
            let local = blobs::Blob::from_pixels(
                piece
                    .iter()
                    .map(|&i| ((i % w) as u32, (i / w) as u32))
                    .collect(),
            );
            local.solidity() >= PIECE_COMPACT && local.elongation() <= PIECE_ROUND
        };
        let robots = piece.len() as f64 / area as f64;
        if (piece.len() as f64) < least
            && (robots < PIECE_SMALL || (piece.len() as f64) < blobs::MIN_AREA as f64 || !compact())
        {
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

    /// The image → floor map of a view straight down on `img`, `cell` pixels a cell.
    fn floor_of(img: &RgbImage, cell: f64) -> Homography {
        let (w, h) = (f64::from(img.width()), f64::from(img.height()));
        Homography::floor_to_image(w / cell, h / cell, [(0.0, 0.0), (w, 0.0), (w, h), (0.0, h)])
            .and_then(|m| m.inverse())
            .unwrap()
    }

    /// Three red robots 8 px square on a grey floor 80 × 20 px, and a fourth of colour `pale`
    /// at x = 62..70, its middle 4 × 4 of colour `middle` read as floor when given.
    fn four_robots(pale: [u8; 3], middle: Option<[u8; 3]>) -> (RgbImage, Vec<u8>) {
        let mut img = RgbImage::from_pixel(80, 20, Rgb([128, 128, 128]));
        let mut classes = vec![Class::Floor as u8; 80 * 20];
        for (x0, c) in [
            (2, [200, 20, 20]),
            (22, [150, 15, 15]),
            (42, [210, 30, 25]),
            (62, pale),
        ] {
            for y in 6..14u32 {
                for x in x0..x0 + 8 {
                    let hole = x0 == 62 && (2..6).contains(&(x - x0)) && (8..12).contains(&y);
                    match middle.filter(|_| hole) {
                        Some(m) => img.put_pixel(x, y, Rgb(m)),
                        None => {
                            img.put_pixel(x, y, Rgb(c));
                            classes[y as usize * 80 + x as usize] = Class::Robot as u8;
                        }
                    }
                }
            }
        }
        (img, classes)
    }

    #[test]
    fn a_robot_under_a_highlight_stays_a_robot() {
        // The fourth robot greyed by a highlight, paler and brighter, on cells of 20 px: it
        // stays a robot. The same blob darker (a dusty shelf's piece), or a whole cell large,
        // is turned.
        let classifier = Classifier::new([128.0, 128.0, 128.0], Hue::RED, Hue::GREEN);
        let run = |pale: [u8; 3], cell: f64| {
            let (img, mut classes) = four_robots(pale, None);
            let turned = settle(&mut classes, &img, &classifier, &floor_of(&img, cell));
            (turned, classes[10 * 80 + 66])
        };
        let (_, s) = classifier.hue_from_robots([240, 120, 110]);
        assert!(s < DULL * 0.9, "{s}");
        assert_eq!(run([240, 120, 110], 20.0), (0, Class::Robot as u8));
        assert_eq!(run([150, 75, 70], 20.0), (1, Class::Obstacle as u8));
        assert_eq!(run([240, 120, 110], 8.0), (1, Class::Obstacle as u8));
    }

    #[test]
    fn a_highlight_read_as_floor_in_a_robot_s_middle_is_the_robot_s() {
        // As above, the fourth robot's middle 4 × 4 so pale that it reads as floor: a ring of
        // the robots' colour, dull, whose hole is the robot's.
        let classifier = Classifier::new([128.0, 128.0, 128.0], Hue::RED, Hue::GREEN);
        let (img, mut classes) = four_robots([240, 120, 110], Some([250, 235, 230]));
        assert_eq!(
            settle(&mut classes, &img, &classifier, &floor_of(&img, 20.0)),
            0
        );
        for x in 62..70 {
            assert_eq!(classes[10 * 80 + x], Class::Robot as u8, "x = {x}");
        }
        // A floor pixel beside it is left as it is.
        assert_eq!(classes[10 * 80 + 70], Class::Floor as u8);
    }

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
        assert_eq!(
            settle(&mut classes, &img, &classifier, &floor_of(&img, 10.0)),
            1
        );
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
        assert_eq!(
            settle(&mut classes, &img, &classifier, &floor_of(&img, 10.0)),
            1
        );
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
        assert_eq!(
            settle(&mut classes, &img, &classifier, &floor_of(&img, 10.0)),
            1
        );
        assert_eq!(classes[8 * 70 + 40], Class::Obstacle as u8);
    }

    #[test]
    fn a_compact_piece_of_a_robot_against_a_dull_shelf_stays_a_robot() {
        // Three red robots of 60 px and a dusty-rose shelf; against it a vivid piece of 25 px
        // (0.42 robots) stays a robot when compact (its rim blurred into the shelf), and is
        // the shelf's when it is a strip of 24 px.
        let run = |piece: &[(u32, u32)]| {
            let mut img = RgbImage::from_pixel(70, 30, Rgb([128, 128, 128]));
            let classifier = Classifier::new([128.0, 128.0, 128.0], Hue::RED, Hue::GREEN);
            let mut classes = vec![Class::Floor as u8; 70 * 30];
            let mut put = |x: u32, y: u32, c: [u8; 3]| {
                img.put_pixel(x, y, Rgb(c));
                classes[y as usize * 70 + x as usize] = Class::Robot as u8;
            };
            for (x0, c) in [(2, [200, 20, 20]), (12, [150, 15, 15]), (22, [220, 40, 30])] {
                for y in 5..15u32 {
                    for x in x0..x0 + 6 {
                        put(x, y, c);
                    }
                }
            }
            for y in 5..25u32 {
                for x in 34..56u32 {
                    put(x, y, [170, 110, 105]);
                }
            }
            for &(x, y) in piece {
                put(x, y, [200, 25, 20]);
            }
            assert_eq!(
                settle(&mut classes, &img, &classifier, &floor_of(&img, 10.0)),
                1
            );
            classes
        };
        let square: Vec<(u32, u32)> = (56..61)
            .flat_map(|x| (8..13).map(move |y| (x, y)))
            .collect();
        let classes = run(&square);
        for &(x, y) in &square {
            assert_eq!(classes[y as usize * 70 + x as usize], Class::Robot as u8);
        }
        assert_eq!(classes[10 * 70 + 40], Class::Obstacle as u8);
        let strip: Vec<(u32, u32)> = (56..58)
            .flat_map(|x| (6..18).map(move |y| (x, y)))
            .collect();
        let classes = run(&strip);
        for &(x, y) in &strip {
            assert_eq!(classes[y as usize * 70 + x as usize], Class::Obstacle as u8);
        }
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
        assert_eq!(
            settle(&mut classes, &img, &classifier, &floor_of(&img, 10.0)),
            1
        );
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
        assert_eq!(
            settle(&mut classes, &img, &classifier, &floor_of(&img, 10.0)),
            6
        );
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
        assert_eq!(
            settle(&mut classes, &img, &classifier, &floor_of(&img, 10.0)),
            0
        );
        assert_eq!(classes, alone);
        // A second robot in a shadow: darker, as saturated.
        for y in 5..15u32 {
            for x in 12..18u32 {
                img.put_pixel(x, y, Rgb([70, 8, 9]));
                classes[y as usize * 30 + x as usize] = Class::Robot as u8;
            }
        }
        assert_eq!(
            settle(&mut classes, &img, &classifier, &floor_of(&img, 10.0)),
            0
        );
    }
}
