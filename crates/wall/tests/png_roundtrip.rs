//! Render random walls to images (scaled, bordered, anti-aliased, blurred, noisy) and read
//! them back: the reader must recover the exact wall.

use image::{ImageFormat, Rgb, RgbImage};
use mason_wall::generate::{random_layer_text, WallShape};
use mason_wall::{
    parse_layer_text, read_image, read_png, render, BrickType, Location, RasterStyle, Wall,
    WallErrorKind,
};
use proptest::prelude::*;

mod common;
use common::{ambiguous_without_borders, canonical};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

fn blur(img: &RgbImage) -> RgbImage {
    let (w, h) = img.dimensions();
    let pass = |src: &RgbImage, dx: i64, dy: i64| {
        let mut out = RgbImage::new(w, h);
        for y in 0..h {
            for x in 0..w {
                let at = |o: i64| {
                    let xx = (i64::from(x) + o * dx).clamp(0, i64::from(w) - 1) as u32;
                    let yy = (i64::from(y) + o * dy).clamp(0, i64::from(h) - 1) as u32;
                    src.get_pixel(xx, yy).0
                };
                let (a, b, c) = (at(-1), at(0), at(1));
                let mut p = [0u8; 3];
                for k in 0..3 {
                    p[k] =
                        ((u16::from(a[k]) + 2 * u16::from(b[k]) + u16::from(c[k]) + 2) / 4) as u8;
                }
                out.put_pixel(x, y, Rgb(p));
            }
        }
        out
    };
    pass(&pass(img, 1, 0), 0, 1)
}

fn add_noise(img: &mut RgbImage, rng: &mut ChaCha8Rng, amplitude: i16) {
    for p in img.pixels_mut() {
        for c in p.0.iter_mut() {
            *c = (i16::from(*c) + rng.gen_range(-amplitude..=amplitude)).clamp(0, 255) as u8;
        }
    }
}

fn png_bytes(img: &RgbImage) -> Vec<u8> {
    let mut out = std::io::Cursor::new(Vec::new());
    img.write_to(&mut out, ImageFormat::Png).unwrap();
    out.into_inner()
}

/// One drawing's proportions and rendering.
#[derive(Clone, Copy, Debug)]
struct Drawing {
    style: RasterStyle,
    blur: bool,
    noise: i16,
}

/// The grid of proportions the reader is held to (issue #13): layer height 0.3–3 units,
/// borders 0–4 px, 8–40 px per unit, blur and noise or not, white, grey or black borders on
/// white or pale paper.
const LAYER_UNITS: [f64; 7] = [0.3, 0.5, 2.0 / 3.0, 1.0, 1.25, 2.0, 3.0];
const BORDER_PX: [f64; 5] = [0.0, 1.0, 2.0, 3.0, 4.0];
const UNIT_PX: [f64; 6] = [8.0, 12.0, 16.0, 24.0, 32.0, 40.0];
const BORDERS: [[u8; 3]; 3] = [[0, 0, 0], [128, 128, 128], [255, 255, 255]];
const BACKGROUNDS: [[u8; 3]; 2] = [[255, 255, 255], [238, 232, 214]];

fn random_drawing(rng: &mut ChaCha8Rng) -> Drawing {
    let jitter = if rng.gen_bool(0.5) {
        rng.gen_range(0.0..1.0)
    } else {
        0.0
    };
    Drawing {
        style: RasterStyle {
            unit_px: UNIT_PX[rng.gen_range(0..UNIT_PX.len())] + jitter,
            layer_units: LAYER_UNITS[rng.gen_range(0..LAYER_UNITS.len())],
            border_px: BORDER_PX[rng.gen_range(0..BORDER_PX.len())],
            border: BORDERS[rng.gen_range(0..BORDERS.len())],
            background: BACKGROUNDS[rng.gen_range(0..BACKGROUNDS.len())],
            margin_px: rng.gen_range(0..10),
        },
        blur: rng.gen_bool(0.5),
        noise: if rng.gen_bool(0.5) { 20 } else { 0 },
    }
}

/// Whether the reader's documented limits allow the drawing: every brick shows at least
/// 3 px of colour along the wall and 5 px across, and borders are narrower than 0.6 units.
fn within_limits(style: &RasterStyle) -> bool {
    let colour_width = style.unit_px - style.border_px;
    let colour_height = style.layer_units * style.unit_px - style.border_px;
    colour_width >= 3.0 && colour_height >= 5.0 && style.border_px < 0.6 * style.unit_px
}

/// What one round trip showed.
#[derive(Debug, PartialEq)]
enum Trip {
    /// Read back exactly.
    Exact,
    /// Outside the reader's limits, or ambiguous by nature: not drawn.
    Skipped,
    /// The reader said the drawing was ambiguous (one layer, bricks that do not pin the unit).
    Ambiguous,
}

fn draw(wall: &Wall, drawing: &Drawing, rng: &mut ChaCha8Rng) -> RgbImage {
    let mut img = render(wall, &drawing.style);
    if drawing.blur {
        img = blur(&img);
    }
    if drawing.noise > 0 {
        add_noise(&mut img, rng, drawing.noise);
    }
    img
}

fn round_trip(seed: u64) -> Result<Trip, String> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let text = random_layer_text(&mut rng, &WallShape::default());
    let wall = parse_layer_text(&text, "generated").expect("generator makes valid walls");
    let drawing = random_drawing(&mut rng);
    if !within_limits(&drawing.style)
        || (drawing.style.border_px == 0.0 && ambiguous_without_borders(&wall))
    {
        return Ok(Trip::Skipped);
    }
    let img = draw(&wall, &drawing, &mut rng);
    let context = || format!("wall:\n{text}\n{drawing:?}");
    match read_png(&png_bytes(&img), "generated.png") {
        Ok(read) if canonical(&read) == canonical(&wall) => Ok(Trip::Exact),
        Ok(read) => Err(format!(
            "read a different wall:\n{}\n{}",
            mason_wall::to_layer_text(&read),
            context()
        )),
        Err(e) if wall.levels() == 1 && e.to_string().contains("ambiguous") => {
            if std::env::var_os("MASON_STRESS_SHOW_AMBIGUOUS").is_some() {
                println!("ambiguous: {text} {drawing:?}");
            }
            Ok(Trip::Ambiguous)
        }
        Err(e) => Err(format!("{e}\n{}", context())),
    }
}

fn check_round_trip(seed: u64) -> Result<(), TestCaseError> {
    round_trip(seed).map(|_| ()).map_err(TestCaseError::fail)
}

proptest! {
    // A fixed generator seed keeps CI reproducible; the ignored stress test covers more.
    #![proptest_config(ProptestConfig {
        cases: 400,
        rng_seed: proptest::test_runner::RngSeed::Fixed(0x6d61_736f_6e21),
        ..ProptestConfig::default()
    })]
    #[test]
    fn random_walls_at_any_proportions_read_back_exactly(seed in any::<u64>()) {
        check_round_trip(seed)?;
    }
}

/// Every cell of the proportion grid, with one random wall each (blurred and noisy).
#[test]
fn every_cell_of_the_proportion_grid_reads_back() {
    let mut checked = 0;
    for (i, &layer_units) in LAYER_UNITS.iter().enumerate() {
        for (j, &border_px) in BORDER_PX.iter().enumerate() {
            for (k, &unit_px) in UNIT_PX.iter().enumerate() {
                let seed = (i * 100 + j * 10 + k) as u64;
                let mut rng = ChaCha8Rng::seed_from_u64(seed);
                let text = random_layer_text(&mut rng, &WallShape::default());
                let wall = parse_layer_text(&text, "grid").unwrap();
                let drawing = Drawing {
                    style: RasterStyle {
                        unit_px,
                        layer_units,
                        border_px,
                        border: BORDERS[seed as usize % 3],
                        background: BACKGROUNDS[seed as usize % 2],
                        margin_px: 3,
                    },
                    blur: true,
                    noise: 20,
                };
                if !within_limits(&drawing.style)
                    || (border_px == 0.0 && ambiguous_without_borders(&wall))
                {
                    continue;
                }
                let img = draw(&wall, &drawing, &mut rng);
                match read_image(&img, "grid.png") {
                    Ok(read) => {
                        assert_eq!(canonical(&read), canonical(&wall), "{text}\n{drawing:?}")
                    }
                    Err(e) if wall.levels() == 1 && e.to_string().contains("ambiguous") => {}
                    Err(e) => panic!("{e}\n{text}\n{drawing:?}"),
                }
                checked += 1;
            }
        }
    }
    assert!(checked > 150, "only {checked} cells drawn");
}

/// One layer of bricks that touch nothing. Different colours drawn with a visible border are
/// read exactly (the border around the wall is measured); with a border as white as the
/// paper, or with bricks all alike, the drawing may also be reported as ambiguous, never
/// misread.
/// Drawings the stress run once misread, each standing for a kind of drawing: a layer's
/// blurred, noisy lower edge that flickers over several rows (once called a stray mark); two
/// colours blurred into each other between borderless layers (once measured as a 1.5 px
/// border, which picked a grid a quarter as wide); orange on blue across a grey border (orange
/// and blue blend through grey, so that border must not be taken for their blend).
#[test]
fn drawings_the_stress_run_once_misread() {
    let cream = BACKGROUNDS[1];
    let grey = [128, 128, 128];
    // (wall, px per unit, layer height in units, border px, border colour, margin, noise, seed)
    let cases = [
        (
            "G O G G | O R G\nO O R | G R O . R R R R",
            24.04,
            3.0,
            3.0,
            grey,
            1,
            20,
            0x1_1a9d,
        ),
        ("R\nG R R R R", 24.13, 3.0, 0.0, [0, 0, 0], 9, 20, 0x1_5a7f),
        ("B\nO", 16.0, 3.0, 2.0, grey, 7, 0, 0),
        ("B\nO", 24.0, 3.0, 2.0, grey, 8, 0, 0),
        // Borderless: a blurred red on green between layers is no border, and the border
        // seen between layers is tried as the grid's border even where the free fit drifts.
        ("R\nG R R R", 32.0, 1.25, 0.0, grey, 3, 0, 0),
        ("B R B\nB O", 8.4514, 3.0, 0.0, grey, 8, 0, 0),
        // Borderless, blurred and noisy, touching the image's edge: the red on green between
        // the layers blends straight, so no border is seen there (the stress run's seed
        // 187 161 misread this when that rule was dropped).
        ("R\nG R R R R", 12.0, 3.0, 0.0, grey, 0, 20, 1),
    ];
    for (text, unit_px, layer_units, border_px, border, margin_px, noise, seed) in cases {
        let wall = parse_layer_text(text, "t").unwrap();
        let drawing = Drawing {
            style: RasterStyle {
                unit_px,
                layer_units,
                border_px,
                border,
                background: cream,
                margin_px,
            },
            blur: true,
            noise,
        };
        let img = draw(&wall, &drawing, &mut ChaCha8Rng::seed_from_u64(seed));
        let read = read_image(&img, "t.png").unwrap_or_else(|e| panic!("{text}: {e}"));
        assert_eq!(canonical(&read), canonical(&wall), "{text} {drawing:?}");
    }
}

#[test]
fn lone_bricks_in_one_layer() {
    let pinned = ["R . . G . O", "O . . R", "R . G . . B"];
    let equal = ["R . R", "B . . B"];
    for (text, expect_exact) in pinned
        .iter()
        .map(|t| (t, true))
        .chain(equal.iter().map(|t| (t, false)))
    {
        let wall = parse_layer_text(text, "t").unwrap();
        for border in BORDERS {
            for unit_px in [8.0, 9.2, 13.0, 24.0] {
                for border_px in [1.0, 2.0, 3.0] {
                    let style = RasterStyle {
                        unit_px,
                        border_px,
                        border,
                        margin_px: 4,
                        ..RasterStyle::default()
                    };
                    let img = blur(&render(&wall, &style));
                    match read_image(&img, "t.png") {
                        Ok(read) => {
                            assert_eq!(canonical(&read), canonical(&wall), "{text} {style:?}")
                        }
                        Err(e) => {
                            let visible = border != [255, 255, 255];
                            assert!(!(expect_exact && visible), "{text} {style:?}: {e}");
                            assert!(e.to_string().contains("ambiguous"), "{e}");
                        }
                    }
                }
            }
        }
    }
}

#[test]
fn undecodable_bytes_are_an_error() {
    let e = read_png(b"not a png", "x.png").unwrap_err();
    assert!(matches!(e.kind, WallErrorKind::ImageDecode { .. }));
    assert!(e.to_string().starts_with("x.png: cannot decode the image"));
}

#[test]
fn blank_image_has_no_bricks() {
    let img = RgbImage::from_pixel(40, 30, Rgb([255, 255, 255]));
    let e = read_image(&img, "blank.png").unwrap_err();
    assert_eq!(e.kind, WallErrorKind::NoBricksInImage);
    let e = read_image(&RgbImage::new(0, 0), "empty.png").unwrap_err();
    assert!(matches!(e.kind, WallErrorKind::ImageDecode { .. }));
}

#[test]
fn brick_of_wrong_length_names_its_pixel() {
    // Render R G R, then swap the green and blue channels of the green brick's pixels: it
    // becomes a blue brick two units long, and blue bricks are four.
    let wall = parse_layer_text("R G R", "t").unwrap();
    let style = RasterStyle {
        unit_px: 20.0,
        border_px: 2.0,
        margin_px: 0,
        ..RasterStyle::default()
    };
    let mut img = render(&wall, &style);
    for x in 20..60 {
        for y in 0..img.height() {
            let [r, g, b] = img.get_pixel(x, y).0;
            img.put_pixel(x, y, Rgb([r, b, g]));
        }
    }
    let e = read_image(&img, "bad.png").unwrap_err();
    match e.kind {
        WallErrorKind::LengthMismatch { kind, .. } => assert_eq!(kind, BrickType::Blue),
        other => panic!("unexpected {other:?}"),
    }
    assert!(
        matches!(e.location, Location::Pixel(x, _) if (20..60).contains(&x)),
        "{e}"
    );
}

/// Drawings made with ImageMagick (`scripts/draw-fixtures.sh`), not by Mason's renderer:
/// stroked rectangles with anti-aliased edges, at other proportions and on other paper.
#[test]
fn drawings_made_with_imagemagick_read_back() {
    const THREE_LAYERS: &str = "R G R\nG B R G\nB O R G";
    const FIVE_LAYERS: &str = "G R G R . B\nO R G R R\nB B G R\nR O R G R\nG G B R R R";
    let data = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/data");
    for (file, text) in [
        ("wall-imagemagick.png", "R G R\nG B R G\nB O R G"),
        ("thesis-figure-3-2-imagemagick.png", "R G B G R\nG B R R G"),
        ("wall-imagemagick-borderless.png", "R R G . B\nO R R G R R"),
        // Layers 1.25, 1.0, 0.4 and 2.0 units tall, then scaled by 61.8 % and 173 %,
        // stretched 80 % × 130 %, and scaled 150 % with Lanczos.
        ("wall-imagemagick-125-scaled.png", THREE_LAYERS),
        ("wall-imagemagick-100-scaled.png", THREE_LAYERS),
        ("wall-imagemagick-040-stretched.png", THREE_LAYERS),
        ("wall-imagemagick-200-lanczos.png", THREE_LAYERS),
        // Five layers: 4 px dark outlines; 1 px outlines on ivory, blurred.
        ("wall-imagemagick-5-thick.png", FIVE_LAYERS),
        ("wall-imagemagick-5-blurred.png", FIVE_LAYERS),
    ] {
        let bytes = std::fs::read(data.join(file)).unwrap();
        let read = read_png(&bytes, file).unwrap_or_else(|e| panic!("{e}"));
        let expected = parse_layer_text(text, file).unwrap();
        assert_eq!(canonical(&read), canonical(&expected), "{file}");
    }
}

/// A wall drawn with filled rectangles: `(x, y, width, height, colour)`.
fn rectangles(width: u32, height: u32, shapes: &[(u32, u32, u32, u32, [u8; 3])]) -> RgbImage {
    let mut img = RgbImage::from_pixel(width, height, Rgb([255, 255, 255]));
    for &(x, y, w, h, colour) in shapes {
        for yy in y..y + h {
            for xx in x..x + w {
                img.put_pixel(xx, yy, Rgb(colour));
            }
        }
    }
    img
}

const RED: [u8; 3] = [235, 20, 20];
const GREEN: [u8; 3] = [20, 200, 40];

fn layout_error(img: &RgbImage) -> (String, Location) {
    let e = read_image(img, "bad.png").unwrap_err();
    (e.to_string(), e.location)
}

#[test]
fn a_stray_mark_too_thin_for_a_layer_is_named() {
    // A red and a green brick, and far above them a 2 px red line.
    let img = rectangles(
        60,
        40,
        &[
            (2, 25, 18, 12, RED),
            (22, 25, 38, 12, GREEN),
            (10, 5, 20, 2, RED),
        ],
    );
    let (message, at) = layout_error(&img);
    assert!(message.contains("2 px tall stands alone"), "{message}");
    assert!(matches!(at, Location::Pixel(9..=10, 5)), "{at:?}");
}

/// Found by fuzzing: a band whose colour changes every pixel or two has no run of colour
/// at all once the slivers between colours are dropped, and must be an error, not a panic.
#[test]
fn slivers_of_colour_with_no_run_are_named() {
    let data = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/data");
    let bytes = std::fs::read(data.join("fuzz-slivers.png")).unwrap();
    let e = read_png(&bytes, "fuzz-slivers.png").unwrap_err();
    assert!(matches!(e.location, Location::Pixel(..)), "{e}");
    assert!(e.to_string().contains("changes every pixel or two"), "{e}");
}

#[test]
fn a_layer_of_slivers_under_bricks_is_named_not_dropped() {
    // Bricks on top of the slivers that crashed the reader once: dropping that layer would
    // make the bricks above it level 1.
    let data = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/data");
    let slivers = read_png_rgb(&data.join("fuzz-slivers.png"));
    let (w, h) = slivers.dimensions();
    let mut img = rectangles(w, h + 30, &[(0, 4, 60, 20, RED), (62, 4, 120, 20, GREEN)]);
    image::imageops::replace(&mut img, &slivers, 0, 30);
    let (message, location) = layout_error(&img);
    assert!(message.contains("changes every pixel or two"), "{message}");
    assert!(
        matches!(location, Location::Pixel(_, y) if y >= 30),
        "{location:?}"
    );
}

fn read_png_rgb(path: &std::path::Path) -> RgbImage {
    image::open(path).unwrap().to_rgb8()
}

#[test]
fn a_mark_too_narrow_for_a_brick_is_named() {
    let img = rectangles(
        80,
        20,
        &[
            (2, 4, 18, 12, RED),
            (22, 4, 38, 12, GREEN),
            (70, 4, 2, 12, RED),
        ],
    );
    let (message, at) = layout_error(&img);
    assert!(message.contains("wide is too narrow"), "{message}");
    assert!(matches!(at, Location::Pixel(69..=72, _)), "{at:?}");
}

#[test]
fn a_brick_off_the_grid_is_named() {
    // Reds and a green on a 20 px grid with 2 px borders, and one red half a unit off.
    let img = rectangles(
        160,
        20,
        &[
            (1, 4, 18, 12, RED),
            (21, 4, 38, 12, GREEN),
            (61, 4, 18, 12, RED),
            (111, 4, 18, 12, RED),
        ],
    );
    // Three of the four bricks sit on one grid; the message names a brick and the reason.
    let (message, at) = layout_error(&img);
    assert!(
        message.contains("off the 0.30 m grid") || message.contains("bricks are"),
        "{message}"
    );
    assert!(matches!(at, Location::Pixel(..)), "{at:?}");
}

#[test]
fn bricks_too_small_for_any_unit_are_refused() {
    // One red brick 3 px long: a unit of 3 px is below the smallest the reader looks for.
    let img = rectangles(10, 10, &[(3, 2, 3, 6, RED)]);
    let (message, _) = layout_error(&img);
    assert!(message.contains("no unit of at least"), "{message}");
}

#[test]
fn touching_bricks_must_show_the_border_seen_elsewhere() {
    // 2 px borders everywhere, but the last two bricks touch across 6 px.
    let img = rectangles(
        170,
        40,
        &[
            (1, 4, 18, 12, RED),
            (21, 4, 38, 12, GREEN),
            (61, 4, 18, 12, RED),
            (81, 4, 38, 12, GREEN),
            (1, 18, 38, 12, GREEN),
            (41, 18, 18, 12, RED),
            (61, 18, 38, 12, GREEN),
            (105, 18, 12, 12, RED),
        ],
    );
    let e = read_image(&img, "bad.png").unwrap_err();
    assert!(matches!(e.location, Location::Pixel(..)), "{e}");
}

/// The image's size is checked before it is decoded: a PNG whose header claims 10 000 ×
/// 10 000 pixels is refused at once.
#[test]
fn an_oversized_image_is_refused_before_decoding() {
    let mut bytes = png_bytes(&RgbImage::new(1, 1));
    // IHDR: 8-byte signature, 4-byte length, "IHDR", width, height, then its CRC at 29..33.
    bytes[16..20].copy_from_slice(&10_000u32.to_be_bytes());
    bytes[20..24].copy_from_slice(&10_000u32.to_be_bytes());
    let crc = crc32(&bytes[12..29]);
    bytes[29..33].copy_from_slice(&crc.to_be_bytes());
    let e = read_png(&bytes, "huge.png").unwrap_err();
    assert!(e.to_string().contains("more than the"), "{e}");
}

/// A 2×1 palette PNG whose PLTE chunk is `palette` and, when given, whose tRNS chunk is
/// `trns`, every CRC right: the png crate (0.18) panicked on both when it expanded them.
fn palette_png(palette: &[u8], trns: Option<&[u8]>) -> Vec<u8> {
    let mut valid = Vec::new();
    {
        let mut encoder = png::Encoder::new(&mut valid, 2, 1);
        encoder.set_color(png::ColorType::Indexed);
        encoder.set_palette(vec![255, 0, 0, 0, 255, 0]);
        let mut writer = encoder.write_header().unwrap();
        writer.write_image_data(&[0, 1]).unwrap();
    }
    let chunk = |kind: &[u8], data: &[u8]| -> Vec<u8> {
        let mut c = (data.len() as u32).to_be_bytes().to_vec();
        c.extend_from_slice(kind);
        c.extend_from_slice(data);
        c.extend_from_slice(&crc32(&c[4..]).to_be_bytes());
        c
    };
    // Signature and IHDR (8 + 25 bytes), then our chunks, then the encoder's from IDAT on.
    let idat = valid.windows(4).position(|w| w == b"IDAT").unwrap() - 4;
    let mut out = valid[..33].to_vec();
    out.extend(chunk(b"PLTE", palette));
    if let Some(t) = trns {
        out.extend(chunk(b"tRNS", t));
    }
    out.extend_from_slice(&valid[idat..]);
    out
}

#[test]
fn malformed_palettes_are_refused_not_a_panic() {
    // The fixture is right when its palette is: two whole colours read as an image.
    let fine = read_png(&palette_png(&[255, 0, 0, 0, 255, 0], Some(&[255])), "p.png");
    assert!(
        !matches!(&fine, Err(e) if matches!(e.kind, WallErrorKind::ImageDecode { .. })),
        "{fine:?}"
    );
    let e = read_png(&palette_png(&[255, 0, 0, 0, 255], None), "p.png").unwrap_err();
    assert!(matches!(e.kind, WallErrorKind::ImageDecode { .. }), "{e}");
    assert!(e.to_string().contains("PLTE) is 5 bytes"), "{e}");
    let e = read_png(
        &palette_png(&[255, 0, 0, 0, 255, 0], Some(&[1, 2, 3])),
        "p.png",
    )
    .unwrap_err();
    assert!(e.to_string().contains("tRNS) has 3 entries for 2"), "{e}");
}

/// CRC-32 (IEEE), for patching a PNG header.
fn crc32(data: &[u8]) -> u32 {
    let mut crc = !0u32;
    for &byte in data {
        crc ^= u32::from(byte);
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
fn floating_brick_in_an_image_names_its_pixel() {
    // Two layers: bottom R at units 0–1, top R drawn at units 3–4.
    let base = parse_layer_text("R . . R", "t").unwrap();
    let style = RasterStyle {
        unit_px: 20.0,
        border_px: 2.0,
        margin_px: 4,
        ..RasterStyle::default()
    };
    let one = render(&base, &style);
    let (w, h) = one.dimensions();
    let layer_h = (20.0_f64 * 2.0 / 3.0) as u32;
    let mut img = RgbImage::from_pixel(w, h + layer_h, Rgb([255, 255, 255]));
    image::imageops::overlay(&mut img, &one, 0, i64::from(layer_h));
    // Erase the bottom-right brick, so the upper-right one (copied up) floats.
    let upper = image::imageops::crop_imm(&one, 60, 0, w - 60, h).to_image();
    image::imageops::overlay(&mut img, &upper, 60, 0);
    for x in 60..w {
        for y in (layer_h + 4)..(h + layer_h) {
            img.put_pixel(x, y, Rgb([255, 255, 255]));
        }
    }
    let e = read_image(&img, "float.png").unwrap_err();
    assert!(
        matches!(
            e.kind,
            WallErrorKind::FloatingBrick { .. } | WallErrorKind::ImageLayout { .. }
        ),
        "{e}"
    );
    assert!(matches!(e.location, Location::Pixel(..)), "{e}");
}

/// The same round trip over many more seeds, on every core (120 000, or
/// `MASON_STRESS_CASES`): `cargo test -p mason-wall --release --test png_roundtrip --
/// --ignored --nocapture`. Prints how many drawings were read back exactly, skipped (outside
/// the limits or ambiguous by nature) and reported as ambiguous.
#[test]
#[ignore]
fn stress_round_trip_many_seeds() {
    let cases: u64 = std::env::var("MASON_STRESS_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(120_000);
    let threads = std::thread::available_parallelism().map_or(2, |n| n.get()) as u64;
    let results: Vec<(u64, u64, u64, Vec<String>)> = std::thread::scope(|scope| {
        let handles: Vec<_> = (0..threads)
            .map(|t| {
                scope.spawn(move || {
                    let (mut exact, mut skipped, mut ambiguous, mut failures) =
                        (0, 0, 0, Vec::new());
                    for seed in (t..cases).step_by(threads as usize) {
                        match std::panic::catch_unwind(|| round_trip(seed ^ 0x5eed)) {
                            Ok(Ok(Trip::Exact)) => exact += 1,
                            Ok(Ok(Trip::Skipped)) => skipped += 1,
                            Ok(Ok(Trip::Ambiguous)) => ambiguous += 1,
                            Ok(Err(e)) => failures.push(format!("{seed}: {e}")),
                            Err(_) => failures.push(format!("{seed}: the reader panicked")),
                        }
                    }
                    (exact, skipped, ambiguous, failures)
                })
            })
            .collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    });
    let exact: u64 = results.iter().map(|r| r.0).sum();
    let skipped: u64 = results.iter().map(|r| r.1).sum();
    let ambiguous: u64 = results.iter().map(|r| r.2).sum();
    let failures: Vec<&String> = results.iter().flat_map(|r| &r.3).collect();
    let drawn = cases - skipped;
    println!(
        "{cases} seeds: {drawn} drawn, {exact} read back exactly ({:.3} %), {ambiguous} \
         reported ambiguous (one layer), {} wrong or failed; {skipped} skipped",
        100.0 * exact as f64 / drawn.max(1) as f64,
        failures.len()
    );
    for f in &failures {
        println!("{f}");
    }
    // The measured rate (README): 3 of 100 118 drawings misread or refused; fail if that grows
    // past 0.1 %.
    assert!(
        failures.len() as f64 <= 0.001 * drawn as f64,
        "{} failures, first ones:\n{}",
        failures.len(),
        failures
            .iter()
            .take(20)
            .map(|s| s.as_str())
            .collect::<Vec<_>>()
            .join("\n")
    );
}

proptest! {
    #![proptest_config(ProptestConfig {
        cases: 300,
        rng_seed: proptest::test_runner::RngSeed::Fixed(0x6e6f_7061_6e69),
        ..ProptestConfig::default()
    })]
    /// No image makes the reader panic: random rectangles of brick colours, black, white and
    /// grey on random backgrounds either read as some wall or give an error.
    #[test]
    fn arbitrary_images_never_panic(
        width in 1u32..60,
        height in 1u32..40,
        rects in proptest::collection::vec((0u32..60, 0u32..40, 1u32..30, 1u32..15, 0usize..7), 0..12),
        noise in 0i16..30,
        seed in any::<u64>(),
    ) {
        let palette = [
            [230, 20, 20], [20, 200, 40], [30, 40, 220], [255, 165, 0],
            [0, 0, 0], [255, 255, 255], [128, 128, 128],
        ];
        let mut img = RgbImage::from_pixel(width, height, Rgb([255, 255, 255]));
        for (x, y, w, h, c) in rects {
            for yy in y..(y + h).min(height) {
                for xx in x..(x + w).min(width) {
                    img.put_pixel(xx, yy, Rgb(palette[c]));
                }
            }
        }
        add_noise(&mut img, &mut ChaCha8Rng::seed_from_u64(seed), noise.max(1));
        if let Err(e) = read_image(&img, "random.png") {
            prop_assert!(e.to_string().starts_with("random.png"), "{e}");
        }
    }
}

/// Debugging aid: `MASON_PNG_SEED=N cargo test -p mason-wall --test png_roundtrip one_seed
/// -- --ignored --nocapture` draws seed N, saves it to /tmp/mason-seed.png and reads it.
#[test]
#[ignore]
fn one_seed() {
    // Skips (passes without drawing) when the variable is unset or not a number, so that
    // `-- --ignored` runs of the whole file, such as the stress command, pass through it.
    let Some(seed) = std::env::var("MASON_PNG_SEED")
        .ok()
        .and_then(|v| v.parse::<u64>().ok())
    else {
        println!("one_seed: skipped (set MASON_PNG_SEED to a seed)");
        return;
    };
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let text = random_layer_text(&mut rng, &WallShape::default());
    let wall = parse_layer_text(&text, "generated").unwrap();
    let drawing = random_drawing(&mut rng);
    let img = draw(&wall, &drawing, &mut rng);
    img.save("/tmp/mason-seed.png").unwrap();
    println!("{text}\n{drawing:?}\n{:?}", round_trip(seed));
}

/// Debugging aid: `MASON_PNG_TEXT='R B' MASON_PNG_STYLE='unit,layer,border,grey,blur,noise'
/// cargo test -p mason-wall --test png_roundtrip one_drawing -- --ignored --nocapture` draws
/// the wall (border grey level 0–255 on white), saves /tmp/mason-drawing.png and reads it.
#[test]
#[ignore]
fn one_drawing() {
    // Skips (passes without drawing) when either variable is unset or unreadable, so that
    // `-- --ignored` runs of the whole file, such as the stress command, pass through it.
    let text = std::env::var("MASON_PNG_TEXT").map(|t| t.replace("\\n", "\n"));
    let style: Option<Vec<f64>> = std::env::var("MASON_PNG_STYLE")
        .ok()
        .and_then(|s| s.split(',').map(|x| x.trim().parse().ok()).collect());
    let (Ok(text), Some(v)) = (text, style.filter(|v| v.len() >= 6)) else {
        println!(
            "one_drawing: skipped (set MASON_PNG_TEXT and MASON_PNG_STYLE, six or more numbers)"
        );
        return;
    };
    let wall = match parse_layer_text(&text, "t") {
        Ok(wall) => wall,
        Err(e) => {
            println!("one_drawing: MASON_PNG_TEXT: {e}");
            return;
        }
    };
    let drawing = Drawing {
        style: RasterStyle {
            unit_px: v[0],
            layer_units: v[1],
            border_px: v[2],
            border: [v[3] as u8; 3],
            background: if v.len() > 6 {
                BACKGROUNDS[1]
            } else {
                [255, 255, 255]
            },
            margin_px: if v.len() > 7 { v[7] as u32 } else { 3 },
        },
        blur: v[4] > 0.0,
        noise: v[5] as i16,
    };
    let img = draw(&wall, &drawing, &mut ChaCha8Rng::seed_from_u64(1));
    img.save("/tmp/mason-drawing.png").unwrap();
    match read_image(&img, "t.png") {
        Ok(read) => println!("{}", mason_wall::to_layer_text(&read)),
        Err(e) => println!("{e}"),
    }
}

/// A hostile image of more marks than a wall may have bricks is refused as too large (the
/// reader counts its runs before fitting a grid, which keeps a 49 MP image of them to 2 s:
/// README, "Limits and bad input").
#[test]
fn more_marks_than_bricks_allowed_are_refused_as_too_many_bricks() {
    // 3 × 3 px marks 1 px apart: 1 000 000 runs and one more.
    let (w, h) = (4000u32, 4004u32);
    let img = RgbImage::from_fn(w, h, |x, y| {
        let mark = x % 4 != 3 && y % 4 != 3 && (y < 4000 || x < 4);
        Rgb(if mark { RED } else { [255, 255, 255] })
    });
    let e = read_image(&img, "marks.png").unwrap_err();
    assert!(
        matches!(e.kind, WallErrorKind::TooLarge { what: "bricks", .. }),
        "{e}"
    );
}
