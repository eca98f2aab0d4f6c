/* Internal: the vtable behind the opaque vt_peer of peers.h. Each peer (pinocchio_peer.cpp,
 * mujoco_peer.c) fills one vt_peer_vtable and allocates the vt_peer; peer_common.c dispatches. */
#ifndef VT_BENCH_PEER_IMPL_H
#define VT_BENCH_PEER_IMPL_H

#include "peers.h"

#ifdef __cplusplus
extern "C" {
#endif

typedef struct vt_peer_vtable {
    int nmethods;
    const char *const *method_names;                          /* nmethods entries */
    void (*run)(void *impl, int method);                      /* method in [0, nmethods) */
    void (*torques)(const void *impl, double *tau);
    void (*reaction)(const void *impl, int k, double f[3], double n[3]);  /* k in [1, n] */
    void (*destroy)(void *impl);
} vt_peer_vtable;

struct vt_peer {
    const vt_peer_vtable *vt;
    void *impl;  /* the peer's own state */
    int n;       /* number of links reported by reaction(), and of joint coordinates reported by torques()
                  * (not so for the chain tip, n + 1 values, the RUSR four-bar, 4 values on 3 links, and
                  * the machines, nv values on nbody links) */
};

#ifdef __cplusplus
}
#endif

#endif /* VT_BENCH_PEER_IMPL_H */
