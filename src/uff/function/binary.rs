//! The payload of a binary dataset 58b: raw IEEE numbers of the ordinate's precision, point
//! by point x (uneven only), Re, Im (complex only), in the byte order of the header.
//!
//! The UC-SDRL description ("The Binary 58 Universal File Format") says the abscissa is always
//! single precision; pyuff writes it in the ordinate's precision. For an uneven abscissa of a
//! double-precision function both layouts are possible: [`lengths`] gives both payload
//! lengths, the splitter takes the one after which the closing `-1` stands, and [`values`]
//! reads the layout that length implies.

use super::Precision;
use super::records::{DataForm, data_form};
use crate::uff::error::{Located, Problem};
use crate::uff::fields::Line;

/// Payload lengths (bytes) of the 58b layouts that record 7 allows: for an uneven abscissa,
/// x in the ordinate's precision (pyuff) first, then x single precision (UC-SDRL).
pub(crate) fn lengths(header: &[Line], number_line: usize) -> Result<Vec<usize>, Located> {
    if header.len() != 11 {
        return Err(Located::new(
            number_line,
            Problem::Invalid {
                field: "number of ASCII lines (58b header)",
                value: header.len().to_string(),
                allowed: "dataset 58 has 11 header lines",
            },
        ));
    }
    let form = data_form(&header[6])?;
    let size = if form.precision == Precision::Double {
        8
    } else {
        4
    };
    let ordinate = size * (1 + usize::from(form.complex));
    let per_point: Vec<usize> = if form.even {
        vec![ordinate]
    } else if size == 4 {
        vec![ordinate + 4]
    } else {
        vec![ordinate + size, ordinate + 4]
    };
    per_point
        .into_iter()
        .map(|p| {
            p.checked_mul(form.count).ok_or(Located::new(
                header[6].number,
                Problem::Invalid {
                    field: "number of points (record 7)",
                    value: form.count.to_string(),
                    allowed: "the binary payload length overflows",
                },
            ))
        })
        .collect()
}

/// The flat values of a 58b payload, whose length the splitter matched to one layout.
pub(super) fn values(
    form: &DataForm,
    bytes: &[u8],
    big_endian: bool,
    line: usize,
) -> Result<Vec<f64>, Located> {
    let size = if form.precision == Precision::Double {
        8
    } else {
        4
    };
    let ordinate = size * (1 + usize::from(form.complex));
    let x_size = if form.even || Some(bytes.len()) == form.count.checked_mul(ordinate + size) {
        size
    } else {
        4
    };
    let point = ordinate + if form.even { 0 } else { x_size };
    let needed = form.count.saturating_mul(point);
    if bytes.len() < needed {
        return Err(Located::new(
            line,
            Problem::TooFew {
                what: "bytes of binary data",
                expected: needed,
                found: bytes.len(),
            },
        ));
    }
    let mut flat = Vec::with_capacity(bytes.len() / 4);
    let mut pos = 0;
    let mut take = |n: usize| -> f64 {
        let b = &bytes[pos..pos + n];
        pos += n;
        match (n, big_endian) {
            (4, false) => f64::from(f32::from_le_bytes([b[0], b[1], b[2], b[3]])),
            (4, true) => f64::from(f32::from_be_bytes([b[0], b[1], b[2], b[3]])),
            (_, false) => f64::from_le_bytes(b.try_into().unwrap_or([0; 8])),
            (_, true) => f64::from_be_bytes(b.try_into().unwrap_or([0; 8])),
        }
    };
    for _ in 0..form.count {
        if !form.even {
            flat.push(take(x_size));
        }
        for _ in 0..1 + usize::from(form.complex) {
            flat.push(take(size));
        }
    }
    if let Some(i) = flat.iter().position(|v| !v.is_finite()) {
        return Err(Located::new(
            line,
            Problem::Invalid {
                field: "binary data value (record 12)",
                value: format!(
                    "{} (value {} of point {})",
                    flat[i],
                    i % form.per_point() + 1,
                    i / form.per_point() + 1
                ),
                allowed: "it must be finite",
            },
        ));
    }
    Ok(flat)
}
