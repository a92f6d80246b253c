// Starts `awl lsp` for STL files and connects VS Code to it, and runs `awl dap` for the
// debugger type `awl`.
const vscode = require("vscode");
const { LanguageClient } = require("vscode-languageclient/node");

let client;

function activate(context) {
  const command = vscode.workspace.getConfiguration("awl").get("path", "awl");
  const server = { command, args: ["lsp"] };
  client = new LanguageClient(
    "awl",
    "awl",
    { run: server, debug: server },
    {
      documentSelector: [{ scheme: "file", language: "stl" }],
      // The server takes `cpu` and `symbols` at the start and again whenever they change.
      initializationOptions: serverSettings(),
      synchronize: { configurationSection: "awl" },
    },
  );
  context.subscriptions.push(client);
  context.subscriptions.push(
    vscode.debug.registerDebugAdapterDescriptorFactory("awl", {
      createDebugAdapterDescriptor() {
        return new vscode.DebugAdapterExecutable(command, ["dap"]);
      },
    }),
  );
  return client.start();
}

function serverSettings() {
  const settings = vscode.workspace.getConfiguration("awl");
  return { cpu: settings.get("cpu"), symbols: settings.get("symbols", []) };
}

function deactivate() {
  return client ? client.stop() : undefined;
}

module.exports = { activate, deactivate };
