// The report's and the live view's first script: errors of any script or
// resource are listed in #tc-errors (the browser tests read them).
window.tcErrors = [];
window.addEventListener("error", function (e) {
  var what = e.message ? e.message : ("failed resource: " + ((e.target && (e.target.src || e.target.href)) || "?"));
  window.tcErrors.push(what);
  var el = document.getElementById("tc-errors");
  if (el) { el.textContent = window.tcErrors.join("\n"); el.hidden = false; }
}, true);
window.addEventListener("unhandledrejection", function (e) { window.tcErrors.push("unhandled rejection: " + e.reason); });
