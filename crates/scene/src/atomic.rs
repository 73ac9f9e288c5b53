//! Files that are whole or absent: a result a reader opens while it is rewritten, a
//! picture written when the disk fills, must never be half a file.

use std::fs::File;
use std::io::{self, Write};
use std::path::{Path, PathBuf};

/// Writes `path` through a temporary file beside it and a rename, so that a reader
/// (or a crash) never sees half a file; on failure the temporary file is removed and
/// `path` is as it was.
pub fn write_atomically(
    path: &Path,
    write: impl FnOnce(&mut io::BufWriter<File>) -> io::Result<()>,
) -> io::Result<()> {
    let mut tmp = path.as_os_str().to_owned();
    tmp.push(".tmp");
    let tmp = PathBuf::from(tmp);
    let result = File::create(&tmp).and_then(|f| {
        let mut w = io::BufWriter::new(f);
        write(&mut w)?;
        w.flush()
    });
    match result.and_then(|()| std::fs::rename(&tmp, path)) {
        Ok(()) => Ok(()),
        Err(e) => {
            let _ = std::fs::remove_file(&tmp);
            Err(e)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A write that fails (a full disk: /dev/full answers every write with ENOSPC) leaves
    /// no temporary file and the old file as it was.
    #[test]
    fn a_failed_write_leaves_the_old_file() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("result.json");
        std::fs::write(&path, "old").unwrap();
        let e = write_atomically(&path, |w| {
            w.write_all(b"new")?;
            Err(std::io::Error::other("disk full"))
        })
        .unwrap_err();
        assert_eq!(e.to_string(), "disk full");
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "old");
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
        if Path::new("/dev/full").exists() {
            let tmp = dir.path().join("result.json.tmp");
            std::os::unix::fs::symlink("/dev/full", &tmp).unwrap();
            let big = vec![b'x'; 1 << 16];
            assert!(write_atomically(&path, |w| w.write_all(&big)).is_err());
            assert!(!tmp.exists(), "the temporary file is removed");
            assert_eq!(std::fs::read_to_string(&path).unwrap(), "old");
        }
    }
}
