// A small static server for the web demo (no CDN, nothing but node):
//   node examples/web/serve.mjs [--tables DIR] [--shaders DIR] [--port N]
// serves this page, three.js from examples/web/node_modules, tests/js/slut.mjs, the tables
// (default out/, written by `scatterlut generate --format all --out out`) and the WebGL2
// snippets (default build/tables/shaders). Paths are resolved from the repository root.
//
// What it serves, and how it refuses the rest (issue #34; examples/web/serve_test.mjs sends
// the hostile requests):
//   - It listens on 127.0.0.1 only, and answers GET and HEAD; any other method gets 405 with
//     `Allow: GET, HEAD`. HEAD gets the headers of the GET, no body.
//   - A request-target longer than kMaxTarget characters gets 414. It must be origin-form
//     ("/path?query"); anything else ("*", "http://host/path") gets 400.
//   - The path (query and fragment cut off) is split at '/' BEFORE decoding, and each segment
//     is percent-decoded once. 400 (a request no browser sends, so a client error rather than
//     a missing file) for: a malformed escape (`%E0%A4%A`, `%zz`, invalid UTF-8), a NUL, a
//     segment that decodes to '.' or '..' (`..`, `%2e%2e`), a segment holding '/' or '\'
//     once decoded (`%2f`, `%5c`, a raw '\'). Empty segments ("//") are skipped. A
//     double-encoded segment (`%252e%252e`) decodes once to a literal name ("%2e%2e"),
//     which is looked up as such (404).
//   - The first segment picks the mount by equality, not by string prefix (so `tables_private`
//     is not under `tables`); the file is path.resolve(mount, ...rest), and path.relative
//     checks it is inside the mount. Then fs.realpath resolves every symlink of both, and the
//     real file must still be inside the mount's real directory: a symlink out of a mount is
//     404, as is anything missing; a file the server may not read is 403. (A symlinked mount
//     itself is fine: its real path is the reference.)
//   - Only regular files are served; a directory, FIFO, socket or device is 404, except '/',
//     which is index.html.
//   - No request stops the server: an exception in the handler becomes a 500 (logged on
//     stderr, never echoed to the client), and a request node's parser refuses (malformed
//     HTTP; a head over kMaxHeadBytes) gets 400 (431 for the size) on a closed connection.
//   - Error bodies are a fixed "404 Not Found" line in text/plain: nothing from the request
//     is echoed back.
import { createServer, STATUS_CODES } from 'node:http';
import { open, realpath, stat } from 'node:fs/promises';
import { constants } from 'node:fs';
import { resolve, relative, isAbsolute, join, extname, dirname, sep } from 'node:path';
import { fileURLToPath } from 'node:url';

const here = dirname(fileURLToPath(import.meta.url));
const root = resolve(here, '..', '..');
const MIME = { '.html': 'text/html', '.mjs': 'text/javascript', '.js': 'text/javascript', '.json': 'application/json',
	'.essl': 'text/plain', '.wgsl': 'text/plain', '.ktx2': 'application/octet-stream', '.wasm': 'application/wasm' };

// The longest request-target (path and query, in characters) the handler reads; longer: 414.
// Browsers send URLs of a few hundred characters; 4096 is PATH_MAX on Linux.
const kMaxTarget = 4096;
// The largest request head (request line and headers, in bytes) node's parser accepts; larger:
// 431 from the clientError handler. node's default (16 KiB) would answer a URL of 16-128 KiB
// with 431 before the handler sees it; 128 KiB lets the handler give such a URL its 414, and
// bounds what one connection can make the server hold.
const kMaxHeadBytes = 128 * 1024;
// Errors of the file system that mean "no such file here" (404): missing, a file used as a
// directory, a symlink loop, a name longer than the file system allows.
const kNotFoundCodes = new Set(['ENOENT', 'ENOTDIR', 'ELOOP', 'ENAMETOOLONG']);
// open(2) flags: O_NOFOLLOW refuses a final component swapped for a symlink after realpath
// looked at it; O_NONBLOCK keeps a FIFO from blocking the open. (Absent on Windows: 0.)
const kOpenFlags = constants.O_RDONLY | (constants.O_NOFOLLOW ?? 0) | (constants.O_NONBLOCK ?? 0);

// Whether `child` is `parent` or below it (both absolute): by path segments, not by string
// prefix, so /tmp/tables_private is not inside /tmp/tables.
function inside(parent, child) {
	const rel = relative(parent, child);
	return rel === '' || (rel !== '..' && !rel.startsWith('..' + sep) && !isAbsolute(rel));
}

// A status with a fixed one-line text body (node sends no body for HEAD).
function send(res, status, headers = {}) {
	const body = `${status} ${STATUS_CODES[status]}\n`;
	res.writeHead(status, { 'Content-Type': 'text/plain; charset=utf-8', 'Content-Length': Buffer.byteLength(body), ...headers });
	res.end(body);
}

// The request-target → its decoded path segments, or a status (400) if it is refused.
function segmentsOf(target) {
	if (!target.startsWith('/')) return 400; // "*" or absolute-form: not from a browser
	const path = target.split(/[?#]/, 1)[0];
	const segments = [];
	for (const raw of path.split('/')) { // split first: an encoded '/' stays inside its segment
		let s;
		try {
			s = decodeURIComponent(raw);
		} catch {
			return 400; // malformed escape or invalid UTF-8
		}
		if (s === '') continue;
		if (s === '.' || s === '..' || /[/\\\0]/.test(s)) return 400;
		segments.push(s);
	}
	return segments;
}

export function startServer({ tables = join(root, 'out'), shaders = join(root, 'build/tables/shaders'), port = 0 } = {}) {
	// First path segment → directory; a first segment that is none of these is looked up in
	// `here` (the page, fog.mjs, ...).
	const dirs = new Map([['three', join(here, 'node_modules/three')], ['tables', resolve(tables)], ['shaders', resolve(shaders)]]);
	// Path → one file.
	const files = new Map([['slut.mjs', join(root, 'tests/js/slut.mjs')]]);

	// The request's file → its real path, or a status if it cannot be served.
	async function locate(segments) {
		const [first, ...rest] = segments;
		if (segments.length === 1 && files.has(first)) return realpath(files.get(first));
		let base = here, names = segments.length ? segments : ['index.html'];
		if (dirs.has(first)) [base, names] = [dirs.get(first), rest];
		const file = resolve(base, ...names);
		if (!inside(base, file)) return 404; // cannot happen after segmentsOf's checks; kept as the rule
		const [realBase, realFile] = await Promise.all([realpath(base), realpath(file)]);
		return inside(realBase, realFile) ? realFile : 404; // a symlink out of the mount
	}

	async function handle(req, res) {
		if (req.method !== 'GET' && req.method !== 'HEAD') return send(res, 405, { Allow: 'GET, HEAD' });
		if (req.url.length > kMaxTarget) return send(res, 414);
		const segments = segmentsOf(req.url);
		if (typeof segments === 'number') return send(res, segments);
		let fh;
		try {
			const file = await locate(segments);
			if (typeof file === 'number') return send(res, file);
			// stat before open: opening a FIFO can block, opening a device can have side effects.
			if (!(await stat(file)).isFile()) return send(res, 404);
			fh = await open(file, kOpenFlags);
		} catch (e) {
			if (kNotFoundCodes.has(e.code)) return send(res, 404);
			if (e.code === 'EACCES' || e.code === 'EPERM') return send(res, 403);
			throw e; // → 500
		}
		try {
			const st = await fh.stat(); // the opened file, in case it changed since stat
			if (!st.isFile()) return send(res, 404);
			// The type from the name asked for (a symlink's target may be named otherwise).
			const type = MIME[extname(segments.at(-1) ?? 'index.html')] ?? 'application/octet-stream';
			if (req.method === 'HEAD') {
				res.writeHead(200, { 'Content-Type': type, 'Content-Length': st.size });
				return res.end();
			}
			const body = await fh.readFile();
			res.writeHead(200, { 'Content-Type': type, 'Content-Length': body.length });
			res.end(body);
		} finally {
			await fh.close();
		}
	}

	const server = createServer({ maxHeaderSize: kMaxHeadBytes }, (req, res) => {
		handle(req, res).catch((err) => {
			console.error(`serve.mjs: internal error on ${req.method} ${req.url.slice(0, 200)}:`, err);
			try {
				if (res.headersSent) res.destroy(); // a half-sent body cannot be turned into a 500
				else send(res, 500, { Connection: 'close' });
			} catch {
				res.destroy();
			}
		});
	});
	// node's parser refused the request (malformed HTTP, a head over kMaxHeadBytes, a header
	// timeout): answer it and close, unless a response is already under way on this connection
	// (then only close: a status line in the middle of it would corrupt it). node may report
	// several errors for one connection (each further chunk): answer once.
	server.on('clientError', (err, socket) => {
		if (socket.writableEnded) return;
		if (err.code === 'ECONNRESET' || !socket.writable || socket._httpMessage?.headersSent) return socket.destroy();
		const status = err.code === 'HPE_HEADER_OVERFLOW' ? 431 : err.code === 'ERR_HTTP_REQUEST_TIMEOUT' ? 408 : 400;
		const body = `${status} ${STATUS_CODES[status]}\n`;
		socket.end(`HTTP/1.1 ${status} ${STATUS_CODES[status]}\r\nConnection: close\r\nContent-Type: text/plain; charset=utf-8\r\n` +
			`Content-Length: ${body.length}\r\n\r\n${body}`, () => socket.destroy());
	});
	return new Promise((ok, fail) => {
		server.once('error', fail); // e.g. the port is taken
		server.listen(port, '127.0.0.1', () => {
			server.off('error', fail);
			ok(server);
		});
	});
}

if (process.argv[1] === fileURLToPath(import.meta.url)) {
	const arg = (name, fallback) => {
		const i = process.argv.indexOf(name);
		return i > 0 ? process.argv[i + 1] : fallback;
	};
	const server = await startServer({ tables: arg('--tables'), shaders: arg('--shaders'), port: Number(arg('--port', 8080)) });
	console.log(`fog street: http://127.0.0.1:${server.address().port}/  (Ctrl-C to stop)`);
}
