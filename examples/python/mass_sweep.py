"""A sweep in Python: how the rigid and the flexible identification's CoG
height error grows as the body gets heavier on the large rig's soft frame,
plotted with matplotlib.

Sample run (from the repository root; PYTHONPATH=build/python unless the
module is installed):
    $ python3 examples/python/mass_sweep.py --out mass_sweep.png
    mass 1457 kg: rigid zG error -26.6 mm, flexible -0.01 mm
    mass 2186 kg: rigid zG error -38.5 mm, flexible -0.01 mm
    mass 2914 kg: rigid zG error -49.2 mm, flexible -0.00 mm
    mass 4371 kg: rigid zG error -69.8 mm, flexible +0.01 mm
    mass 5828 kg: rigid zG error -87.1 mm, flexible +0.02 mm
    wrote mass_sweep.png
(about 4 s).
Each mass: the body scaled (inertia with it), a virtual measurement of one
set of six pushes, identification by both algorithms against the truth.
"""
import argparse

import matplotlib

matplotlib.use("Agg")  # files, no display
import matplotlib.pyplot as plt
import numpy as np

import rigflex


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--rig", default="examples/large-rig/rig.yaml")
    parser.add_argument("--scales", default="0.5,0.75,1,1.5,2", help="body mass factors")
    parser.add_argument("--out", default="mass_sweep.png")
    args = parser.parse_args()

    rig = rigflex.read_rig(args.rig)
    body = rig.body
    masses, rigid, flexible = [], [], []
    for scale in (float(s) for s in args.scales.split(",")):
        swept = rig.with_body(mass=scale * body["mass"], inertia=scale * body["inertia"])
        sets = rigflex.simulate(swept, sets=1, histories=6, duration=15.0, seed=1)
        result = rigflex.identify(swept, sets, algorithm="both")
        true_z = swept.body["cog"][2]
        dz = {a: 1e3 * (result["algorithms"][a]["mean"]["cog"][2] - true_z) for a in ("rigid", "flexible")}
        masses.append(swept.body["mass"])
        rigid.append(dz["rigid"])
        flexible.append(dz["flexible"])
        print(f"mass {masses[-1]:.0f} kg: rigid zG error {dz['rigid']:+.1f} mm, flexible {dz['flexible']:+.2f} mm")

    fig, ax = plt.subplots(figsize=(7, 4))
    ax.plot(masses, rigid, "o-", label="rigid algorithm")
    ax.plot(masses, flexible, "s--", label="flexible algorithm")
    ax.axhline(0, color="grey", lw=0.8)
    ax.set_xlabel("body + carrying frame mass (kg)")
    ax.set_ylabel("CoG height error, identified - true (mm)")
    ax.set_title(f"{rig.name}: identification error against mass")
    ax.legend()
    fig.tight_layout()
    fig.savefig(args.out, dpi=120)
    print(f"wrote {args.out}")
    return np.isfinite(rigid).all() and np.isfinite(flexible).all()


if __name__ == "__main__":
    raise SystemExit(0 if main() else 1)
