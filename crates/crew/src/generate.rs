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
    let (label, regions) = regions(grid);
    let Some(best) = (0..regions.len()).max_by_key(|&i| (regions[i].len(), std::cmp::Reverse(i)))
    else {
        return;
    };
    for (i, &l) in label.iter().enumerate() {
        if l != u32::MAX && l != best as u32 {
            grid.set_blocked(Cell(i as u32), true);
        }
    }
}

/// The 4-connected free regions of `grid`: each cell's region (`u32::MAX` for a blocked cell)
/// and each region's cells, numbered in the order of their first cell.
fn regions(grid: &Grid) -> (Vec<u32>, Vec<Vec<Cell>>) {
    let mut label = vec![u32::MAX; grid.len()];
    let mut regions: Vec<Vec<Cell>> = Vec::new();
    for s in 0..grid.len() as u32 {
        if !grid.is_free(Cell(s)) || label[s as usize] != u32::MAX {
            continue;
        }
        let id = regions.len() as u32;
        let mut cells = vec![Cell(s)];
        label[s as usize] = id;
        let mut next = 0;
        while let Some(&c) = cells.get(next) {
            next += 1;
            grid.for_each_move(c, crate::grid::Connectivity::Four, |m, _| {
                if label[m.0 as usize] == u32::MAX {
                    label[m.0 as usize] = id;
                    cells.push(m);
                }
            });
        }
        regions.push(cells);
    }
    (label, regions)
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

/// A MovingAI-style random scenario on `grid`: `n` start–goal pairs with distinct starts,
/// distinct goals, each goal reachable from its start (both in one 4-connected free region)
/// and never equal to it. Starts are drawn uniformly from the free cells of regions of two or
/// more cells, each goal uniformly from the unused cells of its start's region. `None` only
/// when the grid has no room for `n` such pairs (more than its cells in regions of two or
/// more).
pub fn random_scenario(grid: &Grid, n: usize, seed: u64) -> Option<Vec<(Cell, Cell)>> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let (region, mut pools) = regions(grid);
    let mut starts: Vec<Cell> = pools
        .iter()
        .filter(|p| p.len() >= 2)
        .flatten()
        .copied()
        .collect();
    starts.shuffle(&mut rng);
    for pool in &mut pools {
        pool.shuffle(&mut rng);
    }
    let mut pairs: Vec<(Cell, Cell)> = Vec::with_capacity(n);
    for start in starts {
        if pairs.len() == n {
            break;
        }
        let r = region[start.0 as usize];
        let pool = &mut pools[r as usize];
        // The pool is shuffled, so its last cell is a uniform draw; the start itself is
        // skipped by looking one further.
        let pick = match pool.last() {
            Some(&g) if g != start => pool.len() - 1,
            Some(_) if pool.len() >= 2 => pool.len() - 2,
            Some(_) => {
                // Only the start itself is left: trade goals with an earlier pair of the
                // region (its goal is not this start, which was still unused).
                let Some(k) = pairs.iter().rposition(|&(s, _)| region[s.0 as usize] == r) else {
                    continue;
                };
                pool.clear();
                let goal = std::mem::replace(&mut pairs[k].1, start);
                pairs.push((start, goal));
                continue;
            }
            None => continue,
        };
        let goal = pool.swap_remove(pick);
        pairs.push((start, goal));
    }
    (pairs.len() == n).then_some(pairs)
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::movingai::{parse_map, parse_scen, scen_text};

    /// Two regions: a 3×2 room on the left and a 2×1 pocket on the right; one lone cell.
    const SPLIT: &str = "type octile\nheight 3\nwidth 7\nmap\n...@..@\n...@@@@\n@@@@@.@\n";

    fn region_of(grid: &Grid, c: Cell) -> u8 {
        let (x, _) = grid.xy(c);
        u8::from(x >= 4)
    }

    #[test]
    fn scenario_pairs_are_distinct_reachable_and_read_back() {
        let grid = parse_map(SPLIT, "split").unwrap();
        for seed in 0..50 {
            let pairs = random_scenario(&grid, 4, seed).expect("room for 4 pairs");
            let starts: std::collections::BTreeSet<_> = pairs.iter().map(|p| p.0).collect();
            let goals: std::collections::BTreeSet<_> = pairs.iter().map(|p| p.1).collect();
            assert_eq!(
                (starts.len(), goals.len()),
                (4, 4),
                "seed {seed}: {pairs:?}"
            );
            for &(s, g) in &pairs {
                assert!(grid.is_free(s) && grid.is_free(g));
                assert_ne!(s, g, "seed {seed}");
                assert_eq!(region_of(&grid, s), region_of(&grid, g), "seed {seed}");
                // The lone cell at (5, 2) has nowhere to go.
                assert_ne!(grid.xy(s), (5, 2));
            }
            let text = scen_text("split.map", &grid, &pairs);
            let back = parse_scen(&text, "s", &grid, 4).unwrap();
            assert_eq!(
                back.iter().map(|a| (a.start, a.goal)).collect::<Vec<_>>(),
                pairs
            );
        }
    }

    #[test]
    fn scenario_is_seeded_and_refuses_what_does_not_fit() {
        let grid = parse_map(SPLIT, "split").unwrap();
        assert_eq!(random_scenario(&grid, 5, 7), random_scenario(&grid, 5, 7));
        let differ = (0..20).any(|s| random_scenario(&grid, 5, s) != random_scenario(&grid, 5, 7));
        assert!(differ, "the seed changes the scenario");
        // 6 + 2 cells in regions of two or more: at most 8 pairs (each region's cells are
        // both starts and goals), and never with the lone cell.
        for seed in 0..50 {
            let all = random_scenario(&grid, 8, seed).expect("8 pairs always fit");
            assert!(all
                .iter()
                .all(|&(s, g)| s != g && region_of(&grid, s) == region_of(&grid, g)));
            assert!(random_scenario(&grid, 9, seed).is_none());
        }
        let lone = parse_map("type octile\nheight 1\nwidth 3\nmap\n.@.\n", "lone").unwrap();
        assert!(random_scenario(&lone, 1, 0).is_none());
    }
}
