// Renders the peer reference images with the Khronos glTF Sample Renderer in headless Chromium.
// Run through scripts/peers/render_khronos.sh, which installs what this needs outside the repository
// and passes:
//   node render_khronos.mjs --data DIR [--out DIR] --modules DIR/node_modules --chromium PATH
//        [--precision highp|as-is] --command "..."
// It serves (on 127.0.0.1 only) khronos_page.html, the renderer's dist/ and the data directory,
// renders every (asset, environment) pair at 256 x 256, writes DIR/khronos_<asset>_<env>.png and
// DIR/manifest.json, and checks the environment rotation with a diagnostic render (see README.md).
import { createServer } from 'node:http';
import { readFileSync, writeFileSync, existsSync } from 'node:fs';
import { createHash } from 'node:crypto';
import { execFileSync } from 'node:child_process';
import { deflateSync } from 'node:zlib';
import path from 'node:path';
import { fileURLToPath } from 'node:url';

const here = path.dirname(fileURLToPath(import.meta.url));
const args = {};
for (let i = 2; i < process.argv.length; i += 2) args[process.argv[i].replace(/^--/, '')] = process.argv[i + 1];
const DATA = path.resolve(args.data);
const OUT = path.resolve(args.out || args.data);   // where the PNGs and manifest.json go
const MODULES = path.resolve(args.modules);
const CHROMIUM = args.chromium;
const COMMAND = args.command || '';
// 'highp' (default): the renderer's shaders get highp int and sampler precision (see khronos_page.html
// and README.md); 'as-is': unchanged (on llvmpipe its IBL prefilter then collapses).
const PRECISION = args.precision || 'highp';
if (!['highp', 'as-is'].includes(PRECISION)) throw new Error('--precision highp|as-is');
const VIEWER = path.join(MODULES, '@khronosgroup', 'gltf-viewer');
const VIEWER_DIST = path.join(VIEWER, 'dist');
const { chromium } = await import(path.join(MODULES, 'playwright-core', 'index.mjs'));

const SIZE = 256;
// The Khronos renderer's own default (GltfState.renderingParameters.environmentRotation); kept.
const KHRONOS_ENV_ROTATION = 90.0;
// What mvr's --env-rotation must be to see the environment as the Khronos renderer does with the
// above (derived from the renderer's source in README.md; checked below by the diagnostic render).
const MVR_ENV_ROTATION = 180.0;
// ANGLE on Mesa's EGL/GLES (llvmpipe here): --use-angle=gl-egl. Chromium block-lists llvmpipe for
// WebGL (and will not fall back to SwiftShader without --enable-unsafe-swiftshader, which we do not
// want), so --ignore-gpu-blocklist is what makes WebGL2 exist at all. playwright-core adds its own
// defaults (--no-sandbox as root, --headless, ...).
const CHROMIUM_FLAGS = ['--headless=new', '--use-angle=gl-egl', '--ignore-gpu-blocklist'];

const ASSETS = [
    { name: 'spheres', file: 'spheres.gltf', camera: 0 },
    { name: 'textured', file: 'textured.gltf', camera: 0 },
    { name: 'coated', file: 'coated.gltf', camera: 0 },
    { name: 'glass', file: 'glass.gltf', camera: 0 },
    { name: 'spec_gloss', file: 'spec_gloss.gltf', camera: 0 },
    { name: 'films', file: 'films.gltf', camera: 0 },
    { name: 'sheen', file: 'sheen.gltf', camera: 0 },
    { name: 'principled', file: 'principled.gltf', camera: 0 },
];
const ENVS = [
    { name: 'uniform', file: 'uniform.hdr' },
    { name: 'sky', file: 'sky.hdr' },
];
const DIAG = { name: 'diag_mirror', file: 'diag_mirror.gltf', camera: 0, env: 'diag_axes.hdr', envName: 'diag_axes' };

// ------------------------------------------------------------------ PNG (8-bit RGB/RGBA, no colour chunks)
const CRC_TABLE = new Int32Array(256).map((_, n) => {
    let c = n;
    for (let k = 0; k < 8; k++) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1;
    return c;
});
function crc32(buf) {
    let c = -1;
    for (const b of buf) c = CRC_TABLE[(c ^ b) & 255] ^ (c >>> 8);
    return (c ^ -1) >>> 0;
}
function chunk(type, data) {
    const len = Buffer.alloc(4); len.writeUInt32BE(data.length);
    const td = Buffer.concat([Buffer.from(type, 'ascii'), data]);
    const crc = Buffer.alloc(4); crc.writeUInt32BE(crc32(td));
    return Buffer.concat([len, td, crc]);
}
// rows: top row first, each width*channels bytes
function encodePng(width, height, channels, rows) {
    const stride = width * channels;
    const raw = Buffer.alloc((stride + 1) * height);
    let prev = Buffer.alloc(stride);
    for (let y = 0; y < height; y++) {
        const row = rows[y];
        // choose the filter with the smallest sum of absolute values (the usual heuristic)
        let best = null, bestSum = Infinity, bestType = 0;
        for (let t = 0; t < 5; t++) {
            const out = Buffer.alloc(stride);
            let sum = 0;
            for (let i = 0; i < stride; i++) {
                const a = i >= channels ? row[i - channels] : 0, b = prev[i], c = i >= channels ? prev[i - channels] : 0;
                let p;
                if (t === 0) p = 0; else if (t === 1) p = a; else if (t === 2) p = b;
                else if (t === 3) p = (a + b) >> 1;
                else { const q = a + b - c, pa = Math.abs(q - a), pb = Math.abs(q - b), pc = Math.abs(q - c); p = pa <= pb && pa <= pc ? a : pb <= pc ? b : c; }
                out[i] = (row[i] - p) & 255;
                sum += out[i] < 128 ? out[i] : 256 - out[i];
            }
            if (sum < bestSum) { bestSum = sum; best = out; bestType = t; }
        }
        raw[y * (stride + 1)] = bestType;
        best.copy(raw, y * (stride + 1) + 1);
        prev = Buffer.from(row);
    }
    const ihdr = Buffer.alloc(13);
    ihdr.writeUInt32BE(width, 0); ihdr.writeUInt32BE(height, 4);
    ihdr[8] = 8; ihdr[9] = channels === 4 ? 6 : 2; ihdr[10] = 0; ihdr[11] = 0; ihdr[12] = 0;
    return Buffer.concat([Buffer.from([137, 80, 78, 71, 13, 10, 26, 10]), chunk('IHDR', ihdr),
        chunk('IDAT', deflateSync(raw, { level: 9 })), chunk('IEND', Buffer.alloc(0))]);
}
// GL pixels (bottom row first, RGBA) -> top-first rows; RGB when every alpha is 255
function glToRows(px, width, height) {
    let opaque = true;
    for (let i = 3; i < px.length; i += 4) if (px[i] !== 255) { opaque = false; break; }
    const channels = opaque ? 3 : 4;
    const rows = [];
    for (let y = 0; y < height; y++) {
        const src = (height - 1 - y) * width * 4;
        const row = Buffer.alloc(width * channels);
        for (let x = 0; x < width; x++) for (let c = 0; c < channels; c++) row[x * channels + c] = px[src + x * 4 + c];
        rows.push(row);
    }
    return { rows, channels, opaque };
}

// ------------------------------------------------------------------ static server (loopback only)
const MIME = { '.html': 'text/html', '.js': 'text/javascript', '.mjs': 'text/javascript', '.wasm': 'application/wasm',
    '.gltf': 'model/gltf+json', '.bin': 'application/octet-stream', '.png': 'image/png', '.hdr': 'application/octet-stream',
    '.json': 'application/json', '.map': 'application/json' };
// The sheen E LUT (lut_sheen_E.png) is not in the renderer's npm package. Whatever is served here is
// never read: 1.1.0 marks its texture initialized without uploading it (loadEnvironment:
// `sheenELut.initialized = true; // iblsampler has already initialized the texture`), so its albedo
// scaling samples an incomplete texture, which reads 0: no albedo scaling under the sheen. (Checked:
// this white stand-in and a real table of E give byte-identical renders of sheen.gltf.)
const SHEEN_STANDIN = encodePng(1, 1, 3, [Buffer.from([255, 255, 255])]);
function resolve(url) {
    const p = decodeURIComponent(new URL(url, 'http://x').pathname);
    if (p === '/' || p === '/page.html') return path.join(here, 'khronos_page.html');
    const map = [['/viewer/', VIEWER_DIST], ['/libs/', path.join(VIEWER_DIST, 'libs')], ['/data/', DATA]];
    for (const [prefix, dir] of map) {
        if (p.startsWith(prefix)) {
            const f = path.resolve(dir, '.' + p.slice(prefix.length - 1));
            if (f.startsWith(dir + path.sep)) return f;
        }
    }
    return null;
}
const requests = [];
const server = createServer((req, res) => {
    if (req.url === '/favicon.ico') { res.writeHead(204); res.end(); return; }
    if (req.url === '/lut_sheen_E.png') { res.writeHead(200, { 'Content-Type': 'image/png' }); res.end(SHEEN_STANDIN); return; }
    const f = resolve(req.url);
    if (!f || !existsSync(f)) { requests.push('404 ' + req.url); res.writeHead(404); res.end(); return; }
    res.writeHead(200, { 'Content-Type': MIME[path.extname(f)] || 'application/octet-stream', 'Cache-Control': 'no-store' });
    res.end(readFileSync(f));
});
await new Promise((r) => server.listen(0, '127.0.0.1', r));
const BASE = `http://127.0.0.1:${server.address().port}`;

// ------------------------------------------------------------------ rendering
const browser = await chromium.launch({ executablePath: CHROMIUM, headless: true, args: CHROMIUM_FLAGS });
const browserVersion = browser.version();
const consoleLog = [];

// One page per environment: the environment is loaded and prefiltered once, then every asset is
// rendered with it (a fresh GltfState each).
async function renderEnv(env, assets, background) {
    const page = await browser.newPage({ viewport: { width: SIZE, height: SIZE }, deviceScaleFactor: 1 });
    page.on('console', (m) => consoleLog.push(`[${env}] ${m.type()}: ${m.text()}`));
    page.on('pageerror', (e) => consoleLog.push(`[${env}] pageerror: ${e.message}`));
    await page.goto(`${BASE}/page.html`);
    await page.waitForFunction(() => window.mvrReady === true);
    const r = await page.evaluate((o) => window.mvrRender(o), {
        hdr: `/data/${env}`, assets: assets.map((a) => ({ gltf: `/data/${a.file}`, cameraIndex: a.camera })),
        width: SIZE, height: SIZE, environmentRotation: KHRONOS_ENV_ROTATION, background, highp: PRECISION === 'highp',
    });
    await page.close();
    if (!r.info.float_ibl) throw new Error('no float render targets: the renderer would filter the environment in 8 bits');
    return r.results.map((res, i) => {
        const what = `${assets[i].name}/${env}`;
        if (!res.stable) throw new Error(`${what}: frames did not settle`);
        if (res.gl_error !== 0) throw new Error(`${what}: GL error ${res.gl_error}`);
        return { px: Buffer.from(res.pixels, 'base64'), info: { ...r.info, ...res, pixels: undefined } };
    });
}

function writePng(file, px) {
    const { rows, channels, opaque } = glToRows(px, SIZE, SIZE);
    const png = encodePng(SIZE, SIZE, channels, rows);
    writeFileSync(path.join(OUT, file), png);
    return { bytes: png.length, sha256: createHash('sha256').update(png).digest('hex'), opaque };
}

function stats(px) {
    let lit = 0, max = 0, sum = 0;
    for (let i = 0; i < px.length; i += 4) {
        const m = Math.max(px[i], px[i + 1], px[i + 2]);
        if (m > 8) lit++;
        if (m > max) max = m;
        sum += px[i] + px[i + 1] + px[i + 2];
    }
    return { lit_pixels: lit, max_value: max, mean_value: +(sum / (px.length / 4 * 3)).toFixed(2) };
}

// ------------------------------------------------------------------ rotation check
// mvr's model of the diagnostic scene: a unit mirror sphere at the origin, the camera at (0, 0, 3)
// looking down -Z with yfov 60 degrees, background = the environment. For each candidate transform
// T of the environment (mvr rotation R in {0, 90, 180, 270}, optionally mirrored in x and/or
// flipped in y) classify every pixel by the axis cap mvr would see, and count agreement with the
// cap the Khronos render shows.
const CAPS = [[[1, 0, 0], [1, 0, 0]], [[-1, 0, 0], [0, 1, 0]], [[0, 1, 0], [0, 0, 1]],
    [[0, -1, 0], [1, 1, 0]], [[0, 0, 1], [1, 0, 1]], [[0, 0, -1], [0, 1, 1]]];
const CAP_COS = Math.cos(35 * Math.PI / 180), GREY = 0.05;
const PALETTE = [...CAPS.map((c) => c[1]), [GREY, GREY, GREY]];
const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
function capOf(d) {            // index into PALETTE, or -1 near a cap's edge (ambiguous)
    let best = 6;
    for (let i = 0; i < 6; i++) {
        const c = dot(d, CAPS[i][0]);
        if (Math.abs(Math.acos(Math.min(1, c)) - 35 * Math.PI / 180) < 4 * Math.PI / 180) return -1;
        if (c > CAP_COS) best = i;
    }
    return best;
}
function classify(rgb) {       // Khronos pixel (gamma 2.2 encoded) -> nearest palette entry
    const lin = rgb.map((v) => Math.pow(v / 255, 2.2));
    let best = 0, bd = Infinity;
    PALETTE.forEach((p, i) => { const d = (p[0] - lin[0]) ** 2 + (p[1] - lin[1]) ** 2 + (p[2] - lin[2]) ** 2; if (d < bd) { bd = d; best = i; } });
    return best;
}
function rotY(deg, d) {        // standard right-handed rotation about +Y (counter-clockwise seen from above)
    const a = deg * Math.PI / 180, c = Math.cos(a), s = Math.sin(a);
    return [c * d[0] + s * d[2], d[1], -s * d[0] + c * d[2]];
}
function hitSphere(o, d, r) {
    const b = dot(o, d), c = dot(o, o) - r * r, disc = b * b - c;
    if (disc < 0) return null;
    const t = -b - Math.sqrt(disc);
    return t > 0 ? [o[0] + t * d[0], o[1] + t * d[1], o[2] + t * d[2]] : null;
}
function rotationCheck(px) {
    const tanHalf = Math.tan(30 * Math.PI / 180), eye = [0, 0, 3];
    const candidates = [];
    for (const mirrorX of [false, true]) for (const flipY of [false, true]) for (const R of [0, 90, 180, 270]) candidates.push({ R, mirrorX, flipY });
    const samples = [];   // [seen, want_0 .. want_15] for every usable pixel
    for (let y = 0; y < SIZE; y++) {
        for (let x = 0; x < SIZE; x++) {
            const nx = ((x + 0.5) / SIZE * 2 - 1) * tanHalf, ny = (1 - (y + 0.5) / SIZE * 2) * tanHalf;
            const l = Math.hypot(nx, ny, 1), d = [nx / l, ny / l, -1 / l];
            const hIn = hitSphere(eye, d, 0.97), hOut = hitSphere(eye, d, 1.03);
            if (!!hIn !== !!hOut) continue;                       // silhouette: skip
            let r = d;
            const h = hitSphere(eye, d, 1.0);
            if (h && hIn) { const k = 2 * dot(d, h); r = [d[0] - k * h[0], d[1] - k * h[1], d[2] - k * h[2]]; }
            const wants = candidates.map((c) => {
                const e = [c.mirrorX ? -r[0] : r[0], c.flipY ? -r[1] : r[1], r[2]];
                return capOf(rotY(-c.R, e));                       // mvr: d sees R_y(-R) d
            });
            if (wants.some((w) => w < 0)) continue;                // near a cap's edge for some candidate
            const gl = ((SIZE - 1 - y) * SIZE + x) * 4;
            samples.push([classify([px[gl], px[gl + 1], px[gl + 2]]), ...wants]);
        }
    }
    candidates.forEach((c, i) => {
        c.agreement = +(samples.filter((s) => s[0] === s[i + 1]).length / samples.length).toFixed(4);
    });
    const order = candidates.map((c, i) => i).sort((a, b) => candidates[b].agreement - candidates[a].agreement);
    const bi = order[0];
    // Against the best, each other candidate is judged only on the pixels where the two predict
    // different caps: there the render must show the best's cap, not the other's.
    candidates.forEach((c, i) => {
        if (i === bi) return;
        const diff = samples.filter((s) => s[i + 1] !== s[bi + 1]);
        c.pixels_differing_from_best = diff.length;
        c.best_right = +(diff.filter((s) => s[0] === s[bi + 1]).length / Math.max(1, diff.length)).toFixed(4);
        c.this_right = +(diff.filter((s) => s[0] === s[i + 1]).length / Math.max(1, diff.length)).toFixed(4);
    });
    return { pixels: samples.length, ranked: order.map((i) => candidates[i]) };
}

// ------------------------------------------------------------------ main
function sh(cmd, argv) { try { return execFileSync(cmd, argv, { encoding: 'utf8' }).trim(); } catch { return null; } }
const pkg = JSON.parse(readFileSync(path.join(VIEWER, 'package.json'), 'utf8'));
const pw = JSON.parse(readFileSync(path.join(MODULES, 'playwright-core', 'package.json'), 'utf8'));
const t0 = Date.now();
const images = [];
let glInfo = null;

const [diag] = await renderEnv(DIAG.env, [DIAG], true);
const diagFile = `khronos_${DIAG.name}_${DIAG.envName}.png`;
const diagPng = writePng(diagFile, diag.px);
const check = rotationCheck(diag.px);
const best = check.ranked[0];
const describe = (c) => `mvr rotation ${c.R}${c.mirrorX ? ', mirrored in x' : ''}${c.flipY ? ', flipped in y' : ''}`;
const worst = check.ranked.slice(1).reduce((w, c) => (c.best_right < w.best_right ? c : w));
console.log(`rotation check: best ${describe(best)}, agreement ${best.agreement} on ${check.pixels} pixels; ` +
    `runner-up ${describe(check.ranked[1])} ${check.ranked[1].agreement}; on the pixels where another candidate differs ` +
    `from the best, the render shows the best's cap in >= ${worst.best_right} of them (${describe(worst)}, ${worst.pixels_differing_from_best} pixels)`);
const checkOk = best.R === MVR_ENV_ROTATION && !best.mirrorX && !best.flipY && best.agreement > 0.97 &&
    check.ranked.slice(1).every((c) => c.pixels_differing_from_best > 500 && c.best_right > 0.9);

for (const env of ENVS) {
    const rendered = await renderEnv(env.file, ASSETS, false);
    for (const [i, asset] of ASSETS.entries()) {
        const r = rendered[i];
        glInfo = glInfo || r.info;
        const file = `khronos_${asset.name}_${env.name}.png`;
        const png = writePng(file, r.px);
        const st = stats(r.px);
        console.log(`${file}: ${png.bytes} bytes, ${r.info.frames} frames, lit pixels ${st.lit_pixels}, max ${st.max_value}, mean ${st.mean_value}`);
        if (st.lit_pixels < 2000 || st.max_value < 64) throw new Error(`${file}: looks black or empty (${JSON.stringify(st)})`);
        images.push({
            file, asset: asset.file, environment: env.file, width: SIZE, height: SIZE, camera_index: asset.camera,
            tone_mapping: 'none', exposure: 1.0, encoding: 'gamma2.2', background: 'clear colour (0, 0, 0, 1)',
            environment_rotation_khronos_deg: KHRONOS_ENV_ROTATION, env_rotation_mvr_deg: MVR_ENV_ROTATION, env_mirror: false,
            ibl_intensity: 1.0, punctual_lights: false, antialias: false, channels: png.opaque ? 'RGB' : 'RGBA',
            sha256: png.sha256, stats: st,
        });
    }
}
await browser.close();
server.close();

const manifest = {
    description: 'Reference images of tests/data/peers/ assets rendered by the Khronos glTF Sample Renderer; see README.md',
    command: COMMAND,
    renderer: { package: pkg.name, version: pkg.version, playwright_core: pw.version, node: process.version,
        precision: PRECISION, precision_patch: glInfo.precision_patch,
        precision_note: PRECISION === 'highp'
            ? 'every shader that declares "precision highp float;" also gets highp int, sampler2D and samplerCube: on Mesa llvmpipe mediump int is 16 bits (the Hammersley radical inverse becomes 0 and the IBL prefilter and GGX LUT collapse) and default-precision samplers return fp16'
            : 'shaders unchanged: on Mesa llvmpipe the IBL prefilter and GGX LUT collapse (see README.md)' },
    browser: { chromium: browserVersion, binary: CHROMIUM, flags: CHROMIUM_FLAGS, user_agent: glInfo.user_agent },
    gl: { renderer: glInfo.gl_renderer, vendor: glInfo.gl_vendor, version: glInfo.gl_version, glsl: glInfo.glsl_version,
        mesa: sh('dpkg-query', ['-W', '-f=${Version}', 'libgl1-mesa-dri']), float_ibl_targets: glInfo.float_ibl },
    settings: {
        size: [SIZE, SIZE], camera: 'the file\'s camera (state.cameraIndex)', tone_mapping: 'None (linear, clamped at 1.0)',
        exposure: 1.0, encoding: 'gamma2.2', encoding_note: 'stored value = round(255 * pow(clamp(c, 0, 1), 1/2.2)); decode with pow(v/255, 2.2), not the sRGB curve',
        environment_rotation_khronos_deg: KHRONOS_ENV_ROTATION, env_rotation_mvr_deg: MVR_ENV_ROTATION, env_mirror: false,
        ibl: 'environment only (usePunctual false, useDirectionalLightsWithDisabledIBL false, iblIntensity 1)',
        background: 'not drawn (renderEnvironmentMap false); clear colour (0, 0, 0, 1)', antialias: false,
        ibl_filtering: { cube_size: 256, ggx_samples: 1024, lambertian_samples: 2048, lowest_mip: 4, mip_count: glInfo.ibl.mipCount,
            intensity_scale: glInfo.ibl.iblIntensityScale, lut: 'GGX LUT computed at load (1024 x 1024, 512 samples)' },
    },
    rotation_check: {
        image: diagFile, asset: DIAG.file, environment: DIAG.env, background: 'environment, unblurred', sha256: diagPng.sha256,
        method: 'mvr model (mirror sphere + background) classified per pixel against the Khronos render for 16 candidate transforms',
        pixels: check.pixels,
        criterion: 'best = the mvr transform whose predicted cap agrees with most pixels; for every other candidate, on the pixels where it predicts a different cap than the best, the render shows the best\'s cap (best_right) and not its own (this_right)',
        best: { env_rotation_mvr_deg: best.R, mirror_x: best.mirrorX, flip_y: best.flipY, agreement: best.agreement },
        candidates: check.ranked.map((c) => ({ env_rotation_mvr_deg: c.R, mirror_x: c.mirrorX, flip_y: c.flipY, agreement: c.agreement,
            pixels_differing_from_best: c.pixels_differing_from_best, best_right: c.best_right, this_right: c.this_right })),
        passed: checkOk,
    },
    images,
    render_seconds: +((Date.now() - t0) / 1000).toFixed(1),
    console: consoleLog.filter((l) => !/GPU stall due to ReadPixels/.test(l)),
    not_found: requests,
};
writeFileSync(path.join(OUT, 'manifest.json'), JSON.stringify(manifest, null, 2) + '\n');
console.log(`wrote ${images.length} images and manifest.json in ${manifest.render_seconds} s`);
if (!checkOk) { console.error('rotation check FAILED: see manifest.json rotation_check'); process.exit(1); }
