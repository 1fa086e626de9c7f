//! Mason's benchmark suites, as library calls that return their table as text (the `mason
//! bench` subcommands print it). Every result inside a suite is checked by its domain's
//! independent validator before it is counted.
//!
//! - [`thesis`]: the thesis's Tables 3.3–3.5 beside ours; [`planning`]: whole-process time
//!   of `mason plan`;
//! - [`thesis_mission`]: the thesis's Table 5.1 setting; [`throughput`]: simulated missions
//!   per second; [`replan`]: static against re-planned schedules under UAV failures;
//! - [`cmcp`]: team schedules on the CMCP walls beside GRASP's published runs;
//! - [`paper`]: the crew paper's Tables 1 and 2 setting and the MovingAI warehouse;
//! - [`mapf`]: MovingAI maps at rising agent counts, one child `mason crew` per case;
//! - [`arrivals`]: the cost of an agent's check on arrival, per message.
//!
//! Suites that run whole `mason` processes ([`planning`], [`mapf`]) take the program's path.
//!
//! ```
//! let text = mason_bench::throughput(1).unwrap();
//! assert!(text.contains("missions/s"));
//! ```

#![deny(missing_docs)]

mod arrivals;
mod cmcp;
mod mapf;
mod missions;
mod paper;
mod support;
mod thesis;

pub use arrivals::arrivals;
pub use cmcp::{cmcp, data_dir as cmcp_data_dir};
pub use mapf::mapf;
pub use missions::{replan, thesis_mission, throughput};
pub use paper::{paper, PAPER_ROBOTS};
pub use support::{benchmarks_dir, search_limit, BenchError, BenchResult};
pub use thesis::{planning, thesis};
