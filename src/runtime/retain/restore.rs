//! Saving and restoring a PLC's retained values through a file, between
//! cycles, on the caller's thread.

use super::fingerprint::RetainDiff;
use super::format::{FileVar, decode, encode};
use super::layout::{RetainLayout, Shape, Snapshot};
use super::{Damage, RestoreMode, RestoreReport, RetainError, RetainedVariable};
use crate::runtime::engine::Plc;
use crate::runtime::names::VarRef;
use crate::runtime::plc_value::Value;
use std::collections::HashMap;
use std::path::Path;

impl Plc {
    /// The retained values (RETAIN and PERSISTENT variables, down to
    /// array elements, structure fields and FB instance variables), in
    /// declaration order: globals, then each program instance.
    ///
    /// ```
    /// use plcrun::{Options, Plc};
    /// let src = "PROGRAM P VAR RETAIN n : DINT; s : STRING[8]; END_VAR VAR x : INT; END_VAR
    ///            n := n + 1; END_PROGRAM";
    /// let plc = Plc::compile_files(&[("p.st", src)], &Options::default())?;
    /// let names: Vec<String> = plc.retained().into_iter().map(|r| r.name).collect();
    /// assert_eq!(names, ["P.n", "P.s"]);
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn retained(&self) -> Vec<RetainedVariable> {
        RetainLayout::new(&self.image)
            .entries
            .into_iter()
            .map(|e| RetainedVariable {
                name: e.name,
                type_name: e.ty,
                persistent: e.persistent,
            })
            .collect()
    }

    /// Writes the retained values to `path` now, atomically (see
    /// [`super::saver::RetainSaver`] to save without waiting for the disk).
    pub fn save_retain(&self, path: impl AsRef<Path>) -> Result<(), RetainError> {
        let path = path.as_ref();
        let layout = RetainLayout::new(&self.image);
        let mut snap = layout.buffer();
        layout.take(&self.machine, self.cycle(), self.time(), &mut snap);
        super::file::write_atomically(path, &encode(&layout, &snap)).map_err(|error| {
            RetainError::Write {
                path: path.to_path_buf(),
                error,
            }
        })
    }

    /// Restores the retained values from `path` (a warm start). With
    /// [`RestoreMode::Exact`] a file whose retained variables (names and
    /// types) differ from the program's is refused and nothing changes;
    /// with [`RestoreMode::Partial`] the values that fit are restored and
    /// the report names the others. A damaged file is always refused.
    pub fn restore_retain(
        &mut self,
        path: impl AsRef<Path>,
        mode: RestoreMode,
    ) -> Result<RestoreReport, RetainError> {
        let path = path.as_ref();
        let text = std::fs::read_to_string(path).map_err(|error| RetainError::Read {
            path: path.to_path_buf(),
            error,
        })?;
        let damaged = |damage| RetainError::Damaged {
            path: path.to_path_buf(),
            damage,
        };
        let file = decode(&text).map_err(damaged)?;
        let layout = RetainLayout::new(&self.image);
        let listed = file
            .variables
            .iter()
            .map(|v| (v.name.as_str(), v.ty.as_str()));
        let program = layout
            .entries
            .iter()
            .map(|e| (e.name.as_str(), e.ty.as_str()));
        let differences = RetainDiff::between(listed, program);
        let (snap, fits) = self
            .decode_values(&layout, &file.variables)
            .map_err(damaged)?;
        let restored = fits.iter().filter(|f| **f).count();
        if !differences.is_empty() && mode == RestoreMode::Exact {
            return Err(RetainError::Mismatch {
                path: path.to_path_buf(),
                differences,
                fitting: restored,
            });
        }
        let now = self.time();
        layout.put(&snap, &mut self.machine, now, Some(&fits));
        Ok(RestoreReport {
            restored,
            cycle: file.cycle,
            differences,
        })
    }

    /// The file's values decoded for the program's entries of the same
    /// name and type (a timer's start instant relative to clock 0), and
    /// which entries they are.
    fn decode_values(
        &self,
        layout: &RetainLayout,
        vars: &[FileVar],
    ) -> Result<(Snapshot, Vec<bool>), Damage> {
        let by_name: HashMap<String, &FileVar> = vars
            .iter()
            .map(|v| (v.name.to_ascii_lowercase(), v))
            .collect();
        let mut snap = layout.buffer();
        let mut fits = vec![false; layout.entries.len()];
        for (k, e) in layout.entries.iter().enumerate() {
            let Some(v) = by_name.get(&e.name.to_ascii_lowercase()) else {
                continue;
            };
            if v.ty != e.ty {
                continue;
            }
            let r = VarRef {
                name: e.name.clone(),
                addr: e.slot,
                ty: e.type_id,
                owner: self.id,
                read_only: None,
                view: None,
            };
            let value = self
                .parse_value(&r, &v.value)
                .map_err(|error| Damage::BadValue {
                    name: v.name.clone(),
                    error: Box::new(error),
                })?;
            match (&e.shape, value) {
                (Shape::Scalar(_, i) | Shape::Enum(_, i), Value::Scalar(_, raw)) => {
                    snap.slots[*i] = raw;
                }
                (Shape::Enum(_, i), Value::Enum(_, x)) => snap.slots[*i] = x as u64,
                (Shape::Text(_, i), Value::String(s, _)) => snap.strings[*i] = s,
                _ => continue,
            }
            fits[k] = true;
        }
        Ok((snap, fits))
    }
}
