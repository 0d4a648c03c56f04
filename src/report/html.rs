//! `report/index.html` (issue 18, item 4): one self-contained page — the plots inline as SVG,
//! the pictures as PNG files in `pictures/` beside it, no script, no address outside the
//! folder — with the summary first (which setting of each knob to use, the systems side by
//! side, the stability table) and the long tables folded below. `report.md` stays for diffs
//! in review.

use std::fmt::Write as _;

use super::pictures::Written;
use super::plot::{good_enough, headline_metric, metric_label, suggestion};
use super::svg::esc;
use super::systems::Systems;
use super::{KNOBS, Row, groups, marked_rows, pareto};

/// Everything the page shows.
pub(super) struct Page<'a> {
    /// The command that made it.
    pub command: String,
    /// Seconds it took.
    pub elapsed_s: f64,
    /// Where they went.
    pub spent: String,
    /// What it ran on.
    pub machine: String,
    /// Every knob's rows.
    pub rows: &'a [Row],
    /// The overview plot (SVG).
    pub overview: &'a str,
    /// Each knob's plot (SVG), in [`KNOBS`] order.
    pub knob_plots: &'a [(&'static str, String)],
    /// The pictures.
    pub pictures: &'a [Written],
    /// The systems.
    pub systems: &'a Systems,
    /// The stability cases.
    pub stability: &'a [ocean_verify::stability::Case],
    /// The planner's section, the scaling section (report.md's Markdown tables, shown as
    /// text) and the scaling plot (SVG).
    pub planner_md: String,
    /// The scaling section's Markdown.
    pub scaling_md: String,
    /// The scaling plot (SVG).
    pub scaling_svg: &'a str,
}

const STYLE: &str = "body{font-family:'DejaVu Sans',Verdana,Arial,sans-serif;max-width:1600px;margin:1.5em auto;padding:0 1em;color:#1b1b1b;line-height:1.45}\
h1{margin-bottom:.2em}h2{border-bottom:2px solid #ccd;padding-bottom:.2em;margin-top:2em}\
table{border-collapse:collapse;margin:.6em 0;font-size:.9em}th,td{border:1px solid #ccc;padding:3px 7px;text-align:left;vertical-align:top}\
th{background:#eef1f6}tr.fail td{background:#fdd}td.ok{color:#176b2c;font-weight:bold}td.bad{color:#a00;font-weight:bold}\
svg{max-width:100%;height:auto}.figure{overflow-x:auto}.shots{display:flex;flex-wrap:wrap;gap:10px}\
.shot{border:1px solid #ddd;padding:4px;background:#fafafa}.shot img{display:block;image-rendering:pixelated}\
.shot .cap{font-size:.8em;max-width:420px}.ref{outline:3px solid #2a7a3a}details{margin:.8em 0}summary{cursor:pointer;font-weight:bold}\
pre{background:#f5f5f5;padding:.6em;overflow-x:auto;font-size:.85em}.note{color:#555;font-size:.9em}";

/// The page.
pub(super) fn page(p: &Page<'_>) -> String {
    let mut o = String::new();
    let _ = writeln!(
        o,
        "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>ocean report</title><style>{STYLE}</style></head><body>"
    );
    let _ = writeln!(o, "<h1>ocean report</h1>");
    let _ = writeln!(
        o,
        "<p class=\"note\">Made by <code>{}</code> in {:.0} s on {} ({}). Times are medians of runs in one process on this machine (compare within this report only). Tables for review: <a href=\"report.md\">report.md</a>, data: <a href=\"error_vs_time.csv\">error_vs_time.csv</a>.</p>",
        esc(&p.command),
        p.elapsed_s,
        esc(&p.machine),
        esc(&p.spent)
    );
    let _ = writeln!(
        o,
        "<p>Contents: <a href=\"#settings\">which setting to use</a> · <a href=\"#systems\">the systems side by side</a> · <a href=\"#stability\">numerical stability</a> · <a href=\"#knobs\">each knob, with pictures</a> · <a href=\"#planner\">planner</a> · <a href=\"#scaling\">scaling</a></p>"
    );
    settings(&mut o, p);
    let _ = writeln!(o, "<h2 id=\"systems\">The systems side by side</h2>");
    let _ = writeln!(
        o,
        "<p><img src=\"systems.png\" alt=\"every system on every viewpoint\" style=\"max-width:100%\"></p>"
    );
    let _ = writeln!(o, "<div class=\"figure\">{}</div>", super::systems_figures::chart(p.systems));
    o.push_str(&super::systems::html(p.systems));
    stability(&mut o, p.stability);
    knobs(&mut o, p);
    let _ =
        writeln!(o, "<h2 id=\"planner\">Planner: what pruning saves on the reference scenes</h2>");
    let _ = writeln!(
        o,
        "<details><summary>The table (from report.md)</summary><pre>{}</pre></details>",
        esc(&p.planner_md)
    );
    let _ =
        writeln!(o, "<h2 id=\"scaling\">Scaling</h2><div class=\"figure\">{}</div>", p.scaling_svg);
    let _ = writeln!(
        o,
        "<details><summary>The fitted exponents (from report.md)</summary><pre>{}</pre></details>",
        esc(&p.scaling_md)
    );
    let _ = writeln!(o, "</body></html>");
    o
}

/// The summary: per knob, the suggested and the Pareto-optimal settings, and the overview.
fn settings(o: &mut String, p: &Page<'_>) {
    let _ = writeln!(o, "<h2 id=\"settings\">Which setting to use</h2>");
    let _ = writeln!(
        o,
        "<p>Per knob, on each back end: the <b>suggested</b> setting is the fastest whose error (the knob's headline metric) is small enough by the rule beside it; the <b>Pareto-optimal</b> settings are those no other setting beats in both error and time (the line in the plots). Knobs that choose between models (shading, post, clouds) have no “correct” setting: their column shows how far each moves the picture.</p>"
    );
    let _ = writeln!(
        o,
        "<table><tr><th>knob</th><th>back end</th><th>headline metric</th><th>suggested</th><th>rule</th><th>Pareto-optimal (error @ ms)</th></tr>"
    );
    for knob in KNOBS {
        let of: Vec<&Row> = p.rows.iter().filter(|r| r.knob == knob.name).collect();
        let Some(metric) = headline_metric(&of) else { continue };
        for (k, m, backend) in groups(p.rows) {
            if k != knob.name || m != metric {
                continue;
            }
            let g: Vec<&Row> = of
                .iter()
                .copied()
                .filter(|r| r.error_metric == m && r.backend == backend)
                .collect();
            let mut front = pareto(&g);
            front.sort_by(|a, b| a.time_ms.total_cmp(&b.time_ms));
            let list: Vec<String> = front
                .iter()
                .map(|r| format!("{} ({:.2e} @ {:.2})", esc(&r.setting), r.error, r.time_ms))
                .collect();
            let (sugg, rule) = match (suggestion(&g), good_enough(m)) {
                (Some(r), Some((_, why))) => (
                    format!("<b>{}</b> ({:.2e} @ {:.2} ms)", esc(&r.setting), r.error, r.time_ms),
                    why,
                ),
                (None, Some((_, why))) => ("none meets the rule".into(), why),
                (_, None) => ("— (a choice of model)".into(), ""),
            };
            let _ = writeln!(
                o,
                "<tr><td><a href=\"#knob-{0}\">{0}</a></td><td>{backend}</td><td>{1}</td><td>{sugg}</td><td class=\"note\">{2}</td><td>{3}</td></tr>",
                knob.name,
                esc(&metric_label(m)),
                esc(rule),
                list.join("; ")
            );
        }
    }
    let _ = writeln!(o, "</table>");
    let _ = writeln!(
        o,
        "<p>Error against time, one panel per knob (its headline metric; every metric is in the knob's own section). Each point is a setting; the line is its back end's Pareto front; grey settings are dominated; the green strip under a log axis holds the reference (error 0). <a href=\"error_vs_time.png\">PNG</a></p><div class=\"figure\">{}</div>",
        p.overview
    );
}

/// Every stability case with its bound and result.
fn stability(o: &mut String, cases: &[ocean_verify::stability::Case]) {
    let failing = cases.iter().filter(|c| !c.passes()).count();
    let _ = writeln!(o, "<h2 id=\"stability\">Numerical stability</h2>");
    let _ = writeln!(
        o,
        "<p>{} cases, {} failing. Each: whether every value is finite, its distance from the f64 reference and the bound it must meet (bounds and their sources: <code>crates/ocean-cpu/src/stability.rs</code>; <code>tests/stability.rs</code> asserts every row).</p>",
        cases.len(),
        failing
    );
    let _ = writeln!(
        o,
        "<table><tr><th>group</th><th>case</th><th>finite</th><th>error</th><th>bound</th><th>metric</th><th>note</th><th>result</th></tr>"
    );
    for c in cases {
        let ok = c.passes();
        let _ = writeln!(
            o,
            "<tr{}><td>{}</td><td>{}</td><td>{}</td><td>{:.2e}</td><td>{:.2e}</td><td>{}</td><td>{}</td><td class=\"{}\">{}</td></tr>",
            if ok { "" } else { " class=\"fail\"" },
            esc(c.group),
            esc(&c.name),
            if c.finite { "yes" } else { "NO" },
            c.error,
            c.bound,
            esc(c.metric),
            esc(&c.note),
            if ok { "ok" } else { "bad" },
            if ok { "holds" } else { "FAILS" }
        );
    }
    let _ = writeln!(o, "</table>");
}

/// Each knob: what it varies, its plot, its pictures, its table folded.
fn knobs(o: &mut String, p: &Page<'_>) {
    let _ = writeln!(o, "<h2 id=\"knobs\">Each knob</h2>");
    for knob in KNOBS {
        let _ = writeln!(o, "<h3 id=\"knob-{0}\">{0}</h3><p>{1}.</p>", knob.name, esc(knob.varies));
        if let Some((_, svg)) = p.knob_plots.iter().find(|(k, _)| *k == knob.name) {
            let _ = writeln!(o, "<div class=\"figure\">{svg}</div>");
        }
        if let Some(w) = p.pictures.iter().find(|w| w.knob == knob.name) {
            let _ = writeln!(
                o,
                "<p class=\"note\">Pictures: {}. Under each setting, its FLIP error map against the reference (magma: black = no visible difference, yellow = the largest) and the whole frame's mean FLIP.</p><div class=\"shots\">",
                esc(&w.caption)
            );
            let scale = if w.size.0 < 200 { 2 } else { 1 };
            for s in &w.shown {
                let (iw, ih) = (w.size.0 * scale, w.size.1 * scale);
                let _ = write!(
                    o,
                    "<div class=\"shot{}\"><img src=\"{}\" width=\"{iw}\" height=\"{ih}\" alt=\"{}\">",
                    if s.is_reference { " ref" } else { "" },
                    s.crop,
                    esc(&s.setting)
                );
                if let Some(f) = &s.flip {
                    let _ = write!(
                        o,
                        "<img src=\"{f}\" width=\"{iw}\" height=\"{ih}\" alt=\"FLIP map of {}\">",
                        esc(&s.setting)
                    );
                }
                let _ = writeln!(
                    o,
                    "<div class=\"cap\"><b>{}</b>{}</div></div>",
                    esc(&s.setting),
                    if s.is_reference {
                        " — the reference".to_string()
                    } else {
                        format!(" — mean FLIP {:.4}", s.flip_mean)
                    }
                );
            }
            let _ = writeln!(o, "</div>");
        }
        let rows = marked_rows(p.rows, knob.name);
        let _ = writeln!(
            o,
            "<details><summary>{} rows</summary><table><tr><th>setting</th><th>metric</th><th>error</th><th>time (ms)</th><th>back end</th><th>Pareto</th></tr>",
            rows.len()
        );
        for (r, front) in rows {
            let _ = writeln!(
                o,
                "<tr><td>{}</td><td>{}</td><td>{:.3e}</td><td>{:.3}</td><td>{}</td><td>{}</td></tr>",
                esc(&r.setting),
                r.error_metric,
                r.error,
                r.time_ms,
                r.backend,
                if front { "✓" } else { "" }
            );
        }
        let _ = writeln!(o, "</table></details>");
    }
}

/// What the report ran on: CPU model and threads, OS, GPU adapter (or why none).
pub(super) fn machine(gpu: &Result<String, String>) -> String {
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|t| {
            t.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split(':').nth(1))
                .map(|s| s.trim().to_string())
        })
        .unwrap_or_else(|| std::env::consts::ARCH.to_string());
    let threads = std::thread::available_parallelism().map_or(1, |n| n.get());
    let gpu = match gpu {
        Ok(a) => format!("GPU: {a}"),
        Err(e) => format!("no GPU adapter ({e})"),
    };
    format!("{cpu}, {threads} threads, {}; {gpu}", std::env::consts::OS)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::report::test_row as row;

    #[test]
    fn the_suggestion_is_the_fastest_good_enough_setting() {
        let rows = [row("ref", 0.0, 10.0), row("ok", 0.005, 4.0), row("fast", 0.2, 1.0)];
        let g: Vec<&Row> = rows.iter().collect();
        assert_eq!(suggestion(&g).unwrap().setting, "ok");
        // Control: with nothing good enough but the reference, the reference.
        let g: Vec<&Row> = [&rows[0], &rows[2]].into_iter().collect();
        assert_eq!(suggestion(&g).unwrap().setting, "ref");
        // A change of model has no suggestion.
        let change = Row { error_metric: "log_l_change", ..row("x", 0.1, 1.0) };
        assert!(suggestion(&[&change]).is_none());
    }
}
