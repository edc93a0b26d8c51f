//! Pictures from the command line: `plcrun draw` (a chart as SVG) and the
//! `--svg` / `--svg-chart` outputs of a run, recorded by a cycle hook.

use super::args::{DrawArgs, RunArgs};
use super::{EXIT_COMPILE, EXIT_OK, EXIT_USAGE};
use plcrun::{
    ChartPicture, CheckOptions, Diagnostics, Session, TimingDiagram, check as check_sources,
    draw_sources,
};
use std::path::Path;
use std::sync::{Arc, Mutex, PoisonError};

fn write_file(path: &Path, text: &str) -> Result<(), String> {
    std::fs::write(path, text).map_err(|e| format!("cannot write `{}`: {e}", path.display()))
}

/// `plcrun draw FILES... [--program P] [-o OUT.svg]`: the chart of P (or
/// the only chart), or P's FBD/LD network (or every one when there is no
/// chart).
pub fn draw(args: &DrawArgs) -> i32 {
    let mut diags = Diagnostics::new();
    let sources = match args.reading.load(&args.files, &mut diags) {
        Ok(s) => s,
        Err(e) => {
            sayln!("error: {e}");
            return EXIT_USAGE;
        }
    };
    let report = check_sources(
        &sources,
        // Charts are drawn whatever their evolution rules: a chart with
        // GRAFCET forcing orders draws as well as an IEC one.
        &CheckOptions {
            grafcet: true,
            strict: args.reading.strict,
            addressing: args.reading.addressing,
            ..CheckOptions::default()
        },
    );
    diags.extend(report.diagnostics);
    say!("{}", diags.render(&sources));
    if diags.has_errors() {
        return EXIT_COMPILE;
    }
    let svg = match draw_sources(&sources, args.program.as_deref()) {
        Ok(svg) => svg,
        Err(e) => {
            sayln!("error: {e}");
            return EXIT_USAGE;
        }
    };
    match &args.output {
        Some(path) => {
            if let Err(e) = write_file(path, &svg) {
                sayln!("error: {e}");
                return EXIT_USAGE;
            }
        }
        None => print!("{svg}"),
    }
    EXIT_OK
}

/// What a run records for `--svg` and `--svg-chart`.
pub struct Pictures {
    timing: Option<Arc<Mutex<TimingDiagram>>>,
    chart: Option<ChartPicture>,
    /// The active steps at `--svg-chart-cycle`, once that cycle has run.
    active: Arc<Mutex<Option<Vec<String>>>>,
}

/// Sets up the recording asked for (none: `Ok(None)`), as the session's
/// cycle hook.
pub fn prepare(args: &RunArgs, session: &mut Session) -> Result<Option<Pictures>, String> {
    if args.svg.is_none() && args.svg_chart.is_none() {
        return Ok(None);
    }
    let timing = match &args.svg {
        Some(_) => Some(Arc::new(Mutex::new(
            TimingDiagram::for_plc(session.plc(), session.trace_names())
                .map_err(|e| format!("--svg: {e}"))?,
        ))),
        None => None,
    };
    let chart = match &args.svg_chart {
        Some(_) => {
            Some(ChartPicture::of_program(session.plc()).map_err(|e| format!("--svg-chart: {e}"))?)
        }
        None => None,
    };
    let active = Arc::new(Mutex::new(None));
    let (hook_timing, hook_active) = (timing.clone(), active.clone());
    let hook_chart = chart.clone();
    let at = args.svg_chart_cycle;
    session.add_cycle_hook(move |plc| {
        if let Some(t) = &hook_timing {
            t.lock().unwrap_or_else(PoisonError::into_inner).record(plc);
        }
        if let (Some(c), Some(n)) = (&hook_chart, at)
            && plc.cycle().checked_sub(1) == Some(n)
        {
            *hook_active.lock().unwrap_or_else(PoisonError::into_inner) = Some(c.active_in(plc));
        }
    });
    Ok(Some(Pictures {
        timing,
        chart,
        active,
    }))
}

/// Writes the pictures after the run.
pub fn finish(args: &RunArgs, pictures: Pictures, session: &Session) -> Result<(), String> {
    if let (Some(t), Some(path)) = (&pictures.timing, &args.svg) {
        let mut t = t.lock().unwrap_or_else(PoisonError::into_inner);
        t.set_end(session.plc().time());
        if let Some(c) = t.stopped_at() {
            sayln!(
                "warning: --svg: the timing diagram stops at cycle {c}: it holds at most {} value changes",
                plcrun::MAX_CHANGES
            );
        }
        write_file(path, &t.to_svg())?;
    }
    if let (Some(chart), Some(path)) = (&pictures.chart, &args.svg_chart) {
        let active = match args.svg_chart_cycle {
            None => chart.active_in(session.plc()),
            Some(n) => pictures
                .active
                .lock()
                .unwrap_or_else(PoisonError::into_inner)
                .clone()
                .ok_or_else(|| format!("--svg-chart-cycle {n}: the run ended before cycle {n}"))?,
        };
        write_file(path, &chart.to_svg_active(&active))?;
    }
    Ok(())
}
