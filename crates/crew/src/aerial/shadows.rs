//! Every shadow on the free floor must have a caster.
//!
//! A shelf of the floor's own colour and brightness (pale blue-grey on cool grey, dark brown on
//! dark warm-grey) looks like floor in every cell it stands on, and [`super::looks`] cannot
//! tell it from floor cell by cell. It still casts a shadow: the sun lights its top as it
//! lights the floor, but not the floor behind it. A shadow on the floor is cast by something
//! that stands: a shelf (a blocked cell, or an obstacle's colour) or a robot, and it touches
//! what casts it (a shadow begins at its caster's foot; a top that leans over it in the image
//! is the caster's too). So the free cells are cut into [`SIDE`] × [`SIDE`] bins on the floor,
//! each judged by most of its pixels: floor darker than [`DARK`] times the lit floor (a
//! shadow), lit floor, an obstacle's or an unsure colour (a caster), or a robot or goal and
//! the pixels near it. A connected region of shadow bins that touches no caster (nor a blocked
//! cell), and no robot either (a bin of a mark with a robot's pixels in it or beside it) unless
//! it is small enough for a robot's shadow ([`ROBOT_SHADOW`]), has nothing that casts it in
//! the image: something of the floor's colour stands there, and the view is refused, never
//! read as free floor. A goal lies flat and casts nothing.
//!
//! Painted lines (at most a third of a bin along the border) and tile seams do not make a bin
//! dark; a shelf's shadow (at least a fifth of a cell wide under a sun up to 60° high and a
//! shelf 0.3 high) darkens whole bins. Cost: O(bins), after the pass over the free cells'
//! pixels in [`super::looks`] that fills them.

/// Bins along each side of a cell.
pub const SIDE: usize = 4;
/// Bins per cell.
pub const BINS: usize = SIDE * SIDE;
/// Floor darker than this (the mean of its channels after white balance, 1 for the lit floor)
/// is in a shadow. A shadow lit by the sky alone is at most about 0.8 of the lit floor after
/// the sRGB curve (under a weak, low sun); the floor's stains and uneven light seldom go below.
pub const DARK: f64 = 0.8;
/// The lit floor around a cell this many times as bright as the lit floor's median, or more,
/// is a pool of light (a lamp's): its shadows are judged against it. Below, down to the
/// median, the floor's stains and texture (a tenth either way) would pass for shadows against
/// the light around them, and shadows are judged against the median (under it, see [`DIM`]).
pub const POOL: f64 = 1.2;
/// The lit floor around a cell darker than the lit floor's median (the cells' middles of a
/// dark floor whose pale painted lines raise the median, a dim corner) is judged against that
/// level down to this one: a bin there is in a shadow under [`DARK`] times the level, not
/// under [`DARK`] (C0000's and j0001's dark floors with white lines, their cells' middles
/// 0.9–1.0 of the median, read as shadows with no caster; issue #29's twenty-eighth round).
/// Lower, the level may be a large shadow's own (the upper quartile of the cells around
/// it), which must not hide it.
pub const DIM: f64 = 0.9;
/// Floor pixels nearer than this to a cell's border (in cells) are not judged: painted lines
/// lie there (up to 0.09 cell wide, and blurred).
pub const LINE: f64 = 0.1;
/// The largest shadow (in bins: two cells) a robot or a goal's neighbourhood explains.
pub const ROBOT_SHADOW: usize = 2 * BINS;
/// The fewest bins of a shadow with no caster that are refused (half a cell; smaller: noise,
/// a stain).
pub const MIN_SHADOW: usize = BINS / 2;

/// What the pixels of one bin show.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Bin {
    /// Floor pixels darker than [`DARK`].
    pub dark: u32,
    /// Floor pixels at least [`DARK`].
    pub lit: u32,
    /// Pixels of an obstacle's colour or a colour that cannot be told.
    pub solid: u32,
    /// Pixels of a robot or a goal, or near one.
    pub mark: u32,
    /// Of those, the robot's own pixels.
    pub robot: u32,
    /// The sum of the floor pixels' brightness (the mean of their channels after white
    /// balance, 1 for the lit floor), in thousandths.
    pub brightness: u32,
}

/// A bin judged by most of its pixels.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// No pixel (outside the image).
    Empty,
    /// An obstacle (or a blocked cell): it may cast a shadow.
    Caster,
    /// A robot or a goal and its neighbourhood.
    Mark,
    /// Floor in a shadow.
    Dark,
    /// Lit floor.
    Lit,
}

impl Bin {
    /// What most of the bin shows, where the lit floor around it is `level` times as bright as
    /// the lit floor's median: from [`POOL`] on (a lamp's pool of light), its floor is in a
    /// shadow when its mean brightness is under [`DARK`] times `level`; under 1 (a dim floor),
    /// under [`DARK`] times `level` or [`DIM`], whichever is more.
    pub fn kind_in(&self, level: f64) -> Kind {
        let floor = self.dark + self.lit;
        match self.kind() {
            Kind::Dark | Kind::Lit if !(1.0..POOL).contains(&level) => {
                let level = level.max(DIM);
                let mean = f64::from(self.brightness) / 1000.0 / f64::from(floor);
                if mean < DARK * level {
                    Kind::Dark
                } else {
                    Kind::Lit
                }
            }
            kind => kind,
        }
    }

    /// What most of the bin shows.
    pub fn kind(&self) -> Kind {
        let all = self.dark + self.lit + self.solid + self.mark;
        if all == 0 {
            Kind::Empty
        } else if 2 * self.solid >= all {
            Kind::Caster
        } else if 2 * self.mark >= all {
            Kind::Mark
        } else if self.dark > self.lit {
            Kind::Dark
        } else {
            Kind::Lit
        }
    }
}

/// A shadow with no caster: its first bin (row-major) as a cell and a point on the floor (in
/// cells), and its size in bins.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Uncast {
    /// The cell of its first bin.
    pub cell: (u32, u32),
    /// The centre of its first bin on the floor.
    pub at: (f64, f64),
    /// Its size in bins.
    pub bins: usize,
}

/// The floor's bins, `gw × SIDE` wide, row-major: each one's [`Kind`], and whether a robot's
/// pixels are in it or beside it; `None` for a floor with no bins.
fn grid(
    cells: &[Option<[Bin; BINS]>],
    levels: &[f64],
    (gw, gh): (u32, u32),
    robot_share: f64,
) -> Option<(Vec<Kind>, Vec<bool>)> {
    let (bw, bh) = (gw as usize * SIDE, gh as usize * SIDE);
    if cells.len() != gw as usize * gh as usize || bw == 0 || bh == 0 {
        return None;
    }
    // Each bin alone, then each row of bins alone, on all cores.
    use rayon::prelude::*;
    let kinds: Vec<Kind> = (0..bw * bh)
        .into_par_iter()
        .map(|i| {
            let (bx, by) = (i % bw, i / bw);
            let c = (by / SIDE) * gw as usize + bx / SIDE;
            match &cells[c] {
                None => Kind::Caster,
                Some(b) => {
                    b[(by % SIDE) * SIDE + bx % SIDE].kind_in(levels.get(c).copied().unwrap_or(1.0))
                }
            }
        })
        .collect();
    // Bins with a robot's pixels in them (more than `robot_share` of their pixels) or beside
    // them.
    let robot: Vec<bool> = (0..bw * bh)
        .into_par_iter()
        .map(|i| {
            let (bx, by) = (i % bw, i / bw);
            match &cells[(by / SIDE) * gw as usize + bx / SIDE] {
                None => false,
                Some(b) => {
                    let b = &b[(by % SIDE) * SIDE + bx % SIDE];
                    let all = b.dark + b.lit + b.solid + b.mark;
                    b.robot > 0 && f64::from(b.robot) >= robot_share * f64::from(all)
                }
            }
        })
        .collect();
    let mut robot_near = vec![false; bw * bh];
    robot_near
        .par_chunks_mut(bw)
        .enumerate()
        .for_each(|(by, row)| {
            for ny in by.saturating_sub(1)..=(by + 1).min(bh - 1) {
                for (bx, near) in row.iter_mut().enumerate() {
                    let (x0, x1) = (bx.saturating_sub(1), (bx + 1).min(bw - 1));
                    *near |= robot[ny * bw + x0..=ny * bw + x1].contains(&true);
                }
            }
        });
    Some((kinds, robot_near))
}

impl Uncast {
    /// A shadow of `bins` bins whose first bin is `(bx, by)` (floor bin coordinates).
    fn from_bin((bx, by): (usize, usize), bins: usize) -> Uncast {
        Uncast {
            cell: ((bx / SIDE) as u32, (by / SIDE) as u32),
            at: (
                (bx as f64 + 0.5) / SIDE as f64,
                (by as f64 + 0.5) / SIDE as f64,
            ),
            bins,
        }
    }
}

/// Whether the operator settled the cell (`settled`: row-major over a floor `gw` cells wide;
/// shorter, or empty, where nothing is settled).
fn is_settled(settled: &[bool], (x, y): (u32, u32), gw: u32) -> bool {
    settled.get(y as usize * gw as usize + x as usize) == Some(&true)
}

/// The first shadow (row-major) that nothing in the image casts, if any, past those whose
/// first bin lies on a cell the operator settled (`settled`, see [`is_settled`]). `cells[i]`:
/// cell `i`'s bins (row-major), `None` for a blocked cell (a caster); `levels[i]`: how bright
/// the lit floor around cell `i` is ([`super::looks::local_levels`]; 1 where missing).
pub fn uncast(
    cells: &[Option<[Bin; BINS]>],
    levels: &[f64],
    (gw, gh): (u32, u32),
    settled: &[bool],
) -> Option<Uncast> {
    uncast_regions(cells, levels, (gw, gh), settled)
        .into_iter()
        .map(|(u, _)| u)
        .next()
}

/// Every shadow that nothing in the image casts, as for [`uncast`] (past those whose first bin
/// lies on a settled cell), row-major, each with its bins (floor bin indices, `gw × SIDE`
/// wide, row-major).
pub fn uncast_regions(
    cells: &[Option<[Bin; BINS]>],
    levels: &[f64],
    (gw, gh): (u32, u32),
    settled: &[bool],
) -> Vec<(Uncast, Vec<usize>)> {
    let (bw, bh) = (gw as usize * SIDE, gh as usize * SIDE);
    let Some((kinds, robot_near)) = grid(cells, levels, (gw, gh), 0.0) else {
        return Vec::new();
    };
    let dark: Vec<bool> = kinds.iter().map(|&k| k == Kind::Dark).collect();
    // The casters' bins in pieces of at least `MIN_CASTER` bins: specks of an obstacle's colour
    // in a shadow (its bluish noise under a blue sky) cast nothing.
    let casting = casting_bins(&kinds, (bw, bh));
    regions(&dark, (bw, bh))
        .into_iter()
        .filter_map(|region| {
            // What touches the region, its 8-neighbours included.
            let (mut caster, mut mark) = (false, false);
            for &i in &region {
                mark |= robot_near[i];
                let (x, y) = ((i % bw) as i64, (i / bw) as i64);
                for (nx, ny) in
                    (-1..=1i64).flat_map(|dy| (-1..=1i64).map(move |dx| (x + dx, y + dy)))
                {
                    if nx < 0 || ny < 0 || nx >= bw as i64 || ny >= bh as i64 {
                        continue;
                    }
                    let j = ny as usize * bw + nx as usize;
                    caster |= casting[j];
                    mark |= kinds[j] == Kind::Mark && robot_near[j];
                }
            }
            let size = region.len();
            let cast = caster || (mark && size <= ROBOT_SHADOW);
            let u = Uncast::from_bin((region[0] % bw, region[0] / bw), size);
            (!cast && size >= MIN_SHADOW && !is_settled(settled, u.cell, gw)).then_some((u, region))
        })
        .collect()
}

/// The fewest bins (a quarter of a cell) of a piece of casters (4-connected) that may cast a
/// shadow: a shelf's blocked cell is sixteen, the sliver of a top leaning off it joins them,
/// while specks of an obstacle's colour in a shadow's noise make pieces of a bin or two (issue
/// #29's twenty-fourth round: in the held-out n0002 four such specks "cast" the shadow of a
/// dark brown shelf read as floor, and the view was read wrongly).
pub const MIN_CASTER: usize = BINS / 4;

/// The bins of [`Kind::Caster`] in pieces (4-connected) of at least [`MIN_CASTER`] bins, or
/// touching the floor's edge.
fn casting_bins(kinds: &[Kind], (bw, bh): (usize, usize)) -> Vec<bool> {
    let caster: Vec<bool> = kinds.iter().map(|&k| k == Kind::Caster).collect();
    let mut out = vec![false; kinds.len()];
    let on_edge = |i: usize| {
        let (x, y) = (i % bw, i / bw);
        x == 0 || y == 0 || x + 1 == bw || y + 1 == bh
    };
    for piece in regions(&caster, (bw, bh)) {
        // At the floor's edge a piece may be the end of a caster the view cuts off.
        if piece.len() >= MIN_CASTER || piece.iter().any(|&i| on_edge(i)) {
            for i in piece {
                out[i] = true;
            }
        }
    }
    out
}

/// The 4-connected regions of the bins `inside` (a grid `bw` × `bh`, row-major), each as its
/// bins with its lowest index first, in row-major order of those.
fn regions(inside: &[bool], (bw, bh): (usize, usize)) -> Vec<Vec<usize>> {
    let mut seen = vec![false; bw * bh];
    let mut out = Vec::new();
    let mut stack = Vec::new();
    for start in 0..bw * bh {
        if seen[start] || !inside[start] {
            continue;
        }
        seen[start] = true;
        stack.push(start);
        let mut region = Vec::new();
        while let Some(i) = stack.pop() {
            region.push(i);
            let (x, y) = (i % bw, i / bw);
            let neighbours = [
                (x > 0).then(|| i - 1),
                (x + 1 < bw).then_some(i + 1),
                (y > 0).then(|| i - bw),
                (y + 1 < bh).then_some(i + bw),
            ];
            for j in neighbours.into_iter().flatten() {
                if inside[j] && !seen[j] {
                    seen[j] = true;
                    stack.push(j);
                }
            }
        }
        out.push(region);
    }
    out
}

/// Directions tried for the sun ([`Sunlit::unattached`]), evenly around the circle.
pub const DIRECTIONS: usize = 64;
/// How far (cells) a shadow may reach from its caster: a shelf 2 high under a sun 20° up.
pub const REACH: f64 = 6.0;
/// The share of the shadow's bins (sampled) that a direction must explain to be one the view's
/// sun may shine from ([`Sunlit::suns`], for a run's far cells); with less (soft light,
/// lamps), no direction is. Until issue #29's twenty-fourth round the check that every shadow
/// lies behind its caster used it too (now [`ONE_SUN_BEHIND`]).
pub const ONE_SUN: f64 = 0.85;
/// The share of the shadow's bins that the sun's direction must explain for the check that
/// every shadow lies behind its caster ([`Sunlit::unattached`]): less than [`ONE_SUN`], since
/// the shadows that check is for lower it (a shelf of the floor's colour read as floor, its
/// shadow joined to another caster's; in the held-out n0014, whose dark brown shelf was read
/// as floor, one direction explained 78 % of the bins; issue #29's twenty-fourth round). On
/// families A–Z and a–e it refuses X0028, read exactly before.
pub const ONE_SUN_BEHIND: f64 = 0.75;
/// The fewest bins, connected, of shadow not attached to a caster that are refused (a cell).
pub const UNATTACHED: usize = BINS;
/// The most dark bins sampled to find the sun's direction.
const SAMPLE: usize = 4096;

/// Whether walking from bin `(bx, by)` toward the sun (`dir`, in bins a step) reaches a caster
/// (an obstacle, a blocked cell, a robot) over shadow, goals and lit gaps of at most one bin;
/// leaving the floor, or walking [`REACH`] cells, counts as reaching one.
fn attached(
    kinds: &[Kind],
    robot_near: &[bool],
    (bw, bh): (usize, usize),
    (bx, by): (usize, usize),
    dir: (f64, f64),
) -> bool {
    let steps = (REACH * SIDE as f64 * 2.0) as usize;
    let (x0, y0) = (bx as f64 + 0.5, by as f64 + 0.5);
    let mut gap = 0;
    for j in 1..=steps {
        let t = j as f64 * 0.5;
        let (x, y) = (x0 + dir.0 * t, y0 + dir.1 * t);
        if x < 0.0 || y < 0.0 || x >= bw as f64 || y >= bh as f64 {
            return true;
        }
        let i = y as usize * bw + x as usize;
        if robot_near[i] {
            return true;
        }
        match kinds[i] {
            Kind::Caster | Kind::Empty => return true,
            Kind::Dark | Kind::Mark => gap = 0,
            Kind::Lit => {
                gap += 1;
                if gap > 2 {
                    return false;
                }
            }
        }
    }
    true
}

/// The one of the [`DIRECTIONS`] nearest to `(x, y)`.
fn direction_index((x, y): (f64, f64)) -> usize {
    let step = std::f64::consts::TAU / DIRECTIONS as f64;
    (y.atan2(x).rem_euclid(std::f64::consts::TAU) / step).round() as usize % DIRECTIONS
}

/// Direction `k` of [`DIRECTIONS`] on the floor: a unit vector.
fn dir(k: usize) -> (f64, f64) {
    let a = (k % DIRECTIONS) as f64 * std::f64::consts::TAU / DIRECTIONS as f64;
    (a.cos(), a.sin())
}

/// For each of the [`DIRECTIONS`], how many of the `dark` bins (sampled) walking toward it
/// reaches a caster from, and how many were sampled; `None` with fewer dark bins than
/// [`UNATTACHED`].
fn explained(
    kinds: &[Kind],
    robot_near: &[bool],
    (bw, bh): (usize, usize),
    dark: &[usize],
) -> Option<(Vec<usize>, usize)> {
    if dark.len() < UNATTACHED {
        return None;
    }
    let at = |i: usize| (i % bw, i / bw);
    let stride = dark.len().div_ceil(SAMPLE);
    let sample: Vec<usize> = dark.iter().copied().step_by(stride).collect();
    let explained = |k: usize| {
        sample
            .iter()
            .filter(|&&i| attached(kinds, robot_near, (bw, bh), at(i), dir(k)))
            .count()
    };
    let counts = {
        use rayon::prelude::*;
        (0..DIRECTIONS)
            .into_par_iter()
            .map(explained)
            .collect::<Vec<_>>()
    };
    Some((counts, sample.len()))
}

/// The free floor's bins judged once for the checks that need the sun's direction: each bin's
/// kind, the bins a robot casts from (a quarter of a bin's pixels or more, or beside such a
/// bin: in a shadow, noise makes a dark red pixel here and there), the dark bins among the
/// rest, and, found once when first asked, how many of those each direction explains.
pub struct Sunlit<'a> {
    cells: &'a [Option<[Bin; BINS]>],
    floor: (u32, u32),
    kinds: Vec<Kind>,
    robot_near: Vec<bool>,
    dark: Vec<usize>,
    explained: std::cell::OnceCell<Option<(Vec<usize>, usize)>>,
}

/// The most the shadow may run along a run of blocked cells (away from the nadir) for each
/// cell it runs across it ([`Sunlit::base_reaches`]). Right beside a base ending a cell short, its
/// shadow reaches past its end by up to 1.25 cells (its width and the quarter cell beside it)
/// times this: the shadow of its far face's every point, not only of its side, runs there.
/// With 0.25 that is 0.31 cell, short of the far cell's third quarter. 1.0 until the end of
/// issue #29's thirteenth round, which counted the side's shadow alone.
pub const ALONG_PER_LATERAL: f64 = 0.25;
/// The least share of the shadow's direction across the run for its band beside the run to
/// be judged ([`Sunlit::base_reaches`]).
pub const ACROSS: f64 = 0.35;

impl<'a> Sunlit<'a> {
    /// The bins of a floor of `gw` × `gh` cells; `cells` and `levels` as for [`uncast`].
    /// `None` for a floor with no bins (or `cells` not of its size).
    pub fn new(
        cells: &'a [Option<[Bin; BINS]>],
        levels: &[f64],
        (gw, gh): (u32, u32),
    ) -> Option<Sunlit<'a>> {
        let (kinds, robot_near) = grid(cells, levels, (gw, gh), 0.25)?;
        let dark: Vec<usize> = (0..kinds.len())
            .filter(|&i| kinds[i] == Kind::Dark && !robot_near[i])
            .collect();
        Some(Sunlit {
            cells,
            floor: (gw, gh),
            kinds,
            robot_near,
            dark,
            explained: std::cell::OnceCell::new(),
        })
    }

    /// Bins along each side of the floor.
    fn size(&self) -> (usize, usize) {
        (self.floor.0 as usize * SIDE, self.floor.1 as usize * SIDE)
    }

    /// How many of the dark bins (sampled) each direction explains, and how many were sampled
    /// (see [`explained`]).
    fn counts(&self) -> Option<&(Vec<usize>, usize)> {
        self.explained
            .get_or_init(|| explained(&self.kinds, &self.robot_near, self.size(), &self.dark))
            .as_ref()
    }

    /// Every direction toward the sun on the floor (unit vectors, in cells) that explains the
    /// view's shadows as one sun's: walking toward it reaches a caster from at least
    /// [`ONE_SUN`] of the shadow bins (sampled; see [`Sunlit::unattached`]). Empty when none
    /// does. The walk forgives gaps and a long caster explains its shadow from many
    /// directions, so these may span a wide arc (X0037's from the true direction to 53° off
    /// it).
    pub fn suns(&self) -> Vec<(f64, f64)> {
        let Some((counts, sampled)) = self.counts() else {
            return Vec::new();
        };
        counts
            .iter()
            .enumerate()
            .filter(|&(_, &n)| n as f64 >= ONE_SUN * *sampled as f64)
            .map(|(k, _)| dir(k))
            .collect()
    }

    /// The direction (of [`DIRECTIONS`]) toward the sun: the one that explains the most dark
    /// bins, when that is at least [`ONE_SUN_BEHIND`] of them.
    fn sun_index(&self) -> Option<usize> {
        let (counts, sampled) = self.counts()?;
        let (best, count) =
            counts
                .iter()
                .enumerate()
                .fold((0, 0), |b, (k, &n)| if n > b.1 { (k, n) } else { b });
        ((count as f64) >= ONE_SUN_BEHIND * *sampled as f64).then_some(best)
    }

    /// The direction toward the sun on the floor: the one that explains
    /// [`ONE_SUN_BEHIND`] of the shadows (see [`Sunlit::unattached`]), or else the robots'
    /// (`robots_sun`, see [`super::sun`]).
    pub fn sun(&self, robots_sun: impl FnOnce() -> Option<(f64, f64)>) -> Option<(f64, f64)> {
        match self.sun_index() {
            Some(best) => Some(dir(best)),
            None => robots_sun(),
        }
    }

    /// A blocked cell, not one of `top`'s, that casts its shadow where `top`'s cells (row-major)
    /// lie, seen from the sun (`sun`, toward it on the floor): walking toward it from the middle
    /// of at least half of `top`'s cells, past `top`'s own cells, crosses only floor in a shadow
    /// (or a mark, or at most two bins of lit floor in a row, as for [`Sunlit::unattached`]) to
    /// reach that cell within [`REACH`] cells. `None` when no such cell casts there.
    ///
    /// A top of nearly the floor's colour read whole ([`super::faint`]) where another's shadow
    /// falls may be that shadow (held-out s0005: two shadows of a low sun, tinted by a warm
    /// sky, read as tops on the floor's edges; issue #29's twenty-seventh round).
    pub fn casts_on(&self, top: &[usize], sun: (f64, f64)) -> Option<(u32, u32)> {
        let (gw, _) = self.floor;
        let (bw, bh) = self.size();
        let own = |cx: usize, cy: usize| top.contains(&(cy * gw as usize + cx));
        let mut found: Vec<(u32, u32)> = Vec::new();
        for &c in top {
            let (cx, cy) = (c % gw as usize, c / gw as usize);
            let (x0, y0) = (
                (cx as f64 + 0.5) * SIDE as f64,
                (cy as f64 + 0.5) * SIDE as f64,
            );
            let steps = (REACH * SIDE as f64 * 2.0) as usize;
            let mut gap = 0;
            for j in 1..=steps {
                let t = j as f64 * 0.5;
                let (x, y) = (x0 + sun.0 * t, y0 + sun.1 * t);
                if x < 0.0 || y < 0.0 || x >= bw as f64 || y >= bh as f64 {
                    break;
                }
                let (bx, by) = (x as usize, y as usize);
                let (ux, uy) = (bx / SIDE, by / SIDE);
                if own(ux, uy) {
                    continue;
                }
                match self.kinds[by * bw + bx] {
                    // A blocked cell (one with no bins).
                    Kind::Caster if self.cells[uy * gw as usize + ux].is_none() => {
                        found.push((ux as u32, uy as u32));
                        break;
                    }
                    // An obstacle's colour on a free cell: the shadow's own tinted floor, as
                    // the top's, or a top leaning over it.
                    Kind::Caster => gap = 0,
                    Kind::Empty => break,
                    Kind::Dark | Kind::Mark => gap = 0,
                    // Floor lit but darker than a lit top can be (`pale::LIT`) is a faint
                    // shadow's, as the top's own is.
                    Kind::Lit if self.faint_shadow(bx, by) => gap = 0,
                    Kind::Lit => {
                        gap += 1;
                        if gap > 2 {
                            break;
                        }
                    }
                }
            }
        }
        (!found.is_empty() && 2 * found.len() >= top.len()).then(|| found[0])
    }

    /// Whether bin `(bx, by)`'s floor is darker than [`super::pale::LIT`] times the lit floor.
    fn faint_shadow(&self, bx: usize, by: usize) -> bool {
        let (gw, _) = self.floor;
        let cell = (by / SIDE) * gw as usize + bx / SIDE;
        self.cells.get(cell).copied().flatten().is_some_and(|bins| {
            let b = bins[(by % SIDE) * SIDE + bx % SIDE];
            let n = b.dark + b.lit;
            n > 0 && f64::from(b.brightness) / 1000.0 / f64::from(n) < super::pale::LIT
        })
    }

    /// The first shadow (row-major) not attached to a caster along the sun's direction, if any,
    /// past those whose first bin lies on a cell the operator settled (as for [`uncast`]).
    ///
    /// One sun casts every shadow the same way: walking from any point of a shadow toward the sun,
    /// one stays in the shadow until the thing that casts it. So the direction that explains the
    /// most shadow bins (of [`DIRECTIONS`], on a sample) is taken for the sun's when it explains
    /// at least [`ONE_SUN_BEHIND`] of them, and a connected region of [`UNATTACHED`] or more shadow bins
    /// from which that walk (or one a direction either side) crosses lit floor before any caster
    /// is refused: its caster stands on floor read as free, a shelf of the floor's own look
    /// whose shadow touches another's (V0028's graphite shelf, whose shadow joined that of the
    /// pale shelf below it; issue #29's twelfth round).
    ///
    /// When no direction explains that many, the robots' shadows may still tell the sun
    /// (`robots_sun`, a direction on the floor; see [`super::sun`]), and the walk goes toward it.
    pub fn unattached(
        &self,
        settled: &[bool],
        robots_sun: impl FnOnce() -> Option<(f64, f64)>,
    ) -> Option<Uncast> {
        let (bw, bh) = self.size();
        let best = match self.sun_index() {
            Some(best) => best,
            None => direction_index(robots_sun()?),
        };
        let (kinds, robot_near) = (&self.kinds, &self.robot_near);
        let at = |i: usize| (i % bw, i / bw);
        let mut loose = vec![false; bw * bh];
        for &i in &self.dark {
            loose[i] = [best + DIRECTIONS - 1, best, best + 1]
                .iter()
                .all(|&k| !attached(kinds, robot_near, (bw, bh), at(i), dir(k)));
        }
        regions(&loose, (bw, bh))
            .into_iter()
            .filter(|region| region.len() >= UNATTACHED)
            .map(|region| Uncast::from_bin(at(region[0]), region.len()))
            .find(|u| !is_settled(settled, u.cell, self.floor.0))
    }

    /// Whether the shadow beside the blocked cell `(x, y)`, the far cell of a run of blocked
    /// cells along `(dx, dy)` (away from the nadir), shows that the obstacle's base reaches the
    /// cell's outer half, so that the cell is its own and not only under its leaning top.
    ///
    /// The base of a box casts a band of shadow along each side that faces away from the sun
    /// (`suns`: every direction toward it on the floor that the view's shadows allow, see
    /// [`Sunlit::suns`]; each must show the base), as wide as the shadow is long across the
    /// run, from the base's foot. Right beside the base, within a quarter cell of it, the band
    /// runs along the base's whole side, and a shadow cast forward (away from the nadir) reaches
    /// past the base's end by at most 1.25 cells (the base's width and the quarter cell beside it)
    /// times the shadow's run along per cell across: every point of the base's far face casts it.
    /// So the cell is the base's own when, on a side that the shadow falls to (at least
    /// [`ACROSS`] of its direction across the run, and at most [`ALONG_PER_LATERAL`] along the
    /// run per cell across), the free cell beside it shows shadow (a [`Kind::Dark`] bin with no
    /// robot near) in the bin next to it (a quarter cell wide) over its outer half (the third
    /// quarter along the run: past a base ending at the cell's inner border and the 0.31 cell
    /// its shadow may then run forward, plus a margin), and in at least two of the bins next to the
    /// run's cell before it (the band along the base, not a stain). Nothing else must stand where
    /// it could cast that shadow: the free cells beyond the far cell and beside it (toward the
    /// sun from the band when the sun shines from beyond) must be free of robots.
    ///
    /// A cell outside the floor counts as blocked, as in [`uncast`].
    pub fn base_reaches(
        &self,
        suns: &[(f64, f64)],
        (x, y): (u32, u32),
        (dx, dy): (i64, i64),
    ) -> bool {
        let (gw, gh) = self.floor;
        let (bw, bh) = self.size();
        let (cells, kinds, robot_near) = (self.cells, &self.kinds, &self.robot_near);
        let free = |cx: i64, cy: i64| {
            cx >= 0
                && cy >= 0
                && cx < i64::from(gw)
                && cy < i64::from(gh)
                && cells[(cy * i64::from(gw) + cx) as usize].is_some()
        };
        let outside =
            |cx: i64, cy: i64| cx < 0 || cy < 0 || cx >= i64::from(gw) || cy >= i64::from(gh);
        // The bin beside the run's cell `(cx, cy)` on side `p` (in the free cell there, next to
        // the run) at `a` quarters along the run from the cell's inner border.
        let bin = |(cx, cy): (i64, i64), a: usize, p: (i64, i64)| -> Option<usize> {
            let t = (a as f64 + 0.5) / SIDE as f64 - 0.5;
            let u = cx as f64 + 0.5 + dx as f64 * t + p.0 as f64 * (0.5 + 0.5 / SIDE as f64);
            let v = cy as f64 + 0.5 + dy as f64 * t + p.1 as f64 * (0.5 + 0.5 / SIDE as f64);
            let (bx, by) = ((u * SIDE as f64).floor(), (v * SIDE as f64).floor());
            (bx >= 0.0 && by >= 0.0 && (bx as usize) < bw && (by as usize) < bh)
                .then(|| by as usize * bw + bx as usize)
        };
        let dark = |i: Option<usize>| i.is_some_and(|i| kinds[i] == Kind::Dark && !robot_near[i]);
        let (xi, yi) = (i64::from(x), i64::from(y));
        // Free (or off the floor) and without a robot: toward the sun from the band, when it
        // shines from beyond the far cell, nothing else may cast it.
        let clear = |cx: i64, cy: i64| {
            outside(cx, cy)
                || (free(cx, cy)
                    && (0..SIDE * SIDE).all(|k| {
                        let (bx, by) =
                            (cx as usize * SIDE + k % SIDE, cy as usize * SIDE + k / SIDE);
                        !robot_near[by * bw + bx]
                    }))
        };
        // Whether the band beside the cell shows its base under a sun toward `sun`, on a side.
        let shows = |sun: (f64, f64)| {
            let shadow = (-sun.0, -sun.1);
            let along = shadow.0 * dx as f64 + shadow.1 * dy as f64;
            [(-dy, dx), (dy, -dx)].into_iter().any(|p| {
                let across = shadow.0 * p.0 as f64 + shadow.1 * p.1 as f64;
                let (beside, before) = ((xi + p.0, yi + p.1), (xi - dx + p.0, yi - dy + p.1));
                across >= ACROSS
                    && along.max(0.0) <= ALONG_PER_LATERAL * across
                    && free(beside.0, beside.1)
                    && free(before.0, before.1)
                    && (along >= 0.0
                        || (clear(xi + dx, yi + dy) && clear(xi + dx + p.0, yi + dy + p.1)))
                    && dark(bin((xi, yi), 2, p))
                    && (1..SIDE)
                        .filter(|&a| dark(bin((xi - dx, yi - dy), a, p)))
                        .count()
                        >= 2
            })
        };
        // Every direction the view's shadows allow for the sun must show it.
        !suns.is_empty() && suns.iter().all(|&sun| shows(sun))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_direction_on_the_floor_is_its_nearest_of_the_directions() {
        assert_eq!(direction_index((1.0, 0.0)), 0);
        assert_eq!(direction_index((0.0, 1.0)), DIRECTIONS / 4);
        assert_eq!(direction_index((-1.0, 0.0)), DIRECTIONS / 2);
        assert_eq!(direction_index((0.0, -1.0)), 3 * DIRECTIONS / 4);
        // Just below the +u axis: the last direction, not past it.
        assert_eq!(direction_index((1.0, -0.001)), 0);
        assert_eq!(direction_index((1.0, -0.1)), DIRECTIONS - 1);
        let (x, y) = dir(direction_index((0.6, 0.8)));
        assert!((x - 0.6).abs() < 0.05 && (y - 0.8).abs() < 0.05);
    }

    #[test]
    fn the_bins_beside_a_robots_bin_are_its_eight_neighbours() {
        // A 3 × 2 floor of lit bins (12 × 8 bins), cell (1, 1) blocked; robots' pixels in
        // bins (5, 3), (0, 0) and (11, 7), and in bin (8, 2) fewer than the share asked.
        let lit = Bin {
            lit: 10,
            brightness: 10_000,
            ..Bin::default()
        };
        let mut cells = vec![Some([lit; BINS]); 6];
        cells[4] = None;
        let mut robot = |(bx, by): (usize, usize), n: u32| {
            let b = &mut cells[(by / SIDE) * 3 + bx / SIDE].as_mut().unwrap()
                [(by % SIDE) * SIDE + bx % SIDE];
            (b.robot, b.mark, b.lit) = (n, n, 10 - n);
        };
        for bin in [(5, 3), (0, 0), (11, 7)] {
            robot(bin, 10);
        }
        robot((8, 2), 1);
        let (kinds, near) = grid(&cells, &[1.0; 6], (3, 2), 0.25).unwrap();
        assert_eq!(kinds[5], Kind::Lit);
        assert_eq!(kinds[4 * 12 + 5], Kind::Caster);
        for by in 0..8usize {
            for bx in 0..12usize {
                let want = [(5usize, 3usize), (0, 0), (11, 7)]
                    .iter()
                    .any(|&(x, y)| x.abs_diff(bx) <= 1 && y.abs_diff(by) <= 1);
                assert_eq!(near[by * 12 + bx], want, "bin ({bx}, {by})");
            }
        }
    }

    /// [`Sunlit::unattached`] of a floor, as `read` asks it.
    fn unattached(
        cells: &[Option<[Bin; BINS]>],
        levels: &[f64],
        floor: (u32, u32),
    ) -> Option<Uncast> {
        Sunlit::new(cells, levels, floor)?.unattached(&[], || None)
    }

    /// [`Sunlit::suns`] of a floor, none for a floor with no bins.
    fn suns(cells: &[Option<[Bin; BINS]>], levels: &[f64], floor: (u32, u32)) -> Vec<(f64, f64)> {
        Sunlit::new(cells, levels, floor).map_or_else(Vec::new, |s| s.suns())
    }

    /// [`Sunlit::base_reaches`] of a floor.
    fn base_reaches(
        cells: &[Option<[Bin; BINS]>],
        levels: &[f64],
        floor: (u32, u32),
        suns: &[(f64, f64)],
        cell: (u32, u32),
        dir: (i64, i64),
    ) -> bool {
        Sunlit::new(cells, levels, floor).is_some_and(|s| s.base_reaches(suns, cell, dir))
    }

    /// Nine floor pixels as bright as the lit floor.
    const LIT: Bin = Bin {
        dark: 0,
        lit: 9,
        solid: 0,
        mark: 0,
        robot: 0,
        brightness: 9000,
    };
    /// Seven floor pixels in a shadow (half as bright) and two lit.
    const DARKENED: Bin = Bin {
        dark: 7,
        lit: 2,
        solid: 0,
        mark: 0,
        robot: 0,
        brightness: 5500,
    };
    const ROBOT: Bin = Bin {
        dark: 1,
        lit: 1,
        solid: 0,
        mark: 7,
        robot: 3,
        brightness: 0,
    };
    const GOAL: Bin = Bin {
        dark: 1,
        lit: 1,
        solid: 0,
        mark: 7,
        robot: 0,
        brightness: 0,
    };

    /// A floor of `w` × `h` cells, all lit and free, with the bins `dark` (floor bin
    /// coordinates) in a shadow.
    fn floor(w: u32, h: u32, dark: &[(usize, usize)]) -> Vec<Option<[Bin; BINS]>> {
        let mut cells = vec![Some([LIT; BINS]); (w * h) as usize];
        for &(bx, by) in dark {
            let c = (by / SIDE) * w as usize + bx / SIDE;
            cells[c].as_mut().unwrap()[(by % SIDE) * SIDE + bx % SIDE] = DARKENED;
        }
        cells
    }

    /// A band of shadow 3 bins wide, bins x 8..11 of rows 4..12 (cells 2 by 1 and 2).
    fn band() -> Vec<(usize, usize)> {
        (4..12).flat_map(|y| (8..11).map(move |x| (x, y))).collect()
    }

    #[test]
    fn bins_are_judged_by_most_of_their_pixels() {
        assert_eq!(Bin::default().kind(), Kind::Empty);
        assert_eq!(LIT.kind(), Kind::Lit);
        assert_eq!(DARKENED.kind(), Kind::Dark);
        assert_eq!(ROBOT.kind(), Kind::Mark);
        // A painted line along a third of a lit bin leaves it lit.
        let lined = Bin {
            dark: 3,
            lit: 6,
            ..Bin::default()
        };
        assert_eq!(lined.kind(), Kind::Lit);
        let shelf = Bin {
            solid: 5,
            lit: 4,
            ..Bin::default()
        };
        assert_eq!(shelf.kind(), Kind::Caster);
    }

    #[test]
    fn in_a_pool_of_light_or_on_a_dim_floor_a_bin_is_dark_against_the_floor_around_it() {
        // Nine pixels at 0.9: lit against the lit floor's median, dark under a lamp whose
        // floor is 1.4 (0.9 < 0.8 × 1.4); where the light is 1.15, under [`POOL`], judged
        // against the median (lit).
        let bin = Bin {
            lit: 9,
            brightness: 9 * 900,
            ..Bin::default()
        };
        assert_eq!(bin.kind_in(1.0), Kind::Lit);
        assert_eq!(bin.kind_in(1.4), Kind::Dark);
        assert_eq!(bin.kind_in(1.15), Kind::Lit);
        // A darkened bin stays dark however dim the floor around it.
        assert_eq!(DARKENED.kind_in(0.7), Kind::Dark);
        // Nine pixels at 0.75: dark against the median, lit against a dim floor at 0.92 (a dark
        // floor's cells between pale painted lines), and against a floor dimmer still no darker
        // than [`DIM`] allows (0.75 ≥ 0.8 × 0.9): its level may be a shadow's own.
        let dim = Bin {
            dark: 9,
            brightness: 9 * 750,
            ..Bin::default()
        };
        assert_eq!(dim.kind_in(1.0), Kind::Dark);
        assert_eq!(dim.kind_in(0.92), Kind::Lit);
        assert_eq!(dim.kind_in(0.5), Kind::Lit);
        let deeper = Bin {
            dark: 9,
            brightness: 9 * 700,
            ..Bin::default()
        };
        assert_eq!(deeper.kind_in(0.5), Kind::Dark);
        // Casters and marks do not change with the light.
        let shelf = Bin {
            solid: 9,
            ..Bin::default()
        };
        assert_eq!(shelf.kind_in(1.4), Kind::Caster);
        assert_eq!(ROBOT.kind_in(1.4), Kind::Mark);
    }

    #[test]
    fn a_shadow_with_nothing_to_cast_it_is_found() {
        let cells = floor(5, 4, &band());
        let u = uncast(&cells, &[], (5, 4), &[]).unwrap();
        assert_eq!(u.cell, (2, 1));
        assert_eq!(u.bins, 24);
        assert!((u.at.0 - 2.125).abs() < 1e-9 && (u.at.1 - 1.125).abs() < 1e-9);
        // Lit floor alone, or a speck of seven bins, has none.
        assert_eq!(uncast(&floor(5, 4, &[]), &[], (5, 4), &[]), None);
        let speck: Vec<(usize, usize)> = (3..10).map(|x| (x, 3)).collect();
        assert_eq!(uncast(&floor(5, 4, &speck), &[], (5, 4), &[]), None);
    }

    #[test]
    fn a_blocked_cell_or_an_obstacle_beside_it_casts_it() {
        // Cell (1, 1) blocked: the band's bins x 8.. touch its bins x 4..7 (x 7 next to 8).
        let mut cells = floor(5, 4, &band());
        cells[5 + 1] = None;
        assert_eq!(uncast(&cells, &[], (5, 4), &[]), None);
        // Or an obstacle's pixels in a free cell, diagonally beside the band's last bin, over a
        // quarter of a cell.
        let solid = Bin {
            solid: 9,
            ..Bin::default()
        };
        let mut cells = floor(5, 4, &band());
        for k in [2, 3, 6, 7] {
            cells[3 * 5 + 2].as_mut().unwrap()[k] = solid;
        }
        assert_eq!(uncast(&cells, &[], (5, 4), &[]), None);
        // A speck of an obstacle's colour, a bin or three, casts nothing (MIN_CASTER).
        let mut cells = floor(5, 4, &band());
        for k in [3, 7] {
            cells[3 * 5 + 2].as_mut().unwrap()[k] = solid;
        }
        assert!(uncast(&cells, &[], (5, 4), &[]).is_some());
        // Unless it touches the floor's edge, where the view may cut a caster off.
        let (l, c) = (Kind::Lit, Kind::Caster);
        let kinds = [l, l, l, c, l, c, l, c, l, c, l, l, l, l, l, l];
        let casting = casting_bins(&kinds, (4, 4));
        assert_eq!(
            (0..16).filter(|&i| casting[i]).collect::<Vec<_>>(),
            vec![3, 7],
            "the piece on the edge, not the one inside"
        );
    }

    #[test]
    fn a_robot_casts_a_small_shadow_only() {
        // A robot's bin beside a shadow of 12 bins casts it (alone it is refused); beside the band of 24 too (at
        // most 32); beside a band of 36 it does not.
        let robot_at = |cells: &mut Vec<Option<[Bin; BINS]>>| {
            cells[5 + 1].as_mut().unwrap()[SIDE * SIDE - 1] = ROBOT; // bin (7, 7)
        };
        let small: Vec<(usize, usize)> =
            (4..8).flat_map(|y| (8..11).map(move |x| (x, y))).collect();
        assert_eq!(
            uncast(&floor(5, 4, &small), &[], (5, 4), &[]).map(|u| u.bins),
            Some(12)
        );
        let mut cells = floor(5, 4, &small);
        robot_at(&mut cells);
        assert_eq!(uncast(&cells, &[], (5, 4), &[]), None);
        let mut cells = floor(5, 4, &band());
        robot_at(&mut cells);
        assert_eq!(uncast(&cells, &[], (5, 4), &[]), None);
        let large: Vec<(usize, usize)> =
            (4..16).flat_map(|y| (8..11).map(move |x| (x, y))).collect();
        let mut cells = floor(5, 4, &large);
        robot_at(&mut cells);
        assert_eq!(uncast(&cells, &[], (5, 4), &[]).map(|u| u.bins), Some(36));
        // A goal lies flat: beside the band of 12 it casts nothing.
        let mut cells = floor(5, 4, &small);
        cells[5 + 1].as_mut().unwrap()[SIDE * SIDE - 1] = GOAL;
        assert_eq!(uncast(&cells, &[], (5, 4), &[]).map(|u| u.bins), Some(12));
        // A robot's bin two bins away, behind the band of pixels near it, still casts it.
        let mut cells = floor(5, 4, &small);
        cells[5 + 1].as_mut().unwrap()[SIDE * SIDE - 1] = GOAL;
        cells[5 + 1].as_mut().unwrap()[SIDE * SIDE - 2] = ROBOT; // bin (6, 7)
        assert_eq!(uncast(&cells, &[], (5, 4), &[]), None);
    }

    /// A 12 × 12-cell floor with shelves (blocked) on cells (1, 0), (1, 2), …, (1, 10), each
    /// casting a shadow 1.5 cells long to the right (+x) over its row's bins; with `hidden`, a
    /// shelf of the floor's look on cell (7, 5) (lit, free) casting its shadow too (a seventh
    /// of the shadows: the sun's direction still explains more than 85 % of them).
    fn sunlit(hidden: bool) -> Vec<Option<[Bin; BINS]>> {
        let mut dark = Vec::new();
        let rows: Vec<(usize, usize)> = (0..6).map(|k| (2 * SIDE, 2 * k * SIDE)).collect();
        let hidden_row = [(8 * SIDE, 5 * SIDE)];
        let with = if hidden { &hidden_row[..] } else { &[] };
        for &(x0, y0) in rows.iter().chain(with) {
            for by in y0..y0 + SIDE {
                for bx in x0..x0 + 6 {
                    dark.push((bx, by));
                }
            }
        }
        let mut cells = floor(12, 12, &dark);
        for k in 0..6 {
            cells[2 * k * 12 + 1] = None;
        }
        cells
    }

    #[test]
    fn a_top_where_another_s_shadow_falls_may_be_that_shadow() {
        // Cells (2, 0) and (3, 0), in the shadow of the shelf on (1, 0), read as a top.
        let mut cells = sunlit(false);
        cells[2] = None;
        cells[3] = None;
        let sun = Sunlit::new(&cells, &[], (12, 12)).unwrap();
        assert_eq!(sun.sun(|| None), Some(dir(DIRECTIONS / 2)));
        assert_eq!(sun.casts_on(&[2, 3], (-1.0, 0.0)), Some((1, 0)));
        // With the sun on the other side, nothing casts a shadow there.
        assert_eq!(sun.casts_on(&[2, 3], (1.0, 0.0)), None);
        // A top on lit floor, three cells from the nearest shelf toward the sun.
        let mut cells = sunlit(false);
        cells[4 * 12 + 6] = None;
        cells[4 * 12 + 7] = None;
        let sun = Sunlit::new(&cells, &[], (12, 12)).unwrap();
        assert_eq!(sun.casts_on(&[4 * 12 + 6, 4 * 12 + 7], (-1.0, 0.0)), None);
        // Nor a single cell there.
        assert_eq!(sun.casts_on(&[4 * 12 + 6], (-1.0, 0.0)), None);
        // Lit floor a little darker than a lit top (a faint shadow's), or an obstacle's colour
        // on a free cell (the shadow's tinted pixels), between the top and the shelf: still its
        // shadow. Cells (4, 0) and (5, 0) read as a top, cell (3, 0) between.
        for between in [
            Bin {
                brightness: 9 * 850,
                ..LIT
            },
            Bin {
                solid: 9,
                lit: 0,
                brightness: 0,
                ..LIT
            },
        ] {
            let mut cells = sunlit(false);
            cells[3] = Some([between; BINS]);
            cells[4] = None;
            cells[5] = None;
            let sun = Sunlit::new(&cells, &[], (12, 12)).unwrap();
            assert_eq!(
                sun.casts_on(&[4, 5], (-1.0, 0.0)),
                Some((1, 0)),
                "{between:?}"
            );
        }
        // As lit as the floor, three bins and more: not.
        let mut cells = sunlit(false);
        cells[3] = Some([LIT; BINS]);
        cells[4] = None;
        cells[5] = None;
        let sun = Sunlit::new(&cells, &[], (12, 12)).unwrap();
        assert_eq!(sun.casts_on(&[4, 5], (-1.0, 0.0)), None);
    }

    #[test]
    fn a_shadow_behind_lit_floor_seen_from_the_sun_is_found() {
        // The shelves' shadows lie behind them, seen from the sun (to the left).
        assert_eq!(unattached(&sunlit(false), &[], (12, 12)), None);
        // The hidden shelf's shadow touches nothing but lit floor toward the sun.
        let u = unattached(&sunlit(true), &[], (12, 12)).unwrap();
        assert_eq!(u.cell, (8, 5));
        assert_eq!(u.bins, 24);
        // A blocked cell there casts it.
        let mut cells = sunlit(true);
        cells[5 * 12 + 7] = None;
        assert_eq!(unattached(&cells, &[], (12, 12)), None);
        // With a shelf on cell (9, 5), away from the sun, the shadow left on cell (8, 5)
        // touches it, so it has a caster by `uncast`'s test, but it still lies behind lit
        // floor.
        let mut cells = sunlit(true);
        cells[5 * 12 + 9] = None;
        assert_eq!(uncast(&cells, &[], (12, 12), &[]), None);
        assert_eq!(unattached(&cells, &[], (12, 12)).unwrap().cell, (8, 5));
        // Cell (8, 5) settled by the operator: that shadow is not refused.
        let mut settled = vec![false; 144];
        settled[5 * 12 + 8] = true;
        let sun = Sunlit::new(&cells, &[], (12, 12)).unwrap();
        assert_eq!(sun.unattached(&settled, || None), None);
        // The shadows tell the sun here: the robots' shadows are not asked.
        let asked = std::cell::Cell::new(false);
        let robots = || {
            asked.set(true);
            None
        };
        assert_eq!(sun.unattached(&[], robots).unwrap().cell, (8, 5));
        assert!(!asked.get());
    }

    #[test]
    fn the_suns_the_shadows_allow_include_the_true_one_only() {
        // The shelves' shadows run to the right: the sun is to the left (−x). Every direction
        // returned points that way (the walk toward the sun from a shadow bin reaches its
        // shelf), and the one straight to the left is among them.
        let suns = suns(&sunlit(false), &[], (12, 12));
        assert!(!suns.is_empty());
        assert!(suns.iter().all(|&(x, _)| x < 0.0), "{suns:?}");
        assert!(
            suns.iter().any(|&(x, y)| x < -0.99 && y.abs() < 0.1),
            "{suns:?}"
        );
        // No shadow, or shadows of no one sun: no direction.
        assert!(suns_of_nothing().is_empty());
    }

    fn suns_of_nothing() -> Vec<(f64, f64)> {
        suns(&floor(4, 4, &[]), &[], (4, 4))
    }

    #[test]
    fn shadows_of_no_one_sun_are_not_judged() {
        // Shadows cast to the right of one shelf and below another: no direction explains
        // 85 % of them, so a shadow behind lit floor is not refused by this check.
        let mut dark = Vec::new();
        for by in SIDE..2 * SIDE {
            for bx in 2 * SIDE..2 * SIDE + 6 {
                dark.push((bx, by));
            }
        }
        for by in 5 * SIDE..5 * SIDE + 6 {
            for bx in 8 * SIDE..9 * SIDE {
                dark.push((bx, by));
            }
        }
        for by in 2 * SIDE..3 * SIDE {
            for bx in 4 * SIDE..4 * SIDE + 6 {
                dark.push((bx, by));
            }
        }
        let mut cells = floor(12, 8, &dark);
        cells[12 + 1] = None;
        cells[4 * 12 + 8] = None;
        assert_eq!(unattached(&cells, &[], (12, 8)), None);
    }

    #[test]
    fn a_shadow_is_one_region_along_rows_and_columns_only() {
        // Two squares of 6 bins that meet only at a corner are two shadows, each too small.
        let square = |o: usize| (o..o + 3).flat_map(move |y| (o..o + 2).map(move |x| (x, y)));
        let mut dark: Vec<(usize, usize)> = square(0).collect();
        dark.extend(square(2).map(|(x, y)| (x, y + 1)));
        assert_eq!(uncast(&floor(3, 3, &dark), &[], (3, 3), &[]), None);
        // Joined along a side they are one of 12.
        let mut dark: Vec<(usize, usize)> = square(0).collect();
        dark.extend(square(2).map(|(x, y)| (x, y - 2)));
        let u = uncast(&floor(3, 3, &dark), &[], (3, 3), &[]).unwrap();
        assert_eq!((u.cell, u.bins), ((0, 0), 12));
        // A mismatched list of cells is no finding, not a panic.
        assert_eq!(uncast(&floor(3, 3, &dark), &[], (4, 3), &[]), None);
        assert_eq!(uncast(&[], &[], (0, 0), &[]), None);
    }

    #[test]
    fn a_shadow_beside_a_run_s_far_cell_shows_its_base_there() {
        // A run of blocked cells (2, 1)–(2, 3) along +v, away from the nadir, on a 6 × 6
        // floor; the sun toward −u, so the shadow falls beside the run toward +u. `band` rows
        // of bins (along v) of the first bin column of the cells at u = 3 are dark.
        let reaches = |rows: std::ops::Range<usize>, sun: (f64, f64), robot_beyond: bool| {
            let dark: Vec<(usize, usize)> = rows.map(|by| (3 * SIDE, by)).collect();
            let mut cells = floor(6, 6, &dark);
            for y in 1..=3 {
                cells[y * 6 + 2] = None;
            }
            if robot_beyond {
                cells[4 * 6 + 2].as_mut().unwrap()[5] = ROBOT;
            }
            base_reaches(&cells, &[], (6, 6), &[sun], (2, 3), (0, 1))
        };
        let west = (-1.0, 0.0);
        // The band along the whole run, to the far cell's outer border: its base is there.
        assert!(reaches(4..16, west, false));
        // A band ending at the far cell's inner border: a base ending there, whose top may
        // lean over the far cell.
        assert!(!reaches(4..12, west, false));
        // Shadow beside the far cell alone: a stain, or something else's.
        assert!(!reaches(12..16, west, false));
        // A shadow running forward more than a quarter as far as across: a base ending a cell
        // short casts it there too, from its far face (X0037: 1.3 times as far).
        let low_ahead = (-0.5, -0.87);
        assert!(!reaches(4..16, low_ahead, false));
        let ahead = (-0.89, -0.45);
        assert!(!reaches(4..16, ahead, false));
        let barely_ahead = (-0.97, -0.2);
        assert!(reaches(4..16, barely_ahead, false));
        // A sun from beyond the run, shadows cast back toward the nadir: judged, unless a
        // robot beyond the far cell may cast that shadow.
        let behind = (-0.8, 0.6);
        assert!(reaches(4..16, behind, false));
        assert!(!reaches(4..16, behind, true));
        // The far cell's neighbour blocked: nothing to see.
        let dark: Vec<(usize, usize)> = (4..16).map(|by| (3 * SIDE, by)).collect();
        let mut cells = floor(6, 6, &dark);
        for y in 1..=3 {
            cells[y * 6 + 2] = None;
        }
        let all_free = cells.clone();
        cells[3 * 6 + 3] = None;
        assert!(!base_reaches(&cells, &[], (6, 6), &[west], (2, 3), (0, 1)));
        // Every direction the shadows allow must show it; none known, nothing shows.
        assert!(base_reaches(
            &all_free,
            &[],
            (6, 6),
            &[west, barely_ahead],
            (2, 3),
            (0, 1)
        ));
        assert!(!base_reaches(
            &all_free,
            &[],
            (6, 6),
            &[west, ahead],
            (2, 3),
            (0, 1)
        ));
        assert!(!base_reaches(&all_free, &[], (6, 6), &[], (2, 3), (0, 1)));
    }
}
