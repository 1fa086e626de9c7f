//! Straight segments rasterised to grid moves (Bresenham 1965). Under 8-connectivity a step
//! may be diagonal; under 4-connectivity a diagonal step is split into its x and then its y
//! move. A segment is free when every step is a legal move (DESIGN §6), so a rasterised
//! segment is always a valid grid path.

use crate::grid::{Cell, Connectivity, Grid};

/// The cells after `a` up to and including `b` along the segment, or `None` when a step is
/// blocked or illegal.
pub fn segment(grid: &Grid, conn: Connectivity, a: Cell, b: Cell) -> Option<Vec<Cell>> {
    let mut out = Vec::new();
    walk(grid, conn, a, b, |c| out.push(c)).then_some(out)
}

/// Whether the segment `a → b` is free, without collecting it.
pub fn segment_is_free(grid: &Grid, conn: Connectivity, a: Cell, b: Cell) -> bool {
    walk(grid, conn, a, b, |_| {})
}

fn walk(grid: &Grid, conn: Connectivity, a: Cell, b: Cell, mut visit: impl FnMut(Cell)) -> bool {
    if !grid.is_free(a) || !grid.is_free(b) {
        return false;
    }
    let (x0, y0) = grid.xy(a);
    let (x1, y1) = grid.xy(b);
    let (mut x, mut y) = (x0 as i64, y0 as i64);
    let (x1, y1) = (x1 as i64, y1 as i64);
    let dx = (x1 - x).abs();
    let dy = -(y1 - y).abs();
    let sx = if x < x1 { 1 } else { -1 };
    let sy = if y < y1 { 1 } else { -1 };
    let mut err = dx + dy;
    let mut here = a;
    let mut step = |nx: i64, ny: i64, here: &mut Cell| -> bool {
        let Some(next) = grid.cell(nx, ny) else {
            return false;
        };
        if !grid.is_move(*here, next, conn) {
            return false;
        }
        visit(next);
        *here = next;
        true
    };
    while x != x1 || y != y1 {
        let e2 = 2 * err;
        let move_x = e2 >= dy;
        let move_y = e2 <= dx;
        let (nx, ny) = (
            if move_x { x + sx } else { x },
            if move_y { y + sy } else { y },
        );
        if move_x {
            err += dy;
        }
        if move_y {
            err += dx;
        }
        if move_x && move_y && conn == Connectivity::Four {
            if !step(nx, y, &mut here) || !step(nx, ny, &mut here) {
                return false;
            }
        } else if !step(nx, ny, &mut here) {
            return false;
        }
        x = nx;
        y = ny;
    }
    true
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn segments_are_legal_paths() {
        let grid = Grid::open(9, 7);
        for conn in [Connectivity::Four, Connectivity::Eight] {
            for a in 0..grid.len() as u32 {
                for b in [0u32, 8, 30, 62] {
                    let cells = segment(&grid, conn, Cell(a), Cell(b)).unwrap();
                    let mut prev = Cell(a);
                    for c in &cells {
                        assert!(grid.is_move(prev, *c, conn));
                        prev = *c;
                    }
                    assert_eq!(prev, Cell(b));
                }
            }
        }
    }

    #[test]
    fn blocked_segments_fail() {
        let mut grid = Grid::open(5, 1);
        grid.set_blocked(Cell(2), true);
        assert!(!segment_is_free(
            &grid,
            Connectivity::Eight,
            Cell(0),
            Cell(4)
        ));
        assert!(segment_is_free(
            &grid,
            Connectivity::Eight,
            Cell(0),
            Cell(1)
        ));
    }
}
