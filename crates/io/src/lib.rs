//! Mason's files, read and written the same way by the `mason` command, the agent runtime,
//! the bench suites and the Python package.
//!
//! - [`files`]: every file read is a regular file of bounded size ([`read_input`]), UTF-8
//!   text with a dropped byte-order mark ([`read_input_text`]), or TOML whose errors name the
//!   file and the line ([`read_toml`]).
//! - [`design`]: a wall design from a path or `builtin:NAME`, by format ([`load_wall`]).
//! - [`crew`]: a crew instance from a map and a scenario, or a bird's-eye image ([`load_crew`]).
//! - [`models`]: the thesis cost model ([`load_model`]) and team models ([`load_team_model`]).
//! - [`faults`]: the one parser of `U@T` ([`parse_at`]) and of `A-B` ([`parse_window`]), fault
//!   settings as flags or a TOML file ([`FaultSpec`]), and mission files ([`read_mission`]).
//!
//! - [`artefacts`]: plans, schedules, traces and crew plans read back for checking, from
//!   Mason's JSON or plain formats (an order list, a schedule CSV, a MAPF result file).
//! - [`output`]: outputs checked before any work and written all or none, atomically, and
//!   never renamed over a device, FIFO or socket ([`write_files`]).
//!
//! Every error is an [`InputError`] whose message is one line naming the file, the line or
//! the flag, and what is wrong.
//!
//! ```
//! use mason_io::{load_wall, parse_window, Format, Sizes};
//! let loaded = load_wall("builtin:thesis-2x5", Format::Auto, Sizes::Yaml, false).unwrap();
//! assert_eq!(loaded.wall.len(), 10);
//! let w = parse_window("--cut", "100-125").unwrap();
//! assert_eq!((w.from, w.to), (100.0, 125.0));
//! assert!(parse_window("--cut", "125-100").is_err());
//! ```

#![deny(missing_docs)]

pub mod artefacts;
pub mod crew;
pub mod design;
pub mod error;
pub mod faults;
pub mod files;
pub mod models;
pub mod output;

pub use crew::{
    audit_view, check_size, choices, load_crew, load_grid, load_scenario, load_view, AuditedView,
    CrewChoices, CrewInput, RawChoices, View,
};
pub use design::{load_wall, Format, LoadedWall, Sizes};
pub use error::InputError;
pub use faults::check_uav;
pub use faults::{parse_at, parse_window, read_mission, FaultSpec};
pub use files::{read_input, read_input_text, read_toml, MAX_INPUT_BYTES, MAX_TOML_BYTES};
pub use models::{load_model, load_team_model, objective, time_limit, MAX_TIME_LIMIT_S};
pub use output::{check_output, check_output_folder, make_output_folder, write_file, write_files};
