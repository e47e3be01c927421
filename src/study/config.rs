//! The study file (TOML), parsed into raw serde structs that reject unknown keys, then
//! validated field by field into a [`Study`]. Paths are relative to the study file.
//!
//! ```toml
//! name = "paper-case-1"
//! model = "../models/paper-case-1.toml"
//! [truth]
//! delta = { k1 = 2.0e6, k2 = 2.0e3 }
//! [grid]
//! modes = [1, 2, 3, 4]
//! n = [7, 10]
//! m = [5, 7]
//! nf = [0, 5, 23, ["3:theta", "7:w"]]   # a count (the rule of `unidentified`) or a list
//! weighting = ["equal", "inverse", "inverse-sqrt"]
//! shape_noise = [0.04]
//! frequency_noise = [0.0]
//! [monte_carlo]
//! trials = 10000
//! seed = 1
//! noise = "uniform"
//! [output]
//! csv = "../results/paper-case-1.csv"
//! [check]
//! max_abs_relative_bias = 0.05
//! statistic = "mean"
//! where = { n = [10], weighting = ["inverse", "inverse-sqrt"], nf = [0, 5] }
//! ```
//!
//! `grid` may also be an array of tables (`[[grid]]`), each a product of its own axes; the
//! study's cells are then those of every grid, in order. That expresses condition sets that
//! are not a product, such as the paper's (m = 7 needs n >= 9).
//!
//! `name` names the cluster jobs, scripts and shard files: it must be a plain file name
//! ([`crate::input::safe::FILE_NAME`]: letters, digits, `.`, `_`, `-`).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use serde::Deserialize;
use serde::de::value::{MapAccessDeserializer, SeqAccessDeserializer};
use serde::de::{MapAccess, SeqAccess, Visitor};

use super::measured_noise::MeasuredNoise;
use crate::identify::Weighting;
use crate::input::{FieldCheck, InputError, Number, parse_toml, read_file};
use crate::random::NoiseKind;
use crate::structure::{Direction, DofMap, Structure};

/// Largest number of trials per cell: a cell keeps every trial's corrections in memory
/// (trials x modes x q x 8 bytes: 640 MB at this limit with 4 modes and one joint).
pub const MAX_TRIALS: i64 = 10_000_000;

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawStudy {
    name: String,
    model: String,
    truth: RawTruth,
    grid: RawGrids,
    monte_carlo: RawMonteCarlo,
    output: RawOutput,
    check: Option<RawCheck>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawTruth {
    delta: BTreeMap<String, f64>,
}

/// `grid` as one table or an array of tables.
#[derive(Debug)]
enum RawGrids {
    One(RawGrid),
    Many(Vec<RawGrid>),
}

/// Dispatches on the TOML shape instead of trying variants in turn (as `untagged` would), so
/// that an error inside a grid keeps its own message and field path.
impl<'de> Deserialize<'de> for RawGrids {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct Shape;
        impl<'de> Visitor<'de> for Shape {
            type Value = RawGrids;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a [grid] table or an array of [[grid]] tables")
            }
            fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<RawGrids, A::Error> {
                RawGrid::deserialize(MapAccessDeserializer::new(map)).map(RawGrids::One)
            }
            fn visit_seq<A: SeqAccess<'de>>(self, seq: A) -> Result<RawGrids, A::Error> {
                Vec::deserialize(SeqAccessDeserializer::new(seq)).map(RawGrids::Many)
            }
        }
        d.deserialize_any(Shape)
    }
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawGrid {
    modes: Vec<i64>,
    n: Vec<i64>,
    m: Vec<i64>,
    nf: Vec<RawNf>,
    weighting: Vec<String>,
    shape_noise: Vec<f64>,
    frequency_noise: Vec<f64>,
}

/// An entry of `nf`: a count or a list of DOFs.
#[derive(Debug)]
enum RawNf {
    Count(i64),
    List(Vec<String>),
}

impl<'de> Deserialize<'de> for RawNf {
    fn deserialize<D: serde::Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct Shape;
        impl<'de> Visitor<'de> for Shape {
            type Value = RawNf;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a count of unidentified DOFs or a list of \"node:dof\"")
            }
            fn visit_i64<E: serde::de::Error>(self, v: i64) -> Result<RawNf, E> {
                Ok(RawNf::Count(v))
            }
            fn visit_seq<A: SeqAccess<'de>>(self, seq: A) -> Result<RawNf, A::Error> {
                Vec::deserialize(SeqAccessDeserializer::new(seq)).map(RawNf::List)
            }
        }
        d.deserialize_any(Shape)
    }
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawMonteCarlo {
    trials: i64,
    seed: i64,
    noise: String,
    measured: Option<String>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawOutput {
    csv: String,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawCheck {
    max_abs_relative_bias: f64,
    statistic: Option<String>,
    #[serde(rename = "where", default)]
    filter: RawWhere,
}

#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawWhere {
    modes: Option<Vec<i64>>,
    params: Option<Vec<String>>,
    n: Option<Vec<i64>>,
    m: Option<Vec<i64>>,
    nf: Option<Vec<i64>>,
    weighting: Option<Vec<String>>,
    shape_noise: Option<Vec<f64>>,
    frequency_noise: Option<Vec<f64>>,
}

/// The unidentified DOFs of a grid entry: a count under the documented rule, or a list.
#[derive(Debug, Clone, PartialEq)]
pub enum NfSpec {
    /// NF DOFs chosen by [`super::unidentified::by_rule`].
    Count(usize),
    /// These DOFs (ascending global indices).
    Explicit(Vec<usize>),
}

/// The axes of a grid; every combination is one cell.
#[derive(Debug, Clone, PartialEq)]
pub struct Grid {
    /// Field path of this grid in the file (`grid` or `grid[1]`).
    pub path: String,
    /// Deformable modes identified in every cell.
    pub modes: Vec<usize>,
    /// Basis sizes n.
    pub n: Vec<usize>,
    /// Retained equations m.
    pub m: Vec<usize>,
    /// Unidentified DOFs.
    pub nf: Vec<NfSpec>,
    /// Weightings.
    pub weighting: Vec<Weighting>,
    /// Shape noise levels (see [`NoiseKind`]).
    pub shape_noise: Vec<f64>,
    /// Relative frequency noise standard deviations.
    pub frequency_noise: Vec<f64>,
}

/// Which statistic the CI gate holds to the threshold.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GateStatistic {
    /// The mean (relative bias, with its standard error).
    Mean,
    /// The median (relative deviation of the median, with its standard error).
    Median,
}

/// The `[check]` table: which cells the CI gate looks at and the bias it tolerates.
#[derive(Debug, Clone, PartialEq)]
pub struct CheckSpec {
    /// Largest tolerated |relative bias|.
    pub max_abs_relative_bias: f64,
    /// Mean or median.
    pub statistic: GateStatistic,
    /// Selected modes (all when `None`).
    pub modes: Option<Vec<usize>>,
    /// Selected parameter names (all when `None`).
    pub params: Option<Vec<String>>,
    /// Selected n.
    pub n: Option<Vec<usize>>,
    /// Selected m.
    pub m: Option<Vec<usize>>,
    /// Selected NF counts.
    pub nf: Option<Vec<usize>>,
    /// Selected weightings.
    pub weighting: Option<Vec<Weighting>>,
    /// Selected shape noise levels.
    pub shape_noise: Option<Vec<f64>>,
    /// Selected frequency noise levels.
    pub frequency_noise: Option<Vec<f64>>,
}

/// A validated study.
#[derive(Debug, Clone)]
pub struct Study {
    /// The study file.
    pub file: PathBuf,
    /// Name, for reports.
    pub name: String,
    /// The nominal model's file, resolved.
    pub model_file: PathBuf,
    /// The nominal (initial) model.
    pub model: Structure,
    /// The introduced modification of every joint parameter, in parameter order.
    pub delta: Vec<f64>,
    /// The deformable modes identified in every cell (the same in every grid).
    pub modes: Vec<usize>,
    /// The grids.
    pub grids: Vec<Grid>,
    /// Trials per cell.
    pub trials: usize,
    /// Seed of every random stream.
    pub seed: u64,
    /// Noise distribution of the draws (normal under a measured noise).
    pub noise: NoiseKind,
    /// The noise taken from a measured file (`noise = "measured"`): the grid's noise levels
    /// are then factors on each mode's measured errors.
    pub measured_noise: Option<MeasuredNoise>,
    /// Result CSV, resolved.
    pub output_csv: PathBuf,
    /// The CI gate, if any.
    pub check: Option<CheckSpec>,
}

impl Study {
    /// Reads and validates a study file and the model it names.
    pub fn from_path(path: &Path) -> Result<Study, InputError> {
        Study::from_toml(&read_file(path)?, path)
    }

    /// Parses and validates study TOML; `file` names it in errors and anchors relative paths.
    pub fn from_toml(text: &str, file: &Path) -> Result<Study, InputError> {
        let raw: RawStudy = parse_toml(text, file)?;
        let model_file = file.parent().unwrap_or(Path::new("")).join(&raw.model);
        if raw.model.trim().is_empty() {
            return Err(FieldCheck { file }.invalid(
                "model",
                "\"\"",
                "it must name the model file, relative to the study file",
            ));
        }
        let model = crate::model::from_path(&model_file)?;
        Study::validate(raw, file, model, &model_file)
    }

    /// As [`Study::from_toml`], with the model given instead of read from `model`.
    pub fn from_toml_with_model(
        text: &str,
        file: &Path,
        model: Structure,
        model_file: &Path,
    ) -> Result<Study, InputError> {
        Study::validate(parse_toml(text, file)?, file, model, model_file)
    }

    fn validate(
        raw: RawStudy,
        file: &Path,
        model: Structure,
        model_file: &Path,
    ) -> Result<Study, InputError> {
        let check = FieldCheck { file };
        crate::input::safe::check(&crate::input::safe::FILE_NAME, "name", &raw.name)
            .map_err(|e| check.invalid("name", e.value, e.allowed))?;
        let base = file.parent().unwrap_or(Path::new(""));
        let params = model.identified();
        if params.is_empty() {
            return Err(check.invalid(
                "model",
                format!("\"{}\"", model_file.display()),
                "the model identifies no parameter (no joint, or every parameter held fixed): a study needs at least one",
            ));
        }
        let names: Vec<&str> = params.iter().map(|p| p.name.as_str()).collect();
        for (key, value) in &raw.truth.delta {
            if !names.contains(&key.as_str()) {
                return Err(check.invalid(
                    format!("truth.delta.{key}"),
                    value,
                    format!("the model's parameters are {}", names.join(", ")),
                ));
            }
            if !value.is_finite() {
                return Err(check.invalid(
                    format!("truth.delta.{key}"),
                    Number(*value),
                    "it must be finite",
                ));
            }
        }
        let delta = params
            .iter()
            .map(|p| {
                let d = *raw.truth.delta.get(&p.name).ok_or_else(|| {
                    check.invalid(
                        "truth.delta",
                        format!("no {}", p.name),
                        format!(
                            "every parameter needs its modification: {}",
                            names.join(", ")
                        ),
                    )
                })?;
                if p.value + d <= 0.0 {
                    return Err(check.invalid(
                        format!("truth.delta.{}", p.name),
                        Number(d),
                        format!(
                            "the modified {} = {} + {} must stay > 0",
                            p.name,
                            Number(p.value),
                            Number(d)
                        ),
                    ));
                }
                Ok(d)
            })
            .collect::<Result<Vec<f64>, InputError>>()?;
        let kind = match raw.monte_carlo.noise.as_str() {
            MEASURED => Levels::Factors,
            _ => Levels::Relative,
        };
        let grids = match &raw.grid {
            RawGrids::One(g) => vec![grid(g, "grid", &check, &model, kind)?],
            RawGrids::Many(list) if list.is_empty() => {
                return Err(check.invalid("grid", "[]", "at least one grid is required"));
            }
            RawGrids::Many(list) => list
                .iter()
                .enumerate()
                .map(|(i, g)| grid(g, &format!("grid[{i}]"), &check, &model, kind))
                .collect::<Result<Vec<_>, _>>()?,
        };
        let modes = grids[0].modes.clone();
        if let Some(other) = grids.iter().find(|g| g.modes != modes) {
            return Err(check.invalid(
                format!("{}.modes", other.path),
                format!("{:?}", other.modes),
                format!(
                    "every grid must identify the same modes as {}.modes = {:?}",
                    grids[0].path, modes
                ),
            ));
        }
        let (noise, measured_noise) = study_noise(&raw.monte_carlo, &check, base, &model, &modes)?;
        if let Some(measured) = &measured_noise {
            check_measured_levels(&grids, measured, &check)?;
        }
        let trials =
            check.int_range("monte_carlo.trials", raw.monte_carlo.trials, 1, MAX_TRIALS)?;
        let seed = check.int_range("monte_carlo.seed", raw.monte_carlo.seed, 0, i64::MAX)? as u64;
        let check_spec = raw
            .check
            .as_ref()
            .map(|c| check_spec(c, &check, &names, kind))
            .transpose()?;
        Ok(Study {
            file: file.to_path_buf(),
            name: raw.name,
            model_file: model_file.to_path_buf(),
            model,
            delta,
            modes,
            grids,
            trials,
            seed,
            noise,
            measured_noise,
            output_csv: base.join(&raw.output.csv),
            check: check_spec,
        })
    }
}

impl Study {
    /// The noise as the result CSV names it: `uniform`, `gaussian` or `measured`.
    pub fn noise_name(&self) -> &'static str {
        match self.measured_noise {
            Some(_) => MEASURED,
            None => self.noise.name(),
        }
    }

    /// The factors that turn a cell's shape and frequency noise levels into mode r's:
    /// the mode's measured relative errors under a measured noise, 1 otherwise.
    pub fn noise_scale(&self, r: usize) -> (f64, f64) {
        match self.measured_noise.as_ref().and_then(|m| m.of(r)) {
            Some(m) => (m.shape, m.frequency),
            None => (1.0, 1.0),
        }
    }
}

/// The name of a noise taken from a measured file.
const MEASURED: &str = "measured";

/// The draws' distribution and, under `noise = "measured"`, the measured file's errors of
/// every mode.
fn study_noise(
    raw: &RawMonteCarlo,
    check: &FieldCheck,
    base: &Path,
    model: &Structure,
    modes: &[usize],
) -> Result<(NoiseKind, Option<MeasuredNoise>), InputError> {
    match (raw.noise.as_str(), &raw.measured) {
        (MEASURED, Some(file)) => {
            let path = base.join(file);
            let measured =
                MeasuredNoise::read(&path, model, modes, check, "monte_carlo.measured")?;
            Ok((NoiseKind::Gaussian, Some(measured)))
        }
        (MEASURED, None) => Err(check.invalid(
            "monte_carlo.noise",
            "\"measured\"",
            "a measured noise needs `measured = \"FILE.csv\"`: a measured-modes file with standard errors, relative to the study file",
        )),
        (other, Some(file)) => Err(check.invalid(
            "monte_carlo.measured",
            format!("\"{file}\""),
            format!("a measured file is read only under noise = \"measured\", not \"{other}\""),
        )),
        (other, None) => other
            .parse()
            .map(|kind| (kind, None))
            .map_err(|e: String| {
                check.invalid(
                    "monte_carlo.noise",
                    format!("\"{other}\""),
                    format!("{e}, or \"measured\" (with `measured = \"FILE.csv\"`)"),
                )
            }),
    }
}

fn non_empty<T>(v: &[T], path: &str, check: &FieldCheck) -> Result<(), InputError> {
    if v.is_empty() {
        Err(check.invalid(path, "[]", "at least one value is required"))
    } else {
        Ok(())
    }
}

fn ints(
    values: &[i64],
    path: &str,
    lo: i64,
    hi: i64,
    check: &FieldCheck,
) -> Result<Vec<usize>, InputError> {
    non_empty(values, path, check)?;
    let out = values
        .iter()
        .enumerate()
        .map(|(i, &v)| check.int_range(format!("{path}[{i}]"), v, lo, hi))
        .collect::<Result<Vec<_>, _>>()?;
    for (i, v) in out.iter().enumerate() {
        if out[..i].contains(v) {
            return Err(check.invalid(format!("{path}[{i}]"), v, "values must be distinct"));
        }
    }
    Ok(out)
}

/// What a grid's noise levels are: relative errors, or, under a measured noise, factors on
/// each mode's measured relative errors.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Levels {
    Relative,
    Factors,
}

fn levels(
    values: &[f64],
    path: &str,
    unit: &str,
    kind: Levels,
    check: &FieldCheck,
) -> Result<Vec<f64>, InputError> {
    non_empty(values, path, check)?;
    values
        .iter()
        .enumerate()
        .map(|(i, &v)| match kind {
            Levels::Relative => check.relative_level(format!("{path}[{i}]"), v, unit),
            Levels::Factors => check.non_negative(
                format!("{path}[{i}]"),
                v,
                "a factor on the measured file's errors",
            ),
        })
        .collect()
}

/// Under a measured noise, every grid level times every mode's measured relative error must
/// stay a relative error below 1.
fn check_measured_levels(
    grids: &[Grid],
    measured: &MeasuredNoise,
    check: &FieldCheck,
) -> Result<(), InputError> {
    for g in grids {
        let shape = measured.modes.iter().map(|m| (m.mode, m.shape));
        let frequency = measured.modes.iter().map(|m| (m.mode, m.frequency));
        factors_below_one(
            &format!("{}.shape_noise", g.path),
            &g.shape_noise,
            shape,
            check,
        )?;
        let path = format!("{}.frequency_noise", g.path);
        factors_below_one(&path, &g.frequency_noise, frequency, check)?;
    }
    Ok(())
}

/// Every factor of the grid field `path` times every mode's relative error (mode, error)
/// below 1.
fn factors_below_one(
    path: &str,
    factors: &[f64],
    errors: impl Iterator<Item = (usize, f64)> + Clone,
    check: &FieldCheck,
) -> Result<(), InputError> {
    for (i, &factor) in factors.iter().enumerate() {
        if let Some((mode, error)) = errors.clone().find(|(_, e)| factor * e >= 1.0) {
            return Err(check.invalid(
                format!("{path}[{i}]"),
                Number(factor),
                format!(
                    "times mode {mode}'s measured relative error {} it must stay below 1 (100%)",
                    Number(error)
                ),
            ));
        }
    }
    Ok(())
}

fn weightings(
    values: &[String],
    path: &str,
    check: &FieldCheck,
) -> Result<Vec<Weighting>, InputError> {
    non_empty(values, path, check)?;
    values
        .iter()
        .enumerate()
        .map(|(i, w)| {
            w.parse()
                .map_err(|e: String| check.invalid(format!("{path}[{i}]"), format!("\"{w}\""), e))
        })
        .collect()
}

fn grid(
    raw: &RawGrid,
    path: &str,
    check: &FieldCheck,
    model: &Structure,
    kind: Levels,
) -> Result<Grid, InputError> {
    let dofs = model.dof_count() as i64;
    let deformable = dofs - model.rigid as i64;
    let nf = {
        non_empty(&raw.nf, &format!("{path}.nf"), check)?;
        raw.nf
            .iter()
            .enumerate()
            .map(|(i, entry)| match entry {
                RawNf::Count(c) => Ok(NfSpec::Count(check.int_range(format!("{path}.nf[{i}]"), *c, 0, dofs - 1)?)),
                RawNf::List(list) => {
                    let mut out = Vec::with_capacity(list.len());
                    for (j, item) in list.iter().enumerate() {
                        let at = format!("{path}.nf[{i}][{j}]");
                        let Some(d) = dof_of_label(&model.dofs, item) else {
                            let allowed = match model.dofs.dofs().iter().filter_map(|d| d.node).max() {
                                Some(last) => format!("an unidentified DOF is \"node:dof\" with node 0 to {last} and dof w or theta, not held by a support"),
                                None => "an unidentified DOF is a DOF label of the model".to_string(),
                            };
                            return Err(check.invalid(at, format!("\"{item}\""), allowed));
                        };
                        if out.contains(&d) {
                            return Err(check.invalid(at, format!("\"{item}\""), "each DOF may be listed once"));
                        }
                        out.push(d);
                    }
                    out.sort_unstable();
                    Ok(NfSpec::Explicit(out))
                }
            })
            .collect::<Result<Vec<_>, InputError>>()?
    };
    let at = |field: &str| format!("{path}.{field}");
    Ok(Grid {
        path: path.to_string(),
        modes: ints(&raw.modes, &at("modes"), 1, deformable, check)?,
        n: ints(&raw.n, &at("n"), model.rigid as i64 + 1, dofs, check)?,
        m: ints(&raw.m, &at("m"), 1, deformable, check)?,
        nf,
        weighting: weightings(&raw.weighting, &at("weighting"), check)?,
        shape_noise: levels(
            &raw.shape_noise,
            &at("shape_noise"),
            "relative error",
            kind,
            check,
        )?,
        frequency_noise: levels(
            &raw.frequency_noise,
            &at("frequency_noise"),
            "relative standard deviation",
            kind,
            check,
        )?,
    })
}

/// The DOF a label names: the label itself, or `node:dof` written with spaces.
fn dof_of_label(dofs: &DofMap, item: &str) -> Option<usize> {
    dofs.index(item.trim()).or_else(|| {
        let (node, dof) = item.split_once(':')?;
        let node: usize = node.trim().parse().ok()?;
        let dof = Direction::parse(dof.trim())?;
        dofs.index(&DofMap::node_label(node, dof))
    })
}

fn check_spec(
    raw: &RawCheck,
    check: &FieldCheck,
    names: &[&str],
    kind: Levels,
) -> Result<CheckSpec, InputError> {
    let w = &raw.filter;
    let statistic = match raw.statistic.as_deref() {
        None | Some("mean") => GateStatistic::Mean,
        Some("median") => GateStatistic::Median,
        Some(other) => {
            return Err(check.invalid(
                "check.statistic",
                format!("\"{other}\""),
                "it must be \"mean\" or \"median\"",
            ));
        }
    };
    if let Some(params) = &w.params {
        for (i, p) in params.iter().enumerate() {
            if !names.contains(&p.as_str()) {
                return Err(check.invalid(
                    format!("check.where.params[{i}]"),
                    format!("\"{p}\""),
                    format!("the model's parameters are {}", names.join(", ")),
                ));
            }
        }
    }
    let opt_ints = |v: &Option<Vec<i64>>, path: &str| {
        v.as_ref()
            .map(|v| ints(v, path, 0, i64::MAX, check))
            .transpose()
    };
    let opt_levels = |v: &Option<Vec<f64>>, path: &str| {
        v.as_ref()
            .map(|v| levels(v, path, "relative", kind, check))
            .transpose()
    };
    Ok(CheckSpec {
        max_abs_relative_bias: check.non_negative(
            "check.max_abs_relative_bias",
            raw.max_abs_relative_bias,
            "relative",
        )?,
        statistic,
        modes: opt_ints(&w.modes, "check.where.modes")?,
        params: w.params.clone(),
        n: opt_ints(&w.n, "check.where.n")?,
        m: opt_ints(&w.m, "check.where.m")?,
        nf: opt_ints(&w.nf, "check.where.nf")?,
        weighting: w
            .weighting
            .as_ref()
            .map(|v| weightings(v, "check.where.weighting", check))
            .transpose()?,
        shape_noise: opt_levels(&w.shape_noise, "check.where.shape_noise")?,
        frequency_noise: opt_levels(&w.frequency_noise, "check.where.frequency_noise")?,
    })
}
