//! Shelves of the floor's colour, told by two kinds of evidence that agree.
//!
//! A shelf whose top is the floor's own colour shows in three ways, each refused on its own
//! until issue #29's twenty-second round: its cells do not quite look like the floor
//! ([`super::looks`]: brighter or more tinted than the lit floor around them), it casts a
//! shadow that nothing else in the image casts ([`super::shadows`]), and the painted lines
//! between its cells do not show ([`super::painted`]). One of them alone is weak: uneven
//! light, a stain or the glare of a nearby top makes free cells look a little unlike the
//! floor (on issue #29's families A–Z and a–g, 106 of 210 such regions were free floor). Two
//! that agree are not: a region of cells unlike the floor (4-connected) is a shelf's top when
//! - a shadow that nothing casts touches it (a bin of the shadow beside a bin of one of its
//!   cells: a shadow begins at its caster's foot), or
//! - a painted line between two of its cells does not show.
//!
//! Measured on those families with every other refusal bypassed: all 64 regions corroborated
//! so were blocked in the truth, none free.
//!
//! Such regions are proposed, not read: the reader reads the view again with them settled as
//! blocked, and keeps that reading only when it refuses nothing. The reading again checks the
//! rest: every shadow must then have a caster it touches, and, under one sun, lie behind it,
//! not behind lit floor ([`super::shadows::Sunlit::unattached`]): a shadow running on past the
//! region's cells (the rest of a longer shelf that looks like the floor) is still refused.
//! A view that shows one such shelf may show more that nothing tells, so two more guards keep
//! the first refusal instead: another free cell looks more like the tops than like the floor
//! ([`alone`]), or a free cell's window is [`FREE_COVER`] covered or more (a shelf read only in
//! part, or a cell a neighbour's leaning top was taken to cover).
//!
//! Cost: O(cells) and O(bins of the shadows nothing casts), and a second reading of the view,
//! only for a view refused for these reasons with a region so told.

use super::shadows::SIDE;

/// The cells (row-major indices, sorted) of the regions of `unlike` cells that a shadow in
/// `shadows` (bins, `gw × SIDE` wide, row-major) touches, or that a hidden line in `hidden`
/// (two cells, (x, y) each) runs within, on a floor of `gw` × `gh` cells.
pub fn shelves(
    unlike: &[usize],
    shadows: &[Vec<usize>],
    hidden: &[[(u32, u32); 2]],
    (gw, gh): (u32, u32),
) -> Vec<usize> {
    let (w, h) = (gw as usize, gh as usize);
    let mut is_unlike = vec![false; w * h];
    for &i in unlike {
        if let Some(u) = is_unlike.get_mut(i) {
            *u = true;
        }
    }
    let mut region = vec![usize::MAX; w * h];
    let mut regions: Vec<Vec<usize>> = Vec::new();
    for &start in unlike {
        if start >= w * h || region[start] != usize::MAX {
            continue;
        }
        let id = regions.len();
        region[start] = id;
        let mut cells = vec![start];
        let mut k = 0;
        while k < cells.len() {
            let i = cells[k];
            k += 1;
            let (x, y) = (i % w, i / w);
            let next = [
                (x > 0).then(|| i - 1),
                (x + 1 < w).then_some(i + 1),
                (y > 0).then(|| i - w),
                (y + 1 < h).then_some(i + w),
            ];
            for j in next.into_iter().flatten() {
                if region[j] == usize::MAX && is_unlike[j] {
                    region[j] = id;
                    cells.push(j);
                }
            }
        }
        regions.push(cells);
    }
    let mut told = vec![false; regions.len()];
    let cell = |(x, y): (u32, u32)| (x < gw && y < gh).then(|| y as usize * w + x as usize);
    for [a, b] in hidden {
        if let (Some(a), Some(b)) = (cell(*a), cell(*b)) {
            if region[a] != usize::MAX && region[a] == region[b] {
                told[region[a]] = true;
            }
        }
    }
    let (bw, bh) = (w * SIDE, h * SIDE);
    for shadow in shadows {
        for &b in shadow {
            let (bx, by) = (b % bw, b / bw);
            let beside = [
                (bx > 0).then(|| (bx - 1, by)),
                (bx + 1 < bw).then_some((bx + 1, by)),
                (by > 0).then(|| (bx, by - 1)),
                (by + 1 < bh).then_some((bx, by + 1)),
            ];
            for (nx, ny) in beside.into_iter().flatten() {
                let r = region[(ny / SIDE) * w + nx / SIDE];
                if r != usize::MAX {
                    told[r] = true;
                }
            }
        }
    }
    let mut out: Vec<usize> = regions
        .iter()
        .zip(&told)
        .filter(|(_, &t)| t)
        .flat_map(|(cells, _)| cells.iter().copied())
        .collect();
    out.sort_unstable();
    out
}

/// Less than this share of every free cell's window may be covered by an obstacle in a view
/// read with tops told so (half of [`super::HALF_COVERED`]'s lower bound).
pub const FREE_COVER: f64 = 0.15;

/// The share of the way from the floor's look to the tops' at or past which a free cell looks
/// like the tops ([`alone`]).
pub const LIKE_TOPS: f64 = 0.5;

/// Whether no free cell outside `tops` looks like them: `looks[i]`, for each free cell the
/// reader judges, its brightness ([`super::looks::Look::bright`]), its saturation after white
/// balance and the level of the lit floor around it ([`super::looks::local_levels`]).
///
/// A view that shows one shelf of the floor's colour may show another with no shadow beside
/// it and no line to hide (a high sun, a floor without lines), or the rest of the same shelf,
/// whose cells are as the floor's look allows cell by cell. Having seen what the shelf's top
/// looks like, the reader looks for it on the free floor. The tops' look differs from the
/// floor's by their median brightness over the level of the lit floor around them and their
/// median saturation over the free floor's; each free cell's difference from the floor (its
/// brightness over the level around it, its saturation over the free floor's) is projected on
/// that difference, and a cell at [`LIKE_TOPS`] of the way or more may be such a top.
///
/// On issue #29's families A–Z and a–e, the tops kept without this check and [`FREE_COVER`]
/// read 10 views wrongly: some with the rest of a shelf, beside the tops, within 0.01 of their
/// brightness (read free), others with another shelf that nothing told. This check refuses
/// eight of them; [`FREE_COVER`] the other two.
pub fn alone(tops: &[usize], looks: &[Option<(f64, f64, f64)>]) -> bool {
    let median = |mut v: Vec<f64>| -> Option<f64> {
        v.sort_by(f64::total_cmp);
        v.get(v.len() / 2).copied()
    };
    let of_tops = |k: usize| {
        median(
            tops.iter()
                .filter_map(|&i| looks.get(i).copied().flatten())
                .map(|l| [l.0 - l.2, l.1][k])
                .collect(),
        )
    };
    let floor_saturation = median(
        looks
            .iter()
            .enumerate()
            .filter(|(i, _)| tops.binary_search(i).is_err())
            .filter_map(|(_, l)| l.map(|l| l.1))
            .collect(),
    );
    let (Some(lift), Some(tint), Some(floor_tint)) = (of_tops(0), of_tops(1), floor_saturation)
    else {
        return false;
    };
    // The tops' difference from the floor along each measure: brightness over the level
    // around, and saturation over the free floor's.
    let axis = [lift, tint - floor_tint];
    let norm = axis[0] * axis[0] + axis[1] * axis[1];
    if norm <= 0.0 {
        return false;
    }
    looks.iter().enumerate().all(|(i, l)| {
        let Some((b, s, level)) = *l else {
            return true;
        };
        if tops.binary_search(&i).is_ok() {
            return true;
        }
        let d = [b - level, s - floor_tint];
        (d[0] * axis[0] + d[1] * axis[1]) / norm < LIKE_TOPS
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The bins of cell `(x, y)`'s column `col` of bins, on a floor `gw` cells wide.
    fn column(gw: usize, (x, y): (usize, usize), col: usize) -> Vec<usize> {
        (0..SIDE)
            .map(|r| (y * SIDE + r) * gw * SIDE + x * SIDE + col)
            .collect()
    }

    #[test]
    fn a_region_unlike_the_floor_is_a_shelf_only_where_a_shadow_or_a_hidden_line_tells_it() {
        // A 6 × 4 floor: cells (1, 1) and (1, 2) unlike the floor, and cell (4, 1) alone.
        let (gw, gh) = (6u32, 4u32);
        let at = |x: usize, y: usize| y * 6 + x;
        let unlike = [at(1, 1), at(1, 2), at(4, 1)];
        // Nothing tells: none.
        assert!(shelves(&unlike, &[], &[], (gw, gh)).is_empty());
        // A shadow in cell (2, 1), its first column of bins right beside cell (1, 1): that
        // region, both its cells.
        let beside = column(6, (2, 1), 0);
        assert_eq!(
            shelves(&unlike, &[beside], &[], (gw, gh)),
            [at(1, 1), at(1, 2)]
        );
        // A shadow in cell (3, 1) whose nearest bins are a bin away from (4, 1)'s: none.
        let apart = column(6, (3, 1), 2);
        assert!(shelves(&unlike, &[apart], &[], (gw, gh)).is_empty());
        // A hidden line between (1, 1) and (1, 2), within the region: that region.
        assert_eq!(
            shelves(&unlike, &[], &[[(1, 1), (1, 2)]], (gw, gh)),
            [at(1, 1), at(1, 2)]
        );
        // A hidden line between (4, 1) and the free (4, 2): not within a region, none.
        assert!(shelves(&unlike, &[], &[[(4, 1), (4, 2)]], (gw, gh)).is_empty());
        // A line off the floor is ignored.
        assert!(shelves(&unlike, &[], &[[(9, 9), (9, 10)]], (gw, gh)).is_empty());
    }
}
