/* vtdyn — The builder (model/builder.c): the definitions as they are added, validated and
 * normalized, before vt_builder_build (model/model.c) lays them out as a model; the joint kinds'
 * sizes, a cut joint's and a drive's rows, names and the inertia check. */
#ifndef VT_MODEL_BUILDER_H
#define VT_MODEL_BUILDER_H

#include "vtdyn.h"
#include "model/names.h"

/* A name as the builder and the model keep it (VT_NAME_MAX bytes, "" when unnamed). */
typedef char vt_name[VT_NAME_MAX];

/* The definitions added so far; vt_builder_build reads them. Each kind's names are indexed
 * (model/names.h: duplicates refused and finds in O(log n)); every count stays within
 * VT_COUNT_MAX. */
struct vt_builder {
    vt_model_def def;
    vt_body_def *bodies;  /* validated and normalized definitions (cap) */
    vt_name *body_names, *joint_names; /* (cap each, grown with bodies) */
    int n, cap, capnames;
    int nq, nv;           /* the bodies' coordinates and rates so far */
    vt_names body_index, joint_index, drive_index, cut_index, frame_index, coupling_index;
    vt_drive_def *drives;
    vt_name *drive_names;
    int ndrive, capdrive, capdrivenames;
    double **samples; /* per drive: its splines' t, y and f'' (3 nsample each), the builder's; or NULL */
    int capsamples;
    vt_cut_joint_def *cuts;
    vt_name *cut_names;
    int ncut, capcut, capcutnames;
    vt_frame_def *frames;
    vt_name *frame_names;
    int nframe, capframe, capframenames;
    vt_coupling_def *couplings;
    vt_name *coupling_names;
    int ncoupling, capcoupling, capcouplingnames;
    char message[VT_MESSAGE_SIZE];
};

/* Coordinates (q) and rates (v) of a joint type (Table 1; the order of vt_joint_type). */
static inline int vt_joint_nq(int joint)
{
    static const int nq[VT_JOINT_TYPE_COUNT] = {7, 1, 2, 4, 1, 2, 7};
    return nq[joint];
}
static inline int vt_joint_nv(int joint)
{
    static const int nv[VT_JOINT_TYPE_COUNT] = {7, 1, 2, 3, 1, 2, 6};
    return nv[joint];
}

/* Index of name among the n names of VT_NAME_MAX bytes each at names, or VT_ERR_NOT_FOUND (also
 * for NULL or ""). */
int vt_find_name(const char *names, int n, const char *name);

/* Rows of a cut joint: its kind's, or 2 for a planar pin. */
int vt_cut_nrows(const vt_cut_joint_def *c);
/* An orientation drive, absolute or relative (3 rows, p_d(t) from prescribed orientation) */
static inline int vt_drive_turns(vt_drive_type type)
{
    return type == VT_DRIVE_ORIENTATION || type == VT_DRIVE_RELATIVE_ORIENTATION;
}
/* Rows of one drive */
static inline int vt_drive_nrows(const vt_drive_def *d) { return vt_drive_turns(d->type) ? 3 : 1; }
/* A drive's time functions (f; with an orientation drive's sequence also f2, f3; none for an
 * orientation callback) into fs; returns how many */
static inline int vt_drive_functions(const vt_drive_def *d, const vt_function *fs[3])
{
    if (vt_drive_turns(d->type) && d->orientation_callback) return 0;
    fs[0] = &d->f;
    if (!vt_drive_turns(d->type) || !d->sequence) return 1;
    fs[1] = &d->f2;
    fs[2] = &d->f3;
    return 3;
}

#endif
