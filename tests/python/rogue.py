"""A stranger on the team's network (issue #27): PyPI's `eclipse-zenoh` tries to join a running
team and to speak in it.

Usage: rogue.py ENDPOINT[,ENDPOINT...] PREFIX MISSION SECONDS ATTACK [CA CERT KEY]

Opens a peer-mode Zenoh session (multicast scouting off) connected to the endpoints, subscribes to
PREFIX/MISSION/** and, during SECONDS, carries out ATTACK, one of:

- `malformed`: samples that are not messages (`{}`, bytes that are not JSON, a string where a
  number goes) on UAV 1's status key;
- `as-uav-2`: a forged status of UAV 2 saying every brick is placed, and `{}`, on UAV 2's keys;
- `as-uav-0`: the same on UAV 0's keys;
- `unknown-uav`: heartbeats of UAV 7, on UAV 7's key;
- `replay`: every message heard, sent again on its own key a second later;
- `flood`: 10 000 samples a second (copies of the last message heard, or `{}` before any) on
  UAV 1's heartbeat key.

With CA (the authority's certificate) the link is TLS (`quic/` or `tls/` endpoints); with CERT and KEY too, the rogue shows
that certificate (mutual TLS); CERT and KEY may be `-` for none. Prints one line of JSON:
`{"heard": samples heard from others, "sent": samples put}`. The test that runs it decides
from the team's outcome and its drop counters whether the attack got in.
"""

import json
import sys
import threading
import time

import zenoh

FLOOD_PER_S = 10_000


def forged(mission, uav, uavs=3, bricks=42, t=0.0):
    """A status of `uav` that claims every brick placed, under a high incarnation."""
    return {
        "v": 1, "mission": mission, "uav": uav, "incarnation": 9, "seq": 1, "t": t,
        "kind": "heartbeat",
        "status": {
            "state": "Landed", "outcome": "done", "x": 0.0, "y": 0.0, "z": 0.0, "mode": "comm",
            "brick": None, "claimed_at": 0.0, "grasped": False, "pair": None, "in_zone": False,
            "request": None, "acks": [], "placed": list(range(bricks)), "heard": [t] * uavs,
            "out": [],
        },
    }


def main():
    if len(sys.argv) not in (6, 9):
        sys.exit(__doc__)
    endpoint, prefix, mission, seconds, attack = sys.argv[1:6]
    seconds = float(seconds)
    base = f"{prefix}/{mission}"
    conf = zenoh.Config()
    conf.insert_json5("mode", '"peer"')
    conf.insert_json5("connect/endpoints", json.dumps(endpoint.split(",")))
    conf.insert_json5("scouting/multicast/enabled", "false")
    if len(sys.argv) == 9:
        ca, cert, key = sys.argv[6:9]
        tls = "transport/link/tls"
        conf.insert_json5(f"{tls}/root_ca_certificate", json.dumps(ca))
        conf.insert_json5(f"{tls}/verify_name_on_connect", "false")
        if cert != "-":
            conf.insert_json5(f"{tls}/enable_mtls", "true")
            for side in ("listen", "connect"):
                conf.insert_json5(f"{tls}/{side}_certificate", json.dumps(cert))
                conf.insert_json5(f"{tls}/{side}_private_key", json.dumps(key))
    lock = threading.Lock()
    heard = []
    session = zenoh.open(conf)

    def on_sample(sample):
        with lock:
            heard.append((time.monotonic(), str(sample.key_expr), sample.payload.to_bytes()))

    sub = session.declare_subscriber(f"{base}/**", on_sample)
    remote = zenoh.Locality.REMOTE

    def put(key, payload):
        # Only to others: what the rogue hears is the team's.
        session.put(key, payload, allowed_destination=remote)

    sent = 0
    replayed = 0
    start = time.monotonic()
    while time.monotonic() - start < seconds:
        now = time.monotonic()
        if attack == "malformed":
            key = f"{base}/1/heartbeat"
            for payload in (b"{}", b"\xff\xfe not json", b'{"v":1,"mission":3}', b"[" * 5000):
                put(key, payload)
                sent += 1
        elif attack in ("as-uav-2", "as-uav-0"):
            uav = int(attack[-1])
            put(f"{base}/{uav}/heartbeat", json.dumps(forged(mission, uav)))
            put(f"{base}/{uav}/placed", b"{}")
            sent += 2
        elif attack == "unknown-uav":
            put(f"{base}/7/heartbeat", json.dumps(forged(mission, 7)))
            sent += 1
        elif attack == "replay":
            with lock:
                due = [h for h in heard[replayed:] if now - h[0] >= 1.0]
            for _, key, payload in due:
                put(key, payload)
            replayed += len(due)
            sent += len(due)
        elif attack == "flood":
            with lock:
                last = heard[-1][2] if heard else b"{}"
            key = f"{base}/1/heartbeat"
            # 100 samples every 10 ms.
            for _ in range(FLOOD_PER_S // 100):
                put(key, last)
            sent += FLOOD_PER_S // 100
            time.sleep(max(0.0, 0.01 - (time.monotonic() - now)))
            continue
        else:
            sys.exit(f"unknown attack {attack!r}")
        time.sleep(0.05)
    sub.undeclare()
    session.close()
    with lock:
        count = len(heard)
    print(json.dumps({"attack": attack, "heard": count, "sent": sent}))


if __name__ == "__main__":
    main()
