// Layout probe of tests/test_browser.py, run in the report's page by headless Chromium.
//
// Measures the page twice: as shown (the window's width) and as printed (the
// report's @media print rules applied, the page as wide as an A4 landscape
// sheet's content, 297 mm less two 10 mm margins, at 96 px/in). Each time it lists
// the elements that reach past that width, the chart text that runs past its
// chart's edge (clipped: an <svg> shows nothing outside its viewBox), the chart
// text shown smaller than 11 px, and the charts of each profile section. The
// result is left, as JSON, in the hidden pre element #gyrovib-layout, for --dump-dom.
//
// Elements marked data-probe are the test's own deliberate faults (they must be
// found, so the probe is known to see them) and are named as such.
(function () {
  "use strict";
  // A4 landscape, @page margin 10 mm: (297 - 2*10) mm at 96 px/in
  var PAGE = (297 - 20) / 25.4 * 96;
  var MIN_TEXT = 11;
  function name(el) {
    var s = el.tagName.toLowerCase();
    if (el.id) s += "#" + el.id;
    if (el.getAttribute("class")) s += "." + el.getAttribute("class").split(" ").join(".");
    var text = (el.textContent || "").trim().slice(0, 40);
    if (el.closest("[data-probe]")) s = "PROBE " + s;
    return s + (text ? " '" + text + "'" : "");
  }
  function chartOf(el) {
    var svg = el.closest("svg");
    return (svg && svg.hasAttribute("data-probe") ? "PROBE " : "") +
      (svg ? (svg.getAttribute("aria-label") || "") : "");
  }
  function measure(width) {
    var out = {overflow: [], clipped: [], small: [], charts: {}, width: width};
    var all = document.body.querySelectorAll("*");
    for (var k = 0; k < all.length; k++) {
      var el = all[k];
      if (el.closest("svg") && el.tagName.toLowerCase() !== "svg") continue;
      if (el.id === "gyrovib-layout") continue;
      var r = el.getBoundingClientRect();
      if (r.width > 0 && r.right > width + 0.5) out.overflow.push(name(el) + " right=" + r.right.toFixed(1));
    }
    var svgs = document.querySelectorAll("svg.chart");
    for (var s = 0; s < svgs.length; s++) {
      var svg = svgs[s], vb = svg.viewBox.baseVal, box = svg.getBoundingClientRect();
      var scale = box.width / vb.width;
      var texts = svg.querySelectorAll("text");
      for (var t = 0; t < texts.length; t++) {
        // the text's box in the chart's own units, its transform (a rotation) applied
        var b = texts[t].getBBox();
        var m = svg.getScreenCTM().inverse().multiply(texts[t].getScreenCTM());
        var xs = [], ys = [];
        [[b.x, b.y], [b.x + b.width, b.y], [b.x, b.y + b.height],
         [b.x + b.width, b.y + b.height]].forEach(function (c) {
          xs.push(m.a * c[0] + m.c * c[1] + m.e);
          ys.push(m.b * c[0] + m.d * c[1] + m.f);
        });
        if (Math.min.apply(null, xs) < vb.x - 0.5 || Math.min.apply(null, ys) < vb.y - 0.5 ||
            Math.max.apply(null, xs) > vb.x + vb.width + 0.5 ||
            Math.max.apply(null, ys) > vb.y + vb.height + 0.5)
          out.clipped.push(chartOf(texts[t]) + ": '" + texts[t].textContent + "'");
        var size = parseFloat(getComputedStyle(texts[t]).fontSize) * scale;
        if (size < MIN_TEXT - 0.01)
          out.small.push(chartOf(texts[t]) + ": '" + texts[t].textContent + "' " + size.toFixed(1) + " px");
      }
    }
    var sections = document.querySelectorAll("section.profile");
    for (var p = 0; p < sections.length; p++) {
      var titles = [], charts = sections[p].querySelectorAll("svg.chart");
      for (var c = 0; c < charts.length; c++) {
        var rc = charts[c].getBoundingClientRect();
        if (rc.width > 0 && rc.height > 0) titles.push(charts[c].getAttribute("aria-label"));
      }
      out.charts[sections[p].id] = titles;
    }
    return out;
  }
  var screen = measure(document.documentElement.clientWidth);
  // the print stylesheet, as printing applies it, at the printed page's content width
  var rules = [];
  for (var i = 0; i < document.styleSheets.length; i++) {
    var list = document.styleSheets[i].cssRules;
    for (var j = 0; j < list.length; j++) {
      if (list[j].media && /print/.test(list[j].media.mediaText)) {
        for (var q = 0; q < list[j].cssRules.length; q++) rules.push(list[j].cssRules[q].cssText);
      }
    }
  }
  var style = document.createElement("style");
  style.textContent = rules.join("\n");
  document.head.appendChild(style);
  document.documentElement.style.width = PAGE + "px";
  var printed = measure(PAGE);
  printed.rules = rules.length;
  document.head.removeChild(style);
  document.documentElement.style.width = "";
  var pre = document.createElement("pre");
  pre.id = "gyrovib-layout";
  pre.style.display = "none";
  pre.textContent = JSON.stringify({screen: screen, print: printed});
  document.body.appendChild(pre);
  console.log("gyrovib-layout-probe");
})();
