//! Universal-file layouts built by hand from the dataset descriptions (UC-SDRL / I-DEAS
//! "Universal Dataset Number 58", the "Binary 58 Universal File Format", 55, 15, 2411, 164),
//! independently of the reader: binary 58b in both byte orders, single and double precision,
//! with the abscissa in single precision (the UC-SDRL layout; pyuff's layout with a double
//! abscissa is covered by the pyuff fixture); ASCII variants real files take (blank-separated
//! fields, run-together values, zero padding, Fortran exponents); and the error messages of
//! malformed files.

use std::path::Path;

use faer::c64;
use jointid::uff::{
    Abscissa, Encoding, FunctionType, Precision, Problem, Record, UffError, Values, read,
};

/// The ASCII header of a dataset 58 (records 1-11) for the given record 7 fields.
fn header_58(ord_type: u32, n: usize, even: bool, start: f64, step: f64) -> String {
    let mut s = String::new();
    for id in ["hand-built", "NONE", "NONE", "NONE", "NONE"] {
        s += &format!("{id:<80}\n");
    }
    s += "    4         1    0         0       NONE         7   3       NONE         9  -3\n";
    s += &format!(
        "{ord_type:>10}{n:>10}{:>10}{start:>13.5e}{step:>13.5e}{:>13.5e}\n",
        u8::from(even),
        0.0
    );
    s += "        18    0    0    0 Frequency            Hz                  \n";
    s += "        12    0    0    0 Acceleration         m/s^2/V             \n";
    s += "         0    0    0    0 NONE                 NONE                \n";
    s += "         0    0    0    0 NONE                 NONE                \n";
    s
}

fn only_function(bytes: &[u8]) -> jointid::uff::Function {
    let records = read(bytes, Path::new("hand.uff")).unwrap();
    assert_eq!(records.len(), 1);
    match records.into_iter().next().unwrap() {
        Record::Function(f) => f,
        other => panic!("function expected, got {other:?}"),
    }
}

#[test]
fn binary_big_endian_real_single_even() {
    let y = [1.5f32, -2.25, 1e-3, 3.0e5, 0.0, -7.125, 42.0];
    let mut file = format!(
        "    -1\n    58b{:>6}{:>6}{:>12}{:>12}{:>6}{:>6}{:>12}{:>12}\n",
        2,
        2,
        11,
        4 * y.len(),
        0,
        0,
        0,
        0
    )
    .into_bytes();
    file.extend(header_58(2, y.len(), true, 10.0, 0.5).bytes());
    for v in y {
        file.extend(v.to_be_bytes());
    }
    file.extend(b"    -1\n");
    let f = only_function(&file);
    assert_eq!(f.encoding, Encoding::Binary { big_endian: true });
    assert_eq!(f.precision, Precision::Single);
    assert_eq!(
        f.abscissa,
        Abscissa::Even {
            start: 10.0,
            step: 0.5
        }
    );
    let expected: Vec<f64> = y.iter().map(|&v| f64::from(v)).collect();
    assert_eq!(f.ordinate, Values::Real(expected));
    assert_eq!((f.response.node, f.response.direction), (7, 3));
    assert_eq!((f.reference.node, f.reference.direction), (9, -3));
    assert_eq!(f.ordinate_axis.units, "m/s^2/V");
}

#[test]
fn binary_little_endian_complex_double_uneven_with_single_abscissa_and_crlf() {
    // UC-SDRL layout: x single precision, then Re, Im double; CRLF header lines; the closing
    // -1 after a line terminator. A payload byte equal to '\n' must not end the data.
    let x = [0.0f32, 0.5, 1.25, 10.0];
    let y = [
        c64::new(1.0, -1.0),
        c64::new(f64::from_bits(0x0A0A_0A0A_0A0A_0A0A), 2.0),
        c64::new(-3.5, 0.0),
        c64::new(1e-300, 1e300),
    ];
    let n_bytes = x.len() * 20;
    let mut file = format!("    -1\r\n    58b     1     2          11{n_bytes:>12}     0     0           0           0\r\n")
        .into_bytes();
    file.extend(
        header_58(6, x.len(), false, 0.0, 0.0)
            .replace('\n', "\r\n")
            .bytes(),
    );
    for (xi, yi) in x.iter().zip(&y) {
        file.extend(xi.to_le_bytes());
        file.extend(yi.re.to_le_bytes());
        file.extend(yi.im.to_le_bytes());
    }
    file.extend(b"\r\n    -1\r\n    -1\r\n  2412\r\n    -1\r\n");
    let records = read(&file, Path::new("hand.uff")).unwrap();
    let Record::Function(f) = &records[0] else {
        panic!("function expected")
    };
    assert_eq!(f.encoding, Encoding::Binary { big_endian: false });
    assert_eq!(f.precision, Precision::Double);
    assert_eq!(
        f.abscissa,
        Abscissa::Uneven(x.iter().map(|&v| f64::from(v)).collect())
    );
    assert_eq!(f.ordinate, Values::Complex(y.to_vec()));
    // The dataset after the binary one, on the line the file's text gives it: 2 + 11 header
    // lines, the payload (holding 8 + 8 newline bytes), the terminator, `-1`, `-1`, `2412`.
    let newlines = file[..file.len() - 10]
        .iter()
        .filter(|&&b| b == b'\n')
        .count();
    assert_eq!(
        records[1],
        Record::Other {
            kind: 2412,
            first_line: newlines + 1
        }
    );
}

#[test]
fn ascii_variants_of_real_files() {
    // Fields by blanks off their columns, D exponents, a three-digit exponent without letter,
    // uneven real double with a zero-padded last line, values run together in their columns.
    let mut s = String::from("    -1\n    58\nID\nNONE\nNONE\nNONE\nNONE\n");
    s += "1 0 0 0 NONE 12 1 NONE 0 0\n";
    s += "4 3 0\n";
    s += "17 0 0 0 Time s\n12 0 0 0 NONE m/s^2\n0 0 0 0\n0 0 0 0 NONE NONE\n";
    s += "  1.00000E-03 -1.500000000000D+00  2.00000E-03 2.5000000000-100\n";
    s += "  3.00000E-03-1.000000000000E+00  0.00000E+00  0.000000000000E+00\n";
    s += "    -1\n";
    let f = only_function(s.as_bytes());
    assert_eq!(f.function_type, FunctionType::TimeResponse);
    assert_eq!(f.abscissa, Abscissa::Uneven(vec![1e-3, 2e-3, 3e-3]));
    assert_eq!(f.ordinate, Values::Real(vec![-1.5, 2.5e-100, -1.0]));
    assert_eq!(
        (
            f.abscissa_axis.label.as_str(),
            f.abscissa_axis.units.as_str()
        ),
        ("Time", "s")
    );
    assert_eq!(f.ordinate_axis.units, "m/s^2");
    assert_eq!(f.response.node, 12);
}

#[test]
fn other_datasets_are_kept_by_number() {
    let s = "    -1\n  2412\n         1        11         2         1         7         2\n    -1\n\
             \n    -1\n    18\n         1         0         0         8         1\nSYS1\n    -1\n";
    let records = read(s.as_bytes(), Path::new("x.uff")).unwrap();
    assert_eq!(
        records,
        [
            Record::Other {
                kind: 2412,
                first_line: 2
            },
            Record::Other {
                kind: 18,
                first_line: 7
            }
        ]
    );
}

fn error(text: &str) -> (String, UffError) {
    let err = read(text.as_bytes(), Path::new("frf.uff")).unwrap_err();
    (err.to_string(), err)
}

/// A file of two nodes then a dataset 58 with `data` as record 12.
fn file_with_58(record7: &str, data: &str) -> String {
    let mut s =
        String::from("    -1\n    15\n 1 0 0 1 0.0 0.0 0.0\n 2 0 0 1 1.0 0.0 0.0\n    -1\n");
    s += "    -1\n    58\nID\nNONE\nNONE\nNONE\nNONE\n";
    s += "    4         0    0         0       NONE         1   2       NONE       100   2\n";
    s += record7;
    s += "        18    0    0    0 NONE                 NONE                \n";
    s += "        12    0    0    0 NONE                 m/s^2/V             \n";
    s += "         0    0    0    0 NONE                 NONE                \n";
    s += "         0    0    0    0 NONE                 NONE                \n";
    s += data;
    s += "    -1\n";
    s
}

#[test]
fn error_messages_name_file_record_line_and_what_was_expected() {
    let r7 = "         4         8         1  0.00000e+00  5.00000e-01  0.00000e+00\n";
    // Lines: 1-5 the 15, 6 `-1`, 7 `58`, 8-12 ID lines, 13 record 6, 14 record 7, 15-18
    // records 8-11, 19.. data.
    let (msg, _) = error(&file_with_58(r7, "1 2 3 4\n"));
    assert_eq!(
        msg,
        "frf.uff: record 2 (dataset 58), line 20: expected 8 ordinate values, the record ends after 4"
    );
    let (msg, _) = error(&file_with_58(r7, "1 2 3 4\n5 6 7 8\n9\n"));
    assert_eq!(
        msg,
        "frf.uff: record 2 (dataset 58), line 21: expected 8 ordinate values, found 9"
    );
    let (msg, _) = error(&file_with_58(r7, "1 2 3 4\n5 6 7 8 9\n"));
    assert_eq!(
        msg,
        "frf.uff: record 2 (dataset 58), line 20: expected 8 ordinate values, found 9"
    );
    let (msg, _) = error(&file_with_58(r7, "1 2 3 4\n5 6 x7 8\n"));
    assert_eq!(
        msg,
        "frf.uff: record 2 (dataset 58), line 20: data value (record 12): \"x7\" is not a finite real number"
    );
    let bad_type = "         3         8         1  0.00000e+00  5.00000e-01  0.00000e+00\n";
    let (msg, _) = error(&file_with_58(bad_type, "1 2 3 4\n5 6 7 8\n"));
    assert_eq!(
        msg,
        "frf.uff: record 2 (dataset 58), line 14: ordinate data type (record 7) = 3 is not a known code: \
         allowed 2 real single, 4 real double, 5 complex single, 6 complex double"
    );
    // Zero padding of the last line is accepted.
    let ok = file_with_58(r7, "1 2 3 4\n5 6 7 8 0 0\n");
    assert!(read(ok.as_bytes(), Path::new("frf.uff")).is_ok());
}

#[test]
fn structural_errors() {
    let r7 = "         4         2         1  0.00000e+00  5.00000e-01  0.00000e+00\n";
    let unterminated = file_with_58(r7, "1 2\n");
    let unterminated = &unterminated[..unterminated.len() - "    -1\n".len()];
    let (msg, err) = error(unterminated);
    assert!(
        matches!(
            err,
            UffError::Record {
                record: 2,
                dataset: 58,
                line: 19,
                problem: Problem::Unterminated,
                ..
            }
        ),
        "{msg}"
    );
    let (msg, _) = error("    -1\n    15\n    -1\n  1 0 0 0 1.0 2.0 3.0\n");
    assert_eq!(
        msg,
        "frf.uff: line 4: expected a `-1` line opening a dataset, found \"  1 0 0 0 1.0 2.0 3.0\""
    );
    let (msg, _) = error("    -1\n    58\nID\nNONE\n    -1\n");
    assert_eq!(
        msg,
        "frf.uff: record 1 (dataset 58), line 5: the record ends before the ID lines (records 1-5)"
    );
    let (msg, _) = error(
        "    -1\n    58b     1     2          11         800     0     0           0           0\nID\n",
    );
    assert_eq!(
        msg,
        "frf.uff: record 1 (dataset 58), line 3: the record ends before the ASCII header lines of the binary dataset"
    );
    let (msg, _) = error("    -1\n    15\n 1 0 0 1 0.0 0.0\n    -1\n");
    assert_eq!(
        msg,
        "frf.uff: record 1 (dataset 15), line 3: node (record 1) = \" 1 0 0 1 0.0 0.0\" is invalid: \
         it must hold label, 2 coordinate systems, color, X, Y, Z (4I10,3E13.5)"
    );
}

#[test]
fn truncated_binary_payload_is_an_error() {
    let mut file = b"    -1\n    58b     1     2          11          64     0     0           0           0\n".to_vec();
    file.extend(header_58(4, 8, true, 0.0, 1.0).bytes());
    file.extend([0u8; 40]);
    let (msg, _) = error(&String::from_utf8_lossy(&file));
    assert_eq!(
        msg,
        "frf.uff: record 1 (dataset 58), line 14: expected 64 bytes of binary data, the record ends after 40"
    );
    file.extend([0u8; 24]);
    file.extend(b"garbage\n");
    let (msg, _) = error(&String::from_utf8_lossy(&file));
    assert_eq!(
        msg,
        "frf.uff: record 1 (dataset 58), line 14: no closing `-1` after the 64 bytes of binary data \
         that the header declares (checked layouts: 64)"
    );
}

#[test]
fn mode_shape_with_run_together_values_and_an_ideas_id_line() {
    // After the form of a commercial export in pyuff's test data: complex mode (analysis 3),
    // 3 DOF (characteristic 2), complex data (5), values run together in E13.5 columns.
    let s = "    -1\n    55\nTEST\nNONE\nNONE\nNONE\n    999999         3         8        13\n\
             \x20        1         3         2         8         5         3\n\
             \x20        2         6         0         1\n\
             -1.111111E-01 4.111111E+01 4.111111E+03-3.111111E+03-1.111110E+05-2.111110E+05\n\
             \x20   111111\n\
             \x200.000000E+00 0.000000E+00 1.111111E-01 9.111111E-02 7.111111E-03 4.111111E-03\n    -1\n";
    let records = read(s.as_bytes(), Path::new("m.uff")).unwrap();
    let Record::ModeShape(m) = &records[0] else {
        panic!("mode shape expected")
    };
    assert_eq!(m.nodes, [111111]);
    assert_eq!(m.values_per_node, 3);
    let jointid::uff::Analysis::ComplexMode {
        eigenvalue,
        modal_a,
        modal_b,
        mode,
        ..
    } = m.analysis
    else {
        panic!("complex mode expected")
    };
    assert_eq!(mode, 1);
    assert_eq!(eigenvalue, c64::new(-1.111111E-01, 4.111111E+01));
    assert_eq!(modal_a, c64::new(4.111111E+03, -3.111111E+03));
    assert_eq!(modal_b, c64::new(-1.111110E+05, -2.111110E+05));
    assert_eq!(m.value(0, 2), Some(c64::new(7.111111E-03, 4.111111E-03)));
    assert_eq!(m.value(0, 3), None);
}

#[test]
fn even_abscissa_is_recognised_within_the_written_digits() {
    let text = file_with_58(
        "         4         2         1  0.00000e+00  5.00000e-01  0.00000e+00\n",
        "1 2\n",
    );
    let Some(Record::Function(mut f)) = read(text.as_bytes(), Path::new("f.uff")).unwrap().pop()
    else {
        panic!("function expected")
    };
    assert_eq!(f.even_abscissa(0.0), Some((0.0, 0.5)));
    // 1/3 Hz steps stored to 6 digits: even within 5e-6, not within 1e-7.
    let x: Vec<f64> = (0..100)
        .map(|i| {
            format!("{:.5e}", -5.0 + f64::from(i) / 3.0)
                .parse()
                .unwrap()
        })
        .collect();
    f.ordinate = Values::Real(vec![0.0; 100]);
    f.abscissa = Abscissa::Uneven(x.clone());
    let (start, step) = f.even_abscissa(5e-6).unwrap();
    assert_eq!(start, -5.0);
    assert!((step - 1.0 / 3.0).abs() < 1e-6);
    assert_eq!(f.even_abscissa(1e-7), None);
    // A real gap is not even.
    let mut gap = x;
    gap[50] += 0.01;
    f.abscissa = Abscissa::Uneven(gap);
    assert_eq!(f.even_abscissa(5e-6), None);
    f.abscissa = Abscissa::Uneven(vec![1.0]);
    assert_eq!(f.even_abscissa(5e-6), None);
}

/// 2100 lines of 0.0625 Hz from 0 Hz to 6 digits: the last written 131.188, line 1601
/// (100.0625) written 100.062. The step from the written span is off by 2.4e-7 Hz, which
/// with line 1601's own rounding puts it 8.8e-4 Hz from the line, more than its rounding
/// alone (5e-4 Hz): the tolerance is that of the three written values, not of one.
#[test]
fn an_even_axis_whose_last_line_is_rounded_is_even() {
    let text = file_with_58(
        "         4         2         1  0.00000e+00  5.00000e-01  0.00000e+00\n",
        "1 2\n",
    );
    let Some(Record::Function(mut f)) = read(text.as_bytes(), Path::new("f.uff")).unwrap().pop()
    else {
        panic!("function expected")
    };
    let x: Vec<f64> = (0..2100)
        .map(|i| format!("{:.5e}", f64::from(i) * 0.0625).parse().unwrap())
        .collect();
    assert_eq!((x[1601], x[2099]), (100.062, 131.188));
    f.ordinate = Values::Real(vec![0.0; x.len()]);
    f.abscissa = Abscissa::Uneven(x.clone());
    let (start, step) = f.even_abscissa(5e-6).expect("an even axis");
    assert_eq!(start, 0.0);
    assert!((step - 0.0625).abs() < 1e-6, "{step}");
    // a line missing in the middle is still uneven
    let mut gap = x;
    gap.remove(1000);
    f.ordinate = Values::Real(vec![0.0; gap.len()]);
    f.abscissa = Abscissa::Uneven(gap);
    assert_eq!(f.even_abscissa(5e-6), None);
}
