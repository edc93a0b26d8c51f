//! R_TRIG and F_TRIG. Layout: CLK, Q, M.

/// `Q := CLK AND NOT M; M := CLK;` (M starts FALSE).
#[inline(always)]
pub fn r_trig(s: &mut [u64]) {
    let clk = s[0];
    s[1] = clk & !s[2] & 1;
    s[2] = clk;
}

/// `Q := NOT CLK AND NOT M; M := NOT CLK;` (M starts TRUE).
#[inline(always)]
pub fn f_trig(s: &mut [u64]) {
    let not_clk = s[0] ^ 1;
    s[1] = not_clk & !s[2] & 1;
    s[2] = not_clk;
}
