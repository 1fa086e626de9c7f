//! The wall as ROS 2 shows it: one `CUBE` marker per brick of the design, at its place
//! ([`brick_box`]) and size, coloured by its status ([`BrickStatus`]), in the frame
//! [`FRAME`]. One description for the bag and for the live bridge: the bridge asks an agent
//! for [`wall_scene_json`] and colours the bricks by the statuses it hears.

use super::messages::Cube;
use crate::mcap::brick_box;
use mason_mission::Arena;
use mason_wall::{brick_rgb, Wall};
use serde_json::{json, Value};

/// The frame every pose and marker is in: the arena's (x east, y north, z up; m), as
/// [`Arena`] lays it out.
pub const FRAME: &str = "arena";

/// The marker namespace of the wall's bricks.
pub const BRICK_NS: &str = "bricks";

/// Version of [`wall_scene_json`]'s layout.
pub const SCENE_VERSION: u32 = 1;

/// Where a brick is in the mission.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BrickStatus {
    /// On the pile, or nobody holds it: grey, translucent.
    Pending,
    /// A UAV has it (claimed or in its gripper): its colour, translucent.
    Claimed,
    /// On the wall: its colour, opaque.
    Placed,
}

/// Opacity of a claimed brick.
const CLAIMED_ALPHA: f32 = 0.4;
/// A pending brick's colour.
const PENDING_RGBA: [f32; 4] = [0.6, 0.6, 0.6, 0.25];

/// Brick `index`'s colour when it has `status`.
fn brick_rgba(wall: &Wall, index: usize, status: BrickStatus) -> [f32; 4] {
    let [r, g, b] = brick_rgb(wall.bricks()[index].kind).map(|v| f32::from(v) / 255.0);
    match status {
        BrickStatus::Pending => PENDING_RGBA,
        BrickStatus::Claimed => [r, g, b, CLAIMED_ALPHA],
        BrickStatus::Placed => [r, g, b, 1.0],
    }
}

/// The wall's markers, one per brick (id: its label), coloured by `status` (by brick index).
pub fn wall_cubes(arena: &Arena, wall: &Wall, status: &[BrickStatus]) -> Vec<Cube> {
    wall.ids()
        .zip(status)
        .map(|(b, &s)| {
            let (centre, size) = brick_box(arena, wall, b);
            Cube {
                id: i32::try_from(wall.brick(b).label).unwrap_or(i32::MAX),
                centre,
                size,
                rgba: brick_rgba(wall, b.index(), s),
            }
        })
        .collect()
}

/// The wall as JSON, for a client that draws it from the team's statuses (the ROS 2 bridge):
/// `{"v":1,"wall":NAME,"frame":"arena","ns":"bricks","bricks":[{"brick":INDEX,"label":L,
/// "type":"red","centre":[x,y,z],"size":[x,y,z],"pending":[r,g,b,a],"claimed":[…],
/// "placed":[…]},…]}`, bricks in wall-index order (the `brick` of the agents' messages).
pub fn wall_scene_json(arena: &Arena, wall: &Wall) -> Value {
    let bricks: Vec<Value> = wall
        .ids()
        .map(|b| {
            let (centre, size) = brick_box(arena, wall, b);
            let brick = wall.brick(b);
            let rgba = |s| brick_rgba(wall, b.index(), s);
            json!({
                "brick": b.index(), "label": brick.label, "type": brick.kind.to_string(),
                "centre": centre, "size": size,
                "pending": rgba(BrickStatus::Pending), "claimed": rgba(BrickStatus::Claimed),
                "placed": rgba(BrickStatus::Placed),
            })
        })
        .collect();
    json!({
        "v": SCENE_VERSION, "wall": wall.name(), "frame": FRAME, "ns": BRICK_NS,
        "bricks": bricks,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_scene_json_and_the_bag_markers_agree() {
        let wall = mason_wall::parse_layer_text("R G\nB O", "two").unwrap();
        let arena = Arena::default();
        let status = [
            BrickStatus::Placed,
            BrickStatus::Claimed,
            BrickStatus::Pending,
            BrickStatus::Placed,
        ];
        let cubes = wall_cubes(&arena, &wall, &status);
        let scene = wall_scene_json(&arena, &wall);
        let bricks = scene["bricks"].as_array().unwrap();
        assert_eq!(bricks.len(), wall.len());
        for ((cube, b), s) in cubes.iter().zip(bricks).zip(status) {
            assert_eq!(i64::from(cube.id), b["label"].as_i64().unwrap());
            let key = match s {
                BrickStatus::Pending => "pending",
                BrickStatus::Claimed => "claimed",
                BrickStatus::Placed => "placed",
            };
            let rgba: Vec<f32> = b[key]
                .as_array()
                .unwrap()
                .iter()
                .map(|v| v.as_f64().unwrap() as f32)
                .collect();
            assert_eq!(rgba, cube.rgba);
            assert_eq!(b["centre"][2].as_f64().unwrap(), cube.centre[2]);
        }
        assert_eq!(cubes[0].rgba[3], 1.0);
        assert_eq!(cubes[1].rgba[3], CLAIMED_ALPHA);
        assert_eq!(cubes[2].rgba, PENDING_RGBA);
    }
}
