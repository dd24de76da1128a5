// The VS Code extension (editors/vscode/extension.js) with VS Code and vscode-languageclient stubbed:
// without the client library it warns once and still loads (the grammar keeps colouring); with it,
// it starts the server command the settings give, and that command line, run for real, is a
// language server that answers `initialize`. Usage: node vscode_extension_test.js EXTENSION_DIR SANDPAPER
'use strict';
const assert = require('assert');
const Module = require('module');
const path = require('path');
const { spawn } = require('child_process');

const [extensionDir, sandpaper] = process.argv.slice(2);
const manifest = require(path.join(extensionDir, 'package.json'));

let settings = {};
let warnings = [];
let created = [];
let clientInstalled = true;

// Starts the server as the client would (stdio), sends initialize, then shutdown and exit.
function runServer(run) {
  return new Promise((resolve, reject) => {
    const child = spawn(run.command, run.args, { stdio: ['pipe', 'pipe', 'inherit'] });
    let buffer = Buffer.alloc(0);
    let answer = null;
    const send = (m) => {
      const body = Buffer.from(JSON.stringify(m));
      child.stdin.write(`Content-Length: ${body.length}\r\n\r\n`);
      child.stdin.write(body);
    };
    child.stdout.on('data', (chunk) => {
      buffer = Buffer.concat([buffer, chunk]);
      const end = buffer.indexOf('\r\n\r\n');
      if (end < 0 || answer) return;
      const length = Number(/Content-Length: (\d+)/i.exec(buffer.subarray(0, end).toString())[1]);
      if (buffer.length < end + 4 + length) return;
      answer = JSON.parse(buffer.subarray(end + 4, end + 4 + length).toString());
      send({ jsonrpc: '2.0', id: 2, method: 'shutdown' });
      send({ jsonrpc: '2.0', method: 'exit' });
      child.stdin.end();
    });
    child.on('error', reject);
    child.on('exit', (code) => (answer ? resolve({ answer, code }) : reject(new Error(`server exited ${code} without answering`))));
    send({ jsonrpc: '2.0', id: 1, method: 'initialize', params: { processId: process.pid, capabilities: {} } });
  });
}

class LanguageClient {
  constructor(id, name, serverOptions, clientOptions) {
    created.push({ id, name, serverOptions, clientOptions });
    this.serverOptions = serverOptions;
  }
  start() { return runServer(this.serverOptions.run); }
  stop() { return Promise.resolve(); }
}

const stubs = {
  vscode: {
    window: { showWarningMessage: (m) => warnings.push(m) },
    workspace: { getConfiguration: (section) => ({ get: (key) => (section === 'sandpaper' ? settings[key] : undefined) }) },
  },
  'vscode-languageclient/node': { TransportKind: { stdio: 0 }, LanguageClient },
};
const load = Module._load;
Module._load = function (request, parent, isMain) {
  if (request === 'vscode-languageclient/node' && !clientInstalled) {
    const e = new Error(`Cannot find module '${request}'`);
    e.code = 'MODULE_NOT_FOUND';
    throw e;
  }
  if (request in stubs) return stubs[request];
  return load.call(this, request, parent, isMain);
};

function freshExtension() {
  const file = path.join(extensionDir, manifest.main);
  delete require.cache[require.resolve(file)];
  return require(file);
}

(async () => {
  const language = manifest.contributes.languages[0].id;
  assert.deepStrictEqual(manifest.activationEvents, [`onLanguage:${language}`]);

  clientInstalled = false;
  const context = { subscriptions: [] };
  assert.strictEqual(freshExtension().activate(context), undefined);
  assert.strictEqual(warnings.length, 1);
  assert.match(warnings[0], /npm ci/);
  assert.strictEqual(created.length, 0);

  clientInstalled = true;
  settings = { path: sandpaper, serverArgs: ['--device', 'sim'] };
  const { answer, code } = await freshExtension().activate(context);
  assert.strictEqual(created.length, 1);
  const run = created[0].serverOptions.run;
  assert.strictEqual(run.command, sandpaper);
  assert.deepStrictEqual(run.args, ['lsp', '--device', 'sim']);
  assert.ok(created[0].clientOptions.documentSelector.some((s) => s.language === language && s.scheme === 'file'));
  assert.strictEqual(answer.id, 1);
  assert.strictEqual(answer.result.capabilities.hoverProvider, true);
  assert.strictEqual(answer.result.capabilities.definitionProvider, true);
  assert.strictEqual(code, 0, 'the server exits 0 after shutdown and exit');
  assert.strictEqual(context.subscriptions.length, 1);

  settings = {};  // the default: `sandpaper` from PATH
  assert.deepStrictEqual(freshExtension().serverCommand(stubs.vscode.workspace.getConfiguration('sandpaper')),
                         { command: 'sandpaper', args: ['lsp'] });
  console.log(`vscode extension: ok (server ${run.command} ${run.args.join(' ')} answered initialize, exit ${code})`);
})().catch((e) => {
  console.error(e);
  process.exit(1);
});
