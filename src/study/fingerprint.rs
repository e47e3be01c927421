//! The fingerprint of a study: what makes two runs of it the same computation, so that shards
//! of different study files, models or jointid versions never merge.
//!
//! The fingerprint is the 64-bit FNV-1a hash (Fowler, Noll, Vo; the parameters of
//! <http://www.isthe.com/chongo/tech/comp/fnv/>) of the tool version, the study file's values
//! and the model file's values ([`canonical`]: comments, layout, the spelling of numbers and
//! the order of keys do not count, and neither do the study's `[output]`, which only names
//! where the CSV goes, and `[check]`, which `jointid check` applies to the merged rows), the
//! bytes of the files an external model names (its matrices and DOF
//! table, [`model_data_files`]) and of the measured file a measured noise reads, each prefixed
//! by its length. So a comment, an output path or a check edited between two shards' runs does
//! not keep them apart, and any value that changes a row does. It guards against mistakes, not
//! against forgery. [`crate::cluster`] writes it into every shard file and merges only
//! shards that carry the same one.

use std::path::{Path, PathBuf};

use super::Study;

/// The 64-bit FNV-1a hash of `bytes`, continuing from `hash` (start from [`FNV_OFFSET`]).
pub fn fnv1a(mut hash: u64, bytes: &[u8]) -> u64 {
    for &b in bytes {
        hash ^= u64::from(b);
        hash = hash.wrapping_mul(0x0000_0100_0000_01b3);
    }
    hash
}

/// The FNV-1a 64-bit offset basis.
pub const FNV_OFFSET: u64 = 0xcbf2_9ce4_8422_2325;

/// The fingerprint of a study: the tool version and the bytes of its files (the study file,
/// the model file, the model's data files; see the module docs), as 16 hexadecimal digits.
pub fn fingerprint(tool: &str, files: &[&[u8]]) -> String {
    let mut h = FNV_OFFSET;
    for part in std::iter::once(tool.as_bytes()).chain(files.iter().copied()) {
        h = fnv1a(h, &(part.len() as u64).to_le_bytes());
        h = fnv1a(h, part);
    }
    format!("{h:016x}")
}

/// The files a model file names, whose bytes are part of the model: for an external model
/// (`kind = "matrices"`) K, M, the DOF table and every dK/dp and dM/dp, in file order; none for
/// a beam chain (everything is in the model file). `text` is the model file's content.
pub fn model_data_files(text: &str, model_file: &Path) -> Vec<PathBuf> {
    use crate::model::matrices::config::RawMatrices;
    let Ok(raw) = crate::input::parse_toml::<RawMatrices>(text, model_file) else {
        return Vec::new();
    };
    let Ok(m) = raw.validate(model_file) else {
        return Vec::new();
    };
    let mut files = vec![m.stiffness, m.mass, m.dofs];
    for p in m.parameters {
        files.push(p.dk);
        files.extend(p.dm);
    }
    files
}

/// The values of the TOML file `bytes`, less its top-level tables `leave_out`, written in one
/// form: keys sorted, numbers in shortest round-trip form, strings quoted, no comments. The
/// bytes themselves where they are not TOML.
pub fn canonical(bytes: &[u8], leave_out: &[&str]) -> Vec<u8> {
    let parsed = std::str::from_utf8(bytes)
        .ok()
        .and_then(|text| toml::from_str::<toml::Table>(text).ok());
    let Some(mut table) = parsed else {
        return bytes.to_vec();
    };
    for key in leave_out {
        table.remove(*key);
    }
    let mut out = String::new();
    write_value(&mut out, &toml::Value::Table(table));
    out.into_bytes()
}

/// Appends `value` in the one form of [`canonical`].
fn write_value(out: &mut String, value: &toml::Value) {
    match value {
        toml::Value::Table(t) => {
            let mut keys: Vec<&String> = t.keys().collect();
            keys.sort();
            out.push('{');
            for k in keys {
                out.push_str(&format!("{k:?}="));
                write_value(out, &t[k.as_str()]);
                out.push(',');
            }
            out.push('}');
        }
        toml::Value::Array(a) => {
            out.push('[');
            for v in a {
                write_value(out, v);
                out.push(',');
            }
            out.push(']');
        }
        toml::Value::String(s) => out.push_str(&format!("{s:?}")),
        toml::Value::Integer(i) => out.push_str(&format!("i{i}")),
        toml::Value::Float(x) => out.push_str(&format!("f{x:?}")),
        toml::Value::Boolean(b) => out.push_str(&format!("{b}")),
        toml::Value::Datetime(d) => out.push_str(&format!("d{d}")),
    }
}

/// The study file's tables that change no row: where the CSV goes, and the gate on it.
pub const ROWLESS: [&str; 2] = ["output", "check"];

/// This tool's version as the fingerprint records it: `jointid X.Y.Z`.
pub fn tool_version() -> String {
    format!("jointid {}", env!("CARGO_PKG_VERSION"))
}

/// A file of the study that cannot be read for its fingerprint.
#[derive(Debug, thiserror::Error)]
#[error("{}: cannot read: {cause}", file.display())]
pub struct FingerprintError {
    /// The file.
    pub file: PathBuf,
    /// Why.
    pub cause: std::io::Error,
}

/// The fingerprint of `study` as this tool runs it: [`tool_version`], the study file's and its
/// model file's values, the files the model names and the measured file of a measured noise,
/// read from disk now.
pub fn study_fingerprint(study: &Study) -> Result<String, FingerprintError> {
    let read = |path: &Path| {
        std::fs::read(path).map_err(|cause| FingerprintError {
            file: path.into(),
            cause,
        })
    };
    let model = read(&study.model_file)?;
    let mut files = vec![canonical(&read(&study.file)?, &ROWLESS)];
    for path in model_data_files(&String::from_utf8_lossy(&model), &study.model_file) {
        files.push(read(&path)?);
    }
    files.insert(1, canonical(&model, &[]));
    if let Some(noise) = &study.measured_noise {
        files.push(read(&noise.file)?);
    }
    let parts: Vec<&[u8]> = files.iter().map(|f| f.as_slice()).collect();
    Ok(fingerprint(&tool_version(), &parts))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn fnv1a_reference_vectors() {
        // Published test vectors of FNV-1a 64 (isthe.com/chongo/src/fnv/test_fnv.c).
        assert_eq!(fnv1a(FNV_OFFSET, b""), 0xcbf29ce484222325);
        assert_eq!(fnv1a(FNV_OFFSET, b"a"), 0xaf63dc4c8601ec8c);
        assert_eq!(fnv1a(FNV_OFFSET, b"foobar"), 0x85944171f73967e8);
    }

    #[test]
    fn fingerprint_sees_every_part_and_their_boundaries() {
        let base = fingerprint("jointid 0.1.0", &[b"study", b"model"]);
        assert_eq!(base.len(), 16);
        assert_ne!(base, fingerprint("jointid 0.1.1", &[b"study", b"model"]));
        assert_ne!(base, fingerprint("jointid 0.1.0", &[b"study ", b"model"]));
        assert_ne!(base, fingerprint("jointid 0.1.0", &[b"study", b"model2"]));
        assert_ne!(base, fingerprint("jointid 0.1.0", &[b"studym", b"odel"]));
        assert_ne!(
            base,
            fingerprint("jointid 0.1.0", &[b"study", b"model", b"K"])
        );
    }

    #[test]
    fn a_study_s_fingerprint_is_that_of_its_files_values_and_a_missing_one_is_named() {
        let mut study = Study::from_path(Path::new("studies/ci-bias.toml")).unwrap();
        let bytes = |p: &Path| std::fs::read(p).unwrap();
        let file = canonical(&bytes(&study.file), &ROWLESS);
        let model = canonical(&bytes(&study.model_file), &[]);
        assert_eq!(
            study_fingerprint(&study).unwrap(),
            fingerprint(&tool_version(), &[&file, &model])
        );
        study.file = PathBuf::from("studies/no-such-study.toml");
        let e = study_fingerprint(&study).unwrap_err();
        assert!(
            e.to_string()
                .starts_with("studies/no-such-study.toml: cannot read: "),
            "{e}"
        );
    }

    #[test]
    fn comments_layout_number_spelling_and_the_output_table_do_not_count() {
        let base = "# a study\nname = \"s\"\ntrials = 300\nk = 1.0e7\n[output]\ncsv = \"a.csv\"\n";
        let same = [
            "name = \"s\"   # edited\nk = 10000000.0\ntrials = 300\n\n[output]\ncsv = \"b/c.csv\"\n",
            "trials = 300\nname = \"s\"\nk = 1e7\n",
        ];
        let c = canonical(base.as_bytes(), &["output"]);
        for text in same {
            assert_eq!(c, canonical(text.as_bytes(), &["output"]), "{text}");
        }
        for text in [
            "name = \"s\"\ntrials = 301\nk = 1.0e7\n",
            "name = \"s\"\ntrials = 300\nk = 1.0000001e7\n",
            "name = \"s\"\ntrials = 300\nk = 1.0e7\nseed = 1\n",
            "name = \"t\"\ntrials = 300\nk = 1.0e7\n",
        ] {
            assert_ne!(c, canonical(text.as_bytes(), &["output"]), "{text}");
        }
        // An integer and a float of one value are two values to TOML.
        assert_ne!(canonical(b"a = 1", &[]), canonical(b"a = 1.0", &[]));
        // Not TOML: the bytes.
        assert_eq!(canonical(b"\xff[", &[]), b"\xff[".to_vec());
    }
}
