/* C reference of bench_c_fb_unrolled.st and bench_c_fb_array.st (ported from
 * benches/native/c_fb.rs): 1000 R_TRIG + 1000 CTU + 1000 TON instances per
 * cycle. Instance i sees CLK := ((cycles + i) MOD 4) < 2, counts the pulses
 * with CU := trig.Q, R := cnt.Q (the counter's previous Q) and
 * PV := 50 + i MOD 7, and times cnt.CV > 25 with PT := T#10ms. */
#include <stdlib.h>

#include "fbs.h"

enum { INSTANCES = 1000 };
#define TIMER_PT_NS 10000000LL

typedef struct {
    int32_t checksum, cycles;
    RTrig trig[INSTANCES];
    Ctu cnt[INSTANCES];
    Ton tmr[INSTANCES];
    int32_t i, phase, sum_cv, pulses, ton_q;
} BenchC;

void *bench_c_new(void)
{
    BenchC *s = calloc(1, sizeof *s);
    if (!s)
        abort();
    return s;
}

void bench_c_cycle(void *state, int64_t now)
{
    BenchC *s = state;
    OPAQUE(s);
    OPAQUE(now);
    s->cycles = wadd(s->cycles, 1);
    int32_t sum_cv = 0, ton_q = 0, pulses = s->pulses, phase = s->phase;
    for (int32_t i = 0; i < INSTANCES; i++) {
        phase = wadd(s->cycles, i) % 4;
        RTrig *trig = &s->trig[i];
        rtrig_call(trig, phase < 2);
        if (trig->q)
            pulses = wadd(pulses, 1);
        Ctu *cnt = &s->cnt[i];
        ctu_call(cnt, trig->q, cnt->q, (int16_t)(50 + i % 7));
        Ton *tmr = &s->tmr[i];
        ton_call(tmr, cnt->cv > 25, TIMER_PT_NS, now);
        if (tmr->q)
            ton_q = wadd(ton_q, 1);
        sum_cv = wadd(sum_cv, cnt->cv);
    }
    s->i = INSTANCES;
    s->phase = phase;
    s->pulses = pulses;
    s->sum_cv = sum_cv;
    s->ton_q = ton_q;
    s->checksum = wadd(sum_cv, wmul(pulses % 100000, 1000));
}

int32_t bench_c_checksum(const void *state)
{
    return ((const BenchC *)state)->checksum;
}
