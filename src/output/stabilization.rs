//! The stabilisation chart of an extraction as SVG: every pole of every model order at its
//! frequency (x, Hz) and order (y), its marker by stability class, the chosen poles circled and
//! the identified frequencies as vertical lines, the rejected candidates crossed out with the
//! rule that rejected them; on a secondary log axis, the sum over the
//! responses of |H| measured and of the identified model (the usual overlay that shows which
//! peaks the chosen modes explain).

use plotters::coord::Shift;
use plotters::prelude::*;

use super::plot::{PALETTE, PlotError, log_ticks, svg, tick};
use crate::extract::{Extraction, FrfSet, Quantity, StabilityClass};
use crate::uff::Function;

const FONT: &str = "sans-serif";
/// The colour of the rejected candidates' marks.
const REJECTED: RGBColor = RGBColor(200, 30, 30);

fn err<E: std::fmt::Debug>(e: E) -> PlotError {
    PlotError(format!("{e:?}"))
}

/// The units the chart's axes are labelled with: those the FRF file states, else SI.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ChartUnits {
    /// The frequency axis, e.g. `Hz`.
    pub frequency: String,
    /// The FRF, e.g. `m/s^2/V` or `(m/s^2)/N`.
    pub frf: String,
}

/// A units label that says something (UFF writes `NONE` or blanks for none).
fn stated(label: &str) -> Option<&str> {
    let label = label.trim();
    (!label.is_empty() && !label.eq_ignore_ascii_case("none")).then_some(label)
}

impl ChartUnits {
    /// SI units of an FRF of quantity `q` per newton, frequency in Hz.
    pub fn si(q: Quantity) -> Self {
        let frf = match q {
            Quantity::Displacement => "m/N",
            Quantity::Velocity => "(m/s)/N",
            Quantity::Acceleration => "(m/s^2)/N",
        };
        Self {
            frequency: "Hz".into(),
            frf: frf.into(),
        }
    }

    /// The units a dataset 58 states (its abscissa's units label; its ordinate's, over its
    /// denominator's when that is given), each falling back to [`ChartUnits::si`] of `q`
    /// where the file leaves it blank or `NONE`.
    pub fn of_function(f: &Function, q: Quantity) -> Self {
        let si = Self::si(q);
        let frf = match (
            stated(&f.ordinate_axis.units),
            stated(&f.denominator_axis.units),
        ) {
            (Some(num), Some(den)) if num.contains('/') => format!("({num})/{den}"),
            (Some(num), Some(den)) => format!("{num}/{den}"),
            (Some(num), None) => num.to_string(),
            (None, _) => si.frf,
        };
        Self {
            frequency: stated(&f.abscissa_axis.units).map_or(si.frequency, str::to_string),
            frf,
        }
    }
}

/// Marker colour and legend text of a class.
fn style(class: StabilityClass) -> (RGBColor, &'static str) {
    match class {
        StabilityClass::New => (RGBColor(170, 170, 170), "new (not stable in frequency)"),
        StabilityClass::Frequency => (PALETTE[0], "stable in frequency"),
        StabilityClass::Damping => (PALETTE[4], "stable in frequency and damping"),
        StabilityClass::Shape => (PALETTE[3], "stable in frequency and shape"),
        StabilityClass::Stable => (PALETTE[2], "stable (frequency, damping, shape)"),
    }
}

const CLASSES: [StabilityClass; 5] = [
    StabilityClass::New,
    StabilityClass::Frequency,
    StabilityClass::Damping,
    StabilityClass::Shape,
    StabilityClass::Stable,
];

/// The sum over responses of |H| on the band's lines.
fn magnitude_sum(series: impl Iterator<Item = Vec<f64>>, len: usize) -> Vec<f64> {
    let mut sum = vec![0.0; len];
    for s in series {
        for (acc, v) in sum.iter_mut().zip(s) {
            *acc += v;
        }
    }
    sum
}

/// The sums over responses of |H|, measured and of the identified model, on the band's lines.
fn band_magnitudes(frf: &FrfSet, ex: &Extraction) -> (Vec<f64>, Vec<f64>) {
    let n = ex.frequencies_hz.len();
    let measured = magnitude_sum(
        frf.responses
            .iter()
            .map(|h| ex.lines.iter().map(|&k| h[k].norm()).collect()),
        n,
    );
    let model = magnitude_sum(
        ex.synthesized
            .iter()
            .map(|h| h.iter().map(|v| v.norm()).collect()),
        n,
    );
    (measured, model)
}

/// The smallest and largest positive finite values, or (1e-12, 1) when there is none.
fn positive_range(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let positive = values.filter(|v| *v > 0.0 && v.is_finite());
    let (lo, hi) = positive.fold((f64::INFINITY, 0.0_f64), |(a, b), v| (a.min(v), b.max(v)));
    if !lo.is_finite() || hi <= 0.0 {
        (1e-12, 1.0)
    } else {
        (lo, hi)
    }
}

/// Draws the chart of `ex` (extracted from `frf`) on `area`, its axes labelled in `units`.
pub fn draw(
    area: &DrawingArea<SVGBackend, Shift>,
    frf: &FrfSet,
    ex: &Extraction,
    title: &str,
    units: &ChartUnits,
) -> Result<(), PlotError> {
    let (width, _) = area.dim_in_pixel();
    let (plot_area, legend_area) = area.split_horizontally(width as i32 - 300);
    let (measured, model) = band_magnitudes(frf, ex);
    let (lo, hi) = positive_range(measured.iter().chain(&model).copied());
    let (x0, x1) = ex.band_hz;
    let top = ex.max_order as f64 + 1.0;
    let mut chart = ChartBuilder::on(&plot_area)
        .caption(title, (FONT, 16))
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(60)
        .right_y_label_area_size(80)
        .build_cartesian_2d(x0..x1, 0.0..top)
        .map_err(err)?
        .set_secondary_coord(x0..x1, ((lo / 3.0)..(hi * 3.0)).log_scale());
    let magnitude_ticks = log_ticks(lo / 3.0, hi * 3.0);
    chart
        .configure_mesh()
        .light_line_style(RGBColor(245, 245, 245))
        .x_desc(format!("frequency ({})", units.frequency))
        .y_desc("model order")
        .x_label_formatter(&|v| tick(*v))
        .y_label_formatter(&|v| format!("{v:.0}"))
        .axis_desc_style((FONT, 14))
        .draw()
        .map_err(err)?;
    chart
        .configure_secondary_axes()
        .y_desc(format!("sum over responses of |H| ({})", units.frf))
        .y_label_formatter(&magnitude_ticks)
        .axis_desc_style((FONT, 14))
        .draw()
        .map_err(err)?;
    let points = |values: &[f64]| -> Vec<(f64, f64)> {
        ex.frequencies_hz
            .iter()
            .zip(values)
            .filter(|(_, v)| **v > 0.0 && v.is_finite())
            .map(|(f, v)| (*f, *v))
            .collect()
    };
    chart
        .draw_secondary_series(LineSeries::new(
            points(&measured),
            BLACK.mix(0.55).stroke_width(1),
        ))
        .map_err(err)?;
    chart
        .draw_secondary_series(DashedLineSeries::new(
            points(&model),
            6,
            4,
            PALETTE[1].stroke_width(1),
        ))
        .map_err(err)?;
    for mode in &ex.modes {
        chart
            .draw_series(DashedLineSeries::new(
                vec![(mode.frequency_hz, 0.0), (mode.frequency_hz, top)],
                3,
                3,
                PALETTE[1].mix(0.6).stroke_width(1),
            ))
            .map_err(err)?;
    }
    for class in CLASSES {
        let (colour, _) = style(class);
        let these = ex.chart.iter().filter(|p| p.class() == class);
        let at = |p: &crate::extract::ChartPole| (p.frequency_hz, p.order as f64);
        match class {
            StabilityClass::New => chart
                .draw_series(these.map(|p| Circle::new(at(p), 2, colour.stroke_width(1))))
                .map(|_| ()),
            StabilityClass::Frequency => chart
                .draw_series(these.map(|p| Cross::new(at(p), 3, colour.stroke_width(1))))
                .map(|_| ()),
            StabilityClass::Damping | StabilityClass::Shape => chart
                .draw_series(these.map(|p| TriangleMarker::new(at(p), 3, colour.filled())))
                .map(|_| ()),
            StabilityClass::Stable => chart
                .draw_series(these.map(|p| Circle::new(at(p), 3, colour.filled())))
                .map(|_| ()),
        }
        .map_err(err)?;
    }
    chart
        .draw_series(ex.chart.iter().filter(|p| p.selected).map(|p| {
            Circle::new(
                (p.frequency_hz, p.order as f64),
                7,
                PALETTE[1].stroke_width(2),
            )
        }))
        .map_err(err)?;
    let rejected = ex.decisions.iter().filter_map(|d| {
        let why = d.rejected.as_ref()?;
        let p = &ex.chart[d.pole];
        Some(((p.frequency_hz, p.order as f64), why.code()))
    });
    for (at, code) in rejected {
        chart
            .draw_series([Cross::new(at, 7, REJECTED.stroke_width(2))])
            .map_err(err)?;
        chart
            .draw_series([Text::new(
                code.to_string(),
                (at.0, at.1 + 1.5),
                (FONT, 11).into_font().color(&REJECTED),
            )])
            .map_err(err)?;
    }
    legend(&legend_area, frf, ex)
}

/// The legend in its strip: marker classes, the chosen poles, the FRF sums, the thresholds.
fn legend(
    area: &DrawingArea<SVGBackend, Shift>,
    frf: &FrfSet,
    ex: &Extraction,
) -> Result<(), PlotError> {
    let text = |s: String, y: i32| Text::new(s, (34, y - 6), (FONT, 12).into_font());
    let mut y = 50;
    for class in CLASSES {
        let (colour, name) = style(class);
        let at = (16, y);
        match class {
            StabilityClass::New => area.draw(&Circle::new(at, 2, colour.stroke_width(1))),
            StabilityClass::Frequency => area.draw(&Cross::new(at, 3, colour.stroke_width(1))),
            StabilityClass::Damping | StabilityClass::Shape => {
                area.draw(&TriangleMarker::new(at, 3, colour.filled()))
            }
            StabilityClass::Stable => area.draw(&Circle::new(at, 3, colour.filled())),
        }
        .map_err(err)?;
        area.draw(&text(name.to_string(), y)).map_err(err)?;
        y += 20;
    }
    area.draw(&Circle::new((16, y), 7, PALETTE[1].stroke_width(2)))
        .map_err(err)?;
    area.draw(&text(
        format!("chosen pole ({} modes kept)", ex.modes.len()),
        y,
    ))
    .map_err(err)?;
    y += 20;
    area.draw(&Cross::new((16, y), 7, REJECTED.stroke_width(2)))
        .map_err(err)?;
    let rejected = ex.decisions.iter().filter(|d| d.rejected.is_some()).count();
    area.draw(&text(
        format!("rejected candidate ({rejected}), its rule"),
        y,
    ))
    .map_err(err)?;
    y += 20;
    area.draw(&PathElement::new(
        vec![(6, y), (26, y)],
        BLACK.mix(0.55).stroke_width(1),
    ))
    .map_err(err)?;
    area.draw(&text("measured, sum of |H| (right axis)".into(), y))
        .map_err(err)?;
    y += 20;
    area.draw(&PathElement::new(
        vec![(6, y), (26, y)],
        PALETTE[1].stroke_width(1),
    ))
    .map_err(err)?;
    area.draw(&text("identified model, sum of |H|".into(), y))
        .map_err(err)?;
    y += 30;
    let c = &ex.criteria;
    for line in [
        format!("{} responses, {}", frf.responses.len(), frf.quantity.name()),
        format!(
            "stable: df/f < {}, dzeta/zeta < {},",
            c.frequency_tolerance, c.damping_tolerance
        ),
        format!(
            "MAC > {}; chosen: >= {} stable orders",
            c.mac_min, c.min_stable
        ),
        match ex.requested {
            Some(n) => format!("the {n} most stable (--modes)"),
            None => format!(
                "in a run from order <= {}, MPC >= {}",
                ex.rules.last_start(),
                ex.rules.mpc_min
            ),
        },
    ] {
        area.draw(&Text::new(line, (6, y), (FONT, 12).into_font()))
            .map_err(err)?;
        y += 18;
    }
    Ok(())
}

/// The chart as an SVG document of 1200 x 650 pixels, its axes labelled in `units`.
pub fn stabilization_svg(
    frf: &FrfSet,
    ex: &Extraction,
    title: &str,
    units: &ChartUnits,
) -> Result<String, PlotError> {
    svg((1200, 650), |area| draw(area, frf, ex, title, units))
}
