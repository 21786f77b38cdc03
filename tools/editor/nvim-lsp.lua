-- Neovim's built-in LSP client against `vcnc lsp`, headless: the session of
-- crates/vcnc/tests/lsp.rs under a real editor's client (Debian's neovim,
-- 0.7 and later). Run by tools/editor/nvim-check.sh, which passes the
-- program, the vcnc binary and a log file in the environment; exits 0 when
-- every step gave what it should, 1 otherwise.

local vcnc = os.getenv('VCNC_BIN')
local file = os.getenv('VCNC_PROGRAM')
local log = io.open(os.getenv('VCNC_LOG'), 'w')
local failed = false

local function say(fmt, ...)
  log:write(string.format(fmt, ...) .. '\n')
  log:flush()
end

local function check(ok, what)
  say('%s %s', ok and 'ok  ' or 'FAIL', what)
  if not ok then failed = true end
end

vim.cmd('edit ' .. file)
local buf = vim.api.nvim_get_current_buf()
local id = vim.lsp.start_client({
  name = 'vcnc',
  cmd = { vcnc, 'lsp' },
  root_dir = vim.fn.fnamemodify(file, ':h'),
  init_options = { vcnc = { dialect = 'fanuc' } },
})
check(id ~= nil, 'the client started vcnc lsp')
vim.lsp.buf_attach_client(buf, id)
local client = vim.lsp.get_client_by_id(id)
check(vim.wait(10000, function() return client.initialized end), 'initialize')

local function errors()
  return vim.diagnostic.get(buf, { severity = vim.diagnostic.severity.ERROR })
end

check(vim.wait(10000, function() return #errors() == 2 end), 'didOpen: two diagnostics')
for _, d in ipairs(errors()) do
  say('     line %d: %s', d.lnum + 1, (d.message:gsub('\n.*', '')))
end

-- Fix the arc: I3. becomes I5. on line 12 (index 11), as a person types it.
vim.api.nvim_buf_set_text(buf, 11, 12, 11, 14, { 'I5' })
check(vim.wait(10000, function() return #errors() == 1 end), 'didChange: one diagnostic remains')

local function at(line, character)
  return { textDocument = vim.lsp.util.make_text_document_params(buf),
           position = { line = line, character = character } }
end

local hover = client.request_sync('textDocument/hover', at(7, 1), 10000, buf)
local text = hover and hover.result and hover.result.contents.value or ''
check(text:find('G83', 1, true) and text:find('peck', 1, true), 'hover on G83 explains a peck cycle')
say('     %s', (text:gsub('\n.*', '')))

local def = client.request_sync('textDocument/definition', at(13, 5), 10000, buf)
local r = def and def.result
local loc = r and (r.range and r or r[1])
check(loc and loc.range.start.line == 15, 'definition of M98 P100 is O100 (line 16)')

local sym = client.request_sync('textDocument/documentSymbol',
  { textDocument = vim.lsp.util.make_text_document_params(buf) }, 10000, buf)
local found = false
local function walk(list)
  for _, s in ipairs(list or {}) do
    if s.name == 'T1' then found = true; say('     %s  %s', s.name, s.detail or '') end
    walk(s.children)
  end
end
walk(sym and sym.result)
check(found, 'document symbols list the tool change')

client.stop()
check(vim.wait(10000, function() return client.is_stopped() end), 'shutdown and exit')
log:close()
vim.cmd(failed and 'cquit 1' or 'qall!')
