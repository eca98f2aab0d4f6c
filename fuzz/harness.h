/* fuzz_model's bytes, its reports of a broken promise and the checks of every call (harness.c) */
#ifndef FUZZ_HARNESS_H
#define FUZZ_HARNESS_H

#include <setjmp.h>
#include <stddef.h>
#include <stdint.h>

#include "vtdyn.h"

/* the input's bytes not yet read */
typedef struct {
    const uint8_t *p;
    size_t n;
} bytes;

/* the next byte (0 once they are used up) */
unsigned byte(bytes *b);
/* a number from one byte, or more for the escapes (harness.c) */
double num(bytes *b);

/* what fail() describes besides its reason: the model and the two results being compared */
typedef struct {
    const vt_model *m;
    const vt_data *a, *b;
} fuzz_context;
extern fuzz_context context;
/* where fail() jumps for a reason FUZZ_EXCLUDE sets aside (set by LLVMFuzzerTestOneInput) */
extern jmp_buf skip_input;

/* the context on stderr: the model, and the two results being compared */
void describe(void);
/* 1 when FUZZ_EXCLUDE ("text;text;...") names a part of reason: a known bug set aside */
int excluded(const char *reason);
/* a broken promise: its reason and the context on stderr, then abort (or, excluded, a jump to
 * skip_input) */
void fail(const char *fmt, ...) __attribute__((format(printf, 1, 2)));

double maxabs(const double *a, int n);
/* a[0..n) finite after `call` returned VT_OK, or fail naming `field` */
void finite(const double *a, int n, const char *call, const char *field);
/* the caller's inputs of a data (q, q̇, xfrc, qfrc, then time: input_count + 1 doubles) */
size_t input_count(const vt_model *m);
void save_inputs(const vt_model *m, const vt_data *d, double *buf);
/* a failed call: a message, and the inputs bit for bit as save_inputs kept them before */
void failed_call(const vt_model *m, const vt_data *d, const double *before, vt_status st, const char *call);
/* every output array the stages and the instants fill */
void data_finite(const vt_model *m, const vt_data *d, const char *call);
/* a[0..n) of unit length, what names it and k its index */
void unit(const double *a, int n, const char *what, int k);
/* what the builder accepted satisfies the checks it documents */
void model_check(const vt_model *m);
/* every array of an analysis's filled rows finite after `call` returned VT_OK */
void trajectory_finite(const vt_model *m, const vt_trajectory *tr, const char *call);

#endif
