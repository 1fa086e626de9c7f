//! MCAP logs of a mission, for Foxglove: UAV poses, states, the wall zone, bricks, the wall as a
//! 3-D scene, every event as a log line, and the coordination messages.
//!
//! Every channel is JSON (`message_encoding = "json"`) with a JSON Schema
//! (`schema encoding = "jsonschema"`). The channels Foxglove draws use the schema names it knows,
//! so the file opens without set-up; the JSON Schemas are written here from Foxglove's public
//! schema definitions (the `foxglove` crate is not used).
//!
//! | topic | schema | one message per |
//! |---|---|---|
//! | `/uav/<i>/pose` | `foxglove.PoseInFrame` | pose sample of UAV i |
//! | `/uav/<i>/state` | `mason.UavState` | state transition of UAV i |
//! | `/zone` | `mason.Zone` | zone enter or leave |
//! | `/bricks` | `mason.Brick` | brick grasped, placed or lost |
//! | `/wall` | `foxglove.SceneUpdate` | start of the log, and each placement |
//! | `/events` | `foxglove.Log` | trace event |
//! | `/messages` | `mason.Message` | coordination message |
//!
//! Times: a message's `log_time` and `publish_time` are its mission time in nanoseconds (0 =
//! mission start), and every `timestamp` field is the same time as `{sec, nsec}`. Nothing reads
//! the wall clock, so one trace always gives the same bytes. Chunks are uncompressed and indexed.
//!
//! Geometry, in the frame `world`: x east and y north as in [`Arena`], z up, metres. The wall
//! runs along x with its middle at [`Arena::wall`]: a brick's centre is
//! `wall.x + (x0 + x1)/2 − m_x`, `wall.y + (y0 + y1)/2 − m_y`, `(level − ½) · BRICK_HEIGHT`,
//! where `m` is the middle of the box around every brick's footprint; its size is its footprint
//! by `BRICK_HEIGHT`. Each `/wall` message holds the whole scene (zone box, piles, every brick
//! of the design as a faint cube and every brick placed so far as a solid one, entity
//! `brick/<label>`), so a viewer that seeks and shows only the latest message still shows the
//! right wall.
//!
//! ```
//! use mason_mission::{Arena, Event, EventKind, UavState};
//! let wall = mason_wall::parse_layer_text("R G", "example").unwrap();
//! let arena = Arena::default();
//! let meta = mason_report::LogMeta { mission_id: "demo", uavs: 1, arena: &arena, wall: &wall };
//! let trace = [Event {
//!     t: 0.0,
//!     uav: 0,
//!     kind: EventKind::State { state: UavState::Check, outcome: "start", x: 50.0, y: 45.0 },
//! }];
//! let bytes = mason_report::mission_mcap(&meta, &trace, 10.0).unwrap();
//! assert!(bytes.starts_with(b"\x89MCAP0\r\n"));
//! ```

use mason_mission::{Arena, Event, EventKind, Point, UavState};
use mason_wall::{brick_rgb, BrickId, BrickType, Wall, BRICK_HEIGHT};
use serde_json::{json, Value};
use std::collections::BTreeMap;
use std::io::{Cursor, Seek, Write};

/// Rate of the interpolated poses [`write_trace`] adds along each leg (per second).
pub const POSE_RATE_HZ: f64 = 2.0;

/// Cruise altitude of UAV `i` (m): 3 + i, so that the UAVs fly at their own altitudes.
pub fn cruise_altitude(uav: u32) -> f64 {
    3.0 + f64::from(uav)
}

/// Why an MCAP log could not be written.
#[derive(Debug, thiserror::Error)]
pub enum McapLogError {
    /// The MCAP writer failed (an I/O error of the sink, or a record it refused).
    #[error("MCAP writer: {0}")]
    Mcap(#[from] ::mcap::McapError),
    /// A pose, event or message names a UAV outside the team.
    #[error("UAV {uav} is not in the team of {uavs}")]
    UnknownUav {
        /// The UAV named.
        uav: u32,
        /// The team size.
        uavs: usize,
    },
    /// An event names a brick the wall does not have.
    #[error("brick index {brick} is not in the wall of {bricks} bricks")]
    UnknownBrick {
        /// The brick index.
        brick: u32,
        /// The wall's brick count.
        bricks: usize,
    },
}

/// What a log is of: written once, at the start, as the MCAP metadata record `mission`, and
/// used to draw the scene.
#[derive(Clone, Copy, Debug)]
pub struct LogMeta<'a> {
    /// Names the mission in the metadata and in every `/messages` entry.
    pub mission_id: &'a str,
    /// Team size: one pose and one state channel per UAV.
    pub uavs: usize,
    /// The layout: piles, wall position, zone.
    pub arena: &'a Arena,
    /// The design being built.
    pub wall: &'a Wall,
}

/// A UAV's pose in the `world` frame: position (m) and heading (radians from east, counter-
/// clockwise).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct UavPose {
    /// East (m).
    pub x: f64,
    /// North (m).
    pub y: f64,
    /// Up (m).
    pub z: f64,
    /// Heading (rad).
    pub yaw: f64,
}

struct Channels {
    pose: Vec<u16>,
    state: Vec<u16>,
    zone: u16,
    bricks: u16,
    wall: u16,
    events: u16,
    messages: u16,
}

/// An MCAP log being written. Call [`McapLog::pose`], [`McapLog::event`] and
/// [`McapLog::message`] in mission-time order (equal times in any order), then
/// [`McapLog::finish`].
pub struct McapLog<'a, W: Write + Seek> {
    out: ::mcap::Writer<W>,
    meta: LogMeta<'a>,
    channels: Channels,
    sequence: BTreeMap<u16, u32>,
    /// Placement time and UAV of each brick placed so far, by brick index.
    placed: Vec<Option<(f64, u32)>>,
    placed_count: usize,
    inside: Vec<u32>,
}

/// Mission seconds → nanoseconds (negative and NaN → 0).
fn nanos(t: f64) -> u64 {
    (t.max(0.0) * 1e9).round() as u64
}

/// A Foxglove `time`.
fn stamp(t: f64) -> Value {
    let ns = nanos(t);
    json!({"sec": ns / 1_000_000_000, "nsec": ns % 1_000_000_000})
}

/// `v` rounded to `1 / scale` (positions to the micrometre: no float noise in the JSON).
fn round(v: f64, scale: f64) -> f64 {
    (v * scale).round() / scale
}

fn vec3(x: f64, y: f64, z: f64) -> Value {
    let r = |v| round(v, 1e6);
    json!({"x": r(x), "y": r(y), "z": r(z)})
}

fn pose_json(x: f64, y: f64, z: f64, yaw: f64) -> Value {
    let (s, c) = (round((yaw / 2.0).sin(), 1e9), round((yaw / 2.0).cos(), 1e9));
    json!({
        "position": vec3(x, y, z),
        "orientation": {"x": 0.0, "y": 0.0, "z": s, "w": c},
    })
}

fn colour(rgb: [u8; 3], a: f64) -> Value {
    let c = |v: u8| round(f64::from(v) / 255.0, 1e4);
    json!({"r": c(rgb[0]), "g": c(rgb[1]), "b": c(rgb[2]), "a": a})
}

fn cube(centre: [f64; 3], size: [f64; 3], rgba: Value) -> Value {
    json!({
        "pose": pose_json(centre[0], centre[1], centre[2], 0.0),
        "size": vec3(size[0], size[1], size[2]),
        "color": rgba,
    })
}

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

/// The centre and size (m) of a brick on the wall (see the module's convention).
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

/// Height of the drawn wall-zone box (m).
const ZONE_HEIGHT: f64 = 4.0;

impl<'a, W: Write + Seek> McapLog<'a, W> {
    /// Starts a log in `sink`: the header, the schemas and channels, the metadata record
    /// `mission` (mission id, wall name, bricks, team size) and the first `/wall` scene at t = 0.
    pub fn new(sink: W, meta: &LogMeta<'a>) -> Result<Self, McapLogError> {
        let options = ::mcap::WriteOptions::new()
            .compression(None)
            .profile("")
            .library(concat!("mason-report/", env!("CARGO_PKG_VERSION")));
        let mut out = options.create(sink)?;
        let schema = |out: &mut ::mcap::Writer<W>, name: &str, body: Value| {
            out.add_schema(name, "jsonschema", body.to_string().as_bytes())
        };
        let pose_schema = schema(&mut out, "foxglove.PoseInFrame", pose_in_frame_schema())?;
        let state_schema = schema(&mut out, "mason.UavState", uav_state_schema())?;
        let zone_schema = schema(&mut out, "mason.Zone", zone_schema())?;
        let brick_schema = schema(&mut out, "mason.Brick", brick_schema())?;
        let scene_schema = schema(&mut out, "foxglove.SceneUpdate", scene_update_schema())?;
        let log_schema = schema(&mut out, "foxglove.Log", log_schema())?;
        let message_schema = schema(&mut out, "mason.Message", message_schema())?;
        let none = BTreeMap::new();
        let channel = |out: &mut ::mcap::Writer<W>, schema: u16, topic: &str| {
            out.add_channel(schema, topic, "json", &none)
        };
        let mut pose = Vec::with_capacity(meta.uavs);
        let mut state = Vec::with_capacity(meta.uavs);
        for i in 0..meta.uavs {
            pose.push(channel(&mut out, pose_schema, &format!("/uav/{i}/pose"))?);
            state.push(channel(&mut out, state_schema, &format!("/uav/{i}/state"))?);
        }
        let channels = Channels {
            pose,
            state,
            zone: channel(&mut out, zone_schema, "/zone")?,
            bricks: channel(&mut out, brick_schema, "/bricks")?,
            wall: channel(&mut out, scene_schema, "/wall")?,
            events: channel(&mut out, log_schema, "/events")?,
            messages: channel(&mut out, message_schema, "/messages")?,
        };
        out.write_metadata(&::mcap::records::Metadata {
            name: "mission".into(),
            metadata: BTreeMap::from([
                ("mission_id".into(), meta.mission_id.into()),
                ("wall".into(), meta.wall.name().into()),
                ("bricks".into(), meta.wall.len().to_string()),
                ("uavs".into(), meta.uavs.to_string()),
                ("frame".into(), "world: x east, y north, z up (m)".into()),
            ]),
        })?;
        let mut log = McapLog {
            out,
            meta: *meta,
            channels,
            sequence: BTreeMap::new(),
            placed: vec![None; meta.wall.len()],
            placed_count: 0,
            inside: Vec::new(),
        };
        log.scene(0.0)?;
        Ok(log)
    }

    fn write(&mut self, channel: u16, t: f64, body: &Value) -> Result<(), McapLogError> {
        let seq = self.sequence.entry(channel).or_insert(0);
        *seq += 1;
        let header = ::mcap::records::MessageHeader {
            channel_id: channel,
            sequence: *seq,
            log_time: nanos(t),
            publish_time: nanos(t),
        };
        self.out
            .write_to_known_channel(&header, body.to_string().as_bytes())?;
        Ok(())
    }

    fn check_uav(&self, uav: u32) -> Result<usize, McapLogError> {
        let i = uav as usize;
        if i < self.meta.uavs {
            Ok(i)
        } else {
            Err(McapLogError::UnknownUav {
                uav,
                uavs: self.meta.uavs,
            })
        }
    }

    /// UAV `uav`'s pose at mission time `t` (s), on `/uav/<uav>/pose`.
    pub fn pose(&mut self, t: f64, uav: u32, p: UavPose) -> Result<(), McapLogError> {
        let i = self.check_uav(uav)?;
        let body = json!({
            "timestamp": stamp(t),
            "frame_id": "world",
            "pose": pose_json(p.x, p.y, p.z, p.yaw),
        });
        self.write(self.channels.pose[i], t, &body)
    }

    /// One trace event: a line on `/events`, and by kind a `/uav/<i>/state`, `/zone` or
    /// `/bricks` message; a placement also writes the new `/wall` scene.
    pub fn event(&mut self, e: &Event) -> Result<(), McapLogError> {
        let i = self.check_uav(e.uav)?;
        let t = e.t;
        let (level, line) = match e.kind {
            EventKind::State {
                state,
                outcome,
                x,
                y,
            } => {
                let body = json!({
                    "timestamp": stamp(t), "uav": e.uav, "state": state.name(),
                    "outcome": outcome, "x": x, "y": y,
                });
                self.write(self.channels.state[i], t, &body)?;
                let level = match state {
                    UavState::SafeLand | UavState::Down => 3,
                    _ if outcome == "failed" || outcome == "gave_up" => 3,
                    _ => 2,
                };
                (
                    level,
                    format!("{} ({outcome}) at ({x:.2}, {y:.2})", state.name()),
                )
            }
            EventKind::Grasp { brick } | EventKind::Place { brick } | EventKind::Lost { brick } => {
                let label = self.label(brick)?;
                let action = match e.kind {
                    EventKind::Grasp { .. } => "grasp",
                    EventKind::Place { .. } => "place",
                    _ => "lost",
                };
                if action == "place" && self.placed[brick.index()].is_none() {
                    self.placed[brick.index()] = Some((t, e.uav));
                    self.placed_count += 1;
                }
                let body = json!({
                    "timestamp": stamp(t), "uav": e.uav, "action": action, "brick": label,
                    "placed": self.placed_count,
                });
                self.write(self.channels.bricks, t, &body)?;
                if action == "place" {
                    self.scene(t)?;
                }
                let level = if action == "lost" { 3 } else { 2 };
                (level, format!("{action} brick {label}"))
            }
            EventKind::ZoneEnter | EventKind::ZoneLeave => {
                let enter = matches!(e.kind, EventKind::ZoneEnter);
                if enter {
                    if !self.inside.contains(&e.uav) {
                        self.inside.push(e.uav);
                        self.inside.sort_unstable();
                    }
                } else {
                    self.inside.retain(|&u| u != e.uav);
                }
                let what = if enter { "enter" } else { "leave" };
                let body = json!({
                    "timestamp": stamp(t), "uav": e.uav, "event": what,
                    "inside": self.inside, "count": self.inside.len(),
                });
                self.write(self.channels.zone, t, &body)?;
                (2, format!("zone {what} (inside: {:?})", self.inside))
            }
            EventKind::Fail => (4, "failed: out of the mission".to_string()),
            EventKind::Replan { bricks } => (2, format!("re-planned the rest: {bricks} bricks")),
            EventKind::Comm { mode } => {
                let name = match mode {
                    mason_mission::CommMode::Comm => "comm",
                    mason_mission::CommMode::Windows => "windows",
                };
                let level = if name == "windows" { 3 } else { 2 };
                (level, format!("coordination mode: {name}"))
            }
        };
        let body = json!({
            "timestamp": stamp(t), "level": level, "message": line,
            "name": format!("uav{}", e.uav), "file": "", "line": 0,
        });
        self.write(self.channels.events, t, &body)
    }

    /// A coordination message sent by `from_uav` at `t`, on `/messages`: its `kind` (heartbeat,
    /// claim, zone request, …) and its JSON body, tagged with the mission id.
    pub fn message(
        &mut self,
        t: f64,
        from_uav: u32,
        kind: &str,
        body: &Value,
    ) -> Result<(), McapLogError> {
        self.check_uav(from_uav)?;
        let msg = json!({
            "timestamp": stamp(t), "mission_id": self.meta.mission_id, "from": from_uav,
            "kind": kind, "body": body,
        });
        self.write(self.channels.messages, t, &msg)
    }

    /// Writes the summary and the footer, and returns the sink.
    pub fn finish(mut self) -> Result<W, McapLogError> {
        self.out.finish()?;
        Ok(self.out.into_inner())
    }

    fn label(&self, brick: BrickId) -> Result<u32, McapLogError> {
        if brick.index() < self.meta.wall.len() {
            Ok(self.meta.wall.brick(brick).label)
        } else {
            Err(McapLogError::UnknownBrick {
                brick: brick.0,
                bricks: self.meta.wall.len(),
            })
        }
    }

    /// The whole scene at `t` on `/wall`.
    fn scene(&mut self, t: f64) -> Result<(), McapLogError> {
        let (arena, wall) = (self.meta.arena, self.meta.wall);
        let mut entities = Vec::with_capacity(3 + self.placed_count);
        let zone_centre = [arena.wall.x, arena.wall.y, ZONE_HEIGHT / 2.0];
        entities.push(entity(
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
        ));
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
        entities.push(entity(t, "piles", &[], pile_cubes, pile_texts));
        let plan: Vec<Value> = wall
            .ids()
            .map(|b| {
                let (c, s) = brick_box(arena, wall, b);
                cube(c, s, colour(brick_rgb(wall.brick(b).kind), 0.12))
            })
            .collect();
        entities.push(entity(
            t,
            "design",
            &[("wall", wall.name().to_string())],
            plan,
            Vec::new(),
        ));
        for b in wall.ids() {
            let Some((at, uav)) = self.placed[b.index()] else {
                continue;
            };
            let brick = wall.brick(b);
            let (c, s) = brick_box(arena, wall, b);
            entities.push(entity(
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
            ));
        }
        let body = json!({"deletions": [], "entities": entities});
        self.write(self.channels.wall, t, &body)
    }
}

/// Altitude of UAV `uav` at the start of `state`: on the ground before take-off and after
/// landing, at its cruise altitude otherwise (so take-off climbs and landing descends).
fn altitude(uav: u32, state: UavState) -> f64 {
    match state {
        UavState::Check | UavState::TakeOff | UavState::Landed | UavState::Down => 0.0,
        _ => cruise_altitude(uav),
    }
}

/// Writes a simulated mission's trace into `log`, ending at `end_s`: every event, and each
/// UAV's pose at each of its state events and at [`POSE_RATE_HZ`] (on the grid `k /
/// POSE_RATE_HZ`) along every leg between two of them, where it flies straight, plus its last
/// pose at `end_s`. The trace's state events give the positions (x, y); z is
/// [`cruise_altitude`] in the air and 0 on the ground; the heading follows the last leg flown.
/// The trace is taken in time order, as the simulator emits it; poses and events are merged
/// in time order (at one instant, the poses first).
pub fn write_trace<W: Write + Seek>(
    log: &mut McapLog<'_, W>,
    trace: &[Event],
    end_s: f64,
) -> Result<(), McapLogError> {
    let uavs = log.meta.uavs;
    let mut samples: Vec<(f64, u32, UavPose)> = Vec::new();
    let mut last: Vec<Option<(f64, UavPose)>> = vec![None; uavs];
    let step = 1.0 / POSE_RATE_HZ;
    for e in trace {
        let EventKind::State { state, x, y, .. } = e.kind else {
            continue;
        };
        let i = log.check_uav(e.uav)?;
        let mut here = UavPose {
            x,
            y,
            z: altitude(e.uav, state),
            yaw: 0.0,
        };
        if let Some((t0, from)) = last[i] {
            let (dx, dy) = (here.x - from.x, here.y - from.y);
            here.yaw = if dx.hypot(dy) > 1e-9 {
                dy.atan2(dx)
            } else {
                from.yaw
            };
            let moving = dx != 0.0 || dy != 0.0 || here.z != from.z;
            if moving && e.t > t0 {
                let mut k = (t0 * POSE_RATE_HZ).floor() + 1.0;
                while k * step < e.t {
                    let t = k * step;
                    let f = (t - t0) / (e.t - t0);
                    let p = UavPose {
                        x: from.x + dx * f,
                        y: from.y + dy * f,
                        z: from.z + (here.z - from.z) * f,
                        yaw: here.yaw,
                    };
                    samples.push((t, e.uav, p));
                    k += 1.0;
                }
            }
        }
        samples.push((e.t, e.uav, here));
        last[i] = Some((e.t, here));
    }
    for (i, l) in last.iter().enumerate() {
        if let Some((t, p)) = l {
            if end_s > *t {
                samples.push((end_s, i as u32, *p));
            }
        }
    }
    // Stable: at one time, UAVs in order, and a UAV's samples in the order made.
    samples.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    let mut events = trace.iter().peekable();
    for (t, uav, p) in samples {
        while let Some(e) = events.next_if(|e| e.t < t) {
            log.event(e)?;
        }
        log.pose(t, uav, p)?;
    }
    for e in events {
        log.event(e)?;
    }
    Ok(())
}

/// The MCAP log of a simulated mission (see [`write_trace`]) as bytes.
pub fn mission_mcap(
    meta: &LogMeta<'_>,
    trace: &[Event],
    end_s: f64,
) -> Result<Vec<u8>, McapLogError> {
    let mut log = McapLog::new(Cursor::new(Vec::new()), meta)?;
    write_trace(&mut log, trace, end_s)?;
    Ok(log.finish()?.into_inner())
}

// JSON Schemas, after Foxglove's published definitions (time, duration, Vector3, Quaternion,
// Pose, Color, KeyValuePair, CubePrimitive, TextPrimitive, SceneEntity, SceneEntityDeletion,
// SceneUpdate, PoseInFrame, Log), and Mason's own.

fn time_schema(description: &str) -> Value {
    json!({
        "type": "object", "title": "time", "description": description,
        "properties": {
            "sec": {"type": "integer", "minimum": 0},
            "nsec": {"type": "integer", "minimum": 0, "maximum": 999_999_999},
        },
    })
}

fn numbers(title: &str, description: &str, keys: &[&str]) -> Value {
    let properties: serde_json::Map<String, Value> = keys
        .iter()
        .map(|k| (k.to_string(), json!({"type": "number"})))
        .collect();
    json!({"type": "object", "title": title, "description": description, "properties": properties})
}

fn pose_schema() -> Value {
    json!({
        "type": "object", "title": "foxglove.Pose",
        "description": "A position and orientation for an object or reference frame in 3D space",
        "properties": {
            "position": numbers("foxglove.Vector3", "Point denoting position in 3D space", &["x", "y", "z"]),
            "orientation": numbers("foxglove.Quaternion", "Quaternion denoting orientation in 3D space", &["x", "y", "z", "w"]),
        },
    })
}

fn colour_schema() -> Value {
    numbers(
        "foxglove.Color",
        "A color in RGBA format, each component in 0..1",
        &["r", "g", "b", "a"],
    )
}

fn pose_in_frame_schema() -> Value {
    json!({
        "title": "foxglove.PoseInFrame",
        "description": "A timestamped pose for an object or reference frame in 3D space",
        "type": "object",
        "properties": {
            "timestamp": time_schema("Timestamp of pose"),
            "frame_id": {"type": "string", "description": "Frame of reference for pose position and orientation"},
            "pose": pose_schema(),
        },
    })
}

fn open_array(description: &str) -> Value {
    json!({"type": "array", "description": description, "items": {"type": "object"}})
}

fn scene_update_schema() -> Value {
    let cube = json!({
        "type": "object", "title": "foxglove.CubePrimitive", "description": "A primitive representing a cube or rectangular prism",
        "properties": {
            "pose": pose_schema(),
            "size": numbers("foxglove.Vector3", "Size of the cube along each axis", &["x", "y", "z"]),
            "color": colour_schema(),
        },
    });
    let text = json!({
        "type": "object", "title": "foxglove.TextPrimitive", "description": "A primitive representing a text label",
        "properties": {
            "pose": pose_schema(),
            "billboard": {"type": "boolean"},
            "font_size": {"type": "number"},
            "scale_invariant": {"type": "boolean"},
            "color": colour_schema(),
            "text": {"type": "string"},
        },
    });
    let entity = json!({
        "type": "object", "title": "foxglove.SceneEntity",
        "description": "A visual element in a 3D scene, made of primitives sharing one frame of reference",
        "properties": {
            "timestamp": time_schema("Timestamp of the entity"),
            "frame_id": {"type": "string", "description": "Frame of reference"},
            "id": {"type": "string", "description": "Replaces any earlier entity on the topic with the same id"},
            "lifetime": {
                "type": "object", "title": "duration", "description": "Time after which the entity is removed; zero: until replaced or deleted",
                "properties": {
                    "sec": {"type": "integer"},
                    "nsec": {"type": "integer", "minimum": 0, "maximum": 999_999_999},
                },
            },
            "frame_locked": {"type": "boolean"},
            "metadata": {
                "type": "array",
                "items": {
                    "type": "object", "title": "foxglove.KeyValuePair",
                    "properties": {"key": {"type": "string"}, "value": {"type": "string"}},
                },
            },
            "arrows": open_array("Arrow primitives (Mason writes none)"),
            "cubes": {"type": "array", "items": cube},
            "spheres": open_array("Sphere primitives (Mason writes none)"),
            "cylinders": open_array("Cylinder primitives (Mason writes none)"),
            "lines": open_array("Line primitives (Mason writes none)"),
            "triangles": open_array("Triangle list primitives (Mason writes none)"),
            "texts": {"type": "array", "items": text},
            "models": open_array("Model primitives (Mason writes none)"),
        },
    });
    json!({
        "title": "foxglove.SceneUpdate",
        "description": "An update to the entities displayed in a 3D scene",
        "type": "object",
        "properties": {
            "deletions": {
                "type": "array",
                "items": {
                    "type": "object", "title": "foxglove.SceneEntityDeletion",
                    "properties": {
                        "timestamp": time_schema("Only matching entities earlier than this are deleted"),
                        "type": {
                            "title": "foxglove.SceneEntityDeletionType",
                            "oneOf": [
                                {"title": "MATCHING_ID", "const": 0},
                                {"title": "ALL", "const": 1},
                            ],
                        },
                        "id": {"type": "string"},
                    },
                },
            },
            "entities": {"type": "array", "items": entity},
        },
    })
}

fn log_schema() -> Value {
    let levels: Vec<Value> = ["UNKNOWN", "DEBUG", "INFO", "WARNING", "ERROR", "FATAL"]
        .iter()
        .enumerate()
        .map(|(i, name)| json!({"title": name, "const": i}))
        .collect();
    json!({
        "title": "foxglove.Log",
        "description": "A log message",
        "type": "object",
        "properties": {
            "timestamp": time_schema("Timestamp of log message"),
            "level": {"title": "foxglove.LogLevel", "description": "Log level", "oneOf": levels},
            "message": {"type": "string", "description": "Log message"},
            "name": {"type": "string", "description": "Process or node name (Mason: uav<i>)"},
            "file": {"type": "string", "description": "Filename"},
            "line": {"type": "integer", "minimum": 0, "description": "Line number in the file"},
        },
    })
}

fn uav_state_schema() -> Value {
    let states: Vec<&str> = UavState::ALL.iter().map(|s| s.name()).collect();
    json!({
        "title": "mason.UavState",
        "description": "A UAV's state transition (thesis Fig. 4.3): the new state, the outcome of the state left, and where it happened",
        "type": "object",
        "properties": {
            "timestamp": time_schema("Mission time"),
            "uav": {"type": "integer", "minimum": 0},
            "state": {"type": "string", "enum": states},
            "outcome": {"type": "string"},
            "x": {"type": "number", "description": "East (m)"},
            "y": {"type": "number", "description": "North (m)"},
        },
        "required": ["timestamp", "uav", "state", "outcome", "x", "y"],
    })
}

fn zone_schema() -> Value {
    json!({
        "title": "mason.Zone",
        "description": "A UAV entered or left the wall zone; who is inside after it",
        "type": "object",
        "properties": {
            "timestamp": time_schema("Mission time"),
            "uav": {"type": "integer", "minimum": 0},
            "event": {"type": "string", "enum": ["enter", "leave"]},
            "inside": {"type": "array", "items": {"type": "integer", "minimum": 0}},
            "count": {"type": "integer", "minimum": 0},
        },
        "required": ["timestamp", "uav", "event", "inside", "count"],
    })
}

fn brick_schema() -> Value {
    json!({
        "title": "mason.Brick",
        "description": "A brick grasped, placed or lost; brick is its label (thesis id), placed the bricks on the wall after it",
        "type": "object",
        "properties": {
            "timestamp": time_schema("Mission time"),
            "uav": {"type": "integer", "minimum": 0},
            "action": {"type": "string", "enum": ["grasp", "place", "lost"]},
            "brick": {"type": "integer"},
            "placed": {"type": "integer", "minimum": 0},
        },
        "required": ["timestamp", "uav", "action", "brick", "placed"],
    })
}

fn message_schema() -> Value {
    json!({
        "title": "mason.Message",
        "description": "A coordination message one UAV sent (heartbeat, state, claim, zone request or release, placed)",
        "type": "object",
        "properties": {
            "timestamp": time_schema("Mission time it was sent"),
            "mission_id": {"type": "string"},
            "from": {"type": "integer", "minimum": 0},
            "kind": {"type": "string"},
            "body": {},
        },
        "required": ["timestamp", "mission_id", "from", "kind", "body"],
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use mason_mission::{make_policy, simulate, Coord, MissionConfig, MissionInput};

    /// A 3-UAV mission on the thesis's 2 × 5 wall: the trace and its end time.
    fn flown() -> (Wall, MissionConfig, Vec<Event>, f64) {
        let wall = mason_wall::builtin("thesis-2x5").unwrap().wall();
        let model = mason_order::CostModel::default();
        let order: Vec<_> = wall.ids().collect();
        let config = MissionConfig::with_uavs(3);
        let input = MissionInput {
            wall: &wall,
            order: &order,
            model: &model,
            assignment: None,
            replanner: None,
            config: &config,
        };
        let mut trace = Vec::new();
        let r = simulate(
            input,
            make_policy(Coord::Comm, 20.0).as_mut(),
            7,
            &mut trace,
        );
        let end = r.metrics.end_s;
        (wall, config, trace, end)
    }

    fn bytes_of(wall: &Wall, config: &MissionConfig, trace: &[Event], end: f64) -> Vec<u8> {
        let meta = LogMeta {
            mission_id: "test",
            uavs: 3,
            arena: &config.arena,
            wall,
        };
        mission_mcap(&meta, trace, end).unwrap()
    }

    /// (topic, schema name, schema encoding, message encoding, log_time, payload) per message.
    fn read_back(bytes: &[u8]) -> Vec<(String, String, String, String, u64, Value)> {
        ::mcap::MessageStream::new(bytes)
            .unwrap()
            .map(|m| {
                let m = m.unwrap();
                let schema = m
                    .channel
                    .schema
                    .as_ref()
                    .expect("every channel has a schema");
                let body: Value = serde_json::from_slice(&m.data).unwrap();
                assert_eq!(m.log_time, m.publish_time);
                (
                    m.channel.topic.clone(),
                    schema.name.clone(),
                    schema.encoding.clone(),
                    m.channel.message_encoding.clone(),
                    m.log_time,
                    body,
                )
            })
            .collect()
    }

    #[test]
    fn the_log_reads_back_with_foxglove_schema_names_and_json() {
        let (wall, config, trace, end) = flown();
        let messages = read_back(&bytes_of(&wall, &config, &trace, end));
        let mut schemas = BTreeMap::new();
        for (topic, schema, schema_enc, msg_enc, log_time, body) in &messages {
            assert_eq!(schema_enc, "jsonschema");
            assert_eq!(msg_enc, "json");
            schemas.insert(topic.clone(), schema.clone());
            // The payload's timestamp is the message's log time.
            if let Some(ts) = body.get("timestamp") {
                let ns = ts["sec"].as_u64().unwrap() * 1_000_000_000 + ts["nsec"].as_u64().unwrap();
                assert_eq!(ns, *log_time, "{topic}");
            }
        }
        for i in 0..3 {
            assert_eq!(schemas[&format!("/uav/{i}/pose")], "foxglove.PoseInFrame");
            assert_eq!(schemas[&format!("/uav/{i}/state")], "mason.UavState");
        }
        assert_eq!(schemas["/wall"], "foxglove.SceneUpdate");
        assert_eq!(schemas["/events"], "foxglove.Log");
        assert_eq!(schemas["/zone"], "mason.Zone");
        assert_eq!(schemas["/bricks"], "mason.Brick");
        // The simulator sends no message: the channel exists, empty.
        assert!(!schemas.contains_key("/messages"));
        // Messages are in time order.
        assert!(messages.windows(2).all(|w| w[0].4 <= w[1].4));
    }

    #[test]
    fn every_event_is_logged_once_and_every_placement_once() {
        let (wall, config, trace, end) = flown();
        let messages = read_back(&bytes_of(&wall, &config, &trace, end));
        let count = |topic: &str| messages.iter().filter(|m| m.0 == topic).count();
        assert_eq!(count("/events"), trace.len());
        let placed = trace
            .iter()
            .filter(|e| matches!(e.kind, EventKind::Place { .. }))
            .count();
        assert_eq!(placed, wall.len());
        let places: Vec<&Value> = messages
            .iter()
            .filter(|m| m.0 == "/bricks" && m.5["action"] == "place")
            .map(|m| &m.5)
            .collect();
        assert_eq!(places.len(), placed);
        assert_eq!(places.last().unwrap()["placed"], json!(placed));
        // The scene: once at the start, once per placement; the last one shows every brick.
        assert_eq!(count("/wall"), 1 + placed);
        let last_scene = &messages.iter().rev().find(|m| m.0 == "/wall").unwrap().5;
        let bricks = last_scene["entities"]
            .as_array()
            .unwrap()
            .iter()
            .filter(|e| e["id"].as_str().unwrap().starts_with("brick/"))
            .count();
        assert_eq!(bricks, wall.len());
        for i in 0..3u32 {
            let states = trace
                .iter()
                .filter(|e| e.uav == i && matches!(e.kind, EventKind::State { .. }))
                .count();
            assert_eq!(count(&format!("/uav/{i}/state")), states);
        }
        let zone_events = trace
            .iter()
            .filter(|e| matches!(e.kind, EventKind::ZoneEnter | EventKind::ZoneLeave))
            .count();
        assert_eq!(count("/zone"), zone_events);
    }

    #[test]
    fn poses_move_forward_in_time_and_stay_in_the_arena() {
        let (wall, config, trace, end) = flown();
        let messages = read_back(&bytes_of(&wall, &config, &trace, end));
        for i in 0..3 {
            let poses: Vec<_> = messages
                .iter()
                .filter(|m| m.0 == format!("/uav/{i}/pose"))
                .collect();
            // At least the 2 Hz samples of a mission that long.
            assert!(poses.len() as f64 > end, "UAV {i}: {} poses", poses.len());
            assert!(poses.windows(2).all(|w| w[0].4 <= w[1].4), "UAV {i}");
            assert_eq!(poses.last().unwrap().4, nanos(end));
            for p in &poses {
                let pos = &p.5["pose"]["position"];
                let (x, y, z) = (
                    pos["x"].as_f64().unwrap(),
                    pos["y"].as_f64().unwrap(),
                    pos["z"].as_f64().unwrap(),
                );
                assert!((0.0..=config.arena.width).contains(&x), "{x}");
                assert!((0.0..=config.arena.depth).contains(&y), "{y}");
                assert!((0.0..=cruise_altitude(i)).contains(&z), "{z}");
                assert_eq!(p.5["frame_id"], "world");
            }
            // Landed at the end.
            assert_eq!(poses.last().unwrap().5["pose"]["position"]["z"], json!(0.0));
        }
    }

    #[test]
    fn one_trace_gives_the_same_bytes() {
        let (wall, config, trace, end) = flown();
        let a = bytes_of(&wall, &config, &trace, end);
        let b = bytes_of(&wall, &config, &trace, end);
        assert_eq!(a, b);
    }

    #[test]
    fn messages_are_logged_and_strangers_refused() {
        let wall = mason_wall::builtin("thesis-2x5").unwrap().wall();
        let arena = Arena::default();
        let meta = LogMeta {
            mission_id: "m-1",
            uavs: 2,
            arena: &arena,
            wall: &wall,
        };
        let mut log = McapLog::new(Cursor::new(Vec::new()), &meta).unwrap();
        log.message(1.5, 1, "claim", &json!({"brick": 101}))
            .unwrap();
        let err = log.message(2.0, 2, "claim", &json!({})).unwrap_err();
        assert!(
            matches!(err, McapLogError::UnknownUav { uav: 2, uavs: 2 }),
            "{err}"
        );
        let stranger = Event {
            t: 2.0,
            uav: 5,
            kind: EventKind::Fail,
        };
        assert!(log.event(&stranger).is_err());
        let far_brick = Event {
            t: 2.0,
            uav: 0,
            kind: EventKind::Place { brick: BrickId(99) },
        };
        assert!(matches!(
            log.event(&far_brick),
            Err(McapLogError::UnknownBrick { brick: 99, .. })
        ));
        let bytes = log.finish().unwrap().into_inner();
        let messages = read_back(&bytes);
        let sent: Vec<_> = messages.iter().filter(|m| m.0 == "/messages").collect();
        assert_eq!(sent.len(), 1);
        assert_eq!(sent[0].1, "mason.Message");
        assert_eq!(sent[0].4, 1_500_000_000);
        assert_eq!(sent[0].5["mission_id"], "m-1");
        assert_eq!(sent[0].5["body"]["brick"], 101);
    }
}
