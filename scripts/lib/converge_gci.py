"""The arithmetic of a refinement study: observed order, Richardson extrapolate and Grid
Convergence Index (GCI) of the finest level, with the convergence verdict. No file I/O.

Notation of Celik et al. (2008), J. Fluids Eng. 130, 078001, "Procedure for estimation and
reporting of uncertainty due to discretization in CFD applications": level 1 the finest,
3 the coarsest of the three finest levels; r21 = h2/h1, r32 = h3/h2 (> 1);
eps21 = phi2 - phi1, eps32 = phi3 - phi2; s = sign(eps32/eps21);
    p = |ln|eps32/eps21| + q(p)| / ln r21,   q(p) = ln((r21^p - s)/(r32^p - s))      (Celik 5)
    phi_ext = (r21^p phi1 - phi2)/(r21^p - 1)                                        (Celik 6)
    GCI_fine = Fs |eps21| / (r21^p - 1)          (absolute; Celik divides by |phi1|)  (Celik 7)
with the safety factor Fs = 1.25 for three or more levels and 3 for two (Roache 1994, 1998;
ASME V&V 20-2009).

The verdict (status), from the three finest levels:
  asymptotic      0 < eps21/eps32 < 1 and the observed order within ORDER_WINDOW (relative)
                  of the scheme's formal order (refining time and space together: of the
                  range between the two orders): Fs = 1.25 with the observed order (Celik)
  not_asymptotic  monotone convergence at an order far from the formal one, or only two
                  levels (no order can be observed): Fs = 3 (Roache's fall-back)
  oscillatory     eps21/eps32 < 0 (the differences change sign), and |eps21| < |eps32|: Fs = 3,
                  and the band at most Fs |eps21| (below)
  diverging       |eps21| >= |eps32|: the differences do not shrink; no extrapolate, no band
  unchanged       the three finest levels agree to round-off (|eps21|, |eps32| <= ROUNDOFF
                  |phi|): no order can be observed (it is nan), nothing is converging at any
                  order; the band is of the differences' size (Fs = 1.25 with the formal order)
  first_step      (converge.py, event times) the event lies in the first time step on every
                  level: its time is the step's, not the solution's (the contact starts at
                  t = 0 or within the first step); no order, extrapolate or band
In the Fs = 3 cases the order used is p_used = min(max(P_MIN, p), p_formal) (never more
than the formal order, the lower one of a range, never below P_MIN), applied to the larger of |eps21| and
|eps32| / r32^p_used (the next difference scaled to the finest level), so that a ladder whose
two finest levels agree by accident still gets a band.
Oscillatory convergence: read as errors e_k = phi_k - phi that alternate in sign from level
to level (the model behind the sign test), the exact value lies between the two finest
levels, so |e1| <= |eps21| (for fields: <e1, e2> <= 0 gives ||e1||^2 <= ||e1||^2 + ||e2||^2
- 2 <e1, e2> = ||eps21||^2). The band is therefore min(Fs delta / (r21^p_used - 1),
Fs |eps21|): the order-based band capped at Fs times that bound, which it exceeds whenever
r21^p_used < 2 (p_used < 1 for r21 = 2) — a bound from the oscillation's range instead of an
extrapolation with an uncertain order. Stern et al. (2001), J. Fluids Eng. 123, 793-802,
bound the error of oscillatory convergence by the oscillation's range too (half the range of
the levels' solutions).

Fields: the same with vectors on a common grid; |eps| becomes the L2 norm over the rod and s
the sign of the inner product <eps32, eps21>.
"""

import math

import numpy as np

FS_THREE = 1.25          # safety factor, three or more levels, asymptotic (Roache; ASME V&V 20)
FS_TWO = 3.0             # safety factor, two levels or outside the asymptotic range
ORDER_WINDOW = 0.25      # |p - p_formal| <= ORDER_WINDOW * p_formal counts as asymptotic
P_MIN = 0.5              # the smallest order a Fs = 3 band assumes
ROUNDOFF = 1e-11         # differences below ROUNDOFF * |phi| are round-off: converged

STATUSES = ("asymptotic", "not_asymptotic", "oscillatory", "diverging", "unchanged", "first_step")


def observed_order(e21, e32, r21, r32, s=None, iterations=200, tol=1e-12):
    """Celik's observed order p from |eps21|, |eps32| (> 0) and the ratios r21, r32, by the
    fixed-point iteration of his eq. (5) (one step when r21 = r32). s: the sign of
    eps32/eps21 (+1 when None). Returns p (may be <= 0 when the differences grow)."""
    s = 1.0 if s is None else math.copysign(1.0, s)
    ratio = math.log(abs(e32) / abs(e21))
    if abs(r21 - r32) < 1e-12 * r21:
        return ratio / math.log(r21)
    p = ratio / math.log(r21)
    for _ in range(iterations):
        try:
            q = math.log((r21 ** p - s) / (r32 ** p - s))
        except (ValueError, ZeroDivisionError, OverflowError):
            break
        p_new = (ratio + q) / math.log(r21)
        if abs(p_new - p) <= tol * max(1.0, abs(p)):
            return p_new
        p = p_new
    return p


def formal_range(p_formal):
    """(lo, hi) of a formal order given as a number or as a pair: refining time and space
    together, the error C_t dt^pt + C_h h^ps converges at an order between pt and ps."""
    if isinstance(p_formal, (tuple, list)):
        return float(min(p_formal)), float(max(p_formal))
    return float(p_formal), float(p_formal)


def verdict(e21, e32, s, r21, r32, p_formal, scale, trusted=True):
    """(status, p_observed, p_used, fs, delta) for the magnitudes |eps21| = e21, |eps32| = e32
    (None for two levels) and the sign s of eps32/eps21; delta is the difference the band is
    built on, band = fs delta / (r21^p_used - 1) (see the module's docstring); scale: |phi| for the round-off test. trusted =
    False (an inconsistent ladder): never asymptotic."""
    tiny = ROUNDOFF * scale
    if e32 is None:                                   # two levels: formal order, Fs = 3
        return "not_asymptotic", math.nan, formal_range(p_formal)[0], FS_TWO, e21
    if e21 <= tiny and e32 <= tiny:                   # identical to round-off: no order to observe
        return ("unchanged" if trusted else "not_asymptotic"), math.nan, formal_range(p_formal)[0], FS_THREE, e21
    if e21 <= tiny:                                   # the two finest agree, the next do not
        p = math.inf
    else:
        p = observed_order(e21, e32, r21, r32, s)
    if e21 >= e32 or p <= 0:
        return "diverging", p, math.nan, math.nan, e21
    lo, hi = formal_range(p_formal)
    p_used = min(max(P_MIN, p), lo)
    delta = max(e21, e32 / r32 ** p_used)
    if s < 0:                                         # the band at most FS_TWO e21 (docstring)
        return "oscillatory", p, p_used, FS_TWO, min(delta, e21 * (r21 ** p_used - 1.0))
    if trusted and lo * (1 - ORDER_WINDOW) <= p <= hi * (1 + ORDER_WINDOW):
        return "asymptotic", p, p, FS_THREE, e21
    return "not_asymptotic", p, p_used, FS_TWO, delta


def scalar(phis, hs, p_formal, trusted=True):
    """The study of one scalar: phis[k], hs[k] for the levels, finest LAST (any number >= 2).
    Returns dict fine, extrapolated, observed_order, gci_abs, gci_rel, status (the three
    finest levels decide)."""
    phi1, phi2 = float(phis[-1]), float(phis[-2])
    r21 = hs[-2] / hs[-1]
    e21 = abs(phi2 - phi1)
    if len(phis) >= 3:
        phi3 = float(phis[-3])
        r32 = hs[-3] / hs[-2]
        e32 = abs(phi3 - phi2)
        s = math.copysign(1.0, (phi3 - phi2) * (phi2 - phi1)) if e21 > 0 and e32 > 0 else 1.0
    else:
        r32, e32, s = r21, None, 1.0
    scale = max(abs(phi1), abs(phi2))
    status, p, p_used, fs, delta = verdict(e21, e32, s, r21, r32, p_formal, scale, trusted)
    return finish(phi1, phi2, r21, status, p, p_used, fs, delta, abs(phi1))


def finish(phi1, phi2, r21, status, p, p_used, fs, delta, norm1):
    """The row of a study from its verdict: extrapolate with p_used (none when diverging),
    gci_abs = fs delta / (r21^p_used - 1), gci_rel = gci_abs / norm1."""
    if status == "diverging" or not math.isfinite(p_used):
        ext, gci = math.nan, math.nan
    else:
        rp = r21 ** p_used
        ext = (rp * phi1 - phi2) / (rp - 1.0)
        gci = fs * delta / (rp - 1.0)
    if norm1 > 0:
        rel = gci / norm1
    else:
        rel = 0.0 if gci == 0 else math.inf
    return {"fine": phi1, "extrapolated": ext, "observed_order": p, "gci_abs": gci,
            "gci_rel": rel, "status": status}


def weights(x):
    """The trapezoidal-rule weights of the grid x: integral of f = sum(weights * f)."""
    w = np.empty_like(x, dtype=float)
    dx = np.diff(x)
    w[0], w[-1] = dx[0] / 2, dx[-1] / 2
    w[1:-1] = (dx[:-1] + dx[1:]) / 2
    return w


def l2(values, x):
    """The L2 norm over the rod of nodal values on the grid x (trapezoidal rule)."""
    return math.sqrt(float(np.sum(weights(x) * values * values)))


def field(fs, hs, x, p_formal, trusted=True):
    """The study of one field at one time: fs[k] the nodal values of level k on the common
    grid x, finest LAST. Row: fine = ||f1||, extrapolated = ||f_ext|| (the Richardson field),
    observed_order from ||eps32|| / ||eps21||, gci_abs the band on ||f1 - f||, gci_rel =
    gci_abs / ||f1||, status as for scalars with s = sign <eps32, eps21>."""
    f1, f2 = np.asarray(fs[-1], float), np.asarray(fs[-2], float)
    d21 = f2 - f1
    e21 = l2(d21, x)
    r21 = hs[-2] / hs[-1]
    norm1 = l2(f1, x)
    if len(fs) >= 3:
        d32 = np.asarray(fs[-3], float) - f2
        e32 = l2(d32, x)
        r32 = hs[-3] / hs[-2]
        inner = float(np.sum(weights(x) * d32 * d21))
        s = math.copysign(1.0, inner) if e21 > 0 and e32 > 0 else 1.0
    else:
        r32, e32, s = r21, None, 1.0
    status, p, p_used, fsafe, delta = verdict(e21, e32, s, r21, r32, p_formal, max(norm1, l2(f2, x)),
                                              trusted)
    row = finish(norm1, math.nan, r21, status, p, p_used, fsafe, delta, norm1)
    if math.isfinite(p_used) and status != "diverging":
        rp = r21 ** p_used
        row["extrapolated"] = l2((rp * f1 - f2) / (rp - 1.0), x)
    return row
