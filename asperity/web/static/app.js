// asperity serve: draws the Plotly figures of a page, polls a running job, and shows the
// fields that apply to the choices made in a form.  Hand-written, no build step.
(function () {
  "use strict";

  function drawFigures() {
    if (typeof Plotly === "undefined") { return; }
    document.querySelectorAll("[data-figure]").forEach(function (el) {
      var src = document.getElementById(el.getAttribute("data-figure"));
      if (!src) { return; }
      var fig = JSON.parse(src.textContent);
      // the title is the caption above the plot, where Plotly's toolbar cannot cover it
      if (document.getElementById(el.getAttribute("data-caption") || "-")) {
        delete fig.layout.title;
        fig.layout.margin = Object.assign({}, fig.layout.margin, {t: 34});
      }
      Plotly.newPlot(el, fig.data, fig.layout, {responsive: true, displaylogo: false});
      el.setAttribute("data-drawn", "1");
    });
  }

  function pollJob() {
    var box = document.getElementById("progress");
    if (!box) { return; }
    var id = box.getAttribute("data-job");
    var bar = document.getElementById("progress-bar");
    var pct = document.getElementById("progress-pct");
    var status = document.getElementById("progress-status");
    var clock = document.getElementById("progress-time");
    // the bar never goes back and shows 100 % only once the job is done (the worker's
    // fraction is monotone already; this holds for an older worker's too)
    var shown = Number(bar.value) || 0;
    function tick() {
      fetch("/api/jobs/" + id, {headers: {"Accept": "application/json"}})
        .then(function (r) { return r.json(); })
        .then(function (j) {
          if (j.status === "done" || j.status === "failed" || j.status === "cancelled") {
            window.location.reload();
            return;
          }
          shown = Math.max(shown, Math.min(Number(j.fraction) || 0, 0.99));
          bar.value = shown;
          pct.textContent = Math.floor(100 * shown) + " %";
          status.textContent = (j.status === "queued" ? "waiting for a free worker" : "computing") +
            (j.label ? ": " + j.label : "");
          clock.textContent = timeText(j);
          setTimeout(tick, 400);
        })
        .catch(function () { setTimeout(tick, 2000); });
    }
    tick();
  }

  // "1 min 05 s": as the server's duration() writes it
  function duration(s) {
    s = Math.round(s || 0);
    function two(n) { return (n < 10 ? "0" : "") + n; }
    if (s < 60) { return s + " s"; }
    if (s < 3600) { return Math.floor(s / 60) + " min " + two(s % 60) + " s"; }
    return Math.floor(s / 3600) + " h " + two(Math.floor(s % 3600 / 60)) + " min";
  }

  // elapsed time from the job's stored start (a reload does not reset it), time left
  function timeText(j) {
    if (j.since !== "running") { return "waiting for " + duration(j.elapsed_s); }
    return duration(j.elapsed_s) + " elapsed" +
      (j.left_s === null || j.left_s === undefined ? "" : ", about " + duration(j.left_s) + " left");
  }

  function dependentFields() {
    document.querySelectorAll("[data-when]").forEach(function (el) {
      var form = el.closest("form");
      var select = form && form.querySelector("[name='" + el.getAttribute("data-when") + "']");
      if (!select) { return; }
      function update() {
        el.hidden = el.getAttribute("data-values").split(" ").indexOf(select.value) < 0;
      }
      select.addEventListener("change", update);
      update();
    });
  }

  // a select whose options belong to the choice of another (the Law page's pressures, each
  // of one result): only the options of the result chosen are offered
  function ownOptions() {
    document.querySelectorAll("select[data-source-of]").forEach(function (sel) {
      var source = sel.form && sel.form.querySelector("[name='" + sel.getAttribute("data-source-of") + "']");
      if (!source) { return; }
      function update() {
        var first = null;
        Array.prototype.forEach.call(sel.options, function (o) {
          var mine = o.getAttribute("data-source") === source.value;
          o.hidden = !mine;
          o.disabled = !mine;
          if (mine && first === null) { first = o; }
        });
        var cur = sel.options[sel.selectedIndex];
        if ((!cur || cur.disabled) && first) { first.selected = true; }
      }
      source.addEventListener("change", update);
      update();
    });
  }

  // the pressure of a law family shows for an uploaded gauge file only when the file
  // chosen is a family (version 2): read in the browser, nothing sent
  function familyUpload() {
    var input = document.getElementById("f-slide-gauge");
    var box = document.getElementById("law-family-pressure");
    if (!input || !box || !window.FileReader) { return; }
    input.addEventListener("change", function () {
      var file = input.files[0];
      var values = box.getAttribute("data-values").split(" ").filter(function (v) {
        return v && v !== "upload";
      });
      function done(family) {
        box.setAttribute("data-values", (family ? values.concat(["upload"]) : values).join(" "));
        var select = input.form.querySelector("[name='law']");
        if (select) { select.dispatchEvent(new Event("change")); }
      }
      if (!file || file.size > 64 * 1024 * 1024) { done(false); return; }
      var reader = new FileReader();
      reader.onload = function () {
        var obj = null;
        try { obj = JSON.parse(reader.result); } catch (e) { obj = null; }
        done(!!obj && obj.format === "asperity-gauge" && obj.version === 2);
      };
      reader.onerror = function () { done(false); };
      reader.readAsText(file);
    });
  }

  function unitHint() {
    var input = document.getElementById("f-file");
    var box = document.getElementById("units");
    if (!input || !box) { return; }
    input.addEventListener("change", function () {
      var name = (input.files[0] && input.files[0].name || "").toLowerCase().replace(/\.gz$/, "");
      var none = /\.(stl|obj|ply|npy|npz)$/.test(name);
      box.classList.toggle("attention", none);
    });
  }

  // a refused field inside a collapsed section (<details>) opens it, and the page scrolls
  // to the first refused field
  function openErrors() {
    var errs = document.querySelectorAll(".field-error");
    errs.forEach(function (e) {
      for (var d = e.closest("details"); d; d = d.parentElement && d.parentElement.closest("details")) {
        d.open = true;
      }
    });
    if (errs.length && errs[0].scrollIntoView) { errs[0].scrollIntoView({block: "center"}); }
  }

  // the fields of the page's other forms, as chosen, survive the answer to one form (an
  // error redraws the page with only the submitted form's fields): kept in the tab's
  // sessionStorage on submit, restored once when the same page comes back
  var KEEP = "asperity-forms:";
  function keepOtherForms() {
    var here = KEEP + window.location.pathname.replace(/\/(slide|risk|open)$/, "");
    var forms = Array.prototype.slice.call(document.querySelectorAll("form[id]"));
    forms.forEach(function (form) {
      form.addEventListener("submit", function () {
        var kept = {};
        forms.forEach(function (other) {
          if (other === form) { return; }
          var fields = {};
          Array.prototype.forEach.call(other.elements, function (el) {
            if (!el.name || el.type === "file" || el.type === "hidden" || el.type === "submit") { return; }
            fields[el.name + (el.id ? "#" + el.id : "")] = el.value;
          });
          kept[other.id] = fields;
        });
        try { sessionStorage.setItem(here, JSON.stringify({from: form.id, forms: kept})); } catch (e) { /* private mode */ }
      });
    });
    var saved = null;
    try { saved = JSON.parse(sessionStorage.getItem(here) || "null"); sessionStorage.removeItem(here); } catch (e) { saved = null; }
    if (!saved || !document.getElementById("error")) { return; }   // only a form sent back
    Object.keys(saved.forms || {}).forEach(function (id) {
      var form = document.getElementById(id);
      if (!form || id === saved.from) { return; }
      Array.prototype.forEach.call(form.elements, function (el) {
        var key = el.name + (el.id ? "#" + el.id : "");
        if (!el.name || !(key in saved.forms[id]) || el.type === "file" || el.type === "hidden") { return; }
        if (el.tagName === "SELECT" && !Array.prototype.some.call(el.options, function (o) {
          return o.value === saved.forms[id][key]; })) { return; }
        el.value = saved.forms[id][key];
        el.dispatchEvent(new Event("change"));
      });
    });
  }

  function busyButtons() {
    document.querySelectorAll("form").forEach(function (form) {
      form.addEventListener("submit", function () {
        var b = form.querySelector("button[type=submit]");
        if (b) { b.classList.add("busy"); b.textContent = "working..."; }
      });
    });
  }

  document.addEventListener("DOMContentLoaded", function () {
    drawFigures();
    pollJob();
    keepOtherForms();
    dependentFields();
    ownOptions();
    openErrors();
    familyUpload();
    unitHint();
    busyButtons();
  });
})();
