"""The browser harness of the 3D pages' tests can fail: a request leaving the file, an error on the console and an
uncaught exception are each recorded, and a clean page with a WebGL2 canvas records nothing. Also: the vendored
three.js runs in it offline, imported from blob: URLs made of inlined text, as the pages will do."""

from __future__ import annotations

from pathlib import Path

from browserpage import open_page


def _page(tmp_path: Path, body: str, name: str = "page.html") -> Path:
    path = tmp_path / name
    path.write_text(f"<!doctype html><html><head><meta charset='utf-8'><title>t</title></head><body>{body}</body>"
                    "</html>", encoding="utf-8")
    return path


def test_a_request_off_the_file_is_recorded_and_aborted(chromium, tmp_path):
    page = _page(tmp_path, "<script src='https://example.invalid/x.js'></script>"
                           "<script>window.loaded = typeof window.fromNetwork;</script>")
    with open_page(chromium, page) as probe:
        assert probe.left_file == ["https://example.invalid/x.js"]
        assert probe.page.evaluate("window.loaded") == "undefined"   # aborted: nothing ran from it


def test_fetch_and_websocket_off_the_file_are_recorded(chromium, tmp_path):
    page = _page(tmp_path, "<script>fetch('http://example.invalid/data.json').catch(() => {});"
                           "new WebSocket('wss://example.invalid/socket');</script>")
    with open_page(chromium, page) as probe:
        assert probe.wait_until(lambda: len(probe.left_file) == 2), probe.left_file
        assert sorted(probe.left_file) == ["http://example.invalid/data.json", "wss://example.invalid/socket"]


def test_console_error_is_recorded(chromium, tmp_path):
    with open_page(chromium, _page(tmp_path, "<script>console.error('boom', 42)</script>")) as probe:
        assert len(probe.console_errors) == 1 and probe.console_errors[0].startswith("console: boom 42")
        assert probe.left_file == []


def test_uncaught_exception_is_recorded(chromium, tmp_path):
    with open_page(chromium, _page(tmp_path, "<script>throw new Error('kaboom')</script>")) as probe:
        assert probe.console_errors == ["pageerror: kaboom"] or \
            any("kaboom" in e and e.startswith("pageerror:") for e in probe.console_errors), probe.console_errors


def test_a_clean_webgl2_page_records_nothing(chromium, tmp_path):
    body = """<canvas id="c" width="64" height="48"></canvas><script>
      const gl = document.getElementById('c').getContext('webgl2', {preserveDrawingBuffer: true});
      gl.clearColor(1, 0.5, 0, 1); gl.clear(gl.COLOR_BUFFER_BIT);
      const px = new Uint8Array(4); gl.readPixels(10, 10, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, px);
      window.result = {webgl2: gl instanceof WebGL2RenderingContext, pixel: Array.from(px)};
    </script>"""
    with open_page(chromium, _page(tmp_path, body), viewport=(640, 480)) as probe:
        result = probe.page.evaluate("window.result")
        assert result["webgl2"] is True
        assert result["pixel"][0] == 255 and 120 <= result["pixel"][1] <= 135 and result["pixel"][2] == 0
        assert probe.page.evaluate("!!document.createElement('canvas').getContext('webgl2')")
        assert probe.page.viewport_size == {"width": 640, "height": 480}
        assert probe.console_errors == [] and probe.left_file == []


def test_vendored_three_renders_offline(chromium, tmp_path):
    from worldgen.view.vendor import modules

    texts = modules()
    inlined = "".join(f'<script type="text/x-three-module" id="{name}">{texts[name]}</script>'
                      for name in ("three", "OrbitControls"))
    boot = """<script>
      const url = (id) => URL.createObjectURL(new Blob([document.getElementById(id).textContent],
                                                       {type: 'text/javascript'}));
      const map = document.createElement('script');
      map.type = 'importmap';
      map.textContent = JSON.stringify({imports: {three: url('three')}});
      document.head.appendChild(map);
      const main = document.createElement('script');
      main.type = 'module';
      main.textContent = `
        import * as THREE from 'three';
        const {OrbitControls} = await import('${url('OrbitControls')}');
        const renderer = new THREE.WebGLRenderer({preserveDrawingBuffer: true});
        renderer.setSize(200, 150); document.body.appendChild(renderer.domElement);
        const scene = new THREE.Scene(); scene.background = new THREE.Color(0x0000ff);
        const camera = new THREE.PerspectiveCamera(50, 200 / 150, 0.1, 100); camera.position.set(0, 0, 3);
        new OrbitControls(camera, renderer.domElement);
        scene.add(new THREE.Mesh(new THREE.BoxGeometry(1, 1, 1), new THREE.MeshBasicMaterial({color: 0xff0000})));
        renderer.render(scene, camera);
        const gl = renderer.getContext(); const px = new Uint8Array(8);
        gl.readPixels(100, 75, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, px.subarray(0, 4));
        gl.readPixels(2, 2, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, px.subarray(4, 8));
        window.result = {revision: THREE.REVISION, webgl2: renderer.capabilities.isWebGL2 !== false,
                         centre: Array.from(px.subarray(0, 4)), corner: Array.from(px.subarray(4, 8))};`;
      document.body.appendChild(main);
    </script>"""
    page = _page(tmp_path, inlined + boot, "three.html")
    with open_page(chromium, page) as probe:
        probe.page.wait_for_function("window.result !== undefined")
        result = probe.page.evaluate("window.result")
        assert result["revision"] == "170"
        assert result["centre"][:3] == [255, 0, 0] and result["corner"][:3] == [0, 0, 255], result
        assert probe.console_errors == [] and probe.left_file == []
