#!/usr/bin/env python3
"""Rewrites every quoted #include of a project header to its prefixed, unambiguous form.

    kernels/<area>/x.hpp   host/kernels/...   (include root: host/)
    luax/, vm/, sandbox/, app/, repl/, cli/   host/...          (include root: host/)
    bindings/...           bindings/...       (include root: the top level)

Before, host/kernels, host/ and bindings/ were all include roots, so "stats/kde.hpp" and
"stats/args.hpp" named files in two trees. Each include is resolved the way the compiler
resolved it under the old roots (the including file's folder first, then the roots in the order
its target saw them) and rewritten from where the header really is. Headers moved by
move_runtime.sh are followed through MOVED. Files outside host/ and bindings/ (tests, bench,
scripts) keep their own local includes ("fe_test_util.hpp"); only project headers change.

Each run of consecutive quoted includes is then sorted by path (the file's own header first).
Idempotent: a prefixed include resolves to the same file and is written back unchanged. Run it
from anywhere: python3 tools/migrate/prefix_includes.py [repo root]. Prints each file changed
and any include it cannot resolve (left as is) or finds ambiguous (first match taken).
"""
import os
import re
import sys

ROOT = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(__file__), "..", ".."))
EXTS = (".cpp", ".hpp", ".h", ".inc", ".cc", ".hh")
SKIP_DIRS = {".git", "build", "tmp", "tools"}
INCLUDE = re.compile(r'^(\s*#\s*include\s*)"([^"]+)"(.*)$')

# Headers that moved: old repository path -> new repository path (see move_runtime.sh).
MOVED = {
    "host/vm/runtime.hpp": "host/app/runtime.hpp",
    "host/vm/docs.hpp": "host/app/docs.hpp",
}
UNMOVED = {new: old for old, new in MOVED.items()}  # a rewritten include before the move ran


def old_roots(rel_file):
    """The include roots the file's target had before the change, in the compiler's order."""
    if rel_file.startswith("bindings/"):
        return ["bindings", "host/kernels", "host", ""]
    if rel_file.startswith("host/kernels/") or rel_file.startswith("tests/kernels/"):
        return ["host/kernels", "host", "bindings", ""]
    return ["host", "bindings", "host/kernels", ""]


def exists(rel):
    return any(os.path.isfile(os.path.join(ROOT, p)) for p in (rel, MOVED.get(rel, rel), UNMOVED.get(rel, rel)))


def prefixed(rel_target):
    """The include text for a header at repository path rel_target, or None if not a project header."""
    rel_target = MOVED.get(rel_target, rel_target)
    if rel_target.startswith("host/"):
        return rel_target[len("host/"):]
    if rel_target.startswith("bindings/"):
        return rel_target
    return None


def resolve(rel_file, inc):
    """Repository path of the header `inc` included from rel_file, or None."""
    here = os.path.dirname(rel_file)
    local = os.path.normpath(os.path.join(here, inc))
    if exists(local):
        return local, []
    hits = []
    for r in old_roots(rel_file):
        cand = os.path.normpath(os.path.join(r, inc)) if r else os.path.normpath(inc)
        if exists(cand) and MOVED.get(cand, cand) not in [MOVED.get(h, h) for h in hits]:
            hits.append(cand)
    if not hits:
        return None, []
    return hits[0], hits[1:]


def rewrite(rel_file):
    path = os.path.join(ROOT, rel_file)
    with open(path, encoding="utf-8") as f:
        lines = f.read().split("\n")
    changed = False
    for i, line in enumerate(lines):
        m = INCLUDE.match(line)
        if not m:
            continue
        inc = m.group(2)
        target, others = resolve(rel_file, inc)
        if target is None:
            if not inc.endswith(".inc") and "/" in inc:
                print(f"{rel_file}:{i + 1}: cannot resolve \"{inc}\" (left as is)", file=sys.stderr)
            continue
        if others:
            print(f"{rel_file}:{i + 1}: \"{inc}\" is ambiguous ({target} and {', '.join(others)}); took {target}",
                  file=sys.stderr)
        new = prefixed(target)
        in_project = rel_file.startswith("host/") or rel_file.startswith("bindings/")
        # A test's or solver's own header beside it stays local; a project header gets its prefix.
        if new is None or (not in_project and os.path.dirname(target) == os.path.dirname(rel_file)):
            continue
        if new != inc:
            lines[i] = f'{m.group(1)}"{new}"{m.group(3)}'
            changed = True
    if in_scope(rel_file) and sort_blocks(rel_file, lines):
        changed = True
    if changed:
        with open(path, "w", encoding="utf-8") as f:
            f.write("\n".join(lines))
        print(rel_file)


def in_scope(rel_file):
    return rel_file.startswith(("host/", "bindings/", "tests/", "bench/"))


def sort_blocks(rel_file, lines):
    """Sorts each run of consecutive quoted includes by path (prefixing reorders the layers, so
    "bindings/...", "kernels/...", "luax/..." end up interleaved otherwise). A .cpp file's own
    header stays first in its run. Returns True if anything moved."""
    own = os.path.splitext(os.path.basename(rel_file))[0] + ".hpp"
    moved = False
    i = 0
    while i < len(lines):
        if not INCLUDE.match(lines[i]):
            i += 1
            continue
        j = i
        while j < len(lines) and INCLUDE.match(lines[j]):
            j += 1
        block = lines[i:j]
        head = []
        if rel_file.endswith(".cpp") and os.path.basename(INCLUDE.match(block[0]).group(2)) == own:
            head, block = block[:1], block[1:]
        ordered = head + sorted(block, key=lambda l: INCLUDE.match(l).group(2))
        if ordered != lines[i:j]:
            lines[i:j] = ordered
            moved = True
        i = j
    return moved


def main():
    for dirpath, dirnames, filenames in os.walk(ROOT):
        dirnames[:] = sorted(d for d in dirnames if d not in SKIP_DIRS and not d.startswith("build"))
        for name in sorted(filenames):
            if name.endswith(EXTS):
                rewrite(os.path.relpath(os.path.join(dirpath, name), ROOT))


if __name__ == "__main__":
    main()
