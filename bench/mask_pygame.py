# bench/mask_pygame.py DIR ROUND — pygame.mask's side of the mask overlap
# benchmark (bench/mask_bench.lua runs it): the same PNG masks as tether's
# (bench_mask.c writes them), the same calls and offsets, ns per call as
# "case call median min max" lines. Run by Debian's /usr/bin/python3 with
# python3-pygame (2.1.2).
import os
import sys
import time

os.environ.setdefault("PYGAME_HIDE_SUPPORT_PROMPT", "1")
os.environ.setdefault("SDL_VIDEODRIVER", "dummy")
import pygame  # noqa: E402

d = sys.argv[1]


def load(name):
    return pygame.mask.from_surface(pygame.image.load(os.path.join(d, name)), 127)


def timed(fn):
    n = 1
    while True:
        t0 = time.perf_counter()
        fn(n)
        dt = time.perf_counter() - t0
        if dt >= 0.02:
            break
        n *= 4
    ts = [dt / n]
    for _ in range(6):
        t0 = time.perf_counter()
        fn(n)
        ts.append((time.perf_counter() - t0) / n)
    ts.sort()
    return ts[3] * 1e9, ts[0] * 1e9, ts[-1] * 1e9


def run():
    for s in (32, 128, 512, 1024):
        for kind in ("random", "solid"):
            a, b = load("mask_%s_a_%d.png" % (kind, s)), load("mask_%s_b_%d.png" % (kind, s))
            for align in ("unaligned", "aligned"):
                off = (13, 7) if align == "unaligned" else (0, 7)
                for call in ("overlap", "overlap_area", "overlap_mask"):
                    f = getattr(a, call)

                    def loop(n, f=f, off=off):
                        for _ in range(n):
                            f(b, off)
                    med, lo, hi = timed(loop)
                    print("%s-%d-%s %s %.1f %.1f %.1f" % (kind, s, align, call, med, lo, hi), flush=True)
    a = load("mask_worst_a.png")
    bs = [load("mask_worst_%d.png" % k) for k in range(8)]
    offs = [tuple(int(v) for v in line.split()) for line in open(os.path.join(d, "mask_worst.txt"))]
    for k in range(8):
        assert a.overlap(bs[k], offs[k]) is None, "worst case shares a bit"
    pairs = list(zip(bs, offs))

    def worst(n):
        for i in range(n):
            b, off = pairs[i & 7]
            a.overlap(b, off)
    med, lo, hi = timed(worst)
    print("worst-1024 overlap %.1f %.1f %.1f" % (med, lo, hi), flush=True)


run()
