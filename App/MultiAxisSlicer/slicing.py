# SPDX-License-Identifier: LGPL-2.1-or-later
"""Adaptive multi-axis slicing into "3-D" layers and the deposition paths in every layer (Ruan et
al., Sec. 4.2), for scripts and FreeCAD.

Every sub-component is sliced from its base face along its own centroidal axis; a layer's plane
may tilt against the one below it, its thickness then varying across it. The engine's headers
App/include/mas/Slicing.hpp and App/include/mas/Paths.hpp explain the definitions (thickness,
volumetric difference, support) and the reading of the paper. Re-exported by the package::

    import MultiAxisSlicer as mas
    result = mas.slice(App.ActiveDocument.Part, min_layer=0.5, max_layer=2.0, bead_width=1.2)
    for layer in result.layers:
        print(layer.component, layer.normal, layer.min_thickness, layer.max_thickness)
    for path in result.paths(0):
        print(path.kind, path.deposit, len(path.points))
"""

import math
import numbers

from . import _as_list, _as_vector, _model, _require_engine
from . import progress as _progress
from .axis import CentroidalAxis, _number, centroidal_axis
from .decompose import Decomposition, _checked_params, _engine_args, _max_tilt

__all__ = ["Layer", "ToolPath", "FilledHole", "SliceResult", "slice", "SLICE_DEFAULTS"]

# The slicing parameters slice() takes, with their defaults (lengths in mm, angles in degrees).
SLICE_DEFAULTS = {
    "min_layer": 0.5,
    "max_layer": 2.0,
    "max_volume_difference": 0.1,
    "eps_angle": 1.0,
    "overhang_angle": 45.0,
    "max_tilt": 100.0,
    "volume_samples": 4,
    "strict": False,
    "bead_width": 1.0,
    "overlap": 0.15,
    "contour_count": 2,
    "infill": "raster",
    "raster_angle": 0.0,
    "raster_angle_step": 90.0,
    "min_feature": 0.0,
    "measure_coverage": False,
    "fill_holes": 0.0,
    "split_mesh": True,
    "avoid_collisions": True,
    "nozzle_standoff": 10.0,
    "nozzle_tip_diameter": 10.0,
    "nozzle_cone_angle": 30.0,
    "nozzle_body_diameter": 50.0,
    "nozzle_body_length": 200.0,
    "nozzle_margin": 2.0,
    "check_plate": True,
    "nozzle_max_lean": 30.0,
}

_AXIS_KEYS = ("step", "distance_threshold", "eps", "break_angle", "base_z", "frame")


class ToolPath:
    """One polyline of a layer: ``kind`` ("travel", "contour", "infill" or "centre_line"),
    ``deposit`` (False for travel), ``region`` (index into the layer's regions, -1 for travel),
    ``points`` (FreeCAD.Vector on the layer's plane; a closed loop repeats its first point),
    ``thickness`` (deposit thickness under each point, mm) and ``tool_axis`` (the same for every
    point: the layer's normal, or the nozzle leaned from it where coaxial it would collide; see
    ``SliceResult.tool_axis``)."""

    __slots__ = ("kind", "region", "_points", "thickness", "_axis")

    def __init__(self, data, axis):
        self.kind = data["kind"]
        self.region = data["region"]
        self._points = data["points"]
        self.thickness = list(data["thickness_mm"])
        self._axis = axis

    @property
    def deposit(self):
        return self.kind != "travel"

    @property
    def points(self):
        return [_as_vector(p) for p in self._points]

    @property
    def tool_axis(self):
        return _as_vector(self._axis)

    def length(self):
        """Length of the polyline, mm."""
        return sum(math.dist(a, b) for a, b in zip(self._points, self._points[1:]))

    def to_dict(self):
        return {"kind": self.kind, "region": self.region,
                "points": [_as_list(p) for p in self._points],
                "thickness_mm": list(self.thickness)}

    def __repr__(self):
        return "<MultiAxisSlicer.ToolPath {} points={} length={:.6g} mm>".format(
            self.kind, len(self._points), self.length())


def _regions_as_vectors(regions):
    return [{"outer": [_as_vector(p) for p in r["outer"]],
             "holes": [[_as_vector(p) for p in h] for h in r["holes"]]} for r in regions]


def _regions_as_lists(regions):
    return [{"outer": [_as_list(p) for p in r["outer"]],
             "holes": [[_as_list(p) for p in h] for h in r["holes"]]} for r in regions]


class Layer:
    """One "3-D" layer: what is deposited between its lower plane and its plane.

    Attributes: ``component`` (index of its sub-component), ``origin`` and ``normal`` (its plane,
    the layer's top; the tool axis unless the nozzle leans, ``SliceResult.tool_axis``),
    ``lower_origin`` and ``lower_normal`` (the plane
    it is deposited on), ``regions`` (list of dicts with ``outer`` and ``holes``: loops as lists of
    FreeCAD.Vector on the plane), ``area`` (mm²), ``min_thickness`` and ``max_thickness`` (mm, over
    its region), ``volume`` (mm³ deposited), ``material_volume`` (mm³ of the part between the
    planes), ``volume_difference`` (the volume of the symmetric difference of the two over the
    deposited volume, Eq. 9's VolDiff), ``meets_volume_difference``, ``unsupported_area`` (mm² of
    its footprint outside the layer below grown by the overhang allowance), ``unsupported_regions``
    (where that is: regions like ``regions``, on the lower plane, empty when the layer is
    supported), ``outline_length`` (mm, every loop of ``regions``: times the deflection, the strip
    along them that a layer's mesh sections can show unsupported on a part with nothing hanging),
    ``axis_node`` (the centroidal-axis node it follows) and ``axis_point``. Vectors are
    FreeCAD.Vector when FreeCAD is importable, else tuples.
    """

    def __init__(self, data):
        self._data = data
        self.component = data["component"]
        self.area = data["area_mm2"]
        self.min_thickness = data["min_thickness_mm"]
        self.max_thickness = data["max_thickness_mm"]
        self.volume = data["volume_mm3"]
        self.material_volume = data["material_volume_mm3"]
        self.volume_difference = data["volume_difference"]
        self.meets_volume_difference = data["meets_volume_difference"]
        self.unsupported_area = data["unsupported_area_mm2"]
        self.outline_length = data["outline_length_mm"]
        self.axis_node = data["axis_node"]

    origin = property(lambda self: _as_vector(self._data["origin"]))
    normal = property(lambda self: _as_vector(self._data["normal"]))
    lower_origin = property(lambda self: _as_vector(self._data["lower_origin"]))
    lower_normal = property(lambda self: _as_vector(self._data["lower_normal"]))
    axis_point = property(lambda self: _as_vector(self._data["axis_point"]))

    @property
    def regions(self):
        return _regions_as_vectors(self._data["regions"])

    @property
    def unsupported_regions(self):
        return _regions_as_vectors(self._data["unsupported_regions"])

    def loops(self):
        """Every loop of every region (outers and holes) as lists of FreeCAD.Vector."""
        out = []
        for r in self.regions:
            out.append(r["outer"])
            out.extend(r["holes"])
        return out

    def to_dict(self):
        d = self._data
        return {
            "component": d["component"],
            "origin": _as_list(d["origin"]),
            "normal": _as_list(d["normal"]),
            "lower_origin": _as_list(d["lower_origin"]),
            "lower_normal": _as_list(d["lower_normal"]),
            "regions": _regions_as_lists(d["regions"]),
            "area_mm2": d["area_mm2"],
            "min_thickness_mm": d["min_thickness_mm"],
            "max_thickness_mm": d["max_thickness_mm"],
            "volume_mm3": d["volume_mm3"],
            "material_volume_mm3": d["material_volume_mm3"],
            "volume_difference": d["volume_difference"],
            "meets_volume_difference": d["meets_volume_difference"],
            "unsupported_area_mm2": d["unsupported_area_mm2"],
            "unsupported_regions": _regions_as_lists(d["unsupported_regions"]),
            "outline_length_mm": d["outline_length_mm"],
            "axis_node": d["axis_node"],
            "axis_point": _as_list(d["axis_point"]),
        }

    def __repr__(self):
        return ("<MultiAxisSlicer.Layer component={} normal={} thickness=[{:.4g}, {:.4g}] mm "
                "volume_difference={:.3g}>").format(
                    self.component, tuple(round(c, 6) for c in self._data["normal"]),
                    self.min_thickness, self.max_thickness, self.volume_difference)


class FilledHole:
    """A round hole deposited solid, to be drilled afterwards (``fill_holes``): ``component``
    (index of its sub-component), ``centre`` (the middle of its extent along its axis) and
    ``axis`` (unit, along the build direction where not perpendicular to it) as FreeCAD.Vector,
    ``diameter`` and ``length`` (its extent along the axis) in mm. The material the fills add is
    the result's ``stats["filled_volume_mm3"]``."""

    __slots__ = ("_data",)

    def __init__(self, data):
        self._data = data

    component = property(lambda self: self._data["component"])
    centre = property(lambda self: _as_vector(self._data["centre"]))
    axis = property(lambda self: _as_vector(self._data["axis"]))
    diameter = property(lambda self: self._data["diameter_mm"])
    length = property(lambda self: self._data["length_mm"])

    def to_dict(self):
        d = self._data
        return {"component": d["component"], "centre": _as_list(d["centre"]),
                "axis": _as_list(d["axis"]), "diameter_mm": d["diameter_mm"],
                "length_mm": d["length_mm"]}

    def __repr__(self):
        return "<MultiAxisSlicer.FilledHole component={} diameter={:.6g} mm at {}>".format(
            self.component, self.diameter, tuple(round(c, 6) for c in self._data["centre"]))


class Collision:
    """A layer whose deposition has the nozzle meet what is already deposited (the paper's Eq. 10,
    which no build order avoided): ``layer`` (its index), ``obstacle_layer`` (the deposited
    layer that comes deepest into the nozzle, -1 for the build plate), ``obstacle`` (that
    layer's point deepest in the nozzle, or nearest it when none is inside; on the plate, below
    the nozzle's lowest point) and ``nozzle_at`` (the deposit point the nozzle stands over then)
    as FreeCAD.Vector."""

    __slots__ = ("_data",)

    def __init__(self, data):
        self._data = data

    layer = property(lambda self: self._data["layer"])
    obstacle_layer = property(lambda self: self._data["obstacle_layer"])
    nozzle_at = property(lambda self: _as_vector(self._data["nozzle_at"]))
    obstacle = property(lambda self: _as_vector(self._data["obstacle"]))

    def to_dict(self):
        d = self._data
        return {"layer": d["layer"], "obstacle_layer": d["obstacle_layer"],
                "nozzle_at": _as_list(d["nozzle_at"]), "obstacle": _as_list(d["obstacle"])}

    def __repr__(self):
        return "<MultiAxisSlicer.Collision layer {} meets {}>".format(
            self.layer, "the plate" if self.obstacle_layer < 0 else
            "layer {}".format(self.obstacle_layer))


class SliceResult:
    """The layers of every sub-component and the paths in every layer.

    Attributes: ``layers`` (list of ``Layer``: component by component in build order, each bottom
    to top), ``build_order`` (the component indices in the order they start: the root, then each
    time the component whose first layer what is built leaves least unsupported), ``sequence``
    (the layer indices in the order they are deposited: a component is left for another where
    going on would put its layers in the nozzle's way to the other's), ``collisions``
    (``Collision`` list: the layers whose nozzle still meets what is deposited, even leaned),
    ``components`` (per sub-component, by index: first_layer, layer_count, guide_nodes,
    volume_mm3), ``stats`` (dict: layer_count, min_thickness_mm, max_thickness_mm,
    part_volume_mm3, deposited_volume_mm3, material_volume_mm3, max_volume_difference,
    layers_over_volume_difference, worst_unsupported_area_mm2, worst_unsupported_layer,
    deposit_length_mm, travel_length_mm, centre_line_passes, unfilled_features, colliding_layers,
    component_switches, leaned_layers, filled_holes, filled_volume_mm3), ``filled_holes`` (``FilledHole`` list:
    the holes deposited solid, to drill), ``notes`` (when ``slice()`` decomposed the part, the
    decomposition's notes first, each "decomposition: ...", saying which branches got no
    component of their own and why; then one string per hole that qualified for filling and
    stayed open, saying why), ``params`` (the slicing parameters used), ``axis`` (the ``CentroidalAxis``),
    ``decomposition`` (the ``Decomposition``, None for a mesh), ``kind`` ("solid" or "mesh"),
    ``plate`` (the build plate the part stands on and the nozzle was checked against: (origin,
    normal) as ``FreeCAD.Vector``, the normal up; None for a result made without it).
    """

    def __init__(self, data, params, axis, decomposition, kind):
        self._data = data
        self.layers = [Layer(d) for d in data["layers"]]
        self.components = [dict(c) for c in data["components"]]
        self.build_order = list(data["build_order"])
        self.sequence = list(data["sequence"])
        self.collisions = [Collision(c) for c in data["collisions"]]
        self.stats = dict(data["stats"])
        self.filled_holes = [FilledHole(h) for h in data["filled_holes"]]
        self.notes = list(data["notes"])
        self.params = dict(params)
        self.axis = axis
        self.decomposition = decomposition
        self.kind = kind
        self.plate = ((_as_vector(data["plate_origin"]), _as_vector(data["plate_normal"]))
                      if "plate_origin" in data else None)

    def __len__(self):
        return len(self.layers)

    def paths(self, layer_index):
        """The paths of layer ``layer_index`` in deposition order (``ToolPath``): a travel move
        before every deposit path, the first one from where the layer before it in ``sequence``
        ended."""
        d = self._data["layers"][layer_index]
        return [ToolPath(p, d["tool_axis"]) for p in d["paths"]]

    def tool_axis(self, layer_index):
        """The tool axis layer ``layer_index`` is deposited along: its normal, or, where the
        coaxial nozzle would meet the plate or what is deposited before it, the nozzle leaned
        from it by the least of 5, 10, ... degrees up to ``nozzle_max_lean`` that clears (the
        layer and its paths stay as they are)."""
        return _as_vector(self._data["layers"][layer_index]["tool_axis"])

    def leaned_layers(self):
        """The indices of the layers whose tool axis leans from their normal."""
        return [i for i, d in enumerate(self._data["layers"])
                if _as_list(d["tool_axis"]) != _as_list(d["normal"])]

    def layer_report(self, layer_index):
        """Per-layer path facts: centre_line_regions (regions narrower than a bead, run as one
        centre line), unfilled (features too small for that: region, area_mm2, centroid),
        deposit_length_mm, travel_length_mm, uncovered_area_mm2 (-1 unless measure_coverage)."""
        d = self._data["layers"][layer_index]
        return {"centre_line_regions": list(d["centre_line_regions"]),
                "unfilled": [{"region": u["region"], "area_mm2": u["area_mm2"],
                              "centroid": _as_list(u["centroid"])} for u in d["unfilled"]],
                "deposit_length_mm": d["deposit_length_mm"],
                "travel_length_mm": d["travel_length_mm"],
                "uncovered_area_mm2": d["uncovered_area_mm2"]}

    def gcode(self, progress=None, **machine):
        """The 5-axis G-code program that deposits this result: ``MultiAxisSlicer.gcode(self,
        progress, **machine)`` (see there for the machine parameters)."""
        from .gcode import gcode
        return gcode(self, progress, **machine)

    def to_dict(self):
        """JSON-ready plain data in the layout of ``multiaxis-slicer slice FILE --json`` (without
        its "file"): kind, params, stats, filled_holes, notes, build_order, sequence, collisions,
        components, layers (each with its paths and report)."""
        layers = []
        for i, layer in enumerate(self.layers):
            d = layer.to_dict()
            d["tool_axis"] = _as_list(self._data["layers"][i]["tool_axis"])
            d["paths"] = [p.to_dict() for p in self.paths(i)]
            d.update(self.layer_report(i))
            layers.append(d)
        return {"kind": self.kind, "params": dict(self.params), "stats": dict(self.stats),
                "filled_holes": [h.to_dict() for h in self.filled_holes],
                "notes": list(self.notes), "build_order": list(self.build_order),
                "sequence": list(self.sequence),
                "collisions": [c.to_dict() for c in self.collisions],
                "components": [dict(c) for c in self.components], "layers": layers}

    def __repr__(self):
        s = self.stats
        return ("<MultiAxisSlicer.SliceResult layers={} components={} thickness=[{:.4g}, {:.4g}] "
                "mm deposited={:.6g} of {:.6g} mm3>").format(
                    s["layer_count"], len(self.components), s["min_thickness_mm"],
                    s["max_thickness_mm"], s["deposited_volume_mm3"], s["part_volume_mm3"])


def _slice_params(values):
    """Checks the slicing parameters (ValueError / TypeError naming the bad one) and returns them
    in the engine's names and units."""
    p = {}
    for name in ("min_layer", "max_layer", "min_feature", "bead_width", "fill_holes",
                 "nozzle_standoff", "nozzle_tip_diameter", "nozzle_body_diameter",
                 "nozzle_body_length", "nozzle_margin"):
        p[name] = _number(values[name], name, "millimetres")
    for name in ("eps_angle", "overhang_angle", "raster_angle", "raster_angle_step",
                 "nozzle_cone_angle", "nozzle_max_lean"):
        p[name] = _number(values[name], name, "degrees")
    p["max_volume_difference"] = _number(values["max_volume_difference"],
                                         "max_volume_difference", "a fraction")
    p["overlap"] = _number(values["overlap"], "overlap", "a fraction")
    for name in ("volume_samples", "contour_count"):
        v = values[name]
        if isinstance(v, bool) or not isinstance(v, numbers.Integral):
            raise TypeError("{} must be an integer, got {!r}".format(name, v))
        p[name] = int(v)
    for name in ("strict", "measure_coverage", "check_plate", "split_mesh", "avoid_collisions"):
        if not isinstance(values[name], (bool, numbers.Integral)):
            raise TypeError("{} must be True or False, got {!r}".format(name, values[name]))
        p[name] = bool(values[name])
    if values["infill"] not in ("raster", "contour", "none"):
        raise ValueError("infill must be 'raster', 'contour' or 'none', got {!r}".format(
            values["infill"]))
    p["infill"] = values["infill"]
    if not (0.0 < p["bead_width"] < math.inf):
        raise ValueError("bead_width must be a positive, finite number of millimetres, got "
                         "{}".format(p["bead_width"]))
    if not (0.0 < p["min_layer"] <= p["max_layer"] < math.inf):
        raise ValueError("need 0 < min_layer <= max_layer, got min_layer {} and max_layer {} "
                         "mm".format(p["min_layer"], p["max_layer"]))
    if not (p["fill_holes"] >= 0.0 and math.isfinite(p["fill_holes"])):
        raise ValueError("fill_holes must be a diameter of 0 or more millimetres, got {}".format(
            p["fill_holes"]))
    if not (p["max_volume_difference"] > 0.0):
        raise ValueError("max_volume_difference must be a positive fraction, got {}".format(
            p["max_volume_difference"]))
    p["max_tilt"] = _max_tilt(values["max_tilt"])
    _check_nozzle(p)
    return p


def _slice_decomposing(solid, axis, decomposition_params, p, progress):
    """slice() of an engine solid it decomposes: decomposed with ``decomposition_params`` (a
    Decomposition's ``params``, checked), sliced with ``p`` (checked), decomposed again keeping in
    their fathers the branches whose layers the nozzle cannot reach (unless p["avoid_collisions"]
    is false). The result's decomposition has the params that give it again."""
    data = _require_engine().slice_solid_part(solid, axis._engine_dict(),
                                               _engine_args(decomposition_params), p, progress)
    d = data.pop("decomposition")
    params = dict(decomposition_params, keep_branches=tuple(d["kept_branches"]),
                  square_branches=tuple(d["square_branches"]))
    return SliceResult(data, p, axis, Decomposition(d, axis, params), "solid")


def _check_mesh_params(caller, what, deflection, fill_holes):
    """ValueError, from `caller`, when a mesh (`what`) is given a deflection (true when one is set)
    or holes to fill: it is not tessellated, and has no BREP holes."""
    if deflection:
        raise ValueError("{}: {} is a mesh, sliced as it is; deflection applies to solids "
                         "only".format(caller, what))
    if fill_holes > 0.0:
        raise ValueError("{}: {} is a mesh, sliced as it is; fill_holes needs a solid, on whose "
                         "BREP holes are recognised".format(caller, what))


def _check_nozzle(p):
    """ValueError naming the first nozzle parameter out of its range (the engine's own rules,
    checked here before any decomposing)."""
    def check(ok, name, rule):
        if not ok:
            raise ValueError("{} {}, got {}".format(name, rule, p[name]))
    finite = math.isfinite
    check(p["nozzle_standoff"] >= 0.0 and finite(p["nozzle_standoff"]), "nozzle_standoff",
          "must be 0 or more millimetres")
    check(p["nozzle_tip_diameter"] > 0.0 and finite(p["nozzle_tip_diameter"]),
          "nozzle_tip_diameter", "must be a positive number of millimetres")
    check(p["nozzle_body_diameter"] >= p["nozzle_tip_diameter"] and
          finite(p["nozzle_body_diameter"]), "nozzle_body_diameter",
          "must be at least nozzle_tip_diameter ({} mm)".format(p["nozzle_tip_diameter"]))
    check(p["nozzle_body_length"] > 0.0 and finite(p["nozzle_body_length"]),
          "nozzle_body_length", "must be a positive number of millimetres")
    check(finite(p["nozzle_cone_angle"]) and
          (p["nozzle_body_diameter"] == p["nozzle_tip_diameter"] or
           0.0 < p["nozzle_cone_angle"] < 90.0), "nozzle_cone_angle",
          "(the cone's half-angle) must lie between 0 and 90 degrees")
    check(p["nozzle_margin"] > 0.0 and finite(p["nozzle_margin"]), "nozzle_margin",
          "must be a positive number of millimetres")
    # The check grows the nozzle by twice the margin: a tip closer would meet its own layer.
    check(p["nozzle_standoff"] >= 2.0 * p["nozzle_margin"], "nozzle_margin",
          "must be at most half nozzle_standoff ({} mm)".format(p["nozzle_standoff"]))
    check(0.0 <= p["nozzle_max_lean"] < 90.0, "nozzle_max_lean",
          "must lie within [0, 90) degrees")


def slice(shape, axis=None, components=None, deflection=None, progress=None,  # noqa: A001
          **params):
    """Slices a part into adaptive multi-axis "3-D" layers and plans the paths in every layer.

    ``shape``: a ``Part.Shape`` holding one closed solid (or solids sharing material, fused into
    one: see ``centroidal_axis``), a document object with one, a file path (.step/.stp,
    .iges/.igs, .brep/.brp; .stl/.off too) or a closed ``Mesh.Mesh``. A mesh, which
    has no faces to split at, stands on its lowest point and is split at section planes where its
    axis turns or branches (the engine's decompose_mesh, SlicePart.hpp), each piece closed with a
    cap, and at the flat facets under a bridge (a handle's bar, a portal's lintel: built along a
    diagonal, as a solid's; README, bridges). A solid is decomposed (``decompose()``) unless
    ``components`` are given. A mesh's piece, or a solid's sub-component decomposed here, some of
    whose layers the nozzle could not reach (they would meet the plate or what is deposited before
    them) is left in its father (where cuts were turned square to their branches' lines, those
    cuts are first made square to the branches' directions: all of them, or only those whose
    layers the nozzle could not reach where that slices better), and the part is split and sliced
    again, up to five times. A solid's sub-component with a layer hanging past a strip as wide
    as the deflection along its outline is then left in its father where that leaves fewer such
    layers or as many, the worst hanging less, and none more in the nozzle's way (up to three
    times, one at a time; README, *Sequence*). It is sliced as one component when that leaves
    fewer layers in the nozzle's way (``avoid_collisions=False``: the first split is kept, those
    layers listed in ``collisions``). The result's ``notes`` say which branches got no component
    and why; for a solid its ``decomposition`` is the one sliced (its ``kept_branches`` the
    branches so kept, its ``square_branches`` those so cut).

    ``axis``: the part's ``CentroidalAxis``; None: computed here (with ``step``,
    ``distance_threshold``, ``eps``, ``break_angle``, ``base_z``, ``frame`` from ``params`` when
    given; with an axis or components given they must stay unset, ValueError otherwise).
    ``components``: the part's ``Decomposition`` (from ``decompose(shape, axis)``); None: computed
    here with the axis. ``deflection``: chordal deflection for tessellating the components (mm;
    None: derived from the part's size).

    Slicing parameters (lengths in mm, angles in degrees; FreeCAD Quantities accepted), defaults in
    ``SLICE_DEFAULTS``:
      * ``min_layer``, ``max_layer``: bounds on the thickness anywhere on a layer (0.5, 2.0).
      * ``max_volume_difference``: Eq. 9's bound on a layer's volumetric difference, a fraction of
        its volume (0.1). A layer that cannot meet it even at min_layer (a dome's cap) is kept at
        min_layer and flagged; ``strict=True`` makes that an error.
      * ``eps_angle``: direction averaging stops below this angle (1).
      * ``overhang_angle``: the support allowance is the layer thickness x tan(this) (45).
      * ``max_tilt``: the most a layer's normal (the tool axis) tilts from the build plate's +Z,
        in [90, 180]: the machine's reach (100, the default machine's A from -100 to 50; 180: no
        limit). Where the axis turns further (a return bend's far leg), the layers stop there.
      * ``volume_samples``: sections per layer integrating VolDiff (4).
      * ``bead_width`` (1.0), ``overlap`` (fraction of a bead shared with its neighbour, 0.15),
        ``contour_count`` (2), ``infill`` ("raster", "contour" or "none"), ``raster_angle`` (0;
        in the part's frame, the axis' ``frame``: a layer square to Z rasters at this angle to
        the part's turned X) and ``raster_angle_step`` (90, added every layer), ``min_feature``
        (centre lines shorter than this are reported, not run; 0: half a bead),
        ``measure_coverage`` (also measure the area each layer's beads leave uncovered; False).
      * ``split_mesh``: a mesh is split as above (True); False slices it as one component, along
        its axis' first branch. A solid is always decomposed (``components`` gives the split).
      * ``avoid_collisions``: branches whose own layers the nozzle cannot reach, or a solid's
        whose layers hang where their fathers' would not, stay in their fathers, as above
        (True); False keeps the first split. Given ``components`` are sliced
        as they are.
      * ``fill_holes``: round holes up to this diameter whose axis leans past ``overhang_angle``
        off their sub-component's build direction, which a drill reaches from outside the part,
        are deposited solid, to be drilled afterwards: their ceilings would overhang (0: none; a
        solid's only). The result's ``filled_holes`` lists them, ``notes`` those left open. A
        split into sub-components that would cut such a hole along its length is not made where
        that leaves less unsupported: the branch stays in its father (README, *Holes to drill*).
      * The nozzle the build sequence keeps clear of what is deposited (the paper's Eq. 10): a
        cone tip ``nozzle_tip_diameter`` across (10) at ``nozzle_standoff`` above the deposit
        point (10), widening at ``nozzle_cone_angle`` (half-angle, 30) to a body
        ``nozzle_body_diameter`` across (50) and ``nozzle_body_length`` long (200), kept
        ``nozzle_margin`` away (2, at most half the standoff, at least 5e-4 of the part's
        bounding-box diagonal and a 1e-5th of the body's end's distance from the deposit point:
        the checks sample and step by it; else an EngineError); ``check_plate``: the build plate
        is an obstacle too (True). ``nozzle_max_lean`` (30): where a layer's coaxial nozzle
        would still meet the plate or what is deposited, its tool axis may lean this far from
        the layer's normal, by the least of 5, 10, ... degrees that clears, towards the plate's
        normal, away from the obstacle, or any other way round the normal every 22.5 degrees (0:
        always coaxial, as the paper).

    ``progress``: None or ``progress(fraction, stage)``, called now and then with the fraction of
    the whole done (decomposing, when done here, is the first fifth); an exception it raises
    (``Cancelled``) stops the work and is raised again (see ``MultiAxisSlicer.progress``).

    Returns a ``SliceResult``. Raises TypeError / ValueError for a bad parameter (naming it) and
    EngineError (with ``code``) for a part the engine cannot use or parameters no layer fits
    (invalid_argument), or strict and a layer over the bound (geometry_failure). Nothing the
    caller passed is modified.
    """
    axis_params = {k: params.pop(k) for k in _AXIS_KEYS if k in params}
    unknown = sorted(set(params) - set(SLICE_DEFAULTS))
    if unknown:
        raise TypeError("slice() got unknown parameter(s): {}".format(", ".join(unknown)))
    values = dict(SLICE_DEFAULTS)
    values.update(params)
    p = _slice_params(values)
    _progress.check(progress)
    if axis is not None and not isinstance(axis, CentroidalAxis):
        raise TypeError("axis must be a CentroidalAxis (from centroidal_axis()) or None, got "
                        "{}".format(type(axis).__name__))
    if components is not None and not isinstance(components, Decomposition):
        raise TypeError("components must be a Decomposition (from decompose()) or None, got "
                        "{}".format(type(components).__name__))
    if (axis is not None or components is not None) and axis_params:
        raise ValueError("slice: {} is given, so the axis parameters ({}) would be ignored; pass "
                         "one or the other".format("an axis" if axis is not None else
                                                   "a decomposition (which carries its axis)",
                                                   ", ".join(sorted(axis_params))))
    if components is not None and axis is not None and components.axis is not axis:
        raise ValueError("slice: the decomposition given follows another axis than the one given")
    if deflection is not None:
        d = _number(deflection, "deflection", "millimetres")
        if not (d > 0.0 and math.isfinite(d)):
            raise ValueError("deflection must be a positive number of millimetres, got {}".format(d))
        p["deflection"] = d
    eng = _require_engine()
    kind, part, what = _model(shape)
    if kind == "mesh":
        if components is not None:
            raise TypeError("slice: {} is a mesh, which cannot be decomposed; pass no "
                            "components".format(what))
        _check_mesh_params("slice", what, "deflection" in p, p["fill_holes"])
        mesh = eng.make_closed(part, what)
        if axis is None:
            axis = centroidal_axis(mesh, **axis_params)
        data = eng.slice_mesh_part(mesh, axis._engine_dict(), p, progress)
        return SliceResult(data, p, axis, None, kind)
    if not p["split_mesh"]:
        raise ValueError("slice: {} is a solid, which is always decomposed; split_mesh=False "
                         "applies to a mesh (pass components to choose the split)".format(what))
    solid = part.single_solid(what)
    if components is not None:
        axis = components.axis
    elif axis is None:
        axis = centroidal_axis(solid, **axis_params)
    if components is None:
        # Decomposed as decompose() does, with no component thinner than a layer nor built past
        # the reach (the slicer could not lay one on it), and again where layers collide; the
        # notes say why a branch got no component of its own, as the CLI does.
        return _slice_decomposing(solid, axis, _checked_params(
            min_component_height=p["min_layer"], max_tilt=p["max_tilt"]), p, progress)
    engine_components = [{"solid": c._solid, "parent": c.parent,
                          "build_direction": tuple(c._build_direction),
                          "base_origin": tuple(c._base_origin), "branch": c.branch,
                          "turned": c.turned, "rule": c.rule}
                         for c in components]
    data = eng.slice_part(solid, axis._engine_dict(), engine_components, p, progress)
    return SliceResult(data, p, axis, components, kind)
