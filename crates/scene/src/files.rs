//! How the loaders reach files and memory: the scene file, the files it references
//! (glTF buffers and images, OBJ `mtllib` and `map_Kd`, COLLADA `<init_from>`), and
//! the memory a file's declared sizes ask for.
//!
//! A scene file may come from anyone, so by default a reference must be a relative
//! path that stays inside the scene file's folder tree: `..` is resolved, and so are
//! symbolic links (the canonical path must lie under the canonical folder), so that
//! `/etc/hostname`, `../../../etc/passwd` or a link to them is refused with a
//! [`LoadError`] naming the reference. [`LoadOptions::allow_outside_paths`] lifts that
//! for trusted files. Whatever the options, only regular files are read: `/dev/zero`
//! (read unbounded it took 2.1 GB) or a FIFO would never end. Every read is bounded, by
//! the size the format declares when it declares one (a glTF buffer's `byteLength`)
//! and by the memory budget.
//!
//! The budget ([`LoadOptions::max_memory`]) is charged before each large allocation
//! made from a declared size: the scene file, buffers, accessor copies, decoded
//! images. It is a running total, never refunded, so it over-counts transient copies
//! a little; its point is to refuse a 4 KB file that claims 2 GB of vertices, or a PNG
//! whose header declares 13 000² pixels, with the figure, before allocating.

use crate::error::LoadError;
use crate::load::LoadOptions;
use std::cell::Cell;
use std::fmt;
use std::io::Read;
use std::path::{Component, Path, PathBuf};

/// The hint of a reference refused for lying outside the scene's folder.
const OUTSIDE_HINT: &str = "a scene file may only reference files in its own folder or below; \
    copy the file there, or pass --allow-outside-paths (LoadOptions::allow_outside_paths) \
    if you trust the scene";

/// Reaches files for one load: the folder tree references must stay in, and the
/// memory budget.
pub(crate) struct Files {
    /// The scene file's folder, canonical; references must lead under it unless
    /// `allow_outside`.
    root: PathBuf,
    /// The same folder as written (absolute, `..` resolved, links kept), which a
    /// reference must stay under before links are followed.
    written_root: PathBuf,
    allow_outside: bool,
    /// Bytes the load may allocate from declared sizes, and how many it has.
    limit: u64,
    used: Cell<u64>,
}

/// A byte count for messages: `2.1 GB`, `512 MB`, `3.0 kB`.
pub(crate) fn show_bytes(n: u64) -> String {
    let n = n as f64;
    match n {
        n if n >= 1e9 => format!("{:.1} GB", n / 1e9),
        n if n >= 1e6 => format!("{:.0} MB", n / 1e6),
        n if n >= 1e3 => format!("{:.1} kB", n / 1e3),
        n => format!("{n} bytes"),
    }
}

/// The hint of a refusal for memory.
pub(crate) fn memory_hint(limit: u64) -> String {
    format!(
        "the limit is {} (--max-memory, LoadOptions::max_memory; by default half of this \
         machine's memory): raise it if the machine has the memory and you trust the file",
        show_bytes(limit)
    )
}

impl Files {
    /// The files of the scene at `scene`.
    pub fn new(scene: &Path, options: &LoadOptions) -> Files {
        let folder = scene.parent().unwrap_or(Path::new(""));
        let folder = if folder.as_os_str().is_empty() {
            Path::new(".")
        } else {
            folder
        };
        Files {
            root: folder
                .canonicalize()
                .unwrap_or_else(|_| lexical_absolute(folder)),
            written_root: lexical_absolute(folder),
            allow_outside: options.allow_outside_paths,
            limit: options.max_memory,
            used: Cell::new(0),
        }
    }

    /// Charges `bytes` to the budget, or refuses with the figure: `what` says what
    /// needs them (`12 000 000 VEC3 positions`), `from` and `loc` where it is declared.
    pub fn charge(&self, from: &Path, loc: &str, bytes: u64, what: &str) -> Result<(), LoadError> {
        let used = self.used.get().saturating_add(bytes);
        if used > self.limit {
            return Err(LoadError::at(
                from,
                loc,
                format!(
                    "{what} need {}, which would bring the load to {}, past its limit of {}",
                    show_bytes(bytes),
                    show_bytes(used),
                    show_bytes(self.limit)
                ),
            )
            .with_hint(memory_hint(self.limit)));
        }
        self.used.set(used);
        Ok(())
    }

    /// Reads the scene file itself: a regular file, within the budget.
    pub fn read_scene(&self, path: &Path) -> Result<Vec<u8>, LoadError> {
        let file = open_regular(path).map_err(|e| match e {
            Open::Missing => LoadError::new(path, "no such file"),
            Open::Refused(m) => LoadError::new(path, m),
        })?;
        let size = file.metadata().map(|m| m.len()).unwrap_or(0);
        self.charge(path, "", size, "the file's bytes")?;
        read_at_most(file, size)
            .map_err(|e| LoadError::new(path, format!("cannot read the file: {e}")))
    }

    /// Resolves a reference `written` at `loc` in the file `from` (whose folder a
    /// relative reference starts from), already unescaped to a path: the file to read,
    /// or an error if it lies outside the scene's folder tree (unless allowed).
    pub fn resolve(
        &self,
        from: &Path,
        loc: &str,
        written: &str,
        reference: &Path,
    ) -> Result<PathBuf, LoadError> {
        let dir = from.parent().unwrap_or(Path::new(""));
        let absolute = reference.is_absolute()
            || reference.has_root()
            || matches!(reference.components().next(), Some(Component::Prefix(_)))
            || looks_like_drive(reference);
        if self.allow_outside {
            return Ok(if absolute {
                reference.to_path_buf()
            } else {
                dir.join(reference)
            });
        }
        let refuse = |why: &str| {
            Err(LoadError::at(from, loc, format!("{written} {why}")).with_hint(OUTSIDE_HINT))
        };
        if absolute {
            return refuse("is an absolute path, outside the scene's folder");
        }
        let joined = dir.join(reference);
        // `..` first, without touching the file system, then links through the
        // canonical path when the file exists (a missing file is the caller's error).
        if !lexical_absolute(&joined).starts_with(&self.written_root) {
            return refuse("leads outside the scene's folder");
        }
        if let Ok(real) = joined.canonicalize()
            && !real.starts_with(&self.root)
        {
            return refuse(&format!(
                "leads outside the scene's folder (through a link, to {})",
                real.display()
            ));
        }
        Ok(joined)
    }

    /// Reads a referenced file (resolved by [`Files::resolve`]): a regular file, at most
    /// `declared` bytes when the format declares its size, and within the budget.
    /// `Err` holds the message for the caller to place.
    pub fn read(
        &self,
        from: &Path,
        loc: &str,
        file: &Path,
        declared: Option<u64>,
    ) -> Result<Vec<u8>, ReadError> {
        let f = open_regular(file).map_err(|e| match e {
            Open::Missing => ReadError::Missing,
            Open::Refused(m) => ReadError::Io(m),
        })?;
        let size = f.metadata().map(|m| m.len()).unwrap_or(0);
        let wanted = declared.map_or(size, |d| d.min(size));
        self.charge(
            from,
            loc,
            wanted,
            &format!("the {} bytes of {}", wanted, file.display()),
        )
        .map_err(ReadError::Budget)?;
        read_at_most(f, wanted).map_err(|e| ReadError::Io(e.to_string()))
    }
}

/// Why a referenced file could not be read.
pub(crate) enum ReadError {
    /// It does not exist.
    Missing,
    /// It is unreadable or not a regular file (the message says which).
    Io(String),
    /// It does not fit in the budget (a complete, located error).
    Budget(LoadError),
}

/// Why a file was not opened.
enum Open {
    Missing,
    Refused(String),
}

/// Opens `path` if it is a regular file (after links): a device, FIFO or folder is
/// refused before anything is read from it.
fn open_regular(path: &Path) -> Result<std::fs::File, Open> {
    let meta = std::fs::metadata(path).map_err(|e| {
        if e.kind() == std::io::ErrorKind::NotFound {
            Open::Missing
        } else {
            Open::Refused(e.to_string())
        }
    })?;
    if !meta.is_file() {
        return Err(Open::Refused(if meta.is_dir() {
            "it is a folder, not a file".to_string()
        } else {
            "it is not a regular file (a device or a pipe): refused, as reading it may never end"
                .to_string()
        }));
    }
    std::fs::File::open(path).map_err(|e| Open::Refused(e.to_string()))
}

/// Reads at most `n` bytes (the file may have shrunk or grown since it was measured).
fn read_at_most(file: std::fs::File, n: u64) -> std::io::Result<Vec<u8>> {
    let mut out = Vec::with_capacity(n.min(1 << 30) as usize);
    file.take(n).read_to_end(&mut out)?;
    Ok(out)
}

/// `path` made absolute against the current folder and with `.` and `..` resolved
/// lexically (no link is followed; `..` above the root stays at the root).
fn lexical_absolute(path: &Path) -> PathBuf {
    let joined = if path.is_absolute() {
        path.to_path_buf()
    } else {
        std::env::current_dir().unwrap_or_default().join(path)
    };
    let mut out = PathBuf::new();
    for c in joined.components() {
        match c {
            Component::CurDir => {}
            Component::ParentDir => {
                out.pop();
            }
            other => out.push(other),
        }
    }
    out
}

/// `C:/x` or `C:\x`: a Windows drive path, absolute there whatever this system says.
fn looks_like_drive(p: &Path) -> bool {
    let s = p.to_string_lossy();
    let b = s.as_bytes();
    b.len() >= 2 && b[0].is_ascii_alphabetic() && b[1] == b':'
}

/// Half of this machine's memory, the default of [`LoadOptions::max_memory`]: on Linux
/// the smallest of `MemTotal` (`/proc/meminfo`), the control group's `memory.max` and
/// the process's soft address-space and data limits (`ulimit -v`, `ulimit -d`, from
/// `/proc/self/limits`), elsewhere (or when none can be read) 4 GiB. Half, because the
/// scene is not all that runs: the photon tracer, the renderer and the rest of the
/// machine need room. The limits count because past them an allocation aborts the
/// process rather than failing the load with the figure.
pub(crate) fn default_max_memory() -> u64 {
    let meminfo = std::fs::read_to_string("/proc/meminfo").ok().and_then(|s| {
        s.lines()
            .find_map(|l| l.strip_prefix("MemTotal:"))
            .and_then(|v| v.trim().trim_end_matches("kB").trim().parse::<u64>().ok())
            .map(|kb| kb * 1024)
    });
    let cgroup = std::fs::read_to_string("/sys/fs/cgroup/memory.max")
        .ok()
        .and_then(|s| s.trim().parse::<u64>().ok());
    let limits = std::fs::read_to_string("/proc/self/limits")
        .ok()
        .and_then(|s| process_limit(&s));
    [meminfo, cgroup, limits]
        .into_iter()
        .flatten()
        .min()
        .map_or(4 << 30, |m| m / 2)
}

/// The smaller soft limit of "Max address space" and "Max data size" in the text of
/// `/proc/self/limits` (bytes; `None` when both are unlimited).
fn process_limit(limits: &str) -> Option<u64> {
    limits
        .lines()
        .filter_map(|l| {
            l.strip_prefix("Max address space")
                .or_else(|| l.strip_prefix("Max data size"))
        })
        .filter_map(|rest| rest.split_whitespace().next()?.parse::<u64>().ok())
        .min()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lexical_paths_resolve_dots() {
        assert_eq!(
            lexical_absolute(Path::new("/a/b/../c/./d")),
            PathBuf::from("/a/c/d")
        );
        assert_eq!(
            lexical_absolute(Path::new("/a/../../x")),
            PathBuf::from("/x")
        );
    }

    #[test]
    fn references_stay_inside_the_folder() {
        let scene =
            Path::new(env!("CARGO_MANIFEST_DIR")).join("../../tests/data/gltf/external.gltf");
        let files = Files::new(&scene, &LoadOptions::default());
        let ok = |r: &str| files.resolve(&scene, "x", r, Path::new(r));
        assert!(ok("external.bin").is_ok());
        assert!(ok("sub/../external.bin").is_ok());
        assert!(ok("../gltf/external.bin").is_ok());
        for bad in [
            "../obj/names.mtl",
            "/etc/hostname",
            "C:/Windows/win.ini",
            "../../../../../../etc/passwd",
        ] {
            let e = ok(bad).unwrap_err();
            assert!(e.message.contains(bad), "{e}");
            assert!(
                e.hint.as_deref().unwrap().contains("--allow-outside-paths"),
                "{e}"
            );
        }
        let trusting = Files::new(
            &scene,
            &LoadOptions {
                allow_outside_paths: true,
                ..LoadOptions::default()
            },
        );
        assert_eq!(
            trusting
                .resolve(&scene, "x", "/etc/hostname", Path::new("/etc/hostname"))
                .unwrap(),
            PathBuf::from("/etc/hostname")
        );
    }

    #[test]
    fn budget_refuses_with_the_figure() {
        let files = Files::new(
            Path::new("a.gltf"),
            &LoadOptions {
                max_memory: 1000,
                ..LoadOptions::default()
            },
        );
        assert!(
            files
                .charge(Path::new("a.gltf"), "x", 600, "vertices")
                .is_ok()
        );
        let e = files
            .charge(Path::new("a.gltf"), "x", 600, "vertices")
            .unwrap_err();
        assert!(
            e.message.contains("600 bytes") && e.message.contains("1.2 kB"),
            "{e}"
        );
    }

    #[test]
    fn process_limits_are_read() {
        let unlimited = "Limit                     Soft Limit           Hard Limit           Units
Max data size             unlimited            unlimited            bytes
Max stack size            8388608              unlimited            bytes
Max address space         unlimited            unlimited            bytes
";
        assert_eq!(process_limit(unlimited), None);
        let limited = unlimited.replace(
            "Max address space         unlimited",
            "Max address space         4294967296",
        );
        assert_eq!(process_limit(&limited), Some(4 << 30));
        let both = limited.replace(
            "Max data size             unlimited",
            "Max data size             1073741824",
        );
        assert_eq!(process_limit(&both), Some(1 << 30));
    }

    #[test]
    fn default_budget_is_half_the_machine() {
        let m = default_max_memory();
        assert!(m >= 256 << 20, "{m}");
    }
}

/// A `--max-memory` value that is not a byte count; each variant holds the text given.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum MemorySizeError {
    /// A unit other than K, M, G or T.
    UnknownUnit(String),
    /// No number before the unit.
    NotASize(String),
    /// Less than a byte, or more than a `u64` counts.
    OutOfRange(String),
}

impl fmt::Display for MemorySizeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            MemorySizeError::UnknownUnit(s) => write!(f, "'{s}': the unit must be K, M, G or T"),
            MemorySizeError::NotASize(s) => {
                write!(f, "'{s}' is not a size such as 8G, 512M or 1000000")
            }
            MemorySizeError::OutOfRange(s) => {
                write!(f, "'{s}' is not a size between 1 byte and 16 EiB")
            }
        }
    }
}

impl std::error::Error for MemorySizeError {}

/// A byte count as people write one: digits with an optional K, M, G or T (×1024ⁿ,
/// with or without `iB`/`B`), e.g. `8G`, `1.5G`, `512M`, `1000000` — the value of
/// `--max-memory`.
pub fn parse_memory_size(s: &str) -> Result<u64, MemorySizeError> {
    let t = s.trim();
    let (number, unit) = match t.char_indices().find(|(_, c)| c.is_ascii_alphabetic()) {
        Some((i, _)) => (
            &t[..i],
            t[i..].trim_end_matches(['B', 'b']).trim_end_matches('i'),
        ),
        None => (t, ""),
    };
    let shift = match unit.to_ascii_uppercase().as_str() {
        "" => 0,
        "K" => 10,
        "M" => 20,
        "G" => 30,
        "T" => 40,
        _ => return Err(MemorySizeError::UnknownUnit(s.to_string())),
    };
    let value: f64 = number
        .trim()
        .parse()
        .map_err(|_| MemorySizeError::NotASize(s.to_string()))?;
    let bytes = value * (1u64 << shift) as f64;
    if !(bytes.is_finite() && bytes >= 1.0 && bytes < u64::MAX as f64) {
        return Err(MemorySizeError::OutOfRange(s.to_string()));
    }
    Ok(bytes as u64)
}

#[cfg(test)]
mod size_tests {
    use super::parse_memory_size;

    #[test]
    fn memory_sizes() {
        assert_eq!(parse_memory_size("8G"), Ok(8 << 30));
        assert_eq!(parse_memory_size("512M"), Ok(512 << 20));
        assert_eq!(parse_memory_size("1.5g"), Ok(3 << 29));
        assert_eq!(parse_memory_size("64KiB"), Ok(64 << 10));
        assert_eq!(parse_memory_size("1000000"), Ok(1_000_000));
        for bad in ["", "G", "8X", "-1G", "0", "1e30T", "nan"] {
            assert!(parse_memory_size(bad).is_err(), "{bad}");
        }
        assert_eq!(
            parse_memory_size("8X").unwrap_err().to_string(),
            "'8X': the unit must be K, M, G or T"
        );
        assert_eq!(
            parse_memory_size("G").unwrap_err().to_string(),
            "'G' is not a size such as 8G, 512M or 1000000"
        );
        assert_eq!(
            parse_memory_size("0").unwrap_err().to_string(),
            "'0' is not a size between 1 byte and 16 EiB"
        );
    }
}
