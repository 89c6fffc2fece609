# SPDX-License-Identifier: LGPL-2.1-or-later
"""Multi-Axis Slicer: cross-sections and centroidal axes of solids and meshes, for scripts and
FreeCAD.

The scripting API over the C++ engine (the compiled module ``MultiAxisSlicer._engine``). It runs in
FreeCAD (GUI or ``freecadcmd``) and in a plain Python 3.11 script; FreeCAD types (``Part.Shape``,
``Mesh.Mesh``, document objects, ``FreeCAD.Vector``) are used when FreeCAD is importable::

    import MultiAxisSlicer as mas
    for s in mas.sections(App.ActiveDocument.Box, normal=(0, 0, 1), step=2.0):
        print(s.origin, s.area, s.centroid)
    axis = mas.centroidal_axis(App.ActiveDocument.Box, step=2.0)   # see MultiAxisSlicer.axis
    parts = mas.decompose(App.ActiveDocument.Box, step=2.0)  # see MultiAxisSlicer.decompose

Errors:
  * ``EngineError`` (a ``RuntimeError``) for a part the engine cannot use; ``error.code`` names the
    problem (``not_a_solid``, ``multiple_solids``, ``open_mesh``, ``non_finite_coordinate``,
    ``empty_input``, ``read_failed``, ``unsupported_format``, ``invalid_argument``, ...) and
    ``str(error)`` says what and where.
  * ``ValueError`` / ``TypeError`` for bad parameters (``step <= 0``, a zero or NaN normal,
    ``None``).
  * ``EngineUnavailableError`` when the compiled engine is missing: importing this package always
    works, the functions that need the engine raise it with the build command.
  * ``Cancelled`` (or whatever a ``progress=`` callback raises) when the callback stopped a long
    computation: see ``MultiAxisSlicer.progress``.

Nothing here modifies the caller's shape, mesh or document object: solids cross into the engine as
BREP text, meshes as coordinate arrays.
"""

import math
import numbers
import os

__version__ = "0.1.0"

__all__ = [
    "AxisBranch",
    "AxisLink",
    "AxisNode",
    "Cancelled",
    "CentroidalAxis",
    "Collision",
    "Component",
    "Decomposition",
    "EngineError",
    "EngineUnavailableError",
    "FilledHole",
    "GcodeProgram",
    "Layer",
    "MACHINE_DEFAULTS",
    "MAX_SECTION_POINTS",
    "Region",
    "SLICE_DEFAULTS",
    "Section",
    "SliceResult",
    "ToolPath",
    "deflection",
    "engine_available",
    "engine_missing_message",
    "centroidal_axis",
    "decompose",
    "exact_sections",
    "gcode",
    "make_build_preview",
    "make_centroidal_axis",
    "make_decomposition",
    "make_machine_program",
    "make_sections",
    "make_slice",
    "parallel_planes",
    "read",
    "section",
    "sections",
    "slice",
    "to_engine_mesh",
]

BUILD_COMMAND = "./tools/setup.sh install"

try:
    from . import _engine
except ImportError as _error:  # not built yet, or built against another Python/OCCT
    _engine = None
    _engine_import_error = _error
else:
    _engine_import_error = None

try:  # FreeCAD is optional: results use FreeCAD.Vector when it is there, tuples otherwise
    import FreeCAD as _FreeCAD
except ImportError:
    _FreeCAD = None


class EngineUnavailableError(RuntimeError):
    """The compiled engine ``MultiAxisSlicer/_engine.so`` is missing or does not load."""


if _engine is not None:
    EngineError = _engine.EngineError
else:

    class EngineError(RuntimeError):
        """An engine failure or bad input: ``code`` names it, ``str(error)`` explains it."""

        code = "internal"
        message = ""


def _engine_error(code, message):
    error = EngineError(message)
    error.code = code
    error.message = message
    return error


def engine_available():
    """True if the compiled engine loaded, so that the functions of this package work."""
    return _engine is not None


def engine_missing_message():
    """Why the engine is unavailable and how to build it; an empty string when it is available."""
    if _engine is not None:
        return ""
    folder = os.path.dirname(os.path.abspath(__file__))
    built = any(n.startswith("_engine.") and n.endswith((".so", ".pyd"))
                for n in os.listdir(folder))
    problem = (
        "does not load ({})".format(_engine_import_error)
        if built
        else "is not built (no _engine.so in {})".format(folder)
    )
    return (
        "Multi-Axis Slicer: the compiled engine {}. Build and install it from the add-on's source "
        "folder with: {}".format(problem, BUILD_COMMAND)
    )


def _require_engine():
    if _engine is None:
        raise EngineUnavailableError(engine_missing_message())
    return _engine


# ---- parameters ----------------------------------------------------------------------------------


def _vector3(value, name):
    """(x, y, z) floats from a FreeCAD.Vector, a tuple or a list; TypeError otherwise."""
    if value is None:
        raise TypeError("{} must be 3 numbers, got None".format(name))
    if all(hasattr(value, a) for a in ("x", "y", "z")):
        coords = (value.x, value.y, value.z)
    else:
        try:
            coords = tuple(value)
        except TypeError:
            raise TypeError(
                "{} must be 3 numbers, got {}".format(name, type(value).__name__)
            ) from None
    if len(coords) != 3 or not all(
        isinstance(c, numbers.Real) and not isinstance(c, bool) for c in coords
    ):
        raise TypeError("{} must be 3 numbers, got {!r}".format(name, value))
    return tuple(float(c) for c in coords)


def _direction(value, name="normal"):
    v = _vector3(value, name)
    if not all(math.isfinite(c) for c in v):
        raise ValueError("{} has NaN or infinite coordinates: {}".format(name, v))
    scale = max(abs(c) for c in v)
    if scale == 0.0 or scale * math.sqrt(sum((c / scale) ** 2 for c in v)) <= 1e-12:
        raise ValueError("{} is the zero vector".format(name))
    # A vector whose length would overflow ((1e300, 1e300, 1e300)) comes down to 1 along its
    # largest coordinate; any other is kept as given.
    return tuple(c / scale for c in v) if scale > 1e150 else v


def _point(value, name):
    v = _vector3(value, name)
    if not all(math.isfinite(c) for c in v):
        raise ValueError("{} has NaN or infinite coordinates: {}".format(name, v))
    return v


def _length(value, name, allow_zero=False):
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        value = getattr(value, "Value", value)  # a FreeCAD Quantity in mm
        if isinstance(value, bool) or not isinstance(value, numbers.Real):
            raise TypeError("{} must be a number of millimetres, got {!r}".format(name, value))
    value = float(value)
    if not math.isfinite(value) or value < 0.0 or (value == 0.0 and not allow_zero):
        raise ValueError(
            "{} must be a {} number of millimetres, got {}".format(
                name, "non-negative" if allow_zero else "positive", value
            )
        )
    return value


def _deflection_mm(deflection):
    """None or 0 -> 0.0 (the engine derives it from the part's size)."""
    if deflection is None:
        return 0.0
    return _length(deflection, "deflection", allow_zero=True)


# ---- turning whatever the caller has into the engine's types -------------------------------------


def _is_part_shape(obj):
    # not hasattr(obj, "ShapeType"): a null Part.Shape raises a FreeCAD error on reading it
    return hasattr(obj, "exportBrepToString") and hasattr(obj, "isNull")


def _is_fc_mesh(obj):
    # On the type: hasattr(obj, "Topology") reads the property, every point and facet of the mesh
    # into Python objects (half the time it takes to reach the engine), only to drop them.
    return hasattr(type(obj), "Topology") and hasattr(type(obj), "CountFacets")


def _is_document_object(obj):
    return hasattr(obj, "TypeId") and hasattr(obj, "Document") and hasattr(obj, "Name")


def _label(obj):
    label = getattr(obj, "Label", None) or getattr(obj, "Name", None)
    return "'{}'".format(label) if label else "the object"


def _engine_shape_from_part(shape, what):
    if shape.isNull():
        raise _engine_error("empty_input", "{} is empty".format(what) if what == "the shape"
                            else "{}: the shape is empty".format(what))
    return _require_engine().Shape.from_brep_string(shape.exportBrepToString())


def _engine_mesh_from_fc_mesh(mesh, what):
    if mesh.CountFacets == 0:
        raise _engine_error("empty_input", "{}: the mesh has no triangles".format(what))
    points, facets = mesh.Topology  # points with the mesh's placement applied
    return _require_engine().Mesh.from_topology(points, facets)


class _Converted:
    """A part already turned into the engine's type by ``_model``, with the name its messages give
    it: what a caller that had to convert a document object (a Layers object's mesh fingerprint)
    hands on, so that it is not converted again."""

    __slots__ = ("kind", "part", "what")

    def __init__(self, kind, part, what):
        self.kind, self.part, self.what = kind, part, what


def _groups_of(obj):
    """The groups a document object sits in (an ``App::Part``, a PartDesign ``Body`` holding a
    feature), innermost first; none for anything else."""
    parent_of = getattr(obj, "getParentGeoFeatureGroup", None)
    group, seen = (parent_of() if parent_of is not None else None), set()
    while group is not None and group.Name not in seen:  # a group in itself: FreeCAD refuses it
        seen.add(group.Name)
        yield group
        group = group.getParentGeoFeatureGroup()


def _containers_placement(obj):
    """The placement of the groups a document object sits in (``_groups_of``), combined outermost
    first: what the 3D view applies to its shape on top of the object's own placement, which the
    shape already carries. None where it sits in none, or they do not move it."""
    placement = None
    for group in _groups_of(obj):
        own = getattr(group, "Placement", None)
        if own is not None:
            placement = own if placement is None else own.multiply(placement)
    if placement is None or placement.isIdentity():
        return None
    return placement


def _mesh_array_of(obj):
    """The mesh object a link array ``obj`` (its ElementCount set) holds copies of; None when
    ``obj`` is no link array, or one of something else."""
    if not getattr(obj, "ElementCount", 0):
        return None
    target = getattr(obj, "LinkedObject", None)
    if isinstance(target, tuple):  # (container, sub-object's name): a link into a group
        owner, sub = target[0], target[1]
        if isinstance(sub, (list, tuple)):
            sub = sub[0] if sub else ""
        target = owner.getSubObject(sub, 1) if sub else owner
    target = target.getLinkedObject(True) if target is not None else None
    return target if target is not None and target.isDerivedFrom("Mesh::Feature") else None


def _linked_mesh(obj):
    """(mesh object, matrix) when the document object ``obj`` links to a mesh object (an
    ``App::Link``, or a chain of them, to a ``Mesh::Feature``): the mesh object and the transform
    the link applies to its mesh's own coordinates, as the 3D view shows it (the link's placement,
    or the mesh object's too with LinkTransform). None for anything else. A link array of a mesh
    (ElementCount set), or a link to one, holds several copies, which no one part is:
    ValueError."""
    if obj.isDerivedFrom("Mesh::Feature") or not hasattr(obj, "getLinkedObject"):
        return None
    import FreeCAD

    linked, matrix = obj.getLinkedObject(True, FreeCAD.Matrix(), True)
    if linked is None:
        return None
    array = _mesh_array_of(linked)
    if array is not None:
        raise ValueError("{} {} {} copies of the mesh {} (a link array): select the mesh".format(
            _label(obj), "is" if linked is obj else "links to", linked.ElementCount,
            _label(array)))
    if linked is obj or not linked.isDerivedFrom("Mesh::Feature"):
        return None
    return linked, matrix


def _placed(obj):
    """A document object's ``Part.Shape`` or ``Mesh.Mesh`` where the 3D view shows it: with the
    placements of the groups it sits in applied (``_containers_placement``), since the plate is
    the document's XY plane. A copy where those move it, else its own shape or mesh; None when it
    has neither. Anything that is not a document object is given back as it is."""
    if not _is_document_object(obj):
        return obj
    link = _linked_mesh(obj)
    if obj.isDerivedFrom("Mesh::Feature"):
        model = obj.Mesh
    elif link is not None:
        import FreeCAD

        # The mesh in its own coordinates, moved as the link shows it.
        model = link[0].Mesh.copy()
        model.Placement = FreeCAD.Placement()
        model.transform(link[1])
    else:
        model = getattr(obj, "Shape", None)
        if model is None:
            try:
                import Part

                model = Part.getShape(obj)  # App::Link and other shape-less containers
            except Exception:
                return None
        if not _is_part_shape(model):
            return None
        if model.isNull():
            return model
    placement = _containers_placement(obj)
    if placement is None:
        return model
    model = model.copy()
    model.Placement = placement.multiply(model.Placement)
    return model


def _model(obj, what=None):
    """(kind, engine part, name): ("solid", engine Shape) or ("mesh", engine Mesh) for anything the
    API accepts."""
    eng = _require_engine()
    if isinstance(obj, _Converted):
        return obj.kind, obj.part, what or obj.what
    if obj is None:
        raise TypeError(
            "expected a solid or a closed mesh (Part.Shape, Mesh.Mesh, document object or file "
            "path), got None"
        )
    if isinstance(obj, eng.Shape):
        return "solid", obj, what or "shape"
    if isinstance(obj, eng.Mesh):
        return "mesh", obj, what or "mesh"
    if isinstance(obj, (str, bytes, os.PathLike)):
        path = os.fsdecode(obj)
        kind, part = eng.read_model(path)
        return kind, part, what or os.path.basename(path)
    if _is_part_shape(obj):
        what = what or ("the given {}".format(obj.ShapeType) if not obj.isNull() else "the shape")
        return "solid", _engine_shape_from_part(obj, what), what
    if _is_fc_mesh(obj):
        what = what or "the mesh"
        return "mesh", _engine_mesh_from_fc_mesh(obj, what), what
    if _is_document_object(obj):
        what = what or _label(obj)
        model = _placed(obj)
        if model is None:
            raise TypeError("{} ({}) has no shape or mesh".format(what, obj.TypeId))
        return _model(model, what)
    raise TypeError(
        "expected a solid or a closed mesh (Part.Shape, Mesh.Mesh, document object or file path), "
        "got {}".format(type(obj).__name__)
    )


def to_engine_mesh(obj, deflection=None):
    """The closed triangle mesh (an engine ``Mesh``) the section kernel cuts for ``obj``.

    ``obj`` may be a ``Part.Shape`` holding exactly one closed solid (a compound of one solid is
    fine; solids sharing material, as a CompSolid, are fused into the one body they make), a closed
    ``Mesh.Mesh``, a FreeCAD document object with such a ``Shape`` or ``Mesh`` (taken where the 3D
    view shows it, the placements of the groups it sits in applied), a file path
    (.step/.stp, .iges/.igs, .brep/.brp, .stl, .off), or an engine ``Shape``/``Mesh``.
    Solids are tessellated with chordal ``deflection`` mm (None or 0: derived from the part's size,
    see ``deflection()``). Meshes are checked and copied: an inside-out mesh is flipped in the copy,
    and the copy's vertices are sorted by their coordinates and its triangles by their vertices, so
    that the same surface given in any order (another exporter, a shuffled STL) slices the same.

    Raises EngineError (not_a_solid for a face, shell or wire; multiple_solids for solids apart;
    open_mesh; non_finite_coordinate; empty_input; read_failed; unsupported_format), TypeError for
    anything else, ValueError for a negative or NaN deflection.
    """
    d = _deflection_mm(deflection)
    kind, part, what = _model(obj)
    eng = _engine
    if kind == "solid":
        return eng.tessellate(part.single_solid(what), d)
    return eng.make_closed(part, what)


def deflection(shape, deflection=None):
    """The chordal deflection (mm) a solid is tessellated with: ``deflection`` if given and > 0,
    else 0.05% of the part's bounding-box diagonal clamped to [0.005, 0.1] mm.

    A mesh section's boundary lies within about this distance of the exact section, so a section's
    area differs from the exact one by at most about deflection x perimeter. ``shape`` is anything
    ``to_engine_mesh`` accepts as a solid; a mesh raises TypeError (it is used as it is).
    """
    d = _deflection_mm(deflection)
    kind, part, what = _model(shape)
    if kind != "solid":
        raise TypeError(
            "{} is a mesh: it is cut as it is, no tessellation deflection applies".format(what))
    return _engine.effective_deflection(part.single_solid(what), d)


def read(path):
    """Reads a part file: an engine ``Shape`` for .step/.stp, .iges/.igs, .brep/.brp, an engine
    ``Mesh`` for .stl and .off. Both can be passed to every function here;
    ``Shape.to_brep_string()`` gives BREP text for ``Part.Shape().importBrepFromString()``.

    Raises EngineError read_failed / empty_input / unsupported_format / non_finite_coordinate.
    """
    if not isinstance(path, (str, bytes, os.PathLike)):
        raise TypeError("path must be a file name, got {}".format(type(path).__name__))
    return _require_engine().read_model(os.fsdecode(path))[1]


# ---- results -------------------------------------------------------------------------------------


def _as_vector(p):
    return _FreeCAD.Vector(*p) if _FreeCAD is not None else tuple(p)


def _as_list(p):
    return [float(c) for c in p]


class Region:
    """One connected piece of a section: an outer loop and the holes inside it.

    Attributes: ``area`` (mm², outer minus holes), ``centroid`` (area centroid, on the plane),
    ``bounds`` ((min, max) corners of the outer loop), ``outer`` (the outer loop, counter-clockwise
    seen from the side the normal points to), ``holes`` (list of loops, clockwise), ``loops``
    (outer first, then holes). Points are FreeCAD.Vector when FreeCAD is importable, else tuples;
    a loop's last point is not repeated.
    """

    __slots__ = ("area", "_centroid", "_bounds", "_loops")

    def __init__(self, data):
        self.area = data["area"]
        self._centroid = data["centroid"]
        self._bounds = data["bounds"]
        self._loops = data["loops"]

    @property
    def centroid(self):
        return _as_vector(self._centroid)

    @property
    def bounds(self):
        if self._bounds is None:
            return None
        return (_as_vector(self._bounds[0]), _as_vector(self._bounds[1]))

    @property
    def loops(self):
        return [[_as_vector(p) for p in loop] for loop in self._loops]

    @property
    def outer(self):
        return [_as_vector(p) for p in self._loops[0]] if self._loops else []

    @property
    def holes(self):
        return [[_as_vector(p) for p in loop] for loop in self._loops[1:]]

    def to_dict(self):
        """JSON-ready plain data."""
        return {
            "area": self.area,
            "centroid": _as_list(self._centroid),
            "bounds": None
            if self._bounds is None
            else {"min": _as_list(self._bounds[0]), "max": _as_list(self._bounds[1])},
            "outer": [_as_list(p) for p in self._loops[0]] if self._loops else [],
            "holes": [[_as_list(p) for p in loop] for loop in self._loops[1:]],
        }

    def __repr__(self):
        return "<MultiAxisSlicer.Region area={:.6g} mm2 holes={}>".format(
            self.area, max(len(self._loops) - 1, 0)
        )


class Section:
    """Everything one plane cuts out of a part.

    Attributes: ``origin`` and ``normal`` (unit) of the plane, ``area`` (mm², all regions),
    ``centroid`` (area centroid of all regions; the plane's origin when
    empty), ``regions`` (list of ``Region``, largest first), ``open_chains`` (segment chains that
    did not close: 0 for a closed part). Points are FreeCAD.Vector when FreeCAD is importable.
    """

    __slots__ = ("area", "open_chains", "regions", "_origin", "_normal", "_centroid")

    def __init__(self, data):
        self._origin = data["origin"]
        self._normal = data["normal"]
        self._centroid = data["centroid"]
        self.area = data["area"]
        self.open_chains = data["open_chains"]
        self.regions = [Region(r) for r in data["regions"]]

    @property
    def origin(self):
        return _as_vector(self._origin)

    @property
    def normal(self):
        return _as_vector(self._normal)

    @property
    def centroid(self):
        return _as_vector(self._centroid)

    def empty(self):
        """True if the plane misses the part."""
        return not self.regions

    def to_dict(self):
        """JSON-ready plain data (lists and floats)."""
        return {
            "origin": _as_list(self._origin),
            "normal": _as_list(self._normal),
            "area": self.area,
            "centroid": _as_list(self._centroid),
            "open_chains": self.open_chains,
            "regions": [r.to_dict() for r in self.regions],
        }

    def __repr__(self):
        return "<MultiAxisSlicer.Section origin={} area={:.6g} mm2 regions={}>".format(
            tuple(round(c, 6) for c in self._origin), self.area, len(self.regions)
        )


# ---- sections ------------------------------------------------------------------------------------


def _planes(planes):
    """[(origin, normal), ...] as tuples, checked."""
    if planes is None:
        raise TypeError("planes must be a list of (origin, normal) pairs, got None")
    out = []
    for i, plane in enumerate(planes):
        try:
            origin, normal = plane
        except (TypeError, ValueError):
            raise TypeError(
                "planes[{}] must be an (origin, normal) pair, got {!r}".format(i, plane)
            ) from None
        out.append(
            (_point(origin, "planes[{}] origin".format(i)),
             _direction(normal, "planes[{}] normal".format(i)))
        )
    return out


def parallel_planes(obj, normal=(0, 0, 1), step=1.0, deflection=None):
    """[(origin, normal), ...]: planes ``step`` mm apart across ``obj`` along ``normal``, each in
    the middle of its slab (the planes ``sections()`` cuts). Points are FreeCAD.Vector if
    available."""
    n = _direction(normal)
    step = _length(step, "step")
    mesh = to_engine_mesh(obj, deflection)
    return [(_as_vector(o), _as_vector(v)) for o, v in _engine.parallel_planes(mesh, n, step)]


# sections() with a progress callback cuts up to this many planes in one call; more in about ten
# calls of at least 500 (each call prepares the mesh again: a few tenths of a second on a large one).
_SECTIONS_IN_ONE_CALL = 2000

# sections() keeps every loop point as Python floats, about 230 bytes each (2.3 GB at this limit,
# measured): a step that would give more is refused before anything is cut.
MAX_SECTION_POINTS = 10000000


def sections(obj, normal=(0, 0, 1), step=1.0, deflection=None, progress=None):
    """Cross-sections of a solid or closed mesh by parallel planes ``step`` mm apart along
    ``normal``, across the part's whole extent, each plane in the middle of its slab.

    ``obj``: see ``to_engine_mesh``. Returns a list of ``Section``, in order along the normal.
    ``progress``: None or ``progress(fraction, stage)``, called with the fraction of the planes
    cut: once at the end for up to 2000 planes, else about ten times (every tenth, at least 500
    planes apart); an exception it raises (``Cancelled``) stops the work and is raised again (see
    ``MultiAxisSlicer.progress``). Raises ValueError for ``step <= 0`` or a
    zero/NaN ``normal``, TypeError for a wrong type, and EngineError (with ``code``) for a part
    the engine cannot cut, or a step that would give more than 100000 planes or sections holding
    more than ``MAX_SECTION_POINTS`` loop points (counted before anything is cut).
    """
    return _parallel_sections(obj, normal, step, deflection, progress, MAX_SECTION_POINTS,
                              "sections() keeps")


def _parallel_sections(obj, normal, step, deflection, progress, max_points, keeps):
    """sections(), refusing sections that hold more than ``max_points`` loop points; ``keeps``
    says who holds them in the message ("sections() keeps")."""
    from . import progress as _progress

    n = _direction(normal)
    step = _length(step, "step")
    _progress.check(progress)
    mesh = to_engine_mesh(obj, deflection)
    planes = _engine.parallel_planes(mesh, n, step)
    points = sum(_engine.section_point_counts(mesh, planes))
    if points > max_points:
        raise _engine_error(
            "invalid_argument",
            "step {:.6g} mm is too small for this part: its {} sections would hold {} loop "
            "points, more than the {} {}; use a larger step".format(
                step, len(planes), points, max_points, keeps))
    if progress is None:
        return [Section(d) for d in _engine.slice(mesh, planes, True)]
    out = []
    size = len(planes) if len(planes) <= _SECTIONS_IN_ONE_CALL else max(500, -(-len(planes) // 10))
    for start in range(0, len(planes), size):
        chunk = planes[start:start + size]
        out += [Section(d) for d in _engine.slice(mesh, chunk, True)]
        progress(len(out) / len(planes), "cutting {} sections".format(len(planes)))
    return out


def section(obj, origin, normal, deflection=None):
    """The cross-section of a solid or closed mesh by one plane through ``origin`` with ``normal``.
    An empty ``Section`` if the plane misses the part."""
    plane = (_point(origin, "origin"), _direction(normal))
    mesh = to_engine_mesh(obj, deflection)
    return Section(_engine.slice(mesh, [plane], True)[0])


def exact_sections(shape, planes, loop_deflection=0.01):
    """OCCT's exact sections of a solid (no tessellation), as ``Section`` objects: the reference the
    mesh-based ``sections()`` is checked against, 13 to 23 times slower on the example bracket and
    about 500 times across a torus' tube.

    ``shape``: a solid as ``to_engine_mesh`` accepts it (not a mesh). ``planes``: [(origin, normal),
    ...], e.g. from ``parallel_planes()``. Region loops are discretised within ``loop_deflection``
    mm. Areas and centroids are exact where the section's curves are lines, circles or ellipses;
    where OCCT can only trace them (a torus off its axis, a B-spline surface), within perimeter x
    ``loop_deflection`` of the traced loops.
    """
    planes = _planes(planes)
    loop_deflection = _length(loop_deflection, "loop_deflection")
    kind, part, what = _model(shape)
    if kind != "solid":
        raise TypeError("exact_sections() needs a solid; {} is a mesh".format(what))
    solid = part.single_solid(what)
    return [Section(d) for d in _engine.exact_sections(solid, planes, loop_deflection)]


# ---- document objects ----------------------------------------------------------------------------


def make_sections(source, normal=(0, 0, 1), step=5.0, deflection=0.0, name="Sections", doc=None):
    """Adds a parametric ``Sections`` object (FreeCAD only) cutting the document object ``source``
    and returns it; recompute the document to compute it. See ``MultiAxisSlicer.features``."""
    from . import features

    return features.make_sections(source, normal=normal, step=step, deflection=deflection,
                                  name=name, doc=doc)


def make_centroidal_axis(source, step=0.0, distance_threshold=0.0, eps=0.001, break_angle=30.0,
                         deflection=0.0, frame="Part", name="CentroidalAxis", doc=None):
    """Adds a parametric ``CentroidalAxis`` object (FreeCAD only) over the document object
    ``source`` and returns it; recompute the document to compute it. 0 for ``step``,
    ``distance_threshold`` or ``deflection`` means derived from the part; ``frame`` "Part" lines
    the +-X and +-Y it marches along up with the part's sides, "Document" keeps the document's.
    See ``MultiAxisSlicer.features``."""
    from . import features

    return features.make_centroidal_axis(source, step=step, distance_threshold=distance_threshold,
                                         eps=eps, break_angle=break_angle, deflection=deflection,
                                         frame=frame, name=name, doc=doc)


def make_decomposition(source, axis=None, face_angle=10.0, section_plane_fallback=True,
                       deflection=0.0, name="Decomposition", doc=None, min_component_height=0.0,
                       max_tilt=100.0, keep_branches=(), square_branches=()):
    """Adds a parametric ``Decomposition`` object (FreeCAD only) splitting the document object
    ``source`` (optionally following the ``CentroidalAxis`` object ``axis``, whose parameters are
    then used), computes it and adds one ``Component`` object per sub-component (labelled
    Component001, ... in tree order). Returns the Decomposition object. ``keep_branches``: axis
    branches left in their fathers (its KeepBranches; ``features.keep_unreachable_branches()``
    sets those whose own layers a Layers object's nozzle cannot reach); ``square_branches``: axis
    branches cut square to their directions (its SquareBranches; set there where the cuts turned
    square to their lines leave the nozzle no way). See ``MultiAxisSlicer.features``."""
    from . import features

    return features.make_decomposition(source, axis=axis, face_angle=face_angle,
                                       section_plane_fallback=section_plane_fallback,
                                       deflection=deflection, name=name, doc=doc,
                                       min_component_height=min_component_height,
                                       max_tilt=max_tilt, keep_branches=keep_branches,
                                       square_branches=square_branches)


def make_slice(part, deflection=0.0, show_travel=False, name="Layers", toolpath_name="Toolpath",
               doc=None, **params):
    """Adds a parametric ``Layers`` object (FreeCAD only) slicing ``part`` into adaptive multi-axis
    layers, and a ``Toolpath`` object showing the bead paths planned in them; returns (layers,
    toolpath). Recompute the document to compute them. ``part`` is a ``Decomposition`` object
    (its part sliced component by component) or a closed mesh object (``Mesh::Feature``, split at
    section planes as ``slice()`` splits a mesh), or a ``CentroidalAxis`` object over such a mesh
    (whose parameters the mesh's axis then takes). ``params`` are ``slice()``'s slicing parameters
    (min_layer, max_layer, bead_width, infill, ...), checked before anything is added. See
    ``MultiAxisSlicer.features``."""
    from . import features

    return features.make_slice(part, deflection=deflection, show_travel=show_travel, name=name,
                               toolpath_name=toolpath_name, doc=doc, **params)


def make_machine_program(layers, name="MachineProgram", doc=None, **machine):
    """Adds a parametric ``MachineProgram`` object (FreeCAD only) writing the 5-axis G-code that
    deposits a ``Layers`` (or ``Toolpath``) object's layers; returns it. Recompute the document to
    compute it; ``features.export_gcode(obj, path)`` writes the program. ``machine`` are
    ``gcode()``'s machine parameters (a_min, a_max, feed, clearance, ...), their names and types
    checked before anything is added. See ``MultiAxisSlicer.features``."""
    from . import features

    return features.make_machine_program(layers, name=name, doc=doc, **machine)


def make_build_preview(layers, step=0, show_nozzle=True, show_paths=True, show_plate=True,
                       name="BuildPreview", doc=None):
    """Adds a parametric ``BuildPreview`` object (FreeCAD only) showing the build of a ``Layers``
    (or ``Toolpath``) object after ``step`` steps of its deposition sequence (0: all of them): the
    layers deposited so far, the step's in its own colour with its deposit paths, the nozzle at
    the step's layer along its tool axis, and the build plate; returns it. Recompute the document
    to compute it; set its ``Step`` and recompute to step through the build. See
    ``MultiAxisSlicer.features``."""
    from . import features

    return features.make_build_preview(layers, step=step, show_nozzle=show_nozzle,
                                       show_paths=show_paths, show_plate=show_plate, name=name,
                                       doc=doc)


# The centroidal axis, the decomposition and the slicing (after the helpers above, which they use).
from .progress import Cancelled  # noqa: E402
from .axis import AxisBranch, AxisLink, AxisNode, CentroidalAxis, centroidal_axis  # noqa: E402
from .decompose import Component, Decomposition, decompose  # noqa: E402
from .slicing import (SLICE_DEFAULTS, Collision, FilledHole, Layer, SliceResult,  # noqa: E402
                      ToolPath, slice)  # noqa: A001
from .gcode import MACHINE_DEFAULTS, GcodeProgram, gcode  # noqa: E402
