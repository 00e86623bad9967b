#!/usr/bin/env python3
"""Unit tests of the WGSL translator (tables/shaders/wgsl/slut_wgsl.py) on small inputs: what it
writes for each construct of the shared subset, and that it refuses, with a message, every
construct it does not handle. With SLUT_WGSL_SHADER_DIR set (CTest: the build's
tables/shaders), also checks the generated snippets: ASCII, no placeholder left, one shared part
per tier, the accurate tier equal to the file without a tier where the .slsl says so.

  SLUT_WGSL_CPP="c++ -E -x c" python3 tests/shaders/test_slut_wgsl.py [-v]
(the C preprocessor: SLUT_WGSL_CPP, default "cpp").
"""
import glob
import os
import re
import subprocess
import sys
import tempfile
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(ROOT, 'tables', 'shaders', 'wgsl'))
import slut_wgsl  # noqa: E402

CPP = os.environ.get('SLUT_WGSL_CPP', 'cpp')
PRELUDE = open(os.path.join(ROOT, 'tables', 'shaders', 'src', 'prelude.wgsl.h'), encoding='utf-8').read()


def wgsl(src, defines=(), prelude=False):
    """The WGSL of a small GLSL-subset source (all its declarations, joined)."""
    _, decls = slut_wgsl.translate_text((PRELUDE if prelude else '') + src, CPP, defines)
    return '\n'.join(text for _, text in decls)


def squash(text):
    return re.sub(r'\s+', ' ', text).strip()


class Translates(unittest.TestCase):
    def has(self, src, *expected, **kw):
        out = squash(wgsl(src, **kw))
        for e in expected:
            self.assertIn(squash(e), out, msg='\n--- source:\n%s\n--- WGSL:\n%s' % (src, wgsl(src, **kw)))
        return out

    def test_types_and_functions(self):
        self.has('float f(int i, bool b, uint u) { return b ? float(i) : float(u); }',
                 'fn f(i: i32, b: bool, u: u32) -> f32 {', 'return select(f32(u), f32(i), b);')
        self.has('vec3 f(vec3 a, ivec2 b) { return a * float(b.x) + vec3(1.0, 2.0, 3.0); }',
                 'fn f(a: vec3<f32>, b: vec2<i32>) -> vec3<f32> {',
                 'return a * f32(b.x) + vec3<f32>(1.0, 2.0, 3.0);')

    def test_structs_by_value(self):
        self.has('struct S { float a; int n; }; S make(float a) { S s; s.a = a; s.n = 2; return s; }',
                 'struct S { a: f32, n: i32, }', 'fn make(a: f32) -> S {', 'var s: S;', 's.a = a;', 's.n = 2;')

    def test_out_parameters_become_pointers(self):
        self.has('void f(float x, out float s, inout int n) { s = x; n += 1; }\n'
                 'float g() { float s; int n = 0; f(2.0, s, n); return s; }',
                 'fn f(x: f32, s: ptr<function, f32>, n: ptr<function, i32>) {', '*s = x;', '*n += 1;',
                 'f(2.0, &s, &n);')
        # an out parameter passed on is the pointer itself; read as (*p)
        self.has('void f(out float s) { s = 1.0; } void g(out float t) { f(t); t = t * 2.0; }',
                 'fn g(t: ptr<function, f32>) {', 'f(t);', '*t = (*t) * 2.0;')

    def test_out_array_parameter(self):
        self.has('void f(out float c[3]) { for (int k = 0; k < 3; ++k) c[k] = float(k); }\n'
                 'float g() { float c[3]; f(c); return c[1]; }',
                 'fn f(c: ptr<function, array<f32, 3>>) {', 'for (var k: i32 = 0; k < 3; k++) {',
                 '(*c)[k] = f32(k);', 'var c: array<f32, 3>;', 'f(&c);')

    def test_assigned_parameter_is_copied(self):
        self.has('float f(float x) { x = x * 2.0; return x; }',
                 'fn f(x_in: f32) -> f32 {', 'var x: f32 = x_in;', 'x = x * 2.0;')

    def test_const_arrays(self):
        self.has('const float w[3] = {1.0, 2.0, 3.0}; float f(int k) { return w[k]; }',
                 'const w: array<f32, 3> = array<f32, 3>(1.0, 2.0, 3.0);', 'return w[k];')
        self.has(PRELUDE + 'SLUT_CONST_ARRAY4(v, 1.0, 2.0, 3.0, 4.0); float f() { return v[2]; }',
                 'const v: array<f32, 4> = array<f32, 4>(1.0, 2.0, 3.0, 4.0);')

    def test_ternaries(self):
        # scalars without calls: select(false, true, cond)
        self.has('float f(float x) { return x > 0.0 ? x : -x; }', 'return select(-x, x, x > 0.0);')
        # a branch that calls a function: if/else (select would evaluate both)
        self.has('float g(float x) { return x; } float f(float x) { float y = x > 0.0 ? g(x) : 0.0; return y; }',
                 'var y: f32;', 'if (x > 0.0) { y = g(x); } else { y = 0.0; }')
        self.has('float g(float x) { return x; } float f(float x) { return x > 0.0 ? g(x) : 1.0; }',
                 'if (x > 0.0) { return g(x); } else { return 1.0; }')
        # a struct value inside an argument: hoisted into a temporary
        self.has('struct S { float a; }; float h(S s) { return s.a; }\n'
                 'float f(S a, S b, int w) { return h(w == 0 ? a : b); }',
                 'var slut_wgsl_sel_0: S;', 'if (w == 0) { slut_wgsl_sel_0 = a; } else { slut_wgsl_sel_0 = b; }',
                 'return h(slut_wgsl_sel_0);')
        # nested scalar ?: inside a branch of a call ?:
        self.has('float g(float x) { return x; }\n'
                 'float f(float x) { float y = x > 0.0 ? g(x) : (x < -1.0 ? 2.0 : 3.0); return y; }',
                 'y = select(3.0, 2.0, x < -1.0);')

    def test_precedence(self):
        self.has('float f(float a, float b, float c) { return a - (b - c); }', 'return a - (b - c);')
        self.has('float f(float a, float b, float c) { return (a + b) * c; }', 'return (a + b) * c;')
        self.has('float f(float a, float b, float c) { return a / (b * c); }', 'return a / (b * c);')
        self.has('bool f(bool a, bool b, bool c) { return a && (b || c); }', 'return a && (b || c);')
        self.has('bool f(bool a, bool b, bool c) { return a && b || c; }', 'return (a && b) || c;')
        self.has('bool f(int k) { return (k & 1) != 0; }', 'return (k & 1) != 0;')
        self.has('float f(float x) { return -(-x); }', 'return -(-x);')
        self.has('bool f(float x) { return !(x > 0.0); }', 'return !(x > 0.0);')
        self.has('float f(vec3 a, vec3 b) { return (a + b).x; }', 'return (a + b).x;')

    def test_statements(self):
        self.has('float f(int n) { float s = 0.0; for (int i = 0; i < n; i += 2) { if (i == 4) continue; '
                 'if (s > 9.0) break; s += 1.0; } return s; }',
                 'for (var i: i32 = 0; i < n; i += 2) {', 'if (i == 4) { continue; }', 'if (s > 9.0) { break; }')
        self.has('float f(float x) { while (x > 1.0) x = x * 0.5; return x; }',
                 'while (x_in > 1.0)'.replace('x_in', 'x'), 'x = x * 0.5;')
        self.has('float f(float x) { float y = x; y++; return y; }', 'y += 1.0;')
        self.has('int f(int x) { int y = x; y--; return y; }', 'y--;')
        self.has('float f(float x) { if (x > 0.0) return 1.0; else if (x < 0.0) return -1.0; else return 0.0; }',
                 'if (x > 0.0) { return 1.0; } else { if (x < 0.0) { return -1.0; } else { return 0.0; } }')

    def test_unreachable_code_is_dropped(self):
        out = self.has('float f(float x) { return x; float y = 2.0; return y; }', 'return x;')
        self.assertNotIn('y', out)

    def test_vectors(self):
        self.has('vec3 f(vec3 s) { vec3 L = vec3(0.0, 0.0, 0.0); for (int c = 0; c < 3; ++c) L[c] = s[c] * 2.0; '
                 'L.x = 1.0; return L; }', 'L[c] = s[c] * 2.0;', 'L.x = 1.0;')
        self.has('float f(vec3 a, vec3 b) { return length(cross(a, b)) + dot(a, b); }',
                 'return length(cross(a, b)) + dot(a, b);')

    def test_builtins(self):
        self.has('float f(float y, float x) { return atan(y, x) + atan(y) + inversesqrt(x); }',
                 'return atan2(y, x) + atan(y) + inverseSqrt(x);')
        self.has('float f(float x) { return clamp(abs(x), 0.0, 1.0) + max(min(x, 2.0), 1.0) + sqrt(exp(log(x))); }',
                 'clamp(abs(x), 0.0, 1.0) + max(min(x, 2.0), 1.0) + sqrt(exp(log(x)))')

    def test_reserved_words_are_renamed(self):
        self.has('struct S { float filter; float min; }; float f(S s) { float target = s.filter + s.min; '
                 'float length = target; return length; }',
                 'filter_: f32,', 'min: f32,', 'var target_: f32 = s.filter_ + s.min;', 'var length_: f32 = target_;')

    def test_literals(self):
        self.has('float f() { return 3.40282347e38; }', 'return 3.4028234663852886e+38;')
        self.has('uint f() { return 0x7F800000u; }', 'return 0x7F800000u;')
        self.has('float f() { return 1.0f + .5 + 2. + 1e-3; }', 'return 1.0 + .5 + 2. + 1e-3;')

    def test_textures(self):
        src = ('float f(SLUT_TEX2D_PARAM(t), int i, float x) { return SLUT_TEXEL2D(t, i, i + 1) + '
               'SLUT_TEXTURE_SIZE2D(t).x; }\n'
               'float g(SLUT_TEX3D_PARAM(t), float x) { return SLUT_FILTER3D(t, x, x, x); }\n')
        self.has(PRELUDE + src.replace('float g', '// float g').split('\n')[0] + '\n',
                 'fn f(t: texture_2d<f32>, i: i32, x: f32) -> f32 {',
                 'return textureLoad(t, vec2<i32>(i, i + 1), 0).r + vec2<f32>(textureDimensions(t, 0)).x;')
        self.has(PRELUDE + src, 'fn g(t: texture_3d<f32>, t_sampler: sampler, x: f32) -> f32 {',
                 'return textureSampleLevel(t, t_sampler, vec3<f32>(x, x, x), 0.0).r;', defines=['SLUT_TIER_FAST'])
        self.has(PRELUDE + 'float f() { return slut_inf(); }', 'var<private> slut_wgsl_inf_bits: u32 = 0x7F800000u;',
                 'return bitcast<f32>(slut_wgsl_inf_bits);')


class Refuses(unittest.TestCase):
    def refuses(self, src, *words):
        with self.assertRaises(slut_wgsl.TranslateError, msg=src) as cm:
            wgsl(src)
        for w in words:
            self.assertIn(w, str(cm.exception), msg='message for %r: %s' % (src, cm.exception))
        return str(cm.exception)

    def test_statements(self):
        self.refuses('float f(int k) { switch (k) { case 0: return 1.0; } return 0.0; }', 'switch')
        self.refuses('float f(float x) { do { x = x * 0.5; } while (x > 1.0); return x; }', 'do-while')
        self.refuses('float f(float x) { goto end; end: return x; }', 'goto')
        self.refuses('float f(float x) { if (x > 0.0) return 1.0; }', 'may end without returning')
        self.refuses('float f(int n) { for (int i = 0, j = 0; i < n; ++i) {} return 1.0; }', 'several declarations')
        self.refuses('float f(float x) { x; return x; }', 'unsupported statement')

    def test_pointers_and_casts(self):
        self.refuses('float f(float *p) { return 1.0; }', 'pointer')
        self.refuses('float g(float x) { return x; } float f(float x) { return g(*(&x)); }', 'pointer')
        self.refuses('void g(out float s) { s = 1.0; } float f(float x) { g(&x); return x; }', 'not a variable')
        self.refuses('float f(int i) { return (float)i; }', 'C cast')
        self.refuses('struct S { float a; }; float f(S s) { return s->a; }', "'->'")

    def test_expressions(self):
        self.refuses('float f(float a, float b) { return (a, b); }', 'comma')
        self.refuses('float f(float a, float b) { float c; c = a = b; return c; }', 'assignment inside an expression')
        self.refuses('int f(int i) { int j = i++; return j; }', '++/--')
        self.refuses('vec3 f(vec3 v) { v.xy = vec2(1.0, 2.0); return v; }', 'swizzle')
        self.refuses('float f(float x) { return mystery(x); }', "call to 'mystery'", 'in f()')
        self.refuses('float f(float x) { return y; }', "undeclared identifier 'y'")
        self.refuses('float f(float x) { return mod(x, 2.0); }', 'mod')
        self.refuses('float f(float x) { return round(x); }', 'round')
        self.refuses('bool f(float x) { return isnan(x); }', 'isnan')
        self.refuses('float f(int i) { if (i) return 1.0; return 0.0; }', 'condition')
        self.refuses('float f(int i, float x) { return float(i) + i * x; }', 'converts nothing')
        self.refuses('float f(float x) { return x % 2.0; }', "'%'")

    def test_struct_ternary_where_it_cannot_branch(self):
        self.refuses('struct S { float a; }; bool h(S s) { return s.a > 0.0; }\n'
                     'bool f(S a, S b, bool c) { return c && h(c ? a : b); }', 'cannot become an if/else')

    def test_declarations(self):
        self.refuses('typedef float real; real f(real x) { return x; }', 'typedef')
        self.refuses('float f(float x) { return x; } float f(int x) { return 1.0; }', 'overloading')
        self.refuses('float f(int n) { float a[n]; return 1.0; }', 'array size')
        self.refuses('float f(float x) { const float y; return x; }', 'const')

    def test_literals(self):
        self.refuses('float f() { return 1e39; }', "beyond float's range")
        self.refuses('int f() { return 010; }', 'octal')
        self.refuses('float f() { return 0x1.8p1; }', 'hex floats')
        self.refuses('int f() { return 3000000000; }', 'i32')

    def test_reserved_names_of_the_translator(self):
        self.refuses('float f(volatile float x) { return x; }', 'volatile')

    def test_message_names_the_place(self):
        msg = self.refuses('float f(float x) {\n  return x;\n}\nfloat g(float x) {\n  return nope(x);\n}\n',
                           "call to 'nope'")
        self.assertRegex(msg, r'line 5 of the assembled input, in g\(\)')

    def test_command_line_fails_with_a_message(self):
        with tempfile.TemporaryDirectory() as tmp:
            src = os.path.join(tmp, 'bad.wgsl.in')
            out = os.path.join(tmp, 'bad.wgsl')
            with open(src, 'w') as f:
                f.write('float f(int k) { switch (k) { default: return 1.0; } }\n')
            p = subprocess.run([sys.executable, slut_wgsl.__file__, 'snippet', '--cpp', CPP, '--name', 'bad', src,
                                out], capture_output=True, text=True)
            self.assertEqual(p.returncode, 1)
            self.assertIn('cannot translate', p.stderr)
            self.assertIn('switch', p.stderr)
            self.assertFalse(os.path.exists(out), 'no output file on failure')


SHADER_DIR = os.environ.get('SLUT_WGSL_SHADER_DIR')
SNIPPETS = ['airlight', 'airlight_hg', 'nearlight', 'nearlight_hg', 'surface']


@unittest.skipUnless(SHADER_DIR, 'SLUT_WGSL_SHADER_DIR not set (the generated snippets)')
class GeneratedSnippets(unittest.TestCase):
    def read(self, name):
        with open(os.path.join(SHADER_DIR, name), encoding='utf-8') as f:
            return f.read()

    def code(self, text):
        return text[text.index('// ==== BEGIN SHARED'):]

    def shared(self, text):
        return text[text.index('// ==== BEGIN SHARED'):text.index('// ==== END SHARED')]

    def test_every_snippet_and_tier_is_there(self):
        for s in SNIPPETS:
            for suffix in ('', '_fast', '_accurate'):
                text = self.read('scatterlut_%s%s.wgsl' % (s, suffix))
                self.assertTrue(text.isascii(), s + suffix)
                leftover = set(re.findall(r'\bslut_wgsl_\w+', text)) - {'slut_wgsl_inf_bits'}
                leftover = {x for x in leftover if not re.fullmatch(r'slut_wgsl_sel_\d+', x)}
                self.assertEqual(leftover, set(), '%s%s: placeholders left' % (s, suffix))
                for glsl in ('texelFetch', 'textureLod', 'vec3', 'float', 'int', 'out'):
                    self.assertIsNone(re.search(r'\b%s\b(?!<)' % glsl, self.code(text)), '%s%s: GLSL left' % (s, suffix))

    def test_one_shared_part_per_tier(self):
        for suffix in ('', '_fast', '_accurate'):
            parts = {s: self.shared(self.read('scatterlut_%s%s.wgsl' % (s, suffix))) for s in SNIPPETS}
            for s in SNIPPETS:
                self.assertEqual(parts[s], parts['airlight'], '%s%s: shared part differs' % (s, suffix))

    def test_accurate_tier_is_the_default_except_for_airlight(self):
        for s in SNIPPETS:
            plain = self.code(self.read('scatterlut_%s.wgsl' % s))
            accurate = self.code(self.read('scatterlut_%s_accurate.wgsl' % s))
            fast = self.code(self.read('scatterlut_%s_fast.wgsl' % s))
            self.assertNotEqual(fast, accurate, s)
            if s == 'airlight':  # the tiers sample the airlight_rational table, no tier airlight_F
                self.assertNotEqual(plain, accurate)
            else:
                self.assertEqual(plain, accurate, s)


if __name__ == '__main__':
    unittest.main()
