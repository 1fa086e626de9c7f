//! The reservation table of prioritized planning: which robot holds which cell at which step,
//! which moves are under way, and where robots rest on their goals for good.

use crate::grid::{Cell, Grid};
use rustc_hash::FxHashMap;

/// A conflict with a reserved robot.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Clash {
    /// The robot already reserved.
    pub other: u32,
    /// True when that robot rests on its goal there for good (no wait can help).
    pub resting: bool,
}

/// Reserved cells and moves of the robots planned so far.
#[derive(Clone, Debug, Default)]
pub struct ReservationTable {
    vertex: FxHashMap<(u32, u32), u32>,
    moves: FxHashMap<(u32, u32, u32), u32>,
    resting: FxHashMap<u32, (u32, u32)>,
    last_use: FxHashMap<u32, u32>,
    horizon: u32,
}

impl ReservationTable {
    /// An empty table.
    pub fn new() -> Self {
        ReservationTable::default()
    }

    /// The last step at which any reserved robot still moves.
    pub fn horizon(&self) -> u32 {
        self.horizon
    }

    /// Reserves `path` for `robot`, who then rests on its last cell.
    pub fn reserve(&mut self, robot: u32, path: &[Cell]) {
        let last = path.len() - 1;
        for (t, w) in path.windows(2).enumerate() {
            let t = t as u32;
            self.vertex.insert((w[0].0, t), robot);
            let used = self.last_use.entry(w[0].0).or_insert(0);
            *used = (*used).max(t);
            if w[0] != w[1] {
                self.moves.insert((w[0].0, w[1].0, t), robot);
            }
        }
        self.resting.insert(path[last].0, (last as u32, robot));
        self.horizon = self.horizon.max(last as u32);
    }

    /// Who holds `cell` at step `t`, if anyone.
    pub fn occupant(&self, cell: Cell, t: u32) -> Option<Clash> {
        if let Some(&other) = self.vertex.get(&(cell.0, t)) {
            return Some(Clash {
                other,
                resting: false,
            });
        }
        match self.resting.get(&cell.0) {
            Some(&(from, other)) if from <= t => Some(Clash {
                other,
                resting: true,
            }),
            _ => None,
        }
    }

    /// The clash, if any, of moving (or waiting, when `a == b`) from `a` at step `t` to `b` at
    /// step `t + 1`: the target cell is held, or another robot swaps with it, or crosses its
    /// diagonal in the same 2×2 square.
    pub fn move_clash(&self, grid: &Grid, a: Cell, b: Cell, t: u32) -> Option<Clash> {
        if let Some(c) = self.occupant(b, t + 1) {
            return Some(c);
        }
        if a == b {
            return None;
        }
        let edge = |from: Cell, to: Cell| {
            self.moves.get(&(from.0, to.0, t)).map(|&other| Clash {
                other,
                resting: false,
            })
        };
        if let Some(c) = edge(b, a) {
            return Some(c);
        }
        let (ax, ay) = grid.xy(a);
        let (bx, by) = grid.xy(b);
        if ax != bx && ay != by {
            let c = grid.cell(bx as i64, ay as i64).expect("inside");
            let d = grid.cell(ax as i64, by as i64).expect("inside");
            return edge(c, d).or_else(|| edge(d, c));
        }
        None
    }

    /// The first step from which a robot may rest on `cell` for good: after every reserved
    /// visit. `None` when another robot rests there.
    pub fn free_for_good_from(&self, cell: Cell) -> Option<u32> {
        if self.resting.contains_key(&cell.0) {
            return None;
        }
        Some(self.last_use.get(&cell.0).map_or(0, |t| t + 1))
    }
}
