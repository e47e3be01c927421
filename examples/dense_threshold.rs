//! Where the dense all-pairs solution stops paying: the paper's chain (k1 = 1e7 N/m,
//! k2 = 1e4 N m/rad) refined to `e` + `e` elements, the dense solve of every pair beside the
//! sparse solve of the lowest 20, median wall time of 5 runs, and the first elastic frequency
//! by both. Run: `cargo run --release --example dense_threshold`.
use std::time::Instant;

use jointid::modal::ModalSolution;
use jointid::model::chain::{Chain, Joint};
use jointid::model::fixtures::steel_bar;

fn median(mut t: Vec<f64>) -> f64 {
    t.sort_by(f64::total_cmp);
    t[t.len() / 2]
}

fn main() {
    println!("N,dense_ms,sparse20_ms,f1_dense_hz,f1_sparse_hz,relative_difference");
    for e in [10, 20, 30, 40, 50, 75, 100, 150, 250, 500] {
        let chain = Chain::free(
            vec![steel_bar(0.2, e), steel_bar(0.3, e)],
            vec![Joint::identified(1e7, 1e4)],
        );
        let mats = chain.build().assemble();
        let n = mats.size();
        let count = 20.min(n);
        let (mut td, mut ts) = (Vec::new(), Vec::new());
        let (mut fd, mut fs) = (0.0, 0.0);
        for _ in 0..5 {
            let t = Instant::now();
            let d = ModalSolution::solve(&mats).expect("dense solve");
            td.push(t.elapsed().as_secs_f64() * 1e3);
            fd = d.frequency_hz(2);
            let t = Instant::now();
            let s = ModalSolution::lowest(mats.k.as_faer(), mats.m.as_faer(), count)
                .expect("sparse solve");
            ts.push(t.elapsed().as_secs_f64() * 1e3);
            fs = s.frequency_hz(2);
        }
        println!(
            "{n},{:.3},{:.3},{fd:.9},{fs:.9},{:.2e}",
            median(td),
            median(ts),
            (fd - fs).abs() / fs
        );
    }
}
