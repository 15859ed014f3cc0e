#!/usr/bin/python3
# SPDX-License-Identifier: MIT
"""Rewrites the checksums of a smi-lock.json as smi-lua computes them (vm/lockfile.cpp), so a
test can hand smi-lua a lockfile forged with valid checksums: the checksums catch accidents,
not attacks, and every field must still be checked as data.

usage: lockfile_forge.py FILE   (reads the JSON in FILE, writes it back with fresh checksums)"""
import hashlib
import json
import sys


def fields(*parts):
    h = hashlib.sha256()
    for p in parts:
        b = p.encode()
        h.update(b)
        h.update(b"\x1f%d\x1e" % len(b))
    return "sha256:" + h.hexdigest()


def folder_hash(files):
    parts = ["smi-lib-folder-v1"]
    for rel in sorted(files):
        parts += [rel, files[rel]]
    return fields(*parts)


def entry_checksum(e):
    parts = ["smi-lock-entry-v1", e["name"], e["version"], e["source"], e.get("ref", ""), e.get("commit", ""),
             str(len(e.get("requires", [])))] + e.get("requires", [])
    parts += [e["hash"], str(len(e["files"]))]
    for rel in sorted(e["files"]):
        parts += [rel, e["files"][rel]]
    return fields(*parts)


doc = json.load(open(sys.argv[1]))
doc["libraries"].sort(key=lambda e: e["name"])
for e in doc["libraries"]:
    e["hash"] = folder_hash(e["files"])
    e["checksum"] = entry_checksum(e)
doc["checksum"] = fields("smi-lock-v1", doc["tree"], *[e["checksum"] for e in doc["libraries"]])
json.dump(doc, open(sys.argv[1], "w"), indent=2)
