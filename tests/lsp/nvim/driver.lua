-- Drives Neovim's built-in LSP client against `cncc lsp` (tests/lsp/test_neovim.py).
--
--   nvim --headless --clean -l driver.lua PLAN.json
--
-- PLAN: { recipe = "file.lua", out = "result.json", docs = { { path = ..., checks = { ... } } } }.
-- The recipe (a block of docs/editors.md) sets up the filetype and starts the client; this
-- script opens each document, waits for the client and the first diagnostics, runs the
-- checks (hover, definition, completion, inlay hints, code actions) through the client and
-- writes what it saw to `out`.  The expected values are asserted in Python.
local plan = vim.json.decode(table.concat(vim.fn.readfile(arg[1]), "\n"))
local ok_recipe, recipe_err = pcall(dofile, plan.recipe)
local out = { version = tostring(vim.version()), recipe_error = (not ok_recipe) and tostring(recipe_err) or nil,
              docs = {} }

local published = {}
vim.api.nvim_create_autocmd("DiagnosticChanged", {
  callback = function(args) published[args.buf] = (published[args.buf] or 0) + 1 end,
})

local function request(buf, method, params)
  local got = vim.lsp.buf_request_sync(buf, method, params, 20000) or {}
  for _, r in pairs(got) do
    if r.err then return nil, vim.inspect(r.err) end
    return r.result, nil
  end
  return nil, "no answer"
end

local function position_params(buf, line, col)
  return { textDocument = vim.lsp.util.make_text_document_params(buf), position = { line = line, character = col } }
end

local function hover_text(result)
  if not result or not result.contents then return nil end
  local c = result.contents
  if type(c) == "string" then return c end
  if c.value then return c.value end
  return vim.inspect(c)
end

local function run_check(buf, client, check)
  local r = { kind = check.kind }
  if check.kind == "hover" then
    local res, err = request(buf, "textDocument/hover", position_params(buf, check.line, check.col))
    r.text, r.err = hover_text(res), err
  elseif check.kind == "definition" then
    local res, err = request(buf, "textDocument/definition", position_params(buf, check.line, check.col))
    r.err = err
    r.locations = {}
    if res and res.uri then res = { res } end
    for _, loc in ipairs(res or {}) do
      local uri = loc.uri or loc.targetUri
      local range = loc.range or loc.targetSelectionRange
      table.insert(r.locations, { uri = uri, line = range.start.line })
    end
  elseif check.kind == "completion" then
    local res, err = request(buf, "textDocument/completion", position_params(buf, check.line, check.col))
    r.err = err
    r.labels = {}
    local items = res and (res.items or res) or {}
    for _, it in ipairs(items) do table.insert(r.labels, it.label) end
  elseif check.kind == "inlay" then
    local n = vim.api.nvim_buf_line_count(buf)
    local res, err = request(buf, "textDocument/inlayHint", {
      textDocument = vim.lsp.util.make_text_document_params(buf),
      range = { start = { line = 0, character = 0 }, ["end"] = { line = n, character = 0 } } })
    r.err = err
    r.hints = {}
    for _, h in ipairs(res or {}) do
      local label = type(h.label) == "string" and h.label or (h.label[1] and h.label[1].value) or ""
      table.insert(r.hints, { line = h.position.line, label = label })
    end
  elseif check.kind == "action" then
    local diags = {}
    for _, d in ipairs(vim.diagnostic.get(buf)) do
      if d.code == check.code and d.user_data and d.user_data.lsp then table.insert(diags, d.user_data.lsp) end
    end
    r.diagnostics = #diags
    if #diags > 0 then
      local res, err = request(buf, "textDocument/codeAction", {
        textDocument = vim.lsp.util.make_text_document_params(buf), range = diags[1].range,
        context = { diagnostics = diags } })
      r.err = err
      r.titles = {}
      for _, a in ipairs(res or {}) do
        table.insert(r.titles, a.title)
        if not r.applied and a.edit and vim.startswith(a.title, check.title) then
          vim.lsp.util.apply_workspace_edit(a.edit, client.offset_encoding or "utf-16")
          r.applied = a.title
        end
      end
      r.line_after = vim.api.nvim_buf_get_lines(buf, diags[1].range.start.line, diags[1].range.start.line + 1,
                                                false)[1]
    end
  end
  return r
end

for _, doc in ipairs(plan.docs) do
  vim.cmd.edit(vim.fn.fnameescape(doc.path))
  local buf = vim.api.nvim_get_current_buf()
  local res = { path = doc.path, filetype = vim.bo[buf].filetype, checks = {} }
  res.attached = vim.wait(30000, function() return #vim.lsp.get_clients({ bufnr = buf }) > 0 end, 20)
  local client = vim.lsp.get_clients({ bufnr = buf })[1]
  if client then
    res.client = client.name
    res.published = vim.wait(60000, function() return (published[buf] or 0) > 0 end, 20)
    res.diagnostics = {}
    for _, d in ipairs(vim.diagnostic.get(buf)) do
      table.insert(res.diagnostics, { code = d.code, line = d.lnum, message = d.message })
    end
    for _, check in ipairs(doc.checks or {}) do
      table.insert(res.checks, run_check(buf, client, check))
    end
  end
  table.insert(out.docs, res)
end

vim.fn.writefile({ vim.json.encode(out) }, plan.out)
for _, c in ipairs(vim.lsp.get_clients()) do c:stop(true) end
vim.wait(2000, function() return #vim.lsp.get_clients() == 0 end, 20)
