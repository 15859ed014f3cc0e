#!/bin/sh
# SPDX-License-Identifier: MIT
# A report an engineer can print. Renders tests/report/wide_report.lua's report in
# headless Chromium on screen (1280 px) and with the print styles at the printable width of an A4
# page (688 px: 210 mm less 2 x 14 mm margins), and prints it to PDF. Checks that no element is
# wider than the page (nothing cut off, no sideways scrolling) and that no number in the page's
# text carries more than 10 significant digits (binary noise such as 1.4999999999999998e-09).
# Keeps WORKDIR/screen.png, print.png and report.pdf for people to look at.
#   print_report.sh SMI_LUA REPORT_SCRIPT WORKDIR
# Exit 77 (ctest: skipped) when /usr/bin/chromium is missing; 1 with a message on any failure.
set -u
SMI_LUA=$1
SCRIPT=$2
WORK=$3
. "$(dirname "$0")/../chromium.sh"  # CHROMIUM, the skip, fail, chrome, console_lines, check_console_detector

rm -rf "$WORK"
mkdir -p "$WORK"
WORK=$(cd "$WORK" && pwd)
"$SMI_LUA" --quiet --out "$WORK/out" "$SCRIPT" > "$WORK/run.log" 2>&1 || { cat "$WORK/run.log"; fail "the report script failed"; }
REPORT="$WORK/out/report.html"
[ -s "$REPORT" ] || fail "no $REPORT"
check_console_detector

# The measuring script, added to copies of the page (the report itself has no script): every
# element's right edge against the page width, and every decimal number of the visible text.
cat > "$WORK/measure.js" <<'JS'
(function(){
  var W=document.documentElement.clientWidth,wide=[],noisy=[];
  var all=document.body.getElementsByTagName("*");
  for(var i=0;i<all.length;i++){var el=all[i],r=el.getBoundingClientRect();
    if(r.width>0&&(r.right>W+0.5||r.left<-0.5)){var name=el.tagName.toLowerCase()+(el.id?"#"+el.id:"")+(el.className&&el.className.baseVal===undefined?"."+el.className:"");
      wide.push(name+" ["+Math.round(r.left)+", "+Math.round(r.right)+"]");}}
  if(document.documentElement.scrollWidth>W)wide.push("the page scrolls sideways: "+document.documentElement.scrollWidth+" > "+W);
  /* a table may scroll in its own box on screen (said on the output), never printed */
  var boxes=document.querySelectorAll(".table-wrap"),scrolls=0;
  for(var b=0;b<boxes.length;b++)if(boxes[b].scrollWidth>boxes[b].clientWidth+1)scrolls++;
  var text=document.body.innerText,re=/\d+\.\d+(?:e[-+]?\d+)?/gi,m;
  while((m=re.exec(text))!==null){var digits=m[0].replace(/e.*$/i,"").replace(".","").replace(/^0+/,"");
    if(digits.length>10)noisy.push(m[0]);}
  var out=document.createElement("pre");out.id="smi-measure";
  out.textContent="WIDTH "+W+"\nSCROLLS "+scrolls+"\nWIDE "+wide.length+"\n"+wide.slice(0,20).join("\n")+"\nNOISY "+noisy.length+"\n"+noisy.slice(0,20).join("\n");
  document.body.appendChild(out);
})();
JS
measure() {  # measure PAGE WIDTH NAME: fails when an element is too wide or a number is noisy
  chrome --window-size="$2,1000" --dump-dom "file://$1" > "$WORK/$3.dom" 2> "$WORK/$3.log" || fail "chromium --dump-dom failed on $1"
  if console_lines "$WORK/$3.log"; then fail "console messages while loading $1 (above)"; fi
  sed -n '/<pre id="smi-measure">/,/<\/pre>/p' "$WORK/$3.dom" > "$WORK/$3.txt"
  grep -q '^WIDE ' "$WORK/$3.txt" || fail "the measuring script did not run (see $WORK/$3.dom)"
  if ! grep -q '^WIDE 0$' "$WORK/$3.txt"; then cat "$WORK/$3.txt"; fail "$3: elements wider than the page (above)"; fi
  if ! grep -q '^NOISY 0$' "$WORK/$3.txt"; then cat "$WORK/$3.txt"; fail "$3: numbers with more than 10 significant digits (above)"; fi
  if [ "$3" = print ] && ! grep -q '^SCROLLS 0$' "$WORK/$3.txt"; then cat "$WORK/$3.txt"; fail "printed, a table would need scrolling"; fi
  grep '^SCROLLS' "$WORK/$3.txt" | sed "s/^/$3: tables scrolling in their box: /"
}
# (a script after </html> is parsed into the body, and runs after the page is laid out)
with_script() { cat; printf '<script>'; cat "$WORK/measure.js"; printf '</script>\n'; }
# on screen
with_script < "$REPORT" > "$WORK/screen.html"
measure "$WORK/screen.html" 1280 screen
# printed: the print styles applied on screen at the printable width of an A4 page
sed 's/@media print/@media all/' "$REPORT" | with_script > "$WORK/print.html"
measure "$WORK/print.html" 688 print

chrome --no-pdf-header-footer --print-to-pdf="$WORK/report.pdf" "file://$REPORT" > /dev/null 2> "$WORK/pdf.log" \
  || fail "chromium --print-to-pdf failed (see $WORK/pdf.log)"
[ -s "$WORK/report.pdf" ] || fail "no PDF printed"
pages=$(grep -ac '/Type /Page\b' "$WORK/report.pdf")
[ "$pages" -ge 1 ] || fail "the PDF has no pages"
chrome --window-size=1280,3000 --screenshot="$WORK/screen.png" "file://$REPORT" > /dev/null 2>&1
sed 's/@media print/@media all/' "$REPORT" > "$WORK/print-view.html"
chrome --window-size=688,3000 --screenshot="$WORK/print.png" "file://$WORK/print-view.html" > /dev/null 2>&1
echo "OK: no element wider than the page on screen (1280 px) or printed (688 px), no noisy number; $pages PDF pages ($WORK/report.pdf); screenshots $WORK/screen.png, $WORK/print.png"
