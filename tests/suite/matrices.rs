//! External models (`kind = "matrices"`): the reader against analytic frequencies, the export
//! round trip of the paper's model, and every bad input with its message.
//!
//! Independence of the test data: the 2-DOF fixtures (tests/fixtures/matrices/two-dof/) are
//! hand-written Matrix Market files of a spring-mass system whose eigenvalues are known in
//! closed form (see its README); no code of the crate produced them. The round trip compares
//! the exported-and-read model with the beam-chain builder's model, a different code path that
//! shares only the Matrix Market writer's output; its claim is bitwise identity (see
//! `paper_model_round_trips_bit_for_bit`). Bad inputs are the fixtures with one edit each.

use crate::common;

use std::path::{Path, PathBuf};

use crate::common::{paper_model, scratch};
use jointid::modal::ModalSolution;
use jointid::model::matrices::{export, export::identical};
use jointid::structure::{Direction, Role};

const FIXTURES: &str = concat!(
    env!("CARGO_MANIFEST_DIR"),
    "/tests/fixtures/matrices/two-dof"
);

fn fixture(name: &str) -> PathBuf {
    Path::new(FIXTURES).join(name)
}

/// A scratch copy of the fixtures with `edits` (file name, new text) applied.
fn edited(name: &str, edits: &[(&str, &str)]) -> PathBuf {
    let dir = scratch("matrices", name);
    for entry in std::fs::read_dir(FIXTURES).unwrap() {
        let p = entry.unwrap().path();
        std::fs::copy(&p, dir.join(p.file_name().unwrap())).unwrap();
    }
    for (file, text) in edits {
        std::fs::write(dir.join(file), text).unwrap();
    }
    dir
}

fn eigenvalues(model: &jointid::structure::Structure) -> Vec<f64> {
    ModalSolution::solve(&model.assemble())
        .unwrap()
        .values()
        .to_vec()
}

#[test]
fn grounded_two_dof_system_has_the_analytic_eigenvalues() {
    let model = jointid::model::from_path(&fixture("grounded.toml")).unwrap();
    assert_eq!(model.dof_count(), 2);
    assert_eq!(model.rigid, 0);
    // The table lists m2 first: rows come back in dof order.
    assert_eq!(model.dofs.get(0).label, "m1");
    assert_eq!(model.dofs.get(1).position, [0.1, 0.0, 0.0]);
    assert_eq!(model.dofs.get(1).direction, Direction::X);
    assert_eq!(model.parameters[0].role, Role::Identified);
    assert_eq!(model.parameters[0].unit, "N/m");
    // lambda = (3 -+ sqrt 5) / 2 k / m, k = 5000 N/m, m = 2 kg.
    let km = 5000.0 / 2.0;
    let expected = [
        (3.0 - 5f64.sqrt()) / 2.0 * km,
        (3.0 + 5f64.sqrt()) / 2.0 * km,
    ];
    for (got, want) in eigenvalues(&model).iter().zip(expected) {
        assert!(((got - want) / want).abs() < 1e-14, "{got} against {want}");
    }
    // The mass scale of the effects: the rigid translation's mass, 4 kg.
    assert_eq!(model.sites.beam_mass, 4.0);
}

#[test]
fn free_two_dof_system_has_one_rigid_body_mode() {
    let model = jointid::model::from_path(&fixture("free.toml")).unwrap();
    assert_eq!(model.rigid, 1);
    let values = eigenvalues(&model);
    // lambda = 0 (to round-off of the elastic scale) and 2 k / m = 5000 rad^2/s^2.
    assert!(values[0].abs() < 1e-12 * 5000.0, "{}", values[0]);
    assert!(
        ((values[1] - 5000.0) / 5000.0).abs() < 1e-14,
        "{}",
        values[1]
    );
    // dK/dk is the spring pattern read from the lower triangle.
    let mut k = model.parameters[0].stiffness.entries().to_vec();
    k.sort_by_key(|e| (e.0, e.1));
    assert_eq!(
        k,
        vec![(0, 0, 1.0), (0, 1, -1.0), (1, 0, -1.0), (1, 1, 1.0)]
    );
}

/// Export of the paper's model and read back: identical matrices, hence identical
/// frequencies, bit for bit. Bitwise rather than to a tolerance because nothing is
/// recomputed: every value is written in shortest round-trip decimal form (it parses back to
/// the same double), each position's entries keep their order, so K(p) and M(p) are formed by
/// the same additions in the same order, and the dense solver is deterministic.
#[test]
fn paper_model_round_trips_bit_for_bit() {
    let chain = paper_model(1.0e7, 1.0e4);
    let dir = scratch("matrices", "round-trip");
    let exported = export(&chain, "models/paper-case-1.toml").unwrap();
    for (name, bytes) in &exported.files {
        std::fs::write(dir.join(name), bytes).unwrap();
    }
    let back = jointid::model::from_path(&dir.join("model.toml")).unwrap();
    identical(&chain, &back).unwrap();
    let (a, b) = (chain.assemble(), back.assemble());
    let bits = |e: Vec<(usize, usize, f64)>| -> Vec<(usize, usize, u64)> {
        e.into_iter().map(|(i, j, v)| (i, j, v.to_bits())).collect()
    };
    assert_eq!(bits(a.k.entries()), bits(b.k.entries()));
    assert_eq!(bits(a.m.entries()), bits(b.m.entries()));
    let (fa, fb) = (eigenvalues(&chain), eigenvalues(&back));
    assert_eq!(fa.len(), 38);
    for (x, y) in fa.iter().zip(&fb) {
        assert_eq!(x.to_bits(), y.to_bits(), "{x} against {y}");
    }
    assert_eq!(back.rigid, 2);
    // The derivatives come back as the same lists, in order: sums over their entries (the
    // sensitivities of eq. (10)) are the same bits as well, and the export says nothing
    // about reordering.
    for (p, q) in chain.parameters.iter().zip(&back.parameters) {
        let list = |s: &jointid::structure::SparseSym| -> Vec<(usize, usize, u64)> {
            s.entries()
                .iter()
                .map(|&(i, j, v)| (i, j, v.to_bits()))
                .collect()
        };
        assert_eq!(list(&p.stiffness), list(&q.stiffness), "{}", p.name);
        assert_eq!(list(&p.mass), list(&q.mass), "{}", p.name);
    }
    assert_eq!(exported.notes.len(), 2, "{:?}", exported.notes);
    // The mass scale of the effects: the rigid translation's mass, rho A L of both beams.
    let beams = 7850.0 * 2.4e-3 * 0.5;
    assert!(
        ((back.sites.beam_mass - beams) / beams).abs() < 1e-13,
        "{}",
        back.sites.beam_mass
    );
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn shipped_example_is_the_paper_model() {
    let shipped = jointid::model::from_path(Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/models/paper-matrices/model.toml"
    )))
    .unwrap();
    identical(&paper_model(1.0e7, 1.0e4), &shipped).unwrap();
}

#[test]
fn fixed_roles_and_mass_derivatives_are_read() {
    let dir = edited(
        "dm",
        &[
            (
                "grounded.toml",
                "kind = \"matrices\"\nstiffness = \"K.mtx\"\nmass = \"M.mtx\"\ndofs = \"dofs.csv\"\n[[parameter]]\nname = \"k\"\nvalue = 5000.0\ndk = \"dK.mtx\"\nrole = \"fixed\"\n[[parameter]]\nname = \"m\"\nunit = \"kg\"\nvalue = 1.0\ndk = \"Z.mtx\"\ndm = \"dM.mtx\"\n",
            ),
            (
                "Z.mtx",
                "%%MatrixMarket matrix coordinate real symmetric\n2 2 0\n",
            ),
            (
                "dM.mtx",
                "%%MatrixMarket matrix coordinate real symmetric\n2 2 1\n2 2 1\n",
            ),
        ],
    );
    let model = jointid::model::from_path(&dir.join("grounded.toml")).unwrap();
    assert_eq!(model.parameters[0].role, Role::Fixed);
    assert_eq!(model.identified().len(), 1);
    // M = diag(2, 2 + 1 kg).
    assert_eq!(model.assemble().m.diagonal(), vec![2.0, 3.0]);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// Every bad input of issue 12: the message names the file, the line or field, the value.
#[test]
fn bad_inputs_are_refused_with_file_line_and_field() {
    let toml = |extra: &str| {
        format!(
            "kind = \"matrices\"\nstiffness = \"K.mtx\"\nmass = \"M.mtx\"\ndofs = \"dofs.csv\"\n{extra}[[parameter]]\nname = \"k\"\nvalue = 5000.0\ndk = \"dK.mtx\"\n"
        )
    };
    type Case<'a> = (&'a str, Vec<(&'a str, String)>, &'a str);
    let cases: Vec<Case> = vec![
        (
            "size",
            vec![("dK.mtx", "%%MatrixMarket matrix coordinate real symmetric\n3 3 1\n3 3 1\n".into())],
            "grounded.toml: parameter[0].dk: the matrix is 3 x 3, but K (stiffness) is 2 x 2: every matrix must have the size of K",
        ),
        (
            "nonsymmetric",
            vec![("M.mtx", "%%MatrixMarket matrix coordinate real general\n2 2 3\n1 1 2\n2 2 2\n1 2 0.5\n".into())],
            "M.mtx:5: the matrix is not symmetric: a(1,2) = 5e-1 but a(2,1) = 0e0",
        ),
        (
            "indefinite",
            vec![("M.mtx", "%%MatrixMarket matrix coordinate real symmetric\n2 2 3\n1 1 1\n2 1 2\n2 2 1\n".into())],
            "grounded.toml: mass: M (with the parameters' p dM/dp) is not positive definite",
        ),
        (
            "massless",
            vec![("M.mtx", "%%MatrixMarket matrix coordinate real symmetric\n2 2 1\n1 1 2\n".into())],
            "grounded.toml: mass: M (with the parameters' p dM/dp) has M[2,2] = 0e0 at dof 2 (`m2`): M must be positive definite, every DOF must carry mass",
        ),
        (
            "no-dk",
            vec![("grounded.toml", "kind = \"matrices\"\nstiffness = \"K.mtx\"\nmass = \"M.mtx\"\ndofs = \"dofs.csv\"\n[[parameter]]\nname = \"k\"\nvalue = 5000.0\n".into())],
            "grounded.toml: parameter[0].dk = (missing) is invalid: every parameter needs dk, the Matrix Market file of dK/dp",
        ),
        (
            "zero-dk",
            vec![("dK.mtx", "%%MatrixMarket matrix coordinate real symmetric\n2 2 1\n1 1 0\n".into())],
            "grounded.toml: parameter[0] (k): dK/dp (and dM/dp) has no nonzero entry",
        ),
        (
            "dk-file",
            vec![("dK.mtx", "%%MatrixMarket matrix coordinate real symmetric\n2 2 1\n1 1 x\n".into())],
            "grounded.toml: parameter[0].dk: ",
        ),
        (
            "dofs",
            vec![("dofs.csv", "dof,label,x,y,z,direction\n1,m1,0,0,0,x\n2,m1,0,0,0,x\n".into())],
            "dofs.csv:3: label = `m1` is given twice (first on line 2): labels must be unique",
        ),
        (
            "dofs-size",
            vec![("dofs.csv", "dof,label,x,y,z,direction\n1,m1,0,0,0,x\n".into())],
            "dofs.csv: dof 2 is missing: the table must list every dof from 1 to 2 once",
        ),
        (
            "rigid",
            vec![("grounded.toml", toml("rigid_body_modes = 1\n"))],
            "grounded.toml: rigid_body_modes = 1 is invalid: the model has 0 (eigenvalues below the rigid-body tolerance",
        ),
        (
            "rigid-remedy",
            vec![("grounded.toml", toml("rigid_body_modes = 1\n"))],
            "Hz: declare the count the model has, or find why it differs (more: a part or a DOF that nothing ties to the rest; fewer: a support or a spring to the ground)",
        ),
        (
            "dofs-direction",
            vec![("dofs.csv", "dof,label,x,y,z,direction\n1,m1,0,0,0,x\n2,m2,0.1,0,0,\n".into())],
            "grounded.toml: dofs: ",
        ),
        (
            "dofs-direction-message",
            vec![("dofs.csv", "dof,label,x,y,z,direction\n1,m1,0,0,0,x\n2,m2,0.1,0,0,\n".into())],
            "dofs.csv:3: direction is empty: every DOF needs one, of w, theta, x, y, z, rx, ry, rz",
        ),
        (
            "k-indefinite",
            vec![("K.mtx", "%%MatrixMarket matrix coordinate real symmetric\n2 2 1\n1 1 -20000\n".into())],
            "grounded.toml: stiffness: K (with the parameters' p dK/dp) is not positive semidefinite",
        ),
        (
            "kind",
            vec![("grounded.toml", "kind = \"matrix\"\n".into())],
            "grounded.toml: kind = \"matrix\" is invalid: it must be \"chain\" (the default) or \"matrices\"",
        ),
        (
            "missing-file",
            vec![("grounded.toml", toml("").replace("K.mtx", "nothere.mtx"))],
            "grounded.toml: stiffness: ",
        ),
    ];
    for (name, edits, message) in cases {
        let edits: Vec<(&str, &str)> = edits.iter().map(|(f, t)| (*f, t.as_str())).collect();
        let dir = edited(name, &edits);
        let e = jointid::model::from_path(&dir.join("grounded.toml"))
            .unwrap_err()
            .to_string();
        assert!(e.contains(message), "{name}: {e}");
        std::fs::remove_dir_all(&dir).unwrap();
    }
}

/// A chain with what the paper's lacks: a fixed joint stiffness, an identified support spring,
/// an identified point mass (dM/dp with rotary inertia), a mass on its own spring DOF and a
/// clamp removing DOFs. Export and read back: the same model bit for bit, the same
/// eigenvalues.
#[test]
fn chain_with_supports_masses_and_fixed_parameters_round_trips() {
    let text = r#"
[[beam]]
length = 0.3
elements = 6
youngs_modulus = 2.1e11
density = 7850.0
area = 2.4e-3
second_moment = 3.2e-7

[[beam]]
length = 0.2
elements = 4
youngs_modulus = 7.0e10
density = 2700.0
area = 2.4e-3
second_moment = 3.2e-7

[[joint]]
k1 = 1.0e7
k2 = 1.0e4
fixed = ["k1"]

[[support]]
x = 0.0
kind = "clamped"

[[support]]
x = 0.5
kind = "spring"
translational = 1.0e5
rotational = 50.0
identify = ["rotational"]

[[mass]]
x = 0.15
mass = 0.05
rotary_inertia = 1e-5
identify = true

[[mass]]
x = 0.4
mass = 0.02
spring = 5.0e4
"#;
    let chain = jointid::model::from_toml(text, Path::new("chain.toml")).unwrap();
    let exported = export(&chain, "chain.toml").unwrap();
    let names: Vec<&str> = exported.files.iter().map(|f| f.0.as_str()).collect();
    assert_eq!(
        names,
        [
            "model.toml",
            "K.mtx",
            "M.mtx",
            "dK_k1.mtx",
            "dK_k2.mtx",
            "dK_support1.rotational.mtx",
            "dK_mass0.m.mtx",
            "dM_mass0.m.mtx",
            "dofs.csv"
        ]
    );
    let dir = scratch("matrices", "setup");
    for (name, bytes) in &exported.files {
        std::fs::write(dir.join(name), bytes).unwrap();
    }
    let back = jointid::model::from_path(&dir.join("model.toml")).unwrap();
    identical(&chain, &back).unwrap();
    assert_eq!(back.parameters[0].role, Role::Fixed);
    assert_eq!(back.identified().len(), 3);
    assert_eq!(back.rigid, 0);
    for (x, y) in eigenvalues(&chain).iter().zip(&eigenvalues(&back)) {
        assert_eq!(x.to_bits(), y.to_bits());
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A nearly free system: a grounded spring k0 = 1e-9 N/m puts lambda_0 = k0 / (m1 + m2) =
/// 2.5e-10 rad^2/s^2 (to first order in k0 / k, 1e-13) above the rigid-body tolerance
/// 1e-14 * 2500 = 2.5e-11: counted, it is elastic; declared as rigid, the gap to
/// lambda_1 = 5000 makes the declaration acceptable.
#[test]
fn a_declared_rigid_count_is_accepted_across_a_clear_gap() {
    let soft = "%%MatrixMarket matrix coordinate real symmetric\n2 2 1\n1 1 1e-9\n";
    let dir = edited("gap", &[("K0.mtx", soft)]);
    let declared = jointid::model::from_path(&dir.join("free.toml")).unwrap();
    assert_eq!(declared.rigid, 1);
    let text = std::fs::read_to_string(dir.join("free.toml"))
        .unwrap()
        .replace("rigid_body_modes = 1\n", "");
    std::fs::write(dir.join("counted.toml"), text).unwrap();
    let counted = jointid::model::from_path(&dir.join("counted.toml")).unwrap();
    assert_eq!(counted.rigid, 0);
    let lambda = eigenvalues(&counted);
    // The dense solution resolves lambda_0 to its absolute round-off, eps * lambda_max ~ 1e-12.
    assert!((lambda[0] - 2.5e-10).abs() < 1e-12, "{}", lambda[0]);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A finer chain (2 x 125 elements, N = 504): the counted rigid-body modes are the chain's two,
/// whose own count is analytic (`rigid_body_modes` of the supports), not from eigenvalues.
#[test]
fn rigid_body_modes_of_a_finer_chain_are_counted() {
    let chain = jointid::model::chain::Chain::free(
        vec![common::steel_bar(0.2, 100), common::steel_bar(0.3, 150)],
        vec![jointid::model::Joint::identified(1e7, 1e4)],
    )
    .build();
    assert_eq!(chain.rigid, 2);
    let dir = scratch("matrices", "fine");
    for (name, bytes) in export(&chain, "fine.toml").unwrap().files {
        let text = String::from_utf8(bytes).unwrap();
        std::fs::write(dir.join(name), text.replace("rigid_body_modes = 2\n", "")).unwrap();
    }
    let back = jointid::model::from_path(&dir.join("model.toml")).unwrap();
    assert_eq!(back.rigid, 2);
    std::fs::remove_dir_all(&dir).unwrap();
}

/// A lapped joint (`kind = "lap"`, the layered lap assembled in the model) of Timoshenko beams
/// exports and reads back with the same eigenvalues, bit for bit: its interface and layer
/// terms are listed symmetrically, entry by entry (the export refused every lap model as
/// "not symmetric" before).
#[test]
fn a_lapped_chain_exports_and_round_trips() {
    let beam = "[[beam]]\nlength = 0.3\nelements = 12\nyoungs_modulus = 2.0e11\ndensity = 7850.0\narea = 3.2258e-4\nsecond_moment = 4.33574e-9\nshear_factor = 0.8333\npoisson = 0.29\n";
    let text = format!(
        "{beam}{beam}[[joint]]\nkind = \"lap\"\n[joint.lap]\nlength = 0.1\nlayers = \"half\"\nk_n = 1.6e10\nk_s = 2.5e9\nk_r = 4.0e3\n"
    );
    let chain = jointid::model::from_toml(&text, Path::new("lap.toml")).unwrap();
    let k = chain.assemble().k;
    assert_eq!(k.asymmetry(), 0.0);
    let exported = export(&chain, "lap.toml").unwrap();
    let dir = scratch("matrices", "lap");
    for (name, bytes) in &exported.files {
        std::fs::write(dir.join(name), bytes).unwrap();
    }
    let back = jointid::model::from_path(&dir.join("model.toml")).unwrap();
    identical(&chain, &back).unwrap();
    assert_eq!(back.identified().len(), 3);
    for (x, y) in eigenvalues(&chain).iter().zip(&eigenvalues(&back)) {
        assert_eq!(x.to_bits(), y.to_bits());
    }
    std::fs::remove_dir_all(&dir).unwrap();
}

/// An open face (issue 43): two bodies touching at a point that nothing ties, as the notch
/// faces of a lap or an open contact in any real mesh. Hand-written, analytic:
///
/// ```text
///   ground --k0-- m1 --k-- m2 | m3 --k0-- ground     m = 2 kg, k0 = k = 5000 N/m,
///                            (m2, m3 both x at 0.1 m)
/// ```
///
/// lambda = (3 -+ sqrt 5) / 2 k / m for m1, m2 and k0 / m for m3. The model reads and solves,
/// the commands say the open face once, and a sensor by position on it asks for the label.
#[test]
fn an_open_face_reads_solves_and_asks_a_sensor_on_it_for_its_label() {
    let dir = edited(
        "open-face",
        &[
            (
                "K.mtx",
                "%%MatrixMarket matrix coordinate real symmetric\n3 3 2\n1 1 5000\n3 3 5000\n",
            ),
            (
                "M.mtx",
                "%%MatrixMarket matrix coordinate real symmetric\n3 3 3\n1 1 2\n2 2 2\n3 3 2\n",
            ),
            (
                "dK.mtx",
                "%%MatrixMarket matrix coordinate real symmetric\n3 3 3\n1 1 1\n2 1 -1\n2 2 1\n",
            ),
            (
                "dofs.csv",
                "dof,label,x,y,z,direction\n1,m1,0,0,0,x\n2,m2,0.1,0,0,x\n3,m3,0.1,0,0,x\n",
            ),
        ],
    );
    let path = dir.join("grounded.toml");
    let model = jointid::model::from_path(&path).unwrap();
    assert_eq!(model.open_faces, 1);
    let found = eigenvalues(&model);
    let r = 5000.0 / 2.0;
    let exact = [
        (3.0 - 5f64.sqrt()) / 2.0 * r,
        r,
        (3.0 + 5f64.sqrt()) / 2.0 * r,
    ];
    for (a, b) in found.iter().zip(exact) {
        assert!((a - b).abs() <= 1e-9 * b, "{found:?} vs {exact:?}");
    }
    let out = dir.join("modes.csv");
    let run = crate::common::jointid_ok(&[
        "simulate",
        "--model",
        path.to_str().unwrap(),
        "--modes",
        "2",
        "--out",
        out.to_str().unwrap(),
    ]);
    let err = String::from_utf8_lossy(&run.stderr);
    assert_eq!(
        err.matches("1 pair(s) of coincident DOFs that nothing ties")
            .count(),
        1,
        "{err}"
    );
    let by_position = dir.join("by_position.csv");
    std::fs::write(
        &by_position,
        "mode,frequency_hz,x,y,z,dof,value\n1,7.0,0.1,0,0,x,1.0\n",
    )
    .unwrap();
    let e = jointid::measured::MeasuredModes::from_path(&by_position, &model)
        .unwrap_err()
        .to_string();
    assert!(e.contains("name the one measured by label"), "{e}");
    let by_label = dir.join("by_label.csv");
    std::fs::write(&by_label, "mode,frequency_hz,label,value\n1,7.0,m3,1.0\n").unwrap();
    assert!(jointid::measured::MeasuredModes::from_path(&by_label, &model).is_ok());
    std::fs::remove_dir_all(&dir).unwrap();
}
