// The compare page: the entries named in the hash (#e=corduroy&e=pinwale-corduroy), each read from
// its entries/<name>.compare.js (compare_data.hpp), side by side: the thumbnails, which all show the
// same square at one scale, the numbers, and the force along a scan line on shared axes.
(function () {
  'use strict';
  var PICTURE_PX = 256;  // CSS pixels a picture's square is drawn at: the same for every entry
  var names = new URLSearchParams(location.hash.replace(/^#/, '')).getAll('e')
    .filter(function (n, i, all) { return n !== '' && all.indexOf(n) === i; });
  var table = document.getElementById('compare');
  var missingNote = document.getElementById('compare-missing');

  function element(tag, attributes, text) {
    var e = document.createElement(tag);
    for (var a in attributes) e.setAttribute(a, attributes[a]);
    if (text !== undefined) e.textContent = text;
    return e;
  }
  function svg(tag, attributes, text) {
    var e = document.createElementNS('http://www.w3.org/2000/svg', tag);
    for (var a in attributes) e.setAttribute(a, attributes[a]);
    if (text !== undefined) e.textContent = text;
    return e;
  }
  function digits(v, n) { return String(Number(v.toPrecision(n))); }
  function page(name) { return '../entries/' + encodeURIComponent(name) + '.html'; }

  var load = window.sandpaperLoadScript;  // assets/load.js

  // 1, 2 or 5 times a power of ten, about `target` steps over [lo, hi] (plot.hpp's nice_ticks).
  function ticks(lo, hi, target) {
    var raw = (hi - lo) / target, mag = Math.pow(10, Math.floor(Math.log10(raw))), r = raw / mag;
    var step = (r >= 5 ? 5 : r >= 2 ? 2 : 1) * mag, out = [];
    for (var t = Math.ceil(lo / step - 1e-9) * step; t <= hi + step * 1e-9; t += step) out.push(Math.abs(t) < step * 1e-9 ? 0 : t);
    return out;
  }

  function row(label, cells) {
    var tr = element('tr');
    tr.appendChild(element('th', {scope: 'row'}, label));
    cells.forEach(function (c) {
      var td = element('td');
      if (typeof c === 'string') td.textContent = c;
      else td.appendChild(c);
      tr.appendChild(td);
    });
    return tr;
  }

  function picture(e) {
    var fig = element('figure', {'class': 'compare-picture'});
    if (e.thumbnail) {
      fig.appendChild(element('img', {src: '../entries/' + encodeURIComponent(e.thumbnail), width: String(PICTURE_PX),
                                      height: String(PICTURE_PX), alt: 'shaded height field of ' + e.name,
                                      'data-window-mm': String(e.window_m * 1e3)}));
    } else {
      fig.appendChild(element('div', {'class': 'no-picture', style: 'width:' + PICTURE_PX + 'px;height:' + PICTURE_PX + 'px'},
                              'no position-dependent force to draw'));
    }
    return fig;
  }

  function scaleBar(windowMm) {
    var mm = windowMm >= 40 ? 10 : windowMm >= 8 ? 2 : 0.5;
    var bar = element('div', {'class': 'scale-bar'});
    bar.appendChild(element('span', {'class': 'bar', style: 'width:' + (mm / windowMm * PICTURE_PX) + 'px'}));
    bar.appendChild(element('span', {}, ' ' + mm + ' mm'));
    return bar;
  }

  function plot(e, axes) {
    var W = 640, H = 182, left = 66, right = 626, top = 14, bottom = 140;
    var x = function (mm) { return left + (mm - axes.x0) / (axes.x1 - axes.x0) * (right - left); };
    var y = function (n) { return bottom - (n - axes.y0) / (axes.y1 - axes.y0) * (bottom - top); };
    var s = svg('svg', {'class': 'force-plot', viewBox: '0 0 ' + W + ' ' + H, role: 'img', 'data-name': e.name,
                        'data-y-max': String(axes.y1), 'aria-label': 'lateral force of ' + e.name});
    ticks(axes.y0, axes.y1, 4).forEach(function (t) {
      s.appendChild(svg('line', {'class': 'grid' + (t === 0 ? ' zero' : ''), x1: left, x2: right, y1: y(t), y2: y(t)}));
      s.appendChild(svg('text', {x: left - 6, y: y(t) + 4, 'text-anchor': 'end'}, digits(t, 3)));
    });
    ticks(axes.x0, axes.x1, 8).forEach(function (t) {
      s.appendChild(svg('text', {x: x(t), y: bottom + 16, 'text-anchor': 'middle'}, digits(t, 3)));
    });
    s.appendChild(svg('rect', {'class': 'frame', x: left, y: top, width: right - left, height: bottom - top, fill: 'none'}));
    var pts = e.scan.s_mm.map(function (mm, i) { return x(mm).toFixed(2) + ',' + y(e.scan.along_N[i]).toFixed(2); });
    s.appendChild(svg('polyline', {'class': 'force-along', fill: 'none', points: pts.join(' ')}));
    s.appendChild(svg('text', {'class': 'axis-label', x: (left + right) / 2, y: H - 4, 'text-anchor': 'middle'},
                      'position along the scan (mm)'));
    s.appendChild(svg('text', {'class': 'axis-label', x: 14, y: (top + bottom) / 2, 'text-anchor': 'middle',
                               transform: 'rotate(-90 14 ' + (top + bottom) / 2 + ')'}, 'force (N)'));
    var fig = element('figure', {'class': 'plot'});
    fig.appendChild(element('figcaption', {}, e.name + ': ' + e.scan.description));
    fig.appendChild(s);
    return fig;
  }

  function show(entries, missing) {
    if (missing.length) {
      missingNote.hidden = false;
      missingNote.textContent = 'Not in this catalog: ' + missing.join(', ') + '.';
    }
    if (!entries.length) {
      document.getElementById('compare-what').textContent = names.length
        ? 'None of the entries named is in this catalog.'
        : 'No entries named: tick two or more in the index and choose \u201cCompare side by side\u201d.';
      document.body.setAttribute('data-ready', 'true');
      return;
    }
    var head = element('tr');
    head.appendChild(element('th', {scope: 'col'}));
    entries.forEach(function (e) {
      var th = element('th', {scope: 'col', 'data-name': e.name});
      th.appendChild(element('a', {href: page(e.name)}, e.name));
      head.appendChild(th);
    });
    table.tHead.appendChild(head);
    var windowMm = entries[0].window_m * 1e3;
    var body = table.tBodies[0];
    body.appendChild(row('height field, ' + digits(windowMm, 3) + ' mm square', entries.map(picture)));
    body.appendChild(row('scale', entries.map(function () { return scaleBar(windowMm); })));
    body.appendChild(row('describes', entries.map(function (e) { return e.describes; })));
    body.appendChild(row('roughness (compiled)', entries.map(function (e) {
      return e.roughness === null ? '\u2014 (no texture)' : digits(e.roughness, 3);
    })));
    body.appendChild(row('maximum lateral force', entries.map(function (e) {
      return e.max_lateral_force_N > 0 ? digits(e.max_lateral_force_N, 3) + ' N' : '\u2014';
    })));
    // A photograph has no period: its scale (the period of a sinusoid whose heights decorrelate as
    // fast; docs/LIBRARY.md, "near") stands in for it, and says so.
    body.appendChild(row('spatial period', entries.map(function (e) {
      return !(e.period_m > 0) ? '\u2014' : digits(e.period_m * 1e3, 3) + ' mm' + (e.kind === 'image' ? ' (scale of a photograph)' : '');
    })));
    body.appendChild(row('texture', entries.map(function (e) { return e.kind || '\u2014'; })));
    body.appendChild(row('terms', entries.map(function (e) { return e.terms || '\u2014'; })));
    body.appendChild(row('family', entries.map(function (e) { return e.family || '\u2014'; })));
    body.appendChild(row('sources', entries.map(function (e) { return e.sources.length ? e.sources.join(', ') : 'none stated'; })));
    body.appendChild(row('licence', entries.map(function (e) { return e.licence || 'not stated'; })));
    if (entries.some(function (e) { return e.root; }))
      body.appendChild(row('root', entries.map(function (e) { return e.root; })));
    body.appendChild(row('compiled for', entries.map(function (e) { return e.device; })));

    // One scale: every scan's span and the largest force of any of them, symmetric about zero.
    var axes = {x0: Infinity, x1: -Infinity, y1: 0};
    entries.forEach(function (e) {
      axes.x0 = Math.min(axes.x0, e.scan.s_mm[0]);
      axes.x1 = Math.max(axes.x1, e.scan.s_mm[e.scan.s_mm.length - 1]);
      e.scan.along_N.forEach(function (f) { axes.y1 = Math.max(axes.y1, Math.abs(f)); });
    });
    if (!(axes.y1 > 0)) axes.y1 = 1;
    axes.y1 = ticks(0, axes.y1 * 1.05, 3).filter(function (t) { return t >= axes.y1; })[0] || axes.y1 * 1.05;
    axes.y0 = -axes.y1;
    var plots = document.getElementById('plots');
    entries.forEach(function (e) { plots.appendChild(plot(e, axes)); });
    document.getElementById('compare-force-how').textContent =
      'The force the runtime\u2019s evaluator returns as the hand moves at ' + digits(entries[0].scan.speed_m_s * 1e3, 3) +
      ' mm/s; the component along the scan, on the same axes for every entry (\u00b1' + digits(axes.y1, 3) + ' N).';
    document.getElementById('compare-force').hidden = false;
    document.title = 'Compare ' + entries.map(function (e) { return e.name; }).join(', ') + ' \u2014 Sandpaper catalog';
    document.body.setAttribute('data-ready', 'true');
  }

  if (!names.length) { show([], []); return; }
  var left = names.length;
  names.forEach(function (n) {
    load('../entries/' + encodeURIComponent(n) + '.compare.js', function () {
      if (--left > 0) return;
      var got = Object.create(null);
      (window.sandpaperCompare || []).forEach(function (e) { if (e && e.format === 1) got[e.name] = e; });
      show(names.filter(function (m) { return m in got; }).map(function (m) { return got[m]; }),
           names.filter(function (m) { return !(m in got); }));
    });
  });
})();
