#!/usr/bin/env python3
"""Writes the validation robots of data/robots/ that no maker's constants went into: robots of the
kinds users bring (a 6-joint arm with a parallel-jaw gripper of many small links, mimic joints and
a MoveIt SRDF; a mobile manipulator whose 7-joint arm rides on a prismatic torso, with continuous
roll joints, wheels and a head), so that defaults are tuned on more than Panda and Baxter.

    scripts/make_validation_robots.py data/robots

Writes gripper-arm.urdf, gripper-arm.srdf, mobile-arm.urdf and mobile-arm.srdf. The SRDFs
disable the pairs a MoveIt Setup Assistant would (links that touch by construction, within the
gripper), name the planning groups, and like real configurations name a few links the URDF does
not have (a camera, a laser), which readers must skip with a warning.
"""
import itertools
import math
import sys
from pathlib import Path

HALF_PI = math.pi / 2


def origin(xyz=(0, 0, 0), rpy=(0, 0, 0)):
    return f'<origin xyz="{xyz[0]:g} {xyz[1]:g} {xyz[2]:g}" rpy="{rpy[0]:g} {rpy[1]:g} {rpy[2]:g}"/>'


def box(size, at=(0, 0, 0), rpy=(0, 0, 0)):
    return (f'<collision>{origin(at, rpy)}<geometry><box size="{size[0]:g} {size[1]:g} '
            f'{size[2]:g}"/></geometry></collision>')


def cylinder(radius, length, at=(0, 0, 0), rpy=(0, 0, 0)):
    return (f'<collision>{origin(at, rpy)}<geometry><cylinder radius="{radius:g}" '
            f'length="{length:g}"/></geometry></collision>')


def sphere(radius, at=(0, 0, 0)):
    return f'<collision>{origin(at)}<geometry><sphere radius="{radius:g}"/></geometry></collision>'


def capsule(radius, start, end):
    """A cylinder between two points plus a sphere on each end (the loader merges them)."""
    d = [e - s for s, e in zip(start, end)]
    length = math.sqrt(sum(c * c for c in d))
    mid = [(s + e) / 2 for s, e in zip(start, end)]
    # Turn z onto d: pitch about y, then yaw about z.
    yaw = math.atan2(d[1], d[0])
    pitch = math.atan2(math.hypot(d[0], d[1]), d[2])
    return (cylinder(radius, length, mid, (0, pitch, yaw)) + sphere(radius, start) +
            sphere(radius, end))


class Urdf:
    def __init__(self, name, comment):
        self.parts = [f'<?xml version="1.0"?>\n<!-- {comment} -->\n<robot name="{name}">']
        self.links = []

    def link(self, name, *collisions):
        self.links.append(name)
        body = "".join(f"\n    {c}" for c in collisions)
        self.parts.append(f'  <link name="{name}">{body}\n  </link>' if body else
                          f'  <link name="{name}"/>')

    def joint(self, name, kind, parent, child, at=(0, 0, 0), rpy=(0, 0, 0), axis=(0, 0, 1),
              limits=None, mimic=None):
        lines = [f'  <joint name="{name}" type="{kind}">', f'    <parent link="{parent}"/>',
                 f'    <child link="{child}"/>', f"    {origin(at, rpy)}"]
        if kind != "fixed":
            lines.append(f'    <axis xyz="{axis[0]:g} {axis[1]:g} {axis[2]:g}"/>')
        if limits is not None:
            lines.append(f'    <limit lower="{limits[0]:g}" upper="{limits[1]:g}" effort="50" '
                         'velocity="2"/>')
        if mimic is not None:
            lines.append(f'    <mimic joint="{mimic[0]}" multiplier="{mimic[1]:g}" '
                         f'offset="{mimic[2]:g}"/>')
        lines.append("  </joint>")
        self.parts.append("\n".join(lines))

    def text(self):
        return "\n".join(self.parts + ["</robot>", ""])


def srdf(name, groups, disabled, extra=""):
    lines = [f'<?xml version="1.0"?>\n<robot name="{name}">']
    for group, body in groups:
        lines.append(f'  <group name="{group}">{body}</group>')
    lines.append(extra)
    for a, b, reason in disabled:
        lines.append(f'  <disable_collisions link1="{a}" link2="{b}" reason="{reason}"/>')
    lines.append("</robot>\n")
    return "\n".join(line for line in lines if line)


def gripper_arm():
    """Six revolute joints (yaw, two pitches, a spherical wrist) and a four-bar parallel-jaw
    gripper: one driven knuckle joint, five joints that mimic it, ten small links."""
    u = Urdf("gripper_arm", "A 6-joint arm with a linkage gripper of many small links "
             "(scripts/make_validation_robots.py). Flange at (0, 0.105, 1.095) at q = 0.")
    u.link("base_link", cylinder(0.075, 0.1, (0, 0, 0.05)))
    u.joint("base_yaw", "revolute", "base_link", "turret", (0, 0, 0.1), limits=(-3.14159, 3.14159))
    u.link("turret", cylinder(0.065, 0.12, (0, 0, 0.05)), capsule(0.06, (0, -0.06, 0.11), (0, 0.08, 0.11)))
    u.joint("shoulder_pitch", "revolute", "turret", "upper_arm", (0, 0.13, 0.11), axis=(0, 1, 0),
            limits=(-2.2, 2.2))
    u.link("upper_arm", capsule(0.055, (0, 0, 0), (0, 0, 0.40)))
    u.joint("elbow_pitch", "revolute", "upper_arm", "forearm", (0, -0.115, 0.40), axis=(0, 1, 0),
            limits=(-2.7, 2.7))
    u.link("forearm", capsule(0.045, (0, 0, 0), (0, 0, 0.36)))
    u.joint("wrist_pitch", "revolute", "forearm", "wrist_1", (0, 0.09, 0.36), axis=(0, 1, 0),
            limits=(-3.14159, 3.14159))
    u.link("wrist_1", capsule(0.04, (0, -0.03, 0), (0, 0.03, 0)))
    u.joint("wrist_yaw", "revolute", "wrist_1", "wrist_2", (0, 0, 0.055), limits=(-3.14159, 3.14159))
    u.link("wrist_2", capsule(0.038, (0, 0, 0), (0, 0, 0.04)))
    u.joint("wrist_roll", "revolute", "wrist_2", "flange", (0, 0, 0.07), axis=(0, 1, 0),
            limits=(-3.14159, 3.14159))
    u.link("flange", cylinder(0.035, 0.03, (0, 0, 0.0)))
    u.joint("gripper_mount", "fixed", "flange", "gripper_base", (0, 0, 0.015))
    u.link("gripper_base", box((0.06, 0.13, 0.07), (0, 0, 0.035)))
    u.joint("grasp_frame", "fixed", "gripper_base", "grasp_target", (0, 0, 0.16))
    u.link("grasp_target")
    for side, sign in (("left", 1), ("right", -1)):
        axis = (sign, 0, 0)
        knuckle = "finger_joint" if side == "left" else "right_outer_knuckle_joint"
        mimic = None if side == "left" else ("finger_joint", 1, 0)
        u.joint(knuckle, "revolute", "gripper_base", f"{side}_outer_knuckle",
                (0, sign * 0.03, 0.075), axis=axis, limits=(0, 0.8), mimic=mimic)
        u.link(f"{side}_outer_knuckle", box((0.02, 0.014, 0.045), (0, sign * 0.006, 0.02)))
        u.joint(f"{side}_outer_finger_joint", "fixed", f"{side}_outer_knuckle", f"{side}_outer_finger",
                (0, sign * 0.012, 0.045))
        u.link(f"{side}_outer_finger", box((0.02, 0.01, 0.05), (0, 0, 0.025)))
        u.joint(f"{side}_inner_knuckle_joint", "revolute", "gripper_base", f"{side}_inner_knuckle",
                (0, sign * 0.012, 0.09), axis=axis, limits=(0, 0.8), mimic=("finger_joint", 1, 0))
        u.link(f"{side}_inner_knuckle", box((0.018, 0.01, 0.05), (0, 0, 0.025)))
        u.joint(f"{side}_inner_finger_joint", "revolute", f"{side}_outer_finger", f"{side}_inner_finger",
                (0, 0, 0.05), axis=axis, limits=(-0.8, 0), mimic=("finger_joint", -1, 0))
        u.link(f"{side}_inner_finger", box((0.02, 0.012, 0.045), (0, -sign * 0.006, 0.022)))
        u.joint(f"{side}_pad_joint", "fixed", f"{side}_inner_finger", f"{side}_finger_pad",
                (0, -sign * 0.012, 0.03))
        u.link(f"{side}_finger_pad", box((0.022, 0.004, 0.025)))
    gripper_links = [l for l in u.links if l.startswith(("left_", "right_"))] + ["gripper_base"]
    disabled = [(a, b, "Never") for a, b in itertools.combinations(gripper_links, 2)]
    disabled += [(l, "flange", "Never") for l in gripper_links] + [(l, "wrist_2", "Never") for l in gripper_links]
    disabled += [("base_link", "turret", "Adjacent"), ("wrist_1", "flange", "Never"),
                 ("camera_link", "gripper_base", "Adjacent"), ("camera_link", "flange", "Never")]
    groups = [("manipulator", '<chain base_link="base_link" tip_link="flange"/>'),
              ("gripper", '<joint name="finger_joint"/><joint name="right_outer_knuckle_joint"/>'),
              ("arm_and_gripper", '<group name="manipulator"/><group name="gripper"/>')]
    extra = ('  <end_effector name="hand" parent_link="flange" group="gripper" '
             'parent_group="manipulator"/>\n'
             '  <virtual_joint name="world_joint" type="fixed" parent_frame="world" '
             'child_link="base_link"/>')
    return u.text(), srdf("gripper_arm", groups, disabled, extra)


def mobile_arm():
    """A wheeled base, a prismatic torso carrying a 7-joint arm with three continuous roll
    joints, a pan-tilt head, and a two-finger gripper whose second finger mimics the first."""
    u = Urdf("mobile_arm", "A mobile manipulator: prismatic torso and 7-joint arm "
             "(scripts/make_validation_robots.py); the base rests on the ground.")
    u.link("base_link", box((0.56, 0.52, 0.28), (-0.02, 0, 0.2)), cylinder(0.26, 0.08, (0, 0, 0.1)))
    for side, y in (("l", 0.19), ("r", -0.19)):
        u.joint(f"{side}_wheel_joint", "continuous", "base_link", f"{side}_wheel_link", (0, y, 0.06),
                axis=(0, 1, 0))
        u.link(f"{side}_wheel_link", cylinder(0.06, 0.04, rpy=(HALF_PI, 0, 0)))
    u.joint("torso_lift_joint", "prismatic", "base_link", "torso_lift_link", (-0.09, 0, 0.38),
            limits=(0, 0.38))
    u.link("torso_lift_link", box((0.2, 0.3, 0.72), (-0.02, 0, 0.08)))
    u.joint("head_pan_joint", "revolute", "torso_lift_link", "head_pan_link", (0.05, 0, 0.5),
            limits=(-1.57, 1.57))
    u.link("head_pan_link", box((0.16, 0.26, 0.08), (0.02, 0, 0.04)))
    u.joint("head_tilt_joint", "revolute", "head_pan_link", "head_tilt_link", (0.1, 0, 0.12),
            axis=(0, 1, 0), limits=(-0.76, 1.45))
    u.link("head_tilt_link", box((0.08, 0.24, 0.07)))
    u.joint("shoulder_pan_joint", "revolute", "torso_lift_link", "shoulder_pan_link", (0.14, 0, 0.31),
            limits=(-1.6, 1.6))
    u.link("shoulder_pan_link", cylinder(0.065, 0.14, (0, 0, 0)))
    u.joint("shoulder_lift_joint", "revolute", "shoulder_pan_link", "shoulder_lift_link",
            (0.11, 0, 0), axis=(0, 1, 0), limits=(-1.22, 1.52))
    u.link("shoulder_lift_link", sphere(0.065))
    u.joint("upperarm_roll_joint", "continuous", "shoulder_lift_link", "upperarm_roll_link",
            (0.12, 0, 0), axis=(1, 0, 0))
    u.link("upperarm_roll_link", capsule(0.055, (0, 0, 0), (0.17, 0, 0)))
    u.joint("elbow_flex_joint", "revolute", "upperarm_roll_link", "elbow_flex_link", (0.23, 0, 0),
            axis=(0, 1, 0), limits=(-2.25, 2.25))
    u.link("elbow_flex_link", sphere(0.055))
    u.joint("forearm_roll_joint", "continuous", "elbow_flex_link", "forearm_roll_link", (0.1, 0, 0),
            axis=(1, 0, 0))
    u.link("forearm_roll_link", capsule(0.05, (0, 0, 0), (0.14, 0, 0)))
    u.joint("wrist_flex_joint", "revolute", "forearm_roll_link", "wrist_flex_link", (0.2, 0, 0),
            axis=(0, 1, 0), limits=(-2.16, 2.16))
    u.link("wrist_flex_link", sphere(0.045))
    u.joint("wrist_roll_joint", "continuous", "wrist_flex_link", "wrist_roll_link", (0.07, 0, 0),
            axis=(1, 0, 0))
    u.link("wrist_roll_link", cylinder(0.04, 0.05, (0.01, 0, 0), (0, HALF_PI, 0)))
    u.joint("gripper_axis", "fixed", "wrist_roll_link", "gripper_link", (0.09, 0, 0))
    u.link("gripper_link", box((0.06, 0.13, 0.06)))
    u.joint("l_gripper_finger_joint", "prismatic", "gripper_link", "l_gripper_finger_link",
            (0.055, 0.012, 0), axis=(0, 1, 0), limits=(0, 0.05))
    u.link("l_gripper_finger_link", box((0.06, 0.012, 0.03), (0.0, 0.006, 0)))
    u.joint("r_gripper_finger_joint", "prismatic", "gripper_link", "r_gripper_finger_link",
            (0.055, -0.012, 0), axis=(0, -1, 0), limits=(0, 0.05), mimic=("l_gripper_finger_joint", 1, 0))
    u.link("r_gripper_finger_link", box((0.06, 0.012, 0.03), (0.0, -0.006, 0)))
    disabled = [("base_link", "torso_lift_link", "Adjacent"), ("torso_lift_link", "shoulder_pan_link", "Adjacent"),
                ("l_gripper_finger_link", "r_gripper_finger_link", "Never"),
                ("l_gripper_finger_link", "wrist_roll_link", "Never"),
                ("r_gripper_finger_link", "wrist_roll_link", "Never"),
                ("base_link", "l_wheel_link", "Adjacent"), ("base_link", "r_wheel_link", "Adjacent"),
                ("head_tilt_link", "torso_lift_link", "Never"),
                ("base_laser_link", "base_link", "Adjacent"), ("base_laser_link", "torso_lift_link", "Never"),
                ("estop_link", "base_link", "Adjacent")]
    groups = [("arm", '<chain base_link="torso_lift_link" tip_link="gripper_link"/>'),
              ("arm_with_torso", '<chain base_link="base_link" tip_link="gripper_link"/>'),
              ("gripper", '<joint name="l_gripper_finger_joint"/><joint name="r_gripper_finger_joint"/>'),
              ("head", '<joint name="head_pan_joint"/><joint name="head_tilt_joint"/>')]
    extra = ('  <virtual_joint name="world_joint" type="planar" parent_frame="odom" child_link="base_link"/>\n'
             '  <passive_joint name="l_wheel_joint"/>\n  <passive_joint name="r_wheel_joint"/>')
    return u.text(), srdf("mobile_arm", groups, disabled, extra)


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    out = Path(sys.argv[1])
    for name, (urdf, semantic) in (("gripper-arm", gripper_arm()), ("mobile-arm", mobile_arm())):
        (out / f"{name}.urdf").write_text(urdf)
        (out / f"{name}.srdf").write_text(semantic)


if __name__ == "__main__":
    main()
