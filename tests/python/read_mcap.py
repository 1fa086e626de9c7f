"""Reads a Mason MCAP log with PyPI's `mcap` reader (not Mason's writer) and checks it.

Usage: read_mcap.py FILE [--foxglove DIR]

Every message is read and JSON-decoded and validated (PyPI `jsonschema`) against the JSON
Schema its channel declares; every schema must be a valid JSON Schema with the name its
topic should have, every channel JSON, every `timestamp` equal to the message's log time, and
each topic's log times non-decreasing (a `/wall` scene update has no timestamp: its
entities must be stamped no later than the message). Prints one line of JSON: messages per topic, schema per
topic, bricks placed, state events, zone entries, log lines by level, the MCAP metadata, and
the time span. Exits 1 with a message on the first failed check.

With `--foxglove DIR` (the published schemas, `foxglove.NAME.json`, from
scripts/fetch-foxglove-schemas.sh), every `foxglove.*` schema the log declares is compared with
the published one: each keyword Mason states, descriptions aside, must be there with the same
value (Mason may leave out what it never writes, such as `required` lists and the fields of
primitives it does not draw), and every message must validate against the published schema too.
"""

import json
import os
import re
import sys

import jsonschema
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


IGNORED = {"description", "$comment"}


def disagreement(ours, published, path=""):
    """The first place where `ours` states something `published` does not, or None."""
    if isinstance(ours, dict):
        if not isinstance(published, dict):
            return f"{path or '/'}: an object where the published schema has {published!r}"
        for key, value in ours.items():
            if key in IGNORED:
                continue
            if key not in published:
                return f"{path}/{key}: not in the published schema"
            found = disagreement(value, published[key], f"{path}/{key}")
            if found:
                return found
        return None
    if isinstance(ours, list):
        if not isinstance(published, list) or len(ours) != len(published):
            return f"{path}: {ours!r} against the published {published!r}"
        for i, (a, b) in enumerate(zip(ours, published)):
            found = disagreement(a, b, f"{path}[{i}]")
            if found:
                return found
        return None
    if ours != published:
        return f"{path}: {ours!r} against the published {published!r}"
    return None


def validator_for(schema_text, where):
    schema = json.loads(schema_text)
    cls = jsonschema.validators.validator_for(schema)
    try:
        cls.check_schema(schema)
    except jsonschema.SchemaError as e:
        fail(f"{where}: not a valid JSON Schema: {e.message}")
    return schema, cls(schema)


def main(path, foxglove_dir=None):
    validators = {}
    published = {}
    validated = 0
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
            if schema.id not in validators:
                ours, validators[schema.id] = validator_for(schema.data, f"{topic}: {schema.name}")
                if foxglove_dir is not None and schema.name.startswith("foxglove."):
                    file = os.path.join(foxglove_dir, f"{schema.name}.json")
                    if not os.path.exists(file):
                        fail(f"{schema.name}: no published schema {file}")
                    with open(file, encoding="utf-8") as f:
                        theirs, checker = validator_for(f.read(), file)
                    found = disagreement(ours, theirs)
                    if found:
                        fail(f"{schema.name} differs from Foxglove's published schema at {found}")
                    published[schema.id] = (schema.name, checker)
            body = json.loads(message.data)
            checks = [("", schema.name, validators[schema.id])]
            if schema.id in published:
                checks.append(("the published ", *published[schema.id]))
            for which, name, checker in checks:
                error = jsonschema.exceptions.best_match(checker.iter_errors(body))
                if error is not None:
                    where = "/".join(str(p) for p in error.absolute_path)
                    fail(
                        f"{topic}: the message at {message.log_time} ns breaks {which}{name} "
                        f"at /{where}: {error.message}"
                    )
            validated += 1
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
                "validated": validated,
                "compared_with_foxglove": sorted(name for name, _ in published.values()),
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
    args = sys.argv[1:]
    if len(args) == 3 and args[1] == "--foxglove":
        main(args[0], args[2])
    elif len(args) == 1:
        main(args[0])
    else:
        fail("usage: read_mcap.py FILE [--foxglove DIR]")
