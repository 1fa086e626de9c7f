//! The grid from lines painted on the floor, when neither the grid nor the cell size is given.
//!
//! Along each floor axis the brightness profile is the median, across the floor, of each
//! slice's brightness (robots and shelves cover less than half a slice, so the median sees the
//! floor). Minus its running median, painted lines stand out as narrow dips (dark lines) or
//! peaks (bright lines). N cells put N − 1 inner lines at k/N of the floor; N's score is the
//! lower quartile, over k, of the extreme within ±1 sample there, in units of the
//! profile's noise (1.4826 × its median absolute deviation). N/2 cells score as well as N (their
//! lines are among N's) and 2N scores low (half its places fall between lines), so the answer
//! is the largest N scoring close to the best. A best score under [`MIN_SCORE`] means no lines.

/// The weakest line contrast, in noise units, taken as painted lines.
pub const MIN_SCORE: f64 = 5.0;
/// N scoring at least this share of the best is as good as the best.
const NEAR_BEST: f64 = 0.7;
/// The fewest samples per cell in the profile.
const MIN_SAMPLES_PER_CELL: usize = 4;

fn median(v: &mut [f64]) -> f64 {
    if v.is_empty() {
        return 0.0;
    }
    let mid = v.len() / 2;
    *v.select_nth_unstable_by(mid, f64::total_cmp).1
}

/// How many cells a profile's painted lines cut it into, with the score; `None` when it
/// shows no lines.
pub fn cells_along(profile: &[f64]) -> Option<(u32, f64)> {
    let n = profile.len();
    if n < 3 * MIN_SAMPLES_PER_CELL {
        return None;
    }
    let r = (n / 50).max(3);
    let detrended: Vec<f64> = (0..n)
        .map(|i| {
            let mut window: Vec<f64> = profile[i.saturating_sub(r)..(i + r + 1).min(n)].to_vec();
            profile[i] - median(&mut window)
        })
        .collect();
    let mut dev: Vec<f64> = detrended.iter().map(|d| d.abs()).collect();
    let noise = (1.4826 * median(&mut dev)).max(0.5);
    let mut best: Vec<(u32, f64, bool)> = Vec::new();
    let most = (n / MIN_SAMPLES_PER_CELL).min(1024);
    for cells in 2..=most {
        let spacing = n as f64 / cells as f64;
        // The same window for every N, so that noise lifts every N's score alike.
        let half = 1;
        for dark in [true, false] {
            let mut extremes: Vec<f64> = (1..cells)
                .map(|k| {
                    let at = (k as f64 * spacing).round() as usize;
                    let window = &detrended[at.saturating_sub(half)..(at + half + 1).min(n)];
                    let e = if dark {
                        window.iter().copied().fold(f64::INFINITY, f64::min)
                    } else {
                        window.iter().copied().fold(f64::NEG_INFINITY, f64::max)
                    };
                    if dark {
                        -e
                    } else {
                        e
                    }
                })
                .collect();
            let q = extremes.len() / 4;
            let quartile = *extremes.select_nth_unstable_by(q, f64::total_cmp).1;
            best.push((cells as u32, quartile / noise, dark));
        }
    }
    let top = best.iter().map(|b| b.1).fold(f64::NEG_INFINITY, f64::max);
    if top < MIN_SCORE {
        return None;
    }
    let dark = best.iter().find(|b| b.1 == top).map(|b| b.2)?;
    best.iter()
        .filter(|b| b.2 == dark && b.1 >= NEAR_BEST * top)
        .map(|b| (b.0, b.1))
        .max_by_key(|b| b.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn profile(n: usize, cells: usize, noise_seed: u64) -> Vec<f64> {
        let spacing = n as f64 / cells as f64;
        let mut state = noise_seed;
        (0..n)
            .map(|i| {
                state = state
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                let noise = ((state >> 33) as f64 / (1u64 << 31) as f64 - 0.5) * 6.0;
                let off = (i as f64 / spacing).fract();
                let line = !(0.06..=0.94).contains(&off);
                150.0 + 20.0 * (i as f64 / n as f64) + noise - if line { 60.0 } else { 0.0 }
            })
            .collect()
    }

    #[test]
    fn counts_painted_cells() {
        for (n, cells) in [(480, 24), (960, 30), (300, 10), (1000, 125)] {
            assert_eq!(
                cells_along(&profile(n, cells, 7)).map(|c| c.0),
                Some(cells as u32),
                "{n} samples, {cells} cells"
            );
        }
    }

    #[test]
    fn a_plain_floor_has_no_lines() {
        let flat: Vec<f64> = profile(480, 1, 3);
        assert_eq!(cells_along(&flat), None);
    }
}
