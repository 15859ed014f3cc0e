-- SPDX-License-Identifier: MIT
--- smi.doc.html: the reference as self-contained HTML pages (smi-lua doc --html DIR).
-- index.html lists the modules and searches every entry (plain JavaScript over an index
-- embedded in the page: no network, no file fetch); one page per module holds its entries
-- with options, returns, errors and the example with the output it printed when the
-- reference was made (an example that fails stops the generation).
local doc = require "smi.doc"

local M = {}

local function esc(s)
  return (tostring(s):gsub("[&<>\"]", { ["&"] = "&amp;", ["<"] = "&lt;", [">"] = "&gt;", ['"'] = "&quot;" }))
end

local function js_string(s)
  return '"' .. tostring(s):gsub('[%c"\\<>&]', function(c)
    return ("\\u%04x"):format(c:byte())
  end) .. '"'
end

-- Which page an entry lives on: the longest public stdlib module that prefixes it, else smi.<first word>.
local function page_of(name)
  local best
  for _, m in ipairs(doc.stdlib) do
    if (name == m or name:sub(1, #m + 1) == m .. "." or name:sub(1, #m + 1) == m .. ":") and (not best or #m > #best) then best = m end
  end
  if best then return best end
  local top = name:match("^(smi%.[%w_]+)") or "smi"
  -- a type's methods live on the page of the module that makes it; types are named after that
  -- module (smi.kriging:predict on smi.kriging), but for the verdicts of smi.metric
  local home = { ["smi.verdict"] = "smi.metric" }
  return home[top] or top
end

local function anchor(name) return (name:gsub("[^%w_%.%-]", "_")) end
local function file_of(page) return page .. ".html" end

local CSS = [[
body{font:15px/1.45 "Liberation Sans",Arial,sans-serif;margin:0;color:#1b1f24;background:#fff}
header{background:#1f3a5f;color:#fff;padding:10px 24px;display:flex;gap:24px;align-items:center}
header a{color:#fff;text-decoration:none;font-weight:bold}
header input{flex:1;max-width:420px;padding:5px 8px;font-size:15px;border-radius:4px;border:0}
main{max-width:1000px;margin:0 auto;padding:8px 24px 40px}
h1{font-size:24px;margin:18px 0 6px}h2{font-size:18px;margin:28px 0 6px;border-top:1px solid #d0d7de;padding-top:14px}
code,pre{font:13px/1.4 "Liberation Mono",monospace}pre{background:#f6f8fa;padding:8px 10px;overflow-x:auto;border-radius:4px}
pre.out{background:#eef6ee;border-left:3px solid #4c9a4c}
table{border-collapse:collapse;margin:6px 0}td,th{border:1px solid #d0d7de;padding:3px 8px;text-align:left;vertical-align:top}
th{background:#f0f3f6}.sig{font-weight:bold}.lbl{font-weight:bold;color:#57606a}
ul.mods{list-style:none;padding:0}ul.mods li{padding:3px 0}ul.mods a{font-family:"Liberation Mono",monospace}
#results li{padding:2px 0}#results{margin-top:8px}.muted{color:#57606a}
]]

-- Search over the embedded index: every page carries it, so the box works on any page.
local JS = [[
(function(){
  var box=document.getElementById("q"),list=document.getElementById("results");
  function show(q){
    q=q.trim().toLowerCase();list.innerHTML="";
    if(!q){list.style.display="none";return;}
    var hits=[],words=q.split(/\s+/);
    function score(e,w){var s=0,n=e.n.toLowerCase();
      if(n===w||n.endsWith("."+w)||n.endsWith(":"+w))s=100;else if(n.indexOf(w)>=0)s=50;
      if(e.o.toLowerCase().indexOf(w)>=0)s+=20;if(e.s.toLowerCase().indexOf(w)>=0)s+=10;
      if(e.t.toLowerCase().indexOf(w)>=0)s+=3;return s;}
    /* every word must appear (in any order, in any field); the entry's score adds theirs up */
    for(var i=0;i<SMI_INDEX.length;i++){var e=SMI_INDEX[i],s=0;
      for(var k=0;k<words.length;k++){var sk=score(e,words[k]);if(sk===0){s=0;break;}s+=sk;}
      if(s>0)hits.push([s,e]);}
    hits.sort(function(a,b){return b[0]-a[0]||(a[1].n<b[1].n?-1:1);});
    var h=document.createElement("p");h.className="muted";h.textContent=hits.length+" entries mention \u201c"+q+"\u201d";list.appendChild(h);
    for(var j=0;j<hits.length&&j<60;j++){var e2=hits[j][1],li=document.createElement("li"),a=document.createElement("a");
      a.href=e2.p+"#"+e2.a;a.textContent=e2.n;li.appendChild(a);li.appendChild(document.createTextNode(" \u2014 "+e2.s));list.appendChild(li);}
    list.style.display="block";
  }
  box.addEventListener("input",function(){show(box.value);});
  var m=/[?&]q=([^&#]*)/.exec(location.search);if(m){box.value=decodeURIComponent(m[1]);show(box.value);}
})();
]]

local function index_js(entries)
  local parts = {}
  for _, e in ipairs(entries) do
    local opts = {}
    for _, o in ipairs(e.options) do opts[#opts + 1] = o.name .. " " .. o.meaning end
    parts[#parts + 1] = ("{n:%s,s:%s,o:%s,t:%s,p:%s,a:%s}"):format(js_string(e.name), js_string(e.summary or ""),
      js_string(table.concat(opts, " ")), js_string((e.description or "") .. " " .. (e.returns or "")),
      js_string(file_of(page_of(e.name))), js_string(anchor(e.name)))
  end
  return "var SMI_INDEX=[" .. table.concat(parts, ",\n") .. "];"
end

local function page(title, body, index)
  return table.concat {
    "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>", esc(title),
    "</title><meta name=\"viewport\" content=\"width=device-width\"><style>", CSS, "</style></head><body>",
    "<header><a href=\"index.html\">smi-lua reference</a><input id=\"q\" type=\"search\" placeholder=\"search: bandwidth, seed, smi.kde ...\" autocomplete=\"off\"></header>",
    "<main><ul id=\"results\" style=\"display:none\"></ul>", body, "</main><script>", index, JS, "</script></body></html>\n" }
end

-- Escaped text with every name of the reference in it ("as smi.kde_bd") linked to its entry.
local function linked(text)
  local all = {}
  for _, e in ipairs(doc.list()) do all[e.name] = true end
  return (esc(text):gsub("smi[%w_%.:]*[%w_]", function(name)
    if all[name] then return ("<a href=\"%s#%s\">%s</a>"):format(file_of(page_of(name)), anchor(name), name) end
    return name
  end))
end

local function entry_html(e)
  local out = { ("<h2 id=\"%s\"><code class=\"sig\">%s</code></h2>"):format(anchor(e.name), esc(e.signature)) }
  if e.description and e.description ~= "" then
    for para in (e.description .. "\n"):gmatch("(.-)\n") do
      if para:match("%S") then out[#out + 1] = "<p>" .. linked(para) .. "</p>" end
    end
  end
  if #e.options > 0 then
    out[#out + 1] = "<table><tr><th>option</th><th>default</th><th>meaning</th></tr>"
    for _, o in ipairs(e.options) do
      out[#out + 1] = ("<tr><td><code>%s</code></td><td><code>%s</code></td><td>%s</td></tr>"):format(esc(o.name), esc(o.default), linked(o.meaning))
    end
    out[#out + 1] = "</table>"
  end
  if e.returns then out[#out + 1] = "<p><span class=\"lbl\">Returns</span> " .. linked(e.returns) .. "</p>" end
  if e.errors then out[#out + 1] = "<p><span class=\"lbl\">Errors</span> " .. linked(e.errors) .. "</p>" end
  if e.example then
    local ok, printed = doc.run_example(e)
    if not ok then error(("smi-lua doc --html: the example of %s failed: %s"):format(e.name, printed), 0) end
    out[#out + 1] = "<p class=\"lbl\">Example</p><pre>" .. esc(e.example) .. "</pre>"
    if printed ~= "" then out[#out + 1] = "<pre class=\"out\">" .. esc(printed) .. "</pre>" end
  end
  return table.concat(out, "\n")
end

local function write_file(path, text)
  local f, err = io.open(path, "w")
  if not f then error("smi-lua doc --html: " .. tostring(err), 0) end
  f:write(text)
  f:close()
end

-- The guides (docs/*.md), rendered, in dir/guides/: {{name =, title =}} in the order given.
local function write_guides(dir, guides)
  local md = require "smi.doc.markdown"
  local out = {}
  for _, g in ipairs(guides or {}) do
    local f, err = io.open(g, "rb")
    if not f then error("smi-lua doc --html: cannot read the guide " .. tostring(err), 0) end
    local text = f:read("a")
    f:close()
    local name = g:match("([^/]+)%.md$") or g
    local title = md.title(text) or name
    local body = md.render(text)
    write_file(dir .. "/guides/" .. name .. ".html", table.concat {
      "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>", esc(title),
      " — smi-lua</title><meta name=\"viewport\" content=\"width=device-width\"><style>", CSS,
      ".table-wrap{overflow-x:auto}blockquote{margin:8px 0;padding:2px 12px;border-left:3px solid #d0d7de;color:#57606a}</style></head><body>",
      "<header><a href=\"../index.html\">smi-lua reference</a></header><main>", body, "</main></body></html>\n" })
    out[#out + 1] = { name = name, title = title }
  end
  return out
end

--- Writes the reference into dir, and the guides (paths of docs/*.md) into dir/guides/;
-- returns the number of pages and of examples run.
function M.write(dir, guides)
  local entries = doc.list()
  local index = index_js(entries)
  local pages, names = {}, {}
  for _, e in ipairs(entries) do
    local p = page_of(e.name)
    if not pages[p] then pages[p] = {}; names[#names + 1] = p end
    table.insert(pages[p], e)
  end
  table.sort(names)
  local examples = 0
  for _, p in ipairs(names) do
    local list = pages[p]
    -- the module's own entry first, then the rest by name
    table.sort(list, function(a, b)
      if (a.name == p) ~= (b.name == p) then return a.name == p end
      return a.name < b.name
    end)
    local body = { "<h1>" .. esc(p) .. "</h1>" }
    local toc = {}
    for _, e in ipairs(list) do toc[#toc + 1] = ("<a href=\"#%s\"><code>%s</code></a>"):format(anchor(e.name), esc(e.name)) end
    body[#body + 1] = "<p class=\"muted\">" .. table.concat(toc, " &middot; ") .. "</p>"
    for _, e in ipairs(list) do
      body[#body + 1] = entry_html(e)
      if e.example then examples = examples + 1 end
    end
    write_file(dir .. "/" .. file_of(p), page(p .. " — smi-lua reference", table.concat(body, "\n"), index))
  end
  local items = {}
  local all = {}
  for _, e in ipairs(entries) do all[e.name] = e end
  for _, p in ipairs(names) do
    local e = all[p]
    items[#items + 1] = ("<li><a href=\"%s\">%s</a> — %s <span class=\"muted\">(%d)</span></li>"):format(file_of(p), esc(p), esc(e and e.summary or ""), #pages[p])
  end
  local written = write_guides(dir, guides)
  local glist = {}
  for i, g in ipairs(written) do glist[i] = ("<li><a href=\"guides/%s.html\">%s</a></li>"):format(esc(g.name), esc(g.title)) end
  local body = table.concat {
    #glist > 0 and ("<h1>Guides</h1><ul class=\"mods\">" .. table.concat(glist, "\n") .. "</ul>") or "",
    "<h1>smi-lua reference</h1><p>Every public function, method and options table of smi-lua ", esc(smi and smi.version or ""),
    ", generated by <code>smi-lua doc --html</code> from the texts compiled into the program (the same text ",
    "<code>help(smi.kde)</code> prints in the REPL). Type in the box above to search; each example below ran when this ",
    "reference was made, and its output is shown beneath it.</p><ul class=\"mods\">", table.concat(items, "\n"), "</ul>" }
  write_file(dir .. "/index.html", page("smi-lua reference", body, index))
  return #names + 1 + #written, examples
end

return M
