//! Step 2, *find layers*: the horizontal bands of colour, top to bottom.

use super::*;

/// Rows differ where a span of one has this many pixels without the same colour in the other.
const ROW_CHANGE_PX: usize = 3;
/// A band's row whose colour is below this share of the strongest rows above and below it
/// is a faint border line.
const FAINT_ROW: f32 = 0.75;

/// A stretch `[start, end)` of one kind: columns of one colour, or rows of a band.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Span<K = BrickType> {
    pub(super) kind: K,
    pub(super) start: usize,
    pub(super) end: usize,
}

/// The stretches of one kind at least `shortest` long in a sequence (`None` is no kind).
pub(super) fn spans<K: Copy + PartialEq>(
    items: impl Iterator<Item = Option<K>>,
    shortest: usize,
) -> Vec<Span<K>> {
    let mut out = Vec::new();
    let mut open: Option<Span<K>> = None;
    for (i, item) in items.chain(std::iter::once(None)).enumerate() {
        if open.is_some_and(|s| Some(s.kind) == item) {
            continue;
        }
        if let Some(mut s) = open.take() {
            s.end = i;
            if s.end - s.start >= shortest {
                out.push(s);
            }
        }
        open = item.map(|kind| Span {
            kind,
            start: i,
            end: i,
        });
    }
    out
}

/// Whether rows with spans `a` and rows with spans `b` show different bricks: some span of
/// one has a stretch of [`ROW_CHANGE_PX`] pixels without its colour in the other (an edge
/// that flickers by a pixel or two is the same row).
pub(super) fn rows_differ(a: &[Span], b: &[Span]) -> bool {
    let uncovered = |a: &[Span], b: &[Span]| {
        a.iter().any(|s| {
            let mut reached = s.start;
            // Spans are in order and apart: those over `s` follow the last that ends before it.
            let over = &b[b.partition_point(|t| t.end <= s.start)..];
            let over = over.iter().take_while(|t| t.start < s.end);
            for t in over.filter(|t| t.kind == s.kind) {
                if t.start >= reached + ROW_CHANGE_PX {
                    return true;
                }
                reached = reached.max(t.end);
            }
            s.end >= reached + ROW_CHANGE_PX
        })
    };
    uncovered(a, b) || uncovered(b, a)
}

/// Rows `[top, bottom)` of the image: a segment, a band, and in the end a layer.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Rows {
    pub(super) top: usize,
    pub(super) bottom: usize,
}

impl Rows {
    /// At least [`MIN_COLOUR_PX`] rows: tall enough for a layer.
    fn tall(&self) -> bool {
        self.bottom - self.top >= MIN_COLOUR_PX
    }
}

/// Step 2: the layers, top to bottom.
///
/// Consecutive rows whose spans agree form a segment. Touching tall segments that agree are
/// one band (noise cut it, or two layers are drawn alike with no border line); thin ones
/// between them do not keep them apart. A thin segment is checked: the blurred edge of a band
/// or a speck of noise is dropped, a stray mark is an error. Last, a band is split where a
/// faint border line dims its colour; its tall parts are the layers.
pub(super) fn find_layers(px: &Pixels) -> Result<Vec<Rows>, Failure> {
    let mut segments: Vec<Rows> = Vec::new();
    let mut above: Vec<Span> = Vec::new();
    for y in 0..px.height {
        let row = row_spans(px, y);
        if !row.is_empty() {
            match segments.last_mut() {
                Some(s) if s.bottom == y && !rows_differ(&above, &row) => s.bottom = y + 1,
                _ => segments.push(Rows {
                    top: y,
                    bottom: y + 1,
                }),
            }
        }
        above = row;
    }
    let bands = join_segments(px, &segments);
    check_thin_segments(px, &segments, &bands)?;
    Ok(bands
        .iter()
        .flat_map(|&b| split_at_faint_borders(px, b))
        .filter(Rows::tall)
        .collect())
}

/// A row's spans of one colour at least [`MIN_COLOUR_PX`] long.
fn row_spans(px: &Pixels, y: usize) -> Vec<Span> {
    let classes = px.class[y * px.width..(y + 1) * px.width].iter().copied();
    spans(classes, MIN_COLOUR_PX)
}

/// Touching tall segments whose spans agree, joined into bands. Each band's colour counts
/// are kept as it grows, so that joining costs one pass over the image.
fn join_segments(px: &Pixels, segments: &[Rows]) -> Vec<Rows> {
    let mut bands: Vec<Rows> = Vec::new();
    let mut counts = Vec::new(); // the last band's, per column
    let add = |counts: &mut Vec<[u32; 4]>, more: &[[u32; 4]]| {
        for (total, add) in counts.iter_mut().zip(more) {
            (0..4).for_each(|k| total[k] += add[k]);
        }
    };
    // A band never reaches across a row with no colour: it joins segments of one stack.
    for stack in segments.chunk_by(|a, b| a.bottom == b.top) {
        let stack_start = bands.len();
        for s in stack.iter().filter(|s| s.tall()) {
            let own = column_counts(px, *s);
            let joinable = bands.len() > stack_start;
            match bands.last_mut() {
                Some(band)
                    if joinable
                        && !rows_differ(
                            &majority_spans(&counts, *band),
                            &majority_spans(&own, *s),
                        ) =>
                {
                    // The thin segments between them are rows of the band as well.
                    let between = Rows {
                        top: band.bottom,
                        bottom: s.top,
                    };
                    add(&mut counts, &column_counts(px, between));
                    add(&mut counts, &own);
                    band.bottom = s.bottom;
                }
                _ => {
                    bands.push(*s);
                    counts = own;
                }
            }
        }
    }
    bands
}

/// A thin segment is the blurred edge of a band (in a stack of touching segments with a tall
/// one, or at most two rows from a band), a speck of noise (no span as long as two bricks'
/// least colour), or a stray mark: an error naming it.
fn check_thin_segments(px: &Pixels, segments: &[Rows], bands: &[Rows]) -> Result<(), Failure> {
    for stack in segments.chunk_by(|a, b| a.bottom == b.top) {
        let solid = stack.iter().any(Rows::tall);
        for s in stack.iter().filter(|s| !s.tall()) {
            // Bands are in order: the first that ends near or below the segment is the one
            // that may be near it.
            let next = bands.get(bands.partition_point(|b| b.bottom + 2 < s.top));
            let near = solid || next.is_some_and(|b| b.top <= s.bottom + 2);
            let speck = (s.top..s.bottom)
                .flat_map(|y| row_spans(px, y))
                .all(|r| r.end - r.start < 2 * MIN_COLOUR_PX);
            if !near && !speck {
                let first = row_spans(px, s.top)[0];
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
    }
    Ok(())
}

/// Splits a band where its colour dips below [`FAINT_ROW`] of the strongest rows above and
/// below: a border line between two layers drawn alike, too faint to change the colours'
/// classes.
fn split_at_faint_borders(px: &Pixels, band: Rows) -> Vec<Rows> {
    // Each row's mean saturation over the columns coloured in the band.
    let columns: Vec<usize> = majority_spans(&column_counts(px, band), band)
        .iter()
        .flat_map(|s| s.start + 1..s.end.saturating_sub(1))
        .collect();
    let strength: Vec<f32> = (band.top..band.bottom)
        .map(|y| {
            let saturation = |x: &usize| {
                let part = colour_part(px.rgb(y * px.width + x));
                part.into_iter().fold(0f32, f32::max)
            };
            columns.iter().map(saturation).sum::<f32>() / columns.len().max(1) as f32
        })
        .collect();
    let n = strength.len();
    let mut peak_above = vec![0f32; n];
    let mut peak_below = vec![0f32; n];
    for i in 1..n {
        peak_above[i] = peak_above[i - 1].max(strength[i - 1]);
        peak_below[n - 1 - i] = peak_below[n - i].max(strength[n - i]);
    }
    let dip = |i: usize| strength[i] < FAINT_ROW * peak_above[i].min(peak_below[i]);
    spans((0..n).map(|i| (!dip(i)).then_some(())), 1)
        .iter()
        .map(|s| Rows {
            top: band.top + s.start,
            bottom: band.top + s.end,
        })
        .collect()
}

/// Each column's majority colour over the band's rows (`None` where no colour has more than
/// half of them).
pub(super) fn column_classes(px: &Pixels, band: Rows) -> Vec<Option<BrickType>> {
    majority(&column_counts(px, band), band)
}

/// How many of the band's pixels in each column are of each colour.
fn column_counts(px: &Pixels, band: Rows) -> Vec<[u32; 4]> {
    let mut counts = vec![[0u32; 4]; px.width];
    for y in band.top..band.bottom {
        let row = &px.class[y * px.width..(y + 1) * px.width];
        for (count, class) in counts.iter_mut().zip(row) {
            if let Some(k) = class {
                count[k.index()] += 1;
            }
        }
    }
    counts
}

fn majority(counts: &[[u32; 4]], band: Rows) -> Vec<Option<BrickType>> {
    let rows = (band.bottom - band.top) as u32;
    let winner = |c: &[u32; 4]| (0..4).find(|&k| 2 * c[k] > rows).map(|k| BrickType::ALL[k]);
    counts.iter().map(winner).collect()
}

fn majority_spans(counts: &[[u32; 4]], band: Rows) -> Vec<Span> {
    spans(majority(counts, band).into_iter(), MIN_COLOUR_PX)
}
