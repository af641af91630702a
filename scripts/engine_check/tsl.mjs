// An eager stand-in for three.js's TSL: every node is a value computed at once (a number or an
// array of numbers), so an engine's TSL functions run in node on concrete inputs. Arithmetic is
// rounded to float32 after every operation (Math.fround), or kept in float64 with setFloat64(true).
let F64 = false;
export function setFloat64(on) { F64 = on; PI.v = r(Math.PI); }
const r = (x) => (F64 ? x : Math.fround(x));

const SW = { x: 0, y: 1, z: 2, w: 3, r: 0, g: 1, b: 2, a: 3, s: 0, t: 1, p: 2, q: 3 };

export class Val {
  constructor(v) { this.v = v; }
  get isVec() { return Array.isArray(this.v); }
  // Swizzles: .x, .xy, .rgb ...
  static swizzle(self, name) {
    if (name.length === 1) return new Val(self.isVec ? self.v[SW[name]] : self.v);
    return new Val([...name].map((c) => (self.isVec ? self.v[SW[c]] : self.v)));
  }
  toVar() { return new Val(copy(this.v)); }
  toConst() { return this; }
  assign(o) { this.v = copy(val(o)); return this; }
  addAssign(o) { return this.assign(add(this, o)); }
  subAssign(o) { return this.assign(sub(this, o)); }
  mulAssign(o) { return this.assign(mul(this, o)); }
  divAssign(o) { return this.assign(div(this, o)); }
  toFloat() { return this; }
}
const copy = (v) => (Array.isArray(v) ? v.slice() : v);
const val = (x) => (x instanceof Val ? x.v : typeof x === 'boolean' ? x : Array.isArray(x) ? x.map(val) : x);
const wrap = (v) => new Val(v);

// A JS number literal in engine code is a shader constant: float, like every other operand.
const lit = (x) => (typeof x === 'number' ? r(x) : Array.isArray(x) ? x.map(lit) : x);
function zip(a, b, f) {
  a = lit(val(a)); b = lit(val(b));
  if (Array.isArray(a) && Array.isArray(b)) return a.map((x, i) => f(x, b[i]));
  if (Array.isArray(a)) return a.map((x) => f(x, b));
  if (Array.isArray(b)) return b.map((y) => f(a, y));
  return f(a, b);
}
const map1 = (a, f) => { a = lit(val(a)); return Array.isArray(a) ? a.map(f) : f(a); };
const n1 = (f) => (a) => wrap(map1(a, (x) => r(f(x))));
const n2 = (f) => (a, b) => wrap(zip(a, b, (x, y) => r(f(x, y))));
const fold = (f) => (a, ...rest) => rest.reduce((acc, b) => f(acc, b), a instanceof Val ? a : wrap(val(a)));

export const add = fold(n2((x, y) => x + y));
export const sub = fold(n2((x, y) => x - y));
export const mul = fold(n2((x, y) => x * y));
export const div = fold(n2((x, y) => x / y));
export const pow = n2((x, y) => Math.pow(x, y));
export const max = fold(n2((x, y) => (x < y ? y : x)));
export const min = fold(n2((x, y) => (y < x ? y : x)));
export const exp = n1(Math.exp);
export const exp2 = n1((x) => Math.pow(2, x));
export const log = n1(Math.log);
export const log2 = n1(Math.log2);
export const sqrt = n1(Math.sqrt);
export const inverseSqrt = n1((x) => 1 / Math.sqrt(x));
export const abs = n1(Math.abs);
export const sign = n1(Math.sign);
export const floor = n1(Math.floor);
export const fract = n1((x) => x - Math.floor(x));
export const sin = n1(Math.sin);
export const cos = n1(Math.cos);
export const negate = n1((x) => -x);
export const pow2 = (a) => mul(a, a);
// A flat batch has no screen-space derivatives.
export const dFdx = (a) => wrap(map1(a, () => 0));
export const dFdy = dFdx;
export const oneMinus = n1((x) => 1 - x);
export const reciprocal = n1((x) => 1 / x);
export const clamp = (a, lo = 0, hi = 1) => min(max(a, lo), hi);
export const saturate = (a) => clamp(a, 0, 1);
export const mix = (a, b, t) => add(a, mul(sub(b, a), t));
export const step = n2((e, x) => (x < e ? 0 : 1));
export const dot = (a, b) => { const p = val(mul(a, b)); return wrap(p.slice(1).reduce((s, x) => r(s + x), p[0])); };
export const length = (a) => sqrt(dot(a, a));
export const normalize = (a) => div(a, length(a));
export const cross = (a, b) => { const [x, y, z] = val(a); const [u, v, w] = val(b);
  return wrap([r(r(y * w) - r(z * v)), r(r(z * u) - r(x * w)), r(r(x * v) - r(y * u))]); };
export const lessThan = (a, b) => wrap(val(a) < val(b));
export const lessThanEqual = (a, b) => wrap(val(a) <= val(b));
export const greaterThan = (a, b) => wrap(val(a) > val(b));
export const greaterThanEqual = (a, b) => wrap(val(a) >= val(b));
export const equal = (a, b) => wrap(val(a) === val(b));
export const notEqual = (a, b) => wrap(val(a) !== val(b));
export const and = (a, b) => wrap(val(a) && val(b));
export const or = (a, b) => wrap(val(a) || val(b));
export const not = (a) => wrap(!val(a));
export const select = (c, a, b) => (val(c) ? wrap(copy(val(a))) : wrap(copy(val(b))));

const METHODS = { add, sub, mul, div, pow, max, min, exp, exp2, log, log2, sqrt, inverseSqrt, abs, sign,
  floor, fract, sin, cos, negate, oneMinus, reciprocal, clamp, saturate, mix: (a, b, t) => mix(b, t, a), pow2, dFdx, dFdy,
  notEqual, element: (a, i) => wrap(val(a)[val(i)]),
  step: (x, e) => step(e, x), dot, length, normalize, cross, lessThan, lessThanEqual, greaterThan,
  greaterThanEqual, equal, and, or, not, select: (c, a, b) => select(c, a, b) };
for (const [k, f] of Object.entries(METHODS)) Val.prototype[k] = function (...a) { return f(this, ...a); };
for (const k of Object.keys(SW)) Object.defineProperty(Val.prototype, k, { get() { return Val.swizzle(this, k); } });
for (const k of ['xy', 'xz', 'yz', 'xyz', 'rgb', 'rg', 'zw', 'ba', 'xyzw', 'rgba']) {
  Object.defineProperty(Val.prototype, k, { get() { return Val.swizzle(this, k); } });
}

const vec = (n) => (...a) => {
  const flat = a.flatMap((x) => { const v = val(x); return Array.isArray(v) ? v : [v]; });
  if (flat.length === 0) return wrap(new Array(n).fill(0));
  if (flat.length === 1) return wrap(new Array(n).fill(r(flat[0])));
  return wrap(flat.slice(0, n).map(r));
};
export const float = (x = 0) => wrap(r(val(x) instanceof Array ? val(x)[0] : val(x)));
export const int = (x = 0) => wrap(Math.trunc(val(x)));
export const bool = (x = false) => wrap(!!val(x));
export const vec2 = vec(2);
export const vec3 = vec(3);
export const vec4 = vec(4);
export const color = vec3;
export const PI = wrap(r(Math.PI));
export const EPSILON = wrap(1e-6);
export const mat3 = (...a) => wrap(a.flatMap((x) => { const v = val(x); return Array.isArray(v) ? v : [v]; }).map(r));
// TSL's defined(): a node's value, anything else as it is.
export const defined = (v) => (v instanceof Val ? v.v : typeof v === 'object' && v !== null ? v.value : v);

// Fn(f): a function over nodes; TSL passes inputs as one object (or as a list with setLayout).
// Positional arguments arrive as an array that also carries the layout's input names.
const plain = (x) => x && typeof x === 'object' && !(x instanceof Val) && !Array.isArray(x);
export function Fn(f) {
  let names = [];
  const g = (...args) => {
    if (args.length === 1 && plain(args[0])) return f(args[0], {});
    const a = [...args];
    names.forEach((n, i) => { a[n] = args[i]; });
    return f(a, {});
  };
  g.setLayout = (layout) => { names = (layout.inputs || []).map((i) => i.name); return g; };
  return g;
}
export const tslFn = Fn;
export function If(c, body) {
  let done = !!val(c);
  if (done) body();
  const chain = {
    ElseIf(c2, b2) { if (!done && val(c2)) { done = true; b2(); } return chain; },
    Else(b3) { if (!done) b3(); return chain; },
  };
  return chain;
}

// What an engine file imports and the stand-in does not provide: usable only as a value that
// throws when the check's code path touches it.
export function missing(name) {
  return new Proxy(function () {}, {
    get(t, k) { if (k === Symbol.toPrimitive || k === 'then') return undefined; throw new Error(`TSL stand-in lacks ${name}.${String(k)}`); },
    apply() { throw new Error(`TSL stand-in lacks ${name}()`); },
  });
}

// Textures: a DataTexture keeps its texels; texture(t, uv) samples them as a GPU samples a
// texture with linear filtering and clamp-to-edge (texel centres at (i + 0.5)/size).
const half = (h) => { const e = (h >> 10) & 0x1f, m = h & 0x3ff, s = h & 0x8000 ? -1 : 1;
  return e === 0 ? s * m * 2 ** -24 : e === 31 ? (m ? NaN : s * Infinity) : s * (m + 1024) * 2 ** (e - 25); };
export class DataTexture {
  constructor(data, width, height, format, type) { Object.assign(this, { data, width, height, format, type }); }
}
export function texture(t, uv) {
  const [u, v] = val(uv).map(r);
  const n = t.data.length / (t.width * t.height);
  const x = min(max(sub(mul(u, t.width), 0.5), 0), t.width - 1).v;
  const y = min(max(sub(mul(v, t.height), 0.5), 0), t.height - 1).v;
  const x0 = Math.min(Math.floor(x), t.width - 2), y0 = Math.min(Math.floor(y), t.height - 2);
  const fx = r(x - x0), fy = r(y - y0);
  const texel = t.data instanceof Uint16Array ? half : (x) => x;  // half-float bits, or float texels
  const at = (i, j, c) => r(texel(t.data[(j * t.width + i) * n + c]));
  const out = [];
  for (let c = 0; c < n; ++c) {
    const lo = mix(at(x0, y0, c), at(x0 + 1, y0, c), fx), hi = mix(at(x0, y0 + 1, c), at(x0 + 1, y0 + 1, c), fx);
    out.push(mix(lo, hi, fy).v);
  }
  while (out.length < 4) out.push(out.length === 3 ? 1 : 0);
  return wrap(out);
}
// The viewport textures of transmission: created when the lighting model's module loads, never
// sampled by the direct-light path the check runs.
export const viewportMipTexture = () => missing('viewportMipTexture()');
export const viewportOpaqueMipTexture = () => missing('viewportOpaqueMipTexture()');

// three.js's per-fragment state (PropertyNode, Normal, Position, AccessorsUtils): nodes whose
// values a driver sets before it runs the engine's lighting model.
const state = (n) => new Val(n === 1 ? 0 : new Array(n).fill(0));
export const diffuseColor = state(4), diffuseContribution = state(3), diffuseRoughness = state(1);
export const specularColor = state(3), specularColorBlended = state(3), specularF90 = state(1);
export const roughness = state(1), metalness = state(1), ior = state(1);
export const clearcoat = state(1), clearcoatRoughness = state(1), sheen = state(3), sheenRoughness = state(1);
export const iridescence = state(1), iridescenceIOR = state(1), iridescenceThickness = state(1);
export const anisotropy = state(1), alphaT = state(1), anisotropyT = state(3), anisotropyB = state(3);
export const thickness = state(1), transmission = state(1), attenuationDistance = state(1), attenuationColor = state(3);
export const dispersion = state(1), retroreflectivity = state(1);
export const normalView = state(3), clearcoatNormalView = state(3), transformedNormalView = normalView;
export const normalWorld = state(3), normalGeometry = state(3);
export const positionViewDirection = state(3), positionView = state(3), positionWorld = state(3);
