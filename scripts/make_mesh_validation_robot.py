#!/usr/bin/env python3
"""Writes a validation robot of meshes in the layout a user's MoveIt configuration has: a 6-joint
arm of a UR5's kinematics (joints of +-2 pi) carrying a parallel-jaw gripper of six small links
driven by one joint and five mimic joints, every collision shape a binary STL mesh referred to by
a package:// URI, and an SRDF as the MoveIt Setup Assistant writes it (a chain group, an end
effector group, a virtual joint, adjacent and never-colliding pairs, and a link the URDF lacks).
No maker's constants went into Fastron's defaults from it: it is for measuring them.

    scripts/make_mesh_validation_robot.py DIR

Writes DIR/mesh-arm.urdf, DIR/mesh-arm.srdf and DIR/mesh_arm_description/meshes/*.stl; load it with
`--robot DIR/mesh-arm.urdf --srdf DIR/mesh-arm.srdf --package-path DIR --group manipulator`.
"""
import math
import struct
import sys
from pathlib import Path

PI = math.pi


def ring(radius, z, segments):
    return [(radius * math.cos(2 * PI * k / segments), radius * math.sin(2 * PI * k / segments), z)
            for k in range(segments)]


def capsule_mesh(radius, length, segments=24, rings=6):
    """Triangles of a capsule along z from 0 to `length` (hemispheres beyond both ends)."""
    layers = []
    for i in range(rings, 0, -1):  # the lower cap, pole first
        a = PI / 2 * i / rings
        layers.append(ring(radius * math.cos(a), -radius * math.sin(a), segments))
    layers.append(ring(radius, length, segments))
    for i in range(1, rings + 1):
        a = PI / 2 * i / rings
        layers.append(ring(radius * math.cos(a), length + radius * math.sin(a), segments))
    triangles = []
    for lower, upper in zip(layers, layers[1:]):
        for k in range(segments):
            k1 = (k + 1) % segments
            triangles.append((lower[k], lower[k1], upper[k1]))
            triangles.append((lower[k], upper[k1], upper[k]))
    return triangles


def box_mesh(sx, sy, sz, centre=(0, 0, 0)):
    cx, cy, cz = centre
    v = [(cx + x * sx / 2, cy + y * sy / 2, cz + z * sz / 2)
         for x in (-1, 1) for y in (-1, 1) for z in (-1, 1)]
    faces = [(0, 1, 3, 2), (4, 6, 7, 5), (0, 4, 5, 1), (2, 3, 7, 6), (0, 2, 6, 4), (1, 5, 7, 3)]
    triangles = []
    for a, b, c, d in faces:
        triangles.append((v[a], v[b], v[c]))
        triangles.append((v[a], v[c], v[d]))
    return triangles


def turned(triangles, axis, offset=(0, 0, 0)):
    """The triangles with z turned onto `axis` ('x', 'y' or 'z'), then moved by `offset`."""
    def turn(p):
        x, y, z = p
        q = {"z": (x, y, z), "x": (z, y, -x), "y": (x, z, -y)}[axis]
        return tuple(c + o for c, o in zip(q, offset))
    return [tuple(turn(p) for p in t) for t in triangles]


def write_stl(path, triangles):
    with open(path, "wb") as f:
        f.write(b"mesh-arm validation mesh".ljust(80, b" "))
        f.write(struct.pack("<I", len(triangles)))
        for t in triangles:
            f.write(struct.pack("<3f", 0, 0, 0))
            for p in t:
                f.write(struct.pack("<3f", *p))
            f.write(b"\0\0")


# name: (triangles, parent, joint type, origin xyz, origin rpy, axis, lower, upper, mimic)
def robot_parts():
    return [
        ("base_link", turned(capsule_mesh(0.075, 0.03), "z", (0, 0, 0.01)), None),
        ("shoulder_link", turned(capsule_mesh(0.06, 0.10), "z", (0, 0, -0.05)),
         ("base_link", "revolute", (0, 0, 0.089159), (0, 0, 0), (0, 0, 1), -2 * PI, 2 * PI)),
        ("upper_arm_link", turned(capsule_mesh(0.055, 0.425), "z", (0, 0, 0)) +
         turned(capsule_mesh(0.06, 0.12), "y", (0, -0.06, 0)),
         ("shoulder_link", "revolute", (0, 0.13585, 0), (0, PI / 2, 0), (0, 1, 0), -2 * PI,
          2 * PI)),
        ("forearm_link", turned(capsule_mesh(0.042, 0.39225), "z", (0, 0, 0)) +
         turned(capsule_mesh(0.05, 0.10), "y", (0, -0.02, 0)),
         ("upper_arm_link", "revolute", (0, -0.1197, 0.425), (0, 0, 0), (0, 1, 0), -PI, PI)),
        ("wrist_1_link", turned(capsule_mesh(0.042, 0.09), "y", (0, 0.0, 0)),
         ("forearm_link", "revolute", (0, 0, 0.39225), (0, PI / 2, 0), (0, 1, 0), -2 * PI,
          2 * PI)),
        ("wrist_2_link", turned(capsule_mesh(0.042, 0.08), "z", (0, 0, 0.0)),
         ("wrist_1_link", "revolute", (0, 0.093, 0), (0, 0, 0), (0, 0, 1), -2 * PI, 2 * PI)),
        ("wrist_3_link", turned(capsule_mesh(0.04, 0.05), "y", (0, 0.02, 0)),
         ("wrist_2_link", "revolute", (0, 0, 0.09465), (0, 0, 0), (0, 1, 0), -2 * PI, 2 * PI)),
        ("tool0", None, ("wrist_3_link", "fixed", (0, 0.0823, 0), (-PI / 2, 0, 0))),
        ("gripper_base", box_mesh(0.08, 0.12, 0.07, (0, 0, 0.035)),
         ("tool0", "fixed", (0, 0, 0), (0, 0, 0))),
    ] + gripper_parts()


def gripper_parts():
    parts = []
    for side, sign in (("left", 1), ("right", -1)):
        y = 0.03 * sign
        parts += [
            (f"{side}_outer_knuckle", box_mesh(0.02, 0.012, 0.035, (0, 0, 0.017)),
             ("gripper_base", "revolute", (0, y, 0.07), (0, 0, 0), (sign, 0, 0), 0, 0.8,
              None if side == "left" else ("left_outer_knuckle_joint", 1))),
            (f"{side}_inner_knuckle", box_mesh(0.018, 0.01, 0.04, (0, 0, 0.02)),
             ("gripper_base", "revolute", (0, 0.012 * sign, 0.075), (0, 0, 0), (sign, 0, 0), 0,
              0.8, ("left_outer_knuckle_joint", 1))),
            (f"{side}_inner_finger", box_mesh(0.022, 0.014, 0.045, (0, -0.004 * sign, 0.022)),
             (f"{side}_outer_knuckle", "revolute", (0, 0, 0.035), (0, 0, 0), (sign, 0, 0), -0.8,
              0, ("left_outer_knuckle_joint", -1))),
        ]
    return parts


def urdf(parts):
    out = ['<?xml version="1.0"?>',
           "<!-- written by scripts/make_mesh_validation_robot.py: a validation robot of meshes -->",
           '<robot name="mesh_arm">']
    for name, triangles, joint in parts:
        if triangles is None:
            out.append(f'  <link name="{name}"/>')
        else:
            uri = f"package://mesh_arm_description/meshes/{name}.stl"
            out.append(f'  <link name="{name}">\n    <visual><geometry><mesh filename="{uri}"/>'
                       f'</geometry></visual>\n    <collision><geometry><mesh filename="{uri}"/>'
                       f"</geometry></collision>\n  </link>")
        if joint is None:
            continue
        parent, kind, xyz, rpy = joint[:4]
        jname = f"{name}_joint" if name.endswith("knuckle") or name.endswith("finger") else {
            "shoulder_link": "shoulder_pan_joint", "upper_arm_link": "shoulder_lift_joint",
            "forearm_link": "elbow_joint", "wrist_1_link": "wrist_1_joint",
            "wrist_2_link": "wrist_2_joint", "wrist_3_link": "wrist_3_joint"}.get(
                name, f"{parent}-{name}_fixed_joint")
        body = (f'    <parent link="{parent}"/>\n    <child link="{name}"/>\n'
                f'    <origin xyz="{xyz[0]:g} {xyz[1]:g} {xyz[2]:g}" '
                f'rpy="{rpy[0]:.12g} {rpy[1]:.12g} {rpy[2]:.12g}"/>')
        if kind == "revolute":
            axis, lower, upper = joint[4:7]
            mimic = joint[7] if len(joint) > 7 else None
            body += (f'\n    <axis xyz="{axis[0]:g} {axis[1]:g} {axis[2]:g}"/>\n'
                     f'    <limit lower="{lower:.12g}" upper="{upper:.12g}" effort="150" '
                     f'velocity="3.15"/>')
            if mimic:
                body += f'\n    <mimic joint="{mimic[0]}" multiplier="{mimic[1]:g}" offset="0"/>'
        out.append(f'  <joint name="{jname}" type="{kind}">\n{body}\n  </joint>')
    out.append("</robot>")
    return "\n".join(out) + "\n"


def srdf(parts):
    gripper = [name for name, triangles, _ in parts if triangles is not None and
               (name.startswith("gripper") or "knuckle" in name or "finger" in name)]
    pairs = []
    for name, triangles, joint in parts:
        if joint is not None and triangles is not None:
            parent = joint[0]
            if parent == "tool0":  # a frame without a shape: the link that carries it
                parent = "wrist_3_link"
            pairs.append((parent, name, "Adjacent"))
    # As the Setup Assistant finds them: links that can never touch, and the gripper's own links.
    pairs += [("base_link", "upper_arm_link", "Default"), ("base_link", "wrist_1_link", "Never"), ("shoulder_link", "wrist_1_link", "Never"),
              ("wrist_1_link", "wrist_3_link", "Never"), ("wrist_2_link", "gripper_base", "Never")]
    # What `fastron robots --self-collisions URDF --srdf SRDF --samples 100000` found never
    # touching (the Setup Assistant's sampling would disable them too).
    pairs += [("forearm_link", "wrist_2_link", "Never"), ("shoulder_link", "wrist_2_link", "Never")]
    pairs += [(f"{side}_{part}", wrist, "Never") for side in ("left", "right")
              for part in ("inner_finger", "inner_knuckle", "outer_knuckle")
              for wrist in ("wrist_1_link", "wrist_2_link")]
    pairs += [(f"{side}_inner_finger", "wrist_3_link", "Never") for side in ("left", "right")]
    pairs += [(a, b, "Never") for i, a in enumerate(gripper) for b in gripper[i + 1:]
              if (a, b, "Adjacent") not in pairs and (b, a, "Adjacent") not in pairs]
    pairs.append(("base_link", "camera_link", "Never"))  # a link this URDF does not have
    lines = ['<?xml version="1.0" ?>', '<robot name="mesh_arm">',
             '  <group name="manipulator">', '    <chain base_link="base_link" tip_link="tool0"/>',
             "  </group>", '  <group name="gripper">']
    lines += [f'    <link name="{g}"/>' for g in gripper]
    lines += ["  </group>", '  <group_state name="home" group="manipulator">']
    lines += [f'    <joint name="{j}" value="0"/>' for j in
              ("shoulder_pan_joint", "shoulder_lift_joint", "elbow_joint", "wrist_1_joint",
               "wrist_2_joint", "wrist_3_joint")]
    lines += ["  </group_state>",
              '  <end_effector name="hand" parent_link="tool0" group="gripper"/>',
              '  <virtual_joint name="fixed_base" type="fixed" parent_frame="world" '
              'child_link="base_link"/>']
    lines += [f'  <disable_collisions link1="{a}" link2="{b}" reason="{r}"/>' for a, b, r in pairs]
    lines.append("</robot>")
    return "\n".join(lines) + "\n"


def main():
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    out = Path(sys.argv[1])
    meshes = out / "mesh_arm_description" / "meshes"
    meshes.mkdir(parents=True, exist_ok=True)
    parts = robot_parts()
    for name, triangles, _ in parts:
        if triangles is not None:
            write_stl(meshes / f"{name}.stl", triangles)
    (out / "mesh-arm.urdf").write_text(urdf(parts))
    (out / "mesh-arm.srdf").write_text(srdf(parts))


if __name__ == "__main__":
    main()
