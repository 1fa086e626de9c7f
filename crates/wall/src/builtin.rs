//! The built-in walls used by `mason demo` and `mason bench thesis`.

use crate::text::{parse_layer_text, parse_mbzirc};
use crate::wall::Wall;

/// A built-in wall: its name, what it is, and its layer text (top layer first).
#[derive(Clone, Copy, Debug)]
pub struct BuiltinWall {
    /// Short name, usable as `builtin:NAME` on the command line.
    pub name: &'static str,
    /// One line on what it is.
    pub description: &'static str,
    /// The design text.
    pub text: &'static str,
    /// True when `text` is in the MBZIRC 21-token pattern.
    pub mbzirc: bool,
}

/// All built-in walls, smallest first.
pub const BUILTIN_WALLS: [BuiltinWall; 4] = [
    BuiltinWall {
        name: "thesis-2x5",
        description: "thesis-size wall: 2 levels of 5 bricks",
        text: "R G B G R\nG B R R G\n",
        mbzirc: false,
    },
    BuiltinWall {
        name: "levels5-width5",
        description: "thesis Table 3.4 size: 5 levels of 5 bricks (25)",
        text: "R R R R R\nR R G R R\nR G R G R\nG R B R G\nB G R G B\n",
        mbzirc: false,
    },
    BuiltinWall {
        name: "levels5-width10",
        description: "thesis Table 3.5 size: 5 levels of 10 bricks (50)",
        text: "R R G R R R G R R R\nR G R R G R R G R R\nR G R G R B R G R R\nG R G B R G R G R G\nO G R B G R G B R G\n",
        mbzirc: false,
    },
    BuiltinWall {
        name: "mbzirc",
        description: "MBZIRC pattern: 2 layers of 3 segments × 7 bricks",
        text: "R G B G R R G  G R B R G R R  R B G G R R G\nO B G R R G B  B O G R G R R  G G B O R R B\n",
        mbzirc: true,
    },
];

impl BuiltinWall {
    /// Parses the built-in wall. Built-in texts are valid by construction (tested).
    pub fn wall(&self) -> Wall {
        let name = format!("builtin:{}", self.name);
        let parsed = if self.mbzirc {
            parse_mbzirc(self.text, &name)
        } else {
            parse_layer_text(self.text, &name)
        };
        parsed.unwrap_or_else(|e| panic!("built-in wall {} is invalid: {e}", self.name))
    }
}

/// The built-in wall called `name`.
pub fn builtin(name: &str) -> Option<&'static BuiltinWall> {
    BUILTIN_WALLS.iter().find(|w| w.name == name)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_builtin_wall_parses_with_the_promised_shape() {
        let sizes: Vec<(u32, usize)> = BUILTIN_WALLS
            .iter()
            .map(|b| (b.wall().levels(), b.wall().len()))
            .collect();
        assert_eq!(sizes[0], (2, 10));
        // Tables 3.4 and 3.5: 5 levels, 25 and 50 bricks, at most 5 and 10 on a level.
        assert_eq!(sizes[1], (5, 25));
        assert_eq!(sizes[2], (5, 50));
        assert_eq!(sizes[3], (2, 42));
        for b in &BUILTIN_WALLS[1..3] {
            let w = b.wall();
            let widest = (1..=5)
                .map(|l| w.bricks().iter().filter(|x| x.level == l).count())
                .max()
                .unwrap();
            assert!(widest <= if b.name.ends_with("5") { 5 } else { 10 });
        }
    }
}
