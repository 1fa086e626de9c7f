//! `mason wall show`: parse, validate and describe a wall design.

use crate::fail::{write_file, CliResult};
use crate::input::DesignArgs;
use mason_wall::Wall;
use std::path::PathBuf;

/// `mason wall` subcommands.
#[derive(clap::Subcommand)]
pub enum WallCommand {
    /// Parse, validate and describe a wall design
    Show {
        #[command(flatten)]
        design: DesignArgs,
        /// Draw the wall as SVG
        #[arg(long)]
        svg: Option<PathBuf>,
        /// Print JSON instead of a table
        #[arg(long)]
        json: bool,
    },
}

/// `mason wall …`.
pub fn run(command: WallCommand) -> CliResult<()> {
    let WallCommand::Show { design, svg, json } = command;
    let wall = design.load()?;
    if let Some(path) = svg {
        write_file(&path, mason_report::wall_svg(&wall, None).as_bytes())?;
    }
    if json {
        crate::cmd::plan::print_json(&mason_report::WallDoc(&wall))?;
    } else {
        print!("{}", wall_table(&wall));
    }
    Ok(())
}

/// A table of bricks with ids, levels, supports and neighbours.
pub fn wall_table(wall: &Wall) -> String {
    let mut out = format!(
        "wall {}: {} bricks, {} levels\n   id  type    level  seg   x from–to (m)   supports        neighbours\n",
        wall.name(),
        wall.len(),
        wall.levels()
    );
    let labels = |ids: &[mason_wall::BrickId]| {
        let v: Vec<String> = ids
            .iter()
            .map(|&i| wall.brick(i).label.to_string())
            .collect();
        if v.is_empty() {
            "-".to_string()
        } else {
            v.join(",")
        }
    };
    for id in wall.ids() {
        let b = wall.brick(id);
        out.push_str(&format!(
            "{:>5}  {:<6}  {:>5}  {:>3}  {:>6.2} – {:<6.2}  {:<14}  {}\n",
            b.label,
            b.kind.name(),
            b.level,
            b.segment,
            b.footprint.x0,
            b.footprint.x1,
            labels(wall.supports(id)),
            labels(wall.neighbours(id))
        ));
    }
    for w in wall.warnings() {
        out.push_str(&format!("warning: {w}\n"));
    }
    out
}
