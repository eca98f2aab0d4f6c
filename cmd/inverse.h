/* The command's `inverse` (cmd/inverse.c): efforts and joint reactions from a CSV or .npy file of
 * states or of samples of a trajectory. */
#ifndef VTDYN_CMD_INVERSE_H
#define VTDYN_CMD_INVERSE_H

#include <stdio.h>

#include "vtdyn.h"

/* the output's groups of columns (--columns) */
#define COLS_EFFORT 1u /* each joint's effort (a floating root's six, world and link axes) */
#define COLS_WORLD 2u  /* each joint's reaction in world axes */
#define COLS_LINK 4u   /* each joint's reaction in its child link's axes (the URDF joint's frame) */
#define COLS_BEARING 8u /* each joint's bearing split: axial and radial force, axial and tilting moment */
#define COLS_LIMITS 16u /* each joint's excess beyond its position, velocity and effort limits */
#define COLS_PARTS 256u /* each joint's effort's parts: rigid-body, armature, damping, friction */

/* the most --payload options of one run */
#define CMD_PAYLOAD_MAX 64

/* the options of `inverse` */
typedef struct {
    int floating;       /* --floating: the root link floats */
    int threads;        /* -j: threads, 0 every CPU the process may use */
    unsigned groups;    /* --columns: COLS_* */
    int precision;      /* --precision: a CSV number's significant digits, 1 to 17; 0: the fewest that read back */
    int precision_given;
    double quat_tol;    /* --normalize-quaternions: a floating root's |norm − 1| normalised */
    int format;         /* --format: FMT_CSV or FMT_NPY (cmd/input.h), -1 by -o's name */
    int times;          /* --times: the rows and the time spent on standard error */
    const char *payload[CMD_PAYLOAD_MAX]; /* --payload: each LINK,mass,x,y,z[,inertia] as given */
    int npayload;
    const char *joint_params; /* --joint-params: a CSV file of joint,armature,damping,friction */
    int ideal;          /* --ideal-joints: the URDF's <dynamics> ignored */
    double inertia_tol; /* --inertia-tol: the inertia checks' tolerance, -1 the library's default */
    const char *contacts; /* --contacts: a CSV file of frame,mu (the feet on the ground) */
    const char *loads;  /* --loads: the frames F whose wrench columns F_fx ... F_nz the states hold */
} inverse_options;

/* `vtdyn inverse [options] URDF STATES [-o OUTPATH]`: one output row per input row, to OUTPATH
 * (written beside it and renamed when complete) or standard output when NULL; 0, or 1 with the
 * message printed */
int cmd_inverse(const char *urdf, const char *states, const char *outpath, const inverse_options *o);

/* `vtdyn info`'s line of the input columns of a states file for the robot p (loaded as `inverse`
 * loads it), comma separated, after a line saying what it is; 0, or 1 when `inverse` does not
 * take the robot (the line says why) */
int cmd_states_header(const vt_model *p, FILE *out);

#endif
