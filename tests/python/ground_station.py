"""A ground station that Mason did not write: PyPI's `eclipse-zenoh` listens to a running team.

Usage: ground_station.py ENDPOINT[,ENDPOINT...] PREFIX MISSION SECONDS [client|peer] [TLS_DIR]

Opens a Zenoh session (peer mode by default, multicast scouting off) connected to ENDPOINT
(over mutual TLS with the station's ca.pem, cert.pem and key.pem of TLS_DIR, if given),
subscribes to PREFIX/MISSION/**, and for SECONDS decodes every sample as JSON and checks it
against the message schema of the README (version 1): the key PREFIX/MISSION/UAV/KIND, the
fields and their types, the status inside. Prints one line of JSON: messages per UAV and kind,
the states and modes seen per UAV, the highest incarnation and sequence number per UAV, and
the first schema errors. Exits 1 if any message failed a check or none arrived.
"""

import json
import sys
import threading
import time

import zenoh

KINDS = {"heartbeat", "state", "claim", "zone_request", "zone_enter", "zone_release", "placed"}
STATES = {
    "Check", "TakeOff", "ChooseBrick", "FlyToPile", "Detect", "FlyAbove", "Grasp",
    "FlyToWallWait", "WaitForZone", "EnterAndPlace", "Land", "SafeLand", "Landed", "Down",
}
MODES = {"comm", "windows"}


def is_int(v):
    return isinstance(v, int) and not isinstance(v, bool)


def is_num(v):
    return (isinstance(v, (int, float))) and not isinstance(v, bool)


def check(key, encoding, m, prefix, mission):
    """The schema errors of one message (an empty list when it is good)."""
    errors = []

    def need(ok, what):
        if not ok:
            errors.append(f"{key}: {what}")

    parts = key.split("/")
    base = prefix.split("/") + [mission]
    need(parts[: len(base)] == base and len(parts) == len(base) + 2, "key is not PREFIX/MISSION/UAV/KIND")
    need(encoding.startswith("application/json"), f"encoding {encoding}")
    if not isinstance(m, dict):
        return errors + [f"{key}: not a JSON object"]
    need(m.get("v") == 1, "v != 1")
    need(m.get("mission") == mission, "mission differs from the key")
    need(is_int(m.get("uav")) and str(m.get("uav")) == parts[-2], "uav missing or not the key's")
    need(is_int(m.get("incarnation")) and m["incarnation"] >= 1, "incarnation")
    need(is_int(m.get("seq")) and m["seq"] >= 1, "seq")
    need(is_num(m.get("t")), "t")
    need(m.get("kind") in KINDS and m.get("kind") == parts[-1], "kind missing or not the key's")
    s = m.get("status")
    if not isinstance(s, dict):
        return errors + [f"{key}: status is not an object"]
    need(s.get("state") in STATES, f"status.state {s.get('state')!r}")
    need(isinstance(s.get("outcome"), str), "status.outcome")
    for f in ("x", "y", "z", "claimed_at"):
        need(is_num(s.get(f)), f"status.{f}")
    need(s.get("mode") in MODES, "status.mode")
    need(s.get("brick") is None or is_int(s.get("brick")), "status.brick")
    for f in ("grasped", "in_zone"):
        need(isinstance(s.get(f), bool), f"status.{f}")
    r = s.get("request")
    need(r is None or (isinstance(r, dict) and all(is_int(r.get(f)) for f in ("id", "brick", "rank"))
                       and is_num(r.get("expires"))), "status.request")
    p = s.get("pair")
    need(p is None or (isinstance(p, dict) and is_int(p.get("uav")) and is_int(p.get("incarnation"))
                       and is_num(p.get("claimed_at")) and is_num(p.get("since"))), "status.pair")
    acks = s.get("acks")
    need(isinstance(acks, list) and all(isinstance(a, dict) and all(is_int(a.get(f)) for f in ("uav", "incarnation", "id"))
                                        for a in acks), "status.acks")
    placed = s.get("placed")
    need(isinstance(placed, list) and all(is_int(b) for b in placed) and placed == sorted(placed), "status.placed")
    heard = s.get("heard")
    need(isinstance(heard, list) and all(is_num(h) for h in heard), "status.heard")
    out = s.get("out")
    need(isinstance(out, list) and all(isinstance(o, dict) and is_int(o.get("uav")) and is_int(o.get("incarnation"))
                                       for o in out), "status.out")
    return errors


def main():
    if len(sys.argv) not in (5, 6, 7):
        sys.exit(__doc__)
    endpoints, prefix, mission, seconds = sys.argv[1].split(","), sys.argv[2], sys.argv[3], float(sys.argv[4])
    mode = sys.argv[5] if len(sys.argv) >= 6 else "peer"
    conf = zenoh.Config()
    conf.insert_json5("mode", json.dumps(mode))
    conf.insert_json5("connect/endpoints", json.dumps(endpoints))
    conf.insert_json5("scouting/multicast/enabled", "false")
    if len(sys.argv) == 7:
        tls, folder = "transport/link/tls", sys.argv[6]
        conf.insert_json5(f"{tls}/root_ca_certificate", json.dumps(f"{folder}/ca.pem"))
        conf.insert_json5(f"{tls}/enable_mtls", "true")
        conf.insert_json5(f"{tls}/verify_name_on_connect", "false")
        for side in ("listen", "connect"):
            conf.insert_json5(f"{tls}/{side}_certificate", json.dumps(f"{folder}/cert.pem"))
            conf.insert_json5(f"{tls}/{side}_private_key", json.dumps(f"{folder}/key.pem"))
    lock = threading.Lock()
    per_uav, states, modes, latest, errors = {}, {}, {}, {}, []
    count = [0]

    def on_sample(sample):
        key = str(sample.key_expr)
        try:
            m = json.loads(sample.payload.to_bytes())
        except ValueError as e:
            with lock:
                errors.append(f"{key}: not JSON: {e}")
            return
        problems = check(key, str(sample.encoding), m, prefix, mission)
        with lock:
            count[0] += 1
            errors.extend(problems)
            if problems:
                return
            u = str(m["uav"])
            kinds = per_uav.setdefault(u, {})
            kinds[m["kind"]] = kinds.get(m["kind"], 0) + 1
            seen = states.setdefault(u, [])
            if m["status"]["state"] not in seen:
                seen.append(m["status"]["state"])
            ms = modes.setdefault(u, [])
            if m["status"]["mode"] not in ms:
                ms.append(m["status"]["mode"])
            latest[u] = max(latest.get(u, (0, 0)), (m["incarnation"], m["seq"]))

    session = zenoh.open(conf)
    sub = session.declare_subscriber(f"{prefix}/{mission}/**", on_sample)
    time.sleep(seconds)
    sub.undeclare()
    session.close()
    with lock:
        summary = {
            "messages": count[0],
            "per_uav": per_uav,
            "states": states,
            "modes": modes,
            "latest": {u: {"incarnation": i, "seq": s} for u, (i, s) in latest.items()},
            "errors": errors[:20],
            "error_count": len(errors),
        }
    print(json.dumps(summary, sort_keys=True))
    sys.exit(1 if errors or count[0] == 0 else 0)


if __name__ == "__main__":
    main()
