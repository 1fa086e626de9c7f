//! Differential and validator-oracle tests of the crew solvers on generated maps.

use mason_crew::astar::astar;
use mason_crew::distance::{path_lengths, step_distances, UNREACHABLE};
use mason_crew::hungarian::hungarian;
use mason_crew::perm::permutation_assignment;
use mason_crew::prm::{PrmConfig, Roadmap};
use mason_crew::{
    solve, validate, AssignMethod, Budget, Cell, Connectivity, CrewConfig, Grid, Instance,
    PathMethod, Resolution, Status,
};
use proptest::prelude::*;

fn arb_grid() -> impl Strategy<Value = Grid> {
    (3u32..14, 3u32..14, 0.0f64..0.35, any::<u64>()).prop_map(|(w, h, density, seed)| {
        let mut s = seed | 1;
        let blocked = (0..w * h)
            .map(|_| {
                s ^= s << 13;
                s ^= s >> 7;
                s ^= s << 17;
                (s % 1000) as f64 / 1000.0 < density
            })
            .collect();
        Grid::new(w, h, blocked)
    })
}

fn arb_conn() -> impl Strategy<Value = Connectivity> {
    prop_oneof![Just(Connectivity::Four), Just(Connectivity::Eight)]
}

fn total(cost: &[Vec<f64>], a: &[usize]) -> f64 {
    a.iter().enumerate().map(|(i, &j)| cost[i][j]).sum()
}

/// Random distinct robots and goals in the free cells, picked by `picks`.
fn tasks(grid: &Grid, n: usize, picks: &[u32]) -> Option<(Vec<Cell>, Vec<Cell>)> {
    let free: Vec<Cell> = (0..grid.len() as u32)
        .map(Cell)
        .filter(|&c| grid.is_free(c))
        .collect();
    if free.len() < 2 * n {
        return None;
    }
    let mut pool = free;
    let mut chosen = Vec::new();
    for &p in picks.iter().take(2 * n) {
        let i = p as usize % pool.len();
        chosen.push(pool.swap_remove(i));
    }
    Some((chosen[..n].to_vec(), chosen[n..].to_vec()))
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 200,
        rng_seed: proptest::test_runner::RngSeed::Fixed(0x6372_6577),
        ..ProptestConfig::default()
    })]

    #[test]
    fn hungarian_equals_perm(n in 1usize..=7, extra in 0usize..3, seed in any::<u64>()) {
        let m = n + extra;
        let mut s = seed | 1;
        let cost: Vec<Vec<f64>> = (0..n)
            .map(|_| (0..m).map(|_| { s = s.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407); ((s >> 33) % 1000) as f64 / 7.0 }).collect())
            .collect();
        let h = hungarian(&cost);
        let p = permutation_assignment(&cost);
        let mut used = h.clone();
        used.sort_unstable();
        used.dedup();
        prop_assert_eq!(used.len(), n, "hungarian gives distinct goals");
        prop_assert!((total(&cost, &h) - total(&cost, &p)).abs() < 1e-9);
    }

    #[test]
    fn astar_length_equals_dijkstra(grid in arb_grid(), conn in arb_conn(), a in any::<u32>(), b in any::<u32>()) {
        let s = Cell(a % grid.len() as u32);
        let t = Cell(b % grid.len() as u32);
        prop_assume!(grid.is_free(s) && grid.is_free(t));
        let dist = path_lengths(&grid, conn, s)[t.0 as usize];
        let (path, _) = astar(&grid, conn, s, t);
        match path {
            None => prop_assert!(dist.is_infinite()),
            Some(p) => {
                prop_assert!((p.length - dist).abs() < 1e-9, "A* {} vs Dijkstra {}", p.length, dist);
                prop_assert_eq!(p.cells[0], s);
                prop_assert_eq!(*p.cells.last().unwrap(), t);
                prop_assert!(p.cells.windows(2).all(|w| grid.is_move(w[0], w[1], conn)));
                // In 4-connectivity steps and length agree with BFS.
                if conn == Connectivity::Four {
                    prop_assert_eq!(p.cells.len() as u32 - 1, step_distances(&grid, conn, s)[t.0 as usize]);
                }
            }
        }
    }

    #[test]
    fn prm_paths_are_valid(grid in arb_grid(), conn in arb_conn(), samples in 5usize..60, k in 1usize..8, seed in any::<u64>(), a in any::<u32>(), b in any::<u32>()) {
        let s = Cell(a % grid.len() as u32);
        let t = Cell(b % grid.len() as u32);
        prop_assume!(grid.is_free(s) && grid.is_free(t));
        let map = Roadmap::build(&grid, conn, PrmConfig { samples, neighbours: k, seed });
        let (path, _) = map.path(&grid, conn, s, t);
        if let Some(p) = path {
            prop_assert_eq!(p[0], s);
            prop_assert_eq!(*p.last().unwrap(), t);
            prop_assert!(p.windows(2).all(|w| grid.is_move(w[0], w[1], conn)), "illegal step in {:?}", p);
        } else {
            // PRM may miss, but never when the goal is unreachable anyway is fine; it must not
            // miss a straight free segment.
            prop_assert!(!mason_crew::line::segment_is_free(&grid, conn, s, t));
        }
    }

    #[test]
    fn plans_pass_the_validator(grid in arb_grid(), conn in arb_conn(), n in 1usize..7, picks in prop::collection::vec(any::<u32>(), 14), paper in any::<bool>(), prm in any::<bool>()) {
        let Some((robots, goals)) = tasks(&grid, n, &picks) else { return Ok(()); };
        let inst = Instance::new(grid.clone(), conn, robots, goals, None, "gen").unwrap();
        let config = CrewConfig {
            assign: AssignMethod::Hungarian,
            paths: if paper && prm { PathMethod::Prm } else { PathMethod::Astar },
            resolve: if paper { Resolution::Paper } else { Resolution::St },
            prm: PrmConfig { samples: 40, neighbours: 6, seed: 7 },
            ..CrewConfig::default()
        };
        let out = solve(&inst, &config, &Budget { node_limit: Some(200_000), ..Budget::default() }).unwrap();
        match out.status {
            Status::Optimal | Status::Feasible => {
                let paths = out.paths.expect("plan");
                let m = validate(&inst.grid, conn, &inst.robots, &out.goals, &paths);
                prop_assert!(m.is_ok(), "{:?}", m);
                // Nobody arrives sooner than its shortest path allows.
                for (r, p) in paths.iter().enumerate() {
                    let d = step_distances(&inst.grid, conn, inst.robots[r])[out.goals[r].0 as usize];
                    prop_assert!(d != UNREACHABLE && mason_crew::validate::arrival(p) as u32 >= d);
                }
            }
            _ => {
                prop_assert!(out.paths.is_none());
                prop_assert!(out.reason.is_some());
            }
        }
    }
}

/// A corridor one cell wide with robot 1 standing in robot 0's way: neither method can pass,
/// and both must say so rather than return a plan with conflicts.
#[test]
fn one_wide_corridor_is_reported_infeasible_by_both() {
    let grid = mason_crew::movingai::parse_map(
        "type octile\nheight 1\nwidth 8\nmap\n........\n",
        "corridor",
    )
    .unwrap();
    let c = |x| grid.cell(x, 0).unwrap();
    let inst = Instance::new(
        grid.clone(),
        Connectivity::Four,
        vec![c(0), c(2)],
        vec![c(7), c(3)],
        Some(vec![0, 1]),
        "corridor",
    )
    .unwrap();
    for resolve in [Resolution::Paper, Resolution::St] {
        let config = CrewConfig {
            assign: AssignMethod::Given,
            resolve,
            ..CrewConfig::default()
        };
        let out = solve(&inst, &config, &Budget::unlimited()).unwrap();
        assert_eq!(out.status, Status::Infeasible, "{resolve:?}");
        assert!(out.paths.is_none());
        assert!(
            out.reason.as_deref().unwrap().contains("robot"),
            "{:?}",
            out.reason
        );
    }
}

#[test]
fn st_lets_a_robot_wait_in_a_side_pocket() {
    // Row 1 has a pocket at (2,1) where robot 1 can step aside.
    let grid = mason_crew::movingai::parse_map(
        "type octile\nheight 2\nwidth 6\nmap\n......\n@@.@@@\n",
        "pocket",
    )
    .unwrap();
    let c = |x, y| grid.cell(x, y).unwrap();
    let inst = Instance::new(
        grid.clone(),
        Connectivity::Four,
        vec![c(0, 0), c(3, 0)],
        vec![c(5, 0), c(1, 0)],
        Some(vec![0, 1]),
        "pocket",
    )
    .unwrap();
    let config = CrewConfig {
        assign: AssignMethod::Given,
        resolve: Resolution::St,
        ..CrewConfig::default()
    };
    let out = solve(&inst, &config, &Budget::unlimited()).unwrap();
    assert_eq!(out.status, Status::Feasible, "{:?}", out.reason);
    let paths = out.paths.unwrap();
    validate(
        &inst.grid,
        inst.connectivity,
        &inst.robots,
        &out.goals,
        &paths,
    )
    .unwrap();
}

#[test]
fn perm_refuses_eleven_robots() {
    let grid = Grid::open(30, 1);
    let robots: Vec<Cell> = (0..11).map(Cell).collect();
    let goals: Vec<Cell> = (15..26).map(Cell).collect();
    let inst = Instance::new(grid, Connectivity::Eight, robots, goals, None, "wide").unwrap();
    let config = CrewConfig {
        assign: AssignMethod::Perm,
        ..CrewConfig::default()
    };
    let e = solve(&inst, &config, &Budget::unlimited()).unwrap_err();
    assert!(e.to_string().contains("at most 10 robots, not 11"), "{e}");
}

#[test]
fn same_seed_same_prm_plan() {
    let grid = mason_crew::generate::warehouse(80, 60, 0.02, 3);
    let (robots, goals) = mason_crew::generate::random_tasks(&grid, 8, 9);
    let inst = Instance::new(grid, Connectivity::Eight, robots, goals, None, "w").unwrap();
    let config = CrewConfig {
        paths: PathMethod::Prm,
        resolve: Resolution::Paper,
        prm: PrmConfig {
            samples: 400,
            neighbours: 8,
            seed: 11,
        },
        ..CrewConfig::default()
    };
    let a = solve(&inst, &config, &Budget::unlimited()).unwrap();
    let b = solve(&inst, &config, &Budget::unlimited()).unwrap();
    assert_eq!(a.paths, b.paths);
    assert_eq!(a.status, b.status);
}
