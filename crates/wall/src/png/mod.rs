//! Wall images: a front view of the wall, read with no assumption about proportions.
//!
//! A wall drawing is a stack of horizontal bands, one per layer, and in each band a row of
//! coloured bricks. Every brick and every gap is a whole number of 0.30 m units, and the
//! colours' lengths are red : green : blue : orange = 1 : 2 : 4 : 6. Borders between bricks
//! may be 0 to a few pixels wide, in any grey, on a white or pale background. The height of a
//! band says nothing about the bricks: the MBZIRC sheets, the thesis's figures and sketches are
//! not drawn to scale in height. The reader goes through seven steps, one file each, read in
//! this order; [`read_image`] below calls them:
//!
//! 1. *classify* ([`classify`], `pixels.rs`): each pixel is red, green, blue, orange or
//!    nothing, by the thesis rule (DESIGN §2) plus our orange rule, applied to the pixel's
//!    colour part (the pixel minus its grey part, so that a brick colour blended with a white,
//!    grey or black border keeps its class), and only where the pixel is saturated (max − min
//!    ≥ 60). Against noise, a pixel is classified by its mean with its left and right
//!    neighbours.
//! 2. *find layers* ([`find_layers`], `layers.rs`): rows whose spans of colour agree form a
//!    segment; touching segments that agree are one band, and thin ones are blurred edges,
//!    noise or an error; a band is split where its colour dips (a faint border line between
//!    two layers drawn alike). Each band is a layer, of any height.
//! 3. *find runs* ([`find_runs`], `runs.rs`): in each layer, columns take their rows' majority
//!    colour, and runs of one colour are found (and split where their colour dips). Each run's
//!    sub-pixel edges come from its colour's area (a blurred or anti-aliased edge keeps it);
//!    where two colours blend into each other, the edge is where they blend half and half,
//!    which is their grid line.
//! 4. *see the border* ([`border_between_layers`], [`border_around_wall`], `borders.rs`): how
//!    wide the border is where it shows apart from the bricks, to choose among grids.
//! 5. *read at one unit* ([`read_at`], `fit.rs`): near a given unit (pixels per 0.30 m), the
//!    border and grid that put every run's edges on whole units (least squares over all
//!    edges), with every run a whole number of its colour's length; touching bricks must show
//!    the border, and so must the seams of a run read as several bricks.
//! 6. *choose the grid* ([`fit_grid`], `grid.rs`): units are proposed by the distances between
//!    edges and read at; the border seen picks among the readings that fit, then the fewest
//!    bricks win, a clearly better fit settles a tie, and what is still tied, or rests on a
//!    thick border where thin borders and more bricks fit as well, is reported as ambiguous.
//! 7. *cut bricks and assemble* ([`cut_bricks`], [`assemble`], `bricks.rs`): a run `k` times
//!    its colour's length is `k` bricks (two touching reds with no border between them are two
//!    reds); bricks get levels (bottom layer = level 1), grid positions, labels and segments (a
//!    column range empty on every layer starts a new segment), and [`Wall::from_bricks`]
//!    checks that nothing floats.
//!
//! Limits, each a clear error: at most [`MAX_PIXELS`] pixels; every brick shows at least
//! [`MIN_COLOUR_PX`] pixels of its colour each way (5 px across when blurred with no border,
//! as tested); the unit is at least [`MIN_UNIT_PX`] pixels; borders are narrower than
//! [`MAX_BORDER_SHARE`] of a unit; more runs than [`MAX_BRICKS`] is refused before the grid is
//! fitted. Touching layers drawn alike with no border line between them read as one layer
//! (nothing in the drawing tells them apart), and paler rows across such a band as a faint
//! border line between two layers. Outlines drawn outside the bricks (not centred on their
//! edges or inside them) put the wall's outer edges off the grid and are not read.
//!
//! Tested by drawing random walls over a grid of proportions (layer height 0.3–3 units,
//! borders 0–4 px, unit 8–40 px, blur, noise, white, grey and black borders, white and pale
//! backgrounds) and reading them back (`tests/png_roundtrip.rs`), by drawings made with
//! ImageMagick (`tests/data/*.png`), by walls drawn and screenshotted by headless Chromium
//! (`tests/png_chromium.rs`), and by malformed images.
//! What each rule buys, measured by taking it out: the README, "Why each rule of the PNG
//! reader is there".

use crate::brick::{Brick, BrickType, Footprint, Origin, BRICK_DEPTH, UNIT_LENGTH};
use crate::decode::{decode_png_rgb, PngDecodeError};
use crate::error::{Location, WallError, WallErrorKind};
use crate::limits::MAX_BRICKS;
use crate::text::label_base;
use crate::wall::Wall;
use image::RgbImage;
use std::collections::BTreeMap;

/// The fewest pixels of colour a brick shows along and across the wall.
pub const MIN_COLOUR_PX: usize = 3;
/// The smallest unit (pixels per 0.30 m) the reader looks for.
pub const MIN_UNIT_PX: f64 = 4.0;
/// Borders are narrower than this share of a unit.
pub const MAX_BORDER_SHARE: f64 = 0.6;
/// The largest image read, in pixels (about 7 000 × 7 000).
pub const MAX_PIXELS: u64 = 50_000_000;
/// How far past a run's last coloured column its blurred edge is summed (px).
const EDGE_REACH: usize = 3;

mod borders;
mod bricks;
mod fit;
mod grid;
mod layers;
mod pixels;
mod runs;

use borders::*;
use bricks::*;
use fit::*;
use grid::*;
use layers::*;
use pixels::*;
use runs::*;

pub use pixels::classify_pixel;

/// Why a step failed: where, and why.
type Failure = (Location, String);

/// Decodes PNG bytes and reads the wall.
///
/// The image's size is checked from its header before it is decoded: more than
/// [`MAX_PIXELS`] is an error. It is decoded straight to 8-bit RGB (16-bit samples cut to 8,
/// grey spread to three channels, alpha dropped), so a 50-megapixel image needs about 4 bytes
/// per pixel at most while decoding.
pub fn read_png(bytes: &[u8], name: &str) -> Result<Wall, WallError> {
    let img = decode_png_rgb(bytes, MAX_PIXELS).map_err(|e| match e {
        PngDecodeError::TooLarge { width, height } => too_many_pixels(name, width, height),
        PngDecodeError::Malformed(reason) => {
            WallError::new(name, Location::Whole, WallErrorKind::ImageDecode { reason })
        }
    })?;
    read_image(&img, name)
}

fn too_many_pixels(name: &str, width: u32, height: u32) -> WallError {
    let reason =
        format!("{width}×{height} is more than the {MAX_PIXELS} pixels a wall image may have");
    WallError::new(name, Location::Whole, WallErrorKind::ImageDecode { reason })
}

/// Reads a wall from a decoded image (see the module documentation for the steps).
pub fn read_image(img: &RgbImage, name: &str) -> Result<Wall, WallError> {
    let fail = |location, reason: String| {
        WallError::new(name, location, WallErrorKind::ImageLayout { reason })
    };
    if img.width() == 0 || img.height() == 0 {
        return Err(WallError::new(
            name,
            Location::Whole,
            WallErrorKind::ImageDecode {
                reason: "the image is empty".into(),
            },
        ));
    }
    if u64::from(img.width()) * u64::from(img.height()) > MAX_PIXELS {
        return Err(too_many_pixels(name, img.width(), img.height()));
    }
    let pixels = classify(img);
    let layers = find_layers(&pixels).map_err(|(at, reason)| fail(at, reason))?;
    if layers.is_empty() {
        return Err(WallError::new(
            name,
            Location::Whole,
            WallErrorKind::NoBricksInImage,
        ));
    }
    let runs = find_runs(&pixels, &layers).map_err(|(at, reason)| fail(at, reason))?;
    if runs.len() > MAX_BRICKS {
        // Each run is at least one brick.
        let kind = WallErrorKind::TooLarge {
            what: "bricks",
            limit: MAX_BRICKS as u64,
            name: "MAX_BRICKS",
        };
        return Err(WallError::new(name, Location::Whole, kind));
    }
    let mut has_runs = vec![false; layers.len()];
    runs.iter().for_each(|r| has_runs[r.layer] = true);
    if let Some(empty) = has_runs.iter().position(|&has| !has) {
        // Every mark of colour in the layer is a sliver between two others (found by fuzzing).
        let top = layers[empty].top;
        let x = (0..pixels.width)
            .find(|&x| pixels.class[top * pixels.width + x].is_some())
            .unwrap_or(0);
        return Err(fail(
            Location::Pixel(x as u32, top as u32),
            format!(
                "the colour here changes every pixel or two: no brick shows {MIN_COLOUR_PX} px \
                 of one colour"
            ),
        ));
    }
    let border_seen = border_between_layers(&pixels, &layers, &runs)
        .or_else(|| border_around_wall(&pixels, &layers, &runs));
    let reading = fit_grid(&runs, border_seen).map_err(|misfit| misfit.into_error(name))?;
    assemble(name, layers.len(), cut_bricks(&runs, &reading))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// PNG bytes of `img` in any of the `image` crate's colour types.
    fn encode(img: &image::DynamicImage) -> Vec<u8> {
        let mut out = std::io::Cursor::new(Vec::new());
        img.write_to(&mut out, image::ImageFormat::Png).unwrap();
        out.into_inner()
    }

    #[test]
    fn every_png_colour_type_decodes_to_the_same_rgb() {
        let rgb = RgbImage::from_fn(7, 5, |x, y| {
            image::Rgb([(40 * x) as u8, (50 * y) as u8, (13 * x * y) as u8])
        });
        let dynamic = image::DynamicImage::ImageRgb8(rgb.clone());
        let close = |a: &RgbImage, b: &RgbImage| {
            a.dimensions() == b.dimensions()
                && a.as_raw()
                    .iter()
                    .zip(b.as_raw())
                    .all(|(x, y)| x.abs_diff(*y) <= 1)
        };
        for img in [
            dynamic.clone(),
            image::DynamicImage::ImageRgba8(dynamic.to_rgba8()),
            image::DynamicImage::ImageRgb16(dynamic.to_rgb16()),
            image::DynamicImage::ImageRgba16(dynamic.to_rgba16()),
            image::DynamicImage::ImageLuma8(dynamic.to_luma8()),
            image::DynamicImage::ImageLumaA8(dynamic.to_luma_alpha8()),
            image::DynamicImage::ImageLuma16(dynamic.to_luma16()),
        ] {
            let decoded = decode_png_rgb(&encode(&img), MAX_PIXELS).unwrap();
            assert!(close(&decoded, &img.to_rgb8()), "{:?}", img.color());
        }
        // A palette image, as paint programs save small drawings.
        let mut bytes = Vec::new();
        {
            let mut encoder = png::Encoder::new(&mut bytes, 3, 1);
            encoder.set_color(png::ColorType::Indexed);
            encoder.set_palette(vec![255, 0, 0, 0, 255, 0, 0, 0, 255]);
            let mut writer = encoder.write_header().unwrap();
            writer.write_image_data(&[2, 1, 0]).unwrap();
        }
        let decoded = decode_png_rgb(&bytes, MAX_PIXELS).unwrap();
        assert_eq!(decoded.as_raw(), &vec![0, 0, 255, 0, 255, 0, 255, 0, 0]);
        assert!(decode_png_rgb(b"not a png", MAX_PIXELS).is_err());
        let big = encode(&image::DynamicImage::ImageRgb8(RgbImage::new(20, 10)));
        assert_eq!(
            decode_png_rgb(&big, 199),
            Err(PngDecodeError::TooLarge {
                width: 20,
                height: 10
            })
        );
    }

    fn ambiguous(fit: Result<Reading, Misfit>) -> bool {
        matches!(fit, Err(Misfit { kind: WallErrorKind::ImageLayout { reason }, .. }) if reason.contains("ambiguous"))
    }

    /// A run drawn as a flat block of colour from `left` to `right`.
    fn run(layer: usize, kind: BrickType, left: f64, right: f64) -> Run {
        let first_column = left.floor() as usize;
        Run {
            layer,
            kind,
            left,
            right,
            pixel: (left as u32, 0),
            blended: (false, false),
            first_column,
            coverage: (first_column..right.ceil() as usize)
                .map(|x| {
                    let x = x as f64;
                    ((x + 1.0).min(right) - x.max(left)) as f32
                })
                .collect(),
        }
    }

    #[test]
    fn two_pieces_of_one_colour_do_not_blend() {
        // A red run split at a faint grey border: the border column lies near the line
        // between the two pieces' colours (they differ by a grey level), but two pieces of
        // one colour never blend: their edges are measured by their colour's area, and the
        // border between them is checked.
        let (red, also_red) = ([230.0, 30.0, 30.0], [231.0, 30.0, 30.0]);
        let means = [red, red, red, [215.0, 45.0, 45.0], red, red, red];
        let piece = |start, end| Span {
            kind: BrickType::Red,
            start,
            end,
        };
        let junction = colour_junction(&means, &[piece(0, 3), piece(4, 7)], &[red, also_red]);
        assert_eq!(junction, None);
    }

    #[test]
    fn blended_pixels_keep_their_colour() {
        let red = [235u8, 20, 20];
        let with = |other: u8, share: f32| {
            red.map(|c| (share * f32::from(c) + (1.0 - share) * f32::from(other)) as u8)
        };
        for other in [0, 128, 255] {
            let p = with(other, 0.5);
            assert_eq!(
                classify_pixel(p).map(|c| c.0),
                Some(BrickType::Red),
                "{p:?}"
            );
        }
        // Greys, white, black and pale paper are nothing.
        for p in [[255, 255, 255], [0, 0, 0], [128, 128, 128], [245, 235, 215]] {
            assert_eq!(classify_pixel(p), None, "{p:?}");
        }
        assert_eq!(
            classify_pixel([255, 165, 0]).map(|c| c.0),
            Some(BrickType::Orange)
        );
    }

    #[test]
    fn rows_differ_only_by_a_run_of_colour_not_by_a_flickering_edge() {
        let r = |start, end| Span {
            kind: BrickType::Red,
            start,
            end,
        };
        let g = |start, end| Span {
            kind: BrickType::Green,
            start,
            end,
        };
        // Edges moved by two pixels, or two runs joined across a thin border: the same row.
        assert!(!rows_differ(&[r(0, 10), r(12, 22)], &[r(0, 22)]));
        assert!(!rows_differ(&[r(2, 10)], &[r(0, 11)]));
        // A red that became green, or a brick that appeared: a new layer.
        assert!(rows_differ(&[r(0, 10)], &[g(0, 10)]));
        assert!(rows_differ(&[r(0, 10)], &[r(0, 10), r(20, 23)]));
    }

    #[test]
    fn the_grid_comes_from_the_lengths_not_the_layer_height() {
        // R G B at 10 px per unit with a 2 px border: colour widths 8, 18, 38.
        let runs = [
            run(0, BrickType::Red, 1.0, 9.0),
            run(0, BrickType::Green, 11.0, 29.0),
            run(0, BrickType::Blue, 31.0, 69.0),
        ];
        let reading = fit_grid(&runs, None).unwrap();
        assert!((reading.unit - 10.0).abs() < 1e-6, "{reading:?}");
        assert!((reading.border - 2.0).abs() < 1e-6, "{reading:?}");
        assert_eq!(reading.places, vec![(0, 1), (1, 2), (3, 4)]);
    }

    #[test]
    fn a_run_twice_its_colours_length_is_two_bricks() {
        // R R drawn touching with no border, and a lone red two units on: 20 px, then 10 px.
        let runs = [
            run(0, BrickType::Red, 0.0, 20.0),
            run(0, BrickType::Red, 40.0, 50.0),
        ];
        // A thick-bordered reading (one red at 35 px per unit with a 15 px border) would need
        // the two runs to be as long as each other; it does not fit.
        let reading = fit_grid(&runs, None).unwrap();
        assert_eq!(reading.places, vec![(0, 2), (4, 1)]);
        assert!(reading.border.abs() < 1e-9, "{}", reading.border);
        let found = cut_bricks(&runs, &reading);
        assert_eq!(
            found.iter().map(|f| f.first_unit).collect::<Vec<_>>(),
            vec![0, 1, 4]
        );
    }

    #[test]
    fn equal_lone_bricks_need_the_border_seen_between_layers() {
        // Two reds 5 units apart with an invisible 3 px border at 10 px per unit: 4 or 5
        // units apart at other units and borders fit as well.
        let runs = [
            run(0, BrickType::Red, 1.5, 8.5),
            run(0, BrickType::Red, 51.5, 58.5),
        ];
        assert!(ambiguous(fit_grid(&runs, None)));
        let reading = fit_grid(&runs, Some(3.0)).unwrap();
        assert_eq!(reading.places, vec![(0, 1), (5, 1)]);
    }

    #[test]
    fn a_brick_of_the_wrong_length_is_named() {
        // A red as long as a green beside a green, a blue and a red.
        let runs = [
            run(0, BrickType::Red, 1.0, 9.0),
            run(0, BrickType::Green, 11.0, 29.0),
            run(0, BrickType::Blue, 31.0, 69.0),
            run(0, BrickType::Red, 71.0, 84.0),
        ];
        let misfit = fit_grid(&runs, None).unwrap_err();
        assert_eq!(misfit.pixel, (71, 0), "{misfit:?}");
    }

    #[test]
    fn distant_bricks_stay_on_the_grid() {
        // Reds every other unit at 9.7 px per unit, 200 of them, with a 1 px border.
        let runs: Vec<Run> = (0..200)
            .map(|i| {
                let x = 2.0 * 9.7 * f64::from(i);
                run(0, BrickType::Red, x + 0.5, x + 9.2)
            })
            .collect();
        let reading = fit_grid(&runs, Some(1.0)).unwrap();
        let expected: Vec<(i64, u32)> = (0..200).map(|i| (2 * i, 1)).collect();
        assert_eq!(reading.places, expected);
    }
}
