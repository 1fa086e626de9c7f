//! Mason walls: bricks, wall designs, their readers, the precedence DAG and neighbours.
//!
//! A [`Wall`] is built from bricks by [`Wall::from_bricks`], which derives the supports of every
//! brick (the precedence DAG) and its neighbours exactly as DESIGN §3 defines them. Readers turn
//! layer text ([`parse_layer_text`]), the MBZIRC 21-token pattern ([`parse_mbzirc`]), images
//! ([`read_png`]) and CMCP 3-D walls ([`parse_cmcp`]) into walls; they take bytes or text, never
//! paths, and report bad input as a [`WallError`] naming the line or pixel.
//!
//! ```
//! use mason_wall::{parse_layer_text, BrickId};
//!
//! let wall = parse_layer_text("R R\nG R", "example").unwrap();
//! // Bottom layer first: G (101), R (102); then R (201), R (202).
//! assert_eq!(wall.brick(BrickId(2)).label, 201);
//! assert_eq!(wall.supports(BrickId(2)), &[BrickId(0)]);          // 201 rests on the green
//! assert_eq!(wall.supports(BrickId(3)), &[BrickId(0)]);          // and so does 202
//! assert_eq!(wall.neighbours(BrickId(0)), &[BrickId(1)]);
//! ```
#![deny(missing_docs)]

mod brick;
mod builtin;
mod cmcp;
mod decode;
mod error;
pub mod generate;
pub mod limits;
mod png;
mod raster;
pub mod stop;
pub mod structure;
mod text;
pub mod violations;
mod wall;

pub use brick::{
    Brick, BrickId, BrickType, Footprint, Origin, BRICK_DEPTH, BRICK_HEIGHT, NEIGHBOUR_GAP,
    OVERLAP_EPS, UNIT_LENGTH,
};
pub use builtin::{builtin, BuiltinWall, BUILTIN_WALLS};
pub use cmcp::{looks_like_cmcp, parse_cmcp, parse_cmcp_strict, CmcpSizes};
pub use decode::{decode_png_rgb, PngDecodeError};
pub use error::{Location, WallError, WallErrorKind};
pub use png::{classify_pixel, read_image, read_png, MAX_PIXELS};
pub use raster::{brick_rgb, render, RasterStyle};
pub use text::{parse_layer_text, parse_mbzirc, to_layer_text};
pub use wall::Wall;
