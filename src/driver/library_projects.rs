//! Libraries a TwinCAT project references that are themselves TwinCAT
//! projects in source form (SLAC's `LCLS General`, referenced by PMPS as
//! `<PlaceholderReference Include="LCLS General">`): given folders to
//! search (`--library-path`), each reference is resolved to the `.plcproj`
//! whose `<Title>` (or else `<Name>`) is the library's name, and that
//! project is loaded with the ones given, as are the libraries it
//! references in turn. A reference found nowhere is left to plcrun's own
//! TwinCAT library or reported where a symbol of it is used.

use super::project::{has_extension, plcproj_of, walk};
use std::collections::HashMap;
use std::io;
use std::path::{Path, PathBuf};

/// `paths`, followed by the library projects under `search` that the
/// TwinCAT projects among them reference, directly or through another
/// library, each once and after the project that first references it.
pub fn with_library_projects(paths: &[PathBuf], search: &[PathBuf]) -> io::Result<Vec<PathBuf>> {
    let mut out: Vec<PathBuf> = paths.to_vec();
    if search.is_empty() {
        return Ok(out);
    }
    let catalogue = library_catalogue(search)?;
    let mut next = 0;
    while next < out.len() {
        let path = out[next].clone();
        next += 1;
        let Some(plcproj) = plcproj_of(&path) else {
            continue;
        };
        for name in references(&plcproj)? {
            let Some(found) = catalogue.get(&name.to_ascii_uppercase()) else {
                continue;
            };
            let known = out
                .iter()
                .filter_map(|p| plcproj_of(p))
                .any(|p| same_file(&p, found));
            if !known {
                out.push(found.clone());
            }
        }
    }
    Ok(out)
}

/// Every `.plcproj` under the folders of `search`, by its library name
/// (upper case): its `<Title>`, else its `<Name>`; the first found wins.
fn library_catalogue(search: &[PathBuf]) -> io::Result<HashMap<String, PathBuf>> {
    let mut found: Vec<PathBuf> = Vec::new();
    for dir in search {
        if !dir.is_dir() {
            return Err(io::Error::new(
                io::ErrorKind::NotFound,
                format!("--library-path {}: not a folder", dir.display()),
            ));
        }
        walk(dir, 0, &mut |file| {
            if has_extension(file, &["plcproj"]) {
                found.push(file.to_path_buf());
            }
        })?;
    }
    let mut catalogue = HashMap::new();
    for project in found {
        let Ok(text) = std::fs::read_to_string(&project) else {
            continue;
        };
        if let Some(name) = library_name(&text) {
            catalogue
                .entry(name.to_ascii_uppercase())
                .or_insert(project);
        }
    }
    Ok(catalogue)
}

/// The names of the libraries a `.plcproj` references:
/// `<PlaceholderReference Include="LCLS General">` and
/// `<LibraryReference Include="LCLS General, 1.0 (SLAC)">`, the name
/// before a version.
fn references(plcproj: &Path) -> io::Result<Vec<String>> {
    let text = std::fs::read_to_string(plcproj)?;
    let Ok(doc) = crate::syntax::plcopen::read_xml(text.trim_start_matches('\u{FEFF}')) else {
        return Ok(Vec::new());
    };
    Ok(doc
        .descendants()
        .filter(|n| n.has_tag_name("PlaceholderReference") || n.has_tag_name("LibraryReference"))
        .filter_map(|n| n.attribute("Include"))
        .map(|i| i.split(',').next().unwrap_or(i).trim().to_string())
        .filter(|n| !n.is_empty())
        .collect())
}

/// A project's library name: its `<Title>`, else its `<Name>`.
fn library_name(text: &str) -> Option<String> {
    let doc = crate::syntax::plcopen::read_xml(text.trim_start_matches('\u{FEFF}')).ok()?;
    let field = |tag: &str| {
        doc.descendants()
            .find(|n| n.has_tag_name(tag))
            .and_then(|n| n.text())
            .map(str::trim)
            .filter(|t| !t.is_empty())
            .map(str::to_string)
    };
    field("Title").or_else(|| field("Name"))
}

/// True when two paths name the same file.
fn same_file(a: &Path, b: &Path) -> bool {
    match (a.canonicalize(), b.canonicalize()) {
        (Ok(x), Ok(y)) => x == y,
        _ => a == b,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_library_is_named_by_its_title_else_its_name_and_references_drop_the_version() {
        let project = "<Project><PropertyGroup><Name>LCLSGeneral</Name><Title>LCLS General</Title></PropertyGroup></Project>";
        assert_eq!(library_name(project).as_deref(), Some("LCLS General"));
        let untitled =
            "<Project><PropertyGroup><Name>Lib</Name><Title> </Title></PropertyGroup></Project>";
        assert_eq!(library_name(untitled).as_deref(), Some("Lib"));
        assert_eq!(library_name("not xml"), None);
    }
}
