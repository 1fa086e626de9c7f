//! Step 5, *read at one unit*: the grid near a given unit that puts every run's edges on
//! whole units, and each run's place on it, or the run that no such grid fits.

use super::*;

/// Touching bricks show the border between them within this many pixels.
pub(super) const GAP_AGREEMENT_PX: f64 = 1.25;

/// A grid that fits: pixels per unit, border width and every run's place on it.
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

/// A grid of whole units: grid line `k` is at `offset + k · unit` (px), and the border
/// (px) is centred on it.
#[derive(Clone, Copy, Debug)]
pub(super) struct Grid {
    pub(super) offset: f64,
    pub(super) unit: f64,
    pub(super) border: f64,
}

/// A run's edge as measured and the grid line it belongs to. A left edge lies half a border
/// right of its line (`side` +½), a right edge half a border left of it (−½), and an edge
/// where two colours blend lies on it (0).
#[derive(Clone, Copy, Debug)]
pub(super) struct Edge {
    pub(super) at: f64,
    pub(super) line: i64,
    pub(super) side: f64,
    run: usize,
    right: bool,
}

impl Grid {
    /// How far an edge is from where this grid puts it (px).
    pub(super) fn off(&self, e: &Edge) -> f64 {
        (e.at - self.offset - e.line as f64 * self.unit - e.side * self.border).abs()
    }
}

/// How far a measured edge may be off the grid (px).
pub(super) fn tolerance(unit: f64) -> f64 {
    (0.1 * unit).max(1.5).min(0.25 * unit)
}

/// Reads every run's place at about `unit` px per unit with the border fitted, or with no
/// border when that fails (with few runs the border is poorly determined: it trades off
/// against the unit). On failure, how many runs fitted and the first that did not.
pub(super) fn read_at(runs: &[Run], unit: f64) -> Result<Reading, (usize, Misfit)> {
    read_with(runs, unit, None).or_else(|e| read_with(runs, unit, Some(0.0)).map_err(|_| e))
}

/// Reads every run's place at about `unit` px per unit, with the border fitted or fixed:
/// 1. the border is first the circular mean of what each run lacks of a whole unit;
/// 2. grid lines are each run's left edge minus half a border and right edge plus half a
///    border, numbered along the wall by rounding the step from the last one;
/// 3. offset, unit and border are refitted to the edges by least squares, then once more
///    without the edges far off (so that one misdrawn brick does not tilt the grid);
/// 4. every run must sit on the grid, be a whole number of its colour's length and show the
///    border at the seams between its bricks, and touching bricks must show the border.
pub(super) fn read_with(
    runs: &[Run],
    unit: f64,
    fixed_border: Option<f64>,
) -> Result<Reading, (usize, Misfit)> {
    let border = fixed_border.unwrap_or_else(|| circular_border(runs, unit));
    let mut edges: Vec<Edge> = Vec::with_capacity(2 * runs.len());
    for (i, r) in runs.iter().enumerate() {
        let edge = |at, right: bool, blended: bool| Edge {
            at,
            line: 0,
            side: if blended {
                0.0
            } else if right {
                -0.5
            } else {
                0.5
            },
            run: i,
            right,
        };
        edges.push(edge(r.left, false, r.blended.0));
        edges.push(edge(r.right, true, r.blended.1));
    }
    let guess = |e: &Edge| e.at + if e.right { border / 2.0 } else { -border / 2.0 };
    edges.sort_by(|a, b| guess(a).total_cmp(&guess(b)));
    for k in 1..edges.len() {
        let step = ((guess(&edges[k]) - guess(&edges[k - 1])) / unit).round() as i64;
        edges[k].line = edges[k - 1].line + step;
    }
    let first_guess = Grid {
        offset: guess(&edges[0]),
        unit,
        border,
    };
    let mut grid = fit_edges(&edges, |_| true, fixed_border).unwrap_or(first_guess);
    let near = |e: &Edge| grid.off(e) <= tolerance(grid.unit);
    if let Some(refit) = fit_edges(&edges, near, fixed_border) {
        grid = refit;
    }
    let (unit, tol) = (grid.unit, tolerance(grid.unit));
    if unit < MIN_UNIT_PX || grid.border > MAX_BORDER_SHARE * unit || grid.border < -tol {
        return Err((0, Misfit::no_unit(&runs[0])));
    }
    let border = grid.border.max(0.0);
    // Each run's first and last grid line, and its edges' distance from the grid.
    let (mut starts, mut ends, mut off) = (
        vec![0i64; runs.len()],
        vec![0i64; runs.len()],
        vec![0f64; runs.len()],
    );
    for e in &edges {
        off[e.run] = off[e.run].max(grid.off(e));
        if e.right {
            ends[e.run] = e.line;
        } else {
            starts[e.run] = e.line;
        }
    }
    // The first run that does not fit is named (its message is written only for it).
    let mut first_misfit: Option<Misfit> = None;
    let mut fits: usize = 0;
    for (i, r) in runs.iter().enumerate() {
        let n = ends[i] - starts[i];
        let length = i64::from(r.kind.units());
        if off[i] > tol {
            first_misfit.get_or_insert_with(|| {
                let reason = format!(
                    "this {} brick's edge is {:.2} units off the 0.30 m grid ({unit:.1} px per \
                     unit): bricks and gaps must be whole units",
                    r.kind,
                    off[i] / unit
                );
                Misfit::layout(r, reason)
            });
        } else if n < length
            || n % length != 0
            || !seams_show_the_border(r, starts[i], n / length, &grid)
        {
            first_misfit.get_or_insert_with(|| {
                let kind = WallErrorKind::LengthMismatch {
                    kind: r.kind,
                    measured: (r.width() + border) / unit * UNIT_LENGTH,
                    pixels: r.width().round() as u32,
                    unit,
                    expected: r.kind.length(),
                };
                Misfit {
                    pixel: r.pixel,
                    kind,
                }
            });
        } else {
            fits += 1;
        }
    }
    // Runs come in order along each layer: those that touch show the border between them.
    for i in 1..runs.len() {
        let (a, b) = (&runs[i - 1], &runs[i]);
        let touching = a.layer == b.layer && ends[i - 1] == starts[i] && !b.blended.0;
        if touching && (b.left - a.right - border).abs() > GAP_AGREEMENT_PX {
            first_misfit.get_or_insert_with(|| {
                let reason = format!(
                    "this {} brick touches the brick before it across {:.1} px, but borders \
                     elsewhere are {border:.1} px",
                    b.kind,
                    b.left - a.right
                );
                Misfit::layout(b, reason)
            });
            fits = fits.saturating_sub(1);
        }
    }
    if let Some(m) = first_misfit {
        return Err((fits, m));
    }
    let first = starts.iter().copied().min().unwrap_or(0);
    let places = starts
        .iter()
        .zip(&ends)
        .map(|(&s, &e)| (s - first, (e - s) as u32));
    Ok(Reading {
        unit,
        border,
        places: places.collect(),
        residual: off.iter().copied().fold(0.0, f64::max),
    })
}

/// Whether a run read as `bricks` bricks shows the border between them: at each seam, the
/// colour it lacks adds up to the border's width (within [`GAP_AGREEMENT_PX`]). A run of one
/// brick has no seam.
fn seams_show_the_border(run: &Run, first: i64, bricks: i64, grid: &Grid) -> bool {
    let length = i64::from(run.kind.units());
    (1..bricks).all(|k| {
        let seam = grid.offset + (first + k * length) as f64 * grid.unit;
        let seam = seam - run.first_column as f64;
        let from = (seam - EDGE_REACH as f64).round().max(0.0) as usize;
        let to = ((seam + EDGE_REACH as f64).round().max(0.0) as usize).min(run.coverage.len());
        let lacking: f64 = run.coverage[from.min(to)..to]
            .iter()
            .map(|&c| 1.0 - f64::from(c))
            .sum();
        (lacking - grid.border.max(0.0)).abs() <= GAP_AGREEMENT_PX
    })
}

/// The border that makes every run's width plus the border a whole number of units: the
/// circular mean of `−width mod unit`, in (−0.25, 0.75] units.
fn circular_border(runs: &[Run], unit: f64) -> f64 {
    let (mut s, mut c) = (0.0, 0.0);
    for r in runs {
        let angle = -std::f64::consts::TAU * r.width() / unit;
        s += angle.sin();
        c += angle.cos();
    }
    let border = s.atan2(c) / std::f64::consts::TAU * unit;
    if border <= -0.25 * unit {
        border + unit
    } else if border > 0.75 * unit {
        border - unit
    } else {
        border
    }
}

/// Offset, unit and border by least squares over the edges `keep` keeps, or offset and unit
/// alone with the border fixed (`None` when the edges do not determine them). A border
/// cannot be negative: where the free fit says so, the best fit has none.
fn fit_edges(
    edges: &[Edge],
    keep: impl Fn(&Edge) -> bool + Copy,
    fixed_border: Option<f64>,
) -> Option<Grid> {
    // Normal equations of position = offset + line · unit + side · border, as an augmented
    // matrix (right-hand side in the last column), solved by Gaussian elimination.
    let n = if fixed_border.is_some() { 2 } else { 3 };
    let mut m = [[0f64; 4]; 3];
    for e in edges.iter().filter(|e| keep(e)) {
        let y = e.at - e.side * fixed_border.unwrap_or(0.0);
        let row = [1.0, e.line as f64, e.side, y];
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
