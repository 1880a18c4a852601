#!/usr/bin/env python3
"""The golden vessel profile of docs/math/curves.md section 2, for bench/vessel_vs_openscad.sh.

Quasi-cubic uniform B-spline, control points p0..p4 = (1.5,6),(1,5),(2,4),(3,3),(1.5,2)
in (radius, height), interior lambdas 0 (ends 4), scaled to millimetres.

Usage:
  vessel_exact_volume.py volume [--scale S]
      Exact volume (mm^3) of the solid bounded by the axis and the revolved smooth
      profile: V = -pi * integral r(t)^2 z'(t) dt (z falls as t rises), by
      Gauss-Legendre on each span (8 nodes: exact for the degree-11 integrand),
      cross-checked against exact rational integration of the polynomials.
  vessel_exact_volume.py sample K [--scale S] [--grid G] [--min-offset D]
      K points of the profile from p0 (rim, top) to pn (base), rounded to
      multiples of G mm (default 2^-10, see DEFAULT_GRID), one "r z" line each with as many
      decimals as G needs. Points are uniform in the global parameter
      T in [0, n], except that points within D mm (default 1e-4) of the chord
      of their neighbours are dropped (OpenSCAD would drop them), sampling a
      few more until exactly K remain.
  vessel_exact_volume.py selftest
      Checks the evaluator against the golden values of docs/math/curves.md.

Plain Python 3, no third-party modules.
"""
import math
import sys
from fractions import Fraction

GOLDEN = [(1.5, 6.0), (1.0, 5.0), (2.0, 4.0), (3.0, 3.0), (1.5, 2.0)]
DEFAULT_SCALE = 30.0
# OpenSCAD 2021 snaps 2D polygon coordinates down to a 2^-16 mm grid (Clipper's
# fixed-point scale): a decimal grid like 1e-3 mm would shift its vertices by
# ~7.6e-6 mm on average (a -2.3e-7 relative volume bias vs fabmesh). A binary
# grid of 2^-10 mm (~1 um) is kept exactly by both tools and prints exactly
# with 10 decimals.
DEFAULT_GRID = 2.0 ** -10


def supplemented(points):
    return [points[0]] + list(points) + [points[-1]]


def lambdas_for(points, interior=None):
    n = len(points) - 1
    inner = list(interior) if interior is not None else [0] * (n - 1)
    return [4] + inner + [4]


def basis(t, l, m):
    """b_{i,0..3}(t) of docs/math/curves.md section 2 (works on floats and Fractions)."""
    u = 1 - t
    return (
        ((4 - l) * u**4 + 4 * (1 - l) * u**3 * t) / 24,
        (2 * (8 + l) * u**4 + 8 * (8 + l) * u**3 * t + 72 * u**2 * t**2
         + 4 * (7 - m) * u * t**3 + (4 - m) * t**4) / 24,
        ((4 - l) * u**4 + 4 * (7 - l) * u**3 * t + 72 * u**2 * t**2
         + 8 * (8 + m) * u * t**3 + 2 * (8 + m) * t**4) / 24,
        (4 * (1 - m) * u * t**3 + (4 - m) * t**4) / 24,
    )


def basis_deriv(t, l, m):
    """d/dt of basis(), differentiated by hand (u = 1 - t, du/dt = -1)."""
    u = 1 - t
    return (
        (-4 * (4 - l) * u**3 + 4 * (1 - l) * (u**3 - 3 * u**2 * t)) / 24,
        (-8 * (8 + l) * u**3 + 8 * (8 + l) * (u**3 - 3 * u**2 * t)
         + 72 * (2 * u**2 * t - 2 * u * t**2)
         + 4 * (7 - m) * (3 * u * t**2 - t**3) + 4 * (4 - m) * t**3) / 24,
        (-4 * (4 - l) * u**3 + 4 * (7 - l) * (u**3 - 3 * u**2 * t)
         + 72 * (2 * u**2 * t - 2 * u * t**2)
         + 8 * (8 + m) * (3 * u * t**2 - t**3) + 8 * (8 + m) * t**3) / 24,
        (4 * (1 - m) * (3 * u * t**2 - t**3) + 4 * (4 - m) * t**3) / 24,
    )


def span_eval(pts, lam, i, t, deriv=False):
    p = supplemented(pts)
    b = (basis_deriv if deriv else basis)(t, lam[i], lam[i + 1])
    r = sum(b[j] * p[i + j][0] for j in range(4))
    z = sum(b[j] * p[i + j][1] for j in range(4))
    return r, z


def gauss_legendre(n):
    """Nodes and weights on [0, 1] (Newton on P_n)."""
    nodes, weights = [], []
    for k in range(1, n + 1):
        x = math.cos(math.pi * (k - 0.25) / (n + 0.5))
        for _ in range(100):
            p0, p1 = 1.0, x
            for j in range(2, n + 1):
                p0, p1 = p1, ((2 * j - 1) * x * p1 - (j - 1) * p0) / j
            dp = n * (x * p1 - p0) / (x * x - 1)
            dx = p1 / dp
            x -= dx
            if abs(dx) < 1e-16:
                break
        nodes.append(0.5 * (1 - x))
        weights.append(1.0 / ((1 - x * x) * dp * dp))  # 2/((1-x^2)P'^2), halved for [0,1]
    return nodes, weights


def volume_gauss(pts, lam, nodes=8):
    xs, ws = gauss_legendre(nodes)
    total = 0.0
    for i in range(len(pts) - 1):
        for x, w in zip(xs, ws):
            r, _ = span_eval(pts, lam, i, x)
            _, dz = span_eval(pts, lam, i, x, deriv=True)
            total += w * r * r * dz
    # Positive orientation: the region r in [0, r(z)] swept as z rises. The
    # profile may run either way; the solid's volume is |pi * integral r^2 dz|
    # as long as z is monotone (it is for the golden data: pz falls).
    return math.pi * abs(total), total


# --- exact check: polynomial coefficients in Fractions -----------------------

def poly_mul(a, b):
    out = [Fraction(0)] * (len(a) + len(b) - 1)
    for i, x in enumerate(a):
        for j, y in enumerate(b):
            out[i + j] += x * y
    return out


def poly_add(a, b):
    out = [Fraction(0)] * max(len(a), len(b))
    for i, x in enumerate(a):
        out[i] += x
    for i, x in enumerate(b):
        out[i] += x
    return out


def poly_scale(a, s):
    return [x * s for x in a]


def poly_deriv(a):
    return [i * a[i] for i in range(1, len(a))] or [Fraction(0)]


def poly_pow(a, k):
    out = [Fraction(1)]
    for _ in range(k):
        out = poly_mul(out, a)
    return out


def volume_exact_rational(pts, lam):
    """Returns integral r^2 z' dt exactly (a Fraction), pts/lam as Fractions."""
    t = [Fraction(0), Fraction(1)]
    u = [Fraction(1), Fraction(-1)]
    p = supplemented(pts)
    total = Fraction(0)
    for i in range(len(pts) - 1):
        l, m = Fraction(lam[i]), Fraction(lam[i + 1])
        U = [poly_pow(u, k) for k in range(5)]
        T = [poly_pow(t, k) for k in range(5)]

        def term(c, a, b):  # c * u^a * t^b
            return poly_scale(poly_mul(U[a], T[b]), Fraction(c))

        b0 = poly_add(term(4 - l, 4, 0), term(4 * (1 - l), 3, 1))
        b1 = [Fraction(0)]
        for c, a, bb in ((2 * (8 + l), 4, 0), (8 * (8 + l), 3, 1), (72, 2, 2),
                         (4 * (7 - m), 1, 3), (4 - m, 0, 4)):
            b1 = poly_add(b1, term(c, a, bb))
        b2 = [Fraction(0)]
        for c, a, bb in ((4 - l, 4, 0), (4 * (7 - l), 3, 1), (72, 2, 2),
                         (8 * (8 + m), 1, 3), (2 * (8 + m), 0, 4)):
            b2 = poly_add(b2, term(c, a, bb))
        b3 = poly_add(term(4 * (1 - m), 1, 3), term(4 - m, 0, 4))
        bs = [poly_scale(b, Fraction(1, 24)) for b in (b0, b1, b2, b3)]
        r = [Fraction(0)]
        z = [Fraction(0)]
        for j in range(4):
            r = poly_add(r, poly_scale(bs[j], Fraction(p[i + j][0])))
            z = poly_add(z, poly_scale(bs[j], Fraction(p[i + j][1])))
        integrand = poly_mul(poly_mul(r, r), poly_deriv(z))
        total += sum(c / (k + 1) for k, c in enumerate(integrand))
    return total


def scaled(scale):
    return [(x * scale, y * scale) for x, y in GOLDEN]


def exact_volume(scale):
    pts = scaled(scale)
    lam = lambdas_for(pts)
    vol, signed = volume_gauss(pts, lam)
    fr_pts = [(Fraction(x) * Fraction(scale), Fraction(y) * Fraction(scale)) for x, y in GOLDEN]
    exact = volume_exact_rational(fr_pts, lam)
    if abs(float(exact) - signed) > 1e-11 * abs(float(exact)):
        raise SystemExit("vessel_exact_volume.py: Gauss-Legendre %r disagrees with exact %r"
                         % (signed, float(exact)))
    return vol


def decimals_for(grid):
    d = 0
    while d < 12 and abs(round(grid * 10**d) - grid * 10**d) > 1e-9:
        d += 1
    return d


def sample_raw(k, scale, grid):
    pts = scaled(scale)
    lam = lambdas_for(pts)
    n = len(pts) - 1
    out = []
    for j in range(k):
        T = n * j / (k - 1)
        i = min(int(T), n - 1)
        r, z = span_eval(pts, lam, i, T - i)
        r = round(r / grid) * grid
        z = round(z / grid) * grid
        if out and (r, z) == out[-1]:
            raise SystemExit("vessel_exact_volume.py: K=%d too large for grid %g (duplicate point)" % (k, grid))
        out.append((r, z))
    return out


def drop_flat(points, min_offset):
    """Drops interior points closer than min_offset to the chord of their
    neighbours. OpenSCAD's 2D polygon clean-up removes (nearly) collinear
    vertices (observed up to ~2.3e-5 mm off the chord), so without this the two tools would mesh different polylines."""
    pts = list(points)
    changed = True
    while changed:
        changed = False
        keep = [pts[0]]
        for i in range(1, len(pts) - 1):
            a, b, c = keep[-1], pts[i], pts[i + 1]
            cross = (b[0] - a[0]) * (c[1] - a[1]) - (b[1] - a[1]) * (c[0] - a[0])
            if abs(cross) < min_offset * math.hypot(c[0] - a[0], c[1] - a[1]):
                changed = True
                continue
            keep.append(b)
        keep.append(pts[-1])
        pts = keep
    return pts


def sample(k, scale, grid, min_offset):
    """Exactly k points: samples kk >= k points uniformly in T and drops the
    flat ones, adjusting kk until exactly k remain."""
    def count(kk):
        raw = sample_raw(kk, scale, grid)
        return drop_flat(raw, min_offset) if min_offset > 0 else raw

    kk, tried = k, {}
    while kk not in tried and k <= kk <= 4 * k:
        out = count(kk)
        tried[kk] = len(out)
        if len(out) == k:
            return out
        kk += k - len(out) if len(out) < k else -1
    for kk in range(k, 4 * k + 1):  # fallback: plain scan
        out = count(kk)
        if len(out) == k:
            return out
    raise SystemExit("vessel_exact_volume.py: no sample count gives exactly %d points" % k)


def selftest():
    pts = list(GOLDEN)
    lam = lambdas_for(pts)
    golden = [(1.296875, 5.53125), (1.53125, 4.5), (2.447916666667, 3.5), (2.151041666667, 2.46875)]
    for i, (gy, gz) in enumerate(golden):
        r, z = span_eval(pts, lam, i, 0.5)
        assert abs(r - gy) < 1e-9 and abs(z - gz) < 1e-9, (i, r, z)
    # interpolation of the ends, C1 at the joints, derivative vs finite difference
    assert span_eval(pts, lam, 0, 0.0) == (1.5, 6.0)
    r, z = span_eval(pts, lam, 3, 1.0)
    assert abs(r - 1.5) < 1e-12 and abs(z - 2.0) < 1e-12
    for i in range(3):
        a = span_eval(pts, lam, i, 1.0, deriv=True)
        b = span_eval(pts, lam, i + 1, 0.0, deriv=True)
        assert abs(a[0] - b[0]) < 1e-12 and abs(a[1] - b[1]) < 1e-12
        h = 1e-6
        f1, f0 = span_eval(pts, lam, i, 0.3 + h), span_eval(pts, lam, i, 0.3 - h)
        d = span_eval(pts, lam, i, 0.3, deriv=True)
        assert abs((f1[0] - f0[0]) / (2 * h) - d[0]) < 1e-6
    print("ok: golden values, end interpolation, C1 joints, derivatives; V(scale 1) = %.12f"
          % exact_volume(1.0))


def main(argv):
    if not argv or argv[0] in ("-h", "--help"):
        print(__doc__)
        return 0
    cmd, rest = argv[0], argv[1:]
    opts = {"--scale": DEFAULT_SCALE, "--grid": DEFAULT_GRID, "--min-offset": 1e-4}
    pos = []
    it = iter(rest)
    for a in it:
        if a in opts:
            opts[a] = float(next(it))
        else:
            pos.append(a)
    if cmd == "volume":
        print("%.9f" % exact_volume(opts["--scale"]))
    elif cmd == "sample":
        k = int(pos[0])
        if k < 2:
            raise SystemExit("vessel_exact_volume.py: K must be >= 2")
        dec = decimals_for(opts["--grid"])
        for r, z in sample(k, opts["--scale"], opts["--grid"], opts["--min-offset"]):
            print("%.*f %.*f" % (dec, r, dec, z))
    elif cmd == "selftest":
        selftest()
    else:
        raise SystemExit("vessel_exact_volume.py: unknown command %r (volume | sample K | selftest)" % cmd)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
