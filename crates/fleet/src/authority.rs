//! The mission authority (DESIGN §8, issue #27): a certificate authority made for one mission,
//! which signs one certificate per UAV and one per ground station, and the check of a member's
//! files before its Zenoh session opens (feature `zenoh`).
//!
//! The files of a mission folder (`mason keys`, or `mason launch` in its `--out`):
//!
//! ```text
//! MISSION_DIR/authority/ca.pem   the authority's certificate
//! MISSION_DIR/authority/ca.key   its private key (0600): keep it off the vehicles
//! MISSION_DIR/uav-<i>/           ca.pem, cert.pem, key.pem (0600) of UAV i
//! MISSION_DIR/station-<s>/       ca.pem, cert.pem, key.pem (0600) of ground station s
//! ```
//!
//! A member's certificate names it in its common name (`uav-0`, `station-0`), the mission in
//! its organisation, and again as a DNS name `MEMBER.mason` in its subject alternative names.
//! Zenoh's access control matches the common name ([`crate::zenoh_link`]): what a session may
//! publish follows from the certificate it showed, not from what its messages say.
//!
//! Keys are ECDSA P-256, made by `rcgen` from the system's randomness: two runs give other
//! keys (nothing else in Mason depends on them). Certificates are valid from a day before
//! they are made for [`VALID_DAYS`] days.

use crate::error::{FleetError, FleetResult};
use crate::network::check_chunks;
use rcgen::{
    BasicConstraints, CertificateParams, DnType, ExtendedKeyUsagePurpose, IsCa, Issuer, KeyPair,
    KeyUsagePurpose, PublicKeyData,
};
use std::path::{Path, PathBuf};

/// How long the certificates of a mission are valid (days).
pub const VALID_DAYS: i64 = 365;
/// The most ground stations of a mission (as the check on arrival, [`MAX_STATIONS`]).
pub const MAX_STATIONS: usize = mason_mission::agent::MAX_STATIONS;
/// The most UAVs a `mason keys` run makes certificates for.
pub const MAX_UAVS: usize = 256;
/// The longest certificate or key file read (bytes).
pub const MAX_PEM_BYTES: u64 = 64 * 1024;

/// The folder of the authority's own files in a mission folder.
pub const AUTHORITY_DIR: &str = "authority";
/// The authority's certificate (in every member's folder too).
pub const CA_FILE: &str = "ca.pem";
/// The authority's private key (in [`AUTHORITY_DIR`] only).
pub const CA_KEY_FILE: &str = "ca.key";
/// A member's certificate.
pub const CERT_FILE: &str = "cert.pem";
/// A member's private key.
pub const KEY_FILE: &str = "key.pem";

/// Who a certificate is for.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Member {
    /// UAV `i` (0-based).
    Uav(usize),
    /// Ground station `s` (0-based).
    Station(usize),
}

impl Member {
    /// Its common name and folder name: `uav-<i>` or `station-<s>`.
    pub fn name(self) -> String {
        match self {
            Member::Uav(i) => format!("uav-{i}"),
            Member::Station(s) => format!("station-{s}"),
        }
    }

    /// The member a common name names, if any.
    pub fn parse(name: &str) -> Option<Member> {
        let index = |s: &str| -> Option<usize> {
            (!s.is_empty()
                && s.bytes().all(|b| b.is_ascii_digit())
                && (s == "0" || !s.starts_with('0')))
            .then(|| s.parse().ok())
            .flatten()
        };
        if let Some(i) = name.strip_prefix("uav-").and_then(index) {
            return Some(Member::Uav(i));
        }
        name.strip_prefix("station-")
            .and_then(index)
            .map(Member::Station)
    }
}

/// The three files a member's session needs, from its folder (`--tls-dir`).
#[derive(Clone, Debug, PartialEq)]
pub struct TlsFiles {
    /// The folder.
    pub dir: PathBuf,
    /// The mission authority's certificate.
    pub ca: PathBuf,
    /// The member's certificate.
    pub cert: PathBuf,
    /// The member's private key.
    pub key: PathBuf,
}

impl TlsFiles {
    /// The files of folder `dir`: `ca.pem`, `cert.pem`, `key.pem`.
    pub fn in_dir(dir: &Path) -> TlsFiles {
        TlsFiles {
            dir: dir.to_path_buf(),
            ca: dir.join(CA_FILE),
            cert: dir.join(CERT_FILE),
            key: dir.join(KEY_FILE),
        }
    }
}

/// What a mission folder holds after [`make_keys`].
#[derive(Clone, Debug)]
pub struct Keys {
    /// The mission folder.
    pub dir: PathBuf,
    /// The mission id in every certificate.
    pub mission: String,
    /// UAVs with a folder.
    pub uavs: usize,
    /// Ground stations with a folder.
    pub stations: usize,
}

impl Keys {
    /// The files of a member.
    pub fn member(&self, m: Member) -> TlsFiles {
        TlsFiles::in_dir(&self.dir.join(m.name()))
    }
}

fn io(path: &Path) -> impl FnOnce(std::io::Error) -> FleetError + '_ {
    move |source| FleetError::Io {
        path: path.to_path_buf(),
        source,
    }
}

fn rc(what: &str) -> impl FnOnce(rcgen::Error) -> FleetError + '_ {
    move |e| FleetError::Network(format!("cannot make the {what}: {e}"))
}

/// Writes `text` to `path`, readable by its owner only when `secret`.
fn write(path: &Path, text: &str, secret: bool) -> FleetResult<()> {
    use std::io::Write;
    let mut o = std::fs::OpenOptions::new();
    o.write(true).create(true).truncate(true);
    #[cfg(unix)]
    if secret {
        use std::os::unix::fs::OpenOptionsExt;
        o.mode(0o600);
    }
    #[cfg(not(unix))]
    let _ = secret;
    let mut f = o.open(path).map_err(io(path))?;
    // A file that was there before keeps its mode: tighten it.
    #[cfg(unix)]
    if secret {
        use std::os::unix::fs::PermissionsExt;
        f.set_permissions(std::fs::Permissions::from_mode(0o600))
            .map_err(io(path))?;
    }
    f.write_all(text.as_bytes()).map_err(io(path))
}

fn validity(p: &mut CertificateParams) {
    let now = time::OffsetDateTime::now_utc();
    p.not_before = now - time::Duration::days(1);
    p.not_after = now + time::Duration::days(VALID_DAYS);
}

/// Makes a mission authority in `dir` and one certificate and key per UAV (`uavs`) and per
/// ground station (`stations`), overwriting the files of an earlier run there. Errors name the
/// file or the bad value.
pub fn make_keys(dir: &Path, mission: &str, uavs: usize, stations: usize) -> FleetResult<Keys> {
    check_chunks("--mission", mission, true)?;
    if uavs == 0 || uavs > MAX_UAVS {
        return Err(FleetError::bad(format!(
            "--uavs {uavs}: expected 1..{MAX_UAVS}"
        )));
    }
    if stations > MAX_STATIONS {
        return Err(FleetError::bad(format!(
            "--stations {stations}: expected 0..{MAX_STATIONS}"
        )));
    }
    let auth_dir = dir.join(AUTHORITY_DIR);
    std::fs::create_dir_all(&auth_dir).map_err(io(&auth_dir))?;
    let mut params = CertificateParams::new(Vec::new()).map_err(rc("authority"))?;
    params.is_ca = IsCa::Ca(BasicConstraints::Constrained(0));
    params.distinguished_name.push(
        DnType::CommonName,
        format!("mason mission authority {mission}"),
    );
    params
        .distinguished_name
        .push(DnType::OrganizationName, mission);
    params.key_usages = vec![KeyUsagePurpose::KeyCertSign, KeyUsagePurpose::CrlSign];
    validity(&mut params);
    let ca_key = KeyPair::generate().map_err(rc("authority's key"))?;
    let ca_cert = params.self_signed(&ca_key).map_err(rc("authority"))?;
    let ca_pem = ca_cert.pem();
    write(&auth_dir.join(CA_FILE), &ca_pem, false)?;
    write(&auth_dir.join(CA_KEY_FILE), &ca_key.serialize_pem(), true)?;
    let issuer = Issuer::new(params, ca_key);
    let members = (0..uavs)
        .map(Member::Uav)
        .chain((0..stations).map(Member::Station));
    for m in members {
        let name = m.name();
        let mdir = dir.join(&name);
        std::fs::create_dir_all(&mdir).map_err(io(&mdir))?;
        let mut p = CertificateParams::new(vec![format!("{name}.mason")]).map_err(rc(&name))?;
        p.distinguished_name.push(DnType::CommonName, name.as_str());
        p.distinguished_name.push(DnType::OrganizationName, mission);
        p.use_authority_key_identifier_extension = true;
        p.key_usages = vec![KeyUsagePurpose::DigitalSignature];
        // A member both listens and connects.
        p.extended_key_usages = vec![
            ExtendedKeyUsagePurpose::ServerAuth,
            ExtendedKeyUsagePurpose::ClientAuth,
        ];
        validity(&mut p);
        let key = KeyPair::generate().map_err(rc(&name))?;
        let cert = p.signed_by(&key, &issuer).map_err(rc(&name))?;
        let files = TlsFiles::in_dir(&mdir);
        write(&files.ca, &ca_pem, false)?;
        write(&files.cert, &cert.pem(), false)?;
        write(&files.key, &key.serialize_pem(), true)?;
    }
    Ok(Keys {
        dir: dir.to_path_buf(),
        mission: mission.to_string(),
        uavs,
        stations,
    })
}

/// Reads a PEM file of at most [`MAX_PEM_BYTES`]; errors name the flag and the file.
fn read_pem(flag: &str, path: &Path) -> FleetResult<String> {
    let bad = |why: String| FleetError::bad(format!("{flag}: {}: {why}", path.display()));
    let meta = std::fs::metadata(path).map_err(|e| bad(format!("cannot read it ({e})")))?;
    if !meta.is_file() {
        return Err(bad("not a file".into()));
    }
    if meta.len() > MAX_PEM_BYTES {
        return Err(bad(format!(
            "{} bytes, over the {MAX_PEM_BYTES} of a PEM file",
            meta.len()
        )));
    }
    std::fs::read_to_string(path).map_err(|e| bad(format!("cannot read it ({e})")))
}

/// Checks a member's files before its session opens (errors name the flag and the file):
/// the three files are there and readable, `cert.pem` is signed by `ca.pem` and is in force,
/// it names `member` and `mission`, and `key.pem` is its key.
pub fn check_member(
    flag: &str,
    files: &TlsFiles,
    mission: &str,
    member: Member,
) -> FleetResult<()> {
    if !files.dir.is_dir() {
        return Err(FleetError::bad(format!(
            "{flag} {}: not a folder (make one with `mason keys`)",
            files.dir.display()
        )));
    }
    let ca_pem = read_pem(flag, &files.ca)?;
    let cert_pem = read_pem(flag, &files.cert)?;
    let key_pem = read_pem(flag, &files.key)?;
    let bad = |p: &Path, why: String| FleetError::bad(format!("{flag}: {}: {why}", p.display()));
    let (_, ca) = x509_parser::pem::parse_x509_pem(ca_pem.as_bytes())
        .map_err(|_| bad(&files.ca, "not a PEM certificate".into()))?;
    let ca = ca
        .parse_x509()
        .map_err(|e| bad(&files.ca, format!("not an X.509 certificate ({e})")))?;
    let (_, cert) = x509_parser::pem::parse_x509_pem(cert_pem.as_bytes())
        .map_err(|_| bad(&files.cert, "not a PEM certificate".into()))?;
    let cert = cert
        .parse_x509()
        .map_err(|e| bad(&files.cert, format!("not an X.509 certificate ({e})")))?;
    if !ca.is_ca() {
        return Err(bad(&files.ca, "not a certificate authority".into()));
    }
    cert.verify_signature(Some(ca.public_key())).map_err(|_| {
        bad(
            &files.cert,
            format!(
                "not signed by the mission authority of {}",
                files.ca.display()
            ),
        )
    })?;
    if !cert.validity().is_valid() {
        return Err(bad(&files.cert, "expired or not yet valid".into()));
    }
    let cn = first_str(cert.subject().iter_common_name());
    if cn != member.name() {
        return Err(bad(
            &files.cert,
            format!("made for `{cn}`, not `{}`", member.name()),
        ));
    }
    let org = first_str(cert.subject().iter_organization());
    if org != mission {
        return Err(bad(
            &files.cert,
            format!("made for mission `{org}`, not `{mission}` (--mission)"),
        ));
    }
    let key =
        KeyPair::from_pem(&key_pem).map_err(|_| bad(&files.key, "not a PEM private key".into()))?;
    if key.der_bytes() != cert.public_key().subject_public_key.data.as_ref() {
        return Err(bad(
            &files.key,
            format!("not the key of {}", files.cert.display()),
        ));
    }
    Ok(())
}

/// The first attribute's text ("" if none, or not text).
fn first_str<'a>(
    mut it: impl Iterator<Item = &'a x509_parser::x509::AttributeTypeAndValue<'a>>,
) -> String {
    it.next()
        .and_then(|a| a.as_str().ok())
        .unwrap_or("")
        .to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("mason-keys-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        d
    }

    #[test]
    fn member_names_round_trip() {
        for m in [Member::Uav(0), Member::Uav(12), Member::Station(3)] {
            assert_eq!(Member::parse(&m.name()), Some(m));
        }
        for bad in [
            "uav-",
            "uav-01",
            "uav--1",
            "station-x",
            "uav-1 ",
            "ground-1",
        ] {
            assert_eq!(Member::parse(bad), None, "{bad}");
        }
    }

    #[test]
    fn a_mission_folder_holds_one_checked_set_per_member() {
        let dir = scratch("ok");
        let keys = make_keys(&dir, "m-1", 2, 1).unwrap();
        for m in [Member::Uav(0), Member::Uav(1), Member::Station(0)] {
            check_member("--tls-dir", &keys.member(m), "m-1", m).unwrap();
        }
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            let mode = |p: PathBuf| std::fs::metadata(p).unwrap().permissions().mode() & 0o777;
            assert_eq!(mode(dir.join("authority/ca.key")), 0o600);
            assert_eq!(mode(dir.join("uav-1/key.pem")), 0o600);
        }
        // Another member's set, another mission, a missing file: refused, naming the file.
        let e = check_member(
            "--tls-dir",
            &keys.member(Member::Uav(1)),
            "m-1",
            Member::Uav(0),
        )
        .unwrap_err()
        .to_string();
        assert!(
            e.contains("uav-1/cert.pem") && e.contains("not `uav-0`"),
            "{e}"
        );
        let e = check_member(
            "--tls-dir",
            &keys.member(Member::Uav(0)),
            "m-2",
            Member::Uav(0),
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("mission `m-1`, not `m-2`"), "{e}");
        let e = check_member(
            "--tls-dir",
            &keys.member(Member::Uav(5)),
            "m-1",
            Member::Uav(5),
        )
        .unwrap_err()
        .to_string();
        assert!(e.contains("not a folder"), "{e}");
        // A key of another member, a certificate of another authority.
        let other = make_keys(&scratch("other"), "m-1", 1, 0).unwrap();
        let mixed = dir.join("mixed");
        std::fs::create_dir_all(&mixed).unwrap();
        let u0 = keys.member(Member::Uav(0));
        std::fs::copy(&u0.ca, mixed.join(CA_FILE)).unwrap();
        std::fs::copy(&u0.cert, mixed.join(CERT_FILE)).unwrap();
        std::fs::copy(keys.member(Member::Uav(1)).key, mixed.join(KEY_FILE)).unwrap();
        let files = TlsFiles::in_dir(&mixed);
        let e = check_member("--tls-dir", &files, "m-1", Member::Uav(0))
            .unwrap_err()
            .to_string();
        assert!(e.contains("key.pem: not the key of"), "{e}");
        std::fs::copy(other.member(Member::Uav(0)).cert, mixed.join(CERT_FILE)).unwrap();
        let e = check_member("--tls-dir", &files, "m-1", Member::Uav(0))
            .unwrap_err()
            .to_string();
        assert!(e.contains("not signed by the mission authority"), "{e}");
        std::fs::write(mixed.join(CERT_FILE), "garbage").unwrap();
        let e = check_member("--tls-dir", &files, "m-1", Member::Uav(0))
            .unwrap_err()
            .to_string();
        assert!(e.contains("cert.pem: not a PEM certificate"), "{e}");
        std::fs::write(mixed.join(CERT_FILE), vec![b'x'; 70_000]).unwrap();
        let e = check_member("--tls-dir", &files, "m-1", Member::Uav(0))
            .unwrap_err()
            .to_string();
        assert!(e.contains("over the 65536"), "{e}");
        std::fs::remove_dir_all(&dir).unwrap();
        std::fs::remove_dir_all(&other.dir).unwrap();
    }

    #[test]
    fn bad_counts_and_missions_are_refused() {
        let dir = scratch("bad");
        assert!(make_keys(&dir, "a/b", 1, 0).is_err());
        assert!(make_keys(&dir, "m", 0, 0)
            .unwrap_err()
            .to_string()
            .contains("--uavs 0"));
        assert!(make_keys(&dir, "m", 1, 17)
            .unwrap_err()
            .to_string()
            .contains("--stations 17"));
        let _ = std::fs::remove_dir_all(&dir);
    }
}
