/* src/model/urdf.c when libxml2 runs out of memory while parsing: libxml2's allocator replaced
 * (xmlMemSetup, process-wide, so an executable of its own, set before any libxml2 call) by one
 * that fails its n-th allocation after being armed. For every n up to the number of
 * allocations a whole parse makes, the load returns VT_OK (the failure was absorbed or not
 * reached) or VT_ERR_NO_MEMORY with an out-of-memory message, never VT_ERR_XML "malformed XML"
 * nor any other status; nothing is written to standard error; a failed load leaves *builder
 * NULL. The allocation sequence is the same from run to run (one thread, the same input), so
 * the test is deterministic. */
#define _POSIX_C_SOURCE 200809L /* dup, fileno */
#include <stdio.h>
#include <stdlib.h>
#include <unistd.h>

#include <libxml/parser.h>
#include <libxml/xmlmemory.h>

#include "vt_test.h"

#ifndef VT_TEST_URDF_DIR
#error "VT_TEST_URDF_DIR: the directory of the test's URDF files (tests/meson.build)"
#endif

static long countdown = -1; /* allocations left before the failing one; -1: none fails */
static long count;          /* allocations made since armed */

static int take(void)
{
    count++;
    if (countdown < 0) return 1;
    if (countdown == 0) return 0;
    countdown--;
    return 1;
}

static void *oom_malloc(size_t n)
{
    return take() ? malloc(n) : NULL;
}

static void *oom_realloc(void *p, size_t n)
{
    return take() ? realloc(p, n) : NULL;
}

static char *oom_strdup(const char *s)
{
    return take() ? strdup(s) : NULL;
}

static const char *robot =
    "<?xml version=\"1.0\"?>\n<!-- a comment -->\n<robot name=\"r\">\n"
    "  <link name=\"world\"/>\n"
    "  <link name=\"a\"><inertial><origin xyz=\"0.5 0 0\" rpy=\"0 0 0.1\"/><mass value=\"2\"/>\n"
    "    <inertia ixx=\"0.01\" ixy=\"0\" ixz=\"0\" iyy=\"0.2\" iyz=\"0\" izz=\"0.2\"/></inertial></link>\n"
    "  <link name=\"b&amp;c\"><inertial><mass value=\"1\"/><inertia ixx=\"0.1\" iyy=\"0.1\" izz=\"0.1\"/></inertial></link>\n"
    "  <joint name=\"j1\" type=\"revolute\"><parent link=\"world\"/><child link=\"a\"/><axis xyz=\"0 1 0\"/>\n"
    "    <limit lower=\"-1\" upper=\"1\" effort=\"10\" velocity=\"2\"/></joint>\n"
    "  <joint name=\"j2\" type=\"prismatic\"><parent link=\"a\"/><child link=\"b&amp;c\"/><origin xyz=\"1 0 0\"/>\n"
    "    <axis xyz=\"1 0 0\"/></joint>\n"
    "</robot>\n";

/* one load with the n-th allocation failing (n < 0: none), standard error captured */
static vt_status load(long n, char *msg, vt_builder **b, char *said, size_t said_size)
{
    fflush(stderr);
    FILE *cap = tmpfile();
    assert_non_null(cap);
    const int saved = dup(2);
    assert_true(saved >= 0);
    assert_true(dup2(fileno(cap), 2) >= 0);
    count = 0;
    countdown = n;
    const vt_status st = vt_urdf_builder_string(b, robot, NULL, msg);
    countdown = -1;
    fflush(stderr);
    dup2(saved, 2);
    close(saved);
    rewind(cap);
    const size_t got = fread(said, 1, said_size - 1, cap);
    said[got] = '\0';
    fclose(cap);
    return st;
}

static void test_out_of_memory(void **state)
{
    (void)state;
    char msg[256], said[512];
    vt_builder *b = NULL;
    assert_int_equal(load(-1, msg, &b, said, sizeof said), VT_OK);
    assert_string_equal(said, "");
    vt_builder_free(b);
    const long total = count; /* the allocations of a whole parse */
    assert_true(total > 20);
    long refused = 0;
    for (long n = 0; n < total; n++) {
        b = (vt_builder *)&msg;
        msg[0] = '\0';
        const vt_status st = load(n, msg, &b, said, sizeof said);
        if (said[0]) fail_msg("allocation %ld of %ld failing: printed \"%s\"", n, total, said);
        if (st == VT_OK) {
            assert_non_null(b);
            vt_builder_free(b);
            continue;
        }
        if (st != VT_ERR_NO_MEMORY || !strstr(msg, "out of memory") || b)
            fail_msg("allocation %ld of %ld failing: status %d (%s), message \"%s\"", n, total, (int)st,
                     vt_status_string(st), msg);
        refused++;
    }
    printf("%ld allocations in a parse; %ld of them, failing, gave VT_ERR_NO_MEMORY\n", total, refused);
    assert_true(refused > 0);
}

int main(void)
{
    /* before any libxml2 call (the library's first parse calls xmlInitParser) */
    if (xmlMemSetup(free, oom_malloc, oom_realloc, oom_strdup) != 0) return 1;
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_out_of_memory),
    };
    const int failed = cmocka_run_group_tests(tests, NULL, NULL);
    xmlCleanupParser();
    xmlMemSetup(free, malloc, realloc, strdup); /* as it was */
    return failed;
}
