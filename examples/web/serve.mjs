// A small static server for the web demo (no CDN, nothing but node):
//   node examples/web/serve.mjs [--tables DIR] [--shaders DIR] [--port N]
// serves this page, three.js from examples/web/node_modules, tests/js/slut.mjs, the tables
// (default out/, written by `scatterlut generate --format all --out out`) and the WebGL2
// snippets (default build/tables/shaders). Paths are resolved from the repository root.
import { createServer } from 'node:http';
import { readFile } from 'node:fs/promises';
import { resolve, join, normalize, extname, dirname } from 'node:path';
import { fileURLToPath } from 'node:url';

const here = dirname(fileURLToPath(import.meta.url));
const root = resolve(here, '..', '..');
const MIME = { '.html': 'text/html', '.mjs': 'text/javascript', '.js': 'text/javascript', '.json': 'application/json',
	'.essl': 'text/plain', '.ktx2': 'application/octet-stream', '.wasm': 'application/wasm' };

export function startServer({ tables = join(root, 'out'), shaders = join(root, 'build/tables/shaders'), port = 0 } = {}) {
	const mounts = [ // URL prefix → directory
		['/three/', join(here, 'node_modules/three')], ['/tables/', resolve(tables)], ['/shaders/', resolve(shaders)],
		['/slut.mjs', join(root, 'tests/js/slut.mjs')], ['/', here],
	];
	const server = createServer(async (req, res) => {
		const path = decodeURIComponent(new URL(req.url, 'http://x').pathname);
		for (const [prefix, dir] of mounts) {
			if (!path.startsWith(prefix)) continue;
			const rest = path === '/' ? 'index.html' : path.slice(prefix.length);
			const file = prefix.endsWith('/') ? normalize(join(dir, rest)) : dir;
			if (!file.startsWith(dir)) break; // no way out of the mounted directory
			try {
				const body = await readFile(file);
				res.writeHead(200, { 'Content-Type': MIME[extname(file)] ?? 'application/octet-stream' });
				res.end(body);
			} catch {
				res.writeHead(404).end(`not found: ${path}`);
			}
			return;
		}
		res.writeHead(404).end(`not found: ${path}`);
	});
	return new Promise((ok) => server.listen(port, '127.0.0.1', () => ok(server)));
}

if (process.argv[1] === fileURLToPath(import.meta.url)) {
	const arg = (name, fallback) => {
		const i = process.argv.indexOf(name);
		return i > 0 ? process.argv[i + 1] : fallback;
	};
	const server = await startServer({ tables: arg('--tables'), shaders: arg('--shaders'), port: Number(arg('--port', 8080)) });
	console.log(`fog street: http://127.0.0.1:${server.address().port}/  (Ctrl-C to stop)`);
}
