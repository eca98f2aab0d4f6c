/* Generic part of the peer interface (peers.h): dispatch through the peer's vtable. */
#include <stdlib.h>
#include <string.h>

#include "peer_impl.h"

int vt_peer_nmethods(const vt_peer *p)
{
    return p ? p->vt->nmethods : 0;
}

const char *vt_peer_method(const vt_peer *p, int method)
{
    if (!p || method < 0 || method >= p->vt->nmethods) return NULL;
    return p->vt->method_names[method];
}

void vt_peer_run(vt_peer *p, int method)
{
    if (p && method >= 0 && method < p->vt->nmethods) p->vt->run(p->impl, method);
}

void vt_peer_torques(const vt_peer *p, double *tau)
{
    if (p) p->vt->torques(p->impl, tau);
}

void vt_peer_reaction(const vt_peer *p, int k, double f[3], double n[3])
{
    if (p && k >= 1 && k <= p->n) {
        p->vt->reaction(p->impl, k, f, n);
    } else {
        memset(f, 0, 3 * sizeof(double));
        memset(n, 0, 3 * sizeof(double));
    }
}

void vt_peer_free(vt_peer *p)
{
    if (!p) return;
    p->vt->destroy(p->impl);
    free(p);
}
