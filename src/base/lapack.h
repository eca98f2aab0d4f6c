/* vtdyn — LAPACK's and BLAS's Fortran entry points that vtdyn calls. The trailing size_t are the
 * hidden lengths of the character arguments, as gfortran passes them. BLAS is called through its
 * Fortran entry points, not CBLAS: the reference CBLAS writes process-wide variables
 * (RowMajorStrg, CBLAS_CallFromC) at every call, a data race between threads that call it (the
 * batches' threads); the Fortran routines keep no state. */
#ifndef VT_BASE_LAPACK_H
#define VT_BASE_LAPACK_H

#include <stddef.h>

void dgemv_(const char *trans, const int *m, const int *n, const double *alpha, const double *a, const int *lda,
            const double *x, const int *incx, const double *beta, double *y, const int *incy, size_t ltrans);
void dgemm_(const char *transa, const char *transb, const int *m, const int *n, const int *k, const double *alpha,
            const double *a, const int *lda, const double *b, const int *ldb, const double *beta, double *c,
            const int *ldc, size_t la, size_t lb);
void dtrsm_(const char *side, const char *uplo, const char *transa, const char *diag, const int *m, const int *n,
            const double *alpha, const double *a, const int *lda, double *b, const int *ldb, size_t l1, size_t l2,
            size_t l3, size_t l4);
void dtrsv_(const char *uplo, const char *trans, const char *diag, const int *n, const double *a, const int *lda,
            double *x, const int *incx, size_t l1, size_t l2, size_t l3);
void dsyrk_(const char *uplo, const char *trans, const int *n, const int *k, const double *alpha, const double *a,
            const int *lda, const double *beta, double *c, const int *ldc, size_t l1, size_t l2);
void dsymv_(const char *uplo, const int *n, const double *alpha, const double *a, const int *lda, const double *x,
            const int *incx, const double *beta, double *y, const int *incy, size_t l);

/* the BLAS calls by value, column-major, the options as LAPACK's letters ('N', 'T', 'L', ...) */
static inline void vt_dgemv(char trans, int m, int n, double alpha, const double *a, int lda, const double *x, int incx,
                            double beta, double *y, int incy)
{
    dgemv_(&trans, &m, &n, &alpha, a, &lda, x, &incx, &beta, y, &incy, 1);
}
static inline void vt_dgemm(char ta, char tb, int m, int n, int k, double alpha, const double *a, int lda,
                            const double *b, int ldb, double beta, double *c, int ldc)
{
    dgemm_(&ta, &tb, &m, &n, &k, &alpha, a, &lda, b, &ldb, &beta, c, &ldc, 1, 1);
}
static inline void vt_dtrsm(char side, char uplo, char ta, char diag, int m, int n, double alpha, const double *a,
                            int lda, double *b, int ldb)
{
    dtrsm_(&side, &uplo, &ta, &diag, &m, &n, &alpha, a, &lda, b, &ldb, 1, 1, 1, 1);
}
static inline void vt_dtrsv(char uplo, char trans, char diag, int n, const double *a, int lda, double *x, int incx)
{
    dtrsv_(&uplo, &trans, &diag, &n, a, &lda, x, &incx, 1, 1, 1);
}
static inline void vt_dsymv(char uplo, int n, double alpha, const double *a, int lda, const double *x, int incx,
                            double beta, double *y, int incy)
{
    dsymv_(&uplo, &n, &alpha, a, &lda, x, &incx, &beta, y, &incy, 1);
}
static inline void vt_dsyrk(char uplo, char trans, int n, int k, double alpha, const double *a, int lda, double beta,
                            double *c, int ldc)
{
    dsyrk_(&uplo, &trans, &n, &k, &alpha, a, &lda, &beta, c, &ldc, 1, 1);
}


/* the Goldfarb–Idnani QP (numeric/qp.c): G's Cholesky factor, the Givens rotations that update
 * the active constraints' QR factors, and the norms, dot products and sums of its steps */
void dpotrf_(const char *uplo, const int *n, double *a, const int *lda, int *info, size_t l);
void drot_(const int *n, double *x, const int *incx, double *y, const int *incy, const double *c, const double *s);
void dlartg_(const double *f, const double *g, double *c, double *s, double *r);
double dnrm2_(const int *n, const double *x, const int *incx);
double ddot_(const int *n, const double *x, const int *incx, const double *y, const int *incy);
void daxpy_(const int *n, const double *alpha, const double *x, const int *incx, double *y, const int *incy);

void dsyev_(const char *jobz, const char *uplo, const int *n, double *a, const int *lda,
            double *w, double *work, const int *lwork, int *info, size_t ljobz, size_t luplo);

/* tridiagonal solve with partial pivoting (the spline's second derivatives, functions.c) */
void dgtsv_(const int *n, const int *nrhs, double *dl, double *d, double *du, double *b, const int *ldb, int *info);

/* LAPACK routines of the solve (solve.c) */
void dsytrf_rk_(const char *uplo, const int *n, double *a, const int *lda, double *e, int *ipiv, double *work,
                const int *lwork, int *info, size_t luplo);
void dsytrs_3_(const char *uplo, const int *n, const int *nrhs, const double *a, const int *lda, const double *e,
               const int *ipiv, double *b, const int *ldb, int *info, size_t luplo);
void dsycon_3_(const char *uplo, const int *n, const double *a, const int *lda, const double *e, const int *ipiv,
               const double *anorm, double *rcond, double *work, int *iwork, int *info, size_t luplo);
double dlansy_(const char *norm, const char *uplo, const int *n, const double *a, const int *lda,
               double *work, size_t lnorm, size_t luplo);
void dgels_(const char *trans, const int *m, const int *n, const int *nrhs, double *a, const int *lda,
            double *b, const int *ldb, double *work, const int *lwork, int *info, size_t ltrans);
void dgelsd_(const int *m, const int *n, const int *nrhs, double *a, const int *lda, double *b, const int *ldb,
             double *s, const double *rcond, int *rank, double *work, const int *lwork, int *iwork, int *info);
void dtrtrs_(const char *uplo, const char *trans, const char *diag, const int *n, const int *nrhs, const double *a,
             const int *lda, double *b, const int *ldb, int *info, size_t l1, size_t l2, size_t l3);
void dpotf2_(const char *uplo, const int *n, double *a, const int *lda, int *info, size_t l);
void dpotrs_(const char *uplo, const int *n, const int *nrhs, const double *a, const int *lda, double *b,
             const int *ldb, int *info, size_t l);
void dpocon_(const char *uplo, const int *n, const double *a, const int *lda, const double *anorm, double *rcond,
             double *work, int *iwork, int *info, size_t l);
void dgeqp3_(const int *m, const int *n, double *a, const int *lda, int *jpvt, double *tau,
             double *work, const int *lwork, int *info);
void dgesvd_(const char *jobu, const char *jobvt, const int *m, const int *n, double *a, const int *lda, double *s,
             double *u, const int *ldu, double *vt, const int *ldvt, double *work, const int *lwork, int *info,
             size_t lu, size_t lvt);
void dgetf2_(const int *m, const int *n, double *a, const int *lda, int *ipiv, int *info);
void dgetrs_(const char *trans, const int *n, const int *nrhs, const double *a, const int *lda, const int *ipiv,
             double *b, const int *ldb, int *info, size_t ltrans);
void dgecon_(const char *norm, const int *n, const double *a, const int *lda, const double *anorm, double *rcond,
             double *work, int *iwork, int *info, size_t lnorm);
/* and of the maximal-coordinate route (maximal.c) */
void dgetrf_(const int *m, const int *n, double *a, const int *lda, int *ipiv, int *info);
void dgeequb_(const int *m, const int *n, const double *a, const int *lda, double *r, double *c, double *rowcnd,
              double *colcnd, double *amax, int *info);
void dlacn2_(const int *n, double *v, double *x, int *isgn, double *est, int *kase, int *isave);

#endif
