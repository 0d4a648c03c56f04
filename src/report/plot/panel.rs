//! One panel of a plot: its legend, its axes with the strip of error 0 under the log scale,
//! each back end's Pareto front, the page's rule, and the points with labels placed where
//! they cover the least.

use super::{GOOD, GREY, LogAxis, Panel, ZERO_STRIP, colour, good_enough, suggestion, tick_text};
use crate::report::svg::{Anchor, Svg, text_width};
use crate::report::{Row, pareto};

/// An axis-aligned box (x0, y0, x1, y1).
type Boxed = (f64, f64, f64, f64);

fn overlap(a: Boxed, b: Boxed) -> f64 {
    let w = (a.2.min(b.2) - a.0.max(b.0)).max(0.0);
    let h = (a.3.min(b.3) - a.1.max(b.1)).max(0.0);
    w * h
}

/// Font size of a point's label, px.
const LABEL: f64 = 10.5;

/// Font size of the legend, px.
const KEY: f64 = 10.5;

/// One panel at `(ox, oy)` of size `(w, h)`: title, legend, axes, fronts, the page's rule,
/// points and labels, in that order (each drawn over the one before).
pub(super) fn draw_panel(svg: &mut Svg, (ox, oy): (f64, f64), (w, h): (f64, f64), p: &Panel<'_>) {
    svg.text_styled(
        (ox + w / 2.0, oy + 20.0),
        15.0,
        Anchor::Middle,
        &p.title,
        r##"fill="#111111" font-weight="bold""##,
    );
    let drawable: Vec<&Row> =
        p.rows.iter().copied().filter(|r| r.time_ms > 0.0 && r.time_ms.is_finite()).collect();
    let left_out = p.rows.len() - drawable.len();
    let mut backends: Vec<&str> = Vec::new();
    for r in &drawable {
        if !backends.contains(&r.backend) {
            backends.push(r.backend);
        }
    }
    let ly = draw_legend(svg, (ox, oy), w, &backends, &drawable);
    let Some(area) = PlotArea::lay_out((ox, oy), (w, h), ly, &drawable) else {
        svg.text((ox + w / 2.0, oy + h / 2.0), 12.0, Anchor::Middle, "no timed setting");
        return;
    };
    area.draw_frame(svg);
    area.draw_ticks(svg, ox + w / 2.0);
    svg.text((ox + w / 2.0 + 24.0, oy + h - 12.0), 11.5, Anchor::Middle, p.x_label);
    svg.vertical_text((ox + 16.0, (area.top + area.bottom) / 2.0), 11.5, &p.y_label);
    if left_out > 0 {
        svg.text_styled(
            (area.right, oy + h - 2.0),
            9.0,
            Anchor::End,
            &format!("{left_out} setting(s) without a time not drawn"),
            r##"fill="#777777""##,
        );
    }
    let on_front = draw_fronts(svg, &area, &backends, &drawable);
    draw_rule(svg, &area, &backends, &drawable);
    // Points, dominated ones first so that the front's sit on top.
    let mut order: Vec<&Row> = drawable.clone();
    order.sort_by_key(|r| is_on(&on_front, r));
    let mut taken: Vec<Boxed> = order
        .iter()
        .map(|r| {
            let (px, py) = area.at(r);
            (px - 5.0, py - 5.0, px + 5.0, py + 5.0)
        })
        .collect();
    for r in &order {
        let fill = if is_on(&on_front, r) { colour(r.backend) } else { GREY };
        svg.marker(
            area.at(r),
            r.backend == "gpu",
            4.0,
            &format!(r##"fill="{fill}" stroke="#ffffff" stroke-width="0.8""##),
        );
    }
    // Labels: the front's first, each at the free place nearest its point.
    let mut labelled = order.clone();
    labelled.reverse();
    for r in labelled {
        draw_label(svg, &area, &mut taken, r, backends.len() > 1, is_on(&on_front, r));
    }
}

/// Whether `r` is one of `front` (by address: two settings may measure alike).
fn is_on(front: &[&Row], r: &Row) -> bool {
    front.iter().any(|f| std::ptr::eq(*f, r))
}

/// An entry of a panel's legend.
#[derive(Clone, Copy)]
enum Key<'k> {
    Backend(&'k str),
    Front,
    Dominated,
    Zero,
    Suggested,
}

impl<'k> Key<'k> {
    fn text(self) -> &'k str {
        match self {
            Key::Backend(b) => b,
            Key::Front => "Pareto front",
            Key::Dominated => "dominated",
            Key::Zero => "error 0 (reference)",
            Key::Suggested => "suggested",
        }
    }
}

/// The legend, above the plot area, wrapped onto a second line where it is too wide; returns
/// the baseline of its last line.
fn draw_legend(
    svg: &mut Svg,
    (ox, oy): (f64, f64),
    w: f64,
    backends: &[&str],
    drawable: &[&Row],
) -> f64 {
    let mut keys: Vec<Key<'_>> = backends.iter().map(|b| Key::Backend(b)).collect();
    keys.extend([Key::Front, Key::Dominated]);
    if drawable.iter().any(|r| r.error == 0.0) {
        keys.push(Key::Zero);
    }
    if drawable.first().and_then(|r| good_enough(r.error_metric)).is_some() {
        keys.push(Key::Suggested);
    }
    let (mut lx, mut ly) = (ox + 62.0, oy + 38.0);
    for key in keys {
        let text = key.text();
        let swatch = if matches!(key, Key::Front) { 22.0 } else { 12.0 };
        let width = swatch + text_width(text, KEY) + 12.0;
        if lx + width > ox + w - 8.0 {
            (lx, ly) = (ox + 62.0, ly + 14.0);
        }
        let mid = (lx + 4.0, ly - 4.0);
        match key {
            Key::Backend(b) => {
                svg.marker(mid, b == "gpu", 4.0, &format!(r#"fill="{}""#, colour(b)));
            }
            Key::Front => svg.line(
                (lx, ly - 4.0),
                (lx + 18.0, ly - 4.0),
                r##"stroke="#555555" stroke-width="1.5""##,
            ),
            Key::Dominated => svg.circle(mid, 4.0, &format!(r#"fill="{GREY}""#)),
            Key::Zero => svg.rect((lx - 2.0, ly - 9.0), (12.0, 10.0), ZERO_STRIP),
            Key::Suggested => {
                svg.circle(mid, 5.0, &format!(r#"fill="none" stroke="{GOOD}" stroke-width="2""#))
            }
        }
        svg.text((lx + swatch, ly), KEY, Anchor::Start, text);
        lx += width;
    }
    ly
}

/// Where a panel's data go, px: the plot area, its log axes, and the strip under the y axis
/// that holds the settings of error 0 (none where no setting has it).
struct PlotArea {
    left: f64,
    right: f64,
    top: f64,
    bottom: f64,
    /// The bottom of the log scale: above the zero strip and its gap.
    log_bottom: f64,
    has_zero: bool,
    /// The zero strip's height (0 without one).
    strip: f64,
    /// The height at which a setting of error 0 is drawn.
    zero_y: f64,
    x: LogAxis,
    /// `None` where every setting has error 0.
    y: Option<LogAxis>,
}

impl PlotArea {
    /// The area of the panel at `(ox, oy)` of size `(w, h)` under a legend whose last line is
    /// at `ly`, its axes covering `drawable`; `None` where no setting has a time to place.
    fn lay_out(
        (ox, oy): (f64, f64),
        (w, h): (f64, f64),
        ly: f64,
        drawable: &[&Row],
    ) -> Option<Self> {
        let (left, right, top, bottom) = (ox + 62.0, ox + w - 14.0, ly + 12.0, oy + h - 46.0);
        let has_zero = drawable.iter().any(|r| r.error == 0.0);
        let strip = if has_zero { 24.0 } else { 0.0 };
        let log_bottom = bottom - strip - if has_zero { 8.0 } else { 0.0 };
        let x = LogAxis::covering(drawable.iter().map(|r| r.time_ms), left, right)?;
        let y = LogAxis::covering(drawable.iter().map(|r| r.error), log_bottom, top);
        let zero_y = bottom - strip / 2.0;
        Some(Self { left, right, top, bottom, log_bottom, has_zero, strip, zero_y, x, y })
    }

    /// Where a setting's point is drawn.
    fn at(&self, r: &Row) -> (f64, f64) {
        let py = match (&self.y, r.error > 0.0) {
            (Some(y), true) => y.at(r.error),
            _ => self.zero_y,
        };
        (self.x.at(r.time_ms), py)
    }

    /// The frame round the log scale, and the zero strip with its break marks.
    fn draw_frame(&self, svg: &mut Svg) {
        let (left, right, top, bottom) = (self.left, self.right, self.top, self.bottom);
        let (log_bottom, strip) = (self.log_bottom, self.strip);
        let frame = r##"fill="none" stroke="#444444" stroke-width="1""##;
        svg.rect((left, top), (right - left, log_bottom - top), frame);
        if self.has_zero {
            svg.rect((left, bottom - strip), (right - left, strip), ZERO_STRIP);
            svg.text((left - 6.0, self.zero_y + 4.0), 10.0, Anchor::End, "0");
            // Break marks: the strip is not on the log scale.
            for xx in [left, right] {
                svg.line(
                    (xx - 4.0, log_bottom + 6.0),
                    (xx + 4.0, log_bottom + 2.0),
                    r##"stroke="#444444""##,
                );
            }
        }
    }

    /// Both axes' ticks and grid lines (or, without a y axis, why there is none, centred at
    /// `mid_x`: the panel's middle).
    fn draw_ticks(&self, svg: &mut Svg, mid_x: f64) {
        let (left, right, top, bottom) = (self.left, self.right, self.top, self.bottom);
        let grid = r##"stroke="#e4e4e4" stroke-width="1""##;
        for (v, major) in self.x.ticks() {
            let px = self.x.at(v);
            svg.line((px, top), (px, bottom), grid);
            svg.line(
                (px, bottom),
                (px, bottom + if major { 5.0 } else { 3.0 }),
                r##"stroke="#444444""##,
            );
            svg.text((px, bottom + 16.0), 10.0, Anchor::Middle, &tick_text(v));
        }
        if let Some(y) = &self.y {
            for (v, major) in y.ticks() {
                let py = y.at(v);
                svg.line((left, py), (right, py), grid);
                svg.line(
                    (left - if major { 5.0 } else { 3.0 }, py),
                    (left, py),
                    r##"stroke="#444444""##,
                );
                svg.text((left - 7.0, py + 3.5), 10.0, Anchor::End, &tick_text(v));
            }
        } else {
            svg.text(
                (mid_x, (top + self.log_bottom) / 2.0),
                11.0,
                Anchor::Middle,
                "every setting: error 0",
            );
        }
    }
}

/// Each back end's Pareto front as a line, under the points; returns the settings on a front.
fn draw_fronts<'a>(
    svg: &mut Svg,
    area: &PlotArea,
    backends: &[&str],
    drawable: &[&'a Row],
) -> Vec<&'a Row> {
    let mut on_front: Vec<&Row> = Vec::new();
    for b in backends {
        let group: Vec<&Row> = drawable.iter().copied().filter(|r| r.backend == *b).collect();
        let mut front = pareto(&group);
        front.sort_by(|a, c| a.time_ms.total_cmp(&c.time_ms));
        let pts: Vec<(f64, f64)> = front.iter().map(|r| area.at(r)).collect();
        if pts.len() > 1 {
            svg.polyline(
                &pts,
                &format!(r#"stroke="{}" stroke-width="1.5" stroke-opacity="0.8""#, colour(b)),
            );
        }
        on_front.extend(front);
    }
    on_front
}

/// The rule of the page's suggestion: a dashed line at the bound, a ring round each back
/// end's suggested setting.
fn draw_rule(svg: &mut Svg, area: &PlotArea, backends: &[&str], drawable: &[&Row]) {
    let rule = drawable.first().and_then(|r| good_enough(r.error_metric));
    if let (Some((bound, _)), Some(y)) = (rule, &area.y)
        && (y.lo..=y.hi).contains(&bound.log10())
    {
        let py = y.at(bound);
        svg.line(
            (area.left, py),
            (area.right, py),
            &format!(r#"stroke="{GOOD}" stroke-width="1.2" stroke-dasharray="5 4""#),
        );
        svg.text_styled(
            (area.left + 4.0, py - 4.0),
            9.5,
            Anchor::Start,
            &format!("good enough: ≤ {}", tick_text(bound)),
            &format!(r#"fill="{GOOD}""#),
        );
    }
    if rule.is_some() {
        for b in backends {
            let group: Vec<&Row> = drawable.iter().copied().filter(|r| r.backend == *b).collect();
            if let Some(s) = suggestion(&group) {
                svg.circle(
                    area.at(s),
                    8.5,
                    &format!(r#"fill="none" stroke="{GOOD}" stroke-width="2""#),
                );
            }
        }
    }
}

/// A point's label: its setting (with its back end where the panel has several).
fn label_text(r: &Row, several_backends: bool) -> String {
    // A long setting keeps its name without the details in brackets (the knob's table
    // has them): "projected_grid 8 px (21600 vertices; …)" → "projected_grid 8 px".
    let name = match r.setting.split_once(" (") {
        Some((short, _)) if text_width(&r.setting, LABEL) > 150.0 => short,
        _ => r.setting.as_str(),
    };
    if several_backends { format!("{name} ({})", r.backend) } else { name.to_string() }
}

/// The box a label of width `tw` takes at `(tx, ty)` with its anchor.
fn label_box((tx, ty, a): Placed, tw: f64) -> Boxed {
    let x0 = match a {
        Anchor::Start => tx,
        Anchor::Middle => tx - tw / 2.0,
        Anchor::End => tx - tw,
    };
    (x0, ty - LABEL * 0.8, x0 + tw, ty + LABEL * 0.25)
}

/// A label's place: its anchor point and anchor.
type Placed = (f64, f64, Anchor);

/// The place of a label of width `tw` for the point at `(px, py)`: the first free one in a
/// list nearest first, else the one least covered by `taken` and the outside of the area.
fn place_label(area: &PlotArea, taken: &[Boxed], (px, py): (f64, f64), tw: f64) -> Placed {
    let candidates = [
        (px + 7.0, py + 3.5, Anchor::Start),
        (px - 7.0, py + 3.5, Anchor::End),
        (px, py - 8.0, Anchor::Middle),
        (px, py + 15.0, Anchor::Middle),
        (px + 6.0, py - 7.0, Anchor::Start),
        (px + 6.0, py + 13.0, Anchor::Start),
        (px - 6.0, py - 7.0, Anchor::End),
        (px - 6.0, py + 13.0, Anchor::End),
        // Further out, joined to the point by a leader line.
        (px + 14.0, py - 14.0, Anchor::Start),
        (px + 14.0, py + 20.0, Anchor::Start),
        (px - 14.0, py - 14.0, Anchor::End),
        (px - 14.0, py + 20.0, Anchor::End),
        (px + 24.0, py - 26.0, Anchor::Start),
        (px + 24.0, py + 32.0, Anchor::Start),
        (px - 24.0, py - 26.0, Anchor::End),
        (px - 24.0, py + 32.0, Anchor::End),
    ];
    let cost = |c: Placed| -> f64 {
        let b = label_box(c, tw);
        let outside = (area.left - b.0).max(0.0)
            + (b.2 - area.right).max(0.0)
            + (area.top - b.1).max(0.0)
            + (b.3 - area.bottom).max(0.0);
        taken.iter().map(|t| overlap(*t, b)).sum::<f64>() + 50.0 * outside
    };
    candidates
        .iter()
        .copied()
        .enumerate()
        .min_by(|(i, a), (j, b)| {
            (cost(*a), *i).partial_cmp(&(cost(*b), *j)).unwrap_or(std::cmp::Ordering::Equal)
        })
        .map_or(candidates[0], |(_, c)| c)
}

/// Setting `r`'s label at the free place nearest its point (added to `taken`), joined to the
/// point by a leader line where it had to go further out.
fn draw_label(
    svg: &mut Svg,
    area: &PlotArea,
    taken: &mut Vec<Boxed>,
    r: &Row,
    several_backends: bool,
    on_front: bool,
) {
    let (px, py) = area.at(r);
    let text = label_text(r, several_backends);
    let tw = text_width(&text, LABEL);
    let best = place_label(area, taken, (px, py), tw);
    let b = label_box(best, tw);
    taken.push(b);
    if (best.1 - py).abs() > 16.0 {
        let end_x = match best.2 {
            Anchor::Start => b.0,
            Anchor::End => b.2,
            Anchor::Middle => (b.0 + b.2) / 2.0,
        };
        let end_y = if best.1 < py { b.3 } else { b.1 };
        svg.line((px, py), (end_x, end_y), r##"stroke="#999999" stroke-width="0.7""##);
    }
    let fill = if on_front { "#111111" } else { "#8a8a8a" };
    svg.text_styled((best.0, best.1), LABEL, best.2, &text, &format!(r#"fill="{fill}""#));
}
