//! CODESYS's implicit conversion of an LREAL into a REAL (`r := lr;`):
//! CODESYS V3 and TwinCAT 3 compile it with a warning and round the value
//! to REAL's precision, as `LREAL_TO_REAL` does. plcrun does the same in
//! the files written in that dialect (W491, refused by `--strict`) and
//! refuses it elsewhere (E301), as IEC does.

use super::body::BodyBuilder;
use crate::elementary::ElemType;
use crate::source::Span;

impl BodyBuilder<'_> {
    /// W491 for an implicit LREAL-to-REAL conversion in a CODESYS or
    /// TwinCAT file; true when it is one.
    pub(super) fn implicit_real_conversion(
        &mut self,
        from: ElemType,
        to: ElemType,
        span: Span,
    ) -> bool {
        if (from, to) != (ElemType::Lreal, ElemType::Real)
            || !self.model.codesys_files.contains(&span.file)
        {
            return false;
        }
        self.diags.warning(
            "W491",
            span,
            "implicit conversion of LREAL to REAL (CODESYS): the value is rounded to REAL's \
             precision; write LREAL_TO_REAL to say so",
        );
        true
    }
}
