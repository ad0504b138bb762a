#!/usr/bin/env python3
# Mean ΔE of each frame a `capture DIR` script action saved against `tspplay render` of its step
# and view at full quality (docs/results.md, "No popping"). Usage:
#   bench/popping_frames.py DIR WxH FILE.tsp [TSPPLAY]   (under xvfb-run: render needs GL)
import json, os, subprocess, sys

d, size, tsp = sys.argv[1], sys.argv[2], sys.argv[3]
T = sys.argv[4] if len(sys.argv) > 4 else "build/tspplay"
refs, total = {}, 0.0
for line in open(os.path.join(d, "frames.jsonl")):
    j = json.loads(line)
    key = (j["step"], j["view"][0], j["view"][1])
    if key not in refs:
        out = os.path.join(d, "ref_%d_%g_%g" % key)
        if not os.path.exists(out):
            subprocess.run([T, "render", tsp, "--steps", str(j["step"]), "--size", size,
                            "--view", "%g,%g" % key[1:], "-o", out], check=True, capture_output=True)
        refs[key] = os.path.join(out, "step_%04d.png" % j["step"])
    de = json.loads(subprocess.run([T, "diff", os.path.join(d, j["file"]), refs[key], "--json"],
                                   capture_output=True, text=True, check=True).stdout)
    total += j["frame_report"]["ms"]
    print("%s step %2d %-11s render %7.1f ms (sum %7.1f)  mean dE %6.3f  p99 %6.2f" % (
        j["file"], j["step"], j["stage"], j["frame_report"]["ms"], total, de["mean"], de["p99"]))
