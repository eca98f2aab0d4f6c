/* The mass matrices: the paper's (3) and docs/method.md "Equations of motion".
 *
 *   M^i = diag(m^i I3, 4 G^{iT} J'^i G^i)       (J' about the centre of mass, body axes)
 *   M*  = S^T M S = Σ_i S_i^T M^i S_i           (3)
 * S_i, body i's 7 rows of S, is non-zero only in the columns of the joints on its path, so
 * each term is formed on those k columns alone (a 7 x k block, BLAS dgemm) and added into
 * M*[path, path]. The cost is Σ_i 7 k_i², never a product of dense 7n-sized matrices.
 */
#include <math.h>
#include <stddef.h>
#include <string.h>

#include "dense/mass.h"
#include "kinematics/joint_effects.h"
#include "base/lapack.h"
#include "base/arena.h"
#include "base/scan.h"
#include "base/status.h"
#include "base/vec3.h"
#include "model/model.h"
#include "kinematics/kinematics.h"

/* Mp = 4 G^T J' G (4x4, column-major) */
void vt_rot_mass(double Mp[16], const double J[9], const double p[4])
{
    double G[12], JG[12];
    vt_euler_G(G, p);
    for (int c = 0; c < 4; c++) vt_mulmat3(JG + 3 * c, J, G + 3 * c);
    for (int c = 0; c < 4; c++)
        for (int r = 0; r < 4; r++) Mp[r + 4 * c] = 4.0 * vt_dot3(G + 3 * r, JG + 3 * c);
}

vt_status vt_mass_matrix(const vt_model *m, vt_data *d)
{
    vt_status st = vt_check_dense(m, d, "vt_mass_matrix");
    if (st) return st;
    const int nv = m->nv;
    const size_t k7 = 7 * (size_t)m->maxpath, mark = vt_scratch_mark(d);
    double *Si = VT_SCRATCH(d, double, k7, "S block"), *W = VT_SCRATCH(d, double, k7, "M S block");
    double *C = VT_SCRATCH(d, double, (size_t)m->maxpath * (size_t)m->maxpath, "M* block");
    int *path = VT_SCRATCH(d, int, m->maxpath, "a body's path");
    if (!path) return vt_scratch_fail(d, mark);
    memset(d->Mstar, 0, (size_t)nv * (size_t)nv * sizeof(double));
    for (int i = 1; i <= m->nbody; i++) {
        const int k = vt_body_path(m, i, path);
        const double mass = m->body_mass[i];
        double *Mp = d->Mp + 16 * i;
        vt_rot_mass(Mp, m->body_inertia + 9 * i, d->x + vt_xoff(i) + 3);

        vt_gather_S(Si, m, d, i, path);
        for (int c = 0; c < k; c++)
            for (int r = 0; r < 3; r++) W[r + 7 * c] = mass * Si[r + 7 * c];
        vt_dgemm('N', 'N', 4, k, 4, 1.0, Mp, 4, Si + 3, 7, 0.0, W + 3, 7);
        vt_dgemm('T', 'N', k, k, 7, 1.0, Si, 7, W, 7, 0.0, C, k);
        for (int b = 0; b < k; b++)
            for (int a = 0; a < k; a++) d->Mstar[path[a] + (size_t)path[b] * (size_t)nv] += C[a + k * b];
    }
    vt_scratch_release(d, mark);
    if (m->has_effects) /* the joints' armature: inertia on their own rates (kinematics/joint_effects.c) */
        for (int c = 0; c < nv; c++) d->Mstar[c + (size_t)c * (size_t)nv] += m->dof_effects[4 * c];
    /* a state or inertia near overflow can make a product Inf: refused, naming the entry */
    const size_t nm = (size_t)nv * (size_t)nv; /* past an int from nv = 46,341 */
    if (!vt_all_finite(d->Mstar, nm))
        for (size_t c = 0; c < nm; c++)
            if (!isfinite(d->Mstar[c]))
                return vt_fail(d->message, VT_ERR_NONFINITE, "vt_mass_matrix: M*[%zu, %zu] = %g (overflow)",
                               c % (size_t)nv, c / (size_t)nv, d->Mstar[c]);
    if (!vt_all_finite(d->Mp + 16, 16 * m->nbody))
        return vt_fail(d->message, VT_ERR_NONFINITE, "vt_mass_matrix: a body's rotational mass block overflows");
    return VT_OK;
}

/* a body's S block, M S block, M* block and path */
size_t vt_mass_scratch(const vt_model *m)
{
    const size_t k = (size_t)m->maxpath;
    return 2 * VT_SCRATCH_BYTES(7 * k, sizeof(double)) + VT_SCRATCH_BYTES(k * k, sizeof(double)) +
           VT_SCRATCH_BYTES(k, sizeof(int));
}
