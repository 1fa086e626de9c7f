//! `mason keys`: a mission authority and one set of TLS files per UAV and ground station, for
//! a real deployment ([`mason_fleet::authority`]; `mason launch` makes its own).

use crate::fail::{input_error, CliResult};
use std::path::PathBuf;

/// `mason keys`'s options.
#[derive(clap::Args)]
pub struct KeysArgs {
    /// The mission folder: authority/ (ca.pem, ca.key), uav-<i>/ and station-<s>/ (ca.pem,
    /// cert.pem, key.pem); the files of an earlier run there are replaced
    pub dir: PathBuf,
    /// UAVs of the team
    #[arg(long, allow_negative_numbers = true)]
    pub uavs: usize,
    /// Ground stations
    #[arg(long, default_value_t = 1, allow_negative_numbers = true)]
    pub stations: usize,
    /// The mission id every agent will be given (--mission); default: the folder's name
    #[arg(long)]
    pub mission: Option<String>,
}

/// `mason keys`.
#[cfg(feature = "zenoh")]
pub fn run(a: KeysArgs) -> CliResult<()> {
    let mission = match &a.mission {
        Some(m) => m.clone(),
        None => a
            .dir
            .file_name()
            .map(|f| f.to_string_lossy().into_owned())
            .ok_or_else(|| {
                input_error(format!(
                    "{}: no folder name to take the mission id from (give --mission)",
                    a.dir.display()
                ))
            })?,
    };
    let keys = mason_fleet::authority::make_keys(&a.dir, &mission, a.uavs, a.stations)?;
    println!(
        "mission {}: authority {} (keep ca.key off the vehicles)",
        keys.mission,
        keys.dir
            .join(mason_fleet::authority::AUTHORITY_DIR)
            .display()
    );
    for u in 0..keys.uavs {
        let m = mason_fleet::authority::Member::Uav(u);
        println!(
            "  UAV {u}: mason agent --uav {u} --mission {} --tls-dir {}",
            keys.mission,
            keys.member(m).dir.display()
        );
    }
    for s in 0..keys.stations {
        let m = mason_fleet::authority::Member::Station(s);
        println!("  ground station {s}: {}", keys.member(m).dir.display());
    }
    Ok(())
}

/// Without the `zenoh` feature there is no TLS: exit 2 with a hint.
#[cfg(not(feature = "zenoh"))]
pub fn run(_: KeysArgs) -> CliResult<()> {
    Err(input_error(
        "mason keys needs the zenoh feature: cargo build --release --features zenoh",
    ))
}
