/* C reference of bench_a_bool_logic.st (ported from
 * benches/native/a_bool_logic.rs): a 16-bit LFSR feeds 16 inputs; 10 chains
 * of 20 steps with a transition condition, a step equation, a TON and an
 * action output per step. The ST's 200-fold straight-line repetitions are
 * loops over arrays here (tests/native_reference.rs proves the tables equal
 * the ST text). */
#include <stdlib.h>

#include "fbs.h"

enum { STEPS = 200, CHAIN_LEN = 20, CHAINS = STEPS / CHAIN_LEN, PATTERN_STEPS = 3 };
#define TIMER_PT_NS 20000000LL

typedef struct {
    int32_t checksum, cycles;
    uint16_t lfsr;
    int32_t wraps, pattern;
    bool inputs[16];
    bool x[STEPS], c[STEPS], y[STEPS];
    Ton t[STEPS];
} BenchA;

/* Input indices [a, b, c, d] of Ck := Xk AND ((in[a] XOR in[b]) OR (in[c]
 * AND NOT in[d])), by k mod 16. */
static uint8_t inputs_of[16][4];

static int predecessor(int k)
{
    return k % CHAIN_LEN == 0 ? k + CHAIN_LEN - 1 : k - 1;
}

void *bench_a_new(void)
{
    BenchA *s = calloc(1, sizeof *s);
    if (!s)
        abort();
    for (int k = 0; k < 16; k++) {
        inputs_of[k][0] = (uint8_t)k;
        inputs_of[k][1] = (uint8_t)((3 * k + 1) % 16);
        inputs_of[k][2] = (uint8_t)((5 * k + 2) % 16);
        inputs_of[k][3] = (uint8_t)((7 * k + 5) % 16);
    }
    s->lfsr = 0xACE1;
    for (int chain = 0; chain < CHAINS; chain++)
        s->x[chain * CHAIN_LEN] = true;
    return s;
}

void bench_a_cycle(void *state, int64_t now)
{
    BenchA *s = state;
    OPAQUE(s);
    OPAQUE(now);
    s->cycles = wadd(s->cycles, 1);

    s->lfsr = (s->lfsr & 1) ? (uint16_t)((s->lfsr >> 1) ^ 0xB400) : (uint16_t)(s->lfsr >> 1);
    for (int bit = 0; bit < 16; bit++)
        s->inputs[bit] = (s->lfsr & (1u << bit)) != 0;

    const bool *in = s->inputs;
    for (int k = 0; k < STEPS; k++) {
        const uint8_t *t = inputs_of[k % 16];
        bool a = in[t[0]], b = in[t[1]], c = in[t[2]], d = in[t[3]];
        s->c[k] = s->x[k] && ((a != b) || (c && !d));
    }
    for (int k = 0; k < STEPS; k++)
        s->x[k] = (s->x[k] && !s->c[k]) || s->c[predecessor(k)];
    for (int k = 0; k < STEPS; k++) {
        ton_call(&s->t[k], s->x[k], TIMER_PT_NS, now);
        s->y[k] = s->x[k] && !s->t[k].q;
    }
    for (int chain = 0; chain < CHAINS; chain++)
        if (s->c[chain * CHAIN_LEN + CHAIN_LEN - 1])
            s->wraps = wadd(s->wraps, 1);
    int32_t pattern = 0, weight = 1;
    for (int chain = 0; chain < CHAINS; chain++)
        for (int offset = 0; offset < PATTERN_STEPS; offset++) {
            if (s->x[chain * CHAIN_LEN + offset])
                pattern = wadd(pattern, weight);
            weight++;
        }
    s->pattern = pattern;
    s->checksum = wadd(wmul(s->wraps, 1000), s->pattern);
}

int32_t bench_a_checksum(const void *state)
{
    return ((const BenchA *)state)->checksum;
}
