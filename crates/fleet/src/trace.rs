//! Trace files: one [`Event`] as JSON per line (what [`crate::log::JsonLines`] writes). One
//! strict reader for every use: a bad line is an error naming the file and the line; only the
//! truncated last line of an agent that was killed mid-write is dropped.

use crate::error::{FleetError, FleetResult};
use mason_mission::state::EventRecord;
use mason_mission::{killed_events, Event, EventKind};
use mason_wall::BrickId;
use std::path::{Path, PathBuf};

/// The largest trace file read (1 GiB).
pub const MAX_TRACE_BYTES: u64 = 1 << 30;

/// The longest reason given for a bad line, in characters.
const MAX_REASON_CHARS: usize = 200;

/// A reason on one line: control characters (a newline the bad value carried) escaped, and
/// cut to [`MAX_REASON_CHARS`].
fn one_line(reason: &str) -> String {
    let mut out: String = reason
        .chars()
        .flat_map(|c| {
            if c.is_control() {
                c.escape_default().collect::<Vec<_>>()
            } else {
                vec![c]
            }
        })
        .take(MAX_REASON_CHARS)
        .collect();
    if reason.chars().count() > MAX_REASON_CHARS {
        out.push('…');
    }
    out
}

/// One line of a trace file as an event; a bad line's reason is one line.
pub fn parse_line(line: &str) -> Result<Event, String> {
    serde_json::from_str::<EventRecord>(line.trim_end())
        .map_err(|e| e.to_string())
        .and_then(EventRecord::into_event)
        .map_err(|reason| one_line(&reason))
}

/// The events of a trace file's `text` (read from `path`, named in errors). When `killed`, a
/// last line without its newline (cut off by the kill) is dropped; any other bad line is an
/// error.
pub fn parse_trace(text: &str, path: &Path, killed: bool) -> FleetResult<Vec<Event>> {
    let lines: Vec<&str> = text.split_inclusive('\n').collect();
    let mut events = Vec::with_capacity(lines.len());
    for (i, line) in lines.iter().enumerate() {
        let last = i + 1 == lines.len();
        match parse_line(line) {
            Ok(e) => events.push(e),
            Err(_) if last && killed && !line.ends_with('\n') => {}
            Err(reason) => {
                return Err(FleetError::Trace {
                    path: path.to_path_buf(),
                    line: Some(i + 1),
                    reason,
                })
            }
        }
    }
    Ok(events)
}

/// Reads one agent's trace file (see [`parse_trace`]). A killed agent that had not opened its
/// trace yet left none: a missing file is then no events.
pub fn read_trace(path: &Path, killed: bool) -> FleetResult<Vec<Event>> {
    let text = match mason_io::read_input_text(path, MAX_TRACE_BYTES) {
        Ok(t) => t,
        Err(mason_io::InputError::Io { source, .. })
            if killed && source.kind() == std::io::ErrorKind::NotFound =>
        {
            return Ok(Vec::new())
        }
        Err(e) => {
            return Err(FleetError::Trace {
                path: path.to_path_buf(),
                line: None,
                reason: e
                    .to_string()
                    .trim_start_matches(&format!("{}: ", path.display()))
                    .to_string(),
            })
        }
    };
    parse_trace(&text, path, killed)
}

/// Every agent's events, sorted stably by time: `(file, killed)` per agent run.
pub fn merge(files: &[(PathBuf, bool)]) -> FleetResult<Vec<Event>> {
    let mut all = Vec::new();
    for (path, killed) in files {
        all.extend(read_trace(path, *killed)?);
    }
    all.sort_by(|a, b| a.t.total_cmp(&b.t));
    Ok(all)
}

/// The bricks UAV `uav` placed according to its earlier trace files (a restarted agent
/// remembers its own work). A truncated last line is dropped.
pub fn placed_by(uav: usize, files: &[PathBuf]) -> FleetResult<Vec<BrickId>> {
    let mut placed = Vec::new();
    for p in files {
        let text = mason_io::read_input_text(p, MAX_TRACE_BYTES)?;
        for e in parse_trace(&text, p, true)? {
            match e.kind {
                EventKind::Place { brick } if e.uav as usize == uav => placed.push(brick),
                _ => {}
            }
        }
    }
    Ok(placed)
}

/// Completes the trace of an agent killed at mission time `t`: a truncated last line is cut
/// off, and the events of its death ([`killed_events`]: it fails, leaves the zone, loses what
/// it held, is down) are appended at `t`, or at its last event if that is later. Returns the
/// time used.
pub fn append_death(path: &Path, uav: usize, t: f64) -> FleetResult<f64> {
    let io = |source| FleetError::Io {
        path: path.to_path_buf(),
        source,
    };
    let text = match std::fs::read_to_string(path) {
        Ok(text) => text,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => String::new(),
        Err(e) => return Err(io(e)),
    };
    let complete = text.rfind('\n').map_or(0, |i| i + 1);
    let events = parse_trace(&text, path, true)?;
    let t = events.iter().map(|e| e.t).fold(t, f64::max);
    let mut out = text[..complete].to_string();
    for e in killed_events(&events, uav as u32, t) {
        out.push_str(&serde_json::to_string(&e).map_err(|e| io(std::io::Error::other(e)))?);
        out.push('\n');
    }
    std::fs::write(path, out).map_err(io)?;
    Ok(t)
}

#[cfg(test)]
mod tests {
    use super::*;

    const GOOD: &str =
        r#"{"t":0.0,"uav":1,"kind":"state","state":"Check","outcome":"start","x":1.0,"y":2.0}"#;

    #[test]
    fn a_truncated_last_line_of_a_killed_agent_is_dropped() {
        let text = format!("{GOOD}\n{{\"t\":1.0,\"uav\"");
        let p = Path::new("t.jsonl");
        assert_eq!(parse_trace(&text, p, true).unwrap().len(), 1);
        let e = parse_trace(&text, p, false).unwrap_err().to_string();
        assert!(e.starts_with("t.jsonl: line 2: "), "{e}");
    }

    #[test]
    fn a_bad_line_in_the_middle_is_an_error_even_for_a_killed_agent() {
        let text = format!("{GOOD}\nnot json\n{GOOD}\n");
        let e = parse_trace(&text, Path::new("t.jsonl"), true)
            .unwrap_err()
            .to_string();
        assert!(e.contains("line 2"), "{e}");
        let text = format!("{GOOD}\n{{\"t\":1.0,\"uav\":0,\"kind\":\"place\",\"brick\":-3}}\n");
        assert!(parse_trace(&text, Path::new("t.jsonl"), false).is_err());
    }

    /// Found by the `trace_file` fuzz target: serde echoed a bad value with its newline.
    #[test]
    fn a_bad_value_with_a_newline_is_reported_on_one_line() {
        let text = "{\"t\":0.0,\"uav\":1,\"kind\":\"u\\n\\\"state\"}\n";
        let e = parse_trace(text, Path::new("t.jsonl"), false)
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("t.jsonl: line 1: "), "{e}");
        assert!(!e.contains('\n'), "{e}");
        let long = format!(
            "{{\"t\":0.0,\"uav\":1,\"kind\":\"{}\"}}\n",
            "x".repeat(5000)
        );
        let e = parse_trace(&long, Path::new("t.jsonl"), false)
            .unwrap_err()
            .to_string();
        assert!(e.chars().count() < 260, "{e}");
    }

    #[test]
    fn a_killed_agents_trace_gets_the_events_of_its_death() {
        let dir = std::env::temp_dir().join(format!("mason-fleet-trace-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let p = dir.join("uav-1-1.jsonl");
        std::fs::write(&p, format!("{GOOD}\n{{\"t\":")).unwrap();
        let t = append_death(&p, 1, 5.0).unwrap();
        assert_eq!(t, 5.0);
        let events = read_trace(&p, false).unwrap();
        assert!(events
            .iter()
            .any(|e| e.kind == EventKind::Fail && e.t == 5.0));
        assert!(read_trace(&dir.join("missing.jsonl"), true)
            .unwrap()
            .is_empty());
        let e = read_trace(&dir.join("missing.jsonl"), false)
            .unwrap_err()
            .to_string();
        assert!(e.contains("missing.jsonl"), "{e}");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
