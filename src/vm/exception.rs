//! Faults a `__TRY` catches, and the exception code its `__CATCH`
//! variable gets (the numbers of `__SYSTEM.ExceptionCode`).

use super::fault::FaultKind;
use crate::ir::exception_codes::{
    ACCESS_VIOLATION, ARRAYBOUNDS, DIVIDEBYZERO, OUT_OF_MEMORY, OVERFLOW, STACK_OVERFLOW, UNKNOWN,
};

impl FaultKind {
    /// The exception code a `__CATCH` receives for this fault, or `None`
    /// for the stops no user code may catch: the watchdog, an `abort`, a
    /// failed host body, an unstable GRAFCET chart.
    pub fn exception_code(&self) -> Option<u32> {
        Some(match self {
            FaultKind::Watchdog
            | FaultKind::Aborted
            | FaultKind::HostFunction(_)
            | FaultKind::UnstableChart(_) => return None,
            FaultKind::DivisionByZero => DIVIDEBYZERO,
            FaultKind::IndexOutOfRange { .. }
            | FaultKind::SubrangeViolation { .. }
            | FaultKind::MuxOutOfRange { .. } => ARRAYBOUNDS,
            FaultKind::ConversionOverflow | FaultKind::NegativeExponent => OVERFLOW,
            FaultKind::BadAddress
            | FaultKind::NullReference
            | FaultKind::OutsideObject { .. }
            | FaultKind::StaleReference
            | FaultKind::NullInterface
            | FaultKind::OutsideBytes { .. }
            | FaultKind::ByteViewAggregate
            | FaultKind::NotFromPointer
            | FaultKind::NoIntegerImage
            | FaultKind::NoByteLayout => ACCESS_VIOLATION,
            FaultKind::MethodReentered => STACK_OVERFLOW,
            FaultKind::TooManyReferencedObjects => OUT_OF_MEMORY,
            FaultKind::InvalidBcd => UNKNOWN,
            FaultKind::Raised(code) => *code,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stops_are_not_caught_and_faults_have_their_codes() {
        assert_eq!(FaultKind::Watchdog.exception_code(), None);
        assert_eq!(FaultKind::Aborted.exception_code(), None);
        assert_eq!(FaultKind::DivisionByZero.exception_code(), Some(0x102));
        let bounds = FaultKind::IndexOutOfRange {
            index: 5,
            lo: 0,
            hi: 3,
        };
        assert_eq!(bounds.exception_code(), Some(0x101));
        assert_eq!(FaultKind::NullReference.exception_code(), Some(0x51));
    }
}
