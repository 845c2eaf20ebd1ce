"""Two parts meshed separately in Gmsh (non-matching contact faces): an aluminium punch
20 x 10 mm standing on a steel base 40 x 10 mm. The parts are not fragmented, so the nodes of
the punch's bottom do not coincide with the base's top: alea pairs them by the mortar method.

Regenerate (Gmsh 4.15, `pip install gmsh`):
    python3 examples/meshes/punch-on-base.py
"""

import os

import gmsh

gmsh.initialize()
gmsh.option.setNumber("General.Terminal", 0)
gmsh.model.add("punch-on-base")
occ = gmsh.model.occ
base = occ.addRectangle(0.0, -10.0, 0.0, 40.0, 10.0)
punch = occ.addRectangle(10.0, 0.0, 0.0, 20.0, 10.0)
occ.synchronize()


def curve_at(surface, test):
    for dim, tag in gmsh.model.getBoundary([(2, surface)], oriented=False):
        x, y, _ = gmsh.model.occ.getCenterOfMass(dim, tag)
        if test(x, y):
            return tag
    raise RuntimeError("curve not found")


groups = {
    "base_bottom": curve_at(base, lambda x, y: abs(y + 10.0) < 1e-9),
    "base_top": curve_at(base, lambda x, y: abs(y) < 1e-9),
    "punch_bottom": curve_at(punch, lambda x, y: abs(y) < 1e-9),
    "punch_top": curve_at(punch, lambda x, y: abs(y - 10.0) < 1e-9),
}
gmsh.model.addPhysicalGroup(2, [base], name="base")
gmsh.model.addPhysicalGroup(2, [punch], name="punch")
for name, tag in groups.items():
    gmsh.model.addPhysicalGroup(1, [tag], name=name)
# Different sizes on the two parts: 2 mm on the base, 1.3 mm on the punch.
gmsh.model.mesh.setSize(gmsh.model.getBoundary([(2, base)], recursive=True), 2.0)
gmsh.model.mesh.setSize(gmsh.model.getBoundary([(2, punch)], recursive=True), 1.3)
gmsh.option.setNumber("Mesh.RecombineAll", 1)
gmsh.option.setNumber("Mesh.Algorithm", 8)
gmsh.option.setNumber("Mesh.MshFileVersion", 4.1)
gmsh.option.setNumber("Mesh.Binary", 0)
gmsh.model.mesh.generate(2)
here = os.path.dirname(os.path.abspath(__file__))
gmsh.write(os.path.join(here, "punch-on-base.msh"))
gmsh.finalize()
