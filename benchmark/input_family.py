#!/usr/bin/python3
# SPDX-License-Identifier: LGPL-3.0-or-later
"""Figure 18 with part evolution over a family of inputs changed by 1e-7.

Evolution's decisions depend on rest states that a change of the input far
below its noise moves (the manual, Inputs changed by 1e-7): one run of
`reproduce_paper --evolve` is one draw of the paths the same data can take.
This script runs `reproduce_paper --evolve --threads 1 --input-scale S` for
S = 1, 1 + 1e-7, ..., 1 + (N - 1) 1e-7, a few programs at a time, keeps each
run's CSV in OUTDIR, and prints, per row of Figure 18, the parts and RMS_3
of every input, their mean and median, and the median Chamfer distance and
seconds (seconds only mean something with --jobs 1 on an idle machine).
With --compare OLDDIR (an OUTDIR of an earlier run, e.g. of the code before
a change), it also prints the input-by-input differences of RMS_3 (this
run minus OLDDIR): their mean and standard deviation, and on how many
inputs it is lower or higher by more than 0.05 points.

    benchmark/input_family.py --reproduce-paper build/bin/reproduce_paper OUTDIR
        [--inputs 18] [--jobs 2] [--compare OLDDIR] [-- EXTRA reproduce_paper OPTIONS]

Only the Python standard library is needed.
"""

import argparse
import csv
import os
import statistics
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor


def scale_of(r):
    return "%.10f" % (1.0 + r * 1e-7)


def run_one(binary, outdir, r, extra):
    path = os.path.join(outdir, "r%02d.csv" % r)
    with open(os.path.join(outdir, "r%02d.log" % r), "w") as log:
        subprocess.run([binary, "--evolve", "--threads", "1", "--input-scale", scale_of(r), "--csv", path] + extra,
                       stdout=log, stderr=subprocess.STDOUT, check=True)
    return path


def load(outdir, inputs=None):
    """{data: {input index: row}} from the CSV files of an OUTDIR (of the
    first `inputs` inputs only, if given: the directory may hold more)."""
    rows = {}
    for name in sorted(os.listdir(outdir)):
        if not (name.startswith("r") and name.endswith(".csv") and name[1:-4].isdigit()):
            continue
        r = int(name[1:-4])
        if inputs is not None and r >= inputs:
            continue
        with open(os.path.join(outdir, name), newline="") as f:
            for row in csv.DictReader(f):
                rows.setdefault(row["data"], {})[r] = row
    return rows


def summary(rows, old):
    for data, by_input in rows.items():
        inputs = sorted(by_input)
        rms3 = [float(by_input[r]["rms3"]) for r in inputs]
        parts = [int(by_input[r]["parts"]) for r in inputs]
        chamfer = [float(by_input[r]["chamfer_over_diagonal"]) for r in inputs
                   if by_input[r]["chamfer_over_diagonal"]]
        seconds = [float(by_input[r]["seconds"]) for r in inputs]
        print("%s (%d inputs)" % (data, len(inputs)))
        print("  parts: %s (mean %.1f)" % (" ".join(map(str, parts)), statistics.mean(parts)))
        print("  RMS_3 %%: %s" % " ".join("%.1f" % x for x in rms3))
        print("  RMS_3 mean %.2f %%, median %.2f %%; Chamfer / diagonal median %s; seconds median %.2f" % (
            statistics.mean(rms3), statistics.median(rms3),
            "%.4f" % statistics.median(chamfer) if chamfer else "-", statistics.median(seconds)))
        if old is not None and data in old:
            common = [r for r in inputs if r in old[data]]
            if len(common) < 2:
                continue
            d = [float(by_input[r]["rms3"]) - float(old[data][r]["rms3"]) for r in common]
            print("  against the old run on %d inputs: RMS_3 difference mean %+.2f points (standard deviation %.2f), "
                  "lower on %d, higher on %d" % (len(common), statistics.mean(d), statistics.stdev(d),
                                                 sum(x < -0.05 for x in d), sum(x > 0.05 for x in d)))


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("outdir", help="where each input's CSV and log go (created if missing)")
    parser.add_argument("--reproduce-paper", default=os.path.join("build", "bin", "reproduce_paper"),
                        help="the reproduce_paper program (default: build/bin/reproduce_paper)")
    parser.add_argument("--inputs", type=int, default=18, help="how many inputs (default 18: S = 1 to 1 + 17e-7)")
    parser.add_argument("--jobs", type=int, default=2, help="programs at a time (default 2)")
    parser.add_argument("--compare", metavar="OLDDIR", help="an earlier OUTDIR to compare RMS_3 with, input by input")
    parser.add_argument("--summary-only", action="store_true", help="only summarize the CSV files already in OUTDIR")
    # (what follows "--" goes to reproduce_paper as it is)
    argv = sys.argv[1:]
    extra = argv[argv.index("--") + 1:] if "--" in argv else []
    args = parser.parse_args(argv[:argv.index("--")] if "--" in argv else argv)
    if args.inputs < 1 or args.jobs < 1:
        parser.error("--inputs and --jobs must be at least 1")
    if args.compare is not None and not os.path.isdir(args.compare):
        parser.error("--compare: %s is not a directory" % args.compare)
    if not args.summary_only:
        if not (os.path.isfile(args.reproduce_paper) and os.access(args.reproduce_paper, os.X_OK)):
            parser.error("%s is not an executable; build reproduce_paper (configure with "
                         "-DBLENDED_SHAPE_BUILD_BENCHMARKS=ON) or give --reproduce-paper" % args.reproduce_paper)
        os.makedirs(args.outdir, exist_ok=True)
        with ThreadPoolExecutor(max_workers=args.jobs) as pool:
            futures = [pool.submit(run_one, args.reproduce_paper, args.outdir, r, extra)
                       for r in range(args.inputs)]
            try:
                for f in futures:
                    f.result()
            except subprocess.CalledProcessError as e:
                sys.exit("input_family: %s failed (exit %d); see its log in %s" % (" ".join(e.cmd), e.returncode,
                                                                                  args.outdir))
    elif not os.path.isdir(args.outdir):
        parser.error("%s is not a directory" % args.outdir)
    rows = load(args.outdir, None if args.summary_only else args.inputs)
    if not rows:
        sys.exit("input_family: no CSV files in %s" % args.outdir)
    summary(rows, load(args.compare) if args.compare else None)


if __name__ == "__main__":
    main()
