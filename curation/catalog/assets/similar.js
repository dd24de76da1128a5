// An entry page's similar entries: the nearest in the index's data (catalog-data.js and its parts),
// by the distance `sandpaper library near` measures (curation/src/near.cpp, docs/LIBRARY.md
// "Perceptual distance") over what the data holds: the texture's maximum lateral force in force JND
// steps, its spatial period (kJndPerPeriodDoubling steps a doubling), and a kind or terms that differ.
// Read in the browser rather than written into the page, so that a page need not be drawn again when
// another entry changes. The page's body carries the entry's name and the Weber fraction.
(function () {
  'use strict';
  var LIMIT = 5, JND_PER_PERIOD_DOUBLING = 4, KIND_STEPS = 8, TEXTURE_STEPS = 20;  // near.hpp's weights
  var list = document.getElementById('similar-list');
  if (!list) return;
  var me = document.body.getAttribute('data-entry');
  var weber = Number(document.body.getAttribute('data-weber'));

  function say(text) {
    list.textContent = '';
    var li = document.createElement('li');
    li.className = 'muted';
    li.textContent = text;
    list.appendChild(li);
  }

  var load = window.sandpaperLoadScript;  // assets/load.js

  function partFile(k) { return '../catalog-data/part-' + String(k).padStart(5, '0') + '.js'; }

  function distance(a, b) {
    var ta = a.force > 0, tb = b.force > 0, d2 = 0, extra = 0;
    if (ta && tb) {
      var f = Math.log(b.force / a.force) / Math.log1p(weber);
      d2 += f * f;
      if (a.period > 0 && b.period > 0) {
        var p = JND_PER_PERIOD_DOUBLING * Math.log2(b.period / a.period);
        d2 += p * p;
      } else if ((a.period > 0) !== (b.period > 0)) {
        extra += JND_PER_PERIOD_DOUBLING;
      }
      if (a.kind !== b.kind) extra += KIND_STEPS;
    } else if (ta !== tb) {
      extra += TEXTURE_STEPS;
    }
    if (a.terms !== b.terms) extra += KIND_STEPS;
    return Math.sqrt(d2) + extra;
  }

  function show(parts) {
    parts.sort(function (x, y) { return x.part - y.part; });
    var rows = [];
    parts.forEach(function (p) {
      for (var i = 0; i < p.name.length; i++) {
        var kt = p.kind[i].split('|');
        rows.push({name: p.name[i], force: p.force_N[i], period: p.period_m[i], kind: kt[0], terms: kt[1] || '',
                   roughness: p.roughness[i]});
      }
    });
    var self = rows.filter(function (r) { return r.name === me; })[0];
    if (!self || !(weber > 0)) { say('This entry is not in the index\u2019s data.'); return; }
    var near = rows.filter(function (r) { return r.name !== me; }).map(function (r) {
      return {row: r, d: distance(self, r)};
    });
    near.sort(function (x, y) { return x.d - y.d || (x.row.name < y.row.name ? -1 : x.row.name > y.row.name ? 1 : 0); });
    near = near.slice(0, LIMIT);
    list.textContent = '';
    if (!near.length) say('No other entry.');
    near.forEach(function (n) {
      var li = document.createElement('li');
      li.setAttribute('data-name', n.row.name);
      var a = document.createElement('a');
      a.href = encodeURIComponent(n.row.name) + '.html';
      a.textContent = n.row.name;
      li.appendChild(a);
      li.appendChild(document.createTextNode(' \u00b7 ' + n.d.toFixed(1) + ' JND' +
        (n.row.roughness === null ? '' : ' \u00b7 roughness ' + Number(n.row.roughness.toPrecision(3)))));
      list.appendChild(li);
    });
    var compare = document.createElement('li');
    compare.className = 'compare-link';
    var q = new URLSearchParams();
    q.append('e', me);
    near.slice(0, 3).forEach(function (n) { q.append('e', n.row.name); });
    var a = document.createElement('a');
    a.href = '../assets/compare.html#' + q.toString();
    a.textContent = 'compare ' + me + ' with the nearest ' + Math.min(3, near.length) + ' side by side';
    compare.appendChild(a);
    if (near.length) list.appendChild(compare);
    document.body.setAttribute('data-similar', 'ready');
  }

  load('../catalog-data.js', function (ok) {
    var head = window.sandpaperCatalog;
    if (!ok || !head || head.format !== 3) {
      say('The index\u2019s data (catalog-data.js beside index.html) is missing or from another version.');
      document.body.setAttribute('data-similar', 'error');
      return;
    }
    var left = head.parts.length, failed = false;
    if (left === 0) { show([]); return; }
    for (var k = 0; k < head.parts.length; k++)
      load(partFile(k), function (loaded) {
        failed = failed || !loaded;
        if (--left > 0) return;
        var parts = window.sandpaperCatalogParts || [];
        if (failed || parts.length !== head.parts.length) {
          say('A part of the index\u2019s data (catalog-data/) is missing.');
          document.body.setAttribute('data-similar', 'error');
        } else {
          show(parts.slice());
        }
      });
  });
})();
