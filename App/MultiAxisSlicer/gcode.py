# SPDX-License-Identifier: LGPL-2.1-or-later
"""The post-processor: a sliced part as a 5-axis G-code program, for scripts and FreeCAD.

The program is for LinuxCNC (RS274NGC) on a machine whose nozzle stays vertical while a tilting
rotary table turns the part under it: A tilts the table about X, C turns the part about the
table's normal (LinuxCNC's ``xyzac-trt-kins``, which moves the joints so that the nozzle tip
follows the part's own X Y Z). The engine's header App/include/mas/Gcode.hpp explains how the
angles, the deposition output, the feed and the travel moves are chosen. Re-exported by the
package::

    import MultiAxisSlicer as mas
    result = mas.slice(App.ActiveDocument.Part)
    program = mas.gcode(result, feed=900, a_min=-100, a_max=50)
    program.write("/tmp/part.ngc")
    print(program.stats["deposit_time_min"], program.stats["a_range_deg"])
"""

import numbers

from . import _require_engine
from . import progress as _progress
from .axis import _number

__all__ = ["GcodeProgram", "gcode", "MACHINE_DEFAULTS"]

# The machine parameters gcode() takes, with their defaults (angles in degrees, lengths in mm,
# feeds in mm/min). The angle limits are those of LinuxCNC's sample xyzac-trt configuration.
MACHINE_DEFAULTS = {
    "a_min": -100.0,
    "a_max": 50.0,
    "c_min": -36000.0,
    "c_max": 36000.0,
    "feed": 600.0,
    "reference_thickness": 0.0,
    "max_feed_ratio": 4.0,
    "clearance": 2.0,
    "deposit_output": 0,
    # The X Y Z travel (mm, the machine's frame; None: not checked) and what places the part in
    # it: the work offset (G54) and xyzac-trt-kins' pivot and tool length pins.
    "x_min": None,
    "x_max": None,
    "y_min": None,
    "y_max": None,
    "z_min": None,
    "z_max": None,
    "work_offset_x": 0.0,
    "work_offset_y": 0.0,
    "work_offset_z": 0.0,
    "rot_point_x": 0.0,
    "rot_point_y": 0.0,
    "rot_point_z": 0.0,
    "rot_offset_y": 0.0,
    "rot_offset_z": 0.0,
    "tool_length": 0.0,
}

# The travel limits: None is no limit.
_LIMITS = ("x_min", "x_max", "y_min", "y_max", "z_min", "z_max")
_PLACEMENT = ("work_offset_x", "work_offset_y", "work_offset_z", "rot_point_x", "rot_point_y",
              "rot_point_z", "rot_offset_y", "rot_offset_z", "tool_length")


class GcodeProgram:
    """A G-code program: ``text`` (str), ``stats`` (dict: lines, deposit_moves,
    feed_limited_moves, reorientations, a_range_deg and c_range_deg (the angles used, as (min,
    max)), deposit_length_mm, deposit_time_min (the deposit moves at their feeds),
    rapid_length_mm, reference_thickness_mm, x_range_mm, y_range_mm and z_range_mm (the machine's
    X Y Z joints the program takes, as (min, max), with the work offset, pivot and tool length
    given); and the travel checked against the slicing's nozzle:
    checked_routes, rerouted_travels (ways within a component taken round the part because they
    would meet something), travel_collisions (routes meeting something all the same: dicts of
    layer (the layer the route leads to, -1 off the part), obstacle_layer (-1: the build plate),
    nozzle_at and obstacle as (x, y, z))) and ``machine`` (the machine parameters used)."""

    def __init__(self, data, machine):
        self.text = data["text"]
        self.stats = dict(data["stats"])
        self.stats["a_range_deg"] = tuple(self.stats["a_range_deg"])
        self.stats["c_range_deg"] = tuple(self.stats["c_range_deg"])
        for axis in "xyz":
            self.stats[axis + "_range_mm"] = tuple(self.stats[axis + "_range_mm"])
        self.machine = dict(machine)

    def write(self, path):
        """Writes the program to ``path`` whole or not at all: through a temporary file beside
        it, renamed over it. An existing file keeps its permissions (a new one gets the umask's);
        through a symbolic link, the file it names is replaced. IsADirectoryError for a folder,
        OSError as the system gives it otherwise (FileNotFoundError for a missing folder); one
        naming a file names ``path``, not the temporary file."""
        import os
        import stat
        import tempfile
        path = os.fspath(path)
        if path.endswith(os.sep) or os.path.isdir(path):
            raise IsADirectoryError("{} is a folder, not a file to write the program to".format(
                path))
        target = os.path.realpath(path)
        try:
            mode = stat.S_IMODE(os.stat(target).st_mode)
        except FileNotFoundError:
            umask = os.umask(0)
            os.umask(umask)
            mode = 0o666 & ~umask

        def named(error):  # the system's error named by the path asked for, not the temporary file
            return type(error)(error.errno, error.strerror, path)

        try:
            fd, partial = tempfile.mkstemp(prefix=".mas-", suffix=".partial",
                                           dir=os.path.dirname(target))
        except OSError as error:
            raise named(error) from None
        try:
            with os.fdopen(fd, "w", newline="\n") as f:
                os.fchmod(f.fileno(), mode)
                f.write(self.text)
            try:
                os.replace(partial, target)
            except OSError as error:
                raise named(error) from None
        except BaseException:
            try:
                os.unlink(partial)
            except OSError:
                pass
            raise

    def __str__(self):
        return self.text

    def __repr__(self):
        s = self.stats
        return ("<MultiAxisSlicer.GcodeProgram lines={} deposit={:.6g} mm A=[{:.4g}, {:.4g}] "
                "deg>").format(s["lines"], s["deposit_length_mm"], *s["a_range_deg"])


# A FreeCAD Quantity's unit type for each kind of parameter, and the unit its value is taken in.
_UNITS = {"degrees": ("Angle", "deg"), "millimetres": ("Length", "mm"),
          "millimetres per minute": ("Velocity", "mm/min")}


def _measure(value, name, unit):
    """A float from a number, or from a FreeCAD Quantity of the right kind converted to `unit`
    ("degrees", "millimetres", "millimetres per minute"); TypeError naming the parameter else."""
    kind = getattr(getattr(value, "Unit", None), "Type", None)
    if kind is not None and kind != "" and unit in _UNITS:
        want, symbol = _UNITS[unit]
        if kind != want:
            def article(word):
                return ("an " if word[0] in "aeiou" else "a ") + word

            raise TypeError("{} must be a number of {} or {} quantity, got {} quantity "
                            "({})".format(name, unit, article(want.lower()),
                                          article(kind.lower()), value))
        return float(value.getValueAs(symbol))
    return _number(value, name, unit)


def _machine_params(values):
    """Checks the machine parameters' names and types (TypeError naming the bad one) and takes
    FreeCAD Quantities in their units (a feed of 15 mm/s is 900 mm/min); the engine checks their
    ranges."""
    unknown = sorted(set(values) - set(MACHINE_DEFAULTS))
    if unknown:
        raise TypeError("unknown machine parameter(s): {}; known: {}".format(
            ", ".join(unknown), ", ".join(MACHINE_DEFAULTS)))
    p = dict(MACHINE_DEFAULTS)
    for name in ("a_min", "a_max", "c_min", "c_max"):
        p[name] = _measure(values.get(name, p[name]), name, "degrees")
    for name in ("reference_thickness", "clearance"):
        p[name] = _measure(values.get(name, p[name]), name, "millimetres")
    for name in _LIMITS:
        if values.get(name) is not None:
            p[name] = _measure(values[name], name, "millimetres")
    for name in _PLACEMENT:
        p[name] = _measure(values.get(name, p[name]), name, "millimetres")
    p["feed"] = _measure(values.get("feed", p["feed"]), "feed", "millimetres per minute")
    p["max_feed_ratio"] = _number(values.get("max_feed_ratio", p["max_feed_ratio"]),
                                  "max_feed_ratio", "a ratio")
    output = values.get("deposit_output", p["deposit_output"])
    if isinstance(output, bool) or not isinstance(output, numbers.Integral):
        raise TypeError("deposit_output must be an integer, got {!r}".format(output))
    p["deposit_output"] = int(output)
    return p


def gcode(result, progress=None, **machine):
    """The 5-axis G-code program that deposits a ``SliceResult`` (from ``slice()``), layer by
    layer in its deposition sequence (``result.sequence``).

    Machine parameters (defaults in ``MACHINE_DEFAULTS``; FreeCAD Quantities accepted, in their
    units: ``feed=Quantity("15 mm/s")`` is 900 mm/min):
      * ``a_min``, ``a_max`` (-100, 50), ``c_min``, ``c_max`` (-36000, 36000): the table's travel
        limits, degrees. A layer whose tool axis no angle within them turns up to the nozzle is an
        error naming the layer (EngineError ``unreachable_orientation``).
      * ``feed``: the deposition feed, mm/min, where the deposit is ``reference_thickness`` mm
        thick (600; 0: half-way between the thinnest and the thickest deposit). Where a tilted
        layer is thinner the nozzle goes faster, in proportion, within ``feed / max_feed_ratio``
        to ``feed * max_feed_ratio`` (4; 1 keeps the feed constant).
      * ``clearance``: how far the nozzle retracts along the tool axis between paths, and its
        margin round the part between components, mm (2).
      * ``deposit_output``: the digital output that switches deposition (M62/M63 P, 0).
      * The X Y Z travel, mm in the machine's frame: ``x_min``, ``x_max``, ``y_min``, ``y_max``,
        ``z_min``, ``z_max`` (None: not checked), where the nozzle's gauge line may go (the joint
        limits of the machine's INI file). Where the joints go is computed as LinuxCNC's
        ``xyzac-trt-kins`` does, from ``work_offset_x``, ``work_offset_y``, ``work_offset_z``
        (G54: where the part's origin lies with A and C at 0), ``rot_point_x``, ``rot_point_y``,
        ``rot_point_z``, ``rot_offset_y``, ``rot_offset_z`` (its pins ``x-rot-point`` ...
        ``z-offset``) and ``tool_length`` (its ``tool-offset`` pin: the nozzle's length offset),
        all 0 by default. ``stats`` reports the ranges the program takes whether or not limits
        are given; a program past one is an error naming the axis, its range, the limit and the
        layer (EngineError ``out_of_travel``).

    The travel between paths is checked against the nozzle the result was sliced with and its
    build plate (see Gcode.hpp and Nozzle.hpp): a way within a component that would meet what is
    deposited goes round the part instead, and a route that meets something all the same is kept,
    marked by a warning comment and listed in ``stats["travel_collisions"]``.

    ``progress``: as ``slice()``'s, reported layer by layer. Returns a ``GcodeProgram``. Raises
    TypeError for an unknown parameter or one of the wrong type, EngineError ``invalid_argument``
    for one out of its range (a feed of 0, A's limits the wrong way round, an output beyond 63),
    ``unreachable_orientation`` and ``out_of_travel`` as above, ``empty_input`` when nothing is
    deposited.
    """
    from .slicing import SliceResult
    if not isinstance(result, SliceResult):
        raise TypeError("gcode() needs a SliceResult (from MultiAxisSlicer.slice()), got "
                        "{!r}".format(type(result).__name__))
    p = _machine_params(machine)
    _progress.check(progress)
    eng = _require_engine()
    layers = result._data["layers"]
    # The travel is checked against the nozzle and plate the result was sliced with (a result
    # from before the plate was kept has none: its travel is not checked).
    nozzle = plate = None
    if "plate_origin" in result._data:
        nozzle = {k: v for k, v in result.params.items()
                  if k.startswith("nozzle_") or k == "check_plate"}
        plate = (result._data["plate_origin"], result._data["plate_normal"])
    # In the order they are deposited (the result's sequence, checked against the nozzle), each
    # named by its index in the result.
    # No limit given: none checked (the engine's infinite limits).
    engine_params = {k: v for k, v in p.items() if v is not None}
    return GcodeProgram(eng.write_gcode([dict(layers[i], index=i) for i in result.sequence],
                                        engine_params, progress, nozzle, plate), p)
