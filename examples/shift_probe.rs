use faer::sparse::{SparseColMat, Triplet};
use jointid::modal::lanczos::{LanczosSettings, lowest_modes, default_shift};
use jointid::model::fixtures::steel_bar;
use jointid::modal::lambda_to_hz;

fn chain(na: usize, nb: usize) -> (SparseColMat<usize, f64>, SparseColMat<usize, f64>) {
    let beams = [steel_bar(0.2, na), steel_bar(0.3, nb)];
    let n = 2 * (na + 1 + nb + 1);
    let (mut kt, mut mt) = (Vec::new(), Vec::new());
    let mut first = 0;
    for b in &beams {
        let (ke, me) = (b.element_stiffness(), b.element_mass());
        for e in 0..b.elements {
            let base = 2 * (first + e);
            for i in 0..4 { for j in 0..4 {
                kt.push(Triplet::new(base + i, base + j, ke[i][j]));
                mt.push(Triplet::new(base + i, base + j, me[i][j]));
            }}
        }
        first += b.elements + 1;
    }
    let a = 2 * na; let bb = 2 * (na + 1);
    for (d, k) in [(0, 1e7), (1, 1e4)] {
        kt.push(Triplet::new(a + d, a + d, k)); kt.push(Triplet::new(bb + d, bb + d, k));
        kt.push(Triplet::new(a + d, bb + d, -k)); kt.push(Triplet::new(bb + d, a + d, -k));
    }
    (SparseColMat::try_new_from_triplets(n, n, &kt).unwrap(), SparseColMat::try_new_from_triplets(n, n, &mt).unwrap())
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let na: usize = args[1].parse().unwrap();
    let nb: usize = args[2].parse().unwrap();
    let count: usize = args[3].parse().unwrap();
    let (k, m) = chain(na, nb);
    println!("N = {} default shift {:e}", k.nrows(), default_shift(k.as_ref(), m.as_ref()));
    for s in &args[4..] {
        let shift: Option<f64> = if s == "d" { None } else { Some(-s.trim_start_matches("n").parse::<f64>().unwrap()) };
        let t = std::time::Instant::now();
        let r = lowest_modes(k.as_ref(), m.as_ref(), count, &LanczosSettings { shift, ..Default::default() });
        let dt = t.elapsed().as_secs_f64();
        match r {
            Ok(r) => println!("shift {:e}: {:.3} s restarts {} ops {} f = {:?} eta max {:e}", r.shift, dt, r.restarts, r.operator_applications,
                r.values.iter().take(7).map(|l| format!("{:.6}", lambda_to_hz(*l))).collect::<Vec<_>>(), r.backward_errors.iter().cloned().fold(0.0, f64::max)),
            Err(e) => println!("shift {s}: {e} ({dt:.3} s)"),
        }
    }
}
