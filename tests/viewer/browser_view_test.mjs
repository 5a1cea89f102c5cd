// comply's live view in a real browser: Debian's Chromium (headless, driven by playwright-core)
// loads a page with Foxglove's own WebSocket client and ROS 2 deserializer, connects to
// `comply sim --foxglove`, and the test checks what it received against the run's own recording
// and the URDF: rates, values at the same cycle, both subprotocol names, the 3D panel's
// transforms and markers, and a slow client's drops while a small channel still arrives whole.
//
//   node browser_view_test.mjs COMPLY TASK WORKDIR ROBOT_URDF

import assert from "node:assert/strict";
import { spawn } from "node:child_process";
import { mkdirSync, readFileSync } from "node:fs";
import { join } from "node:path";

import { openViewPage } from "./browser_page.mjs";
import { recordedCycles } from "./recorded_cycles.mjs";
import { checkLayout } from "./layout_checks.mjs";
import { ellipsoidAxes, transformError, urdfJoints } from "./scene_checks.mjs";


const [comply, task, workdir, urdfPath, layoutPath] = process.argv.slice(2);
mkdirSync(workdir, { recursive: true });
const recording = join(workdir, "view.mcap");

function startSim() {
  const child = spawn(comply, ["sim", "--robot", "fr3", "--task", task, "--duration", "25", "--foxglove", "127.0.0.1:0",
    "--foxglove-wait", "60", "--record", recording, "--out", join(workdir, "out"), "--no-plot"]);
  let stderr = "";
  const url = new Promise((resolve, reject) => {
    child.stderr.on("data", (chunk) => {
      stderr += chunk;
      const found = stderr.match(/Foxglove live view on (ws:\/\/\S+)/);
      if (found) resolve(found[1]);
    });
    child.on("exit", (code) => reject(new Error(`comply sim exited (${code}) before serving:\n${stderr}`)));
  });
  const exited = new Promise((resolve) => child.on("exit", (code) => resolve({ code, stderr })));
  return { url, exited, child };
}

const TOPICS = ["/comply/state", "/comply/cycle", "/tf", "/comply/markers", "/robot_description", "/comply/outcome",
  "/comply/diagnostics"];

function checkAdvertised(session) {
  const schemas = Object.fromEntries(session.advertised.map((c) => [c.topic, c.schemaName]));
  assert.equal(session.serverName, "comply");
  assert.equal(schemas["/comply/state"], "comply_msgs/msg/ControllerState");
  assert.equal(schemas["/comply/cycle"], "comply_msgs/msg/CycleRecord");
  assert.equal(schemas["/comply/diagnostics"], "comply_msgs/msg/Diagnostics");
  assert.equal(schemas["/comply/outcome"], "comply_msgs/msg/CommandOutcome");
  assert.equal(schemas["/comply/cartesian_chunk"], "comply_msgs/msg/CartesianChunk");
  assert.equal(schemas["/robot_description"], "std_msgs/msg/String");
  assert.equal(schemas["/tf"], "foxglove.FrameTransforms");
  assert.equal(schemas["/comply/markers"], "foxglove.SceneUpdate");
}

function checkValues(session, cycles) {
  const states = session.messages["/comply/state"];
  const rate = states.length / (session.windowMs / 1000);
  console.log(`state: ${states.length} messages in ${(session.windowMs / 1000).toFixed(2)} s: ${rate.toFixed(0)} Hz`);
  assert.ok(rate >= 100, `state at ${rate} Hz, below 100 Hz`);
  for (let i = 1; i < states.length; ++i) assert.ok(states[i].cycle > states[i - 1].cycle, "state cycles out of order");
  // Watched, comply sim keeps to real time: its clock (the stamps) never ahead of the browser's.
  const simulatedS = Number(BigInt(states.at(-1).stamp) - BigInt(states[0].stamp)) / 1e9;
  const wallS = (states.at(-1).at - states[0].at) / 1000;
  console.log(`pacing: ${simulatedS.toFixed(3)} s simulated while ${wallS.toFixed(3)} s passed in the browser`);
  assert.ok(simulatedS <= wallS * 1.02 + 0.05 && simulatedS > 0.5 * wallS, "not paced to real time while watched");
  for (const state of states) {
    const recorded = cycles.get(state.cycle);
    assert.ok(recorded, `cycle ${state.cycle} is not in the recording`);
    assert.deepEqual(state.position, Array.from(recorded.state.position), `joint positions of cycle ${state.cycle}`);
  }
  const records = session.messages["/comply/cycle"];
  assert.ok(records.length >= 100, `only ${records.length} cycle records`);
  for (const record of records) {
    const recorded = cycles.get(record.cycle);
    const command = recorded.cartesian_in_force[0];
    assert.deepEqual(record.position, Array.from(recorded.state.position));
    assert.deepEqual(record.stiffness, Array.from(command.stiffness_translational), `K of cycle ${record.cycle}`);
    assert.deepEqual(record.damping, Array.from(command.damping_translational), `D of cycle ${record.cycle}`);
    assert.deepEqual(record.damping_ratio, Array.from(command.damping_ratio));
    assert.deepEqual(record.task_frame, Array.from(command.task_frame));
  }
  const last = records.at(-1);
  assert.deepEqual(last.stiffness, [1500, 0, 0, 0, 600, 0, 0, 0, 300], "the task's stiffness in force");
  assert.ok(Math.abs(last.task_frame[2] - Math.sin(Math.PI / 8)) < 1e-12 && Math.abs(last.task_frame[3] - Math.cos(Math.PI / 8)) < 1e-12);
  assert.ok(last.damping.some((d) => d > 0), "damping in force");
  console.log(`values: ${states.length} states and ${records.length} cycle records equal to the recording's at their cycles`);
  return last;
}

function checkScene(session, urdf, last) {
  assert.equal(session.messages["/robot_description"][0].data, urdf, "/robot_description is the robot's URDF");
  const joints = urdfJoints(urdf);
  const states = new Map(session.messages["/comply/state"].map((s) => [s.stamp, s]));
  let compared = 0;
  for (const tf of session.messages["/tf"]) {
    const state = states.get(tf.logTime);
    if (!state) continue;
    const { worst, compared: links } = transformError(tf.message.transforms, joints, state.names, state.position);
    assert.ok(links >= 7, `only ${links} link transforms`);
    assert.ok(worst < 1e-12, `a link's rotation differs from the URDF's at the state's joints (1 - |dot| = ${worst})`);
    const taskFrame = tf.message.transforms.find((t) => t.child_frame_id === "comply/task_frame");
    assert.ok(Math.abs(taskFrame.rotation.z - Math.sin(Math.PI / 8)) < 1e-12);
    compared += 1;
  }
  assert.ok(compared >= 10, `only ${compared} transform messages matched a state`);
  const update = session.messages["/comply/markers"].at(-1).message;
  const sphere = update.entities.find((e) => e.id === "stiffness").spheres[0];
  const axes = ellipsoidAxes(sphere);
  const expected = [1500, 600, 300].map((k) => k * 2e-4); // kStiffnessEllipsoidMPerNPerM
  axes.forEach((a, i) => assert.ok(Math.abs(a.length - expected[i]) < 1e-12, `ellipsoid axis ${i}: ${a.length}`));
  // The stiffest axis is the task frame's x: (cos 45, sin 45, 0) in the base frame.
  const along = Math.abs(axes[0].axis[0] * Math.SQRT1_2 + axes[0].axis[1] * Math.SQRT1_2);
  assert.ok(along > 1 - 1e-12, `the ellipsoid's longest axis is not the task frame's x (${axes[0].axis})`);
  console.log(`scene: ${compared} transform messages equal to the URDF at the state's joints; ellipsoid ${axes.map((a) => a.length.toFixed(4)).join(" ")} m along the task frame`);
}

function checkSlowClient(session) {
  const records = session.messages["/comply/cycle"];
  let gap = 0;
  for (let i = 1; i < records.length; ++i) gap = Math.max(gap, records[i].cycle - records[i - 1].cycle);
  const warnings = session.status.filter((s) => s.level === 1 && s.message.includes("/comply/cycle"));
  console.log(`slow client: blocked ${(session.blockedTo - session.blockedFrom).toFixed(0)} ms; largest gap in cycle records ${gap} cycles; status: ${warnings[0]?.message}`);
  assert.ok(warnings.length > 0, "no status message about the dropped cycle records");
  assert.ok(gap > 100, "the slow client lost no cycle records");
  const outcomes = session.messages["/comply/outcome"].map((o) => BigInt(o.stamp));
  let outcomeGapNs = 0n;
  for (let i = 1; i < outcomes.length; ++i) {
    const step = outcomes[i] - outcomes[i - 1];
    if (step > outcomeGapNs) outcomeGapNs = step;
  }
  const during = session.messages["/comply/outcome"].filter((o) => o.at > session.blockedTo).length;
  console.log(`slow client: ${outcomes.length} outcomes, none missing (largest step ${Number(outcomeGapNs) / 1e6} ms), ${during} of them read after the block`);
  assert.ok(outcomes.length > 300, "too few outcomes");
  assert.ok(outcomeGapNs <= 10_000_001n, `an outcome is missing (a ${outcomeGapNs} ns step between command stamps)`);
}

const sim = startSim();
const url = await sim.url;
const { browser, page } = await openViewPage("comply live view test");
try {
  assert.equal(await page.evaluate(([u]) => window.complyView.refuses(u, "foxglove.other.v9"), [url]), true, "an unknown subprotocol was accepted");
  const [main, old] = await Promise.all([
    page.evaluate(([u, t]) => window.complyView.watch(u, "foxglove.sdk.v1", t, { durationMs: 4000 }), [url, TOPICS]),
    page.evaluate(([u]) => window.complyView.watch(u, "foxglove.websocket.v1", ["/comply/outcome"], { durationMs: 1000 }), [url]),
  ]);
  assert.equal(main.protocol, "foxglove.sdk.v1");
  assert.equal(old.protocol, "foxglove.websocket.v1");
  assert.ok(old.messages["/comply/outcome"].length > 20, "the foxglove.websocket.v1 client got no outcomes");
  checkAdvertised(main);
  checkAdvertised(old);
  const slow = await page.evaluate(([u]) => window.complyView.watch(u, "foxglove.sdk.v1", ["/comply/state", "/comply/cycle", "/comply/outcome"],
    { durationMs: 7000, blockAfterMs: 1000, blockMs: 4000 }), [url]);
  await page.evaluate(() => window.complyView.closeAll());
  const { code, stderr } = await sim.exited;
  assert.equal(code, 0, `comply sim failed:\n${stderr}`);
  const cycles = recordedCycles(recording);
  const last = checkValues(main, cycles);
  checkScene(main, readFileSync(urdfPath, "utf8"), last);
  checkSlowClient(slow);
  const layoutPaths = checkLayout(JSON.parse(readFileSync(layoutPath, "utf8")), main.advertised.map((c) => c.topic), main.first);
  console.log(`layout: ${layoutPaths} topics and paths of ${layoutPath} served`);
  const summary = stderr.match(/live view: .*/)?.[0];
  console.log(`comply sim: ${summary}`);
  assert.ok(summary && /, [1-9][0-9]* dropped/.test(summary), "comply sim's summary names no dropped messages");
  console.log("ok");
} finally {
  await browser.close();
  sim.child.kill();
}
