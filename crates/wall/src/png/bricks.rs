//! Step 7, *cut bricks* and *assemble*: runs into bricks, bricks into a wall.

use super::*;

/// A brick found in the image: layer (top = 0), colour, first unit on the grid and a pixel
/// inside it.
#[derive(Clone, Copy, Debug)]
pub(super) struct Found {
    pub(super) layer: usize,
    pub(super) kind: BrickType,
    pub(super) first_unit: u32,
    pub(super) pixel: (u32, u32),
}

/// Step 7: a run `k` times its colour's length is `k` bricks, side by side.
pub(super) fn cut_bricks(runs: &[Run], reading: &Reading) -> Vec<Found> {
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
                first_unit: first,
                pixel: (middle.max(0.0) as u32, r.pixel.1),
            });
        }
    }
    found
}

/// Step 7, continued: levels (the bottom of the `layers` layers is level 1), labels, segments and
/// footprints.
pub(super) fn assemble(name: &str, layers: usize, found: Vec<Found>) -> Result<Wall, WallError> {
    let level = |f: &Found| (layers - f.layer) as u32;
    let mut placed = found;
    placed.sort_by_key(|f| (level(f), f.first_unit));
    let width = placed
        .iter()
        .map(|f| f.first_unit + f.kind.units())
        .max()
        .unwrap_or(0) as usize;
    let mut used = vec![false; width];
    for f in &placed {
        for u in f.first_unit..f.first_unit + f.kind.units() {
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
            segment: segment_of[f.first_unit as usize],
            footprint: Footprint {
                x0: f64::from(f.first_unit) * UNIT_LENGTH,
                x1: f64::from(f.first_unit + f.kind.units()) * UNIT_LENGTH,
                y0: 0.0,
                y1: BRICK_DEPTH,
            },
            origin: Origin::Pixel(f.pixel.0, f.pixel.1),
        });
    }
    Wall::from_bricks(name, bricks)
}
