//! Export of configurations, resources, tasks and program instances.

use super::writer::Writer;
use super::{ExportError, Exporter};
use crate::syntax::ast::{Configuration, ProgramInstance, Resource};

impl Exporter<'_> {
    /// `<configuration>` with its globals and resources.
    pub(super) fn configuration(
        &self,
        w: &mut Writer,
        c: &Configuration,
    ) -> Result<(), ExportError> {
        w.open("configuration", &[("name", &c.name.name)]);
        for r in &c.resources {
            self.resource(w, r)?;
        }
        for g in &c.globals {
            self.var_block(w, g)?;
        }
        w.close("configuration");
        Ok(())
    }

    /// `<resource>`: tasks with their program instances, globals, then
    /// instances without a task (the TC6 order).
    fn resource(&self, w: &mut Writer, r: &Resource) -> Result<(), ExportError> {
        w.open("resource", &[("name", &r.name.name)]);
        for t in &r.tasks {
            let mut attrs: Vec<(String, String)> = vec![("name".into(), t.name.name.clone())];
            for (key, value) in &t.settings {
                let attr = match key.name.to_ascii_uppercase().as_str() {
                    "INTERVAL" => "interval",
                    "PRIORITY" => "priority",
                    "SINGLE" => "single",
                    other => return Err(self.refuse(format!("task setting `{other}`"), key.span)),
                };
                attrs.push((attr.into(), self.value_text(value.span).into_owned()));
            }
            if !attrs.iter().any(|(k, _)| k == "priority") {
                // TC6 requires a priority; 0 is what IEC assumes without one.
                attrs.push(("priority".into(), "0".into()));
            }
            let borrowed: Vec<(&str, &str)> = attrs
                .iter()
                .map(|(k, v)| (k.as_str(), v.as_str()))
                .collect();
            w.open("task", &borrowed);
            for p in r.programs.iter().filter(|p| task_is(p, &t.name.name)) {
                self.pou_instance(w, p)?;
            }
            w.close("task");
        }
        for g in &r.globals {
            self.var_block(w, g)?;
        }
        for p in &r.programs {
            match &p.task {
                None => self.pou_instance(w, p)?,
                Some(t)
                    if !r
                        .tasks
                        .iter()
                        .any(|d| d.name.name.eq_ignore_ascii_case(&t.name)) =>
                {
                    return Err(self.refuse(
                        format!(
                            "a program instance WITH `{}`, a task of no resource",
                            t.name
                        ),
                        t.span,
                    ));
                }
                Some(_) => {}
            }
        }
        w.close("resource");
        Ok(())
    }

    /// `<pouInstance name typeName/>`.
    fn pou_instance(&self, w: &mut Writer, p: &ProgramInstance) -> Result<(), ExportError> {
        if !p.args.is_empty() {
            return Err(self.refuse("a program instance with connections (`x := g`)", p.span));
        }
        w.empty(
            "pouInstance",
            &[("name", &p.name.name), ("typeName", &p.type_name.name)],
        );
        Ok(())
    }
}

/// True when `p` runs in the task named `task`.
fn task_is(p: &ProgramInstance, task: &str) -> bool {
    p.task
        .as_ref()
        .is_some_and(|t| t.name.eq_ignore_ascii_case(task))
}
