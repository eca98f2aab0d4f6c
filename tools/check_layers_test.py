#!/usr/bin/env python3
"""Self-test of tools/check_layers: it fails where it should.

Each case writes a small source tree into a temporary directory and runs check_layers on it
(--src, and its own folder order --layers: base < model < dense < analysis):
  clean          a layered tree, headers with inlines and macros calling down: passes;
  upward_include model/ includes a dense/ header (no cycle): fails on the upward edge only;
  inline_circle  a header-only base/scan.h whose static inline calls dense/solve.c, which
                 includes it: fails on the cycle (only the inline edge closes it) and the
                 upward edge; the same tree without that call passes;
  macro_circle   the same circle through a function-like macro;
  flat_circle    a flat tree (src/*.c + src/internal.h) whose internal.h inline calls
                 reactions.c: the cycle internal.h -> reactions.c -> internal.h, the folder
                 order not checked;
  outside        a file directly in src/ and a folder the order does not list: both fail;
  objects        (with a C compiler and nm) the tree compiled into objects named as meson
                 names them, in an archive: an upward call that only nm sees fails.
Usage: check_layers_test.py [path/to/check_layers]   (default: beside this script)
"""

import os
import shutil
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
TOOL = os.path.join(HERE, 'check_layers')
ORDER = 'base\nmodel\ndense\nanalysis\n'

CLEAN = {
    'base/arena.h': '''#ifndef ARENA_H
#define ARENA_H
void *vt_take(int n);
/* an inline calling its own file: no edge */
static inline void *vt_take_small(int n) { return n < 16 ? vt_take(n) : 0; }
#define VT_TAKE(n) vt_take_small(n)
#endif
''',
    'base/arena.c': '''#include "base/arena.h"
static char pool[64];
void *vt_take(int n) { (void)n; return pool; }
''',
    'base/vec3.h': '''#ifndef VEC3_H
#define VEC3_H
static inline double vt_dot3(const double *a, const double *b)
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
#endif
''',
    'model/model.h': '''#ifndef MODEL_H
#define MODEL_H
#include "base/arena.h"
int vt_model_rows(void);
/* an inline calling down: an edge model -> base, allowed */
static inline void *vt_model_scratch(void) { return VT_TAKE(vt_model_rows()); }
#endif
''',
    'model/model.c': '''#include "model/model.h"
int vt_model_rows(void) { return vt_take(1) ? 3 : 0; }
''',
    'dense/lu.h': '''#ifndef LU_H
#define LU_H
int vt_lu(double *a, int n);
#endif
''',
    'dense/lu.c': '''#include "dense/lu.h"
#include "base/vec3.h"
int vt_lu(double *a, int n) { return n > 0 && vt_dot3(a, a) > 0.0; }
''',
    'dense/solve.h': '''#ifndef SOLVE_H
#define SOLVE_H
int vt_solve_check(int x);
int vt_solve(double *a);
#endif
''',
    'dense/solve.c': '''#include "dense/solve.h"
#include "dense/lu.h"
#include "model/model.h"
#include "base/scan.h"
/* a comment naming vt_analysis_run ( and #include "analysis/run.h" is no edge */
static const char *msg = "vt_analysis_run(";
int vt_solve_check(int x) { return x > 0 && msg[0]; }
int vt_solve(double *a)
{
    if (!vt_scan_ok(a)) return -1;
    return vt_lu(a, vt_model_rows());
}
''',
    'base/scan.h': '''#ifndef SCAN_H
#define SCAN_H
static inline int vt_scan_ok(const double *a)
{
    return a[0] == a[0];
}
#endif
''',
    'analysis/run.h': '''#ifndef RUN_H
#define RUN_H
int vt_analysis_run(double *a);
#endif
''',
    'analysis/run.c': '''#include "analysis/run.h"
#include "dense/solve.h"
int vt_analysis_run(double *a) { return vt_solve(a); }
''',
}

FLAT = {
    'internal.h': '''#ifndef INTERNAL_H
#define INTERNAL_H
void *vt_scratch_refuse(int n);
int vt_reactions_nonunique(int n);
static inline int vt_reactions_unique(int n)
{
    return n > 0 ? vt_reactions_nonunique(n) : 0;
}
#endif
''',
    'arena.c': '''#include "internal.h"
void *vt_scratch_refuse(int n) { (void)n; return 0; }
''',
    'reactions.c': '''#include "internal.h"
int vt_reactions_nonunique(int n) { return vt_scratch_refuse(n) != 0; }
''',
}


def with_changes(base, **changes):
    tree = dict(base)
    for k, v in changes.items():
        path = k.replace('__', '/').replace('_DOT_', '.')
        if v is None:
            tree.pop(path, None)
        else:
            tree[path] = v
    return tree


def find_cc():
    for name in (os.environ.get('CC', '').split() or [None])[:1] + ['cc', 'gcc', 'clang']:
        if name and shutil.which(name):
            return name
    return None


class Case(unittest.TestCase):

    def setUp(self):
        self.tmp = tempfile.mkdtemp(prefix='check_layers_test.')

    def tearDown(self):
        shutil.rmtree(self.tmp, ignore_errors=True)

    def write(self, tree):
        src = os.path.join(self.tmp, 'src')
        for rel, text in tree.items():
            path = os.path.join(src, rel)
            os.makedirs(os.path.dirname(path), exist_ok=True)
            with open(path, 'w', encoding='utf-8') as f:
                f.write(text)
        order = os.path.join(self.tmp, 'layers.txt')
        with open(order, 'w', encoding='utf-8') as f:
            f.write(ORDER)
        return src, order

    def run_tool(self, tree, *inputs, layers=None):
        src, order = self.write(tree)
        cmd = [sys.executable, TOOL, '--src', src, '--layers', layers or order] + list(inputs)
        res = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                             universal_newlines=True)
        self.output = res.stdout
        return res.returncode, res.stdout

    def assertIn(self, member, container, msg=None):
        super().assertIn(member, container, msg or '\n--- check_layers printed:\n' + self.output)

    def assertNotIn(self, member, container, msg=None):
        super().assertNotIn(member, container, msg or '\n--- check_layers printed:\n' + self.output)

    def assertRc(self, rc, want):
        self.assertEqual(rc, want, 'exit status %d, wanted %d\n--- check_layers printed:\n%s'
                         % (rc, want, self.output))

    # (c) a clean tree passes
    def test_clean(self):
        rc, out = self.run_tool(CLEAN)
        self.assertRc(rc, 0)
        self.assertEqual(out.rstrip().splitlines()[-2], 'no cycles, no upward edges')
        # the layer order shows each file's folder and level
        self.assertRegex(out, r'\n\s+\d+\s+2 dense/\s+dense/solve\.c\s+-> ')
        self.assertRegex(out, r'\n\s+\d+\s+0 base/\s+base/scan\.h\s+-> \(nothing of ours\)')

    # (a) an upward include, no cycle: the folder order alone catches it
    def test_upward_include(self):
        tree = with_changes(CLEAN, model__model_DOT_c='#include "model/model.h"\n'
                            '#include "dense/lu.h"\nint vt_model_rows(void) { return 3; }\n')
        rc, out = self.run_tool(tree)
        self.assertRc(rc, 1)
        self.assertIn('model/model.c [1 model/] -> dense/lu.c [2 dense/]: include: dense/lu.h', out)
        self.assertIn('1 upward edge', out)
        self.assertNotIn('cycle', out.split('\n\n')[-1])

    # (b) an inline in a header calling up into a file that includes it
    def test_inline_circle(self):
        scan = CLEAN['base/scan.h'].replace('return a[0] == a[0];',
                                            'return vt_solve_check(a[0] == a[0]);')
        rc, out = self.run_tool(with_changes(CLEAN, base__scan_DOT_h=scan))
        self.assertRc(rc, 1)
        self.assertIn('cycle A: base/scan.h, dense/solve.c', out)
        self.assertIn('base/scan.h -> dense/solve.c [inline: vt_scan_ok calls vt_solve_check] '
                      '-> base/scan.h [include: base/scan.h]', out)
        self.assertRegex(out, r'cycle A: .*; needs the [a-z ]*inline edges\)')
        self.assertIn('base/scan.h [0 base/] -> dense/solve.c [2 dense/]: inline: '
                      'vt_scan_ok calls vt_solve_check', out)
        # without the inline's call the same includes are clean: only the inline shows it
        rc, _ = self.run_tool(CLEAN)
        self.assertRc(rc, 0)

    def test_macro_circle(self):
        scan = CLEAN['base/scan.h'].replace('#endif', '#define VT_SCAN(x) (vt_solve_check(x) > 0)\n'
                                            '#endif')
        rc, out = self.run_tool(with_changes(CLEAN, base__scan_DOT_h=scan))
        self.assertRc(rc, 1)
        self.assertIn('dense/solve.c [inline: VT_SCAN calls vt_solve_check]', out)
        self.assertIn('-> base/scan.h [include: base/scan.h]', out)

    # (b) in the flat tree of today: internal.h is its own node
    def test_flat_circle(self):
        rc, out = self.run_tool(FLAT)
        self.assertRc(rc, 1)
        self.assertIn('internal.h -> reactions.c [inline: vt_reactions_unique calls '
                      'vt_reactions_nonunique] -> internal.h [include: internal.h]', out)
        self.assertIn('no folders under src/: the folder order is not checked', out)
        self.assertNotIn('upward', out)
        # a .c and its own .h are one node: with internal.h -> reactions.h the circle is gone
        flat = {'reactions.h': FLAT['internal.h'], 'arena.c': '#include "reactions.h"\n',
                'reactions.c': '#include "reactions.h"\nint vt_reactions_nonunique(int n) '
                               '{ return n; }\n'}
        rc, out = self.run_tool(flat)
        self.assertRc(rc, 0)

    # files outside the folders once folders exist, and a folder the order does not list
    def test_outside(self):
        tree = with_changes(CLEAN, stray_DOT_c='int vt_stray(void) { return 0; }\n',
                            extra__x_DOT_c='int vt_extra(void) { return 0; }\n')
        rc, out = self.run_tool(tree)
        self.assertRc(rc, 1)
        self.assertIn('1 file directly in src/', out)
        self.assertIn('  stray.c', out)
        self.assertIn('folder extra/ is not in the order', out)

    # the project's order file parses (its folders need not be the fixture's)
    def test_project_order_file(self):
        rc, out = self.run_tool(CLEAN, layers=os.path.join(HERE, 'layers.txt'))
        self.assertIn(rc, (0, 1))
        self.assertIn('folder order, bottom first', out)

    # calls from the objects: an upward call that no include shows, read with nm from an
    # archive whose members are named as meson names them (src_model_model.c.o)
    def test_objects(self):
        cc, nm = find_cc(), os.environ.get('NM', 'nm')
        if cc is None or shutil.which(nm) is None:
            self.skipTest('no C compiler or nm')
        tree = with_changes(CLEAN, base__arena_DOT_c='#include "base/arena.h"\n'
                            'int vt_model_rows(void);\nstatic char pool[64];\n'
                            'void *vt_take(int n) { return n > vt_model_rows() ? 0 : pool; }\n')
        src, _ = self.write(tree)
        objs = []
        for rel in sorted(tree):
            if rel.endswith('.c'):
                obj = os.path.join(self.tmp, 'src_' + rel.replace('/', '_') + '.o')
                res = subprocess.run([cc, '-c', '-I', src, os.path.join(src, rel), '-o', obj],
                                     stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                                     universal_newlines=True)
                if res.returncode != 0:
                    self.skipTest('%s cannot compile: %s' % (cc, res.stdout))
                objs.append(obj)
        inputs = objs
        if shutil.which('ar'):
            lib = os.path.join(self.tmp, 'libfixture.a')
            subprocess.run(['ar', 'rcs', lib] + objs, check=True)
            inputs = [lib]
        rc, out = self.run_tool(tree, *inputs)
        self.assertRc(rc, 1)
        self.assertIn('base/arena.c [0 base/] -> model/model.c [1 model/]: call: vt_model_rows', out)
        self.assertIn('cycle A: base/arena.c, model/model.c', out)
        self.assertNotIn('has no source', out)


if __name__ == '__main__':
    if len(sys.argv) > 1 and not sys.argv[1].startswith('-'):
        TOOL = os.path.abspath(sys.argv.pop(1))
    unittest.main(verbosity=2)
