//! The assertion functions as host functions: one typed function per
//! elementary type (the checker picks it from the values' type, see
//! `sema::assert_calls`), each recording its failures into a shared log.

use super::tcunit::State;
use crate::elementary::ElemType;
use crate::runtime::host_blocks::{
    HostBlocks, HostDeclError, HostIo, HostIoError, HostResult, HostSignature,
};
use crate::sema::assert_calls::{
    ASSERT_EQ_ANY_PREFIX, ASSERT_EQ_ENUM_HOST, ASSERT_EQ_PREFIX, ASSERT_NEAR_PREFIX,
    ASSERT_TRUE_HOST, TCUNIT_LTIME_HOST,
};
use std::sync::{Arc, Mutex};

/// Most failures kept per test (a failing assertion in a loop stays readable).
pub(crate) const MAX_FAILURES: usize = 100;

/// One failed assertion, as the host function saw it.
#[derive(Debug, Clone)]
pub(crate) struct Recorded {
    /// The encoded position of the call (`sema::assert_calls::encode_location`).
    pub(crate) loc: i64,
    /// The expected value as an IEC literal.
    pub(crate) expected: String,
    /// The actual value as an IEC literal.
    pub(crate) actual: String,
    /// The element index, for `AssertArrayEquals`.
    pub(crate) index: Option<i64>,
    /// The element's path (`[2,3]`, `[1].x`), for `AssertArrayEquals` of
    /// a multi-dimensional array or an array of structures.
    pub(crate) element: Option<String>,
    /// The assertion's message.
    pub(crate) message: String,
}

/// Failures of the cycle being run, shared with the host functions.
#[derive(Debug, Clone, Default)]
pub(crate) struct Log {
    /// Failures not yet collected by the runner.
    pub(crate) failures: Arc<Mutex<Vec<Recorded>>>,
    /// Failures dropped beyond [`MAX_FAILURES`].
    pub(crate) dropped: Arc<Mutex<usize>>,
    /// Under TcUnit's rules, every assertion that runs goes to the test
    /// being run instead (`super::tcunit`).
    pub(crate) suites: Option<Arc<Mutex<State>>>,
}

impl Log {
    /// A log whose assertions count for the TcUnit tests of `state`.
    pub(crate) fn for_suites(state: Arc<Mutex<State>>) -> Log {
        Log {
            suites: Some(state),
            ..Log::default()
        }
    }

    /// An assertion of host `host` held (its pins in `io`).
    fn held(&self, io: &HostIo<'_>, host: &str) -> Result<(), HostIoError> {
        if let Some(state) = &self.suites {
            let loc = io.get_i64("Loc")?;
            let values = (
                format!("{host}:{}", io.get("Expected")?.to_literal()),
                io.get("Actual")?.to_literal(),
            );
            let message = io.get_str("Message")?;
            state
                .lock()
                .unwrap_or_else(|p| p.into_inner())
                .assertion_call(loc, values, &message, None);
        }
        Ok(())
    }

    fn push(&self, r: Recorded, host: &str) {
        if let Some(state) = &self.suites {
            let loc = r.loc;
            let values = (format!("{host}:{}", r.expected), r.actual.clone());
            let message = r.message.clone();
            state
                .lock()
                .unwrap_or_else(|p| p.into_inner())
                .assertion_call(loc, values, &message, Some(r));
            return;
        }
        let mut list = self.failures.lock().unwrap_or_else(|p| p.into_inner());
        if list.len() < MAX_FAILURES {
            list.push(r);
        } else {
            *self.dropped.lock().unwrap_or_else(|p| p.into_inner()) += 1;
        }
    }

    /// Takes the failures recorded so far.
    pub(crate) fn take(&self) -> Vec<Recorded> {
        std::mem::take(&mut *self.failures.lock().unwrap_or_else(|p| p.into_inner()))
    }

    /// How many failures were not kept.
    pub(crate) fn dropped(&self) -> usize {
        *self.dropped.lock().unwrap_or_else(|p| p.into_inner())
    }
}

/// Records a held assertion (TcUnit counts them) and sets the result to
/// TRUE.
fn pass(io: &mut HostIo<'_>, log: &Log, result: &str) -> HostResult {
    log.held(io, result)?;
    io.set_bool(result, true)?;
    Ok(())
}

/// Records a failure from the pins `Expected`, `Actual`, `Message`, `Loc`
/// (and `IsElement`/`Index` when present); sets the result to FALSE.
fn fail(io: &mut HostIo<'_>, log: &Log, result: &str, element: bool) -> HostResult {
    let expected = io.get("Expected")?.to_literal();
    let actual = io.get("Actual")?.to_literal();
    fail_with(io, log, result, element, (expected, actual))
}

/// [`fail`] with the expected and actual values already written out.
fn fail_with(
    io: &mut HostIo<'_>,
    log: &Log,
    result: &str,
    element: bool,
    (expected, actual): (String, String),
) -> HostResult {
    let index = if element && io.get_bool("IsElement")? {
        Some(io.get_i64("Index")?)
    } else {
        None
    };
    let path = if element {
        Some(io.get_str("Element")?).filter(|p| !p.is_empty())
    } else {
        None
    };
    log.push(
        Recorded {
            loc: io.get_i64("Loc")?,
            expected,
            actual,
            index,
            element: path,
            message: io.get_str("Message")?,
        },
        result,
    );
    io.set_bool(result, false)?;
    Ok(())
}

/// The pins of an equality assertion on values of type `t` (with a
/// `Delta` of that type when `delta`): the values, the message and source
/// location, and where an array assertion's element stands.
fn equality_signature(name: &str, t: ElemType, delta: bool) -> HostSignature {
    let sig = HostSignature::function(name, ElemType::Bool)
        .input("Expected", t)
        .input("Actual", t);
    let sig = if delta { sig.input("Delta", t) } else { sig };
    sig.input("Message", ElemType::String)
        .input("Loc", ElemType::Lint)
        .input("IsElement", ElemType::Bool)
        .input("Index", ElemType::Lint)
        .input("Element", ElemType::String)
}

fn is_real(t: ElemType) -> bool {
    matches!(t, ElemType::Real | ElemType::Lreal)
}

/// Registers every assertion host function, recording into `log`.
pub(crate) fn register(hosts: &mut HostBlocks, log: &Log) -> Result<(), HostDeclError> {
    for t in ElemType::ALL {
        let name = format!("{ASSERT_EQ_PREFIX}{}", t.name());
        let sig = equality_signature(&name, t, false);
        let log = log.clone();
        let result = name.clone();
        hosts.function(sig, move |io| {
            let same = if is_real(t) {
                io.get_f64("Expected")? == io.get_f64("Actual")?
            } else {
                io.get("Expected")? == io.get("Actual")?
            };
            if same {
                pass(io, &log, &result)
            } else {
                fail(io, &log, &result, true)
            }
        })?;
    }
    for t in [ElemType::Real, ElemType::Lreal] {
        let name = format!("{ASSERT_NEAR_PREFIX}{}", t.name());
        let sig = equality_signature(&name, t, true);
        let log = log.clone();
        let result = name.clone();
        hosts.function(sig, move |io| {
            let (e, a, d) = (
                io.get_f64("Expected")?,
                io.get_f64("Actual")?,
                io.get_f64("Delta")?,
            );
            // NaN anywhere fails: `<=` is false for it.
            if (e - a).abs() <= d.abs() {
                pass(io, &log, &result)
            } else {
                fail(io, &log, &result, true)
            }
        })?;
    }
    register_any_strings(hosts, log)?;
    register_tcunit_ltime(hosts, log)?;
    register_enum(hosts, log)?;
    let sig = HostSignature::function(ASSERT_TRUE_HOST, ElemType::Bool)
        .input("Expected", ElemType::Bool)
        .input("Actual", ElemType::Bool)
        .input("Message", ElemType::String)
        .input("Loc", ElemType::Lint);
    let log = log.clone();
    hosts.function(sig, move |io| {
        if io.get_bool("Expected")? == io.get_bool("Actual")? {
            pass(io, &log, ASSERT_TRUE_HOST)
        } else {
            fail(io, &log, ASSERT_TRUE_HOST, false)
        }
    })?;
    Ok(())
}

/// TcUnit's `AssertEquals(ANY, ANY)` of two STRINGs (WSTRINGs): TcUnit
/// compares the values' sizes first, a string's being its length, and
/// reports two strings of other lengths by their lengths, `(Data size
/// (LEN) = 16)`; two of one length by their texts.
fn register_any_strings(hosts: &mut HostBlocks, log: &Log) -> Result<(), HostDeclError> {
    for (t, len) in [(ElemType::String, "LEN"), (ElemType::WString, "WLEN")] {
        let name = format!("{ASSERT_EQ_ANY_PREFIX}{}", t.name());
        let sig = equality_signature(&name, t, false);
        let log = log.clone();
        hosts.function(sig, move |io| {
            let (e, a) = (io.get_str("Expected")?, io.get_str("Actual")?);
            let (ne, na) = (e.chars().count(), a.chars().count());
            if e == a {
                pass(io, &log, &name)
            } else if ne != na {
                // Quoted, as the type classes of two types are.
                let size = |n: usize| format!("'(Data size ({len}) = {n})'");
                fail_with(io, &log, &name, true, (size(ne), size(na)))
            } else {
                fail(io, &log, &name, true)
            }
        })?;
    }
    Ok(())
}

/// TcUnit's LTIME equality: as plcrun's, but a failure shows the values
/// as TwinCAT's unsigned LTIME (`LT#213503d23h34m33s709ms551us615ns`, not
/// `LT#-1ns`).
fn register_tcunit_ltime(hosts: &mut HostBlocks, log: &Log) -> Result<(), HostDeclError> {
    let sig = equality_signature(TCUNIT_LTIME_HOST, ElemType::Ltime, false);
    let log = log.clone();
    hosts.function(sig, move |io| {
        let (e, a) = (io.get("Expected")?, io.get("Actual")?);
        if e == a {
            return pass(io, &log, TCUNIT_LTIME_HOST);
        }
        let shown = (e.to_unsigned_literal(), a.to_unsigned_literal());
        fail_with(io, &log, TCUNIT_LTIME_HOST, true, shown)
    })?;
    Ok(())
}

/// The equality of two values of one enumeration, passed as the integers
/// they are stored as, with the enumeration's value names
/// (`Type;name=value;...`, sema::assert_enums) to report them by name.
fn register_enum(hosts: &mut HostBlocks, log: &Log) -> Result<(), HostDeclError> {
    let sig = HostSignature::function(ASSERT_EQ_ENUM_HOST, ElemType::Bool)
        .input("Expected", ElemType::Lint)
        .input("Actual", ElemType::Lint)
        .input("Message", ElemType::String)
        .input("Loc", ElemType::Lint)
        .input("Names", ElemType::String);
    let log = log.clone();
    hosts.function(sig, move |io| {
        let (e, a) = (io.get_i64("Expected")?, io.get_i64("Actual")?);
        if e == a {
            return pass(io, &log, ASSERT_EQ_ENUM_HOST);
        }
        let names = io.get_str("Names")?;
        let values = (enum_literal(&names, e), enum_literal(&names, a));
        fail_with(io, &log, ASSERT_EQ_ENUM_HOST, false, values)
    })?;
    Ok(())
}

/// `Type#name` for value `v` of the enumeration described by `names`
/// (`Type;name=value;...`), or the number when no name is listed for it.
fn enum_literal(names: &str, v: i64) -> String {
    let mut parts = names.split(';');
    let ty = parts.next().unwrap_or_default();
    parts
        .filter_map(|p| p.split_once('='))
        .find(|(_, n)| n.parse::<i64>() == Ok(v))
        .map_or_else(|| v.to_string(), |(name, _)| format!("{ty}#{name}"))
}

#[cfg(test)]
mod tests {
    use super::enum_literal;

    #[test]
    fn an_enumeration_value_is_written_by_name_when_listed() {
        let names = "E_Mode;Idle=0;Run=1;Stop=-3";
        assert_eq!(enum_literal(names, 1), "E_Mode#Run");
        assert_eq!(enum_literal(names, -3), "E_Mode#Stop");
        assert_eq!(enum_literal(names, 7), "7");
    }
}
