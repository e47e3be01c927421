//! `jointid report` and `jointid diagnose --plots`: the expected figures exist, parse as XML,
//! carry their axis labels and reference lines, and the pages reference only files that exist.

use std::path::Path;

use crate::common::{jointid, scratch};

const MODEL: &str = include_str!("../../models/paper-case-1.toml");

/// The texts of an SVG, after checking that it parses as XML.
fn svg_texts(path: &Path) -> Vec<String> {
    let text = std::fs::read_to_string(path).unwrap();
    let doc = roxmltree::Document::parse(&text)
        .unwrap_or_else(|e| panic!("{}: not XML: {e}", path.display()));
    assert_eq!(doc.root_element().tag_name().name(), "svg");
    doc.descendants()
        .filter(|n| n.is_element() && n.tag_name().name() == "text")
        .filter_map(|n| n.text())
        .map(|t| t.trim().to_string())
        .collect()
}

/// Every `src="..."` of a page exists beside it.
fn assert_page_references_exist(page: &Path) -> usize {
    let html = std::fs::read_to_string(page).unwrap();
    let dir = page.parent().unwrap();
    let sources: Vec<&str> = html
        .split("src=\"")
        .skip(1)
        .map(|s| s.split('"').next().unwrap())
        .collect();
    for src in &sources {
        assert!(
            dir.join(src).exists(),
            "{} references missing {src}",
            page.display()
        );
    }
    sources.len()
}

#[test]
fn study_report_has_every_figure_with_labels_and_reference_lines() {
    let dir = scratch("report", "study");
    std::fs::write(dir.join("model.toml"), MODEL).unwrap();
    std::fs::write(
        dir.join("s.toml"),
        "name = \"s\"\nmodel = \"model.toml\"\n[truth]\ndelta = { k1 = 2.0e6, k2 = 2.0e3 }\n[grid]\nmodes = [1, 2]\nn = [10, 12]\nm = [5]\nnf = [0, 5]\nweighting = [\"inverse\"]\nshape_noise = [0.01]\nfrequency_noise = [0.0]\n[monte_carlo]\ntrials = 500\nseed = 1\nnoise = \"uniform\"\n[output]\ncsv = \"s.csv\"\n",
    )
    .unwrap();
    assert!(
        jointid(&["study", dir.join("s.toml").to_str().unwrap(), "--quiet"])
            .status
            .success()
    );
    let out = dir.join("report");
    let run = jointid(&[
        "report",
        dir.join("s.csv").to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
        "--title",
        "Small",
    ]);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    for (mode, param, unit, introduced) in [
        (1, "k1", "N/m", "2.00e6"),
        (1, "k2", "N m/rad", "2000"),
        (2, "k1", "N/m", "2.00e6"),
        (2, "k2", "N m/rad", "2000"),
    ] {
        let texts = svg_texts(&out.join(format!("box_mode{mode}_{param}.svg")));
        assert!(
            texts.contains(&format!("Delta {param} ({unit})")),
            "mode {mode} {param}: {texts:?}"
        );
        assert!(texts.contains(&"condition n/m/NF/W".to_string()));
        assert!(
            texts.contains(&format!("introduced {introduced}")),
            "mode {mode} {param}: {texts:?}"
        );
        assert!(
            texts.iter().any(|t| t == "10/5/0/2") && texts.iter().any(|t| t == "12/5/5/2"),
            "tick labels: {texts:?}"
        );
    }
    // n and NF vary; m, weighting and the noise levels do not.
    for axis in ["n", "nf"] {
        let texts = svg_texts(&out.join(format!("trend_{axis}.svg")));
        assert!(
            texts.contains(&"|median / introduced - 1|".to_string())
                && texts.contains(&"(q75 - q25) / |introduced|".to_string()),
            "{texts:?}"
        );
        assert!(
            texts.iter().any(|t| t.starts_with("mode 2, k2")),
            "legend: {texts:?}"
        );
    }
    assert!(!out.join("trend_m.svg").exists() && !out.join("trend_weighting.svg").exists());
    assert_eq!(assert_page_references_exist(&out.join("index.html")), 4 + 2);
    let html = std::fs::read_to_string(out.join("index.html")).unwrap();
    assert!(
        html.contains("<th>r=2 &Delta;k2</th>") && html.contains("Summary in the paper's layout")
    );
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn a_csv_that_is_not_a_study_output_is_refused_naming_the_missing_columns() {
    let dir = scratch("report", "bad");
    let csv = dir.join("identify.csv");
    std::fs::write(&csv, "mode,param,initial,correction,corrected,relative_correction,frequency_measured_hz,frequency_model_hz,condition\n1,k1,1e7,2e6,1.2e7,0.2,150,149,3\n").unwrap();
    let out = dir.join("r");
    let run = jointid(&[
        "report",
        csv.to_str().unwrap(),
        "--out",
        out.to_str().unwrap(),
    ]);
    assert_eq!(run.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert!(stderr.contains("identify.csv is not a jointid study output: missing column(s) cell, n, m, nf, weighting, shape_noise, frequency_noise, noise, introduced, trials, failures, median, q05, q25, q75, q95, relative_bias"), "{stderr}");
    assert!(!out.exists());
    std::fs::remove_dir_all(dir).unwrap();
}

#[test]
fn diagnose_plots_show_shapes_errors_corrections_and_candidates() {
    let dir = scratch("report", "diag");
    let model = dir.join("model.toml");
    std::fs::write(&model, MODEL).unwrap();
    let data = dir.join("d.csv");
    let m = model.to_str().unwrap();
    assert!(
        jointid(&[
            "simulate",
            "--model",
            m,
            "--effect",
            "joint_mass=0.05",
            "--modes",
            "4",
            "--frequency-noise",
            "0.001",
            "--shape-noise",
            "0.02",
            "--measure",
            "w",
            "--out",
            data.to_str().unwrap()
        ])
        .status
        .success()
    );
    let plots = dir.join("plots");
    let run = jointid(&[
        "diagnose",
        "--model",
        m,
        "--measured",
        data.to_str().unwrap(),
        "--plots",
        plots.to_str().unwrap(),
        "--json",
        dir.join("report.json").to_str().unwrap(),
    ]);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    for mode in 1..=4 {
        let texts = svg_texts(&plots.join(format!("shape_mode{mode}.svg")));
        assert!(
            texts.contains(&"position along the chain x (m)".to_string())
                && texts.contains(&"measured".to_string()),
            "{texts:?}"
        );
    }
    let texts = svg_texts(&plots.join("frequency_error.svg"));
    assert!(
        texts.contains(&"(f model - f measured) / f measured (%)".to_string())
            && texts.contains(&"after".to_string())
    );
    for param in ["k1", "k2"] {
        let texts = svg_texts(&plots.join(format!("corrections_{param}.svg")));
        assert!(
            texts.contains(&"measured frequency (Hz)".to_string())
                && texts.contains(&"no correction".to_string()),
            "{texts:?}"
        );
    }
    for param in ["k1", "k2"] {
        let texts = svg_texts(&plots.join(format!("stiffness_{param}.svg")));
        assert!(
            texts.contains(&"weighted mean over the modes".to_string())
                && texts.contains(&"frequency-independent joint: mean + 2 std".to_string())
                && texts
                    .iter()
                    .any(|t| t.starts_with(&format!("Per-mode {param} against frequency: slope"))),
            "{texts:?}"
        );
    }
    let texts = svg_texts(&plots.join("candidates.svg"));
    // Every candidate's significance against the threshold -log10(0.01) = 2.
    assert!(
        texts.contains(&"selected".to_string())
            && texts.contains(&"significant above 2 (p = 0.01)".to_string()),
        "{texts:?}"
    );
    assert_eq!(
        assert_page_references_exist(&plots.join("index.html")),
        4 + 1 + 2 + 2 + 1
    );
    std::fs::remove_dir_all(dir).unwrap();
}
