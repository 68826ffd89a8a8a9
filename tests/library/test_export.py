"""twolink.export: the MJCF and URDF models give MuJoCo twolink's dynamics, limits and gravity."""

import dataclasses
from xml.etree import ElementTree

import numpy as np
import pytest
from hypothesis import assume, given, settings
from hypothesis import strategies as st

from conftest import acceleration_scale, dynamic_arms
from twolink import TwoLinkArm, arms, export
from twolink.errors import InputTypeError
from twolink.statics import Wall

mujoco = pytest.importorskip("mujoco")

pytestmark = pytest.mark.usefixtures("mujoco_log_in_tmp")

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
    with pytest.raises(ValueError, match="link 1 has mass 0 kg .*give m1 > 0"):
        export.to_mjcf(arm)
    with pytest.raises(ValueError, match="link 1 has mass 0 kg .*give m1 > 0"):
        export.to_urdf(arm)


#: Every arm the constructor accepts: lengths and masses over their whole ranges, log-uniform.
log_lengths = st.integers(-50, 50).map(lambda e: 10.0**e) | st.floats(1e-3, 1e3)
log_masses = st.integers(-50, 50).map(lambda e: 10.0**e) | st.floats(1e-3, 1e3)


@st.composite
def any_arms(draw):
    inertias = draw(st.sampled_from([None, "given"]))
    l1, l2, m1, m2 = (
        draw(log_lengths),
        draw(log_lengths),
        draw(log_masses),
        draw(log_masses),
    )
    extra = {}
    if inertias == "given":
        extra = {
            "I1": draw(log_masses) * l1 * l1 / 12.0,
            "I2": draw(log_masses) * l2 * l2 / 12.0,
        }
        assume(all(value <= 1e150 for value in extra.values()))
    return TwoLinkArm(l1, l2, m1=m1, m2=m2, **extra)


def _inertia_of(link):
    element = link.find("inertial/inertia")
    values = {key: float(value) for key, value in element.attrib.items()}
    return np.array(
        [
            [values["ixx"], values["ixy"], values["ixz"]],
            [values["ixy"], values["iyy"], values["iyz"]],
            [values["ixz"], values["iyz"], values["izz"]],
        ]
    )


@settings(max_examples=150, deadline=None)
@given(arm=any_arms())
def test_every_arm_gives_a_urdf_that_parses_with_physical_inertias(arm):
    """The axial inertia was made up (1e-6 of the transverse one); now derived from the link's cylinder."""
    root = ElementTree.fromstring(export.to_urdf(arm))
    for name, length, mass, inertia in (
        ("link1", arm.l1, arm.m1, arm.inertias[0]),
        ("link2", arm.l2, arm.m2, arm.inertias[1]),
    ):
        link = root.find(f"link[@name='{name}']")
        assert float(link.find("inertial/mass").attrib["value"]) == mass
        tensor = _inertia_of(link)
        principal = np.diag(tensor)
        assert np.all(principal > 0.0)  # positive definite (diagonal)
        a, b, c = principal
        assert a <= b + c and b <= a + c and c <= a + b  # the triangle inequality
        assert principal[1] == principal[2] == inertia
        cylinder = link.find("visual/geometry/cylinder")
        radius = float(cylinder.attrib["radius"])
        assert radius == pytest.approx(length / 100.0, rel=1e-15)
        assert principal[0] == pytest.approx(
            min(mass * radius**2 / 2.0, inertia), rel=1e-12
        )


@settings(max_examples=150, deadline=None)
@given(arm=any_arms())
def test_every_arm_gives_an_mjcf_that_mujoco_loads_or_a_clear_refusal(arm):
    """1 mm, 1 g links failed in MuJoCo with its own words (the axial inertia, 8e-17, below its minimum)."""
    mujoco = pytest.importorskip("mujoco")
    try:
        text = export.to_mjcf(arm)
    except ValueError as error:
        assert "above 1e-15 (MuJoCo's mjMINVAL)" in str(error)
        assert "choose units in which its numbers are larger" in str(error)
        radius = np.array([arm.l1, arm.l2]) / 100.0
        axial = np.minimum(np.array([arm.m1, arm.m2]) * radius**2 / 2.0, arm.inertias)
        assert min(arm.m1, arm.m2, *axial, *arm.inertias) <= 1e-15
        return
    model = mujoco.MjModel.from_xml_string(text)
    assert np.allclose(model.body_mass[1:], [arm.m1, arm.m2], rtol=1e-12, atol=0.0)
    radius = np.array([arm.l1, arm.l2]) / 100.0
    axial = np.minimum(np.array([arm.m1, arm.m2]) * radius**2 / 2.0, arm.inertias)
    if (
        min(*axial, *arm.inertias) > 2e-14
    ):  # MuJoCo reads a URDF's inertia as fullinertia: 1e-14 at least
        urdf = mujoco.MjModel.from_xml_string(export.to_urdf(arm))
        assert urdf.nbody == 3


def test_the_arms_of_the_finding_load():
    mujoco = pytest.importorskip("mujoco")
    for length in (0.01, 0.001):
        arm = TwoLinkArm(length, length, m1=0.001, m2=0.001)
        for text in (export.to_mjcf(arm), export.to_urdf(arm)):
            assert mujoco.MjModel.from_xml_string(text).nbody == 3


@pytest.mark.parametrize("name", ["arm\x01", "arm\n", "", "a<b", 'a"b', "a&b", 3, None])
def test_a_name_that_xml_cannot_hold_is_refused_naming_it(name):
    with pytest.raises(
        ValueError, match="model_name must be a non-empty string of printable"
    ):
        export.to_mjcf(arms.two_metre, model_name=name)
    with pytest.raises(
        ValueError, match="robot_name must be a non-empty string of printable"
    ):
        export.to_urdf(arms.two_metre, robot_name=name)


@pytest.mark.parametrize("bad", ["12", "0.02 1", [[0.02, 1.0]], [0.02, "1"]])
def test_solver_parameters_are_numbers_not_the_digits_of_a_string(bad):
    """to_mjcf(contact_solref="12") wrote solref="1.0 2.0"."""
    with pytest.raises(ValueError, match="contact_solref"):
        export.to_mjcf(
            arms.two_metre, wall=[[4.0, 0.0], [0.0, 4.0]], contact_solref=bad
        )


@pytest.mark.parametrize("to_model", [export.to_mjcf, export.to_urdf])
def test_anything_but_an_arm_is_refused_naming_arm(to_model):
    with pytest.raises(
        InputTypeError, match=r"arm must be a twolink.TwoLinkArm; got 'arm' \(str\)"
    ):
        to_model("arm")


def test_urdf_refuses_absolute_limits():
    with pytest.raises(ValueError, match="absolute angles"):
        export.to_urdf(arms.two_metre_limited)
