//! Errors of the wall readers, with the place in the input they refer to.

use crate::brick::BrickType;
use std::fmt;
use thiserror::Error;

/// A place in an input.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Location {
    /// The input as a whole.
    Whole,
    /// A 1-based line number.
    Line(usize),
    /// A pixel (column, row).
    Pixel(u32, u32),
}

/// What is wrong with a wall input.
#[derive(Clone, Debug, PartialEq, Error)]
pub enum WallErrorKind {
    /// A token that is not `R G B O . |`.
    #[error("unknown token `{token}` (expected R, G, B, O, `.` or `|`)")]
    UnknownToken {
        /// The offending token.
        token: String,
    },
    /// A brick above level 1 without support.
    #[error("floating brick {label} ({kind}) on level {level}: nothing below it in its segment")]
    FloatingBrick {
        /// Display id.
        label: u32,
        /// Colour.
        kind: BrickType,
        /// Level.
        level: u32,
    },
    /// No bricks at all.
    #[error("the wall has no bricks")]
    Empty,
    /// An MBZIRC pattern line without 21 tokens.
    #[error("an MBZIRC pattern line needs 21 tokens (3 segments of 7), found {found}")]
    MbzircTokenCount {
        /// Tokens found.
        found: usize,
    },
    /// `|` is not allowed in MBZIRC pattern lines.
    #[error("`{token}` is not allowed in an MBZIRC pattern (tokens are R, G, B, O)")]
    MbzircToken {
        /// The token.
        token: String,
    },
    /// A CMCP line with the wrong number of fields.
    #[error("a CMCP brick line needs 6 fields `id type x y z yaw_rotated`, found {found}")]
    FieldCount {
        /// Fields found.
        found: usize,
    },
    /// A field that does not parse.
    #[error("field `{field}` is `{value}`, which is not {expected}")]
    BadField {
        /// Field name.
        field: &'static str,
        /// Raw value.
        value: String,
        /// What was expected.
        expected: &'static str,
    },
    /// An unknown CMCP type id.
    #[error("unknown brick type {value} (expected 1 red, 2 green, 3 blue, 4 orange)")]
    UnknownType {
        /// The id.
        value: i64,
    },
    /// A CMCP id given twice.
    #[error("brick id {id} appears twice (first on line {first_line})")]
    DuplicateId {
        /// The id.
        id: u32,
        /// Line of the first use.
        first_line: usize,
    },
    /// A CMCP z that is not on a layer.
    #[error("z = {z} m is not on a layer (expected 0.1 + 0.2·k)")]
    OffLayer {
        /// The z value.
        z: f64,
    },
    /// An input over one of the [`limits`](crate::limits).
    #[error("more than {limit} {what} (the limit of mason_wall::limits::{name})")]
    TooLarge {
        /// What is counted, e.g. `bricks`.
        what: &'static str,
        /// The limit.
        limit: u64,
        /// The constant's name in [`limits`](crate::limits).
        name: &'static str,
    },
    /// The image could not be decoded.
    #[error("cannot decode the image: {reason}")]
    ImageDecode {
        /// Decoder message.
        reason: String,
    },
    /// The image holds no brick colours.
    #[error("no brick colours found in the image")]
    NoBricksInImage,
    /// A brick whose pixel length fits no colour.
    #[error("{kind} brick is {measured:.2} m long ({pixels} px at {unit:.1} px per 0.30 m); {kind} bricks are {expected:.2} m")]
    LengthMismatch {
        /// Colour read.
        kind: BrickType,
        /// Length measured (m).
        measured: f64,
        /// Length in pixels.
        pixels: u32,
        /// Pixels per 0.30 m.
        unit: f64,
        /// Length of the colour (m).
        expected: f64,
    },
    /// A band of the image that is too thin or irregular to be a layer.
    #[error("{reason}")]
    ImageLayout {
        /// What is wrong.
        reason: String,
    },
}

/// A wall input error: the input's name, the place, and what is wrong.
#[derive(Clone, Debug, PartialEq, Error)]
pub struct WallError {
    /// Name of the input (usually the file path).
    pub source_name: String,
    /// Where in the input.
    pub location: Location,
    /// What is wrong.
    pub kind: WallErrorKind,
}

impl WallError {
    /// A new error.
    pub fn new(source_name: &str, location: Location, kind: WallErrorKind) -> Self {
        WallError {
            source_name: source_name.to_string(),
            location,
            kind,
        }
    }
}

impl fmt::Display for WallError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.location {
            Location::Whole => write!(f, "{}: {}", self.source_name, self.kind),
            Location::Line(l) => write!(f, "{}:{}: {}", self.source_name, l, self.kind),
            Location::Pixel(x, y) => {
                write!(
                    f,
                    "{}: pixel ({}, {}): {}",
                    self.source_name, x, y, self.kind
                )
            }
        }
    }
}
