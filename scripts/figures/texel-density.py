#!/usr/bin/env python3
"""Texel density of cascades against a warped projection (Wimmer et al. 2004; Lloyd et al. 2008),
on city (640 m under a low sun, seen from eye height), every projection with the same texel
budget and the hard filter: screen pixels per shadow-map texel near the camera, and the error
against the ray-traced reference."""
import figures

args = figures.options("texel-density", __doc__)
budget = str(512 * 512 if args.small else 2048 * 2048)
rows = {p: figures.compare(args, p, ["--scene", "city", "--filter", "hard", "--projection", p, "--shadow-budget", budget])
        for p in ("uniform", "csm", "lispsm")}
u, c, w = rows["uniform"], rows["csm"], rows["lispsm"]
figures.write(
    args, "Texel density: cascades against a warped projection",
    "Wimmer et al. (2004, *Light Space Perspective Shadow Maps*, EGSR) warp one shadow map with a "
    "perspective in light space, so texels follow the camera's 1/z and the ground near the viewer "
    "gets many more of them than a uniform map gives. Lloyd et al. (2008, *Logarithmic Perspective "
    "Shadow Maps*, ACM TOG) compare warping with z-partitioning (cascades) for the same texels: both "
    "cut the perspective aliasing error by large factors over a uniform map, warping doing with one "
    "map what partitioning does with several.",
    f"`city` (640 m of streets, sun 20° high), the `hard` filter, every projection under one texel "
    f"budget (`--shadow-budget {budget}`: csm's four cascades share it). Texel density is screen pixels "
    "per texel (lower is finer: above 1, a texel covers several pixels); near = within 20 m of the camera.",
    [("projection", "projection"), ("texel density, near median", "texel_density_near_median"),
     ("texel density, median", "texel_density_median"), ("undersampled %", "undersampled_pct"),
     ("rmse", "rmse"), ("penumbra_rmse", "penumbra_rmse")],
    [(f"Warping puts more texels near the viewer than a uniform map (near median "
      f"{figures.fmt(w['texel_density_near_median'])} against {figures.fmt(u['texel_density_near_median'])} pixels per texel)",
      w["texel_density_near_median"] < u["texel_density_near_median"]),
     (f"Cascades do too (near median {figures.fmt(c['texel_density_near_median'])})",
      c["texel_density_near_median"] < u["texel_density_near_median"]),
     (f"One warped map does at least as well near the viewer as four cascades of the same texels "
      f"({figures.fmt(w['texel_density_near_median'])} against {figures.fmt(c['texel_density_near_median'])})",
      w["texel_density_near_median"] <= c["texel_density_near_median"]),
     (f"The warped map's shadows are closer to the truth than the cascades' (RMSE {figures.fmt(w['rmse'])} "
      f"against {figures.fmt(c['rmse'])})", w["rmse"] <= c["rmse"])])
