/* C reference of bench_b_int_sieve.st (ported from
 * benches/native/b_int_sieve.rs): a full sieve of Eratosthenes to 10 000
 * every cycle, then the prime count folded into a hash modulo 65521. The
 * loop variables live in registers during the loops; their final values
 * are stored back, so the state after a cycle is the ST's. */
#include <stdlib.h>

#include "fbs.h"

enum { LIMIT = 10000 };

typedef struct {
    int32_t checksum, cycles;
    bool flags[LIMIT + 1];
    int32_t i, j, primes, hash;
} BenchB;

void *bench_b_new(void)
{
    BenchB *s = calloc(1, sizeof *s);
    if (!s)
        abort();
    return s;
}

void bench_b_cycle(void *state, int64_t now)
{
    BenchB *s = state;
    OPAQUE(s);
    OPAQUE(now);
    s->cycles = wadd(s->cycles, 1);

    int32_t i;
    for (i = 2; i <= LIMIT; i++)
        s->flags[i] = true;

    int32_t j = s->j;
    for (i = 2; wmul(i, i) <= LIMIT; i++)
        if (s->flags[i])
            for (j = wmul(i, i); j <= LIMIT; j = wadd(j, i))
                s->flags[j] = false;

    int32_t primes = 0, hash = s->cycles;
    for (i = 2; i <= LIMIT; i++)
        if (s->flags[i]) {
            primes = wadd(primes, 1);
            hash = wadd(wmul(hash, 31), i) % 65521;
        }
    s->i = i;
    s->j = j;
    s->primes = primes;
    s->hash = hash;
    s->checksum = wadd(wmul(primes, 100000), hash);
}

int32_t bench_b_checksum(const void *state)
{
    return ((const BenchB *)state)->checksum;
}
