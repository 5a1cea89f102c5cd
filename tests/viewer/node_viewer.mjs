// A viewer without a browser: view_page.mjs (Foxglove's client and deserializer) run by Node with
// its WebSocket (node --experimental-websocket), in a process of its own. It subscribes to TOPICS
// for DURATION_MS and prints how many messages of each it decoded, as JSON.
//
//   node --experimental-websocket node_viewer.mjs URL DURATION_MS TOPIC...

import { createRequire } from "node:module";

const require = createRequire(new URL("./node/package.json", import.meta.url));
const esbuild = require("esbuild");

const [url, durationText, ...topics] = process.argv.slice(2);
const bundle = await esbuild.build({
  entryPoints: [new URL("./view_page.mjs", import.meta.url).pathname],
  bundle: true, format: "iife", platform: "browser", write: false, logLevel: "error",
  nodePaths: [new URL("./node/node_modules", import.meta.url).pathname],
});
globalThis.window = globalThis;
new Function(bundle.outputFiles[0].text)();
const result = await window.complyView.watch(url, "foxglove.sdk.v1", topics, { durationMs: Number(durationText) });
window.complyView.closeAll();
console.log(JSON.stringify(Object.fromEntries(Object.entries(result.messages).map(([t, m]) => [t, m.length]))));
