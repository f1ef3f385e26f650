//! Named pipes: how a caller talks to a program that reads commands from a path
//! (`perf record --control fifo:CTL,ACK`).

use std::path::Path;

/// Creates a named pipe at `path` (owner read and write only).
pub fn make_fifo(path: &Path) -> std::io::Result<()> {
    let c_path = std::ffi::CString::new(path.as_os_str().as_encoded_bytes())
        .map_err(|_| std::io::Error::other("a path with a NUL byte"))?;
    // SAFETY: a valid NUL-terminated path; mkfifo has no other memory effects.
    if unsafe { libc::mkfifo(c_path.as_ptr(), 0o600) } != 0 {
        return Err(std::io::Error::last_os_error());
    }
    Ok(())
}

/// Opens a named pipe for reading and writing: on Linux this never blocks waiting for
/// the other side, so a program that dies before opening its end cannot hang us.
pub fn open_fifo(path: &Path) -> std::io::Result<std::fs::File> {
    std::fs::OpenOptions::new()
        .read(true)
        .write(true)
        .open(path)
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::io::{BufRead, Write};

    #[test]
    fn a_fifo_carries_a_line_without_blocking_on_open() {
        let dir = std::env::temp_dir().join(format!("launch-fifo-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("ctl");
        make_fifo(&path).unwrap();
        let mut w = open_fifo(&path).unwrap();
        let r = open_fifo(&path).unwrap();
        w.write_all(b"enable\n").unwrap();
        let mut line = String::new();
        std::io::BufReader::new(r).read_line(&mut line).unwrap();
        assert_eq!(line, "enable\n");
        assert!(make_fifo(&path).is_err(), "exists already");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
