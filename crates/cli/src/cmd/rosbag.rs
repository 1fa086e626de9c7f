//! `--rosbag DIR` of `mason simulate` and `mason launch`: a mission's trace as a ROS 2 bag
//! ([`mason_report::mission_rosbag`]), written as `DIR/metadata.yaml` and `DIR/<DIR>_0.mcap`.

use crate::fail::{input_error, CliResult};
use mason_mission::{Arena, CommMode, Coord, Event};
use mason_wall::Wall;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// What the bag is of.
pub struct BagSource<'a> {
    /// The team size.
    pub uavs: usize,
    /// The arena.
    pub arena: &'a Arena,
    /// The wall.
    pub wall: &'a Wall,
    /// The coordination policy (the UAVs' mode at the start: windows, or comm).
    pub coord: Coord,
    /// Messages dropped on arrival, by cause.
    pub rejected: &'a BTreeMap<String, u64>,
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
    src: &BagSource<'_>,
    trace: &[Event],
    end_s: f64,
) -> CliResult<Vec<(PathBuf, Vec<u8>)>> {
    let name = dir
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .filter(|n| !n.is_empty() && n != "." && n != "..")
        .unwrap_or_else(|| "mason".into());
    let mode = match src.coord {
        Coord::Windows => CommMode::Windows,
        Coord::Comm | Coord::Auto => CommMode::Comm,
    };
    let meta = mason_report::BagMeta {
        uavs: src.uavs,
        arena: src.arena,
        wall: src.wall,
        mode,
        rejected: src.rejected,
    };
    let bag = mason_report::mission_rosbag(&name, &meta, trace, end_s)
        .map_err(|e| input_error(format!("internal error: {}: {e}", dir.display())))?;
    mason_io::make_output_folder(dir)?;
    Ok(vec![
        (dir.join("metadata.yaml"), bag.metadata.into_bytes()),
        (dir.join(bag.mcap_name), bag.mcap),
    ])
}
