/* Instructions of one build of vtdyn per recursive instant, for callgrind: loads one object made by
 * bench/ab/build.sh, sets up a scene (bench_inverse.c's state) and runs `calls` instants in one
 * ab_batch call.
 *   valgrind --tool=callgrind --toggle-collect=ab_batch --callgrind-out-file=/dev/null \
 *       count <X.so> <scene> <n> [calls]      (default 1000 calls)
 * callgrind prints "Collected : I" on stderr: the instructions of the batch; divided by calls
 * (and by n) they are the instructions per instant (per body). bench/ab/count.sh runs it on two
 * trees. */
#define _POSIX_C_SOURCE 200809L
#include <dlfcn.h>
#include <stdio.h>
#include <stdlib.h>

int main(int argc, char **argv)
{
    if (argc < 4) {
        fprintf(stderr, "usage: count <X.so> <scene> <n> [calls]\n");
        return 2;
    }
    void *h = dlopen(argv[1], RTLD_NOW | RTLD_LOCAL);
    if (!h) {
        fprintf(stderr, "count: %s\n", dlerror());
        return 1;
    }
    int (*setup)(const char *, int);
    double (*batch)(long);
    *(void **)&setup = dlsym(h, "ab_setup");
    *(void **)&batch = dlsym(h, "ab_batch");
    if (!setup || !batch) {
        fprintf(stderr, "count: %s lacks ab_setup/ab_batch\n", argv[1]);
        return 1;
    }
    const long calls = argc > 4 ? atol(argv[4]) : 1000;
    if (setup(argv[2], atoi(argv[3])) || batch(calls) < 0.0) {
        fprintf(stderr, "count: scene %s n = %s failed\n", argv[2], argv[3]);
        return 1;
    }
    return 0;
}
