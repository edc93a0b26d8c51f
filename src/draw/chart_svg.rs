//! Draws a [`ChartModel`] as SVG on the layout of `chart_layout`.
//!
//! Conventions (IEC 61131-3 / IEC 60848): a step is a box, an initial step
//! a double box; an active step is filled green with a token dot; a
//! transition is a short thick bar on the flow line with its condition on
//! the right; the action block of a step sits on its right, one row per
//! association: qualifier (with its duration), action name, indicators.
//! A selection divergence or convergence is a single horizontal line, a
//! simultaneous one a double line. Links going up (loops) run in lanes on
//! the left with an upward arrow.
//!
//! Every element carries a `class` (`step`, `initial`, `active`,
//! `transition`, `condition`, `action`, `qualifier`, `link`, `loop`,
//! `selection`, `simultaneous`) and steps and transitions a `data-name`, so
//! tests and style sheets can find them.

use super::chart_layout::{GAP, Layout, NodeKind, NodeSize, layout};
use super::chart_model::{ChartModel, StepNode, TransitionNode};
use super::svg_writer::{Element, SvgWriter};

/// Width of one character of the 12 px monospace font.
const CHAR_W: f64 = 7.2;
/// Height of a step box.
const STEP_H: f64 = 32.0;
/// Height of one action block row.
const ACTION_ROW: f64 = 20.0;
/// Gap between a step box and its action block.
const ACTION_GAP: f64 = 18.0;
/// Half the width of a transition bar.
const BAR_HALF: f64 = 12.0;
/// Height of one condition text line.
const COND_LINE: f64 = 14.0;
/// Longest condition line before it wraps.
const WRAP: usize = 44;
/// Offset of the second line of a double (simultaneous) line.
const DOUBLE: f64 = 2.5;

fn text_w(s: &str) -> f64 {
    s.chars().count() as f64 * CHAR_W
}

fn box_w(step: &StepNode) -> f64 {
    (text_w(&step.name) + 20.0).max(48.0)
}

/// Column widths of a step's action block (qualifier, name, indicators).
fn action_columns(step: &StepNode) -> [f64; 3] {
    let mut cols = [0.0f64; 3];
    for a in &step.actions {
        cols[0] = cols[0].max(text_w(&qualifier_text(a)) + 10.0);
        cols[1] = cols[1].max(text_w(&a.action) + 12.0);
        if !a.indicators.is_empty() {
            cols[2] = cols[2].max(text_w(&a.indicators.join(", ")) + 12.0);
        }
    }
    cols
}

fn qualifier_text(a: &super::chart_model::ActionLine) -> String {
    match &a.duration {
        Some(d) => format!("{} {d}", a.qualifier),
        None => a.qualifier.clone(),
    }
}

/// Splits a condition line at spaces so no line is longer than [`WRAP`].
fn wrap(line: &str) -> Vec<String> {
    let mut out = Vec::new();
    let mut cur = String::new();
    for word in line.split(' ') {
        if !cur.is_empty() && cur.chars().count() + 1 + word.chars().count() > WRAP {
            out.push(std::mem::take(&mut cur));
        }
        if !cur.is_empty() {
            cur.push(' ');
        }
        cur.push_str(word);
    }
    if !cur.is_empty() || out.is_empty() {
        out.push(cur);
    }
    out
}

/// The text lines beside a transition bar: its name and priority (if
/// any), then the condition.
fn transition_lines(t: &TransitionNode) -> Vec<String> {
    let mut lines = Vec::new();
    match (&t.name, &t.priority) {
        (Some(n), Some(p)) => lines.push(format!("{n} (PRIORITY := {p})")),
        (Some(n), None) => lines.push(format!("{n}:")),
        (None, Some(p)) => lines.push(format!("(PRIORITY := {p})")),
        (None, None) => {}
    }
    for l in &t.condition {
        lines.extend(wrap(l));
    }
    lines
}

fn step_size(s: &StepNode) -> NodeSize {
    let half = box_w(s) / 2.0;
    let cols = action_columns(s);
    let block = cols.iter().sum::<f64>();
    NodeSize {
        left: half,
        right: if s.actions.is_empty() {
            half
        } else {
            half + ACTION_GAP + block
        },
        height: STEP_H.max(s.actions.len() as f64 * ACTION_ROW),
    }
}

fn transition_size(t: &TransitionNode) -> NodeSize {
    let lines = transition_lines(t);
    let widest = lines.iter().map(|l| text_w(l)).fold(0.0, f64::max);
    NodeSize {
        left: BAR_HALF,
        right: BAR_HALF + 8.0 + widest,
        height: (lines.len() as f64 * COND_LINE + 6.0).max(18.0),
    }
}

/// Draws `model`, filling the steps named in `active` (case-insensitive).
pub fn chart_svg(model: &ChartModel, active: &[String]) -> String {
    let sizes: Vec<NodeSize> = model
        .steps
        .iter()
        .map(step_size)
        .chain(model.transitions.iter().map(transition_size))
        .collect();
    let initial: Vec<usize> = (0..model.steps.len())
        .filter(|&i| model.steps[i].initial)
        .collect();
    let trans: Vec<(Vec<usize>, Vec<usize>)> = model
        .transitions
        .iter()
        .map(|t| (t.from.clone(), t.to.clone()))
        .collect();
    let l = layout(model.steps.len(), &initial, &trans, &sizes);
    let mut w = SvgWriter::new(l.width, l.height);
    w.text(Element::new("title"), &format!("Chart of {}", model.pou));
    w.text(
        Element::new("text")
            .attr("class", "title")
            .num("x", super::chart_layout::MARGIN)
            .num("y", super::chart_layout::MARGIN + 10.0)
            .attr("font-weight", "bold"),
        &model.pou,
    );
    links(&mut w, &l);
    for node in &l.nodes {
        let row = l.rows[node.layer];
        match node.kind {
            NodeKind::Step(i) => {
                let step = &model.steps[i];
                let on = active.iter().any(|a| a.eq_ignore_ascii_case(&step.name));
                draw_step(&mut w, step, node.x, row.top, row.bottom(), on);
            }
            NodeKind::Transition(i) => {
                draw_transition(&mut w, model, i, node.x, row.top, row.bottom());
            }
            NodeKind::Dummy => {
                let e = line(node.x, row.top, node.x, row.bottom()).attr("class", "link");
                w.empty(e);
            }
        }
    }
    w.finish()
}

/// A thin black line from (x1, y1) to (x2, y2).
pub(super) fn line(x1: f64, y1: f64, x2: f64, y2: f64) -> Element {
    Element::new("line")
        .num("x1", x1)
        .num("y1", y1)
        .num("x2", x2)
        .num("y2", y2)
        .attr("stroke", "black")
}

fn draw_step(w: &mut SvgWriter, step: &StepNode, x: f64, top: f64, bottom: f64, active: bool) {
    let bw = box_w(step);
    let mut class = String::from("step");
    if step.initial {
        class.push_str(" initial");
    }
    if active {
        class.push_str(" active");
    }
    w.open(
        Element::new("g")
            .attr("class", class)
            .attr("data-name", step.name.clone()),
    );
    let fill = if active { "#8fdc8f" } else { "white" };
    let frame = |inset: f64| {
        Element::new("rect")
            .num("x", x - bw / 2.0 + inset)
            .num("y", top + inset)
            .num("width", bw - 2.0 * inset)
            .num("height", STEP_H - 2.0 * inset)
            .attr("fill", if inset == 0.0 { fill } else { "none" })
            .attr("stroke", "black")
    };
    w.empty(frame(0.0));
    if step.initial {
        w.empty(frame(3.5));
    }
    w.text(
        Element::new("text")
            .attr("class", "name")
            .num("x", x)
            .num("y", top + STEP_H / 2.0 + 4.0)
            .attr("text-anchor", "middle"),
        &step.name,
    );
    if active {
        w.empty(
            Element::new("circle")
                .attr("class", "token")
                .num("cx", x)
                .num("cy", top + STEP_H - 7.0)
                .num("r", 2.5)
                .attr("fill", "black"),
        );
    }
    if bottom > top + STEP_H {
        w.empty(line(x, top + STEP_H, x, bottom).attr("class", "link"));
    }
    if !step.actions.is_empty() {
        draw_actions(w, step, x + bw / 2.0, top);
    }
    w.close();
}

fn draw_actions(w: &mut SvgWriter, step: &StepNode, box_right: f64, top: f64) {
    let cols = action_columns(step);
    let left = box_right + ACTION_GAP;
    w.empty(line(
        box_right,
        top + STEP_H / 2.0,
        left,
        top + STEP_H / 2.0,
    ));
    for (r, a) in step.actions.iter().enumerate() {
        let y = top + r as f64 * ACTION_ROW;
        w.open(
            Element::new("g")
                .attr("class", "action")
                .attr("data-name", a.action.clone()),
        );
        let texts = [qualifier_text(a), a.action.clone(), a.indicators.join(", ")];
        let classes = ["qualifier", "action-name", "indicator"];
        let mut cx = left;
        for c in 0..3 {
            if cols[c] == 0.0 {
                continue;
            }
            w.empty(
                Element::new("rect")
                    .num("x", cx)
                    .num("y", y)
                    .num("width", cols[c])
                    .num("height", ACTION_ROW)
                    .attr("fill", "white")
                    .attr("stroke", "black"),
            );
            w.text(
                Element::new("text")
                    .attr("class", classes[c])
                    .num("x", cx + 5.0)
                    .num("y", y + ACTION_ROW / 2.0 + 4.0),
                &texts[c],
            );
            cx += cols[c];
        }
        w.close();
    }
}

fn draw_transition(w: &mut SvgWriter, model: &ChartModel, i: usize, x: f64, top: f64, bottom: f64) {
    let t = &model.transitions[i];
    let names = |steps: &[usize]| {
        steps
            .iter()
            .map(|&s| model.steps[s].name.clone())
            .collect::<Vec<_>>()
            .join(",")
    };
    let mut g = Element::new("g").attr("class", "transition");
    if let Some(n) = &t.name {
        g = g.attr("data-name", n.clone());
    }
    w.open(
        g.attr("data-from", names(&t.from))
            .attr("data-to", names(&t.to)),
    );
    let mid = (top + bottom) / 2.0;
    w.empty(line(x, top, x, bottom).attr("class", "link"));
    w.empty(
        Element::new("rect")
            .attr("class", "bar")
            .num("x", x - BAR_HALF)
            .num("y", mid - 1.5)
            .num("width", 2.0 * BAR_HALF)
            .num("height", 3.0)
            .attr("fill", "black"),
    );
    let lines = transition_lines(t);
    let first = mid - (lines.len() as f64 - 1.0) * COND_LINE / 2.0 + 4.0;
    let named = t.name.is_some() || t.priority.is_some();
    for (k, text) in lines.iter().enumerate() {
        let class = if named && k == 0 {
            "label"
        } else {
            "condition"
        };
        let mut e = Element::new("text")
            .attr("class", class)
            .num("x", x + BAR_HALF + 8.0)
            .num("y", first + k as f64 * COND_LINE);
        if class == "label" {
            e = e.attr("fill", "#555555");
        }
        w.text(e, text);
    }
    w.close();
}

/// The links between rows: plain jogs, divergence and convergence lines,
/// and the loops on the left.
fn links(w: &mut SvgWriter, l: &Layout) {
    let n = l.nodes.len();
    let mut outdeg = vec![0usize; n];
    let mut indeg = vec![0usize; n];
    for &(a, b) in &l.segments {
        outdeg[a] += 1;
        indeg[b] += 1;
    }
    for b in &l.back {
        outdeg[b.from] += 1;
        indeg[b.to] += 1;
    }
    let is_trans = |v: usize| matches!(l.nodes[v].kind, NodeKind::Transition(_));
    let bottom = |v: usize| l.rows[l.nodes[v].layer].bottom();
    let top = |v: usize| l.rows[l.nodes[v].layer].top;
    // The heights of the horizontal parts inside a gap, top to bottom:
    // divergence lines, plain jogs, loops leaving, loops entering,
    // convergence lines; apart, so no two kinds of line run together.
    let div_y = |v: usize| bottom(v) + GAP * 0.18;
    let mid_y = |v: usize| bottom(v) + GAP * 0.36;
    let leave_y = |v: usize| bottom(v) + GAP * 0.54;
    let enter_y = |v: usize| top(v) - GAP * 0.3;
    let conv_y = |v: usize| top(v) - GAP * 0.14;
    w.open(
        Element::new("g")
            .attr("class", "links")
            .attr("fill", "none"),
    );
    for &(a, b) in &l.segments {
        let (xa, xb) = (l.nodes[a].x, l.nodes[b].x);
        let (ya, yb) = (bottom(a), top(b));
        if outdeg[a] > 1 {
            let d = if is_trans(a) { DOUBLE } else { 0.0 };
            w.empty(line(xa, ya, xa, div_y(a) - d).attr("class", "link"));
            w.empty(line(xb, div_y(a) + d, xb, yb).attr("class", "link"));
        } else if indeg[b] > 1 {
            let d = if is_trans(b) { DOUBLE } else { 0.0 };
            w.empty(line(xa, ya, xa, conv_y(b) - d).attr("class", "link"));
            w.empty(line(xb, conv_y(b) + d, xb, yb).attr("class", "link"));
        } else {
            let ym = mid_y(a);
            w.empty(
                Element::new("polyline")
                    .attr("class", "link")
                    .points(&[(xa, ya), (xa, ym), (xb, ym), (xb, yb)])
                    .attr("stroke", "black"),
            );
        }
    }
    for v in 0..n {
        if outdeg[v] > 1 {
            let xs: Vec<f64> = l
                .segments
                .iter()
                .filter(|s| s.0 == v)
                .map(|s| l.nodes[s.1].x)
                .collect();
            bar(w, l.nodes[v].x, &xs, div_y(v), is_trans(v));
        }
        if indeg[v] > 1 {
            let xs: Vec<f64> = l
                .segments
                .iter()
                .filter(|s| s.1 == v && outdeg[s.0] == 1)
                .map(|s| l.nodes[s.0].x)
                .collect();
            // Sources on a divergence line come down from it instead.
            if !xs.is_empty() {
                bar(w, l.nodes[v].x, &xs, conv_y(v), is_trans(v));
            }
        }
    }
    for b in &l.back {
        let (xf, xt) = (l.nodes[b.from].x, l.nodes[b.to].x);
        let y_leave = if outdeg[b.from] > 1 {
            div_y(b.from)
        } else {
            leave_y(b.from)
        };
        let y_enter = if indeg[b.to] > 1 {
            conv_y(b.to)
        } else {
            enter_y(b.to)
        };
        w.open(Element::new("g").attr("class", "loop"));
        let pts = [
            (xf, bottom(b.from)),
            (xf, y_leave),
            (b.lane, y_leave),
            (b.lane, y_enter),
            (xt, y_enter),
            (xt, top(b.to)),
        ];
        w.empty(
            Element::new("polyline")
                .points(&pts)
                .attr("stroke", "black"),
        );
        let ym = (y_leave + y_enter) / 2.0;
        w.empty(
            Element::new("polygon")
                .attr("class", "arrow")
                .points(&[
                    (b.lane - 4.0, ym + 4.0),
                    (b.lane + 4.0, ym + 4.0),
                    (b.lane, ym - 5.0),
                ])
                .attr("fill", "black"),
        );
        w.close();
    }
    w.close();
}

/// A divergence or convergence line through `x` and `xs`: single for a
/// selection (at a step), double for a simultaneous one (at a transition).
fn bar(w: &mut SvgWriter, x: f64, xs: &[f64], y: f64, simultaneous: bool) {
    let lo = xs.iter().copied().fold(x, f64::min);
    let hi = xs.iter().copied().fold(x, f64::max);
    if simultaneous {
        w.open(Element::new("g").attr("class", "simultaneous"));
        w.empty(line(lo - 6.0, y - DOUBLE, hi + 6.0, y - DOUBLE));
        w.empty(line(lo - 6.0, y + DOUBLE, hi + 6.0, y + DOUBLE));
        w.close();
    } else {
        w.empty(line(lo, y, hi, y).attr("class", "selection"));
    }
}
