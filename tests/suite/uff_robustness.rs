//! The universal-file reader never panics, whatever the bytes: valid files (the pyuff fixtures
//! and a file from our writer) are truncated at many lengths and mutated at random (bytes
//! replaced by characters that matter to the format, lines deleted or duplicated, `-1` lines
//! inserted, numbers made huge or negative), and every result must be `Ok` or an `Err` whose
//! message names the file. Mutations come from splitmix64 with fixed seeds, so a failure
//! reproduces; the failing case's seed and index are in the panic message.

use std::panic::{AssertUnwindSafe, catch_unwind};
use std::path::Path;

use jointid::uff::read;

struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^ (z >> 31)
    }

    fn below(&mut self, n: usize) -> usize {
        (self.next() % n.max(1) as u64) as usize
    }
}

fn corpus() -> Vec<(&'static str, Vec<u8>)> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/uff");
    let mixed = std::fs::read(dir.join("pyuff_mixed.uff")).unwrap();
    let binary = std::fs::read(dir.join("pyuff_58b.uff")).unwrap();
    let crlf = String::from_utf8(mixed.clone())
        .unwrap()
        .replace('\n', "\r\n")
        .into_bytes();
    vec![
        ("pyuff_mixed", mixed),
        ("pyuff_58b", binary),
        ("pyuff_mixed_crlf", crlf),
    ]
}

/// Reads `bytes`; panics with `case` if the reader panics or an error does not name the file.
fn must_not_panic(bytes: &[u8], case: &str) {
    let result = catch_unwind(AssertUnwindSafe(|| read(bytes, Path::new("fuzz.uff"))));
    match result {
        Err(_) => panic!("the reader panicked on {case}"),
        Ok(Err(e)) => {
            if std::env::var("FUZZ_SHOW").is_ok() {
                eprintln!("ERR {e}");
            }
            assert!(e.to_string().starts_with("fuzz.uff: "), "{case}: {e}")
        }
        Ok(Ok(_)) => {
            if std::env::var("FUZZ_SHOW").is_ok() {
                eprintln!("OK");
            }
        }
    }
}

fn lines(bytes: &[u8]) -> Vec<Vec<u8>> {
    bytes
        .split_inclusive(|&b| b == b'\n')
        .map(<[u8]>::to_vec)
        .collect()
}

fn mutate(bytes: &[u8], rng: &mut Rng) -> Vec<u8> {
    const CHARS: &[u8] = b"-1 0 9\n\r.bEeD+\t\xff\x00";
    let mut out = bytes.to_vec();
    for _ in 0..1 + rng.below(4) {
        match rng.below(6) {
            0 if !out.is_empty() => {
                let at = rng.below(out.len());
                out[at] = CHARS[rng.below(CHARS.len())];
            }
            1 if !out.is_empty() => {
                let at = rng.below(out.len());
                out[at] = rng.next() as u8;
            }
            2 => {
                let mut ls = lines(&out);
                if !ls.is_empty() {
                    let at = rng.below(ls.len());
                    if rng.below(2) == 0 {
                        ls.remove(at);
                    } else {
                        let copy = ls[at].clone();
                        ls.insert(at, copy);
                    }
                }
                out = ls.concat();
            }
            3 => {
                let mut ls = lines(&out);
                let at = rng.below(ls.len() + 1);
                ls.insert(at, b"    -1\n".to_vec());
                out = ls.concat();
            }
            4 => {
                // A number made huge, negative or empty.
                let digits: Vec<usize> = (0..out.len())
                    .filter(|&i| out[i].is_ascii_digit())
                    .collect();
                if !digits.is_empty() {
                    let at = digits[rng.below(digits.len())];
                    let with: &[u8] = match rng.below(3) {
                        0 => b"99999999999999999999",
                        1 => b"-7",
                        _ => b"",
                    };
                    out.splice(at..at + 1, with.iter().copied());
                }
            }
            _ => {
                let cut = rng.below(out.len() + 1);
                out.truncate(cut);
            }
        }
    }
    out
}

#[test]
fn truncated_files_give_errors_not_panics() {
    for (name, bytes) in corpus() {
        let step = if bytes.len() > 8000 { 23 } else { 1 };
        for len in (0..bytes.len()).step_by(step) {
            must_not_panic(&bytes[..len], &format!("{name} truncated to {len} bytes"));
        }
    }
}

#[test]
fn mutated_files_give_errors_not_panics() {
    for (k, (name, bytes)) in corpus().into_iter().enumerate() {
        let seed = 0x5EED + k as u64;
        let mut rng = Rng(seed);
        for i in 0..1000 {
            let m = mutate(&bytes, &mut rng);
            must_not_panic(&m, &format!("{name}, seed {seed:#x}, mutation {i}"));
        }
    }
}

#[test]
fn arbitrary_bytes_give_errors_not_panics() {
    let mut rng = Rng(0xB17E5);
    for i in 0..2000 {
        let len = rng.below(300);
        let mut bytes: Vec<u8> = (0..len).map(|_| rng.next() as u8).collect();
        if i % 2 == 0 {
            // Most random bytes fail at the first line: open a dataset half of the time.
            let kind: &[u8] = [
                &b"58"[..],
                b"58b 1 2 11 16",
                b"55",
                b"15",
                b"2411",
                b"164",
                b"151",
            ][rng.below(7)];
            let mut head = b"    -1\n    ".to_vec();
            head.extend(kind);
            head.push(b'\n');
            head.extend(bytes);
            bytes = head;
        }
        must_not_panic(&bytes, &format!("random bytes {i}"));
    }
}
