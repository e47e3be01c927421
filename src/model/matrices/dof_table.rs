//! The DOF table of an external model (CSV): what every row and column of its matrices is.
//!
//! ```text
//! dof,label,x,y,z,direction
//! 1,7:w,0.2,0,0,w
//! 2,7:theta,0.2,0,0,theta
//! ```
//!
//! `dof` is the 1-based index of the row and column in the Matrix Market files; every index
//! from 1 to N appears exactly once (in any order). `label` is what measured files and studies
//! name the DOF by: unique, not empty. `x, y, z` is its position, m. `direction` is one of `w`,
//! `theta` (a planar beam) or `x`, `y`, `z`, `rx`, `ry`, `rz`.

use std::collections::HashMap;
use std::io::{self, Read, Write};
use std::path::{Path, PathBuf};

use crate::structure::{Direction, DofInfo};

/// The header of the table.
pub const HEADER: [&str; 6] = ["dof", "label", "x", "y", "z", "direction"];

/// A DOF table that cannot be used.
#[derive(Debug, thiserror::Error)]
pub enum DofTableError {
    /// The file cannot be read.
    #[error("{file}: cannot read the file: {cause}")]
    Read {
        /// The file.
        file: PathBuf,
        /// The cause.
        cause: io::Error,
    },
    /// A line is invalid.
    #[error("{file}:{line}: {message}")]
    Line {
        /// The file.
        file: PathBuf,
        /// 1-based line.
        line: u64,
        /// What is wrong, the value and what is allowed.
        message: String,
    },
    /// Not every index from 1 to N is given.
    #[error(
        "{file}: dof {missing} is missing: the table must list every dof from 1 to {size} once"
    )]
    Missing {
        /// The file.
        file: PathBuf,
        /// The first missing index, 1-based.
        missing: usize,
        /// N.
        size: usize,
    },
}

/// Reads a DOF table for matrices of size `size`: the DOFs in index order.
pub fn from_path(path: &Path, size: usize) -> Result<Vec<DofInfo>, DofTableError> {
    let file = std::fs::File::open(path).map_err(|cause| DofTableError::Read {
        file: path.to_path_buf(),
        cause,
    })?;
    read(file, path, size)
}

/// The 0-based index of the `dof` field (1 to `size`); the message when it is invalid.
fn dof_index(dof: &str, size: usize) -> Result<usize, String> {
    match dof.parse::<usize>() {
        Ok(i) if (1..=size).contains(&i) => Ok(i - 1),
        _ => Err(format!(
            "dof = `{dof}` is invalid: it must be an integer from 1 to {size} (the size of the matrices)"
        )),
    }
}

/// The position (the `x`, `y`, `z` fields, m) and the direction of a row; the message when
/// one is invalid.
fn placement(xyz: [&str; 3], direction: &str) -> Result<([f64; 3], Direction), String> {
    let mut position = [0.0; 3];
    for ((p, text), name) in position.iter_mut().zip(xyz).zip(["x", "y", "z"]) {
        *p = match text.parse::<f64>() {
            Ok(v) if v.is_finite() => v,
            _ => {
                return Err(format!(
                    "{name} = `{text}` is invalid: it must be a finite number (m)"
                ));
            }
        };
    }
    Ok((position, direction_of(direction)?))
}

/// A direction by its name; the message when it is not one.
fn direction_of(direction: &str) -> Result<Direction, String> {
    Direction::parse(direction).ok_or_else(|| {
        let names: Vec<&str> = Direction::ALL.iter().map(|d| d.name()).collect();
        if direction.is_empty() {
            format!(
                "direction is empty: every DOF needs one, of {}",
                names.join(", ")
            )
        } else {
            format!(
                "direction = `{direction}` is invalid: it must be one of {}",
                names.join(", ")
            )
        }
    })
}

/// A DOF table given by its columns in memory, row i the DOF of index i: every label not
/// empty and unique, every position finite (m), every direction one of [`Direction::ALL`];
/// `name` names the table in errors, and a row's "line" there is its 1-based index.
pub fn from_columns(
    labels: &[String],
    positions: &[[f64; 3]],
    directions: &[String],
    name: &Path,
) -> Result<Vec<DofInfo>, DofTableError> {
    let line_err = |row: usize, message: String| DofTableError::Line {
        file: name.to_path_buf(),
        line: row as u64 + 1,
        message,
    };
    let mut first: HashMap<&str, usize> = HashMap::new();
    let mut dofs = Vec::with_capacity(labels.len());
    for (row, ((label, position), direction)) in
        labels.iter().zip(positions).zip(directions).enumerate()
    {
        if label.is_empty() {
            return Err(line_err(
                row,
                "label is empty: every DOF needs a label".into(),
            ));
        }
        if let Some(before) = first.insert(label, row) {
            return Err(line_err(
                row,
                format!(
                    "label = `{label}` is given twice (first in row {}): labels must be unique",
                    before + 1
                ),
            ));
        }
        if let Some((axis, v)) = ["x", "y", "z"]
            .iter()
            .zip(position)
            .find(|(_, v)| !v.is_finite())
        {
            return Err(line_err(
                row,
                format!("{axis} = {v} is invalid: it must be a finite number (m)"),
            ));
        }
        dofs.push(DofInfo {
            label: label.clone(),
            position: *position,
            direction: direction_of(direction).map_err(|m| line_err(row, m))?,
            node: None,
        });
    }
    Ok(dofs)
}

/// Reads a DOF table from `reader` for matrices of size `size`; `file` names it in errors.
pub fn read(reader: impl Read, file: &Path, size: usize) -> Result<Vec<DofInfo>, DofTableError> {
    let line_err = |line: u64, message: String| DofTableError::Line {
        file: file.to_path_buf(),
        line,
        message: crate::input::safe::clip_quotes(message),
    };
    let mut csv = ::csv::ReaderBuilder::new()
        .has_headers(false)
        .trim(::csv::Trim::All)
        .flexible(true)
        .from_reader(crate::input::bounded::Bounded::new(
            reader,
            crate::input::bounded::TABLE,
        ));
    let mut slots: Vec<Option<DofInfo>> = vec![None; size];
    let mut first_line: Vec<u64> = vec![0; size];
    let mut labels: HashMap<String, u64> = HashMap::new();
    let mut header_seen = false;
    for record in csv.records() {
        let record = record.map_err(|e| {
            let line = e.position().map_or(0, |p| p.line());
            line_err(line, format!("not valid CSV: {e}"))
        })?;
        let line = record.position().map_or(0, |p| p.line());
        if !header_seen {
            let head: Vec<&str> = record.iter().collect();
            if head != HEADER {
                return Err(line_err(
                    line,
                    format!(
                        "header `{}` is invalid: it must be `{}`",
                        head.join(","),
                        HEADER.join(",")
                    ),
                ));
            }
            header_seen = true;
            continue;
        }
        if record.iter().all(str::is_empty) {
            continue;
        }
        let f: Vec<&str> = record.iter().collect();
        let [dof, label, x, y, z, direction] = f[..] else {
            return Err(line_err(
                line,
                format!("{} fields: a row has 6 ({})", f.len(), HEADER.join(",")),
            ));
        };
        let index = dof_index(dof, size).map_err(|message| line_err(line, message))?;
        if slots[index].is_some() {
            return Err(line_err(
                line,
                format!(
                    "dof = {dof} is given twice (first on line {})",
                    first_line[index]
                ),
            ));
        }
        if label.is_empty() {
            return Err(line_err(
                line,
                "label is empty: every DOF needs a label".into(),
            ));
        }
        if let Some(first) = labels.insert(label.to_string(), line) {
            return Err(line_err(
                line,
                format!(
                    "label = `{label}` is given twice (first on line {first}): labels must be unique"
                ),
            ));
        }
        let (position, direction) =
            placement([x, y, z], direction).map_err(|message| line_err(line, message))?;
        slots[index] = Some(DofInfo {
            label: label.to_string(),
            position,
            direction,
            node: None,
        });
        first_line[index] = line;
    }
    if !header_seen {
        return Err(line_err(
            1,
            format!(
                "the file is empty: it must start with `{}`",
                HEADER.join(",")
            ),
        ));
    }
    match slots.iter().position(Option::is_none) {
        Some(missing) => Err(DofTableError::Missing {
            file: file.to_path_buf(),
            missing: missing + 1,
            size,
        }),
        None => Ok(slots.into_iter().flatten().collect()),
    }
}

/// Writes the table of `dofs` (in index order), positions in shortest round-trip form.
pub fn write(out: &mut dyn Write, dofs: &[DofInfo]) -> io::Result<()> {
    write_iter(out, dofs.iter().cloned())
}

/// [`write`](fn@write) from an iterator of the DOFs in index order (a large table written as
/// it is made).
pub fn write_iter(out: &mut dyn Write, dofs: impl Iterator<Item = DofInfo>) -> io::Result<()> {
    let mut w = ::csv::Writer::from_writer(out);
    let to_io = |e: ::csv::Error| io::Error::other(e.to_string());
    w.write_record(HEADER).map_err(to_io)?;
    for (i, d) in dofs.enumerate() {
        let [x, y, z] = d.position.map(|v| v.to_string());
        w.write_record([
            (i + 1).to_string(),
            d.label.clone(),
            x,
            y,
            z,
            d.direction.name().to_string(),
        ])
        .map_err(to_io)?;
    }
    w.flush()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read_str(text: &str, size: usize) -> Result<Vec<DofInfo>, DofTableError> {
        read(text.as_bytes(), Path::new("dofs.csv"), size)
    }

    #[test]
    fn rows_in_any_order_come_back_in_index_order_and_round_trip() {
        let dofs = read_str(
            "dof,label,x,y,z,direction\n2,tip,0.5,0,0,z\n1,root:rx,0.1,0.0,-0.25,rx\n",
            2,
        )
        .unwrap();
        assert_eq!(dofs[0].label, "root:rx");
        assert_eq!(dofs[0].position, [0.1, 0.0, -0.25]);
        assert_eq!(dofs[0].direction, Direction::Rx);
        assert_eq!(dofs[1].label, "tip");
        let mut bytes = Vec::new();
        write(&mut bytes, &dofs).unwrap();
        assert_eq!(
            read_str(std::str::from_utf8(&bytes).unwrap(), 2).unwrap(),
            dofs
        );
    }

    #[test]
    fn bad_tables_name_the_line_and_what_is_allowed() {
        let h = "dof,label,x,y,z,direction\n";
        let cases = [
            (
                "dof,label,x,direction\n".to_string(),
                "dofs.csv:1: header `dof,label,x,direction` is invalid: it must be `dof,label,x,y,z,direction`",
            ),
            (
                format!("{h}3,a,0,0,0,w\n"),
                "dofs.csv:2: dof = `3` is invalid: it must be an integer from 1 to 2 (the size of the matrices)",
            ),
            (
                format!("{h}1,a,0,0,0,w\n1,b,0,0,0,w\n"),
                "dofs.csv:3: dof = 1 is given twice (first on line 2)",
            ),
            (
                format!("{h}1,a,0,0,0,w\n2,a,0,0,0,theta\n"),
                "dofs.csv:3: label = `a` is given twice (first on line 2): labels must be unique",
            ),
            (
                format!("{h}1,a,0,0,0,u\n"),
                "dofs.csv:2: direction = `u` is invalid: it must be one of w, theta, x, y, z, rx, ry, rz",
            ),
            (
                format!("{h}1,a,NaN,0,0,w\n"),
                "dofs.csv:2: x = `NaN` is invalid: it must be a finite number (m)",
            ),
            (
                format!("{h}1,a,0,0,0,w\n"),
                "dofs.csv: dof 2 is missing: the table must list every dof from 1 to 2 once",
            ),
            (
                format!("{h}1,,0,0,0,w\n"),
                "dofs.csv:2: label is empty: every DOF needs a label",
            ),
            (
                format!("{h}1,a,0,0,0,\n"),
                "dofs.csv:2: direction is empty: every DOF needs one, of w, theta, x, y, z, rx, ry, rz",
            ),
            (
                format!("{h}1,a,0,0,0\n"),
                "dofs.csv:2: 5 fields: a row has 6 (dof,label,x,y,z,direction)",
            ),
        ];
        for (text, message) in cases {
            assert_eq!(read_str(&text, 2).unwrap_err().to_string(), message);
        }
    }
}
