//! Input limits of the crew readers, checked before anything is allocated for the input.
//!
//! | limit | value | applies to |
//! |---|---|---|
//! | [`MAX_CELLS`] | 16 777 216 (4096²) | MovingAI maps (from the header), occupancy and bird's-eye PNGs (from the image header) |
//! | [`MAX_AGENTS`] | 10 000 | scenario agents taken, robots in a bird's-eye image |
//! | [`MAX_AGENT_CELLS`] | 250 000 000 | robots × free cells (one distance table per robot and goal) |

/// The most cells a grid may have.
pub const MAX_CELLS: u64 = 1 << 24;
/// The most agents (robots) an instance may have.
pub const MAX_AGENTS: usize = 10_000;
/// The most robots × free cells an instance may have: the assignment and the paths keep a
/// distance table over the grid per robot and goal, so this bounds their memory (about 1 GB of
/// 4-byte distances; a 450×450 bird's-eye picture with 1000 robots is 146 000 000).
pub const MAX_AGENT_CELLS: u64 = 250_000_000;
