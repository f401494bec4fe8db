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
    function tick() {
      fetch("/api/jobs/" + id, {headers: {"Accept": "application/json"}})
        .then(function (r) { return r.json(); })
        .then(function (j) {
          if (j.status === "done" || j.status === "failed" || j.status === "cancelled") {
            window.location.reload();
            return;
          }
          var f = j.fraction || 0;
          bar.value = f;
          pct.textContent = Math.round(100 * f) + " %";
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
    dependentFields();
    familyUpload();
    unitHint();
    busyButtons();
  });
})();
