// Reads a teleop MCAP recording with the MCAP project's own reader (@mcap/core) and decodes every
// message with the ros2msg schema embedded in the file (@foxglove/rosmsg parses it,
// @foxglove/rosmsg2-serialization reads the CDR): the independent check of teleop's writer.
//   TELEOP_NPM_DIR=build/npm node read_mcap.mjs FILE indexed|streamed [--min-messages N] [--topics N]
//     [--check-samples]   (the values write_sample_mcap puts in its JointStates and headers)
// (the packages as scripts/setup.sh installs them into TELEOP_NPM_DIR/node_modules)
// Prints one JSON line; exits 1 with the reason when anything does not read or decode.
import { open } from "node:fs/promises";
import { createRequire } from "node:module";
import { join } from "node:path";

const require = createRequire(join(process.env.TELEOP_NPM_DIR ?? ".", "node_modules"));
const { McapIndexedReader, McapStreamReader } = require("@mcap/core");
const { loadDecompressHandlers } = require("@mcap/support");
const { parse } = require("@foxglove/rosmsg");
const { MessageReader } = require("@foxglove/rosmsg2-serialization");

const [file, mode, ...rest] = process.argv.slice(2);
const option = (name) => {
  const at = rest.indexOf(name);
  return at < 0 ? 0 : Number(rest[at + 1]);
};

function fail(reason) {
  console.error(`read_mcap: ${file}: ${reason}`);
  process.exit(1);
}

// a decoder per channel, from the channel's schema as the file carries it
function decoderFor(channel, schema) {
  if (!schema) fail(`topic ${channel.topic} has no schema`);
  if (schema.encoding !== "ros2msg") fail(`topic ${channel.topic}: schema encoding ${schema.encoding}`);
  if (channel.messageEncoding !== "cdr") fail(`topic ${channel.topic}: message encoding ${channel.messageEncoding}`);
  if (!schema.name.startsWith("teleop_msgs/msg/")) fail(`topic ${channel.topic}: schema name ${schema.name}`);
  const text = new TextDecoder().decode(schema.data);
  return new MessageReader(parse(text, { ros2: true }));
}

// what write_sample_mcap wrote: the values must come back through the schema, not just parse
function checkSample(type, decoded, message) {
  const same = (a, b) => JSON.stringify(a) === JSON.stringify(b);
  if (decoded.header.source !== "write_sample_mcap") fail(`${type}: header.source ${decoded.header.source}`);
  if (message.publishTime !== BigInt(decoded.header.stamp_ns)) fail(`${type}: publish time is not the header stamp`);
  if (type === "teleop_msgs/msg/JointState" &&
      (decoded.robot !== "panda" || decoded.arm !== "right" || !same(Array.from(decoded.q_rad), [0.5, -1.25, 2]) ||
       !same(Array.from(decoded.tau_ext_nm), [0.1]))) {
    fail(`JointState decodes to ${JSON.stringify(decoded, (k, v) => (typeof v === "bigint" ? String(v) : v))}`);
  }
}

class Tally {
  constructor() {
    this.messages = 0;
    this.topics = {};
    this.decoders = new Map();
    this.lastLogTime = -1n;
  }
  add(channel, schema, message) {
    if (!this.decoders.has(channel.id)) this.decoders.set(channel.id, decoderFor(channel, schema));
    let decoded;
    try {
      decoded = this.decoders.get(channel.id).readMessage(message.data);
    } catch (e) {
      fail(`message ${this.messages} of ${channel.topic} does not decode with its schema: ${e.message}`);
    }
    if (decoded.header === undefined || typeof decoded.header.seq !== "bigint") {
      fail(`message of ${channel.topic} decodes without its header.seq: ${JSON.stringify(Object.keys(decoded))}`);
    }
    if (message.publishTime === 0n || message.logTime === 0n) fail(`message of ${channel.topic} has no times`);
    if (rest.includes("--check-samples")) checkSample(schema.name, decoded, message);
    this.messages += 1;
    this.topics[channel.topic] = (this.topics[channel.topic] ?? 0) + 1;
  }
}

async function readIndexed(handle, decompressHandlers, tally) {
  const size = BigInt((await handle.stat()).size);
  const readable = {
    size: async () => size,
    read: async (offset, length) => {
      const buffer = new Uint8Array(Number(length));
      await handle.read(buffer, 0, Number(length), Number(offset));
      return buffer;
    },
  };
  const reader = await McapIndexedReader.Initialize({ readable, decompressHandlers });
  if (reader.chunkIndexes.length === 0) fail("no chunk indexes");
  if (!reader.statistics) fail("no statistics");
  for await (const message of reader.readMessages()) {
    const channel = reader.channelsById.get(message.channelId);
    if (message.logTime < tally.lastLogTime) fail("messages out of log-time order");
    tally.lastLogTime = message.logTime;
    tally.add(channel, reader.schemasById.get(channel.schemaId), message);
  }
  if (BigInt(tally.messages) !== reader.statistics.messageCount) {
    fail(`read ${tally.messages} messages, the statistics say ${reader.statistics.messageCount}`);
  }
  return { chunks: reader.chunkIndexes.length, compression: [...new Set(reader.chunkIndexes.map((c) => c.compression))] };
}

async function readStreamed(handle, decompressHandlers, tally) {
  const reader = new McapStreamReader({ decompressHandlers, validateCrcs: true });
  reader.append(await handle.readFile());
  const schemas = new Map();
  const channels = new Map();
  for (let record; (record = reader.nextRecord()); ) {
    if (record.type === "Schema") schemas.set(record.id, record);
    else if (record.type === "Channel") channels.set(record.id, record);
    else if (record.type === "Message") {
      const channel = channels.get(record.channelId);
      tally.add(channel, schemas.get(channel.schemaId), record);
    }
  }
  return { complete: reader.done() };
}

const handle = await open(file, "r");
const decompressHandlers = await loadDecompressHandlers();
const tally = new Tally();
const details = mode === "indexed" ? await readIndexed(handle, decompressHandlers, tally)
  : await readStreamed(handle, decompressHandlers, tally);
await handle.close();
if (tally.messages < option("--min-messages")) fail(`only ${tally.messages} messages`);
if (Object.keys(tally.topics).length < option("--topics")) fail(`only the topics ${Object.keys(tally.topics)}`);
console.log(JSON.stringify({ file, mode, messages: tally.messages, topics: tally.topics, ...details }));
