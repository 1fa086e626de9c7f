//! Differential tests: every planner against `brute` and `exact`, every order through the
//! independent validator.

use mason_order::{
    validate, validate_claim, Budget, BuildProblem, CostModel, OrderError, PlannerSpec, Status,
};
use mason_wall::generate::{random_layer_text, WallShape};
use mason_wall::{parse_cmcp, parse_layer_text, BrickId, CmcpSizes, Wall};
use proptest::prelude::*;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

const PLANNERS: [PlannerSpec; 5] = [
    PlannerSpec::Brute,
    PlannerSpec::Greedy,
    PlannerSpec::Improved { n: 1, k: 4 },
    PlannerSpec::Improved { n: 0, k: 2 },
    PlannerSpec::Exact,
];

/// A random wall of at most `max` bricks.
fn small_wall(rng: &mut ChaCha8Rng, max: usize) -> Wall {
    let shape = WallShape {
        max_segments: 2,
        max_levels: 3,
        max_units: 8,
        orange: true,
    };
    loop {
        let text = random_layer_text(rng, &shape);
        let wall = parse_layer_text(&text, "generated").expect("valid by construction");
        if wall.len() <= max {
            return wall;
        }
    }
}

fn random_model(rng: &mut ChaCha8Rng) -> CostModel {
    let mut m = CostModel::default();
    if rng.gen_bool(0.5) {
        // Arbitrary κ, even decreasing: the exact DP must not assume monotone κ.
        m.kappa = [
            rng.gen_range(0.0..2.0),
            rng.gen_range(0.0..2.0),
            rng.gen_range(0.0..2.0),
        ];
        m.alpha = rng.gen_range(0.0..1.0);
    }
    m
}

fn check_all_planners(wall: &Wall, model: CostModel) -> Result<(), TestCaseError> {
    let problem = BuildProblem::new(wall, model).unwrap();
    let exact = PlannerSpec::Exact.plan(&problem, &Budget::unlimited());
    prop_assert_eq!(exact.status, Status::Optimal);
    let optimum = exact.total_cost.unwrap();
    for spec in PLANNERS {
        let out = spec.plan(&problem, &Budget::unlimited());
        let order = out.order.as_ref().expect("every planner finds an order");
        let claimed = out.total_cost.unwrap();
        let eval = validate_claim(wall, problem.model(), order, claimed)
            .map_err(|e| TestCaseError::fail(format!("{spec}: {e}")))?;
        prop_assert!(
            eval.total_cost >= optimum - 1e-9,
            "{} beat the optimum: {} < {}",
            spec,
            eval.total_cost,
            optimum
        );
        if spec == PlannerSpec::Brute {
            prop_assert_eq!(out.status, Status::Optimal);
            prop_assert!(
                (claimed - optimum).abs() < 1e-9,
                "exact {} ≠ brute {}",
                optimum,
                claimed
            );
        }
    }
    Ok(())
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 300,
        rng_seed: proptest::test_runner::RngSeed::Fixed(0x706c_616e),
        ..ProptestConfig::default()
    })]

    #[test]
    fn exact_equals_brute_and_heuristics_are_never_better(seed in any::<u64>()) {
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let wall = small_wall(&mut rng, 9);
        let model = random_model(&mut rng);
        check_all_planners(&wall, model)?;
    }

    #[test]
    fn exact_equals_brute_on_3d_walls_with_neighbour_cycles(seed in any::<u64>()) {
        // A 2-deep layer of red bricks: neighbours form a ladder, full of cycles.
        let mut rng = ChaCha8Rng::seed_from_u64(seed);
        let cols = rng.gen_range(2..=4);
        let mut src = String::new();
        let mut id = 1;
        for c in 0..cols {
            for row in 0..2 {
                src.push_str(&format!("{id} 1 {:.2} {:.2} 0.1 0\n", c as f64 * 0.35, row as f64 * 0.25));
                id += 1;
            }
        }
        if rng.gen_bool(0.5) {
            src.push_str(&format!("{id} 2 0.3 0.0 0.3 0\n"));
        }
        let wall = parse_cmcp(&src, "ladder", CmcpSizes::Yaml).unwrap();
        let model = random_model(&mut rng);
        check_all_planners(&wall, model)?;
    }
}

#[test]
fn exact_is_optimal_and_valid_on_a_5000_brick_wall() {
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let text = mason_wall::generate::large_layer_text(&mut rng, 5000, 50);
    let wall = parse_layer_text(&text, "big").unwrap();
    assert!(wall.len() >= 5000);
    let problem = BuildProblem::new(&wall, CostModel::default()).unwrap();
    let exact = PlannerSpec::Exact.plan(&problem, &Budget::unlimited());
    assert_eq!(exact.status, Status::Optimal);
    let order = exact.order.unwrap();
    let eval = validate(&wall, problem.model(), &order).unwrap();
    let greedy = PlannerSpec::Greedy.plan(&problem, &Budget::unlimited());
    let g = validate(&wall, problem.model(), &greedy.order.unwrap()).unwrap();
    assert!(eval.total_cost <= g.total_cost + 1e-6);
    // The optimum, found without any planner: `chain_optimum` is a lower bound on every
    // order's cost and is reached by some valid order, so the validated cost must equal it.
    let optimum = chain_optimum(&wall, &problem);
    assert!(
        (eval.total_cost - optimum).abs() <= 1e-9 * optimum,
        "exact {} against the optimum {optimum}",
        eval.total_cost
    );
    assert!(g.total_cost > optimum + 1e-6, "greedy is not optimal here");
}

/// The optimal cost of a wall whose bricks have at most two neighbours each, under a model
/// whose κ is linear (κ_k = κ_0 + k·d), computed from the wall and the model alone.
///
/// A brick placed beside k placed neighbours costs `c0 + k·Δ` (Δ = its cost at k = 1 minus
/// k = 0). Every neighbour edge adds the Δ of whichever end is placed later, so every order
/// costs at least `Σ c0 + Σ_edges min(Δ_a, Δ_b)`. That bound is reached: place level by
/// level (precedence only points up a level) and, within a level, bricks of larger (Δ, id)
/// first, an acyclic orientation of every edge in which the later end has the smaller Δ.
fn chain_optimum(wall: &Wall, problem: &BuildProblem<'_>) -> f64 {
    let k = problem.model().kappa;
    assert!(
        ((k[2] - k[1]) - (k[1] - k[0])).abs() < 1e-12,
        "κ is not linear"
    );
    let mut total = 0.0;
    for b in wall.ids() {
        assert!(wall.neighbours(b).len() <= 2, "brick {b:?}");
        total += problem.cost(b, 0);
        let delta = |x: BrickId| problem.cost(x, 1) - problem.cost(x, 0);
        for &n in wall.neighbours(b) {
            if n.index() > b.index() {
                total += delta(b).min(delta(n));
            }
        }
    }
    total
}

/// One level of red bricks in two rows of `cols`, 5 cm apart both ways: a ladder of neighbours,
/// one component full of cycles, of `2 · cols` bricks.
fn ladder_wall(cols: usize) -> Wall {
    let mut src = String::new();
    for c in 0..cols {
        for row in 0..2 {
            let id = 1 + 2 * c + row;
            src.push_str(&format!(
                "{id} 1 {:.2} {:.2} 0.1 0\n",
                c as f64 * 0.35,
                row as f64 * 0.25
            ));
        }
    }
    parse_cmcp(&src, "ladder", CmcpSizes::Yaml).unwrap()
}

#[test]
fn exact_falls_back_to_greedy_on_a_neighbour_cycle_over_20_bricks_and_says_feasible() {
    // 20 bricks: still inside the subset dynamic programming, so proven optimal.
    let wall = ladder_wall(10);
    assert_eq!(wall.len(), mason_order::exact::SUBSET_DP_LIMIT);
    let problem = BuildProblem::new(&wall, CostModel::default()).unwrap();
    let out = PlannerSpec::Exact.plan(&problem, &Budget::unlimited());
    assert_eq!(out.status, Status::Optimal);
    // 22 bricks in one cyclic component: the greedy fallback, a complete and valid order,
    // reported as feasible (not proven optimal), its claimed cost the validator's.
    let wall = ladder_wall(11);
    let edges: usize = wall.ids().map(|b| wall.neighbours(b).len()).sum::<usize>() / 2;
    assert!(edges >= wall.len(), "the ladder has a cycle");
    let problem = BuildProblem::new(&wall, CostModel::default()).unwrap();
    let out = PlannerSpec::Exact.plan(&problem, &Budget::unlimited());
    assert_eq!(out.status, Status::Feasible);
    let order = out.order.expect("a complete order");
    assert_eq!(order.len(), 22);
    validate_claim(&wall, problem.model(), &order, out.total_cost.unwrap()).unwrap();
    // Within the component the fallback is greedy: the same cost as the greedy planner's.
    let greedy = PlannerSpec::Greedy.plan(&problem, &Budget::unlimited());
    let g = validate(&wall, problem.model(), &greedy.order.unwrap()).unwrap();
    assert!((out.total_cost.unwrap() - g.total_cost).abs() < 1e-6);
}

#[test]
fn brute_reports_timeout_with_its_best_order_when_the_budget_runs_out() {
    let wall = mason_wall::builtin("levels5-width5").unwrap().wall();
    let problem = BuildProblem::new(&wall, CostModel::default()).unwrap();
    let out = PlannerSpec::Brute.plan(&problem, &Budget::nodes(10_000));
    assert_eq!(out.status, Status::Timeout);
    let order = out.order.expect("best order so far");
    validate_claim(&wall, problem.model(), &order, out.total_cost.unwrap()).unwrap();
    let exact = PlannerSpec::Exact.plan(&problem, &Budget::unlimited());
    assert!(out.total_cost.unwrap() >= exact.total_cost.unwrap() - 1e-9);
}

fn labels_of(wall: &Wall, order: &[BrickId]) -> Vec<u32> {
    order.iter().map(|&b| wall.brick(b).label).collect()
}

#[test]
fn greedy_breaks_ties_by_smallest_label() {
    // Three identical reds: every first choice costs the same; 101 goes first.
    let wall = parse_layer_text("R R R", "t").unwrap();
    let problem = BuildProblem::new(&wall, CostModel::default()).unwrap();
    let out = PlannerSpec::Greedy.plan(&problem, &Budget::unlimited());
    let labels = labels_of(&wall, &out.order.unwrap());
    // 101 (k=0), then 103 (k=0 is cheaper than 102 with k=1), then 102 (k=2).
    assert_eq!(labels, vec![101, 103, 102]);
}

#[test]
fn exact_places_the_cheap_bricks_last_in_a_chain() {
    // Default κ grows with placed neighbours, so the costliest drops (blue) go first and the
    // cheap red between them last.
    let wall = parse_layer_text("B R B", "t").unwrap();
    let problem = BuildProblem::new(&wall, CostModel::default()).unwrap();
    let out = PlannerSpec::Exact.plan(&problem, &Budget::unlimited());
    let labels: Vec<u32> = out
        .order
        .unwrap()
        .iter()
        .map(|&b| wall.brick(b).label)
        .collect();
    assert_eq!(labels, vec![101, 103, 102]);
}

#[test]
fn the_cost_formula_matches_a_hand_computation() {
    // One red on level 1: (1 + e^-0.1)·(14 + 22.5 + 1.0·8).
    let wall = parse_layer_text("R", "t").unwrap();
    let eval = validate(&wall, &CostModel::default(), &[BrickId(0)]).unwrap();
    let expected = (1.0 + (-0.1f64).exp()) * (14.0 + 22.5 + 8.0);
    assert!((eval.total_cost - expected).abs() < 1e-12);
}

#[test]
fn validator_rejects_bad_orders() {
    let wall = parse_layer_text("R\nR R", "t").unwrap();
    let m = CostModel::default();
    let err = |o: &[u32]| {
        validate(
            &wall,
            &m,
            &o.iter().map(|&i| BrickId(i)).collect::<Vec<_>>(),
        )
    };
    assert!(matches!(
        err(&[0, 1]),
        Err(OrderError::WrongLength {
            found: 2,
            expected: 3
        })
    ));
    assert!(matches!(
        err(&[0, 0, 2]),
        Err(OrderError::Repeated {
            step: 1,
            label: 101
        })
    ));
    assert!(matches!(
        err(&[1, 2, 0]),
        Err(OrderError::Unsupported {
            step: 1,
            label: 201,
            support: 101
        })
    ));
    assert!(matches!(
        err(&[0, 1, 7]),
        Err(OrderError::UnknownBrick { step: 2, index: 7 })
    ));
    assert!(err(&[1, 0, 2]).is_ok());
    let ok = validate_claim(&wall, &m, &[BrickId(0), BrickId(1), BrickId(2)], 1.0);
    assert!(matches!(ok, Err(OrderError::CostMismatch { .. })));
}

#[test]
fn planner_names_parse_and_print() {
    for s in ["brute", "greedy", "exact", "improved:1,4", "improved:2,3"] {
        assert_eq!(s.parse::<PlannerSpec>().unwrap().to_string(), s);
    }
    for s in [
        "",
        "astar",
        "improved:",
        "improved:1",
        "improved:a,b",
        "improved:1,0",
    ] {
        assert!(s.parse::<PlannerSpec>().is_err(), "{s}");
    }
}

#[test]
fn invalid_models_are_rejected_with_the_field() {
    let mut m = CostModel::default();
    m.kappa[1] = f64::NAN;
    let wall = parse_layer_text("R", "t").unwrap();
    let e = BuildProblem::new(&wall, m).unwrap_err();
    assert_eq!(e.field, "kappa[1]");
    let mut m = CostModel::default();
    m.blue.drop = -1.0;
    assert_eq!(BuildProblem::new(&wall, m).unwrap_err().field, "blue.drop");
}
