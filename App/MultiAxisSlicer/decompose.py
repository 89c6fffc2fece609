# SPDX-License-Identifier: LGPL-2.1-or-later
"""Decomposition of a solid into sub-components (Ruan et al., Sec. 4.1), for scripts and FreeCAD.

The part is split where its centroidal axis turns or branches; every sub-component is built from
its base face along its own build direction, after its father. The engine's header
App/include/mas/Decompose.hpp explains the reading of the paper it follows. Re-exported by the
package::

    import MultiAxisSlicer as mas
    parts = mas.decompose(App.ActiveDocument.Part, step=2.5)
    for c in parts:
        print(c.parent, c.rule, c.build_direction, c.volume)      # mm^3
        Part.show(c.shape)
"""

import numbers

from . import _FreeCAD, _as_list, _as_vector, _model, _require_engine
from . import progress as _progress
from .axis import CentroidalAxis, _number, centroidal_axis

__all__ = ["Component", "Decomposition", "decompose"]

# Axis parameters of decompose() and their defaults: with a given axis, none may be set.
_AXIS_DEFAULTS = {"step": None, "distance_threshold": None, "eps": 0.001, "break_angle": 30.0,
                  "base_z": None, "deflection": None, "frame": None}


def _part_shape(brep):
    """A Part.Shape from BREP text (FreeCAD only)."""
    import Part

    shape = Part.Shape()
    shape.importBrepFromString(brep)
    return shape


def _angle(value, name, upper):
    angle = _number(value, name, "degrees")
    if not (0.0 <= angle < upper):  # also NaN
        raise ValueError("{} must be in [0, {}) degrees, got {}".format(name, upper, angle))
    return angle


def _max_tilt(value):
    """The machine's reach, checked as the engine does (decomposing and slicing alike)."""
    tilt = _number(value, "max_tilt", "degrees")
    if not (90.0 <= tilt <= 180.0):  # also NaN
        raise ValueError("max_tilt must be in [90, 180] degrees, got {}".format(tilt))
    return tilt


def _checked_params(face_angle=10.0, concave_angle=1.0, projection_tolerance=0.01,
                    section_plane_fallback=True, min_component_height=0.0, max_tilt=100.0,
                    keep_branches=(), square_branches=(), turn_cuts=True):
    """decompose()'s decomposition parameters, checked (TypeError / ValueError naming the bad one),
    as a Decomposition's ``params``."""
    face_angle_deg = _angle(face_angle, "face_angle", 90.0)
    concave_angle_deg = _angle(concave_angle, "concave_angle", 180.0)
    tolerance_mm = _number(projection_tolerance, "projection_tolerance", "millimetres")
    if not (0.0 <= tolerance_mm < float("inf")):
        raise ValueError("projection_tolerance must be a finite, non-negative number of "
                         "millimetres, got {}".format(tolerance_mm))
    min_height_mm = _number(min_component_height, "min_component_height", "millimetres")
    if not (0.0 <= min_height_mm < float("inf")):
        raise ValueError("min_component_height must be a finite, non-negative number of "
                         "millimetres, got {}".format(min_height_mm))
    max_tilt_deg = _max_tilt(max_tilt)
    keep = _branch_list(keep_branches)
    square = _branch_list(square_branches, "square_branches")
    if not isinstance(turn_cuts, (bool, numbers.Integral)):
        raise TypeError("turn_cuts must be True or False, got {!r}".format(turn_cuts))
    if not isinstance(section_plane_fallback, (bool, numbers.Integral)):
        raise TypeError("section_plane_fallback must be True or False, got {!r}".format(
            section_plane_fallback))
    return {"face_angle_deg": face_angle_deg, "concave_angle_deg": concave_angle_deg,
            "projection_tolerance_mm": tolerance_mm,
            "section_plane_fallback": bool(section_plane_fallback),
            "min_component_height_mm": min_height_mm, "max_tilt_deg": max_tilt_deg,
            "keep_branches": keep, "square_branches": square, "turn_cuts": bool(turn_cuts)}


def _engine_args(params):
    """A Decomposition's ``params`` as the engine's decompose() takes them."""
    return {"face_angle": params["face_angle_deg"], "concave_angle": params["concave_angle_deg"],
            "projection_tolerance": params["projection_tolerance_mm"],
            "section_plane_fallback": params["section_plane_fallback"],
            "min_component_height": params["min_component_height_mm"],
            "max_tilt": params["max_tilt_deg"], "keep_branches": list(params["keep_branches"]),
            "square_branches": list(params["square_branches"]), "turn_cuts": params["turn_cuts"]}


def _branch_list(value, name="keep_branches"):
    """keep_branches (or the parameter `name`) as a sorted tuple of distinct ints (which exist is
    the engine's to say)."""
    if isinstance(value, (str, bytes)) or not hasattr(value, "__iter__"):
        raise TypeError("{} must be a sequence of axis branch indices, got {!r}".format(
            name, value))
    out = set()
    for b in value:
        if isinstance(b, bool) or not isinstance(b, numbers.Integral):
            raise TypeError("{} must hold axis branch indices (ints), got {!r}".format(name, b))
        out.add(int(b))
    return tuple(sorted(out))


class Component:
    """One sub-component: a closed solid built from its base face along its build direction (the
    root, on the build plate, may be several: a portal's two legs without its lintel).

    Attributes:
      * ``shape``: the solid, a ``Part.Solid`` when FreeCAD is importable (for a root standing on
        several feet, a ``Part.Compound`` of its solids), else the engine ``Shape``; ``brep``: its
        BREP text (``Part.Shape().importBrepFromString()`` reads it).
      * ``parent``: index of the father component in the decomposition, -1 for the root.
      * ``build_direction``: unit vector the component is deposited along (the reverse of its base
        face's outward normal; +Z for the root).
      * ``base_face``: the planar face it was cut at (a ``Part.Face``; the engine ``Shape`` without
        FreeCAD), None for the root, which stands on the build plate. ``base_face_brep``: its BREP
        text or None.
      * ``base_origin`` (mm): the base face's centroid (the root: the centre of the bottom of its
        bounding box); ``base_normal``: its outward unit normal (= -build_direction).
      * ``branch``: the axis branch that made it (0 for the root); ``break_link``: that branch's
        first link (the break, turn or split), -1 for the root.
      * ``rule``: how it was cut: "root", "planar_face" (a face meeting the paper's three criteria),
        "section_plane" (the fallback: the plane where the branch's march started) or "bridge"
        (cut at a bridge's flat underside where two tracks merge, built along the diagonal half
        way between the march and the way across the gap: the README's bridges);
        ``turned``: True where that plane was turned square to the branch's own line, which runs
        between the six directions (a blade on a hub 33 degrees off -X), not to its direction.
      * ``volume``: mm³.
    Vectors are FreeCAD.Vector when FreeCAD is importable, else tuples.
    """

    __slots__ = ("parent", "branch", "break_link", "rule", "turned", "volume", "has_base_face",
                 "_solid", "_face", "_build_direction", "_base_origin", "_base_normal", "_shape",
                 "_base_face")

    def __init__(self, data):
        self._solid = data["solid"]
        self._face = data["base_face"]
        self.parent = data["parent"]
        self.has_base_face = data["has_base_face"]
        self._build_direction = data["build_direction"]
        self._base_origin = data["base_origin"]
        self._base_normal = data["base_normal"]
        self.branch = data["branch"]
        self.break_link = data["break_link"]
        self.rule = data["rule"]
        self.turned = bool(data["turned"])
        self.volume = data["volume_mm3"]
        self._shape = None
        self._base_face = None

    @property
    def brep(self):
        return self._solid.to_brep_string()

    @property
    def base_face_brep(self):
        return self._face.to_brep_string() if self._face is not None else None

    @property
    def shape(self):
        if _FreeCAD is None:
            return self._solid
        if self._shape is None:
            import Part

            shape = _part_shape(self.brep)
            solids = shape.Solids
            self._shape = Part.Compound(solids) if len(solids) > 1 else Part.Solid(shape)
        return self._shape

    @property
    def base_face(self):
        if self._face is None:
            return None
        if _FreeCAD is None:
            return self._face
        if self._base_face is None:
            import Part

            self._base_face = Part.Face(_part_shape(self.base_face_brep))
        return self._base_face

    @property
    def build_direction(self):
        return _as_vector(self._build_direction)

    @property
    def base_origin(self):
        return _as_vector(self._base_origin)

    @property
    def base_normal(self):
        return _as_vector(self._base_normal)

    def to_dict(self):
        """JSON-ready, as ``multiaxis-slicer decompose --json`` writes a component."""
        return {
            "parent": self.parent,
            "build_direction": _as_list(self._build_direction),
            "has_base_face": self.has_base_face,
            "base_origin": _as_list(self._base_origin),
            "base_normal": _as_list(self._base_normal),
            "branch": self.branch,
            "break_link": self.break_link,
            "rule": self.rule,
            "turned": self.turned,
            "volume_mm3": self.volume,
        }

    def __repr__(self):
        return "<MultiAxisSlicer.Component parent={} rule={} build_direction={} volume={:.6g} " \
               "mm3>".format(self.parent, self.rule,
                             tuple(round(c, 6) for c in self._build_direction), self.volume)


class Decomposition:
    """The sub-components of a part in tree order (a father before its children; [0] is the root).

    A sequence: ``len(d)``, ``d[i]``, ``for c in d``. Attributes: ``components`` (the list of
    ``Component``), ``axis`` (the ``CentroidalAxis`` it followed), ``part_volume`` (mm³, the
    part's; the components' volumes add up to it), ``params`` (the decomposition's parameters:
    face_angle_deg, concave_angle_deg, projection_tolerance_mm, section_plane_fallback,
    min_component_height_mm, max_tilt_deg, keep_branches, square_branches, turn_cuts),
    ``notes`` (one line per axis branch that asked for a cut and got none: why, and which
    component kept its material), ``kept_branches`` (the branches of keep_branches that stayed in
    their fathers so) and ``square_branches`` (as asked): ``decompose(...,
    keep_branches=d.kept_branches, square_branches=d.square_branches)`` gives this decomposition
    again. ``slice()`` asks for both where the nozzle could not reach some layers: it cuts square
    to their directions the branches whose cuts it had turned square to their lines, and keeps the
    others.
    """

    def __init__(self, data, axis, params):
        self.components = [Component(c) for c in data["components"]]
        self.part_volume = data["part_volume_mm3"]
        self.notes = list(data["notes"])
        self.kept_branches = list(data["kept_branches"])
        self.square_branches = list(data["square_branches"])
        self.axis = axis
        self.params = params

    def __len__(self):
        return len(self.components)

    def __getitem__(self, index):
        return self.components[index]

    def __iter__(self):
        return iter(self.components)

    def children(self, index):
        """Indices of the components whose father is component ``index``."""
        return [i for i, c in enumerate(self.components) if c.parent == index]

    def to_dict(self):
        """JSON-ready plain data in the layout of ``multiaxis-slicer decompose FILE --json``
        (without its "file"): kind, part_volume_mm3, axis (step_mm, nodes, branches), components
        [{parent, build_direction, has_base_face, base_origin, base_normal, branch, break_link,
        rule, turned, volume_mm3}], notes."""
        return {
            "kind": "solid",
            "part_volume_mm3": self.part_volume,
            "axis": {"step_mm": self.axis.params["step_mm"], "nodes": len(self.axis.nodes),
                     "branches": len(self.axis.branches)},
            "components": [c.to_dict() for c in self.components],
            "notes": list(self.notes),
        }

    def __repr__(self):
        return "<MultiAxisSlicer.Decomposition components={} part_volume={:.6g} mm3>".format(
            len(self.components), self.part_volume)


def decompose(shape, axis=None, step=None, distance_threshold=None, break_angle=30.0,
              deflection=None, face_angle=10.0, concave_angle=1.0, section_plane_fallback=True,
              eps=0.001, base_z=None, projection_tolerance=0.01, min_component_height=0.0,
              max_tilt=100.0, keep_branches=(), square_branches=(), turn_cuts=True, frame=None,
              progress=None):
    """Splits one solid into sub-components where its centroidal axis turns or branches.

    ``shape``: a ``Part.Shape`` holding exactly one closed solid (or solids sharing material, fused
    into one: see ``centroidal_axis``), a document object with such a Shape, a .step/.stp,
    .iges/.igs or .brep/.brp file, or an engine Shape. A mesh cannot be split into solids:
    ``Mesh.Mesh``, mesh objects and .stl/.off files raise TypeError
    (``slice()`` splits a mesh into mesh pieces as it slices it, see the README's "Meshes").

    ``axis``: the ``CentroidalAxis`` of this very shape (``centroidal_axis(shape, ...)``, also of a
    mesh of it). None: computed here with ``step``, ``distance_threshold``, ``eps``,
    ``break_angle``, ``base_z``, ``deflection`` and ``frame``, which mean what they mean for
    ``centroidal_axis()``; with an axis given they must stay unset (ValueError otherwise). An axis
    marched in a turned frame is decomposed in that frame (the part turned into it, the
    components turned back): its branches' directions, its cuts and its children's build
    directions are the frame's.

    Decomposition parameters (angles in degrees, lengths in mm; FreeCAD Quantities accepted):
      * ``face_angle``: a splitting face's normal is within this of the branch's direction
        (criterion 1; default 10, in [0, 90)).
      * ``concave_angle``: an edge is concave when the interior angle exceeds 180 degrees by more
        than this (criterion 2; default 1, in [0, 180)).
      * ``section_plane_fallback``: with no face meeting the criteria, cut at the plane where the
        branch's march started (default True); False leaves that material in the father.
      * ``projection_tolerance``: slack on Eq. 5's interval (criterion 3; default 0.01 mm).
      * ``min_component_height``: a child must reach at least this far past its splitting plane,
        and at least one axis step; a thinner piece stays in its father (default 0 mm: the step).
        ``slice()`` passes its ``min_layer``, so that every component fits a layer.
      * ``max_tilt``: no child is built further than this from the build plate's +Z (default
        100, in [90, 180]): the machine's reach. A branch marching further (straight down) is
        not cut, and a face whose child would tilt further is no splitting face. ``slice()``
        passes its own ``max_tilt``.
      * ``keep_branches``: indices of axis branches (``axis.branches``, not the root's, 0) to
        leave in their fathers' components whatever they qualify for, each with a note (default
        none); their own sub-branches are cut from there as usual. ``slice()`` keeps so the
        branches whose own components' layers the nozzle could not reach.
      * ``square_branches``: indices of axis branches cut, where a section plane cuts them, square
        to their directions (+-X, +-Y, +-Z), never turned square to their own lines (default
        none). ``slice()`` asks for this where the turned cuts leave the nozzle no way.
      * ``turn_cuts``: False turns no cut square to a branch's line, as if every branch were in
        ``square_branches`` (default True; a FreeCAD document saved before the turned cuts keeps
        False).

    ``progress``: None or ``progress(fraction, stage)``, reported branch by branch; an exception it
    raises (``Cancelled``) stops the work and is raised again (see ``MultiAxisSlicer.progress``).

    Returns a ``Decomposition``. Raises TypeError for a mesh, None or another type (or
    keep_branches or square_branches not of ints); ValueError for a parameter out of range;
    EngineError (with ``code``) not_a_solid (a face, a shell), multiple_solids, empty_input,
    read_failed, invalid_argument (an axis of another part, a malformed axis, a kept or squared
    branch the axis lacks or its root), geometry_failure. Nothing the caller passed is modified.
    """
    params = _checked_params(face_angle, concave_angle, projection_tolerance,
                             section_plane_fallback, min_component_height, max_tilt, keep_branches,
                             square_branches, turn_cuts)
    _progress.check(progress)
    axis_params = {"step": step, "distance_threshold": distance_threshold, "eps": eps,
                   "break_angle": break_angle, "base_z": base_z, "deflection": deflection,
                   "frame": frame}
    if axis is not None:
        if not isinstance(axis, CentroidalAxis):
            raise TypeError("axis must be a CentroidalAxis (from centroidal_axis()) or None, got "
                            "{}".format(type(axis).__name__))
        changed = sorted(k for k, v in axis_params.items() if v != _AXIS_DEFAULTS[k])
        if changed:
            raise ValueError("decompose: an axis is given, so the axis parameters ({}) would be "
                             "ignored; pass one or the other".format(", ".join(changed)))
    eng = _require_engine()
    kind, part, what = _model(shape)
    if kind != "solid":
        mesh = "a mesh" if what in ("the mesh", "mesh") else "{}, a mesh,".format(what)
        raise TypeError("decompose() splits a BREP solid (Part.Shape, STEP, IGES or BREP file); "
                        "{} cannot be split into solids (slice() splits a mesh into mesh pieces "
                        "as it slices it)".format(mesh))
    solid = part.single_solid(what)
    if axis is None:
        axis = centroidal_axis(solid, **axis_params)
    data = eng.decompose(solid, axis._engine_dict(), progress=progress, **_engine_args(params))
    return Decomposition(data, axis, params)
