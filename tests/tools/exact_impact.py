#!/usr/bin/env python3
"""The exact solution of the impact case (input/impact.nml): an elastic bar on [0, 1] with
rho = alpha = 1, no viscosity and no coupling, u(0, t) = 0, u(x, 0) = 0, v(x, 0) = A x, and a
rigid obstacle at u(1, t) = g (Signorini: u(1) <= g, sigma(1) = u_x(1) <= 0, sigma (u(1) - g) = 0).

Derivation (characteristics). u_tt = u_xx with u(0, t) = 0 gives u(x, t) = Phi(t + x) - Phi(t - x);
u(x, 0) = 0 makes Phi even, v(x, 0) = 2 psi(x) with psi = Phi', so psi(xi) = A xi / 2 on [-1, 1].
Then
    v(x, t) = psi(t + x) - psi(t - x),   u_x(x, t) = psi(t + x) + psi(t - x),
    u(1, t) = int_{t-1}^{t+1} psi,       E(t) = int_0^1 (v^2 + u_x^2)/2 dx = int_{t-1}^{t+1} psi^2,
and the end x = 1 fixes psi on [t + 1, ...] from psi(t - 1), known from earlier:
    free end (sigma(1) = 0):     psi(t + 1) = -psi(t - 1),  v(1, t) = -2 psi(t - 1),
    in contact (v(1) = 0):       psi(t + 1) = +psi(t - 1),  sigma(1, t) = 2 psi(t - 1).
A free phase ends (onset) when u(1, t) reaches g; a contact phase ends (release) when
sigma(1, t) = 2 psi(t - 1) reaches 0 from below. psi is piecewise linear (linear initial data,
linear reflections), so u(1, t) is piecewise quadratic and every event is the root of a
quadratic or linear function: the solution below is exact up to round-off, for any g < A/2
(contact happens before t = 1) and any t_end (psi on [-1, t_end + 1] is built).
E(t) = A^2/6 for all t (the reflections keep |psi|).

For g = 0.05, A = 1: onset t1 = 1 - sqrt(1 - 2g/A), sigma(1, t) = -A (1 - t) until the release
at t = 1, u(1, t) = g - A (t - 1)^2 / 2 on [1, 2], next onset t2 = 3 + 2 sqrt(g/A) with
sigma(1, t) = -A (t - 3); `--check` verifies these (and the energy) against the march.

    exact_impact.py --check                      # the closed forms above, several (g, A)
    exact_impact.py --g 0.05 --A 1 --t-end 4     # events and contact intervals
    exact_impact.py compare RUN.h5 [--tv-margin 0.02]   # a run of impact.nml against it
"""
import argparse
import math
import os
import sys

import numpy as np

TINY = 1e-13


class ExactImpact:
    """psi as linear pieces (xi0, xi1, a, b): psi(xi) = a + b (xi - xi0) on [xi0, xi1]; the end's
    phases as (t0, t1, contact, a, b): psi(t - 1) = a + b (t - t0) on [t0, t1]."""

    def __init__(self, g=0.05, A=1.0, t_end=4.0):
        if not (0.0 < g < A / 2.0):
            raise ValueError(f"need 0 < g < A/2 (contact before t = 1): g = {g}, A = {A}")
        self.g, self.A, self.t_end = float(g), float(A), float(t_end)
        self.psi = [(-1.0, 1.0, -A / 2.0, A / 2.0)]
        self.phases = []
        self.events = []          # (t, +1 onset / -1 release)
        self._march()

    def _psi_piece(self, xi):
        """The piece of psi holding xi (the later one at a breakpoint; pieces are contiguous)."""
        if xi < self.psi[0][0] - TINY:
            raise ValueError(f"psi not known at {xi}")
        for p in self.psi:
            if xi < p[1] - TINY:
                return p
        return self.psi[-1]

    def _march(self):
        t, u_end, contact = 0.0, 0.0, False
        g = self.g
        while t < self.t_end - TINY:
            xi0, xi1, a0, b = self._psi_piece(t - 1.0)
            a = a0 + b * (t - 1.0 - xi0)              # psi(t - 1) at tau = 0
            dt_piece = min(xi1 + 1.0 - t, self.t_end - t)
            tau_event = None
            if contact:
                # release: sigma = 2 (a + b tau) reaches 0 from below
                if b > 0.0 and a < 0.0:
                    tau = -a / b
                    if tau <= dt_piece + TINY:
                        tau_event = tau
            else:
                # onset: u(1) = u_end - 2 (a tau + b tau^2 / 2) reaches g while rising
                tau_event = _first_root(b, 2.0 * a, g - u_end, dt_piece)
            dt_phase = dt_piece if tau_event is None else min(tau_event, dt_piece)
            sign = 1.0 if contact else -1.0
            self.psi.append((t + 1.0, t + 1.0 + dt_phase, sign * a, sign * b))
            self.phases.append((t, t + dt_phase, contact, a, b))
            if not contact:
                u_end -= 2.0 * (a * dt_phase + b * dt_phase ** 2 / 2.0)
            t += dt_phase
            if tau_event is not None and tau_event <= dt_piece + TINY and t < self.t_end - TINY:
                contact = not contact
                self.events.append((t, 1 if contact else -1))
                if contact:
                    u_end = g

    # --- evaluation -------------------------------------------------------------------------
    def _phase_at(self, t):
        for ph in self.phases:
            if ph[0] - TINY <= t <= ph[1] + TINY:
                return ph
        raise ValueError(f"t = {t} outside [0, {self.t_end}]")

    def sigma_end(self, t):
        """sigma(1, t) = u_x(1, t): 0 when free, 2 psi(t - 1) in contact (array or scalar)."""
        return np.vectorize(self._sigma_scalar)(np.asarray(t, dtype=float))

    def _sigma_scalar(self, t):
        t0, _, contact, a, b = self._phase_at(t)
        return 2.0 * (a + b * (t - t0)) if contact else 0.0

    def psi_integral(self, lo, hi, power=1):
        """int_lo^hi psi^power dxi (power 1 or 2), exact for the linear pieces."""
        total = 0.0
        for xi0, xi1, a, b in self.psi:
            x0, x1 = max(lo, xi0), min(hi, xi1)
            if x1 <= x0:
                continue
            f0, f1 = a + b * (x0 - xi0), a + b * (x1 - xi0)
            if power == 1:
                total += (f0 + f1) * (x1 - x0) / 2.0
            else:
                total += (f0 * f0 + f0 * f1 + f1 * f1) * (x1 - x0) / 3.0
        return total

    def u(self, x, t):
        """u(x, t) = int_{t-x}^{t+x} psi."""
        return self.psi_integral(t - x, t + x)

    def u_end(self, t):
        return np.vectorize(lambda s: self.u(1.0, s))(np.asarray(t, dtype=float))

    def energy(self, t):
        """E(t) = int_{t-1}^{t+1} psi^2 (= A^2/6)."""
        return self.psi_integral(t - 1.0, t + 1.0, power=2)

    def impulse(self, t):
        """int_0^t sigma(1, s) ds."""
        total = 0.0
        for t0, t1, contact, a, b in self.phases:
            if not contact or t <= t0:
                continue
            tau = min(t, t1) - t0
            total += 2.0 * (a * tau + b * tau * tau / 2.0)
        return total

    def sigma_average(self, t0, t1):
        """(1/(t1 - t0)) int_{t0}^{t1} sigma(1, t) dt for arrays of step ends."""
        t0, t1 = np.asarray(t0, dtype=float), np.asarray(t1, dtype=float)
        imp = np.vectorize(self.impulse)
        return (imp(t1) - imp(t0)) / (t1 - t0)

    def sigma_l2(self):
        """||sigma(1, .)||_{L2(0, t_end)}."""
        total = 0.0
        for t0, t1, contact, a, b in self.phases:
            if contact:
                f0, f1 = 2.0 * a, 2.0 * (a + b * (t1 - t0))
                total += (f0 * f0 + f0 * f1 + f1 * f1) * (t1 - t0) / 3.0
        return math.sqrt(total)

    def contact_intervals(self):
        """[(t_on, t_off)] merged over consecutive contact phases (t_off = t_end if still on)."""
        out = []
        for t0, t1, contact, _, _ in self.phases:
            if not contact:
                continue
            if out and abs(out[-1][1] - t0) < TINY:
                out[-1] = (out[-1][0], t1)
            else:
                out.append((t0, t1))
        return out

    def sigma_tv(self, t_on, t_off):
        """Total variation of sigma(1, .) on the open interval (t_on, t_off) inside contact."""
        values = []
        for t0, t1, contact, a, b in self.phases:
            if not contact or t1 <= t_on + TINY or t0 >= t_off - TINY:
                continue
            lo, hi = max(t0, t_on), min(t1, t_off)
            values += [2.0 * (a + b * (lo - t0)), 2.0 * (a + b * (hi - t0))]
        return float(np.sum(np.abs(np.diff(values))))


def _first_root(qa, qb, qc, limit):
    """Smallest tau in (TINY, limit] with qa tau^2 + qb tau + qc = 0 where the left side rises
    through 0 (the end reaching the obstacle), else None."""
    roots = []
    if abs(qa) < 1e-300:
        if qb != 0.0:
            roots = [-qc / qb]
    else:
        disc = qb * qb - 4.0 * qa * qc
        if disc >= 0.0:
            sq = math.sqrt(disc)
            # stable pair of roots
            q = -0.5 * (qb + math.copysign(sq, qb)) if qb != 0.0 else -0.5 * sq
            cand = [q / qa]
            if q != 0.0:
                cand.append(qc / q)
            roots = cand
    roots = [r for r in roots if 1e-12 < r <= limit + TINY]
    # the quadratic is g - u(1, t): it falls through 0 (the end arriving; grazing included)
    roots = [r for r in roots if 2.0 * qa * r + qb < 0.0 or abs(2.0 * qa * r + qb) < 1e-15]
    return min(roots) if roots else None


# --- checks of the closed forms ----------------------------------------------------------------
def check_closed_forms(pairs=((0.05, 1.0), (0.02, 1.0), (0.1, 0.5), (0.2, 2.0), (0.3, 0.8))):
    """The issue's closed forms against the march; returns a list of failure messages."""
    fails = []

    def close(name, got, want, tol=1e-12):
        if not abs(got - want) <= tol * max(1.0, abs(want)):
            fails.append(f"{name}: {got!r} against {want!r}")

    for g, A in pairs:
        ex = ExactImpact(g, A, 4.0)
        tag = f"g={g} A={A}"
        t1 = 1.0 - math.sqrt(1.0 - 2.0 * g / A)
        t2 = 3.0 + 2.0 * math.sqrt(g / A)
        kinds = [k for _, k in ex.events]
        times = [t for t, _ in ex.events]
        if kinds != ([1, -1, 1] if t2 < 4.0 else [1, -1]):
            fails.append(f"{tag}: events {ex.events}")
            continue
        close(tag + " t1", times[0], t1)
        close(tag + " release", times[1], 1.0)
        if t2 <= 4.0:
            close(tag + " t2", times[2], t2)
        for t in np.linspace(0.0, t1, 7):
            close(tag + f" u(1,{t:.3f}) before contact", float(ex.u_end(t)), A * (t - t * t / 2.0))
        for t in np.linspace(t1, 1.0, 7)[1:-1]:
            close(tag + f" sigma({t:.3f})", float(ex.sigma_end(t)), -A * (1.0 - t))
            close(tag + f" u(1,{t:.3f}) in contact", float(ex.u_end(t)), g)
        for t in np.linspace(1.0, 2.0, 7):
            close(tag + f" u(1,{t:.3f}) on [1,2]", float(ex.u_end(t)), g - A * (t - 1.0) ** 2 / 2.0)
        for t in (np.linspace(t2, 4.0, 5)[1:-1] if t2 < 4.0 else []):
            close(tag + f" sigma({t:.3f}) 2nd contact", float(ex.sigma_end(t)), -A * (t - 3.0))
        for t in np.linspace(0.0, 4.0, 41):
            close(tag + f" E({t:.2f})", ex.energy(t), A * A / 6.0)
            if float(ex.u_end(t)) > g + 1e-14:
                fails.append(f"{tag}: u(1,{t}) = {float(ex.u_end(t))} > g")
        # sigma and v(1) vanish in each other's phases; the impulse is the integral of sigma
        close(tag + " impulse 1st contact", ex.impulse(1.0), -A * (1.0 - t1) ** 2 / 2.0)
    if abs(ExactImpact().sigma_l2() - 0.767) > 5e-4:
        fails.append(f"||sigma|| = {ExactImpact().sigma_l2()} (issue: 0.767)")
    return fails


# --- a run against it ----------------------------------------------------------------------------
def compare_run(path, tv_margin=0.02):
    """Error measures of a run of the impact case (rho = alpha = 1, u(0) = 0, v0 = A x, Signorini
    or penalty) against the exact solution: a dict (see the keys)."""
    sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "scripts", "lib"))
    import rodrun  # noqa: E402
    with rodrun.open_run(path) as f:
        g = float(rodrun.attr_value(f, "contact.g")) if hasattr(rodrun, "attr_value") else float(f.attrs["contact.g"])
        coeffs = f.attrs["initial.u1_poly"]
        A = float(coeffs[1])
        t = f["series/t"][:]
        u_end = f["series/u_end"][:]
        sig = f["series/contact_stress"][:]
        energy = f["series/energy"][:]
        ev_t, ev_k = rodrun.events(f)
        wall = float(f.attrs["wall_seconds"]) if "wall_seconds" in f.attrs else float("nan")
    return measures(ExactImpact(g, A, float(t[-1])), t, u_end, sig, energy, ev_t, ev_k, wall, tv_margin)


def measures(ex, t, u_end, sig, energy, ev_t, ev_k, wall=float("nan"), tv_margin=0.02):
    t = np.asarray(t)
    steps = slice(1, None)
    t0, t1 = t[:-1], t[1:]
    exact_avg = ex.sigma_average(t0, t1)
    dtv = t1 - t0
    err_sig = math.sqrt(np.sum((sig[steps] - exact_avg) ** 2 * dtv))
    ue = ex.u_end(t)
    out = {
        "g": ex.g, "A": ex.A, "t_end": float(t[-1]), "steps": len(t) - 1,
        "u_err": float(np.max(np.abs(u_end - ue))),
        "u_max_minus_g": float(np.max(u_end) - ex.g),
        "sigma_norm": ex.sigma_l2(),
        "sigma_err": err_sig, "sigma_err_rel": err_sig / ex.sigma_l2(),
        "events": len(ev_t), "events_exact": len(ex.events),
        "event_times": [float(x) for x in ev_t], "event_times_exact": [e[0] for e in ex.events],
        "energy_drift": float(energy[-1] / energy[0] - 1.0),
        "energy_max_rise": float(np.max(np.diff(energy) / energy[0])) if len(energy) > 1 else 0.0,
        "wall": wall,
    }
    tvs = []
    for (on, off) in ex.contact_intervals():
        inside = (t0 >= on + tv_margin) & (t1 <= off - tv_margin)
        if np.count_nonzero(inside) < 2:
            continue
        tv_run = float(np.sum(np.abs(np.diff(sig[steps][inside]))))
        tv_exact = float(np.sum(np.abs(np.diff(exact_avg[inside]))))
        tvs.append((on, off, tv_run, tv_exact))
    out["tv"] = tvs
    return out


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("command", nargs="?", choices=["show", "compare"], default="show")
    ap.add_argument("run", nargs="?", help="compare: the run file")
    ap.add_argument("--g", type=float, default=0.05)
    ap.add_argument("--A", type=float, default=1.0)
    ap.add_argument("--t-end", type=float, default=4.0)
    ap.add_argument("--tv-margin", type=float, default=0.02,
                    help="compare: the total variation counts the steps at least this far inside a contact interval")
    ap.add_argument("--check", action="store_true", help="check the closed forms; exit 1 on a mismatch")
    a = ap.parse_args(argv)
    if a.check:
        fails = check_closed_forms()
        for m in fails:
            print("FAIL", m)
        print("exact_impact: closed forms", "FAIL" if fails else "ok")
        return 1 if fails else 0
    if a.command == "compare":
        if not a.run:
            ap.error("compare needs a run file")
        m = compare_run(a.run, a.tv_margin)
        for k, v in m.items():
            print(f"{k} = {v}")
        return 0
    ex = ExactImpact(a.g, a.A, a.t_end)
    print(f"g = {a.g}, A = {a.A}, t_end = {a.t_end}: energy {a.A ** 2 / 6:.6g}, ||sigma||_L2 = {ex.sigma_l2():.6g}")
    for t, k in ex.events:
        print(f"  {'onset' if k > 0 else 'release'} at t = {t:.12g}")
    for on, off in ex.contact_intervals():
        print(f"  contact [{on:.6g}, {off:.6g}]: TV(sigma) = {ex.sigma_tv(on, off):.6g}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
