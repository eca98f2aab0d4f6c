/* src/base/status.c: every status has its own text; vt_version() and the header's macros equal
 * meson's project version. */
#include <stdio.h>

#include "vt_test.h"

static void test_status_strings_distinct(void **state)
{
    (void)state;
    for (int a = VT_ERR_CONTACT; a <= 0; a++) { /* the lowest status: every one */
        const char *sa = vt_status_string((vt_status)a);
        assert_non_null(sa);
        assert_true(strlen(sa) > 0);
        for (int c = a + 1; c <= 0; c++) assert_string_not_equal(sa, vt_status_string((vt_status)c));
    }
}

/* vt_version() and the header's macros against meson's project version (passed by
 * tests/meson.build as VT_TEST_PROJECT_VERSION) */
static void test_version(void **state)
{
    (void)state;
    assert_string_equal(vt_version(), VT_TEST_PROJECT_VERSION);
    assert_string_equal(VT_VERSION_STRING, VT_TEST_PROJECT_VERSION);
    char parts[64];
    snprintf(parts, sizeof parts, "%d.%d.%d", VT_VERSION_MAJOR, VT_VERSION_MINOR, VT_VERSION_PATCH);
    assert_string_equal(parts, VT_TEST_PROJECT_VERSION);
}

int main(void)
{
    const struct CMUnitTest tests[] = {
        cmocka_unit_test(test_status_strings_distinct),
        cmocka_unit_test(test_version),
    };
    return cmocka_run_group_tests(tests, NULL, NULL);
}
