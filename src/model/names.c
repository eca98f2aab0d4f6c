/* An index of names (model/names.h): an AVL tree over a caller's entries, ordered by strcmp of
 * their names. Each node is an entry's number; its children and height sit in one int array
 * (3 per entry), links as entry + 1 so that a zeroed index is an empty one. The tree's height
 * stays below 1.45 log2(n + 2), so a find or an insert compares at most that many names. */
#include <limits.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#include "model/names.h"

#define LEFT(x, t) ((x)[3 * (size_t)((t) - 1)])
#define RIGHT(x, t) ((x)[3 * (size_t)((t) - 1) + 1])
#define HEIGHT(x, t) ((x)[3 * (size_t)((t) - 1) + 2])

static int height(const int *node, int t)
{
    return t ? HEIGHT(node, t) : 0;
}

static void update(int *node, int t)
{
    const int l = height(node, LEFT(node, t)), r = height(node, RIGHT(node, t));
    HEIGHT(node, t) = 1 + (l > r ? l : r);
}

/* t's left child up, t its right child; the new subtree root */
static int rotate_right(int *node, int t)
{
    const int l = LEFT(node, t);
    LEFT(node, t) = RIGHT(node, l);
    RIGHT(node, l) = t;
    update(node, t);
    update(node, l);
    return l;
}

static int rotate_left(int *node, int t)
{
    const int r = RIGHT(node, t);
    RIGHT(node, t) = LEFT(node, r);
    LEFT(node, r) = t;
    update(node, t);
    update(node, r);
    return r;
}

/* the subtree at t balanced again after an insert below it (heights differ by at most 2) */
static int rebalance(int *node, int t)
{
    update(node, t);
    const int l = LEFT(node, t), r = RIGHT(node, t), bf = height(node, l) - height(node, r);
    if (bf > 1) {
        if (height(node, LEFT(node, l)) < height(node, RIGHT(node, l))) LEFT(node, t) = rotate_left(node, l);
        return rotate_right(node, t);
    }
    if (bf < -1) {
        if (height(node, RIGHT(node, r)) < height(node, LEFT(node, r))) RIGHT(node, t) = rotate_right(node, r);
        return rotate_left(node, t);
    }
    return t;
}

/* node k + 1 under the subtree at t (recursion as deep as the tree: below 45 levels for any int
 * count); the subtree's new root */
static int insert(int *node, const void *list, vt_name_at at, int t, int k, const char *name)
{
    if (!t) return k + 1;
    if (strcmp(name, at(list, t - 1)) < 0)
        LEFT(node, t) = insert(node, list, at, LEFT(node, t), k, name);
    else
        RIGHT(node, t) = insert(node, list, at, RIGHT(node, t), k, name);
    return rebalance(node, t);
}

vt_status vt_names_reserve(vt_names *x, int n)
{
    if (n <= x->cap) return VT_OK;
    /* half again (at least 16), within what an int counts and 3 ints per entry can address */
    const int most = (int)((SIZE_MAX / (3 * sizeof(int)) < (size_t)INT_MAX) ? SIZE_MAX / (3 * sizeof(int)) : INT_MAX);
    if (n > most) return VT_ERR_TOO_MANY_BODIES;
    int cap = x->cap < 16 ? 16 : x->cap;
    while (cap < n) cap = cap > most - cap / 2 ? most : cap + cap / 2;
    int *p = realloc(x->node, 3 * (size_t)cap * sizeof(int));
    if (!p) return VT_ERR_NO_MEMORY;
    memset(p + 3 * (size_t)x->cap, 0, 3 * (size_t)(cap - x->cap) * sizeof(int));
    x->node = p;
    x->cap = cap;
    return VT_OK;
}

int vt_names_find(const vt_names *x, const void *list, vt_name_at at, const char *name)
{
    if (!name) return -1;
    int t = x->root;
    while (t) {
        const int c = strcmp(name, at(list, t - 1));
        if (c == 0) return t - 1;
        t = c < 0 ? LEFT(x->node, t) : RIGHT(x->node, t);
    }
    return -1;
}

void vt_names_insert(vt_names *x, const void *list, vt_name_at at, int k)
{
    int *node = x->node;
    LEFT(node, k + 1) = RIGHT(node, k + 1) = 0;
    HEIGHT(node, k + 1) = 1;
    x->root = insert(node, list, at, x->root, k, at(list, k));
}

void vt_names_free(vt_names *x)
{
    free(x->node);
    x->node = NULL;
    x->cap = 0;
    x->root = 0;
}

const char *vt_name_in_array(const void *names, int k)
{
    return (const char *)names + (size_t)VT_NAME_MAX * (size_t)k;
}
