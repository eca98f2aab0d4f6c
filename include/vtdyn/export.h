/* vtdyn — VT_API marks the library's public functions. The library is built with hidden
 * symbol visibility (GCC and Clang), so the shared library exports exactly the functions
 * declared with VT_API in the public headers, and none of its internal ones (tests/exports.py
 * checks both). Harmless in a static library; empty with compilers without the attribute. */
#ifndef VTDYN_EXPORT_H
#define VTDYN_EXPORT_H

#if defined(__GNUC__) || defined(__clang__)
#define VT_API __attribute__((visibility("default")))
#else
#define VT_API
#endif

#endif
