//! Bounded reads of regular files (never a FIFO, device or folder, which could block or never
//! end), UTF-8 text, and TOML whose errors name the file and the line.

use crate::error::{InputError, InputResult};
use std::io::Read;
use std::path::Path;

/// The largest design, map, scenario, image or trace file read, in bytes (64 MiB).
pub const MAX_INPUT_BYTES: u64 = 64 << 20;
/// The largest TOML file read (model, faults, mission, network), in bytes (1 MiB).
pub const MAX_TOML_BYTES: u64 = 1 << 20;

/// Reads a whole input file: only a regular file of at most `limit` bytes, checked before
/// anything is allocated and again while reading. A leading UTF-8 byte-order mark is dropped.
pub fn read_input(path: &Path, limit: u64) -> InputResult<Vec<u8>> {
    let io = |source| InputError::Io {
        path: path.to_path_buf(),
        source,
    };
    let too_big = || InputError::TooLarge {
        path: path.to_path_buf(),
        limit,
    };
    let meta = std::fs::metadata(path).map_err(io)?;
    if !meta.is_file() {
        let kind = if meta.is_dir() {
            "a folder"
        } else {
            "not a regular file (a FIFO, socket or device)"
        };
        return Err(InputError::NotAFile {
            path: path.to_path_buf(),
            kind,
        });
    }
    if meta.len() > limit {
        return Err(too_big());
    }
    let file = std::fs::File::open(path).map_err(io)?;
    let mut bytes = Vec::with_capacity(meta.len() as usize);
    file.take(limit + 1).read_to_end(&mut bytes).map_err(io)?;
    if bytes.len() as u64 > limit {
        return Err(too_big());
    }
    if bytes.starts_with(b"\xEF\xBB\xBF") {
        bytes.drain(..3);
    }
    Ok(bytes)
}

/// [`read_input`] as UTF-8 text.
pub fn read_input_text(path: &Path, limit: u64) -> InputResult<String> {
    String::from_utf8(read_input(path, limit)?).map_err(|e| InputError::NotText {
        path: path.to_path_buf(),
        byte: e.utf8_error().valid_up_to(),
    })
}

/// Parses TOML `text` read from `path` into `T`; errors name the file and the line.
pub fn parse_toml<T: serde::de::DeserializeOwned>(text: &str, path: &Path) -> InputResult<T> {
    let shown = path.display();
    toml::from_str(text).map_err(|e| {
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
            Some(l) => InputError::bad(format!("{shown}:{l}: {msg}")),
            None => InputError::bad(format!("{shown}: {msg}")),
        }
    })
}

/// Reads a TOML file (at most [`MAX_TOML_BYTES`]) into `T`; errors name the file and the line.
pub fn read_toml<T: serde::de::DeserializeOwned>(path: &Path) -> InputResult<T> {
    let text = read_input_text(path, MAX_TOML_BYTES)?;
    parse_toml(&text, path)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> std::path::PathBuf {
        let dir = std::env::temp_dir().join(format!("mason-input-{}-{name}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn a_folder_a_missing_file_and_a_large_file_are_refused_by_name() {
        let dir = scratch("files");
        let e = read_input(&dir, 10).unwrap_err().to_string();
        assert!(e.contains("a folder"), "{e}");
        let missing = dir.join("missing.txt");
        let e = read_input(&missing, 10).unwrap_err().to_string();
        assert!(e.contains("missing.txt"), "{e}");
        let big = dir.join("big.txt");
        std::fs::write(&big, "x".repeat(11)).unwrap();
        let e = read_input(&big, 10).unwrap_err().to_string();
        assert!(e.contains("larger than 10 bytes"), "{e}");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_byte_order_mark_is_dropped_and_bad_utf8_is_named() {
        let dir = scratch("bom");
        let p = dir.join("a.txt");
        std::fs::write(&p, b"\xEF\xBB\xBFR G").unwrap();
        assert_eq!(read_input_text(&p, 100).unwrap(), "R G");
        std::fs::write(&p, b"R \xFF").unwrap();
        let e = read_input_text(&p, 100).unwrap_err().to_string();
        assert!(e.contains("byte 2"), "{e}");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn toml_errors_name_the_line() {
        #[derive(serde::Deserialize, Debug)]
        #[allow(dead_code)]
        struct T {
            a: f64,
        }
        let e = parse_toml::<T>("\n\na = \"x\"\n", Path::new("m.toml"))
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("m.toml:3:"), "{e}");
        assert!(!e.contains('\n'));
    }
}
