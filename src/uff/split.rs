//! The datasets of a universal file: `-1` delimiters, line terminators and binary payloads.
//!
//! A dataset is a line `-1` (right-justified in `I6`), a line with the dataset number, the
//! dataset's lines, and a closing `-1`. Lines end in LF or CRLF. A binary dataset (`58b`) has
//! a longer number line, `Format(I6,1A1,I6,I6,I12,I12,I6,I6,I12,I12)`: the number, `b`, the
//! byte order (1 little, 2 big endian), the floating-point format (2 = IEEE 754), the number
//! of ASCII lines that follow (11 for dataset 58) and the number of bytes after them; the raw
//! bytes follow the last ASCII line's terminator, and the closing `-1` follows the bytes,
//! directly or after a line terminator (both are found in practice). The byte count of the
//! header is not trusted (pyuff writes half the count for complex data): for dataset 58 the
//! payload length comes from record 7, and the layout after which the closing `-1` stands is
//! taken. The splitter knows no dataset's layout: its caller gives the lengths
//! ([`PayloadLengths`]; [`super::read`] asks [`super::function`] for dataset 58).
//!
//! Layout of the binary variant after the UC-SDRL description "The Binary 58 Universal File
//! Format" (reproduced in pyuff's `dataset_58.py`).

use std::borrow::Cow;

use super::error::{Located, Problem};
use super::fields::{Line, integer};

/// The most lines one dataset may hold (a dataset 58 of a million complex points has half a
/// million): the splitter keeps a dataset's lines, about 32 bytes each beside the file's
/// bytes, so this bounds its memory to about 130 MB whatever the file holds.
pub const MAX_DATASET_LINES: usize = 4_000_000;

/// The binary header of a `58b`-style dataset number line.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct BinaryHeader {
    /// Byte order of the payload.
    pub big_endian: bool,
    /// Number of bytes the header declares (informative only).
    pub declared_bytes: usize,
}

/// One dataset cut out of the file, not yet interpreted.
#[derive(Debug)]
pub(crate) struct RawDataset<'a> {
    /// 1-based index in the file.
    pub index: usize,
    /// Dataset number.
    pub kind: u32,
    /// Line of the dataset number.
    pub number_line: usize,
    /// The binary header, for a binary dataset.
    pub binary: Option<BinaryHeader>,
    /// The ASCII lines between the number line and the closing `-1` (for a binary dataset:
    /// the ASCII header lines).
    pub lines: Vec<Line<'a>>,
    /// The binary payload and the line it starts on.
    pub payload: Option<(&'a [u8], usize)>,
    /// Line of the closing `-1`.
    pub end_line: usize,
}

/// A splitting error: the record it happened in (index, dataset), if any.
pub(crate) type SplitError = (Option<(usize, u32)>, Located);

/// The candidate payload lengths (bytes) of a binary dataset of number `kind`, from its ASCII
/// header lines (`line`: the line after them, for errors), in the order to try them; `None`
/// to take the byte count the dataset's number line declares.
pub(crate) type PayloadLengths =
    fn(kind: u32, header: &[Line<'_>], line: usize) -> Result<Option<Vec<usize>>, Located>;

/// Walks a file dataset by dataset.
pub(crate) struct Splitter<'a> {
    bytes: &'a [u8],
    pos: usize,
    /// Number of the line starting at `pos`.
    line: usize,
    index: usize,
    failed: bool,
    lengths: PayloadLengths,
}

fn text(bytes: &[u8]) -> Cow<'_, str> {
    String::from_utf8_lossy(bytes)
}

fn is_delimiter(bytes: &[u8]) -> bool {
    text(bytes).trim() == "-1"
}

impl<'a> Splitter<'a> {
    /// The splitter of `bytes`, which asks `lengths` for the payload of a binary dataset.
    pub(crate) fn new(bytes: &'a [u8], lengths: PayloadLengths) -> Self {
        Splitter {
            // A UTF-8 byte-order mark, as some Windows programs write, is no content.
            bytes: bytes.strip_prefix(b"\xEF\xBB\xBF").unwrap_or(bytes),
            pos: 0,
            line: 1,
            index: 0,
            failed: false,
            lengths,
        }
    }

    /// The next line (number, content without terminator), if any.
    fn next_line(&mut self) -> Option<(usize, &'a [u8])> {
        if self.pos >= self.bytes.len() {
            return None;
        }
        let rest = &self.bytes[self.pos..];
        let (content, consumed) = match rest.iter().position(|&b| b == b'\n') {
            Some(nl) => (&rest[..nl], nl + 1),
            None => (rest, rest.len()),
        };
        let content = content.strip_suffix(b"\r").unwrap_or(content);
        let number = self.line;
        self.pos += consumed;
        self.line += 1;
        Some((number, content))
    }

    fn dataset(&mut self) -> Result<Option<RawDataset<'a>>, SplitError> {
        // Blank lines between datasets are tolerated.
        let (open_line, open) = loop {
            match self.next_line() {
                None => return Ok(None),
                Some((_, l)) if text(l).trim().is_empty() => continue,
                Some(found) => break found,
            }
        };
        if !is_delimiter(open) {
            let found = text(open).trim_end().chars().take(80).collect();
            return Err((
                None,
                Located::new(open_line, Problem::NotADelimiter { found }),
            ));
        }
        self.index += 1;
        let index = self.index;
        let Some((number_line, id)) = self.next_line() else {
            return Err((
                None,
                Located::new(
                    open_line,
                    Problem::Truncated {
                        what: "the dataset number",
                    },
                ),
            ));
        };
        let id = text(id);
        let trimmed = id.trim_start();
        let digits = trimmed.bytes().take_while(u8::is_ascii_digit).count();
        let kind = trimmed[..digits].parse::<u32>().map_err(|_| {
            let found = id.trim_end().chars().take(80).collect();
            (
                None,
                Located::new(number_line, Problem::NoDatasetNumber { found }),
            )
        })?;
        let in_record = |located: Located| (Some((index, kind)), located);
        let binary_flag = trimmed[digits..].starts_with(['b', 'B']);
        if !binary_flag {
            let mut lines = Vec::new();
            loop {
                let Some((number, content)) = self.next_line() else {
                    return Err(in_record(Located::new(
                        self.line.saturating_sub(1).max(number_line),
                        Problem::Unterminated,
                    )));
                };
                if is_delimiter(content) {
                    return Ok(Some(RawDataset {
                        index,
                        kind,
                        number_line,
                        binary: None,
                        lines,
                        payload: None,
                        end_line: number,
                    }));
                }
                if lines.len() == MAX_DATASET_LINES {
                    return Err(in_record(Located::new(
                        number,
                        Problem::TooManyLines {
                            limit: MAX_DATASET_LINES,
                        },
                    )));
                }
                lines.push(Line {
                    number,
                    text: text(content),
                });
            }
        }
        let (header, ascii_lines) =
            binary_header(&trimmed[digits + 1..], number_line).map_err(in_record)?;
        let mut lines = Vec::new();
        for _ in 0..ascii_lines {
            let Some((number, content)) = self.next_line() else {
                return Err(in_record(Located::new(
                    self.line.saturating_sub(1),
                    Problem::Truncated {
                        what: "the ASCII header lines of the binary dataset",
                    },
                )));
            };
            lines.push(Line {
                number,
                text: text(content),
            });
        }
        let lengths = (self.lengths)(kind, &lines, self.line)
            .map_err(in_record)?
            .unwrap_or_else(|| vec![header.declared_bytes]);
        let start_line = self.line;
        let (payload, end_line) = self.payload(&lengths).map_err(in_record)?;
        Ok(Some(RawDataset {
            index,
            kind,
            number_line,
            binary: Some(header),
            lines,
            payload: Some((payload, start_line)),
            end_line,
        }))
    }

    /// Takes the binary payload: the first of the candidate `lengths` after which the closing
    /// `-1` stands (after an optional line terminator). Returns it and the `-1`'s line.
    fn payload(&mut self, lengths: &[usize]) -> Result<(&'a [u8], usize), Located> {
        let rest = &self.bytes[self.pos.min(self.bytes.len())..];
        for &n in lengths {
            let Some(after) = rest.get(n..) else { continue };
            let after_nl = after
                .strip_prefix(b"\r\n")
                .or_else(|| after.strip_prefix(b"\n"))
                .unwrap_or(after);
            let skipped = after.len() - after_nl.len();
            let end = after_nl
                .iter()
                .position(|&b| b == b'\n')
                .unwrap_or(after_nl.len());
            if is_delimiter(&after_nl[..end]) {
                let payload = &rest[..n];
                let newlines = |b: &[u8]| b.iter().filter(|&&c| c == b'\n').count();
                let end_line = self.line + newlines(payload) + newlines(&after[..skipped]);
                let consumed = n + skipped + (end + 1).min(after_nl.len());
                self.pos += consumed;
                self.line = end_line + 1;
                return Ok((payload, end_line));
            }
        }
        let shortest = lengths.iter().copied().min().unwrap_or(0);
        if rest.len() < shortest {
            return Err(Located::new(
                self.line,
                Problem::TooFew {
                    what: "bytes of binary data",
                    expected: shortest,
                    found: rest.len(),
                },
            ));
        }
        let layouts = lengths
            .iter()
            .map(|n| n.to_string())
            .collect::<Vec<_>>()
            .join(", ");
        Err(Located::new(
            self.line,
            Problem::BinaryNotClosed {
                expected: lengths.first().copied().unwrap_or(0),
                layouts,
            },
        ))
    }
}

/// Parses the fields after `b` of a binary dataset number line; returns the header and the
/// number of ASCII lines that follow.
fn binary_header(fields: &str, line: usize) -> Result<(BinaryHeader, usize), Located> {
    let at = |p| Located::new(line, p);
    let tokens: Vec<&str> = fields.split_whitespace().collect();
    if tokens.len() < 4 {
        return Err(at(Problem::Truncated {
            what: "the byte order, floating-point format, line and byte counts of the binary header",
        }));
    }
    let order = integer(tokens[0], "byte ordering method").map_err(at)?;
    let big_endian = match order {
        1 => false,
        2 => true,
        v => {
            return Err(at(Problem::Code {
                field: "byte ordering method",
                value: v,
                allowed: "1 (little endian), 2 (big endian)",
            }));
        }
    };
    let format = integer(tokens[1], "floating-point format").map_err(at)?;
    if format != 2 {
        return Err(at(Problem::Code {
            field: "floating-point format",
            value: format,
            allowed: "2 (IEEE 754); 1 (DEC VMS) and 3 (IBM 370) are not read",
        }));
    }
    let count = |t: &str, field: &'static str| -> Result<usize, Located> {
        let v = integer(t, field).map_err(at)?;
        usize::try_from(v).map_err(|_| {
            at(Problem::Invalid {
                field,
                value: v.to_string(),
                allowed: "it must be >= 0",
            })
        })
    };
    let ascii_lines = count(tokens[2], "number of ASCII lines")?;
    let declared_bytes = count(tokens[3], "number of bytes")?;
    Ok((
        BinaryHeader {
            big_endian,
            declared_bytes,
        },
        ascii_lines,
    ))
}

impl<'a> Iterator for Splitter<'a> {
    type Item = Result<RawDataset<'a>, SplitError>;

    fn next(&mut self) -> Option<Self::Item> {
        if self.failed {
            return None;
        }
        let item = self.dataset().transpose();
        if matches!(item, Some(Err(_))) {
            self.failed = true;
        }
        item
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// No dataset's layout known: every payload as long as its header declares.
    fn declared(_: u32, _: &[Line<'_>], _: usize) -> Result<Option<Vec<usize>>, Located> {
        Ok(None)
    }

    fn kinds(bytes: &[u8]) -> Vec<(u32, usize, usize, usize)> {
        Splitter::new(bytes, declared)
            .map(|d| {
                let d = d.unwrap();
                (d.kind, d.number_line, d.lines.len(), d.end_line)
            })
            .collect()
    }

    #[test]
    fn splits_on_delimiters_with_lf_and_crlf() {
        let lf = b"    -1\n   164\na\nb\n    -1\n    -1\n  2412  \nx\n    -1\n";
        assert_eq!(kinds(lf), [(164, 2, 2, 5), (2412, 7, 1, 9)]);
        let crlf = String::from_utf8_lossy(lf).replace('\n', "\r\n");
        assert_eq!(kinds(crlf.as_bytes()), [(164, 2, 2, 5), (2412, 7, 1, 9)]);
        let bom = [&b"\xEF\xBB\xBF"[..], lf].concat();
        assert_eq!(kinds(&bom), [(164, 2, 2, 5), (2412, 7, 1, 9)]);
        // no final terminator, blank lines between datasets
        assert_eq!(
            kinds(b"\n  -1\n 15\n  -1\n\n  -1\n 18\n  -1"),
            [(15, 3, 0, 4), (18, 7, 0, 8)]
        );
    }

    #[test]
    fn a_dataset_of_millions_of_blank_lines_is_refused_not_held() {
        let mut bytes = b"    -1\n    15\n".to_vec();
        bytes.extend(std::iter::repeat_n(b'\n', MAX_DATASET_LINES + 10));
        bytes.extend(b"    -1\n");
        let e = Splitter::new(&bytes, declared).next().unwrap().unwrap_err();
        assert_eq!(e.0, Some((1, 15)));
        assert_eq!(e.1.line, MAX_DATASET_LINES + 3);
        assert!(matches!(e.1.problem, Problem::TooManyLines { .. }));
    }

    #[test]
    fn structural_errors_carry_lines() {
        let err = |b: &[u8]| Splitter::new(b, declared).find_map(Result::err).unwrap();
        let (rec, loc) = err(b"    -1\n    15\n 1 0 0 0 1 2 3\n");
        assert_eq!(rec, Some((1, 15)));
        assert_eq!(loc.problem, Problem::Unterminated);
        assert_eq!(loc.line, 3);
        let (rec, loc) = err(b"    -1\n    15\n    -1\ngarbage\n");
        assert_eq!(rec, None);
        assert_eq!(loc.line, 4);
        assert!(matches!(loc.problem, Problem::NotADelimiter { .. }));
        let (_, loc) = err(b"    -1\n  abc\n    -1\n");
        assert!(matches!(loc.problem, Problem::NoDatasetNumber { .. }));
    }

    #[test]
    fn unknown_binary_dataset_uses_declared_bytes() {
        let mut file = b"    -1\n  2414b     1     2           1           5\nhead\n".to_vec();
        file.extend_from_slice(&[0, b'\n', 2, 3, 4]);
        file.extend_from_slice(b"    -1\n    -1\n    15\n    -1\n");
        let sets: Vec<_> = Splitter::new(&file, declared).map(Result::unwrap).collect();
        assert_eq!(sets.len(), 2);
        assert_eq!(sets[0].payload.unwrap().0, &[0, b'\n', 2, 3, 4]);
        // the payload's newline counts: payload starts on line 4, `-1` on line 5
        assert_eq!(sets[0].end_line, 5);
        assert_eq!(sets[1].number_line, 7);
    }
}
