#!/usr/bin/env python3
"""Writes a long, deterministic G-code program for the planner benchmark (default 100 000 lines).

The tool wanders over the ch5 hexapod's comfortable range like a finishing path would: mostly short G1 lines
(0.2-2 mm), tangent G2/G3 arcs (radius 2-12 mm, 15-120 degrees), a new feed (500-3000 mm/min) every few dozen
blocks, a slow drift in Z, and now and then a small A/B tilt. Everything stays within +-50 mm in X/Y,
+-10 mm in Z and +-5 degrees in A/B around program zero. A fixed seed makes every run write the same file.
The output is generated, not committed: run this script where the benchmark needs the program.

Usage: scripts/gen-long-program.py OUTPUT [LINE_COUNT]   (standard library only)
"""
import math
import random
import sys

SEED = 20190705
XY_LIMIT = 48.0  # turn back before +-50 mm
Z_LIMIT = 9.5
TILT_LIMIT = 5.0  # degrees
HEADER = [
    "(long benchmark program written by scripts/gen-long-program.py; deterministic, seed {})".format(SEED),
    "G21 G90 G17 G94",
    "G0 Z10",
    "G0 X0 Y0",
    "G0 Z0",
]
FOOTER = ["G0 Z10", "M2"]


def num(v):
    """Four decimals like a CAM post; the state keeps the rounded value so that arcs start where the file says."""
    text = "{:.4f}".format(v).rstrip("0").rstrip(".")
    return "0" if text in ("-0", "") else text


def rounded(v):
    return float(num(v))


class Walker:
    def __init__(self, rng):
        self.rng = rng
        self.x = self.y = self.z = 0.0
        self.a = self.b = 0.0
        self.heading = 0.0  # radians, direction of travel in XY
        self.feed = 1200.0
        self.feed_due = True  # the first cutting block must carry an F word

    def inside(self, x, y):
        return abs(x) <= XY_LIMIT and abs(y) <= XY_LIMIT

    def feed_word(self):
        if self.feed_due:
            self.feed_due = False
            return " F{}".format(num(self.feed))
        return ""

    def line(self):
        rng = self.rng
        self.heading += rng.gauss(0.0, 0.25)
        length = rng.uniform(0.2, 2.0)
        x = self.x + length * math.cos(self.heading)
        y = self.y + length * math.sin(self.heading)
        if not self.inside(x, y):  # head back towards the middle, with some spread
            self.heading = math.atan2(-self.y, -self.x) + rng.uniform(-0.6, 0.6)
            x = self.x + length * math.cos(self.heading)
            y = self.y + length * math.sin(self.heading)
        z = self.z + rng.uniform(-0.05, 0.05)
        if abs(z) > Z_LIMIT:
            z = self.z - math.copysign(0.05, self.z)
        words = "G1 X{} Y{} Z{}".format(num(x), num(y), num(z))
        if rng.random() < 0.01:  # a small tilt now and then
            self.a = max(-TILT_LIMIT, min(TILT_LIMIT, self.a + rng.uniform(-1.0, 1.0)))
            self.b = max(-TILT_LIMIT, min(TILT_LIMIT, self.b + rng.uniform(-1.0, 1.0)))
            self.a, self.b = rounded(self.a), rounded(self.b)
            words += " A{} B{}".format(num(self.a), num(self.b))
        self.x, self.y, self.z = rounded(x), rounded(y), rounded(z)
        return words + self.feed_word()

    def arc(self):
        """A G2/G3 tangent to the current heading; None if it would leave the range."""
        rng = self.rng
        ccw = rng.random() < 0.5
        radius = rng.uniform(2.0, 12.0)
        sweep = math.radians(rng.uniform(15.0, 120.0))
        side = 1.0 if ccw else -1.0  # the centre lies left of the heading for G3, right for G2
        cx = self.x - side * radius * math.sin(self.heading)
        cy = self.y + side * radius * math.cos(self.heading)
        start_angle = math.atan2(self.y - cy, self.x - cx)
        end_angle = start_angle + side * sweep
        x = cx + radius * math.cos(end_angle)
        y = cy + radius * math.sin(end_angle)
        # The whole arc must stay inside: check its extreme points along the way.
        for k in range(1, 9):
            t = start_angle + side * sweep * k / 8.0
            if not self.inside(cx + radius * math.cos(t), cy + radius * math.sin(t)):
                return None
        x, y = rounded(x), rounded(y)
        i, j = cx - self.x, cy - self.y
        self.x, self.y = x, y
        self.heading = end_angle + side * math.pi / 2.0
        return "{} X{} Y{} I{} J{}".format("G3" if ccw else "G2", num(x), num(y), num(i), num(j)) + self.feed_word()

    def block(self):
        rng = self.rng
        if rng.random() < 0.02:
            self.feed = float(rng.randint(50, 300) * 10)  # 500..3000 mm/min
            self.feed_due = True
        if rng.random() < 0.15:
            words = self.arc()
            if words is not None:
                return words
        return self.line()


def main():
    if len(sys.argv) < 2 or len(sys.argv) > 3:
        sys.exit("usage: gen-long-program.py OUTPUT [LINE_COUNT]")
    count = int(sys.argv[2]) if len(sys.argv) == 3 else 100000
    if count < len(HEADER) + len(FOOTER):
        sys.exit("LINE_COUNT must be at least {}".format(len(HEADER) + len(FOOTER)))
    walker = Walker(random.Random(SEED))
    with open(sys.argv[1], "w", encoding="ascii", newline="\n") as out:
        out.write("\n".join(HEADER) + "\n")
        for _ in range(count - len(HEADER) - len(FOOTER)):
            out.write(walker.block() + "\n")
        out.write("\n".join(FOOTER) + "\n")


if __name__ == "__main__":
    main()
