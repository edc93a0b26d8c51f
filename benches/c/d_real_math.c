/* C reference of bench_d_real_math.st (ported from
 * benches/native/d_real_math.rs): 1000 PID-like loops per cycle on arrays of
 * REAL (float), with SIN for the set-point, SQRT(ABS(u)) in a first-order
 * plant model and an anti-windup clamp. float arithmetic in the ST's
 * evaluation order (built with -ffp-contract=off: no fused multiply-add),
 * the ST's literals as float, REAL_TO_DINT rounding halves away from zero
 * (roundf). sinf and sqrtf are the C library's, which Rust's f32::sin and
 * f32::sqrt call or compile to as well. */
#include <math.h>
#include <stdlib.h>

#include "fbs.h"

enum { LOOPS = 1000 };
#define PHASE_WRAP 6.2831853f

typedef struct {
    int32_t checksum, cycles;
    float pv[LOOPS], integ[LOOPS], prev_err[LOOPS], outp[LOOPS];
    int32_t i;
    float x, phase, sp, err, deriv, u, acc, kp, ki, kd, tstep;
} BenchD;

void *bench_d_new(void)
{
    BenchD *s = calloc(1, sizeof *s);
    if (!s)
        abort();
    s->kp = 1.2f;
    s->ki = 0.5f;
    s->kd = 0.05f;
    s->tstep = 0.01f;
    return s;
}

void bench_d_cycle(void *state, int64_t now)
{
    BenchD *s = state;
    OPAQUE(s);
    OPAQUE(now);
    s->cycles = wadd(s->cycles, 1);
    s->phase += 0.001f;
    if (s->phase > PHASE_WRAP)
        s->phase -= PHASE_WRAP;
    const float kp = s->kp, ki = s->ki, kd = s->kd, tstep = s->tstep, phase = s->phase;
    float acc = 0.0f, x = 0.0f;
    float sp = s->sp, err = s->err, deriv = s->deriv, u = s->u;
    for (int i = 0; i < LOOPS; i++) {
        sp = 50.0f + 40.0f * sinf(phase + x);
        err = sp - s->pv[i];
        float integ = s->integ[i] + ki * err * tstep;
        if (integ > 100.0f)
            integ = 100.0f;
        else if (integ < -100.0f)
            integ = -100.0f;
        s->integ[i] = integ;
        deriv = (err - s->prev_err[i]) / tstep;
        u = kp * err + integ + kd * deriv;
        s->prev_err[i] = err;
        s->pv[i] = s->pv[i] + (u - s->pv[i]) * 0.05f + 0.01f * sqrtf(fabsf(u));
        s->outp[i] = u;
        acc += u;
        x += 0.00628f;
    }
    s->i = LOOPS;
    s->sp = sp;
    s->err = err;
    s->deriv = deriv;
    s->u = u;
    s->acc = acc;
    s->x = x;
    s->checksum = (int32_t)roundf(acc * 10.0f);
}

int32_t bench_d_checksum(const void *state)
{
    return ((const BenchD *)state)->checksum;
}
