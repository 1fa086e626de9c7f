//! Wall images: a front view of the wall, read with no assumption about proportions.
//!
//! A wall drawing is a stack of horizontal bands, one per layer, and in each band a row of
//! coloured bricks. Every brick and every gap is a whole number of 0.30 m units, and the
//! colours' lengths are red : green : blue : orange = 1 : 2 : 4 : 6. Borders between bricks
//! may be 0 to a few pixels wide, in any grey, on a white or pale background. The height of a
//! band says nothing about the bricks: the MBZIRC sheets, the thesis's figures and sketches are
//! not drawn to scale in height. The reader goes through six steps, one function each:
//!
//! 1. [`classify`]: each pixel is red, green, blue, orange or nothing, by the thesis rule
//!    (DESIGN §2) plus our orange rule, applied to the pixel's colour part (the pixel minus its
//!    grey part, so that a brick colour blended with a white, grey or black border keeps its
//!    class), and only where the pixel is saturated (max − min ≥ 60). Against noise, a pixel
//!    is classified by its mean with its left and right neighbours.
//! 2. [`find_layers`]: rows whose coloured runs agree form a band; a border line or a change of
//!    colour between rows ends it. Bands thinner than [`MIN_COLOUR_PX`] are the blurred edges
//!    of their neighbours; touching bands that agree are one, split again where their colour
//!    dips (a faint border line between two layers drawn alike).
//! 3. [`find_runs`]: in each band, columns take their rows' majority colour, and runs of one
//!    colour are found (and split where their colour dips). Each run's sub-pixel edges come
//!    from its colour's area (a blurred or anti-aliased edge keeps it); where two colours blend
//!    into each other, the edge is where they blend half and half, which is their grid line.
//! 4. [`fit_grid`]: the unit (pixels per 0.30 m) and the border width are the ones that put
//!    every run's edges on one grid of whole units (least squares over all edges) and make
//!    every run a whole number of its colour's length; touching bricks must show the border,
//!    and so must the seams of a run read as several bricks. Candidate units come from the
//!    distances between edges. Of the readings that fit, one at a whole fraction of another's
//!    unit only cuts bricks into seamless pieces and is dropped; the border seen between
//!    layers (or around the wall) picks among the rest; then the fewest bricks win, a clearly
//!    better fit settles a tie, and what is still tied, or rests on a thick border where thin
//!    borders and more bricks fit as well, is reported as ambiguous.
//! 5. [`cut_bricks`]: a run `k` times its colour's length is `k` bricks (two touching reds
//!    with no border between them are two reds).
//! 6. [`assemble`]: bricks get levels (bottom band = level 1), grid positions, labels and
//!    segments (a column range empty on every layer starts a new segment), and
//!    [`Wall::from_bricks`] checks that nothing floats.
//!
//! Limits, each a clear error: at most [`MAX_PIXELS`] pixels; every brick shows at least
//! [`MIN_COLOUR_PX`] pixels of its colour each way (5 px across when blurred with no border,
//! as tested); the unit is at least [`MIN_UNIT_PX`] pixels; borders are narrower than
//! [`MAX_BORDER_SHARE`] of a unit.
//!
//! Tested by drawing random walls over a grid of proportions (layer height 0.3–3 units,
//! borders 0–4 px, unit 8–40 px, blur, noise, white, grey and black borders, white and pale
//! backgrounds) and reading them back (`tests/png_roundtrip.rs`), by drawings made with
//! ImageMagick (`tests/data/*.png`), and by malformed images.

use crate::brick::{Brick, BrickType, Footprint, Origin, BRICK_DEPTH, UNIT_LENGTH};
use crate::error::{Location, WallError, WallErrorKind};
use crate::text::label_base;
use crate::wall::Wall;
use image::RgbImage;
use std::collections::BTreeMap;

/// Minimum saturation (max − min channel) of a brick pixel: ±20 noise on any grey stays
/// below it.
const MIN_SATURATION: f32 = 60.0;
/// The fewest pixels of colour a brick shows along and across the wall.
pub const MIN_COLOUR_PX: usize = 3;
/// Rows differ where a run of one has this many pixels without the same colour in the other.
const ROW_CHANGE_PX: usize = 3;
/// The smallest unit (pixels per 0.30 m) the reader looks for.
pub const MIN_UNIT_PX: f64 = 4.0;
/// Borders are narrower than this share of a unit.
pub const MAX_BORDER_SHARE: f64 = 0.6;
/// Touching bricks show the border between them within this many pixels.
const GAP_AGREEMENT_PX: f64 = 1.25;
/// A reading whose edges are this much farther (px) from its grid than the best reading's
/// does not explain the drawing.
const FIT_SLACK_PX: f64 = 0.75;
/// Borders up to this share of a unit are thin.
const THIN_BORDER_SHARE: f64 = 0.2;
/// A reading whose edges are this much closer (px) to its grid than any other's is preferred.
const CLEARLY_BETTER_PX: f64 = 0.5;
/// A reading's border agrees with the border seen between layers within this many pixels.
const BORDER_AGREEMENT_PX: f64 = 1.0;
/// The largest image read, in pixels (about 7 000 × 7 000).
pub const MAX_PIXELS: u64 = 50_000_000;
/// A column inside a run holding less than this share of its colour is a faint border.
const DIP_COVERAGE: f64 = 0.75;
/// A share of a brick's colour below this is a tint of the paper or noise, not colour.
const FAINT_SHARE: f64 = 0.15;
/// A column where two colours meet is their blend when it lies this close to the line
/// between them (RGB distance).
const BLEND_DISTANCE: f32 = 40.0;
/// How far past a run's last coloured column its blurred edge is summed (px).
const EDGE_REACH: usize = 3;
/// How far past a colour's edge the border around the wall is looked for (px).
const RING_REACH: usize = 8;
/// A border around the wall differs from the paper by at least this much (RGB distance).
const MIN_RING_CONTRAST: f32 = 40.0;
/// The most distances between edges used to propose units.
const MAX_DISTANCES: usize = 24;
/// The most divisions of one distance tried as a unit.
const MAX_DIVISIONS: usize = 64;

/// Classifies one pixel; returns its colour and saturation (max − min channel).
///
/// The thesis rule (red if r > 2g and r > 1.5b; green if g > 1.5r and g > 1.5b; blue if
/// b > 1.5r and b > 1.5g) and our orange rule (0.5r ≤ g ≤ 0.85r and b < 0.5g) are applied to
/// the pixel minus its smallest channel, its colour part: blending a brick colour with any
/// grey changes only the grey part, so anti-aliased edges keep their class.
pub fn classify_pixel(p: [u8; 3]) -> Option<(BrickType, f32)> {
    let lowest = p[0].min(p[1]).min(p[2]);
    let [r, g, b] = p.map(|c| f32::from(c - lowest));
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

/// Decodes PNG bytes and reads the wall.
///
/// The image's size is checked from its header before it is decoded: more than
/// [`MAX_PIXELS`] is an error. It is decoded straight to 8-bit RGB (16-bit samples cut to 8,
/// grey spread to three channels, alpha dropped), so a 50-megapixel image needs about 4 bytes
/// per pixel at most while decoding.
pub fn read_png(bytes: &[u8], name: &str) -> Result<Wall, WallError> {
    let img = decode_rgb(bytes).map_err(|reason| {
        WallError::new(name, Location::Whole, WallErrorKind::ImageDecode { reason })
    })?;
    read_image(&img, name)
}

/// PNG bytes as 8-bit RGB, refusing more than [`MAX_PIXELS`] before allocating for them.
fn decode_rgb(bytes: &[u8]) -> Result<RgbImage, String> {
    let mut decoder = png::Decoder::new(std::io::Cursor::new(bytes));
    decoder.set_transformations(png::Transformations::EXPAND | png::Transformations::STRIP_16);
    let mut reader = decoder.read_info().map_err(|e| e.to_string())?;
    let (w, h) = reader.info().size();
    if u64::from(w) * u64::from(h) > MAX_PIXELS {
        return Err(format!(
            "{w}×{h} is more than the {MAX_PIXELS} pixels a wall image may have"
        ));
    }
    let size = reader
        .output_buffer_size()
        .ok_or_else(|| format!("{w}×{h} does not fit in memory"))?;
    let mut buf = vec![0u8; size];
    let frame = reader.next_frame(&mut buf).map_err(|e| e.to_string())?;
    buf.truncate(frame.buffer_size());
    let pixels = w as usize * h as usize;
    let rgb = match frame.color_type {
        png::ColorType::Rgb => buf,
        png::ColorType::Rgba => {
            for i in 0..pixels {
                buf.copy_within(4 * i..4 * i + 3, 3 * i);
            }
            buf.truncate(3 * pixels);
            buf
        }
        png::ColorType::Grayscale | png::ColorType::GrayscaleAlpha => {
            let step = if frame.color_type == png::ColorType::Grayscale {
                1
            } else {
                2
            };
            buf.iter().step_by(step).flat_map(|&g| [g, g, g]).collect()
        }
        png::ColorType::Indexed => return Err("an indexed image was not expanded".into()),
    };
    RgbImage::from_raw(w, h, rgb).ok_or_else(|| "the decoded image is short".into())
}

/// Reads a wall from a decoded image (see the module documentation for the steps).
pub fn read_image(img: &RgbImage, name: &str) -> Result<Wall, WallError> {
    let fail = |location, reason: String| {
        WallError::new(name, location, WallErrorKind::ImageLayout { reason })
    };
    if img.width() == 0 || img.height() == 0 {
        return Err(WallError::new(
            name,
            Location::Whole,
            WallErrorKind::ImageDecode {
                reason: "the image is empty".into(),
            },
        ));
    }
    if u64::from(img.width()) * u64::from(img.height()) > MAX_PIXELS {
        return Err(fail(
            Location::Whole,
            format!("the image has more than {MAX_PIXELS} pixels"),
        ));
    }
    let pixels = classify(img);
    let layers = find_layers(&pixels).map_err(|(at, reason)| fail(at, reason))?;
    if layers.is_empty() {
        return Err(WallError::new(
            name,
            Location::Whole,
            WallErrorKind::NoBricksInImage,
        ));
    }
    let runs = find_runs(&pixels, &layers).map_err(|(at, reason)| fail(at, reason))?;
    let border_seen = border_between_layers(&pixels, &layers, &runs)
        .or_else(|| border_around_wall(&pixels, &layers, &runs));
    let reading = fit_grid(&runs, border_seen).map_err(|misfit| misfit.into_error(name))?;
    assemble(name, cut_bricks(&runs, &reading))
}

/// Step 1: every pixel's class, beside the image itself.
struct Pixels<'a> {
    width: usize,
    height: usize,
    class: Vec<Option<BrickType>>,
    img: &'a RgbImage,
}

impl Pixels<'_> {
    /// The colour of pixel `i` (row-major) as floats.
    fn rgb(&self, i: usize) -> [f32; 3] {
        let raw = &self.img.as_raw()[3 * i..3 * i + 3];
        [raw[0], raw[1], raw[2]].map(f32::from)
    }
}

fn classify(img: &RgbImage) -> Pixels<'_> {
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

/// A stretch of columns `[start, end)` of one colour.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Span {
    kind: BrickType,
    start: usize,
    end: usize,
}

/// Runs of one class at least `shortest` long in a sequence of classes.
fn spans(classes: impl Iterator<Item = Option<BrickType>>, shortest: usize) -> Vec<Span> {
    let mut out = Vec::new();
    let mut open: Option<Span> = None;
    for (x, c) in classes.chain(std::iter::once(None)).enumerate() {
        match (open, c) {
            (Some(s), Some(k)) if s.kind == k => {}
            _ => {
                if let Some(mut s) = open.take() {
                    s.end = x;
                    if s.end - s.start >= shortest {
                        out.push(s);
                    }
                }
                open = c.map(|kind| Span {
                    kind,
                    start: x,
                    end: x,
                });
            }
        }
    }
    out
}

/// Whether some span of `a` has a stretch of [`ROW_CHANGE_PX`] pixels without its colour in
/// `b` (an edge that flickers by a pixel or two is the same row).
fn uncovered(a: &[Span], b: &[Span]) -> bool {
    a.iter().any(|s| {
        let mut reached = s.start;
        for t in b
            .iter()
            .filter(|t| t.kind == s.kind && t.end > s.start && t.start < s.end)
        {
            if t.start >= reached + ROW_CHANGE_PX {
                return true;
            }
            reached = reached.max(t.end);
        }
        s.end >= reached + ROW_CHANGE_PX
    })
}

fn rows_differ(a: &[Span], b: &[Span]) -> bool {
    uncovered(a, b) || uncovered(b, a)
}

/// A layer: rows `[top, bottom)` of the image.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Layer {
    top: usize,
    bottom: usize,
}

type Failure = (Location, String);

/// Step 2: the layers, top to bottom.
///
/// Consecutive rows whose runs agree form a segment. A segment at least [`MIN_COLOUR_PX`]
/// rows tall is a layer; a thinner one touching a layer is that layer's blurred edge (or the
/// blend between two layers) and is dropped; a thinner one standing alone is an error.
/// Touching layers whose runs agree are one layer drawn with no border.
fn find_layers(px: &Pixels) -> Result<Vec<Layer>, Failure> {
    let row_spans: Vec<Vec<Span>> = (0..px.height)
        .map(|y| {
            spans(
                px.class[y * px.width..(y + 1) * px.width].iter().copied(),
                MIN_COLOUR_PX,
            )
        })
        .collect();
    let mut segments: Vec<Layer> = Vec::new();
    for y in 0..px.height {
        if row_spans[y].is_empty() {
            continue;
        }
        match segments.last_mut() {
            Some(s) if s.bottom == y && !rows_differ(&row_spans[y - 1], &row_spans[y]) => {
                s.bottom = y + 1
            }
            _ => segments.push(Layer {
                top: y,
                bottom: y + 1,
            }),
        }
    }
    // Touching segments that agree are one band (noise cut it, or two layers are drawn alike
    // with no border line).
    let tall = |s: &Layer| s.bottom - s.top >= MIN_COLOUR_PX;
    // Thin segments between them (a flickering row) do not keep them apart.
    let mut bands: Vec<Layer> = Vec::new();
    let mut unbroken = false; // every row since the last band is in some segment
    let mut previous_end = 0;
    for s in &segments {
        unbroken &= s.top == previous_end;
        previous_end = s.bottom;
        if !tall(s) {
            continue;
        }
        match bands.last_mut() {
            Some(l) if unbroken && !rows_differ(&band_spans(px, *l), &band_spans(px, *s)) => {
                l.bottom = s.bottom
            }
            _ => bands.push(*s),
        }
        unbroken = true;
    }
    // A faint border line that leaves the colours' classes alone still dims them.
    let layers: Vec<Layer> = bands
        .iter()
        .flat_map(|&b| split_at_faint_borders(px, b))
        .filter(tall)
        .collect();
    // A thin segment is the blurred edge of a layer (at most two rows away, or joined to it
    // by coloured rows all the way), a speck of noise (no run as long as two bricks' least
    // colour), or a stray mark.
    let mut block = vec![0usize; segments.len()]; // stacks of segments with no row between
    for i in 1..segments.len() {
        block[i] = block[i - 1] + usize::from(segments[i].top != segments[i - 1].bottom);
    }
    let mut has_layer = vec![false; block.last().map_or(0, |b| b + 1)];
    for (s, &b) in segments.iter().zip(&block) {
        has_layer[b] |= tall(s);
    }
    let solid: Vec<bool> = block.iter().map(|&b| has_layer[b]).collect();
    for (i, s) in segments.iter().enumerate().filter(|(_, s)| !tall(s)) {
        let near = solid[i]
            || bands
                .iter()
                .any(|l| l.bottom + 2 >= s.top && s.bottom + 2 >= l.top);
        let speck = (s.top..s.bottom)
            .flat_map(|y| &row_spans[y])
            .all(|r| r.end - r.start < 2 * MIN_COLOUR_PX);
        if !near && !speck {
            let first = row_spans[s.top][0];
            return Err((
                Location::Pixel(first.start as u32, s.top as u32),
                format!(
                    "a coloured mark {} px tall stands alone: a layer needs at least \
                     {MIN_COLOUR_PX} px of brick colour",
                    s.bottom - s.top
                ),
            ));
        }
    }
    Ok(layers)
}

/// How saturated each row of a band is, over the columns coloured in the band.
fn row_strength(px: &Pixels, band: Layer) -> Vec<f32> {
    let columns: Vec<usize> = band_spans(px, band)
        .iter()
        .flat_map(|s| s.start + 1..s.end.saturating_sub(1))
        .collect();
    (band.top..band.bottom)
        .map(|y| {
            columns
                .iter()
                .map(|&x| {
                    colour_part(px.rgb(y * px.width + x))
                        .into_iter()
                        .fold(0f32, f32::max)
                })
                .sum::<f32>()
                / columns.len().max(1) as f32
        })
        .collect()
}

/// Splits a band where its colour dips below three quarters of the rows above and below it:
/// a border line between two layers drawn alike.
fn split_at_faint_borders(px: &Pixels, band: Layer) -> Vec<Layer> {
    let strength = row_strength(px, band);
    let n = strength.len();
    let mut peak_above = vec![0f32; n];
    let mut peak_below = vec![0f32; n];
    for i in 1..n {
        peak_above[i] = peak_above[i - 1].max(strength[i - 1]);
        peak_below[n - 1 - i] = peak_below[n - i].max(strength[n - i]);
    }
    let dip = |i: usize| strength[i] < 0.75 * peak_above[i].min(peak_below[i]);
    let mut parts = Vec::new();
    let mut start = None;
    for i in 0..=n {
        match (i < n && !dip(i), start) {
            (true, None) => start = Some(i),
            (false, Some(s)) => {
                parts.push(Layer {
                    top: band.top + s,
                    bottom: band.top + i,
                });
                start = None;
            }
            _ => {}
        }
    }
    parts
}

/// The runs of a layer, from its columns' majority colours.
fn band_spans(px: &Pixels, layer: Layer) -> Vec<Span> {
    spans(column_classes(px, layer).into_iter(), MIN_COLOUR_PX)
}

/// Each column's majority class over the layer's rows (no class wins ties with a colour).
fn column_classes(px: &Pixels, layer: Layer) -> Vec<Option<BrickType>> {
    let rows = layer.bottom - layer.top;
    (0..px.width)
        .map(|x| {
            let mut counts = [0usize; 4];
            for y in layer.top..layer.bottom {
                if let Some(k) = px.class[y * px.width + x] {
                    counts[k.index()] += 1;
                }
            }
            let (best, &n) = counts
                .iter()
                .enumerate()
                .max_by_key(|&(i, n)| (*n, std::cmp::Reverse(i)))
                .expect("four colours");
            (2 * n > rows).then(|| BrickType::ALL[best])
        })
        .collect()
}

/// A run of one colour in one layer, with sub-pixel edges.
#[derive(Clone, Debug, PartialEq)]
struct Run {
    /// Index of the layer, top to bottom.
    layer: usize,
    kind: BrickType,
    /// Left edge of the colour (px, sub-pixel).
    left: f64,
    /// Right edge of the colour (px, sub-pixel).
    right: f64,
    /// A pixel inside the run, for messages.
    pixel: (u32, u32),
    /// Whether the left and right edges are blends with a touching run, found on the grid
    /// line itself rather than half a border from it.
    blended: (bool, bool),
    /// The first column classified as the run's colour.
    first_column: usize,
    /// How much of the colour each column from `first_column` on holds, in [0, 1].
    coverage: Vec<f32>,
}

impl Run {
    fn width(&self) -> f64 {
        self.right - self.left
    }
}

/// The mean colour of each column over the layer's rows.
fn column_means(px: &Pixels, layer: Layer) -> Vec<[f32; 3]> {
    let n = (layer.bottom - layer.top) as f32;
    (0..px.width)
        .map(|x| {
            let mut sum = [0f32; 3];
            for y in layer.top..layer.bottom {
                let p = px.rgb(y * px.width + x);
                for c in 0..3 {
                    sum[c] += p[c];
                }
            }
            sum.map(|s| s / n)
        })
        .collect()
}

/// The colour part of a colour: minus its smallest channel.
fn colour_part(p: [f32; 3]) -> [f32; 3] {
    let lowest = p[0].min(p[1]).min(p[2]);
    p.map(|c| c - lowest)
}

/// How much of `reference`'s colour part `p` holds, in [0, 1]; a faint tint counts as none.
fn coverage(p: [f32; 3], reference: [f32; 3]) -> f64 {
    let share = colour_share(p, reference);
    if share < FAINT_SHARE {
        0.0
    } else {
        share
    }
}

/// How much of `reference`'s colour part `p` holds, in [0, 1].
fn colour_share(p: [f32; 3], reference: [f32; 3]) -> f64 {
    let (p, k) = (colour_part(p), colour_part(reference));
    let dot: f32 = (0..3).map(|c| p[c] * k[c]).sum();
    let norm: f32 = (0..3).map(|c| k[c] * k[c]).sum();
    if norm <= 0.0 {
        return 0.0;
    }
    f64::from(dot / norm).clamp(0.0, 1.0)
}

/// Step 3: the runs of every layer with sub-pixel edges.
///
/// A run shorter than [`MIN_COLOUR_PX`] that touches another is the blend where two colours
/// meet and belongs to the gap between them; alone, it is an error. Each run owns the columns
/// up to half-way to its neighbours (at most [`EDGE_REACH`] past its last coloured column),
/// and its width and centre are the area and centroid of its colour over them.
fn find_runs(px: &Pixels, layers: &[Layer]) -> Result<Vec<Run>, Failure> {
    let mut runs = Vec::new();
    for (index, &layer) in layers.iter().enumerate() {
        let means = column_means(px, layer);
        let middle = ((layer.top + layer.bottom) / 2) as u32;
        // A run too short for a brick that touches another is the blend where two colours
        // meet; alone, it is measured (and refused below as too narrow).
        let all = spans(column_classes(px, layer).into_iter(), 1);
        let touches = |i: usize| {
            (i > 0 && all[i - 1].end == all[i].start)
                || all.get(i + 1).is_some_and(|n| n.start == all[i].end)
        };
        // A border too faint to break a run's colour still dims it: split the run there.
        let kept: Vec<Span> = (0..all.len())
            .filter(|&i| all[i].end - all[i].start >= MIN_COLOUR_PX || !touches(i))
            .flat_map(|i| split_at_dips(&means, all[i]))
            .collect();
        let references: Vec<[f32; 3]> = kept.iter().map(|s| reference_colour(&means, *s)).collect();
        // Where two runs meet with no border between them, the edge is where their colours
        // blend half and half.
        let junction: Vec<Option<f64>> = kept
            .windows(2)
            .zip(references.windows(2))
            .map(|(pair, colours)| colour_junction(&means, pair, colours))
            .collect();
        for (i, s) in kept.iter().enumerate() {
            let k = references[i];
            let middle_column = (s.start + s.end) / 2;
            let inner_left = (s.start + EDGE_REACH).min(middle_column);
            let inner_right = s.end.saturating_sub(EDGE_REACH).max(middle_column);
            let area = |columns: std::ops::Range<usize>| -> f64 {
                columns.map(|x| coverage(means[x], k)).sum()
            };
            // Towards a border or the background, the edge is where the colour's area ends;
            // gap columns are shared half-way with the neighbour.
            let left = match i.checked_sub(1) {
                Some(j) if junction[j].is_some() => junction[j].expect("checked"),
                previous => {
                    let mut limit = s.start.saturating_sub(EDGE_REACH);
                    if let Some(j) = previous {
                        limit = limit.max((kept[j].end + s.start).div_ceil(2));
                    }
                    inner_left as f64 - area(limit..inner_left)
                }
            };
            let right = match junction.get(i) {
                Some(Some(edge)) => *edge,
                _ => {
                    let mut limit = (s.end + EDGE_REACH).min(px.width);
                    if let Some(next) = kept.get(i + 1) {
                        limit = limit.min((s.end + next.start) / 2);
                    }
                    inner_right as f64 + area(inner_right..limit)
                }
            };
            if right - left < MIN_COLOUR_PX as f64 - 0.5 {
                return Err((
                    Location::Pixel(s.start as u32, middle),
                    format!(
                        "a {} mark {:.1} px wide is too narrow for a brick (at least \
                         {MIN_COLOUR_PX} px of colour)",
                        s.kind,
                        right - left
                    ),
                ));
            }
            runs.push(Run {
                layer: index,
                kind: s.kind,
                left,
                right,
                pixel: (middle_column as u32, middle),
                blended: (
                    i > 0 && junction[i - 1].is_some(),
                    junction.get(i).is_some_and(|j| j.is_some()),
                ),
                first_column: s.start,
                coverage: (s.start..s.end)
                    .map(|x| coverage(means[x], k) as f32)
                    .collect(),
            });
        }
    }
    Ok(runs)
}

/// A run's pieces between the columns where its colour dips below [`DIP_COVERAGE`] of itself
/// with full colour on both sides (a faint border between touching bricks of one colour).
fn split_at_dips(means: &[[f32; 3]], run: Span) -> Vec<Span> {
    let k = reference_colour(means, run);
    let c: Vec<f64> = (run.start..run.end)
        .map(|x| coverage(means[x], k))
        .collect();
    let full = |range: std::ops::Range<usize>| range.into_iter().any(|i| c[i] >= 0.9);
    let mut pieces = Vec::new();
    let mut start = 0;
    for i in MIN_COLOUR_PX..c.len().saturating_sub(MIN_COLOUR_PX) {
        let lowest = c[i] < DIP_COVERAGE && c[i] <= c[i - 1] && c[i] < c[i + 1];
        if lowest
            && i >= start + MIN_COLOUR_PX
            && full(i.saturating_sub(2 * EDGE_REACH)..i)
            && full(i + 1..(i + 1 + 2 * EDGE_REACH).min(c.len()))
        {
            pieces.push(Span {
                start: run.start + start,
                end: run.start + i,
                ..run
            });
            start = i + 1;
        }
    }
    pieces.push(Span {
        start: run.start + start,
        ..run
    });
    pieces
}

/// The edge between two runs whose colours blend into each other: the place where they blend
/// half and half, from each column's share of the second colour. That is their grid line,
/// with no border or with a border of the grey their blend passes through (orange and blue
/// blend through grey). `None` when a column where they meet is off the blend (a border of
/// another grey lies between them).
fn colour_junction(means: &[[f32; 3]], pair: &[Span], colours: &[[f32; 3]]) -> Option<f64> {
    let (a, b) = (pair[0], pair[1]);
    let blend = Blend::new(colours[0], colours[1])?;
    if b.start - a.end > 2 || (a.end - 1..b.start + 1).any(|x| !blend.holds(means[x])) {
        return None;
    }
    let from = a.end.saturating_sub(EDGE_REACH).max((a.start + a.end) / 2);
    let to = (b.start + EDGE_REACH).min((b.start + b.end) / 2);
    let first_share: f64 = (from..to)
        .map(|x| 1.0 - f64::from(blend.share_of_second(means[x])))
        .sum();
    Some(from as f64 + first_share)
}

/// The colours on the straight line from one colour to another: what two colours blurred or
/// anti-aliased into each other make.
struct Blend {
    first: [f32; 3],
    step: [f32; 3],
    norm: f32,
}

impl Blend {
    /// `None` when the two colours are the same.
    fn new(first: [f32; 3], second: [f32; 3]) -> Option<Blend> {
        let step: [f32; 3] = std::array::from_fn(|c| second[c] - first[c]);
        let norm: f32 = step.iter().map(|v| v * v).sum();
        (norm > 0.0).then_some(Blend { first, step, norm })
    }

    /// How much of the second colour `p` holds, in [0, 1].
    fn share_of_second(&self, p: [f32; 3]) -> f32 {
        let along: f32 = (0..3).map(|c| (p[c] - self.first[c]) * self.step[c]).sum();
        (along / self.norm).clamp(0.0, 1.0)
    }

    /// Whether every blend of the two is a colour: orange and blue blend through grey, and
    /// there a grey border between them would look like their blend.
    fn keeps_colour(&self) -> bool {
        [0.25f32, 0.5, 0.75].into_iter().all(|t| {
            let p: [f32; 3] = std::array::from_fn(|c| self.first[c] + t * self.step[c]);
            colour_part(p).into_iter().fold(0f32, f32::max) >= MIN_SATURATION
        })
    }

    /// Whether `p` lies on the line, within [`BLEND_DISTANCE`].
    fn holds(&self, p: [f32; 3]) -> bool {
        let t = self.share_of_second(p);
        let off: f32 = (0..3)
            .map(|c| (p[c] - self.first[c] - t * self.step[c]).powi(2))
            .sum();
        off.sqrt() <= BLEND_DISTANCE
    }
}

/// A run's colour: the median of its columns, its two edge columns left out.
fn reference_colour(means: &[[f32; 3]], run: Span) -> [f32; 3] {
    if run.end - run.start > 2 {
        median_colour(&means[run.start + 1..run.end - 1])
    } else {
        median_colour(&means[run.start..run.end])
    }
}

fn median_colour(columns: &[[f32; 3]]) -> [f32; 3] {
    let mut out = [0f32; 3];
    for (c, o) in out.iter_mut().enumerate() {
        let mut v: Vec<f32> = columns.iter().map(|p| p[c]).collect();
        v.sort_by(f32::total_cmp);
        *o = v[v.len() / 2];
    }
    out
}

/// How much of a reference colour a pixel holds.
type ShareOf = fn([f32; 3], [f32; 3]) -> f64;

/// The border between layers (px), where layers touch: the median gap between the colour of
/// a layer and of the layer below it, over columns where both have colour. `None` for a
/// single layer or layers that never sit on each other.
fn border_between_layers(px: &Pixels, layers: &[Layer], runs: &[Run]) -> Option<f64> {
    let mut gaps = Vec::new();
    for pair in 0..layers.len().saturating_sub(1) {
        let (upper, lower) = (layers[pair], layers[pair + 1]);
        if lower.top - upper.bottom > 4 * EDGE_REACH {
            continue;
        }
        // Where one colour sits on the same colour, no blend of two colours blurs the gap.
        let all = inside_runs(px, runs, &[pair, pair + 1]);
        let (above, below) = (
            colour_inside(px, runs, pair),
            colour_inside(px, runs, pair + 1),
        );
        let alike: Vec<usize> = all
            .iter()
            .copied()
            .filter(|&x| above[x] == below[x])
            .collect();
        // Over two colours blending into each other, faint shares count (they add up to the
        // whole); over a border, a faint tint is the paper's.
        let two_colours = alike.is_empty();
        let (columns, share_of): (Vec<usize>, ShareOf) = if two_colours {
            (all, colour_share)
        } else {
            (alike, coverage)
        };
        if columns.is_empty() {
            continue;
        }
        let middle = (upper.bottom + lower.top) / 2;
        let upper_inner = upper
            .bottom
            .saturating_sub(2 * EDGE_REACH)
            .max((upper.top + upper.bottom) / 2);
        let lower_inner = (lower.top + 2 * EDGE_REACH).min((lower.top + lower.bottom) / 2);
        // Each column's colour in each layer. Where two colours blend straight into each other
        // (every row between them on the line from one to the other, each pixel averaged with
        // its left and right neighbours against noise, and no grey on that line), each row's
        // share of the lower colour is measured along that line: the shares add up to one and
        // show no border.
        let upper_colours = column_means(px, upper);
        let lower_colours = column_means(px, lower);
        let smoothed = |x: usize, y: usize| -> [f32; 3] {
            let near = x.saturating_sub(1)..(x + 2).min(px.width);
            let n = near.len() as f32;
            let mut sum = [0f32; 3];
            for xx in near {
                let p = px.rgb(y * px.width + xx);
                (0..3).for_each(|c| sum[c] += p[c]);
            }
            sum.map(|v| v / n)
        };
        let blends: Vec<Option<Blend>> = columns
            .iter()
            .map(|&x| {
                let blend = Blend::new(upper_colours[x], lower_colours[x])?;
                let straight = two_colours
                    && blend.keeps_colour()
                    && (upper_inner..lower_inner).all(|y| blend.holds(smoothed(x, y)));
                straight.then_some(blend)
            })
            .collect();
        // Each row's share of a layer's colour near the gap (`lower`: of the lower layer's).
        let share = |y: usize, lower_layer: bool| -> f64 {
            columns
                .iter()
                .zip(&blends)
                .map(|(&x, blend)| {
                    let p = px.rgb(y * px.width + x);
                    match (blend, lower_layer) {
                        (Some(b), true) => f64::from(b.share_of_second(p)),
                        (Some(b), false) => 1.0 - f64::from(b.share_of_second(p)),
                        (None, true) => share_of(p, lower_colours[x]),
                        (None, false) => share_of(p, upper_colours[x]),
                    }
                })
                .sum::<f64>()
                / columns.len() as f64
        };
        let colour_bottom =
            upper_inner as f64 + (upper_inner..middle).map(|y| share(y, false)).sum::<f64>();
        let colour_top =
            lower_inner as f64 - (middle..lower_inner).map(|y| share(y, true)).sum::<f64>();
        gaps.push(colour_top - colour_bottom);
    }
    if gaps.is_empty() {
        return None;
    }
    gaps.sort_by(f64::total_cmp);
    Some(gaps[gaps.len() / 2].max(0.0))
}

/// The border seen above the top layer (or below the bottom one): the rows between the
/// colour's edge and the paper, each counted by how far it is from the paper's colour
/// relative to the farthest. `None` where the border looks like the paper, or the paper is
/// not in view.
fn border_around_wall(px: &Pixels, layers: &[Layer], runs: &[Run]) -> Option<f64> {
    let sides = [(0, true), (layers.len() - 1, false)];
    sides.into_iter().find_map(|(index, above)| {
        let layer = layers[index];
        let columns = inside_runs(px, runs, &[index]);
        if columns.is_empty() {
            return None;
        }
        let colours = column_means(px, layer);
        let middle = (layer.top + layer.bottom) / 2;
        // Rows outward from inside the colour to the paper (at most RING_REACH past the
        // colour's edge, or the image's), nearest first.
        let reach = 2 * EDGE_REACH + RING_REACH;
        let outward: Vec<usize> = if above {
            let inner = (layer.top + 2 * EDGE_REACH).min(middle);
            (inner.saturating_sub(reach)..inner).rev().collect()
        } else {
            let inner = layer.bottom.saturating_sub(2 * EDGE_REACH).max(middle);
            (inner..(inner + reach).min(px.height)).collect()
        };
        if outward.len() < 2 * EDGE_REACH + 2 {
            return None;
        }
        let n = columns.len() as f32;
        let mean_of = |f: &dyn Fn(usize) -> [f32; 3]| -> [f32; 3] {
            let mut sum = [0f32; 3];
            for &x in &columns {
                let p = f(x);
                (0..3).for_each(|c| sum[c] += p[c]);
            }
            sum.map(|v| v / n)
        };
        let colour = mean_of(&|x| colours[x]);
        let paper = mean_of(&|x| px.rgb(outward[outward.len() - 1] * px.width + x));
        // Each row: its share of colour, and what is left once the colour is taken out.
        let rows: Vec<(f64, f32)> = outward
            .iter()
            .map(|&y| {
                let p = mean_of(&|x| px.rgb(y * px.width + x));
                let c = colour_share(p, colour);
                let rest: [f32; 3] = std::array::from_fn(|k| {
                    (p[k] - c as f32 * colour[k]) / (1.0 - c as f32).max(0.05)
                });
                let far: f32 = (0..3)
                    .map(|k| (rest[k] - paper[k]).powi(2))
                    .sum::<f32>()
                    .sqrt();
                (c, far)
            })
            .collect();
        // Only rows with next to no colour show whether there is a border at all.
        let deepest = rows
            .iter()
            .filter(|r| r.0 < FAINT_SHARE)
            .map(|r| r.1)
            .fold(0f32, f32::max);
        if deepest < MIN_RING_CONTRAST {
            return None;
        }
        Some(
            rows.iter()
                .map(|&(c, far)| (1.0 - c) * f64::from((far / deepest).min(1.0)))
                .sum(),
        )
    })
}

/// The columns well inside the runs of every listed layer.
fn inside_runs(px: &Pixels, runs: &[Run], layers: &[usize]) -> Vec<usize> {
    let maps: Vec<Vec<Option<BrickType>>> =
        layers.iter().map(|&l| colour_inside(px, runs, l)).collect();
    (0..px.width)
        .filter(|&x| maps.iter().all(|m| m[x].is_some()))
        .collect()
}

/// Per column, the colour of the layer's run that covers the whole pixel, if any: one pass
/// over the layer's runs.
fn colour_inside(px: &Pixels, runs: &[Run], layer: usize) -> Vec<Option<BrickType>> {
    let mut map = vec![None; px.width];
    for r in runs.iter().filter(|r| r.layer == layer) {
        let first = r.left.max(0.0).ceil() as usize;
        let end = (r.right.max(0.0).floor() as usize).min(px.width);
        for slot in map.iter_mut().take(end).skip(first) {
            *slot = Some(r.kind);
        }
    }
    map
}

/// A fitted grid: pixels per unit, border width and every run's place on it.
#[derive(Clone, Debug, PartialEq)]
struct Reading {
    unit: f64,
    border: f64,
    /// Per run: its first unit and its length in units.
    places: Vec<(i64, u32)>,
    /// The largest distance of an edge from its grid line (px).
    residual: f64,
}

/// Why no grid fits: the pixel of the run to blame, and what is wrong.
#[derive(Debug)]
struct Misfit {
    pixel: (u32, u32),
    kind: WallErrorKind,
}

impl Misfit {
    fn layout(run: &Run, reason: String) -> Misfit {
        Misfit {
            pixel: run.pixel,
            kind: WallErrorKind::ImageLayout { reason },
        }
    }

    /// A run that is not a whole number of its colour's length (`units` long).
    fn length(run: &Run, unit: f64, units: f64) -> Misfit {
        Misfit {
            pixel: run.pixel,
            kind: WallErrorKind::LengthMismatch {
                kind: run.kind,
                measured: units * UNIT_LENGTH,
                pixels: run.width().round() as u32,
                unit,
                expected: run.kind.length(),
            },
        }
    }

    fn no_unit(run: &Run) -> Misfit {
        Misfit::layout(
            run,
            format!("no unit of at least {MIN_UNIT_PX} px per 0.30 m fits the bricks"),
        )
    }

    fn into_error(self, name: &str) -> WallError {
        WallError::new(name, Location::Pixel(self.pixel.0, self.pixel.1), self.kind)
    }
}

/// How far a measured edge may be off the grid (px).
fn tolerance(unit: f64) -> f64 {
    (0.1 * unit).max(1.5).min(0.25 * unit)
}

/// Step 4: the unit and border that put every run on one grid of whole units.
fn fit_grid(runs: &[Run], border_seen: Option<f64>) -> Result<Reading, Misfit> {
    let mut readings: Vec<Reading> = Vec::new();
    // Without a fit, the message names a run that the grid fitting most runs (at the largest
    // unit among equals) leaves out.
    let mut best_misfit: Option<(usize, f64, Misfit)> = None;
    for unit in candidate_units(runs) {
        let result = read_at(runs, unit);
        match result {
            Ok(r) => readings.push(r),
            Err((fits, misfit)) => {
                if best_misfit
                    .as_ref()
                    .is_none_or(|(f, u, _)| fits > *f || (fits == *f && unit > *u))
                {
                    best_misfit = Some((fits, unit, misfit));
                }
            }
        }
    }
    if readings.is_empty() {
        return Err(best_misfit
            .map(|(_, _, m)| m)
            .unwrap_or_else(|| Misfit::no_unit(&runs[0])));
    }
    // The border seen between layers is the border between bricks.
    let mut hinted = false;
    if let Some(seen) = border_seen {
        let matching = |r: &Reading| (r.border - seen).abs() <= BORDER_AGREEMENT_PX;
        if readings.iter().any(matching) {
            readings.retain(matching);
            hinted = true;
        }
    }
    // A reading at a whole fraction of another's unit with the same border only cuts that
    // one's bricks in pieces with no border between them: keep the coarser.
    readings.sort_by(|a, b| b.unit.total_cmp(&a.unit));
    let mut distinct: Vec<Reading> = Vec::new();
    for r in readings {
        let finer = |k: &Reading| {
            let ratio = k.unit / r.unit;
            ratio > 1.5
                && (ratio - ratio.round()).abs() < 0.02 * ratio
                && (k.border - r.border).abs() <= BORDER_AGREEMENT_PX
        };
        if !distinct.iter().any(|k| k.places == r.places || finer(k)) {
            distinct.push(r);
        }
    }
    // Only readings that fit about as well as the best are explanations at all.
    let closest = distinct
        .iter()
        .map(|r| r.residual)
        .fold(f64::INFINITY, f64::min);
    distinct.retain(|r| r.residual <= closest + FIT_SLACK_PX);
    // The fewest bricks explain the drawing best ("R R" with a border, not "RRRR . RRRR"
    // with none); of different walls with as few, one that fits clearly better wins.
    let bricks = |r: &Reading| -> u64 {
        runs.iter()
            .zip(&r.places)
            .map(|(run, &(_, n))| u64::from(n / run.kind.units()))
            .sum()
    };
    let fewest = distinct.iter().map(bricks).min().expect("some reading");
    let (mut best, others): (Vec<Reading>, Vec<Reading>) =
        distinct.into_iter().partition(|r| bricks(r) == fewest);
    best.sort_by(|a, b| a.residual.total_cmp(&b.residual));
    let ambiguous = |a: &Reading, b: &Reading| {
        let differs = (0..runs.len())
            .find(|&i| a.places[i] != b.places[i])
            .unwrap_or(0);
        Misfit::layout(
            &runs[differs],
            format!(
                "ambiguous drawing: {:.1} and {:.1} px per 0.30 m fit equally well and place \
                 this {} brick differently; draw the borders darker than the background, or \
                 add a layer",
                a.unit, b.unit, runs[differs].kind
            ),
        )
    };
    if best.len() > 1 && best[0].residual + CLEARLY_BETTER_PX >= best[1].residual {
        return Err(ambiguous(&best[0], &best[1]));
    }
    let chosen = best.remove(0);
    // A thick border explains gaps that whole units with thin borders explain as well; with
    // no border seen between layers to tell, the drawing is ambiguous.
    let thin = |r: &Reading| r.border <= THIN_BORDER_SHARE * r.unit;
    if !hinted && !thin(&chosen) {
        if let Some(other) = others.iter().find(|r| thin(r)) {
            return Err(ambiguous(&chosen, other));
        }
    }
    Ok(chosen)
}

/// Units proposed by the distances between left edges and between right edges of
/// neighbouring runs (each a whole number of units whatever the border), divided by 1, 2, …;
/// with no such distance, by the narrowest run's width over its colour's length.
fn candidate_units(runs: &[Run]) -> Vec<f64> {
    let mut distances = Vec::new();
    let mut by_position: Vec<&Run> = runs.iter().collect();
    by_position.sort_by(|a, b| a.left.total_cmp(&b.left));
    for pair in by_position.windows(2) {
        let d = pair[1].left - pair[0].left;
        if d >= MIN_UNIT_PX / 2.0 {
            distances.push(d);
        }
    }
    by_position.sort_by(|a, b| a.right.total_cmp(&b.right));
    for pair in by_position.windows(2) {
        let d = pair[1].right - pair[0].right;
        if d >= MIN_UNIT_PX / 2.0 {
            distances.push(d);
        }
    }
    distances.sort_by(f64::total_cmp);
    distances.dedup_by(|a, b| (*a - *b).abs() < 0.5);
    let mut units = Vec::new();
    for &d in distances.iter().take(MAX_DISTANCES) {
        for m in 1..=MAX_DIVISIONS {
            let u = d / m as f64;
            if u < MIN_UNIT_PX {
                break;
            }
            units.push(u);
        }
    }
    let narrowest = runs
        .iter()
        .min_by(|a, b| {
            (a.width() / f64::from(a.kind.units()))
                .total_cmp(&(b.width() / f64::from(b.kind.units())))
        })
        .expect("at least one run");
    units.push(narrowest.width() / f64::from(narrowest.kind.units()));
    units.sort_by(f64::total_cmp);
    units.dedup_by(|a, b| (*a - *b).abs() < 0.005 * *b);
    units
}

/// Reads every run's place at about `unit` px per unit: the border is the circular mean of
/// what each run lacks of a whole unit, grid lines are each run's left edge minus half a
/// border and right edge plus half a border, and unit and offset are refitted to them by
/// least squares. On failure, how many runs fitted and the first that did not.
fn read_at(runs: &[Run], unit: f64) -> Result<Reading, (usize, Misfit)> {
    // With few runs the border is poorly determined (it trades off against the unit); a
    // drawing with no border is tried as well before giving up.
    read_with(runs, unit, None).or_else(|e| read_with(runs, unit, Some(0.0)).map_err(|_| e))
}

/// [`read_at`] with the border fitted, or fixed at `border`.
fn read_with(
    runs: &[Run],
    unit: f64,
    fixed_border: Option<f64>,
) -> Result<Reading, (usize, Misfit)> {
    let border = fixed_border.unwrap_or_else(|| circular_border(runs, unit));
    // Grid lines in order along the wall, numbered by rounding the step from the last one.
    let mut lines: Vec<(f64, usize, bool)> = Vec::with_capacity(2 * runs.len());
    for (i, r) in runs.iter().enumerate() {
        lines.push((r.left - border / 2.0, i, false));
        lines.push((r.right + border / 2.0, i, true));
    }
    lines.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut number = vec![0i64; lines.len()];
    for k in 1..lines.len() {
        number[k] = number[k - 1] + ((lines[k].0 - lines[k - 1].0) / unit).round() as i64;
    }
    // The edges measured: a left edge is its grid line plus half a border, a right edge its
    // grid line minus half a border.
    let edges: Vec<(f64, i64, f64)> = lines
        .iter()
        .zip(&number)
        .map(|(&(_, i, right), &k)| {
            let r = &runs[i];
            match (right, r.blended) {
                (true, (_, true)) | (false, (true, _)) => {
                    (if right { r.right } else { r.left }, k, 0.0)
                }
                (true, _) => (r.right, k, -0.5),
                (false, _) => (r.left, k, 0.5),
            }
        })
        .collect();
    let guess = Grid {
        offset: lines[0].0,
        unit,
        border,
    };
    let mut grid = fit_edges(&edges, |_| true, fixed_border).unwrap_or(guess);
    // Once more without the edges far off it, so that one misdrawn brick does not tilt it.
    let near = |k: usize| grid.off(edges[k]) <= tolerance(grid.unit);
    if let Some(refit) = fit_edges(&edges, near, fixed_border) {
        grid = refit;
    }
    let Grid {
        offset,
        unit,
        border,
    } = grid;
    if unit < MIN_UNIT_PX {
        return Err((0, Misfit::no_unit(&runs[0])));
    }
    let tol = tolerance(unit);
    if border > MAX_BORDER_SHARE * unit || border < -tol {
        return Err((0, Misfit::no_unit(&runs[0])));
    }
    let border = border.max(0.0);
    let mut places = vec![(0i64, 0u32); runs.len()];
    let mut ends = vec![0i64; runs.len()];
    let mut off = vec![0f64; runs.len()];
    for (k, &(_, i, right)) in lines.iter().enumerate() {
        off[i] = off[i].max(grid.off(edges[k]));
        if right {
            ends[i] = number[k];
        } else {
            places[i].0 = number[k];
        }
    }
    // Every run must sit on the grid and be a whole number of its colour's length.
    let mut first_misfit = None;
    let mut fits: usize = 0;
    for (i, r) in runs.iter().enumerate() {
        let n = ends[i] - places[i].0;
        let length = i64::from(r.kind.units());
        let misfit = if off[i] > tol {
            Some(Misfit::layout(
                r,
                format!(
                    "this {} brick's edge is {:.2} units off the 0.30 m grid ({unit:.1} px per \
                     unit): bricks and gaps must be whole units",
                    r.kind,
                    off[i] / unit
                ),
            ))
        } else if n < length
            || n % length != 0
            || !seams_show_the_border(r, places[i].0, n, length, (offset, unit), border)
        {
            Some(Misfit::length(r, unit, (r.width() + border) / unit))
        } else {
            None
        };
        match misfit {
            None => {
                places[i].1 = n as u32;
                fits += 1;
            }
            Some(m) => {
                first_misfit.get_or_insert(m);
            }
        }
    }
    // Bricks that touch show the border between them.
    let mut order: Vec<usize> = (0..runs.len()).collect();
    order.sort_by_key(|&i| (runs[i].layer, places[i].0));
    for w in order.windows(2) {
        let (i, j) = (w[0], w[1]);
        let touching =
            runs[i].layer == runs[j].layer && ends[i] == places[j].0 && !runs[j].blended.0;
        if touching && (runs[j].left - runs[i].right - border).abs() > GAP_AGREEMENT_PX {
            first_misfit.get_or_insert(Misfit::layout(
                &runs[j],
                format!(
                    "this {} brick touches the brick before it across {:.1} px, but borders \
                     elsewhere are {border:.1} px",
                    runs[j].kind,
                    runs[j].left - runs[i].right
                ),
            ));
            fits = fits.saturating_sub(1);
        }
    }
    if let Some(m) = first_misfit {
        return Err((fits, m));
    }
    let first = places.iter().map(|p| p.0).min().unwrap_or(0);
    for p in &mut places {
        p.0 -= first;
    }
    Ok(Reading {
        unit,
        border,
        places,
        residual: off.iter().copied().fold(0.0, f64::max),
    })
}

/// Whether a run read as several bricks shows the border between them: at each seam, the
/// colour it lacks adds up to the border's width (within [`GAP_AGREEMENT_PX`]). A run of one
/// brick has no seam.
fn seams_show_the_border(
    run: &Run,
    first: i64,
    units: i64,
    length: i64,
    (offset, unit): (f64, f64),
    border: f64,
) -> bool {
    (1..units / length).all(|k| {
        let seam = offset + (first + k * length) as f64 * unit - run.first_column as f64;
        let from = (seam - EDGE_REACH as f64).round().max(0.0) as usize;
        let to = ((seam + EDGE_REACH as f64).round().max(0.0) as usize).min(run.coverage.len());
        let lacking: f64 = run.coverage[from.min(to)..to]
            .iter()
            .map(|&c| 1.0 - f64::from(c))
            .sum();
        (lacking - border).abs() <= GAP_AGREEMENT_PX
    })
}

/// The border that makes every run's width plus the border a whole number of units: the
/// circular mean of `−width mod unit`, in (−0.25, 0.75] units.
fn circular_border(runs: &[Run], unit: f64) -> f64 {
    let (mut s, mut c) = (0.0, 0.0);
    for r in runs {
        let angle = -std::f64::consts::TAU * r.width() / unit;
        s += angle.sin();
        c += angle.cos();
    }
    let mut border = s.atan2(c) / std::f64::consts::TAU * unit;
    if border <= -0.25 * unit {
        border += unit;
    }
    if border > 0.75 * unit {
        border -= unit;
    }
    border
}

/// A grid of whole units: grid line `k` is at `offset + k · unit` (px), and the border
/// (px) is centred on it.
#[derive(Clone, Copy, Debug)]
struct Grid {
    offset: f64,
    unit: f64,
    border: f64,
}

impl Grid {
    /// How far an edge `(position, grid line, side)` is from where this grid puts it; `side`
    /// is +½ for a left edge and −½ for a right edge.
    fn off(&self, (position, k, side): (f64, i64, f64)) -> f64 {
        (position - self.offset - k as f64 * self.unit - side * self.border).abs()
    }
}

/// Offset, unit and border by least squares over the edges `keep` keeps, or offset and unit
/// alone with the border fixed (`None` when the edges do not determine them). A border
/// cannot be negative: where the free fit says so, the best fit has none.
fn fit_edges(
    edges: &[(f64, i64, f64)],
    keep: impl Fn(usize) -> bool,
    fixed_border: Option<f64>,
) -> Option<Grid> {
    // Normal equations of position = offset + k · unit + side · border.
    let mut ata = [[0f64; 3]; 3];
    let mut aty = [0f64; 3];
    for (i, &(position, k, side)) in edges.iter().enumerate() {
        if !keep(i) {
            continue;
        }
        let row = [1.0, k as f64, side];
        let y = position - side * fixed_border.unwrap_or(0.0);
        for a in 0..3 {
            for b in 0..3 {
                ata[a][b] += row[a] * row[b];
            }
            aty[a] += row[a] * y;
        }
    }
    // Offset and unit with the border given.
    let two = |border: f64| {
        let (n, sk, skk) = (ata[0][0], ata[0][1], ata[1][1]);
        let d = n * skk - sk * sk;
        (d.abs() >= 1e-9).then(|| Grid {
            offset: (aty[0] * skk - sk * aty[1]) / d,
            unit: (n * aty[1] - sk * aty[0]) / d,
            border,
        })
    };
    if let Some(border) = fixed_border {
        return two(border);
    }
    let det = |m: &[[f64; 3]; 3]| {
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    };
    let d = det(&ata);
    if d.abs() < 1e-9 {
        return None;
    }
    // Cramer's rule.
    let solve = |column: usize| {
        let mut m = ata;
        for (r, row) in m.iter_mut().enumerate() {
            row[column] = aty[r];
        }
        det(&m) / d
    };
    let border = solve(2);
    if border < 0.0 {
        return two(0.0);
    }
    Some(Grid {
        offset: solve(0),
        unit: solve(1),
        border,
    })
}

/// A brick found in the image: layer (top = 0), colour, first unit and a pixel inside it.
#[derive(Clone, Copy, Debug)]
struct Found {
    layer: usize,
    kind: BrickType,
    x: u32,
    pixel: (u32, u32),
}

/// Step 5: a run `k` times its colour's length is `k` bricks, side by side.
fn cut_bricks(runs: &[Run], reading: &Reading) -> Vec<Found> {
    let mut found = Vec::new();
    for (r, &(x, n)) in runs.iter().zip(&reading.places) {
        let length = r.kind.units();
        for k in 0..n / length {
            let first = x as u32 + k * length;
            let middle = r.left - reading.border / 2.0
                + (f64::from(k * length) + f64::from(length) / 2.0) * reading.unit;
            found.push(Found {
                layer: r.layer,
                kind: r.kind,
                x: first,
                pixel: (middle.max(0.0) as u32, r.pixel.1),
            });
        }
    }
    found
}

/// Step 6: levels (the bottom layer is level 1), labels, segments and footprints.
fn assemble(name: &str, found: Vec<Found>) -> Result<Wall, WallError> {
    let layers = found.iter().map(|f| f.layer).max().unwrap_or(0) + 1;
    let level = |f: &Found| (layers - f.layer) as u32;
    let mut placed = found;
    placed.sort_by_key(|f| (level(f), f.x));
    let width = placed
        .iter()
        .map(|f| f.x + f.kind.units())
        .max()
        .unwrap_or(0) as usize;
    let mut used = vec![false; width];
    for f in &placed {
        for u in f.x..f.x + f.kind.units() {
            used[u as usize] = true;
        }
    }
    // segment_of[u] = 1 + number of empty stretches left of column u.
    let mut segment_of = vec![1u32; width];
    let mut segment = 1;
    for u in 1..width {
        if used[u] && !used[u - 1] {
            segment += 1;
        }
        segment_of[u] = segment;
    }
    let mut per_level: BTreeMap<u32, usize> = BTreeMap::new();
    for f in &placed {
        *per_level.entry(level(f)).or_default() += 1;
    }
    let base = label_base(per_level.values().copied().max().unwrap_or(0));
    let mut position = 0;
    let mut current = 0;
    let mut bricks = Vec::with_capacity(placed.len());
    for f in &placed {
        let l = level(f);
        if l != current {
            current = l;
            position = 0;
        }
        position += 1;
        bricks.push(Brick {
            label: base * l + position,
            kind: f.kind,
            level: l,
            segment: segment_of[f.x as usize],
            footprint: Footprint {
                x0: f64::from(f.x) * UNIT_LENGTH,
                x1: f64::from(f.x + f.kind.units()) * UNIT_LENGTH,
                y0: 0.0,
                y1: BRICK_DEPTH,
            },
            origin: Origin::Pixel(f.pixel.0, f.pixel.1),
        });
    }
    Wall::from_bricks(name, bricks)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// PNG bytes of `img` in any of the `image` crate's colour types.
    fn encode(img: &image::DynamicImage) -> Vec<u8> {
        let mut out = std::io::Cursor::new(Vec::new());
        img.write_to(&mut out, image::ImageFormat::Png).unwrap();
        out.into_inner()
    }

    #[test]
    fn every_png_colour_type_decodes_to_the_same_rgb() {
        let rgb = RgbImage::from_fn(7, 5, |x, y| {
            image::Rgb([(40 * x) as u8, (50 * y) as u8, (13 * x * y) as u8])
        });
        let dynamic = image::DynamicImage::ImageRgb8(rgb.clone());
        let close = |a: &RgbImage, b: &RgbImage| {
            a.dimensions() == b.dimensions()
                && a.as_raw()
                    .iter()
                    .zip(b.as_raw())
                    .all(|(x, y)| x.abs_diff(*y) <= 1)
        };
        for img in [
            dynamic.clone(),
            image::DynamicImage::ImageRgba8(dynamic.to_rgba8()),
            image::DynamicImage::ImageRgb16(dynamic.to_rgb16()),
            image::DynamicImage::ImageRgba16(dynamic.to_rgba16()),
            image::DynamicImage::ImageLuma8(dynamic.to_luma8()),
            image::DynamicImage::ImageLumaA8(dynamic.to_luma_alpha8()),
            image::DynamicImage::ImageLuma16(dynamic.to_luma16()),
        ] {
            let decoded = decode_rgb(&encode(&img)).unwrap();
            assert!(close(&decoded, &img.to_rgb8()), "{:?}", img.color());
        }
        // A palette image, as paint programs save small drawings.
        let mut bytes = Vec::new();
        {
            let mut encoder = png::Encoder::new(&mut bytes, 3, 1);
            encoder.set_color(png::ColorType::Indexed);
            encoder.set_palette(vec![255, 0, 0, 0, 255, 0, 0, 0, 255]);
            let mut writer = encoder.write_header().unwrap();
            writer.write_image_data(&[2, 1, 0]).unwrap();
        }
        let decoded = decode_rgb(&bytes).unwrap();
        assert_eq!(decoded.as_raw(), &vec![0, 0, 255, 0, 255, 0, 255, 0, 0]);
        assert!(decode_rgb(b"not a png").is_err());
    }

    fn ambiguous(fit: Result<Reading, Misfit>) -> bool {
        matches!(fit, Err(Misfit { kind: WallErrorKind::ImageLayout { reason }, .. }) if reason.contains("ambiguous"))
    }

    /// A run drawn as a flat block of colour from `left` to `right`.
    fn run(layer: usize, kind: BrickType, left: f64, right: f64) -> Run {
        let first_column = left.floor() as usize;
        Run {
            layer,
            kind,
            left,
            right,
            pixel: (left as u32, 0),
            blended: (false, false),
            first_column,
            coverage: (first_column..right.ceil() as usize)
                .map(|x| {
                    let x = x as f64;
                    ((x + 1.0).min(right) - x.max(left)) as f32
                })
                .collect(),
        }
    }

    #[test]
    fn blended_pixels_keep_their_colour() {
        let red = [235u8, 20, 20];
        let with = |other: u8, share: f32| {
            red.map(|c| (share * f32::from(c) + (1.0 - share) * f32::from(other)) as u8)
        };
        for other in [0, 128, 255] {
            let p = with(other, 0.5);
            assert_eq!(
                classify_pixel(p).map(|c| c.0),
                Some(BrickType::Red),
                "{p:?}"
            );
        }
        // Greys, white, black and pale paper are nothing.
        for p in [[255, 255, 255], [0, 0, 0], [128, 128, 128], [245, 235, 215]] {
            assert_eq!(classify_pixel(p), None, "{p:?}");
        }
        assert_eq!(
            classify_pixel([255, 165, 0]).map(|c| c.0),
            Some(BrickType::Orange)
        );
    }

    #[test]
    fn rows_differ_only_by_a_run_of_colour_not_by_a_flickering_edge() {
        let r = |start, end| Span {
            kind: BrickType::Red,
            start,
            end,
        };
        let g = |start, end| Span {
            kind: BrickType::Green,
            start,
            end,
        };
        // Edges moved by two pixels, or two runs joined across a thin border: the same row.
        assert!(!rows_differ(&[r(0, 10), r(12, 22)], &[r(0, 22)]));
        assert!(!rows_differ(&[r(2, 10)], &[r(0, 11)]));
        // A red that became green, or a brick that appeared: a new layer.
        assert!(rows_differ(&[r(0, 10)], &[g(0, 10)]));
        assert!(rows_differ(&[r(0, 10)], &[r(0, 10), r(20, 23)]));
    }

    #[test]
    fn the_grid_comes_from_the_lengths_not_the_layer_height() {
        // R G B at 10 px per unit with a 2 px border: colour widths 8, 18, 38.
        let runs = [
            run(0, BrickType::Red, 1.0, 9.0),
            run(0, BrickType::Green, 11.0, 29.0),
            run(0, BrickType::Blue, 31.0, 69.0),
        ];
        let reading = fit_grid(&runs, None).unwrap();
        assert!((reading.unit - 10.0).abs() < 1e-6, "{reading:?}");
        assert!((reading.border - 2.0).abs() < 1e-6, "{reading:?}");
        assert_eq!(reading.places, vec![(0, 1), (1, 2), (3, 4)]);
    }

    #[test]
    fn a_run_twice_its_colours_length_is_two_bricks() {
        // R R drawn touching with no border, and a lone red two units on: 20 px, then 10 px.
        let runs = [
            run(0, BrickType::Red, 0.0, 20.0),
            run(0, BrickType::Red, 40.0, 50.0),
        ];
        // A thick-bordered reading (one red at 35 px per unit with a 15 px border) would need
        // the two runs to be as long as each other; it does not fit.
        let reading = fit_grid(&runs, None).unwrap();
        assert_eq!(reading.places, vec![(0, 2), (4, 1)]);
        assert_eq!(reading.border, 0.0);
        let found = cut_bricks(&runs, &reading);
        assert_eq!(found.iter().map(|f| f.x).collect::<Vec<_>>(), vec![0, 1, 4]);
    }

    #[test]
    fn equal_lone_bricks_need_the_border_seen_between_layers() {
        // Two reds 5 units apart with an invisible 3 px border at 10 px per unit: 4 or 5
        // units apart at other units and borders fit as well.
        let runs = [
            run(0, BrickType::Red, 1.5, 8.5),
            run(0, BrickType::Red, 51.5, 58.5),
        ];
        assert!(ambiguous(fit_grid(&runs, None)));
        let reading = fit_grid(&runs, Some(3.0)).unwrap();
        assert_eq!(reading.places, vec![(0, 1), (5, 1)]);
    }

    #[test]
    fn a_brick_of_the_wrong_length_is_named() {
        // A red as long as a green beside a green, a blue and a red.
        let runs = [
            run(0, BrickType::Red, 1.0, 9.0),
            run(0, BrickType::Green, 11.0, 29.0),
            run(0, BrickType::Blue, 31.0, 69.0),
            run(0, BrickType::Red, 71.0, 84.0),
        ];
        let misfit = fit_grid(&runs, None).unwrap_err();
        assert_eq!(misfit.pixel, (71, 0), "{misfit:?}");
    }

    #[test]
    fn distant_bricks_stay_on_the_grid() {
        // Reds every other unit at 9.7 px per unit, 200 of them, with a 1 px border.
        let runs: Vec<Run> = (0..200)
            .map(|i| {
                let x = 2.0 * 9.7 * f64::from(i);
                run(0, BrickType::Red, x + 0.5, x + 9.2)
            })
            .collect();
        let reading = fit_grid(&runs, Some(1.0)).unwrap();
        let expected: Vec<(i64, u32)> = (0..200).map(|i| (2 * i, 1)).collect();
        assert_eq!(reading.places, expected);
    }
}
