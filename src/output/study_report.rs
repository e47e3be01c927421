//! `jointid report`: figures of a study CSV and the page that shows them with the study's
//! conditions and the summary in the paper's layout.
//!
//! Figures:
//! - `box_mode{r}_{param}.svg`: per mode and parameter, the distribution of Delta p in every
//!   cell (box from the stored quantiles), the introduced value as a dashed reference line;
//! - `trend_{axis}.svg` for every grid axis that varies: |relative bias of the median| and the
//!   relative spread (q75 - q25) / |introduced| against that axis, one line per (mode,
//!   parameter), the median over the cells that share the axis value; log y.

use std::collections::BTreeMap;

use super::plot::{LineAxes, PlotError, Series, boxes, lines, svg, tick};
use super::table::sci;
use crate::report::{Axis, StudyResults};
use crate::stats::quantile_sorted;

/// One figure of a report.
#[derive(Debug, Clone)]
pub struct Figure {
    /// File name (`*.svg`).
    pub name: String,
    /// Caption on the page.
    pub caption: String,
    /// SVG text.
    pub svg: String,
}

/// Unit of a joint parameter name (`k1`, `joint2.k2`, ...).
pub fn unit_of(param: &str) -> &'static str {
    if param.ends_with("k2") {
        "N m/rad"
    } else {
        "N/m"
    }
}

fn file_safe(s: &str) -> String {
    s.chars()
        .map(|c| if c.is_ascii_alphanumeric() { c } else { '_' })
        .collect()
}

/// Every figure of a study report.
pub fn study_figures(results: &StudyResults, title: &str) -> Result<Vec<Figure>, PlotError> {
    let mut out = Vec::new();
    let cells: Vec<usize> = results.cells.keys().copied().collect();
    let noise_varies = Axis::ShapeNoise.varies(results) || Axis::FrequencyNoise.varies(results);
    let labels: Vec<String> = cells
        .iter()
        .map(|c| {
            let cond = &results.cells[c];
            if noise_varies {
                format!(
                    "{} s{} f{}",
                    cond.short(),
                    cond.shape_noise,
                    cond.frequency_noise
                )
            } else {
                cond.short()
            }
        })
        .collect();
    for mode in results.modes() {
        for param in results.params() {
            let quantiles: Vec<_> = cells
                .iter()
                .map(|&c| results.row(c, mode, &param).and_then(|r| r.quantiles))
                .collect();
            let Some(introduced) = cells
                .iter()
                .find_map(|&c| results.row(c, mode, &param))
                .map(|r| r.introduced)
            else {
                continue;
            };
            let fig_title = format!("{title}: mode {mode}, Delta {param} in every condition");
            let body = svg((1300, 560), |area| {
                boxes(
                    area,
                    &fig_title,
                    "condition n/m/NF/W",
                    &format!("Delta {param} ({})", unit_of(&param)),
                    &labels,
                    &quantiles,
                    introduced,
                    &format!("introduced {}", tick(introduced)),
                )
            })?;
            out.push(Figure {
                name: format!("box_mode{mode}_{}.svg", file_safe(&param)),
                caption: format!("Mode {mode}, Delta {param}: median, [q25, q75] and [q05, q95] of every condition against the introduced value {} {}.", tick(introduced), unit_of(&param)),
                svg: body,
            });
        }
    }
    for axis in Axis::ALL.into_iter().filter(|a| a.varies(results)) {
        let (bias, spread) = trend_series(results, axis);
        let log_x = matches!(axis, Axis::ShapeNoise | Axis::FrequencyNoise) && spans_decades(&bias);
        let body = svg((1200, 500), |area| {
            let (left, right) = area.split_horizontally(600);
            let axes = |y: &str| LineAxes {
                x_desc: axis.label().to_string(),
                y_desc: y.to_string(),
                log_x,
                log_y: true,
                reference: None,
                clip_errors: false,
            };
            lines(
                &left,
                &format!("{title}: |relative bias of the median|"),
                &axes("|median / introduced - 1|"),
                &bias,
            )?;
            lines(
                &right,
                &format!("{title}: relative spread"),
                &axes("(q75 - q25) / |introduced|"),
                &spread,
            )
        })?;
        out.push(Figure {
            name: format!("trend_{}.svg", axis.name()),
            caption: format!(
                "Against {}: relative bias of the median and relative spread, one line per mode and parameter, each point the median over the conditions that share that value; log scales.",
                axis.label()
            ),
            svg: body,
        });
    }
    Ok(out)
}

fn spans_decades(series: &[Series]) -> bool {
    let xs: Vec<f64> = series
        .iter()
        .flat_map(|s| s.points.iter().map(|p| p.0))
        .filter(|x| *x > 0.0)
        .collect();
    let (lo, hi) = xs
        .iter()
        .fold((f64::INFINITY, 0.0_f64), |(a, b), &x| (a.min(x), b.max(x)));
    hi / lo >= 10.0
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    quantile_sorted(&v, 0.5)
}

/// (bias series, spread series) against `axis`.
fn trend_series(results: &StudyResults, axis: Axis) -> (Vec<Series>, Vec<Series>) {
    let mut bias = Vec::new();
    let mut spread = Vec::new();
    for mode in results.modes() {
        for param in results.params() {
            let mut by_value: BTreeMap<i64, (f64, Vec<f64>, Vec<f64>)> = BTreeMap::new();
            for row in results
                .rows
                .iter()
                .filter(|r| r.mode == mode && r.param == param && r.introduced != 0.0)
            {
                let Some(q) = row.quantiles else { continue };
                let x = axis.value(&results.cells[&row.cell]);
                let entry =
                    by_value
                        .entry((x * 1e9).round() as i64)
                        .or_insert((x, Vec::new(), Vec::new()));
                entry.1.push((q[2] / row.introduced - 1.0).abs());
                entry.2.push((q[3] - q[1]) / row.introduced.abs());
            }
            let name = format!("mode {mode}, {param}");
            bias.push(Series {
                name: name.clone(),
                points: by_value
                    .values()
                    .map(|(x, b, _)| (*x, median(b.clone())))
                    .collect(),
                errors: None,
                line: true,
            });
            spread.push(Series {
                name,
                points: by_value
                    .values()
                    .map(|(x, _, s)| (*x, median(s.clone())))
                    .collect(),
                errors: None,
                line: true,
            });
        }
    }
    (bias, spread)
}

/// `s` with the HTML special characters escaped.
pub(crate) fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

const STYLE: &str = "body { font-family: sans-serif; margin: 2em; color: #222; }\ntable { border-collapse: collapse; font-size: 12px; }\nth, td { border: 1px solid #bbb; padding: 3px 6px; text-align: right; white-space: nowrap; }\nth { background: #eee; }\nfigure { margin: 2em 0; }\nfigcaption { font-size: 14px; color: #444; max-width: 1100px; }\nimg { max-width: 100%; border: 1px solid #ddd; }\n";

/// The page's head, styles and `<h1>` title.
pub(crate) fn page_head(title: &str) -> String {
    format!(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>{t}</title>\n<style>\n{STYLE}</style>\n</head>\n<body>\n<h1>{t}</h1>\n",
        t = escape(title)
    )
}

/// Every figure with its caption.
pub(crate) fn page_figures(html: &mut String, figures: &[Figure]) {
    for f in figures {
        html.push_str(&format!(
            "<figure>\n<img src=\"{}\" alt=\"{}\">\n<figcaption>{}</figcaption>\n</figure>\n",
            f.name,
            escape(&f.caption),
            escape(&f.caption)
        ));
    }
}

/// The page: conditions, the paper-layout table, the figures.
pub fn index_html(title: &str, source: &str, results: &StudyResults, figures: &[Figure]) -> String {
    let modes = results.modes();
    let params = results.params();
    let trials: Vec<usize> = {
        let mut t: Vec<usize> = results.rows.iter().map(|r| r.trials).collect();
        t.sort_unstable();
        t.dedup();
        t
    };
    let failures: usize = results.rows.iter().map(|r| r.failures).sum();
    let mut html = page_head(title);
    html.push_str(&format!(
        "<h2>Conditions</h2>\n<p>Source: <code>{}</code>. {} cell(s); modes {}; parameters {}; {} trial(s) per cell; {} noise; rank-deficient trials in all: {}. W: 1 equal weights, 2 eq. (16-a), 3 eq. (16-b).</p>\n",
        escape(source),
        results.cells.len(),
        modes.iter().map(|m| m.to_string()).collect::<Vec<_>>().join(", "),
        escape(&params.join(", ")),
        trials.iter().map(|t| t.to_string()).collect::<Vec<_>>().join(", "),
        escape(&results.noise),
        failures
    ));
    html.push_str("<h2>Summary in the paper's layout</h2>\n<p>Median and [q05, q95] of every correction.</p>\n<table>\n<tr><th>cell</th><th>n</th><th>m</th><th>NF</th><th>W</th><th>shape noise</th><th>freq. noise</th>");
    for mode in &modes {
        for p in &params {
            html.push_str(&format!("<th>r={mode} &Delta;{}</th>", escape(p)));
        }
    }
    html.push_str("</tr>\n");
    for (cell, c) in &results.cells {
        html.push_str(&format!(
            "<tr><td>{cell}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td>",
            c.n,
            c.m,
            c.nf,
            c.w(),
            c.shape_noise,
            c.frequency_noise
        ));
        for mode in &modes {
            for p in &params {
                let text = match results.row(*cell, *mode, p).and_then(|r| r.quantiles) {
                    Some(q) => format!("{} [{}, {}]", sci(q[2]), sci(q[0]), sci(q[4])),
                    None => "all failed".into(),
                };
                html.push_str(&format!("<td>{text}</td>"));
            }
        }
        html.push_str("</tr>\n");
    }
    html.push_str("</table>\n<h2>Figures</h2>\n");
    page_figures(&mut html, figures);
    html.push_str("</body>\n</html>\n");
    html
}
