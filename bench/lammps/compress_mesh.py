#!/usr/bin/env python3
"""A dense, uniformly compressed packing of a mesh-gen voronoi mesh, for the contact comparison.

usage: compress_mesh.py MESH.h5 OUT.h5 [--strain EPS]     (needs h5py: apt-get install python3-h5py)

dem-run has no scene key that puts every cell in contact at t = 0 (its loadings start from the stress-free
tessellation and reach the bulk only after a wave has crossed it), so the packing is made here: the same
polygons (vertices, areas, second moments unchanged: the same masses), their centroids moved towards the
box centre, c' = C + (1 - EPS)(c - C) (default EPS = 0.002). Every pair of cells that shared a side then
overlaps by about EPS times their centroid distance (2e-5 m for 1 cm cells): ~3 overlapping pairs per cell.
The strain is small so that LAMMPS's rounded polygons (make_polygon_bodies.py, rounding 2e-4 m) never
overlap past their rounding as the released packing rearranges.
The beams are dropped (empty /connectivity/beams: a beam's section must equal a side the two cells share,
which no longer holds); run it with --physics.beams off. The file is otherwise the input mesh (SCHEMA.md),
and passes mesh-gen check. make_polygon_bodies.py reads it for the LAMMPS side.
"""
import argparse
import shutil

import h5py
import numpy as np


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("mesh")
    ap.add_argument("out")
    ap.add_argument("--strain", type=float, default=0.002, help="EPS, the uniform compressive strain (default 0.002)")
    a = ap.parse_args()
    if not 0 <= a.strain < 0.2:
        raise SystemExit("--strain must lie in [0, 0.2)")
    shutil.copyfile(a.mesh, a.out)
    with h5py.File(a.out, "r+") as f:
        if f.attrs["kind"] != "mesh" or "particles/cells" not in f:
            raise SystemExit(a.mesh + ": not a mesh of polygon cells (mesh-gen voronoi)")
        cells = f["particles/cells"]
        b = cells["box"].attrs["bounds"]
        centre = np.array([0.5 * (b[0] + b[2]), 0.5 * (b[1] + b[3])])
        c = cells["centroid"][...]
        cells["centroid"][...] = centre + (1.0 - a.strain) * (c - centre)
        beams = f["connectivity/beams"]
        for name, dtype, shape, unit in (("pairs", "<i8", (0, 2), None), ("length", "<f8", (0,), "m"),
                                         ("section", "<f8", (0,), "m")):
            del beams[name]
            d = beams.create_dataset(name, shape=shape, dtype=dtype)
            if unit:
                d.attrs.create("unit", unit, dtype=h5py.string_dtype("utf-8"))
    print(f"{a.out}: {len(c)} cells, centroids compressed by {a.strain} towards {centre.tolist()}, beams dropped")


if __name__ == "__main__":
    main()
