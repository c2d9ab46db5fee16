/* SignStudy's corrections to Django's admin pages (issue 55, item 8: axe-core).
 * A tabular inline's first and last header cells (the row's original object, its
 * delete box) are empty; a screen reader then announces columns without names. */
(function () {
  "use strict";
  // The script element's data attributes carry the names, in the researcher's language.
  const names = document.currentScript.dataset;
  document.querySelectorAll(".inline-related table thead th").forEach(function (cell) {
    if (cell.textContent.trim()) { return; }
    const hidden = document.createElement("span");
    hidden.className = "visually-hidden";
    hidden.textContent = cell.classList.contains("original") ? names.original : names.delete;
    cell.append(hidden);
  });
})();
