//! Input limits of the crew readers, checked before anything is allocated for the input.
//!
//! | limit | value | applies to |
//! |---|---|---|
//! | [`MAX_CELLS`] | 16 777 216 (4096²) | MovingAI maps (from the header), occupancy and bird's-eye PNGs (from the image header) |
//! | [`MAX_AGENTS`] | 10 000 | scenario agents taken, robots in a bird's-eye image |

/// The most cells a grid may have.
pub const MAX_CELLS: u64 = 1 << 24;
/// The most agents (robots) an instance may have.
pub const MAX_AGENTS: usize = 10_000;
