//! The retain file: JSON, one retained variable per line, every value an
//! IEC literal. See docs/runtime.md, "Retained data", for the format.

use super::layout::{RetainLayout, Shape, Snapshot};
use crate::elementary::ElemType;
use crate::value::format::{format_string, write_value};
use serde::{Deserialize, Serialize};

/// The `format` field of every retain file.
pub(crate) const FORMAT: &str = "plcrun-retain";
/// The version of the format this build writes and reads.
pub(crate) const VERSION: u32 = 1;

/// A retain file as read.
#[derive(Debug, Clone, Deserialize)]
pub(crate) struct RetainFile {
    /// Always [`FORMAT`].
    pub format: String,
    /// [`VERSION`].
    pub version: u32,
    /// The fingerprint of the variables' names and types.
    pub fingerprint: String,
    /// The cycle number at the snapshot (informative).
    pub cycle: u64,
    /// The clock at the snapshot, an IEC TIME literal (informative).
    #[allow(dead_code)]
    pub time: String,
    /// The values.
    pub variables: Vec<FileVar>,
}

/// One retained value in the file.
#[derive(Debug, Clone, PartialEq, Deserialize)]
pub(crate) struct FileVar {
    /// The outside path.
    pub name: String,
    /// The type (`DINT`, `STRING[80]`).
    #[serde(rename = "type")]
    pub ty: String,
    /// The value, an IEC literal.
    pub value: String,
    /// A timer's start instant, written as its distance to the snapshot's
    /// clock (`T#-300ms`: 300 ms before it).
    #[serde(default, skip_serializing_if = "is_false")]
    pub relative: bool,
    /// Declared PERSISTENT (informative).
    #[serde(default, skip_serializing_if = "is_false")]
    pub persistent: bool,
}

/// [`FileVar`] as written, borrowing its texts.
#[derive(Serialize)]
struct FileVarRef<'a> {
    name: &'a str,
    #[serde(rename = "type")]
    ty: &'a str,
    value: &'a str,
    #[serde(skip_serializing_if = "is_false")]
    relative: bool,
    #[serde(skip_serializing_if = "is_false")]
    persistent: bool,
}

fn is_false(b: &bool) -> bool {
    !*b
}

/// The file text for `snap` (taken with `layout`).
pub(crate) fn encode(layout: &RetainLayout, snap: &Snapshot) -> String {
    let mut out = String::with_capacity(64 + layout.entries.len() * 64);
    let quoted = |s: &str| serde_json::Value::from(s).to_string();
    let mut time = String::new();
    write_value(&mut time, ElemType::Time, snap.now as u64);
    out.push_str("{\n");
    out.push_str(&format!("  \"format\": {},\n", quoted(FORMAT)));
    out.push_str(&format!("  \"version\": {VERSION},\n"));
    out.push_str(&format!(
        "  \"fingerprint\": {},\n",
        quoted(&layout.fingerprint)
    ));
    out.push_str(&format!("  \"cycle\": {},\n", snap.cycle));
    out.push_str(&format!("  \"time\": {},\n", quoted(&time)));
    out.push_str("  \"variables\": [");
    let mut value = String::new();
    for (k, e) in layout.entries.iter().enumerate() {
        value.clear();
        match &e.shape {
            Shape::Scalar(t, i) => {
                let raw = snap.slots.get(*i).copied().unwrap_or(0);
                if e.clock_instant {
                    let since = (raw as i64).wrapping_sub(snap.now);
                    write_value(&mut value, ElemType::Time, since as u64);
                } else {
                    write_value(&mut value, *t, raw);
                }
            }
            Shape::Enum(values, i) => {
                let raw = snap.slots.get(*i).copied().unwrap_or(0) as i64;
                match values.iter().find(|(_, v)| *v == raw) {
                    Some((name, _)) => value.push_str(name),
                    None => value.push_str(&raw.to_string()),
                }
            }
            Shape::Text(wide, i) => {
                let s = snap.strings.get(*i).map_or("", String::as_str);
                value.push_str(&format_string(s, *wide));
            }
        }
        let var = FileVarRef {
            name: &e.name,
            ty: &e.ty,
            value: &value,
            relative: e.clock_instant,
            persistent: e.persistent,
        };
        // Strings and booleans always serialise.
        let line = serde_json::to_string(&var).unwrap_or_default();
        out.push_str(if k == 0 { "\n    " } else { ",\n    " });
        out.push_str(&line);
    }
    out.push_str(if layout.entries.is_empty() {
        "]\n}\n"
    } else {
        "\n  ]\n}\n"
    });
    out
}

/// Parses a retain file's text; the error says what is wrong.
pub(crate) fn decode(text: &str) -> Result<RetainFile, super::Damage> {
    let file: RetainFile = serde_json::from_str(text).map_err(|e| super::Damage::Json {
        line: e.line(),
        column: e.column(),
        message: e.to_string(),
    })?;
    if file.format != FORMAT {
        return Err(super::Damage::NotRetainData {
            format: file.format,
        });
    }
    if file.version != VERSION {
        return Err(super::Damage::Version {
            version: file.version,
        });
    }
    let listed = file
        .variables
        .iter()
        .map(|v| (v.name.as_str(), v.ty.as_str()));
    if super::fingerprint::fingerprint(listed) != file.fingerprint {
        return Err(super::Damage::Fingerprint);
    }
    let mut seen = std::collections::HashSet::new();
    for v in &file.variables {
        if !seen.insert(v.name.to_ascii_lowercase()) {
            return Err(super::Damage::Duplicate {
                name: v.name.clone(),
            });
        }
    }
    Ok(file)
}
