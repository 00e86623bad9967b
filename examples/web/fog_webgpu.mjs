// The fog street on WebGPU (fog.mjs picks it where the browser has WebGPU): the same picture as
// the WebGL2 path, from the WGSL snippets of the same tier (scatterlut_airlight[_fast|_accurate].wgsl,
// scatterlut_nearlight[...].wgsl: generated from the same source as the .essl ones; docs/SHADERS.md
// "WGSL (WebGPU)") in plain WebGPU: the tables straight from their .ktx2 files (r32float, one
// level, no supercompression: docs/FORMAT.md §7) as a 2-D and a 3-D texture, read with textureLoad
// (tiers accurate and airlight_F: no filtering, no device feature) or through a linear
// clamp-to-edge sampler (tier fast: the device feature float32-filterable, without which the
// accurate tier serves), the scene's numbers in one uniform buffer, one full-screen triangle whose
// fragment shader does per pixel what fog.mjs's GLSL does.
import { read } from 'three/addons/libs/ktx-parse.module.js';
import { metadataFromKtx2KeyValue } from './slut.mjs';

const kLamps = 8; // fog.mjs's scene.lights

// The scene's numbers (struct Scene below: 15 vec4 and four per lamp; WGSL's uniform layout, every
// member 16-byte aligned).
const kVec4s = 15 + 4 * kLamps;

// The scene's shader, appended to the snippets: `fast` passes each table's sampler after it,
// `rational` builds the airlight tiers' table (slut_airlight_table(m_count, t_count)).
function sceneShader(fast, rational) {
	const airArg = fast ? 'airlight_table, airlight_sampler' : 'airlight_table';
	const nearArg = fast ? 'near_table, near_sampler' : 'near_table';
	const airTable = rational ? 'slut_airlight_table(i32(scene.air_u.w), i32(scene.air_w.w))'
		: 'slut_airlight_table(scene.air_u.y, scene.air_u.z, i32(scene.air_u.w), scene.air_w.x, i32(scene.air_w.w))';
	return /* wgsl */ `
struct Scene {
    air_u: vec4<f32>,           // min, max, scale, count of the airlight axes (u, w; tiers: x_m, x_t)
    air_w: vec4<f32>,
    near_T: vec4<f32>,          // of the E3 axes T, g, r
    near_g: vec4<f32>,
    near_r: vec4<f32>,
    near_warps: vec4<i32>,      // their warps
    eye: vec4<f32>,             // xyz (m)
    fwd: vec4<f32>,
    right: vec4<f32>,
    up: vec4<f32>,
    view: vec4<f32>,            // tan_half_fov, aspect, exposure, -
    resolution: vec4<f32>,      // width, height (pixels), -, -
    fog_sigma: vec4<f32>,       // sigma_s, sigma_a (1/m), -, -
    slab_sigma: vec4<f32>,
    pad: vec4<f32>,
    lights: array<vec4<f32>, ${kLamps}>,        // xyz position (m), w I0 (W/sr)
    light_colors: array<vec4<f32>, ${kLamps}>,
    light_axes: array<vec4<f32>, ${kLamps}>,    // xyz a spot's axis (light -> lit points), -
    light_cones: array<vec4<f32>, ${kLamps}>,   // its outer, inner cone half-angle (rad), -, -
}
@group(0) @binding(0) var airlight_table: texture_2d<f32>;
@group(0) @binding(1) var near_table: texture_3d<f32>;
@group(0) @binding(2) var<uniform> scene: Scene;
${fast ? '@group(0) @binding(3) var airlight_sampler: sampler;\n@group(0) @binding(4) var near_sampler: sampler;' : ''}

const kWallZ = -90.0;
const kWallH = 14.0;
const kSlabZ = -9.0;
const kSlabX0 = 1.2;
const kSlabX1 = 3.2;
const kSlabH = 2.0;
const kSlabColor = vec3<f32>(1.0, 0.5, 0.25);

// Reinhard after exposure, then the sRGB curve (render_fog's tone_map); +inf is white.
// glTF's falloff of light k towards p (render_fog's falloff_towards): kernels/slut_spot.h in
// the airlight snippet.
fn falloff_towards(k: i32, p: vec3<f32>) -> f32 {
    let vers = slut_spot_versine_of(slut_vec3_of(normalize(p - scene.lights[k].xyz)),
                                    slut_vec3_of(normalize(scene.light_axes[k].xyz)));
    return slut_spot_falloff(vers, slut_spot_versine(scene.light_cones[k].x), slut_spot_versine(scene.light_cones[k].y));
}

fn tone(x: f32) -> f32 {
    let c = select(1.0, x / (1.0 + x), x < 3.0e38);
    return select(1.055 * pow(c, 1.0 / 2.4) - 0.055, 12.92 * c, c <= 0.0031308);
}

@vertex
fn vs(@builtin(vertex_index) v: u32) -> @builtin(position) vec4<f32> {
    return vec4<f32>(vec2<f32>(f32(v & 1u), f32(v >> 1u)) * 4.0 - 1.0, 0.0, 1.0);
}

@fragment
fn fs(@builtin(position) frag: vec4<f32>) -> @location(0) vec4<f32> {
    // Pixel (i, j) of render_fog, j counted from the top (WebGPU's frag.y is).
    let i = frag.x - 0.5;
    let j = frag.y - 0.5;
    let px = (2.0 * (i + 0.5) / scene.resolution.x - 1.0) * scene.view.x * scene.view.y;
    let py = (1.0 - 2.0 * (j + 0.5) / scene.resolution.y) * scene.view.x;
    let d = normalize(scene.fwd.xyz + px * scene.right.xyz + py * scene.up.xyz);
    let eye = scene.eye.xyz;
    var s = slut_inf();
    var slab = false;
    if (d.y < 0.0) {
        s = min(s, -eye.y / d.y);
    }
    if (d.z < 0.0) {
        var t = (kWallZ - eye.z) / d.z;
        var p = eye + t * d;
        if (t < s && p.y <= kWallH) {
            s = t;
        }
        t = (kSlabZ - eye.z) / d.z;
        p = eye + t * d;
        if (t < s && p.x >= kSlabX0 && p.x <= kSlabX1 && p.y >= 0.0 && p.y <= kSlabH) {
            s = t;
            slab = true;
        }
    }
    let air = ${airTable};
    let e3 = slut_near_light_table_e3(
        slut_axis_make(scene.near_T.x, scene.near_T.y, scene.near_T.z, scene.near_warps.x, i32(scene.near_T.w)),
        slut_axis_make(scene.near_g.x, scene.near_g.y, scene.near_g.z, scene.near_warps.y, i32(scene.near_g.w)),
        slut_axis_make(scene.near_r.x, scene.near_r.y, scene.near_r.z, scene.near_warps.z, i32(scene.near_r.w)));
    var L = vec3<f32>(0.0);
    let fog_t = scene.fog_sigma.x + scene.fog_sigma.y;
    for (var k = 0; k < ${kLamps}; k++) {
        L += slut_airlight_spot_radiance_points(${airArg}, air, eye, d, scene.lights[k].xyz, scene.light_axes[k].xyz,
                                                scene.light_cones[k].x, scene.light_cones[k].y, s, scene.fog_sigma.x,
                                                scene.fog_sigma.y, scene.lights[k].w) * scene.light_colors[k].xyz;
    }
    if (slab) {
        let p = eye + s * d;
        for (var k = 0; k < ${kLamps}; k++) {
            let rel = scene.lights[k].xyz - p;
            let att = exp(-fog_t * (length(rel) + s));
            let Ln = slut_near_light_radiance(${nearArg}, e3, scene.slab_sigma.x, scene.slab_sigma.y, scene.lights[k].w,
                                              vec3<f32>(0.0, 0.0, 1.0), -d, rel, slut_inf(), 1.0, false) * att *
                     falloff_towards(k, p);
            L += Ln * scene.light_colors[k].xyz * kSlabColor;
        }
    }
    let x = scene.view.z;
    return vec4<f32>(tone(L.r * x), tone(L.g * x), tone(L.b * x), 1.0);
}
`;
}

async function fetchOk(url) {
	const r = await fetch(url);
	if (!r.ok) throw new Error(`${url}: HTTP ${r.status}`);
	return r;
}

// A table's .ktx2 file: its metadata and its level 0 as an r32float texture.
async function loadTable(device, url) {
	const ktx = read(new Uint8Array(await (await fetchOk(url)).arrayBuffer()));
	if (ktx.vkFormat !== 100 || ktx.supercompressionScheme !== 0 || ktx.levels.length !== 1)
		throw new Error(`${url}: expected one uncompressed R32_SFLOAT level (vkFormat 100), not ${ktx.vkFormat}`);
	const meta = metadataFromKtx2KeyValue(ktx.keyValue);
	const three_d = ktx.pixelDepth > 0;
	const size = [ktx.pixelWidth, ktx.pixelHeight, three_d ? ktx.pixelDepth : 1];
	const texture = device.createTexture({ size, format: 'r32float', dimension: three_d ? '3d' : '2d',
		usage: GPUTextureUsage.TEXTURE_BINDING | GPUTextureUsage.COPY_DST });
	const data = ktx.levels[0].levelData;
	device.queue.writeTexture({ texture }, data, { bytesPerRow: 4 * size[0], rowsPerImage: size[1] }, size);
	return { texture, meta };
}

const axis = (a) => [a.min, a.max, a.scale, a.count];

// Sets up the WebGPU renderer of the scene, W x H, in tier `asked` (fog.mjs's kTiers: the
// airlight table each samples): on `canvas` (its 'webgpu' context), or, with canvas null, into a
// texture of its own (the test's frame: headless Chromium cannot present a WebGPU canvas on
// SwiftShader). Returns draw(view) (view: the camera vectors and the scene's numbers, as fog.mjs
// computes them), readFrame(), the last drawn view as 8-bit RGB rows top to bottom (render_fog's
// order), and tier, the tier that runs (fast falls back to accurate without float32-filterable).
export async function startWebGPU(adapter, canvas, W, H, asked, tiers) {
	let tier = asked;
	if (tier === 'fast' && !adapter.features.has('float32-filterable')) {
		console.warn('float32-filterable missing: r32float tables cannot be filtered; the accurate tier instead');
		tier = 'accurate';
	}
	const fast = tier === 'fast', rational = tiers[tier].airlight === 'airlight_rational';
	const suffix = tier === 'airlight_F' ? '' : `_${tier}`;
	const device = await adapter.requestDevice({ requiredFeatures: fast ? ['float32-filterable'] : [] });
	device.lost.then((info) => { if (info.reason !== 'destroyed') window.slutError = `WebGPU device lost: ${info.message}`; });
	const [air, near, airSnippet, nearSnippet] = await Promise.all([
		loadTable(device, `tables/${tiers[tier].airlight}.ktx2`), loadTable(device, 'tables/near_light_E3.ktx2'),
		fetchOk(`shaders/scatterlut_airlight${suffix}.wgsl`).then((r) => r.text()),
		fetchOk(`shaders/scatterlut_nearlight${suffix}.wgsl`).then((r) => r.text()),
	]);
	if (air.meta.kind !== tiers[tier].airlight || near.meta.kind !== 'near_light_E3')
		throw new Error(`unexpected tables ${air.meta.kind}, ${near.meta.kind}`);
	// slut_airlight_table() takes the default airlight axes: u log1p from 0, w asinh_cot to pi/2.
	if (!rational && (air.meta.axes[0].warpName !== 'log1p' || air.meta.axes[1].warpName !== 'asinh_cot'))
		throw new Error('airlight_F: expected axes u (log1p) and w (asinh_cot)');
	// Two snippets in one module: their shared part (the float math, kernels/) once.
	const marker = '// ==== END SHARED';
	if (!nearSnippet.includes(marker)) throw new Error('scatterlut_nearlight.wgsl has no shared-part marker');
	const code = airSnippet + nearSnippet.slice(nearSnippet.indexOf(marker) + marker.length) + sceneShader(fast, rational);
	device.pushErrorScope('validation');
	const module = device.createShaderModule({ code });
	const errors = (await module.getCompilationInfo()).messages.filter((m) => m.type === 'error');
	if (errors.length) throw new Error(`WGSL: ${errors.map((m) => `${m.lineNum}:${m.linePos} ${m.message}`).join('\n')}`);
	// The canvas's preferred format (a non-sRGB one: the shader writes sRGB-encoded values itself).
	const format = canvas ? navigator.gpu.getPreferredCanvasFormat() : 'rgba8unorm';
	const context = canvas ? canvas.getContext('webgpu') : null;
	if (context) context.configure({ device, format, alphaMode: 'opaque' });
	const pipeline = await device.createRenderPipelineAsync({
		layout: 'auto', vertex: { module, entryPoint: 'vs' },
		fragment: { module, entryPoint: 'fs', targets: [{ format }] }, primitive: { topology: 'triangle-list' },
	});
	const uniform = device.createBuffer({ size: 16 * kVec4s, usage: GPUBufferUsage.UNIFORM | GPUBufferUsage.COPY_DST });
	const entries = [{ binding: 0, resource: air.texture.createView() }, { binding: 1, resource: near.texture.createView() },
		{ binding: 2, resource: { buffer: uniform } }];
	if (fast) { // the hardware filter: linear, clamp-to-edge, no mipmaps
		const sampler = device.createSampler({ magFilter: 'linear', minFilter: 'linear', addressModeU: 'clamp-to-edge',
			addressModeV: 'clamp-to-edge', addressModeW: 'clamp-to-edge' });
		entries.push({ binding: 3, resource: sampler }, { binding: 4, resource: sampler });
	}
	const group = device.createBindGroup({ layout: pipeline.getBindGroupLayout(0), entries });
	const error = await device.popErrorScope();
	if (error) throw new Error(`WebGPU: ${error.message}`);

	const [au, aw] = air.meta.axes, [nT, ng, nr] = near.meta.axes;
	const f = new Float32Array(4 * kVec4s), i32 = new Int32Array(f.buffer);
	function render(target) {
		const encoder = device.createCommandEncoder();
		const pass = encoder.beginRenderPass({ colorAttachments: [{ view: target.createView(), loadOp: 'clear', storeOp: 'store',
			clearValue: [0, 0, 0, 1] }] });
		pass.setPipeline(pipeline);
		pass.setBindGroup(0, group);
		pass.draw(3);
		pass.end();
		device.queue.submit([encoder.finish()]);
	}
	function draw(v) {
		const put = (k, values) => f.set(values, 4 * k);
		put(0, axis(au)); put(1, axis(aw)); put(2, axis(nT)); put(3, axis(ng)); put(4, axis(nr));
		i32.set([nT.warp, ng.warp, nr.warp, 0], 4 * 5);
		put(6, [...v.eye, 0]); put(7, [...v.fwd, 0]); put(8, [...v.right, 0]); put(9, [...v.up, 0]);
		put(10, [v.tanHalfFov, W / H, v.exposure, 0]); put(11, [W, H, 0, 0]);
		put(12, [v.fogSigmaS, v.fogSigmaA, 0, 0]); put(13, [v.slabSigmaS, v.slabSigmaA, 0, 0]);
		v.lights.forEach((l, k) => {
			put(15 + k, [l[0], l[1], l[2], l[3]]);
			put(15 + kLamps + k, [l[4], l[5], l[6], 0]);
			put(15 + 2 * kLamps + k, [l[7], l[8], l[9], 0]);
			put(15 + 3 * kLamps + k, [(l[10] * Math.PI) / 180, (l[11] * Math.PI) / 180, 0, 0]);
		});
		device.queue.writeBuffer(uniform, 0, f);
		render(context ? context.getCurrentTexture() : offscreen);
	}
	const offscreen = context ? null : device.createTexture({ size: [W, H], format,
		usage: GPUTextureUsage.RENDER_ATTACHMENT | GPUTextureUsage.COPY_SRC });
	// The last drawn view's pixels: drawn once more into a texture of the canvas's format, read back.
	async function readFrame() {
		const texture = offscreen ?? device.createTexture({ size: [W, H], format,
			usage: GPUTextureUsage.RENDER_ATTACHMENT | GPUTextureUsage.COPY_SRC });
		if (!offscreen) render(texture);
		const bytesPerRow = Math.ceil((4 * W) / 256) * 256;
		const buffer = device.createBuffer({ size: bytesPerRow * H, usage: GPUBufferUsage.COPY_DST | GPUBufferUsage.MAP_READ });
		const encoder = device.createCommandEncoder();
		encoder.copyTextureToBuffer({ texture }, { buffer, bytesPerRow }, [W, H]);
		device.queue.submit([encoder.finish()]);
		await buffer.mapAsync(GPUMapMode.READ);
		const bytes = new Uint8Array(buffer.getMappedRange());
		const order = format.startsWith('bgra') ? [2, 1, 0] : [0, 1, 2];
		const rgb = new Array(W * H * 3);
		for (let y = 0; y < H; y++)
			for (let x = 0; x < W; x++)
				for (let c = 0; c < 3; c++) rgb[(y * W + x) * 3 + c] = bytes[y * bytesPerRow + 4 * x + order[c]];
		buffer.unmap();
		buffer.destroy();
		if (texture !== offscreen) texture.destroy();
		return rgb;
	}
	return { draw, readFrame, tier };
}
