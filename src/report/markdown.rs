//! `report.md` and `error_vs_time.csv`: the report's tables as text, for diffs in review.

use std::fmt::Write as _;

use super::{Args, KNOBS, PlannerRow, Row, groups, marked_rows, pareto};

pub(super) fn csv(rows: &[Row]) -> String {
    let mut s = String::from("knob,setting,error_metric,error,time_ms,backend\n");
    let quote = |v: &str| {
        if v.contains([',', '"', '\n']) {
            format!("\"{}\"", v.replace('"', "\"\""))
        } else {
            v.into()
        }
    };
    for r in rows {
        let _ = writeln!(
            s,
            "{},{},{},{:e},{:.4},{}",
            r.knob,
            quote(&r.setting),
            r.error_metric,
            r.error,
            r.time_ms,
            r.backend
        );
    }
    s
}

pub(super) fn markdown(
    args: &Args,
    runs: usize,
    rows: &[Row],
    planner: &[PlannerRow],
    stability: &[ocean_verify::stability::Case],
    elapsed_s: f64,
) -> String {
    let mut s = String::new();
    let command = if args.quick { "ocean report --quick" } else { "ocean report" };
    let _ = writeln!(s, "# ocean report\n");
    let _ = writeln!(
        s,
        "Made by `{command} --out-dir {}` in {elapsed_s:.0} s. Times are medians of {} runs on \
         this machine (shared, so compare within this report only); image knobs render the \
         default scene at {}×{} on the CPU oracle.\n",
        args.out_dir.display(),
        runs,
        if args.quick { 160 } else { 640 },
        if args.quick { 90 } else { 360 },
    );
    let _ = writeln!(s, "## Pareto-optimal settings\n");
    let _ = writeln!(
        s,
        "A setting is Pareto-optimal when no other setting of its knob is both as accurate and \
         as fast (and better in one). The reference (error 0) is always on the front.\n"
    );
    let _ = writeln!(s, "| knob | metric | backend | Pareto-optimal settings (error @ ms) |");
    let _ = writeln!(s, "|---|---|---|---|");
    for (knob, metric, backend) in groups(rows) {
        let g: Vec<&Row> = rows
            .iter()
            .filter(|r| r.knob == knob && r.error_metric == metric && r.backend == backend)
            .collect();
        let mut front = pareto(&g);
        front.sort_by(|a, b| a.time_ms.total_cmp(&b.time_ms));
        let list: Vec<String> = front
            .iter()
            .map(|r| format!("{} ({:.2e} @ {:.3})", r.setting, r.error, r.time_ms))
            .collect();
        let _ = writeln!(s, "| {knob} | {metric} | {backend} | {} |", list.join("; "));
    }
    for knob in KNOBS {
        let _ = writeln!(s, "\n## {}\n\n{}.\n", knob.name, knob.varies);
        let _ = writeln!(s, "| setting | metric | error | time (ms) | backend | Pareto |");
        let _ = writeln!(s, "|---|---|---|---|---|---|");
        for (r, front) in marked_rows(rows, knob.name) {
            let _ = writeln!(
                s,
                "| {} | {} | {:.3e} | {:.3} | {} | {} |",
                r.setting,
                r.error_metric,
                r.error,
                r.time_ms,
                r.backend,
                if front { "✓" } else { "" }
            );
        }
    }
    let _ = writeln!(s, "\n## Planner: what pruning saves on the reference scenes\n");
    let _ = writeln!(
        s,
        "Each scene rendered by `FramePlan::full` (every rule off) and by its pruned plan \
         (`ocean plan SCENE` prints it with reasons); the pictures are compared bit for bit.\n"
    );
    let _ = writeln!(
        s,
        "| scene | left out | objects culled | full (ms) | pruned (ms) | saved (ms) | HDR pixels differing |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|---|");
    for p in planner {
        let names: Vec<&str> = p.pruned.iter().map(|q| q.name()).collect();
        let _ = writeln!(
            s,
            "| {} | {} | {} | {:.1} | {:.1} | {:.1} | {} |",
            p.scene,
            if names.is_empty() { "—".into() } else { names.join(", ") },
            if p.culled.is_empty() { "—" } else { &p.culled },
            p.full_ms,
            p.pruned_ms,
            p.full_ms - p.pruned_ms,
            p.differing
        );
    }
    let _ = writeln!(s, "\n## Numerical stability\n");
    let _ = writeln!(
        s,
        "Each case: whether every value is finite, its distance from the f64 reference and the \
         bound it must meet (where each bound comes from: `crates/ocean-cpu/src/stability.rs`; \
         `tests/stability.rs` asserts every row).\n"
    );
    let _ = writeln!(s, "| group | case | finite | error | bound | metric | note | ok |");
    let _ = writeln!(s, "|---|---|---|---|---|---|---|---|");
    let cell = |v: &str| v.replace('|', "\\|");
    for c in stability {
        let _ = writeln!(
            s,
            "| {} | {} | {} | {:.2e} | {:.2e} | {} | {} | {} |",
            c.group,
            cell(&c.name),
            if c.finite { "yes" } else { "NO" },
            c.error,
            c.bound,
            cell(c.metric),
            cell(&c.note),
            if c.passes() { "✓" } else { "FAIL" }
        );
    }
    s
}
