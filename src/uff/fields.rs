//! Fields of the Fortran fixed formats of universal files, read robustly.
//!
//! The formats are column-exact (`I10`, `E13.5`, `A20`, ...), but many writers separate the
//! numbers by blanks and drift from the columns. Numbers are therefore read by blanks first;
//! only when a line does not split into numbers (two values run together, as in
//! `4.111111E+03-3.111111E+03`, or a blank integer field) is it read by the columns of its
//! format. Text fields (ID lines, labels) are always read by columns, since they may hold
//! blanks. Reals accept the Fortran forms `1.0D+00`, `1.0E+000` and `1.0-100` (exponent without
//! letter); infinities and NaN are refused.

use std::borrow::Cow;

use super::error::{Located, Problem};

/// One line of a dataset, without its terminator.
#[derive(Debug, Clone)]
pub(crate) struct Line<'a> {
    /// 1-based line number in the file.
    pub number: usize,
    /// The text (bytes that are not UTF-8 replaced by U+FFFD).
    pub text: Cow<'a, str>,
}

/// Walks the lines of one dataset in order.
pub(crate) struct Cursor<'d, 'a> {
    lines: &'d [Line<'a>],
    pos: usize,
    /// Line of the closing `-1`, where a truncated record ends.
    end_line: usize,
}

impl<'d, 'a> Cursor<'d, 'a> {
    pub(crate) fn new(lines: &'d [Line<'a>], end_line: usize) -> Self {
        Cursor {
            lines,
            pos: 0,
            end_line,
        }
    }

    /// The next line, which must exist: `what` names it in the error.
    pub(crate) fn next(&mut self, what: &'static str) -> Result<&'d Line<'a>, Located> {
        let line = self
            .lines
            .get(self.pos)
            .ok_or(Located::new(self.end_line, Problem::Truncated { what }))?;
        self.pos += 1;
        Ok(line)
    }

    /// The next line that is not blank, if any, consuming the blank ones.
    pub(crate) fn next_non_blank(&mut self) -> Option<&'d Line<'a>> {
        while let Some(line) = self.lines.get(self.pos) {
            self.pos += 1;
            if !line.text.trim().is_empty() {
                return Some(line);
            }
        }
        None
    }

    /// The lines not yet read.
    pub(crate) fn rest(&self) -> &'d [Line<'a>] {
        &self.lines[self.pos.min(self.lines.len())..]
    }

    /// Line of the closing `-1`.
    pub(crate) fn end_line(&self) -> usize {
        self.end_line
    }
}

/// A real number in any of the Fortran output forms.
pub(crate) fn real(text: &str, field: &'static str) -> Result<f64, Problem> {
    let bad = || Problem::Number {
        field,
        text: text.trim().to_string(),
    };
    let t = text.trim();
    if t.is_empty()
        || t.bytes()
            .any(|b| b.is_ascii_alphabetic() && !b"EeDd".contains(&b))
    {
        return Err(bad());
    }
    let mut s: String = t
        .chars()
        .map(|c| if c == 'D' || c == 'd' { 'E' } else { c })
        .collect();
    if !s.contains(['E', 'e']) {
        // `1.234-100`: Fortran drops the letter of a three-digit exponent.
        if let Some(at) = s.rfind(['+', '-']).filter(|&at| at > 0) {
            s.insert(at, 'E');
        }
    }
    match s.parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        _ => Err(bad()),
    }
}

/// An integer (`I` format), sign allowed.
pub(crate) fn integer(text: &str, field: &'static str) -> Result<i64, Problem> {
    text.trim().parse::<i64>().map_err(|_| Problem::Integer {
        field,
        text: text.trim().to_string(),
    })
}

/// The text between character columns `start` and `start + width` (0-based), trimmed;
/// empty past the end of the line.
pub(crate) fn column(text: &str, start: usize, width: usize) -> &str {
    let mut indices = text.char_indices().map(|(i, _)| i).chain([text.len()]);
    let Some(from) = indices.nth(start) else {
        return "";
    };
    let to = text
        .char_indices()
        .map(|(i, _)| i)
        .chain([text.len()])
        .nth(start + width)
        .unwrap_or(text.len());
    text[from..to].trim()
}

/// The fields of a line cut at the widths of its format, repeated cyclically, up to the end
/// of the line.
fn cut<'t>(text: &'t str, widths: &[usize]) -> Vec<&'t str> {
    let n_chars = text.chars().count();
    let mut fields = Vec::new();
    let mut start = 0;
    for &w in widths.iter().cycle() {
        if start >= n_chars || w == 0 {
            break;
        }
        fields.push(column(text, start, w));
        start += w;
    }
    fields
}

/// The real numbers of a line: by blanks, else by the columns `widths` (repeated cyclically;
/// blank trailing fields are no values).
pub(crate) fn reals(
    text: &str,
    widths: &[usize],
    field: &'static str,
) -> Result<Vec<f64>, Problem> {
    let by_blanks: Result<Vec<f64>, Problem> =
        text.split_whitespace().map(|t| real(t, field)).collect();
    if by_blanks.is_ok() || widths.is_empty() {
        return by_blanks;
    }
    let mut fields = cut(text, widths);
    while fields.last().is_some_and(|f| f.is_empty()) {
        fields.pop();
    }
    // When the columns fail too, the blank-separated token that failed says more.
    fields
        .into_iter()
        .map(|f| real(f, field))
        .collect::<Result<_, _>>()
        .or(by_blanks)
}

/// The integers of a line: by blanks, else by the columns `widths` (a blank field is 0, as
/// Fortran reads it).
pub(crate) fn integers(
    text: &str,
    widths: &[usize],
    field: &'static str,
) -> Result<Vec<i64>, Problem> {
    let by_blanks: Result<Vec<i64>, Problem> =
        text.split_whitespace().map(|t| integer(t, field)).collect();
    if by_blanks.is_ok() || widths.is_empty() {
        return by_blanks;
    }
    cut(text, widths)
        .into_iter()
        .map(|f| {
            if f.is_empty() {
                Ok(0)
            } else {
                integer(f, field)
            }
        })
        .collect::<Result<_, _>>()
        .or(by_blanks)
}

/// Exactly `n` integers: by blanks when the line has `n` of them, else by the columns
/// `widths` (a blank field is 0).
pub(crate) fn integers_n(
    text: &str,
    n: usize,
    widths: &[usize],
    field: &'static str,
) -> Result<Vec<i64>, Problem> {
    let tokens: Vec<&str> = text.split_whitespace().collect();
    if tokens.len() == n
        && let Ok(v) = tokens.iter().map(|t| integer(t, field)).collect()
    {
        return Ok(v);
    }
    let mut fields = cut(text, widths);
    fields.resize(n, "");
    fields[..n]
        .iter()
        .map(|f| {
            if f.is_empty() {
                Ok(0)
            } else {
                integer(f, field)
            }
        })
        .collect()
}

/// `count` real values spread over the next lines, read with the columns `widths`. Values
/// come in groups of `group` (a point of an uneven complex function is x, Re, Im); errors
/// count groups and call them `what`. Blank lines are skipped. The line that completes the
/// count may carry zeros after it (padding of the last line, as some writers do); anything
/// else there is an error. The lines after the count are left to the caller.
pub(crate) fn collect_reals(
    cursor: &mut Cursor<'_, '_>,
    count: usize,
    group: usize,
    widths: &[usize],
    what: &'static str,
    field: &'static str,
) -> Result<Vec<f64>, Located> {
    let group = group.max(1);
    // No trust in the declared count for the allocation: at most what the lines can hold.
    let mut values = Vec::with_capacity(count.min(cursor.rest().len().saturating_mul(8)));
    while values.len() < count {
        let Some(line) = cursor.next_non_blank() else {
            return Err(Located::new(
                cursor.end_line(),
                Problem::TooFew {
                    what,
                    expected: count / group,
                    found: values.len() / group,
                },
            ));
        };
        let read = reals(&line.text, widths, field).map_err(|p| Located::new(line.number, p))?;
        let room = count - values.len();
        if read.len() > room {
            if read[room..].iter().any(|&v| v != 0.0) {
                return Err(Located::new(
                    line.number,
                    Problem::TooMany {
                        what,
                        expected: count / group,
                        found: (values.len() + read.len()).div_ceil(group),
                    },
                ));
            }
            values.extend_from_slice(&read[..room]);
        } else {
            values.extend_from_slice(&read);
        }
    }
    Ok(values)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reals_accept_fortran_forms() {
        assert_eq!(real(" 1.5D+00", "x"), Ok(1.5));
        assert_eq!(real("0.00000E+000", "x"), Ok(0.0));
        assert_eq!(real("-2.5-100", "x"), Ok(-2.5e-100));
        assert_eq!(real("2.5+002", "x"), Ok(250.0));
        assert_eq!(real(".5", "x"), Ok(0.5));
        for bad in ["", "NaN", "inf", "1e999", "1.2.3", "abc", "--1"] {
            assert!(real(bad, "x").is_err(), "{bad:?} accepted");
        }
    }

    #[test]
    fn run_together_values_are_read_by_columns() {
        let line = "-1.111111E-01 4.111111E+01 4.111111E+03-3.111111E+03-1.111110E+05-2.111110E+05";
        let v = reals(line, &[13], "data").unwrap();
        assert_eq!(
            v,
            [
                -1.111111E-01,
                4.111111E+01,
                4.111111E+03,
                -3.111111E+03,
                -1.111110E+05,
                -2.111110E+05
            ]
        );
        // 2(E13.5,E20.12) with the second pair run together
        let line = "  1.00000E+00 -2.000000000000E+00  3.00000E+00-4.000000000000E+00";
        assert_eq!(
            reals(line, &[13, 20], "data").unwrap(),
            [1.0, -2.0, 3.0, -4.0]
        );
    }

    #[test]
    fn blank_integer_columns_read_as_zero() {
        let line = "    4         0              0";
        assert_eq!(
            integers_n(line, 4, &[5, 10, 5, 10], "r6").unwrap(),
            [4, 0, 0, 0]
        );
        assert_eq!(integers_n("1 2 3 4", 4, &[5], "r6").unwrap(), [1, 2, 3, 4]);
        // by blanks when possible
        assert_eq!(integers(" 1 2  3", &[5], "r6").unwrap(), [1, 2, 3]);
    }

    #[test]
    fn columns_count_characters_not_bytes() {
        let line = "m/s²  kg";
        assert_eq!(column(line, 0, 4), "m/s²");
        assert_eq!(column(line, 6, 2), "kg");
        assert_eq!(column(line, 20, 4), "");
    }

    fn lines(texts: &[&'static str]) -> Vec<Line<'static>> {
        texts
            .iter()
            .enumerate()
            .map(|(i, t)| Line {
                number: i + 1,
                text: Cow::Borrowed(*t),
            })
            .collect()
    }

    #[test]
    fn collect_allows_zero_padding_only() {
        let ls = lines(&["1 2 3", "4 5 0 0", "9"]);
        let mut c = Cursor::new(&ls, 4);
        assert_eq!(
            collect_reals(&mut c, 5, 1, &[13], "v", "d").unwrap(),
            [1.0, 2.0, 3.0, 4.0, 5.0]
        );
        assert_eq!(c.rest().len(), 1);

        let ls = lines(&["1 2 3", "4 5 6"]);
        let mut c = Cursor::new(&ls, 3);
        let err = collect_reals(&mut c, 5, 1, &[13], "v", "d").unwrap_err();
        assert_eq!(err.line, 2);
        assert!(matches!(
            err.problem,
            Problem::TooMany {
                expected: 5,
                found: 6,
                ..
            }
        ));

        let ls = lines(&["1 2 3", "", "4"]);
        let mut c = Cursor::new(&ls, 4);
        let err = collect_reals(&mut c, 6, 2, &[13], "pairs", "d").unwrap_err();
        assert_eq!(err.line, 4);
        assert_eq!(
            err.problem,
            Problem::TooFew {
                what: "pairs",
                expected: 3,
                found: 2
            }
        );
    }
}
