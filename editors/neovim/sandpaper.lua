-- Sandpaper materials (.hmat) and workspaces (.hws) in Neovim 0.7 or later (Debian 12 ships 0.7.2):
-- the filetype and `sandpaper lsp` (diagnostics; C-x C-o completion, K hover, gd go to definition). Source it
-- from init.lua (`dofile("/path/to/editors/neovim/sandpaper.lua")`) or copy it there; docs/EDITORS.md.
-- Only calls Neovim 0.7 has: vim.lsp.start and vim.fs came in 0.8.

-- Set, not `setfiletype`: Neovim 0.7's filetype.vim calls a file with # comments `conf` first.
vim.api.nvim_create_autocmd({ "BufNewFile", "BufRead" }, {
  pattern = { "*.hmat", "*.hws" },
  command = "set filetype=sandpaper",
})

-- The keys a user expects of a language server, on each buffer it attaches to: C-x C-o completes
-- (omnifunc), K shows the hover, gd goes to the definition. Neovim 0.7 sets none of them itself and
-- has no LspAttach event (0.8), so the client's on_attach does it, for that buffer only.
local function on_attach(_, bufnr)
  vim.bo[bufnr].omnifunc = "v:lua.vim.lsp.omnifunc"
  local opts = { buffer = bufnr, silent = true }
  vim.keymap.set("n", "K", vim.lsp.buf.hover, opts)
  vim.keymap.set("n", "gd", vim.lsp.buf.definition, opts)
end

-- One server for every Sandpaper buffer of this Neovim, started with the first.
local client_id = nil
vim.api.nvim_create_autocmd("FileType", {
  pattern = "sandpaper",
  callback = function(args)
    vim.bo[args.buf].commentstring = "# %s"
    if client_id == nil or vim.lsp.get_client_by_id(client_id) == nil then
      local file = vim.api.nvim_buf_get_name(args.buf)
      client_id = vim.lsp.start_client({
        name = "sandpaper",
        cmd = { vim.g.sandpaper_command or "sandpaper", "lsp" },
        root_dir = vim.fn.fnamemodify(file ~= "" and file or ".", ":p:h"),
        on_attach = on_attach,
      })
    end
    if client_id then vim.lsp.buf_attach_client(args.buf, client_id) end
  end,
})
