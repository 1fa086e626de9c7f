//! Where and how an agent talks: the mission id, the key prefix, the Zenoh endpoints and its
//! security (the files of its mission authority, or `--insecure`), from flags and a network
//! TOML file, every one checked before a transport sees it.

use crate::error::{FleetError, FleetResult};
use serde::Deserialize;
use std::path::{Path, PathBuf};

/// The default key prefix.
pub const DEFAULT_PREFIX: &str = "mason";

/// Where and how an agent talks, checked.
#[derive(Clone, Debug, PartialEq)]
pub struct Network {
    /// The mission id (one key chunk).
    pub mission: String,
    /// The key prefix (key chunks, no wildcard).
    pub prefix: String,
    /// Endpoints to listen on.
    pub listen: Vec<String>,
    /// Endpoints to connect to.
    pub connect: Vec<String>,
    /// How the links are secured.
    pub security: Security,
}

/// How an agent's links are secured (DESIGN §8).
#[derive(Clone, Debug, PartialEq)]
pub enum Security {
    /// Zenoh TLS with mutual authentication and access control, from the member's folder of
    /// `ca.pem`, `cert.pem` and `key.pem` (`--tls-dir`, see `mason keys`). Endpoints are
    /// `quic/` (TLS 1.3 inside QUIC, Mason's default, see [`SecureLink`]) or `tls/` (TLS over
    /// TCP).
    Tls(PathBuf),
    /// Plain links (`tcp/`, `udp/`), no authentication (`--insecure`): any peer on the network
    /// can join and speak for any UAV; only the check on arrival stands.
    Insecure,
}

impl Security {
    /// `mutual-tls` or `insecure`, as logs and `trace.json` say it.
    pub fn name(&self) -> &'static str {
        match self {
            Security::Tls(_) => "mutual-tls",
            Security::Insecure => "insecure",
        }
    }
}

/// The Zenoh link that carries a team's mutual TLS.
///
/// Both authenticate each peer by its certificate from the mission authority and give Zenoh's
/// access control the certificate's common name. `Quic` is the default: Zenoh 1.10.2's `tls`
/// link lets its reading and writing tasks take `&mut` of one rustls connection at once, a data
/// race that crashed about 2 % of agents (SIGILL) in fault runs; its QUIC link keeps sending
/// and receiving on separate streams of a connection that locks its own state.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum SecureLink {
    /// `quic/HOST:PORT` (UDP).
    #[default]
    Quic,
    /// `tls/HOST:PORT` (TCP).
    Tls,
}

impl SecureLink {
    /// How the TLS is carried, for people: `in QUIC` or `over TCP`.
    pub fn carrier(self) -> &'static str {
        match self {
            SecureLink::Quic => "in QUIC",
            SecureLink::Tls => "over TCP",
        }
    }

    /// The endpoint scheme: `quic` or `tls`.
    pub fn scheme(self) -> &'static str {
        match self {
            SecureLink::Quic => "quic",
            SecureLink::Tls => "tls",
        }
    }
}

/// The schemes of links that carry mutual TLS.
pub const SECURE_SCHEMES: [&str; 2] = ["quic", "tls"];

/// The scheme of an endpoint (`quic` of `quic/127.0.0.1:7447`).
fn scheme(e: &str) -> &str {
    e.split_once('/').map_or("", |(p, _)| p)
}

impl Network {
    /// With TLS, the secure schemes of this agent's endpoints, each once (`quic` before
    /// `tls`): the only links its session accepts and opens.
    pub fn secure_protocols(&self) -> Vec<String> {
        SECURE_SCHEMES
            .iter()
            .filter(|s| {
                self.listen
                    .iter()
                    .chain(&self.connect)
                    .any(|e| scheme(e) == **s)
            })
            .map(|s| s.to_string())
            .collect()
    }
}

/// The network flags of an agent (`mason agent`), before they are checked.
#[derive(Clone, Debug, Default)]
pub struct NetworkFlags {
    /// `--mission`.
    pub mission: Option<String>,
    /// `--prefix`.
    pub prefix: Option<String>,
    /// `--listen`.
    pub listen: Vec<String>,
    /// `--connect`.
    pub connect: Vec<String>,
    /// `--tls-dir`.
    pub tls_dir: Option<PathBuf>,
    /// `--insecure`.
    pub insecure: bool,
}

/// The network options of a TOML file (`mason agent --config`).
#[derive(Clone, Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NetworkFile {
    /// The mission id.
    pub mission: Option<String>,
    /// The key prefix.
    pub prefix: Option<String>,
    /// Endpoints to listen on.
    #[serde(default)]
    pub listen: Vec<String>,
    /// Endpoints to connect to.
    #[serde(default)]
    pub connect: Vec<String>,
    /// The member's folder of TLS files (relative to the TOML file's folder).
    pub tls_dir: Option<PathBuf>,
    /// Plain links, no authentication.
    #[serde(default)]
    pub insecure: bool,
}

impl Network {
    /// The network of a file's settings (if any) with the flags on top: `mission`, `prefix`
    /// and `tls_dir` override the file's, `listen` and `connect` add to its lists. Every value
    /// is checked; errors name the flag (and the file). One of `tls_dir` and `insecure` is
    /// needed, and the endpoints must match it (`quic/` and `tls/`, or `tcp/` and `udp/`).
    pub fn resolve(file: Option<&Path>, flags: &NetworkFlags) -> FleetResult<Network> {
        let from_file: NetworkFile = match file {
            Some(p) => mason_io::read_toml(p)?,
            None => NetworkFile::default(),
        };
        let shown = |flag: &str| match file {
            Some(p) => format!("{} ({}: {flag})", flag, p.display()),
            None => flag.to_string(),
        };
        let mission = flags.mission.clone().or(from_file.mission).ok_or_else(|| {
            FleetError::bad(
                "--mission: every agent needs the mission id (or `mission` in --config)",
            )
        })?;
        check_chunks(&shown("--mission"), &mission, true)?;
        let prefix = flags
            .prefix
            .clone()
            .or(from_file.prefix)
            .unwrap_or_else(|| DEFAULT_PREFIX.into());
        check_chunks(&shown("--prefix"), &prefix, false)?;
        let beside_file = |d: PathBuf| match file.and_then(Path::parent) {
            Some(parent) if d.is_relative() => parent.join(d),
            _ => d,
        };
        let tls_dir = flags.tls_dir.clone().or(from_file.tls_dir.map(beside_file));
        let security = match (tls_dir, flags.insecure || from_file.insecure) {
            (Some(d), false) => Security::Tls(d),
            (None, true) => Security::Insecure,
            (Some(_), true) => {
                return Err(FleetError::bad(format!(
                    "{} and {}: choose one (TLS with the mission's keys, or plain links)",
                    shown("--tls-dir"),
                    shown("--insecure")
                )))
            }
            (None, false) => {
                return Err(FleetError::bad(
                    "--tls-dir: an agent needs its folder of mission keys (ca.pem, cert.pem, key.pem; made by `mason keys` or `mason launch`), or --insecure for plain links on a trusted bench",
                ))
            }
        };
        let mut all_listen = from_file.listen;
        all_listen.extend(flags.listen.iter().cloned());
        let mut all_connect = from_file.connect;
        all_connect.extend(flags.connect.iter().cloned());
        for (flag, list, listen) in [
            ("--listen", &all_listen, true),
            ("--connect", &all_connect, false),
        ] {
            for e in list {
                let flag = shown(flag);
                check_endpoint(&flag, e, listen)?;
                let tls = SECURE_SCHEMES.contains(&scheme(e));
                if tls != matches!(security, Security::Tls(_)) {
                    let why = if tls {
                        "a quic/ or tls/ endpoint needs --tls-dir, not --insecure"
                    } else {
                        "plain links need --insecure; with --tls-dir use quic/HOST:PORT or tls/HOST:PORT"
                    };
                    return Err(FleetError::bad(format!("{flag} `{e}`: {why}")));
                }
            }
        }
        Ok(Network {
            mission,
            prefix,
            listen: all_listen,
            connect: all_connect,
            security,
        })
    }
}

/// Checks a Zenoh endpoint `proto/host:port` (tcp, udp, quic or tls; port 0 only to listen).
pub fn check_endpoint(flag: &str, e: &str, listen: bool) -> FleetResult<()> {
    if e.chars().count() > MAX_ENDPOINT {
        let head: String = e.chars().take(80).collect();
        return Err(FleetError::bad(format!(
            "{flag} `{head}…`: longer than {MAX_ENDPOINT} characters"
        )));
    }
    let bad = |why: &str| FleetError::bad(format!("{flag} `{e}`: {why}"));
    let (proto, addr) = e
        .split_once('/')
        .ok_or_else(|| bad("expected PROTO/HOST:PORT, e.g. tcp/127.0.0.1:7447"))?;
    if !["tcp", "udp", "quic", "tls"].contains(&proto) {
        return Err(bad(&format!(
            "unknown protocol `{proto}` (Mason speaks quic and tls, and tcp and udp with --insecure)"
        )));
    }
    let addr = addr.split(['?', '#']).next().unwrap_or_default();
    let (host, port) = addr.rsplit_once(':').ok_or_else(|| bad("missing :PORT"))?;
    let host = host.trim_start_matches('[').trim_end_matches(']');
    if host.is_empty() || host.chars().any(|c| c.is_whitespace() || c == '/') {
        return Err(bad("missing or bad host"));
    }
    match port.parse::<u16>() {
        Ok(0) if !listen => Err(bad("port 0 can only be listened on")),
        Ok(_) => Ok(()),
        Err(_) => Err(bad(&format!("`{port}` is not a port (0..65535)"))),
    }
}

/// The longest endpoint, in characters.
pub const MAX_ENDPOINT: usize = 256;
/// The longest key chunk (mission id, each chunk of a prefix), in characters.
pub const MAX_KEY_CHUNK: usize = 64;
/// The most chunks in a key prefix.
pub const MAX_PREFIX_CHUNKS: usize = 8;

/// Checks one key chunk (`one`) or chunks joined by `/`: letters, digits and `- _ . ~ + =`,
/// at most [`MAX_KEY_CHUNK`] characters each and [`MAX_PREFIX_CHUNKS`] chunks, before any
/// transport sees them. The value is shown cut to 80 characters.
pub fn check_chunks(flag: &str, s: &str, one: bool) -> FleetResult<()> {
    let shown = || mason_wall::limits::shown(s);
    let chunks = s.split('/').count();
    if s.split('/').any(|c| c.chars().count() > MAX_KEY_CHUNK)
        || (!one && chunks > MAX_PREFIX_CHUNKS)
    {
        return Err(FleetError::bad(format!(
            "{flag} `{}`: at most {MAX_KEY_CHUNK} characters per key chunk and {MAX_PREFIX_CHUNKS} chunks",
            shown()
        )));
    }
    let chunk_ok = |c: &str| {
        !c.is_empty()
            && c.chars()
                .all(|ch| ch.is_ascii_alphanumeric() || "-_.~+=".contains(ch))
    };
    let ok = if one {
        chunk_ok(s)
    } else {
        s.split('/').all(chunk_ok)
    };
    if ok {
        return Ok(());
    }
    let what = if one {
        "one key chunk of letters, digits and - _ . ~ + ="
    } else {
        "key chunks of letters, digits and - _ . ~ + =, joined by /"
    };
    Err(FleetError::bad(format!(
        "{flag} `{}`: expected {what}",
        shown()
    )))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn endpoints_are_checked() {
        assert!(check_endpoint("--listen", "tcp/127.0.0.1:0", true).is_ok());
        assert!(check_endpoint("--connect", "tcp/[::1]:7447", false).is_ok());
        assert!(check_endpoint("--connect", "quic/1.2.3.4:5", false).is_ok());
        for bad in [
            "127.0.0.1:7447",
            "ws/1.2.3.4:5",
            "quic/1.2.3.4",
            "tcp/127.0.0.1",
            "tcp/:7447",
            "tcp/h:99999",
            "tcp/h:0",
        ] {
            let e = check_endpoint("--connect", bad, false)
                .unwrap_err()
                .to_string();
            assert!(e.contains(bad), "{e}");
        }
    }

    #[test]
    fn ids_and_prefixes_are_key_chunks() {
        assert!(check_chunks("--mission", "m-1", true).is_ok());
        assert!(check_chunks("--prefix", "a/b", false).is_ok());
        for bad in ["", "a/b", "*", "a b", "$x"] {
            assert!(check_chunks("--mission", bad, true).is_err(), "{bad}");
        }
        assert!(check_chunks("--prefix", "a//b", false).is_err());
        let long = "m".repeat(70_000);
        let e = check_chunks("--mission", &long, true)
            .unwrap_err()
            .to_string();
        assert!(e.contains("at most 64 characters") && e.len() < 300, "{e}");
        assert!(check_chunks("--prefix", "a/b/c/d/e/f/g/h/i", false).is_err());
        let flags = NetworkFlags {
            mission: Some("m".into()),
            connect: vec!["tcp/h:1".into()],
            insecure: true,
            ..NetworkFlags::default()
        };
        let n = Network::resolve(None, &flags).unwrap();
        assert_eq!(n.prefix, DEFAULT_PREFIX);
        assert_eq!(n.security, Security::Insecure);
        let e = Network::resolve(None, &NetworkFlags::default())
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("--mission"), "{e}");
    }

    #[test]
    fn tls_or_insecure_is_chosen_and_endpoints_follow_it() {
        let base = NetworkFlags {
            mission: Some("m".into()),
            ..NetworkFlags::default()
        };
        let e = Network::resolve(None, &base).unwrap_err().to_string();
        assert!(
            e.starts_with("--tls-dir") && e.contains("--insecure"),
            "{e}"
        );
        let tls = NetworkFlags {
            tls_dir: Some("keys/uav-0".into()),
            connect: vec!["tls/127.0.0.1:7447".into()],
            ..base.clone()
        };
        let n = Network::resolve(None, &tls).unwrap();
        assert_eq!(n.security, Security::Tls("keys/uav-0".into()));
        assert_eq!(n.secure_protocols(), ["tls"]);
        // QUIC carries the same mutual TLS; an agent accepts and opens the schemes it names.
        let quic = NetworkFlags {
            listen: vec!["quic/127.0.0.1:7448".into()],
            ..tls.clone()
        };
        let n = Network::resolve(None, &quic).unwrap();
        assert_eq!(n.secure_protocols(), ["quic", "tls"]);
        let quic_insecure = NetworkFlags {
            tls_dir: None,
            insecure: true,
            connect: vec![],
            ..quic
        };
        let e = Network::resolve(None, &quic_insecure)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("quic/127.0.0.1:7448") && e.contains("needs --tls-dir"),
            "{e}"
        );
        let both = NetworkFlags {
            insecure: true,
            ..tls.clone()
        };
        let e = Network::resolve(None, &both).unwrap_err().to_string();
        assert!(e.contains("choose one"), "{e}");
        let plain = NetworkFlags {
            connect: vec!["tcp/127.0.0.1:7447".into()],
            ..tls.clone()
        };
        let e = Network::resolve(None, &plain).unwrap_err().to_string();
        assert!(e.contains("need --insecure"), "{e}");
        let tls_insecure = NetworkFlags {
            tls_dir: None,
            insecure: true,
            ..tls
        };
        let e = Network::resolve(None, &tls_insecure)
            .unwrap_err()
            .to_string();
        assert!(e.contains("needs --tls-dir"), "{e}");
    }
}
