// The web demo's static server (serve.mjs) against hostile requests (issue #34):
//   node --test examples/web/serve_test.mjs          (CTest: WebDemoServerHostile, label js)
// Only node (>= 18) and its built-in modules: no npm modules, no browser.
//
// It makes a temporary tree under os.tmpdir():
//   tables/                 mounted as /tables/: airlight_F.ktx2, alias.ktx2 (a symlink to it),
//                           escape (a symlink to ../tables_private), secret_link.txt (a
//                           symlink to ../tables_private/secret.txt), sub/ (a directory),
//                           fifo (a named pipe, where mkfifo exists)
//   tables_private/         beside the mount, sharing its name as a prefix: secret.txt
//   shaders/                mounted as /shaders/: scatterlut_airlight.essl
// starts the server on port 0 and sends every request over a raw TCP socket (so no client
// normalises the path: "..", "%2e", "\" reach the server as written), one connection each
// ("Connection: close", read to the end). Each case checks the status code and that no
// response (status line, headers, body) holds the secret's text; the last cases check the
// server still serves its files.
import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import net from 'node:net';
import { mkdtempSync, mkdirSync, writeFileSync, readFileSync, symlinkSync, rmSync } from 'node:fs';
import fsp from 'node:fs/promises';
import { syncBuiltinESMExports } from 'node:module';
import { execFileSync } from 'node:child_process';
import { tmpdir } from 'node:os';
import { join, dirname } from 'node:path';
import { fileURLToPath } from 'node:url';
import { randomUUID, randomBytes } from 'node:crypto';
import { startServer } from './serve.mjs';

const here = dirname(fileURLToPath(import.meta.url));
const secret = `SECRET-${randomUUID()}`; // the private file's text: must never come back
let tmp, server, port, table, hasFifo = false;
let responses = 0; // responses read, all checked for the secret

before(async () => {
	tmp = mkdtempSync(join(tmpdir(), 'slut-serve-'));
	const tables = join(tmp, 'tables'), priv = join(tmp, 'tables_private'), shaders = join(tmp, 'shaders');
	for (const d of [tables, priv, shaders, join(tables, 'sub')]) mkdirSync(d);
	writeFileSync(join(priv, 'secret.txt'), secret);
	writeFileSync(join(priv, 'airlight_F.ktx2'), secret);
	table = randomBytes(3000);
	writeFileSync(join(tables, 'airlight_F.ktx2'), table);
	writeFileSync(join(shaders, 'scatterlut_airlight.essl'), '// a snippet\n');
	symlinkSync('airlight_F.ktx2', join(tables, 'alias.ktx2')); // inside the mount: served
	symlinkSync(priv, join(tables, 'escape')); // out of the mount (a directory)
	symlinkSync(join(priv, 'secret.txt'), join(tables, 'secret_link.txt')); // out of the mount (a file)
	try {
		execFileSync('mkfifo', [join(tables, 'fifo')], { stdio: 'ignore' });
		hasFifo = true;
	} catch { /* no mkfifo (not POSIX): that case is skipped */ }
	server = await startServer({ tables, shaders, port: 0 });
	port = server.address().port;
});

after(() => {
	server?.closeAllConnections?.();
	server?.close();
	if (tmp) rmSync(tmp, { recursive: true, force: true });
});

// Bytes → the server, over a fresh connection; resolves with the parsed response once the
// server closes it. A reset after the response still yields what arrived.
function exchange(bytes) {
	return new Promise((ok, fail) => {
		const socket = net.connect(port, '127.0.0.1');
		const chunks = [];
		socket.setTimeout(20000, () => { socket.destroy(); fail(new Error('no answer within 20 s')); });
		socket.on('data', (c) => chunks.push(c));
		socket.on('error', () => {}); // e.g. ECONNRESET: judged on what arrived, at 'close'
		socket.on('close', () => {
			const all = Buffer.concat(chunks), text = all.toString('latin1');
			responses++;
			// The secret must appear nowhere: status line, headers or body.
			if (text.includes(secret)) return fail(new Error(`the secret came back:\n${text.slice(0, 500)}`));
			const end = all.indexOf('\r\n\r\n');
			if (end < 0) return fail(new Error(`no complete response (${all.length} bytes): ${JSON.stringify(text.slice(0, 200))}`));
			const [statusLine, ...lines] = all.subarray(0, end).toString('latin1').split('\r\n');
			const status = Number(/^HTTP\/1\.[01] (\d{3}) /.exec(statusLine)?.[1]);
			const headers = Object.fromEntries(lines.map((l) => [l.slice(0, l.indexOf(':')).toLowerCase(), l.slice(l.indexOf(':') + 1).trim()]));
			ok({ status, headers, body: all.subarray(end + 4) });
		});
		socket.write(bytes);
	});
}

// One request: METHOD target HTTP/1.1, Host, Connection: close, and `extra` (header lines).
const request = (method, target, extra = '') =>
	exchange(Buffer.from(`${method} ${target} HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n${extra}\r\n`, 'latin1'));

const shown = (s) => (s.length > 70 ? `${s.slice(0, 40)}... (${s.length} chars)` : s);

// --- the legitimate requests, one per kind of mount ---------------------------------------
async function expectFile(target, bytes, type) {
	const r = await request('GET', target);
	assert.equal(r.status, 200);
	assert.equal(r.headers['content-type'], type);
	assert.equal(Number(r.headers['content-length']), bytes.length);
	assert.ok(r.body.equals(bytes), 'the body is the file');
}
const legit = [
	['/ → index.html', () => expectFile('/', readFileSync(join(here, 'index.html')), 'text/html')],
	['/index.html', () => expectFile('/index.html', readFileSync(join(here, 'index.html')), 'text/html')],
	['/slut.mjs (one file)', () => expectFile('/slut.mjs', readFileSync(join(here, '../../tests/js/slut.mjs')), 'text/javascript')],
	['/tables/airlight_F.ktx2', () => expectFile('/tables/airlight_F.ktx2', table, 'application/octet-stream')],
	['/tables/airlight_F.ktx2?v=1 (a query is ignored)', () => expectFile('/tables/airlight_F.ktx2?v=1', table, 'application/octet-stream')],
	['/tables/alias.ktx2 (a symlink inside the mount)', () => expectFile('/tables/alias.ktx2', table, 'application/octet-stream')],
	['/tables/airlight%5FF.ktx2 (an encoded ordinary character)', () => expectFile('/tables/airlight%5FF.ktx2', table, 'application/octet-stream')],
	['/shaders/scatterlut_airlight.essl', () => expectFile('/shaders/scatterlut_airlight.essl', Buffer.from('// a snippet\n'), 'text/plain')],
	['HEAD /tables/airlight_F.ktx2: the headers, no body', async () => {
		const r = await request('HEAD', '/tables/airlight_F.ktx2');
		assert.equal(r.status, 200);
		assert.equal(Number(r.headers['content-length']), table.length);
		assert.equal(r.body.length, 0);
	}],
];
for (const [name, check] of legit) test(`legit: ${name}`, check);

// --- hostile requests: [method, target, status, why] -------------------------------------
// 400: a request no browser sends (dot segments, encoded separators, NUL, bad escapes);
// 404: nothing servable there (or a way out of a mount, which must look like nothing).
const secretPath = 'tables_private/secret.txt';
const hostile = [
	['GET', `/tables/../${secretPath}`, 400, '".." segment'],
	['GET', `/tables/./../${secretPath}`, 400, '"." segment'],
	['GET', '/shaders/../../../../../../etc/passwd', 400, '".." segments'],
	['GET', `/tables/%2e%2e/${secretPath}`, 400, 'encoded dots'],
	['GET', `/tables/%2E%2E/${secretPath}`, 400, 'encoded dots, upper case'],
	['GET', `/tables/.%2e/${secretPath}`, 400, 'half-encoded dots'],
	['GET', `/tables/..%2F${secretPath.replace('/', '%2F')}`, 400, 'encoded "/"'],
	['GET', `/tables%2F..%2F${secretPath.replace('/', '%2F')}`, 400, 'encoded "/" in the mount segment'],
	['GET', `/tables/..%5C${secretPath.replace('/', '%5C')}`, 400, 'encoded "\\"'],
	['GET', `/tables/..\\${secretPath.replace('/', '\\')}`, 400, 'raw "\\"'],
	['GET', `/tables/%252e%252e/${secretPath}`, 404, 'double-encoded dots: a literal "%2e%2e"'],
	['GET', `/tables/%252e%252e%252f${secretPath.replace('/', '%252f')}`, 404, 'double-encoded dots and "/"'],
	['GET', '/tables/%C0%AE%C0%AE/tables_private/secret.txt', 400, 'overlong UTF-8 dots'],
	['GET', '/tables/secret.txt%00.ktx2', 400, 'NUL'],
	['GET', '/tables/airlight_F.ktx2%00', 400, 'NUL after a real file'],
	['GET', `/${'a'.repeat(100000)}`, 414, 'a 100 000-character path'],
	['GET', `/tables/${'a'.repeat(300)}`, 404, 'a name longer than the file system allows (ENAMETOOLONG)'],
	['GET', '/%E0%A4%A', 400, 'malformed escape (truncated)'],
	['GET', '/tables/%', 400, 'malformed escape (bare %)'],
	['GET', '/tables/%zz', 400, 'malformed escape (not hex)'],
	['GET', '/tables/%FF', 400, 'escape of invalid UTF-8'],
	['GET', `/${secretPath}`, 404, 'the sibling directory sharing the mount\'s prefix'],
	['GET', `//${secretPath}`, 404, 'the sibling directory, empty segment first'],
	['GET', '/tables_private/airlight_F.ktx2', 404, 'the sibling directory, a table\'s name'],
	['GET', '/tables/escape/secret.txt', 404, 'a directory symlink out of the mount'],
	['GET', '/tables/secret_link.txt', 404, 'a file symlink out of the mount'],
	['GET', '/tables/', 404, 'a directory'],
	['GET', '/tables/sub', 404, 'a directory'],
	['GET', '/tables/missing.ktx2', 404, 'a missing file'],
	['GET', '/slut.mjs/x', 404, 'below a one-file mount'],
	['GET', `http://127.0.0.1/tables/../${secretPath}`, 400, 'absolute-form target'],
	['GET', '*', 400, 'asterisk-form target'],
	['POST', '/index.html', 405, 'POST'],
	['PUT', '/tables/airlight_F.ktx2', 405, 'PUT'],
	['DELETE', '/tables/airlight_F.ktx2', 405, 'DELETE'],
	['POST', `/tables/../${secretPath}`, 405, 'POST with ".."'],
	['OPTIONS', '*', 405, 'OPTIONS'],
];
for (const [method, target, status, why] of hostile) {
	test(`hostile: ${method} ${shown(target)} → ${status} (${why})`, async () => {
		const r = await request(method, target, method === 'POST' || method === 'PUT' ? `Content-Length: ${secret.length}\r\n` : '');
		assert.equal(r.status, status);
		if (status === 405) assert.equal(r.headers.allow, 'GET, HEAD');
	});
}
test('hostile: GET /tables/fifo → 404 (a named pipe: not a regular file, and no hang)', { skip: !hasFifo && 'no mkfifo' }, async () => {
	assert.equal((await request('GET', '/tables/fifo')).status, 404);
});

// Requests node's HTTP parser refuses: the clientError handler answers them.
const malformed = [
	['a version that is not HTTP', 'GET / FOO/1.1\r\nHost: x\r\n\r\n', 400],
	['a Content-Length that is not a number', 'GET / HTTP/1.1\r\nHost: x\r\nContent-Length: abc\r\n\r\n', 400],
	['both Content-Length and chunked (smuggling)', 'POST / HTTP/1.1\r\nHost: x\r\nContent-Length: 3\r\nTransfer-Encoding: chunked\r\n\r\n0\r\n\r\n', 400],
	['binary garbage', '\x00\x01\x02\xff garbage\r\n\r\n', 400],
	['a header line without a colon', 'GET / HTTP/1.1\r\nHost: x\r\nno colon here\r\n\r\n', 400],
	['a control character in the target', 'GET /tables/a\x01b HTTP/1.1\r\nHost: x\r\n\r\n', 400],
	['a head over the 128 KiB limit', `GET / HTTP/1.1\r\nHost: x\r\nX-Big: ${'b'.repeat(140 * 1024)}\r\n\r\n`, 431],
];
for (const [name, bytes, status] of malformed) {
	test(`malformed HTTP: ${name} → ${status}`, async () => {
		assert.equal((await exchange(Buffer.from(bytes, 'latin1'))).status, status);
	});
}

test('all the hostile requests at once, then still serving', async () => {
	const rs = await Promise.all(hostile.map(([method, target]) => request(method, target)));
	assert.deepEqual(rs.map((r) => r.status), hostile.map(([, , status]) => status));
	await expectFile('/tables/airlight_F.ktx2', table, 'application/octet-stream');
});

// An exception inside the handler (here: fs.realpath made to throw, through node's own hook
// for patching built-in modules' ESM exports) is a 500 with no detail, and the server lives on.
test('an exception in the handler → 500, then still serving', async () => {
	const realpath = fsp.realpath;
	fsp.realpath = async () => { throw new Error(`injected failure ${secret}`); };
	syncBuiltinESMExports();
	const logged = console.error;
	console.error = () => {}; // the server logs it on stderr; keep the test's output clean
	try {
		const r = await request('GET', '/tables/airlight_F.ktx2');
		assert.equal(r.status, 500); // exchange() also checks the error's text did not come back
	} finally {
		fsp.realpath = realpath;
		syncBuiltinESMExports();
		console.error = logged;
	}
	await expectFile('/tables/airlight_F.ktx2', table, 'application/octet-stream');
});

test('after everything: the server still serves each kind of mount', async (t) => {
	for (const [, check] of legit) await check();
	assert.ok(responses > hostile.length * 2);
	t.diagnostic(`${responses} responses read, none with the secret`);
});
