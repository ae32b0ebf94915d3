//! Minimal plotting: line and scatter series on linear or log axes, written as SVG and rendered to PNG.
//!
//! Kept by hand rather than moved to `plotters`: the report needs log axes, dashed series, a legend
//! outside the data and byte-stable SVG (a regenerated report diffs only where numbers changed); this
//! module does that in 250 lines with no font or backend dependency of its own, and `resvg` (already
//! here for the PNGs) renders the same SVG the Markdown links. Every axis label carries its unit.
// The SVG templates are multi-line raw strings that end in a newline; `write!` is what they need.
#![allow(clippy::write_with_newline)]

use std::fmt::Write as _;
use std::path::Path;

/// One axis.
#[derive(Clone, Copy)]
pub struct Axis {
    pub label: &'static str,
    pub log: bool,
}

/// One series: points, drawn as a line, markers or both.
pub struct Series {
    pub name: String,
    pub points: Vec<(f64, f64)>,
    pub line: bool,
    pub marker: bool,
    pub dashed: bool,
    /// The palette entry to draw it in (`None`: its place in the list; past the palette, dashed with square
    /// markers): series that belong together share one.
    pub colour: Option<usize>,
}

impl Series {
    pub fn line(name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Self {
            name: name.into(),
            points,
            line: true,
            marker: false,
            dashed: false,
            colour: None,
        }
    }
    /// Markers only, no line.
    pub fn markers(name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Self {
            name: name.into(),
            points,
            line: false,
            marker: true,
            dashed: false,
            colour: None,
        }
    }
    pub fn both(name: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Self {
            name: name.into(),
            points,
            line: true,
            marker: true,
            dashed: false,
            colour: None,
        }
    }
    pub fn dashed(mut self) -> Self {
        self.dashed = true;
        self
    }
    /// Drawn in the palette's entry `i` (modulo its length), whatever its place in the list.
    pub fn colour(mut self, i: usize) -> Self {
        self.colour = Some(i);
        self
    }
}

const COLORS: [&str; 12] = [
    "#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd", "#8c564b", "#e377c2", "#17becf",
    "#7f7f7f", "#bcbd22", "#000000", "#aec7e8",
];

fn fwd(v: f64, log: bool) -> Option<f64> {
    if log {
        (v > 0.0 && v.is_finite()).then(|| v.log10())
    } else {
        v.is_finite().then_some(v)
    }
}

fn tick_label(v: f64, log: bool) -> String {
    if log {
        format!("1e{}", v.round() as i64)
    } else if v.abs() >= 1e4 || (v != 0.0 && v.abs() < 1e-2) {
        format!("{v:.1e}")
    } else {
        format!("{}", (v * 1000.0).round() / 1000.0)
    }
}

/// Writes `name.svg` and `name.png` in `dir`.
pub fn plot(
    dir: &Path,
    name: &str,
    title: &str,
    x: Axis,
    y: Axis,
    series: &[Series],
) -> std::io::Result<()> {
    // The legend sits right of the plot area, never over the data: wide enough for the longest name
    // (about 7.3 px per character at 13 px), tall enough for every entry.
    let longest = series
        .iter()
        .map(|s| s.name.chars().count())
        .max()
        .unwrap_or(0) as f64;
    let r = (56.0 + 7.3 * longest).max(300.0);
    let (l, t, b) = (80.0, 40.0, 60.0);
    let w = 760.0 + l + r;
    let h = (t + b + 20.0 + 18.0 * series.len() as f64).max(560.0);
    let pts: Vec<(f64, f64)> = series
        .iter()
        .flat_map(|s| s.points.iter())
        .filter_map(|&(a, c)| Some((fwd(a, x.log)?, fwd(c, y.log)?)))
        .collect();
    let (mut x0, mut x1, mut y0, mut y1) = pts.iter().fold(
        (
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        ),
        |(a, b, c, d), &(px, py)| (a.min(px), b.max(px), c.min(py), d.max(py)),
    );
    if !x0.is_finite() {
        (x0, x1, y0, y1) = (0.0, 1.0, 0.0, 1.0);
    }
    if x.log {
        x0 = x0.floor();
        x1 = x1.ceil().max(x0 + 1.0);
    }
    if y.log {
        y0 = y0.floor();
        y1 = y1.ceil().max(y0 + 1.0);
    }
    if x1 <= x0 {
        x1 = x0 + 1.0;
    }
    if y1 <= y0 {
        y1 = y0 + 1.0;
    }
    let px = |v: f64| l + (v - x0) / (x1 - x0) * (w - l - r);
    let py = |v: f64| h - b - (v - y0) / (y1 - y0) * (h - t - b);
    let mut s = String::new();
    let _ = write!(
        s,
        r#"<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}" font-family="DejaVu Sans" font-size="13">
<rect width="100%" height="100%" fill="white"/>
<text x="{}" y="24" font-size="16" text-anchor="middle">{}</text>
"#,
        (l + w - r) / 2.0,
        xml(title)
    );
    // Grid and ticks.
    let ticks = |a: f64, c: f64, log: bool| -> Vec<f64> {
        if log {
            let step = ((c - a) / 8.0).ceil().max(1.0);
            let mut v = a;
            let mut out = Vec::new();
            while v <= c + 1e-9 {
                out.push(v);
                v += step;
            }
            out
        } else {
            (0..=5).map(|i| a + (c - a) * i as f64 / 5.0).collect()
        }
    };
    for v in ticks(x0, x1, x.log) {
        let label = tick_label(v, x.log);
        grid_tick(
            &mut s,
            [px(v), t, px(v), h - b],
            (px(v), h - b + 18.0),
            "middle",
            &label,
        );
    }
    for v in ticks(y0, y1, y.log) {
        let label = tick_label(v, y.log);
        grid_tick(
            &mut s,
            [l, py(v), w - r, py(v)],
            (l - 6.0, py(v) + 4.0),
            "end",
            &label,
        );
    }
    let _ = write!(
        s,
        r##"<rect x="{l}" y="{t}" width="{}" height="{}" fill="none" stroke="#333"/>
<text x="{}" y="{}" text-anchor="middle">{}</text>
<text x="18" y="{}" text-anchor="middle" transform="rotate(-90 18 {})">{}</text>
"##,
        w - l - r,
        h - t - b,
        (l + w - r) / 2.0,
        h - 18.0,
        xml(x.label),
        (t + h - b) / 2.0,
        (t + h - b) / 2.0,
        xml(y.label)
    );
    for (i, se) in series.iter().enumerate() {
        let c = COLORS[se.colour.unwrap_or(i) % COLORS.len()];
        // Past the palette (a series without a colour of its own): the same colours again, dashed with
        // square markers.
        let second_round = se.colour.is_none() && i >= COLORS.len();
        let p: Vec<(f64, f64)> = se
            .points
            .iter()
            .filter_map(|&(a, d)| Some((px(fwd(a, x.log)?), py(fwd(d, y.log)?))))
            .collect();
        if se.line && p.len() > 1 {
            let d: Vec<String> = p.iter().map(|(a, b)| format!("{a:.1},{b:.1}")).collect();
            let dash = if se.dashed || second_round {
                r#" stroke-dasharray="6 4""#
            } else {
                ""
            };
            let _ = writeln!(
                s,
                r#"<polyline points="{}" fill="none" stroke="{c}" stroke-width="1.8"{dash}/>"#,
                d.join(" ")
            );
        }
        if se.marker {
            for &(a, b) in &p {
                marker(&mut s, a, b, c, second_round);
            }
        }
        // The legend entry draws the series as it is drawn: its dash and its marker.
        let ly = t + 12.0 + 18.0 * i as f64;
        let (x0, x1) = (w - r + 10.0, w - r + 34.0);
        let dash = if se.dashed || second_round {
            r#" stroke-dasharray="6 4""#
        } else {
            ""
        };
        if se.line {
            let _ = writeln!(
                s,
                r#"<line x1="{x0}" y1="{ly}" x2="{x1}" y2="{ly}" stroke="{c}" stroke-width="2.4"{dash}/>"#
            );
        }
        if se.marker || !se.line {
            marker(&mut s, 0.5 * (x0 + x1), ly, c, second_round);
        }
        let _ = writeln!(
            s,
            r#"<text x="{}" y="{}">{}</text>"#,
            x1 + 8.0,
            ly + 4.5,
            xml(&se.name)
        );
    }
    s.push_str("</svg>\n");
    std::fs::write(dir.join(format!("{name}.svg")), &s)?;
    png(&s, &dir.join(format!("{name}.png")))
}

/// A point's marker at `(x, y)`: a square for a series on the second round of colours, else a dot.
fn marker(s: &mut String, x: f64, y: f64, colour: &str, square: bool) {
    if square {
        let _ = writeln!(
            s,
            r#"<rect x="{:.1}" y="{:.1}" width="6.4" height="6.4" fill="{colour}"/>"#,
            x - 3.2,
            y - 3.2
        );
    } else {
        let _ = writeln!(
            s,
            r#"<circle cx="{x:.1}" cy="{y:.1}" r="3.2" fill="{colour}"/>"#
        );
    }
}

/// One tick of an axis: its grid line `[x1, y1, x2, y2]` and its label at `(x, y)`, anchored `anchor`.
fn grid_tick(s: &mut String, line: [f64; 4], at: (f64, f64), anchor: &str, label: &str) {
    let [x1, y1, x2, y2] = line;
    let (x, y) = at;
    let _ = writeln!(
        s,
        r##"<line x1="{x1}" y1="{y1}" x2="{x2}" y2="{y2}" stroke="#ddd"/><text x="{x}" y="{y}" text-anchor="{anchor}">{label}</text>"##
    );
}

fn xml(t: &str) -> String {
    t.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// The system's fonts, loaded once per process (every plot's text uses them).
fn fonts() -> std::sync::Arc<resvg::usvg::fontdb::Database> {
    static FONTS: std::sync::OnceLock<std::sync::Arc<resvg::usvg::fontdb::Database>> =
        std::sync::OnceLock::new();
    FONTS
        .get_or_init(|| {
            let mut db = resvg::usvg::fontdb::Database::new();
            db.load_system_fonts();
            std::sync::Arc::new(db)
        })
        .clone()
}

/// Renders an SVG document to a PNG file at `path`, its text in the system's fonts.
pub fn png(svg: &str, path: &Path) -> std::io::Result<()> {
    use resvg::{tiny_skia, usvg};
    let opt = usvg::Options {
        fontdb: fonts(),
        ..usvg::Options::default()
    };
    let tree = usvg::Tree::from_str(svg, &opt).map_err(|e| std::io::Error::other(e.to_string()))?;
    let size = tree.size().to_int_size();
    let mut pix = tiny_skia::Pixmap::new(size.width(), size.height())
        .ok_or_else(|| std::io::Error::other("empty plot"))?;
    resvg::render(&tree, tiny_skia::Transform::default(), &mut pix.as_mut());
    pix.save_png(path)
        .map_err(|e| std::io::Error::other(e.to_string()))
}
