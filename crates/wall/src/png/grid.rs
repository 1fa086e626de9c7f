//! Step 4, *fit the grid*: the unit and border that put every run on whole units.

use super::*;

/// Touching bricks show the border between them within this many pixels.
const GAP_AGREEMENT_PX: f64 = 1.25;
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

/// A fitted grid: pixels per unit, border width and every run's place on it.
#[derive(Clone, Debug, PartialEq)]
pub(super) struct Reading {
    pub(super) unit: f64,
    pub(super) border: f64,
    /// Per run: its first unit and its length in units.
    pub(super) places: Vec<(i64, u32)>,
    /// The largest distance of an edge from its grid line (px).
    pub(super) residual: f64,
}

/// Why no grid fits: the pixel of the run to blame, and what is wrong.
#[derive(Debug)]
pub(super) struct Misfit {
    pub(super) pixel: (u32, u32),
    pub(super) kind: WallErrorKind,
}

impl Misfit {
    pub(super) fn layout(run: &Run, reason: String) -> Misfit {
        let kind = WallErrorKind::ImageLayout { reason };
        Misfit {
            pixel: run.pixel,
            kind,
        }
    }

    pub(super) fn no_unit(run: &Run) -> Misfit {
        let reason = format!("no unit of at least {MIN_UNIT_PX} px per 0.30 m fits the bricks");
        Misfit::layout(run, reason)
    }

    pub(super) fn into_error(self, name: &str) -> WallError {
        WallError::new(name, Location::Pixel(self.pixel.0, self.pixel.1), self.kind)
    }
}

/// How far a measured edge may be off the grid (px).
pub(super) fn tolerance(unit: f64) -> f64 {
    (0.1 * unit).max(1.5).min(0.25 * unit)
}

/// Step 4: the unit and border that put every run on one grid of whole units.
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
    let (mut best, others): (Vec<Reading>, Vec<Reading>) =
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
    if best.len() > 1 && best[0].residual + CLEARLY_BETTER_PX >= best[1].residual {
        return Err(ambiguous(&best[0], &best[1]));
    }
    let chosen = best.remove(0);
    // A thick border explains gaps that whole units with thin borders explain as well; with
    // no border seen to tell, the drawing is ambiguous.
    let thin = |r: &Reading| r.border <= THIN_BORDER_SHARE * r.unit;
    if !border_confirmed && !thin(&chosen) {
        if let Some(other) = others.iter().find(|r| thin(r)) {
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
    let per_unit = |r: &Run| r.width() / f64::from(r.kind.units());
    units.push(runs.iter().map(per_unit).fold(f64::INFINITY, f64::min));
    units.sort_by(f64::total_cmp);
    units.dedup_by(|a, b| (*a - *b).abs() < 0.005 * *b);
    units
}

/// Reads every run's place at about `unit` px per unit: the border is the circular mean of
/// what each run lacks of a whole unit, grid lines are each run's left edge minus half a
/// border and right edge plus half a border, and unit and offset are refitted to them by
/// least squares. On failure, how many runs fitted and the first that did not.
pub(super) fn read_at(runs: &[Run], unit: f64) -> Result<Reading, (usize, Misfit)> {
    // With few runs the border is poorly determined (it trades off against the unit); a
    // drawing with no border is tried as well before giving up.
    read_with(runs, unit, None).or_else(|e| read_with(runs, unit, Some(0.0)).map_err(|_| e))
}

/// [`read_at`] with the border fitted, or fixed at `border`.
pub(super) fn read_with(
    runs: &[Run],
    unit: f64,
    fixed_border: Option<f64>,
) -> Result<Reading, (usize, Misfit)> {
    let border = fixed_border.unwrap_or_else(|| circular_border(runs, unit));
    // Grid lines in order along the wall, numbered by rounding the step from the last one.
    let mut lines: Vec<(f64, usize, bool)> = Vec::with_capacity(2 * runs.len());
    for (i, r) in runs.iter().enumerate() {
        lines.push((r.left - border / 2.0, i, false));
        lines.push((r.right + border / 2.0, i, true));
    }
    lines.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut number = vec![0i64; lines.len()];
    for k in 1..lines.len() {
        number[k] = number[k - 1] + ((lines[k].0 - lines[k - 1].0) / unit).round() as i64;
    }
    // The edges measured: a left edge is its grid line plus half a border, a right edge its
    // grid line minus half a border.
    let edges: Vec<(f64, i64, f64)> = lines
        .iter()
        .zip(&number)
        .map(|(&(_, i, right), &k)| {
            let r = &runs[i];
            match (right, r.blended) {
                (true, (_, true)) | (false, (true, _)) => {
                    (if right { r.right } else { r.left }, k, 0.0)
                }
                (true, _) => (r.right, k, -0.5),
                (false, _) => (r.left, k, 0.5),
            }
        })
        .collect();
    let guess = Grid {
        offset: lines[0].0,
        unit,
        border,
    };
    let mut grid = fit_edges(&edges, |_| true, fixed_border).unwrap_or(guess);
    // Once more without the edges far off it, so that one misdrawn brick does not tilt it.
    let near = |k: usize| grid.off(edges[k]) <= tolerance(grid.unit);
    if let Some(refit) = fit_edges(&edges, near, fixed_border) {
        grid = refit;
    }
    let Grid {
        offset,
        unit,
        border,
    } = grid;
    if unit < MIN_UNIT_PX {
        return Err((0, Misfit::no_unit(&runs[0])));
    }
    let tol = tolerance(unit);
    if border > MAX_BORDER_SHARE * unit || border < -tol {
        return Err((0, Misfit::no_unit(&runs[0])));
    }
    let border = border.max(0.0);
    let mut places = vec![(0i64, 0u32); runs.len()];
    let mut ends = vec![0i64; runs.len()];
    let mut off = vec![0f64; runs.len()];
    for (k, &(_, i, right)) in lines.iter().enumerate() {
        off[i] = off[i].max(grid.off(edges[k]));
        if right {
            ends[i] = number[k];
        } else {
            places[i].0 = number[k];
        }
    }
    // Every run must sit on the grid and be a whole number of its colour's length.
    let mut first_misfit = None;
    let mut fits: usize = 0;
    for (i, r) in runs.iter().enumerate() {
        let n = ends[i] - places[i].0;
        let length = i64::from(r.kind.units());
        let misfit = if off[i] > tol {
            Some(Misfit::layout(
                r,
                format!(
                    "this {} brick's edge is {:.2} units off the 0.30 m grid ({unit:.1} px per \
                     unit): bricks and gaps must be whole units",
                    r.kind,
                    off[i] / unit
                ),
            ))
        } else if n < length
            || n % length != 0
            || !seams_show_the_border(r, places[i].0, n, length, (offset, unit), border)
        {
            let kind = WallErrorKind::LengthMismatch {
                kind: r.kind,
                measured: (r.width() + border) / unit * UNIT_LENGTH,
                pixels: r.width().round() as u32,
                unit,
                expected: r.kind.length(),
            };
            Some(Misfit {
                pixel: r.pixel,
                kind,
            })
        } else {
            None
        };
        match misfit {
            None => {
                places[i].1 = n as u32;
                fits += 1;
            }
            Some(m) => {
                first_misfit.get_or_insert(m);
            }
        }
    }
    // Bricks that touch show the border between them.
    let mut order: Vec<usize> = (0..runs.len()).collect();
    order.sort_by_key(|&i| (runs[i].layer, places[i].0));
    for w in order.windows(2) {
        let (i, j) = (w[0], w[1]);
        let touching =
            runs[i].layer == runs[j].layer && ends[i] == places[j].0 && !runs[j].blended.0;
        if touching && (runs[j].left - runs[i].right - border).abs() > GAP_AGREEMENT_PX {
            first_misfit.get_or_insert(Misfit::layout(
                &runs[j],
                format!(
                    "this {} brick touches the brick before it across {:.1} px, but borders \
                     elsewhere are {border:.1} px",
                    runs[j].kind,
                    runs[j].left - runs[i].right
                ),
            ));
            fits = fits.saturating_sub(1);
        }
    }
    if let Some(m) = first_misfit {
        return Err((fits, m));
    }
    let first = places.iter().map(|p| p.0).min().unwrap_or(0);
    for p in &mut places {
        p.0 -= first;
    }
    Ok(Reading {
        unit,
        border,
        places,
        residual: off.iter().copied().fold(0.0, f64::max),
    })
}

/// Whether a run read as several bricks shows the border between them: at each seam, the
/// colour it lacks adds up to the border's width (within [`GAP_AGREEMENT_PX`]). A run of one
/// brick has no seam.
pub(super) fn seams_show_the_border(
    run: &Run,
    first: i64,
    units: i64,
    length: i64,
    (offset, unit): (f64, f64),
    border: f64,
) -> bool {
    (1..units / length).all(|k| {
        let seam = offset + (first + k * length) as f64 * unit - run.first_column as f64;
        let from = (seam - EDGE_REACH as f64).round().max(0.0) as usize;
        let to = ((seam + EDGE_REACH as f64).round().max(0.0) as usize).min(run.coverage.len());
        let lacking: f64 = run.coverage[from.min(to)..to]
            .iter()
            .map(|&c| 1.0 - f64::from(c))
            .sum();
        (lacking - border).abs() <= GAP_AGREEMENT_PX
    })
}

/// The border that makes every run's width plus the border a whole number of units: the
/// circular mean of `−width mod unit`, in (−0.25, 0.75] units.
pub(super) fn circular_border(runs: &[Run], unit: f64) -> f64 {
    let (mut s, mut c) = (0.0, 0.0);
    for r in runs {
        let angle = -std::f64::consts::TAU * r.width() / unit;
        s += angle.sin();
        c += angle.cos();
    }
    let mut border = s.atan2(c) / std::f64::consts::TAU * unit;
    if border <= -0.25 * unit {
        border += unit;
    }
    if border > 0.75 * unit {
        border -= unit;
    }
    border
}

/// A grid of whole units: grid line `k` is at `offset + k · unit` (px), and the border
/// (px) is centred on it.
#[derive(Clone, Copy, Debug)]
pub(super) struct Grid {
    pub(super) offset: f64,
    pub(super) unit: f64,
    pub(super) border: f64,
}

impl Grid {
    /// How far an edge `(position, grid line, side)` is from where this grid puts it; `side`
    /// is +½ for a left edge and −½ for a right edge.
    pub(super) fn off(&self, (position, k, side): (f64, i64, f64)) -> f64 {
        (position - self.offset - k as f64 * self.unit - side * self.border).abs()
    }
}

/// Offset, unit and border by least squares over the edges `keep` keeps, or offset and unit
/// alone with the border fixed (`None` when the edges do not determine them). A border
/// cannot be negative: where the free fit says so, the best fit has none.
pub(super) fn fit_edges(
    edges: &[(f64, i64, f64)],
    keep: impl Fn(usize) -> bool + Copy,
    fixed_border: Option<f64>,
) -> Option<Grid> {
    // Normal equations of position = offset + k · unit + side · border, as an augmented
    // matrix (right-hand side in the last column), solved by Gaussian elimination.
    let n = if fixed_border.is_some() { 2 } else { 3 };
    let mut m = [[0f64; 4]; 3];
    for (_, &(position, k, side)) in edges.iter().enumerate().filter(|(i, _)| keep(*i)) {
        let row = [
            1.0,
            k as f64,
            side,
            position - side * fixed_border.unwrap_or(0.0),
        ];
        for a in 0..n {
            for b in (0..n).chain([3]) {
                m[a][b] += row[a] * row[b];
            }
        }
    }
    for col in 0..n {
        let pivot = (col..n).max_by(|&a, &b| m[a][col].abs().total_cmp(&m[b][col].abs()))?;
        m.swap(col, pivot);
        if m[col][col].abs() < 1e-9 {
            return None;
        }
        for r in (0..n).filter(|&r| r != col) {
            let (f, pivot_row) = (m[r][col] / m[col][col], m[col]);
            for (value, p) in m[r].iter_mut().zip(pivot_row).skip(col) {
                *value -= f * p;
            }
        }
    }
    let solution = |i: usize| m[i][3] / m[i][i];
    let border = fixed_border.unwrap_or_else(|| solution(2));
    if border < 0.0 {
        return fit_edges(edges, keep, Some(0.0));
    }
    Some(Grid {
        offset: solution(0),
        unit: solution(1),
        border,
    })
}
