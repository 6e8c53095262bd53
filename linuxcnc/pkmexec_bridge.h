/* The C face of pkm's executor of planned motion for LinuxCNC's pkmexec component (linuxcnc/pkmexec.c,
 * docs/linuxcnc.md). The executor itself is src/execution/step_executor.hpp: it takes the nominal periods of
 * `pkm linuxcnc stream` and releases one period of whole drive steps per servo period, scaled in time by the
 * feed override, a feed hold or an abort within the drives' limits.
 *
 * pkmexec_create reads the machine file and allocates (once, when the module loads); every other function
 * never allocates, never blocks and never throws: they run in the servo thread. Positions are whole steps
 * (int64); set points are in steps too. */
#ifndef PKM_LINUXCNC_PKMEXEC_BRIDGE_H
#define PKM_LINUXCNC_PKMEXEC_BRIDGE_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

#define PKMEXEC_MAX_DRIVES 6

typedef struct pkmexec_executor pkmexec_executor;

/* The state of the executor, as the component's `state` pin gives it. */
enum pkmexec_state {
    PKMEXEC_IDLE = 0,             /* no program yet */
    PKMEXEC_RUNNING = 1,          /* moving, or held at K = 0 by the operator */
    PKMEXEC_STARVED = 2,          /* slowing or stopped: the stream has not delivered enough periods ahead */
    PKMEXEC_FINISHED = 3,         /* the program's last period has been released */
    PKMEXEC_ABORTED = 4,          /* stopped by an abort, the rest of the program dropped */
    PKMEXEC_STOPPED_AT_LIMIT = 5, /* stopped before a position outside the drives' software stops */
    PKMEXEC_REFUSED = 6,          /* a program that does not start where the drives are */
    PKMEXEC_NOT_HANDED_OVER = 7   /* a program that came while the drives were not handed over (the enable
                                     pin false: LinuxCNC off, not homed, or moving) */
};

struct pkmexec_period_out {
    long long position[PKMEXEC_MAX_DRIVES]; /* whole steps at the period's end */
    long long steps[PKMEXEC_MAX_DRIVES];    /* in this period */
    double set_point[PKMEXEC_MAX_DRIVES];   /* the continuous set point, in steps */
    int line;
    double factor; /* the time-scaling factor K at the period's end (1 = as planned) */
    double tau;    /* nominal periods of the program executed */
    int state;     /* enum pkmexec_state */
};

/* Reads the machine file; the servo period in seconds sets the override's rates. NULL on failure with the
 * message (file, line, key) in `error`. */
pkmexec_executor* pkmexec_create(const char* machine_file, double period_s, char* error, size_t error_size);
void pkmexec_free(pkmexec_executor* executor);

int pkmexec_drive_count(const pkmexec_executor* executor);
/* One step in the joints' unit (mm, or degrees for angular actuators). */
double pkmexec_step(const pkmexec_executor* executor);
/* The drives' positions at the machine file's home, in whole steps. */
void pkmexec_home_steps(const pkmexec_executor* executor, long long* steps);

/* A new program starting from `start` (whole steps), the drives handed over to the executor or not. 0; -1
 * when they were not (state PKMEXEC_NOT_HANDED_OVER) or are more than one step from `start` (state
 * PKMEXEC_REFUSED), until the next start. */
int pkmexec_start(pkmexec_executor* executor, const long long* start, int handed_over);
/* The executor commands the drives: a program is running, held, or waiting for its stream. */
int pkmexec_active(const pkmexec_executor* executor);
/* While it is not active, the drives are where something else put them (LinuxCNC's motion controller jogs
 * and homes them): the executor follows them (positions in the joints' unit, taken to the nearest step), and
 * the next program must start there. */
void pkmexec_follow(pkmexec_executor* executor, const double* position);
/* Room for another nominal period. */
int pkmexec_has_room(const pkmexec_executor* executor);
/* One nominal period (call with room). 0; -1 when it is outside the software stops (the executor stops
 * before it). */
int pkmexec_push(pkmexec_executor* executor, int line, const double* ideal, const long long* position);
void pkmexec_end_of_program(pkmexec_executor* executor);
/* One servo period with the operator's controls. */
void pkmexec_period(pkmexec_executor* executor, double override_factor, int hold, int abort,
                    struct pkmexec_period_out* out);
int pkmexec_state(const pkmexec_executor* executor);
int pkmexec_fault_line(const pkmexec_executor* executor);
long pkmexec_periods_ahead(const pkmexec_executor* executor);

#ifdef __cplusplus
}
#endif

#endif
