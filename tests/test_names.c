/* src/model/names.c: the index of names against a linear search. Random names (short, long,
 * sharing prefixes, some repeated) inserted as a builder does (a duplicate refused: found first,
 * not inserted), some entries left out (unnamed); every name and some absent ones found as the
 * linear search finds them, the list moved (realloc) between calls; the tree's height within the
 * AVL bound, checked by walking it (in order: the names sorted by strcmp; every node balanced),
 * and the string compares of a find counted, within that bound. */
#include <stdio.h>

#include "vt_test.h"

#include "model/names.h"

/* the list: VT_NAME_MAX bytes a name, as the builder's; compares counted */
static long compares;
static const char *at_counted(const void *list, int k)
{
    compares++;
    return vt_name_in_array(list, k);
}

static int linear(const char *names, int n, const int *in, const char *name)
{
    for (int k = 0; k < n; k++)
        if (in[k] && strcmp(names + (size_t)VT_NAME_MAX * (size_t)k, name) == 0) return k;
    return -1;
}

/* a deterministic generator (no global state of the library's, none of libc's rand) */
static uint64_t next(uint64_t *s)
{
    *s ^= *s << 13;
    *s ^= *s >> 7;
    *s ^= *s << 17;
    return *s;
}

/* a random name: a prefix of 0-40 'a's (long shared prefixes), then 1-8 letters of a small
 * alphabet (repeats happen), at most VT_NAME_MAX − 1 bytes */
static void random_name(char *out, uint64_t *s)
{
    const int pre = (int)(next(s) % 41), tail = 1 + (int)(next(s) % 8);
    int n = 0;
    for (int k = 0; k < pre; k++) out[n++] = 'a';
    for (int k = 0; k < tail; k++) out[n++] = "abcd_xyz"[next(s) % 8];
    out[n] = '\0';
}

/* the subtree at t (entry + 1): its height, every node balanced and its names in order between
 * lo and hi (NULL: open); counts its nodes into *count */
static int walk(const vt_names *x, const char *names, int t, const char *lo, const char *hi, int *count)
{
    if (!t) return 0;
    const int *nd = x->node + 3 * (size_t)(t - 1);
    const char *name = vt_name_in_array(names, t - 1);
    if (lo) assert_true(strcmp(lo, name) < 0);
    if (hi) assert_true(strcmp(name, hi) < 0);
    const int l = walk(x, names, nd[0], lo, name, count), r = walk(x, names, nd[1], name, hi, count);
    assert_true(l - r <= 1 && r - l <= 1);
    assert_int_equal(nd[2], 1 + (l > r ? l : r));
    (*count)++;
    return nd[2];
}

static void check_against_linear(int n, uint64_t seed)
{
    char *names = malloc((size_t)n * VT_NAME_MAX);
    int *in = calloc((size_t)n, sizeof(int));
    assert_true(names && in);
    vt_names x = {0};
    uint64_t s = seed;
    int inserted = 0, refused = 0;
    for (int k = 0; k < n; k++) {
        char *name = names + (size_t)VT_NAME_MAX * (size_t)k;
        random_name(name, &s);
        assert_int_equal(vt_names_reserve(&x, k + 1), VT_OK);
        if (next(&s) % 10 == 0) continue; /* unnamed: reserved, never linked */
        const int found = vt_names_find(&x, names, at_counted, name);
        assert_int_equal(found, linear(names, k, in, name)); /* a duplicate: the first entry */
        if (found >= 0) {
            refused++;
            continue;
        }
        vt_names_insert(&x, names, at_counted, k);
        in[k] = 1;
        inserted++;
    }
    if (n >= 100) assert_true(inserted > n / 4 && refused > 0); /* both kinds met */
    /* the list moves: the index holds entry numbers only */
    char *moved = malloc((size_t)n * VT_NAME_MAX);
    assert_non_null(moved);
    memcpy(moved, names, (size_t)n * VT_NAME_MAX);
    memset(names, 0, (size_t)n * VT_NAME_MAX);
    free(names);
    names = moved;
    int count = 0;
    const int h = walk(&x, names, x.root, NULL, NULL, &count);
    assert_int_equal(count, inserted);
    assert_true(h <= 1.45 * log2((double)inserted + 2.0)); /* AVL */
    /* every entry's name, and names that are in no entry */
    for (int k = 0; k < n; k++) {
        const char *name = names + (size_t)VT_NAME_MAX * (size_t)k;
        compares = 0;
        assert_int_equal(vt_names_find(&x, names, at_counted, name), linear(names, n, in, name));
        assert_true(compares <= h);
    }
    for (int k = 0; k < 200; k++) {
        char name[VT_NAME_MAX];
        random_name(name, &s);
        strcat(name, k % 2 ? "!" : ""); /* '!' is in no name: absent; the others at random */
        assert_int_equal(vt_names_find(&x, names, at_counted, name), linear(names, n, in, name));
    }
    assert_int_equal(vt_names_find(&x, names, at_counted, NULL), -1);
    assert_int_equal(vt_names_find(&x, names, at_counted, ""), linear(names, n, in, ""));
    vt_names_free(&x);
    assert_null(x.node);
    assert_int_equal(x.root, 0);
    free(names);
    free(in);
}

static void test_random_names(void **state)
{
    (void)state;
    check_against_linear(1, 1);
    check_against_linear(7, 2);
    check_against_linear(100, 3);
    check_against_linear(3000, 4);
}

/* names inserted in order (a generated file's "link0000001", "link0000002", ...: sorted input,
 * the worst case of an unbalanced tree): the height stays logarithmic, and a chain's 50,000
 * names cost at most that many compares each */
static void test_sorted_input(void **state)
{
    (void)state;
    const int n = 50000;
    char *names = malloc((size_t)n * VT_NAME_MAX);
    assert_non_null(names);
    vt_names x = {0};
    compares = 0;
    for (int k = 0; k < n; k++) {
        snprintf(names + (size_t)VT_NAME_MAX * (size_t)k, VT_NAME_MAX, "link%07d", k);
        assert_int_equal(vt_names_reserve(&x, k + 1), VT_OK);
        assert_int_equal(vt_names_find(&x, names, at_counted, names + (size_t)VT_NAME_MAX * (size_t)k), -1);
        vt_names_insert(&x, names, at_counted, k);
    }
    int count = 0;
    const int h = walk(&x, names, x.root, NULL, NULL, &count);
    assert_int_equal(count, n);
    assert_true(h <= 1.45 * log2(n + 2.0)); /* 16 for a perfect tree; at most 22 */
    assert_true(compares <= 2L * n * h); /* a find and an insert per name */
    for (int k = 0; k < n; k += 997) assert_int_equal(vt_names_find(&x, names, at_counted, names + (size_t)VT_NAME_MAX * (size_t)k), k);
    assert_int_equal(vt_names_find(&x, names, at_counted, "link"), -1);
    vt_names_free(&x);
    free(names);
}

/* reserve: grows (the index kept), never shrinks; an empty index finds nothing */
static void test_reserve(void **state)
{
    (void)state;
    char names[3][VT_NAME_MAX] = {"b", "a", "c"};
    vt_names x = {0};
    assert_int_equal(vt_names_find(&x, names, vt_name_in_array, "a"), -1); /* empty */
    assert_int_equal(vt_names_reserve(&x, 2), VT_OK);
    vt_names_insert(&x, names, vt_name_in_array, 0);
    vt_names_insert(&x, names, vt_name_in_array, 1);
    const int cap = x.cap;
    assert_int_equal(vt_names_reserve(&x, 1), VT_OK);
    assert_int_equal(x.cap, cap);
    assert_int_equal(vt_names_reserve(&x, cap + 1), VT_OK);
    assert_true(x.cap > cap);
    vt_names_insert(&x, names, vt_name_in_array, 2);
    assert_int_equal(vt_names_reserve(&x, -1), VT_OK); /* nothing to do */
    for (int k = 0; k < 3; k++) assert_int_equal(vt_names_find(&x, names, vt_name_in_array, names[k]), k);
    vt_names_free(&x);
    vt_names_free(&x); /* twice: nothing */
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_random_names),
        cmocka_unit_test(test_sorted_input),
        cmocka_unit_test(test_reserve),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
