//! The team protocol on the wire (schema version [`SCHEMA_VERSION`]): one [`Message`] as a
//! JSON object per Zenoh sample, on the key `<prefix>/<mission>/<uav>/<kind>`.
//!
//! Programs that Mason did not write follow this schema too (the Python ground station of
//! `tests/python/ground_station.py`, the ROS 2 bridge), so every field is documented with its
//! JSON name, type and unit. Field names are those of the Rust structs below; enums are
//! strings (`kind` in snake_case, `state` in CamelCase, `mode` in lowercase); `Option`s are
//! `null` when absent (a reader treats a missing `pair` as `null`); times are mission seconds
//! as JSON numbers; indices (`uav`, `brick`) are 0-based integers. A message of another schema
//! version, of another mission, or that fails these rules is ignored by the agents.
//!
//! ```json
//! {"v":1,"mission":"m1","uav":2,"incarnation":3,"seq":17,"t":12.5,"kind":"zone_request",
//!  "status":{"state":"WaitForZone","outcome":"arrived","x":1.5,"y":-2.0,"z":5.0,
//!   "mode":"windows","brick":4,"claimed_at":3.25,"grasped":true,
//!   "pair":{"uav":1,"incarnation":2,"claimed_at":3.0,"since":4.0},"in_zone":false,
//!   "request":{"id":7,"brick":4,"rank":2,"expires":17.5},
//!   "acks":[{"uav":0,"incarnation":1,"id":9}],"placed":[0,1,3],
//!   "heard":[11.0,-1.0,12.5],"out":[{"uav":1,"incarnation":1}]}}
//! ```

use crate::state::{CommMode, UavState};
use serde::{Deserialize, Serialize};

/// The message schema's version; a message of another version is ignored.
pub const SCHEMA_VERSION: u32 = 1;

/// Why a message was sent (JSON: a snake_case string, also the key's last segment). Every
/// message carries the whole status anyway, so a reader may treat them all alike.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum MessageKind {
    /// `heartbeat`: the periodic heartbeat (every `coord.heartbeat_s`).
    Heartbeat,
    /// `state`: a state transition, or a change of what it holds out or its mode.
    State,
    /// `claim`: a brick claimed (or a claim dropped).
    Claim,
    /// `zone_request`: a zone request made or renewed.
    ZoneRequest,
    /// `zone_enter`: entered the zone.
    ZoneEnter,
    /// `zone_release`: left the zone (and released the request).
    ZoneRelease,
    /// `placed`: a brick placed.
    Placed,
}

impl MessageKind {
    /// The last segment of the message's key (`<prefix>/<mission>/<uav>/<kind>`).
    pub fn key(self) -> &'static str {
        match self {
            MessageKind::Heartbeat => "heartbeat",
            MessageKind::State => "state",
            MessageKind::Claim => "claim",
            MessageKind::ZoneRequest => "zone_request",
            MessageKind::ZoneEnter => "zone_enter",
            MessageKind::ZoneRelease => "zone_release",
            MessageKind::Placed => "placed",
        }
    }

    /// How telling the reason is: when several happen in one tick, the most telling one names
    /// the message (a placement over a zone message over a claim over a state change over a
    /// heartbeat).
    pub(super) fn weight(self) -> u8 {
        match self {
            MessageKind::Heartbeat => 0,
            MessageKind::State => 1,
            MessageKind::Claim => 2,
            MessageKind::ZoneRequest => 3,
            MessageKind::ZoneEnter => 4,
            MessageKind::ZoneRelease => 5,
            MessageKind::Placed => 6,
        }
    }
}

/// A zone request (JSON object `request`): the sender asks its flying teammates to keep out
/// of the wall zone while it places `brick`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct Request {
    /// `id`: the request's number, counted from 1 within the sender's incarnation; a renewed
    /// request gets a new number.
    pub id: u64,
    /// `brick`: the brick to place (wall index).
    pub brick: u32,
    /// `rank`: the brick's rank in the shared order (lower goes first; ties go to the lower
    /// UAV number).
    pub rank: u32,
    /// `expires`: the request may be used to enter until then (mission s); renewed while
    /// waiting.
    pub expires: f64,
}

/// An acknowledgement of a teammate's zone request (JSON object in `acks`): the sender keeps
/// out of the zone until the request is released or its lease and the longest zone time
/// have passed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Ack {
    /// `uav`: the requester.
    pub uav: u32,
    /// `incarnation`: the requester's incarnation.
    pub incarnation: u64,
    /// `id`: the request's number.
    pub id: u64,
}

/// The partner a pair's leader carries an orange brick with (JSON object `pair`): that UAV
/// under that claim.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct PairRef {
    /// `uav`: the partner.
    pub uav: u32,
    /// `incarnation`: the partner's incarnation.
    pub incarnation: u64,
    /// `claimed_at`: when the partner claimed the brick (mission s; compared with a
    /// tolerance of 1e-6 relative, so a JSON round trip may change its last bits).
    pub claimed_at: f64,
    /// `since`: when the pair formed (mission s): a fall of the brick reported since then is
    /// this pair's.
    pub since: f64,
}

/// A teammate declared out (JSON object in `out`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Out {
    /// `uav`: the UAV.
    pub uav: u32,
    /// `incarnation`: the incarnation declared out (a later one is back in).
    pub incarnation: u64,
}

/// What a UAV tells its team in every message (JSON object `status`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Status {
    /// `state`: its state, a CamelCase string (`"Check"`, `"TakeOff"`, … `"Down"`).
    pub state: UavState,
    /// `outcome`: the outcome that led to that state (`"start"`, `"arrived"`, …).
    pub outcome: String,
    /// `x`: position east (m, arena frame).
    pub x: f64,
    /// `y`: position north (m, arena frame).
    pub y: f64,
    /// `z`: altitude (m; see [`mod@crate::altitude`]).
    pub z: f64,
    /// `mode`: its coordination mode now, `"comm"` or `"windows"`.
    pub mode: CommMode,
    /// `brick`: the brick it claims (wall index), or `null`.
    pub brick: Option<u32>,
    /// `claimed_at`: when it claimed it (mission s; 0 before any claim).
    pub claimed_at: f64,
    /// `grasped`: whether it holds the brick.
    pub grasped: bool,
    /// `pair`: leading an orange brick's pair, the partner it carries it with; else `null`.
    pub pair: Option<PairRef>,
    /// `in_zone`: whether it is inside the wall zone.
    pub in_zone: bool,
    /// `request`: its zone request, or `null`.
    pub request: Option<Request>,
    /// `acks`: the teammates' requests it acknowledges.
    pub acks: Vec<Ack>,
    /// `placed`: every brick it knows placed (wall indices, ascending).
    pub placed: Vec<u32>,
    /// `heard`: one number per UAV of the team (its own entry is the send time): the send
    /// time, by the sender's clock, of the last message heard from that UAV (-1: never).
    pub heard: Vec<f64>,
    /// `out`: the teammates it holds out.
    pub out: Vec<Out>,
}

/// One message of the team protocol (schema version [`SCHEMA_VERSION`]); JSON on the wire.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Message {
    /// `v`: the schema version, [`SCHEMA_VERSION`].
    pub v: u32,
    /// `mission`: the mission id (also in the key): two missions on one network never mix.
    pub mission: String,
    /// `uav`: the sender (0-based; also in the key).
    pub uav: u32,
    /// `incarnation`: the sender's incarnation, from 1; it grows when an agent restarts or
    /// rejoins after being declared out.
    pub incarnation: u64,
    /// `seq`: the sequence number within the incarnation, from 1. A receiver keeps only a
    /// message newer by (incarnation, seq) than the last it kept from that sender.
    pub seq: u64,
    /// `t`: mission time when sent (s).
    pub t: f64,
    /// `kind`: why it was sent.
    pub kind: MessageKind,
    /// `status`: the sender's whole status.
    pub status: Status,
}

/// What a ground station orders (JSON: the `command` field, a snake_case string).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(tag = "command", rename_all = "snake_case")]
pub enum Order {
    /// `abort`: every UAV lands after the brick in hand, and its mission ends.
    Abort,
    /// `land` (with `uav`): that UAV lands after the brick in hand and waits on the ground
    /// for `resume`.
    Land {
        /// `uav`: the UAV (0-based).
        uav: u32,
    },
    /// `resume`: UAVs waiting on the ground take off again, and landings not yet begun are
    /// called off (an `abort` included).
    Resume,
}

/// A ground station's command (schema version [`SCHEMA_VERSION`]), on the key
/// `<prefix>/<mission>/station-<station>/command`:
/// `{"v":1,"mission":"m1","station":0,"seq":3,"t":120.0,"command":"land","uav":1}`.
///
/// Without TLS and access control (issue #27 items 1 and 2) anyone on the network can send
/// one: the checks on arrival hold it to the schema, the mission, the station's key, a time
/// window and a growing `seq`, not to who sent it.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct Command {
    /// `v`: the schema version, [`SCHEMA_VERSION`].
    pub v: u32,
    /// `mission`: the mission id.
    pub mission: String,
    /// `station`: the ground station (0-based, below [`super::gate::MAX_STATIONS`]).
    pub station: u32,
    /// `seq`: the station's sequence number, from 1; a receiver obeys only a higher one.
    pub seq: u64,
    /// `t`: mission time when sent (s).
    pub t: f64,
    /// `command` (and its fields): what to do.
    #[serde(flatten)]
    pub order: Order,
}

impl Command {
    /// The last chunks of the command's key: `station-<station>/command`.
    pub fn key(&self) -> String {
        format!("{}{}/{}", STATION_CHUNK, self.station, COMMAND_KIND)
    }
}

/// A station's key chunk is this prefix and its number.
pub const STATION_CHUNK: &str = "station-";
/// The last chunk of a command's key.
pub const COMMAND_KIND: &str = "command";

/// Whether two times that may have crossed the wire name the same instant: a JSON round trip
/// by another client may change a float's last bits.
pub(super) fn same_time(a: f64, b: f64) -> bool {
    (a - b).abs() <= 1e-6 * (1.0 + a.abs().max(b.abs()))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The message of the module documentation.
    fn sample() -> Message {
        Message {
            v: SCHEMA_VERSION,
            mission: "m1".into(),
            uav: 2,
            incarnation: 3,
            seq: 17,
            t: 12.5,
            kind: MessageKind::ZoneRequest,
            status: Status {
                state: UavState::WaitForZone,
                outcome: "arrived".into(),
                x: 1.5,
                y: -2.0,
                z: 5.0,
                mode: CommMode::Windows,
                brick: Some(4),
                claimed_at: 3.25,
                grasped: true,
                pair: Some(PairRef {
                    uav: 1,
                    incarnation: 2,
                    claimed_at: 3.0,
                    since: 4.0,
                }),
                in_zone: false,
                request: Some(Request {
                    id: 7,
                    brick: 4,
                    rank: 2,
                    expires: 17.5,
                }),
                acks: vec![Ack {
                    uav: 0,
                    incarnation: 1,
                    id: 9,
                }],
                placed: vec![0, 1, 3],
                heard: vec![11.0, -1.0, 12.5],
                out: vec![Out {
                    uav: 1,
                    incarnation: 1,
                }],
            },
        }
    }

    /// Written by the schema before the agent was split into files: the wire must not change.
    const SAMPLE_JSON: &str = concat!(
        r#"{"v":1,"mission":"m1","uav":2,"incarnation":3,"seq":17,"t":12.5,"kind":"zone_request","#,
        r#""status":{"state":"WaitForZone","outcome":"arrived","x":1.5,"y":-2.0,"z":5.0,"#,
        r#""mode":"windows","brick":4,"claimed_at":3.25,"grasped":true,"#,
        r#""pair":{"uav":1,"incarnation":2,"claimed_at":3.0,"since":4.0},"in_zone":false,"#,
        r#""request":{"id":7,"brick":4,"rank":2,"expires":17.5},"#,
        r#""acks":[{"uav":0,"incarnation":1,"id":9}],"placed":[0,1,3],"#,
        r#""heard":[11.0,-1.0,12.5],"out":[{"uav":1,"incarnation":1}]}}"#
    );

    #[test]
    fn the_wire_format_is_unchanged() {
        assert_eq!(serde_json::to_string(&sample()).unwrap(), SAMPLE_JSON);
        let back: Message = serde_json::from_str(SAMPLE_JSON).unwrap();
        assert_eq!(back, sample());
    }

    #[test]
    fn the_module_example_is_the_sample() {
        let doc: Message = serde_json::from_str(
            r#"{"v":1,"mission":"m1","uav":2,"incarnation":3,"seq":17,"t":12.5,"kind":"zone_request",
             "status":{"state":"WaitForZone","outcome":"arrived","x":1.5,"y":-2.0,"z":5.0,
              "mode":"windows","brick":4,"claimed_at":3.25,"grasped":true,
              "pair":{"uav":1,"incarnation":2,"claimed_at":3.0,"since":4.0},"in_zone":false,
              "request":{"id":7,"brick":4,"rank":2,"expires":17.5},
              "acks":[{"uav":0,"incarnation":1,"id":9}],"placed":[0,1,3],
              "heard":[11.0,-1.0,12.5],"out":[{"uav":1,"incarnation":1}]}}"#,
        )
        .unwrap();
        assert_eq!(doc, sample());
    }

    #[test]
    fn a_missing_pair_reads_as_none() {
        let mut v = serde_json::to_value(sample()).unwrap();
        v["status"].as_object_mut().unwrap().remove("pair");
        let m: Message = serde_json::from_value(v).unwrap();
        assert_eq!(m.status.pair, None);
    }

    #[test]
    fn every_kind_is_named_on_the_wire_as_in_its_key() {
        let kinds = [
            MessageKind::Heartbeat,
            MessageKind::State,
            MessageKind::Claim,
            MessageKind::ZoneRequest,
            MessageKind::ZoneEnter,
            MessageKind::ZoneRelease,
            MessageKind::Placed,
        ];
        for (i, k) in kinds.iter().enumerate() {
            assert_eq!(serde_json::to_value(k).unwrap(), serde_json::json!(k.key()));
            // Declared from the least to the most telling.
            assert_eq!(usize::from(k.weight()), i);
        }
    }

    #[test]
    fn commands_read_as_documented() {
        let c: Command = serde_json::from_str(
            r#"{"v":1,"mission":"m1","station":0,"seq":3,"t":120.0,"command":"land","uav":1}"#,
        )
        .unwrap();
        assert_eq!(c.order, Order::Land { uav: 1 });
        assert_eq!(c.key(), "station-0/command");
        let abort = Command {
            order: Order::Abort,
            ..c.clone()
        };
        assert_eq!(
            serde_json::to_string(&abort).unwrap(),
            r#"{"v":1,"mission":"m1","station":0,"seq":3,"t":120.0,"command":"abort"}"#
        );
        for bad in [r#""command":"explode""#, r#""command":"land""#] {
            let text = format!(r#"{{"v":1,"mission":"m","station":0,"seq":1,"t":0.0,{bad}}}"#);
            assert!(serde_json::from_str::<Command>(&text).is_err(), "{bad}");
        }
    }

    #[test]
    fn times_that_crossed_the_wire_still_match() {
        assert!(same_time(3.0, 3.0));
        assert!(same_time(1234.5678, 1234.5678 + 1e-9));
        assert!(!same_time(3.0, 3.01));
        assert!(!same_time(0.0, 1e-3));
    }
}
