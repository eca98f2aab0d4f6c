/* The CPU a benchmark ran on, from /proc/cpuinfo: model name, family and model, and the vector
 * extensions the -march=native builds can use (AVX2, FMA, AVX-512F). Shared by bench_inverse.c
 * and ab/ab.c so that both print the same line. */
#ifndef VT_BENCH_CPUINFO_H
#define VT_BENCH_CPUINFO_H

#include <stdio.h>
#include <string.h>

static void vt_bench_cpu_line(void)
{
    char line[8192], model[256] = "?", fam[32] = "?", mod[32] = "?";
    int avx2 = 0, fma = 0, avx512 = 0;
    FILE *f = fopen("/proc/cpuinfo", "r");
    while (f && fgets(line, sizeof line, f)) {
        char *v = strchr(line, ':');
        if (!v || !v[1]) continue;
        v += 2;
        v[strcspn(v, "\n")] = 0;
        if (!strncmp(line, "model name", 10)) snprintf(model, sizeof model, "%s", v);
        else if (!strncmp(line, "cpu family", 10)) snprintf(fam, sizeof fam, "%s", v);
        else if (!strncmp(line, "model\t", 6)) snprintf(mod, sizeof mod, "%s", v);
        else if (!strncmp(line, "flags", 5)) {
            avx2 = strstr(v, " avx2") != NULL;
            fma = strstr(v, " fma") != NULL;
            avx512 = strstr(v, " avx512f") != NULL;
            break;
        }
    }
    if (f) fclose(f);
    printf("cpu: %s (family %s model %s), %s%s%s\n", model, fam, mod, avx2 ? "AVX2" : "no AVX2", fma ? " + FMA" : "",
           avx512 ? ", AVX-512F" : ", no AVX-512");
}

#endif
