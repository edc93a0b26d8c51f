//! Export of a textual SFC as a TC6 network: steps, transitions, selection
//! and simultaneous divergences and convergences, action blocks, each with
//! a localId, its connections and a position on a simple grid.

use super::writer::Writer;
use super::{ExportError, Exporter, trim_body};
use crate::syntax::ast::{
    Action, Body, Pou, SfcElement, Step, Stmt, Transition, TransitionCondition,
};
use crate::syntax::plcopen::body::SFC_STATEMENTS_DATA;

/// The localIds of a chart's elements.
struct Ids {
    step: Vec<usize>,
    transition: Vec<usize>,
    /// Per step, the selection divergence after it (several transitions leave it).
    sel_div: Vec<Option<usize>>,
    /// Per step, the selection convergence before it (several transitions enter it).
    sel_conv: Vec<Option<usize>>,
    /// Per transition, the simultaneous convergence before it.
    sim_conv: Vec<Option<usize>>,
    /// Per transition, the simultaneous divergence after it.
    sim_div: Vec<Option<usize>>,
    /// Per step, its action block.
    block: Vec<Option<usize>>,
}

/// A chart: its steps and transitions, with transitions' steps as indices.
struct Chart<'a> {
    steps: Vec<&'a Step>,
    transitions: Vec<&'a Transition>,
    from: Vec<Vec<usize>>,
    to: Vec<Vec<usize>>,
    /// Per step, the transitions leaving it and entering it.
    outs: Vec<Vec<usize>>,
    ins: Vec<Vec<usize>>,
}

impl Exporter<'_> {
    /// A POU whose body is a chart: `<actions>`, then the `<SFC>` body,
    /// then plcrun's plain statements in `<addData>`.
    pub(super) fn sfc_pou(
        &self,
        w: &mut Writer,
        pou: &Pou,
        elements: &[SfcElement],
    ) -> Result<(), ExportError> {
        let actions: Vec<&Action> = elements
            .iter()
            .filter_map(|e| match e {
                SfcElement::Action(a) => Some(a),
                _ => None,
            })
            .collect();
        let statements: Vec<&Stmt> = elements
            .iter()
            .filter_map(|e| match e {
                SfcElement::Statement(s) => Some(s),
                _ => None,
            })
            .collect();
        if !actions.is_empty() {
            w.open("actions", &[]);
            for a in &actions {
                w.open("action", &[("name", &a.name.name)]);
                w.open("body", &[]);
                let lang = if matches!(a.body, Body::Il(_)) {
                    "IL"
                } else {
                    "ST"
                };
                w.text_body(lang, &self.action_text(a)?);
                w.close("body");
                w.close("action");
            }
            w.close("actions");
        }
        let chart = self.chart(pou, elements)?;
        let ids = numbering(&chart);
        w.open("body", &[]);
        w.open("SFC", &[]);
        for (s, step) in chart.steps.iter().enumerate() {
            self.write_step(w, &chart, &ids, s, step)?;
        }
        for (t, tr) in chart.transitions.iter().enumerate() {
            self.write_transition(w, &chart, &ids, t, tr)?;
        }
        write_bars(w, &chart, &ids);
        w.close("SFC");
        if !statements.is_empty() {
            let text: Vec<String> = statements
                .iter()
                .map(|s| {
                    let t = self.text(s.span).trim();
                    if t.ends_with(';') {
                        t.to_string()
                    } else {
                        format!("{t};")
                    }
                })
                .collect();
            w.open("addData", &[]);
            w.open(
                "data",
                &[
                    ("name", SFC_STATEMENTS_DATA),
                    ("handleUnknown", "implementation"),
                ],
            );
            w.text_body("ST", &format!("{}\n", text.join("\n")));
            w.close("data");
            w.close("addData");
        }
        w.close("body");
        Ok(())
    }

    /// The steps and transitions, with the transitions' steps resolved.
    fn chart<'a>(&self, pou: &Pou, elements: &'a [SfcElement]) -> Result<Chart<'a>, ExportError> {
        let steps: Vec<&Step> = elements
            .iter()
            .filter_map(|e| match e {
                SfcElement::Step(s) => Some(s),
                _ => None,
            })
            .collect();
        let transitions: Vec<&Transition> = elements
            .iter()
            .filter_map(|e| match e {
                SfcElement::Transition(t) => Some(t),
                _ => None,
            })
            .collect();
        let find = |name: &crate::syntax::ast::Ident| {
            steps
                .iter()
                .position(|s| s.name.name.eq_ignore_ascii_case(&name.name))
                .ok_or_else(|| {
                    self.refuse(
                        format!(
                            "a transition from or to `{}`, which is not a step",
                            name.name
                        ),
                        name.span,
                    )
                })
        };
        let mut from = Vec::new();
        let mut to = Vec::new();
        for t in &transitions {
            from.push(t.from.iter().map(find).collect::<Result<Vec<_>, _>>()?);
            to.push(t.to.iter().map(find).collect::<Result<Vec<_>, _>>()?);
        }
        if steps.is_empty() {
            return Err(self.refuse("an SFC body without steps", pou.span));
        }
        let mut outs = vec![Vec::new(); steps.len()];
        let mut ins = vec![Vec::new(); steps.len()];
        for t in 0..transitions.len() {
            for &s in &from[t] {
                outs[s].push(t);
            }
            for &s in &to[t] {
                ins[s].push(t);
            }
        }
        Ok(Chart {
            steps,
            transitions,
            from,
            to,
            outs,
            ins,
        })
    }

    /// The text of an action's body: after `ACTION name :`, before `END_ACTION`.
    fn action_text(&self, a: &Action) -> Result<String, ExportError> {
        let whole = self.text(a.span);
        let after_name = (a.name.span.end - a.span.start) as usize;
        let colon = whole
            .get(after_name..)
            .and_then(|t| t.find(':'))
            .map(|c| after_name + c + 1);
        let cut = whole.len().checked_sub("END_ACTION".len());
        match (colon, cut) {
            (Some(c), Some(e))
                if c <= e
                    && whole.is_char_boundary(e)
                    && whole[e..].eq_ignore_ascii_case("END_ACTION") =>
            {
                Ok(trim_body(&whole[c..e]))
            }
            _ => Err(self.refuse(
                "an ACTION not written `ACTION name : ... END_ACTION`",
                a.span,
            )),
        }
    }

    /// `<step>` and its `<actionBlock>`.
    fn write_step(
        &self,
        w: &mut Writer,
        chart: &Chart,
        ids: &Ids,
        s: usize,
        step: &Step,
    ) -> Result<(), ExportError> {
        let id = ids.step[s].to_string();
        let mut attrs = vec![
            ("localId", id.as_str()),
            ("name", step.name.name.as_str()),
            ("height", "40"),
            ("width", "60"),
        ];
        if step.initial {
            attrs.push(("initialStep", "true"));
        }
        w.open("step", &attrs);
        position(w, ids.step[s], 0);
        let sources: Vec<usize> = match ids.sel_conv[s] {
            Some(c) => vec![c],
            None => chart.ins[s]
                .iter()
                .map(|&t| ids.sim_div[t].unwrap_or(ids.transition[t]))
                .collect(),
        };
        connection_in(w, &sources);
        w.empty("connectionPointOut", &[("formalParameter", "")]);
        if let Some(block) = ids.block[s] {
            w.empty("connectionPointOutAction", &[("formalParameter", "")]);
            w.close("step");
            self.write_block(w, block, ids.step[s], step)?;
        } else {
            w.close("step");
        }
        Ok(())
    }

    /// `<actionBlock>` of a step: one `<action>` per association.
    fn write_block(
        &self,
        w: &mut Writer,
        id: usize,
        step_id: usize,
        step: &Step,
    ) -> Result<(), ExportError> {
        let id_text = id.to_string();
        w.open(
            "actionBlock",
            &[("localId", &id_text), ("height", "30"), ("width", "120")],
        );
        position(w, id, 1);
        connection_in(w, &[step_id]);
        for assoc in &step.actions {
            if assoc.indicators.len() > 1 {
                return Err(
                    self.refuse("an action association with several indicators", assoc.span)
                );
            }
            let qualifier = assoc.qualifier.as_ref().map_or("N", |q| q.name.as_str());
            let mut attrs = vec![("localId", "0"), ("qualifier", qualifier)];
            if let Some(d) = &assoc.duration {
                attrs.push(("duration", self.text(d.span)));
            }
            if let Some(i) = assoc.indicators.first() {
                attrs.push(("indicator", i.name.as_str()));
            }
            w.open("action", &attrs);
            w.empty("relPosition", &[("x", "0"), ("y", "0")]);
            w.empty("reference", &[("name", &assoc.action.name)]);
            w.close("action");
        }
        w.close("actionBlock");
        Ok(())
    }

    /// `<transition>` with its condition.
    fn write_transition(
        &self,
        w: &mut Writer,
        chart: &Chart,
        ids: &Ids,
        t: usize,
        tr: &Transition,
    ) -> Result<(), ExportError> {
        let id = ids.transition[t].to_string();
        let mut attrs = vec![("localId", id.as_str()), ("height", "2"), ("width", "20")];
        if let Some(p) = &tr.priority {
            attrs.push(("priority", self.text(p.span)));
        }
        w.open("transition", &attrs);
        position(w, ids.transition[t], 0);
        let sources: Vec<usize> = match ids.sim_conv[t] {
            Some(c) => vec![c],
            None => chart.from[t].iter().map(|&s| out_point(ids, s)).collect(),
        };
        connection_in(w, &sources);
        w.empty("connectionPointOut", &[]);
        w.open("condition", &[]);
        let name = tr.name.as_ref().map_or("", |n| n.name.as_str());
        w.open("inline", &[("name", name)]);
        match &tr.condition {
            TransitionCondition::Expr(e) => w.text_body("ST", &format!("{}\n", self.text(e.span))),
            TransitionCondition::Il(lines) => {
                let (Some(first), Some(last)) = (lines.first(), lines.last()) else {
                    return Err(self.refuse("an empty IL condition", tr.span));
                };
                w.text_body("IL", &format!("{}\n", self.text(first.span.to(last.span))));
            }
        }
        w.close("inline");
        w.close("condition");
        w.close("transition");
        Ok(())
    }
}

/// Where the flow leaves step `s`: its selection divergence or the step.
fn out_point(ids: &Ids, s: usize) -> usize {
    ids.sel_div[s].unwrap_or(ids.step[s])
}

/// Numbers every element: steps, transitions, then the bars and blocks.
fn numbering(chart: &Chart) -> Ids {
    let n_steps = chart.steps.len();
    let n_tr = chart.transitions.len();
    let mut next = 1;
    let mut take = || {
        let id = next;
        next += 1;
        id
    };
    let step: Vec<usize> = (0..n_steps).map(|_| take()).collect();
    let transition: Vec<usize> = (0..n_tr).map(|_| take()).collect();
    let sel_div = (0..n_steps)
        .map(|s| (chart.outs[s].len() > 1).then(&mut take))
        .collect();
    let sel_conv = (0..n_steps)
        .map(|s| (chart.ins[s].len() > 1).then(&mut take))
        .collect();
    let sim_conv = (0..n_tr)
        .map(|t| (chart.from[t].len() > 1).then(&mut take))
        .collect();
    let sim_div = (0..n_tr)
        .map(|t| (chart.to[t].len() > 1).then(&mut take))
        .collect();
    let block = chart
        .steps
        .iter()
        .map(|s| (!s.actions.is_empty()).then(&mut take))
        .collect();
    Ids {
        step,
        transition,
        sel_div,
        sel_conv,
        sim_conv,
        sim_div,
        block,
    }
}

/// The divergences and convergences.
fn write_bars(w: &mut Writer, chart: &Chart, ids: &Ids) {
    for s in 0..chart.steps.len() {
        if let Some(id) = ids.sel_div[s] {
            bar(
                w,
                "selectionDivergence",
                id,
                &[ids.step[s]],
                chart.outs[s].len(),
            );
        }
        if let Some(id) = ids.sel_conv[s] {
            let sources: Vec<usize> = chart.ins[s]
                .iter()
                .map(|&t| ids.sim_div[t].unwrap_or(ids.transition[t]))
                .collect();
            bar(w, "selectionConvergence", id, &sources, 1);
        }
    }
    for t in 0..chart.transitions.len() {
        if let Some(id) = ids.sim_conv[t] {
            let sources: Vec<usize> = chart.from[t].iter().map(|&s| out_point(ids, s)).collect();
            bar(w, "simultaneousConvergence", id, &sources, 1);
        }
        if let Some(id) = ids.sim_div[t] {
            bar(
                w,
                "simultaneousDivergence",
                id,
                &[ids.transition[t]],
                chart.to[t].len(),
            );
        }
    }
}

/// One bar: a `connectionPointIn` per source (one for a divergence) and
/// `outs` connection points out.
fn bar(w: &mut Writer, kind: &str, id: usize, sources: &[usize], outs: usize) {
    let id_text = id.to_string();
    w.open(
        kind,
        &[("localId", &id_text), ("height", "1"), ("width", "100")],
    );
    position(w, id, 2);
    let converges = kind.ends_with("Convergence");
    if converges {
        for &s in sources {
            connection_in(w, &[s]);
        }
    } else {
        connection_in(w, sources);
    }
    for k in 0..outs {
        if converges {
            w.empty("connectionPointOut", &[]);
        } else {
            w.empty("connectionPointOut", &[("formalParameter", &k.to_string())]);
        }
    }
    w.close(kind);
}

/// `<connectionPointIn>` naming `sources`.
fn connection_in(w: &mut Writer, sources: &[usize]) {
    if sources.is_empty() {
        return;
    }
    w.open("connectionPointIn", &[]);
    for s in sources {
        w.empty("connection", &[("refLocalId", &s.to_string())]);
    }
    w.close("connectionPointIn");
}

/// A position on a grid: one row per localId, one column per kind.
fn position(w: &mut Writer, id: usize, column: usize) {
    let x = (100 + 200 * column).to_string();
    let y = (40 * id).to_string();
    w.empty("position", &[("x", &x), ("y", &y)]);
}
