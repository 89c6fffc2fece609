# SPDX-License-Identifier: LGPL-2.1-or-later
"""Parametric FreeCAD document objects over the engine (App side: imports without FreeCADGui).

``Sections``: the cross-sections of a solid or closed mesh by parallel planes, as a compound of
closed wires. ``CentroidalAxis``: the part's centroidal axis, as a compound of vertices (nodes) and
line segments (links). Thin like FreeCAD's own features: properties -> MultiAxisSlicer -> Shape.

    import MultiAxisSlicer.features as features
    obj = features.make_sections(doc.Box, normal=(0, 0, 1), step=2.0)
    axis = features.make_centroidal_axis(doc.Box, step=2.0)
    doc.recompute()
"""

import functools

import FreeCAD
import Part

import MultiAxisSlicer as mas

# Bad input the user can fix (a face instead of a solid, an open mesh, Step = 0, no Source): FreeCAD
# shows the object as failed with the message. Anything else is a bug and keeps its traceback.
_USER_ERRORS = (mas.EngineError, mas.EngineUnavailableError, ValueError, TypeError)

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


class _EngineFeature:
    """What every proxy here shares: recompute errors reported by their message, nothing to save
    beyond the properties, a view provider when the GUI opens a document made without it.

    A subclass sets TYPE and VIEW_PROVIDER (a class name in MultiAxisSlicerGui.view_providers) and
    defines ensure_properties(obj) and recompute(obj)."""

    TYPE = ""
    VIEW_PROVIDER = ""

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
            self.recompute(obj)
        except _USER_ERRORS as error:
            return error
        return None

    def _recompute_raising(self, obj):
        self.recompute(obj)

    def onDocumentRestored(self, obj):
        self.Type = self.TYPE
        self.ensure_properties(obj)
        # A document made without the GUI (freecadcmd, a script) saved no view provider: give it
        # one when the GUI opens it, so the object gets its icon and colours.
        if FreeCAD.GuiUp and obj.ViewObject is not None and obj.ViewObject.Proxy is None:
            _attach_view_provider(obj, self.VIEW_PROVIDER)

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


class SectionsFeature(_EngineFeature):
    """Proxy of a ``Part::FeaturePython`` holding cross-sections of its ``Source``.

    Inputs: Source (a solid or closed mesh), Normal, Step (mm between planes), Deflection (mm
    chordal deflection for tessellating a solid, 0 = automatic). Outputs: Shape (a compound of
    one closed wire per section loop), SectionCount, TotalArea (sum of all section areas).
    """

    TYPE = "MultiAxisSlicer::Sections"
    VIEW_PROVIDER = "ViewProviderSections"

    @staticmethod
    def ensure_properties(obj):
        group = "Sections"
        _add_property(obj, "App::PropertyLink", "Source", group,
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
        result = mas.sections(obj.Source, normal=obj.Normal, step=obj.Step.Value,
                              deflection=deflection)
        obj.Shape = sections_shape(result)
        obj.SectionCount = len(result)
        obj.TotalArea = sum(s.area for s in result)


def sections_shape(sections):
    """A compound of closed polygonal wires, one per section loop (outer loops and holes)."""
    wires = []
    for s in sections:
        for region in s.regions:
            for loop in region.loops:
                if len(loop) >= 3:
                    wires.append(Part.makePolygon(loop + [loop[0]]))
    return Part.makeCompound(wires)


def make_sections(source, normal=(0, 0, 1), step=5.0, deflection=0.0, name="Sections", doc=None):
    """Adds a ``Sections`` object cutting ``source`` to ``doc`` (default: the source's document) and
    returns it; recompute the document to compute it. The source is not changed.

    In the GUI it gets its view provider (icon, line colour)."""
    if doc is None:
        doc = source.Document if source is not None else FreeCAD.ActiveDocument
    if doc is None:
        raise ValueError("no document to add the Sections object to")
    obj = doc.addObject("Part::FeaturePython", name)
    SectionsFeature(obj)
    obj.Source = source
    obj.Normal = FreeCAD.Vector(*mas._direction(normal))
    obj.Step = mas._length(step, "step")
    obj.Deflection = mas._length(deflection, "deflection", allow_zero=True)
    if FreeCAD.GuiUp:
        _attach_view_provider(obj, SectionsFeature.VIEW_PROVIDER)
    return obj


class CentroidalAxisFeature(_EngineFeature):
    """Proxy of a ``Part::FeaturePython`` holding the centroidal axis of its ``Source``.

    Inputs: Source (a solid or closed mesh standing on its lowest point), Step (mm between
    sections, 0 = derived from the part), DistanceThreshold (mm, 0 = twice the step), Epsilon (mm),
    BreakAngle (degrees), Deflection (mm chordal deflection for tessellating a solid, 0 =
    automatic). Outputs: Shape (a compound of one vertex per node, then one line segment per link:
    first the ordinary links, then the C1 breaks from edge index BreakEdgeStart on, so that the
    view provider can colour them), NodeCount, BranchCount, BreakCount, UsedStep,
    UsedDistanceThreshold, SearchedVolume.
    """

    TYPE = "MultiAxisSlicer::CentroidalAxis"
    VIEW_PROVIDER = "ViewProviderCentroidalAxis"

    @staticmethod
    def ensure_properties(obj):
        group = "Centroidal axis"
        _add_property(obj, "App::PropertyLink", "Source", group,
                      "Solid or closed mesh, standing on its lowest point")
        _add_property(obj, "App::PropertyLength", "Step", group,
                      "Distance between consecutive sections (0 = derived from the part: half "
                      "its thinnest wall)", 0.0)
        _add_property(obj, "App::PropertyLength", "DistanceThreshold", group,
                      "A section part sticking out farther than this starts a new branch "
                      "(0 = twice the step)", 0.0)
        _add_property(obj, "App::PropertyLength", "Epsilon", group,
                      "Distance of a march's first section inside the part", 0.001)
        _add_property(obj, "App::PropertyAngle", "BreakAngle", group,
                      "Links turning more than this from the previous link are C1 breaks", 30.0)
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
        _add_property(obj, "App::PropertyVolume", "SearchedVolume", result,
                      "Volume swept by the nodes' sections: the part's volume when every region "
                      "was searched once", 0.0, _OUTPUT)

    @staticmethod
    def recompute(obj):
        """Properties -> engine -> Shape and the result properties. Raises on bad input."""
        if obj.Source is None:
            raise ValueError("{}: Source is not set".format(obj.Label))
        axis = mas.centroidal_axis(
            obj.Source,
            step=obj.Step.Value or None,
            distance_threshold=obj.DistanceThreshold.Value or None,
            eps=obj.Epsilon.Value,
            break_angle=obj.BreakAngle.Value,
            deflection=obj.Deflection.Value or None,
        )
        shape, break_edge_start = axis_shape(axis)
        # BreakEdgeStart before Shape: the view provider colours the edges when the Shape changes.
        obj.BreakEdgeStart = break_edge_start
        obj.Shape = shape
        obj.NodeCount = len(axis.nodes)
        obj.BranchCount = len(axis.branches)
        obj.BreakCount = len(axis.break_links())
        obj.UsedStep = axis.params["step_mm"]
        obj.UsedDistanceThreshold = axis.params["distance_threshold_mm"]
        obj.SearchedVolume = axis.searched_volume


def axis_shape(axis):
    """(compound, break_edge_start): one vertex per node in node order, then one line segment per
    link, ordinary links first (in link order), then the breaks; break_edge_start is the index of
    the first break among the compound's edges."""
    points = [FreeCAD.Vector(n.position) for n in axis.nodes]
    ordinary, breaks = [], []
    for link in axis.links:
        a, b = points[link.start], points[link.end]
        if a.isEqual(b, 1e-9):  # no edge for a zero-length link (nodes lie a step apart)
            continue
        (breaks if link.is_break else ordinary).append(Part.LineSegment(a, b).toShape())
    vertices = [Part.Vertex(p) for p in points]
    return Part.makeCompound(vertices + ordinary + breaks), len(ordinary)


def make_centroidal_axis(source, step=0.0, distance_threshold=0.0, eps=0.001, break_angle=30.0,
                         deflection=0.0, name="CentroidalAxis", doc=None):
    """Adds a ``CentroidalAxis`` object over ``source`` to ``doc`` (default: the source's document)
    and returns it; recompute the document to compute it. Lengths in mm, ``break_angle`` in
    degrees; 0 for ``step``, ``distance_threshold`` or ``deflection`` means derived from the part.
    The source is not changed.

    In the GUI it gets its view provider (icon, nodes as points, links as lines, breaks in red)."""
    if doc is None:
        doc = source.Document if source is not None else FreeCAD.ActiveDocument
    if doc is None:
        raise ValueError("no document to add the CentroidalAxis object to")
    step = mas._length(step, "step", allow_zero=True)
    distance_threshold = mas._length(distance_threshold, "distance_threshold", allow_zero=True)
    eps = mas._length(eps, "eps")
    break_angle = mas.axis._break_angle(break_angle)
    deflection = mas._length(deflection, "deflection", allow_zero=True)
    obj = doc.addObject("Part::FeaturePython", name)
    CentroidalAxisFeature(obj)
    obj.Source = source
    obj.Step = step
    obj.DistanceThreshold = distance_threshold
    obj.Epsilon = eps
    obj.BreakAngle = break_angle
    obj.Deflection = deflection
    if FreeCAD.GuiUp:
        _attach_view_provider(obj, CentroidalAxisFeature.VIEW_PROVIDER)
    return obj


def _attach_view_provider(obj, class_name):
    import MultiAxisSlicerGui.view_providers as view_providers

    getattr(view_providers, class_name)(obj.ViewObject)
