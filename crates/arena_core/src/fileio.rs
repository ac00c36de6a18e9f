//! File access at the edges of the core. Output is atomic: a temporary file beside the
//! target, created exclusively (`create_new`, i.e. `O_EXCL`) under an unpredictable short
//! name, then renamed over the target, so a crash, an error or a planted symlink never
//! leaves a half-written or redirected file. Input must be a regular file of bounded size,
//! checked before it is opened, so a FIFO, a device or a directory is refused, not read.

use crate::error::{ArenaError, Result};
use std::collections::hash_map::RandomState;
use std::hash::{BuildHasher, Hasher};
use std::io::{ErrorKind, Read, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

static COUNTER: AtomicU64 = AtomicU64::new(0);

/// 64 unpredictable bits: `RandomState` is seeded from the OS per process; mix in a
/// counter and the clock so successive names differ.
fn random_u64() -> u64 {
    let mut h = RandomState::new().build_hasher();
    h.write_u64(COUNTER.fetch_add(1, Ordering::Relaxed));
    h.write_u128(
        std::time::SystemTime::now()
            .duration_since(std::time::UNIX_EPOCH)
            .map(|d| d.as_nanos())
            .unwrap_or(0),
    );
    h.write_u32(std::process::id());
    h.finish()
}

/// Create a new temporary file in `dir` exclusively, under a short random name (short so
/// a 255-byte target name still has a valid temporary beside it).
fn create_temp(dir: &Path) -> std::io::Result<(std::fs::File, PathBuf)> {
    for _ in 0..16 {
        let tmp = dir.join(format!(".arena-{:016x}.tmp", random_u64()));
        match std::fs::OpenOptions::new()
            .write(true)
            .create_new(true)
            .open(&tmp)
        {
            Ok(f) => return Ok((f, tmp)),
            Err(e) if e.kind() == ErrorKind::AlreadyExists => continue,
            Err(e) => return Err(e),
        }
    }
    Err(std::io::Error::new(
        ErrorKind::AlreadyExists,
        "no free temporary name",
    ))
}

/// Write `bytes` to `path` atomically (creating missing parent directories).
pub fn atomic_write(path: &Path, bytes: &[u8]) -> Result<()> {
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    if path.file_name().is_none() {
        return Err(ArenaError::io(path, "not a file path"));
    }
    if path.is_dir() {
        return Err(ArenaError::io(path, "is a directory, expected a file name"));
    }
    std::fs::create_dir_all(dir)
        .map_err(|e| ArenaError::io(dir, format!("cannot create directory: {e}")))?;
    let (mut f, tmp) =
        create_temp(dir).map_err(|e| ArenaError::io(path, format!("cannot write: {e}")))?;
    let result = (|| {
        f.write_all(bytes)?;
        f.sync_all()?;
        drop(f);
        std::fs::rename(&tmp, path)
    })();
    if let Err(e) = result {
        let _ = std::fs::remove_file(&tmp);
        return Err(ArenaError::io(path, format!("cannot write: {e}")));
    }
    Ok(())
}

/// What a path that is not a regular file is, for the error message.
fn describe_non_regular(ft: std::fs::FileType) -> &'static str {
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if ft.is_fifo() {
            return "is a FIFO (named pipe), not a regular file";
        }
        if ft.is_char_device() || ft.is_block_device() {
            return "is a device, not a regular file";
        }
        if ft.is_socket() {
            return "is a socket, not a regular file";
        }
    }
    if ft.is_dir() {
        "is a directory, not a regular file"
    } else {
        "is not a regular file"
    }
}

/// Read the regular file `path` (a `what`, for messages) of at most `max_bytes`. A missing
/// path, a directory, a FIFO, a device, a symlink loop or an oversized file is refused
/// with a message saying which, before any data is read.
pub fn read_regular(path: &Path, what: &str, max_bytes: u64) -> Result<Vec<u8>> {
    let meta = std::fs::metadata(path).map_err(|e| {
        let why = match e.kind() {
            ErrorKind::NotFound => "does not exist".to_string(),
            ErrorKind::PermissionDenied => "permission denied".to_string(),
            // ELOOP: 40 on Linux, 62 on macOS and the BSDs.
            _ if matches!(e.raw_os_error(), Some(40) | Some(62)) => {
                "is a symlink loop (too many levels of symbolic links)".to_string()
            }
            _ => e.to_string(),
        };
        ArenaError::io(path, format!("cannot read {what}: {why}"))
    })?;
    if !meta.is_file() {
        return Err(ArenaError::io(
            path,
            format!(
                "cannot read {what}: {}",
                describe_non_regular(meta.file_type())
            ),
        ));
    }
    if meta.len() > max_bytes {
        return Err(ArenaError::io(
            path,
            format!(
                "{what} is {} bytes, more than the {max_bytes} allowed",
                meta.len()
            ),
        ));
    }
    let f = std::fs::File::open(path)
        .map_err(|e| ArenaError::io(path, format!("cannot read {what}: {e}")))?;
    let mut bytes = Vec::with_capacity(meta.len() as usize);
    // `take` also bounds a file that grows after the size check.
    f.take(max_bytes.saturating_add(1))
        .read_to_end(&mut bytes)
        .map_err(|e| ArenaError::io(path, format!("cannot read {what}: {e}")))?;
    if bytes.len() as u64 > max_bytes {
        return Err(ArenaError::io(
            path,
            format!("{what} is more than the {max_bytes} bytes allowed"),
        ));
    }
    Ok(bytes)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn writes_and_leaves_no_temporary() {
        let dir = std::env::temp_dir().join(format!("arena_fileio_{}", std::process::id()));
        let p = dir.join("sub").join("x.txt");
        atomic_write(&p, b"hello").unwrap();
        assert_eq!(std::fs::read(&p).unwrap(), b"hello");
        let names: Vec<_> = std::fs::read_dir(p.parent().unwrap())
            .unwrap()
            .map(|e| e.unwrap().file_name())
            .collect();
        assert_eq!(names.len(), 1);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn temp_names_are_short_and_differ() {
        let dir = std::env::temp_dir().join(format!("arena_fileio_t_{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let (_a, pa) = create_temp(&dir).unwrap();
        let (_b, pb) = create_temp(&dir).unwrap();
        assert_ne!(pa, pb);
        assert!(pa.file_name().unwrap().len() < 32);
        // A 255-byte target name still works: the temporary name does not embed it.
        let long = dir.join("x".repeat(255));
        atomic_write(&long, b"ok").unwrap();
        assert!(atomic_write(&dir, b"no").is_err());
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn read_regular_refuses_non_files() {
        let dir = std::env::temp_dir().join(format!("arena_fileio_r_{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let e = read_regular(&dir, "map YAML", 10).unwrap_err().to_string();
        assert!(e.contains("directory"), "{e}");
        let e = read_regular(&dir.join("nope"), "map YAML", 10)
            .unwrap_err()
            .to_string();
        assert!(e.contains("does not exist"), "{e}");
        #[cfg(unix)]
        {
            let e = read_regular(Path::new("/dev/zero"), "map image", 10)
                .unwrap_err()
                .to_string();
            assert!(e.contains("device"), "{e}");
            let l = dir.join("loop");
            std::os::unix::fs::symlink(&l, &l).unwrap();
            let e = read_regular(&l, "map YAML", 10).unwrap_err().to_string();
            assert!(e.contains("symlink loop"), "{e}");
        }
        let f = dir.join("big");
        std::fs::write(&f, [0u8; 20]).unwrap();
        assert!(read_regular(&f, "x", 10)
            .unwrap_err()
            .to_string()
            .contains("20 bytes"));
        assert_eq!(read_regular(&f, "x", 20).unwrap().len(), 20);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
