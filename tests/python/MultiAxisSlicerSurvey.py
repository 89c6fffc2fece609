# SPDX-License-Identifier: LGPL-2.1-or-later
"""Parts nobody tuned for: twenty-one families of the parts a deposition shop builds (pipe bends,
hubs with blades, lugs and clevises, angle brackets, the same placed turned on the plate, branches
leaning off columns, Z brackets, manifold blocks with ports, round valve bodies with ports, wye
fittings, handles and walls with windows, portals, tables and gates on feet apart, candelabra,
walls with shelves, canes and hooks, chairs, cranks, tripods, braced frames, coat racks,
goosenecks), each part drawn at random from its family's ranges, and a survey slicing them as a
user would (defaults, G-code).

``part(family, index, seed)`` gives the same solid for the same arguments, whatever else is
drawn; ``survey()`` slices parts and reports, per part, what the measure of success is: layers
the nozzle meets, travel routes meeting anything, and the unsupported area (tools/survey.py
prints it; TestMultiAxisSlicerSurvey asserts it)."""

import math
import random
import time

import FreeCAD
import Part

import MultiAxisSlicer as mas

V = FreeCAD.Vector


def _bore(radius, rise, bend_radius, run, z0):
    """A round channel up from below the plate, round a 90-degree bend and along +X."""
    up = Part.makeCylinder(radius, rise + 1, V(0, 0, z0 - 1))
    disc = Part.Face(Part.Wire(Part.makeCircle(radius, V(0, 0, z0 + rise), V(0, 0, 1))))
    bend = disc.revolve(V(bend_radius, 0, z0 + rise), V(0, 1, 0), 90)
    along = Part.makeCylinder(radius, run + 1, V(bend_radius, 0, z0 + rise + bend_radius),
                              V(1, 0, 0))
    return up.fuse([bend, along])


def pipe_bend(rng):
    """A flange on the plate, a riser, a 90-degree bend into the horizontal and a straight run;
    hollow (a bore through all of it) or solid."""
    r = rng.uniform(6, 12)
    bore = r - rng.uniform(2, 4)
    rise, run = rng.uniform(10, 40), rng.uniform(10, 40)
    bend_radius = rng.uniform(r + 4, 3 * r)
    flange = rng.uniform(4, 10)
    hollow = rng.random() < 0.5
    solid = Part.makeCylinder(r + flange, 4).fuse(_bore(r, rise, bend_radius, run, 4))
    if hollow:
        solid = solid.cut(_bore(bore, rise, bend_radius, run, 4))
    return solid, {"radius": r, "bore": bore if hollow else 0.0, "bend_radius": bend_radius}


def hub_with_blades(rng):
    """A round hub standing on the plate with 2 to 6 flat blades round it, square to the plate
    or twisted 15 or 30 degrees about their length; a bore through the hub or not."""
    hub, height, count = rng.uniform(8, 15), rng.uniform(20, 40), rng.randint(2, 6)
    length, thickness = rng.uniform(15, 35), rng.uniform(3, 6)
    width = rng.uniform(0.4, 0.8) * height
    twist = rng.choice([0, 0, 15, 30])
    solid = Part.makeCylinder(hub, height)
    for i in range(count):
        blade = Part.makeBox(length + hub / 2, thickness, width,
                             V(hub / 2, -thickness / 2, (height - width) / 2))
        blade.rotate(V(0, 0, height / 2), V(1, 0, 0), twist)
        blade.rotate(V(0, 0, 0), V(0, 0, 1), 360.0 * i / count + rng.uniform(0, 10))
        solid = solid.fuse(blade)
    if rng.random() < 0.5:
        solid = solid.cut(Part.makeCylinder(hub / 3, height + 2, V(0, 0, -1)))
    return solid, {"blades": count, "twist_deg": twist}


def lug(rng):
    """A base plate with one upright lug, or two (a clevis), each with a round top and a pin
    hole through it along Y."""
    width, depth, plate = rng.uniform(30, 60), rng.uniform(20, 40), rng.uniform(5, 10)
    thickness, height = rng.uniform(5, 10), rng.uniform(15, 35)
    lug_width = rng.uniform(15, min(width, 30))
    ys = [0.0] if rng.random() < 0.5 else [-depth / 4, depth / 4]
    solid = Part.makeBox(width, depth, plate, V(-width / 2, -depth / 2, 0))
    for y in ys:
        upright = Part.makeBox(lug_width, thickness, height,
                               V(-lug_width / 2, y - thickness / 2, plate))
        upright = upright.fuse(Part.makeCylinder(lug_width / 2, thickness,
                                                 V(0, y - thickness / 2, plate + height),
                                                 V(0, 1, 0)))
        upright = upright.cut(Part.makeCylinder(lug_width / 4, thickness + 2,
                                                V(0, y - thickness / 2 - 1, plate + height),
                                                V(0, 1, 0)))
        solid = solid.fuse(upright)
    return solid, {"lugs": len(ys), "hole_diameter": lug_width / 2}


def angle_bracket(rng):
    """An angle: a foot on the plate and a wall at its end, a triangular web between them or not,
    an arm off the wall's top reaching the other way or not."""
    length, width = rng.uniform(30, 60), rng.uniform(20, 40)
    thickness, height = rng.uniform(4, 8), rng.uniform(25, 50)
    solid = Part.makeBox(length, width, thickness).fuse(Part.makeBox(thickness, width, height))
    web = rng.random() < 0.5
    if web:
        y = width / 2 - 2
        outline = Part.makePolygon([V(thickness, y, thickness),
                                    V(thickness + 0.6 * length, y, thickness),
                                    V(thickness, y, thickness + 0.6 * height),
                                    V(thickness, y, thickness)])
        solid = solid.fuse(Part.Face(outline).extrude(V(0, 4, 0)))
    arm = rng.random() < 0.5
    if arm:
        reach = rng.uniform(10, 30)
        solid = solid.fuse(Part.makeBox(reach + thickness, thickness, thickness,
                                        V(-reach, width / 2 - thickness / 2, height - thickness)))
    return solid, {"web": web, "arm": arm}


def turned_angle_bracket(rng):
    """An angle bracket placed turned on the plate, 5 to 85 degrees about Z: its wall and arm lie
    between the document's X and Y."""
    solid, description = angle_bracket(rng)
    turn = rng.uniform(5, 85)
    solid.rotate(V(0, 0, 0), V(0, 0, 1), turn)
    return solid, dict(description, turn_deg=turn)


def leaning_branch(rng):
    """A round column with a round branch leaving its side at 20 to 70 degrees from the vertical,
    the column going on above it."""
    height, r = rng.uniform(40, 70), rng.uniform(6, 12)
    lean = rng.uniform(20, 70)
    z = rng.uniform(0.3, 0.6) * height
    d = V(math.sin(math.radians(lean)), 0, math.cos(math.radians(lean)))
    solid = Part.makeCylinder(r, height).fuse(
        Part.makeCylinder(r * rng.uniform(0.5, 1.0), rng.uniform(20, 40), V(0, 0, z), d))
    # whatever of the branch's end dips under the plate is cut off
    solid = solid.common(Part.makeBox(400, 400, 400, V(-200, -200, 0)))
    return solid, {"lean_deg": lean}


def z_bracket(rng):
    """A Z: a foot on the plate, a wall at its end and a flange off the wall's top reaching the
    other way; a bolt hole through the foot and one through the flange, or none."""
    length, width = rng.uniform(25, 45), rng.uniform(20, 40)
    thickness, height, reach = rng.uniform(3, 6), rng.uniform(25, 50), rng.uniform(15, 35)
    solid = Part.makeBox(length, width, thickness).fuse(Part.makeBox(thickness, width, height))
    solid = solid.fuse(Part.makeBox(reach + thickness, width, thickness,
                                    V(-reach, 0, height - thickness)))
    holes = rng.random() < 0.5
    if holes:
        radius = rng.uniform(2, 4)
        for x, z in ((thickness + 0.6 * (length - thickness), -1),
                     (-0.5 * reach, height - thickness - 1)):
            solid = solid.cut(Part.makeCylinder(radius, thickness + 2, V(x, width / 2, z)))
    return solid, {"reach": reach, "holes": holes}


def manifold(rng):
    """A block standing on the plate with 1 to 4 round bosses (ports) sticking out of its sides,
    each at its own height and place along its side, bored along its axis or not."""
    w, d, h = rng.uniform(30, 60), rng.uniform(30, 60), rng.uniform(30, 60)
    solid = Part.makeBox(w, d, h, V(-w / 2, -d / 2, 0))
    sides = rng.sample([(1, 0), (-1, 0), (0, 1), (0, -1)], rng.randint(1, 4))
    bored = 0
    for sx, sy in sides:
        r, reach = rng.uniform(4, 10), rng.uniform(5, 20)
        z = rng.uniform(r + 2, h - r - 2)
        half, width = (w / 2, d) if sx else (d / 2, w)
        along = rng.uniform(-(width / 2 - r - 1), width / 2 - r - 1)
        out = V(sx, sy, 0)
        root = out * (half - 1) + (V(0, along, z) if sx else V(along, 0, z))
        solid = solid.fuse(Part.makeCylinder(r, reach + 1, root, out))
        if rng.random() < 0.5:
            bored += 1
            solid = solid.cut(Part.makeCylinder(r / 2, reach + half, root + out * (reach + 2),
                                                out * -1))
    return solid, {"bosses": len(sides), "bored": bored}


def valve_body(rng):
    """A round body standing on the plate with 1 to 4 round bosses (ports) sticking out of it
    along +-X and +-Y, each at its own height; bored (a blind bore down the body, and one along
    each boss into it) or solid."""
    radius, height = rng.uniform(12, 25), rng.uniform(40, 70)
    solid = Part.makeCylinder(radius, height)
    sides = rng.sample([(1, 0), (-1, 0), (0, 1), (0, -1)], rng.randint(1, 4))
    bored = rng.random() < 0.5
    bores = [Part.makeCylinder(radius / 2, height - 4, V(0, 0, 4))]
    for sx, sy in sides:
        r, reach = rng.uniform(5, min(10, radius - 2)), rng.uniform(5, 20)
        z = rng.uniform(r + 2, height - r - 2)
        out = V(sx, sy, 0)
        solid = solid.fuse(Part.makeCylinder(r, radius + reach, V(0, 0, z), out))
        bores.append(Part.makeCylinder(r / 2, radius + reach + 1, V(0, 0, z), out))
    if bored:
        solid = solid.cut(bores[0].fuse(bores[1:]))
    return solid, {"bosses": len(sides), "bored": bored}


def wye_fitting(rng):
    """A pipe fitting: a riser standing on the plate with one lateral leaving its side at 30 to 60
    degrees from the vertical, or two leaving opposite sides, the riser going on past their ends;
    hollow (the laterals' bores opening into the riser's, the riser open at both ends) or solid."""
    r, lean = rng.uniform(6, 12), rng.uniform(30, 60)
    lateral_r = r * rng.uniform(0.6, 1.0)
    length, z = rng.uniform(20, 40), rng.uniform(10, 25)
    a = math.radians(lean)
    height = z + length * math.cos(a) + lateral_r * math.sin(a) + rng.uniform(5, 15)
    fork = rng.random() < 0.5
    hollow = rng.random() < 0.5
    wall = rng.uniform(2, 3)
    sides = [V(math.sin(a), 0, math.cos(a))] + ([V(-math.sin(a), 0, math.cos(a))] if fork else [])
    solid = Part.makeCylinder(r, height)
    for d in sides:
        solid = solid.fuse(Part.makeCylinder(lateral_r, length, V(0, 0, z), d))
    if hollow:
        bore = Part.makeCylinder(r - wall, height + 2, V(0, 0, -1))
        for d in sides:
            bore = bore.fuse(Part.makeCylinder(lateral_r - wall, length + 1, V(0, 0, z), d))
        solid = solid.cut(bore)
    return solid, {"lean_deg": lean, "laterals": len(sides), "hollow": hollow}


def handle(rng):
    """A bridge: a plate with two square posts and a bar across their tops (a handle), or a wall
    standing on its edge with a rectangular window through it; across X or, turned, across Y."""
    if rng.random() < 0.5:
        length, width, plate = rng.uniform(40, 80), rng.uniform(15, 30), rng.uniform(3, 6)
        post, height, bar = rng.uniform(5, 10), rng.uniform(15, 40), rng.uniform(4, 10)
        x0 = rng.uniform(2, 8)
        x1 = length - x0 - post
        y0 = (width - post) / 2
        solid = Part.makeBox(length, width, plate).fuse(
            [Part.makeBox(post, post, height + 0.5, V(x, y0, plate - 0.5)) for x in (x0, x1)] +
            [Part.makeBox(x1 + post - x0, post, bar, V(x0, y0, plate + height))])
        description = {"kind": "handle", "span": x1 - x0 - post}
    else:
        length, height, thick = rng.uniform(40, 80), rng.uniform(30, 60), rng.uniform(4, 10)
        w, h = rng.uniform(6, 0.4 * length), rng.uniform(6, 0.4 * height)
        z = rng.uniform(5, height - h - 5)
        solid = Part.makeBox(length, thick, height).cut(
            Part.makeBox(w, thick + 2, h, V((length - w) / 2, -1, z)))
        description = {"kind": "window", "span": w}
    return _across(rng, solid, description)


def _across(rng, solid, description):
    """(solid, description) as drawn across X, or turned a quarter about Z to lie across Y."""
    if rng.random() < 0.5:
        solid.rotate(V(0, 0, 0), V(0, 0, 1), 90)
        description["across"] = "Y"
    else:
        description["across"] = "X"
    return solid, description


def feet(rng):
    """A bridge on feet standing apart on the plate, nothing joining them below: a portal (two
    legs, a lintel across their tops, maybe reaching past them), a table (three or four square
    legs under a top) or a gate (three or four posts in a row under a beam); across X or, turned,
    across Y."""
    kind = rng.choice(["portal", "table", "gate"])
    if kind == "portal":
        leg, depth, height = rng.uniform(5, 12), rng.uniform(5, 20), rng.uniform(15, 50)
        span, lintel = rng.uniform(20, 80), rng.uniform(4, 10)
        past = rng.choice([0.0, rng.uniform(1, 8)])
        solid = Part.makeBox(leg, depth, height).fuse(
            [Part.makeBox(leg, depth, height, V(leg + span, 0, 0)),
             Part.makeBox(2 * (leg + past) + span, depth, lintel, V(-past, 0, height))])
    elif kind == "table":
        leg, length, width = rng.uniform(4, 8), rng.uniform(30, 70), rng.uniform(20, 50)
        height, top, legs = rng.uniform(15, 40), rng.uniform(3, 8), rng.choice([3, 4])
        corners = ([(0, 0), (length - leg, 0), (0, width - leg), (length - leg, width - leg)]
                   if legs == 4 else [(0, 0), (length - leg, 0), ((length - leg) / 2, width - leg)])
        solid = Part.makeBox(length, width, top, V(0, 0, height)).fuse(
            [Part.makeBox(leg, leg, height, V(x, y, 0)) for x, y in corners])
        span = length - 2 * leg
    else:
        posts, post, gap = rng.choice([3, 4]), rng.uniform(5, 10), rng.uniform(15, 40)
        height, beam = rng.uniform(15, 45), rng.uniform(4, 8)
        solid = Part.makeBox(posts * post + (posts - 1) * gap, post, beam, V(0, 0, height)).fuse(
            [Part.makeBox(post, post, height, V(k * (post + gap), 0, 0)) for k in range(posts)])
        span = gap
    return _across(rng, solid, {"kind": kind, "span": span, "legs": 2 if kind == "portal" else
                                legs if kind == "table" else posts})


def _bar(a, b, side):
    """A square bar `side` across from point a to point b, which differ along one axis only."""
    lo = V(min(a.x, b.x), min(a.y, b.y), min(a.z, b.z)) - V(side, side, side) * 0.5
    size = V(abs(b.x - a.x), abs(b.y - a.y), abs(b.z - a.z)) + V(side, side, side)
    return Part.makeBox(size.x, size.y, size.z, lo)


def candelabra(rng):
    """A round column on a round foot with 2 to 4 square arms leaving it along +-X and +-Y, each
    at its own height, each with a post rising off its end."""
    r, height = rng.uniform(5, 10), rng.uniform(40, 70)
    solid = Part.makeCylinder(r + rng.uniform(4, 10), rng.uniform(3, 6)).fuse(
        Part.makeCylinder(r, height))
    ways = rng.sample([(1, 0), (-1, 0), (0, 1), (0, -1)], rng.randint(2, 4))
    side = rng.uniform(4, 8)
    for dx, dy in ways:
        z, length, rise = rng.uniform(0.4, 0.9) * height, rng.uniform(15, 35), rng.uniform(8, 25)
        root, end = V(0, 0, z), V(dx * (r + length), dy * (r + length), z)
        solid = solid.fuse(_bar(root, end, side)).fuse(_bar(end, end + V(0, 0, rise), side))
    return solid, {"arms": len(ways)}


def shelves(rng):
    """A wall standing on its edge with 1 to 3 shelves reaching square off one face, or off both,
    each at its own height."""
    width, thick, height = rng.uniform(30, 60), rng.uniform(5, 10), rng.uniform(40, 80)
    solid = Part.makeBox(width, thick, height, V(-width / 2, -thick / 2, 0))
    count = rng.randint(1, 3)
    heights = sorted(rng.uniform(10, height - 6) for _ in range(count))
    both = rng.random() < 0.4
    for z in heights:
        shelf, reach = rng.uniform(3, 6), rng.uniform(10, 30)
        along = rng.uniform(0.5, 1.0) * width
        for side in ((1, -1) if both else (1,)):
            y0 = thick / 2 - 0.5 if side > 0 else -thick / 2 - reach
            solid = solid.fuse(Part.makeBox(along, reach + 0.5, shelf,
                                            V(-along / 2, y0, min(z, height - shelf))))
    return solid, {"shelves": count, "both": both}


def cane(rng):
    """A round riser on a round foot bending over along +X round a 90, 135 or 180 degree bend,
    no run after it; after a 180 degree bend (a hook), a leg hanging down from its end or not."""
    r, height = rng.uniform(4, 8), rng.uniform(20, 50)
    bend_radius = rng.uniform(r + 3, 3 * r)
    foot = Part.makeCylinder(r + rng.uniform(3, 8), rng.uniform(3, 5))
    disc = Part.Face(Part.Wire(Part.makeCircle(r, V(0, 0, height), V(0, 0, 1))))
    angle = rng.choice([90, 135, 180])
    solid = foot.fuse([Part.makeCylinder(r, height),
                       disc.revolve(V(bend_radius, 0, height), V(0, 1, 0), angle)])
    description = {"bend_deg": angle, "down": 0.0}
    if angle == 180:
        down = rng.uniform(0, 0.5) * height
        if down > 1:
            solid = solid.fuse(Part.makeCylinder(r, down, V(2 * bend_radius, 0, height - down)))
        description["down"] = down
    return solid, description


def chair(rng):
    """A table's top on four square legs with a back standing on the top's far edge; along X or,
    turned, along Y."""
    leg, length, width = rng.uniform(4, 8), rng.uniform(30, 50), rng.uniform(30, 50)
    height, top = rng.uniform(20, 40), rng.uniform(3, 6)
    back, thick = rng.uniform(15, 40), rng.uniform(3, 6)
    solid = Part.makeBox(length, width, top, V(0, 0, height)).fuse(
        [Part.makeBox(leg, leg, height, V(x, y, 0))
         for x in (0, length - leg) for y in (0, width - leg)])
    solid = solid.fuse(Part.makeBox(length, thick, back, V(0, width - thick, height + top - 0.5)))
    turned = rng.random() < 0.5
    if turned:
        solid.rotate(V(0, 0, 0), V(0, 0, 1), 90)
    return solid, {"back": back, "turned": turned}


def crank(rng):
    """A square bar rising off a square plate, then running three legs along the six directions
    (+X, +Y, +Z; +X, +Z, +Y; +X, +Y, -X back beside the first; +Y, +X, +Z), 15 to 30 mm each."""
    side = rng.uniform(5, 10)
    points = [V(0, 0, 0), V(0, 0, rng.uniform(15, 35))]
    legs = rng.choice([[(1, 0, 0), (0, 1, 0), (0, 0, 1)], [(1, 0, 0), (0, 0, 1), (0, 1, 0)],
                       [(1, 0, 0), (0, 1, 0), (-1, 0, 0)], [(0, 1, 0), (1, 0, 0), (0, 0, 1)]])
    for leg in legs:
        points.append(points[-1] + V(*leg) * rng.uniform(15, 30))
    solid = Part.makeBox(4 * side, 4 * side, 3, V(-2 * side, -2 * side, 0))
    for a, b in zip(points, points[1:]):
        solid = solid.fuse(_bar(a + V(0, 0, side / 2) if a.z == 0 else a, b, side))
    return solid, {"legs": legs, "returns": legs[2] == (-1, 0, 0)}



def _rod(a, b, r):
    """A round rod `r` in radius from point a to point b."""
    return Part.makeCylinder(r, (b - a).Length, a, b - a)


def tripod(rng):
    """Three or four round legs from a circle on the plate leaning in 10 to 40 degrees to meet
    at a point, a round post rising off it or not."""
    legs, spread, height = rng.choice([3, 4]), rng.uniform(10, 40), rng.uniform(30, 60)
    r, post = rng.uniform(3, 6), rng.choice([0.0, rng.uniform(5, 25)])
    top = V(0, 0, height)
    solid = Part.makeCylinder(r, post + r, V(0, 0, height - r)) if post else Part.makeSphere(r, top)
    turn = rng.uniform(0, 90)
    for k in range(legs):
        a = math.radians(turn + 360.0 * k / legs)
        solid = solid.fuse(_rod(V(spread * math.cos(a), spread * math.sin(a), -r), top, r))
    solid = solid.common(Part.makeBox(400, 400, 400, V(-200, -200, 0)))
    return solid, {"legs": legs, "lean_deg": math.degrees(math.atan2(spread, height)),
                   "post": post}


def truss(rng):
    """A braced frame: two square posts on a plate, a beam across their tops and a round brace
    from low on one post up to the other's top, or two crossing (the second a quarter thinner);
    across X or, turned, across Y."""
    post, gap, height = rng.uniform(5, 10), rng.uniform(20, 50), rng.uniform(25, 60)
    r = rng.uniform(2, 4)
    solid = Part.makeBox(2 * post + gap + 10, post + 6, 3, V(-5, -3, 0))
    solid = solid.fuse([Part.makeBox(post, post, height, V(x, 0, 2.5)) for x in (0, post + gap)])
    solid = solid.fuse(Part.makeBox(2 * post + gap, post, post, V(0, 0, height + 2)))
    cross = rng.random() < 0.5
    y = post / 2
    low, high = V(post - 1, y, 3 + post), V(post + gap + 1, y, height)
    braces = [(low, high)] + ([(V(post - 1, y, height), V(post + gap + 1, y, 3 + post))]
                              if cross else [])
    # (The second brace thinner: two rods alike crossing meet along curves OCCT meshes badly. A
    # brace's end disc grazing the beam's underside does too: its end is lowered 0.2 mm where its
    # top edge comes within 0.1 mm of that plane.)
    rods = []
    for k, (a, b) in enumerate(braces):
        radius = r * (1.0 - 0.25 * k)
        u = (b - a).normalize()
        if abs(b.z + radius * math.sqrt(1.0 - u.z * u.z) - (height + 2)) < 0.1:
            b = b - V(0, 0, 0.2)
        rods.append(_rod(a, b, radius))
    solid = solid.fuse(rods)
    return _across(rng, solid, {"braces": len(braces), "brace_deg": math.degrees(
        math.atan2(high.z - low.z, high.x - low.x))})


def pegs(rng):
    """A wall standing on its edge with 1 to 4 round pegs off one face, level or rising 10 to 30
    degrees (a coat rack), each at its own place (pegs may overlap)."""
    width, thick, height = rng.uniform(30, 60), rng.uniform(5, 10), rng.uniform(30, 60)
    solid = Part.makeBox(width, thick, height, V(-width / 2, -thick / 2, 0))
    count = rng.randint(1, 4)
    rise = rng.choice([0.0, 0.0, rng.uniform(10, 30)])
    d = V(0, math.cos(math.radians(rise)), math.sin(math.radians(rise)))
    for _ in range(count):
        r, reach = rng.uniform(2, 5), rng.uniform(10, 30)
        x = rng.uniform(-width / 2 + r + 1, width / 2 - r - 1)
        z = rng.uniform(r + 3, height - r - 3)
        solid = solid.fuse(Part.makeCylinder(r, reach + thick / 2, V(x, 0, z), d))
    return solid, {"pegs": count, "rise_deg": rise}


def gooseneck(rng):
    """A round riser on a round foot bending over along +X, a level run or none, and bending back
    up into a second riser."""
    r, rise, up = rng.uniform(4, 8), rng.uniform(10, 30), rng.uniform(5, 25)
    run, bend_radius = rng.choice([0.0, rng.uniform(5, 25)]), rng.uniform(r + 3, 3 * r)
    z = rise + bend_radius
    first = Part.Face(Part.Wire(Part.makeCircle(r, V(0, 0, rise), V(0, 0, 1))))
    second = Part.Face(Part.Wire(Part.makeCircle(r, V(bend_radius + run, 0, z), V(1, 0, 0))))
    solid = Part.makeCylinder(r + rng.uniform(3, 8), 4).fuse(
        [Part.makeCylinder(r, rise), first.revolve(V(bend_radius, 0, rise), V(0, 1, 0), 90),
         second.revolve(V(bend_radius + run, 0, z + bend_radius), V(0, 1, 0), -90),
         Part.makeCylinder(r, up, V(2 * bend_radius + run, 0, z + bend_radius))] +
        ([Part.makeCylinder(r, run, V(bend_radius, 0, z), V(1, 0, 0))] if run else []))
    return solid, {"run": run, "bend_radius": bend_radius}

FAMILIES = {
    "pipe bend": pipe_bend,
    "hub with blades": hub_with_blades,
    "lug": lug,
    "angle bracket": angle_bracket,
    "turned angle bracket": turned_angle_bracket,
    "leaning branch": leaning_branch,
    "z bracket": z_bracket,
    "manifold": manifold,
    "valve body": valve_body,
    "wye fitting": wye_fitting,
    "handle": handle,
    "feet": feet,
    "candelabra": candelabra,
    "shelves": shelves,
    "cane": cane,
    "chair": chair,
    "crank": crank,
    "tripod": tripod,
    "truss": truss,
    "pegs": pegs,
    "gooseneck": gooseneck,
}


def part(family, index, seed=39):
    """(solid, description) of part `index` of `family` (a key of FAMILIES) for `seed`: one
    valid closed solid standing on the plate (z = 0), the same for the same arguments."""
    rng = random.Random("{}/{}/{}".format(seed, family, index))
    solid, description = FAMILIES[family](rng)
    solid = solid.removeSplitter()
    if not solid.isValid() or len(solid.Solids) != 1:
        raise RuntimeError("{} {} (seed {}) is not one valid solid".format(family, index, seed))
    solid.translate(V(0, 0, -solid.BoundBox.ZMin))
    return solid, dict(description, family=family, index=index, seed=seed)


def support_tolerance(layer, deflection):
    """The unsupported area (mm²) that a layer's mesh sections can show on a part with none: a
    strip as wide as the deflection along its outlines."""
    return layer.outline_length * deflection


def survey_part(solid, description, fill_holes=0.0):
    """Slices `solid` at the defaults (holes up to `fill_holes` mm deposited solid), writes its
    G-code, and reports: components, layers, seconds, the axis' step, worst and summed
    unsupported area, layers over their tolerance (support_tolerance), colliding layers, travel
    routes meeting something, layers out of the thickness bounds, holes filled, notes, the
    components' rules and how many solids the root is (its feet apart on the plate)."""
    start = time.perf_counter()
    result = mas.slice(solid, fill_holes=fill_holes)
    program = result.gcode()
    seconds = time.perf_counter() - start
    deflection = mas.deflection(solid)
    layers = result.layers
    over = [i for i, layer in enumerate(layers)
            if layer.unsupported_area > support_tolerance(layer, deflection)]
    # Thickness bounds as the engine keeps them: everywhere on a layer at most max_layer and
    # more than 0 (planes never cross in the part); at least min_layer but on the last layer of
    # a component, which is thinner where less than that was left.
    lp = result.params
    last = {i for i, layer in enumerate(layers)
            if i + 1 == len(layers) or layers[i + 1].component != layer.component}
    out_of_bounds = [i for i, layer in enumerate(layers)
                     if layer.max_thickness > lp["max_layer"] + 1e-9
                     or layer.min_thickness <= 0.0
                     or (i not in last and layer.min_thickness < lp["min_layer"] - 1e-9)]
    return dict(description, components=len(result.components), layers=len(layers),
                seconds=seconds, step=result.axis.params["step_mm"],
                worst_unsupported=max(l.unsupported_area for l in layers),
                total_unsupported=sum(l.unsupported_area for l in layers),
                unsupported_layers=over, colliding_layers=result.stats["colliding_layers"],
                travel_collisions=len(program.stats["travel_collisions"]),
                layers_out_of_bounds=out_of_bounds,
                filled_holes=len(result.filled_holes), notes=list(result.notes),
                rules=[c.rule for c in result.decomposition],
                feet=len(result.decomposition[0].shape.Solids))


def survey(per_family, seed=39, fill_holes=16.0, families=None):
    """survey_part() of `per_family` parts of each family (all of FAMILIES unless `families`):
    yields each report as it is made."""
    for family in families or FAMILIES:
        for index in range(per_family):
            solid, description = part(family, index, seed)
            yield survey_part(solid, description, fill_holes)
