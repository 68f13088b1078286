#!/usr/bin/env python3
# SPDX-License-Identifier: MIT
"""Writes the generated reference scenes (stacks, pyramid, stacking regressions, tipping, nonconvex) into scenes/.

Run from anywhere: python3 scripts/generate_scenes.py. The hand-written scenes 1-8 are not touched.
"""
import json
import math
import pathlib
import random
import re

SCENES = pathlib.Path(__file__).resolve().parent.parent / "scenes"
GROUND = {"name": "ground", "static": True, "shape": {"type": "plane", "normal": [0, 0, 1], "offset": 0},
          "material": "default"}


def write(name, description, bodies, duration, materials=None, dt=0.001):
    scene = {"name": name, "description": description, "gravity": [0, 0, -9.81], "dt": dt, "duration": duration,
             "materials": materials or {"default": {"restitution": 0.0, "friction": 0.5}}, "bodies": bodies}
    text = json.dumps(scene, indent=2)
    # keep short numeric arrays on one line
    text = re.sub(r"\[\s*([-0-9.e, \n]+?)\s*\]", lambda m: "[" + ", ".join(x.strip() for x in m.group(1).split(",")) + "]", text)
    (SCENES / f"{name}.json").write_text(text + "\n")


def box(name, half, position, mass=None, density=None, static=False, material="default", orientation=None,
        exact=False):
    """A box body; exact keeps the position's every digit (a tilted box whose edge must touch a plane)."""
    body = {"name": name}
    if static:
        body["static"] = True
    body["shape"] = {"type": "box", "half_extents": [round(h, 12) for h in half]}
    if mass is not None:
        body["mass"] = mass
    if density is not None:
        body["density"] = density
    body["position"] = list(position) if exact else [round(p, 12) for p in position]
    if orientation is not None:
        body["orientation"] = orientation
    body["material"] = material
    return body


def box_stack(n, duration=20.0):
    cubes = [box(f"cube{k}", [0.1] * 3, [0, 0, 0.1 + 0.2 * k], mass=1.0) for k in range(n)]
    write(f"box_stack_{n}", f"Reference scene 9: {n} cubes of side 0.2 stacked exactly on the ground; nothing may move.",
          [GROUND] + cubes, duration)


def pyramid(bottom=20):
    cubes = []
    for row in range(bottom):
        count = bottom - row
        for i in range(count):
            x = (i - (count - 1) / 2) * 0.21
            cubes.append(box(f"r{row}c{i}", [0.1] * 3, [x, 0, 0.1 + 0.2 * row], mass=1.0))
    write("pyramid", f"Reference scene 10: a 2-D pyramid of {len(cubes)} cubes of side 0.2, bottom row of {bottom}, "
          "gaps of 0.01 in a row; it must stand.", [GROUND] + cubes, 10.0)


def heavy_on_light():
    masses = [1, 10, 100, 1, 1000]
    cubes = [box(f"cube{k}_{m}kg", [0.1] * 3, [0, 0, 0.1 + 0.2 * k], mass=float(m)) for k, m in enumerate(masses)]
    write("heavy_on_light", "Five cubes of side 0.2 with masses 1, 10, 100, 1, 1000 kg from the bottom up; the heavy "
          "cubes must not sink through the light ones.", [GROUND] + cubes, 10.0)


def lintel():
    bodies = [GROUND]
    bodies += [box(f"left{k}", [0.1, 0.1, 0.1], [-0.4, 0, 0.1 + 0.2 * k], density=500.0) for k in range(2)]
    bodies += [box(f"right{k}", [0.1, 0.1, 0.05], [0.4, 0, 0.05 + 0.1 * k], density=500.0) for k in range(4)]
    bodies.append(box("lintel", [0.5, 0.1, 0.05], [0, 0, 0.45], density=500.0))
    write("lintel", "A 1.0 x 0.2 x 0.1 lintel across two stacks of equal height: 2 cubes on the left, 4 half-height "
          "boxes on the right. It must stand; breadth-first levels would deadlock here.", bodies, 10.0)


def seesaw():
    bodies = [GROUND,
              box("pivot", [0.05, 0.2, 0.15], [0, 0, 0.15], static=True),
              box("plank", [1.0, 0.15, 0.025], [0, 0, 0.325], mass=10.0),
              box("light", [0.1, 0.1, 0.1], [-0.85, 0, 0.45], mass=5.0),
              box("heavy", [0.1, 0.1, 0.1], [0.85, 0, 1.45], mass=20.0)]
    write("seesaw", "A 10 kg plank on a static pivot, a 5 kg cube at rest on one end and a 20 kg cube dropped from "
          "1 m onto the other: the heavy side goes down and the light cube is thrown up.", bodies, 3.0)


PLANK = [0.25, 0.1, 0.05]  # a 0.5 x 0.2 x 0.1 plank


def plank_stack(offsets):
    """Planks of 1 kg stacked flush on the ground, each moved along +x by offsets[k] from the one below."""
    x, bodies = 0.0, []
    for k in range(len(offsets) + 1):
        if k > 0:
            x += offsets[k - 1]
        bodies.append(box(f"plank{k + 1}", PLANK, [x, 0, 0.05 + 0.1 * k], mass=1.0))
    return bodies


def overhang(name, d, duration, verdict):
    """Four planks each offset d past the one below: the upper three's centre of mass lies 2 d from the
    bottom plank's centre, against its edge at 0.25; the upper two on plank 2 at 1.5 d, the top one at d."""
    write(name, f"Four planks 0.5 x 0.2 x 0.1 m of 1 kg stacked flush on the ground, mu = 0.6, eps = 0, each offset "
          f"{d} m along +x from the plank below. The upper three's centre of mass is at 2 d = {2 * d:.3f} m from the "
          f"bottom plank's centre, {abs(2 * d - 0.25) * 1000:.0f} mm {'past' if 2 * d > 0.25 else 'inside'} its edge "
          f"at 0.25 m; every smaller sub-stack is within its support (the upper two at 1.5 d = {1.5 * d:.4f}, the "
          f"top one at d = {d} from the centre of the plank below). {verdict}",
          [GROUND] + plank_stack([d] * 3), duration, materials={"default": {"restitution": 0.0, "friction": 0.6}})


def harmonic_stack():
    """Six planks, the k-th from the top offset 0.9 L / (2 k) past the one below (L = 0.5, k = 1..5): the top k
    planks' centre of mass is 0.9 L / 2 = 0.225 from the centre of the plank below, 25 mm inside its edge."""
    offsets = [0.9 * 0.5 / (2 * k) for k in range(5, 0, -1)]  # from the bottom up: k = 5, 4, 3, 2, 1
    write("harmonic_stack", "Six planks 0.5 x 0.2 x 0.1 m of 1 kg stacked flush on the ground, mu = 0.6, eps = 0, "
          "the k-th from the top offset 0.9 L / (2 k) past the one below (L = 0.5; k = 5..1 from the bottom up: "
          "0.045, 0.05625, 0.075, 0.1125, 0.225 m; the top plank's centre 0.51375 m from the bottom one's). The top "
          "k planks' centre of mass is then 0.225 m from the centre of the plank below, 25 mm (0.1 L / 2) inside "
          "its edge, for every k: it must stand, every plank within 1 mm of its start over 5 s.",
          [GROUND] + plank_stack(offsets), 5.0, materials={"default": {"restitution": 0.0, "friction": 0.6}})


def tower_drop_time(n, degrees, lam):
    """When the top cube's centre of a tower of n cubes (side 0.2) tipping rigidly about its bottom downhill
    edge has dropped 0.1 m: q'' = lambda^2 sin q from rest, q the centre of mass's angle past the vertical."""
    up = (-math.sin(math.radians(degrees)), math.cos(math.radians(degrees)))  # in (downhill, normal)
    q0 = math.atan2(-0.1 * up[1] - 0.1 * n * up[0], -0.1 * up[0] + 0.1 * n * up[1])
    top = (-0.1, 0.2 * n - 0.1)

    def height(turn):
        c, s_ = math.cos(turn), math.sin(turn)
        return (top[0] * c + top[1] * s_) * up[0] + (-top[0] * s_ + top[1] * c) * up[1]

    q, w, t, step = q0, 0.0, 0.0, 1e-5
    while height(0.0) - height(q - q0) <= 0.1:
        w += step * lam * lam * math.sin(q)
        q += step * w
        t += step
    return t


def leaning_tower(n, degrees=15, mu=0.9, name=None):
    """n cubes of side 0.2 stacked along the normal of a plane inclined `degrees` (downhill is +x)."""
    angle = math.radians(degrees)
    normal = [math.sin(angle), 0.0, math.cos(angle)]
    bodies = [{"name": "incline", "static": True, "shape": {"type": "plane", "normal": normal, "offset": 0},
               "material": "default"}]
    for k in range(n):
        bodies.append(box(f"cube{k}", [0.1] * 3, [(0.1 + 0.2 * k) * c for c in normal], mass=1.0,
                          orientation={"axis": [0, 1, 0], "angle_deg": degrees}, exact=True))
    # seen from the bottom cube's downhill edge, the centre of mass is atan(0.1 / (0.1 n)) uphill of
    # the incline's normal, which leans `degrees` downhill of the vertical
    past = degrees - math.degrees(math.atan2(0.1, 0.1 * n))
    rigid = math.sqrt(n * 9.81 * 0.1 * math.hypot(1, n) / (n * 0.04 * (1 + n * n) / 3))
    if n * math.tan(angle) > 1:
        verdict = (f"n tan {degrees} = {n * math.tan(angle):.3f} > 1: the centre of mass is {past:.3f} degrees "
                   "past the vertical over the bottom cube's downhill edge, and the tower tips over about that edge "
                   f"(mu = {mu} > tan {degrees} = {math.tan(angle):.3f}: it does not slide). Rigid about the edge, "
                   f"lambda = sqrt(m g d / I_edge) = {rigid:.3f} /s, and the top cube's centre has dropped 0.1 m "
                   f"after {tower_drop_time(n, degrees, rigid):.3f} s.")
        duration = 3.0
    else:
        verdict = (f"n tan {degrees} = {n * math.tan(angle):.3f} < 1: the centre of mass is {-past:.3f} degrees "
                   f"uphill of the vertical over the bottom cube's downhill edge and mu = {mu} > tan {degrees} = "
                   f"{math.tan(angle):.3f}: it stands, every cube within 1 mm of its start over 5 s.")
        duration = 5.0
    write(name or f"leaning_tower_{n}", f"{n} cubes of side 0.2, 1 kg, stacked flush along the normal of a static "
          f"plane through the origin inclined {degrees} degrees (normal (sin {degrees}, 0, cos {degrees}); downhill "
          f"is +x), each rotated {degrees} degrees about y, the bottom one flat on the plane; mu = {mu}, eps = 0. A "
          f"tower of n tips iff n tan {degrees} > 1. {verdict}", bodies, duration,
          materials={"default": {"restitution": 0.0, "friction": mu}})


def domino(name, past_deg, duration, verdict):
    """A 0.05 x 0.2 x 0.4 box tilted about y by the critical angle atan(0.05 / 0.4) plus past_deg, its bottom
    edge along y at x = 0.025 exactly on the ground: centre = edge + R (-0.025, 0, 0.2)."""
    critical = math.degrees(math.atan2(0.05, 0.4))
    tilt = critical + past_deg
    t = math.radians(tilt)
    centre = [0.025 - 0.025 * math.cos(t) + 0.2 * math.sin(t), 0.0, 0.025 * math.sin(t) + 0.2 * math.cos(t)]
    bodies = [GROUND, box("domino", [0.025, 0.1, 0.2], centre, mass=1.0,
                          orientation={"axis": [0, 1, 0], "angle_deg": tilt}, exact=True)]
    write(name, "A domino 0.05 x 0.2 x 0.4 m (thickness along x, width along y, height along z), 1 kg, mu = 0.6, "
          f"eps = 0, released from rest tilted {tilt:.4f} degrees about y with its bottom edge at x = 0.025 exactly "
          f"on the ground: the critical angle atan(0.05 / 0.4) = {critical:.4f} degrees "
          f"{'plus' if past_deg > 0 else 'minus'} {abs(past_deg):g} degree. {verdict}", bodies, duration,
          materials={"default": {"restitution": 0.0, "friction": 0.6}})


def tipping_scenes():
    overhang("overhang_topples", 0.135, 2.0, "The upper three topple off the bottom plank's edge: rigid about that "
             "edge (lambda = 4.84 /s, 7.6 degrees past balance) the top plank's centre has dropped 0.1 m after "
             "0.46 s.")
    overhang("overhang_stands", 0.115, 5.0, "It must stand: every plank within 1 mm of its start over 5 s.")
    harmonic_stack()
    leaning_tower(3)
    leaning_tower(4)
    for n in (5, 6, 20):
        leaning_tower(n, degrees=10, mu=0.8, name=f"incline_tower_{n}")
    domino("domino_falls", 1.0, 3.0, "Its centre of mass is 1 degree past the vertical over that edge: it falls "
           "over (lambda = sqrt(m g d / I_edge) = 6.04 /s; tilted 80 degrees after 0.83 s) and ends at rest lying "
           "on its broad face, centre at z = 0.025.")
    domino("domino_rocks_back", -1.0, 20.0, "Its centre of mass is 1 degree short of the vertical over that edge: "
           "it rocks back, upright after 0.439 s, never tilts past the critical angle the other way (at most 6.125 "
           "degrees by energy), and ends at rest standing on its base, centre at z = 0.2. Landing on the opposite "
           "edge with eps = 0 does not stop a slender block: it rocks on about that edge with its angular velocity "
           "times 1 - 1.5 sin^2 7.125 = 0.977 (Housner 1963), amplitudes 5.32, 4.79, 4.39 ... degrees, and is at "
           "rest after 17.07 s.")


def mesh(name, file, position, orientation=None, mass=None, density=None, static=False, material="default"):
    """A mesh body; position and orientation place the mesh file's own frame."""
    body = {"name": name}
    if static:
        body["static"] = True
    body["shape"] = {"type": "mesh", "file": f"meshes/{file}"}
    if mass is not None:
        body["mass"] = mass
    if density is not None:
        body["density"] = density
    body["position"] = [round(p, 12) for p in position]
    if orientation is not None:
        body["orientation"] = orientation
    body["material"] = material
    return body


def ring_on_peg():
    bodies = [GROUND, mesh("peg", "peg.obj", [0, 0, 0], static=True),
              mesh("ring", "ring.obj", [0.05, 0, 1.0], {"axis": [1, 0, 0], "angle_deg": 30}, mass=1.0)]
    write("ring_on_peg", "Reference scene 13: a torus (hole radius 0.25) tilted 30 degrees falls over a static peg of "
          "radius 0.15; it must end on the ground around the peg, not on its top as its convex hull would.",
          bodies, 3.0)


def tori_stack():
    bodies = [GROUND] + [mesh(f"torus{k}", "torus.obj", [0, 0, 0.05 + 0.1 * k], mass=1.0) for k in range(3)]
    write("tori_stack", "Three tori (centre-line radius 0.2, tube radius 0.05) stacked flat, touching; mesh against "
          "mesh resting contact: they must stand.", bodies, 5.0)


def random_unit_quaternion(rng):
    # uniform over rotations (Shoemake's subgroup algorithm)
    u1, u2, u3 = rng.random(), rng.random(), rng.random()
    a, b = math.sqrt(1 - u1), math.sqrt(u1)
    return [round(x, 12) for x in (a * math.sin(2 * math.pi * u2), a * math.cos(2 * math.pi * u2),
                                    b * math.sin(2 * math.pi * u3), b * math.cos(2 * math.pi * u3))]


# middle of the bounding box of the meshes whose file origin is not at their middle
FILE_BOX_CENTRES = {"l_block.obj": (0.06, 0.06, 0.03)}


def rotate(q, v):
    """Rotates v by the unit quaternion q = [w, x, y, z]."""
    w, x, y, z = q
    tx, ty, tz = 2 * (y * v[2] - z * v[1]), 2 * (z * v[0] - x * v[2]), 2 * (x * v[1] - y * v[0])
    return (v[0] + w * tx + y * tz - z * ty, v[1] + w * ty + z * tx - x * tz, v[2] + w * tz + x * ty - y * tx)


def layered_height(n, per_row, spacing):
    """The walls' height for n bodies dropped in layers of per_row x per_row from z = 0.3."""
    per_layer = per_row * per_row
    layers = (n + per_layer - 1) // per_layer
    return 0.3 + spacing * (layers - 1) + 1.0


def walled_box(inner, height):
    """Four static walls 0.2 m thick around the square |x|, |y| < inner, `height` tall."""
    return [box(name, half, centre, static=True) for name, half, centre in (
        ("wall_x_minus", [0.1, inner + 0.2, height / 2], [-(inner + 0.1), 0, height / 2]),
        ("wall_x_plus", [0.1, inner + 0.2, height / 2], [inner + 0.1, 0, height / 2]),
        ("wall_y_minus", [inner, 0.1, height / 2], [0, -(inner + 0.1), height / 2]),
        ("wall_y_plus", [inner, 0.1, height / 2], [0, inner + 0.1, height / 2]))]


def jittered_slot(k, per_row, spacing, rng):
    """Body k's drop position: layers of per_row x per_row slots from z = 0.3, x and y jittered by 2 cm."""
    layer, slot = divmod(k, per_row * per_row)
    row, column = divmod(slot, per_row)
    return [(column - (per_row - 1) / 2) * spacing + rng.uniform(-0.02, 0.02),
            (row - (per_row - 1) / 2) * spacing + rng.uniform(-0.02, 0.02),
            0.3 + spacing * layer]


def nonconvex_pile(n):
    rng = random.Random(14)
    pieces = ["small_torus.obj", "l_block.obj", "star.obj", "dumbbell.obj", "gear.stl"]
    per_row, spacing = 8, 0.25
    bodies = [GROUND] + walled_box(1.0, layered_height(n, per_row, spacing))
    for k in range(n):
        position = jittered_slot(k, per_row, spacing, rng)
        piece = pieces[k % len(pieces)]
        orientation = random_unit_quaternion(rng)
        # the scene places a mesh's file frame: put the middle of each piece's box at the slot
        offset = rotate(orientation, FILE_BOX_CENTRES.get(piece, (0.0, 0.0, 0.0)))
        position = [round(p - o, 12) for p, o in zip(position, offset)]
        bodies.append(mesh(f"piece{k}", piece, position, orientation, density=1000.0))
    write(f"nonconvex_pile_{n}", f"Reference scene 14: {n} nonconvex meshes (tori, L-blocks, stars, dumbbells, gears) "
          "dropped into a 2 m x 2 m box with random orientations; mu = 0.5, eps = 0.3. They must settle without "
          "interpenetrating.", bodies, 10.0, materials={"default": {"restitution": 0.3, "friction": 0.5}})


def read_initial_states(name):
    """Rows of scenes/initial-states/NAME.csv (the t = 0 rows of the trajectory format), by body."""
    rows = (SCENES / "initial-states" / f"{name}.csv").read_text().splitlines()
    header = rows[0].split(",")
    states = [dict(zip(header, (float(x) for x in row.split(",")))) for row in rows[1:] if row]
    return sorted(states, key=lambda state: state["body"])


def pile(kind, n):
    """Reference scenes 11 and 12: a ground plane and four static walls 0.2 thick, inner faces at
    x, y = +-2, from z = 0 to 1 m above the top layer; the bodies start at the shipped states."""
    states = read_initial_states(f"{kind}_pile_{n}")
    height = max(state["z"] for state in states) + 1.0
    bodies = [GROUND]
    for name, half, centre in (("wall_x_minus", [0.1, 2.2, height / 2], [-2.1, 0, height / 2]),
                               ("wall_x_plus", [0.1, 2.2, height / 2], [2.1, 0, height / 2]),
                               ("wall_y_minus", [2.0, 0.1, height / 2], [0, -2.1, height / 2]),
                               ("wall_y_plus", [2.0, 0.1, height / 2], [0, 2.1, height / 2])):
        bodies.append(box(name, half, centre, static=True))
    for state in states:
        k = int(state["body"])
        position = [state["x"], state["y"], state["z"]]
        if kind == "sphere":
            body = {"name": f"ball{k}", "shape": {"type": "sphere", "radius": 0.1}, "mass": 1.0,
                    "position": position, "material": "default"}
        else:
            body = box(f"cube{k}", [0.1] * 3, position, mass=1.0)
            body["orientation"] = [state["qw"], state["qx"], state["qy"], state["qz"]]
        if any(state[v] != 0.0 for v in ("vx", "vy", "vz")):
            body["velocity"] = [state["vx"], state["vy"], state["vz"]]
        if any(state[w] != 0.0 for w in ("wx", "wy", "wz")):
            body["angular_velocity"] = [state["wx"], state["wy"], state["wz"]]
        bodies.append(body)
    number = 11 if kind == "sphere" else 12
    shape = "spheres of radius 0.1" if kind == "sphere" else "cubes of side 0.2"
    write(f"{kind}_pile_{n}", f"Reference scene {number}: {n} {shape}, m = 1, start at rest at the positions of "
          f"initial-states/{kind}_pile_{n}.csv and fall into a 4 m x 4 m box; mu = 0.5, eps = 0.3. None may escape "
          "the box or end inside another.", bodies, 5.0,
          materials={"default": {"restitution": 0.3, "friction": 0.5}})


def mixed_pile(n, meshes):
    """Spheres, cubes, capsules and nonconvex meshes, each with its own random restitution and
    friction, fall into the 4 m x 4 m box of scenes 11 and 12 (a long run: 20 s)."""
    rng = random.Random(35)
    pieces = ["small_torus.obj", "l_block.obj", "star.obj", "dumbbell.obj", "gear.stl"]
    per_row, spacing = 10, 0.4
    materials = {"default": {"restitution": 0.0, "friction": 0.5}}
    bodies = [GROUND] + walled_box(2.0, layered_height(n, per_row, spacing))
    # every fourth body of the first 4 * meshes is a mesh; the rest cycle sphere, cube, capsule
    kinds = []
    for k in range(n):
        if k < 4 * meshes and k % 4 == 3:
            kinds.append("mesh")
        else:
            kinds.append(("sphere", "cube", "capsule")[len([x for x in kinds if x != "mesh"]) % 3])
    for k in range(n):
        position = jittered_slot(k, per_row, spacing, rng)
        orientation = random_unit_quaternion(rng)
        material = f"body{k}"
        materials[material] = {"restitution": round(rng.uniform(0.0, 0.8), 3),
                               "friction": round(rng.uniform(0.1, 1.0), 3)}
        kind = kinds[k]
        if kind == "mesh":
            piece = pieces[(k // 4) % len(pieces)]
            offset = rotate(orientation, FILE_BOX_CENTRES.get(piece, (0.0, 0.0, 0.0)))
            position = [round(p - o, 12) for p, o in zip(position, offset)]
            body = mesh(f"{piece.split('.')[0]}{k}", piece, position, orientation, density=1000.0, material=material)
        elif kind == "cube":
            body = box(f"cube{k}", [0.1] * 3, position, density=1000.0, material=material, orientation=orientation)
        else:
            shape = {"type": "sphere", "radius": 0.1} if kind == "sphere" else \
                {"type": "capsule", "radius": 0.07, "half_length": 0.09}
            body = {"name": f"{kind}{k}", "shape": shape, "density": 1000.0,
                    "position": [round(p, 12) for p in position], "orientation": orientation, "material": material}
        bodies.append(body)
    write(f"mixed_pile_{n}", f"{n} bodies ({meshes} nonconvex meshes; spheres, cubes and capsules share the rest), "
          "each with its own random restitution in [0, 0.8] and friction in [0.1, 1], fall into the 4 m x 4 m box "
          "of scenes 11 and 12 and settle over 20 s: a long run that must keep every number finite, every body "
          "in the box, the energy below its start and every overlap under 1 % of the smaller body.",
          bodies, 20.0, materials=materials)


if __name__ == "__main__":
    box_stack(10)
    box_stack(50)
    pyramid()
    heavy_on_light()
    lintel()
    seesaw()
    ring_on_peg()
    tori_stack()
    nonconvex_pile(200)
    nonconvex_pile(1000)
    tipping_scenes()
    for pile_kind in ("sphere", "box"):
        for pile_size in (1000, 10000):
            # the piles' initial states are the reference scenes' own data, not shipped with impulse
            if (SCENES / "initial-states" / f"{pile_kind}_pile_{pile_size}.csv").exists():
                pile(pile_kind, pile_size)
            else:
                print(f"{pile_kind}_pile_{pile_size}: kept as shipped (no initial-states/{pile_kind}_pile_{pile_size}.csv)")
    mixed_pile(1000, meshes=100)
