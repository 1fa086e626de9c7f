//! Tests of whole logs, read back with the `mcap` crate: schemas and encodings, one message per
//! event and placement, poses in time order inside the arena, identical bytes for one trace,
//! and coordination messages.

use super::values::nanos;
use super::{cruise_altitude, mission_mcap, LogMeta, McapLog, McapLogError};
use mason_mission::{
    make_policy, simulate, Arena, Coord, Event, EventKind, MissionConfig, MissionInput,
};
use mason_wall::{BrickId, Wall};
use serde_json::{json, Value};
use std::collections::BTreeMap;
use std::io::Cursor;

/// A 3-UAV mission on the thesis's 2 × 5 wall: the trace and its end time.
fn flown() -> (Wall, MissionConfig, Vec<Event>, f64) {
    let wall = mason_wall::builtin("thesis-2x5").unwrap().wall();
    let model = mason_order::CostModel::default();
    let order: Vec<_> = wall.ids().collect();
    let config = MissionConfig::with_uavs(3);
    let input = MissionInput {
        wall: &wall,
        order: &order,
        model: &model,
        assignment: None,
        replanner: None,
        config: &config,
    };
    let mut trace = Vec::new();
    let r = simulate(
        input,
        make_policy(Coord::Comm, 20.0).as_mut(),
        7,
        &mut trace,
    );
    let end = r.metrics.end_s;
    (wall, config, trace, end)
}

fn bytes_of(wall: &Wall, config: &MissionConfig, trace: &[Event], end: f64) -> Vec<u8> {
    let meta = LogMeta {
        mission_id: "test",
        uavs: 3,
        arena: &config.arena,
        wall,
    };
    mission_mcap(&meta, trace, end).unwrap()
}

/// (topic, schema name, schema encoding, message encoding, log_time, payload) per message.
fn read_back(bytes: &[u8]) -> Vec<(String, String, String, String, u64, Value)> {
    ::mcap::MessageStream::new(bytes)
        .unwrap()
        .map(|m| {
            let m = m.unwrap();
            let schema = m
                .channel
                .schema
                .as_ref()
                .expect("every channel has a schema");
            let body: Value = serde_json::from_slice(&m.data).unwrap();
            assert_eq!(m.log_time, m.publish_time);
            (
                m.channel.topic.clone(),
                schema.name.clone(),
                schema.encoding.clone(),
                m.channel.message_encoding.clone(),
                m.log_time,
                body,
            )
        })
        .collect()
}

#[test]
fn the_log_reads_back_with_foxglove_schema_names_and_json() {
    let (wall, config, trace, end) = flown();
    let messages = read_back(&bytes_of(&wall, &config, &trace, end));
    let mut schemas = BTreeMap::new();
    for (topic, schema, schema_enc, msg_enc, log_time, body) in &messages {
        assert_eq!(schema_enc, "jsonschema");
        assert_eq!(msg_enc, "json");
        schemas.insert(topic.clone(), schema.clone());
        // The payload's timestamp is the message's log time.
        if let Some(ts) = body.get("timestamp") {
            let ns = ts["sec"].as_u64().unwrap() * 1_000_000_000 + ts["nsec"].as_u64().unwrap();
            assert_eq!(ns, *log_time, "{topic}");
        }
    }
    for i in 0..3 {
        assert_eq!(schemas[&format!("/uav/{i}/pose")], "foxglove.PoseInFrame");
        assert_eq!(schemas[&format!("/uav/{i}/state")], "mason.UavState");
    }
    assert_eq!(schemas["/wall"], "foxglove.SceneUpdate");
    assert_eq!(schemas["/events"], "foxglove.Log");
    assert_eq!(schemas["/zone"], "mason.Zone");
    assert_eq!(schemas["/bricks"], "mason.Brick");
    // The simulator sends no message: the channel exists, empty.
    assert!(!schemas.contains_key("/messages"));
    // Messages are in time order.
    assert!(messages.windows(2).all(|w| w[0].4 <= w[1].4));
}

#[test]
fn every_event_is_logged_once_and_every_placement_once() {
    let (wall, config, trace, end) = flown();
    let messages = read_back(&bytes_of(&wall, &config, &trace, end));
    let count = |topic: &str| messages.iter().filter(|m| m.0 == topic).count();
    assert_eq!(count("/events"), trace.len());
    let placed = trace
        .iter()
        .filter(|e| matches!(e.kind, EventKind::Place { .. }))
        .count();
    assert_eq!(placed, wall.len());
    let places: Vec<&Value> = messages
        .iter()
        .filter(|m| m.0 == "/bricks" && m.5["action"] == "place")
        .map(|m| &m.5)
        .collect();
    assert_eq!(places.len(), placed);
    assert_eq!(places.last().unwrap()["placed"], json!(placed));
    // The scene: once at the start, once per placement; the last one shows every brick.
    assert_eq!(count("/wall"), 1 + placed);
    let last_scene = &messages.iter().rev().find(|m| m.0 == "/wall").unwrap().5;
    let bricks = last_scene["entities"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|e| e["id"].as_str().unwrap().starts_with("brick/"))
        .count();
    assert_eq!(bricks, wall.len());
    for i in 0..3u32 {
        let states = trace
            .iter()
            .filter(|e| e.uav == i && matches!(e.kind, EventKind::State { .. }))
            .count();
        assert_eq!(count(&format!("/uav/{i}/state")), states);
    }
    let zone_events = trace
        .iter()
        .filter(|e| matches!(e.kind, EventKind::ZoneEnter | EventKind::ZoneLeave))
        .count();
    assert_eq!(count("/zone"), zone_events);
}

#[test]
fn poses_move_forward_in_time_and_stay_in_the_arena() {
    let (wall, config, trace, end) = flown();
    let messages = read_back(&bytes_of(&wall, &config, &trace, end));
    for i in 0..3 {
        let poses: Vec<_> = messages
            .iter()
            .filter(|m| m.0 == format!("/uav/{i}/pose"))
            .collect();
        // At least the 2 Hz samples of a mission that long.
        assert!(poses.len() as f64 > end, "UAV {i}: {} poses", poses.len());
        assert!(poses.windows(2).all(|w| w[0].4 <= w[1].4), "UAV {i}");
        assert_eq!(poses.last().unwrap().4, nanos(end));
        for p in &poses {
            let pos = &p.5["pose"]["position"];
            let (x, y, z) = (
                pos["x"].as_f64().unwrap(),
                pos["y"].as_f64().unwrap(),
                pos["z"].as_f64().unwrap(),
            );
            assert!((0.0..=config.arena.width).contains(&x), "{x}");
            assert!((0.0..=config.arena.depth).contains(&y), "{y}");
            assert!((0.0..=cruise_altitude(i)).contains(&z), "{z}");
            assert_eq!(p.5["frame_id"], "world");
        }
        // Landed at the end.
        assert_eq!(poses.last().unwrap().5["pose"]["position"]["z"], json!(0.0));
    }
}

#[test]
fn one_trace_gives_the_same_bytes() {
    let (wall, config, trace, end) = flown();
    let a = bytes_of(&wall, &config, &trace, end);
    let b = bytes_of(&wall, &config, &trace, end);
    assert_eq!(a, b);
}

#[test]
fn messages_are_logged_and_strangers_refused() {
    let wall = mason_wall::builtin("thesis-2x5").unwrap().wall();
    let arena = Arena::default();
    let meta = LogMeta {
        mission_id: "m-1",
        uavs: 2,
        arena: &arena,
        wall: &wall,
    };
    let mut log = McapLog::new(Cursor::new(Vec::new()), &meta).unwrap();
    log.message(1.5, 1, "claim", &json!({"brick": 101}))
        .unwrap();
    let err = log.message(2.0, 2, "claim", &json!({})).unwrap_err();
    assert!(
        matches!(err, McapLogError::UnknownUav { uav: 2, uavs: 2 }),
        "{err}"
    );
    let stranger = Event {
        t: 2.0,
        uav: 5,
        kind: EventKind::Fail,
    };
    assert!(log.event(&stranger).is_err());
    let far_brick = Event {
        t: 2.0,
        uav: 0,
        kind: EventKind::Place { brick: BrickId(99) },
    };
    assert!(matches!(
        log.event(&far_brick),
        Err(McapLogError::UnknownBrick { brick: 99, .. })
    ));
    let bytes = log.finish().unwrap().into_inner();
    let messages = read_back(&bytes);
    let sent: Vec<_> = messages.iter().filter(|m| m.0 == "/messages").collect();
    assert_eq!(sent.len(), 1);
    assert_eq!(sent[0].1, "mason.Message");
    assert_eq!(sent[0].4, 1_500_000_000);
    assert_eq!(sent[0].5["mission_id"], "m-1");
    assert_eq!(sent[0].5["body"]["brick"], 101);
}
