//! `mason generate`: seeded inputs for the README's scaling figures, the same for the same seed.
//! `wall`: a layer-text wall (`mason_wall::generate::large_layer_text`); `structure`: a CMCP
//! wall, L, tower or storeys (`mason_wall::structure::structure_cmcp`); `scene`: a bird's-eye
//! PNG of a warehouse with robots and goals (`mason_crew::generate::birdseye_scene`); `scen`: a
//! MovingAI random scenario for a map (`mason_crew::generate::random_scenario`).

use crate::fail::{input_error, write_file, CliResult};
use std::path::PathBuf;

/// `mason generate` subcommands.
#[derive(clap::Subcommand)]
pub enum GenerateCommand {
    /// Print a layer-text wall of about N bricks (a running bond of red and green bricks)
    Wall {
        /// About this many bricks (every layer the same width)
        #[arg(long)]
        bricks: usize,
        /// Layers
        #[arg(long)]
        levels: usize,
        /// Seed of the generator
        #[arg(long, default_value_t = 0)]
        seed: u64,
    },
    /// Print a CMCP-format structure of about N bricks (`yaml` sizes): a straight wall, an L
    /// or a tower (a square ring), over --levels layers split into --storeys storeys (each
    /// storey but the last topped by an orange ring beam)
    Structure {
        /// wall, l or tower
        #[arg(long, default_value = "wall")]
        shape: String,
        /// About this many bricks
        #[arg(long)]
        bricks: usize,
        /// Layers in all
        #[arg(long)]
        levels: usize,
        /// Storeys (1 to --levels)
        #[arg(long, default_value_t = 1)]
        storeys: usize,
        /// Seed of the generator
        #[arg(long, default_value_t = 0)]
        seed: u64,
    },
    /// Write a bird's-eye PNG (one pixel a cell): a warehouse of 10×2 shelves, robots red,
    /// goals green, for `mason crew --image`
    Scene {
        /// Width and height in cells (pixels)
        #[arg(long, default_value_t = 450)]
        size: u32,
        /// Robots, and as many goals
        #[arg(long)]
        robots: usize,
        /// Seed of the generator (clutter, robots and goals)
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// The PNG to write
        #[arg(long)]
        png: PathBuf,
    },
    /// Print a MovingAI random scenario (.scen, version 1) for a map: distinct starts, distinct
    /// goals, each goal reachable from its start under 4-connectivity and never equal to it
    Scen {
        /// The MovingAI .map file (or occupancy PNG)
        #[arg(long, value_name = "F.map")]
        map: PathBuf,
        /// Start–goal pairs
        #[arg(long)]
        agents: usize,
        /// Seed of the generator
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// Write the scenario here instead of printing it
        #[arg(long, value_name = "F.scen")]
        out: Option<PathBuf>,
    },
}

/// `mason generate …`.
pub fn run(command: GenerateCommand) -> CliResult<()> {
    match command {
        GenerateCommand::Wall {
            bricks,
            levels,
            seed,
        } => {
            print!("{}", wall(bricks, levels, seed)?);
            Ok(())
        }
        GenerateCommand::Structure {
            shape,
            bricks,
            levels,
            storeys,
            seed,
        } => {
            print!("{}", structure(&shape, bricks, levels, storeys, seed)?);
            Ok(())
        }
        GenerateCommand::Scene {
            size,
            robots,
            seed,
            png,
        } => {
            crate::fail::check_output(&png)?;
            let bytes = scene(size, robots, seed)?;
            write_file(&png, &bytes)
        }
        GenerateCommand::Scen {
            map,
            agents,
            seed,
            out,
        } => {
            if let Some(out) = &out {
                crate::fail::check_output(out)?;
            }
            let text = scen(&map, agents, seed)?;
            match out {
                Some(out) => write_file(&out, text.as_bytes()),
                None => {
                    print!("{text}");
                    Ok(())
                }
            }
        }
    }
}

/// The text of `mason generate scen`: `agents` random pairs on the map at `map`.
pub fn scen(map: &std::path::Path, agents: usize, seed: u64) -> CliResult<String> {
    let max_agents = mason_crew::limits::MAX_AGENTS;
    if agents == 0 || agents > max_agents {
        return Err(input_error(format!(
            "--agents {agents}: must lie in 1..={max_agents}"
        )));
    }
    let grid = mason_io::load_grid(&map.to_string_lossy())?;
    let pairs = mason_crew::generate::random_scenario(&grid, agents, seed).ok_or_else(|| {
        input_error(format!(
            "{}: --agents {agents}: the map has no room for that many start-goal pairs (distinct starts, distinct goals, each reachable from its start)",
            map.display()
        ))
    })?;
    let name = map
        .file_name()
        .map_or("map.map".to_string(), |n| n.to_string_lossy().into_owned());
    Ok(mason_crew::movingai::scen_text(&name, &grid, &pairs))
}

/// The layer text of `mason generate wall`, one line per layer (top first), refused when it
/// would break the readers' limits (bricks, layers, line length).
pub fn wall(bricks: usize, levels: usize, seed: u64) -> CliResult<String> {
    use mason_wall::limits::{MAX_BRICKS, MAX_LAYERS, MAX_LINE_CHARS};
    use rand::SeedableRng;
    if bricks == 0 || bricks > MAX_BRICKS {
        return Err(input_error(format!(
            "--bricks {bricks}: must lie in 1..={MAX_BRICKS}"
        )));
    }
    if levels == 0 || levels > MAX_LAYERS.min(bricks) {
        return Err(input_error(format!(
            "--levels {levels}: must lie in 1..={} (at most one per brick)",
            MAX_LAYERS.min(bricks)
        )));
    }
    // A layer is 1.5 units per brick wide and its tokens take two characters each (`R `); a
    // layer of reds only is the longest.
    if 2 * (bricks.div_ceil(levels) * 3 / 2) > MAX_LINE_CHARS {
        return Err(input_error(format!(
            "--bricks {bricks} --levels {levels}: a layer would be longer than {MAX_LINE_CHARS} characters; use more levels"
        )));
    }
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    let text = mason_wall::generate::large_layer_text(&mut rng, bricks, levels);
    Ok(format!("{text}\n"))
}

/// The CMCP text of `mason generate structure`, refused when it would break the readers'
/// limits (bricks, layers).
pub fn structure(
    shape: &str,
    bricks: usize,
    levels: usize,
    storeys: usize,
    seed: u64,
) -> CliResult<String> {
    use mason_wall::limits::{MAX_BRICKS, MAX_LAYERS};
    use mason_wall::structure::{structure_cmcp, Shape, Structure};
    use rand::SeedableRng;
    let shape = Shape::parse(shape).ok_or_else(|| {
        input_error(format!(
            "--shape {}: expected wall, l or tower",
            shape.chars().take(80).collect::<String>()
        ))
    })?;
    // A layer may hold up to twice its share of bricks (reds only), a tower a few more.
    if bricks == 0 || bricks > MAX_BRICKS / 2 {
        return Err(input_error(format!(
            "--bricks {bricks}: must lie in 1..={}",
            MAX_BRICKS / 2
        )));
    }
    if levels == 0 || levels > MAX_LAYERS.min(bricks) {
        return Err(input_error(format!(
            "--levels {levels}: must lie in 1..={} (at most one per brick)",
            MAX_LAYERS.min(bricks)
        )));
    }
    if storeys == 0 || storeys > levels {
        return Err(input_error(format!(
            "--storeys {storeys}: must lie in 1..={levels} (at most one per layer)"
        )));
    }
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(seed);
    Ok(structure_cmcp(
        &mut rng,
        &Structure {
            shape,
            bricks,
            levels,
            storeys,
        },
    ))
}

/// The PNG bytes of `mason generate scene`.
pub fn scene(size: u32, robots: usize, seed: u64) -> CliResult<Vec<u8>> {
    const MAX_SIZE: u32 = 4096;
    if !(30..=MAX_SIZE).contains(&size) {
        return Err(input_error(format!(
            "--size {size}: must lie in 30..={MAX_SIZE} cells"
        )));
    }
    let max_agents = mason_crew::limits::MAX_AGENTS;
    if robots == 0 || robots > max_agents {
        return Err(input_error(format!(
            "--robots {robots}: must lie in 1..={max_agents}"
        )));
    }
    let (grid, starts, goals) = mason_crew::generate::birdseye_scene(size, size, robots, seed)
        .ok_or_else(|| {
            input_error(format!(
                "--robots {robots}: a {size}×{size} warehouse has no room for that many robots and goals apart"
            ))
        })?;
    Ok(mason_crew::image::birdseye_png(&grid, &starts, &goals))
}
