//! One run per folder: two `solve` runs writing into the same folder would interleave
//! their rows and leave one's `run.json` beside the other's `result.json`. A run holds
//! `.invlight.lock` (its process id inside) while it writes; a second run is refused
//! with the holder's pid. A lock left by a process that no longer runs (killed hard) is
//! stale and taken over.

use super::OutputError;
use std::fs::OpenOptions;
use std::io::{self, Write};
use std::path::{Path, PathBuf};

/// The lock file's name.
pub const LOCK_FILE: &str = ".invlight.lock";

/// A held folder lock, released when dropped.
#[derive(Debug)]
pub struct FolderLock {
    path: PathBuf,
}

impl FolderLock {
    /// Takes `dir`'s lock, or says which process holds it.
    pub fn take(dir: &Path) -> Result<FolderLock, OutputError> {
        let path = dir.join(LOCK_FILE);
        for _ in 0..2 {
            match OpenOptions::new().write(true).create_new(true).open(&path) {
                Ok(mut f) => {
                    writeln!(f, "{}", std::process::id())?;
                    return Ok(FolderLock { path });
                }
                Err(e) if e.kind() == io::ErrorKind::AlreadyExists => {
                    let text = std::fs::read_to_string(&path).unwrap_or_default();
                    let holder = text.trim().parse::<u32>().ok();
                    match holder {
                        Some(pid) if alive(pid) => {
                            return Err(OutputError::Locked(format!(
                                "{} is in use by another invlight run (process {pid}); wait for it to finish or choose another --output",
                                dir.display()
                            )));
                        }
                        // Stale (or unreadable, written by a process killed mid-write).
                        _ => std::fs::remove_file(&path)?,
                    }
                }
                Err(e) => return Err(e.into()),
            }
        }
        Err(OutputError::Locked(format!(
            "{} is in use by another invlight run (its lock file {} keeps coming back)",
            dir.display(),
            path.display()
        )))
    }
}

impl Drop for FolderLock {
    fn drop(&mut self) {
        let _ = std::fs::remove_file(&self.path);
    }
}

/// Whether process `pid` runs. On Linux, /proc tells; elsewhere a lock is assumed held
/// (the user removes a stale one, as the message says). A zombie (state `Z` after the
/// command in /proc/PID/stat, proc(5)) runs no more: a run killed hard, e.g. by
/// `mpirun` when another rank of its job died, stays one until its parent reaps it, and
/// `--resume` must not wait for that.
fn alive(pid: u32) -> bool {
    if pid == std::process::id() {
        return true;
    }
    let proc = Path::new("/proc");
    if proc.is_dir() {
        let stat = std::fs::read_to_string(proc.join(pid.to_string()).join("stat"));
        stat.is_ok_and(|s| {
            s.rsplit_once(')')
                .is_some_and(|(_, rest)| !rest.trim_start().starts_with('Z'))
        })
    } else {
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A child that has exited but is not reaped is a zombie: its lock is stale.
    #[test]
    #[cfg(target_os = "linux")]
    fn a_zombie_holds_no_lock() {
        let mut child = std::process::Command::new("true").spawn().unwrap();
        let pid = child.id();
        let zombie = (0..200).any(|_| {
            std::thread::sleep(std::time::Duration::from_millis(10));
            !alive(pid)
        });
        assert!(
            Path::new(&format!("/proc/{pid}")).exists(),
            "not reaped yet"
        );
        child.wait().unwrap();
        assert!(
            zombie,
            "process {pid} still counted as running after it exited"
        );
        assert!(alive(std::process::id()));
    }
}
