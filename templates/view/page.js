// worldgen's 3D page: a Gazebo world (and a run replayed in it) drawn with three.js from the data worldgen wrote
// into this file. Z is up and units are metres, as in Gazebo.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';

const WALL_CUT = '#3b3b3b';      // the plan's colours, as worldgen preview draws them
const OBSTACLE_CUT = '#2f6db5';
const DOOR = '#e08a1e';
const WINDOW = '#35b7d6';
const ROBOT = '#d62728';
const RAY_HIT = '#2ca02c';
const RAY_MISS = '#b0b0b0';
const PATH = '#1f77b4';
const BACKGROUND = '#c9ced6';

const data = JSON.parse(document.getElementById('worldgen-data').textContent);
const replay = data.replay || null;

function el(id) { return document.getElementById(id); }

function material(colour, alpha, extra) {
  const options = Object.assign({ color: new THREE.Color(colour) }, extra || {});
  if (alpha !== undefined && alpha < 1) Object.assign(options, { transparent: true, opacity: alpha, depthWrite: false });
  return new THREE.MeshLambertMaterial(options);
}

function primitive(item) {
  if (item.k === 'box') return new THREE.BoxGeometry(item.s[0], item.s[1], item.s[2]);
  if (item.k === 'cylinder') return new THREE.CylinderGeometry(item.r, item.r, item.l, 32).rotateX(Math.PI / 2);
  if (item.k === 'sphere') return new THREE.SphereGeometry(item.r, 24, 16);
  return null;
}

function place(object, item) {
  object.position.set(item.p[0], item.p[1], item.p[2]);
  object.quaternion.set(item.q[0], item.q[1], item.q[2], item.q[3]);
  return object;
}

function polygonShapes(polygons) {
  const shapes = [];
  for (const rings of polygons) {
    const shape = new THREE.Shape(rings[0].map(p => new THREE.Vector2(p[0], p[1])));
    for (const hole of rings.slice(1)) shape.holes.push(new THREE.Path(hole.map(p => new THREE.Vector2(p[0], p[1]))));
    shapes.push(shape);
  }
  return shapes;
}

function flat(polygons, colour, z, opacity) {
  const geometry = new THREE.ShapeGeometry(polygonShapes(polygons));
  const options = { color: new THREE.Color(colour), side: THREE.DoubleSide };
  if (opacity !== undefined) Object.assign(options, { transparent: true, opacity: opacity, depthWrite: false });
  const mesh = new THREE.Mesh(geometry, new THREE.MeshBasicMaterial(options));
  mesh.position.z = z;
  return mesh;
}

async function meshGeometries() {
  if (!data.glb) return {};
  const bytes = Uint8Array.from(atob(data.glb), c => c.charCodeAt(0));
  const gltf = await new GLTFLoader().parseAsync(bytes.buffer, '');
  const found = {};
  gltf.scene.traverse(node => {
    if (node.isMesh) found[node.name] = node.geometry;
    else if (node.name && /^m\d+$/.test(node.name)) node.traverse(child => { if (child.isMesh) found[node.name] = child.geometry; });
  });
  return found;
}

function triangles(geometry) {
  return (geometry.index ? geometry.index.count : geometry.attributes.position.count) / 3;
}

function label(object, text) { object.userData.label = text; return object; }

function sizeText(item) {
  if (item.k === 'box') return `box ${item.s.map(v => v.toFixed(2)).join(' × ')} m`;
  if (item.k === 'cylinder') return `cylinder r ${item.r.toFixed(2)} m, ${item.l.toFixed(2)} m long`;
  if (item.k === 'sphere') return `sphere r ${item.r.toFixed(2)} m`;
  return 'mesh';
}

function niceLength(span) {
  const target = span / 5;
  const power = Math.pow(10, Math.floor(Math.log10(target)));
  let best = power;
  for (const m of [1, 2, 5]) if (m * power <= target) best = m * power;
  return best;
}

class WorldView {
  constructor(container) {
    this.container = container;
    this.renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(1);
    this.renderer.localClippingEnabled = true;
    this.renderer.setClearColor(BACKGROUND);
    container.prepend(this.renderer.domElement);
    this.scene = new THREE.Scene();
    this.pickable = [];
    this.solids = [];   // what hides what is behind it: opaque walls and obstacles
    this.cut = [new THREE.Plane(new THREE.Vector3(0, 0, -1), data.plan.z[1])];
    this.cutMaterials = [];
    this.top = false;
    const [x0, y0, x1, y1] = data.bounds;
    this.centre = new THREE.Vector3((x0 + x1) / 2, (y0 + y1) / 2, 0);
    this.span = Math.max(x1 - x0, y1 - y0, 1);
    this.lights();
    this.perspective = new THREE.PerspectiveCamera(50, 1, 0.02, 500);
    this.perspective.up.set(0, 0, 1);
    this.ortho = new THREE.OrthographicCamera(-1, 1, 1, -1, 0.1, 200);
    this.ortho.up.set(0, 1, 0);
    this.camera = this.perspective;
    this.controls = new OrbitControls(this.camera, this.renderer.domElement);
    this.controls.addEventListener('change', () => this.render());
    this.home();
    new ResizeObserver(() => this.resize()).observe(container);
  }

  lights() {
    this.scene.add(new THREE.HemisphereLight(0xffffff, 0x7a7a7a, 2.2));
    const sun = new THREE.DirectionalLight(0xffffff, 1.4);
    sun.position.set(-0.5, -0.8, 1.5);
    this.scene.add(sun);
  }

  async build() {
    const geometries = await meshGeometries();
    const [fx0, fy0, fx1, fy1] = data.floor.box;   // a square floor of whole metres, its 1 m grid on metre lines
    const cells = 2 * Math.ceil(Math.max(fx1 - fx0, fy1 - fy0) / 2);
    const fx = Math.round((fx0 + fx1) / 2), fy = Math.round((fy0 + fy1) / 2);
    const floor = new THREE.Mesh(new THREE.PlaneGeometry(cells, cells),
      material(data.floor.c, 1, { polygonOffset: true, polygonOffsetFactor: 2, polygonOffsetUnits: 2 }));
    floor.position.set(fx, fy, 0);
    this.scene.add(floor);
    const grid = new THREE.GridHelper(cells, cells, 0x8a8a8a, 0x9c9c9c);
    grid.rotateX(Math.PI / 2);
    grid.position.set(fx, fy, 0.0005);
    this.grid = grid;
    this.scene.add(grid);
    for (const item of data.items) {
      let geometry = primitive(item);
      if (!geometry && item.m !== undefined) geometry = geometries['m' + item.m];
      if (!geometry) continue;
      const mat = material(item.c, item.a, item.m !== undefined ? { flatShading: true, side: THREE.DoubleSide } : {});
      if (item.g === 'wall' || item.g === 'obstacle') this.cutMaterials.push(mat);
      const mesh = place(new THREE.Mesh(geometry, mat), item);
      const kind = item.g === 'marking' ? 'floor marking' : item.g;
      this.scene.add(label(mesh, `${kind} ${item.n}: ${sizeText(item)}`));
      this.pickable.push(mesh);
      if ((item.g === 'wall' || item.g === 'obstacle') && !(item.a < 1) && triangles(geometry) <= 20000) {
        this.solids.push(mesh);   // (a bigger mesh is left out: testing the first view against it would be slow)
      }
    }
    this.plan = new THREE.Group();
    this.plan.add(flat(data.plan.walls, WALL_CUT, data.plan.z[1] + 0.001));
    this.plan.add(flat(data.plan.obstacles, OBSTACLE_CUT, data.plan.z[1] + 0.001));
    for (const o of data.openings) {   // the plan's openings: solid, as preview draws them
      const mark = new THREE.Mesh(new THREE.PlaneGeometry(o.s[0], o.s[1]),
        new THREE.MeshBasicMaterial({ color: o.type === 'door' ? DOOR : WINDOW }));
      mark.position.set(o.p[0], o.p[1], data.plan.z[1] + 0.002);
      mark.rotation.z = o.yaw;
      this.plan.add(label(mark, o.n));
      this.pickable.push(mark);
    }
    this.plan.visible = false;
    this.scene.add(this.plan);
    for (const room of data.plan.rooms) {
      const mesh = flat(room.poly, '#ffffff', 0.002, 0.0);
      this.scene.add(label(mesh, room.n));
      this.pickable.push(mesh);
    }
    this.openings = new THREE.Group();
    for (const o of data.openings) {
      const colour = o.type === 'door' ? DOOR : WINDOW;
      const box = new THREE.Mesh(new THREE.BoxGeometry(o.s[0], o.s[1] * 1.2, o.s[2]), material(colour, 0.35));
      box.position.set(o.p[0], o.p[1], o.p[2]);
      box.rotation.z = o.yaw;
      this.openings.add(label(box, o.n));
      this.pickable.push(box);
    }
    this.scene.add(this.openings);
    this.robot = this.buildRobot(data.robot, Boolean(data.robot.spawn) || Boolean(replay));
    for (const other of data.others || []) this.buildRobot(other, true);
    this.rays = new THREE.LineSegments(new THREE.BufferGeometry(),
      new THREE.LineBasicMaterial({ vertexColors: true, transparent: true, opacity: 0.45 }));
    this.rays.frustumCulled = false;
    this.rays.visible = false;
    this.scene.add(this.rays);
    if (data.rays) {
      this.setRays(data.rays);
      this.rays.visible = true;
      el('btn-rays').classList.add('on');
    }
    this.legend();
    this.homeAt = this.chooseHome();
    this.home();
  }

  buildRobot(spec, shown) {
    const group = new THREE.Group();
    const body = new THREE.Group();
    for (const part of spec.parts) {
      const mesh = place(new THREE.Mesh(primitive(part), material(part.c)), part);
      body.add(label(mesh, `TurtleBot3 ${spec.ns ? spec.ns + ' ' : ''}${part.n}`));
      this.pickable.push(mesh);
    }
    group.add(body);
    const ring = new THREE.Mesh(new THREE.RingGeometry(spec.radius, spec.radius + 0.035, 48),
      new THREE.MeshBasicMaterial({ color: ROBOT, side: THREE.DoubleSide }));
    ring.position.z = 0.003;
    group.add(ring);
    const arrow = new THREE.Shape([new THREE.Vector2(spec.radius + 0.02, -0.06), new THREE.Vector2(spec.radius + 0.16, 0),
      new THREE.Vector2(spec.radius + 0.02, 0.06)]);
    const head = new THREE.Mesh(new THREE.ShapeGeometry(arrow), new THREE.MeshBasicMaterial({ color: ROBOT, side: THREE.DoubleSide }));
    head.position.z = 0.003;
    group.add(head);
    group.visible = shown;
    if (spec.spawn) this.pose(group, spec.spawn[0], spec.spawn[1], spec.spawn[2]);
    this.scene.add(group);
    return group;
  }

  pose(group, x, y, yaw) {
    group.position.set(x, y, 0);
    group.rotation.set(0, 0, yaw);
  }

  setRays(rays) {
    const z = data.robot.lidar ? data.robot.lidar.p[2] : 0.18;
    const points = new Float32Array(rays.length * 6);
    const colours = new Float32Array(rays.length * 6);
    const hit = new THREE.Color(RAY_HIT), miss = new THREE.Color(RAY_MISS);
    rays.forEach((r, i) => {
      points.set([r[0], r[1], z, r[2], r[3], z], i * 6);
      const c = r[4] ? hit : miss;
      colours.set([c.r, c.g, c.b, c.r, c.g, c.b], i * 6);
    });
    this.rays.geometry.setAttribute('position', new THREE.BufferAttribute(points, 3));
    this.rays.geometry.setAttribute('color', new THREE.BufferAttribute(colours, 3));
    this.rays.geometry.computeBoundingSphere();
  }

  legend() {
    const entries = [];
    const groups = new Set(data.items.map(i => i.g));
    if (groups.has('wall')) entries.push([WALL_CUT, 'wall']);
    if (groups.has('obstacle')) entries.push([OBSTACLE_CUT, 'obstacle']);
    const types = new Set(data.openings.map(o => o.type));
    if (types.has('door')) entries.push([DOOR, 'door']);
    if (types.has('window')) entries.push([WINDOW, 'window']);
    if (this.robot.visible) entries.push([ROBOT, `${data.robot.model}`]);
    if (replay) entries.push([PATH, 'path']);
    el('legend').innerHTML = '';
    for (const [colour, text] of entries) {
      const span = document.createElement('span');
      const swatch = document.createElement('i');
      swatch.style.background = colour;
      span.append(swatch, document.createTextNode(text));
      el('legend').append(span);
    }
  }

  home() {
    const c = this.centre;
    const d = this.span * 1.25 + 2;
    if (this.homeAt) this.perspective.position.copy(this.homeAt);
    else this.perspective.position.set(c.x - d * 0.4, c.y - d * 0.7, d * 0.95);
    this.controls.target.copy(c);
    this.controls.update();
  }

  focusPoints() {
    // What the first 3D view must show: the robot (its centre and four points of its ring) where it starts, the
    // path a run takes (24 points of it), and the other robots
    const points = [];
    const robot = (x, y, r) => {
      points.push(new THREE.Vector3(x, y, 0.1));
      for (let k = 0; k < 4; k++) {
        points.push(new THREE.Vector3(x + r * Math.cos(k * Math.PI / 2), y + r * Math.sin(k * Math.PI / 2), 0.01));
      }
    };
    if (replay && replay.t.length) {
      robot(replay.x[0], replay.y[0], data.robot.radius + 0.02);
      const step = Math.max(1, Math.ceil(replay.t.length / 24));
      for (let i = step; i < replay.t.length; i += step) points.push(new THREE.Vector3(replay.x[i], replay.y[i], 0.01));
    } else if (data.robot.spawn) robot(data.robot.spawn[0], data.robot.spawn[1], data.robot.radius + 0.02);
    for (const other of data.others || []) if (other.spawn) robot(other.spawn[0], other.spawn[1], other.radius + 0.02);
    return points;
  }

  chooseHome() {
    // Where the 3D view starts: looking at the world's centre from the south-west, 50 degrees up; when a wall or
    // an obstacle would hide the robot or its path from there (a robot near the wall in front, tall walls), from
    // another side, then from higher up, until every point of focusPoints() is in the picture and in sight
    const points = this.focusPoints();
    const c = this.centre, d = this.span * 1.25 + 2;
    const distance = d * Math.hypot(0.4, 0.7, 0.95), side = Math.atan2(-0.7, -0.4);
    const eye = this.perspective.clone();
    const w = this.container.clientWidth, h = this.container.clientHeight;
    if (w && h) eye.aspect = w / h;
    eye.updateProjectionMatrix();
    this.scene.updateMatrixWorld();
    const caster = new THREE.Raycaster();
    let best = null;
    const elevations = [Math.atan2(0.95, Math.hypot(0.4, 0.7)), ...[60, 70, 80, 88].map(e => e * Math.PI / 180)];
    for (const elevation of elevations) {
      for (const turn of [0, 1, -1, 2]) {
        const a = side + turn * Math.PI / 2, across = distance * Math.cos(elevation);
        const at = new THREE.Vector3(c.x + across * Math.cos(a), c.y + across * Math.sin(a),
          distance * Math.sin(elevation));
        const hidden = this.hiddenFrom(at, points, eye, caster);
        if (hidden === 0) return at;
        if (!best || hidden < best.hidden) best = { at: at, hidden: hidden };
      }
    }
    return best.at;
  }

  hiddenFrom(at, points, eye, caster) {
    // How many of the points an eye at `at`, looking at the centre, would not see
    eye.position.copy(at);
    eye.lookAt(this.centre);
    eye.updateMatrixWorld();
    let hidden = 0;
    for (const p of points) {
      const seen = p.clone().project(eye);
      if (Math.abs(seen.x) > 0.95 || Math.abs(seen.y) > 0.95 || seen.z > 1) { hidden += 1; continue; }
      const towards = p.clone().sub(at);
      caster.set(at, towards.clone().normalize());
      caster.far = towards.length() - 0.01;
      if (caster.intersectObjects(this.solids, false).length) hidden += 1;
    }
    return hidden;
  }

  setTop(top) {
    this.top = top;
    for (const mat of this.cutMaterials) { mat.clippingPlanes = top ? this.cut : null; mat.needsUpdate = true; }
    if (this.plan) this.plan.visible = top;
    if (this.openings) this.openings.visible = !top;
    if (this.grid) this.grid.visible = !top;
    this.camera = top ? this.ortho : this.perspective;
    this.controls.object = this.camera;
    if (top) {
      this.ortho.position.set(this.centre.x, this.centre.y, 100);
      this.ortho.zoom = 1;
      this.controls.target.set(this.centre.x, this.centre.y, 0);
      this.controls.enableRotate = false;
      this.controls.mouseButtons.LEFT = THREE.MOUSE.PAN;   // a plan is dragged, not turned
    } else {
      this.controls.enableRotate = true;
      this.controls.mouseButtons.LEFT = THREE.MOUSE.ROTATE;
      this.home();
    }
    this.resize();
    this.controls.update();
    el('btn-top').classList.toggle('on', top);
    el('btn-3d').classList.toggle('on', !top);
  }

  resize() {
    const w = this.container.clientWidth, h = this.container.clientHeight;
    if (!w || !h) return;
    this.renderer.setSize(w, h, false);
    this.perspective.aspect = w / h;
    this.perspective.updateProjectionMatrix();
    const half = this.span / 2 + 0.5;   // preview's square: the bounds and half a metre around
    const sx = w >= h ? half * w / h : half, sy = w >= h ? half : half * h / w;
    Object.assign(this.ortho, { left: -sx, right: sx, top: sy, bottom: -sy });
    this.ortho.updateProjectionMatrix();
    this.render();
  }

  frame() {
    // What the top view shows: world x, y at the canvas' centre and metres per CSS pixel (for tests and the scale)
    const canvas = this.renderer.domElement;
    const perPixel = (this.ortho.right - this.ortho.left) / this.ortho.zoom / canvas.clientWidth;
    const t = this.controls.target;
    return { x: t.x, y: t.y, perPixel: perPixel, width: canvas.clientWidth, height: canvas.clientHeight, top: this.top };
  }

  scale() {
    const box = el('scale');
    if (!this.top) { box.hidden = false; el('scale-bar').style.width = '0'; el('scale-text').textContent = 'grid: 1 m squares'; return; }
    const f = this.frame();
    const length = niceLength(f.perPixel * f.width);
    el('scale-bar').style.width = `${Math.round(length / f.perPixel)}px`;
    el('scale-text').textContent = `${length} m`;
  }

  render() {
    this.renderer.render(this.scene, this.camera);
    this.scale();
  }

  pick(event) {
    const rect = this.renderer.domElement.getBoundingClientRect();
    const pointer = new THREE.Vector2(((event.clientX - rect.left) / rect.width) * 2 - 1,
      -((event.clientY - rect.top) / rect.height) * 2 + 1);
    const caster = new THREE.Raycaster();
    caster.setFromCamera(pointer, this.camera);
    const shown = object => { for (let o = object; o; o = o.parent) if (!o.visible) return false; return true; };
    const hits = caster.intersectObjects(this.pickable, false)
      .filter(h => shown(h.object) && !(this.top && h.point.z > data.plan.z[1] + 0.01 && h.object.material.clippingPlanes));
    return hits.length ? hits[0].object.userData.label : null;
  }
}

class Replay {
  constructor(view) {
    this.view = view;
    this.t = 0;
    this.playing = false;
    this.speed = 4;
    this.last = null;
    const r = replay;
    this.end = r.t[r.t.length - 1] || 0;
    const points = r.t.map((_, i) => new THREE.Vector3(r.x[i], r.y[i], 0.01));
    const path = new THREE.Line(new THREE.BufferGeometry().setFromPoints(points), new THREE.LineBasicMaterial({ color: PATH }));
    view.scene.add(label(path, 'the path'));
    for (const c of r.contacts) {
      const mark = new THREE.Group();
      for (const a of [Math.PI / 4, -Math.PI / 4]) {
        const bar = new THREE.Mesh(new THREE.BoxGeometry(0.16, 0.03, 0.01), new THREE.MeshBasicMaterial({ color: '#000000' }));
        bar.rotation.z = a;
        mark.add(bar);
      }
      mark.position.set(c.x, c.y, 0.012);
      view.scene.add(mark);
      const hit = new THREE.Mesh(new THREE.CircleGeometry(0.1, 16), new THREE.MeshBasicMaterial({ transparent: true, opacity: 0 }));
      hit.position.set(c.x, c.y, 0.013);
      view.scene.add(label(hit, `contact at ${c.t.toFixed(2)} s${c.n ? ' with ' + c.n : ''}`));
      view.pickable.push(hit);
    }
    view.rays.visible = true;
    el('btn-rays').classList.add('on');
    this.plots = [
      new Plot(el('plot-cmd'), 'cmd_vel', [['v', 'linear.x (m/s)', '#1f77b4'], ['w', 'angular.z (rad/s)', '#ff7f0e']], r),
      new Plot(el('plot-dist'), 'distance to the wall ahead (m)', [['d', 'front LiDAR distance', '#2ca02c']], r),
    ];
    for (const plot of this.plots) plot.canvas.addEventListener('click', e => this.seek(plot.timeAt(e)));
    el('btn-play').addEventListener('click', () => (this.playing ? this.pause() : this.play()));
    el('speed').addEventListener('change', e => { this.speed = Number(e.target.value); });
    this.speed = Number(el('speed').value);
    el('slider').addEventListener('input', e => { this.pause(); this.seek(Number(e.target.value)); });
    document.addEventListener('keydown', e => {   // space: play or pause; arrows: a tenth of a second (shift: 1 s)
      if (e.target.closest && e.target.closest('input, select')) return;
      if (e.key === ' ') { e.preventDefault(); if (this.playing) this.pause(); else this.play(); }
      else if (e.key === 'ArrowRight' || e.key === 'ArrowLeft') {
        this.pause();
        this.seek(this.t + (e.key === 'ArrowRight' ? 1 : -1) * (e.shiftKey ? 1 : 0.1));
      }
    });
    this.seek(0);
  }

  index(times, t) {
    let lo = 0, hi = times.length - 1;
    if (hi < 0 || t <= times[0]) return 0;
    while (lo < hi) { const mid = (lo + hi + 1) >> 1; if (times[mid] <= t) lo = mid; else hi = mid - 1; }
    return lo;
  }

  poseAt(t) {
    const r = replay;
    const i = this.index(r.t, t);
    const j = Math.min(i + 1, r.t.length - 1);
    const span = r.t[j] - r.t[i];
    const f = span > 0 ? Math.min(1, Math.max(0, (t - r.t[i]) / span)) : 0;
    let dyaw = r.yaw[j] - r.yaw[i];
    dyaw = Math.atan2(Math.sin(dyaw), Math.cos(dyaw));
    return { x: r.x[i] + f * (r.x[j] - r.x[i]), y: r.y[i] + f * (r.y[j] - r.y[i]), yaw: r.yaw[i] + f * dyaw, i: i };
  }

  scanAt(t) {
    const s = replay.scans;
    if (!s || !s.t.length || t < s.t[0]) return [];
    const k = this.index(s.t, t);
    const [ox, oy, oyaw] = s.o[k];
    return s.r[k].map((range, b) => {
      const a = oyaw + s.min + b * s.inc;
      const hit = range >= 0;
      const d = hit ? range / 100 : s.max;
      return [ox, oy, ox + d * Math.cos(a), oy + d * Math.sin(a), hit ? 1 : 0];
    });
  }

  seek(t) {
    this.t = Math.max(0, Math.min(this.end, t));
    if (replay.t.length) {   // a run without odometry (it never started) keeps the robot at its spawn
      const p = this.poseAt(this.t);
      this.view.pose(this.view.robot, p.x, p.y, p.yaw);
    }
    this.view.setRays(this.scanAt(this.t));
    el('slider').value = String(this.t);
    el('clock').textContent = `${this.t.toFixed(2)} s of ${this.end.toFixed(2)} s`;
    for (const plot of this.plots) plot.draw(this.t);
    this.view.render();
  }

  play() {
    if (this.t >= this.end) this.seek(0);
    this.playing = true;
    this.last = null;
    el('btn-play').textContent = '❚❚ pause';
    requestAnimationFrame(now => this.tick(now));
  }

  pause() {
    this.playing = false;
    el('btn-play').textContent = '▶ play';
  }

  tick(now) {
    if (!this.playing) return;
    if (this.last !== null) this.seek(this.t + (now - this.last) / 1000 * this.speed);
    this.last = now;
    if (this.t >= this.end) { this.pause(); return; }
    requestAnimationFrame(n => this.tick(n));
  }
}

class Plot {
  constructor(canvas, title, series, r) {
    this.canvas = canvas;
    this.title = title;
    this.series = series;
    this.r = r;
    this.pad = { l: 48, r: 12, t: 18, b: 22 };
    const values = [];
    for (const [key] of series) for (const v of r[key] || []) if (v !== null && Number.isFinite(v)) values.push(v);
    this.lo = Math.min(0, ...values);
    this.hi = Math.max(0.1, ...values);
    if (this.hi - this.lo < 1e-6) this.hi = this.lo + 1;
    this.end = r.t[r.t.length - 1] || 1;
  }

  x(t) { const w = this.canvas.width - this.pad.l - this.pad.r; return this.pad.l + w * t / this.end; }
  y(v) { const h = this.canvas.height - this.pad.t - this.pad.b; return this.pad.t + h * (1 - (v - this.lo) / (this.hi - this.lo)); }

  timeAt(event) {
    const rect = this.canvas.getBoundingClientRect();
    const px = (event.clientX - rect.left) * this.canvas.width / rect.width;
    return (px - this.pad.l) / (this.canvas.width - this.pad.l - this.pad.r) * this.end;
  }

  draw(t) {
    const c = this.canvas;
    c.width = c.clientWidth || 600;
    const g = c.getContext('2d');
    g.clearRect(0, 0, c.width, c.height);
    g.font = '11px sans-serif';
    g.fillStyle = '#333';
    g.fillText(this.title, this.pad.l, 12);
    g.strokeStyle = '#ccc';
    g.beginPath();
    g.moveTo(this.pad.l, this.y(0)); g.lineTo(c.width - this.pad.r, this.y(0));
    g.moveTo(this.pad.l, this.pad.t); g.lineTo(this.pad.l, c.height - this.pad.b);
    g.stroke();
    g.fillStyle = '#555';
    g.fillText(this.hi.toFixed(2), 4, this.y(this.hi) + 4);
    g.fillText(this.lo.toFixed(2), 4, this.y(this.lo));
    g.fillText(`${this.end.toFixed(1)} s`, c.width - this.pad.r - 40, c.height - 6);
    let legendX = this.pad.l + g.measureText(this.title).width + 16;
    for (const [key, name, colour] of this.series) {
      const values = this.r[key] || [];
      g.strokeStyle = colour;
      g.lineWidth = 1.5;
      g.beginPath();
      let pen = false;
      values.forEach((v, i) => {
        if (v === null || !Number.isFinite(v)) { pen = false; return; }
        const px = this.x(this.r.t[i]), py = this.y(v);
        if (pen) g.lineTo(px, py); else g.moveTo(px, py);
        pen = true;
      });
      g.stroke();
      g.fillStyle = colour;
      g.fillText(name, legendX, 12);
      legendX += g.measureText(name).width + 16;
    }
    g.strokeStyle = '#d62728';
    g.lineWidth = 1;
    for (const contact of this.r.contacts) {
      g.beginPath(); g.moveTo(this.x(contact.t), c.height - this.pad.b); g.lineTo(this.x(contact.t), c.height - this.pad.b - 8); g.stroke();
    }
    g.strokeStyle = '#000';
    g.beginPath(); g.moveTo(this.x(t), this.pad.t); g.lineTo(this.x(t), c.height - this.pad.b); g.stroke();
  }
}

export async function start() {
  const status = el('status');
  const probe = document.createElement('canvas');
  if (!probe.getContext('webgl2') && !probe.getContext('webgl')) {
    status.textContent = 'This page needs WebGL, which this browser has turned off.';
    return;
  }
  const view = new WorldView(el('view'));
  await view.build();
  const player = replay ? new Replay(view) : null;
  el('btn-3d').addEventListener('click', () => view.setTop(false));
  el('btn-top').addEventListener('click', () => view.setTop(true));
  el('btn-rays').addEventListener('click', () => {
    view.rays.visible = !view.rays.visible;
    el('btn-rays').classList.toggle('on', view.rays.visible);
    view.render();
  });
  const tooltip = el('tooltip');
  view.renderer.domElement.addEventListener('pointermove', event => {
    const text = view.pick(event);
    tooltip.hidden = !text;
    if (text) {
      const rect = view.container.getBoundingClientRect();
      tooltip.textContent = text;
      tooltip.style.left = `${event.clientX - rect.left + 14}px`;
      tooltip.style.top = `${event.clientY - rect.top + 14}px`;
    }
  });
  view.renderer.domElement.addEventListener('pointerleave', () => { tooltip.hidden = true; });
  view.resize();
  status.hidden = true;
  window.worldgen = {
    ready: true,
    topView: () => view.setTop(true),
    view3d: () => view.setTop(false),
    frame: () => view.frame(),
    hover: (x, y) => view.pick({ clientX: x, clientY: y }),
    robot: () => ({ x: view.robot.position.x, y: view.robot.position.y, yaw: view.robot.rotation.z }),
    time: () => (player ? player.t : 0),
    playing: () => (player ? player.playing : false),
    seek: t => player && player.seek(t),
  };
}
