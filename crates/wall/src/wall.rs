//! A wall: its bricks, the precedence DAG (supports) and the neighbour relation.

use crate::brick::{Brick, BrickId, Origin, NEIGHBOUR_GAP};
use crate::error::{Location, WallError, WallErrorKind};
use serde::Serialize;

/// A validated wall design.
///
/// Invariants, established by [`Wall::from_bricks`]: there is at least one brick; every brick
/// above level 1 has at least one support; supports are exactly the bricks of the level below,
/// in the same segment, whose footprints overlap by more than 1 mm; neighbours are symmetric.
#[derive(Clone, Debug, Serialize)]
pub struct Wall {
    name: String,
    bricks: Vec<Brick>,
    supports: Vec<Vec<BrickId>>,
    carried: Vec<Vec<BrickId>>,
    neighbours: Vec<Vec<BrickId>>,
    levels: u32,
    warnings: Vec<String>,
    overlapping_pairs: usize,
}

fn location_of(origin: Origin) -> Location {
    match origin {
        Origin::None => Location::Whole,
        Origin::Line(l) => Location::Line(l),
        Origin::Pixel(x, y) => Location::Pixel(x, y),
    }
}

/// Bricks of one level sorted by left edge, with the longest x-extent among them.
struct LevelIndex {
    sorted: Vec<usize>,
    max_extent: f64,
}

impl LevelIndex {
    fn new(bricks: &[Brick], members: &[usize]) -> Self {
        let mut sorted = members.to_vec();
        sorted.sort_by(|&a, &b| {
            bricks[a]
                .footprint
                .x0
                .total_cmp(&bricks[b].footprint.x0)
                .then(a.cmp(&b))
        });
        let max_extent = members
            .iter()
            .map(|&i| bricks[i].footprint.x1 - bricks[i].footprint.x0)
            .fold(0.0, f64::max);
        LevelIndex { sorted, max_extent }
    }

    /// Bricks whose x-interval may come within `slack` of `[x0, x1]`.
    fn near<'a>(
        &'a self,
        bricks: &'a [Brick],
        x0: f64,
        x1: f64,
        slack: f64,
    ) -> impl Iterator<Item = usize> + 'a {
        let lo = x0 - self.max_extent - slack - 1e-9;
        let start = self
            .sorted
            .partition_point(|&i| bricks[i].footprint.x0 < lo);
        self.sorted[start..]
            .iter()
            .copied()
            .take_while(move |&i| bricks[i].footprint.x0 <= x1 + slack + 1e-9)
    }
}

impl Wall {
    /// Builds a wall from bricks, computing supports and neighbours (DESIGN §3).
    ///
    /// `source_name` names the input in errors. Fails on an empty wall and on a floating
    /// brick. Same-level bricks whose footprints overlap are reported in [`Wall::warnings`].
    pub fn from_bricks(source_name: &str, bricks: Vec<Brick>) -> Result<Wall, WallError> {
        Self::build(source_name, bricks, false)
    }

    /// [`Wall::from_bricks`], except that a brick above level 1 with nothing under it is
    /// accepted with no supports (CMCP walls, DESIGN §3); one warning counts such bricks.
    pub fn from_bricks_allowing_floating(
        source_name: &str,
        bricks: Vec<Brick>,
    ) -> Result<Wall, WallError> {
        Self::build(source_name, bricks, true)
    }

    fn build(
        source_name: &str,
        bricks: Vec<Brick>,
        allow_floating: bool,
    ) -> Result<Wall, WallError> {
        if bricks.is_empty() {
            return Err(WallError::new(
                source_name,
                Location::Whole,
                WallErrorKind::Empty,
            ));
        }
        if bricks.len() > crate::limits::MAX_BRICKS {
            return Err(WallError::new(
                source_name,
                Location::Whole,
                WallErrorKind::TooLarge {
                    what: "bricks",
                    limit: crate::limits::MAX_BRICKS as u64,
                    name: "MAX_BRICKS",
                },
            ));
        }
        let levels = bricks.iter().map(|b| b.level).max().unwrap_or(0);
        let mut by_level: Vec<Vec<usize>> = vec![Vec::new(); levels as usize + 1];
        for (i, b) in bricks.iter().enumerate() {
            by_level[b.level as usize].push(i);
        }
        let index: Vec<LevelIndex> = by_level
            .iter()
            .map(|m| LevelIndex::new(&bricks, m))
            .collect();

        let n = bricks.len();
        let mut supports = vec![Vec::new(); n];
        let mut carried = vec![Vec::new(); n];
        let mut neighbours = vec![Vec::new(); n];
        let mut warnings = Vec::new();
        let mut floating = 0usize;
        let mut overlapping_pairs = 0usize;
        let mut pairs = 0usize;
        let too_many_pairs = || {
            WallError::new(
                source_name,
                Location::Whole,
                WallErrorKind::TooLarge {
                    what: "related brick pairs (supports, neighbours, overlaps)",
                    limit: crate::limits::MAX_PAIRS as u64,
                    name: "MAX_PAIRS",
                },
            )
        };

        for (i, b) in bricks.iter().enumerate() {
            let f = &b.footprint;
            if b.level > 1 {
                let below = &index[b.level as usize - 1];
                for j in below.near(&bricks, f.x0, f.x1, 0.0) {
                    let s = &bricks[j];
                    if s.segment == b.segment && s.footprint.overlaps(f) {
                        supports[i].push(BrickId(j as u32));
                        carried[j].push(BrickId(i as u32));
                        pairs += 1;
                        if pairs > crate::limits::MAX_PAIRS {
                            return Err(too_many_pairs());
                        }
                    }
                }
                if supports[i].is_empty() && allow_floating {
                    floating += 1;
                } else if supports[i].is_empty() {
                    return Err(WallError::new(
                        source_name,
                        location_of(b.origin),
                        WallErrorKind::FloatingBrick {
                            label: b.label,
                            kind: b.kind,
                            level: b.level,
                        },
                    ));
                }
            }
            let same = &index[b.level as usize];
            for j in same.near(&bricks, f.x0, f.x1, NEIGHBOUR_GAP) {
                let o = &bricks[j];
                if j <= i || o.segment != b.segment {
                    continue;
                }
                if o.footprint.overlaps(f) || o.footprint.faces(f) {
                    pairs += 1;
                    if pairs > crate::limits::MAX_PAIRS {
                        return Err(too_many_pairs());
                    }
                }
                if o.footprint.overlaps(f) {
                    overlapping_pairs += 1;
                }
                if o.footprint.overlaps(f)
                    && overlapping_pairs <= crate::limits::MAX_OVERLAP_WARNINGS
                {
                    warnings.push(format!(
                        "bricks {} and {} on level {} overlap by {:.3} m × {:.3} m",
                        b.label,
                        o.label,
                        b.level,
                        o.footprint.x_overlap(f),
                        o.footprint.y_overlap(f)
                    ));
                }
                if o.footprint.faces(f) {
                    neighbours[i].push(BrickId(j as u32));
                    neighbours[j].push(BrickId(i as u32));
                }
            }
        }
        if overlapping_pairs > crate::limits::MAX_OVERLAP_WARNINGS {
            warnings.push(format!(
                "… and {} more pairs of same-level bricks overlap (the first {} are listed)",
                overlapping_pairs - crate::limits::MAX_OVERLAP_WARNINGS,
                crate::limits::MAX_OVERLAP_WARNINGS
            ));
        }
        if floating > 0 {
            warnings.push(format!(
                "{floating} brick(s) above level 1 rest on nothing in the layer below; they are planned with no predecessor"
            ));
        }
        for list in supports
            .iter_mut()
            .chain(carried.iter_mut())
            .chain(neighbours.iter_mut())
        {
            list.sort_unstable();
            list.dedup();
        }
        Ok(Wall {
            name: source_name.to_string(),
            bricks,
            supports,
            carried,
            neighbours,
            levels,
            warnings,
            overlapping_pairs,
        })
    }

    /// The wall's name (its file, or the built-in name).
    pub fn name(&self) -> &str {
        &self.name
    }

    /// Number of bricks.
    pub fn len(&self) -> usize {
        self.bricks.len()
    }

    /// Always false: a wall has at least one brick.
    pub fn is_empty(&self) -> bool {
        self.bricks.is_empty()
    }

    /// Number of levels.
    pub fn levels(&self) -> u32 {
        self.levels
    }

    /// All bricks, indexed by [`BrickId`].
    pub fn bricks(&self) -> &[Brick] {
        &self.bricks
    }

    /// One brick.
    pub fn brick(&self, id: BrickId) -> &Brick {
        &self.bricks[id.index()]
    }

    /// All brick ids in index order.
    pub fn ids(&self) -> impl Iterator<Item = BrickId> + '_ {
        (0..self.bricks.len() as u32).map(BrickId)
    }

    /// The bricks that must be placed before `id`.
    pub fn supports(&self, id: BrickId) -> &[BrickId] {
        &self.supports[id.index()]
    }

    /// The bricks that rest on `id`.
    pub fn carried(&self, id: BrickId) -> &[BrickId] {
        &self.carried[id.index()]
    }

    /// The neighbours of `id` (DESIGN §3).
    pub fn neighbours(&self, id: BrickId) -> &[BrickId] {
        &self.neighbours[id.index()]
    }

    /// How many pairs of same-level bricks overlap (a CMCP wall may have some).
    pub fn overlapping_pairs(&self) -> usize {
        self.overlapping_pairs
    }

    /// What a reader accepted but a person should know (overlapping same-level bricks, at most
    /// [`crate::limits::MAX_OVERLAP_WARNINGS`] of them one by one; floating bricks).
    pub fn warnings(&self) -> &[String] {
        &self.warnings
    }

    /// The brick with this display label, if any.
    pub fn by_label(&self, label: u32) -> Option<BrickId> {
        self.bricks
            .iter()
            .position(|b| b.label == label)
            .map(|i| BrickId(i as u32))
    }
}
