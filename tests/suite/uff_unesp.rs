//! The UNESP-BERT bolted cantilever (real measured FRFs, UFF 58 ASCII, and its geometry as
//! UFF 15) read through `jointid::uff`. The expected structure (8 datasets per file: 4 H1 FRFs,
//! function type 4, then 4 coherences, type 6; 8193 points from 0 to 512 Hz in 0.0625 Hz
//! steps; responses at nodes 1-4, reference node 100, all in direction 2; FRF units m/s^2/V)
//! comes from the data set's README and was confirmed by reading the files with grep/awk.
//! Sample values are checked against the file's text, split by blanks and parsed with
//! `str::parse`, independently of the reader's field logic.
//!
//! The data are not in the repository (licence CC BY-NC-SA): they are read from
//! `$CARGO_MANIFEST_DIR/../shared/data/unesp-bert/`. So the tests here are `#[ignore]`d (the summary
//! of `cargo test` counts them as ignored, never as passed without data); `.ci/run` runs them
//! with `--ignored` where the folder is present, and each skips, saying so, where it is absent.

use crate::common;

use std::path::PathBuf;

use jointid::uff::{
    Abscissa, Encoding, FunctionType, NodeFormat, Precision, Record, Values, read_path,
};

fn frf_files(dir: &PathBuf) -> Vec<PathBuf> {
    let mut files: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| {
            let name = p.file_name().unwrap().to_string_lossy().to_string();
            name.starts_with("frf_") && name.ends_with(".uff")
        })
        .collect();
    files.sort();
    files
}

/// The numbers of 1-based line `n` of a text, by blanks.
fn line_numbers(text: &str, n: usize) -> Vec<f64> {
    text.lines()
        .nth(n - 1)
        .unwrap()
        .split_whitespace()
        .map(|t| t.parse().unwrap())
        .collect()
}

/// 1-based line numbers of the first data line of each dataset 58: 12 lines after the line
/// holding `58` alone (5 ID lines, records 6-11).
fn data_starts(text: &str) -> Vec<usize> {
    let lines: Vec<&str> = text.lines().collect();
    (1..lines.len())
        .filter(|&i| lines[i].trim() == "58" && lines[i - 1].trim() == "-1")
        .map(|i| i + 1 + 12)
        .collect()
}

#[test]
#[ignore = "needs ../shared/data/unesp-bert (outside the project): .ci/run runs it where present"]
fn every_frf_file_reads_as_four_frfs_and_four_coherences() {
    let Some(dir) = common::unesp_dir() else {
        return;
    };
    let files = frf_files(&dir);
    assert_eq!(files.len(), 6, "six excitation levels");
    for file in files {
        let records = read_path(&file).unwrap();
        let text = std::fs::read_to_string(&file).unwrap();
        let starts = data_starts(&text);
        assert_eq!(records.len(), 8, "{}", file.display());
        assert_eq!(starts.len(), 8);
        for (k, (record, &start)) in records.iter().zip(&starts).enumerate() {
            let Record::Function(f) = record else {
                panic!("{}: record {} is not a function", file.display(), k + 1)
            };
            let frf = k < 4;
            assert_eq!(
                f.function_type,
                if frf {
                    FunctionType::Frf
                } else {
                    FunctionType::Coherence
                }
            );
            assert_eq!(f.len(), 8193);
            assert_eq!(
                (f.response.node, f.response.direction),
                (k as u64 % 4 + 1, 2)
            );
            assert_eq!((f.reference.node, f.reference.direction), (100, 2));
            assert_eq!(f.precision, Precision::Double);
            assert_eq!(f.encoding, Encoding::Ascii);
            assert_eq!(f.abscissa_axis.data_type, 18, "frequency");
            let units = if frf { "m/s^2/V" } else { "NONE" };
            assert_eq!(f.ordinate_axis.units, units);
            assert_eq!(f.ordinate.is_complex(), frf);
            // Uneven abscissa 0..512 Hz in 0.0625 Hz steps, stored to 6 significant digits.
            let Abscissa::Uneven(x) = &f.abscissa else {
                panic!("uneven abscissa expected")
            };
            for (i, &xi) in x.iter().enumerate() {
                let exact = i as f64 * 0.0625;
                assert!((xi - exact).abs() <= 5e-6 * exact, "x[{i}] = {xi}");
            }
            assert_eq!(x[8192], 512.0);
            assert_eq!(f.even_abscissa(5e-6), Some((0.0, 0.0625)));
            assert_eq!(
                f.even_abscissa(1e-7),
                None,
                "the 6-digit rounding is visible"
            );
            // Values against the text: FRF lines hold x, Re, Im; coherence lines two (x, y) pairs.
            let last = if frf { 8192 } else { 4096 };
            for offset in [0, 1, 2047, last] {
                let nums = line_numbers(&text, start + offset);
                match &f.ordinate {
                    Values::Complex(h) => {
                        assert_eq!(x[offset], nums[0]);
                        assert_eq!((h[offset].re, h[offset].im), (nums[1], nums[2]));
                    }
                    Values::Real(c) => {
                        for (j, pair) in nums.chunks(2).enumerate() {
                            assert_eq!((x[2 * offset + j], c[2 * offset + j]), (pair[0], pair[1]));
                        }
                    }
                }
            }
        }
    }
}

#[test]
#[ignore = "needs ../shared/data/unesp-bert (outside the project): .ci/run runs it where present"]
fn first_value_of_the_first_frf_is_the_files_text() {
    let Some(dir) = common::unesp_dir() else {
        return;
    };
    let records = read_path(&dir.join("frf_0p05V.uff")).unwrap();
    let Record::Function(f) = &records[0] else {
        panic!("function expected")
    };
    // Line 14 of the file: "  0.00000e+00   4.51675354004e+02   0.00000000000e+00"
    let Values::Complex(h) = &f.ordinate else {
        panic!("complex FRF expected")
    };
    assert_eq!((h[0].re, h[0].im), (451.675354004, 0.0));
    assert_eq!((h[1].re, h[1].im), (-124.947723389, 268.566528320));
    assert_eq!(f.id_lines[0], "H1 Acc1/shaker voltage, 0p05 V random");
}

#[test]
#[ignore = "needs ../shared/data/unesp-bert (outside the project): .ci/run runs it where present"]
fn geometry_holds_the_five_nodes_of_the_readme() {
    let Some(dir) = common::unesp_dir() else {
        return;
    };
    let records = read_path(&dir.join("geometry.uff")).unwrap();
    assert_eq!(records.len(), 1);
    let Record::Nodes(nodes) = &records[0] else {
        panic!("nodes expected")
    };
    assert_eq!(nodes.format, NodeFormat::Single15);
    let labels: Vec<u64> = nodes.nodes.iter().map(|n| n.label).collect();
    assert_eq!(labels, [1, 2, 3, 4, 100]);
    let x: Vec<f64> = nodes.nodes.iter().map(|n| n.coordinates[0]).collect();
    assert_eq!(x, [0.5, 0.357, 0.176, 0.028, 0.085]);
    for n in &nodes.nodes {
        assert_eq!((n.coordinates[1], n.coordinates[2]), (0.0, 0.0));
        assert_eq!((n.definition_cs, n.displacement_cs, n.color), (0, 0, 1));
    }
}
