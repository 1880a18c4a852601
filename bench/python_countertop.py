#!/usr/bin/python3
"""One design built in this process, call after call: what a countertop costs
without a process start (issue 29: "keep the per-call overhead of the Python
module visible beside the whole processes").

Usage (with a built module; the design and its CSV files as
bench/countertop_vs_openscad.sh leaves them with KEEP=1):

    PYTHONPATH=build-bench/python /usr/bin/python3 bench/python_countertop.py DESIGN.yaml [--runs 50]

Each call is fabmesh.load_design(path) (YAML and CSV files read again) then
fabmesh.build(design) (curves, region checks, triangulation, slab,
validation and the STL encoded in memory; nothing written). Prints the
median and minimum wall time of a call and of its two halves, after one
warm-up call, and stops if a build is not valid.
"""
import argparse
import statistics
import sys
import time

import fabmesh


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("design")
    parser.add_argument("--runs", type=int, default=50)
    args = parser.parse_args()
    load_ms, build_ms = [], []
    for run in range(args.runs + 1):
        start = time.perf_counter()
        design = fabmesh.load_design(args.design)
        loaded = time.perf_counter()
        mesh = fabmesh.build(design)
        built = time.perf_counter()
        if not mesh.valid:
            sys.exit(f"{args.design}: the build is not valid")
        if run > 0:  # the first call warms the caches
            load_ms.append(1e3 * (loaded - start))
            build_ms.append(1e3 * (built - loaded))
    total = [a + b for a, b in zip(load_ms, build_ms)]
    for name, values in (("load_design", load_ms), ("build", build_ms), ("call", total)):
        print(f"{name:12s} median {statistics.median(values):7.2f} ms, min {min(values):7.2f} ms")


if __name__ == "__main__":
    main()
