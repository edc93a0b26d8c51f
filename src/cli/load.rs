//! Reading source files into a source map.

use plcrun::diagnostics::Diagnostics;
use plcrun::runtime::engine::invalid_utf8;
use plcrun::source::SourceMap;
use std::path::PathBuf;

/// Reads every file; unreadable files are usage errors (returned as text),
/// invalid UTF-8 becomes a diagnostic.
pub fn load(files: &[PathBuf], diags: &mut Diagnostics) -> Result<SourceMap, String> {
    let mut sources = SourceMap::new();
    for path in files {
        let bytes =
            std::fs::read(path).map_err(|e| format!("cannot read `{}`: {e}", path.display()))?;
        let name = path.display().to_string();
        match String::from_utf8(bytes) {
            Ok(text) => {
                sources.add(name, text);
            }
            Err(e) => {
                let offset = e.utf8_error().valid_up_to();
                let text = String::from_utf8_lossy(e.as_bytes()).into_owned();
                let id = sources.add(name, text);
                diags.push(invalid_utf8(id, offset));
            }
        }
    }
    Ok(sources)
}
