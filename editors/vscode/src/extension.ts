// The plcrun extension: starts `plcrun lsp` for IEC 61131-3 files, adds
// two commands that run plcrun in a terminal ("Run with plcrun",
// "Compare with another program"), and runs `plcrun debug` as the debug
// adapter of "plcrun" launch configurations, with commands for its custom
// requests (a cycle step, forcing).
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
  const live = vscode.workspace.getConfiguration("plcrun").get<string>("liveValues");
  const options: LanguageClientOptions = {
    documentSelector: LANGUAGES.map((language) => ({ scheme: "file", language })),
    // `plcrun lsp`'s live values (docs/editors.md, "Live values").
    initializationOptions: live ? { live } : undefined,
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

// The debug session of plcrun running now, if any.
function debugSession(): vscode.DebugSession | undefined {
  const session = vscode.debug.activeDebugSession;
  return session?.type === "plcrun" ? session : undefined;
}

async function cycleStep(): Promise<void> {
  await debugSession()?.customRequest("cycleStep", { threadId: 1 });
}

async function force(release: boolean): Promise<void> {
  const session = debugSession();
  if (!session) {
    return;
  }
  const name = await vscode.window.showInputBox({ prompt: "Variable (e.g. Main.motor.run)" });
  if (!name) {
    return;
  }
  if (release) {
    await session.customRequest("unforce", { name });
    return;
  }
  const value = await vscode.window.showInputBox({ prompt: `Force ${name} to (IEC literal)` });
  if (value !== undefined) {
    await session.customRequest("force", { name, value });
  }
}

export async function activate(context: vscode.ExtensionContext): Promise<void> {
  context.subscriptions.push(
    vscode.debug.registerDebugAdapterDescriptorFactory("plcrun", {
      createDebugAdapterDescriptor: () => new vscode.DebugAdapterExecutable(executable(), ["debug"]),
    }),
    vscode.commands.registerCommand("plcrun.cycleStep", cycleStep),
    vscode.commands.registerCommand("plcrun.force", () => force(false)),
    vscode.commands.registerCommand("plcrun.unforce", () => force(true)),
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
