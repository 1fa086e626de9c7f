//! The round-trip oracle shared by the PNG reader's tests: a wall's canonical form, and
//! whether a drawing with no borders is ambiguous by nature.

use mason_wall::{BrickType, Wall};

/// Per brick (level, type, x in units, label), then supports and neighbours by label.
pub type Canonical = (
    Vec<(u32, BrickType, i64, u32)>,
    Vec<Vec<u32>>,
    Vec<Vec<u32>>,
);

/// A canonical description: per brick (level, type, x in units), and the relations by label.
pub fn canonical(w: &Wall) -> Canonical {
    let x_min = w
        .bricks()
        .iter()
        .map(|b| b.footprint.x0)
        .fold(f64::INFINITY, f64::min);
    let bricks = w
        .bricks()
        .iter()
        .map(|b| {
            let x = ((b.footprint.x0 - x_min) / 0.3).round() as i64;
            (b.level, b.kind, x, b.label)
        })
        .collect();
    let labels = |ids: &[mason_wall::BrickId]| ids.iter().map(|&i| w.brick(i).label).collect();
    let supports = w.ids().map(|i| labels(w.supports(i))).collect();
    let neighbours = w.ids().map(|i| labels(w.neighbours(i))).collect();
    (bricks, supports, neighbours)
}

/// Per layer (top first), the runs of one colour as drawn with no border: (start, end, type)
/// in units; touching bricks of one colour make one run.
fn borderless_runs(wall: &Wall) -> Vec<Vec<(i64, i64, BrickType)>> {
    let mut layers = vec![Vec::new(); wall.levels() as usize];
    let mut bricks: Vec<_> = wall.bricks().iter().collect();
    bricks.sort_by(|a, b| a.footprint.x0.total_cmp(&b.footprint.x0));
    for b in bricks {
        let x0 = (b.footprint.x0 / 0.3).round() as i64;
        let x1 = (b.footprint.x1 / 0.3).round() as i64;
        let runs: &mut Vec<(i64, i64, BrickType)> = &mut layers[(wall.levels() - b.level) as usize];
        match runs.last_mut() {
            Some(last) if last.1 == x0 && last.2 == b.kind => last.1 = x1,
            _ => runs.push((x0, x1, b.kind)),
        }
    }
    layers
}

/// Whether a drawing with no borders is ambiguous by nature, whatever the reader: two
/// touching layers draw the same, or the colour runs also fit a coarser grid with fewer bricks
/// and a thin border (at most a fifth of the coarser unit, the gaps between runs read as
/// borders). On a grid of `p / q` drawn units with a border of `b` drawn units, a run's grid
/// lines are its edges moved out by half the border, except where it touches another run (two
/// colours blending, no border): every grid line must fall on the coarse grid and every run be
/// a whole number of its colour's length.
pub fn ambiguous_without_borders(wall: &Wall) -> bool {
    let layers = borderless_runs(wall);
    if layers.windows(2).any(|w| w[0] == w[1]) {
        return true;
    }
    let bricks = |q: i64, p: i64, b: i64| -> Option<i64> {
        // Coordinates doubled, so that half a border is whole; whole multiples of `p / q`
        // that are whole drawn units are multiples of `p`.
        let mut lines = Vec::new();
        let mut count = 0;
        for runs in &layers {
            for (i, &(a, e, kind)) in runs.iter().enumerate() {
                let touches_left = i > 0 && runs[i - 1].1 == a;
                let touches_right = runs.get(i + 1).is_some_and(|n| n.0 == e);
                let left = 2 * a - if touches_left { 0 } else { b };
                let right = 2 * e + if touches_right { 0 } else { b };
                lines.extend([left, right]);
                let length = right - left;
                if length % (2 * p) != 0 || (length / (2 * p) * q) % i64::from(kind.units()) != 0 {
                    return None;
                }
                count += length / (2 * p) * q / i64::from(kind.units());
            }
        }
        lines
            .iter()
            .all(|&l| (l - lines[0]).rem_euclid(2 * p) == 0)
            .then_some(count)
    };
    let drawn = bricks(1, 1, 0).expect("the drawn grid fits");
    let widest = layers.iter().flatten().map(|r| r.1).max().unwrap_or(0);
    (2..=widest.max(2)).any(|p| {
        (1..p)
            .filter(|&q| gcd(p, q) == 1)
            .any(|q| (0..=p / (5 * q)).any(|b| bricks(q, p, b).is_some_and(|n| n < drawn)))
    })
}

fn gcd(a: i64, b: i64) -> i64 {
    if b == 0 {
        a
    } else {
        gcd(b, a % b)
    }
}
