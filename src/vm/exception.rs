//! Faults a `__TRY` catches, and the exception code its `__CATCH`
//! variable gets (the numbers of `__SYSTEM.ExceptionCode`).

use super::fault::FaultKind;

const ACCESS_VIOLATION: u32 = 0x51;
const STACK_OVERFLOW: u32 = 0x54;
const OUT_OF_MEMORY: u32 = 0x1C;
const ARRAYBOUNDS: u32 = 0x101;
const DIVIDEBYZERO: u32 = 0x102;
const OVERFLOW: u32 = 0x103;
const UNKNOWN: u32 = 0xFFFF_FFFF;

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
