#!/usr/bin/env python3
"""Smoke test of `hush bench --quick` (DESIGN.md principle 4): runs it once with every output
and checks what it wrote; with --interleave, a short interleaved run instead (see
check_interleaved).

  - JSON parses; every row has a finite ns_per_sample > 0 and the error fields; hush rows have
    finite errors (rms <= max abs) within the noise's float budget, gradient rows gradient
    errors; libnoise rows (double only) have null errors; the rows cover every noise x backend
    x workload x output of hush plus the peer rows, and the machine fields are there.
  - stdout and --markdown hold the same Markdown table, one line per JSON row.
  - the SVG parses as XML and draws one marker per row plus one per legend entry.

Usage: check_bench.py HUSH_EXE SCRATCH_DIR [--interleave]   (exit 0: all checks pass)
"""
import json
import math
import os
import re
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET

# Loose float budgets against the double reference, to catch a broken backend or reference
# (those miss by O(1)), not to restate the tests' bounds. perlin.hpp states 2^-16 for the
# value; the gradient gets 8 times that. A 4-octave fBm of unit variance weighs its bands
# 1, 1/2, 1/4, 1/8 (sum < 2) times 1/sqrt(variance * 1.33) < 3.4, so < 4 * 3.4 bands' worth;
# its gradient multiplies band i by frequency 2^i (sum of weight * frequency = 4).
PERLIN_VALUE, PERLIN_GRADIENT, FBM_SCALE = 2.0 ** -16, 8 * 2.0 ** -16, 4 * 3.4
# Coherent noise (coherent.hpp): 12 / (1 - alpha) + 1 = 601 roundings of 2^-24 at alpha 0.98
# on outputs below ~8 (unit variance): 3e-4; the loose budget is 1e-3.
# Gabor (gabor.hpp float_budget: 2^-21 (1 + 2 pi Phi) sqrt(N')) and anisotropic noise
# (anisotropic.hpp float_budget; its GLSL rows add the texture filter's weight rounding) measure
# 1.6e-6 / 8.1e-6 (Gabor values / gradients) and 1.7e-5 (anisotropic) in `hush bench --quick`;
# the loose budgets, like the others, sit well above and far below an O(1) miss.
# NPR Gabor noise (npr_gabor.hpp: 2^-21 (1 + 2 pi F0 r) per kernel times the sum of |w v|
# scale over the kernels at a pixel) measured 8.3e-7 in its tests; the loose budget is 1e-4.
# Wavelet noise (wavelet.hpp float_budget: (21 D + bands + 2) 2^-24 bound(), 512 in place of
# 21 D for the projection's kernels; bound() ~ 10 at unit variance) measures 1.6e-6 / 1.4e-6
# (values / gradients, every backend) in `hush bench --quick`; loose budgets like Gabor's.
# NPR Gabor on GLSL computes stage 1 (positions, pixel boxes, depth planes) in float on the GPU,
# so a pixel where the double reference sits on a decision boundary (the depth test's tolerance,
# or a kernel's pixel box at its truncation radius, where the kernel is e^-pi of its peak) can
# take the other side: that pixel misses or gains one kernel's term, up to one kernel's amplitude
# (the tests count such pixels: tests/gabor/glsl_gabor_test.cpp "npr"; measured 7.3e-3 at one
# pixel of `hush bench --quick`'s 192 x 108 frame). These rows are held to the budget in RMS,
# which a few such pixels barely move and a wrong record or kernel exceeds at once, and their
# max to one kernel's amplitude at unit variance.
NPR_GLSL_MAX = 0.25
VALUE_BUDGET = {"perlin": PERLIN_VALUE, "fbm": FBM_SCALE * PERLIN_VALUE, "coherent": 1e-3,
                "gabor": 1e-4, "anisotropic": 1e-3, "npr-gabor": 1e-4, "wavelet": 1e-4}
GRADIENT_BUDGET = {"perlin": PERLIN_GRADIENT, "fbm": FBM_SCALE * PERLIN_GRADIENT, "gabor": 1e-3,
                   "wavelet": 1e-3}
# Wavelet rows carry the band leakage (hush/detail/band_limit.hpp) of band 0 beside Perlin's
# as their quality note; the expected figures are ~0.0002 and ~0.02: wavelet 2D must leak at
# most a tenth of Perlin's (measured 0.0003 vs 0.010), and the 3D noise projected onto the
# slice plane at most a quarter of what the slice leaks (measured 0.0068 vs 0.079), as in
# tests/wavelet/wavelet_spectrum_test.cpp.
WAVELET_LEAK_RATIO, PROJECTED_LEAK_RATIO = 0.1, 0.25

failures = []


def check(cond, what):
    if not cond:
        failures.append(what)


# Unfiltered Gabor 2D and 3D rows carry "spectrum error E (sampling alone: S)"
# (bench/gabor_quality.hpp): E is a relative RMS whose expectation for a correct noise is
# about S (each ring's mean has relative sampling error ~S) plus the window's ~1% (2D) or
# ~2% (3D) bias; 2 S + 0.05 leaves room for a high draw, while a wrong spectrum (frequency
# or bandwidth off) gives E of order 1.
def check_spectrum_note(name, note):
    m = re.search(r"spectrum error ([0-9.]+) \(sampling alone: ([0-9.]+)\)", note)
    check(m is not None, name + ": no spectrum error in %r" % note)
    if m:
        err, alone = float(m.group(1)), float(m.group(2))
        check(0 < alone < 0.2 and err <= 2 * alone + 0.05,
              name + ": spectrum error %g (sampling alone %g)" % (err, alone))


# `hush bench --quick --repetitions 3 --interleave` on four small rows of two names (a
# --filter of two texts; about two seconds): each matched row appears once in the JSON and the
# table, with the median of its 3 repetitions, a finite time and its errors, and the report
# says the run was interleaved.
INTERLEAVE_FILTER = "perlin2D/simd/grid|fbm2D/simd/grid"
INTERLEAVE_ROWS = {"%s2D/simd/grid/%s" % (n, o) for n in ("perlin", "fbm")
                   for o in ("value", "value+gradient")}


def run_bench(exe, args, json_path, timeout):
    """Runs `hush bench ARGS`; returns (the finished process, the JSON document) or (run, None)
    after recording the failure when it exited non-zero."""
    run = subprocess.run([exe, "bench"] + args, capture_output=True, text=True, timeout=timeout)
    check(run.returncode == 0, "exit code %d, stderr: %s" % (run.returncode, run.stderr))
    if run.returncode != 0:
        return run, None
    with open(json_path) as f:
        return run, json.load(f)


def check_interleaved(exe, scratch):
    paths = {k: os.path.join(scratch, "interleaved." + k) for k in ("json", "md")}
    run, doc = run_bench(exe, ["--quick", "--repetitions", "3", "--interleave", "--filter",
                               INTERLEAVE_FILTER, "--json", paths["json"], "--markdown",
                               paths["md"]], paths["json"], 120)
    if doc is None:
        return
    check("--interleave" in doc["command"], "command %r" % doc["command"])
    settings = doc["settings"]
    check(settings["interleave"] is True and settings["repetitions"] == 3
          and settings["filter"] == INTERLEAVE_FILTER, "settings %r" % settings)
    ids = [r["id"] for r in doc["rows"]]
    check(sorted(ids) == sorted(INTERLEAVE_ROWS), "rows %r, want each of %r once"
          % (ids, sorted(INTERLEAVE_ROWS)))
    for r in doc["rows"]:
        ns, mx = r["ns_per_sample"], r["max_abs_error"]
        check(isinstance(ns, (int, float)) and math.isfinite(ns) and ns > 0,
              r["id"] + ": ns_per_sample %r" % ns)
        check(r["repetitions"] == 3, r["id"] + ": repetitions %r" % r["repetitions"])
        check(isinstance(mx, (int, float)) and 0 <= mx <= PERLIN_VALUE,
              r["id"] + ": max abs error %r" % mx)
    with open(paths["md"]) as f:
        md = f.read()
    check(md == run.stdout, "--markdown differs from stdout")
    check("interleaved in random order" in md and "--interleave" in md,
          "the table does not say it was interleaved")
    table = [line for line in md.splitlines() if line.startswith("|")]
    check(len(table) == len(INTERLEAVE_ROWS) + 2, "markdown has %d table lines for %d rows"
          % (len(table), len(INTERLEAVE_ROWS)))


def main():
    if len(sys.argv) < 3 or sys.argv[3:] not in ([], ["--interleave"]):
        sys.exit("usage: check_bench.py HUSH_EXE SCRATCH_DIR [--interleave]")
    exe, scratch = sys.argv[1], sys.argv[2]
    shutil.rmtree(scratch, ignore_errors=True)
    os.makedirs(scratch)
    if sys.argv[3:] == ["--interleave"]:
        check_interleaved(exe, scratch)
        return
    paths = {k: os.path.join(scratch, "bench." + k) for k in ("json", "md", "svg")}
    run, doc = run_bench(exe, ["--quick", "--json", paths["json"], "--markdown", paths["md"],
                               "--plot", paths["svg"]], paths["json"], 300)
    if doc is None:
        return

    for key in ("cpu", "compiler", "build", "simd_target", "peers"):
        check(isinstance(doc["machine"].get(key), str) and doc["machine"][key],
              "machine." + key)
    check(doc["settings"]["quick"] is True and doc["settings"]["repetitions"] == 1
          and doc["settings"]["interleave"] is False, "settings")
    rows = doc["rows"]
    fields = ("ns_per_sample", "max_abs_error", "rms_error", "gradient_max_abs_error",
              "gradient_rms_error", "error_reference")
    hush_keys = set()
    for r in rows:
        name = r.get("id", "?")
        for k in fields:
            check(k in r, name + ": field " + k)
        ns = r["ns_per_sample"]
        check(isinstance(ns, (int, float)) and math.isfinite(ns) and ns > 0,
              name + ": ns_per_sample %r" % ns)
        if r["error_reference"].startswith("n.a."):
            check(r["max_abs_error"] is None and r["rms_error"] is None, name + ": n.a. error")
            continue
        mx, rms = r["max_abs_error"], r["rms_error"]
        check(isinstance(mx, (int, float)) and math.isfinite(mx) and 0 <= rms <= mx,
              name + ": errors %r %r" % (mx, rms))
        if r["peer"]:
            continue
        family = r["noise"].split()[0]
        if family == "npr-gabor" and r["backend"].startswith("glsl"):
            check(rms <= VALUE_BUDGET[family] and mx <= NPR_GLSL_MAX,
                  name + ": RMS %g or max abs %g over budget" % (rms, mx))
        else:
            check(mx <= VALUE_BUDGET[family], name + ": max abs %g over budget" % mx)
        gmx, grms = r["gradient_max_abs_error"], r["gradient_rms_error"]
        if r["output"] == "value+gradient":
            check(gmx is not None and 0 <= grms <= gmx <= GRADIENT_BUDGET[family],
                  name + ": gradient errors %r %r" % (gmx, grms))
        else:
            check(gmx is None and grms is None, name + ": gradient error without gradient")
        hush_keys.add((r["noise"], r["backend"], r["workload"].split()[0], r["output"]))
        if (r["noise"].startswith(("gabor 2D", "gabor 3D"))
                and not any(k in r["noise"] for k in ("filtered", "surface"))):
            check_spectrum_note(name, r.get("quality", ""))
    want = {(n, b, w, o) for n in ("perlin 2D", "perlin 3D", "fbm 2D", "fbm 3D")
            for b in ("scalar", "simd") for w in ("grid", "points")
            for o in ("value", "value+gradient")}
    want |= {(n, b, w, o) for n in ("wavelet 2D", "wavelet 3D")
             for b in ("scalar", "simd") for w in ("grid", "points")
             for o in ("value", "value+gradient")}
    want |= {("wavelet %s b%d" % (d, k), b, w, "value") for d in ("2D", "3D") for k in (2, 4)
             for b in ("scalar", "simd") for w in ("grid", "points")}
    want |= {(n, b, "samples", "value") for b in ("scalar", "simd")
             for n in ("wavelet 3D projected", "wavelet 3D projected approx")}
    want |= {("gabor 3D", b, w, "value") for b in ("scalar", "simd") for w in ("grid", "points")}
    want |= {("gabor %s" % n, b, "samples", "value") for b in ("scalar", "simd")
             for n in ("2D filtered", "2D filtered anisotropic", "3D filtered", "3D surface")}
    # wavelet 3D points' memory bounds (SIMD only): tile reads L1-resident, a 32^3 tile.
    bounds = ("points-L1", "points-L2")
    want |= {("wavelet 3D", "simd", w, "value") for w in bounds}
    check(want <= hush_keys, "missing hush rows: %s" % sorted(want - hush_keys))
    leak = {}
    for r in rows:
        if r["peer"] or r["noise"] not in ("wavelet 2D", "wavelet 3D", "wavelet 3D projected"):
            continue
        if r["workload"].split()[0] in bounds:  # speed rows: the leakage is the spread row's
            continue
        m = re.match(r"band leakage ([0-9.e+-]+) \(perlin 2D ([0-9.e+-]+)\)", r.get("quality", ""))
        check(m is not None, r["id"] + ": quality %r" % r.get("quality"))
        if m:
            leak[r["noise"]] = float(m.group(1))
            leak["perlin"] = float(m.group(2))
    if len(leak) == 4:
        check(leak["wavelet 2D"] <= WAVELET_LEAK_RATIO * leak["perlin"],
              "wavelet 2D band leakage %g vs perlin %g" % (leak["wavelet 2D"], leak["perlin"]))
        check(leak["wavelet 3D projected"] <= PROJECTED_LEAK_RATIO * leak["wavelet 3D"],
              "projected band leakage %g vs 3D slice %g"
              % (leak["wavelet 3D projected"], leak["wavelet 3D"]))
    peers = {r["backend"] for r in rows if r["peer"]}
    check({"glm::perlin", "libnoise"} <= peers or doc["machine"]["peers"].startswith("none"),
          "peer rows: %s" % sorted(peers))

    # The Markdown table: a header, a rule, one line per row; stdout equals --markdown.
    with open(paths["md"]) as f:
        md = f.read()
    check(md == run.stdout, "--markdown differs from stdout")
    table = [line for line in md.splitlines() if line.startswith("|")]
    check(len(table) == len(rows) + 2, "markdown has %d table lines for %d rows"
          % (len(table), len(rows)))

    svg = ET.parse(paths["svg"]).getroot()
    ns = "{http://www.w3.org/2000/svg}"
    markers = [e for e in svg.iter() if e.tag in (ns + "circle", ns + "rect", ns + "polygon")]
    # Markers: one per row and one per legend entry, plus the background and the frame rects.
    series = {(r["backend"], r["output"] if not r["peer"] else "") for r in rows}
    check(len(markers) == len(rows) + len(series) + 2,
          "svg has %d markers for %d rows and %d series" % (len(markers), len(rows), len(series)))


if __name__ == "__main__":
    main()
    for f in failures:
        print("FAIL:", f)
    print("%d failure(s)" % len(failures))
    sys.exit(1 if failures else 0)
