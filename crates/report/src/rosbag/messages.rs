//! The ROS 2 messages of Mason's topics: their types, their definitions as rosbag2 stores them
//! (`ros2msg`), and their CDR encoding ([`Cdr`]).
//!
//! A definition is the type's own fields, then each type it depends on, once, after a line of
//! 80 `=` and a line `MSG: package/Type`: the concatenated form `ros2 bag record` writes and
//! every ROS 2 bag reader parses. The field lists are those of ROS 2 Kilted
//! (`std_msgs`, `geometry_msgs`, `visualization_msgs` 5.5.1; `builtin_interfaces` 2.3.0;
//! `sensor_msgs` 5.5.1); comments are left out, constants and default values kept.
//!
//! Type hashes (`RIHS01_…`, which rosbag2 writes in the bag's metadata) are those the
//! message packages ship; the bag read-back test compares them with the installed packages.

use super::cdr::Cdr;

/// The line between two definitions.
const SEPARATOR: &str =
    "================================================================================";

const TIME: &str = "int32 sec\nuint32 nanosec\n";
const DURATION: &str = "int32 sec\nuint32 nanosec\n";
const HEADER: &str = "builtin_interfaces/Time stamp\nstring frame_id\n";
const POINT: &str = "float64 x\nfloat64 y\nfloat64 z\n";
const VECTOR3: &str = "float64 x\nfloat64 y\nfloat64 z\n";
const QUATERNION: &str = "float64 x 0\nfloat64 y 0\nfloat64 z 0\nfloat64 w 1\n";
const POSE: &str = "geometry_msgs/Point position\ngeometry_msgs/Quaternion orientation\n";
const POSE_STAMPED: &str = "std_msgs/Header header\ngeometry_msgs/Pose pose\n";
const STRING: &str = "string data\n";
const COLOR_RGBA: &str = "float32 r\nfloat32 g\nfloat32 b\nfloat32 a\n";
const COMPRESSED_IMAGE: &str = "std_msgs/Header header\nstring format\nuint8[] data\n";
const UV_COORDINATE: &str = "float32 u\nfloat32 v\n";
const MESH_FILE: &str = "string filename\nuint8[] data\n";
const MARKER: &str = "int32 ARROW=0
int32 CUBE=1
int32 SPHERE=2
int32 CYLINDER=3
int32 LINE_STRIP=4
int32 LINE_LIST=5
int32 CUBE_LIST=6
int32 SPHERE_LIST=7
int32 POINTS=8
int32 TEXT_VIEW_FACING=9
int32 MESH_RESOURCE=10
int32 TRIANGLE_LIST=11
int32 ARROW_STRIP=12
int32 ADD=0
int32 MODIFY=0
int32 DELETE=2
int32 DELETEALL=3
std_msgs/Header header
string ns
int32 id
int32 type
int32 action
geometry_msgs/Pose pose
geometry_msgs/Vector3 scale
std_msgs/ColorRGBA color
builtin_interfaces/Duration lifetime
bool frame_locked
geometry_msgs/Point[] points
std_msgs/ColorRGBA[] colors
string texture_resource
sensor_msgs/CompressedImage texture
visualization_msgs/UVCoordinate[] uv_coordinates
string text
string mesh_resource
visualization_msgs/MeshFile mesh_file
bool mesh_use_embedded_materials
";
const MARKER_ARRAY: &str = "visualization_msgs/Marker[] markers\n";

/// A ROS 2 message type Mason publishes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum RosType {
    /// `geometry_msgs/msg/PoseStamped`: a UAV's pose.
    PoseStamped,
    /// `std_msgs/msg/String`: JSON text.
    String,
    /// `visualization_msgs/msg/MarkerArray`: the wall.
    MarkerArray,
}

impl RosType {
    /// The type's full name (`package/msg/Type`).
    pub fn name(self) -> &'static str {
        match self {
            RosType::PoseStamped => "geometry_msgs/msg/PoseStamped",
            RosType::String => "std_msgs/msg/String",
            RosType::MarkerArray => "visualization_msgs/msg/MarkerArray",
        }
    }

    /// The type hash of ROS 2 Kilted's message packages (RIHS01).
    pub fn hash(self) -> &'static str {
        match self {
            RosType::PoseStamped => {
                "RIHS01_10f3786d7d40fd2b54367835614bff85d4ad3b5dab62bf8bca0cc232d73b4cd8"
            }
            RosType::String => {
                "RIHS01_df668c740482bbd48fb39d76a70dfd4bd59db1288021743503259e948f6b1a18"
            }
            RosType::MarkerArray => {
                "RIHS01_86cb8800b6fb05b5eff1abd7a56f62a5641d3ae9a1c29e78e67e704f1d067dcf"
            }
        }
    }

    /// The full definition, dependencies included, in rosbag2's concatenated form.
    pub fn definition(self) -> String {
        let (own, deps): (&str, &[(&str, &str)]) = match self {
            RosType::PoseStamped => (
                POSE_STAMPED,
                &[
                    ("std_msgs/Header", HEADER),
                    ("builtin_interfaces/Time", TIME),
                    ("geometry_msgs/Pose", POSE),
                    ("geometry_msgs/Point", POINT),
                    ("geometry_msgs/Quaternion", QUATERNION),
                ],
            ),
            RosType::String => (STRING, &[]),
            RosType::MarkerArray => (
                MARKER_ARRAY,
                &[
                    ("visualization_msgs/Marker", MARKER),
                    ("std_msgs/Header", HEADER),
                    ("builtin_interfaces/Time", TIME),
                    ("geometry_msgs/Pose", POSE),
                    ("geometry_msgs/Point", POINT),
                    ("geometry_msgs/Quaternion", QUATERNION),
                    ("geometry_msgs/Vector3", VECTOR3),
                    ("std_msgs/ColorRGBA", COLOR_RGBA),
                    ("builtin_interfaces/Duration", DURATION),
                    ("sensor_msgs/CompressedImage", COMPRESSED_IMAGE),
                    ("visualization_msgs/UVCoordinate", UV_COORDINATE),
                    ("visualization_msgs/MeshFile", MESH_FILE),
                ],
            ),
        };
        let mut text = own.to_string();
        for (name, body) in deps {
            text.push_str(SEPARATOR);
            text.push_str("\nMSG: ");
            text.push_str(name);
            text.push('\n');
            text.push_str(body);
        }
        text
    }
}

/// A ROS 2 time (`builtin_interfaces/Time`): mission time, 0 = mission start.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Stamp {
    /// Whole seconds.
    pub sec: i32,
    /// Nanoseconds, below 10⁹.
    pub nanosec: u32,
}

impl Stamp {
    /// Mission time `t` (s) to the nanosecond (negative and NaN → 0; past `i32::MAX` s, that).
    pub fn of_seconds(t: f64) -> Self {
        Stamp::of_nanos(crate::mcap::nanos(t))
    }

    /// A time in nanoseconds.
    pub fn of_nanos(ns: u64) -> Self {
        let sec = (ns / 1_000_000_000).min(i32::MAX as u64) as i32;
        Stamp {
            sec,
            nanosec: (ns % 1_000_000_000) as u32,
        }
    }
}

/// An axis-aligned box of the wall (`visualization_msgs/msg/Marker`, type `CUBE`).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cube {
    /// The marker's id in its namespace.
    pub id: i32,
    /// Centre (m).
    pub centre: [f64; 3],
    /// Size along x, y, z (m).
    pub size: [f64; 3],
    /// Colour and opacity, each in 0..1.
    pub rgba: [f32; 4],
}

/// The marker type `CUBE`.
const CUBE: i32 = 1;
/// The marker action `ADD` (add or modify).
const ADD: i32 = 0;

fn header(c: &mut Cdr, stamp: Stamp, frame: &str) {
    c.i32(stamp.sec);
    c.u32(stamp.nanosec);
    c.string(frame);
}

fn pose(c: &mut Cdr, position: [f64; 3], yaw: f64) {
    for v in position {
        c.f64(v);
    }
    let (s, w) = (yaw / 2.0).sin_cos();
    for v in [0.0, 0.0, s, w] {
        c.f64(v);
    }
}

/// A `geometry_msgs/msg/PoseStamped` at `position`, heading `yaw` (rad from x, about z).
pub fn pose_stamped(stamp: Stamp, frame: &str, position: [f64; 3], yaw: f64) -> Vec<u8> {
    let mut c = Cdr::new();
    header(&mut c, stamp, frame);
    pose(&mut c, position, yaw);
    c.finish()
}

/// A `std_msgs/msg/String`.
pub fn string(text: &str) -> Vec<u8> {
    let mut c = Cdr::new();
    c.string(text);
    c.finish()
}

/// A `visualization_msgs/msg/MarkerArray` of `CUBE` markers in namespace `ns`, added (or
/// replaced, by id), lasting until replaced.
pub fn cube_array(stamp: Stamp, frame: &str, ns: &str, cubes: &[Cube]) -> Vec<u8> {
    let mut c = Cdr::new();
    c.sequence(cubes.len());
    for cube in cubes {
        header(&mut c, stamp, frame);
        c.string(ns);
        c.i32(cube.id);
        c.i32(CUBE);
        c.i32(ADD);
        pose(&mut c, cube.centre, 0.0);
        for v in cube.size {
            c.f64(v);
        }
        for v in cube.rgba {
            c.f32(v);
        }
        c.i32(0); // lifetime: forever
        c.u32(0);
        c.bool(false); // frame_locked
        c.sequence(0); // points
        c.sequence(0); // colors
        c.string(""); // texture_resource
        header(&mut c, Stamp::of_nanos(0), ""); // texture: no image
        c.string("");
        c.sequence(0);
        c.sequence(0); // uv_coordinates
        c.string(""); // text
        c.string(""); // mesh_resource
        c.string(""); // mesh_file: none
        c.sequence(0);
        c.bool(false); // mesh_use_embedded_materials
    }
    c.finish()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn definitions_list_each_dependency_once_after_a_separator() {
        let d = RosType::MarkerArray.definition();
        assert!(d.starts_with("visualization_msgs/Marker[] markers\n"));
        for dep in [
            "std_msgs/Header",
            "geometry_msgs/Pose",
            "visualization_msgs/MeshFile",
        ] {
            assert_eq!(d.matches(&format!("\nMSG: {dep}\n")).count(), 1, "{dep}");
        }
        assert_eq!(d.matches(SEPARATOR).count(), 12);
        assert_eq!(RosType::String.definition(), "string data\n");
        // Every type a definition names is defined in it (or is a primitive).
        for t in [RosType::PoseStamped, RosType::MarkerArray] {
            let d = t.definition();
            for line in d
                .lines()
                .filter(|l| !l.starts_with('=') && !l.starts_with("MSG:"))
            {
                let ty = line
                    .split_whitespace()
                    .next()
                    .unwrap()
                    .trim_end_matches("[]");
                if ty.contains('/') {
                    assert!(d.contains(&format!("MSG: {ty}\n")), "{ty} in {t:?}");
                }
            }
        }
    }

    #[test]
    fn a_pose_stamped_is_laid_out_as_cdr() {
        let b = pose_stamped(Stamp::of_seconds(1.5), "arena", [1.0, 2.0, 3.0], 0.0);
        // header: sec, nanosec, "arena" (4 + 6 bytes) → 18 after the encapsulation; pose
        // aligned to 24: 7 doubles.
        assert_eq!(&b[4..8], &1i32.to_le_bytes());
        assert_eq!(&b[8..12], &500_000_000u32.to_le_bytes());
        assert_eq!(&b[12..22], b"\x06\0\0\0arena\0");
        assert_eq!(&b[28..36], &1.0f64.to_le_bytes());
        assert_eq!(&b[76..84], &1.0f64.to_le_bytes()); // w
        assert_eq!(b.len(), 4 + 24 + 56);
    }

    #[test]
    fn stamps_split_seconds_and_nanoseconds() {
        assert_eq!(
            Stamp::of_seconds(12.25),
            Stamp {
                sec: 12,
                nanosec: 250_000_000
            }
        );
        assert_eq!(Stamp::of_seconds(-3.0), Stamp::of_nanos(0));
        assert_eq!(Stamp::of_seconds(f64::NAN), Stamp::of_nanos(0));
    }
}
