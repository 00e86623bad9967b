#!/usr/bin/env python3
"""slut_wgsl.py -- the scatterlut snippets' shared GLSL subset to WGSL (docs/SHADERS.md, "WGSL").

The WGSL snippets come from the same source as the GLSL, HLSL and GLSL ES ones: the assembled
text of cmake/assemble_shaders.cmake with LANG=wgsl (the .slsl body, prelude.wgsl.h, common.slsl
and the kernels/ headers in their SLUT_SHADER branch), which this script runs through the C
preprocessor (with the tier's define), parses with pycparser (Debian: python3-pycparser) and
writes out as WGSL. It translates a small subset -- the one the snippets are written in -- and
refuses everything else with a message naming the construct, the function and the line of the
assembled input: it never guesses.

What it handles and how:
  types         float -> f32, int -> i32, uint -> u32, bool, vecN/ivecN/uvecN/bvecN ->
                vecN<f32/i32/u32/bool>, structs (by value), fixed-size arrays; the prelude's
                placeholder types slut_wgsl_texture_2d/_3d/_sampler -> texture_2d<f32>,
                texture_3d<f32>, sampler
  functions     fn with typed parameters; GLSL `out`/`inout` parameters (scalars, structs,
                arrays) -> ptr<function, T>, read and written as (*p), passed as &local; a
                by-value parameter the body assigns to is copied into a var first (WGSL
                parameters are immutable); statements after a return, break or continue in
                the same block are dropped (unreachable); a function that may end without
                returning its value is refused
  declarations  locals -> var (const locals -> let); module-scope const -> const (arrays from
                C initialiser lists), other module-scope variables -> var<private>
  statements    if/else, for (init; cond; ++i / i++ / i += k), while, break, continue, return,
                blocks, assignments (=, op=), ++/-- as statements, calls as statements
  expressions   arithmetic, comparison, logical and bitwise operators (parenthesised as WGSL's
                grammar requires), GLSL constructors float(x)/int(x)/vec3(...) -> f32(x)/i32(x)/
                vec3<f32>(...), member access and swizzles, indexing, true/false, the math
                built-ins in BUILTINS; `c ? a : b` -> select(b, a, c) for scalars and vectors,
                or, where a branch calls a function or the value is a struct or array, an
                if/else into a temporary before the statement (where that keeps the evaluation
                order: not in the right operand of && or ||, not in a loop condition)
  placeholders  slut_wgsl_texel2d/3d (textureLoad), slut_wgsl_filter2d/3d (textureSampleLevel,
                level 0), slut_wgsl_texture_size2d (textureDimensions), slut_wgsl_bitcast_f32
  names         identifiers that are WGSL keywords, reserved words, built-in functions or
                predeclared types get a trailing underscore

Refused (a TranslateError, exit status 1): switch, do-while, goto, pointers and address-of in the
source, casts, the comma operator, assignments inside expressions, ++/-- inside expressions,
multi-component swizzle assignment, struct-valued ?: where it cannot be hoisted, unknown
functions or identifiers, overloaded function names, recursion is left to WGSL (it refuses it),
literals float cannot hold, octal and hex-float literals, typedefs, and anything else pycparser
parses but this file does not know.

Usage:
  slut_wgsl.py snippet --cpp "CPP ARGS" [-D NAME]... --name NAME --tier TIER IN OUT
      IN: the assembled snippet (scatterlut_NAME.wgsl.in); OUT: the WGSL file.
  slut_wgsl.py harness --cpp "CPP ARGS" [-D NAME]... --snippet-in IN --body FILE --params TEXT
                       --texture 2d|3d OUT
      the compute shader wrapper of the WebGPU test (tests/shaders/webgpu_snippets.mjs): the test
      body (GLSL-subset text calling the snippet) translated against the snippet, plus bindings
      (0 the table, 4 its sampler in the fast tier, 1 the queries q[], 2 the results r[], 3 the
      parameters TEXT as a uniform struct) and @compute fn main. Append it to the snippet's WGSL.
"""

import argparse
import os
import re
import shlex
import subprocess
import sys

try:
    from pycparser import c_ast, c_parser
except ImportError:  # pragma: no cover - reported by CMake at configure time
    c_ast = c_parser = None
# pycparser 2.x (Debian 12: 2.21) has ParseError in plyparser; 3.x in c_parser.
ParseError = getattr(c_parser, 'ParseError', None)
if ParseError is None:
    try:
        from pycparser.plyparser import ParseError
    except ImportError:  # pragma: no cover
        ParseError = Exception


class TranslateError(Exception):
    """A construct the translator does not handle (or a source error it detects)."""


# ------------------------------------------------------------------------------ WGSL names

WGSL_KEYWORDS = set("""
alias break case const const_assert continue continuing default diagnostic discard else enable
false fn for if let loop override requires return struct switch true var while
""".split())

WGSL_RESERVED = set("""
NULL Self abstract active alignas alignof as asm asm_fragment async attribute auto await become
binding_array cast catch class co_await co_return co_yield coherent column_major common compile
compile_fragment concept const_cast consteval constexpr constinit crate debugger decltype delete
demote demote_to_helper do dynamic_cast enum explicit export extends extern external fallthrough
filter final finally friend from fxgroup get goto groupshared highp impl implements import inline
instanceof interface layout lowp macro macro_rules match mediump meta mod module move mut mutable
namespace new nil noexcept noinline nointerpolation noperspective null nullptr of operator package
packoffset partition pass patch pixelfragment precise precision premerge priv protected pub public
readonly ref regardless register reinterpret_cast require resource restrict self set shared sizeof
smooth snorm static static_assert static_cast std subroutine super target template this
thread_local throw trait try type typedef typeid typename typeof union unless unorm unsafe unsized
use using varying virtual volatile wgsl where with writeonly yield
""".split())

WGSL_PREDECLARED = set("""
bool f16 f32 i32 u32 vec2 vec3 vec4 mat2x2 mat2x3 mat2x4 mat3x2 mat3x3 mat3x4 mat4x2 mat4x3 mat4x4
vec2i vec3i vec4i vec2u vec3u vec4u vec2f vec3f vec4f vec2h vec3h vec4h array atomic ptr sampler
sampler_comparison texture_1d texture_2d texture_2d_array texture_3d texture_cube
texture_cube_array texture_multisampled_2d texture_storage_1d texture_storage_2d
texture_storage_2d_array texture_storage_3d texture_depth_2d texture_depth_2d_array
texture_depth_cube texture_depth_cube_array texture_depth_multisampled_2d texture_external
read write read_write function private workgroup uniform storage handle
abs acos acosh all any arrayLength asin asinh atan atan2 atanh bitcast ceil clamp cos cosh
countLeadingZeros countOneBits countTrailingZeros cross degrees determinant distance dot
dot4I8Packed dot4U8Packed dpdx dpdxCoarse dpdxFine dpdy dpdyCoarse dpdyFine exp exp2
extractBits faceForward firstLeadingBit firstTrailingBit floor fma fract frexp fwidth
fwidthCoarse fwidthFine insertBits inverseSqrt ldexp length log log2 max min mix modf normalize
pack2x16float pack2x16snorm pack2x16unorm pack4x8snorm pack4x8unorm pow quantizeToF16 radians
reflect refract reverseBits round saturate select sign sin sinh smoothstep sqrt step
storageBarrier tan tanh textureBarrier textureDimensions textureGather textureGatherCompare
textureLoad textureNumLayers textureNumLevels textureNumSamples textureSample textureSampleBias
textureSampleCompare textureSampleCompareLevel textureSampleGrad textureSampleLevel
textureSampleBaseClampToEdge textureStore transpose trunc unpack2x16float unpack2x16snorm
unpack2x16unorm unpack4x8snorm unpack4x8unorm workgroupBarrier workgroupUniformLoad
""".split())

# Names a member of a struct may not have (members live in their own namespace otherwise).
MEMBER_FORBIDDEN = WGSL_KEYWORDS | WGSL_RESERVED
# Names a variable, parameter, function or struct may not keep.
NAME_FORBIDDEN = WGSL_KEYWORDS | WGSL_RESERVED | WGSL_PREDECLARED


# ------------------------------------------------------------------------------- types

class T:
    """A WGSL type: kind in scalar (name f32/i32/u32/bool), abstract (name int/float), vector
    (name = component scalar, n), struct (name), array (elem, n), texture (name), sampler, void,
    ptr (elem)."""

    def __init__(self, kind, name=None, n=0, elem=None):
        self.kind, self.name, self.n, self.elem = kind, name, n, elem

    def __eq__(self, other):
        return isinstance(other, T) and (self.kind, self.name, self.n, self.elem) == (
            other.kind, other.name, other.n, other.elem)

    def __hash__(self):
        return hash((self.kind, self.name, self.n))

    def wgsl(self):
        if self.kind == 'scalar':
            return self.name
        if self.kind == 'abstract':
            return 'f32' if self.name == 'float' else 'i32'
        if self.kind == 'vector':
            return 'vec%d<%s>' % (self.n, self.name)
        if self.kind == 'struct':
            return self.name
        if self.kind == 'array':
            return 'array<%s, %d>' % (self.elem.wgsl(), self.n)
        if self.kind in ('texture', 'sampler'):
            return self.name
        if self.kind == 'ptr':
            return 'ptr<function, %s>' % self.elem.wgsl()
        raise TranslateError('internal: no WGSL spelling of type kind %s' % self.kind)

    def __repr__(self):
        return self.wgsl() if self.kind not in ('void', 'abstract') else '<%s %s>' % (self.kind, self.name)

    def is_numeric_scalar(self):
        return self.kind in ('scalar', 'abstract') and self.name != 'bool'

    def selectable(self):
        return self.kind in ('scalar', 'abstract', 'vector')


F32, I32, U32, BOOL = T('scalar', 'f32'), T('scalar', 'i32'), T('scalar', 'u32'), T('scalar', 'bool')
ABSTRACT_INT, ABSTRACT_FLOAT = T('abstract', 'int'), T('abstract', 'float')
VOID = T('void')

SCALAR_NAMES = {'float': F32, 'int': I32, 'uint': U32, 'unsigned': U32, 'unsigned int': U32,
                'bool': BOOL, '_Bool': BOOL}
VECTOR_PREFIX = {'': 'f32', 'i': 'i32', 'u': 'u32', 'b': 'bool'}
PLACEHOLDER_TYPES = {'slut_wgsl_texture_2d': T('texture', 'texture_2d<f32>'),
                     'slut_wgsl_texture_3d': T('texture', 'texture_3d<f32>'),
                     'slut_wgsl_sampler': T('sampler', 'sampler')}


def vector_type(name):
    m = re.fullmatch(r'([iub]?)vec([234])', name)
    if not m:
        return None
    return T('vector', VECTOR_PREFIX[m.group(1)], int(m.group(2)))


# The parser's view of the GLSL type names (pycparser needs them declared as typedefs).
PARSER_PRELUDE = ''.join('typedef int %s;\n' % n for n in [
    'uint', 'bool', 'vec2', 'vec3', 'vec4', 'ivec2', 'ivec3', 'ivec4', 'uvec2', 'uvec3', 'uvec4',
    'bvec2', 'bvec3', 'bvec4'] + sorted(PLACEHOLDER_TYPES))
PARSER_PRELUDE_FILE = '<slut_wgsl parser prelude>'

CONSTRUCTOR_NAMES = ['float', 'int', 'uint', 'bool'] + [
    p + 'vec' + str(n) for p in ('', 'i', 'u', 'b') for n in (2, 3, 4)]
CTOR_PREFIX = 'slut_wgsl_ctor_'

# GLSL built-ins the shared code may call: GLSL name -> (WGSL name, result rule, arity).
# Result rules: 'arg0' (the first argument's type), 'f32', 'elem0' (the component type of the
# first argument), 'bool'.
BUILTINS = {
    'abs': ('abs', 'arg0', 1), 'min': ('min', 'arg0', 2), 'max': ('max', 'arg0', 2),
    'clamp': ('clamp', 'arg0', 3), 'floor': ('floor', 'arg0', 1), 'ceil': ('ceil', 'arg0', 1),
    'fract': ('fract', 'arg0', 1), 'trunc': ('trunc', 'arg0', 1), 'sign': ('sign', 'arg0', 1),
    'exp': ('exp', 'arg0', 1), 'exp2': ('exp2', 'arg0', 1), 'log': ('log', 'arg0', 1),
    'log2': ('log2', 'arg0', 1), 'sqrt': ('sqrt', 'arg0', 1), 'inversesqrt': ('inverseSqrt', 'arg0', 1),
    'pow': ('pow', 'arg0', 2), 'sin': ('sin', 'arg0', 1), 'cos': ('cos', 'arg0', 1),
    'tan': ('tan', 'arg0', 1), 'asin': ('asin', 'arg0', 1), 'acos': ('acos', 'arg0', 1),
    'sinh': ('sinh', 'arg0', 1), 'cosh': ('cosh', 'arg0', 1), 'tanh': ('tanh', 'arg0', 1),
    'mix': ('mix', 'arg0', 3), 'step': ('step', 'arg1', 2), 'smoothstep': ('smoothstep', 'arg2', 3),
    'fma': ('fma', 'arg0', 3), 'length': ('length', 'elem0', 1), 'distance': ('distance', 'elem0', 2),
    'dot': ('dot', 'elem0', 2), 'cross': ('cross', 'arg0', 2), 'normalize': ('normalize', 'arg0', 1),
}
# atan: one argument -> atan, two -> atan2 (GLSL's atan(y, x)). Refused on purpose: mod (GLSL's
# x - y floor(x/y) is not WGSL's %), round (WGSL rounds half to even), isnan/isinf (WGSL has
# none), and anything else not listed.
REFUSED_BUILTINS = {
    'mod': "GLSL's mod(x, y) = x - y*floor(x/y) differs from WGSL's % (truncated): write it out",
    'round': 'WGSL round() rounds halves to even, GLSL leaves it to the implementation: write floor(x + 0.5)',
    'isnan': 'WGSL has no isnan (and may assume no NaN): compare instead, e.g. !(x == x)',
    'isinf': 'WGSL has no isinf (and may assume no infinity): compare with a bound instead',
}

# The prelude's placeholders: name -> (arity, result type, WGSL template).
PLACEHOLDER_CALLS = {
    'slut_wgsl_texel2d': (3, F32, 'textureLoad({0}, vec2<i32>({1}, {2}), 0).r'),
    'slut_wgsl_texel3d': (4, F32, 'textureLoad({0}, vec3<i32>({1}, {2}, {3}), 0).r'),
    'slut_wgsl_filter2d': (4, F32, 'textureSampleLevel({0}, {1}, vec2<f32>({2}, {3}), 0.0).r'),
    'slut_wgsl_filter3d': (5, F32, 'textureSampleLevel({0}, {1}, vec3<f32>({2}, {3}, {4}), 0.0).r'),
    'slut_wgsl_texture_size2d': (1, T('vector', 'f32', 2), 'vec2<f32>(textureDimensions({0}, 0))'),
    'slut_wgsl_bitcast_f32': (1, F32, 'bitcast<f32>({0})'),
}

FLT_MAX = 3.4028234663852886e38
FLT_ROUNDS_TO_INF = 3.4028235677973366e38  # FLT_MAX + half an ulp: rounds to +inf in float

ARITH_OPS = {'*', '/', '%', '+', '-'}
MUL_OPS = {'*', '/', '%'}
ADD_OPS = {'+', '-'}
SHIFT_OPS = {'<<', '>>'}
REL_OPS = {'<', '>', '<=', '>=', '==', '!='}
BIT_OPS = {'&', '|', '^'}
LOGIC_OPS = {'&&', '||'}


# ------------------------------------------------------------------------ preprocessing

def section_markers(text):
    """`#line` directives that name each part of an assembled snippet (the line numbers stay
    those of the assembled file), inserted before its `// ---- <source>` headings."""
    out = []
    lines = text.split('\n')
    section = 'prelude'
    out.append('#line 1 "%s"' % section)
    for number, line in enumerate(lines, start=1):
        m = re.match(r'// ---- ((?:kernels|tables/shaders/src)/[A-Za-z0-9_./]+)', line)
        name = None
        if m:
            name = m.group(1).rstrip(':')
        elif line.startswith('// ==== BEGIN SHARED BODY'):
            name = 'tables/shaders/src/common.slsl'
        elif line.startswith('// ---- back to the GPU'):
            name = 'tables/shaders/src/common.slsl'
        else:
            m = re.match(r'#ifndef SLUT_([A-Z0-9_]+)_CODE$', line)
            if m and m.group(1) != 'SHADER_COMMON':
                name = 'tables/shaders/src/%s.slsl' % m.group(1).lower()
        if name:
            out.append('#line %d "%s"' % (number, name))
        out.append(line)
    return '\n'.join(out)


def run_cpp(cpp, text, defines, what):
    command = shlex.split(cpp) + ['-undef', '-nostdinc'] + ['-D' + d for d in defines] + ['-']
    try:
        done = subprocess.run(command, input=text, capture_output=True, text=True, check=False)
    except OSError as e:
        raise TranslateError('cannot run the C preprocessor %r: %s' % (cpp, e))
    if done.returncode != 0:
        raise TranslateError('the C preprocessor failed on %s:\n%s' % (what, done.stderr.strip()))
    return done.stdout


def glsl_to_c(text):
    """The GLSL subset, preprocessed, as C pycparser can parse: `out`/`inout` parameters marked
    volatile (the translator's marker for a pointer parameter), `in` dropped, constructor calls
    renamed (float(x) is no C expression), every struct named as a typedef."""
    for word in ('volatile', 'restrict', CTOR_PREFIX):
        if re.search(r'\b' + word, text):
            raise TranslateError("the source uses '%s', which the translator reserves" % word)
    text = re.sub(r'\b(?:out|inout)\s+(?=[A-Za-z_])', 'volatile ', text)
    text = re.sub(r'([(,]\s*)in\s+(?=[A-Za-z_])', r'\1', text)
    text = re.sub(r'\b(%s)\s*\(' % '|'.join(CONSTRUCTOR_NAMES), CTOR_PREFIX + r'\1(', text)
    structs = re.findall(r'\bstruct\s+([A-Za-z_][A-Za-z0-9_]*)\s*\{', text)
    typedefs = ''.join('typedef struct %s %s;\n' % (s, s) for s in dict.fromkeys(structs))
    return '# 1 "%s"\n%s%s# 1 "<input>"\n' % (PARSER_PRELUDE_FILE, PARSER_PRELUDE, typedefs) + text


def parse(c_text):
    try:
        return c_parser.CParser().parse(c_text, filename='<input>')
    except ParseError as e:
        raise TranslateError('not in the translatable subset (pycparser: %s)' % e)


# -------------------------------------------------------------------------- translator

class Scope:
    def __init__(self, parent=None):
        self.parent, self.names = parent, {}

    def lookup(self, name):
        s = self
        while s is not None:
            if name in s.names:
                return s.names[name]
            s = s.parent
        return None


class Var:
    """A name in scope: its type, its WGSL spelling, and what it is."""

    def __init__(self, type_, wgsl, kind, mutable=True):
        self.type, self.wgsl, self.kind, self.mutable = type_, wgsl, kind, mutable
        # kind: local, param, ptr (an out parameter), global_const, global_var, extern


class Function:
    def __init__(self, name, wgsl, ret, params, node, section):
        self.name, self.wgsl, self.ret, self.params, self.node, self.section = name, wgsl, ret, params, node, section


class Translator:
    def __init__(self, ast, externs=None):
        self.ast = ast
        self.structs = {}      # name -> [(member, T)]
        self.struct_nodes = {}  # name -> (node, section)
        self.functions = {}    # name -> Function
        self.globals = Scope()
        self.global_decls = []  # (node, section)
        self.order = []        # ('struct'|'global'|'function', name, section) in source order
        self.renamed = {}
        self.temp_counter = 0
        self.externs = externs or {}
        self.function = None   # the function being translated
        self._depth = 1        # the indentation of the statement being translated
        for name, (type_, wgsl) in self.externs.items():
            self.globals.names[name] = Var(type_, wgsl, 'extern')

    # ---- messages
    def where(self, node):
        c = getattr(node, 'coord', None)
        place = '%s, line %s of the assembled input' % (c.file, c.line) if c else 'unknown place'
        if self.function is not None:
            place += ', in %s()' % self.function.name
        return place

    def fail(self, node, message):
        raise TranslateError('%s: %s' % (self.where(node), message))

    # ---- names
    def name(self, name, node, member=False):
        forbidden = MEMBER_FORBIDDEN if member else NAME_FORBIDDEN
        if name.startswith('__') or name == '_':
            self.fail(node, "identifier '%s' is not a valid WGSL identifier" % name)
        if name in forbidden:
            return name + '_'
        return name

    # ---- types
    def type_of_names(self, names, node):
        key = ' '.join(names)
        if key in SCALAR_NAMES:
            return SCALAR_NAMES[key]
        if key == 'void':
            return VOID
        v = vector_type(key)
        if v:
            return v
        if key in PLACEHOLDER_TYPES:
            return PLACEHOLDER_TYPES[key]
        if key in self.structs:
            return T('struct', self.name(key, node))
        self.fail(node, "unknown type '%s'" % key)

    def decl_type(self, tnode, node):
        if isinstance(tnode, c_ast.TypeDecl):
            inner = tnode.type
            if isinstance(inner, c_ast.IdentifierType):
                return self.type_of_names(inner.names, node)
            if isinstance(inner, c_ast.Struct):
                if inner.decls is not None:
                    self.fail(node, 'a struct defined inside a declaration')
                return self.type_of_names([inner.name], node)
            self.fail(node, 'unsupported type %s' % type(inner).__name__)
        if isinstance(tnode, c_ast.ArrayDecl):
            elem = self.decl_type(tnode.type, node)
            if tnode.dim is None:
                self.fail(node, 'an array without a size')
            n = self.const_int(tnode.dim)
            if n is None or n <= 0:
                self.fail(node, 'an array size that is not a positive integer constant')
            return T('array', elem=elem, n=n)
        if isinstance(tnode, c_ast.PtrDecl):
            self.fail(node, 'a pointer (the shared subset has none; out parameters are GLSL `out`)')
        if isinstance(tnode, c_ast.FuncDecl):
            self.fail(node, 'a function declared inside a declaration')
        self.fail(node, 'unsupported declarator %s' % type(tnode).__name__)

    def const_int(self, e):
        if isinstance(e, c_ast.Constant) and e.type == 'int':
            return int(self.int_literal(e)[0], 0)
        if isinstance(e, c_ast.BinaryOp) and e.op in ('+', '-', '*'):
            a, b = self.const_int(e.left), self.const_int(e.right)
            if a is None or b is None:
                return None
            return a + b if e.op == '+' else a - b if e.op == '-' else a * b
        return None

    # ---- pass 1: declarations
    def collect(self):
        for ext in self.ast.ext:
            section = ext.coord.file if ext.coord else '?'
            if section == PARSER_PRELUDE_FILE:
                continue
            if isinstance(ext, c_ast.Typedef):
                if isinstance(ext.type, c_ast.TypeDecl) and isinstance(ext.type.type, c_ast.Struct) \
                        and ext.type.type.name == ext.name and ext.type.type.decls is None:
                    continue  # the struct typedefs glsl_to_c adds
                self.fail(ext, 'typedef (not in the shared subset)')
            if isinstance(ext, c_ast.FuncDef):
                self.declare_function(ext.decl, ext, section)
            elif isinstance(ext, c_ast.Decl):
                if isinstance(ext.type, c_ast.Struct):
                    self.declare_struct(ext.type, ext, section)
                elif isinstance(ext.type, c_ast.FuncDecl):
                    self.declare_prototype(ext, section)
                else:
                    self.declare_global(ext, section)
            else:
                self.fail(ext, 'unsupported top-level construct %s' % type(ext).__name__)

    def declare_struct(self, s, node, section):
        if s.decls is None:
            self.fail(node, "a forward declaration of struct '%s'" % s.name)
        if s.name in self.structs:
            self.fail(node, "struct '%s' defined twice" % s.name)
        self.structs[s.name] = []  # (itself unknown inside: no recursive structs)
        members = []
        for d in s.decls:
            if d.bitsize is not None or d.init is not None:
                self.fail(d, 'bit-field or initialised struct member')
            members.append((d.name, self.decl_type(d.type, d)))
        if not members:
            self.fail(node, "empty struct '%s'" % s.name)
        self.structs[s.name] = members
        self.order.append(('struct', s.name, section))
        self.struct_nodes[s.name] = node

    def signature(self, decl, node):
        ftype = decl.type
        ret = self.decl_type(ftype.type, node)
        params = []
        if ftype.args is not None:
            for p in ftype.args.params:
                if isinstance(p, c_ast.EllipsisParam):
                    self.fail(node, 'variadic function')
                if isinstance(p, c_ast.Typename):
                    if isinstance(p.type, c_ast.TypeDecl) and isinstance(p.type.type, c_ast.IdentifierType) \
                            and p.type.type.names == ['void']:
                        continue
                    self.fail(node, 'a parameter without a name')
                quals = set(p.quals)
                t = self.decl_type(p.type, p)
                if t.kind == 'void':
                    self.fail(p, 'a void parameter')
                is_out = 'volatile' in quals
                params.append((p.name, t, is_out))
        return ret, params

    def declare_function(self, decl, node, section):
        name = decl.name
        if name in self.functions and self.functions[name].node is not None:
            self.fail(node, "function '%s' defined twice (WGSL has no overloading)" % name)
        if name.startswith('slut_wgsl_') or name in BUILTINS or name in PLACEHOLDER_CALLS:
            self.fail(node, "function '%s' shadows a built-in or placeholder" % name)
        ret, params = self.signature(decl, node)
        old = self.functions.get(name)
        if old is not None and (old.ret != ret or [p[1:] for p in old.params] != [p[1:] for p in params]):
            self.fail(node, "function '%s' defined with another signature than its prototype" % name)
        self.functions[name] = Function(name, self.name(name, node), ret, params, node, section)
        self.order.append(('function', name, section))

    def declare_prototype(self, decl, section):
        name = decl.name
        ret, params = self.signature(decl, decl)
        old = self.functions.get(name)
        if old is not None:
            if old.ret != ret or [p[1:] for p in old.params] != [p[1:] for p in params]:
                self.fail(decl, "function '%s' declared with two signatures (WGSL has no overloading)" % name)
            return
        self.functions[name] = Function(name, self.name(name, decl), ret, params, None, section)

    def declare_global(self, d, section):
        if d.storage and set(d.storage) - {'static'}:
            self.fail(d, 'storage class %s' % ' '.join(d.storage))
        t = self.decl_type(d.type, d)
        if d.name in self.globals.names:
            self.fail(d, "'%s' declared twice" % d.name)
        is_const = 'const' in d.quals
        self.globals.names[d.name] = Var(t, self.name(d.name, d), 'global_const' if is_const else 'global_var',
                                         mutable=not is_const)
        self.global_decls.append(d)
        self.order.append(('global', d.name, section))

    # ---- pass 2: output
    def translate(self, sections=None):
        """WGSL text of every declaration (of the given sections only, if any), with a heading
        where the section changes. Returns [(section, text)]."""
        self.collect()
        for f in self.functions.values():
            if f.node is None:
                self.fail(f.node, "function '%s' declared but never defined" % f.name)
        out = []
        for kind, name, section in self.order:
            if sections is not None and section not in sections:
                continue
            if kind == 'struct':
                text = self.emit_struct(name)
            elif kind == 'global':
                text = self.emit_global(next(d for d in self.global_decls if d.name == name))
            else:
                text = self.emit_function(self.functions[name])
            out.append((section, text))
        return out

    def emit_struct(self, name):
        node = self.struct_nodes[name]
        lines = ['struct %s {' % self.name(name, node)]
        for member, t in self.structs[name]:
            lines.append('    %s: %s,' % (self.name(member, node, member=True), t.wgsl()))
        lines.append('}')
        return '\n'.join(lines)

    def emit_global(self, d):
        v = self.globals.names[d.name]
        if d.init is None:
            if v.kind == 'global_const':
                self.fail(d, 'a const without a value')
            return 'var<private> %s: %s;' % (v.wgsl, v.type.wgsl())
        self.function = None
        scope = Scope(self.globals)
        init = self.initializer(d.init, v.type, scope, d, const_context=True)
        if v.kind == 'global_const':
            return 'const %s: %s = %s;' % (v.wgsl, v.type.wgsl(), init)
        return 'var<private> %s: %s = %s;' % (v.wgsl, v.type.wgsl(), init)

    def initializer(self, init, t, scope, node, const_context=False):
        if isinstance(init, c_ast.InitList):
            if t.kind != 'array':
                self.fail(node, 'a brace initialiser for a non-array')
            if len(init.exprs) != t.n:
                self.fail(node, 'an array initialiser with %d values for %d elements' % (len(init.exprs), t.n))
            items = [self.initializer(e, t.elem, scope, node, const_context) for e in init.exprs]
            return '%s(%s)' % (t.wgsl(), ', '.join(items))
        if const_context and self.contains_call(init, user_only=True):
            self.fail(node, 'a module-scope value computed by a function (WGSL needs a constant expression)')
        text, et = self.expr(init, scope, ctx=None)
        self.check_assignable(t, et, node)
        return text

    def calls_user_function(self, e):
        return self.contains_call(e, user_only=True)

    def contains_call(self, e, user_only=False):
        found = []

        class V(c_ast.NodeVisitor):
            def visit_FuncCall(v, n):
                name = n.name.name if isinstance(n.name, c_ast.ID) else None
                if not user_only or name in self.functions:
                    found.append(n)
                v.generic_visit(n)

        V().visit(e)
        return bool(found)

    # ---- functions
    def emit_function(self, f):
        self.function = f
        self.temp_counter = 0
        scope = Scope(self.globals)
        body = f.node.body
        mutated = self.assigned_names(body)
        params, prologue = [], []
        for pname, t, is_out in f.params:
            wname = self.name(pname, f.node)
            if t.kind in ('texture', 'sampler') and is_out:
                self.fail(f.node, 'an out texture or sampler parameter')
            if is_out:
                params.append('%s: %s' % (wname, T('ptr', elem=t).wgsl()))
                scope.names[pname] = Var(t, wname, 'ptr')
            elif pname in mutated:
                if t.kind in ('texture', 'sampler'):
                    self.fail(f.node, "texture or sampler parameter '%s' assigned to" % pname)
                param_name = self.fresh(wname + '_in', scope)
                params.append('%s: %s' % (param_name, t.wgsl()))
                prologue.append('    var %s: %s = %s;' % (wname, t.wgsl(), param_name))
                scope.names[pname] = Var(t, wname, 'local')
            else:
                params.append('%s: %s' % (wname, t.wgsl()))
                scope.names[pname] = Var(t, wname, 'param', mutable=False)
        ret = '' if f.ret.kind == 'void' else ' -> %s' % f.ret.wgsl()
        if f.ret.kind in ('texture', 'sampler'):
            self.fail(f.node, 'a function returning a texture or sampler')
        lines = ['fn %s(%s)%s {' % (f.wgsl, ', '.join(params), ret)] + prologue
        lines += self.block_items(body.block_items or [], scope, 1)
        if f.ret.kind != 'void' and not self.returns_always(body):
            self.fail(f.node, "function '%s' may end without returning a value (WGSL refuses that)" % f.name)
        lines.append('}')
        self.function = None
        return '\n'.join(lines)

    def fresh(self, base, scope):
        name = base
        k = 2
        while scope.lookup(name) is not None or name in self.functions or name in self.structs:
            name = '%s%d' % (base, k)
            k += 1
        return name

    def assigned_names(self, body):
        """Names assigned to (or passed as out arguments) anywhere in body: root identifiers."""
        names = set()
        tr = self

        def root(e):
            while isinstance(e, (c_ast.StructRef, c_ast.ArrayRef)):
                e = e.name
            return e.name if isinstance(e, c_ast.ID) else None

        class V(c_ast.NodeVisitor):
            def visit_Assignment(v, n):
                names.add(root(n.lvalue))
                v.generic_visit(n)

            def visit_UnaryOp(v, n):
                if n.op in ('++', '--', 'p++', 'p--'):
                    names.add(root(n.expr))
                v.generic_visit(n)

            def visit_FuncCall(v, n):
                f = tr.functions.get(n.name.name) if isinstance(n.name, c_ast.ID) else None
                if f is not None and n.args is not None:
                    for (pname, t, is_out), a in zip(f.params, n.args.exprs):
                        if is_out:
                            names.add(root(a))
                v.generic_visit(n)

        V().visit(body)
        names.discard(None)
        return names

    def returns_always(self, s):
        if isinstance(s, c_ast.Return):
            return True
        if isinstance(s, c_ast.Compound):
            return any(self.returns_always(x) for x in (s.block_items or []))
        if isinstance(s, c_ast.If):
            return s.iffalse is not None and self.returns_always(s.iftrue) and self.returns_always(s.iffalse)
        return False

    @staticmethod
    def leaves_block(s):
        return isinstance(s, (c_ast.Return, c_ast.Break, c_ast.Continue))

    # ---- statements
    def block_items(self, items, scope, depth):
        lines = []
        for s in items:
            lines += self.stmt(s, scope, depth)
            if self.leaves_block(s) or (isinstance(s, (c_ast.If, c_ast.Compound)) and self.returns_always(s)):
                break  # the rest of the block is unreachable
        return lines

    def braced(self, s, scope, depth):
        inner = Scope(scope)
        items = s.block_items or [] if isinstance(s, c_ast.Compound) else [s]
        return self.block_items(items, inner, depth + 1)

    def stmt(self, s, scope, depth):
        # The statements hoisted out of s's expressions go before it, at its indentation.
        saved, self._depth = self._depth, depth
        try:
            return self.stmt_at_depth(s, scope, depth)
        finally:
            self._depth = saved

    def stmt_at_depth(self, s, scope, depth):
        ind = '    ' * depth
        pre = []  # statements hoisted out of this one's expressions
        if isinstance(s, c_ast.Decl):
            return self.local_decl(s, scope, depth)
        if isinstance(s, c_ast.DeclList):
            self.fail(s, 'several declarations in one for-initialiser')
        if isinstance(s, c_ast.Compound):
            return [ind + '{'] + self.braced(s, scope, depth) + [ind + '}']
        if isinstance(s, c_ast.EmptyStatement):
            return []
        if isinstance(s, c_ast.Return):
            if s.expr is None:
                if self.function.ret.kind != 'void':
                    self.fail(s, 'return without a value from a function that has one')
                return [ind + 'return;']
            if self.function.ret.kind == 'void':
                self.fail(s, 'return with a value from a void function')
            if isinstance(s.expr, c_ast.TernaryOp) and self.needs_branch(s.expr, scope):
                c = s.expr
                cond, ct = self.expr(c.cond, scope, ctx=pre)
                self.check_bool(ct, c.cond)
                lines = pre + [ind + 'if (%s) {' % cond]
                lines += self.stmt(c_ast.Return(c.iftrue, coord=s.coord), scope, depth + 1)
                lines += [ind + '} else {']
                lines += self.stmt(c_ast.Return(c.iffalse, coord=s.coord), scope, depth + 1)
                return lines + [ind + '}']
            text, et = self.expr(s.expr, scope, ctx=pre)
            self.check_assignable(self.function.ret, et, s)
            return pre + [ind + 'return %s;' % text]
        if isinstance(s, c_ast.Break):
            return [ind + 'break;']
        if isinstance(s, c_ast.Continue):
            return [ind + 'continue;']
        if isinstance(s, c_ast.If):
            cond, ct = self.expr(s.cond, scope, ctx=pre)
            self.check_bool(ct, s.cond)
            lines = pre + [ind + 'if (%s) {' % cond] + self.braced(s.iftrue, scope, depth)
            if s.iffalse is not None:
                lines += [ind + '} else {'] + self.braced(s.iffalse, scope, depth)
            return lines + [ind + '}']
        if isinstance(s, c_ast.For):
            return self.for_stmt(s, scope, depth)
        if isinstance(s, c_ast.While):
            cond, ct = self.expr(s.cond, scope, ctx=None)
            self.check_bool(ct, s.cond)
            return [ind + 'while (%s) {' % cond] + self.braced(s.stmt, scope, depth) + [ind + '}']
        if isinstance(s, c_ast.Assignment):
            return self.assignment(s, scope, depth)
        if isinstance(s, c_ast.UnaryOp) and s.op in ('++', '--', 'p++', 'p--'):
            return [ind + self.increment(s, scope) + ';']
        if isinstance(s, c_ast.FuncCall):
            text, _ = self.expr(s, scope, ctx=pre, statement=True)
            return pre + [ind + text + ';']
        if isinstance(s, c_ast.DoWhile):
            self.fail(s, 'do-while loop (not handled: write a for or while loop)')
        if isinstance(s, c_ast.Switch):
            self.fail(s, 'switch statement (not handled; the snippets write chains of ifs)')
        if isinstance(s, (c_ast.Goto, c_ast.Label)):
            self.fail(s, 'goto or label')
        self.fail(s, 'unsupported statement %s' % type(s).__name__)

    def local_decl(self, d, scope, depth, in_for=False):
        ind = '' if in_for else '    ' * depth
        if d.storage:
            self.fail(d, 'storage class %s on a local' % ' '.join(d.storage))
        t = self.decl_type(d.type, d)
        if t.kind in ('texture', 'sampler', 'void'):
            self.fail(d, 'a local of type %s' % t.wgsl())
        if d.name in scope.names:
            self.fail(d, "'%s' declared twice in one scope" % d.name)
        wname = self.name(d.name, d)
        is_const = 'const' in d.quals
        pre = []
        lines = []
        if d.init is None:
            if is_const:
                self.fail(d, 'a const local without a value')
            text = '%svar %s: %s;' % (ind, wname, t.wgsl())
        elif isinstance(d.init, c_ast.TernaryOp) and not in_for and self.needs_branch(d.init, scope):
            # var x: T; if (c) { x = a; } else { x = b; }  (its own temporary)
            scope.names[d.name] = Var(t, wname, 'local')
            lines = ['%svar %s: %s;' % (ind, wname, t.wgsl())]
            lines += self.branch_assign(wname, t, d.init, scope, depth, d)
            if is_const:
                scope.names[d.name].mutable = False
            return lines
        else:
            init = self.initializer(d.init, t, scope, d) if isinstance(d.init, c_ast.InitList) else None
            if init is None:
                init, et = self.expr(d.init, scope, ctx=None if in_for else pre)
                self.check_assignable(t, et, d)
            text = '%s%s %s: %s = %s;' % (ind, 'let' if is_const else 'var', wname, t.wgsl(), init)
        scope.names[d.name] = Var(t, wname, 'local', mutable=not is_const)
        if in_for:
            return [text.rstrip(';')]
        return pre + [text]

    def branch_assign(self, target, t, tern, scope, depth, node):
        """if (c) { target = a; } else { target = b; } for target of type t (both branches
        translated as statements, so that nested ?: with calls branch too)."""
        ind = '    ' * depth
        pre = []
        cond, ct = self.expr(tern.cond, scope, ctx=pre)
        self.check_bool(ct, tern.cond)
        lines = pre + [ind + 'if (%s) {' % cond]
        for k, branch in enumerate((tern.iftrue, tern.iffalse)):
            if k == 1:
                lines.append(ind + '} else {')
            if isinstance(branch, c_ast.TernaryOp) and self.needs_branch(branch, scope):
                lines += self.branch_assign(target, t, branch, scope, depth + 1, node)
            else:
                bpre = []
                text, et = self.expr(branch, scope, ctx=bpre)
                self.check_assignable(t, et, node)
                lines += bpre + ['%s    %s = %s;' % (ind, target, text)]
        return lines + [ind + '}']

    def for_stmt(self, s, scope, depth):
        ind = '    ' * depth
        inner = Scope(scope)
        init = ''
        if isinstance(s.init, c_ast.DeclList):
            if len(s.init.decls) != 1:
                self.fail(s, 'several declarations in one for-initialiser')
            init = self.local_decl(s.init.decls[0], inner, depth, in_for=True)[0]
        elif isinstance(s.init, c_ast.Assignment):
            init = self.assignment(s.init, inner, depth, in_for=True)[0]
        elif s.init is not None:
            self.fail(s, 'unsupported for-initialiser %s' % type(s.init).__name__)
        cond = ''
        if s.cond is not None:
            cond, ct = self.expr(s.cond, inner, ctx=None)
            self.check_bool(ct, s.cond)
        step = ''
        if s.next is not None:
            if isinstance(s.next, c_ast.UnaryOp) and s.next.op in ('++', '--', 'p++', 'p--'):
                step = self.increment(s.next, inner)
            elif isinstance(s.next, c_ast.Assignment):
                step = self.assignment(s.next, inner, depth, in_for=True)[0]
            else:
                self.fail(s, 'unsupported for-step %s (write ++i, i++ or i += k)' % type(s.next).__name__)
        return [ind + 'for (%s; %s; %s) {' % (init, cond, step)] + self.braced(s.stmt, inner, depth) + [ind + '}']

    def increment(self, s, scope):
        target, t = self.lvalue(s.expr, scope)
        op = '+' if '+' in s.op else '-'
        if t.kind == 'scalar' and t.name in ('i32', 'u32'):
            return '%s%s%s' % (target, op, op)
        if t.kind == 'scalar' and t.name == 'f32':
            return '%s %s= 1.0' % (target, op)
        self.fail(s, '++/-- on a %s' % t.wgsl())

    def assignment(self, s, scope, depth, in_for=False):
        ind = '' if in_for else '    ' * depth
        target, t = self.lvalue(s.lvalue, scope)
        pre = []
        if s.op == '=' and isinstance(s.rvalue, c_ast.TernaryOp) and not in_for and self.needs_branch(s.rvalue, scope) \
                and not self.mentions(s.rvalue, s.lvalue):
            return self.branch_assign(target, t, s.rvalue, scope, depth, s)
        value, vt = self.expr(s.rvalue, scope, ctx=None if in_for else pre)
        if s.op == '=':
            self.check_assignable(t, vt, s)
        elif s.op[:-1] in ARITH_OPS | BIT_OPS | SHIFT_OPS:
            self.binary_type(s.op[:-1], t, vt, s)
        else:
            self.fail(s, 'assignment operator %s' % s.op)
        text = '%s%s %s %s' % (ind, target, s.op, value)
        if in_for:
            if pre:
                self.fail(s, 'a branch in a for-loop clause')
            return [text]
        return pre + [text + ';']

    @staticmethod
    def mentions(expr, lvalue):
        names = set()

        class V(c_ast.NodeVisitor):
            def visit_ID(v, n):
                names.add(n.name)

        V().visit(expr)
        root = lvalue
        while isinstance(root, (c_ast.StructRef, c_ast.ArrayRef)):
            root = root.name
        return isinstance(root, c_ast.ID) and root.name in names

    def lvalue(self, e, scope):
        """(WGSL text, type) of an assignment target; refuses what WGSL cannot assign."""
        if isinstance(e, c_ast.ID):
            v = scope.lookup(e.name)
            if v is None:
                self.fail(e, "undeclared identifier '%s'" % e.name)
            if v.kind == 'ptr':
                return '*%s' % v.wgsl, v.type
            if not v.mutable or v.kind in ('param', 'global_const', 'extern'):
                self.fail(e, "assignment to '%s', which is not a variable" % e.name)
            return v.wgsl, v.type
        if isinstance(e, c_ast.StructRef):
            if e.type != '.':
                self.fail(e, "'->' (the shared subset has no pointers)")
            base, bt = self.lvalue(e.name, scope)
            base = self.paren_deref(base)
            field = e.field.name
            if bt.kind == 'vector':
                if len(field) != 1:
                    self.fail(e, "assignment to the swizzle '.%s' (WGSL assigns one component at a time)" % field)
                return '%s.%s' % (base, field), T('scalar', bt.name)
            if bt.kind != 'struct':
                self.fail(e, "member '%s' of a %s" % (field, bt.wgsl()))
            return '%s.%s' % (base, self.name(field, e, member=True)), self.member_type(bt, field, e)
        if isinstance(e, c_ast.ArrayRef):
            base, bt = self.lvalue(e.name, scope)
            base = self.paren_deref(base)
            index, it = self.expr(e.subscript, scope, ctx=None)
            self.check_index(it, e)
            if bt.kind == 'array':
                return '%s[%s]' % (base, index), bt.elem
            if bt.kind == 'vector':
                return '%s[%s]' % (base, index), T('scalar', bt.name)
            self.fail(e, 'indexing a %s' % bt.wgsl())
        self.fail(e, 'unsupported assignment target %s' % type(e).__name__)

    @staticmethod
    def paren_deref(text):
        return '(%s)' % text if text.startswith('*') else text

    def member_type(self, st, field, node):
        for name, t in self.structs.get(self.struct_name(st), []):
            if name == field:
                return t
        self.fail(node, "struct %s has no member '%s'" % (st.name, field))

    def struct_name(self, st):
        for name in self.structs:
            if self.name(name, None) == st.name:
                return name
        return st.name

    # ---- type checks
    def check_bool(self, t, node):
        if t != BOOL:
            self.fail(node, 'a condition of type %r (write a comparison: WGSL has no implicit bool)' % t)

    def check_index(self, t, node):
        if not ((t.kind == 'scalar' and t.name in ('i32', 'u32')) or t == ABSTRACT_INT):
            self.fail(node, 'an index of type %r' % t)

    def check_assignable(self, to, frm, node):
        if to == frm:
            return
        if frm.kind == 'abstract' and to.kind == 'scalar':
            if to.name == 'f32' or (frm.name == 'int' and to.name in ('i32', 'u32')):
                return
        self.fail(node, 'a %r value where a %r is needed (WGSL converts nothing implicitly)' % (frm, to))

    def binary_type(self, op, a, b, node):
        """The type of a op b (a, b numeric), or a failure where WGSL would refuse it."""
        def comp(t):
            return T('scalar', t.name) if t.kind == 'vector' else t

        ca, cb = comp(a), comp(b)
        if not (ca.is_numeric_scalar() and cb.is_numeric_scalar()):
            if op in BIT_OPS and ca == cb == BOOL:
                self.fail(node, "'%s' on bools (write && or ||)" % op)
            self.fail(node, "'%s' on %r and %r" % (op, a, b))
        if ca.kind == 'abstract' and cb.kind == 'abstract':
            elem = ABSTRACT_FLOAT if ABSTRACT_FLOAT in (ca, cb) else ABSTRACT_INT
        elif ca.kind == 'abstract':
            self.check_assignable(cb, ca, node)
            elem = cb
        elif cb.kind == 'abstract':
            self.check_assignable(ca, cb, node)
            elem = ca
        else:
            if ca != cb:
                self.fail(node, "'%s' on %r and %r (WGSL converts nothing implicitly)" % (op, a, b))
            elem = ca
        if op in BIT_OPS | SHIFT_OPS | {'%'} and elem.name in ('f32', 'float'):
            if op != '%':
                self.fail(node, "'%s' on floats" % op)
            self.fail(node, "'%' on floats (GLSL has no float %; WGSL's would truncate)")
        if a.kind == 'vector' and b.kind == 'vector' and a.n != b.n:
            self.fail(node, "'%s' on vectors of different sizes" % op)
        vec = a if a.kind == 'vector' else b if b.kind == 'vector' else None
        if vec is not None:
            return T('vector', elem.wgsl() if elem.kind == 'abstract' else elem.name, vec.n)
        return elem

    def unify(self, a, b, node):
        if a == b:
            return a
        if a.kind == 'abstract' and b.kind == 'abstract':
            return ABSTRACT_FLOAT
        if a.kind == 'abstract':
            self.check_assignable(b, a, node)
            return b
        if b.kind == 'abstract':
            self.check_assignable(a, b, node)
            return a
        self.fail(node, 'the two branches of ?: have types %r and %r' % (a, b))

    # ---- expressions
    def needs_branch(self, tern, scope):
        """Whether c ? a : b is written as an if/else rather than select(): a struct or array
        value, or a branch that calls a function (select would evaluate both)."""
        t = self.expr_type(tern, scope)
        return not t.selectable() or self.calls_user_function(tern.iftrue) or self.calls_user_function(tern.iffalse)

    def expr_type(self, e, scope):
        # A dry run: the type without keeping text or hoisting anything.
        saved = self.temp_counter
        _, t = self.expr(e, scope, ctx=None, dry=True)
        self.temp_counter = saved
        return t

    def expr(self, e, scope, ctx, statement=False, dry=False):
        """(WGSL text, type, precedence) -> returns (text, type). ctx: a list to hoist
        statements into (None where hoisting is not allowed)."""
        text, t, _ = self.ex(e, scope, ctx, dry)
        if isinstance(e, c_ast.FuncCall) and not statement and t.kind == 'void':
            self.fail(e, 'the value of a void function')
        return text, t

    def ex(self, e, scope, ctx, dry):
        PRIMARY = 100
        if isinstance(e, c_ast.Constant):
            return self.constant(e) + (PRIMARY,)
        if isinstance(e, c_ast.ID):
            if e.name in ('true', 'false') and scope.lookup(e.name) is None:
                return e.name, BOOL, PRIMARY
            v = scope.lookup(e.name)
            if v is None:
                self.fail(e, "undeclared identifier '%s'" % e.name)
            if v.kind == 'ptr':
                return '(*%s)' % v.wgsl, v.type, PRIMARY
            return v.wgsl, v.type, PRIMARY
        if isinstance(e, c_ast.BinaryOp):
            return self.binary(e, scope, ctx, dry)
        if isinstance(e, c_ast.UnaryOp):
            if e.op in ('-', '+', '!', '~'):
                text, t, prec = self.ex(e.expr, scope, ctx, dry)
                if e.op == '!':
                    self.check_bool(t, e)
                elif e.op == '~':
                    if not (t.kind in ('scalar', 'abstract') and t.name in ('i32', 'u32', 'int')):
                        self.fail(e, "'~' on a %r" % t)
                elif not (t.is_numeric_scalar() or (t.kind == 'vector' and t.name != 'bool')):
                    self.fail(e, "unary '%s' on a %r" % (e.op, t))
                if e.op == '+':
                    return text, t, prec
                if prec < 90 or text.startswith('-') or text.startswith('!'):
                    text = '(%s)' % text
                return e.op + text, t, 90
            if e.op in ('++', '--', 'p++', 'p--'):
                self.fail(e, '++/-- inside an expression (WGSL has them as statements only)')
            if e.op == '&':
                self.fail(e, "address-of '&' (the shared subset has no pointers)")
            if e.op == '*':
                self.fail(e, "pointer dereference '*' (the shared subset has no pointers)")
            if e.op == 'sizeof':
                self.fail(e, 'sizeof')
            self.fail(e, 'unary operator %s' % e.op)
        if isinstance(e, c_ast.TernaryOp):
            return self.ternary(e, scope, ctx, dry)
        if isinstance(e, c_ast.FuncCall):
            return self.call(e, scope, ctx, dry)
        if isinstance(e, c_ast.StructRef):
            if e.type != '.':
                self.fail(e, "'->' (the shared subset has no pointers)")
            base, bt, prec = self.ex(e.name, scope, ctx, dry)
            if prec < 100:
                base = '(%s)' % base
            field = e.field.name
            if bt.kind == 'vector':
                if not re.fullmatch(r'[xyzw]{1,4}|[rgba]{1,4}', field) or \
                        any('xyzw'.find(c) >= bt.n if c in 'xyzw' else 'rgba'.find(c) >= bt.n for c in field):
                    self.fail(e, "swizzle '.%s' of a %r" % (field, bt))
                t = T('scalar', bt.name) if len(field) == 1 else T('vector', bt.name, len(field))
                return '%s.%s' % (base, field), t, PRIMARY
            if bt.kind != 'struct':
                self.fail(e, "member '%s' of a %r" % (field, bt))
            return '%s.%s' % (base, self.name(field, e, member=True)), self.member_type(bt, field, e), PRIMARY
        if isinstance(e, c_ast.ArrayRef):
            base, bt, prec = self.ex(e.name, scope, ctx, dry)
            if prec < 100:
                base = '(%s)' % base
            index, it, _ = self.ex(e.subscript, scope, ctx, dry)
            self.check_index(it, e)
            if bt.kind == 'array':
                return '%s[%s]' % (base, index), bt.elem, PRIMARY
            if bt.kind == 'vector':
                return '%s[%s]' % (base, index), T('scalar', bt.name), PRIMARY
            self.fail(e, 'indexing a %r' % bt)
        if isinstance(e, c_ast.Assignment):
            self.fail(e, 'an assignment inside an expression')
        if isinstance(e, c_ast.Cast):
            self.fail(e, 'a C cast (GLSL has none: use float(x) / int(x))')
        if isinstance(e, c_ast.ExprList):
            self.fail(e, 'the comma operator')
        if isinstance(e, c_ast.InitList):
            self.fail(e, 'a brace initialiser outside an array declaration')
        if isinstance(e, c_ast.CompoundLiteral):
            self.fail(e, 'a compound literal')
        self.fail(e, 'unsupported expression %s' % type(e).__name__)

    def int_literal(self, e):
        v = e.value
        m = re.fullmatch(r'(0[xX][0-9a-fA-F]+|[1-9][0-9]*|0)([uU]?)', v)
        if not m:
            self.fail(e, "integer literal '%s' (octal, long or other suffixes are not translated)" % v)
        return m.group(1), m.group(2)

    def constant(self, e):
        if e.type in ('int', 'unsigned int'):
            digits, suffix = self.int_literal(e)
            value = int(digits, 0)
            if suffix:
                if value > 0xFFFFFFFF:
                    self.fail(e, "'%s' does not fit in u32" % e.value)
                return digits + 'u', U32
            if value > 0x7FFFFFFF:
                self.fail(e, "'%s' does not fit in i32 (write it with a u suffix)" % e.value)
            return digits, ABSTRACT_INT
        if e.type in ('double', 'float'):
            v = e.value
            m = re.fullmatch(r'((?:[0-9]+\.[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?|[0-9]+[eE][+-]?[0-9]+)([fF]?)', v)
            if not m:
                self.fail(e, "floating-point literal '%s' (hex floats and long double are not translated)" % v)
            value = float(m.group(1))
            if value > FLT_MAX:
                # GLSL rounds a literal to float: up to half an ulp above FLT_MAX is FLT_MAX; WGSL
                # refuses any value above FLT_MAX, so write that float itself.
                if value >= FLT_ROUNDS_TO_INF:
                    self.fail(e, "'%s' is beyond float's range" % v)
                return repr(FLT_MAX), ABSTRACT_FLOAT
            return m.group(1), ABSTRACT_FLOAT
        self.fail(e, '%s literal %s' % (e.type, e.value))

    def binary(self, e, scope, ctx, dry):
        op = e.op
        # The right operand of && and || is evaluated only sometimes: nothing hoisted out of it.
        left, lt, lp = self.ex(e.left, scope, ctx, dry)
        right, rt, rp = self.ex(e.right, scope, None if op in LOGIC_OPS else ctx, dry)
        lkind = self.op_kind(e.left)
        rkind = self.op_kind(e.right)
        if op in LOGIC_OPS:
            self.check_bool(lt, e.left)
            self.check_bool(rt, e.right)
            t = BOOL
            left = self.wrap(left, lkind, ok=lambda k: k in ('rel', 'arith', 'primary') or k == op)
            right = self.wrap(right, rkind, ok=lambda k: k in ('rel', 'arith', 'primary'))
            return '%s %s %s' % (left, op, right), t, 20
        if op in REL_OPS:
            if lt == BOOL or rt == BOOL:
                if op not in ('==', '!=') or lt != rt:
                    self.fail(e, "'%s' on %r and %r" % (op, lt, rt))
            else:
                t = self.binary_type(op, lt, rt, e)
                if t.kind == 'vector':
                    self.fail(e, "'%s' on vectors (a vector of bools)" % op)
            left = self.wrap(left, lkind, ok=lambda k: k in ('arith', 'shift', 'primary'))
            right = self.wrap(right, rkind, ok=lambda k: k in ('arith', 'shift', 'primary'))
            return '%s %s %s' % (left, op, right), BOOL, 50
        t = self.binary_type(op, lt, rt, e)
        if op in MUL_OPS:
            left = self.wrap(left, lkind, ok=lambda k: k in ('mul', 'primary'))
            right = self.wrap(right, rkind, ok=lambda k: k == 'primary')
            return '%s %s %s' % (left, op, right), t, 80
        if op in ADD_OPS:
            left = self.wrap(left, lkind, ok=lambda k: k in ('mul', 'add', 'primary'))
            right = self.wrap(right, rkind, ok=lambda k: k in ('mul', 'primary'))
            return '%s %s %s' % (left, op, right), t, 70
        if op in SHIFT_OPS or op in BIT_OPS:
            left = self.wrap(left, lkind, ok=lambda k: k == 'primary' or (op in BIT_OPS and k == op))
            right = self.wrap(right, rkind, ok=lambda k: k == 'primary')
            return '%s %s %s' % (left, op, right), t, 60 if op in SHIFT_OPS else 40
        self.fail(e, 'binary operator %s' % op)

    @staticmethod
    def op_kind(e):
        """The grammar class of a translated expression's top: 'primary' (also unary and calls,
        including select), 'mul', 'add', 'shift', 'rel', '&&', '||', '&', '|', '^'."""
        if isinstance(e, c_ast.BinaryOp):
            op = e.op
            if op in MUL_OPS:
                return 'mul'
            if op in ADD_OPS:
                return 'add'
            if op in SHIFT_OPS:
                return 'shift'
            if op in REL_OPS:
                return 'rel'
            return op
        return 'primary'

    @staticmethod
    def wrap(text, kind, ok):
        """text as an operand: parenthesised unless ok(its grammar class) (or ok('arith') for a
        multiplicative or additive one)."""
        if ok(kind) or (kind in ('mul', 'add') and ok('arith')):
            return text
        return '(%s)' % text

    def ternary(self, e, scope, ctx, dry):
        cond, ct, _ = self.ex(e.cond, scope, ctx, dry)
        self.check_bool(ct, e.cond)
        # The branches are evaluated only sometimes: nothing hoisted out of them.
        a, at, _ = self.ex(e.iftrue, scope, None, dry)
        b, bt, _ = self.ex(e.iffalse, scope, None, dry)
        t = self.unify(at, bt, e)
        branch = not t.selectable() or self.calls_user_function(e.iftrue) or self.calls_user_function(e.iffalse)
        if branch and ctx is not None and not dry:
            name = self.fresh('slut_wgsl_sel_%d' % self.temp_counter, scope)
            self.temp_counter += 1
            ctx.append('%svar %s: %s;' % ('    ' * self._depth, name, t.wgsl()))
            ctx.extend(self.branch_assign(name, t, e, scope, self._depth, e))
            scope.names[name] = Var(t, name, 'local')
            return name, t, 100
        if not t.selectable():
            if dry:
                return 'select(...)', t, 100
            self.fail(e, 'a ?: of type %r where it cannot become an if/else (in a loop clause, the right '
                         'operand of && or ||, or inside another ?:): write it as an if/else' % t)
        return 'select(%s, %s, %s)' % (b, a, cond), t, 100

    def call(self, e, scope, ctx, dry):
        if not isinstance(e.name, c_ast.ID):
            self.fail(e, 'a call through an expression')
        name = e.name.name
        args = e.args.exprs if e.args is not None else []
        if any(isinstance(a, c_ast.ExprList) for a in args):
            self.fail(e, 'the comma operator in an argument')
        if name.startswith(CTOR_PREFIX):
            return self.constructor(name[len(CTOR_PREFIX):], args, e, scope, ctx, dry)
        if name in self.functions:
            f = self.functions[name]
            if len(args) != len(f.params):
                self.fail(e, '%s() takes %d arguments, given %d' % (name, len(f.params), len(args)))
            texts = []
            for (pname, pt, is_out), a in zip(f.params, args):
                if is_out:
                    texts.append(self.out_argument(a, pt, scope, name))
                else:
                    text, at, _ = self.ex(a, scope, ctx, dry)
                    if pt.kind in ('texture', 'sampler'):
                        if at != pt:
                            self.fail(a, "argument '%s' of %s() must be a %s" % (pname, name, pt.wgsl()))
                    else:
                        self.check_assignable(pt, at, a)
                    texts.append(text)
            return '%s(%s)' % (f.wgsl, ', '.join(texts)), f.ret, 100
        if name in PLACEHOLDER_CALLS:
            arity, ret, template = PLACEHOLDER_CALLS[name]
            if len(args) != arity:
                self.fail(e, '%s() takes %d arguments' % (name, arity))
            texts = [self.ex(a, scope, ctx, dry)[0] for a in args]
            return template.format(*texts), ret, 100
        if name == 'atan':
            if len(args) not in (1, 2):
                self.fail(e, 'atan with %d arguments' % len(args))
            wname, rule = ('atan', 'arg0') if len(args) == 1 else ('atan2', 'arg0')
        elif name in BUILTINS:
            wname, rule, arity = BUILTINS[name]
            if len(args) != arity:
                self.fail(e, '%s() takes %d arguments, given %d' % (name, arity, len(args)))
        elif name in REFUSED_BUILTINS:
            self.fail(e, '%s(): %s' % (name, REFUSED_BUILTINS[name]))
        else:
            self.fail(e, "call to '%s', which is neither defined in the source nor a built-in the translator "
                         "knows (BUILTINS in tables/shaders/wgsl/slut_wgsl.py)" % name)
        results = [self.ex(a, scope, ctx, dry) for a in args]
        types = [r[1] for r in results]
        for t in types:
            if not (t.is_numeric_scalar() or (t.kind == 'vector' and t.name != 'bool')):
                self.fail(e, '%s() on a %r' % (name, t))
        if rule == 'arg0':
            ret = types[0]
        elif rule == 'arg1':
            ret = types[1]
        elif rule == 'arg2':
            ret = types[2]
        else:
            ret = T('scalar', types[0].name) if types[0].kind == 'vector' else types[0]
        if ret.kind == 'abstract' and any(t.kind != 'abstract' for t in types):
            ret = next(t for t in types if t.kind != 'abstract')
            ret = T('scalar', ret.name) if rule == 'elem0' and ret.kind == 'vector' else ret
        return '%s(%s)' % (wname, ', '.join(r[0] for r in results)), ret, 100

    def out_argument(self, a, pt, scope, fname):
        """The pointer argument for an out parameter: &local (or a pointer parameter itself)."""
        root = a
        through_vector = False
        while isinstance(root, (c_ast.StructRef, c_ast.ArrayRef)):
            root = root.name
        if not isinstance(root, c_ast.ID):
            self.fail(a, 'an out argument of %s() that is not a variable' % fname)
        v = scope.lookup(root.name)
        if v is None:
            self.fail(a, "undeclared identifier '%s'" % root.name)
        if v.kind not in ('local', 'ptr'):
            self.fail(a, "out argument '%s' of %s() is not a local variable (WGSL passes ptr<function, T>)"
                      % (root.name, fname))
        if isinstance(a, c_ast.ID) and v.kind == 'ptr':
            text, t = v.wgsl, v.type
        else:
            text, t = self.lvalue(a, scope)
            # &v.x of a vector component is not allowed in WGSL
            sub = a
            while isinstance(sub, (c_ast.StructRef, c_ast.ArrayRef)):
                base_t = self.expr_type(sub.name, scope)
                if base_t.kind == 'vector':
                    through_vector = True
                sub = sub.name
            if through_vector:
                self.fail(a, 'an out argument that is a vector component (WGSL has no pointer to one)')
            text = '&%s' % (text if not text.startswith('*') else '(%s)' % text)
        if t != pt:
            self.fail(a, 'out argument of type %r for a %r parameter of %s()' % (t, pt, fname))
        return text

    def constructor(self, tname, args, e, scope, ctx, dry):
        results = [self.ex(a, scope, ctx, dry) for a in args]
        if tname in ('float', 'int', 'uint', 'bool'):
            t = SCALAR_NAMES[tname]
            if len(args) != 1:
                self.fail(e, '%s() with %d arguments' % (tname, len(args)))
            at = results[0][1]
            if not (at.kind in ('scalar', 'abstract')):
                self.fail(e, '%s() of a %r' % (tname, at))
            return '%s(%s)' % (t.wgsl(), results[0][0]), t, 100
        t = vector_type(tname)
        count = 0
        for text, at, _ in results:
            if at.kind == 'vector':
                count += at.n
            elif at.kind in ('scalar', 'abstract'):
                count += 1
            else:
                self.fail(e, '%s() of a %r' % (tname, at))
        if count != t.n and not (len(args) == 1 and results[0][1].kind in ('scalar', 'abstract')):
            self.fail(e, '%s() with %d components' % (tname, count))
        return '%s(%s)' % (t.wgsl(), ', '.join(r[0] for r in results)), t, 100


# ----------------------------------------------------------------------------- drivers

def translate_text(text, cpp, defines=(), what='<input>', externs=None, sections=None, extra=''):
    """The WGSL declarations [(section, text)] of an assembled GLSL-subset text."""
    if c_parser is None:
        raise TranslateError('pycparser is missing (Debian: apt-get install python3-pycparser)')
    pre = run_cpp(cpp, section_markers(text) + extra, defines, what)
    ast = parse(glsl_to_c(pre))
    tr = Translator(ast, externs=externs)
    return tr, tr.translate(sections)


def join_sections(decls, shared):
    out, last = [], None
    in_shared = False
    for section, text in decls:
        is_shared = section in shared
        if is_shared and not in_shared:
            out.append('// ==== BEGIN SHARED (identical in every scatterlut WGSL snippet of one tier: keep it once '
                       'when you paste several into one module)')
            in_shared = True
        if not is_shared and in_shared:
            out.append('// ==== END SHARED')
            in_shared = False
        if section != last:
            out.append('// ---- from %s' % section)
            last = section
        out.append(text + '\n')
    if in_shared:
        out.append('// ==== END SHARED')
    return '\n'.join(out)


SHARED_SECTIONS = ('prelude', 'tables/shaders/src/common.slsl')


def shared_section(section):
    return section in SHARED_SECTIONS or section.startswith('kernels/')


def snippet_main(args):
    text = open(args.input, encoding='utf-8').read()
    defines = list(args.define)
    tr, decls = translate_text(text, args.cpp, defines, what=args.input)
    shared = {s for s, _ in decls if shared_section(s)}
    own = 'tables/shaders/src/%s.slsl' % args.name
    entries = []
    for s, t in decls:
        if s == own and t.startswith('fn '):
            entries.append('//   ' + t.split('{', 1)[0].strip()[3:])
    tier = {'fast': 'tier fast (SLUT_TIER_FAST)', 'accurate': 'tier accurate (SLUT_TIER_ACCURATE)'}.get(
        args.tier, 'no tier (as the GLSL without a tier define)')
    sampler_note = ('every texture argument is followed by its sampler (linear min/mag filter, clamp-to-edge, no '
                    'mipmaps; an r32float table needs the device feature "float32-filterable")'
                    if 'SLUT_TIER_FAST' in defines else
                    'texel fetches only (textureLoad): r32float tables, no sampler, no filtering feature needed')
    header = [
        '// GENERATED at build time by tables/shaders/wgsl/slut_wgsl.py -- do not edit. Translated from %s' %
        os.path.basename(args.input),
        '// (cmake/assemble_shaders.cmake: tables/shaders/src/%s.slsl, prelude.wgsl.h, common.slsl and the kernels/'
        % args.name,
        '// headers of SLUT_SHADER_HEADERS, the source of the GLSL, HLSL and GLSL ES snippets too),'
        ' preprocessed with %s.' % (' '.join('-D' + d for d in defines) or 'no tier define'),
        '//',
        '// scatterlut -- WGSL sampling snippet "%s", %s:' % (args.name, tier),
        '// %s.' % sampler_note,
        '// Use and packing: docs/SHADERS.md, "WGSL" (and the snippet\'s own section there). Paste it into a',
        '// WGSL module (no bindings of its own); call the entry points with your texture, sampler and values:',
    ] + entries + ['']
    out = '\n'.join(header) + '\n' + join_sections(decls, shared)
    write(args.output, out)


def harness_main(args):
    text = open(args.snippet_in, encoding='utf-8').read()
    body = open(args.body, encoding='utf-8').read()
    defines = list(args.define)
    fast = 'SLUT_TIER_FAST' in defines
    texture = PLACEHOLDER_TYPES['slut_wgsl_texture_%s' % args.texture]
    # The parameters: a C declaration list (the GLSL uniform block's fields), parsed alone.
    tp = Translator(parse(glsl_to_c(args.params)))
    tp.collect()
    params = [(d.name, tp.globals.names[d.name].type) for d in tp.global_decls]
    externs = {'q': (T('array', elem=F32, n=1), 'q'), 'slut_test_table': (texture, 'slut_test_table')}
    if fast:
        externs['slut_test_table_sampler'] = (PLACEHOLDER_TYPES['slut_wgsl_sampler'], 'slut_test_table_sampler')
    for name, t in params:
        externs[name] = (t, name)
    extra = '\n#line 1 "<test body>"\n' + body
    tr, decls = translate_text(text, args.cpp, defines, what='the test body', externs=externs,
                               sections={'<test body>'}, extra=extra)
    lines = ['// GENERATED by tables/shaders/wgsl/slut_wgsl.py harness: the WebGPU test\'s compute shader around',
             '// the snippet (append to the snippet\'s WGSL).',
             '@group(0) @binding(0) var slut_test_table: %s;' % texture.wgsl()]
    if fast:
        lines.append('@group(0) @binding(4) var slut_test_table_sampler: sampler;')
    lines += ['@group(0) @binding(1) var<storage, read> q: array<f32>;',
              '@group(0) @binding(2) var<storage, read_write> r: array<f32>;',
              'struct SlutTestParams {']
    lines += ['    %s: %s,' % (name, t.wgsl()) for name, t in params]
    lines += ['}', '@group(0) @binding(3) var<uniform> slut_test_params: SlutTestParams;']
    lines += ['var<private> %s: %s;' % (name, t.wgsl()) for name, t in params]
    lines.append('')
    lines += [t + '\n' for _, t in decls]
    lines.append('@compute @workgroup_size(64)')
    lines.append('fn main(@builtin(global_invocation_id) id: vec3<u32>) {')
    lines += ['    %s = slut_test_params.%s;' % (name, name) for name, _ in params]
    lines += ['    let i = i32(id.x);', '    if (i < n_queries) {', '        r[i] = test_eval(i);', '    }', '}', '']
    write(args.output, '\n'.join(lines))


def write(path, text):
    tmp = path + '.tmp'
    with open(tmp, 'w', encoding='utf-8') as f:
        f.write(text)
    os.replace(tmp, path)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.split('\n\n')[0])
    sub = ap.add_subparsers(dest='mode', required=True)
    for mode in ('snippet', 'harness'):
        p = sub.add_parser(mode)
        p.add_argument('--cpp', required=True, help='the C preprocessor command, e.g. "cpp" or "gcc -E -x c"')
        p.add_argument('-D', '--define', action='append', default=[])
        if mode == 'snippet':
            p.add_argument('--name', required=True)
            p.add_argument('--tier', default='')
            p.add_argument('input')
        else:
            p.add_argument('--snippet-in', required=True)
            p.add_argument('--body', required=True)
            p.add_argument('--params', required=True)
            p.add_argument('--texture', choices=('2d', '3d'), required=True)
        p.add_argument('output')
    args = ap.parse_args(argv)
    try:
        (snippet_main if args.mode == 'snippet' else harness_main)(args)
    except TranslateError as e:
        out = getattr(args, 'input', None) or getattr(args, 'body', '')
        sys.stderr.write('slut_wgsl.py: cannot translate %s to WGSL: %s\n' % (out, e))
        return 1
    return 0


if __name__ == '__main__':
    sys.exit(main())
