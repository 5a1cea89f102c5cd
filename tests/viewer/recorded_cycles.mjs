// The /comply/cycle records of a recording, by cycle index: what the simulation itself recorded,
// read with Foxglove's MCAP and ROS 2 readers, for the browser test to compare against.

import { readFileSync } from "node:fs";
import { createRequire } from "node:module";

const require = createRequire(new URL("./node/package.json", import.meta.url));
const { McapStreamReader } = require("@mcap/core");
const { parse } = require("@foxglove/rosmsg");
const { MessageReader } = require("@foxglove/rosmsg2-serialization");
const { decompress } = require("fzstd");

export function recordedCycles(path) {
  const reader = new McapStreamReader({
    decompressHandlers: { zstd: (data, size) => decompress(data, new Uint8Array(Number(size))) },
  });
  reader.append(readFileSync(path));
  const schemas = new Map();
  const channels = new Map();
  const cycles = new Map();
  for (let record; (record = reader.nextRecord()); ) {
    if (record.type === "Schema") {
      schemas.set(record.id, record);
    } else if (record.type === "Channel" && record.topic === "/comply/cycle") {
      const schema = schemas.get(record.schemaId);
      channels.set(record.id, new MessageReader(parse(new TextDecoder().decode(schema.data), { ros2: true })));
    } else if (record.type === "Message" && channels.has(record.channelId)) {
      const message = channels.get(record.channelId).readMessage(record.data);
      cycles.set(Number(message.state.cycle), message);
    }
  }
  return cycles;
}
