//! Plain aligned text tables for the terminal.

use std::io::{self, Write};

/// Writes `header` and `rows` as right-aligned columns separated by two spaces. Cells of a
/// row beyond the header's columns are a note (why a row has no values), written after its
/// columns and left out of their widths.
pub fn write_table(out: &mut dyn Write, header: &[&str], rows: &[Vec<String>]) -> io::Result<()> {
    let mut widths: Vec<usize> = header.iter().map(|h| h.chars().count()).collect();
    for row in rows {
        for (w, cell) in widths.iter_mut().zip(row) {
            *w = (*w).max(cell.chars().count());
        }
    }
    let line = |cells: &[&str]| {
        let columns = cells.len().min(widths.len());
        let mut text = cells[..columns]
            .iter()
            .zip(&widths)
            .map(|(c, w)| format!("{c:>w$}"))
            .collect::<Vec<_>>()
            .join("  ");
        for note in &cells[columns..] {
            text.push_str("  ");
            text.push_str(note);
        }
        text
    };
    writeln!(out, "{}", line(header))?;
    for row in rows {
        let cells: Vec<&str> = row.iter().map(String::as_str).collect();
        writeln!(out, "{}", line(&cells))?;
    }
    Ok(())
}

/// A number in engineering-friendly scientific notation with 4 significant digits.
pub fn sci(x: f64) -> String {
    if x == 0.0 {
        "0".to_string()
    } else {
        format!("{x:.3e}")
    }
}

/// `value +- se` in [`sci`] form; `not identifiable` when either is not finite (the JSON
/// report's null), never `NaN`.
pub fn plus_minus(value: f64, se: f64) -> String {
    if value.is_finite() && se.is_finite() {
        format!("{} +- {}", sci(value), sci(se))
    } else {
        NOT_IDENTIFIABLE.to_string()
    }
}

/// What a report says of an estimate without a finite value or standard error.
pub const NOT_IDENTIFIABLE: &str = "not identifiable";

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_estimate_without_a_finite_error_is_not_identifiable() {
        assert_eq!(plus_minus(1.5e7, 2.0e5), "1.500e7 +- 2.000e5");
        assert_eq!(plus_minus(0.0, 0.0), "0 +- 0");
        assert_eq!(plus_minus(0.0, f64::NAN), "not identifiable");
        assert_eq!(plus_minus(f64::INFINITY, 1.0), "not identifiable");
    }

    #[test]
    fn columns_align_right() {
        let mut buf = Vec::new();
        write_table(&mut buf, &["a", "long"], &[vec!["123".into(), "x".into()]]).unwrap();
        assert_eq!(String::from_utf8(buf).unwrap(), "  a  long\n123     x\n");
        assert_eq!(sci(2.0e6), "2.000e6");
        // A note beyond the header's columns follows its row and widens no column.
        let mut buf = Vec::new();
        let rows = [
            vec!["12".into(), "x".into(), "a long note".into()],
            vec!["3".into(), "yy".into()],
        ];
        write_table(&mut buf, &["a", "b"], &rows).unwrap();
        assert_eq!(
            String::from_utf8(buf).unwrap(),
            " a   b\n12   x  a long note\n 3  yy\n"
        );
    }
}
