/*
 * A C host around plcrun: compile a small Structured Text program, run it
 * cycle by cycle on the virtual clock, drive an input, read the outputs,
 * and handle errors. Built and run by capi/tests/c_example.rs:
 *
 *   cc -std=c11 -Wall -Wextra -Werror -I include examples/c/counter.c \
 *      target/debug/libplcrun_capi.a -lpthread -ldl -lm -o counter
 */
#include <inttypes.h>
#include <stdio.h>
#include <stdlib.h>

#include "plcrun.h"

static const char *const SOURCE =
    "PROGRAM Counter\n"
    "VAR_INPUT enable : BOOL; limit : INT := 5; END_VAR\n"
    "VAR_OUTPUT count : INT; done : BOOL; ratio : REAL; END_VAR\n"
    "IF enable AND NOT done THEN count := count + 1; END_IF;\n"
    "done := count >= limit;\n"
    "ratio := INT_TO_REAL(count) / INT_TO_REAL(limit);\n"
    "END_PROGRAM\n";

/* Stops the program with the library's message when a call fails. */
static void check(int status, const char *what) {
    if (status != PLC_OK) {
        fprintf(stderr, "%s: %s: %s\n", what, plc_status_text(status), plc_last_error());
        exit(1);
    }
}

int main(void) {
    if (plc_abi_version() != PLC_ABI_VERSION) {
        fprintf(stderr, "plcrun.h does not match the library\n");
        return 1;
    }
    plc_source source = {"counter.st", SOURCE};
    plc_options options;
    check(plc_options_init(&options), "plc_options_init");
    options.cycle_time_ns = 100000000; /* 100 ms */

    plc_handle plc;
    check(plc_create(&source, 1, &options, &plc), "plc_create");

    /* Resolve the variables read every cycle once. */
    plc_var count, done;
    check(plc_resolve(plc, "count", &count), "resolve count");
    check(plc_resolve(plc, "done", &done), "resolve done");
    check(plc_set_i64(plc, "limit", 4), "set limit");

    for (int i = 0; i < 7; i++) {
        if (i == 2) {
            check(plc_set_bool(plc, "enable", true), "set enable");
        }
        int64_t now;
        check(plc_time_ns(plc, &now), "time");
        check(plc_run_cycle(plc), "cycle");
        int64_t n;
        bool finished;
        char ratio[32];
        check(plc_var_get_i64(plc, count, &n), "get count");
        check(plc_var_get_bool(plc, done, &finished), "get done");
        check(plc_get_literal(plc, "ratio", ratio, sizeof ratio, NULL), "get ratio");
        printf("t=%" PRId64 "ms count=%" PRId64 " done=%d ratio=%s\n", now / 1000000, n,
               finished, ratio);
    }

    /* Errors are values: a wrong name, a value that does not fit. */
    int status = plc_set_i64(plc, "limt", 3);
    printf("%s: %s\n", plc_status_text(status), plc_last_error());
    status = plc_set_i64(plc, "limit", 100000);
    printf("%s: %s\n", plc_status_text(status), plc_last_error());

    check(plc_free(plc), "plc_free");
    status = plc_free(plc);
    printf("second free: %s\n", plc_status_text(status));
    return 0;
}
