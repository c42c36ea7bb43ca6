#!/usr/bin/python3
"""What memory touched for the first time costs on this machine, and whether it depends on how
long ago other processes freed theirs (docs/benchmarks.md, "fresh memory").

A virtual machine whose host takes back the pages its guest frees (free page reporting: the
guest's balloon driver hands a page back once it has been free for a second or so) pays the host
for every page it touches afresh: a run that follows another at once gets the pages the first
freed, a run after a pause gets pages the host must find and zero again. rtsim's heap grows in
2 MiB pages (app/heap_pages.cpp), so its runs pay this per megabyte of heap.

Each round maps `--mb` MiB of anonymous memory (advised for huge pages, as rtsim's heap is),
writes a byte in every 4 KiB page, and prints the milliseconds a MiB took; then the same for a
second mapping at once, after the first is freed, and again after `--pause` seconds.

    /usr/bin/python3 bench/fresh_memory.py [--mb 512] [--pause 3] [--rounds 3]
"""
import argparse
import mmap
import sys
import time

PAGE = 4096


def touch_ms_per_mb(mb):
    size = mb << 20
    m = mmap.mmap(-1, size, flags=mmap.MAP_PRIVATE | mmap.MAP_ANONYMOUS)
    if hasattr(m, "madvise") and hasattr(mmap, "MADV_HUGEPAGE"):
        m.madvise(mmap.MADV_HUGEPAGE)
    start = time.perf_counter()
    for offset in range(0, size, PAGE):
        m[offset] = 1
    elapsed = time.perf_counter() - start
    m.close()
    return elapsed * 1000.0 / mb


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--mb", type=int, default=512, help="MiB touched each time (default 512)")
    parser.add_argument("--pause", type=float, default=3.0,
                        help="seconds between the freeing and the paused touch (default 3)")
    parser.add_argument("--rounds", type=int, default=3, help="rounds (default 3)")
    args = parser.parse_args()
    if not 1 <= args.mb <= 65536 or args.pause < 0 or not 1 <= args.rounds <= 100:
        print("fresh_memory.py: --mb must be 1..65536, --pause >= 0, --rounds 1..100",
              file=sys.stderr)
        return 2
    print("| round | first touch | again at once | after a %.1f s pause |" % args.pause)
    print("|---|---:|---:|---:|")
    for r in range(args.rounds):
        first = touch_ms_per_mb(args.mb)
        again = touch_ms_per_mb(args.mb)
        time.sleep(args.pause)
        paused = touch_ms_per_mb(args.mb)
        print("| %d | %.3f ms/MiB | %.3f ms/MiB | %.3f ms/MiB |" % (r + 1, first, again, paused))
    return 0


if __name__ == "__main__":
    sys.exit(main())
