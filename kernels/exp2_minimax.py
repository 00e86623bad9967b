#!/usr/bin/env python3
"""The polynomial of the near-light sweep's 2^f (slut_nl_lanes_exp2, kernels/slut_nearlight_lanes.h).

    python3 kernels/exp2_minimax.py            # prints the coefficients as C hex literals
    python3 kernels/exp2_minimax.py --check    # recomputes them, compares with the header

2^f on [-1/2, 1/2] as 1 + f*P(f), P of degree DEGREE - 1, chosen to minimise the largest
relative error |1 + f*P(f) - 2^f| / 2^f (Remez's exchange algorithm on the weighted error
(P - (2^f - 1)/f) * |f| / 2^f, 60 digits). The constant term is 1 exactly, so 2^0 = 1 and the
rounding of the last Horner step is the only error near f = 0. Degree 10: 2.20e-16 with exact
coefficients, 2.23e-16 after rounding them to doubles (degree 11 would give 3.4e-18 and
2.8e-17, for one more multiply-add per element: ~2.4 % of the E3 kernel's time).
Needs python3 and mpmath (Debian: python3-mpmath); --check exits 77 (CTest's skip code)
without mpmath, 1 if the header's constants are not these.
"""

import argparse
import os
import re
import sys

SKIP = 77

try:
    import mpmath
    from mpmath import mp, mpf
except ImportError as exc:  # pragma: no cover - depends on the machine
    if "--check" in sys.argv[1:]:
        print("skipped: python module mpmath not found (%s; Debian: apt-get install python3-mpmath)" % exc)
        sys.exit(SKIP)
    sys.exit("exp2_minimax.py: needs the python module mpmath (Debian: apt-get install python3-mpmath): %s" % exc)

HERE = os.path.dirname(os.path.abspath(__file__))
HEADER = os.path.join(HERE, "slut_nearlight_lanes.h")
DEGREE = 10
HALF = mpf(1) / 2
GRID = 3000  # points of the search for the error's extrema


def p_of(c, f):
    """P(f) = c[0] + c[1] f + ... (c[k] is the coefficient of f^(k+1) in 2^f)."""
    s = mpf(0)
    for ck in reversed(c):
        s = s * f + ck
    return s


def slope(f):
    """(2^f - 1)/f, ln 2 at 0."""
    return (mpmath.power(2, f) - 1) / f if f != 0 else mpmath.log(2)


def weighted_error(c, f):
    """The relative error of 1 + f*P(f) against 2^f, signed as P - (2^f - 1)/f."""
    return (p_of(c, f) - slope(f)) * abs(f) / mpmath.power(2, f)


def relative_error(c, f):
    return (1 + f * p_of(c, f) - mpmath.power(2, f)) / mpmath.power(2, f)


def extrema(c):
    """One point of largest |error| per run of one sign on [-1/2, 1/2] (a grid, then a
    golden-section search next to each grid maximum)."""
    grid = sorted([-HALF + (i + mpf(1) / 7) / GRID for i in range(GRID)] + [-HALF, HALF])
    runs, best = [], None
    for f in grid:
        e = weighted_error(c, f)
        if best is not None and (e > 0) == (best[1] > 0):
            if abs(e) > abs(best[1]):
                best = (f, e)
        else:
            if best is not None:
                runs.append(best)
            best = (f, e)
    runs.append(best)
    points = []
    for f, e in runs:
        lo, hi = max(-HALF, f - mpf(1) / GRID), min(HALF, f + mpf(1) / GRID)
        for _ in range(60):
            m1, m2 = hi - (hi - lo) * mpf("0.6180339887"), lo + (hi - lo) * mpf("0.6180339887")
            if abs(weighted_error(c, m1)) > abs(weighted_error(c, m2)):
                hi = m2
            else:
                lo = m1
        mid = (lo + hi) / 2
        points.append(mid if abs(weighted_error(c, mid)) >= abs(e) else f)
    return points


def minimax():
    """Remez's exchange: coefficients c (of f^1 .. f^DEGREE) and the levelled error."""
    n = DEGREE
    # Start: Chebyshev-like points, none at f = 0 (where the weight vanishes).
    points = [-HALF * mpmath.cos(mpmath.pi * (i + mpf(1) / 5) / (n + mpf(1) / 2)) for i in range(n + 1)]
    for _ in range(40):
        m, b = mpmath.matrix(n + 1, n + 1), mpmath.matrix(n + 1, 1)
        for i, f in enumerate(points):
            for k in range(n):
                m[i, k] = f**k
            m[i, n] = -((-1) ** i) * mpmath.power(2, f) / abs(f)
            b[i] = slope(f)
        solution = mpmath.lu_solve(m, b)
        c, level = [solution[k] for k in range(n)], abs(solution[n])
        found = extrema(c)
        if len(found) < n + 1:
            raise RuntimeError("Remez: %d alternation points, %d needed" % (len(found), n + 1))
        if len(found) > n + 1:  # the n + 1 consecutive points whose smallest |error| is largest
            found = max((found[s : s + n + 1] for s in range(len(found) - n)),
                        key=lambda run: min(abs(weighted_error(c, f)) for f in run))
        worst = max(abs(weighted_error(c, f)) for f in found)
        points = found
        if worst - level <= level * mpf(10) ** -8:
            return c, worst
    raise RuntimeError("Remez did not level the error in 40 exchanges")


def header_coefficients():
    """The coefficients in the header, between the markers exp2 polynomial begin/end."""
    with open(HEADER, encoding="utf-8") as f:
        text = f.read()
    block = re.search(r"exp2 polynomial begin(.*?)exp2 polynomial end", text, re.S)
    if not block:
        sys.exit("exp2_minimax.py: %s has no 'exp2 polynomial begin' ... 'end' block" % HEADER)
    return [float.fromhex(h) for h in re.findall(r"(-?0x1\.[0-9a-f]+p[-+]?[0-9]+)", block.group(1))]


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true", help="compare with the header's coefficients")
    args = parser.parse_args()
    mp.dps = 60
    c, level = minimax()
    rounded = [float(ck) for ck in c]
    worst_rounded = max(abs(relative_error([mpf(x) for x in rounded], -HALF + i / mpf(20000)))
                        for i in range(20001))
    print("degree %d on [-1/2, 1/2]: minimax relative error %s, %s with double coefficients"
          % (DEGREE, mpmath.nstr(level, 3), mpmath.nstr(worst_rounded, 3)))
    if args.check:
        have = header_coefficients()
        if have != list(reversed(rounded)):
            print("FAIL: %s holds %s, the minimax polynomial is %s (highest power first)"
                  % (HEADER, [x.hex() for x in have], [x.hex() for x in reversed(rounded)]))
            return 1
        print("ok: the header's %d coefficients are the minimax polynomial's" % len(have))
        return 0
    for k in reversed(range(DEGREE)):
        print("    %s, /* f^%d */" % (rounded[k].hex(), k + 1))
    return 0


if __name__ == "__main__":
    sys.exit(main())
