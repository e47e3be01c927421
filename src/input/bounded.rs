//! A reader with limits: no line longer than [`Limits::line_bytes`], no more lines than
//! [`Limits::lines`]. Every line-based reader of the crate (CSV files, result and shard files,
//! the DOF table, Matrix Market files) reads through it, so that a file of one 3 GB line, or
//! of a billion empty lines, is refused with an error naming the line instead of exhausting
//! memory.
//!
//! A file read whole into memory goes through [`read_path`], with the limits of its kind
//! ([`TOML`], [`UFF`], [`WHOLE`]): a regular file larger than its limit is refused before a
//! byte is read, and a pipe or a device (`/dev/zero`) is read only until it passes a limit.
//! docs/security.md lists every limit and the test that holds it.
//!
//! Part of [`crate::input`] (layer 1): imports nothing outside it.

use std::io::{self, Read};
use std::path::Path;

/// The limits of one reader.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Limits {
    /// The longest line, in bytes (the newline not counted).
    pub line_bytes: usize,
    /// The most lines.
    pub lines: u64,
    /// The most bytes in all.
    pub bytes: u64,
    /// The kind of file, as a refusal names it (`a TOML input file`).
    pub what: &'static str,
}

/// The limits of a text table: lines of at most 1 MiB (a row of tens of thousands of
/// numbers), at most 50 million lines and 4 GiB (a Matrix Market file of a model far beyond
/// a dense solve).
pub const TABLE: Limits = Limits {
    line_bytes: 1 << 20,
    lines: 50_000_000,
    bytes: 4 << 30,
    what: "a text table",
};

/// The limits of a file read whole into memory (measured modes): lines of at most 1 MiB, at
/// most a million lines and 256 MiB.
pub const WHOLE: Limits = Limits {
    line_bytes: 1 << 20,
    lines: 1_000_000,
    bytes: 256 << 20,
    what: "a measured-modes file",
};

/// The limits of a TOML input file (model, lap, study, levels, solid specimen), read whole:
/// lines of at most 1 MiB, at most a million lines and 16 MiB. The largest written by hand or
/// by `export` and `solid` hold a few hundred tables (tens of KB); the matrices of a large
/// model are files of their own, read as [`TABLE`]s.
pub const TOML: Limits = Limits {
    line_bytes: 1 << 20,
    lines: 1_000_000,
    bytes: 16 << 20,
    what: "a TOML input file",
};

/// The limits of a universal file (`--frf`, `--geometry`, a level's FRFs), read whole: 1 GiB
/// (a thousand ASCII FRFs of 32768 lines are about 0.86 GB). Lines are not bounded here: a
/// binary payload (58b) has none, and the splitter bounds the lines of each dataset
/// (`uff::split::MAX_DATASET_LINES`).
pub const UFF: Limits = Limits {
    line_bytes: 1 << 30,
    lines: 1 << 30,
    bytes: 1 << 30,
    what: "a universal file",
};

/// `inner` read with `limits`: a read that would pass a limit fails with
/// [`io::ErrorKind::InvalidData`] and a message naming the line and the limit.
#[derive(Debug)]
pub struct Bounded<R> {
    inner: R,
    limits: Limits,
    /// Bytes of the current line so far.
    line_bytes: usize,
    /// Newlines so far.
    newlines: u64,
    /// Bytes so far.
    bytes: u64,
}

impl<R> Bounded<R> {
    /// `inner` with `limits`.
    pub fn new(inner: R, limits: Limits) -> Self {
        Bounded {
            inner,
            limits,
            line_bytes: 0,
            newlines: 0,
            bytes: 0,
        }
    }
}

/// The error of a read past a limit.
fn refused(message: String) -> io::Error {
    io::Error::new(io::ErrorKind::InvalidData, message)
}

/// The error of a file larger than `limits.bytes`.
fn too_large(limits: &Limits) -> io::Error {
    let mib = if limits.bytes >= 1 << 20 {
        format!(" ({} MiB)", limits.bytes >> 20)
    } else {
        String::new()
    };
    refused(format!(
        "the file is larger than {} bytes{mib}, the most {} may have",
        limits.bytes, limits.what
    ))
}

/// The whole of `reader` within `limits`, its buffer never larger than `limits.bytes` and
/// a read block: a stream of unknown size (a pipe, `/dev/zero`) costs at most the limit in
/// memory, where `read_to_end`'s doubling would reserve twice that.
pub fn read_all<R: Read>(reader: R, limits: Limits) -> io::Result<Vec<u8>> {
    read_within(Bounded::new(reader, limits), Vec::new())
}

/// Reads `reader` to its end into `bytes`, growing the buffer by doubling but never past its
/// byte limit and one block.
fn read_within<R: Read>(mut reader: Bounded<R>, mut bytes: Vec<u8>) -> io::Result<Vec<u8>> {
    const BLOCK: usize = 1 << 16;
    let most = usize::try_from(reader.limits.bytes)
        .unwrap_or(usize::MAX)
        .saturating_add(BLOCK);
    loop {
        if bytes.len() == bytes.capacity() {
            // Double, but not past the limit (a block at least, for the read that passes it).
            let room = most.saturating_sub(bytes.capacity()).max(BLOCK);
            bytes.reserve_exact(bytes.capacity().max(BLOCK).min(room));
        }
        let len = bytes.len();
        let room = (bytes.capacity() - len).min(BLOCK);
        bytes.resize(len + room, 0);
        match reader.read(&mut bytes[len..]) {
            Ok(0) => {
                bytes.truncate(len);
                return Ok(bytes);
            }
            Ok(n) => bytes.truncate(len + n),
            Err(e) if e.kind() == io::ErrorKind::Interrupted => bytes.truncate(len),
            Err(e) => return Err(e),
        }
    }
}

/// The file at `path`, opened to be read within `limits`: a regular file whose size passes
/// `limits.bytes` is refused before a byte is read (a sparse file of terabytes costs nothing);
/// any other file (a pipe, a device such as `/dev/zero`) is read until it passes a limit.
pub fn open(path: &Path, limits: Limits) -> io::Result<Bounded<std::fs::File>> {
    let file = std::fs::File::open(path)?;
    if file.metadata()?.len() > limits.bytes {
        return Err(too_large(&limits));
    }
    Ok(Bounded::new(file, limits))
}

/// The whole file at `path` within `limits` ([`open`]): its memory stays within the limit
/// whatever the file holds.
pub fn read_path(path: &Path, limits: Limits) -> io::Result<Vec<u8>> {
    let reader = open(path, limits)?;
    let size = reader.inner.metadata()?.len();
    read_within(reader, Vec::with_capacity(size as usize))
}

impl<R: Read> Read for Bounded<R> {
    fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
        let n = self.inner.read(buf)?;
        self.bytes += n as u64;
        if self.bytes > self.limits.bytes {
            return Err(too_large(&self.limits));
        }
        for &b in &buf[..n] {
            if b == b'\n' {
                self.newlines += 1;
                self.line_bytes = 0;
                if self.newlines > self.limits.lines {
                    return Err(refused(format!(
                        "the file has more than {} lines, the most {} may have",
                        self.limits.lines, self.limits.what
                    )));
                }
            } else {
                self.line_bytes += 1;
                if self.line_bytes > self.limits.line_bytes {
                    return Err(refused(format!(
                        "line {} is longer than {} bytes, the most a line of {} may have",
                        self.newlines + 1,
                        self.limits.line_bytes,
                        self.limits.what
                    )));
                }
            }
        }
        Ok(n)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const SMALL: Limits = Limits {
        line_bytes: 8,
        lines: 4,
        bytes: 40,
        what: "a small file",
    };

    fn read(bytes: &[u8]) -> io::Result<Vec<u8>> {
        let mut out = Vec::new();
        Bounded::new(bytes, SMALL).read_to_end(&mut out)?;
        Ok(out)
    }

    #[test]
    fn a_stream_of_unknown_size_costs_at_most_its_limit_in_memory() {
        let limits = Limits {
            line_bytes: usize::MAX,
            lines: u64::MAX,
            bytes: 3 << 20,
            what: "a stream",
        };
        // Exactly the limit: read whole, in a buffer not above the limit and a block (where
        // doubling from empty would reserve 4 MiB).
        let stream = io::repeat(7).take(limits.bytes);
        let bytes = read_all(stream, limits).unwrap();
        assert_eq!(bytes.len() as u64, limits.bytes);
        assert!(
            bytes.capacity() as u64 <= limits.bytes + (1 << 16),
            "{}",
            bytes.capacity()
        );
        // An endless one (`/dev/zero`): refused once past the limit.
        let err = read_all(io::repeat(0), limits).unwrap_err();
        assert!(
            err.to_string().contains("larger than 3145728 bytes"),
            "{err}"
        );
    }

    #[test]
    fn a_long_line_or_too_many_lines_is_refused_naming_the_line() {
        assert_eq!(read(b"12345678\nab\n").unwrap(), b"12345678\nab\n");
        assert_eq!(
            read(b"ok\n123456789\n").unwrap_err().to_string(),
            "line 2 is longer than 8 bytes, the most a line of a small file may have"
        );
        assert!(read(b"\n\n\n\n").is_ok());
        assert_eq!(
            read(b"\n\n\n\n\n").unwrap_err().to_string(),
            "the file has more than 4 lines, the most a small file may have"
        );
        let wide = Limits {
            line_bytes: 100,
            lines: 100,
            bytes: 40,
            what: "a wide file",
        };
        let mut out = Vec::new();
        assert_eq!(
            Bounded::new(&[b'x'; 41][..], wide)
                .read_to_end(&mut out)
                .unwrap_err()
                .to_string(),
            "the file is larger than 40 bytes, the most a wide file may have"
        );
    }

    #[test]
    fn a_file_past_its_limit_is_refused_before_it_is_read() {
        let path = std::env::temp_dir().join(format!("jointid-bounded-{}", std::process::id()));
        let file = std::fs::File::create(&path).unwrap();
        file.set_len(TOML.bytes + 1).unwrap();
        assert_eq!(
            read_path(&path, TOML).unwrap_err().to_string(),
            "the file is larger than 16777216 bytes (16 MiB), the most a TOML input file may have"
        );
        file.set_len(3).unwrap();
        assert_eq!(read_path(&path, TOML).unwrap(), [0, 0, 0]);
        std::fs::remove_file(&path).unwrap();
        // A device that never ends stops at the first limit it passes.
        if Path::new("/dev/zero").exists() {
            assert_eq!(
                read_path(Path::new("/dev/zero"), TOML)
                    .unwrap_err()
                    .to_string(),
                "line 1 is longer than 1048576 bytes, the most a line of a TOML input file may have"
            );
        }
        assert_eq!(read_all(&b"ab\ncd"[..], TOML).unwrap(), b"ab\ncd".to_vec());
    }
}
