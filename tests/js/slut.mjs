// scatterlut tables in JavaScript (browser or node, no dependencies): reads the binary
// `.slut` format and the metadata of the engine containers, as docs/FORMAT.md defines them.
//
//   parseSlut(arrayBuffer)            → table (metadata and values), checksums verified
//   metadataFromExrHeader(header)     → metadata from three.js EXRLoader's `header`
//   metadataFromKtx2KeyValue(kv)      → metadata from ktx-parse's / KTX2 `keyValue`
//
// A table: { kind, quantityVersion, storage ('f16' | 'f32' | 'f64'), formatVersion,
//   axes: [{ name, meaning, min, max, scale, warp, warpName, count }] (axis 0 fastest),
//   channels: [{ name, meaning, encoding ('linear' | 'log') }], accuracy, provenance, extra,
//   values: Float64Array, channel fastest, then axis 0, axis 1, … }.
// Errors are thrown as Error with a message that says what was expected.

const MAGIC = [0x53, 0x4c, 0x55, 0x54, 0x54, 0x42, 0x4c, 0x00]; // "SLUTTBL\0"
const FORMAT_MAJOR = 1;
const FORMAT_MINOR = 1;
export const WARP_NAMES = ['linear', 'log', 'log1p', 'asinh_cot', 'sqrt1p', 'loglin', 'nl_qodds', 'asinh_cot_peak'];
const STORAGE = { 1: 'f16', 2: 'f32', 3: 'f64' };
const ENCODING = { 0: 'linear', 1: 'log' };

// 64-bit FNV-1a (docs/FORMAT.md §2.5), continued from `state`.
export function fnv1a64(bytes, state = 0xcbf29ce484222325n) {
	const prime = 0x100000001b3n, mask = 0xffffffffffffffffn;
	let h = state;
	for (let i = 0; i < bytes.length; i++) h = ((h ^ BigInt(bytes[i])) * prime) & mask;
	return h;
}

// IEEE binary16 → number, exactly (subnormals included).
export function halfToNumber(h) {
	const s = h & 0x8000 ? -1 : 1, e = (h >> 10) & 0x1f, m = h & 0x3ff;
	if (e === 0) return s * m * 2 ** -24;
	if (e === 31) return m ? NaN : s * Infinity;
	return s * (1 + m / 1024) * 2 ** (e - 15);
}

const decoder = new TextDecoder('utf-8', { fatal: true });

// Records (tag u32, length u32, value) of bytes [begin, end) of `view`.
function records(view, begin, end, what) {
	const out = [];
	let p = begin;
	while (p < end) {
		if (end - p < 8) throw new Error(`${what}: record header at byte ${p} runs past its section`);
		const tag = view.getUint32(p, true), len = view.getUint32(p + 4, true);
		p += 8;
		if (len > end - p) throw new Error(`${what}: record tag ${tag} at byte ${p - 8} claims ${len} bytes, ${end - p} remain`);
		if (tag !== 0) out.push({ tag, at: p, len });
		p += len;
	}
	return out;
}

export function parseSlut(buffer, name = 'table') {
	const bytes = new Uint8Array(buffer);
	const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
	const fail = (what) => { throw new Error(`${name}: ${what}`); };
	for (let i = 0; i < 8; i++) {
		if (i >= bytes.length) fail('truncated inside the magic');
		if (bytes[i] !== MAGIC[i]) fail('not a scatterlut binary table: expected magic 53 4c 55 54 54 42 4c 00');
	}
	if (bytes.length < 48) fail(`truncated: ${bytes.length} bytes, the preamble has 48`);
	const major = view.getUint32(8, true), minor = view.getUint32(12, true);
	if (major !== FORMAT_MAJOR) fail(`format version ${major}.${minor} is not ${FORMAT_MAJOR}.x`);
	const H = view.getBigUint64(16, true), P = view.getBigUint64(24, true);
	if (48n + H + P !== BigInt(bytes.length)) fail(`size ${bytes.length} is not 48 + H ${H} + P ${P}`);
	const headerEnd = 48 + Number(H);
	let sum = fnv1a64(bytes.subarray(0, 32));
	sum = fnv1a64(bytes.subarray(48, headerEnd), sum);
	if (sum !== view.getBigUint64(32, true)) fail('header checksum mismatch');
	if (fnv1a64(bytes.subarray(headerEnd)) !== view.getBigUint64(40, true)) fail('payload checksum mismatch');

	const str = (r) => decoder.decode(bytes.subarray(r.at, r.at + r.len));
	const sized = (r, n, what) => { if (r.len !== n) fail(`${what}: field of ${r.len} bytes, expected ${n}`); return r.at; };
	const u32 = (r, what) => view.getUint32(sized(r, 4, what), true);
	const i32 = (r, what) => view.getInt32(sized(r, 4, what), true);
	const f64 = (r, what) => view.getFloat64(sized(r, 8, what), true);
	const u64 = (r, what) => view.getBigUint64(sized(r, 8, what), true);
	const newer = minor > FORMAT_MINOR; // a newer minor version may add tags: skip them
	const unknown = (what, tag) => { if (!newer) fail(`${what}: unknown tag ${tag}`); };

	const t = { formatVersion: `${major}.${minor}`, axes: [], channels: [], accuracy: {}, provenance: {}, extra: {} };
	for (const r of records(view, 48, headerEnd, name)) {
		switch (r.tag) {
		case 0x01: t.kind = str(r); break;
		case 0x02: t.quantityVersion = u32(r, 'quantity_version'); break;
		case 0x03: t.storage = STORAGE[u32(r, 'storage')] ?? fail('unknown storage id'); break;
		case 0x10: {
			const a = {};
			for (const f of records(view, r.at, r.at + r.len, 'axis')) {
				switch (f.tag) {
				case 1: a.name = str(f); break;
				case 2: a.meaning = str(f); break;
				case 3: a.min = f64(f, 'axis min'); break;
				case 4: a.max = f64(f, 'axis max'); break;
				case 5: a.scale = f64(f, 'axis scale'); break;
				case 6: a.warp = u32(f, 'axis warp'); break;
				case 7: a.count = i32(f, 'axis count'); break;
				default: unknown('axis', f.tag);
				}
			}
			a.warpName = WARP_NAMES[a.warp] ?? fail(`axis ${t.axes.length}: unknown warp id ${a.warp}`);
			if (!(a.count >= 2)) fail(`axis ${t.axes.length}: count ${a.count} is invalid`);
			t.axes.push(a);
			break;
		}
		case 0x11: {
			const c = {};
			for (const f of records(view, r.at, r.at + r.len, 'channel')) {
				if (f.tag === 1) c.name = str(f);
				else if (f.tag === 2) c.meaning = str(f);
				else if (f.tag === 3) c.encoding = ENCODING[u32(f, 'encoding')] ?? fail('unknown encoding id');
				else unknown('channel', f.tag);
			}
			t.channels.push(c);
			break;
		}
		case 0x20: {
			const names = [, 'integration_max_rel', 'sampling_max_rel', 'sampling_p99_rel', 'sampling_median_rel', 'storage_max_rel'];
			for (const f of records(view, r.at, r.at + r.len, 'accuracy')) {
				if (f.tag >= 1 && f.tag <= 5) t.accuracy[names[f.tag]] = f64(f, names[f.tag]);
				else if (f.tag === 6) t.accuracy.sampling_points = u64(f, 'sampling_points');
				else if (f.tag === 7) t.accuracy.sampling_domain = str(f);
				else unknown('accuracy', f.tag);
			}
			break;
		}
		case 0x21: {
			const names = [, 'generator_version', 'command_line', 'scene', 'device', 'created_by'];
			for (const f of records(view, r.at, r.at + r.len, 'provenance')) {
				if (f.tag >= 1 && f.tag <= 5) t.provenance[names[f.tag]] = str(f);
				else unknown('provenance', f.tag);
			}
			break;
		}
		case 0x30: {
			let key, value;
			for (const f of records(view, r.at, r.at + r.len, 'extra')) {
				if (f.tag === 1) key = str(f);
				else if (f.tag === 2) value = str(f);
				else unknown('extra', f.tag);
			}
			t.extra[key] = value;
			break;
		}
		default: unknown('header', r.tag);
		}
	}
	if (t.kind === undefined || t.storage === undefined || !t.axes.length || !t.channels.length)
		fail('header lacks kind, storage, axes or channels');
	const nodes = t.axes.reduce((n, a) => n * a.count, 1);
	const n = nodes * t.channels.length;
	const size = { f16: 2, f32: 4, f64: 8 }[t.storage];
	if (Number(P) !== n * size) fail(`payload is ${P} bytes, expected ${n} values of ${size} bytes`);
	t.values = new Float64Array(n);
	for (let i = 0, p = headerEnd; i < n; i++, p += size) {
		const v = size === 2 ? halfToNumber(view.getUint16(p, true)) : size === 4 ? view.getFloat32(p, true) : view.getFloat64(p, true);
		if (!Number.isFinite(v)) fail(`payload value ${i} is not finite`);
		t.values[i] = v;
	}
	return t;
}

// A real number stored as decimal text (docs/FORMAT.md §4.1): exact in JavaScript too.
function real(text, key) {
	if (typeof text !== 'string' || text.trim() !== text || text === '' || Number.isNaN(Number(text)) && text !== 'nan')
		throw new Error(`attribute '${key}' = '${text}' is not a decimal number`);
	return text === 'nan' ? NaN : text === 'inf' ? Infinity : text === '-inf' ? -Infinity : Number(text);
}

// Metadata from `scatterlut.*` key → value pairs, the values as strings or numbers (EXR
// int attributes come as numbers, text as strings; KTX2 values are all text).
function metadataFromPairs(get, container) {
	const need = (key) => {
		const v = get(key);
		if (v === undefined) throw new Error(`${container}: missing 'scatterlut.${key}'`);
		return v;
	};
	const int = (key) => {
		const v = Number(need(key));
		if (!Number.isInteger(v)) throw new Error(`${container}: 'scatterlut.${key}' is not an integer`);
		return v;
	};
	const m = {
		formatVersion: `${int('format_major')}.${int('format_minor')}`,
		kind: need('kind'), quantityVersion: int('quantity_version'), storage: need('storage'),
		layout: get('layout'), axes: [], channels: [],
	};
	for (let i = 0; i < int('axes'); i++) {
		const k = (f) => `axis.${i}.${f}`;
		m.axes.push({
			name: need(k('name')), meaning: need(k('meaning')),
			min: real(need(k('min')), k('min')), max: real(need(k('max')), k('max')), scale: real(need(k('scale')), k('scale')),
			warp: int(k('warp')), warpName: need(k('warp_name')), count: int(k('count')),
		});
	}
	for (let j = 0; j < int('channels'); j++) {
		const k = (f) => `channel.${j}.${f}`;
		m.channels.push({ name: need(k('name')), meaning: need(k('meaning')), encoding: need(k('encoding')),
			containerChannel: get(k('exr_channel')) });
	}
	return m;
}

// three.js EXRLoader: `texData.header` (attributes by name; strings and ints kept).
export function metadataFromExrHeader(header) {
	const m = metadataFromPairs((k) => header['scatterlut.' + k], 'EXR');
	const major = Number(m.formatVersion.split('.')[0]);
	if (major < 2) throw new Error(`EXR mapping ${m.formatVersion}: its reals are double attributes, which three.js skips; regenerate the table`);
	return m;
}

// KTX2 key/value data: values as ktx-parse gives them (Uint8Array, NUL-terminated UTF-8
// text) or as strings.
export function metadataFromKtx2KeyValue(keyValue) {
	const text = (v) => {
		if (v === undefined || typeof v === 'string') return v;
		const s = decoder.decode(v);
		return s.endsWith('\0') ? s.slice(0, -1) : s;
	};
	return metadataFromPairs((k) => text(keyValue['scatterlut.' + k]), 'KTX2');
}
