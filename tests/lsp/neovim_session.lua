-- Driven by tests/lsp/neovim_test.py inside `nvim --headless`: asks `sandpaper lsp` what a user's
-- editor would (hover, go to definition, completion, diagnostics) through Neovim's own LSP client,
-- and writes what came back to $SANDPAPER_NVIM_OUT as JSON. Neovim 0.7 API only.
local out = { filetype = vim.bo.filetype }
local buf = vim.api.nvim_get_current_buf()

local function finish()
  vim.fn.writefile({ vim.fn.json_encode(out) }, os.getenv("SANDPAPER_NVIM_OUT"))
  vim.cmd("qall!")
end

local function client()
  for _, c in pairs(vim.lsp.buf_get_clients(buf)) do return c end
end

local function at(row, needle)  -- cursor on `needle` in line `row` (1-based), as a user puts it there
  local line = vim.api.nvim_buf_get_lines(buf, row - 1, row, false)[1]
  local col = line:find(needle, 1, true)
  vim.api.nvim_win_set_cursor(0, { row, col - 1 })
  return vim.lsp.util.make_position_params()
end

local function request(method, params)
  local answers = vim.lsp.buf_request_sync(buf, method, params, 15000)
  if not answers then return nil end
  for _, a in pairs(answers) do return a.result end
end

out.attached = vim.wait(20000, function()
  local c = client()
  return c ~= nil and c.initialized == true
end, 20)
if not out.attached then return finish() end
out.server = client().name

-- Hover on a number: explain's line for it.
local hover = request("textDocument/hover", at(4, "3.2"))
out.hover = hover and hover.contents and (hover.contents.value or hover.contents) or vim.NIL

-- Go to definition on the library name after `like`.
local def = request("textDocument/definition", at(3, "corduroy"))
if def and def[1] then def = def[1] end
out.definition = def and (def.uri or def.targetUri) or vim.NIL

-- Completion after `like cor` on a new line.
vim.api.nvim_buf_set_lines(buf, 5, 5, false, { "  like cor" })
local completion = request("textDocument/completion", (function()
  vim.api.nvim_win_set_cursor(0, { 6, 10 })
  return vim.lsp.util.make_position_params()
end)())
local labels = {}
for _, item in ipairs((completion and (completion.items or completion)) or {}) do table.insert(labels, item.label) end
out.completion = labels
vim.api.nvim_buf_set_lines(buf, 5, 6, false, {})

-- A typo in a unit: the compiler's diagnostic arrives as the text changes.
vim.api.nvim_buf_set_lines(buf, 3, 4, false, { "  grating period 3.2 mn hill 50%" })
vim.wait(15000, function()
  for _, d in ipairs(vim.diagnostic.get(buf)) do
    if d.code == "E0204" then return true end
  end
  return false
end, 20)
out.diagnostics = {}
for _, d in ipairs(vim.diagnostic.get(buf)) do
  table.insert(out.diagnostics, { lnum = d.lnum, col = d.col, code = d.code, message = d.message, severity = d.severity })
end
finish()
