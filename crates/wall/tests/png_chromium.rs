//! Walls drawn by a renderer that is not Mason's: headless Chromium lays random walls out as
//! HTML boxes (fractional CSS pixels, outlines centred on the bricks' edges or inside them,
//! several palettes)
//! and screenshots them at device scale factors 1, 1.25, 1.5 and 2, so that its own
//! anti-aliasing and resampling make the edges. Each wall is cut out of the screenshot and read
//! back. `.ci/run` installs Debian's chromium (scripts/install-chromium.sh) and sets
//! MASON_REQUIRE_BROWSER=1; elsewhere the test is skipped when no browser is found.
//!
//! The stress run (ignored): `MASON_CHROMIUM_PAGES=200 cargo test --release -p mason-wall
//! --test png_chromium -- --ignored --nocapture`; MASON_CHROMIUM_SEED=N draws other walls,
//! and MASON_CHROMIUM_KEEP=1 keeps the last page and its screenshot in the temporary
//! directory.

use image::RgbImage;
use mason_wall::generate::{random_layer_text, WallShape};
use mason_wall::{parse_layer_text, read_image, Wall};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::Command;

mod common;
use common::{ambiguous_without_borders, canonical};

/// The first of `chromium`, `chromium-browser` or `google-chrome` found on PATH.
fn find_browser() -> Option<PathBuf> {
    let path = std::env::var_os("PATH")?;
    let names = ["chromium", "chromium-browser", "google-chrome"];
    names.iter().find_map(|name| {
        std::env::split_paths(&path)
            .map(|dir| dir.join(name))
            .find(|p| p.is_file())
    })
}

/// Brick fills as people pick them: (red, green, blue, orange).
const PALETTES: [[&str; 4]; 3] = [
    ["#ff0000", "#00ff00", "#0000ff", "#ffa500"],
    ["#e8201c", "#1ec83a", "#1e3cf0", "#ffa500"],
    ["#c83228", "#3caa46", "#3250c8", "#f0961e"],
];
const OUTLINES: [&str; 3] = ["#000000", "#808080", "#ffffff"];
const PAPERS: [&str; 2] = ["#ffffff", "#eee8d6"];
const SCALES: [f64; 4] = [1.0, 1.25, 1.5, 2.0];

/// Where a brick's outline lies: centred on its edge (as vector tools stroke) or inside it (a
/// CSS border: touching bricks show a line twice as wide as around the wall). Outlines outside
/// the bricks are not drawn: the reader does not read them (see the README's limits).
#[derive(Clone, Copy, Debug, PartialEq)]
enum Stroke {
    Centred,
    Inside,
}

const STROKES: [Stroke; 2] = [Stroke::Centred, Stroke::Inside];

/// One wall as laid out on a page, in CSS pixels.
struct Cell {
    wall: Wall,
    text: String,
    left: f64,
    top: f64,
    width: f64,
    height: f64,
    unit: f64,
    layer: f64,
    outline: f64,
    stroke: Stroke,
    /// Paper shown around the wall in the cut-out (CSS px).
    margin: f64,
}

/// Room between walls on a page (CSS px): more than any cell's margin and outline.
const GAP: f64 = 24.0;

/// A page of `count` random walls, one under the other.
fn random_page(rng: &mut ChaCha8Rng, count: usize) -> (Vec<Cell>, String) {
    let palette = PALETTES[rng.gen_range(0..PALETTES.len())];
    let paper = PAPERS[rng.gen_range(0..PAPERS.len())];
    let mut html = format!(
        "<!doctype html><html><head><style>body{{margin:0;background:{paper}}}\
         div{{position:absolute}}</style></head><body>"
    );
    let mut cells = Vec::new();
    let mut top = GAP;
    for _ in 0..count {
        let text = random_layer_text(rng, &WallShape::default());
        let wall = parse_layer_text(&text, "generated").expect("generator makes valid walls");
        let unit = (rng.gen_range(8.0..30.0f64) * 100.0).round() / 100.0;
        let layer = (unit * rng.gen_range(0.3..3.0f64) * 100.0).round() / 100.0;
        let outline = f64::from(rng.gen_range(0..=4u8));
        let colour = OUTLINES[rng.gen_range(0..OUTLINES.len())];
        let stroke = STROKES[rng.gen_range(0..STROKES.len())];
        let left = GAP + (rng.gen_range(0.0..1.0f64) * 100.0).round() / 100.0;
        let units = wall
            .bricks()
            .iter()
            .map(|b| (b.footprint.x1 / 0.3).round())
            .fold(0.0, f64::max);
        let levels = f64::from(wall.levels());
        for b in wall.bricks() {
            let x = left + (b.footprint.x0 / 0.3).round() * unit;
            let y = top + (levels - f64::from(b.level)) * layer;
            let fill = palette[b.kind.index()];
            let w = f64::from(b.kind.units()) * unit;
            let _ = write!(
                html,
                "<div style=\"left:{x:.2}px;top:{y:.2}px;width:{w:.2}px;height:{layer:.2}px;\
                 background:{fill}"
            );
            if outline > 0.0 {
                let _ = match stroke {
                    Stroke::Centred => write!(
                        html,
                        ";outline:{outline}px solid {colour};outline-offset:-{:.1}px",
                        outline / 2.0
                    ),
                    Stroke::Inside => write!(
                        html,
                        ";box-sizing:border-box;border:{outline}px solid {colour}"
                    ),
                };
            }
            html.push_str("\"></div>");
        }
        let (width, height) = (units * unit, levels * layer);
        let margin = f64::from(rng.gen_range(0..=10u8));
        cells.push(Cell {
            wall,
            text,
            left,
            top,
            width,
            height,
            unit,
            layer,
            outline,
            stroke,
            margin,
        });
        top += height + GAP;
    }
    html.push_str("</body></html>");
    (cells, html)
}

/// Screenshots `html` at `scale`; the page is `width` × `height` CSS px.
fn screenshot(browser: &Path, html: &str, size: (f64, f64), scale: f64, dir: &Path) -> RgbImage {
    let page = dir.join("page.html");
    let shot = dir.join("page.png");
    std::fs::write(&page, html).unwrap();
    let _ = std::fs::remove_file(&shot);
    let out = Command::new(browser)
        .args([
            "--headless",
            "--no-sandbox",
            "--disable-gpu",
            "--hide-scrollbars",
            "--no-first-run",
            "--disable-background-networking",
            "--disable-component-update",
            "--disable-sync",
        ])
        .arg(format!("--user-data-dir={}", dir.join("profile").display()))
        .arg(format!("--force-device-scale-factor={scale}"))
        .arg(format!(
            "--window-size={},{}",
            size.0.ceil() as u32,
            size.1.ceil() as u32
        ))
        .arg(format!("--screenshot={}", shot.display()))
        .arg(format!("file://{}", page.display()))
        .output()
        .expect("chromium runs");
    assert!(
        shot.is_file(),
        "chromium wrote no screenshot: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    image::open(&shot).unwrap().to_rgb8()
}

/// Whether the reader's documented limits allow the cell at `scale` (in device pixels): 3 px
/// of colour along the wall and 5 px across, borders under 0.6 units.
fn within_limits(cell: &Cell, scale: f64) -> bool {
    let line = match cell.stroke {
        Stroke::Centred => cell.outline,
        Stroke::Inside => 2.0 * cell.outline,
    };
    let (unit, layer, line) = (cell.unit * scale, cell.layer * scale, line * scale);
    unit - line >= 3.0 && layer - line >= 5.0 && line < 0.6 * unit
}

#[derive(Debug, Default)]
struct Tally {
    exact: usize,
    skipped: usize,
    ambiguous: usize,
    wrong: Vec<String>,
}

/// Draws `pages` pages of `per_page` walls, one page per scale factor in turn, and reads
/// every wall back.
fn run(browser: &Path, pages: usize, per_page: usize, seed: u64) -> Tally {
    // One directory per run: the tests of this file may run side by side.
    let name = format!("mason-png-chromium-{}-{seed:x}", std::process::id());
    let dir = std::env::temp_dir().join(name);
    std::fs::create_dir_all(&dir).unwrap();
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let mut tally = Tally::default();
    for page in 0..pages {
        let scale = SCALES[page % SCALES.len()];
        let (cells, html) = random_page(&mut rng, per_page);
        let width = cells.iter().map(|c| c.left + c.width).fold(0.0, f64::max) + GAP;
        let height = cells.last().map_or(0.0, |c| c.top + c.height) + GAP;
        let shot = screenshot(browser, &html, (width, height), scale, &dir);
        for cell in &cells {
            if !within_limits(cell, scale)
                || (cell.outline == 0.0 && ambiguous_without_borders(&cell.wall))
            {
                tally.skipped += 1;
                continue;
            }
            let px = |css: f64| (css * scale).round().max(0.0) as u32;
            let reach = cell.margin + cell.outline;
            let (x0, y0) = (px(cell.left - reach), px(cell.top - reach));
            let (x1, y1) = (
                px(cell.left + cell.width + reach).min(shot.width()),
                px(cell.top + cell.height + reach).min(shot.height()),
            );
            let img = image::imageops::crop_imm(&shot, x0, y0, x1 - x0, y1 - y0).to_image();
            let context = || {
                format!(
                    "page {page} (scale {scale}), wall at {:.2},{:.2}: unit {} px, layer {} px, \
                     outline {} px {:?}, margin {}\n{}",
                    cell.left,
                    cell.top,
                    cell.unit,
                    cell.layer,
                    cell.outline,
                    cell.stroke,
                    cell.margin,
                    cell.text
                )
            };
            match read_image(&img, "chromium.png") {
                Ok(read) if canonical(&read) == canonical(&cell.wall) => tally.exact += 1,
                Ok(read) => tally.wrong.push(format!(
                    "read a different wall:\n{}\n{}",
                    mason_wall::to_layer_text(&read),
                    context()
                )),
                Err(e) if cell.wall.levels() == 1 && e.to_string().contains("ambiguous") => {
                    tally.ambiguous += 1
                }
                Err(e) => tally.wrong.push(format!("{e}\n{}", context())),
            }
        }
    }
    if std::env::var_os("MASON_CHROMIUM_KEEP").is_none() {
        let _ = std::fs::remove_dir_all(&dir);
    }
    tally
}

fn browser_or_skip() -> Option<PathBuf> {
    let browser = find_browser();
    if browser.is_none() {
        assert!(
            std::env::var_os("MASON_REQUIRE_BROWSER").is_none(),
            "MASON_REQUIRE_BROWSER is set but no chromium was found (run scripts/install-chromium.sh)"
        );
        eprintln!("skipped: no chromium on PATH (scripts/install-chromium.sh installs it)");
    }
    browser
}

#[test]
fn walls_drawn_by_chromium_read_back() {
    let Some(browser) = browser_or_skip() else {
        return;
    };
    let tally = run(&browser, 4, 20, 0xc0ffee);
    println!("{tally:?}");
    assert!(tally.exact >= 40, "{tally:?}");
    assert!(tally.wrong.is_empty(), "{}", tally.wrong.join("\n\n"));
}

#[test]
#[ignore]
fn stress_walls_drawn_by_chromium() {
    let Some(browser) = browser_or_skip() else {
        return;
    };
    let pages: usize = std::env::var("MASON_CHROMIUM_PAGES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(40);
    let seed = std::env::var("MASON_CHROMIUM_SEED")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(0x5eed_c0de);
    let tally = run(&browser, pages, 25, seed);
    let drawn = tally.exact + tally.ambiguous + tally.wrong.len();
    println!(
        "{} pages: {drawn} walls drawn, {} read back exactly ({:.2} %), {} reported ambiguous \
         (one layer), {} wrong or refused; {} skipped",
        pages,
        tally.exact,
        100.0 * tally.exact as f64 / drawn.max(1) as f64,
        tally.ambiguous,
        tally.wrong.len(),
        tally.skipped
    );
    for w in &tally.wrong {
        println!("{w}\n");
    }
    assert!(tally.wrong.len() as f64 <= 0.001 * drawn as f64);
}
