//! Obstacles by their shape, whatever their colour.
//!
//! A shelf's colour may lie near the goals' (dark green, teal) or between a mark's and
//! another's (amber, yellow under warm light), so some or all of its pixels read as goal or
//! as a colour that cannot be told. Its shape tells what it is: it stands on whole cells and
//! fills them, while a goal is a mark inside one cell, and all goals of a view are alike.
//!
//! The same holds for shelves near the robots' colour (walnut brown, the shaded sides and
//! edges of safety-orange shelves): their pixels, or slivers of them, read as robot.
//!
//! So every 8-connected blob of goal, unsure, robot and obstacle pixels that holds some
//! goal, unsure or robot pixels is judged as a whole, less the robot-sized robot blobs in it
//! (from [`SLIVER`] to [`LARGER`] times the median robot of the view, taken over the robot
//! blobs that do not fill two cells on their own), and the larger robot blobs that
//! [`blobs::split`] separates into robots (robots touching): those stay robots and take no part in
//! the shape. A robot-sized blob at least [`SHELF_LONG`] times as long as wide that fills two
//! cells with its own pixels and does not split is a shelf of the robots' colour, and takes
//! part (since issue #29's twelfth round). The floor pixels it encloses count as its own (its holes: a brown or grey
//! top's specks whose colour, dimmed or desaturated, reads as floor, each with the blob's
//! pixels within [`HOLE`] of a cell on both sides along its row and its column; since issue
//! #29's eleventh round). It is an obstacle when it fills (at least [`FILLED`]
//! of the pixels of the middle [`INNER`] of each cell along both axes) two cells side by side,
//! of the grid or, since the eleventh round, of the grid shifted by quarters of a cell (a top
//! that leans off its own cells under a tilted camera fills the cells of a shifted grid; a
//! blob more than [`MARKS_LARGE`] marks of its colours large (the median goal taken without
//! the blobs that fill cells at [`FILLED`]), more than the touching marks that
//! [`blobs::split`] separates, fills them at [`LOOSE`]: a top whose colour reads as a mark's
//! over part of its width only), and it is at least [`LARGER`] times the median goal of the view (two goals touching fill
//! two cells only when each fills its own, and are then twice the median). Its pixels become
//! obstacle pixels, for the cells' coverage and for the blobs, but for goals joined to it
//! by a colour between or by the shelf's edge (its goal pixels that make a blob on their own
//! mostly outside the cells it fills), and, since the fourteenth round, for goals touching a
//! shelf of the goals' colour (one piece of goal pixels with it): the pieces that piece makes
//! outside the cells the blob fills that are a goal's size ([`GOAL_SIZED`]), solid
//! ([`SOLID`]) and at most [`BUMP_LONG`] elongated (not the end of a top leaning off its
//! cells); since the fifteenth round also those pieces, when not like a goal, opened by
//! [`BUMP_CORE`] of a goal's width: the goal-like pieces left whose hue is [`BUMP_HUE`] or
//! more from that of the shelf's goal pixels in its cells (a goal against the strip of a top
//! leaning off its cells, painted apart from the shelf).
//! Its robot-coloured pieces become obstacle pixels when less than [`GOAL_OUTSIDE`] of one
//! lies outside the cells it fills and they are far from a robot's size: under [`SLIVER`]
//! of the median robot (a sliver of the shelf's edge), or at least [`LARGER`] times it (a
//! shelf of the robots' colour; its pixels outside the filled cells stay robot pixels, and
//! are refused or read as before, but for the pieces of them that are the shelf's own: at
//! least [`LARGER`] robots large and not separated into robots by [`blobs::split`] (its top
//! leaning off its cells; since the fifteenth round, of such a piece opened as goals' are
//! above, the robot-like pieces painted apart from the shelf stay robots: a robot against
//! that top), or at most [`THIN`] of a robot's width thick (its rim); since issue #29's
//! eleventh round). Robot pixels turned so, from [`SWALLOWED`] pixels and a tenth
//! of a robot, are reported ([`Absorbed::swallowed`]): a robot against the shelf may be among
//! them, so a view with more goals than robots is then refused, rather than read without that
//! robot. A goal-coloured piece of a goal's size ([`GOAL_SIZED`]) and solid like a goal
//! ([`SOLID`]) stays a goal wherever it lies.
//! Otherwise nothing changes: the blob's goal pixels are goals, its unsure pixels are
//! refused as before.
//!
//! A blob mostly of a colour that cannot be told ([`ONE_CELL`]) may fill a single cell
//! instead of two: a shelf of one cell whose top reads between a mark's colour and another's
//! (since issue #29's thirtieth round), unless such blobs of its area abound (marks of such a
//! colour).
//!
//! Limit: a goal touching such a blob mostly inside the cells it fills (a goal against the
//! shelf's side, the grid shifted by its lean) is taken as part of it; when the view has as
//! many goals as robots the reading is then refused ("fewer goals than robots").
//!
//! Cost: O(pixels) to label the blobs, and O(pixels of the cells they touch) for the cells'
//! pixel counts when a blob is large.

use super::blobs::{self, column_row, Blob};
use super::colour::Class;
use super::homography::Homography;
use super::pixels::OUTSIDE;
use rayon::prelude::*;

/// The middle of a cell, along each axis, whose pixels a blob must fill.
pub const INNER: (f64, f64) = (0.1, 0.9);
/// The share of those pixels that fills it.
pub const FILLED: f64 = 0.85;
/// An obstacle blob is at least this many times the median goal.
pub const LARGER: f64 = 2.5;
/// A goal joined to an obstacle blob has at least this share of its pixels outside the
/// cells the blob fills.
pub const GOAL_OUTSIDE: f64 = 0.8;
/// A goal-coloured piece of an obstacle blob this large, in median goals, is a goal beside
/// the shelf, wherever it lies (a goal against a shelf's edge lies in the cells of a grid
/// shifted by the lean, T0019): a shelf's piece that size is then read as a goal more, and the
/// view refused for more goals than robots, not read without a goal.
pub const GOAL_SIZED: std::ops::Range<f64> = 0.5..1.7;
/// A goal-sized piece of a goal-coloured shelf's blob outside the cells it fills is a goal
/// against the shelf when at most this elongated ([`Blob::elongation`]): a goal is a disc, a
/// square, a cross or an ellipse (1.7), while the end of a shelf whose top leans off its cells
/// is a strip as wide as the shelf and a fraction of a cell deep (M0022: a strip read as a
/// goal stood for a goal hidden behind another shelf; issue #29's fourteenth round).
pub const BUMP_LONG: f64 = 1.8;
/// ... and at least this [`Blob::solidity`]: a goal is a solid disc or square, while the goal-coloured
/// specks of a shelf of a colour near the goals' are ragged (E0007's olive shelves: 0.51 at
/// most; goals 0.94 and more; since issue #29's twelfth round).
pub const SOLID: f64 = 0.7;
/// A piece of a goal-coloured shelf's blob outside the cells it fills that is not like a goal
/// is opened ([`blobs::opened`]) by this share of a median goal's width (the square root of
/// its area): a goal joined to the strip of the shelf's top that leans off those cells stays a
/// goal when the strip is thinner than about twice that and the goal's hue is apart from the
/// shelf's ([`BUMP_HUE`]; Q0020: a goal against a teal shelf's leaning top; issue #29's
/// fifteenth round).
pub const BUMP_CORE: f64 = 0.25;
/// ... by at least this many degrees between the medians of the opened piece's hue and of the
/// blob's goal-coloured pixels in the cells it fills: the end of the top (one paint, one
/// light) opens into pieces of the top's hue (within 0.5 degrees on families A-Z), a goal
/// painted apart is 12 degrees and more from it.
pub const BUMP_HUE: f64 = 6.0;
/// A robot-coloured piece of an obstacle blob under this share of the median robot is a
/// sliver of the shelf's edge or of its noise (a shelf of a colour near the robots': orange,
/// brown), not a robot.
pub const SLIVER: f64 = 0.3;
/// The fewest robot pixels turned into a shelf's that [`Absorbed::swallowed`] reports.
pub const SWALLOWED: usize = blobs::MIN_AREA;
/// A blob at least this many times the larger of the median robot and the median goal is
/// more than the most marks touching that `blobs::split` separates (4).
pub const MARKS_LARGE: f64 = 4.5;
/// A robot-sized blob at least this elongated ([`Blob::elongation`]) that fills two cells is
/// a shelf: a robot, a disc or a square, is 1 (a tall one leaning under a tilted camera a
/// little more), a shelf of two cells 2 or more.
pub const SHELF_LONG: f64 = 1.7;
/// The share of a cell's middle such a blob must fill, in two cells side by side.
pub const LOOSE: f64 = 0.5;
/// A robot-coloured piece left of a shelf at most this thick, in widths of a median robot
/// (the square root of its area; a robot's own thickness, a disc's radius, is 0.56 of it),
/// is the shelf's rim.
pub const THIN: f64 = 0.25;
/// How far (in cells) a floor pixel may lie from a blob's pixels on each side, along its
/// row and its column, and be a hole in it.
pub const HOLE: f64 = 0.15;

/// The 8-connected blobs of goal, unsure, robot and obstacle pixels that hold some goal,
/// unsure or robot pixels, as lists of pixel indices (in the order walked), in row-major order
/// of their first pixel. Each is grown from its first pixel of a goal, unsure or robot class, so that the
/// shelves of an obstacle's colour alone (most of a warehouse's) are never walked.
fn mixed_blobs(classes: &[u8], width: usize) -> Vec<Vec<usize>> {
    let height = classes.len() / width.max(1);
    let part = |c: u8| {
        c == Class::Goal as u8
            || c == Class::Unsure as u8
            || c == Class::Obstacle as u8
            || c == Class::Robot as u8
    };
    let seed = |c: u8| part(c) && c != Class::Obstacle as u8;
    let mut seen = vec![false; classes.len()];
    let mut out: Vec<(usize, Vec<usize>)> = Vec::new();
    let mut stack = Vec::new();
    const BLOCK: usize = 64;
    let mut next = 0;
    while next < classes.len() {
        let start = next;
        // Past a block of pixels none of which seeds a blob (one test without branches).
        if start % BLOCK == 0
            && start + BLOCK <= classes.len()
            && !classes[start..start + BLOCK]
                .iter()
                .fold(false, |any, &c| any | seed(c))
        {
            next += BLOCK;
            continue;
        }
        next += 1;
        if seen[start] || !seed(classes[start]) {
            continue;
        }
        seen[start] = true;
        stack.push(start);
        let mut pixels = Vec::new();
        let mut first = start;
        while let Some(i) = stack.pop() {
            pixels.push(i);
            first = first.min(i);
            let (x, y) = column_row(i, width);
            for ny in y.saturating_sub(1)..=(y + 1).min(height - 1) {
                for nx in x.saturating_sub(1)..=(x + 1).min(width - 1) {
                    let j = ny * width + nx;
                    if !seen[j] && part(classes[j]) {
                        seen[j] = true;
                        stack.push(j);
                    }
                }
            }
        }
        out.push((first, pixels));
    }
    out.sort_unstable_by_key(|(first, _)| *first);
    out.into_iter().map(|(_, pixels)| pixels).collect()
}

/// The cell (index) under pixel `i` of the grid shifted by `shift` (in cells), if any.
fn cell_of(
    i: usize,
    width: usize,
    image_to_floor: &Homography,
    (w, h): (u32, u32),
    shift: Shift,
) -> Option<usize> {
    let (x, y) = column_row(i, width);
    let (u, v) = image_to_floor.apply((x as f64 + 0.5, y as f64 + 0.5))?;
    let (u, v) = (u - shift.0, v - shift.1);
    (u >= 0.0 && v >= 0.0 && u < f64::from(w) && v < f64::from(h))
        .then(|| v.floor() as usize * w as usize + u.floor() as usize)
}

/// An offset of the grid, in cells along each axis: a shelf's top seen under a tilted camera
/// leans off its cells, and fills cells of a grid shifted by the lean.
pub(crate) type Shift = (f64, f64);
/// The grid itself.
pub(crate) const ALIGNED: Shift = (0.0, 0.0);
/// The shifts tried, in quarters of a cell, when a blob fills no two cells of the grid
/// itself: a top at most an eighth of a cell off one of them still fills the middles.
const SHIFT_STEPS: u32 = 4;

/// The cell (index) whose middle holds pixel `i`, if any.
pub(crate) fn inner_cell(
    i: usize,
    width: usize,
    image_to_floor: &Homography,
    floor: (u32, u32),
) -> Option<usize> {
    inner_cell_at(column_row(i, width), image_to_floor, floor, ALIGNED)
}

/// The cell (index) whose middle holds the pixel at column `x`, row `y`, if any.
fn inner_cell_at(
    (x, y): (usize, usize),
    image_to_floor: &Homography,
    (w, h): (u32, u32),
    shift: Shift,
) -> Option<usize> {
    let (x, y) = (x as f64 + 0.5, y as f64 + 0.5);
    let (u, v) = image_to_floor.apply((x, y))?;
    inner_cell_of((u - shift.0, v - shift.1), (w, h))
}

/// The cell (index) whose middle holds the floor point `(u, v)`, if any.
fn inner_cell_of((u, v): (f64, f64), (w, h): (u32, u32)) -> Option<usize> {
    if !(u >= 0.0 && v >= 0.0 && u < f64::from(w) && v < f64::from(h)) {
        return None;
    }
    // u and v are not negative: truncating is flooring (without a call to libm's floor).
    let (cu, cv) = (u as u64 as f64, v as u64 as f64);
    let inside = |f: f64| (INNER.0..=INNER.1).contains(&f);
    (inside(u - cu) && inside(v - cv)).then(|| cv as usize * w as usize + cu as usize)
}

/// The pixels of the floor in the middle of a cell, and the obstacle pixels among them,
/// counted over the cell's bounding box in the image.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct Middle {
    /// Pixels whose centre lies in the middle of the cell.
    pub pixels: u32,
    /// Obstacle pixels among them.
    pub obstacle: u32,
}

/// The [`Middle`] of `cell`, its counts remembered in `known`.
pub(crate) fn middle(
    known: &mut std::collections::BTreeMap<usize, Middle>,
    classes: &[u8],
    width: usize,
    maps: (&Homography, &Homography),
    floor: (u32, u32),
    cell: usize,
) -> Middle {
    middle_shifted(known, classes, width, maps, floor, (cell, ALIGNED))
}

/// The [`Middle`] of `cell` of the grid shifted by `shift`, its counts remembered in `known`
/// (for that shift alone).
fn middle_shifted(
    known: &mut std::collections::BTreeMap<usize, Middle>,
    classes: &[u8],
    width: usize,
    (floor_to_image, image_to_floor): (&Homography, &Homography),
    floor: (u32, u32),
    (cell, shift): (usize, Shift),
) -> Middle {
    if let Some(&m) = known.get(&cell) {
        return m;
    }
    let w = floor.0 as usize;
    let (fx, fy) = ((cell % w) as f64 + shift.0, (cell / w) as f64 + shift.1);
    let height = classes.len() / width.max(1);
    let mut out = Middle::default();
    let corners = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)]
        .map(|(a, b)| floor_to_image.apply((fx + a, fy + b)));
    if corners.iter().all(Option::is_some) {
        let (mut x0, mut y0, mut x1, mut y1) = (f64::INFINITY, f64::INFINITY, 0.0f64, 0.0f64);
        for (x, y) in corners.into_iter().flatten() {
            (x0, y0, x1, y1) = (x0.min(x), y0.min(y), x1.max(x), y1.max(y));
        }
        let clamp = |v: f64, n: usize| (v.max(0.0) as usize).min(n);
        let (x0, x1) = (
            clamp(x0.floor() - 1.0, width),
            clamp(x1.ceil() + 1.0, width),
        );
        let (y0, y1) = (
            clamp(y0.floor() - 1.0, height),
            clamp(y1.ceil() + 1.0, height),
        );
        // A view straight down along the image's axes: the points from a row and a column.
        let axes = image_to_floor.along_axes((x0, x1), (y0, y1));
        for y in y0..y1 {
            for x in x0..x1 {
                let c = classes[y * width + x];
                let inner = match &axes {
                    Some(axes) => {
                        let (u, v) = axes.at(x, y);
                        inner_cell_of((u - shift.0, v - shift.1), floor)
                    }
                    None => inner_cell_at((x, y), image_to_floor, floor, shift),
                };
                if c != OUTSIDE && inner == Some(cell) {
                    out.pixels += 1;
                    out.obstacle += u32::from(c == Class::Obstacle as u8);
                }
            }
        }
    }
    known.insert(cell, out);
    out
}

/// The cells a blob fills (the middles' counts remembered in `known`), when it fills two
/// side by side; else none.
fn filled_cells(
    pixels: &[usize],
    classes: &[u8],
    width: usize,
    maps: (&Homography, &Homography),
    floor: (u32, u32),
    known: &mut std::collections::BTreeMap<usize, Middle>,
) -> Vec<usize> {
    filled_shifted(
        pixels,
        classes,
        width,
        maps,
        floor,
        (known, ALIGNED, FILLED, false),
    )
}

/// The cells of the grid shifted by `shift` a blob fills, as [`filled_cells`] (`alone`: with
/// its own pixels only, not with the obstacle pixels beside them).
fn filled_shifted(
    pixels: &[usize],
    classes: &[u8],
    width: usize,
    maps: (&Homography, &Homography),
    floor: (u32, u32),
    share: (
        &mut std::collections::BTreeMap<usize, Middle>,
        Shift,
        f64,
        bool,
    ),
) -> Vec<usize> {
    let filled = filled_middles(pixels, classes, width, maps, floor, share);
    let w = floor.0 as usize;
    let side_by_side = filled.iter().any(|&c| {
        (c % w + 1 < w && filled.binary_search(&(c + 1)).is_ok())
            || filled.binary_search(&(c + w)).is_ok()
    });
    if side_by_side {
        filled
    } else {
        Vec::new()
    }
}

/// The cells of the grid shifted by `shift` whose middles a blob fills, one or more, side by
/// side or not (see [`filled_shifted`]), in increasing order.
fn filled_middles(
    pixels: &[usize],
    classes: &[u8],
    width: usize,
    maps: (&Homography, &Homography),
    floor: (u32, u32),
    (known, shift, share, alone): (
        &mut std::collections::BTreeMap<usize, Middle>,
        Shift,
        f64,
        bool,
    ),
) -> Vec<usize> {
    let image_to_floor = maps.1;
    // The blob's pixels other than obstacle pixels in the middle of each cell it holds, by
    // cell (the cells in increasing order).
    let mut count = rustc_hash::FxHashMap::<usize, u32>::default();
    for &i in pixels {
        if let Some(c) = inner_cell_at(column_row(i, width), image_to_floor, floor, shift) {
            *count.entry(c).or_insert(0) += u32::from(classes[i] != Class::Obstacle as u8);
        }
    }
    let mut held: Vec<(usize, u32)> = count.into_iter().collect();
    held.sort_unstable();
    // The obstacle pixels in the middles of those cells (the blob's own too) fill them.
    held.into_iter()
        .filter(|&(c, n)| {
            let m = middle_shifted(known, classes, width, maps, floor, (c, shift));
            let obstacle = if alone { 0 } else { m.obstacle };
            m.pixels > 0 && f64::from(n + obstacle) >= share * f64::from(m.pixels)
        })
        .map(|(c, _)| c)
        .collect()
}

/// What [`absorb`] did.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Absorbed {
    /// How many blobs it turned into obstacle pixels.
    pub turned: usize,
    /// Where (the image point, the centroid of the pixels) it first turned robot pixels
    /// into a shelf's, as many as a piece of a robot that is no noise (at least
    /// [`SWALLOWED`], and [`blobs::NOISE`] of a median robot): a robot standing against a
    /// shelf, its blob joined to the shelf's, or what a pale top leaning over it leaves of
    /// it, would be lost there without a word when the view has goals to spare, so such a
    /// view is refused (see `read_aerial_image`). Until issue #29's eleventh round a piece
    /// under [`SLIVER`] of a robot was taken as the shelf's without a word: C0004 lost a pale
    /// pink robot so, under a khaki top, once its other refusal was gone.
    pub swallowed: Option<(f64, f64)>,
}

/// Turns the blobs that are obstacles by their shape (see the module's comment) into
/// obstacle pixels.
pub fn absorb(
    classes: &mut [u8],
    width: usize,
    (floor_to_image, image_to_floor): (&Homography, &Homography),
    floor: (u32, u32),
    hue_of: &dyn Fn(usize) -> f64,
) -> Absorbed {
    let height = classes.len() / width.max(1);
    let mut out = Absorbed::default();
    let blobs_found = mixed_blobs(classes, width);
    // The areas of the blobs of a colour that cannot be told for the most part: a shelf of
    // such a colour may fill a single cell ([`ONE_CELL`]) unless blobs alike abound.
    let unsure_areas: Vec<usize> = blobs_found
        .iter()
        .filter(|b| mostly_unsure(b, classes))
        .map(Vec::len)
        .collect();
    let alike_abound = |n: usize| {
        unsure_areas
            .iter()
            .filter(|&&m| m * blobs::ALIKE >= n && m <= blobs::ALIKE * n)
            .count()
            >= ONE_CELL_ALIKE
    };
    // Only a blob at least two cells large can fill two.
    let cells = f64::from(floor.0) * f64::from(floor.1);
    let inside = classes
        .iter()
        .map(|&c| usize::from(c != OUTSIDE))
        .sum::<usize>() as f64;
    let two_cells = (2.0 * FILLED * (INNER.1 - INNER.0).powi(2) * inside / cells) as usize;
    let mut known = std::collections::BTreeMap::new();
    let maps = (floor_to_image, image_to_floor);
    let hole_px = ((HOLE * (inside / cells).sqrt()).round() as usize).max(1);
    // The robots' blobs: the median robot among those that do not fill two cells on their
    // own (a shelf of the robots' colour may; so may a robot 1.6 cells wide under a tilted
    // camera, but not most of a view's robots), and the pixels of the robot-sized ones
    // (from [`SLIVER`] to [`LARGER`] median robots), which stay robots and take no part in a
    // shelf's shape (a large robot touching a goal would otherwise fill two cells with it).
    let (robot_median, robot_sized, shelf_like) = {
        let found = blobs::find(classes, width, Class::Robot as u8);
        let index = |b: &blobs::Blob| -> Vec<usize> {
            b.pixels
                .iter()
                .map(|&(x, y)| y as usize * width + x as usize)
                .collect()
        };
        let robots: Vec<blobs::Blob> = found
            .iter()
            .filter(|b| {
                b.area() < two_cells
                    || filled_cells(&index(b), classes, width, maps, floor, &mut known).is_empty()
            })
            .cloned()
            .collect();
        let median = (robot_median_area(robots) as f64).max(blobs::MIN_AREA as f64);
        // One bit a pixel: robots (robot-sized, or separated into robots), and robot-sized
        // blobs at least [`SHELF_LONG`] times as long as wide that fill two cells on their
        // own and do not split into robots: shelves of the robots' colour (Q0003: terracotta
        // shelves, under box robots 1.6 cells wide, are 1.6 robots large; a robot that wide
        // nearly fills two cells' middles too, but it is as wide as long; issue #29's twelfth
        // round).
        let mut sized = vec![0u64; classes.len().div_ceil(64)];
        let mut shelf_like = vec![0u64; classes.len().div_ceil(64)];
        for b in &found {
            let robots = b.area() as f64 / median;
            let splits = || blobs::split(b, median as usize).is_some();
            let mut fills_two = || {
                b.area() >= two_cells && {
                    let pixels = index(b);
                    (0..(SHIFT_STEPS * SHIFT_STEPS) as usize).any(|k| {
                        let known = if k == 0 {
                            &mut known
                        } else {
                            &mut Default::default()
                        };
                        let share = (known, shift_of(k), FILLED, true);
                        !filled_shifted(&pixels, classes, width, maps, floor, share).is_empty()
                    })
                }
            };
            let bits = if (SLIVER..LARGER).contains(&robots) {
                if b.elongation() < SHELF_LONG || !fills_two() || splits() {
                    &mut sized
                } else {
                    &mut shelf_like
                }
            } else if robots >= LARGER && splits() {
                &mut sized
            } else {
                continue;
            };
            for i in index(b) {
                bits[i / 64] |= 1 << (i % 64);
            }
        }
        (median, sized, shelf_like)
    };
    // Each blob alone, on all cores (in the order found).
    let without_robots: Vec<Vec<usize>> = blobs_found
        .into_par_iter()
        .map(|b| {
            b.into_iter()
                .filter(|&i| robot_sized[i / 64] & (1 << (i % 64)) == 0)
                .collect::<Vec<usize>>()
        })
        .filter(|b| {
            // At [`LOOSE`], a blob that fills two cells may be smaller; one of a colour that
            // cannot be told may fill one cell ([`ONE_CELL`]): [`FILLED`] of one cell's
            // worth, the obstacle pixels beside it counting too.
            let least = if mostly_unsure(b, classes) {
                FILLED / 2.0 * two_cells as f64
            } else {
                LOOSE / FILLED * two_cells as f64
            };
            b.len() as f64 >= least && b.iter().any(|&i| classes[i] != Class::Obstacle as u8)
        })
        .map(|b| with_holes(b, classes, width, hole_px))
        .collect();
    if without_robots.is_empty() {
        return out;
    }
    // Each blob with the cells it fills, of the grid itself or else of the first shifted
    // grid whose cells it fills; then a blob larger than the most marks touching that
    // `blobs::split` separates fills them at [`LOOSE`] (a top whose colour reads as a mark's
    // over part of its width only). Marks are measured for that without the blobs that fill
    // cells at [`FILLED`]: the shelves of a colour near the goals' break into specks of goal
    // pixels, and the median goal could be such a speck, several goals large (E0007: an olive
    // shelf ten goals large was then not large; issue #29's twelfth round).
    // The first of the shifted grids (from the grid itself, `k` = 0, when `from_aligned`) whose
    // cells the blob fills. The cells' middles are remembered, one map a shifted grid (`known`:
    // a middle does not depend on what asked for it first).
    let steps = (SHIFT_STEPS * SHIFT_STEPS) as usize;
    type Known = std::collections::BTreeMap<usize, Middle>;
    // `fill` is `filled_shifted` (two cells side by side) or `filled_middles` (one or more).
    type Fill = fn(
        &[usize],
        &[u8],
        usize,
        (&Homography, &Homography),
        (u32, u32),
        (&mut Known, Shift, f64, bool),
    ) -> Vec<usize>;
    let fills_with = |fill: Fill,
                      known: &mut [Known],
                      b: &[usize],
                      classes: &[u8],
                      from_aligned: bool,
                      share: f64| {
        (usize::from(!from_aligned)..steps).find_map(|k| {
            let shift = shift_of(k);
            let cells = fill(
                b,
                classes,
                width,
                maps,
                floor,
                (&mut known[k], shift, share, false),
            );
            (!cells.is_empty()).then_some((cells, shift))
        })
    };
    let fills =
        |known: &mut [Known], b: &[usize], classes: &[u8], from_aligned: bool, share: f64| {
            fills_with(filled_shifted, known, b, classes, from_aligned, share)
        };
    // Each blob alone, on all cores (in the order found).
    let firm: Vec<Option<(Vec<usize>, Shift)>> = {
        let classes = &*classes;
        without_robots
            .par_iter()
            .map_init(
                || (Known::new(), vec![Known::new(); steps]),
                |(known, shifted), b| {
                    let aligned = filled_cells(b, classes, width, maps, floor, known);
                    if !aligned.is_empty() {
                        return Some((aligned, ALIGNED));
                    }
                    fills(shifted, b, classes, false, FILLED).or_else(|| {
                        // A shelf of a colour that cannot be told over one cell.
                        if !mostly_unsure(b, classes) || alike_abound(b.len()) {
                            return None;
                        }
                        fills_with(filled_middles, shifted, b, classes, true, FILLED)
                    })
                },
            )
            .collect()
    };
    let mut loose = vec![Known::new(); steps];
    let firm_ones: Vec<bool> = firm.iter().map(Option::is_some).collect();
    let goal_median = goal_median_without(classes, width, &without_robots, &firm_ones);
    // The marks a blob is measured against: those of the colours that make at least a tenth
    // of its mark-coloured pixels (a goal-coloured shelf against the goals, when the robots
    // are five times larger, E0007), or both.
    let mark = |b: &[usize]| {
        let robot = b
            .iter()
            .filter(|&&i| classes[i] == Class::Robot as u8)
            .count() as f64;
        let goal = b
            .iter()
            .filter(|&&i| classes[i] == Class::Goal as u8)
            .count() as f64;
        let some = |n: f64| n >= 0.1 * (robot + goal);
        match (some(robot) && robot > 0.0, some(goal) && goal > 0.0) {
            (true, false) => robot_median,
            (false, true) => goal_median as f64,
            _ => robot_median.max(goal_median as f64),
        }
    };
    let shaped: Vec<(&Vec<usize>, Vec<usize>, Shift)> = without_robots
        .iter()
        .zip(firm)
        .filter_map(|(b, firm)| {
            let found = firm.or_else(|| {
                (b.len() as f64 >= MARKS_LARGE * mark(b))
                    .then(|| fills(&mut loose, b, classes, true, LOOSE))
                    .flatten()
            });
            found.map(|(cells, shift)| (b, cells, shift))
        })
        .collect();
    if shaped.is_empty() {
        return out;
    }
    // The median goal among the goal pixels outside those blobs.
    let taken: Vec<bool> = without_robots
        .iter()
        .map(|b| shaped.iter().any(|(s, _, _)| std::ptr::eq(*s, b)))
        .collect();
    let median = goal_median_without(classes, width, &without_robots, &taken);
    for (b, cells, shift) in shaped {
        if (b.len() as f64) < LARGER * median as f64 {
            continue;
        }
        let in_filled = |i: usize| {
            cell_of(i, width, image_to_floor, floor, shift)
                .is_some_and(|c| cells.binary_search(&c).is_ok())
        };
        let goals = marks_within(
            classes,
            width,
            b,
            Class::Goal,
            &in_filled,
            &|piece, outside| {
                let goals = piece.len() as f64 / median.max(1) as f64;
                let solid = || Blob::from_indices(piece, width).solidity() >= SOLID;
                if outside >= GOAL_OUTSIDE || (GOAL_SIZED.contains(&goals) && solid()) {
                    Keep::All
                } else if outside > 0.0 {
                    Keep::MarksOutside
                } else {
                    Keep::None
                }
            },
            Some((
                median.max(1) as f64,
                &ShelfPaint::new(b, Class::Goal, classes, &in_filled, hue_of),
            )),
        );
        let robots = marks_within(
            classes,
            width,
            b,
            Class::Robot,
            &in_filled,
            &|piece, outside| {
                // A piece that is mostly a robot-sized shelf of the robots' colour counts as
                // one larger than robots.
                let shelf = piece
                    .iter()
                    .filter(|&&i| shelf_like[i / 64] & (1 << (i % 64)) != 0)
                    .count();
                let robots = if 2 * shelf >= piece.len() {
                    LARGER
                } else {
                    piece.len() as f64 / robot_median
                };
                robot_piece(robots, outside)
            },
            None,
        );
        // A robot joined to a shelf of the robots' colour, told by its paint (as goals above).
        let robots = without_shelf_pieces(
            robots,
            (width, height),
            robot_median,
            &ShelfPaint::new(b, Class::Robot, classes, &in_filled, hue_of),
        );
        // The robot pixels turned, if a robot's worth: a robot may stand against the shelf.
        let (mut sum, mut n) = ((0.0, 0.0), 0usize);
        for &i in b {
            if goals.binary_search(&i).is_err() && robots.binary_search(&i).is_err() {
                if classes[i] == Class::Robot as u8 {
                    let (x, y) = column_row(i, width);
                    sum = (sum.0 + x as f64 + 0.5, sum.1 + y as f64 + 0.5);
                    n += 1;
                }
                classes[i] = Class::Obstacle as u8;
            }
        }
        if n >= SWALLOWED.max((blobs::NOISE * robot_median) as usize) && out.swallowed.is_none() {
            out.swallowed = Some((sum.0 / n as f64, sum.1 / n as f64));
        }
        out.turned += 1;
    }
    out
}

/// A blob of which a colour that cannot be told makes at least this share of the pixels that
/// are not floor (its holes), and at least [`ONE_CELL_MARKS`] times its mark-coloured ones, is
/// mostly of such a colour ([`mostly_unsure`]). Such a blob that fills a single cell (at
/// [`FILLED`], of the grid or of a shifted one) is an obstacle as one filling two is: a shelf of
/// one cell whose top reads between a mark's colour and another's (cartons of brown or beige
/// card, an olive or tan top; since issue #29's thirtieth round). A mark of such a colour as
/// large as a cell is lost to it, and the count of goals against robots refuses the view; the
/// robots of a view whose robots all read so (families w and x: large cylinders of a colour
/// between) are many blobs alike, so a blob with [`ONE_CELL_ALIKE`] such blobs of its area
/// (within [`blobs::ALIKE`], itself among them) is left as it is.
pub const ONE_CELL: f64 = 0.25;
/// ... see [`ONE_CELL`].
pub const ONE_CELL_MARKS: usize = 2;
/// ... see [`ONE_CELL`].
pub const ONE_CELL_ALIKE: usize = 3;

/// Whether a blob (pixel indices) is mostly of a colour that cannot be told ([`ONE_CELL`]).
fn mostly_unsure(b: &[usize], classes: &[u8]) -> bool {
    let (mut unsure, mut marks, mut solid) = (0usize, 0usize, 0usize);
    for &i in b {
        let c = classes[i];
        unsure += usize::from(c == Class::Unsure as u8);
        marks += usize::from(c == Class::Goal as u8 || c == Class::Robot as u8);
        solid += usize::from(c != Class::Floor as u8);
    }
    unsure > 0 && unsure >= ONE_CELL_MARKS * marks && unsure as f64 >= ONE_CELL * solid as f64
}

/// The `k`-th grid shifted by quarters of a cell ([`SHIFT_STEPS`]), row-major from the
/// grid itself (`k` = 0).
fn shift_of(k: usize) -> Shift {
    let step = f64::from(SHIFT_STEPS);
    (
        (k % SHIFT_STEPS as usize) as f64 / step,
        (k / SHIFT_STEPS as usize) as f64 / step,
    )
}

/// The median goal (as [`blobs::sort`] takes it) among the goal pixels outside the blobs
/// `taken` (one flag a blob). Those blobs' goal pixels are set aside for the search and given
/// back.
fn goal_median_without(
    classes: &mut [u8],
    width: usize,
    blobs_found: &[Vec<usize>],
    taken: &[bool],
) -> usize {
    // The blobs' pixels on all cores (the set, not its order, matters).
    let hidden: Vec<usize> = {
        let classes = &*classes;
        blobs_found
            .par_iter()
            .zip(taken)
            .filter(|(_, &t)| t)
            .flat_map_iter(|(b, _)| b.iter().copied())
            .filter(|&i| classes[i] == Class::Goal as u8)
            .collect()
    };
    for &i in &hidden {
        classes[i] = OUTSIDE;
    }
    let median = blobs::sort(blobs::find(classes, width, Class::Goal as u8)).median_area;
    for &i in &hidden {
        classes[i] = Class::Goal as u8;
    }
    median
}

/// Floor pixels enclosed by a blob: with a pixel of the blob or an obstacle pixel within
/// `reach` on both sides along its row and along its column (the specks of a shelf's top whose
/// colour, dimmed or desaturated, reads as floor). Returns the blob's pixels and those, in
/// increasing order.
fn with_holes(blob: Vec<usize>, classes: &[u8], width: usize, reach: usize) -> Vec<usize> {
    let Some((x0, y0, x1, y1)) = blob
        .iter()
        .fold(None::<(usize, usize, usize, usize)>, |b, &i| {
            let (x, y) = column_row(i, width);
            Some(match b {
                None => (x, y, x, y),
                Some((a, b, c, d)) => (a.min(x), b.min(y), c.max(x), d.max(y)),
            })
        })
    else {
        return blob;
    };
    let (bw, bh) = (x1 - x0 + 1, y1 - y0 + 1);
    let mut solid = vec![false; bw * bh];
    for &i in &blob {
        let (x, y) = column_row(i, width);
        solid[(y - y0) * bw + (x - x0)] = true;
    }
    for y in 0..bh {
        for x in 0..bw {
            let c = classes[(y + y0) * width + x + x0];
            solid[y * bw + x] |= c == Class::Obstacle as u8;
        }
    }
    // Running counts of solid pixels along each row and each column.
    let mut rows = vec![0u32; (bw + 1) * bh];
    let mut cols = vec![0u32; bw * (bh + 1)];
    for y in 0..bh {
        for x in 0..bw {
            let s = u32::from(solid[y * bw + x]);
            rows[y * (bw + 1) + x + 1] = rows[y * (bw + 1) + x] + s;
            cols[(y + 1) * bw + x] = cols[y * bw + x] + s;
        }
    }
    let mut out = blob;
    for y in 0..bh {
        for x in 0..bw {
            let i = (y + y0) * width + x + x0;
            if solid[y * bw + x] || classes[i] != Class::Floor as u8 {
                continue;
            }
            let row = |a: usize, b: usize| rows[y * (bw + 1) + b] - rows[y * (bw + 1) + a];
            let col = |a: usize, b: usize| cols[b * bw + x] - cols[a * bw + x];
            let enclosed = row(x.saturating_sub(reach), x) > 0
                && row(x + 1, (x + 1 + reach).min(bw)) > 0
                && col(y.saturating_sub(reach), y) > 0
                && col(y + 1, (y + 1 + reach).min(bh)) > 0;
            if enclosed {
                out.push(i);
            }
        }
    }
    out.sort_unstable();
    out
}

/// The median area of robot blobs, as [`blobs::sort`] takes it.
fn robot_median_area(robots: Vec<blobs::Blob>) -> usize {
    blobs::sort(robots).median_area
}

/// Which pixels of a piece of a mark's colour within an obstacle blob stay the mark's.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Keep {
    /// All of them.
    All,
    /// Those outside the cells the blob fills.
    Outside,
    /// Those outside the cells the blob fills that make, among themselves, pieces like a
    /// mark (a goal against a goal-coloured shelf, joined to it in one piece of the goals'
    /// colour).
    MarksOutside,
    /// None: the piece is part of the obstacle.
    None,
}

/// A robot-coloured piece of an obstacle blob (its area in median robots, and the share of
/// it outside the cells the blob fills): a robot when at least [`GOAL_OUTSIDE`] of it is
/// outside; else a shelf of the robots' colour when at least [`LARGER`] robots large (its
/// pixels outside the filled cells stay robot-coloured, a robot touching the shelf among
/// them: they are refused or read as before), a sliver of the shelf's edge or noise when
/// under [`SLIVER`] of a robot, and otherwise a robot partly hidden, kept whole.
fn robot_piece(robots: f64, outside: f64) -> Keep {
    if outside >= GOAL_OUTSIDE {
        Keep::All
    } else if robots >= LARGER {
        Keep::Outside
    } else if robots < SLIVER {
        Keep::None
    } else {
        Keep::All
    }
}

/// A shelf's paint: the median hue of its blob's pixels of one class in the cells it fills,
/// found when first asked ([`ShelfPaint::apart`]).
struct ShelfPaint<'a> {
    blob: &'a [usize],
    class: Class,
    classes: &'a [u8],
    in_filled: &'a dyn Fn(usize) -> bool,
    hue_of: &'a dyn Fn(usize) -> f64,
    hue: std::cell::OnceCell<Option<f64>>,
}

impl<'a> ShelfPaint<'a> {
    fn new(
        blob: &'a [usize],
        class: Class,
        classes: &'a [u8],
        in_filled: &'a dyn Fn(usize) -> bool,
        hue_of: &'a dyn Fn(usize) -> f64,
    ) -> ShelfPaint<'a> {
        ShelfPaint {
            blob,
            class,
            classes,
            in_filled,
            hue_of,
            hue: std::cell::OnceCell::new(),
        }
    }

    /// Whether pixels are painted apart from the shelf: their median hue at least
    /// [`BUMP_HUE`] from its paint's.
    fn apart(&self, piece: &[usize]) -> bool {
        let shelf = *self.hue.get_or_init(|| {
            median_hue(
                self.blob
                    .iter()
                    .copied()
                    .filter(|&i| self.classes[i] == self.class as u8 && (self.in_filled)(i)),
                self.hue_of,
            )
        });
        hues_apart(median_hue(piece.iter().copied(), self.hue_of), shelf)
    }
}

/// Whether a blob is like one mark of `median` pixels: its size ([`GOAL_SIZED`] medians),
/// solid ([`SOLID`]) and at most [`BUMP_LONG`] elongated.
fn like_a_mark(blob: &Blob, median: f64) -> bool {
    GOAL_SIZED.contains(&(blob.area() as f64 / median))
        && blob.solidity() >= SOLID
        && blob.elongation() <= BUMP_LONG
}

/// The marks of `median` pixels within a blob of their colour joined to a shelf's top that
/// leans off its cells: the blob opened by [`BUMP_CORE`] of a mark's width (the strip of the
/// top drops), the pieces left like a mark ([`like_a_mark`]) and painted apart from the
/// shelf; their pixels.
fn opened_marks(blob: &Blob, median: f64, width: usize, paint: &ShelfPaint) -> Vec<usize> {
    let r = (BUMP_CORE * median.sqrt()).ceil() as u32;
    let mut out = Vec::new();
    for core in blobs::opened(blob, r) {
        if like_a_mark(&core, median) {
            let core = indices(&core, width);
            if paint.apart(&core) {
                out.extend(core);
            }
        }
    }
    out
}

/// The pixels of the marks of class `class` within a blob: its pixels of that class split
/// into 8-connected pieces among themselves, each kept as `keep(area, share outside the
/// cells the blob fills)` says. Goals are kept with at least [`GOAL_OUTSIDE`] of them
/// outside (a goal joined to a shelf by pixels of a colour between: blur mixes a goal's
/// green with a shelf's yellow).
fn marks_within(
    classes: &[u8],
    width: usize,
    blob: &[usize],
    class: Class,
    in_filled: &dyn Fn(usize) -> bool,
    keep: &dyn Fn(&[usize], f64) -> Keep,
    bumps: Option<(f64, &ShelfPaint)>,
) -> Vec<usize> {
    // The blob's pixels of that class, sorted, split into 8-connected pieces among themselves.
    let mut marked: Vec<usize> = blob
        .iter()
        .copied()
        .filter(|&i| classes[i] == class as u8)
        .collect();
    marked.sort_unstable();
    let mut kept = Vec::new();
    let height = classes.len() / width.max(1);
    for piece in blobs::pieces(&marked, width, classes.len() / width.max(1)) {
        let outside = piece.iter().filter(|&&i| !in_filled(i)).count();
        let share = outside as f64 / piece.len() as f64;
        match keep(&piece, share) {
            Keep::All => kept.extend(piece),
            Keep::Outside => kept.extend(piece.into_iter().filter(|&i| !in_filled(i))),
            Keep::MarksOutside => {
                let Some((median, paint)) = bumps else {
                    continue;
                };
                let mut outside: Vec<usize> =
                    piece.into_iter().filter(|&i| !in_filled(i)).collect();
                outside.sort_unstable();
                for sub in blobs::pieces(&outside, width, height) {
                    let sub_blob = Blob::from_indices(&sub, width);
                    if like_a_mark(&sub_blob, median) {
                        kept.extend(sub);
                    } else {
                        // A goal joined to the strip of the shelf's top that leans off the
                        // cells it fills.
                        kept.extend(opened_marks(&sub_blob, median, width, paint));
                    }
                }
            }
            Keep::None => {}
        }
    }
    kept.sort_unstable();
    kept
}

/// The median hue (degrees) of some pixels; `None` for none. The hues of one paint lie within
/// a few degrees, far from 0/360 for the goals' green (the median is taken on the line).
fn median_hue(pixels: impl Iterator<Item = usize>, hue_of: &dyn Fn(usize) -> f64) -> Option<f64> {
    let mut h: Vec<f64> = pixels.map(hue_of).collect();
    if h.is_empty() {
        return None;
    }
    let mid = h.len() / 2;
    Some(*h.select_nth_unstable_by(mid, f64::total_cmp).1)
}

/// Whether two median hues (degrees) are at least [`BUMP_HUE`] apart on the circle; not when
/// either is missing.
fn hues_apart(a: Option<f64>, b: Option<f64>) -> bool {
    match (a, b) {
        (Some(a), Some(b)) => {
            let d = (a - b).abs() % 360.0;
            d.min(360.0 - d) >= BUMP_HUE
        }
        _ => false,
    }
}

/// A blob's pixels as indices in an image `width` pixels wide.
fn indices(blob: &Blob, width: usize) -> Vec<usize> {
    blob.pixels
        .iter()
        .map(|&(x, y)| y as usize * width + x as usize)
        .collect()
}

/// The robot pixels kept in a shelf's blob (sorted), less the pieces (8-connected among
/// themselves) that are the shelf's own: those at least [`LARGER`] median robots large that
/// [`blobs::split`] does not separate into robots (no robot is that large: the shelf's top
/// leaning off the cells it fills), and those at most [`THIN`] of a median robot's width
/// thick (its rim, where the colours averaged over a square mix the shelf's with the floor's).
fn without_shelf_pieces(
    kept: Vec<usize>,
    (width, height): (usize, usize),
    median: f64,
    paint: &ShelfPaint,
) -> Vec<usize> {
    let mut out = Vec::with_capacity(kept.len());
    for piece in blobs::pieces(&kept, width, height) {
        let blob = blobs::Blob::from_indices(&piece, width);
        let large = piece.len() as f64 >= LARGER * median;
        if large && blobs::split(&blob, median as usize).is_none() {
            // A robot standing against the shelf's leaning top, painted apart from it.
            out.extend(opened_marks(&blob, median.max(1.0), width, paint));
            continue;
        }
        if blobs::thickness(&blob) <= (THIN * median.sqrt()).max(1.0) {
            continue;
        }
        out.extend(piece);
    }
    out.sort_unstable();
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::aerial::tests::paint;

    /// Every pixel's hue: one paint.
    fn one_hue(_: usize) -> f64 {
        120.0
    }

    /// A 4 × 2-cell floor, 10 px per cell, straight down: floor → image, image → floor.
    fn floor() -> (Homography, Homography, Vec<u8>) {
        let to_image = Homography::floor_to_image(
            4.0,
            2.0,
            [(0.0, 0.0), (40.0, 0.0), (40.0, 20.0), (0.0, 20.0)],
        )
        .unwrap();
        (
            to_image,
            to_image.inverse().unwrap(),
            vec![Class::Floor as u8; 40 * 20],
        )
    }

    #[test]
    fn a_goal_coloured_shelf_over_two_cells_is_an_obstacle() {
        let (to_image, to_floor, mut classes) = floor();
        // Goals 4 px wide in cells (3, 0) and (3, 1); a shelf over cells (0, 0) and (1, 0),
        // goal-coloured with some unsure pixels.
        paint(&mut classes, 40, (33, 3, 37, 7), Class::Goal);
        paint(&mut classes, 40, (33, 13, 37, 17), Class::Goal);
        paint(&mut classes, 40, (1, 1, 19, 9), Class::Goal);
        paint(&mut classes, 40, (5, 2, 7, 4), Class::Unsure);
        assert_eq!(
            absorb(&mut classes, 40, (&to_image, &to_floor), (4, 2), &one_hue).turned,
            1
        );
        assert_eq!(classes[5 * 40 + 10], Class::Obstacle as u8);
        assert_eq!(classes[5 * 40 + 35], Class::Goal as u8);
    }

    #[test]
    fn a_speckled_shelf_is_an_obstacle_but_goals_a_pixel_apart_are_not_one() {
        let (to_image, to_floor, mut classes) = floor();
        // Goals in cells (3, 0) and (3, 1); a goal-coloured shelf over cells (0, 0) and
        // (1, 0) whose every third pixel in every other row reads as floor: a fifth of its
        // middles, so they are filled only with its holes.
        paint(&mut classes, 40, (33, 3, 37, 7), Class::Goal);
        paint(&mut classes, 40, (33, 13, 37, 17), Class::Goal);
        paint(&mut classes, 40, (1, 1, 19, 9), Class::Goal);
        for y in (1..9).step_by(2) {
            for x in (1..19).step_by(3) {
                classes[y * 40 + x] = Class::Floor as u8;
            }
        }
        let shelf: Vec<usize> = (0..40 * 10)
            .filter(|&i| i % 40 < 20 && classes[i] == Class::Goal as u8)
            .collect();
        let maps = (&to_image, &to_floor);
        let mut known = std::collections::BTreeMap::new();
        let filled =
            |b: &[usize], known: &mut _| filled_cells(b, &classes, 40, maps, (4, 2), known);
        assert!(filled(&shelf, &mut known).is_empty());
        let whole = with_holes(shelf.clone(), &classes, 40, 1);
        // The 24 specks less the 9 on its first row and column (open on one side).
        assert_eq!(whole.len(), shelf.len() + 15);
        assert_eq!(filled(&whole, &mut known), vec![0, 1]);
        assert_eq!(
            absorb(&mut classes, 40, (&to_image, &to_floor), (4, 2), &one_hue).turned,
            1
        );
        assert_eq!(
            classes[3 * 40 + 4],
            Class::Obstacle as u8,
            "a hole turns too"
        );
        assert_eq!(classes[5 * 40 + 35], Class::Goal as u8);
        // Two goals side by side, two pixels apart, are not filled in between: the gap is
        // not closed along its column.
        let (_, _, mut classes) = floor();
        paint(&mut classes, 40, (2, 2, 8, 8), Class::Goal);
        paint(&mut classes, 40, (10, 2, 16, 8), Class::Goal);
        let blob: Vec<usize> = (0..classes.len())
            .filter(|&i| classes[i] == Class::Goal as u8)
            .collect();
        assert_eq!(with_holes(blob.clone(), &classes, 40, 1), blob);
        assert_eq!(with_holes(blob.clone(), &classes, 40, 3), blob);
    }

    #[test]
    fn a_top_leaning_half_a_cell_off_its_cells_fills_cells_of_a_shifted_grid() {
        let (to_image, to_floor, mut classes) = floor();
        // Goals in cells (3, 0) and (3, 1); a goal-coloured top from 0.6 to 2.4 cells across:
        // it fills the middle of cell (1, 0) alone, and of two cells of the grid shifted by
        // half a cell.
        paint(&mut classes, 40, (33, 3, 37, 7), Class::Goal);
        paint(&mut classes, 40, (33, 13, 37, 17), Class::Goal);
        paint(&mut classes, 40, (6, 1, 24, 9), Class::Goal);
        let top: Vec<usize> = (0..40 * 10)
            .filter(|&i| i % 40 < 30 && classes[i] == Class::Goal as u8)
            .collect();
        let maps = (&to_image, &to_floor);
        let mut known = std::collections::BTreeMap::new();
        assert!(filled_cells(&top, &classes, 40, maps, (4, 2), &mut known).is_empty());
        let mut known = std::collections::BTreeMap::new();
        let half = filled_shifted(
            &top,
            &classes,
            40,
            maps,
            (4, 2),
            (&mut known, (0.5, 0.0), FILLED, false),
        );
        assert_eq!(half, vec![0, 1]);
        assert_eq!(absorb(&mut classes, 40, maps, (4, 2), &one_hue).turned, 1);
        assert_eq!(classes[5 * 40 + 7], Class::Obstacle as u8);
        assert_eq!(classes[5 * 40 + 35], Class::Goal as u8);
    }

    #[test]
    fn a_top_read_as_a_mark_over_part_of_its_width_is_an_obstacle_when_no_marks_are_that_large() {
        // Goals of 16 px in cells (2, 0), (2, 1), (3, 0) and (3, 1); a goal-coloured band over
        // cells (0, 0) and (1, 0), rows 1–5 only (the rest of the top reads as floor): 5 of the
        // 8 rows of each middle, 90 px, over 4.5 goals.
        let goals = |classes: &mut Vec<u8>| {
            for (x, y) in [(23, 3), (23, 13), (33, 3), (33, 13)] {
                paint(classes, 40, (x, y, x + 4, y + 4), Class::Goal);
            }
        };
        let (to_image, to_floor, mut classes) = floor();
        goals(&mut classes);
        paint(&mut classes, 40, (1, 1, 19, 6), Class::Goal);
        assert_eq!(
            absorb(&mut classes, 40, (&to_image, &to_floor), (4, 2), &one_hue).turned,
            1
        );
        assert_eq!(classes[3 * 40 + 10], Class::Obstacle as u8);
        assert_eq!(classes[5 * 40 + 35], Class::Goal as u8);
        // The same band 12 px long (60 px, under 4.5 goals): goals touching, left as they are.
        let (to_image, to_floor, mut classes) = floor();
        goals(&mut classes);
        paint(&mut classes, 40, (4, 1, 16, 6), Class::Goal);
        let before = classes.clone();
        assert_eq!(
            absorb(&mut classes, 40, (&to_image, &to_floor), (4, 2), &one_hue).turned,
            0
        );
        assert_eq!(classes, before);
    }

    #[test]
    fn robots_touching_that_split_are_no_shelf() {
        let (to_image, to_floor, mut classes) = floor();
        // Two robots of 64 px in row 1; three in row 0, joined by bridges two pixels long,
        // filling the middles of cells (0, 0), (1, 0) and (2, 0): three times a robot, so no
        // robot-sized blob, but one that splits into three.
        paint(&mut classes, 40, (1, 11, 9, 19), Class::Robot);
        paint(&mut classes, 40, (21, 11, 29, 19), Class::Robot);
        for x0 in [1, 11, 21] {
            paint(&mut classes, 40, (x0, 1, x0 + 8, 9), Class::Robot);
        }
        paint(&mut classes, 40, (9, 5, 11, 6), Class::Robot);
        paint(&mut classes, 40, (19, 5, 21, 6), Class::Robot);
        let before = classes.clone();
        assert_eq!(
            absorb(&mut classes, 40, (&to_image, &to_floor), (4, 2), &one_hue).turned,
            0
        );
        assert_eq!(classes, before);
    }

    #[test]
    fn a_goal_against_a_goal_coloured_shelf_stays_a_goal() {
        let (to_image, to_floor, mut classes) = floor();
        // Goals of 16 px in cells (3, 0) and (3, 1); a goal-coloured shelf over cells (0, 0)
        // and (1, 0), rows 1–7, joined by a row of a colour between to a goal of 16 px below
        // it, a quarter of it in the shelf's cells: a goal's size, so a goal.
        paint(&mut classes, 40, (33, 3, 37, 7), Class::Goal);
        paint(&mut classes, 40, (33, 13, 37, 17), Class::Goal);
        paint(&mut classes, 40, (1, 1, 19, 8), Class::Goal);
        paint(&mut classes, 40, (8, 8, 12, 9), Class::Unsure);
        paint(&mut classes, 40, (8, 9, 12, 13), Class::Goal);
        assert_eq!(
            absorb(&mut classes, 40, (&to_image, &to_floor), (4, 2), &one_hue).turned,
            1
        );
        assert_eq!(classes[5 * 40 + 5], Class::Obstacle as u8);
        assert_eq!(classes[11 * 40 + 10], Class::Goal as u8);
    }

    #[test]
    fn a_goal_against_a_goal_coloured_shelf_in_one_piece_stays_a_goal() {
        let (to_image, to_floor, mut classes) = floor();
        // Goals of 36 px in cells (3, 0) and (3, 1); a goal-coloured shelf over cells (0, 0)
        // and (1, 0), rows 1–8, and a goal of 36 px against it, one piece of the goals' colour
        // with it, a row of it in the shelf's cells: the piece outside is a goal's (issue #29's
        // fourteenth round: X0031, E0005).
        paint(&mut classes, 40, (33, 2, 39, 8), Class::Goal);
        paint(&mut classes, 40, (33, 12, 39, 18), Class::Goal);
        paint(&mut classes, 40, (1, 1, 19, 9), Class::Goal);
        paint(&mut classes, 40, (7, 9, 13, 15), Class::Goal);
        assert_eq!(
            absorb(&mut classes, 40, (&to_image, &to_floor), (4, 2), &one_hue).turned,
            1
        );
        assert_eq!(classes[5 * 40 + 5], Class::Obstacle as u8);
        assert_eq!(classes[12 * 40 + 10], Class::Goal as u8);
    }

    #[test]
    fn the_end_of_a_goal_coloured_top_past_its_cells_is_no_goal() {
        let (to_image, to_floor, mut classes) = floor();
        // As above, but past the shelf's cells a strip as wide as the shelf, 4 px deep, as a
        // top leaning off its cells shows: a goal's size and solid, but no goal's shape
        // (M0022: such a strip stood for a goal hidden elsewhere).
        paint(&mut classes, 40, (33, 2, 39, 8), Class::Goal);
        paint(&mut classes, 40, (33, 12, 39, 18), Class::Goal);
        paint(&mut classes, 40, (1, 1, 19, 9), Class::Goal);
        paint(&mut classes, 40, (3, 9, 15, 14), Class::Goal);
        absorb(&mut classes, 40, (&to_image, &to_floor), (4, 2), &one_hue);
        assert_eq!(classes[5 * 40 + 5], Class::Obstacle as u8);
        assert_eq!(classes[11 * 40 + 8], Class::Obstacle as u8);
    }

    /// Goals of 36 px in cells (3, 0) and (3, 1); a goal-coloured shelf over cells (0, 0) and
    /// (1, 0), rows 1–8, its top leaning off them in a strip 2 px deep past row 9, and a goal
    /// of 36 px against that strip, one piece of the goals' colour with it, its hue `goal_hue`
    /// (the shelf's 150 degrees): whether the goal's middle stays a goal.
    fn goal_against_a_leaning_top(goal_hue: f64) -> bool {
        let (to_image, to_floor, mut classes) = floor();
        paint(&mut classes, 40, (33, 2, 39, 8), Class::Goal);
        paint(&mut classes, 40, (33, 12, 39, 18), Class::Goal);
        paint(&mut classes, 40, (1, 1, 19, 12), Class::Goal);
        paint(&mut classes, 40, (7, 12, 13, 18), Class::Goal);
        let hue_of = |i: usize| {
            let (x, y) = (i % 40, i / 40);
            let goal = (7..13).contains(&x) && (12..18).contains(&y);
            if goal {
                goal_hue
            } else {
                150.0
            }
        };
        absorb(&mut classes, 40, (&to_image, &to_floor), (4, 2), &hue_of);
        assert_eq!(classes[5 * 40 + 5], Class::Obstacle as u8);
        assert_eq!(
            classes[11 * 40 + 2],
            Class::Obstacle as u8,
            "the strip is the top's"
        );
        classes[15 * 40 + 10] == Class::Goal as u8
    }

    #[test]
    fn a_goal_against_a_goal_coloured_top_leaning_off_its_cells_stays_a_goal() {
        // The strip and the goal make two goals' worth outside the shelf's cells, elongated:
        // opened, the strip drops and the goal, painted apart from the shelf, stays (issue
        // #29's fifteenth round: Q0009, T0001).
        assert!(goal_against_a_leaning_top(110.0));
    }

    #[test]
    fn a_piece_of_a_leaning_top_of_the_top_s_own_hue_is_no_goal() {
        // The same shape in the shelf's hue: the end of its top (E0005, Q0003, Q0036).
        assert!(!goal_against_a_leaning_top(151.0));
    }

    /// Robots of 36 px in cells (3, 0) and (3, 1); a robot-coloured shelf over cells (0, 0)
    /// to (2, 0), rows 1–9, its top leaning off them in a strip 3 px deep, and a robot of
    /// 36 px against that strip, one piece of the robots' colour with it (three robots' worth
    /// outside the shelf's cells, not splitting into robots), its hue `robot_hue` (the shelf's
    /// 20 degrees): whether the robot's middle stays a robot.
    fn robot_against_a_leaning_top(robot_hue: f64) -> bool {
        let (to_image, to_floor, mut classes) = floor();
        paint(&mut classes, 40, (33, 2, 39, 8), Class::Robot);
        paint(&mut classes, 40, (33, 12, 39, 18), Class::Robot);
        paint(&mut classes, 40, (1, 1, 29, 13), Class::Robot);
        paint(&mut classes, 40, (12, 13, 18, 19), Class::Robot);
        let hue_of = |i: usize| {
            let (x, y) = (i % 40, i / 40);
            if (12..18).contains(&x) && (13..19).contains(&y) {
                robot_hue
            } else {
                20.0
            }
        };
        absorb(&mut classes, 40, (&to_image, &to_floor), (4, 2), &hue_of);
        assert_eq!(classes[5 * 40 + 5], Class::Obstacle as u8);
        classes[16 * 40 + 15] == Class::Robot as u8
    }

    #[test]
    fn a_robot_against_a_robot_coloured_top_leaning_off_its_cells_stays_a_robot() {
        // Issue #29's fifteenth round: R0013, R0033 (a red robot against a plum shelf).
        assert!(robot_against_a_leaning_top(0.0));
        assert!(!robot_against_a_leaning_top(21.0));
    }

    #[test]
    fn a_goal_joined_to_a_shelf_by_a_colour_between_stays_a_goal() {
        let (to_image, to_floor, mut classes) = floor();
        // A yellow (unsure) shelf over cells (0, 0) and (1, 0); a goal in cell (1, 1) joined
        // to it by a pixel of a colour between; goals in cells (3, 0) and (3, 1).
        paint(&mut classes, 40, (1, 1, 19, 9), Class::Unsure);
        paint(&mut classes, 40, (13, 10, 17, 14), Class::Goal);
        paint(&mut classes, 40, (15, 9, 16, 10), Class::Unsure);
        paint(&mut classes, 40, (33, 3, 37, 7), Class::Goal);
        paint(&mut classes, 40, (33, 13, 37, 17), Class::Goal);
        assert_eq!(
            absorb(&mut classes, 40, (&to_image, &to_floor), (4, 2), &one_hue).turned,
            1
        );
        assert_eq!(classes[5 * 40 + 10], Class::Obstacle as u8);
        assert_eq!(classes[12 * 40 + 15], Class::Goal as u8);
    }

    #[test]
    fn goals_filling_one_cell_each_stay_goals() {
        let (to_image, to_floor, mut classes) = floor();
        // One goal per cell, each filling its cell, touching the next: twice the median.
        paint(&mut classes, 40, (0, 0, 10, 10), Class::Goal);
        paint(&mut classes, 40, (10, 0, 20, 10), Class::Goal);
        paint(&mut classes, 40, (21, 11, 30, 20), Class::Goal);
        paint(&mut classes, 40, (0, 11, 10, 20), Class::Goal);
        let before = classes.clone();
        assert_eq!(
            absorb(&mut classes, 40, (&to_image, &to_floor), (4, 2), &one_hue).turned,
            0
        );
        assert_eq!(classes, before);
    }

    #[test]
    fn a_robot_coloured_shelf_and_slivers_on_a_shelf_are_obstacles_but_robots_stay() {
        let (to_image, to_floor, mut classes) = floor();
        // Robots 5 × 5 px in cells (3, 0), (3, 1) and (2, 1); goals in cells (2, 0) and
        // (0, 1); a robot-coloured shelf over cells (0, 0) and (1, 0) with obstacle pixels in
        // it; a robot touching it in cell (1, 1) stays a robot.
        paint(&mut classes, 40, (33, 3, 38, 8), Class::Robot);
        paint(&mut classes, 40, (33, 13, 38, 18), Class::Robot);
        paint(&mut classes, 40, (23, 13, 28, 18), Class::Robot);
        paint(&mut classes, 40, (23, 3, 27, 7), Class::Goal);
        paint(&mut classes, 40, (3, 13, 7, 17), Class::Goal);
        paint(&mut classes, 40, (1, 1, 19, 9), Class::Robot);
        paint(&mut classes, 40, (4, 4, 8, 6), Class::Obstacle);
        paint(&mut classes, 40, (13, 9, 18, 14), Class::Robot);
        assert_eq!(
            absorb(&mut classes, 40, (&to_image, &to_floor), (4, 2), &one_hue).turned,
            1
        );
        assert_eq!(classes[5 * 40 + 12], Class::Obstacle as u8);
        assert_eq!(classes[12 * 40 + 15], Class::Robot as u8);
        assert_eq!(classes[5 * 40 + 35], Class::Robot as u8);
    }

    #[test]
    fn a_sliver_of_robot_colour_on_a_shelf_is_obstacle_but_a_piece_of_a_robot_is_not() {
        let (to_image, to_floor, mut classes) = floor();
        // Robots of 25 px in cells (3, 0), (3, 1) and (2, 1); goals in cells (2, 0) and
        // (0, 1); an obstacle over cells (0, 0) and (1, 0) with a robot-coloured sliver of
        // 4 px on it (under 0.3 of the median robot) and a robot-coloured piece of 12 px
        // (about half a robot, on the shelf's edge: it might be a robot partly hidden).
        paint(&mut classes, 40, (33, 3, 38, 8), Class::Robot);
        paint(&mut classes, 40, (33, 13, 38, 18), Class::Robot);
        paint(&mut classes, 40, (23, 13, 28, 18), Class::Robot);
        paint(&mut classes, 40, (23, 3, 27, 7), Class::Goal);
        paint(&mut classes, 40, (3, 13, 7, 17), Class::Goal);
        paint(&mut classes, 40, (1, 1, 19, 9), Class::Obstacle);
        paint(&mut classes, 40, (3, 3, 5, 5), Class::Robot);
        paint(&mut classes, 40, (9, 7, 13, 10), Class::Robot);
        assert_eq!(
            absorb(&mut classes, 40, (&to_image, &to_floor), (4, 2), &one_hue).turned,
            1
        );
        assert_eq!(classes[3 * 40 + 3], Class::Obstacle as u8);
        assert_eq!(classes[8 * 40 + 10], Class::Robot as u8);
    }

    #[test]
    fn a_ragged_goal_sized_speck_of_a_shelf_is_the_shelf() {
        let (to_image, to_floor, mut classes) = floor();
        // Goals of 16 px in cells (3, 0) and (3, 1); an unsure shelf over cells (0, 0) and
        // (1, 0) with a goal-coloured diagonal streak of 8 px in it: a goal's size, but
        // ragged, so the shelf's.
        paint(&mut classes, 40, (33, 3, 37, 7), Class::Goal);
        paint(&mut classes, 40, (33, 13, 37, 17), Class::Goal);
        paint(&mut classes, 40, (1, 1, 19, 9), Class::Unsure);
        for k in 0..8 {
            classes[(1 + k) * 40 + 6 + k] = Class::Goal as u8;
        }
        assert_eq!(
            absorb(&mut classes, 40, (&to_image, &to_floor), (4, 2), &one_hue).turned,
            1
        );
        assert_eq!(classes[4 * 40 + 9], Class::Obstacle as u8);
        assert_eq!(classes[5 * 40 + 35], Class::Goal as u8);
    }

    #[test]
    fn a_goal_coloured_top_is_measured_against_goals_not_larger_robots() {
        // Robots of 64 px in cells (2, 1) and (3, 1), goals of 16 px in cells (2, 0), (3, 0),
        // (0, 1) and (1, 1); a goal-coloured band over cells (0, 0) and (1, 0), rows 1–4 (the rest of the
        // top reads as floor): 80 px, 5 goals but 1.25 robots, and it fills half of each
        // middle.
        let (to_image, to_floor, mut classes) = floor();
        for x in [21, 31] {
            paint(&mut classes, 40, (x, 11, x + 8, 19), Class::Robot);
            paint(&mut classes, 40, (x + 2, 2, x + 6, 6), Class::Goal);
            paint(&mut classes, 40, (x - 18, 13, x - 14, 17), Class::Goal);
        }
        paint(&mut classes, 40, (0, 1, 20, 5), Class::Goal);
        assert_eq!(
            absorb(&mut classes, 40, (&to_image, &to_floor), (4, 2), &one_hue).turned,
            1
        );
        assert_eq!(classes[3 * 40 + 10], Class::Obstacle as u8);
        assert_eq!(classes[4 * 40 + 33], Class::Goal as u8);
        assert_eq!(classes[15 * 40 + 25], Class::Robot as u8);
    }

    #[test]
    fn a_shelf_of_the_robots_colour_as_large_as_a_robot_is_an_obstacle() {
        // A robot 14 px square (1.4 cells) over cells (2, 0) to (3, 1); a robot-coloured
        // shelf 18 × 8 px over cells (0, 0) and (1, 0): 0.73 robots, but twice as long as
        // wide, filling two cells.
        let (to_image, to_floor, mut classes) = floor();
        paint(&mut classes, 40, (23, 3, 37, 17), Class::Robot);
        paint(&mut classes, 40, (1, 1, 19, 9), Class::Robot);
        assert_eq!(
            absorb(&mut classes, 40, (&to_image, &to_floor), (4, 2), &one_hue).turned,
            1
        );
        assert_eq!(classes[5 * 40 + 10], Class::Obstacle as u8);
        assert_eq!(classes[10 * 40 + 30], Class::Robot as u8);
        // A robot 18 × 14 px over cells (0, 0) to (1, 1) nearly fills two cells' middles, but
        // it is not twice as long as wide: it stays a robot.
        let (to_image, to_floor, mut classes) = floor();
        paint(&mut classes, 40, (23, 3, 37, 17), Class::Robot);
        paint(&mut classes, 40, (1, 1, 19, 15), Class::Robot);
        let before = classes.clone();
        absorb(&mut classes, 40, (&to_image, &to_floor), (4, 2), &one_hue);
        assert_eq!(classes, before);
    }

    #[test]
    fn a_goal_coloured_blob_filling_one_cell_is_not_judged() {
        let (to_image, to_floor, mut classes) = floor();
        paint(&mut classes, 40, (0, 0, 10, 10), Class::Goal);
        let before = classes.clone();
        assert_eq!(
            absorb(&mut classes, 40, (&to_image, &to_floor), (4, 2), &one_hue).turned,
            0
        );
        assert_eq!(classes, before);
    }

    #[test]
    fn a_top_of_a_colour_between_over_one_cell_is_an_obstacle_unless_many_are_alike() {
        // Goals 5 px wide in cells (3, 0) and (3, 1); a top of a colour that cannot be told,
        // with a few goal-coloured specks, over cell (0, 0): an obstacle.
        let (to_image, to_floor, mut classes) = floor();
        paint(&mut classes, 40, (33, 3, 38, 8), Class::Goal);
        paint(&mut classes, 40, (33, 13, 38, 18), Class::Goal);
        paint(&mut classes, 40, (0, 0, 10, 10), Class::Unsure);
        paint(&mut classes, 40, (4, 4, 6, 6), Class::Goal);
        assert_eq!(
            absorb(&mut classes, 40, (&to_image, &to_floor), (4, 2), &one_hue).turned,
            1
        );
        assert_eq!(classes[5 * 40 + 5], Class::Obstacle as u8);
        assert_eq!(classes[5 * 40 + 35], Class::Goal as u8);
        // Mostly goal-coloured, it is left as it is (two cells side by side are needed).
        let (_, _, mut classes) = floor();
        paint(&mut classes, 40, (33, 3, 38, 8), Class::Goal);
        paint(&mut classes, 40, (0, 0, 10, 10), Class::Goal);
        paint(&mut classes, 40, (2, 2, 8, 8), Class::Unsure);
        let before = classes.clone();
        absorb(&mut classes, 40, (&to_image, &to_floor), (4, 2), &one_hue);
        assert_eq!(classes, before);
        // Three such blobs, one a cell, alike: marks of such a colour, left as they are.
        let (_, _, mut classes) = floor();
        paint(&mut classes, 40, (33, 3, 38, 8), Class::Goal);
        for x0 in [0, 11, 22] {
            paint(&mut classes, 40, (x0, 11, x0 + 9, 20), Class::Unsure);
        }
        let before = classes.clone();
        assert_eq!(
            absorb(&mut classes, 40, (&to_image, &to_floor), (4, 2), &one_hue).turned,
            0
        );
        assert_eq!(classes, before);
    }
}
