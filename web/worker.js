// The playground's worker: runs and debugger sessions away from the page's thread, so a long
// run never holds the page; the page ends the worker to stop a run. It is made from the
// WebAssembly glue and this script, both in the page, and gets the module the page compiled.
// Then one job at a time: { id, kind: "run" | "debug", request, commands }, answered with
// { id, progress } now and then and { id, answer } (the outcome as JSON) at the end.
"use strict";

let awl = null;

onmessage = (event) => {
  const job = event.data;
  if (job.module) {
    wasm_bindgen.initSync({ module: job.module });
    awl = wasm_bindgen;
    return;
  }
  const listener = {
    progress: (clockNs, cycle) => postMessage({ id: job.id, progress: { clockNs, cycle } }),
  };
  const answer = job.kind === "debug"
    ? awl.debug(job.request, job.commands, listener)
    : awl.run(job.request, listener);
  postMessage({ id: job.id, answer });
};
