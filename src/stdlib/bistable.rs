//! SR and RS flip-flops. Layouts: SR = S1, R, Q1; RS = S, R1, Q1.

/// Set dominant: `Q1 := S1 OR (NOT R AND Q1)`.
#[inline(always)]
pub fn sr(s: &mut [u64]) {
    s[2] = s[0] | (!s[1] & s[2] & 1);
}

/// Reset dominant: `Q1 := NOT R1 AND (S OR Q1)`.
#[inline(always)]
pub fn rs(s: &mut [u64]) {
    s[2] = !s[1] & (s[0] | s[2]) & 1;
}
