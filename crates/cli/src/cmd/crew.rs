//! `mason crew`: read a map and a scenario (or a bird's-eye image), solve, validate, print.

use crate::cmd::plan::{pretty, report_overrun, time_limit};
use crate::fail::{check_outputs, input_error, no_solution, write_all, CliResult};
use mason_crew::{
    AssignMethod, Budget, Cell, CrewConfig, CrewOutcome, Grid, Instance, PlanMetrics, Status,
};
use mason_io::crew::{check_size, choices, RawChoices, LACAM_DEFAULT_LIMIT_S};
use serde_json::{json, Value};
use std::path::PathBuf;
use std::time::Duration;

/// `mason crew`'s options.
#[derive(clap::Args)]
pub struct CrewArgs {
    /// MovingAI .map file or occupancy PNG (dark pixels are obstacles); omit with --image
    pub map: Option<String>,
    /// MovingAI .scen file with the robots' starts and goals
    #[arg(long)]
    pub scen: Option<PathBuf>,
    /// Take the first N agents of the scenario (default: all)
    #[arg(long, allow_negative_numbers = true)]
    pub agents: Option<usize>,
    /// The floor seen from above: a photograph (PNG or JPEG; give --grid, --cell-px or paint
    /// grid lines on the floor) or a one-pixel-per-cell map of at most 16 colours (robots red,
    /// goals green, obstacles dark)
    #[arg(long)]
    pub image: Option<PathBuf>,
    /// --image: the floor grid, W×H cells (e.g. 24x16)
    #[arg(long, value_name = "WxH")]
    pub grid: Option<String>,
    /// --image: the cell size in pixels (a straight-down view filling the image)
    #[arg(long, value_name = "N")]
    pub cell_px: Option<f64>,
    /// --image: the floor's corners in the image, "x1,y1 x2,y2 x3,y3 x4,y4" (top-left,
    /// top-right, bottom-right, bottom-left of the grid), for a tilted or perspective camera
    #[arg(long)]
    pub corners: Option<String>,
    /// --image: the robots' colour (red, orange, yellow, green, cyan, blue, magenta, #rrggbb
    /// or hue:DEGREES)
    #[arg(long, default_value = "red")]
    pub robot_colour: String,
    /// --image: the goals' colour
    #[arg(long, default_value = "green")]
    pub goal_colour: String,
    /// --image: accept a photograph with more goals than robots (refused by default: a goal
    /// without a robot may be a robot the reading lost)
    #[arg(long)]
    pub spare_goals: bool,
    /// --image: cells you settle as blocked, "x,y x,y …" (column, row): read as blocked and
    /// never refused. For the cells a refusal names, once you have looked at them (--audit
    /// --overlay shows every one)
    #[arg(long, value_name = "CELLS", allow_hyphen_values = true)]
    pub blocked_cells: Option<String>,
    /// --image: cells you settle as free, "x,y x,y …", likewise
    #[arg(long, value_name = "CELLS", allow_hyphen_values = true)]
    pub free_cells: Option<String>,
    /// --image: draw the image with the grid, blocked cells, robots, goals and paths as read
    #[arg(long, value_name = "FILE.svg")]
    pub overlay: Option<PathBuf>,
    /// --image: write the grid read as a MovingAI .map
    #[arg(long, value_name = "F.map")]
    pub save_map: Option<PathBuf>,
    /// --image: write the robots and their assigned goals as a MovingAI .scen
    #[arg(long, value_name = "F.scen")]
    pub save_scen: Option<PathBuf>,
    /// --image: read past every refusal about a cell (half covered, a top may cover it,
    /// unlike the floor, a shadow nothing casts, a painted line that does not show) and list
    /// them all on stderr, each cell decided as the check found it before doubting it; plans
    /// nothing, writes --overlay (the refusals in magenta), --save-map and --json (the reading
    /// and the refusals), exit 2 when any was found. A robot's or goal's refusal still stops it
    #[arg(long)]
    pub audit: bool,
    /// given (scenario pairing; default with --scen), perm (the paper's n!), hungarian,
    /// path (Hungarian on path lengths) or joint (interchangeable robots: TSWAP solves the
    /// assignment and the paths together; default with --image)
    #[arg(long)]
    pub assign: Option<String>,
    /// Single-robot paths: astar or prm
    #[arg(long, default_value = "astar")]
    pub paths: String,
    /// Collision resolution: paper (priority waits), st (prioritized space-time A*; default)
    /// or lacam (complete LaCAM, then refinement until --time-limit); not with --assign joint
    #[arg(long)]
    pub resolve: Option<String>,
    /// 4 or 8 (diagonals only past two free sides)
    #[arg(long, default_value = "8")]
    pub connectivity: String,
    /// Seed of the roadmap sampler and of lacam (same seed, same plan, unless --time-limit
    /// stops the restarts or the refinement)
    #[arg(long, default_value_t = 0, allow_negative_numbers = true)]
    pub seed: u64,
    /// lacam: refinement rounds at most (0: the first plan as it is; default: until
    /// --time-limit, or 1000 rounds in a row without improvement, then up to 8 new LaCAM plans
    /// refined the same way)
    #[arg(long)]
    pub refine_rounds: Option<u64>,
    /// lacam: refinement neighbourhoods planned side by side in one batch, on all cores
    /// (default 4; 1: one at a time, better on one core). The plan depends on it and on the
    /// seed, not on the cores
    #[arg(long)]
    pub refine_batch: Option<usize>,
    /// PRM samples
    #[arg(long, default_value_t = 2000, allow_negative_numbers = true)]
    pub samples: usize,
    /// PRM neighbours per node
    #[arg(long, default_value_t = 10, allow_negative_numbers = true)]
    pub neighbours: usize,
    /// Time budget in seconds (lacam: 60 when not given; it refines until then)
    #[arg(long, allow_negative_numbers = true)]
    pub time_limit: Option<f64>,
    /// Print JSON instead of a table
    #[arg(long)]
    pub json: bool,
    /// Draw the map, starts, goals and paths as SVG
    #[arg(long)]
    pub svg: Option<PathBuf>,
    /// Write the self-contained HTML replay of the plan
    #[arg(long)]
    pub html: Option<PathBuf>,
}

/// `mason crew`.
pub fn run(a: CrewArgs) -> CliResult<()> {
    let started = std::time::Instant::now();
    check_outputs(&[&a.svg, &a.html, &a.overlay, &a.save_map, &a.save_scen])?;
    let aerial = aerial_config(&a)?;
    if a.audit {
        return audit(&a, aerial.as_ref());
    }
    let limit = time_limit(a.time_limit)?;
    let prm = mason_crew::PrmConfig {
        samples: a.samples,
        neighbours: a.neighbours,
        seed: a.seed,
    };
    let choices = choices(
        RawChoices {
            assign: a.assign.as_deref(),
            paths: &a.paths,
            resolve: a.resolve.as_deref(),
            connectivity: &a.connectivity,
            seed: a.seed,
            refine_rounds: a.refine_rounds,
            refine_batch: a.refine_batch,
        },
        prm,
        a.scen.is_some(),
    )?;
    // lacam is anytime and, on a hard instance, its search could grow until memory runs out:
    // without a limit it gets a default one.
    let limit = match (limit, choices.config.resolve, choices.config.assign) {
        (None, mason_crew::Resolution::Lacam, a) if a != mason_crew::AssignMethod::Joint => {
            Some(LACAM_DEFAULT_LIMIT_S)
        }
        (l, _, _) => l,
    };
    let input = mason_io::CrewInput {
        map: a.map.as_deref(),
        scen: a.scen.as_deref(),
        agents: a.agents,
        image: a.image.as_deref(),
    };
    let (inst, source, view) = match (&a.image, &a.map, &a.scen) {
        (Some(image), None, None) => {
            if a.agents.is_some() {
                return Err(input_error("--agents applies to --scen, not to --image"));
            }
            let v = mason_io::load_view(
                image,
                aerial.as_ref(),
                choices.connectivity,
                a.overlay.is_some(),
            )?;
            (v.inst.clone(), v.name.clone(), Some(v))
        }
        _ => {
            let (inst, source) = mason_io::load_crew(&input, choices.connectivity)?;
            (inst, source, None)
        }
    };
    check_size(&inst, &source)?;
    let result = run_solve(&inst, &choices.config, limit)?;
    let mut files: Vec<(PathBuf, Vec<u8>)> = Vec::new();
    if let Some(path) = &a.svg {
        let title = format!(
            "{source} — {} robots, {} ({})",
            inst.robot_count(),
            result.outcome.status,
            method_label(&choices.config)
        );
        let paths = result.outcome.paths.clone().unwrap_or_default();
        let svg = mason_report::crew_svg(
            &title,
            &inst.grid,
            &inst.robots,
            &result.outcome.goals,
            &paths,
        );
        files.push((path.clone(), svg.into_bytes()));
    }
    if let (Some(path), Some(paths)) = (&a.html, &result.outcome.paths) {
        let title = format!(
            "{source} — {} robots ({})",
            inst.robot_count(),
            method_label(&choices.config)
        );
        let page = mason_report::crew_replay_html(&title, &inst.grid, &result.outcome.goals, paths);
        files.push((path.clone(), page.into_bytes()));
    }
    if let Some(view) = &view {
        files.extend(view_files(&a, view, &result)?);
    }
    write_all(&files)?;
    if a.json {
        let mut v = crew_json(&inst, &source, &choices.config, a.seed, &result);
        if let Some(r) = view.as_ref().and_then(|v| v.aerial.as_ref()) {
            v["reading"] = reading_json(r);
        }
        println!("{}", pretty(&v));
    } else {
        print!("{}", crew_table(&inst, &source, &choices.config, &result));
    }
    report_overrun(limit, started, result.outcome.stats.elapsed.as_secs_f64());
    exit_for(&result)
}

/// `mason crew --image … --audit`: the reading past every cell's refusal, and the refusals.
fn audit(a: &CrewArgs, aerial: Option<&mason_crew::aerial::AerialConfig>) -> CliResult<()> {
    let Some(image) = &a.image else {
        return Err(input_error("--audit reads a photograph: give --image"));
    };
    if a.map.is_some() || a.scen.is_some() {
        return Err(input_error(
            "--audit reads --image alone, not --map or --scen",
        ));
    }
    if a.svg.is_some() || a.html.is_some() || a.save_scen.is_some() {
        return Err(input_error(
            "--audit plans nothing: --svg, --html and --save-scen need a plan (--overlay, --save-map and --json show the reading)",
        ));
    }
    let mason_io::AuditedView {
        name,
        audited,
        bytes,
    } = mason_io::audit_view(image, aerial, a.overlay.is_some())?;
    let r = &audited.reading;
    for doubt in &audited.doubts {
        eprintln!("doubt: {doubt}");
    }
    let blocked = r.grid.len() - r.grid.free_count();
    let mut files = Vec::new();
    if let Some(path) = &a.overlay {
        use mason_crew::Location;
        let doubts: Vec<((f64, f64), String)> = audited
            .doubts
            .iter()
            .filter_map(|d| match d.location {
                Location::Pixel(x, y) => Some(((f64::from(x), f64::from(y)), d.reason.clone())),
                _ => None,
            })
            .collect();
        let title = format!(
            "{name} — audited {}×{} cells, {blocked} blocked, {} robots, {} goals{}; {} (magenta)",
            r.grid.width(),
            r.grid.height(),
            r.robots.len(),
            r.goals.len(),
            settled_note(r),
            refusals(audited.doubts.len())
        );
        let svg = mason_report::aerial_audit_svg(
            &title,
            &bytes,
            r,
            (&r.robot_cells(), &r.goal_cells(), &[]),
            &doubts,
        );
        files.push((path.clone(), svg.into_bytes()));
    }
    if let Some(path) = &a.save_map {
        files.push((
            path.clone(),
            mason_crew::movingai::map_text(&r.grid).into_bytes(),
        ));
    }
    write_all(&files)?;
    if a.json {
        let doubts: Vec<String> = audited.doubts.iter().map(|d| d.to_string()).collect();
        let v = json!({
            "source": name,
            "reading": reading_json(r),
            "doubts": doubts,
        });
        println!("{}", pretty(&v));
    } else {
        println!(
            "{name}: read {}×{} cells, {blocked} blocked, {} robots, {} goals, past {}",
            r.grid.width(),
            r.grid.height(),
            r.robots.len(),
            r.goals.len(),
            refusals(audited.doubts.len())
        );
    }
    match audited.doubts.len() {
        0 => Ok(()),
        n => Err(input_error(format!(
            "{name}: {} (above); read without --audit, it stops at the first",
            refusals(n)
        ))),
    }
}

/// "1 refusal about a cell", "3 refusals about cells".
fn refusals(n: usize) -> String {
    if n == 1 {
        "1 refusal about a cell".to_string()
    } else {
        format!("{n} refusals about cells")
    }
}

/// ", 2 cells settled (dashed orange)" for a title, when the operator settled any, and ", 3
/// cells a shelf of the floor's colour (dotted magenta)" and ", 1 cell half covered but free
/// under a robot or a goal (dotted white)" when the reader read any.
fn settled_note(r: &mason_crew::aerial::AerialReading) -> String {
    let cells = |n: usize| {
        if n == 1 {
            "1 cell".to_string()
        } else {
            format!("{n} cells")
        }
    };
    let mut note = String::new();
    if !r.settled.is_empty() {
        note += &format!(", {} settled (dashed orange)", cells(r.settled.len()));
    }
    if !r.floor_tops.is_empty() {
        note += &format!(
            ", {} a shelf of the floor's colour (dotted magenta)",
            cells(r.floor_tops.len())
        );
    }
    if !r.under_marks.is_empty() {
        note += &format!(
            ", {} half covered but free under a robot or a goal (dotted white)",
            cells(r.under_marks.len())
        );
    }
    if r.balanced_on_middles {
        note += ", white balance on the cells' middles (painted lines tint the floor's)";
    }
    note
}

/// The aerial reader's settings, when any of its flags is given.
fn aerial_config(a: &CrewArgs) -> CliResult<Option<mason_crew::aerial::AerialConfig>> {
    use mason_crew::aerial::{colour::Hue, AerialConfig};
    let given = a.grid.is_some()
        || a.cell_px.is_some()
        || a.corners.is_some()
        || a.robot_colour != "red"
        || a.goal_colour != "green"
        || a.spare_goals
        || a.blocked_cells.is_some()
        || a.free_cells.is_some();
    if a.image.is_none() {
        if given || a.overlay.is_some() || a.save_map.is_some() || a.save_scen.is_some() {
            return Err(input_error(
                "--grid, --cell-px, --corners, --robot-colour, --goal-colour, --spare-goals, --blocked-cells, --free-cells, --overlay, --save-map and --save-scen apply to --image",
            ));
        }
        return Ok(None);
    }
    if !given {
        return Ok(None);
    }
    let grid = a
        .grid
        .as_deref()
        .map(|g| {
            let parsed = g.split_once(['x', 'X', '×']).and_then(|(w, h)| {
                Some((w.trim().parse::<u32>().ok()?, h.trim().parse::<u32>().ok()?))
            });
            parsed.ok_or_else(|| input_error(format!("--grid {g}: give W×H cells, e.g. 24x16")))
        })
        .transpose()?;
    let corners = a.corners.as_deref().map(parse_corners).transpose()?;
    let colour =
        |flag: &str, text: &str| Hue::parse(text).map_err(|e| input_error(format!("--{flag} {e}")));
    Ok(Some(AerialConfig {
        grid,
        cell_px: a.cell_px,
        corners,
        robot_colour: colour("robot-colour", &a.robot_colour)?,
        goal_colour: colour("goal-colour", &a.goal_colour)?,
        spare_goals: a.spare_goals,
        blocked_cells: parse_cells("blocked-cells", a.blocked_cells.as_deref())?,
        free_cells: parse_cells("free-cells", a.free_cells.as_deref())?,
    }))
}

/// `"x,y x,y …"`: cells by column and row (none when the flag is not given).
fn parse_cells(flag: &str, text: Option<&str>) -> CliResult<Vec<(u32, u32)>> {
    let Some(text) = text else {
        return Ok(Vec::new());
    };
    let cells: Option<Vec<(u32, u32)>> = text
        .split_whitespace()
        .map(|c| {
            let (x, y) = c.split_once(',')?;
            Some((x.trim().parse().ok()?, y.trim().parse().ok()?))
        })
        .collect();
    match cells {
        Some(cells) if !cells.is_empty() => Ok(cells),
        _ => Err(input_error(format!(
            "--{flag} {text}: give cells as column,row pairs separated by spaces, e.g. \"3,4 7,0\""
        ))),
    }
}

/// `"x1,y1 x2,y2 x3,y3 x4,y4"`.
fn parse_corners(text: &str) -> CliResult<[(f64, f64); 4]> {
    let bad = || {
        input_error(format!(
            "--corners {text}: give four x,y pixel positions, \"x1,y1 x2,y2 x3,y3 x4,y4\" (top-left, top-right, bottom-right, bottom-left)"
        ))
    };
    let points: Vec<(f64, f64)> = text
        .split_whitespace()
        .map(|p| {
            let (x, y) = p.split_once(',')?;
            let (x, y) = (x.parse::<f64>().ok()?, y.parse::<f64>().ok()?);
            (x.is_finite() && y.is_finite()).then_some((x, y))
        })
        .collect::<Option<_>>()
        .ok_or_else(bad)?;
    points.try_into().map_err(|_| bad())
}

/// The overlay, the map and the scenario of an image, as asked.
fn view_files(
    a: &CrewArgs,
    view: &mason_io::View,
    result: &CrewResult,
) -> CliResult<Vec<(PathBuf, Vec<u8>)>> {
    let inst = &view.inst;
    let mut files = Vec::new();
    if let Some(path) = &a.overlay {
        let reading = view.aerial.as_ref().ok_or_else(|| {
            input_error("--overlay draws a photograph's reading; this image is a one-pixel-per-cell map (use --svg)")
        })?;
        let title = format!(
            "{} — read {}×{} cells, {} robots, {} goals{}; {}",
            view.name,
            inst.grid.width(),
            inst.grid.height(),
            reading.robots.len(),
            reading.goals.len(),
            settled_note(reading),
            result.outcome.status
        );
        let paths = result.outcome.paths.clone().unwrap_or_default();
        let svg = mason_report::aerial_svg(
            &title,
            &view.bytes,
            reading,
            &inst.robots,
            &result.outcome.goals,
            &paths,
        );
        files.push((path.clone(), svg.into_bytes()));
    }
    if let Some(path) = &a.save_map {
        files.push((
            path.clone(),
            mason_crew::movingai::map_text(&inst.grid).into_bytes(),
        ));
    }
    if let Some(path) = &a.save_scen {
        let map_name = a
            .save_map
            .as_ref()
            .and_then(|p| p.file_name())
            .map_or("map.map".to_string(), |n| n.to_string_lossy().into_owned());
        let pairs: Vec<(Cell, Cell)> = inst
            .robots
            .iter()
            .copied()
            .zip(result.outcome.goals.iter().copied())
            .collect();
        files.push((
            path.clone(),
            mason_crew::movingai::scen_text(&map_name, &inst.grid, &pairs).into_bytes(),
        ));
    }
    Ok(files)
}

/// The `reading` object of the JSON: grid, cell size, counts, every robot and goal.
pub fn reading_json(r: &mason_crew::aerial::AerialReading) -> Value {
    let mark = |m: &mason_crew::aerial::Mark| {
        json!({
            "cell": xy(&r.grid, m.cell),
            "floor": [m.floor.0, m.floor.1],
            "pixel": [m.pixel.0, m.pixel.1],
            "area_px": m.area,
            "confidence": m.confidence,
        })
    };
    let settled = |blocked: bool| -> Vec<[u32; 2]> {
        r.settled
            .iter()
            .filter(|s| s.1 == blocked)
            .map(|s| xy(&r.grid, s.0))
            .collect()
    };
    json!({
        "grid": [r.grid.width(), r.grid.height()],
        "grid_from": r.grid_source,
        "cell_px": r.cell_px,
        "image": [r.image_size.0, r.image_size.1],
        "corners": r.corners.iter().map(|c| [c.0, c.1]).collect::<Vec<_>>(),
        "counts": {
            "robots": r.robots.len(),
            "goals": r.goals.len(),
            "blocked": r.grid.len() - r.grid.free_count(),
        },
        "robots": r.robots.iter().map(mark).collect::<Vec<_>>(),
        "goals": r.goals.iter().map(mark).collect::<Vec<_>>(),
        "settled": {
            "blocked": settled(true),
            "free": settled(false),
        },
        "floor_tops": r.floor_tops.iter().map(|&c| xy(&r.grid, c)).collect::<Vec<_>>(),
        "under_marks": r.under_marks.iter().map(|&c| xy(&r.grid, c)).collect::<Vec<_>>(),
        "white_balance": if r.balanced_on_middles { "cell middles" } else { "floor" },
    })
}

/// "assign joint", "resolve lacam", … for titles.
pub fn method_label(config: &CrewConfig) -> String {
    if config.assign == AssignMethod::Joint {
        "joint (TSWAP)".into()
    } else {
        format!(
            "assign {:?}, paths {:?}, resolve {:?}",
            config.assign, config.paths, config.resolve
        )
        .to_lowercase()
    }
}

/// A solve with its validation.
pub struct CrewResult {
    /// The solver's outcome.
    pub outcome: CrewOutcome,
    /// The validator's metrics, when there is a plan.
    pub metrics: Option<PlanMetrics>,
    /// Each robot's fewest steps to its assigned goal (`None` when unreachable); empty when the
    /// solver gave the sum and there are too many robots to list.
    pub shortest: Vec<Option<u64>>,
}

/// Robots listed one per row in the text table.
const TABLE_ROWS: usize = 60;

impl CrewResult {
    /// Σ of the robots' shortest step distances (a lower bound on the sum of costs); `None`
    /// when some goal is unreachable.
    pub fn lower_bound(&self) -> Option<u64> {
        if self.shortest.is_empty() {
            return self.outcome.stats.lower_bound;
        }
        self.shortest.iter().copied().sum()
    }
}

/// Solves and validates (a plan the validator rejects is a bug, reported as such).
pub fn run_solve(
    inst: &Instance,
    config: &CrewConfig,
    limit: Option<f64>,
) -> CliResult<CrewResult> {
    let budget = match limit {
        Some(s) => Budget::time(Duration::from_secs_f64(s)),
        None => Budget::unlimited(),
    };
    let checked = mason_crew::solve_checked(inst, config, &budget).map_err(|e| match e {
        mason_crew::CheckedSolveError::Setup(e) => input_error(e.to_string()),
        e => input_error(format!("internal error: {e}")),
    })?;
    let outcome = checked.outcome;
    // Per robot only where the table shows it, or when the solver did not sum it already;
    // never past the time limit (a BFS per robot on a huge map takes seconds).
    let shortest = if (inst.robot_count() <= TABLE_ROWS || outcome.stats.lower_bound.is_none())
        && !budget.out_of_time()
    {
        mason_crew::shortest_steps(inst, &outcome.goals)
    } else {
        Vec::new()
    };
    Ok(CrewResult {
        outcome,
        metrics: checked.metrics,
        shortest,
    })
}

fn xy(grid: &Grid, c: Cell) -> [u32; 2] {
    let (x, y) = grid.xy(c);
    [x, y]
}

/// The JSON of DESIGN §7, with the inputs' parameters.
pub fn crew_json(
    inst: &Instance,
    source: &str,
    config: &CrewConfig,
    seed: u64,
    r: &CrewResult,
) -> Value {
    let g = &inst.grid;
    let o = &r.outcome;
    let agents: Vec<Value> = (0..inst.robot_count())
        .map(|i| {
            let path: Vec<[u32; 2]> = o
                .paths
                .as_ref()
                .map(|p| p[i].iter().map(|&c| xy(g, c)).collect())
                .unwrap_or_default();
            json!({"start": xy(g, inst.robots[i]), "goal": xy(g, o.goals[i]), "path": path})
        })
        .collect();
    json!({
        "map": {"source": source, "width": g.width(), "height": g.height()},
        "connectivity": inst.connectivity.degree(),
        "assign": format!("{:?}", config.assign).to_lowercase(),
        "paths": format!("{:?}", config.paths).to_lowercase(),
        "resolve": format!("{:?}", config.resolve).to_lowercase(),
        "prm": {"samples": config.prm.samples, "neighbours": config.prm.neighbours},
        "seed": seed,
        "refine_rounds_limit": config.refine.rounds,
        "refine_batch": config.refine.batch,
        "status": o.status,
        "reason": o.reason,
        "agents": agents,
        "sum_of_costs": r.metrics.map(|m| m.sum_of_costs),
        "makespan": r.metrics.map(|m| m.makespan),
        "lower_bound_sum_of_costs": r.lower_bound(),
        "stats": {
            "elapsed_ms": o.stats.elapsed.as_secs_f64() * 1e3,
            "first_solution_ms": o.stats.first_solution.map(|d| d.as_secs_f64() * 1e3),
            "tables_ms": o.stats.tables.map(|d| d.as_secs_f64() * 1e3),
            "guide_ms": o.stats.guide.map(|d| d.as_secs_f64() * 1e3),
            "first_sum_of_costs": o.stats.first_sum_of_costs,
            "configurations": o.stats.configurations,
            "refine_rounds": o.stats.refine_rounds,
            "improvements": o.stats.improvements,
            "restarts": o.stats.restarts,
            "expanded": o.stats.expanded,
            "waits": o.stats.waits,
            "peak_memory_mb": peak_memory_mb(),
        },
    })
}

/// A readable summary, with one row per robot for up to 60 robots.
pub fn crew_table(inst: &Instance, source: &str, config: &CrewConfig, r: &CrewResult) -> String {
    let g = &inst.grid;
    let o = &r.outcome;
    let mut s = format!(
        "{source}: {} robots on {}×{} ({} free cells), {}-connected; {}\n",
        inst.robot_count(),
        g.width(),
        g.height(),
        g.free_count(),
        inst.connectivity.degree(),
        method_label(config)
    );
    if let Some(paths) = &o.paths {
        if inst.robot_count() <= TABLE_ROWS {
            s.push_str(&format!(
                "  {:>5} {:>12} {:>12} {:>8} {:>9}\n",
                "robot", "start", "goal", "arrives", "shortest"
            ));
            for (i, p) in paths.iter().enumerate() {
                s.push_str(&format!(
                    "  {:>5} {:>12} {:>12} {:>8} {:>9}\n",
                    i,
                    format!("{:?}", g.xy(inst.robots[i])),
                    format!("{:?}", g.xy(o.goals[i])),
                    mason_crew::validate::arrival(p),
                    r.shortest
                        .get(i)
                        .copied()
                        .flatten()
                        .map_or("-".into(), |d| d.to_string())
                ));
            }
        }
    }
    s.push_str(&format!("status: {}\n", o.status));
    if let Some(reason) = &o.reason {
        s.push_str(&format!("reason: {reason}\n"));
    }
    if let Some(m) = r.metrics {
        s.push_str(&format!(
            "sum of costs: {} (lower bound {}{}), makespan: {}\n",
            m.sum_of_costs,
            r.lower_bound().map_or("-".into(), |b| b.to_string()),
            r.lower_bound()
                .filter(|&b| b > 0)
                .map_or(String::new(), |b| format!(
                    ", +{:.1} %",
                    (m.sum_of_costs as f64 / b as f64 - 1.0) * 100.0
                )),
            m.makespan
        ));
    }
    if let (Some(first), Some(soc)) = (o.stats.first_solution, o.stats.first_sum_of_costs) {
        s.push_str(&format!(
            "first plan after {:.2} ms with sum of costs {soc}; {} configurations; {} refinement rounds, {} kept\n",
            first.as_secs_f64() * 1e3,
            o.stats.configurations,
            o.stats.refine_rounds,
            o.stats.improvements
        ));
    }
    s.push_str(&format!(
        "time: {:.2} ms, {} nodes expanded, {} waits inserted; plan checked by crew::validate\n",
        o.stats.elapsed.as_secs_f64() * 1e3,
        o.stats.expanded,
        o.stats.waits
    ));
    s
}

/// Exit status: 1 with the reason when there is no plan.
pub fn exit_for(r: &CrewResult) -> CliResult<()> {
    match r.outcome.status {
        Status::Optimal | Status::Feasible => Ok(()),
        status => Err(no_solution(format!(
            "crew: {status}: {}",
            r.outcome.reason.as_deref().unwrap_or("no plan")
        ))),
    }
}

/// The process's peak resident memory in MB (Linux `VmHWM`), if known.
pub fn peak_memory_mb() -> Option<f64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kb: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb / 1024.0)
}
