"""The HTML pages of a grading (report.html, the class page): one self-contained page each.

A page needs nothing from outside: its style and its script are in it, and
its pictures are files beside it. Its table sorts and filters in the page,
with plain JavaScript:

- a header cell with data-sort="KEY" sorts the rows by their data-KEY
  (data-type "num": as numbers, "verdict": failing first, then not
  applicable, then passing; else as text); a second click reverses;
- the select #filter shows every row, or only the rows failing (or
  passing) one criterion (a row's data-CRITERION is pass, fail or na), or
  failing any;
- the state is kept in the address (#sort=KEY:asc&filter=fail:CRITERION),
  so that a view can be linked to, and opened, as it was;
- a picture that cannot be loaded is replaced by the words "plot not
  found" and its path.
"""
import html

STYLE = """
body { font-family: sans-serif; margin: 1em; }
table { border-collapse: collapse; }
td, th { border: 1px solid #999; padding: 4px; vertical-align: top; }
th[data-sort] { cursor: pointer; background: #e8e8f0; }
th[data-sort]:hover { background: #d0d0e8; }
td.figures { max-width: 24em; }
td.pass { background: #d4f0d4; color: #064; }
td.fail { background: #f6cccc; color: #900; }
td.na { background: #eeeeee; color: #555; }
small { color: #333; }
.missing { color: #900; font-style: italic; }
#controls { margin: 0.5em 0; }
"""

SCRIPT = r"""
(function () {
  var table = document.querySelector('table.sortable');
  if (!table) { return; }
  var body = table.tBodies[0];
  var select = document.getElementById('filter');
  var shown = document.getElementById('shown');
  var rank = {fail: 0, na: 1, pass: 2};

  function state() {
    var found = {sort: '', filter: 'all'};
    location.hash.replace(/^#/, '').split('&').forEach(function (part) {
      var pair = part.split('=');
      if (pair.length === 2 && pair[0] in found) { found[pair[0]] = decodeURIComponent(pair[1]); }
    });
    return found;
  }

  function keep(next) {
    var parts = [];
    if (next.sort) { parts.push('sort=' + encodeURIComponent(next.sort)); }
    if (next.filter && next.filter !== 'all') {
      parts.push('filter=' + encodeURIComponent(next.filter));
    }
    location.hash = parts.join('&');
    apply();
  }

  function value(row, key, type) {
    var text = row.getAttribute('data-' + key) || '';
    if (type === 'num') { var n = parseFloat(text); return isNaN(n) ? Infinity : n; }
    if (type === 'verdict') { return text in rank ? rank[text] : 3; }
    return text.toLowerCase();
  }

  function sortBy(spec) {
    var parts = spec.split(':');
    var head = table.querySelector('th[data-sort="' + parts[0] + '"]');
    if (!head) { return; }
    var type = head.getAttribute('data-type') || 'text';
    var sign = parts[1] === 'desc' ? -1 : 1;
    var rows = Array.prototype.slice.call(body.rows);
    rows.sort(function (a, b) {
      var x = value(a, parts[0], type), y = value(b, parts[0], type);
      if (x < y) { return -sign; }
      if (x > y) { return sign; }
      return a.getAttribute('data-order') - b.getAttribute('data-order');
    });
    rows.forEach(function (row) { body.appendChild(row); });
    Array.prototype.forEach.call(table.querySelectorAll('th[data-sort]'), function (th) {
      th.removeAttribute('aria-sort');
    });
    head.setAttribute('aria-sort', sign > 0 ? 'ascending' : 'descending');
  }

  function matches(row, filter) {
    if (filter === 'all') { return true; }
    var parts = filter.split(':');
    if (parts[1] === 'any') {
      return (row.getAttribute('data-failed') || '0') !== '0';
    }
    return row.getAttribute('data-' + parts[1]) === parts[0];
  }

  function apply() {
    var now = state();
    if (now.sort) { sortBy(now.sort); }
    var count = 0;
    Array.prototype.forEach.call(body.rows, function (row) {
      row.hidden = !matches(row, now.filter);
      if (!row.hidden) { count += 1; }
    });
    if (select) { select.value = now.filter; }
    if (shown) { shown.textContent = count + ' of ' + body.rows.length + ' shown'; }
  }

  Array.prototype.forEach.call(table.querySelectorAll('th[data-sort]'), function (th) {
    th.addEventListener('click', function () {
      var now = state();
      var key = th.getAttribute('data-sort');
      now.sort = key + (now.sort === key + ':asc' ? ':desc' : ':asc');
      keep(now);
    });
  });
  if (select) {
    select.addEventListener('change', function () {
      var now = state();
      now.filter = select.value;
      keep(now);
    });
  }
  window.addEventListener('hashchange', apply);

  function missing(img) {
    var note = document.createElement('span');
    note.className = 'missing';
    note.textContent = 'plot not found: ' + img.getAttribute('src');
    var link = img.parentNode.tagName === 'A' ? img.parentNode : img;
    link.parentNode.replaceChild(note, link);
  }
  Array.prototype.forEach.call(document.querySelectorAll('img.plot'), function (img) {
    if (img.complete && img.naturalWidth === 0) { missing(img); }
    else { img.addEventListener('error', function () { missing(img); }); }
  });
  apply();
})();
"""


def escape(text):
    return html.escape(str(text))


def data_attributes(values):
    """' data-key="value"' for each (key, value), values escaped: what the script sorts
    and filters a row by."""
    return ''.join(' data-%s="%s"' % (key, escape(value)) for key, value in values)


def filter_control(criteria, noun):
    """The select that filters the table's rows by criterion, and the count of rows shown."""
    options = [('all', 'every %s' % noun), ('fail:any', 'failing any criterion')]
    for name in criteria:
        options += [('fail:%s' % name, 'failing %s' % name),
                    ('pass:%s' % name, 'passing %s' % name)]
    return ('<p id="controls"><label>Show <select id="filter">%s</select></label> '
            '<span id="shown"></span>; click a column\'s head to sort by it.</p>'
            % ''.join('<option value="%s">%s</option>' % (escape(v), escape(t))
                      for v, t in options))


def document(title, body):
    """A whole page: title, style, body (HTML) and the script."""
    return '\n'.join([
        '<!DOCTYPE html>', '<html><head><meta charset="utf-8">',
        '<title>%s</title>' % escape(title), '<style>%s</style>' % STYLE, '</head><body>',
        body, '<script>%s</script>' % SCRIPT, '</body></html>', ''])
