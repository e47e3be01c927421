//! Values that go into a generated shell script, made safe by construction: every value is
//! checked against the character set of its kind ([`SlurmValue`]) before a script is rendered,
//! and every path or word on a shell line is quoted by the one routine [`sh_quote`].
//!
//! `#SBATCH` lines are read by sbatch, not by the shell, and cannot be quoted: a value there
//! (partition, time, account, memory, an extra option, the log folder) must hold none of
//! newline, space, quote, `$`, backquote, `;`, `&`, `|`, `<`, `>`, `%` or `\`. A newline would
//! end the `#SBATCH` block and run the rest as a command on the compute node.
//!
//! Part of [`crate::cluster`]: imports only [`crate::input`].

use std::path::Path;

use crate::input::SettingError;
use crate::input::safe::{CharSet, check, quoted};

/// `'text'` for sh: the one quoting routine of every generated script. Inside single quotes
/// the shell expands nothing; an embedded `'` is written `'\''`.
pub fn sh_quote(text: &str) -> String {
    format!("'{}'", text.replace('\'', r"'\''"))
}

/// The kinds of value an `#SBATCH` line takes, each with its character set.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SlurmValue {
    /// A partition or account name (a comma-separated list of them).
    Name,
    /// A time limit: `MM`, `HH:MM:SS`, `D-HH:MM:SS`.
    Time,
    /// A memory size: digits and a unit letter (`4G`, `500M`).
    Memory,
    /// The value of an extra option (`--qos=short`: `short`).
    OptionValue,
    /// A folder of the logs (it is written into `#SBATCH --output=`).
    Folder,
}

const NAME: CharSet = CharSet {
    describe: "it must be 1 to 64 letters, digits, `.`, `_`, `-` or `,` (a Slurm name)",
    allows: |c| c.is_ascii_alphanumeric() || matches!(c, '.' | '_' | '-' | ','),
    max_len: 64,
};

const TIME: CharSet = CharSet {
    describe: "it must be a Slurm time of digits, `:` and `-`, e.g. 02:00:00 or 1-12:00:00",
    allows: |c| c.is_ascii_digit() || matches!(c, ':' | '-'),
    max_len: 20,
};

const MEMORY: CharSet = CharSet {
    describe: "it must be a Slurm memory size of digits and a unit K, M, G or T, e.g. 4G",
    allows: |c| c.is_ascii_digit() || matches!(c, 'K' | 'M' | 'G' | 'T' | 'k' | 'm' | 'g' | 't'),
    max_len: 20,
};

const OPTION_VALUE: CharSet = CharSet {
    describe: "an option's value must be 1 to 200 letters, digits or `.`, `_`, `-`, `,`, `:`, `=`, `+`, `@`, `/`",
    allows: |c| {
        c.is_ascii_alphanumeric()
            || matches!(c, '.' | '_' | '-' | ',' | ':' | '=' | '+' | '@' | '/')
    },
    max_len: 200,
};

const FOLDER: CharSet = CharSet {
    describe: "it is written into `#SBATCH --output=`, which cannot be quoted: the absolute path must hold only letters, digits and `/`, `.`, `_`, `-`, `+`, `,`, `@`, `=` (no space)",
    allows: |c| {
        c.is_ascii_alphanumeric() || matches!(c, '/' | '.' | '_' | '-' | '+' | ',' | '@' | '=')
    },
    max_len: 4000,
};

impl SlurmValue {
    fn set(self) -> &'static CharSet {
        match self {
            SlurmValue::Name => &NAME,
            SlurmValue::Time => &TIME,
            SlurmValue::Memory => &MEMORY,
            SlurmValue::OptionValue => &OPTION_VALUE,
            SlurmValue::Folder => &FOLDER,
        }
    }

    /// Checks `value` of `setting` against this kind's set.
    pub fn check(self, setting: &'static str, value: &str) -> Result<(), SettingError> {
        if self == SlurmValue::Folder {
            // An absolute path starts with `/`, which the sets' leading-character rule allows.
            let rest = value.strip_prefix('/').unwrap_or(value);
            return check(self.set(), setting, rest)
                .map_err(|e| SettingError::new(setting, quoted(value), e.allowed));
        }
        check(self.set(), setting, value)
    }
}

/// Checks one extra sbatch option: a single token `--key` or `--key=value`, the key of
/// lower-case letters and `-`, the value in [`SlurmValue::OptionValue`]'s set.
pub fn check_option(setting: &'static str, option: &str) -> Result<(), SettingError> {
    let refuse = || {
        SettingError::new(
            setting,
            quoted(option),
            "it must be one sbatch option `--key` or `--key=value` (a key of lower-case letters and `-`; a value of letters, digits or `.`, `_`, `-`, `,`, `:`, `=`, `+`, `@`, `/`), e.g. --qos=short",
        )
    };
    let body = option.strip_prefix("--").ok_or_else(refuse)?;
    let (key, value) = match body.split_once('=') {
        Some((key, value)) => (key, Some(value)),
        None => (body, None),
    };
    let key_ok = key.starts_with(|c: char| c.is_ascii_lowercase())
        && key.len() <= 40
        && key.chars().all(|c| c.is_ascii_lowercase() || c == '-');
    if !key_ok {
        return Err(refuse());
    }
    match value {
        Some(v) => SlurmValue::OptionValue
            .check(setting, v)
            .map_err(|_| refuse()),
        None => Ok(()),
    }
}

/// Checks a path that a script names on a quoted shell line: valid UTF-8 (the script holds
/// the path it names, no lossy spelling of it) and no control character.
pub fn check_quoted_path(setting: &'static str, path: &Path) -> Result<(), SettingError> {
    match path.to_str() {
        Some(text) if !text.chars().any(char::is_control) => Ok(()),
        Some(text) => Err(SettingError::new(
            setting,
            quoted(text),
            "a path in a script must hold no newline or other control character",
        )),
        None => Err(SettingError::new(
            setting,
            quoted(&path.to_string_lossy()),
            "a path in a script must be valid UTF-8",
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quotes_survive_the_shell() {
        assert_eq!(sh_quote("a'b"), r"'a'\''b'");
        assert_eq!(sh_quote("$(id) `id` \"x\""), "'$(id) `id` \"x\"'");
    }

    #[test]
    fn every_kind_refuses_a_newline_and_shell_characters() {
        let hostile = [
            "a\nb", "a b", "$(id)", "`id`", "a;b", "a|b", "a'b", "a\"b", "",
        ];
        for kind in [
            SlurmValue::Name,
            SlurmValue::Time,
            SlurmValue::Memory,
            SlurmValue::OptionValue,
            SlurmValue::Folder,
        ] {
            for value in hostile {
                assert!(kind.check("v", value).is_err(), "{kind:?} {value:?}");
            }
        }
        assert!(SlurmValue::Name.check("partition", "short,long").is_ok());
        assert!(SlurmValue::Time.check("time", "1-12:00:00").is_ok());
        assert!(SlurmValue::Memory.check("mem", "4G").is_ok());
        assert!(SlurmValue::Folder.check("dir", "/scratch/u/run-1").is_ok());
        assert!(SlurmValue::Folder.check("dir", "/scratch/a%j").is_err());
    }

    #[test]
    fn an_extra_option_is_one_token() {
        for good in ["--qos=short", "--exclusive", "--constraint=gpu,avx2"] {
            assert!(check_option("sbatch", good).is_ok(), "{good}");
        }
        for bad in [
            "--qos=short\necho pwned",
            "--qos=short x",
            "-q short",
            "qos=short",
            "--=x",
            "--QOS=x",
            "--qos=$(id)",
        ] {
            assert!(check_option("sbatch", bad).is_err(), "{bad:?}");
        }
    }

    #[test]
    fn a_quoted_path_holds_no_control_character() {
        assert!(check_quoted_path("out", Path::new("/a b/$(id)'x.csv")).is_ok());
        assert_eq!(
            check_quoted_path("out", Path::new("/a\nb.csv"))
                .unwrap_err()
                .to_string(),
            "out = `/a\\nb.csv` is invalid: a path in a script must hold no newline or other control character"
        );
    }
}
