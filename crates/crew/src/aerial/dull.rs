//! Shelves of the robots' hue, duller than the robots.
//!
//! A view's robots share one paint: under shading and blur their colour keeps its hue and,
//! for the most part, its saturation (a shadow darkens a colour; it does not grey it). A shelf
//! of the robots' hue (dusty rose, mauve, salmon, terracotta against red robots) reads as the
//! robots' colour pixel by pixel, but it is far less saturated. So every 8-connected blob of
//! the robots' colour whose median saturation after white balance is under [`DULL`] times the
//! robots' typical one (the median over the blobs of that colour of at least
//! [`blobs::MIN_AREA`] pixels, each blob one vote: the robots make most of them) becomes an
//! obstacle's, before the cells' cover is counted. Since issue #29's fourteenth round; until
//! then such a shelf was read as a robot (a robot more than goals, refused) and its cells as
//! free.
//!
//! Measured on families A-F and K-Z: of 6188 robots' blobs of at least 20 pixels, 3 (20 to 41
//! pixels: robots mostly hidden, refused then as a robot lost) are under 0.7 times the typical
//! saturation, the next 0.75; the dull shelves that were read as robots are 0.44 to 0.69.
//! Goals are left as they are: their paint varies more, and a goal-coloured shelf is told by
//! its shape ([`super::shelves`]).
//!
//! Cost: O(pixels of the robots' colour).

use super::blobs;
use super::colour::{Class, Classifier};
use image::RgbImage;

/// A blob at most this many times as saturated as the robots is a shelf's.
pub const DULL: f64 = 0.7;

/// Turns the dull blobs of the robots' colour into obstacle blobs; returns how many.
pub fn settle(classes: &mut [u8], img: &RgbImage, classifier: &Classifier) -> usize {
    let width = img.width() as usize;
    let found = blobs::find(classes, width, Class::Robot as u8);
    let saturation = |b: &blobs::Blob| {
        let mut s: Vec<f64> = b
            .pixels
            .iter()
            .map(|&(x, y)| super::pale::saturation(classifier.balanced(img.get_pixel(x, y).0)))
            .collect();
        let mid = s.len() / 2;
        *s.select_nth_unstable_by(mid, f64::total_cmp).1
    };
    let sized: Vec<(&blobs::Blob, f64)> = found
        .iter()
        .filter(|b| b.area() >= blobs::MIN_AREA)
        .map(|b| (b, saturation(b)))
        .collect();
    if sized.len() < 2 {
        return 0;
    }
    let mut all: Vec<f64> = sized.iter().map(|s| s.1).collect();
    let mid = all.len() / 2;
    let typical = *all.select_nth_unstable_by(mid, f64::total_cmp).1;
    let mut turned = 0;
    for (b, s) in sized {
        if s < DULL * typical {
            for &(x, y) in &b.pixels {
                classes[y as usize * width + x as usize] = Class::Obstacle as u8;
            }
            turned += 1;
        }
    }
    turned
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
