// Independent checks of what the 3D panel is sent: the links' transforms recomputed from the URDF
// text and the joint positions (quaternions written out here, not comply's code), the stiffness
// ellipsoid from the stiffness and task frame in force.

const multiply = (a, b) => ({
  w: a.w * b.w - a.x * b.x - a.y * b.y - a.z * b.z,
  x: a.w * b.x + a.x * b.w + a.y * b.z - a.z * b.y,
  y: a.w * b.y - a.x * b.z + a.y * b.w + a.z * b.x,
  z: a.w * b.z + a.x * b.y - a.y * b.x + a.z * b.w,
});

function fromRpy([roll, pitch, yaw]) {
  const about = (axis, angle) => ({ w: Math.cos(angle / 2), x: axis[0] * Math.sin(angle / 2), y: axis[1] * Math.sin(angle / 2), z: axis[2] * Math.sin(angle / 2) });
  return multiply(multiply(about([0, 0, 1], yaw), about([0, 1, 0], pitch)), about([1, 0, 0], roll));
}

function aboutAxis(axis, angle) {
  const n = Math.hypot(...axis);
  const s = Math.sin(angle / 2) / n;
  return { w: Math.cos(angle / 2), x: axis[0] * s, y: axis[1] * s, z: axis[2] * s };
}

export function rotate(q, v) {
  const r = multiply(multiply(q, { w: 0, x: v[0], y: v[1], z: v[2] }), { w: q.w, x: -q.x, y: -q.y, z: -q.z });
  return [r.x, r.y, r.z];
}

const numbers = (text, fallback) => (text ? text.trim().split(/\s+/).map(Number) : fallback);

/// The URDF's joints by name: parent, child, origin rotation, axis, movable.
export function urdfJoints(urdf) {
  const joints = new Map();
  for (const match of urdf.matchAll(/<joint\s+name="([^"]+)"\s+type="([^"]+)"[^>]*>([\s\S]*?)<\/joint>/g)) {
    const [, name, type, body] = match;
    const attribute = (tag, key) => body.match(new RegExp(`<${tag}[^>]*\\s${key}="([^"]*)"`))?.[1];
    joints.set(name, {
      parent: attribute("parent", "link"),
      child: attribute("child", "link"),
      origin: fromRpy(numbers(attribute("origin", "rpy"), [0, 0, 0])),
      axis: numbers(attribute("axis", "xyz"), [1, 0, 0]),
      movable: type === "revolute" || type === "continuous",
    });
  }
  return joints;
}

/// Largest difference between the transforms' rotations and the URDF's at `positions` (the
/// controlled joints in `names`' order), up to a quaternion's sign; and how many were compared.
export function transformError(transforms, joints, names, positions) {
  let worst = 0;
  let compared = 0;
  for (const transform of transforms) {
    const entry = [...joints.entries()].find(([, joint]) => joint.parent === transform.parent_frame_id && joint.child === transform.child_frame_id);
    if (!entry) continue;
    const [name, joint] = entry;
    const index = names.indexOf(name);
    const q = joint.movable && index >= 0 ? positions[index] : 0;
    const expected = multiply(joint.origin, aboutAxis(joint.axis, q));
    const got = transform.rotation;
    const dot = expected.w * got.w + expected.x * got.x + expected.y * got.y + expected.z * got.z;
    worst = Math.max(worst, 1 - Math.abs(dot));
    compared += 1;
  }
  return { worst, compared };
}

/// The ellipsoid's axes in the base frame with their lengths, longest first.
export function ellipsoidAxes(sphere) {
  const q = sphere.pose.orientation;
  return [
    { axis: rotate(q, [1, 0, 0]), length: sphere.size.x },
    { axis: rotate(q, [0, 1, 0]), length: sphere.size.y },
    { axis: rotate(q, [0, 0, 1]), length: sphere.size.z },
  ].sort((a, b) => b.length - a.length);
}
