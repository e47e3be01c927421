//! Benchmark of the sparse eigensolver beside scipy (docs/benchmarks.md, "Large models"; run
//! by `bench/eigen_vs_scipy.sh`). Two steps, so that every timed run is its own process
//! (interleaved with scipy's, peak memory by `/usr/bin/time -v`):
//!
//! - `export chain ELEMENTS DIR`: a clamped-free steel cantilever (the paper's section, 1 m)
//!   of ELEMENTS Euler-Bernoulli elements (N = 2 ELEMENTS DOFs, banded, no rigid-body mode);
//! - `export model MODEL.toml DIR`: an external model (such as `jointid solid` writes) at its
//!   parameter values;
//!
//!   write K and M as Matrix Market files (coordinate, real, symmetric: the lower triangle,
//!   1-based) into DIR, with `case.txt` (the rigid-body count and the solver's default shift,
//!   which scipy is given too);
//! - `solve DIR COUNT`: reads them back and times the lowest `rigid + COUNT` pairs by
//!   `ModalSolution::lowest` (threads: `RAYON_NUM_THREADS`), then prints the time, the
//!   frequencies and, per elastic mode, the relative residual ||K y - lambda M y|| / ||K y||
//!   with its rounding floor and the backward error (`jointid::modal::residual`).
//!
//! `cargo run --release --example eigen_bench -- export chain 50000 /tmp/b`

use std::io::Write;
use std::path::Path;
use std::time::Instant;

use jointid::modal::lanczos::{LanczosSettings, default_shift, lowest_modes};
use jointid::modal::residual::residuals;
use jointid::model::chain::{Chain, Support, SupportKind};
use jointid::model::fixtures::steel_bar;
use jointid::model::matrix_market;
use jointid::structure::{Matrices, SymMatrix};

/// The Matrix Market writer the benchmark needs (not the project's reader/writer).
fn write_matrix_market(a: &SymMatrix, path: &Path) -> std::io::Result<()> {
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

fn read_matrix(path: &Path) -> SymMatrix {
    let lower = matrix_market::from_path(path).expect("a matrix written by `export`");
    SymMatrix::from_entries(lower.size, &lower.both_triangles())
}

/// `structure` as an external model in `dir` (what `jointid simulate` reads in the
/// whole-process runs): an external model needs a parameter, so the cantilever gets a
/// grounded spring at its tip of 1e-300 N/m, which leaves K(p) bitwise K (K's tip entries are
/// of order 1e8).
fn write_external(structure: &mut jointid::structure::Structure, dir: &Path) {
    let tip = structure.dof_count() - 2;
    let mut spring = jointid::structure::SparseSym::zero();
    spring.add(tip, tip, 1.0);
    structure.parameters.push(jointid::structure::Parameter {
        name: "tip_spring".into(),
        unit: "N/m",
        value: 1e-300,
        stiffness: spring,
        mass: jointid::structure::SparseSym::zero(),
        role: jointid::structure::Role::Fixed,
    });
    let exported = jointid::model::matrices::export(structure, "eigen_bench export chain")
        .expect("an exportable chain");
    std::fs::create_dir_all(dir).expect("the model folder");
    for (name, bytes) in &exported.files {
        std::fs::write(dir.join(name), bytes).expect("write the model's files");
    }
}

fn export(kind: &str, what: &str, dir: &Path) {
    let (mats, rigid): (Matrices, usize) = match kind {
        "chain" => {
            let elements: usize = what.parse().expect("ELEMENTS");
            let mut chain = Chain::free(vec![steel_bar(1.0, elements)], vec![]);
            chain.supports.push(Support {
                x: 0.0,
                kind: SupportKind::Clamped,
                identify: [false, false],
            });
            let mut structure = chain.build();
            write_external(&mut structure, &dir.join("model"));
            (structure.assemble(), 0)
        }
        "model" => {
            let path = Path::new(what);
            let text = std::fs::read_to_string(path).expect("the model file");
            let structure =
                jointid::model::matrices::from_toml(&text, path).expect("a valid external model");
            (structure.assemble(), structure.rigid)
        }
        _ => panic!("export chain ELEMENTS DIR | export model MODEL.toml DIR"),
    };
    write_matrix_market(&mats.k, &dir.join("k.mtx")).expect("write k.mtx");
    write_matrix_market(&mats.m, &dir.join("m.mtx")).expect("write m.mtx");
    let shift = default_shift(mats.k.as_faer(), mats.m.as_faer());
    std::fs::write(
        dir.join("case.txt"),
        format!("rigid {rigid}\nshift {shift:e}\ndofs {}\n", mats.size()),
    )
    .expect("write case.txt");
    println!(
        "N = {}, nnz(K) = {}, rigid-body modes {rigid}",
        mats.size(),
        mats.k.nnz()
    );
}

fn solve(dir: &Path, count: usize) {
    let case = std::fs::read_to_string(dir.join("case.txt")).expect("case.txt");
    let rigid: usize = case
        .lines()
        .find_map(|l| l.strip_prefix("rigid "))
        .and_then(|v| v.parse().ok())
        .expect("rigid in case.txt");
    let (k, m) = (
        read_matrix(&dir.join("k.mtx")),
        read_matrix(&dir.join("m.mtx")),
    );
    let t = Instant::now();
    let modes = lowest_modes(
        k.as_faer(),
        m.as_faer(),
        rigid + count,
        &LanczosSettings::default(),
    )
    .expect("solve");
    let seconds = t.elapsed().as_secs_f64();
    let res = residuals(
        k.as_faer(),
        m.as_faer(),
        &modes.values,
        modes.vectors.as_ref(),
    );
    println!("time_s {seconds:.4}");
    println!(
        "threads {} restarts {} operator_applications {} refinement_sweeps {}",
        rayon::current_num_threads(),
        modes.restarts,
        modes.operator_applications,
        modes.refinement_sweeps
    );
    let t = modes.timings;
    println!(
        "phases_s factorisation {:.4} solves {:.4} orthogonalisation {:.4} refinement {:.4} total {:.4}",
        t.factorisation, t.solves, t.orthogonalisation, t.refinement, t.total
    );
    let pairs = modes.values.iter().zip(&res).zip(&modes.backward_errors);
    for (j, ((&lambda, r), eta)) in pairs.enumerate().skip(rigid) {
        println!(
            "mode {} hz {:.9} relative_residual {:.2e} floor {:.2e} backward_error {eta:.1e}",
            j - rigid + 1,
            jointid::modal::lambda_to_hz(lambda),
            r.relative,
            r.floor,
        );
    }
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let arg = |i: usize| args.get(i).map(String::as_str).unwrap_or("");
    match arg(1) {
        "export" => export(arg(2), arg(3), Path::new(arg(4))),
        "solve" => solve(Path::new(arg(2)), arg(3).parse().expect("COUNT")),
        _ => panic!(
            "usage: eigen_bench export chain ELEMENTS DIR | export model MODEL.toml DIR | solve DIR COUNT"
        ),
    }
}
