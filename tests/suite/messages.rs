//! Bad input gets a short message: every value of the model, lap and specimen files replaced
//! by an extreme or long one is refused (when it is) in one message of at most
//! [`LONGEST`] characters that names the file, whatever the value's digits.

use std::path::Path;

use jointid::model::solid::SolidConfig;

/// The longest message a refusal may have (issue 42: "under about 200 characters").
const LONGEST: usize = 200;

const PAPER: &str = include_str!("../../models/paper-case-1.toml");

/// Two beams joined by a layered lap.
pub(crate) const LAP_MODEL: &str = "[mesh]\nelement_length = 0.01\n\
    [[beam]]\nlength = 0.3\nyoungs_modulus = 2.1e11\ndensity = 7850\narea = 2.5e-4\nsecond_moment = 5.2e-10\n\
    [[beam]]\nlength = 0.3\nyoungs_modulus = 2.1e11\ndensity = 7850\narea = 2.5e-4\nsecond_moment = 5.2e-10\n\
    [[joint]]\nkind = \"lap\"\n[joint.lap]\nlength = 0.12\nlayers = \"half\"\nk_n = 1e16\nk_s = 1e15\n";

/// Values whose echo used to be long (17 digits, 309 digits) or that are out of range.
pub(crate) const LONG_VALUES: [&str; 7] = [
    "1e308",
    "-0.30000000000000004",
    "0.07999999999999999",
    "3.0000000000000004e-250",
    "123456789012345678901234567890",
    "-1",
    "0",
];

/// Every `key = value` line of `text` set to each of [`LONG_VALUES`] in turn.
pub(crate) fn mutations(text: &str) -> Vec<String> {
    let lines: Vec<&str> = text.lines().collect();
    let mut out = Vec::new();
    for (i, line) in lines.iter().enumerate() {
        let Some((key, _)) = line.split_once('=') else {
            continue;
        };
        for v in LONG_VALUES {
            let mut l: Vec<String> = lines.iter().map(|l| l.to_string()).collect();
            l[i] = format!("{key}= {v}");
            out.push(l.join("\n"));
        }
    }
    out
}

fn short(message: &str, file: &str, input: &str) {
    assert!(
        message.chars().count() <= LONGEST && message.contains(file),
        "{} characters (at most {LONGEST}, naming {file}): {message}\n--- input:\n{input}",
        message.chars().count()
    );
}

#[test]
fn every_refused_value_of_a_model_or_specimen_file_gets_a_short_message_naming_it() {
    for (name, text) in [("paper.toml", PAPER), ("lap.toml", LAP_MODEL)] {
        for t in mutations(text) {
            if let Err(e) = jointid::model::from_toml(&t, Path::new(name)) {
                short(&format!("{e:#}"), name, &t);
            }
        }
    }
    for t in mutations(crate::solid::LAP) {
        if let Err(e) = SolidConfig::from_toml(&t, Path::new("solid.toml")) {
            short(&format!("{e:#}"), "solid.toml", &t);
        } else if let Err(e) = jointid::model::solid::Solid::generate(
            &SolidConfig::from_toml(&t, Path::new("solid.toml")).unwrap(),
        ) {
            short(&format!("solid.toml: {e:#}"), "solid.toml", &t);
        }
    }
}

#[test]
fn numbers_in_messages_are_compact() {
    use jointid::input::Number;
    for (v, shown) in [
        (0.07999999999999999, "0.08"),
        (0.1 + 0.2, "0.3"),
        (1.0 / 3.0, "0.333333"),
        (1e-21, "1e-21"),
        (123.456, "123.456"),
        (2.0f64.powi(60), "1.15292e18"),
        (1e308, "1e308"),
        (-5e-324, "-5e-324"),
    ] {
        assert_eq!(Number(v).to_string(), shown);
    }
}
