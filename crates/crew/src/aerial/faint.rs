//! Tops of nearly the floor's colour, read whole.
//!
//! A shelf whose colour after white balance is close to the floor's (pale grey on beige, lilac
//! on slate) leans pale pixel by pixel ([`super::pale`]'s loose limits) without making the
//! pale squares that read as an obstacle. Until issue #29's fifteenth round each of its cells
//! was refused as a free cell unlike the floor ([`super::looks`]). It differs from the floor
//! over its whole extent, though, which uneven light, texture and noise do not. So a
//! rectangle of cells (4-connected, filling its bounding box: racks stand on rectangles, a band
//! of light winds) whose middles' floor pixels have leaned pale (at least [`LOWER`] of them in
//! each cell, and at least [`SHARE`] in [`CELLS`] of its cells; the floor showing over at
//! least [`SEEN`] of each middle), amid floor that does not lean so (the median share over the
//! cells around it at most [`RING`]), is such a top: the 8-connected pixels that leaned pale
//! from its middles, its top with its lean over the cells beside it, become an obstacle's
//! before the cells' cover is counted. The top is then read as any shelf's, its lean and its
//! far cells judged as theirs.
//!
//! Outside the rectangle's cells a leaning pixel is followed only where the leaning is thick
//! (at least [`THICK`] of the square [`LINE`] cells around it leaning, or an obstacle's), and
//! not within twice that of the floor's edge: bright lines painted on the floor lean pale over
//! the whole floor, and would join the top to them. Only when the pixels followed lie within
//! [`REACH`] cells of the rectangle (a top leans at most [`super::cover::MAX_LEAN`] cells off
//! its cells): leaning pixels running on over the floor are its light or its texture, and the
//! cells are refused as before. A single cell is left to that refusal too.
//!
//! Measured on families A–Z and a (issue #29's fifteenth round): 566 cells turned, all
//! blocked in the truth. Two cells of free floor side by side lean pale at 0.9 and 1.0 amid
//! clean floor (X0010, 0.905 and 0.962 in T0026: under a top's lean or its glare), so two
//! cells must reach [`SHARE`]; the free rectangles of the Blender families' bright floors that
//! reach it have floor around them leaning by 0.32 and more.
//!
//! The cells' middles miss a top whose face fills them: under a tilted camera a run shows its
//! side facing the nadir (lit otherwise than its top: it does not lean pale) over the part of
//! each cell toward the nadir, and its top, leaning off, over the rest (y0038's pale blue-grey
//! run down column 28: 39–65 % of each middle leaned, 83–99 % of the window away from the
//! nadir; its six cells were refused as free cells unlike the floor, and are now turned).
//! So the tops left are then sought again, each cell judged in the window that
//! [`super::looks`] judges ([`Window::Far`], away from the nadir, where no neighbour's top
//! leans), and such a top must stand on [`FAR_CELLS`] cells at least (since issue #29's
//! thirty-first round). Measured on families A–Z, a–z, 0 and 1: 60 tops turned so, on 260
//! cells, all blocked in the truth; of the tops of two cells it would also turn, 33 were
//! blocked and 3 free (Q0027, S0027, r0017: floor lit pale at the far side of its cells).
//!
//! Cost: O(leaning pixels) to count them per cell, then O(pixels of the cells with enough of
//! them) for their middles, and O(leaning pixels of a top) to turn it.

use super::blobs::column_row;
use super::colour::Class;
use super::homography::Homography;
use super::pale::NOT_LEANED;
use super::pixels::OUTSIDE;
use rayon::prelude::*;

/// The least share of a cell's middle's floor pixels that leaned pale, in [`CELLS`] cells of
/// a top at least.
pub const SHARE: f64 = 0.95;
/// ... and in its other cells (a top's pixels near the camera's noise limit of leaning, or
/// shaded by a mark's shadow, lean a little less).
pub const LOWER: f64 = 0.8;
/// The least share of a cell's middle that must show floor (not a mark or an obstacle).
pub const SEEN: f64 = 0.5;
/// The middle of a cell, along each axis: away from painted lines and the blur of its edges.
pub const MIDDLE: (f64, f64) = (0.2, 0.8);
/// The fewest cells of a top that lean pale by [`SHARE`].
pub const CELLS: usize = 2;
/// ... or this many cells that lean pale by this share: a longer top, of which the camera's
/// noise or the sky's tint leaves a little more floor-like in each cell (issue #29's
/// twenty-fourth round: K0009's top over five cells leaned pale by 0.92–0.97, each cell
/// refused as a free cell unlike the floor). On families A–Z and a–e it read N0017 and b0006,
/// and V0036's top of six cells, read free past its refusals before, blocked; the audit past
/// the refusals reads no free cell blocked by it.
pub const WIDE: (usize, f64) = (3, 0.85);
/// How far (in cells, along each axis) a top's leaning pixels may lie from its cells.
pub const REACH: f64 = 2.0;
/// The largest median share of leaning pixels over the cells around a top (those showing
/// enough floor to be judged): a top differs from the floor around it, light and texture do
/// not.
pub const RING: f64 = 0.2;
/// The half side (in cells) of the square around a leaning pixel outside a top's cells that
/// [`THICK`] judges: a painted line, at most 0.1 cell wide (0.15 blurred), fills under half of
/// it, two crossing ones about half of it at their crossing only, and the line along the
/// floor's edge, twice as wide, is left out (within twice this of the edge).
pub const LINE: f64 = 0.2;
/// The least share of that square's pixels that must lean pale for the pixel to be the top's.
pub const THICK: f64 = 0.5;
/// The fewest floor pixels a cell's middle must show to be judged.
pub const MIN_PIXELS: u32 = 12;

/// The part of each cell whose floor pixels are judged ([`settle`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Window {
    /// The cell's middle, [`MIDDLE`] along each axis.
    Middle,
    /// The window that no neighbour's leaning top reaches, away from the nadir (given:
    /// [`super::pixels::window`]), the one [`super::looks`] judges; a group of cells must then
    /// count at least [`FAR_CELLS`].
    Far((f64, f64)),
}

/// The fewest cells of a top found in the [`Window::Far`] windows.
pub const FAR_CELLS: usize = 3;

/// Turns the tops of nearly the floor's colour into obstacle pixels (see the module's
/// comment), judging the floor pixels of each cell's `window`; `leaned` tells the pixels that
/// leaned pale ([`super::pale::settle`]), either way. Returns the cells of each top turned
/// (row-major indices), top by top.
pub fn settle(
    classes: &mut [u8],
    leaned: &[u8],
    width: usize,
    (floor_to_image, image_to_floor): (&Homography, &Homography),
    (gw, gh): (u32, u32),
    window: Window,
) -> Vec<Vec<usize>> {
    if width == 0 || !leaned.iter().any(|&l| l != NOT_LEANED) {
        return Vec::new();
    }
    let (w, h) = (gw as usize, gh as usize);
    let height = classes.len() / width;
    let floor = Class::Floor as u8;
    let at = |i: usize| -> Option<(usize, usize, f64, f64)> {
        let (x, y) = column_row(i, width);
        let (u, v) = image_to_floor.apply((x as f64 + 0.5, y as f64 + 0.5))?;
        if !(u >= 0.0 && v >= 0.0 && u < f64::from(gw) && v < f64::from(gh)) {
            return None;
        }
        let (cu, cv) = (u as usize, v as usize);
        Some((cu, cv, u - cu as f64, v - cv as f64))
    };
    let least_cells = match window {
        Window::Middle => 1,
        Window::Far(_) => FAR_CELLS,
    };
    // Whether a pixel at `(fu, fv)` within cell `(cu, cv)` lies in the window judged.
    let inner = |cu: usize, cv: usize, fu: f64, fv: f64| {
        let ((u0, u1), (v0, v1)) = match window {
            Window::Middle => (MIDDLE, MIDDLE),
            Window::Far((nu, nv)) => (
                super::pixels::window(cu as f64, Some(nu)),
                super::pixels::window(cv as f64, Some(nv)),
            ),
        };
        (u0..=u1).contains(&fu) && (v0..=v1).contains(&fv)
    };
    // The leaning pixels in each cell's middle first: only a cell with enough of them is
    // counted whole.
    // Counted per run of rows on all cores, then summed (whole numbers: the totals do not
    // depend on how the rows were split).
    let leaning: Vec<u32> = {
        let classes = &*classes;
        let run = width * 64;
        leaned
            .par_chunks(run)
            .enumerate()
            .fold(
                || vec![0u32; w * h],
                |mut leaning, (band, rows)| {
                    for (k, _) in rows.iter().enumerate().filter(|&(_, &l)| l != NOT_LEANED) {
                        let i = band * run + k;
                        if classes[i] != floor {
                            continue;
                        }
                        if let Some((cu, cv, fu, fv)) = at(i) {
                            if inner(cu, cv, fu, fv) {
                                leaning[cv * w + cu] += 1;
                            }
                        }
                    }
                    leaning
                },
            )
            .reduce(
                || vec![0u32; w * h],
                |mut total, part| {
                    total.iter_mut().zip(&part).for_each(|(t, n)| *t += n);
                    total
                },
            )
    };
    // The share of a cell's middle's floor pixels that leaned pale, when it shows enough
    // floor to be judged.
    let share = |c: usize| -> Option<f64> {
        let (x0, y0, x1, y1) =
            floor_to_image.cell_box(((c % w) as u32, (c / w) as u32), width, height)?;
        // The middle's pixels, and its floor pixels.
        let (mut all, mut fl) = (0u32, 0u32);
        for y in y0..y1 {
            for x in x0..x1 {
                let i = y * width + x;
                let cl = classes[i];
                if cl == OUTSIDE {
                    continue;
                }
                if let Some((cu, cv, fu, fv)) = at(i) {
                    if cv * w + cu == c && inner(cu, cv, fu, fv) {
                        all += 1;
                        fl += u32::from(cl == floor);
                    }
                }
            }
        }
        (fl >= MIN_PIXELS && f64::from(fl) >= SEEN * f64::from(all))
            .then(|| f64::from(leaning[c]) / f64::from(fl))
    };
    // Each cell's share, when it leans at least by the lower limit.
    let shares: Vec<Option<f64>> = (0..w * h)
        .into_par_iter()
        .map(|c| {
            (leaning[c] >= MIN_PIXELS)
                .then(|| share(c))
                .flatten()
                .filter(|&s| s >= LOWER)
        })
        .collect();
    // Groups of pale cells side by side.
    let mut group = vec![usize::MAX; w * h];
    let mut groups: Vec<Vec<usize>> = Vec::new();
    for start in 0..w * h {
        if shares[start].is_none() || group[start] != usize::MAX {
            continue;
        }
        let id = groups.len();
        let mut members = vec![start];
        group[start] = id;
        let mut k = 0;
        while k < members.len() {
            let c = members[k];
            k += 1;
            let (x, y) = (c % w, c / w);
            let mut near = Vec::with_capacity(4);
            if x > 0 {
                near.push(c - 1);
            }
            if x + 1 < w {
                near.push(c + 1);
            }
            if y > 0 {
                near.push(c - w);
            }
            if y + 1 < h {
                near.push(c + w);
            }
            for n in near {
                if shares[n].is_some() && group[n] == usize::MAX {
                    group[n] = id;
                    members.push(n);
                }
            }
        }
        groups.push(members);
    }
    let mut turned: Vec<Vec<usize>> = Vec::new();
    // The cells around a group already counted (a flag per cell, cleared after each group:
    // linear in the ring, however large the group).
    let mut ring_seen: Vec<usize> = Vec::new();
    let mut in_ring = vec![false; w * h];
    // The tops' pixels, turned once every group is judged on the classes as they were.
    let mut tops: Vec<usize> = Vec::new();
    let leaning_by = |g: &[usize], least: f64| {
        g.iter()
            .filter(|&&c| shares[c].is_some_and(|s| s >= least))
            .count()
    };
    for (id, members) in groups
        .iter()
        .enumerate()
        .filter(|(_, g)| g.len() >= least_cells)
        .filter(|(_, g)| leaning_by(g, SHARE) >= CELLS || leaning_by(g, WIDE.1) >= WIDE.0)
    {
        // The cells' box on the floor, grown by REACH.
        let (mut x0, mut y0, mut x1, mut y1) = (usize::MAX, usize::MAX, 0, 0);
        for &c in members {
            let (x, y) = (c % w, c / w);
            (x0, y0, x1, y1) = (x0.min(x), y0.min(y), x1.max(x + 1), y1.max(y + 1));
        }
        // A top stands on a rectangle of cells: a band of light or a texture's patch winds.
        if members.len() != (x1 - x0) * (y1 - y0) {
            continue;
        }
        // The floor around the group must not lean as it does.
        let mut ring: Vec<f64> = Vec::new();
        for &c in members {
            let (x, y) = (c % w, c / w);
            for ny in y.saturating_sub(1)..(y + 2).min(h) {
                for nx in x.saturating_sub(1)..(x + 2).min(w) {
                    let n = ny * w + nx;
                    if group[n] == usize::MAX && !in_ring[n] {
                        in_ring[n] = true;
                        ring_seen.push(n);
                        ring.extend(share(n));
                    }
                }
            }
        }
        for n in ring_seen.drain(..) {
            in_ring[n] = false;
        }
        if ring.is_empty() {
            continue;
        }
        let mid = ring.len() / 2;
        if *ring.select_nth_unstable_by(mid, f64::total_cmp).1 > RING {
            continue;
        }
        let within = |i: usize| {
            let (x, y) = column_row(i, width);
            image_to_floor
                .apply((x as f64 + 0.5, y as f64 + 0.5))
                .is_some_and(|(u, v)| {
                    u >= x0 as f64 - REACH
                        && u <= x1 as f64 + REACH
                        && v >= y0 as f64 - REACH
                        && v <= y1 as f64 + REACH
                })
        };
        // Outside the top's cells a leaning pixel is followed where the leaning is thick: a
        // top's lean over the cells beside it is, bright lines painted on the floor (leaning
        // pale over the whole floor, which they would join to the top) are not.
        let member = |cu: usize, cv: usize| group[cv * w + cu] == id;
        let r = members
            .first()
            .and_then(|&c| floor_to_image.cell_box(((c % w) as u32, (c / w) as u32), width, height))
            .map_or(1, |(x0, y0, x1, y1)| {
                ((LINE * (x1 - x0).min(y1 - y0) as f64).round() as usize).max(1)
            });
        let thin = |j: usize| {
            let Some((cu, cv, fu, fv)) = at(j) else {
                return true;
            };
            if member(cu, cv) {
                return false;
            }
            // Not along the floor's edge: the line painted there, twice as wide, is thick.
            let (u, v) = (cu as f64 + fu, cv as f64 + fv);
            if u.min(v).min(f64::from(gw) - u).min(f64::from(gh) - v) < 2.0 * LINE {
                return true;
            }
            let (x, y) = column_row(j, width);
            let (mut all, mut lean) = (0usize, 0usize);
            for ny in y.saturating_sub(r)..(y + r + 1).min(height) {
                for nx in x.saturating_sub(r)..(x + r + 1).min(width) {
                    all += 1;
                    let k = ny * width + nx;
                    lean += usize::from(
                        (leaned[k] != NOT_LEANED && classes[k] == floor)
                            || classes[k] == Class::Obstacle as u8,
                    );
                }
            }
            (lean as f64) < THICK * all as f64
        };
        // The leaning pixels 8-connected to those in the group's middles, but for thin ones.
        let mut seen = std::collections::HashSet::new();
        let mut stack: Vec<usize> = Vec::new();
        for &c in members {
            let Some((x0, y0, x1, y1)) =
                floor_to_image.cell_box(((c % w) as u32, (c / w) as u32), width, height)
            else {
                continue;
            };
            for y in y0..y1 {
                for x in x0..x1 {
                    let i = y * width + x;
                    if leaned[i] == NOT_LEANED || classes[i] != floor {
                        continue;
                    }
                    if let Some((cu, cv, fu, fv)) = at(i) {
                        if cv * w + cu == c && inner(cu, cv, fu, fv) && seen.insert(i) {
                            stack.push(i);
                        }
                    }
                }
            }
        }
        let mut top = Vec::new();
        let mut confined = true;
        while let Some(i) = stack.pop() {
            if !within(i) {
                confined = false;
                break;
            }
            top.push(i);
            let (x, y) = column_row(i, width);
            for ny in y.saturating_sub(1)..(y + 2).min(height) {
                for nx in x.saturating_sub(1)..(x + 2).min(width) {
                    let j = ny * width + nx;
                    if leaned[j] != NOT_LEANED && classes[j] == floor && seen.insert(j) && !thin(j)
                    {
                        stack.push(j);
                    }
                }
            }
        }
        if !confined {
            continue;
        }
        tops.extend(top);
        turned.push(members.clone());
    }
    for i in tops {
        classes[i] = Class::Obstacle as u8;
    }
    turned
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 6 × 3-cell floor, 10 px per cell, straight down: floor → image, image → floor, and
    /// its pixels' classes (all floor).
    fn floor() -> (Homography, Homography, Vec<u8>) {
        let to_image = Homography::floor_to_image(
            6.0,
            3.0,
            [(0.0, 0.0), (60.0, 0.0), (60.0, 30.0), (0.0, 30.0)],
        )
        .unwrap();
        (
            to_image,
            to_image.inverse().unwrap(),
            vec![Class::Floor as u8; 60 * 30],
        )
    }

    /// How many cells of the 6 × 3 floor `settle` turns into tops.
    fn turned(classes: &mut [u8], leaned: &[u8], maps: (&Homography, &Homography)) -> usize {
        turned_in(Window::Middle, classes, leaned, maps)
    }

    /// ... judging the cells' `window`.
    fn turned_in(
        window: Window,
        classes: &mut [u8],
        leaned: &[u8],
        maps: (&Homography, &Homography),
    ) -> usize {
        settle(classes, leaned, 60, maps, (6, 3), window)
            .iter()
            .map(Vec::len)
            .sum()
    }

    /// The pixels of the box `(x0, y0)`–`(x1, y1)` (ends excluded) marked in `leaned`.
    fn lean(leaned: &mut [u8], (x0, y0, x1, y1): (usize, usize, usize, usize)) {
        for y in y0..y1 {
            for x in x0..x1 {
                leaned[y * 60 + x] = super::super::pale::LEANED;
            }
        }
    }

    #[test]
    fn two_cells_side_by_side_that_lean_pale_are_a_top() {
        let (to_image, to_floor, mut classes) = floor();
        let mut leaned = vec![NOT_LEANED; classes.len()];
        // Cells (1, 1) and (2, 1), and a strip 3 px deep of their top leaning below them.
        lean(&mut leaned, (11, 11, 29, 22));
        let n = turned(&mut classes, &leaned, (&to_image, &to_floor));
        assert_eq!(n, 2);
        assert_eq!(classes[15 * 60 + 15], Class::Obstacle as u8);
        assert_eq!(classes[21 * 60 + 20], Class::Obstacle as u8, "its lean too");
        assert_eq!(classes[5 * 60 + 5], Class::Floor as u8);
    }

    #[test]
    fn bright_lines_painted_on_the_floor_are_not_the_top_s() {
        let (to_image, to_floor, mut classes) = floor();
        let mut leaned = vec![NOT_LEANED; classes.len()];
        lean(&mut leaned, (11, 11, 29, 19));
        // White lines 1 px wide along every cell border, leaning pale over the whole floor.
        for k in 0..6 {
            lean(&mut leaned, (10 * k, 0, 10 * k + 1, 30));
        }
        for k in 0..3 {
            lean(&mut leaned, (0, 10 * k, 60, 10 * k + 1));
        }
        assert_eq!(turned(&mut classes, &leaned, (&to_image, &to_floor)), 2);
        assert_eq!(classes[15 * 60 + 15], Class::Obstacle as u8);
        assert_eq!(classes[10 * 60 + 45], Class::Floor as u8, "a line");
    }

    #[test]
    fn a_single_cell_that_leans_pale_is_left_to_the_looks() {
        let (to_image, to_floor, mut classes) = floor();
        let mut leaned = vec![NOT_LEANED; classes.len()];
        lean(&mut leaned, (11, 11, 19, 19));
        assert_eq!(turned(&mut classes, &leaned, (&to_image, &to_floor)), 0);
        assert_eq!(classes[15 * 60 + 15], Class::Floor as u8);
    }

    #[test]
    fn cells_that_lean_pale_in_part_are_no_top() {
        let (to_image, to_floor, mut classes) = floor();
        let mut leaned = vec![NOT_LEANED; classes.len()];
        // Two cells' middles (rows 12–17) leaning but for one row of each: 5 of 6 rows.
        lean(&mut leaned, (11, 11, 29, 16));
        lean(&mut leaned, (11, 17, 29, 19));
        assert_eq!(turned(&mut classes, &leaned, (&to_image, &to_floor)), 0);
    }

    #[test]
    fn three_cells_side_by_side_that_lean_pale_a_little_less_are_a_top() {
        // Each cell's middle (6 × 6 px) leaning but for 4 of its pixels: 0.89, under SHARE.
        let leaned_cells = |cells: usize| {
            let mut leaned = vec![NOT_LEANED; 60 * 30];
            lean(&mut leaned, (11, 11, 9 + 10 * cells, 19));
            for k in 0..cells {
                for y in 12..16 {
                    leaned[y * 60 + 13 + 10 * k] = NOT_LEANED;
                }
            }
            leaned
        };
        let (to_image, to_floor, mut classes) = floor();
        let n = turned(&mut classes, &leaned_cells(2), (&to_image, &to_floor));
        assert_eq!(n, 0, "two cells");
        assert_eq!(
            turned(&mut classes, &leaned_cells(3), (&to_image, &to_floor)),
            3
        );
        assert_eq!(classes[15 * 60 + 35], Class::Obstacle as u8);
    }

    #[test]
    fn leaning_pixels_running_on_over_the_floor_are_its_light() {
        let (to_image, to_floor, mut classes) = floor();
        let mut leaned = vec![NOT_LEANED; classes.len()];
        // Two cells leaning whole, joined by a band of leaning pixels 0.4 cell wide (between
        // the middles of the next row of cells) to the floor's far end, more than REACH cells
        // away: a pool of light, not a top.
        lean(&mut leaned, (11, 11, 29, 19));
        lean(&mut leaned, (11, 19, 60, 23));
        assert_eq!(turned(&mut classes, &leaned, (&to_image, &to_floor)), 0);
        assert_eq!(classes[15 * 60 + 15], Class::Floor as u8);
    }

    #[test]
    fn a_top_s_third_cell_may_lean_a_little_less() {
        let (to_image, to_floor, mut classes) = floor();
        let mut leaned = vec![NOT_LEANED; classes.len()];
        // Cells (1, 1) to (3, 1), the middle of (3, 1) leaning in 5 of its 6 rows (83 %).
        lean(&mut leaned, (11, 11, 29, 19));
        lean(&mut leaned, (29, 11, 39, 16));
        lean(&mut leaned, (29, 17, 39, 19));
        assert_eq!(turned(&mut classes, &leaned, (&to_image, &to_floor)), 3);
        assert_eq!(classes[14 * 60 + 34], Class::Obstacle as u8);
    }

    #[test]
    fn cells_leaning_pale_in_no_rectangle_are_no_top() {
        let (to_image, to_floor, mut classes) = floor();
        let mut leaned = vec![NOT_LEANED; classes.len()];
        // Cells (1, 1), (2, 1) and (2, 0): an L, as a band of light winds.
        lean(&mut leaned, (11, 11, 29, 19));
        lean(&mut leaned, (21, 1, 29, 11));
        assert_eq!(turned(&mut classes, &leaned, (&to_image, &to_floor)), 0);
    }

    #[test]
    fn cells_leaning_pale_as_the_floor_around_them_does_are_no_top() {
        let (to_image, to_floor, mut classes) = floor();
        let mut leaned = vec![NOT_LEANED; classes.len()];
        lean(&mut leaned, (11, 11, 29, 19));
        // A pixel in four of the floor around leans pale too, each apart from the others: the
        // cells around lean by a quarter.
        for y in (0..30).step_by(2) {
            for x in (0..60).step_by(2) {
                leaned[y * 60 + x] = super::super::pale::LEANED;
            }
        }
        assert_eq!(turned(&mut classes, &leaned, (&to_image, &to_floor)), 0);
    }

    #[test]
    fn marks_in_a_cell_leave_too_little_floor_to_judge() {
        let (to_image, to_floor, mut classes) = floor();
        let mut leaned = vec![NOT_LEANED; classes.len()];
        lean(&mut leaned, (11, 11, 29, 19));
        // A goal over two thirds of cell (2, 1)'s middle (columns 22–25 of 22–27).
        for y in 11..19 {
            for x in 21..26 {
                classes[y * 60 + x] = Class::Goal as u8;
            }
        }
        assert_eq!(turned(&mut classes, &leaned, (&to_image, &to_floor)), 0);
    }

    /// A run of `cells` cells down column 1 whose top, seen from a camera whose nadir lies
    /// left of the floor, leans 0.4 cell right: its leaning pixels are the right 0.6 of each
    /// cell and the left 0.4 of column 2 (the left 0.4 of column 1 shows the run's shaded
    /// face, which does not lean pale).
    fn leaning_run(cells: usize) -> Vec<u8> {
        let mut leaned = vec![NOT_LEANED; 60 * 30];
        lean(&mut leaned, (14, 1, 24, 10 * cells - 1));
        leaned
    }

    /// The nadir left of the 6 × 3 floor, level with its middle row.
    const LEFT: Window = Window::Far((-5.0, 1.5));

    #[test]
    fn a_run_whose_face_fills_its_cells_middles_is_judged_in_its_far_windows() {
        let (to_image, to_floor, mut classes) = floor();
        let leaned = leaning_run(3);
        let maps = (&to_image, &to_floor);
        // The middles (0.2–0.8 across) lean by 4 of 6 columns: under LOWER.
        assert_eq!(turned(&mut classes.clone(), &leaned, maps), 0);
        // The windows away from the nadir (0.4–0.95 across) lean whole.
        assert_eq!(turned_in(LEFT, &mut classes, &leaned, maps), 3);
        assert_eq!(classes[15 * 60 + 16], Class::Obstacle as u8);
        assert_eq!(classes[15 * 60 + 22], Class::Obstacle as u8, "its lean");
        assert_eq!(classes[15 * 60 + 12], Class::Floor as u8, "its face");
    }

    #[test]
    fn a_top_judged_in_the_far_windows_stands_on_three_cells_at_least() {
        let (to_image, to_floor, mut classes) = floor();
        let leaned = leaning_run(2);
        let maps = (&to_image, &to_floor);
        assert_eq!(turned_in(LEFT, &mut classes, &leaned, maps), 0);
        assert_eq!(classes[15 * 60 + 16], Class::Floor as u8);
    }
}
