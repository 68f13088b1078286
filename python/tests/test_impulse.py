# SPDX-License-Identifier: MIT
"""The Python module against the same analytic results as the C++ tests, its arrays against the
per-body accessors, bad input against the exceptions it must raise, and runs against each other."""
import math
import os
import pathlib
import subprocess
import sys

import numpy as np
import pytest

import impulse

SCENES = pathlib.Path(os.environ.get("IMPULSE_SCENES_DIR", pathlib.Path(__file__).parents[2] / "scenes"))
DATA = pathlib.Path(os.environ.get("IMPULSE_TEST_DATA_DIR", pathlib.Path(__file__).parents[2] / "tests" / "data"))
EXAMPLES = pathlib.Path(os.environ.get("IMPULSE_EXAMPLES_DIR", pathlib.Path(__file__).parents[2] / "examples"))
DT = 1e-3


def free_space():
    world = impulse.World(gravity=(0.0, 0.0, 0.0))
    material = world.create_material()
    return world, material


# ---- physics ----


def test_a_constant_force_gives_f_t_over_m():
    world, material = free_space()
    ball = world.create_body(impulse.Sphere(0.1), material=material, mass=2.0, position=(0.3, -0.2, 1.0))
    force = np.array([3.0, -1.0, 0.5])
    n = 1000
    for _ in range(n):
        world.apply_force(ball, force)
        world.step(dt=DT)
    a = force / 2.0
    np.testing.assert_allclose(world.linear_velocities()[ball], a * n * DT, rtol=1e-12)
    # symplectic Euler: x = x0 + a dt^2 n (n + 1) / 2
    np.testing.assert_allclose(world.positions()[ball], [0.3, -0.2, 1.0] + a * DT * DT * n * (n + 1) / 2, rtol=1e-12)
    # the force was for each step only
    assert np.array_equal(world.applied_force(ball), [0.0, 0.0, 0.0])


def test_forces_for_many_bodies_in_one_call():
    world, material = free_space()
    bodies = [world.create_body(impulse.Sphere(0.1), material=material, mass=m, position=(m, 0, 0)) for m in (1.0, 2.0, 4.0)]
    forces = np.array([[1.0, 0.0, 0.0], [0.0, 2.0, 0.0], [0.0, 0.0, 4.0]])
    world.apply_forces(bodies, forces=forces)
    world.step(dt=DT)
    np.testing.assert_allclose(world.linear_velocities(), [[DT, 0, 0], [0, DT, 0], [0, 0, DT]], rtol=1e-15)


def test_a_torque_about_a_principal_axis_spins_up_to_tau_t_over_i():
    world, material = free_space()
    box = world.create_body(impulse.Box((0.1, 0.2, 0.3)), material=material, mass=1.5)
    torque = np.array([0.0, 0.7, 0.0])
    n = 1000
    for _ in range(n):
        world.apply_torque(box, torque)
        world.step(dt=DT)
    iy = 1.5 * (0.2**2 + 0.6**2) / 12.0
    np.testing.assert_allclose(world.principal_inertia(box)[1], iy, rtol=1e-15)
    np.testing.assert_allclose(world.angular_momenta()[box], torque * n * DT, rtol=1e-13, atol=1e-16)
    np.testing.assert_allclose(world.angular_velocities()[box], torque * n * DT / iy, rtol=1e-12, atol=1e-15)
    # the turn about y: theta = tau / I dt^2 n (n + 1) / 2, so q = (cos theta/2, 0, sin theta/2, 0)
    theta = 0.7 / iy * DT * DT * n * (n + 1) / 2
    np.testing.assert_allclose(world.orientations()[box], [math.cos(theta / 2), 0, math.sin(theta / 2), 0], atol=1e-12)


def test_an_impulse_at_an_offset_point_gives_j_over_m_and_r_cross_j():
    world, material = free_space()
    centre = np.array([0.5, 0.0, 2.0])
    box = world.create_body(impulse.Box((0.1, 0.2, 0.3)), material=material, mass=3.0, position=centre)
    j = np.array([0.2, -0.5, 1.0])
    r = np.array([0.05, 0.1, -0.02])
    world.apply_impulse(box, j, point=centre + r)
    state = world.state(box)
    np.testing.assert_allclose(state["linear_velocity"], j / 3.0, rtol=1e-15)
    np.testing.assert_allclose(state["angular_momentum"], np.cross(r, j), rtol=1e-15)
    # identity orientation: w = I^-1 L with the box's principal moments
    np.testing.assert_allclose(state["angular_velocity"], np.cross(r, j) / world.principal_inertia(box), rtol=1e-14)


def test_a_full_inertia_tensor_is_diagonalised():
    world, material = free_space()
    c, s = math.cos(0.6), math.sin(0.6)
    q = np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])
    tensor = q @ np.diag([0.5, 0.8, 1.1]) @ q.T
    box = world.create_body(impulse.Box((0.1, 0.2, 0.3)), material=material, mass=1.0, inertia=tensor)
    np.testing.assert_allclose(world.principal_inertia(box), [0.5, 0.8, 1.1], rtol=1e-14)
    np.testing.assert_allclose(world.inertia(box), tensor, atol=1e-15)
    axes = world.principal_axes(box)
    np.testing.assert_allclose(axes @ np.diag(world.principal_inertia(box)) @ axes.T, tensor, atol=1e-15)


def test_a_body_weighted_off_centre_turns_about_its_centre_of_mass():
    world, material = free_space()
    offset = np.array([0.05, 0.0, 0.0])
    box = world.create_body(impulse.Box((0.1, 0.1, 0.1)), material=material, mass=1.0,
                            angular_velocity=(0.0, 0.0, 2.0), center_of_mass=offset)
    np.testing.assert_array_equal(world.center_of_mass(box), offset)
    for _ in range(500):
        world.step(dt=DT)
    # the centre of mass stays put and the box circles it at 2 rad/s
    angle = 2.0 * world.time
    position, _ = world.shape_pose(box)
    np.testing.assert_allclose(position, [-0.05 * math.cos(angle), -0.05 * math.sin(angle), 0.0], atol=1e-9)
    np.testing.assert_allclose(world.positions()[box], [0.0, 0.0, 0.0], atol=1e-15)
    # moved back to the box's centre: the box stays where it is
    world.set_mass_properties(box, 1.0, world.inertia(box), center_of_mass=(0.0, 0.0, 0.0))
    np.testing.assert_allclose(world.shape_pose(box)[0], position, atol=1e-15)


def test_a_dropped_ball_keeps_its_energy_within_the_symplectic_bound():
    scene = impulse.load_scene(SCENES / "ball_drop_elastic.json")
    world = scene.world
    ball = scene.dynamic_bodies[0]
    mass = world.mass(ball)
    g = 9.81
    start = world.kinetic_energy() + world.potential_energy()
    for _ in range(2000):
        scene.step()
        v = world.linear_velocities()[ball]
        # the arrays give the energies the world reports
        kinetic = 0.5 * mass * v @ v
        assert kinetic == pytest.approx(world.kinetic_energy(), rel=1e-14, abs=1e-14)
        assert mass * g * world.positions()[ball][2] == pytest.approx(world.potential_energy(), rel=1e-14)
        # symplectic Euler samples a moving ball's energy off by at most m g |v| dt / 2
        total = kinetic + world.potential_energy()
        assert abs(total - start) <= mass * g * np.linalg.norm(v) * scene.options.dt / 2 + 1e-9


def test_the_contacts_of_a_resting_box_carry_its_weight_every_step():
    world = impulse.World()
    material = world.create_material(restitution=0.0, friction=0.5)
    ground = world.create_body(impulse.Plane(), material=material, static=True)
    box = world.create_body(impulse.Box((0.2, 0.1, 0.05)), material=material, mass=3.0, position=(0.0, 0.0, 0.05))
    for _ in range(100):
        world.step(dt=DT)
        contacts = world.contacts()
        assert len(contacts["normal_impulses"]) > 0
        assert set(contacts["body_a"]) == {ground} and set(contacts["body_b"]) == {box}
        # the normal points from the box (b) toward the ground (a)
        np.testing.assert_allclose(contacts["normals"], [[0.0, 0.0, -1.0]] * len(contacts["normals"]), atol=1e-12)
        assert contacts["normal_impulses"].sum() == pytest.approx(3.0 * 9.81 * DT, rel=1e-12)
        assert np.abs(contacts["friction_impulses"]).max() < 1e-12
        assert contacts["points"].shape == (len(contacts["normal_impulses"]), 3)


# ---- arrays ----


def test_state_arrays_cover_every_body_in_one_call():
    scene = impulse.load_scene(SCENES / "box_stack_10.json")
    world = scene.world
    scene.step(steps=50)
    n = world.body_count
    assert world.positions().shape == (n, 3)
    assert world.orientations().shape == (n, 4)
    assert world.linear_velocities().shape == (n, 3)
    assert world.angular_velocities().shape == (n, 3)
    for b in range(n):
        state = world.state(b)
        assert np.array_equal(world.positions()[b], state["position"])
        assert np.array_equal(world.orientations()[b], state["orientation"])  # w first
    np.testing.assert_allclose(np.linalg.norm(world.orientations(), axis=1), 1.0, rtol=1e-12)
    chosen = scene.dynamic_bodies[2:5]
    assert np.array_equal(world.positions(chosen), world.positions()[chosen])


def test_written_states_are_read_back_and_a_refused_write_changes_nothing():
    world, material = free_space()
    bodies = [world.create_body(impulse.Sphere(0.1), material=material, mass=1.0, position=(k, 0, 0)) for k in range(3)]
    positions = np.array([[0.0, 1.0, 2.0], [3.0, 4.0, 5.0], [6.0, 7.0, 8.0]])
    velocities = np.array([[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])
    world.set_states(bodies, positions=positions, linear_velocities=velocities)
    assert np.array_equal(world.positions(), positions)
    assert np.array_equal(world.linear_velocities(), velocities)
    bad = positions.copy()
    bad[2, 1] = np.nan
    with pytest.raises(ValueError, match="positions: must be finite"):
        world.set_states(bodies, positions=bad + 1.0)
    assert np.array_equal(world.positions(), positions)
    with pytest.raises(ValueError, match=r"must be an array of shape \(3, 4\)"):
        world.set_states(bodies, orientations=np.ones((3, 3)))


def test_filtered_bodies_pass_through_and_removed_bodies_leave_the_arrays():
    world = impulse.World()
    material = world.create_material(restitution=0.5, friction=0.3)
    ground = world.create_body(impulse.Plane(), material=material, static=True, group=2)
    ball = world.create_body(impulse.Sphere(0.1), material=material, mass=1.0, position=(0, 0, 1), mask=~2 & 0xFFFFFFFF)
    other = world.create_body(impulse.Sphere(0.1), material=material, mass=1.0, position=(1, 0, 1))
    assert not world.collision_enabled(ball, ground)
    world.step(dt=DT, steps=1000)
    n = 1000
    assert world.positions()[ball][2] == pytest.approx(1.0 - 9.81 * DT * DT * n * (n + 1) / 2, abs=1e-12)
    assert world.positions()[other][2] > 0.09  # not filtered: it bounced
    world.remove_body(ball)
    assert not world.contains(ball)
    assert np.isnan(world.positions()[ball]).all()
    v = world.linear_velocities()[other]
    assert world.kinetic_energy() == pytest.approx(0.5 * v @ v + 0.5 * world.angular_velocities()[other] @ world.angular_momenta()[other], rel=1e-14)
    assert world.dynamic_bodies() == [other]


def test_a_snapshot_restores_the_run_bit_for_bit():
    scene = impulse.load_scene(SCENES / "box_stack_10.json")
    scene.step(steps=100)
    snapshot = scene.world.snapshot()
    scene.step(steps=100)
    first = scene.world.positions()
    scene.world.restore(snapshot)
    assert scene.world.time == pytest.approx(snapshot.time)
    scene.step(steps=100)
    assert np.array_equal(scene.world.positions(), first)


def test_step_options_as_an_object_or_as_keywords_are_the_same():
    def run(**how):
        scene = impulse.load_scene(SCENES / "box_stack_10.json")
        if "options" in how:
            scene.world.step(how["options"], steps=200)
        else:
            scene.world.step(steps=200, **how)
        return scene.world.state_hash()

    options = impulse.StepOptions(dt=2e-3, contact_iterations=5, shock_propagation=False, resting_approach=0.5)
    assert options.scheme == "guendelman"
    assert options.resting_approach == 0.5
    assert run(options=options) == run(dt=2e-3, contact_iterations=5, shock_propagation=False, resting_approach=0.5)
    assert run(dt=2e-3) != run(dt=2e-3, shock_propagation=False, contact_iterations=5)


def test_two_runs_give_identical_arrays():
    def run():
        world = impulse.World()
        material = world.create_material(restitution=0.3, friction=0.5)
        world.create_body(impulse.Plane(), material=material, static=True)
        for k in range(12):
            shape = [impulse.Sphere(0.1), impulse.Box((0.1, 0.08, 0.06)), impulse.Capsule(0.05, 0.08)][k % 3]
            world.create_body(shape, material=material, density=500.0,
                              position=(0.03 * math.cos(k), 0.03 * math.sin(k), 0.15 + 0.22 * k),
                              orientation=(math.cos(0.2 * k), math.sin(0.2 * k), 0.0, 0.0))
        world.step(steps=1500)
        return world.positions(), world.orientations(), world.linear_velocities(), world.angular_velocities()

    first, second = run(), run()
    for a, b in zip(first, second):
        assert np.array_equal(a, b)


def test_meshes_from_files_and_models():
    mesh = impulse.load_mesh(SCENES / "meshes" / "torus.obj", scale=0.5)
    assert mesh.triangle_count > 0 and mesh.volume > 0
    world = impulse.World()
    material = world.create_material()
    world.create_body(impulse.Plane(), material=material, static=True)
    torus = world.create_body(mesh, material=material, density=500.0, position=(0, 0, 0.5))
    world.step(steps=300)
    assert world.positions()[torus][2] < 0.5
    if impulse.has_mujoco:
        model = impulse.load(EXAMPLES / "falling_shapes.xml")
        assert len(model.dynamic_bodies) > 0 and all(model.body_names[b] for b in model.dynamic_bodies)
        start = model.world.positions(model.dynamic_bodies)
        model.step(steps=100)
        assert not np.array_equal(model.world.positions(model.dynamic_bodies), start)


# ---- warnings: legal input that gives a poor simulation (docs/warnings.md) ----


def test_warnings_say_what_would_make_a_run_poor():
    scene = impulse.load_scene(SCENES / "ball_drop_elastic.json")
    assert scene.warnings() == []
    (step,) = scene.warnings(dt=1.0)
    assert "dt = 1 s is too large" in step and '"ball"' in step
    world, material = free_space()
    world.create_body(impulse.Sphere(0.1), material=material, mass=1.0)
    world.create_body(impulse.Sphere(0.1), material=material, mass=1.0, position=(0.15, 0.0, 0.0))
    (overlap,) = world.warnings(names=["a", "b"])
    assert '"a" and "b" overlap by 0.05 m' in overlap
    assert "body 0 and body 1 overlap" in world.warnings(dt=1e-3)[0]


def test_a_body_the_tolerances_do_not_serve_is_refused_when_stepped():
    world, material = free_space()
    world.create_body(impulse.Sphere(1e-5), material=material, mass=1e-11)
    with pytest.raises(ValueError, match=r"size: body 0: .*push_out_allowance \(0\.0001 m\)"):
        world.step(dt=1e-3)
    world.step(dt=1e-4, contact_thickness=1e-7, push_out_allowance=1e-6)


# ---- bad input ----


def test_a_bad_scene_file_raises_with_the_file_and_the_field():
    with pytest.raises(impulse.SceneError, match=r"negative_radius\.json: .*radius"):
        impulse.load_scene(DATA / "bad" / "negative_radius.json")
    with pytest.raises(impulse.SceneError, match="missing.json"):
        impulse.load_scene(DATA / "bad" / "missing.json")
    with pytest.raises(ValueError, match="bad_json.json"):  # SceneError is a ValueError
        impulse.load_scene(DATA / "bad" / "bad_json.json")
    if impulse.has_mujoco:
        with pytest.raises(impulse.ModelError, match="unsupported.xml"):
            impulse.load_model(DATA / "mujoco" / "unsupported.xml")


def test_unknown_and_removed_handles_are_refused():
    world, material = free_space()
    ball = world.create_body(impulse.Sphere(0.1), material=material, mass=1.0)
    with pytest.raises(ValueError, match=r"body: no body 7 in this world \(it has 1\)"):
        world.apply_force(7, (1.0, 0.0, 0.0))
    with pytest.raises(ValueError, match="body: no body -1"):
        world.state(-1)
    world.remove_body(ball)
    with pytest.raises(ValueError, match="body: body 0 was removed"):
        world.apply_impulse(ball, (1.0, 0.0, 0.0))


def test_bad_values_are_refused_naming_the_field():
    world, material = free_space()
    ball = world.create_body(impulse.Sphere(0.1), material=material, mass=1.0)
    with pytest.raises(ValueError, match="force: must be finite"):
        world.apply_force(ball, (math.nan, 0.0, 0.0))
    with pytest.raises(ValueError, match=r"torque: must be 3 numbers, got an array of shape \(2,\)"):
        world.apply_torque(ball, (1.0, 2.0))
    with pytest.raises(ValueError, match="mass: must be a positive finite number"):
        world.set_mass(ball, -1.0)
    with pytest.raises(ValueError, match="inertia: must be positive definite"):
        world.set_mass_properties(ball, 1.0, (1.0, 1.0, -1.0))
    with pytest.raises(ValueError, match="radius: must be a positive finite number"):
        world.create_body(impulse.Sphere(-1.0), material=material, mass=1.0)
    with pytest.raises(ValueError, match="shape: must be impulse.Sphere"):
        world.create_body("ball", material=material, mass=1.0)
    with pytest.raises(ValueError, match="dt: must be a positive finite number"):
        world.step(dt=-1.0)
    with pytest.raises(ValueError, match='scheme: must be "guendelman" or "traditional"'):
        world.step(scheme="euler")
    with pytest.raises(TypeError, match="unexpected keyword argument 'dtt'"):
        world.step(dtt=1e-3)
    assert world.time == 0.0


# ---- the example ----


def test_the_drop_pile_example_writes_its_plot(tmp_path):
    out = tmp_path / "energy.png"
    done = subprocess.run([sys.executable, str(EXAMPLES / "python" / "drop_pile.py"), "--bodies", "8",
                           "--duration", "0.5", "--out", str(out)], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "kinetic energy" in done.stdout
