//! Input limits of the wall readers: every reader checks them before it allocates for the
//! input, and a larger input is a [`WallErrorKind::TooLarge`](crate::WallErrorKind) error
//! naming the limit.
//!
//! | limit | value | applies to |
//! |---|---|---|
//! | [`MAX_BRICKS`] | 1 000 000 | every wall |
//! | [`MAX_LAYERS`] | 1 000 | layer text and MBZIRC (lines holding bricks) |
//! | [`MAX_LINE_CHARS`] | 100 000 | layer text, MBZIRC and CMCP (characters per line) |
//! | [`MAX_COORD_M`] | 100 000 m | CMCP `x` and `y` |
//! | [`MAX_PAIRS`] | 4 000 000 | supports, neighbours and overlaps of a wall, together |
//! | [`MAX_OVERLAP_WARNINGS`] | 1 000 | overlapping same-level pairs listed (the rest counted) |
//! | [`MAX_PIXELS`](crate::MAX_PIXELS) | 50 000 000 | PNG images (checked from the header) |

/// The most bricks a wall may have.
pub const MAX_BRICKS: usize = 1_000_000;
/// The most layers (non-empty lines) of a layer-text or MBZIRC wall.
pub const MAX_LAYERS: usize = 1_000;
/// The longest line of a text input, in characters.
pub const MAX_LINE_CHARS: usize = 100_000;
/// The largest |x| or |y| of a CMCP brick, in metres.
pub const MAX_COORD_M: f64 = 100_000.0;
/// The most brick pairs a wall may relate (supports, neighbours, same-level overlaps): a real
/// wall has a few per brick; bricks piled on each other by the thousand would make every later
/// step quadratic.
pub const MAX_PAIRS: usize = 4_000_000;
/// The most overlapping same-level pairs listed one by one in [`crate::Wall::warnings`]; the
/// rest are counted ([`crate::Wall::overlapping_pairs`]).
pub const MAX_OVERLAP_WARNINGS: usize = 1_000;
/// How much of a bad token or line an error message shows, in characters.
pub const SHOWN_CHARS: usize = 80;

/// `s` cut to [`SHOWN_CHARS`] characters, with `…` and the full length when it was longer.
pub fn shown(s: &str) -> String {
    let n = s.chars().count();
    if n <= SHOWN_CHARS {
        return s.to_string();
    }
    let head: String = s.chars().take(SHOWN_CHARS).collect();
    format!("{head}… ({n} characters)")
}
