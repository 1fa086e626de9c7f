//! The JSON form of the values every message is made of: a mission time as Foxglove's `time`,
//! a vector, a pose and a colour. Positions are rounded to the micrometre and quaternion
//! components to 1e-9, so no float noise reaches the JSON.

use serde_json::{json, Value};

/// Mission seconds → nanoseconds (negative and NaN → 0).
pub(crate) fn nanos(t: f64) -> u64 {
    (t.max(0.0) * 1e9).round() as u64
}

/// A Foxglove `time`.
pub(super) fn stamp(t: f64) -> Value {
    let ns = nanos(t);
    json!({"sec": ns / 1_000_000_000, "nsec": ns % 1_000_000_000})
}

/// `v` rounded to `1 / scale` (positions to the micrometre: no float noise in the JSON).
fn round(v: f64, scale: f64) -> f64 {
    (v * scale).round() / scale
}

/// A Foxglove `Vector3` (m, to the micrometre).
pub(super) fn vec3(x: f64, y: f64, z: f64) -> Value {
    let r = |v| round(v, 1e6);
    json!({"x": r(x), "y": r(y), "z": r(z)})
}

/// A Foxglove `Pose`: a position and a heading `yaw` (rad from east) as a quaternion about z.
pub(super) fn pose_json(x: f64, y: f64, z: f64, yaw: f64) -> Value {
    let (s, c) = (round((yaw / 2.0).sin(), 1e9), round((yaw / 2.0).cos(), 1e9));
    json!({
        "position": vec3(x, y, z),
        "orientation": {"x": 0.0, "y": 0.0, "z": s, "w": c},
    })
}

/// A Foxglove `Color` from 8-bit RGB and an opacity `a` in 0..1.
pub(super) fn colour(rgb: [u8; 3], a: f64) -> Value {
    let c = |v: u8| round(f64::from(v) / 255.0, 1e4);
    json!({"r": c(rgb[0]), "g": c(rgb[1]), "b": c(rgb[2]), "a": a})
}
