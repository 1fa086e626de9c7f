//! JSON documents read with their line numbers: serde's errors carry one, and the values kept
//! raw ([`RawValue`]) know where they sit in the text.

use super::at;
use crate::error::InputError;
use serde::de::DeserializeOwned;
use serde::Deserialize;
use serde_json::value::RawValue;
use std::path::Path;

/// The line (1-based) where `part`, a slice of `text`, begins.
pub(super) fn line_of(text: &str, part: &str) -> usize {
    let offset = (part.as_ptr() as usize)
        .saturating_sub(text.as_ptr() as usize)
        .min(text.len());
    text[..offset].matches('\n').count() + 1
}

/// The lines of a document: where each begins, found once, so that a value's line is a
/// binary search (counting newlines for every value of a large file would be quadratic).
pub(super) struct LineIndex<'a> {
    text: &'a str,
    newlines: Vec<usize>,
}

impl<'a> LineIndex<'a> {
    pub(super) fn new(text: &'a str) -> Self {
        let newlines = text.match_indices('\n').map(|(i, _)| i).collect();
        LineIndex { text, newlines }
    }

    /// The line (1-based) where `part`, a slice of the text, begins.
    pub(super) fn of(&self, part: &str) -> usize {
        let offset = (part.as_ptr() as usize)
            .saturating_sub(self.text.as_ptr() as usize)
            .min(self.text.len());
        self.newlines.partition_point(|&n| n < offset) + 1
    }
}

/// A serde error as `path:line: reason` (the line counted from `first_line`).
fn error(path: &Path, first_line: usize, e: &serde_json::Error) -> InputError {
    let reason = e.to_string();
    // serde_json ends its messages with " at line L column C": the line is given apart.
    let reason = reason
        .split(" at line ")
        .next()
        .unwrap_or(&reason)
        .to_string();
    at(path, first_line + e.line().max(1) - 1, reason)
}

/// `text` (the whole file) as `T`.
pub(super) fn document<'a, T: Deserialize<'a>>(
    text: &'a str,
    path: &Path,
) -> Result<T, InputError> {
    serde_json::from_str(text).map_err(|e| error(path, 1, &e))
}

/// One raw value of `text` as `T`; errors name its line in the file.
pub(super) fn value<T: DeserializeOwned>(
    text: &str,
    raw: &RawValue,
    path: &Path,
) -> Result<T, InputError> {
    serde_json::from_str(raw.get()).map_err(|e| error(path, line_of(text, raw.get()), &e))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_line_index_agrees_with_counting_newlines() {
        let text = "{\n\"a\": [1,\n2],\n\n\"b\": 3}\n";
        let lines = LineIndex::new(text);
        for (offset, _) in text.char_indices() {
            let part = &text[offset..];
            assert_eq!(lines.of(part), line_of(text, part), "offset {offset}");
        }
        assert_eq!(lines.of(&text[text.find('2').unwrap()..]), 3);
        assert_eq!(lines.of(&text[text.find("\"b\"").unwrap()..]), 5);
    }
}
