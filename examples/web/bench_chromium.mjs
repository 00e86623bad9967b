// What the SwiftShader benches (bench_airlight.mjs, bench_compile.mjs) share: their command
// line, headless Chromium with SwiftShader's WebGL2 (ANGLE on SwiftShader's Vulkan, as the
// web demo's test runs it) and the median. Not a test: the benches exit 77 without Chromium or
// the npm modules (npm ci in examples/web).
import { existsSync, readdirSync, readFileSync } from 'node:fs';

// The command line: `valued` options take the next argument, `flags` none; intOption checks a
// range and exits 2 with the usage on anything else, as does an unknown option.
export function parseArgs(argv, valued, flags, usage, tool) {
	const opt = (name, fallback) => { const i = argv.indexOf(name); return i >= 0 ? argv[i + 1] : fallback; };
	const positional = argv.filter((a, i) => !a.startsWith('--') && !(i > 0 && valued.includes(argv[i - 1])));
	function intOption(name, fallback, lo, hi) {
		const text = opt(name, String(fallback)), v = Number(text);
		if (!Number.isInteger(v) || v < lo || v > hi) {
			console.error(`${tool}: ${name} ${text}: expected an integer in [${lo}, ${hi}]\n${usage}`);
			process.exit(2);
		}
		return v;
	}
	for (const a of argv)
		if (a.startsWith('--') && !valued.includes(a) && !flags.includes(a)) { console.error(`${tool}: unknown option ${a}\n${usage}`); process.exit(2); }
	return { opt, flag: (name) => argv.includes(name), positional, intOption };
}

// Headless Chromium on SwiftShader (the flags of browser_test.mjs), or exit 77 without it.
// DevTools calls wait while SwiftShader compiles a shader: protocolTimeout covers the longest.
export async function launchSwiftShader(chromiumOption) {
	const chromium = chromiumOption ?? ['/usr/bin/chromium', '/usr/bin/chromium-browser'].find((p) => existsSync(p));
	if (!chromium) { console.log('skipped: chromium not found'); process.exit(77); }
	let puppeteer;
	try {
		puppeteer = (await import('puppeteer-core')).default;
	} catch (e) {
		console.log(`skipped: npm modules missing (npm ci in examples/web): ${e.message}`);
		process.exit(77);
	}
	return puppeteer.launch({
		executablePath: chromium, headless: true,
		args: ['--headless=new', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--no-sandbox',
			'--disable-gpu-sandbox', '--disable-gpu-shader-disk-cache'],
		protocolTimeout: 1800000,
	});
}

// A page on about:blank whose console lines go to stderr with the seconds since it opened.
export async function blankPage(browser) {
	const page = await browser.newPage();
	const start = Date.now();
	page.on('console', (m) => console.error(`[${((Date.now() - start) / 1000).toFixed(1)} s] ${m.text()}`));
	await page.goto('about:blank');
	return page;
}

// CPU seconds (user + system) the browser's GPU process has used so far, where ANGLE
// translates and SwiftShader compiles and draws: on a loaded machine a steadier measure of the
// work than the wall clock. Linux (/proc); undefined elsewhere.
export function gpuProcessCpuSeconds(browser) {
	const root = browser.process()?.pid;
	if (!root || !existsSync('/proc/self/stat')) return undefined;
	for (const entry of readdirSync('/proc')) {
		if (!/^[0-9]+$/.test(entry)) continue;
		let stat, cmdline;
		try {
			stat = readFileSync(`/proc/${entry}/stat`, 'latin1');
			cmdline = readFileSync(`/proc/${entry}/cmdline`, 'latin1');
		} catch { continue; }
		const fields = stat.slice(stat.lastIndexOf(')') + 2).split(' '); // from field 3 (state) on
		if (Number(fields[1]) !== root || !cmdline.includes('--type=gpu-process')) continue;
		return (Number(fields[11]) + Number(fields[12])) / clockTicksPerSecond;
	}
	return undefined;
}
const clockTicksPerSecond = 100; // USER_HZ, 100 on every Linux ABI Chromium runs on

export const median = (a) => { const s = [...a].sort((x, y) => x - y); return s[Math.floor(s.length / 2)]; };
