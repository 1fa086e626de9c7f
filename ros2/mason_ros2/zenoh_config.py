"""The bridge's Zenoh session: peer mode, no multicast scouting, the team's endpoints, and
with ``--tls-dir DIR`` TLS with mutual authentication from the station's files (the layout of
``mason launch``: ``MISSION_DIR/station-<s>/{ca.pem,cert.pem,key.pem}``)."""

import json
import os

TLS_FILES = ("ca.pem", "cert.pem", "key.pem")


def tls_files(tls_dir: str):
    """The station's CA, certificate and key paths, or the reason they cannot be used."""
    paths = [os.path.join(tls_dir, f) for f in TLS_FILES]
    for p in paths:
        if not os.path.isfile(p):
            return f"{p}: missing (a TLS folder holds {', '.join(TLS_FILES)})"
        if not os.access(p, os.R_OK):
            return f"{p}: not readable"
    return paths


SECURE_SCHEMES = ("quic", "tls")


def secure_protocols(endpoints: list) -> list:
    """The secure schemes (quic before tls) that `endpoints` use, each once."""
    used = {e.split("/", 1)[0] for e in endpoints}
    return [s for s in SECURE_SCHEMES if s in used]


def config_entries(endpoints: list, tls_dir: str | None) -> dict:
    """The configuration as key → JSON5 value (checked by :func:`tls_files` first)."""
    e = {
        "mode": json.dumps("peer"),
        "scouting/multicast/enabled": "false",
        "connect/endpoints": json.dumps(endpoints),
        # Keep trying: the bridge may start before the team (100 ms, doubling up to 1 s).
        "connect/timeout_ms": "-1",
        "connect/exit_on_failure": "false",
        "connect/retry": json.dumps({"period_init_ms": 100, "period_max_ms": 1000,
                                     "period_increase_factor": 2}),
    }
    if tls_dir is not None:
        ca, cert, key = tls_files(tls_dir)
        tls = "transport/link/tls"
        e[f"{tls}/root_ca_certificate"] = json.dumps(ca)
        e[f"{tls}/connect_certificate"] = json.dumps(cert)
        e[f"{tls}/connect_private_key"] = json.dumps(key)
        e[f"{tls}/enable_mtls"] = "true"
        # Peers are reached by address: the mission's authority and the names are what count.
        e[f"{tls}/verify_name_on_connect"] = "false"
        # No listener of its own (Zenoh's default is plain tcp) and secure links only (the
        # schemes of its endpoints, quic and/or tls): an agent that reached the station over a
        # plain link, learnt by gossip, would see no certificate, and its access control would
        # drop the station's commands (an abort once reached one agent of three this way).
        e["listen/endpoints"] = json.dumps([])
        e["transport/link/protocols"] = json.dumps(secure_protocols(endpoints))
    return e


def zenoh_config(endpoints: list, tls_dir: str | None):
    """A ``zenoh.Config`` for the bridge."""
    import zenoh

    conf = zenoh.Config()
    for k, v in config_entries(endpoints, tls_dir).items():
        conf.insert_json5(k, v)
    return conf
