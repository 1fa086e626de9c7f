//! A colour that cannot be told, told by the view's own marks.
//!
//! The robots' and the goals' hue bands are wide (see [`super::colour`]): a view's paint,
//! light and white balance put its marks anywhere in them, and a mark's pixels just beyond
//! its band, with a doubt of [`super::colour`]'s `HUE_DOUBT` further, read as a colour that
//! cannot be told. Within one view the marks of a kind are alike: their hue agrees within a
//! few degrees (see [`super::dull`]). So an unsure blob no larger than [`blobs::ALIKE`]
//! typical marks of a kind, whose median hue is within [`HUE_NEAR`] of that kind's typical
//! hue in the view and whose median saturation is at least [`super::dull::DULL`] times
//! theirs, is of that kind: a green goal in a bluish shadow, or the part of a goal whose
//! paint sits at the band's edge (issue #29's twenty-fifth round; N0013 was refused, "a
//! blob whose colour is neither the robots' nor the goals'", U0031 and H0001 as a goal's
//! piece too small, or goals touching).
//!
//! The other way round, a piece of a mark's colour too large for noise and too small for a
//! mark whose colour is unlike the view's marks of its kind ([`unlike_marks`]: a shelf's
//! shaded side or edge of a colour near the goals', the green specks of a dark floor's
//! noise) is set aside as no mark, as a piece an obstacle leaves is (see
//! `blobs::behind_obstacle`): the view is then read only if it has exactly as many goals as
//! robots (M0017, b0019; they were refused for such a piece).
//!
//! A kind's typical hue and saturation are the medians over its blobs of about its typical
//! area (within a factor [`blobs::ALIKE`] of [`blobs::sort`]'s), each blob one vote; a kind
//! with fewer than [`LEAST_MARKS`] such blobs has none. It runs after [`super::enclosed`],
//! on the unsure blobs that are left.
//!
//! Cost: O(pixels of the marks' colours and unsure pixels).

use super::blobs;
use super::colour::{Class, Classifier};
use image::RgbImage;

/// An unsure blob's median hue at most this many degrees from a kind's typical hue is of
/// that kind (with the saturation and the size of its marks).
pub const HUE_NEAR: f64 = 12.0;
/// A kind's typical colour needs at least this many of its blobs of a typical area.
pub const LEAST_MARKS: usize = 3;

/// A kind's typical marks in one view: their area, and their median hue (from the kind's,
/// signed) and saturation.
#[derive(Clone, Copy, Debug)]
struct Typical {
    area: usize,
    hue: f64,
    saturation: f64,
}

/// The median of `values` (not empty).
fn middle(values: &mut [f64]) -> f64 {
    let mid = values.len() / 2;
    *values.select_nth_unstable_by(mid, f64::total_cmp).1
}

/// A blob's median hue from the mark `class`'s and its median saturation.
fn colour_of(b: &blobs::Blob, img: &RgbImage, classifier: &Classifier, class: Class) -> (f64, f64) {
    let (mut hues, mut sats): (Vec<f64>, Vec<f64>) = b
        .pixels
        .iter()
        .map(|&(x, y)| classifier.hue_from(img.get_pixel(x, y).0, class))
        .unzip();
    (middle(&mut hues), middle(&mut sats))
}

/// The typical marks of kind `class` (robot or goal), if the view has enough of them.
fn typical(
    classes: &mut [u8],
    img: &RgbImage,
    classifier: &Classifier,
    class: Class,
) -> Option<Typical> {
    let found = blobs::find(classes, img.width() as usize, class as u8);
    let area = blobs::sort(found.clone()).median_area;
    let (mut hues, mut sats): (Vec<f64>, Vec<f64>) = found
        .iter()
        .filter(|b| b.area() * blobs::ALIKE >= area && b.area() <= blobs::ALIKE * area)
        .map(|b| colour_of(b, img, classifier, class))
        .unzip();
    (area >= blobs::MIN_AREA && hues.len() >= LEAST_MARKS).then(|| Typical {
        area,
        hue: middle(&mut hues),
        saturation: middle(&mut sats),
    })
}

/// Whether a piece of the mark `class`'s colour is unlike the view's `marks` of that kind
/// (each of a typical area, at least [`LEAST_MARKS`] of them): its median hue more than
/// [`HUE_NEAR`] from their typical hue, or its median saturation under
/// [`super::dull::DULL`] times theirs. False when there are too few marks to tell.
pub fn unlike_marks(
    piece: &blobs::Blob,
    marks: &[blobs::Blob],
    img: &RgbImage,
    classifier: &Classifier,
    class: Class,
) -> bool {
    if marks.len() < LEAST_MARKS {
        return false;
    }
    let (mut hues, mut sats): (Vec<f64>, Vec<f64>) = marks
        .iter()
        .map(|b| colour_of(b, img, classifier, class))
        .unzip();
    let (hue, saturation) = (middle(&mut hues), middle(&mut sats));
    let (h, s) = colour_of(piece, img, classifier, class);
    (h - hue).abs() > HUE_NEAR || s < super::dull::DULL * saturation
}

/// A piece whose median brightness (its brightest channel after white balance) is under
/// this share of the view's typical mark's is dimmer than its marks ([`dimmer_than_marks`]).
pub const DIM: f64 = 0.6;

/// Whether a piece of a mark's colour is dimmer than the view's `marks` of its kind (each of
/// a typical area, at least [`LEAST_MARKS`] of them): its median brightness under [`DIM`]
/// times theirs. A speck of a mark's colour in a shadow or on a dark floor, whose noise white
/// balance makes saturated (Z0039's green speck at 0.37 of the goals' brightness, e0029's at
/// 0.18), is so; so may be a mark cut by a top's edge in the top's shadow (U0018's goal), which
/// is tried whole first (see `cut_mark`). False when there are too few marks to tell. Since
/// issue #29's twenty-ninth round.
pub fn dimmer_than_marks(
    piece: &blobs::Blob,
    marks: &[blobs::Blob],
    img: &RgbImage,
    classifier: &Classifier,
) -> bool {
    if marks.len() < LEAST_MARKS {
        return false;
    }
    let mut bright: Vec<f64> = marks
        .iter()
        .map(|b| super::dull::brightness_of(b, img, classifier))
        .collect();
    super::dull::brightness_of(piece, img, classifier) < DIM * middle(&mut bright)
}

/// Gives each unsure blob like one kind's marks that kind; returns how many it settled.
pub fn settle(classes: &mut [u8], img: &RgbImage, classifier: &Classifier) -> usize {
    let width = img.width() as usize;
    let kinds: Vec<(Class, Typical)> = [Class::Robot, Class::Goal]
        .into_iter()
        .filter_map(|c| typical(classes, img, classifier, c).map(|t| (c, t)))
        .collect();
    if kinds.is_empty() {
        return 0;
    }
    let mut settled = 0;
    for b in blobs::find(classes, width, Class::Unsure as u8) {
        let like = kinds.iter().find(|(class, t)| {
            let (hue, saturation) = colour_of(&b, img, classifier, *class);
            b.area() <= blobs::ALIKE * t.area
                && (hue - t.hue).abs() <= HUE_NEAR
                && saturation >= super::dull::DULL * t.saturation
        });
        if let Some(&(class, _)) = like {
            b.paint(classes, width, class as u8);
            settled += 1;
        }
    }
    settled
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::aerial::colour::Hue;
    use image::Rgb;

    /// A grey floor with square blobs of colour `c`, each `side` pixels, from column `x0` on.
    fn put(img: &mut RgbImage, classes: &mut [u8], (x0, side): (u32, u32), c: [u8; 3]) {
        let classifier = Classifier::new([128.0, 128.0, 128.0], Hue::RED, Hue::GREEN);
        let width = img.width() as usize;
        for y in 2..2 + side {
            for x in x0..x0 + side {
                img.put_pixel(x, y, Rgb(c));
                classes[y as usize * width + x as usize] = classifier.classify(c) as u8;
            }
        }
    }

    /// A grey floor 120 × 30 px with three goals of hue 150° (at their band's edge, 120° ±
    /// 35°), 6 px square, from columns 2, 12 and 22; its classifier and class map.
    fn three_goals() -> (Classifier, RgbImage, Vec<u8>) {
        let classifier = Classifier::new([128.0, 128.0, 128.0], Hue::RED, Hue::GREEN);
        let mut img = RgbImage::from_pixel(120, 30, Rgb([128, 128, 128]));
        let mut classes = vec![Class::Floor as u8; 120 * 30];
        for x0 in [2, 12, 22] {
            put(&mut img, &mut classes, (x0, 6), [54, 180, 117]);
        }
        (classifier, img, classes)
    }

    #[test]
    fn a_blob_like_the_view_s_goals_beyond_their_band_is_a_goal() {
        // Three goals of hue 150°, at their band's edge (120° ± 35°) ...
        let (classifier, mut img, mut classes) = three_goals();
        assert_eq!(classes[3 * 120 + 3], Class::Goal as u8);
        // ... a fourth of hue 160° (in a bluish shadow), just beyond it: a colour that cannot
        // be told ...
        put(&mut img, &mut classes, (32, 6), [54, 180, 138]);
        assert_eq!(classes[3 * 120 + 33], Class::Unsure as u8);
        // ... a brown box of the same size, 28°, between the robots' red and another colour,
        // and a shelf of 160°, twelve goals large.
        put(&mut img, &mut classes, (42, 6), [180, 110, 50]);
        put(&mut img, &mut classes, (52, 21), [54, 180, 138]);
        assert_eq!(classes[3 * 120 + 43], Class::Unsure as u8);
        assert_eq!(settle(&mut classes, &img, &classifier), 1);
        assert_eq!(classes[3 * 120 + 33], Class::Goal as u8);
        assert_eq!(classes[3 * 120 + 43], Class::Unsure as u8);
        assert_eq!(classes[3 * 120 + 53], Class::Unsure as u8);
        // Two goals make no typical colour: nothing is settled.
        let mut img = RgbImage::from_pixel(120, 30, Rgb([128, 128, 128]));
        let mut classes = vec![Class::Floor as u8; 120 * 30];
        for x0 in [2, 12] {
            put(&mut img, &mut classes, (x0, 6), [54, 180, 117]);
        }
        put(&mut img, &mut classes, (32, 6), [54, 180, 138]);
        assert_eq!(settle(&mut classes, &img, &classifier), 0);
    }

    #[test]
    fn a_piece_unlike_the_view_s_marks_is_told() {
        let (classifier, mut img, mut classes) = three_goals();
        // A piece of a goal's paint, a dark green shelf side (as saturated, 25° away) and a
        // greyish green speck (half as saturated).
        put(&mut img, &mut classes, (32, 3), [54, 180, 117]);
        put(&mut img, &mut classes, (42, 3), [40, 100, 40]);
        put(&mut img, &mut classes, (52, 3), [90, 150, 110]);
        let goals = blobs::find(&mut classes, 120, Class::Goal as u8);
        assert_eq!(goals.len(), 6);
        let like = |i: usize, marks: &[blobs::Blob]| {
            !unlike_marks(&goals[i], marks, &img, &classifier, Class::Goal)
        };
        assert!(like(3, &goals[..3]));
        assert!(!like(4, &goals[..3]));
        assert!(!like(5, &goals[..3]));
        // Too few marks to tell: nothing is unlike them.
        assert!(like(4, &goals[..2]));
    }

    #[test]
    fn a_speck_in_a_shadow_is_dimmer_than_the_view_s_marks() {
        let (classifier, mut img, mut classes) = three_goals();
        // A goal's piece as bright as the goals (180: 1.41 of the floor), a green speck at
        // 0.55 of their brightness (a shadow's), and one at 0.65.
        put(&mut img, &mut classes, (32, 3), [54, 180, 117]);
        put(&mut img, &mut classes, (42, 3), [30, 99, 64]);
        put(&mut img, &mut classes, (52, 3), [35, 117, 76]);
        let goals = blobs::find(&mut classes, 120, Class::Goal as u8);
        assert_eq!(goals.len(), 6);
        let dim = |i: usize, marks: &[blobs::Blob]| {
            dimmer_than_marks(&goals[i], marks, &img, &classifier)
        };
        assert!(!dim(3, &goals[..3]));
        assert!(dim(4, &goals[..3]));
        assert!(!dim(5, &goals[..3]));
        // Too few marks to tell.
        assert!(!dim(4, &goals[..2]));
    }
}
