//! The one way this program writes a file: a temporary file created exclusively (never through
//! a symlink, never an existing file) in the target's folder, synced, then moved into place —
//! without replacing an existing target unless asked. A crash leaves the old file or the new
//! one, never half of either, and no planted link can redirect the write.

use std::fs::{File, OpenOptions};
use std::io;
use std::path::{Path, PathBuf};

/// Largest preset, theme or lesson file read (they are a few kilobytes).
pub const MAX_CONFIG_BYTES: u64 = 1 << 20;

/// Reads a text file that must be a regular file of at most `limit` bytes: a FIFO, a device
/// (`/dev/zero`) or a folder is refused without being opened, so nothing blocks or fills
/// memory.
///
/// # Errors
/// `InvalidInput` for a file that is not regular or too large, else what the system says.
pub fn read_bounded(path: &Path, limit: u64) -> io::Result<String> {
    String::from_utf8(read_bounded_bytes(path, limit)?)
        .map_err(|e| io::Error::new(io::ErrorKind::InvalidData, e.utf8_error()))
}

/// [`read_bounded`] without the UTF-8 check (callers that locate an encoding error).
///
/// # Errors
/// As [`read_bounded`].
pub fn read_bounded_bytes(path: &Path, limit: u64) -> io::Result<Vec<u8>> {
    let meta = std::fs::metadata(path)?;
    if !meta.is_file() {
        return Err(io::Error::new(
            io::ErrorKind::InvalidInput,
            "not a regular file (a FIFO, a device or a folder); skipped",
        ));
    }
    if meta.len() > limit {
        return Err(io::Error::new(
            io::ErrorKind::InvalidInput,
            format!("{} bytes, more than the {limit} allowed", meta.len()),
        ));
    }
    let mut bytes = Vec::new();
    io::Read::read_to_end(
        &mut io::Read::take(File::open(path)?, limit + 1),
        &mut bytes,
    )?;
    if bytes.len() as u64 > limit {
        return Err(io::Error::new(
            io::ErrorKind::InvalidInput,
            format!("more than the {limit} bytes allowed"),
        ));
    }
    Ok(bytes)
}

/// Writes `bytes` to `path` atomically. With `replace = false` an existing `path` (file, link or
/// anything else) is an `AlreadyExists` error and is left untouched.
///
/// # Errors
/// `AlreadyExists`, or what the system says; the temporary file is removed on every error.
pub fn write_atomic(path: &Path, bytes: &[u8], replace: bool) -> io::Result<()> {
    write_atomic_with(path, replace, &mut |w| w.write_all(bytes))
}

/// [`write_atomic`] for content produced by `fill` as it goes (streamed through a buffer into
/// the temporary file, never held whole in memory); returns what `fill` returned.
///
/// # Errors
/// As [`write_atomic`], and `fill`'s own errors.
pub fn write_atomic_with<T>(
    path: &Path,
    replace: bool,
    fill: &mut dyn FnMut(&mut dyn io::Write) -> io::Result<T>,
) -> io::Result<T> {
    let dir = path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    let name = path
        .file_name()
        .ok_or_else(|| io::Error::new(io::ErrorKind::InvalidInput, "not a file name"))?;
    if !replace && std::fs::symlink_metadata(path).is_ok() {
        return Err(io::Error::new(
            io::ErrorKind::AlreadyExists,
            format!("{} exists", path.display()),
        ));
    }
    let (tmp, file) = create_temporary(dir, &name.to_string_lossy())?;
    let result = (|| {
        let mut out = io::BufWriter::new(file);
        let value = fill(&mut out)?;
        let file = out.into_inner().map_err(io::IntoInnerError::into_error)?;
        file.sync_all()?;
        drop(file);
        if replace {
            // rename replaces the target itself, never what a link there points to.
            std::fs::rename(&tmp, path)?;
        } else {
            // A hard link fails if the target appeared meanwhile: no clobbering, even in a race.
            std::fs::hard_link(&tmp, path)?;
            std::fs::remove_file(&tmp)?;
        }
        Ok(value)
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}

/// A new file `.NAME.tmp-PID-N` in `dir`, created with `O_CREAT | O_EXCL` (an existing file or
/// a planted symlink at that name makes it try the next `N`).
fn create_temporary(dir: &Path, name: &str) -> io::Result<(PathBuf, File)> {
    let pid = std::process::id();
    let seed = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.subsec_nanos());
    for n in 0..64u32 {
        let tmp = dir.join(format!(".{name}.tmp-{pid}-{}", seed.wrapping_add(n)));
        match OpenOptions::new().write(true).create_new(true).open(&tmp) {
            Ok(f) => return Ok((tmp, f)),
            Err(e) if e.kind() == io::ErrorKind::AlreadyExists => {}
            Err(e) => return Err(e),
        }
    }
    Err(io::Error::new(
        io::ErrorKind::AlreadyExists,
        format!("no free temporary name in {}", dir.display()),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dir(name: &str) -> PathBuf {
        let d =
            std::env::temp_dir().join(format!("rattleback-write-{name}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        d
    }

    #[test]
    fn never_clobbers_unless_asked_and_never_follows_a_link() {
        let d = dir("clobber");
        let target = d.join("a.toml");
        write_atomic(&target, b"one", false).unwrap();
        let e = write_atomic(&target, b"two", false).unwrap_err();
        assert_eq!(e.kind(), io::ErrorKind::AlreadyExists);
        assert_eq!(std::fs::read(&target).unwrap(), b"one");
        write_atomic(&target, b"two", true).unwrap();
        assert_eq!(std::fs::read(&target).unwrap(), b"two");
        // A link planted at the target is replaced, not written through.
        let outside = d.join("outside");
        std::fs::write(&outside, b"keep").unwrap();
        let link = d.join("b.toml");
        std::os::unix::fs::symlink(&outside, &link).unwrap();
        assert!(write_atomic(&link, b"x", false).is_err());
        write_atomic(&link, b"x", true).unwrap();
        assert_eq!(std::fs::read(&outside).unwrap(), b"keep");
        assert!(
            !std::fs::symlink_metadata(&link)
                .unwrap()
                .file_type()
                .is_symlink()
        );
        // No temporary file is left behind.
        let left: Vec<_> = std::fs::read_dir(&d)
            .unwrap()
            .filter_map(Result::ok)
            .filter(|e| e.file_name().to_string_lossy().contains(".tmp-"))
            .collect();
        assert!(left.is_empty());
        let _ = std::fs::remove_dir_all(&d);
    }

    #[test]
    fn a_planted_link_at_a_temporary_name_is_not_followed() {
        let d = dir("planted");
        let outside = d.join("outside");
        std::fs::write(&outside, b"keep").unwrap();
        // Plant links at every name this process could try for the next second.
        let pid = std::process::id();
        for n in 0..1000u32 {
            let _ = std::os::unix::fs::symlink(&outside, d.join(format!(".c.toml.tmp-{pid}-{n}")));
        }
        write_atomic(&d.join("c.toml"), b"new", false).unwrap();
        assert_eq!(std::fs::read(&outside).unwrap(), b"keep");
        assert_eq!(std::fs::read(d.join("c.toml")).unwrap(), b"new");
        let _ = std::fs::remove_dir_all(&d);
    }
}
