//! `report --svg`: grouped bar charts, written as SVG text.
//!
//! One chart of storage (bytes per simplex; a group per dataset, a bar per structure, linear
//! scale), then one chart of times per dataset (a group per relation family plus the build
//! time per simplex, a bar per structure, log scale since structures differ by orders of
//! magnitude). Every bar carries its value as a label and as a hover title; a structure that
//! cannot encode a dataset gets a grey "n/a" instead of a bar.

use std::fmt::Write as _;

use super::Dataset;
use super::timing::Family;

/// One color per structure (Tableau 10), in [`topoplex::StructureKind::NAMED`] order.
const COLORS: [&str; 10] = [
    "#4e79a7", "#f28e2b", "#e15759", "#76b7b2", "#59a14f", "#edc948", "#b07aa1", "#ff9da7",
    "#9c755f", "#bab0ac",
];

const PLOT_H: f64 = 260.0;
const LEFT: f64 = 80.0;
const TOP: f64 = 56.0;
const BOTTOM: f64 = 60.0;
const LEGEND_W: f64 = 110.0;

struct Chart {
    title: String,
    subtitle: String,
    y_label: String,
    groups: Vec<String>,
    series: Vec<String>,
    /// `values[group][series]`; `None`: no bar (shown as n/a).
    values: Vec<Vec<Option<f64>>>,
    log: bool,
}

fn esc(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

/// A dataset's short name for a group label: the file name, shortened.
fn short(name: &str) -> String {
    let base = std::path::Path::new(name)
        .file_name()
        .map_or(name.to_string(), |f| f.to_string_lossy().into_owned());
    if base.chars().count() > 24 {
        base.chars().take(23).collect::<String>() + "…"
    } else {
        base
    }
}

fn fmt_value(v: f64) -> String {
    if v >= 100.0 {
        format!("{v:.0}")
    } else if v >= 10.0 {
        format!("{v:.1}")
    } else {
        format!("{v:.2}")
    }
}

/// A "nice" tick step (1, 2 or 5 × 10^k) for about five ticks up to `max`.
fn nice_step(max: f64) -> f64 {
    let raw = max / 5.0;
    let mag = 10f64.powf(raw.log10().floor());
    let f = raw / mag;
    mag * if f <= 1.0 {
        1.0
    } else if f <= 2.0 {
        2.0
    } else if f <= 5.0 {
        5.0
    } else {
        10.0
    }
}

impl Chart {
    fn width(&self) -> f64 {
        let per_group = (self.series.len() as f64 * 16.0 + 24.0).max(90.0);
        (LEFT + self.groups.len() as f64 * per_group + LEGEND_W + 20.0).max(720.0)
    }

    fn height(&self) -> f64 {
        TOP + PLOT_H + BOTTOM
    }

    /// Draws the chart with its top-left corner at (0, `y0`).
    fn draw(&self, s: &mut String, y0: f64) {
        let plot_w = self.width() - LEFT - LEGEND_W - 20.0;
        let base = y0 + TOP + PLOT_H;
        let scale = self.scale();
        self.draw_titles(s, y0);
        self.draw_axes(s, &scale, plot_w, base);
        self.draw_bars(s, &scale, plot_w, base);
        self.draw_legend(s, y0);
    }

    /// The y axis for the chart's positive finite values: from 0 to a nice step above the
    /// largest, or log from the decade below the smallest to the decade above the largest.
    fn scale(&self) -> Scale {
        let all: Vec<f64> = self
            .values
            .iter()
            .flatten()
            .flatten()
            .copied()
            .filter(|v| v.is_finite() && *v > 0.0)
            .collect();
        let max = all.iter().copied().fold(0.0f64, f64::max);
        let (lo, hi, ticks): (f64, f64, Vec<f64>) = if self.log {
            let min = all.iter().copied().fold(f64::INFINITY, f64::min);
            let (lo, hi) = if all.is_empty() {
                (0.0, 1.0)
            } else {
                (
                    min.log10().floor(),
                    max.log10().ceil().max(min.log10().floor() + 1.0),
                )
            };
            let ticks = (lo as i32..=hi as i32).map(|e| 10f64.powi(e)).collect();
            (lo, hi, ticks)
        } else {
            let step = if max > 0.0 { nice_step(max) } else { 1.0 };
            let hi = (max / step).ceil().max(1.0) * step;
            let n = (hi / step).round() as usize;
            (0.0, hi, (0..=n).map(|i| i as f64 * step).collect())
        };
        Scale {
            log: self.log,
            lo,
            hi,
            ticks,
        }
    }

    /// The title and subtitle above the plot.
    fn draw_titles(&self, s: &mut String, y0: f64) {
        let _ = writeln!(
            s,
            r#"<text x="{}" y="{}" font-size="16" font-weight="bold">{}</text>"#,
            LEFT,
            y0 + 24.0,
            esc(&self.title)
        );
        let _ = writeln!(
            s,
            r##"<text x="{}" y="{}" font-size="11" fill="#555">{}</text>"##,
            LEFT,
            y0 + 40.0,
            esc(&self.subtitle)
        );
    }

    /// Axes, grid and ticks, and the y label.
    fn draw_axes(&self, s: &mut String, scale: &Scale, plot_w: f64, base: f64) {
        for &t in &scale.ticks {
            let y = base - scale.height(t);
            let _ = writeln!(
                s,
                r##"<line x1="{LEFT}" y1="{y:.1}" x2="{:.1}" y2="{y:.1}" stroke="#ddd"/><text x="{}" y="{:.1}" font-size="11" text-anchor="end">{}</text>"##,
                LEFT + plot_w,
                LEFT - 6.0,
                y + 4.0,
                if t >= 1.0 || t == 0.0 {
                    format!("{t}")
                } else {
                    format!("{t:e}")
                }
            );
        }
        let _ = writeln!(
            s,
            r##"<line x1="{LEFT}" y1="{:.1}" x2="{LEFT}" y2="{base:.1}" stroke="#333"/><line x1="{LEFT}" y1="{base:.1}" x2="{:.1}" y2="{base:.1}" stroke="#333"/>"##,
            base - PLOT_H,
            LEFT + plot_w
        );
        let _ = writeln!(
            s,
            r#"<text transform="translate({:.1},{:.1}) rotate(-90)" font-size="12" text-anchor="middle">{}</text>"#,
            LEFT - 52.0,
            base - PLOT_H / 2.0,
            esc(&self.y_label)
        );
    }

    /// A group of bars per group, its label under it.
    fn draw_bars(&self, s: &mut String, scale: &Scale, plot_w: f64, base: f64) {
        let gw = plot_w / self.groups.len().max(1) as f64;
        let inner = gw * 0.8;
        let bw = inner / self.series.len().max(1) as f64;
        for (g, name) in self.groups.iter().enumerate() {
            let gx = LEFT + g as f64 * gw + gw * 0.1;
            let _ = writeln!(
                s,
                r#"<text x="{:.1}" y="{:.1}" font-size="12" text-anchor="middle">{}</text>"#,
                gx + inner / 2.0,
                base + 18.0,
                esc(name)
            );
            for (k, series) in self.series.iter().enumerate() {
                let x = gx + k as f64 * bw;
                let bar = Bar {
                    x,
                    width: bw,
                    base,
                    color: COLORS[k % COLORS.len()],
                    series,
                    group: name,
                };
                match self.values[g][k] {
                    Some(v) if v.is_finite() && v > 0.0 => bar.draw(s, v, scale.height(v)),
                    _ => bar.draw_missing(s),
                }
            }
        }
    }

    /// A coloured square and the name of every series, right of the plot.
    fn draw_legend(&self, s: &mut String, y0: f64) {
        let lx = self.width() - LEGEND_W;
        for (k, series) in self.series.iter().enumerate() {
            let ly = y0 + TOP + k as f64 * 18.0;
            let _ = writeln!(
                s,
                r#"<rect x="{lx:.1}" y="{ly:.1}" width="12" height="12" fill="{}"/><text x="{:.1}" y="{:.1}" font-size="12">{}</text>"#,
                COLORS[k % COLORS.len()],
                lx + 18.0,
                ly + 10.5,
                esc(series)
            );
        }
    }
}

/// A chart's y axis: linear or log from `lo` to `hi` (decades when log), with its ticks.
struct Scale {
    log: bool,
    lo: f64,
    hi: f64,
    ticks: Vec<f64>,
}

impl Scale {
    /// The pixel height of `v` above the axis.
    fn height(&self, v: f64) -> f64 {
        let t = if self.log {
            (v.log10() - self.lo) / (self.hi - self.lo)
        } else {
            (v - self.lo) / (self.hi - self.lo)
        };
        t.clamp(0.0, 1.0) * PLOT_H
    }
}

/// One bar's place: left edge `x`, `width`, the axis at `base`, and what it shows.
struct Bar<'a> {
    x: f64,
    width: f64,
    base: f64,
    color: &'a str,
    series: &'a str,
    group: &'a str,
}

impl Bar<'_> {
    /// The bar of value `v`, `h` pixels high (at least 1), with its value as a label and title.
    fn draw(&self, s: &mut String, v: f64, h: f64) {
        let (x, base) = (self.x, self.base);
        let cx = x + self.width / 2.0;
        let h = h.max(1.0);
        let _ = writeln!(
            s,
            r#"<rect x="{x:.1}" y="{:.1}" width="{:.1}" height="{h:.1}" fill="{}"><title>{} — {}: {}</title></rect>"#,
            base - h,
            (self.width - 1.0).max(1.0),
            self.color,
            esc(self.series),
            esc(self.group),
            fmt_value(v)
        );
        let _ = writeln!(
            s,
            r##"<text transform="translate({:.1},{:.1}) rotate(-90)" font-size="9" fill="#333">{}</text>"##,
            cx + 3.0,
            base - h - 3.0,
            fmt_value(v)
        );
    }

    /// A grey "n/a" where the structure has no value.
    fn draw_missing(&self, s: &mut String) {
        let cx = self.x + self.width / 2.0;
        let _ = writeln!(
            s,
            r##"<text transform="translate({:.1},{:.1}) rotate(-90)" font-size="9" fill="#999"><title>{} — {}: not available</title>n/a</text>"##,
            cx + 3.0,
            self.base - 3.0,
            esc(self.series),
            esc(self.group)
        );
    }
}

fn charts(datasets: &[Dataset]) -> Vec<Chart> {
    let series: Vec<String> = datasets
        .first()
        .map(|d| {
            d.structures
                .iter()
                .map(|r| r.kind.name().to_string())
                .collect()
        })
        .unwrap_or_default();
    let mut out = vec![Chart {
        title: "Storage: heap bytes per simplex".into(),
        subtitle: "heap bytes of the built structure / number of simplices (all dimensions); n/a: cannot encode".into(),
        y_label: "bytes per simplex".into(),
        groups: datasets.iter().map(|d| short(&d.name)).collect(),
        series: series.clone(),
        values: datasets
            .iter()
            .map(|d| {
                d.structures
                    .iter()
                    .map(|r| r.outcome.as_ref().ok().map(|m| m.bytes_per_simplex))
                    .collect()
            })
            .collect(),
        log: false,
    }];
    for d in datasets {
        let mut groups: Vec<String> = vec!["build (ns per simplex)".into()];
        groups.extend(Family::ALL.iter().map(|f| {
            match f {
                Family::Boundary => "boundary",
                Family::Coboundary => "co-boundary",
                Family::AdjacencyVertex => "adjacency (vertex)",
                Family::AdjacencyTop => "adjacency (top)",
            }
            .to_string()
        }));
        let mut values = vec![
            d.structures
                .iter()
                .map(|r| r.outcome.as_ref().ok().map(|m| m.build_ns_per_simplex))
                .collect::<Vec<_>>(),
        ];
        for f in Family::ALL {
            values.push(
                d.structures
                    .iter()
                    .map(|r| {
                        r.outcome.as_ref().ok().and_then(|m| {
                            m.families
                                .iter()
                                .find(|t| t.family == f)
                                .and_then(|t| t.ns_per_element)
                        })
                    })
                    .collect(),
            );
        }
        out.push(Chart {
            title: format!(
                "Time on {} (ns per retrieved element, log scale)",
                short(&d.name)
            ),
            subtitle: super::render::sample_text(d),
            y_label: "ns per element".into(),
            groups,
            series: series.clone(),
            values,
            log: true,
        });
    }
    out
}

/// The whole SVG document.
pub fn svg(datasets: &[Dataset]) -> String {
    let charts = charts(datasets);
    let width = charts.iter().map(Chart::width).fold(0.0, f64::max);
    let height: f64 = charts.iter().map(Chart::height).sum();
    let mut s = String::new();
    let _ = writeln!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{width:.0}" height="{height:.0}" viewBox="0 0 {width:.0} {height:.0}" font-family="sans-serif">"#
    );
    let _ = writeln!(s, r#"<rect width="100%" height="100%" fill="white"/>"#);
    let mut y = 0.0;
    for c in &charts {
        c.draw(&mut s, y);
        y += c.height();
    }
    s.push_str("</svg>\n");
    s
}
