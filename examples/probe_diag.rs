use jointid::diagnose::fit::{Noise, fit};
use jointid::modal::ModalSolution;
use jointid::model::effects::{Configured, EffectContext, by_name, candidates};
use jointid::model::fixtures::paper_model;
use jointid::simulate::{Errors, measured_modes};
use jointid::stats::chi2_sf;
use jointid::study::NoiseKind;
use std::sync::Arc;
fn main() {
    let model = paper_model(1e7, 1e4);
    let nominal = ModalSolution::solve(&model.assemble()).unwrap();
    let ctx = EffectContext {
        model: model.clone(),
        sensor_nodes: (0..19).collect(),
        first_elastic_hz: nominal.frequency_hz(2),
    };
    let dofs: Vec<usize> = (0..38).step_by(2).collect();
    let noise = Noise {
        frequency: 0.001,
        shape: 0.02,
    };
    for (name, size) in [
        ("none", 0.0),
        ("joint_mass", 0.05),
        ("sensor_mass", 0.03),
        ("joint_coupling", 0.5),
        ("suspension", 0.2),
        ("shear", 1.0),
        ("element_damage", 0.3),
    ] {
        for seed in [1, 2] {
            let effects = if name == "none" {
                vec![]
            } else {
                let e = by_name(name).unwrap();
                let t = e.theta_of_size(&ctx, size);
                vec![(e, t)]
            };
            let truth = Configured {
                ctx: ctx.clone(),
                model: model.clone(),
                effects,
            };
            let tm = ModalSolution::solve(&truth.assemble()).unwrap();
            let data = measured_modes(
                &tm,
                &[1, 2, 3, 4, 5, 6],
                &dofs,
                Errors {
                    shape: 0.02,
                    frequency: 0.001,
                    kind: NoiseKind::Gaussian,
                    seed,
                },
            );
            let t0 = std::time::Instant::now();
            let base = fit(&ctx, &data, noise, &[]).unwrap();
            let mut line = format!(
                "{name:>15} s{seed}: base chi2 {:.1}/{} p {:.2e} it {} |",
                base.chi2,
                base.dof,
                chi2_sf(base.chi2, base.dof as f64),
                base.iterations
            );
            for c in candidates() {
                match fit(&ctx, &data, noise, &[c.clone() as Arc<_>]) {
                    Ok(f) => {
                        let est = f.estimates.last().unwrap();
                        line += &format!(
                            " {}: d{:.1} it{} ({:.3}±{:.3})",
                            &c.name()[..5],
                            base.chi2 - f.chi2,
                            f.iterations,
                            c.size_of_theta(&ctx, &[est.value]),
                            est.se / est.value.abs().max(1e-300)
                                * c.size_of_theta(&ctx, &[est.value]).abs()
                        );
                    }
                    Err(e) => {
                        line += &format!(" {}: ERR {e}", c.name());
                    }
                }
            }
            println!("{line} [{:.0} ms]", t0.elapsed().as_secs_f64() * 1e3);
        }
    }
}
