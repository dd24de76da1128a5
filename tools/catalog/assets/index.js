// The catalog index: a page of rows at a time from the entries in catalog-data.js and its parts,
// filtered by family, roughness range and words. The data comes by <script src> rather than fetch(),
// which browsers refuse for file://; it is columns of arrays (index_page.hpp, index_files), and only the rows of the
// page shown are ever made, so that 100,000 entries open as fast as 100. The filters and the page live
// in the URL hash (#family=textiles&rmin=0.2&rmax=0.5&q=silk&page=3), so a view can be bookmarked or
// shared and the back button returns to it.
(function () {
  'use strict';
  var PAGE_SIZE = 100;
  var family = document.getElementById('family');
  var rmin = document.getElementById('rmin');
  var rmax = document.getElementById('rmax');
  var q = document.getElementById('q');
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

  // The parts' columns end to end; a part's rows are numbered within it, so its aliases, deprecations
  // and missing thumbnails are shifted by the rows before it. Null if any part is missing or not its own.
  function joinParts(head, parts) {
    if (!head || head.format !== 2 || !Array.isArray(head.parts) || parts.length !== head.parts.length) return null;
    var d = {families: head.families, name: [], family: [], roughness: [], describes: [], aliases: {},
             deprecated_by: {}, no_thumbnail: []};
    for (var k = 0; k < parts.length; k++) {
      var p = parts[k], base = d.name.length;
      if (!p || p.format !== 2 || p.part !== k || p.name.length !== head.parts[k].rows) return null;
      ['name', 'family', 'roughness', 'describes'].forEach(function (c) { Array.prototype.push.apply(d[c], p[c]); });
      Object.keys(p.aliases).forEach(function (i) { d.aliases[base + Number(i)] = p.aliases[i]; });
      Object.keys(p.deprecated_by).forEach(function (i) { d.deprecated_by[base + Number(i)] = p.deprecated_by[i]; });
      p.no_thumbnail.forEach(function (i) { d.no_thumbnail.push(base + i); });
    }
    return d.name.length === head.entries ? d : null;
  }

  function grouped(n) { return n.toLocaleString('en-US'); }

  function aliasesOf(i) { return data.aliases[i] || []; }

  function haystack(i) {
    if (haystacks === null) {
      haystacks = new Array(total);
      for (var k = 0; k < total; k++) {
        var f = data.families[data.family[k]];
        haystacks[k] = [data.name[k], aliasesOf(k).join(' '), data.describes[k], f ? f.id : '', f ? f.title : '']
                           .join(' ').toLowerCase();
      }
    }
    return haystacks[i];
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
      page: page
    };
    f.min = number(f.rmin);
    f.max = number(f.rmax);
    f.words = f.q.toLowerCase().split(/\s+/).filter(function (w) { return w !== ''; });
    return f;
  }

  function hashOf(f) {
    var p = new URLSearchParams();
    if (f.family) p.set('family', f.family);
    if (f.rmin) p.set('rmin', f.rmin);
    if (f.rmax) p.set('rmax', f.rmax);
    if (f.q) p.set('q', f.q);
    if (f.page > 1) p.set('page', String(f.page));
    return p.toString();
  }

  // The indices of the entries that pass the filters, in the library's order. An entry without a
  // roughness (no texture) passes only while no roughness bound is set.
  var last = {key: null, shown: null};
  function filtered(f) {
    var key = JSON.stringify([f.family, f.min, f.max, f.words]);
    if (key === last.key) return last.shown;
    var fam = f.family === '' ? null : f.family === '(none)' ? -1 : familyOf[f.family];
    var ranged = f.min !== null || f.max !== null;
    var shown = [];
    for (var i = 0; i < total; i++) {
      if (fam !== null && data.family[i] !== fam) continue;
      if (ranged) {
        var r = data.roughness[i];
        if (r === null || (f.min !== null && r < f.min) || (f.max !== null && r > f.max)) continue;
      }
      if (f.words.length) {
        var h = haystack(i), ok = true;
        for (var w = 0; w < f.words.length && ok; w++) ok = h.indexOf(f.words[w]) >= 0;
        if (!ok) continue;
      }
      shown.push(i);
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
    tr.appendChild(cell);

    var f = data.families[data.family[i]];
    var fam = element('td', {'class': 'family'});
    if (f) fam.textContent = f.title;
    else fam.appendChild(element('span', {'class': 'muted'}, '\u2014'));
    tr.appendChild(fam);

    var r = data.roughness[i];
    tr.appendChild(element('td', {'class': 'num'}, r === null ? '\u2014' : String(Number(r.toPrecision(3)))));
    tr.appendChild(element('td', {}, data.describes[i]));
    return tr;
  }

  var current = null;  // the state shown: readControls' object with the page clamped

  function render(f) {
    var shown = filtered(f);
    var pages = Math.max(1, Math.ceil(shown.length / PAGE_SIZE));
    f.page = Math.min(Math.max(1, Math.floor(f.page) || 1), pages);
    var from = (f.page - 1) * PAGE_SIZE, to = Math.min(from + PAGE_SIZE, shown.length);
    var rows = document.createDocumentFragment();
    for (var k = from; k < to; k++) rows.appendChild(row(shown[k]));
    tbody.textContent = '';
    tbody.appendChild(rows);

    count.textContent = shown.length === total ? grouped(total) + ' entries'
                                               : grouped(shown.length) + ' of ' + grouped(total) + ' entries match';
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

  [family, rmin, rmax, q].forEach(function (el) {
    el.addEventListener('input', filtersChanged);
    el.addEventListener('change', filtersChanged);
  });
  document.getElementById('clear').addEventListener('click', function () {
    family.value = '';
    rmin.value = rmax.value = q.value = '';
    filtersChanged();
  });
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
