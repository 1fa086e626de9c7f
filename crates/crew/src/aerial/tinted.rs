//! Marks on a floor that is not grey.
//!
//! White balance makes the floor's median colour grey. When the floor itself has a colour
//! (beige, bluish), that turns the hues of pale marks: a pale green goal on a beige floor
//! becomes cyan, a colour of no mark, so its pixels read as an obstacle's. Its shape and its
//! colour before white balance tell what it is: it fills no cell, and most of its pixels are
//! a mark's colour before white balance ([`Classifier::raw_mark`]).
//!
//! The same holds for a mark whose balanced colour falls just outside its hue band (a
//! colour that cannot be told): a pale green goal on a brown floor.
//!
//! So every 8-connected blob of obstacle (or of unsure) pixels of which at least [`MOSTLY`] are one mark's
//! colour before white balance, and which fills no cell (fewer than
//! [`shelves::FILLED`](super::shelves::FILLED) of the pixels of any cell's middle), becomes
//! that mark's blob. An obstacle fills its cells; a shelf of a colour near a mark's before
//! white balance (dark green) stays an obstacle. Cost: one pass over the obstacle pixels' colours
//! (on all cores), then only the blobs holding a pixel of a mark's colour are walked.

use super::blobs;
use super::colour::{Class, Classifier};
use super::homography::Homography;
use super::shelves::{inner_cell, middle, FILLED};
use image::RgbImage;
use rayon::prelude::*;

/// The least share of a blob's pixels of one mark's colour before white balance.
pub const MOSTLY: f64 = 0.5;

/// Turns obstacle blobs that are marks by their colour before white balance into marks;
/// returns how many it turned.
pub fn recover(
    classes: &mut [u8],
    img: &RgbImage,
    classifier: &Classifier,
    (floor_to_image, image_to_floor): (&Homography, &Homography),
    floor: (u32, u32),
) -> usize {
    let width = img.width() as usize;
    let raw = img.as_raw();
    let colour = |x: u32, y: u32| {
        let i = (y as usize * width + x as usize) * 3;
        [raw[i], raw[i + 1], raw[i + 2]]
    };
    // The pixels of the cells' middles (only their count, which turning blobs into marks
    // does not change).
    let mut known = std::collections::BTreeMap::new();
    let maps = (floor_to_image, image_to_floor);
    let mut turned = 0;
    // Only a blob with a pixel of a mark's colour before white balance can turn: the blobs
    // grown from those pixels (found on all cores), not every shelf.
    let seeds = |class: Class| -> Vec<usize> {
        classes
            .par_chunks(width.max(1))
            .enumerate()
            .flat_map_iter(|(y, row)| {
                row.iter().enumerate().filter_map(move |(x, &c)| {
                    (c == class as u8 && classifier.raw_mark(colour(x as u32, y as u32)).is_some())
                        .then_some(y * width + x)
                })
            })
            .collect()
    };
    let seeded = [Class::Obstacle, Class::Unsure].map(|c| (c, seeds(c)));
    let found: Vec<blobs::Blob> = seeded
        .iter()
        .flat_map(|(c, seeds)| blobs::find_from(classes, width, *c as u8, seeds))
        .collect();
    for blob in found {
        let (mut robot, mut goal) = (0usize, 0usize);
        let least = MOSTLY * blob.area() as f64;
        for (k, &(x, y)) in blob.pixels.iter().enumerate() {
            // Past the point where even every pixel left being a mark's would not make it
            // mostly one, the counts cannot turn the blob: stop.
            let left = blob.pixels.len() - k;
            if k % 64 == 0 && ((robot.max(goal) + left) as f64) < least {
                break;
            }
            match classifier.raw_mark(colour(x, y)) {
                Some(Class::Robot) => robot += 1,
                Some(Class::Goal) => goal += 1,
                _ => {}
            }
        }
        let (mark, n) = if goal >= robot {
            (Class::Goal, goal)
        } else {
            (Class::Robot, robot)
        };
        if (n as f64) < MOSTLY * blob.area() as f64 {
            continue;
        }
        let mut held = std::collections::BTreeMap::<usize, u32>::new();
        for &(x, y) in &blob.pixels {
            let i = y as usize * width + x as usize;
            if let Some(cell) = inner_cell(i, width, image_to_floor, floor) {
                *held.entry(cell).or_insert(0) += 1;
            }
        }
        let fills = held.iter().any(|(&c, &n)| {
            let m = middle(&mut known, classes, width, maps, floor, c);
            m.pixels > 0 && f64::from(n) >= FILLED * f64::from(m.pixels)
        });
        if fills {
            continue;
        }
        blob.paint(classes, width, mark as u8);
        turned += 1;
    }
    turned
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::aerial::colour::Hue;
    use crate::aerial::pixels;
    use crate::aerial::tests::paint;

    #[test]
    fn an_unsure_blob_of_a_goals_colour_before_white_balance_is_a_goal_unless_it_fills_a_cell() {
        // A grey floor, 10 px per cell; a green goal read as unsure in cell (3, 1), and an
        // unsure green square filling cell (0, 0).
        let grey = [150u8, 150, 150];
        let green = [60u8, 170, 80];
        let mut img = RgbImage::from_pixel(40, 20, image::Rgb(grey));
        let mut classes = vec![Class::Floor as u8; 40 * 20];
        for (x0, y0, x1, y1) in [(33, 13, 37, 17), (0, 0, 10, 10)] {
            for y in y0..y1 {
                for x in x0..x1 {
                    img.put_pixel(x as u32, y as u32, image::Rgb(green));
                }
            }
            paint(&mut classes, 40, (x0, y0, x1, y1), Class::Unsure);
        }
        let to_image = Homography::floor_to_image(
            4.0,
            2.0,
            [(0.0, 0.0), (40.0, 0.0), (40.0, 20.0), (0.0, 20.0)],
        )
        .unwrap();
        let to_floor = to_image.inverse().unwrap();
        let classifier = Classifier::new(grey.map(f64::from), Hue::RED, Hue::GREEN);
        assert_eq!(classifier.raw_mark(green), Some(Class::Goal));
        let maps = (&to_image, &to_floor);
        assert_eq!(recover(&mut classes, &img, &classifier, maps, (4, 2)), 1);
        assert_eq!(classes[15 * 40 + 35], Class::Goal as u8);
        assert_eq!(classes[5 * 40 + 5], Class::Unsure as u8);
    }

    #[test]
    fn a_pale_green_goal_on_a_beige_floor_is_a_goal_and_a_teal_shelf_an_obstacle() {
        // A 4 × 2-cell beige floor, 10 px per cell: a pale green goal in cell (3, 1), and a
        // shelf of the same colour over cells (0, 0) and (1, 0).
        let beige = [200u8, 180, 140];
        let pale_green = [100u8, 150, 110];
        let mut img = RgbImage::from_pixel(40, 20, image::Rgb(beige));
        for y in 13..17 {
            for x in 33..37 {
                img.put_pixel(x, y, image::Rgb(pale_green));
            }
        }
        for y in 1..9 {
            for x in 1..19 {
                img.put_pixel(x, y, image::Rgb(pale_green));
            }
        }
        let to_image = Homography::floor_to_image(
            4.0,
            2.0,
            [(0.0, 0.0), (40.0, 0.0), (40.0, 20.0), (0.0, 20.0)],
        )
        .unwrap();
        let to_floor = to_image.inverse().unwrap();
        let classifier = Classifier::new(beige.map(f64::from), Hue::RED, Hue::GREEN);
        // After white balance the pale green is cyan: an obstacle's colour.
        assert_eq!(classifier.classify(pale_green), Class::Obstacle);
        let mut classes = pixels::classify(&img, &classifier, &to_floor, (4, 2), 0);
        assert_eq!(
            recover(
                &mut classes,
                &img,
                &classifier,
                (&to_image, &to_floor),
                (4, 2)
            ),
            1
        );
        assert_eq!(classes[15 * 40 + 35], Class::Goal as u8);
        assert_eq!(classes[5 * 40 + 10], Class::Obstacle as u8);
    }
}
