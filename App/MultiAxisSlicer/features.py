# SPDX-License-Identifier: LGPL-2.1-or-later
"""Parametric FreeCAD document objects over the engine (App side: imports without FreeCADGui).

``Sections``: the cross-sections of a solid or closed mesh by parallel planes, as a compound of
closed wires. Thin like FreeCAD's own features: properties -> MultiAxisSlicer.sections() -> Shape.

    import MultiAxisSlicer.features as features
    obj = features.make_sections(doc.Box, normal=(0, 0, 1), step=2.0)
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


class SectionsFeature:
    """Proxy of a ``Part::FeaturePython`` holding cross-sections of its ``Source``.

    Inputs: Source (a solid or closed mesh), Normal, Step (mm between planes), Deflection (mm
    chordal deflection for tessellating a solid, 0 = automatic). Outputs: Shape (a compound of
    one closed wire per section loop), SectionCount, TotalArea (sum of all section areas).
    """

    TYPE = "MultiAxisSlicer::Sections"

    def __init__(self, obj):
        self.Type = self.TYPE
        obj.Proxy = self
        self.ensure_properties(obj)

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

    def onDocumentRestored(self, obj):
        self.Type = self.TYPE
        self.ensure_properties(obj)
        # A document made without the GUI (freecadcmd, a script) saved no view provider: give it
        # one when the GUI opens it, so the sections get their icon and colour.
        if FreeCAD.GuiUp and obj.ViewObject is not None and obj.ViewObject.Proxy is None:
            _attach_view_provider(obj)

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
        _attach_view_provider(obj)
    return obj


def _attach_view_provider(obj):
    import MultiAxisSlicerGui.view_providers as view_providers

    view_providers.ViewProviderSections(obj.ViewObject)
