#!/usr/bin/python3
"""The serial fraction of a DEM step, from a profile of the timed steps at one thread.

Reads `perf script --no-demangle` output of a `perf record --call-graph
dwarf` session of dem_throughput (bench/paper_model.sh, PROFILE=1) on stdin.
A sample belongs to a parallel region when a frame of its call chain is an
OpenMP outlined function (GCC names them `<function>._omp_fn.<n>`, a suffix
the demangler would hide; where the unwinding stops early the leaf alone
decides, and the hot kernels are inlined into their outlined function, so
the leaf is that function): at one thread that work
runs on one core, and on p cores it divides by p. Everything else (the
step's own loops over walls, the wall-force distribution, the list rebuild's
serial parts, libgomp's fork and join) is serial. Amdahl then bounds the
speed-up on p cores by 1 / (s + (1 - s) / p); memory bandwidth, which the
cores of a node share, lowers it further (docs/dem_benchmarks.md).

  perf script --no-demangle -F comm,ip,sym -i perf.data | bench/serial_fraction.py [--top N] [--cores "16 64"]
"""
import argparse
import collections
import subprocess
import sys


def samples(lines):
    """Yields each sample's call chain (leaf first) as a list of symbol names."""
    chain = []
    for line in lines:
        text = line.strip()
        if not text:
            if chain:
                yield chain
            chain = []
            continue
        if line[0] not in " \t":  # the sample's header line (comm)
            if chain:
                yield chain
            chain = []
            continue
        # "  7f12ab34 symbol+0x12 (dso)" or "symbol" alone: keep the symbol.
        parts = text.split(None, 1)
        symbol = parts[1] if len(parts) == 2 and all(c in "0123456789abcdef" for c in parts[0]) else text
        chain.append(symbol.rsplit(" (", 1)[0].split("+0x")[0])
    if chain:
        yield chain


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--top", type=int, default=8, help="how many serial symbols to list (default 8)")
    parser.add_argument("--cores", default="16 64", help='core counts to project to (default "16 64")')
    args = parser.parse_args()
    total = parallel = 0
    serial_by_symbol = collections.Counter()
    for chain in samples(sys.stdin):
        total += 1
        if any("._omp_fn." in frame for frame in chain):
            parallel += 1
        else:
            # Name the serial work by its innermost frame of our own code
            # (dfc::), else by the leaf (libc, libgomp, the kernel).
            own = next((f for f in chain if f.startswith("_ZN3dfc")), chain[0])
            serial_by_symbol[own] += 1
    if total == 0:
        sys.exit("serial_fraction.py: no samples on stdin (was the profile empty?)")
    s = (total - parallel) / total
    print(f"samples {total}, in parallel regions {parallel}: serial fraction {100 * s:.2f} %")
    for p in (int(c) for c in args.cores.split()):
        print(f"Amdahl bound on {p} cores: speed-up {1 / (s + (1 - s) / p):.1f} (of {p})")
    print("serial samples by function (share of all samples):")
    top = serial_by_symbol.most_common(args.top)
    names = demangled([symbol for symbol, _ in top])
    for (symbol, count), name in zip(top, names):
        print(f"  {100 * count / total:6.2f} %  {name[:120]}")


def demangled(symbols):
    """The readable names (c++filt where installed; the mangled ones otherwise)."""
    try:
        out = subprocess.run(["c++filt"], input="\n".join(symbols), capture_output=True, text=True, check=True).stdout
        return out.splitlines() if len(out.splitlines()) == len(symbols) else symbols
    except (OSError, subprocess.CalledProcessError):
        return symbols


if __name__ == "__main__":
    main()
