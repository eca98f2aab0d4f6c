/* One build of vtdyn behind three exported entry points, for the A/B driver (bench/ab/ab.c).
 * Compiled once per tree against that tree's headers and examples/scenes.c, linked with its
 * libvtdyn.a into a shared object that exports only ab_setup, ab_batch and ab_check
 * (bench/ab/build.sh). Public API only. The scenes and their states are bench/bench_inverse.c's.
 * build.sh defines AB_HAVE_<scene function> for each builder the tree's scenes.h declares. */
#define _POSIX_C_SOURCE 200809L
#include <math.h>
#include <string.h>
#include <time.h>

#include "scenes.h"

#define AB_EXPORT __attribute__((visibility("default")))

static vt_model *m;
static vt_data *d;
#if defined(AB_HAVE_vt_scene_delta_ik) || defined(AB_HAVE_vt_scene_stewart) || defined(AB_HAVE_vt_scene_knee)
#define AB_MACHINE_T 0.1 /* bench_inverse.c's instant of the machines */
#endif
#ifdef AB_HAVE_vt_scene_delta_ik
static vt_delta_ik delta_ik;
#endif
#ifdef AB_HAVE_vt_scene_stewart
static vt_stewart stewart = {3.14159265358979323846, 0.0, {{0}}};
#endif

static void release(void)
{
    vt_data_free(d);
    vt_model_free(m);
    d = NULL;
    m = NULL;
}

/* builds the scene's model and data at a consistent instant: 0, or 1 (unknown scene, or its
 * builder is missing in this tree), 2 (build failed), 3 (the instant fails) */
AB_EXPORT int ab_setup(const char *scene, int n)
{
    release();
    vt_status st = VT_OK;
    int known = 0;
    if (strcmp(scene, "chain") == 0 || strcmp(scene, "chain_tip") == 0) {
#ifdef AB_HAVE_vt_scene_chain
        known = 1;
        st = vt_scene_chain(&m, n, strcmp(scene, "chain") == 0 ? VT_CHAIN_JOINT_DRIVEN : VT_CHAIN_TIP_DRIVE);
        if (!st) st = vt_data_create(&d, m);
        if (!st) {
            double qdd;
            for (int k = 0; k < m->nv; k++) vt_scene_chain_state(k, &d->q[k], &d->qd[k], &qdd);
            d->time = 0.0;
        }
#endif
    } else if (strcmp(scene, "double_link") == 0) {
#ifdef AB_HAVE_vt_scene_double_link
        known = 1;
        st = vt_scene_double_link(&m, 1);
        if (!st) st = vt_data_create(&d, m);
        if (!st) {
            d->q[0] = -0.6;
            d->qd[0] = -sqrt(7.3575 * sin(0.6));
        }
#endif
    } else if (strcmp(scene, "fourbar") == 0) {
#ifdef AB_HAVE_vt_scene_fourbar
        known = 1;
        st = vt_scene_fourbar(&m, vt_function_sine(0.3, 1.0, 2.0, 0.0));
        if (!st) st = vt_data_create(&d, m);
        if (!st && vt_scene_fourbar_assemble(m, d, 0.3, 1.0, NULL, NULL)) st = VT_ERR_NULL;
#endif
    } else if (strcmp(scene, "fourbar_rusr") == 0) {
#ifdef AB_HAVE_vt_scene_fourbar_rusr
        known = 1;
        st = vt_scene_fourbar_rusr(&m, vt_function_sine(0.3, 1.0, 2.0, 0.0));
        if (!st) st = vt_data_create(&d, m);
        if (!st && vt_scene_fourbar_rusr_assemble(m, d, 0.3, 1.0, NULL, NULL)) st = VT_ERR_NULL;
#endif
    } else if (strcmp(scene, "delta") == 0) {
#ifdef AB_HAVE_vt_scene_delta_ik
        known = 1;
        st = vt_scene_delta_ik(&m, &delta_ik, 1.0);
        if (!st) st = vt_data_create(&d, m);
        if (!st) {
            double p[3];
            vt_scene_delta_path(AB_MACHINE_T, 1.0, p, NULL, NULL);
            if (vt_scene_delta_assemble(m, d, p)) st = VT_ERR_NEWTON;
            d->time = AB_MACHINE_T;
            if (!st) st = vt_kinematic_solve(m, d, 1e-13, 30);
        }
#endif
    } else if (strcmp(scene, "stewart") == 0) {
#ifdef AB_HAVE_vt_scene_stewart
        known = 1;
        st = vt_scene_stewart(&m, &stewart);
        if (!st) st = vt_data_create(&d, m);
        if (!st) {
            vt_scene_stewart_assemble(m, d, &stewart, AB_MACHINE_T);
            st = vt_kinematic_solve(m, d, 1e-13, 30);
        }
#endif
    } else if (strcmp(scene, "knee") == 0) {
#ifdef AB_HAVE_vt_scene_knee
        known = 1;
        const double pi = 3.14159265358979323846;
        st = vt_scene_knee(&m, vt_function_sine(-0.25 * pi, 0.35, 4.0 * pi, 0.0),
                           vt_function_sine(0.5 * pi, 0.4, 4.0 * pi, 0.8), 1);
        if (!st) st = vt_data_create(&d, m);
        if (!st) {
            double hip[3], mot[3];
            vt_function_eval(hip, &m->drive[0].f, AB_MACHINE_T);
            vt_function_eval(mot, &m->drive[1].f, AB_MACHINE_T);
            if (vt_scene_knee_assemble(m, d, hip[0], hip[1], mot[0], mot[1], NULL)) st = VT_ERR_NEWTON;
            d->time = AB_MACHINE_T;
            if (!st) st = vt_kinematic_solve(m, d, 1e-13, 30);
        }
#endif
    } else if (strcmp(scene, "five_link") == 0) {
#ifdef AB_HAVE_vt_scene_five_link
        known = 1;
        st = vt_scene_five_link(&m);
        if (!st) st = vt_data_create(&d, m);
        if (!st) {
            vt_scene_five_link_guess(m, d, 0.1);
            d->time = 0.1;
            st = vt_kinematic_solve(m, d, 1e-13, 30);
        }
#endif
    }
    if (!known) return 1;
    if (st) {
        release();
        return 2;
    }
    if (vt_inverse_dynamics_recursive(m, d)) {
        release();
        return 3;
    }
    return 0;
}

/* seconds taken by `calls` recursive instants (CLOCK_MONOTONIC); negative if one fails */
AB_EXPORT double ab_batch(long calls)
{
    struct timespec t0, t1;
    int bad = 0;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    for (long i = 0; i < calls; i++) bad |= vt_inverse_dynamics_recursive(m, d) != VT_OK;
    clock_gettime(CLOCK_MONOTONIC, &t1);
    return bad ? -1.0 : (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
}

/* the outputs of one fresh instant (drive efforts, q̇-space drive forces, joint and cut
 * reactions) into out[0..cap-1]; returns how many there are (-1 if the instant fails), and
 * their checksum Σ|v| in *sum */
AB_EXPORT int ab_check(double *out, int cap, double *sum)
{
    if (!m || vt_inverse_dynamics_recursive(m, d)) return -1;
    const struct { const double *v; int n; } part[] = {
        {d->drive_effort, m->ndrive},         {d->qfrc_drive, m->nv},
        {d->jnt_force, 3 * (m->nbody + 1)},   {d->jnt_moment, 3 * (m->nbody + 1)},
        {d->cut_force, 3 * m->ncut},          {d->cut_moment, 3 * m->ncut},
    };
    int k = 0;
    *sum = 0.0;
    for (size_t p = 0; p < sizeof part / sizeof part[0]; p++)
        for (int i = 0; i < part[p].n; i++, k++) {
            if (k < cap) out[k] = part[p].v[i];
            *sum += fabs(part[p].v[i]);
        }
    return k;
}
