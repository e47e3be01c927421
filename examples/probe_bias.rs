use jointid::diagnose::fit::{Noise, fit};
use jointid::modal::ModalSolution;
use jointid::model::effects::{Configured, EffectContext, by_name};
use jointid::model::fixtures::paper_model;
use jointid::simulate::{Errors, measured_modes};
use jointid::study::NoiseKind;
fn main() {
    let model = paper_model(1e7, 1e4);
    let nominal = ModalSolution::solve(&model.assemble()).unwrap();
    let ctx = EffectContext {
        model: model.clone(),
        sensor_nodes: (0..19).collect(),
        first_elastic_hz: nominal.frequency_hz(2),
    };
    let dofs: Vec<usize> = (0..38).step_by(2).collect();
    let args: Vec<String> = std::env::args().collect();
    let (name, size, sn, fnz): (&str, f64, f64, f64) = (
        &args[1],
        args[2].parse().unwrap(),
        args[3].parse().unwrap(),
        args[4].parse().unwrap(),
    );
    let noise = Noise {
        frequency: 0.001,
        shape: 0.02,
    };
    let e = by_name(name).unwrap();
    let truth_theta = e.theta_of_size(&ctx, size);
    let truth = Configured {
        ctx: ctx.clone(),
        model: model.clone(),
        effects: vec![(e.clone(), truth_theta.clone())],
    };
    let tm = ModalSolution::solve(&truth.assemble()).unwrap();
    let mut z = vec![Vec::new(); 3];
    for seed in 1..=150 {
        let data = measured_modes(
            &tm,
            &[1, 2, 3, 4, 5, 6],
            &dofs,
            Errors {
                shape: sn,
                frequency: fnz,
                kind: NoiseKind::Gaussian,
                seed,
            },
        );
        let f = fit(&ctx, &data, noise, &[e.clone()]).unwrap();
        let t = [1e7, 1e4, truth_theta[0]];
        for k in 0..3 {
            z[k].push((f.estimates[k].value - t[k]) / f.estimates[k].se);
        }
    }
    for (k, zk) in z.iter().enumerate() {
        let mean = zk.iter().sum::<f64>() / zk.len() as f64;
        let sd =
            (zk.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (zk.len() - 1) as f64).sqrt();
        println!("{name} shape {sn} freq {fnz} param {k}: z mean {mean:.2} sd {sd:.2}");
    }
}
