//! Every file the tool writes goes through [`write_file`], and is whole or untouched: the bytes go
//! to a temporary file in the destination's folder, which is synced and then renamed over the
//! destination (a rename within one folder is atomic), so a full disk, a failed write or a killed
//! process leaves the previous file as it was; the temporary file a killed run leaves is removed
//! by the next write of the same file once its process is gone. [`check`] and [`create_folder`] refuse, before the
//! work, an output that could not be written or that is an input; [`lock_folder`] keeps two runs
//! out of one folder.

use super::Failure;
use std::fs::{self, File, OpenOptions, Permissions, TryLockError};
use std::io::{self, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

/// At most this many symbolic links are followed to find a destination (Linux's MAXSYMLINKS).
const MAX_LINKS: usize = 40;

/// The number of this process's next temporary file: parallel writes (`lessons`) never share one.
static NEXT_TEMP: AtomicU64 = AtomicU64::new(0);

/// Writes `bytes` to `path`, whole or not at all: on any error the temporary file is removed and
/// the destination keeps its previous contents (or stays absent). A symbolic link is written
/// through (its target is replaced, the link stays); a device or a pipe (`/dev/null`), which has
/// no previous contents to keep, is written directly.
pub fn write_file(path: &Path, bytes: &[u8]) -> Result<(), Failure> {
    let fail = |e: String| Failure::other(format!("{}: cannot write: {e}", path.display()));
    let dest = resolve(path);
    if target(&dest).map_err(fail)? == Target::Device {
        return OpenOptions::new()
            .write(true)
            .open(&dest)
            .and_then(|mut f| f.write_all(bytes))
            .map_err(|e| fail(e.to_string()));
    }
    sweep_stale(&dest);
    let temp = temp_beside(&dest);
    // A file replaced keeps its permissions, as a file written in place would.
    let keep = fs::metadata(&dest).ok().map(|m| m.permissions());
    let written = write_synced(&temp, bytes, keep).and_then(|()| fs::rename(&temp, &dest));
    written.map_err(|e| {
        let _ = fs::remove_file(&temp);
        fail(e.to_string())
    })
}

/// Creates `temp` (never an existing file), with the permissions `keep` if given, writes `bytes`
/// and syncs them to the disk.
fn write_synced(temp: &Path, bytes: &[u8], keep: Option<Permissions>) -> io::Result<()> {
    let mut file = OpenOptions::new().write(true).create_new(true).open(temp)?;
    if let Some(permissions) = keep {
        file.set_permissions(permissions)?;
    }
    file.write_all(bytes)?;
    file.sync_all()
}

/// The temporary file beside `dest`: `.NAME.tmp-PID-N`, hidden, unique to this process and write.
fn temp_beside(dest: &Path) -> PathBuf {
    let name = dest.file_name().map_or_else(|| "output".into(), |n| n.to_string_lossy().into_owned());
    let n = NEXT_TEMP.fetch_add(1, Ordering::Relaxed);
    dest.with_file_name(format!(".{name}.tmp-{}-{n}", std::process::id()))
}

/// Where the processes' folders are (`/proc/PID`): a temporary file's process is gone when its
/// folder is. Without it (not Linux) nothing is swept, since nothing can tell a live run.
const PROCESSES: &str = "/proc";

/// Removes the temporary files `.NAME.tmp-PID-N` of `dest` left by a run that was killed: those
/// whose process `PID` is gone. A live run's (another `lessons` writing the same file) is kept.
/// Best effort: a file that cannot be listed or removed stays, as it would have without it.
fn sweep_stale(dest: &Path) {
    let processes = Path::new(PROCESSES);
    if !processes.join("self").exists() {
        return;
    }
    let (Some(name), Ok(entries)) = (dest.file_name(), fs::read_dir(folder_of(dest))) else { return };
    let prefix = format!(".{}.tmp-", name.to_string_lossy());
    for entry in entries.filter_map(Result::ok) {
        let file = entry.file_name();
        let Some(rest) = file.to_str().and_then(|f| f.strip_prefix(&prefix)) else { continue };
        let Some((pid, n)) = rest.split_once('-') else { continue };
        let ours = pid.parse::<u32>().is_ok_and(|p| p == std::process::id());
        let numbered = !pid.is_empty() && pid.bytes().chain(n.bytes()).all(|b| b.is_ascii_digit());
        if numbered && !n.is_empty() && !ours && !processes.join(pid).exists() {
            let _ = fs::remove_file(entry.path());
        }
    }
}

/// `path` after its symbolic links (also a dangling one: its target is the file to create).
fn resolve(path: &Path) -> PathBuf {
    let mut path = path.to_path_buf();
    for _ in 0..MAX_LINKS {
        let Ok(link) = fs::read_link(&path) else { break };
        // A relative link is relative to its own folder; `join` keeps an absolute one as it is.
        path = path.parent().map_or_else(|| link.clone(), |dir| dir.join(&link));
    }
    path
}

/// What a destination (after its links) is.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Target {
    /// A regular file, or nothing yet: written through a temporary file.
    File,
    /// A device or a pipe: written directly.
    Device,
}

/// The kind of destination `dest` is; a folder or a read-only file cannot be one.
fn target(dest: &Path) -> Result<Target, String> {
    match fs::metadata(dest) {
        Ok(m) if m.is_dir() => Err("is a folder".into()),
        Ok(m) if m.is_file() && m.permissions().readonly() => Err("the file is read-only".into()),
        Ok(m) if !m.is_file() => Ok(Target::Device),
        _ => Ok(Target::File),
    }
}

/// The folder a file is written into (`.` for a bare name).
fn folder_of(path: &Path) -> &Path {
    path.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or_else(|| Path::new("."))
}

/// `path` made absolute with every link resolved; a file that does not exist yet by its folder's.
fn canonical(path: &Path) -> Option<PathBuf> {
    fs::canonicalize(path)
        .ok()
        .or_else(|| Some(fs::canonicalize(folder_of(path)).ok()?.join(path.file_name()?)))
}

/// Checks, before the work, one file a command will write: it is none of `inputs` (compared
/// after links, so a symbolic link to the scene is caught), its folder exists and can be written,
/// it is not a folder or a read-only file, and it ends in one of `extensions` (said as
/// "the output must end in .png or .svg"). Returns the index of its extension; a device or a
/// pipe, which takes any bytes, gets the first. Every refusal is bad input (exit 2).
pub fn check(path: &Path, extensions: &[&str], inputs: &[&Path]) -> Result<usize, Failure> {
    let dest = resolve(path);
    let refuse = |why: String| Failure::input(format!("{}: {why}", path.display()));
    if let Some(out) = canonical(&dest) {
        if let Some(input) = inputs.iter().find(|i| canonical(i).as_ref() == Some(&out)) {
            return Err(refuse(format!("is the input scene {}; write to another file", input.display())));
        }
    }
    check_folder(folder_of(&dest))?;
    if target(&dest).map_err(refuse)? == Target::Device {
        return Ok(0);
    }
    let ext = dest.extension().and_then(|e| e.to_str()).map(str::to_ascii_lowercase);
    extensions.iter().position(|e| ext.as_deref() == Some(*e)).ok_or_else(|| {
        let names: Vec<String> = extensions.iter().map(|e| format!(".{e}")).collect();
        refuse(format!("the output must end in {}", names.join(" or ")))
    })
}

/// Checks that `dir` is a folder this process can write into, by creating and removing a
/// temporary file in it (permissions alone do not say it: a read-only mount, a privileged user).
fn check_folder(dir: &Path) -> Result<(), Failure> {
    let refuse = |why: String| Failure::input(format!("{}: {why}", dir.display()));
    match fs::metadata(dir) {
        Err(e) if e.kind() == io::ErrorKind::NotFound => {
            return Err(refuse("the output folder does not exist".into()))
        }
        Err(e) => return Err(refuse(format!("cannot use the output folder: {e}"))),
        Ok(m) if !m.is_dir() => return Err(refuse("is not a folder".into())),
        Ok(_) => {}
    }
    let probe = temp_beside(&dir.join("probe"));
    write_synced(&probe, &[], None)
        .map_err(|e| refuse(format!("the output folder cannot be written: {e}")))?;
    let _ = fs::remove_file(&probe);
    Ok(())
}

/// Creates the output folder `dir` (and its parents) if missing and checks that it can be
/// written, before the work.
pub fn create_folder(dir: &Path) -> Result<(), Failure> {
    fs::create_dir_all(dir)
        .map_err(|e| Failure::input(format!("{}: cannot create the output folder: {e}", dir.display())))?;
    check_folder(dir)
}

/// An exclusive lock on an output folder for one run. The operating system holds it on the open
/// file and drops it when the file is closed or the process ends, however it ends, so a killed
/// run leaves no stale lock (the empty lock file stays, and means nothing unlocked).
#[derive(Debug)]
pub struct FolderLock {
    /// The locked file, kept open for the run.
    _file: File,
}

/// Takes the lock file `name` in `dir` without waiting; a folder another run holds is refused
/// (exit 2) with the lock file named.
pub fn lock_folder(dir: &Path, name: &str) -> Result<FolderLock, Failure> {
    let path = dir.join(name);
    let cannot =
        |e: String| Failure::other(format!("{}: cannot lock the output folder: {e}", path.display()));
    let file = OpenOptions::new()
        .write(true)
        .create(true)
        .truncate(false)
        .open(&path)
        .map_err(|e| cannot(e.to_string()))?;
    match file.try_lock() {
        Ok(()) => Ok(FolderLock { _file: file }),
        Err(TryLockError::WouldBlock) => Err(Failure::input(format!(
            "{}: the output folder {} is in use by another run; try again when it has finished",
            path.display(),
            dir.display()
        ))),
        Err(TryLockError::Error(e)) => Err(cannot(e.to_string())),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_killed_runs_temporary_file_is_swept_by_the_next_write() {
        if !Path::new(PROCESSES).join("1").exists() {
            eprintln!("no {PROCESSES}: nothing is swept, nothing to check");
            return;
        }
        let scratch = tempfile::tempdir().unwrap();
        let dir = scratch.path();
        // No process has this number (Linux's pid_max is at most 2^22); process 1 always runs.
        let stale = dir.join(".x.png.tmp-4000000000-7");
        let live = dir.join(".x.png.tmp-1-0");
        let other = dir.join(".y.png.tmp-4000000000-0");
        for path in [&stale, &live, &other] {
            fs::write(path, b"partial").unwrap();
        }
        write_file(&dir.join("x.png"), b"whole").unwrap();
        assert_eq!(fs::read(dir.join("x.png")).unwrap(), b"whole");
        assert!(!stale.exists(), "the killed run's file is swept");
        assert!(live.exists() && other.exists(), "a live run's file and another file's stay");
    }
}
