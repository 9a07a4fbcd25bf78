// The cncc language server for documents of the `gcode` language (registered in package.json).
// The dialect is not set here: cncc detects it per file (docs/editors.md, "Which dialect").
const vscode = require("vscode");
const { LanguageClient } = require("vscode-languageclient/node");

let client;

function activate(context) {
  const config = vscode.workspace.getConfiguration("cncc");
  const command = config.get("server.path", "cncc");
  const args = config.get("server.args", ["lsp"]);
  client = new LanguageClient(
    "cncc",
    "cncc",
    { command, args },
    {
      documentSelector: [{ scheme: "file", language: "gcode" }, { scheme: "untitled", language: "gcode" }],
      synchronize: { fileEvents: vscode.workspace.createFileSystemWatcher("**/cncc.toml") },
    },
  );
  context.subscriptions.push(client);
  return client.start();
}

function deactivate() {
  return client ? client.stop() : undefined;
}

module.exports = { activate, deactivate };
