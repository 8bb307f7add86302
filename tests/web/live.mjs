// live.mjs: the live view (show()) in a real browser: Debian's chromium,
// headless, driven by playwright-core (installed by `make web`). Prints
// "PASS web/name" / "FAIL web/name: why" lines for tests/run.sh.
// Usage: node tests/web/live.mjs TDS_BINARY
// Bounded: every wait has a timeout and the whole run stops after
// LIMIT_MS; tds and the browser are ended on every exit path.
import { spawn } from 'node:child_process';
import { readFileSync, writeFileSync } from 'node:fs';
import http from 'node:http';
import net from 'node:net';
import { createRequire } from 'node:module';

const require = createRequire(new URL('../../web/package.json', import.meta.url));
const { chromium } = require('playwright-core');
const { PNG } = require('pngjs');

const TDS = process.argv[2] || process.env.TDS;
const DATAFILE = '/usr/share/doc/evolver/examples/cube.fe'; // Evolver's, not ours
const LIMIT_MS = 240000;
const W = 800, H = 600;

let tds = null, browser = null;
const report = (name, ok, why) => {
  console.log(ok ? `PASS web/${name}` : `FAIL web/${name}: ${why}`);
};

async function cleanup() {
  if (browser) await browser.close().catch(() => {});
  browser = null;
  if (tds && tds.exitCode === null) tds.kill('SIGKILL');
}
const guard = setTimeout(async () => {
  report('time_limit', false, `did not finish in ${LIMIT_MS / 1000} s`);
  await cleanup();
  process.exit(1);
}, LIMIT_MS);

// tds at its prompt (stdin is a pipe: no tty, one line at a time).
let out = '', mark = 0;
function startTds(file = DATAFILE) {
  out = '';
  tds = spawn(TDS, ['-q', '-i', file], { stdio: ['pipe', 'pipe', 'pipe'] });
  tds.stdout.on('data', (d) => { out += d; });
  tds.stderr.on('data', (d) => { out += d; });
}
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));
async function waitFor(pred, ms, what) {
  const t0 = Date.now();
  for (;;) {
    const v = await pred();
    if (v) return v;
    if (Date.now() - t0 > ms) throw new Error(`timed out waiting for ${what}`);
    await sleep(50);
  }
}
// Run Lua at the prompt; resolves with what it printed.
async function run(code, ms = 60000) {
  const m = `@@mark${++mark}@@`;
  const start = out.length;
  tds.stdin.write(`${code}\nprint("${m}")\n`);
  await waitFor(() => out.indexOf(m, start) >= 0, ms, `tds to run: ${code}`);
  return out.slice(start, out.indexOf(m, start));
}
const num = async (expr) => Number((await run(`print(string.format("%.17g", ${expr}))`)).trim());

// Raw request (no URL normalisation, any method): [status, body].
function request(port, path, method = 'GET', headers = {}) {
  return new Promise((resolve) => {
    const req = http.request({ host: '127.0.0.1', port, path, method, headers }, (res) => {
      let b = '';
      res.on('data', (d) => { b += d; });
      res.on('end', () => resolve([res.statusCode, b]));
    });
    req.on('error', (e) => resolve([0, e.code]));
    req.end();
  });
}

// Pixels of a screenshot that are not the white background, in a box.
function countInk(png, x0, y0, x1, y1, test = (r, g, b) => r < 245 || g < 245 || b < 245) {
  let n = 0, all = 0;
  for (let y = Math.floor(y0); y < y1; y++)
    for (let x = Math.floor(x0); x < x1; x++) {
      const i = 4 * (y * png.width + x);
      all++;
      if (test(png.data[i], png.data[i + 1], png.data[i + 2])) n++;
    }
  return n / all;
}
const shot = async (page) => PNG.sync.read(await page.screenshot());
const near = (a, b, tol) => Math.abs(a - b) <= tol * Math.max(1, Math.abs(b));

async function main() {
  startTds();
  const addr = await run('show{ open = false }');
  const m = addr.match(/live view: http:\/\/127\.0\.0\.1:(\d+)\//);
  report('show_prints_address', !!m, `show printed ${JSON.stringify(addr)}`);
  if (!m) return;
  const port = Number(m[1]), url = `http://127.0.0.1:${port}/`;

  // Listening on 127.0.0.1 only: the socket table has it bound to
  // 0100007F (little-endian 127.0.0.1) and no IPv6 socket on the port.
  const hex = port.toString(16).toUpperCase().padStart(4, '0');
  const rows = (f) => readFileSync(f, 'utf8').split('\n').slice(1)
    .map((l) => l.trim().split(/\s+/)).filter((c) => c[1] && c[1].endsWith(`:${hex}`) && c[3] === '0A');
  const v4 = rows('/proc/net/tcp'), v6 = rows('/proc/net/tcp6');
  report('loopback_only', v4.length === 1 && v4[0][1] === `0100007F:${hex}` && v6.length === 0,
    `listening sockets: ${JSON.stringify(v4.concat(v6).map((c) => c[1]))}`);

  // The routes: the page, three, the API; nothing outside web/.
  const checks = [
    ['/', 200], ['/live.js', 200], ['/three/build/three.module.js', 200],
    ['/three/examples/jsm/controls/OrbitControls.js', 200], ['/api/version', 200],
    ['/api/snapshot', 200], ['/three/build/../../../package.json', 404],
    ['/three/package.json', 404], ['/package.json', 404], ['/nope', 404]];
  const bad = [];
  for (const [p, want] of checks) {
    const [st] = await request(port, p);
    if (st !== want) bad.push(`${p}: ${st} (want ${want})`);
  }
  const [post] = await request(port, '/api/version', 'POST');
  if (post !== 405) bad.push(`POST: ${post} (want 405)`);
  const [rebound] = await request(port, '/api/snapshot', 'GET', { Host: `evil.example:${port}` });
  if (rebound !== 403) bad.push(`foreign Host: ${rebound} (want 403)`);
  const [named] = await request(port, '/api/version', 'GET', { Host: `localhost:${port}` });
  if (named !== 200) bad.push(`Host localhost: ${named} (want 200)`);
  report('http_routes', bad.length === 0, bad.join('; '));

  browser = await chromium.launch({
    executablePath: '/usr/bin/chromium', headless: true,
    args: ['--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
      '--disable-background-networking', '--disable-component-update', '--disable-sync',
      '--use-angle=swiftshader', '--enable-unsafe-swiftshader'] });
  const page = await browser.newPage({ viewport: { width: W, height: H } });
  const errors = [];
  page.on('pageerror', (e) => errors.push(e.message));
  await page.goto(url);
  await page.waitForFunction(() => window.tdsLive && window.tdsLive.version >= 1, null, { timeout: 30000 });
  const text = async (id) => (await page.textContent(`#${id}`)).trim();
  const status = await text('status');
  const nv = await num('vertex_count'), e0 = await num('total_energy');
  report('page_loads', errors.length === 0 && status === '' &&
    Number(await text('vertices')) === nv && near(Number(await text('energy')), e0, 1e-13),
  `errors ${JSON.stringify(errors)}, status '${status}', page shows ${await text('vertices')} vertices ` +
  `and energy ${await text('energy')}; tds has ${nv} and ${e0}`);

  // The picture: the cube is fitted to the middle of the window, so the
  // central box is covered and the right and bottom margins are empty
  // (the panel sits top left).
  await sleep(300);
  let png = await shot(page);
  const centre = countInk(png, 0.4 * W, 0.4 * H, 0.6 * W, 0.6 * H);
  const margin = Math.max(countInk(png, 0.95 * W, 0, W, H), countInk(png, 0, 0.95 * H, W, H));
  report('screenshot_surface', png.width === W && centre > 0.98 && margin < 0.002,
    `centre covered ${centre.toFixed(3)}, margins ${margin.toFixed(4)}`);

  // Facet edges: dark lines; hiding them leaves (almost) no such pixels.
  const dark = (r, g, b) => r < 60 && g < 60 && b < 70;
  const withEdges = countInk(png, 0.2 * W, 0.2 * H, 0.8 * W, 0.8 * H, dark);
  await page.uncheck('#showedges');
  await sleep(200);
  const noEdges = countInk(await shot(page), 0.2 * W, 0.2 * H, 0.8 * W, 0.8 * H, dark);
  await page.check('#showedges');
  report('edges_drawn', withEdges > 0.005 && noEdges < withEdges / 10,
    `dark pixels ${withEdges.toFixed(4)} with edges, ${noEdges.toFixed(4)} without`);

  // After g 10 at the prompt the page shows tds's new energy and count.
  const v0 = await page.evaluate(() => window.tdsLive.version);
  await run('g 10');
  const e1 = await num('total_energy'), it1 = await num('iteration_counter');
  let got = null;
  try {
    got = await page.waitForFunction((e) => {
      const h = window.tdsLive.head;
      return h && Math.abs(h.energy - e) <= 1e-13 * Math.abs(e) && h;
    }, e1, { timeout: 15000 }).then((h) => h.jsonValue());
  } catch { /* reported below */ }
  report('updates_after_g', got && e1 < e0 && Number(await text('iterations')) === it1 &&
    near(Number(await text('energy')), e1, 1e-13) && got.version > v0,
  `tds energy ${e0} -> ${e1} (iteration ${it1}); page shows ${await text('energy')} ` +
  `at iteration ${await text('iterations')}`);

  // Topology changes too: refine, the page shows the new counts.
  await run('r');
  const nv2 = await num('vertex_count'), nf2 = await num('facet_count');
  let ok = true;
  try {
    await page.waitForFunction((n) => window.tdsLive.head.vertices === n, nv2, { timeout: 15000 });
  } catch { ok = false; }
  report('updates_after_refine', ok && nv2 > nv && Number(await text('vertices')) === nv2 &&
    Number(await text('facets')) === nf2,
  `tds has ${nv2} vertices, ${nf2} facets; page ${await text('vertices')}, ${await text('facets')}`);

  // While a long g runs the REPL is busy, yet the page shows snapshots
  // published between its iterations: energies strictly between the
  // energy before and after, at versions before the final one.
  await run('r; r');
  const eStart = await num('total_energy');
  const vStart = await page.evaluate(() => window.tdsLive.version);
  // About two seconds of iterations, measured on this machine.
  await run('local c = os.clock(); g(5); N = math.max(20, math.ceil(5 * 2.5 / math.max(os.clock() - c, 1e-3)))');
  await run('g(N)', 120000);
  const eEnd = await num('total_energy');
  await page.waitForFunction((e) => Math.abs(window.tdsLive.head.energy - e) <= 1e-13 * Math.abs(e), eEnd, { timeout: 15000 });
  const hist = await page.evaluate(() => window.tdsLive.history);
  const vEnd = hist[hist.length - 1].version;
  const during = hist.filter((h) => h.version > vStart && h.version < vEnd && h.energy < eStart && h.energy > eEnd);
  report('updates_during_g', during.length >= 2,
    `${during.length} snapshots seen during g(${await num('N')}) (energy ${eStart} -> ${eEnd}); ` +
    `versions seen ${JSON.stringify(hist.map((h) => h.version))}`);

  // Ctrl-C during a long g with the server running: the signal reaches
  // the command (the server's thread blocks signals), g stops with its
  // message, the prompt goes on and the page gets the stopped surface.
  const before = out.length;
  tds.stdin.write('g 100000000\n');
  await sleep(1500);
  tds.kill('SIGINT');
  let intr = '';
  try {
    await waitFor(() => /interrupted: \d+ of 100000000/.test(out.slice(before)), 20000, 'the interruption');
    const eInt = await num('total_energy');
    await page.waitForFunction((e) => Math.abs(window.tdsLive.head.energy - e) <= 1e-13 * Math.abs(e), eInt, { timeout: 15000 });
    intr = (await run('print((check()))')).trim();
  } catch (e) { intr = e.message; }
  report('interrupt_with_view', intr === 'true', `after Ctrl-C: ${intr}; tds said ${JSON.stringify(out.slice(before, before + 300))}`);

  // pg also publishes; the final energy is tds's.
  await run('pg(30)', 120000);
  const ePg = await num('total_energy');
  ok = true;
  try {
    await page.waitForFunction((e) => Math.abs(window.tdsLive.head.energy - e) <= 1e-13 * Math.abs(e), ePg, { timeout: 15000 });
  } catch { ok = false; }
  report('updates_after_pg', ok && ePg !== eEnd, `tds energy after pg ${ePg}, page ${await text('energy')}`);

  // Field values come from tds: the ranges the page has equal tds's own
  // smallest angle (quality) and curvature attributes.
  const qmin = await num('quality{ quiet = true }.min');
  const hmin = await num('(function() local a = math.huge; for v in vertices() do local h = v.mean_curvature; if h and h == h then a = math.min(a, h) end end; return a end)()');
  const hmax = await num('(function() local a = -math.huge; for v in vertices() do local h = v.mean_curvature; if h and h == h then a = math.max(a, h) end end; return a end)()');
  const f = await page.evaluate(() => Object.fromEntries(window.tdsLive.head.fields.map((x) => [x.name, x])));
  report('fields_match_tds', near(f.min_angle.min, qmin, 1e-12) && near(f.mean_curvature.min, hmin, 1e-12) &&
    near(f.mean_curvature.max, hmax, 1e-12),
  `page: min_angle ${f.min_angle.min}, curvature ${f.mean_curvature.min}..${f.mean_curvature.max}; ` +
  `tds: ${qmin}, ${hmin}..${hmax}`);

  // Colouring: show{color=...} sets the page's field; Evolver colours show.
  const plain = await shot(page);
  await run('for f in facets() do f.color = 4 end; show{ open = false, color = "color" }');
  ok = true;
  try {
    await page.waitForFunction(() => window.tdsLive.field === 'color', null, { timeout: 15000 });
  } catch { ok = false; }
  await sleep(200);
  png = await shot(page);
  const red = countInk(png, 0.4 * W, 0.4 * H, 0.6 * W, 0.6 * H, (r, g, b) => r > 2 * g + 20 && r > 2 * b + 20);
  const wasRed = countInk(plain, 0.4 * W, 0.4 * H, 0.6 * W, 0.6 * H, (r, g, b) => r > 2 * g + 20 && r > 2 * b + 20);
  report('show_sets_color', ok && (await page.inputValue('#color')) === 'color' && red > 0.8 && wasRed < 0.01,
    `select ${await page.inputValue('#color')}, red share ${red.toFixed(3)} (before ${wasRed.toFixed(3)})`);
  await page.selectOption('#color', 'mean_curvature');
  await sleep(200);
  const curv = await shot(page);
  let changed = 0;
  for (let i = 0; i < curv.data.length; i += 4)
    if (Math.abs(curv.data[i] - png.data[i]) + Math.abs(curv.data[i + 2] - png.data[i + 2]) > 60) changed++;
  const surf = countInk(curv, 0, 0, W, H) * W * H;
  report('page_selects_field', changed > 0.3 * surf && !(await page.isHidden('#legend')),
    `${changed} of ${surf} drawn pixels changed, legend ${await page.isHidden('#legend') ? 'hidden' : 'shown'}`);

  // A surface four times larger, moved away, is looked at anew: it is
  // framed as before (centre covered, margins empty).
  await run('for v in vertices() do v.x, v.y, v.z = 4 * v.x + 10, 4 * v.y, 4 * v.z end');
  await page.waitForFunction(() => window.tdsLive.head.area > 10, null, { timeout: 15000 }).catch(() => {});
  await sleep(300);
  png = await shot(page);
  const c2 = countInk(png, 0.4 * W, 0.4 * H, 0.6 * W, 0.6 * H);
  const m2 = Math.max(countInk(png, 0.95 * W, 0, W, H), countInk(png, 0, 0.95 * H, W, H));
  report('refits_moved_surface', c2 > 0.98 && m2 < 0.002,
    `centre covered ${c2.toFixed(3)}, margins ${m2.toFixed(4)}, area ${await page.evaluate(() => window.tdsLive.head.area)}`);

  // Errors: unknown option names the key; a busy port is refused and the
  // running view is kept.
  const bogus = await run('show{ bogus = 1 }');
  const blocker = net.createServer();
  await new Promise((r) => blocker.listen(0, '127.0.0.1', r));
  const busy = blocker.address().port;
  const busyMsg = await run(`show{ open = false, port = ${busy} }`);
  const [stillUp] = await request(port, '/api/version');
  blocker.close();
  report('errors', /unknown option 'bogus'/.test(bogus) && /port in use/.test(busyMsg) && stillUp === 200,
    `bogus -> ${JSON.stringify(bogus)}, busy port -> ${JSON.stringify(busyMsg)}, old server ${stillUp}`);

  // show(false) stops; show{port = p} starts again on that port.
  const stopped = await run('show(false)');
  const [after] = await request(port, '/api/version');
  await sleep(500);
  const pageSays = await text('status');
  report('stop', /live view stopped/.test(stopped) && after === 0 && /not answering/.test(pageSays),
    `show(false) printed ${JSON.stringify(stopped)}, request -> ${after}, page status '${pageSays}'`);
  const again = await run(`show{ open = false, port = ${port} }`);
  const [up] = await request(port, '/api/version');
  await run('show{ stop = true }');
  const [down] = await request(port, '/api/version');
  report('port_option', again.includes(`127.0.0.1:${port}/`) && up === 200 && down === 0,
    `restart printed ${JSON.stringify(again)}, then ${up}, after stop ${down}`);
  await quitTds('clean_exit');

  // Colour by body: two cubes sharing a face, seen from the front left,
  // body 1 on the left and body 2 on the right; their hues must differ.
  startTds(new URL('two_cubes.tds', import.meta.url).pathname);
  // Refined past 20000 facets, the page starts with the edges hidden.
  const addr2 = (await run('g(3); for i = 1, 5 do r() end; show{ open = false, color = "body" }')).match(/127\.0\.0\.1:(\d+)/);
  await page.goto(`http://127.0.0.1:${addr2[1]}/`);
  await page.waitForFunction(() => window.tdsLive && window.tdsLive.version >= 1, null, { timeout: 30000 });
  await sleep(300);
  png = await shot(page);
  const hue = (x0, x1) => { // hue (degrees) of the mean lit surface colour in a band
    let r = 0, g = 0, b = 0, n = 0;
    for (let y = Math.floor(0.3 * H); y < 0.7 * H; y++)
      for (let x = Math.floor(x0 * W); x < x1 * W; x++) {
        const i = 4 * (y * W + x), p = png.data;
        if (Math.max(p[i], p[i + 1], p[i + 2]) > 245 || Math.max(p[i], p[i + 1], p[i + 2]) < 60) continue;
        r += p[i]; g += p[i + 1]; b += p[i + 2]; n++;
      }
    const c = new Array(3);
    [c[0], c[1], c[2]] = [r / n, g / n, b / n];
    const mx = Math.max(...c), mn = Math.min(...c);
    if (!n || mx - mn < 10) return NaN;
    let h = mx === c[0] ? (c[1] - c[2]) / (mx - mn) : mx === c[1] ? 2 + (c[2] - c[0]) / (mx - mn) : 4 + (c[0] - c[1]) / (mx - mn);
    return ((h * 60) + 360) % 360;
  };
  const hl = hue(0.15, 0.35), hr = hue(0.65, 0.85);
  const dh = Math.min(Math.abs(hl - hr), 360 - Math.abs(hl - hr));
  const bodies = await page.evaluate(() => window.tdsLive.head.bodies);
  if (process.env.LIVE_SHOT) writeFileSync(process.env.LIVE_SHOT, PNG.sync.write(png));
  report('color_by_body', bodies === 2 && dh > 60, `page has ${bodies} bodies; hues left ${hl}, right ${hr}`);
  const nf3 = await num('facet_count');
  const dense = await page.evaluate(() => window.tdsLive.head.facets);
  report('dense_edges_hidden', nf3 > 20000 && dense === nf3 && !(await page.isChecked('#showedges')),
    `${nf3} facets in tds, ${dense} on the page, edges ${await page.isChecked('#showedges') ? 'shown' : 'hidden'}`);
}

// q ends tds (and its server); under the sanitizers a leak or a data
// error at exit would show here.
async function quitTds(name) {
  if (!tds || tds.exitCode !== null) return;
  tds.stdin.end('q\n');
  const code = await Promise.race([new Promise((r) => tds.once('exit', (c) => r(c))), sleep(20000).then(() => 'hung')]);
  const san = out.match(/(AddressSanitizer|LeakSanitizer|ThreadSanitizer|runtime error)[^\n]*/);
  report(name, code === 0 && !san, `exit ${code}${san ? ', ' + san[0] : ''}`);
  if (code === 'hung') tds.kill('SIGKILL');
}

try {
  await main();
} catch (e) {
  report('run', false, e.message.split('\n')[0]);
}
await quitTds('clean_exit_two_cubes');
await cleanup();
clearTimeout(guard);
// Failures are reported as FAIL lines; a non-zero status means the run itself broke.
process.exit(0);
