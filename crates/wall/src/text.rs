//! Layer-text walls (`.txt`, `.wall`) and the MBZIRC 21-token pattern.
//!
//! Each line is one layer, the top line the top layer. Tokens `R G B O` are bricks laid end to
//! end from the left, `.` is an empty 0.30 m slot, `|` starts a new segment and `#` starts a
//! comment. Tokens are separated by white space; a run such as `RGB.|R` is read one token per
//! character. Segment `s` starts 0.30 m to the right of the widest layer of segment `s − 1`.

use crate::brick::{Brick, BrickType, Footprint, Origin, BRICK_DEPTH, UNIT_LENGTH};
use crate::error::{Location, WallError, WallErrorKind};
use crate::limits::{shown, MAX_BRICKS, MAX_LAYERS, MAX_LINE_CHARS};
use crate::wall::Wall;

#[derive(Clone, Copy, Debug, PartialEq)]
enum Token {
    Brick(BrickType),
    Empty,
    Segment,
}

fn token_of(raw: &str) -> Option<Token> {
    match raw {
        "." => Some(Token::Empty),
        "|" => Some(Token::Segment),
        _ => BrickType::from_token(&raw.to_ascii_uppercase()).map(Token::Brick),
    }
}

/// Splits one line into tokens; compact runs like `RG.B` are read per character.
fn tokens_of(line: &str) -> Result<Vec<Token>, String> {
    let mut out = Vec::new();
    for word in line.split_whitespace() {
        if let Some(t) = token_of(word) {
            out.push(t);
            continue;
        }
        let chars: Option<Vec<Token>> = word
            .chars()
            .map(|c| token_of(c.encode_utf8(&mut [0; 4])))
            .collect();
        match chars {
            Some(ts) => out.extend(ts),
            None => return Err(shown(&word.escape_debug().to_string())),
        }
    }
    Ok(out)
}

/// One layer: its line number and its segments, each a list of tokens (bricks and gaps).
struct Layer {
    line: usize,
    segments: Vec<Vec<Token>>,
}

fn strip_comment(line: &str) -> &str {
    line.split('#').next().unwrap_or("").trim()
}

/// A too-large input at line `line`.
pub(crate) fn too_large(
    name: &str,
    line: usize,
    what: &'static str,
    limit: usize,
    limit_name: &'static str,
) -> WallError {
    WallError::new(
        name,
        Location::Line(line),
        WallErrorKind::TooLarge {
            what,
            limit: limit as u64,
            name: limit_name,
        },
    )
}

/// `src` without a leading byte-order mark.
pub(crate) fn without_bom(src: &str) -> &str {
    src.strip_prefix('\u{feff}').unwrap_or(src)
}

/// Refuses a line over [`MAX_LINE_CHARS`] characters.
pub(crate) fn check_line(name: &str, line: usize, raw: &str) -> Result<(), WallError> {
    if raw.len() > MAX_LINE_CHARS && raw.chars().count() > MAX_LINE_CHARS {
        return Err(too_large(
            name,
            line,
            "characters on a line",
            MAX_LINE_CHARS,
            "MAX_LINE_CHARS",
        ));
    }
    Ok(())
}

fn read_layers(src: &str, name: &str) -> Result<Vec<Layer>, WallError> {
    let mut layers = Vec::new();
    let mut bricks = 0usize;
    for (i, raw) in without_bom(src).lines().enumerate() {
        check_line(name, i + 1, raw)?;
        let body = strip_comment(raw);
        if body.is_empty() {
            continue;
        }
        if layers.len() == MAX_LAYERS {
            return Err(too_large(name, i + 1, "layers", MAX_LAYERS, "MAX_LAYERS"));
        }
        let tokens = tokens_of(body).map_err(|token| {
            WallError::new(
                name,
                Location::Line(i + 1),
                WallErrorKind::UnknownToken { token },
            )
        })?;
        bricks += tokens
            .iter()
            .filter(|t| matches!(t, Token::Brick(_)))
            .count();
        if bricks > MAX_BRICKS {
            return Err(too_large(name, i + 1, "bricks", MAX_BRICKS, "MAX_BRICKS"));
        }
        let segments = tokens
            .split(|t| *t == Token::Segment)
            .map(|s| s.to_vec())
            .collect();
        layers.push(Layer {
            line: i + 1,
            segments,
        });
    }
    Ok(layers)
}

fn units_of(tokens: &[Token]) -> u32 {
    tokens
        .iter()
        .map(|t| match t {
            Token::Brick(k) => k.units(),
            _ => 1,
        })
        .sum()
}

/// Thesis label multiplier: 100, or the next power of ten above the widest layer.
pub(crate) fn label_base(max_bricks_per_layer: usize) -> u32 {
    let mut base = 100u32;
    while (base as usize) <= max_bricks_per_layer {
        base = base.saturating_mul(10);
    }
    base
}

fn build(name: &str, layers: Vec<Layer>) -> Result<Wall, WallError> {
    let segment_count = layers.iter().map(|l| l.segments.len()).max().unwrap_or(0);
    let mut origins = Vec::with_capacity(segment_count);
    let mut next = 0u32;
    for s in 0..segment_count {
        origins.push(next);
        let width = layers
            .iter()
            .filter_map(|l| l.segments.get(s))
            .map(|t| units_of(t))
            .max()
            .unwrap_or(0);
        next += width + 1;
    }
    let bricks_in = |l: &Layer| {
        l.segments
            .iter()
            .flatten()
            .filter(|t| matches!(t, Token::Brick(_)))
            .count()
    };
    let base = label_base(layers.iter().map(bricks_in).max().unwrap_or(0));
    let n_levels = layers.len() as u32;
    let mut bricks = Vec::new();
    // Bottom layer first, so dense indices run level by level, left to right.
    for (depth, layer) in layers.iter().rev().enumerate() {
        let level = depth as u32 + 1;
        debug_assert!(level <= n_levels);
        let mut position = 0u32;
        for (s, tokens) in layer.segments.iter().enumerate() {
            let mut x = origins[s];
            for t in tokens {
                match t {
                    Token::Brick(kind) => {
                        position += 1;
                        bricks.push(Brick {
                            label: base * level + position,
                            kind: *kind,
                            level,
                            segment: s as u32 + 1,
                            footprint: Footprint {
                                x0: f64::from(x) * UNIT_LENGTH,
                                x1: f64::from(x + kind.units()) * UNIT_LENGTH,
                                y0: 0.0,
                                y1: BRICK_DEPTH,
                            },
                            origin: Origin::Line(layer.line),
                        });
                        x += kind.units();
                    }
                    _ => x += 1,
                }
            }
        }
    }
    Wall::from_bricks(name, bricks)
}

/// Reads a layer-text wall. `name` labels errors (normally the file path).
///
/// ```
/// let wall = mason_wall::parse_layer_text("R G\nB", "doc").unwrap();
/// assert_eq!(wall.len(), 3);
/// assert_eq!(wall.brick(mason_wall::BrickId(1)).label, 201);
/// ```
pub fn parse_layer_text(src: &str, name: &str) -> Result<Wall, WallError> {
    build(name, read_layers(src, name)?)
}

/// Number of tokens in an MBZIRC pattern line.
pub const MBZIRC_TOKENS: usize = 21;
/// Bricks per segment in an MBZIRC pattern.
pub const MBZIRC_SEGMENT: usize = 7;

/// Reads the MBZIRC pattern: each line holds 21 brick tokens, 3 segments of 7 bricks.
pub fn parse_mbzirc(src: &str, name: &str) -> Result<Wall, WallError> {
    let mut layers = read_layers(src, name)?;
    for layer in &mut layers {
        let at = |kind| WallError::new(name, Location::Line(layer.line), kind);
        if layer.segments.len() > 1 {
            return Err(at(WallErrorKind::MbzircToken { token: "|".into() }));
        }
        let tokens = layer.segments.pop().unwrap_or_default();
        if tokens.contains(&Token::Empty) {
            return Err(at(WallErrorKind::MbzircToken { token: ".".into() }));
        }
        if tokens.len() != MBZIRC_TOKENS {
            return Err(at(WallErrorKind::MbzircTokenCount {
                found: tokens.len(),
            }));
        }
        layer.segments = tokens.chunks(MBZIRC_SEGMENT).map(|c| c.to_vec()).collect();
    }
    build(name, layers)
}

/// Writes a wall built from layer text back as layer text (one line per level, top first).
///
/// Works for any wall whose bricks lie on the 0.30 m grid along x; other walls (CMCP) are
/// written with their bricks end to end.
pub fn to_layer_text(wall: &Wall) -> String {
    let mut out = String::new();
    for level in (1..=wall.levels()).rev() {
        let mut row: Vec<&crate::Brick> =
            wall.bricks().iter().filter(|b| b.level == level).collect();
        row.sort_by(|a, b| {
            (a.segment, a.footprint.x0)
                .partial_cmp(&(b.segment, b.footprint.x0))
                .unwrap_or(std::cmp::Ordering::Equal)
        });
        let mut words: Vec<String> = Vec::new();
        let mut segment = 1;
        let mut cursor = segment_origin(wall, 1);
        for b in row {
            while segment < b.segment {
                segment += 1;
                words.push("|".into());
                cursor = segment_origin(wall, segment);
            }
            let gap = ((b.footprint.x0 - cursor) / UNIT_LENGTH).round();
            for _ in 0..(gap.max(0.0) as usize) {
                words.push(".".into());
            }
            words.push(b.kind.token().to_string());
            cursor = b.footprint.x1;
        }
        out.push_str(&words.join(" "));
        out.push('\n');
    }
    out
}

fn segment_origin(wall: &Wall, segment: u32) -> f64 {
    wall.bricks()
        .iter()
        .filter(|b| b.segment == segment)
        .map(|b| b.footprint.x0)
        .fold(f64::INFINITY, f64::min)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::BrickId;

    fn kind_of(e: WallError) -> (Location, WallErrorKind) {
        (e.location, e.kind)
    }

    #[test]
    fn layers_are_read_top_line_first() {
        let w = parse_layer_text("# a wall\nR G\nB R R\n", "t").unwrap();
        assert_eq!(w.levels(), 2);
        let labels: Vec<u32> = w.bricks().iter().map(|b| b.label).collect();
        assert_eq!(labels, vec![101, 102, 103, 201, 202]);
        assert_eq!(w.brick(BrickId(0)).kind, BrickType::Blue);
        // 201 (R, 0–0.3) rests on the blue; 202 (G, 0.3–0.9) also on the blue only.
        assert_eq!(w.supports(BrickId(3)), &[BrickId(0)]);
        assert_eq!(w.supports(BrickId(4)), &[BrickId(0)]);
    }

    #[test]
    fn brick_spanning_two_supports_needs_both() {
        let w = parse_layer_text("G\nR R", "t").unwrap();
        assert_eq!(w.supports(BrickId(2)), &[BrickId(0), BrickId(1)]);
    }

    #[test]
    fn touching_by_less_than_a_millimetre_is_no_support() {
        // The top red covers 0.3–0.6; below, a red at 0–0.3 and a gap: floating.
        let e = parse_layer_text(". R\nR", "t").unwrap_err();
        assert!(matches!(
            e.kind,
            WallErrorKind::FloatingBrick { label: 201, .. }
        ));
        assert_eq!(e.location, Location::Line(1));
    }

    #[test]
    fn empty_slots_break_neighbourhood() {
        let w = parse_layer_text("R . R R", "t").unwrap();
        assert!(w.neighbours(BrickId(0)).is_empty());
        assert_eq!(w.neighbours(BrickId(1)), &[BrickId(2)]);
    }

    #[test]
    fn segments_never_support_or_neighbour_each_other() {
        let w = parse_layer_text("R | R\nR | R", "t").unwrap();
        assert_eq!(w.brick(BrickId(1)).segment, 2);
        assert!(w.neighbours(BrickId(0)).is_empty());
        assert_eq!(w.supports(BrickId(2)), &[BrickId(0)]);
        assert_eq!(w.supports(BrickId(3)), &[BrickId(1)]);
        assert_eq!(w.brick(BrickId(3)).label, 202);
    }

    #[test]
    fn compact_tokens_and_lower_case_are_read() {
        let a = parse_layer_text("RG.b|o", "t").unwrap();
        let b = parse_layer_text("R G . B | O", "t").unwrap();
        assert_eq!(a.bricks(), b.bricks());
    }

    #[test]
    fn unknown_token_names_line_and_token() {
        let (loc, kind) = kind_of(parse_layer_text("R G\nR X R\n", "t").unwrap_err());
        assert_eq!(loc, Location::Line(2));
        assert_eq!(kind, WallErrorKind::UnknownToken { token: "X".into() });
        let msg = parse_layer_text("R\nR Q", "walls/a.txt")
            .unwrap_err()
            .to_string();
        assert_eq!(
            msg,
            "walls/a.txt:2: unknown token `Q` (expected R, G, B, O, `.` or `|`)"
        );
    }

    #[test]
    fn empty_inputs_are_errors() {
        for src in ["", "# only a comment\n\n", ". . .\n"] {
            let e = parse_layer_text(src, "t").unwrap_err();
            assert_eq!(e.kind, WallErrorKind::Empty, "{src:?}");
        }
    }

    #[test]
    fn floating_brick_above_gap_is_reported_on_its_line() {
        let e = parse_layer_text("R R R\n\nR . R\n", "t").unwrap_err();
        assert_eq!(e.location, Location::Line(1));
        assert!(matches!(
            e.kind,
            WallErrorKind::FloatingBrick {
                level: 2,
                label: 202,
                ..
            }
        ));
    }

    #[test]
    fn mbzirc_reads_three_segments_of_seven() {
        let line = "R G B G R R G  G R B R G R R  R B G G R R G";
        let w = parse_mbzirc(line, "t").unwrap();
        assert_eq!(w.len(), 21);
        let segs: Vec<u32> = w.bricks().iter().map(|b| b.segment).collect();
        assert_eq!(&segs[5..9], &[1, 1, 2, 2]);
        assert_eq!(w.brick(BrickId(20)).label, 121);
    }

    #[test]
    fn mbzirc_rejects_wrong_counts_and_tokens() {
        let e = parse_mbzirc("R R R", "t").unwrap_err();
        assert_eq!(e.kind, WallErrorKind::MbzircTokenCount { found: 3 });
        let e = parse_mbzirc(&"R . ".repeat(11), "t").unwrap_err();
        assert!(matches!(e.kind, WallErrorKind::MbzircToken { .. }));
        let e = parse_mbzirc("R | R", "t").unwrap_err();
        assert!(matches!(e.kind, WallErrorKind::MbzircToken { .. }));
    }

    #[test]
    fn wide_layers_get_wider_labels() {
        let w = parse_layer_text(&"R ".repeat(120), "t").unwrap();
        assert_eq!(w.brick(BrickId(0)).label, 1001);
        assert_eq!(w.brick(BrickId(119)).label, 1120);
    }

    #[test]
    fn layer_text_round_trips() {
        let src = "R G . R | B\nG B R G | O\n";
        let w = parse_layer_text(src, "t").unwrap();
        let again = parse_layer_text(&to_layer_text(&w), "t").unwrap();
        assert_eq!(w.bricks(), again.bricks());
    }
}
