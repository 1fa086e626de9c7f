//! Where an agent writes what it does: the [`AgentLog`] sink, its trace file ([`JsonLines`])
//! and its MCAP log for Foxglove ([`McapAgentLog`]).

use mason_mission::agent::{Command, DropCause, DropCounts, Message};
use mason_mission::Event;
use std::io::Write;

/// Where an agent's events, messages and poses go.
pub trait AgentLog {
    /// One trace event.
    fn event(&mut self, e: &Event) -> std::io::Result<()>;
    /// A message sent (`sent`) or heard.
    fn message(&mut self, _t: f64, _m: &Message, _sent: bool) -> std::io::Result<()> {
        Ok(())
    }
    /// The UAV's pose at mission time `t` (m), after every tick.
    fn pose(&mut self, _t: f64, _pose: (f64, f64, f64)) -> std::io::Result<()> {
        Ok(())
    }
    /// A ground station's command, checked, heard at mission time `t`.
    fn command(&mut self, _t: f64, _c: &Command) -> std::io::Result<()> {
        Ok(())
    }
    /// The first sample dropped on arrival for `cause`, at mission time `t` (once per cause).
    fn dropped(&mut self, _t: f64, _cause: DropCause) -> std::io::Result<()> {
        Ok(())
    }
    /// The samples dropped on arrival, per cause, when the agent stops.
    fn drops(&mut self, _t: f64, _counts: &DropCounts) -> std::io::Result<()> {
        Ok(())
    }
    /// The agent stopped: complete the log.
    fn finish(&mut self) -> std::io::Result<()> {
        Ok(())
    }
}

/// Keeps the events in memory.
impl AgentLog for Vec<Event> {
    fn event(&mut self, e: &Event) -> std::io::Result<()> {
        self.push(*e);
        Ok(())
    }
}

/// Logs to none, one or several logs.
impl AgentLog for Vec<Box<dyn AgentLog + '_>> {
    fn event(&mut self, e: &Event) -> std::io::Result<()> {
        self.iter_mut().try_for_each(|l| l.event(e))
    }
    fn message(&mut self, t: f64, m: &Message, sent: bool) -> std::io::Result<()> {
        self.iter_mut().try_for_each(|l| l.message(t, m, sent))
    }
    fn pose(&mut self, t: f64, p: (f64, f64, f64)) -> std::io::Result<()> {
        self.iter_mut().try_for_each(|l| l.pose(t, p))
    }
    fn command(&mut self, t: f64, c: &Command) -> std::io::Result<()> {
        self.iter_mut().try_for_each(|l| l.command(t, c))
    }
    fn dropped(&mut self, t: f64, cause: DropCause) -> std::io::Result<()> {
        self.iter_mut().try_for_each(|l| l.dropped(t, cause))
    }
    fn drops(&mut self, t: f64, counts: &DropCounts) -> std::io::Result<()> {
        self.iter_mut().try_for_each(|l| l.drops(t, counts))
    }
    fn finish(&mut self) -> std::io::Result<()> {
        self.iter_mut().try_for_each(|l| l.finish())
    }
}

/// The most bytes an agent writes to one log (its trace file or its MCAP log): what
/// [`crate::trace::read_trace`] reads back, 1 GiB.
pub const MAX_LOG_BYTES: u64 = crate::trace::MAX_TRACE_BYTES;

/// A writer that refuses to grow past a number of bytes: a runaway agent fails with a clear
/// error instead of filling the disk.
pub struct Capped<W> {
    inner: W,
    written: u64,
    limit: u64,
}

impl<W> Capped<W> {
    /// `inner`, which may take at most `limit` bytes.
    pub fn new(inner: W, limit: u64) -> Self {
        Capped {
            inner,
            written: 0,
            limit,
        }
    }
}

impl<W: Write> Write for Capped<W> {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        if self.written + buf.len() as u64 > self.limit {
            return Err(std::io::Error::other(format!(
                "the log would grow past {} bytes (MAX_LOG_BYTES)",
                self.limit
            )));
        }
        let n = self.inner.write(buf)?;
        self.written += n as u64;
        Ok(n)
    }
    fn flush(&mut self) -> std::io::Result<()> {
        self.inner.flush()
    }
}

impl<W: std::io::Seek> std::io::Seek for Capped<W> {
    fn seek(&mut self, pos: std::io::SeekFrom) -> std::io::Result<u64> {
        self.inner.seek(pos)
    }
}

/// The trace file: one [`Event`] as JSON per line, written and flushed line by line so that
/// an agent killed mid-mission leaves every event but at most a truncated last line
/// ([`crate::trace::read_trace`] reads it back). At most [`MAX_LOG_BYTES`].
pub struct JsonLines<W: Write>(pub Capped<W>);

impl<W: Write> JsonLines<W> {
    /// Trace lines into `out`.
    pub fn new(out: W) -> Self {
        JsonLines(Capped::new(out, MAX_LOG_BYTES))
    }
}

impl<W: Write> AgentLog for JsonLines<W> {
    fn event(&mut self, e: &Event) -> std::io::Result<()> {
        let mut line = serde_json::to_vec(e).map_err(std::io::Error::other)?;
        line.push(b'\n');
        self.0.write_all(&line)?;
        self.0.flush()
    }
}

type Mcap<'a, W> = mason_report::McapLog<'a, std::io::BufWriter<Capped<W>>>;

/// The agent's MCAP log (the topics of `simulate --mcap`): poses as
/// [`mason_report::PoseSampler`] samples them (at every event, else at
/// [`mason_report::POSE_RATE_HZ`], heading along the last move); every event; every message
/// sent or heard on `/messages` (`kind` is `sent/KIND` or `heard/KIND`, `body` the whole
/// message); every command of a ground station it obeys (`kind` `heard/command`, `body` the
/// command, `from` this UAV); the first sample dropped on arrival for each cause (`kind` `dropped/CAUSE`, `body`
/// `{"cause"}`), and when it stops the counts per cause (`kind` `dropped/counts`, `body` the
/// counts by cause name). At most [`MAX_LOG_BYTES`].
pub struct McapAgentLog<'a, W: Write + std::io::Seek> {
    log: Option<Mcap<'a, W>>,
    sampler: mason_report::PoseSampler,
}

impl<'a, W: Write + std::io::Seek> McapAgentLog<'a, W> {
    /// A log into `out` for UAV `uav` of the mission `meta` describes.
    pub fn new(out: W, meta: &mason_report::LogMeta<'a>, uav: usize) -> std::io::Result<Self> {
        let log = mason_report::McapLog::new(
            std::io::BufWriter::new(Capped::new(out, MAX_LOG_BYTES)),
            meta,
        )
        .map_err(std::io::Error::other)?;
        Ok(McapAgentLog {
            log: Some(log),
            sampler: mason_report::PoseSampler::new(uav as u32),
        })
    }

    fn log(&mut self) -> std::io::Result<&mut Mcap<'a, W>> {
        self.log
            .as_mut()
            .ok_or_else(|| std::io::Error::other("the MCAP log is finished"))
    }
}

impl<W: Write + std::io::Seek> AgentLog for McapAgentLog<'_, W> {
    fn event(&mut self, e: &Event) -> std::io::Result<()> {
        self.sampler.mark_due();
        self.log()?.event(e).map_err(std::io::Error::other)
    }

    fn message(&mut self, t: f64, m: &Message, sent: bool) -> std::io::Result<()> {
        let body = serde_json::to_value(m).map_err(std::io::Error::other)?;
        let kind = format!("{}/{}", if sent { "sent" } else { "heard" }, m.kind.key());
        self.log()?
            .message(t, m.uav, &kind, &body)
            .map_err(std::io::Error::other)
    }

    fn command(&mut self, t: f64, c: &Command) -> std::io::Result<()> {
        let uav = self.sampler.uav();
        let body = serde_json::to_value(c).map_err(std::io::Error::other)?;
        self.log()?
            .message(t, uav, "heard/command", &body)
            .map_err(std::io::Error::other)
    }

    fn dropped(&mut self, t: f64, cause: DropCause) -> std::io::Result<()> {
        let uav = self.sampler.uav();
        let body = serde_json::json!({ "cause": cause.name() });
        self.log()?
            .message(t, uav, &format!("dropped/{}", cause.name()), &body)
            .map_err(std::io::Error::other)
    }

    fn drops(&mut self, t: f64, counts: &DropCounts) -> std::io::Result<()> {
        let uav = self.sampler.uav();
        let body = serde_json::to_value(counts).map_err(std::io::Error::other)?;
        self.log()?
            .message(t, uav, "dropped/counts", &body)
            .map_err(std::io::Error::other)
    }

    fn pose(&mut self, t: f64, p: (f64, f64, f64)) -> std::io::Result<()> {
        let Some(pose) = self.sampler.sample(t, p) else {
            return Ok(());
        };
        let uav = self.sampler.uav();
        self.log()?
            .pose(t, uav, pose)
            .map_err(std::io::Error::other)
    }

    fn finish(&mut self) -> std::io::Result<()> {
        match self.log.take() {
            Some(log) => {
                let mut out = log.finish().map_err(std::io::Error::other)?;
                out.flush()
            }
            None => Ok(()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_capped_log_refuses_to_grow_past_its_limit() {
        let mut w = Capped::new(Vec::new(), 10);
        w.write_all(b"0123456789").unwrap();
        let e = w.write_all(b"x").unwrap_err().to_string();
        assert!(e.contains("MAX_LOG_BYTES"), "{e}");
        assert_eq!(w.inner.len(), 10);
    }
    use mason_mission::EventKind;

    #[test]
    fn trace_lines_read_back_as_the_events_written() {
        let events = [
            Event {
                t: 1.5,
                uav: 2,
                kind: EventKind::ZoneEnter,
            },
            Event {
                t: 2.0,
                uav: 2,
                kind: EventKind::Place {
                    brick: mason_wall::BrickId(3),
                },
            },
        ];
        let mut log = JsonLines::new(Vec::new());
        for e in &events {
            log.event(e).unwrap();
        }
        let text = String::from_utf8(log.0.inner).unwrap();
        let back =
            crate::trace::parse_trace(&text, std::path::Path::new("t.jsonl"), false).unwrap();
        assert_eq!(back, events);
    }
}
