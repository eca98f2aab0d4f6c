/* libFuzzer harness of the contacts: bytes become a state of the quadruped of examples/scenes.c
 * (joint angles, the free root's place and orientation, every rate and acceleration, with
 * magnitudes from 1e-3 to 1e6), up to six contact definitions (a foot's frame or any body and
 * point, unilateral or bilateral, μ, faces, the ground's normal, the weight, the ground or
 * another body touched; bad values among them), the effort weights and each contact's activity.
 * Whatever the bytes:
 *
 * - vt_contacts_create either refuses, with a message and no contacts, or accepts definitions
 *   whose values are in range;
 * - vt_inverse_dynamics_contacts answers with a status: on a failure the message is not empty
 *   and the caller's force array and xfrc are untouched; on VT_OK every force is finite, an
 *   inactive contact's is zero, a unilateral one pushes and stays in its pyramid, and the free
 *   root's efforts vanish — each to 1e-7 of the instant's scale (its efforts and forces, with
 *   the lever arms of the feet), a test of gross errors (a wrong sign, a wrong Jacobian), not of
 *   round-off;
 * - the same row in a batch with one or two wrenches at frames (loaded_row): refused with a
 *   message and nothing written, or finite, the free root's efforts vanishing alike.
 *
 * A broken promise prints which and aborts (libFuzzer keeps the input). Built and run by
 * fuzz/run.sh beside the other harnesses. */
#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "scenes.h"
#include "vtdyn.h"

#define PI 3.14159265358979323846

typedef struct {
    const uint8_t *p;
    size_t n, k;
} bytes;

static unsigned byte(bytes *b)
{
    return b->k < b->n ? b->p[b->k++] : 0u;
}

/* a number in [−1, 1] from two bytes */
static double unit(bytes *b)
{
    const unsigned v = byte(b) << 8 | byte(b);
    return (double)v / 32767.5 - 1.0;
}

/* a magnitude 10^(−3 … 6) with a sign, or a few special values */
static double scaled(bytes *b)
{
    const unsigned s = byte(b);
    if (s == 255) return NAN;
    if (s == 254) return INFINITY;
    if (s == 253) return 0.0;
    return unit(b) * pow(10.0, -3.0 + 9.0 * (s % 64) / 63.0);
}

static void fail(const char *fmt, const char *what, double a, double b)
{
    fprintf(stderr, "fuzz_contact: ");
    fprintf(stderr, fmt, what, a, b);
    fputc('\n', stderr);
    abort();
}

static vt_model *model;

/* The same state and contacts as a batch's row with one or two wrenches at the robot's frames
 * (the last bytes; none without them, so older inputs mean what they meant): a refusal has its
 * message and writes nothing; VT_OK gives finite efforts and forces, the free root's efforts
 * vanishing to 1e-7 of the row's scale (the loads', with the lever arms of the feet, counted). */
static void loaded_row(const vt_model *m, vt_data *d, bytes *b, const vt_contact_def *def, int n, const double *weights,
                       const int *active)
{
    const int nl = (int)(byte(b) % 3);
    if (nl == 0 || m->nframe == 0) return;
    int frame[2];
    double w[12], scale = 1.0;
    for (int k = 0; k < nl; k++) {
        frame[k] = (int)(byte(b) % (unsigned)m->nframe);
        for (int e = 0; e < 6; e++) w[6 * k + e] = scaled(b);
        for (int e = 0; e < 6; e++) scale = fmax(scale, 4.0 * fabs(w[6 * k + e])); /* |f| times a leg's reach */
    }
    vt_batch_def bd = vt_default_batch_def();
    bd.threads = 1;
    bd.contacts = def;
    bd.ncontact = n;
    bd.effort_weight = weights;
    vt_batch *bt = NULL;
    if (vt_batch_create(&bt, m, &bd)) fail("%s: contacts accepted alone, refused by a batch (%g %g)", "vt_batch_create", 0, 0);
    double force[18], effort[18];
    for (int k = 0; k < 18; k++) force[k] = effort[k] = 42.0;
    int status = 42;
    vt_batch_io io = {0};
    io.nrow = 1;
    io.q = d->q, io.qd = d->qd, io.qdd = d->qdd;
    io.contact_active = active, io.contact_force = force, io.effort = effort, io.status = &status;
    io.nload = nl, io.load_frame = frame, io.load = w;
    const vt_status st = vt_batch_inverse_dynamics_motion(bt, &io);
    if (st) {
        if (!vt_batch_message(bt)[0]) fail("%s failed (%g) with an empty message%g", "the loaded batch", st, 0);
        for (int k = 0; k < 18; k++)
            if (force[k] != 42.0 || effort[k] != 42.0) fail("%s failed and wrote its outputs (%g %g)", "the loaded batch", k, 0);
    } else {
        for (int a = 0; a < m->nv; a++) {
            if (!isfinite(effort[a])) fail("%s: effort[%g] = %g", "the loaded batch", a, effort[a]);
            scale = fmax(scale, fabs(effort[a]));
        }
        for (int k = 0; k < 3 * n; k++) {
            if (!isfinite(force[k])) fail("%s: force[%g] = %g", "the loaded batch", k, force[k]);
            scale = fmax(scale, fabs(force[k]));
        }
        for (int a = 0; a < 6; a++)
            if (!(fabs(effort[a]) <= 1e-7 * scale)) fail("%s: the free root's effort %g of scale %g", "the loaded batch", effort[a], scale);
    }
    vt_batch_free(bt);
}

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
    if (!model && vt_scene_quadruped(&model)) abort();
    const vt_model *m = model;
    bytes b = {data, size, 0};
    vt_data *d = NULL;
    if (vt_data_create(&d, m)) abort();
    /* the state: near the stand, then each rate and acceleration at a scale of the bytes' */
    vt_scene_quadruped_stand(m, d, 0.6 * (1.0 + 0.5 * unit(&b)));
    for (int i = 2; i <= m->nbody; i++) d->q[m->body_qadr[i]] += (byte(&b) & 1) ? PI * unit(&b) : 0.0;
    double quat[4] = {1.0 + unit(&b), 0.3 * unit(&b), 0.3 * unit(&b), 0.3 * unit(&b)};
    const double qn = sqrt(quat[0] * quat[0] + quat[1] * quat[1] + quat[2] * quat[2] + quat[3] * quat[3]);
    for (int e = 0; e < 4; e++) d->q[3 + e] = qn > 0.1 ? quat[e] / qn : (e == 0);
    const double rate = pow(10.0, -2.0 + 4.0 * byte(&b) / 255.0);
    for (int a = 0; a < m->nv; a++) {
        d->qd[a] = rate * unit(&b);
        d->qdd[a] = (byte(&b) == 7) ? scaled(&b) : rate * unit(&b);
    }
    /* the contacts: 1 to 6 */
    static const char *const feet[4] = {"FL_foot", "FR_foot", "HL_foot", "HR_foot"};
    static const char *const names[6] = {"c0", "c1", "c2", "c3", "c4", "c5"};
    const int n = 1 + (int)(byte(&b) % 6);
    vt_contact_def def[6];
    for (int k = 0; k < n; k++) {
        def[k] = vt_default_contact_def();
        const unsigned how = byte(&b);
        def[k].name = (how & 64) ? names[(k + ((how & 129) == 129)) % 6] : NULL; /* a name twice, now and then */
        if (how & 1) {
            def[k].frame = feet[k % 4];
        } else {
            const unsigned body = byte(&b); /* now and then the ground or past the last body: refused */
            def[k].body = body == 255 ? 0 : body == 254 ? m->nbody + 1 : 1 + (int)(body % (unsigned)m->nbody);
            for (int e = 0; e < 3; e++) def[k].point[e] = 0.3 * unit(&b);
        }
        if (how & 2) def[k].kind = VT_CONTACT_BILATERAL;
        const int odd = (how & 0xC0) == 0xC0 && (byte(&b) & 3) == 0; /* a value out of range, seldom */
        if (how & 4) def[k].mu = odd ? scaled(&b) : 1.5 * (1.0 + unit(&b));
        if (how & 8) {
            const unsigned f = byte(&b);
            def[k].faces = f >= 250 ? (int)(f % 70) : 3 + (int)(f % 62);
        }
        if (how & 16)
            for (int e = 0; e < 3; e++) def[k].normal[e] = unit(&b) + (e == 2);
        if (how & 32) def[k].weight = odd ? scaled(&b) : pow(10.0, -6.0 + 8.0 * byte(&b) / 255.0);
    }
    double ew[18], *weights = NULL;
    if (byte(&b) & 1) {
        for (int a = 0; a < m->nv; a++) ew[a] = pow(10.0, -3.0 + 6.0 * byte(&b) / 255.0);
        if (byte(&b) == 3) ew[byte(&b) % (unsigned)m->nv] = -1.0;
        weights = ew;
    }
    int active[6];
    const unsigned act = byte(&b);
    for (int k = 0; k < n; k++) active[k] = act == 0 || (act >> k & 1);
    /* last, so that inputs without these bytes mean what they meant: what each point touches,
     * the ground (0, most often) or another body of the robot (now and then itself or past the
     * last body: refused) */
    for (int k = 0; k < n; k++) {
        const unsigned o = byte(&b);
        def[k].other = o < 192 ? 0 : o == 255 ? def[k].body : o == 254 ? m->nbody + 1 : 1 + (int)(o % (unsigned)m->nbody);
    }
    char msg[VT_MESSAGE_SIZE];
    vt_contacts *c = (vt_contacts *)def;
    const vt_status cs = vt_contacts_create(&c, m, def, n, weights, msg);
    if (cs) {
        if (c) fail("%s: a refused definition left contacts (%g %g)", "vt_contacts_create", 0, 0);
        if (!msg[0]) fail("%s: refused (%g) with an empty message%g", "vt_contacts_create", cs, 0);
        vt_data_free(d);
        return 0;
    }
    for (int k = 0; k < n; k++) {
        if (def[k].kind == VT_CONTACT_UNILATERAL && !(def[k].mu >= 0.0 && isfinite(def[k].mu)))
            fail("%s: mu %g accepted (%g)", "vt_contacts_create", def[k].mu, 0);
        if (!(def[k].weight > 0.0)) fail("%s: weight %g accepted (%g)", "vt_contacts_create", def[k].weight, 0);
    }
    double force[18], xfrc0[6 * 14];
    for (int k = 0; k < 18; k++) force[k] = 42.0;
    const size_t nx = 6 * (size_t)(m->nbody + 1);
    memcpy(xfrc0, d->xfrc, nx * sizeof(double));
    const vt_status st = vt_inverse_dynamics_contacts(m, d, c, active, force);
    if (memcmp(xfrc0, d->xfrc, nx * sizeof(double)) != 0) fail("%s changed xfrc (%g %g)", "the call", 0, 0);
    if (st) {
        if (!d->message[0]) fail("%s failed (%g) with an empty message%g", "vt_inverse_dynamics_contacts", st, 0);
        for (int k = 0; k < 3 * n; k++)
            if (force[k] != 42.0) fail("%s failed and wrote force (%g %g)", "vt_inverse_dynamics_contacts", k, force[k]);
    } else {
        double scale = 1.0;
        for (int a = 0; a < m->nv; a++) scale = fmax(scale, fabs(d->qfrc_drive[a]));
        for (int k = 0; k < 3 * n; k++) {
            if (!isfinite(force[k])) fail("%s: force[%g] = %g", "vt_inverse_dynamics_contacts", k, force[k]);
            scale = fmax(scale, fabs(force[k]));
        }
        const double tol = 1e-7 * scale;
        for (int a = 0; a < 6; a++)
            if (!(fabs(d->qfrc_drive[a]) <= tol)) fail("%s: the free root's effort %g of scale %g", "contacts", d->qfrc_drive[a], scale);
        for (int k = 0; k < n; k++) {
            const double *f = force + 3 * k;
            if (!active[k]) {
                if (f[0] != 0.0 || f[1] != 0.0 || f[2] != 0.0) fail("%s: an inactive contact's force %g (%g)", "contacts", f[2], k);
                continue;
            }
            if (def[k].kind != VT_CONTACT_UNILATERAL) continue;
            double nl[3] = {def[k].normal[0], def[k].normal[1], def[k].normal[2]}, nrm[3];
            if (!(nl[0] * nl[0] + nl[1] * nl[1] + nl[2] * nl[2] > 0.0)) nl[2] = 1.0; /* opposite to gravity */
            if (def[k].other > 0) { /* in the touched body's axes: turned with it */
                const double *A = d->A + 9 * def[k].other;
                for (int e = 0; e < 3; e++) nrm[e] = A[e] * nl[0] + A[e + 3] * nl[1] + A[e + 6] * nl[2];
            } else {
                for (int e = 0; e < 3; e++) nrm[e] = nl[e];
            }
            const double nn = sqrt(nrm[0] * nrm[0] + nrm[1] * nrm[1] + nrm[2] * nrm[2]);
            const double fn = (f[0] * nrm[0] + f[1] * nrm[1] + f[2] * nrm[2]) / nn;
            const double ft2 = f[0] * f[0] + f[1] * f[1] + f[2] * f[2] - fn * fn;
            if (fn < -tol) fail("%s: a unilateral contact pulls: %g (scale %g)", "contacts", fn, scale);
            /* the pyramid is inscribed in the cone: the tangential force within μ f_n */
            if (sqrt(fmax(ft2, 0.0)) > def[k].mu * fn + tol)
                fail("%s: a contact slips: |f_t| %g beyond mu f_n %g", "contacts", sqrt(fmax(ft2, 0.0)), def[k].mu * fn);
        }
    }
    loaded_row(m, d, &b, def, n, weights, active);
    vt_contacts_free(c);
    vt_data_free(d);
    return 0;
}
