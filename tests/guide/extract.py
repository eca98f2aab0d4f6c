#!/usr/bin/env python3
"""Compiles every C snippet of a Markdown guide against the in-tree headers and library.

Usage: extract.py GUIDE --out DIR --lib LIBVTDYN --include DIR [--include DIR ...]
                  [--sundials 0|1] [--urdf 0|1] [--cflag FLAG ...]
The compiler is $CC (default "cc"; it may hold several words, e.g. "ccache cc").

Every ```c block of GUIDE is a snippet, by these conventions:
  - a block that defines main() is a complete program: it is compiled, linked and run, and
    must exit with status 0 (a program checks its numbers and returns nonzero when wrong);
  - a block whose first line starts with "// fragment" is compiled and linked, not run: it is
    wrapped in the body of a function
        int guide_fragment(vt_builder *b, vt_model *m, vt_data *d, vt_trajectory *tr)
    after #include <math.h>, <stdio.h>, <stdlib.h>, <string.h> and <vtdyn.h>, so that it may
    use those four names (unused ones are not warned about) and `return 0;` is appended;
  - a block whose first line says "needs SUNDIALS" is skipped in a build without SUNDIALS
    (--sundials 0), where vt_dynamic_analysis() and the forward check do not exist;
  - a block whose first line says "needs URDF" is skipped in a build without libxml2
    (--urdf 0), where vt_urdf_builder() does not exist;
  - any other ```c block is an error, so that no snippet goes untested.
Programs are compiled with -std=c11 -Wall -Wextra -Werror -pedantic; compiler messages point at
the guide's own lines (#line). Sources and executables are left in DIR for inspection.
Prints one line per snippet and exits 1 if any failed (0 if all passed or were skipped).
"""
import argparse
import os
import re
import shlex
import subprocess
import sys

FRAGMENT_PRELUDE = """#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <vtdyn.h>
int guide_fragment(vt_builder *b, vt_model *m, vt_data *d, vt_trajectory *tr);
int guide_fragment(vt_builder *b, vt_model *m, vt_data *d, vt_trajectory *tr)
{
    (void)b; (void)m; (void)d; (void)tr;
"""
FRAGMENT_EPILOGUE = """
    return 0;
}
int main(void) { return 0; }
"""


def snippets(path):
    """(line of the first code line, code) of every ```c block."""
    out, code, start = [], None, 0
    with open(path, encoding="utf-8") as f:
        for n, line in enumerate(f, 1):
            fence = line.strip()
            if code is None:
                if fence == "```c":
                    code, start = [], n + 1
            elif fence == "```":
                out.append((start, "".join(code)))
                code = None
            else:
                code.append(line)
    if code is not None:
        sys.exit(f"{path}:{start - 1}: unterminated ```c block")
    return out


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("guide")
    ap.add_argument("--out", required=True)
    ap.add_argument("--lib", required=True)
    ap.add_argument("--include", action="append", default=[])
    ap.add_argument("--sundials", default="1")
    ap.add_argument("--urdf", default="1")
    ap.add_argument("--cflag", action="append", default=[])
    a = ap.parse_args()
    cc = shlex.split(os.environ.get("CC", "") or "cc")
    os.makedirs(a.out, exist_ok=True)
    libdir = os.path.dirname(os.path.abspath(a.lib))
    blocks = snippets(a.guide)
    if not blocks:
        print(f"{a.guide}: no ```c blocks")
        return 1
    failed = 0
    for k, (line, code) in enumerate(blocks, 1):
        where = f"{a.guide}:{line}"
        first = code.lstrip().split("\n", 1)[0]
        fragment = first.startswith("// fragment")
        program = re.search(r"\bint\s+main\s*\(", code) is not None
        if not fragment and not program:
            print(f"not ok {k} - {where}: neither a program (main) nor marked '// fragment'")
            failed += 1
            continue
        if "needs SUNDIALS" in first and a.sundials != "1":
            print(f"ok {k} - {where} # SKIP needs SUNDIALS")
            continue
        if "needs URDF" in first and a.urdf != "1":
            print(f"ok {k} - {where} # SKIP needs URDF")
            continue
        src = os.path.join(a.out, f"snippet{k:02d}.c")
        exe = os.path.join(a.out, f"snippet{k:02d}")
        body = f'#line {line} "{a.guide}"\n{code}'
        with open(src, "w", encoding="utf-8") as f:
            f.write(FRAGMENT_PRELUDE + body + FRAGMENT_EPILOGUE if fragment else body)
        flags = ["-std=c11", "-Wall", "-Wextra", "-Werror", "-pedantic"]
        if fragment:
            flags += ["-Wno-unused-variable", "-Wno-unused-but-set-variable"]
        flags += [f"-I{d}" for d in a.include] + a.cflag
        cmd = cc + flags + [src, "-o", exe, a.lib, f"-Wl,-rpath,{libdir}", "-lm"]
        r = subprocess.run(cmd, capture_output=True, text=True)
        if r.returncode != 0:
            print(f"not ok {k} - {where}: does not compile\n  {shlex.join(cmd)}\n{r.stdout}{r.stderr}")
            failed += 1
            continue
        if fragment:
            print(f"ok {k} - {where} (fragment, compiled)")
            continue
        try:
            r = subprocess.run([exe], capture_output=True, text=True, timeout=300)
        except subprocess.TimeoutExpired:
            print(f"not ok {k} - {where}: timed out")
            failed += 1
            continue
        out = "".join("  | " + s + "\n" for s in (r.stdout + r.stderr).splitlines())
        if r.returncode != 0:
            print(f"not ok {k} - {where}: exit status {r.returncode}\n{out}", end="")
            failed += 1
        else:
            print(f"ok {k} - {where} (program, ran)\n{out}", end="")
    print(f"{len(blocks) - failed} of {len(blocks)} snippets passed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
