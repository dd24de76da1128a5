// The catalog index's filters: family, roughness range and words. The entries come from the JSON
// embedded in the page (no fetch: it must work from file://); the filter state lives in the URL hash
// (#family=textiles&rmin=0.2&rmax=0.5&q=silk), so a filtered view can be bookmarked or shared.
(function () {
  'use strict';
  var data = JSON.parse(document.getElementById('catalog-data').textContent);
  var rows = {};
  Array.prototype.forEach.call(document.querySelectorAll('#entries tbody tr'), function (tr) {
    rows[tr.getAttribute('data-name')] = tr;
  });
  var family = document.getElementById('family');
  var rmin = document.getElementById('rmin');
  var rmax = document.getElementById('rmax');
  var q = document.getElementById('q');
  var count = document.getElementById('count');
  var none = document.getElementById('none');

  function number(input) {
    var text = input.value.trim();
    if (text === '') return null;
    var v = Number(text);
    return isFinite(v) ? v : null;
  }

  // An entry without a roughness (no texture) is shown only while no roughness bound is set.
  function matches(e, f) {
    if (f.family === '(none)' ? e.family !== '' : f.family !== '' && e.family !== f.family) return false;
    if (f.min !== null || f.max !== null) {
      if (e.roughness === null) return false;
      if (f.min !== null && e.roughness < f.min) return false;
      if (f.max !== null && e.roughness > f.max) return false;
    }
    if (f.words.length) {
      var hay = [e.name, e.aliases.join(' '), e.describes, e.family, e.family_title].join(' ').toLowerCase();
      for (var i = 0; i < f.words.length; i++) if (hay.indexOf(f.words[i]) < 0) return false;
    }
    return true;
  }

  function state() {
    return {
      family: family.value,
      min: number(rmin),
      max: number(rmax),
      words: q.value.toLowerCase().split(/\s+/).filter(function (w) { return w !== ''; })
    };
  }

  function writeHash() {
    var p = new URLSearchParams();
    if (family.value) p.set('family', family.value);
    if (rmin.value.trim()) p.set('rmin', rmin.value.trim());
    if (rmax.value.trim()) p.set('rmax', rmax.value.trim());
    if (q.value.trim()) p.set('q', q.value.trim());
    var hash = p.toString();
    var url = location.href.split('#')[0] + (hash ? '#' + hash : '');
    try {
      history.replaceState(null, '', url);
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
  }

  function apply() {
    var f = state();
    var shown = 0;
    data.entries.forEach(function (e) {
      var ok = matches(e, f);
      var tr = rows[e.name];
      if (tr) tr.hidden = !ok;
      if (ok) shown++;
    });
    count.textContent = shown === data.entries.length ? data.entries.length + ' entries'
                                                       : shown + ' of ' + data.entries.length + ' entries';
    none.hidden = shown !== 0;
    document.body.setAttribute('data-shown', String(shown));
  }

  function changed() {
    apply();
    writeHash();
  }

  [family, rmin, rmax, q].forEach(function (el) {
    el.addEventListener('input', changed);
    el.addEventListener('change', changed);
  });
  document.getElementById('clear').addEventListener('click', function () {
    family.value = '';
    rmin.value = rmax.value = q.value = '';
    changed();
  });
  window.addEventListener('hashchange', function () {
    readHash();
    apply();
  });
  readHash();
  apply();
  document.body.setAttribute('data-ready', 'true');
})();
