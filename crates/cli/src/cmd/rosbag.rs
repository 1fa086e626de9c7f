//! `--rosbag DIR` of `mason simulate` and `mason launch`: a mission's trace as a ROS 2 bag
//! ([`mason_report::mission_rosbag`]), written as `DIR/metadata.yaml` and `DIR/<DIR>_0.mcap`.

use crate::fail::{input_error, CliResult};
use mason_mission::{CommMode, Coord, Event};
use std::path::{Path, PathBuf};

/// The UAVs' mode at the start of a mission flown under `coord`.
pub fn start_mode(coord: Coord) -> CommMode {
    match coord {
        Coord::Windows => CommMode::Windows,
        Coord::Comm | Coord::Auto => CommMode::Comm,
    }
}

/// Checks, before any work, that a bag can go to `dir`.
pub fn check(dir: &Option<PathBuf>) -> CliResult<()> {
    match dir {
        Some(d) => Ok(mason_io::check_output_folder(d)?),
        None => Ok(()),
    }
}

/// The bag's two files (its folder made if missing), to write with the command's other outputs.
pub fn files(
    dir: &Path,
    meta: &mason_report::BagMeta<'_>,
    trace: &[Event],
    end_s: f64,
) -> CliResult<Vec<(PathBuf, Vec<u8>)>> {
    let name = dir
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .filter(|n| !n.is_empty() && n != "." && n != "..")
        .unwrap_or_else(|| "mason".into());
    let bag = mason_report::mission_rosbag(&name, meta, trace, end_s)
        .map_err(|e| input_error(format!("internal error: {}: {e}", dir.display())))?;
    mason_io::make_output_folder(dir)?;
    Ok(vec![
        (dir.join("metadata.yaml"), bag.metadata.into_bytes()),
        (dir.join(bag.mcap_name), bag.mcap),
    ])
}
