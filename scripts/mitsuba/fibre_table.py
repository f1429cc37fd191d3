#!/usr/bin/env python3
# Mitsuba 3's hair BSDF (Chiang et al. 2016) on plait's fibre grid, written
# to tests/fixtures/chiang_mitsuba.txt so tests/fibre.rs checks the `chiang`
# shading technique against it without Python. The grid is tests/fibre.rs's
# (fibre along the tangent, light at θi ∈ {0, 30, 60, 80}°, φi = 0; eye at
# row j: θo = −90° + (j + ½)·180°/128, column i: φo = (i + ½)·360°/256).
# Each value is the BSDF's eval (cosine included: radiance per irradiance)
# averaged over the eye ray's offset h ∈ [−1, 1] (4000 midpoint points
# in γ = asin h), as
# a pixel covering the fibre sees it; fibre_probe.py documents the frame.
# The fibre is plait::mitsuba::Fibre::standard (the shading point's defaults: β_m 0.3, β_n 0.3, tilt 2°,
# η 1.55), the tilt given to Mitsuba as the export gives it (scale_tilt −2); σ_a from the colour by Chiang 2016 §4.2, the same formula as
# plait::mitsuba::sigma_a_from_color.
# Usage: eval "$(bash scripts/ensure-mitsuba.sh)";
#   $PLAIT_MITSUBA_PYTHON scripts/mitsuba/fibre_table.py > tests/fixtures/chiang_mitsuba.txt
import mitsuba as mi, drjit as dr, numpy as np
mi.set_variant('scalar_rgb')
PI = np.pi
ANGLES, AZIMUTHS = 128, 256
LIGHTS = [0.0, 30.0, 60.0, 80.0]
COLOURS = {'white': (1.0, 1.0, 1.0), 'blond': (0.85, 0.65, 0.40),
           'dark_brown': (0.32, 0.20, 0.11), 'black': (0.02, 0.02, 0.02)}
BETA_M, BETA_N, TILT, ETA = 0.3, 0.3, 2.0, 1.55
# Mitsuba's scale_tilt for plait's α: −α, as the export writes it (issue 42;
# crates/plait/src/mitsuba/write.rs, scripts/mitsuba/tilt_side.py).
MITSUBA_TILT = -TILT

def sigma_a(c, b=BETA_N):
    d = 5.969 - 0.215*b + 2.532*b**2 - 10.73*b**3 + 5.574*b**4 + 0.245*b**5
    return [(np.log(x)/d)**2 for x in c]

def bsdf(sig):
    return mi.load_dict({'type': 'hair', 'longitudinal_roughness': BETA_M, 'azimuthal_roughness': BETA_N,
                         'scale_tilt': MITSUBA_TILT, 'int_ior': ETA, 'sigma_a': mi.ScalarColor3f(*sig)})

si = dr.zeros(mi.SurfaceInteraction3f)
si.sh_frame = mi.Frame3f([1, 0, 0], [0, 1, 0], [0, 0, 1]); si.n = [0, 0, 1]; si.dp_du = [0, 1, 0]
ctx = mi.BSDFContext()

def d(th, ph):  # Mitsuba 3 hair: tangent = local y, normal z
    return np.array([np.cos(th)*np.sin(ph), np.sin(th), np.cos(th)*np.cos(ph)])

# ½∫ f dh with h = sin γ: the midpoint rule in γ, weight cos γ. Uniform
# points in h (400 of them) miss the R lobe's spike at the fibre's edge at
# φ ≈ π (4 % low there); 4000 points in γ agree with 40000 in h to 0.01 %.
def mean_over_h(b, th_e, th_l, phi, n=4000):
    acc = np.zeros(3)
    for g in -PI/2 + (np.arange(n) + 0.5)*PI/n:
        si.wi = mi.Vector3f(d(th_e, g)); v = b.eval(ctx, si, mi.Vector3f(d(th_l, g + phi)))
        acc += np.cos(g)*np.array([v[0], v[1], v[2]])
    return acc*PI/(2*n)

print(f"# Mitsuba {mi.__version__} hair BSDF, beta_m {BETA_M} beta_n {BETA_N} tilt {TILT} eta {ETA} "
      f"(scale_tilt {MITSUBA_TILT}); "
      "scripts/mitsuba/fibre_table.py")
print("# colour light_k row_j column_i theta_i_deg theta_o_deg phi_deg r g b")
for name, c in COLOURS.items():
    b = bsdf(sigma_a(c))
    for k, ti in enumerate(LIGHTS):
        spec = int(round((-ti + 90.0)/180.0*ANGLES - 0.5))
        rows = sorted({spec, min(spec + 6, ANGLES - 1), ANGLES//2, ANGLES//4, 3*ANGLES//4})
        for j in rows:
            to = -PI/2 + (j + 0.5)*PI/ANGLES
            for i in [0, 16, 64, 110, 127]:
                po = (i + 0.5)*2*PI/AZIMUTHS
                v = mean_over_h(b, to, np.radians(ti), po)
                print(f"{name} {k} {j} {i} {ti:.1f} {np.degrees(to):.4f} {np.degrees(po):.4f} "
                      f"{v[0]:.6e} {v[1]:.6e} {v[2]:.6e}")

# The white furnace: ∫ f dωo (dω = cos θo dθo dφo) under each light, by the
# midpoint rule, 64 × 64 eye directions, 64 points over h.
print("# furnace light_k theta_i_deg integral (white)")
b = bsdf([0.0, 0.0, 0.0])
for k, ti in enumerate(LIGHTS):
    n = 64
    total = 0.0
    for to in -PI/2 + (np.arange(n) + 0.5)*PI/n:
        for po in (np.arange(n) + 0.5)*2*PI/n:
            total += mean_over_h(b, to, np.radians(ti), po, n=64)[0]*np.cos(to)*(PI/n)*(2*PI/n)
    print(f"furnace {k} {ti:.1f} {total:.6f}")
