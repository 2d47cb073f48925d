//! The page's full metrics table: one row per series (filtered ones included), sortable by any
//! column with a click (a few lines of inline script; no external files).
use crate::coherence::{EstimatorReport, has_ratio, ratio};
use crate::html::{escape, fmt};
use std::fmt::Write;

/// The columns: (metric name, heading, unit).
const TABLE: &[(&str, &str, &str)] = &[
    ("max_jump", "max jump", "Δu′v′/frame"),
    ("max_jump_frame", "at frame", ""),
    ("mean_step", "mean step", "Δu′v′/frame"),
    ("p95_step", "p95 step", "Δu′v′/frame"),
    ("total_variation", "path length", "Δu′v′"),
    ("n_jumps_0.001", "jumps > 0.001", "count"),
    ("n_jumps_0.004", "jumps > 0.004", "count"),
    ("n_jumps_0.007", "jumps > 0.007", "count"),
    ("hf_rms", "hf_rms", "Δu′v′"),
    ("noise_floor", "noise floor", "Δu′v′"),
    ("dE_cat_mean", "dE_cat mean", "ΔE00"),
    ("dE_cat_max", "dE_cat max", "ΔE00"),
    ("n_dE_cat_gt_1", "dE_cat > 1", "frames"),
    ("dE_cat_grey_mean", "dE_cat_grey mean", "ΔE00"),
    ("flicker_ratio", "flicker ratio", "1"),
    ("n_excess", "excess > 1", "frames"),
];

/// Sorts a `table.sortable` by the clicked column: numbers by `data-v` (undefined last, in
/// both directions), text by its content; a second click reverses.
pub const SORT_SCRIPT: &str = r#"<script>
document.querySelectorAll("table.sortable").forEach(function (table) {
  var heads = table.querySelectorAll("thead th");
  heads.forEach(function (th, col) {
    th.addEventListener("click", function () {
      var up = th.getAttribute("aria-sort") !== "ascending";
      heads.forEach(function (h) { h.removeAttribute("aria-sort"); });
      th.setAttribute("aria-sort", up ? "ascending" : "descending");
      var numeric = th.dataset.type === "number";
      var key = function (row) {
        var cell = row.cells[col];
        return numeric ? parseFloat(cell.dataset.v) : cell.textContent;
      };
      var body = table.tBodies[0];
      var rows = Array.prototype.slice.call(body.rows);
      rows.sort(function (a, b) {
        var x = key(a), y = key(b);
        if (!numeric) return up ? x.localeCompare(y) : y.localeCompare(x);
        if (isNaN(x)) return isNaN(y) ? 0 : 1;
        if (isNaN(y)) return -1;
        return up ? x - y : y - x;
      });
      rows.forEach(function (row) { body.appendChild(row); });
    });
  });
});
</script>
"#;

/// The `<table class="sortable">` of every series' metrics, each with its ratio to eye.
pub fn metrics_table(h: &mut String, reports: &[EstimatorReport]) {
    let eye = reports
        .iter()
        .find(|r| r.name == "eye")
        .map(|r| r.metrics());
    h.push_str(
        "<table class=\"sortable\"><thead><tr><th class=\"name\" data-type=\"text\">estimator</th>",
    );
    for (_, head, unit) in TABLE {
        let _ = write!(h, "<th data-type=\"number\">{}", escape(head));
        if !unit.is_empty() {
            let _ = write!(h, "<br><span class=\"ratio\">{}</span>", escape(unit));
        }
        h.push_str("</th>");
    }
    h.push_str("</tr></thead>\n<tbody>\n");
    for r in reports {
        let ms = r.metrics();
        let _ = write!(h, "<tr><td class=\"name\">{}</td>", escape(&r.name));
        for (name, _, _) in TABLE {
            let Some(k) = ms.iter().position(|m| m.name == *name) else {
                h.push_str("<td data-v=\"NaN\">–</td>");
                continue;
            };
            let v = ms[k].value;
            let rat = eye
                .as_ref()
                .filter(|_| has_ratio(name) && r.name != "eye")
                .map(|e| ratio(v, e[k].value))
                .filter(|x| x.is_finite());
            let _ = write!(h, "<td data-v=\"{v}\">{}", fmt(v));
            if let Some(x) = rat {
                let _ = write!(h, " <span class=\"ratio\">×{}</span>", fmt(x));
            }
            h.push_str("</td>");
        }
        h.push_str("</tr>\n");
    }
    h.push_str("</tbody></table>\n");
}
