//! Probe of the sparse eigensolver (module docs of `jointid::modal::lanczos`): the lowest
//! `count` frequencies of the paper's chain refined to `na` + `nb` elements, for each shift
//! given (a positive number s means sigma = -s; `d` the default rule), with time, restarts,
//! operator applications, refinement sweeps and the largest backward error.
//!
//! `cargo run --release --example shift_probe -- 5000 5000 7 1e6 1e8 d`
use jointid::modal::lambda_to_hz;
use jointid::modal::lanczos::{LanczosSettings, default_shift, lowest_modes};
use jointid::model::chain::Chain;
use jointid::model::chain::joint::Joint;
use jointid::model::fixtures::steel_bar;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let na: usize = args[1].parse().unwrap();
    let nb: usize = args[2].parse().unwrap();
    let count: usize = args[3].parse().unwrap();
    let chain = Chain::free(
        vec![steel_bar(0.2, na), steel_bar(0.3, nb)],
        vec![Joint::identified(1e7, 1e4)],
    );
    let mats = chain.build().assemble();
    let (k, m) = (mats.k.as_faer(), mats.m.as_faer());
    println!("N = {} default shift {:e}", k.nrows(), default_shift(k, m));
    for s in &args[4..] {
        let shift: Option<f64> = if s == "d" {
            None
        } else {
            Some(-s.parse::<f64>().unwrap())
        };
        let t = std::time::Instant::now();
        let r = lowest_modes(
            k,
            m,
            count,
            &LanczosSettings {
                shift,
                ..Default::default()
            },
        );
        let dt = t.elapsed().as_secs_f64();
        match r {
            Ok(r) => println!(
                "shift {:e}: {:.3} s restarts {} ops {} sweeps {} f = {:?} eta max {:e}",
                r.shift,
                dt,
                r.restarts,
                r.operator_applications,
                r.refinement_sweeps,
                r.values
                    .iter()
                    .take(7)
                    .map(|l| format!("{:.6}", lambda_to_hz(*l)))
                    .collect::<Vec<_>>(),
                r.backward_errors.iter().cloned().fold(0.0, f64::max)
            ),
            Err(e) => println!("shift {s}: {e} ({dt:.3} s)"),
        }
    }
}
