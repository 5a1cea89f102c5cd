// The layout file (config/foxglove/comply_layout.json) against what the live view serves: every
// topic its panels name is advertised, and every plotted path leads to a number in a message
// the view sent (Foxglove's message path syntax: /topic.field[index].field).

import assert from "node:assert/strict";

function resolvePath(path, advertised, first) {
  const topic = advertised.filter((t) => path === t || path.startsWith(`${t}.`)).sort((a, b) => b.length - a.length)[0];
  assert.ok(topic, `the layout names ${path}, which the live view does not advertise`);
  let value = first[topic];
  assert.ok(value !== undefined, `no message of ${topic} to check ${path} against`);
  for (const token of path.slice(topic.length).match(/\.[A-Za-z_0-9]+|\[\d+\]/g) ?? []) {
    value = token.startsWith(".") ? value?.[token.slice(1)] : value?.[Number(token.slice(1, -1))];
  }
  return value;
}

/// Checks the layout; returns how many paths it checked.
export function checkLayout(layout, advertised, first) {
  const scripts = Object.values(layout.userNodes);
  let checked = 0;
  for (const [id, config] of Object.entries(layout.configById)) {
    const paths = (config.paths ?? []).map((p) => p.value);
    if (config.topicPath) paths.push(config.topicPath);
    for (const path of paths) {
      if (path.startsWith("/studio_script/")) {
        // A user script's output: its inputs must be served.
        const script = scripts.find((s) => s.sourceCode.includes(path.split(".")[0]));
        assert.ok(script, `${id}: no user script writes ${path}`);
        for (const input of script.sourceCode.match(/inputs = \[([^\]]*)\]/)[1].match(/"[^"]+"/g)) {
          assert.ok(advertised.includes(JSON.parse(input)), `${id}: the script reads ${input}`);
        }
      } else if (config.topicPath === path) {
        assert.ok(advertised.includes(path), `${id}: ${path} is not advertised`);
      } else {
        const value = resolvePath(path, advertised, first);
        assert.equal(typeof value, "number", `${id}: ${path} is ${JSON.stringify(value)}, not a number`);
      }
      checked += 1;
    }
    for (const layer of Object.values(config.layers ?? {})) {
      if (layer.sourceType === "topic") {
        assert.ok(advertised.includes(layer.topic), `${id}: the layer's topic ${layer.topic}`);
        checked += 1;
      }
    }
  }
  return checked;
}
