//! Files the front ends write: never half-written, never replacing what is at their path.
//!
//! * An output path that is absent or a regular file is written atomically: into a hidden
//!   temporary file beside it, then renamed over it.
//! * A symbolic link is followed to its target, which is written the same way (the link
//!   stays a link).
//! * A FIFO, a character device (`/dev/null`, a terminal) or a stream named through
//!   `/dev/stdout`, `/dev/fd/N` or `/proc/PID/fd/N` is written in place: the bytes go to
//!   whatever reads it, and the node itself is never replaced.
//! * Anything else (a folder where a file is asked, a block device, a socket) is refused
//!   with a message that says what is there.
//!
//! Folders of results ([`OutputSet`]) are written the same way as a whole: a staging folder
//! beside the target replaces it by renames, and the target may only hold files a run of
//! the same command writes. Temporary files and folders carry the writing process's id; an
//! interrupted run (Ctrl-C) removes its own, and every later run removes those of
//! processes that no longer exist.

use crate::ReportError as Error;
use std::fs::{self, File, OpenOptions};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// The longest chain of symbolic links followed before giving up.
const MAX_LINKS: usize = 40;

/// What is at an output path.
#[derive(Debug, Clone, PartialEq, Eq)]
enum Node {
    /// Nothing: created atomically at this path (the target of a dangling link).
    Absent(PathBuf),
    /// A regular file, to be replaced atomically (its real path).
    Regular(PathBuf),
    /// A folder (its real path).
    Folder(PathBuf),
    /// A stream written in place: a FIFO, a character device or a process's descriptor.
    Stream(PathBuf),
    /// Something no output may touch, named.
    Other(&'static str),
}

/// Follows `path` to what it names, without replacing or creating anything.
fn inspect(path: &Path) -> Result<Node, Error> {
    let io = |e: std::io::Error| write_error(path, e);
    // a descriptor of this or another process names a stream, whatever is behind it
    let mut p = path.to_path_buf();
    for _ in 0..MAX_LINKS {
        if is_descriptor(&p) {
            return Ok(Node::Stream(path.to_path_buf()));
        }
        match fs::symlink_metadata(&p) {
            Ok(m) if m.file_type().is_symlink() => {
                let t = fs::read_link(&p).map_err(io)?;
                p = if t.is_absolute() {
                    t
                } else {
                    p.parent().unwrap_or(Path::new(".")).join(t)
                };
            }
            Ok(_) => break,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(Node::Absent(p)),
            Err(e) => return Err(io(e)),
        }
    }
    let m = match fs::metadata(&p) {
        Ok(m) => m,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(Node::Absent(p)),
        Err(e) => return Err(io(e)),
    };
    let real = || fs::canonicalize(&p).unwrap_or_else(|_| p.clone());
    let t = m.file_type();
    if t.is_file() {
        return Ok(Node::Regular(real()));
    }
    if t.is_dir() {
        return Ok(Node::Folder(real()));
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if t.is_fifo() || t.is_char_device() {
            return Ok(Node::Stream(path.to_path_buf()));
        }
        if t.is_block_device() {
            return Ok(Node::Other("a block device"));
        }
        if t.is_socket() {
            return Ok(Node::Other("a socket"));
        }
    }
    Ok(Node::Other("not a regular file"))
}

/// `/dev/stdout`, `/dev/stderr`, `/dev/fd/N`, `/proc/PID/fd/N`: names of open descriptors.
fn is_descriptor(p: &Path) -> bool {
    let s = p.to_string_lossy();
    s == "/dev/stdout"
        || s == "/dev/stderr"
        || s.starts_with("/dev/fd/")
        || (s.starts_with("/proc/") && s.contains("/fd/"))
}

fn write_error(path: &Path, source: std::io::Error) -> Error {
    Error::Write {
        path: path.display().to_string(),
        source,
    }
}

fn refuse(path: &Path, what: impl Into<String>) -> Error {
    write_error(path, std::io::Error::other(what.into()))
}

/// Checks, before any computation, that `path` can take one output file: absent, a
/// regular file, a stream or a link to one of those, in a folder that exists.
pub fn check_file(path: &Path) -> Result<(), Error> {
    match inspect(path)? {
        Node::Absent(p) | Node::Regular(p) => {
            let parent = parent_of(&p);
            if !parent.is_dir() {
                return Err(refuse(
                    path,
                    format!("the folder {} does not exist", parent.display()),
                ));
            }
            Ok(())
        }
        Node::Stream(_) => Ok(()),
        Node::Folder(_) => Err(refuse(path, "it is a folder, not a file")),
        Node::Other(what) => Err(refuse(
            path,
            format!("it is {what}: an output never replaces one"),
        )),
    }
}

/// Writes one file: atomically for a regular or absent file (a link's target included),
/// in place for a stream; refused for anything else.
pub fn write_file(path: &Path, bytes: &[u8]) -> Result<(), Error> {
    match inspect(path)? {
        Node::Absent(p) | Node::Regular(p) => atomic_file(path, &p, bytes),
        Node::Stream(p) => {
            let mut f = open_stream(path, &p)?;
            f.write_all(bytes)
                .and_then(|()| f.flush())
                .map_err(|e| write_error(path, e))
        }
        Node::Folder(_) => Err(refuse(path, "it is a folder, not a file")),
        Node::Other(what) => Err(refuse(
            path,
            format!("it is {what}: an output never replaces one"),
        )),
    }
}

/// Opens a stream for writing without blocking on a FIFO that nobody reads (refused with a
/// message instead of waiting for ever); the writes themselves then block as usual.
fn open_stream(shown: &Path, p: &Path) -> Result<File, Error> {
    let mut options = OpenOptions::new();
    options.append(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt;
        options.custom_flags(libc::O_NONBLOCK);
    }
    let f = options.open(p).map_err(|e| {
        #[cfg(unix)]
        if e.raw_os_error() == Some(libc::ENXIO) {
            return refuse(
                shown,
                "it is a FIFO with no reader: start the reader first (an output never waits for one)",
            );
        }
        write_error(shown, e)
    })?;
    #[cfg(unix)]
    {
        use std::os::unix::io::AsRawFd;
        let fd = f.as_raw_fd();
        // SAFETY: fcntl on a descriptor this function owns, flags read then written back
        // without O_NONBLOCK; no memory is passed.
        let cleared = unsafe {
            let flags = libc::fcntl(fd, libc::F_GETFL);
            flags >= 0 && libc::fcntl(fd, libc::F_SETFL, flags & !libc::O_NONBLOCK) == 0
        };
        if !cleared {
            return Err(write_error(shown, std::io::Error::last_os_error()));
        }
    }
    Ok(f)
}

fn parent_of(p: &Path) -> PathBuf {
    match p.parent() {
        Some(q) if !q.as_os_str().is_empty() => q.to_path_buf(),
        _ => PathBuf::from("."),
    }
}

fn base_name(p: &Path) -> String {
    p.file_name()
        .map(|n| n.to_string_lossy().to_string())
        .unwrap_or_else(|| "out".into())
}

/// Writes `bytes` to `target` through a temporary file beside it (`shown`: the path the
/// user gave, for messages).
fn atomic_file(shown: &Path, target: &Path, bytes: &[u8]) -> Result<(), Error> {
    let parent = parent_of(target);
    let base = base_name(target);
    sweep_stale(&parent, &base);
    let tmp = parent.join(temp_name(&base, "new"));
    let guard = Pending::register(vec![tmp.clone()]);
    let result = (|| {
        let mut f = File::create(&tmp)?;
        f.write_all(bytes)?;
        f.sync_all()?;
        fs::rename(&tmp, target)
    })();
    if result.is_err() {
        let _ = fs::remove_file(&tmp);
    }
    drop(guard);
    result.map_err(|e| write_error(shown, e))
}

/// `.BASE.KIND-PID-NANOS`: hidden, and naming the process that writes it.
fn temp_name(base: &str, kind: &str) -> String {
    format!(".{base}.{kind}-{}-{}", std::process::id(), nanos())
}

fn nanos() -> u128 {
    std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map(|d| d.as_nanos())
        .unwrap_or(0)
}

/// Removes the temporary files and folders `.BASE.new-PID-*` and `.BASE.old-PID-*` in
/// `folder` left by processes that no longer run (an interrupted or killed run).
fn sweep_stale(folder: &Path, base: &str) {
    let Ok(entries) = fs::read_dir(folder) else {
        return;
    };
    for entry in entries.flatten() {
        let name = entry.file_name().to_string_lossy().to_string();
        let Some(pid) = stale_pid(&name, base) else {
            continue;
        };
        if pid == std::process::id() || process_runs(pid) {
            continue;
        }
        let p = entry.path();
        match entry.file_type() {
            Ok(t) if t.is_dir() => {
                let _ = fs::remove_dir_all(&p);
            }
            Ok(t) if t.is_file() => {
                let _ = fs::remove_file(&p);
            }
            _ => {}
        }
    }
}

/// The process id in a temporary name of `base`, if `name` is one.
fn stale_pid(name: &str, base: &str) -> Option<u32> {
    let rest = name.strip_prefix(&format!(".{base}."))?;
    let rest = rest
        .strip_prefix("new-")
        .or_else(|| rest.strip_prefix("old-"))?;
    let (pid, nonce) = rest.split_once('-')?;
    if nonce.is_empty() || !nonce.bytes().all(|b| b.is_ascii_digit()) {
        return None;
    }
    pid.parse().ok()
}

/// Whether process `pid` exists (Linux: /proc; elsewhere assumed running, so nothing of
/// another process is removed).
fn process_runs(pid: u32) -> bool {
    let proc_root = Path::new("/proc");
    if proc_root.join("self").exists() {
        proc_root.join(pid.to_string()).exists()
    } else {
        true
    }
}

/// Temporary paths of this process, removed if it is interrupted (SIGINT, SIGTERM; with
/// the feature `interrupt`, which a program that owns its signals turns on: the command
/// line does, a Python extension does not).
static PENDING: Mutex<Vec<Pending>> = Mutex::new(Vec::new());
#[cfg(feature = "interrupt")]
static HANDLER: std::sync::Once = std::sync::Once::new();

/// One registered write: temporary paths to remove on interruption, and a folder moved
/// aside to put back.
#[derive(Debug, Clone, Default)]
struct Pending {
    id: u128,
    remove: Vec<PathBuf>,
    /// (retired, target): if interrupted between the two renames, the retired folder goes
    /// back to the target.
    restore: Option<(PathBuf, PathBuf)>,
}

/// Unregisters its write when dropped.
struct PendingGuard(u128);

impl Pending {
    fn register(remove: Vec<PathBuf>) -> PendingGuard {
        // without a handler an interruption leaves the temporary files; a later run
        // sweeps them
        #[cfg(feature = "interrupt")]
        HANDLER.call_once(|| {
            let _ = ctrlc::set_handler(|| {
                clean_up_pending();
                std::process::exit(130);
            });
        });
        let id = nanos();
        lock_pending().push(Pending {
            id,
            remove,
            restore: None,
        });
        PendingGuard(id)
    }
}

impl Drop for PendingGuard {
    fn drop(&mut self) {
        lock_pending().retain(|p| p.id != self.0);
    }
}

fn lock_pending() -> std::sync::MutexGuard<'static, Vec<Pending>> {
    PENDING.lock().unwrap_or_else(|e| e.into_inner())
}

#[cfg_attr(not(feature = "interrupt"), allow(dead_code))]
fn clean_up_pending() {
    let mut pending = lock_pending();
    for p in pending.drain(..) {
        if let Some((retired, target)) = &p.restore {
            if retired.exists() && !target.exists() {
                let _ = fs::rename(retired, target);
            }
        }
        for r in &p.remove {
            if r.is_dir() {
                let _ = fs::remove_dir_all(r);
            } else {
                let _ = fs::remove_file(r);
            }
        }
    }
}

/// Files of one run, written together or not at all: into a fresh folder beside the
/// target, which then replaces the target by renames. The target may only hold files a
/// run of the same command writes (`known`), so that nothing of an earlier run is left
/// beside new results and nothing else is ever removed. A symbolic link to a folder is
/// followed: the folder it names is replaced, the link stays.
#[derive(Debug)]
pub struct OutputSet {
    dir: PathBuf,
    known: &'static [&'static str],
    files: Vec<(String, Vec<u8>)>,
}

impl OutputSet {
    /// A set for folder `dir` of a command that can write the files named in `known`.
    pub fn new(dir: &Path, known: &'static [&'static str]) -> Self {
        Self {
            dir: dir.to_path_buf(),
            known,
            files: Vec::new(),
        }
    }

    /// Adds a file (its name must be one of `known`).
    pub fn add(&mut self, name: &str, bytes: impl Into<Vec<u8>>) {
        debug_assert!(self.known.contains(&name), "{name} not declared");
        self.files.push((name.to_string(), bytes.into()));
    }

    /// The names of the files added.
    pub fn names(&self) -> Vec<String> {
        self.files.iter().map(|f| f.0.clone()).collect()
    }

    /// Checks, before any computation, that the folder can take the results: absent (its
    /// parent existing or creatable), or a folder (a link's target included) holding only
    /// files this command writes. Returns the real folder the results will replace.
    pub fn check(dir: &Path, known: &[&str]) -> Result<PathBuf, Error> {
        match inspect(dir)? {
            Node::Absent(p) => Ok(p),
            Node::Folder(p) => {
                let entries = fs::read_dir(&p).map_err(|e| write_error(dir, e))?;
                for entry in entries {
                    let entry = entry.map_err(|e| write_error(dir, e))?;
                    let name = entry.file_name().to_string_lossy().to_string();
                    let is_file = entry.file_type().map(|t| t.is_file()).unwrap_or(false);
                    if !is_file || !known.contains(&name.as_str()) {
                        return Err(refuse(
                            dir,
                            format!(
                                "the folder holds `{name}`, which this command does not write; give an empty or new folder (it is replaced as a whole)"
                            ),
                        ));
                    }
                }
                Ok(p)
            }
            Node::Regular(_) => Err(refuse(dir, "it is a file, not a folder")),
            Node::Stream(_) => Err(refuse(
                dir,
                "it is a stream or device, not a folder: give a folder (--out, or the folder of save())",
            )),
            Node::Other(what) => Err(refuse(dir, format!("it is {what}, not a folder"))),
        }
    }

    /// Writes the set: all files appear together in the folder, replacing what an earlier
    /// run of the command left there.
    pub fn commit(self) -> Result<Vec<PathBuf>, Error> {
        let target = Self::check(&self.dir, self.known)?;
        let shown = &self.dir;
        let parent = parent_of(&target);
        // errors name the folder the user gave, never the hidden staging folder
        fs::create_dir_all(&parent).map_err(|e| write_error(shown, e))?;
        let base = base_name(&target);
        sweep_stale(&parent, &base);
        let staging = parent.join(temp_name(&base, "new"));
        let retired = parent.join(temp_name(&base, "old"));
        let guard = Pending::register(vec![staging.clone(), retired.clone()]);
        let result = (|| {
            fs::create_dir(&staging).map_err(|e| write_error(shown, e))?;
            for (name, bytes) in &self.files {
                let p = staging.join(name);
                let named = shown.join(name);
                let mut f = File::create(&p).map_err(|e| write_error(&named, e))?;
                f.write_all(bytes)
                    .and_then(|()| f.sync_all())
                    .map_err(|e| write_error(&named, e))?;
            }
            // the two renames as one step for an interruption: the handler waits for the
            // lock and finds either the old folder or the new one in place
            let mut pending = lock_pending();
            if let Some(p) = pending.iter_mut().find(|p| p.id == guard.0) {
                p.restore = Some((retired.clone(), target.clone()));
            }
            if target.exists() {
                fs::rename(&target, &retired).map_err(|e| write_error(shown, e))?;
            }
            if let Err(e) = fs::rename(&staging, &target) {
                // put the earlier results back rather than leave nothing
                let _ = fs::rename(&retired, &target);
                return Err(write_error(shown, e));
            }
            drop(pending);
            let _ = fs::remove_dir_all(&retired);
            Ok(())
        })();
        if result.is_err() {
            let _ = fs::remove_dir_all(&staging);
        }
        drop(guard);
        result?;
        Ok(self.files.iter().map(|f| self.dir.join(&f.0)).collect())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn temporary_names_carry_the_process_and_are_recognised() {
        let n = temp_name("out", "new");
        assert_eq!(stale_pid(&n, "out"), Some(std::process::id()));
        assert_eq!(stale_pid(".out.old-12-345", "out"), Some(12));
        assert_eq!(stale_pid(".out.new-12-", "out"), None);
        assert_eq!(stale_pid(".other.new-12-3", "out"), None);
        assert_eq!(stale_pid("out", "out"), None);
    }

    #[test]
    fn descriptors_are_streams() {
        for p in [
            "/dev/stdout",
            "/dev/fd/3",
            "/proc/self/fd/1",
            "/proc/42/fd/7",
        ] {
            assert!(is_descriptor(Path::new(p)), "{p}");
        }
        for p in ["/dev/null", "out/switch.svg", "/proc/cpuinfo"] {
            assert!(!is_descriptor(Path::new(p)), "{p}");
        }
    }
}
