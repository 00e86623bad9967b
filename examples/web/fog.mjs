// The fog street of examples/render_fog.cpp in the browser (its spots_ picture: the street
// lamps as spots under shades, a parked car's headlights, a bare bulb before the slab): three.js
// (npm), the default tables as KTX2 textures (airlight_F: 2-D, near_light_E3: 3-D), and the WebGL2
// sampling snippets (scatterlut_airlight.essl, scatterlut_nearlight.essl) in one full-screen
// fragment shader: per pixel, the airlight of every light along the view ray (the snippet's spot
// entry point, slut_airlight_spot_radiance_points: a point light is a spot whose cones are the
// whole sphere) and, where the ray meets the wax slab, the near light through its face times the
// light's glTF falloff towards the point; Reinhard + sRGB as render_fog.
// Where the browser has WebGPU, the same picture from the WGSL snippets of the same tier
// (scatterlut_airlight[_tier].wgsl, scatterlut_nearlight[_tier].wgsl) in plain WebGPU:
// fog_webgpu.mjs.
//
// URL parameters: exposure=X (render_fog prints it; default: a night-scene value),
// test=1 (fixed view, no controls; sets window.slutDone when the frame is drawn),
// tier=fast|accurate|airlight_F (docs/SHADERS.md, "Tiers"; default fast): fast and accurate
// sample the airlight_rational table (fast: hardware filtering, which needs WebGL2's
// OES_texture_float_linear for R32F textures; without it the page takes the accurate tier),
// airlight_F the airlight_F table as the C++ runtime does; on WebGPU the fast tier needs the
// device feature float32-filterable, without it the page takes the accurate tier too.
// backend=webgpu|webgl2 (default: WebGPU where the browser gives an adapter, else WebGL2;
// window.slutBackend says which drew).
import * as THREE from 'three';
import { KTX2Loader } from 'three/addons/loaders/KTX2Loader.js';
import { read } from 'three/addons/libs/ktx-parse.module.js';
import { metadataFromKtx2KeyValue } from './slut.mjs';
import { startWebGPU } from './fog_webgpu.mjs';

const W = 480, H = 270; // render_fog's image
const kLights = 8;       // scene.lights (the shaders' arrays)
const params = new URLSearchParams(location.search);
const testMode = params.has('test');
// The snippets' tier: its define, and the airlight table it samples.
const kTiers = {
	fast: { define: 'SLUT_TIER_FAST', airlight: 'airlight_rational' },
	accurate: { define: 'SLUT_TIER_ACCURATE', airlight: 'airlight_rational' },
	airlight_F: { define: '', airlight: 'airlight_F' },
};

// The scene of render_fog.cpp (metres, 1/m; y up, camera looking down -z).
const scene = {
	eye: new THREE.Vector3(0, 1.7, 0), target: new THREE.Vector3(0, 2.4, -30), fovYDeg: 50,
	fogSigmaS: 0.04, fogSigmaA: 0.01, slabSigmaS: 5.0, slabSigmaA: 0.2,
	// render_fog's kSpotLights: position (m), I0 (W/sr; a spot's on its axis), colour, the spot's
	// axis (light -> lit points, any length), its outer and inner cone half-angles (degrees; glTF
	// KHR_lights_punctual's falloff between them; 180, 180: a point light).
	lights: [
		[-3.5, 5.0, -12.0, 300, 1.0, 0.72, 0.38, 0.35, -1.0, 0.0, 55, 35], // sodium lamps under shades
		[3.8, 5.0, -26.0, 300, 1.0, 0.72, 0.38, -0.35, -1.0, 0.0, 55, 35],
		[-3.8, 5.0, -45.0, 300, 1.0, 0.72, 0.38, 0.35, -1.0, 0.0, 55, 35],
		[3.8, 5.0, -70.0, 300, 1.0, 0.72, 0.38, -0.35, -1.0, 0.0, 55, 35],
		[2.0, 1.2, -8.6, 40, 0.85, 0.9, 1.0, 0.0, -1.0, 0.0, 180, 180], // bare bulb before the slab
		[-2.0, 4.0, 3.0, 200, 1.0, 0.72, 0.38, 0.35, -1.0, 0.0, 55, 35], // behind the camera
		[2.2, 0.75, -19.3, 800, 0.9, 0.95, 1.0, -1.0, -0.06, 0.0, 20, 12], // the parked car's headlights
		[2.2, 0.75, -20.7, 800, 0.9, 0.95, 1.0, -1.0, -0.06, 0.0, 20, 12],
	],
	exposure: Number(params.get('exposure') ?? 2.0),
};

async function text(url) {
	const r = await fetch(url);
	if (!r.ok) throw new Error(`${url}: HTTP ${r.status}`);
	return r.text();
}

// A table: its texture (KTX2Loader) and its metadata (ktx-parse key/value data).
// filter: THREE.LinearFilter for the fast tier's hardware filtering, else NearestFilter (the
// texelFetch paths need no float filtering).
async function loadTable(loader, url, filter) {
	const r = await fetch(url);
	if (!r.ok) throw new Error(`${url}: HTTP ${r.status} (generate the tables with --format all)`);
	const bytes = await r.arrayBuffer();
	const meta = metadataFromKtx2KeyValue(read(new Uint8Array(bytes)).keyValue);
	const texture = await new Promise((ok, no) => loader.parse(bytes, ok, no));
	texture.minFilter = texture.magFilter = filter;
	texture.needsUpdate = true;
	return { texture, meta };
}

const axisUniform = (a) => new THREE.Vector4(a.min, a.max, a.scale, a.count);

function fragmentShader(tierDefine, airlightSnippet, nearSnippet) {
	return (tierDefine ? `#define ${tierDefine}\n` : '') + airlightSnippet + nearSnippet + /* glsl */ `
uniform sampler2D airlight_table;
uniform sampler3D near_table;
uniform vec4 air_u, air_w;                 // min, max, scale, count of the airlight axes (u, w; tiers: x_m, x_t)
uniform vec4 near_T, near_g, near_r;       // of the E3 axes T, g, r
uniform ivec3 near_warps;
uniform vec3 eye, fwd, right, up;
uniform float tan_half_fov, aspect, exposure;
uniform vec2 fog_sigma, slab_sigma;         // (sigma_s, sigma_a) in 1/m
uniform vec4 lights[${kLights}];                     // xyz position (m), w I0 (W/sr)
uniform vec3 light_colors[${kLights}];
uniform vec3 light_axes[${kLights}];                 // a spot's axis (light -> lit points)
uniform vec2 light_cones[${kLights}];                // its outer, inner cone half-angle (rad)
uniform vec2 resolution;
out vec4 colour;

const float kWallZ = -90.0, kWallH = 14.0;
const float kSlabZ = -9.0, kSlabX0 = 1.2, kSlabX1 = 3.2, kSlabH = 2.0;
const vec3 kSlabColor = vec3(1.0, 0.5, 0.25);

// glTF's falloff of light k towards p (render_fog's falloff_towards): kernels/slut_spot.h in
// the airlight snippet.
float falloff_towards(int k, vec3 p) {
	float vers = slut_spot_versine_of(slut_vec3_of(normalize(p - lights[k].xyz)), slut_vec3_of(normalize(light_axes[k])));
	return slut_spot_falloff(vers, slut_spot_versine(light_cones[k].x), slut_spot_versine(light_cones[k].y));
}

float tone(float x) { // Reinhard after exposure, then the sRGB curve (render_fog's tone_map)
	float c = isinf(x) ? 1.0 : x / (1.0 + x);
	return c <= 0.0031308 ? 12.92 * c : 1.055 * pow(c, 1.0 / 2.4) - 0.055;
}

void main() {
	// Pixel (i, j) of render_fog, j counted from the top.
	float i = gl_FragCoord.x - 0.5, j = resolution.y - gl_FragCoord.y - 0.5;
	float px = (2.0 * (i + 0.5) / resolution.x - 1.0) * tan_half_fov * aspect;
	float py = (1.0 - 2.0 * (j + 0.5) / resolution.y) * tan_half_fov;
	vec3 d = normalize(fwd + px * right + py * up);
	float s = slut_inf();
	bool slab = false;
	if (d.y < 0.0) s = min(s, -eye.y / d.y);
	if (d.z < 0.0) {
		float t = (kWallZ - eye.z) / d.z;
		vec3 p = eye + t * d;
		if (t < s && p.y <= kWallH) s = t;
		t = (kSlabZ - eye.z) / d.z;
		p = eye + t * d;
		if (t < s && p.x >= kSlabX0 && p.x <= kSlabX1 && p.y >= 0.0 && p.y <= kSlabH) { s = t; slab = true; }
	}
#if defined(SLUT_TIER_FAST) || defined(SLUT_TIER_ACCURATE)
	SlutAirlightTable air = slut_airlight_table(int(air_u.w), int(air_w.w));
#else
	SlutAirlightTable air = slut_airlight_table(air_u.y, air_u.z, int(air_u.w), air_w.x, int(air_w.w));
#endif
	SlutNearLightTable e3 = slut_near_light_table_e3(
		slut_axis_make(near_T.x, near_T.y, near_T.z, near_warps.x, int(near_T.w)),
		slut_axis_make(near_g.x, near_g.y, near_g.z, near_warps.y, int(near_g.w)),
		slut_axis_make(near_r.x, near_r.y, near_r.z, near_warps.z, int(near_r.w)));
	vec3 L = vec3(0.0);
	float fog_t = fog_sigma.x + fog_sigma.y;
	for (int k = 0; k < ${kLights}; ++k) {
		L += slut_airlight_spot_radiance_points(airlight_table, air, eye, d, lights[k].xyz, light_axes[k], light_cones[k].x,
		                                        light_cones[k].y, s, fog_sigma.x, fog_sigma.y, lights[k].w) * light_colors[k];
	}
	if (slab) {
		vec3 p = eye + s * d;
		for (int k = 0; k < ${kLights}; ++k) {
			vec3 rel = lights[k].xyz - p;
			float att = exp(-fog_t * (length(rel) + s));
			float Ln = slut_near_light_radiance(near_table, e3, slab_sigma.x, slab_sigma.y, lights[k].w,
			                                    vec3(0.0, 0.0, 1.0), -d, rel, slut_inf(), 1.0, false) * att *
			           falloff_towards(k, p);
			L += Ln * light_colors[k] * kSlabColor;
		}
	}
	colour = vec4(tone(L.r * exposure), tone(L.g * exposure), tone(L.b * exposure), 1.0);
}
`;
}

// The camera vectors and the scene's numbers both renderers take.
function view() {
	const fwd = scene.target.clone().sub(scene.eye).normalize();
	const right = fwd.clone().cross(new THREE.Vector3(0, 1, 0)).normalize();
	const up = right.clone().cross(fwd);
	return {
		eye: scene.eye.toArray(), fwd: fwd.toArray(), right: right.toArray(), up: up.toArray(),
		tanHalfFov: Math.tan((scene.fovYDeg * Math.PI) / 360), exposure: scene.exposure,
		fogSigmaS: scene.fogSigmaS, fogSigmaA: scene.fogSigmaA, slabSigmaS: scene.slabSigmaS, slabSigmaA: scene.slabSigmaA,
		lights: scene.lights,
	};
}

// WebGPU where asked for or, without a backend parameter, where the browser gives an adapter.
async function webgpuAdapter() {
	const asked = params.get('backend');
	if (asked === 'webgl2') return null;
	const adapter = navigator.gpu ? await navigator.gpu.requestAdapter() : null;
	if (!adapter && asked === 'webgpu') throw new Error('backend=webgpu: this browser gives no WebGPU adapter');
	return adapter;
}

async function main() {
	const canvas = document.querySelector('canvas');
	canvas.width = W;
	canvas.height = H;
	const asked = params.get('tier') ?? 'fast';
	if (!(asked in kTiers)) throw new Error(`tier=${asked}: expected one of ${Object.keys(kTiers).join(', ')}`);
	const adapter = await webgpuAdapter();
	window.slutBackend = adapter ? 'webgpu' : 'webgl2';
	if (adapter) {
		document.title = 'scatterlut: fog street (WebGPU)';
		// The test's fixed view goes into a texture of the page's own (headless Chromium cannot
		// present a WebGPU canvas on SwiftShader).
		const gpu = await startWebGPU(adapter, testMode ? null : canvas, W, H, asked, kTiers);
		const update = () => gpu.draw(view());
		update();
		if (testMode) {
			window.slutFrame = await gpu.readFrame();
			window.slutTier = gpu.tier;
			window.slutDone = true;
			return;
		}
		await controls(update, gpu.tier);
		return;
	}
	const renderer = new THREE.WebGLRenderer({ canvas, antialias: false, preserveDrawingBuffer: true });
	renderer.setPixelRatio(1);
	renderer.setSize(W, H, false);
	const loader = new KTX2Loader().detectSupport(renderer);
	let tierName = asked;
	if (tierName === 'fast' && !renderer.extensions.has('OES_texture_float_linear')) {
		console.warn('OES_texture_float_linear missing: R32F tables cannot be filtered; the accurate tier instead');
		tierName = 'accurate';
	}
	const tier = kTiers[tierName];
	const filter = tierName === 'fast' ? THREE.LinearFilter : THREE.NearestFilter;
	const [air, near, airSnippet, nearSnippet] = await Promise.all([
		loadTable(loader, `tables/${tier.airlight}.ktx2`, filter), loadTable(loader, 'tables/near_light_E3.ktx2', filter),
		text('shaders/scatterlut_airlight.essl'), text('shaders/scatterlut_nearlight.essl'),
	]);
	if (air.meta.kind !== tier.airlight || near.meta.kind !== 'near_light_E3')
		throw new Error(`unexpected tables ${air.meta.kind}, ${near.meta.kind}`);
	// slut_airlight_table() takes the default airlight axes: u log1p from 0, w asinh_cot to pi/2.
	if (tier.airlight === 'airlight_F' && (air.meta.axes[0].warpName !== 'log1p' || air.meta.axes[1].warpName !== 'asinh_cot'))
		throw new Error('airlight_F: expected axes u (log1p) and w (asinh_cot)');
	const [au, aw] = air.meta.axes, [nT, ng, nr] = near.meta.axes;
	const uniforms = {
		airlight_table: { value: air.texture }, near_table: { value: near.texture },
		air_u: { value: axisUniform(au) }, air_w: { value: axisUniform(aw) },
		near_T: { value: axisUniform(nT) }, near_g: { value: axisUniform(ng) }, near_r: { value: axisUniform(nr) },
		near_warps: { value: [nT.warp, ng.warp, nr.warp] },
		eye: { value: new THREE.Vector3() }, fwd: { value: new THREE.Vector3() },
		right: { value: new THREE.Vector3() }, up: { value: new THREE.Vector3() },
		tan_half_fov: { value: 0 }, aspect: { value: W / H }, exposure: { value: scene.exposure },
		fog_sigma: { value: new THREE.Vector2() }, slab_sigma: { value: new THREE.Vector2() },
		lights: { value: scene.lights.map(() => new THREE.Vector4()) },
		light_colors: { value: scene.lights.map(() => new THREE.Vector3()) },
		light_axes: { value: scene.lights.map(() => new THREE.Vector3()) },
		light_cones: { value: scene.lights.map(() => new THREE.Vector2()) },
		resolution: { value: new THREE.Vector2(W, H) },
	};
	// glslVersion GLSL3: three.js puts "#version 300 es" first; the snippets declare highp.
	const material = new THREE.RawShaderMaterial({
		glslVersion: THREE.GLSL3, uniforms,
		vertexShader: 'in vec3 position;\nvoid main() { gl_Position = vec4(position.xy, 0.0, 1.0); }\n',
		fragmentShader: fragmentShader(tier.define, airSnippet, nearSnippet),
	});
	const quad = new THREE.Mesh(new THREE.PlaneGeometry(2, 2), material);
	const root = new THREE.Scene();
	root.add(quad);
	const camera = new THREE.Camera();

	function update() {
		const v = view();
		uniforms.eye.value.fromArray(v.eye);
		uniforms.fwd.value.fromArray(v.fwd);
		uniforms.right.value.fromArray(v.right);
		uniforms.up.value.fromArray(v.up);
		uniforms.tan_half_fov.value = v.tanHalfFov;
		uniforms.fog_sigma.value.set(scene.fogSigmaS, scene.fogSigmaA);
		uniforms.slab_sigma.value.set(scene.slabSigmaS, scene.slabSigmaA);
		uniforms.exposure.value = scene.exposure;
		scene.lights.forEach((l, k) => {
			uniforms.lights.value[k].set(l[0], l[1], l[2], l[3]);
			uniforms.light_colors.value[k].set(l[4], l[5], l[6]);
			uniforms.light_axes.value[k].set(l[7], l[8], l[9]);
			uniforms.light_cones.value[k].set((l[10] * Math.PI) / 180, (l[11] * Math.PI) / 180);
		});
		renderer.render(root, camera);
	}
	update();

	if (testMode) {
		// The frame as 8-bit RGB, rows top to bottom (render_fog's order).
		const gl = renderer.getContext();
		const rgba = new Uint8Array(W * H * 4);
		gl.readPixels(0, 0, W, H, gl.RGBA, gl.UNSIGNED_BYTE, rgba);
		const rgb = new Array(W * H * 3);
		for (let y = 0; y < H; y++)
			for (let x = 0; x < W; x++)
				for (let c = 0; c < 3; c++) rgb[(y * W + x) * 3 + c] = rgba[((H - 1 - y) * W + x) * 4 + c];
		window.slutFrame = rgb;
		window.slutTier = tierName; // the tier that ran (fast falls back to accurate without float filtering)
		window.slutDone = true;
		return;
	}
	await controls(update, tierName);
}

// Interactive: the tier (reloads the page), camera yaw/pitch, the small lamp's position, the
// media's sigma; update() redraws.
async function controls(update, tierName) {
	const { GUI } = await import('three/addons/libs/lil-gui.module.min.js');
	const gui = new GUI();
	gui.add({ tier: tierName }, 'tier', Object.keys(kTiers)).name('tier (docs/SHADERS.md)').onChange((t) => {
		params.set('tier', t);
		location.search = params.toString();
	});
	const angles = { yawDeg: 0, pitchDeg: 1.3, eyeX: 0, eyeZ: 0 };
	const aim = () => {
		scene.eye.set(angles.eyeX, 1.7, angles.eyeZ);
		const yaw = (angles.yawDeg * Math.PI) / 180, pitch = (angles.pitchDeg * Math.PI) / 180;
		scene.target.set(scene.eye.x - 30 * Math.sin(yaw), scene.eye.y + 30 * Math.tan(pitch), scene.eye.z - 30 * Math.cos(yaw));
		update();
	};
	const cam = gui.addFolder('camera');
	cam.add(angles, 'yawDeg', -60, 60).onChange(aim);
	cam.add(angles, 'pitchDeg', -20, 30).onChange(aim);
	cam.add(angles, 'eyeX', -4, 4).onChange(aim);
	cam.add(angles, 'eyeZ', -8, 5).onChange(aim);
	const lamp = { x: 2.0, y: 1.2, z: -8.6, I0: 40 };
	const lampFolder = gui.addFolder('small lamp (in front of the slab)');
	for (const [k, lo, hi] of [['x', 0, 4], ['y', 0.2, 3], ['z', -8.95, -6], ['I0', 0, 200]])
		lampFolder.add(lamp, k, lo, hi).onChange(() => {
			scene.lights[4] = [lamp.x, lamp.y, lamp.z, lamp.I0, 0.85, 0.9, 1.0, 0.0, -1.0, 0.0, 180, 180];
			update();
		});
	const media = gui.addFolder('media (1/m)');
	media.add(scene, 'fogSigmaS', 0, 0.2).name('fog sigma_s').onChange(update);
	media.add(scene, 'fogSigmaA', 0, 0.1).name('fog sigma_a').onChange(update);
	media.add(scene, 'slabSigmaS', 0.5, 20).name('slab sigma_s').onChange(update);
	media.add(scene, 'slabSigmaA', 0, 2).name('slab sigma_a').onChange(update);
	gui.add(scene, 'exposure', 0.01, 50).onChange(update);
}

main().catch((e) => {
	console.error(e);
	window.slutError = String(e && e.stack || e);
	document.body.insertAdjacentHTML('beforeend', `<pre style="color:#f66">${String(e)}</pre>`);
});
