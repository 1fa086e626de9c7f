//! Does a free cell look like the floor?
//!
//! A cell is read as free when no obstacle colour covers it, so a shelf whose colour after
//! white balance is nearly grey (a pale colour on a floor of a similar hue: lilac on slate,
//! olive on sand) would read as free floor. Every free cell is therefore compared with the lit
//! floor, which after white balance is grey at brightness 1 (the floor's median colour): its
//! texture and uneven light vary that a little, a shadow only darkens it (grey, or tinted by
//! the sky's light), and painted lines lie along the cell's border. A free cell is refused,
//! never guessed, when the floor pixels of its middle (the window that a neighbour's leaning
//! top cannot reach, see [`super::pixels`], without a band of [`BORDER`] along the border
//! where lines are painted, and without the pixels near a robot or goal: a mark's blurred
//! edge, shadow and reflection) are
//! - brighter than the lit floor can be: a median more than [`BRIGHTER`] times the lit
//!   floor's, or
//! - lit (a median at least [`LIT`] times the lit floor's: no shadow) but tinted: their
//!   colour's saturation after white balance over [`TINTED`], or
//! - mostly (over [`UNSURE`]) of a colour that cannot be told.
//!
//! A darker cell (a shadow) is not judged by its colour: a shadow's tint depends on the light.
//!
//! A pale shelf's top of nearly the floor's colour may pass these limits cell by cell (uneven
//! light makes floor brighter than such a top), but it differs from the floor beside it over
//! its whole extent: [`unlike_ring`] refuses three or more lit free cells side by side each
//! brighter ([`RING`], or less on an even floor: [`ring_limit`]) or more saturated
//! ([`RING_TINT`]) than the lit free cells around them, or both at once by less
//! ([`RING_BOTH`]).

use super::blobs;
use super::colour::{Class, Classifier};
use super::homography::Homography;
use super::pixels::window;
use super::shadows;
use image::RgbImage;
use rayon::prelude::*;

/// The brightest a free cell's floor may be, relative to the lit floor's median.
pub const BRIGHTER: f64 = 1.35;
/// At least this bright (relative to the lit floor) a cell is lit, not in a shadow.
pub const LIT: f64 = 0.85;
/// The largest saturation after white balance of a lit free cell (the lit floor is grey).
pub const TINTED: f64 = 0.17;
/// The largest share of a free cell's middle's floor pixels that lean pale (their colour
/// averaged as in [`super::pixels`]: at least 1.3 times as bright as the lit floor, or at
/// least 0.8 with a saturation of 0.1; see [`super::pale`]) without making a pale obstacle.
/// A pixel whose tint the view's shadows' light explains is not counted
/// ([`super::pale::LEANED_IN_SHADE`]).
pub const LEANING: f64 = 0.5;
/// ... judged on at least this share of the cell's pixels. The middle shrinks where a
/// neighbour's top may lean over the cell and near a robot or a goal; a few dozen pixels
/// there, beside a mark (its colour's glow) or in a shadow's lit rim, lean pale as often as
/// not. On families A-F and K-Z, none of the cells read free but blocked in truth that this
/// check caught (pale tops) was judged on less than a tenth of its pixels, and 95 cells free
/// in truth were refused so (issue #29's fourteenth round).
pub const LEANING_SAMPLE: f64 = 0.1;
/// ... and on at least this many pixels: on families A-F and K-Z, 146 of the 274 cells free in
/// truth that the check refused were judged on fewer, and 19 of the 772 blocked ones it caught,
/// none of those then in a view that is read (another check refuses each; issue #29's
/// fourteenth round).
pub const LEANING_PIXELS: usize = 20;

/// A view's free floor leans pale when at least a quarter of its lit cells read free, judged on
/// [`LEANING_PIXELS`] or more, lean pale over at least this share of their middle's floor
/// ([`floor_leans`]).
pub const FLOOR_LEANS: f64 = 0.1;
/// [`floor_leans`] judges a view on at least this many cells.
pub const FLOOR_LEANS_CELLS: usize = 8;

/// Whether the view's free floor leans pale as a whole: the 75th percentile of the share of
/// their middle's floor that leans pale, over the lit cells read free (`looks`, one a cell,
/// `None` for a blocked one) judged on [`LEANING_PIXELS`] or more, is at least [`FLOOR_LEANS`]
/// (at least [`FLOOR_LEANS_CELLS`] of them). A pale shelf's top stands out of a floor that
/// does not lean pale; on a floor that does (a pale, grainy or unevenly lit floor: the Blender
/// families' white floors, sunlit sand), the cells that lean pale over half their middle were
/// all free in truth (issue #29's twenty-ninth round: 299 such cells over the 1840 views, and
/// none of the 707 pale tops the check caught lay in such a view; at 0.05, 27 of them did).
pub fn floor_leans(looks: &[Option<Look>]) -> bool {
    let mut shares: Vec<f64> = looks
        .iter()
        .flatten()
        .filter(|l| l.bright.is_some() && l.leaning.1 >= LEANING_PIXELS)
        .map(|l| l.leaning.0 as f64 / l.leaning.1 as f64)
        .collect();
    if shares.len() < FLOOR_LEANS_CELLS {
        return false;
    }
    let k = 3 * shares.len() / 4;
    *shares.select_nth_unstable_by(k, f64::total_cmp).1 >= FLOOR_LEANS
}
/// The largest share of a free cell's middle of a colour that cannot be told.
pub const UNSURE: f64 = 0.6;
/// The band along a cell's border (each side, in cells) that is not judged: painted lines (up
/// to 0.1 cell wide, twice as wide inside the floor's edge) and their blur.
pub const BORDER: f64 = 0.15;
/// The fewest pixels a cell's middle must show to be judged.
pub const MIN_PIXELS: usize = 12;
/// The brightest a region of [`RING_CELLS`] or more lit free cells side by side may be, each
/// relative to the lit free cells around it ([`ring_ratios`]): the floor's texture and light
/// change little from one cell to the next, while the top of a pale shelf of nearly the
/// floor's colour, nearer the light and the camera, is brighter than the floor beside it over
/// its whole extent. Chosen on families A–G: such regions of free floor reach 1.12, the pale
/// blue-grey shelf of G0024 1.155.
pub const RING: f64 = 1.14;
/// The most saturated (after white balance) a region of [`RING_CELLS`] or more lit free cells
/// side by side may be, each above the lit free cells around it ([`ring_tints`]). Chosen on
/// families A–G: such regions of free floor reach 0.06, the pale blue-grey shelves of G0024
/// and G0033 (on blue-grey and light grey floors) 0.075 and 0.09.
pub const RING_TINT: f64 = 0.075;
/// Brighter and more saturated at once than the lit free floor around it, by at least this
/// ratio and this saturation (as [`RING`] and [`RING_TINT`]), each cell of a region of
/// [`RING_CELLS`] or more: the top of a shelf of a paler, bluer grey than the floor, lit by the
/// same sun (V0004's graphite top on a grey floor, read as floor until issue #29's sixteenth
/// round: 1.06–1.14 and 0.033–0.042). Free floor's regions pass one limit or the other, seldom
/// both: on families A–F and K–Z, regions of free cells past both limits were found in two
/// views, each refused for other reasons, and none in a view read exactly; at 1.07 or 0.025
/// instead, in O0006, read exactly.
pub const RING_BOTH: (f64, f64) = (1.08, 0.03);
/// A view's free floor sets a lower limit than [`RING`] where its cells differ little from
/// each other: this many times the spread of its cells' ratios to their rings (the 90th
/// percentile less the median, [`ring_limit`]) above 1, ...
pub const RING_SPREAD: f64 = 5.0;
/// ... and at least this. On an even floor an off-white top on pale warm grey, 1.05–1.08
/// times its ring, stands out of cells within 1.3 % of theirs (held-out Blender family 3,
/// 30016: a shelf of four cells read as free floor, the view read wrongly); on families A–Z,
/// a–z and 0–3 this limit refuses one view read exactly (G0018: two runs of free cells
/// 1.06–1.11 times their rings under ceiling lights) and no other (at 4 times the spread,
/// O0034 too: free cells between two pale shelves, 1.14–1.19 against a limit of 1.136).
/// Since issue #29's thirty-first round.
pub const RING_LEAST: f64 = 1.04;
/// The fewest cells with a ratio that tell the floor's spread; with fewer, [`RING`] alone.
pub const RING_SAMPLE: usize = 12;
/// The fewest lit free neighbours (of the eight) a cell needs to be compared with them.
pub const RING_MIN: usize = 3;
/// The fewest cells side by side, each brighter than [`RING`] times its ring, that are refused.
pub const RING_CELLS: usize = 3;

/// A region of lit free cells side by side, each brighter ([`RING`]) or more tinted
/// ([`RING_TINT`]) than the lit free floor around it.
#[derive(Clone, Debug, PartialEq)]
pub struct Region {
    /// Its cells' indices, row-major, in increasing order.
    pub cells: Vec<usize>,
    /// The smallest of its cells' values (brightness ratio or saturation above the ring).
    pub least: f64,
    /// The limit each of its cells' values is over.
    pub limit: f64,
}

/// The limit over which lit free cells are brighter than the floor around them
/// ([`unlike_ring`]), from their `ratios` ([`ring_ratios`]): [`RING_SPREAD`] times the spread
/// of the ratios above 1, within [`RING_LEAST`] and [`RING`]; [`RING`] with fewer than
/// [`RING_SAMPLE`] ratios.
pub fn ring_limit(ratios: &[Option<f64>]) -> f64 {
    let mut values: Vec<f64> = ratios.iter().flatten().copied().collect();
    if values.len() < RING_SAMPLE {
        return RING;
    }
    values.sort_by(f64::total_cmp);
    let median = values[values.len() / 2];
    let high = values[9 * (values.len() - 1) / 10];
    let limit = 1.0 + RING_SPREAD * (high - median);
    // At the cap (within rounding), RING itself: the ratios are ratios of medians of whole
    // pixel values, and a spread of exactly (RING - 1) / RING_SPREAD must not lower it.
    if limit >= RING - 1e-9 {
        RING
    } else {
        limit.max(RING_LEAST)
    }
}

/// Each lit free cell's brightness ([`LIT`] or brighter) relative to its ring: the lower third
/// of its lit free neighbours' brightness (at least [`RING_MIN`] of the eight; a shelf cell's
/// other shelf cells must not set it) or the lit floor's (1), whichever is brighter (beside
/// shadows and dim corners a lit cell of ordinary floor is brighter than its neighbours);
/// `None` for the others. `bright` holds each cell's median brightness (`None` for a blocked
/// cell or one with too few floor pixels), row-major over a `gw` × `gh` grid.
pub fn ring_ratios(bright: &[Option<f64>], (gw, gh): (u32, u32)) -> Vec<Option<f64>> {
    let lit: Vec<Option<f64>> = bright.iter().map(|b| b.filter(|&b| b >= LIT)).collect();
    against_ring(&lit, (gw, gh), |b, ring| b / ring.max(1.0))
}

/// Each cell's `value` (`None`: not compared, not a neighbour) set against the lower third of
/// its neighbours' values (at least [`RING_MIN`] of the eight) by `compare`; `None` for the
/// cells without a value or with too few neighbours that have one.
fn against_ring(
    values: &[Option<f64>],
    (gw, gh): (u32, u32),
    compare: impl Fn(f64, f64) -> f64,
) -> Vec<Option<f64>> {
    let (gw, gh) = (gw as usize, gh as usize);
    let value = |i: usize| values.get(i).copied().flatten();
    let mut out = vec![None; gw * gh];
    let mut ring = Vec::with_capacity(8);
    for y in 0..gh {
        for x in 0..gw {
            let Some(v) = value(y * gw + x) else { continue };
            ring.clear();
            for ny in y.saturating_sub(1)..(y + 2).min(gh) {
                for nx in x.saturating_sub(1)..(x + 2).min(gw) {
                    if (nx, ny) != (x, y) {
                        if let Some(n) = value(ny * gw + nx) {
                            ring.push(n);
                        }
                    }
                }
            }
            if ring.len() < RING_MIN {
                continue;
            }
            ring.sort_by(f64::total_cmp);
            out[y * gw + x] = Some(compare(v, ring[(ring.len() - 1) / 3]));
        }
    }
    out
}

/// The largest region (ties: the first in row-major order) of at least [`RING_CELLS`] cells
/// side by side (sharing edges) each of a value over `limit` (`values` from [`ring_ratios`]
/// or [`ring_tints`]): the top of a pale shelf of nearly the floor's colour differs from the
/// floor over its whole extent, while the floor's texture, noise and the glow of a mark make
/// single cells or pairs brighter.
pub fn odd_region(values: &[Option<f64>], (gw, gh): (u32, u32), limit: f64) -> Option<Region> {
    let (gw, gh) = (gw as usize, gh as usize);
    let over = |i: usize| values.get(i).copied().flatten().filter(|&r| r > limit);
    let mut seen = vec![false; gw * gh];
    let mut best: Option<Region> = None;
    let mut stack = Vec::new();
    for start in 0..gw * gh {
        if seen[start] || over(start).is_none() {
            continue;
        }
        seen[start] = true;
        stack.push(start);
        let mut cells = Vec::new();
        let mut least = f64::INFINITY;
        while let Some(i) = stack.pop() {
            cells.push(i);
            least = least.min(over(i).unwrap_or(least));
            let (x, y) = (i % gw, i / gw);
            for j in [
                (x > 0).then(|| i - 1),
                (x + 1 < gw).then_some(i + 1),
                (y > 0).then(|| i - gw),
                (y + 1 < gh).then_some(i + gw),
            ]
            .into_iter()
            .flatten()
            {
                if !seen[j] && over(j).is_some() {
                    seen[j] = true;
                    stack.push(j);
                }
            }
        }
        if cells.len() >= RING_CELLS && best.as_ref().is_none_or(|b| cells.len() > b.cells.len()) {
            cells.sort_unstable();
            best = Some(Region {
                cells,
                least,
                limit,
            });
        }
    }
    best
}

/// Each lit free cell's saturation after white balance ([`LIT`] or brighter) above its ring's:
/// the lower third of its lit free neighbours' saturation (at least [`RING_MIN`] of the
/// eight); `None` for the others. `bright` as for [`ring_ratios`], `saturation` each cell's.
pub fn ring_tints(
    bright: &[Option<f64>],
    saturation: &[f64],
    (gw, gh): (u32, u32),
) -> Vec<Option<f64>> {
    let lit: Vec<Option<f64>> = bright
        .iter()
        .enumerate()
        .map(|(i, b)| {
            b.filter(|&b| b >= LIT)
                .and_then(|_| saturation.get(i).copied())
        })
        .collect();
    against_ring(&lit, (gw, gh), |s, ring| s - ring)
}

/// How a region of free cells differs from the floor around it ([`unlike_ring`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Unlike {
    /// Brighter ([`RING`]).
    Brighter,
    /// More saturated ([`RING_TINT`]).
    Tinted,
    /// Both at once, by less ([`RING_BOTH`]).
    Both,
}

/// A region of free cells that do not look like the floor around them: brighter than it
/// ([`RING`], first), more tinted ([`RING_TINT`]), or both by less ([`RING_BOTH`]). For
/// [`Unlike::Both`] the region's `least` is the least of its cells' ratios. `bright` and
/// `saturation` hold each cell's [`Look`] (`None` for a blocked cell or one with too few floor
/// pixels), row-major over a `gw` × `gh` grid. A cell the operator settled (`settled[i]`;
/// shorter, or empty, where nothing is settled) stays in its neighbours' rings but is never
/// part of a region.
pub fn unlike_ring(
    bright: &[Option<f64>],
    saturation: &[f64],
    (gw, gh): (u32, u32),
    settled: &[bool],
) -> Option<(Unlike, Region)> {
    let unsettled = |values: Vec<Option<f64>>| -> Vec<Option<f64>> {
        values
            .into_iter()
            .enumerate()
            .map(|(i, v)| v.filter(|_| settled.get(i) != Some(&true)))
            .collect()
    };
    let ratios = unsettled(ring_ratios(bright, (gw, gh)));
    let tints = unsettled(ring_tints(bright, saturation, (gw, gh)));
    if let Some(r) = odd_region(&ratios, (gw, gh), ring_limit(&ratios)) {
        return Some((Unlike::Brighter, r));
    }
    if let Some(r) = odd_region(&tints, (gw, gh), RING_TINT) {
        return Some((Unlike::Tinted, r));
    }
    // Both: each cell's ratio where its tint passes too (`None` elsewhere).
    let (ratio, tint) = RING_BOTH;
    let both: Vec<Option<f64>> = ratios
        .iter()
        .zip(&tints)
        .map(|(&r, &t)| r.filter(|_| t.is_some_and(|t| t >= tint)))
        .collect();
    odd_region(&both, (gw, gh), ratio).map(|r| (Unlike::Both, r))
}

/// How a free cell's middle looks after white balance.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Look {
    /// The median brightness (brightest channel) of its floor pixels, 1 for the lit floor;
    /// `None` when fewer than [`MIN_PIXELS`] show floor.
    pub bright: Option<f64>,
    /// The saturation of the mean colour of its floor pixels between the first and third
    /// quartile of brightness (texture and specks left out).
    pub saturation: f64,
    /// Whether that mean colour's tint is the floor's under a mix of the sun's light and the
    /// shadows' ([`Classifier::shaded_with`] at [`TINTED`]): a shadow's soft rim or a faint
    /// shadow under a coloured sky, not a tinted top.
    pub shaded: bool,
    /// The tint of that mean colour that no mix of the sun's light and the shadows' explains
    /// ([`Classifier::unexplained_tint`]): for [`Look::dark_unlike`].
    pub unexplained: f64,
    /// The pixels of a colour that cannot be told, and all the pixels judged (not near a mark).
    pub unsure: (usize, usize),
    /// Of its middle's floor pixels, those that leaned pale without making a pale square
    /// ([`super::pale::settle`]), and all of them.
    pub leaning: (usize, usize),
    /// The pixels of the whole cell.
    pub area: usize,
    /// The whole cell in [`shadows::SIDE`] × [`shadows::SIDE`] bins on the floor, row-major:
    /// what its pixels show, for the check that every shadow has a caster ([`shadows`]).
    pub bins: [shadows::Bin; shadows::BINS],
}

/// The least tint ([`Look::unexplained`]) of a dark free cell that the shadows' light does not
/// explain, for it to be a candidate dark top ([`Look::dark_unlike`]).
pub const DARK_TINT: f64 = 0.12;

impl Look {
    /// Whether the cell is darker than the lit floor (in a shadow, or a dark top lit by the
    /// sun) with a tint that no mix of the sun's light and the shadows' gives the floor
    /// ([`DARK_TINT`]): a shelf's dark top, of another hue than the shadows', read as floor in
    /// a shadow. Not refused for it (a dark cell is not judged by its tint): it is only proposed
    /// with the casterless shadow beside it ([`super::corroborated`]).
    pub fn dark_unlike(&self) -> bool {
        self.bright
            .is_some_and(|b| (super::pale::SHADE_BRIGHT.0..LIT).contains(&b))
            && self.unexplained >= DARK_TINT
    }

    /// Why the cell does not look like the floor, if it does not.
    pub fn odd(&self) -> Option<String> {
        self.odd_in(false)
    }

    /// Like [`Look::odd`], in a view whose free floor leans pale (`floor_leans`, see
    /// [`floor_leans`]): there a cell is not refused for leaning pale.
    pub fn odd_in(&self, floor_leans: bool) -> Option<String> {
        let (unsure, all) = self.unsure;
        match self.bright {
            Some(b) if b > BRIGHTER => Some(format!(
                "{b:.2} times as bright as the lit floor (its texture and uneven light make floor at most {BRIGHTER:.2} times as bright)"
            )),
            Some(b) if b >= LIT && self.saturation > TINTED && !self.shaded => Some(format!(
                "lit ({b:.2} times as bright as the lit floor, no shadow) but tinted (saturation {:.2} after white balance on the floor, the lit floor's at most {TINTED:.2})",
                self.saturation
            )),
            Some(_)
                if !floor_leans
                    && self.leaning.0 as f64 > LEANING * self.leaning.1 as f64
                    && self.leaning.1 as f64 >= LEANING_SAMPLE * self.area as f64
                    && self.leaning.1 >= LEANING_PIXELS =>
            {
                Some(format!(
                "{:.0} % of its middle's floor leans pale (brighter or more tinted than lit floor, over squares of half a cell, but not enough for a pale obstacle; at most {:.0} %): the top of a pale shelf may stand there",
                100.0 * self.leaning.0 as f64 / self.leaning.1 as f64,
                100.0 * LEANING
                ))
            }
            _ if all >= MIN_PIXELS && unsure as f64 > UNSURE * all as f64 => Some(format!(
                "{:.0} % of its middle is a colour that cannot be told (at most {:.0} %)",
                100.0 * unsure as f64 / all as f64,
                100.0 * UNSURE
            )),
            _ => None,
        }
    }
}

/// How far (in cells, a square) [`local_levels`] looks around a cell.
pub const LOCAL: usize = 3;
/// The fewest free cells around a cell that give it a level of its own.
pub const LOCAL_MIN: usize = 8;

/// How bright the lit floor is around each cell: the upper quartile of the brightness of the
/// free cells ([`Look::bright`]) within [`LOCAL`] cells, or 1 (the lit floor's median) with
/// fewer than [`LOCAL_MIN`] of them. Lamps light a floor unevenly; a shadow is darker than
/// the floor around it, wherever that is.
pub fn local_levels(bright: &[Option<f64>], (gw, gh): (u32, u32)) -> Vec<f64> {
    let (w, h) = (gw as usize, gh as usize);
    let mut around = Vec::with_capacity((2 * LOCAL + 1).pow(2));
    (0..w * h)
        .map(|i| {
            let (x, y) = (i % w, i / w);
            around.clear();
            for ny in y.saturating_sub(LOCAL)..(y + LOCAL + 1).min(h) {
                for nx in x.saturating_sub(LOCAL)..(x + LOCAL + 1).min(w) {
                    around.extend(bright.get(ny * w + nx).copied().flatten());
                }
            }
            if around.len() < LOCAL_MIN {
                return 1.0;
            }
            let q = 3 * around.len() / 4;
            *around.select_nth_unstable_by(q, f64::total_cmp).1
        })
        .collect()
}

/// How the middle of cell `(cx, cy)` looks (see the module's comment); how near each pixel
/// lies to a mark from [`mark_reach`] (its edge, halo and glow): the pixels near a mark, left out of everything (its blurred
/// edge and its shadow); the wider halo left out of the middle's look (the mark's colour
/// spread into the floor by blur and JPEG), whose floor pixels still count in the shadow bins
/// (a shadow beside a mark is the mark's only when it touches the mark itself); and within a
/// cell of a mark, where a floor pixel leaning pale in a mark's hue is the mark's glow, not a
/// pale top's (since issue #29's eleventh round: large blurred marks spread their glow past
/// the quarter cell).
#[allow(clippy::too_many_arguments)]
pub fn look(
    img: &RgbImage,
    classes: &[u8],
    classifier: &Classifier,
    floor_to_image: &Homography,
    image_to_floor: &Homography,
    nadir: Option<(f64, f64)>,
    near_mark: &[u8],
    leaned: &[u8],
    (cx, cy): (u32, u32),
) -> Look {
    let width = img.width() as usize;
    let height = img.height() as usize;
    let (fx, fy) = (f64::from(cx), f64::from(cy));
    let inside = |(lo, hi): (f64, f64)| (lo.max(BORDER), hi.min(1.0 - BORDER));
    let (wu, wv) = (
        inside(window(fx, nadir.map(|n| n.0))),
        inside(window(fy, nadir.map(|n| n.1))),
    );
    let mut out = Look {
        bright: None,
        saturation: 0.0,
        shaded: false,
        unexplained: 0.0,
        unsure: (0, 0),
        leaning: (0, 0),
        area: 0,
        bins: [shadows::Bin::default(); shadows::BINS],
    };
    let Some((x0, y0, x1, y1)) = floor_to_image.cell_box((cx, cy), width, height) else {
        return out;
    };
    // Floor pixels: (brightness, colour) after white balance.
    type Seen = (f64, u32, [f64; 3]);
    let mut seen: Vec<Seen> = Vec::with_capacity((x1 - x0) * (y1 - y0));
    // Where a pixel lies in the cell, from its offset `t` (0–1) along one axis: its bin
    // along that axis, whether it lies on a painted line, and whether within the middle's
    // window; `None` outside the cell.
    let place = |t: f64, (lo, hi): (f64, f64)| {
        (0.0..1.0).contains(&t).then(|| {
            (
                ((t * shadows::SIDE as f64) as usize).min(shadows::SIDE - 1),
                t.min(1.0 - t) < shadows::LINE,
                !(t < lo || t > hi),
            )
        })
    };
    type Along = (usize, bool, bool);
    let mut visit = |x: usize, y: usize, (bu, line_u, in_u): Along, (bv, line_v, in_v): Along| {
        out.area += 1;
        let class = classes[y * width + x];
        let bin = &mut out.bins[bv * shadows::SIDE + bu];
        let near = near_mark[y * width + x];
        if near == NEAR_EDGE || class == Class::Robot as u8 || class == Class::Goal as u8 {
            bin.mark += 1;
            // A speck of the robots' colour (on a shelf's edge, in noise) is no robot: only
            // the pixels of a robot's blob count (issue #29's fifteenth round, U0017).
            bin.robot += u32::from(class == Class::Robot as u8 && near == NEAR_EDGE);
            return;
        }
        let floor = class == Class::Floor as u8;
        // Only the floor's pixels are seen in colour.
        let rgb = if floor {
            classifier.balanced(img.get_pixel(x as u32, y as u32).0)
        } else {
            [0.0; 3]
        };
        if floor {
            if line_u || line_v {
                // Painted lines and their blur: neither shadow nor lit floor.
            } else {
                let b = (rgb[0] + rgb[1] + rgb[2]) / 3.0;
                if b < shadows::DARK {
                    bin.dark += 1;
                } else {
                    bin.lit += 1;
                }
                bin.brightness = bin.brightness.saturating_add(thousandths(b));
            }
        } else {
            bin.solid += 1;
        }
        if !(in_u && in_v) || near <= NEAR_HALO {
            return;
        }
        out.unsure.1 += 1;
        match class {
            c if c == Class::Unsure as u8 => out.unsure.0 += 1,
            c if c == Class::Floor as u8 => {
                seen.push((rgb[0].max(rgb[1]).max(rgb[2]), seen.len() as u32, rgb));
                out.leaning.1 += 1;
                // Leaning pale in a mark's hue within a cell of a mark: its glow.
                let glowing = || near <= NEAR_GLOW && classifier.of_a_marks_hue(rgb);
                if leaned.get(y * width + x) == Some(&super::pale::LEANED) && !glowing() {
                    out.leaning.0 += 1;
                }
            }
            _ => {}
        }
    };
    match image_to_floor.along_axes((x0, x1), (y0, y1)) {
        // Straight down: a pixel's place along each axis is its column's and its row's.
        Some(axes) => {
            let columns: Vec<_> = (x0..x1).map(|x| place(axes.at(x, y0).0 - fx, wu)).collect();
            for y in y0..y1 {
                let Some(along_v) = place(axes.at(x0, y).1 - fy, wv) else {
                    continue;
                };
                for (x, along_u) in (x0..x1).zip(&columns) {
                    if let Some(along_u) = *along_u {
                        visit(x, y, along_u, along_v);
                    }
                }
            }
        }
        None => {
            for y in y0..y1 {
                for x in x0..x1 {
                    let Some((u, v)) = image_to_floor.apply((x as f64 + 0.5, y as f64 + 0.5))
                    else {
                        continue;
                    };
                    if let (Some(along_u), Some(along_v)) = (place(u - fx, wu), place(v - fy, wv)) {
                        visit(x, y, along_u, along_v);
                    }
                }
            }
        }
    }
    if seen.len() < MIN_PIXELS {
        return out;
    }
    // By brightness, ties in the order seen: the median, and the middle half (selected, not
    // sorted: a cell's hundreds of pixels, for every free cell of the floor).
    let order = |a: &Seen, b: &Seen| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1));
    let n = seen.len();
    let (lo, hi) = (n / 4, 3 * n / 4);
    seen.select_nth_unstable_by(lo, order);
    seen[lo + 1..].select_nth_unstable_by(hi - lo - 1, order);
    let middle = &mut seen[lo..hi];
    middle.select_nth_unstable_by(n / 2 - lo, order);
    out.bright = Some(middle[n / 2 - lo].0);
    let mut mean = [0.0; 3];
    for (_, _, rgb) in middle.iter() {
        for c in 0..3 {
            mean[c] += rgb[c] / middle.len() as f64;
        }
    }
    let max = mean[0].max(mean[1]).max(mean[2]);
    let min = mean[0].min(mean[1]).min(mean[2]);
    out.saturation = if max > 0.0 { (max - min) / max } else { 0.0 };
    out.shaded = out.saturation > TINTED && classifier.shaded_with(mean, TINTED);
    out.unexplained = classifier.unexplained_tint(mean);
    out
}

/// `b` in thousandths, rounded half away from zero and at most a million (a bin's brightness
/// sums them): as `(b * 1000.0).round().min(1e6) as u32`, without the call `round` costs on
/// every floor pixel (the sum with the largest double below one half, truncated, rounds
/// every double as `round` does; negative values and NaN give what the cast gives them).
#[inline]
fn thousandths(b: f64) -> u32 {
    (b * 1000.0 + 0.499_999_999_999_999_94).min(1e6) as u32
}

/// How near each pixel lies to a robot's or a goal's blob of at least [`blobs::MIN_AREA`]
/// pixels (smaller specks of a mark's colour are noise, on a shelf too): the index of the
/// first of `reach` (in pixels, ascending) within which it lies, a square around each of the
/// blob's pixels, or `reach.len()` when it lies within none. One map for every reach the reader
/// needs (a mark's edge and shadow, its halo, its glow: [`NEAR_EDGE`], [`NEAR_HALO`],
/// [`NEAR_GLOW`]), from the blobs found once.
pub fn mark_reach(classes: &mut [u8], width: usize, reach: &[usize]) -> Vec<u8> {
    let width = width.max(1);
    let height = classes.len() / width;
    let mut seeds: Vec<(usize, usize)> = Vec::new();
    for class in [Class::Robot, Class::Goal] {
        for b in blobs::find(classes, width, class as u8) {
            if b.area() >= blobs::MIN_AREA {
                seeds.extend(b.pixels.iter().map(|&(x, y)| (x as usize, y as usize)));
            }
        }
    }
    let mut out = vec![reach.len() as u8; classes.len()];
    if seeds.is_empty() {
        return out;
    }
    // The seeds' columns, row by row.
    let mut starts = vec![0usize; height + 1];
    for &(_, y) in &seeds {
        starts[y + 1] += 1;
    }
    for y in 0..height {
        starts[y + 1] += starts[y];
    }
    let mut columns = vec![0usize; seeds.len()];
    let mut next = starts.clone();
    for &(x, y) in &seeds {
        columns[next[y]] = x;
        next[y] += 1;
    }
    let mut rows = vec![false; classes.len()];
    // The widest reach first, each narrower one over it; rows and bands of rows on all cores
    // (each pixel's value does not depend on how they are split).
    for (k, &r) in reach.iter().enumerate().rev() {
        // Along rows: the pixels within r of a marked pixel of their row.
        rows.par_chunks_mut(width).enumerate().for_each(|(y, row)| {
            row.fill(false);
            for &x in &columns[starts[y]..starts[y + 1]] {
                row[x.saturating_sub(r)..=(x + r).min(width - 1)].fill(true);
            }
        });
        // Then along columns, a band of rows at a time: each column's count of the rows
        // within r marked there, slid down the band.
        let band = (4 * r).max(64);
        let rows = &rows;
        out.par_chunks_mut(width * band)
            .enumerate()
            .for_each(|(b, out)| {
                let row = |y: usize| &rows[y * width..(y + 1) * width];
                let y0 = b * band;
                let mut count = vec![0u32; width];
                // As the sweep left it at the band's previous row.
                for y in y0.saturating_sub(r + 1)..(y0 + r).min(height) {
                    count
                        .iter_mut()
                        .zip(row(y))
                        .for_each(|(n, &m)| *n += u32::from(m));
                }
                for (dy, line) in out.chunks_mut(width).enumerate() {
                    let y = y0 + dy;
                    if y + r < height {
                        count
                            .iter_mut()
                            .zip(row(y + r))
                            .for_each(|(n, &m)| *n += u32::from(m));
                    }
                    if y > r {
                        count
                            .iter_mut()
                            .zip(row(y - r - 1))
                            .for_each(|(n, &m)| *n -= u32::from(m));
                    }
                    for (o, &n) in line.iter_mut().zip(&count) {
                        if n > 0 {
                            *o = k as u8;
                        }
                    }
                }
            });
    }
    out
}

/// [`mark_reach`]'s level of a pixel within a mark's blurred edge and shadow (left out of
/// everything in [`look`]).
pub const NEAR_EDGE: u8 = 0;
/// Within its halo (left out of the middle's look, and of the painted lines').
pub const NEAR_HALO: u8 = 1;
/// Within its glow (see [`look`]).
pub const NEAR_GLOW: u8 = 2;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn local_levels_follow_the_light_around_each_cell() {
        // A 9 × 9 floor lit 1.0 on its left and 1.5 from column 5 on; a blocked cell (None)
        // and a shadow (0.4) do not move the upper quartile much.
        let mut bright: Vec<Option<f64>> = (0..81)
            .map(|i| Some(if i % 9 >= 5 { 1.5 } else { 1.0 }))
            .collect();
        bright[4 * 9 + 7] = None;
        bright[3 * 9 + 7] = Some(0.4);
        let levels = local_levels(&bright, (9, 9));
        assert_eq!(levels.len(), 81);
        assert_eq!(levels[4 * 9], 1.0);
        assert_eq!(levels[4 * 9 + 8], 1.5);
        assert_eq!(levels[3 * 9 + 7], 1.5);
        // Too few free cells around: the lit floor's median.
        let sparse: Vec<Option<f64>> = (0..81).map(|i| (i == 40).then_some(2.0)).collect();
        assert!(local_levels(&sparse, (9, 9)).iter().all(|&l| l == 1.0));
    }

    fn lit(bright: f64, saturation: f64) -> Look {
        Look {
            bright: Some(bright),
            saturation,
            shaded: false,
            unexplained: 0.0,
            unsure: (0, 100),
            leaning: (0, 100),
            area: 400,
            bins: Default::default(),
        }
    }

    #[test]
    fn a_dark_cell_of_a_tint_no_shadow_gives_may_be_a_dark_top() {
        let dark = |bright: f64, unexplained: f64| Look {
            unexplained,
            ..lit(bright, unexplained)
        };
        assert!(dark(0.6, 0.15).dark_unlike());
        // Lit, or darker than a shadow's floor: not a dark top's; of the shadows' tint: floor.
        assert!(!dark(0.9, 0.15).dark_unlike());
        assert!(!dark(0.2, 0.15).dark_unlike());
        assert!(!dark(0.6, 0.05).dark_unlike());
        // Never refused for it: a dark cell is not judged by its tint.
        assert_eq!(dark(0.6, 0.15).odd(), None);
    }

    #[test]
    fn a_floor_that_leans_pale_as_a_whole_does_not_tell_a_pale_top() {
        let leaning = |share: usize| Look {
            leaning: (share, 100),
            ..lit(1.2, 0.05)
        };
        // Twelve cells: eight lean pale over 2 % of their middle, three over 30 %, one over
        // 70 %. The 75th percentile (the tenth smallest) is 30 %: the floor leans pale, and
        // the one at 70 % is not refused for it.
        let mut looks: Vec<Option<Look>> = (0..8).map(|_| Some(leaning(2))).collect();
        looks.extend((0..3).map(|_| Some(leaning(30))));
        looks.push(Some(leaning(70)));
        looks.push(None);
        assert!(floor_leans(&looks));
        assert!(leaning(70).odd().is_some());
        assert_eq!(leaning(70).odd_in(true), None);
        // Ten at 2 %: the tenth smallest is 2 %, the floor does not lean, the top stands out.
        looks[8] = Some(leaning(2));
        looks[9] = Some(leaning(2));
        assert!(!floor_leans(&looks));
        // Cells judged on too few pixels, or not lit, do not count; nor does a view of fewer
        // than eight cells.
        let few = |l: Look| {
            Some(Look {
                leaning: (30, 19),
                ..l
            })
        };
        let some: Vec<Option<Look>> = (0..12).map(|_| few(lit(1.2, 0.05))).collect();
        assert!(!floor_leans(&some));
        assert!(!floor_leans(&vec![Some(leaning(50)); 7]));
        assert!(floor_leans(&vec![Some(leaning(50)); 8]));
    }

    #[test]
    fn lit_grey_floor_and_shadows_look_like_floor() {
        for (b, s) in [(1.0, 0.02), (1.3, 0.1), (0.4, 0.4), (0.8, 0.3)] {
            assert_eq!(lit(b, s).odd(), None);
        }
    }

    #[test]
    fn a_bright_a_lit_tinted_or_an_unsure_cell_does_not() {
        assert!(lit(1.8, 0.0).odd().unwrap().contains("1.80 times"));
        assert!(lit(0.95, 0.25).odd().unwrap().contains("tinted"));
        // Tinted as the shadows' light tints the floor (a soft shadow's rim): floor.
        let rim = Look {
            shaded: true,
            ..lit(0.95, 0.25)
        };
        assert_eq!(rim.odd(), None);
        let unsure = Look {
            bright: None,
            saturation: 0.0,
            shaded: false,
            unexplained: 0.0,
            unsure: (70, 100),
            leaning: (0, 0),
            area: 400,
            bins: Default::default(),
        };
        assert!(unsure.odd().unwrap().contains("70 %"));
        // A lit grey cell most of whose floor leaned pale without making a pale obstacle.
        let leaning = Look {
            leaning: (60, 100),
            ..lit(1.2, 0.05)
        };
        assert!(leaning
            .odd()
            .unwrap()
            .contains("60 % of its middle's floor leans pale"));
        let few = Look {
            leaning: (40, 100),
            ..lit(1.2, 0.05)
        };
        assert_eq!(few.odd(), None);
        // As many leaning, but judged on under a tenth of the cell (beside a mark, under a
        // neighbour's possible lean): too few pixels to tell.
        let small = Look {
            leaning: (60, 100),
            area: 1001,
            ..lit(1.2, 0.05)
        };
        assert_eq!(small.odd(), None);
        let enough = Look {
            area: 1000,
            ..small
        };
        assert!(enough.odd().is_some());
        // On under 20 pixels, however large a share of the cell.
        let few_pixels = Look {
            leaning: (15, 19),
            area: 100,
            ..lit(1.2, 0.05)
        };
        assert_eq!(few_pixels.odd(), None);
        let just_enough = Look {
            leaning: (16, 20),
            ..few_pixels
        };
        assert!(just_enough.odd().is_some());
    }

    #[test]
    fn cells_brighter_than_the_floor_around_them_are_found() {
        // 5 x 4 cells: the lit floor brightening across the grid (uneven light) passes.
        let (gw, gh) = (5u32, 4u32);
        let grey = [0.02; 20];
        let gradient: Vec<Option<f64>> =
            (0..20).map(|i| Some(1.0 + 0.03 * (i % 5) as f64)).collect();
        assert_eq!(unlike_ring(&gradient, &grey, (gw, gh), &[]), None);
        // A pale top over a 3 x 2 block, 1.2 times the floor, is found whole.
        let mut shelf = vec![Some(1.0); 20];
        for i in [6, 7, 8, 11, 12, 13] {
            shelf[i] = Some(1.2);
        }
        shelf[7] = Some(1.25);
        let (kind, r) = unlike_ring(&shelf, &grey, (gw, gh), &[]).unwrap();
        assert_eq!(kind, Unlike::Brighter);
        assert_eq!(r.cells, vec![6, 7, 8, 11, 12, 13]);
        assert!((r.least - 1.2).abs() < 1e-9);
        // Cells the operator settled are never part of it: three settled leave three, all but
        // two leave too few.
        let mut settled = vec![false; 20];
        for i in [6, 7, 8] {
            settled[i] = true;
        }
        let (_, r) = unlike_ring(&shelf, &grey, (gw, gh), &settled).unwrap();
        assert_eq!(r.cells, vec![11, 12, 13]);
        settled[11] = true;
        assert_eq!(unlike_ring(&shelf, &grey, (gw, gh), &settled), None);
        // Two bright cells side by side (noise, a stain, a mark's glow) are not enough.
        let mut two = vec![Some(1.0); 20];
        two[6] = Some(1.3);
        two[7] = Some(1.3);
        assert_eq!(unlike_ring(&two, &grey, (gw, gh), &[]), None);
        // Three on a diagonal are not side by side.
        two[7] = Some(1.0);
        two[12] = Some(1.3);
        two[18] = Some(1.3);
        assert_eq!(unlike_ring(&two, &grey, (gw, gh), &[]), None);
        // Shadows and blocked cells around them are not their ring.
        let mut lone = vec![Some(0.5); 20];
        for i in [6, 7, 8] {
            lone[i] = Some(1.2);
        }
        lone[0] = None;
        assert_eq!(unlike_ring(&lone, &grey, (gw, gh), &[]), None);
        // Lit floor beside a penumbra (0.86) is compared with the lit floor, not the penumbra.
        let mut dim = vec![Some(0.86); 20];
        for i in [6, 7, 8] {
            dim[i] = Some(1.0);
        }
        assert_eq!(unlike_ring(&dim, &grey, (gw, gh), &[]), None);
        // No panic on an empty or a short list.
        assert_eq!(unlike_ring(&[], &[], (gw, gh), &[]), None);
        assert_eq!(unlike_ring(&[Some(2.0); 3], &[0.5; 2], (gw, gh), &[]), None);
    }

    #[test]
    fn on_an_even_floor_cells_a_little_brighter_than_the_floor_around_them_are_found() {
        // 8 x 5 cells of floor within half a percent of each other (a ripple of 0.997 to 1.005),
        // and a pale top over a run of four, 1.06 times the floor.
        let (gw, gh) = (8u32, 5u32);
        let grey = [0.02; 40];
        let even: Vec<Option<f64>> = (0..40)
            .map(|i| Some(1.0 + 0.004 * ((i * 7) % 3) as f64 - 0.003))
            .collect();
        assert_eq!(unlike_ring(&even, &grey, (gw, gh), &[]), None);
        let mut top = even.clone();
        for i in [10, 11, 12, 13] {
            top[i] = Some(1.06);
        }
        let (kind, r) = unlike_ring(&top, &grey, (gw, gh), &[]).unwrap();
        assert_eq!(kind, Unlike::Brighter);
        assert_eq!(r.cells, vec![10, 11, 12, 13]);
        assert!((r.limit - RING_LEAST).abs() < 1e-9, "{}", r.limit);
        // On a blotchy floor (cells up to 7 % apart, unevenly) the same top is floor as far as
        // this tells: its cells differ from their rings no more than the floor's do.
        let blotchy: Vec<Option<f64>> = (0..40)
            .map(|i| Some(1.0 + 0.012 * ((i * 5) % 7) as f64))
            .collect();
        assert_eq!(unlike_ring(&blotchy, &grey, (gw, gh), &[]), None);
        let mut top = blotchy.clone();
        for i in [10, 11, 12, 13] {
            top[i] = Some(top[i].unwrap() * 1.06);
        }
        assert_eq!(unlike_ring(&top, &grey, (gw, gh), &[]), None);
    }

    #[test]
    fn the_ring_limit_follows_the_floor_s_spread_within_its_bounds() {
        // Too few cells to tell a spread: RING.
        assert_eq!(ring_limit(&[Some(1.0); RING_SAMPLE - 1]), RING);
        // An even floor: RING_LEAST.
        assert_eq!(ring_limit(&[Some(1.0); 30]), RING_LEAST);
        // A spread of 0.012 (the 90th percentile over the median): 1 + RING_SPREAD × 0.012.
        let mut spread: Vec<Option<f64>> = vec![Some(1.0); 27];
        spread.extend([Some(1.012); 3]);
        spread.push(Some(1.3));
        assert!((ring_limit(&spread) - (1.0 + RING_SPREAD * 0.012)).abs() < 1e-9);
        // A wide spread: RING, and so at the cap exactly (no rounding below it).
        let mut wide: Vec<Option<f64>> = vec![Some(1.0); 27];
        wide.extend([Some(1.0 + (RING - 1.0) / RING_SPREAD); 4]);
        assert_eq!(ring_limit(&wide), RING);
        // Cells without a ratio do not count.
        assert_eq!(ring_limit(&[None; 40]), RING);
    }

    #[test]
    fn cells_more_tinted_than_the_floor_around_them_are_found() {
        let (gw, gh) = (5u32, 4u32);
        let lit = vec![Some(1.05); 20];
        // A floor tinted all over (a coloured floor after white balance on its median) passes.
        assert_eq!(unlike_ring(&lit, &[0.12; 20], (gw, gh), &[]), None);
        // A bluish top over three cells, 0.1 above the floor's saturation, is found.
        let mut sat = vec![0.02; 20];
        for i in [1, 6, 11] {
            sat[i] = 0.12;
        }
        let (kind, r) = unlike_ring(&lit, &sat, (gw, gh), &[]).unwrap();
        assert_eq!(kind, Unlike::Tinted);
        assert_eq!(r.cells, vec![1, 6, 11]);
        // Not in a shadow (a shadow's tint depends on the light).
        let mut shade = lit.clone();
        for i in [1, 6, 11] {
            shade[i] = Some(0.6);
        }
        assert_eq!(unlike_ring(&shade, &sat, (gw, gh), &[]), None);
        // Not two cells alone.
        sat[11] = 0.02;
        assert_eq!(unlike_ring(&lit, &sat, (gw, gh), &[]), None);
    }

    #[test]
    fn cells_both_brighter_and_more_tinted_than_the_floor_around_them_are_found() {
        // V0004's graphite top on grey floor: 1.06-1.14 as bright, 0.03-0.04 more saturated.
        let (gw, gh) = (6u32, 3u32);
        let mut bright = vec![Some(1.0); 18];
        let mut sat = vec![0.01; 18];
        for (i, (b, s)) in [(7, (1.10, 0.045)), (8, (1.09, 0.043)), (9, (1.12, 0.048))] {
            bright[i] = Some(b);
            sat[i] = s;
        }
        let (kind, r) = unlike_ring(&bright, &sat, (gw, gh), &[]).unwrap();
        assert_eq!(kind, Unlike::Both);
        assert_eq!(r.cells, vec![7, 8, 9]);
        // Either alone at that level is floor: brighter only, or tinted only.
        let grey = vec![0.01; 18];
        assert_eq!(unlike_ring(&bright, &grey, (gw, gh), &[]), None);
        let even = vec![Some(1.0); 18];
        assert_eq!(unlike_ring(&even, &sat, (gw, gh), &[]), None);
        // One cell under either limit breaks the region (two cells are not enough).
        let mut dim = bright.clone();
        dim[8] = Some(1.06);
        assert_eq!(unlike_ring(&dim, &sat, (gw, gh), &[]), None);
        let mut pale = sat.clone();
        pale[8] = 0.035;
        assert_eq!(unlike_ring(&bright, &pale, (gw, gh), &[]), None);
    }

    #[test]
    fn the_reach_of_a_mark_is_a_square_around_each_mark_pixel() {
        let (w, h) = (9, 7);
        let mut classes = vec![Class::Floor as u8; w * h];
        // A robot of 6 pixels (the smallest blob that is one) and a speck of 2.
        let robot = [(4, 3), (3, 3), (5, 3), (4, 2), (4, 4), (5, 4)];
        for (x, y) in robot {
            classes[y * w + x] = Class::Robot as u8;
        }
        classes[6 * w] = Class::Goal as u8;
        classes[6 * w + 1] = Class::Goal as u8;
        let near = mark_reach(&mut classes, w, &[1, 2, 3]);
        for y in 0..h {
            for x in 0..w {
                let want = robot
                    .iter()
                    .any(|&(rx, ry): &(usize, usize)| rx.abs_diff(x) <= 2 && ry.abs_diff(y) <= 2);
                assert_eq!(near[y * w + x] <= 1, want, "({x}, {y})");
            }
        }
    }

    #[test]
    fn the_reach_is_the_same_across_the_bands_of_rows_it_is_swept_in() {
        // Tall enough for several bands of rows at every reach; robots of 3 × 3 pixels (each
        // a blob large enough to be a mark) scattered, some on the image's edges and some
        // within a reach of a band's border.
        let (w, h) = (37, 413);
        let mut classes = vec![Class::Floor as u8; w * h];
        let mut centres = Vec::new();
        let mut state = 7u64;
        for _ in 0..40 {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1);
            let (x, y) = (
                1 + ((state >> 33) % (w as u64 - 2)) as usize,
                1 + ((state >> 17) % (h as u64 - 2)) as usize,
            );
            centres.push((x, y));
        }
        centres.extend([(1, 1), (w - 2, h - 2), (18, 63), (18, 64), (5, 127)]);
        for &(x, y) in &centres {
            for ny in y - 1..=y + 1 {
                for nx in x - 1..=x + 1 {
                    classes[ny * w + nx] = Class::Robot as u8;
                }
            }
        }
        let marked: Vec<bool> = classes.iter().map(|&c| c == Class::Robot as u8).collect();
        let reach = [2, 5, 19];
        let near = mark_reach(&mut classes, w, &reach);
        for y in 0..h {
            for x in 0..w {
                let within = |r: usize| {
                    (y.saturating_sub(r)..=(y + r).min(h - 1)).any(|ny| {
                        (x.saturating_sub(r)..=(x + r).min(w - 1)).any(|nx| marked[ny * w + nx])
                    })
                };
                let want = reach.iter().position(|&r| within(r)).unwrap_or(reach.len());
                assert_eq!(usize::from(near[y * w + x]), want, "({x}, {y})");
            }
        }
    }
}
