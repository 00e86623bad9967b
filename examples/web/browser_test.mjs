// The web demo in headless Chromium against the C++ render of the same view:
//   node examples/web/browser_test.mjs SCATTERLUT RENDER_FOG WORK_DIR [--chromium PATH]
//        [--shaders DIR (the generated .essl / .wgsl snippets; default build/tables/shaders)]
//        [--backend webgl2|webgpu] [--require]
// generates the default tables (--format all) into WORK_DIR/tables, renders
// WORK_DIR/spots_table.png with render_fog (C++, the tables through scatterlut::tables: the
// street's lamps as spots, a car's headlights and a bare bulb, the picture the demo draws), opens
// the page (?test=1, render_fog's exposure) in Chromium with SwiftShader's WebGL2 (the .essl
// snippets; the default) or WebGPU (--backend webgpu: the .wgsl snippets, fog_webgpu.mjs), reads
// the frame back (WORK_DIR/browser_<tier>.png; browser_webgpu_<tier>.png) and requires PSNR >= 40 dB between the two
// tone-mapped 8-bit images, once per tier of the snippets (fast, accurate, airlight_F:
// docs/SHADERS.md, "Tiers"; fog.mjs's tier parameter), printing each tier's first frame (its
// shader's build on SwiftShader, then one draw); then opens the interactive page and waits for
// its controls (WebGL2 only: headless Chromium cannot present a WebGPU canvas on SwiftShader,
// so the WebGPU page draws the fixed view into a texture of its own).
// Without Chromium, the npm modules (npm ci in examples/web) or, for webgpu, a WebGPU adapter
// it prints "skipped: ..." and exits 77, or fails with --require.
import { execFileSync } from 'node:child_process';
import { existsSync, readFileSync, mkdirSync, writeFileSync } from 'node:fs';
import { inflateSync, deflateSync } from 'node:zlib';
import { join } from 'node:path';

const args = process.argv.slice(2);
const require = args.includes('--require');
const opt = (name) => { const i = args.indexOf(name); return i >= 0 ? args[i + 1] : undefined; };
const valued = ['--chromium', '--shaders', '--backend'];
const [scatterlut, renderFog, work] = args.filter((a, i) => !a.startsWith('--') && !(i > 0 && valued.includes(args[i - 1])));
if (!work) {
	console.error('usage: node browser_test.mjs SCATTERLUT RENDER_FOG WORK_DIR [--chromium PATH] [--shaders DIR] [--require]');
	process.exit(2);
}
function skip(why) {
	if (require) { console.error(`FAIL (required): ${why}`); process.exit(1); }
	console.log(`skipped: ${why}`);
	process.exit(77);
}
const backend = opt('--backend') ?? 'webgl2';
if (!['webgl2', 'webgpu'].includes(backend)) {
	console.error(`--backend: webgl2 or webgpu, not '${backend}'`);
	process.exit(2);
}
const chromium = opt('--chromium') ?? ['/usr/bin/chromium', '/usr/bin/chromium-browser'].find((p) => existsSync(p));
if (!chromium || !existsSync(chromium)) skip('chromium not found (Debian: apt-get install chromium)');
let puppeteer;
try {
	puppeteer = (await import('puppeteer-core')).default;
	await import('three');
} catch (e) {
	skip(`npm modules missing (run \`npm ci\` in examples/web, or \`make test\`): ${e.message}`);
}
const { startServer } = await import('./serve.mjs');

// Tables and the C++ picture.
const tables = join(work, 'tables');
mkdirSync(tables, { recursive: true });
execFileSync(scatterlut, ['generate', '--format', 'all', '--out', tables], { stdio: 'ignore' });
const out = execFileSync(renderFog, [join(tables, 'airlight_F.slut'), join(tables, 'near_light_E3.slut'), work]).toString();
// render_fog prints a block per picture pair (blank-line separated): the spots_ pair's exposure.
const spotsBlock = out.split('\n\n').find((b) => /^wrote \S*spots_table\.png/m.test(b)) ?? '';
const exposure = Number(/^exposure (\S+)/m.exec(spotsBlock)?.[1]);
if (!Number.isFinite(exposure)) throw new Error(`render_fog printed no exposure for spots_table.png:\n${out}`);

// A PNG (8-bit RGB, the project's encoder) → rows top to bottom.
function decodePng(bytes) {
	let p = 8, width = 0, height = 0;
	const idat = [];
	while (p < bytes.length) {
		const len = bytes.readUInt32BE(p), type = bytes.toString('latin1', p + 4, p + 8), data = bytes.subarray(p + 8, p + 8 + len);
		if (type === 'IHDR') {
			width = data.readUInt32BE(0); height = data.readUInt32BE(4);
			if (data[8] !== 8 || data[9] !== 2 || data[12] !== 0) throw new Error('expected an 8-bit RGB non-interlaced PNG');
		} else if (type === 'IDAT') idat.push(data);
		p += 12 + len;
	}
	const raw = inflateSync(Buffer.concat(idat)), stride = width * 3, img = new Uint8Array(stride * height);
	for (let y = 0; y < height; y++) {
		const f = raw[y * (stride + 1)], row = raw.subarray(y * (stride + 1) + 1, (y + 1) * (stride + 1));
		for (let x = 0; x < stride; x++) {
			const a = x >= 3 ? img[y * stride + x - 3] : 0, b = y ? img[(y - 1) * stride + x] : 0;
			const c = x >= 3 && y ? img[(y - 1) * stride + x - 3] : 0;
			const pa = Math.abs(b - c), pb = Math.abs(a - c), pc = Math.abs(a + b - 2 * c);
			const pred = [0, a, b, (a + b) >> 1, pa <= pb && pa <= pc ? a : pb <= pc ? b : c][f];
			img[y * stride + x] = (row[x] + pred) & 255;
		}
	}
	return { width, height, img };
}
const cpp = decodePng(readFileSync(join(work, 'spots_table.png')));
const t0 = Date.now();
// The page's waits guard against a hang, not a speed. Nearly all of the page's time is
// SwiftShader building the fragment shader (one frame takes 1.5-2 s once built): 11-22 s for
// the fixed view at load 10-25 on a 2-core machine, where the warp switch the snippets had
// until 2026-12-02 took 200-740 s (examples/web/bench_airlight.mjs, bench_compile.mjs;
// bench/README.md, "Compile cost on SwiftShader"). The whole test took 45 s at load 7
// (`ctest -R WebDemoChromium -V` prints the phases); 180 s per page is 8x the slowest build
// measured, and CTest's TIMEOUT (600 s) bounds it all.
const kPageWait_ms = 180000;
const phase = (what) => console.log(`[${((Date.now() - t0) / 1000).toFixed(1)} s] ${what}`);

// The page in Chromium.
const server = await startServer({ tables, shaders: opt('--shaders') });
const browser = await puppeteer.launch({
	executablePath: chromium, headless: true,
	args: ['--headless=new', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--no-sandbox', '--disable-gpu-sandbox',
		...(backend === 'webgpu' ? ['--enable-unsafe-webgpu', '--use-webgpu-adapter=swiftshader', '--enable-features=Vulkan'] : [])],
	// The page's first frame blocks its renderer until SwiftShader has compiled the shader, and
	// every DevTools call with it: puppeteer's default limit per call (180 s) would cut the
	// page wait short.
	protocolTimeout: kPageWait_ms + 60000,
});
const kTiers = ['fast', 'accurate', 'airlight_F'];
const frames = {};
try {
	for (const tier of kTiers) {
		const page = await browser.newPage();
		const logs = [];
		page.on('console', (m) => logs.push(m.text()));
		const start = Date.now();
		await page.goto(`http://127.0.0.1:${server.address().port}/?test=1&tier=${tier}&exposure=${exposure}&backend=${backend}`);
		await page.waitForFunction('window.slutDone || window.slutError', { timeout: kPageWait_ms });
		const error = await page.evaluate('window.slutError');
		if (error && backend === 'webgpu' && /gives no WebGPU adapter/.test(error)) skip(`Chromium gives no WebGPU adapter here: ${error}`);
		if (error) throw new Error(`page (tier ${tier}) failed: ${error}\n${logs.join('\n')}`);
		const used = await page.evaluate('window.slutBackend');
		if (used !== backend) throw new Error(`the page drew with ${used}, not ${backend}`);
		const ran = await page.evaluate('window.slutTier');
		if (ran !== tier) throw new Error(`tier ${tier} asked, ${ran} ran: ${logs.join('\n')}`);
		frames[tier] = await page.evaluate('window.slutFrame');
		phase(`tier ${tier}: fixed view rendered and read back, first frame (load, build, draw) ${((Date.now() - start) / 1000).toFixed(1)} s`);
		await page.close();
	}
	// The interactive page (no test parameter) comes up with its controls and no error. Not for
	// WebGPU: headless Chromium cannot present a WebGPU canvas on SwiftShader here (its swap
	// chain finds no shared-image backing and the GPU instance is dropped); the fixed views above
	// are drawn into a texture of the page's own.
	if (backend === 'webgpu') {
		console.log('interactive page: not checked on WebGPU (headless Chromium cannot present a WebGPU canvas on SwiftShader)');
	} else {
		const live = await browser.newPage();
		await live.goto(`http://127.0.0.1:${server.address().port}/?backend=${backend}`);
		await live.waitForFunction("document.querySelector('.lil-gui') || window.slutError", { timeout: kPageWait_ms });
		const liveError = await live.evaluate('window.slutError');
		if (liveError) throw new Error(`interactive page failed: ${liveError}`);
		phase('interactive page up');
	}
} finally {
	await browser.close();
	server.close();
}

// The browser's frame as WORK_DIR/browser.png (8-bit RGB, filter 0), to look at.
function encodePng(width, height, rgb) {
	const crcTable = Array.from({ length: 256 }, (_, n) => {
		let c = n;
		for (let k = 0; k < 8; k++) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1;
		return c >>> 0;
	});
	const crc = (buf) => { let c = 0xffffffff; for (const x of buf) c = crcTable[(c ^ x) & 255] ^ (c >>> 8); return (c ^ 0xffffffff) >>> 0; };
	const chunk = (type, data) => {
		const out = Buffer.alloc(12 + data.length);
		out.writeUInt32BE(data.length, 0);
		out.write(type, 4, 'latin1');
		data.copy(out, 8);
		out.writeUInt32BE(crc(out.subarray(4, 8 + data.length)), 8 + data.length);
		return out;
	};
	const ihdr = Buffer.alloc(13);
	ihdr.writeUInt32BE(width, 0); ihdr.writeUInt32BE(height, 4); ihdr[8] = 8; ihdr[9] = 2;
	const raw = Buffer.alloc((width * 3 + 1) * height);
	for (let y = 0; y < height; y++) for (let x = 0; x < width * 3; x++) raw[y * (width * 3 + 1) + 1 + x] = rgb[y * width * 3 + x];
	return Buffer.concat([Buffer.from([137, 80, 78, 71, 13, 10, 26, 10]), chunk('IHDR', ihdr), chunk('IDAT', deflateSync(raw)), chunk('IEND', Buffer.alloc(0))]);
}
let failed = false;
for (const tier of kTiers) {
	const frame = frames[tier];
	writeFileSync(join(work, `browser_${backend === 'webgpu' ? 'webgpu_' : ''}${tier}.png`), encodePng(cpp.width, cpp.height, frame));
	if (frame.length !== cpp.img.length) throw new Error(`frame has ${frame.length} values, the C++ picture ${cpp.img.length}`);
	let mse = 0, max = 0;
	for (let k = 0; k < frame.length; k++) {
		const d = frame[k] - cpp.img[k];
		mse += d * d;
		max = Math.max(max, Math.abs(d));
	}
	mse /= frame.length;
	const psnr = mse > 0 ? 10 * Math.log10((255 * 255) / mse) : Infinity;
	console.log(`tier ${tier}: browser (Chromium, SwiftShader ${backend === 'webgpu' ? 'WebGPU, WGSL' : 'WebGL2, GLSL ES'}) vs render_fog: ${cpp.width}x${cpp.height}, PSNR ${psnr.toFixed(2)} dB, max |diff| ${max} levels, exposure ${exposure}`);
	if (!(psnr >= 40)) {
		console.error(`FAIL: tier ${tier}: PSNR below 40 dB`);
		failed = true;
	}
}
if (failed) process.exit(1);
