// What viewers cost the control cycle: `comply run --sim` for DURATION seconds with 0, 1 and 3
// Foxglove clients connected, each a process of its own (node_viewer.mjs: Foxglove's client and
// ROS 2 deserializer, decoding every message of every channel), and the cycle's start lateness
// and compute time as comply run reports them, ROUNDS times in turn. A measurement, not a test:
// run it by hand on an otherwise idle machine (docs/live-view.md).
//
//   node tests/viewer/viewer_timing.mjs build/apps/comply/comply [DURATION_S] [ROUNDS] [RUN_OPTION...]
//
// RUN_OPTIONs go to comply run as they are (e.g. --warm-ahead-us 200).

import { spawn } from "node:child_process";

import { viewUrlFrom } from "./browser_page.mjs";

const [comply, durationText = "20", roundsText = "3", ...runOptions] = process.argv.slice(2);
const duration = Number(durationText);
const TOPICS = ["/comply/state", "/comply/cycle", "/comply/diagnostics", "/comply/outcome", "/tf",
  "/comply/markers", "/robot_description"];
const config = new URL("../../config/cartesian_impedance.yaml", import.meta.url).pathname;

function output(child) {
  let text = "";
  child.stdout.on("data", (chunk) => (text += chunk));
  return new Promise((resolve) => child.on("exit", (code) => resolve({ code, text })));
}

async function run(viewers) {
  const host = spawn(comply, ["run", "--sim", "--config", config, "--duration", String(duration),
    "--transport", "in_process", "--foxglove", "127.0.0.1:0", ...runOptions]);
  const hostDone = output(host);
  const url = await viewUrlFrom(host.stdout);
  const clients = Array.from({ length: viewers }, () => output(spawn(process.execPath,
    ["--experimental-websocket", "--no-warnings", new URL("./node_viewer.mjs", import.meta.url).pathname,
      url, String((duration - 2) * 1000), ...TOPICS])));
  const received = (await Promise.all(clients)).map((c) => Object.values(JSON.parse(c.text)).reduce((a, b) => a + b, 0));
  const { code, text } = await hostDone;
  const found = text.match(/lateness p50 (\d+) us, p99 (\d+) us, max (\d+) us; compute p50 (\d+) us, p99 (\d+) us, max (\d+) us/);
  if (code !== 0 || !found) throw new Error(`comply run failed (${code}):\n${text}`);
  const [p50, p99, max, c50, c99, cmax] = found.slice(1).map(Number);
  return { viewers, p50, p99, max, c50, c99, cmax, received, view: text.match(/live view: .*/)?.[0] ?? "" };
}

console.log(`comply run --sim ${runOptions.join(" ")}, FR3 Cartesian impedance at 1 kHz, ${duration} s a run; us (10 us bins, max exact)`);
console.log("| round | viewers | start lateness p50 | p99 | max | compute p50 | p99 | max | messages per viewer |");
console.log("|---|---|---|---|---|---|---|---|---|");
for (let round = 1; round <= Number(roundsText); ++round) {
  for (const viewers of [0, 1, 3]) {
    const r = await run(viewers);
    console.log(`| ${round} | ${r.viewers} | ${r.p50} | ${r.p99} | ${r.max} | ${r.c50} | ${r.c99} | ${r.cmax} | ${r.received.join(", ") || "-"} |`);
  }
}
