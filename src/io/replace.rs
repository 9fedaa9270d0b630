//! Writing files so that a failed write loses nothing.
//!
//! Every file this library writes (meshes, `.pvd` series, models) goes through
//! [`write_files`]: the bytes go first to a temporary file beside each destination (same
//! directory, hence same file system), and only when all of them are wholly written are
//! they renamed over their destinations — a rename replaces a file atomically on POSIX. A
//! write that fails part way (a full disk, a quota, a file-size limit, a killed process)
//! leaves the files that were there untouched, which matters when a user writes a cut model
//! over the model it was read from, and a reader never sees half a file. A TetGen pair is
//! replaced together, so a failure cannot leave a new `.node` beside an old `.ele`.
//!
//! The data are not synced to disk before the rename: this guards against failed writes,
//! not against power loss (ext4 and XFS order a replacing rename after its data anyway).

use std::ffi::OsString;
use std::fs::{File, OpenOptions, Permissions};
use std::io::{self, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU32, Ordering};

/// Distinguishes the temporary files of concurrent writes within one process.
static NEXT: AtomicU32 = AtomicU32::new(0);

/// Where a destination's bytes go before they replace it.
enum Plan {
    /// Written to `file`, then moved over the destination.
    Replace { file: File, staged: Staged },
    /// Written in place: the destination is not a regular file (`/dev/null`, a FIFO, a
    /// directory, which then fails as a plain write does), or no file can be created in
    /// its directory although the destination itself may be writable.
    InPlace(PathBuf),
}

/// A temporary file at `tmp`, to be renamed to `target` with the permissions of the file
/// it replaces (if any).
struct Staged {
    /// The destination's index in the caller's list.
    index: usize,
    tmp: PathBuf,
    target: PathBuf,
    permissions: Option<Permissions>,
}

/// Writes each `(path, bytes)`, replacing what was there only once every file is written
/// (see the [module docs](self)). A symbolic link is followed: the file it points to is
/// replaced and the link kept. On error, returns the index of the file that failed and
/// why; the temporary files are removed and no destination has changed, unless one of
/// them could only be written in place or a rename fails after others succeeded (both
/// rare: it takes a directory that takes no new file, or one changed during the write).
pub(crate) fn write_files(files: &[(&Path, &[u8])]) -> Result<(), (usize, io::Error)> {
    let mut staged: Vec<Staged> = Vec::with_capacity(files.len());
    for (i, &(path, bytes)) in files.iter().enumerate() {
        let written = match plan(path, i) {
            Plan::Replace {
                mut file,
                staged: s,
            } => {
                // Listed before the result is known, so that a failed write's temporary
                // file is removed too.
                staged.push(s);
                file.write_all(bytes)
            }
            Plan::InPlace(p) => std::fs::write(p, bytes),
        };
        if let Err(e) = written {
            remove_temporaries(&staged);
            return Err((i, e));
        }
    }
    for (k, s) in staged.iter().enumerate() {
        let moved = match &s.permissions {
            Some(p) => std::fs::set_permissions(&s.tmp, p.clone()),
            None => Ok(()),
        }
        .and_then(|()| std::fs::rename(&s.tmp, &s.target));
        if let Err(e) = moved {
            remove_temporaries(&staged[k..]);
            return Err((s.index, e));
        }
    }
    Ok(())
}

fn remove_temporaries(staged: &[Staged]) {
    for s in staged {
        // Best effort: the write's own error is the one worth reporting.
        let _ = std::fs::remove_file(&s.tmp);
    }
}

/// How `path` will be written: to a new temporary file beside it, or in place (where
/// the plain write reports whatever is wrong with the destination).
fn plan(path: &Path, index: usize) -> Plan {
    let target = match std::fs::symlink_metadata(path) {
        Ok(m) if m.file_type().is_symlink() => match std::fs::canonicalize(path) {
            Ok(t) => t,
            // A dangling link: writing through it creates the file it names.
            Err(_) => return Plan::InPlace(path.to_path_buf()),
        },
        _ => path.to_path_buf(),
    };
    let permissions = match std::fs::metadata(&target) {
        Ok(m) if !m.is_file() => return Plan::InPlace(target),
        Ok(m) => Some(m.permissions()),
        Err(_) => None,
    };
    let Some(name) = target.file_name() else {
        return Plan::InPlace(target);
    };
    let dir = match target.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let mut tmp_name = OsString::from(".");
    tmp_name.push(name);
    tmp_name.push(format!(
        ".{}-{}.mtcut-tmp",
        std::process::id(),
        NEXT.fetch_add(1, Ordering::Relaxed)
    ));
    let tmp = dir.join(tmp_name);
    // A directory that takes no new file (not writable, a name too long with the
    // suffix, a missing directory) is left to the plain write, which reports the
    // destination's own error or succeeds on a writable file.
    match OpenOptions::new().write(true).create_new(true).open(&tmp) {
        Ok(file) => Plan::Replace {
            file,
            staged: Staged {
                index,
                tmp,
                target,
                permissions,
            },
        },
        Err(_) => Plan::InPlace(target),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dir(name: &str) -> PathBuf {
        let d = std::env::temp_dir().join(format!("mtcut-replace-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    fn leftovers(d: &Path) -> Vec<String> {
        std::fs::read_dir(d)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .filter(|n| n.contains("mtcut-tmp"))
            .collect()
    }

    #[test]
    fn files_are_replaced_and_nothing_is_left_beside_them() {
        let d = dir("replace");
        let (a, b) = (d.join("a.node"), d.join("a.ele"));
        write_files(&[(&a, b"one"), (&b, b"two")]).unwrap();
        write_files(&[(&a, b"three"), (&b, b"four")]).unwrap();
        assert_eq!(std::fs::read(&a).unwrap(), b"three");
        assert_eq!(std::fs::read(&b).unwrap(), b"four");
        assert!(leftovers(&d).is_empty(), "{:?}", leftovers(&d));
        std::fs::remove_dir_all(&d).unwrap();
    }

    #[test]
    fn a_failure_on_the_second_file_keeps_the_first() {
        let d = dir("second");
        let a = d.join("a.node");
        std::fs::write(&a, b"old").unwrap();
        // The second destination's directory does not exist.
        let b = d.join("missing").join("a.ele");
        let (i, e) = write_files(&[(&a, b"new"), (&b, b"new")]).unwrap_err();
        assert_eq!((i, e.kind()), (1, io::ErrorKind::NotFound));
        assert_eq!(std::fs::read(&a).unwrap(), b"old");
        assert!(leftovers(&d).is_empty(), "{:?}", leftovers(&d));
        std::fs::remove_dir_all(&d).unwrap();
    }

    #[test]
    fn permissions_and_symbolic_links_are_kept() {
        use std::os::unix::fs::PermissionsExt;
        let d = dir("links");
        let target = d.join("model.mt");
        std::fs::write(&target, b"old").unwrap();
        std::fs::set_permissions(&target, Permissions::from_mode(0o640)).unwrap();
        let link = d.join("link.mt");
        std::os::unix::fs::symlink(&target, &link).unwrap();
        write_files(&[(&link, b"new")]).unwrap();
        assert!(
            std::fs::symlink_metadata(&link)
                .unwrap()
                .file_type()
                .is_symlink()
        );
        assert_eq!(std::fs::read(&target).unwrap(), b"new");
        let mode = std::fs::metadata(&target).unwrap().permissions().mode();
        assert_eq!(mode & 0o777, 0o640);
        std::fs::remove_dir_all(&d).unwrap();
    }

    #[test]
    fn devices_and_directories_are_written_in_place() {
        write_files(&[(Path::new("/dev/null"), b"bytes")]).unwrap();
        let d = dir("directory");
        let (i, _) = write_files(&[(&d, b"bytes")]).unwrap_err();
        assert_eq!(i, 0);
        assert!(d.is_dir());
        std::fs::remove_dir_all(&d).unwrap();
    }
}
