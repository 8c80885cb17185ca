#!/usr/bin/env python3
"""Light bleeding of variance shadow maps against moment shadow maps (Peters & Klein 2015),
measured against the ray-traced reference on fence's view from behind the wall, where the slats
and the wall overlap in the map: the light that leaks into the umbra is umbra_leak_pct."""
import figures

args = figures.options("light-bleeding", __doc__)
view = ["--scene", "fence", "--camera", "4,3,-6:0,0,-3.5:50"]
rows = {f: figures.compare(args, f, view + ["--filter", f]) for f in ("pcf", "vsm", "msm")}
vsm, msm, pcf = rows["vsm"], rows["msm"], rows["pcf"]
figures.write(
    args, "Light bleeding: VSM against moment shadow maps",
    "Peters & Klein (2015, *Moment Shadow Mapping*, I3D) store four moments of depth and bound the lit "
    "fraction with the Hamburger 4-moment problem; where occluders at several depths overlap in a "
    "filter region, the bound is much tighter than Chebyshev's two-moment bound of variance shadow "
    "maps, so MSM leaks far less light into umbrae than VSM; the price is four moments per texel instead of "
    "two, which the paper puts at well under twice VSM's cost.",
    "`fence` seen from behind the wall (`--camera 4,3,-6:0,0,-3.5:50`): the slats in front of the "
    "wall and the wall itself overlap in the sun's map, VSM's worst case. Every filter at its "
    "defaults (no bleeding reduction); pcf, which compares depths and cannot bleed, as the baseline.",
    [("filter", "filter"), ("umbra_leak_pct", "umbra_leak_pct"), ("leak_pct", "leak_pct"), ("rmse", "rmse"),
     ("penumbra_rmse", "penumbra_rmse"), ("shadow cost (ms, median)", lambda r: r["shadow_cost_ms"]["median"])],
    [(f"MSM leaks less light into the umbra than VSM (umbra_leak_pct {figures.fmt(msm['umbra_leak_pct'])} % "
      f"against {figures.fmt(vsm['umbra_leak_pct'])} %)", msm["umbra_leak_pct"] < vsm["umbra_leak_pct"]),
     (f"MSM's whole error is below VSM's (RMSE {figures.fmt(msm['rmse'])} against {figures.fmt(vsm['rmse'])})",
      msm["rmse"] < vsm["rmse"]),
     (f"MSM's leak is gone, as a depth comparison's is (pcf {figures.fmt(pcf['umbra_leak_pct'])} %, "
      f"MSM {figures.fmt(msm['umbra_leak_pct'])} %, within 0.5 percentage points)",
      msm["umbra_leak_pct"] <= pcf["umbra_leak_pct"] + 0.5),
     (f"MSM costs less than twice VSM (shadow cost ×{msm['shadow_cost_ms']['median'] / vsm['shadow_cost_ms']['median']:.2f}; "
      "medians of separate runs)", msm["shadow_cost_ms"]["median"] < 2.0 * vsm["shadow_cost_ms"]["median"])])
