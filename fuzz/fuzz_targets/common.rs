//! Shared by the fuzz targets: every wall a reader accepts must be a valid planning input.
#![allow(dead_code)] // each target uses part of it

use mason_order::{validate, Budget, BuildProblem, CostModel, PlannerSpec};
use mason_wall::Wall;

/// The largest wall planned with `exact` and checked with `order::validate`.
pub const SMALL_WALL: usize = 40;

/// A wall accepted by a reader: when small, `exact` must plan it and `order::validate` must
/// accept the order and agree with the claimed cost.
pub fn check_wall(wall: &Wall) {
    assert!(!wall.is_empty());
    if wall.len() > SMALL_WALL {
        return;
    }
    let model = CostModel::default();
    let problem = BuildProblem::new(wall, model.clone()).expect("default model is valid");
    let outcome = PlannerSpec::Exact.plan(&problem, &Budget::unlimited());
    let order = outcome.order.expect("exact plans every accepted wall");
    let eval = validate(wall, &model, &order).expect("exact's order passes order::validate");
    let cost = outcome.total_cost.expect("a cost with the order");
    assert!((eval.total_cost - cost).abs() <= 1e-6 * cost.abs().max(1.0));
}

/// Width × height of a PNG from its header, when it has one.
pub fn png_size(bytes: &[u8]) -> Option<u64> {
    let (w, h) = image::ImageReader::new(std::io::Cursor::new(bytes))
        .with_guessed_format()
        .ok()?
        .into_dimensions()
        .ok()?;
    Some(u64::from(w) * u64::from(h))
}
