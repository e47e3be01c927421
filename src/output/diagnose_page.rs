//! The page of `jointid diagnose --plots DIR` (`DIR/index.html`): the verdict in words, the
//! noise, the errors of the model as given, calibrated and after, the candidates' table, the
//! fitted parameters, then the figures. The tables are the text report's (the same rows from
//! [`super::diagnose`]), as HTML.
//!
//! Layer 7 (outputs; see the crate docs): imports [`crate::diagnose`] and its siblings
//! [`super::diagnose`], [`super::study_report`] and [`super::table`].

use super::diagnose::{
    CANDIDATE_HEADERS, SUMMARY_HEADERS, candidate_rows, summary_rows, verdict_text,
};
use super::study_report::{Figure, escape, page_figures, page_head};
use super::table::sci;
use crate::diagnose::Report;

/// An HTML table of `header` and `rows`, every cell escaped.
fn html_table(header: &[&str], rows: &[Vec<String>]) -> String {
    let cells = |tag: &str, row: &mut dyn Iterator<Item = &str>| -> String {
        row.map(|c| format!("<{tag}>{}</{tag}>", escape(c)))
            .collect::<String>()
    };
    let mut html = format!(
        "<table>\n<tr>{}</tr>\n",
        cells("th", &mut header.iter().copied())
    );
    for row in rows {
        html.push_str(&format!(
            "<tr>{}</tr>\n",
            cells("td", &mut row.iter().map(String::as_str))
        ));
    }
    html.push_str("</table>\n");
    html
}

/// The noise stated and the one the selection used, in one sentence.
fn noise_sentence(r: &Report) -> String {
    let e = &r.noise_estimate;
    if e.stated_kept {
        return format!(
            "Noise stated: frequency {}, shape {} (relative standard deviations), and used: no model's residuals pass the checks that do not stand on the noise level. The largest model ({}) leaves shape {:.3e} ({:.2}x stated).",
            r.noise.frequency, r.noise.shape, e.from_model, e.shape, e.shape_factor
        );
    }
    format!(
        "Noise stated: frequency {}, shape {} (relative standard deviations). Estimated from the shape residuals of the largest model that fits ({}): shape {:.3e} ({:.2}x stated). The selection used frequency {:.3e}, shape {:.3e}.",
        r.noise.frequency,
        r.noise.shape,
        e.from_model,
        e.shape,
        e.shape_factor,
        e.working.frequency,
        e.working.shape
    )
}

/// The page: `title`, the verdict, the summary and candidate tables, the fitted parameters
/// and the `figures` (written beside the page).
pub fn diagnose_page(title: &str, r: &Report, figures: &[Figure]) -> String {
    let mut html = page_head(title);
    html.push_str(&format!(
        "<h2>Verdict</h2>\n<p><strong>{}</strong></p>\n",
        escape(&verdict_text(r, true))
    ));
    for w in &r.warnings {
        html.push_str(&format!("<p>Warning: {}</p>\n", escape(w)));
    }
    html.push_str(&format!("<p>{}</p>\n", escape(&noise_sentence(r))));
    html.push_str(
        "<h2>Errors of the model</h2>\n<p>As given, with the joint calibrated (\"before\") and with the selected effect (\"after\"); P(fit) is the p-value of chi^2 under the noise the selection used.</p>\n",
    );
    html.push_str(&html_table(&SUMMARY_HEADERS, &summary_rows(r)));
    html.push_str(&format!(
        "<h2>Candidates</h2>\n<p>{}</p>\n",
        escape(&r.criterion)
    ));
    html.push_str(&html_table(&CANDIDATE_HEADERS, &candidate_rows(r)));
    let parameters: Vec<Vec<String>> = r
        .after
        .parameters
        .iter()
        .map(|e| vec![e.name.clone(), sci(e.value), sci(e.se), e.unit.to_string()])
        .collect();
    html.push_str("<h2>Fitted parameters, after</h2>\n");
    html.push_str(&html_table(
        &["parameter", "value", "+- std", "unit"],
        &parameters,
    ));
    html.push_str("<h2>Figures</h2>\n");
    page_figures(&mut html, figures);
    html.push_str("</body>\n</html>\n");
    html
}
