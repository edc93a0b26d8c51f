/*
 * plcrun.h: the C interface of plcrun, an IEC 61131-3 soft-PLC core.
 *
 * Link with libplcrun_capi.a (add -lpthread -ldl -lm) or libplcrun_capi.so,
 * both built by `cargo build -p plcrun-capi` (target/<profile>/).
 * docs/embedding.md, "From C", explains the rules below with an example;
 * examples/c/counter.c is a complete program.
 *
 * This header is written by hand; capi/tests/header.rs checks that it
 * declares every entry point of the library with the same parameter and
 * return types, and the same status codes.
 *
 * Rules for every function:
 * - The return value is a status: PLC_OK (0) or a negative PLC_E_* code.
 *   plc_last_error() then gives the message (valid until the next plc_*
 *   call on the same thread).
 * - Pointers that a function reads or writes must not be NULL (else
 *   PLC_E_NULL_ARGUMENT), except where said. Text in is NUL-terminated
 *   UTF-8 and is copied: the caller keeps ownership.
 * - Handles are checked values, not pointers: a handle that was freed,
 *   never created, zero, or (for plc_var) resolved by another PLC gives
 *   PLC_E_INVALID_HANDLE. Nothing the library returns is to be freed by
 *   the caller except a PLC (plc_free).
 * - Text out ("buf, capacity, needed"): the text and its NUL are copied
 *   into buf when capacity is large enough; *needed (if needed is not
 *   NULL) gets the size that holds it, NUL included, whether or not it
 *   fit. When it does not fit, buf holds "" and the result is
 *   PLC_E_BUFFER_TOO_SMALL. buf may be NULL when capacity is 0, to ask
 *   for the size.
 * - No Rust panic crosses this interface: a bug inside plcrun returns
 *   PLC_E_PANIC, and the PLC it happened in refuses later calls with
 *   PLC_E_PANIC (free it).
 * - Threads: a PLC may be used from any thread; calls on one PLC are
 *   serialised (a lock per PLC); different PLCs run in parallel. The one
 *   exception is plc_abort, through a stop token: it takes no PLC lock, so
 *   it ends a cycle that another thread is running.
 */
#ifndef PLCRUN_H
#define PLCRUN_H

#include <stdbool.h>
#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* The interface version this header describes; plc_abi_version() gives
 * the library's. */
#define PLC_ABI_VERSION 1

/* ---- Status codes ------------------------------------------------------ */

enum plc_status {
    PLC_OK = 0,
    PLC_E_NULL_ARGUMENT = -1,    /* a required pointer argument is NULL */
    PLC_E_INVALID_HANDLE = -2,   /* invalid or freed handle */
    PLC_E_INVALID_ARGUMENT = -3, /* text not UTF-8, cycle time <= 0, no source */
    PLC_E_COMPILE = -4,          /* the sources do not compile (diagnostics in plc_last_error) */
    PLC_E_UNKNOWN_VARIABLE = -5, /* no such variable, or not a single value */
    PLC_E_BAD_VALUE = -6,        /* the literal is not a value of the variable's type */
    PLC_E_WRONG_TYPE = -7,       /* typed accessor on a variable of another type, or
                                    image accessor on an address of another width */
    PLC_E_OUT_OF_RANGE = -8,     /* the number does not fit the variable's type */
    PLC_E_RUNTIME_FAULT = -9,    /* the cycle stopped on a runtime fault */
    PLC_E_FAULTED = -10,         /* the PLC is stopped on an earlier fault */
    PLC_E_BUFFER_TOO_SMALL = -11, /* see "Text out" above */
    PLC_E_PANIC = -12,           /* internal error caught at the boundary */
    PLC_E_READ_ONLY = -13,       /* CONSTANT, SFC step/action flag, or the %Q area */
    PLC_E_BAD_ADDRESS = -14,     /* not an image address, or one with no place in it */
    PLC_E_ADDRESS_OUT_OF_RANGE = -15, /* past the end of its image area */
    PLC_E_RETAIN_FILE = -16,     /* retain file unreadable, unwritable or damaged */
    PLC_E_RETAIN_MISMATCH = -17, /* retain file of other variables; nothing restored */
    PLC_E_UNKNOWN_TASK = -18,    /* no task of that name */
    PLC_E_NOT_PERMITTED = -19,   /* the system refused a real-time setting */
    PLC_E_SERVER = -20           /* the OPC UA server could not start */
};

/* A static description of a status ("unknown status" for other values). */
const char *plc_status_text(int status);

/* The message of the last plc_* call on this thread ("" after success). */
const char *plc_last_error(void);

/* ---- Version ----------------------------------------------------------- */

/* The library's version, e.g. "0.1.0" (static). */
const char *plc_version(void);

/* The interface version the library implements (compare with
 * PLC_ABI_VERSION). */
int plc_abi_version(void);

/* ---- Creating and freeing a PLC ---------------------------------------- */

/* A compiled PLC with its state. Zero-initialised is invalid. */
typedef struct plc_handle {
    uint64_t id;
} plc_handle;

/* One source file. The name's extension chooses the language (.st, .il,
 * .sfc); the name appears in diagnostics and fault locations. */
typedef struct plc_source {
    const char *name;
    const char *text;
} plc_source;

typedef struct plc_options {
    int64_t cycle_time_ns; /* cycle of the implicit task, > 0 (default 10 ms) */
    const char *program;   /* the PROGRAM to run if there are several, or NULL */
    int64_t watchdog_ns;   /* wall-clock limit of one cycle; <= 0: none (default 1 s) */
} plc_options;

/* Fills *options with the defaults. */
int plc_options_init(plc_options *options);

/* Compiles count source files (options may be NULL for the defaults) and
 * stores the new PLC in *out ({0} on failure). PLC_E_COMPILE: the
 * diagnostics, with file:line:column, are in plc_last_error(). */
int plc_create(const plc_source *sources, size_t count, const plc_options *options,
               plc_handle *out);

/* Frees a PLC; its handle and variable handles become invalid. */
int plc_free(plc_handle plc);

/* The compilation's warnings, rendered ("" when none). Text out. */
int plc_warnings(plc_handle plc, char *buf, size_t capacity, size_t *needed);

/* ---- Cycles and the virtual clock -------------------------------------- */

/* Runs one cycle (every task due at this tick), then advances the clock.
 * PLC_E_RUNTIME_FAULT: plc_last_error() gives the fault, its POU,
 * file:line:column and cycle; the PLC is then stopped (later cycles give
 * PLC_E_FAULTED until a reset; variables stay readable and writable). */
int plc_run_cycle(plc_handle plc);

/* Cold reset: every variable back to its initial value (retained ones
 * too), cycle and clock back to 0, the fault and any abort cleared; cycles
 * run again. Watchdog limits, forces and plc_var handles stay. */
int plc_reset_cold(plc_handle plc);

/* Warm reset: as plc_reset_cold, but RETAIN and PERSISTENT variables keep
 * their values. */
int plc_reset_warm(plc_handle plc);

/* Whether the PLC is stopped on a fault. */
int plc_is_faulted(plc_handle plc, bool *out);

/* The fault that stopped the PLC ("" when none). Text out. */
int plc_fault_message(plc_handle plc, char *buf, size_t capacity, size_t *needed);

/* The number of the next cycle (0 before the first). */
int plc_cycle(plc_handle plc, uint64_t *out);

/* The virtual clock at the start of the next cycle, in nanoseconds. */
int plc_time_ns(plc_handle plc, int64_t *out);

/* The cycle time (base tick), in nanoseconds. */
int plc_cycle_time_ns(plc_handle plc, int64_t *out);

/* ---- Variables ---------------------------------------------------------
 * A path names one value as on the command line: `x`, `inst.Q`, `arr[3]`,
 * `grid[1,2]`, `S1.X`, `prog.x`, `%IX0.1` (case-insensitive). Literals are
 * IEC literals of the variable's type: TRUE, 42, 16#FF, 2.5, T#1s500ms,
 * 'text', an enumeration value's name.
 *
 * Typed accessors, and the types they accept (others: PLC_E_WRONG_TYPE):
 *   bool    BOOL
 *   int64_t SINT..LINT, USINT..ULINT, BYTE..LWORD, subranges, enumerations
 *           (the value's number), TIME and LTIME (nanoseconds)
 *   double  REAL, LREAL (a REAL is rounded to the nearest REAL on writing)
 * A number the type cannot hold is PLC_E_OUT_OF_RANGE.
 */

/* A variable resolved once for repeated access; valid until its PLC is
 * freed; needs no freeing. Zero-initialised is invalid. */
typedef struct plc_var {
    uint64_t id;
} plc_var;

int plc_resolve(plc_handle plc, const char *path, plc_var *out);

/* By path. */
int plc_get_literal(plc_handle plc, const char *path, char *buf, size_t capacity,
                    size_t *needed);
int plc_set_literal(plc_handle plc, const char *path, const char *literal);
int plc_get_bool(plc_handle plc, const char *path, bool *out);
int plc_set_bool(plc_handle plc, const char *path, bool value);
int plc_get_i64(plc_handle plc, const char *path, int64_t *out);
int plc_set_i64(plc_handle plc, const char *path, int64_t value);
int plc_get_f64(plc_handle plc, const char *path, double *out);
int plc_set_f64(plc_handle plc, const char *path, double value);

/* By resolved handle. */
int plc_var_get_literal(plc_handle plc, plc_var var, char *buf, size_t capacity,
                        size_t *needed);
int plc_var_set_literal(plc_handle plc, plc_var var, const char *literal);
int plc_var_get_bool(plc_handle plc, plc_var var, bool *out);
int plc_var_set_bool(plc_handle plc, plc_var var, bool value);
int plc_var_get_i64(plc_handle plc, plc_var var, int64_t *out);
int plc_var_set_i64(plc_handle plc, plc_var var, int64_t value);
int plc_var_get_f64(plc_handle plc, plc_var var, double *out);
int plc_var_set_f64(plc_handle plc, plc_var var, double value);

/* ---- Forcing and soft writes -------------------------------------------
 * A forced variable keeps its value whatever the program or the host
 * writes (forces are applied before and after every program run) until it
 * is unforced. An unknown path is PLC_E_UNKNOWN_VARIABLE, a literal not of
 * the variable's type PLC_E_BAD_VALUE, a CONSTANT or an SFC step/action
 * flag (S1.X) PLC_E_READ_ONLY.
 */

/* Forces path to the literal (again: replaces the value). */
int plc_force(plc_handle plc, const char *path, const char *literal);

/* Releases the force on path; *was_forced (was_forced may be NULL) says
 * whether it was forced (not being forced is no error). The variable keeps
 * the forced value, or the last value soft-written while it was forced. */
int plc_unforce(plc_handle plc, const char *path, bool *was_forced);

/* Releases every force. */
int plc_unforce_all(plc_handle plc);

/* A write that a force overrides (every plc_set_* is one). */
int plc_soft_write(plc_handle plc, const char *path, const char *literal);

/* The forces are listed by index 0 .. count-1, in the order of forcing:
 * plc_force_at gives the path and the value (a literal), each under the
 * "text out" rules with its own buffer; if either is too small both hold
 * "" and both *needed are set. An index >= count: PLC_E_INVALID_ARGUMENT. */
int plc_force_count(plc_handle plc, size_t *out);
int plc_force_at(plc_handle plc, size_t index, char *path_buf, size_t path_capacity,
                 size_t *path_needed, char *value_buf, size_t value_capacity,
                 size_t *value_needed);

/* ---- The process image -------------------------------------------------
 * %I (inputs), %Q (outputs) and %M (memory) are byte areas, each as long
 * as the highest address the program uses there. Inputs are latched at
 * the start of a task's cycle, outputs published at its end. Addresses are
 * as in the language: %IX0.3 (bit 3 of byte 0), %IB2, %QW4, %MD8, %QL8,
 * and the Moeller form %I0.0.0.0.1; which bytes a word names follows the
 * PLC's addressing convention (below; docs/runtime.md, "Addressing"):
 * under PLC_ADDRESSING_IEC %QW4 is bytes 8-9 (little-endian), under
 * PLC_ADDRESSING_BYTE bytes 4-5, under PLC_ADDRESSING_OPENPLC word 4 of
 * a %QW table of its own (each size of each area is then a table apart:
 * the area functions below reach the byte table, %IB/%QB/%MB, the table
 * functions every one).
 * The host writes %I and %M only
 * (%Q: PLC_E_READ_ONLY). Errors: PLC_E_BAD_ADDRESS (syntax, bit > 7, a
 * non-zero leading field), PLC_E_ADDRESS_OUT_OF_RANGE (past the area's
 * end), PLC_E_WRONG_TYPE (an accessor of another width than the address,
 * e.g. plc_image_read_word on %IX0.1).
 */

enum plc_area {
    PLC_AREA_INPUT = 0,  /* %I */
    PLC_AREA_OUTPUT = 1, /* %Q */
    PLC_AREA_MEMORY = 2  /* %M */
};

int plc_image_read_bit(plc_handle plc, const char *address, bool *out);
int plc_image_read_byte(plc_handle plc, const char *address, uint8_t *out);
int plc_image_read_word(plc_handle plc, const char *address, uint16_t *out);
int plc_image_read_dword(plc_handle plc, const char *address, uint32_t *out);
int plc_image_read_lword(plc_handle plc, const char *address, uint64_t *out);
int plc_image_write_bit(plc_handle plc, const char *address, bool value);
int plc_image_write_byte(plc_handle plc, const char *address, uint8_t value);
int plc_image_write_word(plc_handle plc, const char *address, uint16_t value);
int plc_image_write_dword(plc_handle plc, const char *address, uint32_t value);
int plc_image_write_lword(plc_handle plc, const char *address, uint64_t value);

/* Whole areas (area: a plc_area value, else PLC_E_INVALID_ARGUMENT). The
 * copies cover bytes offset .. offset+length-1 of the area
 * (PLC_E_ADDRESS_OUT_OF_RANGE past its end); buf / data may be NULL when
 * length is 0. */
int plc_image_area_size(plc_handle plc, int area, size_t *out);
int plc_image_read_area(plc_handle plc, int area, size_t offset, uint8_t *buf, size_t length);
int plc_image_write_area(plc_handle plc, int area, size_t offset, const uint8_t *data,
                         size_t length);

/* The table of one size of one area (PLC_WIDTH_*): under
 * PLC_ADDRESSING_OPENPLC each size is a table of its own (%QX, %QW, %MD...),
 * under IEC and BYTE every size of an area is the area. Size, copies out
 * and in (%I and %M only) as for the areas above. */
enum plc_width {
    PLC_WIDTH_BIT = 0,   /* X */
    PLC_WIDTH_BYTE = 1,  /* B */
    PLC_WIDTH_WORD = 2,  /* W */
    PLC_WIDTH_DWORD = 3, /* D */
    PLC_WIDTH_LWORD = 4  /* L */
};

int plc_image_table_size(plc_handle plc, int area, int width, size_t *out);
int plc_image_read_table(plc_handle plc, int area, int width, size_t offset, uint8_t *buf,
                         size_t length);
int plc_image_write_table(plc_handle plc, int area, int width, size_t offset,
                          const uint8_t *data, size_t length);

/* How direct addresses are numbered. The default follows the sources:
 * BYTE for S7-200 STL, OPENPLC for PLCopen XML from the OpenPLC Editor or
 * Beremiz, IEC otherwise. */
enum plc_addressing {
    PLC_ADDRESSING_IEC = 0,     /* CODESYS: %QWn is bytes 2n..2n+1 */
    PLC_ADDRESSING_OPENPLC = 1, /* matiec: %QX, %QW, %MW, %MD, %ML separate tables */
    PLC_ADDRESSING_BYTE = 2     /* S7: every number a byte offset */
};

/* Lays the image out again under a PLC_ADDRESSING_* convention (call it
 * before the first cycle): located variables keep their values and the
 * overlap warnings (W203) of plc_warnings are judged again. An unknown
 * code: PLC_E_INVALID_ARGUMENT. */
int plc_set_addressing(plc_handle plc, int addressing);
/* The PLC's convention (PLC_ADDRESSING_*) into *out. */
int plc_addressing(plc_handle plc, int *out);

/* ---- Retained data -----------------------------------------------------
 * RETAIN and PERSISTENT variables, in a JSON file with IEC literals that
 * carries the retained variables' names and types (docs/runtime.md).
 */

/* Saves them to path, atomically (old or new file, never a torn one).
 * PLC_E_RETAIN_FILE when it cannot be written. */
int plc_retain_save(plc_handle plc, const char *path);

/* Restores them from path. A file of other variables (names, types) is
 * PLC_E_RETAIN_MISMATCH, the message saying what differs, and nothing is
 * restored; with partial true the values that fit are restored instead.
 * *restored (restored may be NULL) gets how many values were. Unreadable
 * or damaged: PLC_E_RETAIN_FILE. */
int plc_retain_restore(plc_handle plc, const char *path, bool partial, size_t *restored);

/* ---- Real time ------------------------------------------------------------ */

/* Prepares the calling thread, the one that will call plc_run_cycle on the
 * wall clock: priority 1-99 runs it under SCHED_FIFO (0: keep the policy),
 * cpu >= 0 pins it to that CPU (-1: keep the affinity), lock_memory locks
 * the process's memory (mlockall) and pre-faults the thread's stack. The
 * thread's timer slack is set to 1 ns in every case. PLC_E_NOT_PERMITTED
 * when the system refuses the priority or the lock (plc_last_error says
 * what would permit it; the settings before it were applied),
 * PLC_E_INVALID_ARGUMENT for a priority over 99 or an unavailable CPU.
 * Linux only (elsewhere only (0, -1, false) succeeds). */
int plc_rt_setup(int priority, int cpu, bool lock_memory);

/* ---- Watchdog and abort ------------------------------------------------ */

/* The watchdog limit of the task named task (case-insensitive; "default"
 * for a program without configuration), or of every task when task is
 * NULL, in milliseconds; 0 turns it off, < 0 is PLC_E_INVALID_ARGUMENT.
 * A cycle that runs longer stops with PLC_E_RUNTIME_FAULT (R008). */
int plc_set_watchdog_ms(plc_handle plc, const char *task, int64_t limit_ms);

/* A stop token: aborts its PLC's cycle from another thread. Zero-
 * initialised is invalid. */
typedef struct plc_stop {
    uint64_t id;
} plc_stop;

/* Makes a token for plc into *out ({0} on failure); take it before
 * starting the cycle to abort (this call waits for the PLC's lock). It
 * stays valid until plc_stop_token_free, even after plc_free (an abort
 * then does nothing). */
int plc_stop_token(plc_handle plc, plc_stop *out);

/* Aborts the running cycle without taking the PLC's lock: it stops at its
 * next backward jump or call, even in an endless loop, and plc_run_cycle
 * returns PLC_E_RUNTIME_FAULT (R009, aborted); the PLC is then faulted
 * until a reset. With no cycle running, the next one is aborted. */
int plc_abort(plc_stop token);

/* Frees a token. */
int plc_stop_token_free(plc_stop token);

/* ---- OPC UA server ------------------------------------------------------
 * Serves the PLC's variables over OPC UA (docs/opcua.md) while the host
 * runs plc_run_cycle, which then exchanges with the server after each
 * cycle: clients read the last cycle's values, their writes land before
 * the next one, forced variables stay forced.
 */
enum {
    PLC_OPCUA_ALLOW_INSECURE = 1, /* also serve SecurityPolicy None (read-only) */
    PLC_OPCUA_TRUST_CLIENTS = 2   /* accept every client certificate */
};

/* Starts a server on address ("127.0.0.1:4840"; port 0 for a free one)
 * serving every variable. users_file (NULL: none; anonymous clients only
 * read) is written by `plcrun opcua-user add`; pki_dir keeps the server's
 * certificate, made on first start. flags: PLC_OPCUA_*. A server already
 * running on this PLC is stopped first. PLC_E_SERVER when it cannot start
 * (plc_last_error gives the E95x code and the reason). */
int plc_opcua_start(plc_handle plc, const char *address, const char *users_file,
                    const char *pki_dir, uint32_t flags);

/* The port it listens on into *port, and the namespace index of the
 * variables' NodeIds (ns=<index>;s=<path>) into *ns_index (may be NULL).
 * PLC_E_INVALID_ARGUMENT when no server runs. */
int plc_opcua_port(plc_handle plc, uint16_t *port, uint16_t *ns_index);

/* Stops the server (nothing when none runs); plc_free stops it too. */
int plc_opcua_stop(plc_handle plc);

/* ---- Reserved for the next versions ------------------------------------
 * Each feature below gets a section of its own here, with its status codes
 * appended after PLC_E_UNKNOWN_TASK (existing values never change):
 * - Real-time running on a thread with per-task statistics.
 * - Online change (loading a new program version between cycles).
 * - Host-registered native functions and function blocks.
 */

#ifdef __cplusplus
}
#endif

#endif /* PLCRUN_H */
