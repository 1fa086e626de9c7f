//! Robots and goals as blobs of their colour, and where each stands on the floor.
//!
//! A blob is an 8-connected set of pixels of one class. Within one view the robots are alike
//! and so are the goals, so blob sizes are judged against the median blob of their kind: a
//! small piece next to a blob (a highlight or a shaded side cut it off) joins it, a speck is
//! noise, a blob far larger than the median is several robots touching, and a mid-sized blob
//! alone is refused.
//!
//! Where a robot stands: under a perspective camera a robot's top appears farther from the
//! nadir (the point under the camera) than its base, so its blob, mapped to the floor, is
//! its footprint swept away from the nadir: longer along that direction than across by the
//! lean, and its centroid half the lean beyond the footprint's centre (the footprint's width
//! is the blob's across, its top's, a little wider for a tall robot close to the camera). The
//! centre is then the centroid less half the lean. Both extents leave out
//! [`SPREAD_TAIL`] of the pixels at each end, and the centroid averages every pixel, so a
//! few stray pixels (a speck of the shadow's rim, a highlight cut off) move it little; until
//! issue #29's tenth round the near end and the width were the blob's extremes, and a robot's
//! centre was off by up to 0.38 cell on the rendered families (0.25 since, with the 99th
//! percentile from 0.16 to 0.10). Goals are flat: their centre is the blob's centroid on the
//! floor.

use super::homography::{Homography, Point};

/// One blob, in image pixels.
#[derive(Clone, Debug, Default)]
pub struct Blob {
    /// Its pixels (x, y).
    pub pixels: Vec<(u32, u32)>,
    /// Bounding box: min x, min y, max x, max y.
    pub bbox: (u32, u32, u32, u32),
}

/// The eight neighbours of a pixel.
pub const NEIGHBOURS: [(i64, i64); 8] = [
    (-1, -1),
    (0, -1),
    (1, -1),
    (-1, 0),
    (1, 0),
    (-1, 1),
    (0, 1),
    (1, 1),
];

impl Blob {
    /// Sets the class of every pixel of the blob in `classes` (rows of `width` pixels).
    pub fn paint(&self, classes: &mut [u8], width: usize, class: u8) {
        for &(x, y) in &self.pixels {
            classes[y as usize * width + x as usize] = class;
        }
    }

    /// How elongated the blob is: the square root of the ratio of its pixels' second moments
    /// along their principal axes, each pixel a unit square (1 for a disc, a square or a
    /// single pixel, 2 for a bar twice as long as wide, its length for a line one pixel wide;
    /// infinite for no pixel).
    pub fn elongation(&self) -> f64 {
        let n = self.pixels.len() as f64;
        if n == 0.0 {
            return f64::INFINITY;
        }
        let (mx, my) = self.pixels.iter().fold((0.0, 0.0), |(a, b), &(x, y)| {
            (a + f64::from(x) / n, b + f64::from(y) / n)
        });
        let (mut xx, mut yy, mut xy) = (0.0, 0.0, 0.0);
        for &(x, y) in &self.pixels {
            let (dx, dy) = (f64::from(x) - mx, f64::from(y) - my);
            (xx, yy, xy) = (xx + dx * dx / n, yy + dy * dy / n, xy + dx * dy / n);
        }
        // A pixel is a unit square: each axis gains 1/12 (so a single pixel is a square).
        let (xx, yy) = (xx + 1.0 / 12.0, yy + 1.0 / 12.0);
        let half = (xx + yy) / 2.0;
        let spread = (((xx - yy) / 2.0).powi(2) + xy * xy).sqrt();
        ((half + spread) / (half - spread).max(1e-12)).sqrt()
    }

    /// How solid the blob is: the share of its pixels whose four neighbours are all its own,
    /// over that share for a disc of its area. About 1 for a disc or a square, less for a
    /// ragged or thin blob, 0 for one too small to have an inside (since issue #29's twelfth
    /// round).
    pub fn solidity(&self) -> f64 {
        let inside = self.inside() as f64;
        let area = self.pixels.len() as f64;
        let radius = (area / std::f64::consts::PI).sqrt();
        let disc = (radius - 1.0).max(0.0).powi(2) * std::f64::consts::PI / area;
        if disc <= 0.0 {
            return 0.0;
        }
        inside / area / disc
    }

    /// How many of its pixels have all four neighbours in the blob: on a map of its bounding
    /// box, or, for a sparse blob in a large box, by searching its sorted pixels.
    fn inside(&self) -> usize {
        if self.pixels.is_empty() {
            return 0;
        }
        let (x0, y0, x1, y1) = self.bbox;
        let (bw, bh) = ((x1 - x0) as usize + 1, (y1 - y0) as usize + 1);
        if bw.saturating_mul(bh) <= 16 * self.pixels.len() + 4096 {
            let mut has = vec![false; bw * bh];
            let at = |x: u32, y: u32| (y - y0) as usize * bw + (x - x0) as usize;
            for &(x, y) in &self.pixels {
                has[at(x, y)] = true;
            }
            // A pixel on the box's edge has a neighbour outside it.
            self.pixels
                .iter()
                .filter(|&&(x, y)| {
                    x > x0
                        && x < x1
                        && y > y0
                        && y < y1
                        && has[at(x - 1, y)]
                        && has[at(x + 1, y)]
                        && has[at(x, y - 1)]
                        && has[at(x, y + 1)]
                })
                .count()
        } else {
            self.inside_sorted()
        }
    }

    /// [`Blob::inside`] by searching the sorted pixels.
    fn inside_sorted(&self) -> usize {
        let mut sorted: Vec<(u32, u32)> = self.pixels.iter().map(|&(x, y)| (y, x)).collect();
        sorted.sort_unstable();
        let has = |p: (u32, u32)| sorted.binary_search(&p).is_ok();
        self.pixels
            .iter()
            .filter(|&&(x, y)| {
                x > 0
                    && y > 0
                    && has((y, x - 1))
                    && has((y, x + 1))
                    && has((y - 1, x))
                    && has((y + 1, x))
            })
            .count()
    }

    /// The blob of pixels given by index (row-major, `width` pixels a row).
    pub fn from_indices(indices: &[usize], width: usize) -> Blob {
        Blob::from_pixels(
            indices
                .iter()
                .map(|&i| {
                    let (x, y) = column_row(i, width);
                    (x as u32, y as u32)
                })
                .collect(),
        )
    }

    /// The blob of these pixels (x, y), its bounding box found.
    pub fn from_pixels(pixels: Vec<(u32, u32)>) -> Blob {
        let bbox = pixels
            .iter()
            .fold((u32::MAX, u32::MAX, 0, 0), |b, &(x, y)| {
                (b.0.min(x), b.1.min(y), b.2.max(x), b.3.max(y))
            });
        Blob { pixels, bbox }
    }

    /// Pixel count.
    pub fn area(&self) -> usize {
        self.pixels.len()
    }

    /// Mean pixel centre.
    pub fn centroid(&self) -> Point {
        let n = self.pixels.len().max(1) as f64;
        let (sx, sy) = self.pixels.iter().fold((0.0, 0.0), |(a, b), &(x, y)| {
            (a + f64::from(x) + 0.5, b + f64::from(y) + 0.5)
        });
        (sx / n, sy / n)
    }

    fn gap(&self, other: &Blob) -> u32 {
        let dx = if other.bbox.0 > self.bbox.2 {
            other.bbox.0 - self.bbox.2
        } else {
            self.bbox.0.saturating_sub(other.bbox.2)
        };
        let dy = if other.bbox.1 > self.bbox.3 {
            other.bbox.1 - self.bbox.3
        } else {
            self.bbox.1.saturating_sub(other.bbox.3)
        };
        dx.max(dy)
    }
}

/// The share of the pixels around `blob` (within [`RING`] pixels of it, inside the image, not
/// in it) whose class is `class` (the high bit ignored).
pub fn ring_share(blob: &Blob, classes: &[u8], width: usize, class: u8) -> f64 {
    let height = classes.len() / width.max(1);
    if blob.pixels.is_empty() || height == 0 {
        return 0.0;
    }
    let r = RING as usize;
    let x0 = (blob.bbox.0 as usize).saturating_sub(r);
    let y0 = (blob.bbox.1 as usize).saturating_sub(r);
    let x1 = (blob.bbox.2 as usize + r).min(width - 1);
    let y1 = (blob.bbox.3 as usize + r).min(height - 1);
    let (bw, bh) = (x1 - x0 + 1, y1 - y0 + 1);
    // 0: away, 1: around, 2: in the blob.
    let mut mask = vec![0u8; bw * bh];
    for &(x, y) in &blob.pixels {
        let (x, y) = (x as usize, y as usize);
        for ny in y.saturating_sub(r).max(y0)..=(y + r).min(y1) {
            for nx in x.saturating_sub(r).max(x0)..=(x + r).min(x1) {
                let m = &mut mask[(ny - y0) * bw + nx - x0];
                *m = (*m).max(1);
            }
        }
    }
    for &(x, y) in &blob.pixels {
        mask[(y as usize - y0) * bw + x as usize - x0] = 2;
    }
    let (mut around, mut hit) = (0u32, 0u32);
    for yy in 0..bh {
        for xx in 0..bw {
            if mask[yy * bw + xx] == 1 {
                around += 1;
                hit += u32::from(classes[(y0 + yy) * width + x0 + xx] & 0x7f == class);
            }
        }
    }
    if around == 0 {
        0.0
    } else {
        f64::from(hit) / f64::from(around)
    }
}

/// The largest 8-connected region of pixels of class `class` that touches `blob` (within
/// [`RING`] pixels of it), counted up to `cap` pixels (a region that large is not counted
/// further).
pub fn largest_around(blob: &Blob, classes: &[u8], width: usize, class: u8, cap: usize) -> usize {
    let height = classes.len() / width.max(1);
    if blob.pixels.is_empty() || height == 0 {
        return 0;
    }
    let r = RING as usize;
    let mut seen = std::collections::HashSet::new();
    let mut best = 0;
    for &(x, y) in &blob.pixels {
        let (x, y) = (x as usize, y as usize);
        for sy in y.saturating_sub(r)..=(y + r).min(height - 1) {
            for sx in x.saturating_sub(r)..=(x + r).min(width - 1) {
                let start = sy * width + sx;
                if classes[start] & 0x7f != class || !seen.insert(start) {
                    continue;
                }
                let mut size = 0;
                let mut stack = vec![start];
                while let Some(i) = stack.pop() {
                    size += 1;
                    if size >= cap {
                        return cap;
                    }
                    let (px, py) = (i % width, i / width);
                    for ny in py.saturating_sub(1)..=(py + 1).min(height - 1) {
                        for nx in px.saturating_sub(1)..=(px + 1).min(width - 1) {
                            let j = ny * width + nx;
                            if classes[j] & 0x7f == class && seen.insert(j) {
                                stack.push(j);
                            }
                        }
                    }
                }
                best = best.max(size);
            }
        }
    }
    best
}

/// How far (pixels) around a blob [`ring_share`] looks.
pub const RING: u32 = 2;

/// The obstacle region a doubtful piece lies against is at least this many cells large (a
/// shelf's top or side, not a stray pixel of a mark's shading).
pub const OBSTACLE_CELLS: f64 = 0.5;
/// A doubtful piece with at least this share of the pixels around it of an obstacle lies
/// against one.
pub const AGAINST: f64 = 0.35;
/// The doubtful pieces against an obstacle near one piece (within [`NEAR_MEDIANS`] median
/// widths) together under this share of the median: what is left of a mark the obstacle
/// hides.
pub const HIDDEN_SHARE: f64 = 0.3;
/// How near (in widths of a median blob: the square root of its area) pieces count as one.
pub const NEAR_MEDIANS: f64 = 1.5;

/// Which doubtful pieces can be set aside as what an obstacle leaves: a stray of its edge's
/// colour, or the remains of a mark it hides. Such a piece lies against an obstacle (at least
/// [`AGAINST`] of the pixels around it are obstacle pixels, of a region of at least
/// `obstacle_least` pixels: a shelf's top or side, not a mark's own stray shading), and the
/// pieces against one near it, itself included, come to less than [`HIDDEN_SHARE`] of the
/// median; pieces that add up to more may be a mark cut by an obstacle's edge and stay
/// doubtful.
///
/// Setting aside is not proof: a mark whose centre shows may still show as little as a sixth
/// of itself beside a shelf leaning over it (family E, E0034: a goal's 19 px of a median
/// 114). So the caller reads a view with pieces set aside only when it then has exactly as
/// many goals as robots: a mark wrongly set aside leaves its pair over, and the piece is
/// refused as before.
pub fn behind_obstacle(
    doubtful: &[Blob],
    median: usize,
    (classes, width): (&[u8], usize),
    obstacle_least: usize,
) -> Vec<bool> {
    let against: Vec<bool> = doubtful
        .iter()
        .map(|b| against_obstacle(b, (classes, width), obstacle_least))
        .collect();
    let reach = NEAR_MEDIANS * (median as f64).sqrt();
    let centres: Vec<Point> = doubtful.iter().map(Blob::centroid).collect();
    (0..doubtful.len())
        .map(|i| {
            against[i] && {
                let near: usize = (0..doubtful.len())
                    .filter(|&j| {
                        against[j]
                            && (centres[i].0 - centres[j].0).hypot(centres[i].1 - centres[j].1)
                                <= reach
                    })
                    .map(|j| doubtful[j].area())
                    .sum();
                (near as f64) < HIDDEN_SHARE * median as f64
            }
        })
        .collect()
}

/// Whether a piece lies against an obstacle: at least [`AGAINST`] of the pixels around it
/// are obstacle pixels, of a region of at least `obstacle_least` pixels (a shelf's top or
/// side, not a mark's own stray shading).
pub fn against_obstacle(b: &Blob, (classes, width): (&[u8], usize), obstacle_least: usize) -> bool {
    const OBSTACLE: u8 = super::colour::Class::Obstacle as u8;
    ring_share(b, classes, width, OBSTACLE) >= AGAINST
        && largest_around(b, classes, width, OBSTACLE, obstacle_least) >= obstacle_least
}

/// A mark cut by an obstacle's edge (a piece of it shows beside the top leaning over the rest)
/// is a disc of the median's area (radius r) that holds every pixel of the piece within
/// [`CUT_OUT`] r of its centre (a square's corners lie 1.25 r out) ...
pub const CUT_OUT: f64 = 1.35;
/// ... and whose pixels within [`CUT_IN`] r of its centre, but for the piece's, are at least
/// [`CUT_HIDDEN`] obstacle pixels (the top hides them).
pub const CUT_IN: f64 = 0.75;
/// See [`CUT_IN`].
pub const CUT_HIDDEN: f64 = 0.8;
/// The candidate centres are this many to r apart (at least a pixel).
pub const CUT_STEP: f64 = 0.2;

/// The whole marks a piece could be the visible part of, when an obstacle hides the rest (see
/// [`CUT_OUT`]): discs of `median` pixels, whose centres lie on a lattice [`CUT_STEP`] r apart
/// around the piece, each as a blob of the pixels within r of its centre. None when any disc
/// would leave the image. The caller reads the piece as a mark only when every such disc puts
/// the mark on the same cell.
pub fn cut_discs(piece: &Blob, median: usize, (classes, width): (&[u8], usize)) -> Vec<Blob> {
    const OBSTACLE: u8 = super::colour::Class::Obstacle as u8;
    let height = classes.len() / width.max(1);
    let r = (median.max(1) as f64 / std::f64::consts::PI).sqrt();
    if piece.pixels.is_empty() || height == 0 {
        return Vec::new();
    }
    let step = (CUT_STEP * r).max(1.0);
    let reach = CUT_OUT * r;
    let (bx0, by0, bx1, by1) = piece.bbox;
    // The piece's pixels, one flag each over its bounding box.
    let bw = (bx1 - bx0 + 1) as usize;
    let mut mask = vec![false; bw * (by1 - by0 + 1) as usize];
    for &(x, y) in &piece.pixels {
        mask[(y - by0) as usize * bw + (x - bx0) as usize] = true;
    }
    let in_piece = |x: i64, y: i64| {
        x >= i64::from(bx0)
            && y >= i64::from(by0)
            && x <= i64::from(bx1)
            && y <= i64::from(by1)
            && mask[(y - i64::from(by0)) as usize * bw + (x - i64::from(bx0)) as usize]
    };
    let (x0, y0) = (f64::from(bx0) + 0.5 - reach, f64::from(by0) + 0.5 - reach);
    let (x1, y1) = (f64::from(bx1) + 0.5 + reach, f64::from(by1) + 0.5 + reach);
    let mut out = Vec::new();
    let mut cy = y0;
    while cy <= y1 {
        let mut cx = x0;
        while cx <= x1 {
            let holds = piece
                .pixels
                .iter()
                .all(|&(x, y)| (f64::from(x) + 0.5 - cx).hypot(f64::from(y) + 0.5 - cy) <= reach);
            if holds {
                // The disc's pixels, and its inner pixels outside the piece hidden.
                let (px0, py0) = ((cx - r).floor() as i64, (cy - r).floor() as i64);
                let (px1, py1) = ((cx + r).ceil() as i64, (cy + r).ceil() as i64);
                if px0 < 0 || py0 < 0 || px1 >= width as i64 || py1 >= height as i64 {
                    return Vec::new(); // a mark the image's edge may cut
                }
                let (mut pixels, mut inner, mut hidden) = (Vec::new(), 0u32, 0u32);
                for y in py0..=py1 {
                    for x in px0..=px1 {
                        let d = (x as f64 + 0.5 - cx).hypot(y as f64 + 0.5 - cy);
                        if d > r {
                            continue;
                        }
                        pixels.push((x as u32, y as u32));
                        if d <= CUT_IN * r && !in_piece(x, y) {
                            inner += 1;
                            hidden += u32::from(
                                classes[y as usize * width + x as usize] & 0x7f == OBSTACLE,
                            );
                        }
                    }
                }
                if f64::from(hidden) >= CUT_HIDDEN * f64::from(inner) {
                    out.push(Blob::from_pixels(pixels));
                }
            }
            cx += step;
        }
        cy += step;
    }
    out
}

/// The 8-connected blobs of pixels whose class is `class`, in row-major order of their first
/// pixel. Visited pixels get their high bit set in `classes` (cleared again at the end).
pub fn find(classes: &mut [u8], width: usize, class: u8) -> Vec<Blob> {
    const SEEN: u8 = 0x80;
    let mut out = Vec::new();
    let mut stack = Vec::new();
    let mut next = 0;
    while let Some(start) = next_of(classes, next, class) {
        next = start + 1;
        out.push(grow(classes, width, class, start, &mut stack).0);
    }
    // Clear the marks: pixel by pixel when the blobs are few, else in one pass.
    let marked: usize = out.iter().map(Blob::area).sum();
    if marked < classes.len() / 16 {
        for b in &out {
            for &(x, y) in &b.pixels {
                classes[y as usize * width + x as usize] &= !SEEN;
            }
        }
    } else {
        for c in classes.iter_mut() {
            *c &= !SEEN;
        }
    }
    out
}

/// Like [`find`], only the blobs that hold one of `seeds` (pixel indices in increasing
/// order), each grown from its first seed: the blobs are in row-major order of their first
/// pixel, as [`find`] gives them, but each blob's pixels are in another order. For a class
/// whose blobs are mostly of no interest (the obstacles' shelves), found without walking them.
pub fn find_from(classes: &mut [u8], width: usize, class: u8, seeds: &[usize]) -> Vec<Blob> {
    const SEEN: u8 = 0x80;
    let mut out: Vec<(usize, Blob)> = Vec::new();
    let mut stack = Vec::new();
    for &start in seeds {
        if classes.get(start) != Some(&class) {
            continue; // another class, or a blob already found
        }
        let (blob, first) = grow(classes, width, class, start, &mut stack);
        out.push((first, blob));
    }
    for (_, b) in &out {
        for &(x, y) in &b.pixels {
            classes[y as usize * width + x as usize] &= !SEEN;
        }
    }
    out.sort_unstable_by_key(|(first, _)| *first);
    out.into_iter().map(|(_, b)| b).collect()
}

/// The 8-connected blob of pixels of `class` grown from pixel `start` (of that class), its
/// pixels in the order walked (depth first), and its least pixel index. Its pixels get the
/// high bit set in `classes` (the caller clears them); `stack` is scratch space.
/// The blob grown from `piece` over the 8-connected pixels `faint` accepts (indices into an
/// image `width` wide and `height` high; the caller bounds them).
pub fn grow_faint(
    piece: &Blob,
    (width, height): (usize, usize),
    faint: impl Fn(usize) -> bool,
) -> Blob {
    let mut seen: std::collections::HashSet<usize> = piece
        .pixels
        .iter()
        .map(|&(x, y)| y as usize * width + x as usize)
        .collect();
    let mut stack: Vec<usize> = seen.iter().copied().collect();
    stack.sort_unstable();
    let mut pixels = piece.pixels.clone();
    while let Some(i) = stack.pop() {
        let (x, y) = (i % width, i / width);
        for (dx, dy) in NEIGHBOURS {
            let (nx, ny) = (x as i64 + dx, y as i64 + dy);
            if nx < 0 || ny < 0 || nx >= width as i64 || ny >= height as i64 {
                continue;
            }
            let j = ny as usize * width + nx as usize;
            if seen.contains(&j) || !faint(j) {
                continue;
            }
            seen.insert(j);
            pixels.push((nx as u32, ny as u32));
            stack.push(j);
        }
    }
    Blob::from_pixels(pixels)
}

fn grow(
    classes: &mut [u8],
    width: usize,
    class: u8,
    start: usize,
    stack: &mut Vec<usize>,
) -> (Blob, usize) {
    const SEEN: u8 = 0x80;
    let height = classes.len() / width.max(1);
    classes[start] |= SEEN;
    stack.push(start);
    let mut first = start;
    let mut blob = Blob {
        pixels: Vec::new(),
        bbox: (u32::MAX, u32::MAX, 0, 0),
    };
    while let Some(i) = stack.pop() {
        first = first.min(i);
        let (x, y) = column_row(i, width);
        let (px, py) = (x as u32, y as u32);
        blob.pixels.push((px, py));
        blob.bbox = (
            blob.bbox.0.min(px),
            blob.bbox.1.min(py),
            blob.bbox.2.max(px),
            blob.bbox.3.max(py),
        );
        for ny in y.saturating_sub(1)..=(y + 1).min(height - 1) {
            for nx in x.saturating_sub(1)..=(x + 1).min(width - 1) {
                let j = ny * width + nx;
                if classes[j] == class {
                    classes[j] |= SEEN;
                    stack.push(j);
                }
            }
        }
    }
    (blob, first)
}

/// The column and row of pixel `i` of an image `width` pixels wide (in 32 bits when they
/// fit: a faster division).
#[inline]
pub(crate) fn column_row(i: usize, width: usize) -> (usize, usize) {
    match (u32::try_from(i), u32::try_from(width)) {
        (Ok(i), Ok(w)) if w > 0 => ((i % w) as usize, (i / w) as usize),
        _ => (i % width, i / width),
    }
}

/// The first index from `from` on whose value is `class`: 64 values at a time (the test of
/// a block has no branch, so it runs on vector instructions), then one by one in the block
/// that holds one.
fn next_of(values: &[u8], from: usize, class: u8) -> Option<usize> {
    const BLOCK: usize = 64;
    let rest = values.get(from..)?;
    let mut blocks = rest.chunks_exact(BLOCK);
    for (k, block) in blocks.by_ref().enumerate() {
        if block.iter().fold(false, |any, &v| any | (v == class)) {
            return block
                .iter()
                .position(|&v| v == class)
                .map(|i| from + k * BLOCK + i);
        }
    }
    let tail = rest.len() - blocks.remainder().len();
    blocks
        .remainder()
        .iter()
        .position(|&v| v == class)
        .map(|i| from + tail + i)
}

/// Blobs sorted out by size against the median of their kind.
#[derive(Debug, Default)]
pub struct Sorted {
    /// The robots (or goals), each one blob.
    pub kept: Vec<Blob>,
    /// Blobs far larger than the median: several touching.
    pub merged: Vec<Blob>,
    /// Blobs too large for noise and too small for one whole robot (or goal).
    pub doubtful: Vec<Blob>,
    /// The median area of the kept blobs.
    pub median_area: usize,
}

/// The smallest blob that can be a robot or a goal, in pixels.
pub const MIN_AREA: usize = 6;
/// A blob larger than this many medians is several touching.
const MERGED: f64 = 1.7;
/// A blob smaller than this share of the median is a piece (joined to a blob next to it) or
/// noise.
const PIECE: f64 = 0.4;
/// A lone piece smaller than this share of the median is noise; larger, it is doubtful.
pub const NOISE: f64 = 0.1;
/// ... unless it is ragged, less solid than this ([`Blob::solidity`]): a shelf's rim or edge
/// read in a mark's colour, a line of specks, not a piece of a robot or a goal (K0017, L0025,
/// Q0010; issue #29's twelfth round). A mark lost so leaves the view with fewer robots than
/// goals (or the reverse), which is refused.
pub const RAGGED: f64 = 0.3;
/// A kept blob under this share of the median is a robot (or goal) partly hidden, or a
/// single one among robots touching in pairs that made the median: the reading is refused
/// when a blob of the median's size splits in two.
pub const SMALL: f64 = 0.6;
/// A piece this close (pixels, bounding boxes) to a blob joins it.
const JOIN_GAP: u32 = 2;

/// Sorts blobs by size: see the module's comment.
pub fn sort(mut blobs: Vec<Blob>) -> Sorted {
    blobs.retain(|b| b.area() >= MIN_AREA / 2);
    let mut areas: Vec<usize> = blobs
        .iter()
        .filter(|b| b.area() >= MIN_AREA && b.solidity() >= RAGGED)
        .map(Blob::area)
        .collect();
    if areas.is_empty() {
        areas = blobs
            .iter()
            .map(Blob::area)
            .filter(|&a| a >= MIN_AREA)
            .collect();
    }
    if areas.is_empty() {
        return Sorted::default();
    }
    areas.sort_unstable();
    let median = typical_area(&areas);
    let piece = |b: &Blob| (b.area() as f64) < PIECE * median as f64;
    let (mut whole, pieces): (Vec<Blob>, Vec<Blob>) = blobs.into_iter().partition(|b| !piece(b));
    let mut doubtful = Vec::new();
    for p in pieces {
        let near = whole
            .iter_mut()
            .filter(|b| b.gap(&p) <= JOIN_GAP)
            .min_by_key(|b| b.gap(&p));
        match near {
            Some(b) => {
                b.bbox = (
                    b.bbox.0.min(p.bbox.0),
                    b.bbox.1.min(p.bbox.1),
                    b.bbox.2.max(p.bbox.2),
                    b.bbox.3.max(p.bbox.3),
                );
                b.pixels.extend(p.pixels);
            }
            None if p.area() >= MIN_AREA
                && p.area() as f64 >= NOISE * median as f64
                && p.solidity() >= RAGGED =>
            {
                doubtful.push(p)
            }
            None => {}
        }
    }
    let (merged, kept): (Vec<Blob>, Vec<Blob>) = whole
        .into_iter()
        .partition(|b| b.area() as f64 > MERGED * median as f64);
    Sorted {
        kept,
        merged,
        doubtful,
        median_area: median,
    }
}

/// Blobs within this factor of each other's area are of one kind for the typical robot (see `sort`).
pub const ALIKE: usize = 2;

/// The area of the view's typical robot (or goal), from its blobs' `areas` (ascending, not
/// empty): the median of the group of blobs whose areas lie within a factor [`ALIKE`] of
/// the smallest of them that has the most blobs times their total area (the larger on a
/// tie). Robots are alike and make the bulk of their colour: a shelf of their colour, or
/// its pieces, makes a few blobs of other sizes, and specks, however many, little area.
/// Until issue #29's eleventh round this was the median of the blobs at least a quarter of
/// the largest, and one shelf of the robots' (or goals') colour made the median its own: the
/// robots were then refused as too small (16 of the 59 such refusals of families A–Q).
/// [`sort`] gives it the solid blobs' areas ([`RAGGED`]) when there are any: on a dark, noisy
/// floor the specks of a mark's colour, however ragged, outnumbered the goals and made the
/// typical area theirs (X0026, Z0008: crosses of 140 and 245 px refused as twenty goals
/// touching; issue #29's fourteenth round).
fn typical_area(areas: &[usize]) -> usize {
    let mut best = (0, 0, 0);
    let mut end = 0;
    let mut sums = vec![0usize; areas.len() + 1];
    for (i, &a) in areas.iter().enumerate() {
        sums[i + 1] = sums[i] + a;
    }
    for (start, &a) in areas.iter().enumerate() {
        end = end.max(start);
        while end < areas.len() && areas[end] <= ALIKE * a {
            end += 1;
        }
        let score = (end - start) * (sums[end] - sums[start]);
        if score >= best.2 {
            best = (start, end, score);
        }
    }
    let group = &areas[best.0..best.1];
    group[group.len() / 2]
}

/// Pixels (indices, sorted) split into their 8-connected pieces.
pub(crate) fn pieces(pixels: &[usize], width: usize, height: usize) -> Vec<Vec<usize>> {
    let mut seen = vec![false; pixels.len()];
    let mut out = Vec::new();
    let mut stack = Vec::new();
    for start in 0..pixels.len() {
        if seen[start] {
            continue;
        }
        seen[start] = true;
        stack.push(start);
        let mut piece = Vec::new();
        while let Some(k) = stack.pop() {
            let i = pixels[k];
            piece.push(i);
            let (x, y) = (i % width, i / width);
            for ny in y.saturating_sub(1)..=(y + 1).min(height - 1) {
                for nx in x.saturating_sub(1)..=(x + 1).min(width - 1) {
                    if let Ok(n) = pixels.binary_search(&(ny * width + nx)) {
                        if !seen[n] {
                            seen[n] = true;
                            stack.push(n);
                        }
                    }
                }
            }
        }
        out.push(piece);
    }
    out
}

/// A blob opened by `r` pixels (eroded by `r`, then grown back by `r` within it: what fits a
/// disc of radius about `r` is kept, strips thinner than about `2r` are not), in its
/// 8-connected pieces, largest first.
pub fn opened(blob: &Blob, r: u32) -> Vec<Blob> {
    let (x0, y0) = (blob.bbox.0 as usize, blob.bbox.1 as usize);
    let (dist, bw, bh) = chamfer(blob);
    let reach = 3 * r;
    // Grown back: chamfer distance from the core (deeper than r), within the blob.
    let mut grown = vec![u32::MAX; bw * bh];
    let mut queue = std::collections::BinaryHeap::new();
    for (i, &d) in dist.iter().enumerate() {
        if d > reach {
            grown[i] = 0;
            queue.push(std::cmp::Reverse((0u32, i)));
        }
    }
    while let Some(std::cmp::Reverse((g, i))) = queue.pop() {
        if g > grown[i] {
            continue;
        }
        let (x, y) = ((i % bw) as isize, (i / bw) as isize);
        for (dx, dy, w) in [
            (-1, -1, 4),
            (0, -1, 3),
            (1, -1, 4),
            (-1, 0, 3),
            (1, 0, 3),
            (-1, 1, 4),
            (0, 1, 3),
            (1, 1, 4),
        ] {
            let (nx, ny) = (x + dx, y + dy);
            if nx < 0 || ny < 0 || nx >= bw as isize || ny >= bh as isize {
                continue;
            }
            let j = ny as usize * bw + nx as usize;
            let ng = g + w;
            if dist[j] > 0 && ng <= reach && ng < grown[j] {
                grown[j] = ng;
                queue.push(std::cmp::Reverse((ng, j)));
            }
        }
    }
    // Indices in an image as wide as the box's right edge: ascending as the box's are.
    let width = blob.bbox.2 as usize + 1;
    let kept: Vec<usize> = (0..bw * bh)
        .filter(|&i| grown[i] != u32::MAX)
        .map(|i| (i / bw + y0) * width + i % bw + x0)
        .collect();
    let mut pieces: Vec<Blob> = pieces(&kept, width, blob.bbox.3 as usize + 1)
        .iter()
        .map(|p| Blob::from_indices(p, width))
        .collect();
    pieces.sort_by_key(|b| std::cmp::Reverse(b.area()));
    pieces
}

/// The chamfer distance (3 a step along an axis, 4 diagonally) of each pixel of a blob's
/// bounding box to the blob's outside (0 outside it), by two passes over the box (padded by
/// 0), with the box's width and height.
fn chamfer(blob: &Blob) -> (Vec<u32>, usize, usize) {
    let (x0, y0) = (blob.bbox.0 as usize, blob.bbox.1 as usize);
    let bw = blob.bbox.2 as usize - x0 + 1;
    let bh = blob.bbox.3 as usize - y0 + 1;
    let mut dist = vec![0u32; bw * bh];
    for &(x, y) in &blob.pixels {
        dist[(y as usize - y0) * bw + x as usize - x0] = u32::MAX;
    }
    let at = |d: &[u32], x: isize, y: isize| -> u32 {
        if x < 0 || y < 0 || x >= bw as isize || y >= bh as isize {
            0
        } else {
            d[y as usize * bw + x as usize]
        }
    };
    for y in 0..bh as isize {
        for x in 0..bw as isize {
            let i = y as usize * bw + x as usize;
            if dist[i] == 0 {
                continue;
            }
            let m = [(-1, -1, 4), (0, -1, 3), (1, -1, 4), (-1, 0, 3)]
                .iter()
                .map(|&(dx, dy, w)| at(&dist, x + dx, y + dy).saturating_add(w))
                .min()
                .unwrap_or(0);
            dist[i] = m.min(dist[i]);
        }
    }
    for y in (0..bh as isize).rev() {
        for x in (0..bw as isize).rev() {
            let i = y as usize * bw + x as usize;
            if dist[i] == 0 {
                continue;
            }
            let m = [(1, 1, 4), (0, 1, 3), (-1, 1, 4), (1, 0, 3)]
                .iter()
                .map(|&(dx, dy, w)| at(&dist, x + dx, y + dy).saturating_add(w))
                .min()
                .unwrap_or(0);
            dist[i] = dist[i].min(m);
        }
    }
    (dist, bw, bh)
}

/// How thick a blob is: its deepest pixel's distance to its outside, in pixels (1 for a
/// line one pixel wide).
pub fn thickness(blob: &Blob) -> f64 {
    let (dist, _, _) = chamfer(blob);
    f64::from(dist.iter().copied().max().unwrap_or(0)) / 3.0
}

/// A blob whose bounding box's diagonal, squared, is more than this many times its area is
/// a line ([`line_like`]): two to four discs touching in a row make 3.2 to 5.4.
pub const LINE_LIKE: f64 = 8.0;

/// A line is at most this share of a mark's thickness (its radius, as a disc of the median
/// area) thick.
pub const LINE_THIN: f64 = 0.75;

/// Whether a blob is a line rather than marks touching, against marks of `median` area:
/// longer, for its area, than four discs in a row ([`LINE_LIKE`]), and thinner than a mark
/// ([`LINE_THIN`]; a mark touching the line would make it a mark's thickness there). A
/// shelf's edge or rim read in a mark's colour (L0004, Q0013: 11 to 15 long, 2 to 3 px thick
/// against marks 4 px), or a line painted on the floor in it; since issue #29's twelfth round
/// such a blob that [`split`] does not separate is no mark. A mark lost so leaves fewer
/// robots than goals (or the reverse), which is refused.
pub fn line_like(blob: &Blob, median: usize) -> bool {
    let (w, h) = (
        f64::from(blob.bbox.2 - blob.bbox.0 + 1),
        f64::from(blob.bbox.3 - blob.bbox.1 + 1),
    );
    let mark = (median as f64 / std::f64::consts::PI).sqrt();
    w * w + h * h > LINE_LIKE * blob.area() as f64 && thickness(blob) < LINE_THIN * mark
}

/// A blob at most this many medians large may be one larger mark ([`one_large`]).
pub const ONE_LARGE: f64 = 2.2;
/// ... when it is at most this elongated ([`Blob::elongation`]): two discs touching are 1.9 or
/// more (two of a disc's radius apart at least, their centres), one disc 1.
pub const ROUND: f64 = 1.35;
/// ... and at least this solid ([`Blob::solidity`]): two discs joined by a neck are less.
pub const ROUND_SOLID: f64 = 0.85;

/// Whether a blob that [`split`] does not separate, against marks of `median` area, is one
/// mark larger than the typical one rather than marks touching: at most [`ONE_LARGE`] medians,
/// as round as one mark ([`ROUND`]) and as solid ([`ROUND_SOLID`]). Marks of one view are
/// alike, but a robot seen nearer the camera, a tall one's leaning side, or its shadow's edge
/// read in its colour make some twice the median (O0016's robot: 1.8 medians, 8 × 7 px); two
/// marks touching, each at least a fifth of a cell from the other, make a blob at least twice
/// as long as wide. Since issue #29's twelfth round. A view that loses a mark so, or gains one,
/// has fewer robots than goals (or the reverse), which is refused.
pub fn one_large(blob: &Blob, median: usize) -> bool {
    (blob.area() as f64) <= ONE_LARGE * median as f64
        && blob.elongation() <= ROUND
        && blob.solidity() >= ROUND_SOLID
}

/// A merged blob is split only when its area is this close (in medians) to a whole number.
pub const SPLIT_SLACK: f64 = 0.3;
/// Each piece of a split blob is within this share of the median (either way).
pub const PIECE_SPREAD: f64 = 0.4;

/// Splits a blob of several touching robots (or goals) of median area `median` into one blob
/// each, or `None` when that cannot be done with confidence.
///
/// The count is the area in medians when it is within [`SPLIT_SLACK`] of a whole number from
/// 2 to 4; else each of the two whole numbers next to it is tried, and the one that alone
/// succeeds is taken. The blob is eroded (chamfer distance to its outside) until
/// its core falls apart into exactly that many pieces, each at least a 40th of the median;
/// the cores then grow back down the depths (at each depth, breadth first from all cores at
/// once into the pixels at least that deep, in a fixed order), like a watershed. Refused: no
/// count, or two, that succeed; a core that never falls apart into that many pieces (or into
/// more first), or a piece whose area is more than [`PIECE_SPREAD`] from the median.
pub fn split(blob: &Blob, median: usize) -> Option<Vec<Blob>> {
    let ratio = blob.area() as f64 / median.max(1) as f64;
    let n = ratio.round();
    if (2.0..=4.0).contains(&n) && (ratio - n).abs() <= SPLIT_SLACK {
        return split_into(blob, median, n as usize);
    }
    // Between two counts (robots of a view differ in size with blur, perspective and their
    // shadows: F0002's two robots touching were 2.5 medians): each count from 2 to 4 next
    // to the area is tried, and the split is taken when exactly one of them succeeds (the
    // core falls apart into that many pieces, each within [`PIECE_SPREAD`] of the median;
    // since issue #29's twelfth round).
    let found: Vec<Vec<Blob>> = [ratio.floor(), ratio.ceil()]
        .into_iter()
        .filter(|n| (2.0..=4.0).contains(n))
        .filter_map(|n| split_into(blob, median, n as usize))
        .collect();
    match <[Vec<Blob>; 1]>::try_from(found) {
        Ok([one]) => Some(one),
        Err(_) => None,
    }
}

/// [`split`] into `n` blobs.
fn split_into(blob: &Blob, median: usize, n: usize) -> Option<Vec<Blob>> {
    let (x0, y0) = (blob.bbox.0 as usize, blob.bbox.1 as usize);
    let (dist, bw, bh) = chamfer(blob);
    let at = |d: &[u32], x: isize, y: isize| -> u32 {
        if x < 0 || y < 0 || x >= bw as isize || y >= bh as isize {
            0
        } else {
            d[y as usize * bw + x as usize]
        }
    };
    let dist = &dist;
    // The 8-neighbours of pixel `i` (and `i` itself) at least `t` deep, as indices.
    let deep = |i: usize, t: u32| {
        let (x, y) = ((i % bw) as isize, (i / bw) as isize);
        (-1..=1)
            .flat_map(move |dy| (-1..=1).map(move |dx| (x + dx, y + dy)))
            .filter(move |&(nx, ny)| at(dist, nx, ny) >= t)
            .map(move |(nx, ny)| ny as usize * bw + nx as usize)
    };
    let deepest = dist.iter().copied().max().unwrap_or(0);
    // At most about 64 depths are tried, so a huge blob costs O(64 × its bounding box).
    let stride = (deepest / 64).max(1) as usize;
    let min_core = (median / 40).max(1);
    let mut label = vec![0u32; bw * bh];
    let mut found = None;
    for t in (4..=deepest).step_by(stride) {
        // The cores at depth t: 8-connected pieces of the pixels at least t deep.
        label.iter_mut().for_each(|l| *l = 0);
        let mut sizes: Vec<usize> = Vec::new();
        let mut stack = Vec::new();
        for start in 0..bw * bh {
            if dist[start] < t || label[start] != 0 {
                continue;
            }
            sizes.push(0);
            let id = sizes.len() as u32;
            label[start] = id;
            stack.push(start);
            while let Some(i) = stack.pop() {
                sizes[id as usize - 1] += 1;
                for j in deep(i, t) {
                    if label[j] == 0 {
                        label[j] = id;
                        stack.push(j);
                    }
                }
            }
        }
        let big = sizes.iter().filter(|&&s| s >= min_core).count();
        if big > n {
            return None;
        }
        if big == n {
            // Drop the small cores: their pixels are grown into like any other.
            for l in label.iter_mut() {
                if *l != 0 && sizes[*l as usize - 1] < min_core {
                    *l = 0;
                }
            }
            found = Some((sizes, t));
            break;
        }
        if big == 0 {
            return None;
        }
    }
    let (sizes, level) = found?;
    // Renumber the kept cores 1..=n in order of their first pixel.
    let mut renumber = vec![0u32; sizes.len() + 1];
    let mut next = 0;
    for l in label.iter_mut() {
        if *l != 0 {
            if renumber[*l as usize] == 0 {
                next += 1;
                renumber[*l as usize] = next;
            }
            *l = renumber[*l as usize];
        }
    }
    // Grow the cores down the depths, as water rises: at each depth, breadth first from all
    // cores at once into the pixels at least that deep.
    for t in (1..level).rev().step_by(stride).chain([1]) {
        let mut queue: std::collections::VecDeque<usize> =
            (0..bw * bh).filter(|&i| label[i] != 0).collect();
        while let Some(i) = queue.pop_front() {
            for j in deep(i, t) {
                if label[j] == 0 {
                    label[j] = label[i];
                    queue.push_back(j);
                }
            }
        }
    }
    // Pixels the growth did not reach (a piece joined across a gap, see [`sort`]) join the
    // piece whose reached pixels' centroid is nearest.
    let mut sums = vec![(0.0f64, 0.0f64, 0usize); n + 1];
    for (i, &l) in label.iter().enumerate() {
        if l != 0 {
            let c = &mut sums[l as usize];
            (c.0, c.1, c.2) = (c.0 + (i % bw) as f64, c.1 + (i / bw) as f64, c.2 + 1);
        }
    }
    for &(x, y) in &blob.pixels {
        let i = (y as usize - y0) * bw + x as usize - x0;
        if label[i] == 0 {
            let (px, py) = ((i % bw) as f64, (i / bw) as f64);
            let nearest = (1..=n).filter(|&l| sums[l].2 > 0).min_by(|&a, &b| {
                let d = |l: usize| {
                    let m = sums[l].2 as f64;
                    (sums[l].0 / m - px).powi(2) + (sums[l].1 / m - py).powi(2)
                };
                d(a).total_cmp(&d(b))
            })?;
            label[i] = nearest as u32;
        }
    }
    let mut pieces = vec![
        Blob {
            pixels: Vec::new(),
            bbox: (u32::MAX, u32::MAX, 0, 0),
        };
        n
    ];
    for &(x, y) in &blob.pixels {
        let l = label[(y as usize - y0) * bw + x as usize - x0];
        let b = pieces.get_mut((l as usize).checked_sub(1)?)?;
        b.pixels.push((x, y));
        b.bbox = (
            b.bbox.0.min(x),
            b.bbox.1.min(y),
            b.bbox.2.max(x),
            b.bbox.3.max(y),
        );
    }
    let fits = |b: &Blob| (b.area() as f64 / median.max(1) as f64 - 1.0).abs() <= PIECE_SPREAD;
    pieces.iter().all(fits).then_some(pieces)
}

/// Where a standing object's footprint centre is on the floor, from its blob and the nadir
/// (see the module's comment). `px` is one pixel's size on the floor, in cells.
pub fn standing_centre(floor_points: &[Point], nadir: Option<Point>, px: f64) -> Point {
    standing_centre_scaled(floor_points, nadir, px, None)
}

/// A standing object's blob on the floor as seen from the nadir.
struct Leaning {
    centroid: Point,
    /// The unit way from the nadir to the centroid.
    way: Point,
    /// The centroid's distance from the nadir.
    dist: f64,
    /// The blob's length along the way less its width across it: its lean, for a footprint
    /// as long as wide.
    own: f64,
}

/// The blob measured from the nadir; `Err` with its centroid when nothing leans (no nadir, or
/// the nadir inside the footprint).
fn leaning(floor_points: &[Point], nadir: Option<Point>, px: f64) -> Result<Leaning, Point> {
    let n = floor_points.len().max(1) as f64;
    let centroid = floor_points
        .iter()
        .fold((0.0, 0.0), |(a, b), p| (a + p.0 / n, b + p.1 / n));
    let Some(nadir) = nadir.filter(|_| !floor_points.is_empty()) else {
        return Err(centroid);
    };
    let (dx, dy) = (centroid.0 - nadir.0, centroid.1 - nadir.1);
    let dist = (dx * dx + dy * dy).sqrt();
    let (ux, uy) = (dx / dist.max(1e-12), dy / dist.max(1e-12));
    let (vx, vy) = (-uy, ux);
    let mut along = Vec::with_capacity(floor_points.len());
    let mut across = Vec::with_capacity(floor_points.len());
    for p in floor_points {
        let (qx, qy) = (p.0 - nadir.0, p.1 - nadir.1);
        along.push(qx * ux + qy * uy);
        across.push(qx * vx + qy * vy);
    }
    let extent = |values: &mut Vec<f64>| -> f64 {
        values.sort_by(f64::total_cmp);
        let at = |q: f64| values[((values.len() - 1) as f64 * q).round() as usize];
        at(1.0 - SPREAD_TAIL) - at(SPREAD_TAIL) + px
    };
    let (length, width) = (extent(&mut along), extent(&mut across));
    // Under the camera (the nadir inside the footprint) nothing leans: the centroid it is.
    if dist < width {
        return Err(centroid);
    }
    Ok(Leaning {
        centroid,
        way: (ux, uy),
        dist,
        own: (length - width).max(0.0),
    })
}

/// The lean of a standing object's blob per cell of its distance from the nadir, as
/// [`standing_centre`] measures it; `None` without a nadir or under the camera.
pub fn lean_per_distance(floor_points: &[Point], nadir: Option<Point>, px: f64) -> Option<f64> {
    leaning(floor_points, nadir, px)
        .ok()
        .map(|l| l.own / l.dist)
}

/// A robot's lean may be this many times the view's (see [`view_lean`]), or this share of it.
pub const LEAN_SPREAD: f64 = 2.0;

/// The view's lean per cell of distance from the nadir: the median of its robots' (each
/// [`lean_per_distance`]), given at least three that lean. A top of height z under a camera
/// at height H is its base scaled by H / (H − z) about the nadir, so robots of one height
/// lean by one factor of their distance: a robot longer than wide along the way from the
/// nadir (a capsule, a box turned that way) is not taken to lean by its length, nor one
/// longer across it to stand upright.
pub fn view_lean(robots: &[Vec<Point>], nadir: Option<Point>, px: f64) -> Option<f64> {
    let mut r: Vec<f64> = robots
        .iter()
        .filter_map(|pts| lean_per_distance(pts, nadir, px))
        .collect();
    if r.len() < 3 {
        return None;
    }
    let mid = r.len() / 2;
    Some(*r.select_nth_unstable_by(mid, f64::total_cmp).1)
}

/// [`standing_centre`], with the lean held within [`LEAN_SPREAD`] times (or that share of)
/// `view` times the distance from the nadir when the view's lean is given ([`view_lean`]).
/// The blob is the footprint swept away from the nadir: its centroid lies half the lean
/// beyond the footprint's centre.
pub fn standing_centre_scaled(
    floor_points: &[Point],
    nadir: Option<Point>,
    px: f64,
    view: Option<f64>,
) -> Point {
    match leaning(floor_points, nadir, px) {
        Err(centroid) => centroid,
        Ok(l) => {
            let lean = match view {
                Some(k) if k.is_finite() && k >= 0.0 => l
                    .own
                    .clamp(k * l.dist / LEAN_SPREAD, LEAN_SPREAD * k * l.dist),
                _ => l.own,
            };
            (
                l.centroid.0 - lean / 2.0 * l.way.0,
                l.centroid.1 - lean / 2.0 * l.way.1,
            )
        }
    }
}

/// The share of a blob's pixels at each end left out of its extents (stray pixels). Not
/// more: a long blob (a tall robot far from the nadir) loses more of its length than of its
/// width to the same share, and its lean is then underestimated (2 % put the centre of the
/// test's cylinder 0.07 cell off).
pub const SPREAD_TAIL: f64 = 0.01;

/// The blob's pixel centres on the floor.
pub fn on_floor(blob: &Blob, image_to_floor: &Homography) -> Vec<Point> {
    blob.pixels
        .iter()
        .filter_map(|&(x, y)| image_to_floor.apply((f64::from(x) + 0.5, f64::from(y) + 0.5)))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    proptest::proptest! {
        #[test]
        fn the_inside_on_a_map_of_the_box_is_the_inside_searched(
            pixels in proptest::collection::vec((0u32..24, 0u32..18), 0..300),
            far in proptest::option::of((1000u32..5000, 1000u32..5000)),
        ) {
            // Dense in a small box (the map), or with a pixel far away (the search), and a
            // pixel given twice counted twice as the search counts it.
            let mut pixels = pixels;
            pixels.extend(far);
            let blob = Blob::from_pixels(pixels);
            proptest::prop_assert_eq!(blob.inside(), blob.inside_sorted());
        }
    }

    /// A `w` × `h` class map of `fill`, with the rectangles given set to their class.
    fn class_map(
        w: usize,
        h: usize,
        fill: u8,
        rects: &[(usize, usize, usize, usize, u8)],
    ) -> Vec<u8> {
        let mut c = vec![fill; w * h];
        for &(x0, y0, x1, y1, class) in rects {
            for y in y0..y1 {
                for x in x0..x1 {
                    c[y * w + x] = class;
                }
            }
        }
        c
    }

    fn square_blob(x0: u32, y0: u32, side: u32) -> Blob {
        let pixels: Vec<(u32, u32)> = (y0..y0 + side)
            .flat_map(|y| (x0..x0 + side).map(move |x| (x, y)))
            .collect();
        Blob {
            pixels,
            bbox: (x0, y0, x0 + side - 1, y0 + side - 1),
        }
    }

    #[test]
    fn solidity_tells_a_mark_from_a_ragged_speck() {
        let blob = |pixels: Vec<(u32, u32)>| {
            Blob::from_indices(
                &pixels
                    .iter()
                    .map(|&(x, y)| y as usize * 40 + x as usize)
                    .collect::<Vec<_>>(),
                40,
            )
        };
        let square = blob((0..100).map(|k| (5 + k % 10, 5 + k / 10)).collect());
        let disc = blob(
            (0..40 * 20)
                .map(|i| (i % 40, i / 40))
                .filter(|&(x, y)| (x as f64 - 20.0).powi(2) + (y as f64 - 10.0).powi(2) <= 36.0)
                .collect(),
        );
        // A diagonal line 16 px long and a checkerboard: no pixel inside.
        let line = blob((0..16).map(|k| (2 + k, 2 + k)).collect());
        let checks = blob(
            (0..40 * 10)
                .map(|i| (i % 40, i / 40))
                .filter(|&(x, y)| (x + y) % 2 == 0)
                .collect(),
        );
        assert!(square.solidity() >= 0.9, "{}", square.solidity());
        assert!(disc.solidity() >= 0.9, "{}", disc.solidity());
        assert_eq!(line.solidity(), 0.0);
        assert_eq!(checks.solidity(), 0.0);
        // Too small to have an inside.
        assert_eq!(blob(vec![(3, 3)]).solidity(), 0.0);
    }

    #[test]
    fn ring_share_counts_only_the_pixels_around() {
        const OB: u8 = super::super::colour::Class::Obstacle as u8;
        // A 3 × 3 piece at (10, 10); obstacle fills the columns left of x = 10.
        let c = class_map(30, 30, 0, &[(0, 0, 10, 30, OB)]);
        let b = square_blob(10, 10, 3);
        // The ring (2 px) is 7 × 7 less the 3 × 3: 40 pixels, 14 of them (x = 8, 9) obstacle.
        let share = ring_share(&b, &c, 30, OB);
        assert!((share - 14.0 / 40.0).abs() < 1e-9, "{share}");
        assert_eq!(ring_share(&square_blob(20, 10, 3), &c, 30, OB), 0.0);
    }

    #[test]
    fn largest_around_finds_the_region_touching_and_stops_at_the_cap() {
        const OB: u8 = super::super::colour::Class::Obstacle as u8;
        // A big obstacle (10 × 30) left of the piece, a small one (2 × 2) right of it.
        let c = class_map(40, 30, 0, &[(0, 0, 10, 30, OB), (14, 10, 16, 12, OB)]);
        let b = square_blob(10, 10, 3);
        assert_eq!(largest_around(&b, &c, 40, OB, 1000), 300);
        assert_eq!(largest_around(&b, &c, 40, OB, 50), 50);
        // Only the small one touches a piece at (17, 10): it is 4 pixels.
        assert_eq!(largest_around(&square_blob(17, 10, 2), &c, 40, OB, 1000), 4);
    }

    #[test]
    fn only_small_pieces_against_a_large_obstacle_are_set_aside() {
        const OB: u8 = super::super::colour::Class::Obstacle as u8;
        let c = class_map(60, 40, 0, &[(0, 0, 10, 40, OB), (40, 20, 42, 22, OB)]);
        let median = 100;
        let pieces = vec![
            square_blob(10, 5, 3),  // 9 px against the big obstacle: set aside
            square_blob(25, 5, 3),  // 9 px on open floor: doubtful
            square_blob(42, 20, 3), // 9 px against a 4-pixel obstacle: doubtful
        ];
        assert_eq!(
            behind_obstacle(&pieces, median, (&c, 60), 200),
            vec![true, false, false]
        );
        // Two pieces of 3 × 6 px against the obstacle one above the other, 18 + 18 px: 0.36
        // of the median together, and a mark cut by the obstacle's edge may show so much:
        // both stay doubtful, while either alone is set aside.
        let tall = |y0: u32| Blob {
            pixels: (y0..y0 + 6)
                .flat_map(|y| (10..13).map(move |x| (x, y)))
                .collect(),
            bbox: (10, y0, 12, y0 + 5),
        };
        let cut = vec![tall(5), tall(13)];
        assert_eq!(
            behind_obstacle(&cut[..1], median, (&c, 60), 200),
            vec![true]
        );
        assert_eq!(
            behind_obstacle(&cut, median, (&c, 60), 200),
            vec![false, false]
        );
    }

    fn disc(cx: f64, cy: f64, r: f64) -> Vec<Point> {
        let mut out = Vec::new();
        let mut y = cy - r;
        while y <= cy + r {
            let mut x = cx - r;
            while x <= cx + r {
                if (x - cx).powi(2) + (y - cy).powi(2) <= r * r {
                    out.push((x, y));
                }
                x += 0.01;
            }
            y += 0.01;
        }
        out
    }

    /// A robot's blob on the floor as a camera over `nadir` sees it: its footprint (the points
    /// `footprint(centre, s)` gives at scale s) swept from its base (s = 1) to its top
    /// (s = k, scaled about the nadir), in `steps` steps, each point once on a lattice of 0.02.
    fn swept(
        (nadir, centre, k): (Point, Point, f64),
        steps: u32,
        footprint: impl Fn(Point, f64) -> Vec<Point>,
    ) -> Vec<Point> {
        let mut seen = std::collections::BTreeSet::new();
        let mut pts = Vec::new();
        for step in 0..=steps {
            let s = 1.0 + (k - 1.0) * f64::from(step) / f64::from(steps);
            let c = (
                nadir.0 + (centre.0 - nadir.0) * s,
                nadir.1 + (centre.1 - nadir.1) * s,
            );
            for p in footprint(c, s) {
                let key = ((p.0 * 50.0).round() as i64, (p.1 * 50.0).round() as i64);
                if seen.insert(key) {
                    pts.push((key.0 as f64 / 50.0, key.1 as f64 / 50.0));
                }
            }
        }
        pts
    }

    /// A cylinder of radius 0.3 at (18.5, 12.5), its top 1.05 times as far from the nadir
    /// at (2, 2) as its base (a lean of almost a cell): the blob is the base, the top and the
    /// band between them, each point of the floor once (as the pixels of a blob are).
    #[test]
    fn a_leaning_robot_stands_on_its_base() {
        let (nadir, centre, r, k) = ((2.0, 2.0), (18.5, 12.5), 0.3, 1.05);
        let pts = swept((nadir, centre, k), 40, |c, s| disc(c.0, c.1, r * s));
        let got = standing_centre(&pts, Some(nadir), 0.01);
        let err = ((got.0 - centre.0).powi(2) + (got.1 - centre.1).powi(2)).sqrt();
        // The top is 15 % wider: the centre is off by at most 0.15 r.
        assert!(err < 0.15 * r + 0.02, "{got:?}");
        let naive = standing_centre(&pts, None, 0.01);
        let naive_err = ((naive.0 - centre.0).powi(2) + (naive.1 - centre.1).powi(2)).sqrt();
        assert!(naive_err > 3.0 * err, "{naive:?} vs {got:?}");
    }

    /// A robot 1.4 cells long and 0.5 wide lying along the way from the nadir, its top 1.004
    /// times as far from the nadir as its base (a lean of 0.04 cell): its own blob, longer
    /// than wide, reads as a lean of most of a cell, and its centre 0.45 cell toward the
    /// nadir. With the view's lean per distance from the nadir (the other robots', 0.004),
    /// it stands where it is (the I0004 capsules; issue #29's twenty-eighth round).
    #[test]
    fn a_long_robot_leans_as_the_others_do() {
        let (nadir, centre, k) = ((0.0, 5.5), (10.5, 5.5), 1.004);
        let (half_long, half_wide) = (0.7, 0.25);
        let pts = swept((nadir, centre, k), 10, |c, s| {
            let mut out = Vec::new();
            let mut y = c.1 - half_wide * s;
            while y <= c.1 + half_wide * s {
                let mut x = c.0 - half_long * s;
                while x <= c.0 + half_long * s {
                    out.push((x, y));
                    x += 0.01;
                }
                y += 0.01;
            }
            out
        });
        let off = |p: Point| ((p.0 - centre.0).powi(2) + (p.1 - centre.1).powi(2)).sqrt();
        let own = standing_centre(&pts, Some(nadir), 0.01);
        assert!(off(own) > 0.3, "{own:?}");
        let ratio = lean_per_distance(&pts, Some(nadir), 0.01).unwrap();
        assert!(ratio > 0.05, "{ratio}");
        let scaled = standing_centre_scaled(&pts, Some(nadir), 0.01, Some(0.004));
        assert!(off(scaled) < 0.05, "{scaled:?}");
        // Without the view's lean, or under the camera, as before.
        assert_eq!(standing_centre_scaled(&pts, Some(nadir), 0.01, None), own);
        assert_eq!(lean_per_distance(&pts, None, 0.01), None);
    }

    /// A robot of radius 0.3 at (8.5, 3.5), seen from a nadir at (2, 3.5), with a few stray
    /// pixels joined to its blob: a thin rim toward the nadir and a speck at its side (a
    /// shadow's edge, noise). They move the centre by little, while the blob's extremes
    /// would move it by about half their reach.
    #[test]
    fn stray_pixels_hardly_move_a_robot() {
        let (nadir, centre, r) = ((2.0, 3.5), (8.5, 3.5), 0.3);
        let mut pts = disc(centre.0, centre.1, r);
        let clean = standing_centre(&pts, Some(nadir), 0.01);
        // A rim 0.2 cell long toward the nadir, and a speck 0.15 cell off to the side.
        for i in 0..12 {
            pts.push((centre.0 - r - 0.2 * f64::from(i) / 11.0, centre.1));
        }
        pts.extend([
            (centre.0, centre.1 + r + 0.15),
            (centre.0, centre.1 + r + 0.14),
        ]);
        let got = standing_centre(&pts, Some(nadir), 0.01);
        let err = ((got.0 - centre.0).powi(2) + (got.1 - centre.1).powi(2)).sqrt();
        let clean_err = ((clean.0 - centre.0).powi(2) + (clean.1 - centre.1).powi(2)).sqrt();
        assert!(clean_err < 0.01, "{clean:?}");
        assert!(err < 0.02, "{got:?}");
    }

    fn blob_at(x: u32, y: u32, side: u32) -> Blob {
        let pixels: Vec<(u32, u32)> = (0..side * side)
            .map(|i| (x + i % side, y + i / side))
            .collect();
        Blob {
            pixels,
            bbox: (x, y, x + side - 1, y + side - 1),
        }
    }

    #[test]
    fn sizes_sort_pieces_noise_and_touching_robots() {
        let blobs = vec![
            blob_at(0, 0, 6),
            blob_at(20, 0, 6),
            blob_at(40, 0, 6),
            blob_at(26, 0, 2), // a piece beside the second: joins it
            blob_at(60, 0, 9), // 81 px: more than 1.7 × 36
            blob_at(80, 0, 1), // noise
            blob_at(90, 0, 3), // 9 px alone: doubtful
        ];
        let s = sort(blobs);
        assert_eq!(s.median_area, 36);
        assert_eq!(s.kept.len(), 3);
        assert_eq!(s.kept[1].area(), 40);
        assert_eq!(s.merged.len(), 1);
        assert_eq!(s.doubtful.len(), 1);
    }

    #[test]
    fn many_ragged_specks_do_not_make_the_median() {
        // Four goals of 100 px (crosses on a dark floor), and forty specks of noise of the
        // goals' colour, diagonal lines of 7 px each (X0026: the median was a speck's).
        let mut blobs: Vec<Blob> = (0..4).map(|k| blob_at(k * 20, 0, 10)).collect();
        for k in 0..40u32 {
            let (x0, y0) = (k * 10, 30);
            let pixels: Vec<(u32, u32)> = (0..7).map(|i| (x0 + i, y0 + i)).collect();
            blobs.push(Blob {
                pixels,
                bbox: (x0, y0, x0 + 6, y0 + 6),
            });
        }
        let s = sort(blobs.clone());
        assert_eq!(s.median_area, 100);
        assert_eq!(s.kept.len(), 4);
        // Without the goals, the specks are all there is: their own median.
        assert_eq!(sort(blobs.split_off(4)).median_area, 7);
    }

    #[test]
    fn a_ragged_lone_piece_is_noise_and_a_solid_one_doubtful() {
        // Three robots of 100 px; alone, a solid piece of 16 px and a diagonal line of 16 px
        // (a shelf's rim in the robots' colour).
        let mut blobs: Vec<Blob> = (0..3).map(|k| blob_at(20 * k, 0, 10)).collect();
        blobs.push(blob_at(0, 40, 4));
        let line: Vec<(u32, u32)> = (0..16).map(|k| (40 + k, 40 + k)).collect();
        blobs.push(Blob {
            pixels: line,
            bbox: (40, 40, 55, 55),
        });
        let s = sort(blobs);
        assert_eq!(s.kept.len(), 3);
        assert_eq!(s.doubtful.len(), 1);
        assert_eq!(s.doubtful[0].bbox, (0, 40, 3, 43));
    }

    #[test]
    fn a_shelf_of_the_robots_colour_or_specks_do_not_make_the_median() {
        // Six robots of 36 px and one shelf of 400 px (a quarter of it is more than a robot):
        // the median is a robot's.
        let mut blobs: Vec<Blob> = (0..6).map(|k| blob_at(20 * k, 0, 6)).collect();
        blobs.push(blob_at(0, 40, 20));
        let s = sort(blobs);
        assert_eq!(s.median_area, 36);
        assert_eq!(s.kept.len(), 6);
        assert_eq!(s.merged.len(), 1);
        // Three robots of 100 px and eight specks of 9 px: still a robot's.
        let mut blobs: Vec<Blob> = (0..3).map(|k| blob_at(20 * k, 0, 10)).collect();
        blobs.extend((0..8).map(|k| blob_at(10 * k, 40, 3)));
        assert_eq!(sort(blobs).median_area, 100);
        // Areas within a factor of 2 are one group; the most blobs times their area wins,
        // the larger on a tie.
        assert_eq!(typical_area(&[10, 12, 30, 50, 55]), 50);
        assert_eq!(typical_area(&[10, 10, 10, 10, 40]), 10);
        assert_eq!(typical_area(&[10, 20, 40]), 40);
        assert_eq!(typical_area(&[7]), 7);
    }

    /// Pixel discs of radius `r` at the given centres, as one blob.
    #[test]
    fn opening_drops_a_thin_strip_and_keeps_a_disc() {
        // A disc of radius 8 and, touching it, a strip 3 px thick and 30 long (a shelf's rim).
        let mut blob = discs(&[(20.0, 20.0)], 8.0);
        let disc = blob.area();
        for y in 28..31u32 {
            for x in 5..35u32 {
                if !blob.pixels.contains(&(x, y)) {
                    blob.pixels.push((x, y));
                }
            }
        }
        blob.bbox = (blob.bbox.0.min(5), blob.bbox.1, blob.bbox.2.max(34), 30);
        let pieces = opened(&blob, 2);
        assert_eq!(
            pieces.len(),
            1,
            "{:?}",
            pieces.iter().map(Blob::area).collect::<Vec<_>>()
        );
        let kept = pieces[0].area();
        // The disc, and the few pixels of the strip where it meets the disc.
        assert!(
            kept * 100 <= disc * 115 && kept >= disc * 9 / 10,
            "{kept} of {disc}"
        );
        // Two discs joined by a bridge 2 px wide open into two.
        let mut pair = discs(&[(15.0, 20.0), (40.0, 20.0)], 7.0);
        for y in 19..21u32 {
            for x in 21..35u32 {
                if !pair.pixels.contains(&(x, y)) {
                    pair.pixels.push((x, y));
                }
            }
        }
        assert_eq!(opened(&pair, 2).len(), 2);
    }

    fn discs(centres: &[(f64, f64)], r: f64) -> Blob {
        let mut pixels = Vec::new();
        for y in 0..60u32 {
            for x in 0..80u32 {
                let (px, py) = (f64::from(x) + 0.5, f64::from(y) + 0.5);
                if centres
                    .iter()
                    .any(|c| (px - c.0).powi(2) + (py - c.1).powi(2) <= r * r)
                {
                    pixels.push((x, y));
                }
            }
        }
        let bbox = pixels
            .iter()
            .fold((u32::MAX, u32::MAX, 0, 0), |b, &(x, y)| {
                (b.0.min(x), b.1.min(y), b.2.max(x), b.3.max(y))
            });
        Blob { pixels, bbox }
    }

    #[test]
    fn touching_robots_are_split_when_the_count_is_clear() {
        let one = discs(&[(10.0, 10.0)], 5.0).area();
        // Two discs overlapping by a pixel, and three in a row.
        for centres in [
            vec![(20.0, 20.0), (29.5, 21.0)],
            vec![(10.0, 30.0), (19.6, 30.0), (29.2, 30.0)],
        ] {
            let blob = discs(&centres, 5.0);
            let pieces = split(&blob, one).expect("split");
            assert_eq!(pieces.len(), centres.len());
            let mut got: Vec<Point> = pieces.iter().map(Blob::centroid).collect();
            got.sort_by(|a, b| a.0.total_cmp(&b.0));
            for (g, c) in got.iter().zip(&centres) {
                assert!(
                    (g.0 - c.0).abs() < 1.0 && (g.1 - c.1).abs() < 1.0,
                    "{got:?}"
                );
            }
            assert_eq!(pieces.iter().map(Blob::area).sum::<usize>(), blob.area());
        }
        // 2.5 medians: the count is not clear.
        let mut blob = discs(&[(20.0, 20.0), (29.5, 21.0)], 5.0);
        let small = discs(&[(24.5, 28.0)], 3.5);
        let extra: Vec<(u32, u32)> = small
            .pixels
            .iter()
            .copied()
            .filter(|p| !blob.pixels.contains(p))
            .collect();
        blob.pixels.extend(extra);
        blob.bbox.3 = small.bbox.3;
        let ratio = blob.area() as f64 / one as f64;
        assert!((ratio - 2.5).abs() < 0.2, "{ratio}");
        assert!(split(&blob, one).is_none());
        // Twice the median but no neck: a bar of 20 × 8 px.
        let bar = blob_at(0, 0, 20);
        let bar = Blob {
            pixels: bar.pixels.into_iter().filter(|p| p.1 < 8).collect(),
            bbox: (0, 0, 19, 7),
        };
        assert!(split(&bar, 80).is_none());
    }

    #[test]
    fn robots_larger_than_the_median_touching_split_between_counts() {
        // Two discs of radius 5.6 touching, against a median disc of radius 5: 2.5 medians,
        // between two counts; only two cores are found, each piece 1.25 medians.
        let one = discs(&[(10.0, 10.0)], 5.0).area();
        let blob = discs(&[(20.0, 20.0), (30.8, 20.0)], 5.6);
        let ratio = blob.area() as f64 / one as f64;
        assert!((ratio - 2.5).abs() < 0.15, "{ratio}");
        let pieces = split(&blob, one).expect("split");
        assert_eq!(pieces.len(), 2);
    }

    #[test]
    fn elongation_of_discs_bars_and_lines() {
        let disc = discs(&[(20.0, 20.0)], 6.0);
        assert!(
            (disc.elongation() - 1.0).abs() < 0.05,
            "{}",
            disc.elongation()
        );
        let bar = Blob {
            pixels: (0..200).map(|k| (k % 20, k / 20)).collect(),
            bbox: (0, 0, 19, 9),
        };
        assert!(
            (bar.elongation() - 2.0).abs() < 0.05,
            "{}",
            bar.elongation()
        );
        // The same bar on its diagonal.
        let diagonal = Blob {
            pixels: (0..20)
                .flat_map(|k| (0..3).map(move |j| (k + j, k)))
                .collect(),
            bbox: (0, 0, 21, 19),
        };
        assert!(diagonal.elongation() > 4.0, "{}", diagonal.elongation());
    }

    #[test]
    fn one_larger_mark_is_not_marks_touching() {
        // A disc of radius 6.7 against marks of radius 5: 1.8 medians, round and solid.
        let one = discs(&[(10.0, 10.0)], 5.0).area();
        let large = discs(&[(30.0, 30.0)], 6.7);
        assert!(large.area() as f64 > 1.7 * one as f64);
        assert!(one_large(&large, one));
        // Two discs of radius 5 touching: as large, but twice as long as wide.
        let two = discs(&[(20.0, 20.0), (29.5, 21.0)], 5.0);
        assert!(!one_large(&two, one));
        // A disc of 2.4 medians is more than one mark.
        assert!(!one_large(&discs(&[(30.0, 30.0)], 7.9), one));
    }

    #[test]
    fn a_line_is_no_marks_touching() {
        // Four discs in a row are no line; a bar 40 × 3 px and a diagonal band are.
        let row = discs(
            &[(10.0, 10.0), (20.0, 10.0), (30.0, 10.0), (40.0, 10.0)],
            5.0,
        );
        assert!(!line_like(&row, 80));
        let bar = Blob {
            pixels: (0..120).map(|k| (k % 40, 5 + k / 40)).collect(),
            bbox: (0, 5, 39, 7),
        };
        assert!(line_like(&bar, 80));
        // Against marks of 12 px (2 px thick), the bar (2 px thick) is as thick as one.
        assert!(!line_like(&bar, 12));
        let band: Vec<(u32, u32)> = (0..30).flat_map(|k| [(k, k), (k + 1, k)]).collect();
        assert!(line_like(
            &Blob {
                pixels: band,
                bbox: (0, 0, 30, 29),
            },
            80
        ));
    }

    /// Two discs of radius 120 px touching: about 64 depths are tried, not 360.
    #[test]
    fn a_huge_blob_splits_in_few_depths() {
        let r = 120.0f64;
        let mut pixels = Vec::new();
        for y in 0..250u32 {
            for x in 0..500u32 {
                let (px, py) = (f64::from(x) + 0.5, f64::from(y) + 0.5);
                if [(125.0, 125.0), (364.0, 125.0)]
                    .iter()
                    .any(|c: &(f64, f64)| (px - c.0).powi(2) + (py - c.1).powi(2) <= r * r)
                {
                    pixels.push((x, y));
                }
            }
        }
        let bbox = pixels
            .iter()
            .fold((u32::MAX, u32::MAX, 0, 0), |b, &(x, y)| {
                (b.0.min(x), b.1.min(y), b.2.max(x), b.3.max(y))
            });
        let blob = Blob { pixels, bbox };
        let pieces = split(&blob, blob.area() / 2).expect("split");
        assert_eq!(pieces.len(), 2);
        assert!(pieces
            .iter()
            .all(|p| p.centroid().0 < 245.0 || p.centroid().0 > 245.0));
        assert!(
            (pieces[0].centroid().0 - 125.0).abs() < 2.0,
            "{:?}",
            pieces[0].centroid()
        );
    }

    #[test]
    fn the_next_value_of_a_class_is_found_past_blocks() {
        let mut values = vec![0u8; 300];
        for i in [5, 64, 130, 299] {
            values[i] = 3;
        }
        let mut found = Vec::new();
        let mut from = 0;
        while let Some(i) = next_of(&values, from, 3) {
            found.push(i);
            from = i + 1;
        }
        assert_eq!(found, [5, 64, 130, 299]);
        assert_eq!(next_of(&values, 300, 3), None);
        assert_eq!(next_of(&values, 301, 3), None);
        assert_eq!(next_of(&values[..299], 131, 3), None);
    }

    #[test]
    fn finds_eight_connected_blobs() {
        #[rustfmt::skip]
        let mut classes = vec![
            1, 0, 0, 1,
            0, 1, 0, 1,
            0, 0, 0, 0,
            2, 2, 0, 1,
        ];
        let blobs = find(&mut classes, 4, 1);
        assert_eq!(blobs.len(), 3);
        assert_eq!(blobs[0].area(), 2);
        assert_eq!(classes[0], 1, "marks are cleared");
    }

    #[test]
    fn blobs_from_seeds_are_those_of_find_that_hold_a_seed_in_the_same_order() {
        // Blobs of class 1: a U (first pixel 0), a bar (first pixel 7) and a dot (28).
        #[rustfmt::skip]
        let mut classes = vec![
            1, 0, 1, 0, 0, 0, 0, 1,
            1, 0, 1, 0, 0, 0, 0, 1,
            1, 1, 1, 0, 2, 0, 0, 1,
            1, 0, 0, 0, 1, 0, 0, 0,
        ];
        let all = find(&mut classes, 8, 1);
        assert_eq!(all.len(), 3);
        let set = |b: &Blob| {
            let mut p = b.pixels.clone();
            p.sort_unstable();
            (p, b.bbox)
        };
        // Seeds away from the blobs' first pixels (the bar's 23 before the U's 17 and 24), one
        // on another class (20): the U and the bar, in row-major order of their first pixels,
        // whole.
        let from = find_from(&mut classes, 8, 1, &[20, 23, 24]);
        assert_eq!(from.len(), 2);
        assert_eq!(set(&from[0]), set(&all[0]));
        let from = find_from(&mut classes, 8, 1, &[17, 20, 23, 24]);
        assert_eq!(from.len(), 2);
        assert_eq!(set(&from[0]), set(&all[0]));
        assert_eq!(set(&from[1]), set(&all[1]));
        assert!(classes.iter().all(|&c| c < 0x80), "marks are cleared");
        // No seed, no blob.
        assert!(find_from(&mut classes, 8, 1, &[]).is_empty());
    }
}
