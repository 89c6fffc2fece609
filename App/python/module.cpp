// Boost.Python module `MultiAxisSlicer._engine`: the engine's stages as plain Python calls.
// Thin on purpose: Python values in, engine structs through, plain tuples/lists/dicts out. Errors
// leave as one exception class, EngineError(code, message); the GIL is released around engine work.
#include "mas/CentroidalAxis.hpp"
#include "mas/Decompose.hpp"
#include "mas/Error.hpp"
#include "mas/Gcode.hpp"
#include "mas/Mesh.hpp"
#include "mas/Polygon2.hpp"
#include "mas/Section.hpp"
#include "mas/Shape.hpp"
#include "mas/SlicePart.hpp"
#include "mas/Triangulate.hpp"

// Boost 1.74's Boost.Python still includes deprecated Boost headers; keep the build output quiet.
#define BOOST_BIND_GLOBAL_PLACEHOLDERS
#define BOOST_ALLOW_DEPRECATED_HEADERS
#include <boost/python.hpp>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <exception>
#include <iomanip>
#include <limits>
#include <optional>
#include <sstream>
#include <string>
#include <vector>

namespace bp = boost::python;

namespace {

// ---- errors
// ---------------------------------------------------------------------------------------

PyObject* engine_error_type = nullptr;  // MultiAxisSlicer._engine.EngineError, owned by the module

// Raises EngineError(message) with `code` and `message` attributes. Messages may carry file names
// in any encoding: undecodable bytes are replaced rather than turning into a UnicodeDecodeError.
void set_engine_error(const char* code, const std::string& message) {
    PyObject* text = PyUnicode_DecodeUTF8(message.data(), Py_ssize_t(message.size()), "replace");
    if (!text) return;  // MemoryError already set
    PyObject* exc = PyObject_CallOneArg(engine_error_type, text);
    if (exc) {
        PyObject* code_obj = PyUnicode_FromString(code);
        if (code_obj) {
            PyObject_SetAttrString(exc, "code", code_obj);
            Py_DECREF(code_obj);
        }
        PyObject_SetAttrString(exc, "message", text);
        PyErr_SetObject(engine_error_type, exc);
        Py_DECREF(exc);
    }
    Py_DECREF(text);
}

void translate_engine_error(const mas::Error& e) {
    set_engine_error(mas::to_string(e.code()), e.what());
}

// Anything else the engine lets through is a bug on our side, reported as such rather than
// crashing.
void translate_std_exception(const std::exception& e) {
    set_engine_error("internal", std::string("internal engine error: ") + e.what());
}

// Calls function(argument). When it *returns* an exception instance, raises that exception with no
// Python traceback. FreeCAD prints the traceback of any exception a document object's execute()
// raises; for bad input (an open mesh, a face instead of a solid) the message is all the user
// needs. Exceptions the function raises itself (bugs) propagate unchanged, traceback included.
bp::object call_quietly(const bp::object& function, const bp::object& argument) {
    bp::object result = function(argument);
    if (PyExceptionInstance_Check(result.ptr())) {
        PyException_SetTraceback(result.ptr(), Py_None);
        PyErr_SetObject(reinterpret_cast<PyObject*>(Py_TYPE(result.ptr())), result.ptr());
        bp::throw_error_already_set();
    }
    return result;
}

[[noreturn]] void invalid_argument(const std::string& message) {
    throw mas::Error(mas::ErrorCode::InvalidArgument, message);
}

// ---- the GIL
// ---------------------------------------------------------------------------------------

// Lets other Python threads (FreeCAD's GUI among them) run while the engine works. No Python object
// may be touched while an instance is alive: convert inputs before, outputs after.
class GilRelease {
public:
    GilRelease() : state_(PyEval_SaveThread()) {}
    ~GilRelease() { PyEval_RestoreThread(state_); }
    GilRelease(const GilRelease&) = delete;
    GilRelease& operator=(const GilRelease&) = delete;

    // Takes the GIL back for a while, on the thread that released it (a Python callback).
    class Hold {
    public:
        explicit Hold(GilRelease& released) : released_(released) {
            PyEval_RestoreThread(released_.state_);
        }
        ~Hold() { released_.state_ = PyEval_SaveThread(); }
        Hold(const Hold&) = delete;
        Hold& operator=(const Hold&) = delete;

    private:
        GilRelease& released_;
    };

private:
    PyThreadState* state_;
};

// Runs work(progress) with the GIL released, `progress` reporting to the Python callable
// `callback(fraction, stage)` (None: no reports). The engine reports from this thread only, so each
// report takes the GIL back for the call. The engine reports thousands of times a second on small
// layers; the callback hears from it at most every kReportInterval, and at every new stage and at
// the end. Python's signal handlers run there too, callback or not: Ctrl-C (KeyboardInterrupt)
// stops a script's long decomposition or slicing within kReportInterval of the engine's next
// report. An exception the callback or a handler raises (the user cancelled) stops the work and is
// raised again here, unchanged, once the GIL is back.
constexpr std::chrono::milliseconds kReportInterval{10};

template <class Work>
void run_reporting(const bp::object& callback, Work&& work) {
    PyObject* fn = callback.is_none() ? nullptr : callback.ptr();
    if (fn && !PyCallable_Check(fn))
        invalid_argument(std::string("progress must be callable as progress(fraction, stage) or "
                                     "None, not '") +
                         Py_TYPE(fn)->tp_name + "'");
    struct Raised {};
    PyObject *type = nullptr, *value = nullptr, *traceback = nullptr;
    std::exception_ptr failure;
    {
        GilRelease nogil;
        std::string last_stage;
        auto last_call = std::chrono::steady_clock::now();
        bool called = false;
        const mas::Progress progress([&](double fraction, const std::string& stage) {
            const auto now = std::chrono::steady_clock::now();
            const bool news = !called || fraction >= 1.0 || stage != last_stage;
            if (now - last_call < kReportInterval && !(fn && news)) return;
            called = true;
            last_call = now;
            last_stage = stage;
            GilRelease::Hold gil(nogil);
            PyObject* result = PyErr_CheckSignals() != 0 ? nullptr
                               : fn ? PyObject_CallFunction(fn, "ds", fraction, stage.c_str())
                                    : Py_NewRef(Py_None);
            if (!result) {
                PyErr_Fetch(&type, &value, &traceback);
                throw Raised{};
            }
            Py_DECREF(result);
        });
        try {
            work(progress);
        } catch (const Raised&) {
        } catch (...) {
            failure = std::current_exception();
        }
    }
    // The callback's exception wins over whatever the engine made of it.
    if (type || value) {
        PyErr_Restore(type, value, traceback);
        bp::throw_error_already_set();
    }
    if (failure) std::rethrow_exception(failure);
}

// ---- conversions
// ---------------------------------------------------------------------------------

// A new reference to a list/tuple view of any sequence or iterable; invalid_argument otherwise.
bp::handle<> fast_sequence(const bp::object& value, const std::string& what) {
    PyObject* seq = PySequence_Fast(value.ptr(), "");
    if (!seq) {
        PyErr_Clear();
        invalid_argument(what + " must be a sequence, not '" + Py_TYPE(value.ptr())->tp_name + "'");
    }
    return bp::handle<>(seq);
}

double number_at(PyObject* item, const std::string& what, Py_ssize_t index) {
    const double x = PyFloat_AsDouble(item);
    if (x == -1.0 && PyErr_Occurred()) {
        PyErr_Clear();
        invalid_argument(what + "[" + std::to_string(index) + "] is not a number but '" +
                         Py_TYPE(item)->tp_name + "'");
    }
    return x;
}

// Three numbers from a tuple, a list or anything iterable (a FreeCAD.Vector converts on the Python
// side).
Eigen::Vector3d vector3(const bp::object& value, const std::string& what) {
    bp::handle<> seq = fast_sequence(value, what);
    if (PySequence_Fast_GET_SIZE(seq.get()) != 3)
        invalid_argument(what + " must have 3 coordinates, got " +
                         std::to_string(PySequence_Fast_GET_SIZE(seq.get())));
    PyObject** items = PySequence_Fast_ITEMS(seq.get());
    return {number_at(items[0], what, 0), number_at(items[1], what, 1),
            number_at(items[2], what, 2)};
}

double finite_number(double x, const std::string& what) {
    if (!std::isfinite(x))
        invalid_argument(what + " must be a finite number, got " + mas::format_number(x));
    return x;
}

bp::tuple to_py(const Eigen::Vector3d& p) { return bp::make_tuple(p.x(), p.y(), p.z()); }

// ((xmin, ymin, zmin), (xmax, ymax, zmax)), or None for an empty box.
bp::object to_py(const Eigen::AlignedBox3d& box) {
    if (box.isEmpty()) return bp::object();
    return bp::make_tuple(to_py(box.min()), to_py(box.max()));
}

// [(origin, normal), ...] -> planes; each plane is checked by mas::make_plane (zero normal, NaN).
std::vector<mas::Plane> planes_from_py(const bp::object& value) {
    bp::handle<> seq = fast_sequence(value, "planes");
    const Py_ssize_t n = PySequence_Fast_GET_SIZE(seq.get());
    PyObject** items = PySequence_Fast_ITEMS(seq.get());
    std::vector<mas::Plane> planes;
    planes.reserve(std::size_t(n));
    for (Py_ssize_t i = 0; i < n; ++i) {
        const std::string what = "planes[" + std::to_string(i) + "]";
        bp::handle<> pair = fast_sequence(bp::object(bp::handle<>(bp::borrowed(items[i]))), what);
        if (PySequence_Fast_GET_SIZE(pair.get()) != 2)
            invalid_argument(what + " must be an (origin, normal) pair");
        PyObject** on = PySequence_Fast_ITEMS(pair.get());
        const Eigen::Vector3d origin =
            vector3(bp::object(bp::handle<>(bp::borrowed(on[0]))), what + " origin");
        const Eigen::Vector3d normal =
            vector3(bp::object(bp::handle<>(bp::borrowed(on[1]))), what + " normal");
        try {
            planes.push_back(mas::make_plane(origin, normal));
        } catch (const mas::Error& e) {
            throw mas::Error(e.code(), what + ": " + e.what());
        }
    }
    return planes;
}

bp::tuple plane_to_py(const mas::Plane& plane) {
    return bp::make_tuple(to_py(plane.origin), to_py(plane.normal));
}

// One section as plain data: the regions carry their loops in 3-D, outer loop first.
bp::dict section_to_py(const mas::Section& section) {
    bp::dict out;
    out["origin"] = to_py(section.plane.origin);
    out["normal"] = to_py(section.plane.normal);
    out["area"] = section.area;
    out["centroid"] = to_py(section.centroid);
    out["open_chains"] = section.open_chains;
    bp::list regions;
    for (std::size_t r = 0; r < section.regions.size(); ++r) {
        const mas::SectionRegion& region = section.regions[r];
        bp::dict d;
        d["area"] = region.area;
        d["centroid"] = to_py(region.centroid);
        d["bounds"] = to_py(region.bounds);
        bp::list loops;
        for (const auto& loop : section.loops_3d(r)) {
            bp::list points;
            for (const auto& p : loop) points.append(to_py(p));
            loops.append(points);
        }
        d["loops"] = loops;
        regions.append(d);
    }
    out["regions"] = regions;
    return out;
}

bp::list sections_to_py(const std::vector<mas::Section>& sections) {
    bp::list out;
    for (const auto& s : sections) out.append(section_to_py(s));
    return out;
}

mas::TessellationParams tessellation_params(double deflection, double angular_deflection) {
    mas::TessellationParams params;
    params.deflection_mm = finite_number(deflection, "deflection");  // <= 0: derived from the part
    params.angular_deflection_rad = finite_number(angular_deflection, "angular_deflection");
    if (!(params.angular_deflection_rad > 0.0))
        invalid_argument("angular_deflection must be positive");
    return params;
}

// ---- stage: shapes (OCCT behind a handle)
// ----------------------------------------------------------

mas::Shape shape_from_brep_string(const std::string& brep) {
    GilRelease nogil;
    return mas::Shape::from_brep_string(brep);
}

std::string shape_to_brep_string(const mas::Shape& shape) {
    GilRelease nogil;
    return shape.to_brep_string();
}

bp::dict shape_info(const mas::Shape& shape) {
    mas::ShapeInfo info;
    {
        GilRelease nogil;
        info = shape.info();
    }
    bp::dict d;
    d["solids"] = info.solids;
    d["shells"] = info.shells;
    d["faces"] = info.faces;
    d["edges"] = info.edges;
    d["free_faces"] = info.free_faces;
    d["free_edges"] = info.free_edges;
    d["volume_mm3"] = info.volume_mm3;
    d["bounds"] = to_py(info.bounds);
    return d;
}

mas::Shape shape_single_solid(const mas::Shape& shape, const std::string& what) {
    GilRelease nogil;
    return shape.single_solid(what);
}

std::string shape_repr(const mas::Shape& shape) {
    if (shape.is_null()) return "<MultiAxisSlicer._engine.Shape null>";
    const mas::ShapeInfo info = shape.info();
    return "<MultiAxisSlicer._engine.Shape solids=" + std::to_string(info.solids) +
           " faces=" + std::to_string(info.faces) + ">";
}

void bind_shape() {
    bp::class_<mas::Shape>("Shape",
                           "An immutable OCCT shape (copies share geometry). Create it with "
                           "Shape.from_brep_string(text) or read_model(path).",
                           bp::no_init)
        .def("from_brep_string", &shape_from_brep_string, bp::arg("brep"),
             "Shape from BREP text, as FreeCAD's Part.Shape.exportBrepToString() writes it.")
        .staticmethod("from_brep_string")
        .def("to_brep_string", &shape_to_brep_string,
             "BREP text; Part.Shape().importBrepFromString(text) reads it back.")
        .def("is_null", &mas::Shape::is_null)
        .def("info", &shape_info,
             "dict: solids, shells, faces, edges, free_faces, free_edges, volume_mm3, bounds "
             "((min), (max)) or None.")
        .def("single_solid", &shape_single_solid, bp::arg("what"),
             "The one closed solid in the shape; EngineError not_a_solid / multiple_solids / "
             "empty_input otherwise. `what` names the input in the message.")
        .def("__repr__", &shape_repr);
}

// ---- stage: triangle meshes
// ------------------------------------------------------------------------

// The next vertex of a mesh read from Python values, refused when not finite.
void push_vertex(mas::TriangleMesh& mesh, const Eigen::Vector3d& p) {
    if (!p.allFinite())
        throw mas::Error(
            mas::ErrorCode::NonFiniteCoordinate,
            "vertex " + std::to_string(mesh.vertices.size()) + " has a NaN or infinite coordinate");
    mesh.vertices.push_back(p);
}

// A vertex index read from a Python value, refused unless an integer in [0, vertex_count);
// name() says where it stands ("triangles[4]"), called only for the message.
template <class Name>
int vertex_index(PyObject* item, long long vertex_count, const Name& name) {
    const long long index = PyLong_AsLongLong(item);
    if (index == -1 && PyErr_Occurred()) {
        PyErr_Clear();
        invalid_argument(name() + " is not an integer but '" + Py_TYPE(item)->tp_name + "'");
    }
    if (index < 0 || index >= vertex_count)
        invalid_argument(name() + " = " + std::to_string(index) +
                         " is not a vertex index (there are " + std::to_string(vertex_count) +
                         " vertices)");
    return int(index);
}

// A mesh from flat arrays [x0, y0, z0, x1, ...] and [a0, b0, c0, a1, ...]: every value is checked
// here, so the engine never sees a NaN vertex or an index out of range.
mas::TriangleMesh mesh_from_arrays(const bp::object& vertices, const bp::object& triangles) {
    mas::TriangleMesh mesh;
    {
        bp::handle<> seq = fast_sequence(vertices, "vertices");
        const Py_ssize_t n = PySequence_Fast_GET_SIZE(seq.get());
        if (n % 3 != 0)
            invalid_argument("vertices must be a flat sequence of x, y, z values; its length " +
                             std::to_string(n) + " is not a multiple of 3");
        PyObject** items = PySequence_Fast_ITEMS(seq.get());
        mesh.vertices.reserve(std::size_t(n / 3));
        for (Py_ssize_t i = 0; i < n; i += 3) {
            push_vertex(mesh, Eigen::Vector3d(number_at(items[i], "vertices", i),
                                              number_at(items[i + 1], "vertices", i + 1),
                                              number_at(items[i + 2], "vertices", i + 2)));
        }
    }
    {
        bp::handle<> seq = fast_sequence(triangles, "triangles");
        const Py_ssize_t n = PySequence_Fast_GET_SIZE(seq.get());
        if (n % 3 != 0)
            invalid_argument(
                "triangles must be a flat sequence of vertex indices a, b, c; its "
                "length " +
                std::to_string(n) + " is not a multiple of 3");
        PyObject** items = PySequence_Fast_ITEMS(seq.get());
        const long long vertex_count = static_cast<long long>(mesh.vertices.size());
        mesh.triangles.reserve(std::size_t(n / 3));
        Eigen::Vector3i t;
        for (Py_ssize_t i = 0; i < n; ++i) {
            t[int(i % 3)] = vertex_index(items[i], vertex_count,
                                         [i] { return "triangles[" + std::to_string(i) + "]"; });
            if (i % 3 == 2) mesh.triangles.push_back(t);
        }
    }
    return mesh;
}

// A mesh from points and facets as FreeCAD's Mesh.Topology gives them: [(x, y, z) or an object
// with x, y and z (a FreeCAD.Vector), ...] and [(a, b, c), ...]. Read here, item by item, with the
// checks of mesh_from_arrays: flattening half a million facets into lists in Python first took
// five times as long as reading them so.
mas::TriangleMesh mesh_from_topology(const bp::object& points, const bp::object& facets) {
    mas::TriangleMesh mesh;
    {
        static PyObject* const names[3] = {PyUnicode_InternFromString("x"),
                                           PyUnicode_InternFromString("y"),
                                           PyUnicode_InternFromString("z")};
        bp::handle<> seq = fast_sequence(points, "points");
        const Py_ssize_t n = PySequence_Fast_GET_SIZE(seq.get());
        PyObject** items = PySequence_Fast_ITEMS(seq.get());
        mesh.vertices.reserve(std::size_t(n));
        const auto bad_point = [](Py_ssize_t i, PyObject* item) {
            PyErr_Clear();
            invalid_argument("points[" + std::to_string(i) +
                             "] is not 3 numbers (a tuple, a list or a vector with x, y, z) but '" +
                             Py_TYPE(item)->tp_name + "'");
        };
        for (Py_ssize_t i = 0; i < n; ++i) {
            PyObject* item = items[i];
            Eigen::Vector3d p;
            if (PyTuple_Check(item) || PyList_Check(item)) {
                if (PySequence_Fast_GET_SIZE(item) != 3) bad_point(i, item);
                PyObject** xyz = PySequence_Fast_ITEMS(item);
                for (int k = 0; k < 3; ++k) {
                    p[k] = PyFloat_AsDouble(xyz[k]);
                    if (p[k] == -1.0 && PyErr_Occurred()) bad_point(i, item);
                }
            } else {
                // A FreeCAD.Vector is a sequence of three: read so, it takes half the time its
                // x, y and z attributes do, or less. Other objects: their x, y, z.
                const bool sequence = PySequence_Check(item) && PySequence_Size(item) == 3;
                if (!sequence) PyErr_Clear();
                for (int k = 0; k < 3; ++k) {
                    PyObject* c =
                        sequence ? PySequence_GetItem(item, k) : PyObject_GetAttr(item, names[k]);
                    if (!c) bad_point(i, item);
                    p[k] = PyFloat_AsDouble(c);
                    Py_DECREF(c);
                    if (p[k] == -1.0 && PyErr_Occurred()) bad_point(i, item);
                }
            }
            push_vertex(mesh, p);
        }
    }
    {
        bp::handle<> seq = fast_sequence(facets, "facets");
        const Py_ssize_t n = PySequence_Fast_GET_SIZE(seq.get());
        PyObject** items = PySequence_Fast_ITEMS(seq.get());
        const long long vertex_count = static_cast<long long>(mesh.vertices.size());
        mesh.triangles.reserve(std::size_t(n));
        for (Py_ssize_t i = 0; i < n; ++i) {
            PyObject* item = items[i];
            if (!(PyTuple_Check(item) || PyList_Check(item)) || PySequence_Fast_GET_SIZE(item) != 3)
                invalid_argument("facets[" + std::to_string(i) +
                                 "] is not 3 vertex indices (a tuple or a list) but '" +
                                 Py_TYPE(item)->tp_name + "'");
            PyObject** abc = PySequence_Fast_ITEMS(item);
            Eigen::Vector3i t;
            for (int k = 0; k < 3; ++k)
                t[k] = vertex_index(abc[k], vertex_count, [i, k] {
                    return "facets[" + std::to_string(i) + "][" + std::to_string(k) + "]";
                });
            mesh.triangles.push_back(t);
        }
    }
    return mesh;
}

std::size_t mesh_vertex_count(const mas::TriangleMesh& mesh) { return mesh.vertices.size(); }
std::size_t mesh_triangle_count(const mas::TriangleMesh& mesh) { return mesh.triangles.size(); }

bp::list mesh_vertices(const mas::TriangleMesh& mesh) {
    bp::list out;
    for (const auto& p : mesh.vertices) out.append(to_py(p));
    return out;
}

bp::list mesh_triangles(const mas::TriangleMesh& mesh) {
    bp::list out;
    for (const auto& t : mesh.triangles) out.append(bp::make_tuple(t[0], t[1], t[2]));
    return out;
}

bp::dict mesh_check(const mas::TriangleMesh& mesh) {
    mas::MeshReport r;
    {
        GilRelease nogil;
        r = mas::check_mesh(mesh);
    }
    bp::dict d;
    d["vertices"] = r.vertices;
    d["triangles"] = r.triangles;
    d["non_finite_vertices"] = r.non_finite_vertices;
    d["degenerate_triangles"] = r.degenerate_triangles;
    d["boundary_edges"] = r.boundary_edges;
    d["non_manifold_edges"] = r.non_manifold_edges;
    d["inconsistent_edges"] = r.inconsistent_edges;
    d["volume_mm3"] = r.volume_mm3;
    d["closed"] = r.closed();
    return d;
}

bp::object mesh_bounds(const mas::TriangleMesh& mesh) { return to_py(mas::bounding_box(mesh)); }

// FNV-1a over the bytes of every vertex coordinate and triangle index, in order: equal for equal
// meshes, and unequal, but for a 2^-64 chance, for any change of a coordinate or a facet.
unsigned long long mesh_digest(const mas::TriangleMesh& mesh) {
    std::uint64_t h = 14695981039346656037ull;
    const auto add = [&h](const void* data, std::size_t size) {
        const auto* bytes = static_cast<const unsigned char*>(data);
        for (std::size_t i = 0; i < size; ++i) h = (h ^ bytes[i]) * 1099511628211ull;
    };
    const std::uint64_t counts[2] = {mesh.vertices.size(), mesh.triangles.size()};
    add(counts, sizeof counts);
    for (const Eigen::Vector3d& v : mesh.vertices) add(v.data(), 3 * sizeof(double));
    for (const Eigen::Vector3i& t : mesh.triangles) add(t.data(), 3 * sizeof(int));
    return h;
}

std::string mesh_repr(const mas::TriangleMesh& mesh) {
    return "<MultiAxisSlicer._engine.Mesh vertices=" + std::to_string(mesh.vertices.size()) +
           " triangles=" + std::to_string(mesh.triangles.size()) + ">";
}

// A checked copy: closed, finite, outward-oriented (an inside-out copy is flipped), in the
// canonical order (mas::canonical_order); the argument itself is never changed.
mas::TriangleMesh make_closed(const mas::TriangleMesh& mesh, const std::string& what) {
    mas::TriangleMesh copy = mesh;
    GilRelease nogil;
    mas::require_closed_mesh(copy, what);
    mas::require_one_solid(copy, what);
    mas::canonical_order(copy);
    return copy;
}

void bind_mesh() {
    bp::class_<mas::TriangleMesh>(
        "Mesh",
        "An indexed triangle mesh (mm), triangles counter-clockwise seen "
        "from outside. Create it with Mesh.from_arrays(), tessellate() or "
        "read_model().",
        bp::no_init)
        .def("from_arrays", &mesh_from_arrays, (bp::arg("vertices"), bp::arg("triangles")),
             "Mesh from a flat sequence of vertex coordinates [x0, y0, z0, x1, ...] and a flat "
             "sequence of vertex indices [a0, b0, c0, ...]. EngineError invalid_argument on wrong "
             "lengths, non-numbers or indices out of range, non_finite_coordinate on NaN/inf.")
        .staticmethod("from_arrays")
        .def("from_topology", &mesh_from_topology, (bp::arg("points"), bp::arg("facets")),
             "Mesh from points [(x, y, z) or a vector with x, y, z, ...] and facets [(a, b, c), "
             "...], as FreeCAD's Mesh.Topology gives them. Errors as from_arrays.")
        .staticmethod("from_topology")
        .def("vertex_count", &mesh_vertex_count)
        .def("triangle_count", &mesh_triangle_count)
        .def("vertices", &mesh_vertices, "[(x, y, z), ...]")
        .def("triangles", &mesh_triangles, "[(a, b, c), ...]")
        .def("check", &mesh_check,
             "dict: vertices, triangles, non_finite_vertices, degenerate_triangles, "
             "boundary_edges, non_manifold_edges, inconsistent_edges, volume_mm3, closed.")
        .def("bounds", &mesh_bounds, "((xmin, ymin, zmin), (xmax, ymax, zmax)), None if empty.")
        .def("digest", &mesh_digest,
             "A 64-bit hash of every vertex coordinate and triangle index, in order: what tells "
             "one mesh from another (equal meshes, equal digests).")
        .def("__repr__", &mesh_repr);

    bp::def("make_closed", &make_closed, (bp::arg("mesh"), bp::arg("what") = "mesh"),
            "A checked copy of `mesh`: EngineError empty_input / open_mesh / non_finite_coordinate "
            "unless it is a closed, consistently oriented surface, not_a_solid unless its shells "
            "bound one solid (none overlapping, a cavity's facing in); an inside-out mesh is "
            "flipped.");
}

// ---- stage: reading parts
// ------------------------------------------------------------------------

bp::tuple read_model(const std::string& path) {
    mas::Model model;
    {
        GilRelease nogil;
        model = mas::read_model(path);
    }
    if (model.kind == mas::Model::Kind::Solid)
        return bp::make_tuple("solid", bp::object(model.shape));
    return bp::make_tuple("mesh", bp::object(model.mesh));
}

mas::TriangleMesh model_mesh(const std::string& path, double deflection,
                             double angular_deflection) {
    const mas::TessellationParams params = tessellation_params(deflection, angular_deflection);
    GilRelease nogil;
    return mas::model_mesh(mas::read_model(path), params);
}

void bind_read() {
    bp::def("read_model", &read_model, bp::arg("path"),
            "(kind, part) from a .step/.stp, .iges/.igs, .brep/.brp, .stl or .off file: "
            "('solid', Shape) or ('mesh', Mesh). EngineError read_failed / empty_input / "
            "unsupported_format / non_finite_coordinate.");
    bp::def("model_mesh", &model_mesh,
            (bp::arg("path"), bp::arg("deflection") = 0.0, bp::arg("angular_deflection") = 0.35),
            "The closed mesh the section kernel cuts for the part in a file: a solid is "
            "tessellated, a mesh is checked.");
}

// ---- stage: tessellation
// -------------------------------------------------------------------------

double effective_deflection(const mas::Shape& shape, double deflection, double angular_deflection) {
    const mas::TessellationParams params = tessellation_params(deflection, angular_deflection);
    GilRelease nogil;
    return mas::effective_deflection(shape, params);
}

mas::TriangleMesh tessellate(const mas::Shape& shape, double deflection,
                             double angular_deflection) {
    const mas::TessellationParams params = tessellation_params(deflection, angular_deflection);
    GilRelease nogil;
    return mas::tessellate(shape, params);
}

void bind_tessellate() {
    bp::def("effective_deflection", &effective_deflection,
            (bp::arg("shape"), bp::arg("deflection") = 0.0, bp::arg("angular_deflection") = 0.35),
            "Chordal deflection (mm) tessellate() uses: `deflection` if > 0, else derived from "
            "the part's size.");
    bp::def(
        "tessellate", &tessellate,
        (bp::arg("shape"), bp::arg("deflection") = 0.0, bp::arg("angular_deflection") = 0.35),
        "Closed, outward-oriented triangle mesh of the shape's one solid; deflection <= 0 means "
        "automatic. EngineError not_a_solid / multiple_solids / geometry_failure.");
}

// ---- stage: cross-sections of a mesh
// ---------------------------------------------------------------

bp::list parallel_planes(const mas::TriangleMesh& mesh, const bp::object& normal, double step) {
    const Eigen::Vector3d n = vector3(normal, "normal");
    std::vector<mas::Plane> planes;
    {
        GilRelease nogil;
        planes = mas::parallel_planes(mesh, n, step);
    }
    bp::list out;
    for (const auto& p : planes) out.append(plane_to_py(p));
    return out;
}

bp::list slice(const mas::TriangleMesh& mesh, const bp::object& planes_py, bool build_regions) {
    const std::vector<mas::Plane> planes = planes_from_py(planes_py);
    mas::SliceParams params;
    params.build_regions = build_regions;
    std::vector<mas::Section> sections;
    {
        GilRelease nogil;
        sections = mas::slice_mesh(mesh, planes, params);
    }
    return sections_to_py(sections);
}

bp::list section_point_counts(const mas::TriangleMesh& mesh, const bp::object& planes_py) {
    const std::vector<mas::Plane> planes = planes_from_py(planes_py);
    std::vector<std::size_t> counts;
    {
        GilRelease nogil;
        counts = mas::section_point_counts(mesh, planes);
    }
    bp::list out;
    for (std::size_t c : counts) out.append(c);
    return out;
}

void bind_section() {
    bp::def(
        "parallel_planes", &parallel_planes, (bp::arg("mesh"), bp::arg("normal"), bp::arg("step")),
        "[(origin, normal), ...]: planes `step` mm apart across the mesh along `normal`, each in "
        "the middle of its slab. EngineError invalid_argument on a bad step or normal.");
    bp::def("section_point_counts", &section_point_counts, (bp::arg("mesh"), bp::arg("planes")),
            "[count, ...]: how many loop points the section by each plane holds (the plane's "
            "crossings with the mesh's facets), counted without cutting.");
    bp::def(
        "slice", &slice, (bp::arg("mesh"), bp::arg("planes"), bp::arg("build_regions") = true),
        "Cuts a closed mesh by planes [(origin, normal), ...]; one dict per plane: origin, normal, "
        "area (mm^2), centroid, open_chains, regions [{area, centroid, bounds, loops}] where "
        "loops[0] is the outer loop and the rest are holes, each [(x, y, z), ...].");
}

// ---- stage: OCCT's exact sections (the reference)
// ------------------------------------------------

bp::list exact_sections(const mas::Shape& shape, const bp::object& planes_py,
                        double loop_deflection) {
    const std::vector<mas::Plane> planes = planes_from_py(planes_py);
    finite_number(loop_deflection, "loop_deflection");
    if (!(loop_deflection > 0.0)) invalid_argument("loop_deflection must be positive");
    std::vector<mas::Section> sections;
    {
        GilRelease nogil;
        sections = mas::exact_sections(shape, planes, loop_deflection);
    }
    return sections_to_py(sections);
}

void bind_exact_section() {
    bp::def(
        "exact_sections", &exact_sections,
        (bp::arg("shape"), bp::arg("planes"), bp::arg("loop_deflection") = 0.01),
        "OCCT's exact sections of a solid, as dicts like slice() returns; loops are discretised "
        "within `loop_deflection` mm. About 100x slower than slice().");
}

// ---- stage: centroidal axis
// ----------------------------------------------------------------------

const char* link_kind(mas::AxisLink::Kind kind) {
    return kind == mas::AxisLink::Kind::Connecting ? "connecting" : "step";
}

// A node's region as bytes for the Python side to hand back unread (it has no use for it; the
// decomposition and the slicer do): native doubles, the loop count, then per loop (outer first,
// then its holes) its point count and its points' u, v.
bp::object region_to_py(const mas::Region2& region) {
    std::vector<double> data;
    if (!region.outer.points.empty()) {
        data.push_back(double(1 + region.holes.size()));
        auto loop = [&](const mas::Polygon2& p) {
            data.push_back(double(p.points.size()));
            for (const auto& q : p.points) data.insert(data.end(), {q.x(), q.y()});
        };
        loop(region.outer);
        for (const auto& h : region.holes) loop(h);
    }
    return bp::object(bp::handle<>(PyBytes_FromStringAndSize(
        reinterpret_cast<const char*>(data.data()), Py_ssize_t(data.size() * sizeof(double)))));
}

// The region region_to_py wrote; InvalidArgument naming `what` for bytes it cannot have written.
mas::Region2 region_from_py(const bp::object& value, const std::string& what) {
    char* bytes = nullptr;
    Py_ssize_t size = 0;
    if (!PyBytes_Check(value.ptr()) || PyBytes_AsStringAndSize(value.ptr(), &bytes, &size) != 0) {
        PyErr_Clear();
        invalid_argument(what + " must be the bytes the engine gave");
    }
    if (size % Py_ssize_t(sizeof(double)) != 0) invalid_argument(what + " is cut short");
    std::vector<double> data(std::size_t(size) / sizeof(double));
    if (size > 0) std::memcpy(data.data(), bytes, std::size_t(size));
    mas::Region2 region;
    std::size_t at = 0;
    auto count = [&]() {
        if (at >= data.size() || !(data[at] >= 0.0) || data[at] > double(data.size()) ||
            data[at] != std::floor(data[at]))
            invalid_argument(what + " is not a region the engine wrote");
        return std::size_t(data[at++]);
    };
    const std::size_t loops = data.empty() ? 0 : count();
    for (std::size_t k = 0; k < loops; ++k) {
        mas::Polygon2 loop;
        const std::size_t n = count();
        if (n < 3 || data.size() - at < 2 * n)
            invalid_argument(what + " is not a region the engine wrote");
        for (std::size_t i = 0; i < n; ++i, at += 2) {
            if (!std::isfinite(data[at]) || !std::isfinite(data[at + 1]))
                invalid_argument(what + " has a NaN or infinite point");
            loop.points.emplace_back(data[at], data[at + 1]);
        }
        (k == 0 ? region.outer : region.holes.emplace_back()) = std::move(loop);
    }
    if (at != data.size()) invalid_argument(what + " is not a region the engine wrote");
    return region;
}

// The axis as plain data. Each node's region goes as opaque bytes (region_to_py): the Python side
// hands it back for the decomposition (the branch's first section) and the slicer (what a split
// took from a node), and leaves it out of to_dict().
bp::dict axis_to_py(const mas::CentroidalAxis& axis) {
    bp::list nodes;
    for (const auto& n : axis.nodes) {
        bp::dict d;
        d["position"] = to_py(n.position);
        d["normal"] = to_py(n.normal);
        d["area"] = n.area;
        d["offset"] = n.offset;
        d["thickness"] = n.thickness;
        d["slab_start"] = n.slab_start;
        d["branch"] = n.branch;
        d["incoming_link"] = n.incoming_link;
        d["interior"] = to_py(n.interior);
        d["region"] = region_to_py(n.region);
        nodes.append(d);
    }
    bp::list links;
    for (const auto& l : axis.links) {
        bp::dict d;
        d["start"] = l.start;
        d["end"] = l.end;
        d["kind"] = link_kind(l.kind);
        d["is_break"] = l.is_break;
        d["turn_deg"] = l.turn_deg;
        links.append(d);
    }
    bp::list branches;
    for (const auto& b : axis.branches) {
        bp::dict d;
        d["parent"] = b.parent;
        d["direction"] = to_py(b.direction);
        bp::list members;
        for (int n : b.nodes) members.append(n);
        d["nodes"] = members;
        d["parent_node"] = b.parent_node;
        d["first_link"] = b.first_link;
        d["depth"] = b.depth;
        d["merged_into"] = b.merged_into;
        branches.append(d);
    }
    bp::dict params;
    params["step_mm"] = axis.params.step_mm;
    params["distance_threshold_mm"] = axis.params.distance_threshold_mm;
    params["eps_mm"] = axis.params.eps_mm;
    params["break_angle_deg"] = axis.params.break_angle_deg;
    params["base_z_mm"] = axis.params.base_z_mm;
    params["min_region_area_mm2"] = axis.params.min_region_area_mm2;
    params["frame_deg"] = axis.params.frame_deg;
    bp::dict out;
    out["nodes"] = nodes;
    out["links"] = links;
    out["branches"] = branches;
    out["params"] = params;
    out["searched_volume_mm3"] = axis.searched_volume_mm3;
    out["sections_cut"] = axis.sections_cut;
    return out;
}

bp::dict centroidal_axis(const mas::TriangleMesh& mesh, double step, double distance_threshold,
                         double eps, double break_angle, double base_z, double min_region_area,
                         double frame, const bp::object& progress) {
    mas::AxisParams params;
    params.step_mm = finite_number(step, "step");  // <= 0: derived from the part
    params.distance_threshold_mm = finite_number(distance_threshold, "distance_threshold");
    params.eps_mm = finite_number(eps, "eps");
    params.break_angle_deg = finite_number(break_angle, "break_angle");
    if (std::isinf(base_z))
        invalid_argument("base_z must be a finite number (or NaN: the part's lowest point)");
    params.base_z_mm = base_z;
    params.min_region_area_mm2 = finite_number(min_region_area, "min_region_area");
    params.frame_deg = frame;  // NaN: derived from the part; infinite: the engine refuses it
    mas::CentroidalAxis axis;
    run_reporting(progress,
                  [&](const mas::Progress& p) { axis = mas::centroidal_axis(mesh, params, p); });
    return axis_to_py(axis);
}

double derive_axis_step(const mas::TriangleMesh& mesh) {
    GilRelease nogil;
    return mas::derive_axis_step(mesh);
}

double derive_axis_frame(const mas::TriangleMesh& mesh) {
    GilRelease nogil;
    return mas::derive_axis_frame(mesh);
}

void bind_axis() {
    bp::def(
        "centroidal_axis", &centroidal_axis,
        (bp::arg("mesh"), bp::arg("step") = 0.0, bp::arg("distance_threshold") = 0.0,
         bp::arg("eps") = 0.001, bp::arg("break_angle") = 30.0,
         bp::arg("base_z") = std::numeric_limits<double>::quiet_NaN(),
         bp::arg("min_region_area") = 1e-6,
         bp::arg("frame") = std::numeric_limits<double>::quiet_NaN(),
         bp::arg("progress") = bp::object()),
        "The centroidal axis of a closed mesh (make_closed() or tessellate() give one), lengths "
        "in mm, angles in degrees: step <= 0 is derived from the part, distance_threshold <= 0 "
        "is twice the step (at most a sixth of a section's size), base_z NaN is the part's lowest "
        "point, frame (the turn about Z of the +-X and +-Y it marches along) NaN is derived from "
        "the part (derive_axis_frame()). Returns a dict: nodes "
        "[{position, normal, area, offset, thickness, slab_start, branch, incoming_link, "
        "interior}], links [{start, end, kind ('step' | 'connecting'), is_break, turn_deg}], "
        "branches [{parent, direction, nodes, parent_node, first_link, depth, merged_into}], "
        "params (the values used: step_mm, distance_threshold_mm, eps_mm, break_angle_deg, "
        "base_z_mm, min_region_area_mm2, frame_deg), "
        "searched_volume_mm3, sections_cut. EngineError invalid_argument on NaN or out-of-range "
        "parameters, a step not smaller than the part's height, or a part that does not stand "
        "on base_z; empty_input for an empty mesh. `progress`: None or progress(fraction, stage), "
        "called now and then from this thread with the volume swept so far over the part's; an "
        "exception it raises stops the search and is raised again here.");
    bp::def("derive_axis_step", &derive_axis_step, bp::arg("mesh"),
            "The step (mm) centroidal_axis() derives when none is given: half the part's thinnest "
            "wall, within [diagonal / 2000, diagonal / 20], at most half the part's height. "
            "(centroidal_axis() derives it on the part turned into its frame.)");
    bp::def("derive_axis_frame", &derive_axis_frame, bp::arg("mesh"),
            "The frame (degrees about Z, in (-45, 45]) centroidal_axis() derives when none is "
            "given: the turn lining +-X and +-Y up with the part's sides, 0 when they do not "
            "agree on one.");
}

// ---- stage: decomposition into sub-components
// ------------------------------------------------------

// The value of `key` in a dict; invalid_argument naming `what` when it is missing or `value` is
// not a dict.
bp::object required(const bp::object& value, const char* key, const std::string& what) {
    if (!PyDict_Check(value.ptr()))
        invalid_argument(what + " must be a dict, not '" + Py_TYPE(value.ptr())->tp_name + "'");
    PyObject* item = PyDict_GetItemString(value.ptr(), key);  // borrowed
    if (!item) invalid_argument(what + " has no '" + key + "'");
    return bp::object(bp::handle<>(bp::borrowed(item)));
}

double number_of(const bp::object& value, const char* key, const std::string& what) {
    const bp::object item = required(value, key, what);
    const double x = PyFloat_AsDouble(item.ptr());
    if (x == -1.0 && PyErr_Occurred()) {
        PyErr_Clear();
        invalid_argument(what + "['" + key + "'] is not a number");
    }
    return x;
}

int index_of(const bp::object& value, const char* key, const std::string& what) {
    const bp::object item = required(value, key, what);
    const long i = PyLong_AsLong(item.ptr());
    if (i == -1 && PyErr_Occurred()) {
        PyErr_Clear();
        invalid_argument(what + "['" + key + "'] is not an integer");
    }
    if (i < -1 || i > std::numeric_limits<int>::max())
        invalid_argument(what + "['" + key + "'] is out of range");
    return int(i);
}

// A list of the items of value[key], a sequence.
// The items of the sequence `value` (`what` in errors).
std::vector<bp::object> items_from(const bp::object& value, const std::string& what) {
    bp::handle<> seq = fast_sequence(value, what);
    const Py_ssize_t n = PySequence_Fast_GET_SIZE(seq.get());
    PyObject** items = PySequence_Fast_ITEMS(seq.get());
    std::vector<bp::object> out;
    out.reserve(std::size_t(n));
    for (Py_ssize_t i = 0; i < n; ++i) out.emplace_back(bp::handle<>(bp::borrowed(items[i])));
    return out;
}

std::vector<bp::object> items_of(const bp::object& value, const char* key,
                                 const std::string& what) {
    return items_from(required(value, key, what), what + "['" + key + "']");
}

// The engine's axis from the dict centroidal_axis() returns (node regions are optional: without
// them the decomposition takes a square of the node's area for a branch's first section, and the
// slicer leaves guide nodes where they are). Indices are checked by mas::decompose itself.
mas::CentroidalAxis axis_from_py(const bp::object& value) {
    mas::CentroidalAxis axis;
    const std::vector<bp::object> nodes = items_of(value, "nodes", "axis");
    axis.nodes.reserve(nodes.size());
    for (std::size_t i = 0; i < nodes.size(); ++i) {
        const std::string what = "axis['nodes'][" + std::to_string(i) + "]";
        mas::AxisNode n;
        n.position = vector3(required(nodes[i], "position", what), what + "['position']");
        n.normal = vector3(required(nodes[i], "normal", what), what + "['normal']");
        n.area = number_of(nodes[i], "area", what);
        n.offset = number_of(nodes[i], "offset", what);
        n.thickness = number_of(nodes[i], "thickness", what);
        // Optional: where the node's slab starts (a turned branch's first node: Eq. 4's T).
        n.slab_start = PyDict_GetItemString(nodes[i].ptr(), "slab_start")
                           ? number_of(nodes[i], "slab_start", what)
                           : n.offset;
        n.branch = index_of(nodes[i], "branch", what);
        n.incoming_link = index_of(nodes[i], "incoming_link", what);
        if (!n.position.allFinite() || !n.normal.allFinite() || !std::isfinite(n.area) ||
            !std::isfinite(n.offset) || !std::isfinite(n.thickness) || !std::isfinite(n.slab_start))
            invalid_argument(what + " has a NaN or infinite value");
        // Optional: a point in the node's material (the decomposition finds pipes by it).
        if (PyDict_GetItemString(nodes[i].ptr(), "interior")) {
            n.interior = vector3(required(nodes[i], "interior", what), what + "['interior']");
            if (!n.interior.allFinite()) invalid_argument(what + "['interior'] is not finite");
        }
        // Optional: the region, as the engine gave it (region_to_py).
        if (PyObject* region = PyDict_GetItemString(nodes[i].ptr(), "region"))
            n.region =
                region_from_py(bp::object(bp::handle<>(bp::borrowed(region))), what + "['region']");
        axis.nodes.push_back(n);
    }
    const std::vector<bp::object> links = items_of(value, "links", "axis");
    axis.links.reserve(links.size());
    for (std::size_t i = 0; i < links.size(); ++i) {
        const std::string what = "axis['links'][" + std::to_string(i) + "]";
        mas::AxisLink l;
        l.start = index_of(links[i], "start", what);
        l.end = index_of(links[i], "end", what);
        const bp::extract<std::string> kind_text(required(links[i], "kind", what));
        if (!kind_text.check()) invalid_argument(what + "['kind'] must be a string");
        const std::string kind = kind_text();
        if (kind == "step")
            l.kind = mas::AxisLink::Kind::Step;
        else if (kind == "connecting")
            l.kind = mas::AxisLink::Kind::Connecting;
        else
            invalid_argument(what + "['kind'] must be 'step' or 'connecting', not '" + kind + "'");
        l.is_break = PyObject_IsTrue(required(links[i], "is_break", what).ptr()) == 1;
        l.turn_deg = number_of(links[i], "turn_deg", what);
        axis.links.push_back(l);
    }
    const std::vector<bp::object> branches = items_of(value, "branches", "axis");
    axis.branches.reserve(branches.size());
    for (std::size_t i = 0; i < branches.size(); ++i) {
        const std::string what = "axis['branches'][" + std::to_string(i) + "]";
        mas::AxisBranch b;
        b.parent = index_of(branches[i], "parent", what);
        b.direction = vector3(required(branches[i], "direction", what), what + "['direction']");
        if (!b.direction.allFinite() || b.direction.norm() < 1e-12)
            invalid_argument(what + "['direction'] must be a finite, non-zero vector");
        for (const bp::object& n : items_of(branches[i], "nodes", what)) {
            const long k = PyLong_AsLong(n.ptr());
            if (k == -1 && PyErr_Occurred()) {
                PyErr_Clear();
                invalid_argument(what + "['nodes'] holds a non-integer");
            }
            if (k < 0 || k > std::numeric_limits<int>::max())
                invalid_argument(what + "['nodes'] holds an index out of range");
            b.nodes.push_back(int(k));
        }
        b.parent_node = index_of(branches[i], "parent_node", what);
        b.first_link = index_of(branches[i], "first_link", what);
        b.depth = index_of(branches[i], "depth", what);
        b.merged_into = index_of(branches[i], "merged_into", what);
        axis.branches.push_back(b);
    }
    const bp::object params = required(value, "params", "axis");
    axis.params.step_mm = number_of(params, "step_mm", "axis['params']");
    axis.params.eps_mm = number_of(params, "eps_mm", "axis['params']");
    axis.params.distance_threshold_mm =
        number_of(params, "distance_threshold_mm", "axis['params']");
    axis.params.break_angle_deg = number_of(params, "break_angle_deg", "axis['params']");
    axis.params.base_z_mm = number_of(params, "base_z_mm", "axis['params']");
    // Optional: the frame it was marched in (decompose() reads it off the branches' directions).
    if (PyDict_GetItemString(params.ptr(), "frame_deg"))
        axis.params.frame_deg = number_of(params, "frame_deg", "axis['params']");
    // Optional: the deflection of the tessellation the axis was cut from (0: not known).
    if (PyDict_GetItemString(params.ptr(), "deflection_mm")) {
        axis.deflection_mm = number_of(params, "deflection_mm", "axis['params']");
        if (!(std::isfinite(axis.deflection_mm) && axis.deflection_mm >= 0.0))
            invalid_argument("axis['params']['deflection_mm'] must be a non-negative number");
    }
    if (!(std::isfinite(axis.params.step_mm) && axis.params.step_mm > 0.0) ||
        !(std::isfinite(axis.params.eps_mm) && axis.params.eps_mm >= 0.0))
        invalid_argument("axis['params'] needs a positive step_mm and a non-negative eps_mm");
    axis.searched_volume_mm3 = number_of(value, "searched_volume_mm3", "axis");
    return axis;
}

bp::dict decomposition_to_py(const mas::Decomposition& d, double part_volume) {
    bp::list components;
    for (const auto& c : d.components) {
        bp::dict out;
        out["solid"] = bp::object(c.solid);
        out["parent"] = c.parent;
        out["build_direction"] = to_py(c.build_direction);
        out["has_base_face"] = c.has_base_face;
        out["base_face"] = c.has_base_face ? bp::object(c.base_face) : bp::object();
        out["base_origin"] = to_py(c.base_origin);
        out["base_normal"] = to_py(c.base_normal);
        out["branch"] = c.branch;
        out["break_link"] = c.break_link;
        out["rule"] = mas::to_string(c.rule);
        out["turned"] = c.turned;
        out["volume_mm3"] = c.volume_mm3;
        components.append(out);
    }
    bp::list notes, kept, square;
    for (const auto& n : d.notes) notes.append(n);
    for (int b : d.kept_branches) kept.append(b);
    for (int b : d.square_branches) square.append(b);
    bp::dict result;
    result["components"] = components;
    result["part_volume_mm3"] = part_volume;
    result["notes"] = notes;
    result["kept_branches"] = kept;
    result["square_branches"] = square;
    return result;
}

// Calls take(name, value) for every item of a dict of `what` parameters, whose names must be
// strings.
void for_each_param(const bp::dict& d, const std::string& what,
                    const std::function<void(const std::string&, const bp::object&)>& take) {
    const bp::list keys = d.keys();
    for (bp::ssize_t i = 0; i < bp::len(keys); ++i) {
        const bp::extract<std::string> name(keys[i]);
        if (!name.check()) invalid_argument(what + " parameter names must be strings");
        take(name(), d[keys[i]]);
    }
}

// Branch indices: a sequence of ints, the parameter `name`'s.
std::vector<int> branches_from_py(const bp::object& value, const std::string& name) {
    std::vector<int> out;
    bp::handle<> seq = fast_sequence(value, name);
    const Py_ssize_t n = PySequence_Fast_GET_SIZE(seq.get());
    PyObject** items = PySequence_Fast_ITEMS(seq.get());
    for (Py_ssize_t i = 0; i < n; ++i) {
        const bp::extract<int> b(items[i]);
        if (!PyLong_Check(items[i]) || !b.check())
            invalid_argument(name + "[" + std::to_string(i) + "] must be a branch index");
        out.push_back(b());
    }
    return out;
}

// Branches to keep in their fathers (a sequence of ints), each "kept in its father, as asked".
std::vector<mas::KeptBranch> kept_branches_from_py(const bp::object& value) {
    std::vector<mas::KeptBranch> kept;
    for (const int b : branches_from_py(value, "keep_branches"))
        kept.push_back({b, "kept in its father, as asked (keep_branches)"});
    return kept;
}

// decompose()'s parameters from a dict of its argument names (face_angle, concave_angle,
// projection_tolerance, section_plane_fallback, min_component_height, max_tilt, keep_branches,
// square_branches, turn_cuts);
// missing ones take the engine's defaults, unknown names are errors.
mas::DecomposeParams decompose_params_from_py(const bp::dict& d) {
    mas::DecomposeParams p;
    for_each_param(d, "decomposition", [&](const std::string& key, const bp::object& value) {
        const auto number = [&] { return finite_number(bp::extract<double>(value)(), key); };
        if (key == "face_angle")
            p.face_angle_deg = number();
        else if (key == "concave_angle")
            p.concave_angle_deg = number();
        else if (key == "projection_tolerance")
            p.projection_tolerance_mm = number();
        else if (key == "section_plane_fallback")
            p.section_plane_fallback = bp::extract<bool>(value)();
        else if (key == "min_component_height")
            p.min_component_height_mm = number();
        else if (key == "max_tilt")
            p.max_tilt_deg = number();
        else if (key == "keep_branches")
            p.keep_branches = kept_branches_from_py(value);
        else if (key == "square_branches")
            p.square_branches = branches_from_py(value, "square_branches");
        else if (key == "turn_cuts")
            p.turn_cuts = bp::extract<bool>(value)();
        else
            invalid_argument("unknown decomposition parameter '" + key + "'");
    });
    return p;
}

bp::dict decompose(const mas::Shape& shape, const bp::object& axis_py, double face_angle,
                   double concave_angle, double projection_tolerance, bool section_plane_fallback,
                   double min_component_height, double max_tilt, const bp::object& keep_branches,
                   const bp::object& square_branches, bool turn_cuts, const bp::object& progress) {
    bp::dict given;
    given["face_angle"] = face_angle;
    given["concave_angle"] = concave_angle;
    given["projection_tolerance"] = projection_tolerance;
    given["section_plane_fallback"] = section_plane_fallback;
    given["min_component_height"] = min_component_height;
    given["max_tilt"] = max_tilt;
    given["keep_branches"] = keep_branches;
    given["square_branches"] = square_branches;
    given["turn_cuts"] = turn_cuts;
    const mas::DecomposeParams params = decompose_params_from_py(given);
    const mas::CentroidalAxis axis = axis_from_py(axis_py);
    mas::Decomposition d;
    double part_volume = 0.0;
    run_reporting(progress, [&](const mas::Progress& p) {
        d = mas::decompose(shape, axis, params, p);
        part_volume = shape.info().volume_mm3;
    });
    return decomposition_to_py(d, part_volume);
}

void bind_decompose() {
    bp::def(
        "decompose", &decompose,
        (bp::arg("shape"), bp::arg("axis"), bp::arg("face_angle") = 10.0,
         bp::arg("concave_angle") = 1.0, bp::arg("projection_tolerance") = 0.01,
         bp::arg("section_plane_fallback") = true, bp::arg("min_component_height") = 0.0,
         bp::arg("max_tilt") = 100.0, bp::arg("keep_branches") = bp::tuple(),
         bp::arg("square_branches") = bp::tuple(), bp::arg("turn_cuts") = true,
         bp::arg("progress") = bp::object()),
        "Splits a solid (a Shape holding one closed solid) into sub-components along its "
        "centroidal axis `axis` (the dict centroidal_axis() returns for this solid; node regions "
        "are not needed). Angles in degrees, projection_tolerance and min_component_height (the "
        "least a child reaches past its splitting plane, besides one axis step) in mm; max_tilt: "
        "no child is built further from +Z, degrees (the machine's reach); keep_branches: axis "
        "branches (ints, not the root's) left in their fathers' components; square_branches: "
        "axis branches cut at a section plane square to their directions, never turned (square "
        "to their lines, or halfway round a bend); turn_cuts: False turns none. Returns a dict: "
        "components [{solid (Shape), parent (-1 for the root), build_direction, has_base_face, "
        "base_face (Shape or None), base_origin, base_normal, branch, break_link, rule ('root' | "
        "'planar_face' | 'section_plane' | 'bridge'), turned (cut square to its branch's line, or "
        "halfway round a bend, and built along the plane's normal), "
        "volume_mm3}] in tree order (a father before its "
        "children), part_volume_mm3, notes (branches that got no cut, and why), kept_branches "
        "(those of keep_branches kept so), square_branches (as given, sorted). EngineError "
        "not_a_solid / multiple_solids / empty_input "
        "for the shape, invalid_argument for bad parameters, a malformed axis or an axis of "
        "another part, geometry_failure when OCCT fails on the input. `progress`: None or "
        "progress(fraction, stage), called now and then from this thread (fraction 0 to 1, never "
        "decreasing); an exception it raises stops the work and is raised here unchanged.");
}

// ---- stage: adaptive multi-axis slicing and paths
// ------------------------------------------------

// Layer and path parameters from a dict of the names slice() documents; unknown names are errors.
mas::SlicePartParams slice_params_from_py(const bp::dict& d) {
    mas::SlicePartParams p;
    for_each_param(d, "slicing", [&](const std::string& key, const bp::object& value) {
        auto number = [&]() {
            const double x = PyFloat_AsDouble(value.ptr());
            if (x == -1.0 && PyErr_Occurred()) {
                PyErr_Clear();
                invalid_argument(key + " must be a number");
            }
            return x;
        };
        auto integer = [&]() {
            int overflow = 0;
            const long x = PyLong_AsLongAndOverflow(value.ptr(), &overflow);
            if (x == -1 && PyErr_Occurred()) {
                PyErr_Clear();
                invalid_argument(key + " must be an integer");
            }
            if (overflow != 0 || x < std::numeric_limits<int>::min() ||
                x > std::numeric_limits<int>::max())
                invalid_argument(key + " is out of range, got " +
                                 bp::extract<std::string>(bp::str(value))());
            return int(x);
        };
        auto truth = [&]() {
            const int x = PyObject_IsTrue(value.ptr());
            if (x < 0) {
                PyErr_Clear();
                invalid_argument(key + " must be True or False");
            }
            return x == 1;
        };
        if (key == "min_layer")
            p.layers.min_layer_mm = number();
        else if (key == "max_layer")
            p.layers.max_layer_mm = number();
        else if (key == "max_volume_difference")
            p.layers.max_volume_difference = number();
        else if (key == "eps_angle")
            p.layers.eps_angle_deg = number();
        else if (key == "initial_offset")
            p.layers.initial_offset_mm = number();
        else if (key == "overhang_angle")
            p.layers.overhang_angle_deg = number();
        else if (key == "max_tilt")
            p.layers.max_tilt_deg = number();
        else if (key == "volume_samples")
            p.layers.volume_samples = integer();
        else if (key == "strict")
            p.layers.strict = truth();
        else if (key == "bead_width")
            p.paths.bead_width_mm = number();
        else if (key == "overlap")
            p.paths.overlap = number();
        else if (key == "contour_count")
            p.paths.contour_count = integer();
        else if (key == "infill") {
            const bp::extract<std::string> name(value);
            if (!name.check()) invalid_argument("infill must be 'raster', 'contour' or 'none'");
            p.paths.infill = mas::infill_pattern_from_string(name().c_str());
        } else if (key == "raster_angle")
            p.paths.raster_angle_deg = number();
        else if (key == "raster_angle_step")
            p.paths.raster_angle_step_deg = number();
        else if (key == "min_feature")
            p.paths.min_feature_mm = number();
        else if (key == "measure_coverage")
            p.paths.measure_coverage = truth();
        else if (key == "deflection")
            p.tessellation.deflection_mm = number();
        else if (key == "fill_holes")
            p.fill_holes_up_to_mm = number();
        else if (key == "split_mesh")
            p.split_mesh = truth();
        else if (key == "avoid_collisions")
            p.avoid_collisions = truth();
        else if (key == "nozzle_standoff")
            p.nozzle.standoff_mm = number();
        else if (key == "nozzle_tip_diameter")
            p.nozzle.tip_diameter_mm = number();
        else if (key == "nozzle_cone_angle")
            p.nozzle.cone_angle_deg = number();
        else if (key == "nozzle_body_diameter")
            p.nozzle.body_diameter_mm = number();
        else if (key == "nozzle_body_length")
            p.nozzle.body_length_mm = number();
        else if (key == "nozzle_margin")
            p.nozzle.margin_mm = number();
        else if (key == "check_plate")
            p.nozzle.check_plate = truth();
        else if (key == "nozzle_max_lean")
            p.nozzle.max_lean_deg = number();
        else
            invalid_argument("unknown slicing parameter '" + key + "'");
    });
    mas::validate(p.layers);
    mas::validate(p.paths);
    mas::validate(p.nozzle);
    return p;
}

bp::list points_to_py(const std::vector<Eigen::Vector3d>& points) {
    bp::list out;
    for (const auto& p : points) out.append(to_py(p));
    return out;
}

// {"outer": points, "holes": [points, ...]} from a region's 3-D loops (outer first).
bp::dict region_to_py(const std::vector<std::vector<Eigen::Vector3d>>& loops) {
    bp::dict region;
    region["outer"] = points_to_py(loops.front());
    bp::list holes;
    for (std::size_t h = 1; h < loops.size(); ++h) holes.append(points_to_py(loops[h]));
    region["holes"] = holes;
    return region;
}

// A nozzle's collision (NozzleCollision, TravelCollision): {layer, obstacle_layer, nozzle_at,
// obstacle}.
template <class Collision>
bp::dict collision_to_py(const Collision& c) {
    bp::dict d;
    d["layer"] = c.layer;
    d["obstacle_layer"] = c.obstacle_layer;
    d["nozzle_at"] = to_py(c.nozzle_at);
    d["obstacle"] = to_py(c.obstacle);
    return d;
}

bp::dict sliced_to_py(const mas::SlicedPart& r) {
    bp::list layers;
    for (std::size_t i = 0; i < r.layers.size(); ++i) {
        const mas::Layer& l = r.layers[i];
        bp::dict d;
        d["component"] = l.component;
        d["origin"] = to_py(l.plane.origin);
        d["normal"] = to_py(l.plane.normal);
        d["lower_origin"] = to_py(l.lower.origin);
        d["lower_normal"] = to_py(l.lower.normal);
        bp::list regions;
        for (std::size_t k = 0; k < l.regions.size(); ++k)
            regions.append(region_to_py(l.loops_3d(k)));
        d["regions"] = regions;
        bp::list unsupported;
        for (std::size_t k = 0; k < l.unsupported.size(); ++k)
            unsupported.append(region_to_py(l.unsupported_loops_3d(k)));
        d["unsupported_regions"] = unsupported;
        d["area_mm2"] = l.area_mm2;
        d["min_thickness_mm"] = l.min_thickness_mm;
        d["max_thickness_mm"] = l.max_thickness_mm;
        d["volume_mm3"] = l.volume_mm3;
        d["material_volume_mm3"] = l.material_volume_mm3;
        d["volume_difference"] = l.volume_difference;
        d["meets_volume_difference"] = l.meets_volume_difference;
        d["unsupported_area_mm2"] = l.unsupported_area_mm2;
        d["outline_length_mm"] = mas::perimeter(l.regions);
        d["axis_node"] = l.axis_node;
        d["axis_point"] = to_py(l.axis_point);
        const mas::LayerToolpaths& t = r.toolpaths[i];
        bp::list paths;
        for (const mas::ToolPath& p : t.paths) {
            bp::dict path;
            path["kind"] = mas::to_string(p.kind);
            path["region"] = p.region;
            path["points"] = points_to_py(p.points);
            bp::list thickness;
            for (double x : p.thickness_mm) thickness.append(x);
            path["thickness_mm"] = thickness;
            paths.append(path);
        }
        d["tool_axis"] = to_py(t.tool_axis);
        d["paths"] = paths;
        bp::list centre;
        for (int k : t.centre_line_regions) centre.append(k);
        d["centre_line_regions"] = centre;
        bp::list unfilled;
        const mas::PlaneFrame frame(l.plane.normal);
        for (const auto& u : t.unfilled) {
            bp::dict f;
            f["region"] = u.region;
            f["area_mm2"] = u.area_mm2;
            f["centroid"] = to_py(frame.to_3d(u.centroid, l.plane));
            unfilled.append(f);
        }
        d["unfilled"] = unfilled;
        d["deposit_length_mm"] = t.deposit_length_mm;
        d["travel_length_mm"] = t.travel_length_mm;
        d["uncovered_area_mm2"] = t.uncovered_area_mm2;
        layers.append(d);
    }
    bp::list components;
    for (const auto& c : r.components) {
        bp::dict d;
        d["component"] = c.component;
        d["first_layer"] = c.first_layer;
        d["layer_count"] = c.layer_count;
        d["guide_nodes"] = c.guide_nodes;
        d["volume_mm3"] = c.volume_mm3;
        components.append(d);
    }
    bp::list order;
    for (const int c : r.build_order) order.append(c);
    const mas::SliceStats& s = r.stats;
    bp::dict stats;
    stats["layer_count"] = s.layer_count;
    stats["min_thickness_mm"] = s.min_thickness_mm;
    stats["max_thickness_mm"] = s.max_thickness_mm;
    stats["part_volume_mm3"] = s.part_volume_mm3;
    stats["deposited_volume_mm3"] = s.deposited_volume_mm3;
    stats["material_volume_mm3"] = s.material_volume_mm3;
    stats["max_volume_difference"] = s.max_volume_difference;
    stats["layers_over_volume_difference"] = s.layers_over_volume_difference;
    stats["worst_unsupported_area_mm2"] = s.worst_unsupported_area_mm2;
    stats["worst_unsupported_layer"] = s.worst_unsupported_layer;
    stats["deposit_length_mm"] = s.deposit_length_mm;
    stats["travel_length_mm"] = s.travel_length_mm;
    stats["centre_line_passes"] = s.centre_line_passes;
    stats["unfilled_features"] = s.unfilled_features;
    stats["colliding_layers"] = s.colliding_layers;
    stats["component_switches"] = s.component_switches;
    stats["leaned_layers"] = s.leaned_layers;
    stats["filled_holes"] = s.filled_holes;
    stats["filled_volume_mm3"] = s.filled_volume_mm3;
    bp::list holes;
    for (const mas::FilledHole& h : r.filled_holes) {
        bp::dict d;
        d["component"] = h.component;
        d["centre"] = to_py(h.centre);
        d["axis"] = to_py(h.axis);
        d["diameter_mm"] = h.diameter_mm;
        d["length_mm"] = h.length_mm;
        holes.append(d);
    }
    bp::list notes;
    for (const std::string& n : r.notes) notes.append(n);
    bp::list sequence;
    for (const int i : r.sequence.layers) sequence.append(i);
    bp::list collisions;
    for (const mas::NozzleCollision& c : r.sequence.collisions)
        collisions.append(collision_to_py(c));
    bp::dict out;
    out["plate_origin"] = to_py(r.plate.origin);
    out["plate_normal"] = to_py(r.plate.normal);
    out["filled_holes"] = holes;
    out["notes"] = notes;
    out["layers"] = layers;
    out["components"] = components;
    out["build_order"] = order;
    out["sequence"] = sequence;
    out["collisions"] = collisions;
    out["stats"] = stats;
    return out;
}

// The engine's decomposition from the component dicts decompose() returned (only what slicing
// reads: solid, parent, build direction, base origin and normal, branch, turned, rule).
mas::Decomposition decomposition_from_py(const bp::object& value) {
    mas::Decomposition d;
    bp::handle<> seq = fast_sequence(value, "components");
    const Py_ssize_t n = PySequence_Fast_GET_SIZE(seq.get());
    PyObject** items = PySequence_Fast_ITEMS(seq.get());
    for (Py_ssize_t i = 0; i < n; ++i) {
        const bp::object item(bp::handle<>(bp::borrowed(items[i])));
        const std::string what = "components[" + std::to_string(i) + "]";
        mas::Component c;
        const bp::extract<mas::Shape> solid(required(item, "solid", what));
        if (!solid.check()) invalid_argument(what + "['solid'] must be an engine Shape");
        c.solid = solid();
        c.parent = index_of(item, "parent", what);
        c.build_direction =
            vector3(required(item, "build_direction", what), what + "['build_direction']");
        c.base_origin = vector3(required(item, "base_origin", what), what + "['base_origin']");
        c.base_normal = -c.build_direction;
        c.branch = index_of(item, "branch", what);
        // Optional: cut square to its branch's line (decompose()'s "turned"), built along it.
        if (bp::extract<bp::dict>(item).check() && bp::dict(item).has_key("turned")) {
            const bp::extract<bool> turned(item["turned"]);
            if (!turned.check()) invalid_argument(what + "['turned'] must be True or False");
            c.turned = turned();
        }
        // Optional: how it was cut (decompose()'s "rule"); a bridge's piece whose branch crosses
        // its gap is sliced straight along its diagonal (SlicePart.hpp's ComponentMesh::bridge).
        if (bp::extract<bp::dict>(item).check() && bp::dict(item).has_key("rule")) {
            const bp::extract<std::string> rule(item["rule"]);
            bool known = false;
            for (const auto r :
                 {mas::Component::SplitRule::Root, mas::Component::SplitRule::PlanarFace,
                  mas::Component::SplitRule::SectionPlane, mas::Component::SplitRule::Bridge})
                if (rule.check() && rule() == mas::to_string(r)) {
                    c.rule = r;
                    known = true;
                }
            if (!known)
                invalid_argument(what +
                                 "['rule'] must be 'root', 'planar_face', 'section_plane' or "
                                 "'bridge'");
        }
        if (!c.build_direction.allFinite() || c.build_direction.norm() < 1e-12 ||
            !c.base_origin.allFinite())
            invalid_argument(what + " has a non-finite or zero build direction or base origin");
        d.components.push_back(std::move(c));
    }
    return d;
}

bp::dict slice_part(const mas::Shape& shape, const bp::object& axis_py,
                    const bp::object& components_py, const bp::dict& params_py,
                    const bp::object& progress) {
    const mas::SlicePartParams params = slice_params_from_py(params_py);
    const mas::CentroidalAxis axis = axis_from_py(axis_py);
    const mas::Decomposition d = decomposition_from_py(components_py);
    mas::SlicedPart r;
    run_reporting(progress,
                  [&](const mas::Progress& p) { r = mas::slice_part(shape, axis, d, params, p); });
    return sliced_to_py(r);
}

bp::dict slice_solid_part(const mas::Shape& shape, const bp::object& axis_py,
                          const bp::dict& decompose_py, const bp::dict& params_py,
                          const bp::object& progress) {
    const mas::SlicePartParams params = slice_params_from_py(params_py);
    const mas::CentroidalAxis axis = axis_from_py(axis_py);
    const mas::DecomposeParams dp = decompose_params_from_py(decompose_py);
    mas::SlicedPart r;
    mas::Decomposition d;
    double part_volume = 0.0;
    run_reporting(progress, [&](const mas::Progress& p) {
        r = mas::slice_solid_part(shape, axis, dp, params, d, p);
        part_volume = shape.info().volume_mm3;
    });
    bp::dict out = sliced_to_py(r);
    out["decomposition"] = decomposition_to_py(d, part_volume);
    return out;
}

bp::dict slice_mesh_part(const mas::TriangleMesh& mesh, const bp::object& axis_py,
                         const bp::dict& params_py, const bp::object& progress) {
    if (params_py.has_key("deflection"))
        invalid_argument("a mesh is sliced as it is: 'deflection' applies to solids only");
    const mas::SlicePartParams params = slice_params_from_py(params_py);
    const mas::CentroidalAxis axis = axis_from_py(axis_py);
    mas::SlicedPart r;
    run_reporting(progress,
                  [&](const mas::Progress& p) { r = mas::slice_mesh_part(mesh, axis, params, p); });
    return sliced_to_py(r);
}

void bind_slice() {
    const char* params_doc =
        " `params` is a dict of slicing parameters (lengths in mm, angles in degrees): "
        "min_layer, max_layer, max_volume_difference, eps_angle, initial_offset, overhang_angle, "
        "max_tilt, volume_samples, strict, bead_width, overlap, contour_count, infill ('raster' | "
        "'contour' | 'none'), raster_angle, raster_angle_step, min_feature, measure_coverage, "
        "deflection and fill_holes (the largest hole diameter to deposit solid and drill; "
        "a solid's only), split_mesh, avoid_collisions; missing ones take the engine's defaults. "
        "Returns a dict: "
        "layers [{component, origin, normal, lower_origin, lower_normal, regions [{outer, "
        "holes}] as 3-D points, area_mm2, min_thickness_mm, max_thickness_mm, volume_mm3, "
        "material_volume_mm3, volume_difference, meets_volume_difference, unsupported_area_mm2, "
        "unsupported_regions [{outer, holes}] on the lower plane, outline_length_mm (every loop of "
        "regions), axis_node, axis_point, "
        "tool_axis, paths [{kind, region, points, thickness_mm}], "
        "centre_line_regions, unfilled [{region, area_mm2, centroid}], deposit_length_mm, "
        "travel_length_mm, uncovered_area_mm2}], components [{component, first_layer, "
        "layer_count, guide_nodes, volume_mm3}] indexed by component, build_order (the "
        "components in the order they start, the order of the layers), sequence (the layer "
        "indices in deposition order), collisions [{layer, obstacle_layer (-1: the plate), "
        "nozzle_at, obstacle}], stats {...}, filled_holes "
        "[{component, centre, axis, diameter_mm, length_mm}], notes [str]. "
        "EngineError "
        "invalid_argument for bad parameters or a part no layer fits. `progress`: None or "
        "progress(fraction, stage), called now and then from this thread (fraction 0 to 1, never "
        "decreasing, 1 when done); an exception it raises stops the work and is raised here "
        "unchanged.";
    bp::def("slice_part", &slice_part,
            (bp::arg("shape"), bp::arg("axis"), bp::arg("components"), bp::arg("params"),
             bp::arg("progress") = bp::object()),
            (std::string("Slices a solid's sub-components (the component dicts decompose() "
                         "returned, in tree order) along its centroidal axis `axis`.") +
             params_doc)
                .c_str());
    bp::def(
        "slice_solid_part", &slice_solid_part,
        (bp::arg("shape"), bp::arg("axis"), bp::arg("decompose_params"), bp::arg("params"),
         bp::arg("progress") = bp::object()),
        (std::string("Decomposes a solid along its centroidal axis `axis` (with "
                     "`decompose_params`, a dict of decompose()'s keyword arguments: face_angle, "
                     "concave_angle, projection_tolerance, section_plane_fallback, "
                     "min_component_height, max_tilt, keep_branches, square_branches, turn_cuts) "
                     "and slices it; where some layers would meet what is deposited before them, "
                     "the cuts turned square to their branches' lines are made square to their "
                     "directions, else their components' branches are kept in their fathers, "
                     "and it is done again (unless avoid_collisions is false; SlicePart.hpp). "
                     "The result "
                     "also holds `decomposition`, the one sliced, as decompose() returns "
                     "it.") +
         params_doc)
            .c_str());
    bp::def(
        "slice_mesh_part", &slice_mesh_part,
        (bp::arg("mesh"), bp::arg("axis"), bp::arg("params"), bp::arg("progress") = bp::object()),
        (std::string("Slices a closed mesh, split at section planes where its axis turns or "
                     "branches (unless split_mesh is false: one component), keeping in "
                     "their fathers the branches whose layers would meet what is deposited "
                     "before them (unless avoid_collisions is false).") +
         params_doc)
            .c_str());
}

// ---- stage: post-processor
// ---------------------------------------------------------------------------------

// Points from a sequence of 3-sequences.
std::vector<Eigen::Vector3d> points_from(const bp::object& value, const std::string& what) {
    bp::handle<> seq = fast_sequence(value, what);
    const Py_ssize_t n = PySequence_Fast_GET_SIZE(seq.get());
    PyObject** items = PySequence_Fast_ITEMS(seq.get());
    std::vector<Eigen::Vector3d> out;
    out.reserve(std::size_t(n));
    for (Py_ssize_t k = 0; k < n; ++k)
        out.push_back(vector3(bp::object(bp::handle<>(bp::borrowed(items[k]))),
                              what + "[" + std::to_string(k) + "]"));
    return out;
}

std::vector<Eigen::Vector3d> points_of(const bp::object& value, const char* key,
                                       const std::string& what) {
    return points_from(required(value, key, what), what + "['" + key + "']");
}

mas::ToolPath::Kind path_kind(const std::string& name, const std::string& what) {
    for (const auto kind : {mas::ToolPath::Kind::Travel, mas::ToolPath::Kind::Contour,
                            mas::ToolPath::Kind::Infill, mas::ToolPath::Kind::CentreLine})
        if (name == mas::to_string(kind)) return kind;
    invalid_argument(what + " is no path kind: '" + name + "'");
    return mas::ToolPath::Kind::Travel;
}

// The layers as slice_part() returns them: component, tool_axis, max_thickness_mm, regions
// [{outer, holes}], paths [{kind, points, thickness_mm}].
// With `prisms`, each needs its prism too (origin, normal, lower_origin, lower_normal).
std::vector<mas::GcodeLayer> gcode_layers_from_py(const bp::object& value, bool prisms) {
    bp::handle<> seq = fast_sequence(value, "layers");
    const Py_ssize_t n = PySequence_Fast_GET_SIZE(seq.get());
    PyObject** items = PySequence_Fast_ITEMS(seq.get());
    std::vector<mas::GcodeLayer> layers(static_cast<std::size_t>(n));
    for (Py_ssize_t i = 0; i < n; ++i) {
        const bp::object item(bp::handle<>(bp::borrowed(items[i])));
        const std::string what = "layers[" + std::to_string(i) + "]";
        mas::GcodeLayer& l = layers[std::size_t(i)];
        if (PyBool_Check(required(item, "component", what).ptr()))
            invalid_argument(what + "['component'] is not an integer but a bool");
        l.component = index_of(item, "component", what);
        if (bp::extract<bp::dict>(item).check() && bp::dict(item).has_key("index"))
            l.index = index_of(item, "index", what);
        l.tool_axis = vector3(required(item, "tool_axis", what), what + "['tool_axis']");
        l.max_thickness_mm = number_of(item, "max_thickness_mm", what);
        // The prism, for the travel check: the layer's planes and its regions on the top one.
        std::optional<mas::PlaneFrame> frame;
        if (prisms) {
            l.prism.plane = {vector3(required(item, "origin", what), what + "['origin']"),
                             vector3(required(item, "normal", what), what + "['normal']")};
            l.prism.lower = {
                vector3(required(item, "lower_origin", what), what + "['lower_origin']"),
                vector3(required(item, "lower_normal", what), what + "['lower_normal']")};
            for (const mas::Plane& plane : {l.prism.plane, l.prism.lower})
                if (!plane.origin.allFinite() || !(std::abs(plane.normal.norm() - 1.0) <= 1e-6))
                    invalid_argument(what + ": its planes need finite origins and unit normals");
            if (!(l.prism.plane.normal.dot(l.prism.lower.normal) > 1e-6))
                invalid_argument(what +
                                 ": its lower plane must face the way its top does (normal . "
                                 "lower_normal > 0)");
            frame.emplace(l.prism.plane.normal);
        }
        // Each loop's points go into the outline and, with the prism, onto its top plane.
        auto read_loop = [&](const bp::object& points, const std::string& lw) {
            mas::Polygon2 out;
            for (const auto& q : points_from(points, lw)) {
                l.outline.push_back(q);
                if (frame) out.points.push_back(frame->to_2d(q));
            }
            return out;
        };
        const std::vector<bp::object> regions = items_of(item, "regions", what);
        for (std::size_t r = 0; r < regions.size(); ++r) {
            const std::string rw = what + "['regions'][" + std::to_string(r) + "]";
            mas::Region2 region;
            region.outer = read_loop(required(regions[r], "outer", rw), rw + "['outer']");
            const std::vector<bp::object> holes = items_of(regions[r], "holes", rw);
            for (std::size_t h = 0; h < holes.size(); ++h)
                region.holes.push_back(
                    read_loop(holes[h], rw + "['holes'][" + std::to_string(h) + "]"));
            if (prisms) l.prism.regions.push_back(std::move(region));
        }
        if (prisms) {
            l.prism.max_thickness_mm = l.max_thickness_mm;
            // Its lower plane under its top wherever it reaches.
            for (std::size_t r = 0; r < l.prism.regions.size(); ++r)
                for (const auto& loop : l.prism.loops_3d(r))
                    for (const Eigen::Vector3d& q : loop) {
                        const double t = l.prism.thickness_at(q);
                        if (!(t >= -1e-6 && std::isfinite(t)))
                            invalid_argument(what + ": its lower plane lies " +
                                             mas::format_number(-t) +
                                             " mm above its top at a corner of its region");
                    }
        }
        const std::vector<bp::object> paths = items_of(item, "paths", what);
        for (std::size_t k = 0; k < paths.size(); ++k) {
            const std::string pw = what + "['paths'][" + std::to_string(k) + "]";
            mas::ToolPath path;
            const bp::extract<std::string> kind(required(paths[k], "kind", pw));
            if (!kind.check()) invalid_argument(pw + "['kind'] must be a string");
            path.kind = path_kind(kind(), pw + "['kind']");
            path.points = points_of(paths[k], "points", pw);
            const std::vector<bp::object> t = items_of(paths[k], "thickness_mm", pw);
            for (std::size_t j = 0; j < t.size(); ++j)
                path.thickness_mm.push_back(
                    number_at(t[j].ptr(), pw + "['thickness_mm']", Py_ssize_t(j)));
            l.paths.push_back(std::move(path));
        }
    }
    return layers;
}

mas::MachineParams machine_from_py(const bp::dict& d) {
    mas::MachineParams m;
    for_each_param(d, "machine", [&](const std::string& key, const bp::object& value) {
        if (PyBool_Check(value.ptr()))
            invalid_argument("machine parameter " + key + " must be a number, not a bool");
        const double x = PyFloat_AsDouble(value.ptr());
        if (x == -1.0 && PyErr_Occurred()) {
            PyErr_Clear();
            invalid_argument("machine parameter " + key + " must be a number");
        }
        // The plain numbers, each to its field.
        const std::pair<const char*, double*> numbers[] = {
            {"a_min", &m.a_min_deg},
            {"a_max", &m.a_max_deg},
            {"c_min", &m.c_min_deg},
            {"c_max", &m.c_max_deg},
            {"feed", &m.feed_mm_min},
            {"reference_thickness", &m.reference_thickness_mm},
            {"max_feed_ratio", &m.max_feed_ratio},
            {"clearance", &m.clearance_mm},
            {"x_min", &m.travel_min.x()},
            {"x_max", &m.travel_max.x()},
            {"y_min", &m.travel_min.y()},
            {"y_max", &m.travel_max.y()},
            {"z_min", &m.travel_min.z()},
            {"z_max", &m.travel_max.z()},
            {"work_offset_x", &m.work_offset.x()},
            {"work_offset_y", &m.work_offset.y()},
            {"work_offset_z", &m.work_offset.z()},
            {"rot_point_x", &m.rot_point.x()},
            {"rot_point_y", &m.rot_point.y()},
            {"rot_point_z", &m.rot_point.z()},
            {"rot_offset_y", &m.rot_offset_y_mm},
            {"rot_offset_z", &m.rot_offset_z_mm},
            {"tool_length", &m.tool_length_mm}};
        for (const auto& [name, field] : numbers)
            if (key == name) {
                *field = x;
                return;
            }
        if (key == "deposit_output") {
            if (x != std::floor(x))
                invalid_argument("machine parameter deposit_output must be a whole number, got " +
                                 mas::format_number(x));
            if (!(std::abs(x) < 1e9)) {  // validate() names the range
                std::ostringstream got;  // whole, as given: 1099511627776, not 1.09951e+12
                if (std::abs(x) < 1e18)
                    got << std::fixed << std::setprecision(0) << x;
                else
                    got << mas::format_number(x);
                invalid_argument(
                    "machine: the deposition output must be a digital output 0 to 63, got " +
                    got.str());
            }
            m.deposit_output = int(x);
        } else
            invalid_argument("unknown machine parameter '" + key + "'");
    });
    return m;
}

bp::dict write_gcode(const bp::object& layers_py, const bp::dict& machine_py,
                     const bp::object& progress, const bp::object& nozzle_py,
                     const bp::object& plate_py) {
    const mas::MachineParams machine = machine_from_py(machine_py);
    mas::validate(machine);
    std::optional<mas::TravelNozzle> nozzle;
    if (nozzle_py.is_none() && !plate_py.is_none())
        invalid_argument("plate is for the travel check: give the nozzle too");
    if (!nozzle_py.is_none()) {
        const bp::extract<bp::dict> d(nozzle_py);
        if (!d.check())
            invalid_argument("nozzle must be a dict of the slicing's nozzle parameters");
        if (plate_py.is_none())
            invalid_argument("the travel check needs the plate: (origin, normal)");
        bp::handle<> plate = fast_sequence(plate_py, "plate");
        if (PySequence_Fast_GET_SIZE(plate.get()) != 2)
            invalid_argument("plate must be (origin, normal), got " +
                             std::to_string(PySequence_Fast_GET_SIZE(plate.get())) + " items");
        PyObject** ends = PySequence_Fast_ITEMS(plate.get());
        nozzle = mas::TravelNozzle{
            slice_params_from_py(d()).nozzle,
            {vector3(bp::object(bp::handle<>(bp::borrowed(ends[0]))), "the plate's origin"),
             vector3(bp::object(bp::handle<>(bp::borrowed(ends[1]))), "the plate's normal")}};
        if (!nozzle->plate.origin.allFinite() ||
            !(std::abs(nozzle->plate.normal.norm() - 1.0) <= 1e-6))
            invalid_argument("the plate needs a finite origin and a unit normal");
    }
    const std::vector<mas::GcodeLayer> layers = gcode_layers_from_py(layers_py, nozzle.has_value());
    std::string text;
    mas::GcodeStats s;
    run_reporting(progress, [&](const mas::Progress& p) {
        text = mas::write_gcode(layers, machine, &s, p, nozzle ? &*nozzle : nullptr);
    });
    bp::dict stats;
    stats["lines"] = s.lines;
    stats["deposit_moves"] = s.deposit_moves;
    stats["feed_limited_moves"] = s.feed_limited_moves;
    stats["reorientations"] = s.reorientations;
    stats["a_range_deg"] = bp::make_tuple(s.a_min_deg, s.a_max_deg);
    stats["c_range_deg"] = bp::make_tuple(s.c_min_deg, s.c_max_deg);
    stats["deposit_length_mm"] = s.deposit_length_mm;
    stats["deposit_time_min"] = s.deposit_time_min;
    stats["rapid_length_mm"] = s.rapid_length_mm;
    stats["reference_thickness_mm"] = s.reference_thickness_mm;
    stats["x_range_mm"] = bp::make_tuple(s.machine_min.x(), s.machine_max.x());
    stats["y_range_mm"] = bp::make_tuple(s.machine_min.y(), s.machine_max.y());
    stats["z_range_mm"] = bp::make_tuple(s.machine_min.z(), s.machine_max.z());
    stats["checked_routes"] = s.checked_routes;
    stats["rerouted_travels"] = s.rerouted_travels;
    bp::list collisions;
    for (const mas::TravelCollision& c : s.travel_collisions) collisions.append(collision_to_py(c));
    stats["travel_collisions"] = collisions;
    bp::dict out;
    out["text"] = text;
    out["stats"] = stats;
    return out;
}

void bind_gcode() {
    bp::def("write_gcode", &write_gcode,
            (bp::arg("layers"), bp::arg("machine") = bp::dict(), bp::arg("progress") = bp::object(),
             bp::arg("nozzle") = bp::object(), bp::arg("plate") = bp::object()),
            "The 5-axis G-code program (LinuxCNC, tilting rotary table XYZAC, xyzac-trt-kins) "
            "that deposits `layers` (slice_part()'s layer dicts, in the order they are deposited: "
            "its sequence; an 'index' in one is its number in the part, which comments and errors "
            "name, else its place in `layers`). `machine`: a "
            "dict of a_min, a_max, c_min, c_max (degrees), feed (mm/min at the reference "
            "thickness), reference_thickness (mm, 0: derived), max_feed_ratio, clearance (mm), "
            "deposit_output, and the X Y Z travel (mm): x_min, x_max, y_min, y_max, z_min, z_max "
            "(infinite: not checked), work_offset_x/y/z (G54), rot_point_x/y/z, rot_offset_y, "
            "rot_offset_z (xyzac-trt-kins' pivot pins), tool_length; missing ones take the "
            "engine's defaults. Returns {text, stats "
            "{lines, deposit_moves, feed_limited_moves, reorientations, a_range_deg, c_range_deg, "
            "deposit_length_mm, deposit_time_min, rapid_length_mm, reference_thickness_mm, "
            "x_range_mm, y_range_mm, z_range_mm (the machine's joints), checked_routes, "
            "rerouted_travels, travel_collisions [{layer, obstacle_layer, "
            "nozzle_at, obstacle}]}}. `nozzle` (a dict of slice_part()'s nozzle_* parameters and "
            "check_plate) and `plate` ((origin, normal)): the travel is checked against them and "
            "the layers' prisms (their origin, normal, lower_origin, lower_normal and regions). "
            "EngineError invalid_argument for bad parameters, unreachable_orientation for a "
            "layer the table cannot turn to the nozzle, out_of_travel for a program past the X Y "
            "Z limits. `progress` as slice_part()'s.");
}

// ---- drawing
// ---------------------------------------------------------------------------------------------

// A loop of 3-D points (`what` in errors) in `frame`'s 2-D coordinates.
mas::Polygon2 loop_in(const mas::PlaneFrame& frame, const bp::object& points,
                      const std::string& what) {
    mas::Polygon2 out;
    for (const Eigen::Vector3d& q : points_from(points, what)) {
        if (!q.allFinite()) invalid_argument(what + " has a point that is not finite");
        out.points.push_back(frame.to_2d(q));
    }
    return out;
}

// The build preview's drawing of a layer: prism_mesh() of its regions.
bp::tuple prism_mesh_py(const bp::object& regions_py, const bp::object& origin,
                        const bp::object& normal, double depth) {
    const mas::Plane plane = mas::make_plane(vector3(origin, "origin"), vector3(normal, "normal"));
    if (!(depth > 0.0 && std::isfinite(depth)))
        invalid_argument("depth must be a positive number of mm, got " + mas::format_number(depth));
    const mas::PlaneFrame frame(plane.normal);
    const std::vector<bp::object> items = items_from(regions_py, "regions");
    mas::Regions2 regions;
    for (std::size_t r = 0; r < items.size(); ++r) {
        const bp::object& item = items[r];
        const std::string what = "regions[" + std::to_string(r) + "]";
        mas::Region2 region;
        region.outer = loop_in(frame, required(item, "outer", what), what + "['outer']");
        const std::vector<bp::object> holes = items_of(item, "holes", what);
        for (std::size_t h = 0; h < holes.size(); ++h)
            region.holes.push_back(
                loop_in(frame, holes[h], what + "['holes'][" + std::to_string(h) + "]"));
        regions.push_back(std::move(region));
    }
    const mas::TriangleMesh mesh = mas::prism_mesh(regions, plane, depth);
    return bp::make_tuple(mesh_vertices(mesh), mesh_triangles(mesh));
}

// The triangles of a planar polygon with holes: triangulate() of `loops` (3-D points, outer loop
// first) seen along `normal`.
bp::list triangulate_py(const bp::object& loops_py, const bp::object& normal) {
    const mas::Plane plane = mas::make_plane(Eigen::Vector3d::Zero(), vector3(normal, "normal"));
    const mas::PlaneFrame frame(plane.normal);
    const std::vector<bp::object> items = items_from(loops_py, "loops");
    mas::Region2 region;
    for (std::size_t k = 0; k < items.size(); ++k) {
        mas::Polygon2 loop = loop_in(frame, items[k], "loops[" + std::to_string(k) + "]");
        if (k == 0)
            region.outer = std::move(loop);
        else
            region.holes.push_back(std::move(loop));
    }
    bp::list out;
    for (const auto& t : mas::triangulate(region)) out.append(bp::make_tuple(t[0], t[1], t[2]));
    return out;
}

void bind_drawing() {
    bp::def("triangulate", &triangulate_py, (bp::arg("loops"), bp::arg("normal")),
            "[(i, j, k)]: triangles covering the planar polygon `loops` (lists of (x, y, z), the "
            "outer loop first, then its holes; either way round), counter-clockwise seen from "
            "`normal`'s side, as indices into the loops' points taken in turn. Ear clipping, the "
            "holes bridged to the outline; no point added. EngineError invalid_argument for a "
            "zero normal or a point that is not finite.");
    bp::def(
        "prism_mesh", &prism_mesh_py,
        (bp::arg("regions"), bp::arg("origin"), bp::arg("normal"), bp::arg("depth")),
        "(points [(x, y, z)], triangles [(i, j, k)]): the closed surface of `regions` ([{outer, "
        "holes}], loops of points on the plane (origin, normal)) swept back along -normal by "
        "`depth` mm, every triangle counter-clockwise seen from outside: each region's face "
        "(ear clipping, its holes bridged to its outline), the same face below, and a wall "
        "along each edge. Points: per region, its points on the plane (outer loop first, "
        "then each hole), then the same points below. What the build preview draws a layer "
        "with. EngineError invalid_argument for a bad plane or depth.");
}

}  // namespace

BOOST_PYTHON_MODULE(_engine) {
    bp::scope module;
    module.attr("__doc__") =
        "Multi-Axis Slicer's C++ engine. Use the MultiAxisSlicer package; this module is its "
        "low-level layer.";

    bp::dict class_attrs;
    class_attrs["code"] = "internal";
    class_attrs["message"] = "";
    class_attrs["__doc__"] =
        "An engine failure or bad input: `code` is a stable name such as 'open_mesh', "
        "'not_a_solid' or 'invalid_argument'; `message` (= str(error)) says what and where.";
    engine_error_type = PyErr_NewException("MultiAxisSlicer._engine.EngineError",
                                           PyExc_RuntimeError, class_attrs.ptr());
    if (!engine_error_type) bp::throw_error_already_set();
    module.attr("EngineError") = bp::object(bp::handle<>(bp::borrowed(engine_error_type)));

    // Boost.Python tries the most recently registered translator first: the specific one goes last.
    bp::register_exception_translator<std::exception>(&translate_std_exception);
    bp::register_exception_translator<mas::Error>(&translate_engine_error);

    bp::def(
        "call_quietly", &call_quietly, (bp::arg("function"), bp::arg("argument")),
        "function(argument); if that returns an exception instance, raises it without a Python "
        "traceback (FreeCAD reports a document object's recompute error by its message alone).");

    bind_shape();
    bind_mesh();
    bind_read();
    bind_tessellate();
    bind_section();
    bind_exact_section();
    bind_axis();
    bind_decompose();
    bind_slice();
    bind_gcode();
    bind_drawing();
}
