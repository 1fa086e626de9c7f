"""Reads a Mason MCAP log with PyPI's `mcap` reader (not Mason's writer) and checks it.

Usage: read_mcap.py FILE

Every message is read and JSON-decoded; every schema must be a JSON Schema with the name its
topic should have, every channel JSON, every `timestamp` equal to the message's log time, and
each topic's log times non-decreasing (a `/wall` scene update has no timestamp: its
entities must be stamped no later than the message). Prints one line of JSON: messages per topic, schema per
topic, bricks placed, state events, zone entries, log lines by level, the MCAP metadata, and
the time span. Exits 1 with a message on the first failed check.
"""

import json
import re
import sys

from mcap.reader import make_reader

EXPECTED = {
    "/zone": "mason.Zone",
    "/bricks": "mason.Brick",
    "/wall": "foxglove.SceneUpdate",
    "/events": "foxglove.Log",
    "/messages": "mason.Message",
}
PER_UAV = {
    re.compile(r"^/uav/\d+/pose$"): "foxglove.PoseInFrame",
    re.compile(r"^/uav/\d+/state$"): "mason.UavState",
}


def expected_schema(topic):
    if topic in EXPECTED:
        return EXPECTED[topic]
    for pattern, name in PER_UAV.items():
        if pattern.match(topic):
            return name
    return None


def nanos(stamp):
    return stamp["sec"] * 1_000_000_000 + stamp["nsec"]


def fail(message):
    print(f"read_mcap: {message}", file=sys.stderr)
    sys.exit(1)


def main(path):
    counts = {}
    schemas = {}
    last_time = {}
    placed = []
    states = 0
    zone_entries = 0
    levels = {}
    with open(path, "rb") as stream:
        reader = make_reader(stream)
        summary = reader.get_summary()
        if summary is None:
            fail("no summary section")
        metadata = {}
        for record in reader.iter_metadata():
            metadata[record.name] = dict(record.metadata)
        for schema, channel, message in reader.iter_messages(log_time_order=False):
            topic = channel.topic
            if schema is None:
                fail(f"{topic}: no schema")
            want = expected_schema(topic)
            if want is None:
                fail(f"unexpected topic {topic}")
            if schema.name != want:
                fail(f"{topic}: schema {schema.name}, expected {want}")
            if schema.encoding != "jsonschema":
                fail(f"{topic}: schema encoding {schema.encoding}")
            if channel.message_encoding != "json":
                fail(f"{topic}: message encoding {channel.message_encoding}")
            json.loads(schema.data)
            body = json.loads(message.data)
            if topic == "/wall":
                # A scene update has no timestamp; its entities are stamped when they appeared.
                for entity in body["entities"]:
                    if nanos(entity["timestamp"]) > message.log_time:
                        fail(f"/wall: entity {entity['id']} is stamped after its message")
            elif "timestamp" not in body:
                fail(f"{topic}: no timestamp")
            elif nanos(body["timestamp"]) != message.log_time:
                fail(f"{topic}: timestamp {body['timestamp']} is not the log time {message.log_time}")
            if message.log_time < last_time.get(topic, 0):
                fail(f"{topic}: log time goes back at {message.log_time}")
            last_time[topic] = message.log_time
            counts[topic] = counts.get(topic, 0) + 1
            schemas[topic] = schema.name
            if topic == "/bricks" and body["action"] == "place":
                placed.append(body["brick"])
            elif topic.endswith("/state"):
                states += 1
            elif topic == "/zone" and body["event"] == "enter":
                zone_entries += 1
            elif topic == "/events":
                levels[str(body["level"])] = levels.get(str(body["level"]), 0) + 1
            elif topic.endswith("/pose"):
                p = body["pose"]["position"]
                float(p["x"]), float(p["y"]), float(p["z"])
    stats = summary.statistics
    total = sum(counts.values())
    if stats is not None and stats.message_count != total:
        fail(f"statistics count {stats.message_count} messages, read {total}")
    print(
        json.dumps(
            {
                "messages": total,
                "topics": dict(sorted(counts.items())),
                "schemas": dict(sorted(schemas.items())),
                "channels": sorted(c.topic for c in summary.channels.values()),
                "placed": len(placed),
                "placed_bricks": placed,
                "states": states,
                "zone_entries": zone_entries,
                "log_levels": dict(sorted(levels.items())),
                "metadata": metadata,
                "start_ns": stats.message_start_time if stats else None,
                "end_ns": stats.message_end_time if stats else None,
            },
            sort_keys=True,
        )
    )


if __name__ == "__main__":
    if len(sys.argv) != 2:
        fail("usage: read_mcap.py FILE")
    main(sys.argv[1])
