#!/usr/bin/env python3
"""check_make_order.py [TOP] - no rule names a variable that a later fragment defines.

make expands a rule's targets and prerequisites when it reads the rule; the
fragments mk/*.mk are read in file-name order.  A variable set in a later
fragment is therefore empty in an earlier fragment's rule, and the rule
silently loses a prerequisite (the demo-experiments rule once had no tdc-sim
prerequisite that way, so `make demo` in a fresh clone failed).  Names that
several fragments use belong in the Makefile, before the fragments.

Reads the Makefile and the fragments in make's order and reports every rule
line (not a recipe, not a variable assignment) that names $(VAR) where VAR is
first assigned, or appended to (+=), after that line: the rule would see
none or only part of the list.  $$(VAR) (second expansion) is fine.
Exit 0 when there is none, 1 otherwise.
"""
import glob
import os
import re
import sys

ASSIGN = re.compile(r'^\s*(?:export\s+|override\s+)?([A-Za-z_][A-Za-z0-9_]*)\s*(?:\?=|:=|::=|\+=|=)')
REF = re.compile(r'(?<!\$)\$\(([A-Za-z_][A-Za-z0-9_]*)\)')
COND = re.compile(r'^\s*(ifeq|ifneq|ifdef|ifndef|else|endif|define|endef|include|-include|\$\((eval|info|error|warning) )')


def lines_in_make_order(top):
    main = open(os.path.join(top, 'Makefile')).read().split('\n')
    at = next(i for i, l in enumerate(main) if l.startswith('include $(sort $(wildcard mk/*.mk))'))
    seq = [('Makefile', i + 1, l) for i, l in enumerate(main[:at])]
    for f in sorted(glob.glob(os.path.join(top, 'mk', '*.mk'))):
        seq += [(os.path.relpath(f, top), i + 1, l) for i, l in enumerate(open(f).read().split('\n'))]
    seq += [('Makefile', at + i + 2, l) for i, l in enumerate(main[at + 1:])]
    return seq


def main():
    top = sys.argv[1] if len(sys.argv) > 1 else '.'
    seq = lines_in_make_order(top)
    first = {}
    last_append = {}
    for pos, (f, n, l) in enumerate(seq):
        m = ASSIGN.match(l)
        if m and not l.startswith('\t'):
            first.setdefault(m.group(1), (pos, f, n))
            if '+=' in l.split('#')[0]:
                last_append[m.group(1)] = (pos, f, n)
    bad = 0
    # a recursive (=) assignment, global or target-specific, that names itself
    # loops when expanded (make stops: "Recursive variable ... references itself")
    selfref = re.compile(r'(?:^|:)\s*(?:export\s+|override\s+)?([A-Za-z_][A-Za-z0-9_]*)\s*=(?!=)(.*)$')
    for f, n, l in seq:
        if l.startswith('\t') or l.lstrip().startswith('#'):
            continue
        m = selfref.search(l)
        if m and not re.search(r'[:+?!]$', l[:m.end(1)].rstrip() + l[m.end(1):].split('=')[0].strip()) \
                and '$(%s)' % m.group(1) in m.group(2):
            print(f'{f}:{n}: recursive variable {m.group(1)} names itself (use := ): {l.strip()[:90]}')
            bad = 1
    for pos, (f, n, l) in enumerate(seq):
        if l.startswith('\t') or l.lstrip().startswith('#') or ':' not in l or ASSIGN.match(l) or COND.match(l):
            continue
        for var in REF.findall(l):
            if var in first and first[var][0] > pos:
                print(f'{f}:{n}: rule names $({var}), first set at {first[var][1]}:{first[var][2]} '
                      f'(read later: empty here): {l.strip()[:90]}')
                bad = 1
            elif var in last_append and last_append[var][0] > pos:
                print(f'{f}:{n}: rule names $({var}), appended to later at {last_append[var][1]}:'
                      f'{last_append[var][2]} (this rule sees part of the list): {l.strip()[:90]}')
                bad = 1
    if not bad:
        print(f'check_make_order: {len(seq)} lines of the Makefile and mk/*.mk: no rule names a variable set later')
    return bad


if __name__ == '__main__':
    sys.exit(main())
