//! The I/O configuration's loopback links under the TcUnit runner
//! ([`crate::address::IoLink`]): a link names its variables by their paths in the
//! project's PROGRAM (`PRG_Test.fb_PTM_Test.fbPump.i_iTemp`), where the
//! runner runs the suite instance `PRG_Test.fb_PTM_Test` as its own
//! `suiteK`; the paths are moved there. Before each cycle every input
//! takes its output's value, as TwinCAT's I/O update does between two
//! cycles of the task. A link whose variables are not in a suite (a
//! PROGRAM's own variable, which the runner does not run) is left out.

use super::{DRIVER, Plan};
use crate::address::IoLink;
use crate::runtime::engine::Plc;
use crate::runtime::names::VarRef;

/// The links of `links` whose two ends are variables of the suites of
/// `plan` in `plc`.
pub(super) fn resolve(plc: &Plc, plan: &Plan, links: &[IoLink]) -> Vec<(VarRef, VarRef)> {
    let moved = |path: &str| in_suite(plan, path);
    links
        .iter()
        .filter_map(|l| {
            let input = plc.resolve(&moved(&l.input)?).ok()?;
            let output = plc.resolve(&moved(&l.output)?).ok()?;
            Some((input, output))
        })
        .collect()
}

/// `path`, a variable of a suite instance as the project names it
/// (`PRG_Test.fb_PTM_Test.fbPump.i_iTemp`), where the runner has it
/// (`suiteK.fbPump.i_iTemp`); `None` outside the suites.
pub(super) fn in_suite(plan: &Plan, path: &str) -> Option<String> {
    let upper = path.to_ascii_uppercase();
    plan.suites.iter().enumerate().find_map(|(k, s)| {
        let prefix = format!("{}.", s.path.to_ascii_uppercase());
        upper
            .starts_with(&prefix)
            .then(|| format!("{DRIVER}.suite{k}.{}", &path[prefix.len()..]))
    })
}

/// Gives each linked input its output's value (converted when the two
/// differ in type, as a literal; a value that does not fit is left).
pub(super) fn copy(plc: &mut Plc, links: &[(VarRef, VarRef)]) {
    for (input, output) in links {
        let Ok(value) = plc.get(output) else {
            continue;
        };
        if plc.set(input, &value).is_err()
            && let Ok(converted) = plc.parse_value(input, &value.to_literal())
        {
            let _ = plc.set(input, &converted);
        }
    }
}
