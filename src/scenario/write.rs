//! The one way this program writes a file: a temporary file created exclusively (never through
//! a symlink, never an existing file) in the target's folder by `tempfile`, synced, then moved
//! into place with `persist` (replace) or `persist_noclobber` (never replace, even in a race). A
//! crash leaves the old file or the new one, never half of either, and no planted link can
//! redirect the write.

use std::fs::File;
use std::io;
use std::path::Path;

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

/// The most read from standard input (`-`): the largest file any reader takes.
const MAX_STDIN_BYTES: u64 = 256 << 20;

/// Whether `path` is `-`, standard input (as a command line writes it).
#[must_use]
pub fn is_stdin(path: &Path) -> bool {
    path.as_os_str() == "-"
}

/// How a file is named in messages: `stdin` for `-`, else its path.
#[must_use]
pub fn label(path: &Path) -> String {
    if is_stdin(path) {
        "stdin".to_owned()
    } else {
        path.display().to_string()
    }
}

/// Standard input, read once (bounded) and kept, so every reader of `-` in this process sees
/// the same bytes (a preset is read to check it, then again to print it).
fn stdin_bytes() -> io::Result<Vec<u8>> {
    static READ: std::sync::OnceLock<Result<Vec<u8>, String>> = std::sync::OnceLock::new();
    let read = READ.get_or_init(|| {
        let mut bytes = Vec::new();
        io::Read::read_to_end(
            &mut io::Read::take(io::stdin().lock(), MAX_STDIN_BYTES + 1),
            &mut bytes,
        )
        .map_err(|e| e.to_string())?;
        Ok(bytes)
    });
    read.clone()
        .map_err(|e| io::Error::other(format!("standard input: {e}")))
}

/// Whether a file is reached through a symbolic link at its own name.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Links {
    /// Followed, as any program does (a preset or lesson linked into place).
    Follow,
    /// Refused: the file named, never what a link there points to (`serve`, issue 80: a link
    /// swapped in served `/etc/passwd`).
    Refuse,
}

/// Opens `path` for reading, only if it is a regular file, without ever blocking: opened
/// non-blocking (a FIFO does not wait for a writer) and checked on the open descriptor (no race
/// between the check and the open); with [`Links::Refuse`] a link at the name is refused.
///
/// # Errors
/// `InvalidInput` for a FIFO, a device, a folder, a socket or (refused) a link, saying which;
/// else what the system says.
#[cfg_attr(not(unix), allow(unused_variables))]
pub fn open_regular(path: &Path, links: Links) -> io::Result<File> {
    let mut options = std::fs::OpenOptions::new();
    options.read(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt as _;
        let nofollow = if links == Links::Refuse {
            libc::O_NOFOLLOW
        } else {
            0
        };
        options.custom_flags(libc::O_NONBLOCK | nofollow);
    }
    let file = options.open(path).map_err(|e| {
        #[cfg(unix)]
        if links == Links::Refuse && e.raw_os_error() == Some(libc::ELOOP) {
            return io::Error::new(
                io::ErrorKind::InvalidInput,
                "a symbolic link: only the file named is read, never what a link points to",
            );
        }
        e
    })?;
    let meta = file.metadata()?;
    if !meta.is_file() {
        return Err(io::Error::new(
            io::ErrorKind::InvalidInput,
            format!("not a regular file ({}); skipped", kind_of(&meta)),
        ));
    }
    Ok(file)
}

/// Whether a writer may replace `path`: nothing is there, or a regular file (issue 80, N8:
/// `--force` renamed a file over the device `/dev/full`). The one check of every writer.
///
/// # Errors
/// `InvalidInput` saying what is there instead: a link, a FIFO, a device, a socket, a folder.
pub fn replaceable(path: &Path) -> io::Result<()> {
    match std::fs::symlink_metadata(path) {
        Ok(meta) if !meta.is_file() => Err(io::Error::new(
            io::ErrorKind::InvalidInput,
            format!(
                "{} is {}: only a regular file is ever replaced, even with --force",
                path.display(),
                kind_of(&meta)
            ),
        )),
        _ => Ok(()),
    }
}

/// What a file that is not regular is, in words.
fn kind_of(meta: &std::fs::Metadata) -> &'static str {
    let t = meta.file_type();
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt as _;
        if t.is_fifo() {
            return "a FIFO";
        }
        if t.is_block_device() || t.is_char_device() {
            return "a device";
        }
        if t.is_socket() {
            return "a socket";
        }
    }
    if t.is_dir() {
        "a folder"
    } else if t.is_symlink() {
        "a symbolic link"
    } else {
        "not a regular file"
    }
}

/// [`read_bounded`] without the UTF-8 check (callers that locate an encoding error).
///
/// # Errors
/// As [`read_bounded`].
pub fn read_bounded_bytes(path: &Path, limit: u64) -> io::Result<Vec<u8>> {
    read_bounded_bytes_with(path, limit, Links::Follow)
}

/// [`read_bounded_bytes`], links followed or refused as `links` says.
///
/// # Errors
/// As [`read_bounded`].
pub fn read_bounded_bytes_with(path: &Path, limit: u64, links: Links) -> io::Result<Vec<u8>> {
    if is_stdin(path) {
        let bytes = stdin_bytes()?;
        if bytes.len() as u64 > limit {
            return Err(io::Error::new(
                io::ErrorKind::InvalidInput,
                format!("more than the {limit} bytes allowed"),
            ));
        }
        return Ok(bytes);
    }
    let file = open_regular(path, links)?;
    let meta = file.metadata()?;
    if meta.len() > limit {
        return Err(io::Error::new(
            io::ErrorKind::InvalidInput,
            format!("{} bytes, more than the {limit} allowed", meta.len()),
        ));
    }
    let mut bytes = Vec::new();
    io::Read::read_to_end(&mut io::Read::take(file, limit + 1), &mut bytes)?;
    if bytes.len() as u64 > limit {
        return Err(io::Error::new(
            io::ErrorKind::InvalidInput,
            format!("more than the {limit} bytes allowed"),
        ));
    }
    Ok(bytes)
}

/// Writes `bytes` to `path` atomically. With `replace = false` an existing `path` (file, link or
/// anything else) is an `AlreadyExists` error and is left untouched; with `replace = true` only
/// a regular file there is replaced (anything else is `InvalidInput`, untouched).
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
    // Even when asked to replace, only a regular file is.
    replaceable(path)?;
    // A randomly named file created with O_EXCL in the target's folder (tempfile): no planted
    // link can redirect it, and it is removed on every error path when dropped.
    let prefix = format!(".{}.", name.to_string_lossy());
    let mut builder = tempfile::Builder::new();
    builder.prefix(&prefix).suffix(".tmp");
    // Readable like any file the user makes (0666 less the umask), not tempfile's private 0600.
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt as _;
        builder.permissions(std::fs::Permissions::from_mode(0o666));
    }
    let mut tmp = builder.tempfile_in(dir)?;
    // A fault or a signal's watchdog that ends the process removes it (issue 56).
    #[cfg(not(target_arch = "wasm32"))]
    let _pending = crate::fault::pending(tmp.path());
    let value = {
        let mut out = io::BufWriter::new(tmp.as_file_mut());
        let value = fill(&mut out)?;
        io::Write::flush(&mut out)?;
        value
    };
    tmp.as_file().sync_all()?;
    if replace {
        // rename replaces the target itself, never what a link there points to.
        tmp.persist(path).map_err(|e| e.error)?;
    } else {
        // Fails if the target appeared meanwhile: no clobbering, even in a race.
        tmp.persist_noclobber(path).map_err(|e| e.error)?;
    }
    Ok(value)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::path::PathBuf;

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
        // A link planted at the target is neither written through nor replaced, even when
        // asked to replace (issue 80: only a regular file is ever replaced).
        let outside = d.join("outside");
        std::fs::write(&outside, b"keep").unwrap();
        let link = d.join("b.toml");
        std::os::unix::fs::symlink(&outside, &link).unwrap();
        assert!(write_atomic(&link, b"x", false).is_err());
        let e = write_atomic(&link, b"x", true).unwrap_err();
        assert_eq!(e.kind(), io::ErrorKind::InvalidInput);
        assert!(e.to_string().contains("a symbolic link"), "{e}");
        assert_eq!(std::fs::read(&outside).unwrap(), b"keep");
        assert!(
            std::fs::symlink_metadata(&link)
                .unwrap()
                .file_type()
                .is_symlink()
        );
        // Nor a FIFO, nor a folder.
        let fifo = d.join("f.toml");
        assert!(
            std::process::Command::new("mkfifo")
                .arg(&fifo)
                .status()
                .unwrap()
                .success()
        );
        let e = write_atomic(&fifo, b"x", true).unwrap_err();
        assert!(e.to_string().contains("a FIFO"), "{e}");
        let e = write_atomic(&d, b"x", true).unwrap_err();
        assert!(e.to_string().contains("a folder"), "{e}");
        // No temporary file is left behind.
        let left: Vec<_> = std::fs::read_dir(&d)
            .unwrap()
            .filter_map(Result::ok)
            .filter(|e| e.file_name().to_string_lossy().ends_with(".tmp"))
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

    #[cfg(unix)]
    #[test]
    fn files_get_the_usual_permissions_not_private_ones() {
        use std::os::unix::fs::PermissionsExt as _;
        let d = dir("mode");
        let target = d.join("m.csv");
        write_atomic(&target, b"x", false).unwrap();
        let mode = std::fs::metadata(&target).unwrap().permissions().mode() & 0o777;
        assert_eq!(
            mode & 0o044,
            0o044 & !umask(),
            "readable by others unless the umask says no: {mode:o}"
        );
        let _ = std::fs::remove_dir_all(&d);
    }

    /// The process's umask (read by setting and restoring it is racy; read it from /proc).
    #[cfg(unix)]
    fn umask() -> u32 {
        std::fs::read_to_string("/proc/self/status")
            .ok()
            .and_then(|s| {
                s.lines()
                    .find_map(|l| l.strip_prefix("Umask:"))
                    .and_then(|v| u32::from_str_radix(v.trim(), 8).ok())
            })
            .unwrap_or(0o022)
    }

    #[test]
    fn no_clobber_holds_under_a_race() {
        let d = dir("race");
        for round in 0..20 {
            let target = d.join(format!("r{round}.toml"));
            let winners: Vec<usize> = std::thread::scope(|s| {
                let handles: Vec<_> = (0..8)
                    .map(|i| {
                        let target = &target;
                        s.spawn(move || {
                            write_atomic(target, format!("writer {i}").as_bytes(), false)
                                .ok()
                                .map(|()| i)
                        })
                    })
                    .collect();
                handles
                    .into_iter()
                    .filter_map(|h| h.join().unwrap())
                    .collect()
            });
            assert_eq!(winners.len(), 1, "round {round}: {winners:?}");
            let text = std::fs::read_to_string(&target).unwrap();
            assert_eq!(text, format!("writer {}", winners[0]));
        }
        let left = std::fs::read_dir(&d).unwrap().count();
        assert_eq!(left, 20, "no temporary file is left behind");
        let _ = std::fs::remove_dir_all(&d);
    }
}

/// `YYYY-MM-DD-HHMMSS` (UTC) of `unix` seconds: file names that sort by time and read as dates.
#[must_use]
pub fn timestamp(unix: u64) -> String {
    // Days to civil date (H. Hinnant's algorithm), proleptic Gregorian.
    let days = i64::try_from(unix / 86_400).unwrap_or(0);
    let secs = unix % 86_400;
    let z = days + 719_468;
    let era = z.div_euclid(146_097);
    let doe = z.rem_euclid(146_097);
    let yoe = (doe - doe / 1460 + doe / 36_524 - doe / 146_096) / 365;
    let doy = doe - (365 * yoe + yoe / 4 - yoe / 100);
    let mp = (5 * doy + 2) / 153;
    let d = doy - (153 * mp + 2) / 5 + 1;
    let m = if mp < 10 { mp + 3 } else { mp - 9 };
    let y = yoe + era * 400 + i64::from(m <= 2);
    format!(
        "{y:04}-{m:02}-{d:02}-{:02}{:02}{:02}",
        secs / 3600,
        secs / 60 % 60,
        secs % 60
    )
}

/// A new file name in `dir`: `STEM-YYYY-MM-DD-HHMMSS.EXT`, with `-2`, `-3`… when taken.
#[must_use]
pub fn fresh_name(dir: &Path, stem: &str, ext: &str) -> std::path::PathBuf {
    let unix = std::time::SystemTime::now()
        .duration_since(std::time::UNIX_EPOCH)
        .map_or(0, |d| d.as_secs());
    let base = format!("{stem}-{}", timestamp(unix));
    let mut path = dir.join(format!("{base}.{ext}"));
    let mut n = 2;
    while std::fs::symlink_metadata(&path).is_ok() {
        path = dir.join(format!("{base}-{n}.{ext}"));
        n += 1;
    }
    path
}

#[cfg(test)]
mod name_tests {
    use super::*;

    #[test]
    fn timestamps_are_civil_dates() {
        assert_eq!(timestamp(0), "1970-01-01-000000");
        assert_eq!(timestamp(951_782_400), "2000-02-29-000000");
        assert_eq!(timestamp(1_795_425_135), "2026-11-23-091215");
    }
}
