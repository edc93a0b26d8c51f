// Drives a browser on code-server (VS Code in the browser) with the plcrun
// extension installed and takes the screenshots of docs/editors.md. Started
// by scripts/vscode_screenshots, which installs code-server and
// playwright-core, starts code-server, the live plcrun and Xvfb, and sets
// these variables:
//   URL      code-server's address, with ?folder= the workspace
//   WS       the workspace folder (a copy of programs/ files)
//   OUT      where the PNG files go
//   LIVE     the web monitor of the running plcrun (HOST:PORT), for the
//            live values
//   CHROMIUM the browser executable (Debian's chromium)
//   FAILED   where the page is saved when a step fails
// Each screenshot is the browser's page, 1280x800, as a person sees it.
const fs = require("fs");
const path = require("path");
const { chromium } = require("playwright-core");

const URL = process.env.URL;
const WS = process.env.WS;
const OUT = process.env.OUT;
const LIVE = process.env.LIVE;
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));
let page;

const QUICK_INPUT = '.quick-input-widget:not([style*="display: none"]) input';

// Runs a command of the command palette by its title: the row whose label
// is exactly the title is clicked (the palette puts recently used commands
// first, so the first row may be another one).
async function command(title) {
  await page.keyboard.press("F1");
  await page.waitForSelector(QUICK_INPUT);
  await page.keyboard.type(title);
  await pick(title);
  await sleep(700);
}

// Clicks the row of the open quick pick whose label is exactly `label`.
async function pick(label) {
  const row = page
    .locator(".quick-input-list .monaco-list-row")
    .filter({ has: page.locator(".label-name", { hasText: new RegExp(`^${escape(label)}$`) }) })
    .first();
  await row.waitFor({ timeout: 10000 });
  await row.click();
  await page.mouse.move(200, 640); // off the title bar and breadcrumbs, whose tooltips would show
}

// Hides the panel (Problems, Output, Debug Console...) if it shows.
async function hidePanel() {
  if (await page.locator(".part.panel").isVisible()) await command("View: Toggle Panel Visibility");
}

function escape(text) {
  return text.replace(/[.*+?^${}()|[\]\\]/g, "\\$&");
}

async function openFile(name) {
  await page.keyboard.press("Control+P");
  await page.waitForSelector(QUICK_INPUT);
  await page.keyboard.type(name);
  await pick(name);
  await page.waitForSelector(`.tab[data-resource-name="${name}"]`, { timeout: 10000 });
  await sleep(1500);
}

// Moves the cursor to "LINE" or "LINE:COLUMN" (Go to Line).
async function gotoLine(position) {
  await page.keyboard.press("Control+G");
  await page.waitForSelector(QUICK_INPUT);
  await page.keyboard.type(position);
  await page.keyboard.press("Enter");
  await sleep(500);
}

async function shot(name) {
  const file = path.join(OUT, `${name}.png`);
  await page.screenshot({ path: file });
  console.log(`wrote ${file}`);
}

// 1. A typo underlined, plcrun's diagnostic in the Problems panel, and a
//    hover on a variable.
async function diagnostics() {
  await openFile("cmd_monitor.st");
  await gotoLine("73:14"); // CMD := MON.CMD ;  ->  MON.CDM
  for (let i = 0; i < 3; i++) await page.keyboard.press("Delete");
  await page.keyboard.type("CDM");
  await page.waitForSelector(".squiggly-error", { timeout: 30000 });
  await command("View: Focus Problems (Errors, Warnings, Infos)");
  for (let i = 0; i < 4; i++) await command("Decrease Current View Size");
  await gotoLine("71:50"); // the T_CMD_MAX after `T_CMD_MAX :=`
  await page.keyboard.press("Control+K");
  await page.keyboard.press("Control+I"); // Show or Focus Hover
  await page.waitForSelector(".monaco-hover:not(.hidden)", { timeout: 15000 });
  await sleep(1000);
  await shot("vscode-diagnostics");
  await page.keyboard.press("Escape");
  await command("File: Revert File");
}

// 2. Completion after `MON.`: the members of a CMD_MONITOR instance.
async function completion() {
  await gotoLine("74");
  await page.keyboard.press("End");
  await page.keyboard.press("Enter");
  await page.keyboard.type("MON.");
  await page.waitForSelector(".suggest-widget.visible", { timeout: 15000 });
  await sleep(1500);
  await shot("vscode-completion");
  await page.keyboard.press("Escape");
  await command("File: Revert File");
  await command("View: Close All Editors");
  await hidePanel();
}

// 3. CHARIOT under the debugger, stopped on a breakpoint on the action
//    association `KMAV(N, fcB) ;` of step AV.
async function debug() {
  await openFile("chariot.sfc");
  await gotoLine("23");
  await command("Debug: Toggle Breakpoint");
  await command("Debug: Select and Start Debugging");
  await page.keyboard.type("CHARIOT");
  await pick("CHARIOT"); // the configuration of .vscode/launch.json
  await page.waitForSelector(".debug-top-stack-frame-line", { timeout: 60000 });
  await sleep(2000);
  // Fold the Watch view (empty) to give the variables its room, unfold
  // the second scope (Inputs/Outputs) and the active step AV.
  const watch = page.locator('.pane-header:has(h3.title:text-is("Watch"))');
  if ((await watch.getAttribute("aria-expanded")) === "true") await watch.click();
  await sleep(500);
  const box = await watch.boundingBox(); // drag the sash above it down
  await page.mouse.move(box.x + 100, box.y - 1);
  await page.mouse.down();
  await page.mouse.move(box.x + 100, box.y + 120, { steps: 10 });
  await page.mouse.up();
  const scope = page.locator('.debug-variables .monaco-list-row[aria-level="1"]').nth(1);
  if ((await scope.getAttribute("aria-expanded")) === "false") await scope.click();
  await sleep(500);
  const step = page.locator(".debug-variables .monaco-list-row").filter({ hasText: /^\s*AV\s*=\s*STEP\s*$/ });
  await step.first().click();
  await hidePanel();
  await page.mouse.move(200, 700);
  await sleep(1500);
  await shot("vscode-debug");
  await command("Debug: Stop");
  await sleep(1000);
  await command("Remove All Breakpoints");
  await command("View: Close All Editors");
  await command("View: Show Explorer");
}

// 4. The values of a running plcrun (programs/oop_machine.st in real time,
//    its web monitor at LIVE) as inlay hints.
async function live() {
  fs.mkdirSync(path.join(WS, ".vscode"), { recursive: true });
  fs.writeFileSync(
    path.join(WS, ".vscode", "settings.json"),
    JSON.stringify({ "plcrun.liveValues": LIVE }, null, 2) + "\n",
  );
  await sleep(1500);
  await command("plcrun: Restart the language server");
  await sleep(2000);
  await openFile("oop_machine.st");
  await gotoLine("112");
  await sleep(4000);
  await shot("vscode-live-values");
}

(async () => {
  const browser = await chromium.launch({
    executablePath: process.env.CHROMIUM || "/usr/bin/chromium",
    headless: false, // a real window, on Xvfb's display
    args: [
      "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
      "--disable-background-networking", "--disable-component-update", "--disable-sync",
      "--window-size=1280,800",
    ],
  });
  const context = await browser.newContext({ viewport: { width: 1280, height: 800 } });
  page = await context.newPage();
  await page.goto(URL);
  await page.waitForSelector(".monaco-workbench .explorer-folders-view", { timeout: 60000 });
  await sleep(4000);
  const steps = { diagnostics, completion, debug, live };
  const only = process.argv.slice(2);
  for (const [name, step] of Object.entries(steps)) {
    if (only.length === 0 || only.includes(name)) {
      const start = Date.now();
      await step();
      console.log(`${name}: ${((Date.now() - start) / 1000).toFixed(1)} s`);
    }
  }
  await browser.close();
})().catch(async (e) => {
  console.error(e);
  if (page) {
    await page.screenshot({ path: process.env.FAILED }).catch(() => {});
    console.error(`the page at the failure: ${process.env.FAILED}`);
  }
  process.exit(1);
});
