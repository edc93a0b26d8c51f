//! Timing diagrams: a recorder fed one row of values per cycle, drawn as
//! SVG with one trace row per variable under a common time axis.
//!
//! BOOL values are logic lines (high / low, the high level shaded);
//! numbers (integers, reals, TIME) are step lines scaled between the
//! variable's smallest and largest value, with the value written at each
//! change where there is room for it before the next change; strings,
//! enumerations and other values are labelled segments (a "bus" line with a
//! cross at each change). Spans where a variable was forced get a red
//! background. The time axis is the cycles' clock times with 1-2-5 (or
//! seconds / minutes / hours) ticks.
//!
//! Memory: only changes are kept (a value that holds for a million cycles
//! costs one entry). After [`MAX_CHANGES`] changes in all the recorder
//! stops recording; [`TimingDiagram::stopped_at`] says at which cycle and
//! the picture ends there with a note saying so: nothing is dropped
//! silently.

use super::svg_writer::{Element, SvgWriter};
use crate::runtime::engine::Plc;
use crate::runtime::names::VarRef;
use crate::runtime::plc_value::Value;
use crate::runtime::var_error::VarError;
use crate::value::literal::format_duration;

/// The most value changes a [`TimingDiagram`] keeps (all variables
/// together); a picture with more would not be readable anyway.
pub const MAX_CHANGES: usize = 100_000;

const CHAR_W: f64 = 7.2;
const PLOT_W: f64 = 960.0;
const MARGIN: f64 = 16.0;
const ROW_GAP: f64 = 10.0;
const TOP: f64 = 40.0;

/// One change of one variable.
#[derive(Debug, Clone, PartialEq)]
struct Change {
    time: i64,
    value: Value,
    forced: bool,
}

/// How a variable is drawn, from its first value.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Kind {
    Logic,
    Number,
    Label,
}

fn kind_of(v: &Value) -> Kind {
    match v {
        Value::Scalar(crate::elementary::ElemType::Bool, _) => Kind::Logic,
        Value::Scalar(
            crate::elementary::ElemType::Real | crate::elementary::ElemType::Lreal,
            _,
        ) => Kind::Number,
        v if number(v).is_some() => Kind::Number,
        _ => Kind::Label,
    }
}

fn number(v: &Value) -> Option<f64> {
    match v {
        // NaN and infinities have no place on the scale: drawn mid-row.
        Value::Scalar(..) => v
            .as_f64()
            .or_else(|| v.to_literal().parse().ok())
            .filter(|x: &f64| x.is_finite()),
        _ => None,
    }
}

/// Records the values of some variables cycle by cycle and draws them as
/// a timing diagram.
///
/// ```
/// use plcrun::{Options, Plc, TimingDiagram};
///
/// let src = "PROGRAM p VAR_OUTPUT q : BOOL; n : INT; END_VAR q := NOT q; n := n + 1; END_PROGRAM";
/// let mut plc = Plc::compile_files(&[("p.st", src)], &Options::default())?;
/// let mut diagram = TimingDiagram::for_plc(&plc, &["q", "n"])?;
/// for _ in 0..10 {
///     plc.run_cycle()?;
///     diagram.record(&plc);
/// }
/// diagram.set_end(plc.time());
/// let svg = diagram.to_svg();
/// assert!(svg.contains("data-name=\"q\""));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone)]
pub struct TimingDiagram {
    names: Vec<String>,
    refs: Vec<VarRef>,
    signals: Vec<Vec<Change>>,
    first: Option<(u64, i64)>,
    last: Option<(u64, i64)>,
    step: i64,
    end: Option<i64>,
    changes: usize,
    stopped_at: Option<u64>,
}

impl TimingDiagram {
    /// A diagram of the variables `names`, fed with [`Self::push_row`].
    pub fn new<S: AsRef<str>>(names: &[S]) -> TimingDiagram {
        TimingDiagram {
            names: names.iter().map(|s| s.as_ref().to_string()).collect(),
            refs: Vec::new(),
            signals: vec![Vec::new(); names.len()],
            first: None,
            last: None,
            step: 0,
            end: None,
            changes: 0,
            stopped_at: None,
        }
    }

    /// A diagram of the variables `names` of `plc` (named as with
    /// `--trace`), fed with [`Self::record`] after each cycle.
    pub fn for_plc<S: AsRef<str>>(plc: &Plc, names: &[S]) -> Result<TimingDiagram, VarError> {
        let mut d = TimingDiagram::new(names);
        d.refs = names
            .iter()
            .map(|n| plc.resolve(n.as_ref()))
            .collect::<Result<_, _>>()?;
        Ok(d)
    }

    /// The variables' names, one trace row each.
    pub fn names(&self) -> &[String] {
        &self.names
    }

    /// Records the values of the cycle `plc` just ran (for a diagram made
    /// by [`Self::for_plc`]). A variable that can no longer be read (after
    /// an online change removed it) is looked up again by name, and keeps
    /// its last value when it is gone.
    pub fn record(&mut self, plc: &Plc) {
        let mut values = Vec::with_capacity(self.refs.len());
        let mut forced = Vec::with_capacity(self.refs.len());
        for (i, r) in self.refs.iter_mut().enumerate() {
            let value = match plc.get(r) {
                Ok(v) => Some(v),
                Err(_) => match plc.resolve(&self.names[i]) {
                    Ok(fresh) => {
                        *r = fresh;
                        plc.get(r).ok()
                    }
                    Err(_) => None,
                },
            };
            let last = self.signals[i].last().map(|c| c.value.clone());
            match value.or(last) {
                Some(v) => values.push(v),
                None => values.push(Value::String(String::from("?"), false)),
            }
            forced.push(plc.is_forced(r));
        }
        let cycle = plc.cycle().saturating_sub(1);
        self.push_row(cycle, plc.last_cycle_time(), &values, &forced);
    }

    /// Records the row of cycle `cycle` at clock `time_ns`: one value per
    /// name (missing values keep the previous one), and which were forced
    /// (an empty slice: none). Rows must come in time order.
    pub fn push_row(&mut self, cycle: u64, time_ns: i64, values: &[Value], forced: &[bool]) {
        if self.stopped_at.is_some() {
            return;
        }
        if let Some((_, t)) = self.last {
            self.step = time_ns - t;
        }
        self.first.get_or_insert((cycle, time_ns));
        let mut new = 0;
        for (i, v) in values.iter().enumerate().take(self.signals.len()) {
            let f = forced.get(i).copied().unwrap_or(false);
            let same = self.signals[i]
                .last()
                .is_some_and(|c| c.value == *v && c.forced == f);
            if !same {
                new += 1;
            }
        }
        if self.changes + new > MAX_CHANGES {
            self.stopped_at = Some(cycle);
            self.end = Some(time_ns);
            return;
        }
        for (i, v) in values.iter().enumerate().take(self.signals.len()) {
            let f = forced.get(i).copied().unwrap_or(false);
            let same = self.signals[i]
                .last()
                .is_some_and(|c| c.value == *v && c.forced == f);
            if !same {
                self.signals[i].push(Change {
                    time: time_ns,
                    value: v.clone(),
                    forced: f,
                });
            }
        }
        self.changes += new;
        self.last = Some((cycle, time_ns));
    }

    /// Sets where the time axis ends (the clock after the last cycle);
    /// without it, the last row lasts as long as the one before it.
    pub fn set_end(&mut self, time_ns: i64) {
        if self.stopped_at.is_none() {
            self.end = Some(time_ns);
        }
    }

    /// The cycle at which recording stopped because the diagram held
    /// [`MAX_CHANGES`] changes, if it did.
    pub fn stopped_at(&self) -> Option<u64> {
        self.stopped_at
    }

    /// Number of value changes recorded.
    pub fn changes(&self) -> usize {
        self.changes
    }

    /// The diagram as an SVG document.
    pub fn to_svg(&self) -> String {
        draw(self)
    }
}

/// The time span shown and the mapping of times to x.
struct Axis {
    t0: i64,
    t1: i64,
    left: f64,
}

impl Axis {
    fn x(&self, t: i64) -> f64 {
        let span = (self.t1 - self.t0).max(1) as f64;
        self.left + (t - self.t0) as f64 / span * PLOT_W
    }
}

/// The tick distance: the smallest "round" duration giving ticks at least
/// about 90 px apart.
fn tick_step(span: i64) -> i64 {
    const MS: i64 = 1_000_000;
    const S: i64 = 1_000 * MS;
    let want = (span as f64 * 90.0 / PLOT_W).max(1.0) as i64;
    let mut candidates = Vec::new();
    let mut p: i64 = 1;
    while p < S {
        candidates.extend([p, 2 * p, 5 * p]);
        p *= 10;
    }
    for base in [S, 60 * S, 3600 * S] {
        candidates.extend([1, 2, 5, 10, 15, 30].map(|k| k * base));
    }
    let day = 24 * 3600 * S;
    candidates.extend([day / 2, day]);
    candidates
        .into_iter()
        .find(|&c| c >= want)
        .unwrap_or_else(|| (want / day + 1) * day)
}

fn row_height(kind: Kind) -> f64 {
    match kind {
        Kind::Number => 36.0,
        _ => 24.0,
    }
}

fn draw(d: &TimingDiagram) -> String {
    let (first_cycle, t0) = d.first.unwrap_or((0, 0));
    let last = d.last.map_or(t0, |(_, t)| t);
    let t1 = d.end.unwrap_or(last + d.step.max(1)).max(t0 + 1);
    let name_w = d.names.iter().map(|n| n.chars().count()).max().unwrap_or(1) as f64 * CHAR_W;
    let axis = Axis {
        t0,
        t1,
        left: MARGIN + name_w + 16.0,
    };
    let kinds: Vec<Kind> = d
        .signals
        .iter()
        .map(|s| s.first().map_or(Kind::Label, |c| kind_of(&c.value)))
        .collect();
    let rows_h: f64 = kinds.iter().map(|&k| row_height(k) + ROW_GAP).sum();
    let axis_y = TOP + rows_h + 4.0;
    let notes = usize::from(d.stopped_at.is_some())
        + usize::from(d.signals.iter().flatten().any(|c| c.forced));
    let height = axis_y + 40.0 + notes as f64 * 16.0 + MARGIN;
    let width = axis.left + PLOT_W + MARGIN + 40.0;
    let mut w = SvgWriter::new(width, height);
    let last_cycle = d.last.map_or(first_cycle, |(c, _)| c);
    let title = format!("Timing diagram, cycles {first_cycle} to {last_cycle}");
    w.text(Element::new("title"), &title);
    w.text(
        Element::new("text")
            .attr("class", "title")
            .num("x", MARGIN)
            .num("y", MARGIN + 8.0)
            .attr("font-weight", "bold"),
        &title,
    );
    draw_axis(&mut w, &axis, TOP - 6.0, axis_y);
    let mut y = TOP;
    for (i, name) in d.names.iter().enumerate() {
        let h = row_height(kinds[i]);
        draw_signal(&mut w, &axis, name, &d.signals[i], kinds[i], y, h);
        y += h + ROW_GAP;
    }
    let mut note_y = axis_y + 40.0;
    if d.signals.iter().flatten().any(|c| c.forced) {
        w.empty(
            Element::new("rect")
                .num("x", MARGIN)
                .num("y", note_y - 10.0)
                .num("width", 24.0)
                .num("height", 12.0)
                .attr("fill", "#ffc8c8"),
        );
        w.text(
            Element::new("text")
                .attr("class", "note")
                .num("x", MARGIN + 30.0)
                .num("y", note_y),
            "forced value",
        );
        note_y += 16.0;
    }
    if let Some(c) = d.stopped_at {
        w.text(
            Element::new("text")
                .attr("class", "note")
                .num("x", MARGIN)
                .num("y", note_y)
                .attr("fill", "#b00000"),
            &format!(
                "recording stopped at cycle {c}: {MAX_CHANGES} value changes reached (the trace has every value)"
            ),
        );
    }
    w.finish()
}

/// Ticks, their labels and light grid lines from `top` to `bottom`.
fn draw_axis(w: &mut SvgWriter, axis: &Axis, top: f64, bottom: f64) {
    let step = tick_step(axis.t1 - axis.t0);
    w.open(Element::new("g").attr("class", "axis"));
    w.empty(
        Element::new("line")
            .num("x1", axis.left)
            .num("y1", bottom)
            .num("x2", axis.left + PLOT_W)
            .num("y2", bottom)
            .attr("stroke", "black"),
    );
    // The first tick at or after t0, on a multiple of the step.
    let mut t = axis.t0.div_euclid(step) * step;
    if t < axis.t0 {
        t += step;
    }
    while t <= axis.t1 {
        let x = axis.x(t);
        let label = format_duration(t, "");
        w.open(
            Element::new("g")
                .attr("class", "tick")
                .attr("data-time", label.clone()),
        );
        w.empty(
            Element::new("line")
                .num("x1", x)
                .num("y1", top)
                .num("x2", x)
                .num("y2", bottom)
                .attr("stroke", "#dddddd"),
        );
        w.empty(
            Element::new("line")
                .num("x1", x)
                .num("y1", bottom)
                .num("x2", x)
                .num("y2", bottom + 5.0)
                .attr("stroke", "black"),
        );
        w.text(
            Element::new("text")
                .num("x", x)
                .num("y", bottom + 18.0)
                .attr("text-anchor", "middle"),
            &label,
        );
        w.close();
        t += step;
    }
    w.text(
        Element::new("text")
            .attr("class", "unit")
            .num("x", axis.left + PLOT_W)
            .num("y", bottom + 34.0)
            .attr("text-anchor", "end")
            .attr("fill", "#555555"),
        "time (cycle clock)",
    );
    w.close();
}

/// The spans of `changes`: (start x, end x, change).
fn spans<'a>(axis: &Axis, changes: &'a [Change]) -> Vec<(f64, f64, &'a Change)> {
    changes
        .iter()
        .enumerate()
        .map(|(i, c)| {
            let end = changes.get(i + 1).map_or(axis.t1, |n| n.time);
            (axis.x(c.time), axis.x(end), c)
        })
        .collect()
}

fn draw_signal(
    w: &mut SvgWriter,
    axis: &Axis,
    name: &str,
    changes: &[Change],
    kind: Kind,
    top: f64,
    h: f64,
) {
    let class = match kind {
        Kind::Logic => "signal logic",
        Kind::Number => "signal number",
        Kind::Label => "signal label",
    };
    w.open(
        Element::new("g")
            .attr("class", class)
            .attr("data-name", name),
    );
    w.text(
        Element::new("text")
            .attr("class", "name")
            .num("x", MARGIN)
            .num("y", top + h / 2.0 + 4.0),
        name,
    );
    let spans = spans(axis, changes);
    for &(x0, x1, c) in &spans {
        if c.forced {
            w.empty(
                Element::new("rect")
                    .attr("class", "forced")
                    .num("x", x0)
                    .num("y", top - 2.0)
                    .num("width", (x1 - x0).max(1.0))
                    .num("height", h + 4.0)
                    .attr("fill", "#ffc8c8"),
            );
        }
    }
    match kind {
        Kind::Logic => draw_logic(w, &spans, top, h),
        Kind::Number => draw_number(w, &spans, top, h),
        Kind::Label => draw_label(w, &spans, top, h),
    }
    w.close();
}

fn draw_logic(w: &mut SvgWriter, spans: &[(f64, f64, &Change)], top: f64, h: f64) {
    let (hi, lo) = (top + 3.0, top + h - 3.0);
    let mut pts = Vec::new();
    for &(x0, x1, c) in spans {
        let high = c.value.as_bool() == Some(true);
        let y = if high { hi } else { lo };
        if high {
            w.empty(
                Element::new("rect")
                    .attr("class", "high")
                    .num("x", x0)
                    .num("y", hi)
                    .num("width", x1 - x0)
                    .num("height", lo - hi)
                    .attr("fill", "#cfe3ff"),
            );
        }
        pts.push((x0, y));
        pts.push((x1, y));
    }
    wave(w, &pts, "#0040a0");
}

fn draw_number(w: &mut SvgWriter, spans: &[(f64, f64, &Change)], top: f64, h: f64) {
    let values: Vec<f64> = spans.iter().filter_map(|s| number(&s.2.value)).collect();
    let lo = values.iter().copied().fold(f64::INFINITY, f64::min);
    let hi = values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
    let (y_top, y_bottom) = (top + 14.0, top + h - 3.0);
    let y_of = |v: Option<f64>| match v {
        Some(v) if hi > lo => y_bottom - (v - lo) / (hi - lo) * (y_bottom - y_top),
        _ => (y_top + y_bottom) / 2.0,
    };
    let mut pts = Vec::new();
    for &(x0, x1, c) in spans {
        let y = y_of(number(&c.value));
        pts.push((x0, y));
        pts.push((x1, y));
    }
    wave(w, &pts, "#a04000");
    values_written(w, spans, top + 10.0);
}

/// The value at each change, where it fits before the next change.
fn values_written(w: &mut SvgWriter, spans: &[(f64, f64, &Change)], y: f64) {
    for &(x0, x1, c) in spans {
        let text = c.value.to_literal();
        let need = text.chars().count() as f64 * 6.0 + 4.0;
        if x1 - x0 >= need {
            w.text(
                Element::new("text")
                    .attr("class", "value")
                    .num("x", x0 + 2.0)
                    .num("y", y)
                    .attr("font-size", "10"),
                &text,
            );
        }
    }
}

fn draw_label(w: &mut SvgWriter, spans: &[(f64, f64, &Change)], top: f64, h: f64) {
    let (y0, y1, ym) = (top + 3.0, top + h - 3.0, top + h / 2.0);
    for &(x0, x1, _) in spans {
        let k = ((x1 - x0) / 2.0).min(3.0);
        w.empty(
            Element::new("polygon")
                .attr("class", "segment")
                .points(&[
                    (x0, ym),
                    (x0 + k, y0),
                    (x1 - k, y0),
                    (x1, ym),
                    (x1 - k, y1),
                    (x0 + k, y1),
                ])
                .attr("fill", "#f4f4e0")
                .attr("stroke", "#606000"),
        );
    }
    values_written(w, spans, ym + 4.0);
}

/// The line of one variable's wave (BOOL or number), when it has points.
fn wave(w: &mut SvgWriter, pts: &[(f64, f64)], stroke: &str) {
    if pts.is_empty() {
        return;
    }
    w.empty(
        Element::new("polyline")
            .attr("class", "wave")
            .points(pts)
            .attr("fill", "none")
            .attr("stroke", stroke)
            .num("stroke-width", 1.5),
    );
}
