//! The grid world: free and blocked cells, and the moves allowed between them (DESIGN §6).

use serde::Serialize;

/// A grid cell, as a dense row-major index. Use [`Grid::xy`] for (column, row).
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize)]
pub struct Cell(pub u32);

/// Which moves a robot may make in one time step (besides waiting).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize)]
pub enum Connectivity {
    /// Up, down, left, right.
    Four,
    /// Also the diagonals, each only when both orthogonal cells beside it are free.
    Eight,
}

impl Connectivity {
    /// 4 or 8.
    pub fn degree(self) -> u32 {
        match self {
            Connectivity::Four => 4,
            Connectivity::Eight => 8,
        }
    }
}

impl std::str::FromStr for Connectivity {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        match s {
            "4" => Ok(Connectivity::Four),
            "8" => Ok(Connectivity::Eight),
            _ => Err(format!("connectivity must be 4 or 8, not `{s}`")),
        }
    }
}

/// Offsets of the 8 moves: orthogonal first, then diagonal.
pub(crate) const MOVES: [(i32, i32); 8] = [
    (1, 0),
    (-1, 0),
    (0, 1),
    (0, -1),
    (1, 1),
    (1, -1),
    (-1, 1),
    (-1, -1),
];

/// A rectangular occupancy grid.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Grid {
    width: u32,
    height: u32,
    blocked: Vec<bool>,
}

impl Grid {
    /// A grid from row-major blocked flags. Panics if the length is not `width · height`.
    pub fn new(width: u32, height: u32, blocked: Vec<bool>) -> Self {
        assert_eq!(blocked.len(), width as usize * height as usize);
        Grid {
            width,
            height,
            blocked,
        }
    }

    /// An empty (all free) grid.
    pub fn open(width: u32, height: u32) -> Self {
        Grid::new(width, height, vec![false; width as usize * height as usize])
    }

    /// Columns.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Rows.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// Number of cells.
    pub fn len(&self) -> usize {
        self.blocked.len()
    }

    /// True for a 0×0 grid.
    pub fn is_empty(&self) -> bool {
        self.blocked.is_empty()
    }

    /// The cell at (column, row), if it is inside the grid.
    pub fn cell(&self, x: i64, y: i64) -> Option<Cell> {
        if x < 0 || y < 0 || x >= self.width as i64 || y >= self.height as i64 {
            None
        } else {
            Some(Cell(y as u32 * self.width + x as u32))
        }
    }

    /// (column, row) of a cell.
    pub fn xy(&self, c: Cell) -> (u32, u32) {
        (c.0 % self.width, c.0 / self.width)
    }

    /// Whether a robot may stand on the cell.
    pub fn is_free(&self, c: Cell) -> bool {
        !self.blocked[c.0 as usize]
    }

    /// Marks a cell blocked or free.
    pub fn set_blocked(&mut self, c: Cell, blocked: bool) {
        self.blocked[c.0 as usize] = blocked;
    }

    /// Number of free cells.
    pub fn free_count(&self) -> usize {
        self.blocked.iter().filter(|b| !**b).count()
    }

    /// Whether (x, y) is inside and free.
    fn free_at(&self, x: i64, y: i64) -> bool {
        self.cell(x, y).is_some_and(|c| self.is_free(c))
    }

    /// Calls `f` for every cell reachable from `c` in one move (waiting excluded).
    #[inline]
    pub fn for_each_move(&self, c: Cell, conn: Connectivity, mut f: impl FnMut(Cell, bool)) {
        let (x, y) = self.xy(c);
        let (x, y) = (x as i64, y as i64);
        for &(dx, dy) in &MOVES[..conn.degree() as usize] {
            let (nx, ny) = (x + dx as i64, y + dy as i64);
            if !self.free_at(nx, ny) {
                continue;
            }
            let diagonal = dx != 0 && dy != 0;
            if diagonal && !(self.free_at(x + dx as i64, y) && self.free_at(x, y + dy as i64)) {
                continue;
            }
            f(Cell(ny as u32 * self.width + nx as u32), diagonal);
        }
    }

    /// The cells reachable from `c` in one move, with whether the move is diagonal.
    pub fn moves(&self, c: Cell, conn: Connectivity) -> Vec<(Cell, bool)> {
        let mut out = Vec::with_capacity(8);
        self.for_each_move(c, conn, |n, d| out.push((n, d)));
        out
    }

    /// Whether `a → b` is a legal single move (not a wait) under `conn`.
    pub fn is_move(&self, a: Cell, b: Cell, conn: Connectivity) -> bool {
        let (ax, ay) = self.xy(a);
        let (bx, by) = self.xy(b);
        let dx = bx as i64 - ax as i64;
        let dy = by as i64 - ay as i64;
        if dx.abs() > 1 || dy.abs() > 1 || (dx == 0 && dy == 0) {
            return false;
        }
        if !self.is_free(a) || !self.is_free(b) {
            return false;
        }
        if dx != 0 && dy != 0 {
            conn == Connectivity::Eight
                && self.free_at(ax as i64 + dx, ay as i64)
                && self.free_at(ax as i64, ay as i64 + dy)
        } else {
            true
        }
    }

    /// Straight-line (Euclidean) distance between cell centres.
    pub fn euclidean(&self, a: Cell, b: Cell) -> f64 {
        let (ax, ay) = self.xy(a);
        let (bx, by) = self.xy(b);
        let dx = ax as f64 - bx as f64;
        let dy = ay as f64 - by as f64;
        (dx * dx + dy * dy).sqrt()
    }

    /// The admissible heuristic for path length: octile with 8-connectivity, Manhattan with 4.
    pub fn octile(&self, a: Cell, b: Cell, conn: Connectivity) -> f64 {
        let (ax, ay) = self.xy(a);
        let (bx, by) = self.xy(b);
        let dx = ax.abs_diff(bx) as f64;
        let dy = ay.abs_diff(by) as f64;
        match conn {
            Connectivity::Four => dx + dy,
            Connectivity::Eight => {
                let (lo, hi) = if dx < dy { (dx, dy) } else { (dy, dx) };
                hi + (std::f64::consts::SQRT_2 - 1.0) * lo
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn diagonal_needs_both_sides_free() {
        let mut g = Grid::open(3, 3);
        let a = g.cell(0, 0).unwrap();
        let d = g.cell(1, 1).unwrap();
        assert!(g.is_move(a, d, Connectivity::Eight));
        assert!(!g.is_move(a, d, Connectivity::Four));
        g.set_blocked(g.cell(1, 0).unwrap(), true);
        assert!(!g.is_move(a, d, Connectivity::Eight));
        assert_eq!(g.moves(a, Connectivity::Eight).len(), 1);
    }

    #[test]
    fn cells_outside_are_none() {
        let g = Grid::open(4, 2);
        assert_eq!(g.cell(4, 0), None);
        assert_eq!(g.cell(-1, 0), None);
        assert_eq!(g.xy(g.cell(3, 1).unwrap()), (3, 1));
    }
}
