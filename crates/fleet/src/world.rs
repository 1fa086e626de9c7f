//! The simulated world that the agents' simulated cameras see, across processes: the bricks on
//! the wall and the bricks that fell are read from the team's trace files (every `*.jsonl` in
//! one folder, which `mason launch` fills: each agent's own events, and for a killed agent the
//! events of its death). A real vehicle would look at the wall instead.

use crate::trace::parse_line;
use mason_mission::agent::WallView;
use mason_mission::EventKind;
use mason_wall::BrickId;
use std::collections::BTreeMap;
use std::io::{Read, Seek, SeekFrom};
use std::path::PathBuf;
use std::sync::Mutex;

/// What the trace files of a folder say about the wall, read incrementally. Lines are read
/// with the one strict trace reader: a bad complete line stops that file, and the first such
/// problem is kept for [`TraceWorld::problem`] (a camera cannot fail, so it sees less).
pub struct TraceWorld {
    dir: PathBuf,
    state: Mutex<Seen>,
}

#[derive(Default)]
struct Seen {
    /// Per file: bytes of complete lines read so far, or `None` after a bad line.
    read: BTreeMap<PathBuf, Option<u64>>,
    placed: Vec<bool>,
    lost: Vec<(BrickId, f64)>,
    problem: Option<String>,
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

    /// The first bad line met, naming the file and the line, if any.
    pub fn problem(&self) -> Option<String> {
        self.lock().problem.clone()
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, Seen> {
        self.state
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
    }

    fn refresh(&self) -> std::sync::MutexGuard<'_, Seen> {
        let mut seen = self.lock();
        let Ok(entries) = std::fs::read_dir(&self.dir) else {
            return seen;
        };
        for entry in entries.flatten() {
            let path = entry.path();
            if path.extension().is_none_or(|e| e != "jsonl") {
                continue;
            }
            let Some(from) = seen.read.get(&path).copied().unwrap_or(Some(0)) else {
                continue;
            };
            let Ok(mut f) = std::fs::File::open(&path) else {
                continue;
            };
            let mut text = String::new();
            if f.seek(SeekFrom::Start(from)).is_err() || f.read_to_string(&mut text).is_err() {
                continue;
            }
            // Only complete lines; a line being written is read next time.
            let complete = text.rfind('\n').map_or(0, |i| i + 1);
            let mut next = Some(from + complete as u64);
            for line in text[..complete].lines() {
                match parse_line(line) {
                    Ok(e) => match e.kind {
                        EventKind::Place { brick } => {
                            if let Some(p) = seen.placed.get_mut(brick.index()) {
                                *p = true;
                            }
                        }
                        EventKind::Lost { brick } => seen.lost.push((brick, e.t)),
                        _ => {}
                    },
                    Err(reason) => {
                        if seen.problem.is_none() {
                            seen.problem = Some(format!("{}: {reason}", path.display()));
                        }
                        next = None;
                        break;
                    }
                }
            }
            seen.read.insert(path, next);
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
        assert!(w.problem().is_none());
        assert_eq!(
            crate::trace::placed_by(0, std::slice::from_ref(&a)).unwrap(),
            vec![BrickId(3)]
        );
        assert!(crate::trace::placed_by(1, &[a]).unwrap().is_empty());
        std::fs::write(dir.join("uav-1-1.jsonl"), "garbage\n").unwrap();
        assert!(!w.placed(BrickId(5)));
        let p = w.problem().expect("the bad line is kept");
        assert!(p.contains("uav-1-1.jsonl"), "{p}");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
