//! Crew instances: a grid (MovingAI `.map` or occupancy PNG) with a MovingAI scenario, or a
//! bird's-eye PNG with its own robots and goals.

use crate::error::{InputError, InputResult};
use crate::files::{read_input, MAX_INPUT_BYTES};
use mason_crew::aerial::{decode, read_aerial_image, AerialConfig, AerialReading, MAX_PIXELS};
use mason_crew::image::{read_birdseye, read_occupancy};
use mason_crew::movingai::{parse_map, parse_scen};
use mason_crew::{
    AssignMethod, Cell, Connectivity, CrewConfig, Grid, Instance, PathMethod, PrmConfig,
    RefineConfig, Resolution,
};
use std::path::Path;

/// Where the robots and goals come from.
pub struct CrewInput<'a> {
    /// A `.map` file or an occupancy PNG.
    pub map: Option<&'a str>,
    /// A MovingAI scenario.
    pub scen: Option<&'a Path>,
    /// Take the first N agents of the scenario.
    pub agents: Option<usize>,
    /// A bird's-eye PNG with robots and goals.
    pub image: Option<&'a Path>,
}

fn read(path: &Path) -> InputResult<Vec<u8>> {
    read_input(path, MAX_INPUT_BYTES)
}

fn read_text(path: &Path) -> InputResult<String> {
    String::from_utf8(read(path)?)
        .map_err(|_| InputError::bad(format!("{}: not UTF-8 text", path.display())))
}

/// Reads the grid, robots and goals.
pub fn load_crew(input: &CrewInput<'_>, conn: Connectivity) -> InputResult<(Instance, String)> {
    let bad = |e: mason_crew::CrewError| InputError::bad(e.to_string());
    match (input.map, input.scen, input.image) {
        (None, None, Some(image)) => {
            if input.agents.is_some() {
                return Err(InputError::bad(
                    "--agents applies to --scen, not to --image",
                ));
            }
            let view = load_view(image, None, conn, false)?;
            Ok((view.inst, view.name))
        }
        (Some(map), Some(scen), None) => {
            let grid = load_grid(map)?;
            let scen_name = scen.display().to_string();
            let (robots, goals) = load_scenario(scen, &grid, input.agents)?;
            let pairing = Some((0..robots.len()).collect());
            let inst =
                Instance::new(grid, conn, robots, goals, pairing, &scen_name).map_err(bad)?;
            Ok((inst, map.to_string()))
        }
        (Some(_), None, None) => Err(InputError::bad(
            "a map needs a scenario: give --scen F [--agents N], or use --image PNG alone",
        )),
        (_, _, Some(_)) => Err(InputError::bad(
            "--image brings its own robots and goals; give it without a map or --scen",
        )),
        (None, _, None) => Err(InputError::bad("give a MAP with --scen F, or --image PNG")),
    }
}

/// What an image gave: the instance and, for a photograph, what was read.
pub struct View {
    /// Robots, goals and the grid.
    pub inst: Instance,
    /// The image's name.
    pub name: String,
    /// The aerial reading (`None` for a one-pixel-per-cell map).
    pub aerial: Option<AerialReading>,
    /// The image file's bytes (for an overlay), when asked to keep them; else empty.
    pub bytes: Vec<u8>,
}

/// Reads an image: with `aerial` (grid, cell size or corners given) as a photograph of the
/// floor; without, a one-pixel-per-cell map of at most 16 colours reads as before
/// ([`read_birdseye`]) and anything else as a photograph whose grid is painted on the floor,
/// or is refused. The file's bytes are kept in the view with `keep_bytes` (to draw an
/// overlay); without, a photograph's are let go once decoded, before it is read (the speed
/// case's 27 MB PNG is a fifth of the reading's peak memory).
pub fn load_view(
    path: &Path,
    aerial: Option<&AerialConfig>,
    conn: Connectivity,
    keep_bytes: bool,
) -> InputResult<View> {
    let bad = |e: mason_crew::CrewError| InputError::bad(e.to_string());
    let name = path.display().to_string();
    let mut bytes = read(path)?;
    let (grid, robots, goals, reading) = if pixel_map(&bytes, &name, aerial) {
        let seen = read_birdseye(&bytes, &name).map_err(bad)?;
        (seen.grid, seen.robots, seen.goals, None)
    } else {
        let config = aerial.cloned().unwrap_or_default();
        let img = decode(&bytes, &name, MAX_PIXELS).map_err(bad)?;
        if !keep_bytes {
            bytes = Vec::new();
        }
        let r = read_aerial_image(&img, &name, &config).map_err(bad)?;
        (r.grid.clone(), r.robot_cells(), r.goal_cells(), Some(r))
    };
    let inst = Instance::new(grid, conn, robots, goals, None, &name).map_err(bad)?;
    Ok(View {
        inst,
        name,
        aerial: reading,
        bytes,
    })
}

/// Whether an image is a one-pixel-per-cell map: a PNG of at most 16 colours, given with no
/// aerial setting.
fn pixel_map(bytes: &[u8], name: &str, aerial: Option<&AerialConfig>) -> bool {
    aerial.is_none()
        && bytes.starts_with(&[0x89, b'P', b'N', b'G'])
        && mason_crew::aerial::decode(bytes, name, mason_crew::limits::MAX_CELLS)
            .is_ok_and(|img| mason_crew::aerial::is_pixel_map(&img))
}

/// A photograph read past its cells' refusals ([`audit_view`]).
#[derive(Clone, Debug)]
pub struct AuditedView {
    /// The image's name.
    pub name: String,
    /// The reading and the refusals.
    pub audited: mason_crew::aerial::Audited,
    /// The image file's bytes (for an overlay), when asked to keep them; else empty.
    pub bytes: Vec<u8>,
}

/// Reads a photograph of the floor past every refusal about a cell
/// ([`mason_crew::aerial::audit_aerial`]). A one-pixel-per-cell map (without `aerial`) has
/// nothing to audit and is refused. The file's bytes as for [`load_view`].
pub fn audit_view(
    path: &Path,
    aerial: Option<&AerialConfig>,
    keep_bytes: bool,
) -> InputResult<AuditedView> {
    let bad = |e: mason_crew::CrewError| InputError::bad(e.to_string());
    let name = path.display().to_string();
    let mut bytes = read(path)?;
    if pixel_map(&bytes, &name, aerial) {
        return Err(InputError::bad(format!(
            "{name}: a one-pixel-per-cell map has no refusal to audit (--audit reads photographs)"
        )));
    }
    let config = aerial.cloned().unwrap_or_default();
    let img = decode(&bytes, &name, MAX_PIXELS).map_err(bad)?;
    if !keep_bytes {
        bytes = Vec::new();
    }
    let audited = mason_crew::aerial::audit_aerial_image(&img, &name, &config).map_err(bad)?;
    Ok(AuditedView {
        name,
        audited,
        bytes,
    })
}

/// The starts and goals of a MovingAI scenario's first `agents` agents (all when `None`), in
/// order, on `grid`.
pub fn load_scenario(
    scen: &Path,
    grid: &Grid,
    agents: Option<usize>,
) -> InputResult<(Vec<Cell>, Vec<Cell>)> {
    if agents == Some(0) {
        return Err(InputError::bad("--agents must be at least 1"));
    }
    let name = scen.display().to_string();
    let agents = parse_scen(&read_text(scen)?, &name, grid, agents.unwrap_or(usize::MAX))
        .map_err(|e| InputError::bad(e.to_string()))?;
    Ok(agents.iter().map(|a| (a.start, a.goal)).unzip())
}

/// A grid from a MovingAI `.map` file or an occupancy PNG (by its `.png` extension).
pub fn load_grid(map: &str) -> InputResult<Grid> {
    let path = Path::new(map);
    let bytes = read(path)?;
    let is_png = path
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("png"));
    if is_png {
        read_occupancy(&bytes, map).map_err(|e| InputError::bad(e.to_string()))
    } else {
        let text = String::from_utf8(bytes).map_err(|_| {
            InputError::bad(format!(
                "{map}: not UTF-8 text (a PNG map must end in .png)"
            ))
        })?;
        parse_map(&text, map).map_err(|e| InputError::bad(e.to_string()))
    }
}

/// The parsed solver choices.
pub struct CrewChoices {
    /// The solver configuration.
    pub config: CrewConfig,
    /// Moves allowed.
    pub connectivity: Connectivity,
}

/// The time limit of `--resolve lacam` when `--time-limit` is not given, in seconds.
pub const LACAM_DEFAULT_LIMIT_S: f64 = 60.0;

/// The solver flags as given.
pub struct RawChoices<'a> {
    /// `--assign`.
    pub assign: Option<&'a str>,
    /// `--paths`.
    pub paths: &'a str,
    /// `--resolve`.
    pub resolve: Option<&'a str>,
    /// `--connectivity`.
    pub connectivity: &'a str,
    /// `--seed`.
    pub seed: u64,
    /// `--refine-rounds`.
    pub refine_rounds: Option<u64>,
    /// `--refine-batch`.
    pub refine_batch: Option<usize>,
}

/// The largest `--refine-batch`: more neighbourhoods than that per batch would mostly be
/// planned against a stale plan.
const MAX_REFINE_BATCH: usize = 64;

/// Parses the solver options (a bad one is an [`InputError`] naming its flag).
pub fn choices(raw: RawChoices<'_>, prm: PrmConfig, has_pairing: bool) -> InputResult<CrewChoices> {
    let assign: AssignMethod = match raw.assign {
        Some(a) => a
            .parse()
            .map_err(|e| InputError::bad(format!("--assign: {e}")))?,
        None if has_pairing => AssignMethod::Given,
        None => AssignMethod::Joint,
    };
    let paths: PathMethod = raw
        .paths
        .parse()
        .map_err(|e| InputError::bad(format!("--paths: {e}")))?;
    if assign == AssignMethod::Joint && raw.resolve.is_some() {
        return Err(InputError::bad(
            "--assign joint plans the paths itself (TSWAP); drop --resolve, or choose another --assign",
        ));
    }
    if assign == AssignMethod::Joint && paths != PathMethod::Astar {
        return Err(InputError::bad(
            "--assign joint moves robots on the grid itself; drop --paths prm",
        ));
    }
    let resolve: Resolution = raw
        .resolve
        .unwrap_or("st")
        .parse()
        .map_err(|e| InputError::bad(format!("--resolve: {e}")))?;
    let connectivity: Connectivity = raw
        .connectivity
        .parse()
        .map_err(|e| InputError::bad(format!("--connectivity: {e}")))?;
    if prm.samples == 0 || prm.neighbours == 0 {
        return Err(InputError::bad(
            "--samples and --neighbours must be at least 1",
        ));
    }
    if prm.samples > MAX_PRM_SAMPLES || prm.neighbours > MAX_PRM_NEIGHBOURS {
        return Err(InputError::bad(format!(
            "--samples is at most {MAX_PRM_SAMPLES} and --neighbours at most {MAX_PRM_NEIGHBOURS}"
        )));
    }
    if raw.refine_rounds.is_some() && resolve != Resolution::Lacam {
        return Err(InputError::bad(
            "--refine-rounds applies to --resolve lacam",
        ));
    }
    if raw.refine_batch.is_some() && resolve != Resolution::Lacam {
        return Err(InputError::bad("--refine-batch applies to --resolve lacam"));
    }
    let mut refine = RefineConfig::default();
    if let Some(r) = raw.refine_rounds {
        refine.rounds = Some(r);
        refine.stall = None;
    }
    if let Some(b) = raw.refine_batch {
        if !(1..=MAX_REFINE_BATCH).contains(&b) {
            return Err(InputError::bad(format!(
                "--refine-batch is 1 to {MAX_REFINE_BATCH}"
            )));
        }
        refine.batch = b;
    }
    Ok(CrewChoices {
        config: CrewConfig {
            assign,
            paths,
            resolve,
            prm,
            seed: raw.seed,
            refine,
        },
        connectivity,
    })
}

/// The most PRM samples `--samples` accepts.
pub const MAX_PRM_SAMPLES: usize = 1_000_000;
/// The most PRM neighbours `--neighbours` accepts.
pub const MAX_PRM_NEIGHBOURS: usize = 1_000;

/// Refuses an instance over [`mason_crew::limits::MAX_AGENT_CELLS`] (robots × free cells).
pub fn check_size(inst: &Instance, source: &str) -> InputResult<()> {
    let size = inst.robot_count() as u64 * inst.grid.free_count() as u64;
    let limit = mason_crew::limits::MAX_AGENT_CELLS;
    if size > limit {
        return Err(InputError::bad(format!(
            "{source}: {} robots × {} free cells is more than {limit} (mason_crew::limits::MAX_AGENT_CELLS); take fewer robots (--agents N) or a smaller map",
            inst.robot_count(),
            inst.grid.free_count()
        )));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A photograph read without keeping its file's bytes reads the same, and keeps none.
    #[test]
    fn a_view_keeps_its_file_only_when_asked() {
        let path = Path::new(concat!(
            env!("CARGO_MANIFEST_DIR"),
            "/../../tests/data/aerial/A0901.png"
        ));
        let config = AerialConfig {
            grid: Some((12, 8)),
            ..AerialConfig::default()
        };
        let kept = load_view(path, Some(&config), Connectivity::Eight, true).unwrap();
        let let_go = load_view(path, Some(&config), Connectivity::Eight, false).unwrap();
        assert_eq!(kept.bytes, std::fs::read(path).unwrap());
        assert!(let_go.bytes.is_empty());
        assert_eq!(kept.inst.grid, let_go.inst.grid);
        assert_eq!(kept.inst.robots, let_go.inst.robots);
        assert_eq!(kept.inst.goals, let_go.inst.goals);
        let audited = audit_view(path, Some(&config), false).unwrap();
        assert!(audited.bytes.is_empty());
        assert_eq!(
            audit_view(path, Some(&config), true).unwrap().bytes,
            kept.bytes
        );
        assert_eq!(audited.audited.reading.grid, kept.inst.grid);
    }

    #[test]
    fn the_inputs_must_come_in_a_sensible_combination() {
        let none = CrewInput {
            map: None,
            scen: None,
            agents: None,
            image: None,
        };
        let e = load_crew(&none, Connectivity::Eight)
            .unwrap_err()
            .to_string();
        assert!(e.contains("give a MAP"), "{e}");
        let lone_map = CrewInput {
            map: Some("m.map"),
            ..none
        };
        let e = load_crew(&lone_map, Connectivity::Eight)
            .unwrap_err()
            .to_string();
        assert!(e.contains("needs a scenario"), "{e}");
    }
}
