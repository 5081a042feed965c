#!/usr/bin/python3
"""Writes the seed corpus of fuzz/fuzz_pipeline.cpp into fuzz/pipeline-seeds/ (or the folder
given): one input per case the target is meant to reach (the larger ones at a coarser edge length) — crossings, coincident and nearly
coincident curves, touching ends, tiny crossing angles, tiny and huge curves, extreme scales, and a
dense soup of 100 cubics. Each input is written in the target's layout (see its header): the
values in the order the target reads them, stored from the last byte backwards.

usage: fuzz/pipeline-seeds.py [FOLDER]
"""
import os
import random
import sys


class Input:
    def __init__(self, scale_exponent, coarseness=0):
        self.read = []  # bytes in the order the target consumes them
        self.byte(scale_exponent + 6)  # ConsumeIntegralInRange(-6, 12)
        self.byte(coarseness)  # ConsumeIntegralInRange(0, 3): l = 1/20, 1/10, 1/5, 1/2

    def byte(self, b):
        self.read.append(b & 0xFF)
        return self

    def coordinate(self, x):
        """x in [-1, 1): a 16-bit fraction of the scale, most significant byte first."""
        u = max(0, min(65535, round((x + 1.0) * 32768)))
        return self.byte(u >> 8).byte(u & 0xFF)

    def point(self, x, y):
        return self.coordinate(x).coordinate(y)

    def op(self, k):
        return self.byte(k)

    def bytes(self):
        return bytes(reversed(self.read))


def cubic(s, *xy):
    s.op(0)
    for k in range(4):
        s.point(xy[2 * k], xy[2 * k + 1])


def segment(s, ax, ay, bx, by):
    s.op(1).point(ax, ay).point(bx, by)


def seeds():
    out = {}
    # A square and a loop through it: ordinary crossings.
    s = Input(0)
    for a, b in [((-.5, -.5), (.5, -.5)), ((.5, -.5), (.5, .5)), ((.5, .5), (-.5, .5)), ((-.5, .5), (-.5, -.5))]:
        segment(s, *a, *b)
    cubic(s, -.8, 0, -.2, .9, .2, -.9, .8, 0)
    out["square-and-loop"] = s
    # The same curve three times (again, reversed) at coordinates near 1e12.
    s = Input(12, 2)
    cubic(s, -.9, -.1, -.3, .8, .3, -.8, .9, .1)
    s.op(2).byte(0)
    s.op(7).byte(0)
    out["coincident-1e12"] = s
    # A curve and its copy 1e-15 of the scale away, at 1e-6.
    s = Input(-6, 1)
    cubic(s, -.9, -.1, -.3, .8, .3, -.8, .9, .1)
    s.op(3).byte(0).byte(6).byte(1)  # earlier 0, 10^-(9+6), up
    s.op(3).byte(0).byte(0).byte(0)  # earlier 0, 10^-9, down
    out["nearly-coincident-1e-6"] = s
    # A chain of cubics, each starting where the one before ends.
    s = Input(3, 1)
    cubic(s, -.9, -.9, -.5, -.2, -.4, .3, -.2, .1)
    for k in range(6):
        s.op(4).byte(k).point(.1 * k, .5).point(-.3, .1 * k).point(.15 * k - .3, .8 - .2 * k)
    out["touching-chain"] = s
    # Segments crossing a cubic at 1e-1 … 1e-12 radians.
    s = Input(1, 1)
    cubic(s, -.9, 0, -.3, .2, .3, -.2, .9, 0)
    for k, e in enumerate([0, 3, 6, 9, 11]):
        s.op(5).byte(0).byte(40 + 40 * k).byte(e).byte(k % 4)
    out["tiny-angles"] = s
    # Tiny cubics beside a huge one.
    s = Input(0)
    cubic(s, -.9, -.9, -.3, .9, .3, -.9, .9, .9)
    s.op(6).point(.1, .1).byte(0).byte(3)
    s.op(6).point(-.2, .3).byte(6).byte(250)
    s.op(9).byte(3).point(-.9, .2).point(.1, .9).point(.5, -.9).point(.9, -.2)
    out["tiny-and-huge"] = s
    # Segments from points inside earlier curves, fanning out.
    s = Input(-3, 1)
    cubic(s, -.9, 0, -.3, .9, .3, -.9, .9, 0)
    for k in range(8):
        s.op(8).byte(k % (k + 1)).byte(30 * k).point(-.8 + .2 * k, .9 if k % 2 else -.9)
    out["fans"] = s
    # 100 random cubics, all over the square: many crossings.
    rnd = random.Random(20)
    s = Input(2, 3)
    for _ in range(100):
        cubic(s, *[rnd.uniform(-1, 1) for _ in range(8)])
    out["dense-100"] = s
    # Every operation once, in a mixed soup.
    rnd = random.Random(7)
    s = Input(6, 2)
    cubic(s, -.5, -.5, 0, .5, .5, -.5, .9, .5)
    for k in range(1, 40):
        s.op(k % 10)
        s.read += [rnd.randrange(256) for _ in range(9)]
    out["mixed"] = s
    return out


def main():
    folder = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                                                 "pipeline-seeds")
    os.makedirs(folder, exist_ok=True)
    for name, s in seeds().items():
        with open(os.path.join(folder, name), "wb") as f:
            f.write(s.bytes())
    print(f"{len(seeds())} seeds in {folder}")


if __name__ == "__main__":
    main()
