// vcnc for VS Code: a client that starts `vcnc lsp` for G-code documents
// (the language configuration in package.json names their extensions) and
// hands it the `vcnc.*` settings, at start and whenever they change.
// Plain JavaScript, so the folder runs as it is, without a build step.
'use strict';

const vscode = require('vscode');
const { LanguageClient, TransportKind } = require('vscode-languageclient/node');

let client;

function activate(context) {
  const config = vscode.workspace.getConfiguration('vcnc');
  const command = config.get('path') || 'vcnc';
  const serverOptions = {
    command,
    args: ['lsp'],
    transport: TransportKind.stdio,
  };
  const clientOptions = {
    documentSelector: [
      { scheme: 'file', language: 'gcode' },
      { scheme: 'untitled', language: 'gcode' },
    ],
    // didChangeConfiguration carries { vcnc: { … } } on every change.
    synchronize: { configurationSection: 'vcnc' },
    initializationOptions: { vcnc: settings(config) },
  };
  client = new LanguageClient('vcnc', 'vcnc', serverOptions, clientOptions);
  context.subscriptions.push(client);
  return client.start();
}

// The settings as a plain object (the configuration object also holds
// functions).
function settings(config) {
  const keys = ['dialect', 'machine', 'tools', 'programDir', 'blockDelete', 'optionalStop', 'inlayHints'];
  return Object.fromEntries(keys.map((k) => [k, config.get(k)]));
}

function deactivate() {
  return client ? client.stop() : undefined;
}

module.exports = { activate, deactivate };
