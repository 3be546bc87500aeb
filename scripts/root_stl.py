"""Write an aortic-root surface as a segmentation would give it (STL, in mm, open at both ends)
and its landmarks (JSON, mm), for the bring-your-own-valve path (docs/patient_valve.md):
  /usr/bin/python3 scripts/root_stl.py OUT.stl [--asymmetric] [--ascii] [--h MM]
The idealised root is meshes/valve.geo's (annulus radius 12.5 mm, 15 mm of LVOT, three Valsalva
sinus bulges centred on the wall at the commissure height 16.875 mm, 50 mm of aorta above it).
--asymmetric: an elliptic annulus (semi-axes 13.5 and 11.5 mm) and unequal sinuses (depths 4,
3 and 5 mm), the kind of root a patient brings.  Landmarks (OUT.json): the three commissures
(on the wall at the commissure height, at 30, 150, 270 degrees) and the three sinus bottoms
(the leaflets' nadirs, on the wall at the annulus plane z = 0, at 90, 210, 330 degrees), in
counter-clockwise order about the flow direction (+z), nadir k between commissures k and k+1."""
import argparse
import json
import math

import gmsh

RA, LIN, LOUT, ZC = 12.5, 15.0, 50.0, 16.875  # [mm], valve.geo's defaults (zc = 1.25 x 13.5)
SWIDTH, SHEIGHT = 9.0, 0.75 * ZC  # [mm] the sinus bulges' half-width and half-height


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("out")
    ap.add_argument("--asymmetric", action="store_true")
    ap.add_argument("--ascii", action="store_true")
    ap.add_argument("--h", type=float, default=1.5, help="triangle size [mm] (default 1.5)")
    a = ap.parse_args()
    ax, ay = (13.5 / RA, 11.5 / RA) if a.asymmetric else (1.0, 1.0)
    depths = (4.0, 3.0, 5.0) if a.asymmetric else (4.0, 4.0, 4.0)

    gmsh.initialize()
    gmsh.option.setNumber("General.Verbosity", 1)
    occ = gmsh.model.occ
    tube = occ.addCylinder(0, 0, -LIN, 0, 0, LIN + ZC + LOUT, RA)
    occ.rotate([(3, tube)], 0, 0, 0, 0, 0, 1, math.pi / 6)  # its seam at a commissure
    bulges = []
    for k, depth in enumerate(depths):
        b = occ.addSphere(0, 0, 0, 1)
        occ.dilate([(3, b)], 0, 0, 0, depth, SWIDTH, SHEIGHT)
        occ.translate([(3, b)], RA, 0, ZC)
        occ.rotate([(3, b)], 0, 0, 0, 0, 0, 1, math.pi / 2 + 2 * math.pi * k / 3)
        bulges.append((3, b))
    root, _ = occ.fuse([(3, tube)], bulges)
    occ.dilate(root, 0, 0, 0, ax, ay, 1)
    occ.synchronize()
    # The wall only: the two flat ends are the segmentation's open cuts.
    ends = (-LIN, ZC + LOUT)
    wall = [s for _, s in gmsh.model.getBoundary(root, oriented=False)
            if min(abs(occ.getCenterOfMass(2, s)[2] - z) for z in ends) > 1e-6]
    gmsh.model.addPhysicalGroup(2, wall)
    gmsh.option.setNumber("Mesh.MeshSizeMin", a.h)
    gmsh.option.setNumber("Mesh.MeshSizeMax", a.h)
    gmsh.model.mesh.generate(2)
    gmsh.option.setNumber("Mesh.Binary", 0 if a.ascii else 1)
    gmsh.write(a.out)
    gmsh.finalize()

    def wall_point(deg, z):
        th = math.radians(deg)
        return [round(RA * ax * math.cos(th), 6), round(RA * ay * math.sin(th), 6), z]

    marks = {"unit": "mm",
             "commissures": [wall_point(30 + 120 * k, ZC) for k in range(3)],
             "sinus_bottoms": [wall_point(90 + 120 * k, 0.0) for k in range(3)]}
    with open(a.out.rsplit(".", 1)[0] + ".json", "w") as f:
        f.write("{\n" + ",\n".join(f' "{k}": {json.dumps(v)}' for k, v in marks.items()) + "\n}\n")
    print(f"root_stl: {a.out} ({'asymmetric' if a.asymmetric else 'idealised'} root, "
          f"{'ASCII' if a.ascii else 'binary'}), landmarks {a.out.rsplit('.', 1)[0]}.json")


if __name__ == "__main__":
    main()
