//! Output files: checked before any work, written all or none, atomically (a temporary name in
//! the same folder, then a rename), and never renamed over something that is not a regular
//! file. A character device (`/dev/null`, `/dev/stdout`) is written in place; a FIFO, socket,
//! folder or block device is refused.

use crate::error::{InputError, InputResult};
use std::path::{Path, PathBuf};

/// The folder `path` goes into (`.` for a bare file name).
fn folder_of(path: &Path) -> &Path {
    path.parent()
        .filter(|d| !d.as_os_str().is_empty())
        .unwrap_or(Path::new("."))
}

/// What stands at an output path today.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Target {
    /// Nothing, or a regular file: written atomically.
    File,
    /// A character device: written in place.
    Device,
}

fn target(path: &Path) -> InputResult<Target> {
    let shown = path.display();
    let meta = match std::fs::metadata(path) {
        Ok(m) => m,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(Target::File),
        Err(e) => {
            return Err(InputError::bad(format!("{shown}: cannot be written ({e})")));
        }
    };
    if meta.is_file() {
        return Ok(Target::File);
    }
    if meta.is_dir() {
        return Err(InputError::bad(format!(
            "{shown}: is a folder; give a file name"
        )));
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        let t = meta.file_type();
        if t.is_char_device() {
            return Ok(Target::Device);
        }
        let kind = if t.is_fifo() {
            "a FIFO"
        } else if t.is_socket() {
            "a socket"
        } else {
            "a block device"
        };
        Err(InputError::bad(format!(
            "{shown}: is {kind}, not a regular file; give a file name (it is never replaced)"
        )))
    }
    #[cfg(not(unix))]
    Err(InputError::bad(format!(
        "{shown}: not a regular file; give a file name"
    )))
}

/// Checks, before any work, that an output can go to `path`: its folder exists (no folder is
/// created), `path` is a regular file, nothing yet, or a character device, and a file can be
/// made in the folder (a read-only folder, or one like `/proc`, is named, not met halfway).
pub fn check_output(path: &Path) -> InputResult<()> {
    let dir = folder_of(path);
    if !dir.is_dir() {
        return Err(InputError::bad(format!(
            "{}: the folder {} does not exist (create it first)",
            path.display(),
            dir.display()
        )));
    }
    if target(path)? == Target::File {
        let probe = temporary(path);
        match std::fs::OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&probe)
        {
            Ok(_) => {
                let _ = std::fs::remove_file(&probe);
            }
            // Another process of ours has the name: the folder is writable.
            Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists => {}
            Err(e) => {
                return Err(InputError::bad(format!(
                    "{}: cannot be written there: its folder {} takes no new file ({e})",
                    path.display(),
                    folder_of(path).display()
                )))
            }
        }
    }
    Ok(())
}

/// Checks, before any work, that an output folder (a ROS 2 bag: its files are written into it
/// with [`write_files`]) can go to `path`: its parent folder exists, and `path` is nothing yet
/// (it is made by [`make_output_folder`]) or a folder. A file, FIFO, socket or device there is
/// refused, never replaced.
pub fn check_output_folder(path: &Path) -> InputResult<()> {
    let parent = folder_of(path);
    if !parent.is_dir() {
        return Err(InputError::bad(format!(
            "{}: the folder {} does not exist (create it first)",
            path.display(),
            parent.display()
        )));
    }
    match std::fs::metadata(path) {
        Ok(m) if m.is_dir() => Ok(()),
        Ok(_) => Err(InputError::bad(format!(
            "{}: is not a folder; give a folder name (it is never replaced)",
            path.display()
        ))),
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => Ok(()),
        Err(e) => Err(InputError::bad(format!(
            "{}: cannot be written ({e})",
            path.display()
        ))),
    }
}

/// Makes the output folder `path` (checked by [`check_output_folder`]) if it is missing.
pub fn make_output_folder(path: &Path) -> InputResult<()> {
    check_output_folder(path)?;
    match std::fs::create_dir(path) {
        Ok(()) => Ok(()),
        Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists && path.is_dir() => Ok(()),
        Err(e) => Err(InputError::bad(format!(
            "{}: cannot make the folder ({e})",
            path.display()
        ))),
    }
}

/// The temporary name `path` is written under before it is renamed into place.
fn temporary(path: &Path) -> PathBuf {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    folder_of(path).join(format!(".{name}.mason-{}.tmp", std::process::id()))
}

/// Writes all of a command's output files, or none of the regular ones: every path is checked
/// first, each regular file is written to a temporary name in its own folder, and only when
/// all are written are they renamed into place (on failure the temporary files are removed).
/// Character devices are written in place, last.
pub fn write_files(files: &[(&Path, &[u8])]) -> InputResult<()> {
    let mut kinds = Vec::with_capacity(files.len());
    for (path, _) in files {
        check_output(path)?;
        kinds.push(target(path)?);
    }
    let fail = |path: &Path, e: std::io::Error| InputError::bad(format!("{}: {e}", path.display()));
    let mut written: Vec<(PathBuf, &Path)> = Vec::new();
    let clean = |written: &[(PathBuf, &Path)]| {
        for (t, _) in written {
            let _ = std::fs::remove_file(t);
        }
    };
    for ((path, contents), kind) in files.iter().zip(&kinds) {
        if *kind == Target::Device {
            continue;
        }
        let tmp = temporary(path);
        if let Err(e) = std::fs::write(&tmp, contents) {
            let _ = std::fs::remove_file(&tmp);
            clean(&written);
            return Err(fail(path, e));
        }
        written.push((tmp, path));
    }
    for (i, (tmp, path)) in written.iter().enumerate() {
        if let Err(e) = std::fs::rename(tmp, path) {
            clean(&written[i..]);
            return Err(fail(path, e));
        }
    }
    for ((path, contents), kind) in files.iter().zip(&kinds) {
        if *kind == Target::Device {
            let mut f = std::fs::OpenOptions::new()
                .write(true)
                .open(path)
                .map_err(|e| fail(path, e))?;
            std::io::Write::write_all(&mut f, contents).map_err(|e| fail(path, e))?;
        }
    }
    Ok(())
}

/// Writes one output file (see [`write_files`]).
pub fn write_file(path: &Path, contents: &[u8]) -> InputResult<()> {
    write_files(&[(path, contents)])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_bag_folder_is_made_once_and_never_replaces_a_file() {
        let dir = std::env::temp_dir().join(format!("mason-io-bag-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let bag = dir.join("bag");
        check_output_folder(&bag).unwrap();
        make_output_folder(&bag).unwrap();
        make_output_folder(&bag).unwrap();
        assert!(bag.is_dir());
        let file = dir.join("file");
        std::fs::write(&file, "keep").unwrap();
        let e = make_output_folder(&file).unwrap_err();
        assert!(e.to_string().contains("is not a folder"), "{e}");
        assert_eq!(std::fs::read_to_string(&file).unwrap(), "keep");
        let e = check_output_folder(&dir.join("missing/bag")).unwrap_err();
        assert!(e.to_string().contains("does not exist"), "{e}");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn outputs_are_written_all_or_none() {
        let dir = std::env::temp_dir().join(format!("mason-io-out-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let a = dir.join("a.txt");
        let missing = dir.join("nope/b.txt");
        let e = write_files(&[(&a, b"1"), (&missing, b"2")]).unwrap_err();
        assert!(e.to_string().contains("does not exist"), "{e}");
        assert!(!a.exists());
        write_files(&[(&a, b"1")]).unwrap();
        assert_eq!(std::fs::read(&a).unwrap(), b"1");
        let e = write_file(&dir, b"x").unwrap_err();
        assert!(e.to_string().contains("is a folder"), "{e}");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[cfg(target_os = "linux")]
    #[test]
    fn a_file_that_cannot_be_written_is_named_as_such() {
        let e = check_output(Path::new("/proc/version"))
            .unwrap_err()
            .to_string();
        assert!(
            e.starts_with("/proc/version: cannot be written there: its folder /proc takes no"),
            "{e}"
        );
    }

    #[cfg(unix)]
    #[test]
    fn a_fifo_is_refused_not_replaced() {
        let dir = std::env::temp_dir().join(format!("mason-io-fifo-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let fifo = dir.join("pipe");
        let made = std::process::Command::new("mkfifo").arg(&fifo).status();
        if made.is_ok_and(|s| s.success()) {
            let e = write_file(&fifo, b"x").unwrap_err().to_string();
            assert!(
                e.contains("is a FIFO") && e.contains("never replaced"),
                "{e}"
            );
            use std::os::unix::fs::FileTypeExt;
            assert!(std::fs::metadata(&fifo).unwrap().file_type().is_fifo());
        }
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[cfg(unix)]
    #[test]
    fn a_device_is_written_in_place_never_replaced() {
        use std::os::unix::fs::FileTypeExt;
        let null = Path::new("/dev/null");
        write_file(null, b"hello").unwrap();
        let t = std::fs::metadata(null).unwrap().file_type();
        assert!(t.is_char_device());
    }
}
