# SPDX-License-Identifier: LGPL-2.1-or-later
"""Parametric FreeCAD document objects over the engine (App side: imports without FreeCADGui).

``Sections``: the cross-sections of a solid or closed mesh by parallel planes, as a compound of
closed wires. ``CentroidalAxis``: the part's centroidal axis, as a compound of vertices (nodes) and
line segments (links). ``Decomposition``: the part's sub-components, as a compound of solids in
tree order, with one ``Component`` object per solid (Component001, ...) for the tree and the 3D
view. Thin like FreeCAD's own features: properties -> MultiAxisSlicer -> Shape.

    import MultiAxisSlicer.features as features
    obj = features.make_sections(doc.Box, normal=(0, 0, 1), step=2.0)
    axis = features.make_centroidal_axis(doc.Box, step=2.0)
    parts = features.make_decomposition(doc.Box, axis=axis)   # computes it, adds the components
    doc.recompute()
"""

import functools

import FreeCAD
import Part

import MultiAxisSlicer as mas
from MultiAxisSlicer.decompose import _angle

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


class DecompositionFeature(_EngineFeature):
    """Proxy of a ``Part::FeaturePython`` holding the sub-components of its ``Source``.

    Inputs: Source (one solid: a mesh cannot be split), Axis (optional ``CentroidalAxis`` object:
    when set, the axis is computed with its Step, DistanceThreshold, Epsilon, BreakAngle and
    Deflection, and its Source is used when Source is empty), Step (mm, 0 = derived; used without
    Axis), Deflection (mm, 0 = automatic; used without Axis), FaceAngle, ConcaveAngle,
    SectionPlaneFallback. Outputs: Shape (a compound of the component solids in tree order: a
    father before its children, the root first), ComponentCount, and per component, in the same
    order, ComponentParents (index of the father, -1 for the root), BuildDirections, BaseOrigins,
    Rules ("root", "planar_face", "section_plane"), Volumes (mm³); PartVolume, UsedStep.

    The ``Component`` objects (``ComponentFeature``) show the solids one by one; they are created
    by ``make_decomposition()`` / ``sync_components()``, never inside a recompute (adding or
    removing document objects during a recompute is unsafe in FreeCAD).
    """

    TYPE = "MultiAxisSlicer::Decomposition"
    VIEW_PROVIDER = "ViewProviderDecomposition"

    @staticmethod
    def ensure_properties(obj):
        group = "Decomposition"
        _add_property(obj, "App::PropertyLink", "Source", group,
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
                      "How each component was cut: root, planar_face or section_plane", None,
                      _OUTPUT)
        _add_property(obj, "App::PropertyFloatList", "Volumes", result,
                      "Each component's volume (mm^3)", None, _OUTPUT)
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
        axis_obj = obj.Axis
        if axis_obj is not None and getattr(getattr(axis_obj, "Proxy", None), "Type",
                                            None) != CentroidalAxisFeature.TYPE:
            raise TypeError("{}: Axis '{}' is not a CentroidalAxis object".format(
                obj.Label, axis_obj.Label))
        source = obj.Source if obj.Source is not None else getattr(axis_obj, "Source", None)
        if axis_obj is not None and axis_obj.Source is not None and source != axis_obj.Source:
            raise ValueError("{}: Axis '{}' belongs to '{}', not to the Source '{}'".format(
                obj.Label, axis_obj.Label, axis_obj.Source.Label, source.Label))
        if source is None:
            raise ValueError("{}: Source is not set".format(obj.Label))
        if axis_obj is not None:
            axis_params = dict(step=axis_obj.Step.Value or None,
                               distance_threshold=axis_obj.DistanceThreshold.Value or None,
                               eps=axis_obj.Epsilon.Value, break_angle=axis_obj.BreakAngle.Value,
                               deflection=axis_obj.Deflection.Value or None)
        else:
            axis_params = dict(step=obj.Step.Value or None,
                               deflection=obj.Deflection.Value or None)
        result = mas.decompose(source, face_angle=obj.FaceAngle.Value,
                               concave_angle=obj.ConcaveAngle.Value,
                               section_plane_fallback=obj.SectionPlaneFallback, **axis_params)
        obj.ComponentParents = [c.parent for c in result]
        obj.BuildDirections = [FreeCAD.Vector(c.build_direction) for c in result]
        obj.BaseOrigins = [FreeCAD.Vector(c.base_origin) for c in result]
        obj.Rules = [c.rule for c in result]
        obj.Volumes = [c.volume for c in result]
        obj.PartVolume = result.part_volume
        obj.UsedStep = result.axis.params["step_mm"]
        obj.Notes = result.notes
        for note in result.notes:
            FreeCAD.Console.PrintWarning("{}: {}\n".format(obj.Label, note))
        # ComponentCount after the lists and before Shape: the view provider colours the faces
        # per component when the Shape changes.
        obj.ComponentCount = len(result)
        obj.Shape = Part.makeCompound([c.shape for c in result])


class ComponentFeature(_EngineFeature):
    """Proxy of a ``Part::FeaturePython`` showing one sub-component of a ``Decomposition``.

    Inputs: Decomposition (the object it belongs to), Index (its place in tree order, 0 = the
    root). Outputs: Shape (the component's solid), Parent (index of the father component, -1 for
    the root), BuildDirection, BaseOrigin, Rule, Volume. It follows the Decomposition on every
    recompute; an Index the Decomposition no longer has is an error until ``sync_components()``
    (or the GUI, after a recompute) removes the object."""

    TYPE = "MultiAxisSlicer::Component"
    VIEW_PROVIDER = "ViewProviderComponent"

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
                      "How it was cut: root, planar_face or section_plane", None, _OUTPUT)
        _add_property(obj, "App::PropertyVolume", "Volume", result, "Volume", 0.0, _OUTPUT)

    @staticmethod
    def recompute(obj):
        d = obj.Decomposition
        if d is None:
            raise ValueError("{}: Decomposition is not set".format(obj.Label))
        i = obj.Index
        solids = d.Shape.Solids
        if not (0 <= i < min(d.ComponentCount, len(solids))):
            raise ValueError("{}: '{}' now has {} component(s), this was number {}: left over "
                             "until the components are synchronised".format(
                                 obj.Label, d.Label, d.ComponentCount, i + 1))
        obj.Parent = d.ComponentParents[i]
        obj.BuildDirection = d.BuildDirections[i]
        obj.BaseOrigin = d.BaseOrigins[i]
        obj.Rule = d.Rules[i]
        obj.Volume = d.Volumes[i]
        obj.Shape = solids[i].copy()


def is_decomposition(obj):
    return getattr(getattr(obj, "Proxy", None), "Type", None) == DecompositionFeature.TYPE


def components_of(decomposition):
    """The Component objects of a Decomposition object, in Index order."""
    found = [o for o in decomposition.InList
             if getattr(getattr(o, "Proxy", None), "Type", None) == ComponentFeature.TYPE
             and o.Decomposition == decomposition]
    return sorted(found, key=lambda o: o.Index)


def sync_components(decomposition):
    """Makes the Decomposition object's Component objects match its ComponentCount: one per
    component, labelled Component001, Component002, ... in tree order, each recomputed; extra
    ones are removed. Call it outside a recompute (after ``doc.recompute()``); the GUI does it
    after every recompute that changes the count. Returns the Component objects."""
    doc = decomposition.Document
    existing = components_of(decomposition)
    count = decomposition.ComponentCount if decomposition.isValid() else len(existing)
    keep = [c for c in existing if c.Index < count]
    for c in existing[len(keep):]:
        doc.removeObject(c.Name)
    have = {c.Index for c in keep}
    for i in range(count):
        if i in have:
            continue
        obj = doc.addObject("Part::FeaturePython", "Component")
        ComponentFeature(obj)
        obj.Decomposition = decomposition
        obj.Index = i
        obj.Label = "Component{:03d}".format(i + 1)
        if FreeCAD.GuiUp:
            _attach_view_provider(obj, ComponentFeature.VIEW_PROVIDER)
        keep.append(obj)
    keep.sort(key=lambda o: o.Index)
    for c in keep:
        if "Touched" in c.State or c.Shape.isNull():
            c.recompute()
    return keep


def make_decomposition(source, axis=None, face_angle=10.0, section_plane_fallback=True,
                       deflection=0.0, name="Decomposition", doc=None):
    """Adds a ``Decomposition`` object splitting ``source`` to ``doc`` (default: the source's,
    else the axis object's document), computes it and adds its Component objects; returns the
    Decomposition object. ``axis``: an optional ``CentroidalAxis`` object whose parameters (and
    Source, when ``source`` is None) are used. ``face_angle`` in degrees, ``deflection`` in mm (0 =
    automatic; used without ``axis``). A failing computation leaves the object marked invalid with
    the message, without components. The source is not changed.

    In the GUI the objects get their view providers (one distinct colour per component)."""
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
    obj = doc.addObject("Part::FeaturePython", name)
    DecompositionFeature(obj)
    obj.Source = source
    obj.Axis = axis
    obj.FaceAngle = face_angle
    obj.SectionPlaneFallback = bool(section_plane_fallback)
    obj.Deflection = deflection
    if FreeCAD.GuiUp:
        _attach_view_provider(obj, DecompositionFeature.VIEW_PROVIDER)
    obj.recompute(True)  # with what it depends on: the count decides the Component objects
    if obj.isValid():
        sync_components(obj)
    return obj


def is_centroidal_axis(obj):
    return getattr(getattr(obj, "Proxy", None), "Type", None) == CentroidalAxisFeature.TYPE


def _attach_view_provider(obj, class_name):
    import MultiAxisSlicerGui.view_providers as view_providers

    getattr(view_providers, class_name)(obj.ViewObject)
