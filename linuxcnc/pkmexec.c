/* pkmexec: pkm's executor of planned motion as a LinuxCNC real-time component (docs/linuxcnc.md).
 *
 *   loadrt pkmexec machine=/path/to/machine.yaml period_ns=1000000
 *   addf pkmexec.update servo-thread
 *
 * It creates a HAL stream (key 0x706b6d78, "pkmx") that linuxcnc/pkm_feed.py fills from `pkm linuxcnc
 * stream` while the program runs, and each servo period releases the drives' next whole-step positions:
 * the planned steps themselves at 100 % feed, time-scaled within the drives' limits under the feed override,
 * a feed hold or an abort (pkmexec_bridge.h). A new program may follow the last one without reloading; it must
 * start where the drives are.
 *
 * Pins (J = 0 … drives − 1):
 *   in  float pkmexec.feed-override   K the operator asks for (1 = 100 %; 0 … 1.2)
 *   in  bit   pkmexec.feed-hold       stop along the path; resume when released
 *   in  bit   pkmexec.abort           stop along the path and drop the rest of the program
 *   in  bit   pkmexec.enable          the drives are handed over: a program may start (default true)
 *   in  float pkmexec.J.pos-fb        where the drive is, in the joints' unit, while pkmexec does not move it
 *   out bit   pkmexec.active          pkmexec commands the drives: a program running, held or waiting, and
 *                                     after it until the drives reach its last command (1 s at most)
 *   out s32   pkmexec.J.counts        the drive's position, whole steps
 *   out s32   pkmexec.J.steps         its steps in this period
 *   out float pkmexec.J.pos-cmd       counts × step (mm, or degrees): a position command for a drive
 *   out float pkmexec.J.set-point     the continuous set point the counts are rounded from (same unit)
 *   out s32   pkmexec.state           0 idle, 1 running, 2 starved, 3 finished, 4 aborted, 5 stopped at a
 *                                     software stop, 6 refused (the program starts elsewhere), 7 not
 *                                     handed over (a program came while enable was false)
 *   out s32   pkmexec.line            program line being executed; pkmexec.fault-line: the software stop's
 *   out float pkmexec.factor          K now; pkmexec.tau: nominal periods executed
 *   out s32   pkmexec.periods-ahead   nominal periods waiting; pkmexec.programs: programs started
 *   out s32   pkmexec.exec-time-ns    this function's time in the last period; pkmexec.exec-time-max-ns */
#include "hal.h"
#include "rtapi.h"
#include "rtapi_app.h"
#include "pkmexec_bridge.h"

MODULE_LICENSE("GPL");
MODULE_AUTHOR("pkm");
MODULE_DESCRIPTION("pkm executor of planned motion");

static char* machine = "";
RTAPI_MP_STRING(machine, "pkm machine file (YAML)");
static int period_ns = 1000000;
RTAPI_MP_INT(period_ns, "servo thread period, ns (sets the override's rates; must match the thread)");

#define PKMEXEC_STREAM_KEY 0x706b6d78
#define PKMEXEC_STREAM_DEPTH 4096
/* kind, line, ideal × 6, position × 6 */
#define PKMEXEC_ROW_TYPES "ssffffffssssss"
#define PKMEXEC_ROW_START 1
#define PKMEXEC_ROW_PERIOD 2
#define PKMEXEC_ROW_END 3
/* Rows taken per period at most (bounds the function's time; the stream runs ahead by thousands). */
#define PKMEXEC_ROWS_PER_PERIOD 8

struct drive_pins {
    hal_s32_t* counts;
    hal_s32_t* steps;
    hal_float_t* pos_cmd;
    hal_float_t* set_point;
    hal_float_t* pos_fb;
};

struct pkmexec_pins {
    hal_float_t* feed_override;
    hal_bit_t* feed_hold;
    hal_bit_t* abort;
    hal_bit_t* enable;
    hal_bit_t* active;
    hal_s32_t* state;
    hal_s32_t* line;
    hal_s32_t* fault_line;
    hal_float_t* factor;
    hal_float_t* tau;
    hal_s32_t* periods_ahead;
    hal_s32_t* programs;
    hal_s32_t* exec_time_ns;
    hal_s32_t* exec_time_max_ns;
    struct drive_pins drive[PKMEXEC_MAX_DRIVES];
};

static int comp_id = -1;
static pkmexec_executor* executor = 0;
static struct pkmexec_pins* pins = 0;
static hal_stream_t stream;
static int stream_created = 0;
static int drives = 0;
static double step = 0.001;
static int discarding = 0; /* dropping the rest of a program that was aborted, stopped or refused */
/* Periods left holding the last command of a program that has ended, until the drives reach it (servo drives
 * lag their command): pkmexec hands the drives back only where it left them, or after a second at most. */
static int holding = 0;
static int settle_periods = 1000;

static int may_take_row(void) {
    int state = pkmexec_state(executor);
    if (discarding || state == PKMEXEC_IDLE || state == PKMEXEC_FINISHED) return 1;
    return pkmexec_has_room(executor);
}

static void take_row(const union hal_stream_data* row) {
    long long position[PKMEXEC_MAX_DRIVES];
    double ideal[PKMEXEC_MAX_DRIVES];
    int j;
    for (j = 0; j < drives; ++j) {
        ideal[j] = row[2 + j].f;
        position[j] = row[2 + PKMEXEC_MAX_DRIVES + j].s;
    }
    switch (row[0].s) {
    case PKMEXEC_ROW_START:
        discarding = pkmexec_start(executor, position, *pins->enable) != 0;
        *pins->programs += 1;
        break;
    case PKMEXEC_ROW_PERIOD:
        if (!discarding && pkmexec_push(executor, row[1].s, ideal, position) != 0) discarding = 1;
        break;
    case PKMEXEC_ROW_END:
        if (!discarding) pkmexec_end_of_program(executor);
        discarding = 0;
        break;
    default:
        break;
    }
}

/* Where the drives are while something else commands them. */
static void follow_drives(void) {
    double position[PKMEXEC_MAX_DRIVES];
    int j;
    for (j = 0; j < drives; ++j) position[j] = *pins->drive[j].pos_fb;
    pkmexec_follow(executor, position);
}

/* Every drive within half a step of pkmexec's command. */
static int drives_at_command(void) {
    int j;
    for (j = 0; j < drives; ++j) {
        double error = *pins->drive[j].pos_fb - *pins->drive[j].pos_cmd;
        if (error > 0.5 * step || error < -0.5 * step) return 0;
    }
    return 1;
}

static void update(void* arg, long period) {
    union hal_stream_data row[HAL_STREAM_MAX_PINS];
    struct pkmexec_period_out out;
    long long started = rtapi_get_time(), elapsed;
    int taken = 0, was_active, j;
    (void)arg;
    (void)period;
    if (!pkmexec_active(executor) && !holding) follow_drives();
    while (taken < PKMEXEC_ROWS_PER_PERIOD && may_take_row() && hal_stream_readable(&stream) &&
           hal_stream_read(&stream, row, 0) == 0) {
        take_row(row);
        ++taken;
    }
    was_active = pkmexec_active(executor);
    pkmexec_period(executor, *pins->feed_override, *pins->feed_hold, *pins->abort, &out);
    if (pkmexec_active(executor))
        holding = 0;
    else if (was_active)
        holding = settle_periods; /* the last period's command goes out; the drives then have to reach it */
    else if (holding && (drives_at_command() || --holding == 0))
        holding = 0;
    if (out.state == PKMEXEC_ABORTED || out.state == PKMEXEC_STOPPED_AT_LIMIT) discarding = 1;
    for (j = 0; j < drives; ++j) {
        *pins->drive[j].counts = (hal_s32_t)out.position[j];
        *pins->drive[j].steps = (hal_s32_t)out.steps[j];
        *pins->drive[j].pos_cmd = (double)out.position[j] * step;
        *pins->drive[j].set_point = out.set_point[j] * step;
    }
    *pins->state = out.state;
    *pins->active = pkmexec_active(executor) || holding;
    *pins->line = out.line;
    *pins->fault_line = pkmexec_fault_line(executor);
    *pins->factor = out.factor;
    *pins->tau = out.tau;
    *pins->periods_ahead = (hal_s32_t)pkmexec_periods_ahead(executor);
    elapsed = rtapi_get_time() - started;
    *pins->exec_time_ns = (hal_s32_t)elapsed;
    if (elapsed > *pins->exec_time_max_ns) *pins->exec_time_max_ns = (hal_s32_t)elapsed;
}

static int export_pins(void) {
    int res = 0, j;
    res += hal_pin_float_newf(HAL_IN, &pins->feed_override, comp_id, "pkmexec.feed-override");
    res += hal_pin_bit_newf(HAL_IN, &pins->feed_hold, comp_id, "pkmexec.feed-hold");
    res += hal_pin_bit_newf(HAL_IN, &pins->abort, comp_id, "pkmexec.abort");
    res += hal_pin_bit_newf(HAL_IN, &pins->enable, comp_id, "pkmexec.enable");
    res += hal_pin_bit_newf(HAL_OUT, &pins->active, comp_id, "pkmexec.active");
    res += hal_pin_s32_newf(HAL_OUT, &pins->state, comp_id, "pkmexec.state");
    res += hal_pin_s32_newf(HAL_OUT, &pins->line, comp_id, "pkmexec.line");
    res += hal_pin_s32_newf(HAL_OUT, &pins->fault_line, comp_id, "pkmexec.fault-line");
    res += hal_pin_float_newf(HAL_OUT, &pins->factor, comp_id, "pkmexec.factor");
    res += hal_pin_float_newf(HAL_OUT, &pins->tau, comp_id, "pkmexec.tau");
    res += hal_pin_s32_newf(HAL_OUT, &pins->periods_ahead, comp_id, "pkmexec.periods-ahead");
    res += hal_pin_s32_newf(HAL_OUT, &pins->programs, comp_id, "pkmexec.programs");
    res += hal_pin_s32_newf(HAL_OUT, &pins->exec_time_ns, comp_id, "pkmexec.exec-time-ns");
    res += hal_pin_s32_newf(HAL_OUT, &pins->exec_time_max_ns, comp_id, "pkmexec.exec-time-max-ns");
    for (j = 0; j < drives; ++j) {
        res += hal_pin_s32_newf(HAL_OUT, &pins->drive[j].counts, comp_id, "pkmexec.%d.counts", j);
        res += hal_pin_s32_newf(HAL_OUT, &pins->drive[j].steps, comp_id, "pkmexec.%d.steps", j);
        res += hal_pin_float_newf(HAL_OUT, &pins->drive[j].pos_cmd, comp_id, "pkmexec.%d.pos-cmd", j);
        res += hal_pin_float_newf(HAL_OUT, &pins->drive[j].set_point, comp_id, "pkmexec.%d.set-point", j);
        res += hal_pin_float_newf(HAL_IN, &pins->drive[j].pos_fb, comp_id, "pkmexec.%d.pos-fb", j);
    }
    return res;
}

static void fail_cleanup(void) {
    if (stream_created) hal_stream_destroy(&stream);
    stream_created = 0;
    if (comp_id >= 0) hal_exit(comp_id);
    comp_id = -1;
    pkmexec_free(executor);
    executor = 0;
}

int rtapi_app_main(void) {
    char error[1024];
    long long home[PKMEXEC_MAX_DRIVES];
    int j;
    executor = pkmexec_create(machine, period_ns * 1e-9, error, sizeof error);
    if (!executor) {
        rtapi_print_msg(RTAPI_MSG_ERR, "pkmexec: %s\n", error);
        return -1;
    }
    drives = pkmexec_drive_count(executor);
    settle_periods = period_ns > 0 ? 1000000000 / period_ns : 1000;
    step = pkmexec_step(executor);
    comp_id = hal_init("pkmexec");
    if (comp_id < 0) {
        fail_cleanup();
        return -1;
    }
    pins = hal_malloc(sizeof(struct pkmexec_pins));
    if (!pins || export_pins() != 0) {
        rtapi_print_msg(RTAPI_MSG_ERR, "pkmexec: could not export its pins\n");
        fail_cleanup();
        return -1;
    }
    if (hal_stream_create(&stream, comp_id, PKMEXEC_STREAM_KEY, PKMEXEC_STREAM_DEPTH, PKMEXEC_ROW_TYPES) < 0) {
        rtapi_print_msg(RTAPI_MSG_ERR, "pkmexec: could not create its stream (key 0x%x)\n", PKMEXEC_STREAM_KEY);
        fail_cleanup();
        return -1;
    }
    stream_created = 1;
    if (hal_export_funct("pkmexec.update", update, 0, 1, 0, comp_id) != 0) {
        rtapi_print_msg(RTAPI_MSG_ERR, "pkmexec: could not export its function\n");
        fail_cleanup();
        return -1;
    }
    *pins->feed_override = 1.0;
    *pins->enable = 1;
    pkmexec_home_steps(executor, home);
    for (j = 0; j < drives; ++j) {
        *pins->drive[j].counts = (hal_s32_t)home[j];
        *pins->drive[j].pos_cmd = (double)home[j] * step;
        *pins->drive[j].set_point = (double)home[j] * step;
        *pins->drive[j].pos_fb = (double)home[j] * step;
    }
    rtapi_print_msg(RTAPI_MSG_INFO, "pkmexec: %s, %d drives, step %g\n", machine, drives, step);
    hal_ready(comp_id);
    return 0;
}

void rtapi_app_exit(void) { fail_cleanup(); }
