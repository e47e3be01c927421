//! The candidate sensor sites of a plan, resolved on the model's DOFs, and the sensors given
//! by position or label (fixed ones, the model's own) found among them.
//!
//! A study perturbs and reads DOFs, so a site is a DOF: the transverse DOF `w` of a node for
//! `nodes` and for a position (the node at that abscissa: a `[[sensor]]` of a chain model puts
//! one there), any DOF for a label.

use serde::Serialize;

use super::request::Sites;
use crate::input::SettingError;
use crate::structure::{Direction, DofMap, Structure};

/// Two abscissae closer than this (m) are the same site.
pub const SAME_POSITION: f64 = 1e-9;

/// A candidate site.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Candidate {
    /// The DOF it reads.
    pub dof: usize,
    /// Its label (`7:w`).
    pub label: String,
    /// Its abscissa, m.
    pub x: f64,
    /// Its direction (`w`, ...).
    pub direction: String,
}

impl Candidate {
    fn of(dofs: &DofMap, dof: usize) -> Candidate {
        let info = dofs.get(dof);
        Candidate {
            dof,
            label: info.label.clone(),
            x: info.position[0],
            direction: info.direction.name().to_string(),
        }
    }
}

/// The candidates of `sites` on `structure`, in DOF order, each once.
pub fn resolve(structure: &Structure, sites: &Sites) -> Result<Vec<Candidate>, SettingError> {
    let dofs = &structure.dofs;
    let mut out: Vec<usize> = match sites {
        Sites::Nodes => {
            let w: Vec<usize> = (0..dofs.len())
                .filter(|&d| dofs.get(d).direction == Direction::W)
                .collect();
            if w.is_empty() {
                return Err(SettingError::new(
                    "sites",
                    "nodes",
                    "the model has no transverse (w) DOF: name the candidate DOFs by label",
                ));
            }
            w
        }
        Sites::Positions(xs) => xs
            .iter()
            .map(|&x| node_at(dofs, x).map_err(|why| SettingError::new("sites", x, why)))
            .collect::<Result<_, _>>()?,
        Sites::Labels(labels) => labels
            .iter()
            .map(|l| {
                dofs.index(l).ok_or_else(|| {
                    SettingError::new(
                        "sites",
                        format!("\"{l}\""),
                        "it must be a DOF label of the model",
                    )
                })
            })
            .collect::<Result<_, _>>()?,
    };
    out.sort_unstable();
    out.dedup();
    Ok(out.into_iter().map(|d| Candidate::of(dofs, d)).collect())
}

/// The `w` DOF of the first node at abscissa `x`, or why there is none.
fn node_at(dofs: &DofMap, x: f64) -> Result<usize, String> {
    let w = (0..dofs.len()).filter(|&d| dofs.get(d).direction == Direction::W);
    let nearest = w.min_by(|&a, &b| {
        let da = (dofs.get(a).position[0] - x).abs();
        let db = (dofs.get(b).position[0] - x).abs();
        da.total_cmp(&db)
    });
    match nearest {
        Some(d) if (dofs.get(d).position[0] - x).abs() <= SAME_POSITION => Ok(d),
        Some(d) => Err(format!(
            "no node of the model lies there (the nearest is at {} m): add a [[sensor]] at this x to the model, which puts a node there, or choose a node",
            dofs.get(d).position[0]
        )),
        None => Err("the model has no transverse (w) DOF".to_string()),
    }
}

/// The index among `candidates` of a sensor given as a position (m) or a DOF label, or why it
/// is none of them (the error names `setting`).
pub fn find(
    structure: &Structure,
    candidates: &[Candidate],
    given: &str,
    setting: &'static str,
) -> Result<usize, SettingError> {
    let dof = match given.trim().parse::<f64>() {
        Ok(x) => node_at(&structure.dofs, x).map_err(|why| SettingError::new(setting, x, why))?,
        Err(_) => structure.dofs.index(given.trim()).ok_or_else(|| {
            SettingError::new(
                setting,
                format!("\"{given}\""),
                "it must be a DOF label of the model or a position (m)",
            )
        })?,
    };
    candidates.iter().position(|c| c.dof == dof).ok_or_else(|| {
        SettingError::new(
            setting,
            given,
            format!(
                "a fixed sensor must be one of the {} candidate sites (DOF {} is not)",
                candidates.len(),
                structure.dofs.get(dof).label
            ),
        )
    })
}

/// The candidates that the model's own `[[sensor]]` entries read (a sensor that reads no
/// single candidate DOF is left out and counted).
pub fn model_sensors(structure: &Structure, candidates: &[Candidate]) -> (Vec<usize>, usize) {
    let mut found = Vec::new();
    let mut missed = 0;
    for s in &structure.sensors {
        match s
            .single_dof()
            .and_then(|d| candidates.iter().position(|c| c.dof == d))
        {
            Some(i) if !found.contains(&i) => found.push(i),
            Some(_) => {}
            None => missed += 1,
        }
    }
    found.sort_unstable();
    (found, missed)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::fixtures::paper_model;

    #[test]
    fn nodes_positions_and_labels_resolve_to_dofs_or_say_why_not() {
        let model = paper_model(1e7, 1e4);
        let nodes = resolve(&model, &Sites::Nodes).unwrap();
        // 19 nodes (two beams of 8 and 11 nodes), one w each.
        assert_eq!(nodes.len(), 19);
        assert!(nodes.iter().all(|c| c.direction == "w"));
        let at = resolve(&model, &Sites::Positions(vec![0.5, 0.0])).unwrap();
        assert_eq!(at.len(), 2);
        assert_eq!((at[0].x, at[1].x), (0.0, 0.5));
        let e = resolve(&model, &Sites::Positions(vec![0.01])).unwrap_err();
        assert!(
            e.to_string().starts_with(
                "sites = 0.01 is invalid: no node of the model lies there (the nearest is at 0"
            ),
            "{e}"
        );
        let e = find(&model, &at, "3:w", "fixed").unwrap_err();
        assert!(
            e.to_string().starts_with(
                "fixed = 3:w is invalid: a fixed sensor must be one of the 2 candidate sites"
            ),
            "{e}"
        );
        assert_eq!(find(&model, &at, "0.5", "fixed").unwrap(), 1);
    }
}
