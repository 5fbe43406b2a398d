#!/usr/bin/env python3
"""Writes a validation robot of primitives in another maker's layout than the project's robots: a
7-joint arm with a Kinova Gen3's kinematics (four continuous joints, axes offset by a few
millimetres, links turned by +-pi/2 about x) carrying a three-finger gripper driven by one joint
and two mimic joints, and an SRDF whose arm group lists joints (not a chain), whose gripper group
lists links, with an end effector, a virtual joint, adjacent pairs and a link the URDF lacks.
No maker's constants went into Fastron's defaults from it: it is for measuring them.

    scripts/make_continuous_validation_robot.py DIR

Writes DIR/continuous-arm.urdf and DIR/continuous-arm.srdf; load it with
`--robot DIR/continuous-arm.urdf --srdf DIR/continuous-arm.srdf --group arm`.
"""
import math
import sys
from pathlib import Path

PI = math.pi
ARM = ["base_link", "shoulder_link", "half_arm_1_link", "half_arm_2_link", "forearm_link",
       "wrist_1_link", "wrist_2_link", "bracelet_link", "gripper_base"]
FINGERS = [f"finger_{k}" for k in range(3)]
ALONG_Z, ALONG_Y = "0 0 0", "1.5708 0 0"  # a cylinder's axis: z as written, or turned onto y


def cylinder(radius, length, xyz, rpy):
    return f'<cylinder radius="{radius}" length="{length}"/>', xyz, rpy


def sphere(radius):
    return f'<sphere radius="{radius}"/>', "0 0 0", "0 0 0"


def box(x, y, z, xyz):
    return f'<box size="{x} {y} {z}"/>', xyz, "0 0 0"


def links():
    """Each link's collision shapes: a cylinder along it and, on the arm's six links between the
    shoulder and the bracelet, a sphere at its joint; a box per finger."""
    shapes = {
        "base_link": [cylinder(0.06, 0.15, "0 0 0.075", ALONG_Z)],
        "shoulder_link": [cylinder(0.055, 0.13, "0 0 -0.065", ALONG_Z), sphere(0.055)],
        "half_arm_1_link": [cylinder(0.05, 0.21, "0 -0.105 0", ALONG_Y), sphere(0.05)],
        "half_arm_2_link": [cylinder(0.05, 0.21, "0 0 -0.105", ALONG_Z), sphere(0.05)],
        "forearm_link": [cylinder(0.045, 0.21, "0 -0.105 0", ALONG_Y), sphere(0.045)],
        "wrist_1_link": [cylinder(0.04, 0.105, "0 0 -0.05", ALONG_Z), sphere(0.04)],
        "wrist_2_link": [cylinder(0.04, 0.105, "0 -0.05 0", ALONG_Y), sphere(0.04)],
        "bracelet_link": [cylinder(0.04, 0.06, "0 0 -0.03", ALONG_Z)],
        "gripper_base": [cylinder(0.045, 0.06, "0 0 0.03", ALONG_Z)],
    }
    shapes.update({finger: [box(0.015, 0.02, 0.07, "0 0 0.035")] for finger in FINGERS})
    out = []
    for name, parts in shapes.items():
        out.append(f'  <link name="{name}">')
        out += [f'    <collision><origin xyz="{xyz}" rpy="{rpy}"/><geometry>{geometry}</geometry>'
                "</collision>" for geometry, xyz, rpy in parts]
        out.append("  </link>")
    return out


def joint(name, kind, parent, child, xyz, rpy, axis="0 0 1", limits=None, mimic=None):
    out = [f'  <joint name="{name}" type="{kind}">',
           f'    <parent link="{parent}"/><child link="{child}"/>',
           f'    <origin xyz="{xyz}" rpy="{rpy}"/><axis xyz="{axis}"/>']
    if limits:
        out.append(f'    <limit lower="{limits[0]}" upper="{limits[1]}" effort="10" velocity="1"/>')
    elif kind == "continuous":
        out.append('    <limit effort="10" velocity="1"/>')
    if mimic:
        out.append(f'    <mimic joint="{mimic}" multiplier="1" offset="0"/>')
    out.append("  </joint>")
    return out


def joints():
    down, up = f"{PI / 2:.6f} 0 0", f"{-PI / 2:.6f} 0 0"
    out = []
    out += joint("joint_1", "continuous", "base_link", "shoulder_link", "0 0 0.2848", f"{PI:.6f} 0 0")
    out += joint("joint_2", "revolute", "shoulder_link", "half_arm_1_link", "0 0.0054 -0.1284", down,
                 limits=(-2.24, 2.24))
    out += joint("joint_3", "continuous", "half_arm_1_link", "half_arm_2_link", "0 -0.2104 -0.0064", up)
    out += joint("joint_4", "revolute", "half_arm_2_link", "forearm_link", "0 0.0064 -0.2104", down,
                 limits=(-2.57, 2.57))
    out += joint("joint_5", "continuous", "forearm_link", "wrist_1_link", "0 -0.2084 -0.0064", up)
    out += joint("joint_6", "revolute", "wrist_1_link", "wrist_2_link", "0 0 -0.1059", down,
                 limits=(-2.09, 2.09))
    out += joint("joint_7", "continuous", "wrist_2_link", "bracelet_link", "0 -0.1059 0", up)
    out += joint("gripper_mount", "fixed", "bracelet_link", "gripper_base", "0 0 -0.0615",
                 f"{PI:.6f} 0 0")
    for k, finger in enumerate(FINGERS):  # round the palm, a third of a turn apart
        angle = 2 * PI * k / 3
        xyz = f"{0.03 * math.cos(angle):.4f} {0.03 * math.sin(angle):.4f} 0.06"
        out += joint(f"{finger}_joint", "revolute", "gripper_base", finger, xyz, f"0 0 {angle:.6f}",
                     axis="0 1 0", limits=(0, 0.8), mimic=None if k == 0 else "finger_0_joint")
    return out


def urdf():
    return "\n".join(['<?xml version="1.0"?>',
                      "<!-- written by scripts/make_continuous_validation_robot.py -->",
                      '<robot name="continuous_arm">', *links(), *joints(), "</robot>"]) + "\n"


def srdf():
    adjacent = list(zip(ARM, ARM[1:])) + [("gripper_base", finger) for finger in FINGERS]
    never = [(a, b) for i, a in enumerate(FINGERS) for b in FINGERS[i + 1:]]
    never += [("bracelet_link", finger) for finger in FINGERS] + [("wrist_2_link", "gripper_base")]
    never.append(("base_link", "camera_link"))  # a link this URDF does not have
    lines = ['<?xml version="1.0" ?>', '<robot name="continuous_arm">', '  <group name="arm">']
    lines += [f'    <joint name="joint_{i}"/>' for i in range(1, 8)]
    lines += ["  </group>", '  <group name="gripper">', '    <link name="gripper_base"/>']
    lines += [f'    <link name="{finger}"/>' for finger in FINGERS]
    lines += ["  </group>", '  <group_state name="home" group="arm">']
    lines += [f'    <joint name="joint_{i}" value="0"/>' for i in range(1, 8)]
    lines += ["  </group_state>",
              '  <end_effector name="hand" parent_link="bracelet_link" group="gripper" '
              'parent_group="arm"/>',
              '  <virtual_joint name="world_joint" type="fixed" parent_frame="world" '
              'child_link="base_link"/>']
    lines += [f'  <disable_collisions link1="{a}" link2="{b}" reason="Adjacent"/>' for a, b in adjacent]
    lines += [f'  <disable_collisions link1="{a}" link2="{b}" reason="Never"/>' for a, b in never]
    lines.append("</robot>")
    return "\n".join(lines) + "\n"


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    out = Path(sys.argv[1])
    out.mkdir(parents=True, exist_ok=True)
    (out / "continuous-arm.urdf").write_text(urdf())
    (out / "continuous-arm.srdf").write_text(srdf())


if __name__ == "__main__":
    main()
