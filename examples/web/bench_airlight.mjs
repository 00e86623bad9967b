// Per-pixel cost of the airlight snippet on Chromium's SwiftShader (WebGL2), A/B, per tier:
//   node examples/web/bench_airlight.mjs TABLE.slut SNIPPET.essl [SNIPPET2.essl ...]
//        [--rational RATIONAL.slut [--tiers fast,accurate,none]] [--chromium PATH] [--rounds N]
//        [--frames N] [--lamps 1..6] [--near NEAR_E3.slut]
// renders the web demo's fixed view (fog.mjs: 480 x 270, the street, its six lamps; the rays
// end on the ground, the far wall or the slab) with the airlight of its lamps only (no near
// light), once per given GLSL ES snippet (scatterlut_airlight.essl, e.g. one assembled
// before a change) and tier, once with the closed form engines use (Macklin 2010, × e^{−σ_t D})
// and once with Sun et al. 2005's two-fetch form on a plain 64 x 64 F(u, v) table (u in [0, 10],
// v in [0, π/2], linear axes, bilinear, clamped; F by composite Simpson here), as
// bench/bench_gpu_pixel.cpp writes them for llvmpipe, into an R32F target. Rounds A B C … with the order rotated each round; per frame
// drawArrays + a one-pixel readPixels (which waits for the frame), wall clock; per round each
// method's median frame, and its ratio to the first method in the same round. Prints per
// method: compile + link ms, the first frame (SwiftShader builds the pipeline there), the
// median frame, ns per pixel and lamp, the per-round ratios, and the largest relative
// difference of its frame from the first method's (pixels with a finite, nonzero value).
// TABLE.slut: the default airlight table (`scatterlut generate --out DIR`, airlight_F.slut).
// Tiers (docs/SHADERS.md, "Tiers"; fog.mjs's ?tier=): without --rational every snippet runs
// without a tier (on TABLE.slut); with --rational RATIONAL.slut (airlight_rational.slut of the
// same run) every snippet runs in each tier of --tiers (default fast,accurate,none, in that
// order): fast (#define SLUT_TIER_FAST, the airlight_rational table with linear filtering,
// which needs OES_texture_float_linear), accurate (SLUT_TIER_ACCURATE, the same table, texel
// fetches) and none (TABLE.slut, texel fetches).
// With --near NEAR_E3.slut (near_light_E3.slut of the same run) a snippet argument may be
// AIR.essl+NEAR.essl: that method also renders the near light through the slab, as fog.mjs
// does (the whole fixed view of the web demo), in the same tier (the define sets both
// snippets' tier; fast filters the E3 table linearly too).
// Needs the npm modules (npm ci in examples/web) and Chromium; exits 77 without them.
import { existsSync, readFileSync } from 'node:fs';
import { basename } from 'node:path';
import { parseSlut } from '../../tests/js/slut.mjs';
import { parseArgs, launchSwiftShader, blankPage, median } from './bench_chromium.mjs';

const usage = 'usage: node bench_airlight.mjs TABLE.slut SNIPPET.essl [SNIPPET2.essl ...] ' +
	'[--rational RATIONAL.slut [--tiers fast,accurate,none]] [--chromium PATH] ' +
	'[--rounds 1..100] [--frames 1..100] [--lamps 1..6] [--near NEAR_E3.slut]';
const { opt, positional, intOption } = parseArgs(process.argv.slice(2),
	['--chromium', '--rounds', '--frames', '--lamps', '--near', '--rational', '--tiers'], [], usage, 'bench_airlight');
if (positional.length < 2) { console.error(usage); process.exit(2); }
const rounds = intOption('--rounds', 5, 1, 100), frames = intOption('--frames', 3, 1, 100);
const lamps = intOption('--lamps', 6, 1, 6);
const [tablePath, ...snippetPaths] = positional;
const nearPath = opt('--near'), rationalPath = opt('--rational');
for (const p of [...positional.flatMap((a) => a.split('+')), ...(nearPath ? [nearPath] : []),
	...(rationalPath ? [rationalPath] : [])])
	if (!existsSync(p)) { console.error(`bench_airlight: ${p}: no such file`); process.exit(2); }
const table = parseSlut(readFileSync(tablePath), tablePath);
if (table.kind !== 'airlight_F' || table.axes[0].warpName !== 'log1p' || table.axes[1].warpName !== 'asinh_cot') {
	console.error(`bench_airlight: ${tablePath}: expected the default airlight_F table (u log1p, w asinh_cot), got ${table.kind}`);
	process.exit(2);
}
const [au, aw] = table.axes;
const near = nearPath ? parseSlut(readFileSync(nearPath), nearPath) : undefined;
if (near && near.kind !== 'near_light_E3') {
	console.error(`bench_airlight: ${nearPath}: expected a near_light_E3 table, got ${near.kind}`);
	process.exit(2);
}
const rational = rationalPath ? parseSlut(readFileSync(rationalPath), rationalPath) : undefined;
if (rational && rational.kind !== 'airlight_rational') {
	console.error(`bench_airlight: ${rationalPath}: expected an airlight_rational table, got ${rational.kind}`);
	process.exit(2);
}
// The tiers: their define and the airlight table they sample (fog.mjs's kTiers).
const kTiers = {
	fast: { define: 'SLUT_TIER_FAST', table: 'rational', linear: true },
	accurate: { define: 'SLUT_TIER_ACCURATE', table: 'rational', linear: false },
	none: { define: '', table: 'F', linear: false },
};
const tiers = (opt('--tiers') ?? (rational ? 'fast,accurate,none' : 'none')).split(',');
for (const t of tiers) {
	if (!(t in kTiers)) { console.error(`bench_airlight: --tiers: ${t}: expected fast, accurate or none\n${usage}`); process.exit(2); }
	if (kTiers[t].table === 'rational' && !rational) {
		console.error(`bench_airlight: the ${t} tier samples the airlight_rational table: give --rational RATIONAL.slut`);
		process.exit(2);
	}
}
const methods = snippetPaths.flatMap((p) => {
	const [air, nl] = p.split('+');
	if (nl && !near) { console.error(`bench_airlight: ${p}: a near-light snippet needs --near NEAR_E3.slut`); process.exit(2); }
	return tiers.map((t) => ({ ...kTiers[t], tier: t, path: p, snippet: readFileSync(air, 'utf8'),
		nearSnippet: nl ? readFileSync(nl, 'utf8') : '' }));
}).map((m, k) => ({ ...m, name: `${String.fromCharCode(65 + k)}: ${m.path}${rational ? ` [${m.tier}]` : ''}` }));
methods.push({ name: 'closed form × e^{−σ_t D} (Macklin 2010)', snippet: '', builtin: 'closed' });
methods.push({ name: 'Sun et al. 2005, 64² F table, two fetches', snippet: '', builtin: 'sun' });

// The two baselines' GLSL, shared with bench/bench_gpu_pixel.cpp (bench/shaders/).
const [closedGlsl, sunGlsl] = ['closed_form.glsl', 'sun2005.glsl'].map((name) =>
	readFileSync(new URL(`../../bench/shaders/${name}`, import.meta.url), 'utf8'));

// Sun et al.'s F(u, v) = ∫_0^v e^{−u tan ξ} dξ on the Rain sample's plain grid: composite
// Simpson, 4096 intervals (the integrand is smooth up to ξ = π/2, where it vanishes for u > 0).
const kFCount = 64, kFUMax = 10.0;
const fTable = new Float32Array(kFCount * kFCount);
for (let j = 0; j < kFCount; ++j) {
	for (let i = 0; i < kFCount; ++i) {
		const u = (kFUMax * i) / (kFCount - 1), v = (0.5 * Math.PI * j) / (kFCount - 1), n = 4096, h = v / n;
		const f = (x) => (x >= 0.5 * Math.PI ? (u > 0 ? 0 : 1) : Math.exp(-u * Math.tan(x)));
		let sum = f(0) + f(v);
		for (let k = 1; k < n; ++k) sum += (k & 1 ? 4 : 2) * f(k * h);
		fTable[j * kFCount + i] = (sum * h) / 3;
	}
}

// The page: everything inside one evaluate (no server; WebGL2 on about:blank).
async function pageBench({ methods, values, air, rationalTable, nearTable, fTable, fCount, fUMax, rounds, frames, lamps,
	closedGlsl, sunGlsl }) {
	const W = 480, H = 270;
	const canvas = document.createElement('canvas');
	canvas.width = W; canvas.height = H;
	const gl = canvas.getContext('webgl2', { antialias: false });
	if (!gl) throw new Error('no WebGL2');
	if (!gl.getExtension('EXT_color_buffer_float')) throw new Error('no EXT_color_buffer_float');
	const renderer = gl.getParameter(gl.RENDERER);
	const tex = gl.createTexture();
	gl.activeTexture(gl.TEXTURE0);
	gl.bindTexture(gl.TEXTURE_2D, tex);
	gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
	gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
	gl.texImage2D(gl.TEXTURE_2D, 0, gl.R32F, air.u.count, air.w.count, 0, gl.RED, gl.FLOAT, new Float32Array(values));
	let rationalTex = null, t3 = null;
	if (rationalTable) { // the tiers' table (unit 0 while a tier draws), clamped to its edges
		const [m, t] = rationalTable.axes;
		rationalTex = gl.createTexture();
		gl.bindTexture(gl.TEXTURE_2D, rationalTex);
		gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_S, gl.CLAMP_TO_EDGE);
		gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_T, gl.CLAMP_TO_EDGE);
		gl.texImage2D(gl.TEXTURE_2D, 0, gl.R32F, m.count, t.count, 0, gl.RED, gl.FLOAT,
			new Float32Array(rationalTable.values));
		gl.bindTexture(gl.TEXTURE_2D, tex);
	}
	if (nearTable) {
		const [T, g, r] = nearTable.axes;
		t3 = gl.createTexture();
		gl.activeTexture(gl.TEXTURE1);
		gl.bindTexture(gl.TEXTURE_3D, t3);
		for (const wrap of [gl.TEXTURE_WRAP_S, gl.TEXTURE_WRAP_T, gl.TEXTURE_WRAP_R])
			gl.texParameteri(gl.TEXTURE_3D, wrap, gl.CLAMP_TO_EDGE);
		gl.texParameteri(gl.TEXTURE_3D, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
		gl.texParameteri(gl.TEXTURE_3D, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
		gl.texImage3D(gl.TEXTURE_3D, 0, gl.R32F, T.count, g.count, r.count, 0, gl.RED, gl.FLOAT,
			new Float32Array(nearTable.values));
		gl.activeTexture(gl.TEXTURE0);
	}
	const haveFloatLinear = gl.getExtension('OES_texture_float_linear') !== null;
	const fTex = gl.createTexture();
	gl.activeTexture(gl.TEXTURE2);
	gl.bindTexture(gl.TEXTURE_2D, fTex);
	gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, gl.LINEAR);
	gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, gl.LINEAR);
	gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_S, gl.CLAMP_TO_EDGE);
	gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_WRAP_T, gl.CLAMP_TO_EDGE);
	gl.texImage2D(gl.TEXTURE_2D, 0, haveFloatLinear ? gl.R32F : gl.R16F, fCount, fCount, 0, gl.RED, gl.FLOAT,
		new Float32Array(fTable));
	gl.activeTexture(gl.TEXTURE0);
	if (methods.some((m) => m.linear) && !haveFloatLinear)
		throw new Error('the fast tier filters R32F tables linearly: this WebGL2 lacks OES_texture_float_linear');
	// A method's tables on units 0 (airlight) and 1 (E3), filtered as its tier samples them.
	const bindTables = (m) => {
		const filter = m.linear ? gl.LINEAR : gl.NEAREST;
		gl.activeTexture(gl.TEXTURE0);
		gl.bindTexture(gl.TEXTURE_2D, m.table === 'rational' ? rationalTex : tex);
		gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MIN_FILTER, filter);
		gl.texParameteri(gl.TEXTURE_2D, gl.TEXTURE_MAG_FILTER, filter);
		if (t3) {
			gl.activeTexture(gl.TEXTURE1);
			gl.texParameteri(gl.TEXTURE_3D, gl.TEXTURE_MIN_FILTER, filter);
			gl.texParameteri(gl.TEXTURE_3D, gl.TEXTURE_MAG_FILTER, filter);
			gl.activeTexture(gl.TEXTURE0);
		}
	};
	const target = gl.createTexture();
	gl.bindTexture(gl.TEXTURE_2D, target);
	gl.texStorage2D(gl.TEXTURE_2D, 1, gl.R32F, W, H);
	gl.bindTexture(gl.TEXTURE_2D, tex);
	const fbo = gl.createFramebuffer();
	gl.bindFramebuffer(gl.FRAMEBUFFER, fbo);
	gl.framebufferTexture2D(gl.FRAMEBUFFER, gl.COLOR_ATTACHMENT0, gl.TEXTURE_2D, target, 0);
	gl.viewport(0, 0, W, H);

	// fog.mjs's fixed view and lamps.
	const lights = [[-3.5, 5.0, -12.0, 300], [3.8, 5.0, -26.0, 300], [-3.8, 5.0, -45.0, 300],
		[3.8, 5.0, -70.0, 300], [2.0, 1.2, -8.6, 40], [-2.0, 4.0, 3.0, 200]];
	const eye = [0, 1.7, 0], tgt = [0, 2.4, -30];
	const sub = (a, b) => a.map((x, i) => x - b[i]);
	const norm = (a) => { const n = Math.hypot(...a); return a.map((x) => x / n); };
	const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
	const fwd = norm(sub(tgt, eye)), right = norm(cross(fwd, [0, 1, 0])), up = cross(right, fwd);

	const vs = '#version 300 es\nvoid main() { vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));' +
		' gl_Position = vec4(2.0 * p - 1.0, 0.0, 1.0); }\n';
	const closed = `${closedGlsl}
float closed_points(vec3 eye, vec3 d, vec3 light, float s, float ss, float sa, float i0) {
    vec3 to_light = light - eye;
    float dist = length(to_light);
    float sin_part = length(cross(d, to_light)), cos_part = dot(d, to_light);
    float n = sqrt(sin_part * sin_part + cos_part * cos_part);
    return closed_form_attenuated(ss, sa, i0, dist, sin_part / n, cos_part / n, s);
}
`;
	const slabLoop = `
    if (slab) {
        vec3 p = eye + s * d;
        for (int k = 0; k < ${lamps}; ++k) {
            vec3 rel = lights[k].xyz - p;
            float att = exp(-(fog_sigma.x + fog_sigma.y) * (length(rel) + s));
            L += slut_near_light_radiance(near_table, slut_near_light_table_e3(
                     slut_axis_make(near_T.x, near_T.y, near_T.z, near_warps.x, int(near_T.w)),
                     slut_axis_make(near_g.x, near_g.y, near_g.z, near_warps.y, int(near_g.w)),
                     slut_axis_make(near_r.x, near_r.y, near_r.z, near_warps.z, int(near_r.w))),
                     5.0, 0.2, lights[k].w, vec3(0.0, 0.0, 1.0), -d, rel, slut_inf(), 1.0, false) * att;
        }
    }`;
	const sun = `${sunGlsl}
float sun_points(vec3 eye, vec3 d, vec3 light, float s, float ss, float sa, float i0) {
    vec3 to_light = light - eye;
    float dist = length(to_light);
    float sin_part = length(cross(d, to_light)), cos_part = dot(d, to_light);
    float n = sqrt(sin_part * sin_part + cos_part * cos_part);
    return sun2005(ss, sa, i0, dist, sin_part / n, cos_part / n, min(s, 1e30));
}
`;
	// The snippet's table: the airlight_rational table's two counts in a tier (fog.mjs), else the
	// airlight_F table's axes.
	const airTable = `#if defined(SLUT_TIER_FAST) || defined(SLUT_TIER_ACCURATE)
    SlutAirlightTable air = slut_airlight_table(int(air_u.w), int(air_w.w));
#else
    SlutAirlightTable air = slut_airlight_table(air_u.y, air_u.z, int(air_u.w), air_w.x, int(air_w.w));
#endif
`;
	const snippetCall = 'slut_airlight_radiance_points(airlight_table, air, eye, d, lights[k].xyz, s, fog_sigma.x, ' +
		'fog_sigma.y, lights[k].w)';
	const main = (call, withNear) => `
uniform sampler2D airlight_table;${withNear ? '\nuniform sampler3D near_table;\nuniform vec4 near_T, near_g, near_r;\nuniform ivec3 near_warps;' : ''}
uniform vec4 air_u, air_w;
uniform vec3 eye, fwd, right, up;
uniform float tan_half_fov, aspect;
uniform vec2 fog_sigma;
uniform vec4 lights[6];
out float radiance;
void main() {
    float i = gl_FragCoord.x - 0.5, j = ${H.toFixed(1)} - gl_FragCoord.y - 0.5;
    float px = (2.0 * (i + 0.5) / ${W.toFixed(1)} - 1.0) * tan_half_fov * aspect;
    float py = (1.0 - 2.0 * (j + 0.5) / ${H.toFixed(1)}) * tan_half_fov;
    vec3 d = normalize(fwd + px * right + py * up);
    float s = uintBitsToFloat(0x7F800000u);
    bool slab = false;
    if (d.y < 0.0) s = min(s, -eye.y / d.y);
    if (d.z < 0.0) {
        float t = (-90.0 - eye.z) / d.z;
        vec3 p = eye + t * d;
        if (t < s && p.y <= 14.0) s = t;
        t = (-9.0 - eye.z) / d.z;
        p = eye + t * d;
        if (t < s && p.x >= 1.2 && p.x <= 3.2 && p.y >= 0.0 && p.y <= 2.0) { s = t; slab = true; }
    }
${call === snippetCall ? airTable : ''}    float L = 0.0;
    for (int k = 0; k < ${lamps}; ++k) L += ${call};${withNear ? slabLoop : ''}
    radiance = L;
}
`;

	const closedCall = 'closed_points(eye, d, lights[k].xyz, s, fog_sigma.x, fog_sigma.y, lights[k].w)';
	const sunCall = 'sun_points(eye, d, lights[k].xyz, s, fog_sigma.x, fog_sigma.y, lights[k].w)';
	const one = new Float32Array(4);
	const finish = () => gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.FLOAT, one);
	const results = [];
	for (const m of methods) {
		const t0 = performance.now();
		const shader = (type, text) => {
			const s = gl.createShader(type);
			gl.shaderSource(s, text);
			gl.compileShader(s);
			if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) throw new Error(`${m.name}: ${gl.getShaderInfoLog(s)}`);
			return s;
		};
		const program = gl.createProgram();
		gl.attachShader(program, shader(gl.VERTEX_SHADER, vs));
		gl.attachShader(program, shader(gl.FRAGMENT_SHADER, '#version 300 es\n' + (m.define ? `#define ${m.define}\n` : '') +
			(m.snippet ? m.snippet + m.nearSnippet + main(snippetCall, m.nearSnippet !== '')
				: m.builtin === 'closed' ? 'precision highp float;\n' + closed + main(closedCall, false)
					: 'precision highp float;\n' + sun + main(sunCall, false))));
		gl.linkProgram(program);
		if (!gl.getProgramParameter(program, gl.LINK_STATUS)) throw new Error(`${m.name}: ${gl.getProgramInfoLog(program)}`);
		const t1 = performance.now();
		gl.useProgram(program);
		const loc = (n) => gl.getUniformLocation(program, n);
		gl.uniform1i(loc('airlight_table'), 0);
		gl.uniform1i(loc('f_table'), 2);
		gl.uniform1f(loc('f_u_max'), fUMax);
		const [au, aw] = m.table === 'rational' ? rationalTable.axes : [air.u, air.w];
		gl.uniform4f(loc('air_u'), au.min, au.max, au.scale, au.count);
		gl.uniform4f(loc('air_w'), aw.min, aw.max, aw.scale, aw.count);
		gl.uniform3fv(loc('eye'), eye); gl.uniform3fv(loc('fwd'), fwd);
		gl.uniform3fv(loc('right'), right); gl.uniform3fv(loc('up'), up);
		gl.uniform1f(loc('tan_half_fov'), Math.tan((50 * Math.PI) / 360));
		gl.uniform1f(loc('aspect'), W / H);
		gl.uniform2f(loc('fog_sigma'), 0.04, 0.01);
		gl.uniform4fv(loc('lights'), lights.flat());
		if (m.nearSnippet) {
			const [T, g, r] = nearTable.axes;
			gl.uniform1i(loc('near_table'), 1);
			for (const [n, a] of [['near_T', T], ['near_g', g], ['near_r', r]]) gl.uniform4f(loc(n), a.min, a.max, a.scale, a.count);
			gl.uniform3i(loc('near_warps'), T.warp, g.warp, r.warp);
		}
		bindTables(m);
		gl.drawArrays(gl.TRIANGLES, 0, 3);
		finish();
		const t2 = performance.now();
		console.log(`${m.name}: compile + link ${(t1 - t0).toFixed(0)} ms, first frame ${(t2 - t1).toFixed(0)} ms`);
		const frame = new Float32Array(W * H * 4);
		gl.readPixels(0, 0, W, H, gl.RGBA, gl.FLOAT, frame);
		results.push({ name: m.name, method: m, program, compile_ms: t1 - t0, first_frame_ms: t2 - t1,
			frame: Array.from({ length: W * H }, (_, k) => frame[4 * k]), round_ms: [] });
	}
	for (let r = 0; r < rounds; ++r) {
		for (let q = 0; q < results.length; ++q) {
			const m = results[(q + r) % results.length];
			gl.useProgram(m.program);
			bindTables(m.method);
			const times = [];
			for (let f = 0; f < frames; ++f) {
				const t0 = performance.now();
				gl.drawArrays(gl.TRIANGLES, 0, 3);
				finish();
				times.push(performance.now() - t0);
			}
			times.sort((a, b) => a - b);
			m.round_ms.push(times[Math.floor(times.length / 2)]);
		}
	}
	const base = results[0].frame;
	for (const m of results) {
		let maxRel = 0;
		for (let k = 0; k < base.length; ++k) {
			if (!(Number.isFinite(base[k]) && base[k] > 0 && Number.isFinite(m.frame[k]))) continue;
			maxRel = Math.max(maxRel, Math.abs(m.frame[k] - base[k]) / base[k]);
		}
		m.max_rel_vs_A = maxRel;
		delete m.frame;
		delete m.program;
		delete m.method;
	}
	return { renderer, W, H, results, haveFloatLinear };
}

const browser = await launchSwiftShader(opt('--chromium'));
try {
	const page = await blankPage(browser);
	const out = await page.evaluate(pageBench, {
		methods, values: Array.from(table.values), rounds, frames, lamps,
		fTable: Array.from(fTable), fCount: kFCount, fUMax: kFUMax, closedGlsl, sunGlsl,
		nearTable: near ? { axes: near.axes, values: Array.from(near.values) } : undefined,
		rationalTable: rational ? { axes: rational.axes, values: Array.from(rational.values) } : undefined,
		air: { u: au, w: aw },
	});
	const pixels = out.W * out.H;
	console.log(`${out.renderer}; ${out.W} x ${out.H} pixels, ${lamps} lamp(s), ${rounds} rounds x ${frames} frames, ` +
		`table ${basename(tablePath)} (${au.count} x ${aw.count})` +
		(rational ? `, tiers' table ${basename(rationalPath)} (${rational.axes[0].count} x ${rational.axes[1].count})` : '') +
		`; F table ${out.haveFloatLinear ? 'R32F' : 'R16F (no OES_texture_float_linear)'}`);
	console.log('| method | compile + link, ms | first frame, ms | frame, ms: median [min-max] of rounds | ns per pixel and lamp | / A: median [min-max] of per-round ratios | max rel. diff from A |');
	console.log('|---|---|---|---|---|---|---|');
	const a = out.results[0].round_ms;
	for (const m of out.results) {
		const ratios = m.round_ms.map((t, r) => t / a[r]);
		const ms = median(m.round_ms);
		console.log(`| ${m.name} | ${m.compile_ms.toFixed(0)} | ${m.first_frame_ms.toFixed(0)} | ${ms.toFixed(1)} ` +
			`[${Math.min(...m.round_ms).toFixed(1)}-${Math.max(...m.round_ms).toFixed(1)}] | ` +
			`${((ms * 1e6) / (pixels * lamps)).toFixed(0)} | ${median(ratios).toFixed(2)} ` +
			`[${Math.min(...ratios).toFixed(2)}-${Math.max(...ratios).toFixed(2)}] | ${m.max_rel_vs_A.toExponential(1)} |`);
	}
} finally {
	await browser.close();
}
