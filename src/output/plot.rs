//! Figures as SVG strings (plotters' SVG backend: no fonts or system libraries; text is left
//! to the viewer). Every figure has a title, axis labels with units, a legend where there are
//! several series, and log axes where the values span decades.

use std::ops::Range;

use plotters::coord::Shift;
use plotters::coord::ranged1d::ValueFormatter;
use plotters::prelude::*;

/// Series colours, in order.
pub const PALETTE: [RGBColor; 8] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
    RGBColor(255, 127, 14),
    RGBColor(23, 190, 207),
    RGBColor(140, 86, 75),
    RGBColor(127, 127, 127),
];

/// A drawing failure (plotters' errors are not Send; kept as text).
#[derive(Debug, thiserror::Error)]
#[error("drawing a figure: {0}")]
pub struct PlotError(pub String);

fn err<E: std::fmt::Debug>(e: E) -> PlotError {
    PlotError(format!("{e:?}"))
}

const FONT: &str = "sans-serif";

/// Renders `draw` on an SVG canvas of `size` pixels.
pub fn svg(
    size: (u32, u32),
    draw: impl FnOnce(&DrawingArea<SVGBackend, Shift>) -> Result<(), PlotError>,
) -> Result<String, PlotError> {
    let mut out = String::new();
    {
        let root = SVGBackend::with_string(&mut out, size).into_drawing_area();
        root.fill(&WHITE).map_err(err)?;
        draw(&root)?;
        root.present().map_err(err)?;
    }
    Ok(start_rotated_labels(&out))
}

/// plotters centres a rotated label on its tick, so half of it lies above the axis: anchor
/// rotated labels at their start instead, centred across the tick.
fn start_rotated_labels(svg: &str) -> String {
    svg.lines()
        .map(|line| {
            if line.starts_with("<text") && line.contains("transform=\"rotate(90,") {
                line.replace("text-anchor=\"middle\"", "text-anchor=\"start\"")
                    .replace("dy=\"0.76em\"", "dy=\"0.35em\"")
            } else {
                line.to_string()
            }
        })
        .collect::<Vec<_>>()
        .join("\n")
}

/// The label of the category at x (categories sit at 0, 1, 2, ...; nothing between them).
fn category(labels: &[String], x: f64) -> String {
    let i = x.round();
    if (x - i).abs() < 1e-6 && i >= 0.0 && (i as usize) < labels.len() {
        labels[i as usize].clone()
    } else {
        String::new()
    }
}

/// A box of quantiles: q05, q25, median, q75, q95.
pub type Quantiles = [f64; 5];

/// Engineering number for ticks: 3 significant digits, exponent when large or small.
pub fn tick(v: f64) -> String {
    if v.abs() < 1e-12 {
        "0".into()
    } else if v.abs() >= 1e4 || v.abs() < 1e-2 {
        format!("{v:.2e}")
    } else {
        format!("{}", (v * 1000.0).round() / 1000.0)
    }
}

/// The tick labeller of a logarithmic axis from `lo` to `hi`: one format for every tick of
/// the axis, plain (as [`tick`]) when the whole range lies in [0.01, 1e4), else scientific
/// with the mantissa's trailing zeros dropped (`1e-3`, `2.5e-3`, `0.1` never beside `1e-3`).
pub fn log_ticks(lo: f64, hi: f64) -> impl Fn(&f64) -> String {
    let plain = lo >= 1e-2 && hi < 1e4;
    move |v: &f64| {
        if plain { tick(*v) } else { scientific(*v) }
    }
}

/// `v` in scientific notation, 3 significant digits, trailing zeros of the mantissa dropped.
fn scientific(v: f64) -> String {
    let text = format!("{v:.2e}");
    match text.split_once('e') {
        Some((mantissa, exponent)) if mantissa.contains('.') => {
            let mantissa = mantissa.trim_end_matches('0').trim_end_matches('.');
            format!("{mantissa}e{exponent}")
        }
        _ => text,
    }
}

/// Box plots from stored quantiles, one per category, with a dashed reference line. The y
/// range is the union of the Tukey fences [q25 - 1.5 IQR, q75 + 1.5 IQR] (and the reference);
/// whiskers (q05, q95) beyond it stop at the edge with an open triangle. The legend has its
/// own strip on the right, clear of the boxes and whiskers.
#[allow(clippy::too_many_arguments)]
pub fn boxes(
    whole: &DrawingArea<SVGBackend, Shift>,
    title: &str,
    x_desc: &str,
    y_desc: &str,
    labels: &[String],
    boxes: &[Option<Quantiles>],
    reference: f64,
    reference_label: &str,
) -> Result<(), PlotError> {
    let blue = PALETTE[0];
    let red = PALETTE[1];
    let entries: [Entry; 3] = [
        (reference_label.to_string(), red, Mark::Line),
        ("median, [q25, q75]".to_string(), blue, Mark::Box),
        (
            "[q05, q95] (triangle: beyond the plot)".to_string(),
            blue,
            Mark::Whisker,
        ),
    ];
    let (area, legend_area) = with_legend_strip(whole, &entries);
    legend(&legend_area, &entries)?;
    let area = &area;
    let present: Vec<&Quantiles> = boxes.iter().flatten().collect();
    let mut lo = reference;
    let mut hi = reference;
    for q in &present {
        let iqr = q[3] - q[1];
        lo = lo.min(q[0].max(q[1] - 1.5 * iqr));
        hi = hi.max(q[4].min(q[3] + 1.5 * iqr));
    }
    let pad = 0.05 * (hi - lo).max(reference.abs() * 1e-3).max(f64::MIN_POSITIVE);
    let (lo, hi) = (lo - pad, hi + pad);
    let count = boxes.len();
    let mut chart = ChartBuilder::on(area)
        .caption(title, (FONT, 18))
        .margin(12)
        .x_label_area_size(70)
        .y_label_area_size(80)
        .build_cartesian_2d(-0.5f64..count as f64 - 0.5, lo..hi)
        .map_err(err)?;
    chart
        .configure_mesh()
        .disable_x_mesh()
        .x_desc(x_desc)
        .y_desc(y_desc)
        .x_labels(count.min(40))
        .x_label_formatter(&|x| category(labels, *x))
        .x_label_style((FONT, 11).into_font().transform(FontTransform::Rotate90))
        .y_label_formatter(&|v| tick(*v))
        .axis_desc_style((FONT, 14))
        .draw()
        .map_err(err)?;
    for (i, q) in boxes.iter().enumerate() {
        let Some(q) = q else { continue };
        let x = i as f64;
        let clip = |v: f64| v.clamp(lo, hi);
        chart
            .draw_series(std::iter::once(Rectangle::new(
                [(x - 0.3, clip(q[1])), (x + 0.3, clip(q[3]))],
                blue.mix(0.25).filled(),
            )))
            .map_err(err)?;
        chart
            .draw_series(std::iter::once(Rectangle::new(
                [(x - 0.3, clip(q[1])), (x + 0.3, clip(q[3]))],
                blue.stroke_width(1),
            )))
            .map_err(err)?;
        chart
            .draw_series(std::iter::once(PathElement::new(
                vec![(x - 0.3, clip(q[2])), (x + 0.3, clip(q[2]))],
                blue.stroke_width(2),
            )))
            .map_err(err)?;
        for (from, to) in [(q[1], q[0]), (q[3], q[4])] {
            chart
                .draw_series(std::iter::once(PathElement::new(
                    vec![(x, clip(from)), (x, clip(to))],
                    blue.stroke_width(1),
                )))
                .map_err(err)?;
            if to < lo || to > hi {
                let edge = clip(to);
                chart
                    .draw_series(std::iter::once(TriangleMarker::new(
                        (x, edge),
                        5,
                        blue.stroke_width(1),
                    )))
                    .map_err(err)?;
            } else {
                chart
                    .draw_series(std::iter::once(PathElement::new(
                        vec![(x - 0.15, to), (x + 0.15, to)],
                        blue.stroke_width(1),
                    )))
                    .map_err(err)?;
            }
        }
    }
    chart
        .draw_series(DashedLineSeries::new(
            vec![(-0.5, reference), (count as f64 - 0.5, reference)],
            8,
            5,
            red.stroke_width(2),
        ))
        .map_err(err)?;
    Ok(())
}

/// One series of a line chart.
pub struct Series {
    /// Legend text.
    pub name: String,
    /// Points (x, y); non-positive values are dropped on a log axis.
    pub points: Vec<(f64, f64)>,
    /// Error bar half-widths, when any.
    pub errors: Option<Vec<f64>>,
    /// Whether the points are joined (false: markers alone, as for measured data).
    pub line: bool,
}

/// A fitted curve with its uncertainty band, drawn as a shaded region around a line without
/// markers (a law beside the measured points it was fitted to).
pub struct Band {
    /// Legend text.
    pub name: String,
    /// Points (x, y) of the curve.
    pub points: Vec<(f64, f64)>,
    /// Half-width of the band at each point (0: the curve alone).
    pub half_width: Vec<f64>,
}

/// Axis ranges and scales of a line chart.
pub struct LineAxes {
    /// x label with unit.
    pub x_desc: String,
    /// y label with unit.
    pub y_desc: String,
    /// Logarithmic x.
    pub log_x: bool,
    /// Logarithmic y.
    pub log_y: bool,
    /// A horizontal reference line (value, legend), if any.
    pub reference: Option<(f64, String)>,
    /// Whether the y range follows the points only (error bars beyond it are cut at the
    /// edge): for estimates whose uncertainty spans decades more than their spread.
    pub clip_errors: bool,
}

fn span(values: impl Iterator<Item = f64>, log: bool) -> Range<f64> {
    let v: Vec<f64> = values
        .filter(|v| v.is_finite() && (!log || *v > 0.0))
        .collect();
    let (mut lo, mut hi) = v
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
            (a.min(x), b.max(x))
        });
    if !lo.is_finite() {
        return if log { 0.1..10.0 } else { -1.0..1.0 };
    }
    if log {
        (lo / 1.5)..(hi * 1.5)
    } else {
        if hi - lo < 1e-12 * hi.abs().max(1e-300) {
            lo -= 0.5 * lo.abs().max(1.0);
            hi += 0.5 * hi.abs().max(1.0);
        }
        let pad = 0.08 * (hi - lo);
        (lo - pad)..(hi + pad)
    }
}

/// Whether every x of the series is a whole number (then only whole ticks are labelled).
fn integer_x(series: &[Series]) -> bool {
    series
        .iter()
        .flat_map(|s| s.points.iter())
        .all(|p| p.0.fract() == 0.0)
}

/// How a legend entry shows its series.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Mark {
    /// A filled dot (points, bars).
    Dot,
    /// A horizontal line (a reference).
    Line,
    /// A filled box with its median line (a box plot).
    Box,
    /// A vertical whisker with its cap.
    Whisker,
}

/// One legend entry: its text, colour and mark.
type Entry = (String, RGBColor, Mark);

/// A legend in its own strip: a mark and the name of every series (and the reference).
fn legend(area: &DrawingArea<SVGBackend, Shift>, entries: &[Entry]) -> Result<(), PlotError> {
    for (i, (name, colour, mark)) in entries.iter().enumerate() {
        let y = 50 + 20 * i as i32;
        match mark {
            Mark::Line => area.draw(&PathElement::new(
                vec![(5, y), (25, y)],
                colour.stroke_width(2),
            )),
            Mark::Dot => area.draw(&Circle::new((15, y), 4, colour.filled())),
            Mark::Box => area
                .draw(&Rectangle::new(
                    [(7, y - 6), (23, y + 6)],
                    colour.mix(0.25).filled(),
                ))
                .and_then(|()| {
                    area.draw(&Rectangle::new(
                        [(7, y - 6), (23, y + 6)],
                        colour.stroke_width(1),
                    ))
                })
                .and_then(|()| {
                    area.draw(&PathElement::new(
                        vec![(7, y), (23, y)],
                        colour.stroke_width(2),
                    ))
                }),
            Mark::Whisker => area
                .draw(&PathElement::new(
                    vec![(15, y - 7), (15, y + 7)],
                    colour.stroke_width(1),
                ))
                .and_then(|()| {
                    area.draw(&PathElement::new(
                        vec![(11, y - 7), (19, y - 7)],
                        colour.stroke_width(1),
                    ))
                }),
        }
        .map_err(err)?;
        area.draw(&Text::new(
            name.clone(),
            (32, y - 6),
            (FONT, 12).into_font(),
        ))
        .map_err(err)?;
    }
    Ok(())
}

/// Splits off a strip on the right wide enough for the legend's longest entry.
fn with_legend_strip<'a>(
    whole: &DrawingArea<SVGBackend<'a>, Shift>,
    entries: &[Entry],
) -> (
    DrawingArea<SVGBackend<'a>, Shift>,
    DrawingArea<SVGBackend<'a>, Shift>,
) {
    let width = whole.dim_in_pixel().0 as i32;
    let longest = entries
        .iter()
        .map(|e| e.0.chars().count())
        .max()
        .unwrap_or(0) as i32;
    let strip = (40 + 7 * longest).clamp(120, width / 2);
    whole.split_horizontally(width - strip)
}

/// The colour of series `k` of a line plot (the reference line, when there is one, takes the
/// second colour of the palette).
fn series_colour(axes: &LineAxes, k: usize) -> RGBColor {
    if axes.reference.is_some() {
        PALETTE[(k + 2) % PALETTE.len()]
    } else {
        PALETTE[k % PALETTE.len()]
    }
}

/// The y range of a line plot: every point with its error bar (without, when the bars are
/// clipped: then padded by 30% on a linear axis) and the reference value.
fn line_y_range(axes: &LineAxes, series: &[Series]) -> Range<f64> {
    let y_span = span(
        series
            .iter()
            .flat_map(|s| {
                s.points.iter().enumerate().flat_map(move |(i, p)| {
                    let e = if axes.clip_errors {
                        0.0
                    } else {
                        s.errors.as_ref().map_or(0.0, |e| e[i])
                    };
                    [p.1 - e, p.1 + e, p.1]
                })
            })
            .chain(axes.reference.iter().map(|r| r.0)),
        axes.log_y,
    );
    if axes.clip_errors && !axes.log_y {
        let pad = 0.3 * (y_span.end - y_span.start);
        (y_span.start - pad)..(y_span.end + pad)
    } else {
        y_span
    }
}

/// Lines with markers (and error bars), log axes on request; the legend in a strip on the
/// right.
pub fn lines(
    whole: &DrawingArea<SVGBackend, Shift>,
    title: &str,
    axes: &LineAxes,
    series: &[Series],
) -> Result<(), PlotError> {
    lines_with_bands(whole, title, axes, series, &[])
}

/// [`lines`] with fitted curves and their bands drawn under the series (the bands take the
/// colours after the series').
pub fn lines_with_bands(
    whole: &DrawingArea<SVGBackend, Shift>,
    title: &str,
    axes: &LineAxes,
    series: &[Series],
    bands: &[Band],
) -> Result<(), PlotError> {
    let mut entries: Vec<Entry> = Vec::new();
    if let Some((_, label)) = &axes.reference {
        entries.push((label.clone(), PALETTE[1], Mark::Line));
    }
    for (k, s) in series.iter().enumerate() {
        entries.push((s.name.clone(), series_colour(axes, k), Mark::Dot));
    }
    for (k, b) in bands.iter().enumerate() {
        entries.push((
            b.name.clone(),
            series_colour(axes, series.len() + k),
            Mark::Line,
        ));
    }
    let (area, legend_area) = with_legend_strip(whole, &entries);
    legend(&legend_area, &entries)?;
    let band_ys = bands.iter().flat_map(|b| {
        b.points
            .iter()
            .zip(&b.half_width)
            .flat_map(|(p, w)| [p.1 - w, p.1 + w])
    });
    let ys = line_y_range(axes, series);
    let ys = span(band_ys.chain([ys.start, ys.end]), axes.log_y);
    let plot = LinePlot {
        axes,
        series,
        bands,
        xs: span(
            series
                .iter()
                .flat_map(|s| s.points.iter().map(|p| p.0))
                .chain(bands.iter().flat_map(|b| b.points.iter().map(|p| p.0))),
            axes.log_x,
        ),
        ys: if bands.is_empty() {
            line_y_range(axes, series)
        } else {
            ys
        },
        whole_x: integer_x(series),
    };
    let (xs, ys) = (plot.xs.clone(), plot.ys.clone());
    let mut builder = ChartBuilder::on(&area);
    builder
        .caption(title, (FONT, 16))
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(80);
    match (axes.log_x, axes.log_y) {
        (false, false) => plot.draw(builder.build_cartesian_2d(xs, ys).map_err(err)?),
        (true, false) => plot.draw(
            builder
                .build_cartesian_2d(xs.log_scale(), ys)
                .map_err(err)?,
        ),
        (false, true) => plot.draw(
            builder
                .build_cartesian_2d(xs, ys.log_scale())
                .map_err(err)?,
        ),
        (true, true) => plot.draw(
            builder
                .build_cartesian_2d(xs.log_scale(), ys.log_scale())
                .map_err(err)?,
        ),
    }
}

/// What a line plot draws inside its axes.
struct LinePlot<'s> {
    axes: &'s LineAxes,
    series: &'s [Series],
    bands: &'s [Band],
    xs: Range<f64>,
    ys: Range<f64>,
    /// Whether every x is an integer (then only integer ticks are labelled).
    whole_x: bool,
}

impl LinePlot<'_> {
    /// Draws the mesh, the reference line and every series (error bars, line, markers) on
    /// `chart`, whatever its axes' scales.
    fn draw<X, Y>(
        &self,
        mut chart: ChartContext<'_, SVGBackend<'_>, Cartesian2d<X, Y>>,
    ) -> Result<(), PlotError>
    where
        X: Ranged<ValueType = f64> + ValueFormatter<f64>,
        Y: Ranged<ValueType = f64> + ValueFormatter<f64>,
    {
        let axes = self.axes;
        let (y_lo, y_hi) = (self.ys.start, self.ys.end);
        let ticks = |log: bool, range: &Range<f64>| -> Box<dyn Fn(&f64) -> String> {
            if log {
                Box::new(log_ticks(range.start, range.end))
            } else {
                Box::new(|v: &f64| tick(*v))
            }
        };
        let (x_tick, y_tick) = (ticks(axes.log_x, &self.xs), ticks(axes.log_y, &self.ys));
        chart
            .configure_mesh()
            .light_line_style(RGBColor(245, 245, 245))
            .y_labels(if axes.log_y { 6 } else { 10 })
            .x_labels(if axes.log_x { 6 } else { 10 })
            .x_desc(axes.x_desc.as_str())
            .y_desc(axes.y_desc.as_str())
            .x_label_formatter(&|v| {
                if self.whole_x && v.fract().abs() > 1e-9 {
                    String::new()
                } else {
                    x_tick(v)
                }
            })
            .y_label_formatter(&y_tick)
            .axis_desc_style((FONT, 14))
            .draw()
            .map_err(err)?;
        if let Some((value, _)) = &axes.reference {
            chart
                .draw_series(DashedLineSeries::new(
                    vec![(self.xs.start, *value), (self.xs.end, *value)],
                    8,
                    5,
                    PALETTE[1].stroke_width(2),
                ))
                .map_err(err)?;
        }
        for (k, b) in self.bands.iter().enumerate() {
            let colour = series_colour(axes, self.series.len() + k);
            let upper = b
                .points
                .iter()
                .zip(&b.half_width)
                .map(|(p, w)| (p.0, p.1 + w));
            let lower = b
                .points
                .iter()
                .zip(&b.half_width)
                .map(|(p, w)| (p.0, p.1 - w));
            let outline: Vec<(f64, f64)> = upper.chain(lower.rev()).collect();
            if b.half_width.iter().any(|w| *w > 0.0) {
                chart
                    .draw_series(std::iter::once(Polygon::new(
                        outline,
                        colour.mix(0.2).filled(),
                    )))
                    .map_err(err)?;
            }
            chart
                .draw_series(LineSeries::new(b.points.clone(), colour.stroke_width(2)))
                .map_err(err)?;
        }
        for (k, s) in self.series.iter().enumerate() {
            let colour = series_colour(axes, k);
            let ok = |p: &(f64, f64)| {
                (!axes.log_x || p.0 > 0.0) && (!axes.log_y || p.1 > 0.0) && p.1.is_finite()
            };
            let points: Vec<(f64, f64)> = s.points.iter().copied().filter(ok).collect();
            if let Some(errors) = &s.errors {
                for (p, e) in s.points.iter().zip(errors) {
                    let (lo, hi) = ((p.1 - e).max(y_lo), (p.1 + e).min(y_hi));
                    if ok(p) && (!axes.log_y || lo > 0.0) {
                        chart
                            .draw_series(std::iter::once(PathElement::new(
                                vec![(p.0, lo), (p.0, hi)],
                                colour.stroke_width(1),
                            )))
                            .map_err(err)?;
                    }
                }
            }
            if s.line {
                chart
                    .draw_series(LineSeries::new(points.clone(), colour.stroke_width(2)))
                    .map_err(err)?;
            }
            chart
                .draw_series(points.iter().map(|p| Circle::new(*p, 4, colour.filled())))
                .map_err(err)?;
        }
        Ok(())
    }
}

/// Vertical bars on a log axis with a horizontal threshold line.
/// Bar `highlight`, when given, is drawn in another colour with its own legend entry.
pub fn bars(
    whole: &DrawingArea<SVGBackend, Shift>,
    title: &str,
    y_desc: &str,
    labels: &[String],
    values: &[f64],
    threshold: (f64, &str),
    highlight: Option<(usize, &str)>,
) -> Result<(), PlotError> {
    let mut entries = vec![(y_desc.to_string(), PALETTE[0], Mark::Dot)];
    if let Some((_, name)) = highlight {
        entries.push((name.to_string(), PALETTE[2], Mark::Dot));
    }
    entries.push((threshold.1.to_string(), PALETTE[1], Mark::Line));
    let (area, legend_area) = with_legend_strip(whole, &entries);
    legend(&legend_area, &entries)?;
    let area = &area;
    let floor = 1e-2;
    let ys = span(
        values
            .iter()
            .map(|v| v.max(floor))
            .chain([threshold.0, floor]),
        true,
    );
    let count = labels.len();
    let mut chart = ChartBuilder::on(area)
        .caption(title, (FONT, 16))
        .margin(12)
        .x_label_area_size(45)
        .y_label_area_size(80)
        .build_cartesian_2d(-0.5f64..count as f64 - 0.5, ys.clone().log_scale())
        .map_err(err)?;
    chart
        .configure_mesh()
        .disable_x_mesh()
        .x_desc("candidate effect")
        .y_desc(y_desc)
        .x_labels(count)
        .x_label_formatter(&|x| category(labels, *x))
        .y_label_formatter(&log_ticks(ys.start, ys.end))
        .axis_desc_style((FONT, 14))
        .draw()
        .map_err(err)?;
    chart
        .draw_series(values.iter().enumerate().map(|(i, v)| {
            let colour = if highlight.is_some_and(|(h, _)| h == i) {
                PALETTE[2]
            } else {
                PALETTE[0]
            };
            Rectangle::new(
                [(i as f64 - 0.3, floor), (i as f64 + 0.3, v.max(floor))],
                colour.mix(0.6).filled(),
            )
        }))
        .map_err(err)?;
    chart
        .draw_series(DashedLineSeries::new(
            vec![(-0.5, threshold.0), (count as f64 - 0.5, threshold.0)],
            8,
            5,
            PALETTE[1].stroke_width(2),
        ))
        .map_err(err)?;
    Ok(())
}
