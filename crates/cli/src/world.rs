//! The simulated world that the agents' simulated cameras see, across processes: the bricks on
//! the wall and the bricks that fell are read from the team's trace files (every `*.jsonl` in
//! one folder, which `mason launch` fills: each agent's own events, and for a killed agent the
//! events of its death, which launch appends). A real vehicle would look at the wall instead;
//! without `--world` the simulated vehicle has no camera.

use mason_mission::agent::WallView;
use mason_mission::state::EventRecord;
use mason_mission::EventKind;
use mason_wall::BrickId;
use std::collections::BTreeMap;
use std::io::{Read, Seek, SeekFrom};
use std::path::PathBuf;
use std::sync::Mutex;

/// What the trace files of a folder say about the wall, read incrementally.
pub struct TraceWorld {
    dir: PathBuf,
    state: Mutex<Seen>,
}

#[derive(Default)]
struct Seen {
    /// Per file: bytes of complete lines read so far.
    read: BTreeMap<PathBuf, u64>,
    placed: Vec<bool>,
    lost: Vec<(BrickId, f64)>,
}

impl TraceWorld {
    /// The world of the trace files in `dir`, for a wall of `bricks` bricks.
    pub fn new(dir: PathBuf, bricks: usize) -> Self {
        TraceWorld {
            dir,
            state: Mutex::new(Seen {
                placed: vec![false; bricks],
                ..Seen::default()
            }),
        }
    }

    fn refresh(&self) -> std::sync::MutexGuard<'_, Seen> {
        let mut seen = self
            .state
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner);
        let Ok(entries) = std::fs::read_dir(&self.dir) else {
            return seen;
        };
        for entry in entries.flatten() {
            let path = entry.path();
            if path.extension().is_none_or(|e| e != "jsonl") {
                continue;
            }
            let from = seen.read.get(&path).copied().unwrap_or(0);
            let Ok(mut f) = std::fs::File::open(&path) else {
                continue;
            };
            let mut text = String::new();
            if f.seek(SeekFrom::Start(from)).is_err() || f.read_to_string(&mut text).is_err() {
                continue;
            }
            // Only complete lines; a line being written is read next time.
            let complete = text.rfind('\n').map_or(0, |i| i + 1);
            for line in text[..complete].lines() {
                let Some(e) = serde_json::from_str::<EventRecord>(line)
                    .ok()
                    .and_then(|r| r.into_event().ok())
                else {
                    continue;
                };
                match e.kind {
                    EventKind::Place { brick } => {
                        if let Some(p) = seen.placed.get_mut(brick.index()) {
                            *p = true;
                        }
                    }
                    EventKind::Lost { brick } => seen.lost.push((brick, e.t)),
                    _ => {}
                }
            }
            seen.read.insert(path, from + complete as u64);
        }
        seen
    }
}

impl WallView for TraceWorld {
    fn placed(&self, brick: BrickId) -> bool {
        self.refresh()
            .placed
            .get(brick.index())
            .copied()
            .unwrap_or(false)
    }

    fn lost_since(&self, brick: BrickId, since: f64) -> bool {
        self.refresh()
            .lost
            .iter()
            .any(|&(b, t)| b == brick && t > since)
    }
}

/// The bricks UAV `uav` placed according to its earlier trace files (a restarted agent
/// remembers its own work). A truncated last line is skipped.
pub fn placed_by(uav: usize, files: &[PathBuf]) -> crate::fail::CliResult<Vec<BrickId>> {
    let mut placed = Vec::new();
    for p in files {
        let text = crate::input::read_input_text(p, 1 << 30)?;
        for line in text.lines() {
            if let Some(e) = serde_json::from_str::<EventRecord>(line)
                .ok()
                .and_then(|r| r.into_event().ok())
            {
                if let EventKind::Place { brick } = e.kind {
                    if e.uav as usize == uav {
                        placed.push(brick);
                    }
                }
            }
        }
    }
    Ok(placed)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_world_follows_the_files_as_they_grow() {
        let dir = std::env::temp_dir().join(format!("mason-world-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let a = dir.join("uav-0-1.jsonl");
        std::fs::write(
            &a,
            "{\"t\":5.0,\"uav\":0,\"kind\":\"place\",\"brick\":3}\n{\"t\":6.0,",
        )
        .unwrap();
        let w = TraceWorld::new(dir.clone(), 10);
        assert!(w.placed(BrickId(3)));
        assert!(!w.placed(BrickId(4)));
        let mut f = std::fs::OpenOptions::new().append(true).open(&a).unwrap();
        std::io::Write::write_all(&mut f, b"\"uav\":0,\"kind\":\"lost\",\"brick\":4}\n").unwrap();
        assert!(w.lost_since(BrickId(4), 5.5));
        assert!(!w.lost_since(BrickId(4), 6.5));
        assert_eq!(
            placed_by(0, std::slice::from_ref(&a)).unwrap(),
            vec![BrickId(3)]
        );
        assert!(placed_by(1, &[a]).unwrap().is_empty());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
