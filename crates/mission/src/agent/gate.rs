//! The check on arrival (DESIGN §8, issue #27): every sample heard from the network passes
//! here before it can touch what an agent knows, whatever the transport (Zenoh, the in-process
//! `Hub`, the virtual bus).
//!
//! A transport hands over an [`Arrival`]: the sample's bytes (or a message already decoded,
//! in-process), with the key chunks it came on when the transport has a key.
//! [`Agent::admit`] checks it and names the first rule it breaks: bytes over the size bound
//! are refused unread, then the rules below apply in the order of the table, except that the
//! bounds on arrays and strings (`size`) are checked after `jump`:
//!
//! | cause | the sample |
//! |---|---|
//! | `size` | is longer than [`max_message_bytes`], or an array or string is over its bound (`heard` not one entry per UAV, `placed` over the wall's bricks, `acks` or `out` over the team, `outcome` over [`MAX_OUTCOME_CHARS`]) |
//! | `malformed` | is not a message of the schema (not JSON, a wrong type, a number out of range) |
//! | `version` | is of another schema version |
//! | `mission` | is of another mission |
//! | `unknown_uav` | names a sender outside the team's range of indices |
//! | `own` | names this agent as its sender |
//! | `key` | came on a key whose UAV or kind chunk is not its `uav` or `kind` |
//! | `time` | was sent at a time outside [`TIME_BEHIND_S`] before to [`TIME_AHEAD_S`] after the receiver's clock |
//! | `replay` | is not newer, by (incarnation, seq), than the last kept from its sender: a duplicate or a replay |
//! | `jump` | raises the incarnation by more than [`MAX_INCARNATION_STEP`] (or starts above [`MAX_FIRST_INCARNATION`]), or the sequence number by more than [`SEQ_SLACK`] + [`SEQ_PER_S`] per second of the sender's time |
//! | `range` | holds an index outside the team or the wall, `placed` not strictly ascending, or a number that is not finite or over [`MAX_ABS_NUMBER`] |
//! | `implausible` | says more bricks are placed than one wall zone could have let through by its time |
//! | `overflow` | never reached the check: the transport's receive queue was full (a flood), counted by [`Agent::overflowed`] |
//!
//! A sample that fails is dropped and counted ([`DropCounts`]); [`Dropped::first`] says it is
//! the first of its cause, for a log that names each cause once. Nothing here fails, panics or
//! allocates in proportion to the sample beyond its bounded size: no message can end an agent.
//!
//! What the checks cannot do: tell who sent a sample. That is the transport's part: over
//! Zenoh, mutual TLS with the mission authority and access control on the sender's key
//! (`mason_fleet::zenoh_link`) let only UAV *i* put on UAV *i*'s keys. Without them
//! (`--insecure`), a peer on the network can speak as a teammate with a plausible status: the
//! checks bound what such a message can claim, not who sent it.

use super::wire::{Command, Message, Order, COMMAND_KIND, SCHEMA_VERSION, STATION_CHUNK};
use super::Agent;
use serde::ser::SerializeMap;
use serde::Serialize;

/// Ground stations are numbered below this.
pub const MAX_STATIONS: usize = 16;
/// The longest `outcome` string (characters).
pub const MAX_OUTCOME_CHARS: usize = 32;
/// The most an incarnation may grow from the last one kept from its sender.
pub const MAX_INCARNATION_STEP: u64 = 16;
/// The highest incarnation accepted from a sender never heard before.
pub const MAX_FIRST_INCARNATION: u64 = 1024;
/// Sequence numbers may grow by this much beyond [`SEQ_PER_S`] per second.
pub const SEQ_SLACK: u64 = 256;
/// Sequence numbers may grow by this much per second of the sender's time (an agent sends at
/// most one message per tick, a heartbeat a second when idle).
pub const SEQ_PER_S: f64 = 50.0;
/// A message may be sent at most this long after the receiver's mission time (s).
pub const TIME_AHEAD_S: f64 = 30.0;
/// A message may be sent at most this long before the receiver's mission time (s).
pub const TIME_BEHIND_S: f64 = 120.0;
/// The largest magnitude of any number in a message (positions in m, times in s).
pub const MAX_ABS_NUMBER: f64 = 1e9;

/// The longest sample accepted (bytes) on a wall of `bricks` bricks with `uavs` UAVs: room
/// for every field, a `placed` list of every brick, and `heard`, `acks` and `out` for every
/// UAV. A message of the MBZIRC wall (42 bricks, 3 UAVs) may take 4 888 bytes.
pub fn max_message_bytes(bricks: usize, uavs: usize) -> usize {
    4096 + 12 * bricks + 96 * uavs
}

/// Why a sample was dropped. See the module's table.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum DropCause {
    /// Too long, or an array or string over its bound.
    Size,
    /// Not a message of the schema.
    Malformed,
    /// Another schema version.
    Version,
    /// Another mission.
    Mission,
    /// A sender outside the team.
    UnknownUav,
    /// This agent named as the sender.
    Own,
    /// The key's chunks disagree with the message.
    Key,
    /// Sent outside the plausible window of the receiver's clock.
    Time,
    /// Not newer than the last kept from its sender.
    Replay,
    /// An incarnation or sequence number that jumps too far.
    Jump,
    /// An index or number out of range.
    Range,
    /// More bricks placed than the wall zone could have let through.
    Implausible,
    /// Dropped by the transport before the check: its receive queue was full.
    Overflow,
}

impl DropCause {
    /// Every cause, in the order of the module's table.
    pub const ALL: [DropCause; 13] = [
        DropCause::Size,
        DropCause::Malformed,
        DropCause::Version,
        DropCause::Mission,
        DropCause::UnknownUav,
        DropCause::Own,
        DropCause::Key,
        DropCause::Time,
        DropCause::Replay,
        DropCause::Jump,
        DropCause::Range,
        DropCause::Implausible,
        DropCause::Overflow,
    ];

    /// The cause's name in logs and summaries (snake_case).
    pub fn name(self) -> &'static str {
        match self {
            DropCause::Size => "size",
            DropCause::Malformed => "malformed",
            DropCause::Version => "version",
            DropCause::Mission => "mission",
            DropCause::UnknownUav => "unknown_uav",
            DropCause::Own => "own",
            DropCause::Key => "key",
            DropCause::Time => "time",
            DropCause::Replay => "replay",
            DropCause::Jump => "jump",
            DropCause::Range => "range",
            DropCause::Implausible => "implausible",
            DropCause::Overflow => "overflow",
        }
    }

    fn index(self) -> usize {
        self as usize
    }
}

impl std::fmt::Display for DropCause {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

/// How many samples were dropped, per cause. Serialises as an object of the nonzero counts
/// by cause name (`{"replay": 12, "unknown_uav": 1}`).
#[derive(Clone, Copy, Default, PartialEq, Eq)]
pub struct DropCounts([u64; DropCause::ALL.len()]);

/// The nonzero counts by cause name, as in JSON.
impl std::fmt::Debug for DropCounts {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_map()
            .entries(self.nonzero().map(|(c, k)| (c.name(), k)))
            .finish()
    }
}

impl DropCounts {
    /// Samples dropped for `cause`.
    pub fn count(&self, cause: DropCause) -> u64 {
        self.0[cause.index()]
    }

    /// Samples dropped in all.
    pub fn total(&self) -> u64 {
        self.0.iter().sum()
    }

    /// The causes with a nonzero count, in the order of [`DropCause::ALL`].
    pub fn nonzero(&self) -> impl Iterator<Item = (DropCause, u64)> + '_ {
        DropCause::ALL
            .iter()
            .map(|&c| (c, self.count(c)))
            .filter(|&(_, k)| k > 0)
    }

    /// Adds `other`'s counts (a team's total).
    pub fn add(&mut self, other: &DropCounts) {
        for (a, b) in self.0.iter_mut().zip(other.0) {
            *a = a.saturating_add(b);
        }
    }

    /// Counts one more sample dropped for `cause`; returns its count now.
    pub fn record(&mut self, cause: DropCause) -> u64 {
        let k = &mut self.0[cause.index()];
        *k = k.saturating_add(1);
        *k
    }
}

impl Serialize for DropCounts {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut map = s.serialize_map(None)?;
        for (c, k) in self.nonzero() {
            map.serialize_entry(c.name(), &k)?;
        }
        map.end()
    }
}

/// The chunks of the key a sample came on, `PREFIX/MISSION/UAV/KIND`: the UAV and the kind.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SampleKey {
    /// The UAV chunk, as on the wire.
    pub uav: String,
    /// The kind chunk.
    pub kind: String,
}

impl SampleKey {
    /// The key `m` is published on.
    pub fn of(m: &Message) -> Self {
        SampleKey {
            uav: m.uav.to_string(),
            kind: m.kind.key().to_string(),
        }
    }

    /// The last two chunks of a key `…/UAV/KIND` (`None` with fewer than two).
    pub fn parse(key: &str) -> Option<Self> {
        let mut chunks = key.rsplit('/');
        let kind = chunks.next()?;
        let uav = chunks.next()?;
        Some(SampleKey {
            uav: uav.to_string(),
            kind: kind.to_string(),
        })
    }
}

/// What a sample carries: bytes off the network, or a message decoded already (in-process).
#[derive(Clone, Debug, PartialEq)]
pub enum Body {
    /// The sample's bytes, JSON by the schema if the sender follows it.
    Bytes(Vec<u8>),
    /// A message (the in-process bus and `Hub`).
    Message(Box<Message>),
    /// A ground station's command (in-process).
    Command(Box<Command>),
}

/// A sample as a transport hands it over, before any check.
#[derive(Clone, Debug, PartialEq)]
pub struct Arrival {
    /// The key's chunks, when the transport has keys.
    pub key: Option<SampleKey>,
    /// What it carries.
    pub body: Body,
}

impl Arrival {
    /// `m` on the key it is published on (what an honest sender does).
    pub fn keyed(m: Message) -> Self {
        Arrival {
            key: Some(SampleKey::of(&m)),
            body: Body::Message(Box::new(m)),
        }
    }

    /// A ground station's command on its key.
    pub fn command(c: Command) -> Self {
        Arrival {
            key: Some(SampleKey {
                uav: format!("{STATION_CHUNK}{}", c.station),
                kind: COMMAND_KIND.to_string(),
            }),
            body: Body::Command(Box::new(c)),
        }
    }

    /// Raw bytes heard on `key`.
    pub fn bytes(key: Option<SampleKey>, bytes: Vec<u8>) -> Self {
        Arrival {
            key,
            body: Body::Bytes(bytes),
        }
    }
}

/// A sample that passed every check: only [`Agent::admit`] makes one, and only
/// [`Agent::receive`] takes one.
#[derive(Clone, Debug, PartialEq)]
pub struct Checked(pub(super) Heard);

/// What a checked sample holds.
#[derive(Clone, Debug, PartialEq)]
pub(super) enum Heard {
    /// A teammate's message.
    Status(Box<Message>),
    /// A ground station's command.
    Command(Command),
}

impl Checked {
    /// The teammate's message, if it is one.
    pub fn message(&self) -> Option<&Message> {
        match &self.0 {
            Heard::Status(m) => Some(m),
            Heard::Command(_) => None,
        }
    }

    /// The ground station's command, if it is one.
    pub fn command(&self) -> Option<&Command> {
        match &self.0 {
            Heard::Command(c) => Some(c),
            Heard::Status(_) => None,
        }
    }
}

/// A dropped sample: why, and whether it is the first of that cause (log it then).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Dropped {
    /// Why.
    pub cause: DropCause,
    /// The first sample this agent dropped for this cause.
    pub first: bool,
}

/// The check's own state: its bounds, its counts, and the last command of each station.
#[derive(Clone, Debug)]
pub(super) struct Inbox {
    pub(super) bounds: Bounds,
    pub(super) drops: DropCounts,
    /// The `seq` of the last command obeyed from each station (0: none).
    station_seq: [u64; MAX_STATIONS],
}

impl Inbox {
    pub(super) fn new(setup: &super::AgentSetup<'_>) -> Self {
        Inbox {
            bounds: Bounds::new(setup),
            drops: DropCounts::default(),
            station_seq: [0; MAX_STATIONS],
        }
    }

    /// A command obeyed: later ones from its station must number higher.
    pub(super) fn heard_command(&mut self, c: &Command) {
        if let Some(s) = self.station_seq.get_mut(c.station as usize) {
            *s = c.seq;
        }
    }
}

/// What the checks need to know of the team and the wall, fixed for an agent's life.
#[derive(Clone, Copy, Debug)]
pub(super) struct Bounds {
    /// The longest sample (bytes).
    max_bytes: usize,
    /// The shortest time a brick keeps the wall zone (s); 0: no bound on bricks placed.
    min_zone_s: f64,
}

impl Bounds {
    pub(super) fn new(setup: &super::AgentSetup<'_>) -> Self {
        let drop = setup
            .wall
            .bricks()
            .iter()
            .map(|b| setup.model.times(b.kind).drop)
            .fold(f64::INFINITY, f64::min);
        let kappa = setup
            .model
            .kappa
            .iter()
            .copied()
            .fold(f64::INFINITY, f64::min);
        let min_zone_s = setup.config.uav.zone_transit_s + kappa * drop;
        Bounds {
            max_bytes: max_message_bytes(setup.wall.len(), setup.config.uavs),
            min_zone_s: if min_zone_s.is_finite() && min_zone_s > 0.0 {
                min_zone_s
            } else {
                0.0
            },
        }
    }

    /// The most bricks that can be placed by mission time `t`: one wall zone lets one brick
    /// through per `min_zone_s` at best; a margin of two for the first ones and rounding.
    fn most_placed(&self, t: f64) -> f64 {
        if self.min_zone_s > 0.0 {
            2.0 + 2.0 * t.max(0.0) / self.min_zone_s
        } else {
            f64::INFINITY
        }
    }
}

/// Whether a number off the wire is usable: finite and at most [`MAX_ABS_NUMBER`].
fn sane(x: f64) -> bool {
    x.is_finite() && x.abs() <= MAX_ABS_NUMBER
}

impl Agent<'_> {
    /// Checks a sample heard at `now` (mission s, the receiver's clock). A sample that fails
    /// is counted and dropped; nothing about the agent changes otherwise.
    pub fn admit(&mut self, now: f64, arrival: Arrival) -> Result<Checked, Dropped> {
        match self.check(now, arrival) {
            Ok(heard) => Ok(Checked(heard)),
            Err(cause) => Err(Dropped {
                cause,
                first: self.inbox.drops.record(cause) == 1,
            }),
        }
    }

    /// Checks a sample and applies it if it passes ([`Agent::admit`], then
    /// [`Agent::receive`]).
    pub fn hear(&mut self, now: f64, arrival: Arrival) -> Result<(), Dropped> {
        let m = self.admit(now, arrival)?;
        self.receive(now, m);
        Ok(())
    }

    /// Counts `k` samples the transport dropped unread because its receive queue was full
    /// ([`DropCause::Overflow`]); `Some` the first time, for a log that names it once.
    pub fn overflowed(&mut self, k: u64) -> Option<Dropped> {
        let counts = &mut self.inbox.drops.0[DropCause::Overflow.index()];
        let first = *counts == 0 && k > 0;
        *counts = counts.saturating_add(k);
        first.then_some(Dropped {
            cause: DropCause::Overflow,
            first: true,
        })
    }

    /// The samples dropped so far, per cause.
    pub fn drops(&self) -> &DropCounts {
        &self.inbox.drops
    }

    fn check(&self, now: f64, arrival: Arrival) -> Result<Heard, DropCause> {
        let on_command_key = arrival.key.as_ref().is_some_and(|k| k.kind == COMMAND_KIND);
        let m = match arrival.body {
            Body::Message(m) => *m,
            Body::Command(c) => return self.check_command(now, arrival.key.as_ref(), *c),
            Body::Bytes(b) if b.len() > self.inbox.bounds.max_bytes => return Err(DropCause::Size),
            Body::Bytes(b) if on_command_key => {
                let c = serde_json::from_slice::<Command>(&b).map_err(|_| DropCause::Malformed)?;
                return self.check_command(now, arrival.key.as_ref(), c);
            }
            Body::Bytes(b) => {
                serde_json::from_slice::<Message>(&b).map_err(|_| DropCause::Malformed)?
            }
        };
        self.check_message(now, arrival.key.as_ref(), m)
            .map(|m| Heard::Status(Box::new(m)))
    }

    /// A ground station's command: its schema, mission, station and key, time window, a
    /// growing `seq`, and a UAV of the team to land.
    fn check_command(
        &self,
        now: f64,
        key: Option<&SampleKey>,
        c: Command,
    ) -> Result<Heard, DropCause> {
        if c.v != SCHEMA_VERSION {
            return Err(DropCause::Version);
        }
        if c.mission != self.setup.mission {
            return Err(DropCause::Mission);
        }
        let Some(&last) = self.inbox.station_seq.get(c.station as usize) else {
            return Err(DropCause::UnknownUav);
        };
        if let Some(k) = key {
            if k.kind != COMMAND_KIND || k.uav != format!("{STATION_CHUNK}{}", c.station) {
                return Err(DropCause::Key);
            }
        }
        if !(c.t.is_finite() && c.t >= now - TIME_BEHIND_S && c.t <= now + TIME_AHEAD_S) {
            return Err(DropCause::Time);
        }
        if c.seq <= last {
            return Err(DropCause::Replay);
        }
        if c.seq - last > SEQ_SLACK {
            return Err(DropCause::Jump);
        }
        if let Order::Land { uav } = c.order {
            if uav as usize >= self.n {
                return Err(DropCause::Range);
            }
        }
        Ok(Heard::Command(c))
    }

    fn check_message(
        &self,
        now: f64,
        key: Option<&SampleKey>,
        m: Message,
    ) -> Result<Message, DropCause> {
        if m.v != SCHEMA_VERSION {
            return Err(DropCause::Version);
        }
        if m.mission != self.setup.mission {
            return Err(DropCause::Mission);
        }
        let u = m.uav as usize;
        if u >= self.n {
            return Err(DropCause::UnknownUav);
        }
        if u == self.me {
            return Err(DropCause::Own);
        }
        if let Some(k) = key {
            if k.kind != m.kind.key() || k.uav != m.uav.to_string() {
                return Err(DropCause::Key);
            }
        }
        if !(m.t.is_finite() && m.t >= now - TIME_BEHIND_S && m.t <= now + TIME_AHEAD_S) {
            return Err(DropCause::Time);
        }
        if !self.members.is_newer(u, m.incarnation, m.seq) {
            return Err(DropCause::Replay);
        }
        self.check_jump(&m)?;
        self.check_sizes(&m)?;
        self.check_ranges(&m)?;
        if m.status.placed.len() as f64 > self.inbox.bounds.most_placed(m.t) {
            return Err(DropCause::Implausible);
        }
        Ok(m)
    }

    /// Incarnations and sequence numbers grow, within bounds.
    fn check_jump(&self, m: &Message) -> Result<(), DropCause> {
        let seq_room = |since: f64| {
            SEQ_SLACK.saturating_add((SEQ_PER_S * (m.t - since).max(0.0)).min(1e15) as u64)
        };
        let ok = match &self.members.peers[m.uav as usize] {
            None => m.incarnation <= MAX_FIRST_INCARNATION && m.seq <= seq_room(0.0),
            Some(p) if m.incarnation == p.incarnation => {
                m.seq - p.seq <= seq_room(p.sent_t.max(0.0))
            }
            Some(p) => {
                m.incarnation - p.incarnation <= MAX_INCARNATION_STEP && m.seq <= seq_room(0.0)
            }
        };
        if ok && m.incarnation >= 1 && m.seq >= 1 {
            Ok(())
        } else {
            Err(DropCause::Jump)
        }
    }

    /// Every array and string within its bound.
    fn check_sizes(&self, m: &Message) -> Result<(), DropCause> {
        let s = &m.status;
        let ok = s.heard.len() == self.n
            && s.placed.len() <= self.setup.wall.len()
            && s.acks.len() <= self.n
            && s.out.len() <= self.n
            && s.outcome.chars().count() <= MAX_OUTCOME_CHARS;
        if ok {
            Ok(())
        } else {
            Err(DropCause::Size)
        }
    }

    /// Every index in the team or on the wall, every number finite and bounded.
    fn check_ranges(&self, m: &Message) -> Result<(), DropCause> {
        let s = &m.status;
        let (n, bricks) = (self.n as u32, self.setup.wall.len() as u32);
        let brick_ok = |b: u32| b < bricks;
        let mut ok = [s.x, s.y, s.z, s.claimed_at].into_iter().all(sane)
            && s.brick.is_none_or(brick_ok)
            && s.heard.iter().all(|&h| sane(h) && h >= -1.0)
            && s.acks.iter().all(|a| a.uav < n)
            && s.out.iter().all(|o| o.uav < n)
            && s.placed.windows(2).all(|w| w[0] < w[1])
            && s.placed.last().is_none_or(|&b| brick_ok(b));
        if let Some(p) = &s.pair {
            ok &= p.uav < n && sane(p.claimed_at) && sane(p.since);
        }
        if let Some(r) = &s.request {
            ok &=
                brick_ok(r.brick) && (r.rank as usize) < self.setup.order.len() && sane(r.expires);
        }
        if ok {
            Ok(())
        } else {
            Err(DropCause::Range)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::testkit::Fixture;
    use super::*;
    use crate::coord::Coord;

    /// Agent 0 of a three-UAV team on thesis-2x5, and a message UAV 1 sent at 10 s.
    fn scene(fixture: &Fixture) -> (Vec<Agent<'_>>, Message) {
        let mut agents = fixture.agents(Coord::Comm);
        agents[0].tick(10.0);
        let m = agents[1].tick(10.0).messages.pop().expect("a message");
        (agents, m)
    }

    /// The counts after `arrival` reaches agent 0 at 10.5 s: exactly one drop, of `cause`.
    fn dropped_for(arrival: Arrival, cause: DropCause) {
        let fixture = Fixture::new("thesis-2x5", 3);
        let (mut agents, _) = scene(&fixture);
        let got = agents[0].admit(10.5, arrival);
        assert_eq!(got.err(), Some(Dropped { cause, first: true }));
        assert_eq!(agents[0].drops().count(cause), 1);
        assert_eq!(agents[0].drops().total(), 1, "{:?}", agents[0].drops());
        assert_eq!(agents[0].placed_known(), 0);
    }

    fn hostile(f: impl FnOnce(&mut Message), cause: DropCause) {
        let fixture = Fixture::new("thesis-2x5", 3);
        let (_, mut m) = scene(&fixture);
        f(&mut m);
        dropped_for(Arrival::keyed(m), cause);
    }

    fn bytes_of(m: &Message) -> serde_json::Value {
        serde_json::to_value(m).expect("a message serialises")
    }

    fn raw(v: &serde_json::Value) -> Arrival {
        Arrival::bytes(None, serde_json::to_vec(v).expect("json"))
    }

    #[test]
    fn an_honest_message_passes_keyed_and_as_bytes() {
        let fixture = Fixture::new("thesis-2x5", 3);
        let (mut agents, mut m) = scene(&fixture);
        m.status.placed = vec![0];
        let key = SampleKey::of(&m);
        let bytes = serde_json::to_vec(&m).unwrap();
        assert!(bytes.len() <= max_message_bytes(10, 3));
        assert_eq!(
            agents[0].hear(10.5, Arrival::bytes(Some(key), bytes)),
            Ok(())
        );
        assert_eq!(agents[0].placed_known(), 1);
        m.seq += 1;
        assert!(agents[0].hear(10.6, Arrival::keyed(m)).is_ok());
        assert_eq!(agents[0].drops().total(), 0);
    }

    #[test]
    fn an_oversized_sample_is_dropped_unread() {
        let fixture = Fixture::new("thesis-2x5", 3);
        let (_, m) = scene(&fixture);
        let mut v = bytes_of(&m);
        v["padding"] = serde_json::json!("x".repeat(max_message_bytes(10, 3)));
        dropped_for(raw(&v), DropCause::Size);
    }

    #[test]
    fn arrays_and_strings_over_their_bounds_are_dropped() {
        hostile(|m| m.status.heard.push(0.0), DropCause::Size);
        hostile(|m| m.status.placed = (0..11).collect(), DropCause::Size);
        hostile(
            |m| {
                m.status.out = vec![
                    super::super::Out {
                        uav: 2,
                        incarnation: 1
                    };
                    4
                ];
            },
            DropCause::Size,
        );
        hostile(|m| m.status.outcome = "x".repeat(33), DropCause::Size);
    }

    #[test]
    fn malformed_samples_are_dropped() {
        let fixture = Fixture::new("thesis-2x5", 3);
        let (_, m) = scene(&fixture);
        dropped_for(
            Arrival::bytes(None, b"{not json".to_vec()),
            DropCause::Malformed,
        );
        let mut v = bytes_of(&m);
        v["seq"] = serde_json::json!("seventeen");
        dropped_for(raw(&v), DropCause::Malformed);
        let mut v = bytes_of(&m);
        v["seq"] = serde_json::json!(1e300);
        dropped_for(raw(&v), DropCause::Malformed);
        let mut v = bytes_of(&m);
        v["status"]["state"] = serde_json::json!("Dancing");
        dropped_for(raw(&v), DropCause::Malformed);
        // A number too large for any integer field.
        let text = serde_json::to_string(&m).unwrap().replacen(
            "\"seq\":1",
            "\"seq\":99999999999999999999999",
            1,
        );
        dropped_for(
            Arrival::bytes(None, text.into_bytes()),
            DropCause::Malformed,
        );
    }

    #[test]
    fn other_versions_and_missions_are_dropped() {
        hostile(|m| m.v = SCHEMA_VERSION + 1, DropCause::Version);
        hostile(|m| m.mission = "other".into(), DropCause::Mission);
    }

    #[test]
    fn a_uav_outside_the_team_is_dropped() {
        // The heartbeat of "UAV 7" in a team of 3 that once ended every agent.
        hostile(|m| m.uav = 7, DropCause::UnknownUav);
        hostile(|m| m.uav = u32::MAX, DropCause::UnknownUav);
    }

    #[test]
    fn a_message_in_its_own_name_is_dropped() {
        hostile(|m| m.uav = 0, DropCause::Own);
    }

    #[test]
    fn a_key_that_disagrees_with_the_message_is_dropped() {
        let fixture = Fixture::new("thesis-2x5", 3);
        let (_, m) = scene(&fixture);
        for (uav, kind) in [
            ("2", m.kind.key()),
            ("1", "placed"),
            ("01", m.kind.key()),
            ("x", m.kind.key()),
        ] {
            let key = SampleKey {
                uav: uav.into(),
                kind: kind.into(),
            };
            let a = Arrival {
                key: Some(key),
                body: Body::Message(Box::new(m.clone())),
            };
            dropped_for(a, DropCause::Key);
        }
    }

    #[test]
    fn times_outside_the_window_are_dropped() {
        hostile(|m| m.t = 10.5 + TIME_AHEAD_S + 1.0, DropCause::Time);
        hostile(|m| m.t = 10.5 - TIME_BEHIND_S - 1.0, DropCause::Time);
        hostile(|m| m.t = f64::NAN, DropCause::Time);
    }

    #[test]
    fn replays_and_duplicates_are_dropped() {
        let fixture = Fixture::new("thesis-2x5", 3);
        let (mut agents, m) = scene(&fixture);
        assert!(agents[0].hear(10.5, Arrival::keyed(m.clone())).is_ok());
        let again = agents[0].admit(10.6, Arrival::keyed(m.clone()));
        assert_eq!(again.err().map(|d| d.cause), Some(DropCause::Replay));
        let mut older = m;
        older.incarnation = 0;
        let second = agents[0].admit(10.6, Arrival::keyed(older));
        assert_eq!(
            second.err(),
            Some(Dropped {
                cause: DropCause::Replay,
                first: false
            })
        );
        assert_eq!(agents[0].drops().count(DropCause::Replay), 2);
        assert_eq!(agents[0].drops().total(), 2);
    }

    #[test]
    fn absurd_jumps_are_dropped() {
        hostile(|m| m.incarnation = u64::MAX, DropCause::Jump);
        hostile(
            |m| m.incarnation = MAX_FIRST_INCARNATION + 1,
            DropCause::Jump,
        );
        hostile(|m| m.seq = u64::MAX, DropCause::Jump);
        hostile(|m| m.seq = 0, DropCause::Jump);
        // After an honest message, a bounded step only.
        let fixture = Fixture::new("thesis-2x5", 3);
        let (mut agents, m) = scene(&fixture);
        assert!(agents[0].hear(10.5, Arrival::keyed(m.clone())).is_ok());
        let mut far = m.clone();
        far.incarnation += MAX_INCARNATION_STEP + 1;
        far.seq = 1;
        let mut ahead = m.clone();
        ahead.seq += SEQ_SLACK + 1;
        for x in [far, ahead] {
            let got = agents[0].admit(10.6, Arrival::keyed(x));
            assert_eq!(got.err().map(|d| d.cause), Some(DropCause::Jump));
        }
        let mut next = m;
        next.incarnation += MAX_INCARNATION_STEP;
        next.seq = 1;
        assert!(agents[0].hear(10.7, Arrival::keyed(next)).is_ok());
        assert_eq!(agents[0].drops().count(DropCause::Jump), 2);
    }

    #[test]
    fn indices_and_numbers_out_of_range_are_dropped() {
        hostile(|m| m.status.brick = Some(10), DropCause::Range);
        hostile(|m| m.status.placed = vec![3, 2], DropCause::Range);
        hostile(|m| m.status.placed = vec![2, 2], DropCause::Range);
        hostile(|m| m.status.placed = vec![10], DropCause::Range);
        hostile(|m| m.status.x = f64::INFINITY, DropCause::Range);
        hostile(|m| m.status.y = 1e12, DropCause::Range);
        hostile(|m| m.status.heard[2] = -5.0, DropCause::Range);
        hostile(
            |m| {
                m.status.acks = vec![super::super::Ack {
                    uav: 9,
                    incarnation: 1,
                    id: 1,
                }]
            },
            DropCause::Range,
        );
        hostile(
            |m| {
                m.status.request = Some(super::super::Request {
                    id: 1,
                    brick: 0,
                    rank: 10,
                    expires: 20.0,
                })
            },
            DropCause::Range,
        );
    }

    #[test]
    fn every_brick_placed_early_is_implausible() {
        // The forged status that once landed a team with nothing built: every brick placed,
        // under a higher incarnation.
        hostile(
            |m| {
                m.incarnation += 1;
                m.seq = 1;
                m.status.placed = (0..10).collect();
            },
            DropCause::Implausible,
        );
    }

    fn station(seq: u64, t: f64, order: Order) -> Command {
        Command {
            v: SCHEMA_VERSION,
            mission: "test".into(),
            station: 2,
            seq,
            t,
            order,
        }
    }

    #[test]
    fn commands_are_checked_as_messages_are() {
        let ok = station(5, 10.0, Order::Land { uav: 2 });
        let fixture = Fixture::new("thesis-2x5", 3);
        let (mut agents, _) = scene(&fixture);
        let bytes = serde_json::to_vec(&ok).unwrap();
        let key = SampleKey::parse("mason/test/station-2/command");
        let heard = agents[0].admit(10.5, Arrival::bytes(key, bytes)).unwrap();
        assert_eq!(heard.command(), Some(&ok));
        assert_eq!(heard.message(), None);
        agents[0].receive(10.5, heard);
        // The same again, or an older one: a replay.
        for seq in [5, 4] {
            let got = agents[0].admit(10.6, Arrival::command(station(seq, 10.0, Order::Resume)));
            assert_eq!(got.err().map(|d| d.cause), Some(DropCause::Replay));
        }
        let cases = [
            (Command { v: 2, ..ok.clone() }, DropCause::Version),
            (
                Command {
                    mission: "x".into(),
                    ..ok.clone()
                },
                DropCause::Mission,
            ),
            (
                Command {
                    station: MAX_STATIONS as u32,
                    ..ok.clone()
                },
                DropCause::UnknownUav,
            ),
            (
                Command {
                    t: 500.0,
                    ..ok.clone()
                },
                DropCause::Time,
            ),
            (
                Command {
                    seq: SEQ_SLACK + 1,
                    ..ok.clone()
                },
                DropCause::Jump,
            ),
            (
                Command {
                    order: Order::Land { uav: 3 },
                    ..ok.clone()
                },
                DropCause::Range,
            ),
        ];
        for (c, cause) in cases {
            dropped_for(Arrival::command(c), cause);
        }
        let mut wrong_key = Arrival::command(ok.clone());
        wrong_key.key = SampleKey::parse("mason/test/station-1/command");
        dropped_for(wrong_key, DropCause::Key);
        let junk = Arrival::bytes(SampleKey::parse("m/t/station-2/command"), b"{}".to_vec());
        dropped_for(junk, DropCause::Malformed);
    }

    #[test]
    fn counts_print_by_cause_name() {
        let mut c = DropCounts::default();
        assert_eq!(format!("{c:?}"), "{}");
        c.record(DropCause::Key);
        assert_eq!(format!("{c:?}"), r#"{"key": 1}"#);
    }

    #[test]
    fn counts_serialise_by_cause_name() {
        let mut c = DropCounts::default();
        c.record(DropCause::Replay);
        c.record(DropCause::Replay);
        c.record(DropCause::UnknownUav);
        assert_eq!(
            serde_json::to_string(&c).unwrap(),
            r#"{"unknown_uav":1,"replay":2}"#
        );
        let mut team = c;
        team.add(&c);
        assert_eq!(team.count(DropCause::Replay), 4);
        assert_eq!(team.total(), 6);
        let names: std::collections::BTreeSet<_> =
            DropCause::ALL.iter().map(|c| c.name()).collect();
        assert_eq!(names.len(), DropCause::ALL.len());
        assert!(DropCause::ALL
            .iter()
            .enumerate()
            .all(|(i, c)| c.index() == i));
    }

    /// An honest sample's JSON with one byte changed, a cut, or a number swapped for another.
    fn mangled(json: &str, op: u8, at: usize, number: &str) -> Vec<u8> {
        let at = at % json.len();
        let mut b = json.as_bytes().to_vec();
        match op % 3 {
            0 => b[at] = b[at].wrapping_add(1 + (at % 7) as u8),
            1 => b.truncate(at),
            _ => {
                // The number starting at or after `at`, replaced.
                let start = (at..b.len()).find(|&i| b[i].is_ascii_digit() || b[i] == b'-');
                if let Some(s) = start {
                    let end = (s + 1..b.len())
                        .find(|&i| !(b[i].is_ascii_digit() || b"-+.eE".contains(&b[i])))
                        .unwrap_or(b.len());
                    b.splice(s..end, number.bytes());
                }
            }
        }
        b
    }

    mod mangled {
        use super::*;
        use proptest::prelude::*;

        proptest! {
            #![proptest_config(proptest::test_runner::Config {
                cases: 2000,
                rng_seed: proptest::test_runner::RngSeed::Fixed(27),
                ..proptest::test_runner::Config::default()
            })]

            /// Whatever a sample holds, the check never panics, and what it lets through keeps
            /// every bound.
            #[test]
            fn mangled_samples_never_break_a_bound(
                op in 0u8..3,
                at in 0usize..4096,
                number in prop_oneof![
                    any::<i64>().prop_map(|x| x.to_string()),
                    any::<f64>().prop_map(|x| format!("{x:?}")),
                    Just("1e308".to_string()),
                    Just("18446744073709551615".to_string()),
                ],
            ) {
                let fixture = Fixture::new("thesis-2x5", 3);
                let (mut agents, mut m) = scene(&fixture);
                m.status.placed = vec![0, 1];
                let json = serde_json::to_string(&m).unwrap();
                let sample = Arrival::bytes(Some(SampleKey::of(&m)), mangled(&json, op, at, &number));
                if let Ok(c) = agents[0].admit(10.5, sample) {
                    let m = c.message().expect("a status").clone();
                    prop_assert!(m.uav == 1 && m.incarnation >= 1 && m.seq >= 1);
                    prop_assert!((10.5 - TIME_BEHIND_S..=10.5 + TIME_AHEAD_S).contains(&m.t));
                    prop_assert_eq!(m.status.heard.len(), 3);
                    prop_assert!(m.status.placed.windows(2).all(|w| w[0] < w[1]));
                    prop_assert!(m.status.placed.iter().all(|&b| b < 10));
                    prop_assert!(m.status.brick.is_none_or(|b| b < 10));
                    prop_assert!([m.status.x, m.status.y, m.status.z].iter().all(|v| sane(*v)));
                    agents[0].receive(10.5, c);
                    agents[0].tick(10.6);
                } else {
                    prop_assert_eq!(agents[0].drops().total(), 1);
                }
            }
        }
    }

    #[test]
    fn sample_keys_are_the_last_two_chunks() {
        assert_eq!(
            SampleKey::parse("mason/m1/2/zone_request"),
            Some(SampleKey {
                uav: "2".into(),
                kind: "zone_request".into()
            })
        );
        assert_eq!(SampleKey::parse("heartbeat"), None);
    }
}
