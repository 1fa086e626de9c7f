//! The JSON Schemas of the channels: Foxglove's `PoseInFrame`, `SceneUpdate` and `Log`, written
//! after Foxglove's published definitions (time, duration, Vector3, Quaternion, Pose, Color,
//! KeyValuePair, CubePrimitive, TextPrimitive, SceneEntity, SceneEntityDeletion), and Mason's
//! own `mason.UavState`, `mason.Zone`, `mason.Brick` and `mason.Message`.
//!
//! Each function returns the schema body; the writer registers it under the schema's title
//! with the encoding `jsonschema`.

use mason_mission::UavState;
use serde_json::{json, Value};

/// Foxglove's `time`: seconds and nanoseconds.
fn time_schema(description: &str) -> Value {
    json!({
        "type": "object", "title": "time", "description": description,
        "properties": {
            "sec": {"type": "integer", "minimum": 0},
            "nsec": {"type": "integer", "minimum": 0, "maximum": 999_999_999},
        },
    })
}

/// An object of number fields `keys` (a Vector3, a Quaternion, a Color).
fn numbers(title: &str, description: &str, keys: &[&str]) -> Value {
    let properties: serde_json::Map<String, Value> = keys
        .iter()
        .map(|k| (k.to_string(), json!({"type": "number"})))
        .collect();
    json!({"type": "object", "title": title, "description": description, "properties": properties})
}

/// Foxglove's `Pose`: a position and an orientation.
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

/// Foxglove's `Color`: RGBA in 0..1.
fn colour_schema() -> Value {
    numbers(
        "foxglove.Color",
        "A color in RGBA format, each component in 0..1",
        &["r", "g", "b", "a"],
    )
}

/// `foxglove.PoseInFrame`: the `/uav/<i>/pose` messages.
pub(super) fn pose_in_frame() -> Value {
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

/// An array of primitives Mason never writes (its items left open).
fn open_array(description: &str) -> Value {
    json!({"type": "array", "description": description, "items": {"type": "object"}})
}

/// `foxglove.SceneUpdate`: the `/wall` scene, cubes and texts only.
pub(super) fn scene_update() -> Value {
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

/// `foxglove.Log`: the `/events` lines.
pub(super) fn log() -> Value {
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

/// `mason.UavState`: the `/uav/<i>/state` transitions.
pub(super) fn uav_state() -> Value {
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

/// `mason.Zone`: the `/zone` enter and leave messages.
pub(super) fn zone() -> Value {
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

/// `mason.Brick`: the `/bricks` grasp, place and lost messages.
pub(super) fn brick() -> Value {
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

/// `mason.Message`: the `/messages` coordination messages.
pub(super) fn message() -> Value {
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
