//! Step 2, *find layers*: the horizontal bands of colour, top to bottom.

use super::*;

/// A stretch of columns `[start, end)` of one colour.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Span {
    pub(super) kind: BrickType,
    pub(super) start: usize,
    pub(super) end: usize,
}

/// Runs of one class at least `shortest` long in a sequence of classes.
pub(super) fn spans(
    classes: impl Iterator<Item = Option<BrickType>>,
    shortest: usize,
) -> Vec<Span> {
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
pub(super) fn uncovered(a: &[Span], b: &[Span]) -> bool {
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

pub(super) fn rows_differ(a: &[Span], b: &[Span]) -> bool {
    uncovered(a, b) || uncovered(b, a)
}

/// A layer: rows `[top, bottom)` of the image.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(super) struct Layer {
    pub(super) top: usize,
    pub(super) bottom: usize,
}

/// Step 2: the layers, top to bottom.
///
/// Consecutive rows whose runs agree form a segment. A segment at least [`MIN_COLOUR_PX`]
/// rows tall is a layer; a thinner one touching a layer is that layer's blurred edge (or the
/// blend between two layers) and is dropped; a thinner one standing alone is an error.
/// Touching layers whose runs agree are one layer drawn with no border.
pub(super) fn find_layers(px: &Pixels) -> Result<Vec<Layer>, Failure> {
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
pub(super) fn row_strength(px: &Pixels, band: Layer) -> Vec<f32> {
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
pub(super) fn split_at_faint_borders(px: &Pixels, band: Layer) -> Vec<Layer> {
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
pub(super) fn band_spans(px: &Pixels, layer: Layer) -> Vec<Span> {
    spans(column_classes(px, layer).into_iter(), MIN_COLOUR_PX)
}

/// Each column's majority class over the layer's rows (no class wins ties with a colour).
pub(super) fn column_classes(px: &Pixels, layer: Layer) -> Vec<Option<BrickType>> {
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
