/* The data of a model: one block laid out once, never resized (sizes are fixed when the
 * model is built), allocated by vt_data_create() or the caller's own (vt_data_init()): the
 * inputs, every stage's results, and the scratch arena (base/arena.h) whose size is the sum of
 * the source files' bounds on what each takes at once.
 */
#include <stddef.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "analysis/data.h"
#include "base/arena.h"
#include "base/block.h"
#include "base/status.h"
#include "kinematics/inverse_transform.h"
#include "kinematics/kinematics.h"
#include "numeric/kkt.h"
#include "numeric/maximal.h"
#include "numeric/rank.h"
#include "numeric/roundoff.h"
#include "dense/constraints.h"
#include "dense/forces.h"
#include "dense/mass.h"
#include "dense/reactions.h"
#include "dense/routes.h"
#include "dense/solve.h"
#include "recursive/recursive.h"
#include "analysis/kinematic_solve.h"

/* The scratch every file may hold at once (base/arena.h), for data that holds the dense arrays
 * (full) or not. Without them only the recursive files run, with the rows' and the square LU's
 * parts of numeric/: no M*, S or R, no dense route, no maximal route. */
static size_t arena_size(const vt_model *m, int full)
{
    /* a joint-driven model's instants are the fused passes, its kinematic solve the drives' values:
     * no rows' work at all */
    if (!full && m->joint_driven)
        return vt_kinematics_scratch(m) + vt_reactions_scratch(m) + vt_recursive_scratch(m) +
               vt_kinematic_solve_scratch(m);
    const size_t rows = vt_kinematics_scratch(m) + vt_constraints_scratch(m) + vt_roundoff_scratch(m) +
                        vt_rank_scratch(m) + vt_kkt_scratch(m) + vt_solve_scratch(m) + vt_reactions_scratch(m) +
                        vt_recursive_scratch(m) + vt_kinematic_solve_scratch(m);
    if (!full) return rows;
    return rows + vt_mass_scratch(m) + vt_forces_scratch(m) + vt_routes_scratch(m) + vt_maximal_scratch(m) +
           vt_inverse_transform_scratch(m);
}

/* Whether the sizes of a data laid out full (or not) can be counted in size_t: every array and
 * bound is a sum of fewer than 64 terms of at most 64 (nx + nv + nc)² bytes (full; the dense S,
 * R, M* and routes) or 64 (nx + nv + nc)(nc + 64) bytes (the rows and the O(n) arrays). */
static int countable(const vt_model *m, int full)
{
    const double n = (double)m->nx + (double)m->nv + (double)m->nc;
    const double bytes = 64.0 * 64.0 * n * (full ? n : (double)m->nc + 64.0);
    return bytes < (double)SIZE_MAX / 4.0;
}

/* Lays out the data (base NULL: counts its bytes), full with the dense stages' arrays */
static size_t layout(const vt_model *m, vt_data *d, char *base, int full)
{
    const size_t n = (size_t)m->nbody, nb = n + 1, nx = 7 * n, nv = (size_t)m->nv;
    /* the dense arrays' sizes, 0 without them (their pointers NULL) */
    const size_t nS = full ? nx * nv : 0, nM = full ? nv * nv : 0;
    /* Φ_q: a joint-driven model's rows are unit rows, which the recursive files never form */
    const int phiq = full || !m->joint_driven;
    /* every array on a cache line (VT_DATA_ALIGN: the vectorized kernels' 8-double columns); the
     * arrays of 3-vectors that the body kernels read and write four lanes at a time (base/v4.h)
     * one double longer, for the last body's fourth lane */
    vt_block blk = {.base = base, .used = sizeof(vt_data), .align = VT_DATA_ALIGN};
    d->q = vt_block_take(&blk, (size_t)m->nq, sizeof(double));
    d->qd = vt_block_take(&blk, nv, sizeof(double));
    d->xfrc = vt_block_take(&blk, 6 * nb + 1, sizeof(double));
    d->qfrc = vt_block_take(&blk, nv, sizeof(double));
    /* the arena, beside the inputs: its header, then the sum of the files' bounds (base/arena.h) */
    d->arena = vt_block_take(&blk, 1, sizeof(vt_arena));
    const size_t scratch = arena_size(m, full);
    char *mem = vt_block_take(&blk, scratch, 1);
    if (base) {
        d->arena->base = mem;
        d->arena->size = scratch;
        d->arena->top = 0;
        d->arena->peak = 0;
        d->arena->failed = 0;
    }
    d->x = vt_block_take(&blk, nx, sizeof(double));
    d->xd = vt_block_take(&blk, nx, sizeof(double));
    d->A = vt_block_take(&blk, 9 * nb + 1, sizeof(double));
    d->omega = vt_block_take(&blk, 3 * nb + 1, sizeof(double));
    d->jaxis = vt_block_take(&blk, 9 * nb, sizeof(double));
    d->jsij = vt_block_take(&blk, 3 * nb + 1, sizeof(double));
    d->jd = vt_block_take(&blk, 3 * nb + 1, sizeof(double));
    d->jpoint = vt_block_take(&blk, 3 * nb + 1, sizeof(double));
    d->twist = vt_block_take(&blk, 6 * nv + 1, sizeof(double));
    d->xrel = vt_block_take(&blk, 6 * nb + 1, sizeof(double));
    d->S = full ? vt_block_take(&blk, nS, sizeof(double)) : NULL;
    d->Sdqd = vt_block_take(&blk, nx, sizeof(double));
    d->R = full ? vt_block_take(&blk, nS, sizeof(double)) : NULL;
    d->Mp = vt_block_take(&blk, 16 * nb, sizeof(double));
    d->Mstar = full ? vt_block_take(&blk, nM, sizeof(double)) : NULL;
    d->F = vt_block_take(&blk, nx, sizeof(double));
    d->h = vt_block_take(&blk, nx, sizeof(double));
    d->Q = vt_block_take(&blk, nv, sizeof(double));
    const size_t nc = (size_t)m->nc, nd = (size_t)m->ndrive, nk = (size_t)m->ncut;
    d->Phi = vt_block_take(&blk, nc, sizeof(double));
    d->Phix = vt_block_take(&blk, 14 * nc, sizeof(double));
    d->Phiq = phiq ? vt_block_take(&blk, nc * nv, sizeof(double)) : NULL;
    d->Phit = vt_block_take(&blk, nc, sizeof(double));
    d->gamma = vt_block_take(&blk, nc, sizeof(double));
    d->qdd = vt_block_take(&blk, nv, sizeof(double));
    d->lambda = vt_block_take(&blk, nc, sizeof(double));
    d->xdd = vt_block_take(&blk, nx, sizeof(double));
    d->alpha = vt_block_take(&blk, 3 * nb + 1, sizeof(double));
    d->qfrc_drive = vt_block_take(&blk, nv, sizeof(double));
    d->effort_armature = vt_block_take(&blk, nv, sizeof(double));
    d->effort_damping = vt_block_take(&blk, nv, sizeof(double));
    d->effort_friction = vt_block_take(&blk, nv, sizeof(double));
    d->drive_effort = vt_block_take(&blk, nd, sizeof(double));
    d->drive_force = vt_block_take(&blk, 3 * nd, sizeof(double));
    d->drive_moment = vt_block_take(&blk, 3 * nd, sizeof(double));
    d->jnt_force = vt_block_take(&blk, 3 * nb, sizeof(double));
    d->jnt_moment = vt_block_take(&blk, 3 * nb, sizeof(double));
    d->jnt_force_body = vt_block_take(&blk, 3 * nb, sizeof(double));
    d->jnt_moment_body = vt_block_take(&blk, 3 * nb, sizeof(double));
    d->jnt_force_total = vt_block_take(&blk, 3 * nb, sizeof(double));
    d->jnt_moment_total = vt_block_take(&blk, 3 * nb, sizeof(double));
    d->jnt_force_total_body = vt_block_take(&blk, 3 * nb, sizeof(double));
    d->jnt_moment_total_body = vt_block_take(&blk, 3 * nb, sizeof(double));
    d->cut_force = vt_block_take(&blk, 3 * nk, sizeof(double));
    d->cut_moment = vt_block_take(&blk, 3 * nk, sizeof(double));
    d->cut_force_body = vt_block_take(&blk, 3 * nk, sizeof(double));
    d->cut_moment_body = vt_block_take(&blk, 3 * nk, sizeof(double));
    d->coupling_effort = vt_block_take(&blk, (size_t)m->ncoupling, sizeof(double));
    d->lambda_unique = vt_block_take(&blk, nc ? nc : 1, sizeof(int));
    d->lambda_null = full ? vt_block_take(&blk, nc ? nc * nc : 1, sizeof(double)) : NULL; /* redundant rows: dense */
    d->jnt_unique = vt_block_take(&blk, 6 * nb, sizeof(int));
    d->cut_unique = vt_block_take(&blk, 6 * (nk ? nk : 1), sizeof(int));
    d->jnt_force_joint = vt_block_take(&blk, 3 * nb, sizeof(double));
    d->jnt_moment_joint = vt_block_take(&blk, 3 * nb, sizeof(double));
    d->jnt_bearing = vt_block_take(&blk, 4 * nb, sizeof(double));
    d->limit_excess = vt_block_take(&blk, 3 * (nv ? nv : 1), sizeof(double));
    return blk.used;
}

/* Bytes from the buffer's start to its first VT_DATA_ALIGN boundary: the struct and every
 * array (vt_block_take) start on a cache line. */
static size_t align_pad(const void *buffer)
{
    const uintptr_t a = (uintptr_t)buffer % VT_DATA_ALIGN;
    return a ? (size_t)(VT_DATA_ALIGN - a) : 0;
}

/* the bytes of a data laid out full or not, with its alignment's slack; 0 where they cannot be
 * counted in size_t */
static size_t data_bytes(const vt_model *m, int full)
{
    if (!countable(m, full)) return 0;
    vt_data probe;
    return layout(m, &probe, NULL, full) + (VT_DATA_ALIGN - 1); /* any start can be aligned */
}

size_t vt_data_size(const vt_model *m)
{
    return m ? data_bytes(m, m->layout == VT_LAYOUT_FULL) : 0;
}

/* The one path that lays out a data struct; poison: the arena's free part poisoned in
 * AddressSanitizer builds (our own block, not a caller's buffer) */
static vt_status data_init(vt_data **data, const vt_model *m, void *buffer, size_t size, int poison, int full)
{
    if (!data) return VT_ERR_NULL;
    *data = NULL;
    if (!m || !buffer) return VT_ERR_NULL;
    if (!countable(m, full)) return VT_ERR_TOO_MANY_BODIES;
    vt_data probe;
    const size_t bytes = layout(m, &probe, NULL, full), pad = align_pad(buffer);
    if (size < pad || size - pad < bytes) return VT_ERR_BAD_SIZE; /* the buffer is left untouched */
    char *base = (char *)buffer + pad;
    memset(base, 0, bytes); /* zero: the structural zeros of S and R stay zero */
    vt_data *d = (vt_data *)base;
    layout(m, d, base, full);
    d->arena->poison = poison;
    if (poison) VT_POISON(d->arena->base, d->arena->size); /* nothing taken yet */
    d->model = m;
    d->block = NULL; /* the caller's memory: vt_data_free() leaves it alone */
    /* the ground: identity rotation, at rest */
    d->A[0] = d->A[4] = d->A[8] = 1.0;
    vt_data_reset(m, d);
    *data = d;
    return VT_OK;
}

static vt_status data_create(vt_data **data, const vt_model *m, int full)
{
    if (!data || !m) return VT_ERR_NULL;
    *data = NULL;
    const size_t bytes = data_bytes(m, full);
    if (!bytes) return VT_ERR_TOO_MANY_BODIES;
    void *block = malloc(bytes); /* vt_data_init zeroes what it uses */
    if (!block) return VT_ERR_NO_MEMORY;
    const vt_status st = data_init(data, m, block, bytes, 1, full);
    if (st) {
        free(block);
        return st;
    }
    (*data)->block = block;
    return VT_OK;
}

vt_status vt_data_create(vt_data **data, const vt_model *m)
{
    return data_create(data, m, m && m->layout == VT_LAYOUT_FULL);
}

vt_status vt_data_create_full(vt_data **data, const vt_model *m)
{
    return data_create(data, m, 1);
}

vt_status vt_data_init(vt_data **data, const vt_model *m, void *buffer, size_t size)
{
    return data_init(data, m, buffer, size, 0, m && m->layout == VT_LAYOUT_FULL);
}

void vt_data_free(vt_data *d)
{
    if (!d || !d->block) return; /* NULL for data in the caller's buffer: not ours to free */
    VT_UNPOISON(d->arena->base, d->arena->size); /* the block goes back to malloc whole */
    free(d->block);
}

vt_status vt_data_reset(const vt_model *m, vt_data *d)
{
    vt_status st = vt_check_pair(m, d, "vt_data_reset");
    if (st) return st;
    memcpy(d->q, m->q0, (size_t)m->nq * sizeof(double));
    memset(d->qd, 0, (size_t)m->nv * sizeof(double));
    memset(d->xfrc, 0, 6 * ((size_t)m->nbody + 1) * sizeof(double));
    memset(d->qfrc, 0, (size_t)m->nv * sizeof(double));
    d->ida_flag = 0;
    vt_diagnostics_reset(d);
    d->time = 0.0;
    d->message[0] = '\0';
    return VT_OK;
}
