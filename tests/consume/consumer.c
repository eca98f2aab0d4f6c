/* A program that uses vtdyn as another project would: <vtdyn.h> and the public API only. It is
 * compiled as C99 with -pedantic-errors against the build (tests/consume/meson.build), and by
 * tests/consume/run.sh against an installed vtdyn (pkg-config, shared and static) and as a
 * meson subproject. The paper's double link, joint 2 locked, at one instant of its fall from the
 * horizontal (θ = 0.5 rad, θ̇² = 7.3575 sin θ): θ̈ = 3.67875 cos θ, the locking torque
 * 245.25 cos θ and the joint-1 reaction of (29), by the dense and by the recursive evaluation.
 * Usage: consumer [expected version]. Exit 0 when every number agrees to 1e-10 relative and the
 * versions match, 1 otherwise (the reason on stderr). */
#include <math.h>
#include <stdio.h>
#include <string.h>

#include <vtdyn.h>

static int failures = 0;

static void check(const char *what, double got, double want, double scale)
{
    if (!(fabs(got - want) <= 1e-10 * scale)) {
        fprintf(stderr, "consumer: %s = %.17g, expected %.17g\n", what, got, want);
        failures++;
    }
}

static int instant(const vt_model *m, vt_data *d, int recursive)
{
    const double th = 0.5, s = sin(th), c = cos(th);
    d->q[0] = -th; /* θ = −q1: link 1 falls clockwise about z */
    d->q[1] = 0.0;
    d->qd[0] = -sqrt(7.3575 * s);
    d->qd[1] = 0.0;
    const vt_status st = recursive ? vt_inverse_dynamics_recursive(m, d) : vt_inverse_dynamics(m, d);
    if (st != VT_OK) {
        fprintf(stderr, "consumer: instant analysis failed: %s (%s)\n", vt_status_string(st), d->message);
        return 1;
    }
    check("theta_ddot", -d->qdd[0], 3.67875 * c, 3.67875);
    check("locking torque", fabs(d->drive_effort[0]), 245.25 * c, 245.25);
    check("joint-1 reaction x", d->jnt_force[3 + 0], -2207.25 * sin(2.0 * th), 4905.0);
    check("joint-1 reaction y", d->jnt_force[3 + 1], 4905.0 * s * s + 490.5 * c * c, 4905.0);
    return 0;
}

int main(int argc, char **argv)
{
    if (strcmp(vt_version(), VT_VERSION_STRING) != 0 || (argc > 1 && strcmp(vt_version(), argv[1]) != 0)) {
        fprintf(stderr, "consumer: library version %s, headers %s, expected %s\n", vt_version(),
                VT_VERSION_STRING, argc > 1 ? argv[1] : "(any)");
        return 1;
    }
    vt_builder *b = NULL;
    if (vt_builder_create(&b, NULL) != VT_OK) return 1;
    vt_body_def link = vt_default_body_def(); /* revolute about z, to the ground at the origin */
    link.mass = 100.0;
    link.inertia[4] = link.inertia[8] = 100.0 * 4.0 / 12.0; /* 2 m rod along body x */
    link.joint_child[0] = -1.0;
    const int l1 = vt_builder_add_body(b, &link);
    link.parent = l1;
    link.joint_parent[0] = 1.0;
    const int l2 = vt_builder_add_body(b, &link);
    vt_drive_def lock = vt_default_drive_def(); /* joint 2 held at 0 */
    lock.body = l2;
    const int k = vt_builder_add_drive(b, &lock);
    vt_model *m = NULL;
    if (l1 != 1 || l2 != 2 || k != 0 || vt_builder_build(&m, b) != VT_OK) {
        fprintf(stderr, "consumer: building the model failed: %s\n", vt_builder_message(b));
        vt_builder_free(b);
        return 1;
    }
    vt_builder_free(b);
    vt_data *d = NULL;
    if (vt_data_create(&d, m) != VT_OK) {
        vt_model_free(m);
        return 1;
    }
    int err = instant(m, d, 0);
    const double torque = d->drive_effort[0];
    err |= instant(m, d, 1);
    printf("vtdyn %s (SUNDIALS %s): double link at theta = 0.5 rad, locking torque %.12g N m, "
           "joint-1 reaction (%.12g, %.12g) N\n",
           vt_version(), VT_HAVE_SUNDIALS ? "yes" : "no", torque, d->jnt_force[3], d->jnt_force[4]);
    vt_data_free(d);
    vt_model_free(m);
    return err || failures ? 1 : 0;
}
