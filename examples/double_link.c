/* The paper's double link (Fig. 4): joint 2 locked by a drive (q2 = const.), the pair falls
 * from the horizontal as one 4 m rod. At one pose it prints the velocity transformation S,
 * its inverse R (Table 1), R S, the mass matrix M* = S^T M S (3) and Q (4); then, at a few
 * angles, the instant analysis — θ̈, the locking torque and the joint-1 reaction next to the
 * paper's exact solution (29).
 *
 * Two uniform links, 2 m and 100 kg, revolute joints about z, y up, x along the links at
 * θ = 0; θ is the angle fallen below x, with the exact rate θ̇² = 7.3575 sin θ (method.md).
 * Usage: double_link [theta_deg]
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
    vt_status st = vt_scene_double_link(&m, 1);
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

    printf("\nInstant analysis along the fall (exact: eq. (29), θ̈ = 3.67875 cos θ, |τ2| = 245.25 cos θ)\n");
    printf("%8s %12s %12s %12s %12s %14s %14s %14s %14s\n", "theta_deg", "thdd", "thdd_exact", "tau2_Nm",
           "tau2_exact", "f1x_N", "f1x_exact_N", "f1y_N", "f1y_exact_N");
    double worst = 0.0;
    for (int k = 0; k <= 6; k++) {
        const double th = k * 15.0 * 3.14159265358979323846 / 180.0, sn = sin(th), cs = cos(th);
        d->q[0] = -th;
        d->qd[0] = -sqrt(7.3575 * sn);
        if ((st = vt_inverse_dynamics(m, d))) {
            fprintf(stderr, "double_link: %s: %s\n", vt_status_string(st), d->message);
            break;
        }
        const double fx = -2207.25 * sin(2 * th), fy = 4905.0 * sn * sn + 490.5 * cs * cs;
        printf("%8.1f %12.8f %12.8f %12.6f %12.6f %14.6f %14.6f %14.6f %14.6f\n", k * 15.0, -d->qdd[0], 3.67875 * cs,
               d->drive_effort[0], -245.25 * cs, d->jnt_force[3], fx, d->jnt_force[4], fy);
        worst = fmax(worst, fmax(fabs(d->jnt_force[3] - fx), fabs(d->jnt_force[4] - fy)));
    }
    printf("largest joint-1 reaction error against (29): %.3g N (weight 1962 N)\n", worst);
    vt_data_free(d);
    vt_model_free(m);
    return st ? 1 : 0;
}
