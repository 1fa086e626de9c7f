//! Grids from images: occupancy PNGs (dark pixels are obstacles) and the UAV's bird's-eye PNG,
//! which also marks robots in red and goals in green. One pixel is one grid cell.
//!
//! Colour rules (as the wall reader's): red when r > 2g and r > 1.5b, green when g > 1.5r and
//! g > 1.5b; a pixel is dark when its luma (0.299r + 0.587g + 0.114b) is below 100. A robot or
//! goal is a 4-connected blob of its colour; it stands on the blob's pixel nearest the blob's
//! centroid (ties to the first in row order).

use crate::error::{CrewError, Location};
use crate::grid::{Cell, Grid};
use image::RgbImage;

/// What a bird's-eye image shows.
#[derive(Clone, Debug, PartialEq)]
pub struct BirdsEye {
    /// The world.
    pub grid: Grid,
    /// Robot cells, in row-major order of their blobs' first pixels.
    pub robots: Vec<Cell>,
    /// Goal cells, in the same order.
    pub goals: Vec<Cell>,
}

/// Decodes with the wall reader's PNG decoder (straight to 8-bit RGB, the size checked from
/// the header first, damaged palettes refused).
fn decode(bytes: &[u8], source_name: &str) -> Result<RgbImage, CrewError> {
    let fail = |reason: String| CrewError::new(source_name, Location::Whole, reason);
    let rgb = mason_wall::decode_png_rgb(bytes, crate::limits::MAX_CELLS).map_err(|e| match e {
        mason_wall::PngDecodeError::TooLarge { width, height } => fail(format!(
            "{width}×{height} is more than the {} cells a map may have (mason_crew::limits::MAX_CELLS)",
            crate::limits::MAX_CELLS
        )),
        mason_wall::PngDecodeError::Malformed(reason) => {
            fail(format!("cannot decode the image: {reason}"))
        }
    })?;
    if rgb.width() == 0 || rgb.height() == 0 {
        return Err(fail("the image is empty".into()));
    }
    Ok(rgb)
}

fn is_dark(p: [u8; 3]) -> bool {
    let [r, g, b] = p.map(f64::from);
    0.299 * r + 0.587 * g + 0.114 * b < 100.0
}

fn is_red(p: [u8; 3]) -> bool {
    let [r, g, b] = p.map(u32::from);
    2 * r > 4 * g && 2 * r > 3 * b && r >= 64
}

fn is_green(p: [u8; 3]) -> bool {
    let [r, g, b] = p.map(u32::from);
    2 * g > 3 * r && 2 * g > 3 * b && g >= 64
}

/// Reads an occupancy image: dark pixels are obstacles, everything else is free.
pub fn read_occupancy(bytes: &[u8], source_name: &str) -> Result<Grid, CrewError> {
    let img = decode(bytes, source_name)?;
    let blocked = img
        .pixels()
        .map(|p| is_dark(p.0) && !is_red(p.0) && !is_green(p.0))
        .collect();
    Ok(Grid::new(img.width(), img.height(), blocked))
}

/// Reads a bird's-eye image: obstacles, robots (red) and goals (green).
pub fn read_birdseye(bytes: &[u8], source_name: &str) -> Result<BirdsEye, CrewError> {
    let img = decode(bytes, source_name)?;
    let grid = read_occupancy(bytes, source_name)?;
    let robots = blobs(&img, &grid, is_red);
    let goals = blobs(&img, &grid, is_green);
    if robots.is_empty() {
        return Err(CrewError::new(
            source_name,
            Location::Whole,
            "no robots in the image (robots are red: r > 2g and r > 1.5b)",
        ));
    }
    if robots.len() > crate::limits::MAX_AGENTS {
        return Err(CrewError::new(
            source_name,
            Location::Whole,
            format!(
                "{} robots (red blobs), more than the {} an instance may have (mason_crew::limits::MAX_AGENTS)",
                robots.len(),
                crate::limits::MAX_AGENTS
            ),
        ));
    }
    if robots.len() > goals.len() {
        return Err(CrewError::new(
            source_name,
            Location::Whole,
            format!(
                "{} robots (red) but only {} goals (green); every robot needs a goal",
                robots.len(),
                goals.len()
            ),
        ));
    }
    Ok(BirdsEye {
        grid,
        robots,
        goals,
    })
}

fn blobs(img: &RgbImage, grid: &Grid, colour: fn([u8; 3]) -> bool) -> Vec<Cell> {
    let (w, h) = (img.width() as i64, img.height() as i64);
    let mut seen = vec![false; grid.len()];
    let mut out = Vec::new();
    for start in 0..grid.len() {
        let (sx, sy) = (start as i64 % w, start as i64 / w);
        if seen[start] || !colour(img.get_pixel(sx as u32, sy as u32).0) {
            continue;
        }
        let mut members = Vec::new();
        let mut stack = vec![start];
        seen[start] = true;
        while let Some(i) = stack.pop() {
            members.push(i);
            let (x, y) = (i as i64 % w, i as i64 / w);
            for (nx, ny) in [(x + 1, y), (x - 1, y), (x, y + 1), (x, y - 1)] {
                if nx < 0 || ny < 0 || nx >= w || ny >= h {
                    continue;
                }
                let j = (ny * w + nx) as usize;
                if !seen[j] && colour(img.get_pixel(nx as u32, ny as u32).0) {
                    seen[j] = true;
                    stack.push(j);
                }
            }
        }
        members.sort_unstable();
        let n = members.len() as f64;
        let cx = members.iter().map(|&i| (i as i64 % w) as f64).sum::<f64>() / n;
        let cy = members.iter().map(|&i| (i as i64 / w) as f64).sum::<f64>() / n;
        let best = members
            .iter()
            .copied()
            .min_by(|&a, &b| {
                let d = |i: usize| {
                    let (x, y) = ((i as i64 % w) as f64, (i as i64 / w) as f64);
                    (x - cx).powi(2) + (y - cy).powi(2)
                };
                d(a).total_cmp(&d(b)).then(a.cmp(&b))
            })
            .expect("a blob has a pixel");
        out.push(Cell(best as u32));
    }
    out
}

/// A bird's-eye PNG that [`read_birdseye`] reads back: one pixel per cell, obstacles black,
/// free cells white, robots pure red and goals pure green.
pub fn birdseye_png(grid: &Grid, robots: &[Cell], goals: &[Cell]) -> Vec<u8> {
    let mut img = RgbImage::from_fn(grid.width(), grid.height(), |x, y| {
        let free = grid
            .cell(i64::from(x), i64::from(y))
            .is_some_and(|c| grid.is_free(c));
        image::Rgb(if free { [255, 255, 255] } else { [0, 0, 0] })
    });
    for (cells, colour) in [(robots, [230, 0, 0]), (goals, [0, 200, 0])] {
        for &c in cells {
            let (x, y) = grid.xy(c);
            img.put_pixel(x, y, image::Rgb(colour));
        }
    }
    let mut bytes = Vec::new();
    // Encoding an in-memory RGB image into a Vec cannot fail.
    let _ = img.write_to(
        &mut std::io::Cursor::new(&mut bytes),
        image::ImageFormat::Png,
    );
    bytes
}

#[cfg(test)]
mod tests {
    use super::*;
    use image::{ImageFormat, Rgb};
    use std::io::Cursor;

    fn png(img: &RgbImage) -> Vec<u8> {
        let mut out = Cursor::new(Vec::new());
        img.write_to(&mut out, ImageFormat::Png).unwrap();
        out.into_inner()
    }

    fn scene() -> RgbImage {
        let mut img = RgbImage::from_pixel(10, 6, Rgb([240, 240, 240]));
        for y in 0..4 {
            img.put_pixel(5, y, Rgb([20, 20, 20]));
        }
        // A 2×2 robot and a 1-pixel robot; two goals.
        for (x, y) in [(1, 1), (2, 1), (1, 2), (2, 2), (0, 5)] {
            img.put_pixel(x, y, Rgb([230, 30, 30]));
        }
        for (x, y) in [(8, 1), (8, 4)] {
            img.put_pixel(x, y, Rgb([30, 200, 40]));
        }
        img
    }

    #[test]
    fn reads_robots_goals_and_obstacles() {
        let b = read_birdseye(&png(&scene()), "i").unwrap();
        assert_eq!(b.robots.len(), 2);
        assert_eq!(b.goals.len(), 2);
        assert_eq!(b.grid.xy(b.robots[0]), (1, 1));
        assert_eq!(b.grid.xy(b.robots[1]), (0, 5));
        assert_eq!(b.grid.free_count(), 60 - 4);
    }

    #[test]
    fn malformed_images_give_clear_errors() {
        let mut no_robots = scene();
        for p in no_robots.pixels_mut() {
            if is_red(p.0) {
                *p = Rgb([240, 240, 240]);
            }
        }
        let e = read_birdseye(&png(&no_robots), "i")
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("i: no robots"), "{e}");
        let mut too_many = scene();
        too_many.put_pixel(9, 5, Rgb([230, 30, 30]));
        let e = read_birdseye(&png(&too_many), "i").unwrap_err().to_string();
        assert!(e.contains("3 robots (red) but only 2 goals"), "{e}");
        let e = read_birdseye(b"not a png", "i").unwrap_err().to_string();
        assert!(e.starts_with("i: cannot decode the image"), "{e}");
    }
}
