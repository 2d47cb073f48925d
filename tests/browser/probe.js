// Injected at the top of <head> of a copy of report.html by tests/browser/report.sh.
// Records every error the page raises (script errors, failed resources, console.error and
// console.warn, rejected promises, CSP violations), then, after the load event, checks that
// every image and inline SVG has a size, clicks the first numeric column heading of every
// sortable table, and writes one line per finding into <pre id="probe-result">, which
// `chromium --dump-dom` prints.
(function () {
  var errors = [];
  var say = function (kind, msg) {
    errors.push(kind + ": " + String(msg).replace(/\s+/g, " "));
  };
  window.addEventListener(
    "error",
    function (e) {
      if (e.target && e.target !== window && e.target.tagName) {
        say("resource", e.target.tagName + " " + (e.target.src || e.target.href || ""));
      } else {
        say("script", e.message + " at " + e.filename + ":" + e.lineno);
      }
    },
    true
  );
  window.addEventListener("unhandledrejection", function (e) {
    say("promise", e.reason);
  });
  document.addEventListener("securitypolicyviolation", function (e) {
    say("csp", e.violatedDirective + " " + e.blockedURI);
  });
  ["error", "warn"].forEach(function (level) {
    var original = console[level];
    console[level] = function () {
      say("console." + level, Array.prototype.join.call(arguments, " "));
      return original.apply(console, arguments);
    };
  });

  // A column is sorted when its numbers never decrease, with undefined cells last.
  function sortedAscending(values) {
    var seenUndefined = false;
    for (var i = 0; i < values.length; i++) {
      if (isNaN(values[i])) {
        seenUndefined = true;
      } else if (seenUndefined || (i > 0 && values[i] < values[i - 1])) {
        return false;
      }
    }
    return true;
  }

  function check() {
    var lines = [];
    var imgs = document.images;
    var broken = 0;
    for (var i = 0; i < imgs.length; i++) {
      if (!imgs[i].complete || imgs[i].naturalWidth === 0) {
        broken++;
        say("image", "did not load: " + imgs[i].src.slice(0, 80));
      }
    }
    var svgs = document.querySelectorAll("svg");
    var empty = 0;
    for (var j = 0; j < svgs.length; j++) {
      var r = svgs[j].getBoundingClientRect();
      if (!(r.width > 0 && r.height > 0) || svgs[j].childElementCount === 0) {
        empty++;
        say("svg", "empty or zero-sized SVG #" + j);
      }
    }
    var tables = document.querySelectorAll("table.sortable");
    var sortedOk = 0;
    for (var t = 0; t < tables.length; t++) {
      var heads = tables[t].querySelectorAll("thead th");
      var col = -1;
      for (var h = 0; h < heads.length; h++) {
        if (heads[h].dataset.type === "number") {
          col = h;
          break;
        }
      }
      if (col < 0) {
        say("sort", "table.sortable #" + t + " has no numeric column");
        continue;
      }
      heads[col].click();
      var values = Array.prototype.map.call(
        tables[t].querySelectorAll("tbody tr"),
        function (row) {
          return parseFloat(row.cells[col].dataset.v);
        }
      );
      if (values.length > 1 && sortedAscending(values)) {
        sortedOk++;
      } else {
        say("sort", "clicking column " + col + " of table #" + t + " did not sort it: " + values);
      }
    }
    lines.push(
      "PROBE images=" + imgs.length + " broken=" + broken + " svgs=" + svgs.length +
        " empty=" + empty + " sortable=" + tables.length + " sorted=" + sortedOk +
        " errors=" + errors.length
    );
    errors.forEach(function (e) {
      lines.push("PROBE-ERROR " + e);
    });
    var pre = document.createElement("pre");
    pre.id = "probe-result";
    pre.textContent = "\n" + lines.join("\n") + "\n";
    document.body.appendChild(pre);
  }
  window.addEventListener("load", function () {
    setTimeout(check, 200);
  });
})();
