// Sandpaper for VS Code: colouring comes from the grammar (package.json); this starts the language
// server, `sandpaper lsp`, for diagnostics as you type, completion, hover and go to definition
// (docs/EDITORS.md). It needs vscode-languageclient: `npm ci` in this folder. Without it the
// extension still colours, and says once how to get the rest.
'use strict';
const vscode = require('vscode');

let client;

// The server's command line from the settings: `sandpaper.path` (default: `sandpaper` on PATH) and
// `sandpaper.serverArgs` (for example ["--device", "sandpaper-1995"]).
function serverCommand(config) {
  const command = config.get('path') || 'sandpaper';
  const extra = config.get('serverArgs') || [];
  return { command, args: ['lsp', ...extra] };
}

function activate(context) {
  let lc;
  try {
    lc = require('vscode-languageclient/node');
  } catch (e) {
    vscode.window.showWarningMessage(
      'Sandpaper: run `npm ci` in the extension folder for diagnostics, completion and hover (docs/EDITORS.md).');
    return undefined;
  }
  const { command, args } = serverCommand(vscode.workspace.getConfiguration('sandpaper'));
  const server = { command, args, transport: lc.TransportKind.stdio };
  client = new lc.LanguageClient('sandpaper', 'Sandpaper', { run: server, debug: server }, {
    documentSelector: [{ scheme: 'file', language: 'sandpaper' }, { scheme: 'untitled', language: 'sandpaper' }],
  });
  context.subscriptions.push({ dispose: () => (client ? client.stop() : undefined) });
  return client.start();
}

function deactivate() {
  return client ? client.stop() : undefined;
}

module.exports = { activate, deactivate, serverCommand };
