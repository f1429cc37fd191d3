#!/usr/bin/env python3
# Issue 47, task fibre: one fibre, one direction pair at a time. plait's
# Marschner lobes (a numpy PORT of shaders/lib/marschner.wgsl's functions, not
# the WGSL itself: keep the two in step) against Mitsuba 3's hair BSDF
# (Chiang et al. 2016) evaluated with mi.load_dict({'type': 'hair', ...}).eval,
# averaged over the fibre's width (h = sin γ uniform in [-1, 1], as a pixel
# covering the fibre sees it). Both give L/E: radiance towards the eye per
# irradiance from the light. Mitsuba 3's hair frame: tangent = local y,
# azimuth atan2(z, x), h from the eye direction's angle γ to the normal z
# (the BSDF ignores uv) — found by probing and confirmed in its hair.cpp.
# Usage: $PLAIT_MITSUBA_PYTHON scripts/mitsuba/fibre_probe.py
# (eval "$(bash scripts/ensure-mitsuba.sh)" first). Takes ~1 min.
# One fibre, one direction pair: plait's Marschner (a numpy port of
# shaders/lib/marschner.wgsl) vs Mitsuba 3's hair BSDF (Chiang 2016), the
# latter averaged over the fibre's width (h uniform, as a pixel sees it).
import mitsuba as mi, drjit as dr, numpy as np
mi.set_variant('scalar_rgb')
# Mitsuba's scale_tilt for plait's tilt of 2°: −2, as `plait export mitsuba`
# writes it (issue 42: Mitsuba rotates R by −2α about an axis that runs
# root to tip here, which puts R on the tip's side for α > 0).
MITSUBA_TILT = -2.0
PI=np.pi; D=PI/180
def mbsdf(sig): return mi.load_dict({'type':'hair','longitudinal_roughness':0.3,'azimuthal_roughness':0.3,'scale_tilt':MITSUBA_TILT,'int_ior':1.55,'sigma_a':mi.ScalarColor3f(*sig)})
si = dr.zeros(mi.SurfaceInteraction3f)
si.sh_frame = mi.Frame3f([1,0,0],[0,1,0],[0,0,1]); si.n=[0,0,1]; si.dp_du=[0,1,0]
ctx = mi.BSDFContext()
def d(th,ph): return np.array([np.cos(th)*np.sin(ph), np.sin(th), np.cos(th)*np.cos(ph)])  # Mitsuba 3 hair: tangent = local y
def mitsuba_mean(b, th_e, th_l, phi, lit_only=False, n=400):
    # eye at azimuth g from the normal: h = sin g uniform in [-1,1]
    hs=(np.arange(n)+0.5)/n*2-1; acc=np.zeros(3)
    for h in hs:
        g=np.arcsin(h); e=d(th_e,g); l=d(th_l,g+phi)
        if lit_only and l[2]<=0: continue
        si.wi=mi.Vector3f(e); v=b.eval(ctx,si,mi.Vector3f(l)); acc+=np.array([v[0],v[1],v[2]])
    return acc/n
# ---- plait port
def fresnel(ep,epa,ci):
    s2=max(0,1-ci*ci); sp=s2/ep**2; spa=s2/epa**2
    if sp>=1 or spa>=1: return 1.0
    cp=np.sqrt(1-sp); cpa=np.sqrt(1-spa)
    rp=(ci-ep*cp)/(ci+ep*cp); rpa=(epa*ci-cpa)/(epa*ci+cpa); return 0.5*(rp*rp+rpa*rpa)
def att(p,h,ep,epa,ctt,sig):
    f=fresnel(ep,epa,np.sqrt(max(0,1-h*h)))
    if p==0: return f
    cgt=np.sqrt(max(0,1-(h/ep)**2)); fi=fresnel(1/ep,1/epa,cgt); T=np.exp(-2*sig*cgt/ctt)
    return (1-f)*(1-fi)*(fi if p==2 else 1)*T**p
def phiof(p,h,eta): return 2*p*np.arcsin(h/eta)-2*np.arcsin(h)+p*PI
def slope(p,h,eta): return 2*p/np.sqrt(max(eta*eta-h*h,1e-12))-2/np.sqrt(max(1-h*h,1e-12))
def plait(th_i, th_r, phi, sig=0.1, ior=1.55, caustic=0.25, shift=(-7.5,3.75,11.25), width=(7.5,3.75,15.0)):
    shift=np.array(shift)*D; width=np.array(width)*D
    thh=0.5*(th_i+th_r); dd=thh-shift; M=np.exp(-dd*dd/(2*width**2))/(width*np.sqrt(2*PI))
    ctd=np.cos(0.5*(th_r-th_i)); s2=1-ctd**2; root=np.sqrt(ior**2-s2); ep=root/ctd; epa=ior**2*ctd/root
    ctt=np.sqrt(1-s2/ior**2)
    nr=att(0,-np.sin(phi/2),ep,epa,ctt,sig)*np.cos(phi/2)*0.25
    # TT, TRT: dense root search (sum over all h with phi(p,h)=phi mod 2pi)
    N=[nr,0,0]
    hs=np.linspace(-1+1e-7,1-1e-7,200001)
    for p in (1,2):
        f=np.mod(phiof(p,hs,ep)-phi+PI,2*PI)-PI
        idx=np.where(np.sign(f[:-1])!=np.sign(f[1:]))[0]
        for i in idx:
            if abs(f[i])>1: continue
            h=hs[i]-f[i]*(hs[i+1]-hs[i])/(f[i+1]-f[i])
            N[p]+=att(p,h,ep,epa,ctt,sig)/max(abs(2*slope(p,h,ep)),1e-6)
    N[2]=min(N[2],caustic)
    S=0.5*M*np.array(N)/max(ctd**2,1e-4)
    return np.cos(th_i)*S, M, np.array(N)
def energy(ti, sig_m, nt=120, npf=180, nh=48):
    """Integral of L/E over eye directions (dω = cos θ dθ dφ) at light angle ti."""
    ths=(np.arange(nt)+0.5)/nt*PI-PI/2; phs=(np.arange(npf)+0.5)/npf*2*PI-PI
    dA=(PI/nt)*(2*PI/npf); b=mbsdf(sig_m); acc=0.0
    for tr in ths:
        for ph in phs: acc+=mitsuba_mean(b,tr,ti,ph,n=nh)[0]*np.cos(tr)*dA
    return acc
def plait_energy(ti, nt=30, npf=36):
    ths=(np.arange(nt)+0.5)/nt*PI-PI/2; phs=(np.arange(npf)+0.5)/npf*2*PI-PI
    dA=(PI/nt)*(2*PI/npf); acc=np.zeros(3)
    for tr in ths:
        for ph in phs: acc+=plait(ti,tr,abs(ph),sig=0.0,caustic=1e9)[0]*np.cos(tr)*dA
    return acc
print("mitsuba", mi.__version__, "hair: beta_m 0.3 beta_n 0.3 scale_tilt -2 eta 1.55; plait: marschner_model.toml")
print("-- point values, sigma_a 0 (Mitsuba) / 0 (plait), plait caustic clamp 0.25")
for name,ti,tr,phi in [('back near-specular',20,-20,10),('side',20,-20,90),('forward',20,-20,180),('scene-like',52,5,20),('scene-like',52,-5,20),('scene-like',-52,5,20)]:
    lob,M,N=plait(ti*D,tr*D,phi*D,sig=0.0)
    mt=mitsuba_mean(mbsdf([0.0]*3),tr*D,ti*D,phi*D)[0]; mr=mitsuba_mean(mbsdf([1e4]*3),tr*D,ti*D,phi*D)[0]
    print(f"{name} θi {ti} θr {tr} φ {phi}: plait R {lob[0]:.5f} TT {lob[1]:.5f} TRT {lob[2]:.5f} sum {lob.sum():.5f} (M {M.round(4)} N {N.round(4)}) | mitsuba R only {mr:.5f} all {mt:.5f}")
print("-- energy: integral of L/E over eye directions, sigma_a 0, no caustic clamp")
for t in (0,20,60):
    pe=plait_energy(t*D)
    print(f"θi {t}: plait R {pe[0]:.4f} TT {pe[1]:.4f} TRT {pe[2]:.4f} sum {pe.sum():.4f} | mitsuba R only {energy(t*D,[1e4]*3):.4f} all {energy(t*D,[0.0]*3):.4f}")
print("-- scene-like points, Mitsuba's roughness varied (sigma_a 0): (beta_m, beta_n)")
def mb(bm,bn): return mi.load_dict({'type':'hair','longitudinal_roughness':bm,'azimuthal_roughness':bn,'scale_tilt':MITSUBA_TILT,'int_ior':1.55,'sigma_a':mi.ScalarColor3f(0.0,0.0,0.0)})
for ti,tr,phi in [(52,5,20),(52,-5,20),(-52,5,20)]:
    r=[mitsuba_mean(mb(bm,bn),tr*D,ti*D,phi*D)[0] for bm,bn in [(0.3,0.3),(0.3,0.02),(0.1,0.3),(0.1,0.02)]]
    print(f"θi {ti} θr {tr} φ {phi}: (.3,.3) {r[0]:.5f} (.3,.02) {r[1]:.5f} (.1,.3) {r[2]:.5f} (.1,.02) {r[3]:.5f}")
