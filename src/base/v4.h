/* vtdyn — 3-vectors and Euler parameters in the four lanes of one value: the algebra of the
 * body kernels (kinematics/body.h). A 3-vector holds lanes 0-2, lane 3 is whatever the
 * operations leave there and is never read into lanes 0-2; Euler parameters p hold all four.
 *
 * With GCC or Clang a vt_v4 is a vector of four doubles (their vector extensions): one AVX
 * register, or two SSE2 ones, and each operation a few instructions on the lanes at once where
 * the scalar code of vec3.h takes three to nine. Elsewhere (VT_V4_PORTABLE, or another compiler)
 * it is a struct of four doubles and the same operations are loops: the kernels are written once
 * against the functions below. Each lane of a result is the scalar expression's, term by term
 * in the same order (the compiler contracts a * b + c into an FMA where -ffp-contract allows,
 * as it does the scalar code); tests/test_v4.c checks both forms against vec3.h.
 *
 * Loads and stores: vt_v4_load reads p[0..3] and vt_v4_store writes p[0..3]; a 3-vector is
 * written by vt_v4_store3 (p[0..2] alone), vt_v4_store3_up (p[3] overwritten too, in the vector
 * form: one store) or vt_v4_store3_down (p[-1] too). The arrays read or written so carry a
 * fourth element or one spare double at their end (data.c, model.c), and a pass that stores a
 * 3-vector up writes each array in increasing order, each element's own value after the spare
 * lane of the one before (down: in decreasing order). */
#ifndef VT_BASE_V4_H
#define VT_BASE_V4_H

#include <string.h>

/* every operation inlined, always: one not inlined would pass its vt_v4 through memory */
#if defined(__GNUC__)
#define VT_V4_INLINE static inline __attribute__((always_inline))
#else
#define VT_V4_INLINE static inline
#endif

#if defined(__GNUC__) && defined(__AVX__) && !defined(VT_V4_PORTABLE)
#define VT_V4_VECTOR 1
#if !defined(__clang__)
/* a vt_v4 returned by a function when AVX is not enabled: GCC notes the ABI of such calls; every
 * function here is static inline, and no vt_v4 crosses a translation unit */
#pragma GCC diagnostic ignored "-Wpsabi"
#endif
typedef double vt_v4 __attribute__((vector_size(32)));
typedef double vt_v4_pair __attribute__((vector_size(16)));
#if defined(__clang__) || __GNUC__ >= 12
#define VT_V4_SHUFFLE(a, b, i, j, k, l) __builtin_shufflevector((a), (b), i, j, k, l)
#else
typedef long long vt_v4_index __attribute__((vector_size(32)));
#define VT_V4_SHUFFLE(a, b, i, j, k, l) __builtin_shuffle((a), (b), (vt_v4_index){i, j, k, l})
#endif
#define VT_V4_PERM(a, i, j, k, l) VT_V4_SHUFFLE(a, a, i, j, k, l)
#else
#define VT_V4_VECTOR 0
typedef struct {
    double x, y, z, w;
} vt_v4;
#endif

#if VT_V4_VECTOR
VT_V4_INLINE vt_v4 vt_v4_set(double x, double y, double z, double w) { return (vt_v4){x, y, z, w}; }
VT_V4_INLINE vt_v4 vt_v4_splat(double s) { return (vt_v4){s, s, s, s}; }
VT_V4_INLINE double vt_v4_lane(vt_v4 a, int k) { return a[k]; }
VT_V4_INLINE vt_v4 vt_v4_add(vt_v4 a, vt_v4 b) { return a + b; }
VT_V4_INLINE vt_v4 vt_v4_sub(vt_v4 a, vt_v4 b) { return a - b; }
VT_V4_INLINE vt_v4 vt_v4_mul(vt_v4 a, vt_v4 b) { return a * b; }
/* lanes turned: (a1, a2, a0, a3), (a1, a2, a3, a0), (a3, a0, a1, a2); lane k in all four */
VT_V4_INLINE vt_v4 vt_v4_yzx(vt_v4 a) { return VT_V4_PERM(a, 1, 2, 0, 3); }
VT_V4_INLINE vt_v4 vt_v4_left(vt_v4 a) { return VT_V4_PERM(a, 1, 2, 3, 0); }
VT_V4_INLINE vt_v4 vt_v4_right(vt_v4 a) { return VT_V4_PERM(a, 3, 0, 1, 2); }
VT_V4_INLINE vt_v4 vt_v4_x(vt_v4 a) { return VT_V4_PERM(a, 0, 0, 0, 0); }
VT_V4_INLINE vt_v4 vt_v4_y(vt_v4 a) { return VT_V4_PERM(a, 1, 1, 1, 1); }
VT_V4_INLINE vt_v4 vt_v4_z(vt_v4 a) { return VT_V4_PERM(a, 2, 2, 2, 2); }
VT_V4_INLINE vt_v4 vt_v4_neg(vt_v4 a) { return -a; }
/* lanes picked from a (0-3) and b (4-7), the indices constants; vt_v4_with0: a with lane 0
 * replaced by s. Shuffles, not lane stores: without AVX a lane written alone would be a store
 * to the stack and a wider load of it, which the processor cannot forward */
#define vt_v4_mix(a, b, i, j, k, l) VT_V4_SHUFFLE(a, b, i, j, k, l)
VT_V4_INLINE vt_v4 vt_v4_with0(vt_v4 a, double s) { return VT_V4_SHUFFLE(vt_v4_splat(s), a, 0, 5, 6, 7); }
/* the rows of the 3x3 matrix whose columns are a, b, c (lane 3 of each whatever) */
VT_V4_INLINE void vt_v4_transpose3(vt_v4 a, vt_v4 b, vt_v4 c, vt_v4 *r0, vt_v4 *r1, vt_v4 *r2)
{
    const vt_v4 t0 = VT_V4_SHUFFLE(a, b, 0, 4, 2, 6), t1 = VT_V4_SHUFFLE(a, b, 1, 5, 3, 7);
    *r0 = VT_V4_SHUFFLE(t0, c, 0, 1, 4, 7);
    *r1 = VT_V4_SHUFFLE(t1, c, 0, 1, 5, 7);
    *r2 = VT_V4_SHUFFLE(t0, c, 2, 3, 6, 7);
}
VT_V4_INLINE vt_v4 vt_v4_load(const double *p)
{
    vt_v4 r;
    memcpy(&r, p, sizeof r);
    return r;
}
VT_V4_INLINE void vt_v4_store(double *p, vt_v4 a) { memcpy(p, &a, sizeof a); }
/* lanes 0-2 into p[0..2], p[3] overwritten: for arrays written in increasing order */
VT_V4_INLINE void vt_v4_store3_up(double *p, vt_v4 a) { vt_v4_store(p, a); }
/* lanes 0-2 into p[0..2], p[-1] overwritten: for arrays written in decreasing order */
VT_V4_INLINE void vt_v4_store3_down(double *p, vt_v4 a) { vt_v4_store(p - 1, VT_V4_PERM(a, 3, 0, 1, 2)); }
VT_V4_INLINE void vt_v4_store3(double *p, vt_v4 a)
{
    const vt_v4_pair lo = {a[0], a[1]};
    memcpy(p, &lo, sizeof lo);
    p[2] = a[2];
}
#else
/* the lanes as four scalars: each operation its scalar expressions, which the compiler keeps in
 * registers, a lane never used not computed */
VT_V4_INLINE vt_v4 vt_v4_set(double x, double y, double z, double w) { return (vt_v4){x, y, z, w}; }
VT_V4_INLINE vt_v4 vt_v4_splat(double s) { return (vt_v4){s, s, s, s}; }
VT_V4_INLINE double vt_v4_lane(vt_v4 a, int k) { return k == 0 ? a.x : k == 1 ? a.y : k == 2 ? a.z : a.w; }
VT_V4_INLINE vt_v4 vt_v4_add(vt_v4 a, vt_v4 b) { return (vt_v4){a.x + b.x, a.y + b.y, a.z + b.z, a.w + b.w}; }
VT_V4_INLINE vt_v4 vt_v4_sub(vt_v4 a, vt_v4 b) { return (vt_v4){a.x - b.x, a.y - b.y, a.z - b.z, a.w - b.w}; }
VT_V4_INLINE vt_v4 vt_v4_mul(vt_v4 a, vt_v4 b) { return (vt_v4){a.x * b.x, a.y * b.y, a.z * b.z, a.w * b.w}; }
VT_V4_INLINE vt_v4 vt_v4_neg(vt_v4 a) { return (vt_v4){-a.x, -a.y, -a.z, -a.w}; }
VT_V4_INLINE vt_v4 vt_v4_yzx(vt_v4 a) { return (vt_v4){a.y, a.z, a.x, a.w}; }
VT_V4_INLINE vt_v4 vt_v4_left(vt_v4 a) { return (vt_v4){a.y, a.z, a.w, a.x}; }
VT_V4_INLINE vt_v4 vt_v4_right(vt_v4 a) { return (vt_v4){a.w, a.x, a.y, a.z}; }
VT_V4_INLINE vt_v4 vt_v4_x(vt_v4 a) { return vt_v4_splat(a.x); }
VT_V4_INLINE vt_v4 vt_v4_y(vt_v4 a) { return vt_v4_splat(a.y); }
VT_V4_INLINE vt_v4 vt_v4_z(vt_v4 a) { return vt_v4_splat(a.z); }
VT_V4_INLINE double vt_v4_lane8(vt_v4 a, vt_v4 b, int k) { return k < 4 ? vt_v4_lane(a, k) : vt_v4_lane(b, k - 4); }
#define vt_v4_mix(a, b, i, j, k, l) \
    vt_v4_set(vt_v4_lane8(a, b, i), vt_v4_lane8(a, b, j), vt_v4_lane8(a, b, k), vt_v4_lane8(a, b, l))
VT_V4_INLINE vt_v4 vt_v4_with0(vt_v4 a, double s) { return (vt_v4){s, a.y, a.z, a.w}; }
VT_V4_INLINE void vt_v4_transpose3(vt_v4 a, vt_v4 b, vt_v4 c, vt_v4 *r0, vt_v4 *r1, vt_v4 *r2)
{
    *r0 = (vt_v4){a.x, b.x, c.x, 0.0};
    *r1 = (vt_v4){a.y, b.y, c.y, 0.0};
    *r2 = (vt_v4){a.z, b.z, c.z, 0.0};
}
VT_V4_INLINE vt_v4 vt_v4_load(const double *p) { return (vt_v4){p[0], p[1], p[2], p[3]}; }
VT_V4_INLINE void vt_v4_store(double *p, vt_v4 a) { p[0] = a.x, p[1] = a.y, p[2] = a.z, p[3] = a.w; }
VT_V4_INLINE void vt_v4_store3(double *p, vt_v4 a) { p[0] = a.x, p[1] = a.y, p[2] = a.z; }
VT_V4_INLINE void vt_v4_store3_up(double *p, vt_v4 a) { vt_v4_store3(p, a); }
VT_V4_INLINE void vt_v4_store3_down(double *p, vt_v4 a) { vt_v4_store3(p, a); }
#endif

/* a 3-vector from an array of three (lane 3 a copy of lane 2: no zeroing instruction) */
VT_V4_INLINE vt_v4 vt_v4_load3(const double *p) { return vt_v4_set(p[0], p[1], p[2], p[2]); }
/* a + s b */
VT_V4_INLINE vt_v4 vt_v4_madd(vt_v4 a, double s, vt_v4 b) { return vt_v4_add(a, vt_v4_mul(vt_v4_splat(s), b)); }
VT_V4_INLINE vt_v4 vt_v4_scale(double s, vt_v4 a) { return vt_v4_mul(vt_v4_splat(s), a); }
/* a · b over lanes 0-2, summed in vec3.h's order */
VT_V4_INLINE double vt_v4_dot3(vt_v4 a, vt_v4 b)
{
    const vt_v4 t = vt_v4_mul(a, b);
    return vt_v4_lane(t, 0) + vt_v4_lane(t, 1) + vt_v4_lane(t, 2);
}
/* a × b in lanes 0-2: c = a (b1, b2, b0) − (a1, a2, a0) b holds (r2, r0, r1) */
VT_V4_INLINE vt_v4 vt_v4_cross(vt_v4 a, vt_v4 b)
{
    return vt_v4_yzx(vt_v4_sub(vt_v4_mul(a, vt_v4_yzx(b)), vt_v4_mul(vt_v4_yzx(a), b)));
}
/* A 3x3 matrix as its three columns (a joint's axes, a rotation, an inertia), passed by value */
typedef struct {
    vt_v4 c[3];
} vt_m3;

/* M a */
VT_V4_INLINE vt_v4 vt_m3_mul(vt_m3 M, vt_v4 a)
{
    return vt_v4_add(vt_v4_add(vt_v4_mul(M.c[0], vt_v4_x(a)), vt_v4_mul(M.c[1], vt_v4_y(a))), vt_v4_mul(M.c[2], vt_v4_z(a)));
}
/* the columns of a column-major 3x3 array (A[9] read: a spare double after the array) */
VT_V4_INLINE vt_m3 vt_m3_load(const double *A)
{
    return (vt_m3){{vt_v4_load(A), vt_v4_load(A + 3), vt_v4_load(A + 6)}};
}
/* M^T */
VT_V4_INLINE vt_m3 vt_m3_transpose(vt_m3 M)
{
    vt_m3 T;
    vt_v4_transpose3(M.c[0], M.c[1], M.c[2], &T.c[0], &T.c[1], &T.c[2]);
    return T;
}

/* Euler parameters p = (p0, e) in the four lanes (base/euler.h's products, written out the same) */
/* a ⊗ b = (a0 b0 − a·b, a0 b + b0 a + a × b) */
VT_V4_INLINE vt_v4 vt_v4_quat_mul(vt_v4 a, vt_v4 b)
{
    const vt_v4 av = vt_v4_left(a), bv = vt_v4_left(b);
    const vt_v4 r = vt_v4_add(vt_v4_add(vt_v4_mul(vt_v4_x(a), bv), vt_v4_mul(vt_v4_x(b), av)), vt_v4_cross(av, bv));
    return vt_v4_with0(vt_v4_right(r), vt_v4_lane(a, 0) * vt_v4_lane(b, 0) - vt_v4_dot3(av, bv));
}
/* ½ E(p)^T w = ½ [0; w] ⊗ p: the rate of p turning at w (vt_quat_rate) */
VT_V4_INLINE vt_v4 vt_v4_quat_rate(vt_v4 p, vt_v4 w)
{
    const vt_v4 e = vt_v4_left(p);
    const vt_v4 r = vt_v4_scale(0.5, vt_v4_add(vt_v4_mul(vt_v4_x(p), w), vt_v4_cross(w, e)));
    return vt_v4_with0(vt_v4_right(r), -0.5 * vt_v4_dot3(w, e));
}
/* A(p) = (p0² − e·e) 1 + 2 e e^T + 2 p0 ẽ (vt_euler_A_inline), and A^T (the sign of the ẽ term
 * turned) */
VT_V4_INLINE void vt_v4_rotation(vt_v4 p, vt_m3 *A, vt_m3 *R)
{
    const double p0 = vt_v4_lane(p, 0), p1 = vt_v4_lane(p, 1), p2 = vt_v4_lane(p, 2), p3 = vt_v4_lane(p, 3);
    const vt_v4 S = vt_v4_splat(p0 * p0 - p1 * p1 - p2 * p2 - p3 * p3);
    const vt_v4 e = vt_v4_left(p), e2 = vt_v4_add(e, e), P = vt_v4_scale(2.0 * p0, e), N = vt_v4_neg(P);
    const vt_v4 b0 = vt_v4_mul(e, vt_v4_x(e2)), b1 = vt_v4_mul(e, vt_v4_y(e2)), b2 = vt_v4_mul(e, vt_v4_z(e2));
    /* P = 2 p0 e, N = −P: A's columns add (s, P2, −P1), (−P2, s, P0), (P1, −P0, s), A^T's the
     * signs turned; lanes 0-3 of a mix are P's, 4-7 N's */
    A->c[0] = vt_v4_add(b0, vt_v4_mix(S, vt_v4_mix(P, N, 2, 2, 5, 5), 0, 5, 6, 7));
    A->c[1] = vt_v4_add(b1, vt_v4_mix(vt_v4_mix(P, N, 6, 6, 0, 0), S, 0, 4, 2, 3));
    A->c[2] = vt_v4_add(b2, vt_v4_mix(vt_v4_mix(P, N, 1, 4, 4, 4), S, 0, 1, 4, 3));
    R->c[0] = vt_v4_add(b0, vt_v4_mix(S, vt_v4_mix(P, N, 6, 6, 1, 1), 0, 5, 6, 7));
    R->c[1] = vt_v4_add(b1, vt_v4_mix(vt_v4_mix(P, N, 2, 2, 4, 4), S, 0, 4, 2, 3));
    R->c[2] = vt_v4_add(b2, vt_v4_mix(vt_v4_mix(P, N, 5, 0, 0, 0), S, 0, 1, 4, 3));
}

#endif
