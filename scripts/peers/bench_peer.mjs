// Times a peer renderer drawing one glTF file in headless Chromium (scripts/peers/bench_peers.sh runs it):
//   node bench_peer.mjs --peer threejs|khronos --file SCENE.gltf|.glb --width W --height H --views V
//        --frames F --warmup N --modules DIR/node_modules --chromium PATH --out RESULT.json
//        [--hdr ENV.hdr (khronos)] [--camera CSV_ROW_JSON (threejs)]
// Serves (on 127.0.0.1 only) the peer's page (threejs_page.html, khronos_bench_page.html), its npm
// package and the file's folder; writes RESULT.json (frame time quantiles, the camera used, the GL
// renderer) and, next to it, RESULT.csv: that camera as an mvr camera file (x, y, z, qx, qy, qz, qw,
// fx, fy, cx, cy, width, height; one row per view) for mvr bench --cameras, and RESULT.ppm: view 0 as
// the peer drew it.
import { createServer } from 'node:http';
import { readFileSync, writeFileSync, existsSync } from 'node:fs';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
const args = {};
for (let i = 2; i < process.argv.length; i += 2) args[process.argv[i].replace(/^--/, '')] = process.argv[i + 1];
const FILE = path.resolve(args.file);
const DIR = path.dirname(FILE);
const MODULES = path.resolve(args.modules);
const THREE_DIR = path.join(MODULES, 'three');
const VIEWER_DIST = path.join(MODULES, '@khronosgroup', 'gltf-viewer', 'dist');
const PEER = args.peer || 'threejs';
if (PEER !== 'threejs' && PEER !== 'khronos') throw new Error(`--peer threejs|khronos, not ${PEER}`);
const HDR = args.hdr ? path.resolve(args.hdr) : null;
if (PEER === 'khronos' && !HDR) throw new Error('--hdr ENV.hdr: the Khronos renderer needs an environment');
// the sheen E table is not in the renderer's npm package and is never read (render_khronos.mjs says
// why); a 1 x 1 white PNG stands in
const SHEEN_STANDIN = Buffer.from('iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAIAAACQd1PeAAAADElEQVR4nGP4//8/AAX+Av4N70a4AAAAAElFTkSuQmCC', 'base64');
const W = Number(args.width), H = Number(args.height), V = Number(args.views || 1);
const { chromium } = await import(path.join(MODULES, 'playwright-core', 'index.mjs'));
// ANGLE on Mesa's EGL (llvmpipe), as render_khronos.mjs: WebGL2 exists only with the block list ignored
const CHROMIUM_FLAGS = ['--headless=new', '--use-angle=gl-egl', '--ignore-gpu-blocklist'];

const MIME = { '.html': 'text/html', '.js': 'text/javascript', '.mjs': 'text/javascript', '.gltf': 'model/gltf+json',
    '.glb': 'model/gltf-binary', '.bin': 'application/octet-stream', '.png': 'image/png', '.jpg': 'image/jpeg',
    '.jpeg': 'image/jpeg', '.hdr': 'application/octet-stream', '.wasm': 'application/wasm' };
function resolve(url) {
    const p = decodeURIComponent(new URL(url, 'http://x').pathname);
    if (p === '/' || p === '/page.html') return path.join(here, PEER === 'khronos' ? 'khronos_bench_page.html' : 'threejs_page.html');
    if (p === '/bench_timing.mjs') return path.join(here, 'bench_timing.mjs');
    if (HDR && p === '/env.hdr') return HDR;
    const map = [['/three/', THREE_DIR], ['/viewer/', VIEWER_DIST], ['/libs/', path.join(VIEWER_DIST, 'libs')], ['/data/', DIR]];
    for (const [prefix, dir] of map) {
        if (p.startsWith(prefix)) {
            const f = path.resolve(dir, '.' + p.slice(prefix.length - 1));
            if (f.startsWith(dir + path.sep)) return f;
        }
    }
    return null;
}
const server = createServer((req, res) => {
    if (req.url === '/lut_sheen_E.png') { res.writeHead(200, { 'Content-Type': 'image/png' }); res.end(SHEEN_STANDIN); return; }
    const f = resolve(req.url);
    if (!f || !existsSync(f)) { res.writeHead(404); res.end(); return; }
    res.writeHead(200, { 'Content-Type': MIME[path.extname(f)] || 'application/octet-stream' });
    res.end(readFileSync(f));
});
await new Promise((r) => server.listen(0, '127.0.0.1', r));
const browser = await chromium.launch({ executablePath: args.chromium, headless: true, args: CHROMIUM_FLAGS });
const log = [];
try {
    const page = await browser.newPage({ viewport: { width: W * V, height: H }, deviceScaleFactor: 1 });
    page.on('console', (m) => log.push(`${m.type()}: ${m.text()}`));
    page.on('pageerror', (e) => log.push(`pageerror: ${e.message}`));
    await page.goto(`http://127.0.0.1:${server.address().port}/page.html`);
    await page.waitForFunction(() => window.mvrReady === true);
    const o = { gltf: `/data/${path.basename(FILE)}`, width: W, height: H, views: V, frames: Number(args.frames || 30),
        warmup: Number(args.warmup || 5), camera: args.camera ? JSON.parse(args.camera) : null, hdr: '/env.hdr' };
    const r = await page.evaluate((o) => (o.peer === 'khronos' ? window.benchKhronos(o) : window.benchThree(o)), { ...o, peer: PEER });
    if (r.gl_error) throw new Error(`${PEER}: GL error ${r.gl_error}`);
    const PW = r.pixels_width || W * V;   // three.js: the views side by side; Khronos: one view's canvas
    const px = Buffer.from(r.pixels, 'base64');
    delete r.pixels;
    r.browser = browser.version();
    if (!/llvmpipe/i.test(r.renderer)) log.push(`warning: not llvmpipe: ${r.renderer}`);
    // view 0 as a PPM, top row first
    const rows = [];
    for (let y = H - 1; y >= 0; y--) for (let x = 0; x < W; x++) rows.push(...px.subarray((y * PW + x) * 4, (y * PW + x) * 4 + 3));
    writeFileSync(args.out.replace(/\.json$/, '') + '.ppm', Buffer.concat([Buffer.from(`P6\n${W} ${H}\n255\n`), Buffer.from(rows)]));
    // the camera as an mvr camera file: pinhole, fy from the vertical field of view, one row per view
    const c = r.camera, fy = H / 2 / Math.tan(c.yfov / 2);
    const row = [...c.position, ...c.quaternion, fy, fy, W / 2, H / 2, W, H].map((x) => +Number(x).toPrecision(10)).join(',');
    writeFileSync(args.out.replace(/\.json$/, '') + '.csv',
        'x,y,z,qx,qy,qz,qw,fx,fy,cx,cy,width,height\n' + Array(V).fill(row).join('\n') + '\n');
    r.log = log;
    writeFileSync(args.out, JSON.stringify(r, null, 1) + '\n');
} catch (e) {
    console.error(log.join('\n'));
    throw e;
} finally {
    await browser.close();
    server.close();
}
