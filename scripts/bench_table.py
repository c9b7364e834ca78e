#!/usr/bin/env python3
# SPDX-License-Identifier: Apache-2.0
"""Merges Google Benchmark JSON files (--benchmark_out=FILE --benchmark_out_format=json) into one file with the
machine and date, and prints the same-run ratios as Markdown tables (docs/speed.md's tables are this output).

    bench_table.py merge OUT.json IN.json...   # writes OUT.json, then prints its tables
    bench_table.py table MERGED.json           # prints the tables of a merged file

Every ratio is of CPU time (the steadier figure on a shared machine: time spent descheduled does not count) per
iteration, the median over --benchmark_repetitions, of two cases timed in the same process. Case names:
BM_Project/<who>/<model>/<points>, BM_Blend/<kind>/<format>/<size>, BM_Jpeg/<path>/<format>/<size>/<colours>
(tests/bench/, tests/bench_overlay/). Standard library only."""
import datetime
import json
import os
import statistics
import subprocess
import sys

UNIT_SECONDS = {"ns": 1e-9, "us": 1e-6, "ms": 1e-3, "s": 1.0}


def machine():
    """The CPU as lscpu names it, its core count, and the vector extensions the batch loops choose between."""
    info = {}
    try:
        out = subprocess.run(["lscpu"], capture_output=True, text=True, check=True).stdout
        fields = dict(line.split(":", 1) for line in out.splitlines() if ":" in line)
        fields = {k.strip(): v.strip() for k, v in fields.items()}
        info["model_name"] = fields.get("Model name", "unknown")
        info["cpus"] = int(fields.get("CPU(s)", "0") or 0)
        flags = fields.get("Flags", "").split()
    except (OSError, subprocess.CalledProcessError, ValueError):
        info["model_name"], info["cpus"], flags = "unknown", os.cpu_count() or 0, []
    info["avx2"] = "avx2" in flags
    info["avx512f"] = "avx512f" in flags
    return info


def git_commit():
    try:
        out = subprocess.run(["git", "describe", "--always", "--dirty"], capture_output=True, text=True, check=True)
        return out.stdout.strip()
    except (OSError, subprocess.CalledProcessError):
        return "unknown"


def merge(inputs):
    merged = {"date": datetime.datetime.now(datetime.timezone.utc).isoformat(timespec="seconds"),
              "commit": git_commit(), "machine": machine(), "runs": []}
    for path in inputs:
        with open(path, encoding="utf-8") as f:
            data = json.load(f)
        merged["runs"].append({"executable": data.get("context", {}).get("executable", path),
                               "context": data.get("context", {}), "benchmarks": data.get("benchmarks", [])})
    return merged


def cpu_seconds(merged):
    """name -> CPU seconds per iteration: the "median" aggregate where there is one, else the median of the
    repetitions (a single run is its own median)."""
    repetitions, medians = {}, {}
    for run in merged["runs"]:
        for b in run["benchmarks"]:
            if b.get("error_occurred"):
                continue
            name = b.get("run_name", b["name"])
            seconds = b["cpu_time"] * UNIT_SECONDS[b.get("time_unit", "ns")]
            if b.get("run_type") == "aggregate":
                if b.get("aggregate_name") == "median":
                    medians[name] = seconds
            else:
                repetitions.setdefault(name, []).append(seconds)
    times = {name: statistics.median(values) for name, values in repetitions.items()}
    times.update(medians)
    return times


def in_order(names):
    """Distinct names in the order the benchmarks ran (each program registers its cases in a meaningful order)."""
    return list(dict.fromkeys(names))


def names(merged):
    return [b.get("run_name", b["name"]) for run in merged["runs"] for b in run["benchmarks"]]


def labels(merged):
    return {b.get("run_name", b["name"]): b["label"] for run in merged["runs"] for b in run["benchmarks"]
            if b.get("label")}


def ratio(a, b):
    return f"{a / b:.2f}" if a and b else "–"


def tables(merged):
    t = cpu_seconds(merged)
    lines = []
    m = merged["machine"]
    vectors = ", ".join(name for name in ("avx2", "avx512f") if m.get(name)) or "neither AVX2 nor AVX-512F"
    lines.append(f"Machine: {m['model_name']}, {m['cpus']} CPUs ({vectors}); {merged['date']}, commit "
                 f"{merged['commit']}. CPU time per iteration, median of the repetitions; ratios of cases timed in "
                 "the same process.")

    # Projection: BM_Project/<who>/<model>/<points>.
    projection = sorted({(int(n.split("/")[3]), n.split("/")[2]) for n in t if n.startswith("BM_Project/opencv/")})
    if projection:
        loops = [w for w in ("ours_lanes2", "ours_avx2", "ours_avx512")
                 if any(n.startswith(f"BM_Project/{w}/") for n in t)]
        picked = next((l for n, l in labels(merged).items() if n.startswith("BM_Project/ours/")), "")
        lines += ["", f"**Batch projection** vs `cv::projectPoints` (speed-up; `ours` {picked}):", "",
                  "| model | points | OpenCV ns/point | ours ns/point | ours | " + " | ".join(loops) + " |",
                  "|---|---|---|---|---|" + "---|" * len(loops)]
        order = {"none": 0, "radtan5": 1, "fisheye": 2}
        for points, model in sorted(projection, key=lambda p: (order.get(p[1], 9), p[0])):
            cv = t.get(f"BM_Project/opencv/{model}/{points}")
            ours = t.get(f"BM_Project/ours/{model}/{points}")
            per = [ratio(cv, t.get(f"BM_Project/{w}/{model}/{points}")) + "x" for w in loops]
            lines.append(f"| {model} | {points} | {cv / points * 1e9:.2f} | "
                         f"{ours / points * 1e9 if ours else float('nan'):.2f} | **{ratio(cv, ours)}x** | "
                         + " | ".join(per) + " |")

    # Overlay blend of the Speed scene: BM_Blend/<kind>/<format>/<size>.
    cases = in_order(n.split("/", 2)[2] for n in names(merged) if n.startswith("BM_Blend/memcpy_cold/") and n in t)
    if cases:
        lines += ["", "**Overlay blend** of the Speed scene, against a cold frame copy and OpenCV drawing:", "",
                  "| case | static / memcpy_cold (<= 0.5) | dynamic / memcpy_cold (<= 2) | opencv_naive / static "
                  "(>= 25) | steering / memcpy_cold (<= 2) | steady / memcpy_cold (<= 0.5) |",
                  "|---|---|---|---|---|---|"]
        for c in cases:
            g = lambda kind: t.get(f"BM_Blend/{kind}/{c}")
            copy = g("memcpy_cold")
            lines.append(f"| {c} | {ratio(g('static'), copy)} | {ratio(g('dynamic'), copy)} | "
                         f"{ratio(g('opencv_naive'), g('static'))} | {ratio(g('steering'), copy)} | "
                         f"{ratio(g('steady'), copy)} |")

    # JPEG: BM_Jpeg/<path>/<case>.
    jpeg = in_order(n.split("/", 2)[2] for n in names(merged) if n.startswith("BM_Jpeg/native/") and n in t)
    if jpeg:
        lines += ["", "**JPEG** from the frame's own planes vs the RGB round trip (speed-up):", "",
                  "| case | native ms/frame | round trip ms/frame | speed-up |", "|---|---|---|---|"]
        for c in jpeg:
            native, rgb = t.get(f"BM_Jpeg/native/{c}"), t.get(f"BM_Jpeg/rgb_round_trip/{c}")
            lines.append(f"| {c} | {native * 1e3:.2f} | {rgb * 1e3 if rgb else float('nan'):.2f} | "
                         f"{ratio(rgb, native)}x |")
    return "\n".join(lines)


def main(argv):
    if len(argv) >= 3 and argv[1] == "merge":
        merged = merge(argv[3:])
        with open(argv[2], "w", encoding="utf-8") as f:
            json.dump(merged, f, indent=1)
    elif len(argv) == 3 and argv[1] == "table":
        with open(argv[2], encoding="utf-8") as f:
            merged = json.load(f)
    else:
        sys.exit(__doc__)
    print(tables(merged))


if __name__ == "__main__":
    main(sys.argv)
