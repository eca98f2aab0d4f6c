#!/usr/bin/env python3
"""The shared library exports exactly the public API: every function declared in the public
headers carries VT_API (vtdyn/export.h), and the library's exported symbols (nm -D
--defined-only) are exactly those functions, no internal one. The headers are preprocessed
with this build's configuration (vtdyn/version.h: the URDF and SUNDIALS functions only where
built), VT_API expanding to the visibility attribute, so a declaration is found whatever its
line breaks. Arguments: the C compiler (its command words), -- , the library, include
directories."""
import re
import subprocess
import sys

sep = sys.argv.index('--')
cc, lib, incs = sys.argv[1:sep], sys.argv[sep + 1], sys.argv[sep + 2:]
src = '#include "vtdyn.h"\n'
pre = subprocess.run(cc + ['-E', '-P', '-x', 'c'] + ['-I' + i for i in incs] + ['-'],
                     input=src, capture_output=True, text=True, check=True).stdout
flat = ' '.join(pre.split())
# after preprocessing, "vt_name(" only occurs in declarations (a callback typedef reads
# "(*vt_name)(", which this leaves out)
declared = set(re.findall(r'\b(vt_\w+)\s*\(', flat))
marked = set(re.findall(r'__attribute__\s*\(\(\s*visibility\s*\(\s*"default"\s*\)\s*\)\)\s*[^;(]*?\b(vt_\w+)\s*\(',
                        flat))
nm = subprocess.run(['nm', '-D', '--defined-only', lib], capture_output=True, text=True, check=True).stdout
# names starting with an underscore are the implementation's (a sanitizer's, the toolchain's)
exported = {line.split()[-1].split('@')[0] for line in nm.splitlines()
            if len(line.split()) >= 3 and line.split()[1] in 'TtDdBbRrWiV'} - {''}
exported = {name for name in exported if not name.startswith('_')}
ok = True
if not declared:
    print('no declarations found in the preprocessed headers')
    ok = False
for name in sorted(declared - marked):
    print(f'declared without VT_API (so not exported): {name}')
    ok = False
for name in sorted(exported - marked):
    print(f'exported but not public (not VT_API in the headers): {name}')
    ok = False
for name in sorted(marked - exported):
    print(f'public (VT_API) but not exported by {lib}: {name}')
    ok = False
print(f'{len(declared)} functions declared, {len(marked)} VT_API, {len(exported)} exported')
sys.exit(0 if ok else 1)
