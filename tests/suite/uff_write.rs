//! Round trips of the universal-file writer: every dataset written, read back, gives the same
//! values rounded to the digits the writer states (58 double precision `1PE20.12`: 13
//! significant digits; single precision, uneven abscissa, record 7, 55 and 15 `1PE13.5`: 6;
//! 2411 `1PE25.16` and 164 `1PE25.17`: exact). The expected values are the inputs rounded with
//! Rust's `{:.*e}` formatting, not values read back. Inputs are pseudo-random (splitmix64,
//! fixed seed) over many decades.

use std::path::Path;

use faer::c64;
use jointid::uff::{
    Abscissa, Analysis, Axis, DataCharacteristic, Dof, Encoding, Function, FunctionType, Header,
    ModeShape, Node, NodeFormat, Nodes, Precision, Record, UffError, UnitSystem, Units, Values,
    read, write_record,
};

struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    /// A value of random sign and mantissa, magnitude 1e-8..1e8.
    fn value(&mut self) -> f64 {
        let u = (self.next() >> 11) as f64 / (1u64 << 53) as f64;
        let decade = (self.next() % 17) as i32 - 8;
        let sign = if self.next() % 2 == 0 { 1.0 } else { -1.0 };
        sign * (1.0 + 9.0 * u) * 10f64.powi(decade)
    }

    fn values(&mut self, n: usize) -> Vec<f64> {
        (0..n).map(|_| self.value()).collect()
    }
}

fn round(v: f64, digits: usize) -> f64 {
    format!("{:.*e}", digits - 1, v).parse().unwrap()
}

fn round_all(v: &[f64], digits: usize) -> Vec<f64> {
    v.iter().map(|&x| round(x, digits)).collect()
}

fn round_values(v: &Values, digits: usize) -> Values {
    match v {
        Values::Real(x) => Values::Real(round_all(x, digits)),
        Values::Complex(z) => Values::Complex(
            z.iter()
                .map(|z| c64::new(round(z.re, digits), round(z.im, digits)))
                .collect(),
        ),
    }
}

fn write(record: &Record) -> Vec<u8> {
    let mut out = Vec::new();
    write_record(&mut out, record).unwrap();
    out
}

fn read_one(bytes: &[u8]) -> Record {
    let mut records = read(bytes, Path::new("written.uff")).unwrap();
    assert_eq!(records.len(), 1);
    records.pop().unwrap()
}

fn axis(data_type: i32, label: &str, units: &str) -> Axis {
    Axis {
        data_type,
        length_exponent: 0,
        force_exponent: 0,
        temperature_exponent: 0,
        label: label.into(),
        units: units.into(),
    }
}

fn function(precision: Precision, abscissa: Abscissa, ordinate: Values) -> Function {
    Function {
        id_lines: [
            "FRF of point 3".into(),
            "jointid".into(),
            "NONE".into(),
            "NONE".into(),
            "NONE".into(),
        ],
        function_type: FunctionType::Frf,
        function_id: 12,
        version: 1,
        load_case: 0,
        response: Dof {
            entity: "ACC3".into(),
            node: 3,
            direction: 2,
        },
        reference: Dof {
            entity: "NONE".into(),
            node: 100,
            direction: -2,
        },
        precision,
        abscissa,
        z_value: 0.0,
        abscissa_axis: axis(18, "Frequency", "Hz"),
        ordinate_axis: Axis {
            length_exponent: 1,
            ..axis(12, "Acceleration", "m/s^2")
        },
        denominator_axis: axis(13, "Voltage", "V"),
        z_axis: axis(0, "NONE", "NONE"),
        ordinate,
        encoding: Encoding::Ascii,
    }
}

/// Writes `f`, reads it back and compares with `f` rounded to the stated digits; writing the
/// record read gives the same bytes.
fn round_trip_function(f: Function) {
    let ordinate_digits = if f.precision == Precision::Double {
        13
    } else {
        6
    };
    let expected = Function {
        abscissa: match &f.abscissa {
            Abscissa::Even { start, step } => Abscissa::Even {
                start: round(*start, 6),
                step: round(*step, 6),
            },
            Abscissa::Uneven(x) => Abscissa::Uneven(round_all(x, 6)),
        },
        ordinate: round_values(&f.ordinate, ordinate_digits),
        ..f.clone()
    };
    let bytes = write(&Record::Function(f));
    let back = read_one(&bytes);
    assert_eq!(back, Record::Function(expected));
    assert_eq!(write(&back), bytes);
}

#[test]
fn functions_round_trip_in_every_layout() {
    let mut rng = Rng(58);
    for n in [1, 2, 3, 7, 64] {
        let complex = Values::Complex(
            rng.values(n)
                .chunks(1)
                .map(|v| c64::new(v[0], rng.value()))
                .collect(),
        );
        let real = Values::Real(rng.values(n));
        let even = Abscissa::Even {
            start: 0.0,
            step: 0.0625,
        };
        let uneven = Abscissa::Uneven((0..n).map(|i| (i as f64 + 1.0) * 1.234567891).collect());
        for precision in [Precision::Double, Precision::Single] {
            round_trip_function(function(precision, even.clone(), complex.clone()));
            round_trip_function(function(precision, even.clone(), real.clone()));
            round_trip_function(function(precision, uneven.clone(), complex.clone()));
            round_trip_function(function(precision, uneven.clone(), real.clone()));
        }
    }
    // A negative start and a step of more than 6 digits are rounded to 6.
    let f = function(
        Precision::Double,
        Abscissa::Even {
            start: -0.0123456789,
            step: 0.1220703125,
        },
        Values::Real(vec![1.0, 2.0]),
    );
    round_trip_function(f);
}

#[test]
fn double_values_keep_13_digits_and_extreme_exponents_stay_readable() {
    let mut rng = Rng(13);
    let mut y = rng.values(200);
    y.extend([
        1e-150,
        -2.5e-200,
        3.75e250,
        -1.0e300,
        0.0,
        -0.0,
        f64::MIN_POSITIVE,
        f64::MAX,
    ]);
    let f = function(
        Precision::Double,
        Abscissa::Even {
            start: 0.0,
            step: 1.0,
        },
        Values::Real(y.clone()),
    );
    let Record::Function(back) = read_one(&write(&Record::Function(f))) else {
        panic!()
    };
    let Values::Real(read_y) = back.ordinate else {
        panic!()
    };
    for (x, r) in y.iter().zip(&read_y) {
        // A three-digit exponent costs a negative value a digit (the field keeps a blank).
        let three_digit_exponent = x.abs() >= 1e100 || (x.abs() < 1e-99 && *x != 0.0);
        let digits = if *x < 0.0 && three_digit_exponent {
            12
        } else {
            13
        };
        assert_eq!(*r, round(*x, digits), "{x:e} read as {r:e}");
    }
}

fn shape(
    analysis: Analysis,
    characteristic: DataCharacteristic,
    ndv: usize,
    values: Values,
) -> ModeShape {
    let nodes: Vec<u64> = (1..=(values.len() / ndv) as u64).map(|n| n * 10).collect();
    ModeShape {
        id_lines: [
            "mode 1".into(),
            "NONE".into(),
            "NONE".into(),
            "NONE".into(),
            "NONE".into(),
        ],
        model_type: 1,
        analysis,
        characteristic,
        specific_data_type: 12,
        precision: Precision::Single,
        values_per_node: ndv,
        nodes,
        values,
    }
}

#[test]
fn mode_shapes_round_trip_to_6_digits() {
    let mut rng = Rng(55);
    let normal = Analysis::NormalMode {
        load_case: 1,
        mode: 2,
        frequency_hz: round(98.43751, 6),
        modal_mass: round(0.123456789, 6),
        viscous_damping: 0.0125,
        hysteretic_damping: 0.0,
    };
    let complex_mode = |second_order| Analysis::ComplexMode {
        second_order,
        load_case: 1,
        mode: 3,
        eigenvalue: c64::new(-3.25, 620.5),
        modal_a: c64::new(0.25, -0.5),
        modal_b: c64::new(1.5, 2.0),
    };
    let other = Analysis::Other {
        code: 1,
        integers: vec![4],
        reals: vec![0.0],
    };
    let real = |rng: &mut Rng, n| Values::Real(round_all(&rng.values(n), 6));
    let complex = |rng: &mut Rng, n: usize| {
        Values::Complex(
            (0..n)
                .map(|_| c64::new(round(rng.value(), 6), round(rng.value(), 6)))
                .collect(),
        )
    };
    let cases = [
        shape(
            normal.clone(),
            DataCharacteristic::Translation,
            3,
            real(&mut rng, 12),
        ),
        shape(
            normal.clone(),
            DataCharacteristic::Translation,
            3,
            complex(&mut rng, 9),
        ),
        shape(
            normal,
            DataCharacteristic::TranslationRotation,
            6,
            real(&mut rng, 18),
        ),
        shape(
            complex_mode(false),
            DataCharacteristic::Translation,
            3,
            complex(&mut rng, 6),
        ),
        shape(
            complex_mode(true),
            DataCharacteristic::TranslationRotation,
            6,
            complex(&mut rng, 12),
        ),
        shape(other, DataCharacteristic::Scalar, 1, real(&mut rng, 5)),
    ];
    for s in cases {
        let record = Record::ModeShape(s);
        let bytes = write(&record);
        assert_eq!(read_one(&bytes), record);
    }
    // Unrounded values come back rounded to 6 digits.
    let values = rng.values(30);
    let s = shape(
        complex_mode(false),
        DataCharacteristic::Translation,
        3,
        Values::Real(values.clone()),
    );
    let Record::ModeShape(back) = read_one(&write(&Record::ModeShape(s))) else {
        panic!()
    };
    assert_eq!(back.values, Values::Real(round_all(&values, 6)));
}

#[test]
fn nodes_units_and_header_round_trip() {
    let mut rng = Rng(15);
    let mut nodes = |format, digits| Nodes {
        format,
        nodes: (0..5)
            .map(|i| Node {
                label: 100 + i,
                definition_cs: i % 2,
                displacement_cs: i % 3,
                color: 8,
                coordinates: [rng.value(), rng.value(), rng.value()].map(|c| round(c, digits)),
            })
            .collect(),
    };
    for record in [
        Record::Nodes(nodes(NodeFormat::Single15, 6)),
        Record::Nodes(nodes(NodeFormat::Double2411, 17)),
        Record::Units(Units {
            system: UnitSystem::UserDefined,
            description: "user units".into(),
            temperature_mode: Some(1),
            length: 3.280839895013123,
            force: 0.22480894309971047,
            temperature: 1.8,
            temperature_offset: 459.67,
        }),
        Record::Units(Units {
            system: UnitSystem::Si,
            description: "SI".into(),
            temperature_mode: None,
            length: 1.0,
            force: 1.0,
            temperature: 1.0,
            temperature_offset: 273.15,
        }),
        Record::Header(Header {
            model_file: "beam.toml".into(),
            description: "jointid".into(),
            database_program: "NONE".into(),
            database_created: "01-Jan-25 12:00:00".into(),
            database_saved: "01-Jan-25 12:00:00".into(),
            program: "jointid".into(),
            written: "01-Jan-25 12:00:00".into(),
        }),
    ] {
        assert_eq!(read_one(&write(&record)), record);
    }
}

#[test]
fn written_columns_match_the_fixed_formats() {
    let f = function(
        Precision::Double,
        Abscissa::Even {
            start: 0.0,
            step: 0.5,
        },
        Values::Complex(vec![c64::new(-1.0, 2.0); 3]),
    );
    let text = String::from_utf8(write(&Record::Function(f))).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines[0], "    -1");
    assert_eq!(lines[1], "    58");
    assert_eq!(
        lines[7],
        "    4        12    1         0 ACC3               3   2 NONE             100  -2"
    );
    assert_eq!(
        lines[8],
        "         6         3         1  0.00000E+00  5.00000E-01  0.00000E+00"
    );
    assert_eq!(
        lines[9],
        "        18    0    0    0 Frequency            Hz                  "
    );
    assert_eq!(
        lines[13],
        " -1.000000000000E+00  2.000000000000E+00 -1.000000000000E+00  2.000000000000E+00"
    );
    assert_eq!(lines[14], " -1.000000000000E+00  2.000000000000E+00");
    assert_eq!(lines[15], "    -1");
}

#[test]
fn unwritable_values_are_refused() {
    let mut f = function(
        Precision::Double,
        Abscissa::Even {
            start: 0.0,
            step: 1.0,
        },
        Values::Real(vec![1.0, f64::NAN]),
    );
    let err = write_record(&mut Vec::new(), &Record::Function(f.clone())).unwrap_err();
    assert_eq!(
        err.to_string(),
        "cannot write dataset 58: data value (record 12) = NaN is invalid: it must be finite"
    );
    f.ordinate = Values::Real(vec![1.0, 2.0]);
    f.ordinate_axis.units = "m/s^2 per volt of the amplifier".into();
    let err = write_record(&mut Vec::new(), &Record::Function(f.clone())).unwrap_err();
    assert!(
        matches!(
            err,
            UffError::Unwritable {
                dataset: 58,
                field: "axis units label (records 8-11)",
                ..
            }
        ),
        "{err}"
    );
    f.ordinate_axis.units = "m/s^2/V".into();
    f.response.node = 12_345_678_901;
    let err = write_record(&mut Vec::new(), &Record::Function(f)).unwrap_err();
    assert_eq!(
        err.to_string(),
        "cannot write dataset 58: node (record 6, I10) = 12345678901 is invalid: it does not fit its integer field"
    );
    let other = Record::Other {
        kind: 2412,
        first_line: 1,
    };
    assert!(write_record(&mut Vec::new(), &other).is_err());
}
