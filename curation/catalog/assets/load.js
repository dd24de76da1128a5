// Loads a script by <script src> (browsers refuse fetch() of file://, a script tag is not refused),
// after those added before it (async off): done(true) once it ran, done(false) if it failed to load.
// Used by the compare page and the entry pages' similar entries.
window.sandpaperLoadScript = function (src, done) {
  'use strict';
  var s = document.createElement('script');
  s.src = src;
  s.async = false;
  s.onload = function () { done(true); };
  s.onerror = function () { done(false); };
  document.body.appendChild(s);
};
