"""twolink beside two robotics libraries, one call at a time (``make bench-peers``).

Times, per call and on the same arm (the 1 m / 0.7 m arm with 2 kg and
1.2 kg uniform rods, gravity 9.81 m/s^2 along -y, as a two-link planar
model in each library):

* inverse kinematics of one target: ``twolink.ik.newton`` beside the
  Robotics Toolbox's ``ik_LM`` (C++ Levenberg-Marquardt, position-only mask,
  called on the robot's ``ets()`` built once);
* forward dynamics of one state: ``twolink.dynamics.forward_dynamics``
  beside pinocchio's ``aba`` (C++);
* inverse dynamics: ``twolink.dynamics.inverse_dynamics`` beside
  pinocchio's ``rnea``.

Each peer's answer is checked against twolink's before it is timed (else a
time means nothing).  The peers are not course requirements: ``make
bench-peers`` installs them into a separate virtual environment
(``build/peers-venv``); when one is not importable this script says so in
its table instead of failing.  Not part of ``make test`` (the test suite only
checks that this script runs).

Run with ``make bench-peers`` (``--quick``: tiny sizes, checks it runs).
"""

import argparse
import platform

import numpy as np

from twolink import TwoLinkArm, dynamics, ik
from twolink_course.display import markdown_table
from twolink_course.timing import median_time

ARM = TwoLinkArm(l1=1.0, l2=0.7, m1=2.0, m2=1.2)
Q, QD, TAU, QDD = (0.4, 1.1), (0.3, -0.8), (2.0, -1.0), (1.5, 0.2)
Q0 = (0.5, 1.0)


def twolink_calls(arm):
    p = tuple(arm.fk(list(Q)).tolist())
    return {
        "ik": lambda: ik.newton(arm, p, q0=Q0),
        "forward dynamics": lambda: dynamics.forward_dynamics(arm, Q, QD, TAU),
        "inverse dynamics": lambda: dynamics.inverse_dynamics(arm, Q, QD, QDD),
    }


def robotics_toolbox_ik(arm):
    """``ik_LM`` calls on the same target (default tolerance, and a tolerance it cannot meet), or the reason."""
    try:
        import roboticstoolbox as rtb
    except Exception as error:  # noqa: BLE001 - any import failure is reported, not raised
        return (
            [],
            f"roboticstoolbox-python not importable here ({type(error).__name__}: {error})",
        )
    robot = rtb.DHRobot(
        [rtb.RevoluteDH(a=arm.l1), rtb.RevoluteDH(a=arm.l2)], name="two-link"
    )
    # the C++ solver on the robot's elementary transform sequence, built once (robot.ik_LM rebuilds it
    # on every call, which costs about 20 times the solve itself)
    ets = robot.ets()
    pose = np.eye(4)
    pose[:2, 3] = arm.fk(list(Q))
    mask = np.array(
        [1.0, 1.0, 0.0, 0.0, 0.0, 0.0]
    )  # position only: a planar arm cannot choose its orientation
    q0 = np.array(Q0)
    calls = []
    for label, options in (("default tol", {}), ("tol 1e-12", {"tol": 1e-12})):

        def solve(options=options):
            return ets.ik_LM(pose, q0=q0, mask=mask, **options)

        q = np.asarray(solve()[0], dtype=float)
        error = float(np.hypot(*(arm.fk(q) - pose[:2, 3])))
        calls.append(
            (f"roboticstoolbox ik_LM ({label}), residual {error:.1e} m", solve)
        )
    return calls, f"roboticstoolbox-python {rtb.__version__}"


def pinocchio_model(arm):
    """The arm as a pinocchio model: two revolute-z joints, uniform rods, gravity along -y."""
    import pinocchio as pin

    model = pin.Model()
    inertia_1, inertia_2 = arm.inertias
    joint_1 = model.addJoint(0, pin.JointModelRZ(), pin.SE3.Identity(), "q1")
    rod_1 = pin.Inertia(
        arm.m1, np.array([arm.l1 / 2, 0.0, 0.0]), np.diag([1e-12, inertia_1, inertia_1])
    )
    model.appendBodyToJoint(joint_1, rod_1, pin.SE3.Identity())
    elbow = pin.SE3(np.eye(3), np.array([arm.l1, 0.0, 0.0]))
    joint_2 = model.addJoint(joint_1, pin.JointModelRZ(), elbow, "q2")
    rod_2 = pin.Inertia(
        arm.m2, np.array([arm.l2 / 2, 0.0, 0.0]), np.diag([1e-12, inertia_2, inertia_2])
    )
    model.appendBodyToJoint(joint_2, rod_2, pin.SE3.Identity())
    model.gravity.linear = np.array([0.0, -arm.g, 0.0])
    return pin, model, model.createData()


def pinocchio_dynamics(arm):
    """``aba`` and ``rnea`` calls, checked against twolink, or the reason they cannot run."""
    try:
        pin, model, data = pinocchio_model(arm)
    except Exception as error:  # noqa: BLE001
        return (
            None,
            None,
            f"pinocchio not importable here ({type(error).__name__}: {error})",
        )
    q, qd, tau, qdd = (np.array(v) for v in (Q, QD, TAU, QDD))
    qdd_pin = np.array(pin.aba(model, data, q, qd, tau))
    tau_pin = np.array(pin.rnea(model, data, q, qd, qdd))
    assert np.allclose(
        qdd_pin, dynamics.forward_dynamics(arm, Q, QD, TAU), rtol=1e-9, atol=1e-9
    ), qdd_pin
    assert np.allclose(
        tau_pin, dynamics.inverse_dynamics(arm, Q, QD, QDD), rtol=1e-9, atol=1e-9
    ), tau_pin
    return (
        lambda: pin.aba(model, data, q, qd, tau),
        lambda: pin.rnea(model, data, q, qd, qdd),
        f"pinocchio {pin.__version__} (aba and rnea agree with twolink to 1e-9)",
    )


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument(
        "--quick",
        action="store_true",
        help="tiny sizes: checks the script runs, not the speed",
    )
    quick = parser.parse_args(argv).quick
    repeat, min_seconds = (1, 1e-9) if quick else (7, 0.05)

    def per_call(function):
        return (
            f"{median_time(function, repeat=repeat, min_seconds=min_seconds) * 1e6:.2f}"
        )

    ours = twolink_calls(ARM)
    ik_calls, rtb_note = robotics_toolbox_ik(ARM)
    aba, rnea, pin_note = pinocchio_dynamics(ARM)
    missing = "not available (see note)"
    newton = ours["ik"]()
    ik_label = f"inverse kinematics, one target (ik.newton, residual {float(newton.residual):.1e} m)"
    time_newton = per_call(ours["ik"])
    rows = [(ik_label, time_newton, label, per_call(call)) for label, call in ik_calls]
    rows = rows or [(ik_label, time_newton, "roboticstoolbox ik_LM", missing)]
    rows += [
        (
            "forward dynamics, one state",
            per_call(ours["forward dynamics"]),
            "pinocchio aba",
            per_call(aba) if aba else missing,
        ),
        (
            "inverse dynamics, one state",
            per_call(ours["inverse dynamics"]),
            "pinocchio rnea",
            per_call(rnea) if rnea else missing,
        ),
    ]
    print(
        f"# twolink beside its peers, one call at a time ({platform.machine()}, {platform.python_implementation()} "
        f"{platform.python_version()}, numpy {np.__version__})\n"
    )
    print(f"Median of {repeat} repeats.  Peers: {rtb_note}; {pin_note}.\n")
    print(markdown_table(["call", "twolink [us]", "peer", "peer [us]"], rows))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
