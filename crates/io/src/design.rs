//! Wall designs: a path (layer text, MBZIRC, PNG or CMCP, by `--format` or by extension and
//! content) or `builtin:NAME`.

use crate::error::{InputError, InputResult};
use crate::files::{read_input, MAX_INPUT_BYTES};
use mason_wall::{
    builtin, looks_like_cmcp, parse_cmcp, parse_cmcp_strict, parse_layer_text, parse_mbzirc,
    read_png, CmcpSizes, Wall, BUILTIN_WALLS,
};
use std::path::Path;

/// How to read a design file.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
pub enum Format {
    /// By extension and content: `.png` image, CMCP if lines have 6 numbers, else layer text.
    Auto,
    /// Layer text.
    Text,
    /// MBZIRC 21-token pattern.
    Mbzirc,
    /// PNG image.
    Png,
    /// CMCP `id type x y z yaw_rotated`.
    Cmcp,
}

/// CMCP size table.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
#[cfg_attr(feature = "clap", derive(clap::ValueEnum))]
pub enum Sizes {
    /// CMCP's planner.yaml (green 0.60 m, blue 1.20 m).
    Yaml,
    /// Green and blue swapped, as the `wall_*_multi` files were drawn.
    Swapped,
}

/// A wall read from a design, with the warnings a person should see (one line each).
#[derive(Clone, Debug)]
pub struct LoadedWall {
    /// The wall.
    pub wall: Wall,
    /// Warnings, already summarised: a CMCP wall's floating bricks, and its overlapping
    /// same-level bricks (one line for all of them).
    pub warnings: Vec<String>,
}

/// Loads `design`: a path, or `builtin:NAME`. A CMCP wall's warnings (floating bricks,
/// overlapping same-level bricks) come back with it, or are errors when `strict`.
pub fn load_wall(
    design: &str,
    format: Format,
    sizes: Sizes,
    strict: bool,
) -> InputResult<LoadedWall> {
    if let Some(name) = design.strip_prefix("builtin:") {
        return builtin(name)
            .map(|b| LoadedWall {
                wall: b.wall(),
                warnings: Vec::new(),
            })
            .ok_or_else(|| {
                let names: Vec<&str> = BUILTIN_WALLS.iter().map(|b| b.name).collect();
                InputError::bad(format!(
                    "{design}: no such built-in wall (built-in walls: {})",
                    names.join(", ")
                ))
            });
    }
    let path = Path::new(design);
    let bytes = read_input(path, MAX_INPUT_BYTES)?;
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    let format = match format {
        Format::Auto if ext.as_deref() == Some("png") => Format::Png,
        Format::Auto if looks_like_cmcp(&String::from_utf8_lossy(&bytes)) => Format::Cmcp,
        Format::Auto => Format::Text,
        f => f,
    };
    let text = || {
        std::str::from_utf8(&bytes).map_err(|_| {
            InputError::bad(format!(
                "{design}: not UTF-8 text (is it an image? use --format png)"
            ))
        })
    };
    let cmcp_sizes = match sizes {
        Sizes::Yaml => CmcpSizes::Yaml,
        Sizes::Swapped => CmcpSizes::Swapped,
    };
    let wall = match format {
        Format::Png => read_png(&bytes, design),
        Format::Text | Format::Auto => parse_layer_text(text()?, design),
        Format::Mbzirc => parse_mbzirc(text()?, design),
        Format::Cmcp if strict => parse_cmcp_strict(text()?, design, cmcp_sizes),
        Format::Cmcp => parse_cmcp(text()?, design, cmcp_sizes),
    }
    .map_err(|e| InputError::bad(e.to_string()))?;
    let mut warnings = Vec::new();
    if format == Format::Cmcp {
        if let (true, Some(w)) = (strict, wall.warnings().first()) {
            return Err(InputError::bad(format!("{design}: {w} (--strict)")));
        }
        let (overlaps, other): (Vec<&String>, Vec<&String>) =
            wall.warnings().iter().partition(|w| w.contains(" overlap"));
        match (wall.overlapping_pairs(), overlaps.first()) {
            (0, _) | (_, None) => {}
            (1, Some(one)) => warnings.push(format!("{design}: {one}")),
            (n, Some(first)) => warnings.push(format!(
                "{design}: {n} pairs of same-level bricks overlap, e.g. {first} (`mason wall show` lists them)"
            )),
        }
        warnings.extend(other.iter().map(|w| format!("{design}: {w}")));
    }
    Ok(LoadedWall { wall, warnings })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_unknown_builtin_lists_the_known_ones() {
        let e = load_wall("builtin:nope", Format::Auto, Sizes::Yaml, false)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("builtin:nope") && e.contains("thesis-2x5"),
            "{e}"
        );
    }

    #[test]
    fn a_design_is_read_by_its_content() {
        let dir = std::env::temp_dir().join(format!("mason-input-design-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let text = dir.join("w.txt");
        std::fs::write(&text, "R R\nG G\n").unwrap();
        let w = load_wall(text.to_str().unwrap(), Format::Auto, Sizes::Yaml, false).unwrap();
        assert_eq!(w.wall.len(), 4);
        let cmcp = dir.join("c.txt");
        std::fs::write(&cmcp, "1 1 0 0 0.1 0\n2 1 1 0 0.1 0\n").unwrap();
        let w = load_wall(cmcp.to_str().unwrap(), Format::Auto, Sizes::Yaml, false).unwrap();
        assert_eq!(w.wall.len(), 2);
        let e = load_wall(text.to_str().unwrap(), Format::Png, Sizes::Yaml, false).unwrap_err();
        assert!(e.to_string().contains("w.txt"), "{e}");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
