//! What a chart picture shows, read from the program's own SFC elements:
//! step names, which steps are initial, the action associations as written
//! (qualifier, duration, indicators), and every transition with its
//! preceding and following steps and its condition as the source text.
//!
//! The AST is used rather than the image's step table because the table
//! keeps neither the condition's text nor the durations as written.

use super::DrawError;
use crate::diagnostics::Diagnostics;
use crate::source::{SourceMap, Span};
use crate::syntax::ast::{Body, Item, Pou, SfcElement, TransitionCondition};

/// One action association of a step, as written.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ActionLine {
    /// The qualifier (`N` when none was written).
    pub qualifier: String,
    /// The action (or BOOL variable) name.
    pub action: String,
    /// The duration as written, for timed qualifiers.
    pub duration: Option<String>,
    /// Indicator variables.
    pub indicators: Vec<String>,
}

/// A step of the chart.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct StepNode {
    /// Its name as declared.
    pub name: String,
    /// Declared with `INITIAL_STEP`.
    pub initial: bool,
    /// Its action associations in textual order.
    pub actions: Vec<ActionLine>,
}

/// A transition of the chart.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct TransitionNode {
    /// Its name, if it has one.
    pub name: Option<String>,
    /// Its `PRIORITY` as written.
    pub priority: Option<String>,
    /// Preceding steps (indices into [`ChartModel::steps`]).
    pub from: Vec<usize>,
    /// Following steps (indices into [`ChartModel::steps`]).
    pub to: Vec<usize>,
    /// The condition's source text, one entry per line (IL bodies keep
    /// their lines; an ST expression is one line with its spaces squeezed).
    pub condition: Vec<String>,
}

/// The chart of one POU.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ChartModel {
    /// The POU's name.
    pub pou: String,
    /// Steps in declaration order.
    pub steps: Vec<StepNode>,
    /// Transitions in declaration order.
    pub transitions: Vec<TransitionNode>,
}

/// Squeezes runs of white space (line breaks included) into one space.
fn squeeze(text: &str) -> String {
    text.split_whitespace().collect::<Vec<_>>().join(" ")
}

fn source_text(sources: &SourceMap, span: Span) -> String {
    let text = &sources.file(span.file).text;
    let (start, end) = (span.start as usize, span.end as usize);
    squeeze(text.get(start..end).unwrap_or(""))
}

/// Every POU of `sources` whose body is a chart, in source order.
fn charts(sources: &SourceMap) -> Vec<Pou> {
    let mut out = Vec::new();
    let mut all = Vec::new();
    for (i, file) in sources.files().iter().enumerate() {
        let mut diags = Diagnostics::new();
        let id = crate::source::FileId(i as u32);
        let unit = crate::syntax::parse(id, &file.text, &mut diags);
        for item in unit.items {
            if let Item::Pou(p) = item {
                all.push(p);
            }
        }
    }
    for p in all {
        if matches!(p.body, Body::Sfc(_)) {
            out.push(p);
        }
    }
    out
}

/// Whether `sources` declare a POU named `name` (any body).
pub(super) fn declares(sources: &SourceMap, name: &str) -> bool {
    sources.files().iter().enumerate().any(|(i, file)| {
        let mut diags = Diagnostics::new();
        let unit = crate::syntax::parse(crate::source::FileId(i as u32), &file.text, &mut diags);
        unit.items
            .iter()
            .any(|it| matches!(it, Item::Pou(p) if p.name.name.eq_ignore_ascii_case(name)))
    })
}

/// The chart of POU `pou` (any PROGRAM or FUNCTION_BLOCK whose body is a
/// chart), or of the only chart in `sources` when `pou` is `None`.
pub fn chart_model(sources: &SourceMap, pou: Option<&str>) -> Result<ChartModel, DrawError> {
    let mut found = charts(sources);
    let chosen = match pou {
        Some(name) => match found
            .iter()
            .position(|p| p.name.name.eq_ignore_ascii_case(name.trim()))
        {
            Some(i) => found.swap_remove(i),
            None if declares(sources, name.trim()) => {
                return Err(DrawError::NotAChart(name.trim().to_string()));
            }
            None => return Err(DrawError::NoSuchPou(name.trim().to_string())),
        },
        None => match found.len() {
            0 => return Err(DrawError::NoChart),
            1 => found.remove(0),
            _ => {
                return Err(DrawError::SeveralCharts(
                    found.into_iter().map(|p| p.name.name).collect(),
                ));
            }
        },
    };
    build(sources, &chosen)
}

fn build(sources: &SourceMap, pou: &Pou) -> Result<ChartModel, DrawError> {
    let Body::Sfc(elements) = &pou.body else {
        return Err(DrawError::NotAChart(pou.name.name.clone()));
    };
    let mut model = ChartModel {
        pou: pou.name.name.clone(),
        steps: Vec::new(),
        transitions: Vec::new(),
    };
    for e in elements {
        if let SfcElement::Step(s) = e {
            let actions = s
                .actions
                .iter()
                .map(|a| ActionLine {
                    qualifier: a
                        .qualifier
                        .as_ref()
                        .map_or("N".to_string(), |q| q.name.to_ascii_uppercase()),
                    action: a.action.name.clone(),
                    duration: a.duration.as_ref().map(|d| source_text(sources, d.span)),
                    indicators: a.indicators.iter().map(|i| i.name.clone()).collect(),
                })
                .collect();
            model.steps.push(StepNode {
                name: s.name.name.clone(),
                initial: s.initial,
                actions,
            });
        }
    }
    for e in elements {
        let SfcElement::Transition(t) = e else {
            continue;
        };
        let label = t.name.as_ref().map_or_else(
            || format!("#{}", model.transitions.len() + 1),
            |n| n.name.clone(),
        );
        let index = |id: &crate::syntax::ast::Ident| {
            model
                .steps
                .iter()
                .position(|s| s.name.eq_ignore_ascii_case(&id.name))
                .ok_or_else(|| DrawError::UnknownStep {
                    transition: label.clone(),
                    step: id.name.clone(),
                })
        };
        let from = t.from.iter().map(index).collect::<Result<Vec<_>, _>>()?;
        let to = t.to.iter().map(index).collect::<Result<Vec<_>, _>>()?;
        let condition = match &t.condition {
            TransitionCondition::Expr(e) => vec![source_text(sources, e.span)],
            TransitionCondition::Il(lines) => lines
                .iter()
                .filter(|l| l.instr.is_some() || l.label.is_some())
                .map(|l| source_text(sources, l.span))
                .filter(|s| !s.is_empty())
                .collect(),
        };
        model.transitions.push(TransitionNode {
            name: t.name.as_ref().map(|n| n.name.clone()),
            priority: t.priority.as_ref().map(|p| source_text(sources, p.span)),
            from,
            to,
            condition,
        });
    }
    Ok(model)
}
