//! The figure of a plan: above, the beam with each layout's sensors (one row per layout, the
//! candidate sites as the faint first row); below, the spread per mode, the largest relative
//! std of the mode's corrections for each layout (log axis; a mode a layout leaves
//! undetermined has no point).

use super::plot::{LineAxes, PlotError, Series, lines, svg};
use crate::plan::{Layout, Plan};

/// The layouts drawn: those of the largest count, then the model's own.
fn drawn(plan: &Plan) -> Vec<(String, &Layout)> {
    let mut out: Vec<(String, &Layout)> = Vec::new();
    if let Some(c) = plan.counts.last() {
        out.extend(
            c.layouts
                .iter()
                .map(|l| (format!("{} ({} sensors)", l.kind.name(), c.sensors), l)),
        );
    }
    if let Some(l) = &plan.model_layout {
        out.push((format!("model ({} sensors)", l.sites.len()), l));
    }
    out
}

/// The plan's figure as SVG.
pub fn plan_svg(plan: &Plan) -> Result<String, PlotError> {
    let layouts = drawn(plan);
    let mut sites = vec![Series {
        name: "candidate sites".into(),
        points: plan.candidates.iter().map(|c| (c.x, 0.0)).collect(),
        errors: None,
        line: false,
    }];
    sites.extend(layouts.iter().enumerate().map(|(k, (name, l))| {
        Series {
            name: name.clone(),
            points: l
                .sites
                .iter()
                .map(|&i| (plan.candidates[i].x, (k + 1) as f64))
                .collect(),
            errors: None,
            line: false,
        }
    }));
    let spread: Vec<Series> = layouts
        .iter()
        .map(|(name, l)| Series {
            name: name.clone(),
            points: l
                .evaluation
                .modes
                .iter()
                .filter_map(|m| {
                    let worst = m.relative_std.as_ref()?.iter().copied().fold(0.0, f64::max);
                    Some((m.mode as f64, 100.0 * worst))
                })
                .collect(),
            errors: None,
            line: true,
        })
        .collect();
    svg((900, 800), |root| {
        let (top, bottom) = root.split_vertically(360);
        lines(
            &top,
            "Sensors along the beam",
            &LineAxes {
                x_desc: "x (m)".into(),
                y_desc: "layout (0: candidates)".into(),
                log_x: false,
                log_y: false,
                reference: None,
                clip_errors: false,
            },
            &sites,
        )?;
        lines(
            &bottom,
            &format!(
                "Predicted spread per mode (largest over {})",
                plan.parameters.join(", ")
            ),
            &LineAxes {
                x_desc: "mode".into(),
                y_desc: "std(Delta p) / p (%)".into(),
                log_x: false,
                log_y: true,
                reference: None,
                clip_errors: false,
            },
            &spread,
        )
    })
}
