// Reads an MCAP file with the MCAP project's own TypeScript reader, so that comply's writer is
// checked by code it shares nothing with, and prints one JSON object describing the file.
// Usage: node tests/record/read_mcap.mjs FILE [--messages N]
// The npm packages live in tests/record/node (scripts/install-deps.sh runs npm ci there).
//
// Output: {header, summary, channels, counts, messages, metadata, truncated, complete_chunks}.
// A complete file is read through its summary (McapIndexedReader); a file cut short (no footer)
// through McapStreamReader up to its last complete record. Both paths also stream the whole file:
// that pass counts the chunks and sees every record, indexed or not.
// Every bigint becomes a decimal string, so one field always has one JSON type.
// Each kept message: {log_time, publish_time, sequence, data}, or data null and decode_error.
// Exit 0 on success; 1 with one line on stderr when the file is not MCAP, is corrupt (a CRC, a
// chunk, an index that misses messages) or the packages are missing.
import { readFileSync } from "node:fs";
import { createRequire } from "node:module";

const require = createRequire(new URL("./node/package.json", import.meta.url));

function fail(message) {
  process.stderr.write(`read_mcap: ${message.split("\n")[0]}\n`);
  process.exit(1);
}

let mcap, crc, fzstd, rosmsg, ros2;
try {
  mcap = require("@mcap/core");
  crc = require("@foxglove/crc"); // the CRC-32 @mcap/core uses, for the data section CRC
  fzstd = require("fzstd");
  rosmsg = require("@foxglove/rosmsg");
  ros2 = require("@foxglove/rosmsg2-serialization");
} catch (error) {
  fail(`npm packages missing (run: npm ci --prefix tests/record/node): ${error.message}`);
}

const MAGIC = Uint8Array.from(mcap.MCAP_MAGIC);
// Footer record: opcode, u64 length, u64 summary_start, u64 summary_offset_start, u32 summary_crc.
const FOOTER_LENGTH = 1 + 8 + 8 + 8 + 4;

const decompressHandlers = {
  zstd: (data, size) => {
    // Not decompressed into a buffer of the stated size: fzstd would hand that buffer back whole
    // even when the frame is shorter, and a wrong size would go unseen in a chunk without CRC.
    const out = fzstd.decompress(data);
    if (BigInt(out.byteLength) !== size) {
      throw new Error(`zstd chunk decompressed to ${out.byteLength} bytes, header says ${size}`);
    }
    return out;
  },
};

function parseArgs(argv) {
  let file;
  let messages = 3;
  for (let i = 0; i < argv.length; i++) {
    if (argv[i] === "--messages") {
      messages = Number(argv[++i]);
      if (!Number.isInteger(messages) || messages < 0) fail("--messages needs a count >= 0");
    } else if (file === undefined && !argv[i].startsWith("--")) {
      file = argv[i];
    } else {
      fail(`unexpected argument ${argv[i]}; usage: read_mcap.mjs FILE [--messages N]`);
    }
  }
  if (file === undefined) fail("usage: read_mcap.mjs FILE [--messages N]");
  return { file, messages };
}

// Plain JSON for a decoded value. Non-finite floats become strings because JSON.stringify would
// turn NaN and Infinity into null, hiding them from a test that compares values.
function toJson(value) {
  if (typeof value === "bigint") return value.toString();
  if (typeof value === "number") return Number.isFinite(value) ? value : String(value);
  if (ArrayBuffer.isView(value) && !(value instanceof DataView)) return Array.from(value, toJson);
  if (Array.isArray(value)) return value.map(toJson);
  if (value instanceof Map) {
    return Object.fromEntries(Array.from(value, ([key, item]) => [String(key), toJson(item)]));
  }
  if (value !== null && typeof value === "object") {
    return Object.fromEntries(Object.entries(value).map(([key, item]) => [key, toJson(item)]));
  }
  return value;
}

function startsWithMagic(buffer) {
  return buffer.length >= MAGIC.length && MAGIC.every((byte, i) => buffer[i] === byte);
}

// Whether the file ends as a finished writer leaves it: a Footer record, then the magic. Without
// them the file is taken as cut short, and a reading error ends the reading instead of failing.
function hasFooter(buffer) {
  const end = buffer.length - MAGIC.length;
  const start = end - FOOTER_LENGTH;
  if (start < 2 * MAGIC.length || !MAGIC.every((byte, i) => buffer[end + i] === byte)) return false;
  const view = new DataView(buffer.buffer, buffer.byteOffset + start, FOOTER_LENGTH);
  return view.getUint8(0) === mcap.Opcode.FOOTER && view.getBigUint64(1, true) === 20n;
}

// Decodes the messages of each channel from its schema; a channel whose encoding is not known
// here has its messages shown with their size only.
class Decoders {
  #readers = new Map();

  decode(channel, schema, data) {
    let reader = this.#readers.get(channel.id);
    if (reader === undefined) {
      reader = this.#makeReader(channel, schema);
      this.#readers.set(channel.id, reader);
    }
    return reader(data);
  }

  #makeReader(channel, schema) {
    if (channel.messageEncoding === "cdr" && schema?.encoding === "ros2msg") {
      let reader;
      try {
        reader = new ros2.MessageReader(
          rosmsg.parse(new TextDecoder().decode(schema.data), { ros2: true }),
        );
      } catch (error) {
        const message = `schema ${schema.name} does not parse: ${error.message}`;
        return () => {
          throw new Error(message);
        };
      }
      return (data) => reader.readMessage(data);
    }
    if (channel.messageEncoding === "json") {
      return (data) => JSON.parse(new TextDecoder().decode(data));
    }
    return (data) => ({ undecoded_bytes: data.byteLength });
  }
}

// Gathers what both reading paths report: messages per topic and the first N of each, decoded.
// A message that does not decode is kept with decode_error instead of data, not thrown: the
// container is still worth checking when a payload is not what its schema says.
class Tally {
  counts = {};
  messages = {};
  #decoders = new Decoders();

  constructor(keep) {
    this.keep = keep;
  }

  addChannel(channel) {
    this.counts[channel.topic] ??= 0;
    this.messages[channel.topic] ??= [];
  }

  add(message, channel, schema) {
    this.counts[channel.topic] += 1;
    const kept = this.messages[channel.topic];
    if (kept.length >= this.keep) return;
    const entry = {
      log_time: message.logTime.toString(),
      publish_time: message.publishTime.toString(),
      sequence: message.sequence,
    };
    try {
      entry.data = toJson(this.#decoders.decode(channel, schema, message.data));
    } catch (error) {
      entry.data = null;
      entry.decode_error = error.message.split("\n")[0];
    }
    kept.push(entry);
  }
}

function channelJson(channel, schemasById) {
  const schema = schemasById.get(channel.schemaId);
  return {
    id: channel.id,
    topic: channel.topic,
    message_encoding: channel.messageEncoding,
    schema_name: schema?.name ?? "",
    schema_encoding: schema?.encoding ?? "",
    metadata: Object.fromEntries(channel.metadata),
  };
}

// Every record in file order. In a file cut short the reader stops at the last complete record
// (a chunk counts only once all of it is there); a reading error there ends the pass, said on
// stderr, since a crash may leave anything after the last record written whole.
function streamPass(buffer, keep, complete) {
  const reader = new mcap.McapStreamReader({ includeChunks: true, decompressHandlers });
  const pass = {
    header: undefined,
    footer: undefined,
    schemasById: new Map(),
    channelsById: new Map(),
    metadata: [],
    chunks: 0,
    tally: new Tally(keep),
  };
  // The reader hands out a chunk before unpacking it: the chunk counts once the call after it
  // has succeeded, so one that fails to decompress or check is not counted.
  let unpacking = false;
  reader.append(buffer);
  for (;;) {
    let record;
    try {
      record = reader.nextRecord();
    } catch (error) {
      if (complete) throw error;
      process.stderr.write(`read_mcap: reading stopped early: ${error.message.split("\n")[0]}\n`);
      break;
    }
    if (unpacking) pass.chunks += 1;
    unpacking = record?.type === "Chunk";
    if (record === undefined) break;
    switch (record.type) {
      case "Header":
        pass.header = record;
        break;
      case "Schema":
        pass.schemasById.set(record.id, record);
        break;
      case "Channel":
        pass.channelsById.set(record.id, record);
        pass.tally.addChannel(record);
        break;
      case "Message": {
        const channel = pass.channelsById.get(record.channelId);
        pass.tally.add(record, channel, pass.schemasById.get(channel.schemaId));
        break;
      }
      case "Metadata":
        pass.metadata.push({ name: record.name, metadata: Object.fromEntries(record.metadata) });
        break;
      case "Footer":
        pass.footer = record;
        break;
    }
  }
  pass.done = reader.done();
  return pass;
}

function statisticsJson(statistics) {
  if (statistics === undefined) return null;
  return {
    message_count: statistics.messageCount.toString(),
    schema_count: statistics.schemaCount,
    channel_count: statistics.channelCount,
    chunk_count: statistics.chunkCount,
    message_start_time: statistics.messageStartTime.toString(),
    message_end_time: statistics.messageEndTime.toString(),
    channel_message_counts: toJson(statistics.channelMessageCounts),
  };
}

// The library keeps the data section CRC but does not check it: CRC-32 of every byte from the
// start of the file (magic included) up to the DataEnd record.
function checkDataSectionCrc(buffer, indexed) {
  if (indexed.dataSectionCrc === undefined) return;
  const actual = crc.crc32(buffer.subarray(0, Number(indexed.dataEndOffset)));
  if (actual !== indexed.dataSectionCrc) {
    throw new Error(`data section CRC ${actual} (DataEnd says ${indexed.dataSectionCrc})`);
  }
}

async function indexedPass(buffer, keep) {
  const indexed = await mcap.McapIndexedReader.Initialize({
    readable: new mcap.TempBuffer(buffer),
    decompressHandlers,
  });
  checkDataSectionCrc(buffer, indexed);
  const tally = new Tally(keep);
  for (const channel of indexed.channelsById.values()) tally.addChannel(channel);
  // readMessages checks each chunk's CRC and each message against its index entry.
  for await (const message of indexed.readMessages()) {
    const channel = indexed.channelsById.get(message.channelId);
    tally.add(message, channel, indexed.schemasById.get(channel.schemaId));
  }
  return { indexed, tally };
}

// Messages that the data section holds but the chunk indexes do not lead to are invisible to an
// indexed reader: a writer fault worth failing on. An unchunked file has no chunk index at all;
// its messages are then counted from the data section.
function checkIndexCoversData(indexed, fromIndex, fromData) {
  if (indexed.chunkIndexes.length === 0) return fromData;
  for (const [topic, count] of Object.entries(fromData.counts)) {
    const reached = fromIndex.counts[topic] ?? 0;
    if (reached !== count) {
      throw new Error(`${topic}: ${count} messages in the data section, ${reached} through the index`);
    }
  }
  return fromIndex;
}

async function main() {
  const { file, messages: keep } = parseArgs(process.argv.slice(2));
  let buffer;
  try {
    buffer = readFileSync(file);
  } catch (error) {
    fail(`cannot read ${file}: ${error.message}`);
  }
  if (!startsWithMagic(buffer)) fail(`${file} is not an MCAP file (no MCAP magic at its start)`);

  const complete = hasFooter(buffer);
  const pass = streamPass(buffer, keep, complete);

  // A finished file without a summary (summary_start 0) is valid: it is read as streamed.
  let result;
  if (pass.done && pass.footer.summaryStart !== 0n) {
    const { indexed, tally: fromIndex } = await indexedPass(buffer, keep);
    const tally = checkIndexCoversData(indexed, fromIndex, pass.tally);
    result = {
      header: { profile: indexed.header.profile, library: indexed.header.library },
      summary: {
        statistics: statisticsJson(indexed.statistics),
        chunk_indexes: indexed.chunkIndexes.length,
        metadata_indexes: indexed.metadataIndexes.length,
      },
      channels: Array.from(indexed.channelsById.values(), (c) => channelJson(c, indexed.schemasById)),
      counts: tally.counts,
      messages: tally.messages,
    };
  } else {
    result = {
      // A crash right after the magic leaves no Header.
      header: pass.header ? { profile: pass.header.profile, library: pass.header.library } : null,
      summary: null,
      channels: Array.from(pass.channelsById.values(), (c) => channelJson(c, pass.schemasById)),
      counts: pass.tally.counts,
      messages: pass.tally.messages,
    };
  }
  result.channels.sort((a, b) => a.id - b.id);
  result.metadata = pass.metadata;
  result.truncated = !pass.done;
  result.complete_chunks = pass.chunks;
  process.stdout.write(`${JSON.stringify(result)}\n`);
}

main().catch((error) => fail(error.message));
