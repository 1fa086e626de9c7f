//! Inputs for the commands: the design flags, and reading through [`mason_io`] with its
//! warnings shown on stderr.

use crate::fail::CliResult;
use mason_io::{Format, Sizes};
use mason_wall::Wall;

/// Where a wall design comes from, and how to read it.
#[derive(clap::Args, Clone)]
pub struct DesignArgs {
    /// Wall design: a layer-text, MBZIRC, PNG or CMCP file, or builtin:NAME
    /// (thesis-2x5, levels5-width5, levels5-width10, mbzirc)
    pub design: String,
    /// How to read the design
    #[arg(long, value_enum, default_value = "auto")]
    pub format: Format,
    /// Size table for CMCP walls
    #[arg(long, value_enum, default_value = "yaml")]
    pub cmcp_sizes: Sizes,
    /// CMCP walls: refuse floating bricks and overlapping same-level bricks instead of warning
    #[arg(long)]
    pub strict: bool,
}

impl DesignArgs {
    /// Reads the wall; a CMCP wall's warnings go to stderr.
    pub fn load(&self) -> CliResult<Wall> {
        let loaded = mason_io::load_wall(&self.design, self.format, self.cmcp_sizes, self.strict)?;
        for w in &loaded.warnings {
            eprintln!("mason: warning: {w}");
        }
        Ok(loaded.wall)
    }
}
