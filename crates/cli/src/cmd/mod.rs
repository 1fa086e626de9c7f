//! One module per subcommand: its arguments, resolved into library calls, and its output.

pub mod agent;
pub mod bench;
pub mod check;
pub mod crew;
pub mod demo;
pub mod generate;
pub mod keys;
pub mod launch;
pub mod mission;
pub mod plan;
pub mod rosbag;
pub mod schedule;
pub mod simulate;
pub mod wall;
