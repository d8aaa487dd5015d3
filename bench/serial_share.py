#!/usr/bin/env python3
"""How much of a run's wall time only one thread works, and in what.

Reads `perf script -F tid,time,ip,sym` of a `perf record -g` run (stdin or a
file), cuts the run into windows of --window seconds, and calls a window serial when
one thread alone has samples in it (a thread that waits is not sampled: the
main thread working while the pool sleeps, or one task left at the end of a
parallel loop). Prints the serial share of the run and the functions the
samples of serial windows were in (inclusive: a function counts once per
sample whatever its depth): the library's own and the kernel's page clearing.
That share is what Amdahl's law charges a second thread for.

  perf record -g -o run.data voronoimesh mesh ... --threads 2
  perf script -i run.data -F tid,time,ip,sym | bench/serial_share.py [--window 0.005] [--top 30]
"""
import argparse
import collections
import re
import sys


def read_samples(lines):
    """(tid, time, [frame names, innermost first]) per sample."""
    samples, current = [], None
    for line in lines:
        head = re.match(r"\s*(\d+)\s+([\d.]+):", line)
        if head:
            current = (int(head.group(1)), float(head.group(2)), [])
            samples.append(current)
            continue
        parts = line.strip().split(None, 1)
        if current is not None and len(parts) == 2:
            current[2].append(re.sub(r"\(.*", "", parts[1]))
    return samples


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("script", nargs="?", type=argparse.FileType("r"), default=sys.stdin)
    parser.add_argument("--window", type=float, default=0.005, help="window length in seconds (default 0.005)")
    parser.add_argument("--top", type=int, default=30, help="functions listed (default 30)")
    args = parser.parse_args()
    samples = read_samples(args.script)
    if not samples:
        sys.exit("serial_share.py: no samples (give `perf script -F tid,time,ip,sym` of a `perf record -g` run)")
    start = min(s[1] for s in samples)
    wall = max(s[1] for s in samples) - start
    if wall <= 0:
        sys.exit("serial_share.py: the samples span no time (too short a run to measure)")
    window_of = lambda time: int((time - start) / args.window)
    threads = collections.defaultdict(set)  # window -> the threads sampled in it
    for tid, time, _ in samples:
        threads[window_of(time)].add(tid)
    serial = {w for w, tids in threads.items() if len(tids) == 1}
    in_serial = [s for s in samples if window_of(s[1]) in serial]
    print(f"wall {wall:.3f} s in {len(threads)} windows of {args.window} s; serial {len(serial) * args.window:.3f} s "
          f"({100 * len(serial) * args.window / wall:.0f}%), {len(in_serial)} samples")
    counts = collections.Counter()
    for _, _, frames in in_serial:
        counts.update({f for f in frames if f.startswith(("vm::", "vmcli::")) or "clear_page" in f or "memset" in f})
    for name, n in counts.most_common(args.top):
        print(f"{100 * n / max(len(in_serial), 1):5.1f}%  {name[:120]}")


if __name__ == "__main__":
    main()
