//! `sensor_mass`: accelerometers load the beam. One lumped mass m_s at every node where a
//! translation is measured (the same sensor everywhere).

use super::{Effect, EffectContext, EffectParameter, linear_contribution};
use crate::structure::SparseSym;

/// See the module docs.
#[derive(Debug, Clone, Copy)]
pub struct SensorMass;

fn pattern(ctx: &EffectContext) -> SparseSym {
    let mut s = SparseSym::zero();
    for sensor in &ctx.sensors {
        for &(a, ca) in &sensor.terms {
            for &(b, cb) in &sensor.terms {
                s.push(a, b, ca * cb);
            }
        }
    }
    s
}

/// dM/dm_s.
fn patterns(ctx: &EffectContext) -> Vec<(SparseSym, SparseSym)> {
    vec![(SparseSym::zero(), pattern(ctx))]
}

impl Effect for SensorMass {
    fn name(&self) -> &'static str {
        "sensor_mass"
    }

    fn describe(&self) -> &'static str {
        "one lumped mass at every node where a translation is measured; size = total sensor mass / mass of all beams"
    }

    fn parameters(&self, ctx: &EffectContext) -> Vec<EffectParameter> {
        let sensors = ctx.sensors.len().max(1) as f64;
        vec![EffectParameter {
            name: "sensor_mass.m".into(),
            unit: "kg",
            scale: 0.01 * ctx.structure.sites.beam_mass / sensors,
            non_negative: true,
        }]
    }

    fn contribution(&self, ctx: &EffectContext, theta: &[f64]) -> (SparseSym, SparseSym) {
        linear_contribution(&patterns(ctx), theta)
    }

    fn derivatives(&self, ctx: &EffectContext, _theta: &[f64]) -> Vec<(SparseSym, SparseSym)> {
        patterns(ctx)
    }

    fn theta_of_size(&self, ctx: &EffectContext, size: f64) -> Vec<f64> {
        vec![size * ctx.structure.sites.beam_mass / ctx.sensors.len().max(1) as f64]
    }

    fn size_of_theta(&self, ctx: &EffectContext, theta: &[f64]) -> f64 {
        theta[0] * ctx.sensors.len().max(1) as f64 / ctx.structure.sites.beam_mass
    }

    /// The sensors together are lighter than the beams they sit on.
    fn plausible(&self, ctx: &EffectContext, theta: &[f64]) -> Result<(), String> {
        let total = theta[0] * ctx.sensors.len().max(1) as f64;
        let beams = ctx.structure.sites.beam_mass;
        if total >= beams {
            return Err(format!(
                "the {} sensors weigh {total:.4e} kg together, not less than the mass of all beams {beams:.4e} kg",
                ctx.sensors.len()
            ));
        }
        Ok(())
    }
}
