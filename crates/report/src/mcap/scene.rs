//! The wall as a 3-D scene, the body of each `/wall` message (`foxglove.SceneUpdate`): the wall
//! zone as a translucent box, the piles, every brick of the design as a faint cube and every
//! brick placed so far as a solid one.
//!
//! A brick's place on the wall is [`brick_box`].
//!
//! Each scene is whole (no deletions, no lifetimes), so a viewer that shows only the latest
//! message still shows the right wall.

use super::values::{colour, pose_json, stamp, vec3};
use mason_mission::{Arena, Point};
use mason_wall::{brick_rgb, BrickId, BrickType, Wall, BRICK_HEIGHT};
use serde_json::{json, Value};

/// Height of the drawn wall-zone box (m).
const ZONE_HEIGHT: f64 = 4.0;

/// A brick on the wall: when and by whom it was placed.
#[derive(Clone, Copy, Debug)]
pub(super) struct Placement {
    /// Mission time (s).
    pub(super) at: f64,
    /// The UAV that placed it.
    pub(super) uav: u32,
}

/// The centre and size (m) of a brick on the wall, in the frame `world` (x east, y north, z
/// up). The wall runs along x with its middle at [`Arena::wall`]: a brick's centre is
/// `wall.x + (x0 + x1)/2 − m_x`, `wall.y + (y0 + y1)/2 − m_y`, `(level − ½) · BRICK_HEIGHT`,
/// where `m` is the middle of the box around every brick's footprint; its size is its footprint
/// by [`BRICK_HEIGHT`].
pub fn brick_box(arena: &Arena, wall: &Wall, brick: BrickId) -> ([f64; 3], [f64; 3]) {
    let (mut x_lo, mut x_hi, mut y_lo, mut y_hi) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    for b in wall.bricks() {
        x_lo = x_lo.min(b.footprint.x0);
        x_hi = x_hi.max(b.footprint.x1);
        y_lo = y_lo.min(b.footprint.y0);
        y_hi = y_hi.max(b.footprint.y1);
    }
    let (mx, my) = ((x_lo + x_hi) / 2.0, (y_lo + y_hi) / 2.0);
    let b = wall.brick(brick);
    let f = b.footprint;
    let centre = [
        arena.wall.x + (f.x0 + f.x1) / 2.0 - mx,
        arena.wall.y + (f.y0 + f.y1) / 2.0 - my,
        (f64::from(b.level) - 0.5) * BRICK_HEIGHT,
    ];
    (centre, [f.x1 - f.x0, f.y1 - f.y0, BRICK_HEIGHT])
}

/// The whole scene at mission time `t`: `placed` holds, by brick index, each brick placed so
/// far.
pub(super) fn wall_scene(
    t: f64,
    arena: &Arena,
    wall: &Wall,
    placed: &[Option<Placement>],
) -> Value {
    let mut entities = Vec::with_capacity(3 + placed.iter().flatten().count());
    entities.push(zone(t, arena));
    entities.push(piles(t, arena));
    entities.push(design(t, arena, wall));
    for b in wall.ids() {
        if let Some(p) = placed[b.index()] {
            entities.push(placed_brick(arena, wall, b, p));
        }
    }
    json!({"deletions": [], "entities": entities})
}

/// The wall zone: a translucent box over the wall and its name.
fn zone(t: f64, arena: &Arena) -> Value {
    let zone_centre = [arena.wall.x, arena.wall.y, ZONE_HEIGHT / 2.0];
    entity(
        t,
        "zone",
        &[(
            "what",
            "wall zone: at most one UAV (or an orange pair)".into(),
        )],
        vec![cube(
            zone_centre,
            [
                2.0 * arena.zone_half.x,
                2.0 * arena.zone_half.y,
                ZONE_HEIGHT,
            ],
            json!({"r": 0.26, "g": 0.63, "b": 0.28, "a": 0.12}),
        )],
        vec![text(
            [arena.wall.x, arena.wall.y + arena.zone_half.y, ZONE_HEIGHT],
            "wall zone",
        )],
    )
}

/// One pile per brick type: a low box of its colour and its name.
fn piles(t: f64, arena: &Arena) -> Value {
    let mut pile_cubes = Vec::new();
    let mut pile_texts = Vec::new();
    for kind in BrickType::ALL {
        let p: Point = arena.pile(kind);
        pile_cubes.push(cube(
            [p.x, p.y, 0.2],
            [1.5, 1.5, 0.4],
            colour(brick_rgb(kind), 1.0),
        ));
        pile_texts.push(text([p.x, p.y, 1.0], &format!("{kind} pile")));
    }
    entity(t, "piles", &[], pile_cubes, pile_texts)
}

/// The design: every brick of the wall as a faint cube.
fn design(t: f64, arena: &Arena, wall: &Wall) -> Value {
    let plan: Vec<Value> = wall
        .ids()
        .map(|b| {
            let (c, s) = brick_box(arena, wall, b);
            cube(c, s, colour(brick_rgb(wall.brick(b).kind), 0.12))
        })
        .collect();
    entity(
        t,
        "design",
        &[("wall", wall.name().to_string())],
        plan,
        Vec::new(),
    )
}

/// A placed brick: a solid cube, entity `brick/<label>`, stamped with its placement time.
fn placed_brick(arena: &Arena, wall: &Wall, b: BrickId, placement: Placement) -> Value {
    let Placement { at, uav } = placement;
    let brick = wall.brick(b);
    let (c, s) = brick_box(arena, wall, b);
    entity(
        at,
        &format!("brick/{}", brick.label),
        &[
            ("label", brick.label.to_string()),
            ("type", brick.kind.to_string()),
            ("level", brick.level.to_string()),
            ("placed_by", uav.to_string()),
            ("placed_at_s", format!("{at}")),
        ],
        vec![cube(c, s, colour(brick_rgb(brick.kind), 1.0))],
        Vec::new(),
    )
}

/// A Foxglove `CubePrimitive`, axis-aligned.
fn cube(centre: [f64; 3], size: [f64; 3], rgba: Value) -> Value {
    json!({
        "pose": pose_json(centre[0], centre[1], centre[2], 0.0),
        "size": vec3(size[0], size[1], size[2]),
        "color": rgba,
    })
}

/// A Foxglove `TextPrimitive`: white, facing the camera, a constant size on screen.
fn text(at: [f64; 3], words: &str) -> Value {
    json!({
        "pose": pose_json(at[0], at[1], at[2], 0.0),
        "billboard": true,
        "font_size": 14.0,
        "scale_invariant": true,
        "color": {"r": 1.0, "g": 1.0, "b": 1.0, "a": 1.0},
        "text": words,
    })
}

/// A Foxglove `SceneEntity` in the frame `world` that lasts until replaced.
fn entity(
    t: f64,
    id: &str,
    metadata: &[(&str, String)],
    cubes: Vec<Value>,
    texts: Vec<Value>,
) -> Value {
    json!({
        "timestamp": stamp(t),
        "frame_id": "world",
        "id": id,
        "lifetime": {"sec": 0, "nsec": 0},
        "frame_locked": false,
        "metadata": metadata.iter().map(|(k, v)| json!({"key": k, "value": v})).collect::<Vec<_>>(),
        "arrows": [], "cubes": cubes, "spheres": [], "cylinders": [], "lines": [],
        "triangles": [], "texts": texts, "models": [],
    })
}
