//! Datasets 15 ("Nodes") and 2411 ("Nodes - Double Precision"): node numbers, coordinate
//! systems and coordinates.
//!
//! Dataset 15 has one line per node, `Format(4I10,1P3E13.5)`: node label, definition
//! coordinate system, displacement coordinate system, color, then X, Y, Z in the definition
//! system. Dataset 2411 has two lines per node: `Format(4I10)` (label, export coordinate
//! system, displacement coordinate system, color), then `Format(1P3D25.16)` (X, Y, Z).
//!
//! Layout after the I-DEAS / UC-SDRL descriptions of datasets 15 and 2411 (as reproduced in
//! pyuff's `dataset_15.py` and `dataset_2411.py`).

use super::error::{Located, Problem};
use super::fields::{Cursor, Line, integer, real};
use super::split::RawDataset;

/// Which dataset the nodes came from (and are written as).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NodeFormat {
    /// Dataset 15, single precision coordinates (`E13.5`).
    Single15,
    /// Dataset 2411, double precision coordinates (`D25.16`).
    Double2411,
}

/// One node.
#[derive(Debug, Clone, PartialEq)]
pub struct Node {
    /// Node label.
    pub label: u64,
    /// Definition (15) or export (2411) coordinate system number.
    pub definition_cs: u64,
    /// Displacement coordinate system number.
    pub displacement_cs: u64,
    /// Color.
    pub color: i64,
    /// X, Y, Z in the definition coordinate system.
    pub coordinates: [f64; 3],
}

/// The nodes of one dataset 15 or 2411.
#[derive(Debug, Clone, PartialEq)]
pub struct Nodes {
    /// The dataset they came from.
    pub format: NodeFormat,
    /// The nodes, in file order.
    pub nodes: Vec<Node>,
}

/// The four integers of a node, by blanks or by `I10` columns.
fn node_ints(line: &Line, ints: &[&str]) -> Result<(u64, u64, u64, i64), Located> {
    let at = |p| Located::new(line.number, p);
    let fields = [
        "node label",
        "definition coordinate system",
        "displacement coordinate system",
        "color",
    ];
    let mut v = [0i64; 4];
    for ((slot, text), field) in v.iter_mut().zip(ints).zip(fields) {
        *slot = if text.is_empty() {
            0
        } else {
            integer(text, field).map_err(at)?
        };
    }
    let label = |i: usize| {
        u64::try_from(v[i]).map_err(|_| {
            at(Problem::Invalid {
                field: fields[i],
                value: v[i].to_string(),
                allowed: "it must be >= 0",
            })
        })
    };
    Ok((label(0)?, label(1)?, label(2)?, v[3]))
}

/// The fields of a line: by blanks when there are `n`, else by the columns `widths`.
fn split_fields<'t>(text: &'t str, n: usize, widths: &[usize]) -> Vec<&'t str> {
    let tokens: Vec<&str> = text.split_whitespace().collect();
    if tokens.len() == n {
        return tokens;
    }
    let mut start = 0;
    widths
        .iter()
        .map(|&w| {
            let f = super::fields::column(text, start, w);
            start += w;
            f
        })
        .collect()
}

/// A field error on a line that does not have the `n` blank-separated fields of its format
/// becomes a layout error naming the format.
fn layout_error(
    e: Located,
    line: &Line,
    n: usize,
    field: &'static str,
    layout: &'static str,
) -> Located {
    if line.text.split_whitespace().count() == n {
        return e;
    }
    Located::new(
        line.number,
        Problem::Invalid {
            field,
            value: format!("{:?}", line.text.trim_end()),
            allowed: layout,
        },
    )
}

fn coordinates(line: &Line, fields: &[&str]) -> Result<[f64; 3], Located> {
    let mut xyz = [0.0; 3];
    for ((slot, text), field) in xyz.iter_mut().zip(fields).zip(["X", "Y", "Z"]) {
        if text.is_empty() {
            return Err(Located::new(
                line.number,
                Problem::Truncated { what: field },
            ));
        }
        *slot = real(text, field).map_err(|p| Located::new(line.number, p))?;
    }
    Ok(xyz)
}

/// Reads a dataset 15.
pub(crate) fn parse_15(ds: &RawDataset) -> Result<Nodes, Located> {
    let mut cursor = Cursor::new(&ds.lines, ds.end_line);
    let mut nodes = Vec::new();
    let widths = [10, 10, 10, 10, 13, 13, 13];
    while let Some(line) = cursor.next_non_blank() {
        let f = split_fields(&line.text, 7, &widths);
        let (label, definition_cs, displacement_cs, color, coordinates) = node_ints(line, &f[..4])
            .and_then(|(l, d, c, k)| Ok((l, d, c, k, coordinates(line, &f[4..7])?)))
            .map_err(|e| {
                layout_error(
                    e,
                    line,
                    7,
                    "node (record 1)",
                    "it must hold label, 2 coordinate systems, color, X, Y, Z (4I10,3E13.5)",
                )
            })?;
        nodes.push(Node {
            label,
            definition_cs,
            displacement_cs,
            color,
            coordinates,
        });
    }
    Ok(Nodes {
        format: NodeFormat::Single15,
        nodes,
    })
}

/// Reads a dataset 2411.
pub(crate) fn parse_2411(ds: &RawDataset) -> Result<Nodes, Located> {
    let mut cursor = Cursor::new(&ds.lines, ds.end_line);
    let mut nodes = Vec::new();
    while let Some(line) = cursor.next_non_blank() {
        let f = split_fields(&line.text, 4, &[10, 10, 10, 10]);
        let (label, definition_cs, displacement_cs, color) = node_ints(line, &f).map_err(|e| {
            layout_error(
                e,
                line,
                4,
                "node (record 1)",
                "it must hold label, 2 coordinate systems, color (4I10)",
            )
        })?;
        let coords = cursor.next("the coordinates of the node (record 2)")?;
        let c = split_fields(&coords.text, 3, &[25, 25, 25]);
        let coordinates = coordinates(coords, &c).map_err(|e| {
            layout_error(
                e,
                coords,
                3,
                "node coordinates (record 2)",
                "it must hold X, Y, Z (3D25.16)",
            )
        })?;
        nodes.push(Node {
            label,
            definition_cs,
            displacement_cs,
            color,
            coordinates,
        });
    }
    Ok(Nodes {
        format: NodeFormat::Double2411,
        nodes,
    })
}
