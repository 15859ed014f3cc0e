# SPDX-License-Identifier: MIT
"""Compares two results.json of the same study run in two output folders: every number and text,
except timings, run counts and the output folder itself in paths. Prints "identical" or the count
and the first differences. usage: soak_compare.py REF_OUT_DIR OTHER_OUT_DIR"""
import json
import re
import sys

ref_dir, other_dir = sys.argv[1].rstrip("/"), sys.argv[2].rstrip("/")
SKIP = re.compile(r"seconds|clock|wall|eta|launched|reused|provenance|timings")
# The refinement's "computational cost" criterion (the third) is the measured wall time of a run,
# so its magnitude, its standardized value and the overall ratings differ between any two runs.
SKIP_PATH = re.compile(r"^/steps/refinement/result/(candidates\[\d+\]/(magnitudes|standardized)\[2\]|overall)")


def walk(a, b, path, out):
    if SKIP_PATH.search(path):
        return
    if isinstance(a, dict) and isinstance(b, dict):
        for k in sorted(set(a) | set(b)):
            if SKIP.search(k):
                continue
            if k not in a or k not in b:
                out.append(f"{path}/{k} (missing on one side)")
                continue
            walk(a[k], b[k], f"{path}/{k}", out)
    elif isinstance(a, list) and isinstance(b, list):
        if len(a) != len(b):
            out.append(f"{path} (length {len(a)} != {len(b)})")
            return
        for i, (x, y) in enumerate(zip(a, b)):
            walk(x, y, f"{path}[{i}]", out)
    elif isinstance(a, str) and isinstance(b, str):
        if a.replace(ref_dir, "<out>") != b.replace(other_dir, "<out>"):
            out.append(f"{path}: {a!r} != {b!r}")
    elif a != b:
        out.append(f"{path}: {a!r} != {b!r}")


diffs = []
walk(json.load(open(ref_dir + "/results.json")), json.load(open(other_dir + "/results.json")), "", diffs)
print("identical" if not diffs else f"{len(diffs)} differences, first: " + "; ".join(diffs[:3]))
