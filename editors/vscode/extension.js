// Starts `awl lsp` for STL files and connects VS Code to it.
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
    { documentSelector: [{ scheme: "file", language: "stl" }] },
  );
  context.subscriptions.push(client);
  return client.start();
}

function deactivate() {
  return client ? client.stop() : undefined;
}

module.exports = { activate, deactivate };
