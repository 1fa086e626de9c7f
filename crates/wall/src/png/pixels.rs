//! Step 1, *classify*: each pixel is a brick colour or nothing, and the colour arithmetic
//! the later steps share (a colour's colour part, how much of a colour a pixel holds, the
//! blend of two colours).

use super::*;

/// Minimum saturation (max − min channel) of a brick pixel: ±20 noise on any grey stays
/// below it.
const MIN_SATURATION: f32 = 60.0;
/// A share of a brick's colour below this is a tint of the paper or noise, not colour.
pub(super) const FAINT_SHARE: f64 = 0.15;
/// A column where two colours meet is their blend when it lies this close to the line
/// between them (RGB distance).
const BLEND_DISTANCE: f32 = 40.0;

/// Classifies one pixel; returns its colour and saturation (max − min channel).
///
/// The thesis rule (red if r > 2g and r > 1.5b; green if g > 1.5r and g > 1.5b; blue if
/// b > 1.5r and b > 1.5g) and our orange rule (0.5r ≤ g ≤ 0.85r and b < 0.5g) are applied to
/// the pixel minus its smallest channel, its colour part: blending a brick colour with any
/// grey changes only the grey part, so anti-aliased edges keep their class.
pub fn classify_pixel(p: [u8; 3]) -> Option<(BrickType, f32)> {
    let [r, g, b] = colour_part(p.map(f32::from));
    let sat = r.max(g).max(b);
    if sat < MIN_SATURATION {
        return None;
    }
    let kind = if r > 2.0 * g && r > 1.5 * b {
        BrickType::Red
    } else if g > 1.5 * r && g > 1.5 * b {
        BrickType::Green
    } else if b > 1.5 * r && b > 1.5 * g {
        BrickType::Blue
    } else if g >= 0.5 * r && g <= 0.85 * r && b < 0.5 * g {
        BrickType::Orange
    } else {
        return None;
    };
    Some((kind, sat))
}

/// Step 1: every pixel's class, beside the image itself.
pub(super) struct Pixels<'a> {
    pub(super) width: usize,
    pub(super) height: usize,
    pub(super) class: Vec<Option<BrickType>>,
    pub(super) img: &'a RgbImage,
}

impl Pixels<'_> {
    /// The colour of pixel `i` (row-major) as floats.
    pub(super) fn rgb(&self, i: usize) -> [f32; 3] {
        let raw = &self.img.as_raw()[3 * i..3 * i + 3];
        [raw[0], raw[1], raw[2]].map(f32::from)
    }
}

pub(super) fn classify(img: &RgbImage) -> Pixels<'_> {
    let (width, height) = (img.width() as usize, img.height() as usize);
    // Each pixel is classified by the mean of itself and its left and right neighbours, which
    // keeps noise from flipping its class where a blurred edge leaves little colour.
    let mut class = Vec::with_capacity(width * height);
    for y in 0..height {
        for x in 0..width {
            let near = x.saturating_sub(1)..(x + 2).min(width);
            let n = near.len() as u32;
            let mut sum = [0u32; 3];
            for xx in near {
                let p = img.get_pixel(xx as u32, y as u32).0;
                (0..3).for_each(|c| sum[c] += u32::from(p[c]));
            }
            let mean = sum.map(|v| ((v + n / 2) / n) as u8);
            class.push(classify_pixel(mean).map(|(k, _)| k));
        }
    }
    Pixels {
        width,
        height,
        class,
        img,
    }
}

/// The mean of some colours (black for none).
pub(super) fn mean_colour(colours: impl Iterator<Item = [f32; 3]>) -> [f32; 3] {
    let (mut sum, mut n) = ([0f32; 3], 0usize);
    for p in colours {
        (0..3).for_each(|c| sum[c] += p[c]);
        n += 1;
    }
    sum.map(|v| v / n.max(1) as f32)
}

/// The colour part of a colour: minus its smallest channel.
pub(super) fn colour_part(p: [f32; 3]) -> [f32; 3] {
    let lowest = p[0].min(p[1]).min(p[2]);
    p.map(|c| c - lowest)
}

/// How much of `reference`'s colour part `p` holds, in [0, 1], a faint tint counting as
/// none: how much of the pixel the brick covers.
pub(super) fn coverage(p: [f32; 3], reference: [f32; 3]) -> f64 {
    let share = coverage_with_tints(p, reference);
    if share < FAINT_SHARE {
        0.0
    } else {
        share
    }
}

/// How much of `reference`'s colour part `p` holds, in [0, 1], faint tints included.
pub(super) fn coverage_with_tints(p: [f32; 3], reference: [f32; 3]) -> f64 {
    let (p, k) = (colour_part(p), colour_part(reference));
    let dot: f32 = (0..3).map(|c| p[c] * k[c]).sum();
    let norm: f32 = (0..3).map(|c| k[c] * k[c]).sum();
    if norm <= 0.0 {
        return 0.0;
    }
    f64::from(dot / norm).clamp(0.0, 1.0)
}

/// The colours on the straight line from one colour to another: what two colours blurred or
/// anti-aliased into each other make.
pub(super) struct Blend {
    pub(super) first: [f32; 3],
    pub(super) step: [f32; 3],
    pub(super) norm: f32,
}

impl Blend {
    /// `None` when the two colours are the same.
    pub(super) fn new(first: [f32; 3], second: [f32; 3]) -> Option<Blend> {
        let step: [f32; 3] = std::array::from_fn(|c| second[c] - first[c]);
        let norm: f32 = step.iter().map(|v| v * v).sum();
        (norm > 0.0).then_some(Blend { first, step, norm })
    }

    /// How much of the second colour `p` holds, in [0, 1].
    pub(super) fn share_of_second(&self, p: [f32; 3]) -> f32 {
        let along: f32 = (0..3).map(|c| (p[c] - self.first[c]) * self.step[c]).sum();
        (along / self.norm).clamp(0.0, 1.0)
    }

    /// Whether every blend of the two is a colour: orange and blue blend through grey, and
    /// there a grey border between them would look like their blend.
    pub(super) fn keeps_colour(&self) -> bool {
        [0.25f32, 0.5, 0.75].into_iter().all(|t| {
            let p: [f32; 3] = std::array::from_fn(|c| self.first[c] + t * self.step[c]);
            colour_part(p).into_iter().fold(0f32, f32::max) >= MIN_SATURATION
        })
    }

    /// Whether `p` lies on the line, within [`BLEND_DISTANCE`].
    pub(super) fn holds(&self, p: [f32; 3]) -> bool {
        let t = self.share_of_second(p);
        let off: f32 = (0..3)
            .map(|c| (p[c] - self.first[c] - t * self.step[c]).powi(2))
            .sum();
        off.sqrt() <= BLEND_DISTANCE
    }
}
