// Times three.js drawing one glTF file in headless Chromium (scripts/peers/bench_threejs.sh runs it):
//   node bench_threejs.mjs --file SCENE.gltf|.glb --width W --height H --views V --frames F --warmup N
//        --modules DIR/node_modules --chromium PATH --out RESULT.json [--camera CSV_ROW_JSON]
// Serves (on 127.0.0.1 only) threejs_page.html, the three package and the file's folder; writes
// RESULT.json (frame time quantiles, the camera used, three's revision, the GL renderer) and, next to
// it, RESULT.csv: that camera as an mvr camera file (x, y, z, qx, qy, qz, qw, fx, fy, cx, cy, width,
// height; one row per view) for mvr bench --cameras, and RESULT.ppm: view 0 as three.js drew it.
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
const W = Number(args.width), H = Number(args.height), V = Number(args.views || 1);
const { chromium } = await import(path.join(MODULES, 'playwright-core', 'index.mjs'));
// ANGLE on Mesa's EGL (llvmpipe), as render_khronos.mjs: WebGL2 exists only with the block list ignored
const CHROMIUM_FLAGS = ['--headless=new', '--use-angle=gl-egl', '--ignore-gpu-blocklist'];

const MIME = { '.html': 'text/html', '.js': 'text/javascript', '.mjs': 'text/javascript', '.gltf': 'model/gltf+json',
    '.glb': 'model/gltf-binary', '.bin': 'application/octet-stream', '.png': 'image/png', '.jpg': 'image/jpeg',
    '.jpeg': 'image/jpeg' };
function resolve(url) {
    const p = decodeURIComponent(new URL(url, 'http://x').pathname);
    if (p === '/' || p === '/page.html') return path.join(here, 'threejs_page.html');
    for (const [prefix, dir] of [['/three/', THREE_DIR], ['/data/', DIR]]) {
        if (p.startsWith(prefix)) {
            const f = path.resolve(dir, '.' + p.slice(prefix.length - 1));
            if (f.startsWith(dir + path.sep)) return f;
        }
    }
    return null;
}
const server = createServer((req, res) => {
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
    const r = await page.evaluate((o) => window.benchThree(o), {
        gltf: `/data/${path.basename(FILE)}`, width: W, height: H, views: V, frames: Number(args.frames || 30),
        warmup: Number(args.warmup || 5), camera: args.camera ? JSON.parse(args.camera) : null,
    });
    const px = Buffer.from(r.pixels, 'base64');
    delete r.pixels;
    r.browser = browser.version();
    if (!/llvmpipe/i.test(r.renderer)) log.push(`warning: not llvmpipe: ${r.renderer}`);
    // view 0 as a PPM, top row first
    const rows = [];
    for (let y = H - 1; y >= 0; y--) for (let x = 0; x < W; x++) rows.push(...px.subarray((y * W * V + x) * 4, (y * W * V + x) * 4 + 3));
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
