// The catalog index: a page of rows at a time from the entries in catalog-data.js and its parts,
// filtered by family, roughness range, licence, source kind and words, in name or roughness order;
// ticked entries open side by side in compare.html. The data comes by <script src> rather than fetch(),
// which browsers refuse for file://; it is columns of arrays (index_page.hpp, index_files), and only the rows of the
// page shown are ever made, so that 100,000 entries open as fast as 100. The filters and the page live
// in the URL hash (#family=textiles&rmin=0.2&rmax=0.5&q=silk&order=roughness&page=3&cmp=a,b), so a
// view can be bookmarked or shared and the back button returns to it.
(function () {
  'use strict';
  var PAGE_SIZE = 100;
  var family = document.getElementById('family');
  var rmin = document.getElementById('rmin');
  var rmax = document.getElementById('rmax');
  var q = document.getElementById('q');
  var licence = document.getElementById('licence');
  var source = document.getElementById('source');
  var order = document.getElementById('order');
  var compareBar = document.getElementById('compare-bar');
  var compareCount = document.getElementById('compare-count');
  var compareGo = document.getElementById('compare-go');
  // The source kinds' bits in the data's `sources` column (compiler::SourceKind's order).
  var SOURCE_BITS = {measurement: 1, standard: 2, publication: 4, derived: 8, 'by-ear': 16};
  var ticked = [];  // the names ticked for comparison, in the order ticked
  var count = document.getElementById('count');
  var none = document.getElementById('none');
  var tbody = document.querySelector('#entries tbody');
  var pagers = Array.prototype.slice.call(document.querySelectorAll('nav.pager'));
  // The head (catalog-data.js) and its parts (catalog-data/part-NNNNN.js), each loaded by its own
  // <script src> before this one, joined into one set of columns.
  var data = joinParts(window.sandpaperCatalog, window.sandpaperCatalogParts || []);
  if (!data) {
    count.textContent = 'The entries could not be read: catalog-data.js or a file in catalog-data/, beside ' +
                        'index.html, is missing or from another version of Sandpaper. The entries\u2019 own pages ' +
                        'are in entries/.';
    document.body.setAttribute('data-ready', 'error');
    return;
  }
  var total = data.name.length;
  var familyOf = {};
  data.families.forEach(function (f, i) { familyOf[f.id] = i; });
  var noThumbnail = new Uint8Array(total);
  data.no_thumbnail.forEach(function (i) { noThumbnail[i] = 1; });
  var haystacks = null;  // lower-case text each entry's words are matched in; made at the first word search
  var indexOfName = Object.create(null);
  data.name.forEach(function (n, i) { indexOfName[n] = i; });

  // The licence filter lists the licences the entries state, most used first, with their counts.
  (function listLicences() {
    var counts = {};
    data.licence.forEach(function (l) { counts[l] = (counts[l] || 0) + 1; });
    Object.keys(counts).sort(function (a, b) { return counts[b] - counts[a] || (a < b ? -1 : a > b ? 1 : 0); })
      .forEach(function (l) {
        var o = document.createElement('option');
        o.value = l === '' ? '(none)' : l;
        o.textContent = (l === '' ? 'not stated' : l) + ' (' + grouped(counts[l]) + ')';
        licence.appendChild(o);
      });
  })();

  // The parts' columns end to end; a part's rows are numbered within it, so its aliases, deprecations
  // and missing thumbnails are shifted by the rows before it. Null if any part is missing or not its own.
  function joinParts(head, parts) {
    if (!head || head.format !== 3 || !Array.isArray(head.parts) || parts.length !== head.parts.length) return null;
    var columns = ['name', 'family', 'roughness', 'describes', 'licence', 'sources', 'force_N', 'period_m', 'kind'];
    var d = {families: head.families, aliases: {}, deprecated_by: {}, root: {}, no_thumbnail: []};
    columns.forEach(function (c) { d[c] = []; });
    for (var k = 0; k < parts.length; k++) {
      var p = parts[k], base = d.name.length;
      if (!p || p.format !== 3 || p.part !== k || p.name.length !== head.parts[k].rows) return null;
      columns.forEach(function (c) { Array.prototype.push.apply(d[c], p[c]); });
      Object.keys(p.aliases).forEach(function (i) { d.aliases[base + Number(i)] = p.aliases[i]; });
      Object.keys(p.deprecated_by).forEach(function (i) { d.deprecated_by[base + Number(i)] = p.deprecated_by[i]; });
      Object.keys(p.root).forEach(function (i) { d.root[base + Number(i)] = p.root[i]; });
      p.no_thumbnail.forEach(function (i) { d.no_thumbnail.push(base + i); });
    }
    return d.name.length === head.entries ? d : null;
  }

  function grouped(n) { return n.toLocaleString('en-US'); }

  function aliasesOf(i) { return data.aliases[i] || []; }

  // The word ranking of `sandpaper library search` (curation/word_rank.hpp; docs/LIBRARY.md, "search"),
  // the same rule here: a text's words are its runs of ASCII letters and digits and of other
  // characters above U+007F, ASCII lower-cased; a query word matches a field when it begins one of
  // the field's words; every query word must match; an entry scores, for each query word, the best
  // field it matches: name 8, alias 4, describes 2, family (id or title) 1.
  var NAME_WORD = 8, ALIAS_WORD = 4, DESCRIBES_WORD = 2, FAMILY_WORD = 1;
  function lower(c) { return c.toLowerCase(); }
  function asciiLower(text) { return /[A-Z]/.test(text) ? text.replace(/[A-Z]+/g, lower) : text; }
  function searchTokens(text) {
    return asciiLower(text).split(/[^a-z0-9\u0080-\uffff]+/).filter(function (w) { return w !== ''; });
  }
  // An entry's fields as one lower-case text, made at the first word search: a word that begins a
  // word of a field is in it, so only the entries that hold every query word are split into words.
  function haystack(i) {
    if (haystacks === null) {
      haystacks = new Array(total);
      var familyText = data.families.map(function (f) { return ' ' + asciiLower(f.id + ' ' + f.title); });
      for (var k = 0; k < total; k++) {
        var a = data.aliases[k];
        haystacks[k] = asciiLower(a ? data.name[k] + ' ' + a.join(' ') + ' ' + data.describes[k] : data.name[k] + ' ' + data.describes[k]) +
                       (familyText[data.family[k]] || '');
      }
    }
    return haystacks[i];
  }
  // An entry's fields as words: [name, aliases, describes, family id and title].
  var fieldWords = Object.create(null);
  function fields(i) {
    if (!(i in fieldWords)) {
      var f = data.families[data.family[i]];
      fieldWords[i] = [searchTokens(data.name[i]), searchTokens(aliasesOf(i).join(' ')), searchTokens(data.describes[i]),
                       searchTokens(f ? f.id + ' ' + f.title : '')];
    }
    return fieldWords[i];
  }
  function begins(word, fieldWords) {
    for (var k = 0; k < fieldWords.length; k++) if (fieldWords[k].lastIndexOf(word, 0) === 0) return true;
    return false;
  }
  function wordScore(words, i) {
    var text = haystack(i);
    for (var w = 0; w < words.length; w++) if (text.indexOf(words[w]) < 0) return 0;
    var h = fields(i), score = 0;
    for (w = 0; w < words.length; w++) {
      var best = begins(words[w], h[0]) ? NAME_WORD : begins(words[w], h[1]) ? ALIAS_WORD :
                 begins(words[w], h[2]) ? DESCRIBES_WORD : begins(words[w], h[3]) ? FAMILY_WORD : 0;
      if (best === 0) return 0;
      score += best;
    }
    return score;
  }
  // The query's exact names and aliases, as `library search` takes them: the whole query with its
  // words joined by '-' or by spaces, and each word. rank 0 for a name, 1 for an alias.
  var aliasOwner = null;
  function exactRanks(typed) {
    var out = Object.create(null);
    if (!typed.length) return out;
    if (aliasOwner === null) {
      aliasOwner = Object.create(null);
      Object.keys(data.aliases).forEach(function (i) {
        data.aliases[i].forEach(function (a) { if (!(a in aliasOwner)) aliasOwner[a] = Number(i); });
      });
    }
    var candidates = [typed.join(' '), typed.join('-')].concat(typed);
    candidates.forEach(function (c) { if (c in indexOfName && !(indexOfName[c] in out)) out[indexOfName[c]] = 0; });
    candidates.forEach(function (c) { if (c in aliasOwner && !(aliasOwner[c] in out)) out[aliasOwner[c]] = 1; });
    return out;
  }

  function number(text) {
    text = text.trim();
    if (text === '') return null;
    var v = Number(text);
    return isFinite(v) ? v : null;
  }

  // What the controls ask for, and the page: the hash's form of it is also the key of the last result.
  function readControls(page) {
    var f = {
      family: family.value,
      rmin: rmin.value.trim(),
      rmax: rmax.value.trim(),
      q: q.value.trim(),
      licence: licence.value,
      source: source.value,
      order: order.value,
      page: page
    };
    f.min = number(f.rmin);
    f.max = number(f.rmax);
    f.typed = f.q.split(/\s+/).filter(function (w) { return w !== ''; });
    f.words = searchTokens(f.q);
    return f;
  }

  function hashOf(f) {
    var p = new URLSearchParams();
    if (f.family) p.set('family', f.family);
    if (f.rmin) p.set('rmin', f.rmin);
    if (f.rmax) p.set('rmax', f.rmax);
    if (f.q) p.set('q', f.q);
    if (f.licence) p.set('licence', f.licence);
    if (f.source) p.set('source', f.source);
    if (f.order) p.set('order', f.order);
    if (f.page > 1) p.set('page', String(f.page));
    if (ticked.length) p.set('cmp', ticked.join(','));
    return p.toString();
  }

  function shownRoughness(r) { return Number(r.toPrecision(3)); }
  function within(r, f) { return (f.min === null || r >= f.min) && (f.max === null || r <= f.max); }

  // The indices of the entries that pass the filters, in the library's order or by roughness (the
  // entries without one, having no texture, last; equal ones by name). An entry without a roughness
  // passes only while no roughness bound is set. A source kind keeps the entries with a `source`
  // note of that kind; "none", those with no note at all.
  var last = {key: null, shown: null};
  function filtered(f) {
    var key = JSON.stringify([f.family, f.min, f.max, f.typed, f.licence, f.source, f.order]);
    if (key === last.key) return last.shown;
    var fam = f.family === '' ? null : f.family === '(none)' ? -1 : familyOf[f.family];
    var lic = f.licence === '' ? null : f.licence === '(none)' ? '' : f.licence;
    var bit = f.source === '' || f.source === 'none' ? 0 : SOURCE_BITS[f.source] || -1;
    var ranged = f.min !== null || f.max !== null;
    var exact = exactRanks(f.typed);
    var rank = f.words.length || f.typed.length ? new Float64Array(total) : null;  // lower first
    var stimulus = data.families.map(function (x) { return !!x.stimulus; });
    var shown = [];
    for (var i = 0; i < total; i++) {
      if (fam !== null && data.family[i] !== fam) continue;
      if (lic !== null && data.licence[i] !== lic) continue;
      if (f.source === 'none' ? data.sources[i] !== 0 : bit !== 0 && !(data.sources[i] & bit)) continue;
      if (ranged) {
        var r = data.roughness[i];
        // In when the roughness kept or the one shown (3 significant digits) is, as `library search
        // --roughness` takes it: an entry shown as 0.0982 is within ..0.0982 whatever digits follow.
        if (r === null || !(within(r, f) || within(shownRoughness(r), f))) continue;
      }
      if (rank) {
        // Exact names, then exact aliases, then word matches by score; a published stimulus set's
        // word matches after the materials unless the family filter names theirs.
        if (i in exact) rank[i] = exact[i];
        else {
          var score = f.words.length ? wordScore(f.words, i) : 0;
          if (score === 0) continue;
          rank[i] = (fam === null && stimulus[data.family[i]] ? 3 : 2) - score / 1e6;
        }
      }
      shown.push(i);
    }
    if (rank && !f.order) shown.sort(function (a, b) { return rank[a] - rank[b] || a - b; });
    if (f.order === 'roughness' || f.order === '-roughness') {
      var sign = f.order === 'roughness' ? 1 : -1;
      shown.sort(function (a, b) {
        var ra = data.roughness[a], rb = data.roughness[b];
        if (ra === null || rb === null) return ra === rb ? a - b : ra === null ? 1 : -1;
        return ra !== rb ? sign * (ra - rb) : a - b;
      });
    }
    last = {key: key, shown: shown};
    return shown;
  }

  function element(tag, attributes, text) {
    var e = document.createElement(tag);
    for (var a in attributes) e.setAttribute(a, attributes[a]);
    if (text !== undefined) e.textContent = text;
    return e;
  }

  function row(i) {
    var name = data.name[i];
    var page = 'entries/' + encodeURIComponent(name) + '.html';
    var deprecatedBy = data.deprecated_by[i];
    var tr = element('tr', {'data-name': name});
    if (deprecatedBy) tr.className = 'deprecated';

    var pick = element('td', {'class': 'pick'});
    var box = element('input', {type: 'checkbox', 'aria-label': 'compare ' + name});
    box.checked = ticked.indexOf(name) >= 0;
    box.addEventListener('change', function () { tick(name, box.checked); });
    pick.appendChild(box);
    tr.appendChild(pick);

    var thumb = element('td', {'class': 'thumb'});
    if (noThumbnail[i]) {
      thumb.appendChild(element('span', {'class': 'no-thumb', title: 'no position-dependent force to draw'}, '\u2014'));
    } else {
      // The name's link is the one in the tab order; this one repeats it for the mouse.
      var a = element('a', {href: page, tabindex: '-1'});
      a.appendChild(element('img', {src: 'entries/' + encodeURIComponent(name) + '-thumb.png', alt: '', width: '64',
                                    height: '64', loading: 'lazy', decoding: 'async'}));
      thumb.appendChild(a);
    }
    tr.appendChild(thumb);

    var cell = element('td', {'class': 'name'});
    cell.appendChild(element('a', {href: page}, name));
    var aliases = aliasesOf(i);
    if (aliases.length) cell.appendChild(element('div', {'class': 'aliases'}, aliases.join(', ')));
    if (deprecatedBy) cell.appendChild(element('div', {'class': 'deprecated-tag'}, 'deprecated: use ' + deprecatedBy));
    if (data.root[i]) cell.appendChild(element('div', {'class': 'root-tag'}, 'from ' + data.root[i]));
    tr.appendChild(cell);

    var f = data.families[data.family[i]];
    var fam = element('td', {'class': 'family'});
    if (f) fam.textContent = f.title;
    else fam.appendChild(element('span', {'class': 'muted'}, '\u2014'));
    tr.appendChild(fam);

    var r = data.roughness[i];
    tr.appendChild(element('td', {'class': 'num'}, r === null ? '\u2014' : String(shownRoughness(r))));
    tr.appendChild(element('td', {}, data.describes[i]));
    return tr;
  }

  var current = null;  // the state shown: readControls' object with the page clamped

  // The compare bar: how many are ticked, and the link to see them side by side.
  function showTicked() {
    compareBar.hidden = ticked.length === 0;
    compareCount.textContent = ticked.length + (ticked.length === 1 ? ' entry ticked: tick another to compare'
                                                                      : ' entries ticked');
    var p = new URLSearchParams();
    ticked.forEach(function (n) { p.append('e', n); });
    compareGo.href = 'assets/compare.html#' + p.toString();
    compareGo.setAttribute('aria-disabled', ticked.length < 2 ? 'true' : 'false');
    compareGo.classList.toggle('disabled', ticked.length < 2);
  }

  function tick(name, on) {
    var at = ticked.indexOf(name);
    if (on && at < 0) ticked.push(name);
    if (!on && at >= 0) ticked.splice(at, 1);
    showTicked();
    writeHash(current, false);
  }

  function render(f) {
    var shown = filtered(f);
    var pages = Math.max(1, Math.ceil(shown.length / PAGE_SIZE));
    f.page = Math.min(Math.max(1, Math.floor(f.page) || 1), pages);
    var from = (f.page - 1) * PAGE_SIZE, to = Math.min(from + PAGE_SIZE, shown.length);
    var rows = document.createDocumentFragment();
    for (var k = from; k < to; k++) rows.appendChild(row(shown[k]));
    tbody.textContent = '';
    tbody.appendChild(rows);

    count.textContent = shown.length === total ? grouped(total) + (total === 1 ? ' entry' : ' entries')
                                               : grouped(shown.length) + ' of ' + grouped(total) +
                                                 (total === 1 ? ' entry matches' : shown.length === 1 ? ' entries matches' : ' entries match');
    none.hidden = shown.length !== 0;
    var where = 'page ' + grouped(f.page) + ' of ' + grouped(pages) +
                (shown.length ? ' (' + grouped(from + 1) + '\u2013' + grouped(to) + ')' : '');
    pagers.forEach(function (nav) {
      nav.hidden = pages <= 1;
      nav.querySelector('.page-of').textContent = where;
      nav.querySelector('.prev').disabled = f.page <= 1;
      nav.querySelector('.next').disabled = f.page >= pages;
    });
    // A button that turned disabled under the keyboard's focus would drop the focus to the page's start.
    var focused = document.activeElement;
    if (focused && focused.disabled && focused.closest('nav.pager')) {
      var other = focused.closest('nav.pager').querySelector(focused.classList.contains('next') ? '.prev' : '.next');
      if (!other.disabled) other.focus();
    }
    document.body.setAttribute('data-shown', String(shown.length));
    document.body.setAttribute('data-page', String(f.page));
    document.body.setAttribute('data-pages', String(pages));
    current = f;
  }

  // Typing in a filter replaces the history entry (one per keystroke would bury the page before it);
  // turning a page adds one, so that Back turns it back.
  function writeHash(f, push) {
    var hash = hashOf(f);
    if (location.hash.replace(/^#/, '') === hash) return;
    var url = location.href.split('#')[0] + (hash ? '#' + hash : '');
    try {
      if (push) history.pushState(null, '', url);
      else history.replaceState(null, '', url);
    } catch (err) {
      location.hash = hash;
    }
  }

  function readHash() {
    var p = new URLSearchParams(location.hash.replace(/^#/, ''));
    family.value = p.get('family') || '';
    if (family.selectedIndex < 0) family.value = '';
    rmin.value = p.get('rmin') || '';
    rmax.value = p.get('rmax') || '';
    q.value = p.get('q') || '';
    [[licence, 'licence'], [source, 'source'], [order, 'order']].forEach(function (c) {
      c[0].value = p.get(c[1]) || '';
      if (c[0].selectedIndex < 0) c[0].value = '';
    });
    ticked = (p.get('cmp') || '').split(',').filter(function (n) { return n !== '' && n in indexOfName; });
    showTicked();
    return readControls(Number(p.get('page')) || 1);
  }

  function filtersChanged() {
    render(readControls(1));
    writeHash(current, false);
  }

  function turn(step, nav) {
    var f = readControls(current.page + step);
    render(f);
    writeHash(current, true);
    // From the bottom pager, show the new page from its first row.
    if (nav.id === 'pager-bottom') document.getElementById('entries').scrollIntoView();
  }

  [family, rmin, rmax, q, licence, source, order].forEach(function (el) {
    el.addEventListener('input', filtersChanged);
    el.addEventListener('change', filtersChanged);
  });
  document.getElementById('clear').addEventListener('click', function () {
    family.value = licence.value = source.value = order.value = '';
    rmin.value = rmax.value = q.value = '';
    filtersChanged();
  });
  document.getElementById('compare-clear').addEventListener('click', function () {
    ticked = [];
    Array.prototype.forEach.call(tbody.querySelectorAll('td.pick input'), function (b) { b.checked = false; });
    showTicked();
    writeHash(current, false);
  });
  compareGo.addEventListener('click', function (ev) { if (ticked.length < 2) ev.preventDefault(); });
  pagers.forEach(function (nav) {
    nav.querySelector('.prev').addEventListener('click', function () { turn(-1, nav); });
    nav.querySelector('.next').addEventListener('click', function () { turn(1, nav); });
  });
  // Back and Forward between pages fire popstate; a hash typed into the address bar fires hashchange.
  function restore() {
    if (current && location.hash.replace(/^#/, '') === hashOf(current)) return;
    render(readHash());
  }
  window.addEventListener('popstate', restore);
  window.addEventListener('hashchange', restore);

  render(readHash());
  writeHash(current, false);  // a page past the last, or a family the library lacks, as shown
  if (window.performance && performance.mark) performance.mark('catalog-first-rows');
  document.body.setAttribute('data-ready', 'true');
})();
