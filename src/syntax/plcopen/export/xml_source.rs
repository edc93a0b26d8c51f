//! PLCopen files given to export. Their declarations, types and
//! configurations come from the AST as for textual sources; their bodies
//! do not (the AST holds graphical bodies lowered to ST): every body is
//! read as written ([`ProjectPou`]): text, drawing, or chart.

use super::super::diagram::{ProjectPou, project_pous};
use crate::source::FileId;
use std::collections::HashMap;

/// The POUs of file `file` with their bodies, by file and upper-case name;
/// an error names what cannot be read.
pub(super) fn xml_bodies(
    file: FileId,
    text: &str,
) -> Result<HashMap<(FileId, String), ProjectPou>, String> {
    Ok(project_pous(text)?
        .into_iter()
        .map(|p| ((file, p.name.to_ascii_uppercase()), p))
        .collect())
}
