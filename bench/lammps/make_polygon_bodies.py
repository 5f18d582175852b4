#!/usr/bin/env python3
"""LAMMPS data file of rounded polygons (atom_style body rounded/polygon) from a mesh of polygon cells.

usage: make_polygon_bodies.py MESH.h5 OUT.data [--round 0.02] [--min-edge 6] [--min-turn 20] [--stats]

MESH.h5 is a mesh-gen voronoi mesh (docs/SCHEMA.md), normally the compressed packing of compress_mesh.py,
read with h5py when it is installed, else through h5dump's text output. Every cell becomes one body at its
centroid (units si), of the cell's mass rho*h*A and inertia tensor (Ixx = rho h int y^2 dA, Iyy = rho h
int x^2 dA, Izz = rho h J, Ixy = -rho h int xy dA: the same masses and moments as dem-run's cells), whose
shape is the cell's polygon shrunk inwards by the rounding radius R = ROUND * g (g the mesh spacing; the
polygon clipped by its sides moved in by R), with edges shorter than MIN_EDGE * R merged and corners
turning by less than MIN_TURN degrees removed (see simplify()), vertices relative to the centroid, and
rounded diameter 2R. Core plus rounding is the cell's polygon with rounded corners, so two bodies overlap
about as deep as dem-run's two cells do. pair body/rounded/polygon needs the overlap well below 2R (its
contact is a core vertex within 2R of a core edge; past 2R a vertex crosses the edge and is pushed the wrong
way): compress_mesh.py's default 0.002 strain gives ~2e-5 m for 1 cm cells, 2R = 4e-4 m.

--stats replays, in Python, the contact detection of pair body/rounded/polygon (vertex_against_edge,
compute_distance_to_vertex, k_na = 0, cut_inner = 0) at t = 0 and prints the pairs in contact per body,
the vertex-edge contacts per pair (LAMMPS keeps at most 4 per pair: MAX_CONTACTS), and the pair energy
sum 0.5 k_n R^2 that LAMMPS's first thermo line should show as pe (k_n from --kn). Slow (pure Python):
seconds for 10^4 cells, use it on the small mesh.
"""
import argparse
import math
import re
import subprocess
import sys


def read_mesh(path):
    """(vertex_offset, vertex [(x, y)], centroid [(x, y)], spacing, bounds) of a mesh of cells."""
    try:
        import h5py  # noqa: F401
        have_h5py = True
    except ImportError:
        have_h5py = False
    if have_h5py:
        import h5py
        with h5py.File(path, "r") as f:
            c = f["particles/cells"]
            off = [int(v) for v in c["vertex_offset"][...]]
            vert = [(float(x), float(y)) for x, y in c["vertex"][...]]
            cen = [(float(x), float(y)) for x, y in c["centroid"][...]]
            g = float(c.attrs["spacing"])
            bounds = [float(b) for b in c["box"].attrs["bounds"]]
        return off, vert, cen, g, bounds

    def dump(args):
        out = subprocess.run(["h5dump"] + args + [path], check=True, capture_output=True, text=True).stdout
        body = out[out.index("DATA {") + 6:]
        body = body[:body.index("}")]
        return [float(t) for t in re.split(r"[\s,]+", body) if t and not t.startswith("(")]

    off = [int(v) for v in dump(["-y", "-w", "0", "-d", "/particles/cells/vertex_offset"])]
    v = dump(["-y", "-w", "0", "-m", "%.17g", "-d", "/particles/cells/vertex"])
    c = dump(["-y", "-w", "0", "-m", "%.17g", "-d", "/particles/cells/centroid"])
    g = dump(["-m", "%.17g", "-a", "/particles/cells/spacing"])[0]
    bounds = dump(["-m", "%.17g", "-a", "/particles/cells/box/bounds"])
    return off, list(zip(v[0::2], v[1::2])), list(zip(c[0::2], c[1::2])), g, bounds


def clip(poly, nx, ny, c):
    """The part of convex polygon `poly` where nx*x + ny*y >= c (Sutherland-Hodgman, one line)."""
    out = []
    m = len(poly)
    for k in range(m):
        px, py = poly[k]
        qx, qy = poly[(k + 1) % m]
        sp = nx * px + ny * py - c
        sq = nx * qx + ny * qy - c
        if sp >= 0:
            out.append((px, py))
        if (sp >= 0) != (sq >= 0):
            t = sp / (sp - sq)
            out.append((px + t * (qx - px), py + t * (qy - py)))
    return out


def shrink(poly, r, tol):
    """Convex counter-clockwise polygon `poly` with every side moved inwards by r; near-duplicate vertices
    (closer than tol, from sides that vanished) merged."""
    out = poly
    m = len(poly)
    for k in range(m):
        ax, ay = poly[k]
        bx, by = poly[(k + 1) % m]
        ex, ey = bx - ax, by - ay
        ln = math.hypot(ex, ey)
        if ln == 0:
            continue
        nx, ny = -ey / ln, ex / ln  # inward (left) normal of a counter-clockwise polygon
        out = clip(out, nx, ny, nx * ax + ny * ay + r)
        if len(out) < 3:
            return out
    return simplify(out, tol, 0.0)


def simplify(poly, min_edge, min_turn):
    """Convex polygon `poly` without short edges and flat corners, which pair body/rounded/polygon cannot
    take: an edge shorter than min_edge becomes one vertex at its middle, and a vertex where the boundary
    turns by less than min_turn (radians) goes; while more than 3 vertices remain. Stays convex (a vertex on
    the boundary, or fewer vertices). LAMMPS counts a contact per vertex and edge within the two rounding
    radii, in an array of 4 per pair (MAX_CONTACTS, unchecked): near-duplicate vertices, or one vertex near
    two nearly collinear edges, overflow it when neighbours press their sides together."""
    p = list(poly)
    while len(p) > 3:
        m = len(p)
        lens = [math.hypot(p[(k + 1) % m][0] - p[k][0], p[(k + 1) % m][1] - p[k][1]) for k in range(m)]
        k = min(range(m), key=lens.__getitem__)
        if lens[k] < min_edge:
            q = p[(k + 1) % m]
            mid = (0.5 * (p[k][0] + q[0]), 0.5 * (p[k][1] + q[1]))
            if k + 1 < m:
                p[k:k + 2] = [mid]
            else:
                p = [mid] + p[1:-1]
            continue
        turns = []
        for k in range(m):
            ax, ay = p[k - 1]
            bx, by = p[k]
            cx, cy = p[(k + 1) % m]
            turns.append(math.atan2((bx - ax) * (cy - by) - (by - ay) * (cx - bx),
                                    (bx - ax) * (cx - bx) + (by - ay) * (cy - by)))
        k = min(range(m), key=turns.__getitem__)
        if turns[k] < min_turn:
            del p[k]
            continue
        break
    return p


def moments(poly):
    """(area, int x^2 dA, int y^2 dA, int xy dA) of a counter-clockwise polygon about the origin."""
    a = ixx = iyy = ixy = 0.0
    m = len(poly)
    for k in range(m):
        x0, y0 = poly[k]
        x1, y1 = poly[(k + 1) % m]
        cr = x0 * y1 - x1 * y0
        a += cr
        ixx += cr * (x0 * x0 + x0 * x1 + x1 * x1)
        iyy += cr * (y0 * y0 + y0 * y1 + y1 * y1)
        ixy += cr * (x0 * y1 + 2 * x0 * y0 + 2 * x1 * y1 + x1 * y0)
    return a / 2, ixx / 12, iyy / 12, ixy / 24


def stats(bodies, r, kn):
    """Replays pair body/rounded/polygon's contact detection at t = 0 (k_na = 0, cut_inner = 0)."""
    n = len(bodies)
    erad = [max(math.hypot(x, y) for x, y in b[1]) for b in bodies]
    rad = [e + r for e in erad]
    world = [[(b[0][0] + x, b[0][1] + y) for x, y in b[1]] for b in bodies]
    side = 2 * max(rad)
    grid = {}
    for i, b in enumerate(bodies):
        grid.setdefault((int(b[0][0] // side), int(b[0][1] // side)), []).append(i)
    cd = 2 * r  # contact distance: the two rounded radii
    eps = 1e-3 * r

    def vertex_against_edge(i, j, res):
        xj, yj = bodies[j][0]
        pj = world[j]
        m = len(pj)
        for (vx, vy) in world[i]:
            if math.hypot(vx - xj, vy - yj) > erad[j] + 2 * r:
                continue
            for e in range(m):
                ax, ay = pj[e]
                bx, by = pj[(e + 1) % m]
                ex, ey = bx - ax, by - ay
                le = math.hypot(ex, ey)
                ux, uy = ex / le, ey / le
                s = (vx - ax) * ux + (vy - ay) * uy
                hx, hy = ax + s * ux, ay + s * uy
                d = math.hypot(vx - hx, vy - hy)
                if d > cd:
                    continue
                t = s / le
                if 0 <= t <= 1:
                    R = d - cd
                    if R <= 0:
                        res["energy"] += 0.5 * kn * R * R
                    if d < cd + eps:
                        res["edge"] += 1
                else:
                    px, py = (ax, ay) if t < 0 else (bx, by)
                    dv = math.hypot(vx - px, vy - py)
                    if dv <= cd:
                        R = dv - cd
                        res["energy"] += 0.5 * kn * R * R
                        res["vv"] += 1

    near = 0
    touching = 0
    edge_hist = {}
    energy = 0.0
    for i, b in enumerate(bodies):
        gx, gy = int(b[0][0] // side), int(b[0][1] // side)
        for dx in (-1, 0, 1):
            for dy in (-1, 0, 1):
                for j in grid.get((gx + dx, gy + dy), ()):
                    if j <= i:
                        continue
                    dist = math.hypot(bodies[j][0][0] - b[0][0], bodies[j][0][1] - b[0][1])
                    if dist > rad[i] + rad[j]:
                        continue
                    near += 1
                    res = {"edge": 0, "vv": 0, "energy": 0.0}
                    vertex_against_edge(i, j, res)
                    vertex_against_edge(j, i, res)
                    energy += res["energy"]
                    if res["edge"] or res["vv"]:
                        touching += 1
                    edge_hist[res["edge"]] = edge_hist.get(res["edge"], 0) + 1
    print(f"stats: {n} bodies, {near} pairs within their enclosing circles ({near / n:.2f} per body), "
          f"{touching} pairs in contact ({touching / n:.2f} per body, {2 * touching / n:.2f} contacts per body)")
    print("stats: vertex-edge contacts per pair -> pairs: " +
          ", ".join(f"{k}: {v}" for k, v in sorted(edge_hist.items())))
    if max(edge_hist) > 4:
        print("stats: WARNING: pairs with more than 4 vertex-edge contacts (LAMMPS's MAX_CONTACTS)")
    print(f"stats: pair energy at t = 0, sum 0.5 k_n R^2 = {energy:.6g} J (k_n = {kn:g} N/m)")


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("mesh")
    ap.add_argument("out")
    ap.add_argument("--round", type=float, default=0.02, help="rounding radius R over the mesh spacing g (0.02)")
    ap.add_argument("--density", type=float, default=5000.0, help="kg/m^3 (pulse.ini: 5000)")
    ap.add_argument("--thickness", type=float, default=0.01, help="m (pulse.ini: 0.01)")
    ap.add_argument("--margin", type=float, default=5.0, help="box margin around the mesh's bounds, in g (5)")
    ap.add_argument("--min-edge", type=float, default=6.0, help="shortest core edge, in R (6); see simplify()")
    ap.add_argument("--min-turn", type=float, default=20.0, help="flattest core corner kept, degrees of turn (20)")
    ap.add_argument("--stats", action="store_true", help="replay LAMMPS's contact detection at t = 0")
    ap.add_argument("--kn", type=float, default=5e6, help="k_n for --stats' energy, N/m (5e6)")
    a = ap.parse_args()

    off, vert, cen, g, bnd = read_mesh(a.mesh)
    n = len(cen)
    r = a.round * g
    rho_h = a.density * a.thickness
    bodies = []
    nmin, nmax = 1 << 30, 0
    for k in range(n):
        poly = vert[off[k]:off[k + 1]]
        core = simplify(shrink(poly, r, 1e-6 * g), a.min_edge * r, math.radians(a.min_turn))
        if len(core) < 3:
            sys.exit(f"cell {k} vanishes when shrunk by {r} m: use a smaller --round")
        area, x2, y2, xy = moments(poly)
        bodies.append(((cen[k][0], cen[k][1]), core, rho_h * area, (rho_h * y2, rho_h * x2, rho_h * (x2 + y2), -rho_h * xy)))
        nmin, nmax = min(nmin, len(core)), max(nmax, len(core))

    m = a.margin * g
    out = [f"LAMMPS data file: {n} rounded polygons from {a.mesh} (make_polygon_bodies.py --round {a.round}, "
           f"rho {a.density} kg/m^3, h {a.thickness} m, units si); vertices per body {nmin}..{nmax}\n\n",
           f"{n} atoms\n{n} bodies\n1 atom types\n\n",
           f"{bnd[0] - m:.17g} {bnd[2] + m:.17g} xlo xhi\n{bnd[1] - m:.17g} {bnd[3] + m:.17g} ylo yhi\n"
           f"{-0.5 * g:.17g} {0.5 * g:.17g} zlo zhi\n\nAtoms # body\n\n"]
    w = out.append
    for k, b in enumerate(bodies):
        w(f"{k + 1} 1 1 {b[2]:.17g} {b[0][0]:.17g} {b[0][1]:.17g} 0\n")
    w("\nBodies\n\n")
    for k, b in enumerate(bodies):
        core, inertia = b[1], b[3]
        w(f"{k + 1} 1 {6 + 3 * len(core) + 1}\n{len(core)}\n")
        w(f"{inertia[0]:.17g} {inertia[1]:.17g} {inertia[2]:.17g} {inertia[3]:.17g} 0 0\n")
        for x, y in core:
            w(f"{x:.17g} {y:.17g} 0\n")
        w(f"{2 * r:.17g}\n")
    with open(a.out, "w") as f:
        f.write("".join(out))
    print(f"{a.out}: {n} bodies, {nmin}..{nmax} vertices (atom_style body rounded/polygon {nmin} {nmax}), "
          f"rounding radius {r:g} m, spacing {g:g} m")
    if a.stats:
        stats([(b[0], b[1]) for b in bodies], r, a.kn)


if __name__ == "__main__":
    main()
