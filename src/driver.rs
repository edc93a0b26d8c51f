//! The compile pipeline: source files → parse → check and lower → link and
//! verify. Everything that turns text into a runnable program goes through
//! here; the runtime, the command line and embedders call these functions
//! instead of assembling the stages themselves.

use crate::address::Addressing;
use crate::diagnostics::Diagnostics;
use crate::ir::verify::VerifiedImage;
use crate::progress::Progress;
use crate::sema;
/// What to build from the sources (the program to run, the implicit
/// task's cycle time, check only).
pub(crate) use crate::sema::CompileOptions;
/// Default limit of a program's data (512 MiB), beyond which E120.
pub(crate) use crate::sema::DEFAULT_MAX_DATA_BYTES;
use crate::source::encoding::SourceEncoding;
use crate::source::{FileId, SourceMap};
use crate::syntax::twincat::type_description;
use std::collections::HashSet;
use std::fmt;
use std::path::{Path, PathBuf};

mod address_map;
mod app_info;
mod event_classes;
mod io_links;
mod library_projects;
mod nc_axes;
mod project;
mod source_bytes;
pub(crate) mod twincat_library;
pub use io_links::project_io_links;
pub use library_projects::with_library_projects;
pub use nc_axes::project_nc_axes;
pub use source_bytes::add_source_bytes;

/// Diagnostic code of "several PROGRAMs and none chosen".
pub(crate) const AMBIGUOUS_PROGRAM: &str = "E208";

/// A source file could not be read.
#[derive(Debug)]
pub struct LoadError {
    /// The path as given.
    pub path: PathBuf,
    /// What the operating system said.
    pub error: std::io::Error,
}

impl fmt::Display for LoadError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "cannot read `{}`: {}", self.path.display(), self.error)
    }
}

impl std::error::Error for LoadError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        Some(&self.error)
    }
}

/// The [`LoadError`] of an I/O error on `path`.
fn load_error(path: &Path) -> impl FnOnce(std::io::Error) -> LoadError + '_ {
    move |error| LoadError {
        path: path.to_path_buf(),
        error,
    }
}

/// Reads every file into a source map, named by its path as given, as
/// UTF-8: a file that is not is kept (invalid bytes replaced by U+FFFD)
/// and reported as an `E011` diagnostic, so that its other errors are
/// still found. [`load_files_with`] reads other encodings or detects them
/// (as the command line does).
pub fn load_files<P: AsRef<Path>>(
    paths: &[P],
    diags: &mut Diagnostics,
) -> Result<SourceMap, LoadError> {
    load_files_with(paths, SourceEncoding::Utf8, diags)
}

/// Reads every file into a source map, named by its path as given and read
/// in `encoding` ([`add_source_bytes`] says what is reported: W020 for a
/// file detected as Windows-1252, E011 for one that should be UTF-8 and is
/// not); a file that cannot be read at all is a [`LoadError`]. A folder or
/// a TwinCAT `.plcproj` stands for the files of its project (the `.plcproj`
/// items plcrun reads, in order; in a folder without one, every TwinCAT
/// object and `.st`/`.il`/`.sfc` file, in path order): `docs/twincat.md`.
pub fn load_files_with<P: AsRef<Path>>(
    paths: &[P],
    encoding: SourceEncoding,
    diags: &mut Diagnostics,
) -> Result<SourceMap, LoadError> {
    let mut sources = SourceMap::new();
    let mut events = HashSet::new();
    let mut classes = Vec::new();
    let mut shadowing = LibraryShadowing::default();
    let mut app = AppInfoUse::default();
    let mut system_classes: Vec<&str> = Vec::new();
    for path in paths {
        let path = path.as_ref();
        let is_project = project::is_project(path);
        let (files, descriptions) = if is_project {
            let project = project::project_files(path).map_err(load_error(path))?;
            app.project.get_or_insert(project.name);
            (project.sources, project.descriptions)
        } else {
            (
                vec![path.to_path_buf()],
                project::TypeDescriptions::default(),
            )
        };
        let library = is_project && shadowing.seen_project;
        shadowing.seen_project |= is_project;
        let mut names = SourceNames::default();
        for file in &files {
            let bytes = std::fs::read(file).map_err(load_error(file))?;
            if !shadowing.keeps(&bytes, library) {
                continue;
            }
            names.add(&bytes);
            let id = add_source_bytes(
                &mut sources,
                file.display().to_string(),
                &bytes,
                encoding,
                diags,
            );
            if library {
                sources.mark_library(id);
            }
        }
        for (name, text) in description_sources(&descriptions, &names, &mut events)? {
            classes.extend(type_description::event_classes(&text));
            sources.add(name, text);
        }
        app.named |= is_project && names.used.contains(APP_INFO);
        for class in event_classes::system_classes_named(&names.used) {
            if !system_classes.contains(&class) {
                system_classes.push(class);
            }
        }
    }
    if let Some(text) = event_classes::event_classes_source(&classes, &system_classes) {
        sources.add(event_classes::EVENT_CLASSES_SOURCE, text);
    }
    if let Some(text) = app.source() {
        sources.add(app_info::APP_INFO_SOURCE, text);
    }
    Ok(sources)
}

/// TwinCAT's application information, as the sources name it.
const APP_INFO: &str = "_APPINFO";

/// Whether the TwinCAT projects loaded name `_AppInfo`, and the first
/// one's name.
#[derive(Default)]
struct AppInfoUse {
    /// The first project's name.
    project: Option<String>,
    /// A project's sources name `_AppInfo`.
    named: bool,
}

impl AppInfoUse {
    /// The source declaring `_AppInfo`, when a project names it.
    fn source(&self) -> Option<String> {
        let name = self.project.as_deref().filter(|_| self.named)?;
        Some(app_info::app_info_source(name))
    }
}

/// What a project's sources name and declare (upper case): the global data
/// types of its type system that it uses are taken from there
/// ([`type_description::persistent_types_used`]).
#[derive(Default)]
struct SourceNames {
    /// Every identifier of the sources.
    used: HashSet<String>,
    /// The objects (POUs, types, lists, interfaces) the sources are.
    declared: HashSet<String>,
}

impl SourceNames {
    /// Adds a source file's names.
    fn add(&mut self, bytes: &[u8]) {
        let text = String::from_utf8_lossy(bytes);
        crate::syntax::twincat::identifiers(&text, &mut self.used);
        if let Some(name) = crate::syntax::twincat::object_name(&text) {
            self.declared.insert(name.to_ascii_uppercase());
        }
    }

    /// The names of the files of a project.
    fn of(files: &[PathBuf]) -> Result<SourceNames, LoadError> {
        let mut names = SourceNames::default();
        for file in files {
            names.add(&std::fs::read(file).map_err(load_error(file))?);
        }
        Ok(names)
    }
}

/// How the TwinCAT projects after the first one — the libraries
/// `--library-path` resolves (`with_library_projects`) — are loaded: a
/// library's objects live in its namespace in TwinCAT, where the project's
/// own names come first, and it has no tasks. So a library's task files
/// are left out, and so is an object (POU, type, list, interface) of a
/// name the files before it declare (its test program `PRG_TEST`, the
/// implicit checks `CheckBounds`...): the project's own wins.
#[derive(Default)]
struct LibraryShadowing {
    /// A TwinCAT project was loaded: the next ones are its libraries.
    seen_project: bool,
    /// The objects declared so far (upper case).
    declared: HashSet<String>,
}

impl LibraryShadowing {
    /// Whether the file of `bytes` is loaded (`library`: of a library).
    fn keeps(&mut self, bytes: &[u8], library: bool) -> bool {
        let text = String::from_utf8_lossy(bytes);
        if library && crate::syntax::twincat::is_task_file(&text) {
            return false;
        }
        match crate::syntax::twincat::object_name(&text) {
            Some(name) => self.declared.insert(name.to_ascii_uppercase()) || !library,
            None => true,
        }
    }
}

/// The sources a TwinCAT project (a folder or a `.plcproj`) adds from its
/// type descriptions (docs/twincat.md), as [`load_files_with`] adds them:
/// each description's name and its text narrowed to the global data types
/// the project pins and to the event classes of `TC_EVENTS`. Empty when
/// the project pins nothing and describes no event class.
pub fn type_description_sources(path: &Path) -> Result<Vec<(String, String)>, LoadError> {
    let project = project::project_files(path).map_err(load_error(path))?;
    let names = SourceNames::of(&project.sources)?;
    let mut sources = description_sources(&project.descriptions, &names, &mut HashSet::new())?;
    let classes: Vec<_> = sources
        .iter()
        .flat_map(|(_, text)| type_description::event_classes(text))
        .collect();
    let system = event_classes::system_classes_named(&names.used);
    if let Some(text) = event_classes::event_classes_source(&classes, &system) {
        sources.push((event_classes::EVENT_CLASSES_SOURCE.to_string(), text));
    }
    let app = AppInfoUse {
        project: Some(project.name),
        named: names.used.contains(APP_INFO),
    };
    if let Some(text) = app.source() {
        sources.push((app_info::APP_INFO_SOURCE.to_string(), text));
    }
    Ok(sources)
}

/// The narrowed sources of `descriptions`: the primary one keeps the
/// pinned types, each keeps the event classes no earlier one declared
/// (`events`, upper case, across the projects of one load). A file that
/// keeps nothing is left out; one that is not XML is kept whole when types
/// are pinned from it, for the reader to report.
fn description_sources(
    descriptions: &project::TypeDescriptions,
    names: &SourceNames,
    events: &mut HashSet<String>,
) -> Result<Vec<(String, String)>, LoadError> {
    let primary = descriptions
        .primary
        .iter()
        .map(|p| (p, &descriptions.pinned[..]));
    let others = descriptions.others.iter().map(|p| (p, &[][..]));
    // A type the project declares or pins, or one an earlier description
    // gave, is not taken again.
    let mut shadowed = names.declared.clone();
    shadowed.extend(descriptions.pinned.iter().map(|n| n.to_ascii_uppercase()));
    let mut out = Vec::new();
    for (path, pinned) in primary.chain(others) {
        let bytes = std::fs::read(path).map_err(load_error(path))?;
        let text = String::from_utf8_lossy(&bytes);
        let used = type_description::persistent_types_used(&text, &names.used, &shadowed);
        shadowed.extend(used.iter().cloned());
        let wanted: Vec<String> = pinned.iter().cloned().chain(used).collect();
        let kept = match type_description::narrowed(&text, &wanted, events) {
            Some((_, 0)) => continue,
            Some((narrowed, _)) => narrowed,
            None if wanted.is_empty() => continue,
            None => text.into_owned(),
        };
        out.push((path.display().to_string(), kept));
    }
    Ok(out)
}

/// The source files `paths` stand for, in the order [`load_files_with`]
/// reads them: a folder or a TwinCAT `.plcproj` is expanded into the files
/// of its project, any other path is kept.
pub fn project_files<P: AsRef<Path>>(paths: &[P]) -> Result<Vec<PathBuf>, LoadError> {
    let mut files = Vec::new();
    for path in paths {
        let path = path.as_ref();
        if project::is_project(path) {
            let items = project::source_files(path).map_err(load_error(path))?;
            files.extend(items);
        } else {
            files.push(path.to_path_buf());
        }
    }
    Ok(files)
}

/// Parses and checks every file of `sources`, reporting into `diags`;
/// returns the linked image when there is no error.
///
/// The work runs on a thread of its own with a [`COMPILE_STACK`]-byte
/// stack, so that compiling never depends on the caller's stack: a host's
/// 2 MiB worker thread compiles the same programs as the command line. The
/// recursive walks inside are bounded by the nesting limits of
/// [`crate::syntax::depth`] and of the declaration nesting (E122), which fit
/// in that stack with a wide margin.
pub(crate) fn compile(
    sources: &SourceMap,
    options: &CompileOptions,
    diags: &mut Diagnostics,
) -> Option<VerifiedImage> {
    compile_reporting(sources, options, diags, &())
}

/// [`compile`], reporting each file parsed, then the check, to `progress`.
pub(crate) fn compile_reporting(
    sources: &SourceMap,
    options: &CompileOptions,
    diags: &mut Diagnostics,
    progress: &dyn Progress,
) -> Option<VerifiedImage> {
    // A source this small cannot nest deeply enough to need the big stack
    // (a few hundred levels at most fit in it), and a thread with a 256 MiB
    // stack is not free: under valgrind each one costs about half a second.
    let bytes: usize = sources.files().iter().map(|f| f.text.len()).sum();
    if bytes <= INLINE_COMPILE_BYTES {
        return compile_here(sources, options, diags, progress);
    }
    std::thread::scope(|scope| {
        let worker = std::thread::Builder::new()
            .name("plcrun-compile".into())
            .stack_size(COMPILE_STACK)
            .spawn_scoped(scope, || {
                let mut own = Diagnostics::new();
                let image = compile_here(sources, options, &mut own, progress);
                (image, own)
            });
        match worker {
            Ok(handle) => match handle.join() {
                Ok((image, own)) => {
                    diags.extend(own);
                    if diags.has_errors() { None } else { image }
                }
                Err(panic) => std::panic::resume_unwind(panic),
            },
            // No thread available (resource limits): compile on this one.
            Err(_) => compile_here(sources, options, diags, progress),
        }
    })
}

/// Stack of the compiling thread: 256 MiB of address space, of which only
/// the pages a deep program touches are ever used.
pub const COMPILE_STACK: usize = 256 << 20;

/// Sources of at most this many bytes in all compile on the caller's
/// thread: even a chain of one-line alias types this long nests less than
/// a 2 MiB stack holds (tests/limits.rs checks it on such a thread).
const INLINE_COMPILE_BYTES: usize = 2 << 10;

/// [`compile`] on the current thread.
fn compile_here(
    sources: &SourceMap,
    options: &CompileOptions,
    out: &mut Diagnostics,
    progress: &dyn Progress,
) -> Option<VerifiedImage> {
    let mut found = Diagnostics::new();
    let image = compile_units(sources, options, &mut found, progress);
    out.extend(twincat_library::drop_expected_warnings(sources, found));
    if out.has_errors() { None } else { image }
}

/// [`compile_here`] before the library's warnings are dropped.
fn compile_units(
    sources: &SourceMap,
    options: &CompileOptions,
    diags: &mut Diagnostics,
    progress: &dyn Progress,
) -> Option<VerifiedImage> {
    let files = sources.files();
    // One step per file parsed, and one for the check of them all.
    let total = files.len() as u64 + 1;
    let mut units = Vec::with_capacity(files.len());
    for (i, file) in files.iter().enumerate() {
        progress.report(i as u64, total, &file.name);
        units.push(crate::syntax::parse_source(FileId(i as u32), file, diags));
    }
    progress.report(total - 1, total, "check");
    crate::syntax::twincat::merge_task_configurations(&mut units, |i| {
        crate::syntax::twincat::is_task_file(&files[i].text)
    });
    let image = sema::compile(&units, options, diags);
    crate::syntax::recovery::drop_cascades(sources, &units, diags);
    if options.strict {
        diags.make_strict();
    }
    progress.report(total, total, "done");
    if diags.has_errors() { None } else { image }
}

/// What `plcrun check` does.
#[derive(Debug, Clone, Default)]
pub struct CheckOptions {
    /// The PROGRAM to build when the sources hold several (matters only
    /// with `ir_listing`).
    pub program: Option<String>,
    /// Also build the runnable program and list its IR (a debugging aid;
    /// the sources must then hold one runnable program).
    pub ir_listing: bool,
    /// Also build the runnable program and list its located variables
    /// with their addresses ([`crate::ir::image::Image::address_map`]).
    pub address_map: bool,
    /// Check charts for IEC 60848 evolution (`--grafcet`): forcing orders
    /// are accepted.
    pub grafcet: bool,
    /// Most bytes of program data; 0 means the default (512 MiB). Beyond
    /// it: E120.
    pub max_data_bytes: usize,
    /// Pure IEC 61131-3 (`--strict`): every compatibility-extension
    /// warning (`W300`-`W399`) is an error with the same code.
    pub strict: bool,
    /// How direct addresses are numbered (`--addressing`), for the overlap
    /// warning W204; `None`: chosen from the sources (`byte` for S7-200
    /// STL, `openplc` for PLCopen XML from the OpenPLC Editor or Beremiz,
    /// `iec` otherwise).
    pub addressing: Option<Addressing>,
}

/// The files of `sources` written in the CODESYS V3 / TwinCAT 3 dialect:
/// TwinCAT project files, PLCopen XML exported by CODESYS, and plcrun's
/// own TwinCAT library. CODESYS's implicit integer conversions (W490) are
/// accepted in them only.
pub(crate) fn codesys_files(sources: &SourceMap) -> Vec<FileId> {
    let dialect = |name: &str, text: &str| {
        name == twincat_library::LIBRARY_SOURCE
            || crate::syntax::twincat::is_twincat(text)
            || (crate::syntax::plcopen::is_plcopen(text)
                && crate::syntax::plcopen::origin::written_by_codesys(text))
    };
    (0..sources.files().len())
        .filter(|&i| dialect(&sources.files()[i].name, &sources.files()[i].text))
        .map(|i| FileId(i as u32))
        .collect()
}

/// The CODESYS-dialect files but plcrun's TwinCAT library: the user's
/// TwinCAT code (its STRING is 80 characters long by default, a project's
/// implicit checks apply to it...).
pub(crate) fn checked_files(sources: &SourceMap) -> Vec<FileId> {
    codesys_files(sources)
        .into_iter()
        .filter(|f| sources.files()[f.0 as usize].name != twincat_library::LIBRARY_SOURCE)
        .collect()
}

/// The files of the library projects loaded with an application
/// (`SourceFile::is_library`): TwinCAT runs no implicit check in them.
pub(crate) fn library_files(sources: &SourceMap) -> Vec<FileId> {
    (0..sources.files().len())
        .filter(|&i| sources.files()[i].is_library())
        .map(|i| FileId(i as u32))
        .collect()
}

/// The addressing convention for `sources` when none is given
/// (`docs/runtime.md`, "Addressing"): `byte` when a file is S7-200 STL,
/// `openplc` when a PLCopen project comes from the OpenPLC Editor or
/// Beremiz, `iec` otherwise.
pub fn addressing_of(sources: &SourceMap) -> Addressing {
    let files = sources.files();
    if files
        .iter()
        .any(|f| crate::syntax::s7::recognise(&f.name, &f.text))
    {
        return Addressing::Byte;
    }
    if files.iter().any(|f| {
        crate::syntax::plcopen::is_plcopen(&f.text)
            && crate::syntax::plcopen::origin::written_by_matiec_tools(&f.text)
    }) {
        return Addressing::OpenPlc;
    }
    Addressing::Iec
}

/// The outcome of [`check`].
#[derive(Debug, Clone)]
pub struct CheckReport {
    /// Every error and warning, in the order found.
    pub diagnostics: Diagnostics,
    /// The IR listing of every code block, when asked for and the sources
    /// have no error.
    pub ir_listing: Option<String>,
    /// The located variables and their addresses, when asked for and the
    /// sources have no error.
    pub address_map: Option<String>,
}

impl CheckReport {
    /// True when there is no error (warnings allowed).
    pub fn is_ok(&self) -> bool {
        !self.diagnostics.has_errors()
    }
}

/// Parses and checks sources without running them. Without
/// `ir_listing`, a set of declarations with no PROGRAM is fine.
pub fn check(sources: &SourceMap, options: &CheckOptions) -> CheckReport {
    check_reporting(sources, options, &())
}

/// [`check`], reporting each file parsed and then the check to `progress`
/// (for a progress bar over a large project).
pub fn check_reporting(
    sources: &SourceMap,
    options: &CheckOptions,
    progress: &dyn Progress,
) -> CheckReport {
    let mut diagnostics = Diagnostics::new();
    let mut extended = sources.clone();
    twincat_library::add_library(&mut extended);
    let build = CompileOptions {
        program: options.program.clone(),
        cycle_time: 10_000_000,
        check_only: !(options.ir_listing || options.address_map),
        host_pous: Vec::new(),
        grafcet: options.grafcet,
        max_data_bytes: options.max_data_bytes,
        strict: options.strict,
        unoptimized: false,
        addressing: options.addressing.unwrap_or_else(|| addressing_of(sources)),
        codesys_files: codesys_files(&extended),
        checked_files: checked_files(&extended),
        library_files: library_files(&extended),
    };
    // The library's own diagnostics are dropped or moved into the given
    // files by the compile (twincat_library.rs), so every one renders
    // with `sources`.
    let image = compile_reporting(&extended, &build, &mut diagnostics, progress);
    let ir_listing = image
        .as_ref()
        .filter(|_| options.ir_listing)
        .map(|i| i.dump());
    let address_map = image
        .as_ref()
        .filter(|_| options.address_map)
        .map(|i| address_map::address_map(i));
    CheckReport {
        diagnostics,
        ir_listing,
        address_map,
    }
}

#[cfg(test)]
mod tests {
    use crate::elementary::ElemType;

    /// Literal texts of every shape, including malformed ones.
    fn corpus() -> Vec<String> {
        let mut texts: Vec<String> = [
            "TRUE",
            "false",
            "True",
            "0",
            "1",
            "2",
            "-1",
            "+1",
            "- 5",
            "+ 2.5",
            "42",
            "-42",
            "1_000",
            "1__0",
            "_1",
            "1_",
            "32767",
            "32768",
            "-32768",
            "-32769",
            "65535",
            "65536",
            "255",
            "256",
            "-0",
            "16#FF",
            "16#ff",
            "16#",
            "16#_F",
            "2#1010",
            "8#17",
            "8#18",
            "3#12",
            "-16#FF",
            "16#FFFF_FFFF_FFFF_FFFF",
            "16#1_0000_0000_0000_0000",
            "340282366920938463463374607431768211455",
            "1.5",
            "-1.5",
            "1.",
            ".5",
            "1e3",
            "1E-3",
            "1.5e+3",
            "1e",
            "1.5.5",
            "3.4e38",
            "3.5e38",
            "1e308",
            "1e309",
            "-0.0",
            "0.1",
            "INT#5",
            "INT#-5",
            "int#32768",
            "SINT#-128",
            "SINT#128",
            "USINT#255",
            "UINT#-1",
            "DINT#16#7FFFFFFF",
            "WORD#16#FF",
            "WORD#-1",
            "BYTE#256",
            "LWORD#1",
            "REAL#1.5",
            "REAL#2",
            "LREAL#1e300",
            "REAL#1e300",
            "BOOL#1",
            "BOOL#0",
            "BOOL#2",
            "BOOL#TRUE",
            "BOOL#yes",
            "INT#1.5",
            "INT#",
            "INT#TRUE",
            "-INT#5",
            "MyEnum#Red",
            "Red",
            "Color#Red#x",
            "STRING#'x'",
            "INT#'x'",
            "T#1s",
            "t#1.5s",
            "T#-2ms",
            "-T#2ms",
            "TIME#1h2m3s",
            "T#1d_2h",
            "T#5",
            "T#",
            "LT#5us",
            "LTIME#1ns",
            "D#2024-01-31",
            "DATE#2024-02-30",
            "D#1969-12-31",
            "LD#2000-02-29",
            "TOD#12:30:15",
            "TOD#12:30:15.5",
            "TIME_OF_DAY#23:59:59.999",
            "TOD#24:00:00",
            "LTOD#00:00:00.000000001",
            "DT#2024-01-31-12:30:15",
            "DATE_AND_TIME#1970-01-01-00:00:00",
            "LDT#2024-01-31-12:30:15.25",
            "'A'",
            "'AB'",
            "''",
            "'$41'",
            "'$'",
            "'$''",
            "'a",
            "\"W\"",
            "\"$0041\"",
            "'x' 'y'",
            "1 2",
            "%IX0.1",
            "x.y",
            "",
            "   ",
            "#",
            "INT #5",
            "16 #FF",
            "T# 1s",
            "1h",
            "abc_1",
            "_x",
            "TRUE1",
            "IF",
            "END_IF",
            "NOT TRUE",
            "(1)",
        ]
        .iter()
        .map(|s| s.to_string())
        .collect();
        // Padding with blanks changes nothing.
        let padded: Vec<String> = texts.iter().map(|t| format!("  {t}\t")).collect();
        texts.extend(padded);
        texts
    }

    /// `text` as a value of `ty` read the compiler's way: the lexer, the
    /// prefix check, the encoding of an AST literal.
    fn through_the_lexer(text: &str, ty: ElemType) -> Option<u64> {
        use crate::sema::consts::{Const, literal_to_slot, typed_literal};
        let lit = crate::syntax::parse_literal(text.trim()).ok()?;
        if let Some(prefix) = typed_literal(&lit)
            && prefix != ty
            && !prefix.widens_to(ty)
        {
            return None;
        }
        match literal_to_slot(&lit.value, ty).ok()? {
            Const::Bits(b) => Some(b),
            _ => None,
        }
    }

    /// The runtime's lexer-free reading of a literal agrees with the
    /// compiler's reading of the same text through the lexer, for every
    /// elementary type. (One deliberate difference: a value's text holds no
    /// comments, so `1 (* c *)` is not the number 1 at run time.)
    #[test]
    fn runtime_literals_read_as_the_compiler_reads_them() {
        use crate::value::text::parse_scalar;
        let mut differences = Vec::new();
        let mut accepted = 0;
        for text in corpus() {
            for ty in ElemType::ALL {
                if ty.is_string() {
                    continue;
                }
                let by_lexer = through_the_lexer(&text, ty);
                let without = parse_scalar(&text, ty);
                accepted += usize::from(without.is_some());
                if by_lexer != without {
                    differences.push(format!(
                        "{text:?} as {ty}: lexer {by_lexer:?}, value {without:?}"
                    ));
                }
            }
        }
        assert!(differences.is_empty(), "{}", differences.join("\n"));
        assert!(
            accepted > 500,
            "only {accepted} accepted: the corpus lost its valid literals"
        );
    }
}
