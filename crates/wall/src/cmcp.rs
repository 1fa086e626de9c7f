//! CMCP wall files (`id type x y z yaw_rotated`, one brick per line).
//!
//! Sizes come from CMCP's `planner.yaml` by type id: red 0.30 m, green 0.60 m, blue 1.20 m,
//! orange 1.80 m, each 0.20 m deep. The `wall_*_multi` files were drawn with green and blue
//! swapped; [`CmcpSizes::Swapped`] reads them as drawn. Precedence is footprint overlap with
//! positive area; all bricks form one segment and keep the file's ids as labels.

use crate::brick::{Brick, BrickType, Footprint, Origin, BRICK_DEPTH, BRICK_HEIGHT};
use crate::error::{Location, WallError, WallErrorKind};
use crate::limits::{shown, MAX_BRICKS, MAX_COORD_M};
use crate::text::{check_line, too_large, without_bom};
use crate::wall::Wall;
use std::collections::HashMap;

/// Which length table to use for CMCP type ids.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum CmcpSizes {
    /// CMCP's `planner.yaml`: green 0.60 m, blue 1.20 m.
    #[default]
    Yaml,
    /// As the `wall_*_multi` files were drawn: green 1.20 m, blue 0.60 m.
    Swapped,
}

impl CmcpSizes {
    /// Length (m) of a brick of `kind` under this table.
    pub fn length(self, kind: BrickType) -> f64 {
        match (self, kind) {
            (CmcpSizes::Swapped, BrickType::Green) => BrickType::Blue.length(),
            (CmcpSizes::Swapped, BrickType::Blue) => BrickType::Green.length(),
            _ => kind.length(),
        }
    }
}

/// How far a z value may lie from its layer centre (m).
const Z_TOLERANCE: f64 = 0.03;

fn field<T: std::str::FromStr>(
    raw: &str,
    field: &'static str,
    expected: &'static str,
) -> Result<T, WallErrorKind> {
    raw.parse::<T>().map_err(|_| WallErrorKind::BadField {
        field,
        value: shown(raw),
        expected,
    })
}

fn finite(raw: &str, name: &'static str) -> Result<f64, WallErrorKind> {
    let v: f64 = field(raw, name, "a number")?;
    if v.is_finite() && v.abs() <= MAX_COORD_M {
        Ok(v)
    } else {
        Err(WallErrorKind::BadField {
            field: name,
            value: shown(raw),
            expected: "a number of metres within ±100000 (mason_wall::limits::MAX_COORD_M)",
        })
    }
}

fn parse_line(fields: &[&str], sizes: CmcpSizes) -> Result<(u32, Brick), WallErrorKind> {
    if fields.len() != 6 {
        return Err(WallErrorKind::FieldCount {
            found: fields.len(),
        });
    }
    let id: u32 = field(fields[0], "id", "a whole number ≥ 0")?;
    let type_id: i64 = field(fields[1], "type", "a whole number")?;
    let kind = u8::try_from(type_id)
        .ok()
        .and_then(BrickType::from_id)
        .ok_or(WallErrorKind::UnknownType { value: type_id })?;
    let x = finite(fields[2], "x")?;
    let y = finite(fields[3], "y")?;
    let z = finite(fields[4], "z")?;
    let rotated = match fields[5] {
        "0" => false,
        "1" => true,
        other => {
            return Err(WallErrorKind::BadField {
                field: "yaw_rotated",
                value: shown(other),
                expected: "0 or 1",
            })
        }
    };
    let layer = ((z - BRICK_HEIGHT / 2.0) / BRICK_HEIGHT).round();
    if layer < 0.0
        || (z - (BRICK_HEIGHT / 2.0 + layer * BRICK_HEIGHT)).abs() > Z_TOLERANCE
        || layer > 1e6
    {
        return Err(WallErrorKind::OffLayer { z });
    }
    let (half_x, half_y) = if rotated {
        (BRICK_DEPTH / 2.0, sizes.length(kind) / 2.0)
    } else {
        (sizes.length(kind) / 2.0, BRICK_DEPTH / 2.0)
    };
    let brick = Brick {
        label: id,
        kind,
        level: layer as u32 + 1,
        segment: 1,
        footprint: Footprint {
            x0: x - half_x,
            x1: x + half_x,
            y0: y - half_y,
            y1: y + half_y,
        },
        origin: Origin::None,
    };
    Ok((id, brick))
}

/// Reads a CMCP wall. `name` labels errors (normally the file path).
///
/// ```
/// use mason_wall::{parse_cmcp, CmcpSizes};
/// let src = "#brick_id brick_type x y z yaw\n1 2 0 0 0.1 0\n2 1 0 0 0.3 0\n";
/// let wall = parse_cmcp(src, "doc", CmcpSizes::Yaml).unwrap();
/// assert_eq!(wall.supports(mason_wall::BrickId(1)).len(), 1);
/// ```
pub fn parse_cmcp(src: &str, name: &str, sizes: CmcpSizes) -> Result<Wall, WallError> {
    Wall::from_bricks_allowing_floating(name, read_bricks(src, name, sizes)?)
}

/// [`parse_cmcp`] with floating bricks as errors naming their line (`--strict`); overlapping
/// same-level bricks stay in [`Wall::warnings`] for the caller to refuse.
pub fn parse_cmcp_strict(src: &str, name: &str, sizes: CmcpSizes) -> Result<Wall, WallError> {
    Wall::from_bricks(name, read_bricks(src, name, sizes)?)
}

fn read_bricks(src: &str, name: &str, sizes: CmcpSizes) -> Result<Vec<Brick>, WallError> {
    let mut bricks = Vec::new();
    let mut seen: HashMap<u32, usize> = HashMap::new();
    for (i, raw) in without_bom(src).lines().enumerate() {
        check_line(name, i + 1, raw)?;
        let line = raw.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        if bricks.len() == MAX_BRICKS {
            return Err(too_large(name, i + 1, "bricks", MAX_BRICKS, "MAX_BRICKS"));
        }
        let fields: Vec<&str> = line.split_whitespace().collect();
        let at = |kind| WallError::new(name, Location::Line(i + 1), kind);
        let (id, mut brick) = parse_line(&fields, sizes).map_err(at)?;
        if let Some(&first_line) = seen.get(&id) {
            return Err(at(WallErrorKind::DuplicateId { id, first_line }));
        }
        seen.insert(id, i + 1);
        brick.origin = Origin::Line(i + 1);
        bricks.push(brick);
    }
    Ok(bricks)
}

/// True when `src` looks like a CMCP file: its first data line has six numeric fields.
pub fn looks_like_cmcp(src: &str) -> bool {
    without_bom(src)
        .lines()
        .map(str::trim)
        .find(|l| !l.is_empty() && !l.starts_with('#'))
        .map(|l| {
            let f: Vec<&str> = l.split_whitespace().collect();
            f.len() == 6 && f.iter().all(|x| x.parse::<f64>().is_ok())
        })
        .unwrap_or(false)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::BrickId;

    const HEADER: &str =
        "#brick_id brick_type brick_x_pos brick_y_pos brick_z_pos brick_yaw_rotated\r\n";

    #[test]
    fn reads_crlf_and_keeps_ids() {
        let src = format!(
            "{HEADER}1 2 -1.18 3.0 0.1 0\r\n2 2 -0.54 3.0 0.1 0\r\n3 1 -1.33 3.0 0.3 0\r\n\r\n"
        );
        let w = parse_cmcp(&src, "t", CmcpSizes::Yaml).unwrap();
        assert_eq!(w.len(), 3);
        assert_eq!(w.brick(BrickId(2)).label, 3);
        assert_eq!(w.brick(BrickId(2)).level, 2);
        // Red at −1.48..−1.18 overlaps only the first green (−1.48..−0.88).
        assert_eq!(w.supports(BrickId(2)), &[BrickId(0)]);
        // The greens are 0.04 m apart: neighbours.
        assert_eq!(w.neighbours(BrickId(0)), &[BrickId(1)]);
    }

    #[test]
    fn swapped_sizes_change_lengths() {
        let src = "1 2 0 0 0.1 0\n2 3 2 0 0.1 0\n";
        let yaml = parse_cmcp(src, "t", CmcpSizes::Yaml).unwrap();
        let swapped = parse_cmcp(src, "t", CmcpSizes::Swapped).unwrap();
        let len = |w: &Wall, i| {
            let f = w.brick(BrickId(i)).footprint;
            f.x1 - f.x0
        };
        assert!((len(&yaml, 0) - 0.6).abs() < 1e-9);
        assert!((len(&swapped, 0) - 1.2).abs() < 1e-9);
        assert!((len(&swapped, 1) - 0.6).abs() < 1e-9);
    }

    #[test]
    fn rotated_bricks_face_across_their_long_side() {
        // A rotated green (long along y) next to an unrotated red, 0.05 m apart in x.
        let src = "1 2 0.0 0.0 0.1 1\n2 1 0.25 0.0 0.1 0\n";
        let w = parse_cmcp(src, "t", CmcpSizes::Yaml).unwrap();
        assert_eq!(w.neighbours(BrickId(0)), &[BrickId(1)]);
    }

    #[test]
    fn overlapping_same_level_bricks_warn() {
        let src = "1 1 0 0 0.1 0\n2 1 0.2 0 0.1 0\n";
        let w = parse_cmcp(src, "t", CmcpSizes::Yaml).unwrap();
        assert_eq!(w.warnings().len(), 1);
    }

    /// #32: 1 200 bricks in one spot list the first 1 000 overlaps and count the rest, and
    /// 3 000 (4.5 million overlapping pairs) are refused before planning, not listed.
    #[test]
    fn piled_bricks_are_counted_then_refused() {
        let pile = |n: usize| {
            (1..=n)
                .map(|i| format!("{i} 1 0 0 0.1 0\n"))
                .collect::<String>()
        };
        let w = parse_cmcp(&pile(1_200), "t", CmcpSizes::Yaml).unwrap();
        let pairs = 1_200 * 1_199 / 2;
        assert_eq!(w.overlapping_pairs(), pairs);
        assert_eq!(w.warnings().len(), crate::limits::MAX_OVERLAP_WARNINGS + 1);
        assert!(w
            .warnings()
            .last()
            .unwrap()
            .contains(&format!("{} more", pairs - 1_000)));
        let e = parse_cmcp(&pile(3_000), "t", CmcpSizes::Yaml).unwrap_err();
        assert!(
            matches!(
                e.kind,
                WallErrorKind::TooLarge {
                    name: "MAX_PAIRS",
                    ..
                }
            ),
            "{e}"
        );
    }

    #[test]
    fn malformed_lines_are_reported() {
        let cases: &[(&str, WallErrorKind)] = &[
            ("1 2 0 0 0.1\n", WallErrorKind::FieldCount { found: 5 }),
            ("1 7 0 0 0.1 0\n", WallErrorKind::UnknownType { value: 7 }),
            ("1 0 0 0 0.1 0\n", WallErrorKind::UnknownType { value: 0 }),
            (
                "1 2 zero 0 0.1 0\n",
                WallErrorKind::BadField {
                    field: "x",
                    value: "zero".into(),
                    expected: "a number",
                },
            ),
            ("1 2 0 0 0.2 0\n", WallErrorKind::OffLayer { z: 0.2 }),
            (
                "1 2 0 0 0.1 2\n",
                WallErrorKind::BadField {
                    field: "yaw_rotated",
                    value: "2".into(),
                    expected: "0 or 1",
                },
            ),
            (
                "1 2 NaN 0 0.1 0\n",
                WallErrorKind::BadField {
                    field: "x",
                    value: "NaN".into(),
                    expected: "a number of metres within ±100000 (mason_wall::limits::MAX_COORD_M)",
                },
            ),
        ];
        for (src, kind) in cases {
            let e = parse_cmcp(&format!("# h\n{src}"), "t", CmcpSizes::Yaml).unwrap_err();
            assert_eq!(&e.kind, kind, "{src}");
            assert_eq!(e.location, Location::Line(2), "{src}");
        }
        let e = parse_cmcp("1 1 0 0 0.1 0\n1 1 5 0 0.1 0\n", "t", CmcpSizes::Yaml).unwrap_err();
        assert_eq!(
            e.kind,
            WallErrorKind::DuplicateId {
                id: 1,
                first_line: 1
            }
        );
        // A floating brick: planned with no predecessor and one warning; `strict` refuses it.
        let floating = "1 1 0 0 0.1 0\n2 1 5 0 0.3 0\n";
        let w = parse_cmcp(floating, "t", CmcpSizes::Yaml).unwrap();
        assert!(w.supports(BrickId(1)).is_empty());
        assert_eq!(w.warnings().len(), 1);
        assert!(w.warnings()[0].starts_with("1 brick(s)"));
        let e = parse_cmcp_strict(floating, "t", CmcpSizes::Yaml).unwrap_err();
        assert!(matches!(
            e.kind,
            WallErrorKind::FloatingBrick { label: 2, .. }
        ));
        assert_eq!(e.location, Location::Line(2));
    }

    #[test]
    fn sniffing_tells_cmcp_from_layer_text() {
        assert!(looks_like_cmcp("#h\n\n1 2 0 0 0.1 0\n"));
        assert!(!looks_like_cmcp("R G B\n"));
    }
}
