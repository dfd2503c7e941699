"""Joints from Python: a hinge pendulum's period against 2π√(I/(m·g·d)), a motor, the reaction of a hanging box,
breaking with its event, and misuse refused with the library's status and message (tests/c/test_joints.c has the
full physics)."""
import math

import pytest

import physpix
from pphelpers import raises_from_library, rect

DT = 1.0 / 60.0
G = 980.0


def _swing_period(world, joint, steps):
    """Mean time between upward zero crossings of the joint's angle, s."""
    prev, times = joint.value[0], []
    for k in range(1, steps + 1):
        world.step(DT)
        v = joint.value[0]
        if prev < 0 <= v:
            times.append((k - 1 + prev / (prev - v)) * DT)
        prev = v
    assert len(times) >= 3, times
    return (times[-1] - times[0]) / (len(times) - 1)


def test_hinge_pendulum_period_matches_the_physical_pendulum(world):
    d = 25.0
    rod = rect(world, 10, 60, position=(200, 200))
    joint = world.create_joint("revolute", body_b=rod, anchor_a=(200, 200 - d))
    assert joint.type == physpix.JointType.REVOLUTE and joint.bodies == (None, rod)
    assert world.joints() == [joint]
    w0 = 0.2
    rod.set_velocity((-w0 * d, 0), w0)
    period = _swing_period(world, joint, 600)
    m, inertia = rod.mass, rod.inertia
    analytic = 2 * math.pi * math.sqrt((inertia + m * d * d) / (m * G * d))
    assert period == pytest.approx(analytic, rel=0.02)


def test_motor_speed_and_hanging_reaction(space, world):
    wheel = rect(space, 20, 20, position=(100, 100))
    motor = space.create_joint("revolute", body_b=wheel, anchor_a=(100, 100), enable_motor=1, motor_speed=3,
                               max_motor_force=1e9)
    for _ in range(30):
        space.step(DT)
    assert motor.value[1] == pytest.approx(3, abs=0.01)
    motor.set_motor(False)
    motor.set_limits(True, -0.5, 0.5)

    box = rect(world, 20, 20, position=(100, 100))
    hinge = world.create_joint(physpix.JointType.REVOLUTE, body_b=box, anchor_a=(100, 92))
    for _ in range(60):
        world.step(DT)
    (fx, fy), _ = hinge.reaction
    assert -fy == pytest.approx(box.mass * G, rel=0.02) and abs(fx) < 0.01 * box.mass * G


def test_break_force_queues_the_event_and_the_handle_goes_stale(world):
    box = rect(world, 20, 20, position=(100, 100))
    joint = world.create_joint("revolute", body_b=box, anchor_a=(100, 92), break_force=0.5 * box.mass * G,
                               user_data=7)
    assert joint.user_data == 7
    world.step(DT)
    broken = [e for e in world.events() if e.type == physpix.EventType.JOINT_BROKEN]
    assert len(broken) == 1 and broken[0].joint == joint and broken[0].other == box
    assert world.joints() == []
    raises_from_library(physpix.InvalidHandleError, ["stale"], getattr, joint, "value")


def test_misuse_is_refused_with_the_library_status(world):
    box = rect(world, 20, 20, position=(100, 100))
    raises_from_library(physpix.InvalidArgumentError, ["same"], world.create_joint, "weld", box, box)
    raises_from_library(physpix.InvalidArgumentError, ["both zero"], world.create_joint, "revolute")
    raises_from_library(physpix.InvalidArgumentError, ["anchor_a"], world.create_joint, "revolute", body_b=box,
                        anchor_a=(math.nan, 0))
    raises_from_library(physpix.InvalidArgumentError, ["lower"], world.create_joint, "revolute", body_b=box,
                        lower=1, upper=0)
    raises_from_library(physpix.InvalidArgumentError, ["max_force"], world.create_joint, "mouse", body_b=box,
                        max_force=-1)
    with pytest.raises(ValueError):
        world.create_joint("hinge", body_b=box)
    with pytest.raises(TypeError):
        world.create_joint("revolute", body_b=box, anchour_a=(0, 0))
    with pytest.raises(TypeError):
        world.create_joint("revolute", body_b=box, type=2)
    joint = world.create_joint("revolute", body_b=box, anchor_a=(100, 100))
    raises_from_library(physpix.InvalidArgumentError, ["mouse"], joint.set_target, (0, 0))
    raises_from_library(physpix.InvalidArgumentError, ["max_force"], joint.set_motor, True, 1, -1)
    raises_from_library(physpix.InvalidArgumentError, ["within"], joint.set_limits, True, -4, 0)
    with physpix.World(backend="cpu") as other:
        stranger = rect(other, 10, 10)
        raises_from_library(physpix.InvalidHandleError, ["belongs to world"], world.create_joint, "weld", box,
                            stranger)
    joint.destroy()
    raises_from_library(physpix.InvalidHandleError, ["stale"], joint.destroy)


def test_wheel_sag_rope_slack_and_motor_joint_offsets(world):
    """Issue 41's joints from Python: a wheel sags m·g/k = g/ω², a rope thrown inward flies free, a motor joint
    takes its body to the offsets it is given (set_offsets), a revolute spring rests at its target (set_spring)."""
    hz = 2.0
    hub = rect(world, 24, 24, position=(200, 200))
    wheel = world.create_joint("wheel", body_b=hub, anchor_a=(200, 200), anchor_b=(200, 200), axis=(0, 1),
                               spring_hertz=hz, spring_damping_ratio=0.7)
    assert wheel.type == physpix.JointType.WHEEL
    bob = rect(world, 16, 16, position=(400, 200))
    rope = world.create_joint("distance", body_b=bob, anchor_a=(400, 100), anchor_b=(400, 200), max_length=100)
    crate = rect(world, 20, 20, position=(600, 200))
    motor = world.create_joint("motor", body_b=crate, linear_offset=(640, 150), angular_offset=0.25)
    assert motor.type == physpix.JointType.MOTOR
    for _ in range(240):
        world.step(DT)
    assert wheel.value[0] == pytest.approx(G / (2 * math.pi * hz) ** 2, rel=0.03)
    assert crate.position == pytest.approx((640, 150), abs=0.5) and crate.angle == pytest.approx(0.25, abs=0.01)
    bob.set_velocity((0, -120), 0)
    nearest = 1e9
    for _ in range(30):
        world.step(DT)
        nearest = min(nearest, rope.value[0])
    assert nearest == pytest.approx(100 - 120 ** 2 / (2 * G), abs=0.5)
    motor.set_offsets((560, 180), 0)
    for _ in range(240):
        world.step(DT)
    assert crate.position == pytest.approx((560, 180), abs=0.5)
    raises_from_library(physpix.InvalidArgumentError, ["motor"], wheel.set_offsets, (0, 0), 0)
    raises_from_library(physpix.InvalidArgumentError, ["hertz"], wheel.set_spring, -1, 0)
    door = rect(world, 60, 8, position=(330, 400))
    door.gravity_scale = 0
    hinge = world.create_joint("revolute", body_b=door, anchor_a=(302, 400))
    hinge.set_spring(1.5, 1.0, 0.4)
    for _ in range(300):
        world.step(DT)
    assert hinge.value[0] == pytest.approx(0.4, abs=0.01)
