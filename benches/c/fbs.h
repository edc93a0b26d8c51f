/* Hand-written C references of the benchmark programs: the standard FBs.
 *
 * Ported from benches/native/mod.rs (plcrun's semantics, docs/semantics.md
 * section 4): R_TRIG pulses on a CLK that is TRUE at the first call, CTU
 * counts on the rising edge of CU up to PVmax = 32767, TON records its start
 * on the call where IN rises and uses the clock of the cycle it runs in.
 * The functions are static inline: a C compiler inlines FBs declared in the
 * same translation unit, as the Rust references' `#[inline]` calls are. */
#ifndef PLCRUN_BENCH_FBS_H
#define PLCRUN_BENCH_FBS_H

#include <stdbool.h>
#include <stdint.h>

/* The program state is read and written by unknown code between cycles
 * (the C counterpart of std::hint::black_box at the start of each Rust
 * reference's cycle): nothing is folded or hoisted across cycles, while
 * the work inside a cycle is optimised normally. */
#define OPAQUE(p) __asm__ volatile("" : "+r"(p) : : "memory")

/* R_TRIG: Q := CLK AND NOT M; M := CLK. */
typedef struct {
    bool clk, q, m;
} RTrig;

static inline void rtrig_call(RTrig *t, bool clk)
{
    t->clk = clk;
    t->q = clk && !t->m;
    t->m = clk;
}

/* CTU, INT variant. */
typedef struct {
    bool cu, r, q, cu_m;
    int16_t pv, cv;
} Ctu;

static inline void ctu_call(Ctu *c, bool cu, bool r, int16_t pv)
{
    c->cu = cu;
    c->r = r;
    c->pv = pv;
    bool rose = cu && !c->cu_m;
    c->cu_m = cu;
    if (r)
        c->cv = 0;
    else if (rose && c->cv < INT16_MAX)
        c->cv += 1;
    c->q = c->cv >= pv;
}

/* TON on the cycle clock; times in ns. */
typedef struct {
    bool in, q, prev_in;
    int64_t pt, et, start;
} Ton;

static inline void ton_call(Ton *t, bool in, int64_t pt, int64_t now)
{
    t->in = in;
    t->pt = pt;
    if (in) {
        if (!t->prev_in)
            t->start = now;
        int64_t et = now - t->start;
        if (et > pt)
            et = pt;
        t->et = et;
        t->q = et >= pt;
    } else {
        t->q = false;
        t->et = 0;
    }
    t->prev_in = in;
}

/* DINT arithmetic wraps around (two's complement), as in plcrun. */
static inline int32_t wadd(int32_t a, int32_t b) { return (int32_t)((uint32_t)a + (uint32_t)b); }
static inline int32_t wmul(int32_t a, int32_t b) { return (int32_t)((uint32_t)a * (uint32_t)b); }

/* Each benchmark: a fresh state, one cycle at clock value `now` (ns), the
 * program's checksum. */
#define BENCH_DECL(n)                                                          \
    void *bench_##n##_new(void);                                               \
    void bench_##n##_cycle(void *state, int64_t now);                          \
    int32_t bench_##n##_checksum(const void *state);

BENCH_DECL(a)
BENCH_DECL(b)
BENCH_DECL(c)
BENCH_DECL(d)

#endif
