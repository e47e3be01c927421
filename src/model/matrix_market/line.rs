//! The lines of a Matrix Market file: the header, the size line and the entry lines, each
//! with the message that says what is wrong and what is allowed; and the fast path for the
//! entry lines of a large file.
//!
//! The fast path ([`fast_entry`]) reads the bytes of an entry line as they are in the read
//! buffer: two unsigned decimal indices and a value, separated by spaces or tabs, with no
//! allocation and no second pass over the line. It takes only what the general path
//! ([`entry`]) takes in the same way (ASCII digits, indices within the size, the lower
//! triangle of a `symmetric` file, a finite value by `str::parse::<f64>`), and hands every
//! other line (comments, blank lines, a sign before an index, other whitespace, any error)
//! to the general path, which gives the message. A file is therefore read the same with or
//! without the fast path: the tests of the module check both on the same lines.
//!
//! Where the time goes (the 23,958-DOF lap's K, 22 MB, 891,000 entry lines, release build):
//! the general path took 0.18-0.25 s (a `String` per line and a `Vec` of its fields), the
//! fast path takes the time of `str::parse::<f64>` (std's Eisel-Lemire) and little more.

/// What the header line may be.
pub const HEADER_ALLOWED: &str = "the first line must be `%%MatrixMarket matrix coordinate real symmetric` (or `integer` for `real`, `general` for `symmetric`)";

/// The largest matrix read, in rows (a model far beyond what the solvers handle).
pub const MAX_SIZE: usize = 10_000_000;

/// Whether the header line declares a `general` matrix (else `symmetric`); the message when
/// it is not a header this reader takes.
pub fn is_general(header: &str) -> Result<bool, String> {
    let words: Vec<String> = header
        .split_whitespace()
        .map(str::to_ascii_lowercase)
        .collect();
    match words.iter().map(String::as_str).collect::<Vec<_>>()[..] {
        [
            "%%matrixmarket",
            "matrix",
            "coordinate",
            "real" | "integer",
            "symmetric",
        ] => Ok(false),
        [
            "%%matrixmarket",
            "matrix",
            "coordinate",
            "real" | "integer",
            "general",
        ] => Ok(true),
        [
            "%%matrixmarket",
            "matrix",
            "coordinate",
            "pattern",
            "symmetric" | "general",
        ] => Err(format!(
            "header `{}` is invalid: a `pattern` file has no values (a stiffness or mass matrix needs them); {HEADER_ALLOWED}",
            header.trim()
        )),
        _ => Err(format!(
            "header `{}` is invalid: {HEADER_ALLOWED}",
            header.trim()
        )),
    }
}

/// The size N and the declared number of entries of the size line `t` (trimmed, not a
/// comment); the message when it is not `N N entries`.
pub fn size_line(t: &str) -> Result<(usize, usize), String> {
    let fields: Vec<&str> = t.split_whitespace().collect();
    let parsed: Vec<Option<usize>> = fields.iter().map(|f| f.parse().ok()).collect();
    match parsed[..] {
        [Some(r), Some(c), Some(_)] if r == c && r > MAX_SIZE => Err(format!(
            "size `{t}` is invalid: the matrix is {r} x {c}; at most {MAX_SIZE} rows are read"
        )),
        [Some(r), Some(c), Some(nnz)] if r == c && r > 0 => Ok((r, nnz)),
        [Some(r), Some(c), Some(_)] if r != c => Err(format!(
            "size `{t}` is invalid: the matrix is {r} x {c}; it must be square"
        )),
        _ => Err(format!(
            "size line `{t}` is invalid: it must be `rows columns entries`, three integers, rows = columns > 0"
        )),
    }
}

/// The entry (row, column, value), 0-based, of the entry line `t` (trimmed) of a matrix of
/// size `size` (`general`: any triangle, else the lower one); the message when it is invalid.
pub fn entry(t: &str, size: usize, general: bool) -> Result<(usize, usize, f64), String> {
    let fields: Vec<&str> = t.split_whitespace().collect();
    let [ri, ci, vi] = fields[..] else {
        return Err(format!(
            "entry `{t}` is invalid: it must be `row column value`"
        ));
    };
    let index = |text: &str, name: &str| -> Result<usize, String> {
        match text.parse::<usize>() {
            Ok(k) if (1..=size).contains(&k) => Ok(k - 1),
            _ => Err(format!(
                "{name} = `{text}` is invalid: it must be an integer from 1 to {size}"
            )),
        }
    };
    let (i, j) = (index(ri, "row")?, index(ci, "column")?);
    let value = match vi.parse::<f64>() {
        Ok(v) if v.is_finite() => v,
        _ => {
            return Err(format!(
                "value = `{vi}` at ({ri}, {ci}) is invalid: it must be a finite number"
            ));
        }
    };
    if !general && i < j {
        return Err(format!(
            "entry ({ri}, {ci}) is above the diagonal: a `symmetric` file stores the lower triangle only (row >= column)"
        ));
    }
    Ok((i, j, value))
}

/// Spaces and tabs: the separators of the fast path.
fn blank(b: u8) -> bool {
    b == b' ' || b == b'\t'
}

/// Skips spaces and tabs from `at`.
fn skip_blanks(line: &[u8], mut at: usize) -> usize {
    while at < line.len() && blank(line[at]) {
        at += 1;
    }
    at
}

/// The unsigned decimal at `at` (1 to 19 digits) and where it ends; `None` for anything else.
fn index(line: &[u8], at: usize) -> Option<(usize, usize)> {
    let mut k: u64 = 0;
    let mut end = at;
    while end < line.len() && line[end].is_ascii_digit() {
        if end - at == 19 {
            return None; // 20 digits and more: the general path's (it says the range)
        }
        k = k * 10 + u64::from(line[end] - b'0');
        end += 1;
    }
    if end == at {
        return None;
    }
    usize::try_from(k).ok().map(|k| (k, end))
}

/// The entry of the entry line `line` (its bytes without the newline) by the fast path of
/// the module docs, 0-based; `None` when the line is anything else, to be read by
/// [`entry`] (which then takes it or says why not).
pub fn fast_entry(line: &[u8], size: usize, general: bool) -> Option<(usize, usize, f64)> {
    let at = skip_blanks(line, 0);
    let (row, at) = index(line, at)?;
    if at == line.len() || !blank(line[at]) {
        return None;
    }
    let (col, at) = index(line, skip_blanks(line, at))?;
    if at == line.len() || !blank(line[at]) {
        return None;
    }
    let start = skip_blanks(line, at);
    let mut end = start;
    while end < line.len() && !blank(line[end]) && line[end] != b'\r' {
        end += 1;
    }
    // Only blanks and a carriage return (a CRLF file) may follow the value.
    if line[end..].iter().any(|&b| !blank(b) && b != b'\r') {
        return None;
    }
    let value: f64 = std::str::from_utf8(&line[start..end]).ok()?.parse().ok()?;
    let inside = |k: usize| (1..=size).contains(&k);
    let taken = inside(row) && inside(col) && value.is_finite() && (general || row >= col);
    taken.then(|| (row - 1, col - 1, value))
}

#[cfg(test)]
mod tests {
    //! Every line checked on both paths: the fast path either gives what the general path
    //! gives, or leaves the line to it.
    use super::*;

    /// The general path's reading of `line`, and the fast path's agreement with it.
    fn both(line: &str, size: usize, general: bool) -> Result<(usize, usize, f64), String> {
        let slow = entry(line.trim(), size, general);
        if let Some(fast) = fast_entry(line.as_bytes(), size, general) {
            let slow = slow.clone().expect("the fast path takes only valid lines");
            assert_eq!(
                (fast.0, fast.1, fast.2.to_bits()),
                (slow.0, slow.1, slow.2.to_bits()),
                "{line:?}"
            );
        }
        slow
    }

    #[test]
    fn values_in_every_form_read_the_same_on_both_paths() {
        let cases = [
            ("2 1 2", 2.0),
            ("2 1 -1e4", -1e4),
            ("2 1 -1E+04", -1e4),
            ("2 1 1.5e-300", 1.5e-300),
            ("2 1 .5", 0.5),
            ("2 1 5.", 5.0),
            ("2 1 +3.25", 3.25),
            ("2 1 -0.0", -0.0),
            ("2 1 4.9406564584124654e-324", 5e-324),
            ("2 1 1.7976931348623157e308", f64::MAX),
            ("2 1 0.30000000000000004", 0.1 + 0.2),
            ("2 1 1.00000000000000000000000000001", 1.0),
            ("  2\t1   7  ", 7.0),
            ("2 1 7\r", 7.0),
            ("002 01 7", 7.0),
            ("+2 1 7", 7.0),
        ];
        for (line, value) in cases {
            let (i, j, v) = both(line, 2, false).unwrap();
            assert_eq!((i, j, v.to_bits()), (1, 0, value.to_bits()), "{line:?}");
        }
        // A signed index is the general path's.
        assert!(fast_entry(b"+2 1 7", 2, false).is_none());
        assert!(fast_entry(b"2 1 7", 2, false).is_some());
    }

    #[test]
    fn bad_lines_are_left_to_the_general_path_which_says_why() {
        let cases = [
            (
                "3 1 1.0",
                "row = `3` is invalid: it must be an integer from 1 to 2",
            ),
            (
                "0 1 1.0",
                "row = `0` is invalid: it must be an integer from 1 to 2",
            ),
            (
                "2 x 1.0",
                "column = `x` is invalid: it must be an integer from 1 to 2",
            ),
            (
                "2 1.0 1.0",
                "column = `1.0` is invalid: it must be an integer from 1 to 2",
            ),
            (
                "-2 1 1.0",
                "row = `-2` is invalid: it must be an integer from 1 to 2",
            ),
            (
                "99999999999999999999 1 1",
                "row = `99999999999999999999` is invalid: it must be an integer from 1 to 2",
            ),
            (
                "2 1 1.0d3",
                "value = `1.0d3` at (2, 1) is invalid: it must be a finite number",
            ),
            (
                "2 1 1e309",
                "value = `1e309` at (2, 1) is invalid: it must be a finite number",
            ),
            (
                "2 1 inf",
                "value = `inf` at (2, 1) is invalid: it must be a finite number",
            ),
            (
                "2 1 NaN",
                "value = `NaN` at (2, 1) is invalid: it must be a finite number",
            ),
            (
                "2 1 1..0",
                "value = `1..0` at (2, 1) is invalid: it must be a finite number",
            ),
            (
                "2 1",
                "entry `2 1` is invalid: it must be `row column value`",
            ),
            (
                "2 1 1.0 4",
                "entry `2 1 1.0 4` is invalid: it must be `row column value`",
            ),
            (
                "1 2 1.0",
                "entry (1, 2) is above the diagonal: a `symmetric` file stores the lower triangle only (row >= column)",
            ),
        ];
        for (line, message) in cases {
            assert_eq!(both(line, 2, false).unwrap_err(), message, "{line:?}");
            assert!(fast_entry(line.as_bytes(), 2, false).is_none(), "{line:?}");
        }
        // Above the diagonal is allowed in a `general` file.
        assert_eq!(both("1 2 1.0", 2, true).unwrap(), (0, 1, 1.0));
        // Comments and blank lines are not entries: the caller skips them before `entry`.
        for line in ["% 1 1 1", "", "   ", "\r"] {
            assert!(fast_entry(line.as_bytes(), 2, false).is_none(), "{line:?}");
        }
    }

    #[test]
    fn headers_name_what_is_allowed() {
        assert_eq!(
            is_general("%%MatrixMarket matrix coordinate real symmetric"),
            Ok(false)
        );
        assert_eq!(
            is_general("%%matrixmarket MATRIX Coordinate INTEGER general  "),
            Ok(true)
        );
        assert_eq!(
            is_general("%%MatrixMarket matrix coordinate pattern symmetric").unwrap_err(),
            format!(
                "header `%%MatrixMarket matrix coordinate pattern symmetric` is invalid: a `pattern` file has no values (a stiffness or mass matrix needs them); {HEADER_ALLOWED}"
            )
        );
        for header in [
            "%%MatrixMarket matrix coordinate complex hermitian",
            "%%MatrixMarket matrix coordinate real skew-symmetric",
            "%%MatrixMarket matrix array real general",
            "%MatrixMarket matrix coordinate real symmetric",
        ] {
            assert_eq!(
                is_general(header).unwrap_err(),
                format!("header `{header}` is invalid: {HEADER_ALLOWED}")
            );
        }
    }

    #[test]
    fn size_lines() {
        assert_eq!(size_line("3 3 5"), Ok((3, 5)));
        assert_eq!(size_line("3\t3  0"), Ok((3, 0)));
        assert_eq!(
            size_line("0 0 0").unwrap_err(),
            "size line `0 0 0` is invalid: it must be `rows columns entries`, three integers, rows = columns > 0"
        );
        assert_eq!(
            size_line("3 3").unwrap_err(),
            "size line `3 3` is invalid: it must be `rows columns entries`, three integers, rows = columns > 0"
        );
        assert_eq!(
            size_line("20000000 20000000 1").unwrap_err(),
            "size `20000000 20000000 1` is invalid: the matrix is 20000000 x 20000000; at most 10000000 rows are read"
        );
    }
}
