#!/usr/bin/env python3
# Where plait's hair light differs from Mitsuba's, not just how much: over
# the hair mask of scripts/physical-check.sh's output (Mitsuba's coverage
# >= 0.9), plait chiang ÷ Mitsuba depth 2 (mean of seeds 0 and 1) by
# Mitsuba's brightness (dim half, middle, top 10 %) and by image rows (top,
# middle, bottom third of the mask), and DIR/ratio_map.png: per colour
# (blond, black) Mitsuba | plait | log2 ratio (red plait brighter, blue
# dimmer, saturated at 4x), one exposure per row.
# Then like with like (physical-check.sh's header): the probe with Mitsuba's
# own frame ÷ Mitsuba depth 2 (direct_probe.py reproduces it), the probe with
# the frame rebuilt from the curve's tangent ÷ the probe (1: since the export
# is bsplinecurve Mitsuba's frame is the tangent's), plait chiang with opaque
# fibres (C_plait_chiang_opaque) ÷ Mitsuba depth 2 and ÷ the tangent probe.
# Usage: $PLAIT_MITSUBA_PYTHON scripts/mitsuba/ratio_map.py [DIR]
import sys
import numpy as np, mitsuba as mi, os
mi.set_variant("scalar_rgb")
d=sys.argv[1] if len(sys.argv) > 1 else "target/physical-check"
Y=np.array([0.2126,0.7152,0.0722])
L=lambda n: np.array(mi.Bitmap(os.path.join(d,n)),dtype=np.float64)[...,:3]@Y
# Colours with every image present; a missing one is named, not skipped silently.
need=["_mask.exr","_mitsuba_d2_s0.exr","_mitsuba_d2_s1.exr","_plait_chiang.exr"]
colours=[]
for c in ["blond","dark_brown","black"]:
    missing=[c+n for n in need if not os.path.exists(os.path.join(d,c+n))]
    if missing:
        print(c, "left out, missing:", " ".join(missing))
    else:
        colours.append(c)
for c in colours:
    m=np.array(mi.Bitmap(f"{d}/{c}_mask.exr"),dtype=np.float64)
    m=(m if m.ndim==2 else m[...,0])>=0.9
    mt=(L(f"{c}_mitsuba_d2_s0.exr")+L(f"{c}_mitsuba_d2_s1.exr"))/2; pl=L(f"{c}_plait_chiang.exr")
    q=np.quantile(mt[m],[0.5,0.9])
    rows=[]
    for name,sel in [("all",m),("mitsuba dim half",m&(mt<q[0])),("mid",m&(mt>=q[0])&(mt<q[1])),("top 10%",m&(mt>=q[1]))]:
        rows.append(f"{name}: {pl[sel].mean()/mt[sel].mean():.3f} ({sel.sum()} px, share of Mitsuba light {mt[sel].sum()/mt[m].sum():.2f})")
    # by image row bands (top of head vs bottom)
    ys=np.nonzero(m)[0]; 
    bands=np.quantile(ys,[0,1/3,2/3,1])
    rb=[]
    for i in range(3):
        sel=m.copy(); yy=np.arange(m.shape[0])[:,None]; sel&=(yy>=bands[i])&(yy<=bands[i+1])
        rb.append(f"{pl[sel].mean()/mt[sel].mean():.3f}")
    print(c, "; ".join(rows), "| rows top/mid/bottom:", rb)
def by_rows(m, num, den):
    ys=np.nonzero(m)[0]; b=np.quantile(ys,[0,1/3,2/3,1]); yy=np.arange(m.shape[0])[:,None]
    return [num[m&(yy>=b[i])&(yy<=b[i+1])].mean()/den[m&(yy>=b[i])&(yy<=b[i+1])].mean() for i in range(3)]
for c in colours:
    if not os.path.exists(f"{d}/{c}_probe_fibre_shadowed.exr"):
        continue
    m=np.array(mi.Bitmap(f"{d}/{c}_mask.exr"),dtype=np.float64); m=(m if m.ndim==2 else m[...,0])>=0.9
    mt=(L(f"{c}_mitsuba_d2_s0.exr")+L(f"{c}_mitsuba_d2_s1.exr"))/2
    probe=L(f"{c}_probe_shadowed.exr"); fib=L(f"{c}_probe_fibre_shadowed.exr")
    line=[f"probe/d2 {probe[m].mean()/mt[m].mean():.3f} rows "+" ".join(f"{r:.2f}" for r in by_rows(m,probe,mt)),
          f"probe_fibre/probe {fib[m].mean()/probe[m].mean():.3f} rows "+" ".join(f"{r:.2f}" for r in by_rows(m,fib,probe))]
    if os.path.exists(f"{d}/{c}_plait_chiang_opaque.exr"):
        pl=L(f"{c}_plait_chiang_opaque.exr")
        line.append(f"plait chiang_opaque/d2 {pl[m].mean()/mt[m].mean():.3f} rows "+" ".join(f"{r:.2f}" for r in by_rows(m,pl,mt)))
    for name in ["chiang","chiang_opaque"]:
        if os.path.exists(f"{d}/{c}_plait_{name}.exr"):
            pl=L(f"{c}_plait_{name}.exr")
            line.append(f"plait {name}/probe_fibre {pl[m].mean()/fib[m].mean():.3f} rows "+" ".join(f"{r:.2f}" for r in by_rows(m,pl,fib)))
    print(c, "like with like:", "; ".join(line))
rows=[]
for c in [c for c in ["blond","black"] if c in colours]:
    m=np.array(mi.Bitmap(f"{d}/{c}_mask.exr"),dtype=np.float64); m=(m if m.ndim==2 else m[...,0])>=0.9
    mt=(L(f"{c}_mitsuba_d2_s0.exr")+L(f"{c}_mitsuba_d2_s1.exr"))/2; pl=L(f"{c}_plait_chiang.exr")
    r=np.log2(np.maximum(pl,1e-6)/np.maximum(mt,1e-6)); r=np.clip(r/2,-1,1)
    img=np.zeros(m.shape+(3,)); img[...,0]=np.where(m,np.maximum(r,0),0); img[...,2]=np.where(m,np.maximum(-r,0),0); img[...,1]=np.where(m,0.15,0)
    s=np.percentile(mt[m],99)
    g=lambda a: np.repeat(np.clip(a/s,0,1)[...,None],3,axis=2)**(1/2.2)
    rows.append(np.concatenate([g(mt),g(pl),img],axis=1))
out=np.concatenate(rows,axis=0); out=np.repeat(np.repeat(out,3,0),3,1)
mi.util.write_bitmap(f"{d}/ratio_map.png",(out*255+0.5).astype(np.uint8))
