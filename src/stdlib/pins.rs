//! Interfaces of the native function blocks: pin names, directions, types and
//! slot offsets. The checker reads these to type calls and member accesses;
//! the executor relies on the same offsets.

use crate::elementary::ElemType;
use crate::ir::op::{CounterRange, NativeFb};

/// Direction of a pin.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ParamDir {
    /// VAR_INPUT
    Input,
    /// VAR_OUTPUT
    Output,
    /// Hidden internal state (not accessible from programs).
    Hidden,
}

/// One pin (or hidden state slot) of a native block.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NativeParam {
    /// Name as IEC spells it.
    pub name: &'static str,
    /// Other accepted spellings (CoDeSys/Moeller pin names).
    pub aliases: &'static [&'static str],
    /// Direction.
    pub dir: ParamDir,
    /// Type.
    pub ty: ElemType,
    /// Initial slot value.
    pub init: u64,
}

const fn pin(name: &'static str, dir: ParamDir, ty: ElemType) -> NativeParam {
    NativeParam {
        name,
        aliases: &[],
        dir,
        ty,
        init: 0,
    }
}

use ParamDir::{Hidden, Input, Output};

const R_TRIG: [NativeParam; 3] = [
    pin("CLK", Input, ElemType::Bool),
    pin("Q", Output, ElemType::Bool),
    pin("M", Hidden, ElemType::Bool),
];
const F_TRIG: [NativeParam; 3] = [
    pin("CLK", Input, ElemType::Bool),
    pin("Q", Output, ElemType::Bool),
    NativeParam {
        init: 1,
        ..pin("M", Hidden, ElemType::Bool)
    },
];
const SR: [NativeParam; 3] = [
    NativeParam {
        aliases: &["SET1"],
        ..pin("S1", Input, ElemType::Bool)
    },
    NativeParam {
        aliases: &["RESET"],
        ..pin("R", Input, ElemType::Bool)
    },
    pin("Q1", Output, ElemType::Bool),
];
const RS: [NativeParam; 3] = [
    NativeParam {
        aliases: &["SET"],
        ..pin("S", Input, ElemType::Bool)
    },
    NativeParam {
        aliases: &["RESET1"],
        ..pin("R1", Input, ElemType::Bool)
    },
    pin("Q1", Output, ElemType::Bool),
];
const TIMER: [NativeParam; 7] = [
    pin("IN", Input, ElemType::Bool),
    pin("PT", Input, ElemType::Time),
    pin("Q", Output, ElemType::Bool),
    pin("ET", Output, ElemType::Time),
    pin("START", Hidden, ElemType::Time),
    pin("IN_PREV", Hidden, ElemType::Bool),
    pin("RUNNING", Hidden, ElemType::Bool),
];

const RTC: [NativeParam; 6] = [
    pin("IN", Input, ElemType::Bool),
    pin("PDT", Input, ElemType::Dt),
    pin("Q", Output, ElemType::Bool),
    pin("CDT", Output, ElemType::Dt),
    pin("AT_ZERO", Hidden, ElemType::Dt),
    pin("IN_PREV", Hidden, ElemType::Bool),
];

/// The counters' reset and load inputs, also under the names CODESYS and
/// TwinCAT's Tc2_Standard give them (`CTU(CU := x, RESET := r)`).
const RESET: NativeParam = NativeParam {
    aliases: &["RESET"],
    ..pin("R", Input, ElemType::Bool)
};
const LOAD: NativeParam = NativeParam {
    aliases: &["LOAD"],
    ..pin("LD", Input, ElemType::Bool)
};

macro_rules! counters {
    ($($ty:ident => $ctu:ident, $ctd:ident, $ctud:ident);* $(;)?) => {$(
        const $ctu: [NativeParam; 6] = [
            pin("CU", Input, ElemType::Bool),
            RESET,
            pin("PV", Input, ElemType::$ty),
            pin("Q", Output, ElemType::Bool),
            pin("CV", Output, ElemType::$ty),
            pin("CU_PREV", Hidden, ElemType::Bool),
        ];
        const $ctd: [NativeParam; 6] = [
            pin("CD", Input, ElemType::Bool),
            LOAD,
            pin("PV", Input, ElemType::$ty),
            pin("Q", Output, ElemType::Bool),
            pin("CV", Output, ElemType::$ty),
            pin("CD_PREV", Hidden, ElemType::Bool),
        ];
        const $ctud: [NativeParam; 10] = [
            pin("CU", Input, ElemType::Bool),
            pin("CD", Input, ElemType::Bool),
            RESET,
            LOAD,
            pin("PV", Input, ElemType::$ty),
            pin("QU", Output, ElemType::Bool),
            pin("QD", Output, ElemType::Bool),
            pin("CV", Output, ElemType::$ty),
            pin("CU_PREV", Hidden, ElemType::Bool),
            pin("CD_PREV", Hidden, ElemType::Bool),
        ];
    )*};
}

counters! {
    Int => CTU_INT, CTD_INT, CTUD_INT;
    Dint => CTU_DINT, CTD_DINT, CTUD_DINT;
    Lint => CTU_LINT, CTD_LINT, CTUD_LINT;
    Udint => CTU_UDINT, CTD_UDINT, CTUD_UDINT;
    Ulint => CTU_ULINT, CTD_ULINT, CTUD_ULINT;
}

/// The pins of `fb`, in slot order (pin `i` lives at instance slot `i`).
pub fn interface(fb: NativeFb) -> &'static [NativeParam] {
    use CounterRange as C;
    match fb {
        NativeFb::RTrig => &R_TRIG,
        NativeFb::FTrig => &F_TRIG,
        NativeFb::Sr => &SR,
        NativeFb::Rs => &RS,
        NativeFb::Ton | NativeFb::Tof | NativeFb::Tp => &TIMER,
        NativeFb::Rtc => &RTC,
        NativeFb::Ctu(C::Int) => &CTU_INT,
        NativeFb::Ctu(C::Dint) => &CTU_DINT,
        NativeFb::Ctu(C::Lint) => &CTU_LINT,
        NativeFb::Ctu(C::Udint) => &CTU_UDINT,
        NativeFb::Ctu(C::Ulint) => &CTU_ULINT,
        NativeFb::Ctd(C::Int) => &CTD_INT,
        NativeFb::Ctd(C::Dint) => &CTD_DINT,
        NativeFb::Ctd(C::Lint) => &CTD_LINT,
        NativeFb::Ctd(C::Udint) => &CTD_UDINT,
        NativeFb::Ctd(C::Ulint) => &CTD_ULINT,
        NativeFb::Ctud(C::Int) => &CTUD_INT,
        NativeFb::Ctud(C::Dint) => &CTUD_DINT,
        NativeFb::Ctud(C::Lint) => &CTUD_LINT,
        NativeFb::Ctud(C::Udint) => &CTUD_UDINT,
        NativeFb::Ctud(C::Ulint) => &CTUD_ULINT,
    }
}

/// Finds a native block by its type name (case-insensitive).
pub fn lookup_native(name: &str) -> Option<NativeFb> {
    use CounterRange as C;
    let upper = name.to_ascii_uppercase();
    let counter = |base: &str| -> Option<CounterRange> {
        let rest = upper.strip_prefix(base)?;
        Some(match rest {
            "" | "_INT" => C::Int,
            "_DINT" => C::Dint,
            "_LINT" => C::Lint,
            "_UDINT" => C::Udint,
            "_ULINT" => C::Ulint,
            _ => return None,
        })
    };
    Some(match upper.as_str() {
        "R_TRIG" => NativeFb::RTrig,
        "F_TRIG" => NativeFb::FTrig,
        "SR" => NativeFb::Sr,
        "RS" => NativeFb::Rs,
        "TON" => NativeFb::Ton,
        "TOF" => NativeFb::Tof,
        "TP" => NativeFb::Tp,
        "RTC" => NativeFb::Rtc,
        _ => {
            if let Some(r) = counter("CTUD") {
                NativeFb::Ctud(r)
            } else if let Some(r) = counter("CTU") {
                NativeFb::Ctu(r)
            } else if let Some(r) = counter("CTD") {
                NativeFb::Ctd(r)
            } else {
                return None;
            }
        }
    })
}

/// The canonical type name of a native block.
pub fn native_name(fb: NativeFb) -> String {
    use CounterRange as C;
    let suffix = |r: CounterRange| match r {
        C::Int => "",
        C::Dint => "_DINT",
        C::Lint => "_LINT",
        C::Udint => "_UDINT",
        C::Ulint => "_ULINT",
    };
    match fb {
        NativeFb::RTrig => "R_TRIG".into(),
        NativeFb::FTrig => "F_TRIG".into(),
        NativeFb::Sr => "SR".into(),
        NativeFb::Rs => "RS".into(),
        NativeFb::Ton => "TON".into(),
        NativeFb::Tof => "TOF".into(),
        NativeFb::Tp => "TP".into(),
        NativeFb::Rtc => "RTC".into(),
        NativeFb::Ctu(r) => format!("CTU{}", suffix(r)),
        NativeFb::Ctd(r) => format!("CTD{}", suffix(r)),
        NativeFb::Ctud(r) => format!("CTUD{}", suffix(r)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_ir_knows_every_instance_size() {
        // The verifier keeps native instances in their frame with the IR's
        // size; `call_raw` builds slices of the interface's length.
        use CounterRange as C;
        let mut all = vec![
            NativeFb::RTrig,
            NativeFb::FTrig,
            NativeFb::Sr,
            NativeFb::Rs,
            NativeFb::Ton,
            NativeFb::Tof,
            NativeFb::Tp,
            NativeFb::Rtc,
        ];
        for r in [C::Int, C::Dint, C::Lint, C::Udint, C::Ulint] {
            all.extend([NativeFb::Ctu(r), NativeFb::Ctd(r), NativeFb::Ctud(r)]);
        }
        for fb in all {
            assert_eq!(interface(fb).len(), fb.instance_slots() as usize, "{fb:?}");
        }
    }

    #[test]
    fn standard_instances_are_small() {
        // Bytes per instance: 8 per slot (pins and hidden state).
        let bytes = |name: &str| lookup_native(name).map(|fb| interface(fb).len() * 8);
        assert_eq!(bytes("R_TRIG"), Some(24));
        assert_eq!(bytes("CTU"), Some(48));
        assert_eq!(bytes("TON"), Some(56));
    }
}
