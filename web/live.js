// live.js: the page of tds's live view (doc/output.md, "Live view").
// Polls /api/version; when tds has published a newer snapshot, fetches
// /api/snapshot (layout in src/live_snap.h) and redraws. The snapshot's
// values are computed by tds; this only maps them to colours.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

const POLL_MS = 150;

// Evolver's colour table (its EvolverOBJcolors.mtl), by colour number.
const EVOLVER = [
  [0, 0, 0], [0, 0, 1], [0, 1, 0], [0, 1, 1], [1, 0, 0], [1, 0, 1],
  [1, 0.5, 0], [0.6, 0.6, 0.6], [0.3, 0.3, 0.3], [0.3, 0.8, 1], [0.5, 1, 0.5],
  [0.5, 1, 1], [1, 0.5, 0.5], [1, 0.5, 1], [1, 1, 0], [1, 1, 1]];
const PLAIN = [0.75, 0.8, 0.9];   // colour = none
const MISSING = [0.55, 0.55, 0.55]; // a value tds could not measure (NaN)
// Diverging map, low - middle - high (Moreland's cool to warm end points).
const STOPS = [[0.23, 0.299, 0.754], [0.865, 0.865, 0.865], [0.706, 0.016, 0.15]];

// The colours above are sRGB; three lights and blends in linear space.
const lin = (c) => c.map((x) => (x <= 0.04045 ? x / 12.92 : ((x + 0.055) / 1.055) ** 2.4));

function scalarColor(t) {
  t = Math.min(1, Math.max(0, t)) * 2;
  const i = t >= 1 ? 1 : 0, f = t - i, a = STOPS[i], b = STOPS[i + 1];
  return [a[0] + f * (b[0] - a[0]), a[1] + f * (b[1] - a[1]), a[2] + f * (b[2] - a[2])];
}

function bodyColor(id) {
  if (!(id > 0)) return MISSING;
  const c = new THREE.Color().setHSL((id * 0.618034) % 1, 0.65, 0.55, THREE.LinearSRGBColorSpace);
  return [c.r, c.g, c.b];
}

// Parse a snapshot: header and typed views on the arrays.
function parse(buf) {
  const hlen = new DataView(buf).getUint32(0, true);
  const head = JSON.parse(new TextDecoder().decode(new Uint8Array(buf, 4, hlen)));
  let off = 4 + hlen;
  const take = (Type, n) => { const a = new Type(buf, off, n); off += 4 * n; return a; };
  const snap = { head, fields: {} };
  snap.pos = take(Float32Array, 3 * head.vertices);
  snap.tri = take(Uint32Array, 3 * head.facets);
  snap.edge = take(Uint32Array, 2 * head.edges);
  for (const f of head.fields)
    snap.fields[f.name] = { ...f, values: take(Float32Array, f.per === 'vertex' ? head.vertices : head.facets) };
  return snap;
}

const view = document.getElementById('view');
const $ = (id) => document.getElementById(id);
let renderer = null;
try {
  renderer = new THREE.WebGLRenderer({ antialias: true });
} catch (e) {
  $('status').textContent = 'WebGL is not available in this browser: ' + e.message;
}
const scene = new THREE.Scene();
scene.background = new THREE.Color(0xffffff);
const camera = new THREE.PerspectiveCamera(35, 1, 0.01, 1000);
camera.up.set(0, 0, 1); // Evolver's z is up
scene.add(new THREE.HemisphereLight(0xffffff, 0x606060, 2.2));
const sun = new THREE.DirectionalLight(0xffffff, 1.6);
sun.position.set(0.5, 0.3, 1);
camera.add(sun);
scene.add(camera);

const material = new THREE.MeshLambertMaterial({
  vertexColors: true, side: THREE.DoubleSide,
  polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1 });
const surface = new THREE.Mesh(new THREE.BufferGeometry(), material);
const lines = new THREE.LineSegments(new THREE.BufferGeometry(),
  new THREE.LineBasicMaterial({ color: 0x202030 }));
scene.add(surface, lines);

let controls = null;
if (renderer) {
  renderer.setPixelRatio(window.devicePixelRatio);
  view.appendChild(renderer.domElement);
  controls = new OrbitControls(camera, renderer.domElement);
  controls.addEventListener('change', render);
}

function render() {
  if (renderer) renderer.render(scene, camera);
}

function resize() {
  camera.aspect = window.innerWidth / Math.max(1, window.innerHeight);
  camera.updateProjectionMatrix();
  if (renderer) renderer.setSize(window.innerWidth, window.innerHeight);
  render();
}
window.addEventListener('resize', resize);

// State the test and the user can read.
const live = { version: 0, head: null, field: null, fitted: false, history: [] };
window.tdsLive = live;
let snap = null, headColor = null;

// Colours per corner of the unindexed triangles for the chosen field.
function colours(s, name) {
  const nf = s.head.facets, out = new Float32Array(9 * nf);
  const f = s.fields[name];
  let lo = 0, hi = 1;
  if (f && f.min !== null && name !== 'body' && name !== 'color') {
    lo = f.min; hi = f.max;
    const mid = 0.5 * (lo + hi), half = Math.max(0.5 * (hi - lo), 1e-9 * Math.max(1, Math.abs(mid)));
    lo = mid - half; hi = mid + half;
  }
  for (let t = 0; t < nf; t++) {
    for (let k = 0; k < 3; k++) {
      let c = PLAIN;
      if (f) {
        const v = f.per === 'vertex' ? f.values[s.tri[3 * t + k]] : f.values[t];
        if (Number.isNaN(v)) c = MISSING;
        else if (name === 'color') c = EVOLVER[Math.min(15, Math.max(0, Math.round(v)))];
        else if (name === 'body') c = bodyColor(v);
        else c = scalarColor((v - lo) / (hi - lo));
      }
      out.set(lin(c), 9 * t + 3 * k);
    }
  }
  live.field = name;
  const legend = $('legend');
  legend.hidden = !f || name === 'body' || name === 'color' || f.min === null;
  if (!legend.hidden) {
    $('bar').style.background = 'linear-gradient(to right, ' +
      [0, 0.5, 1].map((u) => 'rgb(' + scalarColor(u).map((x) => Math.round(255 * x)).join(',') + ')').join(',') + ')';
    $('lo').textContent = lo.toPrecision(6);
    $('hi').textContent = hi.toPrecision(6);
  }
  return out;
}

function draw() {
  const s = snap, nf = s.head.facets, pos = new Float32Array(9 * nf);
  for (let t = 0; t < nf; t++)
    for (let k = 0; k < 3; k++) {
      const v = s.tri[3 * t + k];
      pos[9 * t + 3 * k] = s.pos[3 * v];
      pos[9 * t + 3 * k + 1] = s.pos[3 * v + 1];
      pos[9 * t + 3 * k + 2] = s.pos[3 * v + 2];
    }
  const g = new THREE.BufferGeometry();
  g.setAttribute('position', new THREE.BufferAttribute(pos, 3));
  g.setAttribute('color', new THREE.BufferAttribute(colours(s, $('color').value), 3));
  g.computeVertexNormals(); // unindexed: the facet normals, flat shading
  surface.geometry.dispose();
  surface.geometry = g;
  const lg = new THREE.BufferGeometry();
  lg.setAttribute('position', new THREE.BufferAttribute(s.pos, 3));
  lg.setIndex(new THREE.BufferAttribute(s.edge, 1));
  lines.geometry.dispose();
  lines.geometry = lg;
  lines.visible = $('showedges').checked;
  if (s.head.vertices > 0 && (!live.fitted || moved(lg))) fit(lg);
  render();
}

// A surface that grew, shrank or moved a lot (another one loaded) gets
// a new view; small changes keep the user's.
let fitted = null;
function moved(g) {
  g.computeBoundingSphere();
  const b = g.boundingSphere;
  return b.radius > 2 * fitted.radius || b.radius < fitted.radius / 2 ||
    b.center.distanceTo(fitted.center) > fitted.radius;
}

// Look at the whole surface from an oblique direction.
function fit(g) {
  g.computeBoundingSphere();
  const c = g.boundingSphere.center, r = Math.max(g.boundingSphere.radius, 1e-6);
  const d = 1.15 * r / Math.sin(THREE.MathUtils.degToRad(camera.fov / 2));
  const dir = new THREE.Vector3(1.0, -1.6, 0.9).normalize();
  camera.position.copy(c).addScaledVector(dir, d);
  camera.near = d / 100; camera.far = d * 100;
  camera.updateProjectionMatrix();
  if (controls) { controls.target.copy(c); controls.update(); }
  live.fitted = true;
  fitted = g.boundingSphere.clone();
}

const DENSE = 20000; // facets above which edges start hidden (they would hide the surface)

function show(s) {
  const h = s.head;
  if (!snap && h.facets > DENSE) $('showedges').checked = false;
  snap = s;
  if (h.color !== headColor) { headColor = h.color; $('color').value = h.color; }
  const num = (x, p) => (x === null ? '-' : Number(x).toPrecision(p));
  $('energy').textContent = num(h.energy, 15);
  $('area').textContent = num(h.area, 15);
  for (const k of ['iterations', 'vertices', 'edges', 'facets']) $(k).textContent = h[k];
  $('version').textContent = h.version;
  draw();
  live.version = h.version;
  live.head = h;
  live.history.push({ version: h.version, energy: h.energy, vertices: h.vertices, t: performance.now() });
  document.body.dataset.version = h.version;
}

let busy = false;
async function poll() {
  try {
    const r = await fetch('/api/version', { cache: 'no-store' });
    const { version } = await r.json();
    if (version !== live.version && version > 0 && !busy) {
      busy = true;
      try {
        const b = await fetch('/api/snapshot', { cache: 'no-store' });
        if (b.ok) show(parse(await b.arrayBuffer()));
      } finally { busy = false; }
    }
    if (renderer) $('status').textContent = '';
  } catch (e) {
    $('status').textContent = 'tds is not answering (stopped?)';
  }
  setTimeout(poll, POLL_MS);
}

$('color').addEventListener('change', () => { if (snap) draw(); });
$('fit').addEventListener('click', () => { if (snap && snap.head.vertices > 0) { fit(lines.geometry); render(); } });
$('showedges').addEventListener('change', () => { lines.visible = $('showedges').checked; render(); });
resize();
poll();
