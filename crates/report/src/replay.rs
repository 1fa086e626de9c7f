//! Self-contained HTML replays: the data is embedded, nothing is fetched. A mission shows the
//! arena from above with the UAVs moving, the wall from the front filling up brick by brick,
//! and a timeline; a crew plan shows the grid with the robots moving. Both have play, pause,
//! speed and scrub controls, and expose their state on `<body>` (`data-t`, `data-frames`,
//! `data-errors`) for tests.

use crate::gantt::zone_intervals;
use crate::svg::escape;
use mason_crew::{Cell, Grid};
use mason_mission::{Arena, Event, EventKind};
use mason_wall::{brick_rgb, Wall};
use serde_json::{json, Value};

const SCRIPT: &str = include_str!("replay.js");

const STYLE: &str = "body{font-family:sans-serif;margin:16px;color:#222;background:#fafafa}\
canvas{background:#fff;border:1px solid #ccc;margin:4px}\
#controls{display:flex;gap:10px;align-items:center;margin:8px 0}#scrub{flex:1;max-width:700px}\
button,select{font-size:14px}#clock{font-variant-numeric:tabular-nums;min-width:9em}";

/// Records errors before anything else runs, so a test can read them from the DOM.
const ERROR_HOOK: &str = "<script>document.body.dataset.errors='0';\
window.addEventListener('error',function(){document.body.dataset.errors=String(+document.body.dataset.errors+1)});\
(function(){var e=console.error;console.error=function(){document.body.dataset.errors=String(+document.body.dataset.errors+1);e.apply(console,arguments)}})();</script>";

fn page(title: &str, content: &str, data: &Value) -> String {
    // `</` cannot close the data script early.
    let json = data.to_string().replace("</", "<\\/");
    format!(
        "<!DOCTYPE html><html lang=\"en\"><head><meta charset=\"utf-8\"><title>{t}</title><style>{STYLE}</style></head><body>{ERROR_HOOK}<h2>{t}</h2>\
<div id=\"controls\"><button id=\"play\">Pause</button><label>speed <select id=\"speed\">{speeds}</select></label>\
<input id=\"scrub\" type=\"range\" min=\"0\" value=\"0\"><span id=\"clock\"></span><span id=\"status\"></span></div>{content}\
<script id=\"mason-data\" type=\"application/json\">{json}</script><script>{SCRIPT}</script></body></html>",
        t = escape(title),
        speeds = data["speeds"]
            .as_array()
            .expect("speeds")
            .iter()
            .map(|s| {
                let v = s.as_f64().unwrap_or(1.0);
                let sel = if Some(v) == data["speed"].as_f64() { " selected" } else { "" };
                format!("<option value=\"{v}\"{sel}>{v}×</option>")
            })
            .collect::<String>()
    )
}

/// A mission replay page.
pub fn mission_replay_html(
    title: &str,
    wall: &Wall,
    arena: &Arena,
    uavs: usize,
    events: &[Event],
    end: f64,
) -> String {
    let mut tracks: Vec<Vec<Value>> = vec![Vec::new(); uavs];
    let mut placed_at: Vec<Option<f64>> = vec![None; wall.len()];
    for e in events {
        match e.kind {
            EventKind::State { state, x, y, .. } => {
                tracks[e.uav as usize].push(json!([e.t, x, y, state.name()]))
            }
            EventKind::Place { brick } => placed_at[brick.index()] = Some(e.t),
            _ => {}
        }
    }
    let zone: Vec<Value> = zone_intervals(events)
        .into_iter()
        .map(|(a, b)| json!([a, b]))
        .collect();
    // The front view stacks the wall's segments (crate::wall_layout), as the wall SVG does.
    let layout = crate::wall_layout::front_layout(wall);
    let bricks: Vec<Value> = wall
        .bricks()
        .iter()
        .zip(&layout.spots)
        .map(|(b, spot)| {
            let [r, g, bl] = brick_rgb(b.kind);
            json!({"label": b.label, "colour": format!("rgb({r},{g},{bl})"), "x0": spot.x0, "x1": spot.x1, "y": spot.y, "level": b.level})
        })
        .collect();
    let bands: Vec<Value> = layout
        .bands
        .iter()
        .filter(|_| layout.captions)
        .map(|band| json!({"segment": band.segment, "top": band.top}))
        .collect();
    let p = |pt: mason_mission::Point| json!([pt.x, pt.y]);
    let data = json!({
        "kind": "mission",
        "end": end,
        "speeds": [1, 5, 10, 30, 100],
        "speed": 10,
        "arena": {
            "width": arena.width, "depth": arena.depth,
            "piles": arena.piles.iter().map(|&q| p(q)).collect::<Vec<_>>(),
            "wall": p(arena.wall), "zone_half": p(arena.zone_half),
        },
        "tracks": tracks,
        "bricks": bricks,
        "levels": wall.levels(),
        "front": {"width": layout.width, "height": layout.height, "bands": bands},
        "placed_at": placed_at,
        "zone": zone,
    });
    let content =
        "<div><canvas id=\"top\" width=\"600\" height=\"500\" title=\"arena from above\"></canvas>\
<canvas id=\"front\" width=\"600\" height=\"220\" title=\"the wall from the front\"></canvas></div>\
<div id=\"states\"></div>";
    page(title, content, &data)
}

/// A crew replay page; one time step plays in half a second at 1×.
pub fn crew_replay_html(title: &str, grid: &Grid, goals: &[Cell], paths: &[Vec<Cell>]) -> String {
    let mut blocked = Vec::new();
    for y in 0..grid.height() {
        let mut x = 0;
        while x < grid.width() {
            let is_blocked = |x: u32| !grid.is_free(grid.cell(x as i64, y as i64).expect("inside"));
            if is_blocked(x) {
                let x0 = x;
                while x < grid.width() && is_blocked(x) {
                    x += 1;
                }
                blocked.push(json!([x0, y, x - x0]));
            } else {
                x += 1;
            }
        }
    }
    let end = paths
        .iter()
        .map(|p| p.len().saturating_sub(1))
        .max()
        .unwrap_or(0)
        .max(1);
    let data = json!({
        "kind": "crew",
        "end": end,
        "speeds": [0.5, 2, 5, 10, 30],
        "speed": 2,
        "width": grid.width(),
        "height": grid.height(),
        "blocked": blocked,
        "goals": goals.iter().map(|c| c.0).collect::<Vec<_>>(),
        "paths": paths.iter().map(|p| p.iter().map(|c| c.0).collect::<Vec<_>>()).collect::<Vec<_>>(),
    });
    page(title, "<div><canvas id=\"grid\"></canvas></div>", &data)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crew_page_embeds_its_data_safely_and_fetches_nothing() {
        let mut grid = Grid::open(4, 3);
        grid.set_blocked(Cell(5), true);
        let page = crew_replay_html(
            "a </script> title",
            &grid,
            &[Cell(3)],
            &[vec![Cell(0), Cell(1), Cell(2), Cell(3)]],
        );
        assert_eq!(
            page.matches("</script>").count(),
            3,
            "hook, data and player only"
        );
        assert!(page.contains("\"blocked\":[[1,1,1]]"));
        assert!(!page.contains("src=\"http"));
    }
}
