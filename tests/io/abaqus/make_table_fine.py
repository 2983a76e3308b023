# Writes table-fine.inp: the table frame of table-mesh.inp at a converged mesh (16 x 8 S8R plate, 8 B32R per leg).
nx, ny, nl = 16, 8, 8
nodes = {}
def nid(x, y, z):
    key = (round(x, 9), round(y, 9), round(z, 9))
    if key not in nodes: nodes[key] = len(nodes) + 1
    return nodes[key]
dx, dy = 2.0 / nx, 1.0 / ny
shells = []
for j in range(ny):
    for i in range(nx):
        x0, y0 = i * dx, j * dy
        c = [nid(x0, y0, 0), nid(x0 + dx, y0, 0), nid(x0 + dx, y0 + dy, 0), nid(x0, y0 + dy, 0)]
        m = [nid(x0 + dx / 2, y0, 0), nid(x0 + dx, y0 + dy / 2, 0), nid(x0 + dx / 2, y0 + dy, 0), nid(x0, y0 + dy / 2, 0)]
        shells.append(c + m)
legs, feet = [], []
for (x, y) in [(0, 0), (2, 0), (2, 1), (0, 1)]:
    pts = [nid(x, y, -1 + k / (2 * nl)) for k in range(2 * nl + 1)]
    feet.append(pts[0])
    legs += [(pts[2 * e], pts[2 * e + 1], pts[2 * e + 2]) for e in range(nl)]
out = ["** The table frame of table-mesh.inp at a mesh where CalculiX and rigflex have both converged:",
       "** a 2 x 1 m steel plate of 16 x 8 S8R (12 mm) on four pipe legs of 8 B32R each",
       "** (100 x 5 mm, 1 m, clamped feet), 200 kg on the plate's centre node and a",
       "** 1e6 N/m vertical spring under the middle of its front edge. Written by",
       "** make_table_fine.py; read by tests/verification/test_calculix_deck_import.cpp.",
       "*HEADING", "table, converged mesh", "*NODE, NSET=NALL"]
for (x, y, z), k in sorted(nodes.items(), key=lambda kv: kv[1]):
    out.append(f"{k}, {x:.9g}, {y:.9g}, {z:.9g}")
out.append("*ELEMENT, TYPE=S8R, ELSET=PLATE")
out += [f"{e + 1}, " + ", ".join(map(str, s)) for e, s in enumerate(shells)]
out.append("*ELEMENT, TYPE=B32R, ELSET=LEGS")
out += [f"{1001 + e}, {a}, {b}, {c}" for e, (a, b, c) in enumerate(legs)]
out += ["*ELEMENT, TYPE=MASS, ELSET=BLOCK", f"2001, {nid(1, 0.5, 0)}",
        "*ELEMENT, TYPE=SPRING1, ELSET=SPRING", f"2002, {nid(1, 0, 0)}",
        "*NSET, NSET=FEET", ", ".join(map(str, feet)),
        "*MATERIAL, NAME=STEEL", "*ELASTIC", "2.1e11, 0.3", "*DENSITY", "7850.",
        "*SHELL SECTION, ELSET=PLATE, MATERIAL=STEEL", "0.012",
        "*BEAM SECTION, ELSET=LEGS, MATERIAL=STEEL, SECTION=PIPE", "0.05, 0.005", "1., 0., 0.",
        "*MASS, ELSET=BLOCK", "200.", "*SPRING, ELSET=SPRING", "3", "1.e6",
        "*BOUNDARY", "FEET, 1, 6", "*STEP", "*FREQUENCY", "10", "*END STEP"]
open("table-fine.inp", "w").write("\n".join(out) + "\n")
