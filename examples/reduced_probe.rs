//! The reduced model of `jointid::modal::reduced` against the full solve on an external
//! model, at parameters scaled from the nominal ones: the times of the basis, of a reduced
//! solve (with its enrichment) and of a full one, and per elastic pair the two frequencies and
//! the error estimate. The figures of the reduced model's module docs and of
//! docs/benchmarks.md come from it.
//!
//! `cargo run --release --example reduced_probe MODEL.toml 1,1,0.5 0.5,2,0.5 ...` (one factor
//! per identified parameter, in model order); `TOL=1e99` leaves the enrichment out (the
//! basis as built).
use jointid::modal::{ModalSolution, reduced};
use std::sync::Arc;
use std::time::Instant;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let model = jointid::model::from_path(std::path::Path::new(&args[1])).unwrap();
    let (rigid, m) = (model.rigid, 8);
    let t = Instant::now();
    let nominal = ModalSolution::lowest_of(&model.assemble(), rigid + 2 * m + 2).unwrap();
    eprintln!("nominal solve {:.2}s", t.elapsed().as_secs_f64());
    let t = Instant::now();
    let params = model.identified();
    let dirs: Vec<_> = params.iter().map(|p| (&p.stiffness, &p.mass)).collect();
    let tol: f64 = std::env::var("TOL")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(reduced::TOLERANCE);
    let built = reduced::build(&model, &nominal, None, &dirs, rigid..rigid + m + 2, tol).unwrap();
    eprintln!(
        "build {:.2}s, dimension {}",
        t.elapsed().as_secs_f64(),
        built.dimension()
    );
    let mut s = model.clone();
    s.reduced = Some(Arc::new(built));
    for f in &args[2..] {
        let factors: Vec<f64> = f.split(',').map(|x| x.parse().unwrap()).collect();
        let values: Vec<f64> = params
            .iter()
            .zip(&factors)
            .map(|(p, f)| p.value * f)
            .collect();
        let at = s.with_values(&values);
        let t = Instant::now();
        let (red, next) = reduced::lowest_keeping(&at, &[], rigid + m + 2).unwrap();
        let tr = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let full = reduced::full(&at, &[], rigid + m + 2).unwrap();
        let tf = t.elapsed().as_secs_f64();
        let etas = reduced::residuals(&red).to_vec();
        let worst = (rigid..red.len())
            .map(|j| (red.frequency_hz(j) / full.frequency_hz(j) - 1.0).abs())
            .fold(0.0, f64::max);
        println!(
            "factors {f}: reduced {tr:.3}s (enriched {:?}, reduced? {}), full {tf:.2}s, worst rel freq {worst:.2e}, eta max {:.2e}",
            next.as_ref().map(|n| n.dimension()),
            red.reduced().is_some(),
            etas.iter().cloned().fold(0.0, f64::max)
        );
        for j in rigid..red.len() {
            println!(
                "  {j}: {:.6} vs {:.6} rel {:.2e} eta {:.2e}",
                red.frequency_hz(j),
                full.frequency_hz(j),
                red.frequency_hz(j) / full.frequency_hz(j) - 1.0,
                etas.get(j).copied().unwrap_or(f64::NAN)
            );
        }
    }
}
