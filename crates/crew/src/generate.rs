//! Seeded test worlds: warehouse-like grids and random robot/goal placements.

use crate::grid::{Cell, Grid};
use rand::seq::SliceRandom;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// A warehouse-like grid: rows of 10×2 shelves with aisles of 3 cells, a 10-cell open border,
/// and `clutter` (a fraction) of the aisle cells blocked at random, as pallets and debris.
/// The largest connected free region is kept; cut-off pockets are blocked.
pub fn warehouse(width: u32, height: u32, clutter: f64, seed: u64) -> Grid {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut grid = Grid::open(width, height);
    let margin = 10;
    let (shelf_w, shelf_h, aisle) = (10, 2, 3);
    let mut y = margin;
    while y + shelf_h + margin <= height {
        let mut x = margin;
        while x + shelf_w + margin <= width {
            for dy in 0..shelf_h {
                for dx in 0..shelf_w {
                    let c = grid.cell((x + dx) as i64, (y + dy) as i64).expect("inside");
                    grid.set_blocked(c, true);
                }
            }
            x += shelf_w + aisle;
        }
        y += shelf_h + aisle;
    }
    for i in 0..grid.len() as u32 {
        if grid.is_free(Cell(i)) && rng.gen_bool(clutter.clamp(0.0, 1.0)) {
            grid.set_blocked(Cell(i), true);
        }
    }
    keep_largest_region(&mut grid);
    grid
}

/// Blocks every free cell outside the largest 4-connected free region.
pub fn keep_largest_region(grid: &mut Grid) {
    let mut label = vec![u32::MAX; grid.len()];
    let mut sizes = Vec::new();
    for s in 0..grid.len() as u32 {
        if !grid.is_free(Cell(s)) || label[s as usize] != u32::MAX {
            continue;
        }
        let id = sizes.len() as u32;
        let mut size = 0usize;
        let mut stack = vec![Cell(s)];
        label[s as usize] = id;
        while let Some(c) = stack.pop() {
            size += 1;
            grid.for_each_move(c, crate::grid::Connectivity::Four, |n, _| {
                if label[n.0 as usize] == u32::MAX {
                    label[n.0 as usize] = id;
                    stack.push(n);
                }
            });
        }
        sizes.push(size);
    }
    let Some(best) = (0..sizes.len()).max_by_key(|&i| (sizes[i], std::cmp::Reverse(i))) else {
        return;
    };
    for (i, &l) in label.iter().enumerate() {
        if l != u32::MAX && l != best as u32 {
            grid.set_blocked(Cell(i as u32), true);
        }
    }
}

/// `n` distinct start cells and `n` distinct goal cells, drawn from the free cells.
/// Panics if there are fewer than `n` free cells.
pub fn random_tasks(grid: &Grid, n: usize, seed: u64) -> (Vec<Cell>, Vec<Cell>) {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let free: Vec<Cell> = (0..grid.len() as u32)
        .map(Cell)
        .filter(|&c| grid.is_free(c))
        .collect();
    assert!(free.len() >= n, "not enough free cells");
    let starts: Vec<Cell> = free.choose_multiple(&mut rng, n).copied().collect();
    let goals: Vec<Cell> = free.choose_multiple(&mut rng, n).copied().collect();
    (starts, goals)
}

/// A bird's-eye scene for `mason generate scene`: a [`warehouse`] grid (`clutter` 0.005, as
/// `bench paper`) with `n` robots and `n` goals on distinct free cells. No two robots and no
/// two goals touch (4-neighbours), so that each reads back from its image
/// ([`crate::image::birdseye_png`]) as its own blob. `None` when the grid has too little room.
pub fn birdseye_scene(
    width: u32,
    height: u32,
    n: usize,
    seed: u64,
) -> Option<(Grid, Vec<Cell>, Vec<Cell>)> {
    let grid = warehouse(width, height, 0.005, seed);
    let mut rng = ChaCha8Rng::seed_from_u64(seed ^ 0x5ce7e);
    let mut free: Vec<Cell> = (0..grid.len() as u32)
        .map(Cell)
        .filter(|&c| grid.is_free(c))
        .collect();
    free.shuffle(&mut rng);
    let mut taken = vec![false; grid.len()];
    let pick = |taken: &mut Vec<bool>| {
        let mut marked = vec![false; grid.len()];
        let mut chosen = Vec::with_capacity(n);
        for &c in &free {
            if chosen.len() == n {
                break;
            }
            let mut touches = false;
            grid.for_each_move(c, crate::grid::Connectivity::Four, |m, _| {
                touches |= marked[m.0 as usize];
            });
            if taken[c.0 as usize] || touches {
                continue;
            }
            marked[c.0 as usize] = true;
            taken[c.0 as usize] = true;
            chosen.push(c);
        }
        (chosen.len() == n).then_some(chosen)
    };
    let robots = pick(&mut taken)?;
    let goals = pick(&mut taken)?;
    Some((grid, robots, goals))
}
