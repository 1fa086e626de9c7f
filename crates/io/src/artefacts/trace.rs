//! A mission trace read back from JSON: `simulate --json` and `launch`'s `trace.json` (objects
//! with `uavs` and `events`), or a bare list of events in the same schema. Bricks are named by
//! their labels, as those files write them. (An agent's own trace file, one event per line
//! with dense brick ids, is read by `mason_fleet::trace`.)

use super::json::{document, value, LineIndex};
use super::{at, Labels};
use crate::error::InputResult;
use crate::files::{read_input_text, MAX_INPUT_BYTES};
use mason_mission::state::{EventRecord, KindRecord};
use mason_mission::Event;
use mason_order::schedule::MAX_UAVS;
use mason_wall::Wall;
use serde::Deserialize;
use serde_json::value::RawValue;
use std::path::Path;

/// A trace as read.
#[derive(Clone, Debug, PartialEq)]
pub struct TraceFile {
    /// The events, in the file's order.
    pub events: Vec<Event>,
    /// The team size the file states, or the largest UAV index plus one.
    pub uavs: usize,
    /// The verdict the file states (`trace.json`'s `summary.check_trace`), if any.
    pub claimed_check: Option<String>,
    /// `simulate --json`, `trace.json` or `events`.
    pub format: &'static str,
}

#[derive(Deserialize)]
struct Summary {
    check_trace: Option<String>,
}

#[derive(Deserialize)]
struct TraceJson<'a> {
    uavs: Option<usize>,
    #[serde(borrow)]
    events: Vec<&'a RawValue>,
    summary: Option<Summary>,
    metrics: Option<serde::de::IgnoredAny>,
}

/// Reads `path` ([`parse_trace_json`]).
pub fn read_trace_json(path: &Path, wall: &Wall) -> InputResult<TraceFile> {
    parse_trace_json(&read_input_text(path, MAX_INPUT_BYTES)?, path, wall)
}

/// The trace in `text` (from `path`, named in errors). An event that does not parse, names a
/// brick not in `wall`, or a UAV outside the stated team, is an error naming its line.
pub fn parse_trace_json(text: &str, path: &Path, wall: &Wall) -> InputResult<TraceFile> {
    let labels = Labels::new(wall);
    let (raw, uavs, claimed_check, format) = if text.trim_start().starts_with('[') {
        let raw: Vec<&RawValue> = document(text, path)?;
        (raw, None, None, "events")
    } else {
        let doc: TraceJson<'_> = document(text, path)?;
        let format = if doc.metrics.is_some() {
            "simulate --json"
        } else {
            "trace.json"
        };
        let check = doc.summary.and_then(|s| s.check_trace);
        (doc.events, doc.uavs, check, format)
    };
    if let Some(n) = uavs.filter(|&n| n == 0 || n > MAX_UAVS) {
        return Err(at(path, 1, format!("uavs {n}: expected 1 to {MAX_UAVS}")));
    }
    let lines = LineIndex::new(text);
    let mut events = Vec::with_capacity(raw.len());
    let mut seen = 0;
    for r in raw {
        let line = lines.of(r.get());
        let mut record: EventRecord = value(text, r, path)?;
        if let KindRecord::Grasp { brick: b }
        | KindRecord::Place { brick: b }
        | KindRecord::Lost { brick: b } = &mut record.kind
        {
            *b = labels.brick(b.0, path, line)?;
        }
        let uav = record.uav;
        match uavs {
            Some(team) if uav as usize >= team => {
                let why = format!("UAV {uav}: the team has {team} UAVs (0..{team})");
                return Err(at(path, line, why));
            }
            None if uav as usize >= MAX_UAVS => {
                let why = format!("UAV {uav}: a team has at most {MAX_UAVS} UAVs");
                return Err(at(path, line, why));
            }
            _ => {}
        }
        seen = seen.max(record.uav as usize + 1);
        events.push(
            record
                .into_event()
                .map_err(|reason| at(path, line, reason))?,
        );
    }
    Ok(TraceFile {
        events,
        uavs: uavs.unwrap_or(seen.max(1)),
        claimed_check,
        format,
    })
}

/// Whether `text` is one event per line (an agent's trace file) rather than one JSON
/// document: its first non-blank line is by itself a JSON object with a `kind`.
pub fn is_json_lines(text: &str) -> bool {
    let first = text.lines().map(str::trim).find(|l| !l.is_empty());
    first.is_some_and(|l| {
        serde_json::from_str::<serde_json::Map<String, serde_json::Value>>(l)
            .is_ok_and(|o| o.contains_key("kind"))
    })
}

impl TraceFile {
    /// Checks the events with `mission::check_trace` for a team of `uavs` (default: the
    /// file's): the summary, or the broken rules (the first one; with `all`, every one).
    pub fn check(
        &self,
        wall: &Wall,
        uavs: usize,
        all: bool,
    ) -> Result<mason_mission::TraceSummary, Vec<mason_mission::TraceError>> {
        match mason_mission::check_trace(wall, uavs, &self.events) {
            Ok(summary) => Ok(summary),
            Err(first) if !all => Err(vec![first]),
            Err(_) => Err(mason_mission::trace_violations(wall, uavs, &self.events)),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use mason_mission::EventKind;

    #[test]
    fn labels_become_dense_ids_and_bad_events_name_their_line() {
        let w = mason_wall::builtin("thesis-2x5").unwrap().wall();
        let text = "[\n{\"t\": 0, \"uav\": 1, \"kind\": \"grasp\", \"brick\": 102},\n{\"t\": 1, \"uav\": 1, \"kind\": \"zone_enter\"}\n]";
        let f = parse_trace_json(text, Path::new("t.json"), &w).unwrap();
        assert_eq!(f.uavs, 2);
        assert_eq!(f.format, "events");
        assert_eq!(
            f.events[0].kind,
            EventKind::Grasp {
                brick: w.by_label(102).unwrap()
            }
        );
        let cases = [
            ("[\n{\"t\": 0, \"uav\": 0, \"kind\": \"grasp\", \"brick\": 999}]", "t.json:2: brick 999 is not in the wall"),
            ("[\n{\"t\": 0, \"uav\": 0, \"kind\": \"jump\"}]", "t.json:2: unknown variant `jump`"),
            ("{\"uavs\": 2, \"events\": [\n\n{\"t\": 0, \"uav\": 2, \"kind\": \"fail\"}]}", "t.json:3: UAV 2: the team has 2 UAVs"),
            ("[\n{\"t\": 0, \"uav\": 0, \"kind\": \"state\", \"state\": \"Check\", \"outcome\": \"nope\", \"x\": 0, \"y\": 0}]", "t.json:2: unknown outcome `nope`"),
            ("{\"uavs\": 0, \"events\": []}", "t.json:1: uavs 0"),
            ("{\"events\": 3}", "t.json:1: invalid type"),
        ];
        for (text, want) in cases {
            let e = parse_trace_json(text, Path::new("t.json"), &w)
                .unwrap_err()
                .to_string();
            assert!(e.starts_with(want), "{e} / {want}");
        }
    }
}
