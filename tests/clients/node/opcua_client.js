// The node-opcua client of tests/opcua.rs: browse to the data block's setpoint, read, write,
// subscribe, call the PLC's methods, and the refusals of an unknown node and a wrong type.
// Arguments: the port and the case (`s7`, `s5`, `read-only`).

const {
  OPCUAClient, AttributeIds, DataType, StatusCodes, TimestampsToReturn, makeBrowsePath,
} = require("node-opcua-client");

const [port, kind] = process.argv.slice(2);

function check(condition, what) {
  if (!condition) throw new Error(what);
}

async function id(session, ns, path) {
  const result = await session.translateBrowsePath(makeBrowsePath("ObjectsFolder", path));
  check(result.statusCode === StatusCodes.Good, `browse ${path}: ${result.statusCode}`);
  return result.targets[0].targetId.toString();
}

async function write(session, nodeId, dataType, value) {
  return session.write({ nodeId, attributeId: AttributeIds.Value, value: { value: { dataType, value } } });
}

async function read(session, nodeId) {
  return (await session.read({ nodeId, attributeId: AttributeIds.Value })).value.value;
}

async function changes(session, nodeId, wanted) {
  const subscription = await session.createSubscription2({
    requestedPublishingInterval: 20, publishingEnabled: true,
    requestedMaxKeepAliveCount: 20, requestedLifetimeCount: 100,
  });
  const item = await subscription.monitor({ nodeId, attributeId: AttributeIds.Value },
    { samplingInterval: 10, queueSize: 10 }, TimestampsToReturn.Both);
  const seen = [];
  await new Promise((resolve, reject) => {
    const timer = setTimeout(() => reject(new Error(`only ${seen.length} changes`)), 5000);
    item.on("changed", (value) => {
      check(value.sourceTimestamp, "a source timestamp");
      seen.push(value.value.value);
      if (seen.length >= wanted) { clearTimeout(timer); resolve(); }
    });
  });
  await subscription.terminate();
  return seen;
}

async function call(session, ns, method) {
  const result = await session.call({
    objectId: `ns=${ns};s=PLC`, methodId: `ns=${ns};s=PLC.${method}`, inputArguments: [],
  });
  return result.statusCode;
}

async function until(what, readValue, wanted) {
  const deadline = Date.now() + 5000;
  for (;;) {
    const value = await readValue();
    if (value === wanted) return;
    check(Date.now() < deadline, `${what} is ${value}, not ${wanted}`);
    await new Promise((resolve) => setTimeout(resolve, 20));
  }
}

async function step7(session, ns) {
  const setpoint = await id(session, ns, `/${ns}:PLC/${ns}:DataBlocks/${ns}:DB5/${ns}:setpoint`);
  check(setpoint === `ns=${ns};s=DB5.setpoint`, setpoint);
  check(await read(session, setpoint) === 500, "the setpoint");
  check(await write(session, setpoint, DataType.Int16, 720) === StatusCodes.Good, "the write");
  check(await read(session, `ns=${ns};s=DB5.DBW 0`) === 720, "the setpoint's word");
  const wrong = await write(session, setpoint, DataType.Double, 1.5);
  check(wrong === StatusCodes.BadTypeMismatch, `a Double into an INT: ${wrong}`);
  const unknown = await session.read({ nodeId: `ns=${ns};s=XY 1`, attributeId: AttributeIds.Value });
  check(unknown.statusCode === StatusCodes.BadNodeIdUnknown, `an unknown operand: ${unknown.statusCode}`);
  const seen = await changes(session, `ns=${ns};s=DB5.cycles`, 3);
  check(seen[2] > seen[0], `the cycles go on: ${seen}`);
  const state = () => read(session, `ns=${ns};s=PLC.State`);
  check(await call(session, ns, "Stop") === StatusCodes.Good, "the STOP");
  check(await state() === "STOP", "STOP");
  check(await call(session, ns, "ColdRestart") === StatusCodes.Good, "the cold restart");
  await until("the state", state, "RUN");
  check(await read(session, setpoint) === 500, "the cold restart loads the data again");
  return "node-opcua, STEP 7: ok";
}

async function step5(session, ns) {
  const word = await id(session, ns, `/${ns}:PLC/${ns}:DataBlocks/${ns}:DB1/${ns}:DW 0`);
  check(await read(session, word) === 500, "DB 1 DW 0");
  check(await write(session, word, DataType.UInt16, 250) === StatusCodes.Good, "the write");
  check(await read(session, `ns=${ns};s=DB 1 DW 0`) === 250, "the word by operand");
  await changes(session, `ns=${ns};s=PLC.Cycle`, 2);
  check(await call(session, ns, "Stop") === StatusCodes.Good, "the STOP");
  check(await call(session, ns, "WarmRestart") === StatusCodes.Good, "the warm restart");
  return "node-opcua, STEP 5: ok";
}

async function readOnly(session, ns) {
  const setpoint = `ns=${ns};s=DB5.setpoint`;
  check(await read(session, setpoint) === 500, "the setpoint");
  const denied = await write(session, setpoint, DataType.Int16, 1);
  check(denied === StatusCodes.BadUserAccessDenied, `a write: ${denied}`);
  const stop = await call(session, ns, "Stop");
  check(stop === StatusCodes.BadUserAccessDenied, `a STOP: ${stop}`);
  return "node-opcua, read-only: ok";
}

async function main() {
  const client = OPCUAClient.create({ endpointMustExist: false, connectionStrategy: { maxRetry: 2 } });
  await client.connect(`opc.tcp://127.0.0.1:${port}`);
  const session = await client.createSession();
  const namespaces = await session.readNamespaceArray();
  const ns = namespaces.indexOf("urn:awl:plc");
  check(ns > 0, `the namespace in ${namespaces}`);
  const cases = { s7: step7, s5: step5, "read-only": readOnly };
  console.log(await cases[kind](session, ns));
  await session.close();
  await client.disconnect();
}

main().catch((error) => { console.error(error); process.exit(1); });
