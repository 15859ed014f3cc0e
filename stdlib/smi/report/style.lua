-- SPDX-License-Identifier: MIT
--- smi.report.style: the report's CSS, inlined in the page so the file stands alone (no network).
return [[
:root { --ink: #1f2933; --muted: #52606d; --line: #d9dee4; --accent: #0b4f8a; --bg: #f5f7fa;
        --pass: #1b7f3b; --pass-bg: #e3f4e8; --fail: #b42318; --fail-bg: #fde8e6;
        --warn: #8a5a00; --warn-bg: #fff4d6; --info: #3e4c59; --info-bg: #eef1f4; }
* { box-sizing: border-box; }
html { background: var(--bg); }
body { margin: 0 auto; max-width: 1100px; padding: 0 28px 40px; background: #ffffff; color: var(--ink);
       font: 15px/1.55 "DejaVu Sans", "Liberation Sans", Helvetica, Arial, sans-serif;
       box-shadow: 0 0 0 1px var(--line); min-height: 100vh; }
header.title-block { margin: 0 -28px 24px; padding: 28px 28px 20px; background: var(--accent); color: #ffffff; }
header.title-block h1 { margin: 0 0 6px; font-size: 26px; line-height: 1.25; font-weight: 700; }
header.title-block .subtitle { margin: 0 0 10px; font-size: 16px; color: #d6e4f0; }
header.title-block .meta { margin: 0; font-size: 13px; color: #b9cde0; }
h2 { font-size: 20px; margin: 34px 0 10px; padding-bottom: 4px; border-bottom: 2px solid var(--line); }
h3 { font-size: 16px; margin: 24px 0 8px; color: var(--accent); }
h2 .num, h3 .num { color: var(--muted); font-weight: 400; margin-right: 6px; }
p { margin: 8px 0; }
a { color: var(--accent); text-decoration: none; }
a:hover { text-decoration: underline; }
.summary { border: 1px solid var(--line); border-radius: 6px; padding: 12px 16px; margin: 0 0 18px; background: #fbfcfd; }
.summary h2 { margin: 0 0 8px; border: 0; font-size: 17px; }
.summary ul { list-style: none; margin: 0; padding: 0; }
.summary li { padding: 4px 0; border-top: 1px solid #edf0f3; }
.summary li:first-child { border-top: 0; }
nav.toc { border-left: 3px solid var(--accent); padding: 4px 14px; margin: 0 0 10px; font-size: 14px; }
nav.toc h2 { margin: 0 0 4px; border: 0; font-size: 15px; }
nav.toc ol { margin: 0; padding-left: 20px; }
nav.toc ol ol { padding-left: 18px; }
.badge { display: inline-block; min-width: 52px; padding: 1px 8px; border-radius: 10px; font-size: 12px; font-weight: 700;
         text-align: center; letter-spacing: 0.04em; margin-right: 8px; vertical-align: 1px; }
.badge.pass { background: var(--pass-bg); color: var(--pass); border: 1px solid var(--pass); }
.badge.fail { background: var(--fail-bg); color: var(--fail); border: 1px solid var(--fail); }
.badge.warn { background: var(--warn-bg); color: var(--warn); border: 1px solid var(--warn); }
.badge.info { background: var(--info-bg); color: var(--info); border: 1px solid var(--info); }
.verdict { border: 1px solid var(--line); border-left-width: 5px; border-radius: 4px; padding: 8px 12px; margin: 12px 0; }
.verdict.pass { border-left-color: var(--pass); }
.verdict.fail { border-left-color: var(--fail); background: #fffafa; }
.verdict.warn { border-left-color: var(--warn); }
.verdict.info { border-left-color: var(--info); }
.verdict .name { font-weight: 700; }
.verdict .detail { color: var(--muted); font-size: 14px; margin-top: 2px; }
.verdict .checks { margin: 4px 0 0; padding-left: 18px; font-size: 13.5px; }
.verdict .governs { margin-top: 4px; font-size: 13.5px; }
section.answer { border: 2px solid var(--accent); border-radius: 6px; padding: 12px 16px; margin: 0 0 18px; }
section.answer h2 { margin: 0 0 8px; border: 0; font-size: 19px; }
section.answer .conclusion { font-size: 16.5px; font-weight: 600; }
section.answer ul { list-style: none; margin: 6px 0; padding: 0; }
section.answer li { padding: 3px 0; }
section.answer .sub, section.answer .settle { color: var(--muted); font-size: 13.5px; }
section.answer .settle { display: block; margin-left: 18px; }
ul.warnings { list-style: none; padding: 0; }
ul.warnings li { padding: 5px 0; border-top: 1px solid #edf0f3; font-size: 14px; }
ul.warnings .count { font-weight: 700; margin-right: 4px; }
.callout.superseded { background: var(--info-bg); color: var(--muted); }
.summary .counts { margin: 0 0 8px; font-size: 13.5px; color: var(--muted); }
.summary .sub { color: var(--muted); font-size: 13px; }
.badge.inconclusive { background: var(--warn-bg); color: var(--warn); border: 1px dashed var(--warn); }
.badge.skip { background: #ffffff; color: var(--muted); border: 1px dashed var(--muted); }
.verdict.inconclusive { border-left-color: var(--warn); border-left-style: dashed; }
.verdict.skip { border-left-color: var(--muted); border-left-style: dashed; }
.callout { border-radius: 4px; padding: 8px 12px; margin: 12px 0; font-size: 14px; }
.callout.warn { background: var(--warn-bg); color: var(--warn); }
.callout.info { background: var(--info-bg); color: var(--info); }
.callout.fail { background: var(--fail-bg); color: var(--fail); }
/* A table never runs off the page: its cells wrap, and a table still wider than the column scrolls
   inside its own box on screen (the page itself never scrolls sideways). */
.table-wrap { max-width: 100%; overflow-x: auto; margin: 12px 0 18px; }
table.data { border-collapse: collapse; margin: 0; font-size: 13px; min-width: 50%; max-width: 100%; }
table.data td, table.data th { overflow-wrap: break-word; }
table.data td.long { overflow-wrap: anywhere; }
table.data caption { caption-side: top; text-align: left; color: var(--muted); font-size: 13px; padding-bottom: 6px; }
table.data th { text-align: left; background: #eef2f6; border-bottom: 2px solid #c5ced8; padding: 5px 7px; font-weight: 600; }
table.data td { border-bottom: 1px solid #e6eaee; padding: 4px 7px; }
table.data tr:nth-child(even) td { background: #fafbfc; }
table.data .num { text-align: right; font-variant-numeric: tabular-nums; white-space: nowrap; overflow-wrap: normal; }
table.data th.num { white-space: normal; }
/* a table of many columns (a calibration's: bounds, starts, stages, intervals) is condensed on
   screen too, so that it fits a 1280 px window without scrolling: smaller type, tighter cells,
   headers that break inside words if they must */
table.data.wide { font-size: 12px; }
table.data.wide td, table.data.wide th { padding: 3px 4px; }
table.data.wide th { overflow-wrap: break-word; }
table.data th.num { text-align: right; }
figure { margin: 16px 0 22px; }
figure .chart { border: 1px solid var(--line); border-radius: 4px; padding: 6px; display: inline-block; max-width: 100%; background: #ffffff; }
figure svg { display: block; max-width: 100%; height: auto; }
main, section, p, li, dd, figcaption, .callout, .verdict { overflow-wrap: break-word; }
figcaption { color: var(--muted); font-size: 13.5px; margin-top: 6px; max-width: 700px; }
.figrow { display: flex; flex-wrap: wrap; gap: 12px; }
.figrow figure { flex: 1 1 440px; margin: 8px 0; }
dl.prov { display: grid; grid-template-columns: max-content 1fr; gap: 4px 18px; font-size: 13.5px; margin: 8px 0; }
dl.prov dt { color: var(--muted); font-weight: 600; }
dl.prov dd { margin: 0; font-family: "DejaVu Sans Mono", monospace; font-size: 12.5px; word-break: break-all; }
footer { margin-top: 36px; padding-top: 10px; border-top: 1px solid var(--line); color: var(--muted); font-size: 12px; }
/* Printed: A4 with 14 mm margins (smi-lua report --pdf). Tables fit the page width (smaller type, cells wrap,
   numbers too if they must), a figure or a verdict is never cut by a page break, headings stay
   with what follows, and long tables repeat their header on each page. */
@page { size: A4; margin: 14mm; }
@media print {
  html { background: #ffffff; }
  body { box-shadow: none; max-width: none; padding: 0; font-size: 11pt; min-height: 0; }
  header.title-block { margin: 0 0 16px; -webkit-print-color-adjust: exact; print-color-adjust: exact; }
  .badge, .verdict, .callout { -webkit-print-color-adjust: exact; print-color-adjust: exact; }
  nav.toc { display: none; }
  .table-wrap { overflow: visible; }
  table.data { width: 100%; font-size: 8pt; }
  /* columns of equal width: the steering column's decision matrix (10 columns) ran 38 px past
     the page's 688 px with the widths its numbers asked for */
  table.data.wide { font-size: 7pt; table-layout: fixed; }
  table.data th, table.data td { padding: 2px 3px; }
  /* the printed page cannot scroll: a header word may break too ("Calibrat-ed" beats a cut column) */
  table.data th { overflow-wrap: anywhere; }
  thead { display: table-header-group; }
  tr, figure, .figrow figure, .verdict, .callout { break-inside: avoid; }
  .figrow figure { flex: 1 1 300px; margin: 6px 0; }  /* two charts a row on the page */
  figure .chart { display: block; border: 0; padding: 0; }
  figure svg { max-width: 100%; max-height: 120mm; width: auto; }
  h2, h3, caption { break-after: avoid; }
  a { color: inherit; }
}
]]
