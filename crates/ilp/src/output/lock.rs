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
/// (the user removes a stale one, as the message says).
fn alive(pid: u32) -> bool {
    if pid == std::process::id() {
        return true;
    }
    let proc = Path::new("/proc");
    if proc.is_dir() {
        proc.join(pid.to_string()).exists()
    } else {
        true
    }
}
