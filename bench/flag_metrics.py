#!/usr/bin/python3
"""Flag-flapping measures of flag-sim output files, per file and per group of seeds.

Usage:
  flag_metrics.py one FILE [--t0 T] [--json]
  flag_metrics.py table --group LABEL FILE [FILE...] [--group LABEL FILE...] [--reference LABEL]
                  [--t0 T] [--markdown | --json]
  flag_metrics.py plot --group LABEL FILE... [--group ...] [--reference LABEL] -o IMAGE
  flag_metrics.py --selftest

Needs h5py and numpy (/usr/bin/python3 on the project machines).

Definitions (the same as /work/shared/tools/cloth_checks.py `flaglaws`, so the figures match it):
  rest plane    normal n = (R[0,K-1] - R[0,0]) x (R[J-1,0] - R[0,0]) of /lattice/rest_positions R
                (row 0 the top edge, column 0 the pole edge); L = |R[0,K-1] - R[0,0]|.
  z             out-of-plane displacement: position . n minus its time mean, per node, over the
                frames with time >= T0 (default 1.0 s).
  fly-end signal  z of the middle row J//2, last column.
  f_zc          zero crossings of the fly-end signal (linear interpolation between frames):
                f = (crossings - 1) / (2 span), span = time from the first to the last crossing.
                (crossings - 1) half periods lie between the first and last crossing, so this is
                unbiased; crossings / (2 span) overestimates by one half period.  Fewer than 4
                crossings: f = nan (and so lambda, c, St), with a note.
  f_fft         peak of |rfft(signal * Hann)| (zero-padded x4, DC bin excluded as in flaglaws),
                refined by a parabola through the log magnitudes of the peak bin and its
                neighbours.  f = f_zc; f_agree = |f_zc - f_fft| / f_zc <= 0.15.
  phase         complex demodulation of the middle row at f_fft (where the flap's energy is):
                Z(x) = sum_t z(x, t) w(t) exp(-2 pi i f_fft t), w the Hann window (flaglaws
                takes the rfft bin nearest its peak; demodulation needs no bin).
  lambda/L      2 pi / |slope| / L, slope the least-squares slope of unwrap(arg Z) against
                x = distance from the pole node along the middle row at rest, over x >= 0.2 L.
  c/U           f_fft lambda / U, positive when waves run pole -> fly end (slope < 0);
                U = |[wind] velocity| from the root attribute `scene`.
  lambda_L_zc, c_U_zc  the same at f_zc (JSON only; a note when lambda differs by > 15%):
                an irregular flap can add zero crossings that move f_zc off the spectral
                peak, and the phase at a frequency with little energy is noise.
  lambda_L_near, lambda_L_far  the same slope over 0.2-0.6 L (the half by the pole) and over
                0.5-1.0 L (by the fly end), at f_fft (shown by `one`, in JSON): where along
                the flag a wavelength changes (2026-12-07: with the lattice, by the pole).
  A/L           (95th - 5th percentile) of the fly-end signal / L.
  St            f A / U.
  envelope      per-node std over time of z, resampled onto a 17 x 25 grid of normalised
                (row, col) lattice coordinates (bilinear; exact at the nodes of 2^n+1 lattices).
  mean shape    per-node time-mean position (frames >= T0), resampled the same way.
  ms/frame      1000 x median over frames 1.. of the row sums of /stats/stage_seconds.

Table (one row per group of seeds): N = files with status "complete" (others are listed with
their status and left out); mean +- sample std over seeds (std "-" below 2 values; a nan f is
left out of the f-based means).  Against the reference group (default: the last):
  env mm     RMS over the common grid of (group's seed-mean envelope - reference's), mm
  shape mm   RMS over the grid of |group's seed-mean mean shape - reference's|, mm
  rel err    |x - x_ref| / |x_ref| for f, lambda/L, c/U, A/L, St
  spread     per group: RMS over its seeds of each seed's field's distance (as above) to the
             group's seed mean, mm -- the seed-to-seed scatter.
  floor      the distance two seed means would show from seed scatter alone:
             sqrt(spread_g^2 / (N_g - 1) + spread_ref^2 / (N_ref - 1)); a distance well above it
             is a real difference.
"""
import argparse
import json
import math
import re
import sys

import numpy as np

GRID = (17, 25)          # common (rows, cols) grid of the envelope and mean shape
AGREE_TOL = 0.15         # |f_zc - f_fft| / f_zc
PAD = 4                  # zero padding of the f_fft spectrum
MIN_CROSSINGS = 4


# ----------------------------------------------------------------------------------------------
# reading a file

def wind_speed(scene_text):
    """|[wind] velocity| from the scene TOML text (as cloth_checks.flaglaws parses it)."""
    if isinstance(scene_text, bytes):
        scene_text = scene_text.decode()
    m = re.search(r"\[wind\][^\[]*?velocity\s*=\s*\[([^\]]*)\]", str(scene_text), re.S)
    if not m:
        return float("nan")
    return float(np.linalg.norm([float(x) for x in m.group(1).split(",")]))


def _attr(f, name, default=None):
    if name not in f.attrs:
        return default
    v = f.attrs[name]
    if isinstance(v, bytes):
        v = v.decode()
    if isinstance(v, np.ndarray) and v.shape == ():
        v = v[()]
        v = v.decode() if isinstance(v, bytes) else v
    return str(v)


def load(path, t0=1.0):
    """The arrays the measures need from one flag-sim output file (only frames >= t0 of the
    positions are read)."""
    import h5py
    with h5py.File(path, "r") as f:
        t = f["/frames/time"][()].astype(np.float64)
        i0 = int(np.searchsorted(t, t0 - 1e-9))
        rec = {
            "path": str(path),
            "status": _attr(f, "status", "unknown"),
            "t": t[i0:],
            "P": f["/frames/positions"][i0:].astype(np.float64),
            "R": f["/lattice/rest_positions"][()].astype(np.float64),
            "U": wind_speed(_attr(f, "scene", "")),
            "stage_seconds": (f["/stats/stage_seconds"][()].astype(np.float64)
                              if "/stats/stage_seconds" in f else None),
        }
    return rec


# ----------------------------------------------------------------------------------------------
# the measures

def rest_frame(R):
    """unit normal of the rest plane, flag length L, x along the middle row (as flaglaws)."""
    J = R.shape[0]
    L = float(np.linalg.norm(R[0, -1] - R[0, 0]))
    n = np.cross(R[0, -1] - R[0, 0], R[-1, 0] - R[0, 0])
    n = n / np.linalg.norm(n)
    x = np.linalg.norm(R[J // 2] - R[J // 2, 0], axis=-1)
    return n, L, x


def zero_crossing_frequency(t, s):
    """(f, crossings) from the zero crossings of s about its mean; f = (n - 1) / (2 span)."""
    s = s - s.mean()
    pos = s >= 0                      # a sample exactly at the mean counts as positive
    i = np.nonzero(pos[:-1] != pos[1:])[0]
    a, b = s[i], s[i + 1]
    times = t[i] + (t[i + 1] - t[i]) * a / (a - b)
    n = len(times)
    if n < MIN_CROSSINGS:
        return float("nan"), n
    span = times[-1] - times[0]
    return (n - 1) / (2.0 * span), n


def fft_frequency(t, s):
    """Hann-windowed spectral peak of s (zero-padded x PAD), parabola through log magnitudes."""
    n = len(s)
    if n < 4:
        return float("nan")
    dt = float(np.median(np.diff(t)))
    m = PAD * n
    spec = np.abs(np.fft.rfft((s - s.mean()) * np.hanning(n), m))
    lo = PAD  # first bin of the unpadded spectrum: DC excluded as in flaglaws
    if lo >= len(spec) - 1:
        return float("nan")
    k = lo + int(np.argmax(spec[lo:]))
    delta = 0.0
    if lo <= k - 1 and k + 1 < len(spec) and min(spec[k - 1], spec[k], spec[k + 1]) > 0:
        a, b, c = np.log(spec[k - 1]), np.log(spec[k]), np.log(spec[k + 1])
        den = a - 2 * b + c
        if den < 0:
            delta = 0.5 * (a - c) / den
    return (k + delta) / (m * dt)


def demodulate(t, z, f):
    """Z(x) = sum_t z(t, x) hann(t) exp(-2 pi i f (t - t[0]))."""
    w = np.hanning(len(t))
    return ((w * np.exp(-2j * np.pi * f * (t - t[0])))[:, None] * z).sum(0)


def resample(field, grid=GRID):
    """bilinear resampling of a [J, K, ...] field onto grid in normalised (row, col) coords."""
    J, K = field.shape[:2]
    u, v = np.linspace(0, J - 1, grid[0]), np.linspace(0, K - 1, grid[1])

    def lin(a, q, axis):
        n = a.shape[axis]
        i = np.clip(np.floor(q).astype(int), 0, max(n - 2, 0))
        w = q - i
        a0, a1 = np.take(a, i, axis=axis), np.take(a, np.minimum(i + 1, n - 1), axis=axis)
        shape = [1] * a.ndim
        shape[axis] = len(q)
        w = w.reshape(shape)
        return a0 * (1 - w) + a1 * w

    return lin(lin(field, u, 0), v, 1)


def measure(rec):
    """Measures of one record (dict from load() or a synthetic one)."""
    out = {"path": rec.get("path", "?"), "status": rec["status"], "notes": []}
    nan = float("nan")
    for k in ("f", "f_zc", "f_fft", "lambda_L", "c_U", "A_L", "St", "ms_frame", "U", "L",
              "lambda_L_fft", "c_U_fft", "lambda_L_zc", "c_U_zc", "lambda_L_near",
              "lambda_L_far"):
        out[k] = nan
    out.update(f_agree=None, crossings=0, frames=int(len(rec["t"])),
               envelope=None, mean_shape=None)
    st = rec.get("stage_seconds")
    if st is not None and len(st) > 1:
        out["ms_frame"] = 1000.0 * float(np.median(st[1:].sum(1)))
    t, P, R = rec["t"], rec["P"], rec["R"]
    if len(t) < 8:
        out["notes"].append(f"only {len(t)} frames after t0")
        return out
    if not np.isfinite(P).all():
        out["notes"].append("non-finite positions")
        return out
    n, L, x = rest_frame(R)
    U = float(rec["U"])
    out["U"], out["L"] = U, L
    J = P.shape[1]
    zall = P @ n
    zall = zall - zall.mean(0)
    out["envelope"] = resample(zall.std(0))
    out["mean_shape"] = resample(P.mean(0))
    z = zall[:, J // 2]
    s = z[:, -1]
    f_zc, ncross = zero_crossing_frequency(t, s)
    f_fft = fft_frequency(t, s)
    out.update(f_zc=f_zc, f_fft=f_fft, crossings=ncross, f=f_zc)
    A = float(np.percentile(s, 95) - np.percentile(s, 5))
    out["A_L"] = A / L
    if not math.isfinite(f_zc):
        out["notes"].append(f"f = nan: {ncross} zero crossings (< {MIN_CROSSINGS})")
        return out
    out["f_agree"] = bool(abs(f_zc - f_fft) / f_zc <= AGREE_TOL)
    if not out["f_agree"]:
        out["notes"].append(f"f_zc {f_zc:.3f} and f_fft {f_fft:.3f} Hz disagree by more than "
                            f"{100 * AGREE_TOL:.0f}%")
    out["St"] = f_zc * A / U
    # The phase along the flag is taken where the flap's energy is, at the spectral peak: an
    # irregular flap adds zero crossings that move f_zc off it (2026-12-03, 65x97 seed 1:
    # lambda/L 2.08 at f_zc, 1.22 at f_fft, against 1.20-1.29 for the other seeds), and the
    # phase at a frequency with little energy is noise. lambda_L_zc / c_U_zc keep the other.
    lam_zc, c_zc = wave(t, z, x, L, f_zc)
    out.update(lambda_L_zc=lam_zc / L, c_U_zc=c_zc / U)
    lam, c = wave(t, z, x, L, f_fft) if math.isfinite(f_fft) else (lam_zc, c_zc)
    out.update(lambda_L=lam / L, c_U=c / U, lambda_L_fft=lam / L, c_U_fft=c / U)
    f_phase = f_fft if math.isfinite(f_fft) else f_zc
    out["lambda_L_near"] = wave(t, z, x, L, f_phase, 0.2, 0.6)[0] / L
    out["lambda_L_far"] = wave(t, z, x, L, f_phase, 0.5, 1.0)[0] / L
    if abs(lam - lam_zc) > 0.15 * abs(lam):
        out["notes"].append(f"lambda/L hangs on f: {lam_zc / L:.2f} at f_zc, {lam / L:.2f} at "
                            f"f_fft (the latter kept)")
    return out


def wave(t, z, x, L, f, lo=0.2, hi=1.0):
    """(lambda, c) of the row z [frames, K] at frequency f: the phase slope of its complex
    demodulation over lo L <= x <= hi L; c > 0 when the waves run toward larger x (the fly
    end)."""
    Z = demodulate(t, z, f)
    sel = (x >= lo * L) & (x <= hi * L)
    slope = np.polyfit(x[sel], np.unwrap(np.angle(Z[sel])), 1)[0]
    lam = 2 * np.pi / abs(slope) if slope else float("inf")
    return lam, f * lam * (1 if slope < 0 else -1)


def measure_file(path, t0=1.0):
    try:
        rec = load(path, t0)
    except Exception as e:  # unreadable file: reported, left out
        return {"path": str(path), "status": f"unreadable ({e})", "notes": [], "f_agree": None}
    m = measure(rec)
    return m


# ----------------------------------------------------------------------------------------------
# groups

SCALARS = [("f", "f Hz", "{:.3f}"), ("lambda_L", "lambda/L", "{:.3f}"), ("c_U", "c/U", "{:.3f}"),
           ("A_L", "A/L", "{:.3f}"), ("St", "St", "{:.3f}"), ("ms_frame", "ms/frame", "{:.2f}")]
RELERR = ["f", "lambda_L", "c_U", "A_L", "St"]


def _mean_std(vals):
    v = np.array([x for x in vals if x is not None and math.isfinite(x)], float)
    if len(v) == 0:
        return float("nan"), None, 0
    return float(v.mean()), (float(v.std(ddof=1)) if len(v) >= 2 else None), len(v)


def _rms_scalar_field(d):      # envelope difference [G0, G1] in m -> mm
    return 1000.0 * float(np.sqrt(np.mean(d ** 2)))


def _rms_vector_field(d):      # shape difference [G0, G1, 3] in m -> mm
    return 1000.0 * float(np.sqrt(np.mean((d ** 2).sum(-1))))


def group_stats(label, ms):
    """statistics of one group from the measures of its files."""
    ok = [m for m in ms if m["status"] == "complete" and m.get("envelope") is not None]
    g = {"label": label, "files": len(ms), "N": len(ok),
         "excluded": [(m["path"], m["status"]) for m in ms if m not in ok],
         "notes": [(m["path"], n) for m in ok for n in m["notes"]]}
    for key, _, _ in SCALARS:
        g[key], g[key + "_std"], g[key + "_n"] = _mean_std([m[key] for m in ok])
    g["f_fft"], g["f_fft_std"], _ = _mean_std([m["f_fft"] for m in ok])
    g["f_agree"] = sum(1 for m in ok if m["f_agree"])
    if len(ok) == 1:
        g["envelope"], g["mean_shape"] = ok[0]["envelope"], ok[0]["mean_shape"]
        g["env_spread"] = g["shape_spread"] = float("nan")  # no spread from one seed
    elif ok:
        env = np.array([m["envelope"] for m in ok])
        shp = np.array([m["mean_shape"] for m in ok])
        g["envelope"], g["mean_shape"] = env.mean(0), shp.mean(0)
        g["env_spread"] = float(np.sqrt(np.mean([_rms_scalar_field(e - g["envelope"]) ** 2
                                                 for e in env])))
        g["shape_spread"] = float(np.sqrt(np.mean([_rms_vector_field(s - g["mean_shape"]) ** 2
                                                   for s in shp])))
    else:
        g["envelope"] = g["mean_shape"] = None
        g["env_spread"] = g["shape_spread"] = float("nan")
    return g


def compare(groups, ref_label=None):
    """adds the distances to the reference group to each group; returns the reference."""
    ref = groups[-1] if ref_label is None else next(g for g in groups if g["label"] == ref_label)
    for g in groups:
        g["is_reference"] = g is ref
        have = g["envelope"] is not None and ref["envelope"] is not None
        g["env_mm"] = _rms_scalar_field(g["envelope"] - ref["envelope"]) if have else float("nan")
        g["shape_mm"] = (_rms_vector_field(g["mean_shape"] - ref["mean_shape"]) if have
                         else float("nan"))
        for kind in ("env", "shape"):
            sg, sr = g[kind + "_spread"], ref[kind + "_spread"]
            g[kind + "_floor"] = (math.sqrt(sg ** 2 / (g["N"] - 1) + sr ** 2 / (ref["N"] - 1))
                                  if g["N"] >= 2 and ref["N"] >= 2 and g is not ref
                                  else float("nan"))
        for key in RELERR:
            r = ref[key]
            g["rel_" + key] = abs(g[key] - r) / abs(r) if r and math.isfinite(r) else float("nan")
    return ref


# ----------------------------------------------------------------------------------------------
# printing

def _fmt(x, spec="{:.3f}"):
    return "nan" if x is None or not math.isfinite(x) else spec.format(x)


def _dash(x, spec="{:.2f}"):
    return "-" if x is None or not math.isfinite(x) else spec.format(x)


def _pm(g, key, spec):
    s = g[key + "_std"]
    return f"{_fmt(g[key], spec)} +- {'-' if s is None else _fmt(s, spec)}"


def one_line(m):
    if m.get("envelope") is None and "f_zc" not in m:
        return f"{m['path']}  status {m['status']}: not measured"
    agree = "agree" if m["f_agree"] else ("DISAGREE" if m["f_agree"] is False else "-")
    s = (f"{m['path']}  status {m['status']}  f {_fmt(m['f'])} Hz (zc {_fmt(m['f_zc'])}, "
         f"{m['crossings']} crossings; fft {_fmt(m['f_fft'])}: {agree})  "
         f"lambda/L {_fmt(m['lambda_L'])} (by the pole {_fmt(m['lambda_L_near'], '{:.2f}')}, "
         f"by the fly end {_fmt(m['lambda_L_far'], '{:.2f}')})  "
         f"c/U {_fmt(m['c_U'])}  A/L {_fmt(m['A_L'])}  "
         f"St {_fmt(m['St'])}  ms/frame {_fmt(m['ms_frame'], '{:.2f}')}")
    if m["notes"]:
        s += "  [" + "; ".join(m["notes"]) + "]"
    return s


def _scalar_json(m):
    return {k: (v if not isinstance(v, float) or math.isfinite(v) else None)
            for k, v in m.items() if not isinstance(v, np.ndarray)}


def table_rows(groups):
    """two tables: the measures per group, and the comparison with the reference group."""
    head1 = ["group", "N"] + [h for _, h, _ in SCALARS] + ["f_fft Hz", "f agree"]
    rows1 = []
    for g in groups:
        row = [g["label"] + (" (ref)" if g["is_reference"] else ""), f"{g['N']}/{g['files']}"]
        row += [_pm(g, k, spec) for k, _, spec in SCALARS]
        row += [_fmt(g["f_fft"]), f"{g['f_agree']}/{g['f_n']}"]
        rows1.append(row)
    head2 = (["group"] + ["rel " + h.split()[0] for k, h, _ in SCALARS if k in RELERR]
             + ["env mm (floor)", "shape mm (floor)", "env spread", "shape spread"])
    rows2 = []
    for g in groups:
        row = [g["label"] + (" (ref)" if g["is_reference"] else "")]
        row += [_fmt(100 * g["rel_" + k], "{:.1f}%") for k in RELERR]
        row += [f"{_fmt(g['env_mm'], '{:.2f}')} ({_dash(g['env_floor'])})",
                f"{_fmt(g['shape_mm'], '{:.2f}')} ({_dash(g['shape_floor'])})",
                _dash(g["env_spread"]), _dash(g["shape_spread"])]
        rows2.append(row)
    return (head1, rows1), (head2, rows2)


def _print_one_table(head, rows, markdown):
    if markdown:
        print("| " + " | ".join(head) + " |")
        print("|" + "|".join("---" for _ in head) + "|")
        for r in rows:
            print("| " + " | ".join(r) + " |")
    else:
        w = [max(len(h), *(len(r[i]) for r in rows)) for i, h in enumerate(head)]
        print("  ".join(h.ljust(w[i]) for i, h in enumerate(head)).rstrip())
        for r in rows:
            print("  ".join(c.ljust(w[i]) for i, c in enumerate(r)).rstrip())


def print_table(groups, markdown=False, t0=1.0):
    (h1, r1), (h2, r2) = table_rows(groups)
    ref = next(g["label"] for g in groups if g["is_reference"])
    _print_one_table(h1, r1, markdown)
    print()
    print(f"against the reference {ref}:")
    print()
    _print_one_table(h2, r2, markdown)
    print()
    print(f"(frames from t0 = {t0} s; mean +- sample std over seeds; rel: |x - x_ref| / |x_ref|; "
          f"env / shape mm: RMS over the {GRID[0]}x{GRID[1]} grid of the seed means' difference "
          f"from the reference's; spread: RMS over a group's seeds of their distance to its seed "
          f"mean; floor: the distance that spread alone would give)")
    for g in groups:
        for p, st in g["excluded"]:
            print(f"{g['label']}: left out {p}: status {st}")
        for p, n in g["notes"]:
            print(f"{g['label']}: {p}: {n}")


# ----------------------------------------------------------------------------------------------
# self-test on synthetic travelling waves

def synthetic(J=17, K=25, f=2.3, lam_L=1.87, a_tip=0.25, U=10.0, Lw=1.5, H=1.0, fps=30.0,
              T=2.0, t_start=1.0, phase=0.0, noise=0.0, direction=1, seed=0):
    """a [J, K] flag in the x-y plane (row 0 on top at y = 2, column 0 at x = 0) carrying
    z = a(x, y) cos(2 pi f t - direction 2 pi x / lambda + phase) + billow(x), a(x, y) growing
    linearly to a_tip at the fly end (the same on every row at the fly end)."""
    rng = np.random.default_rng(seed)
    xs, ys = np.linspace(0, Lw, K), 2.0 - np.linspace(0, H, J)
    R = np.zeros((J, K, 3))
    R[..., 0], R[..., 1] = xs[None, :], ys[:, None]
    t = t_start + np.arange(int(round(T * fps)) + 1) / fps
    lam = lam_L * Lw
    X, Y = R[..., 0], R[..., 1]
    amp = a_tip * (0.3 + 0.7 * X / Lw) * (1.0 + 0.2 * (Y - ys.mean()) / H * X / Lw)
    z = amp[None] * np.cos(2 * np.pi * f * t[:, None, None] - direction * 2 * np.pi * X / lam
                           + phase)
    z += 0.1 * X * X / Lw            # billow: removed as the time mean
    z += noise * a_tip * rng.standard_normal(z.shape)
    P = np.repeat(R[None], len(t), 0)
    P[..., 2] += z
    P[..., 0] -= 0.02 * X / Lw       # in-plane shortening: not out of plane
    scene = f"[scene]\nname = 'synthetic'\n[wind]\nvelocity = [{U}, 0.0, 0.0]\ndrag = 1.0\n"
    st = 0.001 * (5 + rng.random((len(t), 3)))
    return {"path": f"synthetic {J}x{K} seed {seed}", "status": "complete", "t": t, "P": P,
            "R": R, "U": wind_speed(scene), "stage_seconds": st}


def selftest():
    f, lam_L, a_tip, U, Lw = 2.3, 1.87, 0.25, 10.0, 1.5
    c_U = f * lam_L * Lw / U
    A_L = 2 * a_tip / Lw
    St = f * 2 * a_tip / U
    ok = True

    def check(name, got, want, tol=0.03):
        nonlocal ok
        err = abs(got - want) / abs(want)
        good = err <= tol
        ok &= good
        print(f"  {name:10s} got {got:9.4f}  want {want:9.4f}  err {100 * err:5.2f}%  "
              f"{'ok' if good else 'FAIL'}")

    for (J, K, noise, direction, phase) in [(17, 25, 0.0, 1, 0.0), (33, 49, 0.01, 1, 1.1),
                                            (17, 25, 0.01, -1, 2.0)]:
        m = measure(synthetic(J, K, f, lam_L, a_tip, U, Lw, noise=noise, direction=direction,
                              phase=phase, seed=J + direction))
        print(f"synthetic {J}x{K}, noise {noise}, wave {'pole->fly' if direction > 0 else 'fly->pole'}:"
              f" {m['crossings']} crossings")
        check("f_zc", m["f_zc"], f)
        check("f_fft", m["f_fft"], f)
        check("lambda/L", m["lambda_L"], lam_L)
        check("near", m["lambda_L_near"], lam_L, 0.05)  # half the length, a noisier slope
        check("far", m["lambda_L_far"], lam_L, 0.05)
        check("c/U", m["c_U"], direction * c_U)
        check("A/L", m["A_L"], A_L)   # p95 - p5 of a sine is 0.988 x its peak-to-peak
        check("St", m["St"], St)
        ok &= bool(m["f_agree"])

    # too few crossings: f = nan, said so
    m = measure(synthetic(f=0.3, seed=5))
    slow_ok = math.isnan(m["f"]) and any("zero crossings" in n for n in m["notes"])
    print(f"f = 0.3 Hz over 2 s: {m['crossings']} crossings, f {m['f']}, notes {m['notes']}: "
          f"{'ok' if slow_ok else 'FAIL'}")
    ok &= slow_ok

    # groups: the same physics on two lattices compares to within the seed noise; a diverged
    # file is left out; a lone seed has std "-"
    ga = [measure(synthetic(17, 25, noise=0.01, phase=0.7 * s, seed=s)) for s in range(3)]
    gb = [measure(synthetic(33, 49, noise=0.01, phase=0.5 * s, seed=10 + s)) for s in range(3)]
    bad = measure(synthetic(33, 49, seed=99))
    bad["status"] = "diverged"
    gb.append(bad)
    gc = [measure(synthetic(17, 25, f=2.0, a_tip=0.2, seed=20))]
    groups = [group_stats("A 17x25", ga), group_stats("C lone", gc), group_stats("B 33x49", gb)]
    compare(groups)
    print_table(groups)
    A, C, B = groups
    checks = [("diverged left out", B["N"] == 3 and len(B["excluded"]) == 1),
              ("lone std '-'", C["f_std"] is None and "+- -" in table_rows(groups)[0][1][1][2]),
              ("17x25 vs 33x49 envelope < 2% of a_tip", A["env_mm"] < 0.02 * a_tip * 1000),
              ("17x25 vs 33x49 rel f < 1%", A["rel_f"] < 0.01),
              ("changed flag: envelope distance > 10 x 17x25's floor", C["env_mm"] > 10 * A["env_floor"])]
    for name, good in checks:
        print(f"  {name}: {'ok' if good else 'FAIL'}")
        ok &= good
    print("selftest", "PASSED" if ok else "FAILED")
    return ok


# ----------------------------------------------------------------------------------------------

def plot_cost(groups, path):
    """What accuracy costs: each group's error against the reference (frequency, and the mean
    shape's and the envelope's RMS distance with the seed floor as a bar) over its ms/frame."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 3, figsize=(14, 4.2))
    ref = next(g for g in groups if g["is_reference"])
    for g in groups:
        if g["is_reference"] or not math.isfinite(g["ms_frame"]):
            continue
        kind = "o" if g["label"].startswith("hybrid") else "s"
        f_err = 100.0 * g["rel_f"]
        f_bar = 100.0 * (g["f_std"] or 0.0) / ref["f"]
        for ax, y, bar in ((axes[0], f_err, f_bar), (axes[1], g["shape_mm"], g["shape_floor"]),
                           (axes[2], g["env_mm"], g["env_floor"])):
            ax.errorbar(g["ms_frame"], y, yerr=bar if math.isfinite(bar) else None, fmt=kind,
                        capsize=3)
            ax.annotate(g["label"], (g["ms_frame"], y), textcoords="offset points", xytext=(4, 4),
                        fontsize=7)
    titles = (f"flap frequency error, % (bar: seed std)", "mean shape RMS, mm (bar: seed floor)",
              "flap envelope RMS, mm (bar: seed floor)")
    for ax, title in zip(axes, titles):
        ax.set_xscale("log")
        ax.set_xlabel("ms per frame (one core)")
        ax.set_title(title, fontsize=9)
        ax.set_ylim(bottom=0)
        ax.grid(alpha=0.3)
    fig.suptitle(f"against {ref['label']} ({ref['N']} seeds, {ref['ms_frame']:.0f} ms/frame); "
                 "circles: hybrid, squares: full-lattice references", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)


def main(argv=None):
    argv = sys.argv[1:] if argv is None else argv
    if "--selftest" in argv:
        sys.exit(0 if selftest() else 1)
    if not argv or argv[0] not in ("one", "table", "plot"):
        sys.exit(__doc__)
    cmd, rest = argv[0], argv[1:]
    if cmd == "one":
        ap = argparse.ArgumentParser(prog="flag_metrics.py one")
        ap.add_argument("file")
        ap.add_argument("--t0", type=float, default=1.0)
        ap.add_argument("--json", action="store_true")
        a = ap.parse_args(rest)
        m = measure_file(a.file, a.t0)
        print(json.dumps(_scalar_json(m)) if a.json else one_line(m))
        return
    # table: --group LABEL FILE... repeated
    groups_in, opts, i = [], [], 0
    while i < len(rest):
        if rest[i] == "--group":
            if i + 1 >= len(rest):
                sys.exit("--group needs a LABEL and files")
            groups_in.append((rest[i + 1], []))
            i += 2
            while i < len(rest) and not rest[i].startswith("--"):
                groups_in[-1][1].append(rest[i])
                i += 1
        else:
            opts.append(rest[i])
            i += 1
    ap = argparse.ArgumentParser(prog=f"flag_metrics.py {cmd}")
    ap.add_argument("--reference")
    ap.add_argument("--t0", type=float, default=1.0)
    ap.add_argument("--markdown", action="store_true")
    ap.add_argument("--json", action="store_true")
    ap.add_argument("-o", dest="output", help="plot: the image to write (.png, .svg, .pdf)")
    a = ap.parse_args(opts)
    if cmd == "plot" and not a.output:
        sys.exit("plot needs -o IMAGE")
    if not groups_in or any(not files for _, files in groups_in):
        sys.exit("table needs --group LABEL FILE [FILE...] (each with at least one file)")
    if a.reference and a.reference not in [l for l, _ in groups_in]:
        sys.exit(f"--reference {a.reference}: no such group")
    groups = [group_stats(label, [measure_file(p, a.t0) for p in files])
              for label, files in groups_in]
    compare(groups, a.reference)
    if cmd == "plot":
        plot_cost(groups, a.output)
        return
    if a.json:
        print(json.dumps([_scalar_json(g) for g in groups], indent=1))
    else:
        print_table(groups, a.markdown, a.t0)


if __name__ == "__main__":
    main()
