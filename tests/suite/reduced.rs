//! The parametric reduced model (`jointid::modal::reduced`) on a 3D solid (the small lap of
//! the solid tests, 540 DOFs, read back as an external model): its pairs against the full
//! solve at parameters far from the nominal ones, the enrichment of a basis too poor for
//! them, its derivatives against central differences, the same bits on any number of
//! threads; and a diagnosis of a larger lap on it, checked against the full model.

use std::path::{Path, PathBuf};
use std::sync::Arc;

use jointid::modal::reduced::{self, TOLERANCE, derivative::derivative};
use jointid::modal::{ModalSolution, lambda_to_hz};
use jointid::model::solid::{Solid, SolidConfig};
use jointid::structure::Structure;
use jointid::structure::reduced::Reduced;

use crate::common::scratch;
use crate::solid::LAP;

const RIGID: usize = 6;
/// Pairs asked for: the rigid-body modes and ten elastic ones (eight measured and two).
const COUNT: usize = RIGID + 10;

/// The small lap as an external model, from its files.
fn lap(name: &str, text: &str) -> Structure {
    let dir = scratch("reduced", name);
    let solid =
        Solid::generate(&SolidConfig::from_toml(text, Path::new("lap.toml")).unwrap()).unwrap();
    for file in solid.file_names() {
        let mut f = std::fs::File::create(dir.join(&file)).unwrap();
        solid.write_file(&file, "lap.toml", &mut f).unwrap();
    }
    let structure = jointid::model::from_path(&dir.join("model.toml")).unwrap();
    std::fs::remove_dir_all(&dir).unwrap();
    structure
}

/// `structure` carrying the basis of `jointid diagnose`: the nominal rigid + 2 x 8 + 2 pairs
/// and the static corrections of the ten elastic pairs in every parameter's direction;
/// `modes` nominal pairs and no corrections for a poor one.
fn reduced_lap(structure: &Structure, modes: usize, corrections: bool) -> Structure {
    let nominal = ModalSolution::lowest_of(&structure.assemble(), modes).unwrap();
    let params = structure.identified();
    let directions: Vec<_> = params
        .iter()
        .map(|p| (&p.stiffness, &p.mass))
        .filter(|_| corrections)
        .collect();
    let built = reduced::build(
        structure,
        &nominal,
        None,
        &directions,
        RIGID..COUNT,
        TOLERANCE,
    )
    .unwrap();
    let mut out = structure.clone();
    out.reduced = Some(Arc::new(built));
    out
}

/// `structure` with its parameters (shear x, shear y, normal) scaled by `factors`.
fn scaled(structure: &Structure, factors: [f64; 3]) -> Structure {
    let values: Vec<f64> = structure
        .identified()
        .iter()
        .zip(factors)
        .map(|(p, f)| p.value * f)
        .collect();
    structure.with_values(&values)
}

/// The largest |f_reduced / f_full - 1| and 1 - MAC over the elastic pairs.
fn against_full(reduced: &ModalSolution, structure: &Structure) -> (f64, f64) {
    let full = reduced::full(structure, &[], reduced.len()).unwrap();
    let (mut df, mut dmac) = (0.0_f64, 0.0_f64);
    for j in RIGID..reduced.len() {
        df = df.max((reduced.frequency_hz(j) / full.frequency_hz(j) - 1.0).abs());
        let (a, b) = (reduced.vectors().col(j), full.vectors().col(j));
        let ab = a.transpose() * b;
        dmac = dmac.max(1.0 - ab * ab / (a.squared_norm_l2() * b.squared_norm_l2()));
    }
    (df, dmac)
}

#[test]
fn reduced_pairs_of_a_solid_are_the_full_ones_far_from_the_nominal_springs() {
    let structure = reduced_lap(&lap("far", LAP), RIGID + 2 * 8 + 2, true);
    for factors in [
        [1.0, 1.0, 1.0],
        [1.0, 1.0, 0.5],
        [0.5, 2.0, 0.5],
        [0.2, 3.0, 0.3],
    ] {
        let at = scaled(&structure, factors);
        let modal = reduced::lowest(&at, &[], COUNT).unwrap();
        let pairs = modal.reduced().expect("solved on the reduced model");
        assert!(pairs.residuals.iter().all(|&e| e <= TOLERANCE));
        let (df, dmac) = against_full(&modal, &at);
        assert!(df < 1e-7, "{factors:?}: frequencies {df:e}");
        assert!(dmac < 1e-6, "{factors:?}: 1 - MAC {dmac:e}");
    }
}

/// The basis built on the nominal solve's factor of K - sigma M (identify's path,
/// `ModalSolution::lowest_of_factored`) is the basis built on its own factorisation, bit for
/// bit, and so are the pairs solved on it; a factor of another size is refused.
#[test]
fn a_basis_on_the_nominal_solves_factor_is_the_same_bits() {
    let structure = lap("factor", LAP);
    let mut nominal =
        ModalSolution::lowest_of_factored(&structure.assemble(), RIGID + 2 * 8 + 2).unwrap();
    let factor = nominal
        .take_factor()
        .expect("a sparse solve keeps its factor");
    assert!(nominal.take_factor().is_none(), "taken out");
    let alone = ModalSolution::lowest_of(&structure.assemble(), RIGID + 2 * 8 + 2).unwrap();
    assert_eq!(nominal.values(), alone.values());
    let params = structure.identified();
    let directions: Vec<_> = params.iter().map(|p| (&p.stiffness, &p.mass)).collect();
    let build = |f| {
        reduced::build(
            &structure,
            &nominal,
            f,
            &directions,
            RIGID..COUNT,
            TOLERANCE,
        )
    };
    let (shared, own) = (
        build(Some(Arc::clone(&factor))).unwrap(),
        build(None).unwrap(),
    );
    assert_eq!(shared.k, own.k);
    assert_eq!(shared.m, own.m);
    let with = |r: Reduced| {
        let mut s = scaled(&structure, [0.3, 2.0, 1.0]);
        s.reduced = Some(Arc::new(r));
        reduced::lowest(&s, &[], COUNT).unwrap()
    };
    let (a, b) = (with(shared), with(own));
    assert!(a.reduced().is_some() && b.reduced().is_some());
    assert_eq!(a.values(), b.values());
    assert_eq!(a.vectors(), b.vectors());
    let longer = lap("other", &LAP.replace("length = 0.12", "length = 0.16"));
    assert_ne!(longer.dof_count(), structure.dof_count());
    let other = ModalSolution::lowest_of_factored(&longer.assemble(), RIGID + 1)
        .unwrap()
        .take_factor()
        .unwrap();
    assert!(
        build(Some(other)).is_err(),
        "a factor of another model's size"
    );
}

/// A lap of about 3,000 DOFs (a reduced model's) written as an external model into a scratch
/// directory `name`, and four of its modes as measured, 1% off the model's alternately, each
/// seen at three DOFs: (the directory, model.toml, measured.csv, the model's lowest pairs).
fn lap_read_back(name: &str) -> (PathBuf, PathBuf, PathBuf, ModalSolution) {
    let dir = scratch("reduced", name);
    let text = LAP.replace("size = 0.01\nlayers = 1", "size = 0.005\nlayers = 2");
    let solid =
        Solid::generate(&SolidConfig::from_toml(&text, Path::new("lap.toml")).unwrap()).unwrap();
    for file in solid.file_names() {
        let mut f = std::fs::File::create(dir.join(&file)).unwrap();
        solid.write_file(&file, "lap.toml", &mut f).unwrap();
    }
    let path = dir.join("model.toml");
    let plain = jointid::model::from_path(&path).unwrap();
    assert!(reduced::applies(&plain), "{} DOFs", plain.dof_count());
    let modal = reduced::full(&plain, &[], RIGID + 4).unwrap();
    let mut csv = String::from("mode,frequency_hz,label,value\n");
    for r in 1..=4 {
        let f = modal.frequency_hz(RIGID + r - 1) * if r % 2 == 0 { 1.01 } else { 0.99 };
        for i in [0, plain.dof_count() / 2, plain.dof_count() - 1] {
            let y = modal.vectors()[(i, RIGID + r - 1)];
            csv += &format!("{r},{f},{},{y}\n", plain.dofs.get(i).label);
        }
    }
    let measured_path = dir.join("measured.csv");
    std::fs::write(&measured_path, csv).unwrap();
    (dir, path, measured_path, modal)
}

/// `jointid identify --from-frequency` on a lap of about 3,000 DOFs (a reduced model's): the
/// pairs the check of its rigid-body modes solved when it was read, asked for the
/// identification's count (`nominal_count`), are its nominal pairs with their factor, and
/// identify on them gives the same bits as identify solving them itself.
#[test]
fn identify_takes_the_pairs_and_factor_solved_when_the_model_was_read() {
    use jointid::identify::run::{Request, identify_modes, identify_modes_solved, nominal_count};
    use jointid::measured::MeasuredModes;
    let (dir, path, measured_path, _) = lap_read_back("read-solved");
    let request = Request {
        frequency_noise: Some(1e-3),
        ..Request::default()
    };
    let elastic = |read: &jointid::structure::Structure| {
        let measured = MeasuredModes::from_path(&measured_path, read).unwrap();
        nominal_count(read, &measured, &request).unwrap() - read.rigid
    };
    let (model, nominal) = jointid::model::from_path_solved(&path, &elastic).unwrap();
    let nominal = nominal.unwrap();
    let measured = MeasuredModes::from_path(&measured_path, &model).unwrap();
    assert_eq!(model.rigid, RIGID);
    assert_eq!(
        Some(nominal.len()),
        nominal_count(&model, &measured, &request)
    );
    assert_eq!(nominal.len(), RIGID + 4 + 4 + 2);
    assert!(nominal.clone().take_factor().is_some(), "the read's factor");
    let given = identify_modes_solved(&model, &measured, &request, Some(nominal)).unwrap();
    let alone = identify_modes(&model, &measured, &request).unwrap();
    assert_eq!(format!("{:?}", given.modes), format!("{:?}", alone.modes));
    assert_eq!(given.modes.len(), 4);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// `jointid diagnose` on the same lap: the pairs the check of its rigid-body modes solved when
/// it was read, asked for the diagnosis's count (`diagnose::nominal_count`), are the nominal
/// solution the diagnosis starts from (`calibrate::prepare`), with their factor, the same bits
/// as a solve of its own.
#[test]
fn diagnose_takes_the_pairs_and_factor_solved_when_the_model_was_read() {
    use jointid::diagnose::calibrate::prepare;
    use jointid::diagnose::{DiagnoseSettings, Noise, PairingRule, nominal_count};
    use jointid::measured::MeasuredModes;
    let (dir, path, measured_path, modal) = lap_read_back("read-solved-diagnose");
    let settings = DiagnoseSettings {
        noise: Noise {
            frequency: 1e-3,
            shape: 1e-2,
        },
        pairing: PairingRule::default(),
        per_mode: None,
        extended: false,
        full_model: false,
        causes: Vec::new(),
    };
    let elastic = |read: &jointid::structure::Structure| {
        let measured = MeasuredModes::from_path(&measured_path, read).unwrap();
        nominal_count(read, &measured, &settings) - read.rigid
    };
    let (model, nominal) = jointid::model::from_path_solved(&path, &elastic).unwrap();
    let nominal = nominal.unwrap();
    let measured = MeasuredModes::from_path(&measured_path, &model).unwrap();
    assert_eq!(nominal.len(), nominal_count(&model, &measured, &settings));
    assert_eq!(nominal.len(), RIGID + 2 * 4 + 2);
    let read_factor = nominal.clone().take_factor().unwrap();
    let (_, mut given) = prepare(&model, &measured, &settings, Some(nominal.clone())).unwrap();
    let (_, mut alone) = prepare(&model, &measured, &settings, None).unwrap();
    assert_eq!(given.values(), alone.values());
    assert_eq!(given.vectors(), alone.vectors());
    // Taken, not solved again: the read's own factor, not a new one.
    assert!(
        Arc::ptr_eq(&given.take_factor().unwrap(), &read_factor),
        "the read's pairs and factor taken"
    );
    assert!(!Arc::ptr_eq(&alone.take_factor().unwrap(), &read_factor));
    // A solution of another count is solved again, not taken.
    let (_, other) = prepare(&model, &measured, &settings, Some(modal)).unwrap();
    assert_eq!(other.len(), nominal.len());
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_basis_too_poor_is_enriched_until_its_pairs_are_the_full_ones() {
    let structure = reduced_lap(&lap("poor", LAP), COUNT + 2, false);
    let at = scaled(&structure, [0.6, 1.5, 0.6]);
    // Without the enrichment (a tolerance nothing exceeds), the poor basis misses.
    let mut lax: Reduced = (**structure.reduced.as_ref().unwrap()).clone();
    lax.tolerance = f64::INFINITY;
    let mut unchecked = at.clone();
    unchecked.reduced = Some(Arc::new(lax));
    let poor = reduced::lowest(&unchecked, &[], COUNT).unwrap();
    let (df, _) = against_full(&poor, &at);
    assert!(df > 1e-6, "the poor basis already fits: {df:e}");
    let worst = reduced::residuals(&poor)
        .iter()
        .fold(0.0_f64, |a, &e| a.max(e));
    assert!(
        worst > TOLERANCE,
        "its error estimate {worst:e} does not say so"
    );
    // Checked, it is enriched, stays reduced, and meets the full solve.
    let (modal, enriched) = reduced::lowest_keeping(&at, &[], COUNT).unwrap();
    let enriched = enriched.unwrap_or_else(|| panic!("not enriched (error estimate {worst:e})"));
    assert!(enriched.enriched > 0);
    assert!(enriched.dimension() > structure.reduced.as_ref().unwrap().dimension());
    assert!(modal.reduced().is_some(), "fell back to the full model");
    let (df, dmac) = against_full(&modal, &at);
    assert!(df < 1e-7, "enriched: frequencies {df:e}");
    assert!(dmac < 1e-6, "enriched: 1 - MAC {dmac:e}");
}

/// An enriched copy of a reduction shares the blocks of the basis it grew from
/// (`jointid::structure::columns`). A diagnosis frees the nominal factor its reduced solves
/// kept before it factors the full model for its check (`jointid::modal::reduced::release`):
/// every copy of the reduction, the enriched ones too, lets it go, and a solve after it is the
/// full model's.
#[test]
fn a_released_reduction_frees_its_factor_for_every_copy_and_solves_in_full() {
    let structure = reduced_lap(&lap("release", LAP), COUNT + 2, false);
    let at = scaled(&structure, [0.6, 1.5, 0.6]);
    let (_, enriched) = reduced::lowest_keeping(&at, &[], COUNT).unwrap();
    let enriched = enriched.expect("the poor basis is enriched");
    assert!(enriched.precondition.held());
    // The enriched copy holds the basis it grew from by reference, its new columns alone.
    let first = structure.reduced.as_ref().unwrap().basis.ncols();
    assert!(enriched.basis.ncols() > first);
    for columns in [&enriched.basis, &enriched.k_basis, &enriched.m_basis] {
        assert!(
            columns.shared_blocks() >= 1,
            "the enriched copy copied its basis"
        );
    }
    let mut on_enriched = at.clone();
    on_enriched.reduced = Some(Arc::clone(&enriched));
    assert!(reduced::usable(&on_enriched).is_some());
    reduced::release(&structure);
    assert!(
        !enriched.precondition.held(),
        "the enriched copy kept the factor"
    );
    assert!(reduced::usable(&at).is_none() && reduced::usable(&on_enriched).is_none());
    let after = reduced::lowest(&on_enriched, &[], COUNT).unwrap();
    assert!(after.reduced().is_none(), "solved on a released reduction");
    let full = reduced::full(&at, &[], COUNT).unwrap();
    assert_eq!(after.values(), full.values());
}

#[test]
fn reduced_derivatives_match_central_differences_of_the_reduced_model() {
    let structure = reduced_lap(&lap("derivative", LAP), RIGID + 2 * 8 + 2, true);
    // The basis held fixed: the derivatives are the reduced model's own.
    let mut fixed: Reduced = (**structure.reduced.as_ref().unwrap()).clone();
    fixed.tolerance = f64::INFINITY;
    let mut at = scaled(&structure, [0.7, 1.3, 0.8]);
    at.reduced = Some(Arc::new(fixed));
    let modal = reduced::lowest(&at, &[], COUNT).unwrap();
    let pairs = modal.reduced().unwrap();
    let params = at.identified();
    for (i, p) in params.iter().enumerate() {
        let h = 1e-4 * p.value;
        let solve = |d: f64| {
            let mut values: Vec<f64> = params.iter().map(|q| q.value).collect();
            values[i] += d;
            reduced::lowest(&at.with_values(&values), &[], COUNT).unwrap()
        };
        let (plus, minus) = (solve(h), solve(-h));
        for s in [RIGID, RIGID + 3, COUNT - 1] {
            let (d_lambda, dx) = derivative(&modal, pairs, s, &p.stiffness, &p.mass).unwrap();
            let fd = (plus.values()[s] - minus.values()[s]) / (2.0 * h);
            assert!(
                (fd - d_lambda).abs()
                    <= 1e-5 * d_lambda.abs().max(1e-9 * modal.values()[s] / p.value),
                "{} pair {s}: d lambda {d_lambda:e} against {fd:e}",
                p.name
            );
            let fdx: Vec<f64> = (0..dx.len())
                .map(|k| (plus.vectors()[(k, s)] - minus.vectors()[(k, s)]) / (2.0 * h))
                .collect();
            // A mode that hardly sees the parameter: its vector's change measured against
            // the vector, 1e-8 of it per relative change of the parameter.
            let floor = 1e-8 * modal.vectors().col(s).norm_max() / p.value;
            let scale = fdx.iter().fold(floor, |a, v| a.max(v.abs()));
            let off = dx
                .iter()
                .zip(&fdx)
                .fold(0.0_f64, |a, (x, y)| a.max((x - y).abs()));
            assert!(
                off <= 1e-3 * scale,
                "{} pair {s}: d x off by {off:e} of {scale:e}",
                p.name
            );
        }
    }
}

#[test]
fn a_reduced_solve_is_the_same_bits_on_any_number_of_threads() {
    let structure = reduced_lap(&lap("threads", LAP), COUNT + 2, false);
    let at = scaled(&structure, [0.3, 2.0, 0.4]);
    let on = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| reduced::lowest(&at, &[], COUNT).unwrap())
    };
    let (one, two) = (on(1), on(2));
    let bits = |m: &ModalSolution| -> Vec<u64> {
        m.values()
            .iter()
            .chain(m.vectors().col_as_slice(COUNT - 1))
            .map(|v| v.to_bits())
            .collect()
    };
    assert_eq!(bits(&one), bits(&two));
    assert!(lambda_to_hz(one.values()[RIGID]) > 0.0);
}

/// A lap of about 3,000 DOFs (above `jointid::modal::reduced::MIN_DOFS`), its normal spring
/// halved in the data, diagnosed through the command: on the reduced model, the verdict
/// `none`, the spring calibrated back within three standard errors, and the reduced model's
/// check against one full solve in the report, every frequency within 1e-6. And again with
/// `--full-model` (every solve on the full model, no check in the report): the same verdict,
/// every parameter and its standard error within 0.05 of a standard error of the reduced
/// run's.
#[test]
#[ignore = "seconds in release, a minute unoptimised: .ci/run runs it in release"]
fn a_solid_lap_is_diagnosed_on_its_reduced_model_and_checked_by_a_full_solve() {
    use crate::common::{jointid_ok, s};
    let dir = scratch("reduced", "diagnose");
    let config = dir.join("lap.toml");
    std::fs::write(
        &config,
        LAP.replace("size = 0.01\nlayers = 1", "size = 0.005\nlayers = 2"),
    )
    .unwrap();
    let model = dir.join("model");
    jointid_ok(&["solid", s(&config), "--out", s(&model)]);
    let text = std::fs::read_to_string(model.join("model.toml")).unwrap();
    let at = text.find("name = \"k_normal\"").unwrap();
    let line = at + text[at..].find("value = ").unwrap();
    let end = line + text[line..].find('\n').unwrap();
    let nominal: f64 = text[line + 8..end].trim().parse().unwrap();
    let truth = format!(
        "{}value = {:e}{}",
        &text[..line],
        nominal / 2.0,
        &text[end..]
    );
    std::fs::write(model.join("truth.toml"), truth).unwrap();
    let measured = dir.join("measured.csv");
    jointid_ok(&[
        "simulate",
        "--model",
        s(&model.join("truth.toml")),
        "--modes",
        "6",
        "--measure",
        "w",
        "--shape-noise",
        "0.01",
        "--frequency-noise",
        "0.001",
        "--seed",
        "1",
        "--out",
        s(&measured),
    ]);
    let diagnosed = |name: &str, extra: &[&str]| -> serde_json::Value {
        let json = dir.join(name);
        let model_file = model.join("model.toml");
        let mut args = vec![
            "diagnose",
            "--model",
            s(&model_file),
            "--measured",
            s(&measured),
            "--frequency-noise",
            "0.001",
            "--shape-noise",
            "0.01",
            "--json",
            s(&json),
            "--quiet",
            "--n",
            "16",
            "--m",
            "6",
        ];
        args.extend(extra);
        jointid_ok(&args);
        serde_json::from_str(&std::fs::read_to_string(&json).unwrap()).unwrap()
    };
    let r = diagnosed("diagnose.json", &[]);
    assert_eq!(r["verdict"], "none", "{}", r["verdict"]);
    let check = &r["reduction"];
    assert_eq!(check["verified"], true, "{check}");
    assert!(check["largest_frequency_difference"].as_f64().unwrap() < 1e-6);
    assert_eq!(check["modes"].as_array().unwrap().len(), 6);
    let k = r["after"]["parameters"]
        .as_array()
        .unwrap()
        .iter()
        .find(|p| p["name"] == "k_normal")
        .unwrap();
    let (value, se) = (k["value"].as_f64().unwrap(), k["se"].as_f64().unwrap());
    assert!(
        (value - nominal / 2.0).abs() < 3.0 * se,
        "k_normal {value:e} +- {se:e} against {:e}",
        nominal / 2.0
    );
    let full = diagnosed("full.json", &["--full-model"]);
    assert_eq!(full["verdict"], r["verdict"]);
    assert!(full["reduction"].is_null(), "{}", full["reduction"]);
    let parameters = |r: &serde_json::Value| -> Vec<(String, f64, f64)> {
        r["after"]["parameters"]
            .as_array()
            .unwrap()
            .iter()
            .map(|p| {
                let name = p["name"].as_str().unwrap().to_string();
                (
                    name,
                    p["value"].as_f64().unwrap(),
                    p["se"].as_f64().unwrap(),
                )
            })
            .collect()
    };
    let (on_reduced, on_full) = (parameters(&r), parameters(&full));
    assert_eq!(on_reduced.len(), on_full.len());
    for ((name, value, se), (_, full_value, full_se)) in on_reduced.iter().zip(&on_full) {
        assert!(
            (value - full_value).abs() <= 0.05 * full_se && (se - full_se).abs() <= 0.05 * full_se,
            "{name}: {value:e} +- {se:e} reduced, {full_value:e} +- {full_se:e} full"
        );
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// The frequency-only search's far ends (`jointid::identify::reach`): where the reduced
/// model settles the bracket, its sides are the full model's, and its high end (the side read
/// through the error estimate) is off the full eigenvalue by less than the margin the rule
/// leaves; where it does not (the measured value out of reach), the full model's ends, as
/// before. Measured here: the reduced eigenvalues at or above the full ones (Rayleigh-Ritz);
/// their relative error at the stiff end mostly 1.0-1.1 times the estimate, once 5e-9 against
/// 1e-11; at the soft end up to 40 times it (the nominal factor's inverse is stiffer than the
/// softened model's: the reason the side below the target is read from the Rayleigh-Ritz
/// bound, not from the estimate).
#[test]
fn far_ends_of_a_reach_on_the_reduced_model_take_the_full_models_sides() {
    use jointid::identify::frequency_only::REACH;
    use jointid::identify::reach::{Ends, MARGIN};
    let structure = reduced_lap(&lap("reach", LAP), RIGID + 2 * 8 + 2, true);
    let ends = Ends::new(&structure, COUNT);
    let nominal = reduced::full(&structure, &[], COUNT).unwrap();
    let (mut from_reduced, mut from_full) = (0, 0);
    for param in 0..structure.identified().len() {
        let at = |factor: f64| {
            let mut v: Vec<f64> = structure.identified().iter().map(|p| p.value).collect();
            v[param] *= factor;
            structure.with_values(&v)
        };
        let (low, high) = (at(1.0 / REACH), at(REACH));
        let full_low = reduced::full(&low, &[], COUNT).unwrap();
        let full_high = reduced::full(&high, &[], COUNT).unwrap();
        let estimated = reduced::estimated(&high, &[], COUNT).unwrap().unwrap();
        for t in RIGID..COUNT {
            let (lo, hi) = (full_low.values()[t].ln(), full_high.values()[t].ln());
            // The root at the nominal value, and a measured value 2% above it, out of the
            // reach of some modes.
            for scale in [1.0, 1.02] {
                let target = (scale * nominal.values()[t]).ln();
                let b = ends.bracket(param, t, target).unwrap().unwrap();
                let case = format!("parameter {param}, pair {t}, target x {scale}");
                assert_eq!((b.low - target).signum(), (lo - target).signum(), "{case}");
                assert_eq!((b.high - target).signum(), (hi - target).signum(), "{case}");
                if b.reduced {
                    from_reduced += 1;
                    assert!(b.low - lo > -1e-9, "{case}: below the full model's");
                    let e = reduced::residuals(&estimated)[t];
                    if b.high != hi {
                        assert!(e <= MARGIN * (b.high - target), "{case}: estimate {e:e}");
                    }
                    assert!(
                        (b.high - hi).abs() <= MARGIN * (b.high - target),
                        "{case}: high end {:e} off, estimate {e:e}",
                        b.high - hi
                    );
                } else {
                    from_full += 1;
                    assert!((lo - hi).signum() == (lo - target).signum() || (hi - lo).abs() < 1e-5);
                    assert_eq!((b.low, b.high), (lo, hi), "{case}");
                }
            }
        }
    }
    assert!(
        from_reduced > 0 && from_full > 0,
        "{from_reduced} reduced, {from_full} full"
    );
}
