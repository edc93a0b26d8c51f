//! The NC configuration's axes under the TcUnit runner
//! ([`crate::address::NcAxis`]): before the first cycle, each `AXIS_REF`
//! of a suite that the configuration links to an axis takes that axis'
//! id, name and parameters, which plcrun's simulated axis then runs with
//! (docs/twincat.md, "Motion control"). An axis linked to a variable that
//! is not in a suite, or a parameter plcrun's `AXIS_REF` does not hold,
//! is left out.

use super::Plan;
use super::io_links::in_suite;
use crate::address::NcAxis;
use crate::runtime::engine::Plc;

/// Gives the linked `AXIS_REF`s of the suites of `plan` their axes'
/// settings.
pub(super) fn configure(plc: &mut Plc, plan: &Plan, axes: &[NcAxis]) {
    for axis in axes {
        let Some(base) = in_suite(plan, &axis.axis_ref) else {
            continue;
        };
        let id = axis.id.to_string();
        let name = format!("'{}'", axis.name.replace('\'', "$'"));
        let settings = [
            ("NcToPlc.AxisId", id.as_str()),
            ("Param.AxisId", id.as_str()),
            ("Param.sAxisName", name.as_str()),
        ];
        let parameters = axis
            .parameters
            .iter()
            .map(|(field, value)| (format!("Param.{field}"), value.as_str()));
        let all = settings
            .iter()
            .map(|(f, v)| (f.to_string(), *v))
            .chain(parameters);
        for (field, literal) in all {
            set(plc, &format!("{base}.{field}"), literal);
        }
    }
}

/// Writes `literal` into the variable `path`, when it is there and the
/// literal fits it.
fn set(plc: &mut Plc, path: &str, literal: &str) {
    let Ok(r) = plc.resolve(path) else {
        return;
    };
    if let Ok(value) = plc.parse_value(&r, literal) {
        let _ = plc.set(&r, &value);
    }
}
