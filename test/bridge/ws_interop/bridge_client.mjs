// A client of a running `teleop bridge` built on the Foxglove WebSocket client library
// (@foxglove/ws-protocol, the one Foxglove itself uses) over the `ws` package: it lists the
// channels, checks each one's schema parses as ROS 2 .msg (@foxglove/rosmsg), subscribes to one
// topic and decodes every live message with the schema the bridge embedded
// (@foxglove/rosmsg2-serialization). With --scene, the computed scene/transforms channel
// (foxglove.FrameTransforms, JSON) must carry the follower's frames too. With --stall, a second
// client first subscribes to every channel and then stops reading its socket; the script says
// "stalled client subscribed" and waits for SIGUSR1 (the test sends it once the bridge reports the
// stalled client's drops), then measures the first one: the bridge must keep serving it.
//   TELEOP_NPM_DIR=build/npm node bridge_client.mjs ws://127.0.0.1:PORT --topic T --source NODE
//     [--seconds S] [--max-rate HZ] [--stall] [--scene] [--wait S]
// Prints one JSON line; exits 1 with the reason when anything does not hold.
import { createRequire } from "node:module";
import { join } from "node:path";
import { performance } from "node:perf_hooks";

const require = createRequire(join(process.env.TELEOP_NPM_DIR ?? ".", "node_modules"));
const { FoxgloveClient } = require("@foxglove/ws-protocol");
const { WebSocket } = require("ws");
const { parse } = require("@foxglove/rosmsg");
const { MessageReader } = require("@foxglove/rosmsg2-serialization");

const [url, ...rest] = process.argv.slice(2);
const option = (name, fallback) => {
  const at = rest.indexOf(name);
  return at < 0 ? fallback : rest[at + 1];
};
const topic = option("--topic", "teleop/follower/joint_state");
const source = option("--source", "follower");
const seconds = Number(option("--seconds", "3"));
const maxRate = Number(option("--max-rate", "0"));
const waitSeconds = Number(option("--wait", "20"));
const stall = rest.includes("--stall");
const scene = rest.includes("--scene");

function fail(reason) {
  console.error(`bridge_client: ${url}: ${reason}`);
  process.exit(1);
}
const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));
// (a stalled client may take its while to fill the socket's buffers: the test waits for the bridge)
setTimeout(() => fail("timed out"), (waitSeconds + seconds + 20 + (stall ? 180 : 0)) * 1000).unref();

// every channel as the protocol and teleop's recordings agree: CDR with a ros2msg schema that parses;
// or one the bridge computes: JSON of a Foxglove schema
function checkChannel(channel) {
  if (channel.encoding === "json") {
    if (channel.schemaEncoding !== "jsonschema" || !channel.schemaName.startsWith("foxglove.")) {
      fail(`${channel.topic}: json with schema ${channel.schemaName} (${channel.schemaEncoding})`);
    }
    JSON.parse(channel.schema);
    return undefined;
  }
  if (channel.encoding !== "cdr") fail(`${channel.topic}: encoding ${channel.encoding}`);
  if (channel.schemaEncoding !== "ros2msg") fail(`${channel.topic}: schema encoding ${channel.schemaEncoding}`);
  if (!channel.schemaName.startsWith("teleop_msgs/msg/")) fail(`${channel.topic}: schema name ${channel.schemaName}`);
  try {
    return new MessageReader(parse(channel.schema, { ros2: true }));
  } catch (e) {
    return fail(`${channel.topic}: schema does not parse: ${e.message}`);
  }
}

// a JointState as the follower writes it: its own name, an arm, joints with finite values, in order
function checkJointState(decoded, previousSeq) {
  if (decoded.header.source !== source) fail(`header.source ${decoded.header.source}, expected ${source}`);
  if (typeof decoded.robot !== "string" || decoded.robot === "") fail(`robot '${decoded.robot}'`);
  const q = Array.from(decoded.q_rad);
  if (q.length < 1 || q.length > 32 || !q.every(Number.isFinite)) fail(`q_rad ${JSON.stringify(q)}`);
  if (decoded.dq_radps.length !== q.length) fail(`dq_radps has ${decoded.dq_radps.length} joints, q_rad ${q.length}`);
  const seq = BigInt(decoded.header.seq);
  if (previousSeq !== undefined && seq <= previousSeq) fail(`header.seq ${seq} after ${previousSeq}`);
  return seq;
}

// the client that stops reading: subscribes to everything at full speed, then pauses its socket
// (ws's underlying net.Socket: no public API pauses the reading of a WebSocket)
async function startStalledClient() {
  const ws = new WebSocket(url, [FoxgloveClient.SUPPORTED_SUBPROTOCOL]);
  const channels = await new Promise((resolve, reject) => {
    ws.on("error", reject);
    ws.on("message", (data, binary) => {
      if (binary) return;
      const message = JSON.parse(data.toString());
      if (message.op === "advertise" && message.channels.length > 0) resolve(message.channels);
    });
  });
  ws.send(JSON.stringify({ op: "subscribe", subscriptions: channels.map((c, i) => ({ id: i, channelId: c.id })) }));
  ws._socket.pause();
  return ws;
}

const channels = new Map();
let serverInfo;
const client = new FoxgloveClient({ ws: new WebSocket(url, [FoxgloveClient.SUPPORTED_SUBPROTOCOL]) });
client.on("error", (e) => fail(`client error: ${e?.message ?? e}`));
client.on("serverInfo", (info) => (serverInfo = info));
client.on("advertise", (list) => list.forEach((c) => channels.set(c.id, { channel: c, reader: checkChannel(c) })));

const deadline = performance.now() + waitSeconds * 1000;
const wanted = () => [...channels.values()].find((c) => c.channel.topic === topic);
while (!wanted() && performance.now() < deadline) await sleep(50);
if (!serverInfo) fail("no serverInfo");
if (serverInfo.capabilities.includes("clientPublish")) fail("clientPublish advertised: the bridge is read-only");
if (!wanted()) fail(`no channel ${topic} within ${waitSeconds} s (channels: ${[...channels.values()].map((c) => c.channel.topic)})`);

// the scene's frames: the follower's bodies, each a child of the world
async function checkScene() {
  const transforms = [...channels.values()].find((c) => c.channel.topic === "scene/transforms");
  if (!transforms || transforms.channel.schemaName !== "foxglove.FrameTransforms") fail("no scene/transforms channel");
  const id = client.subscribe(transforms.channel.id);
  const message = await new Promise((resolve) => {
    const take = (event) => {
      if (event.subscriptionId !== id) return;
      client.off("message", take);
      resolve(JSON.parse(new TextDecoder().decode(event.data)));
    };
    client.on("message", take);
  });
  client.unsubscribe(id);
  const frames = message.transforms.filter((t) => t.parent_frame_id === "world" && t.child_frame_id.startsWith("follower/"));
  if (frames.length === 0) fail(`scene/transforms without the follower's frames: ${JSON.stringify(message).slice(0, 300)}`);
  return frames.length;
}
const sceneFrames = scene ? await checkScene() : 0;

const stalled = stall ? await startStalledClient() : undefined;
if (stalled) {
  const go = new Promise((resolve) => process.once("SIGUSR1", resolve));
  console.log("stalled client subscribed");
  await go;
}

const { channel, reader } = wanted();
let received = 0;
let previousSeq;
let subscriptionId;
client.on("message", ({ subscriptionId: id, data }) => {
  if (id !== subscriptionId) return;
  const bytes = new Uint8Array(data.buffer, data.byteOffset, data.byteLength);
  previousSeq = checkJointState(reader.readMessage(bytes), previousSeq);
  ++received;
});
const start = performance.now();
subscriptionId = client.subscribe(channel.id);
await sleep(seconds * 1000);
const counted = received;
const elapsed = (performance.now() - start) / 1000;
client.unsubscribe(subscriptionId);

// each message passed the bridge's limit after the subscription reached it, which is after `start`
const allowed = maxRate > 0 ? Math.floor(maxRate * elapsed) + 2 : Infinity;
if (counted === 0) fail(`no message on ${topic} in ${elapsed.toFixed(2)} s`);
if (counted > allowed) fail(`${counted} messages in ${elapsed.toFixed(2)} s: more than --max-rate ${maxRate} allows (${allowed})`);
if (stalled) stalled.terminate();
console.log(JSON.stringify({ channels: channels.size, topic, received: counted, seconds: elapsed, allowed: String(allowed),
  stalled: stall, scene_frames: sceneFrames }));
client.close();
process.exit(0);
