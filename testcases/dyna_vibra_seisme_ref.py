"""Exact solution of testcases/dyna_vibra_seisme.comm, part B: a mass on a spring whose
support moves by d(t) = -(A/W^2) sin(W t), against a wall fixed in the absolute frame at
x = G, stiffness KN. Absolute coordinate x: m x'' + k (x - d) + KN (x - G)^+ = 0 from
x(0) = d(0) = 0, x'(0) = d'(0) = -A/W. Between contact changes the motion is the closed-form
solution of a linear oscillator under a sine; the changes are found by bisection on it."""
import math

M, K, KN, G, A, W = 1.0, 1.0e4, 1.0e6, 2.0e-4, 1.0, 60.0
TI = [0.05, 0.1, 0.2, 0.3, 0.4, 0.5]


def phase(contact):
    """(w, particular constant, sine amplitude) of x'' + w^2 x = w0^2 d(t) [+ wn^2 G]."""
    w0 = K / M
    wn = KN / M if contact else 0.0
    w2 = w0 + wn
    c = -w0 * A / (W * W) / (w2 - W * W)
    return math.sqrt(w2), (wn * G / w2 if contact else 0.0), c


def solution(t0, x0, v0, contact):
    w, p, c = phase(contact)
    a = x0 - p - c * math.sin(W * t0)
    b = (v0 - c * W * math.cos(W * t0)) / w
    def x(t):
        s = t - t0
        return a * math.cos(w * s) + b * math.sin(w * s) + p + c * math.sin(W * t)
    def v(t):
        s = t - t0
        return -a * w * math.sin(w * s) + b * w * math.cos(w * s) + c * W * math.cos(W * t)
    return x, v


def run(t_end=0.5, dt=1e-6):
    t, x0, v0, contact = 0.0, 0.0, -A / W, False
    x, v = solution(t, x0, v0, contact)
    out = {}
    events = 0
    pending = sorted(TI)
    while t < t_end:
        t1 = min(t + dt, t_end)
        for ti in list(pending):
            if ti <= t1 and (x(t1) - G > 0) == contact:
                out[ti] = x(ti)
                pending.remove(ti)
        if (x(t1) - G > 0) != contact:
            lo, hi = t, t1
            for _ in range(200):
                mid = 0.5 * (lo + hi)
                if (x(mid) - G > 0) == contact:
                    lo = mid
                else:
                    hi = mid
            te = 0.5 * (lo + hi)
            for ti in list(pending):
                if ti <= te:
                    out[ti] = x(ti)
                    pending.remove(ti)
            xe, ve = x(te), v(te)
            contact = not contact
            events += 1
            x, v = solution(te, xe, ve, contact)
            t = te
            continue
        t = t1
    return out, events


if __name__ == "__main__":
    out, events = run()
    print("contact changes:", events)
    print("X = (" + ", ".join("%.15e" % out[t] for t in TI) + ")")
    for t in TI:
        d = -(A / W**2) * math.sin(W * t)
        print(t, out[t], "relative:", out[t] - d)
