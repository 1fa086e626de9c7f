//! Wall images (thesis §3.1, Algorithm 1, extended with orange and made robust).
//!
//! Pixels are classified by the thesis rule (red if r > 2g and r > 1.5b; green if g > 1.5r and
//! g > 1.5b; blue if b > 1.5r and b > 1.5g) plus our orange rule (0.5r ≤ g ≤ 0.85r and
//! b < 0.5g), and only when the pixel is saturated (max − min ≥ 60), so that black, white and
//! grey borders, noise and background are never colours. Each colour's strength is normalised
//! by its median, so every brick interior reads 1 and borders read as dips.
//!
//! Layers are horizontal bands of equal height: separators are rows where many columns dip
//! below 72 % of the rows above and below. The layer pitch follows from the separators and the
//! wall's height. Inside a band, bricks are runs of coloured columns split by background or by
//! dips; a brick's length is its run plus one border width. The length unit (pixels per
//! 0.30 m) is inferred from all bricks together, and every brick's length must match its
//! colour within 0.35 units. Positions snap to the 0.30 m grid. A column range empty on every
//! layer starts a new segment.

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
/// How far to look on each side for a dip's shoulders (px).
const DIP_REACH: usize = 4;
/// A column is part of a brick when its strength is at least this.
const ON: f32 = 0.5;
/// Allowed mismatch between a brick's measured and nominal length (units of 0.30 m).
const LENGTH_TOLERANCE: f64 = 0.35;

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
        Some(Strength {
            width,
            height,
            kind,
            value,
        })
    }

    fn at(&self, x: usize, y: usize) -> f32 {
        self.value[y * self.width + x]
    }
}

/// Marks dips in a profile: runs of values below `DIP_CANDIDATE` of both shoulders whose
/// minimum is below `DIP` of them. Returns a mask of dip positions.
fn dip_mask(profile: &[f32], floor: f32, min_depth: f32, plateau: f32) -> Vec<bool> {
    let n = profile.len();
    let shoulder = |i: usize| {
        let left = profile[i.saturating_sub(DIP_REACH)..i]
            .iter()
            .copied()
            .fold(0.0, f32::max);
        let right = profile[(i + 1).min(n)..(i + 1 + DIP_REACH).min(n)]
            .iter()
            .copied()
            .fold(0.0, f32::max);
        left.min(right)
    };
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
        // A lone column needs a deep dip: noise makes shallow one-column dips.
        if deepest < DIP
            && lowest < DIP * plateau
            && depth >= min_depth
            && (i - start >= 2 || deepest < 0.35)
        {
            mask[start..i].iter_mut().for_each(|m| *m = true);
        }
    }
    mask
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
        let mask = dip_mask(&column, ON, 0.0, 1.0);
        for (y, &m) in mask.iter().enumerate() {
            if m {
                dips[y] += 1;
            }
        }
        for (s, e) in runs(&mask) {
            widths.push(deficit(&column[s..e], 1.0));
        }
    }
    let strongest = dips.iter().copied().max().unwrap_or(0);
    let lit = (0..st.width)
        .filter(|&x| (top..=bottom).any(|y| st.at(x, y) >= ON))
        .count();
    let threshold = (strongest as f64 * 0.3).max(2.0).max(lit as f64 * 0.1);
    let separators: Vec<f64> = runs(
        &dips
            .iter()
            .map(|&d| d as f64 >= threshold)
            .collect::<Vec<_>>(),
    )
    .into_iter()
    .map(|(s, e)| {
        let w: f64 = (s..e).map(|y| dips[y] as f64).sum();
        (s..e)
            .map(|y| (y as f64 + 0.5) * dips[y] as f64)
            .sum::<f64>()
            / w
    })
    .collect();
    let measured = median(widths);
    let border = measured.unwrap_or(0.0);
    let upper = top as f64 - border / 2.0;
    let lower = bottom as f64 + 1.0 + border / 2.0;
    let extent = lower - upper;
    let count = if let Some(n) = count {
        n.max(1)
    } else if separators.is_empty() {
        1
    } else {
        let mut marks = vec![upper];
        marks.extend(separators.iter().copied());
        marks.push(lower);
        // Missed separators double a gap; the smallest sensible gap is one layer.
        let pitch = marks
            .windows(2)
            .map(|w| w[1] - w[0])
            .filter(|&d| d >= 3.0)
            .fold(extent, f64::min);
        ((extent / pitch).round() as usize).max(1)
    };
    let pitch = extent / count as f64;
    let bands = (0..count)
        .map(|j| {
            let bottom_edge = lower - j as f64 * pitch;
            let a = (bottom_edge - pitch).round().max(0.0) as usize;
            let b = (bottom_edge.round() as usize).min(st.height).max(a + 1);
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

/// A brick found in one band, in pixels.
struct Found {
    level: u32,
    kind: BrickType,
    left: f64,
    right: f64,
    centre: (u32, u32),
}

fn bricks_in_band(st: &Strength, (y0, y1): (usize, usize)) -> Vec<(usize, usize, BrickType, f64)> {
    // Rows weighted by their own strength (a matched filter): thin bricks light only a few
    // rows of their band, and the dark rows would add noise but no signal.
    let weights: Vec<f32> = (y0..y1)
        .map(|y| (0..st.width).map(|x| st.at(x, y)).sum::<f32>() / st.width as f32)
        .collect();
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
    let dips = dip_mask(&profile, floor, 4.0 * noise, plateau);
    let on: Vec<bool> = profile
        .iter()
        .zip(&dips)
        .map(|(&p, &d)| p >= floor && !d)
        .collect();
    let found = runs(&on);
    let mut out = Vec::new();
    for (k, &(s, e)) in found.iter().enumerate() {
        let mut votes = [0f32; 4];
        for x in s..e {
            for y in y0..y1 {
                if let Some(kind) = st.kind[y * st.width + x] {
                    votes[kind.index()] += st.at(x, y);
                }
            }
        }
        let best = (0..4)
            .max_by(|&a, &b| votes[a].total_cmp(&votes[b]))
            .unwrap_or(0);
        // The gap before this run, measured as missing area.
        let gap = if k == 0 {
            f64::INFINITY
        } else {
            deficit(&profile[found[k - 1].1..s], plateau)
        };
        out.push((s, e, BrickType::ALL[best], gap));
    }
    out
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
    match read_layers(&st, name, None)? {
        Ok(wall) => Ok(wall),
        // The separators misled the layer count: a layer is 2/3 of the brick unit tall.
        Err(expected_count) => match read_layers(&st, name, Some(expected_count))? {
            Ok(wall) => Ok(wall),
            Err(_) => Err(WallError::new(
                name,
                Location::Whole,
                WallErrorKind::ImageLayout {
                    reason: "the layer height does not fit the brick lengths (a layer should be \
                             2/3 of 0.30 m); is this a front view of a brick wall?"
                        .into(),
                },
            )),
        },
    }
}

/// One reading attempt. `Ok(Err(n))` means the layer pitch disagreed with the brick unit and
/// the wall probably has `n` layers.
fn read_layers(
    st: &Strength,
    name: &str,
    count: Option<usize>,
) -> Result<Result<Wall, usize>, WallError> {
    let layers = find_layers(st, name, count)?;
    let band_runs: Vec<Vec<(usize, usize, BrickType, f64)>> = layers
        .bands
        .iter()
        .map(|&band| bricks_in_band(st, band))
        .collect();
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
    // Border width: from the layer separators, else from the narrowest gaps between bricks.
    let border = layers.border.unwrap_or_else(|| {
        let gaps: Vec<f64> = band_runs
            .iter()
            .flat_map(|r| r.iter().skip(1).map(|run| run.3))
            .collect();
        let narrowest = gaps.iter().copied().fold(f64::INFINITY, f64::min);
        if narrowest <= 6.0 {
            median(gaps.into_iter().filter(|&g| g <= narrowest + 3.0).collect()).unwrap_or(0.0)
        } else {
            implied_border(&band_runs, layers.extent)
        }
    });
    let joined = |gap: f64| gap <= border + 3.0;
    let mut found = Vec::new();
    for (j, runs) in band_runs.iter().enumerate() {
        let level = j as u32 + 1;
        let row = ((layers.bands[j].0 + layers.bands[j].1) / 2) as u32;
        for (i, &(s, e, kind, gap)) in runs.iter().enumerate() {
            let left = match i.checked_sub(1).map(|p| runs[p].1) {
                Some(prev) if joined(gap) => (prev + s) as f64 / 2.0,
                _ => s as f64 - border / 2.0,
            };
            let right = match runs.get(i + 1) {
                Some(next) if joined(next.3) => (e + next.0) as f64 / 2.0,
                _ => e as f64 + border / 2.0,
            };
            found.push(Found {
                level,
                kind,
                left,
                right,
                centre: (((s + e) / 2) as u32, row),
            });
        }
    }
    // The unit is what most of the wall's length agrees on (a median weighted by length):
    // one brick of a wrong length cannot move it, and long bricks measure it best.
    let mut per_unit: Vec<(f64, u32)> = found
        .iter()
        .map(|f| {
            (
                (f.right - f.left) / f64::from(f.kind.units()),
                f.kind.units(),
            )
        })
        .collect();
    per_unit.sort_by(|a, b| a.0.total_cmp(&b.0));
    let half = per_unit.iter().map(|p| p.1).sum::<u32>().div_ceil(2);
    let mut seen = 0;
    let unit = per_unit
        .iter()
        .find(|p| {
            seen += p.1;
            seen >= half
        })
        .map_or(1.0, |p| p.0);
    // The wall's height from edge to edge, with the final border estimate.
    let extent = layers.extent - layers.border.unwrap_or(0.0) + border;
    let ratio = extent / layers.bands.len() as f64 / unit;
    if !(0.45..=0.9).contains(&ratio) {
        return Ok(Err((extent / (unit * 2.0 / 3.0)).round() as usize));
    }
    let origin = found.iter().map(|f| f.left).fold(f64::INFINITY, f64::min);
    let mut bricks = Vec::with_capacity(found.len());
    for f in &found {
        let measured = (f.right - f.left) / unit;
        let expected = f64::from(f.kind.units());
        if (measured - expected).abs() > LENGTH_TOLERANCE.max(0.08 * expected) {
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
        let x = ((f.left - origin) / unit).round() as u32;
        bricks.push((f, x));
    }
    assemble(name, bricks).map(Ok)
}

/// The border that makes a lone layer of isolated bricks 2/3 of a unit tall. With `m` bricks
/// of total nominal length `Σn` units, run lengths `Σr` and coloured height `T`:
/// `T + b = (2/3)·(Σr + m·b)/Σn`.
fn implied_border(band_runs: &[Vec<(usize, usize, BrickType, f64)>], colour_height: f64) -> f64 {
    let runs: Vec<_> = band_runs.iter().flatten().collect();
    let m = runs.len() as f64;
    let sum_n: f64 = runs.iter().map(|r| f64::from(r.2.units())).sum();
    let sum_r: f64 = runs.iter().map(|r| (r.1 - r.0) as f64).sum();
    if sum_n == 0.0 || band_runs.len() != 1 {
        return 0.0;
    }
    let b = (2.0 / 3.0 * sum_r / sum_n - colour_height) / (1.0 - 2.0 * m / (3.0 * sum_n));
    b.clamp(0.0, 0.5 * sum_r / sum_n)
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
