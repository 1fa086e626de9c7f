//! A colour that cannot be told, judged by what surrounds it.
//!
//! Shading moves a colour: a robot's darker cap, a ring goal's dark middle, the shaded side
//! of a magenta shelf under warm light may read as a colour between the robots' (or goals')
//! and another. Such a blob (8-connected unsure pixels) inside a robot, a goal or an obstacle
//! is part of it: when at least [`SURROUNDED`] of the pixels around it (its 8-neighbours, the
//! floor too) are of one kind of robot, goal or obstacle, and at most [`OTHERS`] of those not
//! floor are of another kind, its pixels become that kind. A blob beside two kinds, or mostly
//! beside the floor, stays a colour that cannot be told (and is refused when it is as large
//! as a mark). It runs after [`super::shelves`] has judged the shelves by their shape, on
//! the colours as read: a tan shelf reads as a colour between with its reddest pixels as
//! robot, and settled first it became robot pixels, joined a robot standing beside it, and
//! took the robot with it into the obstacle (until issue #29's eleventh round).
//! Cost: O(unsure pixels).

use super::blobs;
use super::colour::Class;
use super::pixels::OUTSIDE;

/// The least share of the pixels around an unsure blob that must be of one kind.
pub const SURROUNDED: f64 = 0.5;
/// The largest share of the pixels around it, floor aside, of another kind.
pub const OTHERS: f64 = 0.05;

/// Gives each unsure blob surrounded by one kind that kind; returns how many it settled.
pub fn settle(classes: &mut [u8], width: usize) -> usize {
    let height = classes.len() / width.max(1);
    let unsure = Class::Unsure as u8;
    let mut settled = 0;
    for blob in blobs::find(classes, width, unsure) {
        // Pixels around the blob by class: robot, goal, obstacle, anything else.
        let mut around = [0usize; 4];
        for &(x, y) in &blob.pixels {
            let (x, y) = (x as usize, y as usize);
            for ny in y.saturating_sub(1)..=(y + 1).min(height - 1) {
                for nx in x.saturating_sub(1)..=(x + 1).min(width - 1) {
                    let c = classes[ny * width + nx];
                    // Neither the floor's edge nor a painted line says what the blob is
                    // (see `lined`).
                    if c == unsure || c == OUTSIDE {
                        continue;
                    }
                    let k = match c {
                        c if c == Class::Robot as u8 => 0,
                        c if c == Class::Goal as u8 => 1,
                        c if c == Class::Obstacle as u8 => 2,
                        _ => 3,
                    };
                    around[k] += 1;
                }
            }
        }
        let total: usize = around.iter().sum();
        let marked = around[0] + around[1] + around[2];
        let Some(kind) = (0..3).max_by_key(|&k| (around[k], std::cmp::Reverse(k))) else {
            continue;
        };
        let one = around[kind] as f64 >= SURROUNDED * total as f64;
        let alone = (marked - around[kind]) as f64 <= OTHERS * marked as f64;
        if total == 0 || !one || !alone {
            continue;
        }
        let class = [Class::Robot, Class::Goal, Class::Obstacle][kind] as u8;
        blob.paint(classes, width, class);
        settled += 1;
    }
    settled
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::aerial::tests::paint;

    #[test]
    fn a_robot_s_dark_cap_is_the_robot() {
        let mut classes = vec![Class::Floor as u8; 20 * 20];
        paint(&mut classes, 20, (2, 2, 10, 10), Class::Robot);
        paint(&mut classes, 20, (4, 4, 8, 8), Class::Unsure);
        assert_eq!(settle(&mut classes, 20), 1);
        assert!(classes.iter().all(|&c| c != Class::Unsure as u8));
    }

    #[test]
    fn an_unsure_blob_on_the_floor_or_between_two_kinds_stays() {
        let mut classes = vec![Class::Floor as u8; 20 * 20];
        // On the floor, touching an obstacle on one side only.
        paint(&mut classes, 20, (0, 0, 4, 20), Class::Obstacle);
        paint(&mut classes, 20, (4, 2, 9, 7), Class::Unsure);
        // Between a robot and an obstacle.
        paint(&mut classes, 20, (12, 10, 15, 20), Class::Robot);
        paint(&mut classes, 20, (15, 10, 17, 20), Class::Unsure);
        paint(&mut classes, 20, (17, 10, 20, 20), Class::Obstacle);
        let before = classes.clone();
        assert_eq!(settle(&mut classes, 20), 0);
        assert_eq!(classes, before);
    }
}
