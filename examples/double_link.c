/* The paper's double link (Fig. 4) at one pose: prints the velocity transformation S, its
 * inverse R (Table 1), R S, the mass matrix M* = S^T M S (3) and the generalized force Q (4).
 *
 * Two uniform links, 2 m and 100 kg, revolute joints about z, y up. The pose: both links in
 * line, fallen θ = 30° below the horizontal, with the falling rate of the locked pair,
 * θ̇² = 7.3575 sin θ (method.md). Usage: double_link [theta_deg]
 */
#include <math.h>
#include <stdio.h>
#include <stdlib.h>

#include "scenes.h"

static void print_matrix(const char *name, const double *a, int rows, int cols, int ld)
{
    printf("%s (%d x %d)\n", name, rows, cols);
    for (int r = 0; r < rows; r++) {
        for (int c = 0; c < cols; c++) printf(" %11.5f", a[r + (size_t)c * (size_t)ld]);
        printf("\n");
    }
}

int main(int argc, char **argv)
{
    const double deg = argc > 1 ? atof(argv[1]) : 30.0;
    const double theta = deg * 3.14159265358979323846 / 180.0;
    vt_model *m;
    vt_data *d;
    vt_status st = vt_scene_double_link(&m, 0);
    if (st) {
        fprintf(stderr, "double_link: %s\n", vt_status_string(st));
        return 1;
    }
    if ((st = vt_data_create(&d, m))) {
        fprintf(stderr, "double_link: %s\n", vt_status_string(st));
        vt_model_free(m);
        return 1;
    }
    d->q[0] = -theta; /* fallen below +x is a negative turn about z */
    d->q[1] = 0.0;
    d->qd[0] = -sqrt(7.3575 * sin(theta));
    d->qd[1] = 0.0;
    if ((st = vt_kinematics(m, d)) || (st = vt_inverse_transform(m, d)) ||
        (st = vt_mass_matrix(m, d)) || (st = vt_forces(m, d))) {
        fprintf(stderr, "double_link: %s: %s\n", vt_status_string(st), d->message);
        vt_data_free(d);
        vt_model_free(m);
        return 1;
    }
    printf("vtdyn double link, theta = %g deg, theta_dot = %g rad/s\n\n", deg, -d->qd[0]);
    print_matrix("S", d->S, m->nx, m->nv, m->nx);
    printf("\n");
    print_matrix("R", d->R, m->nv, m->nx, m->nv);
    double RS[4] = {0};
    for (int a = 0; a < 2; a++)
        for (int b = 0; b < 2; b++)
            for (int k = 0; k < m->nx; k++) RS[a + 2 * b] += d->R[a + 2 * k] * d->S[k + (size_t)m->nx * b];
    printf("\n");
    print_matrix("R S", RS, 2, 2, 2);
    printf("\n");
    print_matrix("M*", d->Mstar, m->nv, m->nv, m->nv);
    printf("\n");
    print_matrix("Q", d->Q, m->nv, 1, m->nv);
    /* with joint 2 locked the pair is one 4 m, 200 kg rod: inertia m L²/3 about the pivot,
     * gravity moment m g (L/2) cos θ */
    const double mt = 2.0 * VT_DL_MASS, L = 2.0 * VT_DL_LENGTH;
    printf("\nM*[1,1] = %.6f   (4 m rod about the pivot, m L^2/3: %.6f)\n", d->Mstar[0], mt * L * L / 3.0);
    printf("Q[1]    = %.6f  (-m g L/2 cos(theta): %.6f)\n", d->Q[0], -mt * 9.81 * 0.5 * L * cos(theta));
    vt_data_free(d);
    vt_model_free(m);
    return 0;
}
