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

/* the scratch every file may hold at once (base/arena.h) */
static size_t arena_size(const vt_model *m)
{
    return vt_kinematics_scratch(m) + vt_mass_scratch(m) + vt_forces_scratch(m) + vt_constraints_scratch(m) +
           vt_roundoff_scratch(m) + vt_rank_scratch(m) + vt_kkt_scratch(m) + vt_routes_scratch(m) + vt_solve_scratch(m) +
           vt_maximal_scratch(m) + vt_reactions_scratch(m) + vt_recursive_scratch(m) + vt_kinematic_solve_scratch(m) +
           vt_inverse_transform_scratch(m);
}

static size_t layout(const vt_model *m, vt_data *d, char *base)
{
    const size_t n = (size_t)m->nbody, nb = n + 1, nx = 7 * n, nv = (size_t)m->nv;
    /* every array on a cache line (VT_DATA_ALIGN: the vectorized kernels' 8-double columns) */
    vt_block blk = {.base = base, .used = sizeof(vt_data), .align = VT_DATA_ALIGN};
    d->q = vt_block_take(&blk, (size_t)m->nq, sizeof(double));
    d->qd = vt_block_take(&blk, nv, sizeof(double));
    d->xfrc = vt_block_take(&blk, 6 * nb, sizeof(double));
    d->qfrc = vt_block_take(&blk, nv, sizeof(double));
    /* the arena, beside the inputs: its header, then the sum of the files' bounds (base/arena.h) */
    d->arena = vt_block_take(&blk, 1, sizeof(vt_arena));
    const size_t scratch = arena_size(m);
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
    d->A = vt_block_take(&blk, 9 * nb, sizeof(double));
    d->omega = vt_block_take(&blk, 3 * nb, sizeof(double));
    d->jaxis = vt_block_take(&blk, 9 * nb, sizeof(double));
    d->jsij = vt_block_take(&blk, 3 * nb, sizeof(double));
    d->jd = vt_block_take(&blk, 3 * nb, sizeof(double));
    d->jpoint = vt_block_take(&blk, 3 * nb, sizeof(double));
    d->twist = vt_block_take(&blk, 6 * nv, sizeof(double));
    d->xrel = vt_block_take(&blk, 6 * nb, sizeof(double));
    d->S = vt_block_take(&blk, nx * nv, sizeof(double));
    d->Sdqd = vt_block_take(&blk, nx, sizeof(double));
    d->R = vt_block_take(&blk, nv * nx, sizeof(double));
    d->Mp = vt_block_take(&blk, 16 * nb, sizeof(double));
    d->Mstar = vt_block_take(&blk, nv * nv, sizeof(double));
    d->F = vt_block_take(&blk, nx, sizeof(double));
    d->h = vt_block_take(&blk, nx, sizeof(double));
    d->Q = vt_block_take(&blk, nv, sizeof(double));
    const size_t nc = (size_t)m->nc, nd = (size_t)m->ndrive, nk = (size_t)m->ncut;
    d->Phi = vt_block_take(&blk, nc, sizeof(double));
    d->Phix = vt_block_take(&blk, 14 * nc, sizeof(double));
    d->Phiq = vt_block_take(&blk, nc * nv, sizeof(double));
    d->Phit = vt_block_take(&blk, nc, sizeof(double));
    d->gamma = vt_block_take(&blk, nc, sizeof(double));
    d->qdd = vt_block_take(&blk, nv, sizeof(double));
    d->lambda = vt_block_take(&blk, nc, sizeof(double));
    d->xdd = vt_block_take(&blk, nx, sizeof(double));
    d->alpha = vt_block_take(&blk, 3 * nb, sizeof(double));
    d->qfrc_drive = vt_block_take(&blk, nv, sizeof(double));
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
    d->lambda_null = vt_block_take(&blk, nc ? nc * nc : 1, sizeof(double));
    d->jnt_unique = vt_block_take(&blk, 6 * nb, sizeof(int));
    d->cut_unique = vt_block_take(&blk, 6 * (nk ? nk : 1), sizeof(int));
    return blk.used;
}

/* Bytes from the buffer's start to its first VT_DATA_ALIGN boundary: the struct and every
 * array (vt_block_take) start on a cache line. */
static size_t align_pad(const void *buffer)
{
    const uintptr_t a = (uintptr_t)buffer % VT_DATA_ALIGN;
    return a ? (size_t)(VT_DATA_ALIGN - a) : 0;
}

size_t vt_data_size(const vt_model *m)
{
    if (!m) return 0;
    vt_data probe;
    return layout(m, &probe, NULL) + (VT_DATA_ALIGN - 1); /* any start can be aligned */
}

/* The one path that lays out a data struct; poison: the arena's free part poisoned in
 * AddressSanitizer builds (our own block, not a caller's buffer) */
static vt_status data_init(vt_data **data, const vt_model *m, void *buffer, size_t size, int poison)
{
    if (!data) return VT_ERR_NULL;
    *data = NULL;
    if (!m || !buffer) return VT_ERR_NULL;
    vt_data probe;
    const size_t bytes = layout(m, &probe, NULL), pad = align_pad(buffer);
    if (size < pad || size - pad < bytes) return VT_ERR_BAD_SIZE; /* the buffer is left untouched */
    char *base = (char *)buffer + pad;
    memset(base, 0, bytes); /* zero: the structural zeros of S and R stay zero */
    vt_data *d = (vt_data *)base;
    layout(m, d, base);
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

vt_status vt_data_create(vt_data **data, const vt_model *m)
{
    if (!data || !m) return VT_ERR_NULL;
    *data = NULL;
    const size_t bytes = vt_data_size(m);
    void *block = malloc(bytes); /* vt_data_init zeroes what it uses */
    if (!block) return VT_ERR_NO_MEMORY;
    const vt_status st = data_init(data, m, block, bytes, 1);
    if (st) {
        free(block);
        return st;
    }
    (*data)->block = block;
    return VT_OK;
}

vt_status vt_data_init(vt_data **data, const vt_model *m, void *buffer, size_t size)
{
    return data_init(data, m, buffer, size, 0);
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
