// The plcrun extension: starts `plcrun lsp` for IEC 61131-3 files and adds
// two commands that run plcrun in a terminal ("Run with plcrun",
// "Compare with another program").
import * as path from "path";
import * as vscode from "vscode";
import {
  LanguageClient,
  LanguageClientOptions,
  ServerOptions,
} from "vscode-languageclient/node";

const LANGUAGES = ["iec-st", "iec-il", "iec-sfc", "s7-stl"];

let client: LanguageClient | undefined;

function executable(): string {
  return vscode.workspace.getConfiguration("plcrun").get<string>("path") || "plcrun";
}

function cycles(): number {
  return vscode.workspace.getConfiguration("plcrun").get<number>("run.cycles") ?? 100;
}

async function startClient(context: vscode.ExtensionContext): Promise<void> {
  const server: ServerOptions = { command: executable(), args: ["lsp"] };
  const options: LanguageClientOptions = {
    documentSelector: LANGUAGES.map((language) => ({ scheme: "file", language })),
    synchronize: {
      fileEvents: vscode.workspace.createFileSystemWatcher("**/{plcrun.toml,*.plcproj}"),
    },
  };
  client = new LanguageClient("plcrun", "plcrun", server, options);
  context.subscriptions.push(client);
  try {
    await client.start();
  } catch (e) {
    vscode.window.showErrorMessage(
      `plcrun: cannot start \`${executable()} lsp\` (${e}). Set "plcrun.path" to the plcrun executable.`,
    );
  }
}

/// Quotes an argument for the terminal's shell.
function quote(arg: string): string {
  return /^[A-Za-z0-9_./:=-]+$/.test(arg) ? arg : `'${arg.replace(/'/g, "'\\''")}'`;
}

function runInTerminal(args: string[], cwd: string | undefined): void {
  const terminal = vscode.window.createTerminal({ name: "plcrun", cwd });
  terminal.show();
  terminal.sendText([executable(), ...args].map(quote).join(" "));
}

function activeFile(): vscode.Uri | undefined {
  const uri = vscode.window.activeTextEditor?.document.uri;
  if (!uri || uri.scheme !== "file") {
    vscode.window.showWarningMessage("plcrun: open a source file first.");
    return undefined;
  }
  return uri;
}

async function run(): Promise<void> {
  const file = activeFile();
  if (!file) {
    return;
  }
  await vscode.window.activeTextEditor?.document.save();
  runInTerminal([file.fsPath, "--cycles", String(cycles())], path.dirname(file.fsPath));
}

async function compare(): Promise<void> {
  const file = activeFile();
  if (!file) {
    return;
  }
  const other = await vscode.window.showOpenDialog({
    canSelectMany: false,
    openLabel: "Compare with",
    defaultUri: vscode.Uri.file(path.dirname(file.fsPath)),
  });
  if (!other || other.length === 0) {
    return;
  }
  runInTerminal(
    ["compare", file.fsPath, "--", other[0].fsPath, "--cycles", String(cycles()), "--random", "1"],
    path.dirname(file.fsPath),
  );
}

export async function activate(context: vscode.ExtensionContext): Promise<void> {
  context.subscriptions.push(
    vscode.commands.registerCommand("plcrun.run", run),
    vscode.commands.registerCommand("plcrun.compare", compare),
    vscode.commands.registerCommand("plcrun.restartServer", async () => {
      await client?.stop();
      await startClient(context);
    }),
  );
  await startClient(context);
}

export async function deactivate(): Promise<void> {
  await client?.stop();
}
