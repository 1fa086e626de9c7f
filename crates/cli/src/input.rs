//! Reading designs and models from files (the only place the CLI touches input files).

use crate::fail::{input_error, CliResult};
use clap::ValueEnum;
use mason_order::CostModel;
use mason_wall::{
    builtin, looks_like_cmcp, parse_cmcp, parse_cmcp_strict, parse_layer_text, parse_mbzirc,
    read_png, CmcpSizes, Wall, BUILTIN_WALLS,
};
use std::io::Read;
use std::path::Path;

/// The largest design, map, scenario or image file read, in bytes (64 MiB).
pub const MAX_INPUT_BYTES: u64 = 64 << 20;
/// The largest TOML file read (model, faults, mission), in bytes (1 MiB).
pub const MAX_TOML_BYTES: u64 = 1 << 20;

/// Reads a whole input file: only a regular file (never a FIFO, device or folder, which could
/// block or never end) of at most `limit` bytes, checked before anything is allocated and again
/// while reading. A leading UTF-8 byte-order mark is dropped. Every file the CLI reads comes
/// through here.
pub fn read_input(path: &Path, limit: u64) -> CliResult<Vec<u8>> {
    let shown = path.display();
    let fail = |e: std::io::Error| input_error(format!("{shown}: {e}"));
    let too_big = || {
        input_error(format!(
            "{shown}: larger than {limit} bytes, the limit for this input (mason_cli::input::MAX_*_BYTES)"
        ))
    };
    let meta = std::fs::metadata(path).map_err(fail)?;
    if !meta.is_file() {
        let kind = if meta.is_dir() {
            "a folder"
        } else {
            "not a regular file (a FIFO, socket or device)"
        };
        return Err(input_error(format!("{shown}: {kind}; give a file")));
    }
    if meta.len() > limit {
        return Err(too_big());
    }
    let file = std::fs::File::open(path).map_err(fail)?;
    let mut bytes = Vec::with_capacity(meta.len() as usize);
    file.take(limit + 1).read_to_end(&mut bytes).map_err(fail)?;
    if bytes.len() as u64 > limit {
        return Err(too_big());
    }
    if bytes.starts_with(b"\xEF\xBB\xBF") {
        bytes.drain(..3);
    }
    Ok(bytes)
}

/// [`read_input`] as UTF-8 text.
pub fn read_input_text(path: &Path, limit: u64) -> CliResult<String> {
    String::from_utf8(read_input(path, limit)?).map_err(|e| {
        input_error(format!(
            "{}: not UTF-8 text (byte {})",
            path.display(),
            e.utf8_error().valid_up_to()
        ))
    })
}

/// How to read a design file.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
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
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub enum Sizes {
    /// CMCP's planner.yaml (green 0.60 m, blue 1.20 m).
    Yaml,
    /// Green and blue swapped, as the `wall_*_multi` files were drawn.
    Swapped,
}

/// Loads `design`: a path, or `builtin:NAME`. A CMCP wall's warnings (floating bricks,
/// overlapping same-level bricks) go to stderr, or are errors when `strict`.
pub fn load_wall(design: &str, format: Format, sizes: Sizes, strict: bool) -> CliResult<Wall> {
    if let Some(name) = design.strip_prefix("builtin:") {
        return builtin(name).map(|b| b.wall()).ok_or_else(|| {
            let names: Vec<&str> = BUILTIN_WALLS.iter().map(|b| b.name).collect();
            input_error(format!(
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
        Format::Auto => {
            let text = String::from_utf8_lossy(&bytes);
            if looks_like_cmcp(&text) {
                Format::Cmcp
            } else {
                Format::Text
            }
        }
        f => f,
    };
    let text = || {
        String::from_utf8(bytes.clone()).map_err(|_| {
            input_error(format!(
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
        Format::Text | Format::Auto => parse_layer_text(&text()?, design),
        Format::Mbzirc => parse_mbzirc(&text()?, design),
        Format::Cmcp if strict => parse_cmcp_strict(&text()?, design, cmcp_sizes),
        Format::Cmcp => parse_cmcp(&text()?, design, cmcp_sizes),
    };
    let wall = wall.map_err(|e| input_error(e.to_string()))?;
    if format == Format::Cmcp {
        if let (true, Some(w)) = (strict, wall.warnings().first()) {
            return Err(input_error(format!("{design}: {w} (--strict)")));
        }
        let (overlaps, other): (Vec<&String>, Vec<&String>) = wall
            .warnings()
            .iter()
            .partition(|w| w.contains(" overlap by "));
        match overlaps.as_slice() {
            [] => {}
            [one] => eprintln!("mason: warning: {design}: {one}"),
            [first, ..] => eprintln!(
                "mason: warning: {design}: {} pairs of same-level bricks overlap, e.g. {first} (`mason wall show` lists them)",
                overlaps.len()
            ),
        }
        for w in other {
            eprintln!("mason: warning: {design}: {w}");
        }
    }
    Ok(wall)
}

/// Loads a cost model from TOML, or the defaults.
pub fn load_model(path: Option<&Path>) -> CliResult<CostModel> {
    let Some(path) = path else {
        return Ok(CostModel::default());
    };
    let model: CostModel = read_toml(path)?;
    model
        .validate()
        .map_err(|e| input_error(format!("{}: {e}", path.display())))?;
    Ok(model)
}

/// Reads a TOML file into `T`; errors name the file and the line (exit 2).
pub fn read_toml<T: serde::de::DeserializeOwned>(path: &Path) -> CliResult<T> {
    let shown = path.display();
    let text = read_input_text(path, MAX_TOML_BYTES)?;
    toml::from_str(&text).map_err(|e| {
        let line = e
            .span()
            .map(|s| text[..s.start.min(text.len())].matches('\n').count() + 1);
        // One line: the parser's message may span several.
        let msg = e
            .message()
            .trim()
            .lines()
            .map(str::trim)
            .collect::<Vec<_>>()
            .join("; ");
        match line {
            Some(l) => input_error(format!("{shown}:{l}: {msg}")),
            None => input_error(format!("{shown}: {msg}")),
        }
    })
}
