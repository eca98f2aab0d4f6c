/* MuJoCo's models of the examples' closed-loop machines (examples/scenes.h: vt_scene_delta,
 * vt_scene_stewart, vt_scene_knee), written once for the MuJoCo peer (mujoco_peer.c: the inverse
 * instants of bench_inverse.c) and the forward comparisons (delta_mujoco.c, stewart_mujoco.c,
 * knee_mujoco.c). The same bodies, masses, inertias and joints as vtdyn's scenes, each loop
 * closed by an equality `connect` between two sites (the loops are open at qpos0); see
 * mujoco_scenes.c for each model. Needs MuJoCo's headers and examples/scenes.h. */
#ifndef VT_BENCH_MUJOCO_SCENES_H
#define VT_BENCH_MUJOCO_SCENES_H

#include <mujoco/mujoco.h>

enum { VT_MJ_DELTA, VT_MJ_STEWART, VT_MJ_KNEE };

/* flags of vt_mj_scene_model */
enum {
    /* the Delta: MuJoCo's default constraint settings (timestep 0.002, solref "0.02 1", solimp
     * "0.9 0.95 0.001 0.5 2") instead of the stiff ones every other model has (timestep 1e-4,
     * solref "2e-4 1", solimp "0.9999 0.9999 0.001 0.5 2") */
    VT_MJ_DEFAULT_SOFT = 1,
    /* the Stewart platform and the knee: their drives as joint equalities after the connects
     * (Stewart: equalities 6..11 hold slide i at the constant term eq_data[mjNEQDATA (6 + i)];
     * knee: equalities 1, 2 the hip and the motor), for a forward simulation that follows vtdyn's
     * drives; without it the drives' coordinates are free (an inverse instant's motors) */
    VT_MJ_DRIVE_EQUALITIES = 2
};

/* The machine's model, NULL on failure (the reason on stderr). */
mjModel *vt_mj_scene_model(int machine, int flags);

/* Where vtdyn's coordinates, rates and bodies are in MuJoCo's model m of the machine: qadr[k]
 * the qpos address of vtdyn's coordinate k (k < nq), vadr[k] the dof of vtdyn's rate k (k < nv),
 * body[b] MuJoCo's body of vtdyn's body b (b = 1..nbody; body[0] = 0, the world); free[b] = 1
 * where vtdyn's body b is on a free joint. A free joint keeps its order in both (qpos: the
 * position, then w x y z; dofs: linear, then angular); its rates differ in the angular part:
 * vtdyn's angular velocity and acceleration are in world axes, MuJoCo's in the body's
 * (vt_mj_scene_state converts). The Stewart platform and the knee are laid out as vtdyn's
 * (identity maps); the Delta's MJCF nests each arm's rods in the arm. Returns 0, or -1 when
 * m is not that machine's model. */
enum { VT_MJ_MAXQ = 32, VT_MJ_MAXB = 16 };
typedef struct {
    int nq, nv, nbody;
    int qadr[VT_MJ_MAXQ], vadr[VT_MJ_MAXQ];
    int body[VT_MJ_MAXB], free[VT_MJ_MAXB];
    int bvadr[VT_MJ_MAXB];   /* vtdyn's first rate of body b */
} vt_mj_map;
int vt_mj_scene_map(int machine, const mjModel *m, vt_mj_map *map);

/* vtdyn's state (q: nq coordinates, qd and qdd: nv rates, in vtdyn's layout; qdd may be NULL)
 * into MuJoCo's qpos, qvel and qacc: a free joint's angular rates turned into the body's axes
 * (ω_body = Aᵀ ω, ω̇_body = Aᵀ ω̇: A's derivative adds ω × ω = 0). */
void vt_mj_scene_state(const mjModel *m, const vt_mj_map *map, mjData *d, const double *q, const double *qd,
                       const double *qdd);

#endif /* VT_BENCH_MUJOCO_SCENES_H */
