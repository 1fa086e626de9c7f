//! Mason reports: figures drawn from plain data, returned as strings. No I/O.
//!
//! ```
//! let wall = mason_wall::parse_layer_text("R G\nB R R", "example").unwrap();
//! let svg = mason_report::wall_svg(&wall, None);
//! assert!(svg.starts_with("<svg"));
//! ```
#![deny(missing_docs)]

mod crew_svg;
mod svg;
mod wall_svg;

pub use crew_svg::crew_svg;
pub use svg::{escape, robot_colour};
pub use wall_svg::wall_svg;
