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

function zip(a, b, f) {
  a = val(a); b = val(b);
  if (Array.isArray(a) && Array.isArray(b)) return a.map((x, i) => f(x, b[i]));
  if (Array.isArray(a)) return a.map((x) => f(x, b));
  if (Array.isArray(b)) return b.map((y) => f(a, y));
  return f(a, b);
}
const map1 = (a, f) => { a = val(a); return Array.isArray(a) ? a.map(f) : f(a); };
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
export const and = (a, b) => wrap(val(a) && val(b));
export const or = (a, b) => wrap(val(a) || val(b));
export const not = (a) => wrap(!val(a));
export const select = (c, a, b) => (val(c) ? wrap(copy(val(a))) : wrap(copy(val(b))));

const METHODS = { add, sub, mul, div, pow, max, min, exp, exp2, log, log2, sqrt, inverseSqrt, abs, sign,
  floor, fract, sin, cos, negate, oneMinus, reciprocal, clamp, saturate, mix: (a, b, t) => mix(b, t, a),
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
