#!/usr/bin/python3
# SPDX-License-Identifier: LGPL-3.0-or-later
"""Regenerates the figures of the Blended_shape manual (doc/Blended_shape/fig/*.png).

Needs Debian's python3-matplotlib (apt-get install python3-matplotlib), and
cmake with the package's dependencies for the helper program. From anywhere:

    /usr/bin/python3 doc/Blended_shape/fig/scripts/make_figures.py [--blended-fit PATH]

It builds chart_mesh_dump.cpp (this directory) in a temporary build tree, not
in the package build, and runs `blended_fit --trace` (default:
build/bin/blended_fit of the source tree; build it, blended_scan and
blended_make_object first) on the bundled mug scan and on a scan of the
box/cylinder CAD object for the picture sequences of part evolution, with
the split proposals of the force analysis (`--splits forces`) and with
those of crease segments (`--splits creases`, the default), printing each run's figures for the captions; the
final hierarchy is drawn by Graphviz's dot if it is installed.
"""

import argparse
import json
import os
import subprocess
import sys
import tempfile

import matplotlib
matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402
from mpl_toolkits.mplot3d.art3d import Poly3DCollection  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
FIG = os.path.dirname(HERE)
ROOT = os.path.normpath(os.path.join(FIG, "..", "..", ".."))

CHART_COLOURS = [(0.85, 0.50, 0.25), (0.25, 0.55, 0.80)]  # chart 0 (upper), chart 1 (lower)


def build_helper(build_dir):
    subprocess.run(["cmake", "-S", HERE, "-B", build_dir, "-DCMAKE_BUILD_TYPE=Release"],
                   check=True, stdout=subprocess.DEVNULL)
    subprocess.run(["cmake", "--build", build_dir], check=True, stdout=subprocess.DEVNULL)
    return os.path.join(build_dir, "chart_mesh_dump")


def dump_charts(helper, resolution, a1, a2, a3, e1, e2):
    """Chart meshes of a superquadric ellipsoid: per chart, uv (n x 2), xyz (n x 3),
    canonical chart of each vertex (n), faces (m x 3)."""
    out = subprocess.run([helper, str(resolution)] + [repr(v) for v in (a1, a2, a3, e1, e2)],
                         check=True, capture_output=True, text=True).stdout
    charts = {}
    for line in out.splitlines():
        w = line.split()
        c = int(w[1])
        ch = charts.setdefault(c, {"uv": [], "xyz": [], "canon": [], "faces": []})
        if w[0] == "V":
            ch["uv"].append((float(w[2]), float(w[3])))
            ch["xyz"].append((float(w[4]), float(w[5]), float(w[6])))
            ch["canon"].append(int(w[7]))
        else:
            ch["faces"].append((int(w[2]), int(w[3]), int(w[4])))
    for ch in charts.values():
        for k in ch:
            ch[k] = np.array(ch[k])
    return [charts[c] for c in sorted(charts)]


def shade(colour, normal, light=(0.4, -0.5, 0.75)):
    light = np.asarray(light) / np.linalg.norm(light)
    k = 0.45 + 0.55 * max(0.0, float(np.dot(normal, light)))
    return tuple(min(1.0, k * c) for c in colour)


def add_surface(ax, triangles, colours, alpha=1.0, edge=(0, 0, 0, 0.25)):
    faces = []
    facecolours = []
    for t, col in zip(triangles, colours):
        n = np.cross(t[1] - t[0], t[2] - t[0])
        ln = np.linalg.norm(n)
        n = n / ln if ln > 0 else n
        faces.append(t)
        facecolours.append(shade(col, n) + (alpha,))
    coll = Poly3DCollection(faces, facecolors=facecolours, edgecolors=[edge], linewidths=0.2)
    ax.add_collection3d(coll)


def equal_axes(ax, pts):
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    c, r = 0.5 * (lo + hi), 0.5 * (hi - lo).max()
    ax.set_xlim(c[0] - r, c[0] + r)
    ax.set_ylim(c[1] - r, c[1] + r)
    ax.set_zlim(c[2] - r, c[2] + r)
    ax.set_box_aspect((1, 1, 1))


def figure_chart_tessellation(helper, path):
    charts = dump_charts(helper, 6, 1.0, 1.0, 1.0, 1.0, 1.0)
    fig, axes = plt.subplots(1, 2, figsize=(9, 4.6))
    for c, (ax, ch) in enumerate(zip(axes, charts)):
        uv = ch["uv"]
        for f in ch["faces"]:
            tri = uv[list(f) + [f[0]]]
            rho = np.hypot(*uv[list(f)].mean(axis=0))
            if rho > 1.0:  # margin ring: past the equator, overlapping the other chart
                ax.fill(tri[:3, 0], tri[:3, 1], color=CHART_COLOURS[1 - c], alpha=0.35, lw=0)
            ax.plot(tri[:, 0], tri[:, 1], color=CHART_COLOURS[c], lw=0.6)
        t = np.linspace(0, 2 * np.pi, 200)
        ax.plot(np.cos(t), np.sin(t), "k--", lw=1.0, label="equator, rho = 1")
        ax.plot(uv[:, 0], uv[:, 1], ".", color="k", ms=1.5)
        ax.set_aspect("equal")
        ax.set_title("chart %d (%s half): eta = %s(pi/2)(1 - rho)" % (c, "upper" if c == 0 else "lower",
                                                                     "" if c == 0 else "-"), fontsize=10)
        ax.set_xlabel("x")
        ax.set_ylabel("y")
        ax.legend(loc="lower left", fontsize=8, framealpha=0.9)
    fig.suptitle("The two disk charts of Superquadric_ellipsoid (resolution 6, margin 0.2): "
                 "octahedral rings,\nshaded margin ring = overlap with the other chart", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def figure_superquadric(helper, path):
    charts = dump_charts(helper, 12, 1.0, 0.8, 1.2, 0.6, 0.6)
    fig = plt.figure(figsize=(9, 4.6))
    panels = [("both charts' pieces, chart 0 lifted (exploded view)", None), ("chart 0 alone, with its margin band", 0)]
    allpts = np.vstack([ch["xyz"] for ch in charts] + [charts[0]["xyz"] + [0.0, 0.0, 0.5]])
    for k, (title, only) in enumerate(panels):
        ax = fig.add_subplot(1, 2, k + 1, projection="3d")
        tris, cols = [], []
        for c, ch in enumerate(charts):
            if only is not None and c != only:
                continue
            for f in ch["faces"]:
                f = list(f)
                if only is None and not np.any(ch["canon"][f] == c):
                    continue  # wholly in the part the other chart owns (as blended_fit --mesh)
                lift = np.array([0.0, 0.0, 0.5 if (only is None and c == 0) else 0.0])
                tris.append(ch["xyz"][f] + lift)
                cols.append(CHART_COLOURS[c])
        add_surface(ax, tris, cols)
        equal_axes(ax, allpts)
        ax.view_init(elev=18, azim=-60)
        ax.set_title(title, fontsize=10)
        ax.set_axis_off()
    fig.suptitle("Superquadric_ellipsoid a = (1, 0.8, 1.2), e1 = e2 = 0.6: "
                 "chart 0 orange, chart 1 blue", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


def read_ascii_ply(path):
    with open(path) as f:
        lines = f.read().splitlines()
    nv = nf = 0
    i = 0
    while lines[i] != "end_header":
        w = lines[i].split()
        if w[:2] == ["element", "vertex"]:
            nv = int(w[2])
        if w[:2] == ["element", "face"]:
            nf = int(w[2])
        i += 1
    i += 1
    v = np.array([[float(x) for x in lines[i + k].split()[:3]] for k in range(nv)])
    faces, colours = [], []
    for k in range(nf):
        w = [int(x) for x in lines[i + nv + k].split()]
        faces.append(w[1:4])
        colours.append(tuple(c / 255.0 for c in w[4:7]))
    return v, np.array(faces), colours


def trace_sequence(trace_dir):
    """The models of a `blended_fit --trace` directory worth drawing: the first
    fit, the model after each kept split and the final model, as (title, ply
    path, dot path)."""
    steps = []
    for name in sorted(os.listdir(trace_dir)):
        stem, ext = os.path.splitext(name)
        if ext != ".ply":
            continue
        index, kind = stem.split("_", 1)
        if kind == "first_fit":
            steps.append(("first fit: one superquadric", stem))
        elif kind == "split":
            steps.append(("event %d: split kept" % int(index), stem))
        elif kind == "final":
            if steps and steps[-1][0].endswith("split kept"):
                # the last split kept, then fitted to all points: the result
                steps[-1] = (steps[-1][0] + ", final fit", stem)
            else:
                steps.append(("final model: one superquadric (no split kept)", stem))
    return [(t, os.path.join(trace_dir, s + ".ply"), os.path.join(trace_dir, s + ".dot")) for t, s in steps]


def render_dot(dot_path, png_path):
    """The hierarchy drawn by Graphviz's dot, if it is installed."""
    try:
        subprocess.run(["dot", "-Tpng", "-Gdpi=80", dot_path, "-o", png_path], check=True)
        return True
    except (OSError, subprocess.CalledProcessError):
        return False


def figure_evolution(blended_fit, scan, path, title, view, elev, azim, extra=()):
    """The scan, the first fit, the model after each kept split and the final
    hierarchy, from `blended_fit --trace` (the manual's picture sequence).
    Prints the run's figures (for the caption)."""
    with tempfile.TemporaryDirectory() as tmp:
        trace = os.path.join(tmp, "trace")
        summary = os.path.join(tmp, "summary.json")
        subprocess.run([blended_fit, scan, "--trace", trace, "--json", summary, "--quiet"] + list(extra), check=True,
                       stdout=subprocess.DEVNULL)
        with open(summary) as f:
            s = json.load(f)
        events = s["evolution"]["events"]
        diagonal = s["rms"] / s["rms_over_bbox_diagonal"]
        print("%s: %d parts, RMS_1,2,3 %s %%, RMS %.2f %% of the diagonal, %.1f s; events: %s" % (
            os.path.basename(path), s["parts"], ", ".join("%.2f" % (100 * r) for r in s["relative_rms"]),
            100 * s["rms_over_bbox_diagonal"], s["seconds"],
            "; ".join("%d %s (RMS %.2f -> %.2f %%)" % (k + 1, e["kind"], 100 * e["rms_before"] / diagonal,
                                                        100 * e["rms_after"] / diagonal)
                      for k, e in enumerate(events))))
        steps = trace_sequence(trace)
        models = [(t, read_ascii_ply(ply)) for t, ply, _ in steps]
        hierarchy_png = os.path.join(tmp, "hierarchy.png")
        # one part: no hierarchy worth drawing
        has_hierarchy = any("split kept" in t for t, _, _ in steps) and render_dot(steps[-1][2], hierarchy_png)
        hierarchy = plt.imread(hierarchy_png) if has_hierarchy else None
    pts = np.loadtxt(scan, usecols=(0, 1, 2))
    rng = np.random.default_rng(0)
    pts = view(pts[rng.choice(len(pts), size=min(4000, len(pts)), replace=False)])
    panels = 1 + len(models) + (1 if hierarchy is not None else 0)
    fig = plt.figure(figsize=(3.4 * panels, 3.8))
    ax = fig.add_subplot(1, panels, 1, projection="3d")
    ax.scatter(pts[:, 0], pts[:, 1], pts[:, 2], s=0.5, c="k", depthshade=False)
    ax.set_title("the scan (%d points)" % len(np.loadtxt(scan, usecols=(0,))), fontsize=9)
    boxes = [pts]
    axes = [ax]
    for k, (t, (v, faces, colours)) in enumerate(models):
        ax = fig.add_subplot(1, panels, k + 2, projection="3d")
        vv = view(v)
        add_surface(ax, [vv[f] for f in faces], colours, alpha=0.35, edge=(0, 0, 0, 0.04))
        ax.scatter(pts[:, 0], pts[:, 1], pts[:, 2], s=0.3, c="darkred", depthshade=False)
        ax.set_title(t, fontsize=9)
        axes.append(ax)
    for ax in axes:
        equal_axes(ax, np.vstack(boxes))
        ax.view_init(elev=elev, azim=azim)
        ax.set_axis_off()
    if hierarchy is not None:
        ax = fig.add_subplot(1, panels, panels)
        ax.imshow(hierarchy)
        ax.set_title("final blending hierarchy", fontsize=9)
        ax.set_axis_off()
    fig.suptitle(title, fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)


def scanner_view(p):
    """Scanner frame (the camera looks along +z with y down): z as depth, -y up."""
    return np.column_stack([p[:, 0], p[:, 2], -p[:, 1]])


def box_cylinder_scan(bin_dir, tmp):
    """The box/cylinder CAD object scanned from the default view (as benchmark/evolve_parts)."""
    mesh, scan = os.path.join(tmp, "box_cylinder.off"), os.path.join(tmp, "box_cylinder.xyz")
    subprocess.run([os.path.join(bin_dir, "blended_make_object"), "box_cylinder", "-o", mesh], check=True,
                   stdout=subprocess.DEVNULL)
    subprocess.run([os.path.join(bin_dir, "blended_scan"), mesh, "-o", scan], check=True, stdout=subprocess.DEVNULL)
    return scan


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--blended-fit", default=os.path.join(ROOT, "build", "bin", "blended_fit"),
                        help="the blended_fit executable (default: build/bin/blended_fit)")
    parser.add_argument("--helper", help="an already built chart_mesh_dump (default: build it)")
    args = parser.parse_args()
    with tempfile.TemporaryDirectory() as build_dir:
        helper = args.helper or build_helper(build_dir)
        figure_chart_tessellation(helper, os.path.join(FIG, "chart_tessellation.png"))
        figure_superquadric(helper, os.path.join(FIG, "superquadric_charts.png"))
    if os.path.exists(args.blended_fit):
        figure_evolution(args.blended_fit, os.path.join(ROOT, "data", "scans", "pcl_mug_scan.xyz"),
                         os.path.join(FIG, "mug_fit.png"),
                         "blended_fit --splits forces on data/scans/pcl_mug_scan.xyz (one stereo view): part evolution",
                         scanner_view, 20, -110, extra=("--splits", "forces"))
        with tempfile.TemporaryDirectory() as tmp:
            scan = box_cylinder_scan(os.path.dirname(args.blended_fit), tmp)
            figure_evolution(args.blended_fit, scan, os.path.join(FIG, "box_cylinder_evolution.png"),
                             "blended_fit --splits forces on the box/cylinder CAD object scanned from one view (Fig. 19 of the paper)",
                             lambda p: p, 20, -60, extra=("--splits", "forces"))
            figure_evolution(args.blended_fit, scan, os.path.join(FIG, "box_cylinder_creases.png"),
                             "blended_fit --splits creases on the same box/cylinder scan",
                             lambda p: p, 20, -60, extra=("--splits", "creases"))
        figure_evolution(args.blended_fit, os.path.join(ROOT, "data", "scans", "pcl_mug_scan.xyz"),
                         os.path.join(FIG, "mug_creases.png"),
                         "blended_fit --splits creases on data/scans/pcl_mug_scan.xyz",
                         scanner_view, 20, -110, extra=("--splits", "creases"))
    else:
        print("make_figures.py: %s not found, mug_fit.png, box_cylinder_evolution.png, box_cylinder_creases.png "
              "and mug_creases.png not updated "
              "(build blended_fit, blended_scan and blended_make_object first)"
              % args.blended_fit, file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
