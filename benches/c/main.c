/* Timing driver of the C references, run by benches/perf.rs:
 *
 *     plcrun-bench-c NAME CYCLES      (NAME: a, b, c or d)
 *
 * runs a fresh instance for CYCLES cycles (cycle k at k x 10 ms on the
 * virtual clock, as plcrun and the Rust references) and prints the wall time
 * of that loop in ns per cycle and the checksum: "NS_PER_CYCLE CHECKSUM".
 * Only the loop of cycles is timed (as the harness times plcrun's and the
 * Rust references' batches in process): not the process start, nor the
 * allocation of the state. The cycle functions live in other translation
 * units (and are opaque to each other), so no work moves across cycles. */
#define _POSIX_C_SOURCE 199309L /* clock_gettime under -std=c11 */

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "fbs.h"

#define CYCLE_NS 10000000LL

static double seconds(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + (double)t.tv_nsec * 1e-9;
}

#define RUN(n)                                                                 \
    do {                                                                       \
        void *s = bench_##n##_new();                                           \
        double t0 = seconds();                                                 \
        for (long long k = 0; k < cycles; k++)                                 \
            bench_##n##_cycle(s, k * CYCLE_NS);                                \
        double t1 = seconds();                                                 \
        printf("%.3f %ld\n", (t1 - t0) * 1e9 / (double)cycles,                 \
               (long)bench_##n##_checksum(s));                                 \
        free(s);                                                               \
        return 0;                                                              \
    } while (0)

int main(int argc, char **argv)
{
    if (argc != 3) {
        fprintf(stderr, "usage: %s a|b|c|d CYCLES\n", argv[0]);
        return 2;
    }
    long long cycles = atoll(argv[2]);
    if (cycles <= 0) {
        fprintf(stderr, "CYCLES must be positive\n");
        return 2;
    }
    if (!strcmp(argv[1], "a"))
        RUN(a);
    if (!strcmp(argv[1], "b"))
        RUN(b);
    if (!strcmp(argv[1], "c"))
        RUN(c);
    if (!strcmp(argv[1], "d"))
        RUN(d);
    fprintf(stderr, "unknown benchmark %s\n", argv[1]);
    return 2;
}
