//! The NC axes of a TwinCAT solution and the `AXIS_REF`s they are linked
//! to. The solution's `_Config/NC/NC.xti` lists its axes (`<Axis
//! File="Axis_X.xti" Id="2"/>`), each `_Config/NC/Axes/*.xti` holds one
//! axis' parameters (`<Velo Maximum="1"/>`, `<EncPara Offset="12">` with
//! `<SoftEndMinControl Enable="true" Range="4"/>`...), and the PLC's
//! `_Config/PLC/*.xti` (or the `.tsproj`) links its cyclic interface:
//! `<OwnerB Name="TINC^NC-Task 1 SAF^Axes^Axis_X">` holding `<Link
//! VarA="PlcTask Inputs^PRG_TEST.fbTest.stAxis.NcToPlc" .../>`. Only the
//! parameters plcrun's simulated axes act on are read (docs/twincat.md,
//! "Motion control").

use super::project::{plcproj_of, solution};
use crate::address::NcAxis;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// The configured NC axes of the solutions of the TwinCAT projects among
/// `paths` that are linked to an `AXIS_REF`, in the order of each
/// solution's axis list.
pub fn project_nc_axes(paths: &[PathBuf]) -> Vec<NcAxis> {
    let mut seen: Vec<PathBuf> = Vec::new();
    let mut axes = Vec::new();
    for path in paths {
        let Some(tsproj) = plcproj_of(path).as_deref().and_then(solution) else {
            continue;
        };
        if seen.contains(&tsproj) {
            continue;
        }
        if let Some(dir) = tsproj.parent() {
            axes.extend(solution_axes(dir, &tsproj));
        }
        seen.push(tsproj);
    }
    axes
}

/// The linked axes of the solution in `dir`.
fn solution_axes(dir: &Path, tsproj: &Path) -> Vec<NcAxis> {
    let config = dir.join("_Config");
    let Some(list) = read(&config.join("NC").join("NC.xti")) else {
        return Vec::new();
    };
    let mut links = HashMap::new();
    let mut sources = vec![tsproj.to_path_buf()];
    if let Ok(entries) = std::fs::read_dir(config.join("PLC")) {
        let mut plc: Vec<PathBuf> = entries.filter_map(|e| Some(e.ok()?.path())).collect();
        plc.sort();
        sources.extend(plc);
    }
    for source in sources {
        if let Some(text) = read(&source) {
            axis_links(&text, &mut links);
        }
    }
    let mut axes = Vec::new();
    for (file, id) in axis_files(&list) {
        let Some(text) = read(&config.join("NC").join("Axes").join(&file)) else {
            continue;
        };
        let stem = file.strip_suffix(".xti").unwrap_or(&file).to_string();
        let Some((name, parameters)) = axis_parameters(&text, &stem) else {
            continue;
        };
        if let Some(axis_ref) = links.get(&name.to_ascii_uppercase()) {
            axes.push(NcAxis {
                axis_ref: axis_ref.clone(),
                id,
                name,
                parameters,
            });
        }
    }
    axes
}

/// A file's text without its byte-order mark.
fn read(path: &Path) -> Option<String> {
    let text = std::fs::read_to_string(path).ok()?;
    Some(text.trim_start_matches('\u{FEFF}').to_string())
}

/// `NC.xti`'s axes: (file, id).
fn axis_files(text: &str) -> Vec<(String, u32)> {
    let Ok(doc) = crate::syntax::plcopen::read_xml(text) else {
        return Vec::new();
    };
    doc.descendants()
        .filter(|n| n.has_tag_name("Axis"))
        .filter_map(|n| {
            Some((
                n.attribute("File")?.to_string(),
                n.attribute("Id")?.parse().ok()?,
            ))
        })
        .collect()
}

/// The `AXIS_REF` path linked to each axis (by its name, upper case).
fn axis_links(text: &str, into: &mut HashMap<String, String>) {
    let Ok(doc) = crate::syntax::plcopen::read_xml(text) else {
        return;
    };
    for owner in doc.descendants().filter(|n| n.has_tag_name("OwnerB")) {
        let Some(axis) = owner
            .attribute("Name")
            .filter(|n| n.starts_with("TINC^"))
            .and_then(|n| n.rsplit_once("^Axes^"))
            .map(|(_, a)| a)
        else {
            continue;
        };
        for link in owner.children().filter(|n| n.has_tag_name("Link")) {
            let path = [link.attribute("VarA"), link.attribute("VarB")]
                .into_iter()
                .flatten()
                .filter_map(|end| end.split_once('^').map(|(_, p)| p.trim()))
                .find_map(|p| p.strip_suffix(".NcToPlc"));
            if let Some(path) = path {
                into.insert(axis.to_ascii_uppercase(), path.to_string());
            }
        }
    }
}

/// An axis file's name and the parameters it sets (`None` when it holds
/// no axis).
fn axis_parameters(text: &str, stem: &str) -> Option<(String, Vec<(String, String)>)> {
    let doc = crate::syntax::plcopen::read_xml(text).ok()?;
    let axis = doc.descendants().find(|n| n.has_tag_name("Axis"))?;
    let name = axis
        .children()
        .find(|n| n.has_tag_name("Name"))
        .and_then(|n| n.text())
        .map(str::trim)
        .filter(|n| !n.is_empty() && *n != "__FILENAME__")
        .unwrap_or(stem)
        .to_string();
    let mut parameters = Vec::new();
    for node in axis.descendants().filter(|n| n.is_element()) {
        let tag = node.tag_name().name();
        let parent = node.parent().map(|p| p.tag_name().name()).unwrap_or("");
        for attr in node.attributes() {
            let field = field_of(parent, tag, attr.name());
            if let Some((field, boolean)) = field {
                let value = attr.value();
                let literal = if boolean {
                    if value.eq_ignore_ascii_case("true") {
                        "1"
                    } else {
                        "0"
                    }
                    .to_string()
                } else if value.parse::<f64>().is_ok_and(f64::is_finite) {
                    value.to_string()
                } else {
                    continue;
                };
                parameters.push((field.to_string(), literal));
            }
        }
    }
    Some((name, parameters))
}

/// The `ST_AxisParameterSet` field an `.xti` attribute sets (and whether
/// it is a switch, written 1 or 0), for the element `tag` inside `parent`.
fn field_of(parent: &str, tag: &str, attr: &str) -> Option<(&'static str, bool)> {
    Some(match (parent, tag, attr) {
        ("AxisPara", "Velo", "Maximum") => ("fVeloMaximum", false),
        ("AxisPara", "Dynamic", "Acceleration") => ("fAcceleration", false),
        ("AxisPara", "Dynamic", "Deceleration") => ("fDeceleration", false),
        ("AxisPara", "Dynamic", "Jerk") => ("fJerk", false),
        ("AxisPara", "Dynamic", "AccelerationMaximum") => ("fAccelerationMax", false),
        ("AxisPara", "Dynamic", "DecelerationMaximum") => ("fDecelerationMax", false),
        ("AxisPara", "PositionAreaControl", "Enable") => ("bEnablePositionAreaControl", true),
        ("AxisPara", "PositionAreaControl", "Range") => ("fPositionAreaControlRange", false),
        (_, "EncPara", "Offset") => ("fEncOffset", false),
        (_, "EncPara", "ScaleFactorNumerator") => ("fEncScaleFactorNumerator", false),
        (_, "EncPara", "ScaleFactorDenominator") => ("fEncScaleFactorDenominator", false),
        (_, "EncPara", "ModuloFactor") => ("fEncModuloFactor", false),
        ("EncPara", "SoftEndMinControl", "Enable") => ("bEncEnableSoftEndMinControl", true),
        ("EncPara", "SoftEndMinControl", "Range") => ("fEncSoftEndMin", false),
        ("EncPara", "SoftEndMaxControl", "Enable") => ("bEncEnableSoftEndMaxControl", true),
        ("EncPara", "SoftEndMaxControl", "Range") => ("fEncSoftEndMax", false),
        ("EncPara", "ActPosCorrection", "Enable") => ("bEncEnablePosCorrection", true),
        _ => return None,
    })
}
