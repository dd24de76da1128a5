-- Driven by tests/lsp/neovim_keys_test.py inside `nvim --headless`: presses the keys a user presses
-- on a material (C-x C-o in insert mode, K, gd) and writes what each did to $SANDPAPER_NVIM_OUT as
-- JSON. Keys go in with nvim_input, the way typed keys do, and each step is polled from a timer, so
-- Neovim's main loop handles the keys and the server's answers as it does for a user (a blocking
-- vim.wait would hold insert mode and the completion menu off). Neovim 0.7 API only.
local out = {}
local buf = vim.api.nvim_get_current_buf()
local deadline_ms = 15000  -- a step that has not happened by then will not: record and go on

local function finish()
  vim.fn.writefile({ vim.fn.json_encode(out) }, os.getenv("SANDPAPER_NVIM_OUT"))
  vim.cmd("qall!")
end

local function client()
  for _, c in pairs(vim.lsp.buf_get_clients(buf)) do return c end
end

local function float_text()  -- the text of the first floating window, or nil
  for _, w in ipairs(vim.api.nvim_list_wins()) do
    if vim.api.nvim_win_get_config(w).relative ~= "" then
      return table.concat(vim.api.nvim_buf_get_lines(vim.api.nvim_win_get_buf(w), 0, -1, false), "\n")
    end
  end
end

local steps = {
  { -- The server has started and attached; what the set-up left on the buffer.
    done = function()
      local c = client()
      return c ~= nil and c.initialized == true
    end,
    record = function(ok)
      out.attached = ok
      out.omnifunc = vim.bo[buf].omnifunc
    end,
  },
  { -- Completion: a new line `like cor`, then C-x C-o (the omnifunc) in insert mode.
    keys = "GO  like cor<C-x><C-o>",
    done = function() return #vim.fn.complete_info({ "items" }).items > 0 end,
    record = function(ok)
      out.completion = {}
      for _, item in ipairs(vim.fn.complete_info({ "items" }).items) do table.insert(out.completion, item.word) end
      out.completion_mode = vim.api.nvim_get_mode().mode
    end,
  },
  { -- Leave the menu and take the line back out (hover needs a document that compiles), then K on 3.2.
    keys = "<C-e><Esc>dd4G0f3K",
    done = function() return float_text() ~= nil end,
    record = function() out.hover = float_text() or vim.NIL end,
  },
  { -- gd on `corduroy` after `like` (moving there closes the hover window).
    keys = "3G0fcgd",
    done = function() return vim.api.nvim_buf_get_name(0) ~= vim.api.nvim_buf_get_name(buf) end,
    record = function()
      out.definition_file = vim.api.nvim_buf_get_name(0)
      out.definition_cursor = vim.api.nvim_win_get_cursor(0)
    end,
  },
}

local function run(i)
  if i > #steps then return finish() end
  local step = steps[i]
  if step.keys then vim.api.nvim_input(step.keys) end
  local deadline = vim.loop.now() + deadline_ms
  local function poll()
    local ok = step.done()
    if ok or vim.loop.now() > deadline then
      step.record(ok)
      return run(i + 1)
    end
    vim.defer_fn(poll, 20)
  end
  vim.defer_fn(poll, 20)
end

run(1)
