#!/usr/bin/python3
# SPDX-License-Identifier: LGPL-3.0-or-later
"""Regenerates the figures of the Blended_shape manual (doc/Blended_shape/fig/*.png).

Needs Debian's python3-matplotlib (apt-get install python3-matplotlib), and
cmake with the package's dependencies for the helper program. From anywhere:

    /usr/bin/python3 doc/Blended_shape/fig/scripts/make_figures.py [--blended-fit PATH]

It builds chart_mesh_dump.cpp (this directory) in a temporary build tree, not
in the package build, and runs `blended_fit` (default: build/bin/blended_fit of
the source tree; build it first) on the bundled mug scan for the last figure.
"""

import argparse
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


def figure_mug(blended_fit, path):
    scan = os.path.join(ROOT, "data", "scans", "pcl_mug_scan.xyz")
    with tempfile.TemporaryDirectory() as tmp:
        ply = os.path.join(tmp, "mug_fit.ply")
        subprocess.run([blended_fit, scan, "--mesh", ply, "--quiet"], check=True, stdout=subprocess.DEVNULL)
        v, faces, colours = read_ascii_ply(ply)
    pts = np.loadtxt(scan, usecols=(0, 1, 2))
    rng = np.random.default_rng(0)
    pts = pts[rng.choice(len(pts), size=min(4000, len(pts)), replace=False)]
    # Scanner frame: the camera looks along +z with y down. Show it with z as depth
    # and -y up, seen from the camera's side.
    def view(p):
        return np.column_stack([p[:, 0], p[:, 2], -p[:, 1]])
    vv, pp = view(v), view(pts)
    fig = plt.figure(figsize=(10, 4.8))
    for k, (title, with_model) in enumerate([("the scan (one stereo view, 16234 points)", False),
                                             ("fitted superquadric (blended_fit) and the scan", True)]):
        ax = fig.add_subplot(1, 2, k + 1, projection="3d")
        if with_model:
            add_surface(ax, [vv[f] for f in faces], colours, alpha=0.25, edge=(0, 0, 0, 0.06))
        ax.scatter(pp[:, 0], pp[:, 1], pp[:, 2], s=0.6, c="k" if not with_model else "darkred", depthshade=False)
        equal_axes(ax, np.vstack([pp, vv]) if with_model else pp)
        ax.view_init(elev=20, azim=-110)
        ax.set_title(title, fontsize=10)
        ax.set_axis_off()
    fig.suptitle("data/scans/pcl_mug_scan.xyz: this release fits one superquadric to the whole mug; "
                 "parts and the handle's hole need blending", fontsize=10)
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    plt.close(fig)


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
        figure_mug(args.blended_fit, os.path.join(FIG, "mug_fit.png"))
    else:
        print("make_figures.py: %s not found, mug_fit.png not updated (build blended_fit first)"
              % args.blended_fit, file=sys.stderr)
    return 0


if __name__ == "__main__":
    sys.exit(main())
