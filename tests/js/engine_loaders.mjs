// Engine loaders open scatterlut's tables: three.js's EXRLoader decodes every default table
// (and KTX2Loader every .ktx2 beside it) to the values and metadata scatterlut stored, as
// read from the .slut file of the same table by slut.mjs (an independent reader of
// docs/FORMAT.md). Run by CTest (tests/CMakeLists.txt, label js):
//
//   node tests/js/engine_loaders.mjs TABLE_DIR [--require]
//
// TABLE_DIR holds `scatterlut generate --format all` output. Without the npm modules
// (`npm ci` in tests/js) the test prints "skipped: …" and exits 77, or fails with --require.
import { readFileSync, existsSync } from 'node:fs';
import { join } from 'node:path';
import { parseSlut, metadataFromExrHeader, metadataFromKtx2KeyValue, halfToNumber } from './slut.mjs';

const args = process.argv.slice(2);
const require = args.includes('--require');
const dir = args.find((a) => !a.startsWith('--'));
if (!dir) {
	console.error('usage: node engine_loaders.mjs TABLE_DIR [--require]');
	process.exit(2);
}

function skip(why) {
	if (require) {
		console.error(`FAIL (required): ${why}`);
		process.exit(1);
	}
	console.log(`skipped: ${why}`);
	process.exit(77);
}

const nodeMajor = Number(process.versions.node.split('.')[0]);
if (nodeMajor < 18) skip(`node ${process.versions.node} is older than 18 (Debian 12 ships 18)`);

let THREE, EXRLoader, KTX2Loader;
try {
	THREE = await import('three');
	({ EXRLoader } = await import('three/examples/jsm/loaders/EXRLoader.js'));
	({ KTX2Loader } = await import('three/examples/jsm/loaders/KTX2Loader.js'));
} catch (e) {
	skip(`three.js is not installed (run \`npm ci\` in tests/js, or \`make test\`): ${e.message}`);
}

let failures = 0;
function check(ok, what) {
	if (!ok) {
		failures++;
		console.error(`FAIL: ${what}`);
	}
}

// Same metadata: kind, storage, every axis number exactly, channels.
function compareMetadata(file, got, want) {
	check(got.kind === want.kind, `${file}: kind ${got.kind}, expected ${want.kind}`);
	check(got.quantityVersion === want.quantityVersion, `${file}: quantity version`);
	check(got.storage === want.storage, `${file}: storage ${got.storage}, expected ${want.storage}`);
	check(got.axes.length === want.axes.length, `${file}: ${got.axes.length} axes, expected ${want.axes.length}`);
	want.axes.forEach((a, i) => {
		const b = got.axes[i] ?? {};
		for (const f of ['name', 'min', 'max', 'scale', 'warp', 'warpName', 'count'])
			check(Object.is(b[f], a[f]), `${file}: axis ${i} ${f} = ${b[f]}, expected ${a[f]}`);
	});
	check(got.channels.length === want.channels.length, `${file}: channel count`);
	want.channels.forEach((c, j) => {
		const d = got.channels[j] ?? {};
		check(d.name === c.name && d.encoding === c.encoding, `${file}: channel ${j} is ${d.name}/${d.encoding}, expected ${c.name}/${c.encoding}`);
	});
}

// Values: the loader's numbers (float32, or binary16 bit patterns) equal the stored ones.
// `rowsOf` > 0: the loader returns the image bottom-up (three.js's EXRLoader: its row k is
// the file's row rowsOf − 1 − k, the OpenGL convention), so compare row-flipped.
function compareValues(file, data, isHalf, want, stride = 1, rowsOf = 0) {
	const n = want.values.length;
	check(data.length === n * stride, `${file}: ${data.length} numbers, expected ${n * stride}`);
	const width = rowsOf ? n / rowsOf : n;
	let bad = 0;
	for (let i = 0; i < n && bad < 5; i++) {
		const at = rowsOf ? (rowsOf - 1 - Math.floor(i / width)) * width + (i % width) : i;
		const v = isHalf ? halfToNumber(data[at * stride]) : data[at * stride];
		if (!Object.is(v, want.values[i])) {
			bad++;
			check(false, `${file}: value ${i} is ${v}, expected ${want.values[i]}`);
		}
	}
	return n;
}

const kinds = ['airlight_F', 'near_light_E3', 'near_light_E4', 'airlight_rational'];
for (const kind of kinds) {
	const slutPath = join(dir, `${kind}.slut`);
	if (!existsSync(slutPath)) {
		check(false, `${slutPath} is missing`);
		continue;
	}
	const ours = parseSlut(readFileSync(slutPath), slutPath);
	const nodes = ours.values.length / ours.channels.length;

	// EXR: the image is axis 0 across, the other axes down (a vertical atlas, FORMAT.md §4).
	const exrPath = join(dir, `${kind}.exr`);
	if (existsSync(exrPath)) {
		const buf = readFileSync(exrPath);
		const loader = new EXRLoader().setDataType(THREE.FloatType).setOutputFormat(THREE.RedFormat);
		const tex = loader.parse(buf.buffer.slice(buf.byteOffset, buf.byteOffset + buf.byteLength));
		check(tex.width === ours.axes[0].count && tex.height === nodes / ours.axes[0].count,
			`${exrPath}: ${tex.width} x ${tex.height} pixels`);
		check(tex.format === THREE.RedFormat, `${exrPath}: format ${tex.format}, expected RedFormat`);
		const meta = metadataFromExrHeader(tex.header);
		compareMetadata(exrPath, meta, ours);
		check(meta.channels.every((c) => c.containerChannel === 'Y'), `${exrPath}: single channel stored as Y`);
		const n = compareValues(exrPath, tex.data, false, ours, 1, tex.height);
		// The loader's default output (RGBA, Y copied to R, G and B; A = 1) holds the same values.
		const rgba = new EXRLoader().setDataType(THREE.FloatType).parse(buf.buffer.slice(buf.byteOffset, buf.byteOffset + buf.byteLength));
		compareValues(`${exrPath} (RGBA)`, rgba.data, false, ours, 4, tex.height);
		console.log(`EXRLoader  ${kind}.exr: ${tex.width} x ${tex.height}, ${n} values equal to the .slut file's`);
	} else {
		check(false, `${exrPath} is missing`);
	}

	// KTX2: R32_SFLOAT / R16_SFLOAT, 2-D, 3-D, or 4-D packed into 3-D (FORMAT.md §6).
	const ktxPath = join(dir, `${kind}.ktx2`);
	if (existsSync(ktxPath)) {
		const buf = readFileSync(ktxPath);
		const loader = new KTX2Loader();
		// No renderer under node: report no compressed-texture support. Uncompressed files
		// (vkFormat != 0) never reach the Basis transcoder, which needs one.
		loader.detectSupport({ extensions: { has: () => false, get: () => null } });
		const tex = await new Promise((resolve, reject) =>
			loader.parse(buf.buffer.slice(buf.byteOffset, buf.byteOffset + buf.byteLength), resolve, reject));
		const img = tex.image;
		const c = ours.axes.map((a) => a.count);
		const isHalf = ours.storage === 'f16';
		check(tex.type === (isHalf ? THREE.HalfFloatType : THREE.FloatType), `${ktxPath}: texture type ${tex.type}`);
		check(tex.format === THREE.RedFormat, `${ktxPath}: format ${tex.format}, expected RedFormat`);
		const want3d = c.length >= 3;
		check(Boolean(tex.isData3DTexture) === want3d, `${ktxPath}: ${want3d ? 'a' : 'not a'} 3-D texture expected`);
		// 4-D (T, g, r, q): width c0, height c1·c3 (q slices stacked in y), depth c2.
		const [w, h, d] = c.length === 4 ? [c[0], c[1] * c[3], c[2]] : [c[0], c[1] ?? 1, c[2] ?? 1];
		check(img.width === w && img.height === h && (img.depth ?? 1) === d,
			`${ktxPath}: ${img.width} x ${img.height} x ${img.depth}, expected ${w} x ${h} x ${d}`);
		let want = ours;
		if (c.length === 4) { // reorder ours into the packed texel order (x fastest, then y, then z)
			const packed = new Float64Array(ours.values.length);
			let k = 0;
			for (let i2 = 0; i2 < c[2]; i2++)
				for (let i3 = 0; i3 < c[3]; i3++)
					for (let i1 = 0; i1 < c[1]; i1++)
						for (let i0 = 0; i0 < c[0]; i0++)
							packed[k++] = ours.values[((i3 * c[2] + i2) * c[1] + i1) * c[0] + i0];
			want = { values: packed };
		}
		const n = compareValues(ktxPath, img.data, isHalf, want);
		// Metadata from the key/value data, through ktx-parse (the parser KTX2Loader uses).
		const { read } = await import('three/examples/jsm/libs/ktx-parse.module.js');
		const container = read(new Uint8Array(buf));
		compareMetadata(ktxPath, metadataFromKtx2KeyValue(container.keyValue), ours);
		console.log(`KTX2Loader ${kind}.ktx2: ${img.width} x ${img.height} x ${img.depth ?? 0}, ${n} values equal to the .slut file's`);
	} else {
		check(!args.includes('--ktx2'), `${ktxPath} is missing`);
	}
}

if (failures) {
	console.error(`${failures} check(s) failed`);
	process.exit(1);
}
console.log('all engine-loader checks passed');
