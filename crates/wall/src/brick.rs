//! Brick types, ids and footprints.

use serde::{Deserialize, Serialize};
use std::fmt;

/// Height of every brick (m).
pub const BRICK_HEIGHT: f64 = 0.20;
/// Depth of every brick (m).
pub const BRICK_DEPTH: f64 = 0.20;
/// Length of the shortest brick and of an empty `.` slot (m).
pub const UNIT_LENGTH: f64 = 0.30;
/// Overlap below which two footprints do not touch (m): 1 mm.
pub const OVERLAP_EPS: f64 = 0.001;
/// Largest footprint gap at which two bricks are still neighbours (m).
pub const NEIGHBOUR_GAP: f64 = 0.10;

/// The four MBZIRC brick colours.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum BrickType {
    /// 0.30 m, one UAV.
    Red,
    /// 0.60 m, one UAV.
    Green,
    /// 1.20 m, one UAV.
    Blue,
    /// 1.80 m, two UAVs.
    Orange,
}

impl BrickType {
    /// All types in id order.
    pub const ALL: [BrickType; 4] = [
        BrickType::Red,
        BrickType::Green,
        BrickType::Blue,
        BrickType::Orange,
    ];

    /// The numeric type id (1 red … 4 orange), as in CMCP.
    pub fn id(self) -> u8 {
        self.index() as u8 + 1
    }

    /// Dense index 0..4, for per-type tables.
    pub fn index(self) -> usize {
        match self {
            BrickType::Red => 0,
            BrickType::Green => 1,
            BrickType::Blue => 2,
            BrickType::Orange => 3,
        }
    }

    /// The type with this numeric id (1..=4).
    pub fn from_id(id: u8) -> Option<BrickType> {
        Self::ALL.get(usize::from(id).checked_sub(1)?).copied()
    }

    /// Lower-case colour name.
    pub fn name(self) -> &'static str {
        match self {
            BrickType::Red => "red",
            BrickType::Green => "green",
            BrickType::Blue => "blue",
            BrickType::Orange => "orange",
        }
    }

    /// The layer-text token (`R G B O`).
    pub fn token(self) -> char {
        match self {
            BrickType::Red => 'R',
            BrickType::Green => 'G',
            BrickType::Blue => 'B',
            BrickType::Orange => 'O',
        }
    }

    /// The type for a layer-text token.
    pub fn from_token(token: &str) -> Option<BrickType> {
        match token {
            "R" => Some(BrickType::Red),
            "G" => Some(BrickType::Green),
            "B" => Some(BrickType::Blue),
            "O" => Some(BrickType::Orange),
            _ => None,
        }
    }

    /// Length along the wall (m).
    pub fn length(self) -> f64 {
        f64::from(self.units()) * UNIT_LENGTH
    }

    /// Length in units of 0.30 m.
    pub fn units(self) -> u32 {
        match self {
            BrickType::Red => 1,
            BrickType::Green => 2,
            BrickType::Blue => 4,
            BrickType::Orange => 6,
        }
    }

    /// How many UAVs carry one brick of this type.
    pub fn uavs_needed(self) -> u32 {
        match self {
            BrickType::Orange => 2,
            _ => 1,
        }
    }

    /// Default reward (CMCP's planner configuration).
    pub fn default_reward(self) -> f64 {
        match self {
            BrickType::Red => 1.0,
            BrickType::Green => 2.0,
            BrickType::Blue => 4.0,
            BrickType::Orange => 6.0,
        }
    }
}

impl fmt::Display for BrickType {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// Dense index of a brick inside one [`crate::Wall`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
pub struct BrickId(pub u32);

impl BrickId {
    /// The index as `usize`.
    pub fn index(self) -> usize {
        self.0 as usize
    }
}

/// Axis-aligned rectangle seen from above (m): `x` along the wall, `y` across it.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Footprint {
    /// Left edge.
    pub x0: f64,
    /// Right edge.
    pub x1: f64,
    /// Front edge.
    pub y0: f64,
    /// Back edge.
    pub y1: f64,
}

impl Footprint {
    /// Overlap of the x intervals (negative: the gap).
    pub fn x_overlap(&self, other: &Footprint) -> f64 {
        self.x1.min(other.x1) - self.x0.max(other.x0)
    }

    /// Overlap of the y intervals (negative: the gap).
    pub fn y_overlap(&self, other: &Footprint) -> f64 {
        self.y1.min(other.y1) - self.y0.max(other.y0)
    }

    /// True when the two rectangles share an area of more than 1 mm each way.
    pub fn overlaps(&self, other: &Footprint) -> bool {
        self.x_overlap(other) > OVERLAP_EPS && self.y_overlap(other) > OVERLAP_EPS
    }

    /// True when the rectangles face each other across a gap of at most
    /// [`NEIGHBOUR_GAP`], overlapping by more than 1 mm across that gap.
    pub fn faces(&self, other: &Footprint) -> bool {
        let (xo, yo) = (self.x_overlap(other), self.y_overlap(other));
        (yo > OVERLAP_EPS && xo >= -NEIGHBOUR_GAP - 1e-9)
            || (xo > OVERLAP_EPS && yo >= -NEIGHBOUR_GAP - 1e-9)
    }
}

/// Where a brick came from in its input, for error messages.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Origin {
    /// Built in code.
    None,
    /// A line of a text file (1-based).
    Line(usize),
    /// A pixel of an image (column, row).
    Pixel(u32, u32),
}

/// One brick of a wall.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Brick {
    /// Display id: the thesis id `100·l + p`, or the CMCP file's own id.
    pub label: u32,
    /// Colour.
    #[serde(rename = "type")]
    pub kind: BrickType,
    /// Level, 1 for the bottom layer.
    pub level: u32,
    /// Wall segment, 1-based; segments never support each other.
    pub segment: u32,
    /// Footprint seen from above.
    pub footprint: Footprint,
    /// Where the brick was read from.
    #[serde(skip)]
    pub origin: Origin,
}
