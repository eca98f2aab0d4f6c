/* src/base/block.c: one allocation carved into arrays. Every array starts on an offset that is a
 * multiple of the block's alignment (16, as the model and trajectories use, and VT_DATA_ALIGN, as
 * the data uses), and on an aligned address when the base is; the total is the sum of the parts
 * and of the gaps before them, each gap shorter than the alignment (none when the parts are whole
 * multiples of it); a sizing pass (base NULL) and a carving pass give the same offsets and total,
 * and the carved arrays fill the allocation without overlapping; a size that does not fit in size_t
 * marks the block (overflow) instead of wrapping. */
#include "vt_test.h"

#include "base/block.h"

/* the parts carved, in order: n elements of size bytes (empty arrays and odd sizes included) */
typedef struct {
    size_t n, size;
} part;

static const part parts[] = {{3, sizeof(double)}, {0, sizeof(double)}, {5, sizeof(int)},  {1, 40},
                             {7, 1},              {64, VT_NAME_MAX},   {2, sizeof(double)}, {1, 1},
                             {9, 3 * sizeof(double)}};
enum { NPART = sizeof parts / sizeof parts[0] };

/* the sizing pass, then the carving pass into an allocation aligned to align; start bytes ahead
 * (a header such as the struct itself) */
static void carve(size_t align, size_t start)
{
    vt_block sizing = {.base = NULL, .used = start, .align = align};
    size_t off[NPART], sum = 0;
    for (int k = 0; k < NPART; k++) {
        assert_null(vt_block_take(&sizing, parts[k].n, parts[k].size));
        off[k] = sizing.used - parts[k].n * parts[k].size; /* where part k starts */
        sum += parts[k].n * parts[k].size;
    }
    /* the total: the header, the parts and the gaps before them, each gap < align */
    size_t prev = start, gaps = 0;
    for (int k = 0; k < NPART; k++) {
        assert_int_equal(off[k] % align, 0);
        assert_true(off[k] >= prev && off[k] - prev < align);
        gaps += off[k] - prev;
        prev = off[k] + parts[k].n * parts[k].size;
    }
    assert_int_equal(sizing.used, start + sum + gaps);

    const size_t bytes = (sizing.used + align - 1) / align * align; /* aligned_alloc's size rule */
    char *mem = aligned_alloc(align, bytes);
    assert_non_null(mem);
    vt_block b = {.base = mem, .used = start, .align = align};
    for (int k = 0; k < NPART; k++) {
        char *p = vt_block_take(&b, parts[k].n, parts[k].size);
        assert_ptr_equal(p, mem + off[k]); /* the sizing pass's offset */
        assert_int_equal((uintptr_t)p % align, 0);
        memset(p, 'a' + k, parts[k].n * parts[k].size); /* within the allocation (ASan, valgrind) */
    }
    assert_int_equal(b.used, sizing.used);
    for (int k = 0; k < NPART; k++) /* no later part wrote over an earlier one */
        for (size_t c = 0; c < parts[k].n * parts[k].size; c++) assert_int_equal(mem[off[k] + c], 'a' + k);
    free(mem);
}

static void test_alignment_total_and_passes(void **state)
{
    (void)state;
    const size_t aligns[] = {8, 16, VT_DATA_ALIGN};
    const size_t starts[] = {0, 1, 24, 200};
    for (int a = 0; a < 3; a++)
        for (int s = 0; s < 4; s++) carve(aligns[a], starts[s]);
}

/* parts that are whole multiples of the alignment leave no gap: the total is exactly their sum */
static void test_no_gap_between_whole_parts(void **state)
{
    (void)state;
    vt_block b = {.base = NULL, .used = 0, .align = 16};
    size_t sum = 0;
    for (size_t k = 0; k < 10; k++) {
        vt_block_take(&b, 2 * k, sizeof(double));
        sum += 2 * k * sizeof(double);
        assert_int_equal(b.used, sum);
    }
    vt_block_take(&b, 0, 1); /* an empty array at the end moves nothing */
    assert_int_equal(b.used, sum);
}

/* sizes past size_t: n x size that wraps, used + n x size that wraps, the alignment's round-up
 * that wraps; each marks the block (used SIZE_MAX, NULL returned), and the mark stays for every
 * later take, even a small one; sizes just within it are counted exactly */
static void test_overflow_marked(void **state)
{
    (void)state;
    const size_t half = SIZE_MAX / 2 + 1; /* 2^63 on 64 bits */
    vt_block b = {.base = NULL, .used = 0, .align = 16};
    vt_block_take(&b, half / 8, 8); /* 2^63 bytes: fits */
    assert_false(b.overflow);
    assert_true(b.used == half);
    vt_block_take(&b, 2, SIZE_MAX / 2); /* n x size = SIZE_MAX − 1: fits, but not after used */
    assert_true(b.overflow);
    assert_true(b.used == SIZE_MAX);
    assert_null(vt_block_take(&b, 1, 1)); /* the mark stays */
    assert_true(b.overflow && b.used == SIZE_MAX);

    vt_block p = {.base = NULL, .used = 0, .align = 16};
    vt_block_take(&p, SIZE_MAX / 3 + 1, 3); /* the product itself wraps */
    assert_true(p.overflow && p.used == SIZE_MAX);

    char byte;
    vt_block a = {.base = &byte, .used = SIZE_MAX - 3, .align = 16}; /* rounding up to 16 wraps */
    assert_null(vt_block_take(&a, 0, 1));
    assert_true(a.overflow);

    vt_block e = {.base = NULL, .used = SIZE_MAX - 31, .align = 16}; /* near the top, aligned: fits */
    vt_block_take(&e, 15, 1);
    assert_false(e.overflow);
    assert_true(e.used == SIZE_MAX - 16);
    vt_block_take(&e, 15, 1); /* rounded up to SIZE_MAX − 15, then 15 bytes: SIZE_MAX exactly */
    assert_false(e.overflow);
    assert_true(e.used == SIZE_MAX);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_alignment_total_and_passes),
        cmocka_unit_test(test_no_gap_between_whole_parts),
        cmocka_unit_test(test_overflow_marked),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
