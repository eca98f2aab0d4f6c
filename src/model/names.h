/* vtdyn — An index of names (model/names.c): the entries 0, 1, ... of a caller's list found by
 * name in O(log n) string compares, for the builder's names (duplicates refused, finds) and the
 * URDF loader's links and joints. An AVL tree ordered by strcmp whose nodes are the entries'
 * numbers: the names stay in the caller's list and are read through at(list, k) at each call, so
 * the list may move (realloc) between calls. No global state; the index's one array is its own
 * (vt_names_free). */
#ifndef VT_MODEL_NAMES_H
#define VT_MODEL_NAMES_H

#include "vtdyn.h"

/* the name of entry k of list (a string, not NULL) */
typedef const char *(*vt_name_at)(const void *list, int k);

/* An index; all zero (calloc, {0}) is an empty one. node: per entry, its left and right child
 * (entry + 1, 0 for none) and its height (0 for an entry not in the tree, e.g. unnamed); root:
 * entry + 1, 0 when empty; cap: entries node has room for. */
typedef struct {
    int *node;
    int cap;
    int root;
} vt_names;

/* Room for entries 0..n-1 (amortized: the array grows by half): VT_OK, or VT_ERR_NO_MEMORY with
 * the index as it was (VT_ERR_TOO_MANY_BODIES when n passes what an int array can count). */
vt_status vt_names_reserve(vt_names *x, int n);

/* The entry whose name is name, or -1 (also for NULL). */
int vt_names_find(const vt_names *x, const void *list, vt_name_at at, const char *name);

/* Links entry k (room reserved) into the index under its name at(list, k), which no entry in
 * the index has. */
void vt_names_insert(vt_names *x, const void *list, vt_name_at at, int k);

/* Frees the index's array; x is then empty. */
void vt_names_free(vt_names *x);

/* at() for a list of names VT_NAME_MAX bytes apart (the builder's and the model's) */
const char *vt_name_in_array(const void *names, int k);

#endif
