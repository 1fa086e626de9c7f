//! Aerial views: a photograph of the floor from above (PNG or JPEG) read into a grid, robots
//! and goals (DESIGN §6, "Aerial views").
//!
//! The steps, one file each:
//! 1. the floor's place in the image: the whole image for a straight-down view, or four
//!    corners through a [`homography`], and the grid: given (W × H cells or the cell size in
//!    pixels) or found from painted [`lines`];
//! 2. every pixel's class by [`colour`] after white balance on the floor (shadows stay floor;
//!    painted lines whose colour reads as an obstacle's are set aside: [`lined`])
//!    and each cell's obstacle coverage, in one pass over the [`pixels`]; floor-coloured
//!    pixels that make a square half a cell wide brighter or more tinted than the lit floor
//!    can be are a pale shelf's ([`pale`]); a cell the window
//!    count leaves in doubt is judged on its [`cover`] in finer bins, against what the
//!    leaning tops of the obstacles next to it would cover; a blob that fills whole cells is
//!    an obstacle whatever its colour ([`shelves`]), and a colour that cannot be told inside
//!    a robot, a goal or an obstacle is part of it ([`enclosed`]); a blob that fills no cell
//!    and has a mark's colour before white balance is that mark ([`tinted`]); every free
//!    cell must look like the floor (no brighter than its texture and light allow, not tinted
//!    where lit, and no three side by side brighter or more tinted than the lit floor around
//!    them, and not mostly leaning pale: [`looks`]), and every shadow on the free floor must
//!    touch what casts it ([`shadows`]: a shelf of the floor's own colour shows by its shadow;
//!    in a lamp's pool of light a shadow is judged against the light around it) and, under one
//!    sun, lie behind it, not behind lit floor ([`shadows::Sunlit::unattached`]), and on a
//!    floor with painted lines every line between free cells must show ([`painted`]); where
//!    cells unlike the floor and a shadow nothing casts beside them, or a line hidden among
//!    them, agree, they are a shelf of the floor's colour, and the view is read again with
//!    them blocked ([`corroborated`]);
//! 3. robots and goals as [`blobs`] of their colour, sized against the typical one of their
//!    kind (the most alike blobs by count times area), each put on the cell under its centre on
//!    the floor (a robot's top leans away from the camera; its base is found); a blob of
//!    several touching is split when its area and shape tell how ([`blobs::split`]); a line of
//!    their colour, or a ragged speck, is none ([`blobs::line_like`], [`blobs::RAGGED`]).
//!
//! Whatever cannot be read with confidence is refused with the reason and the pixel, never
//! guessed: two robots touching that cannot be separated, a robot or goal on a cell border, a
//! colour between the robots' or goals' and another, a cell half covered that no leaning top
//! explains, a covered cell on the floor's far edge, or at the far end of a run of blocked
//! cells, that a leaning top may cover whole, a free cell
//! that does not look like the floor, a shadow that nothing casts (or that lies behind lit
//! floor, seen from the sun), a painted line that does
//! not show between free cells, more goals than robots (unless the floor has goals to spare:
//! [`AerialConfig::spare_goals`]), a grid that does not fit the image. Cost: one pass over the pixels (O(pixels), on all cores) plus O(cells), O(pixels of
//! the covered cells), O(blob pixels) and O(pixels) for the free cells' looks, and one more
//! O(pixels) pass (on all cores) only when goals or robots are missing (`missing_faint`).
//!
//! ```
//! use mason_crew::aerial::{read_aerial, AerialConfig};
//! // A 4 × 2-cell floor, 10 px per cell: a robot in cell (0, 0), a goal in cell (3, 1).
//! let mut img = image::RgbImage::from_pixel(40, 20, image::Rgb([150, 150, 150]));
//! for (cx, cy, colour) in [(5, 5, [200, 30, 30]), (35, 15, [30, 160, 40])] {
//!     for y in cy - 3..cy + 3 {
//!         for x in cx - 3..cx + 3 {
//!             img.put_pixel(x, y, image::Rgb(colour));
//!         }
//!     }
//! }
//! let mut png = Vec::new();
//! img.write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png).unwrap();
//! let config = AerialConfig { grid: Some((4, 2)), ..AerialConfig::default() };
//! let seen = read_aerial(&png, "floor.png", &config).unwrap();
//! assert_eq!(seen.grid.xy(seen.robots[0].cell), (0, 0));
//! assert_eq!(seen.grid.xy(seen.goals[0].cell), (3, 1));
//! ```

pub mod alike;
pub mod blobs;
pub mod colour;
pub mod corroborated;
pub mod cover;
pub mod dull;
pub mod enclosed;
pub mod face;
pub mod faint;
pub mod homography;
pub mod lined;
pub mod lines;
pub mod looks;
pub mod painted;
pub mod pale;
pub mod pixels;
pub mod shadows;
pub mod shelves;
pub mod sun;
pub mod tinted;
pub mod tops;

use crate::error::{CrewError, Location};
use crate::grid::{Cell, Grid};
use colour::{Class, Classifier, Hue};
use homography::{Homography, Point};
use image::RgbImage;

/// The most pixels an aerial image may have (checked from its header before decoding).
pub const MAX_PIXELS: u64 = 40_000_000;
/// The most cells an aerial grid may have.
pub const MAX_GRID_CELLS: u64 = 1 << 20;
/// The fewest pixels a cell may be wide.
pub const MIN_CELL_PX: f64 = 3.0;
/// A straight-down view's cells are square: their width and height within this ratio.
pub const SQUARE: f64 = 1.1;
/// A robot's or goal's centre closer than this (in cells) to a cell border is refused.
pub const BORDER_MARGIN: f64 = 0.1;
/// A cell whose window is covered by an obstacle at a share in this range is refused, unless
/// a neighbour's leaning top explains the cover ([`cover`]); above it, the cell is blocked
/// under the same proviso.
pub const HALF_COVERED: (f64, f64) = (0.3, 0.7);

/// How to read an aerial view.
#[derive(Clone, Debug, PartialEq)]
pub struct AerialConfig {
    /// The floor grid, W × H cells.
    pub grid: Option<(u32, u32)>,
    /// Or the cell size in pixels (straight-down views without corners).
    pub cell_px: Option<f64>,
    /// The floor's corners in the image: top-left, top-right, bottom-right, bottom-left.
    /// Without them the floor is the whole image.
    pub corners: Option<[Point; 4]>,
    /// The robots' colour.
    pub robot_colour: Hue,
    /// The goals' colour.
    pub goal_colour: Hue,
    /// Accept more goals than robots. Off by default: in a photograph a goal without a robot
    /// may be a robot the reading lost (too small to tell from noise, hidden, or taken for a
    /// shelf of its colour), so such a view is refused unless the floor is known to have
    /// goals to spare.
    pub spare_goals: bool,
    /// Cells the operator settles as blocked, (column, row): each is read as blocked, and no
    /// refusal names it. For a cell the reader refuses (half covered, a top may cover it,
    /// unlike the floor) that the operator has looked at (`--audit --overlay` shows them).
    pub blocked_cells: Vec<(u32, u32)>,
    /// Cells the operator settles as free, likewise.
    pub free_cells: Vec<(u32, u32)>,
}

impl Default for AerialConfig {
    fn default() -> Self {
        AerialConfig {
            grid: None,
            cell_px: None,
            corners: None,
            robot_colour: Hue::RED,
            goal_colour: Hue::GREEN,
            spare_goals: false,
            blocked_cells: Vec::new(),
            free_cells: Vec::new(),
        }
    }
}

/// Where the grid came from.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum GridSource {
    /// `--grid W×H`.
    Given,
    /// `--cell-px N`.
    CellPx,
    /// Lines painted on the floor.
    Lines,
}

/// A robot or goal as read.
#[derive(Clone, Debug, PartialEq)]
pub struct Mark {
    /// The cell under its centre.
    pub cell: Cell,
    /// Its centre on the floor, in cells.
    pub floor: Point,
    /// Its blob's centroid in the image, in pixels.
    pub pixel: Point,
    /// Its blob's size in pixels.
    pub area: usize,
    /// 0–1: how far its centre is from the cell's border (1: at least a quarter cell) times
    /// how close its size is to the median of its kind.
    pub confidence: f64,
}

/// What an aerial view shows.
#[derive(Clone, Debug)]
pub struct AerialReading {
    /// The floor grid, with its blocked cells.
    pub grid: Grid,
    /// The robots, in row-major order of their blobs (robots split from one blob of several
    /// touching follow the others).
    pub robots: Vec<Mark>,
    /// The goals, likewise.
    pub goals: Vec<Mark>,
    /// Mean cell size in the image, in pixels.
    pub cell_px: f64,
    /// Where the grid came from.
    pub grid_source: GridSource,
    /// The floor's corners in the image (TL, TR, BR, BL).
    pub corners: [Point; 4],
    /// Floor (cells) → image (pixels).
    pub floor_to_image: Homography,
    /// The image's size in pixels.
    pub image_size: (u32, u32),
    /// The cells the operator settled ([`AerialConfig::blocked_cells`] and
    /// [`AerialConfig::free_cells`]), each with whether it is blocked, row-major.
    pub settled: Vec<(Cell, bool)>,
    /// Cells read as blocked by a shelf of the floor's colour: unlike the floor, and with a
    /// shadow that nothing else casts beside them or a painted line hidden between them
    /// ([`corroborated`]), row-major.
    pub floor_tops: Vec<Cell>,
    /// Half-covered cells read as free because a robot or a goal stands on them (see
    /// `under_marks`), row-major.
    pub under_marks: Vec<Cell>,
    /// The white balance was the cells' middles' (their painted lines tint the whole floor's
    /// colour, and the view balanced on the whole floor was refused; see `read`), not the
    /// whole floor's.
    pub balanced_on_middles: bool,
}

impl AerialReading {
    /// The robots' cells.
    pub fn robot_cells(&self) -> Vec<Cell> {
        self.robots.iter().map(|m| m.cell).collect()
    }

    /// The goals' cells.
    pub fn goal_cells(&self) -> Vec<Cell> {
        self.goals.iter().map(|m| m.cell).collect()
    }
}

/// Each cell's state as the operator settles it ([`AerialConfig::blocked_cells`],
/// [`AerialConfig::free_cells`]), row-major; `None` where the reader decides. A cell outside
/// the grid, or given both blocked and free, is refused.
fn settled_cells(
    config: &AerialConfig,
    (gw, gh): (u32, u32),
    source: &str,
) -> Result<Vec<Option<bool>>, CrewError> {
    let mut settled = vec![None; gw as usize * gh as usize];
    for (list, blocked, flag) in [
        (&config.blocked_cells, true, "blocked"),
        (&config.free_cells, false, "free"),
    ] {
        for &(x, y) in list {
            if x >= gw || y >= gh {
                return Err(whole(
                    source,
                    format!("cell ({x}, {y}), settled as {flag}, lies outside the {gw}×{gh} grid (columns 0–{}, rows 0–{})", gw.saturating_sub(1), gh.saturating_sub(1)),
                ));
            }
            let cell = &mut settled[y as usize * gw as usize + x as usize];
            if *cell == Some(!blocked) {
                return Err(whole(
                    source,
                    format!("cell ({x}, {y}) is settled both as blocked and as free"),
                ));
            }
            *cell = Some(blocked);
        }
    }
    Ok(settled)
}

/// A failure at a pixel.
fn at_pixel(source: &str, (x, y): Point, reason: impl Into<String>) -> CrewError {
    let clamp = |v: f64| v.max(0.0).min(f64::from(u32::MAX)) as u32;
    CrewError::new(source, Location::Pixel(clamp(x), clamp(y)), reason)
}

fn whole(source: &str, reason: impl Into<String>) -> CrewError {
    CrewError::new(source, Location::Whole, reason)
}

/// Decodes a PNG or a JPEG to 8-bit RGB, the size checked from the header first.
pub fn decode(bytes: &[u8], source: &str, max_pixels: u64) -> Result<RgbImage, CrewError> {
    let too_large = |w: u32, h: u32| {
        whole(
            source,
            format!(
                "the image is {w}×{h}, more than the {max_pixels} pixels an aerial view may have (mason_crew::aerial::MAX_PIXELS)"
            ),
        )
    };
    let rgb = if bytes.starts_with(&[0x89, b'P', b'N', b'G']) {
        mason_wall::decode_png_rgb(bytes, max_pixels).map_err(|e| match e {
            mason_wall::PngDecodeError::TooLarge { width, height } => too_large(width, height),
            mason_wall::PngDecodeError::Malformed(r) => {
                whole(source, format!("cannot decode the PNG: {r}"))
            }
        })?
    } else if bytes.starts_with(&[0xFF, 0xD8, 0xFF]) {
        let reader = || {
            image::ImageReader::with_format(std::io::Cursor::new(bytes), image::ImageFormat::Jpeg)
        };
        let (w, h) = reader()
            .into_dimensions()
            .map_err(|e| whole(source, format!("cannot decode the JPEG: {e}")))?;
        if u64::from(w) * u64::from(h) > max_pixels {
            return Err(too_large(w, h));
        }
        let mut r = reader();
        let mut limits = image::Limits::default();
        limits.max_image_width = Some(w);
        limits.max_image_height = Some(h);
        limits.max_alloc = Some(max_pixels * 8);
        r.limits(limits);
        r.decode()
            .map_err(|e| whole(source, format!("cannot decode the JPEG: {e}")))?
            .into_rgb8()
    } else {
        return Err(whole(
            source,
            "cannot decode the image: not a PNG or a JPEG (the file starts with neither's signature)",
        ));
    };
    if rgb.width() == 0 || rgb.height() == 0 {
        return Err(whole(source, "the image is empty"));
    }
    Ok(rgb)
}

/// Whether the image is a digitised map (one pixel per cell) rather than a photograph: at most
/// 16 distinct colours.
pub fn is_pixel_map(img: &RgbImage) -> bool {
    let mut seen: Vec<[u8; 3]> = Vec::with_capacity(17);
    for p in img.pixels() {
        if !seen.contains(&p.0) {
            if seen.len() == 16 {
                return false;
            }
            seen.push(p.0);
        }
    }
    true
}

/// Which floor pixels give the white balance: the whole floor's, or the cells' middles' alone
/// (without painted lines; see [`read`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Balance {
    Whole,
    Middles,
}

/// The middle of a cell along each axis that [`Balance::Middles`] samples: painted lines lie
/// along the borders.
const MIDDLES: (f64, f64) = (0.2, 0.8);

/// The floor's colour: each channel's median over every 4th pixel of every 4th row inside the
/// floor, each row of samples shifted by one pixel from the one before (so that the samples
/// do not fall on painted lines every 4th pixel apart, whatever the cell size): over the
/// whole floor, and over the cells' middles alone ([`MIDDLES`]), that one scaled to the whole
/// floor's brightness (the sum of its channels: the reader's levels of light are the whole
/// floor's). `None` for the middles when none is sampled.
fn floor_colours(
    img: &RgbImage,
    image_to_floor: &Homography,
    (w, h): (f64, f64),
) -> ([f64; 3], Option<[f64; 3]>) {
    let mut chans: [Vec<u8>; 3] = Default::default();
    let mut mids: [Vec<u8>; 3] = Default::default();
    for y in (0..img.height()).step_by(4) {
        for x in ((y / 4) % 4..img.width()).step_by(4) {
            let Some((u, v)) = image_to_floor
                .apply((f64::from(x) + 0.5, f64::from(y) + 0.5))
                .filter(|&(u, v)| u >= 0.0 && v >= 0.0 && u < w && v < h)
            else {
                continue;
            };
            let p = img.get_pixel(x, y).0;
            let middle = (MIDDLES.0..MIDDLES.1).contains(&u.fract())
                && (MIDDLES.0..MIDDLES.1).contains(&v.fract());
            for c in 0..3 {
                chans[c].push(p[c]);
                if middle {
                    mids[c].push(p[c]);
                }
            }
        }
    }
    let median = |mut v: Vec<u8>| {
        if v.is_empty() {
            return 128.0;
        }
        let mid = v.len() / 2;
        f64::from(*v.select_nth_unstable(mid).1)
    };
    let all = chans.map(median);
    let middles = (!mids[0].is_empty())
        .then(|| mids.map(median))
        .and_then(|m| {
            let (sa, sm) = (all.iter().sum::<f64>(), m.iter().sum::<f64>());
            (sm > 0.0).then(|| m.map(|c| c * sa / sm))
        });
    (all, middles)
}

/// How far (the largest share of a channel) the cells' middles' colour lies from the whole
/// floor's for [`read`] to try it: painted lines of another colour than the floor's tint the
/// whole floor's median.
pub const MIDDLES_APART: f64 = 0.03;

/// Whether the cells' middles' colour lies [`MIDDLES_APART`] or more from the whole floor's.
fn middles_apart(all: [f64; 3], middles: [f64; 3]) -> bool {
    (0..3)
        .map(|c| (middles[c] / all[c].max(1.0) - 1.0).abs())
        .fold(0.0, f64::max)
        >= MIDDLES_APART
}

/// The image's corners as the floor's.
fn image_corners(img: &RgbImage) -> [Point; 4] {
    let (w, h) = (f64::from(img.width()), f64::from(img.height()));
    [(0.0, 0.0), (w, 0.0), (w, h), (0.0, h)]
}

fn check_corners(corners: &[Point; 4], img: &RgbImage, source: &str) -> Result<(), CrewError> {
    let (w, h) = (f64::from(img.width()), f64::from(img.height()));
    let names = ["top-left", "top-right", "bottom-right", "bottom-left"];
    for (i, &(x, y)) in corners.iter().enumerate() {
        if !(x.is_finite() && y.is_finite()) || x < -1.0 || y < -1.0 || x > w + 1.0 || y > h + 1.0 {
            return Err(whole(
                source,
                format!(
                    "the {} corner ({x}, {y}) is outside the {}×{} image",
                    names[i],
                    img.width(),
                    img.height()
                ),
            ));
        }
    }
    // Convex, and clockwise on screen (y down): every turn has the same positive sign.
    for i in 0..4 {
        let (a, b, c) = (corners[i], corners[(i + 1) % 4], corners[(i + 2) % 4]);
        let cross = (b.0 - a.0) * (c.1 - b.1) - (b.1 - a.1) * (c.0 - b.0);
        if cross <= 0.0 {
            return Err(whole(
                source,
                format!(
                    "the corners do not make a convex floor in the order top-left, top-right, bottom-right, bottom-left (turn at the {} corner)",
                    names[(i + 1) % 4]
                ),
            ));
        }
    }
    Ok(())
}

/// The floor: its grid, its corners in the image and where the grid came from.
type Floor = ((u32, u32), [Point; 4], GridSource);

/// The grid and the floor's corners from the configuration, or from painted lines.
fn grid_and_floor(img: &RgbImage, config: &AerialConfig, source: &str) -> Result<Floor, CrewError> {
    let (iw, ih) = (f64::from(img.width()), f64::from(img.height()));
    let corners = match config.corners {
        Some(c) => {
            check_corners(&c, img, source)?;
            c
        }
        None => image_corners(img),
    };
    let (grid, from) = match (config.grid, config.cell_px) {
        (Some(_), Some(_)) => {
            return Err(whole(source, "give --grid or --cell-px, not both"));
        }
        (Some(g), None) => (g, GridSource::Given),
        (None, Some(px)) => {
            if config.corners.is_some() {
                return Err(whole(
                    source,
                    "--cell-px is for straight-down views filling the image; with --corners give --grid W×H",
                ));
            }
            if !(px.is_finite() && px >= MIN_CELL_PX) {
                return Err(whole(
                    source,
                    format!("--cell-px {px}: a cell is at least {MIN_CELL_PX} pixels"),
                ));
            }
            let fit = |side: f64, name: &str| -> Result<u32, CrewError> {
                let n = (side / px).round();
                if n < 1.0 || (side - n * px).abs() > 0.25 * px {
                    return Err(whole(
                        source,
                        format!(
                            "the grid does not fit the image: its {name} of {side} px is {:.2} cells of {px} px, not a whole number (within a quarter cell)",
                            side / px
                        ),
                    ));
                }
                Ok(n as u32)
            };
            ((fit(iw, "width")?, fit(ih, "height")?), GridSource::CellPx)
        }
        (None, None) => {
            let found = find_grid_lines(img, &corners, config.corners.is_none()).ok_or_else(|| {
                whole(
                    source,
                    "no grid: give --grid W×H or --cell-px N (no lines painted on the floor were found)",
                )
            })?;
            (found, GridSource::Lines)
        }
    };
    let (gw, gh) = grid;
    if gw == 0 || gh == 0 || u64::from(gw) * u64::from(gh) > MAX_GRID_CELLS {
        return Err(whole(
            source,
            format!("a grid of {gw}×{gh} cells: each side at least 1 and at most {MAX_GRID_CELLS} cells in all"),
        ));
    }
    if config.corners.is_none() {
        let (cw, ch) = (iw / f64::from(gw), ih / f64::from(gh));
        if cw < MIN_CELL_PX || ch < MIN_CELL_PX || (cw / ch - 1.0).abs() > SQUARE - 1.0 {
            return Err(whole(
                source,
                format!(
                    "the grid {gw}×{gh} does not fit the {}×{} image: its cells would be {cw:.1}×{ch:.1} px (square cells of at least {MIN_CELL_PX} px, within 10 %; for a tilted camera give --corners)",
                    img.width(),
                    img.height()
                ),
            ));
        }
    } else {
        let side = |a: Point, b: Point| ((a.0 - b.0).powi(2) + (a.1 - b.1).powi(2)).sqrt();
        let shortest = [
            side(corners[0], corners[1]) / f64::from(gw),
            side(corners[3], corners[2]) / f64::from(gw),
            side(corners[0], corners[3]) / f64::from(gh),
            side(corners[1], corners[2]) / f64::from(gh),
        ]
        .into_iter()
        .fold(f64::INFINITY, f64::min);
        if shortest < MIN_CELL_PX {
            return Err(whole(
                source,
                format!("the grid {gw}×{gh} does not fit between the corners: some cells would be {shortest:.1} px wide, fewer than {MIN_CELL_PX}"),
            ));
        }
    }
    Ok(((gw, gh), corners, from))
}

/// The grid from painted lines, both ways, or `None`; its cells square when the view is
/// `straight_down` (no corners given: the floor fills the image).
fn find_grid_lines(
    img: &RgbImage,
    corners: &[Point; 4],
    straight_down: bool,
) -> Option<(u32, u32)> {
    // The floor as a unit square.
    let unit = Homography::floor_to_image(1.0, 1.0, *corners)?;
    let side = |a: Point, b: Point| ((a.0 - b.0).powi(2) + (a.1 - b.1).powi(2)).sqrt();
    let across = side(corners[0], corners[1]).max(side(corners[3], corners[2]));
    let down = side(corners[0], corners[3]).max(side(corners[1], corners[2]));
    let luma = |p: Point| -> Option<f64> {
        let (x, y) = unit.apply(p)?;
        if x < 0.0 || y < 0.0 {
            return None;
        }
        let (xi, yi) = (x as u32, y as u32);
        (xi < img.width() && yi < img.height()).then(|| {
            let [r, g, b] = img.get_pixel(xi, yi).0.map(f64::from);
            0.299 * r + 0.587 * g + 0.114 * b
        })
    };
    let profile = |n: usize, slices: usize, along_u: bool| -> Vec<f64> {
        (0..n)
            .map(|i| {
                let t = (i as f64 + 0.5) / n as f64;
                let mut vals: Vec<f64> = (0..slices)
                    .filter_map(|j| {
                        let s = (j as f64 + 0.5) / slices as f64;
                        luma(if along_u { (t, s) } else { (s, t) })
                    })
                    .collect();
                if vals.is_empty() {
                    return 0.0;
                }
                let mid = vals.len() / 2;
                *vals.select_nth_unstable_by(mid, f64::total_cmp).1
            })
            .collect()
    };
    let nu = (across.round() as usize).clamp(1, 4096);
    let nv = (down.round() as usize).clamp(1, 4096);
    let (pu, pv) = (
        profile(nu, nv.min(301), true),
        profile(nv, nu.min(301), false),
    );
    let (w, _, dark_u) = lines::cells_along(&pu)?;
    let (h, _, dark_v) = lines::cells_along(&pv)?;
    // Cells are square: an axis whose cells come out a whole number of times the other's
    // (its lines found only every few cells) takes the other's size when its own lines show
    // there.
    if !straight_down {
        return Some((w, h));
    }
    let (cell_u, cell_v) = (across / f64::from(w), down / f64::from(h));
    if cell_u > SQUARE * cell_v {
        let n = (across / cell_v).round() as u32;
        if lines::shows(&pu, w, n, dark_u) {
            return Some((n, h));
        }
    } else if cell_v > SQUARE * cell_u {
        let n = (down / cell_u).round() as u32;
        if lines::shows(&pv, h, n, dark_v) {
            return Some((w, n));
        }
    }
    Some((w, h))
}

/// Reads an aerial view.
pub fn read_aerial(
    bytes: &[u8],
    source: &str,
    config: &AerialConfig,
) -> Result<AerialReading, CrewError> {
    let img = decode(bytes, source, MAX_PIXELS)?;
    read_aerial_image(&img, source, config)
}

/// Reads an aerial view already decoded.
pub fn read_aerial_image(
    img: &RgbImage,
    source: &str,
    config: &AerialConfig,
) -> Result<AerialReading, CrewError> {
    read(img, source, config, false).map(|audited| audited.reading)
}

/// A reading made past its cells' refusals ([`audit_aerial`]).
#[derive(Clone, Debug)]
pub struct Audited {
    /// The reading, each doubtful cell decided as the refusal's check found it before doubting
    /// it (a half-covered cell, or one a top may cover almost whole, blocked; a covered cell a
    /// top may cover, blocked; a free cell unlike the floor, free).
    pub reading: AerialReading,
    /// Every cell's refusal, in the order the reader meets them (the first is the one
    /// [`read_aerial`] gives).
    pub doubts: Vec<CrewError>,
}

/// Reads an aerial view past every refusal about a cell (a half-covered cell, a cell a top may
/// cover, a free cell unlike the floor, free cells side by side unlike the floor around them,
/// a shadow no obstacle casts, a painted line that does not show between free cells), listing
/// them all: for seeing everything that stops a view at
/// once, and what the reading would be without the checks (the truth of rendered scenes
/// shows which of them guard a cell the reading would get wrong). Still refused, as by
/// [`read_aerial`]: an image that cannot be read, a grid that does not fit, and a robot's or
/// a goal's reason (touching, on a border, too small, fewer or spare goals, a colour it cannot
/// tell).
pub fn audit_aerial(
    bytes: &[u8],
    source: &str,
    config: &AerialConfig,
) -> Result<Audited, CrewError> {
    let img = decode(bytes, source, MAX_PIXELS)?;
    audit_aerial_image(&img, source, config)
}

/// [`audit_aerial`] on an image already decoded.
pub fn audit_aerial_image(
    img: &RgbImage,
    source: &str,
    config: &AerialConfig,
) -> Result<Audited, CrewError> {
    read(img, source, config, true)
}

/// The reader: with `audit`, past the cells' refusals (see [`audit_aerial`]).
///
/// The white balance is the whole floor's. On a floor whose painted lines tint that (the
/// cells' middles' colour [`MIDDLES_APART`] or more from it), a view refused so, or audited
/// with refusals, is read again balanced on the cells' middles, and that reading is taken
/// when it refuses nothing (since issue #29's twenty-eighth round: white lines on an olive or
/// navy floor turned its cells' floor yellowish or bluish, half covered or tinted).
fn read(
    img: &RgbImage,
    source: &str,
    config: &AerialConfig,
    audit: bool,
) -> Result<Audited, CrewError> {
    let first = read_inner(img, source, config, audit, true, Balance::Whole);
    let clean = |r: &Result<(Audited, f64), CrewError>| {
        r.as_ref()
            .is_ok_and(|(audited, _)| audited.doubts.is_empty())
    };
    if !clean(&first) && lines_tint(img, config, source) {
        let second = read_inner(img, source, config, audit, true, Balance::Middles);
        if clean(&second) {
            return second.map(|(audited, _)| audited);
        }
    }
    first.map(|(audited, _)| audited)
}

/// Whether the view's painted lines tint the whole floor's colour ([`middles_apart`]).
fn lines_tint(img: &RgbImage, config: &AerialConfig, source: &str) -> bool {
    let Ok(((gw, gh), corners, _)) = grid_and_floor(img, config, source) else {
        return false;
    };
    let (fw, fh) = (f64::from(gw), f64::from(gh));
    let Some(image_to_floor) =
        Homography::floor_to_image(fw, fh, corners).and_then(|h| h.inverse())
    else {
        return false;
    };
    match floor_colours(img, &image_to_floor, (fw, fh)) {
        (all, Some(middles)) => middles_apart(all, middles),
        _ => false,
    }
}

/// The reader; with `infer`, the shelves of the floor's colour that two kinds of evidence
/// tell ([`corroborated`]) are proposed and the view read again with them blocked.
fn read_inner(
    img: &RgbImage,
    source: &str,
    config: &AerialConfig,
    audit: bool,
    infer: bool,
    balance: Balance,
) -> Result<(Audited, f64), CrewError> {
    let mut doubts: Vec<CrewError> = Vec::new();
    // A cell's refusal: at once, or, auditing, listed.
    macro_rules! doubt {
        ($error:expr) => {{
            let error = $error;
            if !audit {
                return Err(error);
            }
            doubts.push(error);
        }};
    }
    if config.robot_colour.distance(config.goal_colour.0) < 60.0 {
        return Err(whole(
            source,
            format!(
                "the robots' colour (hue {:.0}°) and the goals' (hue {:.0}°) are too close to tell apart (at least 60° apart)",
                config.robot_colour.0, config.goal_colour.0
            ),
        ));
    }
    let ((gw, gh), corners, grid_source) = grid_and_floor(img, config, source)?;
    let (fw, fh) = (f64::from(gw), f64::from(gh));
    let floor_to_image = Homography::floor_to_image(fw, fh, corners).ok_or_else(|| {
        whole(
            source,
            "the corners do not define a floor (three on a line)",
        )
    })?;
    let image_to_floor = floor_to_image
        .inverse()
        .ok_or_else(|| whole(source, "the corners do not define a floor (singular)"))?;
    let floor = match floor_colours(img, &image_to_floor, (fw, fh)) {
        (_, Some(middles)) if balance == Balance::Middles => middles,
        (all, _) => all,
    };
    let classifier = Classifier::new(floor, config.robot_colour, config.goal_colour);
    let nadir = floor_to_image.nadir((f64::from(img.width()) / 2.0, f64::from(img.height()) / 2.0));
    let px = cell_size_px(&floor_to_image, (fw, fh));
    let radius = pixels::denoise_radius(px);
    // A lit floor-coloured pixel leans pale from a saturation above the floor's own noise; one
    // whose tint the view's shadows' light explains is told apart (`pale::PALE_SHADE`).
    // (The samples are let go here, before the passes over the pixels.)
    let classifier = {
        let mut samples =
            pixels::floor_samples(img, &classifier, &image_to_floor, (gw, gh), radius);
        let sampled = samples.lit_saturations.len() + samples.shaded.len();
        classifier
            .with_lean_tint(pale::lean_tint(&mut samples.lit_saturations))
            .with_shade(pale::shade(&mut samples.shaded, sampled))
    };
    let mut classes = pixels::classify(img, &classifier, &image_to_floor, (gw, gh), radius);
    let width = img.width() as usize;
    let maps = (&floor_to_image, &image_to_floor);
    lined::settle(img, &mut classes, width, maps, (gw, gh), px);
    let leaned = pale::settle(&mut classes, img, &classifier, pale::square_px(px));
    tinted::recover(&mut classes, img, &classifier, maps, (gw, gh));
    dull::settle(&mut classes, img, &classifier, &image_to_floor);
    let hue_of = |i: usize| {
        let p = img.get_pixel((i % width) as u32, (i / width) as u32).0;
        colour::hue_saturation(classifier.balanced(p)).0
    };
    let absorbed = shelves::absorb(&mut classes, width, maps, (gw, gh), &hue_of);
    enclosed::settle(&mut classes, width);
    alike::settle(&mut classes, img, &classifier);
    let mut faint_tops = faint::settle(
        &mut classes,
        &leaned,
        width,
        maps,
        (gw, gh),
        faint::Window::Middle,
    );
    // Then tops whose face fills their cells' middles, judged away from the nadir.
    if let Some(n) = nadir {
        faint_tops.extend(faint::settle(
            &mut classes,
            &leaned,
            width,
            maps,
            (gw, gh),
            faint::Window::Far(n),
        ));
    }
    pixels::set_aside_specks(&mut classes, width, px);
    let coverage = pixels::coverage(&classes, width, &image_to_floor, (gw, gh), nadir);
    let cell_centre_px = |i: usize| {
        floor_to_image
            .apply((
                (i % gw as usize) as f64 + 0.5,
                (i / gw as usize) as f64 + 0.5,
            ))
            .unwrap_or((0.0, 0.0))
    };
    let cells = gw as usize * gh as usize;
    // The cells the operator settles: read as given, never refused.
    let settled = settled_cells(config, (gw, gh), source)?;
    let is_settled: Vec<bool> = settled.iter().map(Option::is_some).collect();
    let mut shares = Vec::with_capacity(cells);
    for i in 0..cells {
        let Some(share) = coverage.share(i) else {
            return Err(at_pixel(
                source,
                cell_centre_px(i),
                format!(
                    "cell ({}, {}) shows no pixel of floor that can be judged",
                    i % gw as usize,
                    i / gw as usize
                ),
            ));
        };
        shares.push(share);
    }
    let index = |x: i64, y: i64| {
        (x >= 0 && y >= 0 && x < i64::from(gw) && y < i64::from(gh))
            .then(|| (y * i64::from(gw) + x) as usize)
    };
    // A cell's cover in bins on the floor (see `cover`).
    let cell_bins =
        |xy: (u32, u32)| cover::bins(&classes, width, &floor_to_image, &image_to_floor, xy);
    // Half-covered cells whose cover is their own top leaning away from the nadir, their face
    // read as floor (see `tops::faced`), on all cores.
    let faced: Vec<bool> = {
        use rayon::prelude::*;
        let share_at = |x: i64, y: i64| index(x, y).map(|k| shares[k]);
        (0..cells)
            .into_par_iter()
            .map(|i| {
                let Some(n) = nadir else { return false };
                if !(HALF_COVERED.0..HALF_COVERED.1).contains(&shares[i]) {
                    return false;
                }
                let (x, y) = ((i % gw as usize) as i64, (i / gw as usize) as i64);
                let side = nadir_side((x, y), n);
                let (sx, sy) = (i64::from(side.0), i64::from(side.1));
                let clear =
                    |dx: i64, dy: i64| share_at(x + dx, y + dy).is_none_or(|s| s <= HALF_COVERED.0);
                // Along x: the neighbours toward the nadir, beside the cell and diagonally, are
                // not covered, and the one beyond (away from the nadir) not mostly: a cell
                // beyond read blocked may be the cell's own top leaning a cell or more, its
                // face read as floor (L0028's row of shelves, read a row too far past its
                // refusals).
                let partial =
                    |dx: i64, dy: i64| share_at(x + dx, y + dy).is_none_or(|s| s < HALF_COVERED.1);
                // Along the other axis, a neighbour toward the nadir mostly covered may lean its
                // top over the cell's far side along this one, diagonally (`across`).
                let clear_x =
                    sx != 0 && clear(sx, 0) && clear(sx, -1) && clear(sx, 1) && partial(-sx, 0);
                let clear_y =
                    sy != 0 && clear(0, sy) && clear(-1, sy) && clear(1, sy) && partial(0, -sy);
                let across = [sy != 0 && !partial(0, sy), sx != 0 && !partial(sx, 0)];
                (clear_x || clear_y)
                    && tops::faced(
                        &cell_bins((x as u32, y as u32)),
                        side,
                        [clear_x, clear_y],
                        across,
                    )
            })
            .collect()
    };
    // Cells whose window is mostly covered, and those whose own top covers them (`faced`);
    // the cells that a neighbour's leaning top from them explains are free (see `cover`).
    let sure: Vec<bool> = shares
        .iter()
        .zip(&faced)
        .map(|(&s, &f)| s >= HALF_COVERED.1 || f)
        .collect();
    let is_sure = |x: i64, y: i64| index(x, y).is_some_and(|k| sure[k]);
    // The fits, on all cores (each cell's alone: the result does not depend on the cores).
    let fits: Vec<Option<cover::Fit>> = {
        use rayon::prelude::*;
        (0..cells)
            .into_par_iter()
            .map(|i| {
                let n = nadir?;
                if shares[i] <= HALF_COVERED.0 {
                    return None;
                }
                let (x, y) = ((i % gw as usize) as u32, (i / gw as usize) as u32);
                // A mostly covered cell can only be free under a top leaning from a blocked
                // neighbour on its side toward the nadir (or level with it).
                let (xi, yi) = (i64::from(x), i64::from(y));
                let leaned_on = neighbours_toward(nadir_side((xi, yi), n))
                    .any(|(dx, dy)| is_sure(xi + dx, yi + dy));
                if shares[i] >= HALF_COVERED.1 && !leaned_on {
                    return None;
                }
                let bins = cell_bins((x, y));
                cover::fit(&bins, (x, y), n, &is_sure)
            })
            .collect()
    };
    // A half-covered cell is blocked when its floor-coloured pixels are a pale shade of its
    // obstacle pixels (a pale top read partly as floor), or, with no covered neighbour toward
    // the nadir (whose top could lean over it), when what covers it stands on it (a block
    // inside the cell, away from the borders toward the nadir: cartons on a pale shelf's top);
    // see `tops` and `own_top_decides`.
    let own_top = |i: usize| -> (bool, bool) {
        let Some(n) = nadir else {
            return (false, false);
        };
        let (x, y) = ((i % gw as usize) as i64, (i / gw as usize) as i64);
        let share_at = |x: i64, y: i64| index(x, y).map(|k| shares[k]);
        let side = nadir_side((x, y), n);
        let leaned = neighbours_toward(side)
            .any(|(dx, dy)| share_at(x + dx, y + dy).is_some_and(|s| s > HALF_COVERED.0));
        let colours = |x: i64, y: i64| {
            tops::window_colours(
                img,
                &classes,
                &classifier,
                maps,
                nadir,
                (x as u32, y as u32),
            )
        };
        let mut ring = Vec::with_capacity(8);
        let mut ring_floor = Vec::with_capacity(8);
        for dy in -1..=1 {
            for dx in -1..=1 {
                if (dx, dy) != (0, 0)
                    && share_at(x + dx, y + dy).is_some_and(|s| s <= HALF_COVERED.0)
                {
                    let around = colours(x + dx, y + dy);
                    ring.extend(around.lit_floor_saturation());
                    ring_floor.extend(around.lit_floor());
                }
            }
        }
        let own = colours(x, y);
        let top_floor = own.top_read_as_floor(&ring_floor);
        let decided = faced[i]
            || own_top_decides(
                leaned,
                || tops::standing(&cell_bins((x as u32, y as u32)), side),
                || own.pale_top(&ring),
            );
        (decided, top_floor)
    };
    let mut blocked = vec![false; cells];
    // Covered cells a neighbour's leaning top may cover almost whole.
    let mut almost: Vec<usize> = Vec::new();
    // Free cells under a long lean whose run shows no face as long (`cover::faceless_lean`).
    let mut faceless: Vec<(usize, cover::Faceless)> = Vec::new();
    // The half-covered cells that nothing above explains, with their refusals: judged once
    // the robots and goals are read (a cell one stands on is free; see `under_marks`).
    let mut half_covered: Vec<(usize, CrewError)> = Vec::new();
    for (i, b) in blocked.iter_mut().enumerate() {
        if let Some(given) = settled[i] {
            *b = given;
            continue;
        }
        let share = shares[i];
        if share <= HALF_COVERED.0 {
            continue;
        }
        let (x, y) = ((i % gw as usize) as u32, (i / gw as usize) as u32);
        let leaning = fits[i];
        if let Some(fit) = leaning.filter(|f| f.free()) {
            // Through corners (as for a run's far cell, below), a long lean needs its face:
            // judged once the suns are known (below).
            if let (Some(n), Some(_), true) = (nadir, config.corners, fit.k > 1.0) {
                if let Some(lacking) =
                    cover::faceless_lean(img, &classes, maps, (gw, gh), &sure, n, (x, y), fit.k)
                {
                    faceless.push((i, lacking));
                }
            }
            continue;
        }
        // A half-covered cell is its obstacle's when that stands on it (`own_top`), or when
        // its window's floor pixels are a top's read as floor (`tops::Window::
        // top_read_as_floor`): then the window is covered whole, and judged as a covered cell
        // (a neighbour's top may cover it almost whole).
        let half = share < HALF_COVERED.1;
        let (own, top_floor) = if half { own_top(i) } else { (false, false) };
        if (!half || top_floor) && leaning.is_some_and(|f| f.doubtful()) {
            // Judged once every cell's cover is known, by the faces toward the nadir and the
            // shadows (below).
            almost.push(i);
        } else if half && !own && !top_floor {
            half_covered.push((
                i,
                at_pixel(
                    source,
                    cell_centre_px(i),
                    format!(
                        "cell ({x}, {y}) is {:.0} % covered by an obstacle (in the window of the cell that no neighbour leans over), and no neighbour's leaning top explains the cover: cannot tell whether it is blocked ({:.0}–{:.0} % is refused)",
                        share * 100.0,
                        HALF_COVERED.0 * 100.0,
                        HALF_COVERED.1 * 100.0
                    ),
                ),
            ));
        }
        *b = true;
    }
    // A covered cell on the floor's edge away from the nadir, behind a blocked cell: the top
    // of the obstacle there may lean over it to the edge (see `cover::lean_doubt`); likewise
    // the far cell of a run of blocked cells with a free cell beyond it, which the top of the
    // run's other cells may cover whole. Only for
    // a view through corners: in a straight-down view filling the image the lean cannot be
    // measured precisely enough on a large floor (a cell 99 cells from the nadir is under a
    // top of k = 1.01), and it would refuse nearly every shelf ending at the far edge; such a
    // view is read as before (see the README: not checked).
    // The shadow beside such a cell may still show that the obstacle's base reaches it (see
    // `shadows::Sunlit::base_reaches`): these cells are judged once the free cells' shadows are
    // known, below.
    let mut far_cells: Vec<(usize, cover::Doubt)> = Vec::new();
    if let (Some(n), Some(_)) = (nadir, config.corners) {
        for i in 0..cells {
            let (x, y) = ((i % gw as usize) as u32, (i / gw as usize) as u32);
            let edge = x == 0 || y == 0 || x + 1 == gw || y + 1 == gh;
            if !blocked[i] || is_settled[i] {
                continue;
            }
            let beyond = if edge {
                cover::Beyond::Edge
            } else {
                cover::Beyond::Free
            };
            if let Some(far) = cover::lean_doubt(
                img,
                &classes,
                width,
                maps,
                (gw, gh),
                &blocked,
                n,
                (x, y),
                beyond,
            ) {
                far_cells.push((i, far));
            }
        }
    }
    // A cell a leaning top may cover almost whole is the run's own when its face toward the
    // nadir, read as the far cell of the run behind it, is too short for a top leaning over
    // it (see `cover::face_tells`); the others are judged with the far cells, below.
    let almost: Vec<(usize, cover::Doubt)> = almost
        .into_iter()
        .filter_map(|i| {
            let (x, y) = ((i % gw as usize) as u32, (i / gw as usize) as u32);
            let no_run = cover::Doubt {
                dir: (0, 0),
                hidden_face: false,
            };
            match nadir {
                Some(n) => cover::face_tells(img, &classes, maps, (gw, gh), &blocked, n, (x, y)),
                None => Some(no_run),
            }
            .map(|d| (i, d))
        })
        .collect();
    // Every free cell must look like the floor (see `looks`): a shelf of a colour close to
    // the floor's is refused there, not read as free (after the robots' and goals' own
    // reasons to refuse, which say more). Pixels within an eighth of a cell of a mark are left
    // out (its blurred edge and shadow), and from the middle's look within a quarter cell:
    // blur and JPEG spread a mark's colour into the floor around it, which then leans pale
    // (C0016, N0036 and Q0012 were refused for a free cell beside a goal or a robot). The
    // shadow bins keep the eighth: with the quarter there too, the held-out S0016's shadow of a
    // pale grey shelf passed for a robot's and the shelf read as floor (issue #29's eleventh
    // round).
    let reach = |cells: f64| (px * cells).round().max(2.0) as usize;
    let near_mark = looks::mark_reach(
        &mut classes,
        width,
        &[reach(1.0 / 8.0), reach(1.0 / 4.0), reach(1.0)],
    );
    // Each cell alone, on all cores; the first odd cell in row-major order is reported, so the
    // result does not depend on the cores.
    let looks: Vec<Option<looks::Look>> = {
        use rayon::prelude::*;
        (0..cells)
            .into_par_iter()
            .map(|i| {
                (!blocked[i]).then(|| {
                    let (x, y) = ((i % gw as usize) as u32, (i / gw as usize) as u32);
                    looks::look(
                        img,
                        &classes,
                        &classifier,
                        &floor_to_image,
                        &image_to_floor,
                        nadir,
                        &near_mark,
                        &leaned,
                        (x, y),
                    )
                })
            })
            .collect()
    };
    // A floor that leans pale as a whole does not tell a pale top by it (see `looks::floor_leans`).
    let floor_leans = looks::floor_leans(&looks);
    // Every such cell (for the shelves of the floor's colour); refused, auditing, each, else the
    // first.
    let (odd_cells, mut not_floor): (Vec<usize>, Vec<CrewError>) = looks
        .iter()
        .enumerate()
        .filter_map(|(i, look)| {
            if is_settled[i] {
                return None;
            }
            let (x, y) = ((i % gw as usize) as u32, (i / gw as usize) as u32);
            look.as_ref()?.odd_in(floor_leans).map(|why| {
                (
                    i,
                    at_pixel(
                        source,
                        cell_centre_px(i),
                        format!(
                            "cell ({x}, {y}) would be free but does not look like the floor: {why}"
                        ),
                    ),
                )
            })
        })
        .unzip();
    if !audit {
        not_floor.truncate(1);
    }
    // Lit free cells side by side brighter or more tinted than the lit free floor around them
    // (see `looks::unlike_ring`): the top of a pale shelf of nearly the floor's colour.
    let bright: Vec<Option<f64>> = looks
        .iter()
        .map(|l| l.as_ref().and_then(|l| l.bright))
        .collect();
    let mut unlike_cells: Vec<usize> = Vec::new();
    let saturation: Vec<f64> = looks
        .iter()
        .map(|l| l.as_ref().map_or(0.0, |l| l.saturation))
        .collect();
    let unlike = {
        looks::unlike_ring(&bright, &saturation, (gw, gh), &is_settled).map(|(kind, r)| {
            unlike_cells.clone_from(&r.cells);
            let first = r.cells.first().copied().unwrap_or(0);
            let (x, y) = ((first % gw as usize) as u32, (first / gw as usize) as u32);
            let why = match kind {
                looks::Unlike::Brighter => format!(
                    "each at least {:.2} times as bright as the lit free floor around it (this floor's cells change at most {:.2} times from cell to cell over {} cells side by side)",
                    r.least,
                    r.limit,
                    looks::RING_CELLS
                ),
                looks::Unlike::Tinted => format!(
                    "each at least {:.3} more saturated after white balance than the lit free floor around it (floor at most {:.3} over {} cells side by side)",
                    r.least,
                    looks::RING_TINT,
                    looks::RING_CELLS
                ),
                looks::Unlike::Both => format!(
                    "each at least {:.2} times as bright as the lit free floor around it and at least {:.3} more saturated after white balance (floor seldom both over {} cells side by side)",
                    r.least,
                    looks::RING_BOTH.1,
                    looks::RING_CELLS
                ),
            };
            at_pixel(
                source,
                cell_centre_px(first),
                format!(
                    "{} cells side by side from cell ({x}, {y}) would be free but do not look like the floor: {why}: the top of a shelf of nearly the floor's colour may stand there (cells {})",
                    r.cells.len(),
                    r.cells
                        .iter()
                        .map(|&c| format!("({}, {})", c % gw as usize, c / gw as usize))
                        .collect::<Vec<_>>()
                        .join(" ")
                ),
            )
        })
    };
    let bins: Vec<Option<[shadows::Bin; shadows::BINS]>> =
        looks.iter().map(|l| l.as_ref().map(|l| l.bins)).collect();
    // Each free cell's tint that the shadows' light does not explain, and whether it is a dark
    // top's (for `corroborated`, below).
    let unexplained: Vec<Option<(f64, bool)>> = looks
        .iter()
        .map(|l| {
            l.as_ref()
                .filter(|l| l.bright.is_some())
                .map(|l| (l.unexplained, l.dark_unlike()))
        })
        .collect();
    drop(looks);
    let levels = looks::local_levels(&bright, (gw, gh));
    // The free floor's shadow bins and the sun's directions, found once for the far cells
    // and the shadows behind lit floor.
    let sunlit = shadows::Sunlit::new(&bins, &levels, (gw, gh));
    // The sun's direction told by the robots' own shadows (see `sun`), found when first
    // needed (for the shadows behind lit floor and the tops where a shadow falls, below).
    let robots_sun_found = std::cell::OnceCell::new();
    let robots_sun = || -> Option<(f64, f64)> {
        *robots_sun_found
            .get_or_init(|| sun::from_robots(&classes, img, &classifier, &image_to_floor))
    };
    // The sun's directions the view's shadows allow, found when first needed (the walk behind
    // them is not cheap, and a view without corners needs none).
    let suns_found = std::cell::OnceCell::new();
    let suns = || -> &Vec<(f64, f64)> {
        suns_found.get_or_init(|| {
            sunlit
                .as_ref()
                .map(shadows::Sunlit::suns)
                .unwrap_or_default()
        })
    };
    // A run of blocked cells whose cells toward the nadir show a band a little darker than the
    // lit floor, which no sun of the view's shadows casts: its base may be there, under a top
    // leaning a whole cell (see `face::shifted_run`). Only for a view through corners, as for
    // the far cells above: straight down, a top leans a whole cell only far from the nadir on
    // a large floor, where the floor's own shading makes such bands (the speed case's 200 × 150
    // floor had one).
    if let (Some(n), Some(_)) = (nadir, config.corners) {
        let suns = suns();
        let side = |x: i64, y: i64| nadir_side((x, y), n);
        let found = face::shifted_run(
            &blocked,
            &is_settled,
            &bright,
            &levels,
            (gw, gh),
            side,
            suns,
        );
        if let Some(((x, y), (dx, dy))) = found {
            doubt!(at_pixel(
                source,
                cell_centre_px((y * i64::from(gw) + x) as usize),
                format!(
                    "the blocked cells from cell ({x}, {y}) on are a run whose free cells toward the camera, from cell ({}, {}) on, show a band {:.2}–{:.2} as bright as the lit floor around them that no shadow explains: the obstacle may stand on those cells, its top leaning a whole cell over the run, its face showing there: cannot tell where it stands",
                    x + dx,
                    y + dy,
                    face::BAND.0,
                    face::BAND.1
                ),
            ));
        }
    }
    // Whether the view's runs that look way `dir` show their faces toward the nadir plainly,
    // the cells `skip` left out (see `cover::face_shown`).
    let faces_shown = |dir: (i64, i64), skip: &[usize]| {
        nadir.is_some_and(|n| {
            cover::face_shown(img, &classes, maps, (gw, gh), &blocked, n, dir, skip)
        })
    };
    // A free cell under a long lean whose run shows no face as long: a plain face too short,
    // or none where a face would show (the sun behind it, or the view's other faces that look
    // that way plain), as for a run's far cell (below).
    if !faceless.is_empty() {
        let suns = suns();
        for &(i, lacking) in &faceless {
            let (x, y) = ((i % gw as usize) as i64, (i / gw as usize) as i64);
            let (dx, dy) = lacking.dir;
            let (rx, ry) = (x - dx, y - dy);
            let would_show = || {
                face::in_own_shadow(suns, lacking.dir)
                    || faces_shown(lacking.dir, &[(ry * i64::from(gw) + rx) as usize])
            };
            if !lacking.hidden || would_show() {
                doubt!(at_pixel(
                    source,
                    cell_centre_px(i),
                    format!(
                        "cell ({x}, {y}) would be free under the top of the obstacle on cell ({rx}, {ry}), leaning {:.2} cell over it, but that obstacle shows no face toward the camera as long as such a lean makes: it may stand a cell nearer, its face read as floor, and cell ({x}, {y}) be its own: cannot tell whether it is blocked",
                        lacking.reach
                    ),
                ));
            }
        }
    }
    // The covered cells past a run of blocked cells (or on the floor's edge) that a leaning
    // top may cover whole, unless the shadow beside them shows the base reaching them.
    if !far_cells.is_empty() || !almost.is_empty() {
        let suns = suns();
        let doubted: Vec<usize> = far_cells.iter().chain(&almost).map(|&(i, _)| i).collect();
        let almost_whole = almost.len();
        // Whether the view's other faces show, for each direction (−u, +u, −v, +v), found
        // once.
        let mut shown: [Option<bool>; 4] = [None; 4];
        let side = |(dx, dy): (i64, i64)| match (dx, dy) {
            (-1, 0) => 0,
            (1, 0) => 1,
            (0, -1) => 2,
            _ => 3,
        };
        for (k, (i, far)) in almost.into_iter().chain(far_cells).enumerate() {
            let (x, y) = ((i % gw as usize) as u32, (i / gw as usize) as u32);
            if far.dir != (0, 0)
                && sunlit
                    .as_ref()
                    .is_some_and(|s| s.base_reaches(suns, (x, y), far.dir))
            {
                continue;
            }
            // No face shows where a free far cell would need a long one, and the sun shines
            // from behind that face (it would be in its own shadow, unlike the lit top), or
            // another run pointing the same way shows its face plainly (faces that look one
            // way are lit alike in one view; see `face`).
            if far.hidden_face
                && (face::in_own_shadow(suns, far.dir)
                    || *shown[side(far.dir)].get_or_insert_with(|| faces_shown(far.dir, &doubted)))
            {
                continue;
            }
            if k < almost_whole {
                doubt!(at_pixel(
                    source,
                    cell_centre_px(i),
                    format!(
                        "cell ({x}, {y}) is {:.0} % covered by an obstacle, but a neighbour's leaning top may cover it almost whole: cannot tell whether it is blocked",
                        shares[i] * 100.0
                    ),
                ));
                continue;
            }
            let edge = x == 0 || y == 0 || x + 1 == gw || y + 1 == gh;
            let why = if edge {
                "on the floor's edge is covered, but the top of the obstacle beside it, toward the camera, may lean over it to the edge: cannot tell whether it is blocked (nothing beyond the edge shows where the top ends, nor does a shadow beside it show the obstacle standing there)"
            } else {
                "is covered, but the top of the obstacle beside it, toward the camera, leans far enough (measured beside that obstacle) to cover it whole: cannot tell whether it is blocked (no shadow beside it shows the obstacle standing there)"
            };
            doubt!(at_pixel(
                source,
                cell_centre_px(i),
                format!("cell ({x}, {y}) {why}"),
            ));
        }
    }
    // Every shadow on the free floor must have a caster (see `shadows`): a shelf of the
    // floor's own colour and brightness shows only by its shadow.
    let shadow_regions = shadows::uncast_regions(&bins, &levels, (gw, gh), &is_settled);
    let uncast = {
        let doubt = |u: shadows::Uncast, why: &str| {
            let (x, y) = u.cell;
            at_pixel(
                source,
                floor_to_image.apply(u.at).unwrap_or((0.0, 0.0)),
                format!(
                    "a shadow on free floor from cell ({x}, {y}) ({:.1} cells of it) that {why}: something of the floor's colour may stand there",
                    u.bins as f64 / shadows::BINS as f64
                ),
            )
        };
        shadow_regions
            .first()
            .map(|&(u, _)| doubt(u, "no obstacle or robot in the image casts"))
            .or_else(|| {
                sunlit.as_ref()?.unattached(&is_settled, robots_sun).map(|u| {
                    doubt(u, "lies behind lit floor, not behind its caster, seen from the sun (whose direction the view's other shadows or the robots' give)")
                })
            })
    };
    // A top of nearly the floor's colour read whole where another's shadow falls, seen from
    // the sun, may be that shadow (see `shadows::Sunlit::casts_on`): each such top, when it is
    // darker than the lit floor (`pale::LIT`), as a shadow is (v0015's pale top, 1.03 times
    // as bright as the lit floor, lies where the rest of its shelf would cast a shadow).
    let faint_shadows: Vec<CrewError> = match sunlit.as_ref() {
        Some(sunlit) if !faint_tops.is_empty() => {
            match sunlit.sun(robots_sun) {
                Some(sun) => faint_tops
                    .iter()
                    .filter(|top| top.iter().all(|&c| !is_settled[c]))
                    .filter(|top| {
                        middle_brightness(img, &classifier, maps, (gw, gh), top)
                            .is_some_and(|b| b < pale::LIT)
                    })
                    .filter_map(|top| Some((top, sunlit.casts_on(top, sun)?)))
                    .map(|(top, (x, y))| {
                        let named: Vec<String> = top
                            .iter()
                            .map(|&c| format!("({}, {})", c % gw as usize, c / gw as usize))
                            .collect();
                        at_pixel(
                            source,
                            cell_centre_px(top[0]),
                            format!(
                                "cells {} read as the top of a shelf of nearly the floor's colour lie where the obstacle on cell ({x}, {y}) casts its shadow, seen from the sun: they may be that shadow: cannot tell whether they are blocked",
                                named.join(" ")
                            ),
                        )
                    })
                    .collect(),
                None => Vec::new(),
            }
        }
        _ => Vec::new(),
    };
    // On a floor with painted lines, every line between free cells must show (see
    // `painted`): a shelf of the floor's colour with hardly a shadow hides them.
    let hidden_lines: Vec<[(u32, u32); 2]>;
    let hidden: Vec<CrewError> = {
        let found = painted::missing(
            img,
            &classes,
            &classifier,
            maps,
            (gw, gh),
            &blocked,
            (&near_mark, px),
        );
        let take = if audit { found.len() } else { 1 };
        let cell = |(x, y): (u32, u32)| y as usize * gw as usize + x as usize;
        hidden_lines = found.iter().map(|m| m.cells).collect();
        found
            .into_iter()
            .filter(|m| !m.cells.iter().all(|&c| is_settled[cell(c)]))
            .take(take)
            .map(|m| {
                let [(x, y), (nx, ny)] = m.cells;
                at_pixel(
                    source,
                    m.at,
                    format!(
                        "the painted line between cells ({x}, {y}) and ({nx}, {ny}) does not show (contrast {:+.2} against the floor's {:+.2}): something of the floor's colour may stand over it",
                        m.contrast.0, m.contrast.1
                    ),
                )
            })
            .collect()
    };
    // The marks are read with the half-covered cells free: a robot or a goal standing on one
    // is not taken for a part of an obstacle there (see `on_shelf`).
    let grid = {
        let mut tentative = blocked.clone();
        for &(i, _) in &half_covered {
            tentative[i] = false;
        }
        Grid::new(gw, gh, tentative)
    };
    let unsure = blobs::sort(blobs::find(&mut classes, width, Class::Unsure as u8));
    let ReadMarks {
        marks: robots,
        set_aside: robots_aside,
        on_shelf: robots_on_shelf,
    } = marks(
        blobs::find(&mut classes, width, Class::Robot as u8),
        "robot",
        &grid,
        (&image_to_floor, nadir),
        1.0 / px,
        source,
        (&classes, width),
        (img, &classifier, Class::Robot),
    )?;
    let ReadMarks {
        marks: goals,
        set_aside: goals_aside,
        on_shelf: goals_on_shelf,
    } = marks(
        blobs::find(&mut classes, width, Class::Goal as u8),
        "goal",
        &grid,
        (&image_to_floor, None),
        1.0 / px,
        source,
        (&classes, width),
        (img, &classifier, Class::Goal),
    )?;
    // A blob of a colour between the robots' (or goals') and another's, as large as a robot,
    // on the floor (on blocked cells it is the obstacle's, as a mark-coloured one is: see
    // `on_shelf`).
    let smallest = robots
        .iter()
        .chain(&goals)
        .map(|m| m.area)
        .min()
        .unwrap_or(blobs::MIN_AREA);
    if let Some(b) = unsure.kept.iter().chain(&unsure.merged).find(|b| {
        2 * b.area() >= smallest && !on_shelf(b, &grid, &image_to_floor, (&classes, width))
    }) {
        return Err(at_pixel(
            source,
            b.centroid(),
            format!(
                "a blob of {} px whose colour is neither the robots' (hue {:.0}°) nor the goals' (hue {:.0}°) nor clearly another",
                b.area(),
                config.robot_colour.0,
                config.goal_colour.0
            ),
        ));
    }
    if robots.is_empty() {
        return Err(whole(
            source,
            format!(
                "no robot found (robots are hue {:.0}° ± 25°)",
                config.robot_colour.0
            ),
        ));
    }
    if robots.len() > crate::limits::MAX_AGENTS {
        return Err(whole(
            source,
            format!(
                "{} robots, more than the {} an instance may have (mason_crew::limits::MAX_AGENTS)",
                robots.len(),
                crate::limits::MAX_AGENTS
            ),
        ));
    }
    // Pieces set aside as what an obstacle's edge or a mark it hides leaves: had one been a
    // mark that should be read, its pair would be left over.
    if let Some(e) = robots_aside.or(goals_aside) {
        if goals.len() != robots.len() {
            return Err(e);
        }
    }
    // A blob of a mark's colour on blocked cells was read as the obstacle's; had it been a
    // mark on a cell misread as blocked, its pair would be left over.
    if goals.len() != robots.len() {
        let (kind, taken) = if goals.len() > robots.len() {
            ("robot", robots_on_shelf)
        } else {
            ("goal", goals_on_shelf)
        };
        if let Some((at, area)) = taken {
            let (u, v) = image_to_floor.apply(at).unwrap_or((-1.0, -1.0));
            return Err(at_pixel(
                source,
                at,
                format!(
                    "a {kind}-coloured blob of {area} px on cell ({}, {}), which an obstacle covers, was read as part of the obstacle, and the view has {} goals but {} robots: a {kind} may stand there",
                    u.floor(),
                    v.floor(),
                    goals.len(),
                    robots.len()
                ),
            ));
        }
    }
    if let Some(at) = absorbed.swallowed.filter(|_| goals.len() > robots.len()) {
        return Err(at_pixel(
            source,
            at,
            format!(
                "robot-coloured pixels here were read as part of a shelf, and the view has {} goals but {} robots: a robot may stand against the shelf",
                goals.len(),
                robots.len()
            ),
        ));
    }
    // Marks that do not show clearly (small goals washed out by blur, noise and JPEG): read
    // from the faint blobs of their colour when exactly as many as are missing show (see
    // `missing_faint`).
    let (mut robots, mut goals) = (robots, goals);
    let short = if goals.len() < robots.len() {
        Some((Class::Goal, robots.len() - goals.len()))
    } else if goals.len() > robots.len() && !config.spare_goals {
        Some((Class::Robot, goals.len() - robots.len()))
    } else {
        None
    };
    if let Some((class, missing)) = short {
        let (list, others, stand) = if class == Class::Goal {
            (&mut goals, &robots, None)
        } else {
            (&mut robots, &goals, nadir)
        };
        if let Ok(more) = missing_faint(
            (list, others),
            missing,
            &grid,
            (&image_to_floor, stand),
            1.0 / px,
            &classes,
            (img, &classifier, class),
        ) {
            list.extend(more);
        }
    }
    if goals.len() > robots.len() && !config.spare_goals {
        return Err(whole(
            source,
            format!(
                "{} goals but only {} robots: a robot may have been lost (too small to tell from noise, hidden, or taken for a shelf of its colour); give --spare-goals if the floor has goals to spare",
                goals.len(),
                robots.len()
            ),
        ));
    }
    if goals.len() < robots.len() {
        return Err(whole(
            source,
            format!(
                "{} robots but only {} goals; every robot needs a goal",
                robots.len(),
                goals.len()
            ),
        ));
    }
    for (kind, list) in [("robots", &robots), ("goals", &goals)] {
        let mut cells: Vec<(Cell, Point)> = list.iter().map(|m| (m.cell, m.pixel)).collect();
        cells.sort_by_key(|c| c.0);
        if let Some(w) = cells.windows(2).find(|w| w[0].0 == w[1].0) {
            let (x, y) = grid.xy(w[0].0);
            return Err(at_pixel(
                source,
                w[1].1,
                format!("two {kind} on cell ({x}, {y})"),
            ));
        }
    }
    // A half-covered cell a robot or a goal stands on is free: the view is read again with it
    // settled so (see `under_marks`); any other is refused.
    if !half_covered.is_empty() {
        let cells: Vec<usize> = half_covered.iter().map(|h| h.0).collect();
        let under = under_marks(&cells, &robots, &goals);
        if under.is_empty() || !audit {
            for (i, error) in half_covered {
                if under.binary_search(&i).is_err() {
                    doubt!(error);
                }
            }
        }
        if !under.is_empty() {
            let xy = |i: usize| ((i % gw as usize) as u32, (i / gw as usize) as u32);
            let mut again = config.clone();
            again.free_cells.extend(under.iter().map(|&i| xy(i)));
            let (mut read, lightly) = read_inner(img, source, &again, audit, infer, balance)?;
            read.reading
                .settled
                .retain(|(c, _)| under.binary_search(&(c.0 as usize)).is_err());
            read.reading.under_marks = under.iter().map(|&i| Cell(i as u32)).collect();
            return Ok((read, lightly));
        }
    }
    let grid = Grid::new(gw, gh, blocked);
    // Shelves of the floor's colour that two kinds of evidence tell: read again with them
    // blocked, and that reading kept when it refuses nothing (see `corroborated`).
    let told = !(not_floor.is_empty() && uncast.is_none() && unlike.is_none() && hidden.is_empty());
    if infer && told && doubts.is_empty() {
        let unlike_all: Vec<usize> = odd_cells.iter().chain(&unlike_cells).copied().collect();
        let shadows_all: Vec<Vec<usize>> =
            shadow_regions.into_iter().map(|(_, bins)| bins).collect();
        let free = |i: usize| grid.is_free(Cell(i as u32)) && !is_settled[i];
        // The view read again with `tops` blocked, kept when it refuses nothing.
        let again_with = |tops: &[usize]| -> Option<(Audited, f64)> {
            let xy = |i: usize| ((i % gw as usize) as u32, (i / gw as usize) as u32);
            let mut again = config.clone();
            again.blocked_cells.extend(tops.iter().map(|&i| xy(i)));
            let (mut read, lightly) =
                read_inner(img, source, &again, audit, false, balance).ok()?;
            if !read.doubts.is_empty() || lightly >= corroborated::FREE_COVER {
                return None;
            }
            read.reading
                .settled
                .retain(|(c, _)| tops.binary_search(&(c.0 as usize)).is_err());
            read.reading.floor_tops = tops.iter().map(|&i| Cell(i as u32)).collect();
            Some((read, lightly))
        };
        let tops = corroborated::shelves(&unlike_all, &shadows_all, &hidden_lines, (gw, gh));
        let free_looks: Vec<Option<(f64, f64, f64)>> = (0..cells)
            .map(|i| {
                let b = bright[i].filter(|_| free(i))?;
                Some((b, saturation[i], levels[i]))
            })
            .collect();
        if !tops.is_empty() && corroborated::alone(&tops, &free_looks) {
            if let Some(read) = again_with(&tops) {
                return Ok(read);
            }
        }
        // Dark tops of another hue than the shadows' (see `looks::Look::dark_unlike`), told by
        // the shadow nothing casts beside them, and alone by that tint on the free floor.
        let dark_cells: Vec<usize> = (0..cells)
            .filter(|&i| free(i) && unexplained[i].is_some_and(|(_, dark)| dark))
            .collect();
        let dark = corroborated::shelves(&dark_cells, &shadows_all, &[], (gw, gh));
        let tints: Vec<Option<(f64, f64, f64)>> = (0..cells)
            .map(|i| {
                let (tint, _) = unexplained[i].filter(|_| free(i))?;
                Some((0.0, tint, 0.0))
            })
            .collect();
        if !dark.is_empty() && dark != tops && corroborated::alone(&dark, &tints) {
            if let Some(read) = again_with(&dark) {
                return Ok(read);
            }
        }
    }
    for e in not_floor
        .into_iter()
        .chain(faint_shadows)
        .chain(uncast)
        .chain(unlike)
        .chain(hidden)
    {
        doubt!(e);
    }
    // The most any free cell's window is covered by an obstacle.
    let lightly = (0..cells)
        .filter(|&i| grid.is_free(Cell(i as u32)))
        .map(|i| shares[i])
        .fold(0.0, f64::max);
    Ok((
        Audited {
            reading: AerialReading {
                grid,
                robots,
                goals,
                cell_px: px,
                grid_source,
                corners,
                floor_to_image,
                image_size: (img.width(), img.height()),
                settled: settled
                    .iter()
                    .enumerate()
                    .filter_map(|(i, s)| s.map(|b| (Cell(i as u32), b)))
                    .collect(),
                floor_tops: Vec::new(),
                under_marks: Vec::new(),
                balanced_on_middles: balance == Balance::Middles,
            },
            doubts,
        },
        lightly,
    ))
}

/// Mean cell side in pixels over the floor.
/// On which side of cell `(x, y)` the nadir `n` lies, along each axis: −1 (before the
/// cell), 1 (beyond it) or 0 (level with it).
fn nadir_side((x, y): (i64, i64), n: Point) -> (i32, i32) {
    let side = |c: i64, at: f64| {
        if at >= c as f64 + 1.0 {
            1
        } else if at < c as f64 {
            -1
        } else {
            0
        }
    };
    (side(x, n.0), side(y, n.1))
}

/// The offsets of a cell's eight neighbours on its side `side` toward the nadir (see
/// [`nadir_side`]; level with it along an axis: both ways along that axis).
fn neighbours_toward(side: (i32, i32)) -> impl Iterator<Item = (i64, i64)> {
    (-1i64..=1)
        .flat_map(|dy| (-1i64..=1).map(move |dx| (dx, dy)))
        .filter(move |&(dx, dy)| {
            (dx, dy) != (0, 0) && dx * i64::from(side.0) >= 0 && dy * i64::from(side.1) >= 0
        })
}

fn cell_size_px(floor_to_image: &Homography, (w, h): (f64, f64)) -> f64 {
    let c = [(0.0, 0.0), (w, 0.0), (w, h), (0.0, h)].map(|p| floor_to_image.apply(p).unwrap_or(p));
    let side = |a: Point, b: Point| ((a.0 - b.0).powi(2) + (a.1 - b.1).powi(2)).sqrt();
    let across = (side(c[0], c[1]) + side(c[3], c[2])) / (2.0 * w);
    let down = (side(c[0], c[3]) + side(c[1], c[2])) / (2.0 * h);
    (across + down) / 2.0
}

/// Robots (with the nadir: standing) or goals (flat) from their blobs.
#[allow(clippy::too_many_arguments)]
fn marks(
    found: Vec<blobs::Blob>,
    kind: &str,
    grid: &Grid,
    (image_to_floor, nadir): (&Homography, Option<Point>),
    px_on_floor: f64,
    source: &str,
    (classes, width): (&[u8], usize),
    faint: (&RgbImage, &Classifier, Class),
) -> Result<ReadMarks, CrewError> {
    // A blob whose pixels lie on blocked cells is part of the obstacle there: marks stand on
    // the floor (see `on_shelf`). The largest such blob not too small for a mark (noise, see
    // `blobs::sort`) is kept to be named should the view then have fewer robots than goals,
    // or the reverse.
    let (shelf, found): (Vec<blobs::Blob>, Vec<blobs::Blob>) = found
        .into_iter()
        .partition(|b| on_shelf(b, grid, image_to_floor, (classes, width)));
    let mut sorted = blobs::sort(found);
    let largest_on_shelf = shelf
        .iter()
        .filter(|b| {
            b.area() >= blobs::MIN_AREA
                && b.area() as f64 >= blobs::NOISE * sorted.median_area as f64
        })
        .max_by_key(|b| b.area())
        .map(|b| (b.centroid(), b.area()));
    for b in std::mem::take(&mut sorted.merged) {
        let Some(pieces) = blobs::split(&b, sorted.median_area) else {
            // A line of the mark's colour, longer than four marks in a row and thinner than a
            // mark: a shelf's edge or rim, or a line painted on the floor, not marks (see
            // `blobs::line_like`).
            if blobs::line_like(&b, sorted.median_area) {
                continue;
            }
            // One mark larger than the typical one, not marks touching (see `blobs::one_large`).
            if blobs::one_large(&b, sorted.median_area) {
                sorted.kept.push(b);
                continue;
            }
            // A mark joined to a thin strip of its colour, a shelf's rim (see `off_rim`).
            if let Some(mark) = off_rim(&b, sorted.median_area) {
                sorted.kept.push(mark);
                continue;
            }
            return Err(at_pixel(
                source,
                b.centroid(),
                format!(
                    "{kind}s touching: a blob of {} px, {:.1} times the median {kind} ({} px), that cannot be separated",
                    b.area(),
                    b.area() as f64 / sorted.median_area as f64,
                    sorted.median_area
                ),
            ));
        };
        sorted.kept.extend(pieces);
    }
    let doubt = |b: &blobs::Blob| {
        at_pixel(
            source,
            b.centroid(),
            format!(
                "a {kind}-coloured blob of {} px, too large for noise and too small for a {kind} (median {} px)",
                b.area(),
                sorted.median_area
            ),
        )
    };
    // Pieces that only an obstacle's edge or a mark it hides leaves (see
    // `blobs::behind_obstacle`) are set aside; the first is refused later unless the view
    // then has exactly as many goals as robots (see `read_aerial_image`).
    let obstacle_least = (blobs::OBSTACLE_CELLS / (px_on_floor * px_on_floor)).ceil() as usize;
    let mut behind = blobs::behind_obstacle(
        &sorted.doubtful,
        sorted.median_area,
        (classes, width),
        obstacle_least,
    );
    // So are pieces against an obstacle whose colour is unlike the view's marks of the kind
    // (see `alike::unlike_marks`): a shelf's edge or shaded side of a colour near the marks'.
    let typical: Vec<blobs::Blob> = {
        let median = sorted.median_area;
        sorted
            .kept
            .iter()
            .filter(|b| b.area() * blobs::ALIKE >= median && b.area() <= blobs::ALIKE * median)
            .cloned()
            .collect()
    };
    {
        let (img, classifier, class) = faint;
        for (b, aside) in sorted.doubtful.iter().zip(behind.iter_mut()) {
            *aside = *aside || alike::unlike_marks(b, &typical, img, classifier, class);
        }
    }
    let mut set_aside = sorted
        .doubtful
        .iter()
        .zip(&behind)
        .find(|(_, &b)| b)
        .map(|(b, _)| doubt(b));
    // The others may be marks cut by an obstacle's edge, read whole where every way to
    // complete them puts them on one cell (see `cut_mark`), or faint marks whose clear pixels
    // are their middle alone (see `faint_mark`); a few at most.
    let cut_pieces: Vec<&blobs::Blob> = sorted
        .doubtful
        .iter()
        .zip(&behind)
        .filter(|(_, &b)| !b)
        .map(|(b, _)| b)
        .collect();
    let mut cut = Vec::new();
    for piece in &cut_pieces {
        let whole = (cut_pieces.len() <= CUT_PIECES)
            .then(|| {
                cut_mark(
                    piece,
                    sorted.median_area,
                    grid,
                    (image_to_floor, nadir),
                    px_on_floor,
                    (classes, width),
                )
                .or_else(|| {
                    faint_mark(
                        piece,
                        sorted.median_area,
                        grid,
                        (image_to_floor, nadir),
                        px_on_floor,
                        (classes, width),
                        faint,
                    )
                })
            })
            .flatten();
        match whole {
            Some(mark) => cut.push(mark),
            // A piece no whole mark completes, dimmer than the view's marks: a speck of their
            // colour in a shadow or on a dark floor, set aside as the pieces above are (see
            // `alike::dimmer_than_marks`).
            None if alike::dimmer_than_marks(piece, &typical, faint.0, faint.1) => {
                set_aside.get_or_insert_with(|| doubt(piece));
            }
            None => return Err(doubt(piece)),
        }
    }
    // A blob well under the median is a partly hidden one, or a single one among pairs
    // touching that made the median: then a blob of the median's size splits in two.
    let median = sorted.median_area as f64;
    if let Some(b) = sorted
        .kept
        .iter()
        .find(|b| (b.area() as f64) < blobs::SMALL * median)
    {
        if let Some(pair) = sorted
            .kept
            .iter()
            .find(|p| blobs::split(p, sorted.median_area / 2).is_some())
        {
            return Err(at_pixel(
                source,
                pair.centroid(),
                format!(
                    "{kind}s touching: a blob of {} px splits in two like {kind}s of half the median ({} px), and a {kind}-coloured blob of {} px is that size: the median may be of {kind}s touching",
                    pair.area(),
                    sorted.median_area,
                    b.area()
                ),
            ));
        }
    }
    let mut out = Vec::with_capacity(sorted.kept.len());
    let on_floors: Vec<Vec<Point>> = sorted
        .kept
        .iter()
        .map(|b| blobs::on_floor(b, image_to_floor))
        .collect();
    // The view's lean per distance from the nadir, its robots' (see `blobs::view_lean`).
    let view = blobs::view_lean(&on_floors, nadir, px_on_floor);
    for (b, on_floor) in sorted.kept.into_iter().zip(on_floors) {
        // Without a nadir (goals, flat) the centroid.
        let centre = blobs::standing_centre_scaled(&on_floor, nadir, px_on_floor, view);
        let pixel = b.centroid();
        let (u, v) = centre;
        let cell = (u >= 0.0 && v >= 0.0)
            .then(|| grid.cell(u.floor() as i64, v.floor() as i64))
            .flatten()
            .ok_or_else(|| {
                at_pixel(
                    source,
                    pixel,
                    format!("a {kind} whose centre ({u:.2}, {v:.2}) is outside the floor"),
                )
            })?;
        let margin = [u.fract(), 1.0 - u.fract(), v.fract(), 1.0 - v.fract()]
            .into_iter()
            .fold(f64::INFINITY, f64::min);
        let (x, y) = grid.xy(cell);
        let unsettled = if margin < BORDER_MARGIN {
            Some(format!(
                "a {kind} on the border of cell ({x}, {y}): its centre ({u:.2}, {v:.2}) is {margin:.2} cells from the border (at least {BORDER_MARGIN} to settle)"
            ))
        } else if !grid.is_free(cell) {
            Some(format!(
                "a {kind} on cell ({x}, {y}), which an obstacle covers"
            ))
        } else {
            None
        };
        if let Some(why) = unsettled {
            // Against an obstacle (`blobs::against_obstacle`), such a blob may be a piece of a
            // shelf of a colour near the marks' (its rim, its top leaning off its cells, its
            // shaded side): it is set aside as the pieces above are, and the view is read only
            // with exactly as many goals as robots (issue #29's twenty-ninth round: o0020's tan
            // shelf and w0002's maroon one left a robot-coloured piece on a border, 5 and 6
            // cells from any robot).
            if blobs::against_obstacle(&b, (classes, width), obstacle_least) {
                set_aside.get_or_insert_with(|| at_pixel(source, pixel, why));
                continue;
            }
            return Err(at_pixel(source, pixel, why));
        }
        let size = b.area() as f64 / sorted.median_area.max(1) as f64;
        let confidence = (margin / 0.25).min(1.0) * size.min(1.0 / size).min(1.0);
        out.push(Mark {
            cell,
            floor: centre,
            pixel,
            area: b.area(),
            confidence,
        });
    }
    out.extend(cut);
    Ok(ReadMarks {
        marks: out,
        set_aside,
        on_shelf: largest_on_shelf,
    })
}

/// At most this many pieces of a kind, too small for a mark and against no obstacle that
/// would set them aside, are tried as marks cut by an obstacle's edge ([`cut_mark`]); with
/// more, the first is refused as before.
pub const CUT_PIECES: usize = 4;

/// The free cell under the floor point `(u, v)` (in cells) and the point's distance from that
/// cell's nearest border; `None` off the floor or on a blocked cell.
fn free_cell_under(grid: &Grid, (u, v): Point) -> Option<(Cell, f64)> {
    if !(u >= 0.0 && v >= 0.0) {
        return None;
    }
    let cell = grid.cell(u.floor() as i64, v.floor() as i64)?;
    let margin = [u.fract(), 1.0 - u.fract(), v.fract(), 1.0 - v.fract()]
        .into_iter()
        .fold(f64::INFINITY, f64::min);
    grid.is_free(cell).then_some((cell, margin))
}

/// A piece of a mark cut by an obstacle's edge (a robot or a goal half under a top leaning
/// over it), read whole: every disc of the median's area it could be the visible part of
/// (`blobs::cut_discs`) must stand on the same free cell, at least [`BORDER_MARGIN`] from its
/// borders, its centre taken as for a whole mark (standing, for a robot). The mark is then the
/// disc's nearest the discs' mean centre, its area and confidence the piece's (its size as a
/// share of the median's). `None`: no such disc, or discs on two cells.
fn cut_mark(
    piece: &blobs::Blob,
    median: usize,
    grid: &Grid,
    (image_to_floor, nadir): (&Homography, Option<Point>),
    px_on_floor: f64,
    (classes, width): (&[u8], usize),
) -> Option<Mark> {
    let discs = blobs::cut_discs(piece, median, (classes, width));
    let mut cell = None;
    let mut margin = f64::INFINITY;
    let mut centres = Vec::with_capacity(discs.len());
    for disc in &discs {
        let (u, v) =
            blobs::standing_centre(&blobs::on_floor(disc, image_to_floor), nadir, px_on_floor);
        let (c, m) = free_cell_under(grid, (u, v))?;
        if cell.is_some_and(|k| k != c) {
            return None;
        }
        cell = Some(c);
        margin = margin.min(m);
        centres.push((u, v));
    }
    let cell = cell?;
    if margin < BORDER_MARGIN {
        return None;
    }
    let n = centres.len() as f64;
    let mean = centres
        .iter()
        .fold((0.0, 0.0), |(a, b), c| (a + c.0 / n, b + c.1 / n));
    let floor = centres.iter().copied().min_by(|a, b| {
        let d = |c: &Point| (c.0 - mean.0).hypot(c.1 - mean.1);
        d(a).total_cmp(&d(b))
    })?;
    let share = piece.area() as f64 / median.max(1) as f64;
    Some(Mark {
        cell,
        floor,
        pixel: piece.centroid(),
        area: piece.area(),
        confidence: (margin / 0.25).min(1.0) * share.min(1.0),
    })
}

/// A faint mark's pixels lie within this many times the median mark's radius of its clear
/// piece's centre (see [`faint_mark`]) ...
const FAINT_REACH: f64 = 2.0;
/// ... it is whole from this share of the median mark's area within that reach ...
const FAINT_WHOLE: f64 = 0.6;
/// ... and at most this share of those pixels again lie past the reach, within [`FAINT_RING`]
/// times it (a tinted stretch of floor runs on).
const FAINT_BOUND: f64 = 0.25;
/// The ring past the reach where a faint mark's pixels are counted, as a multiple of it.
const FAINT_RING: f64 = 1.5;

/// A mark read from a piece too small for one, grown over the pixels around it of its hue with
/// half a mark's colour ([`Classifier::faint_mark`], each pixel's colour the mean of the square
/// [`pixels::denoise_radius`] around it, at least 3 × 3): a small goal or robot washed out
/// by blur, noise and JPEG whose clear pixels are its middle alone. Read as by
/// [`faint_whole`] with the pixels grown within [`FAINT_RING`] times [`FAINT_REACH`] median
/// radii of the piece's centre; its confidence is the piece's share of the median.
fn faint_mark(
    piece: &blobs::Blob,
    median: usize,
    grid: &Grid,
    (image_to_floor, nadir): (&Homography, Option<Point>),
    px_on_floor: f64,
    (classes, width): (&[u8], usize),
    (img, classifier, class): (&RgbImage, &Classifier, Class),
) -> Option<Mark> {
    let height = classes.len() / width.max(1);
    let r = faint_radius(px_on_floor);
    let reach = FAINT_REACH * (median as f64 / std::f64::consts::PI).sqrt();
    let centre = piece.centroid();
    let from_centre = |x: f64, y: f64| (x + 0.5 - centre.0).hypot(y + 0.5 - centre.1);
    let faint = |i: usize| {
        let (x, y) = ((i % width) as f64, (i / width) as f64);
        from_centre(x, y) <= FAINT_RING * reach && faint_at(img, classifier, classes, r, class, i)
    };
    let grown = blobs::grow_faint(piece, (width, height), faint);
    let (mut mark, margin) = faint_whole(
        &grown,
        (centre, reach),
        median,
        grid,
        (image_to_floor, nadir),
        px_on_floor,
    )?;
    let share = piece.area() as f64 / median.max(1) as f64;
    mark.confidence = margin * share.min(1.0);
    Some(mark)
}

/// The half-width of the square over which a pixel's colour is averaged for
/// [`faint_at`]: the denoising square's, at least 1 (3 × 3).
fn faint_radius(px_on_floor: f64) -> i64 {
    pixels::denoise_radius(1.0 / px_on_floor).max(1) as i64
}

/// Whether pixel `i` may be a faint mark's of `class`: floor, a colour that cannot be told or
/// the mark's own class, and its colour averaged over the square of half-width `r` around it
/// of the mark's hue with half a mark's colour ([`Classifier::faint_mark`]).
fn faint_at(
    img: &RgbImage,
    classifier: &Classifier,
    classes: &[u8],
    r: i64,
    class: Class,
    i: usize,
) -> bool {
    let c = classes[i];
    if c != Class::Floor as u8 && c != Class::Unsure as u8 && c != class as u8 {
        return false;
    }
    let (width, height) = (i64::from(img.width()), i64::from(img.height()));
    let (x, y) = (i as i64 % width, i as i64 / width);
    let (mut sum, mut n) = ([0u32; 3], 0u32);
    for qy in (y - r).max(0)..=(y + r).min(height - 1) {
        for qx in (x - r).max(0)..=(x + r).min(width - 1) {
            let p = img.get_pixel(qx as u32, qy as u32).0;
            (0..3).for_each(|k| sum[k] += u32::from(p[k]));
            n += 1;
        }
    }
    let mean = sum.map(|v| ((v + n / 2) / n.max(1)) as u8);
    classifier.faint_mark(mean) == Some(class)
}

/// Where a faint mark is read whole: its pixels within `reach` of `centre` (the rest, in
/// `outer`) at least [`FAINT_WHOLE`] of the `median` mark's area, at most [`FAINT_BOUND`] of
/// that many further out, and the centre of those within reach (standing, for a robot) on a
/// free cell at least [`BORDER_MARGIN`] from its borders. The mark, with the confidence
/// factor of that margin (1 from a quarter cell).
fn faint_whole(
    grown: &blobs::Blob,
    (centre, reach): (Point, f64),
    median: usize,
    grid: &Grid,
    (image_to_floor, nadir): (&Homography, Option<Point>),
    px_on_floor: f64,
) -> Option<(Mark, f64)> {
    let from_centre =
        |x: u32, y: u32| (f64::from(x) + 0.5 - centre.0).hypot(f64::from(y) + 0.5 - centre.1);
    let (inner, outer): (Vec<_>, Vec<_>) = grown
        .pixels
        .iter()
        .partition(|&&(x, y)| from_centre(x, y) <= reach);
    if (inner.len() as f64) < FAINT_WHOLE * median as f64
        || outer.len() as f64 > FAINT_BOUND * inner.len() as f64
    {
        return None;
    }
    let grown = blobs::Blob::from_pixels(inner);
    let floor =
        blobs::standing_centre(&blobs::on_floor(&grown, image_to_floor), nadir, px_on_floor);
    let (cell, margin) = free_cell_under(grid, floor)?;
    if margin < BORDER_MARGIN {
        return None;
    }
    Some((
        Mark {
            cell,
            floor,
            pixel: grown.centroid(),
            area: grown.area(),
            confidence: 0.0,
        },
        (margin / 0.25).min(1.0),
    ))
}

/// Marks of `class` that do not show clearly, when the view lacks `missing` of them beside
/// the `found` ones (of which there is at least one): the faint blobs of the floor
/// ([`faint_at`]; one pass over the image, on all cores, only then) away from every mark read,
/// of either kind (over twice [`FAINT_REACH`] median radii of its kind from its centre: its
/// glow, and the fringe of the other colour that blur and JPEG leave around a small mark),
/// read as by [`faint_whole`] around their centroids; each with half the confidence of its
/// margin. Read only when exactly `missing` are found; else their count.
#[allow(clippy::too_many_arguments)]
fn missing_faint(
    (found, others): (&[Mark], &[Mark]),
    missing: usize,
    grid: &Grid,
    (image_to_floor, nadir): (&Homography, Option<Point>),
    px_on_floor: f64,
    classes: &[u8],
    (img, classifier, class): (&RgbImage, &Classifier, Class),
) -> Result<Vec<Mark>, usize> {
    use rayon::prelude::*;
    let median_of = |marks: &[Mark]| {
        let mut areas: Vec<usize> = marks.iter().map(|m| m.area).collect();
        areas.sort_unstable();
        areas.get(areas.len() / 2).copied()
    };
    let Some(median) = median_of(found) else {
        return Err(0);
    };
    let width = img.width() as usize;
    // A mark read beside an obstacle of nearly its hue may be that obstacle's fringe, and the
    // count it makes up not to be trusted: nothing is read then.
    if found
        .iter()
        .any(|m| beside_own_hue(m, classes, (img, classifier, class)))
    {
        return Err(0);
    }
    let r = faint_radius(px_on_floor);
    let reach_of = |median: usize| FAINT_REACH * (median as f64 / std::f64::consts::PI).sqrt();
    let reach = reach_of(median);
    let other_glow = 2.0 * reach_of(median_of(others).unwrap_or(0));
    let glows: Vec<(Point, f64)> = found
        .iter()
        .map(|m| (m.pixel, 2.0 * reach))
        .chain(others.iter().map(|m| (m.pixel, other_glow)))
        .collect();
    let mut mask: Vec<u8> = vec![0; classes.len()];
    mask.par_chunks_mut(width.max(1))
        .enumerate()
        .for_each(|(y, row)| {
            for (x, m) in row.iter_mut().enumerate() {
                *m = u8::from(faint_at(img, classifier, classes, r, class, y * width + x));
            }
        });
    let mut read: Vec<Mark> = Vec::new();
    for blob in blobs::find(&mut mask, width, 1) {
        let centre = blob.centroid();
        let glow = glows
            .iter()
            .any(|&(at, within)| (at.0 - centre.0).hypot(at.1 - centre.1) <= within);
        if glow
            || (blob.area() as f64) < FAINT_WHOLE * median as f64
            || against_obstacle(&blob, classes, (img, classifier, class)) > FAINT_APART
        {
            continue;
        }
        let Some((mut mark, margin)) = faint_whole(
            &blob,
            (centre, reach),
            median,
            grid,
            (image_to_floor, nadir),
            px_on_floor,
        ) else {
            continue;
        };
        if found.iter().chain(&read).any(|m| m.cell == mark.cell) {
            continue;
        }
        mark.confidence = FAINT_CONFIDENCE * margin;
        read.push(mark);
    }
    if read.len() == missing {
        Ok(read)
    } else {
        Err(read.len())
    }
}

/// The largest share of the pixels around a faint blob (8-connected to it) that may be an
/// obstacle's of a hue near the mark's (within [`FAINT_HUE`]) for it to be read as a mark
/// ([`missing_faint`]): a pale top of a mark's hue leaves faint pieces along its edges (a
/// goal half under a top of another colour shows its faint half against it).
const FAINT_APART: f64 = 0.1;
/// Degrees from the mark's hue within which an obstacle's pixel counts for [`FAINT_APART`].
const FAINT_HUE: f64 = 40.0;

/// The share of the pixels 8-connected to `blob` (not in it, inside the image) that are of an
/// obstacle's colour with a hue within [`FAINT_HUE`] of the mark `class`'s.
fn against_obstacle(
    blob: &blobs::Blob,
    classes: &[u8],
    (img, classifier, class): (&RgbImage, &Classifier, Class),
) -> f64 {
    let width = img.width() as usize;
    let height = classes.len() / width.max(1);
    let inside: std::collections::HashSet<(u32, u32)> = blob.pixels.iter().copied().collect();
    let mut around = std::collections::HashSet::new();
    for &(x, y) in &blob.pixels {
        for dy in -1i64..=1 {
            for dx in -1i64..=1 {
                let (nx, ny) = (i64::from(x) + dx, i64::from(y) + dy);
                if nx < 0 || ny < 0 || nx >= width as i64 || ny >= height as i64 {
                    continue;
                }
                let q = (nx as u32, ny as u32);
                if !inside.contains(&q) {
                    around.insert(q);
                }
            }
        }
    }
    let obstacle = around
        .iter()
        .filter(|&&(x, y)| {
            classes[y as usize * width + x as usize] == Class::Obstacle as u8
                && classifier.near_hue_of(img.get_pixel(x, y).0, class, FAINT_HUE)
        })
        .count();
    obstacle as f64 / around.len().max(1) as f64
}

/// Whether more than [`FAINT_APART`] of the pixels within twice the radius of mark `m`'s
/// area around its centre are an obstacle's of a hue within [`FAINT_HUE`] of its kind's.
fn beside_own_hue(
    m: &Mark,
    classes: &[u8],
    (img, classifier, class): (&RgbImage, &Classifier, Class),
) -> bool {
    let (width, height) = (i64::from(img.width()), i64::from(img.height()));
    let within = 2.0 * (m.area as f64 / std::f64::consts::PI).sqrt() + 1.0;
    let (cx, cy) = m.pixel;
    let (mut all, mut near) = (0usize, 0usize);
    for y in ((cy - within).floor() as i64).max(0)..=((cy + within).ceil() as i64).min(height - 1) {
        for x in
            ((cx - within).floor() as i64).max(0)..=((cx + within).ceil() as i64).min(width - 1)
        {
            if (x as f64 + 0.5 - cx).hypot(y as f64 + 0.5 - cy) > within {
                continue;
            }
            all += 1;
            let i = (y * width + x) as usize;
            if classes[i] == Class::Obstacle as u8
                && classifier.near_hue_of(img.get_pixel(x as u32, y as u32).0, class, FAINT_HUE)
            {
                near += 1;
            }
        }
    }
    near as f64 > FAINT_APART * all as f64
}

/// The confidence of a mark read whole from faint pixels alone, at a margin of a quarter cell.
const FAINT_CONFIDENCE: f64 = 0.5;

/// The marks of one kind read by [`marks`], with what it left out that may have been one.
struct ReadMarks {
    marks: Vec<Mark>,
    /// The first piece set aside as what an obstacle's edge or a mark it hides leaves, a
    /// piece unlike or dimmer than the view's marks, or a mark on a cell border or a blocked
    /// cell against an obstacle (since issue #29's twenty-ninth round): its refusal, given when
    /// the view then has not as many goals as robots.
    set_aside: Option<CrewError>,
    /// The largest blob of the kind's colour on blocked cells, read as the obstacle's: its
    /// pixel and area.
    on_shelf: Option<(Point, usize)>,
}

/// A blob with this share of the pixels around it, or more, of the floor stands on the floor,
/// wherever it lies ([`on_shelf`]).
const FLOOR_AROUND: f64 = 0.75;

/// A blob with at least this share of its pixels (on the floor) on blocked cells lies on a
/// shelf. A mark on a free cell beside a shelf has a few of its pixels there at most (its top
/// leaning, or a large robot reaching over the border); 0.5 and 0.6 read families A–V alike,
/// 0.75 two scenes fewer (L0005, R0017: a shelf's robot-coloured specks partly off its cells;
/// measured before [`FLOOR_AROUND`]).
const ON_SHELF: f64 = 0.6;

/// Whether a mark-coloured blob lies on blocked cells (at least [`ON_SHELF`] of its pixels on
/// the floor): the reddest or greenest pixels of a shelf of a colour near a mark's (walnut,
/// terracotta, olive, dark green), not a mark, which stands on the floor. Since issue #29's
/// thirteenth round; until then such a blob was refused as a mark on a blocked cell, or, too
/// small or too large for a mark, as a piece or as marks touching. A mark so taken from a cell
/// misread as blocked leaves the view with fewer robots than goals (or the reverse), which
/// is refused, naming the blob; and a blob with [`FLOOR_AROUND`] of the pixels around it of
/// the floor is a mark wherever it lies (a mark on a cell misread as blocked, refused as such:
/// S0025's robot and goal, both taken for shelves' in the audit before this held, left the
/// counts equal).
fn on_shelf(
    blob: &blobs::Blob,
    grid: &Grid,
    image_to_floor: &Homography,
    (classes, width): (&[u8], usize),
) -> bool {
    let on = blobs::on_floor(blob, image_to_floor);
    let blocked = on
        .iter()
        .filter(|&&(u, v)| {
            u >= 0.0
                && v >= 0.0
                && grid
                    .cell(u.floor() as i64, v.floor() as i64)
                    .is_some_and(|c| !grid.is_free(c))
        })
        .count();
    !on.is_empty()
        && blocked as f64 >= ON_SHELF * on.len() as f64
        && blobs::ring_share(blob, classes, width, Class::Floor as u8) < FLOOR_AROUND
}

/// The median brightness (the mean of the channels after white balance, 1 for the lit floor)
/// of the pixels of `cells`' middles (0.2–0.8 of a cell along each axis), row-major indices;
/// `None` for no pixel.
fn middle_brightness(
    img: &RgbImage,
    classifier: &Classifier,
    (floor_to_image, image_to_floor): (&Homography, &Homography),
    (gw, _): (u32, u32),
    cells: &[usize],
) -> Option<f64> {
    let (width, height) = (img.width() as usize, img.height() as usize);
    let mut values: Vec<f64> = Vec::new();
    for &c in cells {
        let (cx, cy) = ((c % gw as usize) as u32, (c / gw as usize) as u32);
        let Some((x0, y0, x1, y1)) = floor_to_image.cell_box((cx, cy), width, height) else {
            continue;
        };
        for y in y0..y1 {
            for x in x0..x1 {
                let Some((u, v)) = image_to_floor.apply((x as f64 + 0.5, y as f64 + 0.5)) else {
                    continue;
                };
                let (fu, fv) = (u - f64::from(cx), v - f64::from(cy));
                if (0.2..=0.8).contains(&fu) && (0.2..=0.8).contains(&fv) {
                    let b = classifier.balanced(img.get_pixel(x as u32, y as u32).0);
                    values.push((b[0] + b[1] + b[2]) / 3.0);
                }
            }
        }
    }
    if values.is_empty() {
        return None;
    }
    let mid = values.len() / 2;
    Some(*values.select_nth_unstable_by(mid, f64::total_cmp).1)
}

/// The cells of `half` (half-covered cells that nothing else explains) that a robot or a goal
/// stands on, sorted. A mark stands on the floor (a robot's centre is taken where it stands, a
/// goal is painted on it), so the cell under its centre is free whatever covers part of its
/// window: a robot's blurred rim and its shadow on a dark floor, or a faint goal's pixels, read
/// as an obstacle's (l0005's two faint goals on a dark floor; k0035, n0034 and G0012 were
/// first refused so too, and are refused now for other reasons; issue #29's twenty-seventh
/// round).
/// The marks are read with these cells free, so that a mark on one is not taken for a part of
/// the obstacle there (see `on_shelf`); a mark's centre read in the wrong cell makes the view
/// wrong whatever this decides.
fn under_marks(half: &[usize], robots: &[Mark], goals: &[Mark]) -> Vec<usize> {
    let mut under: Vec<usize> = half
        .iter()
        .copied()
        .filter(|&i| robots.iter().chain(goals).any(|m| m.cell.0 as usize == i))
        .collect();
    under.sort_unstable();
    under.dedup();
    under
}

/// Whether a half-covered cell's own top covers it: `standing` (a cover inside the cell, away
/// from its borders toward the nadir) only when no covered neighbour toward the nadir may lean
/// its top over the cell (`leaned`), since such a top covers from the border they share; a
/// `pale` top (the cell's floor-coloured pixels a pale shade of its obstacle pixels, see
/// [`tops::Window::pale_top`]) whatever its neighbours: the window judged is the part of the
/// cell that no neighbour's top reaches, and cover there whose floor-coloured rest is a pale
/// shade of it is a pale top standing on the cell, read partly as floor (since issue #29's
/// fourteenth round: on families A-F and K-Z, 22 half-covered cells free of doubt so, all
/// blocked in truth, none of the 93 free ones; 6 views more read exactly).
fn own_top_decides(
    leaned: bool,
    standing: impl FnOnce() -> bool,
    pale: impl FnOnce() -> bool,
) -> bool {
    (!leaned && standing()) || pale()
}

/// A blob of marks touching that does not split ([`blobs::split`]) may be one mark joined to
/// a thin strip of its colour: the rim of a shelf of a colour near a mark's (the shaded edges
/// and leaning tops of terracotta and walnut shelves read as the robots' red). Opened by
/// [`RIM`] of a median mark's width ([`blobs::opened`]), it leaves one piece of a mark's size
/// (from [`blobs::SMALL`] to 1.7 medians), and nothing else over [`blobs::NOISE`] of a mark:
/// that piece is the mark, the strip is dropped. Since issue #29's fourteenth round; until
/// then such a blob was refused as marks touching. Two marks joined by a thin bridge open into
/// two pieces and are still refused (when they do not split); a mark lost so leaves the view
/// with fewer robots than goals (or the reverse), which is refused.
fn off_rim(blob: &blobs::Blob, median: usize) -> Option<blobs::Blob> {
    let median = median.max(1) as f64;
    let r = (RIM * median.sqrt()).ceil().max(1.0) as u32;
    let pieces = blobs::opened(blob, r);
    let (first, rest) = pieces.split_first()?;
    let marks = first.area() as f64 / median;
    let specks = rest
        .iter()
        .all(|p| (p.area() as f64) < blobs::NOISE * median);
    ((blobs::SMALL..=1.7).contains(&marks) && specks).then(|| first.clone())
}

/// The radius of [`off_rim`]'s opening, in widths of a median mark (the square root of its
/// area; a disc's radius is 0.56 of it): strips up to about a quarter of a mark's width thick
/// are dropped ([`shelves::THIN`], the rims the shelves module takes for a shelf's).
const RIM: f64 = 0.15;

#[cfg(test)]
mod tests;
