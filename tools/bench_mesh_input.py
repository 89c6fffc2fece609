# A FreeCAD mesh reaching the engine (MultiAxisSlicer.to_engine_mesh on a Mesh.Mesh): its points
# and facets read item by item in C++ (Mesh.from_topology, what the API does) against flattening
# them into lists in Python for Mesh.from_arrays (what it did before), in one run, on CGAL's test
# meshes; make_closed (the engine's check and canonical order) beside, and to_engine_mesh in all
# against it as it was (which also read the whole Topology once more to tell a mesh).
# Run by freecadcmd (tools/setup.sh bench does, figures in out/bench_mesh_input.txt):
#   MAS_APP=build/Mod/MultiAxisSlicer/App MAS_BENCH_DATA=build/bench-data \
#     freecadcmd tools/bench_mesh_input.py
# Medians of 7 runs, milliseconds.
import os
import statistics
import sys
import time
import traceback


def median_ms(work, runs=7):
    times = []
    for _ in range(runs):
        start = time.perf_counter()
        work()
        times.append((time.perf_counter() - start) * 1e3)
    return statistics.median(times)


def main():
    sys.path.insert(0, os.environ["MAS_APP"])
    import Mesh

    import MultiAxisSlicer as mas

    eng = mas._require_engine()
    data = os.environ["MAS_BENCH_DATA"]
    print("\nbench_mesh_input: a Mesh.Mesh to the engine, medians of 7 runs (ms)")
    print("%-18s %8s | %9s | %16s %13s %6s | %11s | %14s %7s %6s" % (
        "mesh", "facets", "Topology", "flat+from_arrays", "from_topology", "ratio",
        "make_closed", "to_engine_mesh", "before", "ratio"))
    for name in ("bunny00", "armadillo", "refined_elephant"):
        path = os.path.join(data, name + ".off")
        if not os.path.isfile(path):
            print("%-18s missing (tools/fetch_bench_data.sh)" % name)
            continue
        mesh = Mesh.Mesh(path)
        points, facets = mesh.Topology

        def flat():
            return eng.Mesh.from_arrays([c for p in points for c in (p.x, p.y, p.z)],
                                        [i for f in facets for i in f])

        def direct():
            return eng.Mesh.from_topology(points, facets)

        a, b = flat(), direct()
        if a.vertices() != b.vertices() or a.triangles() != b.triangles():
            raise RuntimeError("{}: from_topology and from_arrays differ".format(name))
        topology = median_ms(lambda: mesh.Topology)
        old = median_ms(flat)
        new = median_ms(direct)
        def before():
            # to_engine_mesh as it was: hasattr(mesh, "Topology") told a mesh, reading it all.
            if hasattr(mesh, "Topology"):
                points, facets = mesh.Topology
                eng.make_closed(eng.Mesh.from_arrays(
                    [c for p in points for c in (p.x, p.y, p.z)], [i for f in facets for i in f]))

        closed = median_ms(lambda: eng.make_closed(b, name))
        total = median_ms(lambda: mas.to_engine_mesh(mesh))
        was = median_ms(before)
        print("%-18s %8d | %9.1f | %16.1f %13.1f %5.1fx | %11.1f | %14.1f %7.1f %5.1fx" % (
            name, mesh.CountFacets, topology, old, new, old / new, closed, total, was,
            was / total))


try:
    main()
except Exception as e:  # freecadcmd exits 0 on an uncaught exception: say it and fail loudly
    traceback.print_exc()
    print("bench_mesh_input: FAILED: %s" % e)
    sys.exit(1)
