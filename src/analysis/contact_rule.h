/* vtdyn — Contacts: the distribution rule at one instant, the ground's forces on a contact set
 * (analysis/contact_rule.c). Its entry point is public (vtdyn.h: vt_inverse_dynamics_contacts). The
 * set (analysis/contact.c) makes the struct below, its contacts and the rule's workspace in one
 * block, and its vt_contacts_unique takes the rule's Jacobian and loads along the directions the
 * rule chooses. Private to those two files. */
#ifndef VT_ANALYSIS_CONTACT_RULE_H
#define VT_ANALYSIS_CONTACT_RULE_H

#include <math.h>
#include <stddef.h>

#include "recursive/fused.h"
#include "vtdyn.h"

struct vt_contacts {
    const vt_model *model;
    int n;
    int *body;            /* n */
    int *other;           /* n: 0 the ground, else the body touched (its normal and rows in its axes) */
    double *point;        /* body axes from the centre of mass (3n) */
    double *normal;       /* global (the other body's axes where it touches one), unit (3n) */
    double *tangent;      /* t₁, t₂: the same axes, unit, normal to it and to each other (6n) */
    vt_contact_kind *kind;
    double *mu, *weight;  /* n */
    int *faces;           /* n */
    double *cone;         /* each unilateral contact's rows, a 3-vector each: n, then μ cos(π/k) n − d_j
                           * for its k faces (3 (1 + k) from cone_at[c]) */
    int *cone_at;         /* n */
    char *name;           /* VT_NAME_MAX each (n) */
    double *effort_weight; /* nv */
    int nu, *unact;       /* the unactuated rates (a free joint's) */
    int nact, *act;       /* the others */
    /* the instant's workspace, sized for every contact active */
    int *on;              /* the active contacts' indices */
    int *active;          /* a run's schedule at one time (n) */
    int *row_of;          /* each rate's row: ≥ 0 in B (actuated), −1 − its row in Aeq (not) (nv) */
    double *sw;           /* √w_a of the actuated rates (nact) */
    double *B;            /* (√W J_A)ᵀ: 3 na x nact, row 3k + e the velocity of contact on[k]'s point
                           * along e under each actuated rate (a column), weighted */
    double *G, *c, *Aeq, *beq, *Ain, *bin, *f, *tau0, *wtau, *xfrc;
    double *lambda, *res, *slack;     /* the QP's multipliers (nu + rows), residuals (3n), slacks (nu + rows) */
    double *rownorm;                  /* the equalities' and inequalities' rows' 1-norms (nu + rows) */
    double *U, *sig, *Ar, *svd_work; /* the root's equations by their SVD: U (nu x nu), σ, the
                                      * independent rows Uᵣᵀ A_eq (nu x 3n), LAPACK's workspace */
    int svd_lwork;
    double *L;            /* the equality minimum's G = L Lᵀ (3n x 3n); vt_contacts_unique's U */
    double *saved;        /* vt_contacts_unique: the data's outputs while it probes (saved_len) */
    size_t saved_len;
    int *eu, *ju;         /* vt_contacts_unique's flags as they are found (nv, 6 (nbody + 1)) */
    int *row_contact;     /* the contact of each inequality row */
    int *row_face;        /* −1 for its normal row, else its face */
    void *qp;
    size_t qp_bytes;
};

/* vt_inverse_dynamics_contacts() with wrenches at frames in the instant (vt_motion_loaded), before
 * the ground's forces are shared, which then balance them too; loads NULL is
 * vt_inverse_dynamics_contacts() itself (the batch's rows with loads) */
vt_status vt_contacts_inverse(const vt_model *model, vt_data *data, vt_contacts *contacts, const int *active,
                              double *force, const vt_frame_loads *loads);

/* The active contacts' J_c (contacts->on[0 .. na − 1]) at data's instant, split by rows: the actuated
 * rates' weighted, √W J_A into contacts->B, the unactuated ones' into contacts->Aeq */
void vt_contacts_jacobian(const vt_model *model, const vt_data *data, vt_contacts *contacts, int na);

/* contact h's body's load of the force f at its point, and −f on the body it touches, added into
 * xfrc (6 (nbody + 1), as vt_data.xfrc) */
void vt_contacts_add_load(const vt_data *data, const vt_contacts *contacts, int h, const double f[3], double *xfrc);

/* the largest |a_k| (a NaN passed over: the rule's checks fail on it themselves) */
static inline double vt_contacts_max_abs(const double *a, int n, int inc)
{
    double m = 0.0;
    for (int k = 0; k < n; k++) {
        const double v = fabs(a[(size_t)k * (size_t)inc]);
        m = v > m ? v : m;
    }
    return m;
}

#endif
