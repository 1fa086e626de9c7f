//! Render random walls to images (scaled, bordered, anti-aliased, blurred, noisy) and read
//! them back: the reader must recover the exact wall.

use image::{ImageFormat, Rgb, RgbImage};
use mason_wall::generate::{random_layer_text, WallShape};
use mason_wall::{
    parse_layer_text, read_image, read_png, render, BrickType, Location, RasterStyle, Wall,
    WallErrorKind,
};
use proptest::prelude::*;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;

/// Per brick (level, type, x in units, label), then supports and neighbours by label.
type Canonical = (
    Vec<(u32, BrickType, i64, u32)>,
    Vec<Vec<u32>>,
    Vec<Vec<u32>>,
);

/// A canonical description: per brick (level, type, x in units), and the relations by label.
fn canonical(w: &Wall) -> Canonical {
    let x_min = w
        .bricks()
        .iter()
        .map(|b| b.footprint.x0)
        .fold(f64::INFINITY, f64::min);
    let bricks = w
        .bricks()
        .iter()
        .map(|b| {
            let x = ((b.footprint.x0 - x_min) / 0.3).round() as i64;
            (b.level, b.kind, x, b.label)
        })
        .collect();
    let labels = |ids: &[mason_wall::BrickId]| ids.iter().map(|&i| w.brick(i).label).collect();
    let supports = w.ids().map(|i| labels(w.supports(i))).collect();
    let neighbours = w.ids().map(|i| labels(w.neighbours(i))).collect();
    (bricks, supports, neighbours)
}

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

fn check_round_trip(seed: u64) -> Result<(), TestCaseError> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let text = random_layer_text(&mut rng, &WallShape::default());
    let wall = parse_layer_text(&text, "generated").expect("generator makes valid walls");
    let style = RasterStyle {
        unit_px: rng.gen_range(8.0..24.0),
        border_px: f64::from(rng.gen_range(1..=3u8)),
        border: if rng.gen_bool(0.5) {
            [0, 0, 0]
        } else {
            [255, 255, 255]
        },
        background: [255, 255, 255],
        margin_px: rng.gen_range(0..10),
    };
    let mut img = render(&wall, &style);
    if rng.gen_bool(0.7) {
        img = blur(&img);
    }
    add_noise(&mut img, &mut rng, 20);
    let read = read_png(&png_bytes(&img), "generated.png")
        .map_err(|e| TestCaseError::fail(format!("{e}\nwall:\n{text}\nstyle: {style:?}")))?;
    prop_assert_eq!(
        canonical(&read),
        canonical(&wall),
        "wall:\n{}\nstyle: {:?}",
        text,
        style
    );
    Ok(())
}

proptest! {
    // A fixed generator seed keeps CI reproducible; the ignored stress test and the
    // regression below cover other seeds.
    #![proptest_config(ProptestConfig {
        cases: 160,
        rng_seed: proptest::test_runner::RngSeed::Fixed(0x6d61_736f_6e21),
        ..ProptestConfig::default()
    })]
    #[test]
    fn random_walls_survive_scaling_borders_blur_and_noise(seed in any::<u64>()) {
        check_round_trip(seed)?;
    }
}

/// Regression (issue #2): at 8.4 px per 0.30 m with a 1 px black border, blur and noise, the
/// border between two adjacent red bricks dims a single column, and they read as one 0.61 m
/// red brick.
#[test]
fn adjacent_reds_at_8_4_px_with_a_1_px_black_border_stay_apart() {
    check_round_trip(3131920892271388343).unwrap();
}

/// Regression (issue #2): `R . R`, two red bricks alone in one layer, at 8.8–9.1 px per 0.30 m
/// with a 3 px black border. With no joined brick and no layer separator the border came from
/// the 2/3 height rule, which was too rough at that size, and the second brick moved one slot
/// right. The dark ring around each brick now gives the border.
#[test]
fn two_lone_reds_with_a_3_px_black_border_keep_their_empty_slot() {
    for stress_case in [115895, 134349] {
        check_round_trip(stress_case ^ 0x5eed).unwrap();
    }
}

/// Regression (issue #2): `R . R` at 8.0 px per 0.30 m with a 3 px white border. Two bricks
/// of one length with a border as light as the background leave only the layer's height to
/// find the unit by; the clipped strength took 0.4 px off each brick's width, and the second
/// brick moved one slot right. The unit now comes from the grid the two bricks sit on, and
/// the widths from the linear colour share.
#[test]
fn two_lone_reds_with_a_3_px_white_border_keep_their_empty_slot() {
    check_round_trip(79839 ^ 0x5eed).unwrap();
}

/// One layer of bricks that touch nothing: the border must come from the dark ring (black
/// borders), from the lengths of different colours, or from the grid the bricks sit on
/// (white borders), never from the joins.
#[test]
fn lone_bricks_in_one_layer_at_small_scales() {
    let cases: [(&str, &[[u8; 3]]); 4] = [
        ("R . R", &[[0, 0, 0], [255, 255, 255]]),
        ("B . . B", &[[0, 0, 0], [255, 255, 255]]),
        ("R . . G . O", &[[0, 0, 0], [255, 255, 255]]),
        ("O . . R", &[[0, 0, 0], [255, 255, 255]]),
    ];
    for (text, borders) in cases {
        let wall = parse_layer_text(text, "t").unwrap();
        for &border in borders {
            for (i, unit_px) in [8.0, 8.4, 8.8, 9.2, 10.0].into_iter().enumerate() {
                for border_px in [1.0, 2.0, 3.0] {
                    let seed = i as u64;
                    let mut rng = ChaCha8Rng::seed_from_u64(seed);
                    let style = RasterStyle {
                        unit_px,
                        border_px,
                        border,
                        background: [255, 255, 255],
                        margin_px: 2 * i as u32,
                    };
                    let mut img = render(&wall, &style);
                    if i % 2 == 0 {
                        img = blur(&img);
                    }
                    add_noise(&mut img, &mut rng, 20);
                    let read = read_image(&img, "t.png")
                        .unwrap_or_else(|e| panic!("{text} {style:?}: {e}"));
                    assert_eq!(canonical(&read), canonical(&wall), "{text} {style:?}");
                }
            }
        }
    }
}

#[test]
fn smallest_scale_thickest_black_border_with_blur_and_noise() {
    let wall = parse_layer_text("R G R B\nG R O R G\nB B R R O", "t").unwrap();
    for border in [[0, 0, 0], [255, 255, 255]] {
        for seed in 0..20 {
            let mut rng = ChaCha8Rng::seed_from_u64(seed);
            let style = RasterStyle {
                unit_px: 8.0,
                border_px: 3.0,
                border,
                ..RasterStyle::default()
            };
            let mut img = blur(&render(&wall, &style));
            add_noise(&mut img, &mut rng, 20);
            let read = read_image(&img, "t.png").unwrap();
            assert_eq!(canonical(&read), canonical(&wall), "seed {seed}");
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
    // Render R G R, then swap the red and green channels of the green brick's pixels: it
    // becomes a red brick two units long.
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
            img.put_pixel(x, y, Rgb([g, r, b]));
        }
    }
    let e = read_image(&img, "bad.png").unwrap_err();
    match e.kind {
        WallErrorKind::LengthMismatch { kind, .. } => assert_eq!(kind, BrickType::Red),
        other => panic!("unexpected {other:?}"),
    }
    assert!(
        matches!(e.location, Location::Pixel(x, _) if (20..60).contains(&x)),
        "{e}"
    );
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

/// The same round trip over many more seeds (3 000, or `MASON_STRESS_CASES`):
/// `cargo test -p mason-wall --release --test png_roundtrip -- --ignored`.
#[test]
#[ignore]
fn stress_round_trip_many_seeds() {
    let cases = std::env::var("MASON_STRESS_CASES")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(3000u64);
    let failures: Vec<String> = (0..cases)
        .filter_map(
            |seed| match std::panic::catch_unwind(|| check_round_trip(seed ^ 0x5eed)) {
                Ok(Ok(())) => None,
                Ok(Err(e)) => Some(format!("{seed}: {e}")),
                Err(_) => Some(format!("{seed}: the reader panicked")),
            },
        )
        .collect();
    assert!(
        failures.is_empty(),
        "{} failures:\n{}",
        failures.len(),
        failures.join("\n")
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
