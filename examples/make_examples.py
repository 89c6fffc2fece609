# Regenerates the bundled example parts (run with freecadcmd from the repository root):
#   freecadcmd examples/make_examples.py
# bracket.step: an L-bracket standing on the XY plane: a 80 x 40 x 10 base plate with two
# through holes, a 12 mm thick upright at one end with a horizontal hole, and a round boss on the
# plate: it branches (upright and boss rise from the plate) and has overhang-free and overhanging
# features, which is what the slicer is for.
import os

import FreeCAD
import Part

here = os.path.join(os.getcwd(), "examples")
V = FreeCAD.Vector

plate = Part.makeBox(80, 40, 10)
upright = Part.makeBox(12, 40, 50, V(0, 0, 10))
s = plate.fuse(upright)
for x in (35.0, 65.0):
    s = s.cut(Part.makeCylinder(5, 12, V(x, 20, -1), V(0, 0, 1)))
s = s.cut(Part.makeCylinder(6, 14, V(-1, 20, 40), V(1, 0, 0)))
s = s.fuse(Part.makeCylinder(8, 15, V(50, 20, 10), V(0, 0, 1)))
s = s.removeSplitter()
solid = s.Solids[0]
assert solid.isValid() and len(s.Solids) == 1
solid.exportStep(os.path.join(here, "bracket.step"))
print("bracket.step: %d faces, volume %.3f mm3" % (len(solid.Faces), solid.Volume))
