/* pkmkins: pkm's kinematics as a LinuxCNC kinematics module (docs/linuxcnc.md).
 *
 *   loadrt pkmkins machine=/path/to/machine.yaml
 *
 * The machine file is read once, here in rtapi_app_main (never in the servo thread); the kinematics are pkm's
 * through pkmkins_bridge.h. Forward kinematics warm-start from the previous solution and report non-convergence
 * as a failure (-1), never as a wrong pose. Joint count and axis letters follow the machine: see
 * pkmkins.coordinates in the log and `pkm linuxcnc config`, which writes a configuration that matches. */
#include "hal.h"
#include "kinematics.h"
#include "motion.h"
#include "rtapi.h"
#include "rtapi_app.h"
#include "pkmkins_bridge.h"

MODULE_LICENSE("GPL");
MODULE_AUTHOR("pkm");
MODULE_DESCRIPTION("pkm parallel-kinematic machine kinematics");

static char* machine = "";
RTAPI_MP_STRING(machine, "pkm machine file (YAML) to load");

struct pkmkins_pins {
    hal_u32_t* fk_solves;     /* forward solves since load */
    hal_u32_t* fk_failures;   /* of which did not converge (or left the assembly mode) */
    hal_u32_t* fk_iterations; /* Newton iterations of the last converged forward solve */
    hal_bit_t* fk_failed;     /* the last forward solve failed */
};

static int comp_id = -1;
static pkmkins_machine* kins = 0;
static struct pkmkins_pins* pins = 0;

static void publish_counts(int failed) {
    long solves = 0, failures = 0;
    int iterations = 0;
    if (!pins) return;
    pkmkins_forward_counts(kins, &solves, &failures, &iterations);
    *pins->fk_solves = (hal_u32_t)solves;
    *pins->fk_failures = (hal_u32_t)failures;
    *pins->fk_iterations = (hal_u32_t)iterations;
    *pins->fk_failed = failed ? 1 : 0;
}

static void world_from_emc(const EmcPose* pos, double world[6]) {
    world[0] = pos->tran.x;
    world[1] = pos->tran.y;
    world[2] = pos->tran.z;
    world[3] = pos->a;
    world[4] = pos->b;
    world[5] = pos->c;
}

static void emc_from_world(const double world[6], EmcPose* pos) {
    pos->tran.x = world[0];
    pos->tran.y = world[1];
    pos->tran.z = world[2];
    pos->a = world[3];
    pos->b = world[4];
    pos->c = world[5];
}

int kinematicsForward(const double* joints, EmcPose* pos, const KINEMATICS_FORWARD_FLAGS* fflags,
                      KINEMATICS_INVERSE_FLAGS* iflags) {
    double world[6];
    int result;
    (void)fflags;
    (void)iflags;
    world_from_emc(pos, world);
    result = pkmkins_forward(kins, joints, world);
    publish_counts(result != 0);
    if (result != 0) return -1;
    emc_from_world(world, pos);
    return 0;
}

int kinematicsInverse(const EmcPose* pos, double* joints, const KINEMATICS_INVERSE_FLAGS* iflags,
                      KINEMATICS_FORWARD_FLAGS* fflags) {
    double world[6];
    (void)iflags;
    (void)fflags;
    world_from_emc(pos, world);
    return pkmkins_inverse(kins, world, joints) == 0 ? 0 : -1;
}

int kinematicsHome(EmcPose* world_pos, double* joints, KINEMATICS_FORWARD_FLAGS* fflags,
                   KINEMATICS_INVERSE_FLAGS* iflags) {
    double world[6];
    *fflags = 0;
    *iflags = 0;
    if (pkmkins_home(kins, world, joints) != 0) return -1;
    emc_from_world(world, world_pos);
    return 0;
}

KINEMATICS_TYPE kinematicsType(void) { return KINEMATICS_BOTH; }

KINS_NOT_SWITCHABLE
EXPORT_SYMBOL(kinematicsType);
EXPORT_SYMBOL(kinematicsForward);
EXPORT_SYMBOL(kinematicsInverse);
EXPORT_SYMBOL(kinematicsHome);

int rtapi_app_main(void) {
    char error[1024];
    int res = 0;
    kins = pkmkins_load(machine, error, sizeof error);
    if (!kins) {
        rtapi_print_msg(RTAPI_MSG_ERR, "pkmkins: %s\n", error);
        return -1;
    }
    comp_id = hal_init("pkmkins");
    if (comp_id < 0) {
        pkmkins_free(kins);
        kins = 0;
        return comp_id;
    }
    pins = hal_malloc(sizeof(struct pkmkins_pins));
    if (!pins) {
        rtapi_print_msg(RTAPI_MSG_ERR, "pkmkins: hal_malloc failed\n");
        hal_exit(comp_id);
        return -1;
    }
    res += hal_pin_u32_newf(HAL_OUT, &pins->fk_solves, comp_id, "pkmkins.fk-solves");
    res += hal_pin_u32_newf(HAL_OUT, &pins->fk_failures, comp_id, "pkmkins.fk-failures");
    res += hal_pin_u32_newf(HAL_OUT, &pins->fk_iterations, comp_id, "pkmkins.fk-iterations");
    res += hal_pin_bit_newf(HAL_OUT, &pins->fk_failed, comp_id, "pkmkins.fk-failed");
    if (res) {
        rtapi_print_msg(RTAPI_MSG_ERR, "pkmkins: could not export its pins\n");
        hal_exit(comp_id);
        return -1;
    }
    publish_counts(0);
    rtapi_print_msg(RTAPI_MSG_INFO, "pkmkins (pkm %s): %s, %d joints, coordinates %s\n", pkmkins_version(),
                    machine, pkmkins_joint_count(kins), pkmkins_coordinates(kins));
    hal_ready(comp_id);
    return 0;
}

void rtapi_app_exit(void) {
    if (comp_id >= 0) hal_exit(comp_id);
    pkmkins_free(kins);
    kins = 0;
}
