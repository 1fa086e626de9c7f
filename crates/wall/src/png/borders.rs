//! Step 4, *see the border*: how wide the border is where it can be measured apart from the
//! bricks (between layers, or around the wall), to choose among grids.

use super::*;

/// How far past a colour's edge the border around the wall is looked for (px).
const RING_REACH: usize = 8;
/// A border around the wall differs from the paper by at least this much (RGB distance).
const MIN_RING_CONTRAST: f32 = 40.0;
/// Layers up to this far apart (px) may sit on each other, whatever the bricks' size.
const MAX_LAYER_GAP: usize = 12;

/// The border between layers (px), where layers touch: for each layer and the layer below it,
/// the mean gap between their colours over the columns where both have colour; the median
/// of that over the pairs of layers. `None` for a single layer or layers that never sit on
/// each other.
pub(super) fn border_between_layers(px: &Pixels, layers: &[Rows], runs: &[Run]) -> Option<f64> {
    // A border is narrower than MAX_BORDER_SHARE of a unit, and a brick of colour length k
    // shows at least k units less one border: so a border is at most 1.5 times (for a share
    // of 0.6) the narrowest run's width per unit of its colour. Layers farther apart than
    // that do not sit on each other.
    let widest_border = MAX_BORDER_SHARE / (1.0 - MAX_BORDER_SHARE) * narrowest_per_unit(runs);
    let max_gap = (widest_border as usize).max(MAX_LAYER_GAP);
    let mut gaps = Vec::new();
    for pair in 0..layers.len().saturating_sub(1) {
        let (upper, lower) = (layers[pair], layers[pair + 1]);
        if lower.top - upper.bottom > max_gap {
            continue;
        }
        // Where one colour sits on the same colour, no blend of two colours blurs the gap.
        let (above, below) = (
            colour_inside(px, runs, pair),
            colour_inside(px, runs, pair + 1),
        );
        let both = |x: &usize| above[*x].is_some() && below[*x].is_some();
        let all: Vec<usize> = (0..px.width).filter(both).collect();
        let alike: Vec<usize> = all
            .iter()
            .copied()
            .filter(|&x| above[x] == below[x])
            .collect();
        // Over two colours blending into each other, faint shares count (they add up to the
        // whole); over a border, a faint tint is the paper's.
        let two_colours = alike.is_empty();
        let share_of = if two_colours {
            coverage_with_tints
        } else {
            coverage
        };
        let columns = if two_colours { all } else { alike };
        if columns.is_empty() {
            continue;
        }
        let middle = (upper.bottom + lower.top) / 2;
        let upper_inner = upper
            .bottom
            .saturating_sub(2 * EDGE_REACH)
            .max((upper.top + upper.bottom) / 2);
        let lower_inner = (lower.top + 2 * EDGE_REACH).min((lower.top + lower.bottom) / 2);
        // Each column's colour in each layer, and the gap between them in each column: from
        // where the upper colour ends (its share of each row, summed down to the middle) to
        // where the lower one starts. Where two colours blend straight into each other (every
        // row between them on the line from one to the other, each pixel averaged with its
        // left and right neighbours against noise, and no grey on that line) there is no
        // border at all.
        let upper_colours = column_means(px, upper);
        let lower_colours = column_means(px, lower);
        let smoothed = |x: usize, y: usize| {
            let near = x.saturating_sub(1)..(x + 2).min(px.width);
            mean_colour(near.map(|xx| px.rgb(y * px.width + xx)))
        };
        let column_gap = |x: usize| -> f64 {
            let blends = two_colours
                && Blend::new(upper_colours[x], lower_colours[x]).is_some_and(|blend| {
                    blend.keeps_colour()
                        && (upper_inner..lower_inner).all(|y| blend.holds(smoothed(x, y)))
                });
            if blends {
                return 0.0;
            }
            let share =
                |y: usize, colours: &[[f32; 3]]| share_of(px.rgb(y * px.width + x), colours[x]);
            let colour_bottom = upper_inner as f64
                + (upper_inner..middle)
                    .map(|y| share(y, &upper_colours))
                    .sum::<f64>();
            let colour_top = lower_inner as f64
                - (middle..lower_inner)
                    .map(|y| share(y, &lower_colours))
                    .sum::<f64>();
            colour_top - colour_bottom
        };
        gaps.push(columns.iter().map(|&x| column_gap(x)).sum::<f64>() / columns.len() as f64);
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
pub(super) fn border_around_wall(px: &Pixels, layers: &[Rows], runs: &[Run]) -> Option<f64> {
    let sides = [(0, true), (layers.len() - 1, false)];
    sides.into_iter().find_map(|(index, above)| {
        let layer = layers[index];
        let inside = colour_inside(px, runs, index);
        let columns: Vec<usize> = (0..px.width).filter(|&x| inside[x].is_some()).collect();
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
        let row_mean = |y: usize| mean_colour(columns.iter().map(|&x| px.rgb(y * px.width + x)));
        let colour = mean_colour(columns.iter().map(|&x| colours[x]));
        let paper = row_mean(outward[outward.len() - 1]);
        // Each row: its share of colour, and what is left once the colour is taken out.
        let rows: Vec<(f64, f32)> = outward
            .iter()
            .map(|&y| {
                let p = row_mean(y);
                let c = coverage_with_tints(p, colour);
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

/// Per column, the colour of the layer's run that covers the whole pixel, if any: one pass
/// over the layer's runs.
pub(super) fn colour_inside(px: &Pixels, runs: &[Run], layer: usize) -> Vec<Option<BrickType>> {
    let mut map = vec![None; px.width];
    // Runs come layer by layer.
    let first = runs.partition_point(|r| r.layer < layer);
    let end = runs.partition_point(|r| r.layer <= layer);
    for r in &runs[first..end] {
        let first = r.left.max(0.0).ceil() as usize;
        let end = (r.right.max(0.0).floor() as usize).min(px.width);
        for slot in map.iter_mut().take(end).skip(first) {
            *slot = Some(r.kind);
        }
    }
    map
}
