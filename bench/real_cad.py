#!/usr/bin/env python3
"""Real CAD parts at 10^5 triangles (docs/part.md#real-cad-parts): the figures of issue 36's
goals, measured with the programs of a release build on this machine.

  * the sample part, default paving, 2 threads: wall time and VALID boxes, with and without
    --no-reuse (every facet paved on its own; tests/solver/part.cpp checks that the certified
    volume of the facets that take a translate's boxes is their own paving's);
  * counter.off (a real CAD export of 83 750 triangles in mm, --scale 0.001, from the folder given), every facet, 2 threads,
    the binary box store only: wall time, peak resident memory, VALID boxes, bytes on disk,
    facets skipped (buried, covered, duplicates) and how the progress line's ETA would have
    fared (elapsed / done x remaining, after 10 %, 20 %, ... of the facets, against the truth);
  * certipose-plan --coverage 0.95 from counter.off's folder: wall time, cameras, coverage,
    candidates inspected (thinning, docs/coverage.md#thinning); the sample part's plan also with
    --all-candidates;
  * the same runs with --keep-largest K (the disk a user keeps).

    python3 bench/real_cad.py PROGRAMS_DIR SHARED_MESHES OUT_DIR [--keep-largest K] [--skip-counter]
    # e.g. build/release/examples MESHES_DIR /tmp/real_cad  (MESHES_DIR holds counter.off)
It writes OUT_DIR/real_cad.json and prints a Markdown table. A full counter.off run takes
about 20 minutes and ~10 GB of disk here: OUT_DIR must have room.
"""
import json
import os
import re
import subprocess
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)


def timed(cmd):
    """(seconds, peak RSS in MB, stderr) of one command, with GNU time."""
    t0 = time.monotonic()
    p = subprocess.run(["/usr/bin/time", "-v"] + cmd, capture_output=True, text=True)
    seconds = time.monotonic() - t0
    if p.returncode != 0:
        sys.exit(f"failed ({p.returncode}): {' '.join(cmd)}\n{p.stderr[-2000:]}")
    rss = re.search(r"Maximum resident set size \(kbytes\): (\d+)", p.stderr)
    return seconds, int(rss.group(1)) / 1024 if rss else float("nan"), p.stderr


def folder_bytes(d):
    return sum(os.path.getsize(os.path.join(d, f)) for f in os.listdir(d))


def eta_errors(summary):
    """The progress line's ETA (elapsed/done x remaining) after each tenth of the facets, as a
    ratio predicted total / actual total, from the facets' own solve times in order (the
    run's threads share the work evenly, so the sum tracks elapsed time)."""
    secs = [f["seconds"] for f in summary["facets"]]
    total, acc, out = sum(secs), 0.0, {}
    if not secs or total <= 0:
        return out
    cum = []
    for s in secs:
        acc += s
        cum.append(acc)
    for tenth in range(1, 10):
        k = len(secs) * tenth // 10
        out[f"{tenth * 10}%"] = round(cum[k - 1] / k * len(secs) / total, 3)
    return out


def part_run(programs, mesh, scale, out, extra):
    cmd = [f"{programs}/certipose-part", "--mesh", mesh, "--camera", f"{ROOT}/examples/data/camera.json",
           "--position-eps", "0.1", "--orientation-eps", "0.38", "--threads", "2", "--out", out, "-q"] + extra
    if scale != 1:
        cmd += ["--scale", str(scale)]
    seconds, rss, _ = timed(cmd)
    s = json.load(open(f"{out}/summary.json"))
    t = s["totals"]
    return {"seconds": round(seconds, 1), "rss_mb": round(rss), "valid": t["valid"], "skipped": t["skipped"],
            "facets": t["facets"], "disk_mb": round(folder_bytes(out) / 1e6), "eta_ratio": eta_errors(s),
            "survey": s.get("survey"), "reused": sum(1 for f in s["facets"] if "reused_from" in f)}


def plan_run(programs, mesh, scale, folder, out, extra=()):
    cmd = [f"{programs}/certipose-plan", "--mesh", mesh, "--camera", f"{ROOT}/examples/data/camera.json",
           "--part-results", folder, "--coverage", "0.95", "--threads", "2", "--out", out, "-q"] + list(extra)
    if scale != 1:
        cmd += ["--scale", str(scale)]
    seconds, rss, _ = timed(cmd)
    p = json.load(open(out))
    c = p["coverage"]
    return {"seconds": round(seconds, 1), "rss_mb": round(rss), "cameras": len(p["cameras"]),
            "lower_bound": c["lower_bound_cameras"], "candidates": p["settings"]["candidates"],
            "inspected": p["settings"].get("inspected"),
            "coverable_share": round(c["certified_area"] / c["coverable_area"], 4) if c["coverable_area"] else None}


def main():
    import argparse
    ap = argparse.ArgumentParser(description="issue 36's figures", epilog=__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("programs")
    ap.add_argument("shared")
    ap.add_argument("out")
    ap.add_argument("--keep-largest", dest="keep")
    ap.add_argument("--skip-counter", action="store_true")
    a = ap.parse_args()
    programs, shared, out, keep = a.programs, a.shared, a.out, a.keep
    os.makedirs(out, exist_ok=True)
    sample = f"{programs}/sample_part.off"
    counter = f"{shared}/counter.off"
    rows = {}
    rows["sample part, both stores"] = part_run(programs, sample, 1, f"{out}/sample", [])
    rows["sample part, binary store"] = part_run(programs, sample, 1, f"{out}/sample_bin", ["--box-store", "binary"])
    # Before/after the reuse between translates (docs/part.md#reuse-between-translates): the
    # same run with every facet paved on its own.
    rows["sample part, binary store, --no-reuse"] = part_run(programs, sample, 1, f"{out}/sample_bin_alone",
                                                              ["--box-store", "binary", "--no-reuse"])
    rows["sample part plan (binary)"] = plan_run(programs, sample, 1, f"{out}/sample_bin", f"{out}/sample_plan.json")
    rows["sample part plan, --all-candidates"] = plan_run(programs, sample, 1, f"{out}/sample_bin",
                                                          f"{out}/sample_plan_all.json", ["--all-candidates"])
    if not a.skip_counter:
        rows["counter.off, binary store"] = part_run(programs, counter, 0.001, f"{out}/counter", ["--box-store", "binary"])
        rows["counter.off plan"] = plan_run(programs, counter, 0.001, f"{out}/counter", f"{out}/counter_plan.json")
        if keep:
            rows[f"counter.off, --keep-largest {keep}"] = part_run(
                programs, counter, 0.001, f"{out}/counter_keep", ["--box-store", "binary", "--keep-largest", keep])
            rows[f"counter.off plan, --keep-largest {keep}"] = plan_run(
                programs, counter, 0.001, f"{out}/counter_keep", f"{out}/counter_keep_plan.json")
    json.dump(rows, open(f"{out}/real_cad.json", "w"), indent=1)
    print("| run | seconds | peak RSS (MB) | VALID | skipped | disk (MB) | cameras (bound), inspected / candidates | ETA ratio at 10/50/90 % |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- |")
    for name, r in rows.items():
        eta = r.get("eta_ratio") or {}
        cams = f"{r['cameras']} ({r['lower_bound']}), {r['inspected']} / {r['candidates']}" if "cameras" in r else ""
        print(f"| {name} | {r['seconds']} | {r['rss_mb']} | {r.get('valid', '')} | {r.get('skipped', '')} | "
              f"{r.get('disk_mb', '')} | {cams} | "
              f"{' / '.join(str(eta.get(k, '')) for k in ('10%', '50%', '90%')) if eta else ''} |")


if __name__ == "__main__":
    main()
