//! Measured modes (CSV): the identified eigensolutions y_r^m, lambda_r^m of the paper, with
//! partially identified shapes (eq. (15)).
//!
//! ```text
//! mode,frequency_hz,node,dof,value
//! 1,150.2,0,w,0.8812
//! 1,150.2,0,theta,-3.1
//! ```
//! `mode` is the deformable mode number r (1 = first elastic mode). A (node, dof) pair absent
//! for a mode is not identified (the paper's NF). Every row of a mode carries the same
//! frequency. A row may leave `node,dof,value` empty to give a frequency alone; a mode still
//! needs at least one shape row.

use std::collections::BTreeMap;
use std::io::Read;
use std::path::{Path, PathBuf};

use crate::model::{Dof, dof_index};

/// The header every measured-modes file starts with.
pub const HEADER: [&str; 5] = ["mode", "frequency_hz", "node", "dof", "value"];

/// A measured-modes file that cannot be used.
#[derive(Debug, thiserror::Error)]
pub enum MeasuredError {
    /// The file cannot be read.
    #[error("{file}: cannot read the file: {source}")]
    Read {
        /// The file.
        file: PathBuf,
        /// The cause.
        source: std::io::Error,
    },
    /// A line is invalid.
    #[error("{file}:{line}: {message}")]
    Line {
        /// The file.
        file: PathBuf,
        /// 1-based line number.
        line: u64,
        /// What is wrong and what is allowed.
        message: String,
    },
    /// The file holds no mode at all.
    #[error("{file}: no measured mode (only a header, or an empty file)")]
    Empty {
        /// The file.
        file: PathBuf,
    },
}

/// One measured mode: frequency and the identified shape components.
#[derive(Debug, Clone, PartialEq)]
pub struct MeasuredMode {
    /// Deformable mode number r, 1-based.
    pub mode: usize,
    /// Measured natural frequency f_r, Hz.
    pub frequency_hz: f64,
    /// Identified global DOF indices, ascending.
    pub dofs: Vec<usize>,
    /// Shape components at `dofs`.
    pub values: Vec<f64>,
}

impl MeasuredMode {
    /// The measured eigenvalue lambda_r^m = (2 pi f_r)^2.
    pub fn lambda(&self) -> f64 {
        crate::modal::hz_to_lambda(self.frequency_hz)
    }
}

/// All measured modes of a file, ordered by mode number.
#[derive(Debug, Clone, PartialEq)]
pub struct MeasuredModes {
    modes: Vec<MeasuredMode>,
}

struct Pending {
    frequency_hz: f64,
    first_line: u64,
    shape: BTreeMap<usize, (f64, u64)>,
}

impl MeasuredModes {
    /// Builds from modes already validated (used by simulators); sorted by mode number.
    pub fn new(mut modes: Vec<MeasuredMode>) -> Self {
        modes.sort_by_key(|m| m.mode);
        Self { modes }
    }

    /// The modes, ascending mode number.
    pub fn modes(&self) -> &[MeasuredMode] {
        &self.modes
    }

    /// The mode with number `r`, if measured.
    pub fn get(&self, r: usize) -> Option<&MeasuredMode> {
        self.modes.iter().find(|m| m.mode == r)
    }

    /// Reads and validates a file against a model with `node_count` nodes.
    pub fn from_path(path: &Path, node_count: usize) -> Result<Self, MeasuredError> {
        let file = std::fs::File::open(path).map_err(|source| MeasuredError::Read {
            file: path.to_path_buf(),
            source,
        })?;
        Self::from_reader(file, path, node_count)
    }

    /// Reads and validates CSV from any reader; `file` names it in errors.
    pub fn from_reader<R: Read>(
        reader: R,
        file: &Path,
        node_count: usize,
    ) -> Result<Self, MeasuredError> {
        let err = |line: u64, message: String| MeasuredError::Line {
            file: file.to_path_buf(),
            line,
            message,
        };
        let mut csv = csv::ReaderBuilder::new()
            .trim(csv::Trim::All)
            .comment(Some(b'#'))
            .from_reader(reader);
        let header = csv.headers().map_err(|e| err(1, e.to_string()))?.clone();
        if header.iter().ne(HEADER.iter().copied()) {
            return Err(err(
                1,
                format!(
                    "the header must be `{}`, found `{}`",
                    HEADER.join(","),
                    header.iter().collect::<Vec<_>>().join(",")
                ),
            ));
        }
        let mut pending: BTreeMap<usize, Pending> = BTreeMap::new();
        for record in csv.records() {
            let record = record.map_err(|e| {
                let line = e.position().map(|p| p.line()).unwrap_or(0);
                err(line, e.to_string())
            })?;
            let line = record.position().map(|p| p.line()).unwrap_or(0);
            let mode: usize = match record[0].parse() {
                Ok(r) if r >= 1 => r,
                _ => {
                    return Err(err(
                        line,
                        format!(
                            "mode = `{}` is invalid: it must be an integer >= 1 (1 = first elastic mode)",
                            &record[0]
                        ),
                    ));
                }
            };
            let frequency_hz: f64 = match record[1].parse::<f64>() {
                Ok(f) if f.is_finite() && f > 0.0 => f,
                _ => {
                    return Err(err(
                        line,
                        format!(
                            "frequency_hz = `{}` is invalid: it must be finite and > 0 (Hz)",
                            &record[1]
                        ),
                    ));
                }
            };
            let entry = pending.entry(mode).or_insert(Pending {
                frequency_hz,
                first_line: line,
                shape: BTreeMap::new(),
            });
            if entry.frequency_hz != frequency_hz {
                return Err(err(
                    line,
                    format!(
                        "mode {mode} has frequency_hz = {frequency_hz} here but {} on line {}: all rows of a mode must carry the same frequency",
                        entry.frequency_hz, entry.first_line
                    ),
                ));
            }
            if record[2].is_empty() && record[3].is_empty() && record[4].is_empty() {
                continue;
            }
            let node: usize = match record[2].parse() {
                Ok(n) if n < node_count => n,
                _ => {
                    return Err(err(
                        line,
                        format!(
                            "node = `{}` is invalid: the model has nodes 0 to {}",
                            &record[2],
                            node_count - 1
                        ),
                    ));
                }
            };
            let dof = Dof::parse(&record[3]).ok_or_else(|| {
                err(
                    line,
                    format!(
                        "dof = `{}` is invalid: it must be `w` or `theta`",
                        &record[3]
                    ),
                )
            })?;
            let value: f64 = match record[4].parse::<f64>() {
                Ok(v) if v.is_finite() => v,
                _ => {
                    return Err(err(
                        line,
                        format!(
                            "value = `{}` is invalid: it must be a finite number",
                            &record[4]
                        ),
                    ));
                }
            };
            if let Some((_, first)) = entry.shape.insert(dof_index(node, dof), (value, line)) {
                return Err(err(
                    line,
                    format!(
                        "mode {mode}, node {node}, dof {dof} is given twice (first on line {first})"
                    ),
                ));
            }
        }
        if pending.is_empty() {
            return Err(MeasuredError::Empty {
                file: file.to_path_buf(),
            });
        }
        let modes = pending
            .into_iter()
            .map(|(mode, p)| {
                if p.shape.is_empty() {
                    return Err(err(p.first_line, format!("mode {mode} has no shape rows: at least one (node, dof, value) is needed")));
                }
                let (dofs, values) = p.shape.into_iter().map(|(d, (v, _))| (d, v)).unzip();
                Ok(MeasuredMode { mode, frequency_hz: p.frequency_hz, dofs, values })
            })
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Self { modes })
    }

    /// Writes the modes in the file format above.
    pub fn write_csv<W: std::io::Write>(&self, out: W) -> Result<(), csv::Error> {
        let mut w = csv::Writer::from_writer(out);
        w.write_record(HEADER)?;
        for m in &self.modes {
            for (&d, &v) in m.dofs.iter().zip(&m.values) {
                let (node, dof) = crate::model::dof_of_index(d);
                w.write_record([
                    m.mode.to_string(),
                    m.frequency_hz.to_string(),
                    node.to_string(),
                    dof.name().to_string(),
                    v.to_string(),
                ])?;
            }
        }
        w.flush()?;
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read(text: &str) -> Result<MeasuredModes, String> {
        MeasuredModes::from_reader(text.as_bytes(), Path::new("d.csv"), 19)
            .map_err(|e| e.to_string())
    }

    #[test]
    fn reads_modes_sorted_with_their_dofs() {
        let m = read("mode,frequency_hz,node,dof,value\n2,400,3,theta,1.5\n1,150.2,0,w,0.88\n1,150.2,0,theta,-3.1\n2,400,,,\n").unwrap();
        assert_eq!(m.modes().len(), 2);
        assert_eq!(
            m.modes()[0],
            MeasuredMode {
                mode: 1,
                frequency_hz: 150.2,
                dofs: vec![0, 1],
                values: vec![0.88, -3.1]
            }
        );
        assert_eq!(m.get(2).unwrap().dofs, vec![7]);
    }

    #[test]
    fn each_bad_line_names_its_line_and_what_is_allowed() {
        let h = "mode,frequency_hz,node,dof,value\n";
        let cases = [
            (
                "1,150,0,phi,1.0\n",
                "d.csv:2: dof = `phi` is invalid: it must be `w` or `theta`",
            ),
            (
                "1,150,19,w,1.0\n",
                "d.csv:2: node = `19` is invalid: the model has nodes 0 to 18",
            ),
            (
                "1,150,0,w,1.0\n1,150,0,w,2.0\n",
                "d.csv:3: mode 1, node 0, dof w is given twice (first on line 2)",
            ),
            (
                "1,150,0,w,1.0\n1,151,1,w,2.0\n",
                "d.csv:3: mode 1 has frequency_hz = 151 here but 150 on line 2: all rows of a mode must carry the same frequency",
            ),
            (
                "1,150,0,w,inf\n",
                "d.csv:2: value = `inf` is invalid: it must be a finite number",
            ),
            (
                "1,NaN,0,w,1\n",
                "d.csv:2: frequency_hz = `NaN` is invalid: it must be finite and > 0 (Hz)",
            ),
            (
                "0,150,0,w,1\n",
                "d.csv:2: mode = `0` is invalid: it must be an integer >= 1 (1 = first elastic mode)",
            ),
            (
                "1,150,0,w,1\n2,300,,,\n",
                "d.csv:3: mode 2 has no shape rows: at least one (node, dof, value) is needed",
            ),
        ];
        for (body, message) in cases {
            assert_eq!(
                read(&format!("{h}{body}")).unwrap_err(),
                message,
                "for {body:?}"
            );
        }
        assert!(
            read("mode,freq,node,dof,value\n")
                .unwrap_err()
                .starts_with("d.csv:1: the header must be")
        );
        assert_eq!(
            read(h).unwrap_err(),
            "d.csv: no measured mode (only a header, or an empty file)"
        );
        assert!(
            read(&format!("{h}1,150,0,w\n"))
                .unwrap_err()
                .starts_with("d.csv:2: ")
        );
    }

    #[test]
    fn write_then_read_round_trips() {
        let m = MeasuredModes::new(vec![MeasuredMode {
            mode: 3,
            frequency_hz: 812.25,
            dofs: vec![0, 5, 36],
            values: vec![0.1, -1e-7, 3.0],
        }]);
        let mut buf = Vec::new();
        m.write_csv(&mut buf).unwrap();
        assert_eq!(read(std::str::from_utf8(&buf).unwrap()).unwrap(), m);
    }
}
