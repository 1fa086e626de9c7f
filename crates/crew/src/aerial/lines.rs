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
/// The weakest taken at the one count an axis's square cells give, a whole multiple of the
/// count found ([`shows`]): a count not sought among a thousand, and whose lines include
/// those found (on the 901 straight-down views, 5 more grids found right and 5 fewer wrong
/// than at [`MIN_SCORE`], none found on a floor without lines that was not before).
pub const PREDICTED_SCORE: f64 = 3.5;
/// N scoring at least this share of the best is as good as the best.
const NEAR_BEST: f64 = 0.7;
/// The fewest samples per cell in the profile.
const MIN_SAMPLES_PER_CELL: usize = 4;
/// The most cells sought along an axis.
const MOST_CELLS: u32 = 1024;

fn median(v: &mut [f64]) -> f64 {
    if v.is_empty() {
        return 0.0;
    }
    let mid = v.len() / 2;
    *v.select_nth_unstable_by(mid, f64::total_cmp).1
}

/// A profile less its running median, and its noise (1.4826 × the median absolute deviation
/// of that, at least 0.5); `None` for a profile too short to hold lines.
fn detrend(profile: &[f64]) -> Option<(Vec<f64>, f64)> {
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
    Some((detrended, noise))
}

/// The score of `cells` cells along a detrended profile (see the module's comment): the lower
/// quartile of the extremes at the inner lines' places, in noise units, for dark lines or
/// bright ones.
fn score(detrended: &[f64], noise: f64, cells: usize, dark: bool) -> f64 {
    let n = detrended.len();
    let spacing = n as f64 / cells as f64;
    // The same window for every N, so that noise lifts every N's score alike.
    let half = 1;
    let mut extremes: Vec<f64> = (1..cells)
        .map(|k| {
            let at = (k as f64 * spacing).round() as usize;
            let window = &detrended[at.saturating_sub(half)..(at + half + 1).min(n)];
            if dark {
                -window.iter().copied().fold(f64::INFINITY, f64::min)
            } else {
                window.iter().copied().fold(f64::NEG_INFINITY, f64::max)
            }
        })
        .collect();
    if extremes.is_empty() {
        return f64::NEG_INFINITY;
    }
    let q = extremes.len() / 4;
    *extremes.select_nth_unstable_by(q, f64::total_cmp).1 / noise
}

/// How many cells a profile's painted lines cut it into, with the score and whether the lines
/// are dark; `None` when it shows no lines.
pub fn cells_along(profile: &[f64]) -> Option<(u32, f64, bool)> {
    let (detrended, noise) = detrend(profile)?;
    let most = (detrended.len() / MIN_SAMPLES_PER_CELL).min(MOST_CELLS as usize);
    let best: Vec<(u32, f64, bool)> = (2..=most)
        .flat_map(|cells| {
            [true, false].map(|dark| (cells as u32, score(&detrended, noise, cells, dark), dark))
        })
        .collect();
    let top = best.iter().map(|b| b.1).fold(f64::NEG_INFINITY, f64::max);
    if top < MIN_SCORE {
        return None;
    }
    let dark = best.iter().find(|b| b.1 == top).map(|b| b.2)?;
    best.into_iter()
        .filter(|b| b.2 == dark && b.1 >= NEAR_BEST * top)
        .max_by_key(|b| b.0)
}

/// Whether lines of that kind (`dark` or bright) show at `cells` cells along the profile, a
/// multiple of `found` (whose lines are among them): a score of at least [`PREDICTED_SCORE`]. For an
/// axis whose lines were found only every few cells (a shelf in each aisle hides more than a
/// quarter of the others), when the other axis's cells, square, say how many there are.
pub fn shows(profile: &[f64], found: u32, cells: u32, dark: bool) -> bool {
    if found == 0 || cells <= found || cells % found != 0 || cells > MOST_CELLS {
        return false;
    }
    detrend(profile).is_some_and(|(detrended, noise)| {
        cells as usize * MIN_SAMPLES_PER_CELL <= detrended.len()
            && score(&detrended, noise, cells as usize, dark) >= PREDICTED_SCORE
    })
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

    /// 480 samples, 24 cells: lines at every cell, those at every fourth `strong` deep and
    /// the others `weak` deep (0: none).
    fn aisles(strong: f64, weak: f64) -> Vec<f64> {
        let spacing = 20.0;
        let mut state = 11u64;
        (0..480)
            .map(|i| {
                state = state
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                let noise = ((state >> 33) as f64 / (1u64 << 31) as f64 - 0.5) * 6.0;
                let k = ((i as f64 + spacing / 2.0) / spacing).floor() as usize;
                let off = (i as f64 / spacing).fract();
                let line = !(0.06..=0.94).contains(&off);
                let depth = if k % 4 == 0 { strong } else { weak };
                150.0 + noise - if line { depth } else { 0.0 }
            })
            .collect()
    }

    #[test]
    fn lines_found_every_few_cells_show_at_every_cell_when_they_are_there() {
        // Deep lines every fourth cell, faint ones between (shelves in the aisles hid most of
        // them from the median): the axis alone finds 6 cells.
        let faint = aisles(60.0, 18.0);
        let (found, _, dark) = cells_along(&faint).unwrap();
        assert_eq!(found, 6);
        assert!(dark);
        // Square cells from the other axis say 24: the faint lines show there, and at 12.
        assert!(shows(&faint, 6, 24, true));
        assert!(shows(&faint, 6, 12, true));
        // Not a multiple of 6 (8 cells' lines, every third of 24, show too), not the lines'
        // kind, or not more cells: no.
        assert!(!shows(&faint, 6, 8, true));
        assert!(!shows(&faint, 6, 20, true));
        assert!(!shows(&faint, 6, 24, false));
        assert!(!shows(&faint, 6, 6, true));
        // With no line between the deep ones, 24 cells do not show.
        let bare = aisles(60.0, 0.0);
        assert_eq!(cells_along(&bare).map(|c| c.0), Some(6));
        assert!(!shows(&bare, 6, 24, true));
    }
}
