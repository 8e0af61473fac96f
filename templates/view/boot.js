// worldgen's page loader: three.js and the page's own module are inlined as text (or three.js comes from the
// report folder's shared copy, a plain script beside the page defining window.worldgenLibraries); each becomes a
// blob: URL with its imports pointed at the others' URLs, so the page loads nothing from outside its folder.
(function () {
  'use strict';
  var status = document.getElementById('status');
  var shared = window.worldgenLibraries;
  function text(id) {
    var inlined = document.getElementById(id);
    if (inlined) { return inlined.textContent; }
    var name = id.replace(/^lib-/, '');
    if (shared && typeof shared[name] === 'string') { return shared[name]; }
    throw new Error('three.js did not load: keep this page in its folder, beside the three.js file it shares');
  }
  function url(code) { return URL.createObjectURL(new Blob([code], { type: 'text/javascript' })); }
  function link(code, map) {
    return code.replace(/(\bfrom\s*)(['"])([^'"]+)\2/g, function (whole, from, quote, name) {
      return Object.prototype.hasOwnProperty.call(map, name) ? from + quote + map[name] + quote : whole;
    });
  }
  function fail(err) {
    status.hidden = false;
    status.textContent = 'This page could not start: ' + err;
    console.error(err);
  }
  try {
    var map = { 'three': url(text('lib-three')) };
    map['../utils/BufferGeometryUtils.js'] = url(link(text('lib-BufferGeometryUtils'), map));
    map['three/addons/loaders/GLTFLoader.js'] = url(link(text('lib-GLTFLoader'), map));
    map['three/addons/controls/OrbitControls.js'] = url(link(text('lib-OrbitControls'), map));
    import(url(link(text('lib-app'), map))).then(function (app) { return app.start(); }).catch(fail);
  } catch (err) {
    fail(err);
  }
})();
