#!/usr/bin/env python3
# Issue 47 (norm47): where Marschner's light over Chiang's comes from, one
# fibre, lobe by lobe. For a light at θi, each lobe's reflected energy
# ρ_p(θi) = (1/cos θi) ∫ (S_p cos θi) cos θo dωo (docs/formats.md, "Light
# and units"), over the whole sphere and over the light's side only
# (|φ| < 90°: what a front-lit camera sees), for
#   - plait's Marschner in Halén & Wester's form (the form before norm47:
#     one σ_a = 0.1 for every colour, the hair colour multiplying TT and TRT,
#     the added Kajiya-Kay diffuse kd·base/π², kd = 0.8 the scene default);
#   - plait's Marschner in Marschner et al. 2003's form (σ_a per channel
#     from the colour by Chiang et al. 2016 §4.2, no tint, no diffuse);
#   - Chiang et al. 2016 (pbrt-v3 / Mitsuba 3's hair BSDF, the numpy port
#     of scripts/mitsuba/marschner_lobes.py, held to Mitsuba there), averaged
#     over the eye ray's offset h.
# Luminance (Rec. 709) of each, blond / dark brown / black (the colours of
# scripts/physical-check.sh). Marschner's N_p is integrated as a density:
# N_p(φ) = ½ ∫ A(p, h) δ(φ − φ(p, h)) dh, a histogram over φ (so no root
# search); M_p = g(θh − α_p)/2 over θr as shaders/lib/marschner.wgsl.
# Usage: $PLAIT_MITSUBA_PYTHON scripts/mitsuba/marschner_energy.py
# (only numpy is needed).
import numpy as np

PI = np.pi
D = PI / 180
LUM = np.array([0.2126, 0.7152, 0.0722])
COLOURS = {"blond": [0.85, 0.65, 0.40], "dark_brown": [0.32, 0.20, 0.11], "black": [0.02] * 3}
BETA_M, BETA_N, TILT, ETA = 0.3, 0.3, 2.0, 1.55
KD = 0.8
NT, NP, NH = 180, 180, 4000


def sigma_a(c, b=BETA_N):
    d = 5.969 - 0.215 * b + 2.532 * b ** 2 - 10.73 * b ** 3 + 5.574 * b ** 4 + 0.245 * b ** 5
    return (np.log(np.array(c)) / d) ** 2


def fresnel(ep, epa, ci):
    s2 = np.maximum(0, 1 - ci * ci)
    sp, spa = s2 / ep ** 2, s2 / epa ** 2
    tir = (sp >= 1) | (spa >= 1)
    cp, cpa = np.sqrt(np.maximum(0, 1 - sp)), np.sqrt(np.maximum(0, 1 - spa))
    rp = (ci - ep * cp) / (ci + ep * cp)
    rpa = (epa * ci - cpa) / (epa * ci + cpa)
    return np.where(tir, 1.0, 0.5 * (rp * rp + rpa * rpa))


def marschner_rho(ti, sig, shift=(-7.5, 3.75, 11.25), width=(7.5, 3.75, 15.0), lit_side=False):
    """ρ_p(θi) per lobe and channel of plait's Marschner lobes (no caustic
    clamp), σ_a per channel `sig` (3,)."""
    thetas = (np.arange(NT) + 0.5) / NT * PI - PI / 2
    hs = (np.arange(NH) + 0.5) / NH * 2 - 1
    dphi_bin = PI / NP  # φ folded to [0, π]
    out = np.zeros((3, 3))
    shift, width = np.array(shift) * D, np.array(width) * D
    for to in thetas:
        thh, thd = 0.5 * (ti + to), 0.5 * (to - ti)
        m = 0.5 * np.exp(-(thh - shift) ** 2 / (2 * width ** 2)) / (width * np.sqrt(2 * PI))
        ctd = np.cos(thd)
        s2 = 1 - ctd ** 2
        root = np.sqrt(ETA ** 2 - s2)
        ep, epa = root / ctd, ETA ** 2 * ctd / root
        ctt = np.sqrt(1 - s2 / ETA ** 2)
        f = fresnel(ep, epa, np.sqrt(1 - hs ** 2))
        cgt = np.sqrt(1 - (hs / ep) ** 2)
        fi = fresnel(1 / ep, 1 / epa, cgt)
        tr = np.exp(-2 * np.outer(cgt, sig) / ctt)  # (NH, 3)
        for p in range(3):
            a = f[:, None] * np.ones(3) if p == 0 else ((1 - f) * (1 - fi) * (fi if p == 2 else 1))[:, None] * tr ** p
            phi = 2 * p * np.arcsin(hs / ep) - 2 * np.arcsin(hs) + p * PI
            phi = np.abs(np.mod(phi + PI, 2 * PI) - PI)  # folded to [0, π]
            keep = phi < PI / 2 if lit_side else np.ones_like(phi, bool)
            # ∫ N_p dφ over φ ∈ (−π, π] = ∫ A dh / 2 · 2 (both signs of φ
            # come from h and −h): ∫ N_p dφ = ½ ∫_{-1}^{1} A dh.
            n_int = 0.5 * (a * keep[:, None]).sum(0) * (2 / NH)
            # ρ: ∫ S cos θo dωo = ∫∫ (M N / cos²θd) cos²θo dθo dφ
            out[p] += m[p] * n_int / ctd ** 2 * np.cos(to) ** 2 * (PI / NT)
    return out


def chiang_rho(ti, sig, lit_side=False):
    """ρ_p(θi) of Chiang's fibre per lobe (R, TT, TRT, p≥3) and channel, the
    mean over the eye ray's offset h (midpoint in γ, weight cos γ)."""
    import importlib.util, os, sys
    here = os.path.dirname(os.path.abspath(__file__))
    spec = importlib.util.spec_from_file_location("ml", os.path.join(here, "marschner_lobes.py"))
    sys.modules.setdefault("mitsuba", type(sys)("mitsuba"))
    sys.modules.setdefault("drjit", type(sys)("drjit"))
    ml = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(ml)
    thetas = (np.arange(90) + 0.5) / 90 * PI - PI / 2
    phis = (np.arange(180) + 0.5) / 180 * 2 * PI - PI
    gam = (np.arange(32) + 0.5) / 32 * PI - PI / 2
    T, P, G = np.meshgrid(thetas, phis, gam, indexing="ij")
    wo = np.stack([np.sin(T), np.cos(T) * np.cos(G), np.cos(T) * np.sin(G)], -1)
    wi = np.stack([np.full_like(T, np.sin(ti)), np.cos(ti) * np.cos(G + P), np.cos(ti) * np.sin(G + P)], -1)
    h = np.sin(G)
    wgt = np.cos(G) * (PI / 32) / 2  # mean over h ∈ [-1, 1], dh = cos γ dγ
    keep = (np.abs(P) < PI / 2) if lit_side else np.ones_like(P, bool)
    out = np.zeros((4, 3))
    for c in range(3):
        lobes = ml.chiang_lobes(wo, wi, h, sig[c])  # (4, ...): S cos θi
        for p in range(4):
            v = (lobes[p] * wgt * keep).sum(2)  # mean over h
            out[p, c] = (v * np.cos(thetas)[:, None] ** 2).sum() * (PI / 90) * (2 * PI / 180) / np.cos(ti)
    return out


def main():
    print(f"# one fibre, ρ_p(θi) = (1/cos θi) ∫ S_p cos θi cos θo dωo, luminance; kd {KD}; "
          f"Chiang β_m {BETA_M} β_n {BETA_N} tilt {TILT}° η {ETA}")
    print("| colour | θi | side | H&W: R | TT | TRT | diffuse | sum | M2003: R | TT | TRT | sum | Chiang: R | TT | TRT | p≥3 | sum |")
    print("|---|---|---|" + "---|" * 14)
    for name, c in COLOURS.items():
        base = np.array(c)
        sig = sigma_a(c)
        for deg in (0, 30, 50, 70):
            ti = deg * D
            for lit in (False, True):
                hw = marschner_rho(ti, np.full(3, 0.1), lit_side=lit)
                hw[1:] *= base
                diffuse = KD * base * (0.5 if lit else 1.0)
                m03 = marschner_rho(ti, sig, lit_side=lit)
                ch = chiang_rho(ti, sig, lit_side=lit)
                l = lambda v: float(v @ LUM)
                row = [l(hw[0]), l(hw[1]), l(hw[2]), l(diffuse), l(hw.sum(0) + diffuse),
                       l(m03[0]), l(m03[1]), l(m03[2]), l(m03.sum(0)),
                       l(ch[0]), l(ch[1]), l(ch[2]), l(ch[3]), l(ch.sum(0))]
                print(f"| {name} | {deg}° | {'light' if lit else 'all'} | " + " | ".join(f"{v:.3f}" for v in row) + " |")


if __name__ == "__main__":
    main()
