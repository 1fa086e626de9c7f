//! Plans, schedules, traces and crew plans read back for checking, from Mason's own JSON or
//! from the plain formats other tools can be converted to in one line (`mason check`):
//!
//! - [`order`]: a build order, `plan --json` or a list of brick ids ([`read_order`]);
//! - [`schedule`]: a team schedule, `plan --objective … --json` or a CSV of
//!   `uav,brick,start[,end]` rows ([`read_schedule`]);
//! - [`trace`]: a mission trace, `simulate --json`, `launch`'s `trace.json` or a JSON list of
//!   events in the same schema ([`read_trace_json`]);
//! - [`crew_plan`]: a crew plan, `crew --json` or a result file of `key=value` lines whose
//!   `solution=` is followed by one configuration per time step ([`read_crew_plan`]).
//!
//! Bricks are named by their labels (the ids shown by Mason) and mapped to the wall's dense
//! ids here; cells are `(x, y)` as in MovingAI files. Every error is one line naming the file,
//! the line and what is wrong. Whether the artefact keeps the rules is for the validators
//! (`order::validate`, `order::schedule::validate_schedule`, `mission::check_trace`,
//! `crew::validate`) and their `*_violations` twins.

pub mod crew_plan;
mod json;
pub mod order;
pub mod schedule;
pub mod trace;

pub use crew_plan::{crew_instance, parse_crew_plan, read_crew_plan, CrewInstance, CrewPlanFile};
pub use order::{parse_order, read_order, OrderFile};
pub use schedule::{parse_schedule, read_schedule, ScheduleClaims, ScheduleFile, ScheduleSetting};
pub use trace::{is_json_lines, parse_trace_json, read_trace_json, TraceFile};

use crate::error::InputError;
use mason_wall::{BrickId, Wall};
use std::collections::HashMap;
use std::path::Path;

pub use mason_wall::violations::rule;

/// `path:line: reason`, the one-line error of a bad artefact line.
fn at(path: &Path, line: usize, reason: impl std::fmt::Display) -> InputError {
    InputError::bad(format!("{}:{line}: {reason}", path.display()))
}

/// A wall's bricks by label, looked up in constant time.
struct Labels<'w> {
    wall: &'w Wall,
    ids: HashMap<u32, BrickId>,
}

impl<'w> Labels<'w> {
    fn new(wall: &'w Wall) -> Self {
        let mut ids = HashMap::with_capacity(wall.len());
        for id in wall.ids() {
            // The first brick of a label, as `Wall::by_label`.
            ids.entry(wall.brick(id).label).or_insert(id);
        }
        Labels { wall, ids }
    }

    /// The brick labelled `label`, or an error naming the line.
    fn brick(&self, label: u32, path: &Path, line: usize) -> Result<BrickId, InputError> {
        self.ids.get(&label).copied().ok_or_else(|| {
            at(
                path,
                line,
                format!("brick {label} is not in the wall {}", self.wall.name()),
            )
        })
    }
}

/// Whether `text` is a JSON document (its first non-blank character opens an object or a
/// list) rather than a plain format.
fn looks_like_json(text: &str) -> bool {
    text.trim_start().starts_with(['{', '['])
}
