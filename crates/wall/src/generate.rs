//! Seeded random wall designs, for property tests and benchmarks.

use crate::brick::BrickType;
use rand::Rng;

/// The size of the walls to generate.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct WallShape {
    /// Segments: from 1 to this many.
    pub max_segments: usize,
    /// Levels: from 1 to this many.
    pub max_levels: usize,
    /// Width of the bottom layer of a segment, in 0.30 m units: from 3 to this.
    pub max_units: usize,
    /// Whether to use orange bricks.
    pub orange: bool,
}

impl Default for WallShape {
    fn default() -> Self {
        WallShape {
            max_segments: 2,
            max_levels: 4,
            max_units: 14,
            orange: true,
        }
    }
}

/// A random valid layer-text wall (top layer first): every brick above level 1 rests on a
/// brick below. The bottom layer may contain empty slots.
pub fn random_layer_text(rng: &mut impl Rng, shape: &WallShape) -> String {
    let segments = rng.gen_range(1..=shape.max_segments.max(1));
    let levels = rng.gen_range(1..=shape.max_levels.max(1));
    let kinds = if shape.orange { 4 } else { 3 };
    let mut layers: Vec<Vec<String>> = vec![Vec::new(); levels];
    for s in 0..segments {
        let mut below: Option<Vec<bool>> = None; // occupied unit columns of the layer below
        for layer in layers.iter_mut() {
            let mut cols = Vec::new();
            let mut words = Vec::new();
            let limit = below
                .as_ref()
                .map_or_else(|| rng.gen_range(3..=shape.max_units.max(3)), |b| b.len());
            while cols.len() < limit {
                let mut kind = BrickType::ALL[rng.gen_range(0..kinds)];
                if below.is_none() && cols.len() + kind.units() as usize > limit {
                    kind = BrickType::Red;
                }
                let units = kind.units() as usize;
                let start = cols.len();
                let fits = start + units <= limit;
                let supported = below
                    .as_ref()
                    .is_none_or(|b| fits && b[start..start + units].iter().any(|&c| c));
                let empty_ok = below.is_none() && start > 0 && rng.gen_bool(0.1);
                if fits && supported && !empty_ok {
                    words.push(kind.token().to_string());
                    cols.extend(std::iter::repeat_n(true, units));
                } else if below.is_some() && !fits {
                    break;
                } else {
                    words.push(".".into());
                    cols.push(false);
                }
            }
            while words.last().is_some_and(|w| w == ".") {
                words.pop();
                cols.pop();
            }
            if cols.iter().all(|c| !c) {
                break;
            }
            if s > 0 {
                layer.push("|".into());
            }
            layer.extend(words);
            below = Some(cols);
        }
    }
    let lines: Vec<String> = layers
        .iter()
        .filter(|l| l.iter().any(|w| w != "|" && w != "."))
        .map(|l| l.join(" "))
        .collect();
    lines.into_iter().rev().collect::<Vec<_>>().join("\n")
}

/// A layer wall of about `bricks` bricks: `levels` levels, each segment a pyramid-free
/// running bond of red and green bricks, for scaling benchmarks.
pub fn large_layer_text(rng: &mut impl Rng, bricks: usize, levels: usize) -> String {
    let levels = levels.max(1);
    let per_level = bricks.div_ceil(levels).max(1);
    let mut lines = Vec::with_capacity(levels);
    for level in 0..levels {
        let mut words = Vec::with_capacity(per_level);
        // Each layer is the same width: offset odd layers by starting with a red.
        let mut units = 0;
        let width = per_level * 3 / 2;
        while units < width {
            let kind = if (level % 2 == 1 && units == 0) || rng.gen_bool(0.5) {
                BrickType::Red
            } else {
                BrickType::Green
            };
            let kind = if units + kind.units() as usize > width {
                BrickType::Red
            } else {
                kind
            };
            units += kind.units() as usize;
            words.push(kind.token().to_string());
        }
        lines.push(words.join(" "));
    }
    lines.reverse();
    lines.join("\n")
}
