// The documentation's picture of the live view's 3D scene (docs/images/live-view.png): a
// `comply sim --foxglove` run of view_task.yaml watched for a few seconds from headless Chromium
// with Foxglove's client, then its last transforms and markers and the robot description drawn
// by scene_render_page.mjs (three.js). Run by hand: node tests/viewer/scene_snapshot.mjs COMPLY OUT.png

import { spawn } from "node:child_process";
import { writeFileSync } from "node:fs";
import { createRequire } from "node:module";

import { openViewPage, viewUrlFrom } from "./browser_page.mjs";

const require = createRequire(new URL("./node/package.json", import.meta.url));
const esbuild = require("esbuild");

const [comply, out] = process.argv.slice(2);
const task = new URL("./view_task.yaml", import.meta.url).pathname;
const sim = spawn(comply, ["sim", "--robot", "fr3", "--task", task, "--duration", "8", "--foxglove", "127.0.0.1:0",
  "--foxglove-wait", "60", "--no-plot", "--out", "/tmp/comply-scene-snapshot"]);
const url = await viewUrlFrom(sim.stderr);
const { browser, page } = await openViewPage("comply live view scene", ["--use-angle=swiftshader", "--enable-unsafe-swiftshader"]);
try {
  const renderer = await esbuild.build({
    entryPoints: [new URL("./scene_render_page.mjs", import.meta.url).pathname], bundle: true, format: "iife",
    platform: "browser", write: false, logLevel: "error", nodePaths: [new URL("./node/node_modules", import.meta.url).pathname],
  });
  await page.addScriptTag({ content: renderer.outputFiles[0].text });
  const png = await page.evaluate(async ([u]) => {
    const seen = await window.complyView.watch(u, "foxglove.sdk.v1", ["/robot_description", "/tf", "/comply/markers"], { durationMs: 4300 });
    const tf = seen.messages["/tf"].at(-1).message.transforms;
    const markers = seen.messages["/comply/markers"].at(-1).message;
    return window.complyRender.draw(seen.messages["/robot_description"][0].data, tf, markers,
      { "comply/task_frame": 0.25, "fr3_link0": 0.1 });
  }, [url]);
  writeFileSync(out, Buffer.from(png.split(",")[1], "base64"));
  console.log(`wrote ${out}`);
} finally {
  await browser.close();
  sim.kill();
}
