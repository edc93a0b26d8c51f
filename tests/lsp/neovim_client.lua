-- Drives `plcrun lsp` from Neovim's own LSP client (tests/lsp.rs runs it
-- with `nvim --headless`). Reads PLCRUN, ROOT, FILE and OUT from the
-- environment, writes what the client got to OUT as JSON. Uses the
-- client API that Neovim 0.7 and later all have.
local env = vim.env
local result = { diagnostics = {}, hover = "", definition_line = -1 }
local client_id = vim.lsp.start_client({
  name = "plcrun",
  cmd = { env.PLCRUN, "lsp" },
  root_dir = env.ROOT,
})
vim.cmd("edit " .. env.FILE)
vim.lsp.buf_attach_client(0, client_id)
vim.wait(20000, function()
  return #vim.diagnostic.get(0) > 0
end, 50)
for _, d in ipairs(vim.diagnostic.get(0)) do
  table.insert(result.diagnostics, { line = d.lnum, col = d.col, code = d.code, message = d.message })
end
-- Hover and definition on the first use of `level` (line 8, column 0).
local params = { textDocument = { uri = vim.uri_from_bufnr(0) }, position = { line = 8, character = 1 } }
local hover = vim.lsp.buf_request_sync(0, "textDocument/hover", params, 10000) or {}
for _, answer in pairs(hover) do
  if answer.result and answer.result.contents then
    result.hover = answer.result.contents.value or ""
  end
end
local definition = vim.lsp.buf_request_sync(0, "textDocument/definition", params, 10000) or {}
for _, answer in pairs(definition) do
  local r = answer.result
  if r and r.range then
    result.definition_line = r.range.start.line
  end
end
local out = io.open(env.OUT, "w")
out:write(vim.fn.json_encode(result))
out:close()
vim.lsp.stop_client(client_id)
vim.cmd("qa!")
