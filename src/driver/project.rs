//! Project folders and TwinCAT `.plcproj` files given where source files
//! are expected: each becomes the list of source files it stands for.
//!
//! - A `.plcproj` (an MSBuild project) lists its sources as
//!   `<Compile Include="POUs\MAIN.TcPOU">` items; those plcrun reads
//!   (`.TcPOU`, `.TcDUT`, `.TcGVL`, `.TcIO`, `.TcTTO`) are loaded in the
//!   project's order. Visualisations, text lists and the like hold no code
//!   and are left out.
//! - A folder holding one `.plcproj` (at any depth) is that project; a
//!   folder holding several is an error naming them; a folder with none is
//!   every TwinCAT object and IEC source file in it (`.st`, `.il`, `.sfc`),
//!   in path order.
//! - A project that pins global data types of the TwinCAT type system
//!   (`<PinnedGlobalDataType Include="ST_X_IO"/>`) finds them in its `.tmc`
//!   (beside the `.plcproj`, named like it) or else in the solution's
//!   `.tsproj` (the folder above); the event classes of `TC_EVENTS` are
//!   read from those two and the `.tsproj`'s additional `.tmc` files
//!   (`<AdditionalTmcFile>`): [`TypeDescriptions`].

use std::io;
use std::path::{Path, PathBuf};

/// File extensions of the TwinCAT objects plcrun reads (compared ignoring
/// case).
const TWINCAT_OBJECTS: [&str; 5] = ["tcpou", "tcdut", "tcgvl", "tcio", "tctto"];
/// File extensions of textual IEC sources picked up in a folder.
const IEC_SOURCES: [&str; 3] = ["st", "il", "sfc"];
/// Folders TwinCAT writes its build products into: never sources.
const BUILD_FOLDERS: [&str; 3] = ["_Boot", "_CompileInfo", "_Libraries"];
/// Deepest folder nesting searched.
const MAX_DEPTH: usize = 16;

/// True when `path` names a project rather than one source file: a folder
/// or a `.plcproj` file.
pub(crate) fn is_project(path: &Path) -> bool {
    path.is_dir() || has_extension(path, &["plcproj"])
}

pub(crate) fn has_extension(path: &Path, exts: &[&str]) -> bool {
    path.extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| exts.iter().any(|x| e.eq_ignore_ascii_case(x)))
}

/// What a project is read from: its source files, and where the types it
/// takes from the TwinCAT type system are described.
pub(crate) struct ProjectFiles {
    /// The project's name: the `.plcproj`'s `<Name>`, else its file name
    /// without extension (a folder of plain sources: the folder's name).
    pub(crate) name: String,
    /// The source files, in the project's order.
    pub(crate) sources: Vec<PathBuf>,
    /// Its type descriptions (empty for a folder of sources).
    pub(crate) descriptions: TypeDescriptions,
}

/// The type descriptions of a `.plcproj`: the global data types it pins
/// from the type system, and the files that describe them and the event
/// classes. A file named here may be missing: it is then left out (a
/// pinned type is unknown where used).
#[derive(Default)]
pub(crate) struct TypeDescriptions {
    /// The `.tmc` beside the project, else the `.tsproj` above it: the
    /// pinned types are read from it.
    pub(crate) primary: Option<PathBuf>,
    /// The files read for event classes only: the `.tsproj` when the
    /// `.tmc` is the primary, then the `.tsproj`'s additional `.tmc` files.
    pub(crate) others: Vec<PathBuf>,
    /// The pinned types' names, as the `.plcproj` lists them.
    pub(crate) pinned: Vec<String>,
}

/// The source files `path` (a folder or a `.plcproj`) stands for.
pub(crate) fn source_files(path: &Path) -> io::Result<Vec<PathBuf>> {
    project_files(path).map(|p| p.sources)
}

/// The files `path` (a folder or a `.plcproj`) is read from.
pub(crate) fn project_files(path: &Path) -> io::Result<ProjectFiles> {
    if !path.is_dir() {
        return project_items(path);
    }
    let mut projects = Vec::new();
    let mut sources = Vec::new();
    walk(path, 0, &mut |file| {
        if has_extension(file, &["plcproj"]) {
            projects.push(file.to_path_buf());
        } else if has_extension(file, &TWINCAT_OBJECTS) || has_extension(file, &IEC_SOURCES) {
            sources.push(file.to_path_buf());
        }
    })?;
    match projects.len() {
        1 => project_items(&projects[0]),
        0 if sources.is_empty() => Err(io::Error::new(
            io::ErrorKind::NotFound,
            "the folder holds no .plcproj, no TwinCAT object (.TcPOU, .TcDUT, .TcGVL, .TcIO, .TcTTO) and no .st, .il or .sfc file",
        )),
        0 => {
            sources.sort();
            Ok(ProjectFiles {
                name: file_stem(path),
                sources,
                descriptions: TypeDescriptions::default(),
            })
        }
        _ => {
            projects.sort();
            let names: Vec<String> = projects.iter().map(|p| p.display().to_string()).collect();
            Err(io::Error::other(format!(
                "the folder holds {} TwinCAT projects: name one of {}",
                names.len(),
                names.join(", ")
            )))
        }
    }
}

/// The `.plcproj` a path stands for: itself, or the one project of a
/// folder (`None` for a source file or a folder of plain sources).
pub(crate) fn plcproj_of(path: &Path) -> Option<PathBuf> {
    if has_extension(path, &["plcproj"]) {
        return Some(path.to_path_buf());
    }
    if !path.is_dir() {
        return None;
    }
    let mut found = Vec::new();
    walk(path, 0, &mut |file| {
        if has_extension(file, &["plcproj"]) {
            found.push(file.to_path_buf());
        }
    })
    .ok()?;
    (found.len() == 1).then(|| found.remove(0))
}

/// Calls `found` for every file under `dir`, in name order, skipping
/// hidden folders and TwinCAT's build folders.
pub(crate) fn walk(dir: &Path, depth: usize, found: &mut dyn FnMut(&Path)) -> io::Result<()> {
    if depth > MAX_DEPTH {
        return Ok(());
    }
    let mut entries: Vec<PathBuf> = std::fs::read_dir(dir)?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .collect();
    entries.sort();
    for entry in entries {
        let name = entry.file_name().and_then(|n| n.to_str()).unwrap_or("");
        if entry.is_dir() {
            if !name.starts_with('.') && !BUILD_FOLDERS.contains(&name) {
                walk(&entry, depth + 1, found)?;
            }
        } else {
            found(&entry);
        }
    }
    Ok(())
}

/// The sources a `.plcproj` compiles, in its order, as paths next to it,
/// and the types it pins.
fn project_items(project: &Path) -> io::Result<ProjectFiles> {
    let text = std::fs::read_to_string(project)?;
    let text = text.trim_start_matches('\u{FEFF}');
    let doc = crate::syntax::plcopen::read_xml(text).map_err(|(_, e)| {
        io::Error::new(
            io::ErrorKind::InvalidData,
            format!("not a TwinCAT project: malformed XML: {e}"),
        )
    })?;
    if doc.root_element().tag_name().name() != "Project" {
        return Err(io::Error::new(
            io::ErrorKind::InvalidData,
            "not a TwinCAT project: its root element is not an MSBuild `<Project>`",
        ));
    }
    let folder = project.parent().unwrap_or(Path::new(""));
    let files: Vec<PathBuf> = doc
        .descendants()
        .filter(|n| n.has_tag_name("Compile") || n.has_tag_name("None"))
        .filter_map(|n| n.attribute("Include"))
        .map(|include| folder.join(include.replace('\\', "/")))
        .filter(|p| has_extension(p, &TWINCAT_OBJECTS))
        .collect();
    if files.is_empty() {
        return Err(io::Error::new(
            io::ErrorKind::NotFound,
            "the project compiles no POU, DUT, GVL, interface or task file",
        ));
    }
    let names: Vec<String> = doc
        .descendants()
        .filter(|n| n.has_tag_name("PinnedGlobalDataType"))
        .filter_map(|n| n.attribute("Include"))
        .map(|name| name.trim().to_string())
        .collect();
    let name = doc
        .descendants()
        .find(|n| {
            n.has_tag_name("Name") && n.parent().is_some_and(|p| p.has_tag_name("PropertyGroup"))
        })
        .and_then(|n| n.text())
        .map(str::trim)
        .filter(|n| !n.is_empty())
        .map_or_else(|| file_stem(project), str::to_string);
    Ok(ProjectFiles {
        name,
        sources: files,
        descriptions: type_descriptions(project, names),
    })
}

/// A path's last component without its extension.
fn file_stem(path: &Path) -> String {
    path.file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .unwrap_or_default()
}

/// Where a `.plcproj`'s types are described: its `.tmc` (TwinCAT writes it
/// beside the project, with the project's name), the one `.tsproj` of the
/// folder above (the solution's type system), and the additional `.tmc`
/// files that `.tsproj` names (event classes are often kept there).
fn type_descriptions(project: &Path, pinned: Vec<String>) -> TypeDescriptions {
    let tmc = project.with_extension("tmc");
    let tsproj = solution(project);
    let mut others: Vec<PathBuf> = Vec::new();
    let primary = if tmc.is_file() {
        others.extend(tsproj.clone());
        Some(tmc)
    } else {
        tsproj.clone()
    };
    if let Some(ts) = &tsproj {
        others.extend(additional_tmc_files(ts));
    }
    TypeDescriptions {
        primary,
        others,
        pinned,
    }
}

/// The one `.tsproj` of the folder above a `.plcproj`.
pub(crate) fn solution(project: &Path) -> Option<PathBuf> {
    let above = project.parent()?.parent()?;
    let mut found = std::fs::read_dir(above)
        .ok()?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| has_extension(p, &["tsproj"]));
    let first = found.next()?;
    found.next().is_none().then_some(first)
}

/// The files a `.tsproj` names as `<AdditionalTmcFile File="X.tmc"/>`,
/// relative to its folder, that are there.
fn additional_tmc_files(tsproj: &Path) -> Vec<PathBuf> {
    let Ok(text) = std::fs::read_to_string(tsproj) else {
        return Vec::new();
    };
    let Ok(doc) = crate::syntax::plcopen::read_xml(text.trim_start_matches('\u{FEFF}')) else {
        return Vec::new();
    };
    let folder = tsproj.parent().unwrap_or(Path::new(""));
    doc.descendants()
        .filter(|n| n.has_tag_name("AdditionalTmcFile"))
        .filter_map(|n| n.attribute("File"))
        .map(|f| folder.join(f.replace('\\', "/")))
        .filter(|p| p.is_file())
        .collect()
}
