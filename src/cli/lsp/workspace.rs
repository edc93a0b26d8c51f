//! The projects behind the open documents. A document belongs to the
//! project of the nearest `plcrun.toml` (its sources) or TwinCAT `.plcproj`
//! above it; a file in neither is a project of its own. Each project is
//! analysed as one compilation, open documents read from the editor's
//! text, the others from disk, and re-analysed after an edit.

use super::super::project;
use super::super::run::check_as_cli;
use plcrun::{
    Analysis, CheckOptions, Diagnostics, FileId, SourceEncoding, SourceMap, add_source_bytes,
    project_files, type_description_sources,
};
use std::collections::HashMap;
use std::path::{Path, PathBuf};

/// A project: the files compiled together and their analysis.
pub struct Project {
    /// The source files, in compile order.
    pub files: Vec<PathBuf>,
    /// Sources that are not files of their own: the types and event
    /// classes a TwinCAT project takes from its type descriptions, as
    /// [`type_description_sources`] reads them.
    extra: Vec<(String, String)>,
    /// How they are checked (the project file's strictness and addressing).
    options: CheckOptions,
    /// How files read from disk are decoded.
    encoding: SourceEncoding,
    /// The analysis of the current texts; `None` after an edit.
    analysis: Option<Analysis>,
    /// Why the project's own description could not be read, shown on its
    /// first file.
    pub problem: Option<String>,
}

impl Project {
    /// The analysis of the project's current texts.
    pub fn analysis(&mut self, open: &HashMap<PathBuf, String>) -> &Analysis {
        if self.analysis.is_none() {
            self.analysis = Some(analyse(
                &self.files,
                &self.extra,
                &self.options,
                self.encoding,
                open,
            ));
        }
        self.analysis.as_ref().expect("analysed above")
    }

    /// The id of `path` in the analysis.
    pub fn file_id(&self, path: &Path) -> Option<FileId> {
        self.files
            .iter()
            .position(|f| f == path)
            .map(|i| FileId(i as u32))
    }
}

/// Reads and analyses `files`, then the `extra` sources.
fn analyse(
    files: &[PathBuf],
    extra: &[(String, String)],
    options: &CheckOptions,
    encoding: SourceEncoding,
    open: &HashMap<PathBuf, String>,
) -> Analysis {
    let mut sources = SourceMap::new();
    let mut diags = Diagnostics::new();
    for path in files {
        let name = path.display().to_string();
        match open.get(path) {
            Some(text) => {
                sources.add(name, text.clone());
            }
            None => {
                let bytes = std::fs::read(path).unwrap_or_default();
                add_source_bytes(&mut sources, name, &bytes, encoding, &mut diags);
            }
        }
    }
    for (name, text) in extra {
        sources.add(name.clone(), text.clone());
    }
    // The TcUnit form of the check fails only where there is nothing to
    // test; the plain check then says all there is to say.
    let report =
        check_as_cli(&sources, options, &()).unwrap_or_else(|_| plcrun::check(&sources, options));
    diags.extend(report.diagnostics);
    Analysis::with_diagnostics(sources, diags)
}

/// Every project the editor has touched, and the open documents.
#[derive(Default)]
pub struct Workspace {
    /// The folders the editor opened (a project file is looked for up to
    /// them).
    pub roots: Vec<PathBuf>,
    /// Open documents' texts, by path.
    pub open: HashMap<PathBuf, String>,
    /// Projects by the path of what describes them (the project file, the
    /// `.plcproj`, or the lone source file).
    pub projects: HashMap<PathBuf, Project>,
    /// Which project each file was found in.
    owner: HashMap<PathBuf, PathBuf>,
}

impl Workspace {
    /// The key of the project `path` belongs to, found (and loaded) on
    /// first use.
    pub fn project_of(&mut self, path: &Path) -> PathBuf {
        if let Some(key) = self.owner.get(path) {
            return key.clone();
        }
        let project = self.discover(path);
        let key = project.0;
        for file in &project.1.files {
            self.owner.insert(file.clone(), key.clone());
        }
        self.owner.insert(path.to_path_buf(), key.clone());
        self.projects.entry(key.clone()).or_insert(project.1);
        key
    }

    /// A workspace over the folders `roots`.
    pub fn new(roots: Vec<PathBuf>) -> Workspace {
        Workspace {
            roots,
            ..Workspace::default()
        }
    }

    /// Marks the project of `path` for re-analysis; returns its key.
    pub fn touch(&mut self, path: &Path) -> PathBuf {
        let key = self.project_of(path);
        if let Some(p) = self.projects.get_mut(&key) {
            p.analysis = None;
        }
        key
    }

    /// Forgets the projects described by `path` (a project file changed
    /// on disk): they are found again on next use.
    pub fn forget_description(&mut self, path: &Path) {
        if self.projects.remove(path).is_some() {
            self.owner.retain(|_, key| key != path);
        }
    }

    fn discover(&self, path: &Path) -> (PathBuf, Project) {
        let lone = |problem: Option<String>| Project {
            files: vec![path.to_path_buf()],
            extra: Vec::new(),
            options: CheckOptions::default(),
            encoding: SourceEncoding::Detect,
            analysis: None,
            problem,
        };
        for folder in path.ancestors().skip(1) {
            let manifest = folder.join(project::DEFAULT_NAME);
            if manifest.is_file() {
                return match project::load(&manifest) {
                    Ok(p) if p.sources.iter().any(|s| same_file(s, path)) => {
                        let reading = &p.run.reading;
                        let files: Vec<PathBuf> = p.sources.iter().map(|s| absolute(s)).collect();
                        let project = Project {
                            files,
                            extra: Vec::new(),
                            options: CheckOptions {
                                strict: reading.strict,
                                addressing: reading.addressing,
                                ..CheckOptions::default()
                            },
                            encoding: reading.encoding,
                            analysis: None,
                            problem: None,
                        };
                        (manifest, project)
                    }
                    // A file the project does not list is checked alone.
                    Ok(_) => (path.to_path_buf(), lone(None)),
                    Err(rendered) => (path.to_path_buf(), lone(Some(rendered))),
                };
            }
            if let Some(plcproj) = plcproj_in(folder)
                && let Ok(files) = project_files(&[&plcproj])
            {
                let files: Vec<PathBuf> = files.iter().map(|f| absolute(f)).collect();
                if files.iter().any(|f| f == path) {
                    let project = Project {
                        files,
                        // The types the project pins and its event
                        // classes (docs/twincat.md).
                        extra: type_description_sources(&plcproj).unwrap_or_default(),
                        options: CheckOptions::default(),
                        encoding: SourceEncoding::Detect,
                        analysis: None,
                        problem: None,
                    };
                    return (plcproj, project);
                }
            }
            if self.roots.iter().any(|r| r == folder) {
                break;
            }
        }
        (path.to_path_buf(), lone(None))
    }
}

/// The one `.plcproj` of `folder`, if it has exactly one.
fn plcproj_in(folder: &Path) -> Option<PathBuf> {
    let mut found = std::fs::read_dir(folder)
        .ok()?
        .filter_map(|e| e.ok().map(|e| e.path()))
        .filter(|p| {
            p.extension()
                .and_then(|e| e.to_str())
                .is_some_and(|e| e.eq_ignore_ascii_case("plcproj"))
        });
    let first = found.next()?;
    found.next().is_none().then_some(first)
}

/// `path` made canonical where it exists (as project files list theirs).
pub fn absolute(path: &Path) -> PathBuf {
    std::fs::canonicalize(path).unwrap_or_else(|_| path.to_path_buf())
}

fn same_file(a: &Path, b: &Path) -> bool {
    absolute(a) == absolute(b)
}
