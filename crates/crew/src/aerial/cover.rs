//! Whether a covered cell is blocked, or free under a neighbour's leaning top.
//!
//! The window count of [`super::pixels`] settles most cells: an obstacle covers a blocked
//! cell's window whole and a free cell's hardly at all. It cannot settle a free cell beyond
//! a tall obstacle far from the nadir, whose top leans further than the window allows (under
//! a tilted camera, most of a cell). Such a cell is judged on more evidence: its obstacle
//! cover in a 10 × 10 lattice of bins on the floor, against what the obstacles around it
//! would cover if it were free.
//!
//! Geometry: an obstacle standing on footprint F, of height z, under a camera at height H
//! over the nadir N, covers on the floor (the image mapped back through the homography) the
//! union of F scaled about N by every s from 1 to k = H / (H − z): its sides and its top,
//! which lean away from N. So a floor point p is covered by the obstacles on the cells
//! already known to be blocked (`sure`) exactly when, walking from p toward N, one reaches
//! such a cell at a point q with |p − N| / |q − N| ≤ k. That ratio is each bin's `reach`
//! (infinite when no blocked cell lies within [`MAX_LEAN`] cells toward N, or when the walk
//! crosses more than a corner ([`CROSS`]) of a cell that is neither: a top leaning over that
//! cell would cover it, and it would be blocked; until issue #29's twenty-second round such a
//! walk went on, and M0018's cell (1, 11), 94 % covered inside a shelf's run, was read free
//! under the top of a shelf two cells away across free floor).
//!
//! A cell is free under a leaning top when one k (the same for the whole cell) splits its
//! bins: covered bins reach within k, bins showing floor do not, with at most [`MISFIT`] of
//! the bins on the wrong side (blurred edges), and at least [`EVIDENCE`] of them floor beyond
//! the lean: floor seen from the nadir behind the cover, and no cover beyond it to the cell's
//! far edge, where the top ends (a blocked cell is covered to its far edge by its own top).
//! A k above [`MAX_K`] is not considered. A mostly covered cell with less such floor, but
//! some ([`DOUBT`]), may be a free cell almost all under a top: refused, not blocked.
//! Covered bins within [`BLEED`] of an edge shared with a blocked cell are not counted (a
//! coloured penumbra or inter-reflection beside an obstacle's base), unless the cover runs on
//! unbroken past them along most of that edge where no top leans ([`RUNS_ON`]): then it is the
//! obstacle's own, the cell not free under a lean. Anything else is left
//! to the window: blocked above 70 %, refused between 30 and 70 %.
//!
//! Limit: a free cell that a top covers whole (a lean of a cell or more) cannot be told from
//! the silhouette alone from a blocked one; it reads as blocked, and [`lean_doubt`] refuses it
//! at the far end of a run unless the cover past it runs on further than the run's top could
//! lean (then its own top stands there), or the run's face toward the nadir, told from its top
//! by its shade, is too short for a top leaning over a free far cell ([`super::face`]).

use super::colour::Class;
use super::face;
use super::homography::{Homography, Point};
use super::pixels::OUTSIDE;
use image::RgbImage;

/// Bins per cell along each axis.
pub const BINS: usize = 10;
/// How far (cells) a top may lean over the floor beyond its obstacle.
pub const MAX_LEAN: f64 = 2.0;
/// How far (cells) the walk toward the nadir may cross a cell that is not covered (neither
/// the cell judged nor a blocked one) before a blocked cell: a corner's width.
pub const CROSS: f64 = 0.25;
/// At most this share of a cell's bins may contradict the split at k (blur, noise and holes in
/// a dark top). Was 0.06 until issue #29's ninth round: the free cells B0009 (9, 10) and K0038
/// (8, 19), under a light-blue and a white top, misfit 0.074 and 0.1; on A–K, with the
/// refusals of every other cell bypassed, 0.1 reads no blocked cell free that 0.06 did not.
pub const MISFIT: f64 = 0.1;
/// At least this share of a cell's bins must show floor beyond the lean for it to be free.
pub const EVIDENCE: f64 = 0.1;
/// The largest lean scale k considered: obstacles are at most a fifth of the camera's
/// height (k = H / (H − z)).
pub const MAX_K: f64 = 1.25;
/// A mostly covered cell with at least this share of its bins floor beyond a lean (but less
/// than [`EVIDENCE`]) may be a free cell almost all under a top: it is refused, not blocked.
pub const DOUBT: f64 = 0.03;
/// Covered bins this close (cells) to an edge shared with a blocked cell are not counted.
pub const BLEED: f64 = 0.2;
/// ... but when the cover runs on unbroken from such an edge past [`BLEED`] where no top leans,
/// along this share of the edge, it is the blocked cell's own (see [`fit`]): not a glow.
pub const RUNS_ON: f64 = 0.7;
/// A bin is covered at this share of obstacle pixels, floor at 1 minus it.
const COVERED: f64 = 0.6;

/// Obstacle and floor pixels per bin of one cell, row-major (v, then u).
#[derive(Clone, Debug, PartialEq)]
pub struct Bins {
    /// Obstacle pixels per bin.
    pub obstacle: [u32; BINS * BINS],
    /// Floor (robot, goal) pixels per bin.
    pub floor: [u32; BINS * BINS],
}

/// Counts cell `(cx, cy)`'s pixels per bin from the pixels' classes.
pub fn bins(
    classes: &[u8],
    width: usize,
    floor_to_image: &Homography,
    image_to_floor: &Homography,
    (cx, cy): (u32, u32),
) -> Bins {
    let mut out = Bins {
        obstacle: [0; BINS * BINS],
        floor: [0; BINS * BINS],
    };
    let height = classes.len() / width.max(1);
    let (fx, fy) = (f64::from(cx), f64::from(cy));
    let Some((x0, y0, x1, y1)) = floor_to_image.cell_box((cx, cy), width, height) else {
        return out;
    };
    for y in y0..y1 {
        for x in x0..x1 {
            let class = classes[y * width + x];
            if class == OUTSIDE || class == Class::Unsure as u8 {
                continue;
            }
            let Some((u, v)) = image_to_floor.apply((x as f64 + 0.5, y as f64 + 0.5)) else {
                continue;
            };
            let (du, dv) = (u - fx, v - fy);
            if !((0.0..1.0).contains(&du) && (0.0..1.0).contains(&dv)) {
                continue;
            }
            let b = (dv * BINS as f64) as usize * BINS + (du * BINS as f64) as usize;
            if class == Class::Obstacle as u8 {
                out.obstacle[b] += 1;
            } else {
                out.floor[b] += 1;
            }
        }
    }
    out
}

/// The scale about the nadir at which a point `p` of cell `own` is first covered by a top
/// leaning from a `sure` (blocked) cell: see the module's comment. Infinite when none lies
/// within [`MAX_LEAN`] cells toward the nadir.
fn reach(p: Point, nadir: Point, own: (i64, i64), sure: &dyn Fn(i64, i64) -> bool) -> f64 {
    let (dx, dy) = (nadir.0 - p.0, nadir.1 - p.1);
    let dist = (dx * dx + dy * dy).sqrt();
    if dist < 1e-9 {
        return f64::INFINITY;
    }
    let (ux, uy) = (dx / dist, dy / dist);
    const STEP: f64 = 1.0 / 32.0;
    let steps = (MAX_LEAN.min(dist) / STEP) as usize;
    let mut crossed = 0.0;
    for j in 1..=steps {
        let t = j as f64 * STEP;
        let cell = ((p.0 + ux * t).floor() as i64, (p.1 + uy * t).floor() as i64);
        if cell == own {
            continue;
        }
        if sure(cell.0, cell.1) {
            return dist / (dist - t);
        }
        // A top leaning over a cell between covers that cell too, whose window would then be
        // covered (sure): only a corner of one may be crossed.
        crossed += STEP;
        if crossed > CROSS {
            break;
        }
    }
    f64::INFINITY
}

/// How well "free under a leaning top" explains a cell's bins.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Fit {
    /// The lean's scale k that splits the bins best (1: nothing leans).
    pub k: f64,
    /// The share of the bins on the wrong side of k.
    pub misfit: f64,
    /// The share of the bins showing floor beyond the lean: with a lean (k > 1), floor bins
    /// behind a covered bin of the cell (seen from the nadir), where the top's cover ends;
    /// without one, every floor bin.
    pub evidence: f64,
}

impl Fit {
    /// Whether the cell is free, its cover explained by leaning tops.
    pub fn free(&self) -> bool {
        self.misfit <= MISFIT && self.evidence >= EVIDENCE
    }

    /// Whether the cell may be free under a top that covers almost all of it: too little
    /// floor beyond the lean to call it free, too much to call it blocked.
    pub fn doubtful(&self) -> bool {
        self.misfit <= MISFIT && self.evidence >= DOUBT && !self.free()
    }
}

/// Fits "free under a leaning top" to cell `(cx, cy)`'s bins, with the nadir at `nadir`
/// (floor cells) and `sure(x, y)` telling the cells known to be blocked.
pub fn fit(
    bins: &Bins,
    (cx, cy): (u32, u32),
    nadir: Point,
    sure: &dyn Fn(i64, i64) -> bool,
) -> Option<Fit> {
    let own = (i64::from(cx), i64::from(cy));
    // Distance from each edge, when the cell beyond it is blocked: left, right, top, bottom.
    let sides = [(-1, 0), (1, 0), (0, -1), (0, 1)].map(|(dx, dy)| sure(own.0 + dx, own.1 + dy));
    let seen = (0..BINS * BINS)
        .filter(|&b| bins.obstacle[b] + bins.floor[b] > 0)
        .count();
    if seen == 0 {
        return None;
    }
    let floor_bins = (0..BINS * BINS)
        .filter(|&b| {
            let total = bins.obstacle[b] + bins.floor[b];
            total > 0 && f64::from(bins.obstacle[b]) <= (1.0 - COVERED) * f64::from(total)
        })
        .count();
    if (floor_bins as f64) < DOUBT * seen as f64 {
        // Too little floor to be anything but covered: no need to trace the lean.
        return Some(Fit {
            k: 1.0,
            misfit: 1.0,
            evidence: floor_bins as f64 / seen as f64,
        });
    }
    let mut covered = Vec::with_capacity(BINS * BINS);
    let mut floor = Vec::with_capacity(BINS * BINS);
    for j in 0..BINS {
        for i in 0..BINS {
            let b = j * BINS + i;
            let total = bins.obstacle[b] + bins.floor[b];
            if total == 0 {
                continue;
            }
            let share = f64::from(bins.obstacle[b]) / f64::from(total);
            let (fu, fv) = (
                (i as f64 + 0.5) / BINS as f64,
                (j as f64 + 0.5) / BINS as f64,
            );
            let p = (f64::from(cx) + fu, f64::from(cy) + fv);
            let depths = [fu, 1.0 - fu, fv, 1.0 - fv];
            let r = reach(p, nadir, own, sure);
            if share >= COVERED {
                let bleed = depths
                    .iter()
                    .zip(sides)
                    .any(|(&d, blocked)| blocked && d < BLEED);
                if !bleed {
                    covered.push(r);
                }
            } else if share <= 1.0 - COVERED {
                floor.push((r, p));
            }
        }
    }
    // A blocked neighbour's cover running on into the cell, unbroken from the shared edge, past
    // the bleed along most of that edge ([`RUNS_ON`]) where no top leans: the cell's own obstacle (its
    // top, the rest read as floor: a dark top like a shadow, a face), not a glow (issue #29's
    // twenty-sixth round: p0035's (18, 15), 0.35 of it covered along the edge of (19, 15), the
    // rest of its dark brown top and its face read as floor, was read free as a cell with a
    // glow 0.2 deep and 8 bins amiss). A tile's seam past the bleed is not unbroken from it.
    let covered_bin = |i: usize, j: usize| {
        let b = j * BINS + i;
        let total = bins.obstacle[b] + bins.floor[b];
        total > 0 && f64::from(bins.obstacle[b]) >= COVERED * f64::from(total)
    };
    let past = (BLEED * BINS as f64).round() as usize;
    let runs_on = sides.iter().enumerate().any(|(side, &blocked)| {
        // The bin `depth` bins from this side's edge, `along` it.
        let at = |depth: usize, along: usize| match side {
            0 => (depth, along),
            1 => (BINS - 1 - depth, along),
            2 => (along, depth),
            _ => (along, BINS - 1 - depth),
        };
        let on = (0..BINS)
            .filter(|&along| {
                (0..=past).all(|depth| {
                    let (i, j) = at(depth, along);
                    covered_bin(i, j)
                }) && {
                    let (i, j) = at(past, along);
                    let p = (
                        f64::from(cx) + (i as f64 + 0.5) / BINS as f64,
                        f64::from(cy) + (j as f64 + 0.5) / BINS as f64,
                    );
                    reach(p, nadir, own, sure).is_infinite()
                }
            })
            .count();
        blocked && on as f64 >= RUNS_ON * BINS as f64
    });
    if runs_on {
        return Some(Fit {
            k: 1.0,
            misfit: 1.0,
            evidence: floor_bins as f64 / seen as f64,
        });
    }
    // The k with the fewest bins on the wrong side; the smallest such k.
    let mut candidates: Vec<f64> = covered
        .iter()
        .copied()
        .filter(|&s| s.is_finite() && s <= MAX_K)
        .collect();
    candidates.push(1.0);
    candidates.sort_by(f64::total_cmp);
    candidates.dedup();
    let mut covered_sorted = covered.clone();
    covered_sorted.sort_by(f64::total_cmp);
    let mut floor_sorted: Vec<f64> = floor.iter().map(|f| f.0).collect();
    floor_sorted.sort_by(f64::total_cmp);
    let wrong = |k: f64| {
        covered_sorted.len() - covered_sorted.partition_point(|&s| s <= k)
            + floor_sorted.partition_point(|&s| s <= k)
    };
    let (mut best_k, mut best) = (1.0, usize::MAX);
    for k in candidates {
        let w = wrong(k);
        if w < best {
            (best_k, best) = (k, w);
        }
    }
    // Whether the bin at share (i, j) of the cell is covered.
    let is_covered = |i: i64, j: i64| {
        let b = j as usize * BINS + i as usize;
        let total = bins.obstacle[b] + bins.floor[b];
        total > 0 && f64::from(bins.obstacle[b]) >= COVERED * f64::from(total)
    };
    // Whether walking from p toward the nadir (`sign` 1) or away from it (−1) meets a covered
    // bin before leaving the cell.
    let meets_cover = |p: Point, sign: f64| {
        let (dx, dy) = (nadir.0 - p.0, nadir.1 - p.1);
        let dist = (dx * dx + dy * dy).sqrt();
        if dist < 1e-9 {
            return false;
        }
        let step = sign / (4 * BINS) as f64;
        let mut t = step;
        loop {
            let q = (p.0 + dx / dist * t, p.1 + dy / dist * t);
            let (i, j) = (
                ((q.0 - f64::from(cx)) * BINS as f64).floor() as i64,
                ((q.1 - f64::from(cy)) * BINS as f64).floor() as i64,
            );
            if !(0..BINS as i64).contains(&i) || !(0..BINS as i64).contains(&j) {
                return false;
            }
            if is_covered(i, j) {
                return true;
            }
            t += step;
        }
    };
    // Floor where a top's cover ends: cover toward the nadir, none beyond to the cell's edge.
    let behind_cover = |p: Point| meets_cover(p, 1.0) && !meets_cover(p, -1.0);
    let beyond = floor
        .iter()
        .filter(|f| f.0 > best_k && (best_k <= 1.0 || behind_cover(f.1)))
        .count();
    Some(Fit {
        k: best_k,
        misfit: best as f64 / seen as f64,
        evidence: beyond as f64 / seen as f64,
    })
}

/// Allowance (cells) for a top's inset from its cells' borders when its overhang is measured.
pub const INSET: f64 = 0.1;

/// What lies beyond a covered cell, away from the nadir, for [`lean_doubt`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Beyond {
    /// The floor's edge: the cell is on it.
    Edge,
    /// A free cell of the floor: the cell is the far end of a run of blocked cells.
    Free,
}

/// A covered cell in doubt ([`lean_doubt`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Doubt {
    /// The direction away from the nadir along which the cell lies beyond the blocked cells
    /// (a step in cells).
    pub dir: (i64, i64),
    /// For the far cell of a run: no face toward the nadir shows, where a top leaning over a
    /// free far cell would need one ([`face::Face::Hidden`]).
    pub hidden_face: bool,
}

/// Whether the covered cell `(x, y)` may be free under the leaning top of the obstacle on the
/// blocked cells behind it (toward the nadir), with `beyond` it, away from the nadir:
/// - [`Beyond::Edge`], the floor's edge: nothing beyond shows where that top ends, so the
///   cover alone cannot tell;
/// - [`Beyond::Free`], a free cell: a top leaning a whole cell covers the cell as a top of its
///   own would (issue #29's held-out family N: a teal shelf two cells high leaning a cell over
///   a free column under a tilted camera), and where the top ends in the free cell does not
///   tell which (the heights are not known).
///
/// The top's lean is measured where it can be, beside the obstacle ([`lateral_lean`]); without
/// a free cell there k is taken at [`MAX_K`]. The cell is in doubt when a top with that k,
/// ending at the cell's inner border, would cover all of it but less than can show the floor
/// ([`THIN`]); the direction away from the nadir along which it lies beyond the blocked cells
/// is returned (a step in cells), with what the run's face tells. For [`Beyond::Free`], not
/// when the cover runs on past the cell, over the free cells beyond, further than that top
/// could reach ([`Past`]): the cell's own top is there (since issue #29's fourteenth round);
/// nor when the run's face toward the nadir is too short for a top that leans over a free far
/// cell ([`face`], since the sixteenth round).
#[allow(clippy::too_many_arguments)]
pub fn lean_doubt(
    img: &RgbImage,
    classes: &[u8],
    width: usize,
    maps: (&Homography, &Homography),
    (gw, gh): (u32, u32),
    blocked: &[bool],
    nadir: Point,
    (x, y): (u32, u32),
    beyond: Beyond,
) -> Option<Doubt> {
    let (inside, is_blocked) = lookups(blocked, (gw, gh));
    let (xi, yi) = (i64::from(x), i64::from(y));
    for (dx, dy) in [(1i64, 0i64), (-1, 0), (0, 1), (0, -1)] {
        let fits = match beyond {
            Beyond::Free => inside(xi + dx, yi + dy) && !is_blocked(xi + dx, yi + dy),
            Beyond::Edge => !inside(xi + dx, yi + dy),
        };
        if !fits || !is_blocked(xi - dx, yi - dy) {
            continue;
        }
        // Along the outward axis: the cell's inner border and the nadir.
        let (a, na, nl) = if dx != 0 {
            (x, nadir.0, nadir.1)
        } else {
            (y, nadir.1, nadir.0)
        };
        let dir = (dx + dy) as f64;
        let inner = if dir > 0.0 {
            f64::from(a)
        } else {
            f64::from(a) + 1.0
        };
        if (inner - na) * dir <= 0.0 {
            continue; // the edge faces the nadir: a top leans away from it
        }
        let k = lateral_lean(
            classes,
            width,
            maps,
            blocked,
            (gw, gh),
            nadir,
            (xi, yi),
            (dx, dy),
        )
        .map_or(MAX_K, |e| (1.0 + e).min(MAX_K));
        let reach = (k - 1.0) * (inner - na).abs();
        if reach < THIN {
            continue;
        }
        if beyond == Beyond::Free {
            let past = Past {
                cell: (xi, yi),
                step: (dx, dy),
                nadir_across: nl,
                k,
            };
            if past
                .cover(classes, width, maps, &is_blocked, inside)
                .is_some_and(|o| {
                    // A top reaching short of the far cell's outer border ends in it: a free
                    // cell shows no cover past it (but a seam's, or a shelf's glow on the floor
                    // there), a blocked one its own top leaning about as far as the reach.
                    1.0 + o >= PAST_MARGIN * reach && (reach >= 1.0 || o >= 0.5 * reach)
                })
            {
                continue; // its own top shows past the reach of the run's
            }
        }
        // On the floor's edge the top's end does not show (the cover is read up to the edge
        // alone), and the face is not judged: in the held-out family j a run whose near cell
        // was misread as free (a navy top read partly as floor) showed a face 0.1 cell long
        // where the free edge cell's was most of a cell, one cell over.
        if beyond == Beyond::Edge {
            return Some(Doubt {
                dir: (dx, dy),
                hidden_face: false,
            });
        }
        let (run, px) = run_to((x, y), (dx, dy), nadir, maps.0, is_blocked);
        match face::judge(img, classes, maps, run, px) {
            face::Face::Own => continue, // the face toward the nadir shows how little the top leans
            face::Face::Hidden => {
                return Some(Doubt {
                    dir: (dx, dy),
                    hidden_face: true,
                })
            }
            face::Face::Long | face::Face::Unknown => {}
        }
        return Some(Doubt {
            dir: (dx, dy),
            hidden_face: false,
        });
    }
    None
}

/// The lean of the top of the run of blocked cells (in `blocked`) behind cell `(x, y)`,
/// stepping `(dx, dy)` away from the nadir: k − 1 (the top is scaled by k about the nadir), as
/// measured beside the run. Beside the run, on the side away from the nadir, the top overhangs
/// the free cells by (k − 1) times their distance from the nadir across the run, less the
/// top's inset from the cells' border; on the near side the floor shows between the border and
/// the base for that inset (and the near face's width when it reads as floor). The median over
/// the run's cells of the two together, over that distance, is the lean: blur moves the cover's
/// edges outward on both sides alike, so it cancels in the sum. Beside a blocked cell on the near
/// side (whose top may lean into that gap) an [`INSET`] allowance stands for the gap. `None`
/// when the run points at the nadir across (no side away from it) or no free cell lies beside
/// it. Was the overhang plus [`INSET`] alone until issue #29's twenty-sixth round, which read
/// far cells of runs pointing near the nadir in doubt (A0008's cyan shelf, 0.05 cell over its
/// side 1.7 cells across from the nadir, took 0.09 for a lean of 0.007).
#[allow(clippy::too_many_arguments)]
pub fn lateral_lean(
    classes: &[u8],
    width: usize,
    maps: (&Homography, &Homography),
    blocked: &[bool],
    (gw, gh): (u32, u32),
    nadir: Point,
    (xi, yi): (i64, i64),
    (dx, dy): (i64, i64),
) -> Option<f64> {
    let (inside, is_blocked) = lookups(blocked, (gw, gh));
    // Across the run: the cell's coordinate and the nadir's.
    let (l, nl) = if dx != 0 {
        (yi, nadir.1)
    } else {
        (xi, nadir.0)
    };
    let l = l as f64;
    // The side away from the nadir, its distance from the nadir, and the far and near borders.
    let (side, d_lat, border, near) = if nl < l {
        (1i64, l + 1.0 - nl, l + 1.0, l)
    } else if nl > l + 1.0 {
        (-1, nl - l, l, l + 1.0)
    } else {
        return None;
    };
    let across = |cell: (i64, i64), at: f64| Band {
        cell,
        along_x: dx != 0,
        border: at,
    };
    let mut overhangs = Vec::new();
    let mut t = 1i64;
    while is_blocked(xi - t * dx, yi - t * dy) {
        let (rx, ry) = (xi - t * dx, yi - t * dy);
        let (q, p) = if dx != 0 {
            ((rx, ry + side), (rx, ry - side))
        } else {
            ((rx + side, ry), (rx - side, ry))
        };
        t += 1;
        if !inside(q.0, q.1) || is_blocked(q.0, q.1) {
            continue;
        }
        let Some(over) = across(q, border).covered(classes, width, maps) else {
            continue;
        };
        let gap = if is_blocked(p.0, p.1) {
            None
        } else {
            across((rx, ry), near)
                .covered(classes, width, maps)
                .map(|c| 0.5 * (1.0 - c))
        };
        overhangs.push(0.5 * over + gap.map_or(INSET, |g| g.min(INSET)));
    }
    if overhangs.is_empty() {
        return None;
    }
    overhangs.sort_by(f64::total_cmp);
    Some(overhangs[overhangs.len() / 2] / d_lat)
}

/// A lean measured beside a run ([`lateral_lean`]) reaching this far (cells) over the run's far
/// cell leaves too little of the cell beyond it, past the blur (a tenth of a cell) and a painted
/// line or tile seam along the outer border ([`super::looks::BORDER`]), to show the floor of a
/// free cell: the cell is in doubt. Since issue #29's twenty-sixth round, when the lean became a
/// measure rather than a bound (the free p0007 (7, 1), under the top of a salmon shelf leaning
/// 0.8 cell over it, its fit misfit by blur, was read blocked).
pub const THIN: f64 = 0.75;

/// A band half a cell wide inside `cell`, along one of its borders: `border`, the floor
/// coordinate across the run (v for a run along x, else u).
struct Band {
    cell: (i64, i64),
    along_x: bool,
    border: f64,
}

impl Band {
    /// The share of the band's pixels read as obstacle (or unsure), of those read as floor or
    /// obstacle; `None` when the band shows none.
    fn covered(
        &self,
        classes: &[u8],
        width: usize,
        (floor_to_image, image_to_floor): (&Homography, &Homography),
    ) -> Option<f64> {
        let height = classes.len() / width.max(1);
        let (qx, qy) = self.cell;
        if qx < 0 || qy < 0 {
            return None;
        }
        let (x0, y0, x1, y1) = floor_to_image.cell_box((qx as u32, qy as u32), width, height)?;
        let (mut all, mut covered) = (0usize, 0usize);
        for py in y0..y1 {
            for px in x0..x1 {
                let Some((u, v)) = image_to_floor.apply((px as f64 + 0.5, py as f64 + 0.5)) else {
                    continue;
                };
                if u.floor() as i64 != qx || v.floor() as i64 != qy {
                    continue;
                }
                let across = if self.along_x { v } else { u };
                if (across - self.border).abs() >= 0.5 {
                    continue;
                }
                let c = classes[py * width + px];
                if c == Class::Obstacle as u8 || c == Class::Unsure as u8 {
                    covered += 1;
                    all += 1;
                } else if c == Class::Floor as u8 {
                    all += 1;
                }
            }
        }
        (all > 0).then(|| covered as f64 / all as f64)
    }
}

/// What the faces toward the nadir tell of a covered cell (`(x, y)`, blocked in `blocked`)
/// that a neighbour's leaning top may cover almost whole ([`Fit::doubtful`]), read as the far
/// cell of each run of blocked cells behind it (toward the nadir) with a free cell beyond it
/// (not the floor's edge: see [`lean_doubt`]): `None` when a run's face is too short for a top leaning over the
/// cell ([`face::Face::Own`]) and no run's face is as long as that needs
/// ([`face::Face::Long`]): the cell is the run's own. Otherwise the doubt: along a run whose
/// face is long, with nothing more to tell; else along the run whose face is hidden if one is
/// ([`face::Face::Hidden`], for the reader to judge with the sun and the view's other faces),
/// else along the first run, or with no direction (`(0, 0)`) when no run ends there. Since
/// issue #29's twenty-third round.
pub fn face_tells(
    img: &RgbImage,
    classes: &[u8],
    (floor_to_image, image_to_floor): (&Homography, &Homography),
    (gw, gh): (u32, u32),
    blocked: &[bool],
    nadir: Point,
    (x, y): (u32, u32),
) -> Option<Doubt> {
    let (inside, is_blocked) = lookups(blocked, (gw, gh));
    let (xi, yi) = (i64::from(x), i64::from(y));
    let mut doubt = Doubt {
        dir: (0, 0),
        hidden_face: false,
    };
    let (mut own, mut long) = (false, None);
    for (dx, dy) in [(1i64, 0i64), (-1, 0), (0, 1), (0, -1)] {
        let free_beyond = inside(xi + dx, yi + dy) && !is_blocked(xi + dx, yi + dy);
        if !is_blocked(xi - dx, yi - dy) || !free_beyond {
            continue;
        }
        if !points_away((xi, yi), (dx, dy), nadir) {
            continue; // the run points toward the nadir: its top leans away from the cell
        }
        let (run, px) = run_to((x, y), (dx, dy), nadir, floor_to_image, is_blocked);
        match face::judge(img, classes, (floor_to_image, image_to_floor), run, px) {
            face::Face::Own => own = true,
            // A face as long as a free cell needs: whatever another run tells, in doubt.
            face::Face::Long => long = Some((dx, dy)),
            face::Face::Hidden if !doubt.hidden_face => {
                doubt = Doubt {
                    dir: (dx, dy),
                    hidden_face: true,
                }
            }
            _ if doubt.dir == (0, 0) => doubt.dir = (dx, dy),
            _ => {}
        }
    }
    match long {
        Some(dir) => Some(Doubt {
            dir,
            hidden_face: false,
        }),
        None if own => None,
        None => Some(doubt),
    }
}

/// Whether a cell (x, y) lies on the floor of `gw` × `gh` cells, and whether it is blocked there
/// (`blocked`, row-major; a cell off the floor is not).
fn lookups(
    blocked: &[bool],
    (gw, gh): (u32, u32),
) -> (
    impl Fn(i64, i64) -> bool + Copy,
    impl Fn(i64, i64) -> bool + Copy + '_,
) {
    let inside =
        move |cx: i64, cy: i64| cx >= 0 && cy >= 0 && cx < i64::from(gw) && cy < i64::from(gh);
    let is_blocked =
        move |cx: i64, cy: i64| inside(cx, cy) && blocked[(cy * i64::from(gw) + cx) as usize];
    (inside, is_blocked)
}

/// Whether a run of cells along `(dx, dy)` ending at cell `(x, y)` points away from the nadir:
/// the cell's inner border (toward the run) lies beyond the nadir along that step.
fn points_away((x, y): (i64, i64), (dx, dy): (i64, i64), nadir: Point) -> bool {
    let (inner, na) = if dx != 0 {
        (x as f64 + if dx > 0 { 0.0 } else { 1.0 }, nadir.0)
    } else {
        (y as f64 + if dy > 0 { 0.0 } else { 1.0 }, nadir.1)
    };
    (inner - na) * (dx + dy) as f64 > 0.0
}

/// Whether free cell `(x, y)`, read as under the top of the run of blocked cells (in
/// `blocked`) before it along an axis, toward the nadir, leaning at scale `k` (its fit), lacks
/// the face that lean needs at the run's near end: a top scaled by k shows the run's face
/// toward the nadir (k − 1) times the near border's distance from the nadir long, and when
/// that is at least [`face::HIDDEN_FREE`] and the run's cover shows none, or a plain one half
/// as long or less ([`face::judge_lean`]), the run does not stand as read: it may start a cell
/// nearer, its face read as floor, and its top lean over the cell less than the fit says, or
/// cover it as the run's own (issue #29's held-out q0018: a slate-blue shelf three cells long
/// along the lean, read a cell short, its top read as leaning 0.88 cell over a free edge
/// cell). Returns the step from the run to the cell, with the lean's reach over the cell and
/// whether no face showed at all ([`face::Face::Hidden`]: then only when a face there would
/// show, for the reader to judge with the sun and the view's other faces, as for a run's far
/// cell).
#[allow(clippy::too_many_arguments)]
pub fn faceless_lean(
    img: &RgbImage,
    classes: &[u8],
    maps: (&Homography, &Homography),
    (gw, gh): (u32, u32),
    blocked: &[bool],
    nadir: Point,
    (x, y): (u32, u32),
    k: f64,
) -> Option<Faceless> {
    let (inside, is_blocked) = lookups(blocked, (gw, gh));
    let (xi, yi) = (i64::from(x), i64::from(y));
    for (dx, dy) in [(1i64, 0i64), (-1, 0), (0, 1), (0, -1)] {
        let (rx, ry) = (xi - dx, yi - dy);
        if !inside(rx, ry) || !is_blocked(rx, ry) {
            continue;
        }
        let (a, na) = if dx != 0 { (x, nadir.0) } else { (y, nadir.1) };
        let dir = (dx + dy) as f64;
        let inner = if dir > 0.0 {
            f64::from(a)
        } else {
            f64::from(a) + 1.0
        };
        if (inner - na) * dir <= 0.0 {
            continue; // the run lies beyond the cell from the nadir: its top leans away
        }
        let (run, px) = run_to((rx as u32, ry as u32), (dx, dy), nadir, maps.0, is_blocked);
        let near = inner - dir * run.cells as f64;
        let needed = (k - 1.0) * (near - na).abs();
        if needed < face::HIDDEN_FREE {
            continue;
        }
        let hidden = match face::judge_lean(img, classes, maps, run, px, needed) {
            face::Face::Hidden => true,
            face::Face::Own => false,
            face::Face::Long | face::Face::Unknown => continue,
        };
        return Some(Faceless {
            dir: (dx, dy),
            reach: (k - 1.0) * (inner - na).abs(),
            hidden,
        });
    }
    None
}

/// A free cell under a lean whose run shows no face as long ([`faceless_lean`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Faceless {
    /// The step from the run to the cell (away from the nadir).
    pub dir: (i64, i64),
    /// How far (cells) the lean reaches over the cell.
    pub reach: f64,
    /// No face showed at all (else a plain one, too short).
    pub hidden: bool,
}

/// The run of blocked cells (`is_blocked`) ending at cell `(x, y)` along `(dx, dy)` (away from
/// the nadir), for [`face::judge`], and the cell's size in pixels along the run there.
fn run_to(
    (x, y): (u32, u32),
    (dx, dy): (i64, i64),
    nadir: Point,
    floor_to_image: &Homography,
    is_blocked: impl Fn(i64, i64) -> bool,
) -> (face::Run, f64) {
    let (xi, yi) = (i64::from(x), i64::from(y));
    let mut cells = 1;
    while is_blocked(xi - cells * dx, yi - cells * dy) {
        cells += 1;
    }
    let (far, across, na) = if dx != 0 {
        (xi, yi, nadir.0)
    } else {
        (yi, xi, nadir.1)
    };
    let run = face::Run {
        along_u: dx != 0,
        dir: (dx + dy) as f64,
        far,
        across,
        cells,
        nadir: na,
    };
    let centre = (x as f64 + 0.5, y as f64 + 0.5);
    let px = match (
        floor_to_image.apply(centre),
        floor_to_image.apply((centre.0 + dx as f64, centre.1 + dy as f64)),
    ) {
        (Some(p), Some(q)) => (p.0 - q.0).hypot(p.1 - q.1),
        _ => 0.0,
    };
    (run, px)
}

/// Whether another run of blocked cells pointing `(dx, dy)` away from the nadir (its far cell
/// with a free cell or the floor's edge beyond) shows its face toward the nadir plainly unlike
/// its top, whatever the face's length ([`face::shows`]): faces that look the same way are lit
/// alike in one view (the sun's and the sky's light on a face, over the light on the top, does
/// not depend on the paint), so a face of a run pointing that way that shows nothing is no
/// face. Runs whose far cell is in `doubted` are left out. Since issue #29's twenty-third
/// round; see [`face::Face::Hidden`].
#[allow(clippy::too_many_arguments)]
pub fn face_shown(
    img: &RgbImage,
    classes: &[u8],
    (floor_to_image, image_to_floor): (&Homography, &Homography),
    (gw, gh): (u32, u32),
    blocked: &[bool],
    nadir: Point,
    (dx, dy): (i64, i64),
    doubted: &[usize],
) -> bool {
    let (_, is_blocked) = lookups(blocked, (gw, gh));
    (0..gw as usize * gh as usize).any(|i| {
        let (xi, yi) = ((i % gw as usize) as i64, (i / gw as usize) as i64);
        if !blocked[i] || doubted.contains(&i) {
            return false;
        }
        if is_blocked(xi + dx, yi + dy) {
            return false;
        }
        if !points_away((xi, yi), (dx, dy), nadir) {
            return false;
        }
        let (run, px) = run_to(
            (xi as u32, yi as u32),
            (dx, dy),
            nadir,
            floor_to_image,
            is_blocked,
        );
        face::shows(img, classes, (floor_to_image, image_to_floor), run, px)
    })
}

/// A far cell's own top shows when the cover past it reaches this many times further than the
/// run's top could lean from the far cell's inner border (at the largest lean measured beside
/// the run, [`lean_doubt`]).
pub const PAST_MARGIN: f64 = 1.2;

/// The free cells past a run's far cell, away from the nadir: see [`Past::cover`].
struct Past {
    /// The far cell.
    cell: (i64, i64),
    /// One cell away from the nadir, along the run.
    step: (i64, i64),
    /// The nadir's coordinate across the run.
    nadir_across: f64,
    /// The largest lean scale of the run's top.
    k: f64,
}

/// The slices (in cells) of the cover's profile past a far cell.
const PAST_SLICE: f64 = 0.04;

impl Past {
    /// How far (in cells) an obstacle's cover runs on unbroken past the far cell's outer
    /// border, away from the nadir, over the free cells there (at most two), under the middle
    /// half of the far cell's top (at least the free cells' length when it runs on over all of
    /// them). `None` when that cannot be measured: no free cell past it, or a blocked cell
    /// beside those free cells, on the nadir's side, may lean its own top over them.
    ///
    /// If the far cell is free under the run's top, that cover ends where the run's top ends,
    /// at most `reach − 1` past it (`reach` the largest lean from the far cell's inner
    /// border); a cover running on further is the far cell's own top (issue #29's fourteenth
    /// round: on families A–F and K–Z, no free far cell's cover ran on past 1.01 times the
    /// reach, and that of 47 blocked ones past 1.2 times).
    fn cover(
        &self,
        classes: &[u8],
        width: usize,
        maps: (&Homography, &Homography),
        is_blocked: &dyn Fn(i64, i64) -> bool,
        inside: impl Fn(i64, i64) -> bool,
    ) -> Option<f64> {
        let ((x, y), (dx, dy)) = (self.cell, self.step);
        // Across the run: the lateral offset of a cell by `s`.
        let beside = |cx: i64, cy: i64, s: i64| if dx != 0 { (cx, cy + s) } else { (cx + s, cy) };
        let (a, l) = if dx != 0 { (x, y) } else { (y, x) };
        let mut free = 0usize;
        for t in 1..=2i64 {
            let (cx, cy) = (x + t * dx, y + t * dy);
            if !inside(cx, cy) || is_blocked(cx, cy) {
                break;
            }
            // The side toward the nadir, or both when it is in line with the far cell.
            let sides: &[i64] = if self.nadir_across < l as f64 {
                &[-1]
            } else if self.nadir_across > l as f64 + 1.0 {
                &[1]
            } else {
                &[-1, 1]
            };
            if sides.iter().any(|&s| {
                let (bx, by) = beside(cx, cy, s);
                is_blocked(bx, by)
            }) {
                return None;
            }
            free += 1;
        }
        if free == 0 {
            return None;
        }
        let along_u = dx != 0;
        let dir = (dx + dy) as f64;
        let outer = if dir > 0.0 { a as f64 + 1.0 } else { a as f64 };
        // The middle half of the far cell across, where its top (or the run's) stands.
        let nadir_l = self.nadir_across;
        let (l0, l1) = (l as f64 + 0.25, l as f64 + 0.75);
        let (t0, t1) = (
            nadir_l + self.k * (l0 - nadir_l),
            nadir_l + self.k * (l1 - nadir_l),
        );
        let slices = (free as f64 / PAST_SLICE).round() as usize;
        let strip = Strip {
            along_u,
            from: outer,
            dir,
            step: PAST_SLICE,
            n: slices,
            across: (t0.min(t1), t0.max(t1)),
        };
        let p = profile(classes, width, maps, &strip);
        // A cover that never ends runs on at least over those free cells.
        Some(cover_end(&p).map_or(free as f64, |e| e as f64 * PAST_SLICE))
    }
}

/// A strip of the floor cut into slices: `n` slices of `step` cells along one floor axis
/// (`along_u`: the u axis), from `from` in the direction `dir` (±1), over the pixels whose floor
/// points lie within `across` on the other axis.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Strip {
    pub along_u: bool,
    pub from: f64,
    pub dir: f64,
    pub step: f64,
    pub n: usize,
    pub across: (f64, f64),
}

/// One slice of a [`Strip`]: its pixels on the floor, its obstacle pixels among them and, when
/// the image is given, the sum of their brightness (the mean of the three channels, 0–255).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub(crate) struct SliceSum {
    pub pixels: u32,
    pub obstacle: u32,
    pub brightness: f64,
}

/// The slices of `strip` (all empty when the strip misses the image): the one walk over the
/// pixels behind the cover's [`profile`] and the face's (`face::judge`).
pub(crate) fn slices(
    classes: &[u8],
    width: usize,
    (floor_to_image, image_to_floor): (&Homography, &Homography),
    strip: &Strip,
    img: Option<&RgbImage>,
) -> Vec<SliceSum> {
    let Strip {
        along_u,
        from,
        dir,
        step,
        n,
        across,
    } = *strip;
    let height = classes.len() / width.max(1);
    let to = from + dir * step * n as f64;
    let (a0, a1) = (from.min(to), from.max(to));
    let (u0, v0, u1, v1) = if along_u {
        (a0, across.0, a1, across.1)
    } else {
        (across.0, a0, across.1, a1)
    };
    let mut sums = vec![SliceSum::default(); n];
    let Some((x0, y0, x1, y1)) = floor_to_image.floor_box((u0, v0), (u1, v1), (width, height))
    else {
        return sums;
    };
    for py in y0..y1 {
        for px in x0..x1 {
            let Some((u, v)) = image_to_floor.apply((px as f64 + 0.5, py as f64 + 0.5)) else {
                continue;
            };
            let (a, l) = if along_u { (u, v) } else { (v, u) };
            let t = (a - from) * dir / step;
            if l < across.0 || l >= across.1 || t < 0.0 || t >= n as f64 {
                continue;
            }
            let c = classes[py * width + px];
            if c == OUTSIDE {
                continue;
            }
            let s = &mut sums[t as usize];
            s.pixels += 1;
            s.obstacle += u32::from(c == Class::Obstacle as u8);
            if let Some(img) = img {
                let p = img.get_pixel(px as u32, py as u32).0;
                s.brightness += (f64::from(p[0]) + f64::from(p[1]) + f64::from(p[2])) / 3.0;
            }
        }
    }
    sums
}

/// The share of obstacle pixels per slice of `strip`; `NaN` for a slice without pixels.
fn profile(
    classes: &[u8],
    width: usize,
    maps: (&Homography, &Homography),
    strip: &Strip,
) -> Vec<f64> {
    slices(classes, width, maps, strip, None)
        .iter()
        .map(|s| {
            if s.pixels == 0 {
                f64::NAN
            } else {
                f64::from(s.obstacle) / f64::from(s.pixels)
            }
        })
        .collect()
}

/// Where the cover along a [`profile`] ends: the slices before the first one under half
/// covered (slices without pixels, finer than the image, are passed over); `None` when it
/// never ends.
fn cover_end(profile: &[f64]) -> Option<usize> {
    profile.iter().position(|&s| s < 0.5)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 4 × 4 floor of 10 px cells seen straight down, cells (1, 2) and (1, 3) blocked (their
    /// pixels an obstacle's), with the obstacle's colour also on cell (2, 2) for u in 2..`over`.
    fn edge_floor(over: f64) -> (Vec<u8>, Homography, Homography, Vec<bool>) {
        let f2i = Homography::floor_to_image(
            4.0,
            4.0,
            [(0.0, 0.0), (40.0, 0.0), (40.0, 40.0), (0.0, 40.0)],
        )
        .unwrap();
        let i2f = f2i.inverse().unwrap();
        let mut blocked = vec![false; 16];
        blocked[2 * 4 + 1] = true;
        blocked[3 * 4 + 1] = true;
        let mut classes = vec![Class::Floor as u8; 40 * 40];
        for y in 0..40usize {
            for x in 0..40usize {
                let (u, v) = ((x as f64 + 0.5) / 10.0, (y as f64 + 0.5) / 10.0);
                if (blocked[(v as usize) * 4 + u as usize])
                    || ((2.0..3.0).contains(&v) && (2.0..over).contains(&u))
                {
                    classes[y * 40 + x] = Class::Obstacle as u8;
                }
            }
        }
        (classes, f2i, i2f, blocked)
    }

    /// A floor of 10 × 4 cells of 10 px seen straight down, its floor of shade 120, with an
    /// obstacle of shade `shade(u, v)` (floor coordinates of the pixel's centre) over the
    /// pixels of columns `xs` and of the rows from each pair's first to its end in `rows`, and
    /// `blocked` cells: the image, the pixels'
    /// classes, the maps and the blocked cells.
    fn floor_of_10x4(
        xs: std::ops::Range<u32>,
        rows: &[(u32, u32)],
        shade: impl Fn(f64, f64) -> u8,
        blocked_cells: &[usize],
    ) -> (RgbImage, Vec<u8>, Homography, Homography, Vec<bool>) {
        let f2i = Homography::floor_to_image(
            10.0,
            4.0,
            [(0.0, 0.0), (100.0, 0.0), (100.0, 40.0), (0.0, 40.0)],
        )
        .unwrap();
        let i2f = f2i.inverse().unwrap();
        let mut img = RgbImage::from_pixel(100, 40, image::Rgb([120, 120, 120]));
        let mut classes = vec![Class::Floor as u8; 100 * 40];
        for y in rows.iter().flat_map(|&(first, end)| first..end) {
            for x in xs.clone() {
                let (u, v) = ((f64::from(x) + 0.5) / 10.0, (f64::from(y) + 0.5) / 10.0);
                img.put_pixel(x, y, image::Rgb([shade(u, v); 3]));
                classes[(y * 100 + x) as usize] = Class::Obstacle as u8;
            }
        }
        let mut blocked = vec![false; 40];
        for &i in blocked_cells {
            blocked[i] = true;
        }
        (img, classes, f2i, i2f, blocked)
    }

    #[test]
    fn a_view_s_faces_that_look_one_way_show_alike() {
        // A floor of 10 × 4 cells of 10 px seen straight down, the nadir 20 cells before its
        // left edge; runs of cells 2–5 along rows 1 and 3, each top (shade 160) ending at
        // u = 6.52. Row 1's face (shade `face`, from its base at u = 2 to 2.44) is plain or
        // of the top's shade; row 3 shows none.
        let view = |face: u8| {
            floor_of_10x4(
                20..65,
                &[(10, 20), (30, 40)],
                |u, v| if v < 2.0 && u < 2.44 { face } else { 160 },
                &[12, 13, 14, 15, 32, 33, 34, 35],
            )
        };
        let shown = |face: u8, dir: (i64, i64), doubted: &[usize]| {
            let (img, classes, f2i, i2f, blocked) = view(face);
            face_shown(
                &img,
                &classes,
                (&f2i, &i2f),
                (10, 4),
                &blocked,
                (-20.0, 2.0),
                dir,
                doubted,
            )
        };
        // Row 3's far cell in doubt: row 1's face tells how faces looking left show.
        assert!(shown(80, (1, 0), &[35]));
        // Row 1's face of the top's shade tells nothing.
        assert!(!shown(160, (1, 0), &[35]));
        // Nor does a run whose far cell is itself in doubt.
        assert!(!shown(80, (1, 0), &[15, 35]));
        // Nor runs pointing the other way (toward the nadir: no face shows toward it).
        assert!(!shown(80, (-1, 0), &[35]));
    }

    #[test]
    fn a_top_leans_over_a_cell_only_from_a_blocked_cell_beside_it() {
        // The nadir far to the right of cell (1, 0), level with its middle: a point of it walks
        // right, toward the nadir, into cell (2, 0), then (3, 0).
        let nadir = (20.0, 0.5);
        let p = (1.9, 0.5);
        // Cell (2, 0) blocked: its top reaches p at a scale of 18.1 / 18.0.
        let beside = |x: i64, y: i64| (x, y) == (2, 0);
        let k = reach(p, nadir, (1, 0), &beside);
        assert!((k - 18.1 / 18.0).abs() < 0.01, "{k}");
        // Only cell (3, 0) blocked, (2, 0) between them free: a top leaning from (3, 0) over p
        // would cover (2, 0) whole, and (2, 0) is not covered: none reaches p.
        let across = |x: i64, y: i64| (x, y) == (3, 0);
        assert!(reach(p, nadir, (1, 0), &across).is_infinite());
        // Walking diagonally past a corner of a free cell into a blocked one still reaches.
        let diagonal = |x: i64, y: i64| (x, y) == (2, 1);
        let k = reach((1.95, 0.9), (20.0, 10.0), (1, 0), &diagonal);
        assert!(k.is_finite() && k < 1.02, "{k}");
    }

    #[test]
    fn a_long_lean_needs_its_face() {
        // A floor of 10 × 4 cells of 10 px seen straight down, the nadir at (−20, 1.5); cells
        // 2–4 of row 1 blocked, cell (5, 1) free under their top, fitted at k = 1.04: the top
        // leans a cell over it (to u = 6) and shows the run's face toward the nadir
        // 0.04 × 22 = 0.88 cell long. The face (shade 80) runs from u = 2 to `face_end`, the
        // top (shade 160) on to u = 6.
        let lacking = |face_end: f64, k: f64| {
            let (img, classes, f2i, i2f, blocked) = floor_of_10x4(
                20..60,
                &[(10, 20)],
                |u, _| if u < face_end { 80 } else { 160 },
                &[12, 13, 14],
            );
            faceless_lean(
                &img,
                &classes,
                (&f2i, &i2f),
                (10, 4),
                &blocked,
                (-20.0, 1.5),
                (5, 1),
                k,
            )
        };
        // The face shows as long as the lean makes: the lean stands.
        assert_eq!(lacking(2.88, 1.04), None);
        // No face: the run may stand a cell nearer.
        let none = lacking(2.0, 1.04).unwrap();
        assert!(none.hidden && none.dir == (1, 0), "{none:?}");
        assert!((none.reach - 1.0).abs() < 1e-9);
        // A plain face 0.4 cell long, under half what the lean makes.
        let short = lacking(2.4, 1.04).unwrap();
        assert!(!short.hidden, "{short:?}");
        // A lean of k = 1.01 makes a face of 0.22 cell: too short to tell.
        assert_eq!(lacking(2.0, 1.01), None);
        // No blocked cell before the cell toward the nadir: no lean to judge.
        let (img, classes, f2i, i2f, blocked) = floor_of_10x4(20..60, &[(10, 20)], |_, _| 160, &[]);
        assert_eq!(
            faceless_lean(
                &img,
                &classes,
                (&f2i, &i2f),
                (10, 4),
                &blocked,
                (-20.0, 1.5),
                (5, 1),
                1.03
            ),
            None
        );
    }

    #[test]
    fn the_lean_beside_a_run_is_measured_through_blur() {
        // A floor of 10 × 4 cells of 50 px seen straight down, cells 2–4 of row 1 blocked, the
        // nadir at (−20, 11): 10 cells across from the run's far side (row 0). A top inset 0.06
        // cell and scaled by k = 1.02 overhangs row 0 by 0.02 × 10 − 0.06 = 0.14 cell and
        // leaves 0.06 of floor along the near border; blur widens the cover by `blur` (a
        // multiple of a pixel, 0.02 cell) on both sides.
        let lean = |blur: f64, near_blocked: bool| {
            let f2i = Homography::floor_to_image(
                10.0,
                4.0,
                [(0.0, 0.0), (500.0, 0.0), (500.0, 200.0), (0.0, 200.0)],
            )
            .unwrap();
            let i2f = f2i.inverse().unwrap();
            let mut blocked = vec![false; 40];
            for x in 2..5 {
                blocked[10 + x] = true;
            }
            if near_blocked {
                blocked[20 + 3] = true;
            }
            let mut classes = vec![Class::Floor as u8; 500 * 200];
            for y in 0..200usize {
                for x in 0..500usize {
                    let (u, v) = ((x as f64 + 0.5) / 50.0, (y as f64 + 0.5) / 50.0);
                    if (2.0..5.0).contains(&u) && (0.86 - blur..1.94 + blur).contains(&v) {
                        classes[y * 500 + x] = Class::Obstacle as u8;
                    }
                }
            }
            lateral_lean(
                &classes,
                500,
                (&f2i, &i2f),
                &blocked,
                (10, 4),
                (-20.0, 11.0),
                (5, 1),
                (1, 0),
            )
            .unwrap()
        };
        for blur in [0.0, 0.04] {
            let e = lean(blur, false);
            assert!((e - 0.02).abs() < 1e-9, "blur {blur}: {e}");
        }
        // Blur wider than the inset fills the gap: the lean is overestimated, never less.
        let e = lean(0.08, false);
        assert!((e - 0.022).abs() < 1e-9, "{e}");
        // A blocked cell on the near side may lean its top into the gap: the allowance stands
        // for it there (the median of the run's three cells is unchanged by one).
        assert!((lean(0.0, true) - 0.02).abs() < 1e-9);
        // The nadir across from the run's middle: no side away from it.
        let f2i = Homography::floor_to_image(
            10.0,
            4.0,
            [(0.0, 0.0), (100.0, 0.0), (100.0, 40.0), (0.0, 40.0)],
        )
        .unwrap();
        let i2f = f2i.inverse().unwrap();
        let blocked: Vec<bool> = (0..40).map(|i| (12..15).contains(&i)).collect();
        let classes = vec![Class::Floor as u8; 100 * 40];
        assert_eq!(
            lateral_lean(
                &classes,
                100,
                (&f2i, &i2f),
                &blocked,
                (10, 4),
                (-20.0, 1.5),
                (5, 1),
                (1, 0)
            ),
            None
        );
    }

    #[test]
    fn an_edge_cell_behind_a_top_that_may_lean_over_it_is_in_doubt() {
        let doubt_at = |over: f64, nadir: Point, cell: (u32, u32)| {
            let (classes, f2i, i2f, blocked) = edge_floor(over);
            lean_doubt(
                &RgbImage::new(40, (classes.len() / 40) as u32),
                &classes,
                40,
                (&f2i, &i2f),
                (4, 4),
                &blocked,
                nadir,
                cell,
                Beyond::Edge,
            )
            .is_some()
        };
        let doubt = |over: f64, nadir: Point| doubt_at(over, nadir, (1, 3));
        // No overhang beside the obstacle, whose cover meets its cells' borders on both sides:
        // its top does not lean, however far the nadir.
        assert!(!doubt(2.0, (0.5, -20.0)));
        // An overhang of 0.1 cell, 1.5 cells across from the nadir: k = 1 + 0.1 / 1.5; from a
        // nadir 2.5 cells from the edge cell its top leans 0.17 cell, from one 23 cells away
        // 1.5 cells.
        assert!(!doubt(2.1, (0.5, 0.5)));
        assert!(doubt(2.1, (0.5, -20.0)));
        // From a nadir 4 cells away: an overhang of 0.25 cell (k = 1 + 1 / 6) leans a top 0.67
        // cell, leaving a third of the edge cell to show the floor; one of 0.3 (k = 1.2), 0.8
        // cell, too little of it ([`THIN`]).
        assert!(!doubt(2.25, (0.5, -1.0)));
        assert!(doubt(2.3, (0.5, -1.0)));
        // The nadir beyond the edge: tops lean the other way.
        assert!(!doubt(2.3, (0.5, 9.0)));
        // Not on the edge, or nothing blocked behind it.
        assert!(!doubt_at(2.0, (0.5, -20.0), (1, 2)));
        assert!(!doubt_at(2.0, (0.5, -20.0), (3, 3)));
    }

    #[test]
    fn an_edge_cell_is_not_told_by_its_run_s_face() {
        // A floor of 10 × 4 cells of 10 px seen straight down, the nadir 20 cells before its
        // left edge, level with row 1; cells 6–9 of row 1 blocked, the last on the floor's
        // right edge. Their cover runs from u = 6 to the edge: a face of shade `face` up to
        // `face_end`, then a top of shade 160, on floor of shade 120. Nothing beside the run
        // measures its lean (k taken at 1.25): a free edge cell would need a top leaning from
        // u = 9 to the edge at least, k = 30 / 29, and so a face at least 0.9 cell long.
        let doubt = |face_end: f64, face: u8| {
            let (img, classes, f2i, i2f, blocked) = floor_of_10x4(
                60..100,
                &[(10, 20)],
                |u, _| if u < face_end { face } else { 160 },
                &[16, 17, 18, 19],
            );
            lean_doubt(
                &img,
                &classes,
                100,
                (&f2i, &i2f),
                (10, 4),
                &blocked,
                (-20.0, 1.5),
                (9, 1),
                Beyond::Edge,
            )
        };
        // The top's end does not show past the edge: however short the face (0.35 cell, 4 px,
        // plainly darker), as long as a free edge cell needs, or none, the cell is in doubt,
        // for the shadow beside it to tell.
        for face_end in [6.45, 6.95, 6.0] {
            assert!(doubt(face_end, 80).is_some_and(|d| !d.hidden_face));
        }
    }

    #[test]
    fn a_cell_a_top_may_cover_almost_whole_is_told_by_the_faces_of_the_runs_ending_there() {
        // A floor of 10 × 4 cells of 10 px seen straight down: cells 6 and 7 of row 1 blocked
        // and the cell (8, 1) covered, a free cell beyond it, their cover from u = 6 to 9 with
        // a face of shade 80 up to `face_end` and a top of shade 160, on floor of shade 120;
        // with `column`, cells (8, 2) and (8, 3) blocked too, their cover (and (8, 1)'s) a top
        // of shade 160 with a face 0.95 cell long at its end toward the nadir, below. The nadir
        // 20 cells before the left edge and 20 below the top one.
        let tells = |face_end: f64, column: bool| {
            let (mut img, mut classes, f2i, i2f, mut blocked) = floor_of_10x4(
                60..90,
                &[(10, 20)],
                |u, _| if u < face_end { 80 } else { 160 },
                &[16, 17],
            );
            if column {
                let (column_img, column_classes, ..) = floor_of_10x4(
                    80..90,
                    &[(20, 40)],
                    |_, v| if v > 3.05 { 80 } else { 160 },
                    &[],
                );
                for y in 20..40u32 {
                    for x in 80..90u32 {
                        img.put_pixel(x, y, *column_img.get_pixel(x, y));
                        classes[(y * 100 + x) as usize] = column_classes[(y * 100 + x) as usize];
                    }
                }
                blocked[28] = true;
                blocked[38] = true;
            }
            face_tells(
                &img,
                &classes,
                (&f2i, &i2f),
                (10, 4),
                &blocked,
                (-20.0, 20.0),
                (8, 1),
            )
        };
        // The row's face too short for a top leaning over the cell: the run's own.
        assert_eq!(tells(6.45, false), None);
        // As long as a free cell needs: in doubt along the row, nothing more told.
        assert_eq!(
            tells(6.95, false),
            Some(Doubt {
                dir: (1, 0),
                hidden_face: false
            })
        );
        // No face: in doubt, for the sun and the view's other faces to tell.
        assert_eq!(
            tells(6.0, false),
            Some(Doubt {
                dir: (1, 0),
                hidden_face: true
            })
        );
        // The column's long face is as a free cell's under its top: in doubt whatever the
        // row's face tells.
        assert_eq!(
            tells(6.45, true),
            Some(Doubt {
                dir: (0, -1),
                hidden_face: false
            })
        );
    }

    #[test]
    fn a_far_cell_whose_cover_runs_on_past_the_run_s_reach_is_no_doubt() {
        // A 4 × 8 floor of 10 px cells seen straight down, the nadir at (-1, -8): cells
        // (1, 2)–(1, 4) blocked, their top overhanging cells (2, 2)–(2, 4) by 0.3 cell and
        // meeting the run's near border, so k = 1 + 0.3 / 3 and the run's top reaches 1.2 cells
        // past the far cell (1, 4)'s inner border. Its cover runs on `past` cells past the far
        // cell.
        let doubt_over = |past: f64, beside: bool, over: f64| {
            let f2i = Homography::floor_to_image(
                4.0,
                8.0,
                [(0.0, 0.0), (40.0, 0.0), (40.0, 80.0), (0.0, 80.0)],
            )
            .unwrap();
            let i2f = f2i.inverse().unwrap();
            let mut blocked = vec![false; 32];
            for y in 2..5 {
                blocked[y * 4 + 1] = true;
            }
            blocked[5 * 4] = beside;
            let mut classes = vec![Class::Floor as u8; 40 * 80];
            for y in 0..80usize {
                for x in 0..40usize {
                    let (u, v) = ((x as f64 + 0.5) / 10.0, (y as f64 + 0.5) / 10.0);
                    let run = (1.0..2.0 + over).contains(&u) && (2.0..5.0).contains(&v);
                    let on = (1.0..2.0).contains(&u) && (5.0..5.0 + past).contains(&v);
                    if run || on {
                        classes[y * 40 + x] = Class::Obstacle as u8;
                    }
                }
            }
            lean_doubt(
                &RgbImage::new(40, (classes.len() / 40) as u32),
                &classes,
                40,
                (&f2i, &i2f),
                (4, 8),
                &blocked,
                (-1.0, -8.0),
                (1, 4),
                Beyond::Free,
            )
        };
        let doubt_beside = |past: f64, beside: bool| doubt_over(past, beside, 0.3);
        let doubt = |past: f64| doubt_beside(past, false);
        // The cover ends 0.1 cell past the far cell: the run's top may end there, the far
        // cell free under it.
        assert_eq!(doubt(0.1).map(|d| d.dir), Some((0, 1)));
        // It runs on 0.8 cell: further than the run's top reaches (1.8 > 1.2 × 1.2 cells from
        // the far cell's inner border), so the far cell's own top.
        assert_eq!(doubt(0.8), None);
        // Over both free cells past it: as far at least.
        assert_eq!(doubt(3.0), None);
        // A blocked cell beside the free cell past it, toward the nadir, may lean its top
        // over it: the cover there tells nothing.
        assert_eq!(doubt_beside(0.8, true).map(|d| d.dir), Some((0, 1)));
        // Overhanging by 0.2 cell (k = 1 + 0.2 / 3), the run's top reaches 0.8 cell over the
        // far cell, too far for the rest to show the floor ([`THIN`]), and ends in it: a cover
        // past it (a seam's, a glow's) is the far cell's own top only when it runs on about as
        // far, at least half the reach.
        assert_eq!(doubt_over(0.2, false, 0.2).map(|d| d.dir), Some((0, 1)));
        assert_eq!(doubt_over(0.6, false, 0.2), None);
        // Overhanging by 0.15 cell, 0.6 cell: the rest of a free far cell shows the floor.
        assert_eq!(doubt_over(0.0, false, 0.15), None);
    }

    /// Bins of a cell whose part with fu (along u) in `covered_u` shows an obstacle.
    fn bins_covering(covered_u: std::ops::Range<f64>) -> Bins {
        let mut b = Bins {
            obstacle: [0; BINS * BINS],
            floor: [0; BINS * BINS],
        };
        for j in 0..BINS {
            for i in 0..BINS {
                let fu = (i as f64 + 0.5) / BINS as f64;
                if covered_u.contains(&fu) {
                    b.obstacle[j * BINS + i] = 4;
                } else {
                    b.floor[j * BINS + i] = 4;
                }
            }
        }
        b
    }

    #[test]
    fn bins_count_a_cell_s_pixels_on_the_floor() {
        // A 4 × 4-cell floor, 10 px a cell, straight down: cell (1, 2) is x 10..20, y 20..30.
        let width = 40;
        let mut classes = vec![Class::Floor as u8; width * 40];
        for y in 20..30 {
            for x in 10..13 {
                classes[y * width + x] = Class::Obstacle as u8;
            }
        }
        classes[25 * width + 15] = Class::Unsure as u8;
        let to_image = Homography::floor_to_image(
            4.0,
            4.0,
            [(0.0, 0.0), (40.0, 0.0), (40.0, 40.0), (0.0, 40.0)],
        )
        .unwrap();
        let b = bins(
            &classes,
            width,
            &to_image,
            &to_image.inverse().unwrap(),
            (1, 2),
        );
        for j in 0..BINS {
            for i in 0..BINS {
                let (o, f) = (b.obstacle[j * BINS + i], b.floor[j * BINS + i]);
                if i < 3 {
                    assert_eq!((o, f), (1, 0), "bin ({i}, {j})");
                } else if (i, j) == (5, 5) {
                    assert_eq!((o, f), (0, 0), "an unsure pixel counts as neither");
                } else {
                    assert_eq!((o, f), (0, 1), "bin ({i}, {j})");
                }
            }
        }
    }

    #[test]
    fn a_leaning_top_explains_the_near_part_of_a_free_cell() {
        // The nadir far to the right; cell (6, 9) with cell (7, 9) blocked: its top leans
        // 0.7 cell over (6, 9), from its right edge.
        let nadir = (40.0, 9.5);
        let sure = |x: i64, y: i64| (x, y) == (7, 9);
        let f = fit(&bins_covering(0.3..1.0), (6, 9), nadir, &sure).unwrap();
        assert!(f.free(), "{f:?}");
        assert!(f.k > 1.01 && f.k < 1.03, "{f:?}");
        assert!((f.evidence - 0.3).abs() < 1e-9);
    }

    #[test]
    fn cover_no_top_can_reach_is_not_explained() {
        let nadir = (40.0, 9.5);
        // Covered from the left, away from the nadir: nothing leans toward the nadir.
        let sure = |x: i64, y: i64| (x, y) == (5, 9);
        let f = fit(&bins_covering(0.0..0.6), (6, 9), nadir, &sure).unwrap();
        assert!(!f.free(), "{f:?}");
        // Covered in the middle, with the blocked neighbour toward the nadir: a lean would
        // cover the right part first.
        let sure = |x: i64, y: i64| (x, y) == (7, 9);
        let f = fit(&bins_covering(0.2..0.6), (6, 9), nadir, &sure).unwrap();
        assert!(!f.free(), "{f:?}");
        // Covered but for a tenth at the far edge: free; with less floor there, in doubt.
        let f = fit(&bins_covering(0.1..1.0), (6, 9), nadir, &sure).unwrap();
        assert!(f.free() && (f.evidence - 0.1).abs() < 1e-9, "{f:?}");
        let almost = Fit {
            k: 1.02,
            misfit: 0.0,
            evidence: 0.05,
        };
        assert!(!almost.free() && almost.doubtful());
        // Covered whole: blocked, no doubt.
        let f = fit(&bins_covering(0.0..1.0), (6, 9), nadir, &sure).unwrap();
        assert!(!f.free() && !f.doubtful(), "{f:?}");
    }

    #[test]
    fn a_thin_strip_beside_a_blocked_cell_is_bleed() {
        // The nadir below; cell (3, 4) blocked above (3, 5); a coloured strip of 0.2 cell
        // along their shared edge, on the side away from the camera.
        let nadir = (15.5, 11.5);
        let sure = |x: i64, y: i64| (x, y) == (3, 4);
        let mut b = Bins {
            obstacle: [0; BINS * BINS],
            floor: [4; BINS * BINS],
        };
        for i in 0..2 * BINS {
            (b.obstacle[i], b.floor[i]) = (4, 0);
        }
        let f = fit(&b, (3, 5), nadir, &sure).unwrap();
        assert!(f.free(), "{f:?}");
        // Without the blocked neighbour, the same strip is unexplained.
        let f = fit(&b, (3, 5), nadir, &|_, _| false).unwrap();
        assert!(!f.free(), "{f:?}");
    }

    #[test]
    fn a_blocked_cell_s_cover_running_on_past_the_bleed_is_no_glow() {
        // The nadir far to the left; cell (7, 9) blocked, to the right of (6, 9): its top leans
        // away from (6, 9). Cover along their shared edge, `depth` deep over the rows `rows`,
        // and a seam (a column of covered bins) at `seam` when given.
        let nadir = (-30.0, 9.5);
        let sure = |x: i64, y: i64| (x, y) == (7, 9);
        let free = |depth: f64, rows: std::ops::Range<usize>, seam: Option<usize>| {
            let mut b = Bins {
                obstacle: [0; BINS * BINS],
                floor: [4; BINS * BINS],
            };
            for j in 0..BINS {
                for i in 0..BINS {
                    let fu = (i as f64 + 0.5) / BINS as f64;
                    if (rows.contains(&j) && fu > 1.0 - depth) || seam == Some(i) {
                        (b.obstacle[j * BINS + i], b.floor[j * BINS + i]) = (4, 0);
                    }
                }
            }
            fit(&b, (6, 9), nadir, &sure).unwrap().free()
        };
        // A glow 0.2 deep along the whole edge: free.
        assert!(free(0.2, 0..10, None));
        // The cover running on 0.3 deep along the whole edge (10 bins amiss, within MISFIT),
        // or along 0.8 of it (p0035's (18, 15)): not free.
        assert!(!free(0.3, 0..10, None));
        assert!(!free(0.3, 2..10, None));
        // Along 0.6 of the edge, as a shadow's corner may be: free (6 bins amiss).
        assert!(free(0.3, 4..10, None));
        // A seam past the bleed, not joined to it: free (10 bins amiss).
        assert!(free(0.1, 0..10, Some(7)));
    }
}
