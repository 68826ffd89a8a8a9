"""twolink.export: the MJCF and URDF models give MuJoCo twolink's dynamics, limits and gravity."""

import dataclasses

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from conftest import acceleration_scale, dynamic_arms
from twolink import TwoLinkArm, arms, export
from twolink.errors import InputTypeError
from twolink.statics import Wall

mujoco = pytest.importorskip("mujoco")

states = st.tuples(
    *[st.floats(min_value=-np.pi, max_value=np.pi) for _ in range(2)],
    *[st.floats(min_value=-5.0, max_value=5.0) for _ in range(2)],
    *[st.floats(min_value=-50.0, max_value=50.0) for _ in range(2)],
)


def mujoco_qacc(model, q, qd, tau, *, applied=False):
    data = mujoco.MjData(model)
    data.qpos[:], data.qvel[:] = q, qd
    if applied:
        data.qfrc_applied[:] = tau
    else:
        data.ctrl[:] = tau
    mujoco.mj_forward(model, data)
    return data.qacc.copy()


def relative_error(got, expected, scale=None):
    scale = np.max(np.abs(expected)) if scale is None else scale
    return np.max(np.abs(got - expected)) / max(scale, 1e-300)


@settings(max_examples=30, deadline=None)
@given(arm=dynamic_arms(), state=states)
def test_mjcf_accelerations_equal_forward_dynamics(arm, state):
    q, qd, tau = np.array(state[:2]), np.array(state[2:4]), np.array(state[4:])
    model = mujoco.MjModel.from_xml_string(export.to_mjcf(arm))
    expected = arm.forward_dynamics(q, qd, tau)
    scale = acceleration_scale(arm, q, qd, tau)
    assert relative_error(mujoco_qacc(model, q, qd, tau), expected, scale) < 1e-9
    # the motors are plain joint torques: ctrl and qfrc_applied act the same
    assert (
        relative_error(mujoco_qacc(model, q, qd, tau, applied=True), expected, scale)
        < 1e-9
    )


@settings(max_examples=30, deadline=None)
@given(arm=dynamic_arms(), state=states, z_up=st.booleans())
def test_urdf_accelerations_equal_forward_dynamics_with_gravity_set(arm, state, z_up):
    q, qd, tau = np.array(state[:2]), np.array(state[2:4]), np.array(state[4:])
    model = mujoco.MjModel.from_xml_string(export.to_urdf(arm, z_up=z_up))
    assert (
        model.nq == 2 and model.nu == 0
    )  # URDF has no motors: torques go in qfrc_applied
    model.opt.gravity[:] = (0.0, 0.0, -arm.g) if z_up else (0.0, -arm.g, 0.0)
    got = mujoco_qacc(model, q, qd, tau, applied=True)
    assert (
        relative_error(
            got, arm.forward_dynamics(q, qd, tau), acceleration_scale(arm, q, qd, tau)
        )
        < 1e-9
    )


def test_urdf_keeps_mujoco_default_gravity_perpendicular_unless_upright():
    arm = TwoLinkArm(1.0, 0.7, m1=2.0, m2=1.2, g=9.81)
    q, qd, tau = np.array([0.3, -0.5]), np.zeros(2), np.zeros(2)
    flat = mujoco.MjModel.from_xml_string(export.to_urdf(arm))
    upright = mujoco.MjModel.from_xml_string(export.to_urdf(arm, z_up=True))
    horizontal = dataclasses.replace(arm, g=0.0)
    # MuJoCo's default gravity is -9.81 along z: the flat URDF is a horizontal arm, the upright one vertical
    assert np.allclose(mujoco_qacc(flat, q, qd, tau, applied=True), 0.0, atol=1e-12)
    assert np.allclose(horizontal.forward_dynamics(q, qd, tau), 0.0)
    assert (
        relative_error(
            mujoco_qacc(upright, q, qd, tau, applied=True),
            arm.forward_dynamics(q, qd, tau),
        )
        < 1e-9
    )


@pytest.mark.parametrize("preset", [arms.two_metre, arms.ten, arms.osake])
def test_mjcf_and_urdf_of_the_presets_load(preset):
    for text in (export.to_mjcf(preset), export.to_urdf(preset)):
        model = mujoco.MjModel.from_xml_string(text)
        assert model.nq == 2
        assert [model.joint(k).name for k in range(2)] == ["q1", "q2"]


def test_base_offset_carries_over():
    model = mujoco.MjModel.from_xml_string(export.to_mjcf(arms.osake))
    data = mujoco.MjData(model)
    data.qpos[:] = [0.4, 0.9]
    mujoco.mj_kinematics(model, data)
    tip = data.site_xpos[model.site("tip").id]
    assert np.allclose(tip, [*arms.osake.fk([0.4, 0.9]), arms.osake.d], atol=1e-15)


def test_relative_joint_limits_carry_over_to_mjcf_and_urdf():
    arm = arms.ten
    for text in (export.to_mjcf(arm), export.to_urdf(arm)):
        model = mujoco.MjModel.from_xml_string(text)
        assert model.jnt_limited.tolist() == [1, 1]
        assert np.array_equal(model.jnt_range, np.array([arm.q_min, arm.q_max]).T)
    unlimited = mujoco.MjModel.from_xml_string(export.to_urdf(arms.two_metre))
    assert unlimited.jnt_limited.tolist() == [0, 0]
    assert "continuous" in export.to_urdf(arms.two_metre)


def test_a_limit_acts_in_mujoco():
    arm = arms.ten
    model = mujoco.MjModel.from_xml_string(export.to_mjcf(arm))
    inside = mujoco_qacc(model, [0.5, 0.2], [0.0, 0.0], [0.0, 0.0])
    assert (
        relative_error(inside, arm.forward_dynamics([0.5, 0.2], [0.0, 0.0], [0.0, 0.0]))
        < 1e-9
    )
    q_beyond = [
        0.5,
        arm.q_max[1] + 0.05,
    ]  # elbow past its upper limit: the limit pushes it back
    free = arm.forward_dynamics(q_beyond, [0.0, 0.0], [0.0, 0.0])
    limited = mujoco_qacc(model, q_beyond, [0.0, 0.0], [0.0, 0.0])
    assert limited[1] < free[1] - 1.0


def test_absolute_limits_become_a_tendon_range():
    arm = arms.two_metre_limited
    model = mujoco.MjModel.from_xml_string(export.to_mjcf(arm))
    assert model.jnt_limited.tolist() == [1, 0]
    assert np.array_equal(model.jnt_range[0], arm.q_min[0:1] + arm.q_max[0:1])
    assert model.ntendon == 1 and model.tendon_limited[0] == 1
    assert np.array_equal(model.tendon_range[0], [arm.q_min[1], arm.q_max[1]])
    data = mujoco.MjData(model)
    data.qpos[:] = [np.radians(100.0), np.radians(60.0)]  # q1 + q2 = 160 deg > 145 deg
    mujoco.mj_forward(model, data)
    assert np.isclose(data.ten_length[0], np.radians(160.0))
    assert data.nefc >= 1  # the tendon limit is active


def test_horizontal_arm_has_no_gravity_in_mjcf():
    arm = TwoLinkArm(1.0, 0.7, g=0.0)
    model = mujoco.MjModel.from_xml_string(export.to_mjcf(arm))
    assert np.array_equal(model.opt.gravity, [0.0, 0.0, 0.0])
    vertical = mujoco.MjModel.from_xml_string(
        export.to_mjcf(dataclasses.replace(arm, g=9.81))
    )
    assert np.array_equal(vertical.opt.gravity, [0.0, -9.81, 0.0])


def test_only_tip_and_wall_can_touch():
    wall = Wall.through([4.0, 0.0], [0.0, 4.0])
    model = mujoco.MjModel.from_xml_string(export.to_mjcf(arms.two_metre, wall=wall))
    contype, conaffinity = model.geom_contype, model.geom_conaffinity
    pairs = [
        {model.geom(a).name, model.geom(b).name}
        for a in range(model.ngeom)
        for b in range(a + 1, model.ngeom)
        if (contype[a] & conaffinity[b]) or (contype[b] & conaffinity[a])
    ]
    assert pairs == [{"tip", "wall"}]


def test_wall_plane_sits_tip_radius_behind_the_line():
    wall = Wall.through([4.0, 0.0], [0.0, 4.0])
    model = mujoco.MjModel.from_xml_string(
        export.to_mjcf(arms.two_metre, wall=wall, tip_radius=0.01)
    )
    wall_id = model.geom("wall").id
    data = mujoco.MjData(model)
    mujoco.mj_kinematics(model, data)
    z_axis = data.geom_xmat[wall_id].reshape(3, 3)[:, 2]
    assert (
        np.allclose(z_axis[:2], -wall.into_wall()) and abs(z_axis[2]) < 1e-15
    )  # free side faces the base
    assert np.isclose(
        wall.signed_distance(data.geom_xpos[wall_id][:2]),
        0.01 * wall.normal @ wall.into_wall(),
    )


@pytest.mark.parametrize(
    "kwargs, message",
    [
        ({"integrator": "rk4"}, "integrator must be one of"),
        ({"timestep": 0.0}, "timestep"),
        ({"tip_radius": -1.0}, "tip_radius"),
        ({"wall": "x + y = 4"}, "wall must be None"),
        ({"contact_solref": (0.02,)}, "contact_solref"),
        ({"contact_solimp": (0.9, 0.95)}, "contact_solimp"),
        ({"tip_site": 1}, "tip_site"),
    ],
)
def test_to_mjcf_rejects_bad_arguments(kwargs, message):
    with pytest.raises(ValueError, match=message):
        export.to_mjcf(arms.two_metre, **kwargs)


def test_massless_links_are_refused_with_a_clear_message():
    arm = TwoLinkArm(1.0, 1.0, m1=0.0, m2=1.0)
    with pytest.raises(ValueError, match="link 1 has mass 0.0 kg"):
        export.to_mjcf(arm)
    with pytest.raises(ValueError, match="link 1 has mass 0.0 kg"):
        export.to_urdf(arm)


@pytest.mark.parametrize("to_model", [export.to_mjcf, export.to_urdf])
def test_anything_but_an_arm_is_refused_naming_arm(to_model):
    with pytest.raises(
        InputTypeError, match=r"arm must be a twolink.TwoLinkArm; got 'arm' \(str\)"
    ):
        to_model("arm")


def test_urdf_refuses_absolute_limits():
    with pytest.raises(ValueError, match="absolute angles"):
        export.to_urdf(arms.two_metre_limited)
