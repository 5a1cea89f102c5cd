// Draws what the live view sends a 3D panel (the URDF, /tf, the markers) with three.js, for the
// documentation's picture (scene_snapshot.mjs). Exposes window.complyRender.

import * as THREE from "three";

const numbers = (text, fallback) => (text ? text.trim().split(/\s+/).map(Number) : fallback);

function visualsOf(urdfText) {
  const xml = new DOMParser().parseFromString(urdfText, "application/xml");
  const colors = new Map();
  for (const material of xml.querySelectorAll("robot > material")) {
    const rgba = numbers(material.querySelector("color")?.getAttribute("rgba"), [0.7, 0.7, 0.7, 1]);
    colors.set(material.getAttribute("name"), rgba);
  }
  const links = new Map();
  for (const link of xml.querySelectorAll("link")) {
    const visuals = [];
    for (const visual of link.querySelectorAll("visual")) {
      const origin = visual.querySelector("origin");
      const geometry = visual.querySelector("geometry > *");
      const material = visual.querySelector("material");
      visuals.push({
        xyz: numbers(origin?.getAttribute("xyz"), [0, 0, 0]),
        rpy: numbers(origin?.getAttribute("rpy"), [0, 0, 0]),
        kind: geometry.tagName,
        radius: Number(geometry.getAttribute("radius")),
        length: Number(geometry.getAttribute("length")),
        size: numbers(geometry.getAttribute("size"), [0, 0, 0]),
        rgba: numbers(material?.querySelector("color")?.getAttribute("rgba"), colors.get(material?.getAttribute("name")) ?? [0.75, 0.75, 0.78, 1]),
      });
    }
    links.set(link.getAttribute("name"), visuals);
  }
  return links;
}

function meshOf(visual) {
  let geometry;
  if (visual.kind === "cylinder") {
    geometry = new THREE.CylinderGeometry(visual.radius, visual.radius, visual.length, 32);
    geometry.rotateX(Math.PI / 2); // three's cylinders stand along y, a URDF's along z
  } else if (visual.kind === "sphere") {
    geometry = new THREE.SphereGeometry(visual.radius, 32, 16);
  } else if (visual.kind === "box") {
    geometry = new THREE.BoxGeometry(...visual.size);
  } else {
    return null;
  }
  const [r, g, b, a] = visual.rgba;
  const mesh = new THREE.Mesh(geometry, new THREE.MeshStandardMaterial({ color: new THREE.Color(r, g, b), transparent: a < 1, opacity: a, roughness: 0.6 }));
  mesh.position.set(...visual.xyz);
  mesh.rotation.copy(new THREE.Euler(visual.rpy[0], visual.rpy[1], visual.rpy[2], "ZYX")); // fixed-axis roll, pitch, yaw
  return mesh;
}

const vector = (v) => new THREE.Vector3(v.x, v.y, v.z);
const quaternion = (q) => new THREE.Quaternion(q.x, q.y, q.z, q.w);

function markerObjects(update) {
  const group = new THREE.Group();
  for (const entity of update.entities) {
    for (const sphere of entity.spheres) {
      const mesh = new THREE.Mesh(new THREE.SphereGeometry(0.5, 48, 24), new THREE.MeshStandardMaterial({
        color: new THREE.Color(sphere.color.r, sphere.color.g, sphere.color.b), transparent: true, opacity: sphere.color.a, depthWrite: false }));
      mesh.position.copy(vector(sphere.pose.position));
      mesh.quaternion.copy(quaternion(sphere.pose.orientation));
      mesh.scale.set(sphere.size.x, sphere.size.y, sphere.size.z);
      group.add(mesh);
    }
    for (const arrow of entity.arrows) {
      const direction = new THREE.Vector3(1, 0, 0).applyQuaternion(quaternion(arrow.pose.orientation));
      group.add(new THREE.ArrowHelper(direction, vector(arrow.pose.position), arrow.shaft_length + arrow.head_length,
        new THREE.Color(arrow.color.r, arrow.color.g, arrow.color.b), arrow.head_length, arrow.head_diameter));
    }
    for (const line of entity.lines) {
      const geometry = new THREE.BufferGeometry().setFromPoints(line.points.map(vector));
      group.add(new THREE.Line(geometry, new THREE.LineBasicMaterial({ color: new THREE.Color(line.color.r, line.color.g, line.color.b) })));
    }
  }
  return group;
}

/// Draws the scene into a canvas of the page; `axes`: frames drawn as axes, name -> length [m].
function draw(urdfText, transforms, update, axes, { width = 960, height = 720, eye = [0.6, -1.3, 1.35], target = [0.3, 0.02, 0.4] } = {}) {
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(0.96, 0.96, 0.97);
  const frames = new Map();
  const frame = (name) => {
    if (!frames.has(name)) frames.set(name, new THREE.Group());
    return frames.get(name);
  };
  const children = new Set();
  for (const t of transforms) {
    const child = frame(t.child_frame_id);
    child.position.copy(vector(t.translation));
    child.quaternion.copy(quaternion(t.rotation));
    frame(t.parent_frame_id).add(child);
    children.add(t.child_frame_id);
  }
  for (const [name, object] of frames) if (!children.has(name)) scene.add(object);
  for (const [link, visuals] of visualsOf(urdfText)) {
    for (const visual of visuals) {
      const mesh = meshOf(visual);
      if (mesh) frame(link).add(mesh);
    }
  }
  for (const [name, length] of Object.entries(axes)) {
    // x red, y green, z blue, as Foxglove draws a frame's axes.
    [[1, 0, 0, 0xe53935], [0, 1, 0, 0x43a047], [0, 0, 1, 0x1e88e5]].forEach(([x, y, z, color]) =>
      frame(name).add(new THREE.ArrowHelper(new THREE.Vector3(x, y, z), new THREE.Vector3(), length, color, 0.2 * length, 0.08 * length)));
  }
  scene.add(markerObjects(update));
  const grid = new THREE.GridHelper(1.6, 16, 0x9aa4b0, 0xd0d5db);
  grid.rotateX(Math.PI / 2);
  scene.add(grid);
  scene.add(new THREE.AmbientLight(0xffffff, 0.9));
  const sun = new THREE.DirectionalLight(0xffffff, 1.6);
  sun.position.set(1, -1, 2);
  scene.add(sun);
  const camera = new THREE.PerspectiveCamera(40, width / height, 0.01, 20);
  camera.up.set(0, 0, 1);
  camera.position.set(...eye);
  camera.lookAt(...target);
  const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  renderer.setSize(width, height);
  document.body.appendChild(renderer.domElement);
  renderer.render(scene, camera);
  return renderer.domElement.toDataURL("image/png");
}

window.complyRender = { draw };
