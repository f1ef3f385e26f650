document.querySelectorAll("table.sortable thead th").forEach(function (th) {
  th.addEventListener("click", function () {
    var table = th.closest("table");
    var body = table.tBodies[0];
    var column = Array.prototype.indexOf.call(th.parentNode.children, th);
    var ascending = th.getAttribute("data-sort") !== "asc";
    table.querySelectorAll("thead th").forEach(function (h) { h.removeAttribute("data-sort"); });
    th.setAttribute("data-sort", ascending ? "asc" : "desc");
    function key(row) {
      var cell = row.cells[column];
      if (!cell) { return ""; }
      var raw = cell.hasAttribute("data-v") ? cell.getAttribute("data-v") : cell.textContent.trim();
      var n = parseFloat(raw);
      return isNaN(n) ? raw.toLowerCase() : n;
    }
    var rows = Array.prototype.slice.call(body.rows);
    rows.sort(function (a, b) {
      var x = key(a), y = key(b);
      if (typeof x !== typeof y) { return typeof x === "number" ? -1 : 1; }
      return (x < y ? -1 : x > y ? 1 : 0) * (ascending ? 1 : -1);
    });
    rows.forEach(function (row) { body.appendChild(row); });
  });
});
