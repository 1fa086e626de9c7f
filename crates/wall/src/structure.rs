//! Seeded large structures in CMCP's file format (`id type x y z yaw_rotated`, `yaml` sizes),
//! for the assembly-scale figures: a straight wall, an L, a tower (a closed square ring) and
//! storeys.
//!
//! Every layer runs along the same legs, so every brick above the first layer rests on the
//! layer below (no floating bricks, no overlaps). A leg is filled with red and green bricks
//! in a running bond (odd layers start with a red, so joints do not line up); with `storeys`
//! greater than 1 the top layer of each storey but the last is a ring beam of orange bricks
//! (two UAVs each), filled out with reds. Lengths are whole units of 0.30 m, so coordinates
//! are exact. O(bricks) time and memory.
//!
//! ```
//! use mason_wall::structure::{structure_cmcp, Shape, Structure};
//! use rand::SeedableRng;
//! let s = Structure { shape: Shape::L, bricks: 200, levels: 4, storeys: 2 };
//! let text = structure_cmcp(&mut rand_chacha::ChaCha8Rng::seed_from_u64(1), &s);
//! let wall = mason_wall::parse_cmcp_strict(&text, "l", mason_wall::CmcpSizes::Yaml).unwrap();
//! assert!(wall.len() >= 150);
//! ```

use crate::brick::{BrickType, BRICK_DEPTH, BRICK_HEIGHT, UNIT_LENGTH};
use rand::Rng;
use std::fmt::Write;

/// The plan of a structure.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Shape {
    /// One straight leg along x.
    Wall,
    /// Two legs at a right angle: along x, and along y from its start.
    L,
    /// A closed square ring of four legs.
    Tower,
}

impl Shape {
    /// `wall`, `l` or `tower`.
    pub fn parse(s: &str) -> Option<Shape> {
        match s {
            "wall" => Some(Shape::Wall),
            "l" => Some(Shape::L),
            "tower" => Some(Shape::Tower),
            _ => None,
        }
    }
}

/// What to generate: about `bricks` bricks over `levels` layers in all, split into `storeys`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Structure {
    /// The plan.
    pub shape: Shape,
    /// About this many bricks.
    pub bricks: usize,
    /// Layers in all (at least one per storey).
    pub levels: usize,
    /// Storeys: every storey's top layer but the last is an orange ring beam.
    pub storeys: usize,
}

/// One leg: where it starts (units), whether it runs along y, its length (units).
struct Leg {
    x0: i64,
    y0: i64,
    along_y: bool,
    units: i64,
}

/// The legs of `shape` with `total` units of run per layer. A leg along x at y = 0 occupies
/// y ∈ [0, depth]; legs along y start past it, so that legs never overlap.
fn legs(shape: Shape, total: i64) -> Vec<Leg> {
    match shape {
        Shape::Wall => vec![Leg {
            x0: 0,
            y0: 0,
            along_y: false,
            units: total.max(1),
        }],
        Shape::L => {
            let half = (total / 2).max(1);
            vec![
                Leg {
                    x0: 0,
                    y0: 0,
                    along_y: false,
                    units: half,
                },
                Leg {
                    x0: 0,
                    y0: 1,
                    along_y: true,
                    units: (total - half).max(1),
                },
            ]
        }
        Shape::Tower => {
            // Side s (units): two legs along x of s units at y = 0 and y = s, two along y of
            // s − 1 units between them (a unit, 0.30 m, clears the depth of 0.20 m).
            let side = ((total + 2) / 4).max(2);
            vec![
                Leg {
                    x0: 0,
                    y0: 0,
                    along_y: false,
                    units: side,
                },
                Leg {
                    x0: 0,
                    y0: side,
                    along_y: false,
                    units: side,
                },
                Leg {
                    x0: 0,
                    y0: 1,
                    along_y: true,
                    units: side - 1,
                },
                Leg {
                    x0: side - 1,
                    y0: 1,
                    along_y: true,
                    units: side - 1,
                },
            ]
        }
    }
}

/// The bricks of one leg's layer, in units from its start: (offset, type).
fn fill(rng: &mut impl Rng, units: i64, odd: bool, beam: bool) -> Vec<(i64, BrickType)> {
    let mut out = Vec::new();
    let mut at = 0;
    while at < units {
        let kind = if beam {
            BrickType::Orange
        } else if (odd && at == 0) || rng.gen_bool(0.5) {
            BrickType::Red
        } else {
            BrickType::Green
        };
        let kind = if at + i64::from(kind.units()) > units {
            BrickType::Red
        } else {
            kind
        };
        out.push((at, kind));
        at += i64::from(kind.units());
    }
    out
}

/// The CMCP text of `s` (a header line, then one brick per line, ids from 1), the same for the
/// same random state.
pub fn structure_cmcp(rng: &mut impl Rng, s: &Structure) -> String {
    let levels = s.levels.max(1);
    let storeys = s.storeys.clamp(1, levels);
    let per_level = s.bricks.div_ceil(levels).max(1) as i64;
    // Reds and greens alike: 1.5 units a brick.
    let plan = legs(s.shape, per_level * 3 / 2);
    let per_storey = levels.div_ceil(storeys);
    let mut text = String::from(
        "#brick_id brick_type brick_x_pos brick_y_pos brick_z_pos brick_yaw_rotated\n",
    );
    let mut id = 0u64;
    let half_depth = BRICK_DEPTH / 2.0;
    for level in 0..levels {
        let beam = storeys > 1 && (level + 1) % per_storey == 0 && level + 1 < levels;
        let z = BRICK_HEIGHT / 2.0 + level as f64 * BRICK_HEIGHT;
        for leg in &plan {
            for (at, kind) in fill(rng, leg.units, level % 2 == 1, beam) {
                let centre = (at as f64 + f64::from(kind.units()) / 2.0) * UNIT_LENGTH;
                let (x, y) = if leg.along_y {
                    (
                        leg.x0 as f64 * UNIT_LENGTH + half_depth,
                        leg.y0 as f64 * UNIT_LENGTH + centre,
                    )
                } else {
                    (
                        leg.x0 as f64 * UNIT_LENGTH + centre,
                        leg.y0 as f64 * UNIT_LENGTH + half_depth,
                    )
                };
                id += 1;
                let _ = writeln!(
                    text,
                    "{id} {} {x:.4} {y:.4} {z:.4} {}",
                    kind.id(),
                    u8::from(leg.along_y)
                );
            }
        }
    }
    text
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{parse_cmcp_strict, CmcpSizes};
    use rand::SeedableRng;

    fn build(shape: Shape, bricks: usize, levels: usize, storeys: usize, seed: u64) -> String {
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
        structure_cmcp(
            &mut rng,
            &Structure {
                shape,
                bricks,
                levels,
                storeys,
            },
        )
    }

    #[test]
    fn every_shape_reads_strictly_with_every_brick_supported() {
        for shape in [Shape::Wall, Shape::L, Shape::Tower] {
            for (bricks, levels, storeys) in [(60, 3, 1), (400, 8, 2), (1000, 12, 3)] {
                let text = build(shape, bricks, levels, storeys, 5);
                // Strict: no floating bricks, no overlapping bricks of one layer.
                let w = parse_cmcp_strict(&text, "gen", CmcpSizes::Yaml)
                    .unwrap_or_else(|e| panic!("{shape:?} {bricks}: {e}"));
                let n = w.len() as f64;
                assert!(
                    n >= 0.6 * bricks as f64 && n <= 1.6 * bricks as f64,
                    "{shape:?}: {n} bricks for {bricks}"
                );
                assert_eq!(
                    w.bricks().iter().map(|b| b.level).max(),
                    Some(levels as u32)
                );
                let oranges = w.bricks().iter().filter(|b| b.kind == BrickType::Orange);
                assert_eq!(oranges.count() > 0, storeys > 1, "{shape:?} {storeys}");
            }
        }
    }

    #[test]
    fn the_same_seed_gives_the_same_text() {
        assert_eq!(build(Shape::L, 500, 5, 2, 9), build(Shape::L, 500, 5, 2, 9));
        assert_ne!(
            build(Shape::L, 500, 5, 2, 9),
            build(Shape::L, 500, 5, 2, 10)
        );
    }

    #[test]
    fn shapes_parse_by_name() {
        assert_eq!(Shape::parse("tower"), Some(Shape::Tower));
        assert_eq!(Shape::parse("ring"), None);
    }
}
