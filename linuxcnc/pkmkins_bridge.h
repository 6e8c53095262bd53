/* The C face of pkm's kinematics for LinuxCNC's pkmkins module (linuxcnc/pkmkins.c, docs/linuxcnc.md).
 *
 * LinuxCNC builds its real-time modules as C with its own flags, and its headers are C, so the module is a thin C
 * file over these functions; they are C++ inside and reach the mechanism only through pkm's Mechanism interface.
 *
 * World coordinates are LinuxCNC's: world[0..2] = X, Y, Z in mm (the tool point in the machine's base frame)
 * and world[3..5] = A, B, C in degrees, G-code's and LinuxCNC's angles R = Rz(C)·Ry(B)·Rx(A) whatever the
 * machine file's own convention (`angles:`), as `pkm plan` reads a program (docs/part-programs.md, "What A, B
 * and C mean"); planar machines: C is the turn φ. A machine that controls only some of the angles (a 3-RPS
 * tripod) must be written in `angles: abc`, else pkmkins_load refuses it. Joints are the actuators in the
 * machine file's order: strut lengths or carriage positions in mm, or degrees for carriages on a circle.
 *
 * pkmkins_load allocates (once, when the module loads); pkmkins_inverse and pkmkins_forward never allocate, never
 * block and never throw: they run in the servo thread. */
#ifndef PKM_LINUXCNC_PKMKINS_BRIDGE_H
#define PKM_LINUXCNC_PKMKINS_BRIDGE_H

#include <stddef.h>

#ifdef __cplusplus
extern "C" {
#endif

typedef struct pkmkins_machine pkmkins_machine;

/* Reads a pkm machine file. NULL on failure, with the reader's message (file, line, column, key) in `error`. */
pkmkins_machine* pkmkins_load(const char* machine_file, char* error, size_t error_size);
void pkmkins_free(pkmkins_machine* machine);

int pkmkins_joint_count(const pkmkins_machine* machine);
/* The version of pkm the module was built from ("0.1.0"), as pkm --version prints it. */
const char* pkmkins_version(void);
/* The coordinates the machine controls as LinuxCNC axis letters, e.g. "XYZABC" or "ZAB". */
const char* pkmkins_coordinates(const pkmkins_machine* machine);

/* The machine file's home pose and its joints; also restarts forward kinematics from home. 0, or -1 when home is
 * out of reach. */
int pkmkins_home(pkmkins_machine* machine, double world[6], double* joints);

/* Inverse kinematics. 0, or -1 when the pose is out of reach (joints unspecified) or a coordinate the machine
 * controls is not finite. Angular joints (carriages on a circle) come back on the turn of the last joints
 * commanded or solved, so that a carriage going round stays continuous past a full turn. */
int pkmkins_inverse(pkmkins_machine* machine, const double world[6], double* joints);

/* Forward kinematics, warm-started from the previous solution (the machine's home at first), in its assembly mode.
 * The A, B, C angles come back unwrapped to the turn of the previous solution, so that a C axis past 360 degrees stays
 * there. 0; -1 when Newton does not converge to the tolerance, or converges in another assembly mode (world is
 * then left unchanged and the next call starts again from the last good solution). */
int pkmkins_forward(pkmkins_machine* machine, const double* joints, double world[6]);

/* Counters for HAL pins: forward solves done, failed, and the Newton iterations of the last one. */
void pkmkins_forward_counts(const pkmkins_machine* machine, long* solves, long* failures, int* last_iterations);

#ifdef __cplusplus
}
#endif

#endif
