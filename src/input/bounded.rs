//! A reader with limits: no line longer than [`Limits::line_bytes`], no more lines than
//! [`Limits::lines`]. Every line-based reader of the crate (CSV files, result and shard files,
//! the DOF table, Matrix Market files) reads through it, so that a file of one 3 GB line, or
//! of a billion empty lines, is refused with an error naming the line instead of exhausting
//! memory.
//!
//! Part of [`crate::input`] (layer 1): imports nothing outside it.

use std::io::{self, Read};

/// The limits of one reader.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Limits {
    /// The longest line, in bytes (the newline not counted).
    pub line_bytes: usize,
    /// The most lines.
    pub lines: u64,
    /// The most bytes in all.
    pub bytes: u64,
}

/// The limits of a text table: lines of at most 1 MiB (a row of tens of thousands of
/// numbers), at most 50 million lines and 4 GiB (a Matrix Market file of a model far beyond
/// a dense solve).
pub const TABLE: Limits = Limits {
    line_bytes: 1 << 20,
    lines: 50_000_000,
    bytes: 4 << 30,
};

/// The limits of a file read whole into memory (measured modes): lines of at most 1 MiB, at
/// most a million lines and 256 MiB.
pub const WHOLE: Limits = Limits {
    line_bytes: 1 << 20,
    lines: 1_000_000,
    bytes: 256 << 20,
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

impl<R: Read> Read for Bounded<R> {
    fn read(&mut self, buf: &mut [u8]) -> io::Result<usize> {
        let n = self.inner.read(buf)?;
        self.bytes += n as u64;
        if self.bytes > self.limits.bytes {
            return Err(refused(format!(
                "the file is larger than {} bytes, the most a file of this kind may have",
                self.limits.bytes
            )));
        }
        for &b in &buf[..n] {
            if b == b'\n' {
                self.newlines += 1;
                self.line_bytes = 0;
                if self.newlines > self.limits.lines {
                    return Err(refused(format!(
                        "the file has more than {} lines, the most a file of this kind may have",
                        self.limits.lines
                    )));
                }
            } else {
                self.line_bytes += 1;
                if self.line_bytes > self.limits.line_bytes {
                    return Err(refused(format!(
                        "line {} is longer than {} bytes, the most a line of this file may have",
                        self.newlines + 1,
                        self.limits.line_bytes
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
    };

    fn read(bytes: &[u8]) -> io::Result<Vec<u8>> {
        let mut out = Vec::new();
        Bounded::new(bytes, SMALL).read_to_end(&mut out)?;
        Ok(out)
    }

    #[test]
    fn a_long_line_or_too_many_lines_is_refused_naming_the_line() {
        assert_eq!(read(b"12345678\nab\n").unwrap(), b"12345678\nab\n");
        assert_eq!(
            read(b"ok\n123456789\n").unwrap_err().to_string(),
            "line 2 is longer than 8 bytes, the most a line of this file may have"
        );
        assert!(read(b"\n\n\n\n").is_ok());
        assert_eq!(
            read(b"\n\n\n\n\n").unwrap_err().to_string(),
            "the file has more than 4 lines, the most a file of this kind may have"
        );
        let wide = Limits {
            line_bytes: 100,
            lines: 100,
            bytes: 40,
        };
        let mut out = Vec::new();
        assert_eq!(
            Bounded::new(&[b'x'; 41][..], wide)
                .read_to_end(&mut out)
                .unwrap_err()
                .to_string(),
            "the file is larger than 40 bytes, the most a file of this kind may have"
        );
    }
}
