//! Bounded reading of input files (study and case files, Gmsh meshes).
//!
//! Before a byte is read, the path must name a **regular file** (a device such as `/dev/zero`
//! or `/dev/urandom`, a directory or a named pipe is refused: they have no end or block) of at
//! most [`max_input_bytes`] bytes. The limit comes from the memory guard of the studies
//! (`alea_study::limits`): a reader holds the file's bytes and what it builds from them (a few
//! times the bytes for a mesh), so a file larger than a quarter of the available memory cannot
//! be read safely and is refused at once, with its size and the limit in the message. The
//! check is made again on the opened file (it could have been replaced in between), and at most
//! limit + 1 bytes are ever read (a file that grows while read is refused too).

use std::fs::File;
use std::io::Read;
use std::path::Path;

/// Bytes of memory available to this process: `MemAvailable` of `/proc/meminfo` (Linux), else
/// 8 GiB.
pub fn available_memory() -> u64 {
    std::fs::read_to_string("/proc/meminfo")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("MemAvailable:"))
                .and_then(|l| l.split_whitespace().nth(1))
                .and_then(|v| v.parse::<u64>().ok())
        })
        .map_or(8 << 30, |kb| kb * 1024)
}

/// The largest input file read: a quarter of [`available_memory`].
pub fn max_input_bytes() -> u64 {
    available_memory() / 4
}

/// Why an input file is not read: an [`std::io::ErrorKind::InvalidInput`] error whose message
/// says what the path is or how large it is.
fn refused(message: String) -> std::io::Error {
    std::io::Error::new(std::io::ErrorKind::InvalidInput, message)
}

/// The kind of a file that is not a regular file, for messages.
fn kind_of(meta: &std::fs::Metadata) -> &'static str {
    let t = meta.file_type();
    if t.is_dir() {
        return "a directory";
    }
    #[cfg(unix)]
    {
        use std::os::unix::fs::FileTypeExt;
        if t.is_char_device() || t.is_block_device() {
            return "a device";
        }
        if t.is_fifo() {
            return "a named pipe";
        }
        if t.is_socket() {
            return "a socket";
        }
    }
    "not a regular file"
}

fn check(meta: &std::fs::Metadata, max: u64) -> std::io::Result<()> {
    if !meta.is_file() {
        return Err(refused(format!(
            "not a regular file ({}); an input must be a file on disk",
            kind_of(meta)
        )));
    }
    if meta.len() > max {
        return Err(refused(too_large(meta.len(), max)));
    }
    Ok(())
}

fn too_large(len: u64, max: u64) -> String {
    format!(
        "{len} bytes, more than the {max} bytes an input file may have here (a quarter of the \
         available memory)"
    )
}

/// Reads the input file `path` if it is a regular file of at most `max` bytes.
///
/// # Errors
/// The I/O error of the file system (missing file, permissions), or an
/// [`std::io::ErrorKind::InvalidInput`] error for a path that is not a regular file or is
/// larger than `max` bytes; nothing is read then.
pub fn read_bounded(path: &Path, max: u64) -> std::io::Result<Vec<u8>> {
    // `stat` first: opening a named pipe would block until a writer comes.
    check(&std::fs::metadata(path)?, max)?;
    let file = File::open(path)?;
    let meta = file.metadata()?;
    check(&meta, max)?;
    let mut bytes = Vec::with_capacity(meta.len() as usize);
    file.take(max + 1).read_to_end(&mut bytes)?;
    if bytes.len() as u64 > max {
        return Err(refused(too_large(bytes.len() as u64, max)));
    }
    Ok(bytes)
}

/// [`read_bounded`] with the limit [`max_input_bytes`].
///
/// # Errors
/// As [`read_bounded`].
pub fn read_input(path: &Path) -> std::io::Result<Vec<u8>> {
    read_bounded(path, max_input_bytes())
}

/// True if `e` is a refusal of [`read_bounded`] (not a regular file, too large), an input
/// error rather than a file-system failure.
pub fn is_refusal(e: &std::io::Error) -> bool {
    e.kind() == std::io::ErrorKind::InvalidInput
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn devices_directories_and_large_files_are_refused_before_reading() {
        let d = std::env::temp_dir().join(format!("alea-input-{}", std::process::id()));
        std::fs::create_dir_all(&d).unwrap();
        let f = d.join("ten.txt");
        std::fs::write(&f, b"0123456789").unwrap();
        assert_eq!(read_bounded(&f, 10).unwrap(), b"0123456789");
        let e = read_bounded(&f, 9).unwrap_err();
        assert!(
            is_refusal(&e) && e.to_string().starts_with("10 bytes, more than the 9"),
            "{e}"
        );
        let e = read_bounded(&d, 1 << 20).unwrap_err();
        assert!(
            is_refusal(&e) && e.to_string().contains("a directory"),
            "{e}"
        );
        #[cfg(unix)]
        for dev in ["/dev/zero", "/dev/urandom", "/dev/null"] {
            let t = std::time::Instant::now();
            let e = read_bounded(Path::new(dev), 1 << 40).unwrap_err();
            assert!(
                is_refusal(&e) && e.to_string().contains("a device"),
                "{dev}: {e}"
            );
            assert!(t.elapsed().as_secs_f64() < 0.5, "{dev} refused at once");
        }
        let e = read_bounded(&d.join("missing"), 10).unwrap_err();
        assert_eq!(e.kind(), std::io::ErrorKind::NotFound);
        assert!(max_input_bytes() > 0 && max_input_bytes() <= available_memory());
    }
}
