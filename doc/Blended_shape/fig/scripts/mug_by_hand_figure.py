#!/usr/bin/python3
# SPDX-License-Identifier: LGPL-3.0-or-later
"""Renders doc/Blended_shape/fig/mug_by_hand.png, the figure of the section
"Building a Blended Shape by Hand" of the manual, from the files written by
the example examples/build_mug_by_hand.cpp.

Needs Debian's python3-matplotlib. From anywhere:

    /usr/bin/python3 doc/Blended_shape/fig/scripts/mug_by_hand_figure.py [--example PATH | --prefix PREFIX]

By default it runs the example (default: build/bin/build_mug_by_hand of the
source tree; build it first) in a temporary directory. With --prefix it reads
PREFIX.ply (the pieces, colored by component) and PREFIX.off (the unified
mesh) written by an earlier run instead.
"""

import argparse
import os
import struct
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

PLY_TYPES = {"char": "b", "int8": "b", "uchar": "B", "uint8": "B", "short": "h", "int16": "h",
             "ushort": "H", "uint16": "H", "int": "i", "int32": "i", "uint": "I", "uint32": "I",
             "float": "f", "float32": "f", "double": "d", "float64": "d"}


def read_ply(path):
    """Vertices (n x 3), triangles (m x 3) and per-face RGB colours (m x 3, in [0, 1])
    of an ASCII or binary little-endian PLY file with face properties red, green, blue."""
    with open(path, "rb") as f:
        data = f.read()
    end = data.index(b"end_header") + len(b"end_header")
    end = data.index(b"\n", end) + 1
    header = data[:end].decode("ascii").splitlines()
    binary = any(line.startswith("format binary_little_endian") for line in header)
    elements = []  # (name, count, [(property name, type or ("list", count type, item type))])
    for line in header:
        w = line.split()
        if w[:1] == ["element"]:
            elements.append((w[1], int(w[2]), []))
        elif w[:1] == ["property"]:
            prop = (w[4], ("list", w[2], w[3])) if w[1] == "list" else (w[2], w[1])
            elements[-1][2].append(prop)
    vertices, faces, colours = [], [], []
    if binary:
        pos = end
        for name, count, props in elements:
            for _ in range(count):
                rec = {}
                for pname, ptype in props:
                    if isinstance(ptype, tuple):
                        (n,) = struct.unpack_from("<" + PLY_TYPES[ptype[1]], data, pos)
                        pos += struct.calcsize(PLY_TYPES[ptype[1]])
                        fmt = "<%d%s" % (n, PLY_TYPES[ptype[2]])
                        rec[pname] = struct.unpack_from(fmt, data, pos)
                        pos += struct.calcsize(fmt)
                    else:
                        (rec[pname],) = struct.unpack_from("<" + PLY_TYPES[ptype], data, pos)
                        pos += struct.calcsize(PLY_TYPES[ptype])
                store(name, rec, vertices, faces, colours)
    else:
        tokens = iter(data[end:].decode("ascii").split())
        for name, count, props in elements:
            for _ in range(count):
                rec = {}
                for pname, ptype in props:
                    if isinstance(ptype, tuple):
                        n = int(next(tokens))
                        rec[pname] = tuple(int(next(tokens)) for _ in range(n))
                    else:
                        rec[pname] = float(next(tokens))
                store(name, rec, vertices, faces, colours)
    return np.array(vertices), np.array(faces, dtype=int), np.array(colours) / 255.0


def store(element, rec, vertices, faces, colours):
    if element == "vertex":
        vertices.append((rec["x"], rec["y"], rec["z"]))
    elif element == "face":
        faces.append(rec.get("vertex_indices", rec.get("vertex_index")))
        colours.append((rec.get("red", 200), rec.get("green", 200), rec.get("blue", 200)))


def read_off(path):
    with open(path) as f:
        words = [w for line in f for w in line.split("#")[0].split()]
    if words[0] != "OFF":
        raise ValueError("%s is not an OFF file" % path)
    nv, nf = int(words[1]), int(words[2])
    k = 4
    v = np.array(words[k:k + 3 * nv], dtype=float).reshape(nv, 3)
    k += 3 * nv
    faces = []
    for _ in range(nf):
        n = int(words[k])
        faces.append([int(x) for x in words[k + 1:k + 1 + n]])
        k += 1 + n
    return v, np.array(faces, dtype=int)


def add_surface(ax, v, faces, colours, light=(0.3, -0.6, 0.75), edge=None):
    tris = v[faces]
    n = np.cross(tris[:, 1] - tris[:, 0], tris[:, 2] - tris[:, 0])
    n /= np.maximum(np.linalg.norm(n, axis=1), 1e-300)[:, None]
    light = np.asarray(light) / np.linalg.norm(light)
    k = 0.35 + 0.65 * np.clip(n @ light, 0.0, None)
    fc = np.clip(colours * k[:, None], 0.0, 1.0)
    coll = Poly3DCollection(tris, facecolors=fc, edgecolors=fc if edge is None else edge, linewidths=0.05)
    ax.add_collection3d(coll)


def equal_axes(ax, pts, zoom=1.0):
    lo, hi = pts.min(axis=0), pts.max(axis=0)
    c, r = 0.5 * (lo + hi), 0.5 * (hi - lo).max()
    ax.set_xlim(c[0] - r, c[0] + r)
    ax.set_ylim(c[1] - r, c[1] + r)
    ax.set_zlim(c[2] - r, c[2] + r)
    ax.set_box_aspect((1, 1, 1), zoom=zoom)


def figure(prefix, path):
    pv, pf, pc = read_ply(prefix + ".ply")
    uv, uf = read_off(prefix + ".off")
    fig = plt.figure(figsize=(10, 4.8))
    panels = [("the pieces, colored by component (%s.ply)" % os.path.basename(prefix), pv, pf, pc, (25, -30)),
              ("the unified closed mesh, genus 1 (%s.off)" % os.path.basename(prefix), uv, uf,
               np.tile([0.80, 0.80, 0.84], (len(uf), 1)), (10, -75))]
    for k, (title, v, f, c, (elev, azim)) in enumerate(panels):
        ax = fig.add_subplot(1, 2, k + 1, projection="3d")
        add_surface(ax, v, f, c)
        equal_axes(ax, np.vstack([pv, uv]), zoom=1.3)
        ax.view_init(elev=elev, azim=azim)
        ax.set_axis_off()
        fig.text(0.25 + 0.5 * k, 0.03, title, ha="center", fontsize=10)
    fig.suptitle("examples/build_mug_by_hand.cpp: a body, a handle blended in as a part, "
                 "a hole through the handle (tube domain, opened)", fontsize=10)
    fig.subplots_adjust(left=0.0, right=1.0, bottom=0.06, top=0.94, wspace=0.0)
    fig.savefig(path, dpi=90)
    plt.close(fig)


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--example", default=os.path.join(ROOT, "build", "bin", "build_mug_by_hand"),
                        help="the build_mug_by_hand executable (default: build/bin/build_mug_by_hand)")
    parser.add_argument("--prefix", help="read PREFIX.ply and PREFIX.off instead of running the example")
    parser.add_argument("--output", default=os.path.join(FIG, "mug_by_hand.png"), help="the picture to write")
    args = parser.parse_args()
    if args.prefix:
        figure(args.prefix, args.output)
        return 0
    if not os.path.exists(args.example):
        print("mug_by_hand_figure.py: %s not found; build the example first or give --example or --prefix"
              % args.example, file=sys.stderr)
        return 1
    with tempfile.TemporaryDirectory() as tmp:
        prefix = os.path.join(tmp, "mug_by_hand")
        subprocess.run([args.example, prefix], check=True, stdout=subprocess.DEVNULL)
        figure(prefix, args.output)
    return 0


if __name__ == "__main__":
    sys.exit(main())
