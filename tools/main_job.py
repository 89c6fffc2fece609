# The README's main job, run headless by `tools/setup.sh demo` (freecadcmd tools/main_job.py):
# the whole pipeline on the bundled example part, results under out/. Today the pipeline ends at
# the decomposition into sub-components; each stage added to the product extends this job.
#   MAS_EXAMPLE  the part (default examples/bracket.step)
#   MAS_OUT      the output folder (default out/)
import json
import os
import sys
import time

import FreeCAD
import Part

import MultiAxisSlicer as mas

root = os.getcwd()
example = os.environ.get("MAS_EXAMPLE", os.path.join(root, "examples", "bracket.step"))
out = os.environ.get("MAS_OUT", os.path.join(root, "out"))
os.makedirs(out, exist_ok=True)


def main():
    shape = Part.read(example)
    step = 2.0
    start = time.perf_counter()
    sections = mas.sections(shape, normal=(0, 0, 1), step=step)
    seconds = time.perf_counter() - start
    summary = {
        "part": os.path.basename(example),
        "volume_mm3": shape.Volume,
        "faces": len(shape.Faces),
        "deflection_mm": mas.deflection(shape),
        "normal": [0, 0, 1],
        "step_mm": step,
        "seconds": seconds,
        "sections": [s.to_dict() for s in sections],
    }
    with open(os.path.join(out, "sections.json"), "w") as f:
        json.dump(summary, f, indent=1)
    with open(os.path.join(out, "sections.txt"), "w") as f:
        f.write("# %s: %d sections along +Z, %.1f mm apart (%.1f ms)\n"
                % (summary["part"], len(sections), step, 1e3 * seconds))
        f.write("# height_mm regions holes area_mm2 centroid_x centroid_y centroid_z\n")
        for s in sections:
            holes = sum(len(r.holes) for r in s.regions)
            c = s.centroid
            f.write("%.3f %d %d %.4f %.4f %.4f %.4f\n"
                    % (s.origin[2], len(s.regions), holes, s.area, c[0], c[1], c[2]))
    # The centroidal axis (paper Sec. 3), in the command line's JSON layout.
    start = time.perf_counter()
    axis = mas.centroidal_axis(shape)
    axis_seconds = time.perf_counter() - start
    axis_doc = dict(axis.to_dict(), file=os.path.basename(example), seconds=axis_seconds)
    with open(os.path.join(out, "axis.json"), "w") as f:
        json.dump(axis_doc, f, indent=1)
    breaks = sum(1 for link in axis.links if link.is_break)
    # The sub-components (paper Sec. 4.1) along that axis, each also as a STEP file.
    start = time.perf_counter()
    parts = mas.decompose(shape, axis=axis)
    decompose_seconds = time.perf_counter() - start
    for i, component in enumerate(parts):
        component.shape.exportStep(os.path.join(out, "component_%03d.step" % (i + 1)))
    with open(os.path.join(out, "decomposition.json"), "w") as f:
        json.dump(dict(parts.to_dict(), file=os.path.basename(example),
                       seconds=decompose_seconds), f, indent=1)
    # The same as a FreeCAD document: the part with parametric Sections, CentroidalAxis and
    # Decomposition objects (and its Component objects).
    doc = FreeCAD.newDocument("MainJob")
    part = doc.addObject("Part::Feature", "Bracket")
    part.Shape = shape
    axis_object = mas.make_centroidal_axis(part, doc=doc)
    objects = [mas.make_sections(part, normal=(0, 0, 1), step=step, doc=doc), axis_object]
    doc.recompute()
    objects.append(mas.make_decomposition(part, axis=axis_object, doc=doc))
    doc.recompute()
    for obj in objects:
        if obj.State and "Invalid" in obj.State:
            raise RuntimeError("%s failed to recompute: %s" % (obj.Label, obj.State))
    doc.saveAs(os.path.join(out, "bracket.FCStd"))
    print("main job: %d sections of %s in %.1f ms; wrote %s" % (len(sections), summary["part"],
                                                                1e3 * seconds, out))
    print("main job: centroidal axis in %.1f ms: %d nodes, %d branches, %d break links"
          % (1e3 * axis_seconds, len(axis.nodes), len(axis.branches), breaks))
    print("main job: %d sub-components in %.1f ms: %s"
          % (len(parts), 1e3 * decompose_seconds,
             ", ".join("%s along (%g, %g, %g) %.0f mm3" % (c.rule, c.build_direction.x,
                                                       c.build_direction.y, c.build_direction.z,
                                                       c.volume) for c in parts)))
    print("main job: done")


try:
    main()
except Exception as e:  # freecadcmd exits 0 on an uncaught exception: say it and fail loudly
    import traceback
    traceback.print_exc()
    print("main job: FAILED: %s" % e)
    sys.exit(1)
