//! Step 6, *choose the grid*: of the readings at every unit the runs suggest, the one that
//! explains the drawing, or an error saying why none does or which two explain it as well.

use super::*;

/// A reading whose edges are this much farther (px) from its grid than the best reading's
/// does not explain the drawing.
const FIT_SLACK_PX: f64 = 0.75;
/// Borders up to this share of a unit are thin.
const THIN_BORDER_SHARE: f64 = 0.2;
/// A reading whose edges are this much closer (px) to its grid than any other's is preferred.
const CLEARLY_BETTER_PX: f64 = 0.5;
/// A reading's border agrees with the border seen (between layers or around the wall)
/// within this many pixels.
const BORDER_AGREEMENT_PX: f64 = 1.0;
/// The most distances between edges used to propose units.
const MAX_DISTANCES: usize = 24;
/// The most divisions of one distance tried as a unit.
const MAX_DIVISIONS: usize = 64;

/// Step 6: the unit and border that put every run on one grid of whole units.
pub(super) fn fit_grid(runs: &[Run], border_seen: Option<f64>) -> Result<Reading, Misfit> {
    let mut readings: Vec<Reading> = Vec::new();
    // Without a fit, the message names a run that the grid fitting most runs (at the largest
    // unit among equals) leaves out.
    let mut best_misfit: Option<(usize, f64, Misfit)> = None;
    for unit in candidate_units(runs) {
        // With a border seen (`borders.rs`), the grid with that border is tried as well: where
        // few edges show the border (touching colours blend, with none), the free fit can
        // drift to another border that the seen one would then wrongly rule out.
        if let Some(Ok(r)) = border_seen.map(|b| read_with(runs, unit, Some(b))) {
            readings.push(r);
        }
        let result = read_at(runs, unit);
        match result {
            Ok(r) => readings.push(r),
            Err((fits, misfit)) => {
                if best_misfit
                    .as_ref()
                    .is_none_or(|(f, u, _)| fits > *f || (fits == *f && unit > *u))
                {
                    best_misfit = Some((fits, unit, misfit));
                }
            }
        }
    }
    if readings.is_empty() {
        return Err(best_misfit
            .map(|(_, _, m)| m)
            .unwrap_or_else(|| Misfit::no_unit(&runs[0])));
    }
    // The border seen between layers or around the wall is the border between bricks.
    let mut border_confirmed = false;
    if let Some(seen) = border_seen {
        let matching = |r: &Reading| (r.border - seen).abs() <= BORDER_AGREEMENT_PX;
        if readings.iter().any(matching) {
            readings.retain(matching);
            border_confirmed = true;
        }
    }
    // One wall read at two units is one reading.
    readings.sort_by(|a, b| b.unit.total_cmp(&a.unit));
    let mut distinct: Vec<Reading> = Vec::new();
    for r in readings {
        if !distinct.iter().any(|k| k.places == r.places) {
            distinct.push(r);
        }
    }
    // Only readings that fit about as well as the best are explanations at all.
    let closest = distinct
        .iter()
        .map(|r| r.residual)
        .fold(f64::INFINITY, f64::min);
    distinct.retain(|r| r.residual <= closest + FIT_SLACK_PX);
    // The fewest bricks explain the drawing best ("R R" with a border, not "RRRR . RRRR"
    // with none); of different walls with as few, one that fits clearly better wins.
    let bricks = |r: &Reading| -> u64 {
        runs.iter()
            .zip(&r.places)
            .map(|(run, &(_, n))| u64::from(n / run.kind.units()))
            .sum()
    };
    let fewest = distinct.iter().map(bricks).min().expect("some reading");
    let (mut best, more_bricks): (Vec<Reading>, Vec<Reading>) =
        distinct.into_iter().partition(|r| bricks(r) == fewest);
    best.sort_by(|a, b| a.residual.total_cmp(&b.residual));
    let ambiguous = |a: &Reading, b: &Reading| {
        let differs = (0..runs.len())
            .find(|&i| a.places[i] != b.places[i])
            .unwrap_or(0);
        Misfit::layout(
            &runs[differs],
            format!(
                "ambiguous drawing: {:.1} and {:.1} px per 0.30 m fit equally well and place \
                 this {} brick differently; draw the borders darker than the background, or \
                 add a layer",
                a.unit, b.unit, runs[differs].kind
            ),
        )
    };
    // Ambiguous, 1: two walls with as few bricks fit about as well.
    if best.len() > 1 && best[0].residual + CLEARLY_BETTER_PX >= best[1].residual {
        return Err(ambiguous(&best[0], &best[1]));
    }
    let chosen = best.remove(0);
    // Ambiguous, 2: a thick border explains gaps that whole units with thin borders (and more
    // bricks) explain as well, and no border seen tells which.
    let thin = |r: &Reading| r.border <= THIN_BORDER_SHARE * r.unit;
    if !border_confirmed && !thin(&chosen) {
        if let Some(other) = more_bricks.iter().find(|r| thin(r)) {
            return Err(ambiguous(&chosen, other));
        }
    }
    Ok(chosen)
}

/// Units proposed by the distances between left edges and between right edges of
/// neighbouring runs (each a whole number of units whatever the border), divided by 1, 2, …;
/// with no such distance, by the narrowest run's width over its colour's length.
pub(super) fn candidate_units(runs: &[Run]) -> Vec<f64> {
    let mut distances = Vec::new();
    let edges: [fn(&Run) -> f64; 2] = [|r| r.left, |r| r.right];
    for edge in edges {
        let mut at: Vec<f64> = runs.iter().map(edge).collect();
        at.sort_by(f64::total_cmp);
        let steps = at.windows(2).map(|w| w[1] - w[0]);
        distances.extend(steps.filter(|&d| d >= MIN_UNIT_PX / 2.0));
    }
    distances.sort_by(f64::total_cmp);
    distances.dedup_by(|a, b| (*a - *b).abs() < 0.5);
    let mut units = Vec::new();
    for &d in distances.iter().take(MAX_DISTANCES) {
        let divisions = (1..=MAX_DIVISIONS).map(|m| d / m as f64);
        units.extend(divisions.take_while(|&u| u >= MIN_UNIT_PX));
    }
    units.push(narrowest_per_unit(runs));
    units.sort_by(f64::total_cmp);
    units.dedup_by(|a, b| (*a - *b).abs() < 0.005 * *b);
    units
}
