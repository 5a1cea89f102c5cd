// The page the browser test loads (bundled by esbuild): Foxglove's own WebSocket client and ROS 2
// deserializer, as Foxglove's app uses them, against comply's live view. Exposes window.complyView.

import { parse } from "@foxglove/rosmsg";
import { MessageReader } from "@foxglove/rosmsg2-serialization";
import { FoxgloveClient } from "@foxglove/ws-protocol";

const textDecoder = new TextDecoder();

function decoderOf(channel) {
  if (channel.encoding === "cdr" && channel.schemaEncoding === "ros2msg") {
    const reader = new MessageReader(parse(channel.schema, { ros2: true }));
    return (view) =>
      reader.readMessage(new Uint8Array(view.buffer, view.byteOffset, view.byteLength));
  }
  if (channel.encoding === "json") {
    return (view) => JSON.parse(textDecoder.decode(view));
  }
  throw new Error(`no decoder for ${channel.topic} (${channel.encoding})`);
}

const stampNs = (stamp) => BigInt(stamp.sec) * 1000000000n + BigInt(stamp.nanosec);

/// What the test keeps of a decoded message: small, and cloneable back to node.
function summarize(topic, message, logTime) {
  if (topic.endsWith("/state")) {
    return {
      cycle: Number(message.cycle),
      stamp: stampNs(message.header.stamp).toString(),
      names: message.joint_names,
      position: Array.from(message.position),
    };
  }
  if (topic.endsWith("/cycle")) {
    const command = message.cartesian_in_force[0];
    return {
      cycle: Number(message.state.cycle),
      position: Array.from(message.state.position),
      stiffness: Array.from(command.stiffness_translational),
      damping: Array.from(command.damping_translational),
      damping_ratio: Array.from(command.damping_ratio),
      task_frame: Array.from(command.task_frame),
    };
  }
  if (topic.endsWith("/outcome")) {
    return { stamp: stampNs(message.stamp).toString(), outcome: message.outcome };
  }
  if (topic === "/robot_description") {
    return { data: message.data };
  }
  return { message, logTime: logTime.toString() };
}

/// Connects offering `subprotocol`, subscribes to `topics`, and collects for `durationMs`. With
/// `blockMs`, the page's thread is kept busy that long after `blockAfterMs`: a client that stops
/// reading, as a slow machine's viewer does.
async function watch(url, subprotocol, topics, { durationMs, blockAfterMs = 0, blockMs = 0 }) {
  const ws = new WebSocket(url, [subprotocol]);
  const client = new FoxgloveClient({ ws });
  const result = { protocol: "", serverName: "", advertised: [], status: [], messages: {}, first: {} };
  const decoders = new Map();
  const topicOf = new Map();
  let opened = false;
  const open = new Promise((resolve, reject) => {
    client.on("open", () => {
      opened = true;
      result.protocol = ws.protocol;
      resolve();
    });
    client.on("error", (error) => !opened && reject(error));
    client.on("close", () => !opened && reject(new Error("closed before opening")));
  });
  client.on("serverInfo", (info) => (result.serverName = info.name));
  client.on("status", (status) => result.status.push({ level: status.level, message: status.message, at: performance.now() }));
  client.on("advertise", (channels) => {
    for (const channel of channels) {
      result.advertised.push({ topic: channel.topic, schemaName: channel.schemaName, encoding: channel.encoding });
      if (topics.includes(channel.topic)) {
        const id = client.subscribe(channel.id);
        decoders.set(id, decoderOf(channel));
        topicOf.set(id, channel.topic);
        result.messages[channel.topic] = [];
      }
    }
  });
  client.on("message", ({ subscriptionId, timestamp, data }) => {
    const topic = topicOf.get(subscriptionId);
    const decoded = decoders.get(subscriptionId)(data);
    if (!(topic in result.first)) {
      // The whole message once, for the layout's paths: arrays and 64-bit numbers made plain.
      result.first[topic] = JSON.parse(JSON.stringify(decoded, (key, value) =>
        typeof value === "bigint" ? Number(value) : ArrayBuffer.isView(value) ? Array.from(value) : value));
    }
    const entry = summarize(topic, decoded, timestamp);
    entry.at = performance.now();
    result.messages[topic].push(entry);
  });
  await open;
  const start = performance.now();
  if (blockMs > 0) {
    await new Promise((resolve) => setTimeout(resolve, blockAfterMs));
    result.blockedFrom = performance.now();
    while (performance.now() - result.blockedFrom < blockMs) {
      // busy: nothing is read from the socket meanwhile
    }
    result.blockedTo = performance.now();
  }
  await new Promise((resolve) => setTimeout(resolve, Math.max(0, durationMs - (performance.now() - start))));
  result.windowMs = performance.now() - start;
  return { result, close: () => client.close() };
}

/// Whether a connection offering only `subprotocol` is refused (never opens).
function refuses(url, subprotocol) {
  return new Promise((resolve) => {
    const ws = new WebSocket(url, [subprotocol]);
    ws.onopen = () => {
      ws.close();
      resolve(false);
    };
    ws.onerror = () => resolve(true);
  });
}

const open = [];
window.complyView = {
  async watch(url, subprotocol, topics, options) {
    const { result, close } = await watch(url, subprotocol, topics, options);
    open.push(close);
    return result;
  },
  refuses,
  closeAll() {
    for (const close of open.splice(0)) close();
  },
};
