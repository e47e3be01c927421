//! Safe character sets for values that become file names or words of a generated script: a
//! value is checked against its set where it is read, so that no newline, quote, `$`, space
//! or `/` of a hostile name can reach a shell line or climb out of a folder.
//!
//! [`quoted`] shows a value in an error message: escaped (a newline reads `\n`), and cut to
//! about 80 characters, so that an error never echoes a huge or multi-line value.
//!
//! Part of [`crate::input`] (layer 1): imports nothing outside it.

use super::SettingError;

/// The longest part of a value an error message quotes, in characters.
pub const QUOTE_CHARS: usize = 80;

/// `text` as an error message quotes it: between backquotes, control characters escaped,
/// cut after [`QUOTE_CHARS`] characters with `...` and the full length.
pub fn quoted(text: &str) -> String {
    let mut shown = String::new();
    for (count, c) in text.chars().enumerate() {
        if count == QUOTE_CHARS {
            shown.push_str(&format!("... ({} bytes)", text.len()));
            break;
        }
        if c.is_control() {
            shown.extend(c.escape_default());
        } else {
            shown.push(c);
        }
    }
    format!("`{shown}`")
}

/// `message` with every span between backquotes shown as [`quoted`] shows a value: cut to
/// [`QUOTE_CHARS`] characters, control characters escaped, and a number as
/// [`super::Number`] shows it (a parser's echo of `1e308` has 309 digits). The readers pass
/// their line errors through it, so that no error echoes a huge field or line.
pub fn clip_quotes(message: String) -> String {
    if !message.contains('`') {
        return message;
    }
    message
        .split('`')
        .enumerate()
        .map(|(i, part)| {
            // A long decimal (not an integer, which is echoed whole: a count or an index; not
            // a short one, echoed as typed).
            let decimal = part.contains(['.', 'e', 'E']) && part.len() > 12;
            let number = part
                .parse::<f64>()
                .ok()
                .filter(|v| v.is_finite() && decimal);
            // A span [`quoted`] already cut (`... (N bytes)`) is short enough to keep.
            if let (1, Some(v)) = (i % 2, number) {
                super::Number(v).to_string()
            } else if i % 2 == 1 && part.chars().count() > QUOTE_CHARS + 40 {
                let q = quoted(part);
                q[1..q.len() - 1].to_string()
            } else if i % 2 == 1 {
                part.chars()
                    .flat_map(|c| {
                        let escape = c.is_control();
                        c.escape_default()
                            .filter(move |_| escape)
                            .chain(Some(c).filter(|_| !escape))
                    })
                    .collect()
            } else {
                part.to_string()
            }
        })
        .collect::<Vec<_>>()
        .join("`")
}

/// A set of characters a value may hold, and its length limits.
#[derive(Debug, Clone, Copy)]
pub struct CharSet {
    /// What the set allows, as the error says it (`letters, digits, ...`).
    pub describe: &'static str,
    /// Whether a character is in the set.
    pub allows: fn(char) -> bool,
    /// The longest value, in characters.
    pub max_len: usize,
}

/// A file name of its own: letters, digits, `.`, `_` and `-`, not starting with `.` or `-`
/// (no hidden file, no option, no `..`), at most 100 characters. Study names are this set:
/// they name the Slurm scripts, the shard files and the jobs.
pub const FILE_NAME: CharSet = CharSet {
    describe: "it must be 1 to 100 letters, digits, `.`, `_` or `-`, not starting with `.` or `-`",
    allows: |c| c.is_ascii_alphanumeric() || matches!(c, '.' | '_' | '-'),
    max_len: 100,
};

/// Checks `value` of `setting` against `set`: every character in the set, 1 to
/// `set.max_len` characters, and (for every set) no leading `.` or `-`.
pub fn check(set: &CharSet, setting: &'static str, value: &str) -> Result<(), SettingError> {
    let fits = !value.is_empty()
        && value.chars().count() <= set.max_len
        && value.chars().all(set.allows)
        && !value.starts_with(['.', '-']);
    if fits {
        Ok(())
    } else {
        Err(SettingError::new(setting, quoted(value), set.describe))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_file_name_holds_no_path_no_newline_and_no_shell_character() {
        for good in ["paper-case-1", "ci_bias.2", "S"] {
            assert!(check(&FILE_NAME, "name", good).is_ok(), "{good}");
        }
        for bad in [
            "", "..", "../x", "a/b", "a\nb", "a b", "$(id)", "`id`", "a'b", "-x", ".hidden",
        ] {
            assert!(check(&FILE_NAME, "name", bad).is_err(), "{bad:?}");
        }
        assert!(check(&FILE_NAME, "name", &"a".repeat(101)).is_err());
        assert_eq!(
            check(&FILE_NAME, "name", "a\nrm -rf x")
                .unwrap_err()
                .to_string(),
            "name = `a\\nrm -rf x` is invalid: it must be 1 to 100 letters, digits, `.`, `_` or `-`, not starting with `.` or `-`"
        );
    }

    #[test]
    fn a_quote_is_short_and_on_one_line() {
        let long = "x".repeat(100_000_000 / 1000);
        let q = quoted(&long);
        assert!(q.chars().count() < 110, "{q}");
        assert!(q.ends_with("... (100000 bytes)`"), "{q}");
        assert_eq!(quoted("a\r\nb"), "`a\\r\\nb`");
    }

    #[test]
    fn a_message_quotes_at_most_80_characters_of_each_value() {
        let long = "9".repeat(1 << 20);
        let m = clip_quotes(format!(
            "size line `{long}` is invalid: it must be `rows columns entries`"
        ));
        assert!(m.len() < 200, "{m}");
        assert!(m.starts_with("size line `99999"), "{m}");
        assert!(
            m.ends_with("... (1048576 bytes)` is invalid: it must be `rows columns entries`"),
            "{m}"
        );
        assert_eq!(clip_quotes("x = `a` y".into()), "x = `a` y");
        let once = clip_quotes(format!("`{long}`"));
        assert_eq!(clip_quotes(once.clone()), once);
        assert_eq!(clip_quotes("v = `a\nb`".into()), "v = `a\\nb`");
    }
}
