// A page of Debian's Chromium (headless, driven by playwright-core) with view_page.mjs bundled
// into it by esbuild: Foxglove's own WebSocket client and ROS 2 deserializer, as window.complyView.

import { createRequire } from "node:module";

const require = createRequire(new URL("./node/package.json", import.meta.url));
const esbuild = require("esbuild");
const { chromium } = require("playwright-core");

/// `browserArgs`: more Chromium switches (WebGL in software for a picture).
export async function openViewPage(title, browserArgs = []) {
  const bundle = await esbuild.build({
    entryPoints: [new URL("./view_page.mjs", import.meta.url).pathname],
    bundle: true, format: "iife", platform: "browser", write: false, logLevel: "error",
    nodePaths: [new URL("./node/node_modules", import.meta.url).pathname],
  });
  const browser = await chromium.launch({
    executablePath: process.env.COMPLY_CHROMIUM ?? "/usr/bin/chromium",
    // A container's root has no user namespaces for Chromium's sandbox.
    args: ["--no-sandbox", ...browserArgs],
  });
  const page = await browser.newPage();
  page.on("pageerror", (error) => console.error("page error:", error));
  await page.setContent(`<!doctype html><title>${title}</title>`);
  await page.addScriptTag({ content: bundle.outputFiles[0].text });
  return { browser, page };
}

/// The live view's URL once a host prints it on `stream` ("Foxglove live view on ws://...").
export function viewUrlFrom(stream) {
  return new Promise((resolve) => {
    let text = "";
    stream.on("data", (chunk) => {
      text += chunk;
      const found = text.match(/Foxglove live view on (ws:\/\/\S+)/);
      if (found) resolve(found[1]);
    });
  });
}
