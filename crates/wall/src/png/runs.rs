//! Step 3, *find runs*: in each layer, the runs of one colour, with sub-pixel edges.

use super::*;

/// A column inside a run holding less than this share of its colour is a faint border.
const DIP_COVERAGE: f64 = 0.75;
/// A column holding this share of a run's colour is full colour.
const FULL_COVERAGE: f64 = 0.9;
/// Two colours blend into each other across at most this many unclassified columns.
const BLEND_GAP_PX: usize = 2;

/// A run of one colour in one layer, with sub-pixel edges.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Run {
    /// Index of the layer, top to bottom.
    pub(super) layer: usize,
    pub(super) kind: BrickType,
    /// Left edge of the colour (px, sub-pixel).
    pub(super) left: f64,
    /// Right edge of the colour (px, sub-pixel).
    pub(super) right: f64,
    /// A pixel inside the run, for messages.
    pub(super) pixel: (u32, u32),
    /// Whether the left and right edges are blends with a touching run, found on the grid
    /// line itself rather than half a border from it.
    pub(super) blended: (bool, bool),
    /// The first column classified as the run's colour.
    pub(super) first_column: usize,
    /// How much of the colour each column from `first_column` on holds, in [0, 1].
    pub(super) coverage: Vec<f32>,
}

impl Run {
    pub(super) fn width(&self) -> f64 {
        self.right - self.left
    }
}

/// The narrowest run's width per unit of its colour's length (px): the unit less at most a
/// border, or more where a run is several bricks.
pub(super) fn narrowest_per_unit(runs: &[Run]) -> f64 {
    let per_unit = |r: &Run| r.width() / f64::from(r.kind.units());
    runs.iter().map(per_unit).fold(f64::INFINITY, f64::min)
}

/// The mean colour of each column over the layer's rows.
pub(super) fn column_means(px: &Pixels, layer: Rows) -> Vec<[f32; 3]> {
    let column = |x| mean_colour((layer.top..layer.bottom).map(|y| px.rgb(y * px.width + x)));
    (0..px.width).map(column).collect()
}

/// Step 3: the runs of every layer with sub-pixel edges.
///
/// A run shorter than [`MIN_COLOUR_PX`] that touches another is the blend where two colours
/// meet and belongs to the gap between them; alone, it is an error. Each run owns the columns
/// up to half-way to its neighbours (at most [`EDGE_REACH`] past its last coloured column),
/// and its width and centre are the area and centroid of its colour over them.
pub(super) fn find_runs(px: &Pixels, layers: &[Rows]) -> Result<Vec<Run>, Failure> {
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
            // Where the run blends into a touching one, the edge is their junction. Towards a
            // border or the background, it is where the colour's area ends; the gap's columns
            // are shared half-way with the neighbour (the middle column of an odd gap, which
            // is border, with neither).
            let blend_left = i.checked_sub(1).and_then(|j| junction[j]);
            let blend_right = junction.get(i).copied().flatten();
            let left = blend_left.unwrap_or_else(|| {
                let mut limit = s.start.saturating_sub(EDGE_REACH);
                if let Some(previous) = i.checked_sub(1).map(|j| kept[j]) {
                    limit = limit.max((previous.end + s.start).div_ceil(2));
                }
                inner_left as f64 - area(limit..inner_left)
            });
            let right = blend_right.unwrap_or_else(|| {
                let mut limit = (s.end + EDGE_REACH).min(px.width);
                if let Some(next) = kept.get(i + 1) {
                    limit = limit.min((s.end + next.start) / 2);
                }
                inner_right as f64 + area(inner_right..limit)
            });
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
                blended: (blend_left.is_some(), blend_right.is_some()),
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
pub(super) fn split_at_dips(means: &[[f32; 3]], run: Span) -> Vec<Span> {
    let k = reference_colour(means, run);
    let c: Vec<f64> = (run.start..run.end)
        .map(|x| coverage(means[x], k))
        .collect();
    let full = |range: std::ops::Range<usize>| range.into_iter().any(|i| c[i] >= FULL_COVERAGE);
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
pub(super) fn colour_junction(
    means: &[[f32; 3]],
    pair: &[Span],
    colours: &[[f32; 3]],
) -> Option<f64> {
    let (a, b) = (pair[0], pair[1]);
    // Two pieces of one colour (split at a faint border) do not blend.
    if a.kind == b.kind || b.start - a.end > BLEND_GAP_PX {
        return None;
    }
    let blend = Blend::new(colours[0], colours[1])?;
    if (a.end - 1..b.start + 1).any(|x| !blend.holds(means[x])) {
        return None;
    }
    let from = a.end.saturating_sub(EDGE_REACH).max((a.start + a.end) / 2);
    let to = (b.start + EDGE_REACH).min((b.start + b.end) / 2);
    let first_share: f64 = (from..to)
        .map(|x| 1.0 - f64::from(blend.share_of_second(means[x])))
        .sum();
    Some(from as f64 + first_share)
}

/// A run's colour: the median of its columns, its two edge columns left out.
pub(super) fn reference_colour(means: &[[f32; 3]], run: Span) -> [f32; 3] {
    if run.end - run.start > 2 {
        median_colour(&means[run.start + 1..run.end - 1])
    } else {
        median_colour(&means[run.start..run.end])
    }
}

pub(super) fn median_colour(columns: &[[f32; 3]]) -> [f32; 3] {
    let mut out = [0f32; 3];
    for (c, o) in out.iter_mut().enumerate() {
        let mut v: Vec<f32> = columns.iter().map(|p| p[c]).collect();
        v.sort_by(f32::total_cmp);
        *o = v[v.len() / 2];
    }
    out
}
