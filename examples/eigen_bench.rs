//! Benchmark of the sparse eigensolver (README, "Large models"; run by
//! `bench/eigen_vs_scipy.sh`): the lowest `count` modes of a clamped-free steel cantilever
//! (the paper's section, 1 m) of `elements` Euler-Bernoulli elements, N = 2 elements DOFs,
//! banded. Writes K and M as Matrix Market files (coordinate, real, symmetric: the lower
//! triangle, 1-based) into `dir` for the scipy peer, then times
//! `ModalSolution::lowest` `repeat` times and prints the median, the peak resident memory
//! of the process and the frequencies beside the analytic ones.
//!
//! `cargo run --release --example eigen_bench -- ELEMENTS COUNT REPEAT DIR`

use std::io::Write;
use std::time::Instant;

use jointid::modal::ModalSolution;
use jointid::model::chain::{Chain, Support, SupportKind};
use jointid::model::fixtures::steel_bar;
use jointid::structure::SymMatrix;

/// The Matrix Market writer the benchmark needs (not the project's reader/writer).
fn write_matrix_market(a: &SymMatrix, path: &str) -> std::io::Result<()> {
    let lower: Vec<(usize, usize, f64)> = a.entries().into_iter().filter(|e| e.0 >= e.1).collect();
    let mut out = std::io::BufWriter::new(std::fs::File::create(path)?);
    writeln!(out, "%%MatrixMarket matrix coordinate real symmetric")?;
    writeln!(out, "{} {} {}", a.size(), a.size(), lower.len())?;
    for (i, j, v) in lower {
        // {:e} prints the shortest representation that reads back to the same f64.
        writeln!(out, "{} {} {:e}", i + 1, j + 1, v)?;
    }
    out.flush()
}

fn peak_rss_mb() -> f64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("VmHWM:"))
                .and_then(|l| l.split_whitespace().nth(1).map(str::to_string))
        })
        .and_then(|kb| kb.parse::<f64>().ok())
        .map_or(f64::NAN, |kb| kb / 1024.0)
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let elements: usize = args[1].parse().expect("ELEMENTS");
    let count: usize = args[2].parse().expect("COUNT");
    let repeat: usize = args[3].parse().expect("REPEAT");
    let dir = &args[4];
    let length = 1.0;
    let mut chain = Chain::free(vec![steel_bar(length, elements)], vec![]);
    chain.supports.push(Support {
        x: 0.0,
        kind: SupportKind::Clamped,
        identify: [false, false],
    });
    let mats = chain.build().assemble();
    write_matrix_market(&mats.k, &format!("{dir}/k.mtx")).expect("write k.mtx");
    write_matrix_market(&mats.m, &format!("{dir}/m.mtx")).expect("write m.mtx");
    let before = peak_rss_mb();
    let mut times = Vec::new();
    let mut sol = None;
    for _ in 0..repeat {
        let t = Instant::now();
        sol =
            Some(ModalSolution::lowest(mats.k.as_faer(), mats.m.as_faer(), count).expect("solve"));
        times.push(t.elapsed().as_secs_f64());
    }
    times.sort_by(f64::total_cmp);
    let sol = sol.expect("at least one run");
    println!("N = {}, nnz(K) = {}", mats.size(), mats.k.nnz());
    println!(
        "jointid: median {:.3} s of {repeat}, peak RSS {:.0} MB ({:.0} MB before the solves)",
        times[times.len() / 2],
        peak_rss_mb(),
        before
    );
    let frequencies: Vec<String> = (0..count)
        .map(|i| format!("{:.9}", sol.frequency_hz(i)))
        .collect();
    println!("frequencies_hz {}", frequencies.join(" "));
}
