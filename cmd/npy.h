/* The command's NumPy files (cmd/npy.c): the .npy header of a structured array of little-endian
 * float64 fields named as the CSV columns, shape (N,), C order (numpy.load gives the table:
 * arr['joint1_effort']), read and checked, and written (with room for the row count when it is
 * not known ahead, rewritten at the end). */
#ifndef VTDYN_CMD_NPY_H
#define VTDYN_CMD_NPY_H

#include <stdio.h>

/* the longest .npy header read, in bytes (the dict after the length field): a robot at the
 * library's 1000 bodies writes about 500 kB of field names; a longer one is refused unread */
#define NPY_MAX_HEADER (1024 * 1024)

/* reads the header of the .npy file f (path names it in the messages) and checks it: format 1.0,
 * 2.0 or 3.0, 'descr' a list of (name, '<f8') fields, 'fortran_order' False, 'shape' (N,), and,
 * when f is a regular file, its size the header and N rows of 8 bytes a field. The fields' names
 * (UTF-8, each malloc'd) into *names (malloc'd, *ncol of them), N into *nrow, the header's bytes
 * (the data's offset) into *offset; f is left at the data. 0, or 1 with the message printed (the
 * file named, and what was found: a plain array, big-endian or other fields, Fortran order,
 * another shape, a truncated file) and nothing to free */
int npy_read_header(FILE *f, const char *path, char ***names, int *ncol, long long *nrow, long long *offset);

/* the header of a .npy file of ncol '<f8' fields named names (UTF-8) and nrow rows into a new
 * buffer *out (malloc'd, *len bytes, a multiple of 64): format 1.0, or 2.0 when the dict passes
 * 65535 bytes, or 3.0 when a name is not ASCII. Padded with spaces to at least min_len bytes
 * (0: none), so that a header made with the largest row count (npy_max_header_len) can be
 * rewritten in place with the real one. 0, or 1 out of memory */
int npy_header(char **out, size_t *len, const char *const *names, int ncol, long long nrow, size_t min_len);
/* the length of the header for any row count (of up to 19 digits), for npy_header's min_len */
size_t npy_max_header_len(const char *const *names, int ncol);

#endif
