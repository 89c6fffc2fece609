# SPDX-License-Identifier: LGPL-2.1-or-later
"""The centroidal axis of a solid or closed mesh (Ruan et al., Sec. 3), for scripts and FreeCAD.

Centroids of cross-sections marched up from the part's base along +Z, turning into +-X, +-Y or +-Z
where the part turns, joined into branches. The engine's header App/include/mas/CentroidalAxis.hpp
explains the readings of the paper it follows. Re-exported by the package::

    import MultiAxisSlicer as mas
    axis = mas.centroidal_axis(App.ActiveDocument.Part, step=2.5)
    for b in axis.branches:
        print(b.direction, len(b.nodes), b.parent)
"""

import math
import numbers

from . import _as_list, _as_vector, _deflection_mm, _length, _model, _require_engine
from . import progress as _progress

__all__ = ["AxisBranch", "AxisLink", "AxisNode", "CentroidalAxis", "centroidal_axis"]


# ---- parameters ----------------------------------------------------------------------------------


def _number(value, name, unit):
    """A float from a number or a FreeCAD Quantity (its Value: mm or degrees); TypeError else."""
    if isinstance(value, bool) or not isinstance(value, numbers.Real):
        value = getattr(value, "Value", value)
        if isinstance(value, bool) or not isinstance(value, numbers.Real):
            # "a number of millimetres", "a number (a fraction)"
            what = "({})".format(unit) if unit.startswith("a ") else "of " + unit
            raise TypeError("{} must be a number {}, got {!r}".format(name, what, value))
    return float(value)


def _break_angle(value):
    angle = _number(value, "break_angle", "degrees")
    if not (0.0 <= angle <= 180.0):  # also NaN
        raise ValueError("break_angle must be between 0 and 180 degrees, got {}".format(angle))
    return angle


def _finite_or_derived(value, name, unit):
    """None -> NaN, which the engine derives from the part; otherwise a finite number."""
    if value is None:
        return float("nan")
    number = _number(value, name, unit)
    if not math.isfinite(number):
        raise ValueError("{} must be a finite number of {}, got {}".format(name, unit, number))
    return number


def _base_z(value):
    """None -> NaN: the engine takes the part's lowest point."""
    return _finite_or_derived(value, "base_z", "millimetres")


def _frame(value):
    """None -> NaN: the engine derives the frame from the part's sides."""
    return _finite_or_derived(value, "frame", "degrees")


# ---- results -------------------------------------------------------------------------------------


class AxisNode:
    """One node of the axis: the area centroid of one region of a cross-section.

    Attributes: ``position`` (the centroid, mm) and ``normal`` (the section plane's unit normal: the
    branch's marching direction), FreeCAD.Vector when FreeCAD is importable, else tuples; ``area``
    (mm², the region's area left after the parts already searched are taken away), ``offset`` (mm,
    normal . point on the plane), ``thickness`` (mm, the length of the slab this node sweeps along
    its normal), ``slab_start`` (mm, normal . point where that slab starts: ``offset``, except for
    a march's first node, whose slab reaches back to the base plane for a root and to the father
    section's extent, the paper's Eq. 4 T, for a turned branch), ``branch`` (index into
    ``CentroidalAxis.branches``), ``incoming_link`` (index into ``CentroidalAxis.links`` of the
    link ending here, -1 for a root's first node).
    """

    __slots__ = ("area", "offset", "thickness", "slab_start", "branch", "incoming_link",
                 "_position", "_normal", "_interior", "_region")

    def __init__(self, data):
        self._position = data["position"]
        self._normal = data["normal"]
        # A point in the region's material (the engine's; the decomposition finds pipes by it).
        self._interior = data.get("interior", data["position"])
        # The region, as bytes only the engine reads (decomposition and slicing), never shown.
        self._region = data.get("region", b"")
        self.area = data["area"]
        self.offset = data["offset"]
        self.thickness = data["thickness"]
        self.slab_start = data["slab_start"]
        self.branch = data["branch"]
        self.incoming_link = data["incoming_link"]

    @property
    def position(self):
        return _as_vector(self._position)

    @property
    def normal(self):
        return _as_vector(self._normal)

    def to_dict(self):
        """JSON-ready, as ``multiaxis-slicer axis --json`` writes a node."""
        return {
            "position": _as_list(self._position),
            "normal": _as_list(self._normal),
            "area_mm2": self.area,
            "offset_mm": self.offset,
            "thickness_mm": self.thickness,
            "slab_start_mm": self.slab_start,
            "branch": self.branch,
        }

    def __repr__(self):
        return "<MultiAxisSlicer.AxisNode position={} area={:.6g} mm2 branch={}>".format(
            tuple(round(c, 6) for c in self._position), self.area, self.branch
        )


class AxisLink:
    """A link between two nodes.

    Attributes: ``start`` and ``end`` (node indices), ``kind`` ("step": consecutive nodes of one
    march, or a node to the first node of a branch split from it; "connecting": a node of the
    father branch to the first node of a branch that turned), ``is_break`` (a C1 break: the link
    turns more than the break angle from the link arriving at its start), ``turn`` (that angle, in
    degrees; 0 for a root's first link).
    """

    __slots__ = ("start", "end", "kind", "is_break", "turn")

    def __init__(self, data):
        self.start = data["start"]
        self.end = data["end"]
        self.kind = data["kind"]
        self.is_break = data["is_break"]
        self.turn = data["turn_deg"]

    def to_dict(self):
        """JSON-ready, as ``multiaxis-slicer axis --json`` writes a link."""
        return {
            "start": self.start,
            "end": self.end,
            "kind": self.kind,
            "is_break": self.is_break,
            "turn_deg": self.turn,
        }

    def __repr__(self):
        return "<MultiAxisSlicer.AxisLink {} -> {} {}{} turn={:.3g} deg>".format(
            self.start, self.end, self.kind, " break" if self.is_break else "", self.turn
        )


class AxisBranch:
    """One branch: nodes marched in one direction.

    Attributes: ``parent`` (index of the father branch, -1 for a root), ``direction`` (one of +-X,
    +-Y, +-Z; FreeCAD.Vector when FreeCAD is importable), ``nodes`` (node indices in marching
    order), ``parent_node`` (the father's node the first node is linked to, -1 for a root),
    ``first_link`` (that link's index, -1 for a root), ``depth`` (0 for a root),
    ``merged_into`` (the branch that went on with this one's material where their sections
    joined again, e.g. above a hole; -1 when it never merged).
    """

    __slots__ = ("parent", "nodes", "parent_node", "first_link", "depth", "merged_into",
                 "_direction")

    def __init__(self, data):
        self.parent = data["parent"]
        self._direction = data["direction"]
        self.nodes = list(data["nodes"])
        self.parent_node = data["parent_node"]
        self.first_link = data["first_link"]
        self.depth = data["depth"]
        self.merged_into = data["merged_into"]

    @property
    def direction(self):
        return _as_vector(self._direction)

    def to_dict(self):
        """JSON-ready, as ``multiaxis-slicer axis --json`` writes a branch."""
        return {
            "parent": self.parent,
            "direction": _as_list(self._direction),
            "nodes": list(self.nodes),
            "parent_node": self.parent_node,
            "first_link": self.first_link,
            "depth": self.depth,
            "merged_into": self.merged_into,
        }

    def __repr__(self):
        return "<MultiAxisSlicer.AxisBranch direction={} nodes={} parent={}>".format(
            tuple(self._direction), len(self.nodes), self.parent
        )


class CentroidalAxis:
    """A part's centroidal axis: a forest of branches of nodes joined by links.

    Attributes: ``nodes`` (list of ``AxisNode``), ``links`` (list of ``AxisLink``), ``branches``
    (list of ``AxisBranch``, every father before its children), ``params`` (dict of the values
    used, derived ones filled in: ``step_mm``, ``distance_threshold_mm``, ``eps_mm``,
    ``break_angle_deg``, ``base_z_mm``, ``frame_deg``: the turn about Z of the +-X and +-Y the
    axis marched along, ``deflection_mm``: the chordal deflection a solid was
    tessellated with, 0.0 for a mesh used as it is), ``searched_volume`` (mm³, the volume of the
    slabs the nodes swept, section area times slab thickness; every region is searched once, so
    it is the part's volume for prisms along the march and near it otherwise), ``sections_cut``
    (planes cut from the mesh), ``kind`` ("solid" or "mesh"), ``triangles`` (of the mesh that was
    cut).
    """

    def __init__(self, data, kind, triangles, deflection_mm):
        self.nodes = [AxisNode(n) for n in data["nodes"]]
        self.links = [AxisLink(n) for n in data["links"]]
        self.branches = [AxisBranch(b) for b in data["branches"]]
        p = data["params"]
        self.params = {
            "step_mm": p["step_mm"],
            "distance_threshold_mm": p["distance_threshold_mm"],
            "eps_mm": p["eps_mm"],
            "break_angle_deg": p["break_angle_deg"],
            "base_z_mm": p["base_z_mm"],
            "frame_deg": p["frame_deg"],
            "deflection_mm": deflection_mm,
        }
        self.searched_volume = data["searched_volume_mm3"]
        self.sections_cut = data["sections_cut"]
        self.kind = kind
        self.triangles = triangles

    def break_links(self):
        """The links that are C1 breaks, in link order."""
        return [link for link in self.links if link.is_break]

    def to_dict(self):
        """JSON-ready plain data in the layout of ``multiaxis-slicer axis FILE --json`` (without
        its "file"): kind, triangles, deflection_mm, params (step_mm, distance_threshold_mm,
        eps_mm, break_angle_deg, base_z_mm, frame_deg), searched_volume_mm3, nodes, links,
        branches."""
        return {
            "kind": self.kind,
            "triangles": self.triangles,
            "deflection_mm": self.params["deflection_mm"],
            "params": {
                key: self.params[key]
                for key in ("step_mm", "distance_threshold_mm", "eps_mm", "break_angle_deg",
                            "base_z_mm", "frame_deg")
            },
            "searched_volume_mm3": self.searched_volume,
            "nodes": [n.to_dict() for n in self.nodes],
            "links": [link.to_dict() for link in self.links],
            "branches": [b.to_dict() for b in self.branches],
        }

    def _engine_dict(self):
        """The axis in the layout the engine's centroidal_axis() returns, for _engine.decompose()
        (built from the attributes, so that it is exactly what the caller sees)."""
        return {
            "nodes": [{"position": tuple(n._position), "normal": tuple(n._normal),
                       "area": n.area, "offset": n.offset, "thickness": n.thickness,
                       "slab_start": n.slab_start, "branch": n.branch,
                       "incoming_link": n.incoming_link, "interior": tuple(n._interior),
                       "region": n._region}
                      for n in self.nodes],
            "links": [{"start": link.start, "end": link.end, "kind": link.kind,
                       "is_break": link.is_break, "turn_deg": link.turn} for link in self.links],
            "branches": [{"parent": b.parent, "direction": tuple(b._direction),
                          "nodes": list(b.nodes), "parent_node": b.parent_node,
                          "first_link": b.first_link, "depth": b.depth,
                          "merged_into": b.merged_into} for b in self.branches],
            "params": {key: self.params[key] for key in ("step_mm", "distance_threshold_mm",
                                                         "eps_mm", "break_angle_deg",
                                                         "base_z_mm", "frame_deg",
                                                         "deflection_mm")},
            "searched_volume_mm3": self.searched_volume,
        }

    def __repr__(self):
        return "<MultiAxisSlicer.CentroidalAxis nodes={} links={} breaks={} branches={}>".format(
            len(self.nodes), len(self.links), len(self.break_links()), len(self.branches)
        )


# ---- the axis ------------------------------------------------------------------------------------


def centroidal_axis(shape, step=None, distance_threshold=None, eps=0.001, break_angle=30.0,
                    base_z=None, deflection=None, frame=None, progress=None):
    """The centroidal axis of one solid or closed mesh standing on the plane z = ``base_z``.

    ``shape``: a ``Part.Shape`` holding exactly one closed solid, a closed ``Mesh.Mesh``, a document
    object with such a Shape or Mesh, a file path (.step/.stp, .iges/.igs, .brep/.brp, .stl, .off)
    or an engine Shape/Mesh. Several solids that share material (a CompSolid, as Part's
    BooleanFragments leaves them; a compound of a plate and a post standing on it) are fused into
    the one body they make. Solids apart, or meeting only along an edge or at a point, are rejected
    (EngineError multiple_solids): compute one axis per solid, e.g.
    ``[centroidal_axis(s) for s in shape.Solids]``.

    Parameters (lengths in mm, angles in degrees; FreeCAD Quantities are accepted):
      * ``step``: distance between consecutive sections. None: derived from the part, half its
        thinnest wall within [diagonal / 2000, diagonal / 20], at most half the part's height. A
        given step must be smaller than the part's height.
      * ``distance_threshold``: a part of a section sticking out of the one below with its centre
        farther than this outside it starts a new branch. None: twice the step, at most a sixth
        of the size (square root of the area) of the section below.
      * ``eps``: the first plane of a march lies this far inside the part (default 0.001 mm).
      * ``break_angle``: a link turning more than this from the one before it is a C1 break
        (default 30 degrees; 0 to 180).
      * ``base_z``: height of the plane the part stands on. None: its lowest point. A part whose
        lowest point is not on this plane (within eps) is an error.
      * ``deflection``: chordal deflection for tessellating a solid (None: derived from its size,
        see ``deflection()``); a mesh is used as it is.
      * ``frame``: the turn about Z (degrees, read modulo 90) of the +-X and +-Y directions the
        axis marches along. None: derived from the part, the turn that lines them up with its
        sides (a bracket placed 30 degrees round on the plate: 30), 0 when its sides do not agree
        on one (round parts); 0 gives the document's X and Y, as the paper's.
      * ``progress``: None or ``progress(fraction, stage)``, reported as the march goes (at most
        every 10 ms, and at the end), with the volume swept so far over the part's, under the
        stage "centroidal axis"; an exception it raises
        (``Cancelled``) stops the work and is raised again (see ``MultiAxisSlicer.progress``).
        Computing an axis takes milliseconds at the derived step; a small given one may take
        long.

    Returns a ``CentroidalAxis``. Raises ValueError for a parameter out of range (``step <= 0``,
    NaN, a negative threshold), TypeError for a wrong type, and EngineError (with ``code``) for a
    part the engine cannot use: not_a_solid (a face, a shell), multiple_solids, open_mesh,
    empty_input, read_failed, invalid_argument (a step not smaller than the part's height, a part
    that does not stand on ``base_z``, an eps not below the part's height, a part with no
    section larger than a sliver, a step so small that more than 200000 sections would cross the
    part, a march that swept less of the part than its slabs' error allows: what is thinner than
    a step given is lost, and the message names a smaller step). Nothing the caller passed is
    modified.
    """
    step_mm = 0.0 if step is None else _length(step, "step")
    threshold_mm = (0.0 if distance_threshold is None
                    else _length(distance_threshold, "distance_threshold"))
    eps_mm = _length(eps, "eps")
    angle_deg = _break_angle(break_angle)
    base_z_mm = _base_z(base_z)
    frame_deg = _frame(frame)
    d = _deflection_mm(deflection)
    _progress.check(progress)
    eng = _require_engine()
    kind, part, what = _model(shape)
    if kind == "solid":
        solid = part.single_solid(what)
        deflection_mm = eng.effective_deflection(solid, d)
        mesh = eng.tessellate(solid, d)  # as the command line does: the same mesh
    else:
        deflection_mm = 0.0
        mesh = eng.make_closed(part, what)
    data = eng.centroidal_axis(mesh, step=step_mm, distance_threshold=threshold_mm, eps=eps_mm,
                               break_angle=angle_deg, base_z=base_z_mm, frame=frame_deg,
                               progress=progress)
    return CentroidalAxis(data, kind, mesh.triangle_count(), deflection_mm)
