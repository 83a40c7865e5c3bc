"""A large JARM map written to zarr chunk by chunk: time, points per second, peak memory.

Runs ``eccjump map`` in this process (the same code path as the console script) on a
G x G x G grid (default 200^3 = 8e6 points, mu_s = 0.7, full default ranges) and reports
the peak resident memory of the process (``ru_maxrss``; also sampled from /proc during the
run). The map must stay under 1 GiB: only one chunk is in memory at a time. Run:

    python benches/bench_map.py [--grid 200] [--out /tmp/eccjump_bench_map.zarr] [--json PATH]

The figures also go to ``--json`` (default bench_map.json in the current directory).
"""

from __future__ import annotations

import argparse
import os
import platform
import resource
import shutil
import threading
import time

import results

from eccjump import __version__
from eccjump.cli import main

GIB = 1024**3


def rss_bytes() -> int:
    with open("/proc/self/statm") as fh:
        return int(fh.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")


def main_bench() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--grid", type=int, default=200)
    p.add_argument("--mu-s", default="0.7")
    p.add_argument("--out", default="/tmp/eccjump_bench_map.zarr")
    p.add_argument("--threads", default="0")
    p.add_argument("--chunk", default=None, help="alpha slices per chunk (default: auto)")
    p.add_argument("--keep", action="store_true", help="keep the output")
    results.add_json_option(p, "map")
    args = p.parse_args()

    peak = [rss_bytes()]
    stop = threading.Event()

    def sample() -> None:
        while not stop.wait(0.1):
            peak[0] = max(peak[0], rss_bytes())

    sampler = threading.Thread(target=sample, daemon=True)
    sampler.start()
    base = rss_bytes()
    argv = ["map", "--mu-s", args.mu_s, "--grid", str(args.grid), "-o", args.out]
    argv += ["--threads", args.threads, "--overwrite", "--quiet"]
    if args.chunk:
        argv += ["--chunk", args.chunk]
    t0 = time.perf_counter()
    code = main(argv)
    seconds = time.perf_counter() - t0
    stop.set()
    sampler.join()
    maxrss = resource.getrusage(resource.RUSAGE_SELF).ru_maxrss * 1024  # KiB on Linux
    points = args.grid**3
    print()
    print(f"eccjump {__version__}, Python {platform.python_version()}, {os.cpu_count()} CPUs")
    print(f"command        eccjump {' '.join(argv)}")
    print(f"exit status    {code}")
    print(f"points         {points}")
    print(f"wall time      {seconds:.1f} s")
    print(f"points/s       {points / seconds:.0f}")
    print(f"RSS at start   {base / 2**20:.0f} MiB")
    print(f"peak RSS       {max(maxrss, peak[0]) / 2**20:.0f} MiB (ru_maxrss, /proc sampling)")
    print(f"under 1 GiB    {max(maxrss, peak[0]) < GIB}")
    if not args.keep:
        shutil.rmtree(args.out, ignore_errors=True)
    peak_bytes = max(maxrss, peak[0])
    results.write(
        args.json,
        "map",
        args,
        command=["eccjump", *argv],
        exit_status=code,
        points=points,
        wall_s=seconds,
        points_per_s=points / seconds,
        rss_start_mib=base / 2**20,
        peak_rss_mib=peak_bytes / 2**20,
        under_1_gib=peak_bytes < GIB,
    )


if __name__ == "__main__":
    main_bench()
