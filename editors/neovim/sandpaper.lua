-- Sandpaper materials (.hmat) and workspaces (.hws) in Neovim 0.7 or later (Debian 12 ships 0.7.2):
-- the filetype and `sandpaper lsp` (diagnostics, hover, completion, go to definition). Source it
-- from init.lua (`dofile("/path/to/editors/neovim/sandpaper.lua")`) or copy it there; docs/EDITORS.md.
-- Only calls Neovim 0.7 has: vim.lsp.start and vim.fs came in 0.8.

-- Set, not `setfiletype`: Neovim 0.7's filetype.vim calls a file with # comments `conf` first.
vim.api.nvim_create_autocmd({ "BufNewFile", "BufRead" }, {
  pattern = { "*.hmat", "*.hws" },
  command = "set filetype=sandpaper",
})

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
      })
    end
    if client_id then vim.lsp.buf_attach_client(args.buf, client_id) end
  end,
})
