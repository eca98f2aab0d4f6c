/* Writes one double past a scratch allocation, on purpose. In an AddressSanitizer build the
 * write lands in the arena's poisoned padding and ASan stops the program: meson runs this with
 * should_fail, so the test passes only if the overrun is caught where it happens. */
#include <stdio.h>

#include "base/arena.h"
#include "scenes.h"

int main(void)
{
    vt_model *m;
    vt_data *d;
    if (vt_scene_double_link(&m, 1) || vt_data_create(&d, m)) return 0; /* no overrun: the test fails */
    double *volatile a = VT_SCRATCH(d, double, 10, "a");
    if (!a) return 0;
    a[10] = 1.0; /* one past the end */
    printf("the overrun went unnoticed\n");
    vt_scratch_release(d, 0);
    vt_data_free(d);
    vt_model_free(m);
    return 0;
}
