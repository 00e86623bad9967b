// The WGSL snippets (build/tables/shaders/scatterlut_*.wgsl) run in headless Chromium's WebGPU,
// as compute passes over the GLSL shader tests' own tables and queries, against their C++
// references at their tolerances (ctest WebGPUSnippets; docs/SHADERS.md, "WGSL"):
//   node tests/shaders/webgpu_snippets.mjs --work DIR --shaders DIR --python PY --cpp "CPP ARGS"
//        [--chromium PATH] [--only SUBSTRING] [--slow] [--require] TEST_BINARY...
// 1. each TEST_BINARY (test_shaders, test_shaders_nearlight, ...) writes its cases
//    (tests/shaders/wgsl_cases.hpp: SLUT_WGSL_CASES=FILE): table, uniform block, per-query body
//    in the GLSL subset, queries, references, per tier the tolerance a + b * w;
// 2. per case set and tier, tables/shaders/wgsl/slut_wgsl.py harness translates the body
//    against the snippet (DIR/wgsl/scatterlut_<snippet>.wgsl.in) into a compute shader that is
//    appended to the generated scatterlut_<snippet>[_<tier>].wgsl itself;
// 3. a page served from 127.0.0.1 (WebGPU needs a secure context) runs each module on
//    Chromium's WebGPU (SwiftShader where there is no GPU): an r32float texture, textureLoad for
//    the texel fetches, and for the fast tier a linear clamp-to-edge sampler (the device feature
//    float32-filterable); it also measures the filter's weight error w on a 2 x 1 ramp;
// 4. per query: relative error against the reference (infinities must match, NaN never does, 0
//    only by 0; references below 1e-30 absolutely against 1e-30), <= a + b * w; no NaN, nothing
//    negative. Per case set, tier and label: n, max, p99, median, worst error/tolerance; all of it
//    also in DIR/agreement.json.
// Without Chromium, the npm modules (npm ci in examples/web) or a WebGPU adapter it prints
// "skipped: ..." and exits 77, or fails with --require. An adapter without float32-filterable
// skips the fast tier's cases (said so), never silently. On SwiftShader, case sets whose code
// takes minutes to compile there (slow_on_swiftshader: why) are skipped, saying so, unless --slow.
import { execFileSync, spawnSync } from 'node:child_process';
import { createServer } from 'node:http';
import { createRequire } from 'node:module';
import { existsSync, mkdirSync, readFileSync, writeFileSync } from 'node:fs';
import { basename, dirname, join, resolve } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

const here = dirname(fileURLToPath(import.meta.url));
const root = resolve(here, '..', '..');
const args = process.argv.slice(2);
const valued = ['--work', '--shaders', '--python', '--cpp', '--chromium', '--only'];
const slow = args.includes('--slow');
const opt = (name) => { const i = args.indexOf(name); return i >= 0 ? args[i + 1] : undefined; };
const require = args.includes('--require');
const binaries = args.filter((a, i) => !a.startsWith('--') && !(i > 0 && valued.includes(args[i - 1])));
const work = opt('--work'), shaders = opt('--shaders'), python = opt('--python') ?? 'python3', cpp = opt('--cpp');
const only = opt('--only');
if (!work || !shaders || !cpp || binaries.length === 0) {
	console.error('usage: node webgpu_snippets.mjs --work DIR --shaders DIR --python PY --cpp "CPP ARGS" ' +
		'[--chromium PATH] [--only SUBSTRING] [--require] TEST_BINARY...');
	process.exit(2);
}
function skip(why) {
	if (require) { console.error(`FAIL (required): ${why}`); process.exit(1); }
	console.log(`skipped: ${why}`);
	process.exit(77);
}
const t0 = Date.now();
const phase = (what) => console.log(`[${((Date.now() - t0) / 1000).toFixed(1)} s] ${what}`);

// ---------------------------------------------------------------- what the test needs
const chromium = opt('--chromium') ?? ['/usr/bin/chromium', '/usr/bin/chromium-browser'].find((p) => existsSync(p));
if (!chromium || !existsSync(chromium)) skip('chromium not found (Debian: apt-get install chromium)');
let puppeteer;
try {
	const web = createRequire(join(root, 'examples', 'web', 'package.json'));
	puppeteer = (await import(pathToFileURL(web.resolve('puppeteer-core')).href)).default;
} catch (e) {
	skip(`puppeteer-core missing (run \`npm ci\` in examples/web, or \`make test\`): ${e.message}`);
}
const translator = join(root, 'tables', 'shaders', 'wgsl', 'slut_wgsl.py');
mkdirSync(work, { recursive: true });

// ---------------------------------------------------------------- 1. the cases
const sets = [];
for (const bin of binaries) {
	const file = join(work, `${basename(bin)}.json`);
	const r = spawnSync(bin, [], { env: { ...process.env, SLUT_WGSL_CASES: file }, encoding: 'utf8' });
	if (r.status !== 0) throw new Error(`${bin} did not write its cases (status ${r.status}):\n${r.stdout}\n${r.stderr}`);
	for (const c of JSON.parse(readFileSync(file, 'utf8'))) sets.push({ ...c, source: basename(bin) });
}
phase(`cases: ${sets.length} sets, ${sets.reduce((n, c) => n + c.labels.length, 0)} queries`);

// ---------------------------------------------------------------- 2. the modules
const b64 = (s) => Buffer.from(s, 'base64');
const tierDefine = { '': [], fast: ['-DSLUT_TIER_FAST'], accurate: ['-DSLUT_TIER_ACCURATE'] };
const runs = []; // one per case set and tier
for (const [k, c] of sets.entries()) {
	if (only && !c.name.includes(only)) continue;
	const dir = join(work, `case${k}`);
	mkdirSync(dir, { recursive: true });
	writeFileSync(join(dir, 'texels.f32'), b64(c.texels));
	writeFileSync(join(dir, 'queries.f32'), b64(c.queries));
	writeFileSync(join(dir, 'params.bin'), b64(c.params));
	writeFileSync(join(dir, 'body.slsl'), c.body);
	for (const tier of c.tiers) {
		const suffix = tier.name ? `_${tier.name}` : '';
		const snippetFile = join(shaders, `scatterlut_${c.snippet}${suffix}.wgsl`);
		if (!existsSync(snippetFile)) throw new Error(`${snippetFile} is missing (build the target scatterlut_shaders)`);
		const harness = join(dir, `harness${suffix}.wgsl`);
		execFileSync(python, [translator, 'harness', `--cpp=${cpp}`, ...tierDefine[tier.name],
			'--snippet-in', join(shaders, 'wgsl', `scatterlut_${c.snippet}.wgsl.in`), '--body', join(dir, 'body.slsl'),
			'--params', c.params_decl, '--texture', c.texture, harness], { stdio: ['ignore', 'inherit', 'inherit'] });
		const snippet = readFileSync(snippetFile, 'utf8');
		const module = `${snippet}\n${readFileSync(harness, 'utf8')}`;
		writeFileSync(join(dir, `module${suffix}.wgsl`), module);
		// The code after the generated header: tiers whose code is the same run once.
		const code = snippet.slice(snippet.indexOf('// ==== BEGIN SHARED')) + readFileSync(harness, 'utf8');
		runs.push({ set: c, k, tier, url: `/case${k}/module${suffix}.wgsl`, code, file: basename(snippetFile) });
	}
}
phase(`modules: ${runs.length} (case set x tier), translated`);

// ---------------------------------------------------------------- 3. the page
const page_html = `<!doctype html><meta charset="utf-8"><title>scatterlut WGSL snippets</title>
<script type="module">
let device = null, filterable = false;
window.slutInit = async () => {
	if (!navigator.gpu) return { error: 'navigator.gpu is missing (isSecureContext ' + isSecureContext + ')' };
	const adapter = await navigator.gpu.requestAdapter();
	if (!adapter) return { error: 'requestAdapter() gave no adapter' };
	filterable = adapter.features.has('float32-filterable');
	device = await adapter.requestDevice({ requiredFeatures: filterable ? ['float32-filterable'] : [] });
	device.lost.then((info) => { window.slutLost = info.message; });
	const info = adapter.info || {};
	return { filterable, adapter: [info.vendor, info.architecture, info.device, info.description].filter(Boolean).join(' ') };
};
async function bytes(url) {
	const r = await fetch(url);
	if (!r.ok) throw new Error(url + ': ' + r.status);
	return new Uint8Array(await r.arrayBuffer());
}
// One compute pass: binding 0 the table (r32float), 4 its sampler (fast tier), 1 the inputs, 2 the
// n results, 3 the uniform block. Returns the results' bytes as base64, or an error.
async function run(code, texels, w, h, d, three_d, sampler_needed, inputs, n, params) {
	const usage = GPUTextureUsage.TEXTURE_BINDING | GPUTextureUsage.COPY_DST;
	const texture = device.createTexture({ size: [w, h, d], format: 'r32float', usage, dimension: three_d ? '3d' : '2d' });
	device.queue.writeTexture({ texture }, texels, { bytesPerRow: 4 * w, rowsPerImage: h }, [w, h, d]);
	device.pushErrorScope('validation');
	const module = device.createShaderModule({ code });
	const info = await module.getCompilationInfo();
	const errors = info.messages.filter((m) => m.type === 'error');
	if (errors.length) {
		device.popErrorScope();
		return { error: errors.slice(0, 5).map((m) => m.lineNum + ':' + m.linePos + ' ' + m.message).join('\\n') };
	}
	const warnings = info.messages.filter((m) => m.type !== 'info').length;
	const t0 = performance.now();
	const pipeline = await device.createComputePipelineAsync({ layout: 'auto', compute: { module, entryPoint: 'main' } });
	const t1 = performance.now();
	const buffer = (data, usage) => {
		const b = device.createBuffer({ size: Math.max(16, Math.ceil(data.byteLength / 16) * 16), usage: usage | GPUBufferUsage.COPY_DST });
		device.queue.writeBuffer(b, 0, data);
		return b;
	};
	const input = buffer(inputs, GPUBufferUsage.STORAGE);
	const uniform = buffer(params, GPUBufferUsage.UNIFORM);
	const output = device.createBuffer({ size: 4 * n, usage: GPUBufferUsage.STORAGE | GPUBufferUsage.COPY_SRC });
	const readback = device.createBuffer({ size: 4 * n, usage: GPUBufferUsage.MAP_READ | GPUBufferUsage.COPY_DST });
	const entries = [{ binding: 0, resource: texture.createView() }, { binding: 1, resource: { buffer: input } },
		{ binding: 2, resource: { buffer: output } }, { binding: 3, resource: { buffer: uniform } }];
	if (sampler_needed)
		entries.push({ binding: 4, resource: device.createSampler({ magFilter: 'linear', minFilter: 'linear',
			addressModeU: 'clamp-to-edge', addressModeV: 'clamp-to-edge', addressModeW: 'clamp-to-edge' }) });
	const group = device.createBindGroup({ layout: pipeline.getBindGroupLayout(0), entries });
	const encoder = device.createCommandEncoder();
	const pass = encoder.beginComputePass();
	pass.setPipeline(pipeline);
	pass.setBindGroup(0, group);
	pass.dispatchWorkgroups(Math.ceil(n / 64));
	pass.end();
	encoder.copyBufferToBuffer(output, 0, readback, 0, 4 * n);
	device.queue.submit([encoder.finish()]);
	await readback.mapAsync(GPUMapMode.READ);
	const t2 = performance.now();
	const result = new Uint8Array(readback.getMappedRange().slice(0));
	readback.unmap();
	const failed = await device.popErrorScope();
	if (failed) return { error: failed.message };
	for (const b of [input, uniform, output, readback]) b.destroy();
	texture.destroy();
	let s = '';
	for (let i = 0; i < result.length; i += 0x8000) s += String.fromCharCode(...result.subarray(i, i + 0x8000));
	return { results: btoa(s), warnings, build_ms: t1 - t0, run_ms: t2 - t1 };
}
window.slutRun = async (c) => {
	try {
		const [code, texels, inputs, params] = await Promise.all([fetch(c.module).then((r) => r.text()), bytes(c.texels),
			bytes(c.queries), bytes(c.params)]);
		return await run(code, texels, c.width, c.height, c.depth, c.texture === '3d', c.fast, inputs, c.n, params);
	} catch (e) { return { error: String(e && e.stack || e) + (window.slutLost ? ' (device lost: ' + window.slutLost + ')' : '') }; }
};
// The filter's weight error: a 2 x 1 ramp [0, 1], sampled linearly at texel coordinate f between
// the two centres, must give f: the largest |result - f| over 4096 fractions (all 24 bits used).
window.slutWeightError = async () => {
	const n = 4096, f = new Float32Array(n);
	for (let i = 0; i < n; ++i) f[i] = (0.5 + i * 0.6180339887498949) % 1;
	const code = \`@group(0) @binding(0) var ramp: texture_2d<f32>;
@group(0) @binding(4) var ramp_sampler: sampler;
@group(0) @binding(1) var<storage, read> q: array<f32>;
@group(0) @binding(2) var<storage, read_write> r: array<f32>;
@group(0) @binding(3) var<uniform> count: vec4<i32>;
@compute @workgroup_size(64) fn main(@builtin(global_invocation_id) id: vec3<u32>) {
	let i = i32(id.x);
	if (i < count.x) { r[i] = textureSampleLevel(ramp, ramp_sampler, vec2<f32>((q[i] + 0.5) / 2.0, 0.5), 0.0).r; }
}\`;
	const out = await run(code, new Float32Array([0, 1]), 2, 1, 1, false, true, f, n, new Int32Array([n, 0, 0, 0]));
	if (out.error) return out;
	const r = new Float32Array(Uint8Array.from(atob(out.results), (ch) => ch.charCodeAt(0)).buffer);
	let worst = 0;
	for (let i = 0; i < n; ++i) worst = Math.max(worst, Math.abs(r[i] - f[i]));
	return { weight_error: worst };
};
window.slutReady = true;
</script>`;

const server = createServer((req, res) => {
	const path = decodeURIComponent(new URL(req.url, 'http://x').pathname);
	if (path === '/') {
		res.writeHead(200, { 'Content-Type': 'text/html; charset=utf-8' });
		return res.end(page_html);
	}
	// Only the case directories this run wrote.
	const m = /^\/(case\d+)\/([a-z_]+\.(?:wgsl|f32|bin))$/.exec(path);
	if (!m || !existsSync(join(work, m[1], m[2]))) { res.writeHead(404); return res.end(); }
	res.writeHead(200, { 'Content-Type': m[2].endsWith('.wgsl') ? 'text/plain' : 'application/octet-stream' });
	res.end(readFileSync(join(work, m[1], m[2])));
});
await new Promise((r) => server.listen(0, '127.0.0.1', r));
const origin = `http://127.0.0.1:${server.address().port}`;
// A dispatch on SwiftShader takes seconds (compile included): puppeteer's default of 180 s per
// call is far above the slowest measured; CTest's TIMEOUT bounds the whole run.
const browser = await puppeteer.launch({
	executablePath: chromium, headless: true, protocolTimeout: 600000,
	args: ['--headless=new', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--enable-unsafe-webgpu',
		'--use-webgpu-adapter=swiftshader', '--enable-features=Vulkan', '--no-sandbox', '--disable-gpu-sandbox'],
});

// ---------------------------------------------------------------- 4. the comparison
function relErr(got, want) {
	const inf = (x) => x === Infinity || x === -Infinity;
	if (inf(want) || inf(got)) return got === want ? 0 : Infinity;
	if (Number.isNaN(got) || Number.isNaN(want)) return Infinity;
	if (want === 0) return got === 0 ? 0 : Infinity;
	if (Math.abs(want) < 1e-30) return Math.abs(got - want) / 1e-30; // float cannot hold it to full precision
	return Math.abs(got - want) / Math.abs(want);
}
const num = (x) => (x === 'inf' ? Infinity : x === '-inf' ? -Infinity : x === 'nan' ? NaN : x);
const fmt = (x) => (x === 0 ? '0' : Math.abs(x) < 1e-3 || Math.abs(x) >= 1e4 ? x.toExponential(2) : x.toPrecision(3));

let failures = 0;
const report = { adapter: null, weight_error: null, runs: [] };
try {
	const page = await browser.newPage();
	const logs = [];
	page.on('console', (m) => logs.push(m.text()));
	await page.goto(`${origin}/`);
	await page.waitForFunction('window.slutReady', { timeout: 60000 });
	const init = await page.evaluate('window.slutInit()');
	if (init.error) skip(`no WebGPU: ${init.error}`);
	report.adapter = init.adapter;
	phase(`WebGPU adapter: ${init.adapter}; float32-filterable: ${init.filterable}`);
	let weightError = null;
	if (init.filterable) {
		const we = await page.evaluate('window.slutWeightError()');
		if (we.error) throw new Error(`the filter ramp failed: ${we.error}`);
		weightError = we.weight_error;
		report.weight_error = weightError;
		phase(`filter weight error ${fmt(weightError)} (${weightError > 0 ? (-Math.log2(2 * weightError)).toFixed(1) : '24'} bits)`);
	}
	const done = new Map(); // case set and code -> results of a module already run
	for (const run of runs) {
		const c = run.set, n = c.labels.length, tierName = run.tier.name || 'none';
		const title = `${c.name} [${run.file}]`;
		const fast = run.tier.name === 'fast';
		if (c.slow_on_swiftshader && /swiftshader/i.test(init.adapter) && !slow) {
			if (run.tier === c.tiers[0])
				console.log(`${c.name}: not run on SwiftShader (--slow runs it): ${c.slow_on_swiftshader}`);
			report.runs.push({ set: c.name, tier: tierName, file: run.file, skipped: c.slow_on_swiftshader });
			continue;
		}
		if (fast && !init.filterable) {
			console.log(`${title}: skipped: the adapter lacks float32-filterable, which the fast tier's r32float filtering needs`);
			report.runs.push({ set: c.name, tier: tierName, file: run.file, skipped: 'no float32-filterable' });
			continue;
		}
		const key = `${run.k}\n${run.code}`;
		let out = done.get(key), reused = !!out;
		if (!out) {
			out = await page.evaluate((a) => window.slutRun(a), {
				module: run.url, texels: `/case${run.k}/texels.f32`, queries: `/case${run.k}/queries.f32`,
				params: `/case${run.k}/params.bin`, width: c.width, height: c.height, depth: c.depth, texture: c.texture,
				fast, n });
			if (out.error) {
				console.log(`FAIL ${title}: ${out.error}\n${logs.join('\n')}`);
				failures++;
				report.runs.push({ set: c.name, tier: tierName, file: run.file, error: out.error });
				continue;
			}
			done.set(key, out);
		}
		const got = new Float32Array(Buffer.from(out.results, 'base64').buffer.slice(0));
		const w = fast ? weightError : 0;
		const byLabel = new Map();
		let bad = 0, firstBad = -1;
		const queries = new Float32Array(b64(c.queries).buffer.slice(0));
		for (let i = 0; i < n; ++i) {
			const want = num(c.reference[i]), g = got[i];
			const e = relErr(g, want);
			const tol = run.tier.tol[i] + run.tier.tol_per_weight_error[i] * w;
			if (!byLabel.has(c.labels[i])) byLabel.set(c.labels[i], []);
			byLabel.get(c.labels[i]).push({ i, e, ratio: e / tol, tol });
			if (Number.isNaN(g) || g < 0) { if (bad++ === 0) firstBad = i; }
		}
		const timing = reused ? 'the same code as the run above on these queries: its results' :
			`build ${(out.build_ms / 1000).toFixed(1)} s, run ${(out.run_ms / 1000).toFixed(1)} s${out.warnings ? `, ${out.warnings} compiler messages` : ''}`;
		console.log(`${title} tier ${tierName}: ${n} queries (${timing})`);
		const entry = { set: c.name, tier: tierName, file: run.file, n, reused, build_s: out.build_ms / 1000, run_s: out.run_ms / 1000, labels: {} };
		for (const [label, rows] of byLabel) {
			const errs = rows.map((r) => r.e).sort((a, b) => a - b);
			const worst = rows.reduce((a, b) => (b.ratio > a.ratio ? b : a));
			const max = errs[errs.length - 1], p99 = errs[Math.floor(0.99 * (errs.length - 1))], median = errs[Math.floor(errs.length / 2)];
			const ok = worst.ratio <= 1;
			if (!reused || !ok) console.log(`  ${ok ? '  ' : 'FAIL'} ${label.padEnd(10)} n=${String(rows.length).padEnd(5)} max ${fmt(max).padEnd(8)} p99 ${fmt(p99).padEnd(8)} ` +
				`median ${fmt(median).padEnd(8)} max error/tolerance ${worst.ratio.toFixed(2)}`);
			if (!ok) {
				failures++;
				const qf = Array.from(queries.subarray(worst.i * c.query_floats, (worst.i + 1) * c.query_floats));
				console.log(`       query ${worst.i} [${qf.map((x) => x.toPrecision(9)).join(', ')}]: WebGPU ${got[worst.i]}, ` +
					`C++ ${c.reference[worst.i]}, relative error ${fmt(worst.e)} > tolerance ${fmt(worst.tol)}`);
			}
			entry.labels[label] = { n: rows.length, max, p99, median, max_ratio: worst.ratio };
		}
		if (bad) {
			failures++;
			console.log(`  FAIL ${bad} NaN or negative results, the first: query ${firstBad} gave ${got[firstBad]}`);
		}
		report.runs.push(entry);
	}
} finally {
	await browser.close();
	server.close();
}
// The summary: per file and label, over its case sets, the largest max, p99 and median.
const summary = new Map();
for (const r of report.runs) {
	if (!r.labels) continue;
	// The case sets of one test and comparison together (g and the table left out of the name).
	const group = r.set.replace(/ (g=\S+|E\d\S*)/g, '');
	for (const [label, st] of Object.entries(r.labels)) {
		const key = `${r.file} ${label} (${group})`;
		const a = summary.get(key) ?? { n: 0, max: 0, p99: 0, median: 0, ratio: 0 };
		summary.set(key, { n: a.n + st.n, max: Math.max(a.max, st.max), p99: Math.max(a.p99, st.p99),
			median: Math.max(a.median, st.median), ratio: Math.max(a.ratio, st.max_ratio) });
	}
}
console.log('summary (per file and label, the worst of its case sets): n, max, p99, median relative error, error/tolerance');
for (const [key, a] of summary)
	console.log(`  ${key.padEnd(72)} ${String(a.n).padStart(6)}  ${fmt(a.max).padEnd(8)} ${fmt(a.p99).padEnd(8)} ${fmt(a.median).padEnd(8)} ${a.ratio.toFixed(2)}`);
report.summary = Object.fromEntries(summary);
report.seconds = (Date.now() - t0) / 1000;
writeFileSync(join(work, 'agreement.json'), JSON.stringify(report, null, 1));
phase(`${failures ? `${failures} failures` : 'all agree'}; details in ${join(work, 'agreement.json')}`);
process.exit(failures ? 1 : 0);
