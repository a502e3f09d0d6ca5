#!/usr/bin/env python3
"""Compares two aalab report folders for identical results: every row's output hash and
metric values, every scene's reference statistics and cost counters, and the bytes of every
PNG image (references, outputs, heatmaps, edge masks). Timings are ignored.
Usage: compare_reports.py DIR_A DIR_B   (exit 0 when identical, 1 otherwise)."""
import json, os, sys, hashlib

def load(d):
    return json.load(open(os.path.join(d, "report.json")))

def strip_scene(s):
    s = dict(s)
    s.pop("bvh_build_ms", None)
    if "content" in s:
        s["content"] = {k: v for k, v in s["content"].items() if k != "load_ms"}
    s.pop("source", None)
    ref = dict(s.get("reference", {}))
    ref.pop("time_ms", None)
    s["reference"] = ref
    return s

def strip_row(r):
    r = dict(r)
    r.pop("timing", None)
    return r

def main():
    a, b = sys.argv[1], sys.argv[2]
    ra, rb = load(a), load(b)
    bad = 0
    if len(ra["rows"]) != len(rb["rows"]) or len(ra["scenes"]) != len(rb["scenes"]):
        print("different numbers of rows or scenes"); return 1
    for sa, sb in zip(ra["scenes"], rb["scenes"]):
        if strip_scene(sa) != strip_scene(sb):
            print("scene differs:", sa["name"]); bad += 1
    for xa, xb in zip(ra["rows"], rb["rows"]):
        if strip_row(xa) != strip_row(xb):
            print("row differs:", xa["scene"], xa["method"]); bad += 1
    n = 0
    for root, _, files in os.walk(os.path.join(a, "images")):
        for f in files:
            if not f.endswith(".png"):
                continue
            pa = os.path.join(root, f)
            pb = os.path.join(b, os.path.relpath(pa, a))
            n += 1
            if not os.path.exists(pb) or hashlib.sha256(open(pa, "rb").read()).digest() != hashlib.sha256(open(pb, "rb").read()).digest():
                print("image differs:", os.path.relpath(pa, a)); bad += 1
    print(f"compared {len(ra['rows'])} rows, {len(ra['scenes'])} scenes, {n} images: {'IDENTICAL' if bad == 0 else str(bad) + ' DIFFERENCES'}")
    return 0 if bad == 0 else 1

if __name__ == "__main__":
    sys.exit(main())
