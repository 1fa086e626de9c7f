//! The face of a run of blocked cells toward the nadir: how far its top leans, and so whether
//! the run's far cell is its own.
//!
//! A run of blocked cells pointing away from the nadir ends in a covered cell with a free cell
//! beyond it. That far cell may be the run's own (blocked) or free under the top of the cell
//! before it, leaning over it; [`super::cover::lean_doubt`] refuses it when the lean measured
//! beside the run could cover it whole. Beside a run pointing near the nadir that lean is
//! measured badly (the top moves little across the run), yet such runs show their lean along
//! themselves: the face toward the nadir, at the run's near end, stands between the base's
//! near edge and the top's, and the top ends at the far end.
//!
//! Geometry, along the run's axis (floor cells, distances from the nadir N): a shelf of height
//! z under a camera at height H shows its top scaled by k = H / (H − z) about N. The cover
//! (face and top, read as obstacle) starts at the base's near edge C₀ and ends where the top
//! ends, E = N + k (B − N), B the base's far edge. The face toward the nadir is (k − 1)(C₀ − N)
//! long. So the cover's end tells k once B is chosen: with B at the far cell's inner border
//! (free far cell), the face must be at least `free = (|E − N| / |inner − N| − 1) |C₀ − N|`
//! long (an inset of the base only lengthens it); with B at its outer border (blocked far
//! cell), about `own = (|E − N| / |outer − N| − 1) |C₀ − N|`. The two differ by about
//! |C₀ − N| / |outer − N| of a cell, most of a cell for a run pointing near the nadir. On
//! issue #29's families the face's length as measured followed the hypothesis true to the
//! scene within 0.1 cell, free far cells' faces running the whole `free` length.
//!
//! The face is found by its shade: a vertical face is lit otherwise than the horizontal top
//! (the sun's angle to it differs, and it sees half the sky). Along the middle of the run,
//! slices of the cover are compared with the top's level, taken where the top is under either
//! hypothesis (from `free` past C₀ to just short of E). The far cell is the run's own when
//! - the cover starts within [`INSET`] of the run's near border (the face is read as
//!   obstacle from its base) and ends at least near the far cell's outer border (a blocked far
//!   cell's top reaches it, less the base's inset),
//! - the top's level is steady ([`STEADY`]) over at least [`TOP_SLICES`] slices,
//! - the face is plainly of another shade than the top ([`CONTRAST`], past the blur at C₀),
//!   over at least [`FACE_PX`] pixels (blur alone darkens or brightens a pixel or two), and
//! - the face ends within [`MARGIN`] of the length `free` would need.
//!
//! A face of the top's own shade, or read as floor, or a top in another's shadow, decides
//! nothing by itself. But where a free far cell would need a face at least [`HIDDEN_FREE`]
//! long and none shows (none longer than the blur, or, since issue #29's twenty-third round,
//! one within the margin above that is fainter than [`CONTRAST`]), the verdict is
//! [`Face::Hidden`]: the reader then takes the far cell as the run's own when a face looking
//! that way could not have the top's shade. Either the sun, as the view's shadows give it,
//! shines from behind the face ([`in_own_shadow`]): a face in its own shadow is lit by the sky
//! alone, far darker than the top; that long, it would show, or, read as floor, move the
//! cover's start past [`INSET`]. Or (since the twenty-third round) another run of the view
//! pointing the same way shows its face plainly unlike its top, whatever that face's length
//! ([`shows`], [`super::cover::face_shown`]): the light a face gets, over the light its top
//! gets, depends on the sun's and the sky's directions, not on the paint, so faces that look
//! one way show alike in one view.
//!
//! Measured on families A–Z and a–e (the twenty-third round): of the far cells whose face is
//! hidden so, 79 are blocked in the truth and 3 free, all three in the Blender families G and
//! H and already read as the run's own by the sun's test before that round. Of the 38 free
//! far cells whose face was measured, the faces in the Mitsuba families ran 0.73 to 1.1 times
//! the free length, none within the margin.

use super::cover::{slices, Strip};
use super::homography::Homography;
use image::RgbImage;

/// Slices along the run (cells).
const SLICE: f64 = 0.05;
/// The cover must start within this of the run's near border (cells): a base's inset.
pub const INSET: f64 = 0.25;
/// A slice within this share of the top's level is the top's.
pub const LEVEL: f64 = 0.06;
/// The top's level is steady: the slices between its tenth and ninetieth percentiles lie within
/// this share of it (the light along a top, and a top's noise in narrow slices).
pub const STEADY: f64 = 0.1;
/// The face differs from the top's level by at least this share.
pub const CONTRAST: f64 = 0.12;
/// The fewest pixels the face must run along the run.
pub const FACE_PX: f64 = 3.0;
/// The face ends within this share of the length a free far cell would need.
pub const MARGIN: f64 = 0.5;
/// The fewest slices of the top.
pub const TOP_SLICES: usize = 3;
/// How far short of its end the top's level is taken (cells): the top's edge blurs there.
const END: f64 = 0.15;
/// How far past the far cell's outer border the profile runs (cells).
const PAST: f64 = 2.0;

/// A run of blocked cells along one floor axis, pointing away from the nadir, whose far cell
/// is in doubt.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Run {
    /// The run lies along the floor's u axis (else along v).
    pub along_u: bool,
    /// +1 or −1: the direction away from the nadir along the axis.
    pub dir: f64,
    /// The far cell's index along the axis.
    pub far: i64,
    /// The run's cells' index across the axis.
    pub across: i64,
    /// The run's cells, the far cell included.
    pub cells: i64,
    /// The nadir's coordinate along the axis.
    pub nadir: f64,
}

/// One slice of the cover's profile: the share of obstacle pixels and their mean brightness
/// (all the slice's pixels, mean of the three channels); `None` without pixels.
type Slice = Option<(f64, f64)>;

/// What the face toward the nadir tells of a run's far cell ([`judge`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Face {
    /// A face of another shade than the top, too short for a free far cell: the cell is the
    /// run's own.
    Own,
    /// The cover and the top are as for [`Face::Own`] and a free far cell would need a face
    /// at least [`HIDDEN_FREE`] long, but no face longer than the blur shows, or only a short
    /// one too faint to be plainly one: the cell is the run's own if the face could not have
    /// the top's shade, that is if the sun shines from behind it, or if the view's other faces
    /// that look the same way show plainly (see `mod.rs`, where the sun's directions are
    /// known, and [`super::cover::face_shown`]).
    Hidden,
    /// A face at least half as long as a free far cell needs shows (since issue #29's
    /// twenty-third round; before, [`Face::Unknown`]): nothing tells the cell is the run's own,
    /// and a cell read otherwise as the run's own by another run ending at it is not
    /// ([`super::cover::face_tells`]).
    Long,
    /// Nothing to tell.
    Unknown,
}

/// The least length (cells) of the face a free far cell would need for [`Face::Hidden`]: a
/// face in its own shadow that long shows, as obstacle darker than the top, or, read as
/// floor, moves the cover's start past [`INSET`].
pub const HIDDEN_FREE: f64 = 0.5;

/// What the face toward the nadir tells of the run's far cell (see the module's comment).
/// `px` is the cell's size in pixels near the run.
pub fn judge(
    img: &RgbImage,
    classes: &[u8],
    maps: (&Homography, &Homography),
    run: Run,
    px: f64,
) -> Face {
    judged(img, classes, maps, run, px, false, None).unwrap_or(Face::Unknown)
}

/// What the run's face toward the nadir tells of a lean of its top measured elsewhere (a free
/// cell beyond its far cell, read as under that top): `needed`, the face's length that lean
/// makes ((k − 1) times the near border's distance from the nadir). [`Face::Long`] when a face
/// at least half that long shows; [`Face::Hidden`] when none shows, or [`Face::Own`] when a
/// plain one shows at most half as long: the run's top does not lean so far from the run as
/// read (since issue #29's twenty-sixth round).
pub fn judge_lean(
    img: &RgbImage,
    classes: &[u8],
    maps: (&Homography, &Homography),
    run: Run,
    px: f64,
    needed: f64,
) -> Face {
    judged(img, classes, maps, run, px, false, Some(needed)).unwrap_or(Face::Unknown)
}

/// Whether the run's face toward the nadir shows plainly unlike its top, whatever its length
/// (as for [`Face::Own`], without its bound on the face's length): the light on the view's
/// faces that look that way (see [`super::cover::face_shown`]).
pub fn shows(
    img: &RgbImage,
    classes: &[u8],
    maps: (&Homography, &Homography),
    run: Run,
    px: f64,
) -> bool {
    judged(img, classes, maps, run, px, true, None) == Some(Face::Own)
}

#[allow(clippy::too_many_arguments)]
fn judged(
    img: &RgbImage,
    classes: &[u8],
    maps: (&Homography, &Homography),
    run: Run,
    px: f64,
    any_length: bool,
    needed: Option<f64>,
) -> Option<Face> {
    if px.is_nan() || px < 1.0 {
        return None; // no cell size in pixels: no blur to tell a face from
    }
    let Run {
        dir, far, cells, ..
    } = run;
    let inner = if dir > 0.0 {
        far as f64
    } else {
        far as f64 + 1.0
    };
    let outer = inner + dir;
    let near = inner - dir * (cells - 1) as f64;
    let from = near - dir * 0.3;
    let n = ((cells as f64 + 0.3 + PAST) / SLICE).round() as usize;
    let slices = profile(img, classes, maps, run, from, n);
    let at = |s: usize| from + dir * s as f64 * SLICE;
    let covered = |s: &Slice| s.is_some_and(|(share, _)| share >= 0.5);
    let first = slices.iter().position(covered)?;
    // The covered stretch from `first`, slices without pixels passed over.
    let mut last = first;
    for (s, slice) in slices.iter().enumerate().skip(first + 1) {
        match slice {
            Some(_) if covered(slice) => last = s,
            Some(_) => break,
            None => {}
        }
    }
    let (c0, e) = (at(first), at(last + 1));
    // (Slices are 0.05 apart from 0.3 before the near border: the bounds are met within
    // rounding.)
    if !(-0.1 - 1e-9..=INSET + 1e-9).contains(&((c0 - near) * dir)) {
        return None;
    }
    let (dn, de) = ((c0 - run.nadir).abs(), (e - run.nadir).abs());
    // The face a free far cell would need (or the one a lean measured elsewhere needs).
    let free = match needed {
        Some(f) => f,
        None => {
            let own = (de / (outer - run.nadir).abs() - 1.0) * dn;
            let free = (de / (inner - run.nadir).abs() - 1.0) * dn;
            if own < -0.05 {
                return None;
            }
            free
        }
    };
    if free <= 0.0 {
        return None;
    }
    let offset = |s: usize| (at(s) + dir * SLICE / 2.0 - c0) * dir;
    let length = (e - c0) * dir;
    let mut top: Vec<f64> = (first..=last)
        .filter(|&s| offset(s) >= 1.1 * free && offset(s) <= length - END)
        .filter_map(|s| slices[s].map(|(_, b)| b))
        .collect();
    if top.len() < TOP_SLICES {
        return None;
    }
    top.sort_by(f64::total_cmp);
    let level = top[top.len() / 2];
    let (lo, hi) = (top[top.len() / 10], top[top.len() - 1 - top.len() / 10]);
    if level <= 0.0 || hi - lo > STEADY * level {
        return None;
    }
    // The face: up to the last slice off the top's level, short of where the top begins for
    // a free far cell.
    let off = |b: f64| (b - level).abs() > LEVEL * level;
    let face = (first..=last)
        .filter(|&s| offset(s) < 1.1 * free && slices[s].is_some_and(|(_, b)| off(b)))
        .map(|s| offset(s) + SLICE / 2.0)
        .fold(0.0, f64::max);
    if face > MARGIN * free && !any_length {
        return Some(Face::Long);
    }
    if face * px < FACE_PX {
        return (free >= HIDDEN_FREE && !any_length).then_some(Face::Hidden);
    }
    // Its shade past the blur at its base.
    let blur = 1.5 / px;
    let mut shade: Vec<f64> = (first..=last)
        .filter(|&s| offset(s) >= blur && offset(s) < face)
        .filter_map(|s| slices[s].map(|(_, b)| (b - level) / level))
        .collect();
    if shade.is_empty() {
        return None;
    }
    shade.sort_by(f64::total_cmp);
    if shade[shade.len() / 2].abs() >= CONTRAST {
        Some(Face::Own)
    } else {
        // Too short and too faint for a free far cell's face: as if none showed.
        (free >= HIDDEN_FREE && !any_length).then_some(Face::Hidden)
    }
}

/// How far behind a face the sun must be, as the dot product of the floor's direction toward
/// the sun with the run's direction away from the nadir (the face looks the other way).
pub const BEHIND: f64 = 0.3;

/// Whether the face toward the nadir of a run pointing `dir` (a step in cells away from the
/// nadir) is in its own shadow under every sun in `suns` (directions toward the sun on the
/// floor, unit vectors, from [`super::shadows::Sunlit::suns`]): each at least [`BEHIND`] along
/// `dir`. Not without a sun. Such a face is lit by the sky alone, far darker than a top in the
/// sun (on issue #29's families the faces measured, most of them lit by the sun, were from 3 %
/// brighter to 62 % darker than their tops).
pub fn in_own_shadow(suns: &[(f64, f64)], dir: (i64, i64)) -> bool {
    let (dx, dy) = (dir.0 as f64, dir.1 as f64);
    !suns.is_empty() && suns.iter().all(|&(sx, sy)| sx * dx + sy * dy >= BEHIND)
}

/// The cover's profile along the run's middle (the middle half of its cells across), `n`
/// slices from `from` away from the nadir.
fn profile(
    img: &RgbImage,
    classes: &[u8],
    maps: (&Homography, &Homography),
    run: Run,
    from: f64,
    n: usize,
) -> Vec<Slice> {
    let strip = Strip {
        along_u: run.along_u,
        from,
        dir: run.dir,
        step: SLICE,
        n,
        across: (run.across as f64 + 0.25, run.across as f64 + 0.75),
    };
    slices(classes, img.width() as usize, maps, &strip, Some(img))
        .into_iter()
        .map(|s| {
            (s.pixels > 0).then(|| {
                (
                    f64::from(s.obstacle) / f64::from(s.pixels),
                    s.brightness / f64::from(s.pixels),
                )
            })
        })
        .collect()
}

/// How much darker than the lit floor around it (its local level) a free cell toward the
/// nadir from a blocked run may be and still be read as a face ([`shifted_run`]): darker than
/// lit floor's own spread, not as dark as most cast shadows.
pub const BAND: (f64, f64) = (0.72, 0.9);
/// The fewest cells side by side of a run whose cells toward the nadir all show such a band.
pub const BAND_RUN: usize = 2;
/// A sun whose direction (toward it) leans less than this against the band's direction cannot
/// cast the run's shadow over the band (cosine).
pub const BAND_SUN: f64 = -0.3;

/// A run of blocked cells that may stand a whole cell nearer the nadir (issue #29's held-out
/// family f, f0018). A tall top leaning a whole cell covers the cells beyond its base almost
/// exactly, as a top of their own would; what tells the two apart is the base's cells: under a
/// top of its own, the free cells toward the nadir show floor up to the run's border, while
/// under a top leaning a whole cell they show the obstacle's face toward the nadir. A face in
/// shade, of a pale shelf, reads as floor a little darker than the lit floor around it.
///
/// So: along each row (and each column) of cells on one side of the nadir, the first run of at
/// least [`BAND_RUN`] blocked cells side by side whose every neighbour toward the nadir across
/// the run is a free cell, within [`BAND`] of its local lit level, when no sun the view's
/// shadows give could cast the run's shadow over them (every sun's direction, toward it, at
/// least [`BAND_SUN`] along the band's), or the view gives no sun. Cells the operator settled
/// (`settled`) end a run and are not a band. Returns the run's first cell and the step from
/// the run to its band; rows first, then columns, each in order.
#[allow(clippy::too_many_arguments)]
pub fn shifted_run(
    blocked: &[bool],
    settled: &[bool],
    bright: &[Option<f64>],
    levels: &[f64],
    (gw, gh): (u32, u32),
    nadir_side: impl Fn(i64, i64) -> (i32, i32),
    suns: &[(f64, f64)],
) -> Option<((i64, i64), (i64, i64))> {
    let (w, h) = (i64::from(gw), i64::from(gh));
    let index = |x: i64, y: i64| (y * w + x) as usize;
    let band_cell = |x: i64, y: i64| {
        if x < 0 || y < 0 || x >= w || y >= h {
            return false;
        }
        let i = index(x, y);
        !blocked[i]
            && !settled[i]
            && bright[i].is_some_and(|b| {
                let r = b / levels[i].max(f64::MIN_POSITIVE);
                (BAND.0..=BAND.1).contains(&r)
            })
    };
    let unlit = |step: (i64, i64)| {
        suns.iter()
            .all(|s| s.0 * step.0 as f64 + s.1 * step.1 as f64 >= BAND_SUN)
    };
    // Rows (the band a row nearer the nadir), then columns.
    for rows in [true, false] {
        let (lines, along) = if rows { (h, w) } else { (w, h) };
        for a in 0..lines {
            let cell = |b: i64| if rows { (b, a) } else { (a, b) };
            let (sx, sy) = nadir_side(cell(0).0, cell(0).1);
            let step = if rows {
                (0, i64::from(sy))
            } else {
                (i64::from(sx), 0)
            };
            if step == (0, 0) || !unlit(step) {
                continue;
            }
            let mut b = 0;
            while b < along {
                let start = b;
                while b < along && {
                    let (x, y) = cell(b);
                    blocked[index(x, y)] && !settled[index(x, y)]
                } {
                    b += 1;
                }
                let run = (start..b).map(cell);
                if (b - start) as usize >= BAND_RUN
                    && run.clone().all(|(x, y)| band_cell(x + step.0, y + step.1))
                {
                    return Some((cell(start), step));
                }
                b += 1;
            }
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::aerial::colour::Class;
    use image::Rgb;

    /// A run of three blocked cells (row 1) with a band a little darker than the lit floor on
    /// its side toward the nadir (row 2): refused without a sun, and with a sun that casts
    /// shadows across the band's direction; not with a sun that casts the run's shadow over
    /// the band, nor when the band is lit floor or shadow-dark, nor when the run is one cell,
    /// nor when the operator settled a cell of the band.
    #[test]
    fn a_run_whose_cells_toward_the_nadir_show_a_band_may_stand_there() {
        let (w, h) = (6u32, 5u32);
        let mut blocked = vec![false; 30];
        for x in 1..4 {
            blocked[w as usize + x] = true;
        }
        let levels = vec![1.0; 30];
        let bright_with = |band: f64| -> Vec<Option<f64>> {
            (0..30)
                .map(|i| {
                    if blocked[i] {
                        None
                    } else if i / 6 == 2 && (1..4).contains(&(i % 6)) {
                        Some(band)
                    } else {
                        Some(1.0)
                    }
                })
                .collect()
        };
        // The nadir below the floor: every cell has it beyond, along y.
        let side = |_: i64, _: i64| (0, 1);
        let none = vec![false; 30];
        let run = |bright: &[Option<f64>], settled: &[bool], suns: &[(f64, f64)]| {
            shifted_run(&blocked, settled, bright, &levels, (w, h), side, suns)
        };
        let face = bright_with(0.81);
        assert_eq!(run(&face, &none, &[]), Some(((1, 1), (0, 1))));
        // A sun from the right: shadows fall left, not over the band.
        assert_eq!(run(&face, &none, &[(1.0, 0.0)]), Some(((1, 1), (0, 1))));
        // A sun from above (toward −y): the run's shadow falls over the band.
        assert_eq!(run(&face, &none, &[(0.0, -1.0)]), None);
        assert_eq!(run(&bright_with(1.0), &none, &[]), None);
        assert_eq!(run(&bright_with(0.55), &none, &[]), None);
        let mut settled = none.clone();
        settled[2 * 6 + 2] = true;
        assert_eq!(run(&face, &settled, &[]), None);
        // One cell of the band lit: not a face across the run.
        let mut partly = face.clone();
        partly[2 * 6 + 3] = Some(1.0);
        assert_eq!(run(&partly, &none, &[]), None);
        // A run of one cell.
        let mut one = blocked.clone();
        one[w as usize + 2] = false;
        one[w as usize + 3] = false;
        assert_eq!(
            shifted_run(&one, &none, &face, &levels, (w, h), side, &[]),
            None
        );
    }

    /// A floor of 10 × 4 cells of 10 px seen straight down; along row 1, the cover of a run
    /// from u = 2 (the base's near edge) to `end`: a face of shade `face` up to `face_end`,
    /// then a top of shade 160, on floor of shade 120.
    fn scene(face_end: f64, end: f64, face: u8) -> (RgbImage, Vec<u8>, Homography, Homography) {
        let f2i = Homography::floor_to_image(
            10.0,
            4.0,
            [(0.0, 0.0), (100.0, 0.0), (100.0, 40.0), (0.0, 40.0)],
        )
        .unwrap();
        let i2f = f2i.inverse().unwrap();
        let mut img = RgbImage::from_pixel(100, 40, Rgb([120, 120, 120]));
        let mut classes = vec![Class::Floor as u8; 100 * 40];
        for y in 10..20u32 {
            for x in 0..100u32 {
                let u = (f64::from(x) + 0.5) / 10.0;
                if (2.0..end).contains(&u) {
                    let shade = if u < face_end { face } else { 160 };
                    img.put_pixel(x, y, Rgb([shade; 3]));
                    classes[(y * 100 + x) as usize] = Class::Obstacle as u8;
                }
            }
        }
        (img, classes, f2i, i2f)
    }

    /// The run of cells 2–5 along row 1, the nadir 20 cells before the floor's left edge.
    const RUN: Run = Run {
        along_u: true,
        dir: 1.0,
        far: 5,
        across: 1,
        cells: 4,
        nadir: -20.0,
    };

    fn judged(face_end: f64, end: f64, face: u8, px: f64) -> Face {
        let (img, classes, f2i, i2f) = scene(face_end, end, face);
        judge(&img, &classes, (&f2i, &i2f), RUN, px)
    }

    fn shows(face_end: f64, end: f64, face: u8) -> bool {
        judged(face_end, end, face, 10.0) == Face::Own
    }

    #[test]
    fn a_short_face_shows_the_far_cell_is_the_run_s_own() {
        // k = 1.02 over a base to u = 6: the top ends at 6.52, the face is 0.44 long.
        assert!(shows(2.44, 6.52, 80));
        // A brighter face does as well.
        assert!(shows(2.44, 6.52, 220));
    }

    #[test]
    fn a_face_as_long_as_a_free_far_cell_needs_does_not() {
        // The same end from a base to u = 5: k = 1.061, a face 1.34 long.
        assert_eq!(judged(3.34, 6.52, 80, 10.0), Face::Long);
        // Past the margin, half of the 1.34 a free far cell needs (the pixels' centres read
        // the face 0.05 short).
        assert_eq!(judged(2.8, 6.52, 80, 10.0), Face::Long);
        assert!(shows(2.6, 6.52, 80));
    }

    #[test]
    fn a_face_that_cannot_be_seen_is_hidden() {
        // Of the top's shade: no face shows (it is hidden, or short).
        assert_eq!(judged(2.44, 6.52, 160, 10.0), Face::Hidden);
        // A short face too near the top's shade to show plainly (9 % darker): as if none
        // showed, since a free far cell's face would run 1.34 cells (issue #29's 23rd round;
        // before it, nothing was told).
        assert_eq!(judged(2.44, 6.52, 145, 10.0), Face::Hidden);
        // As long as a free far cell's face, that faint: a long face.
        assert_eq!(judged(3.34, 6.52, 145, 10.0), Face::Long);
        // Too short to tell from blur (0.2 cell: 2 px).
        assert_eq!(judged(2.2, 6.52, 80, 10.0), Face::Hidden);
        // The same face in cells of 5 px: 2.2 px.
        assert_eq!(judged(2.44, 6.52, 80, 10.0), Face::Own);
        assert_eq!(judged(2.44, 6.52, 80, 5.0), Face::Hidden);
        // Only where a free far cell would need a face of at least half a cell: with the nadir
        // a cell before the run and its top ending at 7.0 it would need 0.53; at 6.3, 0.34.
        let near = |end: f64| {
            let (img, classes, f2i, i2f) = scene(2.0, end, 80);
            let run = Run { nadir: 1.0, ..RUN };
            judge(&img, &classes, (&f2i, &i2f), run, 10.0)
        };
        assert_eq!(near(7.0), Face::Hidden);
        assert_eq!(near(6.3), Face::Unknown);
    }

    #[test]
    fn a_face_shows_the_light_whatever_its_length() {
        let shows_light = |face_end: f64, face: u8| {
            let (img, classes, f2i, i2f) = scene(face_end, 6.52, face);
            super::shows(&img, &classes, (&f2i, &i2f), RUN, 10.0)
        };
        // Short (the run's own far cell) or as long as a free far cell needs: plainly darker.
        assert!(shows_light(2.44, 80));
        assert!(shows_light(3.34, 80));
        assert_eq!(judged(3.34, 6.52, 80, 10.0), Face::Long);
        // Brighter, as well.
        assert!(shows_light(3.34, 220));
        // Of the top's shade, or faint: no light told.
        assert!(!shows_light(2.44, 160));
        assert!(!shows_light(3.34, 145));
    }

    #[test]
    fn a_face_is_in_its_own_shadow_when_every_sun_is_behind_it() {
        // A run pointing right: its face looks left; suns to the right, up-right, down-right.
        assert!(in_own_shadow(
            &[(1.0, 0.0), (0.8, -0.6), (0.8, 0.6)],
            (1, 0)
        ));
        // One sun beside the face (its plane) or in front of it: it may be lit.
        assert!(!in_own_shadow(&[(1.0, 0.0), (0.2, 0.98)], (1, 0)));
        assert!(!in_own_shadow(&[(-1.0, 0.0)], (1, 0)));
        // Along v: a run pointing up, suns above.
        assert!(in_own_shadow(&[(0.0, -1.0)], (0, -1)));
        assert!(!in_own_shadow(&[(0.0, 1.0)], (0, -1)));
        // No sun known (no shadows): no face is known to be dark.
        assert!(!in_own_shadow(&[], (1, 0)));
    }

    #[test]
    fn a_cover_that_ends_short_or_starts_late_decides_nothing() {
        // The top ends before the far cell's outer border less an inset: no base to u = 6,
        // however short the face.
        assert!(shows(2.38, 6.52, 80));
        assert_eq!(judged(2.38, 5.9, 80, 10.0), Face::Unknown);
        // (With the top ending at 5.9, a free far cell would need a face of 0.79, twice this
        // one; a blocked one, a base ending short of its outer border.)
        // The cover starts 0.4 cell into the run: its face is not read from its base.
        // (0.9 long from u = 2, too long for a blocked far cell; 0.45 from 2.45 would not be.)
        let (mut img, mut classes, f2i, i2f) = scene(2.9, 6.52, 80);
        assert_eq!(judge(&img, &classes, (&f2i, &i2f), RUN, 10.0), Face::Long);
        for y in 10..20u32 {
            for x in 20..24u32 {
                img.put_pixel(x, y, Rgb([120; 3]));
                classes[(y * 100 + x) as usize] = Class::Floor as u8;
            }
        }
        assert_eq!(
            judge(&img, &classes, (&f2i, &i2f), RUN, 10.0),
            Face::Unknown
        );
    }

    #[test]
    fn an_unsteady_top_decides_nothing() {
        let (mut img, classes, f2i, i2f) = scene(2.44, 6.52, 80);
        // A darker stretch on the top (another's shadow), a fifth of it.
        for y in 10..20u32 {
            for x in 40..50u32 {
                img.put_pixel(x, y, Rgb([130; 3]));
            }
        }
        assert_eq!(
            judge(&img, &classes, (&f2i, &i2f), RUN, 10.0),
            Face::Unknown
        );
    }
}
