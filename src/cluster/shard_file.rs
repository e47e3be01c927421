//! The result file of one shard: a few `#` lines that say what it is, then the result CSV of
//! its cells exactly as the single-machine run writes them ([`crate::study::results`]).
//!
//! ```text
//! # jointid shard 2/4
//! # study: paper-case-1
//! # fingerprint: 5f0c6a1d93e2b847
//! # tool: jointid 0.1.0
//! # cells: 36
//! # rows per cell: 8
//! # assignment: 1 2 3 4 4 3 ...
//! # modes: 1 2 3 4
//! # params: ["k1","k2"]
//! # rows hash: 0c1f9e3b5a7d2846
//! cell,mode,param,n,...
//! ```
//!
//! The fingerprint is the study's ([`crate::study::fingerprint`]): shards of different study
//! files, models or jointid versions never merge. `assignment` is the shard (1-based) of every
//! cell in cell order, so that a merge can name the shard a missing cell belongs to. `modes`
//! and `params` (a JSON list) are the study's, in the order of its rows; `rows hash` is the
//! content hash of everything after the header ([`super::shard_rows::rows_hash`]). A file
//! whose rows do not match their hash, or whose rows do not parse as the study's
//! ([`super::shard_rows`]), is refused naming its file, line and fault.

use std::io::{self, BufRead, Read, Write};
use std::path::{Path, PathBuf};

use super::shard::ShardSpec;
use super::shard_rows::{CellRows, RowKey, check_row, rows_hash};
use crate::input::bounded::{Bounded, TABLE};
use crate::study::CellResult;
use crate::study::results::{RESULT_HEADER, write_results};

const MAGIC: &str = "# jointid shard ";

/// What a shard file says about itself.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ShardHeader {
    /// K/N.
    pub spec: ShardSpec,
    /// The study's name.
    pub study: String,
    /// The study's fingerprint.
    pub fingerprint: String,
    /// `jointid <version>` that wrote it.
    pub tool: String,
    /// Rows of every cell, modes times parameters.
    pub rows_per_cell: usize,
    /// The shard (1-based) of every cell of the study, in cell order.
    pub assignment: Vec<usize>,
    /// The study's modes, in the order of its rows.
    pub modes: Vec<usize>,
    /// The study's parameters, in the order of its rows.
    pub params: Vec<String>,
}

/// Writes a shard file: the header, then the result CSV of `results` (the shard's cells).
pub fn write_shard(
    out: &mut dyn Write,
    header: &ShardHeader,
    results: &[CellResult],
    names: &[String],
    noise: &str,
) -> io::Result<()> {
    let words = |v: &[usize]| {
        v.iter()
            .map(|s| s.to_string())
            .collect::<Vec<_>>()
            .join(" ")
    };
    let mut rows = Vec::new();
    write_results(&mut rows, results, names, noise)?;
    write!(
        out,
        "{MAGIC}{}\n# study: {}\n# fingerprint: {}\n# tool: {}\n# cells: {}\n# rows per cell: {}\n# assignment: {}\n# modes: {}\n# params: {}\n# rows hash: {}\n",
        header.spec,
        header.study.replace(['\n', '\r'], " "),
        header.fingerprint,
        header.tool,
        header.assignment.len(),
        header.rows_per_cell,
        words(&header.assignment),
        words(&header.modes),
        serde_json::to_string(&header.params).map_err(io::Error::other)?,
        rows_hash(&rows)
    )?;
    out.write_all(&rows)
}

/// A shard file that cannot be read.
#[derive(Debug, thiserror::Error)]
pub enum ShardFileError {
    /// Cannot read.
    #[error("{file}: cannot read: {cause}")]
    Read {
        /// The file.
        file: PathBuf,
        /// Why.
        cause: io::Error,
    },
    /// No shard header.
    #[error(
        "{file} is not a jointid shard file: it must begin with `{}K/N` (write one with `jointid study S.toml --shard K/N`)",
        MAGIC
    )]
    NotShard {
        /// The file.
        file: PathBuf,
    },
    /// A bad header line or field.
    #[error("{file}:{line}: {message}")]
    Line {
        /// The file.
        file: PathBuf,
        /// Line, 1-based.
        line: u64,
        /// What is wrong.
        message: String,
    },
}

/// One result row of a shard: its cell and place, the record as written, and its line.
#[derive(Debug, Clone)]
pub struct ShardRow {
    /// Cell index.
    pub cell: usize,
    /// Its cell and place in the cell (the merge's order).
    pub key: RowKey,
    /// The fields.
    pub record: csv::StringRecord,
    /// Line in the shard file, 1-based.
    pub line: u64,
}

/// A shard file, read.
#[derive(Debug, Clone)]
pub struct ShardFile {
    /// The file, for messages.
    pub file: PathBuf,
    /// Its header.
    pub header: ShardHeader,
    /// Its result rows in file order.
    pub rows: Vec<ShardRow>,
}

impl ShardFile {
    /// Reads a shard file.
    pub fn from_path(path: &Path) -> Result<Self, ShardFileError> {
        let file = std::fs::File::open(path).map_err(|cause| ShardFileError::Read {
            file: path.into(),
            cause,
        })?;
        Self::from_reader(file, path)
    }

    /// Reads a shard file from `reader` (within [`TABLE`]'s limits); `file` names it in
    /// errors.
    pub fn from_reader<R: Read>(reader: R, file: &Path) -> Result<Self, ShardFileError> {
        let mut reader = io::BufReader::new(Bounded::new(reader, TABLE));
        let read_err = |cause| ShardFileError::Read {
            file: file.into(),
            cause,
        };
        let bad = |line: u64, message: String| ShardFileError::Line {
            file: file.into(),
            line,
            message: crate::input::safe::clip_quotes(message),
        };
        let mut fields: Vec<(String, String)> = Vec::new();
        let mut first = true;
        loop {
            if !reader.fill_buf().map_err(read_err)?.starts_with(b"#") {
                break;
            }
            let mut line = String::new();
            reader.read_line(&mut line).map_err(read_err)?;
            let line = line.trim_end();
            if first {
                let Some(spec) = line.strip_prefix(MAGIC) else {
                    return Err(ShardFileError::NotShard { file: file.into() });
                };
                fields.push(("shard".into(), spec.into()));
                first = false;
                continue;
            }
            let (key, value) = line
                .trim_start_matches('#')
                .split_once(':')
                .ok_or_else(|| {
                    bad(
                        fields.len() as u64 + 1,
                        format!("`{line}` is not `# key: value`"),
                    )
                })?;
            fields.push((key.trim().into(), value.trim().into()));
        }
        if first {
            return Err(ShardFileError::NotShard { file: file.into() });
        }
        let (header, hash) = parse_header(&fields, &bad)?;
        let header_lines = fields.len() as u64;
        let mut rest = Vec::new();
        reader.read_to_end(&mut rest).map_err(read_err)?;
        if rows_hash(&rest) != hash {
            return Err(bad(
                header_lines,
                format!(
                    "the rows hash to {} but the header says {hash}: the file was changed, cut or damaged after it was written; rerun its shard",
                    rows_hash(&rest)
                ),
            ));
        }
        let mut csv = csv::ReaderBuilder::new().from_reader(&rest[..]);
        let columns = csv
            .headers()
            .map_err(|e| bad(header_lines + 1, e.to_string()))?;
        if columns.iter().ne(RESULT_HEADER) {
            return Err(bad(
                header_lines + 1,
                format!(
                    "the columns are not those of a study result: expected {}",
                    RESULT_HEADER.join(",")
                ),
            ));
        }
        let mut rows = Vec::new();
        let mut cells = CellRows::default();
        for record in csv.records() {
            let record = record.map_err(|e| {
                let line = e.position().map_or(0, |p| p.line()) + header_lines;
                bad(line, e.to_string())
            })?;
            let line = record.position().map_or(0, |p| p.line()) + header_lines;
            let key = check_row(
                &record,
                header.assignment.len(),
                &header.modes,
                &header.params,
            )
            .and_then(|key| cells.add(key, &record, line).map(|()| key))
            .map_err(|message| {
                bad(
                    line,
                    format!("{message}: the file is damaged; rerun its shard"),
                )
            })?;
            rows.push(ShardRow {
                cell: key.cell,
                key,
                record,
                line,
            });
        }
        Ok(ShardFile {
            file: file.into(),
            header,
            rows,
        })
    }
}

/// The header's fields, and the rows hash it states.
fn parse_header(
    fields: &[(String, String)],
    bad: &dyn Fn(u64, String) -> ShardFileError,
) -> Result<(ShardHeader, String), ShardFileError> {
    let get = |key: &str| {
        fields
            .iter()
            .position(|(k, _)| k == key)
            .map(|i| (i as u64 + 1, fields[i].1.as_str()))
            .ok_or_else(|| {
                bad(
                    fields.len() as u64,
                    format!("the header has no `# {key}:` line"),
                )
            })
    };
    let number = |key: &str| -> Result<usize, ShardFileError> {
        let (line, v) = get(key)?;
        v.parse()
            .map_err(|_| bad(line, format!("{key} = `{v}` is not a whole number")))
    };
    let (line, spec) = get("shard")?;
    let spec: ShardSpec = spec
        .parse()
        .map_err(|e: super::shard::ShardError| bad(line, e.to_string()))?;
    let cells = number("cells")?;
    let (line, text) = get("assignment")?;
    let assignment: Vec<usize> = text
        .split_whitespace()
        .map(|s| s.parse().ok().filter(|&k| (1..=spec.count).contains(&k)))
        .collect::<Option<_>>()
        .filter(|a: &Vec<usize>| a.len() == cells)
        .ok_or_else(|| {
            bad(
                line,
                format!(
                    "the assignment must list {cells} shard numbers from 1 to {}",
                    spec.count
                ),
            )
        })?;
    let (line, text) = get("modes")?;
    let modes: Vec<usize> = text
        .split_whitespace()
        .map(|m| m.parse().ok())
        .collect::<Option<_>>()
        .filter(|m: &Vec<usize>| !m.is_empty())
        .ok_or_else(|| {
            bad(
                line,
                "modes must list the study's modes, e.g. `1 2 3`".into(),
            )
        })?;
    let (line, text) = get("params")?;
    let params: Vec<String> = serde_json::from_str(text)
        .ok()
        .filter(|p: &Vec<String>| !p.is_empty())
        .ok_or_else(|| {
            bad(
                line,
                "params must list the study's parameters as JSON, e.g. `[\"k1\",\"k2\"]`".into(),
            )
        })?;
    let rows_per_cell = number("rows per cell")?;
    if rows_per_cell != modes.len() * params.len() {
        let (line, _) = get("rows per cell")?;
        return Err(bad(
            line,
            format!(
                "rows per cell = {rows_per_cell} but the header lists {} mode(s) and {} parameter(s)",
                modes.len(),
                params.len()
            ),
        ));
    }
    let header = ShardHeader {
        spec,
        study: get("study")?.1.into(),
        fingerprint: get("fingerprint")?.1.into(),
        tool: get("tool")?.1.into(),
        rows_per_cell,
        assignment,
        modes,
        params,
    };
    Ok((header, get("rows hash")?.1.into()))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_header_reads_back_and_a_bad_one_names_its_line() {
        let header = ShardHeader {
            spec: ShardSpec { index: 2, count: 3 },
            study: "s".into(),
            fingerprint: "00ff".into(),
            tool: "jointid 9".into(),
            rows_per_cell: 8,
            assignment: vec![1, 2, 3, 2],
            modes: vec![1, 2, 3, 4],
            params: vec!["k1".into(), "k 2,\"x\"".into()],
        };
        let mut bytes = Vec::new();
        write_shard(&mut bytes, &header, &[], &[], "uniform").unwrap();
        let back = ShardFile::from_reader(&bytes[..], Path::new("a.csv")).unwrap();
        assert_eq!(back.header, header);
        assert!(back.rows.is_empty());
        let text = String::from_utf8(bytes).unwrap();
        let bad = text.replace("# cells: 4", "# cells: 5");
        let e = ShardFile::from_reader(bad.as_bytes(), Path::new("a.csv")).unwrap_err();
        assert_eq!(
            e.to_string(),
            "a.csv:7: the assignment must list 5 shard numbers from 1 to 3"
        );
        let bad = text.replace("cell,mode", "cell,mood");
        let e = ShardFile::from_reader(bad.as_bytes(), Path::new("a.csv")).unwrap_err();
        assert!(
            e.to_string().starts_with("a.csv:10: the rows hash to "),
            "{e}"
        );
    }

    #[test]
    fn not_a_shard_is_named() {
        let e = ShardFile::from_reader(&b"cell,mode\n"[..], Path::new("x.csv")).unwrap_err();
        assert!(matches!(e, ShardFileError::NotShard { .. }), "{e}");
    }
}
