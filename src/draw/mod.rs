//! Pictures: SVG drawings of charts and timing diagrams of runs.
//!
//! - [`ChartPicture`]: the chart of a PROGRAM or FUNCTION_BLOCK, laid out
//!   top-down (`chart_layout`), drawn by `chart_svg`, optionally with the
//!   active steps of a running PLC marked.
//! - [`TimingDiagram`]: values recorded cycle by cycle, drawn as logic
//!   lines, step lines and labelled segments over a time axis.
//! - [`NetworkPicture`]: the FBD networks and LD rungs of PLCopen
//!   sources at the editor's positions (`network_geometry`, drawn by
//!   `network_svg` and `ld_svg`); [`draw_sources`] chooses between a
//!   chart and them.
//!
//! All SVG text comes out of `svg_writer`.

mod chart_layout;
mod chart_model;
mod chart_svg;
mod ld_svg;
mod network_geometry;
mod network_picture;
mod network_svg;
mod svg_writer;
mod timing_svg;

pub use chart_model::{ActionLine, ChartModel, StepNode, TransitionNode};
pub use network_picture::{NetworkPicture, draw_sources};
pub use timing_svg::{MAX_CHANGES, TimingDiagram};

use crate::runtime::engine::Plc;
use crate::source::SourceMap;

/// Why a chart cannot be drawn.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum DrawError {
    /// No POU of the sources has a chart body.
    NoChart,
    /// Several POUs have a chart; one must be chosen (their names).
    SeveralCharts(Vec<String>),
    /// No POU has this name.
    NoSuchPou(String),
    /// The POU exists but its body is not a chart.
    NotAChart(String),
    /// The POU exists but its body is neither a chart nor an FBD or LD
    /// network.
    NotDrawable(String),
    /// No POU has a chart, an FBD or an LD body.
    NothingToDraw,
    /// A PLCopen file's graphical body cannot be read (the file and why).
    Unreadable(String),
    /// A transition names a step the chart does not declare (the sources
    /// were not checked).
    UnknownStep {
        /// The transition (its name or `#n`, its rank in the chart).
        transition: String,
        /// The step it names.
        step: String,
    },
}

impl std::fmt::Display for DrawError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            DrawError::NoChart => write!(f, "no PROGRAM or FUNCTION_BLOCK has a chart (SFC) body"),
            DrawError::SeveralCharts(names) => write!(
                f,
                "several POUs have a chart ({}); choose one with --program",
                names.join(", ")
            ),
            DrawError::NoSuchPou(n) => write!(f, "there is no POU named `{n}`"),
            DrawError::NotAChart(n) => write!(f, "the body of `{n}` is not a chart (SFC)"),
            DrawError::NotDrawable(n) => write!(
                f,
                "the body of `{n}` is neither a chart (SFC) nor an FBD or LD network; plcrun draws those"
            ),
            DrawError::NothingToDraw => write!(
                f,
                "no PROGRAM or FUNCTION_BLOCK has a chart (SFC) body, and no POU an FBD or LD body"
            ),
            DrawError::Unreadable(why) => write!(f, "{why}"),
            DrawError::UnknownStep { transition, step } => {
                write!(f, "transition {transition} names an unknown step `{step}`")
            }
        }
    }
}

impl std::error::Error for DrawError {}

/// The chart of one POU, ready to be drawn.
///
/// ```
/// use plcrun::{ChartPicture, Options, Plc};
///
/// let src = "PROGRAM p VAR go : BOOL; END_VAR
/// INITIAL_STEP Idle : END_STEP
/// STEP Run : END_STEP
/// TRANSITION FROM Idle TO Run := go; END_TRANSITION
/// TRANSITION FROM Run TO Idle := NOT go; END_TRANSITION
/// END_PROGRAM";
/// let mut plc = Plc::compile_files(&[("p.sfc", src)], &Options::default())?;
/// let chart = ChartPicture::of_program(&plc)?;
/// plc.run_cycle()?;
/// let svg = chart.to_svg_active(&chart.active_in(&plc));
/// assert!(svg.contains(r#"class="step initial active" data-name="Idle""#));
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct ChartPicture {
    model: ChartModel,
    /// The program instance whose chart this is, for the active steps.
    instance: Option<String>,
}

impl ChartPicture {
    /// The chart of POU `pou` in `sources` (of the only chart when `None`).
    /// The sources should have been checked ([`crate::check`] or
    /// [`Plc::compile`]): the picture shows what they say.
    pub fn from_sources(sources: &SourceMap, pou: Option<&str>) -> Result<Self, DrawError> {
        Ok(ChartPicture {
            model: chart_model::chart_model(sources, pou)?,
            instance: None,
        })
    }

    /// The chart of the first program instance of `plc` whose PROGRAM has
    /// a chart body.
    pub fn of_program(plc: &Plc) -> Result<Self, DrawError> {
        for inst in &plc.image().programs {
            if let Ok(model) = chart_model::chart_model(plc.sources(), Some(&inst.type_name)) {
                return Ok(ChartPicture {
                    model,
                    instance: Some(inst.name.clone()),
                });
            }
        }
        Err(DrawError::NoChart)
    }

    /// What the picture shows: steps, transitions, actions.
    pub fn model(&self) -> &ChartModel {
        &self.model
    }

    /// The steps of this chart active in `plc` now (for a picture made by
    /// [`Self::of_program`]; empty otherwise).
    pub fn active_in(&self, plc: &Plc) -> Vec<String> {
        self.instance
            .as_deref()
            .and_then(|i| plc.active_steps(i))
            .unwrap_or_default()
    }

    /// The SVG drawing.
    pub fn to_svg(&self) -> String {
        chart_svg::chart_svg(&self.model, &[])
    }

    /// The SVG drawing with the steps named in `active` marked as active
    /// (filled, with a token).
    pub fn to_svg_active(&self, active: &[String]) -> String {
        chart_svg::chart_svg(&self.model, active)
    }
}

/// The SVG drawing of the chart of POU `pou` (of the only chart when
/// `None`) in the sources of `plc`.
pub fn draw_chart(plc: &Plc, pou: Option<&str>) -> Result<String, DrawError> {
    Ok(ChartPicture::from_sources(plc.sources(), pou)?.to_svg())
}
