/*
 * A C host exchanging a process image with plcrun, and forcing from C:
 * the host writes the inputs (%I) by address, runs a cycle, reads the
 * outputs (%Q) by address and as a block of bytes; then it forces an
 * output as a maintenance engineer would, lists the forces, releases
 * them, and shows what is refused. Built and run by
 * capi/tests/c_example.rs:
 *
 *   cc -std=c11 -Wall -Wextra -Werror -pedantic -I include examples/c/io_force.c \
 *      target/debug/libplcrun_capi.a -lpthread -ldl -lm -o io_force
 */
#include <stdio.h>
#include <stdlib.h>

#include "plcrun.h"

static const char *const SOURCE =
    "PROGRAM Tank\n"
    "VAR\n"
    "    start AT %IX0.0 : BOOL;\n"
    "    level AT %IW1 : INT;\n"
    "    pump AT %QX0.0 : BOOL;\n"
    "    alarm AT %QX0.1 : BOOL;\n"
    "    shown AT %QW1 : INT;\n"
    "END_VAR\n"
    "VAR CONSTANT high : INT := 80; END_VAR\n"
    "pump := start AND level < high;\n"
    "alarm := level >= high;\n"
    "shown := level * 10;\n"
    "END_PROGRAM\n";

static void check(int status, const char *what) {
    if (status != PLC_OK) {
        fprintf(stderr, "%s: %s: %s\n", what, plc_status_text(status), plc_last_error());
        exit(1);
    }
}

/* One scan: inputs in, a cycle, outputs out. */
static void scan(plc_handle plc, uint16_t level) {
    check(plc_image_write_bit(plc, "%IX0.0", true), "write start");
    check(plc_image_write_word(plc, "%IW1", level), "write level");
    check(plc_run_cycle(plc), "cycle");
    bool pump, alarm;
    uint16_t shown;
    check(plc_image_read_bit(plc, "%QX0.0", &pump), "read pump");
    check(plc_image_read_bit(plc, "%QX0.1", &alarm), "read alarm");
    check(plc_image_read_word(plc, "%QW1", &shown), "read shown");
    printf("level=%u pump=%d alarm=%d shown=%u\n", (unsigned)level, pump, alarm,
           (unsigned)shown);
}

/* Prints every force as path = value. */
static void list_forces(plc_handle plc) {
    size_t count;
    check(plc_force_count(plc, &count), "force count");
    printf("%zu forced\n", count);
    for (size_t i = 0; i < count; i++) {
        char path[64], value[64];
        check(plc_force_at(plc, i, path, sizeof path, NULL, value, sizeof value, NULL),
              "force at");
        printf("  %s = %s\n", path, value);
    }
}

/* Prints a call's status and message, for the refusals. */
static void show(const char *what, int status) {
    printf("%s: %s: %s\n", what, plc_status_text(status), plc_last_error());
}

int main(void) {
    plc_source source = {"tank.st", SOURCE};
    plc_handle plc;
    check(plc_create(&source, 1, NULL, &plc), "plc_create");

    size_t in_size, out_size;
    check(plc_image_area_size(plc, PLC_AREA_INPUT, &in_size), "size of %I");
    check(plc_image_area_size(plc, PLC_AREA_OUTPUT, &out_size), "size of %Q");
    printf("%%I: %zu bytes, %%Q: %zu bytes\n", in_size, out_size);

    for (uint16_t level = 0; level <= 90; level += 30) {
        scan(plc, level);
    }

    /* The whole output area as bytes: %QW1 is bytes 2-3 (words are numbered
     * by word, the default `iec` addressing), little-endian. */
    uint8_t outputs[4];
    check(plc_image_read_area(plc, PLC_AREA_OUTPUT, 0, outputs, sizeof outputs), "read %Q");
    printf("%%Q bytes: %02x %02x %02x %02x\n", outputs[0], outputs[1], outputs[2], outputs[3]);

    /* Maintenance: the pump is forced off whatever the program decides. */
    check(plc_force(plc, "pump", "FALSE"), "force pump");
    check(plc_force(plc, "level", "10"), "force level");
    list_forces(plc);
    scan(plc, 50); /* the host's 50 loses against the forced 10 */
    check(plc_unforce_all(plc), "unforce all");
    list_forces(plc);
    scan(plc, 50);

    /* What is refused, with the library's message. */
    show("force a constant", plc_force(plc, "high", "100"));
    show("write an output", plc_image_write_bit(plc, "%QX0.0", true));
    show("bad bit", plc_image_write_bit(plc, "%IX0.9", true));
    show("past the end", plc_image_write_word(plc, "%IW8", 1));
    show("wrong width", plc_image_write_word(plc, "%IX0.0", 1));

    check(plc_free(plc), "plc_free");
    return 0;
}
