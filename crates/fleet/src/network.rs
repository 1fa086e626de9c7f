//! Where and how an agent talks: the mission id, the key prefix and the Zenoh endpoints, from
//! flags and a network TOML file, every one checked before a transport sees it.

use crate::error::{FleetError, FleetResult};
use serde::Deserialize;
use std::path::Path;

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
}

impl Network {
    /// The network of a file's settings (if any) with the flags on top: `mission` and `prefix`
    /// override the file's, `listen` and `connect` add to its lists. Every value is checked;
    /// errors name the flag (and the file).
    pub fn resolve(
        file: Option<&Path>,
        mission: Option<String>,
        prefix: Option<String>,
        listen: &[String],
        connect: &[String],
    ) -> FleetResult<Network> {
        let from_file: NetworkFile = match file {
            Some(p) => mason_io::read_toml(p)?,
            None => NetworkFile::default(),
        };
        let shown = |flag: &str| match file {
            Some(p) => format!("{} ({}: {flag})", flag, p.display()),
            None => flag.to_string(),
        };
        let mission = mission.or(from_file.mission).ok_or_else(|| {
            FleetError::bad(
                "--mission: every agent needs the mission id (or `mission` in --config)",
            )
        })?;
        check_chunks(&shown("--mission"), &mission, true)?;
        let prefix = prefix
            .or(from_file.prefix)
            .unwrap_or_else(|| DEFAULT_PREFIX.into());
        check_chunks(&shown("--prefix"), &prefix, false)?;
        let mut all_listen = from_file.listen;
        all_listen.extend(listen.iter().cloned());
        let mut all_connect = from_file.connect;
        all_connect.extend(connect.iter().cloned());
        for e in &all_listen {
            check_endpoint(&shown("--listen"), e, true)?;
        }
        for e in &all_connect {
            check_endpoint(&shown("--connect"), e, false)?;
        }
        Ok(Network {
            mission,
            prefix,
            listen: all_listen,
            connect: all_connect,
        })
    }
}

/// Checks a Zenoh endpoint `proto/host:port` (tcp or udp; port 0 only to listen).
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
    if proto != "tcp" && proto != "udp" {
        return Err(bad(&format!(
            "unknown protocol `{proto}` (this build speaks tcp and udp)"
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
        for bad in [
            "127.0.0.1:7447",
            "quic/1.2.3.4:5",
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
        let n = Network::resolve(None, Some("m".into()), None, &[], &["tcp/h:1".into()]).unwrap();
        assert_eq!(n.prefix, DEFAULT_PREFIX);
        let e = Network::resolve(None, None, None, &[], &[])
            .unwrap_err()
            .to_string();
        assert!(e.starts_with("--mission"), "{e}");
    }
}
