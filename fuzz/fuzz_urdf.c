/* libFuzzer harness for the URDF loader: the bytes after the first are the XML, the first picks
 * the options (floating root, mimic couplings) and the given motion. The loader must answer
 * with a status: on failure no builder and a message; on success a builder that builds or is
 * refused with a status. A built tree without a base body is then run at q = 0 with a q̇ and q̈
 * from the first byte, and its efforts compared with the dense identity τ = M* q̈ − Q (the mass
 * matrix and forces stages): a loader that makes a model the two evaluations disagree on, or a
 * non-finite result after VT_OK, aborts. (Far from the origin the dense path's round-off grows
 * with the distance, a known limit: no comparison there.)
 * Build and run: bash fuzz/run.sh [seconds] (it runs this harness after fuzz_model). */
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "vtdyn.h"

#define MAX_XML (1 << 16)

static void check_finite(const double *a, int n)
{
    for (int i = 0; i < n; i++)
        if (!isfinite(a[i])) abort(); /* a VT_OK result must be finite */
}

static void run_model(const vt_model *m, unsigned pick)
{
    if (m->ncut > 0 || m->ncoupling > 0) return; /* mimic couplings: the motion of a tree only */
    for (int i = 1; i <= m->nbody; i++)
        if (m->body_joint[i] == VT_JOINT_BASE) return;
    vt_data *d;
    if (vt_data_create(&d, m) != VT_OK) return;
    for (int c = 0; c < m->nv; c++) {
        d->qd[c] = (pick & 2) ? 0.5 - 0.1 * c : 0.0;
        d->qdd[c] = 1.0 - 0.2 * c;
    }
    if (vt_inverse_dynamics_motion(m, d) == VT_OK) {
        check_finite(d->qfrc_drive, m->nv);
        check_finite(d->jnt_force, 3 * (m->nbody + 1));
        check_finite(d->jnt_moment, 3 * (m->nbody + 1));
        double *tau = malloc((size_t)m->nv * sizeof(double) + 1);
        if (tau) {
            memcpy(tau, d->qfrc_drive, (size_t)m->nv * sizeof(double));
            /* the dense path forms M* from absolute positions: its round-off grows with the
             * bodies' distance from the origin, so the comparison is kept to robots within 100 m */
            double far = 0.0;
            for (int i = 0; i < m->nbody; i++)
                for (int k = 0; k < 3; k++) far = fmax(far, fabs(d->x[7 * i + k]));
            if (far <= 100.0 && vt_kinematics(m, d) == VT_OK && vt_mass_matrix(m, d) == VT_OK &&
                vt_forces(m, d) == VT_OK) {
                /* round-off of both evaluations grows with the largest terms, not the sums: those
                 * of M* q̈ − Q, and those M* and Q are summed from, each body's inertia and mass
                 * times the rates' accelerations (a zero inertia about an axis is summed from terms
                 * of |J|: a link of J = diag(0, 33, 33) about x gave M*_aa = 1e-15 against τ = 0) */
                double scale = 1e-300, qdd = 0.0, qd = 0.0;
                for (int a = 0; a < m->nv; a++) {
                    qdd = fmax(qdd, fabs(d->qdd[a]));
                    qd = fmax(qd, fabs(d->qd[a]));
                    scale = fmax(scale, fabs(d->Q[a]));
                    for (int b = 0; b < m->nv; b++)
                        scale = fmax(scale, fabs(d->Mstar[a + (size_t)b * (size_t)m->nv] * d->qdd[b]));
                }
                const double g = fabs(m->gravity[0]) + fabs(m->gravity[1]) + fabs(m->gravity[2]);
                for (int i = 1; i <= m->nbody; i++) {
                    const double *J = m->body_inertia + 9 * i, mass = m->body_mass[i];
                    scale = fmax(scale, (fabs(J[0]) + fabs(J[4]) + fabs(J[8])) * (qdd + qd * qd));
                    scale = fmax(scale, mass * far * (g + far * (qdd + qd * qd)));
                }
                for (int a = 0; a < m->nv && isfinite(scale) && scale < 1e150; a++) {
                    double t = -d->Q[a];
                    for (int b = 0; b < m->nv; b++) t += d->Mstar[a + (size_t)b * (size_t)m->nv] * d->qdd[b];
                    if (!(fabs(tau[a] - t) <= 1e-8 * m->nv * scale)) abort();
                }
            }
            free(tau);
        }
    }
    vt_data_free(d);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (size < 1 || size > MAX_XML) return 0;
    const unsigned pick = data[0];
    char *xml = malloc(size);
    if (!xml) return 0;
    memcpy(xml, data + 1, size - 1);
    xml[size - 1] = '\0';
    vt_urdf_options o = vt_default_urdf_options();
    o.floating = pick & 1;
    o.mimic = (pick >> 2) & 1;
    vt_builder *b = (vt_builder *)&o; /* must be overwritten */
    char message[256] = "";
    const vt_status st = vt_urdf_builder_string(&b, xml, &o, message);
    free(xml);
    if (st != VT_OK) {
        if (b != NULL || message[0] == '\0') abort(); /* no builder left, a reason given */
        return 0;
    }
    if (!b) abort();
    vt_model *m = NULL;
    const vt_status bs = vt_builder_build(&m, b);
    vt_builder_free(b);
    if (bs == VT_OK) {
        if (!m) abort();
        run_model(m, pick);
        vt_model_free(m);
    }
    return 0;
}
