// Compile cost of the GLSL ES snippets on Chromium's SwiftShader (WebGL2), A/B:
//   node examples/web/bench_compile.mjs SNIPPET.essl[+SNIPPET2.essl] [...] [--rounds 1..50]
//        [--lamps 1..6] [--spot] [--tier fast|accurate] [--chromium PATH]
//        [--translated DIR [--no-draw]]
// Each argument is one fragment shader: the snippets joined ('+': e.g. the airlight and the
// near-light snippet, as the web demo loads them) and a main() that calls what they define
// as fog.mjs does: slut_airlight_radiance_points for each of --lamps lamps if the snippets
// define it (--spot: slut_airlight_spot_radiance_points, each lamp a spot with its own axis
// and cone; --tier: the snippets' tier define first, docs/SHADERS.md "Tiers"), and slut_near_light_radiance on an E3 table (thick medium, no refraction) for
// each lamp if they define that. Per shader and round: compile + link (WebGL's
// compileShader, linkProgram and their status: ANGLE's translation), then the first draw
// of an 8 x 8 frame and a one-pixel readPixels, where SwiftShader builds the pipeline
// (compiles the shader to machine code); per round the shaders in rotated order, each made
// new by a constant of its own (no cache can answer). Prints per shader the median [min-max]
// of the rounds for both phases and their sum, the median per-round ratio of the sum to the
// first shader's, and the size of ANGLE's translation (WEBGL_debug_shaders; --translated
// DIR writes it there: SPIR-V words in hex; --no-draw: only that, no pipeline is built). Textures: 2 x 2 (x 2) R32F, zeros; uniform axes as the default
// tables' (the values do not change what is compiled). Exits 77 without Chromium or the
// npm modules (npm ci in examples/web).
import { existsSync, readFileSync, mkdirSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { parseArgs, launchSwiftShader, blankPage, median, gpuProcessCpuSeconds } from './bench_chromium.mjs';

const usage = 'usage: node bench_compile.mjs SNIPPET.essl[+SNIPPET2.essl] [...] [--rounds 1..50] [--lamps 1..6] [--spot] ' +
	'[--tier fast|accurate] [--chromium PATH] [--translated DIR [--no-draw]]';
const { opt, flag, positional, intOption } = parseArgs(process.argv.slice(2), ['--chromium', '--rounds', '--lamps', '--translated', '--tier'],
	['--no-draw', '--spot'], usage, 'bench_compile');
const spot = flag('--spot');
const tier = opt('--tier');
if (tier !== undefined && tier !== 'fast' && tier !== 'accurate') { console.error(`bench_compile: --tier ${tier}: expected fast or accurate`); process.exit(2); }
if (positional.length < 1) { console.error(usage); process.exit(2); }
const rounds = intOption('--rounds', 3, 1, 50), lamps = intOption('--lamps', 6, 1, 6);
for (const p of positional.flatMap((a) => a.split('+')))
	if (!existsSync(p)) { console.error(`bench_compile: ${p}: no such file`); process.exit(2); }

// The fragment shader of one argument: the snippets, then main() (fog.mjs's calls; `salt`
// makes each compile's source and SPIR-V distinct).
function fragmentShader(arg) {
	const snippets = arg.split('+').map((p) => readFileSync(p, 'utf8')).join('');
	const air = (spot ? /\bslut_airlight_spot_radiance_points\s*\(/ : /\bslut_airlight_radiance_points\s*\(/).test(snippets);
	const near = /\bslut_near_light_radiance\s*\(/.test(snippets);
	if (!air && !near) {
		console.error(`bench_compile: ${arg}: defines neither slut_airlight_${spot ? 'spot_' : ''}radiance_points nor slut_near_light_radiance`);
		process.exit(2);
	}
	return { air, near, text: (salt) => `#version 300 es
${tier ? `#define SLUT_TIER_${tier.toUpperCase()}\n` : ''}${snippets}
uniform sampler2D airlight_table;
uniform sampler3D near_table;
uniform vec4 air_u, air_w;
uniform vec4 near_T, near_g, near_r;
uniform ivec3 near_warps;
uniform vec3 eye;
uniform vec2 fog_sigma, slab_sigma;
uniform vec4 lights[6];
uniform vec4 light_axes[6];                 // xyz the beam's axis, w unused
uniform vec2 light_cones[6];                // outer, inner half-angle (rad)
out vec4 colour;
void main() {
    vec3 d = normalize(vec3((gl_FragCoord.xy - 4.0) / 8.0, -1.0));
    float s = (9.0 - eye.z) / -d.z, L = 0.0;
${air ? `    SlutAirlightTable air = ${tier ? 'slut_airlight_table(int(air_u.w), int(air_w.w))'
		: 'slut_airlight_table(air_u.y, air_u.z, int(air_u.w), air_w.x, int(air_w.w))'};
    for (int k = 0; k < ${lamps}; ++k)
${spot ? `        L += slut_airlight_spot_radiance_points(airlight_table, air, eye, d, lights[k].xyz, light_axes[k].xyz,
                                                light_cones[k].x, light_cones[k].y, s, fog_sigma.x, fog_sigma.y,
                                                lights[k].w);` : `        L += slut_airlight_radiance_points(airlight_table, air, eye, d, lights[k].xyz, s, fog_sigma.x, fog_sigma.y,
                                           lights[k].w);`}
` : ''}${near ? `    SlutNearLightTable e3 = slut_near_light_table_e3(
        slut_axis_make(near_T.x, near_T.y, near_T.z, near_warps.x, int(near_T.w)),
        slut_axis_make(near_g.x, near_g.y, near_g.z, near_warps.y, int(near_g.w)),
        slut_axis_make(near_r.x, near_r.y, near_r.z, near_warps.z, int(near_r.w)));
    vec3 p = eye + s * d;
    for (int k = 0; k < ${lamps}; ++k)
        L += slut_near_light_radiance(near_table, e3, slab_sigma.x, slab_sigma.y, lights[k].w, vec3(0.0, 0.0, 1.0),
                                      -d, lights[k].xyz - p, slut_inf(), 1.0, false);
` : ''}    colour = vec4(L, ${salt}.0, 0.0, 1.0);
}
` };
}
const shaders = positional.map((arg, k) => ({ name: `${String.fromCharCode(65 + k)}: ${arg}`, ...fragmentShader(arg) }));

// The page: the context once, then per shader one evaluate for compile + link and one for the
// first draw (no server; WebGL2 on about:blank).
function pageSetup() {
	const canvas = document.createElement('canvas');
	canvas.width = 8; canvas.height = 8;
	const gl = window.slutBenchGl = canvas.getContext('webgl2', { antialias: false });
	if (!gl) throw new Error('no WebGL2');
	const zeros = new Float32Array(8);
	for (const [unit, target] of [[0, gl.TEXTURE_2D], [1, gl.TEXTURE_3D]]) {
		gl.activeTexture(gl.TEXTURE0 + unit);
		gl.bindTexture(target, gl.createTexture());
		gl.texParameteri(target, gl.TEXTURE_MIN_FILTER, gl.NEAREST);
		gl.texParameteri(target, gl.TEXTURE_MAG_FILTER, gl.NEAREST);
		if (target === gl.TEXTURE_2D) gl.texImage2D(target, 0, gl.R32F, 2, 2, 0, gl.RED, gl.FLOAT, zeros);
		else gl.texImage3D(target, 0, gl.R32F, 2, 2, 2, 0, gl.RED, gl.FLOAT, zeros);
	}
	gl.viewport(0, 0, 8, 8);
	const info = gl.getExtension('WEBGL_debug_renderer_info');
	return gl.getParameter(info ? info.UNMASKED_RENDERER_WEBGL : gl.RENDERER);
}

function pageCompile({ fragment, wantTranslated }) {
	const gl = window.slutBenchGl;
	const vs = '#version 300 es\nvoid main() { vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));' +
		' gl_Position = vec4(2.0 * p - 1.0, 0.0, 1.0); }\n';
	const t0 = performance.now();
	const shader = (type, text) => {
		const s = gl.createShader(type);
		gl.shaderSource(s, text);
		gl.compileShader(s);
		if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) throw new Error(gl.getShaderInfoLog(s));
		return s;
	};
	const program = window.slutBenchProgram = gl.createProgram();
	const fs = shader(gl.FRAGMENT_SHADER, fragment);
	gl.attachShader(program, shader(gl.VERTEX_SHADER, vs));
	gl.attachShader(program, fs);
	gl.linkProgram(program);
	if (!gl.getProgramParameter(program, gl.LINK_STATUS)) throw new Error(gl.getProgramInfoLog(program));
	const ms = performance.now() - t0;
	const debug = gl.getExtension('WEBGL_debug_shaders');
	const translated = debug ? debug.getTranslatedShaderSource(fs) : '';
	return { ms, translated_chars: translated.length, translated: wantTranslated ? translated : '' };
}

function pageDraw() {
	const gl = window.slutBenchGl, program = window.slutBenchProgram;
	const t0 = performance.now();
	gl.useProgram(program);
	const loc = (n) => gl.getUniformLocation(program, n);
	gl.uniform1i(loc('airlight_table'), 0);
	gl.uniform1i(loc('near_table'), 1);
	gl.uniform4f(loc('air_u'), 0, 64, 1e-7, 2);
	gl.uniform4f(loc('air_w'), 1e-3, Math.PI / 2, 0, 2);
	gl.uniform4f(loc('near_T'), 1e-3, 64, 1, 2);
	gl.uniform4f(loc('near_g'), -1, 1, 0, 2);
	gl.uniform4f(loc('near_r'), 0, 100, 0.1, 2);
	gl.uniform3i(loc('near_warps'), 5, 4, 2); // LOGLIN, SQRT1P, LOG1P
	gl.uniform3f(loc('eye'), 0, 1.7, 0);
	gl.uniform2f(loc('fog_sigma'), 0.04, 0.01);
	gl.uniform2f(loc('slab_sigma'), 5.0, 0.2);
	gl.uniform4fv(loc('lights'), [-3.5, 5, -12, 300, 3.8, 5, -26, 300, -3.8, 5, -45, 300, 3.8, 5, -70, 300,
		2, 1.2, -8.6, 40, -2, 4, 3, 200]);
	gl.uniform4fv(loc('light_axes'), [0.35, -1, 0, 0, -0.35, -1, 0, 0, 0.35, -1, 0, 0, -0.35, -1, 0, 0, 0, -1, 0, 0, 0.35, -1, 0, 0]);
	gl.uniform2fv(loc('light_cones'), [0.96, 0.61, 0.96, 0.61, 0.96, 0.61, 0.96, 0.61, 0.35, 0.21, 0.96, 0.61]);
	gl.drawArrays(gl.TRIANGLES, 0, 3);
	const pixel = new Uint8Array(4);
	gl.readPixels(0, 0, 1, 1, gl.RGBA, gl.UNSIGNED_BYTE, pixel);
	const ms = performance.now() - t0;
	gl.deleteProgram(program);
	return { ms };
}

const browser = await launchSwiftShader(opt('--chromium'));
try {
	const page = await blankPage(browser);
	const translatedDir = opt('--translated'), noDraw = flag('--no-draw');
	if (translatedDir) mkdirSync(translatedDir, { recursive: true });
	const renderer = await page.evaluate(pageSetup);
	const phases = ['compile', 'draw'];
	for (const s of shaders) for (const ph of phases) s[ph] = { ms: [], cpu_s: [] };
	let salt = 0;
	for (let r = 0; r < rounds; ++r) {
		for (let q = 0; q < shaders.length; ++q) {
			const s = shaders[(q + r) % shaders.length], letter = String.fromCharCode(65 + shaders.indexOf(s));
			const cpu0 = gpuProcessCpuSeconds(browser);
			const c = await page.evaluate(pageCompile, { fragment: s.text(++salt), wantTranslated: Boolean(translatedDir) && r === 0 });
			const cpu1 = gpuProcessCpuSeconds(browser);
			const d = noDraw ? { ms: 0 } : await page.evaluate(pageDraw);
			const cpu2 = gpuProcessCpuSeconds(browser);
			s.compile.ms.push(c.ms); s.draw.ms.push(d.ms);
			s.compile.cpu_s.push(cpu1 - cpu0); s.draw.cpu_s.push(cpu2 - cpu1);
			s.translated_chars = c.translated_chars;
			if (c.translated) writeFileSync(join(translatedDir, `${letter}.translated.glsl`), c.translated);
			console.error(`round ${r + 1}: ${s.name}: compile + link ${c.ms.toFixed(0)} ms (GPU process CPU ${(cpu1 - cpu0).toFixed(1)} s), ` +
				`first draw ${d.ms.toFixed(0)} ms (CPU ${(cpu2 - cpu1).toFixed(1)} s)`);
		}
	}
	const range = (a, digits) => `${median(a).toFixed(digits)} [${Math.min(...a).toFixed(digits)}-${Math.max(...a).toFixed(digits)}]`;
	const total = (s, key) => s.compile[key].map((c, r) => c + s.draw[key][r]);
	console.log(`${renderer}; ${rounds} round(s), ${lamps} ${spot ? 'spot' : 'point'} lamp(s)${tier ? `, tier ${tier}` : ''}; median [min-max] of the rounds; CPU: the GPU process's user + system time`);
	console.log('| shader | compile + link: wall ms / CPU s | first draw (8 x 8): wall ms / CPU s | sum: wall ms / CPU s | ' +
		'sum / A: median of per-round ratios, wall / CPU | ANGLE\'s translation, chars |');
	console.log('|---|---|---|---|---|---|');
	const a = shaders[0];
	for (const s of shaders) {
		const ratio = (key) => median(total(s, key).map((t, r) => t / total(a, key)[r])).toFixed(2);
		console.log(`| ${s.name} (${[s.air ? 'airlight' : '', s.near ? 'near light' : ''].filter(Boolean).join(' + ')}) | ` +
			`${range(s.compile.ms, 0)} / ${range(s.compile.cpu_s, 1)} | ${range(s.draw.ms, 0)} / ${range(s.draw.cpu_s, 1)} | ` +
			`${range(total(s, 'ms'), 0)} / ${range(total(s, 'cpu_s'), 1)} | ${ratio('ms')} / ${ratio('cpu_s')} | ${s.translated_chars} |`);
	}
} finally {
	await browser.close();
}
