//! MovingAI `.map` and `.scen` readers (Sturtevant 2012; Stern et al. 2019).
//!
//! A map is `type octile`, `height H`, `width W`, `map`, then H rows of W characters:
//! `.`, `G` and `S` are free; `@`, `O`, `T` and `W` are blocked. A scenario is `version 1`
//! and then one agent per line: `bucket map W H start_x start_y goal_x goal_y optimal_length`,
//! with x the column and y the row, (0,0) at the top left.

use crate::error::{CrewError, Location};
use crate::grid::{Cell, Grid};

/// `s` cut to 80 characters for a message.
fn shown(s: &str) -> String {
    match s.char_indices().nth(80) {
        Some((i, _)) => format!("{}… ({} characters)", &s[..i], s.chars().count()),
        None => s.to_string(),
    }
}

/// Reads a MovingAI `.map` file.
pub fn parse_map(text: &str, source_name: &str) -> Result<Grid, CrewError> {
    let err =
        |line: usize, reason: String| CrewError::new(source_name, Location::Line(line), reason);
    let mut lines = text
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l.trim_end_matches('\r')));
    let mut width: Option<u32> = None;
    let mut height: Option<u32> = None;
    let mut saw_map = false;
    for (no, line) in lines.by_ref() {
        let line = line.trim();
        if line.is_empty() {
            continue;
        }
        let mut words = line.split_whitespace();
        let key = words.next().unwrap_or_default();
        match key {
            "type" => {}
            "height" | "width" => {
                let value = words
                    .next()
                    .ok_or_else(|| err(no, format!("`{key}` needs a number")))?;
                let n: u32 = value
                    .parse()
                    .ok()
                    .filter(|n| *n > 0 && *n <= 1 << 15)
                    .ok_or_else(|| {
                        err(
                            no,
                            format!(
                                "{key} `{}` is not a whole number in 1..=32768",
                                shown(value)
                            ),
                        )
                    })?;
                if key == "height" {
                    height = Some(n);
                } else {
                    width = Some(n);
                }
            }
            "map" => {
                saw_map = true;
                break;
            }
            _ => {
                return Err(err(
                    no,
                    format!(
                        "unexpected `{}` in the header (expected type, height, width, map)",
                        shown(key)
                    ),
                ))
            }
        }
    }
    if !saw_map {
        return Err(CrewError::new(
            source_name,
            Location::Whole,
            "not a MovingAI map: no `map` line (header is type, height, width, map)",
        ));
    }
    let (Some(width), Some(height)) = (width, height) else {
        return Err(CrewError::new(
            source_name,
            Location::Whole,
            "the header needs both `height` and `width`",
        ));
    };
    if u64::from(width) * u64::from(height) > crate::limits::MAX_CELLS {
        return Err(CrewError::new(
            source_name,
            Location::Whole,
            format!(
                "{width}×{height} is more than the {} cells a map may have (mason_crew::limits::MAX_CELLS)",
                crate::limits::MAX_CELLS
            ),
        ));
    }
    let mut blocked = Vec::with_capacity(width as usize * height as usize);
    let mut rows = 0u32;
    let mut last_line = 0;
    for (no, line) in lines {
        last_line = no;
        if rows == height {
            if line.trim().is_empty() {
                continue;
            }
            return Err(err(
                no,
                format!("more than the {height} rows the header declares"),
            ));
        }
        let cells = line.chars().count();
        if cells != width as usize {
            return Err(err(
                no,
                format!("row has {cells} cells, the header says width {width}"),
            ));
        }
        let chars: Vec<char> = line.chars().collect();
        for (col, ch) in chars.into_iter().enumerate() {
            blocked.push(match ch {
                '.' | 'G' | 'S' => false,
                '@' | 'O' | 'T' | 'W' => true,
                other => {
                    return Err(err(
                        no,
                        format!(
                            "column {col}: unknown terrain `{other}` (free . G S, blocked @ O T W)"
                        ),
                    ))
                }
            });
        }
        rows += 1;
    }
    if rows < height {
        return Err(err(
            last_line.max(1),
            format!("only {rows} rows, the header says height {height}"),
        ));
    }
    Ok(Grid::new(width, height, blocked))
}

/// One agent of a scenario.
#[derive(Clone, Debug, PartialEq)]
pub struct ScenAgent {
    /// Start cell.
    pub start: Cell,
    /// Goal cell.
    pub goal: Cell,
    /// The optimal single-agent path length the file gives (octile, diagonal √2).
    pub optimal_length: f64,
    /// 1-based line in the file.
    pub line: usize,
}

/// Reads a MovingAI `.scen` file against its map. Only the first `limit` agents are read
/// (and checked), as `--agents N` asks.
pub fn parse_scen(
    text: &str,
    source_name: &str,
    grid: &Grid,
    limit: usize,
) -> Result<Vec<ScenAgent>, CrewError> {
    let err =
        |line: usize, reason: String| CrewError::new(source_name, Location::Line(line), reason);
    let mut agents = Vec::new();
    for (i, raw) in text.lines().enumerate() {
        if agents.len() == limit {
            break;
        }
        let no = i + 1;
        let line = raw.trim();
        if line.is_empty() {
            continue;
        }
        if agents.len() == crate::limits::MAX_AGENTS {
            return Err(err(
                no,
                format!(
                    "more than {} agents (mason_crew::limits::MAX_AGENTS); take fewer with --agents N",
                    crate::limits::MAX_AGENTS
                ),
            ));
        }
        if line.starts_with("version") {
            if i != 0 {
                return Err(err(no, "`version` must be the first line".into()));
            }
            continue;
        }
        // At most 10 fields are kept: a huge line is refused without splitting all of it.
        let fields: Vec<&str> = if line.contains('\t') {
            line.split('\t').map(str::trim).take(10).collect()
        } else {
            line.split_whitespace().take(10).collect()
        };
        if fields.len() != 9 {
            return Err(err(
                no,
                format!(
                    "a scenario line needs 9 fields `bucket map W H start_x start_y goal_x goal_y length`, found {}",
                    if fields.len() == 10 { "more".to_string() } else { fields.len().to_string() }
                ),
            ));
        }
        let int = |k: usize, name: &str| -> Result<i64, CrewError> {
            fields[k].parse::<i64>().map_err(|_| {
                err(
                    no,
                    format!("{name} `{}` is not a whole number", shown(fields[k])),
                )
            })
        };
        let (w, h) = (int(2, "map width")?, int(3, "map height")?);
        if w != grid.width() as i64 || h != grid.height() as i64 {
            return Err(err(
                no,
                format!(
                    "scenario is for a {w}×{h} map, the map is {}×{}",
                    grid.width(),
                    grid.height()
                ),
            ));
        }
        let cell = |kx: usize, ky: usize, what: &str| -> Result<Cell, CrewError> {
            let (x, y) = (
                int(kx, &format!("{what} x"))?,
                int(ky, &format!("{what} y"))?,
            );
            let c = grid
                .cell(x, y)
                .ok_or_else(|| err(no, format!("{what} ({x}, {y}) is outside the {w}×{h} map")))?;
            if !grid.is_free(c) {
                return Err(err(no, format!("{what} ({x}, {y}) is on an obstacle")));
            }
            Ok(c)
        };
        let start = cell(4, 5, "start")?;
        let goal = cell(6, 7, "goal")?;
        let optimal_length: f64 = fields[8]
            .parse()
            .ok()
            .filter(|v: &f64| v.is_finite() && *v >= 0.0)
            .ok_or_else(|| {
                err(
                    no,
                    format!("optimal length `{}` is not a number ≥ 0", shown(fields[8])),
                )
            })?;
        agents.push(ScenAgent {
            start,
            goal,
            optimal_length,
            line: no,
        });
    }
    if agents.is_empty() {
        return Err(CrewError::new(
            source_name,
            Location::Whole,
            "the scenario has no agents",
        ));
    }
    if agents.len() < limit && limit != usize::MAX {
        return Err(CrewError::new(
            source_name,
            Location::Whole,
            format!(
                "--agents {limit} asked, but the scenario has only {}",
                agents.len()
            ),
        ));
    }
    Ok(agents)
}

#[cfg(test)]
mod tests {
    use super::*;

    const MAP: &str = "type octile\nheight 3\nwidth 4\nmap\n....\n.@@.\n....\n";

    #[test]
    fn reads_a_map() {
        let g = parse_map(MAP, "m").unwrap();
        assert_eq!((g.width(), g.height()), (4, 3));
        assert!(!g.is_free(g.cell(1, 1).unwrap()));
        assert_eq!(g.free_count(), 10);
    }

    #[test]
    fn malformed_maps_name_the_line() {
        let cases = [
            (
                "type octile\nheight 2\nwidth 2\nmap\n..\n.x\n",
                "m:6: column 1: unknown terrain `x`",
            ),
            (
                "type octile\nheight 2\nwidth 3\nmap\n..\n...\n",
                "m:5: row has 2 cells",
            ),
            (
                "type octile\nheight 3\nwidth 2\nmap\n..\n..\n",
                "m:6: only 2 rows",
            ),
            (
                "type octile\nheight x\nwidth 2\nmap\n",
                "m:2: height `x` is not",
            ),
            (
                "type octile\nwidth 2\nmap\n..\n",
                "m: the header needs both",
            ),
            ("hello\n", "m:1: unexpected `hello`"),
            ("", "m: not a MovingAI map"),
            (
                "type octile\nheight 1\nwidth 2\nmap\n..\n..\n",
                "m:6: more than the 1 rows",
            ),
        ];
        for (text, want) in cases {
            let e = parse_map(text, "m").unwrap_err().to_string();
            assert!(e.starts_with(want), "{e:?} should start with {want:?}");
        }
    }

    #[test]
    fn reads_a_scenario() {
        let g = parse_map(MAP, "m").unwrap();
        let scen =
            "version 1\n0\tm.map\t4\t3\t0\t0\t3\t2\t3.82842712\n0\tm.map\t4\t3\t3\t0\t0\t2\t3.8\n";
        let a = parse_scen(scen, "s", &g, usize::MAX).unwrap();
        assert_eq!(a.len(), 2);
        assert_eq!(g.xy(a[0].goal), (3, 2));
        assert_eq!(a[1].line, 3);
        assert_eq!(parse_scen(scen, "s", &g, 1).unwrap().len(), 1);
    }

    #[test]
    fn malformed_scenarios_name_the_line() {
        let g = parse_map(MAP, "m").unwrap();
        let cases = [
            (
                "version 1\n0 m 4 3 1 1 3 2 1\n",
                "s:2: start (1, 1) is on an obstacle",
            ),
            (
                "version 1\n0 m 4 3 0 0 9 2 1\n",
                "s:2: goal (9, 2) is outside",
            ),
            (
                "version 1\n0 m 5 3 0 0 1 2 1\n",
                "s:2: scenario is for a 5×3 map",
            ),
            (
                "version 1\n0 m 4 3 0 0 1\n",
                "s:2: a scenario line needs 9 fields",
            ),
            ("version 1\n0 m 4 3 a 0 1 2 1\n", "s:2: start x `a` is not"),
            (
                "version 1\n0 m 4 3 0 0 1 2 -1\n",
                "s:2: optimal length `-1`",
            ),
            ("version 1\n", "s: the scenario has no agents"),
        ];
        for (text, want) in cases {
            let e = parse_scen(text, "s", &g, usize::MAX)
                .unwrap_err()
                .to_string();
            assert!(e.starts_with(want), "{e:?} should start with {want:?}");
        }
        let e = parse_scen("0 m 4 3 0 0 1 2 1\n", "s", &g, 5).unwrap_err();
        assert!(e.to_string().contains("--agents 5 asked"), "{e}");
    }
}

/// A grid as a MovingAI `.map` (`.` free, `@` blocked).
pub fn map_text(grid: &Grid) -> String {
    let mut s = format!(
        "type octile\nheight {}\nwidth {}\nmap\n",
        grid.height(),
        grid.width()
    );
    for y in 0..grid.height() {
        for x in 0..grid.width() {
            let free = grid
                .cell(i64::from(x), i64::from(y))
                .is_some_and(|c| grid.is_free(c));
            s.push(if free { '.' } else { '@' });
        }
        s.push('\n');
    }
    s
}

/// Start–goal pairs as a MovingAI `.scen` for the map file `map_name`; the optimal length
/// column is the octile distance (a lower bound, as the field's readers expect of it).
pub fn scen_text(map_name: &str, grid: &Grid, pairs: &[(Cell, Cell)]) -> String {
    let mut s = String::from("version 1\n");
    for &(start, goal) in pairs {
        let ((sx, sy), (gx, gy)) = (grid.xy(start), grid.xy(goal));
        let (dx, dy) = (sx.abs_diff(gx), sy.abs_diff(gy));
        let octile =
            f64::from(dx.max(dy) - dx.min(dy)) + std::f64::consts::SQRT_2 * f64::from(dx.min(dy));
        s.push_str(&format!(
            "0\t{map_name}\t{}\t{}\t{sx}\t{sy}\t{gx}\t{gy}\t{octile:.8}\n",
            grid.width(),
            grid.height()
        ));
    }
    s
}

#[cfg(test)]
mod writer_tests {
    use super::*;

    #[test]
    fn written_maps_and_scenarios_read_back() {
        let grid = parse_map("type octile\nheight 2\nwidth 3\nmap\n.@.\n...\n", "m").unwrap();
        let text = map_text(&grid);
        assert_eq!(parse_map(&text, "m").unwrap(), grid);
        let pairs = [(Cell(0), Cell(5)), (Cell(3), Cell(2))];
        let scen = scen_text("m.map", &grid, &pairs);
        let agents = parse_scen(&scen, "s", &grid, 2).unwrap();
        let back: Vec<(Cell, Cell)> = agents.iter().map(|a| (a.start, a.goal)).collect();
        assert_eq!(back, pairs);
    }
}
