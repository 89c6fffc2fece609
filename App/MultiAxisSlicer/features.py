# SPDX-License-Identifier: LGPL-2.1-or-later
"""Parametric FreeCAD document objects over the engine (App side: imports without FreeCADGui).

``Sections``: the cross-sections of a solid or closed mesh by parallel planes, as a compound of
closed wires. ``CentroidalAxis``: the part's centroidal axis, as a compound of vertices (nodes) and
line segments (links). ``Decomposition``: the part's sub-components, as a compound of solids in
tree order, with one ``Component`` object per solid (labelled Component001, ...) for the tree and
the 3D view. ``Layers``: a decomposition's (or a mesh's) adaptive multi-axis layers, as a compound
of their outlines; ``Toolpath``: the bead paths planned in them, as a compound of polylines;
``MachineProgram``: the 5-axis G-code that deposits them, its travel moves as polylines;
``BuildPreview``: the build after a step of the deposition sequence, the nozzle at the step's
layer. Thin like FreeCAD's own features: properties -> MultiAxisSlicer -> Shape.

    import MultiAxisSlicer.features as features
    obj = features.make_sections(doc.Box, normal=(0, 0, 1), step=2.0)
    axis = features.make_centroidal_axis(doc.Box, step=2.0)
    parts = features.make_decomposition(doc.Box, axis=axis)   # computes it, adds the components
    layers, toolpath = features.make_slice(parts, max_layer=1.5, bead_width=1.2)
    scan_layers, scan_paths = features.make_slice(doc.Scan)      # a closed Mesh::Feature
    program = features.make_machine_program(layers, feed=900)
    preview = features.make_build_preview(layers, step=12)     # the 12th layer deposited
    doc.recompute()
    features.export_gcode(program, "/tmp/part.ngc")
"""

import functools
import math
import re
import types

import FreeCAD
import Part

import MultiAxisSlicer as mas
from MultiAxisSlicer import progress as _progress
from MultiAxisSlicer.decompose import _angle, _branch_list, _checked_params, _max_tilt
from MultiAxisSlicer.gcode import _machine_params

# Bad input the user can fix (a face instead of a solid, an open mesh, Step = 0, no Source), or a
# recompute the user cancelled: FreeCAD shows the object as failed with the message. Anything else
# is a bug and keeps its traceback.
_USER_ERRORS = (mas.EngineError, mas.EngineUnavailableError, ValueError, TypeError,
                mas.Cancelled)


def _names(*pairs):
    """PROPERTY_NAMES entries: (parameter as the engine or the API spells it, property). A
    parameter matches as a whole word, with an "_mm" or "_deg" suffix too."""
    return tuple((r"\b{}(?:_mm|_deg)?\b".format(name), prop) for name, prop in pairs)


_AXIS_NAMES = _names(("step", "Step"), ("distance_threshold", "DistanceThreshold"),
                     ("eps", "Epsilon"), ("break_angle", "BreakAngle"),
                     ("break angle", "BreakAngle"), ("deflection", "Deflection"))

# CentroidalAxis.Frame: the frame the axis marches in (MultiAxisSlicer.centroidal_axis's frame).
AXIS_FRAMES = ["Part", "Document"]


def axis_frame(axis_obj):
    """centroidal_axis()'s ``frame`` for a CentroidalAxis object: None (derived from the part's
    sides) for "Part", 0 (the document's X and Y) for "Document"."""
    return 0.0 if axis_obj.Frame == "Document" else None


# Output properties: read-only in the property editor (1), and setting them does not touch the
# object again (8, App::Prop_Output).
_OUTPUT = 1 | 8


def _add_property(obj, type_id, name, group, doc, default=None, attr=0):
    """Adds a property unless the object has it already (a restored document may)."""
    if name in obj.PropertiesList:
        return False
    obj.addProperty(type_id, name, group, doc, attr)
    if default is not None:
        setattr(obj, name, default)
    return True


def depends_on(obj):
    """The objects ``obj`` is computed from, directly or not, nearest first, each once: what
    FreeCAD's OutListRecursive gives, but answering where links go round in a circle too (which
    OutListRecursive raises on, and _refuse_circular_links marks the object for)."""
    def key(o):
        return o.Document.Name, o.Name

    found, seen, queue = [], {key(obj)}, list(obj.OutList)
    while queue:
        o = queue.pop(0)
        if key(o) in seen:
            continue
        seen.add(key(o))
        found.append(o)
        queue.extend(o.OutList)
    return found


def failure(obj):
    """None when ``obj`` is computed: valid and not waiting for a recompute. Otherwise what stops
    it, as "Label: message": its own error, or that of an object it depends on (FreeCAD does not
    recompute an object whose input failed: it stays touched, valid, and says nothing)."""
    if obj.isValid() and "Touched" not in obj.State:
        return None
    for failed in [obj] + depends_on(obj):
        if not failed.isValid():
            status = failed.getStatusString()
            # Messages that name their object already ("Sections: Source is not set") keep one
            # label.
            if status.startswith(failed.Label + ":"):
                return status
            return "{}: {}".format(failed.Label, status)
    return "{}: not recomputed".format(obj.Label)


def parameters(obj):
    """The inputs of one of this workbench's objects that a user sets, as [(group, [property,
    ...])] in the order its documentation gives them, the links to other objects left out, and
    those that do not apply to it as it is (a Layers object slicing a mesh takes no Deflection
    nor FillHoles): what the GUI's parameter panel edits. [] for any other object."""
    proxy = getattr(obj, "Proxy", None)
    skipped = proxy.not_applicable(obj) if hasattr(proxy, "not_applicable") else ()
    groups = [(group, [p for p in props if p not in skipped])
              for group, props in getattr(proxy, "PARAMETERS", ())]
    return [(group, props) for group, props in groups if props]


def _grouped(pairs):
    """PARAMETERS from (property, group) pairs: each group where it first appears."""
    groups = {}
    for prop, group in pairs:
        groups.setdefault(group, []).append(prop)
    return tuple((group, tuple(props)) for group, props in groups.items())


def remembered_results(objects):
    """What the proxies of `objects` keep in memory of their last computation (a slicing, a
    program), to be put back by restore_results() when their properties go back to the values it
    was computed from (an edit cancelled, its transaction aborted): they then need no computing
    again."""
    return [(o, {k: v for k, v in vars(o.Proxy).items() if k in ("_result", "_program")})
            for o in objects if getattr(o, "Proxy", None) is not None]


def restore_results(remembered):
    """Puts back what remembered_results() took (objects deleted since are skipped)."""
    for obj, kept in remembered:
        try:
            proxy = obj.Proxy
        except Exception:  # deleted
            continue
        for key in ("_result", "_program"):
            if key in kept:
                setattr(proxy, key, kept[key])
            elif hasattr(proxy, key):
                delattr(proxy, key)


def _refuse_circular_links(obj):
    """ValueError where one of ``obj``'s links names ``obj`` itself or an object made from it (a
    Decomposition's Source set to one of its own Component objects): FreeCAD only logs that the
    graph is no longer acyclic, and the object would be computed from its own output."""
    made_from_it = None
    for prop in obj.PropertiesList:
        if obj.getTypeIdOfProperty(prop) not in ("App::PropertyLink", "App::PropertyLinkGlobal"):
            continue
        linked = getattr(obj, prop)
        if linked is None:
            continue
        if linked == obj:
            raise ValueError("{} is this object itself: link another object".format(prop))
        if made_from_it is None:
            made_from_it = obj.InListRecursive  # answers on a circle too (OutListRecursive raises)
        if linked in made_from_it:
            raise ValueError("{} '{}' is made from this object: the links go round in a circle "
                             "(undo the link that closed it)".format(prop, linked.Label))


class _EngineFeature:
    """What every proxy here shares: recompute errors reported by their message, nothing to save
    beyond the properties, a view provider when the GUI opens a document made without it.

    A subclass sets TYPE and VIEW_PROVIDER (a class name in MultiAxisSlicerGui.view_providers) and
    defines ensure_properties(obj) and recompute(obj)."""

    TYPE = ""
    VIEW_PROVIDER = ""
    # (regular expression, property): how the engine and the scripting API name a parameter in a
    # message, and the property that sets it here. A message on the object names the property.
    PROPERTY_NAMES = ()
    # ((group, (property, ...)), ...): the inputs a user sets, in the order the object's
    # documentation gives them; the links to other objects are not among them (parameters()).
    PARAMETERS = ()

    def __init__(self, obj):
        self.Type = self.TYPE
        obj.Proxy = self
        self.ensure_properties(obj)

    # FreeCAD calls `execute(obj)` on recompute. It is handed a C-level callable so that an error
    # the user can fix reaches FreeCAD as its message only, without a Python traceback (FreeCAD
    # prints the traceback of any exception that execute() raises). Read once, when the proxy is
    # attached.
    @property
    def execute(self):
        if mas.engine_available():
            return functools.partial(mas._engine.call_quietly, self._recompute)
        return self._recompute_raising

    def _recompute(self, obj):
        """Returns None, or the exception to report for input the user can fix."""
        try:
            _refuse_circular_links(obj)
            self.recompute(obj)
        except _USER_ERRORS as error:
            return self._in_property_names(error)
        return None

    def _in_property_names(self, error):
        """`error` with the parameters its message names called by their properties ("min_layer"
        -> "MinLayer"), as the user sees them in the property editor."""
        if len(error.args) != 1 or not isinstance(error.args[0], str):
            return error
        # Not inside quotes, where the message names an object by its label ('Part').
        pieces = re.split(r"('[^']*')", error.args[0])
        for i in range(0, len(pieces), 2):
            for pattern, prop in self.PROPERTY_NAMES:
                pieces[i] = re.sub(pattern, prop, pieces[i])
        error.args = ("".join(pieces),)
        return error

    def _recompute_raising(self, obj):
        _refuse_circular_links(obj)
        self.recompute(obj)

    def onDocumentRestored(self, obj):
        self.Type = self.TYPE
        self.ensure_properties(obj)
        # A document made without the GUI (freecadcmd, a script) saved no view provider: give it
        # one when the GUI opens it, so the object gets its icon and colours. FreeCAD 0.20 also
        # opens every object of such a document hidden (its issue 28555, fixed in 1.1): each of
        # this workbench's is shown as its commands would have left it (shown_on_open).
        if FreeCAD.GuiUp and obj.ViewObject is not None and obj.ViewObject.Proxy is None:
            _attach_view_provider(obj, self.VIEW_PROVIDER)
            obj.ViewObject.Visibility = self.shown_on_open(obj)

    @staticmethod
    def shown_on_open(obj):
        """Whether the GUI shows `obj` when it opens a document made without it (see
        onDocumentRestored): as its command leaves it, unless what is made from it takes its
        place in the view."""
        return True

    # Nothing to save: every parameter lives in a property. 0.20.2 calls __getstate__ and
    # __setstate__, 0.21.2 and later dumps and loads.
    def __getstate__(self):
        return None

    def __setstate__(self, state):
        self.Type = self.TYPE

    def dumps(self):
        return None

    def loads(self, state):
        self.Type = self.TYPE


# A Sections object's loops become FreeCAD polygons, about 570 bytes a point, and Coin's copy on
# top (measured): past this many points a Step is refused, before anything is cut.
MAX_DRAWN_SECTION_POINTS = 2000000


class SectionsFeature(_EngineFeature):
    """Proxy of a ``Part::FeaturePython`` holding cross-sections of its ``Source``.

    Inputs: Source (a solid or closed mesh), Normal, Step (mm between planes), Deflection (mm
    chordal deflection for tessellating a solid, 0 = automatic). Outputs: Shape (a compound of
    one closed wire per section loop), SectionCount, TotalArea (sum of all section areas).
    """

    TYPE = "MultiAxisSlicer::Sections"
    VIEW_PROVIDER = "ViewProviderSections"
    PROPERTY_NAMES = _names(("step", "Step"), ("deflection", "Deflection"), ("normal", "Normal"))
    PARAMETERS = (("Sections", ("Normal", "Step", "Deflection")),)

    @staticmethod
    def ensure_properties(obj):
        group = "Sections"
        _add_property(obj, "App::PropertyLinkGlobal", "Source", group,
                      "Solid or closed mesh to cut")
        _add_property(obj, "App::PropertyVector", "Normal", group,
                      "Normal of the cutting planes", FreeCAD.Vector(0, 0, 1))
        _add_property(obj, "App::PropertyLength", "Step", group,
                      "Distance between consecutive planes", 5.0)
        _add_property(obj, "App::PropertyLength", "Deflection", group,
                      "Chordal deflection for tessellating a solid (0 = automatic)", 0.0)
        _add_property(obj, "App::PropertyInteger", "SectionCount", "Result",
                      "Number of cutting planes", 0, _OUTPUT)
        _add_property(obj, "App::PropertyArea", "TotalArea", "Result",
                      "Sum of the areas of all sections", 0.0, _OUTPUT)

    @staticmethod
    def recompute(obj):
        """Properties -> engine -> Shape, SectionCount, TotalArea. Raises on bad input."""
        if obj.Source is None:
            raise ValueError("{}: Source is not set".format(obj.Label))
        deflection = obj.Deflection.Value or None
        with _progress.reporting("Cutting '{}'".format(obj.Label)) as progress:
            result = mas._parallel_sections(
                obj.Source, obj.Normal, obj.Step.Value, deflection,
                _progress.span(progress, 0, 0.5), MAX_DRAWN_SECTION_POINTS,
                "a Sections object draws")
            shape = sections_shape(result, _progress.span(progress, 0.5, 1.0))
        obj.Shape = shape
        obj.SectionCount = len(result)
        obj.TotalArea = sum(s.area for s in result)


def sections_shape(sections, progress=None):
    """A compound of closed polygonal wires, one per section loop (outer loops and holes).
    ``progress``: None or ``progress(fraction, stage)``, called every 500 sections."""
    wires = []
    for i, s in enumerate(sections):
        if progress is not None and i % 500 == 0:
            progress(i / len(sections), "drawing the section outlines")
        for region in s.regions:
            for loop in region.loops:
                if len(loop) >= 3:
                    wires.append(Part.makePolygon(loop + [loop[0]]))
    return Part.makeCompound(wires)


def _check_source(source, function, what="source"):
    """TypeError unless ``source`` is None or a document object: a make_*() function links it
    (a shape or a file name is for the functions of MultiAxisSlicer itself)."""
    if source is not None and not isinstance(source, FreeCAD.DocumentObject):
        raise TypeError("{}() needs a document object as its {} (a Part or Mesh object; "
                        "MultiAxisSlicer's functions take shapes, meshes and files), got {}".format(
                            function, what, type(source).__name__))


def make_sections(source, normal=(0, 0, 1), step=5.0, deflection=0.0, name="Sections", doc=None):
    """Adds a ``Sections`` object cutting ``source`` to ``doc`` (default: the source's document) and
    returns it; recompute the document to compute it. The source is not changed.

    In the GUI it gets its view provider (icon, line colour)."""
    _check_source(source, "make_sections")
    if doc is None:
        doc = source.Document if source is not None else FreeCAD.ActiveDocument
    if doc is None:
        raise ValueError("no document to add the Sections object to")
    # Checked before anything is added: bad arguments leave the document as it was.
    normal = FreeCAD.Vector(*mas._direction(normal))
    step = mas._length(step, "step")
    deflection = mas._length(deflection, "deflection", allow_zero=True)
    obj = doc.addObject("Part::FeaturePython", name)
    SectionsFeature(obj)
    obj.Source = source
    obj.Normal = normal
    obj.Step = step
    obj.Deflection = deflection
    if FreeCAD.GuiUp:
        _attach_view_provider(obj, SectionsFeature.VIEW_PROVIDER)
    return obj


class CentroidalAxisFeature(_EngineFeature):
    """Proxy of a ``Part::FeaturePython`` holding the centroidal axis of its ``Source``.

    Inputs: Source (a solid or closed mesh standing on its lowest point), Step (mm between
    sections, 0 = derived from the part), DistanceThreshold (mm, 0 = twice the step, at most a
    sixth of a section's size), Epsilon (mm), BreakAngle (degrees), Frame ("Part": the +-X and
    +-Y it marches along turned about Z to line up with the part's sides, when they agree on a
    turn; "Document": the document's own), Deflection (mm chordal deflection for tessellating a
    solid, 0 = automatic). Outputs: Shape (a compound of one vertex per node, then one line
    segment per link: first the ordinary links, then the C1 breaks from edge index
    BreakEdgeStart on, so that the view provider can colour them), NodeCount, BranchCount,
    BreakCount, UsedStep, UsedDistanceThreshold, UsedFrame, SearchedVolume.
    """

    TYPE = "MultiAxisSlicer::CentroidalAxis"
    VIEW_PROVIDER = "ViewProviderCentroidalAxis"
    PROPERTY_NAMES = _AXIS_NAMES
    PARAMETERS = (("Centroidal axis",
                   ("Step", "DistanceThreshold", "Epsilon", "BreakAngle", "Frame",
                    "Deflection")),)

    @staticmethod
    def ensure_properties(obj):
        group = "Centroidal axis"
        _add_property(obj, "App::PropertyLinkGlobal", "Source", group,
                      "Solid or closed mesh, standing on its lowest point")
        _add_property(obj, "App::PropertyLength", "Step", group,
                      "Distance between consecutive sections (0 = derived from the part: half "
                      "its thinnest wall)", 0.0)
        _add_property(obj, "App::PropertyLength", "DistanceThreshold", group,
                      "A section part sticking out farther than this starts a new branch "
                      "(0 = twice the step, at most a sixth of a section's size)", 0.0)
        _add_property(obj, "App::PropertyLength", "Epsilon", group,
                      "Distance of a march's first section inside the part", 0.001)
        _add_property(obj, "App::PropertyAngle", "BreakAngle", group,
                      "Links turning more than this from the previous link are C1 breaks", 30.0)
        if _add_property(obj, "App::PropertyEnumeration", "Frame", group,
                         "The +-X and +-Y directions the axis marches along: 'Part' turns them "
                         "about Z to line up with the part's sides (a part placed turned on the "
                         "plate), when they agree on a turn; 'Document' keeps the document's"):
            obj.Frame = AXIS_FRAMES
            obj.Frame = "Part"
        _add_property(obj, "App::PropertyLength", "Deflection", group,
                      "Chordal deflection for tessellating a solid (0 = automatic)", 0.0)
        result = "Result"
        _add_property(obj, "App::PropertyInteger", "NodeCount", result,
                      "Number of nodes (section centroids)", 0, _OUTPUT)
        _add_property(obj, "App::PropertyInteger", "BranchCount", result,
                      "Number of branches", 0, _OUTPUT)
        _add_property(obj, "App::PropertyInteger", "BreakCount", result,
                      "Number of links that are C1 breaks", 0, _OUTPUT)
        _add_property(obj, "App::PropertyInteger", "BreakEdgeStart", result,
                      "Index of the first break link among the Shape's edges (the ordinary "
                      "links come first)", 0, _OUTPUT)
        _add_property(obj, "App::PropertyLength", "UsedStep", result,
                      "The step used (Step, or the one derived from the part)", 0.0, _OUTPUT)
        _add_property(obj, "App::PropertyLength", "UsedDistanceThreshold", result,
                      "The distance threshold used", 0.0, _OUTPUT)
        _add_property(obj, "App::PropertyAngle", "UsedFrame", result,
                      "The turn about Z of the +-X and +-Y the axis marched along", 0.0, _OUTPUT)
        _add_property(obj, "App::PropertyVolume", "SearchedVolume", result,
                      "Volume swept by the nodes' slabs (section area x slab thickness): near "
                      "the part's, as every region is searched once", 0.0, _OUTPUT)

    @staticmethod
    def recompute(obj):
        """Properties -> engine -> Shape and the result properties. Raises on bad input."""
        if obj.Source is None:
            raise ValueError("{}: Source is not set".format(obj.Label))
        with _progress.reporting("Centroidal axis of '{}'".format(obj.Label)) as progress:
            axis = mas.centroidal_axis(
                obj.Source,
                step=obj.Step.Value or None,
                distance_threshold=obj.DistanceThreshold.Value or None,
                eps=obj.Epsilon.Value,
                break_angle=obj.BreakAngle.Value,
                deflection=obj.Deflection.Value or None,
                frame=axis_frame(obj),
                progress=_progress.span(progress, 0, 0.8),
            )
            shape, break_edge_start = axis_shape(axis, _progress.span(progress, 0.8, 1.0))
        # BreakEdgeStart before Shape: the view provider colours the edges when the Shape changes.
        obj.BreakEdgeStart = break_edge_start
        obj.Shape = shape
        obj.NodeCount = len(axis.nodes)
        obj.BranchCount = len(axis.branches)
        obj.BreakCount = len(axis.break_links())
        obj.UsedStep = axis.params["step_mm"]
        obj.UsedDistanceThreshold = axis.params["distance_threshold_mm"]
        obj.UsedFrame = axis.params["frame_deg"]
        obj.SearchedVolume = axis.searched_volume


def axis_shape(axis, progress=None):
    """(compound, break_edge_start): one vertex per node in node order, then one line segment per
    link, ordinary links first (in link order), then the breaks; break_edge_start is the index of
    the first break among the compound's edges. ``progress``: None or ``progress(fraction,
    stage)``, called every 1000 links."""
    points = [FreeCAD.Vector(n.position) for n in axis.nodes]
    ordinary, breaks = [], []
    for i, link in enumerate(axis.links):
        if progress is not None and i % 1000 == 0:
            progress(i / len(axis.links), "drawing the links")
        a, b = points[link.start], points[link.end]
        if a.isEqual(b, 1e-9):  # no edge for a zero-length link (nodes lie a step apart)
            continue
        (breaks if link.is_break else ordinary).append(Part.LineSegment(a, b).toShape())
    vertices = [Part.Vertex(p) for p in points]
    return Part.makeCompound(vertices + ordinary + breaks), len(ordinary)


def make_centroidal_axis(source, step=0.0, distance_threshold=0.0, eps=0.001, break_angle=30.0,
                         deflection=0.0, frame="Part", name="CentroidalAxis", doc=None):
    """Adds a ``CentroidalAxis`` object over ``source`` to ``doc`` (default: the source's document)
    and returns it; recompute the document to compute it. Lengths in mm, ``break_angle`` in
    degrees; 0 for ``step``, ``distance_threshold`` or ``deflection`` means derived from the part;
    ``frame`` is "Part" (the frame lined up with the part's sides) or "Document" (see
    ``CentroidalAxisFeature``). The source is not changed.

    In the GUI it gets its view provider (icon, nodes as points, links as lines, breaks in red)."""
    _check_source(source, "make_centroidal_axis")
    if doc is None:
        doc = source.Document if source is not None else FreeCAD.ActiveDocument
    if doc is None:
        raise ValueError("no document to add the CentroidalAxis object to")
    step = mas._length(step, "step", allow_zero=True)
    distance_threshold = mas._length(distance_threshold, "distance_threshold", allow_zero=True)
    eps = mas._length(eps, "eps")
    break_angle = mas.axis._break_angle(break_angle)
    deflection = mas._length(deflection, "deflection", allow_zero=True)
    if frame not in AXIS_FRAMES:
        raise ValueError("frame must be one of {}, got {!r}".format(", ".join(AXIS_FRAMES), frame))
    obj = doc.addObject("Part::FeaturePython", name)
    CentroidalAxisFeature(obj)
    obj.Source = source
    obj.Step = step
    obj.DistanceThreshold = distance_threshold
    obj.Epsilon = eps
    obj.BreakAngle = break_angle
    obj.Frame = frame
    obj.Deflection = deflection
    if FreeCAD.GuiUp:
        _attach_view_provider(obj, CentroidalAxisFeature.VIEW_PROVIDER)
    return obj


class DecompositionFeature(_EngineFeature):
    """Proxy of a ``Part::FeaturePython`` holding the sub-components of its ``Source``.

    Inputs: Source (one solid: a mesh cannot be split), Axis (optional ``CentroidalAxis`` object:
    when set, the axis is computed with its Step, DistanceThreshold, Epsilon, BreakAngle and
    Deflection, and its Source is used when Source is empty), Step (mm, 0 = derived; used without
    Axis), Deflection (mm, 0 = automatic; used without Axis), FaceAngle, ConcaveAngle,
    SectionPlaneFallback, MinComponentHeight, MaxTilt, KeepBranches (axis branches left in their
    fathers: the Slice command sets those whose own layers the nozzle could not reach),
    SquareBranches (axis branches cut square to their directions, never turned square to their
    lines or halfway round a bend: the Slice command sets them where the turned cuts leave the
    nozzle no way), TurnCuts (False: no cut is turned; a document saved before the turned cuts
    opens so).
    Outputs: Shape (a compound of the component solids in tree order: a
    father before its children, the root first), ComponentCount, and per component, in the same
    order, ComponentParents (index of the father, -1 for the root), BuildDirections, BaseOrigins,
    Rules ("root", "planar_face", "section_plane", "bridge"), Volumes (mm³), Turned (the cut
    turned square to the branch's line, or halfway round a bend, the component built along the
    plane's normal); PartVolume, UsedStep.

    The ``Component`` objects (``ComponentFeature``) show the solids one by one; they are created
    by ``make_decomposition()`` / ``sync_components()``, never inside a recompute (adding or
    removing document objects during a recompute is unsafe in FreeCAD).
    """

    TYPE = "MultiAxisSlicer::Decomposition"
    VIEW_PROVIDER = "ViewProviderDecomposition"
    PROPERTY_NAMES = _AXIS_NAMES + _names(
        ("face_angle", "FaceAngle"), ("concave_angle", "ConcaveAngle"),
        ("min_component_height", "MinComponentHeight"), ("max_tilt", "MaxTilt"),
        ("section_plane_fallback", "SectionPlaneFallback"), ("keep_branches", "KeepBranches"),
        ("square_branches", "SquareBranches"), ("turn_cuts", "TurnCuts"))
    PARAMETERS = (("Decomposition",
                   ("Step", "Deflection", "FaceAngle", "ConcaveAngle", "SectionPlaneFallback",
                    "MinComponentHeight", "MaxTilt")),)

    @staticmethod
    def shown_on_open(obj):
        return False  # its Component objects show it

    @staticmethod
    def ensure_properties(obj):
        group = "Decomposition"
        _add_property(obj, "App::PropertyLinkGlobal", "Source", group,
                      "Solid to split (empty: the Axis object's Source)")
        _add_property(obj, "App::PropertyLink", "Axis", group,
                      "CentroidalAxis object whose parameters are used (optional)")
        _add_property(obj, "App::PropertyLength", "Step", group,
                      "Axis step when no Axis object is set (0 = derived from the part)", 0.0)
        _add_property(obj, "App::PropertyLength", "Deflection", group,
                      "Chordal deflection for the axis when no Axis object is set "
                      "(0 = automatic)", 0.0)
        _add_property(obj, "App::PropertyAngle", "FaceAngle", group,
                      "A splitting face's normal lies within this angle of the branch's "
                      "direction", 10.0)
        _add_property(obj, "App::PropertyAngle", "ConcaveAngle", group,
                      "An edge is concave when the interior angle exceeds 180 degrees by more "
                      "than this", 1.0)
        _add_property(obj, "App::PropertyBool", "SectionPlaneFallback", group,
                      "Without a splitting face, cut where the branch's march started", True)
        _add_property(obj, "App::PropertyLength", "MinComponentHeight", group,
                      "A sub-component reaches at least this far past its cut, and one axis step "
                      "(0 = the step); the Slice command sets MinLayer here", 0.0)
        # A document saved before the reach bounded the build directions keeps them unbounded
        # (MaxTilt 180) until the user changes it.
        if (_add_property(obj, "App::PropertyAngle", "MaxTilt", group,
                          "No sub-component is built further from the build plate's +Z: the "
                          "machine's reach, 90 to 180 (the default machine's table tilts A from "
                          "-100 to 50: 100). Nothing is built straight down", 100.0) and
                "ComponentCount" in obj.PropertiesList):
            obj.MaxTilt = 180.0
        _add_property(obj, "App::PropertyIntegerList", "KeepBranches", group,
                      "Axis branches left in their fathers' components, each with a note (the "
                      "Slice command sets those whose own layers the nozzle cannot reach)")
        _add_property(obj, "App::PropertyIntegerList", "SquareBranches", group,
                      "Axis branches cut square to their directions (+-X, +-Y, +-Z), never "
                      "turned square to their own lines or halfway round a bend (the Slice "
                      "command sets them where the turned cuts leave the nozzle no way)")
        # A document saved before the turned cuts keeps its cuts square to the directions (its
        # KeepBranches were found for them) until the user changes it.
        if (_add_property(obj, "App::PropertyBool", "TurnCuts", group,
                          "Cut a branch running between the six directions (a blade on a hub) "
                          "square to its own line, and one turning off its father round a bend "
                          "at the bend's halfway plane, not square to its direction", True) and
                "ComponentCount" in obj.PropertiesList):
            obj.TurnCuts = False
        result = "Result"
        _add_property(obj, "App::PropertyInteger", "ComponentCount", result,
                      "Number of sub-components", 0, _OUTPUT)
        _add_property(obj, "App::PropertyIntegerList", "ComponentParents", result,
                      "Index of each component's father (-1 for the root)", None, _OUTPUT)
        _add_property(obj, "App::PropertyVectorList", "BuildDirections", result,
                      "Each component's build direction (unit)", None, _OUTPUT)
        _add_property(obj, "App::PropertyVectorList", "BaseOrigins", result,
                      "Each component's base face centroid (mm)", None, _OUTPUT)
        _add_property(obj, "App::PropertyStringList", "Rules", result,
                      "How each component was cut: root, planar_face, section_plane or bridge", None,
                      _OUTPUT)
        _add_property(obj, "App::PropertyFloatList", "Volumes", result,
                      "Each component's volume (mm^3)", None, _OUTPUT)
        _add_property(obj, "App::PropertyBoolList", "Turned", result,
                      "Whether each component's cut was turned square to its branch's line, or "
                      "halfway round a bend (it is built along the plane's normal, between the "
                      "six directions)", None, _OUTPUT)
        _add_property(obj, "App::PropertyVolume", "PartVolume", result,
                      "Volume of the source solid (the components' volumes add up to it)", 0.0,
                      _OUTPUT)
        _add_property(obj, "App::PropertyLength", "UsedStep", result,
                      "The axis step used", 0.0, _OUTPUT)
        _add_property(obj, "App::PropertyStringList", "Notes", result,
                      "Axis branches that got no cut, why, and where their material stayed", None,
                      _OUTPUT)

    @staticmethod
    def recompute(obj):
        """Properties -> engine -> Shape and the result properties. Raises on bad input."""
        result = decomposition_result(obj)
        obj.ComponentParents = [c.parent for c in result]
        obj.BuildDirections = [FreeCAD.Vector(c.build_direction) for c in result]
        obj.BaseOrigins = [FreeCAD.Vector(c.base_origin) for c in result]
        obj.Rules = [c.rule for c in result]
        obj.Volumes = [c.volume for c in result]
        obj.Turned = [c.turned for c in result]
        obj.PartVolume = result.part_volume
        obj.UsedStep = result.axis.params["step_mm"]
        obj.Notes = result.notes
        for note in result.notes:
            FreeCAD.Console.PrintWarning("{}: {}\n".format(obj.Label, note))
        # ComponentCount after the lists and before Shape: the view provider colours the faces
        # per component when the Shape changes.
        obj.ComponentCount = len(result)
        obj.Shape = Part.makeCompound([c.shape for c in result])


def decomposed_part(obj):
    """The part a Decomposition object splits: its Source, else its Axis object's (None for
    neither). Unchecked: decomposition_inputs() says what is wrong with the links."""
    return obj.Source if obj.Source is not None else getattr(obj.Axis, "Source", None)


def decomposition_inputs(obj):
    """(source, keyword arguments of ``MultiAxisSlicer.decompose``) of a Decomposition object, from
    its properties and its Axis object's. Raises ValueError / TypeError for inconsistent links."""
    axis_obj = obj.Axis
    if axis_obj is not None and not is_centroidal_axis(axis_obj):
        raise TypeError("{}: Axis '{}' is not a CentroidalAxis object".format(
            obj.Label, axis_obj.Label))
    source = decomposed_part(obj)
    if axis_obj is not None and axis_obj.Source is not None and source != axis_obj.Source:
        raise ValueError("{}: Axis '{}' belongs to '{}', not to the Source '{}'".format(
            obj.Label, axis_obj.Label, axis_obj.Source.Label, source.Label))
    if source is None:
        raise ValueError("{}: Source is not set".format(obj.Label))
    if axis_obj is not None:
        params = dict(step=axis_obj.Step.Value or None,
                      distance_threshold=axis_obj.DistanceThreshold.Value or None,
                      eps=axis_obj.Epsilon.Value, break_angle=axis_obj.BreakAngle.Value,
                      deflection=axis_obj.Deflection.Value or None, frame=axis_frame(axis_obj))
    else:
        params = dict(step=obj.Step.Value or None, deflection=obj.Deflection.Value or None)
    params.update(face_angle=obj.FaceAngle.Value, concave_angle=obj.ConcaveAngle.Value,
                  section_plane_fallback=bool(obj.SectionPlaneFallback),
                  min_component_height=obj.MinComponentHeight.Value,
                  max_tilt=obj.MaxTilt.Value, keep_branches=tuple(obj.KeepBranches),
                  square_branches=tuple(obj.SquareBranches), turn_cuts=bool(obj.TurnCuts))
    return source, params


def _shape_key(source):
    """A key that changes when the source's geometry or placement does, its groups' included: a
    hash of its BREP text as placed (well under a millisecond for a part of a few dozen faces).
    None when it has no Part shape."""
    shape = mas._placed(source)
    if shape is None or not hasattr(shape, "exportBrepToString") or shape.isNull():
        return None
    return hash(shape.exportBrepToString())


def decomposition_result(obj):
    """The engine's ``MultiAxisSlicer.Decomposition`` of a Decomposition object, as its properties
    and its source's current shape give it.

    The proxy keeps the last one in memory (never saved) with the source and parameters it was
    computed from, so that the Layers object slicing it does not decompose the part again; after a
    reopen, or when anything it depends on changed, it is computed anew. Raises like
    ``MultiAxisSlicer.decompose``."""
    source, params = decomposition_inputs(obj)
    proxy = obj.Proxy
    key = _shape_key(source)
    if key is not None:
        key = (key, tuple(sorted(params.items())))
        cached = getattr(proxy, "_result", None)
        if cached is not None and cached[0] == key:
            return cached[1]
    proxy._result = None
    # Reported through the GUI's progress dialog, when there is one (MultiAxisSlicer.progress).
    with _progress.reporting("Decomposing '{}'".format(obj.Label)) as progress:
        result = mas.decompose(source, progress=progress, **params)
    if key is not None:
        proxy._result = (key, result)
    return result


class ComponentFeature(_EngineFeature):
    """Proxy of a ``Part::FeaturePython`` showing one sub-component of a ``Decomposition``.

    Inputs: Decomposition (the object it belongs to), Index (its place in tree order, 0 = the
    root). Outputs: Shape (the component's solid), Parent (index of the father component, -1 for
    the root), BuildDirection, BaseOrigin, Rule, Volume, Turned. It follows the Decomposition on
    every recompute; an Index the Decomposition no longer has is an error until
    ``sync_components()`` (or the GUI, after a recompute) removes the object."""

    TYPE = "MultiAxisSlicer::Component"
    VIEW_PROVIDER = "ViewProviderComponent"

    @staticmethod
    def shown_on_open(obj):
        # Layers sliced from its decomposition take its place, as the Slice command leaves them.
        decomposition = getattr(obj, "Decomposition", None)
        return decomposition is None or not any(is_layers(o) for o in decomposition.InList)

    @staticmethod
    def ensure_properties(obj):
        group = "Component"
        _add_property(obj, "App::PropertyLink", "Decomposition", group,
                      "The Decomposition this component belongs to", None, _OUTPUT)
        _add_property(obj, "App::PropertyInteger", "Index", group,
                      "Place in the decomposition's tree order (0 = the root)", 0, _OUTPUT)
        result = "Result"
        _add_property(obj, "App::PropertyInteger", "Parent", result,
                      "Index of the father component (-1 for the root)", -1, _OUTPUT)
        _add_property(obj, "App::PropertyVector", "BuildDirection", result,
                      "Direction the component is deposited along (unit)", None, _OUTPUT)
        _add_property(obj, "App::PropertyVector", "BaseOrigin", result,
                      "Centroid of the base face it is built from (mm)", None, _OUTPUT)
        _add_property(obj, "App::PropertyString", "Rule", result,
                      "How it was cut: root, planar_face, section_plane or bridge", None, _OUTPUT)
        _add_property(obj, "App::PropertyVolume", "Volume", result, "Volume", 0.0, _OUTPUT)
        _add_property(obj, "App::PropertyBool", "Turned", result,
                      "Whether its cut was turned square to its branch's line, or halfway round "
                      "a bend (it is built along the plane's normal, between the six "
                      "directions)", False, _OUTPUT)

    @staticmethod
    def recompute(obj):
        d = obj.Decomposition
        if d is None:
            raise ValueError("{}: Decomposition is not set".format(obj.Label))
        i = obj.Index
        # One child shape per component: a solid, or a compound of the solids of a root standing
        # on several feet.
        solids = d.Shape.childShapes() if not d.Shape.isNull() else []
        if not (0 <= i < min(d.ComponentCount, len(solids))):
            raise ValueError("{}: '{}' now has {} component(s), this was number {}: left over "
                             "until the components are synchronised".format(
                                 obj.Label, d.Label, d.ComponentCount, i + 1))
        obj.Parent = d.ComponentParents[i]
        obj.BuildDirection = d.BuildDirections[i]
        obj.BaseOrigin = d.BaseOrigins[i]
        obj.Rule = d.Rules[i]
        obj.Volume = d.Volumes[i]
        # Empty in a document saved before it had Turned, until the decomposition recomputes.
        obj.Turned = i < len(d.Turned) and bool(d.Turned[i])
        obj.Shape = solids[i].copy()


def is_decomposition(obj):
    return getattr(getattr(obj, "Proxy", None), "Type", None) == DecompositionFeature.TYPE


def components_of(decomposition):
    """The Component objects of a Decomposition object, in Index order."""
    found = [o for o in decomposition.InList
             if getattr(getattr(o, "Proxy", None), "Type", None) == ComponentFeature.TYPE
             and o.Decomposition == decomposition]
    return sorted(found, key=lambda o: o.Index)


def _component_label(index):
    return "Component{:03d}".format(index + 1)


def sync_components(decomposition):
    """Makes the Decomposition object's Component objects match its ComponentCount: one per
    component, labelled Component001, Component002, ... in tree order, each recomputed; extra
    ones are removed. Call it outside a recompute (after ``doc.recompute()``); the GUI does it
    after every recompute that changes the count. Two for one component (a script's removal of
    one undone after it was made anew) are one again, the one labelled so kept. An invalid
    Decomposition gets none added. Returns the Component objects."""
    doc = decomposition.Document
    existing = components_of(decomposition)
    valid = decomposition.isValid()
    count = decomposition.ComponentCount if valid else len(existing)
    kept, extra = {}, []
    for c in existing:
        i = c.Index
        if not 0 <= i < count:
            extra.append(c)
        elif i not in kept:
            kept[i] = c
        elif c.Label == _component_label(i) and kept[i].Label != _component_label(i):
            extra.append(kept[i])
            kept[i] = c
        else:
            extra.append(c)
    for c in extra:
        doc.removeObject(c.Name)
    keep = list(kept.values())
    for i in range(count if valid else 0):
        if i in kept:
            continue
        obj = doc.addObject("Part::FeaturePython", "Component")
        ComponentFeature(obj)
        obj.Decomposition = decomposition
        obj.Index = i
        obj.Label = _component_label(i)
        if FreeCAD.GuiUp:
            _attach_view_provider(obj, ComponentFeature.VIEW_PROVIDER)
        keep.append(obj)
    keep.sort(key=lambda o: o.Index)
    for c in keep:
        if "Touched" in c.State or c.Shape.isNull():
            c.recompute()
    return keep


def make_decomposition(source, axis=None, face_angle=10.0, section_plane_fallback=True,
                       deflection=0.0, name="Decomposition", doc=None, min_component_height=0.0,
                       max_tilt=100.0, keep_branches=(), square_branches=()):
    """Adds a ``Decomposition`` object splitting ``source`` to ``doc`` (default: the source's,
    else the axis object's document), computes it and adds its Component objects; returns the
    Decomposition object. ``axis``: an optional ``CentroidalAxis`` object whose parameters (and
    Source, when ``source`` is None) are used. ``face_angle`` in degrees, ``deflection`` in mm (0 =
    automatic; used without ``axis``), ``min_component_height`` in mm (the least a sub-component
    reaches past its cut, besides one axis step), ``max_tilt`` in degrees (no sub-component is
    built further from +Z: the machine's reach, 90 to 180), ``keep_branches`` axis branches to
    leave in their fathers (KeepBranches), ``square_branches`` axis branches to cut square to
    their directions (SquareBranches). A failing computation leaves the object marked invalid
    with the message, without components. The source is not changed.

    In the GUI the objects get their view providers (one distinct colour per component)."""
    _check_source(source, "make_decomposition")
    if axis is not None and not is_centroidal_axis(axis):
        raise TypeError("axis must be a CentroidalAxis object, got {}".format(
            getattr(axis, "TypeId", type(axis).__name__)))
    if doc is None:
        owner = source if source is not None else axis
        doc = owner.Document if owner is not None else FreeCAD.ActiveDocument
    if doc is None:
        raise ValueError("no document to add the Decomposition object to")
    face_angle = _angle(face_angle, "face_angle", 90.0)
    deflection = mas._length(deflection, "deflection", allow_zero=True)
    min_component_height = mas._length(min_component_height, "min_component_height",
                                       allow_zero=True)
    max_tilt = _max_tilt(max_tilt)
    keep_branches = _branch_list(keep_branches)
    square_branches = _branch_list(square_branches, "square_branches")
    obj = doc.addObject("Part::FeaturePython", name)
    DecompositionFeature(obj)
    obj.Source = source
    obj.Axis = axis
    obj.FaceAngle = face_angle
    obj.SectionPlaneFallback = bool(section_plane_fallback)
    obj.Deflection = deflection
    obj.MinComponentHeight = min_component_height
    obj.MaxTilt = max_tilt
    obj.KeepBranches = list(keep_branches)
    obj.SquareBranches = list(square_branches)
    if FreeCAD.GuiUp:
        _attach_view_provider(obj, DecompositionFeature.VIEW_PROVIDER)
    obj.recompute(True)  # with what it depends on: the count decides the Component objects
    if failure(obj) is None:
        sync_components(obj)
    return obj


def is_centroidal_axis(obj):
    return getattr(getattr(obj, "Proxy", None), "Type", None) == CentroidalAxisFeature.TYPE


# ---- slicing: Layers and Toolpath ----------------------------------------------------------------

# The slicing parameters a Layers object holds as properties: (property, group, slice() parameter,
# property type, tooltip). Their defaults are MultiAxisSlicer.SLICE_DEFAULTS (mm, degrees).
_SLICE_PROPERTIES = (
    ("MinLayer", "Layers", "min_layer", "App::PropertyLength",
     "Least thickness anywhere on a layer"),
    ("MaxLayer", "Layers", "max_layer", "App::PropertyLength",
     "Greatest thickness anywhere on a layer"),
    ("MaxVolumeDifference", "Layers", "max_volume_difference", "App::PropertyFloat",
     "Bound on a layer's volumetric difference (Eq. 9), as a fraction of its volume"),
    ("EpsAngle", "Layers", "eps_angle", "App::PropertyAngle",
     "Averaging a layer's direction stops when it changes by less than this"),
    ("OverhangAngle", "Layers", "overhang_angle", "App::PropertyAngle",
     "A layer may stick out over the one below by its thickness x tan(this)"),
    ("MaxTilt", "Layers", "max_tilt", "App::PropertyAngle",
     "The most a layer's normal (the tool axis) tilts from the build plate's +Z: the machine's "
     "reach, 90 to 180 (the default machine's table tilts A from -100 to 50: 100)"),
    ("SplitMesh", "Layers", "split_mesh", "App::PropertyBool",
     "A mesh (Source) is split at section planes where its axis turns or branches, each piece "
     "built along its own direction (off: sliced as one component)"),
    ("AvoidCollisions", "Layers", "avoid_collisions", "App::PropertyBool",
     "A mesh's piece some of whose layers the nozzle cannot reach is built in its father, the "
     "mesh split again (off: the first split is kept, those layers reported). A Decomposition is "
     "sliced as it is: its KeepBranches (set by the Slice command) do this for a solid"),
    ("VolumeSamples", "Layers", "volume_samples", "App::PropertyInteger",
     "Sections per layer for integrating its volumetric difference"),
    ("Strict", "Layers", "strict", "App::PropertyBool",
     "A layer over MaxVolumeDifference even at MinLayer is an error (otherwise it is kept at "
     "MinLayer and counted in LayersOverVolumeDifference)"),
    ("FillHoles", "Layers", "fill_holes", "App::PropertyLength",
     "Round holes up to this diameter whose ceilings would overhang (axis past OverhangAngle off "
     "the build direction) are deposited solid, to be drilled afterwards (0 = none)"),
    ("BeadWidth", "Paths", "bead_width", "App::PropertyLength", "Width of one deposited bead"),
    ("Overlap", "Paths", "overlap", "App::PropertyFloat",
     "Fraction of a bead's width shared with its neighbour"),
    ("ContourCount", "Paths", "contour_count", "App::PropertyInteger",
     "Contour passes along every region's boundary"),
    ("Infill", "Paths", "infill", "App::PropertyEnumeration",
     "Filling inside the contours: raster lines, more contours, or none"),
    ("RasterAngle", "Paths", "raster_angle", "App::PropertyAngle",
     "Direction of the first layer's raster lines, in the part's frame (its axis' UsedFrame)"),
    ("RasterAngleStep", "Paths", "raster_angle_step", "App::PropertyAngle",
     "Added to the raster direction from one layer to the next"),
    ("MinFeature", "Paths", "min_feature", "App::PropertyLength",
     "Centre lines shorter than this are reported, not run (0 = half a bead)"),
    ("MeasureCoverage", "Paths", "measure_coverage", "App::PropertyBool",
     "Also measure the area the beads leave uncovered (slower; see the Toolpath's "
     "UncoveredArea)"),
    ("NozzleStandoff", "Nozzle", "nozzle_standoff", "App::PropertyLength",
     "From the deposit point to the nozzle tip's face, along the tool axis"),
    ("NozzleTipDiameter", "Nozzle", "nozzle_tip_diameter", "App::PropertyLength",
     "Diameter of the nozzle tip's face"),
    ("NozzleConeAngle", "Nozzle", "nozzle_cone_angle", "App::PropertyAngle",
     "Half-angle of the tip's cone, widening from the tip to the body"),
    ("NozzleBodyDiameter", "Nozzle", "nozzle_body_diameter", "App::PropertyLength",
     "Diameter of the nozzle's cylindrical body"),
    ("NozzleBodyLength", "Nozzle", "nozzle_body_length", "App::PropertyLength",
     "Length of the nozzle's body"),
    ("NozzleMargin", "Nozzle", "nozzle_margin", "App::PropertyLength",
     "Clearance the nozzle keeps from what is deposited"),
    ("CheckPlate", "Nozzle", "check_plate", "App::PropertyBool",
     "The build plate (the plane the part stands on) is an obstacle to the nozzle too"),
    ("NozzleMaxLean", "Nozzle", "nozzle_max_lean", "App::PropertyAngle",
     "Where a layer's nozzle would still meet the plate or what is deposited, its tool axis may "
     "lean this far from the layer's normal to clear (0 = always along the normal)"),
)

INFILL_PATTERNS = ["raster", "contour", "none"]

# The Toolpath's Shape: one sub-compound per kind of path, in this order (the view provider
# colours them), each holding that kind's polylines in deposition order.
PATH_KINDS = ("contour", "infill", "centre_line", "travel")


def _check_link(obj, prop, check, what):
    linked = getattr(obj, prop)
    if linked is None:
        raise ValueError("{}: {} is not set".format(obj.Label, prop))
    if not check(linked):
        raise TypeError("{}: {} '{}' is not a {} object".format(obj.Label, prop, linked.Label,
                                                                 what))
    return linked


def is_mesh_part(obj):
    """Whether the document object ``obj`` is a mesh a Layers object can slice as its Source (a
    ``Mesh::Feature``, or a link to one; whether it is closed is checked when it is sliced)."""
    if not mas._is_document_object(obj):
        return False
    try:
        return obj.isDerivedFrom("Mesh::Feature") or mas._linked_mesh(obj) is not None
    except ValueError:  # a link array: slicing it says so
        return True


def sliced_mesh(obj):
    """The mesh a Layers object slices: its Source, else its Axis object's; None when it slices a
    Decomposition. Unchecked: slice_inputs() says what is wrong with the links."""
    if obj.Source is not None:
        return obj.Source
    return getattr(obj.Axis, "Source", None) if obj.Axis is not None else None


def slice_inputs(obj):
    """(Decomposition object or None, mesh object or None, slice() parameters, deflection or None)
    of a Layers object: it slices either a Decomposition's part, component by component, or a mesh
    (its Source, or its Axis object's), the parameters then holding the Axis object's too. Raises
    ValueError / TypeError for a missing or wrong link or a bad parameter (naming it)."""
    decomposition, source, axis = obj.Decomposition, obj.Source, obj.Axis
    mesh_links = [(name, o) for name, o in (("Source", source), ("Axis", axis)) if o is not None]
    if decomposition is not None and mesh_links:
        name, other = mesh_links[0]
        raise ValueError("{}: both Decomposition '{}' and {} '{}' are set: a Layers object slices "
                         "a decomposition or a mesh, not both".format(
                             obj.Label, decomposition.Label, name, other.Label))
    if decomposition is not None:
        _check_link(obj, "Decomposition", is_decomposition, "Decomposition")
    elif not mesh_links:
        raise ValueError("{}: neither Decomposition nor Source is set".format(obj.Label))
    if axis is not None:
        if not is_centroidal_axis(axis):
            raise TypeError("{}: Axis '{}' is not a CentroidalAxis object".format(obj.Label,
                                                                                 axis.Label))
        if axis.Source is None:
            raise ValueError("{}: Axis '{}' has no Source".format(obj.Label, axis.Label))
        if source is not None and axis.Source != source:
            raise ValueError("{}: Axis '{}' belongs to '{}', not to the Source '{}'".format(
                obj.Label, axis.Label, axis.Source.Label, source.Label))
    mesh = sliced_mesh(obj) if decomposition is None else None
    if mesh is not None and not is_mesh_part(mesh):
        raise TypeError("{}: {} '{}' is not a mesh: a solid is sliced through a Decomposition "
                        "object (set Decomposition, not Source or Axis)".format(
                            obj.Label, "Source" if source is not None else "Axis' Source",
                            mesh.Label))
    params = {}
    for prop, _group, name, type_id, _doc in _SLICE_PROPERTIES:
        value = getattr(obj, prop)
        if type_id in ("App::PropertyLength", "App::PropertyAngle"):
            value = value.Value
        params[name] = value
    if decomposition is not None:
        # A mesh's: a Decomposition's part is sliced as the Decomposition splits it (the panel
        # does not show it then; AvoidCollisions, a mesh's too, is passed on and does nothing).
        del params["split_mesh"]
    mas.slicing._slice_params(dict(mas.SLICE_DEFAULTS, **params))  # before any decomposing
    if axis is not None:
        params.update(step=axis.Step.Value or None,
                      distance_threshold=axis.DistanceThreshold.Value or None,
                      eps=axis.Epsilon.Value, break_angle=axis.BreakAngle.Value,
                      frame=axis_frame(axis))
    return decomposition, mesh, params, obj.Deflection.Value or None


def _mesh_fingerprint(mesh_obj):
    """(what tells one state of a mesh object's mesh from another, the mesh as the engine's): a
    Layers object's remembered result is for the mesh it was sliced from. Every point (placed) and
    facet, hashed by the engine (``Mesh.digest``; some 40 ms on a 75000-facet mesh, the
    conversion's, against 1.4 for counts, volume, area, box and placement, which were the same for
    an L turned over in its own box: the Layers object kept the old L's layers). The converted
    mesh is what is sliced, not converted again."""
    converted = mas._Converted(*mas._model(mesh_obj))
    return (mesh_obj.Name, converted.part.digest()), converted


def slice_result(obj, computed=False):
    """The engine's ``MultiAxisSlicer.SliceResult`` of a Layers object, as its properties and its
    Decomposition (or its mesh Source) give it.

    The proxy keeps the last one in memory (never saved): the Toolpath object reads its paths from
    there. After a reopen, or when a parameter, the decomposition or the mesh changed, it is
    computed anew (the decomposition too, unless the Decomposition object still has it). Raises
    like ``MultiAxisSlicer.slice``. ``computed``: the objects made from the Layers object's take
    its remembered result as it is when it and its mesh are valid and not touched (FreeCAD then
    has it recomputed, its mesh's fingerprint taken, since the mesh last changed), its parameters
    unchanged, without reading the mesh again."""
    decomposition_obj, mesh_obj, params, deflection = slice_inputs(obj)
    proxy = obj.Proxy
    cached = getattr(proxy, "_result", None)
    settings = (tuple(sorted(params.items())), deflection)
    if mesh_obj is not None:
        decomposition = None
        if (computed and cached is not None and cached[0][1:] == settings
                and failure(obj) is None and failure(mesh_obj) is None):
            return cached[1]
        # The mesh, not a result holding it: the fingerprint names its state.
        part_key, source = _mesh_fingerprint(mesh_obj)
    else:
        decomposition = decomposition_result(decomposition_obj)
        source, _ = decomposition_inputs(decomposition_obj)
        # The cached result holds its decomposition, so that id() is not reused while it is cached.
        part_key = id(decomposition)
    key = (part_key,) + settings
    if cached is not None and cached[0] == key:
        return cached[1]
    proxy._result = None
    with _progress.reporting("Slicing '{}'".format(obj.Label)) as progress:
        result = mas.slice(source, components=decomposition, deflection=deflection,
                           progress=progress, **params)
    proxy._result = (key, result)
    return result


def hangs_past_strip(result, deflection):
    """Whether some layer of a ``slice()`` result hangs past a strip ``deflection`` mm wide along
    its outlines (what the mesh sections can show on a part with nothing hanging): where one does,
    ``slice()`` decomposing a solid itself keeps its component's branch in its father if less
    hangs so."""
    return any(layer.unsupported_area > layer.outline_length * deflection
               for layer in result.layers)


def has_unreachable_or_hanging(layers):
    """Whether a Layers object slicing a Decomposition object has layers in the nozzle's way or
    hanging past the deflection's strip (``hangs_past_strip``): what keep_unreachable_branches()
    acts on."""
    decomposition_obj, _mesh, _params, deflection = slice_inputs(layers)
    result = slice_result(layers)
    return bool(result.collisions) or hangs_past_strip(
        result, mas.deflection(decomposition_inputs(decomposition_obj)[0], deflection))


def keep_unreachable_branches(layers):
    """Where some layers of a Layers object slicing a Decomposition object would meet the plate or
    what is deposited before them (its CollidingLayers), or hang past the deflection's strip
    (``hangs_past_strip``), keeps their components' branches in their fathers, as
    ``MultiAxisSlicer.slice()`` does when it decomposes a solid itself (first cutting square to
    their directions the branches whose cuts were turned square to their lines: all of them, or
    only the colliding ones where that slices better; a hanging one where less hangs so): the
    part is decomposed (with the Decomposition's parameters) and sliced (with the Layers') again,
    up to five rounds and three more for hanging layers, and as one component if that leaves
    fewer layers in the nozzle's way. The branches kept go to the Decomposition's KeepBranches,
    those cut square to its SquareBranches;
    both objects are recomputed from that result (remembered, not computed once more) and the
    Component objects follow. Returns the branches added to either, in increasing order: [] when
    no layer collides or hangs so, or none is kept, and nothing is changed then. Raises
    TypeError for a Layers object slicing a mesh (AvoidCollisions does this for a mesh) and as
    ``slice()`` (``Cancelled`` too). Call it outside a recompute."""
    decomposition_obj, _mesh, params, deflection = slice_inputs(layers)
    if decomposition_obj is None:
        raise TypeError("keep_unreachable_branches(): '{}' slices a mesh, which its "
                        "AvoidCollisions keeps clear of collisions".format(layers.Label))
    if not has_unreachable_or_hanging(layers):
        return []
    decomposition = decomposition_result(decomposition_obj)
    source, values = decomposition_inputs(decomposition_obj)
    names = ("face_angle", "concave_angle", "section_plane_fallback", "min_component_height",
             "max_tilt", "keep_branches", "square_branches", "turn_cuts")
    checked = _checked_params(**{k: values[k] for k in names})
    p = mas.slicing._slice_params(dict(mas.SLICE_DEFAULTS, **params))
    if deflection is not None:
        p["deflection"] = deflection
    _, part, what = mas._model(source)
    with _progress.reporting("Keeping unreachable branches of '{}'".format(
            decomposition_obj.Label)) as progress:
        again = mas.slicing._slice_decomposing(part.single_solid(what), decomposition.axis,
                                               checked, p, progress)
    kept = again.decomposition.kept_branches
    square = again.decomposition.square_branches
    added = sorted((set(kept) - set(decomposition_obj.KeepBranches)) |
                   (set(square) - set(decomposition_obj.SquareBranches)))
    if not added:
        return []
    decomposition_obj.KeepBranches = kept
    decomposition_obj.SquareBranches = square
    # Both remember the result, as their recompute would key it.
    key = _shape_key(source)
    if key is not None:
        _, values = decomposition_inputs(decomposition_obj)
        decomposition_obj.Proxy._result = ((key, tuple(sorted(values.items()))),
                                           again.decomposition)
        layers.Proxy._result = ((id(again.decomposition), tuple(sorted(params.items())),
                                 deflection), again)
    doc = layers.Document
    doc.recompute([decomposition_obj, layers] + layers.InListRecursive)  # the Toolpath too
    if failure(decomposition_obj) is None:
        sync_components(decomposition_obj)
    return added


def _polyline(points, closed=False):
    """A Part wire through `points` (consecutive repeats dropped); closed: back to the first point.
    None when too few distinct points are left."""
    kept = []
    for p in points:
        if not kept or not p.isEqual(kept[-1], 1e-7):
            kept.append(p)
    if closed:
        if len(kept) > 1 and kept[0].isEqual(kept[-1], 1e-7):
            kept.pop()
        if len(kept) < 3:
            return None
        kept.append(kept[0])
    elif len(kept) < 2:
        return None
    return Part.makePolygon(kept)


def _turn(points, normal):
    """Twice the signed area of a closed loop of points seen from `normal`'s side (> 0:
    counter-clockwise)."""
    o = points[0]
    return sum(((p - o).cross(q - o)).dot(normal) for p, q in zip(points[1:], points[2:]))


def _region_face(region, origin, normal):
    """A planar face bounded by a region's loops (``outer`` and ``holes``, on the plane through
    `origin` square to `normal`), or its outer wire alone when OCCT cannot make the face; None for
    a region with under three distinct points. The face is made on the plane directly, each loop
    turned as OCCT wants it (the outer counter-clockwise seen from `normal`'s side, holes the
    other way), 50 microseconds for a loop of 50 points where OCCT's face makers, finding the
    plane and the holes themselves, took a millisecond; OCCT's Bullseye maker where that fails."""
    normal = FreeCAD.Vector(normal)
    loops = []
    for k, points in enumerate([region["outer"]] + list(region["holes"])):
        if len(points) >= 3 and (_turn(points, normal) > 0.0) != (k == 0):
            points = list(reversed(points))
        wire = _polyline(points, closed=True)
        if wire is None and k == 0:
            return None
        if wire is not None:
            loops.append(wire)
    try:
        return Part.Face(Part.Plane(FreeCAD.Vector(origin), normal), loops)
    except Part.OCCError:
        pass
    try:
        return Part.makeFace(loops, "Part::FaceMakerBullseye")
    except Part.OCCError:
        return loops[0]


def layers_shape(result):
    """A compound of one sub-compound per layer (in the result's order), each holding one closed
    polygonal wire per loop of the layer's regions (outer loops and holes), then one planar face
    per unsupported region of the layer (on the plane it is deposited on: where it stands on
    nothing, see ``MultiAxisSlicer.Layer.unsupported_regions``). The layers hold no other face."""
    layers = []
    for layer in result.layers:
        wires = [_polyline(loop, closed=True) for loop in layer.loops()]
        faces = [_region_face(r, layer.lower_origin, layer.lower_normal)
                 for r in layer.unsupported_regions]
        layers.append(Part.makeCompound([s for s in wires + faces if s is not None]))
    return Part.makeCompound(layers)


def toolpath_shape(result, show_travel=False):
    """(compound, path counts, deposit paths): a compound of one sub-compound per kind of path
    (``PATH_KINDS``: contour, infill, centre_line, travel), each holding that kind's polylines in
    deposition order; travel moves only with ``show_travel``. The counts are of the polylines
    shown, per kind in the same order; deposit paths counts every deposit path of the result."""
    groups = [[] for _ in PATH_KINDS]
    deposits = 0
    for i in range(len(result.layers)):
        for path in result.paths(i):
            deposits += path.deposit
            if not path.deposit and not show_travel:
                continue
            kind = PATH_KINDS.index(path.kind) if path.kind in PATH_KINDS else 0
            wire = _polyline(path.points)
            if wire is not None:
                groups[kind].append(wire)
    return (Part.makeCompound([Part.makeCompound(g) for g in groups]), [len(g) for g in groups],
            deposits)


class LayersFeature(_EngineFeature):
    """Proxy of a ``Part::FeaturePython`` holding the adaptive multi-axis layers of a
    ``Decomposition`` object's part, or of a mesh (``MultiAxisSlicer.slice``).

    Inputs: Decomposition (the Decomposition object: its source and sub-components are sliced, each
    along its own build direction) or, in its place, Source (a closed mesh object, split at
    section planes as ``MultiAxisSlicer.slice`` splits a mesh, or sliced as one component with
    SplitMesh off) and/or Axis (a CentroidalAxis object over that mesh, whose parameters the axis
    then takes; without it they are derived), the layer parameters (MinLayer, MaxLayer,
    MaxVolumeDifference, EpsAngle, OverhangAngle, MaxTilt, SplitMesh, AvoidCollisions (a
    mesh's: its pieces whose layers the nozzle cannot reach stay in their fathers; a
    Decomposition is sliced as it is, see keep_unreachable_branches), VolumeSamples, Strict,
    FillHoles), the path parameters
    (BeadWidth, Overlap, ContourCount, Infill, RasterAngle, RasterAngleStep, MinFeature,
    MeasureCoverage), the nozzle's (NozzleStandoff, NozzleTipDiameter, NozzleConeAngle, NozzleBodyDiameter,
    NozzleBodyLength, NozzleMargin, CheckPlate, NozzleMaxLean) and
    Deflection (mm chordal deflection for tessellating the components, 0 = automatic). Outputs:
    Shape (a compound of one sub-compound per layer, component by component in build order and
    bottom to top, each holding one closed wire per loop of its outline, then a face per region
    where it stands on nothing, on the plane below it: the view provider colours the outlines by
    component and the faces red), LayerCount, MinThickness, MaxThickness, DepositedVolume,
    MaterialVolume, PartVolume, MaxVolumeDifferenceFound, LayersOverVolumeDifference,
    WorstUnsupportedArea, WorstUnsupportedLayer, ComponentLayerCounts (tree order), BuildOrder (the
    components in the order they start), Sequence (the layers in deposition order, checked against
    the nozzle: NozzleStandoff, NozzleTipDiameter, NozzleConeAngle, NozzleBodyDiameter,
    NozzleBodyLength, NozzleMargin, CheckPlate), ComponentSwitches, the layers deposited with the
    nozzle leaned from their normal to clear (LeanedLayers; their axes in LayerToolAxes), the
    layers whose nozzle still meets what is deposited (CollidingLayers and, per collision,
    CollisionLayers, CollisionObstacles, CollisionPoints, CollisionNozzlePoints), the holes deposited solid to drill afterwards
    (FilledHoleCount, FilledVolume and, per hole, FilledHoleComponents, FilledHoleCentres,
    FilledHoleAxes, FilledHoleDiameters, FilledHoleLengths) and, per layer, LayerComponents,
    LayerOrigins, LayerNormals, LayerToolAxes, LayerMinThicknesses, LayerMaxThicknesses,
    LayerVolumeDifferences, LayerUnsupportedAreas.

    The paths are planned in the same computation; the ``Toolpath`` object linked to this one
    shows them. The full result stays in memory only (``slice_result()``)."""

    TYPE = "MultiAxisSlicer::Layers"
    VIEW_PROVIDER = "ViewProviderLayers"
    PROPERTY_NAMES = _names(
        *[(param, prop) for prop, _, param, _, _ in _SLICE_PROPERTIES if "_" in param],
        ("fill_holes_up_to", "FillHoles"), ("deflection", "Deflection")) + (
        (r"\boverlap\b(?= must| [0-9])", "Overlap"), (r"\binfill\b(?= must)", "Infill"))
    PARAMETERS = _grouped([(prop, group) for prop, group, _, _, _ in _SLICE_PROPERTIES] +
                          [("Deflection", "Layers")])

    @staticmethod
    def shown_on_open(obj):
        # A build preview of them takes their place, as the Build preview command leaves it.
        return not any(is_build_preview(o) for o in obj.InList)

    @staticmethod
    def ensure_properties(obj):
        _add_property(obj, "App::PropertyLink", "Decomposition", "Layers",
                      "Decomposition object whose part is sliced, component by component")
        _add_property(obj, "App::PropertyLinkGlobal", "Source", "Layers",
                      "A closed mesh (Mesh feature) sliced in place of a Decomposition: split at "
                      "section planes where its centroidal axis turns (see SplitMesh)")
        _add_property(obj, "App::PropertyLink", "Axis", "Layers",
                      "A CentroidalAxis object over that mesh (which then need not be set as "
                      "Source): the mesh's axis takes its Step, DistanceThreshold, Epsilon and "
                      "BreakAngle (none: derived)")
        # A document saved before the nozzle could lean was computed with it coaxial: it keeps
        # that (NozzleMaxLean 0, each tool axis its layer's normal) until the user changes it;
        # one saved before the layers' tilt was bounded keeps them unbounded (MaxTilt 180).
        computed_coaxial = "LayerCount" in obj.PropertiesList
        for prop, group, name, type_id, doc in _SLICE_PROPERTIES:
            if type_id == "App::PropertyEnumeration":
                if _add_property(obj, type_id, prop, group, doc):
                    setattr(obj, prop, INFILL_PATTERNS)
                    setattr(obj, prop, mas.SLICE_DEFAULTS[name])
            elif (_add_property(obj, type_id, prop, group, doc, mas.SLICE_DEFAULTS[name]) and
                  computed_coaxial):
                if prop == "NozzleMaxLean":
                    obj.NozzleMaxLean = 0.0
                elif prop == "MaxTilt":
                    obj.MaxTilt = 180.0
        _add_property(obj, "App::PropertyLength", "Deflection", "Layers",
                      "Chordal deflection for tessellating the components (0 = automatic)", 0.0)
        result = "Result"
        for type_id, prop, doc, default in (
                ("App::PropertyInteger", "LayerCount", "Number of layers", 0),
                ("App::PropertyLength", "MinThickness", "Least thickness on any layer", 0.0),
                ("App::PropertyLength", "MaxThickness", "Greatest thickness on any layer", 0.0),
                ("App::PropertyVolume", "DepositedVolume", "Volume of all layers (mm^3)", 0.0),
                ("App::PropertyVolume", "MaterialVolume",
                 "Volume of the part between the layers' planes (mm^3)", 0.0),
                ("App::PropertyVolume", "PartVolume", "Volume of the part (mm^3)", 0.0),
                ("App::PropertyFloat", "MaxVolumeDifferenceFound",
                 "Greatest volumetric difference of a layer (fraction of its volume)", 0.0),
                ("App::PropertyInteger", "LayersOverVolumeDifference",
                 "Layers over MaxVolumeDifference even at MinLayer (a dome's cap)", 0),
                ("App::PropertyArea", "WorstUnsupportedArea",
                 "Largest area of a layer outside the one below grown by the overhang allowance",
                 0.0),
                ("App::PropertyInteger", "WorstUnsupportedLayer",
                 "Index of the layer with that area (-1: none)", -1),
                ("App::PropertyIntegerList", "ComponentLayerCounts",
                 "Number of layers of each component (tree order)", None),
                ("App::PropertyIntegerList", "BuildOrder",
                 "The components in the order they start (the layers' order)", None),
                ("App::PropertyIntegerList", "Sequence",
                 "The layers in the order they are deposited: a component is left for another "
                 "where going on would put it in the nozzle's way", None),
                ("App::PropertyInteger", "ComponentSwitches",
                 "Consecutive layers of two components in the Sequence", 0),
                ("App::PropertyInteger", "LeanedLayers",
                 "Layers deposited with the nozzle leaned from their normal, where along it the "
                 "nozzle would meet the plate or what is deposited (NozzleMaxLean)", 0),
                ("App::PropertyInteger", "CollidingLayers",
                 "Layers whose nozzle meets what is deposited before them in the Sequence "
                 "(no order or lean found clears them)",
                 0),
                ("App::PropertyIntegerList", "CollisionLayers",
                 "Each colliding layer", None),
                ("App::PropertyIntegerList", "CollisionObstacles",
                 "The deposited layer each one's nozzle meets (-1: the build plate)", None),
                ("App::PropertyVectorList", "CollisionPoints",
                 "Where each one's nozzle meets it", None),
                ("App::PropertyVectorList", "CollisionNozzlePoints",
                 "The deposit point each one's nozzle stands over then", None),
                ("App::PropertyInteger", "FilledHoleCount",
                 "Holes deposited solid, to be drilled afterwards (FillHoles)", 0),
                ("App::PropertyVolume", "FilledVolume",
                 "Material those holes add (mm^3)", 0.0),
                ("App::PropertyIntegerList", "FilledHoleComponents",
                 "Component of each hole to drill", None),
                ("App::PropertyVectorList", "FilledHoleCentres",
                 "Middle of each hole to drill, along its axis", None),
                ("App::PropertyVectorList", "FilledHoleAxes",
                 "Axis of each hole to drill (unit)", None),
                ("App::PropertyFloatList", "FilledHoleDiameters",
                 "Diameter of each hole to drill (mm)", None),
                ("App::PropertyFloatList", "FilledHoleLengths",
                 "Length of each hole to drill, along its axis (mm)", None),
                ("App::PropertyIntegerList", "LayerComponents",
                 "Component of each layer", None),
                ("App::PropertyVectorList", "LayerOrigins",
                 "A point on each layer's plane (its top)", None),
                ("App::PropertyVectorList", "LayerNormals",
                 "Each layer's normal (unit)", None),
                ("App::PropertyVectorList", "LayerToolAxes",
                 "Each layer's tool axis: its normal, or the nozzle leaned from it (unit)", None),
                ("App::PropertyFloatList", "LayerMinThicknesses",
                 "Each layer's least thickness (mm)", None),
                ("App::PropertyFloatList", "LayerMaxThicknesses",
                 "Each layer's greatest thickness (mm)", None),
                ("App::PropertyFloatList", "LayerVolumeDifferences",
                 "Each layer's volumetric difference (fraction of its volume)", None),
                ("App::PropertyFloatList", "LayerUnsupportedAreas",
                 "Each layer's area outside the one below grown by the overhang allowance (mm^2; "
                 "the red faces)", None)):
            if (_add_property(obj, type_id, prop, result, doc, default, _OUTPUT) and
                    prop == "LayerToolAxes" and computed_coaxial):
                obj.LayerToolAxes = list(obj.LayerNormals)

    @staticmethod
    def not_applicable(obj):
        """The parameters that do not apply to `obj` as it is: a Decomposition's part is a solid,
        sliced as decomposed (SplitMesh and AvoidCollisions are a mesh's); a mesh is not
        tessellated (Deflection) and has no BREP holes to fill (FillHoles)."""
        if getattr(obj, "Source", None) is None and getattr(obj, "Axis", None) is None:
            return ("SplitMesh", "AvoidCollisions")
        return ("Deflection", "FillHoles")

    @staticmethod
    def recompute(obj):
        """Properties -> engine -> Shape and the result properties. Raises on bad input."""
        result = slice_result(obj)
        stats = result.stats
        layers = result.layers
        obj.LayerOrigins = [FreeCAD.Vector(layer.origin) for layer in layers]
        obj.LayerNormals = [FreeCAD.Vector(layer.normal) for layer in layers]
        obj.LayerToolAxes = [result.tool_axis(i) for i in range(len(layers))]
        obj.LayerMinThicknesses = [layer.min_thickness for layer in layers]
        obj.LayerMaxThicknesses = [layer.max_thickness for layer in layers]
        obj.LayerVolumeDifferences = [layer.volume_difference for layer in layers]
        obj.LayerUnsupportedAreas = [layer.unsupported_area for layer in layers]
        obj.ComponentLayerCounts = [c["layer_count"] for c in result.components]
        obj.BuildOrder = result.build_order
        obj.Sequence = result.sequence
        obj.ComponentSwitches = stats["component_switches"]
        obj.LeanedLayers = stats["leaned_layers"]
        collisions = result.collisions
        obj.CollidingLayers = len(collisions)
        obj.CollisionLayers = [c.layer for c in collisions]
        obj.CollisionObstacles = [c.obstacle_layer for c in collisions]
        obj.CollisionPoints = [c.obstacle for c in collisions]
        obj.CollisionNozzlePoints = [c.nozzle_at for c in collisions]
        obj.LayerCount = len(layers)
        obj.MinThickness = stats["min_thickness_mm"]
        obj.MaxThickness = stats["max_thickness_mm"]
        obj.DepositedVolume = stats["deposited_volume_mm3"]
        obj.MaterialVolume = stats["material_volume_mm3"]
        obj.PartVolume = stats["part_volume_mm3"]
        obj.MaxVolumeDifferenceFound = stats["max_volume_difference"]
        obj.LayersOverVolumeDifference = stats["layers_over_volume_difference"]
        obj.WorstUnsupportedArea = stats["worst_unsupported_area_mm2"]
        obj.WorstUnsupportedLayer = stats["worst_unsupported_layer"]
        holes = result.filled_holes
        obj.FilledHoleCount = len(holes)
        obj.FilledVolume = stats["filled_volume_mm3"]
        obj.FilledHoleComponents = [h.component for h in holes]
        obj.FilledHoleCentres = [FreeCAD.Vector(h.centre) for h in holes]
        obj.FilledHoleAxes = [FreeCAD.Vector(h.axis) for h in holes]
        obj.FilledHoleDiameters = [h.diameter for h in holes]
        obj.FilledHoleLengths = [h.length for h in holes]
        for h in holes:
            FreeCAD.Console.PrintMessage(
                "{}: deposited solid, to drill afterwards: a hole {:.6g} mm across, {:.6g} mm "
                "long, at ({:.6g}, {:.6g}, {:.6g}) along ({:.6g}, {:.6g}, {:.6g}) (component "
                "{})\n".format(obj.Label, h.diameter, h.length, *h.centre, *h.axis, h.component))
        for note in result.notes:
            FreeCAD.Console.PrintWarning("{}: {}\n".format(obj.Label, note))
        if collisions:
            shown = collisions[:10]
            FreeCAD.Console.PrintWarning(
                "{}: the nozzle meets what is deposited on {} layer(s), which no order or lean "
                "found clears: {}{}\n".format(
                    obj.Label, len(collisions), "; ".join(
                        "layer {} meets {} at ({:.4g}, {:.4g}, {:.4g})".format(
                            c.layer, "the build plate" if c.obstacle_layer < 0 else
                            "layer {}".format(c.obstacle_layer), *c.obstacle) for c in shown),
                    "; ..." if len(collisions) > len(shown) else ""))
            branches = sorted({result.decomposition[layers[c.layer].component].branch
                               for c in collisions if layers[c.layer].component > 0}
                              if result.decomposition is not None else ())
            if branches:
                FreeCAD.Console.PrintWarning(
                    "{}: those layers' components are axis branch(es) {} of '{}': added to its "
                    "KeepBranches, they are built in their fathers (features."
                    "keep_unreachable_branches does so, as the Slice command does for a solid it "
                    "decomposes)\n".format(obj.Label, ", ".join(str(b) for b in branches),
                                            obj.Decomposition.Label))
        FreeCAD.Console.PrintMessage(
            "{}: {} layers in {} component(s), started in the order {}; worst unsupported area "
            "{:.3g} mm^2{}\n".format(
                obj.Label, len(layers), len(result.components),
                ", ".join(str(c) for c in result.build_order),
                stats["worst_unsupported_area_mm2"],
                " (layer {})".format(stats["worst_unsupported_layer"])
                if stats["worst_unsupported_layer"] >= 0 else ""))
        if stats["layers_over_volume_difference"]:
            FreeCAD.Console.PrintWarning(
                "{}: {} layer(s) over MaxVolumeDifference {:g} even at MinLayer (worst {:.3g}); "
                "kept at MinLayer\n".format(obj.Label, stats["layers_over_volume_difference"],
                                            obj.MaxVolumeDifference,
                                            stats["max_volume_difference"]))
        # LayerComponents before Shape: the view provider colours the layers when Shape changes.
        obj.LayerComponents = [layer.component for layer in layers]
        obj.Shape = layers_shape(result)


class ToolpathFeature(_EngineFeature):
    """Proxy of a ``Part::FeaturePython`` showing the deposition paths of a ``Layers`` object.

    Inputs: Layers (the Layers object, whose computation planned the paths), ShowTravel (also show
    the travel moves between deposit paths). Outputs: Shape (a compound of one sub-compound per
    kind of path: contours, infill, centre lines, travel (empty unless ShowTravel), each holding
    that kind's polylines in deposition order; the view provider colours them per kind),
    PathCounts (per kind, in that order), PathCount (deposit paths), PathLength (deposited),
    TravelLength, CentreLinePasses (regions narrower than a bead, run as one centre line),
    UnfilledFeatures (too small even for that), UncoveredArea (with the Layers' MeasureCoverage)."""

    TYPE = "MultiAxisSlicer::Toolpath"
    VIEW_PROVIDER = "ViewProviderToolpath"

    @staticmethod
    def shown_on_open(obj):
        layers = getattr(obj, "Layers", None)
        return layers is None or LayersFeature.shown_on_open(layers)

    @staticmethod
    def ensure_properties(obj):
        group = "Toolpath"
        _add_property(obj, "App::PropertyLink", "Layers", group,
                      "Layers object whose paths are shown")
        _add_property(obj, "App::PropertyBool", "ShowTravel", group,
                      "Also show the travel moves between deposit paths", False)
        result = "Result"
        for type_id, prop, doc, default in (
                ("App::PropertyInteger", "PathCount", "Number of deposit paths", 0),
                ("App::PropertyIntegerList", "PathCounts",
                 "Paths shown per kind: contour, infill, centre line, travel", None),
                ("App::PropertyLength", "PathLength", "Length of all deposit paths", 0.0),
                ("App::PropertyLength", "TravelLength", "Length of all travel moves", 0.0),
                ("App::PropertyInteger", "CentreLinePasses",
                 "Regions narrower than a bead, deposited as one centre line", 0),
                ("App::PropertyInteger", "UnfilledFeatures",
                 "Features too small even for a centre line, left unfilled", 0),
                ("App::PropertyArea", "UncoveredArea",
                 "Area the beads leave uncovered, all layers (0 unless the Layers object's "
                 "MeasureCoverage is on)", 0.0)):
            _add_property(obj, type_id, prop, result, doc, default, _OUTPUT)

    @staticmethod
    def recompute(obj):
        """The Layers object's result -> Shape and the result properties. Raises on bad input."""
        layers = _check_link(obj, "Layers", is_layers, "Layers")
        result = slice_result(layers, computed=True)
        stats = result.stats
        shape, counts, deposits = toolpath_shape(result, obj.ShowTravel)
        obj.PathCount = deposits
        obj.PathLength = stats["deposit_length_mm"]
        obj.TravelLength = stats["travel_length_mm"]
        obj.CentreLinePasses = stats["centre_line_passes"]
        obj.UnfilledFeatures = stats["unfilled_features"]
        uncovered = [result.layer_report(i)["uncovered_area_mm2"]
                     for i in range(len(result.layers))]
        obj.UncoveredArea = sum(a for a in uncovered if a > 0.0)
        if stats["unfilled_features"]:
            FreeCAD.Console.PrintWarning(
                "{}: {} feature(s) too small for a bead left unfilled\n".format(
                    obj.Label, stats["unfilled_features"]))
        # PathCounts before Shape: the view provider colours the paths when Shape changes.
        obj.PathCounts = counts
        obj.Shape = shape


def is_layers(obj):
    return getattr(getattr(obj, "Proxy", None), "Type", None) == LayersFeature.TYPE


def is_toolpath(obj):
    return getattr(getattr(obj, "Proxy", None), "Type", None) == ToolpathFeature.TYPE


# ---- the build preview: BuildPreview ----------------------------------------------------------


# The least length the preview draws a nozzle's tip radius or cone with (mm), well over OCCT's
# confusion tolerance (1e-7 mm).
_DRAWN_LENGTH_MM = 1e-4


def nozzle_solids(standoff, tip_diameter, cone_angle, body_diameter, body_length, point, axis):
    """The nozzle the build sequence is checked against (``Nozzle.hpp``, Eq. 10), as Part solids
    standing on the deposit point `point` along the tool axis `axis` (FreeCAD vectors; mm and
    degrees): nothing for the first `standoff` (the stream and the beam or arc), then the tip, a
    cone frustum `tip_diameter` across at its face widening at `cone_angle` (half-angle) until it
    is `body_diameter` across, then the body, a cylinder of that diameter `body_length` long.
    Returns [tip, body] ([body] when the tip is as wide as the body, or the cone shorter than
    ``_DRAWN_LENGTH_MM``; [] when the body is narrower or shorter than that: OCCT makes no cone,
    nor a circle, under its confusion tolerance, and slicing takes a tip 1e-9 mm across, or a cone
    angle of 89.9999999 degrees). A tip narrower than that is drawn as a point, the cone as long
    as the tip given makes it. Raises ValueError for a zero axis or a cone that would not close
    (an angle outside 0 to 90 degrees)."""
    axis = FreeCAD.Vector(axis)
    if axis.Length <= 0.0:
        raise ValueError("nozzle_solids(): the tool axis is a zero vector")
    axis.normalize()
    if body_diameter > tip_diameter and not 0.0 < cone_angle < 90.0:
        raise ValueError("nozzle_solids(): the cone angle must be between 0 and 90 degrees, "
                         "got {}".format(cone_angle))
    face = FreeCAD.Vector(point) + axis * standoff
    tip_radius, body_radius = tip_diameter / 2.0, body_diameter / 2.0
    solids = []
    cone_length = 0.0
    if body_radius > tip_radius:
        cone_length = (body_radius - tip_radius) / math.tan(math.radians(cone_angle))
        if cone_length >= _DRAWN_LENGTH_MM and body_radius >= _DRAWN_LENGTH_MM:
            drawn_tip = tip_radius if tip_radius >= _DRAWN_LENGTH_MM else 0.0  # else a point
            solids.append(Part.makeCone(drawn_tip, body_radius, cone_length, face, axis))
        else:
            cone_length = 0.0  # a flat step from the tip to the body
    if body_radius >= _DRAWN_LENGTH_MM and body_length >= _DRAWN_LENGTH_MM:
        solids.append(Part.makeCylinder(body_radius, body_length, face + axis * cone_length, axis))
    return solids


def layer_prism(layer):
    """A deposited layer as the build preview draws it: each region's face on the layer's plane
    swept back along its normal by the layer's greatest thickness (a layer between planes that are
    not parallel reaches that far only at its thick side: drawn so, no gap shows over the layer
    below). A region OCCT cannot make a face of is drawn as its outline. A compound."""
    back = FreeCAD.Vector(layer.normal) * -layer.max_thickness
    pieces = []
    for region in layer.regions:
        face = _region_face(region, layer.origin, layer.normal)
        if face is None:
            continue
        pieces.append(face.extrude(back) if isinstance(face, Part.Face) else face)
    return Part.makeCompound(pieces)


def layer_triangles(layer):
    """(points, triangles) of ``layer_prism(layer)``'s surface, as ``shape_triangles`` gives a
    shape's: [(x, y, z)] and [(i, j, k)], counter-clockwise seen from outside, made by the engine
    from the layer's regions (``MultiAxisSlicer._engine.prism_mesh``: each region's face by ear
    clipping, the same face its greatest thickness below, a wall along each edge) in tens of
    microseconds, where OCCT's face making and meshing took about two milliseconds a region."""
    d = layer._data
    return mas._require_engine().prism_mesh(d["regions"], d["origin"], d["normal"],
                                            layer.max_thickness)


def build_plate_face(result):
    """The build plate under a slicing result's part, as the build preview draws it: a rectangle
    on the plate's plane (``result.plate``) covering every layer's outlines seen along its normal,
    grown all round by a tenth of its longer side or 5 mm, whichever is more, its sides along the
    plate's projections of X and Y (X and Y themselves for a plate facing +Z). A face."""
    origin, normal = result.plate
    normal = FreeCAD.Vector(normal).normalize()
    u = FreeCAD.Vector(1, 0, 0)
    u = u - normal * normal.dot(u)
    if u.Length < 1e-6:  # a plate facing X
        u = FreeCAD.Vector(0, 1, 0) - normal * normal.y
    u.normalize()
    v = normal.cross(u)
    us, vs = [], []
    for layer in result.layers:
        for loop in layer.loops():
            for p in loop:
                d = p - origin
                us.append(d.dot(u))
                vs.append(d.dot(v))
    if not us:
        us = vs = [0.0]
    grow = max(5.0, 0.1 * max(max(us) - min(us), max(vs) - min(vs)))
    u0, u1, v0, v1 = min(us) - grow, max(us) + grow, min(vs) - grow, max(vs) + grow
    corners = [origin + u * a + v * b for a, b in ((u0, v0), (u1, v0), (u1, v1), (u0, v1))]
    return Part.Face(Part.makePolygon(corners + corners[:1]))


def shape_triangles(shape, tolerance=0.1, polygonal=False):
    """(points, triangles) covering the faces of `shape`: [(x, y, z)] and [(i, j, k)] indices
    into points. What the build preview draws: a convex planar face of four edges (a prism's
    side) is split into two triangles along a diagonal, counter-clockwise seen from the side the
    face faces; any other face is tessellated by OCCT within `tolerance` mm (a planar polygon's
    triangles do not depend on it), in its own orientation. With `polygonal` (every edge of
    `shape` straight, as in a layer's solid) any other planar face is triangulated by the engine
    from its corners (``MultiAxisSlicer._engine.triangulate``: tens of microseconds where OCCT's
    meshing took about 0.7 ms a face), counter-clockwise seen from the side it faces too."""
    engine = mas._require_engine() if polygonal else None
    points, triangles = [], []
    for face in shape.Faces:
        wires = face.Wires
        surface = face.Surface
        planar = isinstance(surface, Part.Plane)
        # The way the face faces: its plane's normal, turned for a reversed face.
        normal = (surface.Axis * (-1 if face.Orientation == "Reversed" else 1)) if planar else None
        corners = wires[0].OrderedVertexes if len(wires) == 1 else []
        if len(corners) == 4 and planar and len(face.Edges) == 4:
            p = [v.Point for v in corners]
            turns = [(p[(i + 1) % 4] - p[i]).cross(p[(i + 2) % 4] - p[(i + 1) % 4])
                     for i in range(4)]
            if all(t.dot(turns[0]) > 0.0 for t in turns):  # convex
                base = len(points)
                points += [(q.x, q.y, q.z) for q in p]
                if turns[0].dot(normal) < 0.0:
                    triangles += [(base, base + 2, base + 1), (base, base + 3, base + 2)]
                else:
                    triangles += [(base, base + 1, base + 2), (base, base + 2, base + 3)]
                continue
        if polygonal:
            if planar:
                outer = face.OuterWire
                loops = [[v.Point for v in w.OrderedVertexes]
                         for w in [outer] + [w for w in wires if not w.isSame(outer)]]
                base = len(points)
                points += [(q.x, q.y, q.z) for loop in loops for q in loop]
                triangles += [(base + a, base + b, base + c)
                              for a, b, c in engine.triangulate(loops, normal)]
                continue
        face_points, face_triangles = face.tessellate(tolerance)
        base = len(points)
        points += [(q.x, q.y, q.z) for q in face_points]
        triangles += [(base + a, base + b, base + c) for a, b, c in face_triangles]
    return points, triangles


class BuildPreviewFeature(_EngineFeature):
    """Proxy of an ``App::FeaturePython`` with a Shape, showing a ``Layers`` object's build as
    it stands after one step of its deposition sequence, with the nozzle at that step's layer.
    (Not a ``Part::FeaturePython``: its view provider draws the Shape itself, each layer's
    triangles made once, where Part's took seconds a step on a part of a thousand layers.)

    Inputs: Layers (the Layers object), Step (1 to the number of layers: the layers of its Sequence
    deposited so far, the last of them the one being deposited; 0: the last step, the whole build),
    ShowNozzle, ShowPaths, ShowPlate. Outputs: Shape (a compound of six: the layers deposited before
    the step's, in deposition order, each a compound of its regions swept back along its normal by
    its greatest thickness; the step's layer so; the nozzle, its tip and body solids, standing on
    the deposit point along the layer's tool axis, at the point where it meets what is deposited
    when the layer collides, else at the start of the layer's first deposit path; the step's deposit
    paths, a polyline each, in the order the nozzle follows them; the step's layer's unsupported
    regions, a face each on the plane below it, where it stands on nothing; the build plate,
    ``build_plate_face``; the nozzle's, the paths' and the plate's compounds empty without
    ShowNozzle, ShowPaths and ShowPlate), StepCount, ShownStep, Layer, Component, ToolAxis, Lean
    (its angle from the layer's normal), NozzlePoint, Collides, CollisionObstacle (the layer it
    meets, -1 the build plate; -2 when it collides with nothing), ShownComponents (the component of
    each layer shown, in the Shape's order), UnsupportedArea (the step's layer's, mm²), FlaggedSteps
    (the steps whose layer is leaned for or collides), WorstStep (the step whose layer stands most
    on nothing, 0 when none does). The nozzle is the Layers object's (NozzleStandoff, ...)."""

    TYPE = "MultiAxisSlicer::BuildPreview"
    VIEW_PROVIDER = "ViewProviderBuildPreview"
    PROPERTY_NAMES = _names(("step", "Step"))
    PARAMETERS = (("Build preview", ("Step", "ShowNozzle", "ShowPaths", "ShowPlate")),)

    @staticmethod
    def ensure_properties(obj):
        group = "Build preview"
        _add_property(obj, "App::PropertyLink", "Layers", group,
                      "Layers object whose build is shown")
        _add_property(obj, "App::PropertyInteger", "Step", group,
                      "Step of the deposition sequence shown (1 to the number of layers): the "
                      "layers deposited so far, the last the one being deposited; 0: the last", 0)
        _add_property(obj, "App::PropertyBool", "ShowNozzle", group,
                      "Show the nozzle at the step's layer, along its tool axis", True)
        _add_property(obj, "App::PropertyBool", "ShowPaths", group,
                      "Show the step's deposit paths (bead centre lines) on its layer", True)
        _add_property(obj, "App::PropertyBool", "ShowPlate", group,
                      "Show the build plate the part stands on (an obstacle to the nozzle too)",
                      True)
        _add_property(obj, "Part::PropertyPartShape", "Shape", "Base",
                      "The layers deposited so far, the step's layer, the nozzle and the plate",
                      None, _OUTPUT)
        result = "Result"
        for type_id, prop, doc, default in (
                ("App::PropertyInteger", "StepCount", "Number of steps (layers) in the sequence",
                 0),
                ("App::PropertyInteger", "ShownStep", "The step shown (Step, or the last for 0)",
                 0),
                ("App::PropertyInteger", "Layer", "Index of the step's layer (the Layers "
                 "object's order)", -1),
                ("App::PropertyInteger", "Component", "Component of the step's layer", -1),
                ("App::PropertyVector", "ToolAxis", "The nozzle's axis at the step's layer", None),
                ("App::PropertyAngle", "Lean", "Angle of the tool axis from the layer's normal",
                 0.0),
                ("App::PropertyVector", "NozzlePoint",
                 "Deposit point the nozzle is shown at", None),
                ("App::PropertyBool", "Collides",
                 "Whether the step's layer is one whose nozzle meets what is deposited", False),
                ("App::PropertyInteger", "CollisionObstacle",
                 "What the step's nozzle meets: a layer's index, -1 the build plate, -2 nothing",
                 -2),
                ("App::PropertyIntegerList", "ShownComponents",
                 "Component of each layer shown, deposited first to the step's", None),
                ("App::PropertyArea", "UnsupportedArea",
                 "Area of the step's layer that stands on nothing", 0.0),
                ("App::PropertyIntegerList", "FlaggedSteps",
                 "The steps whose layer the nozzle leans for or collides at", None),
                ("App::PropertyInteger", "WorstStep",
                 "The step whose layer stands most on nothing (0: every layer rests on the one "
                 "below)", 0)):
            _add_property(obj, type_id, prop, result, doc, default, _OUTPUT)

    def recompute(self, obj):
        """The Layers object's result at Step -> Shape and the result properties. Raises on bad
        input (no Layers, a Step past the sequence)."""
        layers_obj = _check_link(obj, "Layers", is_layers, "Layers")
        result = slice_result(layers_obj, computed=True)
        sequence = list(result.sequence)
        count = len(sequence)
        if count == 0:
            raise ValueError("{}: '{}' has no layers to deposit".format(obj.Label,
                                                                         layers_obj.Label))
        if not 0 <= obj.Step <= count:
            raise ValueError("{}: Step must be 0 (the last) to {} (the layers of '{}'), got "
                             "{}".format(obj.Label, count, layers_obj.Label, obj.Step))
        step = obj.Step or count
        index = sequence[step - 1]
        layer = result.layers[index]
        # Kept per slicing result: the prisms made so far (a step reuses those drawn before),
        # the steps leaned or colliding, the step standing most on nothing and the plate.
        cache = getattr(self, "_cache", None)
        if cache is None or cache.result is not result:
            flagged = set(result.leaned_layers()) | {c.layer for c in result.collisions}
            areas = [result.layers[i].unsupported_area for i in sequence]
            worst = max(range(count), key=areas.__getitem__)
            cache = self._cache = types.SimpleNamespace(
                result=result, prisms={}, layer_of={},
                flagged=[k + 1 for k, i in enumerate(sequence) if i in flagged],
                worst=worst + 1 if areas[worst] > 0.0 else 0,
                plate=build_plate_face(result) if result.plate is not None else None)
        prisms = cache.prisms

        def prism(i):
            if i not in prisms:
                prisms[i] = layer_prism(result.layers[i])
                cache.layer_of[prisms[i].hashCode()] = i
            return prisms[i]

        axis = FreeCAD.Vector(result.tool_axis(index))
        collision = next((c for c in result.collisions if c.layer == index), None)
        deposits = [p for p in result.paths(index) if p.deposit and p.points]
        if collision is not None:  # where it meets what is deposited
            point = FreeCAD.Vector(collision.nozzle_at)
        else:  # where the layer starts
            point = FreeCAD.Vector(deposits[0].points[0] if deposits else layer.origin)
        nozzle = []
        if obj.ShowNozzle:
            nozzle = nozzle_solids(
                layers_obj.NozzleStandoff.Value, layers_obj.NozzleTipDiameter.Value,
                layers_obj.NozzleConeAngle.Value, layers_obj.NozzleBodyDiameter.Value,
                layers_obj.NozzleBodyLength.Value, point, axis)
        paths = []
        if obj.ShowPaths:
            paths = [w for w in (_polyline(p.points) for p in deposits) if w is not None]
        unsupported = [f for f in (_region_face(r, layer.lower_origin, layer.lower_normal)
                                   for r in layer.unsupported_regions)
                       if f is not None]
        normal = FreeCAD.Vector(layer.normal)
        obj.StepCount = count
        obj.ShownStep = step
        obj.Layer = index
        obj.Component = layer.component
        obj.ToolAxis = axis
        obj.Lean = math.degrees(axis.getAngle(normal)) if axis.Length > 0 else 0.0
        obj.NozzlePoint = point
        obj.Collides = collision is not None
        obj.CollisionObstacle = collision.obstacle_layer if collision is not None else -2
        obj.UnsupportedArea = layer.unsupported_area
        obj.FlaggedSteps = cache.flagged
        obj.WorstStep = cache.worst
        # ShownComponents before Shape: the view provider draws the layers when Shape changes.
        obj.ShownComponents = [result.layers[i].component for i in sequence[:step]]
        obj.Shape = Part.makeCompound([
            Part.makeCompound([prism(i) for i in sequence[:step - 1]]), prism(index),
            Part.makeCompound(nozzle), Part.makeCompound(paths),
            Part.makeCompound(unsupported),
            Part.makeCompound([cache.plate] if obj.ShowPlate and cache.plate is not None else [])])

    def prism_triangles(self, prism):
        """(points, triangles) drawing `prism`, a layer's solid in this object's Shape, made by
        the engine (``layer_triangles``); None when it is not one this object made since the
        document was opened (then ``shape_triangles(prism)`` draws it)."""
        cache = getattr(self, "_cache", None)
        i = cache.layer_of.get(prism.hashCode()) if cache is not None else None
        if i is None or not cache.prisms[i].isSame(prism):
            return None
        return layer_triangles(cache.result.layers[i])


def is_build_preview(obj):
    return getattr(getattr(obj, "Proxy", None), "Type", None) == BuildPreviewFeature.TYPE


def layers_and_toolpaths(layers):
    """The Layers object `layers` and the Toolpath objects showing its paths: what a build
    preview of it takes the place of in the view."""
    return [layers] + [o for o in layers.InList if is_toolpath(o)]


def make_build_preview(layers, step=0, show_nozzle=True, show_paths=True, show_plate=True,
                       name="BuildPreview", doc=None):
    """Adds a ``BuildPreview`` object showing the build of the ``Layers`` object ``layers`` (a
    ``Toolpath`` object stands for its Layers) after ``step`` steps of its sequence (0: all), the
    nozzle at that step's layer and its deposit paths, and the build plate, to ``doc`` (default:
    the layers' document) and returns it; recompute the document to compute it. Nothing is
    changed on the layers."""
    if is_toolpath(layers):
        if layers.Layers is None:
            raise ValueError("make_build_preview(): the Toolpath '{}' has no Layers".format(
                layers.Label))
        layers = layers.Layers
    if not is_layers(layers):
        raise TypeError("make_build_preview() needs a Layers or Toolpath object, got {}".format(
            getattr(layers, "TypeId", type(layers).__name__)))
    if isinstance(step, bool) or not isinstance(step, int) or step < 0:
        raise ValueError("make_build_preview(): step must be a whole number, 0 (the last) or "
                         "more, got {!r}".format(step))
    if doc is None:
        doc = layers.Document
    obj = doc.addObject("App::FeaturePython", name)
    BuildPreviewFeature(obj)
    obj.Layers = layers
    obj.Step = step
    obj.ShowNozzle = bool(show_nozzle)
    obj.ShowPaths = bool(show_paths)
    obj.ShowPlate = bool(show_plate)
    if FreeCAD.GuiUp:
        _attach_view_provider(obj, BuildPreviewFeature.VIEW_PROVIDER)
    return obj


def _check_angles(values, parameters):
    """ValueError for a value of an angle property (`parameters`: (name, property type) pairs)
    beyond a turn either way, which the property would clamp silently."""
    for name, type_id in parameters:
        if type_id == "App::PropertyAngle" and not (-360.0 <= values[name] <= 360.0):
            raise ValueError("{} must be between -360 and 360 degrees, got {}".format(
                name, values[name]))


def _slice_property_values(params):
    """Checks make_slice()'s keyword arguments like ``MultiAxisSlicer.slice`` does and returns
    {property: value}. Raises TypeError / ValueError naming the bad one."""
    known = {name for _p, _g, name, _t, _d in _SLICE_PROPERTIES}
    unknown = sorted(set(params) - known)
    if unknown:
        raise TypeError("make_slice() got unknown parameter(s): {}".format(", ".join(unknown)))
    checked = mas.slicing._slice_params(dict(mas.SLICE_DEFAULTS, **params))
    # Properties would silently clamp what slice() reports: a negative length, an angle past a turn.
    mas._length(checked["min_feature"], "min_feature", allow_zero=True)
    _check_angles(checked, [(name, type_id) for _p, _g, name, type_id, _d in _SLICE_PROPERTIES])
    return {prop: checked[name] for prop, _g, name, _t, _d in _SLICE_PROPERTIES}


def make_slice(part, deflection=0.0, show_travel=False, name="Layers", toolpath_name="Toolpath",
               doc=None, **params):
    """Adds a ``Layers`` object slicing ``part`` and a ``Toolpath`` object showing its paths to
    ``doc`` (default: the part's document); returns (layers, toolpath). Recompute the document to
    compute them.

    ``part`` is a ``Decomposition`` object, whose part is sliced component by component (a solid),
    or a mesh object (``Mesh::Feature``), split at section planes where its centroidal axis turns,
    the axis' parameters derived (as ``MultiAxisSlicer.slice`` splits a mesh; ``split_mesh=False``:
    one component), or a ``CentroidalAxis`` object over a mesh, whose mesh is sliced so, along an
    axis with the object's parameters (the Layers' Axis). ``params``: the slicing parameters of
    ``MultiAxisSlicer.slice`` (min_layer, max_layer, max_volume_difference, eps_angle,
    overhang_angle, max_tilt, volume_samples, strict, fill_holes, bead_width, overlap,
    contour_count, infill, raster_angle, raster_angle_step, min_feature, measure_coverage, the
    nozzle's nozzle_standoff, nozzle_tip_diameter, nozzle_cone_angle, nozzle_body_diameter,
    nozzle_body_length, nozzle_margin, check_plate, nozzle_max_lean; mm and degrees, defaults
    ``MultiAxisSlicer.SLICE_DEFAULTS``), checked before anything is added. ``deflection``: mm for
    tessellating the components (0 = automatic; a mesh is sliced as it is, and takes none, nor
    ``fill_holes``, which needs a BREP's holes). ``show_travel``: the Toolpath also shows the travel
    moves. Nothing is changed on the decomposition, its source or the mesh.

    In the GUI they get their view providers (layers coloured by component, paths by kind)."""
    axis = is_centroidal_axis(part)
    mesh = part.Source if axis else part
    if axis and not is_mesh_part(mesh):
        raise TypeError("make_slice(): the CentroidalAxis object '{}' is not over a mesh{}: a "
                        "solid is sliced through a Decomposition object (make_decomposition("
                        "None, axis=...))".format(part.Label, "" if mesh is None else
                                                  " but over '{}'".format(mesh.Label)))
    of_mesh = is_mesh_part(mesh)
    if not (of_mesh or is_decomposition(part)):
        raise TypeError("make_slice() needs a Decomposition object or a mesh object, got {}".format(
            getattr(part, "TypeId", type(part).__name__)))
    values = _slice_property_values(params)
    deflection = mas._length(deflection, "deflection", allow_zero=True)
    if of_mesh:
        mas.slicing._check_mesh_params("make_slice", "'{}'".format(mesh.Label), deflection > 0.0,
                                       values["FillHoles"])
    if doc is None:
        doc = part.Document
    layers = doc.addObject("Part::FeaturePython", name)
    LayersFeature(layers)
    if axis:
        layers.Axis = part
    elif of_mesh:
        layers.Source = part
    else:
        layers.Decomposition = part
    for prop, value in values.items():
        setattr(layers, prop, value)
    layers.Deflection = deflection
    toolpath = doc.addObject("Part::FeaturePython", toolpath_name)
    ToolpathFeature(toolpath)
    toolpath.Layers = layers
    toolpath.ShowTravel = bool(show_travel)
    if FreeCAD.GuiUp:
        _attach_view_provider(layers, LayersFeature.VIEW_PROVIDER)
        _attach_view_provider(toolpath, ToolpathFeature.VIEW_PROVIDER)
    return layers, toolpath


# ---- the machine program: MachineProgram ------------------------------------------------------

# The machine parameters a MachineProgram object holds as properties: (property, gcode()
# parameter, property type, tooltip). Their defaults are MultiAxisSlicer.MACHINE_DEFAULTS.
_MACHINE_PROPERTIES = (
    ("AMin", "a_min", "App::PropertyAngle", "Least tilt of the table (A, about X)"),
    ("AMax", "a_max", "App::PropertyAngle", "Greatest tilt of the table (A, about X)"),
    ("CMin", "c_min", "App::PropertyFloat",
     "Least turn of the table (C, about its normal), degrees: far out for a table that turns "
     "without end"),
    ("CMax", "c_max", "App::PropertyFloat",
     "Greatest turn of the table (C, about its normal), degrees"),
    ("Feed", "feed", "App::PropertyFloat",
     "Deposition feed, mm/min, where the deposit is ReferenceThickness thick"),
    ("ReferenceThickness", "reference_thickness", "App::PropertyLength",
     "Deposit thickness at which the nozzle moves at Feed: faster where thinner, in proportion "
     "(0 = half-way between the thinnest and the thickest deposit)"),
    ("MaxFeedRatio", "max_feed_ratio", "App::PropertyFloat",
     "The feed stays within Feed / this to Feed x this as the thickness varies (1 = constant)"),
    ("Clearance", "clearance", "App::PropertyLength",
     "Retract along the tool axis between paths, and the margin round the part between "
     "components"),
    ("DepositOutput", "deposit_output", "App::PropertyInteger",
     "Digital output that switches deposition on and off (M62/M63 P)"),
    ("WorkOffsetX", "work_offset_x", "App::PropertyDistance",
     "Work offset G54's X: where the part's origin lies in the machine's frame, A and C at 0"),
    ("WorkOffsetY", "work_offset_y", "App::PropertyDistance", "Work offset G54's Y"),
    ("WorkOffsetZ", "work_offset_z", "App::PropertyDistance", "Work offset G54's Z"),
    ("RotPointX", "rot_point_x", "App::PropertyDistance",
     "xyzac-trt-kins' x-rot-point: C turns about the vertical line through (RotPointX, "
     "RotPointY)"),
    ("RotPointY", "rot_point_y", "App::PropertyDistance", "xyzac-trt-kins' y-rot-point"),
    ("RotPointZ", "rot_point_z", "App::PropertyDistance",
     "xyzac-trt-kins' z-rot-point: A tilts about the line along X through (RotPointY + "
     "RotOffsetY, RotPointZ + RotOffsetZ)"),
    ("RotOffsetY", "rot_offset_y", "App::PropertyDistance", "xyzac-trt-kins' y-offset"),
    ("RotOffsetZ", "rot_offset_z", "App::PropertyDistance", "xyzac-trt-kins' z-offset"),
    ("ToolLength", "tool_length", "App::PropertyDistance",
     "The nozzle's tool length offset (xyzac-trt-kins' tool-offset): the joints' Z is the tip's "
     "plus this"),
)

# The X Y Z travel limits (property, gcode() parameter, default when checked: the joints of
# LinuxCNC's sample xyzac-trt.ini), checked when CheckTravel is on; an infinite one (set from a
# script) is no limit.
_TRAVEL_LIMITS = (("XMin", "x_min", -200.0), ("XMax", "x_max", 200.0), ("YMin", "y_min", -100.0),
                  ("YMax", "y_max", 100.0), ("ZMin", "z_min", -120.0), ("ZMax", "z_max", 120.0))


def program_travel_shape(text):
    """A compound of polylines through the moves of `text` made with the deposition output off,
    one per run of such moves (from where the run starts)."""
    position = {"X": 0.0, "Y": 0.0, "Z": 0.0}
    on, started, run, wires = False, False, [], []

    def close_run():
        wire = _polyline(run)
        if wire is not None:
            wires.append(wire)
        run.clear()

    for line in text.splitlines():
        words = line.split("(", 1)[0].split()
        if not words:
            continue
        if words[0] == "M62":
            on = True
        elif words[0] in ("M63", "M65"):
            on = False
        elif words[0] in ("G0", "G1"):
            start = FreeCAD.Vector(position["X"], position["Y"], position["Z"])
            for word in words[1:]:
                if word[0] in position:
                    position[word[0]] = float(word[1:])
            end = FreeCAD.Vector(position["X"], position["Y"], position["Z"])
            if on:
                close_run()
            else:
                if not run and started:
                    run.append(start)
                run.append(end)
            started = True
    close_run()
    return Part.makeCompound(wires)


class MachineProgramFeature(_EngineFeature):
    """Proxy of a ``Part::FeaturePython`` holding the 5-axis G-code program that deposits a
    ``Layers`` object's layers (``MultiAxisSlicer.gcode``): the plan the machine runs.

    Inputs: Layers (the Layers object), the machine (AMin, AMax, CMin, CMax, Feed,
    ReferenceThickness, MaxFeedRatio, Clearance, DepositOutput; where the part sits and the table
    pivots: WorkOffsetX/Y/Z, RotPointX/Y/Z, RotOffsetY/Z, ToolLength), and its X Y Z travel
    (CheckTravel, XMin ... ZMax: checked when CheckTravel is on; an infinite limit is none).
    Outputs: Shape (the moves made
    with the deposition off, as polylines: retracts, approaches and the routes round the part
    between components; the Toolpath object shows the deposits), LineCount, DepositMoves,
    FeedLimitedMoves, Reorientations, ARange and CRange (the angles the program uses, [least,
    greatest], degrees), DepositLength, DepositTime (minutes), RapidLength,
    ReferenceThicknessUsed, XRange, YRange and ZRange (the machine's joints, mm), and the
    travel checked against the Layers' nozzle: CheckedRoutes, ReroutedTravels (ways within a
    component taken round the part), TravelCollisions (routes
    meeting what is deposited all the same, each warned of on the console and by a comment in the
    program). The program's text stays in memory only (``machine_program()``);
    ``export_gcode()`` and the Export G-code command write it to a file."""

    TYPE = "MultiAxisSlicer::MachineProgram"
    VIEW_PROVIDER = "ViewProviderMachineProgram"
    PROPERTY_NAMES = ((r"\bA's limits\b", "AMin and AMax"), (r"\bC's limits\b", "CMin and CMax"),
                      (r"\bfeed must\b", "Feed must"),
                      (r"\breference thickness\b", "ReferenceThickness"),
                      (r"\bmax feed ratio\b", "MaxFeedRatio"),
                      (r"\bclearance must\b", "Clearance must"),
                      (r"\bclearance (?=\S+ mm is more than)", "Clearance "),
                      (r"\bthe nozzle's margin\b", "the Layers' NozzleMargin"),
                      (r"\bthe deposition output\b", "DepositOutput"),
                      (r"\bdeposit_output\b", "DepositOutput"),
                      (r"\b([XYZ])'s travel limits\b", r"\1Min and \1Max"),
                      (r"\bthe ([XYZ]) limits\b", r"\1Min and \1Max"),
                      (r"\bthe greatest ([XYZ])\b", r"\1Max"),
                      (r"\bthe least ([XYZ])\b", r"\1Min"),
                      (r"\bthe work offset's ([XYZ])\b", r"WorkOffset\1"),
                      (r"\bthe rot point's ([XYZ])\b", r"RotPoint\1"),
                      (r"\bthe rot offset's ([YZ])\b", r"RotOffset\1"),
                      (r"\bthe tool length\b", "ToolLength"))
    PARAMETERS = _grouped(
        [(prop, "Machine") for prop, _, _, _ in _MACHINE_PROPERTIES] +
        [("CheckTravel", "Machine travel")] + [(prop, "Machine travel")
                                               for prop, _, _ in _TRAVEL_LIMITS])

    @staticmethod
    def ensure_properties(obj):
        group = "Machine program"
        _add_property(obj, "App::PropertyLink", "Layers", group,
                      "Layers object whose paths the program deposits, in its Sequence")
        for prop, name, type_id, doc in _MACHINE_PROPERTIES:
            _add_property(obj, type_id, prop, "Machine", doc, mas.MACHINE_DEFAULTS[name])
        _add_property(obj, "App::PropertyBool", "CheckTravel", "Machine travel",
                      "Check the program against the X Y Z travel limits (the joints' limits of "
                      "the machine's INI file): past one, the program is an error naming it",
                      False)
        for prop, _name, default in _TRAVEL_LIMITS:
            _add_property(obj, "App::PropertyDistance", prop, "Machine travel",
                          "{} of the machine's {} travel (the joint, with CheckTravel)".format(
                              "Least" if prop.endswith("Min") else "Greatest", prop[0]), default)
        result = "Result"
        for type_id, prop, doc, default in (
                ("App::PropertyInteger", "LineCount", "Lines of the program", 0),
                ("App::PropertyInteger", "DepositMoves", "Moves made with the deposition on", 0),
                ("App::PropertyInteger", "FeedLimitedMoves",
                 "Of those, moves held at a bound of the feed range (MaxFeedRatio)", 0),
                ("App::PropertyInteger", "Reorientations", "Moves that turn the table", 0),
                ("App::PropertyFloatList", "ARange",
                 "Least and greatest tilt the program uses (degrees)", None),
                ("App::PropertyFloatList", "CRange",
                 "Least and greatest turn the program uses (degrees)", None),
                ("App::PropertyLength", "DepositLength", "Length of the deposit moves", 0.0),
                ("App::PropertyFloat", "DepositTime",
                 "Time of the deposit moves at their feeds (minutes)", 0.0),
                ("App::PropertyLength", "RapidLength",
                 "Length of the rapid moves of the nozzle tip, in the part's frame", 0.0),
                ("App::PropertyLength", "ReferenceThicknessUsed",
                 "The deposit thickness at which the nozzle moves at Feed", 0.0),
                ("App::PropertyFloatList", "XRange",
                 "Least and greatest X the machine's joints take (mm; the work offset, rot "
                 "point and tool length as given)", None),
                ("App::PropertyFloatList", "YRange",
                 "Least and greatest Y the machine's joints take (mm)", None),
                ("App::PropertyFloatList", "ZRange",
                 "Least and greatest Z the machine's joints take (mm)", None),
                ("App::PropertyInteger", "CheckedRoutes",
                 "Routes between paths checked against the Layers' nozzle and build plate", 0),
                ("App::PropertyInteger", "ReroutedTravels",
                 "Ways within a component taken round the part instead, because they would "
                 "meet what is deposited", 0),
                ("App::PropertyInteger", "TravelCollisions",
                 "Routes whose nozzle meets what is deposited all the same (marked by warning "
                 "comments in the program)", 0)):
            _add_property(obj, type_id, prop, result, doc, default, _OUTPUT)

    @staticmethod
    def recompute(obj):
        """Properties -> engine -> Shape and the result properties. Raises on bad input."""
        program = machine_program(obj)
        s = program.stats
        obj.LineCount = s["lines"]
        obj.DepositMoves = s["deposit_moves"]
        obj.FeedLimitedMoves = s["feed_limited_moves"]
        obj.Reorientations = s["reorientations"]
        obj.ARange = list(s["a_range_deg"])
        obj.CRange = list(s["c_range_deg"])
        obj.DepositLength = s["deposit_length_mm"]
        obj.DepositTime = s["deposit_time_min"]
        obj.RapidLength = s["rapid_length_mm"]
        obj.ReferenceThicknessUsed = s["reference_thickness_mm"]
        obj.XRange = list(s["x_range_mm"])
        obj.YRange = list(s["y_range_mm"])
        obj.ZRange = list(s["z_range_mm"])
        obj.CheckedRoutes = s["checked_routes"]
        obj.ReroutedTravels = s["rerouted_travels"]
        obj.TravelCollisions = len(s["travel_collisions"])
        FreeCAD.Console.PrintMessage(
            "{}: {} lines, {} deposit moves ({} at a feed limit), A {:.6g} to {:.6g} deg, C {:.6g} "
            "to {:.6g} deg, deposit time {:.4g} min; {} routes checked against the nozzle, {} "
            "taken round the part\n".format(
                obj.Label, s["lines"], s["deposit_moves"], s["feed_limited_moves"],
                *s["a_range_deg"], *s["c_range_deg"], s["deposit_time_min"],
                s["checked_routes"], s["rerouted_travels"]))
        collisions = s["travel_collisions"]
        if collisions:
            def name(i, what):
                return what if i < 0 else "layer {}".format(i)

            lines = ["  on the way {} the nozzle meets {} near ({:.4g}, {:.4g}, {:.4g})".format(
                "off the part" if c["layer"] < 0 else "to layer {}".format(c["layer"]),
                name(c["obstacle_layer"], "the build plate"), *c["obstacle"])
                for c in collisions[:10]]
            if len(collisions) > 10:
                lines.append("  and {} more (warning comments in the program)".format(
                    len(collisions) - 10))
            FreeCAD.Console.PrintWarning(
                "{}: {} route(s) between paths meet what is deposited (a way within a component "
                "even round the part):\n"
                "{}\n".format(obj.Label, len(collisions), "\n".join(lines)))
        obj.Shape = program_travel_shape(program.text)


def is_machine_program(obj):
    return getattr(getattr(obj, "Proxy", None), "Type", None) == MachineProgramFeature.TYPE


def machine_inputs(obj):
    """(Layers object, gcode() machine parameters) of a MachineProgram object. Raises ValueError /
    TypeError for a missing or wrong link or a parameter of the wrong type."""
    layers = _check_link(obj, "Layers", is_layers, "Layers")
    machine = {}
    for prop, name, type_id, _doc in _MACHINE_PROPERTIES:
        value = getattr(obj, prop)
        if type_id in ("App::PropertyLength", "App::PropertyAngle", "App::PropertyDistance"):
            value = value.Value
        machine[name] = value
    if obj.CheckTravel:
        for prop, name, _default in _TRAVEL_LIMITS:
            machine[name] = getattr(obj, prop).Value
    return layers, _machine_params(machine)


def machine_program(obj):
    """The ``MultiAxisSlicer.GcodeProgram`` of a MachineProgram object, as its properties and its
    Layers object give it. The proxy keeps the last one in memory (never saved); it is written
    anew when a machine parameter or the slicing changed, or after a reopen. Raises like
    ``MultiAxisSlicer.gcode``."""
    layers, machine = machine_inputs(obj)
    result = slice_result(layers, computed=True)
    proxy = obj.Proxy
    cached = getattr(proxy, "_program", None)  # (the result it was written from, the program)
    if cached is not None and cached[0] is result and cached[1].machine == machine:
        return cached[1]
    proxy._program = None
    with _progress.reporting("Writing the G-code of '{}'".format(obj.Label)) as progress:
        program = mas.gcode(result, progress=progress, **machine)
    proxy._program = (result, program)
    return program


def export_gcode(obj, path):
    """Writes the program of the MachineProgram object ``obj`` to ``path`` (whole or not at all)
    and returns its ``GcodeProgram``. Raises ValueError when the object is not computed (its
    message), else like ``machine_program()`` and ``GcodeProgram.write``."""
    if not is_machine_program(obj):
        raise TypeError("export_gcode() needs a MachineProgram object, got {}".format(
            getattr(obj, "TypeId", type(obj).__name__)))
    problem = failure(obj)
    if problem is None:
        # What the document shows: not a program of layers changed since (their pending
        # parameters would be sliced here).
        changed = [o for o in depends_on(obj) if "Touched" in o.State]
        if changed:
            problem = "{}: not recomputed since '{}' changed: recompute the document".format(
                obj.Label, changed[0].Label)
    if problem is not None:
        raise ValueError(problem)
    program = machine_program(obj)
    program.write(path)
    return program


def make_machine_program(layers, name="MachineProgram", doc=None, **machine):
    """Adds a ``MachineProgram`` object writing the G-code of the ``Layers`` object ``layers`` (a
    ``Toolpath`` object stands for its Layers) to ``doc`` (default: the layers' document) and
    returns it; recompute the document to compute it. ``machine``: ``MultiAxisSlicer.gcode``'s
    machine parameters (defaults ``MultiAxisSlicer.MACHINE_DEFAULTS``), their names and types
    checked before anything is added; travel limits given turn CheckTravel on, those not given
    infinite (no limit). Nothing is changed on the layers."""
    if is_toolpath(layers):
        if layers.Layers is None:
            raise ValueError("make_machine_program(): the Toolpath '{}' has no Layers".format(
                layers.Label))
        layers = layers.Layers
    if not is_layers(layers):
        raise TypeError("make_machine_program() needs a Layers or Toolpath object, got {}".format(
            getattr(layers, "TypeId", type(layers).__name__)))
    values = _machine_params(machine)
    # Properties would silently clamp what gcode() refuses: a negative length, an angle past a
    # turn.
    mas._length(values["reference_thickness"], "reference_thickness", allow_zero=True)
    mas._length(values["clearance"], "clearance")
    _check_angles(values, [(param, type_id) for _p, param, type_id, _d in _MACHINE_PROPERTIES])
    if doc is None:
        doc = layers.Document
    obj = doc.addObject("Part::FeaturePython", name)
    MachineProgramFeature(obj)
    obj.Layers = layers
    for prop, param, _t, _d in _MACHINE_PROPERTIES:
        setattr(obj, prop, values[param])
    # Limits given: the travel is checked, those not given infinite (no limit), as gcode() has it.
    if any(values[param] is not None for _p, param, _d in _TRAVEL_LIMITS):
        obj.CheckTravel = True
        for prop, param, _d in _TRAVEL_LIMITS:
            unlimited = -math.inf if prop.endswith("Min") else math.inf
            setattr(obj, prop, unlimited if values[param] is None else values[param])
    if FreeCAD.GuiUp:
        _attach_view_provider(obj, MachineProgramFeature.VIEW_PROVIDER)
    return obj


def _attach_view_provider(obj, class_name):
    import MultiAxisSlicerGui.view_providers as view_providers

    getattr(view_providers, class_name)(obj.ViewObject)


class _GroupMoves:
    """A document observer: where a group's placement changes (an ``App::Part``, a PartDesign
    ``Body``), the objects here whose ``Source`` lies inside it are marked for recompute. Their
    part is taken where the 3D view shows it (``MultiAxisSlicer._placed``), but the group is none
    of their links, so FreeCAD would not recompute them: a link to it would close a circle as soon
    as one of them were put into the group. What is made from those objects follows as usual."""

    def slotChangedObject(self, obj, prop):
        if prop != "Placement" or not hasattr(obj, "hasExtension"):
            return
        if not obj.hasExtension("App::GeoFeatureGroupExtension"):
            return
        doc = obj.Document
        if getattr(doc, "Restoring", False):  # an opened document is as it was saved
            return
        for o in doc.Objects:
            if not isinstance(getattr(o, "Proxy", None), _EngineFeature):
                continue
            source = getattr(o, "Source", None)
            if source is not None and any(g == obj for g in mas._groups_of(source)):
                o.touch()


# One for the session, from the first import (by a command, a script, or a document that holds
# one of these objects).
_GROUP_MOVES = _GroupMoves()
FreeCAD.addDocumentObserver(_GROUP_MOVES)
