//! `sensor_mass`: accelerometers load the beam. One lumped mass m_s at every point where a
//! translation is measured (the same sensor everywhere), with its rotary inertia J_s about
//! the beam's axis as a second parameter: a sensor glued on a face sits h/2 and more away
//! from the neutral axis, so the section's rotation moves it and J_s is at least
//! m_s (h/2)^2 = 3 m_s I/A for a rectangle, more with the sensor's own size; it is not tied
//! to m_s because the sensor's shape and mounting are not known.
//!
//! ```text
//!   M(m_s, J_s) - M(0) = sum_sensors m_s c_w c_w^T + J_s c_theta c_theta^T
//! ```
//!
//! c_w reads the sensor's translation (a node's DOF, or the element shape functions between
//! nodes), c_theta the section's rotation at the same point (the node's rotation, or the shape
//! functions' slope). J_s is a parameter only where some sensor has a rotation to load.
//! A rotary inertia whose radius of gyration sqrt(J_s / m_s) exceeds twice the section height
//! is no sensor (a rotary inertia without its mass is another effect): not plausible.
//!
//! Size (in `jointid simulate --effect sensor_mass=size`): total sensor mass / mass of all
//! beams, with J_s = 0.

use super::{
    Effect, EffectContext, EffectParameter, LARGEST_GYRATION_HEIGHTS, Tier, beyond,
    linear_contribution,
};
use crate::structure::{Direction, DofMap, Observation, SparseSym};

/// See the module docs.
#[derive(Debug, Clone, Copy)]
pub struct SensorMass;

/// c c^T of every observation.
fn outer(points: &[Observation]) -> SparseSym {
    let mut s = SparseSym::zero();
    for point in points {
        for &(a, ca) in &point.terms {
            for &(b, cb) in &point.terms {
                s.push(a, b, ca * cb);
            }
        }
    }
    s
}

/// The section's rotation where `sensor` reads a translation, if the model has one there.
fn rotation_at(dofs: &DofMap, sensor: &Observation) -> Option<Observation> {
    if let Some(d) = sensor.single_dof() {
        let node = dofs.get(d).node?;
        let theta = dofs.index(&DofMap::node_label(node, Direction::Theta))?;
        return Some(Observation::dof(dofs, theta));
    }
    dofs.at_x(sensor.x, Direction::Theta).ok()
}

/// The rotations under the sensors.
fn rotations(ctx: &EffectContext) -> Vec<Observation> {
    ctx.sensors
        .iter()
        .filter_map(|s| rotation_at(&ctx.structure.dofs, s))
        .collect()
}

/// dM/dm_s, and dM/dJ_s where the sensors have rotations.
fn patterns(ctx: &EffectContext) -> Vec<(SparseSym, SparseSym)> {
    let mut out = vec![(SparseSym::zero(), outer(&ctx.sensors))];
    let rotations = rotations(ctx);
    if !rotations.is_empty() {
        out.push((SparseSym::zero(), outer(&rotations)));
    }
    out
}

/// Mean I / A of the beam elements (a 35 mm square section's where the model has none).
fn gyration_squared(ctx: &EffectContext) -> f64 {
    let elements = &ctx.structure.sites.elements;
    if elements.is_empty() {
        return 1e-4;
    }
    elements
        .iter()
        .map(|e| e.section.gyration_squared())
        .sum::<f64>()
        / elements.len() as f64
}

/// The square of a sensor's largest radius of gyration (of the mean section).
fn largest_gyration_squared(ctx: &EffectContext) -> f64 {
    super::largest_gyration_squared(gyration_squared(ctx))
}

impl Effect for SensorMass {
    fn name(&self) -> &'static str {
        "sensor_mass"
    }

    fn tier(&self) -> Tier {
        Tier::Default
    }

    fn describe(&self) -> &'static str {
        "a lumped mass with its rotary inertia at every point where a translation is measured; size = total sensor mass / mass of all beams (J = 0 in simulate)"
    }

    fn parameters(&self, ctx: &EffectContext) -> Vec<EffectParameter> {
        let sensors = ctx.sensors.len().max(1) as f64;
        let mass_scale = 0.01 * ctx.structure.sites.beam_mass / sensors;
        let mut out = vec![EffectParameter {
            name: "sensor_mass.m".into(),
            unit: "kg",
            scale: mass_scale,
            non_negative: true,
        }];
        if !rotations(ctx).is_empty() {
            out.push(EffectParameter {
                name: "sensor_mass.J".into(),
                unit: "kg m^2",
                scale: 3.0 * mass_scale * gyration_squared(ctx),
                non_negative: true,
            });
        }
        out
    }

    fn contribution(&self, ctx: &EffectContext, theta: &[f64]) -> (SparseSym, SparseSym) {
        linear_contribution(&patterns(ctx), theta)
    }

    fn derivatives(&self, ctx: &EffectContext, _theta: &[f64]) -> Vec<(SparseSym, SparseSym)> {
        patterns(ctx)
    }

    fn theta_of_size(&self, ctx: &EffectContext, size: f64) -> Vec<f64> {
        let mut theta = vec![0.0; self.parameters(ctx).len()];
        theta[0] = size * ctx.structure.sites.beam_mass / ctx.sensors.len().max(1) as f64;
        theta
    }

    fn size_of_theta(&self, ctx: &EffectContext, theta: &[f64]) -> f64 {
        theta[0] * ctx.sensors.len().max(1) as f64 / ctx.structure.sites.beam_mass
    }

    /// J_s <= m_s (LARGEST_GYRATION_HEIGHTS h)^2 where the sensors load rotations.
    fn inequalities(&self, ctx: &EffectContext) -> Vec<Vec<(usize, f64)>> {
        if self.parameters(ctx).len() < 2 {
            return Vec::new();
        }
        vec![vec![(0, largest_gyration_squared(ctx)), (1, -1.0)]]
    }

    /// The sensors together are lighter than the beams they sit on, and a sensor's radius of
    /// gyration about the axis is within twice the section height.
    fn plausible(&self, ctx: &EffectContext, theta: &[f64]) -> Result<(), String> {
        let total = theta[0] * ctx.sensors.len().max(1) as f64;
        let beams = ctx.structure.sites.beam_mass;
        if total >= beams {
            return Err(format!(
                "the {} sensors weigh {total:.4e} kg together, not less than the mass of all beams {beams:.4e} kg",
                ctx.sensors.len()
            ));
        }
        if let Some(&j) = theta.get(1) {
            let height = (12.0 * gyration_squared(ctx)).sqrt();
            let largest = theta[0] * largest_gyration_squared(ctx);
            if beyond(j, largest) {
                return Err(format!(
                    "a sensor's rotary inertia {j:.4e} kg m^2 with its mass {:.4e} kg puts its radius of gyration beyond {LARGEST_GYRATION_HEIGHTS} section heights ({height:.4e} m): no sensor",
                    theta[0]
                ));
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::modal::ModalSolution;
    use crate::model::fixtures::paper_model;

    /// Sensors at node 3 (w) and at x = 0.05 m, between nodes 1 and 2 of the first beam
    /// (element length 0.2 / 7 m).
    fn context() -> EffectContext {
        let structure = paper_model(1e7, 1e4);
        let modal = ModalSolution::solve(&structure.assemble()).unwrap();
        let node = structure
            .dofs
            .index(&DofMap::node_label(3, Direction::W))
            .unwrap();
        let points = [
            Observation::dof(&structure.dofs, node),
            structure.dofs.at_x(0.05, Direction::W).unwrap(),
        ];
        EffectContext::new(structure, &points, modal.frequency_hz(2))
    }

    /// dM/dJ_s is the sum of c_theta c_theta^T over the sensors: at node 3 its own rotation
    /// DOF, between nodes the slope of the shape functions there.
    #[test]
    fn the_rotary_inertia_loads_the_rotation_under_each_sensor() {
        let ctx = context();
        let names: Vec<String> = SensorMass
            .parameters(&ctx)
            .into_iter()
            .map(|p| p.name)
            .collect();
        assert_eq!(names, ["sensor_mass.m", "sensor_mass.J"]);
        let dofs = &ctx.structure.dofs;
        let theta3 = dofs
            .index(&DofMap::node_label(3, Direction::Theta))
            .unwrap();
        let between = dofs.at_x(0.05, Direction::Theta).unwrap();
        let dm_dj = &SensorMass.derivatives(&ctx, &[0.0, 0.0])[1].1;
        // a^T (dM/dJ) a = (c_theta3 . a)^2 + (c_between . a)^2 for any a.
        let n = ctx.structure.dof_count();
        for seed in 0..4 {
            let a: Vec<f64> = (0..n)
                .map(|i| ((i * 7 + seed * 3) % 11) as f64 - 5.0)
                .collect();
            let want = a[theta3].powi(2) + between.read(&a).powi(2);
            let got = dm_dj.form(&a, &a);
            assert!(
                (got - want).abs() <= 1e-12 * want.abs().max(1.0),
                "{got} vs {want}"
            );
        }
    }

    /// A sensor whose radius of gyration sqrt(J_s / m_s) reaches two section heights (the
    /// paper's 40 mm bars: 80 mm) is not plausible; just inside it is, and J_s without m_s never.
    #[test]
    fn a_rotary_inertia_beyond_two_section_heights_is_no_sensor() {
        let ctx = context();
        let m = 0.01;
        let limit = m * (2.0_f64 * 0.04).powi(2);
        assert!(SensorMass.plausible(&ctx, &[m, limit * 0.999]).is_ok());
        let reason = SensorMass.plausible(&ctx, &[m, limit * 1.001]).unwrap_err();
        assert!(reason.contains("no sensor"), "{reason}");
        assert!(SensorMass.plausible(&ctx, &[0.0, 1e-9]).is_err());
    }
}
