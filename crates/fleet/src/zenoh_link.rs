//! The Zenoh transport of an agent (feature `zenoh`): a peer-mode session with
//! multicast scouting off and explicit listen/connect endpoints.
//!
//! By default the links are QUIC (TLS 1.3) with mutual authentication (`tls/` links over TCP
//! carry the same; see [`crate::network::SecureLink`] for why QUIC is the default): every member shows a certificate
//! of the mission authority ([`crate::authority`]), checked before the session opens, and a
//! peer without one cannot join. On top, Zenoh's access control ([`access_control`]) lets in,
//! from the session of UAV *i* (the common name `uav-i` of its certificate), only puts on
//! `PREFIX/MISSION/i/**`, and from ground station *s* only puts on its command key
//! `PREFIX/MISSION/station-s/command`; anyone may subscribe. Every agent enforces this on what
//! it receives from each peer (the team is a full mesh of peers; peers route nothing for each
//! other), so a rogue with UAV 1's certificate cannot reach any agent as UAV 2. With
//! `--insecure` the links are plain and nothing of this applies.
//!
//! Each message goes out as
//! JSON (encoding `application/json`) on `PREFIX/MISSION/UAV/KIND`; the agent subscribes to
//! `PREFIX/MISSION/*/*` and skips its own key. Every other sample is handed over as it came,
//! its bytes and its key's last two chunks ([`Arrival`]), for the agent's check on arrival
//! ([`mason_mission::agent::Agent::admit`]): nothing is decoded here.
//!
//! An agent also answers queries on `PREFIX/MISSION/UAV/scene` with the wall it builds
//! ([`ZenohLink::serve_scene`]): how a client that is not a teammate (the ROS 2 bridge) learns
//! where each brick goes. A query is not a sample: the teammates' subscriptions never see it.

use crate::authority::{check_member, Member, TlsFiles, MAX_STATIONS};
use crate::error::{FleetError, FleetResult};
use crate::network::{Network, Security};
use crate::transport::Transport;
use mason_mission::agent::{Arrival, Message, MessageKind, SampleKey};
use std::collections::HashMap;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{mpsc, Arc};
use std::time::Instant;
use zenoh::bytes::Encoding;
use zenoh::pubsub::{Publisher, Subscriber};
use zenoh::query::Queryable;
use zenoh::{Session, Wait};

/// The most samples waiting to be checked: beyond, a sample is dropped unread and counted
/// ([`mason_mission::agent::DropCause::Overflow`]), so a flood cannot grow an agent's memory.
/// An agent checks samples in about a microsecond each; an honest team of N sends a few per
/// second each.
pub const RECEIVE_QUEUE: usize = 4096;

/// How long a dropped connection waits before it is tried again at first, and at most (ms).
const RETRY_MS: (u32, u32) = (100, 1000);

/// One agent's Zenoh session.
pub struct ZenohLink {
    session: Session,
    prefix: String,
    publishers: HashMap<&'static str, Publisher<'static>>,
    rx: mpsc::Receiver<Arrival>,
    overflow: Arc<AtomicU64>,
    _subscriber: Subscriber<()>,
    scene: Option<Queryable<()>>,
}

/// The last chunk of the key an agent answers scene queries on.
pub const SCENE_KIND: &str = "scene";

fn json_list(items: &[String]) -> String {
    serde_json::to_string(items).expect("strings")
}

/// Zenoh's access control for a team of `uavs` under `PREFIX/MISSION` (`base`), matched on
/// the common names of the peers' certificates: anyone may declare subscribers (and tokens,
/// queries, queryables) under `base/**`; UAV *i* may put only on `base/i/**` and station *s*
/// only on `base/station-s/command`; this agent puts only on its own key (`me`). Anything
/// else is denied.
pub fn access_control(base: &str, uavs: usize, me: &str) -> serde_json::Value {
    use serde_json::json;
    let listen = [
        "declare_subscriber",
        "liveliness_token",
        "declare_liveliness_subscriber",
        "liveliness_query",
        "query",
        "reply",
        "declare_queryable",
    ];
    let mut rules = vec![
        json!({"id": "listen", "messages": listen, "flows": ["ingress", "egress"],
               "permission": "allow", "key_exprs": [format!("{base}/**")]}),
        json!({"id": "own-puts", "messages": ["put"], "flows": ["egress"],
               "permission": "allow", "key_exprs": [format!("{base}/{me}/**")]}),
    ];
    let mut subjects = vec![json!({"id": "anyone"})];
    let mut policies = vec![json!({"rules": ["listen", "own-puts"], "subjects": ["anyone"]})];
    let members = (0..uavs)
        .map(Member::Uav)
        .chain((0..MAX_STATIONS).map(Member::Station));
    for m in members {
        let name = m.name();
        let key = match m {
            Member::Uav(i) => format!("{base}/{i}/**"),
            Member::Station(_) => format!("{base}/{name}/command"),
        };
        rules.push(
            json!({"id": format!("puts-{name}"), "messages": ["put"], "flows": ["ingress"],
                          "permission": "allow", "key_exprs": [key]}),
        );
        subjects.push(json!({"id": name, "cert_common_names": [name]}));
        policies.push(json!({"rules": [format!("puts-{name}")], "subjects": [name]}));
    }
    json!({"enabled": true, "default_permission": "deny",
           "rules": rules, "subjects": subjects, "policies": policies})
}

/// The session's configuration for UAV `me` of `uavs`: peer mode, no multicast scouting, the
/// given endpoints, and with TLS the member's files and the [`access_control`].
pub fn config(net: &Network, me: usize, uavs: usize) -> FleetResult<zenoh::Config> {
    let mut c = zenoh::Config::default();
    let mut set = |key: &str, value: String| {
        c.insert_json5(key, &value)
            .map_err(|e| FleetError::Network(format!("zenoh configuration {key} = {value}: {e}")))
    };
    set("mode", "\"peer\"".into())?;
    set("scouting/multicast/enabled", "false".into())?;
    set("listen/endpoints", json_list(&net.listen))?;
    set("connect/endpoints", json_list(&net.connect))?;
    set(
        "connect/retry",
        format!(
            "{{\"period_init_ms\": {}, \"period_max_ms\": {}, \"period_increase_factor\": 2}}",
            RETRY_MS.0, RETRY_MS.1
        ),
    )?;
    if let Security::Tls(dir) = &net.security {
        let files = TlsFiles::in_dir(dir);
        let path =
            |p: &std::path::Path| serde_json::to_string(&p.to_string_lossy()).expect("a string");
        let tls = "transport/link/tls";
        set(&format!("{tls}/root_ca_certificate"), path(&files.ca))?;
        for side in ["listen", "connect"] {
            set(&format!("{tls}/{side}_certificate"), path(&files.cert))?;
            set(&format!("{tls}/{side}_private_key"), path(&files.key))?;
        }
        set(&format!("{tls}/enable_mtls"), "true".into())?;
        // Peers are reached by address: what matters is the authority and the common name.
        set(&format!("{tls}/verify_name_on_connect"), "false".into())?;
        // Secure links only (the schemes of this agent's endpoints), accepted and opened:
        // gossip tells an agent of every peer's locators, and a link opened to a plain `tcp/`
        // one (a station's default listener) carries no certificate, so the access control
        // below, which knows subjects by their certificates' names, would drop that peer's
        // commands (an abort once reached one agent of three this way).
        set(
            "transport/link/protocols",
            json_list(&net.secure_protocols()),
        )?;
        let base = format!("{}/{}", net.prefix, net.mission);
        set(
            "access_control",
            access_control(&base, uavs, &me.to_string()).to_string(),
        )?;
    }
    Ok(c)
}

/// How long [`ZenohLink::close`] waits for Zenoh to close the session.
pub const CLOSE_GRACE: std::time::Duration = std::time::Duration::from_millis(500);

impl ZenohLink {
    /// Opens the session for UAV `me` of a team of `uavs`, after checking its TLS files
    /// (exit 2 if a file is missing, unreadable or not this UAV's of this mission, or an
    /// endpoint is refused, e.g. a port in use). A sample longer than `max_sample` bytes
    /// ([`mason_mission::agent::max_message_bytes`]) is queued cut to `max_sample + 1` bytes,
    /// enough for the check to drop it as too long: the queue holds at most
    /// [`RECEIVE_QUEUE`] × (`max_sample` + 1) bytes.
    pub fn open(net: &Network, me: usize, uavs: usize, max_sample: usize) -> FleetResult<Self> {
        if let Security::Tls(dir) = &net.security {
            check_member(
                "--tls-dir",
                &TlsFiles::in_dir(dir),
                &net.mission,
                Member::Uav(me),
            )?;
        }
        let session = zenoh::open(config(net, me, uavs)?).wait().map_err(|e| {
            FleetError::Network(format!(
                "zenoh: cannot open a session (listen {:?}, connect {:?}): {e}",
                net.listen, net.connect
            ))
        })?;
        let prefix = format!("{}/{}", net.prefix, net.mission);
        let (tx, rx) = mpsc::sync_channel(RECEIVE_QUEUE);
        let overflow = Arc::new(AtomicU64::new(0));
        let full = overflow.clone();
        let own = format!("{prefix}/{me}/");
        let subscriber = session
            .declare_subscriber(format!("{prefix}/*/*"))
            .callback(move |sample| {
                let key = sample.key_expr().as_str();
                if !key.starts_with(&own) {
                    let payload = sample.payload().to_bytes();
                    let bytes = payload[..payload.len().min(max_sample + 1)].to_vec();
                    let a = Arrival::bytes(SampleKey::parse(key), bytes);
                    if let Err(mpsc::TrySendError::Full(_)) = tx.try_send(a) {
                        full.fetch_add(1, Ordering::Relaxed);
                    }
                }
            })
            .wait()
            .map_err(|e| {
                FleetError::Network(format!("zenoh: cannot subscribe to {prefix}/*/*: {e}"))
            })?;
        Ok(ZenohLink {
            session,
            prefix: format!("{prefix}/{me}"),
            publishers: HashMap::new(),
            rx,
            overflow,
            _subscriber: subscriber,
            scene: None,
        })
    }

    /// Answers every query on `PREFIX/MISSION/UAV/scene` with `scene` (JSON, e.g.
    /// [`mason_report::wall_scene_json`]) for as long as the session is open.
    pub fn serve_scene(&mut self, scene: &serde_json::Value) -> FleetResult<()> {
        let key = format!("{}/{SCENE_KIND}", self.prefix);
        let bytes = serde_json::to_vec(scene).expect("a JSON value serialises");
        let reply_key = key.clone();
        let queryable = self
            .session
            .declare_queryable(&key)
            .callback(move |query| {
                let _ = query
                    .reply(&reply_key, bytes.clone())
                    .encoding(Encoding::APPLICATION_JSON)
                    .wait();
            })
            .wait()
            .map_err(|e| FleetError::Network(format!("zenoh: cannot serve {key}: {e}")))?;
        self.scene = Some(queryable);
        Ok(())
    }

    fn publisher(&mut self, kind: MessageKind) -> Option<&Publisher<'static>> {
        let key = kind.key();
        if !self.publishers.contains_key(key) {
            let p = self
                .session
                .declare_publisher(format!("{}/{key}", self.prefix))
                .encoding(Encoding::APPLICATION_JSON)
                .wait()
                .ok()?;
            self.publishers.insert(key, p);
        }
        self.publishers.get(key)
    }

    /// Closes the session (pending messages are flushed), waiting at most [`CLOSE_GRACE`]:
    /// over QUIC a peer that has already gone without its goodbye reaching us (its process
    /// ended before its endpoint sent it) holds Zenoh's close until its own 10 s timeout. The
    /// team has heard this agent's last words by then; what is cut short is only the goodbye.
    pub fn close(self) {
        let ZenohLink {
            session,
            publishers,
            _subscriber,
            scene,
            ..
        } = self;
        drop(scene);
        drop(_subscriber);
        drop(publishers);
        let (done, closed) = mpsc::channel();
        let closer = std::thread::Builder::new()
            .name("zenoh-close".into())
            .spawn(move || {
                let _ = session.close().wait();
                let _ = done.send(());
            });
        if closer.is_ok() {
            let _ = closed.recv_timeout(CLOSE_GRACE);
        }
    }
}

impl Transport for ZenohLink {
    fn send(&mut self, m: &Message) {
        let bytes = serde_json::to_vec(m).expect("a message serialises");
        if let Some(p) = self.publisher(m.kind) {
            // Best effort: a message lost here is repaired by the next heartbeat.
            let _ = p.put(bytes).wait();
        }
    }

    fn recv(&mut self, deadline: Instant) -> Vec<Arrival> {
        let wait = deadline.saturating_duration_since(Instant::now());
        let mut out = Vec::new();
        if let Ok(a) = self.rx.recv_timeout(wait) {
            out.push(a);
            out.extend(self.rx.try_iter().take(RECEIVE_QUEUE));
        }
        out
    }

    fn overflowed(&mut self) -> u64 {
        self.overflow.swap(0, Ordering::Relaxed)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn network(security: Security) -> Network {
        Network {
            mission: "m".into(),
            prefix: "mason".into(),
            listen: vec!["tls/127.0.0.1:7447".into()],
            connect: Vec::new(),
            security,
        }
    }

    /// A mutual-TLS team accepts and opens its secure links only, so that no peer learnt by
    /// gossip is reached over a plain link without a certificate (where the access control,
    /// which knows its subjects by their certificates, would drop a station's commands).
    #[test]
    fn a_tls_team_opens_and_accepts_secure_links_only() {
        let protocols = |c: &zenoh::Config| -> Vec<String> {
            serde_json::from_str(&c.get_json("transport/link/protocols").unwrap()).unwrap()
        };
        let tls = config(&network(Security::Tls("keys/uav-0".into())), 0, 3).unwrap();
        assert_eq!(protocols(&tls), ["tls"]);
        let mut net = network(Security::Tls("keys/uav-0".into()));
        net.listen = vec!["quic/127.0.0.1:7447".into()];
        net.connect = vec!["quic/127.0.0.1:7448".into()];
        assert_eq!(protocols(&config(&net, 0, 3).unwrap()), ["quic"]);
        assert!(tls
            .get_json("access_control/enabled")
            .unwrap()
            .contains("true"));
        let mut plain = network(Security::Insecure);
        plain.listen = vec!["tcp/127.0.0.1:7447".into()];
        let plain = config(&plain, 0, 3).unwrap();
        assert_eq!(plain.get_json("transport/link/protocols").unwrap(), "null");
    }
}
