# The build preview's drawing: its own view provider (each layer's triangles made once, kept while
# its prism is) against Part's (a Part::Feature given the same Shape, every face tessellated and
# drawn anew at each step: what the preview was first), in one run, on a 100 x 100 mm plate with
# 100 posts (1002 layers). Times each from writing the step to the 3D view redrawn: the first
# drawing of the whole build (each layer's triangles the engine's, from its regions), the same as
# after a reopen (from the saved Shape's faces), then steps one at a time and jumps of 100
# (medians).
# Run by the FreeCAD GUI (tools/setup.sh bench does, under xvfb-run; figures in
# out/bench_build_preview.txt):
#   MAS_MOD=build/Mod/MultiAxisSlicer xvfb-run -a freecad tools/bench_build_preview.py
import os
import statistics
import sys
import time
import traceback


def main():
    mod = os.environ["MAS_MOD"]
    sys.path[:0] = [os.path.join(mod, "App"), os.path.join(mod, "Gui")]
    import FreeCAD
    import FreeCADGui
    import Part
    from PySide import QtGui

    import MultiAxisSlicer.features as features

    def drawn(view):
        QtGui.QApplication.processEvents()
        view.redraw()
        QtGui.QApplication.processEvents()

    doc = FreeCAD.newDocument("BenchPreview")
    part = doc.addObject("Part::Feature", "Posts")
    plate = Part.makeBox(100, 100, 4)
    part.Shape = plate.multiFuse([Part.makeCylinder(2.5, 20, FreeCAD.Vector(5 + 10 * i,
                                                                           5 + 10 * j, 4))
                                  for i in range(10) for j in range(10)]).removeSplitter()
    decomposition = features.make_decomposition(part)
    layers, toolpath = features.make_slice(decomposition)
    doc.recompute()
    count = layers.LayerCount
    for o in doc.Objects:
        o.ViewObject.Visibility = False
    preview = features.make_build_preview(layers, step=0)
    reference = doc.addObject("Part::Feature", "PartDrawn")
    view = FreeCADGui.getDocument(doc.Name).ActiveView
    view.viewIsometric()

    def ours(step, fresh=False, saved=False):
        reference.ViewObject.Visibility = False
        preview.ViewObject.Visibility = True
        if fresh:
            preview.ViewObject.Proxy.geometries = {}
        # As after a reopen: the layers drawn from the Shape's faces, not the engine's triangles.
        preview.Proxy.prism_triangles = (lambda prism: None) if saved else made
        preview.Step = step
        start = time.perf_counter()
        doc.recompute([preview])
        if fresh:
            preview.ViewObject.Proxy.update(preview.ViewObject)
        drawn(view)
        return time.perf_counter() - start

    def parts(step):
        preview.ViewObject.Visibility = False
        reference.ViewObject.Visibility = True
        preview.Step = step
        doc.recompute([preview])  # the same prisms (kept by the preview): only the drawing
        start = time.perf_counter()
        reference.Shape = preview.Shape
        drawn(view)
        return time.perf_counter() - start

    made = preview.Proxy.prism_triangles
    ours(1)  # the prisms made (common to both), then drawn from nothing
    view.fitAll()
    first = (ours(0, fresh=True), parts(0))
    saved = (ours(0, fresh=True, saved=True), parts(0))
    ours(0, fresh=True)
    singles = list(range(count // 2, count // 2 + 9))
    jumps = [100 * k for k in range(1, 10)]
    rows = [("first drawing, all %d layers" % count, [first[0]], [first[1]]),
            ("the same, of a saved Shape", [saved[0]], [saved[1]])]
    for name, steps in (("one step at a time", singles), ("jumps of 100 steps", jumps)):
        rows.append((name, [ours(s) for s in steps], [parts(s) for s in steps]))
    print("\nbench_build_preview: %d layers, %d faces at the last step; seconds (median)" % (
        count, len(preview.Shape.Faces)))
    print("%-30s %10s %10s %8s" % ("", "preview", "Part", "ratio"))
    for name, a, b in rows:
        a, b = statistics.median(a), statistics.median(b)
        print("%-30s %10.3f %10.3f %7.1fx" % (name, a, b, b / a))


try:
    main()
    code = 0
except Exception as e:
    traceback.print_exc()
    print("bench_build_preview: FAILED: %s" % e)
    code = 1
sys.stdout.flush()
os._exit(code)  # the GUI would wait for its window to be closed
