//! Universal files written by pyuff (the peer an engineer would otherwise use), read by
//! `jointid::uff`. The fixtures and the JSON of the inputs given to pyuff come from
//! `scripts/make_uff_fixture.py` (pyuff 2.5.8); every value read is compared with the input
//! rounded to the significant digits pyuff writes it with (the JSON says how many), so equality
//! is exact: nothing here is a number read back by our own reader.

use std::path::Path;

use faer::c64;
use jointid::uff::{
    Abscissa, Analysis, DataCharacteristic, Encoding, FunctionType, NodeFormat, Precision, Record,
    UnitSystem, Values, read,
};
use serde_json::Value;

fn fixture(name: &str) -> (Vec<u8>, Value) {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/uff");
    let bytes = std::fs::read(dir.join(format!("{name}.uff"))).unwrap();
    let json = std::fs::read_to_string(dir.join(format!("{name}.json"))).unwrap();
    (bytes, serde_json::from_str(&json).unwrap())
}

/// `v` rounded to `digits` significant digits, as `%.{digits-1}e` prints it.
fn round(v: f64, digits: usize) -> f64 {
    format!("{:.*e}", digits - 1, v).parse().unwrap()
}

fn strings(v: &Value) -> Vec<f64> {
    v.as_array()
        .unwrap()
        .iter()
        .map(|s| s.as_str().unwrap().parse().unwrap())
        .collect()
}

fn digits(v: &Value) -> usize {
    v["digits"].as_u64().unwrap() as usize
}

/// The real inputs of `v`, rounded to the digits written.
fn reals(v: &Value) -> Vec<f64> {
    strings(&v["values"])
        .into_iter()
        .map(|x| round(x, digits(v)))
        .collect()
}

fn complexes(v: &Value) -> Vec<c64> {
    let d = digits(v);
    strings(&v["re"])
        .into_iter()
        .zip(strings(&v["im"]))
        .map(|(re, im)| c64::new(round(re, d), round(im, d)))
        .collect()
}

fn int(v: &Value) -> i64 {
    v.as_i64().unwrap()
}

fn check_function(record: &Record, e: &Value, encoding: Encoding) {
    let Record::Function(f) = record else {
        panic!("function expected, got {record:?}")
    };
    assert_eq!(f.id_lines[0], e["id1"].as_str().unwrap());
    assert_eq!(
        f.function_type,
        FunctionType::from_code(int(&e["func_type"]) as i32)
    );
    assert_eq!(f.response.node as i64, int(&e["rsp_node"]));
    assert_eq!(i64::from(f.response.direction), int(&e["rsp_dir"]));
    assert_eq!(f.response.entity, e["rsp_ent_name"].as_str().unwrap());
    assert_eq!(f.reference.node as i64, int(&e["ref_node"]));
    assert_eq!(i64::from(f.reference.direction), int(&e["ref_dir"]));
    assert_eq!(f.encoding, encoding);
    let double = e["double"].as_bool().unwrap();
    assert_eq!(
        f.precision,
        if double {
            Precision::Double
        } else {
            Precision::Single
        }
    );
    let axes = [
        (&f.abscissa_axis, &e["abscissa_axis"]),
        (&f.ordinate_axis, &e["ordinate_axis"]),
        (&f.denominator_axis, &e["denominator_axis"]),
    ];
    for (axis, expected) in axes {
        assert_eq!(i64::from(axis.data_type), int(&expected[0]));
        assert_eq!(axis.label, expected[1].as_str().unwrap());
        assert_eq!(axis.units, expected[2].as_str().unwrap());
    }
    let x = strings(&e["x"]["values"]);
    match (&f.abscissa, int(&e["abscissa_spacing"])) {
        (Abscissa::Even { start, step }, 1) => {
            // pyuff writes x[0] and x[1] - x[0] as %13.5e.
            assert_eq!(*start, round(x[0], 6));
            assert_eq!(*step, round(x[1] - x[0], 6));
        }
        (Abscissa::Uneven(xs), 0) => assert_eq!(*xs, reals(&e["x"])),
        (a, s) => panic!("abscissa {a:?} for spacing {s}"),
    }
    match &f.ordinate {
        Values::Real(y) => assert_eq!(*y, reals(&e["data"])),
        Values::Complex(y) => assert_eq!(*y, complexes(&e["data"])),
    }
    assert_eq!(f.len(), x.len());
}

fn check_mixed(records: &[Record], expected: &[Value]) {
    assert_eq!(records.len(), expected.len());
    for (record, e) in records.iter().zip(expected) {
        match int(&e["type"]) {
            151 => {
                let Record::Header(h) = record else {
                    panic!("header expected")
                };
                assert_eq!(h.model_file, e["model_file"].as_str().unwrap());
                assert_eq!(h.description, e["description"].as_str().unwrap());
                assert_eq!(h.program, e["program"].as_str().unwrap());
            }
            164 => {
                let Record::Units(u) = record else {
                    panic!("units expected")
                };
                assert_eq!(
                    u.system,
                    UnitSystem::from_code(int(&e["units_code"])).unwrap()
                );
                assert_eq!(u.system, UnitSystem::MillimeterMillinewton);
                assert_eq!(u.description, e["description"].as_str().unwrap());
                assert_eq!(u.temperature_mode, Some(int(&e["temp_mode"]) as i32));
                let f = reals(&e["factors"]);
                assert_eq!(
                    [u.length, u.force, u.temperature, u.temperature_offset],
                    f[..]
                );
            }
            kind @ (15 | 2411) => {
                let Record::Nodes(n) = record else {
                    panic!("nodes expected")
                };
                let format = if kind == 15 {
                    NodeFormat::Single15
                } else {
                    NodeFormat::Double2411
                };
                assert_eq!(n.format, format);
                let xyz = reals(&e["xyz"]);
                assert_eq!(n.nodes.len(), xyz.len() / 3);
                for (i, node) in n.nodes.iter().enumerate() {
                    assert_eq!(node.label as i64, int(&e["labels"][i]));
                    assert_eq!(node.definition_cs as i64, int(&e["def_cs"][i]));
                    assert_eq!(node.displacement_cs as i64, int(&e["disp_cs"][i]));
                    assert_eq!(node.color, int(&e["color"][i]));
                    assert_eq!(node.coordinates[..], xyz[3 * i..3 * i + 3]);
                }
            }
            58 => check_function(record, e, Encoding::Ascii),
            55 => {
                let Record::ModeShape(s) = record else {
                    panic!("mode shape expected")
                };
                assert_eq!(i64::from(s.characteristic.code()), int(&e["data_ch"]));
                assert_eq!(i64::from(s.specific_data_type), int(&e["spec_data_type"]));
                assert_eq!(s.values_per_node as i64, int(&e["ndv"]));
                let nodes: Vec<i64> = s.nodes.iter().map(|&n| n as i64).collect();
                let expected_nodes: Vec<i64> =
                    e["nodes"].as_array().unwrap().iter().map(int).collect();
                assert_eq!(nodes, expected_nodes);
                let p = reals(&e["params"]);
                match (&s.analysis, int(&e["analysis_type"])) {
                    (
                        Analysis::NormalMode {
                            load_case,
                            mode,
                            frequency_hz,
                            modal_mass,
                            viscous_damping,
                            hysteretic_damping,
                        },
                        2,
                    ) => {
                        assert_eq!(
                            (*load_case, *mode),
                            (int(&e["load_case"]), int(&e["mode_n"]))
                        );
                        assert_eq!(
                            [
                                *frequency_hz,
                                *modal_mass,
                                *viscous_damping,
                                *hysteretic_damping
                            ],
                            p[..]
                        );
                    }
                    (
                        Analysis::ComplexMode {
                            second_order: false,
                            load_case,
                            mode,
                            eigenvalue,
                            modal_a,
                            modal_b,
                        },
                        3,
                    ) => {
                        assert_eq!(
                            (*load_case, *mode),
                            (int(&e["load_case"]), int(&e["mode_n"]))
                        );
                        assert_eq!(*eigenvalue, c64::new(p[0], p[1]));
                        assert_eq!(*modal_a, c64::new(p[2], p[3]));
                        assert_eq!(*modal_b, c64::new(p[4], p[5]));
                    }
                    (a, code) => panic!("analysis {a:?} for code {code}"),
                }
                match &s.values {
                    Values::Real(v) => assert_eq!(*v, reals(&e["values"])),
                    Values::Complex(v) => assert_eq!(*v, complexes(&e["values"])),
                }
            }
            other => panic!("unexpected dataset {other} in the JSON"),
        }
    }
}

#[test]
fn pyuff_mixed_file_reads_as_written() {
    let (bytes, json) = fixture("pyuff_mixed");
    let expected = json["records"].as_array().unwrap();
    let records = read(&bytes, Path::new("pyuff_mixed.uff")).unwrap();
    check_mixed(&records, expected);
    // The kinds the file was meant to cover.
    let shapes: Vec<DataCharacteristic> = records
        .iter()
        .filter_map(|r| match r {
            Record::ModeShape(s) => Some(s.characteristic),
            _ => None,
        })
        .collect();
    assert!(shapes.contains(&DataCharacteristic::Translation));
    assert!(shapes.contains(&DataCharacteristic::TranslationRotation));
}

#[test]
fn crlf_line_ends_read_the_same() {
    let (bytes, _) = fixture("pyuff_mixed");
    let crlf = String::from_utf8(bytes.clone())
        .unwrap()
        .replace('\n', "\r\n");
    let lf = read(&bytes, Path::new("lf.uff")).unwrap();
    assert_eq!(read(crlf.as_bytes(), Path::new("crlf.uff")).unwrap(), lf);
}

#[test]
fn pyuff_binary_58b_reads_as_written() {
    let (bytes, json) = fixture("pyuff_58b");
    let expected = json["records"].as_array().unwrap();
    let records = read(&bytes, Path::new("pyuff_58b.uff")).unwrap();
    assert_eq!(records.len(), expected.len());
    for (record, e) in records.iter().zip(expected) {
        check_function(record, e, Encoding::Binary { big_endian: false });
    }
}
