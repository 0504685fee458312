#!/usr/bin/env python3
# soft_mass_ratio_model.py — a 1-D model of the soft step (kernels/shared/soft_rows.h) on a light
# box under a heavy one on the ground: per step the same prepare (maxSag stiffening from the last
# step's load), per substep gravity, warm start, biased soft solve, positions, relax. It reproduces
# SolverModes.MassRatioThousand at 10 substeps (the stack rings on the ground and falls) and its
# pass at 40, in a second; used to try remedies before writing kernels (README, solver modes).
import math
import sys


def run(M=1000.0, m=1.0, substeps=10, steps=600, order=(0, 1), hertz=60.0, zeta=10.0, max_sag=0.0007,
        push=3.0, ground_share=None, top_share=None, relax_passes=1, verbose=0):
    """Contacts 0 (ground-light) and 1 (light-heavy), solved in `order`. ground_share/top_share:
    that row's relax mass raised to share x the mass it carries (its warm-start load over g h).
    Returns (deepest penetration in m, steps run before the heavy box left by 1 m)."""
    dt = 1 / 60.0
    h = dt / substeps
    g = -9.81
    hz = min(hertz, 0.125 / h)

    def soft(f):
        om = 2 * math.pi * f
        a1 = 2 * zeta + h * om
        a2 = h * om * a1
        return dict(bias=om / a1, a2=a2, om2=om * om)

    springs = [soft(2 * hz), soft(hz)]  # against the ground twice the frequency, as the stage
    x = [0.0, 0.0]  # light, heavy: height above touching
    v = [0.0, 0.0]
    cache = [0.0, 0.0]
    meff = [m, 1 / (1 / m + 1 / M)]
    deepest = 0.0
    for step in range(steps):
        base = [x[0], x[1] - x[0]]
        lam = [c / substeps for c in cache]
        load = lam[:]
        r = [max(lam[c] / (meff[c] * h * springs[c]['om2'] * max_sag), 1.0) if max_sag > 0 else 1.0 for c in range(2)]
        dx = [0.0, 0.0]
        total = [0.0, 0.0]
        for s in range(substeps):
            v[0] += g * h
            v[1] += g * h
            v[0] += (lam[0] - lam[1]) / m
            v[1] += lam[1] / M
            total[0] += lam[0]
            total[1] += lam[1]
            for biased in [1] + [0] * relax_passes:
                for c in order:
                    sep = base[0] + dx[0] if c == 0 else base[1] + dx[1] - dx[0]
                    vn = v[0] if c == 0 else v[1] - v[0]
                    ms, isc, bias = 1.0, 0.0, 0.0
                    if sep > 0:
                        bias = sep / h
                    elif biased:
                        # stiffened r times, damped r^1.5 times (btgSoftStiffened)
                        om = math.sqrt(springs[c]['om2'])
                        a1r = 2 * zeta * r[c] ** 1.5 + h * om * r[c]
                        a2 = h * om * a1r
                        ms, isc = a2 / (1 + a2), 1 / (1 + a2)
                        bias = max(ms * (om * r[c] / a1r) * sep, -push)
                    mass = meff[c]
                    share = ground_share if c == 0 else top_share
                    if share is not None and not biased:
                        mass = max(mass, share * load[c] / (-g * h))
                    old = lam[c]
                    new = max(old - mass * (ms * vn + bias) - isc * old, 0.0)
                    lam[c] = new
                    total[c] += new - old
                    if c == 0:
                        v[0] += (new - old) / m
                    else:
                        v[0] -= (new - old) / m
                        v[1] += (new - old) / M
                if biased:
                    dx[0] += v[0] * h
                    dx[1] += v[1] * h
        x[0] += dx[0]
        x[1] += dx[1]
        cache = total
        deepest = max(deepest, -x[0], -(x[1] - x[0]))
        if verbose and step % verbose == 0:
            print("%d light %.5f heavy %.5f v %.4f %.4f load %.2f %.2f" % (step, x[0], x[1], v[0], v[1], *cache))
        if abs(x[1]) > 1:
            return deepest, step
    return deepest, steps


if __name__ == "__main__":
    for M in (100.0, 400.0, 1000.0):
        for substeps in (10, 20, 40):
            print("M %g, %d substeps:" % (M, substeps),
                  ["%.1f mm @ %d" % (1e3 * p, n) for p, n in (run(M=M, substeps=substeps, order=o) for o in ((0, 1), (1, 0)))])
    sys.exit(0)
