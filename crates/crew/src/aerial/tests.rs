//! The reader on small painted floors (the rendered ones are in the repository's tests).

use super::*;
use image::{ImageFormat, Rgb};
use std::io::Cursor;

/// Sets the pixels x0..x1 by y0..y1 of a class map `width` pixels wide to `c` (the step tests
/// of `shelves` and `enclosed`).
pub(super) fn paint(
    classes: &mut [u8],
    width: usize,
    (x0, y0, x1, y1): (usize, usize, usize, usize),
    c: Class,
) {
    for y in y0..y1 {
        for x in x0..x1 {
            classes[y * width + x] = c as u8;
        }
    }
}

/// A floor painted through a homography: grey with the blocked cells' shadow, optional dark
/// grid lines, blue obstacles on whole cells, red discs (robots) and green discs (goals) at
/// floor points.
struct Paint {
    cells: (u32, u32),
    blocked: Vec<(u32, u32)>,
    robots: Vec<Point>,
    goals: Vec<Point>,
    radius: f64,
    lines: bool,
    shelf: [f64; 3],
    line: [f64; 3],
    floor: [f64; 3],
    /// The camera's noise: each channel of each pixel off by up to this much, either way.
    noise: f64,
}

impl Paint {
    fn new(cells: (u32, u32)) -> Paint {
        Paint {
            cells,
            blocked: vec![],
            robots: vec![],
            goals: vec![],
            radius: 0.3,
            lines: false,
            shelf: [40.0, 70.0, 170.0],
            line: [40.0; 3],
            floor: [170.0, 165.0, 155.0],
            noise: 0.0,
        }
    }

    fn draw(&self, size: (u32, u32), corners: [Point; 4]) -> RgbImage {
        let (w, h) = (f64::from(self.cells.0), f64::from(self.cells.1));
        let to_floor = Homography::floor_to_image(w, h, corners)
            .unwrap()
            .inverse()
            .unwrap();
        RgbImage::from_fn(size.0, size.1, |x, y| {
            let (u, v) = to_floor
                .apply((f64::from(x) + 0.5, f64::from(y) + 0.5))
                .unwrap();
            if u < 0.0 || v < 0.0 || u >= w || v >= h {
                return Rgb([90, 100, 120]);
            }
            let near = |c: &Point| (u - c.0).powi(2) + (v - c.1).powi(2) < self.radius.powi(2);
            // The blocked cells' shadow: the sun toward +u and −v, low (a shadow 1.5 cells long).
            let shaded = (1..=30).any(|t| {
                let t = f64::from(t) * 0.05;
                let (su, sv) = (u + t, v - t / 2.0);
                su >= 0.0
                    && sv >= 0.0
                    && self.blocked.contains(&(su as u32, sv as u32))
                    && !self.blocked.contains(&(u as u32, v as u32))
            });
            let shade = if shaded { 0.45 } else { 1.0 };
            // Noise from a hash of the pixel and the channel, the same on every run.
            let noise = |c: usize| {
                let mut k = (u64::from(x) << 32 | u64::from(y)) * 4 + c as u64;
                k = (k ^ (k >> 31)).wrapping_mul(0x9e37_79b9_7f4a_7c15);
                k = (k ^ (k >> 29)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
                self.noise * ((k >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0)
            };
            let sh = |c: [f64; 3]| {
                Rgb([0, 1, 2].map(|i| (c[i] * shade + noise(i)).clamp(0.0, 255.0) as u8))
            };
            if self.robots.iter().any(near) {
                return sh([200.0, 30.0, 25.0]);
            }
            if self.goals.iter().any(near) {
                return sh([30.0, 170.0, 50.0]);
            }
            if self.blocked.contains(&(u as u32, v as u32)) {
                return sh(self.shelf);
            }
            let line = self.lines
                && (u.fract() < 0.05 || u.fract() > 0.95 || v.fract() < 0.05 || v.fract() > 0.95);
            sh(if line { self.line } else { self.floor })
        })
    }

    fn straight(&self, cell_px: u32) -> RgbImage {
        let (w, h) = (self.cells.0 * cell_px, self.cells.1 * cell_px);
        let (fw, fh) = (f64::from(w), f64::from(h));
        self.draw((w, h), [(0.0, 0.0), (fw, 0.0), (fw, fh), (0.0, fh)])
    }
}

fn png(img: &RgbImage) -> Vec<u8> {
    let mut out = Cursor::new(Vec::new());
    img.write_to(&mut out, ImageFormat::Png).unwrap();
    out.into_inner()
}

/// Paints the pixels x0..x1 by y0..y1 of an image in one colour.
fn fill(img: &mut RgbImage, (x0, y0, x1, y1): (u32, u32, u32, u32), c: [u8; 3]) {
    for y in y0..y1 {
        for x in x0..x1 {
            img.put_pixel(x, y, Rgb(c));
        }
    }
}

/// The test scene with half of the window of cell (7, 4) that no neighbour can lean over
/// (0.4–0.95 of the cell away from the nadir at the image's centre) covered: a strip 2 px
/// wide, 4 px as the pixels' colours are averaged over 3 × 3.
fn half_covered_7_4() -> RgbImage {
    let mut img = scene().straight(12);
    fill(&mut img, (91, 48, 93, 60), [40, 70, 170]);
    img
}

/// The test scene with pixels x0..65 by 37..47 at half their brightness: from x0 = 55, a
/// shadow 0.8 cell square on cells (4, 3) and (5, 3), away from every obstacle, robot and
/// goal; from x0 = 48, running to the blocked cells (3, 1)–(3, 3).
fn shaded_from(x0: u32) -> RgbImage {
    let mut img = scene().straight(12);
    for y in 37..47 {
        for x in x0..65 {
            let p = img.get_pixel(x, y).0;
            img.put_pixel(x, y, Rgb(p.map(|c| (f64::from(c) * 0.5) as u8)));
        }
    }
    img
}

/// Goals to spare: the test scene has three goals and two robots.
fn spare() -> AerialConfig {
    AerialConfig {
        spare_goals: true,
        ..AerialConfig::default()
    }
}

/// The grid given, and goals to spare.
fn grid(w: u32, h: u32) -> AerialConfig {
    AerialConfig {
        grid: Some((w, h)),
        ..spare()
    }
}

fn xy(r: &AerialReading, marks: &[Mark]) -> Vec<(u32, u32)> {
    marks.iter().map(|m| r.grid.xy(m.cell)).collect()
}

fn scene() -> Paint {
    let mut p = Paint::new((8, 5));
    p.blocked = vec![(3, 1), (3, 2), (3, 3)];
    p.robots = vec![(0.6, 0.45), (6.5, 3.5)];
    p.goals = vec![(7.4, 0.6), (1.5, 4.5), (5.5, 1.5)];
    p
}

#[test]
fn reads_a_straight_down_view_with_shadows() {
    let r = read_aerial(&png(&scene().straight(12)), "v.png", &grid(8, 5)).unwrap();
    assert_eq!(xy(&r, &r.robots), vec![(0, 0), (6, 3)]);
    assert_eq!(xy(&r, &r.goals), vec![(7, 0), (5, 1), (1, 4)]);
    let blocked: Vec<(u32, u32)> = (0..40)
        .filter(|&i| !r.grid.is_free(Cell(i)))
        .map(|i| r.grid.xy(Cell(i)))
        .collect();
    assert_eq!(blocked, vec![(3, 1), (3, 2), (3, 3)]);
    assert_eq!(r.grid_source, GridSource::Given);
    assert!((r.cell_px - 12.0).abs() < 1e-9);
    assert!(r
        .robots
        .iter()
        .all(|m| m.confidence > 0.0 && m.confidence <= 1.0));
}

#[test]
fn cell_px_and_painted_lines_give_the_grid() {
    let mut p = scene();
    let cfg = AerialConfig {
        cell_px: Some(12.0),
        ..spare()
    };
    let r = read_aerial(&png(&p.straight(12)), "v.png", &cfg).unwrap();
    assert_eq!((r.grid.width(), r.grid.height()), (8, 5));
    assert_eq!(r.grid_source, GridSource::CellPx);
    // Without grid information a photograph is refused...
    let e = read_aerial(&png(&p.straight(12)), "v.png", &AerialConfig::default()).unwrap_err();
    assert!(e.to_string().contains("no grid"), "{e}");
    // ... unless lines are painted on its floor.
    p.lines = true;
    let r = read_aerial(&png(&p.straight(14)), "v.png", &spare()).unwrap();
    assert_eq!((r.grid.width(), r.grid.height()), (8, 5));
    assert_eq!(r.grid_source, GridSource::Lines);
    assert_eq!(xy(&r, &r.robots), vec![(0, 0), (6, 3)]);
}

#[test]
fn reads_a_tilted_view_through_its_corners() {
    let p = scene();
    let corners = [(40.0, 30.0), (300.0, 12.0), (330.0, 200.0), (10.0, 215.0)];
    let img = p.draw((340, 230), corners);
    let cfg = AerialConfig {
        grid: Some((8, 5)),
        corners: Some(corners),
        ..spare()
    };
    let r = read_aerial(&png(&img), "t.png", &cfg).unwrap();
    assert_eq!(xy(&r, &r.robots), vec![(0, 0), (6, 3)]);
    assert_eq!(xy(&r, &r.goals), vec![(7, 0), (5, 1), (1, 4)]);
    assert_eq!(r.grid.free_count(), 37);
    // The same corners in another order are not a floor.
    let mut bad = cfg.clone();
    bad.corners = Some([corners[1], corners[0], corners[2], corners[3]]);
    let e = read_aerial(&png(&img), "t.png", &bad).unwrap_err();
    assert!(e.to_string().contains("convex"), "{e}");
}

#[test]
fn a_pale_shelf_is_an_obstacle_and_white_lines_are_not() {
    // A pale lilac shelf (saturation 0.18 after white balance, as bright as the floor: floor
    // by its colour class) on a floor with white painted lines (half as bright again as the
    // floor, a tenth of a cell wide).
    let mut p = scene();
    p.shelf = [190.0, 165.0, 190.0];
    p.lines = true;
    p.line = [255.0; 3];
    for px in [12, 20] {
        let r = read_aerial(&png(&p.straight(px)), "v.png", &grid(8, 5)).unwrap();
        let blocked: Vec<(u32, u32)> = (0..40)
            .filter(|&i| !r.grid.is_free(Cell(i)))
            .map(|i| r.grid.xy(Cell(i)))
            .collect();
        assert_eq!(blocked, vec![(3, 1), (3, 2), (3, 3)], "{px} px per cell");
        assert_eq!(xy(&r, &r.robots), vec![(0, 0), (6, 3)]);
    }
}

#[test]
fn reads_jpeg() {
    let img = scene().straight(16);
    let mut out = Cursor::new(Vec::new());
    image::codecs::jpeg::JpegEncoder::new_with_quality(&mut out, 70)
        .encode_image(&img)
        .unwrap();
    let r = read_aerial(&out.into_inner(), "v.jpg", &grid(8, 5)).unwrap();
    assert_eq!(xy(&r, &r.robots), vec![(0, 0), (6, 3)]);
}

fn refusal(p: &Paint, cfg: &AerialConfig) -> String {
    read_aerial(&png(&p.straight(12)), "v.png", cfg)
        .unwrap_err()
        .to_string()
}

#[test]
fn refuses_what_it_cannot_read() {
    // Two robots touching, each on its own cell: split and read.
    let mut touching = scene();
    touching.robots.push((7.1, 3.5));
    touching.goals.push((4.5, 4.5));
    touching.robots.push((1.5, 2.5));
    touching.goals.push((6.5, 0.5));
    let r = read_aerial(&png(&touching.straight(12)), "v.png", &grid(8, 5)).unwrap();
    let mut robots = xy(&r, &r.robots);
    robots.sort_unstable();
    assert_eq!(robots, [(0, 0), (1, 2), (6, 3), (7, 3)]);
    // A red bar as large as two robots, with no neck between them: cannot be separated.
    let mut bar = scene();
    bar.robots.push((1.5, 2.5));
    bar.goals.push((6.5, 0.5));
    let mut img = bar.straight(12);
    fill(&mut img, (64, 28, 76, 35), [200, 30, 25]);
    let e = read_aerial(&png(&img), "v.png", &grid(8, 5))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("robots touching") && e.contains("cannot be separated") && e.contains("pixel ("),
        "{e}"
    );

    // Two robots alone and two pairs touching: the median blob is a pair, and a pair splits
    // into two robots the size of the lone ones.
    let mut pairs = scene();
    pairs
        .robots
        .extend([(1.7, 2.5), (2.3, 2.5), (5.7, 4.5), (6.3, 4.5)]);
    let e = refusal(&pairs, &grid(8, 5));
    assert!(e.contains("the median may be of robots touching"), "{e}");

    let mut border = scene();
    border.robots[1] = (6.03, 3.5);
    let e = refusal(&border, &grid(8, 5));
    assert!(e.contains("border of cell"), "{e}");

    let mut few = scene();
    few.goals.truncate(1);
    assert!(refusal(&few, &grid(8, 5)).contains("2 robots but only 1 goals"));
    // More goals than robots: refused unless the floor has goals to spare.
    let strict = AerialConfig {
        spare_goals: false,
        ..grid(8, 5)
    };
    let e = refusal(&scene(), &strict);
    assert!(
        e.contains("3 goals but only 2 robots") && e.contains("--spare-goals"),
        "{e}"
    );

    let mut none = scene();
    none.robots.clear();
    assert!(refusal(&none, &grid(8, 5)).contains("no robot found"));

    assert!(refusal(&scene(), &grid(8, 9)).contains("does not fit"));
    let cfg = AerialConfig {
        cell_px: Some(11.0),
        ..AerialConfig::default()
    };
    assert!(refusal(&scene(), &cfg).contains("does not fit"));

    // An amber blob: neither the robots' red nor clearly another colour.
    let mut img = scene().straight(12);
    fill(&mut img, (70, 40, 78, 48), [220, 120, 20]);
    let e = read_aerial(&png(&img), "v.png", &grid(8, 5))
        .unwrap_err()
        .to_string();
    assert!(e.contains("neither the robots'"), "{e}");

    // Half of a cell's window that no neighbour leans over covered.
    let e = read_aerial(&png(&half_covered_7_4()), "v.png", &grid(8, 5))
        .unwrap_err()
        .to_string();
    assert!(e.contains("cell (7, 4)") && e.contains("covered"), "{e}");
}

/// The operator settles the cells a refusal names: a half-covered cell, a shadow with no caster,
/// a free cell unlike the floor and a painted line that does not show are read as settled,
/// never refused (also by the audit); cells outside the grid, or settled both ways, are
/// refused. Each guard fails this test when taken out.
#[test]
fn settled_cells_are_read_as_the_operator_says() {
    let settle = |blocked: &[(u32, u32)], free: &[(u32, u32)]| AerialConfig {
        blocked_cells: blocked.to_vec(),
        free_cells: free.to_vec(),
        ..grid(8, 5)
    };
    let blocked_cells = |r: &AerialReading| -> Vec<(u32, u32)> {
        (0..40)
            .filter(|&i| !r.grid.is_free(Cell(i)))
            .map(|i| r.grid.xy(Cell(i)))
            .collect()
    };
    // Cell (7, 4) half covered.
    let half = png(&half_covered_7_4());
    let e = read_aerial(&half, "v.png", &grid(8, 5)).unwrap_err();
    assert!(e.reason.contains("cell (7, 4)"), "{e}");
    let r = read_aerial(&half, "v.png", &settle(&[], &[(7, 4)])).unwrap();
    assert_eq!(blocked_cells(&r), [(3, 1), (3, 2), (3, 3)]);
    assert_eq!(r.settled, [(Cell(39), false)]);
    let r = read_aerial(&half, "v.png", &settle(&[(7, 4)], &[])).unwrap();
    assert_eq!(blocked_cells(&r), [(3, 1), (3, 2), (3, 3), (7, 4)]);
    assert_eq!(r.settled, [(Cell(39), true)]);
    // A cell settled against the view: read as settled (a free cell read blocked, here).
    let r = read_aerial(&half, "v.png", &settle(&[(7, 4)], &[(3, 2)])).unwrap();
    assert_eq!(blocked_cells(&r), [(3, 1), (3, 3), (7, 4)]);
    let audited = audit_aerial(&half, "v.png", &settle(&[], &[(7, 4)])).unwrap();
    assert!(audited.doubts.is_empty(), "{:?}", audited.doubts);
    // Another cell settled: still refused at (7, 4).
    let e = read_aerial(&half, "v.png", &settle(&[], &[(6, 4)])).unwrap_err();
    assert!(e.reason.contains("cell (7, 4)"), "{e}");

    // A shadow from cell (4, 3) that nothing casts (as in `a_shadow_needs_a_caster`): settled
    // free where it starts, or its caster settled blocked beside it.
    let shadow = png(&shaded_from(55));
    let e = read_aerial(&shadow, "v.png", &grid(8, 5)).unwrap_err();
    assert!(e.reason.contains("from cell (4, 3)"), "{e}");
    let r = read_aerial(&shadow, "v.png", &settle(&[], &[(4, 3)])).unwrap();
    assert_eq!(blocked_cells(&r), [(3, 1), (3, 2), (3, 3)]);
    let e = read_aerial(&shadow, "v.png", &settle(&[], &[(5, 3)])).unwrap_err();
    assert!(e.reason.contains("from cell (4, 3)"), "{e}");
    let r = read_aerial(&shadow, "v.png", &settle(&[(5, 2)], &[])).unwrap();
    assert_eq!(blocked_cells(&r), [(3, 1), (3, 2), (5, 2), (3, 3)]);

    // Cell (6, 1) a third brighter than the floor: does not look like the floor, unless
    // settled free.
    let mut img = scene().straight(12);
    fill(&mut img, (72, 12, 84, 24), [224, 218, 205]);
    let bright = png(&img);
    let e = read_aerial(&bright, "v.png", &grid(8, 5)).unwrap_err();
    assert!(
        e.reason
            .contains("cell (6, 1) would be free but does not look like the floor"),
        "{e}"
    );
    let r = read_aerial(&bright, "v.png", &settle(&[], &[(6, 1)])).unwrap();
    assert_eq!(blocked_cells(&r), [(3, 1), (3, 2), (3, 3)]);

    // Painted lines, the one between cells (5, 3) and (5, 4) hidden: refused until both are
    // settled.
    let mut lined = scene();
    lined.lines = true;
    let mut img = lined.straight(14);
    fill(&mut img, (71, 53, 83, 59), [170, 165, 155]);
    let hidden = png(&img);
    let e = read_aerial(&hidden, "v.png", &grid(8, 5)).unwrap_err();
    assert!(
        e.reason
            .contains("painted line between cells (5, 3) and (5, 4)"),
        "{e}"
    );
    let e = read_aerial(&hidden, "v.png", &settle(&[], &[(5, 4)])).unwrap_err();
    assert!(
        e.reason
            .contains("painted line between cells (5, 3) and (5, 4)"),
        "{e}"
    );
    let r = read_aerial(&hidden, "v.png", &settle(&[], &[(5, 3), (5, 4)])).unwrap();
    assert_eq!(blocked_cells(&r), [(3, 1), (3, 2), (3, 3)]);

    let plain = png(&scene().straight(12));
    let e = read_aerial(&plain, "v.png", &settle(&[(8, 0)], &[])).unwrap_err();
    assert!(
        e.reason
            .contains("cell (8, 0), settled as blocked, lies outside the 8×5 grid"),
        "{e}"
    );
    let e = read_aerial(&plain, "v.png", &settle(&[], &[(0, 5)])).unwrap_err();
    assert!(e.reason.contains("settled as free, lies outside"), "{e}");
    let e = read_aerial(&plain, "v.png", &settle(&[(2, 2)], &[(2, 2)])).unwrap_err();
    assert!(
        e.reason.contains("settled both as blocked and as free"),
        "{e}"
    );
}

#[test]
fn a_robot_against_a_shelf_of_its_colour_is_not_lost_without_a_word() {
    // A shelf of the robots' red over cells (3, 1)–(3, 3).
    let mut p = scene();
    p.shelf = [200.0, 30.0, 25.0];
    // As many goals as robots: the shelf is read (its rim, robot-coloured where the colours
    // are averaged over a square, is the shelf's).
    let third_goal = p.goals.pop().unwrap();
    let alone = read_aerial(&png(&p.straight(12)), "v.png", &grid(8, 5)).unwrap();
    assert_eq!(alone.robots.len(), 2);
    assert!(alone.grid.is_free(alone.grid.cell(2, 2).unwrap()));
    assert!(!alone.grid.is_free(alone.grid.cell(3, 2).unwrap()));
    // With a goal to spare, robot-coloured pixels taken for the shelf's may be a robot's.
    p.goals.push(third_goal);
    let e = refusal(&p, &grid(8, 5));
    assert!(e.contains("a robot may stand against the shelf"), "{e}");
    // A third robot against the shelf (on its sunlit side), and a third goal: read, on its
    // cell.
    p.robots.push((4.28, 2.5));
    let r = read_aerial(&png(&p.straight(12)), "v.png", &grid(8, 5)).unwrap();
    let mut robots = xy(&r, &r.robots);
    robots.sort_unstable();
    assert_eq!(robots, [(0, 0), (4, 2), (6, 3)]);
    assert!(!r.grid.is_free(r.grid.cell(3, 2).unwrap()));
}

#[test]
fn a_mark_on_a_border_against_a_shelf_is_set_aside_only_when_the_counts_then_agree() {
    // A robot-coloured disc on the border between the shelf's cell (3, 2) and cell (4, 2),
    // against the shelf: a piece of a shelf of a colour near the robots' may be so.
    let mut p = scene();
    p.robots.push((4.02, 2.5));
    // Three robots and three goals with it: set aside, two robots are left for three goals,
    // and the view is refused for it.
    let e = refusal(&p, &grid(8, 5));
    assert!(e.contains("a robot on the border of cell (4, 2)"), "{e}");
    // Three robots and two goals with it: read without it.
    p.goals.pop();
    let r = read_aerial(&png(&p.straight(12)), "v.png", &grid(8, 5)).unwrap();
    assert_eq!(xy(&r, &r.robots), vec![(0, 0), (6, 3)]);
    // Away from the shelf, on the border of cells (5, 2) and (6, 2), it is refused whatever
    // the counts.
    p.robots.pop();
    p.robots.push((6.0, 2.45));
    let e = refusal(&p, &grid(8, 5));
    assert!(e.contains("a robot on the border of cell (6, 2)"), "{e}");
}

#[test]
fn a_blob_on_blocked_cells_is_the_obstacle_s() {
    // A 4 × 4 floor of 10 px cells, straight down; cell (1, 1) blocked.
    let f2i = Homography::floor_to_image(
        4.0,
        4.0,
        [(0.0, 0.0), (40.0, 0.0), (40.0, 40.0), (0.0, 40.0)],
    )
    .unwrap();
    let i2f = f2i.inverse().unwrap();
    let mut blocked = vec![false; 16];
    blocked[4 + 1] = true;
    let g = Grid::new(4, 4, blocked);
    let square = |x0: u32, y0: u32, side: u32| {
        let px: Vec<usize> = (y0..y0 + side)
            .flat_map(|y| (x0..x0 + side).map(move |x| (y * 40 + x) as usize))
            .collect();
        blobs::Blob::from_indices(&px, 40)
    };
    // The blocked cell's pixels (x and y 10..20) an obstacle's, the rest floor.
    let mut classes = vec![Class::Floor as u8; 40 * 40];
    paint(&mut classes, 40, (10, 10, 20, 20), Class::Obstacle);
    let on = |b: &blobs::Blob| on_shelf(b, &g, &i2f, (&classes, 40));
    // Inside the blocked cell; on the free cell beside it; two thirds on it (x 16..22), and
    // half (x 17..23).
    assert!(on(&square(12, 12, 6)));
    assert!(!on(&square(22, 12, 6)));
    assert!(on(&square(16, 12, 6)));
    assert!(!on(&square(17, 12, 6)));
    // A blob on the blocked cell with floor all around it stands on the floor: a mark on a
    // cell misread as blocked (refused as such, not taken for the shelf's).
    let mut floor_around = classes.clone();
    paint(&mut floor_around, 40, (10, 10, 20, 20), Class::Floor);
    assert!(!on_shelf(&square(12, 12, 6), &g, &i2f, (&floor_around, 40)));
}

#[test]
fn a_mark_coloured_blob_on_a_shelf_is_read_as_the_shelf_s() {
    // A robot-coloured disc on the shelf (its reddest pixels, over the border of two of its
    // cells), two robots and two goals on the floor: read, the disc as the shelf's.
    let mut p = scene();
    let third_goal = p.goals.pop().unwrap();
    p.robots.push((3.5, 2.02));
    let r = read_aerial(&png(&p.straight(12)), "v.png", &grid(8, 5)).unwrap();
    let mut robots = xy(&r, &r.robots);
    robots.sort_unstable();
    assert_eq!(robots, [(0, 0), (6, 3)]);
    assert!(!r.grid.is_free(r.grid.cell(3, 2).unwrap()));
    // With a goal more than robots, that disc may have been a robot on a cell misread as
    // blocked: refused, naming it.
    p.goals.push(third_goal);
    let e = refusal(&p, &grid(8, 5));
    assert!(
        e.contains("robot-coloured blob") && e.contains("on cell (3, 2), which an obstacle covers"),
        "{e}"
    );
}

#[test]
fn a_dark_noisy_floor_looks_like_the_floor() {
    // A dark floor (a quarter of white) whose pixels the camera's noise tints, at 10 px a cell
    // (colours not averaged): its own pixels must not lean pale.
    let mut p = scene();
    p.goals.pop();
    p.floor = [60.0, 60.0, 60.0];
    p.noise = 6.0;
    let r = read_aerial(&png(&p.straight(10)), "v.png", &grid(8, 5)).unwrap();
    assert_eq!(r.robots.len(), 2);
    assert!(!r.grid.is_free(r.grid.cell(3, 2).unwrap()));
    assert!(r.grid.is_free(r.grid.cell(5, 2).unwrap()));
}

#[test]
fn a_shadow_needs_a_caster() {
    // A shadow 0.8 cell square on cells (4, 3) and (5, 3), away from every obstacle, robot and
    // goal: a shelf of the floor's own colour casts it, and the view is refused.
    let e = read_aerial(&png(&shaded_from(55)), "v.png", &grid(8, 5))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("a shadow on free floor from cell (4, 3)") && e.contains("pixel ("),
        "{e}"
    );
    // The same shadow running to the blocked cells (3, 1)–(3, 3): theirs; read as before.
    let r = read_aerial(&png(&shaded_from(48)), "v.png", &grid(8, 5)).unwrap();
    assert_eq!(xy(&r, &r.robots), vec![(0, 0), (6, 3)]);
    assert_eq!(r.grid.width() * r.grid.height(), 40);
    assert_eq!((0..40).filter(|&i| !r.grid.is_free(Cell(i))).count(), 3);
}

#[test]
fn specks_of_the_robots_colour_cast_no_shadow() {
    // The shadow of `a_shadow_needs_a_caster` with specks of the robots' red (2 px, under the
    // smallest blob a robot makes) at its edge, as a shelf's rim or the camera's noise
    // leaves them: no robot stands there to cast it, and the view is still refused (issue #29's
    // fifteenth round: U0017, a cream shelf's shadow taken for a robot's).
    let mut img = scene().straight(12);
    for y in 37..47 {
        for x in 55..65 {
            let p = img.get_pixel(x, y).0;
            img.put_pixel(x, y, Rgb(p.map(|c| (f64::from(c) * 0.5) as u8)));
        }
    }
    for (sx, sy) in [(55, 37), (60, 37), (64, 41), (55, 45)] {
        for (dx, dy) in [(0, 0), (1, 0)] {
            img.put_pixel(sx + dx, sy + dy, Rgb([200, 30, 25]));
        }
    }
    let e = read_aerial(&png(&img), "v.png", &grid(8, 5))
        .unwrap_err()
        .to_string();
    assert!(e.contains("a shadow on free floor from cell (4, 3)"), "{e}");
}

#[test]
fn malformed_and_hostile_images_are_refused() {
    let cfg = grid(8, 5);
    let e = read_aerial(b"GIF89a....", "x", &cfg)
        .unwrap_err()
        .to_string();
    assert!(e.contains("not a PNG or a JPEG"), "{e}");
    let bytes = png(&scene().straight(12));
    let e = read_aerial(&bytes[..bytes.len() / 2], "x", &cfg)
        .unwrap_err()
        .to_string();
    assert!(e.contains("cannot decode the PNG"), "{e}");
    let e = read_aerial(&[0xFF, 0xD8, 0xFF, 0xE0, 0, 16], "x", &cfg)
        .unwrap_err()
        .to_string();
    assert!(e.contains("cannot decode the JPEG"), "{e}");
    // A header that claims 100 000 × 100 000 pixels is refused before decoding.
    let mut huge = bytes.clone();
    huge[16..20].copy_from_slice(&100_000u32.to_be_bytes());
    huge[20..24].copy_from_slice(&100_000u32.to_be_bytes());
    let crc = crc32(&huge[12..29]);
    huge[29..33].copy_from_slice(&crc.to_be_bytes());
    let e = read_aerial(&huge, "x", &cfg).unwrap_err().to_string();
    assert!(e.contains("more than the"), "{e}");
    let e = read_aerial(&bytes, "x", &grid(0, 5))
        .unwrap_err()
        .to_string();
    assert!(e.contains("at least 1"), "{e}");
    let e = read_aerial(&bytes, "x", &grid(100_000, 100_000))
        .unwrap_err()
        .to_string();
    assert!(e.contains("at most"), "{e}");
    let same = AerialConfig {
        goal_colour: Hue(10.0),
        ..grid(8, 5)
    };
    assert!(read_aerial(&bytes, "x", &same)
        .unwrap_err()
        .to_string()
        .contains("too close"));
}

#[test]
fn a_pixel_map_is_told_from_a_photograph() {
    let map = crate::image::birdseye_png(&Grid::open(6, 4), &[Cell(0)], &[Cell(5)]);
    let img = decode(&map, "m", MAX_PIXELS).unwrap();
    assert!(is_pixel_map(&img));
    // Sensor noise: a photograph has far more than 16 colours.
    let mut photo = scene().straight(12);
    for (i, p) in photo.pixels_mut().enumerate() {
        p.0[0] = p.0[0].saturating_add((i * 7919 % 5) as u8);
    }
    assert!(!is_pixel_map(&photo));
}

#[test]
fn same_input_same_reading() {
    let bytes = png(&scene().straight(12));
    let a = read_aerial(&bytes, "v", &grid(8, 5)).unwrap();
    let b = read_aerial(&bytes, "v", &grid(8, 5)).unwrap();
    assert_eq!(a.robots, b.robots);
    assert_eq!(a.goals, b.goals);
    assert_eq!(a.grid, b.grid);
}

/// The PNG chunk checksum (CRC-32, ISO 3309), to forge a valid header.
fn crc32(bytes: &[u8]) -> u32 {
    let mut crc = !0u32;
    for &b in bytes {
        crc ^= u32::from(b);
        for _ in 0..8 {
            crc = if crc & 1 == 1 {
                (crc >> 1) ^ 0xEDB8_8320
            } else {
                crc >> 1
            };
        }
    }
    !crc
}

#[test]
fn the_neighbours_toward_the_nadir_are_those_on_its_side() {
    // The nadir beyond the cell along x, level with it along y; then before it along both.
    assert_eq!(nadir_side((3, 4), (5.5, 4.5)), (1, 0));
    assert_eq!(nadir_side((3, 4), (2.9, 3.0)), (-1, -1));
    let beyond: Vec<(i64, i64)> = neighbours_toward((1, 0)).collect();
    assert_eq!(beyond, [(0, -1), (1, -1), (1, 0), (0, 1), (1, 1)]);
    let before: Vec<(i64, i64)> = neighbours_toward((-1, -1)).collect();
    assert_eq!(before, [(-1, -1), (0, -1), (-1, 0)]);
    assert_eq!(neighbours_toward((0, 0)).count(), 8);
}

#[test]
fn a_mark_joined_to_a_shelf_s_rim_is_cut_from_it() {
    // A robot, a disc of 201 px, and against it a strip of its colour 3 px thick (a
    // terracotta shelf's rim), against a median robot of 201 px: the disc is the robot.
    let disc = |cx: f64, cy: f64| -> Vec<(u32, u32)> {
        let mut out = Vec::new();
        for y in 0..80u32 {
            for x in 0..120u32 {
                let (px, py) = (f64::from(x) + 0.5, f64::from(y) + 0.5);
                if (px - cx).powi(2) + (py - cy).powi(2) <= 64.0 {
                    out.push((x, y));
                }
            }
        }
        out
    };
    let blob_of = |pixels: Vec<(u32, u32)>| {
        let bbox = pixels
            .iter()
            .fold((u32::MAX, u32::MAX, 0, 0), |b, &(x, y)| {
                (b.0.min(x), b.1.min(y), b.2.max(x), b.3.max(y))
            });
        blobs::Blob { pixels, bbox }
    };
    let robot = disc(30.0, 20.0);
    let median = robot.len();
    let mut with_rim = robot.clone();
    for y in 28..31u32 {
        for x in 2..60u32 {
            if !with_rim.contains(&(x, y)) {
                with_rim.push((x, y));
            }
        }
    }
    let found = off_rim(&blob_of(with_rim), median).expect("the robot");
    let (cx, cy) = found.centroid();
    assert!(
        (cx - 30.0).abs() < 0.5 && (cy - 20.0).abs() < 0.5,
        "{cx}, {cy}"
    );
    // Two robots joined by such a strip stay two: not one robot's rim.
    let mut pair = robot;
    pair.extend(disc(70.0, 20.0));
    for y in 28..31u32 {
        for x in 2..100u32 {
            if !pair.contains(&(x, y)) {
                pair.push((x, y));
            }
        }
    }
    assert!(off_rim(&blob_of(pair), median).is_none());
}

#[test]
fn a_cells_middle_brightness_is_its_middle_s_against_the_lit_floor() {
    // A 6 × 4 floor of 20 px cells, grey 150; cell (2, 1) darker (90) but for its rim, and
    // cell (4, 2) darker only along its border (its middle lit).
    let i2f = six_by_four();
    let f2i = i2f.inverse().unwrap();
    let mut img = RgbImage::from_pixel(120, 80, Rgb([150, 150, 150]));
    for y in 0..80u32 {
        for x in 0..120u32 {
            let (cx, cy, fx, fy) = (x / 20, y / 20, x % 20, y % 20);
            let rim = !(2..18).contains(&fx) || !(2..18).contains(&fy);
            if ((cx, cy) == (2, 1) && !rim) || ((cx, cy) == (4, 2) && rim) {
                img.put_pixel(x, y, Rgb([90, 90, 90]));
            }
        }
    }
    let classifier = Classifier::new([150.0; 3], Hue::RED, Hue::GREEN);
    let at = |cells: &[usize]| middle_brightness(&img, &classifier, (&f2i, &i2f), (6, 4), cells);
    assert!((at(&[8]).unwrap() - 0.6).abs() < 1e-9);
    assert!((at(&[2 * 6 + 4]).unwrap() - 1.0).abs() < 1e-9);
    assert!((at(&[0, 1]).unwrap() - 1.0).abs() < 1e-9);
    assert!(at(&[]).is_none());
}

#[test]
fn a_half_covered_cell_a_mark_stands_on_is_free() {
    // On a 4-wide grid: half-covered cells 1, 6, 9 and 14; a robot on cell 6, goals on cells
    // 14 and 3 (not half covered), and a robot next to cell 9, on cell 10.
    let mark = |cell: u32| Mark {
        cell: Cell(cell),
        floor: (f64::from(cell % 4) + 0.5, f64::from(cell / 4) + 0.5),
        pixel: (0.0, 0.0),
        area: 40,
        confidence: 1.0,
    };
    let (robots, goals) = ([mark(6), mark(10)], [mark(14), mark(3)]);
    assert_eq!(under_marks(&[14, 1, 6, 9], &robots, &goals), vec![6, 14]);
    assert!(under_marks(&[1, 9], &robots, &goals).is_empty());
    assert!(under_marks(&[], &robots, &goals).is_empty());
}

#[test]
fn a_pale_top_decides_a_half_covered_cell_whatever_its_neighbours() {
    // A cover standing inside the cell counts only with no neighbour's top that may lean over
    // it; a pale top of the cell's own counts either way.
    assert!(own_top_decides(false, || true, || false));
    assert!(!own_top_decides(true, || true, || false));
    assert!(own_top_decides(true, || false, || true));
    assert!(!own_top_decides(false, || false, || false));
}

#[test]
fn a_mark_cut_by_a_top_is_read_whole_when_every_way_to_complete_it_is_on_one_cell() {
    // A 6 × 4 floor of 20 px cells, straight down; the cells (3, 0)–(3, 3) blocked, their top
    // leaning left over the floor to x = 52 (rows 0–80). A goal of radius 8 px (201 px, the
    // median) centred at (50, 30), on cell (2, 1): its pixels left of x = 52 show.
    let i2f = six_by_four();
    let mut blocked = vec![false; 24];
    for y in 0..4 {
        blocked[y * 6 + 3] = true;
    }
    let g = Grid::new(6, 4, blocked);

    let median = disc_px(50.0, 30.0, 8.0).len();
    // The classes with the top from x = `top_from`, and the piece of the goal at `centre`
    // left of it.
    let view = |top_from: usize, centre: (f64, f64)| {
        let mut classes = vec![Class::Floor as u8; 120 * 80];
        paint(&mut classes, 120, (top_from, 0, 80, 80), Class::Obstacle);
        let piece: Vec<usize> = disc_px(centre.0, centre.1, 8.0)
            .into_iter()
            .filter(|&i| i % 120 < top_from)
            .collect();
        for &i in &piece {
            classes[i] = Class::Goal as u8;
        }
        (classes, blobs::Blob::from_indices(&piece, 120))
    };
    let cut = |(classes, piece): &(Vec<u8>, blobs::Blob)| {
        cut_mark(piece, median, &g, (&i2f, None), 0.05, (classes, 120))
    };
    let whole = view(52, (50.0, 30.0));
    let mark = cut(&whole).expect("read whole");
    assert_eq!(g.xy(mark.cell), (2, 1));
    assert!(mark.area < median && mark.confidence < 1.0, "{mark:?}");
    // Its centre under the top, 0.05 cell from the blocked cell: completed on (3, 1) too.
    assert!(cut(&view(52, (59.0, 30.0))).is_none());
    // On the border of the free cells (1, 1) and (2, 1), the top over (2, 1): both.
    assert!(cut(&view(41, (40.5, 30.0))).is_none());
    // No top beside it: nothing hides the rest of a mark, so it is no cut mark.
    let (mut bare, piece) = view(52, (50.0, 30.0));
    paint(&mut bare, 120, (52, 0, 80, 80), Class::Floor);
    assert!(cut(&(bare, piece)).is_none());
    // A mark the image's edge may cut is not completed: all but the piece an obstacle's, a
    // disc four times wider (reaching past the image's top) is not, one of the median is.
    let dark: Vec<u8> = whole
        .0
        .iter()
        .map(|&c| {
            if c == Class::Floor as u8 {
                Class::Obstacle as u8
            } else {
                c
            }
        })
        .collect();
    assert!(!blobs::cut_discs(&whole.1, median, (&dark, 120)).is_empty());
    assert!(blobs::cut_discs(&whole.1, 16 * median, (&dark, 120)).is_empty());
}

#[test]
fn a_faint_mark_grows_from_its_clear_middle() {
    // A 6 × 4 floor of 20 px cells, straight down, grey; cell (3, 1) blocked. A goal of radius
    // 5 px whose middle (radius 2 px) is a goal's clear green and the rest a washed-out green
    // of half the colour: the piece is the middle alone, the median goal a whole one.
    let (i2f, g) = (six_by_four(), six_by_four_grid());
    let classifier = Classifier::new([128.0; 3], Hue::RED, Hue::GREEN);
    let median = disc_px(50.0, 30.0, 5.0).len();
    let clear = Rgb([60u8, 170, 60]);
    let faint = Rgb([112u8, 142, 112]);
    assert_eq!(classifier.classify(faint.0), Class::Floor);
    assert_eq!(classifier.faint_mark(faint.0), Some(Class::Goal));
    // The view with the goal at `centre` (its washed-out part to radius `r`) and a band of
    // the washed-out green over the rows `band`.
    let view = |centre: (f64, f64), r: f64, band: std::ops::Range<u32>| {
        let mut img = RgbImage::from_pixel(120, 80, Rgb([128, 128, 128]));
        for y in band {
            for x in 0..120 {
                img.put_pixel(x, y, faint);
            }
        }
        for i in disc_px(centre.0, centre.1, r) {
            img.put_pixel((i % 120) as u32, (i / 120) as u32, faint);
        }
        let mut classes = vec![Class::Floor as u8; 120 * 80];
        let piece = disc_px(centre.0, centre.1, 2.0);
        for &i in &piece {
            img.put_pixel((i % 120) as u32, (i / 120) as u32, clear);
            classes[i] = Class::Goal as u8;
        }
        (img, classes, blobs::Blob::from_indices(&piece, 120))
    };
    let read = |(img, classes, piece): &(RgbImage, Vec<u8>, blobs::Blob)| {
        faint_mark(
            piece,
            median,
            &g,
            (&i2f, None),
            0.05,
            (classes, 120),
            (img, &classifier, Class::Goal),
        )
    };
    let mark = read(&view((50.0, 30.0), 5.0, 0..0)).expect("read whole");
    assert_eq!(g.xy(mark.cell), (2, 1));
    assert!(mark.confidence < 1.0, "{mark:?}");
    // Its clear middle alone is too small.
    assert!(read(&view((50.0, 30.0), 2.0, 0..0)).is_none());
    // A stretch of floor of the washed-out green runs on past it: no mark.
    assert!(read(&view((50.0, 30.0), 5.0, 26..35)).is_none());
    // Not as a robot.
    let (img, classes, piece) = view((50.0, 30.0), 5.0, 0..0);
    assert!(faint_mark(
        &piece,
        median,
        &g,
        (&i2f, None),
        0.05,
        (&classes, 120),
        (&img, &classifier, Class::Robot),
    )
    .is_none());
    // On the blocked cell, and on the border of two free cells.
    assert!(read(&view((70.0, 30.0), 5.0, 0..0)).is_none());
    assert!(read(&view((40.5, 30.0), 5.0, 0..0)).is_none());
}

#[test]
fn missing_goals_are_read_from_faint_blobs_only_when_as_many_show() {
    // A 6 × 4 floor of 20 px cells, straight down, grey; cell (3, 1) blocked. One goal read
    // clearly at (10, 10) on cell (0, 0), of the median's 79 px; a goal of the washed-out green
    // alone, radius 5 px, at `at`.
    let (i2f, g) = (six_by_four(), six_by_four_grid());
    let classifier = Classifier::new([128.0; 3], Hue::RED, Hue::GREEN);
    let faint = Rgb([112u8, 142, 112]);
    let found = [Mark {
        cell: g.cell(0, 0).unwrap(),
        floor: (0.5, 0.5),
        pixel: (10.0, 10.0),
        area: 79,
        confidence: 1.0,
    }];
    // The image with faint discs of radius 5 px at `at` and `colour` painted over the pixels
    // `rect` (x0, y0, x1, y1), of its class (an obstacle's: a shelf, as the shelves' pass
    // takes a pale green top).
    let view = |at: &[(f64, f64)], rect: (u32, u32, u32, u32), colour: Rgb<u8>| {
        let mut img = RgbImage::from_pixel(120, 80, Rgb([128, 128, 128]));
        let mut classes = vec![Class::Floor as u8; 120 * 80];
        for y in rect.1..rect.3 {
            for x in rect.0..rect.2 {
                img.put_pixel(x, y, colour);
                classes[y as usize * 120 + x as usize] = match classifier.classify(colour.0) {
                    Class::Goal => Class::Obstacle as u8,
                    c => c as u8,
                };
            }
        }
        for &(cx, cy) in at {
            for y in 0..80u32 {
                for x in 0..120u32 {
                    if (f64::from(x) + 0.5 - cx).hypot(f64::from(y) + 0.5 - cy) <= 5.0 {
                        img.put_pixel(x, y, faint);
                    }
                }
            }
        }
        (img, classes)
    };
    let robot = |x: f64, y: f64| Mark {
        cell: g.cell((x / 20.0) as i64, (y / 20.0) as i64).unwrap(),
        floor: (x / 20.0, y / 20.0),
        pixel: (x, y),
        area: 79,
        confidence: 1.0,
    };
    let robots = [robot(110.0, 70.0)];
    let read_beside = |(img, classes): &(RgbImage, Vec<u8>), missing: usize, robots: &[Mark]| {
        missing_faint(
            (&found, robots),
            missing,
            &g,
            (&i2f, None),
            0.05,
            classes,
            (img, &classifier, Class::Goal),
        )
    };
    let read = |(img, classes): &(RgbImage, Vec<u8>), missing: usize| {
        missing_faint(
            (&found, &robots),
            missing,
            &g,
            (&i2f, None),
            0.05,
            classes,
            (img, &classifier, Class::Goal),
        )
    };
    let none = (0, 0, 0, 0);
    let grey = Rgb([128u8, 128, 128]);
    let one = view(&[(50.0, 30.0)], none, grey);
    let marks = read(&one, 1).expect("read");
    assert_eq!(marks.len(), 1);
    assert_eq!(g.xy(marks[0].cell), (2, 1));
    assert!(marks[0].confidence <= 0.5, "{:?}", marks[0]);
    // As many as are missing, or nothing read.
    assert_eq!(read(&one, 2).unwrap_err(), 1);
    assert_eq!(
        read(&view(&[(50.0, 30.0), (90.0, 50.0)], none, grey), 1).unwrap_err(),
        2
    );
    // Not a stretch of floor of that green, nor one in a shadow.
    assert!(read(&view(&[], (30, 25, 110, 35), faint), 1).is_err());
    let dark = Rgb([56u8, 71, 56]);
    assert_eq!(classifier.faint_mark(dark.0), None);
    assert!(read(&view(&[], (45, 25, 56, 36), dark), 1).is_err());
    // Not against a green shelf (a pale top's faint edge), but against a lilac one.
    let green = Rgb([40u8, 150, 40]);
    assert_eq!(classifier.classify(green.0), Class::Goal);
    let shelf = Rgb([150u8, 60, 160]);
    assert_eq!(classifier.classify(shelf.0), Class::Obstacle);
    assert!(read(&view(&[(50.0, 30.0)], (55, 20, 58, 40), green), 1).is_err());
    assert!(read(&view(&[(50.0, 30.0)], (55, 20, 58, 40), shelf), 1).is_ok());
    // On the blocked cell, next to the goal read (its glow), or to a robot (its fringe).
    assert!(read(&view(&[(70.0, 30.0)], none, grey), 1).is_err());
    assert!(read(&view(&[(20.0, 10.0)], none, grey), 1).is_err());
    assert!(read_beside(&one, 1, &[robot(50.0, 45.0)]).is_err());
    assert!(read_beside(&one, 1, &[robot(50.0, 70.0)]).is_ok());
    // Nothing read when the goal read lies against a green shelf (may be its fringe).
    assert_eq!(
        read(&view(&[(50.0, 30.0)], (14, 0, 20, 20), green), 1).unwrap_err(),
        0
    );
}

/// The image-to-floor map of a 6 × 4 floor of 20 px cells seen straight down (120 × 80 px).
fn six_by_four() -> Homography {
    Homography::floor_to_image(
        6.0,
        4.0,
        [(0.0, 0.0), (120.0, 0.0), (120.0, 80.0), (0.0, 80.0)],
    )
    .and_then(|f2i| f2i.inverse())
    .unwrap()
}

/// The 6 × 4 grid of [`six_by_four`] with cell (3, 1) blocked.
fn six_by_four_grid() -> Grid {
    let mut blocked = vec![false; 24];
    blocked[6 + 3] = true;
    Grid::new(6, 4, blocked)
}

/// The pixels (indices into a 120 × 80 image) whose centres lie within `r` of `(cx, cy)`.
fn disc_px(cx: f64, cy: f64, r: f64) -> Vec<usize> {
    (0..80usize)
        .flat_map(|y| (0..120usize).map(move |x| (x, y)))
        .filter(|&(x, y)| (x as f64 + 0.5 - cx).hypot(y as f64 + 0.5 - cy) <= r)
        .map(|(x, y)| y * 120 + x)
        .collect()
}

/// A shelf of nearly the floor's colour on cell (6, 1): brighter than the floor, with its
/// shadow beside it. Either alone is refused; together they tell the shelf
/// ([`super::corroborated`]), unless another free cell looks like its top, or a free cell's
/// window is partly covered. Each guard fails this test when taken out.
#[test]
fn a_shelf_of_the_floor_s_colour_is_told_by_its_look_and_its_shadow() {
    let top = [224u8, 218, 205];
    let view = |shadow: bool| {
        let mut p = scene();
        if shadow {
            p.blocked.push((6, 1));
        }
        let mut img = p.straight(12);
        fill(&mut img, (72, 12, 84, 24), top);
        img
    };
    let blocked_cells = |r: &AerialReading| -> Vec<(u32, u32)> {
        (0..40)
            .filter(|&i| !r.grid.is_free(Cell(i)))
            .map(|i| r.grid.xy(Cell(i)))
            .collect()
    };
    let told = png(&view(true));
    let r = read_aerial(&told, "v.png", &grid(8, 5)).unwrap();
    assert_eq!(blocked_cells(&r), [(3, 1), (6, 1), (3, 2), (3, 3)]);
    assert_eq!(r.floor_tops, [Cell(14)]);
    assert!(r.settled.is_empty());
    let audited = audit_aerial(&told, "v.png", &grid(8, 5)).unwrap();
    assert!(audited.doubts.is_empty(), "{:?}", audited.doubts);
    assert_eq!(audited.reading.floor_tops, r.floor_tops);
    // The look alone (no shadow): refused.
    let e = read_aerial(&png(&view(false)), "v.png", &grid(8, 5)).unwrap_err();
    assert!(e.reason.contains("does not look like the floor"), "{e}");
    // Another free cell, (1, 3), as bright as the top: it may be one too.
    let mut img = view(true);
    fill(&mut img, (12, 36, 24, 48), top);
    let e = read_aerial(&png(&img), "v.png", &grid(8, 5)).unwrap_err();
    assert!(e.reason.contains("does not look like the floor"), "{e}");
    // A free cell, (5, 3), a fifth brighter than the floor: like the floor on its own, but
    // more like the top than the floor beside a top read so.
    let brighter = [204u8, 198, 186];
    let mut img = scene().straight(12);
    fill(&mut img, (62, 38, 70, 46), brighter);
    let r = read_aerial(&png(&img), "v.png", &grid(8, 5)).unwrap();
    assert!(r.grid.is_free(Cell(29)));
    let mut img = view(true);
    fill(&mut img, (62, 38, 70, 46), brighter);
    let e = read_aerial(&png(&img), "v.png", &grid(8, 5)).unwrap_err();
    assert!(e.reason.contains("does not look like the floor"), "{e}");
    // A free cell, (6, 4), partly covered (a line 8 × 1 px from the right of its window into
    // the edge of the cell beside it that no window counts, past the 3 × 3 averaging a fifth
    // of the window, and longer than a speck: see `pixels::set_aside_specks`): read free
    // alone, but not in a view read so.
    let mut img = view(true);
    fill(&mut img, (80, 55, 88, 56), [40, 70, 170]);
    let e = read_aerial(&png(&img), "v.png", &grid(8, 5)).unwrap_err();
    assert!(e.reason.contains("does not look like the floor"), "{e}");
    let mut img = scene().straight(12);
    fill(&mut img, (80, 55, 88, 56), [40, 70, 170]);
    let r = read_aerial(&png(&img), "v.png", &grid(8, 5)).unwrap();
    assert!(r.grid.is_free(Cell(38)));
}

/// A navy floor with white lines four pixels wide along the borders of its 10 px cells (a
/// blurred line on a small view): the whole floor's median is the lines', the cells' middles' is the navy (scaled to the
/// whole floor's brightness), 3 % or more apart; without lines the two are one.
#[test]
fn painted_lines_tint_the_whole_floor_s_colour_not_the_cells_middles() {
    let (navy, white) = (Rgb([40u8, 48, 60]), Rgb([230u8, 230, 225]));
    let lined = RgbImage::from_fn(80, 80, |x, y| {
        if x % 10 < 2 || x % 10 >= 8 || y % 10 < 2 || y % 10 >= 8 {
            white
        } else {
            navy
        }
    });
    let f2i = Homography::floor_to_image(
        8.0,
        8.0,
        [(0.0, 0.0), (80.0, 0.0), (80.0, 80.0), (0.0, 80.0)],
    )
    .unwrap();
    let i2f = f2i.inverse().unwrap();
    let (all, middles) = floor_colours(&lined, &i2f, (8.0, 8.0));
    let middles = middles.unwrap();
    // The middles' hue is the navy's: its channels in the navy's ratios.
    assert!(
        (middles[2] / middles[0] - 60.0 / 40.0).abs() < 1e-9,
        "{middles:?}"
    );
    assert!(
        ((middles.iter().sum::<f64>()) - all.iter().sum::<f64>()).abs() < 1e-9,
        "{all:?} {middles:?}"
    );
    assert!(middles_apart(all, middles), "{all:?} {middles:?}");
    let plain = RgbImage::from_pixel(80, 80, navy);
    let (all, middles) = floor_colours(&plain, &i2f, (8.0, 8.0));
    assert!(!middles_apart(all, middles.unwrap()));
}
