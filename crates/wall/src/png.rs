//! Wall images (thesis §3.1, Algorithm 1, extended with orange and made robust).
//!
//! Pixels are classified by the thesis rule (red if r > 2g and r > 1.5b; green if g > 1.5r and
//! g > 1.5b; blue if b > 1.5r and b > 1.5g) plus our orange rule (0.5r ≤ g ≤ 0.85r and
//! b < 0.5g), and only when the pixel is saturated (max − min ≥ 60), so that black, white and
//! grey borders, noise and background are never colours. Each colour's strength is normalised
//! by its median, so every brick interior reads 1 and borders read as dips.
//!
//! Layers are horizontal bands of equal height. Separator rows are rows where a good share of
//! the columns lit beside them dip; the layer count is the fewest equal layers whose
//! boundaries explain every separator, and bands sit between the separators. Inside a band
//! (weighted to its core rows), bricks are runs of coloured columns split by background, by
//! dips, or by a change of colour. A dip is a border when it is deep, or when it stands well
//! clear of the band's noise: a 1 px border at 8 px per 0.30 m, blurred, may dim two columns
//! by only a quarter. A brick's length is its colour plus one border width (a lone side is
//! placed from the colour's centroid and area, which blur keeps); the border comes from the
//! layer separators or from the narrowest gaps. One layer of bricks that touch nothing has
//! neither: on a light background each pixel then unmixes linearly into shares of colour,
//! background and black, and the dark ring they leave around each brick is a dark border's
//! width (blur keeps it); a border as light as the background leaves no ring, and the
//! border comes from the lengths of bricks of different colours (`r = n·unit − b`), or, for
//! bricks all of one length, from the grid they sit on: the whole number of units between
//! them whose unit puts every brick on a grid line and makes the layer 2/3 of a unit tall.
//! The length unit (pixels
//! per 0.30 m) is a median over all bricks weighted by length. Lengths then repair the two
//! ways a border can mislead: touching same-coloured pieces that only together make the
//! colour's length are merged, and a run k times its colour's length is split in k. Every
//! brick's length must match its colour within 0.35 units. Positions snap to a 0.30 m grid
//! refitted brick by brick across the wall. A column range empty on every layer starts a new
//! segment.
//!
//! Tested by rendering random walls at 8–24 px per 0.30 m with 1–3 px black or white borders,
//! blur and ±20 noise, and reading them back (`tests/png_roundtrip.rs`).

use crate::brick::{Brick, BrickType, Footprint, Origin, BRICK_DEPTH, UNIT_LENGTH};
use crate::error::{Location, WallError, WallErrorKind};
use crate::text::label_base;
use crate::wall::Wall;
use image::RgbImage;

/// Minimum saturation (max − min channel) of a brick pixel.
const MIN_SATURATION: f32 = 60.0;
/// Saturation that ±20 noise on black, white or mid-grey can reach.
const NOISE_SATURATION: f32 = 40.0;
/// A dip is a profile value below this fraction of both sides.
const DIP: f32 = 0.72;
/// Candidate dip columns are below this fraction of both sides.
const DIP_CANDIDATE: f32 = 0.85;
/// A one-column dip this far below its shoulders (fraction) is a border whatever the noise.
const LONE_DIP: f32 = 0.35;
/// A one-column dip at least this deep (in plateau units) and `CLEAR_SIGMAS` times the
/// profile's noise is a border.
const LONE_DEPTH: f32 = 0.3;
/// A wider dip at least this deep and `CLEAR_SIGMAS` times the profile's noise is a border.
const CLEAR_DEPTH: f32 = 0.15;
/// A dip this many times deeper than the profile's noise is a border.
const CLEAR_SIGMAS: f32 = 8.0;
/// How far to look on each side for a dip's shoulders (px).
const DIP_REACH: usize = 4;
/// A row is a layer separator when this share of the columns lit beside it dip there.
const SEPARATOR_SHARE: f64 = 0.3;
/// A band row is part of its core when it is this strong relative to the band's strongest row.
const CORE_ROW: f32 = 0.7;
/// How far past a lone edge the area of a run or a band is summed (px).
const AREA_REACH: usize = 3;
/// Accepted range of a layer's height over the unit (nominally 2/3).
const LAYER_RATIO: (f64, f64) = (0.5, 0.85);
/// The shortest stretch of one colour that counts as a brick of its own (px).
const MIN_COLOUR_RUN: usize = 3;
/// A brick's columns this many times taller than is typical hold two layers.
const TALL_RUN: f64 = 1.6;
/// A pixel this strong is certainly part of a brick.
const STRONG: f32 = 0.8;
/// A column is part of a brick when its strength is at least this.
const ON: f32 = 0.5;
/// A background is light when its channels average at least this.
const LIGHT_BACKGROUND: f32 = 160.0;
/// The light cluster of unsaturated pixels spans this much of the channel sum below its top.
const LIGHT_SPREAD: f32 = 60.0;
/// How far past a lone edge a run's dark ring is summed (px).
const RING_REACH: usize = 6;
/// A dark ring at least this wide (px) beside a brick shows a dark border.
const RING_MIN: f64 = 0.5;
/// Allowed mismatch between a brick's measured and nominal length (units of 0.30 m).
const LENGTH_TOLERANCE: f64 = 0.35;
/// The most units tried between the outer bricks of a lone layer (`grid_border`).
const MAX_GRID_CANDIDATES: usize = 256;

/// Classifies one pixel by the thesis rules plus orange; returns the type and saturation.
pub fn classify_pixel(p: [u8; 3]) -> Option<(BrickType, f32)> {
    let (r, g, b) = (f32::from(p[0]), f32::from(p[1]), f32::from(p[2]));
    let sat = r.max(g).max(b) - r.min(g).min(b);
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

/// Decodes PNG (or any format the `image` crate was built with) bytes and reads the wall.
pub fn read_png(bytes: &[u8], name: &str) -> Result<Wall, WallError> {
    let img = image::load_from_memory(bytes).map_err(|e| {
        WallError::new(
            name,
            Location::Whole,
            WallErrorKind::ImageDecode {
                reason: e.to_string(),
            },
        )
    })?;
    read_image(&img.to_rgb8(), name)
}

/// Per-pixel classes and normalised strengths.
struct Strength {
    width: usize,
    height: usize,
    kind: Vec<Option<BrickType>>,
    value: Vec<f32>,
    /// The pixels, for `Mixing`.
    rgb: Vec<[u8; 3]>,
    /// Each colour's typical saturation (the median of its pixels').
    reference: [f32; 4],
}

impl Strength {
    fn of(img: &RgbImage) -> Option<Strength> {
        let (width, height) = (img.width() as usize, img.height() as usize);
        let mut kind = Vec::with_capacity(width * height);
        let mut raw = Vec::with_capacity(width * height);
        let mut per_class: [Vec<f32>; 4] = Default::default();
        for p in img.pixels() {
            let [r, g, b] = p.0.map(f32::from);
            raw.push(r.max(g).max(b) - r.min(g).min(b));
            let k = classify_pixel(p.0).map(|(k, s)| {
                per_class[k.index()].push(s);
                k
            });
            kind.push(k);
        }
        let mut all: Vec<f32> = per_class.iter().flatten().copied().collect();
        if all.is_empty() {
            return None;
        }
        let median = |v: &mut Vec<f32>| {
            let mid = v.len() / 2;
            *v.select_nth_unstable_by(mid, f32::total_cmp).1
        };
        let global = median(&mut all);
        let reference: Vec<f32> = per_class
            .iter_mut()
            .map(|v| if v.is_empty() { global } else { median(v) })
            .collect();
        // Continuous strength: saturation above the level that noise on black or white
        // reaches, relative to the colour's median, clipped at 1 so that noise never lifts a
        // brick above its plateau.
        let value = raw
            .iter()
            .zip(&kind)
            .map(|(&s, k)| {
                let r = k.map_or(global, |k| reference[k.index()]);
                ((s - NOISE_SATURATION) / (r - NOISE_SATURATION).max(1.0)).clamp(0.0, 1.0)
            })
            .collect();
        let rgb = img.pixels().map(|p| p.0).collect();
        Some(Strength {
            width,
            height,
            kind,
            value,
            rgb,
            reference: [0, 1, 2, 3].map(|k| reference[k]),
        })
    }

    fn at(&self, x: usize, y: usize) -> f32 {
        self.value[y * self.width + x]
    }
}

/// The linear mixing model of an image on a light background: each pixel is a mixture
/// κ·colour + β·background + (1 − κ − β)·black. Blur and anti-aliasing mix pixels linearly,
/// so shares summed along a row keep the widths of what was drawn.
struct Mixing {
    /// Each colour's typical pixel: the per-channel mean of its strongly saturated pixels.
    colour: [[f32; 3]; 4],
    /// The background's typical pixel.
    background: [f32; 3],
}

impl Mixing {
    /// The model of an image; `None` when its background is dark (a dark border cannot be
    /// told from it).
    fn of(st: &Strength) -> Option<Mixing> {
        let saturation = |p: &[u8; 3]| {
            f32::from(p.iter().max().copied().unwrap_or(0) - p.iter().min().copied().unwrap_or(0))
        };
        let pixel = |p: &[u8; 3]| p.map(f32::from);
        let colour = [0, 1, 2, 3].map(|k| {
            let strong = st.rgb.iter().zip(&st.kind).filter(|(p, c)| {
                c.map(BrickType::index) == Some(k) && saturation(p) >= STRONG * st.reference[k]
            });
            channel_means(strong.map(|(p, _)| pixel(p))).unwrap_or([0.0; 3])
        });
        // The background is the light cluster of the unsaturated pixels (borders may be as
        // many as it at small scales, so a plain median could land on them).
        let sum = |p: &[u8; 3]| p.iter().map(|&c| f32::from(c)).sum::<f32>();
        let mut plain: Vec<&[u8; 3]> = st
            .rgb
            .iter()
            .filter(|p| saturation(p) < MIN_SATURATION)
            .collect();
        plain.sort_by(|a, b| sum(a).total_cmp(&sum(b)));
        let top = sum(plain.get(plain.len() * 9 / 10)?);
        let light = plain.into_iter().filter(|p| sum(p) >= top - LIGHT_SPREAD);
        let background = channel_means(light.map(pixel))?;
        (background.iter().sum::<f32>() >= 3.0 * LIGHT_BACKGROUND)
            .then_some(Mixing { colour, background })
    }

    /// The shares (κ, β) of a brick of `kind` and of background in pixel (x, y).
    fn shares(&self, st: &Strength, x: usize, y: usize, kind: BrickType) -> Option<(f32, f32)> {
        let (c, w) = (self.colour[kind.index()], self.background);
        // The colour's strongest and weakest channels tell it from light and dark.
        let (hi, lo) = strongest_and_weakest(c);
        let det = c[hi] * w[lo] - c[lo] * w[hi];
        if det.abs() < 1.0 {
            return None;
        }
        let v = st.rgb[y * st.width + x].map(f32::from);
        Some((
            (v[hi] * w[lo] - v[lo] * w[hi]) / det,
            (c[hi] * v[lo] - c[lo] * v[hi]) / det,
        ))
    }
}

/// The per-channel means of some pixels (means, since noise clipped at 0 or 255 shifts the
/// mean of every pixel alike); `None` when there are none.
fn channel_means(pixels: impl Iterator<Item = [f32; 3]>) -> Option<[f32; 3]> {
    let mut n = 0.0;
    let mut sum = [0f64; 3];
    for p in pixels {
        n += 1.0;
        sum.iter_mut().zip(p).for_each(|(s, v)| *s += f64::from(v));
    }
    (n > 0.0).then(|| sum.map(|s| (s / n) as f32))
}

/// The indices of a pixel's strongest and weakest channels.
fn strongest_and_weakest(p: [f32; 3]) -> (usize, usize) {
    let by = |a: &usize, b: &usize| p[*a].total_cmp(&p[*b]);
    (
        (0..3).max_by(by).unwrap_or(0),
        (0..3).min_by(by).unwrap_or(0),
    )
}

/// Marks dips in a profile: runs of values below `DIP_CANDIDATE` of both shoulders whose
/// minimum is below `DIP` of them. `noise` is the profile's noise level, when known: dips must
/// then be four times deeper than it. Returns a mask of dip positions.
fn dip_mask(profile: &[f32], floor: f32, noise: Option<f32>, plateau: f32) -> Vec<bool> {
    let min_depth = noise.map_or(0.0, |n| 4.0 * n);
    let n = profile.len();
    let shoulder = |i: usize| shoulders(profile, i, i + 1);
    let candidate: Vec<bool> = (0..n)
        .map(|i| {
            let s = shoulder(i);
            s >= floor && profile[i] < DIP_CANDIDATE * s
        })
        .collect();
    let mut mask = vec![false; n];
    let mut i = 0;
    while i < n {
        if !candidate[i] {
            i += 1;
            continue;
        }
        let start = i;
        while i < n && candidate[i] {
            i += 1;
        }
        let deepest = (start..i)
            .map(|j| profile[j] / shoulder(j).max(f32::EPSILON))
            .fold(f32::INFINITY, f32::min);
        let depth = (start..i)
            .map(|j| shoulder(j) - profile[j])
            .fold(0.0, f32::max);
        let lowest = profile[start..i]
            .iter()
            .copied()
            .fold(f32::INFINITY, f32::min);
        // A deep dip is a border. A lone column needs a very deep one, since noise makes
        // shallow one-column dips. Where the noise is known, a dip that stands well clear of
        // it is a border too: a thin border at a small scale, split over two columns and
        // blurred, may dim them by only a quarter.
        let wide = i - start >= 2;
        let deep = deepest < DIP
            && lowest < DIP * plateau
            && depth >= min_depth
            && (wide || deepest < LONE_DIP);
        let clear = noise.is_some_and(|n| {
            let least = if wide { CLEAR_DEPTH } else { LONE_DEPTH };
            depth >= least.max(CLEAR_SIGMAS * n)
        });
        if deep || clear {
            mask[start..i].iter_mut().for_each(|m| *m = true);
        }
    }
    mask
}

/// The level on both sides of `profile[start..end]`: the lower of the highest values within
/// `DIP_REACH` before it and after it.
fn shoulders(profile: &[f32], start: usize, end: usize) -> f32 {
    let n = profile.len();
    let highest = |r: std::ops::Range<usize>| profile[r].iter().copied().fold(0.0, f32::max);
    highest(start.saturating_sub(DIP_REACH)..start)
        .min(highest(end.min(n)..(end + DIP_REACH).min(n)))
}

/// The width of a gap as the area it lacks below the plateau. Blur and anti-aliasing move
/// intensity around but keep its sum, so this is the border width however soft the edges.
fn deficit(gap: &[f32], plateau: f32) -> f64 {
    gap.iter()
        .map(|&p| f64::from((1.0 - p / plateau.max(f32::EPSILON)).max(0.0)))
        .sum()
}

/// Maximal runs of `true` as half-open ranges.
fn runs(mask: &[bool]) -> Vec<(usize, usize)> {
    let mut out = Vec::new();
    let mut i = 0;
    while i < mask.len() {
        if mask[i] {
            let s = i;
            while i < mask.len() && mask[i] {
                i += 1;
            }
            out.push((s, i));
        } else {
            i += 1;
        }
    }
    out
}

fn median(mut v: Vec<f64>) -> Option<f64> {
    if v.is_empty() {
        return None;
    }
    v.sort_by(f64::total_cmp);
    Some(v[v.len() / 2])
}

/// The layer bands, bottom first, as half-open pixel row ranges from separator to separator,
/// with the layer pitch and the border estimate.
struct Layers {
    bands: Vec<(usize, usize)>,
    pitch: f64,
    /// Height of the wall from its top edge to its bottom edge (px).
    extent: f64,
    /// Border width measured at the layer separators, if there are any.
    border: Option<f64>,
}

fn find_layers(st: &Strength, name: &str, count: Option<usize>) -> Result<Layers, WallError> {
    let layout = |reason: String| {
        WallError::new(name, Location::Whole, WallErrorKind::ImageLayout { reason })
    };
    let wall_rows: Vec<usize> = (0..st.height)
        .filter(|&y| (0..st.width).any(|x| st.at(x, y) >= ON))
        .collect();
    let (top, bottom) = match (wall_rows.first(), wall_rows.last()) {
        (Some(&t), Some(&b)) => (t, b),
        _ => return Err(layout("no brick colours found in the image".into())),
    };
    // Vertical dips per column, counted per row.
    let mut dips = vec![0usize; st.height];
    let mut column = vec![0f32; st.height];
    let mut widths = Vec::new();
    for x in 0..st.width {
        for (y, c) in column.iter_mut().enumerate() {
            *c = st.at(x, y);
        }
        let mask = dip_mask(&column, ON, None, 1.0);
        for (y, &m) in mask.iter().enumerate() {
            if m {
                dips[y] += 1;
            }
        }
        for (s, e) in runs(&mask) {
            // Only a dip between full colour above and below measures the border: at a
            // brick's corner the vertical border beside it adds its own deficit.
            let shoulder = shoulders(&column, s, e);
            if shoulder >= STRONG {
                widths.push(((s + e) as f64 / 2.0, deficit(&column[s..e], shoulder)));
            }
        }
    }
    // A separator row dips in a good part of the columns lit on both of its sides: upper
    // layers are often narrow, so the reference is local, not the widest layer.
    let lit: Vec<usize> = (0..st.height)
        .map(|y| (0..st.width).filter(|&x| st.at(x, y) >= ON).count())
        .collect();
    let widest = |rows: std::ops::Range<usize>| lit[rows].iter().copied().max().unwrap_or(0);
    let separator_rows: Vec<bool> = (0..st.height)
        .map(|y| {
            let above = widest(y.saturating_sub(DIP_REACH)..y);
            let below = widest((y + 1).min(st.height)..(y + 1 + DIP_REACH).min(st.height));
            let reference = above.min(below) as f64;
            dips[y] >= 2 && dips[y] as f64 >= SEPARATOR_SHARE * reference
        })
        .collect();
    let separators: Vec<f64> = runs(&separator_rows)
        .into_iter()
        .map(|(s, e)| {
            let w: f64 = (s..e).map(|y| dips[y] as f64).sum();
            (s..e)
                .map(|y| (y as f64 + 0.5) * dips[y] as f64)
                .sum::<f64>()
                / w
        })
        .collect();
    // The border is measured where layers meet; a stray vertical dip elsewhere says nothing.
    let measured = median(
        widths
            .into_iter()
            .filter(|&(y, _)| separators.iter().any(|&sep| (y - sep).abs() <= 2.0))
            .map(|(_, w)| w)
            .collect(),
    );
    let border = measured.unwrap_or(0.0);
    let upper = top as f64 - border / 2.0;
    let lower = bottom as f64 + 1.0 + border / 2.0;
    let extent = lower - upper;
    let count = if let Some(n) = count {
        n.max(1)
    } else {
        layer_count(&separators, upper, extent)
    };
    let pitch = extent / count as f64;
    // Layer boundaries, top first: on the pitch grid, or on the separator found near it.
    let boundaries: Vec<f64> = (0..=count)
        .map(|k| {
            let grid = upper + k as f64 * pitch;
            let near = separators
                .iter()
                .copied()
                .filter(|&y| (y - grid).abs() <= pitch / 4.0)
                .min_by(|a, b| (a - grid).abs().total_cmp(&(b - grid).abs()));
            match near {
                Some(y) if k > 0 && k < count => y,
                _ => grid,
            }
        })
        .collect();
    let bands = boundaries
        .windows(2)
        .rev()
        .map(|w| {
            let a = (w[0].round().max(0.0) as usize).min(st.height - 1);
            let b = (w[1].round().max(0.0) as usize).min(st.height).max(a + 1);
            (a, b)
        })
        .collect();
    Ok(Layers {
        bands,
        pitch,
        extent,
        border: measured,
    })
}

/// The fewest equal layers between `upper` and `upper + extent` whose boundaries explain
/// every separator: each separator lies within a fifth of a pitch of a boundary, and no two
/// share one. A missed separator only means a boundary without one. A separator on the wall's
/// top or bottom edge (within 3 px) is an artefact of the blurred edge and is ignored.
fn layer_count(separators: &[f64], upper: f64, extent: f64) -> usize {
    let fits = |n: usize| {
        let pitch = extent / n as f64;
        let mut inner = Vec::with_capacity(separators.len());
        for &y in separators {
            let k = ((y - upper) / pitch).round();
            let edge = k == 0.0 || k == n as f64;
            let off = ((y - upper) - k * pitch).abs();
            if k < 0.0 || k > n as f64 || off > (pitch / 5.0).max(if edge { 3.0 } else { 0.0 }) {
                return false;
            }
            if k >= 1.0 && k < n as f64 {
                inner.push(k as usize);
            }
        }
        let placed = inner.len();
        inner.dedup();
        inner.len() == placed
    };
    // Thin layers are at least 3 px apart; beyond that no count explains the separators.
    let most = ((extent / 3.0).floor() as usize).max(separators.len() + 1);
    (1..=most)
        .find(|&n| fits(n))
        .unwrap_or(separators.len() + 1)
}

/// A brick found in one band, in pixels.
#[derive(Clone)]
struct Found {
    level: u32,
    kind: BrickType,
    left: f64,
    right: f64,
    centre: (u32, u32),
    /// The missing area of the gap before it when it touches the brick before (px).
    gap: f64,
    /// Columns inside it that dip a little, too little to count as a border (px).
    faint_dips: Vec<f64>,
}

/// A run of brick columns in one band.
struct Run {
    /// First column.
    start: usize,
    /// One past the last column.
    end: usize,
    kind: BrickType,
    /// The gap before this run as missing area (px); infinite for the first run.
    gap: f64,
    /// The run's coloured width as area (px): its profile summed out to the middle of the gaps
    /// beside it, over the plateau. Blur keeps this sum, so it is the true colour width.
    area: f64,
    /// The middle of its colour (px from the image's left edge): the centroid of the profile
    /// summed for `area`. Blur spreads a brick evenly to both sides, so this does not move.
    middle: f64,
    /// The colour's height in each of the run's columns, as area (px).
    column_heights: Vec<f64>,
    /// Columns that dip a little below their shoulders, too little to count as a border.
    faint_dips: Vec<usize>,
}

/// The weights of a band's rows: each core row's strength, measured on the columns lit in
/// most of the band's rows; zero for the other rows.
fn core_weights(st: &Strength, (y0, y1): (usize, usize)) -> Vec<f32> {
    let lit_in_most: Vec<usize> = (0..st.width)
        .filter(|&x| 2 * (y0..y1).filter(|&y| st.at(x, y) >= ON).count() >= y1 - y0)
        .collect();
    let columns: Vec<usize> = if lit_in_most.is_empty() {
        (0..st.width).collect()
    } else {
        lit_in_most
    };
    let strength: Vec<f32> = (y0..y1)
        .map(|y| columns.iter().map(|&x| st.at(x, y)).sum::<f32>() / columns.len() as f32)
        .collect();
    let core = strength.iter().copied().fold(0.0, f32::max) * CORE_ROW;
    strength
        .iter()
        .map(|&w| if w >= core { w } else { 0.0 })
        .collect()
}

/// A run's inner columns, where its colour is whole: all but the first and last.
fn inner_columns(start: usize, end: usize) -> std::ops::Range<usize> {
    if end - start > 2 {
        start + 1..end - 1
    } else {
        start..end
    }
}

/// The runs of brick columns in a band, left to right, and the band's colour height as area
/// (rows summed over the plateau, measured on the runs' columns). `outer` says whether the
/// band is the top and the bottom of the wall: there the sum reaches past the band's edge,
/// since blur spreads the colour beyond it.
fn bricks_in_band(st: &Strength, (y0, y1): (usize, usize), outer: (bool, bool)) -> (Vec<Run>, f64) {
    // Rows weighted by their own strength (a matched filter): thin bricks light only a few
    // rows of their band, and the dark rows would add noise but no signal.
    // Only the band's core rows count: an edge row may hold a sliver of the layer beside it,
    // whose brick borders would show as phantom dips. A row's strength is measured on the
    // columns lit in most of the band's rows, so that a narrow layer is not outweighed by a
    // blurred sliver of a wide one.
    let weights = core_weights(st, (y0, y1));
    let total = weights.iter().sum::<f32>().max(f32::EPSILON);
    let profile: Vec<f32> = (0..st.width)
        .map(|x| {
            (y0..y1)
                .zip(&weights)
                .map(|(y, w)| w * st.at(x, y))
                .sum::<f32>()
                / total
        })
        .collect();
    // The band's plateau: thin bricks fill only part of the band's rows.
    let mut lit: Vec<f32> = profile.iter().copied().filter(|&p| p > 0.05).collect();
    lit.sort_by(f32::total_cmp);
    let plateau = lit.get(lit.len() * 4 / 5).copied().unwrap_or(1.0);
    let floor = ON * plateau;
    // Noise of the profile: median step between neighbouring lit columns.
    let mut steps: Vec<f32> = profile
        .windows(2)
        .filter(|w| w[0] >= floor && w[1] >= floor)
        .map(|w| (w[1] - w[0]).abs())
        .collect();
    steps.sort_by(f32::total_cmp);
    let noise = steps.get(steps.len() / 2).copied().unwrap_or(0.0);
    let dips = dip_mask(&profile, floor, Some(noise), plateau);
    let on: Vec<bool> = profile
        .iter()
        .zip(&dips)
        .map(|(&p, &d)| p >= floor && !d)
        .collect();
    // Each column's colour votes, over the band's core rows by strength; a run's colour is
    // the sum of its columns' votes.
    let column_votes: Vec<[f32; 4]> = (0..st.width)
        .map(|x| {
            let mut votes = [0f32; 4];
            for (y, w) in (y0..y1).zip(&weights) {
                if let Some(kind) = st.kind[y * st.width + x] {
                    votes[kind.index()] += w * st.at(x, y);
                }
            }
            votes
        })
        .collect();
    let winner = |votes: &[f32; 4]| {
        (0..4)
            .filter(|&k| votes[k] > 0.0)
            .max_by(|&a, &b| votes[a].total_cmp(&votes[b]))
    };
    let column_kind: Vec<Option<usize>> = column_votes.iter().map(winner).collect();
    let found: Vec<(usize, usize)> = runs(&on)
        .into_iter()
        .flat_map(|run| split_by_colour(&column_kind, run))
        .collect();
    let mut out = Vec::new();
    for (k, &(s, e)) in found.iter().enumerate() {
        let votes = column_votes[s..e].iter().fold([0f32; 4], |mut sum, v| {
            sum.iter_mut().zip(v).for_each(|(a, b)| *a += b);
            sum
        });
        let best = winner(&votes).unwrap_or(0);
        // The gap before this run, measured as missing area.
        let gap = if k == 0 {
            f64::INFINITY
        } else {
            deficit(&profile[found[k - 1].1..s], plateau)
        };
        let inner = inner_columns(s, e);
        let from = if k == 0 {
            s.saturating_sub(AREA_REACH)
        } else {
            (found[k - 1].1 + s).div_ceil(2)
        };
        let to = found
            .get(k + 1)
            .map_or((e + AREA_REACH).min(st.width), |next| (e + next.0) / 2);
        // The run's own level, from its inner columns (noise averages out; no clipping).
        let level = profile[inner.clone()].iter().sum::<f32>() / inner.len() as f32;
        let mass = profile[from..to].iter().map(|&p| f64::from(p)).sum::<f64>();
        let area = mass / f64::from(level.max(f32::EPSILON));
        let middle = (from..to)
            .map(|x| (x as f64 + 0.5) * f64::from(profile[x]))
            .sum::<f64>()
            / mass.max(f64::EPSILON);
        out.push(Run {
            start: s,
            end: e,
            kind: BrickType::ALL[best],
            gap,
            area,
            middle,
            column_heights: Vec::new(),
            faint_dips: faint_dips(&profile, s, e),
        });
    }
    // Colour heights, of the band and of each run: from a little above the band to a little
    // below it at the wall's edges (blur spreads them).
    let above = if outer.0 { AREA_REACH } else { 0 };
    let below = if outer.1 { AREA_REACH } else { 0 };
    let rows = y0.saturating_sub(above)..(y1 + below).min(st.height);
    let columns: Vec<usize> = found.iter().flat_map(|&(s, e)| s..e).collect();
    for run in &mut out {
        run.column_heights = (run.start..run.end)
            .map(|x| colour_height(st, &[x], rows.clone()))
            .collect();
    }
    (out, colour_height(st, &columns, rows))
}

/// The width of the dark ring on each side of a run of `kind` (px), measured over a band's
/// rows (`band.0` is its first row, `band.1` the rows' weights) in the `window` of columns
/// around it: a dark border's width where the run stands alone, zero for a border as light
/// as the background. A side is `None` where the image edge cuts its ring off.
///
/// Each pixel splits into its shares of colour and of background (`Mixing`); each
/// share is summed along the window and divided by its median level in the `inner` columns,
/// where the colour is whole. Blur keeps these sums, so they are the widths of the colour and
/// of the colour with its ring, and the ring is their difference.
fn dark_rings(
    st: &Strength,
    mixing: &Mixing,
    kind: BrickType,
    (y0, weights): (usize, &[f32]),
    window: std::ops::Range<usize>,
    inner: std::ops::Range<usize>,
) -> Option<[Option<f64>; 2]> {
    let total = weights.iter().sum::<f32>().max(f32::EPSILON);
    let shares: Vec<(f64, f64)> = window
        .clone()
        .map(|x| {
            let (mut colour, mut filled) = (0.0, 0.0);
            for (y, &w) in (y0..).zip(weights).filter(|(_, &w)| w > 0.0) {
                let (kappa, beta) = mixing.shares(st, x, y, kind)?;
                colour += w * kappa;
                filled += w * (1.0 - beta);
            }
            Some((f64::from(colour / total), f64::from(filled / total)))
        })
        .collect::<Option<_>>()?;
    let inside = &shares[inner.start - window.start..inner.end - window.start];
    let level = |share: fn(&(f64, f64)) -> f64| {
        median(inside.iter().map(share).collect())
            .unwrap_or(1.0)
            .max(f64::EPSILON)
    };
    let (colour, filled) = (level(|s| s.0), level(|s| s.1));
    let ring = |side: &[(f64, f64)]| side.iter().map(|s| s.1 / filled - s.0 / colour).sum();
    let (left, right) = shares.split_at((inner.start + inner.end) / 2 - window.start);
    Some([
        (inner.start > RING_REACH).then(|| ring(left)),
        (inner.end + RING_REACH < st.width).then(|| ring(right)),
    ])
}

/// The height of the colour in `rows` over `columns`, as area: each row's mean strength over
/// the level of the rows inside the colour (those near the strongest), summed.
fn colour_height(st: &Strength, columns: &[usize], rows: std::ops::Range<usize>) -> f64 {
    if columns.is_empty() {
        return 0.0;
    }
    let row_strength: Vec<f32> = rows
        .map(|y| columns.iter().map(|&x| st.at(x, y)).sum::<f32>() / columns.len() as f32)
        .collect();
    let top = row_strength.iter().copied().fold(0.0, f32::max);
    let inside: Vec<f32> = row_strength
        .iter()
        .copied()
        .filter(|&r| r >= 0.9 * top)
        .collect();
    let level = inside.iter().sum::<f32>() / inside.len().max(1) as f32;
    row_strength
        .iter()
        .map(|&r| f64::from(r / level.max(f32::EPSILON)))
        .sum()
}

/// Columns of `profile[s..e]` that are a local minimum below `DIP_CANDIDATE` of their
/// shoulders: where a border may have left only a faint mark.
fn faint_dips(profile: &[f32], s: usize, e: usize) -> Vec<usize> {
    (s + 1..e.saturating_sub(1))
        .filter(|&j| {
            profile[j] <= profile[j - 1]
                && profile[j] <= profile[j + 1]
                && profile[j] < DIP_CANDIDATE * shoulders(profile, j, j + 1)
        })
        .collect()
}

/// Splits a run where its colour changes: two bricks of different colours side by side are
/// two bricks even when the border between them left no dip. Stretches shorter than
/// `MIN_COLOUR_RUN` (blurred edges, noise) join their neighbours.
fn split_by_colour(column_kind: &[Option<usize>], (s, e): (usize, usize)) -> Vec<(usize, usize)> {
    // Stretches of one colour, as (start, end, kind); uncoloured columns join the stretch
    // before them.
    let mut stretches: Vec<(usize, usize, Option<usize>)> = Vec::new();
    for (x, &kind) in column_kind.iter().enumerate().take(e).skip(s) {
        match stretches.last_mut() {
            Some(last) if kind.is_none() || kind == last.2 || last.2.is_none() => {
                last.1 = x + 1;
                if last.2.is_none() {
                    last.2 = kind;
                }
            }
            _ => stretches.push((x, x + 1, kind)),
        }
    }
    // Short stretches join the longer neighbour; then equal neighbours merge.
    while let Some(i) = (0..stretches.len())
        .filter(|&i| stretches[i].1 - stretches[i].0 < MIN_COLOUR_RUN)
        .min_by_key(|&i| stretches[i].1 - stretches[i].0)
        .filter(|_| stretches.len() > 1)
    {
        let short = stretches.remove(i);
        let len = |t: &(usize, usize, Option<usize>)| t.1 - t.0;
        let into_left = match (i.checked_sub(1), stretches.get(i)) {
            (Some(l), Some(r)) => len(&stretches[l]) >= len(r),
            (Some(_), None) => true,
            _ => false,
        };
        if into_left {
            stretches[i - 1].1 = short.1;
        } else {
            stretches[i].0 = short.0;
        }
        let mut j = 1;
        while j < stretches.len() {
            if stretches[j].2 == stretches[j - 1].2 {
                stretches[j - 1].1 = stretches[j].1;
                stretches.remove(j);
            } else {
                j += 1;
            }
        }
    }
    stretches.into_iter().map(|(a, b, _)| (a, b)).collect()
}

/// Reads a wall from an RGB image (see the module docs for the method).
pub fn read_image(img: &RgbImage, name: &str) -> Result<Wall, WallError> {
    if img.width() == 0 || img.height() == 0 {
        return Err(WallError::new(
            name,
            Location::Whole,
            WallErrorKind::ImageDecode {
                reason: "the image is empty (0 pixels)".into(),
            },
        ));
    }
    let st = Strength::of(img)
        .ok_or_else(|| WallError::new(name, Location::Whole, WallErrorKind::NoBricksInImage))?;
    let retry = match read_layers(&st, name, None)? {
        Ok(wall) => return Ok(wall),
        Err(retry) => retry,
    };
    let count = match retry {
        Retry::Count(n) => n,
        Retry::Uncovered { layers, .. } => layers + 1,
    };
    match read_layers(&st, name, Some(count))? {
        Ok(wall) => Ok(wall),
        Err(_) => Err(WallError::new(
            name,
            match retry {
                Retry::Count(_) => Location::Whole,
                Retry::Uncovered { pixel, .. } => Location::Pixel(pixel.0, pixel.1),
            },
            WallErrorKind::ImageLayout {
                reason: match retry {
                    Retry::Count(_) => "the layer height does not fit the brick lengths (a \
                                        layer should be 2/3 of 0.30 m); is this a front view \
                                        of a brick wall?"
                        .into(),
                    Retry::Uncovered { .. } => "these brick-coloured pixels belong to no brick \
                                                of any layer; is this a front view of a brick \
                                                wall?"
                        .into(),
                },
            },
        )),
    }
}

/// Why a reading attempt should be made again with another layer count.
#[derive(Clone, Copy, Debug)]
enum Retry {
    /// The layer pitch disagreed with the brick unit; the wall probably has this many layers.
    Count(usize),
    /// Strongly coloured pixels (the first at `pixel`) lie outside every brick found with
    /// this many layers: a layer was missed.
    Uncovered { layers: usize, pixel: (u32, u32) },
}

/// A pixel that no brick found explains: in columns of a brick much taller than is typical
/// (a layer on top of it was missed), or the first pixel of a stretch of strongly coloured
/// columns, at least `MIN_COLOUR_RUN` wide and two rows tall, that lies in a band but
/// outside every run found there.
fn uncovered(
    st: &Strength,
    bands: &[(usize, usize)],
    band_runs: &[Vec<Run>],
) -> Option<(u32, u32)> {
    // Where a brick has another on top of it in the same band, its columns are much taller
    // than the rest.
    let typical = median(
        band_runs
            .iter()
            .flatten()
            .flat_map(|r| r.column_heights.iter().copied())
            .collect(),
    )
    .unwrap_or(0.0);
    let tall = |h: f64| h > TALL_RUN * typical && h > typical + 2.0;
    for (&(y0, _), runs) in bands.iter().zip(band_runs) {
        for r in runs {
            let mut stretch = 0;
            for (i, &h) in r.column_heights.iter().enumerate() {
                stretch = if tall(h) { stretch + 1 } else { 0 };
                if stretch >= MIN_COLOUR_RUN {
                    return Some(((r.start + i + 1 - stretch) as u32, y0 as u32));
                }
            }
        }
    }
    for (&(y0, y1), runs) in bands.iter().zip(band_runs) {
        let mut stretch = 0;
        for x in 0..st.width {
            let covered = runs.iter().any(|r| x + 1 >= r.start && x <= r.end);
            let strong_rows: Vec<usize> = (y0..y1).filter(|&y| st.at(x, y) >= STRONG).collect();
            if !covered && strong_rows.len() >= 2 {
                stretch += 1;
                if stretch >= MIN_COLOUR_RUN {
                    return Some(((x + 1 - stretch) as u32, strong_rows[0] as u32));
                }
            } else {
                stretch = 0;
            }
        }
    }
    None
}

/// One reading attempt, with the layer count given or found from the separators. `Ok(Err(_))`
/// says why the count looks wrong.
fn read_layers(
    st: &Strength,
    name: &str,
    count: Option<usize>,
) -> Result<Result<Wall, Retry>, WallError> {
    let layers = find_layers(st, name, count)?;
    let (band_runs, heights): (Vec<Vec<Run>>, Vec<f64>) = layers
        .bands
        .iter()
        .enumerate()
        .map(|(j, &band)| bricks_in_band(st, band, (j + 1 == layers.bands.len(), j == 0)))
        .unzip();
    for (j, runs) in band_runs.iter().enumerate() {
        if runs.is_empty() {
            let row = ((layers.bands[j].0 + layers.bands[j].1) / 2) as u32;
            return Err(WallError::new(
                name,
                Location::Pixel(0, row),
                WallErrorKind::ImageLayout {
                    reason: format!(
                        "layer {} (around row {row}) holds no bricks; layers are {:.1} px apart",
                        j + 1,
                        layers.pitch
                    ),
                },
            ));
        }
    }
    if let Some(pixel) = uncovered(st, &layers.bands, &band_runs) {
        return Ok(Err(Retry::Uncovered {
            layers: layers.bands.len(),
            pixel,
        }));
    }
    // Border width: from the layer separators, else from the narrowest gaps between bricks.
    let border = layers.border.unwrap_or_else(|| {
        let gaps: Vec<f64> = band_runs
            .iter()
            .flat_map(|r| r.iter().skip(1).map(|run| run.gap))
            .collect();
        let narrowest = gaps.iter().copied().fold(f64::INFINITY, f64::min);
        if narrowest <= 6.0 {
            median(gaps.into_iter().filter(|&g| g <= narrowest + 3.0).collect()).unwrap_or(0.0)
        } else {
            // Bricks that touch nothing, which only a wall of one layer has (every upper brick
            // stands on a lower one): the dark ring around them, else their lengths, else the
            // grid they sit on.
            let mixing = Mixing::of(st);
            mixing
                .as_ref()
                .and_then(|mixing| dark_border(st, mixing, &layers.bands, &band_runs))
                .or_else(|| fitted_border(&band_runs))
                .unwrap_or_else(|| {
                    lone_layer_border(st, mixing.as_ref(), &layers.bands, &band_runs, &heights)
                })
        }
    });
    let joined = |gap: f64| gap <= border + 3.0;
    let mut found = Vec::new();
    for (j, runs) in band_runs.iter().enumerate() {
        let level = j as u32 + 1;
        let row = ((layers.bands[j].0 + layers.bands[j].1) / 2) as u32;
        for (i, run) in runs.iter().enumerate() {
            let (s, e, kind) = (run.start, run.end, run.kind);
            let left = match i.checked_sub(1).map(|p| runs[p].end) {
                Some(prev) if joined(run.gap) => (prev + s) as f64 / 2.0,
                _ => run.middle - (run.area + border) / 2.0,
            };
            let right = match runs.get(i + 1) {
                Some(next) if joined(next.gap) => (e + next.start) as f64 / 2.0,
                _ => run.middle + (run.area + border) / 2.0,
            };
            found.push(Found {
                level,
                kind,
                left,
                right,
                centre: (((s + e) / 2) as u32, row),
                gap: run.gap,
                faint_dips: run.faint_dips.iter().map(|&x| x as f64 + 0.5).collect(),
            });
        }
    }
    // The unit is what most of the wall's length agrees on: a median of each brick's length
    // per unit, weighted by its nominal units, so that one brick of a wrong length cannot
    // move it and long bricks count most. A second pass caps each weight at the units the
    // brick really measures, so that a sliver cut off a long brick weighs little.
    let per_unit = |f: &Found| (f.right - f.left) / f64::from(f.kind.units());
    let first = weighted_median(
        found
            .iter()
            .map(|f| (per_unit(f), f64::from(f.kind.units())))
            .collect(),
    );
    let unit = weighted_median(
        found
            .iter()
            .map(|f| {
                let nominal = f64::from(f.kind.units());
                (per_unit(f), nominal.min((f.right - f.left) / first))
            })
            .collect(),
    );
    // The wall's height from edge to edge, with the final border estimate.
    let extent = layers.extent - layers.border.unwrap_or(0.0) + border;
    // A layer is 2/3 of a unit tall: its colour (measured as area) plus one border. A wrong
    // layer count shows as bands holding part of a layer, or two.
    let pitch = median(heights.clone()).unwrap_or(0.0) + border;
    let ratio = pitch / unit;
    if !(LAYER_RATIO.0..=LAYER_RATIO.1).contains(&ratio) {
        return Ok(Err(Retry::Count(
            (extent / (unit * 2.0 / 3.0)).round() as usize
        )));
    }
    let found = repair_lengths(found, unit, border);
    let mut bricks = Vec::with_capacity(found.len());
    for f in &found {
        let measured = (f.right - f.left) / unit;
        let expected = f64::from(f.kind.units());
        if !length_fits(measured, expected) {
            return Err(WallError::new(
                name,
                Location::Pixel(f.centre.0, f.centre.1),
                WallErrorKind::LengthMismatch {
                    kind: f.kind,
                    measured: measured * UNIT_LENGTH,
                    pixels: (f.right - f.left).round() as u32,
                    unit,
                    expected: f.kind.length(),
                },
            ));
        }
    }
    for (f, x) in found.iter().zip(grid_positions(&found, unit)) {
        bricks.push((f, x));
    }
    assemble(name, bricks).map(Ok)
}

/// The weighted median of `(value, weight)` pairs; 1 when there are none.
fn weighted_median(mut pairs: Vec<(f64, f64)>) -> f64 {
    pairs.sort_by(|a, b| a.0.total_cmp(&b.0));
    let half = pairs.iter().map(|p| p.1).sum::<f64>() / 2.0;
    let mut seen = 0.0;
    pairs
        .iter()
        .find(|p| {
            seen += p.1;
            seen >= half
        })
        .map_or(1.0, |p| p.0)
}

/// Whether `measured` units is `nominal` units within the reader's tolerance.
fn length_fits(measured: f64, nominal: f64) -> bool {
    (measured - nominal).abs() <= LENGTH_TOLERANCE.max(0.08 * nominal)
}

/// Repairs the two ways a border can mislead at small scales, using the bricks' lengths (no
/// brick of a colour has any length but its own):
/// - two touching pieces of one colour that are each too short but together the colour's
///   length are one brick split by noise;
/// - a run of one colour k times its colour's length is k bricks whose shared borders left
///   no mark.
///
/// `found` holds each layer's bricks left to right.
fn repair_lengths(found: Vec<Found>, unit: f64, border: f64) -> Vec<Found> {
    let units = |f: &Found| (f.right - f.left) / unit;
    let mut merged: Vec<Found> = Vec::with_capacity(found.len());
    for f in found {
        if let Some(last) = merged.last_mut() {
            let nominal = f64::from(f.kind.units());
            // Touching, and the gap between them far fainter than a border: blur keeps a
            // border's missing area, so a real one misses about its width.
            let touching = (f.left - last.right).abs() < 0.5 && f.gap < 0.5 * border.max(1.0);
            if last.level == f.level
                && last.kind == f.kind
                && touching
                && !length_fits(units(last), nominal)
                && !length_fits(units(&f), nominal)
                && length_fits((f.right - last.left) / unit, nominal)
            {
                last.right = f.right;
                last.centre.0 = ((last.left + last.right) / 2.0) as u32;
                last.faint_dips.extend(f.faint_dips);
                continue;
            }
        }
        merged.push(f);
    }
    merged
        .into_iter()
        .flat_map(|f| {
            let nominal = f64::from(f.kind.units());
            let measured = units(&f);
            let k = (measured / nominal).round();
            // Every place a border should be must show at least a faint dip.
            let marked = |j: f64| {
                let x = f.left + j * (f.right - f.left) / k;
                f.faint_dips
                    .iter()
                    .any(|&d| (d - x).abs() <= (0.15 * unit).max(2.0))
            };
            let pieces = if k >= 2.0
                && !length_fits(measured, nominal)
                && length_fits(measured, k * nominal)
                && (1..k as usize).all(|j| marked(j as f64))
            {
                k as usize
            } else {
                1
            };
            let width = (f.right - f.left) / pieces as f64;
            (0..pieces).map(move |p| {
                let left = f.left + p as f64 * width;
                Found {
                    left,
                    right: left + width,
                    centre: if pieces == 1 {
                        f.centre
                    } else {
                        ((left + width / 2.0) as u32, f.centre.1)
                    },
                    ..f.clone()
                }
            })
        })
        .collect()
}

/// Snaps the bricks to the 0.30 m grid: each brick's position in units from the leftmost.
///
/// Every brick edge lies on a grid line `origin + k·unit`. Going left to right, each brick's
/// edges take the nearest line of the grid fitted so far, and the grid (origin and unit) is
/// refitted by least squares on all the edges placed. Adjacent bricks are close, so each step
/// rounds reliably, and the refit lets the long span of the wall pin the unit down: a unit a
/// few per cent off would misplace bricks far from the origin.
fn grid_positions(found: &[Found], unit: f64) -> Vec<u32> {
    let mut order: Vec<usize> = (0..found.len()).collect();
    order.sort_by(|&a, &b| found[a].left.total_cmp(&found[b].left));
    let mut origin = order.first().map_or(0.0, |&i| found[i].left);
    let mut unit = unit;
    // Sums for the least-squares line edge = origin + k·unit.
    let (mut n, mut sk, mut se, mut skk, mut ske) = (0.0, 0.0, 0.0, 0.0, 0.0);
    let mut positions = vec![0u32; found.len()];
    for i in order {
        let f = &found[i];
        let k = ((f.left - origin) / unit).round().max(0.0);
        positions[i] = k as u32;
        for (k, e) in [(k, f.left), (k + f64::from(f.kind.units()), f.right)] {
            n += 1.0;
            sk += k;
            se += e;
            skk += k * k;
            ske += k * e;
        }
        let spread = n * skk - sk * sk;
        if spread > 0.0 {
            unit = (n * ske - sk * se) / spread;
            origin = (se - unit * sk) / n;
        }
    }
    let least = positions.iter().copied().min().unwrap_or(0);
    positions.iter().map(|p| p - least).collect()
}

/// The border width from the dark rings around bricks that stand alone, when the border is
/// dark: the median ring (`None` when there is no ring to see).
fn dark_border(
    st: &Strength,
    mixing: &Mixing,
    bands: &[(usize, usize)],
    band_runs: &[Vec<Run>],
) -> Option<f64> {
    let mut rings = Vec::new();
    for (&band, runs) in bands.iter().zip(band_runs) {
        let weights = core_weights(st, band);
        for (k, r) in runs.iter().enumerate() {
            // From the middle of the gaps beside the run, at most `RING_REACH` past it: blur
            // spreads the ring past the colour.
            let from = k
                .checked_sub(1)
                .map_or(0, |p| (runs[p].end + r.start).div_ceil(2));
            let to = runs.get(k + 1).map_or(st.width, |n| (r.end + n.start) / 2);
            let window = from.max(r.start.saturating_sub(RING_REACH))..to.min(r.end + RING_REACH);
            let inner = inner_columns(r.start, r.end);
            let sides = dark_rings(st, mixing, r.kind, (band.0, &weights), window, inner);
            rings.extend(sides.into_iter().flatten().flatten());
        }
    }
    median(rings).filter(|&ring| ring >= RING_MIN)
}

/// The border width from the lengths of isolated bricks of different colours: each run's
/// coloured width is its nominal length less one border, `r = n·unit − b`, fitted by least
/// squares. `None` when every run has the same nominal length (the fit is then undetermined).
fn fitted_border(band_runs: &[Vec<Run>]) -> Option<f64> {
    let runs: Vec<&Run> = band_runs.iter().flatten().collect();
    let units = run_units(&runs);
    let m = runs.len() as f64;
    let (sn, snn) = units
        .iter()
        .fold((0.0, 0.0), |(a, b), n| (a + n, b + n * n));
    let (sr, snr) = runs
        .iter()
        .zip(&units)
        .fold((0.0, 0.0), |(a, b), (r, n)| (a + r.area, b + n * r.area));
    let spread = m * snn - sn * sn;
    if spread < 0.5 * m {
        return None;
    }
    let unit = (m * snr - sn * sr) / spread;
    // Longer bricks must be wider; anything else is not a wall this fit can read.
    if !unit.is_finite() || unit <= 0.0 {
        return None;
    }
    let border = unit * sn / m - sr / m;
    Some(border.clamp(0.0, 0.5 * unit))
}

/// Each run's nominal length in units. A run may be bricks of one colour whose shared border
/// left no mark: its multiple is its width against the narrowest run of its colour. (Not
/// against other colours: a border takes a larger share of a short brick.)
fn run_units(runs: &[&Run]) -> Vec<f64> {
    runs.iter()
        .map(|r| {
            let narrowest = runs
                .iter()
                .filter(|o| o.kind == r.kind)
                .map(|o| o.area)
                .fold(r.area, f64::min);
            f64::from(r.kind.units()) * (r.area / narrowest).round().max(1.0)
        })
        .collect()
}

/// The border of one layer of isolated bricks of one length whose border is as light as the
/// background: no ring to measure and no lengths to fit (`grid_border`). Each brick's width
/// is measured as linear colour share where the background is light (`linear_width`), else
/// as strength area.
fn lone_layer_border(
    st: &Strength,
    mixing: Option<&Mixing>,
    bands: &[(usize, usize)],
    band_runs: &[Vec<Run>],
    heights: &[f64],
) -> f64 {
    let ([band], [runs], [colour_height]) = (bands, band_runs, heights) else {
        return 0.0;
    };
    let widths: Vec<f64> = runs
        .iter()
        .map(|r| {
            mixing
                .and_then(|mixing| linear_width(st, mixing, *band, r))
                .unwrap_or(r.area)
        })
        .collect();
    grid_border(runs, &widths, *colour_height)
}

/// A lone run's coloured width (px) from the linear colour share κ of `Mixing`: the share
/// summed over a window around it (the colour's area, which blur keeps) over the mean column
/// sum of its inner columns (its height). Their ratio does not depend on how pure the colour
/// reference is, which the strength's clipping and a thin blurred layer both bias.
/// `None` when the colour cannot be unmixed or shows no height.
fn linear_width(
    st: &Strength,
    mixing: &Mixing,
    (y0, y1): (usize, usize),
    run: &Run,
) -> Option<f64> {
    let rows = y0.saturating_sub(AREA_REACH)..(y1 + AREA_REACH).min(st.height);
    let columns = run.start.saturating_sub(AREA_REACH)..(run.end + AREA_REACH).min(st.width);
    let column_sums: Vec<f64> = columns
        .clone()
        .map(|x| {
            rows.clone()
                .map(|y| {
                    mixing
                        .shares(st, x, y, run.kind)
                        .map(|(kappa, _)| f64::from(kappa))
                })
                .sum::<Option<f64>>()
        })
        .collect::<Option<_>>()?;
    let inner = inner_columns(run.start, run.end);
    let height = column_sums[inner.start - columns.start..inner.end - columns.start]
        .iter()
        .sum::<f64>()
        / inner.len() as f64;
    (height > 0.0).then(|| column_sums.iter().sum::<f64>() / height)
}

/// The border of one layer of isolated bricks of one length (`widths` are their coloured
/// widths, `colour_height` the layer's; px), when it leaves no trace. Two facts fix it:
/// - every brick's left edge, its middle less half its nominal length, lies on the grid, so
///   the unit divides the distance between the outer bricks' edges into whole units;
/// - a layer is 2/3 of a unit tall, so each unit `u` implies a border `b = n·u − r` (mean over
///   the runs) and a colour height `2u/3 − b`.
///
/// Each whole number of units between the outer bricks gives a candidate unit. The one whose
/// bricks sit nearest to grid lines and whose implied colour height is nearest the measured
/// one wins (least squares in px): the span pins the unit far better than the height alone,
/// which only has to pick the right whole number. A lone brick has no span; its unit comes
/// from the height rule `u = 3(r − T)` (for one unit). The border returned is the one that
/// makes each run's strength area (`Run::area`, which places the bricks) span its units.
fn grid_border(runs: &[Run], widths: &[f64], colour_height: f64) -> f64 {
    let (Some(first), Some(last)) = (runs.first(), runs.last()) else {
        return 0.0;
    };
    let units = run_units(&runs.iter().collect::<Vec<_>>());
    let m = runs.len() as f64;
    let areas: Vec<f64> = runs.iter().map(|r| r.area).collect();
    let mean_gap = |unit: f64, widths: &[f64]| {
        units
            .iter()
            .zip(widths)
            .map(|(n, w)| n * unit - w)
            .sum::<f64>()
            / m
    };
    let border_for = |unit: f64| mean_gap(unit, widths);
    let placed = |unit: f64| mean_gap(unit, &areas).clamp(0.0, 0.5 * unit);
    let (n0, nl) = (units[0], units[units.len() - 1]);
    let span = last.middle - first.middle;
    if runs.len() < 2 || span <= 0.0 {
        // T = 2u/3 − b and r = n·u − b, averaged over the runs: u = (r̄ − T)/(n̄ − 2/3).
        let mean_n = units.iter().sum::<f64>() / m;
        let mean_r = widths.iter().sum::<f64>() / m;
        return placed(((mean_r - colour_height) / (mean_n - 2.0 / 3.0)).max(0.0));
    }
    // The fewest units the span can hold: the bricks before the last, end to end. The most:
    // a unit no shorter than 3/2 of the colour's height (a border is never negative).
    let fewest = units[..units.len() - 1].iter().sum::<f64>() as usize;
    let shortest = (1.5 * colour_height).max(1.0);
    let score = |unit: f64| {
        let border = border_for(unit);
        let height = 2.0 * unit / 3.0 - border - colour_height;
        let origin = first.middle - n0 * unit / 2.0;
        let off_grid: f64 = runs
            .iter()
            .zip(&units)
            .map(|(r, n)| {
                let k = (r.middle - n * unit / 2.0 - origin) / unit;
                ((k - k.round()) * unit).powi(2)
            })
            .sum();
        height * height + off_grid + border.min(0.0).powi(2)
    };
    (fewest.max(1)..)
        .map(|k| span / (k as f64 + (nl - n0) / 2.0))
        .take_while(|&unit| unit >= shortest)
        .take(MAX_GRID_CANDIDATES)
        .min_by(|&a, &b| score(a).total_cmp(&score(b)))
        .map_or(0.0, placed)
}

/// Turns snapped bricks into a wall: segments from empty columns, labels `100·l + p`.
fn assemble(name: &str, mut placed: Vec<(&Found, u32)>) -> Result<Wall, WallError> {
    placed.sort_by_key(|(f, x)| (f.level, *x));
    let width = placed
        .iter()
        .map(|(f, x)| x + f.kind.units())
        .max()
        .unwrap_or(0) as usize;
    let mut used = vec![false; width];
    for (f, x) in &placed {
        for u in *x..x + f.kind.units() {
            used[u as usize] = true;
        }
    }
    // segment_of[u] = 1 + number of empty runs left of column u.
    let mut segment_of = vec![1u32; width];
    let mut seg = 1;
    for u in 1..width {
        if used[u] && !used[u - 1] {
            seg += 1;
        }
        segment_of[u] = seg;
    }
    let per_level = placed
        .iter()
        .fold(std::collections::BTreeMap::new(), |mut m, (f, _)| {
            *m.entry(f.level).or_insert(0usize) += 1;
            m
        });
    let base = label_base(per_level.values().copied().max().unwrap_or(0));
    let mut position = 0;
    let mut level = 0;
    let mut bricks = Vec::with_capacity(placed.len());
    for (f, x) in placed {
        if f.level != level {
            level = f.level;
            position = 0;
        }
        position += 1;
        bricks.push(Brick {
            label: base * f.level + position,
            kind: f.kind,
            level: f.level,
            segment: segment_of[x as usize],
            footprint: Footprint {
                x0: f64::from(x) * UNIT_LENGTH,
                x1: f64::from(x + f.kind.units()) * UNIT_LENGTH,
                y0: 0.0,
                y1: BRICK_DEPTH,
            },
            origin: Origin::Pixel(f.centre.0, f.centre.1),
        });
    }
    Wall::from_bricks(name, bricks)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn layer_count_keeps_one_layer_per_separator_when_they_are_evenly_spaced() {
        // Four layers whose measured top and bottom are a little off: the smallest gap
        // (5.0 px of 22.7) would suggest five.
        assert_eq!(layer_count(&[9.5, 14.5, 20.26], 3.66, 22.68), 4);
    }

    #[test]
    fn layer_count_adds_the_layers_whose_separators_were_missed() {
        // Layers 10.5 px tall, only the lowest separator found.
        assert_eq!(layer_count(&[35.8], 4.0, 42.0), 4);
        assert_eq!(layer_count(&[], 4.0, 42.0), 1);
    }

    #[test]
    fn a_colour_change_splits_a_run_but_a_flipped_column_does_not() {
        let (r, o) = (Some(0), Some(3));
        let mut kinds = vec![r; 6];
        kinds.extend(vec![o; 8]);
        assert_eq!(split_by_colour(&kinds, (0, 14)), vec![(0, 6), (6, 14)]);
        let mut noisy = vec![o; 14];
        noisy[5] = r;
        noisy[6] = None;
        assert_eq!(split_by_colour(&noisy, (0, 14)), vec![(0, 14)]);
    }

    fn brick(kind: BrickType, left: f64, right: f64) -> Found {
        Found {
            level: 1,
            kind,
            left,
            right,
            centre: (((left + right) / 2.0) as u32, 0),
            gap: 2.0,
            faint_dips: Vec::new(),
        }
    }

    fn spans(found: Vec<Found>) -> Vec<(BrickType, f64, f64)> {
        repair_lengths(found, 10.0, 2.0)
            .iter()
            .map(|f| (f.kind, f.left, f.right))
            .collect()
    }

    #[test]
    fn lengths_merge_a_split_brick_and_split_a_merged_pair() {
        let found = vec![
            Found {
                gap: f64::INFINITY,
                ..brick(BrickType::Green, 0.0, 9.0)
            },
            Found {
                gap: 0.3,
                ..brick(BrickType::Green, 9.0, 20.0)
            },
            Found {
                faint_dips: vec![29.5],
                ..brick(BrickType::Red, 20.0, 40.0)
            },
            brick(BrickType::Blue, 40.0, 80.0),
        ];
        assert_eq!(
            spans(found),
            vec![
                (BrickType::Green, 0.0, 20.0),
                (BrickType::Red, 20.0, 30.0),
                (BrickType::Red, 30.0, 40.0),
                (BrickType::Blue, 40.0, 80.0),
            ]
        );
    }

    #[test]
    fn lengths_keep_what_a_real_border_split_or_no_dip_joined() {
        // Two half greens behind a full-width border, and a seamless 0.6 m red, stay wrong:
        // the length check then reports them.
        let found = vec![
            brick(BrickType::Green, 0.0, 10.0),
            brick(BrickType::Green, 10.0, 20.0),
            brick(BrickType::Red, 20.0, 40.0),
        ];
        assert_eq!(
            spans(found),
            vec![
                (BrickType::Green, 0.0, 10.0),
                (BrickType::Green, 10.0, 20.0),
                (BrickType::Red, 20.0, 40.0),
            ]
        );
    }

    fn run(start: usize, end: usize, column_heights: Vec<f64>) -> Run {
        Run {
            start,
            end,
            kind: BrickType::Red,
            gap: f64::INFINITY,
            area: (end - start) as f64,
            middle: (start + end) as f64 / 2.0,
            column_heights,
            faint_dips: Vec::new(),
        }
    }

    fn lone(kind: BrickType, area: f64) -> Run {
        Run {
            kind,
            area,
            ..run(0, 1, Vec::new())
        }
    }

    #[test]
    fn bricks_of_different_lengths_fix_the_border_and_equal_ones_do_not() {
        // At 8 px per unit with a 3 px border: red shows 5 px of colour, orange 45 px.
        let runs = vec![vec![
            lone(BrickType::Red, 5.0),
            lone(BrickType::Orange, 45.0),
            lone(BrickType::Red, 5.0),
        ]];
        let border = fitted_border(&runs).unwrap();
        assert!((border - 3.0).abs() < 1e-9, "{border}");
        // Against the red, an orange is 1.5 "red units" per unit; it is still one brick.
        let all: Vec<&Run> = runs.iter().flatten().collect();
        assert_eq!(run_units(&all), vec![1.0, 6.0, 1.0]);
        let reds = vec![vec![lone(BrickType::Red, 5.0), lone(BrickType::Red, 5.2)]];
        assert_eq!(fitted_border(&reds), None);
        // A run twice as wide as its colour's narrowest is two bricks.
        let pair = [lone(BrickType::Red, 5.0), lone(BrickType::Red, 10.5)];
        assert_eq!(run_units(&pair.iter().collect::<Vec<_>>()), vec![1.0, 2.0]);
    }

    /// A one-row image: white, a 2 px ring of `ring` colour, 6 px of red, the ring, white.
    #[test]
    fn equal_lone_bricks_take_their_unit_from_the_grid_they_sit_on() {
        // `R . . . . R` at 8 px per unit with a 3 px border: 5 px of colour, 2.33 px tall,
        // middles 40 px apart. A height 0.2 px off either way still picks 5 units between
        // them (the height rule alone would put the unit at 7.4 or 8.6 px).
        let red_at = |middle: f64| Run {
            middle,
            ..lone(BrickType::Red, 5.0)
        };
        let runs = [red_at(12.5), red_at(52.5)];
        for height in [2.13, 2.33, 2.53] {
            let border = grid_border(&runs, &[5.0, 5.0], height);
            assert!(
                (border - 3.0).abs() < 1e-9,
                "height {height}: border {border}"
            );
        }
        // Alone, a brick has only the height rule: u = 3(r − T) = 8 px.
        let border = grid_border(&runs[..1], &[5.0], 7.0 / 3.0);
        assert!((border - 3.0).abs() < 1e-9, "{border}");
    }

    fn ringed_red(ring: [u8; 3]) -> RgbImage {
        RgbImage::from_fn(24, 1, |x, _| {
            image::Rgb(match x {
                8..=13 => [235, 20, 20],
                6 | 7 | 14 | 15 => ring,
                _ => [255, 255, 255],
            })
        })
    }

    #[test]
    fn a_dark_ring_beside_a_lone_brick_is_its_border() {
        let st = Strength::of(&ringed_red([0, 0, 0])).unwrap();
        let mixing = Mixing::of(&st).unwrap();
        let rings = dark_rings(&st, &mixing, BrickType::Red, (0, &[1.0]), 2..20, 9..13);
        let [Some(left), Some(right)] = rings.unwrap() else {
            panic!("both sides are inside the image");
        };
        assert!(
            (left - 2.0).abs() < 0.05 && (right - 2.0).abs() < 0.05,
            "{left} {right}"
        );
        // Cut off by the image edge: that side is not measured.
        let edge = dark_rings(&st, &mixing, BrickType::Red, (0, &[1.0]), 2..20, 3..13).unwrap();
        assert_eq!(edge[0], None);
        // A white border leaves no ring.
        let st = Strength::of(&ringed_red([255, 255, 255])).unwrap();
        let mixing = Mixing::of(&st).unwrap();
        let rings = dark_rings(&st, &mixing, BrickType::Red, (0, &[1.0]), 2..20, 9..13).unwrap();
        assert!(rings.iter().flatten().all(|r| r.abs() < 0.05), "{rings:?}");
    }

    #[test]
    fn pixels_unmix_into_colour_background_and_dark() {
        // A 4×1 image: background, brick, and a pixel that is half brick, a quarter
        // background and a quarter black.
        let red: [f32; 3] = [235.0, 20.0, 20.0];
        let mix = red.map(|c| 0.5 * c + 0.25 * 255.0);
        let mut img = RgbImage::from_pixel(4, 1, image::Rgb([255, 255, 255]));
        img.put_pixel(1, 0, image::Rgb(red.map(|c| c as u8)));
        img.put_pixel(2, 0, image::Rgb(red.map(|c| c as u8)));
        img.put_pixel(3, 0, image::Rgb(mix.map(|c| c.round() as u8)));
        let st = Strength::of(&img).unwrap();
        let mixing = Mixing::of(&st).unwrap();
        let close = |(k, b): (f32, f32), (ek, eb): (f32, f32)| {
            (k - ek).abs() < 0.01 && (b - eb).abs() < 0.01
        };
        let shares = |x| mixing.shares(&st, x, 0, BrickType::Red).unwrap();
        assert!(close(shares(0), (0.0, 1.0)));
        assert!(close(shares(1), (1.0, 0.0)));
        assert!(close(shares(3), (0.5, 0.25)));
        // On a black background there is nothing to measure a dark border against.
        let dark = RgbImage::from_fn(4, 1, |x, _| {
            image::Rgb(if x == 0 { [0, 0, 0] } else { [235, 20, 20] })
        });
        assert!(Mixing::of(&Strength::of(&dark).unwrap()).is_none());
    }

    #[test]
    fn coloured_pixels_outside_every_brick_are_found() {
        let mut img = RgbImage::from_pixel(40, 10, image::Rgb([255, 255, 255]));
        for (x, y) in (2..10)
            .chain(20..30)
            .flat_map(|x| (2..8).map(move |y| (x, y)))
        {
            img.put_pixel(x, y, image::Rgb([230, 20, 20]));
        }
        let st = Strength::of(&img).unwrap();
        let both = vec![vec![run(2, 10, vec![6.0; 8]), run(20, 30, vec![6.0; 10])]];
        assert_eq!(uncovered(&st, &[(0, 10)], &both), None);
        let first_only = vec![vec![run(2, 10, vec![6.0; 8])]];
        assert_eq!(uncovered(&st, &[(0, 10)], &first_only), Some((20, 2)));
        // Columns twice as tall as the rest: a layer on top was missed.
        let mut heights = vec![6.0; 10];
        heights[3..7].iter_mut().for_each(|h| *h = 13.0);
        let tall = vec![vec![run(2, 10, vec![6.0; 8]), run(20, 30, heights)]];
        assert_eq!(uncovered(&st, &[(0, 10)], &tall), Some((23, 0)));
    }

    #[test]
    fn grid_positions_hold_far_from_the_origin_with_a_rough_unit() {
        // Red bricks every other unit at 10 px per unit; the first guess is 4 % short, which
        // alone would put the last brick (at unit 30) on unit 31.
        let found: Vec<Found> = (0..16)
            .map(|i| {
                brick(
                    BrickType::Red,
                    20.0 * f64::from(i),
                    20.0 * f64::from(i) + 10.0,
                )
            })
            .collect();
        let expected: Vec<u32> = (0..16).map(|i| 2 * i).collect();
        assert_eq!(grid_positions(&found, 9.6), expected);
    }
}
