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
}
