# The README's main job, run headless by `tools/setup.sh demo` (freecadcmd tools/main_job.py):
# the whole pipeline on the bundled example part, results under out/. Today the pipeline ends at
# the 5-axis G-code (out/bracket.ngc); each stage added to the product extends this job.
#   MAS_EXAMPLE  the part (default examples/bracket.step)
#   MAS_OUT      the output folder (default out/)
import json
import math
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


# Round holes up to this diameter whose ceilings would overhang are deposited solid and listed to
# drill afterwards: the bracket's 12 mm pin hole through its upright.
FILL_HOLES = 12.0


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
    # Adaptive multi-axis layers of every sub-component and the bead paths in every layer
    # (paper Sec. 4.2), in the command line's JSON layout, plus a line per layer.
    start = time.perf_counter()
    sliced = mas.slice(shape, components=parts, fill_holes=FILL_HOLES)
    slice_seconds = time.perf_counter() - start
    with open(os.path.join(out, "slice.json"), "w") as f:
        json.dump(dict(sliced.to_dict(), file=os.path.basename(example), seconds=slice_seconds),
                  f)
    stats = sliced.stats
    with open(os.path.join(out, "layers.txt"), "w") as f:
        f.write("# %s: %d layers in %d sub-components (%.1f ms); thickness %.3f to %.3f mm; "
                "deposited %.1f of %.1f mm3 (%.1f of it in holes filled); worst unsupported area "
                "%.2f mm2 (layer %d)\n"
                % (os.path.basename(example), stats["layer_count"], len(sliced.components),
                   1e3 * slice_seconds, stats["min_thickness_mm"], stats["max_thickness_mm"],
                   stats["deposited_volume_mm3"], stats["part_volume_mm3"],
                   stats["filled_volume_mm3"],
                   stats["worst_unsupported_area_mm2"], stats["worst_unsupported_layer"]))
        for h in sliced.filled_holes:
            f.write("# deposited solid, to drill afterwards: a hole %.3f mm across, %.3f mm long, "
                    "at (%.3f, %.3f, %.3f) along (%g, %g, %g), component %d\n"
                    % (h.diameter, h.length, h.centre.x, h.centre.y, h.centre.z, h.axis.x,
                       h.axis.y, h.axis.z, h.component))
        for note in sliced.notes:
            f.write("# note: %s\n" % note)
        f.write("# deposition sequence (layers, checked against the nozzle): %s\n"
                % " ".join(str(i) for i in sliced.sequence))
        for i in sliced.leaned_layers():
            a = sliced.tool_axis(i)
            f.write("# leaned: layer %d deposited with the nozzle %.4g degrees off its normal, "
                    "along (%g, %g, %g)\n" % (i, math.degrees(a.getAngle(sliced.layers[i].normal)),
                                              a.x, a.y, a.z))
        for c in sliced.collisions:
            f.write("# collision: layer %d's nozzle meets %s near (%.3f, %.3f, %.3f)\n"
                    % (c.layer, "the build plate" if c.obstacle_layer < 0 else
                       "layer %d" % c.obstacle_layer, c.obstacle.x, c.obstacle.y, c.obstacle.z))
        f.write("# layer component origin_x origin_y origin_z normal_x normal_y normal_z "
                "min_thickness max_thickness area_mm2 volume_difference unsupported_mm2 "
                "deposit_mm travel_mm\n")
        for i, layer in enumerate(sliced.layers):
            o, n = layer.origin, layer.normal
            paths = sliced.paths(i)
            deposit = sum(p.length() for p in paths if p.deposit)
            travel = sum(p.length() for p in paths if not p.deposit)
            f.write("%d %d %.4f %.4f %.4f %.6f %.6f %.6f %.4f %.4f %.3f %.5f %.3f %.2f %.2f\n"
                    % (i, layer.component, o.x, o.y, o.z, n.x, n.y, n.z, layer.min_thickness,
                       layer.max_thickness, layer.area, layer.volume_difference,
                       layer.unsupported_area, deposit, travel))
    # The machine program: LinuxCNC G-code for a tilting rotary table (XYZAC).
    start = time.perf_counter()
    program = sliced.gcode()
    gcode_seconds = time.perf_counter() - start
    program.write(os.path.join(out, "bracket.ngc"))
    # The same as a FreeCAD document: the part with parametric Sections, CentroidalAxis,
    # Decomposition (and its Component objects), Layers, Toolpath, MachineProgram and
    # BuildPreview (the whole build, the nozzle on the last layer) objects.
    doc = FreeCAD.newDocument("MainJob")
    part = doc.addObject("Part::Feature", "Bracket")
    part.Shape = shape
    axis_object = mas.make_centroidal_axis(part, doc=doc)
    objects = [mas.make_sections(part, normal=(0, 0, 1), step=step, doc=doc), axis_object]
    doc.recompute()
    decomposition_object = mas.make_decomposition(part, axis=axis_object, doc=doc)
    objects.append(decomposition_object)
    layers_object, toolpath_object = mas.make_slice(decomposition_object, doc=doc,
                                                    fill_holes=FILL_HOLES)
    objects += [layers_object, toolpath_object, mas.make_machine_program(layers_object, doc=doc),
                mas.make_build_preview(layers_object, doc=doc)]
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
    print("main job: %d layers in %.1f ms, %.3f to %.3f mm thick, %.0f mm of deposit paths, "
          "worst unsupported area %.2f mm2" % (stats["layer_count"], 1e3 * slice_seconds,
                                                stats["min_thickness_mm"],
                                                stats["max_thickness_mm"],
                                                stats["deposit_length_mm"],
                                                stats["worst_unsupported_area_mm2"]))
    print("main job: layers deposited in a sequence with %d switches between components; "
          "%d layer(s) with the nozzle leaned to clear; %d layer(s) where the nozzle meets what is "
          "deposited" % (stats["component_switches"], stats["leaned_layers"],
                         stats["colliding_layers"]))
    print("main job: %d hole(s) deposited solid, to drill afterwards: %s"
          % (len(sliced.filled_holes), ", ".join(
              "%g mm across at (%g, %g, %g)" % (h.diameter, h.centre.x, h.centre.y, h.centre.z)
              for h in sliced.filled_holes) or "none"))
    g = program.stats
    print("main job: G-code in %.1f ms: %d lines, %d deposit moves, A %g to %g deg, deposit time "
          "%.1f min; wrote %s" % (1e3 * gcode_seconds, g["lines"], g["deposit_moves"],
                                  *g["a_range_deg"], g["deposit_time_min"],
                                  os.path.join(out, "bracket.ngc")))
    print("main job: travel checked against the nozzle: %d routes, %d taken round the part, %d "
          "meeting what is deposited" % (g["checked_routes"], g["rerouted_travels"],
                                         len(g["travel_collisions"])))
    print("main job: done")


try:
    main()
except Exception as e:  # freecadcmd exits 0 on an uncaught exception: say it and fail loudly
    import traceback
    traceback.print_exc()
    print("main job: FAILED: %s" % e)
    sys.exit(1)
